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
//! values become creases once their sharpness has decayed.

use super::{Level, Split};
use crate::options::{
    BoundaryInterpolation, CreasingMethod, FVarLinearInterpolation, Options, Scheme,
};
use crate::rules::crease;

/// Tags of an edge for one channel (packed bits).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct EdgeTag(u8);

impl EdgeTag {
    const MISMATCH: u8 = 1;
    const SPLIT_AT_V0: u8 = 2;
    const SPLIT_AT_V1: u8 = 4;
    const LINEAR: u8 = 8;

    /// The channel takes different values on the two sides of the edge.
    #[inline]
    pub fn is_mismatch(self) -> bool {
        self.0 & Self::MISMATCH != 0
    }

    /// The split was detected at the edge's first vertex.
    #[inline]
    pub fn is_split_at_v0(self) -> bool {
        self.0 & Self::SPLIT_AT_V0 != 0
    }

    /// The split was detected at the edge's second vertex.
    #[inline]
    pub fn is_split_at_v1(self) -> bool {
        self.0 & Self::SPLIT_AT_V1 != 0
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
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ValueTag(u8);

impl ValueTag {
    const MISMATCH: u8 = 1;
    const CREASE: u8 = 2;
    const SEMI_SHARP: u8 = 4;
    const DEP_SHARP: u8 = 8;
    const NON_MANIFOLD: u8 = 16;

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

    /// The faces sharing this value do not form a single run around the
    /// vertex, or the vertex is non-manifold: refined as a corner.
    #[inline]
    pub fn is_non_manifold(self) -> bool {
        self.0 & Self::NON_MANIFOLD != 0
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

/// How the faces of a level split: the one scheme-dependent ingredient of
/// face-varying refinement.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum FaceSplit {
    /// Catmull-Clark and bilinear: a face of `n` sides into `n` quads, child
    /// `j` of face `f` numbered `offsets[f] + j`; an edge point lies in two
    /// children of each face of its edge.
    Quads,
    /// Loop: a triangle into four, children of face `f` numbered `4f..4f+4`;
    /// an edge point lies in three children of each face of its edge.
    Triangles,
}

impl FaceSplit {
    fn of(scheme: Scheme) -> Self {
        match scheme {
            Scheme::Loop => FaceSplit::Triangles,
            Scheme::Catmark | Scheme::Bilinear => FaceSplit::Quads,
        }
    }

    /// Children of one parent face around the point of one of its edges.
    fn child_faces_per_edge_face(self) -> usize {
        match self {
            FaceSplit::Quads => 2,
            FaceSplit::Triangles => 3,
        }
    }

    /// The parent face of a child face.
    fn parent_face(self, parent: &Level, child_face: u32) -> u32 {
        match self {
            FaceSplit::Quads => parent.face_vertices.element_of(child_face as usize) as u32,
            FaceSplit::Triangles => child_face / 4,
        }
    }
}

/// One face-varying channel at one level.
#[derive(Debug, Clone, Default)]
pub struct ChannelLevel {
    mode: Mode,
    /// Number of values of the channel at this level.
    value_count: usize,
    /// The value of every face corner, parallel to the level's face-vertices.
    face_values: Vec<u32>,
    /// Per edge.
    edge_tags: Vec<EdgeTag>,
    /// Vertex values of vertex `v`: `value_offsets[v]..value_offsets[v + 1]`.
    value_offsets: Vec<u32>,
    /// Which sibling each vertex-face incidence uses, parallel to the level's
    /// vertex-faces.
    face_siblings: Vec<u16>,
    /// The channel's value index of each vertex value; empty when it is the
    /// vertex value's own index (every level but the base).
    value_indices: Vec<u32>,
    /// Per vertex value.
    value_tags: Vec<ValueTag>,
    /// Per vertex value, with smooth boundaries only: the positions (in the
    /// vertex's faces) of the first and last face of a crease's span.
    crease_ends: Vec<[u16; 2]>,
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

    /// The values of the corners of face `f` of `level`.
    #[inline]
    pub fn face_values_of(&self, level: &Level, f: usize) -> &[u32] {
        &self.face_values[level.face_vertices.range(f)]
    }

    /// Whether the channel is interpolated linearly everywhere.
    #[inline]
    pub fn is_linear(&self) -> bool {
        self.mode.linear
    }

    /// Whether the channel's boundaries are interpolated linearly.
    #[inline]
    pub fn has_linear_boundaries(&self) -> bool {
        self.mode.linear_boundaries
    }

    /// The tag of edge `e`.
    #[inline]
    pub fn edge_tag(&self, e: usize) -> EdgeTag {
        self.edge_tags[e]
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

    /// Which sibling each face of vertex `v` uses (in the level's vertex-face order).
    #[inline]
    pub fn vertex_face_siblings(&self, level: &Level, v: usize) -> &[u16] {
        &self.face_siblings[level.vertex_faces.range(v)]
    }

    /// The values at the two ends of edge `e` (in the edge's vertex order) as
    /// seen from its `i`-th face.
    pub fn edge_face_values(&self, level: &Level, e: usize, i: usize) -> [u32; 2] {
        let [v0, v1] = level.edge_vertices[e];
        if self.vertex_value_count(v0 as usize) + self.vertex_value_count(v1 as usize) > 2 {
            let f = level.edge_faces_of(e)[i] as usize;
            let k = level.edge_face_locals(e)[i] as usize;
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

    /// The value at the far end of each edge of vertex `v`, in the level's
    /// vertex-edge order, for a vertex where the channel is continuous.
    pub fn vertex_edge_values(&self, level: &Level, v: usize, out: &mut Vec<u32>) {
        out.clear();
        let edges = level.vertex_edges_of(v);
        let ends = level.vertex_edge_locals(v);
        let faces = level.vertex_faces_of(v);
        let corners = level.vertex_face_locals(v);
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
                let f = level.edge_faces_of(e as usize)[0] as usize;
                let k = level.edge_face_locals(e as usize)[0] as usize;
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
    /// lies on: the corner after `v` in the span's first face and the corner
    /// before `v` in its last face. Only channels with smooth boundaries keep
    /// crease spans.
    pub fn crease_end_values(&self, level: &Level, v: usize, s: usize) -> [u32; 2] {
        let [start, end] = self.crease_ends[self.value_offsets[v] as usize + s];
        let faces = level.vertex_faces_of(v);
        let corners = level.vertex_face_locals(v);
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
    /// they decay from `parent` to `child` (whose vertex `c` is `v`'s child).
    /// Only channels with smooth boundaries keep crease spans.
    pub fn fractional_weight(
        &self,
        parent: &Level,
        child: &Level,
        v: usize,
        s: usize,
        c: usize,
        creasing: CreasingMethod,
    ) -> f32 {
        let [start, end] = self.crease_ends[self.value_offsets[v] as usize + s];
        let (start, end) = (start as usize, end as usize);
        let p_edges = parent.vertex_edges_of(v);
        let c_edges = child.vertex_edges_of(c);
        let mut p_sharpness = Vec::with_capacity(p_edges.len());
        let mut c_sharpness = Vec::with_capacity(p_edges.len());
        // The edges strictly inside the span: between its consecutive faces.
        let mut take = |i: usize| {
            p_sharpness.push(parent.edge_sharpness_at(p_edges[i] as usize));
            c_sharpness.push(child.edge_sharpness_at(c_edges[i] as usize));
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
    fn count_edge(&mut self, level: &Level, fvar_tags: &[EdgeTag], e: u32) {
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
    let mut fvar = ChannelLevel {
        mode,
        value_count,
        face_values: indices.to_vec(),
        edge_tags: vec![EdgeTag::default(); level.edge_count()],
        value_offsets: Vec::with_capacity(nv + 1),
        face_siblings: vec![0; level.vertex_faces.members.len()],
        value_indices: Vec::new(),
        value_tags: Vec::new(),
        crease_ends: Vec::new(),
    };

    let fvar_mode = options.fvar;
    let corners_sharp = fvar_mode != FVarLinearInterpolation::None;
    // Vertex corners that the vertex data keeps smooth but the channel sharpens.
    let sharpen_smooth_corners =
        options.boundary != BoundaryInterpolation::EdgeAndCorner && corners_sharp;
    let sharpen_both_if_one_corner = fvar_mode == FVarLinearInterpolation::CornersPlus2;
    let sharpen_darts = sharpen_both_if_one_corner || mode.linear_boundaries;

    // First pass: split edges, siblings and the number of values per vertex.
    let mut mismatch = vec![false; nv];
    let mut around: Vec<u32> = Vec::with_capacity(level.max_valence);
    let mut unique: Vec<u32> = Vec::with_capacity(level.max_valence);
    let mut siblings: Vec<u16> = Vec::with_capacity(level.max_valence);
    let mut total = 0u32;
    for v in 0..nv {
        let faces = level.vertex_faces_of(v);
        around.clear();
        around.extend(
            faces
                .iter()
                .zip(level.vertex_face_locals(v))
                .map(|(&f, &k)| {
                    fvar.face_values[level.face_vertices.start(f as usize) + k as usize]
                }),
        );
        let edges = level.vertex_edges_of(v);
        let tag = level.vertex_tag(v);
        let split = |e: u32, edge_tags: &mut [EdgeTag], mismatch: &mut [bool]| {
            let [a, b] = level.edge_vertices[e as usize];
            mismatch[a as usize] = true;
            mismatch[b as usize] = true;
            let t = &mut edge_tags[e as usize];
            t.set(EdgeTag::SPLIT_AT_V0, a as usize == v);
            t.set(EdgeTag::SPLIT_AT_V1, b as usize == v);
            t.set(EdgeTag::MISMATCH, true);
            t.set(EdgeTag::LINEAR, mode.linear_boundaries);
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
                    fvar.edge_tags[edges[0] as usize].set(EdgeTag::LINEAR, true);
                    fvar.edge_tags[edges[edges.len() - 1] as usize].set(EdgeTag::LINEAR, true);
                } else {
                    for &e in edges {
                        if level.edge_tag(e as usize).boundary() {
                            fvar.edge_tags[e as usize].set(EdgeTag::LINEAR, true);
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
        fvar.value_offsets.push(total);
        total += unique.len() as u32;
        if unique.len() > 1 {
            fvar.face_siblings[level.vertex_faces.range(v)]
                .copy_from_slice(&siblings[..faces.len()]);
        }
    }
    fvar.value_offsets.push(total);

    // Second pass: the value of each sibling, and the tags of mismatched values.
    let total = total as usize;
    fvar.value_indices = vec![0; total];
    fvar.value_tags = vec![ValueTag::default(); total];
    if mode.has_crease_ends() {
        fvar.crease_ends = vec![[0, 0]; total];
    }
    let mut spans: Vec<Span> = Vec::with_capacity(level.max_valence);
    for (v, &mismatched) in mismatch.iter().enumerate() {
        let faces = level.vertex_faces_of(v);
        let corners = level.vertex_face_locals(v);
        let corner_value = |i: usize| {
            fvar.face_values[level.face_vertices.start(faces[i] as usize) + corners[i] as usize]
        };
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

/// Refines a channel from `parent_fvar` (on `parent`) to `child`, which
/// `parent` was split into with the numbering `r`.
pub fn refine(
    parent: &Level,
    child: &Level,
    r: &Split,
    parent_fvar: &ChannelLevel,
    options: &Options,
) -> ChannelLevel {
    let p = parent_fvar;
    let split = FaceSplit::of(options.scheme);
    let mode = p.mode;
    let (nv, ne, nf) = (
        parent.vertex_count,
        parent.edge_count(),
        parent.face_count(),
    );
    let ncv = child.vertex_count;

    // Values per child vertex: one per face point; one per edge point, or one
    // per incident face across a split edge; as many per vertex child as its
    // parent had when mismatched.
    let mut counts = vec![0u32; ncv];
    if r.has_face_points() {
        for f in 0..nf {
            counts[r.face_child(f) as usize] = 1;
        }
    }
    for e in 0..ne {
        counts[r.edge_child(e) as usize] = if p.edge_tags[e].is_mismatch() {
            parent.edge_faces.count(e).max(1) as u32
        } else {
            1
        };
    }
    for v in 0..nv {
        let matches = !p.value_tags[p.value_offsets[v] as usize].is_mismatch();
        counts[r.vertex_child(v) as usize] = if matches {
            1
        } else {
            p.vertex_value_count(v) as u32
        };
    }
    let mut value_offsets = Vec::with_capacity(ncv + 1);
    let mut total = 0u32;
    value_offsets.push(0);
    for &c in &counts {
        total += c;
        value_offsets.push(total);
    }
    let total = total as usize;

    let mut fvar = ChannelLevel {
        mode,
        value_count: total,
        face_values: Vec::new(),
        edge_tags: vec![EdgeTag::default(); child.edge_count()],
        value_offsets,
        face_siblings: vec![0; child.vertex_faces.members.len()],
        value_indices: Vec::new(),
        value_tags: vec![ValueTag::default(); total],
        crease_ends: if mode.has_crease_ends() {
            vec![[0, 0]; total]
        } else {
            Vec::new()
        },
    };

    // Siblings of the faces around child vertices with several values.
    for e in 0..ne {
        let e_faces = parent.edge_faces_of(e);
        if !p.edge_tags[e].is_mismatch() || e_faces.len() < 2 {
            continue;
        }
        let c = r.edge_child(e) as usize;
        let range = child.vertex_faces.range(c);
        for (slot, &cf) in fvar.face_siblings[range.clone()]
            .iter_mut()
            .zip(&child.vertex_faces.members[range])
        {
            let pf = split.parent_face(parent, cf);
            if let Some(j) = e_faces.iter().rposition(|&f| f == pf) {
                *slot = j as u16;
            }
        }
    }
    for v in 0..nv {
        let c = r.vertex_child(v) as usize;
        if counts[c] > 1 {
            let range = child.vertex_faces.range(c);
            fvar.face_siblings[range].copy_from_slice(p.vertex_face_siblings(parent, v));
        }
    }

    // Edge tags: edges inside faces are continuous, halves of an edge inherit.
    for e in 0..ne {
        for j in 0..2 {
            fvar.edge_tags[r.edge_child_edge(e, j) as usize] = p.edge_tags[e];
        }
    }

    // Value tags. Face points match; edge points of split or linear edges are
    // creases (corners with linear boundaries); vertex children inherit.
    let split_edge_tag = if mode.has_crease_ends() {
        ValueTag::default()
            .with(ValueTag::MISMATCH)
            .with(ValueTag::CREASE)
    } else {
        ValueTag::default().with(ValueTag::MISMATCH)
    };
    for e in 0..ne {
        let t = p.edge_tags[e];
        if t.is_mismatch() || t.is_linear() {
            let c = r.edge_child(e) as usize;
            let range = fvar.value_offsets[c] as usize..fvar.value_offsets[c + 1] as usize;
            fvar.value_tags[range].fill(split_edge_tag);
        }
    }
    for v in 0..nv {
        let c = r.vertex_child(v) as usize;
        let o = fvar.value_offsets[c] as usize;
        let n = counts[c] as usize;
        let po = p.value_offsets[v] as usize;
        fvar.value_tags[o..o + n].copy_from_slice(&p.value_tags[po..po + n]);
    }

    if mode.has_crease_ends() {
        // An edge point's value i spans the children of the edge's face i.
        let per_face = split.child_faces_per_edge_face();
        for e in 0..ne {
            let c = r.edge_child(e) as usize;
            let o = fvar.value_offsets[c] as usize;
            if !fvar.value_tags[o].is_mismatch() {
                continue;
            }
            for i in 0..counts[c] as usize {
                if !fvar.value_tags[o + i].is_inf_sharp() {
                    let start = i * per_face;
                    fvar.crease_ends[o + i] = [start as u16, (start + per_face - 1) as u16];
                }
            }
        }
        // A vertex's child keeps its faces in the same order: same spans.
        for v in 0..nv {
            let c = r.vertex_child(v) as usize;
            let o = fvar.value_offsets[c] as usize;
            if !fvar.value_tags[o].is_mismatch() {
                continue;
            }
            let po = p.value_offsets[v] as usize;
            for i in 0..counts[c] as usize {
                if !fvar.value_tags[o + i].is_inf_sharp() {
                    fvar.crease_ends[o + i] = p.crease_ends[po + i];
                }
            }
        }
        reclassify_semi_sharp(parent, child, r, p, &mut fvar);
    }

    // Face values: each corner's vertex value, offset by its sibling.
    fvar.face_values = if total > ncv {
        let mut values: Vec<u32> = child
            .face_vertices
            .members
            .iter()
            .map(|&v| fvar.value_offsets[v as usize])
            .collect();
        for (c, _) in counts.iter().enumerate().filter(|&(_, &n)| n > 1) {
            let range = child.vertex_faces.range(c);
            for i in range {
                let s = fvar.face_siblings[i];
                if s != 0 {
                    let f = child.vertex_faces.members[i] as usize;
                    let corner = child.face_vertices.start(f) + child.vertex_face_local[i] as usize;
                    values[corner] += s as u32;
                }
            }
        }
        values
    } else {
        child.face_vertices.members.to_vec()
    };
    fvar
}

/// Turns semi-sharp values of vertex children into creases once no
/// semi-sharp edge is left inside their span (or the vertex lost all its
/// semi-sharp features).
fn reclassify_semi_sharp(
    parent: &Level,
    child: &Level,
    r: &Split,
    p: &ChannelLevel,
    fvar: &mut ChannelLevel,
) {
    for v in 0..parent.vertex_count {
        let c = r.vertex_child(v) as usize;
        let range = fvar.value_offsets[c] as usize..fvar.value_offsets[c + 1] as usize;
        if !fvar.value_tags[range.start].is_mismatch() {
            continue;
        }
        let ptag = parent.vertex_tag(v);
        if !ptag.semi_sharp() && !ptag.semi_sharp_edges() {
            continue;
        }
        let ctag = child.vertex_tag(c);
        if ctag.semi_sharp() || ctag.inf_sharp() {
            continue;
        }
        if !ctag.semi_sharp_edges() {
            for t in &mut fvar.value_tags[range] {
                if t.is_semi_sharp() {
                    *t = t.into_crease();
                }
            }
            continue;
        }
        let c_edges = child.vertex_edges_of(c);
        let semi = |k: usize| child.edge_tag(c_edges[k] as usize).semi_sharp();
        for i in range.clone() {
            let t = fvar.value_tags[i];
            if !t.is_semi_sharp() || t.is_dep_sharp() {
                continue;
            }
            let [start, end] = fvar.crease_ends[i];
            let (start, end) = (start as usize, end as usize);
            let still = if end > start {
                (start + 1..=end).any(semi)
            } else if start > end {
                (start + 1..c_edges.len()).any(semi) || (0..=end).any(semi)
            } else {
                false
            };
            if !still {
                fvar.value_tags[i] = t.into_crease();
            }
        }
        // A dependency on a value that is no longer semi-sharp is dropped.
        if range.len() == 2 && p.mode.dependent_sharpness {
            let (a, b) = (
                fvar.value_tags[range.start],
                fvar.value_tags[range.start + 1],
            );
            let clear = |t: ValueTag| ValueTag(t.0 & !ValueTag::DEP_SHARP);
            if a.is_dep_sharp() && !b.is_semi_sharp() {
                fvar.value_tags[range.start] = clear(a);
            } else if b.is_dep_sharp() && !a.is_semi_sharp() {
                fvar.value_tags[range.start + 1] = clear(b);
            }
        }
    }
}
