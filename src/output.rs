//! What both engines return: the topology of each level ([`LevelTopology`],
//! [`LevelCounts`]), a whole uniform refinement ([`Refinement`]) and limit
//! values ([`Limit`], [`LimitData`]). The types are engine-neutral, so
//! [`crate::compare`] never cares which engine produced what.

use crate::options::{Options, UniformOptions};
use crate::real::{Precision, Real};
use crate::topology::Table;
use glam::DVec3;
use std::fmt;
use std::ops::{Deref, DerefMut};

/// The index OpenSubdiv gives a child that sparse refinement did not create
/// (`Vtr::INDEX_INVALID`, -1 as an unsigned index).
pub const INVALID_INDEX: u32 = u32::MAX;

/// How the components of one level map to those of the next (OpenSubdiv's
/// `Far::TopologyLevel` child queries and `GetFaceParentFace`). After uniform
/// refinement every child exists; after adaptive (sparse) refinement a child
/// that was not created is [`INVALID_INDEX`].
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct ChildMaps {
    /// The child faces of every parent face, one per corner, parallel to the
    /// parent's face-vertices (`GetFaceChildFaces`; Loop: four per triangle,
    /// the middle one last, in `face_child_face_offsets`' ranges).
    pub face_child_faces: Vec<u32>,
    /// Start of each parent face's children in `face_child_faces`, plus one
    /// final entry.
    pub face_child_face_offsets: Vec<u32>,
    /// The child edges inside every parent face (`GetFaceChildEdges`), one per
    /// corner (Loop: three), in `face_child_edge_offsets`' ranges.
    pub face_child_edges: Vec<u32>,
    /// Start of each parent face's interior child edges, plus one final entry.
    pub face_child_edge_offsets: Vec<u32>,
    /// The two child edges of every parent edge, the one at its end 0 first
    /// (`GetEdgeChildEdges`).
    pub edge_child_edges: Vec<[u32; 2]>,
    /// The child vertex of every parent face (`GetFaceChildVertex`; Loop:
    /// always invalid).
    pub face_child_vertex: Vec<u32>,
    /// The child vertex of every parent edge (`GetEdgeChildVertex`).
    pub edge_child_vertex: Vec<u32>,
    /// The child vertex of every parent vertex (`GetVertexChildVertex`).
    pub vertex_child_vertex: Vec<u32>,
    /// The parent face of every child face (`GetFaceParentFace`).
    pub child_face_parent_face: Vec<u32>,
}

/// Face-varying topology of one channel at one level.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FVarTopology {
    /// Number of distinct values in the channel at this level.
    pub value_count: usize,
    /// The value index of every face corner, parallel to [`LevelTopology::face_vertices`].
    pub face_values: Vec<u32>,
}

/// The topology of one level of a refinement, in OpenSubdiv's order.
///
/// OpenSubdiv builds only the face-vertex relation of the last level unless
/// it is refined with full topology, so `edge_vertices` is empty there;
/// `edge_count` and the sharpness tables are always present.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LevelTopology {
    /// Number of vertices.
    pub vertex_count: usize,
    /// Number of edges.
    pub edge_count: usize,
    /// Start of each face in `face_vertices`, plus one final entry.
    pub face_offsets: Vec<u32>,
    /// Vertex indices of all faces, concatenated.
    pub face_vertices: Vec<u32>,
    /// The two vertices of every edge (empty in a last level without full topology).
    pub edge_vertices: Vec<[u32; 2]>,
    /// Sharpness of every edge.
    pub edge_sharpness: Vec<f32>,
    /// Sharpness of every vertex.
    pub vertex_sharpness: Vec<f32>,
    /// Whether each face is a hole.
    pub face_holes: Vec<bool>,
    /// Face-varying topology of every channel.
    pub fvar: Vec<FVarTopology>,
}

impl LevelTopology {
    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.face_offsets.len().saturating_sub(1)
    }

    /// The vertices of face `f`.
    ///
    /// # Panics
    /// If `f >= face_count()`.
    pub fn face(&self, f: usize) -> &[u32] {
        &self.face_vertices[self.face_offsets[f] as usize..self.face_offsets[f + 1] as usize]
    }

    /// Iterates over the faces' vertex lists.
    pub fn faces(&self) -> impl Iterator<Item = &[u32]> + '_ {
        self.face_offsets
            .windows(2)
            .map(move |w| &self.face_vertices[w[0] as usize..w[1] as usize])
    }
}

/// Element counts of one level.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct LevelCounts {
    /// Vertices.
    pub vertices: usize,
    /// Edges.
    pub edges: usize,
    /// Faces.
    pub faces: usize,
    /// Face corners (face-vertex incidences).
    pub face_vertices: usize,
    /// Whether the level has all topological relations; `false` for a last
    /// level refined without full topology, which has no edge-vertex table.
    pub full_topology: bool,
}

/// Limit values and both tangents of one primvar (`width` components per
/// vertex) at the vertices of one level. Each buffer is a [`Values`]: it
/// dereferences to a slice, and a large one lives in memory advised for huge
/// pages that returns to a pool when dropped, so that evaluating the next
/// frame writes its limits without page faults.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LimitData<T: Real> {
    /// Limit values, `width` per vertex.
    pub positions: Values<T>,
    /// First tangents, `width` per vertex.
    pub du: Values<T>,
    /// Second tangents, `width` per vertex.
    pub dv: Values<T>,
}

/// Limit positions, tangents and face-varying values at the vertices of one level.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Limit {
    /// Limit position of every vertex.
    pub positions: Vec<DVec3>,
    /// First tangent (`du`) of every vertex.
    pub du: Vec<DVec3>,
    /// Second tangent (`dv`) of every vertex.
    pub dv: Vec<DVec3>,
    /// Limit values of every face-varying channel, flattened like [`crate::FVarChannel::values`].
    pub fvar_values: Vec<Vec<f64>>,
}

impl Limit {
    /// Unit normals `du × dv` (zero where the tangents are degenerate).
    pub fn normals(&self) -> Vec<DVec3> {
        self.du
            .iter()
            .zip(&self.dv)
            .map(|(a, b)| a.cross(*b).normalize_or_zero())
            .collect()
    }
}

/// A mesh refined uniformly: the topology and the interpolated data of every level.
#[derive(Debug, Clone, PartialEq)]
pub struct Refinement {
    /// The options the mesh was refined with.
    pub options: Options,
    /// The uniform refinement options.
    pub uniform: UniformOptions,
    /// The precision primvars were interpolated in.
    pub precision: Precision,
    /// Topology of levels `0..=uniform.level`.
    pub levels: Vec<LevelTopology>,
    /// Vertex positions of every level.
    pub positions: Vec<Vec<DVec3>>,
    /// Widths of the face-varying channels.
    pub fvar_widths: Vec<usize>,
    /// Face-varying values of every level and channel: `fvar_values[level][channel]`.
    pub fvar_values: Vec<Vec<Vec<f64>>>,
    /// Limit data at the last level, when it was asked for.
    pub limit: Option<Limit>,
}

impl Refinement {
    /// The topology of the last level.
    pub fn last_level(&self) -> &LevelTopology {
        self.levels
            .last()
            .expect("a refinement has at least level 0")
    }

    /// The positions of the last level.
    pub fn last_positions(&self) -> &[DVec3] {
        self.positions.last().map(Vec::as_slice).unwrap_or(&[])
    }

    /// The face-varying values of `channel` at the last level.
    pub fn last_fvar(&self, channel: usize) -> Option<&[f64]> {
        self.fvar_values.last()?.get(channel).map(Vec::as_slice)
    }
}

/// A flat buffer of values (`width` per vertex) computed by the native
/// engine: [`Refiner::interpolate_all`](crate::refiner::Refiner::interpolate_all),
/// [`Refiner::interpolate_last`](crate::refiner::Refiner::interpolate_last) and
/// [`refine_last`](crate::refiner::refine_last) return it. It dereferences to
/// a slice and compares equal to slices and vectors.
///
/// Buffers of 2 MiB and more live in memory advised for transparent huge
/// pages; when dropped, that memory goes to a pool (256 MiB at most) that
/// the next refinement reuses without page faults, as do smaller buffers
/// from 64 KiB up (heap vectors, 128 MiB at most), and
/// [`release_buffer_pool`] hands it back to the system. `SUBDIV_HUGE_PAGES=0`
/// makes every buffer an ordinary heap vector.
#[derive(Clone, Default, PartialEq)]
pub struct Values<T: Real>(pub(crate) Table<T>);

impl<T: Real> Values<T> {
    /// The values as a slice.
    pub fn as_slice(&self) -> &[T] {
        &self.0
    }

    /// The values in a vector (a copy when the buffer is a mapped one).
    pub fn into_vec(self) -> Vec<T> {
        self.0.to_vec()
    }
}

impl<T: Real> Deref for Values<T> {
    type Target = [T];
    fn deref(&self) -> &[T] {
        &self.0
    }
}

impl<T: Real> DerefMut for Values<T> {
    fn deref_mut(&mut self) -> &mut [T] {
        &mut self.0
    }
}

impl<'a, T: Real> IntoIterator for &'a Values<T> {
    type Item = &'a T;
    type IntoIter = std::slice::Iter<'a, T>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

impl<T: Real> fmt::Debug for Values<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

impl<T: Real> From<Vec<T>> for Values<T> {
    fn from(values: Vec<T>) -> Self {
        Values(Table::from(values))
    }
}

impl<T: Real> PartialEq<[T]> for Values<T> {
    fn eq(&self, other: &[T]) -> bool {
        self.as_slice() == other
    }
}

impl<T: Real> PartialEq<Vec<T>> for Values<T> {
    fn eq(&self, other: &Vec<T>) -> bool {
        self.as_slice() == other.as_slice()
    }
}

impl<T: Real> PartialEq<Values<T>> for Vec<T> {
    fn eq(&self, other: &Values<T>) -> bool {
        self.as_slice() == other.as_slice()
    }
}

/// Hands the memory of dropped [`Values`] buffers (and of the native
/// engine's own large tables) back to the system; returns the bytes released.
///
/// ```
/// use subdiv::{refiner::Refiner, release_buffer_pool, shapes, Options, UniformOptions};
/// let mut r = Refiner::new(&shapes::torus(64, 64), &Options::default())?;
/// r.refine_uniform(UniformOptions::new(3))?;
/// let base: Vec<f64> = shapes::torus(64, 64).flat_positions();
/// drop(r.interpolate_last(3, &base)?); // 6 MiB of f64: its map goes to the pool
/// let maps_off = std::env::var("SUBDIV_HUGE_PAGES").is_ok_and(|v| v == "0");
/// assert!(release_buffer_pool() >= 6 << 20 || maps_off);
/// assert_eq!(release_buffer_pool(), 0); // nothing left to release
/// # Ok::<(), subdiv::Error>(())
/// ```
pub fn release_buffer_pool() -> usize {
    crate::topology::release_table_pool()
}

/// The relations OpenSubdiv stores for one level with full topology
/// (`Far::TopologyLevel`'s relation queries and its per-vertex and per-edge
/// tags), in OpenSubdiv's order. A uniform last level refined without full
/// topology has none of them; every adaptive level has all of them.
///
/// Faces are indexed as in [`LevelTopology`]: `face_edges` is parallel to
/// [`LevelTopology::face_vertices`] and shares its `face_offsets`.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct LevelRelations {
    /// The edges of every face, edge `j` from the face's vertex `j` to
    /// vertex `j + 1`, parallel to the face-vertices (`GetFaceEdges`).
    pub face_edges: Vec<u32>,
    /// The faces of every edge, concatenated, in `edge_face_offsets`' ranges
    /// (`GetEdgeFaces`).
    pub edge_faces: Vec<u32>,
    /// Start of each edge's faces in `edge_faces`, plus one final entry.
    pub edge_face_offsets: Vec<u32>,
    /// For every entry of `edge_faces`, the position of the edge in that
    /// face's edges (`GetEdgeFaceLocalIndices`).
    pub edge_face_local: Vec<u16>,
    /// The faces around every vertex, concatenated, in
    /// `vertex_face_offsets`' ranges (`GetVertexFaces`).
    pub vertex_faces: Vec<u32>,
    /// Start of each vertex's faces in `vertex_faces`, plus one final entry.
    pub vertex_face_offsets: Vec<u32>,
    /// For every entry of `vertex_faces`, the position of the vertex in that
    /// face's vertices (`GetVertexFaceLocalIndices`).
    pub vertex_face_local: Vec<u16>,
    /// The edges around every vertex, concatenated, in
    /// `vertex_edge_offsets`' ranges (`GetVertexEdges`).
    pub vertex_edges: Vec<u32>,
    /// Start of each vertex's edges in `vertex_edges`, plus one final entry.
    pub vertex_edge_offsets: Vec<u32>,
    /// For every entry of `vertex_edges`, which end of that edge the vertex
    /// is, 0 or 1 (`GetVertexEdgeLocalIndices`).
    pub vertex_edge_local: Vec<u16>,
    /// The subdivision rule of every vertex (`GetVertexRule`).
    pub vertex_rules: Vec<crate::rules::Rule>,
    /// Whether each vertex lies on a boundary (`IsVertexBoundary`).
    pub vertex_boundary: Vec<bool>,
    /// Whether each vertex has exactly one face (`IsVertexCorner`).
    pub vertex_corner: Vec<bool>,
    /// Whether each vertex has a regular valence for the scheme, or is a
    /// corner (`IsVertexValenceRegular`: not extraordinary).
    pub vertex_valence_regular: Vec<bool>,
    /// Whether each vertex is non-manifold (`IsVertexNonManifold`).
    pub vertex_non_manifold: Vec<bool>,
    /// Whether each vertex is infinitely sharp (`IsVertexInfSharp`).
    pub vertex_inf_sharp: Vec<bool>,
    /// Whether each vertex is semi-sharp (`IsVertexSemiSharp`).
    pub vertex_semi_sharp: Vec<bool>,
    /// Whether each edge is non-manifold (`IsEdgeNonManifold`).
    pub edge_non_manifold: Vec<bool>,
    /// Whether each edge lies on a boundary (`IsEdgeBoundary`).
    pub edge_boundary: Vec<bool>,
    /// Whether each edge is infinitely sharp, boundary edges included
    /// (`IsEdgeInfSharp`).
    pub edge_inf_sharp: Vec<bool>,
    /// Whether each edge is semi-sharp (`IsEdgeSemiSharp`).
    pub edge_semi_sharp: Vec<bool>,
}
