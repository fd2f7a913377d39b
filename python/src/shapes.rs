//! Meshes generated in code (`subdiv::shapes`): the conformance corpus, the
//! command line's built-in shapes and the benchmark tori.

use crate::mesh::Mesh;
use pyo3::prelude::*;

/// The most quads a generated shape may have (2^26), so that a typo cannot
/// exhaust the memory.
const MAX_QUADS: u64 = 1 << 26;

fn check_size(a: u32, b: u32) -> PyResult<()> {
    let quads = u64::from(a) * u64::from(b);
    if quads > MAX_QUADS {
        return Err(crate::errors::SubdivError::new_err(format!(
            "{a} x {b} = {quads} quads: at most {MAX_QUADS} are generated"
        )));
    }
    Ok(())
}

/// The conformance corpus: ``[(name, mesh), ...]`` covering n-gons, poles,
/// boundaries, creases, corners, holes, non-manifold features and UV seams.
#[pyfunction]
pub fn corpus() -> PyResult<Vec<(String, Mesh)>> {
    subdiv::shapes::corpus()
        .into_iter()
        .map(|(name, mesh)| Ok((name, Mesh::from_rust(mesh)?)))
        .collect()
}

/// A built-in shape of ``subdiv refine --builtin``: ``cube``, ``cube-uv``,
/// ``grid``, ``torus`` or ``tetrahedron``.
#[pyfunction]
pub fn builtin(name: &str) -> PyResult<Mesh> {
    match subdiv::shapes::by_name(name) {
        Some(mesh) => Mesh::from_rust(mesh),
        None => Err(crate::errors::SubdivError::new_err(format!(
            "unknown shape '{name}' (expected one of: {})",
            subdiv::shapes::NAMES.join(", ")
        ))),
    }
}

/// A closed torus of ``nu`` by ``nv`` quads (``torus(100, 100)``: the 10k-quad benchmark torus).
#[pyfunction]
pub fn torus(nu: u32, nv: u32) -> PyResult<Mesh> {
    check_size(nu, nv)?;
    Mesh::from_rust(subdiv::shapes::torus(nu.max(3), nv.max(3)))
}

/// An open grid of ``nx`` by ``ny`` unit quads in the z = 0 plane, with per-vertex UVs.
#[pyfunction]
pub fn grid(nx: u32, ny: u32) -> PyResult<Mesh> {
    check_size(nx, ny)?;
    Mesh::from_rust(subdiv::shapes::grid(nx.max(1), ny.max(1)))
}
