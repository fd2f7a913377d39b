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
//! # Text files
//!
//! [`parse_points`], [`read_points`], [`format_points`] and [`write_points`]
//! read and write one point per line (2 or 3 numbers, `#` starts a comment).

use glam::{DVec2, DVec3};
use std::fmt;
use std::ops::{Add, Mul, Sub};
use std::path::{Path, PathBuf};
use thiserror::Error;

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

// ---------------------------------------------------------------------------
// B-spline basis and evaluation
// ---------------------------------------------------------------------------

/// The uniform (cardinal) B-spline of degree `degree` on the knots
/// `0, 1, …, degree + 1`, from its truncated-power definition:
///
/// ```text
/// N_d(x) = 1/d! Σ_{k=0}^{d+1} (-1)^k C(d+1, k) (x - k)_+^d
/// ```
///
/// with `(y)_+^d = y^d` for `y ≥ 0` and 0 otherwise (`(y)_+^0 = 1` for `y ≥ 0`).
/// The support is `[0, d + 1)`; outside it (and for NaN) the value is 0. For
/// `d ≥ 1` the symmetry `N_d(x) = N_d(d + 1 - x)` is used to evaluate on the
/// half `x ≤ (d + 1) / 2`, which keeps the cancellation in the alternating sum small.
///
/// ```
/// use subdiv::curve::bspline_basis;
/// assert_eq!(bspline_basis(1, 0.5), 0.5);                  // the hat function
/// assert_eq!(bspline_basis(2, 1.5), 0.75);                 // quadratic peak
/// assert!((bspline_basis(3, 2.0) - 2.0 / 3.0).abs() < 1e-15); // cubic at its centre
/// ```
pub fn bspline_basis(degree: usize, x: f64) -> f64 {
    let d1 = (degree + 1) as f64;
    if !(x >= 0.0 && x < d1) {
        return 0.0;
    }
    let x = if degree > 0 && x > d1 / 2.0 {
        d1 - x
    } else {
        x
    };
    let mut sum = 0.0;
    let mut binom = 1.0; // C(d+1, k)
    let mut k = 0usize;
    while k <= degree + 1 && (k as f64) <= x {
        let y = x - k as f64;
        let term = binom * y.powi(degree as i32);
        if k % 2 == 0 {
            sum += term;
        } else {
            sum -= term;
        }
        binom = binom * (degree + 1 - k) as f64 / (k + 1) as f64;
        k += 1;
    }
    let factorial: f64 = (1..=degree).map(|i| i as f64).product();
    sum / factorial
}

/// A uniform B-spline curve of any degree, open or closed (periodic):
/// `C(s) = Σ_j P[j] N_d(s + d - j)`, see the [module documentation](self).
#[derive(Debug, Clone, PartialEq)]
pub struct BSplineCurve<P: Point> {
    points: Vec<P>,
    degree: usize,
    closed: bool,
}

/// A polyline approximating a curve, with the curve parameter of each point.
#[derive(Debug, Clone, PartialEq)]
pub struct Polyline<P: Point> {
    /// The points (a closed polyline does not repeat its first point).
    pub points: Vec<P>,
    /// The curve parameter of each point.
    pub params: Vec<f64>,
    /// Whether the polyline is closed (its last point joins its first).
    pub closed: bool,
}

impl<P: Point> BSplineCurve<P> {
    /// The B-spline of degree `degree` with control points `points`; needs
    /// `degree + 1` points open, 3 closed.
    pub fn new(points: Vec<P>, degree: usize, closed: bool) -> Result<Self, CurveError> {
        check_points(&points, &CurveScheme::BSpline { degree }, closed)?;
        Ok(BSplineCurve {
            points,
            degree,
            closed,
        })
    }

    /// The control points.
    pub fn points(&self) -> &[P] {
        &self.points
    }

    /// The degree.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// Whether the curve is closed.
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// The number of polynomial segments: `n - d` open, `n` closed.
    pub fn segment_count(&self) -> usize {
        if self.closed {
            self.points.len()
        } else {
            self.points.len() - self.degree
        }
    }

    /// The parameter domain `[0, segment_count()]` (closed: the period).
    pub fn domain(&self) -> (f64, f64) {
        (0.0, self.segment_count() as f64)
    }

    /// The Greville abscissa of control point `j`, `j - (d - 1) / 2`: the
    /// parameter the control point approaches under refinement. It lies
    /// outside the domain for the first and last `(d - 1) / 2` points of an open curve.
    pub fn greville(&self, j: usize) -> f64 {
        j as f64 - (self.degree as f64 - 1.0) / 2.0
    }

    /// The same curve with half the knot spacing: the control polygon refined
    /// once by [`bspline`], with `refined.eval(2 s) = self.eval(s)`.
    pub fn refine(&self) -> Result<Self, CurveError> {
        refined_count(
            self.points.len(),
            CurveScheme::BSpline {
                degree: self.degree,
            },
            self.closed,
            1,
        )?;
        Ok(BSplineCurve {
            points: bspline_step(&self.points, self.degree, self.closed),
            degree: self.degree,
            closed: self.closed,
        })
    }

    /// The first control point of the segment containing `s` and the local
    /// parameter `t ∈ [0, 1]`.
    fn locate(&self, s: f64) -> Result<(usize, f64), CurveError> {
        let (min, max) = self.domain();
        if self.closed {
            if !s.is_finite() {
                return Err(CurveError::ParameterOutOfRange { s, min, max });
            }
            let u = s.rem_euclid(max);
            let i = (u.floor() as usize).min(self.points.len() - 1);
            Ok((i, u - i as f64))
        } else {
            if !(s >= min && s <= max) {
                return Err(CurveError::ParameterOutOfRange { s, min, max });
            }
            let i = (s.floor() as usize).min(self.segment_count() - 1);
            Ok((i, s - i as f64))
        }
    }

    /// The curve point at `s`, as the sum of the control points weighted by
    /// [`bspline_basis`]. Closed curves take any finite `s` (period `n`); open
    /// curves refuse `s` outside [`domain`](Self::domain).
    pub fn eval(&self, s: f64) -> Result<P, CurveError> {
        let (i, t) = self.locate(s)?;
        let n = self.points.len();
        let d = self.degree;
        let mut sum = P::ZERO;
        for m in 0..=d {
            let w = bspline_basis(d, t + (d - m) as f64);
            sum = sum + self.points[(i + m) % n] * w;
        }
        Ok(sum)
    }

    /// The Bézier control points (degree `d`, `d + 1` of them) of segment `seg`
    /// (`s ∈ [seg, seg + 1]`), from the blossom: control point `P[seg + m]` is
    /// the blossom value at the knots `m - d + 1, …, m`, and the `k`-th Bézier
    /// point is the blossom at `0` (`d - k` times) and `1` (`k` times).
    /// `None` when `seg >= segment_count()`.
    pub fn segment_bezier(&self, seg: usize) -> Option<Vec<P>> {
        if seg >= self.segment_count() {
            return None;
        }
        Some(self.bezier(seg))
    }

    fn bezier(&self, seg: usize) -> Vec<P> {
        let d = self.degree;
        let n = self.points.len();
        let ctrl: Vec<P> = (0..=d).map(|m| self.points[(seg + m) % n]).collect();
        (0..=d).map(|k| blossom(&ctrl, k)).collect()
    }

    /// The limit curve as a polyline whose distance from the curve is at most
    /// `tolerance`.
    ///
    /// Each segment is converted to Bézier form ([`segment_bezier`](Self::segment_bezier))
    /// and pushed on an explicit stack; a popped piece whose
    /// [`flatness_bound`] is at most `tolerance` is replaced by its chord
    /// (its end point is emitted), any other piece is split at its parameter
    /// midpoint by de Casteljau's construction and both halves are pushed
    /// (the classic recursive midpoint construction of Chaikin's curve, without
    /// recursion). Every chord is therefore within `tolerance` of its piece of
    /// curve in the parametric sense (`|C(s) - L(s)| ≤ tolerance` for the
    /// chord `L` parametrised linearly over the same interval), so the
    /// Hausdorff distance between the polyline and the curve is at most
    /// `tolerance`. For Chaikin (degree 2) the bound is the exact largest
    /// deviation, so no piece is split that did not need it.
    ///
    /// Open curves give a polyline from `C(0)` to `C(n - d)`; closed curves a
    /// closed polyline starting at `C(0)`.
    ///
    /// ```
    /// use glam::DVec2;
    /// use subdiv::curve::BSplineCurve;
    /// let c = BSplineCurve::new(vec![DVec2::ZERO, DVec2::new(1.0, 1.0), DVec2::new(2.0, 0.0)], 2, false)?;
    /// // One parabola from (0.5, 0.5) to (1.5, 0.5) bulging 1/4 towards (1, 1):
    /// assert_eq!(c.flatten(0.3)?.points.len(), 2);
    /// assert_eq!(c.flatten(0.2)?.points.len(), 3);      // one split: deviation 1/16
    /// assert_eq!(c.flatten(0.05)?.points.len(), 5);     // 1/64 after two
    /// # Ok::<(), subdiv::curve::CurveError>(())
    /// ```
    pub fn flatten(&self, tolerance: f64) -> Result<Polyline<P>, CurveError> {
        if !(tolerance > 0.0 && tolerance.is_finite()) {
            return Err(CurveError::BadTolerance(tolerance));
        }
        let segments = self.segment_count();
        let first = self.bezier(0)[0];
        let mut points = vec![first];
        let mut params = vec![0.0];
        let mut stack: Vec<(Vec<P>, f64, f64, u32)> = Vec::new();
        for seg in 0..segments {
            stack.push((self.bezier(seg), seg as f64, (seg + 1) as f64, 0));
            while let Some((ctrl, t0, t1, depth)) = stack.pop() {
                if flatness_bound(&ctrl) <= tolerance {
                    if points.len() >= MAX_POINTS {
                        return Err(CurveError::TooManyPoints);
                    }
                    points.push(ctrl[ctrl.len() - 1]);
                    params.push(t1);
                } else if depth >= MAX_FLATTEN_DEPTH {
                    return Err(CurveError::ToleranceTooSmall {
                        tolerance,
                        segment: seg,
                    });
                } else {
                    let (left, right) = split_half(&ctrl);
                    let tm = 0.5 * (t0 + t1);
                    stack.push((right, tm, t1, depth + 1));
                    stack.push((left, t0, tm, depth + 1));
                }
            }
        }
        if self.closed {
            // The last chord ends at C(n) = C(0), the first point.
            points.pop();
            params.pop();
        }
        Ok(Polyline {
            points,
            params,
            closed: self.closed,
        })
    }
}

/// The blossom of one segment's `d + 1` control points at `0` (`d - ones`
/// times) and `1` (`ones` times), by de Boor's algorithm on the knots `t_k = k - d`.
fn blossom<P: Point>(ctrl: &[P], ones: usize) -> P {
    let d = ctrl.len() - 1;
    let mut w = ctrl.to_vec();
    for r in 1..=d {
        let u = if r <= ones { 1.0 } else { 0.0 };
        for m in (r..=d).rev() {
            let alpha = (u - m as f64 + d as f64) / (d + 1 - r) as f64;
            w[m] = w[m - 1] * (1.0 - alpha) + w[m] * alpha;
        }
    }
    w[d]
}

/// De Casteljau's split of a Bézier curve at `t = 1/2`.
fn split_half<P: Point>(ctrl: &[P]) -> (Vec<P>, Vec<P>) {
    let d = ctrl.len() - 1;
    let mut w = ctrl.to_vec();
    let mut left = Vec::with_capacity(d + 1);
    let mut right = Vec::with_capacity(d + 1);
    left.push(w[0]);
    right.push(w[d]);
    for r in 1..=d {
        for i in 0..=d - r {
            w[i] = mid(w[i], w[i + 1]);
        }
        left.push(w[0]);
        right.push(w[d - r]);
    }
    right.reverse();
    (left, right)
}

/// An upper bound of `max_t |B(t) - L(t)|` for the Bézier curve `B` with the
/// control points `ctrl` and its chord `L(t) = (1 - t) b_0 + t b_d`: the
/// smaller of
///
/// 1. `max_i |b_i - ((1 - i/d) b_0 + (i/d) b_d)|`, because
///    `B(t) - L(t) = Σ_i B_i^d(t) (b_i - l_i)` (the chord, degree-elevated,
///    has the control points `l_i`) is a convex combination of these vectors;
/// 2. `d (d - 1) / 8 · max_i |b_i - 2 b_{i+1} + b_{i+2}|`, because
///    `e = B - L` vanishes at 0 and 1, `e'' = B'' = d (d - 1) Σ_i B_i^{d-2} Δ²b_i`
///    and `e(t) = -∫ G(t, τ) e''(τ) dτ` with Green's function `G ≥ 0`,
///    `∫ G(t, τ) dτ = t (1 - t) / 2 ≤ 1/8`.
///
/// The bound is parametric, so the curve is within it of the chord and the
/// chord within it of the curve. For a quadratic (Chaikin) it is exact:
/// `B(t) - L(t) = 2 t (1 - t) (b_1 - (b_0 + b_2) / 2)` reaches
/// `|b_0 - 2 b_1 + b_2| / 4` at `t = 1/2`. Lines (`d ≤ 1`) give 0.
///
/// Coordinates so large that the squared lengths overflow (beyond about
/// 1e154) are measured at a scale of 2^-600 (exact), then scaled back.
pub fn flatness_bound<P: Point>(ctrl: &[P]) -> f64 {
    let bound = unscaled_flatness_bound(ctrl);
    if bound.is_finite() || !ctrl.iter().all(|p| p.is_finite()) {
        return bound;
    }
    const SCALE: f64 = f64::from_bits((1023 - 600) << 52); // 2^-600
    let small: Vec<P> = ctrl.iter().map(|&p| p * SCALE).collect();
    unscaled_flatness_bound(&small) / SCALE
}

fn unscaled_flatness_bound<P: Point>(ctrl: &[P]) -> f64 {
    let n = ctrl.len();
    if n < 3 {
        return 0.0;
    }
    let d = (n - 1) as f64;
    let (a, b) = (ctrl[0], ctrl[n - 1]);
    let hull = ctrl
        .iter()
        .enumerate()
        .map(|(i, &p)| {
            let t = i as f64 / d;
            (p - (a * (1.0 - t) + b * t)).length()
        })
        .fold(0.0, f64::max);
    let second = ctrl
        .windows(3)
        .map(|w| (w[0] - w[1] * 2.0 + w[2]).length())
        .fold(0.0, f64::max)
        * d
        * (d - 1.0)
        / 8.0;
    hull.min(second)
}

/// The limit curve of `points` under `scheme` (Chaikin or a B-spline) as a
/// polyline within `tolerance` of it: [`BSplineCurve::flatten`].
pub fn flatten<P: Point>(
    points: &[P],
    scheme: CurveScheme,
    closed: bool,
    tolerance: f64,
) -> Result<Polyline<P>, CurveError> {
    let degree = scheme.limit_degree().ok_or(CurveError::NoClosedFormLimit {
        scheme: scheme.name(),
    })?;
    check_points(points, &scheme, closed)?;
    BSplineCurve::new(points.to_vec(), degree, closed)?.flatten(tolerance)
}

// ---------------------------------------------------------------------------
// Text files: one point per line
// ---------------------------------------------------------------------------

/// Points read from a text file: all 2-D or all 3-D.
#[derive(Debug, Clone, PartialEq)]
pub enum Points {
    /// Two numbers per line.
    Planar(Vec<DVec2>),
    /// Three numbers per line.
    Spatial(Vec<DVec3>),
}

impl Points {
    /// The number of points.
    pub fn len(&self) -> usize {
        match self {
            Points::Planar(p) => p.len(),
            Points::Spatial(p) => p.len(),
        }
    }

    /// Whether there are no points.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// A points file: the points and where they are.
#[derive(Debug, Clone, PartialEq)]
pub struct PointsFile {
    /// The file name (`<memory>` for in-memory text).
    pub file: PathBuf,
    /// The points.
    pub points: Points,
    /// The 1-based line of each point.
    pub lines: Vec<usize>,
    /// The number of lines in the file.
    pub line_count: usize,
}

impl PointsFile {
    /// Checks that there are enough points for `scheme` on an open or closed
    /// polygon; the error names the last line of the file.
    pub fn require(&self, scheme: &CurveScheme, closed: bool) -> Result<(), PointsError> {
        let needed = scheme.min_points(closed);
        let got = self.points.len();
        if got < needed {
            return Err(PointsError {
                file: self.file.clone(),
                line: self.line_count.max(1),
                kind: PointsErrorKind::TooFewPoints {
                    got,
                    needed,
                    scheme: scheme.name(),
                    closed,
                },
            });
        }
        Ok(())
    }
}

/// An error in a points file, with the file and the 1-based line
/// (`FILE:LINE: what`, or `FILE: what` when no line is concerned).
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{}{}: {kind}", file.display(), if *.line > 0 { format!(":{line}") } else { String::new() })]
pub struct PointsError {
    /// The file name.
    pub file: PathBuf,
    /// The 1-based line (0 when the file could not be read).
    pub line: usize,
    /// What is wrong.
    pub kind: PointsErrorKind,
}

/// What is wrong in a points file.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum PointsErrorKind {
    /// A line with 1 or more than 3 numbers.
    #[error("a point needs 2 or 3 numbers, this line has {0}")]
    WrongCount(usize),
    /// A line whose dimension differs from the first point's.
    #[error(
        "a {found}-D point after {expected}-D points (the first point is on line {first_line})"
    )]
    MixedDimensions {
        /// The dimension of the first point.
        expected: usize,
        /// This line's dimension.
        found: usize,
        /// The line of the first point.
        first_line: usize,
    },
    /// A field that is not a number (as written; the message escapes its
    /// control characters).
    #[error("'{}' is not a number", crate::io::obj::escape(.0))]
    NotANumber(String),
    /// A number that is NaN or infinite.
    #[error("'{}' is not a finite number", crate::io::obj::escape(.0))]
    NonFinite(String),
    /// The file ends with fewer points than the scheme needs.
    #[error("the input ends after {got} point{}; {scheme} on {} polygon needs at least {needed}", if *.got == 1 { "" } else { "s" }, if *.closed { "a closed" } else { "an open" })]
    TooFewPoints {
        /// The number of points read.
        got: usize,
        /// The fewest accepted.
        needed: usize,
        /// The scheme's name.
        scheme: &'static str,
        /// Whether the polygon is closed.
        closed: bool,
    },
    /// Bytes that are not UTF-8, outside a comment ([`read_points`]).
    #[error("invalid UTF-8 at column {column} (byte 0x{byte:02X}): a points file must be text")]
    InvalidUtf8 {
        /// The 1-based byte offset of the invalid sequence in its line.
        column: usize,
        /// Its first byte.
        byte: u8,
    },
    /// The file could not be read.
    #[error("cannot read: {0}")]
    Io(String),
}

/// Parses points, one per line: 2 or 3 numbers separated by white space; `#`
/// starts a comment; blank lines are skipped. Every point must have the
/// dimension of the first.
///
/// ```
/// use std::path::Path;
/// use subdiv::curve::{parse_points, Points};
/// let f = parse_points("# a triangle\n0 0\n1 0  # comment\n\n0 1\n", Path::new("t.txt"))?;
/// assert_eq!(f.points.len(), 3);
/// assert_eq!(f.lines, [2, 3, 5]);
/// assert!(matches!(f.points, Points::Planar(_)));
/// let e = parse_points("0 0\n1 0 0\n", Path::new("t.txt")).unwrap_err();
/// assert_eq!(e.to_string(), "t.txt:2: a 3-D point after 2-D points (the first point is on line 1)");
/// # Ok::<(), subdiv::curve::PointsError>(())
/// ```
pub fn parse_points(text: &str, file: &Path) -> Result<PointsFile, PointsError> {
    let error = |line: usize, kind| PointsError {
        file: file.to_path_buf(),
        line,
        kind,
    };
    let mut planar = Vec::new();
    let mut spatial = Vec::new();
    let mut lines = Vec::new();
    let mut first: Option<(usize, usize)> = None; // (dimension, line)
    let mut line_count = 0;
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        line_count = line;
        let content = raw.split('#').next().unwrap_or("");
        let mut coords = Vec::with_capacity(3);
        for field in content.split_whitespace() {
            let x: f64 = field
                .parse()
                .map_err(|_| error(line, PointsErrorKind::NotANumber(field.to_string())))?;
            if !x.is_finite() {
                return Err(error(line, PointsErrorKind::NonFinite(field.to_string())));
            }
            coords.push(x);
        }
        match coords.len() {
            0 => continue,
            2 | 3 => {}
            k => return Err(error(line, PointsErrorKind::WrongCount(k))),
        }
        let dim = coords.len();
        match first {
            None => first = Some((dim, line)),
            Some((expected, first_line)) if expected != dim => {
                return Err(error(
                    line,
                    PointsErrorKind::MixedDimensions {
                        expected,
                        found: dim,
                        first_line,
                    },
                ));
            }
            Some(_) => {}
        }
        if dim == 2 {
            planar.push(DVec2::new(coords[0], coords[1]));
        } else {
            spatial.push(DVec3::new(coords[0], coords[1], coords[2]));
        }
        lines.push(line);
    }
    let points = match first {
        Some((3, _)) => Points::Spatial(spatial),
        _ => Points::Planar(planar),
    };
    Ok(PointsFile {
        file: file.to_path_buf(),
        points,
        lines,
        line_count,
    })
}

/// Reads a points file ([`parse_points`]).
///
/// Failing to read the file is a [`PointsErrorKind::Io`] error on line 0.
/// The text must be UTF-8 outside comments: the first invalid UTF-8 sequence
/// before a `#` is a [`PointsErrorKind::InvalidUtf8`] error naming its line
/// and column (bytes in comments are ignored, as everything after `#` is).
pub fn read_points(path: &Path) -> Result<PointsFile, PointsError> {
    let error = |line: usize, kind| PointsError {
        file: path.to_path_buf(),
        line,
        kind,
    };
    let bytes = std::fs::read(path).map_err(|e| error(0, PointsErrorKind::Io(e.to_string())))?;
    // Lines as `str::lines` counts them; '#' and '\n' never occur inside a
    // multi-byte UTF-8 sequence, so splitting the bytes at them is safe.
    for (index, line) in bytes.split(|&b| b == b'\n').enumerate() {
        let content = line.split(|&b| b == b'#').next().unwrap_or_default();
        if let Err(e) = std::str::from_utf8(content) {
            let at = e.valid_up_to();
            return Err(error(
                index + 1,
                PointsErrorKind::InvalidUtf8 {
                    column: at + 1,
                    byte: content[at],
                },
            ));
        }
    }
    parse_points(&String::from_utf8_lossy(&bytes), path)
}

/// The points as text, one per line, every coordinate with 17 significant
/// digits (C's `%.17g`, which reads back exactly).
///
/// ```
/// use glam::DVec2;
/// assert_eq!(subdiv::curve::format_points(&[DVec2::new(0.1, -2.0)]), "0.10000000000000001 -2\n");
/// ```
pub fn format_points<P: Point>(points: &[P]) -> String {
    let mut out = String::with_capacity(points.len() * 20 * P::DIM);
    for p in points {
        for (i, x) in p.coords().into_iter().enumerate() {
            if i > 0 {
                out.push(' ');
            }
            crate::io::obj::format_g(x, 17, &mut out);
        }
        out.push('\n');
    }
    out
}

/// Writes [`format_points`] to `path` atomically (a temporary file in the
/// same directory, renamed at the end).
pub fn write_points<P: Point>(path: &Path, points: &[P]) -> Result<(), crate::Error> {
    crate::io::atomic::write_bytes(path, format_points(points).as_bytes())
}
