//! OBJ files with OpenSubdiv's tags: `read_obj`, `parse_obj` and the two
//! writers (a whole mesh with its tags, or one refined level as `subdiv
//! refine -o` writes it). Writes are atomic: a file appears whole or not at all.

use crate::convert::{self, floats, int_vector};
use crate::errors::to_py;
use crate::mesh::Mesh;
use crate::options::{Options, parse};
use pyo3::prelude::*;
use std::path::{Path, PathBuf};
use subdiv::Precision;
use subdiv::io::{ObjOutput, ShapeFile, UvOutput};

/// A read file as `(mesh, options, warnings)`.
fn shape_file(file: ShapeFile) -> PyResult<(Mesh, Options, Vec<String>)> {
    let options = Options {
        inner: file.options(),
    };
    let warnings = file.warnings.iter().map(ToString::to_string).collect();
    Ok((Mesh::from_rust(file.mesh)?, options, warnings))
}

/// Reads an OBJ file with OpenSubdiv's tags: ``(mesh, options, warnings)``,
/// the options being the file's tags over the shape-file defaults.
#[pyfunction]
pub fn read_obj(py: Python<'_>, path: PathBuf) -> PyResult<(Mesh, Options, Vec<String>)> {
    let file = py
        .detach(|| subdiv::io::read_obj(&path))
        .map_err(|e| to_py(e.into()))?;
    shape_file(file)
}

/// Parses OBJ text as ``read_obj`` reads a file; errors name ``name`` and the line.
#[pyfunction]
#[pyo3(signature = (text, name="<string>"))]
pub fn parse_obj(py: Python<'_>, text: &str, name: &str) -> PyResult<(Mesh, Options, Vec<String>)> {
    let file = py
        .detach(|| subdiv::io::parse_obj(text, Path::new(name)))
        .map_err(|e| to_py(e.into()))?;
    shape_file(file)
}

/// Writes a mesh with its creases, corners and holes as ``t`` tags (and UV
/// channel 0 as ``vt``), atomically, so that ``read_obj`` reads it back.
#[pyfunction]
#[pyo3(signature = (path, mesh, precision="f64"))]
pub fn write_mesh_obj(
    py: Python<'_>,
    path: PathBuf,
    mesh: &Bound<'_, Mesh>,
    precision: &str,
) -> PyResult<()> {
    let precision: Precision = parse(precision)?;
    let mesh = &mesh.get().inner;
    py.detach(|| subdiv::io::write_mesh_obj(&path, mesh, precision))
        .map_err(to_py)
}

/// Writes one level as ``subdiv refine -o`` does: ``v`` lines, ``vt`` lines
/// of the UVs, ``f`` lines without the faces flagged in ``holes``; atomically.
#[pyfunction]
#[pyo3(signature = (path, points, face_counts, face_indices, holes=None, uvs=None, uv_indices=None, precision="f64"))]
#[allow(clippy::too_many_arguments)]
pub fn write_level_obj(
    py: Python<'_>,
    path: PathBuf,
    points: &Bound<'_, PyAny>,
    face_counts: &Bound<'_, PyAny>,
    face_indices: &Bound<'_, PyAny>,
    holes: Option<&Bound<'_, PyAny>>,
    uvs: Option<&Bound<'_, PyAny>>,
    uv_indices: Option<&Bound<'_, PyAny>>,
    precision: &str,
) -> PyResult<()> {
    let precision: Precision = parse(precision)?;
    let positions = convert::positions(points, "points")?;
    let counts = int_vector(face_counts, "face_counts")?;
    let face_vertices = int_vector(face_indices, "face_indices")?;
    let face_offsets = convert::face_offsets(&counts, face_vertices.len())?;
    let holes: Option<Vec<bool>> = match holes {
        Some(h) => Some(
            h.py()
                .import("numpy")?
                .call_method1("asarray", (h, "bool"))?
                .extract::<Vec<bool>>()?,
        ),
        None => None,
    };
    let uv_values = uvs.map(|u| floats(u, "uvs")).transpose()?;
    let uv = match (&uv_values, uv_indices) {
        (Some(values), Some(indices)) => {
            let width = match values.shape() {
                [_, w] if *w > 0 => *w,
                shape => {
                    return Err(crate::errors::SubdivError::new_err(format!(
                        "uvs must have the shape (M, width), not {shape:?}"
                    )));
                }
            };
            Some((width, values.to_f64(), int_vector(indices, "uv_indices")?))
        }
        (None, None) => None,
        _ => {
            return Err(crate::errors::SubdivError::new_err(
                "uvs and uv_indices go together",
            ));
        }
    };
    let data = ObjOutput {
        positions: &positions,
        face_offsets: &face_offsets,
        face_vertices: &face_vertices,
        holes: holes.as_deref(),
        uv: uv.as_ref().map(|(width, values, indices)| UvOutput {
            width: *width,
            values,
            face_values: indices,
        }),
        normals: None,
        precision,
    };
    py.detach(|| subdiv::io::write_obj(&path, &data))
        .map_err(to_py)
}
