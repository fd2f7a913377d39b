//! Sparse refinement: part of a level split into the next — the native
//! counterpart of OpenSubdiv's `Vtr::SparseSelector` and of the sparse paths
//! of `Vtr::Refinement`, `Vtr::QuadRefinement` and `Vtr::TriRefinement`
//! (`vtr/sparseSelector.cpp`, `vtr/refinement.cpp`, `vtr/quadRefinement.cpp`,
//! `vtr/triRefinement.cpp`).
//!
//! Faces are selected ([`Selection`]); a selected face marks its edges and
//! vertices. Everything that descends from a selected component is created,
//! and so is the neighbourhood a selected vertex needs to be interpolated and
//! refined again: at each selected vertex, the child face of every incident
//! face at that corner, the child edges inside that face beside it (and the
//! face point), the half of every incident edge at that vertex and the edge
//! point. A triangle beside a selected one also gets its middle child when one
//! of its edges is transitional. Children are numbered as uniform refinement
//! numbers them, with the children not created left out (their index is
//! [`INVALID`]), so a selection of every face numbers everything as
//! [`super::refine_level`] does.
//!
//! A child is *incomplete* when its parent was not selected: it exists only
//! as a neighbour, and its own neighbourhood in the child level is partial.
//! Faces that were not selected but have children are *transitional*: the
//! bits of [`SparseSplit::face_transitional`] say which of their edges have
//! a selected face on one side only.
//!
//! The child level always has full topology (OpenSubdiv builds the levels of
//! an adaptive refinement with every relation).
//!
//! # Files
//! * this file: the selection, the numbering both ways, and the assembly of
//!   the child level;
//! * `quad.rs`, `tri.rs`: which children of a face are created and the child
//!   level's relations, for the quad split (Catmull-Clark, bilinear) and
//!   Loop's triangle split;
//! * `child.rs`: what both splits share in writing the child's relations —
//!   the relations filled element by element, the halves of the parent's
//!   edges, the vertex points' faces and edges;
//! * `views.rs`: the parent level and the numbering as plain slices, read
//!   through their tables once per level;
//! * `tags.rs`: the child's tags and sharpness.

mod child;
mod quad;
mod tags;
mod tri;
mod views;

use crate::options::{Options, Scheme};
use crate::output::INVALID_INDEX as INVALID;
use crate::topology::{Level, Table};

/// The faces selected for sparse refinement, with the edges and vertices
/// they mark (`Vtr::SparseSelector::selectFace`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Selection {
    faces: Vec<bool>,
    edges: Vec<bool>,
    vertices: Vec<bool>,
    any: bool,
}

impl Selection {
    /// Nothing selected in `parent`.
    pub fn new(parent: &Level) -> Self {
        Selection {
            faces: vec![false; parent.face_count()],
            edges: vec![false; parent.edge_count()],
            vertices: vec![false; parent.vertex_count],
            any: false,
        }
    }

    /// Selects face `f` of `parent`, and with it its edges and vertices.
    pub fn select_face(&mut self, parent: &Level, f: usize) {
        if self.faces[f] {
            return;
        }
        self.faces[f] = true;
        self.any = true;
        for &e in parent.face_edges_of(f) {
            self.edges[e as usize] = true;
        }
        for &v in parent.face_verts(f) {
            self.vertices[v as usize] = true;
        }
    }

    /// Whether nothing is selected.
    pub fn is_empty(&self) -> bool {
        !self.any
    }

    /// Whether everything is selected: every face, and so every edge, and
    /// every vertex (none lies outside the faces).
    pub fn is_whole(&self) -> bool {
        self.faces.iter().all(|&f| f) && self.vertices.iter().all(|&v| v)
    }

    /// Whether face `f` is selected.
    pub fn face(&self, f: usize) -> bool {
        self.faces[f]
    }

    /// Whether edge `e` is selected (an edge of a selected face).
    pub fn edge(&self, e: usize) -> bool {
        self.edges[e]
    }

    /// Whether vertex `v` is selected (a vertex of a selected face).
    pub fn vertex(&self, v: usize) -> bool {
        self.vertices[v]
    }
}

/// Where a child vertex comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VertexParent {
    /// The face point of a parent face.
    Face(u32),
    /// The edge point of a parent edge.
    Edge(u32),
    /// The vertex point of a parent vertex.
    Vertex(u32),
}

/// A [`VertexParent`] as plain data, so that the parents of a level's child
/// vertices fit a [`Table`] (recycled memory, not fresh pages each level).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct PackedParent {
    /// 0: a face, 1: an edge, 2: a vertex.
    kind: u16,
    /// 1 when the child is incomplete (see
    /// [`SparseSplit::child_vertex_incomplete`]), else 0.
    incomplete: u16,
    /// The parent's index.
    index: u32,
}

impl PackedParent {
    /// Packs `p`, and whether the child is incomplete.
    #[inline]
    pub fn new(p: VertexParent, incomplete: bool) -> Self {
        let (kind, index) = match p {
            VertexParent::Face(i) => (0, i),
            VertexParent::Edge(i) => (1, i),
            VertexParent::Vertex(i) => (2, i),
        };
        PackedParent {
            kind,
            incomplete: incomplete as u16,
            index,
        }
    }

    /// Whether the child is incomplete: its parent was not selected.
    #[inline]
    pub fn incomplete(self) -> bool {
        self.incomplete != 0
    }

    /// The parent.
    #[inline]
    pub fn get(self) -> VertexParent {
        match self.kind {
            0 => VertexParent::Face(self.index),
            1 => VertexParent::Edge(self.index),
            _ => VertexParent::Vertex(self.index),
        }
    }
}

/// The numbering of one sparse step, both ways: parent components to their
/// children ([`INVALID`] where not created) and children to their parents.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SparseSplit {
    /// The parent's selection.
    pub selection: Selection,
    /// The child faces of each parent face: one at each corner, parallel to
    /// the parent's face-vertices (quad split), or four per triangle, the
    /// middle one last (Loop).
    pub face_child_faces: Table<u32>,
    /// The child edges inside each parent face, parallel to the parent's
    /// face-vertices: from the face point towards the point of face-edge `j`
    /// (quad split), or the edge of the middle triangle opposite corner `j`
    /// (Loop).
    pub face_child_edges: Table<u32>,
    /// The two halves of each parent edge, the one at its end 0 first.
    pub edge_child_edges: Table<[u32; 2]>,
    /// The face point of each parent face (empty under Loop, which has none).
    pub face_child_vertex: Table<u32>,
    /// The edge point of each parent edge.
    pub edge_child_vertex: Table<u32>,
    /// The vertex point of each parent vertex.
    pub vertex_child_vertex: Table<u32>,
    /// The parent face of each child face.
    pub child_face_parent: Table<u32>,
    /// The parent of each child edge: a face for the first
    /// [`SparseSplit::edges_from_faces`] child edges, an edge after them.
    pub child_edge_parent: Table<u32>,
    /// For a child edge of a parent edge, the end of the parent it touches
    /// (0 or 1); for a child edge of a face, its corner in the face.
    pub child_edge_in_parent: Table<u8>,
    /// Number of child edges inside parent faces (numbered first).
    pub edges_from_faces: usize,
    /// The parent of each child vertex, and whether the child is
    /// incomplete ([`SparseSplit::child_vertex_incomplete`]).
    pub child_vertex_parent: Table<PackedParent>,
    /// For each parent face that was not selected but has children, which of
    /// its edges (bit `j` for edge `j`, all bits merged into bit 0 for faces
    /// of more than four sides) have a selected face on one side only.
    pub face_transitional: Table<u8>,
    /// Whether each parent edge has faces selected on one side only.
    pub edge_transitional: Vec<bool>,
    /// Whether the split is Loop's (four children per triangle, no face
    /// points) rather than the quad split (one child per corner).
    pub triangles: bool,
}

impl SparseSplit {
    /// Whether child vertex `c` is incomplete: its parent was not selected,
    /// so only part of its neighbourhood exists in the child level.
    #[inline]
    pub fn child_vertex_incomplete(&self, c: usize) -> bool {
        self.child_vertex_parent[c].incomplete()
    }
}

/// Whether a child is created: marked selected or neighbouring.
const MARKED: u32 = 1;

/// Numbers the marked entries of `marks` from `first` in order, the others
/// [`INVALID`]; returns how many were marked.
fn sequence(marks: &mut [u32], first: u32) -> usize {
    // Without a branch on the mark: marks follow the selection, which
    // changes often enough along a level for a branch to mispredict.
    let mut next = first;
    for m in marks.iter_mut() {
        let marked = *m != 0;
        *m = if marked { next } else { INVALID };
        next += marked as u32;
    }
    (next - first) as usize
}

#[inline]
fn valid(i: u32) -> bool {
    i != INVALID
}

/// Which children of the parent's faces are marked: the child faces, the
/// child edges inside faces, the face points, and the transitional mask of
/// each face (see [`SparseSplit`]'s fields).
struct FaceMarks {
    child_faces: Table<u32>,
    child_edges: Table<u32>,
    child_vertex: Table<u32>,
    transitional: Table<u8>,
}

/// Marks and numbers the children of `parent` under `selection`, in
/// OpenSubdiv's order (children of vertices, faces, then edges; faces,
/// edges, then vertices when `faces_first`).
fn number_children(
    parent: &Level,
    selection: Selection,
    faces_first: bool,
    triangles: bool,
) -> SparseSplit {
    let (nv, ne) = (parent.vertex_count, parent.edge_count());
    let sel = &selection;

    // Vertices: the child of each selected vertex.
    let mut vertex_child_vertex = Table::<u32>::for_overwrite(nv);
    for (v, c) in vertex_child_vertex.iter_mut().enumerate() {
        *c = sel.vertex(v) as u32;
    }

    // Edges: both halves and the edge point of a selected edge; the half at
    // a selected end of any other edge, and its edge point.
    // Every mark is written, marked or not (the tables are not cleared
    // first).
    let mut edge_child_edges = Table::<[u32; 2]>::for_overwrite(ne);
    let mut edge_child_vertex = Table::<u32>::for_overwrite(ne);
    let mut edge_transitional = vec![false; ne];
    let edge_vertices: &[[u32; 2]] = &parent.edge_vertices;
    let edge_faces = parent.edge_faces.view();
    let (child_edges, child_vertex): (&mut [[u32; 2]], &mut [u32]) =
        (&mut edge_child_edges, &mut edge_child_vertex);
    for e in 0..ne {
        if sel.edge(e) {
            child_edges[e] = [MARKED; 2];
            child_vertex[e] = MARKED;
        } else {
            let ends = edge_vertices[e].map(|end| sel.vertex(end as usize));
            child_edges[e] = ends.map(|m| m as u32 * MARKED);
            child_vertex[e] = (ends[0] || ends[1]) as u32 * MARKED;
        }
        // Only a selected edge has a selected face on either side.
        edge_transitional[e] = sel.edge(e)
            && match edge_faces.get(e) {
                [] | [_] => false,
                [f0, rest @ ..] => rest
                    .iter()
                    .any(|&f| sel.face(f as usize) != sel.face(*f0 as usize)),
            };
    }

    let FaceMarks {
        child_faces: mut face_child_faces,
        child_edges: mut face_child_edges,
        child_vertex: mut face_child_vertex,
        transitional: face_transitional,
    } = if triangles {
        tri::mark_faces(parent, sel, &edge_transitional)
    } else {
        quad::mark_faces(parent, sel, &edge_transitional)
    };
    // Numbering, as OpenSubdiv sequences the marks.
    let child_faces = sequence(&mut face_child_faces, 0);
    let edges_from_faces = sequence(&mut face_child_edges, 0);
    let edge_halves = bytemuck::cast_slice_mut::<[u32; 2], u32>(&mut edge_child_edges[..]);
    let edges_from_edges = sequence(edge_halves, edges_from_faces as u32);
    let blocks: [&mut Table<u32>; 3] = if faces_first {
        [
            &mut face_child_vertex,
            &mut edge_child_vertex,
            &mut vertex_child_vertex,
        ]
    } else {
        [
            &mut vertex_child_vertex,
            &mut face_child_vertex,
            &mut edge_child_vertex,
        ]
    };
    let mut first = 0u32;
    for block in blocks {
        first += sequence(block, first) as u32;
    }
    let child_vertices = first as usize;

    // Children to parents.
    // Every child has one parent: each entry is written once.
    let mut child_face_parent = Table::<u32>::for_overwrite(child_faces);
    let mut child_edge_parent = Table::<u32>::for_overwrite(edges_from_faces + edges_from_edges);
    let mut child_edge_in_parent = Table::<u8>::for_overwrite(edges_from_faces + edges_from_edges);
    let (face_parents_of, edge_parents, edge_in_parent): (&mut [u32], &mut [u32], &mut [u8]) = (
        &mut child_face_parent,
        &mut child_edge_parent,
        &mut child_edge_in_parent,
    );
    if !triangles && parent.face_vertices.uniform_size() == Some(4) {
        // Every parent face a quad: corner `i` is corner `i % 4` of face
        // `i / 4`, a flat pass over the corners.
        for (i, &c) in face_child_faces.iter().enumerate() {
            if valid(c) {
                face_parents_of[c as usize] = (i >> 2) as u32;
            }
        }
        for (i, &c) in face_child_edges.iter().enumerate() {
            if valid(c) {
                edge_parents[c as usize] = (i >> 2) as u32;
                edge_in_parent[c as usize] = (i & 3) as u8;
            }
        }
    } else {
        face_parents(
            parent,
            triangles,
            (&face_child_faces, &face_child_edges),
            (face_parents_of, edge_parents, edge_in_parent),
        );
    }
    for (e, halves) in edge_child_edges.iter().enumerate() {
        for (j, &c) in halves.iter().enumerate() {
            if valid(c) {
                edge_parents[c as usize] = e as u32;
                edge_in_parent[c as usize] = j as u8;
            }
        }
    }
    // Every child vertex has one parent: each entry is written once.
    let mut child_vertex_parent = Table::<PackedParent>::for_overwrite(child_vertices);
    let vertex_parents: &mut [PackedParent] = &mut child_vertex_parent;
    for (f, &c) in face_child_vertex.iter().enumerate() {
        if valid(c) {
            vertex_parents[c as usize] =
                PackedParent::new(VertexParent::Face(f as u32), !sel.face(f));
        }
    }
    for (e, &c) in edge_child_vertex.iter().enumerate() {
        if valid(c) {
            vertex_parents[c as usize] =
                PackedParent::new(VertexParent::Edge(e as u32), !sel.edge(e));
        }
    }
    for (v, &c) in vertex_child_vertex.iter().enumerate() {
        if valid(c) {
            vertex_parents[c as usize] =
                PackedParent::new(VertexParent::Vertex(v as u32), !sel.vertex(v));
        }
    }

    SparseSplit {
        selection,
        face_child_faces,
        face_child_edges,
        edge_child_edges,
        face_child_vertex,
        edge_child_vertex,
        vertex_child_vertex,
        child_face_parent,
        child_edge_parent,
        child_edge_in_parent,
        edges_from_faces,
        child_vertex_parent,
        face_transitional,
        edge_transitional,
        triangles,
    }
}

/// The parent face of each child face and of each child edge inside a
/// face, with the edge's corner in the face.
fn face_parents(
    parent: &Level,
    triangles: bool,
    (face_child_faces, face_child_edges): (&[u32], &[u32]),
    (child_face_parent, child_edge_parent, child_edge_in_parent): (
        &mut [u32],
        &mut [u32],
        &mut [u8],
    ),
) {
    for f in 0..parent.face_count() {
        let children = if triangles {
            4 * f..4 * f + 4
        } else {
            parent.face_vertices.range(f)
        };
        for &c in &face_child_faces[children] {
            if valid(c) {
                child_face_parent[c as usize] = f as u32;
            }
        }
        for (j, i) in parent.face_vertices.range(f).enumerate() {
            let c = face_child_edges[i];
            if valid(c) {
                child_edge_parent[c as usize] = f as u32;
                child_edge_in_parent[c as usize] = j.min(255) as u8;
            }
        }
    }
}

/// Splits the selected part of `parent` — into quads (Catmull-Clark,
/// bilinear) or, under Loop, triangles into four — and returns the
/// numbering and the child level with full topology, sharpness, tags and
/// holes.
pub fn refine_sparse(
    parent: &Level,
    options: &Options,
    selection: Selection,
    faces_first: bool,
) -> (SparseSplit, Level) {
    let triangles = options.scheme == Scheme::Loop;
    let whole = selection.is_whole();
    let s = number_children(parent, selection, faces_first, triangles);
    if whole {
        // Every child exists and the numbering is the uniform one: the
        // uniform split builds the same level, faster.
        let (_, child) = super::refine_level(parent, options, faces_first, super::Build::Full);
        return (s, child);
    }
    let t = if triangles {
        tri::topology(parent, &s)
    } else {
        quad::topology(parent, &s)
    };
    let (edge_faces, edge_face_local, max_edge_faces) = t.edge_faces.finish();
    let (vertex_faces, vertex_face_local, max_vf) = t.vertex_faces.finish();
    let (vertex_edges, vertex_edge_local, max_ve) = t.vertex_edges.finish();
    let face_holes = if parent.face_holes.is_empty() {
        Vec::new()
    } else {
        s.child_face_parent
            .iter()
            .map(|&f| parent.is_hole(f as usize))
            .collect()
    };
    let mut child = Level {
        depth: parent.depth + 1,
        vertex_count: s.child_vertex_parent.len(),
        face_vertices: t.face_vertices,
        face_edges: t.face_edges,
        edge_vertices: t.edge_vertices,
        edge_faces,
        edge_face_local,
        vertex_faces,
        vertex_face_local,
        vertex_edges,
        vertex_edge_local,
        derived_relations: false,
        num_edges: s.child_edge_parent.len(),
        face_holes,
        max_edge_faces: parent.max_edge_faces.max(max_edge_faces),
        max_valence: max_vf.max(max_ve).max(if triangles { 3 } else { 4 }),
        ..Level::default()
    };
    tags::propagate_tags(parent, &mut child, &s);
    tags::subdivide_sharpness(parent, &mut child, &s, options);
    child.drop_default_tags();
    (s, child)
}
