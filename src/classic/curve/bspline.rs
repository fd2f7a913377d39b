//! The uniform B-spline basis, B-spline curves (evaluation, derivatives) and
//! adaptive flattening of their limit curve.

use super::{
    CurveError, CurveScheme, MAX_FLATTEN_DEPTH, MAX_POINTS, Point, bspline_step, check_points, mid,
    refined_count,
};

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
        if k.is_multiple_of(2) {
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
/// `C(s) = Σ_j P[j] N_d(s + d - j)`, see the [module documentation](super).
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
    /// once by [`bspline`](super::bspline), with `refined.eval(2 s) = self.eval(s)`.
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
