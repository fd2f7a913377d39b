//! The base level of a face-varying channel: its values analysed from the
//! caller's value index per face corner — seams, siblings, the spans of
//! faces sharing a value, and how each vertex value is to be refined — as
//! OpenSubdiv's `FVarLevel::completeTopologyFromFaceValues`
//! (`vtr/fvarLevel.cpp`) analyses them.

use super::{ChannelLevel, FVarEdgeTag, Mode, ValueTag};
use crate::options::{BoundaryInterpolation, FVarLinearInterpolation, Options};
use crate::topology::{Level, Table};

/// A run of faces around a vertex sharing one value, and what interrupts or
/// crosses it.
#[derive(Debug, Clone, Copy, Default)]
struct Span {
    size: u16,
    start: u16,
    /// Channel splits inside the span (a value met in two separate runs counts too).
    splits: i32,
    semi_sharp_edges: u16,
    inf_sharp_edges: u16,
}

impl Span {
    fn count_edge(&mut self, level: &Level, fvar_tags: &[FVarEdgeTag], e: u32) {
        let e = e as usize;
        if fvar_tags[e].is_mismatch() {
            self.splits += 1;
        } else if level.edge_tag(e).inf_sharp() {
            self.inf_sharp_edges += 1;
        } else if level.edge_tag(e).semi_sharp() {
            self.semi_sharp_edges += 1;
        }
    }
}

/// Builds the base level of a channel from its value index per face corner
/// (`indices`, parallel to the level's face-vertices) and analyses it: seams,
/// siblings, and how each vertex value is to be refined under `options.fvar`.
///
/// `level` must carry its final sharpness and tags.
pub fn build_base(
    level: &Level,
    options: &Options,
    value_count: usize,
    indices: &[u32],
) -> ChannelLevel {
    let mode = Mode::new(options.fvar);
    let nv = level.vertex_count;
    let regular_boundary_valence = if options.scheme == crate::options::Scheme::Loop {
        3
    } else {
        2
    };
    let mut fvar = ChannelLevel {
        mode,
        value_count,
        face_values: Table::from(crate::alloc::copied(indices)),
        edge_tags: Table::zeroed(level.edge_count()),
        value_offsets: Table::new(),
        face_siblings: Table::zeroed(level.vertex_faces.members.len()),
        value_indices: Table::new(),
        value_tags: Table::new(),
        crease_ends: Table::new(),
    };
    let mut value_offsets: Vec<u32> = crate::alloc::with_capacity(nv + 1);

    let fvar_mode = options.fvar;
    let corners_sharp = fvar_mode != FVarLinearInterpolation::None;
    // Vertex corners that the vertex data keeps smooth but the channel sharpens.
    let sharpen_smooth_corners =
        options.boundary != BoundaryInterpolation::EdgeAndCorner && corners_sharp;
    let sharpen_both_if_one_corner = fvar_mode == FVarLinearInterpolation::CornersPlus2;
    let sharpen_darts = sharpen_both_if_one_corner || mode.linear_boundaries;

    // First pass: split edges, siblings and the number of values per vertex.
    let mut mismatch = crate::alloc::vec_or_unwind(false, nv);
    let mut around: Vec<u32> = Vec::with_capacity(level.max_valence);
    let mut unique: Vec<u32> = Vec::with_capacity(level.max_valence);
    let mut siblings: Vec<u16> = Vec::with_capacity(level.max_valence);
    let mut total = 0u32;
    // The relations as slices, read through their tables once; the corner
    // values straight from `indices` (what `face_values` copies).
    let ls = level.slices();
    for v in 0..nv {
        let faces = ls.vertex_faces_of(v);
        around.clear();
        around.extend(
            faces
                .iter()
                .zip(ls.vertex_face_locals(v))
                .map(|(&f, &k)| indices[ls.face_vertices.start(f as usize) + k as usize]),
        );
        let edges = ls.vertex_edges_of(v);
        let tag = ls.vertex_tag(v);
        let split = |e: u32, edge_tags: &mut [FVarEdgeTag], mismatch: &mut [bool]| {
            let [a, b] = ls.edge_vertices[e as usize];
            mismatch[a as usize] = true;
            mismatch[b as usize] = true;
            let t = &mut edge_tags[e as usize];
            t.set(FVarEdgeTag::SPLIT_AT_V0, a as usize == v);
            t.set(FVarEdgeTag::SPLIT_AT_V1, b as usize == v);
            t.set(FVarEdgeTag::MISMATCH, true);
            t.set(FVarEdgeTag::LINEAR, mode.linear_boundaries);
        };
        if !tag.non_manifold() {
            // Around a manifold vertex, edge i separates faces i - 1 and i
            // (the first edge of a boundary vertex has only face 0).
            let n = faces.len();
            for i in tag.boundary() as usize..n {
                let prev = if i == 0 { n - 1 } else { i - 1 };
                if around[i] != around[prev] {
                    split(edges[i], &mut fvar.edge_tags, &mut mismatch);
                }
            }
        } else if !faces.is_empty() {
            // No order to rely on: compare the value at v in every face of each edge.
            for (&e, &end) in edges.iter().zip(level.vertex_edge_locals(v)) {
                if level.edge_faces_of(e as usize).len() < 2 {
                    continue;
                }
                let ev = level.edge_vertices[e as usize];
                let mut first = 0;
                let mut differs = false;
                for (j, (f, k)) in level.edge_faces_at(e as usize).enumerate() {
                    let verts = level.face_verts(f);
                    let reversed = ev[0] != verts[k];
                    let mut corner = k + ((end != 0) != reversed) as usize;
                    if corner == verts.len() {
                        corner = 0;
                    }
                    let value = fvar.face_values_of(level, f)[corner];
                    if j == 0 {
                        first = value;
                    } else if value != first {
                        differs = true;
                        break;
                    }
                }
                if differs {
                    split(e, &mut fvar.edge_tags, &mut mismatch);
                }
            }
        }

        // Boundaries of the mesh are boundaries of the channel too.
        if tag.boundary() && !mismatch[v] {
            if mode.linear_boundaries && !faces.is_empty() {
                mismatch[v] = true;
                if !tag.non_manifold() {
                    fvar.edge_tags[edges[0] as usize].set(FVarEdgeTag::LINEAR, true);
                    fvar.edge_tags[edges[edges.len() - 1] as usize].set(FVarEdgeTag::LINEAR, true);
                } else {
                    for &e in edges {
                        if level.edge_tag(e as usize).boundary() {
                            fvar.edge_tags[e as usize].set(FVarEdgeTag::LINEAR, true);
                        }
                    }
                }
            } else if faces.len() == 1 && sharpen_smooth_corners {
                mismatch[v] = true;
            }
        }

        // Distinct values around the vertex, and each face's sibling. A value
        // differing from its predecessor is looked up among those found so
        // far — except with exactly two found, where it is compared with the
        // first only (so alternating values A B A B give three siblings, as
        // in OpenSubdiv).
        unique.clear();
        siblings.clear();
        unique.push(around.first().copied().unwrap_or(0));
        siblings.push(0);
        for i in 1..around.len() {
            let value = around[i];
            let s = if value == around[i - 1] {
                siblings[i - 1]
            } else if unique.len() == 1 || (unique.len() == 2 && unique[0] != value) {
                unique.push(value);
                (unique.len() - 1) as u16
            } else if let Some(p) = unique.iter().position(|&u| u == value) {
                p as u16
            } else {
                unique.push(value);
                (unique.len() - 1) as u16
            };
            siblings.push(s);
        }
        // Non-manifold vertices can carry several values without a split edge.
        if tag.non_manifold() && !mismatch[v] {
            mismatch[v] = unique.len() > 1;
        }
        value_offsets.push(total);
        total += unique.len() as u32;
        if unique.len() > 1 {
            fvar.face_siblings[ls.vertex_faces.range(v)].copy_from_slice(&siblings[..faces.len()]);
        }
    }
    value_offsets.push(total);
    fvar.value_offsets = value_offsets.into();

    // Second pass: the value of each sibling, and the tags of mismatched values.
    let total = total as usize;
    fvar.value_indices = Table::zeroed(total);
    fvar.value_tags = Table::zeroed(total);
    if mode.has_crease_ends() {
        fvar.crease_ends = Table::zeroed(total);
    }
    let mut spans: Vec<Span> = Vec::with_capacity(level.max_valence);
    for (v, &mismatched) in mismatch.iter().enumerate() {
        let faces = ls.vertex_faces_of(v);
        let corners = ls.vertex_face_locals(v);
        let corner_value =
            |i: usize| indices[ls.face_vertices.start(faces[i] as usize) + corners[i] as usize];
        let o = fvar.value_offsets[v] as usize;
        let count = fvar.vertex_value_count(v);
        fvar.value_indices[o] = if faces.is_empty() { 0 } else { corner_value(0) };
        if !mismatched {
            continue;
        }
        if count > 1 {
            // Sibling k is first met at the k-th change to a new sibling.
            let sibs = &fvar.face_siblings[level.vertex_faces.range(v)];
            let mut next = 1;
            for (i, &s) in sibs.iter().enumerate().skip(1) {
                if s as usize == next {
                    fvar.value_indices[o + next] = corner_value(i);
                    next += 1;
                }
            }
        }

        let vtag = level.vertex_tag(v);
        let mut all_sharp = mode.linear_boundaries
            || vtag.inf_sharp()
            || vtag.non_manifold()
            || (mode.dependent_sharpness && count > 2)
            || (sharpen_darts && count == 1 && !vtag.boundary());

        gather_spans(&fvar, level, v, &mut spans);

        // With two values, the sharpness of one may decide the other's.
        let mut sharpen_dependents = false;
        if !all_sharp && mode.dependent_sharpness && count == 2 {
            let (a, b) = (spans[0], spans[1]);
            all_sharp =
                a.inf_sharp_edges > 0 || b.inf_sharp_edges > 0 || a.splits != 0 || b.splits != 0;
            if sharpen_both_if_one_corner {
                all_sharp |= a.size == 1 || b.size == 1;
            }
            sharpen_dependents = (a.semi_sharp_edges > 0) != (b.semi_sharp_edges > 0);
        }

        for (i, span) in spans.iter().enumerate() {
            let mut vtag_i = ValueTag::default().with(ValueTag::MISMATCH);
            if span.splits != 0 {
                fvar.value_tags[o + i] = vtag_i.with(ValueTag::NON_MANIFOLD);
                continue;
            }
            let inf_sharp =
                all_sharp || span.inf_sharp_edges > 0 || (span.size == 1 && corners_sharp);
            // The features an adaptive selection reads (`considerFVarChannels`).
            let xordinary = if span.size == 1 {
                !inf_sharp
            } else {
                span.size as usize != regular_boundary_valence
            };
            let inf_irregular = if span.inf_sharp_edges > 0 {
                i32::from(span.size) - i32::from(span.inf_sharp_edges) > 1
            } else if inf_sharp {
                span.size > 1
            } else {
                xordinary
            };
            for (on, bit) in [
                (xordinary, ValueTag::XORDINARY),
                (span.inf_sharp_edges > 0, ValueTag::INF_SHARP_EDGES),
                (inf_irregular, ValueTag::INF_IRREGULAR),
            ] {
                if on {
                    vtag_i = vtag_i.with(bit);
                }
            }
            if !inf_sharp {
                vtag_i = if span.semi_sharp_edges > 0 || vtag.semi_sharp() {
                    vtag_i.with(ValueTag::SEMI_SHARP)
                } else if sharpen_dependents {
                    vtag_i.with(ValueTag::SEMI_SHARP).with(ValueTag::DEP_SHARP)
                } else {
                    vtag_i.with(ValueTag::CREASE)
                };
                if mode.has_crease_ends() {
                    let start = span.start as usize;
                    // The span of sibling 0 may wrap past the last face.
                    let last = start + span.size as usize - 1;
                    let end = if i == 0 && start != 0 {
                        last.wrapping_sub(faces.len())
                    } else {
                        last
                    };
                    fvar.crease_ends[o + i] = [start as u16, end as u16];
                }
            }
            fvar.value_tags[o + i] = vtag_i;
        }
    }
    fvar
}

/// The spans of the values of base vertex `v`, one per sibling, into `spans`.
fn gather_spans(fvar: &ChannelLevel, level: &Level, v: usize, spans: &mut Vec<Span>) {
    let count = fvar.vertex_value_count(v);
    spans.clear();
    spans.resize(count, Span::default());
    let edges = level.vertex_edges_of(v);
    let faces = level.vertex_faces_of(v);
    let n = faces.len();
    let boundary = edges.len() > n;

    if level.vertex_tag(v).non_manifold() {
        // Spans around a non-manifold vertex are not analysed: all are split.
        for s in spans.iter_mut() {
            s.size = 0;
            s.splits = 1;
        }
    } else if count == 1 && !boundary {
        // One value all around: a single split edge makes it a dart-like
        // span starting there; a second one disconnects it.
        let s = &mut spans[0];
        for (i, &e) in edges.iter().enumerate() {
            if fvar.edge_tags[e as usize].is_mismatch() {
                if s.size > 0 {
                    s.splits = 1;
                    break;
                }
                s.size = n as u16;
                s.start = i as u16;
            } else if level.edge_tag(e as usize).inf_sharp() {
                s.inf_sharp_edges += 1;
            } else if level.edge_tag(e as usize).semi_sharp() {
                s.semi_sharp_edges += 1;
            }
        }
        s.size = n as u16;
    } else {
        // Walk the faces; a run of sibling 0 at the end of an interior vertex
        // continues the run it started with.
        let sibs = fvar.vertex_face_siblings(level, v);
        let wraps = !boundary && n > 0 && sibs[n - 1] == 0;
        spans[0].size = 1;
        spans[0].start = 0;
        if wraps {
            spans[0].count_edge(level, &fvar.edge_tags, edges[0]);
        }
        for i in 1..n {
            let s = sibs[i] as usize;
            if sibs[i] == sibs[i - 1] {
                spans[s].count_edge(level, &fvar.edge_tags, edges[i]);
            } else {
                if spans[s].size > 0 {
                    spans[s].splits += 1;
                }
                spans[s].start = i as u16;
            }
            spans[s].size += 1;
        }
        if wraps {
            spans[0].splits -= 1;
        }
    }
}
