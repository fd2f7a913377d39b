//! Writing a sparse child level's relations, shared by both splits: the
//! relations filled element by element ([`Filler`]), and the halves of the
//! parent's edges and the vertex points' faces and edges, which the quad
//! and the triangle split build alike.

use super::valid;
use super::views::Numbering;
use crate::topology::LevelSlices;
use crate::topology::{Relation, Table};

/// A relation filled element by element in index order, with a local index
/// per member. Its vectors — kept ones of dropped tables where the pool has
/// some ([`Table::vec_for_push`]) — are reserved at the size a topology that
/// is its own transpose needs ([`Room`]) and grow, fallibly, past it (a
/// non-manifold topology can need more).
pub(super) struct Filler {
    offsets: Vec<u32>,
    members: Vec<u32>,
    locals: Vec<u16>,
    /// The largest element ended so far (kept as elements end, not found
    /// by another pass over the offsets).
    max: u32,
}

impl Filler {
    /// Room for `elements` elements of `members` members in all (each
    /// relation here is the transpose of one whose size is known: the
    /// faces of the edges are the edges of the faces, and so on).
    pub(super) fn new(elements: usize, members: usize) -> Self {
        let mut offsets = Table::vec_for_push(elements + 1);
        offsets.push(0);
        Filler {
            offsets,
            members: Table::vec_for_push(members),
            locals: Table::vec_for_push(members),
            max: 0,
        }
    }

    #[inline]
    pub(super) fn push(&mut self, member: u32, local: usize) {
        if self.members.len() == self.members.capacity() {
            self.grow();
        }
        self.members.push(member);
        self.locals.push(local as u16);
    }

    /// Doubles the room for members, or unwinds with an
    /// [`AllocFailure`](crate::alloc::AllocFailure).
    #[cold]
    #[inline(never)]
    fn grow(&mut self) {
        let more = self.members.len().max(16);
        if crate::alloc::reserve(&mut self.members, more).is_err() {
            crate::alloc::fail(4 * more);
        }
        if crate::alloc::reserve(&mut self.locals, more).is_err() {
            crate::alloc::fail(2 * more);
        }
    }

    /// Members pushed so far.
    #[inline]
    pub(super) fn len(&self) -> usize {
        self.members.len()
    }

    /// Elements ended so far.
    pub(super) fn elements(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Swaps members `i` and `j` (and their local indices).
    #[inline]
    pub(super) fn swap(&mut self, i: usize, j: usize) {
        self.members.swap(i, j);
        self.locals.swap(i, j);
    }

    /// Ends the current element.
    #[inline]
    pub(super) fn end(&mut self) {
        let (start, end) = (
            self.offsets.last().copied().unwrap_or(0),
            self.members.len() as u32,
        );
        self.max = self.max.max(end - start);
        if self.offsets.len() == self.offsets.capacity() {
            Self::grow_offsets(&mut self.offsets);
        }
        self.offsets.push(end);
    }

    #[cold]
    #[inline(never)]
    fn grow_offsets(offsets: &mut Vec<u32>) {
        let more = offsets.len().max(16);
        if crate::alloc::reserve(offsets, more).is_err() {
            crate::alloc::fail(4 * more);
        }
    }

    /// The relation, its local indices and its largest element.
    pub(super) fn finish(self) -> (Relation, Table<u16>, usize) {
        let max = self.max as usize;
        (
            Relation::from_parts(self.offsets.into(), self.members.into()),
            self.locals.into(),
            max,
        )
    }
}

/// The relations of a child level, in its index order.
pub(super) struct Topology {
    pub(super) face_vertices: Relation,
    pub(super) face_edges: Table<u32>,
    pub(super) edge_vertices: Table<[u32; 2]>,
    pub(super) edge_faces: Filler,
    pub(super) vertex_faces: Filler,
    pub(super) vertex_edges: Filler,
}

/// Room for the members of a child level's edge-faces, vertex-faces and
/// vertex-edges: what a topology that is its own transpose needs (every
/// face's corners, every edge's two ends).
#[derive(Debug, Clone, Copy)]
pub(super) struct Room {
    pub(super) edge_faces: usize,
    pub(super) vertex_faces: usize,
    pub(super) vertex_edges: usize,
}

impl Room {
    /// The room of a child level of `faces` faces of `size` corners and
    /// `edges` edges.
    pub(super) fn transposes(faces: usize, size: usize, edges: usize) -> Self {
        Room {
            edge_faces: faces * size,
            vertex_faces: faces * size,
            vertex_edges: 2 * edges,
        }
    }
}

/// The halves of the parent's edges, in child index order: their vertices
/// and their faces. `corner(pf, k)` is corner `k` of parent face `pf`;
/// `child_face(pf, k, end)` is the child face of parent face `pf` beside its
/// edge `k` at the edge's end `end` (as the face runs), and that child's
/// local index of the half.
pub(super) fn edge_halves(
    parent: LevelSlices<'_>,
    s: Numbering<'_>,
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
pub(super) fn half_end(ends: [u32; 2], j: usize, corner: u32) -> usize {
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
pub(super) fn halves_of_edge(
    parent: LevelSlices<'_>,
    s: Numbering<'_>,
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
    let (faces, locals) = parent.edge_faces(e);
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
pub(super) fn vertex_point(
    parent: LevelSlices<'_>,
    s: Numbering<'_>,
    v: usize,
    (vertex_faces, vertex_edges): (&mut Filler, &mut Filler),
    child_face: impl Fn(usize, usize) -> (u32, usize),
) {
    let (faces, locals) = parent.vertex_faces(v);
    for (&pf, &k) in faces.iter().zip(locals) {
        let (cf, local) = child_face(pf as usize, k as usize);
        if valid(cf) {
            vertex_faces.push(cf, local);
        }
    }
    let (edges, ends) = parent.vertex_edges(v);
    for (&pe, &end) in edges.iter().zip(ends) {
        let ce = s.edge_child_edges[pe as usize][end as usize];
        if valid(ce) {
            vertex_edges.push(ce, 1);
        }
    }
}
