//! Writing a sparse child level's relations, shared by both splits: the
//! relations filled element by element ([`Filler`]), and the halves of the
//! parent's edges and the vertex points' faces and edges, which the quad
//! and the triangle split build alike.

use super::valid;
use super::views::Numbering;
use crate::topology::LevelSlices;
use crate::topology::{Relation, Table};

/// The tables a relation is filled into ([`Filler`]): offsets for
/// `elements` elements and room for `members` members with their local
/// indices, none of them cleared first (every value used is written).
pub(super) struct FillTables {
    offsets: Table<u32>,
    members: Table<u32>,
    locals: Table<u16>,
}

impl FillTables {
    /// Tables for `elements` elements and `members` members in all (each
    /// relation here is the transpose of one whose size is known: the
    /// faces of the edges are the edges of the faces, and so on; see
    /// [`Room`]).
    pub(super) fn new(elements: usize, members: usize) -> Self {
        FillTables {
            offsets: Table::for_overwrite(elements + 1),
            members: Table::for_overwrite(members),
            locals: Table::for_overwrite(members),
        }
    }

    /// A filler writing into these tables from their start.
    pub(super) fn filler(&mut self) -> Filler<'_> {
        let offsets: &mut [u32] = &mut self.offsets;
        if let Some(first) = offsets.first_mut() {
            *first = 0;
        }
        Filler {
            offsets,
            members: &mut self.members,
            locals: &mut self.locals,
            len: 0,
            ended: 0,
            start: 0,
            max: 0,
        }
    }

    /// The relation `filler` filled ([`Filler::finish`]), its local
    /// indices and its largest element.
    pub(super) fn finish(mut self, (len, max): (usize, usize)) -> Filled {
        self.members.truncate(len);
        self.locals.truncate(len);
        Filled {
            relation: Relation::from_parts(self.offsets, self.members),
            locals: self.locals,
            max,
        }
    }
}

/// A relation filled element by element in index order, with a local index
/// per member, into the slices of [`FillTables`] taken once: a push is a
/// store and a count, its state in registers. Members past the tables'
/// room are counted, not written ([`Filler::finish`] then asks for the
/// room they need: a non-manifold topology can need more than [`Room`]'s).
pub(super) struct Filler<'a> {
    offsets: &'a mut [u32],
    members: &'a mut [u32],
    locals: &'a mut [u16],
    /// Members pushed so far.
    len: usize,
    /// Elements ended so far.
    ended: usize,
    /// Where the current element's members start.
    start: usize,
    /// The largest element ended so far.
    max: usize,
}

impl Filler<'_> {
    #[inline(always)]
    pub(super) fn push(&mut self, member: u32, local: usize) {
        let n = self.len;
        if let (Some(m), Some(l)) = (self.members.get_mut(n), self.locals.get_mut(n)) {
            *m = member;
            *l = local as u16;
        }
        self.len = n + 1;
    }

    /// Elements ended so far.
    pub(super) fn elements(&self) -> usize {
        self.ended
    }

    /// Ends the current element.
    #[inline(always)]
    pub(super) fn end(&mut self) {
        let end = self.len;
        self.max = self.max.max(end - self.start);
        self.start = end;
        self.ended += 1;
        if let Some(o) = self.offsets.get_mut(self.ended) {
            *o = end as u32;
        }
    }

    /// The members pushed and the largest element, or `Err` with the
    /// members pushed when they did not all fit.
    pub(super) fn finish(self) -> Result<(usize, usize), usize> {
        debug_assert_eq!(
            self.ended + 1,
            self.offsets.len(),
            "every element ended once"
        );
        if self.len <= self.members.len() {
            Ok((self.len, self.max))
        } else {
            Err(self.len)
        }
    }
}

/// A filled relation: its members by element, their local indices and
/// its largest element.
pub(super) struct Filled {
    relation: Relation,
    locals: Table<u16>,
    max: usize,
}

impl Filled {
    /// The relation, its local indices and its largest element.
    pub(super) fn finish(self) -> (Relation, Table<u16>, usize) {
        (self.relation, self.locals, self.max)
    }
}

/// The relations of a child level, in its index order.
pub(super) struct Topology {
    pub(super) face_vertices: Relation,
    pub(super) face_edges: Table<u32>,
    pub(super) edge_vertices: Table<[u32; 2]>,
    pub(super) edge_faces: Filled,
    pub(super) vertex_faces: Filled,
    pub(super) vertex_edges: Filled,
}

/// The three filled relations of a child level ([`Topology`]'s), in
/// tables of [`Room`]'s sizes, or the room they turned out to need.
pub(super) struct Fills {
    edge_faces: FillTables,
    vertex_faces: FillTables,
    vertex_edges: FillTables,
}

impl Fills {
    /// Tables for `edges` edges and `vertices` vertices in `room`.
    pub(super) fn new(edges: usize, vertices: usize, room: Room) -> Self {
        Fills {
            edge_faces: FillTables::new(edges, room.edge_faces),
            vertex_faces: FillTables::new(vertices, room.vertex_faces),
            vertex_edges: FillTables::new(vertices, room.vertex_edges),
        }
    }

    /// A filler for each: edge-faces, vertex-faces, vertex-edges.
    pub(super) fn fillers(&mut self) -> [Filler<'_>; 3] {
        [
            self.edge_faces.filler(),
            self.vertex_faces.filler(),
            self.vertex_edges.filler(),
        ]
    }

    /// The child level's relations: the ones these tables' fillers
    /// filled (`done`: their [`Filler::finish`], in [`Fills::fillers`]'
    /// order), with the others given, or the room the filled ones need
    /// when one did not fit.
    pub(super) fn topology(
        self,
        done: [Result<(usize, usize), usize>; 3],
        face_vertices: Relation,
        face_edges: Table<u32>,
        edge_vertices: Table<[u32; 2]>,
    ) -> Result<Topology, Room> {
        let [edge_faces, vertex_faces, vertex_edges] = self.finish(done)?;
        Ok(Topology {
            face_vertices,
            face_edges,
            edge_vertices,
            edge_faces,
            vertex_faces,
            vertex_edges,
        })
    }

    /// The filled relations (`done`: the fillers' [`Filler::finish`]), or
    /// the room they need when one did not fit.
    fn finish(self, done: [Result<(usize, usize), usize>; 3]) -> Result<[Filled; 3], Room> {
        match done {
            [Ok(ef), Ok(vf), Ok(ve)] => Ok([
                self.edge_faces.finish(ef),
                self.vertex_faces.finish(vf),
                self.vertex_edges.finish(ve),
            ]),
            [ef, vf, ve] => {
                let need = |r: Result<(usize, usize), usize>| r.map_or_else(|n| n, |(n, _)| n);
                Err(Room {
                    edge_faces: need(ef),
                    vertex_faces: need(vf),
                    vertex_edges: need(ve),
                })
            }
        }
    }
}

/// The child level's relations, filled by `fill` in `room` and, when they
/// did not fit, again in the room they were counted to need (the second
/// fill always fits: it counts the same members).
pub(super) fn fill_in(
    mut room: Room,
    mut fill: impl FnMut(Room) -> Result<Topology, Room>,
) -> Topology {
    loop {
        match fill(room) {
            Ok(t) => return t,
            Err(needed) => room = needed,
        }
    }
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
    edge_faces: &mut Filler<'_>,
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
    edge_faces: &mut Filler<'_>,
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
#[inline(always)]
pub(super) fn vertex_point(
    parent: LevelSlices<'_>,
    s: Numbering<'_>,
    v: usize,
    (vertex_faces, vertex_edges): (&mut Filler<'_>, &mut Filler<'_>),
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Fills edge-faces [[7, 8], [], [9]] and vertex-faces and vertex-edges
    /// of one vertex with one member each.
    fn fill(room: Room) -> Result<[Filled; 3], Room> {
        let mut fills = Fills::new(3, 1, room);
        let [mut ef, mut vf, mut ve] = fills.fillers();
        ef.push(7, 0);
        ef.push(8, 1);
        ef.end();
        ef.end();
        ef.push(9, 2);
        ef.end();
        vf.push(4, 3);
        vf.end();
        ve.push(5, 1);
        ve.end();
        assert_eq!((ef.elements(), vf.elements()), (3, 1));
        let done = [ef.finish(), vf.finish(), ve.finish()];
        fills.finish(done)
    }

    #[test]
    fn a_fill_past_its_room_asks_for_the_room_it_needs() {
        let small = Room {
            edge_faces: 2,
            vertex_faces: 1,
            vertex_edges: 0,
        };
        let Err(need) = fill(small) else {
            panic!("three members fitted in room for two");
        };
        assert_eq!(
            (need.edge_faces, need.vertex_faces, need.vertex_edges),
            (3, 1, 1)
        );
        let Ok([ef, vf, ve]) = fill(need) else {
            panic!("the counted room did not fit");
        };
        let (relation, locals, max) = ef.finish();
        assert_eq!(relation.get(0), &[7, 8]);
        assert!(relation.get(1).is_empty());
        assert_eq!(relation.get(2), &[9]);
        assert_eq!(&locals[..], &[0, 1, 2]);
        assert_eq!(max, 2);
        let (relation, locals, max) = vf.finish();
        assert_eq!((relation.get(0), &locals[..], max), (&[4][..], &[3][..], 1));
        let (relation, locals, max) = ve.finish();
        assert_eq!((relation.get(0), &locals[..], max), (&[5][..], &[1][..], 1));
    }
}
