//! `subdiv._subdiv`: the compiled half of the Python module `subdiv`
//! (issue #27). The pure-Python package (`python/subdiv/`) wraps these
//! functions in dataclasses and documents them; see its `__init__.py`.
//!
//! One file per concern: [`errors`] (the exceptions), [`convert`] (numpy in
//! and out), [`mesh`] (`Mesh`), [`options`] (`Options`, names), [`refine`]
//! (`refine`, `compare`), [`refiner`] (`Refiner`: frames, limits,
//! stencils), [`eval`] (`evaluate`: the limit surface through patch
//! tables), [`obj`] (OBJ files), [`shapes`] (generated meshes).

mod convert;
mod errors;
mod eval;
mod mesh;
mod obj;
mod options;
mod refine;
mod refiner;
mod shapes;

use pyo3::prelude::*;

/// The module: classes, functions and exceptions.
#[pymodule]
fn _subdiv(m: &Bound<'_, PyModule>) -> PyResult<()> {
    errors::register(m)?;
    m.add_class::<mesh::Mesh>()?;
    m.add_class::<options::Options>()?;
    m.add_class::<refiner::Refiner>()?;
    m.add_function(wrap_pyfunction!(refine::refine, m)?)?;
    m.add_function(wrap_pyfunction!(refine::compare, m)?)?;
    m.add_function(wrap_pyfunction!(refine::time_rust_refine, m)?)?;
    m.add_function(wrap_pyfunction!(eval::evaluate, m)?)?;
    m.add_function(wrap_pyfunction!(obj::read_obj, m)?)?;
    m.add_function(wrap_pyfunction!(obj::parse_obj, m)?)?;
    m.add_function(wrap_pyfunction!(obj::write_mesh_obj, m)?)?;
    m.add_function(wrap_pyfunction!(obj::write_level_obj, m)?)?;
    m.add_function(wrap_pyfunction!(shapes::corpus, m)?)?;
    m.add_function(wrap_pyfunction!(shapes::builtin, m)?)?;
    m.add_function(wrap_pyfunction!(shapes::torus, m)?)?;
    m.add_function(wrap_pyfunction!(shapes::grid, m)?)?;
    m.add("OSD_VERSION", subdiv::osd::version())?;
    Ok(())
}
