//! The parent level's faces and a split's numbering as plain slices, read
//! through their tables once per level (each access to a [`Table`] or a
//! [`Relation`] otherwise matches on its representation): what the sparse
//! splits read, with the parent's other relations
//! ([`LevelSlices`](crate::topology::LevelSlices)).

use super::{PackedParent, SparseSplit};
#[cfg(doc)]
use crate::topology::Table;
use crate::topology::{Level, Relation};

/// The parent's faces as a split walks them: with `QUADS`, every face is a
/// quad with implicit offsets (each level the quad split made), so a face's
/// corners are found without reading offsets and its size is a constant.
#[derive(Clone, Copy)]
pub(super) struct Faces<'a, const QUADS: bool> {
    pub(super) relation: &'a Relation,
    /// The face-vertices, concatenated.
    pub(super) verts: &'a [u32],
    /// The face-edges, concatenated.
    pub(super) edges: &'a [u32],
}

impl<'a, const QUADS: bool> Faces<'a, QUADS> {
    pub(super) fn of(parent: &'a Level) -> Self {
        debug_assert!(!QUADS || parent.face_vertices.uniform_size() == Some(4));
        Faces {
            relation: &parent.face_vertices,
            verts: &parent.face_vertices.members,
            edges: &parent.face_edges,
        }
    }

    /// Where face `f`'s corners are in the concatenated tables.
    #[inline(always)]
    pub(super) fn range(&self, f: usize) -> std::ops::Range<usize> {
        if QUADS {
            4 * f..4 * f + 4
        } else {
            self.relation.range(f)
        }
    }

    /// Corner `k`'s vertex of face `f`.
    #[inline(always)]
    pub(super) fn corner(&self, f: usize, k: usize) -> u32 {
        self.verts[self.range(f).start + k]
    }
}

/// A [`SparseSplit`]'s numbering as slices (its fields of the same names).
#[derive(Clone, Copy)]
pub(super) struct Numbering<'a> {
    pub(super) face_child_faces: &'a [u32],
    pub(super) face_child_edges: &'a [u32],
    pub(super) edge_child_edges: &'a [[u32; 2]],
    pub(super) face_child_vertex: &'a [u32],
    pub(super) edge_child_vertex: &'a [u32],
    pub(super) vertex_child_vertex: &'a [u32],
    pub(super) child_vertex_parent: &'a [PackedParent],
}

impl<'a> Numbering<'a> {
    pub(super) fn of(s: &'a SparseSplit) -> Self {
        Numbering {
            face_child_faces: &s.face_child_faces,
            face_child_edges: &s.face_child_edges,
            edge_child_edges: &s.edge_child_edges,
            face_child_vertex: &s.face_child_vertex,
            edge_child_vertex: &s.edge_child_vertex,
            vertex_child_vertex: &s.vertex_child_vertex,
            child_vertex_parent: &s.child_vertex_parent,
        }
    }
}
