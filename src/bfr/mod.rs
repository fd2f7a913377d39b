//! Limit surfaces one base face at a time, the way OpenSubdiv 3.5's Bfr
//! ("base face representation") defines them.
//!
//! Bfr gives each base face its own parameterization and tessellation
//! patterns, without a global patch table:
//! - [`Parameterization`] — the (u, v) domain of a face: the unit square, the
//!   unit triangle (Loop), or quadrilateral sub-faces for the other faces of
//!   quad schemes (`Bfr::Parameterization`);
//! - [`Tessellation`] — the points and facets covering that domain at a
//!   uniform rate or a rate per edge, boundary points first so neighbouring
//!   faces can share them (`Bfr::Tessellation`);
//! - [`LimitSurfaces`] — every face's limit surface evaluated at (u, v) in
//!   its parameterization, with derivatives, and face-varying data
//!   (`Bfr::Surface::Evaluate`, through one adaptive refinement of the whole
//!   mesh with Bfr's options rather than a surface per face).
//!
//! Both are OpenSubdiv's index by index and bit for bit (checked against it
//! through the bridge in `tests/bfr_tessellation.rs`).

mod bspline_eval;
mod corner;
mod face_surface;
mod hull;
mod mesh_surfaces;
mod mesher;
pub(crate) mod parameterization;
mod plans;
mod regular;
mod surface_eval;
mod surfaces;
mod tessellation;

pub use face_surface::{Surface, SurfaceFactory};
pub use mesh_surfaces::MeshSurfaces;
pub use mesher::{FaceSurfaces, TessellateOptions, TessellatedMesh, tessellate};
pub use parameterization::{MAX_FACE_SIZE, Parameterization, ParameterizationType};
pub use surface_eval::PointDescriptor;
pub use surfaces::{LimitSurfaces, SurfaceOptions};
pub use tessellation::{CoordIndexMap, FacetSize, MAX_RATE, Tessellation, TessellationOptions};
