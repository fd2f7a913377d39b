//! Splitting one level into the next, in OpenSubdiv's order — the native
//! counterpart of `Vtr::Refinement` and its two subclasses
//! (`vtr/refinement.cpp`, `vtr/quadRefinement.cpp`, `vtr/triRefinement.cpp`).
//!
//! Children are numbered by where they come from:
//!
//! * child **faces**: parent face `f` with `n` vertices gives `n` quads
//!   (child `j` at corner `j`), numbered in parent face order;
//! * child **edges**: first the `n` edges inside each parent face (edge `j`
//!   joins the face point to the point of face-edge `j`), then two per parent
//!   edge (child `j` holds the end vertex `j`);
//! * child **vertices**: by default the children of vertices, then of faces,
//!   then of edges; with `order_vertices_from_faces_first`, faces, edges,
//!   then vertices.
//!
//! Loop's triangle split gives four child faces per triangle instead (the
//! three corner triangles, child `j` at corner `j`, then the middle one) and
//! no face points; its child edges and vertices follow the same order.
//!
//! # Where each part lives
//!
//! * this file: the numbering of one step ([`Split`], OpenSubdiv's
//!   parent-to-child mapping), how much of the child is built ([`Build`]),
//!   the driver [`refine_level`], the carving of parent faces into parallel
//!   chunks and the assembly of the child level (`vtr/refinement.cpp`);
//! * `quad.rs`: the quad split of Catmull-Clark and bilinear — child faces,
//!   edges and the relations of each child vertex (`vtr/quadRefinement.cpp`);
//! * `tri.rs`: Loop's triangle split, likewise (`vtr/triRefinement.cpp`);
//! * `tags.rs`: the sharpness, tags and holes of the child level, built
//!   alongside its topology (`propagateComponentTags` and
//!   `subdivideSharpnessValues` in `vtr/refinement.cpp`), and
//!   [`child_edge_sharpness`] for a minimal last level that stores none;
//! * `relations.rs`: the writers that fill the child's relations element by
//!   element, and the `Sink` the per-vertex rules of both splits write into;
//! * `derive.rs`: the relations of a level built without them
//!   ([`Level::derived_relations`]), derived on demand from its parent with
//!   the same per-vertex rules — what the refiner's interpolation kernel
//!   reads there (OpenSubdiv always stores them).
//!
//! * `sparse.rs`: sparse refinement, part of a level split with explicit
//!   parent-to-child maps (`Vtr::SparseSelector` and the sparse paths of
//!   `vtr/refinement.cpp` and `vtr/quadRefinement.cpp`), what adaptive
//!   refinement builds on.

mod derive;
mod quad;
mod relations;
pub mod sparse;
mod tags;
mod tri;

pub(crate) use derive::{
    derive_edge_faces, derive_half_edge_faces, derive_half_edge_wings, derive_inner_edge_wings,
    derive_limit_ring, derive_quad_edge_faces_in_order, derive_smooth_hood,
    derive_vertex_relations,
};
pub(crate) use tags::child_edge;
pub use tags::child_edge_sharpness;

use super::{Level, Relation, Table};
use crate::options::{Options, Scheme};
use tags::ChildTags;

/// The parent-to-child numbering of one refinement step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Split {
    /// Number of parent vertices, edges, and faces with a face point (0 for Loop).
    pub parent_counts: [usize; 3],
    /// Number of parent face corners.
    pub parent_corners: usize,
    /// Index of the first child vertex of a parent vertex.
    pub first_vertex_from_vertices: u32,
    /// Index of the first child vertex of a parent face.
    pub first_vertex_from_faces: u32,
    /// Index of the first child vertex of a parent edge.
    pub first_vertex_from_edges: u32,
}

impl Split {
    /// Numbering for a parent level, default or faces-first vertex order.
    pub fn new(parent: &Level, faces_first: bool, face_points: bool) -> Self {
        let (nv, ne) = (parent.vertex_count, parent.edge_count());
        // Loop's triangle split has no face points.
        let nf = if face_points { parent.face_count() } else { 0 };
        let (fv, ff, fe) = if faces_first {
            ((nf + ne) as u32, 0, nf as u32)
        } else {
            (0, nv as u32, (nv + nf) as u32)
        };
        Split {
            parent_counts: [nv, ne, nf],
            parent_corners: parent.face_vertices.members.len(),
            first_vertex_from_vertices: fv,
            first_vertex_from_faces: ff,
            first_vertex_from_edges: fe,
        }
    }

    /// The child vertex of parent vertex `v`.
    #[inline]
    pub fn vertex_child(&self, v: usize) -> u32 {
        self.first_vertex_from_vertices + v as u32
    }

    /// Whether parent faces get a child vertex (false for Loop's triangle split).
    #[inline]
    pub fn has_face_points(&self) -> bool {
        self.parent_counts[2] > 0
    }

    /// The child vertex (face point) of parent face `f`.
    #[inline]
    pub fn face_child(&self, f: usize) -> u32 {
        self.first_vertex_from_faces + f as u32
    }

    /// The child vertex (edge point) of parent edge `e`.
    #[inline]
    pub fn edge_child(&self, e: usize) -> u32 {
        self.first_vertex_from_edges + e as u32
    }

    /// The child edge of parent edge `e` at its end `j`.
    #[inline]
    pub fn edge_child_edge(&self, e: usize, j: usize) -> u32 {
        (self.parent_corners + 2 * e + j) as u32
    }

    /// Number of child vertices.
    pub fn child_vertex_count(&self) -> usize {
        self.parent_counts.iter().sum()
    }
}

#[inline]
pub(super) fn prev(j: usize, n: usize) -> usize {
    if j == 0 { n - 1 } else { j - 1 }
}

#[inline]
pub(super) fn next(j: usize, n: usize) -> usize {
    if j + 1 == n { 0 } else { j + 1 }
}

/// How much of a child level [`refine_level`] builds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Build {
    /// Every relation, with local indices: a level that is refined further
    /// into a full level, or that face-varying channels or limit evaluation
    /// read.
    Full,
    /// Every relation but the positions of edges and vertices within their
    /// faces (`edge_face_local` and `vertex_face_local` stay empty): a level
    /// whose only child is a minimal last level. Interpolation does not read
    /// them; only building a full child, face-varying refinement and limit
    /// evaluation do. `vertex_edge_local` stays when the parent has
    /// sharpness: the decay of semi-sharp features into the child reads it.
    /// Where the parent is smooth everywhere (no sharpness, no tags, two
    /// faces on every edge), the vertex-faces, vertex-edges and edge-faces
    /// are left out too and derived from the parent when interpolation reads
    /// them ([`Level::derived_relations`]); face-varying refinement and
    /// interpolation then derive the local indices as well, so a mesh with
    /// channels builds this level only from such a parent.
    Relations,
    /// Only the face-vertices (with vertex sharpness, tags and holes): what
    /// a last level needs for interpolation, as OpenSubdiv builds it unless
    /// asked for full topology. Face-varying channels refine into it too:
    /// OpenSubdiv adds the vertex-faces to a minimal level then, to number
    /// each corner's sibling through them, and keeps its edges' sharpness;
    /// the native refinement reads the siblings from the parent's faces and
    /// decays the few edge sharpnesses it needs from the parent's.
    Minimal,
}

impl Build {
    /// What level `level` of a refinement to `last` builds from `parent`
    /// (level `level - 1`), when the last level is `minimal` or not, for a
    /// mesh with face-varying channels (`fvar`) or without. With channels,
    /// the level before a minimal last one keeps all of its relations and
    /// their local indices, which face-varying refinement and interpolation
    /// read — unless `parent` is smooth everywhere, so that the level
    /// derives them from `parent` ([`Level::derived_relations`]), local
    /// indices included, for the channels as for the vertex data.
    pub fn for_level(
        level: usize,
        last: usize,
        minimal: bool,
        fvar: bool,
        parent: &Level,
    ) -> Build {
        match (minimal, fvar) {
            (true, _) if level == last => Build::Minimal,
            (true, false) if level + 1 == last => Build::Relations,
            (true, true) if level + 1 == last && derive::vertex_relations_derivable(parent) => {
                Build::Relations
            }
            _ => Build::Full,
        }
    }

    /// Whether a level built so is minimal (face-vertices only), and keeps
    /// local indices.
    fn parts(self) -> (bool, bool) {
        match self {
            Build::Full => (false, true),
            Build::Relations => (false, false),
            Build::Minimal => (true, false),
        }
    }
}

/// Splits `parent` once — Catmull-Clark and bilinear: every face into quads;
/// Loop: every triangle into four — and returns the child level with as
/// much topology as `build` says, its sharpness and tags.
pub fn refine_level(
    parent: &Level,
    options: &Options,
    faces_first: bool,
    build: Build,
) -> (Split, Level) {
    if options.scheme == Scheme::Loop {
        return tri::refine_triangles(parent, options, faces_first, build);
    }
    quad::refine_quads(parent, options, faces_first, build)
}

/// Parent faces per parallel task.
const FACE_CHUNK: usize = 2048;

/// Splits `out`, holding `per_corner` values for every parent face corner,
/// into chunks of consecutive parent faces: (face range, its values).
fn carve_by_faces<'a, T>(
    out: &'a mut [T],
    parent: &Level,
    per_corner: usize,
) -> Vec<(std::ops::Range<usize>, &'a mut [T])> {
    let nf = parent.face_count();
    let faces = &parent.face_vertices;
    let mut chunks = Vec::with_capacity(nf.div_ceil(FACE_CHUNK));
    let mut rest = out;
    let mut f0 = 0;
    while f0 < nf {
        let f1 = (f0 + FACE_CHUNK).min(nf);
        let len = (faces.start(f1) - faces.start(f0)) * per_corner;
        let (chunk, tail) = std::mem::take(&mut rest).split_at_mut(len);
        chunks.push((f0..f1, chunk));
        rest = tail;
        f0 = f1;
    }
    chunks
}

/// The relations of a full child level beyond its faces (all empty in a
/// minimal one).
#[derive(Default)]
struct ChildRelations {
    edge_vertices: Table<[u32; 2]>,
    edge_faces: Relation,
    edge_face_local: Table<u16>,
    vertex_faces: Relation,
    vertex_face_local: Table<u16>,
    vertex_edges: Relation,
    vertex_edge_local: Table<u16>,
}

/// The tables of a child level built by a split, before tags and sharpness.
struct Parts {
    vertex_count: usize,
    face_vertices: Relation,
    face_edges: Table<u32>,
    relations: ChildRelations,
    num_edges: usize,
    face_holes: Vec<bool>,
    /// Vertex relations left out, derived from the parent when read.
    derived_relations: bool,
    max_valence: usize,
}

/// The child level from its tables and its tags. A minimal level keeps only
/// face-vertices, vertex sharpness and tags.
fn assemble_child(parent: &Level, tags: ChildTags, p: Parts) -> Level {
    Level {
        depth: parent.depth + 1,
        vertex_count: p.vertex_count,
        face_vertices: p.face_vertices,
        face_edges: p.face_edges,
        edge_vertices: p.relations.edge_vertices,
        edge_faces: p.relations.edge_faces,
        edge_face_local: p.relations.edge_face_local,
        vertex_faces: p.relations.vertex_faces,
        vertex_face_local: p.relations.vertex_face_local,
        vertex_edges: p.relations.vertex_edges,
        vertex_edge_local: p.relations.vertex_edge_local,
        num_edges: p.num_edges,
        edge_sharpness: tags.edge_sharpness,
        vertex_sharpness: tags.vertex_sharpness,
        edge_tags: tags.edge_tags,
        vertex_tags: tags.vertex_tags,
        face_holes: p.face_holes,
        derived_relations: p.derived_relations,
        max_edge_faces: parent.max_edge_faces.max(2),
        max_valence: p.max_valence,
    }
}
