//! `subdiv.Mesh`: a validated base mesh built from numpy arrays.

use crate::convert::{self, check_shape, floats, int_vector, ints};
use crate::errors::{MeshError, mesh_error};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

/// A polygon mesh with OpenSubdiv's tags, validated when it is made.
///
/// ``Mesh(points, face_counts, face_indices, *, creases=None, corners=None,
/// holes=None, uvs=None, uv_indices=None, left_handed=False)``:
///
/// - ``points``: ``(N, 3)`` float32 or float64 positions;
/// - ``face_counts``: ``(F,)`` integers, the number of vertices of each face;
/// - ``face_indices``: ``(sum(face_counts),)`` integers, the vertices of all
///   faces concatenated, counter-clockwise;
/// - ``creases``: ``(edges, sharpness)``, ``edges`` of shape ``(K, 2)`` and
///   ``sharpness`` of shape ``(K,)`` or one number for all;
/// - ``corners``: ``(vertices, sharpness)``, ``vertices`` of shape ``(K,)``;
/// - ``holes``: ``(H,)`` face indices;
/// - ``uvs``: ``(M, 2)`` face-varying values (channel 0);
/// - ``uv_indices``: one value index per face corner, parallel to
///   ``face_indices`` (without it, ``face_indices`` itself: one UV per vertex);
/// - ``left_handed``: the faces are listed clockwise (USD's
///   ``orientation = "leftHanded"``, OpenSubdiv's ``isLeftHanded``); both
///   engines read each face from its first corner backwards.
///
/// Every problem raises ``MeshError`` with the Rust library's message.
#[pyclass(frozen, module = "subdiv")]
pub struct Mesh {
    /// The library's mesh.
    pub inner: subdiv::Mesh,
    /// The validation's warnings, as messages.
    pub warnings: Vec<String>,
}

impl Mesh {
    /// Validates a library mesh and wraps it.
    pub fn from_rust(inner: subdiv::Mesh) -> PyResult<Mesh> {
        let validation = inner.validate().map_err(mesh_error)?;
        let warnings = validation
            .warnings
            .iter()
            .map(ToString::to_string)
            .collect();
        Ok(Mesh { inner, warnings })
    }
}

/// Crease edges `(K, 2)` and their sharpness `(K,)`.
type Creases<'py> = (Bound<'py, PyArray2<i32>>, Bound<'py, PyArray1<f32>>);

/// A pair `(indices, sharpness)`, the sharpness one number or one per index row.
fn tagged(obj: &Bound<'_, PyAny>, what: &str, width: usize) -> PyResult<(Vec<u32>, Vec<f32>)> {
    let pair = obj
        .cast::<PyTuple>()
        .ok()
        .filter(|t| t.len() == 2)
        .ok_or_else(|| {
            crate::errors::type_error(format!("{what} must be a pair (indices, sharpness)"))
        })?;
    let (indices, shape) = ints(&pair.get_item(0)?, &format!("{what} indices"))?;
    let rows = if width == 1 {
        check_shape(&shape, None, &format!("{what} indices"))?
    } else {
        check_shape(&shape, Some(width), &format!("{what} indices"))?
    };
    let sharpness = floats(&pair.get_item(1)?, &format!("{what} sharpness"))?;
    let values = sharpness.to_f64();
    let values: Vec<f32> = match (sharpness.shape(), values.as_slice()) {
        ([], [one]) => vec![*one as f32; rows],
        ([n], _) if *n == rows => values.iter().map(|&v| v as f32).collect(),
        (shape, _) => {
            return Err(MeshError::new_err(format!(
                "{what} sharpness must be one number or {rows} numbers, not an array of shape {shape:?}"
            )));
        }
    };
    Ok((indices, values))
}

#[pymethods]
impl Mesh {
    #[new]
    #[pyo3(signature = (points, face_counts, face_indices, *, creases=None, corners=None, holes=None, uvs=None, uv_indices=None, left_handed=false))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        points: &Bound<'_, PyAny>,
        face_counts: &Bound<'_, PyAny>,
        face_indices: &Bound<'_, PyAny>,
        creases: Option<&Bound<'_, PyAny>>,
        corners: Option<&Bound<'_, PyAny>>,
        holes: Option<&Bound<'_, PyAny>>,
        uvs: Option<&Bound<'_, PyAny>>,
        uv_indices: Option<&Bound<'_, PyAny>>,
        left_handed: bool,
    ) -> PyResult<Mesh> {
        let positions = convert::positions(points, "points")?;
        let counts = int_vector(face_counts, "face_counts")?;
        let face_vertices = int_vector(face_indices, "face_indices")?;
        let face_offsets = convert::face_offsets(&counts, face_vertices.len())?;
        let mut mesh = subdiv::Mesh {
            positions,
            face_offsets,
            face_vertices,
            left_handed,
            ..subdiv::Mesh::default()
        };
        if let Some(creases) = creases {
            let (edges, sharpness) = tagged(creases, "creases", 2)?;
            for (e, s) in edges.chunks_exact(2).zip(sharpness) {
                mesh.add_crease(e[0], e[1], s);
            }
        }
        if let Some(corners) = corners {
            let (vertices, sharpness) = tagged(corners, "corners", 1)?;
            for (v, s) in vertices.into_iter().zip(sharpness) {
                mesh.add_corner(v, s);
            }
        }
        if let Some(holes) = holes {
            mesh.holes = int_vector(holes, "holes")?;
        }
        match (uvs, uv_indices) {
            (Some(uvs), indices) => {
                let uvs = floats(uvs, "uvs")?;
                check_shape(uvs.shape(), Some(2), "uvs")?;
                let indices = match indices {
                    Some(indices) => int_vector(indices, "uv_indices")?,
                    None => mesh.face_vertices.clone(),
                };
                mesh.fvar_channels.push(subdiv::FVarChannel {
                    width: 2,
                    values: uvs.to_f64(),
                    indices,
                });
            }
            (None, Some(_)) => {
                return Err(MeshError::new_err("uv_indices given without uvs"));
            }
            (None, None) => {}
        }
        Mesh::from_rust(mesh)
    }

    /// ``(N, 3)`` float64 vertex positions (a copy).
    #[getter]
    fn points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        convert::points_f64(py, self.inner.positions.clone())
    }

    /// ``(F,)`` int32 number of vertices of each face.
    #[getter]
    fn face_counts<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i32>> {
        convert::face_counts(py, &self.inner.face_offsets)
    }

    /// int32 vertex indices of all faces, concatenated.
    #[getter]
    fn face_indices<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i32>> {
        convert::indices(py, self.inner.face_vertices.clone())
    }

    /// ``(edges, sharpness)``: ``(K, 2)`` int32 and ``(K,)`` float32.
    #[getter]
    fn creases<'py>(&self, py: Python<'py>) -> PyResult<Creases<'py>> {
        let c = &self.inner.creases;
        let edges = c
            .iter()
            .flat_map(|c| c.vertices.map(|v| v as i32))
            .collect();
        let sharpness = c.iter().map(|c| c.sharpness).collect();
        Ok((
            convert::rows(py, edges, c.len(), 2)?,
            convert::vector(py, sharpness),
        ))
    }

    /// ``(vertices, sharpness)``: ``(K,)`` int32 and ``(K,)`` float32.
    #[getter]
    fn corners<'py>(
        &self,
        py: Python<'py>,
    ) -> (Bound<'py, PyArray1<i32>>, Bound<'py, PyArray1<f32>>) {
        let c = &self.inner.corners;
        let vertices = c.iter().map(|c| c.vertex as i32).collect();
        let sharpness = c.iter().map(|c| c.sharpness).collect();
        (
            convert::vector(py, vertices),
            convert::vector(py, sharpness),
        )
    }

    /// ``(H,)`` int32 indices of the faces that are holes.
    #[getter]
    fn holes<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i32>> {
        convert::indices(py, self.inner.holes.clone())
    }

    /// Whether the faces are listed clockwise (read from their first corner backwards).
    #[getter]
    fn left_handed(&self) -> bool {
        self.inner.left_handed
    }

    /// ``(M, width)`` float64 values of face-varying channel 0 (the UVs), or None.
    #[getter]
    fn uvs<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyArray2<f64>>>> {
        self.inner
            .fvar_channels
            .first()
            .map(|c| convert::values(py, c.values.clone(), c.width))
            .transpose()
    }

    /// int32 value index of every face corner of channel 0, or None.
    #[getter]
    fn uv_indices<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<i32>>> {
        self.inner
            .fvar_channels
            .first()
            .map(|c| convert::indices(py, c.indices.clone()))
    }

    /// Number of vertices.
    #[getter]
    fn vertex_count(&self) -> usize {
        self.inner.vertex_count()
    }

    /// Number of faces.
    #[getter]
    fn face_count(&self) -> usize {
        self.inner.face_count()
    }

    /// The validation's warnings (creases between vertices that share no edge), as messages.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.warnings.clone()
    }

    /// Raises ``MeshError`` when the mesh has a warning (as ``subdiv refine --strict``).
    fn validate_strict(&self) -> PyResult<()> {
        self.inner.validate_strict().map(drop).map_err(mesh_error)
    }

    fn __repr__(&self) -> String {
        format!(
            "subdiv.Mesh({} vertices, {} faces, {} creases, {} corners, {} holes, {} face-varying channels)",
            self.inner.vertex_count(),
            self.inner.face_count(),
            self.inner.creases.len(),
            self.inner.corners.len(),
            self.inner.holes.len(),
            self.inner.fvar_channels.len()
        )
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<Mesh>()
            .is_ok_and(|o| o.get().inner == self.inner)
    }
}
