//! Homogeneous control points `(w P, w)`: what every algorithm of the module
//! works on, rational or not (a polynomial curve has `w = 1`, and its point
//! part is then computed exactly as without the weight).

use super::NurbsError;
use crate::curve::Point;
use std::ops::{Add, Mul, Sub};

/// A homogeneous point: the weighted point `p = w P` and the weight `w`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Hom<P> {
    /// `w P`.
    pub p: P,
    /// `w`.
    pub w: f64,
}

impl<P: Point> Hom<P> {
    pub const ZERO: Self = Hom { p: P::ZERO, w: 0.0 };

    /// `(1 - alpha) a + alpha b`, exact at `alpha = 0` and `alpha = 1`.
    pub fn lerp(a: Self, b: Self, alpha: f64) -> Self {
        a * (1.0 - alpha) + b * alpha
    }

    /// The Euclidean point: `p / w` for a rational curve, `p` otherwise.
    pub fn point(self, rational: bool) -> P {
        if rational {
            self.p * (1.0 / self.w)
        } else {
            self.p
        }
    }
}

impl<P: Point> Add for Hom<P> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Hom {
            p: self.p + o.p,
            w: self.w + o.w,
        }
    }
}

impl<P: Point> Sub for Hom<P> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Hom {
            p: self.p - o.p,
            w: self.w - o.w,
        }
    }
}

impl<P: Point> Mul<f64> for Hom<P> {
    type Output = Self;
    fn mul(self, s: f64) -> Self {
        Hom {
            p: self.p * s,
            w: self.w * s,
        }
    }
}

/// Checks the control points (finite) and the weights (as many as points,
/// positive, finite, and `w P` finite), and returns the homogeneous points.
pub(crate) fn homogeneous<P: Point>(
    points: &[P],
    weights: Option<&[f64]>,
) -> Result<Vec<Hom<P>>, NurbsError> {
    if let Some(index) = points.iter().position(|p| !p.is_finite()) {
        return Err(NurbsError::NonFinitePoint { index });
    }
    let Some(weights) = weights else {
        return Ok(points.iter().map(|&p| Hom { p, w: 1.0 }).collect());
    };
    if weights.len() != points.len() {
        return Err(NurbsError::WrongWeightCount {
            expected: points.len(),
            got: weights.len(),
        });
    }
    let mut out = Vec::with_capacity(points.len());
    for (index, (&p, &w)) in points.iter().zip(weights).enumerate() {
        if !(w > 0.0 && w.is_finite()) {
            return Err(NurbsError::BadWeight { index, weight: w });
        }
        let h = Hom { p: p * w, w };
        if !h.p.is_finite() {
            return Err(NurbsError::WeightedOverflow { index });
        }
        out.push(h);
    }
    Ok(out)
}

/// Splits homogeneous points into Euclidean points and (for a rational
/// curve) weights.
pub(crate) fn split_hom<P: Point>(hom: &[Hom<P>], rational: bool) -> (Vec<P>, Option<Vec<f64>>) {
    let points = hom.iter().map(|h| h.point(rational)).collect();
    let weights = rational.then(|| hom.iter().map(|h| h.w).collect());
    (points, weights)
}

/// De Casteljau's algorithm: the Bézier curve with the control points `h` at `s`.
pub(crate) fn de_casteljau<P: Point>(mut h: Vec<Hom<P>>, s: f64) -> Hom<P> {
    for r in 1..h.len() {
        for i in 0..h.len() - r {
            h[i] = Hom::lerp(h[i], h[i + 1], s);
        }
    }
    h.first().copied().unwrap_or(Hom::ZERO)
}

/// The homogeneous points of `points` with the optional `weights` (unchecked).
pub(crate) fn weighted<P: Point>(points: &[P], weights: Option<&[f64]>) -> Vec<Hom<P>> {
    match weights {
        Some(w) => points
            .iter()
            .zip(w)
            .map(|(&p, &w)| Hom { p: p * w, w })
            .collect(),
        None => points.iter().map(|&p| Hom { p, w: 1.0 }).collect(),
    }
}
