//! Writing the relations of a child level: a [`TableWriter`] fills a
//! relation with known totals element by element, and the per-vertex rules
//! of both splits write into a [`Sink`] — a writer while a level is built,
//! a buffer while one vertex's relations are derived
//! ([`super::derive_vertex_relations`]). OpenSubdiv writes into tables sized
//! beforehand (`Refinement::subdivideTopology`); this is the native
//! equivalent.

use super::Split;
use crate::topology::table_pool::vec_with_capacity;
use crate::topology::{Level, Offsets, Relation, Table};

/// Fills a relation with known totals element by element: members and their
/// local indices pushed in order, each element closed by `end_element`. With
/// a `uniform` size (every element has that many members) no offsets are
/// stored.
///
/// The values are pushed into vectors reserved at their final size rather
/// than written into zeroed tables: nothing is written twice (a zeroed
/// allocation that reuses freed memory is cleared first). The vectors are
/// those of dropped tables when the pool keeps some of about that size
/// (`table_pool::vec_with_capacity`): a refinement done again then pushes
/// into memory already faulted in (on the production-like mesh with its UV
/// channel to level 2, 8,600 page faults per refinement before, 380 after).
pub(super) struct TableWriter {
    starts: Starts,
    members: Vec<u32>,
    locals: Option<Vec<u16>>,
    /// The element and member counts given to `new` (checked by `finish`).
    expected: (usize, usize),
}

/// Where the elements of a [`TableWriter`] start.
enum Starts {
    /// The offsets written so far, starting with 0.
    Table(Vec<u32>),
    /// Every element has `size` members; `ended` elements are closed.
    Uniform {
        len: usize,
        size: usize,
        ended: usize,
    },
}

impl TableWriter {
    pub(super) fn new(
        elements: usize,
        members: usize,
        uniform: Option<usize>,
        locals: bool,
    ) -> Self {
        TableWriter {
            starts: match uniform {
                Some(size) => Starts::Uniform {
                    len: elements,
                    size,
                    ended: 0,
                },
                None => {
                    let mut offsets = vec_with_capacity(elements + 1);
                    offsets.push(0);
                    Starts::Table(offsets)
                }
            },
            members: vec_with_capacity(members),
            locals: locals.then(|| vec_with_capacity(members)),
            expected: (elements, members),
        }
    }

    #[inline]
    pub(super) fn push(&mut self, member: u32, local: u16) {
        self.members.push(member);
        if let Some(locals) = &mut self.locals {
            locals.push(local);
        }
    }

    #[inline]
    pub(super) fn end_element(&mut self) {
        match &mut self.starts {
            Starts::Table(offsets) => offsets.push(self.members.len() as u32),
            Starts::Uniform { size, ended, .. } => {
                *ended += 1;
                debug_assert_eq!(self.members.len(), *ended * *size);
            }
        }
    }

    pub(super) fn finish(self) -> (Relation, Table<u16>) {
        let offsets = match self.starts {
            Starts::Table(offsets) => Offsets::Table(offsets.into()),
            Starts::Uniform { len, size, ended } => {
                debug_assert_eq!(ended, len);
                Offsets::Uniform { len, size }
            }
        };
        let relation = Relation {
            offsets,
            members: self.members.into(),
        };
        debug_assert_eq!((relation.len(), relation.members.len()), self.expected);
        debug_assert_eq!(relation.start(relation.len()), relation.members.len());
        (relation, self.locals.unwrap_or_default().into())
    }
}

/// Where the members of one child vertex's relations go, with their local
/// indices: a [`TableWriter`] building a level, or a buffer of members
/// deriving one vertex's relations on demand
/// ([`derive_vertex_relations`](super::derive_vertex_relations)).
pub(super) trait Sink {
    fn push(&mut self, member: u32, local: u16);
    /// Closes the current element (a buffer holds one element: nothing to do).
    #[inline(always)]
    fn end_element(&mut self) {}
}

impl Sink for TableWriter {
    #[inline(always)]
    fn push(&mut self, member: u32, local: u16) {
        TableWriter::push(self, member, local);
    }
    #[inline(always)]
    fn end_element(&mut self) {
        TableWriter::end_element(self);
    }
}

impl Sink for Vec<u32> {
    #[inline(always)]
    fn push(&mut self, member: u32, _: u16) {
        Vec::push(self, member);
    }
}

/// The writers of a child level's vertex-faces and vertex-edges (`vf` and
/// `ve` members in all), filled one child vertex after the other by
/// [`fill_vertex_relations`]. Vertex-face local indices are kept when
/// `locals`; which end of its edges a vertex is, when `locals` too or when
/// the parent has sharpness: building a minimal child reads it only in the
/// sharpness decay, and only at semi-sharp features, which the child can
/// have only if its parent has sharpness (it decays; it never appears).
pub(super) fn vertex_relation_writers(
    parent: &Level,
    r: &Split,
    vf: usize,
    ve: usize,
    locals: bool,
) -> (TableWriter, TableWriter) {
    let n = r.child_vertex_count();
    let edge_ends =
        locals || !parent.edge_sharpness.is_empty() || !parent.vertex_sharpness.is_empty();
    (
        TableWriter::new(n, vf, None, locals),
        TableWriter::new(n, ve, None, edge_ends),
    )
}

/// A child level's vertex-faces and vertex-edges, with their local indices:
/// the children of parent faces, edges and vertices — each filler closing
/// one element of both writers per child, in the order of its parents — are
/// written in the order of the child vertices' indices. The vertex-faces are
/// returned finished, the vertex-edges' sink as it was filled (a
/// [`TableWriter`] to finish, or another [`Sink`]).
pub(super) fn fill_vertex_relations<E: Sink>(
    r: &Split,
    mut vf: TableWriter,
    mut ve: E,
    mut face_children: impl FnMut(&mut TableWriter, &mut E),
    mut edge_children: impl FnMut(&mut TableWriter, &mut E),
    mut vertex_children: impl FnMut(&mut TableWriter, &mut E),
) -> ((Relation, Table<u16>), E) {
    let mut origins = [
        (r.first_vertex_from_faces, 0),
        (r.first_vertex_from_edges, 1),
        (r.first_vertex_from_vertices, 2),
    ];
    // Equal starts only come with empty ranges; the order then does not matter.
    origins.sort_unstable();
    for (_, origin) in origins {
        match origin {
            0 => face_children(&mut vf, &mut ve),
            1 => edge_children(&mut vf, &mut ve),
            _ => vertex_children(&mut vf, &mut ve),
        }
    }
    (vf.finish(), ve)
}

/// The vertex-faces and vertex-edges of the child of parent vertex `v`: the
/// child faces at the vertex's corners (`child_face(f, k)` gives the child
/// of face `f` at corner `k` and the vertex's position in it) and the halves
/// of its edges at its end (where the child vertex is end 1).
#[inline(always)]
pub(super) fn vertex_child_relations(
    parent: &Level,
    r: &Split,
    v: usize,
    vf: &mut impl Sink,
    ve: &mut impl Sink,
    child_face: impl Fn(u32, u16) -> (u32, u16),
) {
    for (&f, &k) in parent
        .vertex_faces_of(v)
        .iter()
        .zip(parent.vertex_face_locals(v))
    {
        let (member, local) = child_face(f, k);
        vf.push(member, local);
    }
    for (&e, &l) in parent
        .vertex_edges_of(v)
        .iter()
        .zip(parent.vertex_edge_locals(v))
    {
        ve.push(r.edge_child_edge(e as usize, l as usize), 1);
    }
}
