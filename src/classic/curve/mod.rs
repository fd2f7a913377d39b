//! Subdivision curves of the classic literature: Chaikin's corner cutting,
//! uniform B-spline refinement of any degree (the averaging algorithm), the
//! interpolating four-point scheme, Jarek's curve between the two; uniform
//! B-spline evaluation and adaptive flattening of the limit curve.
//!
//! Every function works on 2-D ([`DVec2`]) and 3-D ([`DVec3`]) points (the
//! [`Point`] trait), in `f64`, on open or closed polygons. In a closed polygon
//! indices wrap around; an open polygon is used as it is.
//!
//! # Conventions
//!
//! `P[0..n]` is the polygon. One level of:
//!
//! - **bspline, degree d ≥ 1** (the averaging algorithm of Lane and
//!   Riesenfeld): step I builds `b[2j] = P[j]`, `b[2j+1] = (P[j] + P[j+1]) / 2`;
//!   step II applies `d - 1` passes of `b'[j] = (b[j] + b[j+1]) / 2`. Closed:
//!   every index wraps and every pass keeps the count, `2n` points. Open: no
//!   wrap, step I gives `2n - 1` points and every pass drops the last one,
//!   `2n - d` points.
//! - **chaikin** (= bspline of degree 2): `Q[i] = 3/4 P[i] + 1/4 P[i+1]`,
//!   `R[i] = 1/4 P[i] + 3/4 P[i+1]`, output `Q0 R0 Q1 R1 …`; open: `2n - 2`
//!   points, the end points are not kept.
//! - **four-point** with tension `w` (1/16 by default): the old points stay and
//!   `E[i] = (1/2 + w)(P[i] + P[i+1]) - w (P[i-1] + P[i+2])` is inserted between
//!   `P[i]` and `P[i+1]` (with `w = 1/16`: `(-P[i-1] + 9 P[i] + 9 P[i+1] - P[i+2]) / 16`);
//!   output `P0 E0 P1 E1 …`. Any finite `w` is accepted: `w = 0` inserts the
//!   midpoints (the polygon itself is the limit), small positive tensions give
//!   smooth curves (Dyn, Levin and Gregory prove C¹ limit curves for
//!   `0 < w < (√5 - 1) / 8 ≈ 0.1545`; 1/16 also reproduces cubics), and larger
//!   `|w|` pushes the new points ever further out at every level.
//! - **jarek**: the midpoints `M[i] = (P[i] + P[i+1]) / 2` are inserted, then,
//!   all computed from this untweaked polygon, each old point moves a quarter
//!   of the way to the average of its two neighbouring midpoints,
//!   `P'[i] = P[i] + ((M[i-1] + M[i]) / 2 - P[i]) / 4` (half the cubic
//!   B-spline's smoothing), and each midpoint moves away from the average of its
//!   two neighbouring midpoints by an eighth of its distance from it,
//!   `M'[i] = M[i] + (M[i] - (M[i-1] + M[i+1]) / 2) / 8` (half the four-point
//!   bulge); output `P'0 M'0 P'1 M'1 …`.
//! - **open four-point and jarek** use the ghost points `P[-1] = 2 P[0] - P[1]`
//!   and `P[n] = 2 P[n-1] - P[n-2]`; the output runs `P0 M0 P1 … M[n-2] P[n-1]`
//!   (`2n - 1` points): the end points are kept (exactly: they are copied).
//!
//! A closed polygon needs at least 3 points in every scheme; an open one needs
//! `d + 1` for a B-spline of degree `d` (3 for Chaikin) and 2 for four-point
//! and Jarek ([`CurveScheme::min_points`]).
//!
//! Every refined point is finite. Midpoints are computed without overflow, so
//! the averaging schemes (B-splines, Chaikin) accept any finite coordinates;
//! four-point and Jarek extrapolate (ghost points, bulges), and a level in
//! which a coordinate would leave the range of `f64` is refused whole
//! ([`CurveError::Overflow`]) rather than returned with `inf` or `NaN`.
//!
//! # B-spline curves
//!
//! [`BSplineCurve`] is the uniform B-spline of degree `d` with control points
//! `P[j]`, parametrised so that the refined polygon of [`bspline`] describes
//! the same curve at twice the parameter:
//!
//! ```text
//! C(s) = Σ_j P[j] N_d(s + d - j)        open: s ∈ [0, n - d];  closed: s ∈ [0, n), P[j mod n]
//! ```
//!
//! where `N_d` is the cardinal B-spline on the knots `0, 1, …, d + 1`
//! ([`bspline_basis`]). Segment `i` (`s ∈ [i, i + 1]`) depends on
//! `P[i..=i+d]` only; for Chaikin (`d = 2`) it is the parabola from the
//! midpoint of edge `i` to the midpoint of edge `i + 1` with control point
//! `P[i + 1]`. If `b` is `P` refined once by [`bspline`], then
//! `C_b(2s) = C_P(s)`; after `k` levels `C_k(2^k s) = C_P(s)`.
//!
//! ```
//! use glam::DVec2;
//! use subdiv::curve::{self, BSplineCurve, CurveScheme};
//!
//! let p = [DVec2::new(0.0, 0.0), DVec2::new(1.0, 2.0), DVec2::new(3.0, 2.0), DVec2::new(4.0, 0.0)];
//! let once = curve::chaikin(&p, false)?;
//! assert_eq!(once[0], DVec2::new(0.25, 0.5));           // 3/4 P0 + 1/4 P1
//! assert_eq!(once.len(), 6);                            // 2n - 2
//!
//! let fine = curve::refine(&p, CurveScheme::BSpline { degree: 3 }, false, 3)?;
//! let c0 = BSplineCurve::new(p.to_vec(), 3, false)?;
//! let c3 = BSplineCurve::new(fine, 3, false)?;
//! assert!((c3.eval(8.0 * 0.3)? - c0.eval(0.3)?).length() < 1e-12);
//! # Ok::<(), subdiv::curve::CurveError>(())
//! ```
//!
//! # Flattening
//!
//! [`BSplineCurve::flatten`] turns the limit curve into a polyline within a
//! tolerance, splitting each segment at parameter midpoints with an explicit
//! stack; the error bound is [`flatness_bound`].
//!
//! Reading and writing points files (one point per line) is
//! [`crate::io::points`]'s job; this module is mathematics only.

use glam::{DVec2, DVec3};
use std::fmt;
use std::ops::{Add, Mul, Sub};
use thiserror::Error;

mod bspline;
pub use bspline::{BSplineCurve, Polyline, bspline_basis, flatness_bound, flatten};

/// The largest B-spline degree accepted.
pub const MAX_DEGREE: usize = 15;

/// The largest number of points a refinement or a flattening may produce.
pub const MAX_POINTS: usize = 1 << 22;

/// How deep [`BSplineCurve::flatten`] may halve one segment (2^40 pieces).
pub const MAX_FLATTEN_DEPTH: u32 = 40;

/// The default tension of the four-point scheme, 1/16.
pub const DEFAULT_TENSION: f64 = 1.0 / 16.0;

/// A point of a curve: [`DVec2`] or [`DVec3`].
pub trait Point:
    Copy
    + fmt::Debug
    + PartialEq
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<f64, Output = Self>
{
    /// The number of coordinates, 2 or 3.
    const DIM: usize;
    /// The origin.
    const ZERO: Self;
    /// The dot product.
    fn dot(self, other: Self) -> f64;
    /// The Euclidean length.
    fn length(self) -> f64 {
        self.dot(self).sqrt()
    }
    /// Whether every coordinate is finite.
    fn is_finite(self) -> bool;
    /// The point in 3-D (a 2-D point gets `z = 0`).
    fn to_dvec3(self) -> DVec3;
    /// The point with the coordinates `c` (exactly [`Self::DIM`] of them).
    fn from_coords(c: &[f64]) -> Option<Self>;
    /// The coordinates, [`Self::DIM`] of them.
    fn coords(self) -> Vec<f64>;
}

impl Point for DVec2 {
    const DIM: usize = 2;
    const ZERO: Self = DVec2::ZERO;
    fn dot(self, other: Self) -> f64 {
        DVec2::dot(self, other)
    }
    fn is_finite(self) -> bool {
        DVec2::is_finite(self)
    }
    fn to_dvec3(self) -> DVec3 {
        self.extend(0.0)
    }
    fn from_coords(c: &[f64]) -> Option<Self> {
        match c {
            &[x, y] => Some(DVec2::new(x, y)),
            _ => None,
        }
    }
    fn coords(self) -> Vec<f64> {
        self.to_array().to_vec()
    }
}

impl Point for DVec3 {
    const DIM: usize = 3;
    const ZERO: Self = DVec3::ZERO;
    fn dot(self, other: Self) -> f64 {
        DVec3::dot(self, other)
    }
    fn is_finite(self) -> bool {
        DVec3::is_finite(self)
    }
    fn to_dvec3(self) -> DVec3 {
        self
    }
    fn from_coords(c: &[f64]) -> Option<Self> {
        match c {
            &[x, y, z] => Some(DVec3::new(x, y, z)),
            _ => None,
        }
    }
    fn coords(self) -> Vec<f64> {
        self.to_array().to_vec()
    }
}

/// A curve subdivision scheme.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CurveScheme {
    /// Chaikin's corner cutting (the quadratic B-spline).
    Chaikin,
    /// Uniform B-spline refinement of the given degree (the averaging algorithm).
    BSpline {
        /// The degree, `1..=MAX_DEGREE`.
        degree: usize,
    },
    /// The interpolating four-point scheme (Dyn, Levin and Gregory).
    FourPoint {
        /// The tension `w`, any finite number; [`DEFAULT_TENSION`] = 1/16 is the
        /// classic scheme, and `0 < w < (√5 - 1) / 8` gives C¹ limit curves
        /// (see the [module documentation](self)).
        tension: f64,
    },
    /// Jarek Rossignac's curve: half way between the cubic B-spline and the four-point scheme.
    Jarek,
}

impl CurveScheme {
    /// The four-point scheme with the classic tension 1/16.
    pub fn four_point() -> Self {
        CurveScheme::FourPoint {
            tension: DEFAULT_TENSION,
        }
    }

    /// The B-spline scheme of degree `degree`.
    pub fn bspline(degree: usize) -> Self {
        CurveScheme::BSpline { degree }
    }

    /// The name used on the command line: `chaikin`, `bspline`, `four-point` or `jarek`.
    pub fn name(&self) -> &'static str {
        match self {
            CurveScheme::Chaikin => "chaikin",
            CurveScheme::BSpline { .. } => "bspline",
            CurveScheme::FourPoint { .. } => "four-point",
            CurveScheme::Jarek => "jarek",
        }
    }

    /// The degree of the limit curve when it is a uniform B-spline (Chaikin: 2).
    pub fn limit_degree(&self) -> Option<usize> {
        match *self {
            CurveScheme::Chaikin => Some(2),
            CurveScheme::BSpline { degree } => Some(degree),
            _ => None,
        }
    }

    /// Checks the scheme's parameters (degree `1..=MAX_DEGREE`, finite tension).
    ///
    /// A finite but huge tension passes; the refinement then refuses the
    /// first level that overflows ([`CurveError::Overflow`]).
    pub fn check(&self) -> Result<(), CurveError> {
        match *self {
            CurveScheme::BSpline { degree } if !(1..=MAX_DEGREE).contains(&degree) => {
                Err(CurveError::BadDegree { degree })
            }
            CurveScheme::FourPoint { tension } if !tension.is_finite() => {
                Err(CurveError::BadTension(tension))
            }
            _ => Ok(()),
        }
    }

    /// The fewest points the scheme accepts: 3 for any closed polygon; open:
    /// `d + 1` for a B-spline of degree `d` (3 for Chaikin), 2 for four-point and Jarek.
    pub fn min_points(&self, closed: bool) -> usize {
        if closed {
            return 3;
        }
        match *self {
            CurveScheme::Chaikin => 3,
            CurveScheme::BSpline { degree } => degree.saturating_add(1),
            CurveScheme::FourPoint { .. } | CurveScheme::Jarek => 2,
        }
    }

    /// The number of points one level makes of `n`: `2n` closed; open `2n - d`
    /// (B-spline of degree `d`), `2n - 2` (Chaikin), `2n - 1` (four-point, Jarek).
    ///
    /// Only meaningful for `n >= self.min_points(closed)`.
    pub fn refined_len(&self, n: usize, closed: bool) -> usize {
        let twice = n.saturating_mul(2);
        if closed {
            return twice;
        }
        match *self {
            CurveScheme::Chaikin => twice.saturating_sub(2),
            CurveScheme::BSpline { degree } => twice.saturating_sub(degree),
            CurveScheme::FourPoint { .. } | CurveScheme::Jarek => twice.saturating_sub(1),
        }
    }
}

impl fmt::Display for CurveScheme {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            CurveScheme::BSpline { degree } => write!(f, "bspline of degree {degree}"),
            CurveScheme::FourPoint { tension } if tension != DEFAULT_TENSION => {
                write!(f, "four-point with tension {}", Num(tension))
            }
            _ => f.write_str(self.name()),
        }
    }
}

/// A number in a message: as Rust writes it, or in exponent form when it is
/// very large or very small (`1e300` rather than 301 digits).
struct Num(f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let a = self.0.abs();
        if a == 0.0 || !a.is_finite() || (1e-4..1e16).contains(&a) {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

/// Why a curve operation was refused.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum CurveError {
    /// The polygon has fewer points than the scheme needs.
    #[error("{scheme} on {} polygon needs at least {needed} points, got {got}", if *.closed { "a closed" } else { "an open" })]
    TooFewPoints {
        /// The scheme's name.
        scheme: &'static str,
        /// Whether the polygon is closed.
        closed: bool,
        /// The fewest points accepted.
        needed: usize,
        /// The number of points given.
        got: usize,
    },
    /// A B-spline degree outside `1..=MAX_DEGREE`.
    #[error("B-spline degree {degree} is not supported (expected 1 to {MAX_DEGREE})")]
    BadDegree {
        /// The degree asked for.
        degree: usize,
    },
    /// A four-point tension that is not a finite number.
    #[error("four-point tension {0} is not a finite number")]
    BadTension(f64),
    /// An input point with a NaN or infinite coordinate.
    #[error("point {index} has a non-finite coordinate")]
    NonFinitePoint {
        /// The index of the point.
        index: usize,
    },
    /// A refined point would have a coordinate beyond the range of `f64`
    /// (±1.8e308): the input's coordinates (or the four-point tension) are too
    /// large for the scheme, which extrapolates. Nothing is returned.
    #[error(
        "level {level} of {scheme} overflows: its point {index} would have a coordinate beyond the range of f64 ({})",
        if matches!(scheme, CurveScheme::FourPoint { .. }) {
            "the coordinates or the tension are too large"
        } else {
            "the coordinates are too large"
        }
    )]
    Overflow {
        /// The scheme.
        scheme: CurveScheme,
        /// The level (1 for the first refinement).
        level: u32,
        /// The index of the first such point in that level.
        index: usize,
    },
    /// The result would have more than [`MAX_POINTS`] points.
    #[error("the result would have more than {MAX_POINTS} points")]
    TooManyPoints,
    /// A flattening tolerance that is not a positive finite number.
    #[error("tolerance {} is not a positive finite number", Num(*.0))]
    BadTolerance(f64),
    /// The tolerance is not reached after [`MAX_FLATTEN_DEPTH`] halvings (it is
    /// below the rounding error of the curve's coordinates).
    #[error(
        "tolerance {} is not reached after {MAX_FLATTEN_DEPTH} halvings of segment {segment} (it is below the rounding error)",
        Num(*.tolerance)
    )]
    ToleranceTooSmall {
        /// The tolerance.
        tolerance: f64,
        /// The segment that could not be flattened.
        segment: usize,
    },
    /// Flattening needs a limit curve in closed form: Chaikin or a B-spline.
    #[error("{scheme} has no closed-form limit curve; only chaikin and bspline can be flattened")]
    NoClosedFormLimit {
        /// The scheme's name.
        scheme: &'static str,
    },
    /// An open curve evaluated outside its parameter domain.
    #[error("parameter {s} is outside the curve's domain [{min}, {max}]")]
    ParameterOutOfRange {
        /// The parameter.
        s: f64,
        /// The domain's start.
        min: f64,
        /// The domain's end.
        max: f64,
    },
}

fn check_points<P: Point>(
    points: &[P],
    scheme: &CurveScheme,
    closed: bool,
) -> Result<(), CurveError> {
    scheme.check()?;
    let needed = scheme.min_points(closed);
    if points.len() < needed {
        return Err(CurveError::TooFewPoints {
            scheme: scheme.name(),
            closed,
            needed,
            got: points.len(),
        });
    }
    if let Some(index) = points.iter().position(|p| !p.is_finite()) {
        return Err(CurveError::NonFinitePoint { index });
    }
    Ok(())
}

/// The midpoint `(a + b) / 2`, without overflow: where `a + b` overflows
/// (coordinates beyond ±f64::MAX / 2), that coordinate is `a / 2 + b / 2`.
/// Everywhere else the result is exactly `(a + b) * 0.5`.
fn mid<P: Point>(a: P, b: P) -> P {
    let m = (a + b) * 0.5;
    if m.is_finite() || !(a.is_finite() && b.is_finite()) {
        return m;
    }
    let safe: Vec<f64> = a
        .coords()
        .into_iter()
        .zip(b.coords())
        .map(|(x, y)| {
            let m = (x + y) * 0.5;
            if m.is_finite() { m } else { x * 0.5 + y * 0.5 }
        })
        .collect();
    P::from_coords(&safe).unwrap_or(m)
}

/// `points`, level `level` of `scheme`, or [`CurveError::Overflow`] when one
/// of them has a coordinate that is not finite.
fn finite_level<P: Point>(
    points: Vec<P>,
    scheme: CurveScheme,
    level: u32,
) -> Result<Vec<P>, CurveError> {
    match points.iter().position(|p| !p.is_finite()) {
        Some(index) => Err(CurveError::Overflow {
            scheme,
            level,
            index,
        }),
        None => Ok(points),
    }
}

/// One level of uniform B-spline refinement of degree `degree` (the averaging
/// algorithm; see the [module documentation](self) for the exact convention).
///
/// ```
/// use glam::DVec2;
/// let p = [DVec2::new(0.0, 0.0), DVec2::new(4.0, 0.0), DVec2::new(4.0, 4.0), DVec2::new(0.0, 4.0)];
/// let q = subdiv::curve::bspline(&p, 3, true)?;
/// // Cubic: old points become (P[i-1] + 6 P[i] + P[i+1]) / 8, edge points midpoints.
/// assert_eq!(q.len(), 8);
/// assert_eq!(q[0], DVec2::new(2.0, 0.0));   // the midpoint of edge 0
/// assert_eq!(q[1], DVec2::new(3.5, 0.5));   // (P0 + 6 P1 + P2) / 8
/// # Ok::<(), subdiv::curve::CurveError>(())
/// ```
pub fn bspline<P: Point>(points: &[P], degree: usize, closed: bool) -> Result<Vec<P>, CurveError> {
    let scheme = CurveScheme::BSpline { degree };
    check_points(points, &scheme, closed)?;
    finite_level(bspline_step(points, degree, closed), scheme, 1)
}

/// [`bspline`] without the checks (`points.len() >= min_points`, `degree >= 1`).
pub(crate) fn bspline_step<P: Point>(points: &[P], degree: usize, closed: bool) -> Vec<P> {
    let n = points.len();
    let mut b = Vec::with_capacity(2 * n);
    for j in 0..n {
        b.push(points[j]);
        if j + 1 < n {
            b.push(mid(points[j], points[j + 1]));
        } else if closed {
            b.push(mid(points[j], points[0]));
        }
    }
    for _ in 1..degree {
        let m = b.len();
        if closed {
            let first = b[0];
            for j in 0..m - 1 {
                b[j] = mid(b[j], b[j + 1]);
            }
            b[m - 1] = mid(b[m - 1], first);
        } else {
            for j in 0..m - 1 {
                b[j] = mid(b[j], b[j + 1]);
            }
            b.pop();
        }
    }
    b
}

/// One level of Chaikin's corner cutting: `Q[i] = 3/4 P[i] + 1/4 P[i+1]`,
/// `R[i] = 1/4 P[i] + 3/4 P[i+1]`, output `Q0 R0 Q1 R1 …` (`2n - 2` points open, `2n` closed).
///
/// ```
/// use glam::DVec2;
/// let q = subdiv::curve::chaikin(&[DVec2::ZERO, DVec2::new(4.0, 0.0), DVec2::new(4.0, 8.0)], false)?;
/// assert_eq!(q, [DVec2::new(1.0, 0.0), DVec2::new(3.0, 0.0), DVec2::new(4.0, 2.0), DVec2::new(4.0, 6.0)]);
/// # Ok::<(), subdiv::curve::CurveError>(())
/// ```
pub fn chaikin<P: Point>(points: &[P], closed: bool) -> Result<Vec<P>, CurveError> {
    check_points(points, &CurveScheme::Chaikin, closed)?;
    finite_level(chaikin_step(points, closed), CurveScheme::Chaikin, 1)
}

fn chaikin_step<P: Point>(points: &[P], closed: bool) -> Vec<P> {
    let n = points.len();
    let edges = if closed { n } else { n - 1 };
    let mut out = Vec::with_capacity(2 * edges);
    for i in 0..edges {
        let (a, b) = (points[i], points[(i + 1) % n]);
        out.push(a * 0.75 + b * 0.25);
        out.push(a * 0.25 + b * 0.75);
    }
    out
}

/// The polygon with the ghost points `2 P[0] - P[1]` and `2 P[n-1] - P[n-2]`
/// added at the ends (open) or with the wrapped neighbours (closed): `ext[i + 1] = P[i]`.
fn extended<P: Point>(points: &[P], closed: bool) -> Vec<P> {
    let n = points.len();
    let mut ext = Vec::with_capacity(n + 3);
    if closed {
        ext.push(points[n - 1]);
        ext.extend_from_slice(points);
        ext.push(points[0]);
        ext.push(points[1]);
    } else {
        ext.push(points[0] * 2.0 - points[1]);
        ext.extend_from_slice(points);
        ext.push(points[n - 1] * 2.0 - points[n - 2]);
    }
    ext
}

/// One level of the four-point scheme with tension `tension` (1/16 is the
/// classic scheme): old points stay, `E[i] = (1/2 + w)(P[i] + P[i+1]) - w (P[i-1] + P[i+2])`
/// is inserted after `P[i]`. Open polygons use the ghost points
/// `2 P[0] - P[1]` and `2 P[n-1] - P[n-2]` and keep their end points.
///
/// ```
/// use glam::DVec2;
/// let p = [DVec2::new(0.0, 0.0), DVec2::new(16.0, 0.0), DVec2::new(32.0, 16.0), DVec2::new(48.0, 16.0)];
/// let q = subdiv::curve::four_point(&p, subdiv::curve::DEFAULT_TENSION, false)?;
/// assert_eq!(q.len(), 7);
/// assert_eq!(q[2], p[1]);
/// // (-P0 + 9 P1 + 9 P2 - P3) / 16
/// assert_eq!(q[3], DVec2::new(24.0, 8.0));
/// # Ok::<(), subdiv::curve::CurveError>(())
/// ```
pub fn four_point<P: Point>(
    points: &[P],
    tension: f64,
    closed: bool,
) -> Result<Vec<P>, CurveError> {
    let scheme = CurveScheme::FourPoint { tension };
    check_points(points, &scheme, closed)?;
    finite_level(four_point_step(points, tension, closed), scheme, 1)
}

fn four_point_step<P: Point>(points: &[P], w: f64, closed: bool) -> Vec<P> {
    let n = points.len();
    let ext = extended(points, closed);
    let edges = if closed { n } else { n - 1 };
    let mut out = Vec::with_capacity(2 * n);
    for i in 0..edges {
        out.push(points[i]);
        let (pm, p0, p1, p2) = (ext[i], ext[i + 1], ext[i + 2], ext[i + 3]);
        out.push((p0 + p1) * (0.5 + w) - (pm + p2) * w);
    }
    if !closed {
        out.push(points[n - 1]);
    }
    out
}

/// One level of Jarek's curve: midpoints inserted, old points moved a quarter
/// of the way to the average of their neighbouring midpoints, midpoints moved
/// away from the average of their neighbouring midpoints by an eighth of the
/// distance (see the [module documentation](self)). Open polygons use the
/// ghost points and keep their end points.
///
/// ```
/// use glam::DVec2;
/// let p = [DVec2::new(0.0, 0.0), DVec2::new(16.0, 0.0), DVec2::new(16.0, 16.0), DVec2::new(0.0, 16.0)];
/// let q = subdiv::curve::jarek(&p, true)?;
/// // P1 + ((M0 + M1) / 2 - P1) / 4 with M0 = (8, 0), M1 = (16, 8)
/// assert_eq!(q[2], DVec2::new(15.0, 1.0));
/// // M0 + (M0 - (M3 + M1) / 2) / 8 with M3 = (0, 8)
/// assert_eq!(q[1], DVec2::new(8.0, -1.0));
/// # Ok::<(), subdiv::curve::CurveError>(())
/// ```
pub fn jarek<P: Point>(points: &[P], closed: bool) -> Result<Vec<P>, CurveError> {
    check_points(points, &CurveScheme::Jarek, closed)?;
    finite_level(jarek_step(points, closed), CurveScheme::Jarek, 1)
}

fn jarek_step<P: Point>(points: &[P], closed: bool) -> Vec<P> {
    let n = points.len();
    let ext = extended(points, closed);
    // m[k] = midpoint of ext[k], ext[k+1]: m[0] = M[-1], m[i + 1] = M[i].
    let m: Vec<P> = ext.windows(2).map(|w| mid(w[0], w[1])).collect();
    let edges = if closed { n } else { n - 1 };
    let mut out = Vec::with_capacity(2 * n);
    for i in 0..n {
        let p = points[i];
        let moved = p + (mid(m[i], m[i + 1]) - p) * 0.25;
        out.push(if !closed && (i == 0 || i == n - 1) {
            p
        } else {
            moved
        });
        if i < edges {
            let mi = m[i + 1];
            out.push(mi + (mi - mid(m[i], m[i + 2])) * 0.125);
        }
    }
    out
}

/// One level of `scheme`.
pub fn refine_once<P: Point>(
    points: &[P],
    scheme: CurveScheme,
    closed: bool,
) -> Result<Vec<P>, CurveError> {
    check_points(points, &scheme, closed)?;
    finite_level(step(points, scheme, closed), scheme, 1)
}

fn step<P: Point>(points: &[P], scheme: CurveScheme, closed: bool) -> Vec<P> {
    match scheme {
        CurveScheme::Chaikin => chaikin_step(points, closed),
        CurveScheme::BSpline { degree } => bspline_step(points, degree, closed),
        CurveScheme::FourPoint { tension } => four_point_step(points, tension, closed),
        CurveScheme::Jarek => jarek_step(points, closed),
    }
}

/// The number of points after `levels` levels of `scheme` applied to `n`
/// points, or [`CurveError::TooManyPoints`] above [`MAX_POINTS`].
pub fn refined_count(
    n: usize,
    scheme: CurveScheme,
    closed: bool,
    levels: u32,
) -> Result<usize, CurveError> {
    let mut count = n;
    for _ in 0..levels {
        count = scheme.refined_len(count, closed);
        if count > MAX_POINTS {
            return Err(CurveError::TooManyPoints);
        }
    }
    Ok(count)
}

/// The polygon after `levels` levels of `scheme` (`levels = 0` returns a copy).
///
/// A level with a coordinate beyond the range of `f64` is
/// [`CurveError::Overflow`] (four-point and Jarek on huge coordinates, or a
/// huge four-point tension).
///
/// ```
/// use glam::DVec3;
/// use subdiv::curve::{refine, CurveScheme};
/// let p = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// assert_eq!(refine(&p, CurveScheme::four_point(), true, 3)?.len(), 24);
/// assert_eq!(refine(&p, CurveScheme::Chaikin, false, 2)?.len(), 6); // 3 → 4 → 6
/// # Ok::<(), subdiv::curve::CurveError>(())
/// ```
pub fn refine<P: Point>(
    points: &[P],
    scheme: CurveScheme,
    closed: bool,
    levels: u32,
) -> Result<Vec<P>, CurveError> {
    let mut all = refine_levels(points, scheme, closed, levels)?;
    Ok(all.pop().unwrap_or_default())
}

/// Every level from 0 (the input) to `levels`: `levels + 1` polygons, all
/// finite ([`CurveError::Overflow`] names the first level that is not).
pub fn refine_levels<P: Point>(
    points: &[P],
    scheme: CurveScheme,
    closed: bool,
    levels: u32,
) -> Result<Vec<Vec<P>>, CurveError> {
    check_points(points, &scheme, closed)?;
    refined_count(points.len(), scheme, closed, levels)?;
    let mut all = vec![points.to_vec()];
    for level in 1..=levels {
        let next = step(all.last().map_or(&[][..], Vec::as_slice), scheme, closed);
        all.push(finite_level(next, scheme, level)?);
    }
    Ok(all)
}
