//! Knot vectors: validation, the domain, span location, multiplicities, and
//! the periodic (closed) form.

use super::NurbsError;
use crate::curve::MAX_POINTS;

/// A validated knot vector `u_0 ≤ u_1 ≤ … ≤ u_m` of a degree `d ≥ 1`, for
/// `n + 1 = m - d` control points (see the [module documentation](super)).
///
/// Invariants: every knot finite, no knot smaller than the one before it, no
/// value repeated more than `d + 1` times, at least `2d + 2` knots, a
/// non-empty domain `[u_d, u_{m-d}]`, and `u_m - u_0` finite.
///
/// A **periodic** knot vector ([`KnotVector::periodic`]) is stored in the
/// same wrapped form a closed curve uses: for the break points
/// `s_0 ≤ … ≤ s_n` of one period `T = s_n - s_0`, `u_{d+i} = s_i` for
/// `i = 0..=n`, `u_{d+n+i} = s_i + T` and `u_{d-i} = s_{n-i} - T` for
/// `i = 1..=d`: `n + 2d + 1` knots for `n` distinct control points (stored
/// as `n + d`, the last `d` repeating the first `d`), domain `[s_0, s_n]`.
#[derive(Debug, Clone, PartialEq)]
pub struct KnotVector {
    knots: Vec<f64>,
    degree: usize,
    periodic: bool,
}

impl KnotVector {
    /// A knot vector of degree `degree` (at least 1) from its knots.
    ///
    /// ```
    /// use subdiv::nurbs::{KnotVector, NurbsError};
    /// let k = KnotVector::new(vec![0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0], 2)?;
    /// assert_eq!((k.control_count(), k.domain()), (4, (0.0, 2.0)));
    /// assert!(k.is_clamped());
    /// assert_eq!(
    ///     KnotVector::new(vec![0.0, 1.0, 0.5, 2.0], 1),
    ///     Err(NurbsError::DecreasingKnots { index: 2, previous: 1.0, value: 0.5 })
    /// );
    /// # Ok::<(), NurbsError>(())
    /// ```
    pub fn new(knots: Vec<f64>, degree: usize) -> Result<Self, NurbsError> {
        check_degree(degree)?;
        let needed = degree.saturating_mul(2).saturating_add(2);
        if knots.len() < needed {
            return Err(NurbsError::TooFewKnots {
                degree,
                needed,
                got: knots.len(),
            });
        }
        check_knots(&knots, degree.saturating_add(1))?;
        let k = KnotVector {
            knots,
            degree,
            periodic: false,
        };
        let (start, end) = k.domain();
        if start >= end {
            return Err(NurbsError::EmptyDomain { start, end });
        }
        Ok(k)
    }

    /// The uniform knot vector `u_k = k - d` (`k = 0..=points + d`) for
    /// `points` control points: the parametrisation of
    /// [`BSplineCurve`](crate::curve::BSplineCurve) and
    /// [`ControlGrid`](crate::patch::ControlGrid), domain `[0, points - d]`.
    pub fn uniform(points: usize, degree: usize) -> Result<Self, NurbsError> {
        check_degree(degree)?;
        check_open_count(points, degree)?;
        let d = degree as f64;
        Self::new(
            (0..points + degree + 1).map(|k| k as f64 - d).collect(),
            degree,
        )
    }

    /// The clamped uniform knot vector for `points` control points: `0`
    /// repeated `d + 1` times, `1, 2, …`, then `points - d` repeated `d + 1`
    /// times; domain `[0, points - d]`, and the curve starts at its first
    /// control point and ends at its last.
    pub fn clamped(points: usize, degree: usize) -> Result<Self, NurbsError> {
        check_degree(degree)?;
        check_open_count(points, degree)?;
        let last = (points - degree) as f64;
        let knots = (0..points + degree + 1)
            .map(|k| (k as f64 - degree as f64).clamp(0.0, last))
            .collect();
        Self::new(knots, degree)
    }

    /// The periodic knot vector of a closed curve with `n = breaks.len() - 1`
    /// distinct control points: `breaks` are `s_0 ≤ s_1 ≤ … ≤ s_n`, the knots
    /// of one period `T = s_n - s_0` (`s_n` is the image of `s_0`), stored
    /// wrapped as described on [`KnotVector`]. Needs `n ≥ max(d, 2)`.
    ///
    /// ```
    /// use subdiv::nurbs::KnotVector;
    /// let k = KnotVector::periodic(vec![0.0, 1.0, 2.0, 4.0], 2)?;
    /// assert_eq!(k.as_slice(), [-3.0, -2.0, 0.0, 1.0, 2.0, 4.0, 5.0, 6.0]); // s_1 - T, s_2 - T, …, s_1 + T, s_2 + T
    /// assert_eq!((k.control_count(), k.distinct_control_count()), (5, 3));
    /// assert_eq!((k.domain(), k.period()), ((0.0, 4.0), Some(4.0)));
    /// # Ok::<(), subdiv::nurbs::NurbsError>(())
    /// ```
    pub fn periodic(breaks: Vec<f64>, degree: usize) -> Result<Self, NurbsError> {
        check_degree(degree)?;
        let n = breaks.len().saturating_sub(1);
        let needed = degree.max(2);
        if n < needed {
            return Err(NurbsError::TooFewPoints {
                degree,
                closed: true,
                needed,
                got: n,
            });
        }
        check_knots(&breaks, usize::MAX)?;
        let (first, last) = (breaks[0], breaks[n]);
        if first >= last {
            return Err(NurbsError::EmptyDomain {
                start: first,
                end: last,
            });
        }
        let period = last - first;
        // Three periods hold every run of equal knots whole (a run is shorter
        // than a period), so this checks the multiplicities of the periodic sequence.
        let mut three = Vec::with_capacity(3 * n);
        three.extend(breaks[..n].iter().map(|&s| s - period));
        three.extend_from_slice(&breaks[..n]);
        three.extend(breaks[..n].iter().map(|&s| s + period));
        check_knots(&three, degree + 1)?;
        let k = Self::wrap_periodic(&breaks, degree);
        check_knots(&k.knots, degree + 1)?;
        Ok(k)
    }

    /// The periodic vector of the break points `s_0..=s_n` (`n ≥ d`,
    /// `s_0 < s_n`), wrapped, unchecked.
    pub(crate) fn wrap_periodic(breaks: &[f64], degree: usize) -> Self {
        let n = breaks.len() - 1;
        let period = breaks[n] - breaks[0];
        let mut knots = Vec::with_capacity(n + 2 * degree + 1);
        knots.extend((1..=degree).rev().map(|i| breaks[n - i] - period));
        knots.extend_from_slice(breaks);
        knots.extend((1..=degree).map(|i| breaks[i] + period));
        KnotVector {
            knots,
            degree,
            periodic: true,
        }
    }

    /// The periodic knot vector with the break points `0, 1, …, points` (the
    /// parametrisation of a closed [`BSplineCurve`](crate::curve::BSplineCurve)).
    pub fn periodic_uniform(points: usize, degree: usize) -> Result<Self, NurbsError> {
        if points > MAX_POINTS {
            return Err(NurbsError::TooManyPoints { max: MAX_POINTS });
        }
        Self::periodic((0..=points).map(|k| k as f64).collect(), degree)
    }

    /// The degree `d`.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The knots `u_0..=u_m` (wrapped for a periodic vector).
    pub fn as_slice(&self) -> &[f64] {
        &self.knots
    }

    /// The number of knots, `m + 1`.
    pub fn knot_count(&self) -> usize {
        self.knots.len()
    }

    /// The number of basis functions and control points, `n + 1 = m - d`
    /// (for a periodic vector: the wrapped count, distinct points + `d`).
    pub fn control_count(&self) -> usize {
        self.knots.len() - self.degree - 1
    }

    /// The number of distinct control points: [`control_count`](Self::control_count)
    /// minus `d` for a periodic vector, all of them otherwise.
    pub fn distinct_control_count(&self) -> usize {
        if self.periodic {
            self.control_count() - self.degree
        } else {
            self.control_count()
        }
    }

    /// The domain `(u_d, u_{m-d})`.
    pub fn domain(&self) -> (f64, f64) {
        let m = self.knots.len() - 1;
        (self.knots[self.degree], self.knots[m - self.degree])
    }

    /// Whether this is a periodic (closed) knot vector.
    pub fn is_periodic(&self) -> bool {
        self.periodic
    }

    /// The period `T = s_n - s_0` of a periodic vector.
    pub fn period(&self) -> Option<f64> {
        self.periodic.then(|| {
            let (a, b) = self.domain();
            b - a
        })
    }

    /// The break points `s_0..=s_n` of a periodic vector (the knots of the
    /// domain, `u_d..=u_{d+n}`); for any vector, the knots in the domain.
    pub fn breaks(&self) -> &[f64] {
        let m = self.knots.len() - 1;
        &self.knots[self.degree..=m - self.degree]
    }

    /// Whether the first `d + 1` knots are equal and so are the last `d + 1`
    /// (the curve then starts and ends at its end control points).
    pub fn is_clamped(&self) -> bool {
        let d = self.degree;
        let m = self.knots.len() - 1;
        self.knots[0] == self.knots[d] && self.knots[m - d] == self.knots[m]
    }

    /// How many knots equal `t`.
    pub fn multiplicity(&self, t: f64) -> usize {
        let lo = self.knots.partition_point(|&u| u < t);
        let hi = self.knots.partition_point(|&u| u <= t);
        hi - lo
    }

    /// The same vector, not periodic: the wrapped knots as an ordinary knot
    /// vector (a closed curve's open representation).
    pub fn to_open(&self) -> Self {
        KnotVector {
            periodic: false,
            ..self.clone()
        }
    }

    /// `t` checked against the domain; a periodic vector takes any finite `t`
    /// and reduces it into the domain `[s_0, s_n]`.
    pub(crate) fn reduce(&self, t: f64) -> Result<f64, NurbsError> {
        let (start, end) = self.domain();
        let outside = NurbsError::OutsideDomain { t, start, end };
        if self.periodic {
            let r = start + (t - start).rem_euclid(end - start);
            if r.is_finite() {
                Ok(r.min(end))
            } else {
                Err(outside)
            }
        } else if t >= start && t <= end {
            Ok(t)
        } else {
            Err(outside)
        }
    }

    /// The span of `t`: the index `k` in `d..=n` with `u_k ≤ t < u_{k+1}`, or
    /// for `t = u_{m-d}` the last non-empty span, `u_k < u_{k+1} = t`. `t`
    /// must lie in the domain; a periodic vector reduces any finite `t` into it.
    ///
    /// ```
    /// use subdiv::nurbs::KnotVector;
    /// let k = KnotVector::new(vec![0.0, 0.0, 0.0, 1.0, 1.0, 3.0, 3.0, 3.0], 2)?;
    /// assert_eq!(k.span(0.0)?, 2);
    /// assert_eq!(k.span(1.0)?, 4);   // u_4 = 1 ≤ 1 < u_5 = 3
    /// assert_eq!(k.span(3.0)?, 4);   // the end belongs to the last span
    /// assert!(k.span(3.5).is_err());
    /// # Ok::<(), subdiv::nurbs::NurbsError>(())
    /// ```
    pub fn span(&self, t: f64) -> Result<usize, NurbsError> {
        let t = self.reduce(t)?;
        Ok(self.span_of(t))
    }

    /// [`span`](Self::span) of a parameter already in the domain.
    pub(crate) fn span_of(&self, t: f64) -> usize {
        let d = self.degree;
        let n = self.control_count() - 1;
        let end = self.knots[n + 1];
        if t >= end {
            let mut k = n;
            while self.knots[k] >= end {
                k -= 1;
            }
            return k;
        }
        d + self.knots[d..=n + 1].partition_point(|&u| u <= t) - 1
    }

    /// The vector with `t` inserted after the knot `u_k` (`u_k ≤ t ≤ u_{k+1}`).
    pub(crate) fn with_knot_after(&self, k: usize, t: f64) -> Self {
        let mut knots = Vec::with_capacity(self.knots.len() + 1);
        knots.extend_from_slice(&self.knots[..=k]);
        knots.push(t);
        knots.extend_from_slice(&self.knots[k + 1..]);
        KnotVector {
            knots,
            degree: self.degree,
            periodic: false,
        }
    }

    /// An open vector of these knots, unchecked (the caller keeps the invariants).
    pub(crate) fn from_raw(knots: Vec<f64>, degree: usize) -> Self {
        KnotVector {
            knots,
            degree,
            periodic: false,
        }
    }
}

/// Degree 1 and up.
pub(crate) fn check_degree(degree: usize) -> Result<(), NurbsError> {
    if degree == 0 {
        return Err(NurbsError::BadDegree { degree });
    }
    Ok(())
}

/// An open curve needs `d + 1` points, and no more than [`MAX_POINTS`].
pub(crate) fn check_open_count(points: usize, degree: usize) -> Result<(), NurbsError> {
    let needed = degree.saturating_add(1);
    if points < needed {
        return Err(NurbsError::TooFewPoints {
            degree,
            closed: false,
            needed,
            got: points,
        });
    }
    if points > MAX_POINTS {
        return Err(NurbsError::TooManyPoints { max: MAX_POINTS });
    }
    Ok(())
}

/// Finite, non-decreasing, no value more than `max_run` times, a finite range.
fn check_knots(knots: &[f64], max_run: usize) -> Result<(), NurbsError> {
    if let Some(index) = knots.iter().position(|u| !u.is_finite()) {
        return Err(NurbsError::NonFiniteKnot {
            index,
            value: knots[index],
        });
    }
    let mut run = 1;
    for index in 1..knots.len() {
        let (previous, value) = (knots[index - 1], knots[index]);
        if value < previous {
            return Err(NurbsError::DecreasingKnots {
                index,
                previous,
                value,
            });
        }
        run = if value == previous { run + 1 } else { 1 };
        if run > max_run {
            let multiplicity = knots[index..].iter().take_while(|&&u| u == value).count() + run - 1;
            return Err(NurbsError::MultiplicityTooHigh {
                knot: value,
                multiplicity,
                max: max_run,
            });
        }
    }
    let (first, last) = (knots[0], knots[knots.len() - 1]);
    if !(last - first).is_finite() {
        return Err(NurbsError::KnotRangeTooWide { first, last });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spans_at_repeated_knots_and_the_domain_end() {
        // Unclamped, a double knot at the domain's end: the last non-empty span.
        let k = KnotVector::new(vec![0., 1., 2., 3., 3., 4., 5.], 2).unwrap();
        assert_eq!(k.domain(), (2.0, 3.0));
        assert_eq!(k.span(2.0).unwrap(), 2);
        assert_eq!(k.span(2.999).unwrap(), 2);
        assert_eq!(k.span(3.0).unwrap(), 2);
        // An interior knot of multiplicity d + 1: the span on its right.
        let k = KnotVector::new(vec![0., 0., 1., 1., 1., 2., 2.], 1).unwrap_err();
        assert_eq!(
            k,
            NurbsError::MultiplicityTooHigh {
                knot: 1.0,
                multiplicity: 3,
                max: 2
            }
        );
        let k = KnotVector::new(vec![0., 0., 0., 1., 1., 1., 2., 2., 2.], 2).unwrap();
        assert_eq!(k.span(1.0).unwrap(), 5);
        assert_eq!(k.span(0.99).unwrap(), 2);
        assert_eq!(k.multiplicity(1.0), 3);
        assert!(k.is_clamped());
        assert!(!KnotVector::uniform(5, 3).unwrap().is_clamped());
    }

    #[test]
    fn periodic_vectors_wrap_and_reduce() {
        let k = KnotVector::periodic(vec![1.0, 1.5, 3.0, 3.5], 3).unwrap();
        // s = 1, 1.5, 3, 3.5 (T = 2.5): u_0..u_2 = s_0 - T.. s_2 - T, u_7..u_9 = s_1 + T..
        assert_eq!(
            k.as_slice(),
            [-1.5, -1.0, 0.5, 1.0, 1.5, 3.0, 3.5, 4.0, 5.5, 6.0]
        );
        assert_eq!(k.breaks(), [1.0, 1.5, 3.0, 3.5]);
        assert_eq!(k.reduce(3.5 + 2.5 * 4.0 + 0.25).unwrap(), 1.25);
        assert_eq!(k.reduce(-4.0).unwrap(), 1.0);
        assert_eq!(k.span(1.0 - 2.5 * 3.0).unwrap(), 3);
        assert!(k.reduce(f64::INFINITY).is_err());
        assert_eq!(
            KnotVector::periodic(vec![0.0, 1.0], 1),
            Err(NurbsError::TooFewPoints {
                degree: 1,
                closed: true,
                needed: 2,
                got: 1
            })
        );
        assert_eq!(
            KnotVector::periodic_uniform(usize::MAX, 2),
            Err(NurbsError::TooManyPoints { max: MAX_POINTS })
        );
    }
}
