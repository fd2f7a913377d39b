//! The topology of one refinement level, as both engines report it.

/// Face-varying topology of one channel at one level.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FVarLevel {
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
    pub fvar: Vec<FVarLevel>,
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
