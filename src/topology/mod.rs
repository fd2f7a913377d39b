//! One refinement level as flat index tables, built from face-vertex lists and
//! split level by level — the native counterpart of OpenSubdiv's `Vtr::Level`.
//!
//! Every relation is stored as a flat array plus offsets (no per-element
//! allocation, no pointer graph):
//!
//! | relation | members | local index |
//! | --- | --- | --- |
//! | face → vertices, face → edges | in face order; edge `j` runs from vertex `j` to `j+1` | — |
//! | edge → vertices | the two ends | — |
//! | edge → faces | incident faces | position of the edge in each face |
//! | vertex → faces | counter-clockwise around a manifold vertex | position of the vertex in each face |
//! | vertex → edges | counter-clockwise, interleaved with the faces | 0 or 1: which end of the edge |
//!
//! Base edges are numbered as OpenSubdiv numbers them (order of first
//! appearance while walking the faces), non-manifold features are detected and
//! tagged as OpenSubdiv tags them, and children are numbered in OpenSubdiv's
//! order (see [`refine`]).

mod base;
pub mod fvar;
pub mod refine;

pub use base::build_base_level;
pub use refine::{Refinement, refine_level};

use crate::rules::Rule;

/// The first vertex whose rule is smooth (or dart) although its faces and
/// edges do not pair up — possible when a face names the vertex twice without
/// making anything non-manifold. OpenSubdiv's smooth masks assume pairs (its
/// own assertion aborts on such a vertex), so both engines refuse the mesh.
pub fn unpaired_smooth_vertex(level: &Level) -> Option<usize> {
    (0..level.vertex_count).find(|&v| {
        matches!(level.vertex_tags[v].rule, Rule::Smooth | Rule::Dart)
            && level.vertex_faces.count(v) != level.vertex_edges.count(v)
    })
}

/// Tags of an edge (OpenSubdiv's `ETag`, the parts refinement uses).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct EdgeTag {
    /// More than two faces, a repeated or degenerate edge, or faces of opposite winding.
    pub non_manifold: bool,
    /// Fewer than two incident faces.
    pub boundary: bool,
    /// Infinitely sharp.
    pub inf_sharp: bool,
    /// Sharp but finite.
    pub semi_sharp: bool,
}

/// Tags of a vertex (OpenSubdiv's `VTag`, the parts refinement uses).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct VertexTag {
    /// Its incident faces and edges cannot be ordered around it.
    pub non_manifold: bool,
    /// On a boundary edge.
    pub boundary: bool,
    /// A topological corner (one face, two edges) that is infinitely sharp.
    pub corner: bool,
    /// Infinitely sharp.
    pub inf_sharp: bool,
    /// Sharp but finite.
    pub semi_sharp: bool,
    /// Has semi-sharp incident edges.
    pub semi_sharp_edges: bool,
    /// Has infinitely sharp incident edges.
    pub inf_sharp_edges: bool,
    /// The subdivision rule of the vertex.
    pub rule: Rule,
}

impl Default for VertexTag {
    fn default() -> Self {
        VertexTag {
            non_manifold: false,
            boundary: false,
            corner: false,
            inf_sharp: false,
            semi_sharp: false,
            semi_sharp_edges: false,
            inf_sharp_edges: false,
            rule: Rule::Smooth,
        }
    }
}

/// A compressed relation: the members of element `i` are
/// `members[offsets[i]..offsets[i + 1]]`.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Relation {
    /// `count + 1` offsets.
    pub offsets: Vec<u32>,
    /// The members, concatenated.
    pub members: Vec<u32>,
}

impl Relation {
    /// An empty relation over no elements.
    pub fn new() -> Self {
        Relation {
            offsets: vec![0],
            members: Vec::new(),
        }
    }

    /// A relation where every element has `size` members.
    pub fn uniform(count: usize, size: usize) -> Self {
        Relation {
            offsets: (0..=count).map(|i| (i * size) as u32).collect(),
            members: vec![0; count * size],
        }
    }

    /// Number of elements.
    #[inline]
    pub fn len(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Whether there is no element.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The range of element `i`'s members.
    #[inline]
    pub fn range(&self, i: usize) -> std::ops::Range<usize> {
        self.offsets[i] as usize..self.offsets[i + 1] as usize
    }

    /// The members of element `i`.
    #[inline]
    pub fn get(&self, i: usize) -> &[u32] {
        &self.members[self.range(i)]
    }

    /// The members of element `i`, mutably.
    #[inline]
    pub fn get_mut(&mut self, i: usize) -> &mut [u32] {
        let r = self.range(i);
        &mut self.members[r]
    }

    /// Number of members of element `i`.
    #[inline]
    pub fn count(&self, i: usize) -> usize {
        (self.offsets[i + 1] - self.offsets[i]) as usize
    }
}

/// One level of a refinement: topology, sharpness and tags.
#[derive(Debug, Clone, Default)]
pub struct Level {
    /// 0 for the base mesh.
    pub depth: u32,
    /// Number of vertices.
    pub vertex_count: usize,
    /// Face → vertices.
    pub face_vertices: Relation,
    /// Face → edges (same offsets as `face_vertices`).
    pub face_edges: Vec<u32>,
    /// Edge → its two vertices.
    pub edge_vertices: Vec<[u32; 2]>,
    /// Edge → faces.
    pub edge_faces: Relation,
    /// Position of the edge within each of its faces.
    pub edge_face_local: Vec<u16>,
    /// Vertex → faces.
    pub vertex_faces: Relation,
    /// Position of the vertex within each of its faces.
    pub vertex_face_local: Vec<u16>,
    /// Vertex → edges.
    pub vertex_edges: Relation,
    /// Which end of each edge the vertex is (0 or 1).
    pub vertex_edge_local: Vec<u16>,
    /// Number of edges.
    pub num_edges: usize,
    /// Edge sharpness (empty in a minimal last level; see
    /// [`refine::child_edge_sharpness`]).
    pub edge_sharpness: Vec<f32>,
    /// Vertex sharpness.
    pub vertex_sharpness: Vec<f32>,
    /// Edge tags (empty in a minimal last level).
    pub edge_tags: Vec<EdgeTag>,
    /// Vertex tags.
    pub vertex_tags: Vec<VertexTag>,
    /// Hole flag of each face.
    pub face_holes: Vec<bool>,
    /// Largest number of faces at any edge.
    pub max_edge_faces: usize,
    /// Largest number of edges or faces at any vertex, or vertices in any face.
    pub max_valence: usize,
}

impl Level {
    /// Number of faces.
    #[inline]
    pub fn face_count(&self) -> usize {
        self.face_vertices.len()
    }

    /// Number of edges.
    #[inline]
    pub fn edge_count(&self) -> usize {
        self.num_edges
    }

    /// Whether all relations are present. A last level refined with minimal
    /// topology (OpenSubdiv's default) has only its face-vertices, sharpness
    /// and tags.
    #[inline]
    pub fn has_full_topology(&self) -> bool {
        self.edge_vertices.len() == self.num_edges
            && self.edge_sharpness.len() == self.num_edges
            && self.vertex_faces.len() == self.vertex_count
    }

    /// The vertices of face `f`.
    #[inline]
    pub fn face_verts(&self, f: usize) -> &[u32] {
        self.face_vertices.get(f)
    }

    /// The edges of face `f`.
    #[inline]
    pub fn face_edges_of(&self, f: usize) -> &[u32] {
        &self.face_edges[self.face_vertices.range(f)]
    }

    /// The faces of edge `e`.
    #[inline]
    pub fn edge_faces_of(&self, e: usize) -> &[u32] {
        self.edge_faces.get(e)
    }

    /// The position of edge `e` within each of its faces.
    #[inline]
    pub fn edge_face_locals(&self, e: usize) -> &[u16] {
        &self.edge_face_local[self.edge_faces.range(e)]
    }

    /// The faces of vertex `v`.
    #[inline]
    pub fn vertex_faces_of(&self, v: usize) -> &[u32] {
        self.vertex_faces.get(v)
    }

    /// The position of vertex `v` within each of its faces.
    #[inline]
    pub fn vertex_face_locals(&self, v: usize) -> &[u16] {
        &self.vertex_face_local[self.vertex_faces.range(v)]
    }

    /// The edges of vertex `v`.
    #[inline]
    pub fn vertex_edges_of(&self, v: usize) -> &[u32] {
        self.vertex_edges.get(v)
    }

    /// Which end of each of its edges vertex `v` is.
    #[inline]
    pub fn vertex_edge_locals(&self, v: usize) -> &[u16] {
        &self.vertex_edge_local[self.vertex_edges.range(v)]
    }

    /// The vertex at the other end of edge `e` from `v`.
    #[inline]
    pub fn other_vertex(&self, e: usize, v: u32) -> u32 {
        let ev = self.edge_vertices[e];
        if ev[0] == v { ev[1] } else { ev[0] }
    }

    /// The first edge joining `v0` and `v1`, as OpenSubdiv's `findEdge` returns it.
    pub fn find_edge(&self, v0: u32, v1: u32) -> Option<u32> {
        let edges = self.vertex_edges_of(v0 as usize);
        if v0 != v1 {
            edges.iter().copied().find(|&e| {
                let ev = self.edge_vertices[e as usize];
                ev[0] == v1 || ev[1] == v1
            })
        } else {
            edges.iter().copied().find(|&e| {
                let ev = self.edge_vertices[e as usize];
                ev[0] == ev[1]
            })
        }
    }
}
