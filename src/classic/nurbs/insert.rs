//! Knot insertion (Boehm), knot refinement (Piegl and Tiller's A5.4),
//! Bézier decomposition and splitting, on lines of homogeneous control
//! points: the curve's control polygon, or one row or column of a surface.

use super::hom::Hom;
use super::{KnotVector, NurbsError};
use crate::curve::{MAX_POINTS, Point};

/// One knot inserted once: the new knot vector and Boehm's coefficients.
///
/// For `t` in the span `k` (`u_k ≤ t ≤ u_{k+1}`, `u_k < u_{k+1}`), the new
/// control points are `Q_i = P_i` for `i ≤ k - d`,
/// `Q_i = (1 - α_i) P_{i-1} + α_i P_i` with `α_i = (t - u_i) / (u_{i+d} - u_i)`
/// for `k - d < i ≤ k`, and `Q_i = P_{i-1}` for `i > k`. A periodic vector
/// applies the same rule to the periodic sequence of control points
/// (`P_{i+n} = P_i`), which inserts `t` and all its images `t + jT` at once.
#[derive(Debug, Clone)]
pub(crate) struct Insertion {
    /// The span of `t` in the old vector.
    k: usize,
    /// `α_i` for `i = k-d+1..=k`.
    alphas: Vec<f64>,
    /// The number of distinct control points of a periodic vector.
    periodic: Option<usize>,
    /// The new knot vector.
    knots: KnotVector,
}

impl Insertion {
    /// Boehm's coefficients `α_{k-d+1}, …, α_k` and the span `k`.
    pub fn coefficients(&self) -> (usize, &[f64]) {
        (self.k, &self.alphas)
    }

    /// The knot vector after the insertion.
    pub fn knots(&self) -> &KnotVector {
        &self.knots
    }

    /// The control points after the insertion, from those before it (as
    /// stored: wrapped for a periodic vector).
    pub fn apply<P: Point>(&self, line: &[Hom<P>]) -> Vec<Hom<P>> {
        let d = self.knots.degree();
        let k = self.k;
        let Some(n) = self.periodic else {
            let mut out = Vec::with_capacity(line.len() + 1);
            out.extend_from_slice(&line[..=k - d]);
            for (j, &alpha) in self.alphas.iter().enumerate() {
                let i = k - d + 1 + j;
                out.push(Hom::lerp(line[i - 1], line[i], alpha));
            }
            out.extend_from_slice(&line[k..]);
            return out;
        };
        // One period of the new sequence, Q_0..Q_n: Q_i = Q_r for the r ≡ i
        // (mod n + 1) in [k - n, k], where the rule above applies with P
        // taken modulo n.
        let (k, d, n) = (k as isize, d as isize, n as isize);
        let at = |i: isize| line[i.rem_euclid(n) as usize];
        let mut period = Vec::with_capacity((n + 1 + d) as usize);
        for i in 0..=n {
            let r = if i < k - n {
                i + n + 1
            } else if i <= k {
                i
            } else {
                i - n - 1
            };
            period.push(if r <= k - d {
                at(r)
            } else {
                Hom::lerp(at(r - 1), at(r), self.alphas[(r - (k - d + 1)) as usize])
            });
        }
        let d = d as usize;
        let wrap: Vec<Hom<P>> = period[..d].to_vec();
        period.extend(wrap);
        period
    }
}

impl KnotVector {
    /// Boehm's coefficients for inserting `t` once: `(k, [α_{k-d+1}, …, α_k])`
    /// with `k` the span of `t` and `α_i = (t - u_i) / (u_{i+d} - u_i)`; the
    /// new control point `Q_i` is `(1 - α_i) P_{i-1} + α_i P_i`.
    ///
    /// ```
    /// use subdiv::nurbs::KnotVector;
    /// // A cubic on the integer knots -3..=6, a knot inserted at 2.8 (span 5):
    /// let k = KnotVector::uniform(6, 3)?;
    /// let (span, a) = k.insertion_coefficients(2.8)?;
    /// assert_eq!(span, 5);
    /// assert!((a[0] - 14.0 / 15.0).abs() < 1e-15 && (a[1] - 0.6).abs() < 1e-15);
    /// # Ok::<(), subdiv::nurbs::NurbsError>(())
    /// ```
    pub fn insertion_coefficients(&self, t: f64) -> Result<(usize, Vec<f64>), NurbsError> {
        let ins = self.insertion(t)?;
        let (k, alphas) = ins.coefficients();
        Ok((k, alphas.to_vec()))
    }

    /// The insertion of `t` once (periodic: `t` reduced into `[s_0, s_n)`).
    pub(crate) fn insertion(&self, t: f64) -> Result<Insertion, NurbsError> {
        let mut t = self.reduce(t)?;
        let (start, end) = self.domain();
        if self.is_periodic() && t >= end {
            t = start;
        }
        let d = self.degree();
        let multiplicity = self.multiplicity(t) + 1;
        if multiplicity > d + 1 {
            return Err(NurbsError::MultiplicityTooHigh {
                knot: t,
                multiplicity,
                max: d + 1,
            });
        }
        if self.control_count() >= MAX_POINTS {
            return Err(NurbsError::TooManyPoints { max: MAX_POINTS });
        }
        let k = self.span_of(t);
        let u = self.as_slice();
        let alphas = (k + 1 - d..=k)
            .map(|i| (t - u[i]) / (u[i + d] - u[i]))
            .collect();
        let (periodic, knots) = if self.is_periodic() {
            let mut breaks = self.breaks().to_vec();
            breaks.insert(k + 1 - d, t);
            (
                Some(self.distinct_control_count()),
                KnotVector::wrap_periodic(&breaks, d),
            )
        } else {
            (None, self.with_knot_after(k, t))
        };
        Ok(Insertion {
            k,
            alphas,
            periodic,
            knots,
        })
    }

    /// `xs` checked for a refinement of an open vector: every value in the
    /// domain, no multiplicity above `d + 1` after it, the count within
    /// [`MAX_POINTS`]; returned sorted.
    pub(crate) fn check_refinement(&self, xs: &[f64]) -> Result<Vec<f64>, NurbsError> {
        let mut sorted = Vec::with_capacity(xs.len());
        for &x in xs {
            sorted.push(self.reduce(x)?);
        }
        sorted.sort_by(f64::total_cmp);
        if self.control_count().saturating_add(xs.len()) > MAX_POINTS {
            return Err(NurbsError::TooManyPoints { max: MAX_POINTS });
        }
        let d = self.degree();
        for run in sorted.chunk_by(|a, b| a == b) {
            let multiplicity = self.multiplicity(run[0]) + run.len();
            if multiplicity > d + 1 {
                return Err(NurbsError::MultiplicityTooHigh {
                    knot: run[0],
                    multiplicity,
                    max: d + 1,
                });
            }
        }
        Ok(sorted)
    }

    /// The open vector with the sorted knots `xs` merged in.
    pub(crate) fn merged(&self, xs: &[f64]) -> KnotVector {
        let mut knots = Vec::with_capacity(self.knot_count() + xs.len());
        knots.extend_from_slice(self.as_slice());
        knots.extend_from_slice(xs);
        knots.sort_by(f64::total_cmp);
        KnotVector::from_raw(knots, self.degree())
    }

    /// The knots to insert so that every knot of the domain (its ends
    /// included) has multiplicity at least `d`: Bézier decomposition.
    pub(crate) fn bezier_knots(&self) -> Vec<f64> {
        let d = self.degree();
        let mut xs = Vec::new();
        for run in self.breaks().chunk_by(|a, b| a == b) {
            let have = self.multiplicity(run[0]);
            xs.extend(std::iter::repeat_n(run[0], d.saturating_sub(have)));
        }
        xs
    }

    /// The Bézier pieces of a vector in which every knot of the domain has
    /// multiplicity at least `d`: `(L, a, b)` with the piece's control points
    /// `Q_{L-d}..=Q_L` over `[a, b]`.
    pub(crate) fn bezier_pieces(&self) -> Vec<(usize, f64, f64)> {
        let u = self.as_slice();
        let (start, end) = self.domain();
        let mut pieces = Vec::new();
        for l in self.degree()..u.len() - 1 {
            if u[l] < u[l + 1] && u[l] >= start && u[l + 1] <= end {
                pieces.push((l, u[l], u[l + 1]));
            }
        }
        pieces
    }
}

/// Refines a line of control points over the open vector `old` with the
/// sorted knots `xs` (non-empty, checked by [`KnotVector::check_refinement`]),
/// all at once: Piegl and Tiller's algorithm A5.4. The points left of the
/// first affected span and right of the last are copied; the rest is built
/// from the right, each new knot blended in by Boehm's rule against the
/// knots already placed.
pub(crate) fn refine_line<P: Point>(old: &KnotVector, xs: &[f64], line: &[Hom<P>]) -> Vec<Hom<P>> {
    let d = old.degree();
    let u = old.as_slice();
    let n = line.len() - 1;
    let r = xs.len();
    let a = old.span_of(xs[0]);
    let b = old.span_of(xs[r - 1]) + 1;
    let mut q = vec![Hom::ZERO; n + 1 + r];
    let mut ub = vec![0.0; u.len() + r];
    q[..=a - d].copy_from_slice(&line[..=a - d]);
    q[b - 1 + r..].copy_from_slice(&line[b - 1..]);
    ub[..=a].copy_from_slice(&u[..=a]);
    ub[b + d + r..].copy_from_slice(&u[b + d..]);
    let mut i = b + d - 1; // the next old knot to place
    let mut k = b + d - 1 + r; // the next new knot slot
    for &x in xs.iter().rev() {
        // Old knots at or right of x move right, with their control points.
        while x <= u[i] && i > a {
            q[k - d - 1] = line[i - d - 1];
            ub[k] = u[i];
            k -= 1;
            i -= 1;
        }
        q[k - d - 1] = q[k - d];
        for l in 1..=d {
            let ind = k - d + l;
            let num = ub[k + l] - x;
            q[ind - 1] = if num == 0.0 {
                q[ind]
            } else {
                Hom::lerp(q[ind], q[ind - 1], num / (ub[k + l] - u[i - d + l]))
            };
        }
        ub[k] = x;
        k -= 1;
    }
    q
}

/// Where a line is cut to split it at `t`, once `t` has multiplicity `d` or
/// `d + 1` in `knots`: the left piece's knots and the number of its control
/// points, the right piece's knots and the index of its first control point.
pub(crate) fn split_cut(knots: &KnotVector, t: f64) -> (KnotVector, usize, KnotVector, usize) {
    let d = knots.degree();
    let u = knots.as_slice();
    let p = u.partition_point(|&x| x < t);
    let run = knots.multiplicity(t);
    let mut left = u[..p].to_vec();
    left.extend(std::iter::repeat_n(t, d + 1));
    let mut right = vec![t; d + 1];
    right.extend_from_slice(&u[p + run..]);
    (
        KnotVector::from_raw(left, d),
        p,
        KnotVector::from_raw(right, d),
        p + run - d - 1,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nurbs::NurbsCurve;
    use glam::DVec2;

    fn hom(points: &[DVec2]) -> Vec<Hom<DVec2>> {
        points.iter().map(|&p| Hom { p, w: 1.0 }).collect()
    }

    /// A5.4 by hand: the midpoints of a uniform quadratic's domain and its
    /// ends, inserted into the knots -2..=4, give the Bézier points of every
    /// span: the edge midpoints and the inner control points.
    #[test]
    fn refinement_of_a_uniform_quadratic_by_hand() {
        let p = [
            DVec2::new(0.0, 0.0),
            DVec2::new(2.0, 4.0),
            DVec2::new(4.0, 0.0),
            DVec2::new(8.0, 2.0),
        ];
        let k = KnotVector::uniform(4, 2).unwrap();
        let q = refine_line(&k, &[0.0, 1.0, 2.0], &hom(&p));
        let mid = |a: DVec2, b: DVec2| (a + b) * 0.5;
        let expected = [
            p[0],
            mid(p[0], p[1]),
            p[1],
            mid(p[1], p[2]),
            p[2],
            mid(p[2], p[3]),
            p[3],
        ];
        assert_eq!(q.iter().map(|h| h.p).collect::<Vec<_>>(), expected);
        assert_eq!(
            k.merged(&[0.0, 1.0, 2.0]).as_slice(),
            [-2., -1., 0., 0., 1., 1., 2., 2., 3., 4.]
        );
    }

    /// A closed curve's insertion against the open curve over three periods
    /// (the periodic knots and points unrolled) with `t - T`, `t` and
    /// `t + T` inserted: the middle period agrees.
    #[test]
    fn periodic_insertion_equals_inserting_every_image_into_the_unrolled_curve() {
        for d in 1..=4usize {
            let n = d + 2;
            let breaks: Vec<f64> = (0..=n).map(|i| (i * i) as f64 * 0.5 + i as f64).collect();
            let period = breaks[n] - breaks[0];
            let p: Vec<DVec2> = (0..n)
                .map(|i| DVec2::new((i as f64 * 1.7).sin() * 3.0, (i as f64 * 0.9).cos() * 2.0))
                .collect();
            let closed = NurbsCurve::closed(p.clone(), d, breaks.clone(), None).unwrap();
            // u(i) with u(d) = s_0, periodic; the unrolled curve starts a period lower.
            let u = |i: isize| {
                let j = i - d as isize;
                let (q, r) = (j.div_euclid(n as isize), j.rem_euclid(n as isize));
                breaks[r as usize] + q as f64 * period
            };
            let knots: Vec<f64> = (0..=(3 * n + 2 * d) as isize)
                .map(|k| u(k - n as isize))
                .collect();
            let points: Vec<DVec2> = (0..3 * n + d).map(|k| p[k % n]).collect();
            let unrolled = NurbsCurve::new(points, d, knots, None).unwrap();
            for t in [
                breaks[0] + 0.3,
                0.5 * (breaks[1] + breaks[2]),
                breaks[n - 1],
            ] {
                let q = closed.insert(t).unwrap();
                let r = unrolled.insert_many(&[t - period, t, t + period]).unwrap();
                for (i, &qi) in q.points().iter().enumerate() {
                    let ri = r.points()[n + 1 + i];
                    assert!(
                        (qi - ri).length() < 1e-12,
                        "d={d} t={t} i={i}: {qi} vs {ri}"
                    );
                }
                let ks = r.knots().as_slice();
                for (i, &x) in q.knots().as_slice().iter().enumerate() {
                    assert!((x - ks[n + 1 + i]).abs() < 1e-12, "knot {i}");
                }
            }
        }
    }
}
