//! The typed errors of the NURBS module.

use crate::patch::Direction;
use thiserror::Error;

/// Why a knot vector, curve or surface was refused, or an operation on one.
///
/// Every variant carries the numbers involved, so a caller can match on it
/// and report precisely.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum NurbsError {
    /// A degree of 0: the module works with degree 1 and up.
    #[error("B-spline degree {degree} is not supported (the degree must be at least 1)")]
    BadDegree {
        /// The degree asked for.
        degree: usize,
    },
    /// Fewer control points than the degree needs: `d + 1` for an open curve,
    /// `max(d, 2)` distinct points for a closed one.
    #[error(
        "{} curve of degree {degree} needs at least {needed} control points, got {got}",
        if *.closed { "a closed" } else { "an open" }
    )]
    TooFewPoints {
        /// The degree.
        degree: usize,
        /// Whether the curve (or surface direction) is closed.
        closed: bool,
        /// The fewest accepted.
        needed: usize,
        /// The number given.
        got: usize,
    },
    /// A knot vector shorter than `2d + 2`, the fewest a degree-`d` spline has.
    #[error("a knot vector of degree {degree} needs at least {needed} knots, got {got}")]
    TooFewKnots {
        /// The degree.
        degree: usize,
        /// The fewest accepted, `2d + 2`.
        needed: usize,
        /// The number given.
        got: usize,
    },
    /// The number of knots is not `n + d + 2` for `n + 1` control points
    /// (or `n + 1` break points for a closed curve of `n` distinct points).
    #[error("expected {expected} knots, got {got}")]
    WrongKnotCount {
        /// The number needed.
        expected: usize,
        /// The number given.
        got: usize,
    },
    /// A knot smaller than the one before it.
    #[error("knot {index} ({value}) is smaller than knot {} ({previous}): knots must not decrease", index - 1)]
    DecreasingKnots {
        /// The index of the offending knot (at least 1).
        index: usize,
        /// The knot before it.
        previous: f64,
        /// Its value.
        value: f64,
    },
    /// A knot value repeated more than `d + 1` times.
    #[error("knot {knot} has multiplicity {multiplicity}, more than degree + 1 = {max}")]
    MultiplicityTooHigh {
        /// The knot value.
        knot: f64,
        /// Its multiplicity (after the operation, for an insertion).
        multiplicity: usize,
        /// The largest multiplicity accepted, `d + 1`.
        max: usize,
    },
    /// A knot that is NaN or infinite.
    #[error("knot {index} is not a finite number ({value})")]
    NonFiniteKnot {
        /// The index of the knot.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// Knots so far apart that their difference overflows `f64`.
    #[error("the knots span [{first}, {last}], a range too wide for f64 arithmetic")]
    KnotRangeTooWide {
        /// The first knot.
        first: f64,
        /// The last knot.
        last: f64,
    },
    /// A knot vector whose domain `[u_d, u_{m-d}]` is a single value.
    #[error("the domain [{start}, {end}] is empty")]
    EmptyDomain {
        /// `u_d`.
        start: f64,
        /// `u_{m-d}`.
        end: f64,
    },
    /// A control point with a NaN or infinite coordinate.
    #[error("control point {index} has a non-finite coordinate")]
    NonFinitePoint {
        /// The index of the point (row-major `j * nu + i` in a surface).
        index: usize,
    },
    /// The number of weights differs from the number of control points.
    #[error("expected {expected} weights, got {got}")]
    WrongWeightCount {
        /// The number of control points.
        expected: usize,
        /// The number of weights given.
        got: usize,
    },
    /// A weight that is not a positive finite number.
    #[error("weight {index} is {weight}; weights must be positive finite numbers")]
    BadWeight {
        /// The index of the weight.
        index: usize,
        /// Its value.
        weight: f64,
    },
    /// A control point times its weight overflows `f64` (the homogeneous form
    /// `(w P, w)` is what the algorithms work on).
    #[error("control point {index} times its weight overflows f64")]
    WeightedOverflow {
        /// The index of the point.
        index: usize,
    },
    /// A parameter outside the domain `[u_d, u_{m-d}]` (or NaN, or infinite
    /// for a closed curve).
    #[error("parameter {t} is outside the domain [{start}, {end}]")]
    OutsideDomain {
        /// The parameter.
        t: f64,
        /// The domain's start, `u_d`.
        start: f64,
        /// The domain's end, `u_{m-d}`.
        end: f64,
    },
    /// A split parameter that is not strictly inside the domain: one of the
    /// two pieces would be empty.
    #[error("cannot split at {t}: it must lie strictly inside the domain ({start}, {end})")]
    SplitNotInterior {
        /// The parameter.
        t: f64,
        /// The domain's start.
        start: f64,
        /// The domain's end.
        end: f64,
    },
    /// A basis function index beyond the last, `n`.
    #[error("there is no basis function {index}: the knot vector has {count}")]
    NoSuchBasisFunction {
        /// The index asked for.
        index: usize,
        /// The number of basis functions, `n + 1`.
        count: usize,
    },
    /// The result would have more than [`MAX_POINTS`](crate::curve::MAX_POINTS)
    /// control points (or samples).
    #[error("the result would have more than {max} points")]
    TooManyPoints {
        /// The limit.
        max: usize,
    },
    /// A surface's point count is not `nu × nv`.
    #[error("a {nu} × {nv} surface needs {} points, got {got}", nu.saturating_mul(*nv))]
    WrongPointCount {
        /// Points along u.
        nu: usize,
        /// Points along v.
        nv: usize,
        /// The number given.
        got: usize,
    },
    /// An error about one parameter direction of a surface.
    #[error("along {direction}: {source}")]
    Surface {
        /// The direction.
        direction: Direction,
        /// What is wrong along it.
        #[source]
        source: Box<NurbsError>,
    },
}

impl NurbsError {
    /// This error, attributed to the direction `direction` of a surface.
    pub(crate) fn along(self, direction: Direction) -> Self {
        NurbsError::Surface {
            direction,
            source: Box::new(self),
        }
    }
}
