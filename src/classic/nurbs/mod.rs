//! B-spline and NURBS curves and surfaces over arbitrary knot vectors: the
//! general refiner the uniform schemes of [`crate::curve`] and
//! [`crate::patch`] are special cases of.
//!
//! - [`KnotVector`]: validation, domain, spans, multiplicities, and the basis
//!   functions `N_{i,d}` by the Cox–de Boor recursion with their derivatives.
//! - [`NurbsCurve`]: 2-D or 3-D ([`Point`](crate::curve::Point)), open or
//!   closed, optionally rational; evaluation by de Boor's algorithm,
//!   derivatives, sampling, knot insertion (Boehm), knot refinement (Piegl
//!   and Tiller's A5.4), Bézier decomposition, splitting.
//! - [`NurbsSurface`]: the tensor product, with the same operations along u
//!   or v, and a conversion from [`ControlGrid`](crate::patch::ControlGrid).
//!
//! Every constructor and operation validates its input and returns a typed
//! [`NurbsError`]; nothing panics on bad input.
//!
//! # Conventions
//!
//! A curve of **degree** `d ≥ 1` has `n + 1` control points `P_0..P_n` and
//! `n + d + 2` knots `u_0 ≤ u_1 ≤ … ≤ u_m`, **`m = n + d + 1`**:
//!
//! ```text
//! C(t) = Σ_{i=0..n} P_i N_{i,d}(t),      t ∈ [u_d, u_{m-d}] = [u_d, u_{n+1}]
//! ```
//!
//! `N_{i,d}` is the B-spline on the knots `u_i..u_{i+d+1}` (zero outside
//! them). The **domain** `[u_d, u_{m-d}]` is where the basis functions sum to
//! 1; a parameter outside it is refused ([`NurbsError::OutsideDomain`]). It
//! is cut into the spans `[u_k, u_{k+1})`, `d ≤ k ≤ n`; on span `k` the curve
//! depends on `P_{k-d}..P_k` only, and the last non-empty span also takes its
//! right end, so `C(u_{m-d})` is defined.
//!
//! Any non-decreasing vector is accepted: **clamped** (the first `d + 1` and
//! the last `d + 1` knots equal: the curve starts at `P_0` and ends at
//! `P_n`), **unclamped** (e.g. uniform), with interior knots repeated up to
//! `d + 1` times; at a knot of multiplicity `s` the curve is `C^{d-s}` (at
//! `s = d` it passes through a control point, at `s = d + 1` the two sides
//! need not meet). [`KnotVector::uniform`] (`u_k = k - d`) is the
//! parametrisation of [`BSplineCurve`](crate::curve::BSplineCurve).
//!
//! # Closed curves
//!
//! A closed curve has `n ≥ max(d, 2)` **distinct** control points
//! `P_0..P_{n-1}` and the **break points** `s_0 ≤ … ≤ s_n` of one period
//! `T = s_n - s_0` ([`KnotVector::periodic`], [`NurbsCurve::closed`]): the
//! periodic spline `Σ_{i ∈ ℤ} P_{i mod n} N_{i,d}(t)` over the knots
//! `u_{d+i+jn} = s_i + jT`. It is stored **wrapped**, as an ordinary curve
//! over one period: `n + d` control points, the last `d` repeating the
//! first `d` (weights likewise), and the `n + 2d + 1` knots
//! `u_{d-i} = s_{n-i} - T`, `u_{d+i} = s_i`, `u_{d+n+i} = s_i + T` (`i = 1..=d`
//! outside, `i = 0..=n` inside), domain `[s_0, s_n]`. Evaluation takes any
//! finite parameter (reduced modulo `T`); insertion inserts `t` and all its
//! images `t + jT`, so the result is closed again with `n + 1` distinct
//! points; splitting and Bézier decomposition use the open representation
//! ([`NurbsCurve::to_open`]) of one period.
//!
//! # Rational curves
//!
//! With positive weights `w_i`, `C(t) = Σ w_i P_i N_{i,d}(t) / Σ w_i N_{i,d}(t)`.
//! Every algorithm works on the **homogeneous** points `(w_i P_i, w_i)` —
//! de Boor's algorithm, Boehm's insertion and A5.4 are linear in them — and
//! the Euclidean point is the quotient; the derivatives follow by the
//! quotient rule. A curve without weights is computed the same way with
//! `w = 1`, exactly as a polynomial B-spline.
//!
//! ```
//! use glam::DVec2;
//! use subdiv::nurbs::NurbsCurve;
//!
//! // The unit circle: nine control points on the square's corners and edge
//! // midpoints, weights 1 and √2/2.
//! let h = std::f64::consts::FRAC_1_SQRT_2;
//! let p: Vec<DVec2> = [(1., 0.), (1., 1.), (0., 1.), (-1., 1.), (-1., 0.), (-1., -1.), (0., -1.), (1., -1.), (1., 0.)]
//!     .iter().map(|&(x, y)| DVec2::new(x, y)).collect();
//! let w = vec![1.0, h, 1.0, h, 1.0, h, 1.0, h, 1.0];
//! let knots = vec![0., 0., 0., 1., 1., 2., 2., 3., 3., 4., 4., 4.];
//! let circle = NurbsCurve::new(p, 2, knots, Some(w))?;
//! assert!((circle.eval(0.7)?.length() - 1.0).abs() < 1e-15);
//!
//! let finer = circle.insert(0.5)?.insert_many(&[2.25, 2.25])?;
//! assert_eq!(finer.points().len(), 12);
//! assert!((finer.eval(2.3)? - circle.eval(2.3)?).length() < 1e-15);
//! assert_eq!(circle.to_bezier()?.len(), 4);              // four quarter arcs
//! let (left, right) = circle.split(1.5)?;
//! assert_eq!((left.domain(), right.domain()), ((0.0, 1.5), (1.5, 4.0)));
//! # Ok::<(), subdiv::nurbs::NurbsError>(())
//! ```
//!
//! # The uniform schemes as special cases
//!
//! One level of the averaging scheme of degree `d` ([`crate::curve::bspline`];
//! Chaikin for `d = 2`) halves the knot spacing of the uniform B-spline
//! ([`NurbsCurve::from_bspline`]); on `n` points `P`, with `b` its output:
//!
//! - **closed**: inserting the `n` midpoints `i + 1/2` of the period's spans
//!   gives `2n` distinct points `Q` with `Q_j = b_j` for every `j`, and the
//!   break points `0, 1/2, …, n` (the uniform curve of `b` at `2t`);
//! - **open** (knots `-d..=n`, domain `[0, n - d]`): inserting the `n - d`
//!   midpoints of the domain's spans gives `2n - d` points, as many as `b`,
//!   with `Q_j = b_j` for `d - 1 ≤ j ≤ 2n - 2d`. The first and last `d - 1`
//!   differ: the scheme also halves the knot spacing outside the domain (the
//!   knots of `b` are `(k - d)/2`, from `-d/2` on), which no insertion into
//!   the domain does; both polygons describe the same curve on `[0, n - d]`.
//!   For Chaikin, `Q_0 = P_0` and `Q_{2n-3} = P_{n-1}` are the only differences.
//!
//! [`NurbsSurface::from_control_grid`] states the same for
//! [`ControlGrid`](crate::patch::ControlGrid), direction by direction.

mod basis;
mod curve;
mod error;
mod hom;
mod insert;
mod knots;
mod surface;

pub use curve::{BezierSegment, CurveDerivatives, NurbsCurve};
pub use error::NurbsError;
pub use knots::KnotVector;
pub use surface::{BezierPatch, NurbsSurface, SurfaceDerivatives};
