//! # subdiv — subdivision curves and surfaces, checked against OpenSubdiv
//!
//! `subdiv` refines polygon meshes the way Pixar's OpenSubdiv does — same vertex
//! order, same faces, same positions to rounding — and compares its results
//! with OpenSubdiv itself, vertex by vertex.
//!
//! ```text
//!  OBJ + "t" tags ──► Mesh (validated) ──► engine ──► levels: topology + primvars ──► OBJ / compare
//!                                            ├── osd:    C++ shim over OpenSubdiv 3.5 (feature "osd")
//!                                            └── native: pure Rust (in progress)
//! ```
//!
//! The crate has two engines sharing one [`Mesh`] and one set of [`Options`]:
//! the **osd** engine ([`osd`], feature `osd`, on by default) is a thin bridge
//! over Debian's OpenSubdiv, and the **native** engine is pure Rust.
//!
//! ```
//! use subdiv::{Mesh, Options};
//! use glam::DVec3;
//!
//! // A unit quad with one sharp edge.
//! let mut mesh = Mesh::from_faces(
//!     vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
//!     &[&[0, 1, 2, 3]],
//! );
//! mesh.add_crease(0, 1, 10.0);
//! mesh.validate()?;
//! let options = Options::shape_file_defaults();
//! # #[cfg(feature = "osd")] {
//! let refined = subdiv::osd::refine(&mesh, &options, subdiv::UniformOptions::new(2))?;
//! assert_eq!(refined.last_level().face_count(), 16);
//! # }
//! # Ok::<(), subdiv::Error>(())
//! ```

#![warn(missing_docs)]
#![deny(unsafe_code)]

pub mod classic;
pub mod compare;
pub mod engine;
pub mod error;
pub mod io;
pub mod limits;
pub mod mesh;
pub mod names;
pub mod options;
pub mod output;
pub mod real;
pub mod refiner;
pub mod rules;
pub mod shapes;
pub mod stencil;
pub(crate) mod topology;

#[cfg(feature = "osd")]
#[allow(unsafe_code)]
pub mod osd;

pub use classic::{curve, doo_sabin, nurbs, patch};
pub use error::{
    Buffer, Element, Error, LevelRefusal, ObjError, ObjErrorKind, OsdError, OsdErrorKind, Result,
    StencilFault,
};
pub use limits::check_level;
pub use mesh::{Corner, Crease, FVarChannel, Mesh, MeshError, MeshWarning, Validation};
pub use names::{Named, ParseNameError};
pub use options::{
    BoundaryInterpolation, CreasingMethod, Engine, FVarLinearInterpolation, MAX_LEVEL, Options,
    Request, Scheme, TriangleSubdivision, UniformOptions,
};
pub use output::{
    FVarTopology, LevelCounts, LevelTopology, Limit, LimitData, Refinement, Values,
    release_buffer_pool,
};
pub use real::{Precision, Real};
pub use stencil::{LimitStencilTable, StencilTable, StencilTableF32};

/// The README's examples, compiled and run as doctests.
#[cfg(all(doctest, feature = "osd"))]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
