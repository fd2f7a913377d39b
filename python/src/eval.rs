//! `evaluate`: the limit surface at (ptex face, u, v) locations through a
//! patch table (`Far::PatchTableFactory`, `PatchMap`, `EvaluateBasis`), as
//! `subdiv eval` computes it — OpenSubdiv's basis or, natively, the exact
//! limit surface (`exact_limit=True`, `subdiv eval --exact-limit`).

use crate::convert;
use crate::errors::{SubdivError, to_py};
use crate::mesh::Mesh;
use crate::options::{Options, or_default, parse};
use pyo3::prelude::*;
use subdiv::Engine;
use subdiv::patches::{
    Derivatives, EndCapType, Evaluation, PatchData, PatchMap, PatchOptions, SurfaceSamples,
};

/// An end-cap type by the command line's name.
fn end_cap_type(name: &str) -> PyResult<EndCapType> {
    name.parse()
        .map_err(|e: subdiv::ParseNameError| SubdivError::new_err(e.to_string()))
}

/// The locations of `faces` (ptex faces) and `uv` (`(N, 2)` coordinates).
fn locations(faces: &Bound<'_, PyAny>, uv: &Bound<'_, PyAny>) -> PyResult<Vec<(u32, f64, f64)>> {
    let faces = convert::int_vector(faces, "faces")?;
    let uv = convert::floats(uv, "uv")?;
    let n = convert::check_shape(uv.shape(), Some(2), "uv")?;
    if n != faces.len() {
        return Err(SubdivError::new_err(format!(
            "faces has {} entries and uv {n} rows: one face per (u, v)",
            faces.len()
        )));
    }
    let uv = uv.to_f64();
    Ok(faces
        .iter()
        .zip(uv.chunks_exact(2))
        .map(|(&f, c)| (f, c[0], c[1]))
        .collect())
}

/// The limit surface of `mesh` at `locations`, with `engine`.
fn samples(
    mesh: &subdiv::Mesh,
    options: &subdiv::Options,
    patch_options: &PatchOptions,
    engine: Engine,
    locations: &[(u32, f64, f64)],
    derivatives: Derivatives,
    evaluation: Evaluation,
) -> subdiv::Result<SurfaceSamples> {
    let base = mesh.flat_positions::<f64>();
    let adaptive = patch_options.refine_adaptive_options();
    match engine {
        Engine::Native => {
            let refiner =
                subdiv::refiner::Refiner::new(mesh, options)?.refine_adaptive(adaptive, &[])?;
            let table = refiner.patch_table(patch_options, &[])?;
            let points = refiner.patch_points(&table, 3, &base)?;
            subdiv::patches::evaluate_data_as(
                evaluation,
                &PatchMap::new(&table),
                &table,
                PatchData::Vertex,
                &points,
                3,
                locations,
                derivatives,
            )
        }
        Engine::Osd => {
            let mut refiner = subdiv::osd::TopologyRefiner::new(mesh, options)?;
            refiner.refine_adaptive(adaptive, &[])?;
            let table = refiner.patch_table(patch_options, &[])?;
            table.evaluate(&refiner, 3, &base, locations, derivatives)
        }
    }
}

/// The limit surface of `mesh` at the ptex faces `faces` and coordinates
/// `uv`, as `subdiv eval` evaluates it: `(N, 3)` float64 positions, or
/// `(positions, du, dv)` with `derivatives`. `exact_limit` evaluates the
/// exact limit surface where OpenSubdiv's `EvaluateBasis` departs from it
/// (single-crease patches with their sharpness, derivatives under non-quad
/// faces with respect to the ptex face); native engine only.
#[pyfunction]
#[pyo3(signature = (mesh, faces, uv, options=None, isolation=4, engine="native", end_caps="gregory-basis", single_crease=false, inf_sharp=false, double=false, derivatives=false, exact_limit=false))]
#[allow(clippy::too_many_arguments)]
pub fn evaluate<'py>(
    py: Python<'py>,
    mesh: &Bound<'py, Mesh>,
    faces: &Bound<'py, PyAny>,
    uv: &Bound<'py, PyAny>,
    options: Option<&Options>,
    isolation: i64,
    engine: &str,
    end_caps: &str,
    single_crease: bool,
    inf_sharp: bool,
    double: bool,
    derivatives: bool,
    exact_limit: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let engine: Engine = parse(engine)?;
    if !(0..=10).contains(&isolation) {
        return Err(SubdivError::new_err(format!(
            "isolation {isolation}: OpenSubdiv isolates 0 to 10 levels"
        )));
    }
    if exact_limit && engine != Engine::Native {
        return Err(SubdivError::new_err(
            "exact_limit: OpenSubdiv's EvaluateBasis has no exact-limit mode; use engine=\"native\"",
        ));
    }
    let mut patch_options = PatchOptions::new()
        .max_isolation(isolation as u32)
        .end_caps(end_cap_type(end_caps)?)
        .single_crease_patch(single_crease)
        .inf_sharp_patch(inf_sharp);
    patch_options.patch_precision_double = double;
    let at = locations(faces, uv)?;
    let mesh = &mesh.get().inner;
    let options = or_default(options);
    let (derivatives, evaluation) = (
        if derivatives {
            Derivatives::First
        } else {
            Derivatives::None
        },
        if exact_limit {
            Evaluation::ExactLimit
        } else {
            Evaluation::OpenSubdiv
        },
    );
    let s = py
        .detach(|| {
            samples(
                mesh,
                &options,
                &patch_options,
                engine,
                &at,
                derivatives,
                evaluation,
            )
        })
        .map_err(to_py)?;
    let v = s.values;
    let positions = convert::values(py, v.point, 3)?.into_any();
    if derivatives == Derivatives::None {
        return Ok(positions);
    }
    let du = convert::values(py, v.du, 3)?.into_any();
    let dv = convert::values(py, v.dv, 3)?.into_any();
    Ok((positions, du, dv).into_pyobject(py)?.into_any())
}
