//! The parent level and a split's numbering as plain slices, read through
//! their tables once per level (each access to a [`Table`] or a
//! [`Relation`](crate::topology::Relation) otherwise matches on its
//! representation): what the sparse splits read.

use super::{PackedParent, SparseSplit};
#[cfg(doc)]
use crate::topology::Table;
use crate::topology::{Level, Relation, RelationView};

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

/// The parent's edge and vertex relations a split reads, as slices (read
/// through their tables once per level, not on every access).
#[derive(Clone, Copy)]
pub(super) struct ParentView<'a> {
    pub(super) edge_vertices: &'a [[u32; 2]],
    pub(super) edge_faces: RelationView<'a>,
    pub(super) edge_face_local: &'a [u16],
    pub(super) vertex_faces: RelationView<'a>,
    pub(super) vertex_face_local: &'a [u16],
    pub(super) vertex_edges: RelationView<'a>,
    pub(super) vertex_edge_local: &'a [u16],
}

impl<'a> ParentView<'a> {
    pub(super) fn of(parent: &'a Level) -> Self {
        ParentView {
            edge_vertices: &parent.edge_vertices,
            edge_faces: parent.edge_faces.view(),
            edge_face_local: &parent.edge_face_local,
            vertex_faces: parent.vertex_faces.view(),
            vertex_face_local: &parent.vertex_face_local,
            vertex_edges: parent.vertex_edges.view(),
            vertex_edge_local: &parent.vertex_edge_local,
        }
    }

    /// The faces of edge `e`, with the edge's position in each.
    #[inline(always)]
    pub(super) fn edge_faces(&self, e: usize) -> (&'a [u32], &'a [u16]) {
        let r = self.edge_faces.range(e);
        (
            &self.edge_faces.members[r.clone()],
            &self.edge_face_local[r],
        )
    }

    /// The faces of vertex `v`, with the vertex's position in each.
    #[inline(always)]
    pub(super) fn vertex_faces(&self, v: usize) -> (&'a [u32], &'a [u16]) {
        let r = self.vertex_faces.range(v);
        (
            &self.vertex_faces.members[r.clone()],
            &self.vertex_face_local[r],
        )
    }

    /// The edges of vertex `v`, with the vertex's end of each.
    #[inline(always)]
    pub(super) fn vertex_edges(&self, v: usize) -> (&'a [u32], &'a [u16]) {
        let r = self.vertex_edges.range(v);
        (
            &self.vertex_edges.members[r.clone()],
            &self.vertex_edge_local[r],
        )
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
