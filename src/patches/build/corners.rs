//! What a face's corners say about its patch: the combined vertex tags
//! (OpenSubdiv's `Vtr::Level::VTag`, refinement's tags and the adaptive
//! features together), whether the patch is regular, its boundary mask,
//! whether it is a single-crease patch, and the spans of faces around a
//! corner that a regular patch may use (`Far::PatchBuilder`'s topology
//! inspections) — in the vertex topology, or in a face-varying channel's
//! (`fv`: the channel at the patch's level), whose values see the vertex
//! tags as `Vtr::Level::getFaceVTags` and `getFaceETags` combine them.

use super::Builder;
use crate::refiner::adaptive::{CORNER, CREASE, DART, Tag};
use crate::rules::Rule;
use crate::topology::Level;
use crate::topology::fvar::{ChannelLevel, ValueTag};

/// The tags of a patch's corners, without allocating.
pub(super) struct Corners {
    tags: [Tag; 4],
    len: usize,
}

impl std::ops::Deref for Corners {
    type Target = [Tag];
    fn deref(&self) -> &[Tag] {
        &self.tags[..self.len]
    }
}

/// The edges that end a span of faces around a corner: boundary and
/// non-manifold edges, and infinitely sharp ones when asked.
/// In a face-varying channel, an edge the channel is split across is a
/// boundary too.
#[derive(Clone, Copy)]
pub(super) struct Singular<'a> {
    pub inf_sharp: bool,
    pub fv: Option<&'a ChannelLevel>,
}

impl Singular<'_> {
    fn test(self, level: &Level, e: u32) -> bool {
        let t = level.edge_tag(e as usize);
        t.boundary()
            || t.non_manifold()
            || (self.inf_sharp && t.inf_sharp())
            || self
                .fv
                .is_some_and(|c| c.edge_tag(e as usize).is_mismatch())
    }
}

/// The tag of the value at corner `k` of face `f` in channel `fv`
/// (`FVarLevel::getFaceValueTags`); an untagged one without a channel.
pub(super) fn value_tag(fv: Option<&ChannelLevel>, l: &Level, f: usize, k: usize) -> ValueTag {
    let Some(c) = fv else {
        return ValueTag::default();
    };
    let v = l.face_verts(f)[k] as usize;
    let value = c.face_values_of(l, f)[k];
    let tags = c.vertex_value_tags(v);
    (0..tags.len())
        .find(|&s| c.vertex_value(v, s) == value)
        .map_or(ValueTag::default(), |s| tags[s])
}

/// Whether edge `e` is a boundary in the topology read (a channel's split
/// edges included).
fn edge_boundary(fv: Option<&ChannelLevel>, l: &Level, e: u32) -> bool {
    l.edge_tag(e as usize).boundary() || fv.is_some_and(|c| c.edge_tag(e as usize).is_mismatch())
}

impl Builder<'_> {
    /// The tags of the corners of face `f` of `level` (a patch's face: its
    /// first four corners at most), as channel `fv` sees them if any.
    #[inline(always)]
    pub(super) fn corner_tags(&self, level: usize, f: usize, fv: Option<&ChannelLevel>) -> Corners {
        let l = &self.levels[level];
        let features = &self.features[level];
        let mut c = Corners {
            tags: [Tag::default(); 4],
            len: 0,
        };
        for (k, (slot, &v)) in c.tags.iter_mut().zip(l.face_verts(f)).enumerate() {
            let tag = Tag::of(l, features, v as usize);
            *slot = match fv {
                None => tag,
                Some(_) => tag.with_value(value_tag(fv, l, f, k)),
            };
            c.len += 1;
        }
        c
    }

    /// The tags of every corner of face `f` or-ed together
    /// (`getFaceCompositeVTag`).
    #[inline(always)]
    pub(super) fn composite(&self, level: usize, f: usize) -> Tag {
        let l = &self.levels[level];
        let features = &self.features[level];
        l.face_verts(f)
            .iter()
            .map(|&v| Tag::of(l, features, v as usize))
            .fold(Tag::default(), Tag::or)
    }

    /// `PatchBuilder::IsPatchRegular` in the vertex topology or channel
    /// `fv`'s.
    pub(super) fn is_regular(&self, level: usize, f: usize, fv: Option<&ChannelLevel>) -> bool {
        self.linear || self.is_regular_with(level, f, fv, &self.corner_tags(level, f, fv))
    }

    /// [`Builder::is_regular`] from the face's corner tags (`tags`, as
    /// [`Builder::corner_tags`] reads them).
    pub(super) fn is_regular_with(
        &self,
        level: usize,
        f: usize,
        fv: Option<&ChannelLevel>,
        tags: &[Tag],
    ) -> bool {
        if self.linear {
            return true;
        }
        let l = &self.levels[level];
        let all = tags.iter().copied().fold(Tag::default(), Tag::or);
        if !all.inf_sharp && !all.inf_sharp_edges {
            return !all.features.xordinary;
        }
        let test_inf = self.inf_sharp_patch;
        // The features that can make a corner irregular.
        let irregular = |t: &Tag| {
            t.non_manifold || t.features.xordinary || (test_inf && t.features.inf_irregular)
        };
        if !irregular(&all) {
            return true;
        }
        // An isolated feature (past the level where an irregular base face
        // still touches extraordinary vertices) is judged from the
        // combined tags unless it needs a closer look.
        let needs_extra_level = (all.features.xordinary && self.irregular_base_faces) as usize;
        if level > needs_extra_level {
            let closer = all.non_manifold
                || (self.sharp_corners && all.features.xordinary && all.boundary)
                || (test_inf && all.features.inf_irregular && all.inf_sharp_edges);
            if !closer {
                return if test_inf {
                    !all.features.inf_irregular
                } else {
                    !all.features.xordinary
                };
            }
        }
        let regular_boundary_faces = if self.reg == 4 { 2 } else { 3 };
        for (i, tag) in tags.iter().enumerate() {
            if !irregular(tag) {
                continue;
            }
            if tag.non_manifold {
                let n = self.non_manifold_span(
                    level,
                    f,
                    i,
                    Singular {
                        inf_sharp: test_inf,
                        fv,
                    },
                );
                let want = if tag.inf_sharp {
                    1
                } else {
                    regular_boundary_faces
                };
                if n.map(|s| s.faces) != Some(want) {
                    return false;
                }
                continue;
            }
            if tag.features.xordinary {
                if !tag.inf_sharp_edges {
                    return false;
                }
                // A smooth corner may be taken as a sharp one.
                if self.sharp_corners && tag.boundary && !tag.inf_sharp {
                    let edges = l.face_edges_of(f);
                    let prev = if i == 0 { self.reg - 1 } else { i - 1 };
                    let boundary = |k: usize| edge_boundary(fv, l, edges[k]);
                    if boundary(i) && boundary(prev) {
                        continue;
                    }
                }
                if !test_inf {
                    return false;
                }
            }
            if tag.features.inf_irregular {
                if !tag.inf_sharp_edges || (tag.features.inf_sharp_crease && tag.boundary) {
                    return false;
                }
                let n = self
                    .manifold_span(
                        level,
                        f,
                        i,
                        Singular {
                            inf_sharp: true,
                            fv,
                        },
                    )
                    .faces;
                let want = if tag.features.inf_sharp_crease {
                    regular_boundary_faces
                } else {
                    1
                };
                if n != want {
                    return false;
                }
            }
        }
        true
    }

    /// `PatchBuilder::GetRegularPatchBoundaryMask` in the vertex topology
    /// or channel `fv`'s: one bit per boundary edge of a quad, OpenSubdiv's
    /// 5-bit encoding of boundary edges and vertices for a triangle.
    pub(super) fn boundary_mask(&self, level: usize, f: usize, fv: Option<&ChannelLevel>) -> u16 {
        if self.linear {
            return 0;
        }
        self.boundary_mask_with(level, f, fv, &self.corner_tags(level, f, fv))
    }

    /// [`Builder::boundary_mask`] from the face's corner tags.
    pub(super) fn boundary_mask_with(
        &self,
        level: usize,
        f: usize,
        fv: Option<&ChannelLevel>,
        tags: &[Tag],
    ) -> u16 {
        if self.linear {
            return 0;
        }
        let l = &self.levels[level];
        let all = tags.iter().copied().fold(Tag::default(), Tag::or);
        if !all.inf_sharp_edges {
            return 0;
        }
        let test_inf = self.inf_sharp_patch;
        let e_bits =
            l.face_edges_of(f)
                .iter()
                .take(self.reg)
                .enumerate()
                .fold(0u16, |bits, (i, &e)| {
                    let t = l.edge_tag(e as usize);
                    let mismatch = fv.is_some_and(|c| c.edge_tag(e as usize).is_mismatch());
                    let on =
                        t.boundary() || t.non_manifold() || (test_inf && t.inf_sharp()) || mismatch;
                    bits | ((on as u16) << i)
                });
        if self.reg == 4 {
            return e_bits;
        }
        let v_bits = tags.iter().take(3).enumerate().fold(0u16, |bits, (i, t)| {
            let on = t.boundary || t.non_manifold || (test_inf && t.inf_sharp_edges);
            bits | ((on as u16) << i)
        });
        if e_bits == 0 && v_bits == 0 {
            0
        } else {
            encode_tri_boundary(e_bits, v_bits)
        }
    }

    /// `Vtr::Level::isSingleCreasePatch`: a regular interior quad with two
    /// adjacent crease vertices on one regular crease and two smooth ones;
    /// the crease's sharpness and its edge in the face.
    pub(super) fn single_crease(&self, level: usize, f: usize) -> Option<(f32, usize)> {
        if self.reg != 4 {
            return None;
        }
        let l = &self.levels[level];
        let all = self.composite(level, f);
        if all.rule & CREASE == 0
            || all.rule & (CORNER | DART) != 0
            || all.boundary
            || all.features.xordinary
            || all.non_manifold
        {
            return None;
        }
        let verts = l.face_verts(f);
        let mask = verts.iter().enumerate().fold(0usize, |m, (i, &v)| {
            m | (((l.vertex_tag(v as usize).rule() == Rule::Crease) as usize) << i)
        });
        // Two adjacent crease corners name the edge between them.
        const EDGE_OF_MASK: [i8; 16] = [-1, -1, -1, 0, -1, -1, 1, -1, -1, 3, -1, -1, 2, -1, -1, -1];
        let edge = usize::try_from(EDGE_OF_MASK[mask]).ok()?;
        for v in [verts[edge], verts[(edge + 1) % 4]] {
            let e = l.vertex_edges_of(v as usize);
            if e.len() < 4 {
                return None;
            }
            let s = |k: usize| l.edge_sharpness_at(e[k] as usize);
            if s(0) != s(2) || s(1) != s(3) {
                return None;
            }
        }
        Some((l.edge_sharpness_at(l.face_edges_of(f)[edge] as usize), edge))
    }

    /// The span of faces around corner `corner` of face `f` (a manifold
    /// vertex) bounded by singular edges (`identifyManifoldCornerSpan`).
    pub(super) fn manifold_span(
        &self,
        level: usize,
        f: usize,
        corner: usize,
        singular: Singular,
    ) -> Span {
        let l = &self.levels[level];
        let face_edges = l.face_edges_of(f);
        let v = l.face_verts(f)[corner];
        let edges = l.vertex_edges_of(v as usize);
        let n = edges.len();
        let mut span = Span {
            faces: 1,
            ..Span::default()
        };
        let Some(leading_start) = edges.iter().position(|&e| e == face_edges[corner]) else {
            return span;
        };
        let trailing_start = (leading_start + 1) % n;
        let mut leading = leading_start;
        while !singular.test(l, edges[leading]) {
            span.faces += 1;
            span.corner_in_span += 1;
            leading = (leading + n - 1) % n;
            if leading == trailing_start {
                break;
            }
        }
        let mut trailing = trailing_start;
        if trailing != leading {
            while !singular.test(l, edges[trailing]) {
                span.faces += 1;
                trailing = (trailing + 1) % n;
                if trailing == leading_start {
                    break;
                }
            }
        }
        span.start_face = leading;
        span
    }

    /// The span of faces around corner `corner` of face `f` at a
    /// non-manifold vertex, walking across manifold edges
    /// (`identifyNonManifoldCornerSpan`); `None` where the walk meets an
    /// edge without two faces (which the singular test excludes).
    pub(super) fn non_manifold_span(
        &self,
        level: usize,
        f: usize,
        corner: usize,
        singular: Singular,
    ) -> Option<Span> {
        let l = &self.levels[level];
        let fe = l.face_edges_of(f);
        let leading_start = fe[corner];
        let trailing_start = fe[(corner + fe.len() - 1) % fe.len()];
        let other = |e: u32, face: usize| -> Option<usize> {
            let faces = l.edge_faces_of(e as usize);
            if faces.len() != 2 {
                return None;
            }
            Some(if faces[0] as usize == face {
                faces[1]
            } else {
                faces[0]
            } as usize)
        };
        let position = |face: usize, e: u32| l.face_edges_of(face).iter().position(|&x| x == e);
        let mut span = Span {
            faces: 1,
            ..Span::default()
        };
        let (mut start_face, mut start_corner) = (f, corner);
        let mut face = f;
        let mut leading = leading_start;
        while !singular.test(l, leading) {
            span.faces += 1;
            span.corner_in_span += 1;
            face = other(leading, face)?;
            let edges = l.face_edges_of(face);
            start_face = face;
            start_corner = (position(face, leading)? + 1) % edges.len();
            leading = edges[start_corner];
            if leading == trailing_start {
                span.periodic = !singular.test(l, leading);
                break;
            }
        }
        let mut face = f;
        let mut trailing = trailing_start;
        if trailing != leading {
            while !singular.test(l, trailing) {
                span.faces += 1;
                face = other(trailing, face)?;
                let edges = l.face_edges_of(face);
                let k = position(face, trailing)?;
                trailing = edges[(k + edges.len() - 1) % edges.len()];
                if trailing == leading_start {
                    span.periodic = !singular.test(l, trailing);
                    break;
                }
            }
        }
        let v = l.face_verts(f)[corner] as usize;
        let faces = l.vertex_faces_of(v);
        let locals = l.vertex_face_locals(v);
        span.start_face = faces
            .iter()
            .zip(locals)
            .position(|(&x, &k)| x as usize == start_face && k as usize == start_corner)
            .unwrap_or(faces.len());
        Some(span)
    }

    /// `PatchBuilder::GetIrregularPatchCornerSpans` in the vertex topology
    /// or channel `fv`'s: for each corner, the span of its faces the patch
    /// uses where a discontinuity cuts its ring (the whole ring, unassigned,
    /// elsewhere), and whether the corner is sharp.
    pub(super) fn corner_spans(
        &self,
        level: usize,
        f: usize,
        fv: Option<&ChannelLevel>,
    ) -> Vec<Span> {
        let l = &self.levels[level];
        let tags = self.corner_tags(level, f, fv);
        let test_inf = self.inf_sharp_patch;
        let singular = Singular {
            inf_sharp: test_inf,
            fv,
        };
        let verts = l.face_verts(f);
        tags.iter()
            .enumerate()
            .map(|(i, tag)| {
                // The corner's rule as the topology read sees it.
                let dart = tag.rule == DART;
                let mismatch = value_tag(fv, l, f, i).is_mismatch();
                let test_inf_edges = test_inf && tag.inf_sharp_edges && !dart;
                let mut span = if tag.non_manifold {
                    self.non_manifold_span(level, f, i, singular)
                        .unwrap_or_default()
                } else if test_inf_edges || mismatch {
                    self.manifold_span(level, f, i, singular)
                } else {
                    Span::default()
                };
                if tag.corner {
                    // A channel's corner needs its span to be one face.
                    span.sharp = !mismatch || span.faces == 1 || tag.non_manifold;
                } else if tag.non_manifold {
                    span.sharp = tag.inf_sharp;
                } else if test_inf {
                    span.sharp = if test_inf_edges {
                        !tag.features.inf_sharp_crease
                    } else {
                        tag.inf_sharp
                    };
                }
                // The legacy option: a smooth corner of one face is sharp.
                if !span.sharp
                    && self.sharp_corners
                    && tag.features.xordinary
                    && tag.boundary
                    && !tag.inf_sharp
                    && !tag.non_manifold
                {
                    let faces = if span.is_assigned() {
                        span.faces
                    } else {
                        l.vertex_faces_of(verts[i] as usize).len()
                    };
                    span.sharp = faces == 1;
                }
                span
            })
            .collect()
    }
}

/// The faces around a corner a patch uses (`Vtr::Level::VSpan`):
/// unassigned (no faces) when it is the whole ring.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(super) struct Span {
    /// Number of faces (0: unassigned).
    pub faces: usize,
    /// The first face of the span in the vertex's faces.
    pub start_face: usize,
    /// The patch's face within the span.
    pub corner_in_span: usize,
    /// Whether the span closes on itself.
    pub periodic: bool,
    /// Whether the corner is sharp.
    pub sharp: bool,
}

impl Span {
    /// Whether the span was identified (not the whole ring).
    pub fn is_assigned(&self) -> bool {
        self.faces > 0
    }
}

/// OpenSubdiv's 5-bit boundary mask of a triangular patch: the upper two
/// bits say how to read the lower three (0: boundary edges, their vertices
/// implied; 1: boundary vertices only; 2: one boundary edge and the vertex
/// opposite it).
fn encode_tri_boundary(e_bits: u16, v_bits: u16) -> u16 {
    let (upper, lower) = if v_bits != 0 && e_bits == 0 {
        (1, v_bits)
    } else if v_bits == 7 && matches!(e_bits, 1 | 2 | 4) {
        (2, e_bits)
    } else {
        (0, e_bits)
    };
    (upper << 3) | lower
}

/// The boundary edges and boundary vertices of a triangular patch's mask.
pub(super) fn decode_tri_boundary(mask: u16) -> (u16, u16) {
    const VERTS_OF_EDGES: [u16; 8] = [0, 3, 6, 7, 5, 7, 7, 7];
    let lower = mask & 7;
    match (mask >> 3) & 3 {
        1 => (0, lower),
        2 => (lower, 7),
        _ => (lower, VERTS_OF_EDGES[lower as usize]),
    }
}
