//! A regular face's bicubic B-spline patch evaluated as the tensor product
//! it is: at each (u, v) the four weights of each direction (their phantom
//! points folded in one dimension), the 16 control points contracted row
//! by row — 20 multiply-adds per component and derivative instead of the
//! 16 two-dimensional weights `EvaluatePatchBasis` forms and applies.
//!
//! The folding is the same as the two-dimensional one of
//! `patches::basis`: a phantom point beyond a boundary is `2 p - q`, so in
//! each direction the weight of the phantom moves to its neighbour (twice)
//! and the next point (negated). Folding rows, then columns, is the tensor
//! product of the two one-dimensional folds.

use crate::patches::basis::ORDERS;

/// The four uniform cubic B-spline weights of one direction at `t` and,
/// up to order `orders - 1`, their derivatives, with the phantom point at
/// the low end (`low`) and the high end (`high`) folded in. (The same
/// polynomials as `patches::basis::bspline`, their sixths taken by one
/// multiplication.)
#[inline]
fn weights(t: f64, orders: usize, low: bool, high: bool) -> [[f64; 4]; 3] {
    const SIXTH: f64 = 1.0 / 6.0;
    let (t2, c) = (t * t, 1.0 - t);
    let t3 = t2 * t;
    let mut w = [[0.0; 4]; 3];
    w[0] = [
        c * c * c * SIXTH,
        (3.0 * t3 - 6.0 * t2 + 4.0) * SIXTH,
        (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) * SIXTH,
        t3 * SIXTH,
    ];
    if orders > 1 {
        w[1] = [
            -0.5 * c * c,
            1.5 * t2 - 2.0 * t,
            -1.5 * t2 + t + 0.5,
            0.5 * t2,
        ];
    }
    if orders > 2 {
        w[2] = [c, 3.0 * t - 2.0, 1.0 - 3.0 * t, t];
    }
    if low || high {
        for order in w.iter_mut().take(orders) {
            if low {
                let x = order[0];
                order[2] -= x;
                order[1] += 2.0 * x;
                order[0] = 0.0;
            }
            if high {
                let x = order[3];
                order[1] -= x;
                order[2] += 2.0 * x;
                order[3] = 0.0;
            }
        }
    }
    w
}

/// Evaluates a B-spline patch at each of `coords` (in `[0, 1]²`):
/// `points` are its 16 control points, row by row from `v = 0`, `width`
/// values each; `mask` its boundary edges (bit 0 the row `v = 0`, 1 the
/// column `u = 1`, 2 the row `v = 1`, 3 the column `u = 0`). Of values,
/// ∂u, ∂v, ∂uu, ∂uv, ∂vv, the first `columns.len()` are written to
/// `columns`, `width` values per coordinate each. Each coordinate goes
/// through `clamp` first.
pub(super) fn evaluate(
    points: &[f64],
    width: usize,
    mask: u16,
    coords: &[[f64; 2]],
    clamp: impl Fn([f64; 2]) -> [f64; 2],
    columns: &mut [&mut [f64]],
) {
    match width {
        1 => evaluate_n::<1>(points, width, mask, coords, clamp, columns),
        2 => evaluate_n::<2>(points, width, mask, coords, clamp, columns),
        3 => evaluate_n::<3>(points, width, mask, coords, clamp, columns),
        4 => evaluate_n::<4>(points, width, mask, coords, clamp, columns),
        // Wider points, four components at a time.
        _ => evaluate_n::<4>(points, width, mask, coords, clamp, columns),
    }
}

/// [`evaluate`] `N` components at a time (the whole point when `width` is
/// `N`).
fn evaluate_n<const N: usize>(
    points: &[f64],
    width: usize,
    mask: u16,
    coords: &[[f64; 2]],
    clamp: impl Fn([f64; 2]) -> [f64; 2],
    columns: &mut [&mut [f64]],
) {
    // The orders the outputs need in u and in v: 0, then 1, then 2.
    let (u_orders, v_orders) = match columns.len() {
        0 | 1 => (1, 1),
        2 => (2, 1),
        3..=5 => (2, 2),
        _ => (3, 3),
    };
    let (u_low, u_high, v_low, v_high) =
        (mask & 8 != 0, mask & 2 != 0, mask & 1 != 0, mask & 4 != 0);
    for start in (0..width).step_by(N) {
        let n = (width - start).min(N);
        let mut p = [[0.0; N]; 16];
        for (dst, src) in p.iter_mut().zip(points.chunks_exact(width)) {
            dst[..n].copy_from_slice(&src[start..start + n]);
        }
        for (i, &uv) in coords.iter().enumerate() {
            let [u, v] = clamp(uv);
            let bu = weights(u, u_orders, u_low, u_high);
            let bv = weights(v, v_orders, v_low, v_high);
            // rows[order][row]: row `row` contracted with the u weights of
            // that order.
            let mut rows = [[[0.0; N]; 4]; 3];
            for (order, w) in bu.iter().enumerate().take(u_orders) {
                for (row, sum) in rows[order].iter_mut().enumerate() {
                    let q = &p[4 * row..4 * row + 4];
                    for k in 0..N {
                        sum[k] = w[0] * q[0][k] + w[1] * q[1][k] + w[2] * q[2][k] + w[3] * q[3][k];
                    }
                }
            }
            for (column, (ou, ov)) in columns.iter_mut().zip(ORDERS) {
                let (w, r) = (&bv[ov], &rows[ou]);
                let out = &mut column[i * width + start..][..n];
                for (k, o) in out.iter_mut().enumerate() {
                    *o = w[0] * r[0][k] + w[1] * r[1][k] + w[2] * r[2][k] + w[3] * r[3][k];
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::patches::basis::{BasisBuffer, evaluate_basis_into};
    use crate::patches::{Derivatives, PatchParam, PatchType};

    /// The tensor product agrees with the two-dimensional basis for every
    /// boundary mask, derivative and a spread of locations.
    #[test]
    fn agrees_with_the_patch_basis() {
        let width = 3;
        let points: Vec<f64> = (0..16 * width)
            .map(|i| ((i * 37 % 23) as f64 - 11.0) * 0.37 + (i / 3) as f64)
            .collect();
        for mask in 0..16u16 {
            let param = PatchParam::new(0, 0, 0, 0, false, mask, 0, true);
            for (u, v) in [(0.0, 0.0), (1.0, 1.0), (0.25, 0.75), (0.9, 0.1), (0.5, 0.5)] {
                let mut buf: BasisBuffer = [[0.0; 20]; 6];
                let n = evaluate_basis_into(
                    PatchType::Regular,
                    param,
                    u,
                    v,
                    Derivatives::Second,
                    None,
                    &mut buf,
                )
                .unwrap();
                assert_eq!(n, 16);
                // Stale values in the outputs: every one is overwritten.
                let mut out: Vec<Vec<f64>> = vec![vec![f64::NAN; width]; 6];
                let mut columns: Vec<&mut [f64]> = out.iter_mut().map(|c| &mut c[..]).collect();
                evaluate(&points, width, mask, &[[u, v]], |uv| uv, &mut columns);
                for (kind, weights) in buf.iter().enumerate() {
                    for k in 0..width {
                        let expected: f64 =
                            (0..16).map(|i| weights[i] * points[i * width + k]).sum();
                        let got = out[kind][k];
                        assert!(
                            (got - expected).abs() <= 1e-12 * (1.0 + expected.abs()),
                            "mask {mask} ({u}, {v}) kind {kind}: {got} against {expected}"
                        );
                    }
                }
            }
        }
    }
}
