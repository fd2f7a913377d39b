//! Face-varying channels (UVs and the like): their topology at one level and
//! how it is split into the next — the native counterpart of OpenSubdiv's
//! `Vtr::FVarLevel` and `Vtr::FVarRefinement`.
//!
//! # The model
//!
//! A channel gives every face corner a *value* index. Around a vertex the
//! corners may all use one value (the channel is continuous there) or
//! several: the channel has a seam through the vertex. Each distinct value
//! around vertex `v` is a *vertex value*; the first is sibling 0, the others
//! are numbered in the order they are met walking the vertex's faces (the
//! level's counter-clockwise order). A [`ChannelLevel`] stores, flat:
//!
//! * the value of every face corner ([`ChannelLevel::face_values`]);
//! * for every vertex, the range of its vertex values (`value_offsets`) and,
//!   per vertex-face incidence, which sibling that face uses;
//! * a tag per edge (is the channel split across it? must it stay linear?);
//! * a tag per vertex value (does it follow the vertex's own topology, or is
//!   it a corner, a smooth crease along the seam, or a semi-sharp corner
//!   decaying into a crease?) and, for creases, the two faces at the ends of
//!   the run of faces ("span") sharing that value.
//!
//! Vertex values are numbered vertex by vertex, in vertex order. At every
//! refined level the channel's values are exactly these vertex values, so a
//! value's index is its vertex-value index (and the vertex's own index when
//! no vertex has siblings: the face values are then the face-vertices). Only
//! the base level keeps a table from vertex values to the caller's value
//! indices, since the caller numbers values freely.
//!
//! # Refinement
//!
//! Children inherit topology rather than re-analysing it: a face point gets
//! one value; an edge point one value, or one per incident face when the
//! channel is split across the edge; a vertex's child as many values as the
//! vertex, with the same tags, sibling assignment and crease spans. Semi-sharp
//! values become creases once their sharpness has decayed. Into a minimal
//! last level (which keeps no vertex-faces) each corner's value is read from
//! the parent's faces, and the level keeps no siblings, edge tags or spans:
//! nothing refines it further.
//!
//! # Files
//!
//! * this file: the tags, the linear-interpolation mode and [`ChannelLevel`]
//!   with its accessors (`Vtr::FVarLevel`, `vtr/fvarLevel.h`);
//! * `base.rs`: [`build_base`], the analysis of the base level's values —
//!   seams, siblings, spans and value tags
//!   (`FVarLevel::completeTopologyFromFaceValues` in `vtr/fvarLevel.cpp`);
//! * `refine.rs`: [`refine()`], a channel split into the next level
//!   (`Vtr::FVarRefinement`, `vtr/fvarRefinement.cpp`).

mod base;
mod refine;

pub use base::build_base;
pub use refine::Children;
pub(crate) use refine::missing;
pub(crate) use refine::{refine, refine_values_only};

use super::{Around, Hood, Level, Table};
use crate::options::{CreasingMethod, FVarLinearInterpolation};
use crate::rules::crease;

/// Tags of an edge for one channel (packed bits).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(transparent)]
pub struct FVarEdgeTag(u8);

impl FVarEdgeTag {
    const MISMATCH: u8 = 1;
    const SPLIT_AT_V0: u8 = 2;
    const SPLIT_AT_V1: u8 = 4;
    const LINEAR: u8 = 8;

    /// The channel takes different values on the two sides of the edge.
    #[inline]
    pub fn is_mismatch(self) -> bool {
        self.0 & Self::MISMATCH != 0
    }

    /// The edge lies on a boundary of the channel that is interpolated linearly.
    #[inline]
    pub fn is_linear(self) -> bool {
        self.0 & Self::LINEAR != 0
    }

    #[inline]
    fn set(&mut self, bit: u8, on: bool) {
        if on {
            self.0 |= bit;
        } else {
            self.0 &= !bit;
        }
    }
}

/// Tags of one vertex value (packed bits). Only a *mismatched* value has
/// meaningful other bits; it is then exactly one of: a corner (kept as is), a
/// crease (smooth along the seam) or semi-sharp (a corner turning into a
/// crease as sharpness decays).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(transparent)]
pub struct ValueTag(u8);

impl ValueTag {
    const MISMATCH: u8 = 1;
    const CREASE: u8 = 2;
    const SEMI_SHARP: u8 = 4;
    const DEP_SHARP: u8 = 8;
    const NON_MANIFOLD: u8 = 16;
    /// The value's span has not the regular boundary valence (what a
    /// feature-adaptive selection of face-varying features reads).
    const XORDINARY: u8 = 32;
    /// Infinitely sharp edges lie inside the value's span.
    const INF_SHARP_EDGES: u8 = 64;
    /// The value's infinitely sharp features are not a regular patch's.
    const INF_IRREGULAR: u8 = 128;

    /// The channel's topology around the vertex differs from the vertex's
    /// (a seam, a linearly interpolated boundary or a sharpened corner).
    #[inline]
    pub fn is_mismatch(self) -> bool {
        self.0 & Self::MISMATCH != 0
    }

    /// A smooth boundary (crease) of the channel.
    #[inline]
    pub fn is_crease(self) -> bool {
        self.0 & Self::CREASE != 0
    }

    /// Not a crease: refined as a corner (semi-sharp values included).
    #[inline]
    pub fn is_corner(self) -> bool {
        !self.is_crease()
    }

    /// A corner for now, becoming a crease when the sharpness around it decays.
    #[inline]
    pub fn is_semi_sharp(self) -> bool {
        self.0 & Self::SEMI_SHARP != 0
    }

    /// A corner for good.
    #[inline]
    pub fn is_inf_sharp(self) -> bool {
        !self.is_semi_sharp() && !self.is_crease()
    }

    /// Semi-sharp only because the vertex's other value is.
    #[inline]
    pub fn is_dep_sharp(self) -> bool {
        self.0 & Self::DEP_SHARP != 0
    }

    /// Split off by a non-manifold arrangement of the channel.
    #[inline]
    pub fn is_non_manifold(self) -> bool {
        self.0 & Self::NON_MANIFOLD != 0
    }

    /// Its span has not the regular boundary valence.
    #[inline]
    pub fn is_xordinary(self) -> bool {
        self.0 & Self::XORDINARY != 0
    }

    /// Infinitely sharp edges lie inside its span.
    #[inline]
    pub fn has_inf_sharp_edges(self) -> bool {
        self.0 & Self::INF_SHARP_EDGES != 0
    }

    /// Its infinitely sharp features are not a regular patch's.
    #[inline]
    pub fn is_inf_irregular(self) -> bool {
        self.0 & Self::INF_IRREGULAR != 0
    }

    #[inline]
    fn with(self, bit: u8) -> Self {
        ValueTag(self.0 | bit)
    }

    /// Drops the semi-sharp (and dependency) bits, making the value a crease.
    #[inline]
    fn into_crease(self) -> Self {
        ValueTag((self.0 & !(Self::SEMI_SHARP | Self::DEP_SHARP)) | Self::CREASE)
    }
}

/// What the linear-interpolation option implies, per channel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
struct Mode {
    /// Everything linear (`All`).
    linear: bool,
    /// Channel boundaries linear (`All`, `Boundaries`).
    linear_boundaries: bool,
    /// A vertex with two values may be sharpened by its other value
    /// (`CornersPlus1`, `CornersPlus2`).
    dependent_sharpness: bool,
}

impl Mode {
    fn new(fvar: FVarLinearInterpolation) -> Self {
        use FVarLinearInterpolation as F;
        Mode {
            linear: fvar == F::All,
            linear_boundaries: matches!(fvar, F::All | F::Boundaries),
            dependent_sharpness: matches!(fvar, F::CornersPlus1 | F::CornersPlus2),
        }
    }

    /// Smooth channel boundaries keep the faces at the ends of each crease.
    fn has_crease_ends(self) -> bool {
        !self.linear_boundaries
    }
}

/// One face-varying channel at one level.
///
/// Every per-element array is a [`Table`], so that a dropped level's
/// memory goes to the pool for the next level or refinement instead of
/// back to the allocator (as vectors, each level of a sparse refinement
/// faulted its channel's arrays in anew: about 2,000 of the 2,700 page
/// faults of each adaptive refinement of the production-like mesh).
#[derive(Debug, Clone, Default)]
pub struct ChannelLevel {
    mode: Mode,
    /// Number of values of the channel at this level.
    value_count: usize,
    /// The value of every face corner, parallel to the level's face-vertices
    /// (a [`Table`]: as large as the face-vertices, and like them written
    /// into memory a dropped refinement left, when there is some). Empty in
    /// the last level of `refiner::whole`'s private refiner, which returns
    /// only that level's values ([`refine_values_only`]).
    face_values: Table<u32>,
    /// Per edge.
    edge_tags: Table<FVarEdgeTag>,
    /// Vertex values of vertex `v`: `value_offsets[v]..value_offsets[v + 1]`.
    value_offsets: Table<u32>,
    /// Which sibling each vertex-face incidence uses, parallel to the level's
    /// vertex-faces.
    face_siblings: Table<u16>,
    /// The channel's value index of each vertex value; empty when it is the
    /// vertex value's own index (every level but the base).
    value_indices: Table<u32>,
    /// Per vertex value.
    value_tags: Table<ValueTag>,
    /// Per vertex value, with smooth boundaries only: the positions (in the
    /// vertex's faces) of the first and last face of a crease's span.
    crease_ends: Table<[u16; 2]>,
}

impl ChannelLevel {
    /// Number of values.
    #[inline]
    pub fn value_count(&self) -> usize {
        self.value_count
    }

    /// Value index of every face corner, parallel to the level's face-vertices.
    #[inline]
    pub fn face_values(&self) -> &[u32] {
        &self.face_values
    }

    /// The tags of edge `e` for this channel.
    #[inline]
    pub fn edge_tag(&self, e: usize) -> FVarEdgeTag {
        self.edge_tags[e]
    }

    /// The tags of every edge for this channel, in edge order.
    #[inline]
    pub(crate) fn edge_tags(&self) -> &[FVarEdgeTag] {
        &self.edge_tags
    }

    /// The tags of every vertex's first value (sibling 0), in vertex order.
    pub(crate) fn first_value_tags(&self) -> impl Iterator<Item = ValueTag> + '_ {
        let vertices = self.value_offsets.len().saturating_sub(1);
        self.value_offsets[..vertices]
            .iter()
            .map(|&o| self.value_tags[o as usize])
    }

    /// The values of the corners of face `f` of `level`.
    #[inline]
    pub fn face_values_of(&self, level: &Level, f: usize) -> &[u32] {
        &self.face_values[level.face_vertices.range(f)]
    }

    /// The faces of `level` with a corner whose value is not its vertex's
    /// first (sibling 0), in order. Faces of one size (every refined level
    /// but Catmull-Clark's first) are read as fixed-size chunks.
    pub(crate) fn faces_off_first_values(&self, level: &Level) -> Vec<u32> {
        let first = |v: u32| self.vertex_value(v as usize, 0);
        let off =
            |verts: &[u32], values: &[u32]| verts.iter().zip(values).any(|(&v, &x)| first(v) != x);
        let verts: &[u32] = &level.face_vertices.members;
        let values: &[u32] = &self.face_values;
        debug_assert_eq!(verts.len(), values.len());
        let mut out = Vec::new();
        match level.face_vertices.offsets {
            super::Offsets::Uniform { size, .. } if size > 0 => {
                for (f, (vs, xs)) in verts
                    .chunks_exact(size)
                    .zip(values.chunks_exact(size))
                    .enumerate()
                {
                    if off(vs, xs) {
                        out.push(f as u32);
                    }
                }
            }
            _ => {
                let faces = level.face_vertices.view();
                for f in 0..faces.len() {
                    let range = faces.range(f);
                    if off(&verts[range.clone()], &values[range]) {
                        out.push(f as u32);
                    }
                }
            }
        }
        out
    }

    /// Whether the channel is interpolated linearly everywhere.
    #[inline]
    pub fn is_linear(&self) -> bool {
        self.mode.linear
    }

    /// Number of values at vertex `v` (1 unless a seam passes through it).
    #[inline]
    pub fn vertex_value_count(&self, v: usize) -> usize {
        (self.value_offsets[v + 1] - self.value_offsets[v]) as usize
    }

    /// Index of the first vertex value of vertex `v` (its siblings follow).
    #[inline]
    pub fn vertex_value_offset(&self, v: usize) -> u32 {
        self.value_offsets[v]
    }

    /// The channel's value index of sibling `s` of vertex `v`.
    #[inline]
    pub fn vertex_value(&self, v: usize, s: usize) -> u32 {
        let i = self.value_offsets[v] + s as u32;
        if self.value_indices.is_empty() {
            i
        } else {
            self.value_indices[i as usize]
        }
    }

    /// The tags of the values of vertex `v`, sibling by sibling.
    #[inline]
    pub fn vertex_value_tags(&self, v: usize) -> &[ValueTag] {
        &self.value_tags[self.value_offsets[v] as usize..self.value_offsets[v + 1] as usize]
    }

    /// Which sibling each face of vertex `v` uses (in the level's vertex-face
    /// order), for a level that stores its vertex-faces (not one that
    /// derives them: see [`ChannelLevel::corner_sibling`]).
    #[inline]
    pub fn vertex_face_siblings(&self, level: &Level, v: usize) -> &[u16] {
        &self.face_siblings[level.vertex_faces.range(v)]
    }

    /// Which sibling of vertex `v` face `f` of `level` uses at its corner
    /// `k` (where `v` is): stored with the vertex-faces, or — in a refined
    /// level, where a value is numbered as its vertex value — read from the
    /// corner's value.
    #[inline]
    pub(crate) fn corner_sibling(
        &self,
        level: &Level,
        v: usize,
        f: usize,
        k: usize,
        i: usize,
    ) -> u16 {
        if self.face_siblings.is_empty() {
            debug_assert!(self.value_indices.is_empty());
            let value = self.face_values[level.face_vertices.start(f) + k];
            (value - self.value_offsets[v]) as u16
        } else {
            self.face_siblings[level.vertex_faces.start(v) + i]
        }
    }

    /// The values at the two ends of edge `e` (in the edge's vertex order) as
    /// seen from its `i`-th face.
    pub(crate) fn edge_face_values(&self, around: &Around, e: usize, i: usize) -> [u32; 2] {
        let level = around.level;
        let [v0, v1] = level.edge_vertices[e];
        if self.vertex_value_count(v0 as usize) + self.vertex_value_count(v1 as usize) > 2 {
            let (f, k) = around.edge_face(e, i);
            let values = self.face_values_of(level, f);
            let next = if k + 1 < values.len() { k + 1 } else { 0 };
            if level.face_verts(f)[k] == v0 {
                [values[k], values[next]]
            } else {
                [values[next], values[k]]
            }
        } else {
            [
                self.vertex_value(v0 as usize, 0),
                self.vertex_value(v1 as usize, 0),
            ]
        }
    }

    /// The value at the far end of each edge of vertex `v` (whose relations
    /// are `hood`), in the level's vertex-edge order, for a vertex where the
    /// channel is continuous.
    pub(crate) fn vertex_edge_values(
        &self,
        around: &Around,
        hood: &Hood,
        v: usize,
        out: &mut Vec<u32>,
    ) {
        out.clear();
        let level = around.level;
        let (edges, ends) = (hood.edges, hood.edge_locals);
        let (faces, corners) = (hood.faces, hood.face_locals);
        let tag = level.vertex_tag(v);
        for (i, (&e, &end)) in edges.iter().zip(ends).enumerate() {
            let other = level.edge_vertices[e as usize][1 - end as usize] as usize;
            let value = if self.vertex_value_count(other) == 1 {
                self.vertex_value(other, 0)
            } else if !tag.non_manifold() {
                // Edge i leaves v inside face i, except the last edge of a
                // boundary vertex, which closes face i - 1.
                if tag.boundary() && i + 1 == edges.len() {
                    let values = self.face_values_of(level, faces[i - 1] as usize);
                    let k = corners[i - 1] as usize;
                    values[if k == 0 { values.len() - 1 } else { k - 1 }]
                } else {
                    let values = self.face_values_of(level, faces[i] as usize);
                    let k = corners[i] as usize;
                    values[if k + 1 == values.len() { 0 } else { k + 1 }]
                }
            } else {
                // No order around v to rely on: read the edge's first face.
                let (f, k) = around.edge_face(e as usize, 0);
                let values = self.face_values_of(level, f);
                if level.face_verts(f)[k] as usize == other {
                    values[k]
                } else {
                    values[if k + 1 == values.len() { 0 } else { k + 1 }]
                }
            };
            out.push(value);
        }
    }

    /// The values at the two ends of the crease that sibling `s` of vertex `v`
    /// (whose relations are `hood`) lies on: the corner after `v` in the
    /// span's first face and the corner before `v` in its last face. Only
    /// channels with smooth boundaries keep crease spans.
    pub(crate) fn crease_end_values(
        &self,
        level: &Level,
        hood: &Hood,
        v: usize,
        s: usize,
    ) -> [u32; 2] {
        let [start, end] = self.crease_ends[self.value_offsets[v] as usize + s];
        let (faces, corners) = (hood.faces, hood.face_locals);
        let first = self.face_values_of(level, faces[start as usize] as usize);
        let last = self.face_values_of(level, faces[end as usize] as usize);
        let k0 = corners[start as usize] as usize;
        let k1 = corners[end as usize] as usize;
        [
            first[if k0 + 1 == first.len() { 0 } else { k0 + 1 }],
            last[if k1 == 0 { last.len() } else { k1 } - 1],
        ]
    }

    /// The weight of the corner mask when sibling `s` of parent vertex `v`
    /// turns from a semi-sharp corner into a crease: the fractional weight of
    /// the vertex's sharpness and of the edges inside the value's span, as
    /// they decay from `parent` to `child` (whose vertex `c` is `v`'s child;
    /// `hood`: `v`'s relations in `parent`). Only channels with smooth
    /// boundaries keep crease spans.
    pub(crate) fn fractional_weight(
        &self,
        (parent, child): (&Level, &Level),
        hood: &Hood,
        v: usize,
        s: usize,
        c: usize,
        creasing: CreasingMethod,
    ) -> f32 {
        let [start, end] = self.crease_ends[self.value_offsets[v] as usize + s];
        let (start, end) = (start as usize, end as usize);
        let p_edges = hood.edges;
        let c_edges = child_vertex_edge_sharpness((parent, child), hood, c, creasing);
        let mut p_sharpness = Vec::with_capacity(p_edges.len());
        let mut c_sharpness = Vec::with_capacity(p_edges.len());
        // The edges strictly inside the span: between its consecutive faces.
        let mut take = |i: usize| {
            p_sharpness.push(parent.edge_sharpness_at(p_edges[i] as usize));
            c_sharpness.push(c_edges[i]);
        };
        if end > start {
            (start + 1..=end).for_each(&mut take);
        } else if start > end {
            (start + 1..p_edges.len()).for_each(&mut take);
            (0..=end).for_each(&mut take);
        }
        let child_edges = match creasing {
            CreasingMethod::Uniform => None,
            CreasingMethod::Chaikin => Some(c_sharpness.as_slice()),
        };
        crease::fractional_weight_at_vertex(
            parent.vertex_sharpness_at(v),
            child.vertex_sharpness_at(c),
            &p_sharpness,
            child_edges,
        )
    }
}

/// The sharpness of the edges of child vertex `c`, the child of the parent
/// vertex whose relations in `parent` are `hood`, in the order of that
/// vertex's edges: read from a child level that keeps its vertex-edges, or —
/// in a level that keeps none or derives them — the halves of the parent
/// vertex's edges at that vertex decayed from the parent as the child's tags
/// are (`refine::child_edge`).
pub(super) fn child_vertex_edge_sharpness(
    (parent, child): (&Level, &Level),
    hood: &Hood,
    c: usize,
    creasing: CreasingMethod,
) -> Vec<f32> {
    if child.vertex_edges.len() == child.vertex_count {
        return child
            .vertex_edges_of(c)
            .iter()
            .map(|&e| child.edge_sharpness_at(e as usize))
            .collect();
    }
    let mut around = Vec::new();
    hood.edges
        .iter()
        .zip(hood.edge_locals)
        .map(|(&e, &end)| {
            crate::topology::refine::child_edge(
                parent,
                e as usize,
                end as usize,
                creasing,
                &mut around,
            )
            .0
        })
        .collect()
}
