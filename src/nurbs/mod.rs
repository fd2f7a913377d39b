//! B-spline and NURBS curves and surfaces over arbitrary knot vectors (in
//! progress): knot vectors and the basis functions.
//!
//! [`KnotVector`]: validation, domain, spans, multiplicities, and the basis
//! functions `N_{i,d}` by the Cox–de Boor recursion with their derivatives.
//! Knots `u_0 ≤ … ≤ u_m` of degree `d`, `m = n + d + 1` for `n + 1` control
//! points, domain `[u_d, u_{m-d}]`.

mod basis;
mod error;
mod knots;

pub use error::NurbsError;
pub use knots::KnotVector;
