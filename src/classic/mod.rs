//! The classic half of subdivision: the curve and patch schemes the subject
//! starts with, and Doo-Sabin — pure mathematics on points and meshes,
//! without file I/O (points files are [`crate::io::points`], pictures
//! [`crate::io::svg`]).
//!
//! - [`curve`]: Chaikin, uniform B-splines of any degree, the four-point
//!   scheme and Jarek's curve on open and closed polygons; the uniform
//!   B-spline basis, B-spline curve evaluation and flattening.
//! - [`patch`]: tensor-product uniform B-spline control grids (biquadratic,
//!   bicubic, any degree), split and evaluated.
//! - [`nurbs`]: B-splines and NURBS over any knot vector — de Boor
//!   evaluation, knot insertion and refinement, Bézier extraction, splitting;
//!   curves and tensor-product surfaces. The uniform schemes above are its
//!   special cases (midpoint insertion).
//! - [`doo_sabin`]: Doo-Sabin refinement of polygon meshes.
//!
//! Each is re-exported at the crate root (`subdiv::curve`, `subdiv::patch`,
//! `subdiv::doo_sabin`, `subdiv::nurbs`).

pub mod curve;
pub mod doo_sabin;
pub mod nurbs;
pub mod patch;
