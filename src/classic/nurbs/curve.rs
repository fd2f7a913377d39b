//! B-spline and NURBS curves over a knot vector: construction, evaluation by
//! de Boor's algorithm, derivatives, sampling, knot insertion and refinement,
//! Bézier decomposition and splitting.

use super::hom::{Hom, de_casteljau, homogeneous, split_hom, weighted};
use super::insert::{refine_line, split_cut};
use super::knots::{check_degree, check_open_count};
use super::{KnotVector, NurbsError};
use crate::curve::{BSplineCurve, MAX_POINTS, Point};

/// A B-spline curve of degree `d` over a knot vector, optionally rational
/// (NURBS): `C(t) = Σ w_i P_i N_{i,d}(t) / Σ w_i N_{i,d}(t)` on the domain
/// `[u_d, u_{m-d}]` (see the [module documentation](super)).
///
/// A closed curve has a [periodic](KnotVector::periodic) knot vector; its
/// control points (and weights) are stored wrapped, the last `d` repeating
/// the first `d`, and every operation keeps them so.
#[derive(Debug, Clone, PartialEq)]
pub struct NurbsCurve<P: Point> {
    points: Vec<P>,
    weights: Option<Vec<f64>>,
    hom: Vec<Hom<P>>,
    knots: KnotVector,
}

/// A curve point with its first and second derivatives with respect to the
/// parameter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveDerivatives<P> {
    /// `C(t)`.
    pub point: P,
    /// `C'(t)`.
    pub first: P,
    /// `C''(t)`.
    pub second: P,
}

/// One polynomial (or rational) piece of a curve in Bézier form.
#[derive(Debug, Clone, PartialEq)]
pub struct BezierSegment<P> {
    /// The `d + 1` Bézier control points.
    pub points: Vec<P>,
    /// Their weights, for a rational curve.
    pub weights: Option<Vec<f64>>,
    /// The curve parameter at the first control point.
    pub start: f64,
    /// The curve parameter at the last control point.
    pub end: f64,
}

impl<P: Point> BezierSegment<P> {
    /// The piece at the curve parameter `t` (de Casteljau's algorithm on the
    /// homogeneous points at `(t - start) / (end - start)`; a `t` outside
    /// `[start, end]` extrapolates the polynomial).
    pub fn eval(&self, t: f64) -> P {
        let s = (t - self.start) / (self.end - self.start);
        let h = weighted(&self.points, self.weights.as_deref());
        de_casteljau(h, s).point(self.weights.is_some())
    }
}

impl<P: Point> NurbsCurve<P> {
    /// The open curve of degree `degree` with the control points `points`
    /// (`n + 1 ≥ d + 1` of them), the knots `knots` (`n + d + 2`, checked
    /// as by [`KnotVector::new`]) and, for a rational curve, one positive
    /// weight per control point.
    ///
    /// ```
    /// use glam::DVec2;
    /// use subdiv::nurbs::{NurbsCurve, NurbsError};
    /// let p = vec![DVec2::ZERO, DVec2::new(1.0, 2.0), DVec2::new(3.0, 2.0)];
    /// assert_eq!(
    ///     NurbsCurve::new(p.clone(), 2, vec![0.0, 0.0, 1.0, 1.0], None),
    ///     Err(NurbsError::WrongKnotCount { expected: 6, got: 4 })
    /// );
    /// let c = NurbsCurve::new(p, 2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], Some(vec![1.0, 2.0, 1.0]))?;
    /// assert!(c.is_rational());
    /// # Ok::<(), NurbsError>(())
    /// ```
    pub fn new(
        points: Vec<P>,
        degree: usize,
        knots: Vec<f64>,
        weights: Option<Vec<f64>>,
    ) -> Result<Self, NurbsError> {
        check_degree(degree)?;
        check_open_count(points.len(), degree)?;
        let expected = points.len() + degree + 1;
        if knots.len() != expected {
            return Err(NurbsError::WrongKnotCount {
                expected,
                got: knots.len(),
            });
        }
        Self::from_knot_vector(points, KnotVector::new(knots, degree)?, weights)
    }

    /// The closed curve of degree `degree` with the `n` distinct control
    /// points `points` (`n ≥ max(d, 2)`) and the break points
    /// `breaks = s_0 ≤ … ≤ s_n` of one period ([`KnotVector::periodic`]);
    /// `weights`, if any, one per distinct point.
    pub fn closed(
        points: Vec<P>,
        degree: usize,
        breaks: Vec<f64>,
        weights: Option<Vec<f64>>,
    ) -> Result<Self, NurbsError> {
        check_degree(degree)?;
        let needed = degree.max(2);
        if points.len() < needed {
            return Err(NurbsError::TooFewPoints {
                degree,
                closed: true,
                needed,
                got: points.len(),
            });
        }
        if breaks.len() != points.len() + 1 {
            return Err(NurbsError::WrongKnotCount {
                expected: points.len() + 1,
                got: breaks.len(),
            });
        }
        Self::from_knot_vector(points, KnotVector::periodic(breaks, degree)?, weights)
    }

    /// The curve over an existing knot vector: `knots.control_count()`
    /// points for an open vector, `knots.distinct_control_count()` distinct
    /// points (wrapped here) for a periodic one; weights likewise.
    pub fn from_knot_vector(
        points: Vec<P>,
        knots: KnotVector,
        weights: Option<Vec<f64>>,
    ) -> Result<Self, NurbsError> {
        let d = knots.degree();
        let expected = knots.distinct_control_count();
        if points.len() != expected {
            return Err(if knots.is_periodic() {
                NurbsError::WrongKnotCount {
                    expected: points.len() + 1,
                    got: expected + 1,
                }
            } else {
                NurbsError::WrongKnotCount {
                    expected: points.len() + d + 1,
                    got: knots.knot_count(),
                }
            });
        }
        let mut hom = homogeneous(&points, weights.as_deref())?;
        let (mut points, mut weights) = (points, weights);
        if knots.is_periodic() {
            hom.extend_from_within(..d);
            points.extend_from_within(..d);
            if let Some(w) = &mut weights {
                w.extend_from_within(..d);
            }
        }
        // The points and weights as given; the homogeneous form for the algorithms.
        Ok(NurbsCurve {
            points,
            weights,
            hom,
            knots,
        })
    }

    /// The uniform B-spline of [`crate::curve`] as a curve over a knot
    /// vector, with the same parameter: open, the knots `u_k = k - d`
    /// ([`KnotVector::uniform`]); closed, the break points `0, 1, …, n`
    /// ([`KnotVector::periodic_uniform`], which needs `n ≥ max(d, 2)`).
    pub fn from_bspline(curve: &BSplineCurve<P>) -> Result<Self, NurbsError> {
        let (points, d) = (curve.points(), curve.degree());
        let knots = if curve.is_closed() {
            KnotVector::periodic_uniform(points.len(), d)?
        } else {
            KnotVector::uniform(points.len(), d)?
        };
        Self::from_knot_vector(points.to_vec(), knots, None)
    }

    /// The curve of checked homogeneous points (wrapped when periodic).
    pub(crate) fn from_hom(knots: KnotVector, hom: Vec<Hom<P>>, rational: bool) -> Self {
        let (points, weights) = split_hom(&hom, rational);
        NurbsCurve {
            points,
            weights,
            hom,
            knots,
        }
    }

    /// The degree `d`.
    pub fn degree(&self) -> usize {
        self.knots.degree()
    }

    /// The knot vector.
    pub fn knots(&self) -> &KnotVector {
        &self.knots
    }

    /// The control points `P_0..=P_n` (a closed curve: wrapped, the last `d`
    /// repeating the first `d`).
    pub fn points(&self) -> &[P] {
        &self.points
    }

    /// The weights of a rational curve (wrapped like the points).
    pub fn weights(&self) -> Option<&[f64]> {
        self.weights.as_deref()
    }

    /// The distinct control points: all of them for an open curve, the
    /// first `n` (without the wrapped copies) for a closed one.
    pub fn distinct_points(&self) -> &[P] {
        &self.points[..self.knots.distinct_control_count()]
    }

    /// The weights of the [distinct points](Self::distinct_points).
    pub fn distinct_weights(&self) -> Option<&[f64]> {
        let n = self.knots.distinct_control_count();
        self.weights.as_deref().map(|w| &w[..n])
    }

    /// Whether the curve has weights.
    pub fn is_rational(&self) -> bool {
        self.weights.is_some()
    }

    /// Whether the curve is closed (its knot vector periodic).
    pub fn is_closed(&self) -> bool {
        self.knots.is_periodic()
    }

    /// The parameter domain `(u_d, u_{m-d})`.
    pub fn domain(&self) -> (f64, f64) {
        self.knots.domain()
    }

    /// The same curve in its open representation: the wrapped points and
    /// knots as an ordinary (unclamped) curve over the domain.
    pub fn to_open(&self) -> Self {
        NurbsCurve {
            knots: self.knots.to_open(),
            ..self.clone()
        }
    }

    /// The curve point at `t` by de Boor's algorithm (on the homogeneous
    /// points `(w P, w)` of a rational curve, divided at the end). An open
    /// curve refuses `t` outside its domain; a closed one takes any finite
    /// `t` (period `T`).
    ///
    /// ```
    /// use glam::DVec2;
    /// use subdiv::nurbs::NurbsCurve;
    /// // A quarter of the unit circle: a rational quadratic Bézier curve.
    /// let h = std::f64::consts::FRAC_1_SQRT_2;
    /// let p = vec![DVec2::X, DVec2::ONE, DVec2::Y];
    /// let c = NurbsCurve::new(p, 2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], Some(vec![1.0, h, 1.0]))?;
    /// assert!((c.eval(0.3)?.length() - 1.0).abs() < 1e-15);
    /// assert!(c.eval(1.5).is_err());
    /// # Ok::<(), subdiv::nurbs::NurbsError>(())
    /// ```
    pub fn eval(&self, t: f64) -> Result<P, NurbsError> {
        let t = self.knots.reduce(t)?;
        let k = self.knots.span_of(t);
        let (d, u) = (self.degree(), self.knots.as_slice());
        let mut w: Vec<Hom<P>> = self.hom[k - d..=k].to_vec();
        for r in 1..=d {
            for j in (r..=d).rev() {
                let i = k - d + j;
                let alpha = (t - u[i]) / (u[i + d + 1 - r] - u[i]);
                w[j] = Hom::lerp(w[j - 1], w[j], alpha);
            }
        }
        Ok(w[d].point(self.is_rational()))
    }

    /// The point and its first and second derivatives at `t`, from the
    /// basis functions' derivatives: `A^{(q)}(t) = Σ N^{(q)}_{i,d}(t) w_i P_i`
    /// and `w^{(q)}(t) = Σ N^{(q)}_{i,d}(t) w_i`, then for a rational curve
    /// the quotient rule, `C = A / w`, `C' = (A' - w' C) / w`,
    /// `C'' = (A'' - 2 w' C' - w'' C) / w`. At a knot the derivatives are
    /// those of the span on its right (the left one at the domain's end).
    pub fn derivatives(&self, t: f64) -> Result<CurveDerivatives<P>, NurbsError> {
        let t = self.knots.reduce(t)?;
        let k = self.knots.span_of(t);
        let d = self.degree();
        let ders = self.knots.derivatives_at(k, t, 2);
        let a: Vec<Hom<P>> = ders
            .iter()
            .map(|row| {
                row.iter()
                    .zip(&self.hom[k - d..=k])
                    .fold(Hom::ZERO, |acc, (&n, &h)| acc + h * n)
            })
            .collect();
        Ok(quotient_rule(a[0], a[1], a[2], self.is_rational()))
    }

    /// `count` curve points at parameters spaced uniformly over the domain,
    /// both ends included (`count = 1`: the start only).
    pub fn sample(&self, count: usize) -> Result<Vec<P>, NurbsError> {
        if count > MAX_POINTS {
            return Err(NurbsError::TooManyPoints { max: MAX_POINTS });
        }
        let (a, b) = self.domain();
        (0..count)
            .map(|i| {
                let t = if i + 1 == count && count > 1 {
                    b
                } else {
                    a + (b - a) * (i as f64 / (count - 1).max(1) as f64)
                };
                self.eval(t)
            })
            .collect()
    }

    /// The same curve with the knot `t` inserted once (Boehm's algorithm):
    /// one more control point, the knot vector one longer. A closed curve
    /// inserts `t` (reduced into its period) and its images, keeping its
    /// periodic form: one more distinct point.
    ///
    /// ```
    /// use glam::DVec2;
    /// use subdiv::nurbs::NurbsCurve;
    /// let p = vec![DVec2::ZERO, DVec2::new(1.0, 2.0), DVec2::new(3.0, 2.0), DVec2::new(4.0, 0.0)];
    /// let c = NurbsCurve::new(p, 2, vec![0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0], None)?;
    /// let d = c.insert(0.5)?;
    /// assert_eq!(d.knots().as_slice(), [0.0, 0.0, 0.0, 0.5, 1.0, 2.0, 2.0, 2.0]);
    /// assert_eq!(d.points()[1], DVec2::new(0.5, 1.0));   // α = 1/2 between P0 and P1
    /// assert!((d.eval(1.3)? - c.eval(1.3)?).length() < 1e-15);
    /// # Ok::<(), subdiv::nurbs::NurbsError>(())
    /// ```
    pub fn insert(&self, t: f64) -> Result<Self, NurbsError> {
        let ins = self.knots.insertion(t)?;
        Ok(Self::from_hom(
            ins.knots().clone(),
            ins.apply(&self.hom),
            self.is_rational(),
        ))
    }

    /// The knot `t` inserted `times` times (refused as a whole when its
    /// multiplicity would exceed `d + 1`).
    pub fn insert_times(&self, t: f64, times: usize) -> Result<Self, NurbsError> {
        let reduced = self.knots.reduce(t)?;
        let multiplicity = self.knots.multiplicity(reduced).saturating_add(times);
        let max = self.degree() + 1;
        if multiplicity > max {
            return Err(NurbsError::MultiplicityTooHigh {
                knot: reduced,
                multiplicity,
                max,
            });
        }
        (0..times).try_fold(self.clone(), |c, _| c.insert(reduced))
    }

    /// The knots `ts` inserted one after the other, each once, in order (a
    /// repeated value inserts again).
    pub fn insert_many(&self, ts: &[f64]) -> Result<Self, NurbsError> {
        if self.points.len().saturating_add(ts.len()) > MAX_POINTS {
            return Err(NurbsError::TooManyPoints { max: MAX_POINTS });
        }
        ts.iter().try_fold(self.clone(), |c, &t| c.insert(t))
    }

    /// The knots `ts` (any order) inserted all at once: knot refinement by
    /// Piegl and Tiller's algorithm A5.4 for an open curve; a closed curve
    /// inserts them one after the other, in increasing order. The result
    /// equals [`insert_many`](Self::insert_many) to rounding.
    pub fn refine_knots(&self, ts: &[f64]) -> Result<Self, NurbsError> {
        if self.is_closed() {
            let mut sorted = ts.to_vec();
            sorted.sort_by(f64::total_cmp);
            return self.insert_many(&sorted);
        }
        let xs = self.knots.check_refinement(ts)?;
        if xs.is_empty() {
            return Ok(self.clone());
        }
        let hom = refine_line(&self.knots, &xs, &self.hom);
        Ok(Self::from_hom(
            self.knots.merged(&xs),
            hom,
            self.is_rational(),
        ))
    }

    /// The curve as Bézier segments, one per non-empty span of the domain,
    /// by inserting every knot of the domain (its ends included) up to
    /// multiplicity `d` (a closed curve: one period, from its open representation).
    pub fn to_bezier(&self) -> Result<Vec<BezierSegment<P>>, NurbsError> {
        let open = self.to_open();
        let full = open.refine_knots(&open.knots.bezier_knots())?;
        let d = self.degree();
        Ok(full
            .knots
            .bezier_pieces()
            .into_iter()
            .map(|(l, start, end)| BezierSegment {
                points: full.points[l - d..=l].to_vec(),
                weights: full.weights.as_ref().map(|w| w[l - d..=l].to_vec()),
                start,
                end,
            })
            .collect())
    }

    /// The curve split at `t` into the pieces over `[u_d, t]` and
    /// `[t, u_{m-d}]`, by inserting `t` up to multiplicity `d`; both end
    /// clamped at `t`, in `C(t)`. `t` must lie strictly inside the domain (a
    /// closed curve: reduced into its period first; the pieces are open).
    pub fn split(&self, t: f64) -> Result<(Self, Self), NurbsError> {
        let (start, end) = self.domain();
        let reduced = self.knots.reduce(t).unwrap_or(f64::NAN);
        if !(reduced > start && reduced < end) {
            return Err(NurbsError::SplitNotInterior { t, start, end });
        }
        let open = self.to_open();
        let have = open.knots.multiplicity(reduced);
        let full = open.insert_times(reduced, self.degree().saturating_sub(have))?;
        let (left, count, right, first) = split_cut(&full.knots, reduced);
        let rational = self.is_rational();
        Ok((
            Self::from_hom(left, full.hom[..count].to_vec(), rational),
            Self::from_hom(right, full.hom[first..].to_vec(), rational),
        ))
    }
}

/// The point and derivatives from the homogeneous `A`, `A'`, `A''` (with
/// their weights): divided by the quotient rule for a rational curve.
pub(crate) fn quotient_rule<P: Point>(
    a0: Hom<P>,
    a1: Hom<P>,
    a2: Hom<P>,
    rational: bool,
) -> CurveDerivatives<P> {
    if !rational {
        return CurveDerivatives {
            point: a0.p,
            first: a1.p,
            second: a2.p,
        };
    }
    let inv = 1.0 / a0.w;
    let point = a0.p * inv;
    let first = (a1.p - point * a1.w) * inv;
    let second = (a2.p - first * (2.0 * a1.w) - point * a2.w) * inv;
    CurveDerivatives {
        point,
        first,
        second,
    }
}
