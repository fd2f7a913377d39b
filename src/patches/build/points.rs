//! The control vertices of regular patches (`PatchBuilder::
//! GetRegularPatchPoints`): the 16 points of a bicubic B-spline patch around
//! a quad, the 12 of a Loop box-spline patch around a triangle, taken from
//! the faces around each corner in OpenSubdiv's order. Points a boundary
//! patch lacks are filled with the face's first vertex, as OpenSubdiv's
//! patch tables do (`fillMissingBoundaryPoints`). In a face-varying
//! channel the points are the channel's values at the same corners.

use super::Builder;
use super::corners::decode_tri_boundary;
use super::view::LevelView;
use crate::topology::Level;
use crate::topology::fvar::ChannelLevel;

/// The points of face `f`: its vertices, or its values in channel `fv`
/// (`getFacePoints`).
#[inline]
pub(super) fn face_points<'a>(fv: Option<&'a ChannelLevel>, l: &'a Level, f: usize) -> &'a [u32] {
    match fv {
        Some(c) => c.face_values_of(l, f),
        None => l.face_verts(f),
    }
}

/// The faces around a vertex with the vertex's position in each.
struct Ring<'a> {
    faces: &'a [u32],
    locals: &'a [u16],
}

impl<'a> Ring<'a> {
    #[inline]
    fn of(level: &'a Level, v: u32) -> Ring<'a> {
        Ring {
            faces: level.vertex_faces_of(v as usize),
            locals: level.vertex_face_locals(v as usize),
        }
    }

    #[inline]
    fn at(&self, i: usize) -> (usize, usize) {
        (self.faces[i] as usize, self.locals[i] as usize)
    }

    #[inline]
    fn position(&self, f: usize) -> usize {
        self.faces
            .iter()
            .position(|&x| x as usize == f)
            .unwrap_or(0)
    }
}

/// The face across edge `e` from `face` (an edge with two faces).
fn across(level: &Level, e: u32, face: usize) -> usize {
    let faces = level.edge_faces_of(e as usize);
    match faces {
        [a, b] if *a as usize == face => *b as usize,
        [a, ..] => *a as usize,
        [] => face,
    }
}

/// The face after face `i` of a vertex's ring, counter-clockwise, and the
/// vertex's position in it (`getNextFaceInVertFaces`).
fn next_face(level: &Level, ring: &Ring, i: usize, manifold: bool) -> (usize, usize) {
    if manifold {
        return ring.at((i + 1) % ring.faces.len());
    }
    let (face, corner) = ring.at(i);
    let edges = level.face_edges_of(face);
    let e = edges[(corner + edges.len() - 1) % edges.len()];
    let next = across(level, e, face);
    let k = level
        .face_edges_of(next)
        .iter()
        .position(|&x| x == e)
        .unwrap_or(0);
    (next, k)
}

/// The face before face `i` of a vertex's ring and the vertex's position in
/// it (`getPrevFaceInVertFaces`).
fn prev_face(level: &Level, ring: &Ring, i: usize, manifold: bool) -> (usize, usize) {
    if manifold {
        return ring.at((i + ring.faces.len() - 1) % ring.faces.len());
    }
    let (face, corner) = ring.at(i);
    let e = level.face_edges_of(face)[corner];
    let prev = across(level, e, face);
    let edges = level.face_edges_of(prev);
    let k = edges.iter().position(|&x| x == e).unwrap_or(0);
    // OpenSubdiv takes the successor modulo the size of the first face.
    let n = level.face_edges_of(face).len();
    (prev, if k + 1 >= n { k + 1 - n } else { k + 1 })
}

impl Builder<'_> {
    /// [`Builder::regular_points`] of a vertex patch, each plus `offset`,
    /// appended to `out` — written in place (not read back as a whole
    /// right after their scattered stores) when the patch is an interior
    /// quad's whose corners all have four faces, or an interior triangle's
    /// whose corners all have six (`view`: the level's).
    pub(super) fn regular_points_onto(
        &self,
        (level, f): (usize, usize),
        mask: u16,
        view: Option<&LevelView>,
        offset: u32,
        out: &mut Vec<u32>,
    ) {
        if let Some(view) = view.filter(|_| mask == 0) {
            let at = out.len();
            let found = if self.reg == 4 {
                out.resize(at + 16, 0);
                let dst: &mut [u32; 16] = (&mut out[at..]).try_into().expect("16 points");
                view.quad_points_into(f, offset, dst)
            } else {
                out.resize(at + 12, 0);
                let dst: &mut [u32; 12] = (&mut out[at..]).try_into().expect("12 points");
                view.triangle_points_into(f, offset, dst)
            };
            if found.is_some() {
                return;
            }
            out.truncate(at);
        }
        let cvs = self.regular_points(level, f, mask, None);
        out.extend(cvs.iter().map(|&v| v + offset));
    }

    /// The control vertices of the regular patch of face `f` of `level`
    /// (indices within the level, or of channel `fv`'s values there), with
    /// its boundary mask `mask`.
    pub(super) fn regular_points(
        &self,
        level: usize,
        f: usize,
        mask: u16,
        fv: Option<&ChannelLevel>,
    ) -> PatchPoints {
        let l = &self.levels[level];
        if self.linear {
            let mut p = PatchPoints {
                points: [0; 16],
                len: 0,
            };
            for (slot, &v) in p.points.iter_mut().zip(face_points(fv, l, f)) {
                *slot = v;
                p.len += 1;
            }
            p
        } else if self.reg == 4 {
            PatchPoints {
                points: quad_points(l, f, mask, fv),
                len: 16,
            }
        } else {
            let mut points = [0; 16];
            points[..12].copy_from_slice(&tri_points(l, f, mask, fv));
            PatchPoints { points, len: 12 }
        }
    }
}

/// A regular patch's control vertices, without allocating.
pub(super) struct PatchPoints {
    points: [u32; 16],
    len: usize,
}

impl std::ops::Deref for PatchPoints {
    type Target = [u32];
    fn deref(&self) -> &[u32] {
        &self.points[..self.len]
    }
}

/// The 16 points of a B-spline patch: for each corner, the corner and the
/// three points of the face diagonally opposite, or of the faces beside it
/// along a boundary.
fn quad_points(l: &Level, f: usize, mask: u16, fv: Option<&ChannelLevel>) -> [u32; 16] {
    let verts = l.face_verts(f);
    let own = face_points(fv, l, f);
    let interior = mask == 0;
    let fill = if interior { u32::MAX } else { own[0] };
    let mut points = [0u32; 16];
    for (i, slots) in PER_CORNER.iter().enumerate() {
        let v = verts[i];
        let ring = Ring::of(l, v);
        let at = ring.position(f);
        let leading = mask & (1 << i) != 0;
        let trailing = mask & (1 << ((i + 3) % 4)) != 0;
        // The vertex's tag is read only along a boundary (a cache miss).
        let manifold = || !l.vertex_tag(v as usize).non_manifold();
        let outer: [u32; 3] = if interior || (!leading && !trailing) {
            // (at + 2) modulo the valence, without a division.
            let n = ring.faces.len().max(1);
            let mut opposite = at + 2;
            while opposite >= n {
                opposite -= n;
            }
            let (opp, k) = ring.at(opposite);
            let p = face_points(fv, l, opp);
            [p[(k + 1) & 3], p[(k + 2) & 3], p[(k + 3) & 3]]
        } else if leading && trailing {
            [fill; 3]
        } else if leading {
            let (next, k) = next_face(l, &ring, at, manifold());
            [face_points(fv, l, next)[(k + 3) % 4], fill, fill]
        } else {
            let (prev, k) = prev_face(l, &ring, at, manifold());
            [fill, fill, face_points(fv, l, prev)[(k + 1) % 4]]
        };
        points[slots[0]] = own[i];
        points[slots[1]] = outer[0];
        points[slots[2]] = outer[1];
        points[slots[3]] = outer[2];
    }
    points
}

/// The points of a quad's B-spline patch at each of its corners: the
/// corner, then the opposite face's other three.
pub(super) const PER_CORNER: [[usize; 4]; 4] =
    [[5, 4, 0, 1], [6, 2, 3, 7], [10, 11, 15, 14], [9, 13, 12, 8]];

/// The points of a triangle's box-spline patch at each of its corners:
/// the corner, then the far vertex of the second face after the triangle
/// around it and the two far vertices of the third.
pub(super) const TRIANGLE_PER_CORNER: [[usize; 4]; 3] =
    [[4, 7, 3, 0], [5, 1, 2, 6], [8, 9, 11, 10]];

/// The 12 points of a Loop box-spline patch.
fn tri_points(l: &Level, f: usize, mask: u16, fv: Option<&ChannelLevel>) -> [u32; 12] {
    let verts = l.face_verts(f);
    let own = face_points(fv, l, f);
    let interior = mask == 0;
    let (e_mask, v_mask) = if interior {
        (0, 0)
    } else {
        decode_tri_boundary(mask)
    };
    let fill = if interior { u32::MAX } else { own[0] };
    let mut points = [0u32; 12];
    for (i, slots) in TRIANGLE_PER_CORNER.iter().enumerate() {
        let v = verts[i];
        let ring = Ring::of(l, v);
        let n = ring.faces.len();
        let at = ring.position(f);
        let manifold = !l.vertex_tag(v as usize).non_manifold();
        let leading = e_mask & (1 << i) != 0;
        let trailing = e_mask & (1 << ((i + 2) % 3)) != 0;
        let corner = |face: usize, k: usize| face_points(fv, l, face)[k % 3];
        let outer: [u32; 3] = if interior || v_mask & (1 << i) == 0 {
            let (f2, k2) = ring.at((at + 2) % n);
            let (f3, k3) = ring.at((at + 3) % n);
            [corner(f2, k2 + 1), corner(f3, k3 + 1), corner(f3, k3 + 2)]
        } else if leading && trailing {
            [fill; 3]
        } else if leading {
            let (mut f2, mut k2) = ring.at((at + 2) % n);
            if !manifold {
                let (f1, _) = next_face(l, &ring, at, false);
                (f2, k2) = next_face(l, &ring, ring.position(f1), false);
            }
            [corner(f2, k2 + 1), corner(f2, k2 + 2), fill]
        } else if trailing {
            let (mut f0, mut k0) = ring.at((at + n - 2) % n);
            if !manifold {
                let (f1, _) = prev_face(l, &ring, at, false);
                (f0, k0) = prev_face(l, &ring, ring.position(f1), false);
            }
            [fill, fill, corner(f0, k0 + 1)]
        } else {
            let (f2, k2) = next_face(l, &ring, at, manifold);
            [corner(f2, k2 + 2), fill, fill]
        };
        points[slots[0]] = own[i];
        points[slots[1]] = outer[0];
        points[slots[2]] = outer[1];
        points[slots[3]] = outer[2];
    }
    points
}
