//! A level's relations around its edges and vertices as the face-varying
//! code reads them: stored in the level, or — for a level built without them
//! ([`Level::derived_relations`]) — derived from the level before, local
//! indices included. OpenSubdiv always stores them: this has no counterpart
//! there.
//!
//! A level whose relations are derived is smooth everywhere, closed and
//! manifold (see `refine::derive`): no vertex appears twice in a face and no
//! edge joins a vertex to itself, so a vertex's position in a face and an
//! edge's position in a face are found by looking, and an edge's end by
//! comparing.

use super::refine::{derive_edge_faces, derive_vertex_relations};
use super::{Level, Split};

/// The faces of an edge: read from its level, or derived.
pub(crate) enum EdgeFaces<'a> {
    /// Read from the level.
    Stored(&'a [u32]),
    /// Derived from the level before (always two).
    Derived([u32; 2]),
}

impl EdgeFaces<'_> {
    /// The faces, in the level's order.
    pub(crate) fn as_slice(&self) -> &[u32] {
        match self {
            EdgeFaces::Stored(f) => f,
            EdgeFaces::Derived(f) => f,
        }
    }
}

/// A level and, when it derives its relations, the level before and the
/// split between them.
#[derive(Clone, Copy)]
pub(crate) struct Around<'a> {
    /// The level.
    pub level: &'a Level,
    /// The level before, its split into `level` and whether the split is
    /// Loop's: present exactly when `level` derives its relations.
    from: Option<(&'a Level, &'a Split, bool)>,
}

/// Room for the relations of one vertex of a level that derives them.
#[derive(Debug, Default)]
pub(crate) struct AroundBuf {
    faces: Vec<u32>,
    face_locals: Vec<u16>,
    edges: Vec<u32>,
    edge_locals: Vec<u16>,
    edge_list: Vec<(u32, u16)>,
}

/// The faces of a vertex with its position in each, and its edges with its
/// end of each, in the level's order (counter-clockwise, interleaved).
#[derive(Clone, Copy)]
pub(crate) struct Hood<'b> {
    /// The vertex's faces.
    pub faces: &'b [u32],
    /// The vertex's position in each face.
    pub face_locals: &'b [u16],
    /// The vertex's edges.
    pub edges: &'b [u32],
    /// Which end of each edge the vertex is (0 or 1).
    pub edge_locals: &'b [u16],
}

impl<'a> Around<'a> {
    /// `level`, whose relations are read from it, or — where it derives them
    /// — from `before` (the level before and the split into `level`;
    /// `triangles`: Loop's split). A level that derives its relations has a
    /// level before it.
    pub(crate) fn new(
        level: &'a Level,
        before: Option<(&'a Level, &'a Split)>,
        triangles: bool,
    ) -> Self {
        let from = before
            .filter(|_| level.derived_relations)
            .map(|(parent, split)| (parent, split, triangles));
        debug_assert!(!level.derived_relations || from.is_some());
        Around { level, from }
    }

    /// `level`, which stores its relations.
    pub(crate) fn stored(level: &'a Level) -> Self {
        debug_assert!(!level.derived_relations);
        Around { level, from: None }
    }

    /// Whether the level derives its relations from the level before (its
    /// own vertex-faces, vertex-edges and edge-faces are empty).
    #[inline(always)]
    pub(crate) fn derives(&self) -> bool {
        self.from.is_some()
    }

    /// Number of faces of edge `e`.
    #[inline]
    pub(crate) fn edge_face_count(&self, e: usize) -> usize {
        match self.from {
            Some(_) => 2,
            None => self.level.edge_faces.count(e),
        }
    }

    /// The faces of edge `e`.
    #[inline]
    pub(crate) fn edge_faces(&self, e: usize) -> EdgeFaces<'a> {
        match self.from {
            Some((parent, split, triangles)) => {
                EdgeFaces::Derived(derive_edge_faces(&parent.slices(), split, triangles, e))
            }
            None => EdgeFaces::Stored(self.level.edge_faces_of(e)),
        }
    }

    /// Face `i` of edge `e` and the edge's position in it.
    #[inline]
    pub(crate) fn edge_face(&self, e: usize, i: usize) -> (usize, usize) {
        match self.from {
            Some((parent, split, triangles)) => {
                let f = derive_edge_faces(&parent.slices(), split, triangles, e)[i] as usize;
                let k = self
                    .level
                    .face_edges_of(f)
                    .iter()
                    .position(|&x| x as usize == e);
                (f, k.unwrap_or(0))
            }
            None => (
                self.level.edge_faces_of(e)[i] as usize,
                self.level.edge_face_locals(e)[i] as usize,
            ),
        }
    }

    /// The faces and edges of vertex `v`, in the level's order: the level's
    /// own slices, or derived into `buf`.
    #[inline(always)]
    pub(crate) fn vertex_faces_and_edges<'b>(
        &self,
        v: usize,
        buf: &'b mut AroundBuf,
    ) -> (&'b [u32], &'b [u32])
    where
        'a: 'b,
    {
        let l = self.level;
        let Some((parent, split, triangles)) = self.from else {
            return (l.vertex_faces_of(v), l.vertex_edges_of(v));
        };
        derive_vertex_relations(
            parent,
            split,
            triangles,
            v,
            (&mut buf.faces, &mut buf.edges, &mut buf.edge_list),
        );
        (&buf.faces, &buf.edges)
    }

    /// The faces and edges of vertex `v` with their local indices: the
    /// level's own slices, or derived into `buf`.
    pub(crate) fn vertex_hood<'b>(&self, v: usize, buf: &'b mut AroundBuf) -> Hood<'b>
    where
        'a: 'b,
    {
        let l = self.level;
        if self.from.is_none() {
            return Hood {
                faces: l.vertex_faces_of(v),
                face_locals: l.vertex_face_locals(v),
                edges: l.vertex_edges_of(v),
                edge_locals: l.vertex_edge_locals(v),
            };
        }
        self.vertex_faces_and_edges(v, buf);
        buf.face_locals.clear();
        buf.face_locals.extend(buf.faces.iter().map(|&f| {
            let k = l
                .face_verts(f as usize)
                .iter()
                .position(|&x| x as usize == v);
            k.unwrap_or(0) as u16
        }));
        buf.edge_locals.clear();
        buf.edge_locals.extend(
            buf.edges
                .iter()
                .map(|&e| u16::from(l.edge_vertices[e as usize][0] as usize != v)),
        );
        Hood {
            faces: &buf.faces,
            face_locals: &buf.face_locals,
            edges: &buf.edges,
            edge_locals: &buf.edge_locals,
        }
    }
}
