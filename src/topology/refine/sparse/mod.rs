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
//! * `tags.rs`: the child's tags and sharpness.

mod quad;
mod tags;
mod tri;

use crate::options::{Options, Scheme};
use crate::output::INVALID_INDEX as INVALID;
use crate::topology::{Level, Relation, Table};

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
    let mut n = 0;
    for m in marks.iter_mut() {
        if *m != 0 {
            *m = first + n as u32;
            n += 1;
        } else {
            *m = INVALID;
        }
    }
    n
}

#[inline]
fn valid(i: u32) -> bool {
    i != INVALID
}

/// The parent's faces as a split walks them: with `QUADS`, every face is a
/// quad with implicit offsets (each level the quad split made), so a face's
/// corners are found without reading offsets and its size is a constant.
#[derive(Clone, Copy)]
struct Faces<'a, const QUADS: bool> {
    relation: &'a Relation,
    /// The face-vertices, concatenated.
    verts: &'a [u32],
    /// The face-edges, concatenated.
    edges: &'a [u32],
}

impl<'a, const QUADS: bool> Faces<'a, QUADS> {
    fn of(parent: &'a Level) -> Self {
        debug_assert!(!QUADS || parent.face_vertices.uniform_size() == Some(4));
        Faces {
            relation: &parent.face_vertices,
            verts: &parent.face_vertices.members,
            edges: &parent.face_edges,
        }
    }

    /// Where face `f`'s corners are in the concatenated tables.
    #[inline(always)]
    fn range(&self, f: usize) -> std::ops::Range<usize> {
        if QUADS {
            4 * f..4 * f + 4
        } else {
            self.relation.range(f)
        }
    }

    /// Corner `k`'s vertex of face `f`.
    #[inline(always)]
    fn corner(&self, f: usize, k: usize) -> u32 {
        self.verts[self.range(f).start + k]
    }
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
    for e in 0..ne {
        if sel.edge(e) {
            edge_child_edges[e] = [MARKED; 2];
            edge_child_vertex[e] = MARKED;
        } else {
            let ends = parent.edge_vertices[e].map(|end| sel.vertex(end as usize));
            edge_child_edges[e] = ends.map(|m| m as u32 * MARKED);
            edge_child_vertex[e] = (ends[0] || ends[1]) as u32 * MARKED;
        }
        // Only a selected edge has a selected face on either side.
        edge_transitional[e] = sel.edge(e)
            && match parent.edge_faces_of(e) {
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
    if !triangles && parent.face_vertices.uniform_size() == Some(4) {
        // Every parent face a quad: corner `i` is corner `i % 4` of face
        // `i / 4`, a flat pass over the corners.
        for (i, &c) in face_child_faces.iter().enumerate() {
            if valid(c) {
                child_face_parent[c as usize] = (i >> 2) as u32;
            }
        }
        for (i, &c) in face_child_edges.iter().enumerate() {
            if valid(c) {
                child_edge_parent[c as usize] = (i >> 2) as u32;
                child_edge_in_parent[c as usize] = (i & 3) as u8;
            }
        }
    } else {
        face_parents(
            parent,
            triangles,
            (&face_child_faces, &face_child_edges),
            (
                &mut child_face_parent,
                &mut child_edge_parent,
                &mut child_edge_in_parent,
            ),
        );
    }
    for (e, halves) in edge_child_edges.iter().enumerate() {
        for (j, &c) in halves.iter().enumerate() {
            if valid(c) {
                child_edge_parent[c as usize] = e as u32;
                child_edge_in_parent[c as usize] = j as u8;
            }
        }
    }
    // Every child vertex has one parent: each entry is written once.
    let mut child_vertex_parent = Table::<PackedParent>::for_overwrite(child_vertices);
    for (f, &c) in face_child_vertex.iter().enumerate() {
        if valid(c) {
            child_vertex_parent[c as usize] =
                PackedParent::new(VertexParent::Face(f as u32), !sel.face(f));
        }
    }
    for (e, &c) in edge_child_vertex.iter().enumerate() {
        if valid(c) {
            child_vertex_parent[c as usize] =
                PackedParent::new(VertexParent::Edge(e as u32), !sel.edge(e));
        }
    }
    for (v, &c) in vertex_child_vertex.iter().enumerate() {
        if valid(c) {
            child_vertex_parent[c as usize] =
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

/// A relation filled element by element in index order, with a local index
/// per member, in [`Table`]s: memory recycled from the tables of a previous
/// refinement where there is some (large tables are pooled maps), so a
/// level's relations do not fault fresh pages in.
struct Filler {
    offsets: Table<u32>,
    members: Table<u32>,
    locals: Table<u16>,
    /// Elements ended so far.
    elements: usize,
    /// Members pushed so far, also those past the room (not written: see
    /// [`Filler::overflow`]).
    len: usize,
}

impl Filler {
    /// Room for `elements` elements of `members` members in all (each
    /// relation here is the transpose of one whose size is known: the
    /// faces of the edges are the edges of the faces, and so on).
    fn new(elements: usize, members: usize) -> Self {
        let mut offsets = Table::for_overwrite(elements + 1);
        offsets[0] = 0;
        Filler {
            offsets,
            members: Table::for_overwrite(members),
            locals: Table::for_overwrite(members),
            elements: 0,
            len: 0,
        }
    }

    #[inline]
    fn push(&mut self, member: u32, local: usize) {
        if self.len < self.members.len() {
            self.members[self.len] = member;
            self.locals[self.len] = local as u16;
        }
        self.len += 1;
    }

    /// Members pushed so far.
    #[inline]
    fn len(&self) -> usize {
        self.len
    }

    /// Swaps members `i` and `j` (and their local indices).
    #[inline]
    fn swap(&mut self, i: usize, j: usize) {
        if i.max(j) < self.members.len() {
            self.members.swap(i, j);
            self.locals.swap(i, j);
        }
    }

    /// Ends the current element.
    #[inline]
    fn end(&mut self) {
        self.elements += 1;
        if let Some(o) = self.offsets.get_mut(self.elements) {
            *o = self.len as u32;
        }
    }

    /// The room a second attempt needs when more members were pushed than
    /// there was room for (a topology that is not its own transpose).
    fn overflow(&self) -> Option<usize> {
        (self.len > self.members.len()).then_some(self.len)
    }

    /// The relation, its local indices and its largest element.
    fn finish(mut self) -> (Relation, Table<u16>, usize) {
        debug_assert!(self.overflow().is_none());
        debug_assert_eq!(self.elements + 1, self.offsets.len());
        let max = self
            .offsets
            .windows(2)
            .map(|w| (w[1] - w[0]) as usize)
            .max()
            .unwrap_or(0);
        self.members.truncate(self.len);
        self.locals.truncate(self.len);
        (
            Relation::from_parts(self.offsets, self.members),
            self.locals,
            max,
        )
    }
}

/// The relations of a child level, in its index order.
struct Topology {
    face_vertices: Relation,
    face_edges: Table<u32>,
    edge_vertices: Table<[u32; 2]>,
    edge_faces: Filler,
    vertex_faces: Filler,
    vertex_edges: Filler,
}

impl Topology {
    /// The room each relation of [`Room`] needs when one overflowed.
    fn overflow(&self) -> Option<Room> {
        let [a, b, c] =
            [&self.edge_faces, &self.vertex_faces, &self.vertex_edges].map(Filler::overflow);
        (a.is_some() || b.is_some() || c.is_some()).then(|| Room {
            edge_faces: a.unwrap_or(self.edge_faces.len),
            vertex_faces: b.unwrap_or(self.vertex_faces.len),
            vertex_edges: c.unwrap_or(self.vertex_edges.len),
        })
    }
}

/// Room for the members of a child level's edge-faces, vertex-faces and
/// vertex-edges: by default what a topology that is its own transpose needs
/// (every face's corners, every edge's two ends), or what an attempt that
/// overflowed it counted.
#[derive(Debug, Clone, Copy)]
struct Room {
    edge_faces: usize,
    vertex_faces: usize,
    vertex_edges: usize,
}

impl Room {
    /// The default room of a child level of `faces` faces of `size` corners
    /// and `edges` edges.
    fn transposes(faces: usize, size: usize, edges: usize) -> Self {
        Room {
            edge_faces: faces * size,
            vertex_faces: faces * size,
            vertex_edges: 2 * edges,
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
    let topology = |room: Option<Room>| {
        if triangles {
            tri::topology(parent, &s, room)
        } else {
            quad::topology(parent, &s, room)
        }
    };
    let mut t = topology(None);
    if let Some(room) = t.overflow() {
        t = topology(Some(room));
    }
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

/// The halves of the parent's edges, in child index order: their vertices
/// and their faces. `corner(pf, k)` is corner `k` of parent face `pf`;
/// `child_face(pf, k, end)` is the child face of parent face `pf` beside its
/// edge `k` at the edge's end `end` (as the face runs), and that child's
/// local index of the half.
fn edge_halves(
    parent: &Level,
    s: &SparseSplit,
    edge_vertices: &mut Table<[u32; 2]>,
    edge_faces: &mut Filler,
    corner: impl Fn(usize, usize) -> u32,
    child_face: impl Fn(usize, usize, usize) -> (u32, usize),
) {
    let child_edge_vertices: &mut [[u32; 2]] = edge_vertices;
    let half_face = |pf: usize, k: usize, j: usize, ends: [u32; 2]| {
        child_face(pf, k, half_end(ends, j, corner(pf, k)))
    };
    for e in 0..s.edge_child_edges.len() {
        halves_of_edge(parent, s, e, child_edge_vertices, edge_faces, &half_face);
    }
}

/// Which end of a parent edge (its ends `ends`, the face's corner at the
/// edge's start being `corner`) half `j` lies at as the face runs: 0 at the
/// face's corner, 1 at the next (a degenerate edge: by the half's own end).
#[inline]
fn half_end(ends: [u32; 2], j: usize, corner: u32) -> usize {
    if ends[0] == ends[1] {
        j
    } else {
        (corner != ends[j]) as usize
    }
}

/// The halves of parent edge `e` that exist ([`edge_halves`]): their
/// vertices and their faces (`half_face(pf, k, j, ends)`: the child of
/// parent face `pf`, whose edge `k` this is, holding half `j`, and its local
/// index of the half), each half's faces ended. Returns whether one exists
/// (then the edge has a point).
#[inline]
fn halves_of_edge(
    parent: &Level,
    s: &SparseSplit,
    e: usize,
    child_edge_vertices: &mut [[u32; 2]],
    edge_faces: &mut Filler,
    half_face: &impl Fn(usize, usize, usize, [u32; 2]) -> (u32, usize),
) -> bool {
    let halves = s.edge_child_edges[e];
    if !valid(halves[0]) && !valid(halves[1]) {
        return false;
    }
    let ends = parent.edge_vertices[e];
    let point = s.edge_child_vertex[e];
    let faces = parent.edge_faces_of(e);
    let locals = parent.edge_face_locals(e);
    for (j, &c) in halves.iter().enumerate() {
        if !valid(c) {
            continue;
        }
        child_edge_vertices[c as usize] = [point, s.vertex_child_vertex[ends[j] as usize]];
        for (&pf, &k) in faces.iter().zip(locals) {
            let (cf, local) = half_face(pf as usize, k as usize, j, ends);
            if valid(cf) {
                edge_faces.push(cf, local);
            }
        }
        edge_faces.end();
    }
    true
}

/// The faces and edges of the child of parent vertex `v`: the child at the
/// vertex's corner of each of its faces that exists (`child_face(pf, k)`:
/// the child of face `pf` at its corner `k`, with its local index of the
/// vertex) and the half of each of its edges at it.
fn vertex_point(
    parent: &Level,
    s: &SparseSplit,
    v: usize,
    (vertex_faces, vertex_edges): (&mut Filler, &mut Filler),
    child_face: impl Fn(usize, usize) -> (u32, usize),
) {
    for (&pf, &k) in parent
        .vertex_faces_of(v)
        .iter()
        .zip(parent.vertex_face_locals(v))
    {
        let (cf, local) = child_face(pf as usize, k as usize);
        if valid(cf) {
            vertex_faces.push(cf, local);
        }
    }
    for (&pe, &end) in parent
        .vertex_edges_of(v)
        .iter()
        .zip(parent.vertex_edge_locals(v))
    {
        let ce = s.edge_child_edges[pe as usize][end as usize];
        if valid(ce) {
            vertex_edges.push(ce, 1);
        }
    }
}
