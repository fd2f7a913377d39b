//! The OpenSubdiv engine: a safe wrapper over the C shim in `cpp/`.
//!
//! This is the only module of the crate with `unsafe` code. Every call goes
//! through [`TopologyRefiner`], which owns the C++ `Far::TopologyRefiner` and frees it
//! on drop; slices go in, `Vec`s come out, and every failure is an [`Error`](crate::Error).
//!
//! ```
//! use subdiv::{osd, shapes, Options, UniformOptions};
//! let mesh = shapes::cube();
//! let mut refiner = osd::TopologyRefiner::new(&mesh, &Options::default())?;
//! refiner.refine_uniform(UniformOptions::new(1))?;
//! let level1 = refiner.level(1)?;
//! assert_eq!((level1.vertex_count, level1.face_count()), (26, 24));
//! # Ok::<(), subdiv::Error>(())
//! ```
//!
//! # Threads
//! A [`TopologyRefiner`] is `Send` and `Sync`: every query and interpolation is a
//! read-only use of OpenSubdiv's refiner (as OpenSubdiv itself allows from
//! several threads), and only [`TopologyRefiner::refine_uniform`] and
//! [`TopologyRefiner::refine_adaptive`] mutate it, which needs `&mut self`. OpenSubdiv's error messages are captured per thread.

use std::ffi::CStr;

#[allow(
    non_camel_case_types,
    non_upper_case_globals,
    non_snake_case,
    dead_code,
    missing_docs,
    clippy::all
)]
mod ffi {
    include!(concat!(env!("OUT_DIR"), "/shim_bindings.rs"));
}

const ERR_LEN: usize = 1024;
const SDV_VERTEX: i32 = ffi::SDV_VERTEX as i32;
const SDV_VARYING: i32 = ffi::SDV_VARYING as i32;
const SDV_FACE_VARYING: i32 = ffi::SDV_FACE_VARYING as i32;
const SDV_STENCIL_REFINED: i32 = ffi::SDV_STENCIL_REFINED as i32;
const SDV_STENCIL_LIMIT: i32 = ffi::SDV_STENCIL_LIMIT as i32;

/// The version of the OpenSubdiv library the bridge was built against, e.g. `"3.5.0"`.
pub fn version() -> String {
    // SAFETY: the shim returns a pointer to a static NUL-terminated string.
    unsafe { CStr::from_ptr(ffi::sdv_osd_version()) }
        .to_string_lossy()
        .into_owned()
}

/// OpenSubdiv's `OPENSUBDIV_VERSION_NUMBER`, e.g. `30500`.
pub fn version_number() -> u32 {
    // SAFETY: a pure function of the shim.
    unsafe { ffi::sdv_osd_version_number() as u32 }
}

mod adaptive;
mod at_locations;
pub mod bfr;
pub mod bfr_mesh;
pub mod bfr_surface;
mod evaluator;
mod patches;
mod refiner;
mod shim;
mod stencils;
mod whole;

pub use crate::output::{LevelCounts, LimitData};
pub use evaluator::OsdCpuPatchTable;
pub use patches::OsdPatchTable;
pub use refiner::TopologyRefiner;
pub use stencils::StencilEvaluator;
pub use whole::refine;
