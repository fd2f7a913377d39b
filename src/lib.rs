//! # subdiv — subdivision curves and surfaces, checked against OpenSubdiv
//!
//! `subdiv` refines polygon meshes the way Pixar's OpenSubdiv does — same vertex
//! order, same faces, same positions to rounding — and compares its results
//! with OpenSubdiv itself, vertex by vertex. It also implements the classic
//! curve and patch schemes the subject starts with.
//!
//! ```text
//!  OBJ + "t" tags ──► Mesh (validated) ──► Engine + Request ──► Refinement: every level's
//!  (io::obj)          (mesh)               │                   topology, primvars, limit
//!                                          ├── Native: rules → topology → refiner (pure Rust)
//!                                          └── Osd:    C++ shim over OpenSubdiv 3.5 (feature "osd")
//!  Refinement ──► io::obj (OBJ out) · compare (native against osd) · stencil (apply per frame)
//! ```
//!
//! ## Crate map
//!
//! **Engine** — the surface the two engines share, and the native engine:
//! - [`Mesh`] ([`mesh`]): positions, faces, creases, corners, holes,
//!   face-varying channels, and their validation;
//! - [`Options`], [`UniformOptions`], [`Request`] and [`Engine`]
//!   ([`options`]): OpenSubdiv's `Sdc`/`Far` options, what one refinement
//!   computes, which engine; [`limits`]: levels refused before allocating;
//! - [`Engine::refine`] ([`engine`]): the one way to drive either engine,
//!   returning the engine-neutral [`output`] types ([`Refinement`],
//!   [`LevelTopology`], [`Limit`], [`Values`]);
//! - [`refiner`]: the native engine (OpenSubdiv's `Far`), built on
//!   [`rules`] (`Sdc`: masks per scheme) and a crate-private topology layer
//!   (`Vtr`: flat tables per level, and their splitting);
//! - [`stencil`]: stencil tables and their fast apply kernels;
//! - [`ptex`]: ptex face indices and adjacency of a base mesh
//!   ([`PtexIndices`], OpenSubdiv's `Far::PtexIndices`);
//! - [`patches`]: patch tables as data (`Far::PatchTable`'s arrays,
//!   `PatchParam` words, `PatchTableFactory::Options`), built by the `osd`
//!   engine today;
//! - [`bfr`]: limit surfaces one base face at a time (OpenSubdiv's `Bfr`):
//!   parameterizations, tessellation patterns, evaluation at (face, u, v)
//!   and a watertight mesher;
//! - `osd` (feature `osd`): the bridge to OpenSubdiv, the only module with
//!   `unsafe`;
//! - [`compare`]: level-by-level comparison of two refinements;
//! - [`error`]: typed errors ([`Error`]); [`names`]: one naming mechanism for
//!   option values ([`Named`]); [`real`]: `f32`/`f64` ([`Real`], [`Precision`]).
//!
//! **Classic** — [`classic`]: curves ([`curve`]), knot-vector B-splines and
//! NURBS ([`nurbs`]), tensor patches ([`patch`]), Doo-Sabin ([`doo_sabin`]).
//!
//! **I/O** — [`io`]: OBJ with OpenSubdiv's tags, points files, SVG
//! pictures, exact `%g` numbers, atomic writes. [`shapes`]: meshes generated
//! in code (the test corpus, the report set, the benchmark inputs).
//!
//! The `subdiv` command-line application (feature `cli`, on by default) is
//! a separate binary (`src/bin/subdiv/`); a program that depends on this
//! crate with `default-features = false` builds neither it nor the C++ bridge.
//!
//! ```
//! use subdiv::{Engine, Mesh, Options, Request};
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
//! let native = Engine::Native.refine(&mesh, &options, Request::new(2))?;
//! assert_eq!(native.last_level().face_count(), 16);
//! # #[cfg(feature = "osd")] {
//! let osd = Engine::Osd.refine(&mesh, &options, Request::new(2))?;
//! assert_eq!(osd.positions, native.positions); // bit for bit
//! # }
//! # Ok::<(), subdiv::Error>(())
//! ```

#![warn(missing_docs)]
#![deny(unsafe_code)]

mod alloc;
pub mod bfr;
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
pub mod patches;
pub mod ptex;
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
#[cfg(feature = "usd")]
pub use error::{UsdError, UsdErrorKind};
pub use limits::{check_level, check_precision};
pub use mesh::{Corner, Crease, FVarChannel, Mesh, MeshError, MeshWarning, Validation};
pub use names::{Named, ParseNameError};
pub use options::{
    AdaptiveOptions, BoundaryInterpolation, CreasingMethod, Engine, FVarLinearInterpolation,
    MAX_LEVEL, Options, Request, Scheme, TriangleSubdivision, UniformOptions,
};
pub use output::{
    ChildMaps, FVarTopology, INVALID_INDEX, LevelCounts, LevelRelations, LevelTopology, Limit,
    LimitData, Refinement, Values, release_buffer_pool,
};
pub use ptex::{PtexAdjacency, PtexIndices};
pub use real::{Precision, Real};
pub use stencil::{
    LimitStencilTable, StencilInterpolation, StencilOptions, StencilTable, StencilTableF32,
};
pub use topology::Table;

/// The README's examples, compiled and run as doctests.
#[cfg(all(doctest, feature = "osd"))]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
