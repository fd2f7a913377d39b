//! The neighbourhood of an irregular patch as local points (`Far::
//! SourcePatch`): the face's corners, then for each corner the points of its
//! ring not shared with a neighbouring corner, counter-clockwise; and each
//! corner's ring in that numbering, starting after the patch's face. The
//! change-of-basis matrices of end caps are written over these points, and
//! [`Builder::source_points`] says which vertex of the level each one is.

use super::Builder;
use super::corners::Span;
use super::points::face_points;
use crate::rules::Rule;
use crate::topology::fvar::ChannelLevel;

/// One corner of a source patch.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub(super) struct Corner {
    /// Faces around the corner (in its span).
    pub faces: usize,
    /// The patch's face among them.
    pub patch_face: usize,
    pub boundary: bool,
    pub sharp: bool,
    pub dart: bool,
    /// An interior corner of two faces.
    pub val2_interior: bool,
    shares_prev: bool,
    shares_next: bool,
}

/// A source patch: its corners and the numbering of its points (equal
/// source patches have the same change-of-basis matrices).
#[derive(Debug, Clone, Default, PartialEq, Eq, Hash)]
pub(super) struct SourcePatch {
    pub corners: [Corner; 4],
    /// 4 for a quad, 3 for a triangle.
    pub size: usize,
    /// The most faces (plus one on a boundary) at a corner.
    pub max_valence: usize,
    /// The largest corner ring.
    pub max_ring: usize,
    /// Points in all: corners then each corner's own ring points.
    pub points: usize,
    ring_sizes: [usize; 4],
    local_ring_sizes: [usize; 4],
    local_ring_offsets: [usize; 4],
}

impl SourcePatch {
    /// Numbers the points once the corners are known
    /// (`SourcePatch::Finalize`).
    fn finalize(&mut self, size: usize) {
        let quad = size == 4;
        let q = quad as usize;
        self.size = size;
        self.points = size;
        for c in 0..size {
            let prev = (c + 2 + q) % size;
            let next = (c + 1) % size;
            let val2 = |k: usize| self.corners[k].faces == 2 && !self.corners[k].boundary;
            let (prev_val2, this_val2, next_val2) = (val2(prev), val2(c), val2(next));
            let (cp, cn) = (self.corners[prev], self.corners[next]);
            let corner = &mut self.corners[c];
            corner.val2_interior = this_val2;
            let val2_adjacent = prev_val2 || next_val2;
            if corner.faces + corner.boundary as usize > 2 {
                if corner.boundary {
                    corner.shares_prev = quad && corner.patch_face != corner.faces - 1;
                    corner.shares_next = corner.patch_face != 0;
                } else if corner.dart {
                    let prev_on_dart_edge = cp.boundary && cp.patch_face == 0;
                    let next_on_dart_edge = cn.boundary && cn.patch_face + 1 == cn.faces;
                    corner.shares_prev = quad && !prev_on_dart_edge;
                    corner.shares_next = !next_on_dart_edge;
                } else {
                    corner.shares_prev = quad;
                    corner.shares_next = true;
                }
                let ring = corner.faces * (1 + q) + corner.boundary as usize;
                let mut local = ring as isize
                    - (size as isize - 1)
                    - corner.shares_prev as isize
                    - corner.shares_next as isize;
                if val2_adjacent {
                    local -= prev_val2 as isize;
                    local -= (next_val2 && quad) as isize;
                }
                self.ring_sizes[c] = ring;
                self.local_ring_sizes[c] = local.max(0) as usize;
            } else {
                corner.shares_prev = false;
                corner.shares_next = false;
                if corner.faces == 1 {
                    self.ring_sizes[c] = size - 1;
                    self.local_ring_sizes[c] = 0;
                } else {
                    self.ring_sizes[c] = 2 * (1 + q);
                    self.local_ring_sizes[c] = q;
                }
            }
            self.local_ring_offsets[c] = self.points;
            let corner = self.corners[c];
            self.max_valence = self
                .max_valence
                .max(corner.faces + corner.boundary as usize);
            self.max_ring = self.max_ring.max(self.ring_sizes[c]);
            self.points += self.local_ring_sizes[c];
        }
    }

    /// The ring size of corner `c`.
    pub fn ring_size(&self, c: usize) -> usize {
        self.ring_sizes[c]
    }

    /// Every corner's ring in the patch's numbering ([`SourcePatch::ring`])
    /// and the number of points they and the patch's count name.
    pub fn numbering(&self) -> Numbering {
        let rings: Vec<Vec<usize>> = (0..self.size).map(|c| self.ring(c)).collect();
        // Next to interior corners of valence 2 (a dart among them), a
        // ring can name a point past the patch's count; OpenSubdiv writes it
        // into its buffer all the same and its matrix reads it back: so
        // does this.
        let len = rings
            .iter()
            .flatten()
            .map(|&i| i + 1)
            .fold(self.points, usize::max);
        Numbering { rings, len }
    }

    /// The ring of corner `c` in the patch's numbering, starting after the
    /// patch's face (`GetCornerRingPoints`).
    pub fn ring(&self, c: usize) -> Vec<usize> {
        let quad = self.size == 4;
        let q = quad as usize;
        let n = self.size;
        let next = (c + 1) % n;
        let opp = (c + 1 + q) % n;
        let prev = (c + 2 + q) % n;
        let corners = &self.corners;
        let mut ring = Vec::with_capacity(self.ring_sizes[c]);
        ring.push(next);
        if quad {
            ring.push(opp);
        }
        ring.push(prev);
        if corners[prev].val2_interior {
            ring.push(if quad { opp } else { next });
        }
        if corners[c].shares_prev {
            ring.push(self.local_ring_offsets[prev] + self.local_ring_sizes[prev] - 1);
        }
        ring.extend((0..self.local_ring_sizes[c]).map(|i| self.local_ring_offsets[c] + i));
        if quad {
            if corners[c].shares_next {
                ring.push(self.local_ring_offsets[next]);
            }
            if corners[next].val2_interior {
                ring.push(opp);
            }
        } else if corners[c].shares_next {
            ring.push(if corners[next].val2_interior {
                prev
            } else if self.local_ring_sizes[next] == 0 {
                self.local_ring_offsets[prev]
            } else {
                self.local_ring_offsets[next]
            });
        }
        let patch_face = corners[c].patch_face;
        if patch_face > 0 && !ring.is_empty() {
            let len = ring.len();
            let shift = ((1 + q) * patch_face) % len;
            ring.rotate_left((len - shift) % len);
        }
        ring
    }
}

impl Builder<'_> {
    /// The source patch of face `f` of `level` with the spans of its
    /// corners (`assembleIrregularSourcePatch`).
    pub(super) fn source_patch(&self, level: usize, f: usize, spans: &[Span]) -> SourcePatch {
        let l = &self.levels[level];
        let verts = l.face_verts(f);
        let mut patch = SourcePatch::default();
        for (c, (&v, span)) in verts.iter().zip(spans).enumerate().take(4) {
            let tag = l.vertex_tag(v as usize);
            let corner = &mut patch.corners[c];
            if span.is_assigned() {
                corner.faces = span.faces;
                corner.patch_face = span.corner_in_span;
                corner.boundary = !span.periodic;
            } else {
                let faces = l.vertex_faces_of(v as usize);
                corner.faces = faces.len();
                corner.patch_face = faces.iter().position(|&x| x as usize == f).unwrap_or(0);
                corner.boundary = tag.boundary();
            }
            corner.sharp = span.sharp;
            corner.dart = tag.rule() == Rule::Dart && tag.inf_sharp_edges();
        }
        patch.finalize(verts.len().min(4));
        patch
    }

    /// The vertex of the level (or value of channel `fv` there) behind each
    /// point of `patch` (`gatherIrregularSourcePoints`): each corner's ring
    /// from the level, laid over the same ring in the patch's numbering.
    pub(super) fn source_points(
        &self,
        level: usize,
        f: usize,
        spans: &[Span],
        patch: &SourcePatch,
        fv: Option<&ChannelLevel>,
    ) -> Vec<u32> {
        let mut points = Vec::new();
        let numbering = patch.numbering();
        self.source_points_into(
            level,
            f,
            spans,
            &numbering,
            fv,
            &mut points,
            &mut Vec::new(),
        );
        points
    }

    /// [`Builder::source_points`] with the patch's `numbering`, into
    /// `points` (`ring`: scratch space).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn source_points_into(
        &self,
        level: usize,
        f: usize,
        spans: &[Span],
        numbering: &Numbering,
        fv: Option<&ChannelLevel>,
        points: &mut Vec<u32>,
        ring: &mut Vec<u32>,
    ) {
        let l = &self.levels[level];
        let size = numbering.rings.len();
        points.clear();
        points.resize(numbering.len, 0);
        for (c, &v) in l.face_verts(f).iter().enumerate().take(size) {
            ring.clear();
            if spans[c].is_assigned() {
                self.partial_ring(level, v, &spans[c], fv, ring);
            } else if size == 4 {
                self.quad_ring_into(level, v, fv, ring);
            } else {
                self.tri_ring(level, v, fv, ring);
            }
            for (&local, &vertex) in numbering.rings[c].iter().zip(ring.iter()) {
                points[local] = vertex;
            }
        }
    }

    /// The ring around a vertex whose faces are all quads: the two points
    /// each face adds after the vertex, and the last boundary point
    /// (`gatherQuadRegularRingAroundVertex`); channel `fv`'s values if any.
    pub(super) fn quad_ring(&self, level: usize, v: u32, fv: Option<&ChannelLevel>) -> Vec<u32> {
        let mut ring = Vec::new();
        self.quad_ring_into(level, v, fv, &mut ring);
        ring
    }

    /// [`Builder::quad_ring`] pushed onto `ring`.
    fn quad_ring_into(&self, level: usize, v: u32, fv: Option<&ChannelLevel>, ring: &mut Vec<u32>) {
        let l = &self.levels[level];
        let faces = l.vertex_faces_of(v as usize);
        let locals = l.vertex_face_locals(v as usize);
        let boundary = l.vertex_edges_of(v as usize).len() > faces.len();
        ring.reserve(2 * faces.len() + 1);
        for (i, (&f, &k)) in faces.iter().zip(locals).enumerate() {
            let p = face_points(fv, l, f as usize);
            let k = k as usize;
            ring.push(p[(k + 1) % 4]);
            ring.push(p[(k + 2) % 4]);
            if boundary && i + 1 == faces.len() {
                ring.push(p[(k + 3) % 4]);
            }
        }
    }

    /// The ring around a vertex whose faces are all triangles
    /// (`gatherTriRegularRingAroundVertex`).
    fn tri_ring(&self, level: usize, v: u32, fv: Option<&ChannelLevel>, ring: &mut Vec<u32>) {
        let l = &self.levels[level];
        let faces = l.vertex_faces_of(v as usize);
        let locals = l.vertex_face_locals(v as usize);
        let boundary = l.vertex_edges_of(v as usize).len() > faces.len();
        ring.reserve(faces.len() + 1);
        for (i, (&f, &k)) in faces.iter().zip(locals).enumerate() {
            let p = face_points(fv, l, f as usize);
            let k = k as usize;
            ring.push(p[(k + 1) % 3]);
            if boundary && i + 1 == faces.len() {
                ring.push(p[(k + 2) % 3]);
            }
        }
    }

    /// The ring of the faces of a span around vertex `v`
    /// (`gatherRegularPartialRingAroundVertex`).
    fn partial_ring(
        &self,
        level: usize,
        v: u32,
        span: &Span,
        fv: Option<&ChannelLevel>,
        ring: &mut Vec<u32>,
    ) {
        let l = &self.levels[level];
        let manifold = !l.vertex_tag(v as usize).non_manifold();
        let faces = l.vertex_faces_of(v as usize);
        let locals = l.vertex_face_locals(v as usize);
        let Some((&first, &first_k)) = faces.get(span.start_face).zip(locals.get(span.start_face))
        else {
            return;
        };
        let (mut face, mut k) = (first as usize, first_k as usize);
        for i in 0..span.faces {
            let p = face_points(fv, l, face);
            let n = p.len();
            let quad = n == 4;
            if quad {
                ring.push(p[(k + 1) % 4]);
                ring.push(p[(k + 2) % 4]);
            } else {
                ring.push(p[(k + 1) % 3]);
            }
            if i + 1 == span.faces {
                if !span.periodic {
                    ring.push(if quad { p[(k + 3) % 4] } else { p[(k + 2) % 3] });
                }
            } else if manifold {
                let next = (span.start_face + i + 1) % faces.len();
                face = faces[next] as usize;
                k = locals[next] as usize;
            } else {
                let e = l.face_edges_of(face)[(k + n - 1) % n];
                let ef = l.edge_faces_of(e as usize);
                let Some(next) = ef.iter().copied().find(|&x| x as usize != face) else {
                    break;
                };
                let next = next as usize;
                k = l
                    .face_edges_of(next)
                    .iter()
                    .position(|&x| x == e)
                    .unwrap_or(0);
                face = next;
            }
        }
    }
}

/// A source patch's rings in its numbering ([`SourcePatch::numbering`]).
#[derive(Debug, Clone, Default)]
pub(super) struct Numbering {
    /// Each corner's ring ([`SourcePatch::ring`]).
    pub rings: Vec<Vec<usize>>,
    /// The points they and the patch's count name.
    pub len: usize,
}
