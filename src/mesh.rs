//! The base mesh: positions, polygon faces, sharpness tags, holes and
//! face-varying channels, with validation that names every problem precisely.

use glam::DVec3;
use thiserror::Error;

/// Sharpness at or above which OpenSubdiv treats an edge or vertex as
/// infinitely sharp (`Sdc::Crease::SHARPNESS_INFINITE`).
pub const SHARPNESS_INFINITE: f32 = 10.0;

/// The largest number of vertices in one face (and the largest valence)
/// OpenSubdiv supports.
pub const MAX_VALENCE: usize = 65535;

/// A sharpened edge between two vertices.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crease {
    /// The two end vertices of the edge (order does not matter).
    pub vertices: [u32; 2],
    /// Sharpness: `<= 0` smooth, `>= 10` infinitely sharp.
    pub sharpness: f32,
}

/// A sharpened vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Corner {
    /// The vertex index.
    pub vertex: u32,
    /// Sharpness: `<= 0` smooth, `>= 10` infinitely sharp.
    pub sharpness: f32,
}

/// One face-varying channel (such as UVs): its own values and, for every face
/// corner of the mesh, the index of the value that corner uses.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FVarChannel {
    /// Number of `f64` components per value (2 for UVs).
    pub width: usize,
    /// The values, `width` components each, flattened.
    pub values: Vec<f64>,
    /// One value index per face corner, parallel to [`Mesh::face_vertices`].
    pub indices: Vec<u32>,
}

impl FVarChannel {
    /// Number of values in the channel.
    pub fn value_count(&self) -> usize {
        self.values.len().checked_div(self.width).unwrap_or(0)
    }

    /// The values in `T` (rounded to nearest in `f32`), the base data of
    /// [`Refiner::interpolate_face_varying`](crate::refiner::Refiner::interpolate_face_varying).
    pub fn values_as<T: crate::Real>(&self) -> Vec<T> {
        crate::alloc::collect_n(
            self.values.len(),
            self.values.iter().map(|&v| T::from_f64(v)),
        )
    }
}

/// A polygon mesh with OpenSubdiv's tags.
///
/// Faces are stored flat: face `f` uses `face_vertices[face_offsets[f]..face_offsets[f + 1]]`,
/// in counter-clockwise order.
///
/// ```
/// use subdiv::Mesh;
/// use glam::DVec3;
/// let mut mesh = Mesh::from_faces(
///     vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
///     &[&[0, 1, 2, 3]],
/// );
/// mesh.add_crease(0, 1, 2.5);
/// assert_eq!(mesh.face_count(), 1);
/// assert!(mesh.validate().unwrap().warnings.is_empty());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Start of each face in `face_vertices`, plus one final entry: `face_count() + 1` values.
    pub face_offsets: Vec<u32>,
    /// Vertex indices of all faces, concatenated.
    pub face_vertices: Vec<u32>,
    /// Sharpened edges.
    pub creases: Vec<Crease>,
    /// Sharpened vertices.
    pub corners: Vec<Corner>,
    /// Indices of faces that are holes.
    pub holes: Vec<u32>,
    /// Face-varying channels; channel 0 is the UV set read from `vt`.
    pub fvar_channels: Vec<FVarChannel>,
    /// The faces are listed clockwise (USD's `orientation = "leftHanded"`),
    /// as OpenSubdiv's `Far::TopologyDescriptor::isLeftHanded`: both engines
    /// then read each face (and its face-varying indices) from its first
    /// corner backwards, so refined faces come out counter-clockwise.
    /// [`Mesh::right_handed`] gives that reading as a mesh of its own.
    pub left_handed: bool,
}

impl Default for Mesh {
    fn default() -> Self {
        Mesh {
            positions: Vec::new(),
            face_offsets: vec![0],
            face_vertices: Vec::new(),
            creases: Vec::new(),
            corners: Vec::new(),
            holes: Vec::new(),
            fvar_channels: Vec::new(),
            left_handed: false,
        }
    }
}

/// A problem that makes a mesh unusable.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum MeshError {
    /// `face_offsets` is empty, does not start at 0, decreases, or does not end at `face_vertices.len()`.
    #[error("face offsets are malformed: {0}")]
    BadOffsets(String),
    /// A face refers to a vertex that does not exist.
    #[error(
        "face {face} corner {corner}: vertex index {index} is out of range (the mesh has {count} vertices)"
    )]
    VertexOutOfRange {
        /// Face index.
        face: usize,
        /// Corner within the face.
        corner: usize,
        /// The offending vertex index.
        index: u32,
        /// Number of vertices.
        count: usize,
    },
    /// A face has fewer than 3 vertices.
    #[error("face {face} has {size} vertices; a face needs at least 3")]
    FaceTooSmall {
        /// Face index.
        face: usize,
        /// Its vertex count.
        size: usize,
    },
    /// A face has more vertices than OpenSubdiv supports.
    #[error("face {face} has {size} vertices; at most {MAX_VALENCE} are supported")]
    FaceTooLarge {
        /// Face index.
        face: usize,
        /// Its vertex count.
        size: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate ({value})")]
    NonFiniteCoordinate {
        /// Vertex index.
        vertex: usize,
        /// The offending value.
        value: f64,
    },
    /// A crease names a vertex that does not exist.
    #[error("crease {crease}: vertex {vertex} does not exist (the mesh has {count} vertices)")]
    CreaseVertexOutOfRange {
        /// Crease index.
        crease: usize,
        /// The offending vertex index.
        vertex: u32,
        /// Number of vertices.
        count: usize,
    },
    /// A corner names a vertex that does not exist.
    #[error("corner {corner}: vertex {vertex} does not exist (the mesh has {count} vertices)")]
    CornerVertexOutOfRange {
        /// Corner index.
        corner: usize,
        /// The offending vertex index.
        vertex: u32,
        /// Number of vertices.
        count: usize,
    },
    /// A hole names a face that does not exist.
    #[error("hole {hole}: face {face} does not exist (the mesh has {count} faces)")]
    HoleOutOfRange {
        /// Hole index.
        hole: usize,
        /// The offending face index.
        face: u32,
        /// Number of faces.
        count: usize,
    },
    /// A sharpness is NaN or infinite.
    #[error("{what}: sharpness {value} is not a finite number")]
    BadSharpness {
        /// Which tag ("crease 3", "corner 0").
        what: String,
        /// The offending value.
        value: f32,
    },
    /// A face-varying channel is inconsistent with the mesh.
    #[error("face-varying channel {channel}: {problem}")]
    BadFVarChannel {
        /// Channel index.
        channel: usize,
        /// What is wrong.
        problem: String,
    },
    /// A crease joins two vertices that share no edge (an error only in strict mode).
    #[error("crease {crease}: vertices {v0} and {v1} share no edge")]
    CreaseWithoutEdge {
        /// Crease index.
        crease: usize,
        /// First vertex.
        v0: u32,
        /// Second vertex.
        v1: u32,
    },
    /// The mesh is larger than 32-bit indices can address.
    #[error("the mesh is too large: {0}")]
    TooLarge(String),
}

/// A questionable but accepted feature of a mesh, reported by [`Mesh::validate`].
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum MeshWarning {
    /// A crease between two vertices that share no edge; OpenSubdiv ignores it.
    CreaseWithoutEdge {
        /// Crease index.
        crease: usize,
        /// First vertex.
        v0: u32,
        /// Second vertex.
        v1: u32,
    },
}

impl std::fmt::Display for MeshWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            MeshWarning::CreaseWithoutEdge { crease, v0, v1 } => write!(
                f,
                "crease {crease}: vertices {v0} and {v1} share no edge; the crease is ignored"
            ),
        }
    }
}

impl MeshWarning {
    /// The error this warning becomes in strict mode.
    pub fn into_error(self) -> MeshError {
        match self {
            MeshWarning::CreaseWithoutEdge { crease, v0, v1 } => {
                MeshError::CreaseWithoutEdge { crease, v0, v1 }
            }
        }
    }
}

/// The outcome of a successful validation.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Validation {
    /// Accepted oddities, in the order found.
    pub warnings: Vec<MeshWarning>,
}

impl Mesh {
    /// A mesh from positions and a list of faces, with no tags.
    pub fn from_faces(positions: Vec<DVec3>, faces: &[&[u32]]) -> Mesh {
        let mut mesh = Mesh {
            positions,
            ..Mesh::default()
        };
        for face in faces {
            mesh.add_face(face);
        }
        mesh
    }

    /// Appends a face.
    pub fn add_face(&mut self, vertices: &[u32]) {
        self.face_vertices.extend_from_slice(vertices);
        self.face_offsets.push(self.face_vertices.len() as u32);
    }

    /// Adds a crease on the edge `v0`-`v1`.
    pub fn add_crease(&mut self, v0: u32, v1: u32, sharpness: f32) {
        self.creases.push(Crease {
            vertices: [v0, v1],
            sharpness,
        });
    }

    /// Adds a sharp vertex.
    pub fn add_corner(&mut self, vertex: u32, sharpness: f32) {
        self.corners.push(Corner { vertex, sharpness });
    }

    /// The positions as flat `x, y, z` values in `T` (rounded to the nearest
    /// `f32` for `f32`): the vertex data the refiners interpolate.
    ///
    /// ```
    /// let cube = subdiv::shapes::cube();
    /// let flat: Vec<f32> = cube.flat_positions();
    /// assert_eq!(flat.len(), 3 * cube.vertex_count());
    /// assert_eq!(flat[..3], [cube.positions[0].x as f32, cube.positions[0].y as f32, cube.positions[0].z as f32]);
    /// ```
    pub fn flat_positions<T: crate::Real>(&self) -> Vec<T> {
        self.positions
            .iter()
            .flat_map(|p| p.to_array())
            .map(T::from_f64)
            .collect()
    }

    /// [`Mesh::flat_positions`] without a copy when `T` is `f64` (a `DVec3`
    /// is three `f64`s: the positions are borrowed as they are); converted
    /// into a new vector for `f32`. What a refinement that only reads its
    /// base values takes, instead of a second copy of the base.
    ///
    /// ```
    /// let cube = subdiv::shapes::cube();
    /// let flat = cube.positions_as::<f64>();
    /// assert!(matches!(flat, std::borrow::Cow::Borrowed(_)));
    /// assert_eq!(*flat, *cube.flat_positions::<f64>());
    /// assert_eq!(*cube.positions_as::<f32>(), *cube.flat_positions::<f32>());
    /// ```
    pub fn positions_as<T: crate::Real>(&self) -> std::borrow::Cow<'_, [T]> {
        // Only `f64` shares the positions' layout (a cast to `f32` would
        // reinterpret their bits).
        if T::PRECISION == crate::Precision::F64
            && let Ok(flat) = bytemuck::try_cast_slice::<DVec3, T>(&self.positions)
        {
            return std::borrow::Cow::Borrowed(flat);
        }
        std::borrow::Cow::Owned(self.flat_positions())
    }

    /// [`Mesh::positions_as`], consuming the mesh: for `f64` the positions'
    /// own vector, cast without a copy; for `f32` a converted copy. The
    /// rest of the mesh is dropped.
    ///
    /// ```
    /// let cube = subdiv::shapes::cube();
    /// let flat = cube.flat_positions::<f64>();
    /// assert_eq!(cube.clone().into_flat_positions::<f64>(), flat);
    /// assert_eq!(cube.clone().into_flat_positions::<f32>(), cube.flat_positions::<f32>());
    /// ```
    pub fn into_flat_positions<T: crate::Real>(mut self) -> Vec<T> {
        if T::PRECISION == crate::Precision::F64 {
            match bytemuck::allocation::try_cast_vec::<DVec3, T>(std::mem::take(
                &mut self.positions,
            )) {
                Ok(flat) => return flat,
                Err((_, positions)) => self.positions = positions,
            }
        }
        self.flat_positions()
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.face_offsets.len().saturating_sub(1)
    }

    /// The vertex indices of face `f`.
    ///
    /// # Panics
    /// If `f >= face_count()` or the offsets are malformed (see [`Mesh::validate`]).
    pub fn face(&self, f: usize) -> &[u32] {
        &self.face_vertices[self.face_offsets[f] as usize..self.face_offsets[f + 1] as usize]
    }

    /// The schemes that can refine this mesh: Catmull-Clark and bilinear
    /// always, Loop too when every face is a triangle.
    ///
    /// ```
    /// use subdiv::{shapes, Scheme};
    /// assert_eq!(shapes::cube().applicable_schemes(), &[Scheme::Catmark, Scheme::Bilinear]);
    /// let tris = shapes::triangulate(&shapes::cube());
    /// assert!(tris.applicable_schemes().contains(&Scheme::Loop));
    /// ```
    pub fn applicable_schemes(&self) -> &'static [crate::options::Scheme] {
        use crate::options::Scheme;
        if self.faces().all(|f| f.len() == 3) {
            &[Scheme::Catmark, Scheme::Bilinear, Scheme::Loop]
        } else {
            &[Scheme::Catmark, Scheme::Bilinear]
        }
    }

    /// The mesh as the engines read it: itself when it is right-handed; when
    /// [`Mesh::left_handed`], a copy whose faces keep their first corner and
    /// list the others in reverse — OpenSubdiv's `isLeftHanded` reading of
    /// face vertices and face-varying indices alike — marked right-handed.
    /// Faces whose offsets are malformed are left as they are (validation
    /// names them).
    ///
    /// ```
    /// use subdiv::Mesh;
    /// use glam::DVec3;
    /// let mut mesh = Mesh::from_faces(vec![DVec3::ZERO; 4], &[&[0, 1, 2, 3]]);
    /// mesh.left_handed = true;
    /// assert_eq!(mesh.right_handed().face(0), &[0, 3, 2, 1]);
    /// ```
    pub fn right_handed(&self) -> std::borrow::Cow<'_, Mesh> {
        if !self.left_handed {
            return std::borrow::Cow::Borrowed(self);
        }
        // The large arrays are copied fallibly: under `Refiner::new`'s guard
        // a mesh too large to copy is `Error::OutOfMemory`, not an abort.
        use crate::alloc::copied;
        let mut mesh = Mesh {
            positions: copied(&self.positions),
            face_offsets: copied(&self.face_offsets),
            face_vertices: copied(&self.face_vertices),
            creases: self.creases.clone(),
            corners: self.corners.clone(),
            holes: self.holes.clone(),
            fvar_channels: self
                .fvar_channels
                .iter()
                .map(|c| FVarChannel {
                    width: c.width,
                    values: copied(&c.values),
                    indices: copied(&c.indices),
                })
                .collect(),
            left_handed: false,
        };
        let reverse = |list: &mut [u32]| {
            for w in self.face_offsets.windows(2) {
                let face = list.get_mut(w[0] as usize..w[1] as usize);
                if let Some(rest) = face.and_then(|face| face.get_mut(1..)) {
                    rest.reverse();
                }
            }
        };
        reverse(&mut mesh.face_vertices);
        for channel in &mut mesh.fvar_channels {
            reverse(&mut channel.indices);
        }
        std::borrow::Cow::Owned(mesh)
    }

    /// Iterates over the faces' vertex lists (stops early if the offsets are malformed).
    pub fn faces(&self) -> impl Iterator<Item = &[u32]> + '_ {
        self.face_offsets.windows(2).map_while(move |w| {
            let (a, b) = (w[0] as usize, w[1] as usize);
            self.face_vertices.get(a..b)
        })
    }

    /// Number of vertices of every face, in face order.
    pub fn face_sizes(&self) -> Vec<u32> {
        self.face_offsets
            .windows(2)
            .map(|w| w[1].wrapping_sub(w[0]))
            .collect()
    }

    /// The axis-aligned bounding box `(min, max)` of the positions, or `None` when empty.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let first = *self.positions.first()?;
        Some(
            self.positions
                .iter()
                .fold((first, first), |(lo, hi), p| (lo.min(*p), hi.max(*p))),
        )
    }

    /// Checks every index, size and number; returns the warnings of an acceptable mesh.
    pub fn validate(&self) -> Result<Validation, MeshError> {
        let nv = self.positions.len();
        if nv > i32::MAX as usize || self.face_vertices.len() > i32::MAX as usize {
            return Err(MeshError::TooLarge(format!(
                "{} vertices and {} face corners; OpenSubdiv indexes with 32-bit signed integers",
                nv,
                self.face_vertices.len()
            )));
        }
        // Each check first as one pass without an early exit (vectorised:
        // on a valid mesh, all there is), then, only when it fails, the
        // search for the first offender, whose error is the one reported.
        let finite = self.positions.iter().fold(true, |ok, p| ok & p.is_finite());
        if !finite {
            self.first_non_finite_position()?;
        }
        self.validate_offsets()?;
        let (smallest, largest) =
            self.face_offsets
                .windows(2)
                .fold((u32::MAX, 0), |(lo, hi), w| {
                    let size = w[1] - w[0];
                    (lo.min(size), hi.max(size))
                });
        let top = self.face_vertices.iter().fold(0, |m, &v| m.max(v));
        let faces_valid = (self.face_vertices.is_empty() || (top as usize) < nv)
            && (self.face_offsets.len() < 2 || (smallest >= 3 && largest as usize <= MAX_VALENCE));
        if !faces_valid {
            self.first_bad_face()?;
        }
        for (i, c) in self.creases.iter().enumerate() {
            if let Some(&vertex) = c.vertices.iter().find(|&&v| v as usize >= nv) {
                return Err(MeshError::CreaseVertexOutOfRange {
                    crease: i,
                    vertex,
                    count: nv,
                });
            }
            if !c.sharpness.is_finite() {
                return Err(MeshError::BadSharpness {
                    what: format!("crease {i}"),
                    value: c.sharpness,
                });
            }
        }
        for (i, c) in self.corners.iter().enumerate() {
            if c.vertex as usize >= nv {
                return Err(MeshError::CornerVertexOutOfRange {
                    corner: i,
                    vertex: c.vertex,
                    count: nv,
                });
            }
            if !c.sharpness.is_finite() {
                return Err(MeshError::BadSharpness {
                    what: format!("corner {i}"),
                    value: c.sharpness,
                });
            }
        }
        let nf = self.face_count();
        for (hole, &face) in self.holes.iter().enumerate() {
            if face as usize >= nf {
                return Err(MeshError::HoleOutOfRange {
                    hole,
                    face,
                    count: nf,
                });
            }
        }
        for (channel, ch) in self.fvar_channels.iter().enumerate() {
            self.validate_channel(channel, ch)?;
        }
        Ok(Validation {
            warnings: self.crease_warnings(),
        })
    }

    /// Validates, turning every warning into an error.
    pub fn validate_strict(&self) -> Result<Validation, MeshError> {
        let v = self.validate()?;
        match v.warnings.into_iter().next() {
            Some(w) => Err(w.into_error()),
            None => Ok(Validation::default()),
        }
    }

    fn validate_offsets(&self) -> Result<(), MeshError> {
        let off = &self.face_offsets;
        if off.first() != Some(&0) {
            return Err(MeshError::BadOffsets("the first offset must be 0".into()));
        }
        if let Some(i) = off.windows(2).position(|w| w[1] < w[0]) {
            return Err(MeshError::BadOffsets(format!(
                "offset {} ({}) is smaller than offset {} ({})",
                i + 1,
                off[i + 1],
                i,
                off[i]
            )));
        }
        let last = *off.last().unwrap_or(&0) as usize;
        if last != self.face_vertices.len() {
            return Err(MeshError::BadOffsets(format!(
                "the last offset is {last} but there are {} face vertices",
                self.face_vertices.len()
            )));
        }
        Ok(())
    }

    /// The error of the first vertex with a coordinate that is not finite
    /// (the search `validate` runs once its whole-table pass found one).
    fn first_non_finite_position(&self) -> Result<(), MeshError> {
        for (vertex, p) in self.positions.iter().enumerate() {
            if let Some(&value) = p.to_array().iter().find(|c| !c.is_finite()) {
                return Err(MeshError::NonFiniteCoordinate { vertex, value });
            }
        }
        Ok(())
    }

    /// The error of the first face, in face order, that is too small, too
    /// large or has a vertex out of range (the search `validate` runs once
    /// its whole-table passes found one).
    fn first_bad_face(&self) -> Result<(), MeshError> {
        let nv = self.positions.len();
        for (face, verts) in self.faces().enumerate() {
            if verts.len() < 3 {
                return Err(MeshError::FaceTooSmall {
                    face,
                    size: verts.len(),
                });
            }
            if verts.len() > MAX_VALENCE {
                return Err(MeshError::FaceTooLarge {
                    face,
                    size: verts.len(),
                });
            }
            if let Some((corner, &index)) =
                verts.iter().enumerate().find(|&(_, &v)| v as usize >= nv)
            {
                return Err(MeshError::VertexOutOfRange {
                    face,
                    corner,
                    index,
                    count: nv,
                });
            }
        }
        Ok(())
    }

    fn validate_channel(&self, channel: usize, ch: &FVarChannel) -> Result<(), MeshError> {
        let bad = |problem: String| MeshError::BadFVarChannel { channel, problem };
        if ch.width == 0 {
            return Err(bad("width is 0".into()));
        }
        if !ch.values.len().is_multiple_of(ch.width) {
            return Err(bad(format!(
                "{} components is not a multiple of the width {}",
                ch.values.len(),
                ch.width
            )));
        }
        if ch.indices.len() != self.face_vertices.len() {
            return Err(bad(format!(
                "{} value indices for {} face corners",
                ch.indices.len(),
                self.face_vertices.len()
            )));
        }
        // As in `validate`: one vectorised pass each, the search for the
        // first offender only when it fails.
        let finite = ch.values.iter().fold(true, |ok, v| ok & v.is_finite());
        if !finite && let Some(i) = ch.values.iter().position(|v| !v.is_finite()) {
            return Err(bad(format!(
                "value {} has a non-finite component ({})",
                i / ch.width,
                ch.values[i]
            )));
        }
        let count = ch.value_count();
        let top = ch.indices.iter().fold(0, |m, &x| m.max(x));
        let in_range = ch.indices.is_empty() || (top as usize) < count;
        if !in_range {
            for (face, w) in self.face_offsets.windows(2).enumerate() {
                for corner in 0..(w[1] - w[0]) as usize {
                    let index = ch.indices[w[0] as usize + corner];
                    if index as usize >= count {
                        return Err(bad(format!(
                            "face {face} corner {corner}: value index {index} is out of range (the channel has {count} values)"
                        )));
                    }
                }
            }
        }
        Ok(())
    }

    fn crease_warnings(&self) -> Vec<MeshWarning> {
        if self.creases.is_empty() {
            return Vec::new();
        }
        // One pass over the faces' edges that hashes nothing: only an edge
        // whose two ends are both crease ends is looked up, by binary search
        // among the (few) creases' sorted vertex pairs.
        let key = |a: u32, b: u32| if a < b { (a, b) } else { (b, a) };
        let mut keys: Vec<(u32, u32)> = self
            .creases
            .iter()
            .map(|c| key(c.vertices[0], c.vertices[1]))
            .collect();
        keys.sort_unstable();
        keys.dedup();
        let mut end = vec![false; self.positions.len()];
        for &(a, b) in &keys {
            for v in [a, b] {
                if let Some(e) = end.get_mut(v as usize) {
                    *e = true;
                }
            }
        }
        let is_end = |v: u32| end.get(v as usize).copied().unwrap_or(false);
        let mut found = vec![false; keys.len()];
        for f in self.faces() {
            let Some(&(mut prev)) = f.last() else {
                continue;
            };
            for &v in f {
                if is_end(v)
                    && is_end(prev)
                    && let Ok(i) = keys.binary_search(&key(prev, v))
                {
                    found[i] = true;
                }
                prev = v;
            }
        }
        self.creases
            .iter()
            .enumerate()
            .filter(|(_, c)| {
                let k = key(c.vertices[0], c.vertices[1]);
                keys.binary_search(&k).is_ok_and(|i| !found[i])
            })
            .map(|(crease, c)| MeshWarning::CreaseWithoutEdge {
                crease,
                v0: c.vertices[0],
                v1: c.vertices[1],
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad() -> Mesh {
        Mesh::from_faces(
            vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
            &[&[0, 1, 2, 3]],
        )
    }

    #[test]
    fn valid_quad() {
        assert_eq!(quad().validate(), Ok(Validation::default()));
    }

    #[test]
    fn errors_are_precise() {
        let mut m = quad();
        m.face_vertices[2] = 7;
        assert_eq!(
            m.validate(),
            Err(MeshError::VertexOutOfRange {
                face: 0,
                corner: 2,
                index: 7,
                count: 4
            })
        );
        let mut m = quad();
        m.add_face(&[0, 1]);
        assert_eq!(
            m.validate(),
            Err(MeshError::FaceTooSmall { face: 1, size: 2 })
        );
        let mut m = quad();
        m.positions[3].y = f64::NAN;
        assert!(matches!(
            m.validate(),
            Err(MeshError::NonFiniteCoordinate { vertex: 3, .. })
        ));
        let mut m = quad();
        m.add_corner(9, 1.0);
        assert_eq!(
            m.validate(),
            Err(MeshError::CornerVertexOutOfRange {
                corner: 0,
                vertex: 9,
                count: 4
            })
        );
        let mut m = quad();
        m.holes.push(1);
        assert_eq!(
            m.validate(),
            Err(MeshError::HoleOutOfRange {
                hole: 0,
                face: 1,
                count: 1
            })
        );
        let mut m = quad();
        m.add_crease(0, 1, f32::INFINITY);
        assert!(matches!(m.validate(), Err(MeshError::BadSharpness { .. })));
        let mut m = quad();
        m.fvar_channels.push(FVarChannel {
            width: 2,
            values: vec![0.0; 4],
            indices: vec![0, 1, 2, 1],
        });
        assert!(matches!(
            m.validate(),
            Err(MeshError::BadFVarChannel { channel: 0, .. })
        ));
    }

    /// With several bad faces the first in face order is reported,
    /// whichever check it fails, and in a channel the first bad value and
    /// the first corner out of range: the whole-mesh passes that find a
    /// mesh valid leave the reporting to the face-by-face search.
    #[test]
    fn the_first_offender_is_reported() {
        let mut m = quad();
        m.add_face(&[0, 1, 9]);
        m.add_face(&[0, 1]);
        assert_eq!(
            m.validate(),
            Err(MeshError::VertexOutOfRange {
                face: 1,
                corner: 2,
                index: 9,
                count: 4
            })
        );
        let mut m = quad();
        m.add_face(&[0, 1]);
        m.add_face(&[0, 1, 9]);
        assert_eq!(
            m.validate(),
            Err(MeshError::FaceTooSmall { face: 1, size: 2 })
        );
        let mut m = quad();
        let large: Vec<u32> = (0..=MAX_VALENCE as u32).map(|i| i % 4).collect();
        m.add_face(&[0, 1, 2]);
        m.add_face(&large);
        m.add_face(&[0, 9, 1]);
        assert_eq!(
            m.validate(),
            Err(MeshError::FaceTooLarge {
                face: 2,
                size: MAX_VALENCE + 1
            })
        );
        let problem = |m: &Mesh| match m.validate() {
            Err(MeshError::BadFVarChannel {
                channel: 0,
                problem,
            }) => problem,
            other => panic!("{other:?}"),
        };
        let mut m = quad();
        m.fvar_channels.push(FVarChannel {
            width: 2,
            values: vec![0.0, 0.0, f64::INFINITY, 0.0, f64::NAN, 0.0],
            indices: vec![0, 1, 2, 0],
        });
        assert_eq!(problem(&m), "value 1 has a non-finite component (inf)");
        m.fvar_channels[0].values = vec![0.0; 6];
        m.fvar_channels[0].indices = vec![0, 3, 4, 1];
        assert_eq!(
            problem(&m),
            "face 0 corner 1: value index 3 is out of range (the channel has 3 values)"
        );
    }

    #[test]
    fn crease_without_edge_is_a_warning_or_strict_error() {
        let mut m = quad();
        m.add_crease(0, 2, 1.0); // a diagonal, not an edge
        let v = m.validate().unwrap();
        assert_eq!(
            v.warnings,
            vec![MeshWarning::CreaseWithoutEdge {
                crease: 0,
                v0: 0,
                v1: 2
            }]
        );
        assert_eq!(
            m.validate_strict(),
            Err(MeshError::CreaseWithoutEdge {
                crease: 0,
                v0: 0,
                v1: 2
            })
        );
    }
    #[test]
    fn only_creases_off_the_edges_warn_in_any_order_or_repetition() {
        // A 2 × 2 grid of quads, vertices 0..9 row by row.
        let mut m = Mesh::default();
        for j in 0..3 {
            for i in 0..3 {
                m.positions.push(DVec3::new(i as f64, j as f64, 0.0));
            }
        }
        for (i, j) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            let at = |i: u32, j: u32| j * 3 + i;
            m.add_face(&[at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
        m.add_crease(0, 1, 1.0); // an edge
        m.add_crease(4, 1, 2.0); // an edge, reversed
        m.add_crease(0, 4, 1.0); // a diagonal between two crease ends
        m.add_crease(1, 0, 3.0); // the first edge again, reversed
        m.add_crease(4, 0, 1.0); // the diagonal again
        m.add_crease(7, 8, 1.0); // an edge on the far side
        m.add_crease(2, 6, 1.0); // far apart
        let warned: Vec<usize> = m
            .validate()
            .unwrap()
            .warnings
            .iter()
            .map(|w| {
                let MeshWarning::CreaseWithoutEdge { crease, .. } = w;
                *crease
            })
            .collect();
        assert_eq!(warned, [2, 4, 6]);
    }
}
