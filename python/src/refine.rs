//! `refine` and `compare`: whole refinements with either engine, the GIL
//! released while they run, every level handed to numpy without a copy.

use crate::convert;
use crate::errors::{LevelError, to_py};
use crate::mesh::Mesh;
use crate::options::{Options, or_default, parse};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};
use std::time::Instant;
use subdiv::{Engine, Precision, Refinement, Request};

/// A level from Python: negative or beyond `u32` is refused as the library
/// refuses a level that is too deep.
pub fn level_arg(level: i64) -> PyResult<u32> {
    if level < 0 {
        return Err(LevelError::new_err(format!(
            "refinement level {level} refused: a level is at least 0"
        )));
    }
    Ok(u32::try_from(level).unwrap_or(u32::MAX))
}

/// The request of `refine`'s arguments, the level checked against the mesh first.
fn request(
    mesh: &subdiv::Mesh,
    options: &subdiv::Options,
    level: i64,
    precision: &str,
    limit: bool,
    faces_first: bool,
) -> PyResult<Request> {
    let level = level_arg(level)?;
    let precision: Precision = parse(precision)?;
    subdiv::check_level(mesh, options, level).map_err(to_py)?;
    subdiv::check_precision(mesh, precision).map_err(to_py)?;
    Ok(Request::new(level)
        .precision(precision)
        .limit(limit)
        .faces_first(faces_first))
}

/// Positions in the refinement's precision.
fn points<'py>(
    py: Python<'py>,
    points: Vec<glam::DVec3>,
    precision: Precision,
) -> PyResult<Bound<'py, PyAny>> {
    Ok(match precision {
        Precision::F64 => convert::points_f64(py, points)?.into_any(),
        Precision::F32 => convert::points_f32(py, &points)?.into_any(),
    })
}

/// Face-varying values in the refinement's precision.
fn fvar_values<'py>(
    py: Python<'py>,
    values: Vec<f64>,
    width: usize,
    precision: Precision,
) -> PyResult<Bound<'py, PyAny>> {
    Ok(match precision {
        Precision::F64 => convert::values(py, values, width)?.into_any(),
        Precision::F32 => {
            let narrow = values.iter().map(|&v| v as f32).collect();
            convert::values(py, narrow, width)?.into_any()
        }
    })
}

/// A refinement as Python values: a list of levels, each a tuple
/// `(points, face_counts, face_indices, holes, uvs, uv_indices)` (the UVs
/// `None` without face-varying channel 0), and the limit, a tuple
/// `(points, du, dv, uvs)`, or `None`.
fn to_python(py: Python<'_>, r: Refinement) -> PyResult<Bound<'_, PyTuple>> {
    let precision = r.precision;
    let width = r.fvar_widths.first().copied();
    let levels = PyList::empty(py);
    let mut fvar = r.fvar_values.into_iter();
    for (topology, positions) in r.levels.into_iter().zip(r.positions) {
        let counts = convert::face_counts(py, &topology.face_offsets);
        let mut channels = fvar.next().unwrap_or_default().into_iter();
        let mut fvar_topology = topology.fvar.into_iter();
        let (uvs, uv_indices) = match (width, channels.next(), fvar_topology.next()) {
            (Some(w), Some(values), Some(t)) => (
                fvar_values(py, values, w, precision)?,
                convert::indices(py, t.face_values).into_any(),
            ),
            _ => (py.None().into_bound(py), py.None().into_bound(py)),
        };
        let level = (
            points(py, positions, precision)?,
            counts,
            convert::indices(py, topology.face_vertices),
            convert::vector(py, topology.face_holes),
            uvs,
            uv_indices,
        );
        levels.append(level)?;
    }
    let limit = match r.limit {
        Some(l) => {
            let uvs = match (width, l.fvar_values.into_iter().next()) {
                (Some(w), Some(values)) => fvar_values(py, values, w, precision)?,
                _ => py.None().into_bound(py),
            };
            (
                points(py, l.positions, precision)?,
                points(py, l.du, precision)?,
                points(py, l.dv, precision)?,
                uvs,
            )
                .into_pyobject(py)?
                .into_any()
        }
        None => py.None().into_bound(py),
    };
    (levels, limit).into_pyobject(py)
}

/// Refines `mesh` with one engine; the pure-Python `subdiv.refine` wraps the
/// result in dataclasses.
#[pyfunction]
#[pyo3(signature = (mesh, level=2, options=None, engine="native", precision="f64", limit=false, faces_first=false))]
#[allow(clippy::too_many_arguments)]
pub fn refine<'py>(
    py: Python<'py>,
    mesh: &Bound<'py, Mesh>,
    level: i64,
    options: Option<&Options>,
    engine: &str,
    precision: &str,
    limit: bool,
    faces_first: bool,
) -> PyResult<Bound<'py, PyTuple>> {
    let engine: Engine = parse(engine)?;
    let mesh = &mesh.get().inner;
    let options = or_default(options);
    let request = request(mesh, &options, level, precision, limit, faces_first)?;
    let r = py
        .detach(|| engine.refine(mesh, &options, request))
        .map_err(to_py)?;
    to_python(py, r)
}

/// Refines `mesh` with both engines and compares them level by level:
/// `(levels, native_seconds, osd_seconds)`, each level a dict of
/// `subdiv::compare::LevelComparison`'s fields.
#[pyfunction]
#[pyo3(signature = (mesh, level=2, options=None, precision="f64", limit=false, faces_first=false))]
pub fn compare<'py>(
    py: Python<'py>,
    mesh: &Bound<'py, Mesh>,
    level: i64,
    options: Option<&Options>,
    precision: &str,
    limit: bool,
    faces_first: bool,
) -> PyResult<(Bound<'py, PyList>, f64, f64)> {
    let mesh = &mesh.get().inner;
    let options = or_default(options);
    let request = request(mesh, &options, level, precision, limit, faces_first)?;
    let timed = |engine: Engine| {
        let start = Instant::now();
        let r = engine.refine(mesh, &options, request);
        r.map(|r| (r, start.elapsed().as_secs_f64()))
    };
    let (levels, native_seconds, osd_seconds) = py
        .detach(|| {
            let (native, native_seconds) = timed(Engine::Native)?;
            let (osd, osd_seconds) = timed(Engine::Osd)?;
            Ok::<_, subdiv::Error>((
                subdiv::compare::compare(&native, &osd),
                native_seconds,
                osd_seconds,
            ))
        })
        .map_err(to_py)?;
    let out = PyList::empty(py);
    for c in levels {
        let d = PyDict::new(py);
        d.set_item("level", c.level)?;
        d.set_item("native_counts", c.counts[0].to_vec())?;
        d.set_item("osd_counts", c.counts[1].to_vec())?;
        d.set_item("first_face_difference", c.first_face_difference)?;
        d.set_item("tags_equal", c.tags_equal)?;
        d.set_item("max_position_deviation", c.max_position_deviation)?;
        d.set_item("relative_position_deviation", c.relative_position_deviation)?;
        d.set_item("worst_vertex", c.worst_vertex)?;
        d.set_item("fvar_topology_equal", c.fvar_topology_equal)?;
        d.set_item("max_fvar_deviation", c.max_fvar_deviation)?;
        d.set_item("limit_deviation", c.limit_deviation)?;
        d.set_item("topology_equal", c.topology_equal())?;
        out.append(d)?;
    }
    Ok((out, native_seconds, osd_seconds))
}

/// Times the Rust call alone, for `python/bench_overhead.py`: `repeats`
/// runs of `Engine::refine` (the same request as `refine`'s) and the drop
/// of its result (a Python caller frees the arrays too), each timed inside
/// Rust with no conversion to Python, in seconds. The GIL is released.
#[pyfunction]
#[pyo3(signature = (mesh, level=2, options=None, engine="native", repeats=1))]
pub fn time_rust_refine(
    py: Python<'_>,
    mesh: &Bound<'_, Mesh>,
    level: i64,
    options: Option<&Options>,
    engine: &str,
    repeats: usize,
) -> PyResult<Vec<f64>> {
    let engine: Engine = parse(engine)?;
    let mesh = &mesh.get().inner;
    let options = or_default(options);
    let request = request(mesh, &options, level, "f64", false, false)?;
    py.detach(|| {
        (0..repeats)
            .map(|_| {
                let start = Instant::now();
                drop(engine.refine(mesh, &options, request)?);
                Ok(start.elapsed().as_secs_f64())
            })
            .collect::<subdiv::Result<Vec<f64>>>()
    })
    .map_err(to_py)
}
