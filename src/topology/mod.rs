//! One refinement level as flat index tables, built from face-vertex lists and
//! split level by level — the native counterpart of OpenSubdiv's `Vtr::Level`.
//!
//! Every relation is stored as a flat array plus offsets (no per-element
//! allocation, no pointer graph):
//!
//! | relation | members | local index |
//! | --- | --- | --- |
//! | face → vertices, face → edges | in face order; edge `j` runs from vertex `j` to `j+1` | — |
//! | edge → vertices | the two ends | — |
//! | edge → faces | incident faces | position of the edge in each face |
//! | vertex → faces | counter-clockwise around a manifold vertex | position of the vertex in each face |
//! | vertex → edges | counter-clockwise, interleaved with the faces | 0 or 1: which end of the edge |
//!
//! Base edges are numbered as OpenSubdiv numbers them (order of first
//! appearance while walking the faces), non-manifold features are detected and
//! tagged as OpenSubdiv tags them, and children are numbered in OpenSubdiv's
//! order (see [`refine`]).

mod base;
pub mod fvar;
pub mod refine;
mod table;

pub use base::build_base_level;
pub use refine::{Build, Split, refine_level};
pub use table::{Table, release_table_pool};

use crate::rules::Rule;
use bytemuck::Pod;

/// The first vertex whose rule is smooth (or dart) although its faces and
/// edges do not pair up — possible when a face names the vertex twice without
/// making anything non-manifold. OpenSubdiv's smooth masks assume pairs (its
/// own assertion aborts on such a vertex), so both engines refuse the mesh.
pub fn unpaired_smooth_vertex(level: &Level) -> Option<usize> {
    (0..level.vertex_count).find(|&v| {
        matches!(level.vertex_tag(v).rule(), Rule::Smooth | Rule::Dart)
            && level.vertex_faces.count(v) != level.vertex_edges.count(v)
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
fn sparse_at<T: Pod>(table: &[T], i: usize) -> T {
    if table.is_empty() {
        T::zeroed()
    } else {
        table[i]
    }
}

/// Sets entry `i` of a table of `len` entries stored empty while they are
/// all the default: the first other value allocates it.
#[inline]
fn set_sparse<T: Pod>(table: &mut Table<T>, len: usize, i: usize, x: T) {
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
fn drop_if_default<T: Pod>(table: &mut Table<T>) {
    if table.iter().all(|&x| is_default(x)) {
        *table = Table::new();
    }
}

/// Generates a getter and a setter for each bit of a packed tag.
macro_rules! tag_bits {
    ($ty:ty, $bits:ty; $($(#[$doc:meta])* $get:ident, $set:ident = $bit:expr;)*) => {
        impl $ty {
            $(
                $(#[$doc])*
                #[inline]
                pub fn $get(self) -> bool {
                    self.0 & $bit != 0
                }

                #[doc = concat!("Sets [`Self::", stringify!($get), "`].")]
                #[inline]
                pub fn $set(&mut self, on: bool) {
                    if on {
                        self.0 |= $bit;
                    } else {
                        self.0 &= !($bit as $bits);
                    }
                }
            )*
        }
    };
}

/// Tags of an edge (OpenSubdiv's `ETag`, the parts refinement uses), packed
/// in one byte; all clear by default.
#[derive(Clone, Copy, PartialEq, Eq, Default, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(transparent)]
pub struct EdgeTag(u8);

tag_bits! {
    EdgeTag, u8;
    /// More than two faces, a repeated or degenerate edge, or faces of opposite winding.
    non_manifold, set_non_manifold = 1;
    /// Fewer than two incident faces.
    boundary, set_boundary = 2;
    /// Infinitely sharp.
    inf_sharp, set_inf_sharp = 4;
    /// Sharp but finite.
    semi_sharp, set_semi_sharp = 8;
}

impl std::fmt::Debug for EdgeTag {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("EdgeTag")
            .field("non_manifold", &self.non_manifold())
            .field("boundary", &self.boundary())
            .field("inf_sharp", &self.inf_sharp())
            .field("semi_sharp", &self.semi_sharp())
            .finish()
    }
}

/// Tags of a vertex (OpenSubdiv's `VTag`, the parts refinement uses), packed
/// in two bytes; all clear and the rule [`Rule::Smooth`] by default.
#[derive(Clone, Copy, PartialEq, Eq, Default, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(transparent)]
pub struct VertexTag(u16);

tag_bits! {
    VertexTag, u16;
    /// Its incident faces and edges cannot be ordered around it.
    non_manifold, set_non_manifold = 1;
    /// On a boundary edge.
    boundary, set_boundary = 2;
    /// A topological corner (one face, two edges) that is infinitely sharp.
    corner, set_corner = 4;
    /// Infinitely sharp.
    inf_sharp, set_inf_sharp = 8;
    /// Sharp but finite.
    semi_sharp, set_semi_sharp = 16;
    /// Has semi-sharp incident edges.
    semi_sharp_edges, set_semi_sharp_edges = 32;
    /// Has infinitely sharp incident edges.
    inf_sharp_edges, set_inf_sharp_edges = 64;
}

impl VertexTag {
    const RULE_SHIFT: u32 = 8;

    /// The subdivision rule of the vertex.
    #[inline]
    pub fn rule(self) -> Rule {
        match (self.0 >> Self::RULE_SHIFT) & 3 {
            0 => Rule::Smooth,
            1 => Rule::Dart,
            2 => Rule::Crease,
            _ => Rule::Corner,
        }
    }

    /// Sets [`Self::rule`].
    #[inline]
    pub fn set_rule(&mut self, rule: Rule) {
        let code = match rule {
            Rule::Smooth => 0,
            Rule::Dart => 1,
            Rule::Crease => 2,
            Rule::Corner => 3,
        };
        self.0 = (self.0 & !(3 << Self::RULE_SHIFT)) | (code << Self::RULE_SHIFT);
    }
}

impl std::fmt::Debug for VertexTag {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("VertexTag")
            .field("non_manifold", &self.non_manifold())
            .field("boundary", &self.boundary())
            .field("corner", &self.corner())
            .field("inf_sharp", &self.inf_sharp())
            .field("semi_sharp", &self.semi_sharp())
            .field("semi_sharp_edges", &self.semi_sharp_edges())
            .field("inf_sharp_edges", &self.inf_sharp_edges())
            .field("rule", &self.rule())
            .finish()
    }
}

/// Where the members of each element of a [`Relation`] start.
#[derive(Debug, Clone)]
pub enum Offsets {
    /// `len` elements of `size` members each: element `i` starts at
    /// `i * size`, and no table is stored (the faces of every refined
    /// Catmull-Clark or Loop level).
    Uniform {
        /// Number of elements.
        len: usize,
        /// Members per element.
        size: usize,
    },
    /// The start of every element, plus one final entry.
    Table(Table<u32>),
}

impl Default for Offsets {
    fn default() -> Self {
        Offsets::Uniform { len: 0, size: 0 }
    }
}

/// A compressed relation: the members of element `i` are
/// `members[start(i)..start(i + 1)]`.
#[derive(Debug, Clone, Default)]
pub struct Relation {
    /// Where each element starts.
    pub offsets: Offsets,
    /// The members, concatenated.
    pub members: Table<u32>,
}

impl PartialEq for Relation {
    fn eq(&self, other: &Self) -> bool {
        self.len() == other.len()
            && self.members == other.members
            && (0..=self.len()).all(|i| self.start(i) == other.start(i))
    }
}

impl Eq for Relation {}

impl Relation {
    /// An empty relation over no elements.
    pub fn new() -> Self {
        Relation::default()
    }

    /// A relation from its offsets (`count + 1`) and members.
    pub fn from_parts(offsets: Table<u32>, members: Table<u32>) -> Self {
        Relation {
            offsets: Offsets::Table(offsets),
            members,
        }
    }

    /// A relation where every element has `size` members (zeroed), with
    /// implicit offsets.
    pub fn uniform(count: usize, size: usize) -> Self {
        Relation {
            offsets: Offsets::Uniform { len: count, size },
            members: Table::zeroed(count * size),
        }
    }

    /// As [`Relation::uniform`], with members for the caller to write, every
    /// one ([`Table::for_overwrite`]: not cleared first).
    pub(crate) fn uniform_for_overwrite(count: usize, size: usize) -> Self {
        Relation {
            offsets: Offsets::Uniform { len: count, size },
            members: Table::for_overwrite(count * size),
        }
    }

    /// Number of elements.
    #[inline]
    pub fn len(&self) -> usize {
        match &self.offsets {
            Offsets::Uniform { len, .. } => *len,
            Offsets::Table(t) => t.len().saturating_sub(1),
        }
    }

    /// Whether there is no element.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Where element `i`'s members start (`i == len()`: the end of the last).
    #[inline(always)]
    pub fn start(&self, i: usize) -> usize {
        match &self.offsets {
            Offsets::Uniform { size, .. } => i * size,
            Offsets::Table(t) => t[i] as usize,
        }
    }

    /// The range of element `i`'s members.
    #[inline(always)]
    pub fn range(&self, i: usize) -> std::ops::Range<usize> {
        match &self.offsets {
            Offsets::Uniform { size, .. } => i * size..(i + 1) * size,
            Offsets::Table(t) => t[i] as usize..t[i + 1] as usize,
        }
    }

    /// The members of element `i`.
    #[inline(always)]
    pub fn get(&self, i: usize) -> &[u32] {
        &self.members[self.range(i)]
    }

    /// The members of element `i`, mutably.
    #[inline]
    pub fn get_mut(&mut self, i: usize) -> &mut [u32] {
        let r = self.range(i);
        &mut self.members[r]
    }

    /// Number of members of element `i`.
    #[inline(always)]
    pub fn count(&self, i: usize) -> usize {
        match &self.offsets {
            Offsets::Uniform { size, .. } => *size,
            Offsets::Table(t) => (t[i + 1] - t[i]) as usize,
        }
    }

    /// The member count of every element when it is the same for all and the
    /// offsets are implicit.
    #[inline]
    pub fn uniform_size(&self) -> Option<usize> {
        match self.offsets {
            Offsets::Uniform { size, .. } => Some(size),
            Offsets::Table(_) => None,
        }
    }

    /// The same relation with implicit offsets when every element has the
    /// same number of members.
    pub fn compact(self) -> Self {
        match &self.offsets {
            Offsets::Table(t) if t.len() > 1 => {
                let size = (t[1] - t[0]) as usize;
                // Size 0 stays a table: `element_of` divides by the size.
                if size > 0 && t[0] == 0 && t.windows(2).all(|w| (w[1] - w[0]) as usize == size) {
                    Relation {
                        offsets: Offsets::Uniform {
                            len: t.len() - 1,
                            size,
                        },
                        members: self.members,
                    }
                } else {
                    self
                }
            }
            _ => self,
        }
    }

    /// The element whose members include position `member` of `members`.
    pub fn element_of(&self, member: usize) -> usize {
        match &self.offsets {
            Offsets::Uniform { size, .. } => member / size,
            Offsets::Table(t) => t.partition_point(|&o| o as usize <= member) - 1,
        }
    }

    /// The offsets as a slice: borrowed when stored, built when implicit.
    pub fn offsets_slice(&self) -> std::borrow::Cow<'_, [u32]> {
        match &self.offsets {
            Offsets::Uniform { len, size } => (0..=*len)
                .map(|i| (i * size) as u32)
                .collect::<Vec<_>>()
                .into(),
            Offsets::Table(t) => std::borrow::Cow::Borrowed(&t[..]),
        }
    }
}

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
    /// built as [`Build::Relations`]).
    pub edge_face_local: Table<u16>,
    /// Vertex → faces.
    pub vertex_faces: Relation,
    /// Position of the vertex within each of its faces (empty in a level
    /// built as [`Build::Relations`]).
    pub vertex_face_local: Table<u16>,
    /// Vertex → edges.
    pub vertex_edges: Relation,
    /// Which end of each edge the vertex is (0 or 1); empty in a level built
    /// as [`Build::Relations`] from a parent without sharpness (nothing reads
    /// it there).
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
    /// Edge sharpness, empty when every edge is smooth (sharpness `0.0`) and
    /// in a minimal last level (see [`refine::child_edge_sharpness`]); read
    /// it through [`Level::edge_sharpness_at`].
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

    /// Whether all relations are present. A last level refined with minimal
    /// topology (OpenSubdiv's default) has only its face-vertices, vertex
    /// sharpness and vertex tags.
    #[inline]
    pub fn has_full_topology(&self) -> bool {
        self.edge_vertices.len() == self.num_edges
            && (self.derived_relations || self.vertex_faces.len() == self.vertex_count)
    }

    /// The sharpness of edge `e`: `0.0` when the level stores no edge
    /// sharpness (every edge smooth). A minimal last level stores none
    /// either, whatever its edges' sharpness: there it is recomputed from the
    /// parent by [`refine::child_edge_sharpness`].
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
            self.face_holes = vec![false; self.face_count()];
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
    /// their faces: false only for a level built as [`Build::Relations`] (the
    /// level before a minimal last level).
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
    /// [`Build::Relations`] from a parent without sharpness).
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

#[cfg(test)]
mod relation_tests {
    use super::*;

    #[test]
    fn implicit_offsets_read_like_a_table() {
        let members: Table<u32> = (0..12).collect::<Vec<u32>>().into();
        let stored = Relation::from_parts(vec![0, 4, 8, 12].into(), members.clone());
        let compact = stored.clone().compact();
        assert_eq!(compact.uniform_size(), Some(4));
        assert!(stored.uniform_size().is_none());
        assert_eq!(compact, stored);
        for r in [&stored, &compact] {
            assert_eq!(r.len(), 3);
            assert_eq!(r.get(1), &[4, 5, 6, 7]);
            assert_eq!(r.count(2), 4);
            assert_eq!((r.start(2), r.start(3)), (8, 12));
            assert_eq!(r.element_of(7), 1);
            assert_eq!(r.element_of(8), 2);
            assert_eq!(&*r.offsets_slice(), &[0, 4, 8, 12]);
        }
        // Mixed sizes keep their table; the two forms of different sizes differ.
        let mixed = Relation::from_parts(vec![0, 3, 7].into(), (0..7).collect::<Vec<u32>>().into());
        let mixed = mixed.compact();
        assert!(mixed.uniform_size().is_none());
        assert_eq!(mixed.element_of(3), 1);
        assert_ne!(Relation::uniform(2, 3), Relation::uniform(3, 2));
        assert_eq!(Relation::uniform(2, 3).members.len(), 6);
        assert!(Relation::new().is_empty());
        // Elements without members keep their table (no division by zero).
        let empty = Relation::from_parts(vec![0, 0, 0].into(), Table::new()).compact();
        assert!(empty.uniform_size().is_none());
        assert_eq!((empty.len(), empty.count(1)), (2, 0));
    }
}

#[cfg(test)]
mod tests {
    use super::{EdgeTag, VertexTag};
    use crate::mesh::Mesh;
    use crate::options::{BoundaryInterpolation, CreasingMethod, Options, UniformOptions};
    use crate::refiner::Refiner;
    use crate::rules::{Rule, crease};
    use crate::shapes;

    /// `mesh` refined to `depth` under each scheme that applies, with full
    /// topology in the last level or not.
    fn refiners(mesh: &Mesh, depth: u32, full: bool) -> Vec<Refiner> {
        refiners_with(mesh, depth, full, BoundaryInterpolation::None)
    }

    /// [`refiners`] with another boundary interpolation.
    fn refiners_with(
        mesh: &Mesh,
        depth: u32,
        full: bool,
        boundary: BoundaryInterpolation,
    ) -> Vec<Refiner> {
        mesh.applicable_schemes()
            .iter()
            .map(|&scheme| {
                let options = Options::default()
                    .with_scheme(scheme)
                    .with_boundary(boundary)
                    .with_creasing(CreasingMethod::Uniform);
                let mut r = Refiner::new(mesh, &options).unwrap();
                r.refine_uniform(UniformOptions::new(depth).full_topology(full))
                    .unwrap();
                r
            })
            .collect()
    }

    /// Which of edge sharpness, vertex sharpness and holes each level
    /// stores, after checking that the accessors read what
    /// `Refiner::level` reports.
    fn stored(r: &Refiner) -> Vec<[bool; 3]> {
        (0..=r.max_level())
            .map(|l| {
                let level = r.internal_level(l).unwrap();
                let topo = r.level(l).unwrap();
                assert_eq!(topo.edge_sharpness.len(), level.edge_count());
                assert_eq!(topo.vertex_sharpness.len(), level.vertex_count);
                assert_eq!(topo.face_holes.len(), level.face_count());
                if level.has_full_topology() {
                    for (e, &s) in topo.edge_sharpness.iter().enumerate() {
                        assert_eq!(level.edge_sharpness_at(e).to_bits(), s.to_bits());
                    }
                }
                for (v, &s) in topo.vertex_sharpness.iter().enumerate() {
                    assert_eq!(level.vertex_sharpness_at(v).to_bits(), s.to_bits());
                }
                for (f, &h) in topo.face_holes.iter().enumerate() {
                    assert_eq!(level.is_hole(f), h);
                }
                [
                    !level.edge_sharpness.is_empty(),
                    !level.vertex_sharpness.is_empty(),
                    !level.face_holes.is_empty(),
                ]
            })
            .collect()
    }

    /// Which of edge tags and vertex tags each level of `r` stores, after
    /// checking the tags read through the accessors: the same vertex tags at
    /// every level as `full` (the same refinement with full topology in its
    /// last level), the same edge tags where `r` keeps them, and at full
    /// levels tags that match the topology and sharpness (boundary edges and
    /// vertices, sharp flags, rules from the sharp edge count).
    fn stored_tags(r: &Refiner, full: &Refiner) -> Vec<[bool; 2]> {
        (0..=r.max_level())
            .map(|l| {
                let (level, f) = (
                    r.internal_level(l).unwrap(),
                    full.internal_level(l).unwrap(),
                );
                for v in 0..level.vertex_count {
                    assert_eq!(level.vertex_tag(v), f.vertex_tag(v), "level {l} vertex {v}");
                }
                if level.has_full_topology() {
                    for e in 0..level.edge_count() {
                        let tag = level.edge_tag(e);
                        assert_eq!(tag, f.edge_tag(e), "level {l} edge {e}");
                        let faces = r.edge_faces(l, e).unwrap().len();
                        assert_eq!(tag.boundary(), faces < 2);
                        let s = level.edge_sharpness_at(e);
                        assert_eq!(tag.inf_sharp(), crease::is_infinite(s));
                        assert_eq!(tag.semi_sharp(), crease::is_sharp(s) && !tag.inf_sharp());
                    }
                    for v in 0..level.vertex_count {
                        let tag = level.vertex_tag(v);
                        let (_, around) = r.vertex_faces_and_edges(l, v).unwrap();
                        let edges = around.iter().map(|&e| level.edge_tag(e as usize));
                        let sharp = edges.clone().filter(|t| t.inf_sharp() || t.semi_sharp());
                        let s = level.vertex_sharpness_at(v);
                        assert_eq!(tag.boundary(), edges.clone().any(|t| t.boundary()));
                        assert_eq!(tag.inf_sharp(), crease::is_infinite(s));
                        assert_eq!(
                            tag.semi_sharp_edges(),
                            edges.clone().any(|t| t.semi_sharp())
                        );
                        assert_eq!(tag.inf_sharp_edges(), edges.clone().any(|t| t.inf_sharp()));
                        assert_eq!(
                            tag.rule(),
                            crease::vertex_rule_from_sharp_edge_count(s, sharp.count()),
                            "level {l} vertex {v}"
                        );
                    }
                }
                [!level.edge_tags.is_empty(), !level.vertex_tags.is_empty()]
            })
            .collect()
    }

    /// [`stored_tags`] of each refinement of `mesh` to level 3, with and
    /// without full topology in the last level, by scheme.
    fn stored_tags_by_scheme(
        mesh: &Mesh,
        boundary: BoundaryInterpolation,
    ) -> Vec<(bool, Vec<[bool; 2]>)> {
        let full = refiners_with(mesh, 3, true, boundary);
        [false, true]
            .into_iter()
            .flat_map(|f| {
                let full = &full;
                refiners_with(mesh, 3, f, boundary)
                    .into_iter()
                    .zip(full)
                    .map(move |(r, rf)| (f, stored_tags(&r, rf)))
            })
            .collect()
    }

    #[test]
    fn smooth_closed_levels_store_no_tags() {
        for mesh in [shapes::torus(6, 5), shapes::torus_triangles(6, 5)] {
            for (_, stored) in stored_tags_by_scheme(&mesh, BoundaryInterpolation::None) {
                assert_eq!(stored, vec![[false; 2]; 4]);
            }
            for r in refiners(&mesh, 2, true) {
                let level = r.internal_level(1).unwrap();
                assert_eq!(level.vertex_tag(0), VertexTag::default());
                assert_eq!(level.vertex_tag(0).rule(), Rule::Smooth);
                assert_eq!(level.edge_tag(0), EdgeTag::default());
            }
        }
    }

    #[test]
    fn boundaries_creases_corners_and_darts_store_tags() {
        // Boundaries (and their corners) stay at every level; a minimal last
        // level (none with face-varying data) stores no edge tags.
        let mut grid = shapes::grid(3, 2);
        grid.fvar_channels.clear();
        for boundary in [
            BoundaryInterpolation::None,
            BoundaryInterpolation::EdgeAndCorner,
        ] {
            for (full, stored) in stored_tags_by_scheme(&grid, boundary) {
                assert_eq!(
                    stored,
                    [[true, true], [true, true], [true, true], [full, true]]
                );
            }
        }
        for r in refiners_with(&grid, 1, true, BoundaryInterpolation::EdgeAndCorner) {
            let level = r.internal_level(0).unwrap();
            assert!(level.edge_tag(0).boundary() && level.edge_tag(0).inf_sharp());
            let corner = level.vertex_tag(0);
            assert!(corner.corner() && corner.boundary() && corner.inf_sharp());
            assert_eq!(corner.rule(), Rule::Corner);
            assert_eq!(level.vertex_tag(1).rule(), Rule::Crease);
            assert_eq!(level.vertex_tag(5).rule(), Rule::Smooth);
        }
        // A crease of 2 and a corner of 1.5 decay to 0 after two levels:
        // their tags go back to the default and are not stored.
        for mut mesh in [shapes::torus(6, 5), shapes::torus_triangles(6, 5)] {
            mesh.add_crease(0, 1, 2.0);
            mesh.add_corner(10, 1.5);
            for (_, stored) in stored_tags_by_scheme(&mesh, BoundaryInterpolation::None) {
                assert_eq!(stored, [[true, true], [true, true], [false; 2], [false; 2]]);
            }
            for r in refiners(&mesh, 1, true) {
                let level = r.internal_level(0).unwrap();
                assert_eq!(level.vertex_tag(0).rule(), Rule::Dart);
                assert!(level.vertex_tag(0).semi_sharp_edges());
                assert_eq!(level.vertex_tag(10).rule(), Rule::Corner);
                assert!(level.vertex_tag(10).semi_sharp());
                assert!(
                    level
                        .edge_tag(level.find_edge(0, 1).unwrap() as usize)
                        .semi_sharp()
                );
            }
            // An infinitely sharp crease (darts at its ends) stays.
            mesh.add_crease(0, 1, crate::rules::SHARPNESS_INFINITE);
            for (full, stored) in stored_tags_by_scheme(&mesh, BoundaryInterpolation::None) {
                assert_eq!(
                    stored,
                    [[true, true], [true, true], [true, true], [full, true]]
                );
            }
        }
    }

    /// The values above 0.
    fn sharp(values: &[f32]) -> Vec<f32> {
        values.iter().copied().filter(|&s| s > 0.0).collect()
    }

    #[test]
    fn vertex_edge_ends_are_kept_where_sharpness_decays_into_a_minimal_level() {
        // A crease of 3 is still 1 at level 2 and decays while level 3 is
        // built (minimal): level 2 keeps which end of its edges each vertex
        // is, and the positions equal those of a full refinement.
        for mut mesh in [shapes::torus(6, 5), shapes::torus_triangles(6, 5)] {
            mesh.add_crease(0, 1, 3.0);
            mesh.add_corner(10, 2.5);
            let base = mesh.flat_positions::<f64>();
            let minimal = refiners(&mesh, 3, false);
            let full = refiners(&mesh, 3, true);
            for (m, f) in minimal.iter().zip(&full) {
                let level2 = m.internal_level(2).unwrap();
                assert_eq!(
                    level2.vertex_edge_local.len(),
                    level2.vertex_edges.members.len()
                );
                assert!(!level2.has_local_indices());
                assert_eq!(
                    m.interpolate_all(3, &base).unwrap(),
                    f.interpolate_all(3, &base).unwrap()
                );
            }
        }
    }

    #[test]
    fn the_level_before_a_minimal_last_level_keeps_no_face_local_indices() {
        for mesh in [shapes::torus(6, 4), shapes::torus_triangles(6, 4)] {
            for full in [false, true] {
                for r in refiners(&mesh, 3, full) {
                    let kept: Vec<bool> = (0..=3)
                        .map(|l| r.internal_level(l).unwrap().has_local_indices())
                        .collect();
                    // Smooth meshes: level 2 keeps its vertex-edge ends
                    // only if something reads them (a full level 3).
                    let level2 = r.internal_level(2).unwrap();
                    assert_eq!(level2.vertex_edge_local.is_empty(), !full);
                    if full {
                        assert_eq!(kept, [true; 4]);
                    } else {
                        // Level 3 is minimal: nothing to keep, trivially true.
                        assert_eq!(kept, [true, true, false, true]);
                        assert!(level2.vertex_face_local.is_empty());
                        assert!(level2.edge_face_local.is_empty());
                    }
                }
            }
        }
    }

    /// The level before a minimal last level of a smooth closed mesh leaves
    /// out its vertex relations and edge-faces; derived from its parent,
    /// they are the ones a full level stores, element by element, in both
    /// vertex orders and under every scheme. With sharpness in the parent,
    /// they are stored.
    #[test]
    fn derived_relations_equal_the_stored_ones() {
        let mut buf = crate::refiner::HoodBuf::default();
        let meshes = [
            shapes::torus(6, 5),
            shapes::torus_mixed(6, 4),
            shapes::torus_triangles(6, 5),
        ];
        let mut derived_levels = 0;
        for mesh in meshes {
            for &scheme in mesh.applicable_schemes() {
                for faces_first in [false, true] {
                    for depth in 2..=3 {
                        let options = Options::default().with_scheme(scheme);
                        let uniform = UniformOptions::new(depth).faces_first(faces_first);
                        let mut minimal = Refiner::new(&mesh, &options).unwrap();
                        minimal.refine_uniform(uniform).unwrap();
                        let mut full = Refiner::new(&mesh, &options).unwrap();
                        full.refine_uniform(uniform.full_topology(true)).unwrap();
                        let l = depth as usize - 1;
                        let (derived, stored) = (&minimal.levels[l], &full.levels[l]);
                        assert!(derived.derived_relations, "{scheme:?} L{depth}");
                        assert!(derived.vertex_faces.is_empty() && derived.vertex_edges.is_empty());
                        assert!(derived.has_full_topology());
                        assert!(!stored.derived_relations);
                        derived_levels += 1;
                        let triangles = scheme == crate::options::Scheme::Loop;
                        let (grand, r) = (&minimal.levels[l - 1], &minimal.refinements[l - 1]);
                        for v in 0..stored.vertex_count {
                            let (faces, edges) = minimal.vertex_hood(l, v, &mut buf);
                            assert_eq!(
                                faces,
                                stored.vertex_faces_of(v),
                                "{scheme:?} L{depth} v{v}"
                            );
                            assert_eq!(
                                edges,
                                stored.vertex_edges_of(v),
                                "{scheme:?} L{depth} v{v}"
                            );
                            // The kernel's form: faces and far ends, up to 8.
                            let (mut f, mut far) = ([0; 8], [0; 8]);
                            let n = super::refine::derive_smooth_hood(
                                grand, r, triangles, v, &mut f, &mut far,
                            )
                            .expect("valence up to 8");
                            assert_eq!(&f[..n], faces, "{scheme:?} L{depth} v{v}");
                            let fars: Vec<u32> = edges
                                .iter()
                                .map(|&e| stored.other_vertex(e as usize, v as u32))
                                .collect();
                            assert_eq!(&far[..n], &fars[..], "{scheme:?} L{depth} v{v}");
                        }
                        // The public accessors, on the derived level.
                        let (faces, edges) = minimal.vertex_faces_and_edges(l as u32, 7).unwrap();
                        assert_eq!(
                            (&faces[..], &edges[..]),
                            (stored.vertex_faces_of(7), stored.vertex_edges_of(7))
                        );
                        for (e, &[a, b]) in stored.edge_vertices.iter().enumerate() {
                            assert_eq!(minimal.find_edge(l as u32, a, b).unwrap(), Some(e as u32));
                            assert_eq!(minimal.find_edge(l as u32, b, a).unwrap(), Some(e as u32));
                        }
                        assert!(derived.edge_faces.is_empty());
                        for e in 0..stored.edge_count() {
                            let faces = super::refine::derive_edge_faces(grand, r, triangles, e);
                            assert_eq!(
                                &faces[..],
                                stored.edge_faces_of(e),
                                "{scheme:?} L{depth} e{e}"
                            );
                            assert_eq!(minimal.edge_faces(l as u32, e).unwrap(), faces);
                            if triangles {
                                // The vertices opposite the edge in its faces.
                                let wings = match e.checked_sub(r.parent_corners) {
                                    Some(i) => {
                                        super::refine::derive_half_edge_wings(grand, r, i / 2)
                                            .map(|h| h[i % 2])
                                    }
                                    None => super::refine::derive_inner_edge_wings(grand, r, e),
                                };
                                let opposite = faces.map(|f| {
                                    crate::refiner::opposite_vertex(stored, f as usize, e)
                                });
                                assert_eq!(wings, Some(opposite), "{scheme:?} L{depth} e{e}");
                            }
                        }
                        assert!(minimal.edge_faces(l as u32, stored.edge_count()).is_err());
                        let count = stored.vertex_count;
                        assert!(minimal.vertex_faces_and_edges(l as u32, count).is_err());
                        assert!(minimal.find_edge(l as u32, 0, count as u32).is_err());
                    }
                }
            }
        }
        assert_eq!(derived_levels, 2 * 2 * (2 + 2 + 3));
        // A semi-sharp crease in the parent: the relations are stored.
        let mut mesh = shapes::torus(6, 5);
        mesh.add_crease(0, 1, 3.0);
        for r in refiners(&mesh, 3, false) {
            assert!(!r.levels[2].derived_relations);
            assert!(!r.levels[2].vertex_faces.is_empty());
        }
    }

    #[test]
    fn smooth_closed_levels_store_no_sharpness_or_holes() {
        for mesh in [shapes::torus(6, 5), shapes::torus_triangles(6, 5)] {
            for full in [false, true] {
                for r in refiners(&mesh, 3, full) {
                    assert_eq!(stored(&r), vec![[false; 3]; 4], "{:?}", r.options.scheme);
                    assert!(r.internal_level(3).unwrap().has_full_topology() == full);
                }
            }
        }
    }

    #[test]
    fn sharpness_is_stored_until_it_decays_to_zero() {
        for mut mesh in [shapes::torus(6, 5), shapes::torus_triangles(6, 5)] {
            mesh.add_crease(0, 1, 2.0);
            mesh.add_corner(10, 1.5);
            mesh.holes.push(5);
            for full in [false, true] {
                for r in refiners(&mesh, 3, full) {
                    let scheme = r.options.scheme;
                    // A crease of 2 decays to 1, then 0; a corner of 1.5 to
                    // 0.5, then 0; children of holes are holes.
                    let expected = [[true, true, true], [true, true, true], [false, false, true]];
                    assert_eq!(
                        stored(&r),
                        [expected[0], expected[1], expected[2], expected[2]],
                        "{scheme:?} full {full}"
                    );
                    let l1 = r.level(1).unwrap();
                    assert_eq!(sharp(&l1.edge_sharpness), [1.0, 1.0], "{scheme:?}");
                    assert_eq!(sharp(&l1.vertex_sharpness), [0.5], "{scheme:?}");
                }
            }
            // A minimal last level stores no edge sharpness; `Refiner::level`
            // recomputes it from the parent.
            for r in refiners(&mesh, 1, false) {
                assert!(r.internal_level(1).unwrap().edge_sharpness.is_empty());
                assert_eq!(sharp(&r.level(1).unwrap().edge_sharpness), [1.0, 1.0]);
            }
        }
    }
}
