//! One level of a refinement: its relations as flat tables, its sharpness,
//! tags and holes — the native counterpart of OpenSubdiv's `Vtr::Level`
//! (`vtr/level.h`). Tables of default values (sharpness `0.0`, default tags,
//! no hole) are stored empty and read through accessors.

use super::{EdgeTag, Relation, Table, VertexTag};
use crate::rules::Rule;
use bytemuck::Pod;

/// One level of a refinement: topology, sharpness and tags.
#[derive(Debug, Clone, Default)]
pub struct Level {
    /// 0 for the base mesh.
    pub depth: u32,
    /// Number of vertices.
    pub vertex_count: usize,
    /// Face → vertices.
    pub face_vertices: Relation,
    /// Face → edges (same offsets as `face_vertices`).
    pub face_edges: Table<u32>,
    /// Edge → its two vertices.
    pub edge_vertices: Table<[u32; 2]>,
    /// Edge → faces.
    pub edge_faces: Relation,
    /// Position of the edge within each of its faces (empty in a level
    /// built as [`Build::Relations`](super::Build::Relations)).
    pub edge_face_local: Table<u16>,
    /// Vertex → faces.
    pub vertex_faces: Relation,
    /// Position of the vertex within each of its faces (empty in a level
    /// built as [`Build::Relations`](super::Build::Relations)).
    pub vertex_face_local: Table<u16>,
    /// Vertex → edges.
    pub vertex_edges: Relation,
    /// Which end of each edge the vertex is (0 or 1); empty in a level built as
    /// [`Build::Relations`](super::Build::Relations) from a parent without
    /// sharpness (nothing reads it there).
    pub vertex_edge_local: Table<u16>,
    /// Whether `vertex_faces`, `vertex_edges`, `edge_faces` and their local
    /// indices were left out (empty): in the level before a minimal last
    /// level whose parent is smooth everywhere (no sharpness, no tags, two
    /// faces on every edge), where only interpolating the last level reads
    /// them. They are then derived from the parent, element by element, in
    /// the order they would have been stored: [`Level::vertex_faces_of`],
    /// [`Level::vertex_edges_of`], [`Level::edge_faces_of`] and
    /// [`Level::find_edge`] find nothing there, while
    /// [`crate::refiner::Refiner::vertex_faces_and_edges`],
    /// [`crate::refiner::Refiner::edge_faces`] and
    /// [`crate::refiner::Refiner::find_edge`], interpolation and stencils
    /// derive them.
    pub derived_relations: bool,
    /// Number of edges.
    pub num_edges: usize,
    /// Edge sharpness, empty when every edge is smooth (sharpness `0.0`) and in
    /// a minimal last level (see
    /// [`refine::child_edge_sharpness`](super::refine::child_edge_sharpness));
    /// read it through [`Level::edge_sharpness_at`].
    pub edge_sharpness: Table<f32>,
    /// Vertex sharpness, empty when every vertex is smooth (sharpness `0.0`);
    /// read it through [`Level::vertex_sharpness_at`].
    pub vertex_sharpness: Table<f32>,
    /// Edge tags, empty when every tag is the default and in a minimal last
    /// level; read them through [`Level::edge_tag`].
    pub edge_tags: Table<EdgeTag>,
    /// Vertex tags, empty when every tag is the default (every vertex smooth:
    /// no boundary, sharp or non-manifold feature); read them through
    /// [`Level::vertex_tag`].
    pub vertex_tags: Table<VertexTag>,
    /// Hole flag of each face, empty exactly when no face is a hole; read it through
    /// [`Level::is_hole`].
    pub face_holes: Vec<bool>,
    /// Largest number of faces at any edge.
    pub max_edge_faces: usize,
    /// Largest number of edges or faces at any vertex, or vertices in any face.
    pub max_valence: usize,
}

impl Level {
    /// Number of faces.
    #[inline]
    pub fn face_count(&self) -> usize {
        self.face_vertices.len()
    }

    /// Number of edges.
    #[inline]
    pub fn edge_count(&self) -> usize {
        self.num_edges
    }

    /// Drops the tables that only splitting this level and face-varying
    /// channels read — face-edges and the local indices — keeping what
    /// interpolating the next level's vertex data reads under Catmull-Clark
    /// and bilinear rules (Loop's edge points read face-edges). For a
    /// parent whose last child exists, once its channels (if any) are
    /// interpolated.
    pub(crate) fn release_split_tables(&mut self) {
        self.release_face_edges();
        self.edge_face_local = Table::new();
        self.vertex_face_local = Table::new();
        self.vertex_edge_local = Table::new();
    }

    /// Drops the face-edges, which only splitting this level reads under
    /// Catmull-Clark and bilinear rules when the level stores its
    /// relations (Loop's edge points read them, vertex and face-varying
    /// alike, and so does a level derived from this one): for a parent
    /// whose last child exists, before its channels are interpolated.
    pub(crate) fn release_face_edges(&mut self) {
        self.face_edges = Table::new();
    }

    /// Drops the face-vertices, for a last level whose faces were counted
    /// and are not returned: interpolating its vertex data reads its
    /// vertices' tags and sharpness, not its faces.
    pub(crate) fn release_faces(&mut self) {
        self.face_vertices = Default::default();
    }

    /// Whether all relations are present. A last level refined with minimal
    /// topology (OpenSubdiv's default) has only its face-vertices, vertex
    /// sharpness and vertex tags.
    #[inline]
    pub fn has_full_topology(&self) -> bool {
        self.edge_vertices.len() == self.num_edges
            && (self.derived_relations || self.vertex_faces.len() == self.vertex_count)
    }

    /// The sharpness of edge `e`: `0.0` when the level stores no edge sharpness
    /// (every edge smooth). A minimal last level stores none either, whatever
    /// its edges' sharpness: there it is recomputed from the parent by
    /// [`refine::child_edge_sharpness`](super::refine::child_edge_sharpness).
    #[inline(always)]
    pub fn edge_sharpness_at(&self, e: usize) -> f32 {
        sparse_at(&self.edge_sharpness, e)
    }

    /// The sharpness of vertex `v`: `0.0` when the level stores no vertex
    /// sharpness (every vertex smooth).
    #[inline(always)]
    pub fn vertex_sharpness_at(&self, v: usize) -> f32 {
        sparse_at(&self.vertex_sharpness, v)
    }

    /// Whether face `f` is a hole: `false` when the level stores no hole
    /// flags (no face is a hole).
    #[inline(always)]
    pub fn is_hole(&self, f: usize) -> bool {
        !self.face_holes.is_empty() && self.face_holes[f]
    }

    /// The tags of edge `e`: the default when the level stores no edge tags
    /// (every edge smooth and manifold, with two faces). A minimal last level
    /// stores none either, whatever its edges' tags.
    #[inline(always)]
    pub fn edge_tag(&self, e: usize) -> EdgeTag {
        sparse_at(&self.edge_tags, e)
    }

    /// The tags of vertex `v`, with its rule: the default (rule
    /// [`Rule::Smooth`], no flag) when the level stores no vertex tags.
    #[inline(always)]
    pub fn vertex_tag(&self, v: usize) -> VertexTag {
        sparse_at(&self.vertex_tags, v)
    }

    /// Sets the tags of edge `e`. The table stays empty while every tag is
    /// the default: the first other tag allocates it.
    #[inline]
    pub(crate) fn set_edge_tag(&mut self, e: usize, tag: EdgeTag) {
        set_sparse(&mut self.edge_tags, self.num_edges, e, tag);
    }

    /// Sets the tags of vertex `v`, as [`Level::set_edge_tag`] does.
    #[inline]
    pub(crate) fn set_vertex_tag(&mut self, v: usize, tag: VertexTag) {
        set_sparse(&mut self.vertex_tags, self.vertex_count, v, tag);
    }

    /// Changes the tags of vertex `v` with `f`, as [`Level::set_vertex_tag`]
    /// sets them.
    #[inline]
    pub(crate) fn update_vertex_tag(&mut self, v: usize, f: impl FnOnce(&mut VertexTag)) {
        let mut tag = self.vertex_tag(v);
        f(&mut tag);
        self.set_vertex_tag(v, tag);
    }

    /// Empties the tag tables whose tags are all the default.
    pub(crate) fn drop_default_tags(&mut self) {
        drop_if_default(&mut self.edge_tags);
        drop_if_default(&mut self.vertex_tags);
    }

    /// Sets the sharpness of edge `e`. The table stays empty while every
    /// value is `0.0`: the first other value allocates it.
    #[inline]
    pub(crate) fn set_edge_sharpness(&mut self, e: usize, s: f32) {
        set_sparse(&mut self.edge_sharpness, self.num_edges, e, s);
    }

    /// Sets the sharpness of vertex `v`, as [`Level::set_edge_sharpness`] does.
    #[inline]
    pub(crate) fn set_vertex_sharpness(&mut self, v: usize, s: f32) {
        set_sparse(&mut self.vertex_sharpness, self.vertex_count, v, s);
    }

    /// Makes face `f` a hole, allocating the hole flags at the first hole.
    pub(crate) fn set_hole(&mut self, f: usize) {
        if self.face_holes.is_empty() {
            self.face_holes = crate::alloc::vec_or_unwind(false, self.face_count());
        }
        self.face_holes[f] = true;
    }

    /// The vertices of face `f`.
    #[inline(always)]
    pub fn face_verts(&self, f: usize) -> &[u32] {
        self.face_vertices.get(f)
    }

    /// The edges of face `f`.
    #[inline(always)]
    pub fn face_edges_of(&self, f: usize) -> &[u32] {
        &self.face_edges[self.face_vertices.range(f)]
    }

    /// The faces of edge `e`.
    #[inline(always)]
    pub fn edge_faces_of(&self, e: usize) -> &[u32] {
        self.edge_faces.get(e)
    }

    /// The faces of edge `e` with the edge's position in each, as `usize`s.
    ///
    /// # Panics
    /// If the level keeps no local indices ([`Level::has_local_indices`]).
    #[inline(always)]
    pub fn edge_faces_at(&self, e: usize) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.edge_faces_of(e)
            .iter()
            .zip(self.edge_face_locals(e))
            .map(|(&f, &k)| (f as usize, k as usize))
    }

    /// The position of edge `e` within each of its faces.
    ///
    /// # Panics
    /// If the level keeps no local indices ([`Level::has_local_indices`]).
    #[inline(always)]
    pub fn edge_face_locals(&self, e: usize) -> &[u16] {
        &self.edge_face_local[self.edge_faces.range(e)]
    }

    /// Whether the level keeps the positions of its edges and vertices within
    /// their faces: false only for a level built as
    /// [`Build::Relations`](super::Build::Relations) (the level before a
    /// minimal last level).
    pub fn has_local_indices(&self) -> bool {
        !self.derived_relations
            && self.vertex_face_local.len() == self.vertex_faces.members.len()
            && self.edge_face_local.len() == self.edge_faces.members.len()
    }

    /// The faces of vertex `v`.
    #[inline(always)]
    pub fn vertex_faces_of(&self, v: usize) -> &[u32] {
        self.vertex_faces.get(v)
    }

    /// The position of vertex `v` within each of its faces.
    ///
    /// # Panics
    /// If the level keeps no local indices ([`Level::has_local_indices`]).
    #[inline(always)]
    pub fn vertex_face_locals(&self, v: usize) -> &[u16] {
        &self.vertex_face_local[self.vertex_faces.range(v)]
    }

    /// The edges of vertex `v`.
    #[inline(always)]
    pub fn vertex_edges_of(&self, v: usize) -> &[u32] {
        self.vertex_edges.get(v)
    }

    /// Which end of each of its edges vertex `v` is.
    ///
    /// # Panics
    /// If the level keeps no vertex-edge ends (a level built as
    /// [`Build::Relations`](super::Build::Relations) from a parent without
    /// sharpness).
    #[inline(always)]
    pub fn vertex_edge_locals(&self, v: usize) -> &[u16] {
        &self.vertex_edge_local[self.vertex_edges.range(v)]
    }

    /// The vertex at the other end of edge `e` from `v`.
    #[inline]
    pub fn other_vertex(&self, e: usize, v: u32) -> u32 {
        let ev = self.edge_vertices[e];
        if ev[0] == v { ev[1] } else { ev[0] }
    }

    /// The first edge joining `v0` and `v1`, as OpenSubdiv's `findEdge` returns it.
    pub fn find_edge(&self, v0: u32, v1: u32) -> Option<u32> {
        let edges = self.vertex_edges_of(v0 as usize);
        if v0 != v1 {
            edges.iter().copied().find(|&e| {
                let ev = self.edge_vertices[e as usize];
                ev[0] == v1 || ev[1] == v1
            })
        } else {
            edges.iter().copied().find(|&e| {
                let ev = self.edge_vertices[e as usize];
                ev[0] == ev[1]
            })
        }
    }
}

/// The first vertex whose rule is smooth (or dart) although its faces and
/// edges do not pair up — possible when a face names the vertex twice without
/// making anything non-manifold. OpenSubdiv's smooth masks assume pairs (its
/// own assertion aborts on such a vertex), so both engines refuse the mesh.
pub fn unpaired_smooth_vertex(level: &Level) -> Option<usize> {
    // Offsets and tags read as slices: this runs over every base vertex.
    let (vf, ve) = (
        level.vertex_faces.offsets_slice(),
        level.vertex_edges.offsets_slice(),
    );
    let tags: &[VertexTag] = &level.vertex_tags;
    (0..level.vertex_count).find(|&v| {
        vf[v + 1] - vf[v] != ve[v + 1] - ve[v]
            && (tags.is_empty() || matches!(tags[v].rule(), Rule::Smooth | Rule::Dart))
    })
}

/// Whether `x` is the default value a sparse table need not store: all zero
/// bits (a sharpness of `0.0` but not `-0.0` or NaN; a tag with every flag
/// clear and the smooth rule).
#[inline(always)]
fn is_default<T: Pod>(x: T) -> bool {
    bytemuck::bytes_of(&x).iter().all(|&b| b == 0)
}

/// Entry `i` of a sparse table (sharpness, tags), the default when the table
/// is stored empty.
#[inline(always)]
pub(super) fn sparse_at<T: Pod>(table: &[T], i: usize) -> T {
    if table.is_empty() {
        T::zeroed()
    } else {
        table[i]
    }
}

/// Sets entry `i` of a table of `len` entries stored empty while they are
/// all the default: the first other value allocates it.
#[inline]
fn set_sparse<T: Pod + Send>(table: &mut Table<T>, len: usize, i: usize, x: T) {
    if table.is_empty() {
        if is_default(x) {
            return;
        }
        *table = Table::zeroed(len);
    }
    table[i] = x;
}

/// Empties a table whose entries are all the default (values set and later
/// overwritten with the default, or decayed to it).
pub(super) fn drop_if_default<T: Pod + Send>(table: &mut Table<T>) {
    if table.iter().all(|&x| is_default(x)) {
        *table = Table::new();
    }
}
