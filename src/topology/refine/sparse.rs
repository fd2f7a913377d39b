//! Sparse refinement: part of a level split into the next — the native
//! counterpart of OpenSubdiv's `Vtr::SparseSelector` and of the sparse paths
//! of `Vtr::Refinement` and `Vtr::QuadRefinement` (`vtr/sparseSelector.cpp`,
//! `vtr/refinement.cpp`, `vtr/quadRefinement.cpp`).
//!
//! Faces are selected ([`Selection`]); a selected face marks its edges and
//! vertices. Everything that descends from a selected component is created,
//! and so is the neighbourhood a selected vertex needs to be interpolated and
//! refined again: at each selected vertex, the child face of every incident
//! face at that corner, the two child edges inside that face beside it, the
//! face point, the half of every incident edge at that vertex and the edge
//! point. Children are numbered as uniform refinement numbers them, with the
//! children not created left out (their index is [`INVALID`]), so a
//! selection of every face numbers everything as [`super::refine_level`]
//! does.
//!
//! A child is *incomplete* when its parent was not selected: it exists only
//! as a neighbour, and its own neighbourhood in the child level is partial.
//! Faces that were not selected but have children are *transitional*: the
//! bits of [`SparseSplit::face_transitional`] say which of their edges have
//! a selected face on one side only.
//!
//! The child level always has full topology (OpenSubdiv builds the levels of
//! an adaptive refinement with every relation). Only the quad split
//! (Catmull-Clark, bilinear) is sparse so far.

use super::tags::child_edge;
use super::{next, prev};
use crate::options::Options;
use crate::output::INVALID_INDEX as INVALID;
use crate::rules::{SHARPNESS_INFINITE, crease};
use crate::topology::{EdgeTag, Level, Relation, Table, VertexTag};

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

/// The numbering of one sparse step, both ways: parent components to their
/// children ([`INVALID`] where not created) and children to their parents.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SparseSplit {
    /// The parent's selection.
    pub selection: Selection,
    /// The child face at each parent face corner, parallel to the parent's
    /// face-vertices.
    pub face_child_faces: Vec<u32>,
    /// The child edge inside each parent face from its face point towards
    /// the point of face-edge `j`, parallel to the parent's face-vertices.
    pub face_child_edges: Vec<u32>,
    /// The two halves of each parent edge, the one at its end 0 first.
    pub edge_child_edges: Vec<[u32; 2]>,
    /// The face point of each parent face.
    pub face_child_vertex: Vec<u32>,
    /// The edge point of each parent edge.
    pub edge_child_vertex: Vec<u32>,
    /// The vertex point of each parent vertex.
    pub vertex_child_vertex: Vec<u32>,
    /// The parent face of each child face.
    pub child_face_parent: Vec<u32>,
    /// The parent of each child edge: a face for the first
    /// [`SparseSplit::edges_from_faces`] child edges, an edge after them.
    pub child_edge_parent: Vec<u32>,
    /// For a child edge of a parent edge, the end of the parent it touches
    /// (0 or 1); for a child edge of a face, its corner in the face.
    pub child_edge_in_parent: Vec<u8>,
    /// Number of child edges inside parent faces (numbered first).
    pub edges_from_faces: usize,
    /// The parent of each child vertex.
    pub child_vertex_parent: Vec<VertexParent>,
    /// Whether each child vertex is incomplete: its parent was not selected,
    /// so only part of its neighbourhood exists in the child level.
    pub child_vertex_incomplete: Vec<bool>,
    /// For each parent face that was not selected but has children, which of
    /// its edges (bit `j` for edge `j`, all bits merged into bit 0 for faces
    /// of more than four sides) have a selected face on one side only.
    pub face_transitional: Vec<u8>,
    /// Whether each parent edge has faces selected on one side only.
    pub edge_transitional: Vec<bool>,
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

/// Marks and numbers the children of a quad split of `parent` under
/// `selection`, in OpenSubdiv's order (children of vertices, faces, then
/// edges; faces, edges, then vertices when `faces_first`).
fn number_quad_children(parent: &Level, selection: Selection, faces_first: bool) -> SparseSplit {
    let (nv, ne, nf) = (
        parent.vertex_count,
        parent.edge_count(),
        parent.face_count(),
    );
    let corners = parent.face_vertices.members.len();
    let sel = &selection;

    // Vertices: the child of each selected vertex.
    let mut vertex_child_vertex: Vec<u32> = (0..nv).map(|v| sel.vertex(v) as u32).collect();

    // Edges: both halves and the edge point of a selected edge; the half at
    // a selected end of any other edge, and its edge point.
    let mut edge_child_edges = vec![[0u32; 2]; ne];
    let mut edge_child_vertex = vec![0u32; ne];
    let mut edge_transitional = vec![false; ne];
    for e in 0..ne {
        if sel.edge(e) {
            edge_child_edges[e] = [MARKED; 2];
            edge_child_vertex[e] = MARKED;
        } else {
            for (half, &end) in edge_child_edges[e].iter_mut().zip(&parent.edge_vertices[e]) {
                if sel.vertex(end as usize) {
                    *half = MARKED;
                    edge_child_vertex[e] = MARKED;
                }
            }
        }
        let faces = parent.edge_faces_of(e);
        edge_transitional[e] = match faces {
            [] | [_] => false,
            [f0, rest @ ..] => rest
                .iter()
                .any(|&f| sel.face(f as usize) != sel.face(*f0 as usize)),
        };
    }

    // Faces: everything of a selected face; of any other, the child face at
    // each selected corner, the two inner edges beside it and the face point.
    let mut face_child_faces = vec![0u32; corners];
    let mut face_child_edges = vec![0u32; corners];
    let mut face_child_vertex = vec![0u32; nf];
    let mut face_transitional = vec![0u8; nf];
    for f in 0..nf {
        let range = parent.face_vertices.range(f);
        let n = range.len();
        let verts = parent.face_verts(f);
        if sel.face(f) {
            face_child_faces[range.clone()].fill(MARKED);
            face_child_edges[range].fill(MARKED);
            face_child_vertex[f] = MARKED;
            continue;
        }
        let mut marked = false;
        for (j, &v) in verts.iter().enumerate() {
            if sel.vertex(v as usize) {
                face_child_faces[range.start + j] = MARKED;
                face_child_edges[range.start + j] = MARKED;
                face_child_edges[range.start + prev(j, n)] = MARKED;
                marked = true;
            }
        }
        if marked {
            face_child_vertex[f] = MARKED;
            let edges = parent.face_edges_of(f);
            face_transitional[f] = if n <= 4 {
                edges
                    .iter()
                    .enumerate()
                    .map(|(j, &e)| (edge_transitional[e as usize] as u8) << j)
                    .fold(0, |a, b| a | b)
            } else {
                edges.iter().any(|&e| edge_transitional[e as usize]) as u8
            };
        }
    }

    // Numbering, as OpenSubdiv sequences the marks.
    let child_faces = sequence(&mut face_child_faces, 0);
    let edges_from_faces = sequence(&mut face_child_edges, 0);
    let edge_halves = bytemuck::cast_slice_mut::<[u32; 2], u32>(&mut edge_child_edges);
    let edges_from_edges = sequence(edge_halves, edges_from_faces as u32);
    let blocks: [&mut Vec<u32>; 3] = if faces_first {
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
    let mut child_face_parent = vec![0u32; child_faces];
    let mut child_edge_parent = vec![0u32; edges_from_faces + edges_from_edges];
    let mut child_edge_in_parent = vec![0u8; edges_from_faces + edges_from_edges];
    for f in 0..nf {
        let range = parent.face_vertices.range(f);
        for (j, i) in range.enumerate() {
            let c = face_child_faces[i];
            if valid(c) {
                child_face_parent[c as usize] = f as u32;
            }
            let c = face_child_edges[i];
            if valid(c) {
                child_edge_parent[c as usize] = f as u32;
                child_edge_in_parent[c as usize] = j.min(255) as u8;
            }
        }
    }
    for (e, halves) in edge_child_edges.iter().enumerate() {
        for (j, &c) in halves.iter().enumerate() {
            if valid(c) {
                child_edge_parent[c as usize] = e as u32;
                child_edge_in_parent[c as usize] = j as u8;
            }
        }
    }
    let mut child_vertex_parent = vec![VertexParent::Vertex(0); child_vertices];
    let mut child_vertex_incomplete = vec![true; child_vertices];
    for (f, &c) in face_child_vertex.iter().enumerate() {
        if valid(c) {
            child_vertex_parent[c as usize] = VertexParent::Face(f as u32);
            child_vertex_incomplete[c as usize] = !sel.face(f);
        }
    }
    for (e, &c) in edge_child_vertex.iter().enumerate() {
        if valid(c) {
            child_vertex_parent[c as usize] = VertexParent::Edge(e as u32);
            child_vertex_incomplete[c as usize] = !sel.edge(e);
        }
    }
    for (v, &c) in vertex_child_vertex.iter().enumerate() {
        if valid(c) {
            child_vertex_parent[c as usize] = VertexParent::Vertex(v as u32);
            child_vertex_incomplete[c as usize] = !sel.vertex(v);
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
        child_vertex_incomplete,
        face_transitional,
        edge_transitional,
    }
}

/// A relation filled element by element in index order, with a local index
/// per member.
struct Filler {
    offsets: Vec<u32>,
    members: Vec<u32>,
    locals: Vec<u16>,
}

impl Filler {
    fn new(elements: usize) -> Self {
        let mut offsets = Vec::with_capacity(elements + 1);
        offsets.push(0);
        Filler {
            offsets,
            members: Vec::new(),
            locals: Vec::new(),
        }
    }

    #[inline]
    fn push(&mut self, member: u32, local: usize) {
        self.members.push(member);
        self.locals.push(local as u16);
    }

    /// Ends the current element.
    #[inline]
    fn end(&mut self) {
        self.offsets.push(self.members.len() as u32);
    }

    /// The relation, its local indices and its largest element.
    fn finish(self) -> (Relation, Table<u16>, usize) {
        let max = self
            .offsets
            .windows(2)
            .map(|w| (w[1] - w[0]) as usize)
            .max()
            .unwrap_or(0);
        (
            Relation::from_parts(self.offsets.into(), self.members.into()),
            self.locals.into(),
            max,
        )
    }
}

/// Splits the selected part of `parent` into quads (Catmull-Clark and
/// bilinear) and returns the numbering and the child level with full
/// topology, sharpness, tags and holes.
pub fn refine_quads_sparse(
    parent: &Level,
    options: &Options,
    selection: Selection,
    faces_first: bool,
) -> (SparseSplit, Level) {
    let s = number_quad_children(parent, selection, faces_first);
    let nf = s.child_face_parent.len();
    let ne = s.child_edge_parent.len();
    let nv = s.child_vertex_parent.len();

    // Face-vertices and face-edges.
    let mut face_vertices = Relation::uniform_for_overwrite(nf, 4);
    let mut face_edges = Table::zeroed(4 * nf);
    for f in 0..parent.face_count() {
        let range = parent.face_vertices.range(f);
        let n = range.len();
        let (verts, edges) = (parent.face_verts(f), parent.face_edges_of(f));
        for j in 0..n {
            let c = s.face_child_faces[range.start + j];
            if !valid(c) {
                continue;
            }
            let jp = prev(j, n);
            let (e_prev, e_next) = (edges[jp] as usize, edges[j] as usize);
            let corner = verts[j];
            let vs = [
                s.vertex_child_vertex[corner as usize],
                s.edge_child_vertex[e_next],
                s.face_child_vertex[f],
                s.edge_child_vertex[e_prev],
            ];
            let [p0, p1] = parent.edge_vertices[e_prev];
            let in_prev = if p0 != p1 { (p0 != corner) as usize } else { 1 };
            let [n0, n1] = parent.edge_vertices[e_next];
            let in_next = if n0 != n1 { (n0 != corner) as usize } else { 0 };
            let es = [
                s.edge_child_edges[e_next][in_next],
                s.face_child_edges[range.start + j],
                s.face_child_edges[range.start + jp],
                s.edge_child_edges[e_prev][in_prev],
            ];
            // A quad's children keep its orientation: the corner's child
            // sits at position j.
            let rot = if n == 4 { j } else { 0 };
            let (cv, ce) = (c as usize * 4, c as usize * 4);
            for k in 0..4 {
                face_vertices.members[cv + (rot + k) % 4] = vs[k];
                face_edges[ce + (rot + k) % 4] = es[k];
            }
        }
    }

    // Edge-vertices and edge-faces, child edges in index order: those
    // inside faces, then the halves of edges.
    let mut edge_vertices = Table::<[u32; 2]>::zeroed(ne);
    let mut edge_faces = Filler::new(ne);
    for f in 0..parent.face_count() {
        let range = parent.face_vertices.range(f);
        let n = range.len();
        let edges = parent.face_edges_of(f);
        for (j, &edge) in edges.iter().enumerate() {
            let c = s.face_child_edges[range.start + j];
            if !valid(c) {
                continue;
            }
            edge_vertices[c as usize] =
                [s.face_child_vertex[f], s.edge_child_vertex[edge as usize]];
            let jn = next(j, n);
            let here = s.face_child_faces[range.start + j];
            if valid(here) {
                edge_faces.push(here, if n == 4 { jn } else { 1 });
            }
            let there = s.face_child_faces[range.start + jn];
            if valid(there) {
                edge_faces.push(there, if n == 4 { (jn + 2) & 3 } else { 2 });
            }
            edge_faces.end();
        }
    }
    for e in 0..parent.edge_count() {
        let ends = parent.edge_vertices[e];
        for j in 0..2 {
            let c = s.edge_child_edges[e][j];
            if !valid(c) {
                continue;
            }
            edge_vertices[c as usize] = [
                s.edge_child_vertex[e],
                s.vertex_child_vertex[ends[j] as usize],
            ];
            for (&pf, &in_face) in parent
                .edge_faces_of(e)
                .iter()
                .zip(parent.edge_face_locals(e))
            {
                let (pf, in_face) = (pf as usize, in_face as usize);
                let range = parent.face_vertices.range(pf);
                let n = range.len();
                let of_edge = if ends[0] == ends[1] {
                    j
                } else {
                    (parent.face_verts(pf)[in_face] != ends[j]) as usize
                };
                let in_child = (in_face + of_edge) % n;
                let cf = s.face_child_faces[range.start + in_child];
                if valid(cf) {
                    let local = if n == 4 {
                        in_face
                    } else if of_edge == 1 {
                        3
                    } else {
                        0
                    };
                    edge_faces.push(cf, local);
                }
            }
            edge_faces.end();
        }
    }

    // Vertex-faces and vertex-edges, child vertices in index order.
    let mut vertex_faces = Filler::new(nv);
    let mut vertex_edges = Filler::new(nv);
    for (c, &p) in s.child_vertex_parent.iter().enumerate() {
        debug_assert_eq!(vertex_faces.offsets.len(), c + 1);
        match p {
            VertexParent::Face(f) => {
                let range = parent.face_vertices.range(f as usize);
                let n = range.len();
                for j in 0..n {
                    let cf = s.face_child_faces[range.start + j];
                    if valid(cf) {
                        vertex_faces.push(cf, if n == 4 { (j + 2) & 3 } else { 2 });
                    }
                    let lead = s.face_child_edges[range.start + prev(j, n)];
                    if valid(lead) {
                        vertex_edges.push(lead, 0);
                    }
                }
            }
            VertexParent::Edge(e) => {
                let e = e as usize;
                let ends = parent.edge_vertices[e];
                for &half in &s.edge_child_edges[e] {
                    if valid(half) {
                        vertex_edges.push(half, 0);
                    }
                }
                let first = vertex_edges.offsets[c] as usize;
                let faces = parent.edge_faces_of(e);
                for (i, (&pf, &in_face)) in faces.iter().zip(parent.edge_face_locals(e)).enumerate()
                {
                    let (pf, in_face) = (pf as usize, in_face as usize);
                    let range = parent.face_vertices.range(pf);
                    let n = range.len();
                    let (c0, c1) = (in_face, next(in_face, n));
                    let f1 = s.face_child_faces[range.start + c1];
                    if valid(f1) {
                        vertex_faces.push(f1, if n == 4 { c0 } else { 3 });
                    }
                    let f0 = s.face_child_faces[range.start + c0];
                    if valid(f0) {
                        vertex_faces.push(f0, if n == 4 { c1 } else { 1 });
                    }
                    let inner = s.face_child_edges[range.start + in_face];
                    if valid(inner) {
                        vertex_edges.push(inner, 1);
                        // Order [half, inner edge of the first face, half, ...],
                        // the halves as the edge runs in that face.
                        if i == 0 && vertex_edges.members.len() - first == 3 {
                            let m = &mut vertex_edges.members[first..];
                            let l = &mut vertex_edges.locals[first..];
                            if ends[0] != ends[1] && parent.face_verts(pf)[in_face] == ends[0] {
                                m.swap(0, 1);
                                l.swap(0, 1);
                            }
                            m.swap(1, 2);
                            l.swap(1, 2);
                        }
                    }
                }
            }
            VertexParent::Vertex(v) => {
                let v = v as usize;
                for (&pf, &in_face) in parent
                    .vertex_faces_of(v)
                    .iter()
                    .zip(parent.vertex_face_locals(v))
                {
                    let range = parent.face_vertices.range(pf as usize);
                    let cf = s.face_child_faces[range.start + in_face as usize];
                    if valid(cf) {
                        vertex_faces.push(
                            cf,
                            if range.len() == 4 {
                                in_face as usize
                            } else {
                                0
                            },
                        );
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
        }
        vertex_faces.end();
        vertex_edges.end();
    }

    let (edge_faces, edge_face_local, max_edge_faces) = edge_faces.finish();
    let (vertex_faces, vertex_face_local, max_vf) = vertex_faces.finish();
    let (vertex_edges, vertex_edge_local, max_ve) = vertex_edges.finish();
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
        vertex_count: nv,
        face_vertices,
        face_edges,
        edge_vertices,
        edge_faces,
        edge_face_local,
        vertex_faces,
        vertex_face_local,
        vertex_edges,
        vertex_edge_local,
        derived_relations: false,
        num_edges: ne,
        face_holes,
        max_edge_faces: parent.max_edge_faces.max(max_edge_faces),
        max_valence: max_vf.max(max_ve).max(4),
        ..Level::default()
    };
    propagate_tags(parent, &mut child, &s);
    subdivide_sharpness(parent, &mut child, &s, options);
    child.drop_default_tags();
    (s, child)
}

/// Child tags (`Refinement::propagateComponentTags`): halves of edges
/// inherit their parent's tags, edges inside faces and face points are
/// smooth, edge points take their tags from the parent edge, vertex points
/// inherit their parent's.
fn propagate_tags(parent: &Level, child: &mut Level, s: &SparseSplit) {
    for (e, halves) in s.edge_child_edges.iter().enumerate() {
        let t = parent.edge_tag(e);
        for &c in halves {
            if valid(c) {
                child.set_edge_tag(c as usize, t);
            }
        }
        let c = s.edge_child_vertex[e];
        if valid(c) {
            child.set_vertex_tag(c as usize, edge_point_tag(t));
        }
    }
    for (v, &c) in s.vertex_child_vertex.iter().enumerate() {
        if valid(c) {
            child.set_vertex_tag(c as usize, parent.vertex_tag(v));
        }
    }
}

/// The tags of the point of an edge tagged `t`.
fn edge_point_tag(t: EdgeTag) -> VertexTag {
    let sharp = t.semi_sharp() || t.inf_sharp();
    let mut tag = VertexTag::default();
    tag.set_non_manifold(t.non_manifold());
    tag.set_boundary(t.boundary());
    tag.set_semi_sharp_edges(t.semi_sharp());
    tag.set_inf_sharp_edges(t.inf_sharp());
    tag.set_rule(if sharp {
        crate::rules::Rule::Crease
    } else {
        crate::rules::Rule::Smooth
    });
    tag
}

/// Edge and vertex sharpness of the child, then the rules of child vertices
/// whose neighbourhood was semi-sharp (`Refinement::subdivideSharpnessValues`
/// and `reclassifySemisharpVertices`). An incomplete edge point may miss a
/// half: it is a crease when the half it has is semi-sharp.
fn subdivide_sharpness(parent: &Level, child: &mut Level, s: &SparseSplit, options: &Options) {
    let mut around = Vec::new();
    for (e, halves) in s.edge_child_edges.iter().enumerate() {
        let t = parent.edge_tag(e);
        if !t.semi_sharp() && !t.inf_sharp() {
            continue;
        }
        for (j, &c) in halves.iter().enumerate() {
            if valid(c) {
                let (sharpness, tag) = child_edge(parent, e, j, options.creasing, &mut around);
                child.set_edge_sharpness(c as usize, sharpness);
                child.set_edge_tag(c as usize, tag);
            }
        }
    }
    for (v, &c) in s.vertex_child_vertex.iter().enumerate() {
        if !valid(c) {
            continue;
        }
        let c = c as usize;
        let tag = child.vertex_tag(c);
        if tag.inf_sharp() {
            child.set_vertex_sharpness(c, SHARPNESS_INFINITE);
        } else if tag.semi_sharp() {
            let sharpness = crease::subdivide_vertex_sharpness(parent.vertex_sharpness_at(v));
            child.set_vertex_sharpness(c, sharpness);
            if !crease::is_sharp(sharpness) {
                child.update_vertex_tag(c, |t| t.set_semi_sharp(false));
            }
        }
    }
    for (e, &c) in s.edge_child_vertex.iter().enumerate() {
        if !valid(c) || !child.vertex_tag(c as usize).semi_sharp_edges() {
            continue;
        }
        let semi = |h: u32| valid(h) && child.edge_tag(h as usize).semi_sharp();
        let [h0, h1] = s.edge_child_edges[e];
        let rule = if s.child_vertex_incomplete[c as usize] {
            if semi(h0) || semi(h1) {
                crate::rules::Rule::Crease
            } else {
                crate::rules::Rule::Smooth
            }
        } else {
            crease::vertex_rule_from_sharp_edge_count(0.0, semi(h0) as usize + semi(h1) as usize)
        };
        let any = semi(h0) || semi(h1);
        child.update_vertex_tag(c as usize, |t| {
            t.set_semi_sharp_edges(any);
            t.set_rule(rule);
        });
    }
    for (v, &c) in s.vertex_child_vertex.iter().enumerate() {
        if !valid(c) {
            continue;
        }
        let p = parent.vertex_tag(v);
        if !p.semi_sharp() && !p.semi_sharp_edges() {
            continue;
        }
        let c = c as usize;
        let decayed = p.semi_sharp() && !child.vertex_tag(c).semi_sharp();
        if p.semi_sharp_edges() || decayed {
            let (mut inf, mut semi) = (0, 0);
            for &ce in child.vertex_edges_of(c) {
                let t = child.edge_tag(ce as usize);
                inf += t.inf_sharp() as usize;
                semi += t.semi_sharp() as usize;
            }
            child.update_vertex_tag(c, |tag| {
                tag.set_semi_sharp_edges(semi > 0);
                if !tag.semi_sharp() && !tag.inf_sharp() {
                    tag.set_rule(crease::vertex_rule_from_sharp_edge_count(0.0, inf + semi));
                }
            });
        }
    }
}
