//! A level's relations as plain slices ([`LevelSlices`]).

use super::level::sparse_at;
use super::{Level, RelationView, VertexTag};

/// A level's relations as plain slices, read through their tables once
/// ([`Level::slices`]) for loops that look up many elements: each access to a
/// [`Table`](super::Table) or a [`Relation`](super::Relation) otherwise matches
/// on its representation.
#[derive(Clone, Copy)]
pub(crate) struct LevelSlices<'a> {
    pub(crate) face_vertices: RelationView<'a>,
    /// Face → edges, with `face_vertices`' offsets.
    pub(crate) face_edges: &'a [u32],
    pub(crate) edge_vertices: &'a [[u32; 2]],
    pub(crate) edge_faces: RelationView<'a>,
    pub(crate) edge_face_local: &'a [u16],
    pub(crate) vertex_faces: RelationView<'a>,
    pub(crate) vertex_face_local: &'a [u16],
    pub(crate) vertex_edges: RelationView<'a>,
    pub(crate) vertex_edge_local: &'a [u16],
    /// Edge sharpness, empty when every edge is smooth.
    pub(crate) edge_sharpness: &'a [f32],
    /// Vertex tags, empty when every tag is the default.
    pub(crate) vertex_tags: &'a [VertexTag],
}

impl<'a> LevelSlices<'a> {
    #[inline(always)]
    fn of(parent: &'a Level) -> Self {
        LevelSlices {
            face_vertices: parent.face_vertices.view(),
            face_edges: &parent.face_edges,
            edge_vertices: &parent.edge_vertices,
            edge_faces: parent.edge_faces.view(),
            edge_face_local: &parent.edge_face_local,
            vertex_faces: parent.vertex_faces.view(),
            vertex_face_local: &parent.vertex_face_local,
            vertex_edges: parent.vertex_edges.view(),
            vertex_edge_local: &parent.vertex_edge_local,
            edge_sharpness: &parent.edge_sharpness,
            vertex_tags: &parent.vertex_tags,
        }
    }

    /// The vertices of face `f`.
    #[inline(always)]
    pub(crate) fn face_verts(&self, f: usize) -> &'a [u32] {
        self.face_vertices.get(f)
    }

    /// The sharpness of edge `e`, as [`Level::edge_sharpness_at`].
    #[inline(always)]
    pub(crate) fn edge_sharpness_at(&self, e: usize) -> f32 {
        sparse_at(self.edge_sharpness, e)
    }

    /// The tags of vertex `v`, as [`Level::vertex_tag`].
    #[inline(always)]
    pub(crate) fn vertex_tag(&self, v: usize) -> VertexTag {
        sparse_at(self.vertex_tags, v)
    }

    /// The edges of face `f`.
    #[inline(always)]
    pub(crate) fn face_edges_of(&self, f: usize) -> &'a [u32] {
        &self.face_edges[self.face_vertices.range(f)]
    }

    /// The vertex of edge `e` other than `v` (`v` itself on a degenerate
    /// edge), as [`Level::other_vertex`].
    #[inline(always)]
    pub(crate) fn other_vertex(&self, e: usize, v: u32) -> u32 {
        let ev = self.edge_vertices[e];
        if ev[0] == v { ev[1] } else { ev[0] }
    }

    /// The faces of edge `e`.
    #[inline(always)]
    pub(crate) fn edge_faces_of(&self, e: usize) -> &'a [u32] {
        self.edge_faces.get(e)
    }

    /// The faces of edge `e` with the edge's position in each, as
    /// [`Level::edge_faces_at`] (the level keeping local indices).
    #[inline(always)]
    pub(crate) fn edge_faces_at(&self, e: usize) -> impl Iterator<Item = (usize, usize)> + 'a {
        let (faces, locals) = self.edge_faces(e);
        faces
            .iter()
            .zip(locals)
            .map(|(&f, &k)| (f as usize, k as usize))
    }

    /// The faces of vertex `v`.
    #[inline(always)]
    pub(crate) fn vertex_faces_of(&self, v: usize) -> &'a [u32] {
        self.vertex_faces.get(v)
    }

    /// The vertex's position in each of its faces (the level keeping local
    /// indices).
    #[inline(always)]
    pub(crate) fn vertex_face_locals(&self, v: usize) -> &'a [u16] {
        &self.vertex_face_local[self.vertex_faces.range(v)]
    }

    /// The edges of vertex `v`.
    #[inline(always)]
    pub(crate) fn vertex_edges_of(&self, v: usize) -> &'a [u32] {
        self.vertex_edges.get(v)
    }

    /// The faces of edge `e`, with the edge's position in each (the level
    /// keeping local indices).
    #[inline(always)]
    pub(crate) fn edge_faces(&self, e: usize) -> (&'a [u32], &'a [u16]) {
        let r = self.edge_faces.range(e);
        (
            &self.edge_faces.members[r.clone()],
            &self.edge_face_local[r],
        )
    }

    /// The faces of vertex `v`, with the vertex's position in each (the
    /// level keeping local indices).
    #[inline(always)]
    pub(crate) fn vertex_faces(&self, v: usize) -> (&'a [u32], &'a [u16]) {
        let r = self.vertex_faces.range(v);
        (
            &self.vertex_faces.members[r.clone()],
            &self.vertex_face_local[r],
        )
    }

    /// The edges of vertex `v`, with the vertex's end of each (the level
    /// keeping local indices).
    #[inline(always)]
    pub(crate) fn vertex_edges(&self, v: usize) -> (&'a [u32], &'a [u16]) {
        let r = self.vertex_edges.range(v);
        (
            &self.vertex_edges.members[r.clone()],
            &self.vertex_edge_local[r],
        )
    }
}

impl Level {
    /// The level's relations as slices ([`LevelSlices`]).
    #[inline(always)]
    pub(crate) fn slices(&self) -> LevelSlices<'_> {
        LevelSlices::of(self)
    }
}
