//! Basis functions of the triangular patches of Loop tables
//! (`Far::PatchTable::EvaluateBasis` for `LOOP` and `GREGORY_TRIANGLE`):
//! the quartic box spline of regular Loop patches, with the phantom points
//! of boundary edges and vertices folded in, and the 18-point quartic
//! Gregory triangle of Loop end caps.
//!
//! Both are evaluated at `(s, t)` of the triangle with corners `(0, 0)`,
//! `(1, 0)` and `(0, 1)` (barycentric `w = 1 - s - t` at the first corner,
//! as OpenSubdiv orients them); derivatives are with respect to `s` and `t`
//! (the caller scales them to the ptex face). The box spline is evaluated
//! in `f64` from Stam's coefficients, or in OpenSubdiv's operation order in
//! any precision (`box_spline_osd`, the `f32` basis); the phantom points
//! fold in OpenSubdiv's order in both.

use crate::real::Real;

/// Exponents `(a, b)` of the fifteen monomials `s^a t^b` of degree at most
/// four, in the order of the box spline's coefficient rows.
const MONOMIALS: [(usize, usize); 15] = [
    (0, 0),
    (1, 0),
    (0, 1),
    (2, 0),
    (1, 1),
    (0, 2),
    (3, 0),
    (2, 1),
    (1, 2),
    (0, 3),
    (4, 0),
    (3, 1),
    (2, 2),
    (1, 3),
    (0, 4),
];

/// The twelve basis functions of the regular Loop patch (Stam's quartic
/// box spline, "Evaluation of Loop Subdivision Surfaces") as polynomials in
/// `s` and `t`: twelve times the coefficient of each monomial of
/// [`MONOMIALS`]. Points are numbered row by row from `t = 0`:
///
/// ```text
///        10 -- 11
///       /  \  /  \
///      7 -- 8 --- 9
///     / \  / \  /  \
///    3 -- 4 --- 5 -- 6
///     \  / \  / \  /
///      0 -- 1 --- 2
/// ```
///
/// with the patch the triangle 4, 5, 8.
pub(super) const BOX_SPLINE: [[i32; 15]; 12] = [
    [1, -2, -4, 0, 6, 6, 2, 0, -6, -4, -1, -2, 0, 2, 1],
    [1, 2, -2, 0, -6, 0, -4, 0, 6, 2, 2, 4, 0, -2, -1],
    [0, 0, 0, 0, 0, 0, 2, 0, 0, 0, -1, -2, 0, 0, 0],
    [1, -4, -2, 6, 6, 0, -4, -6, 0, 2, 1, 2, 0, -2, -1],
    [6, 0, 0, -12, -12, -12, 8, 12, 12, 8, -1, -2, 0, -2, -1],
    [1, 4, 2, 6, 6, 0, -4, -6, -12, -4, -1, -2, 0, 4, 2],
    [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 2, 0, 0, 0],
    [1, -2, 2, 0, -6, 0, 2, 6, 0, -4, -1, -2, 0, 4, 2],
    [1, 2, 4, 0, 6, 6, -4, -12, -6, -4, 2, 4, 0, -2, -1],
    [0, 0, 0, 0, 0, 0, 2, 6, 6, 2, -1, -2, 0, -2, -1],
    [0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 0, 0, -2, -1],
    [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 1],
];

/// `n! / (n - d)!`: the factor a `d`-th derivative of `x^n` brings down.
const fn falling(n: usize, d: usize) -> f64 {
    let mut product = 1.0;
    let mut k = 0;
    while k < d {
        product *= (n - k) as f64;
        k += 1;
    }
    product
}

/// The index in [`MONOMIALS`] of `s^a t^b`.
const fn monomial_index(a: usize, b: usize) -> usize {
    let mut j = 0;
    while MONOMIALS[j].0 != a || MONOMIALS[j].1 != b {
        j += 1;
    }
    j
}

/// One derivative of the box spline, worked out once: what each monomial
/// becomes and which terms each point's weight sums.
struct Derivative {
    /// For each monomial `s^a t^b`: the factor the derivative brings down
    /// (0 when it removes the monomial) and the powers of `s` and `t` left.
    monomials: [(f64, usize, usize); 15],
    /// For each point: its nonzero coefficients (twelve times the box
    /// spline's) with the index of the monomial each multiplies, in
    /// monomial order, and how many there are.
    terms: [([(f64, usize); 15], usize); 12],
    /// The same terms in OpenSubdiv's form: the derivative's coefficient
    /// divided by twelve times [`Derivative::scale`], and the index of the
    /// monomial `s^(a-ds) t^(b-dt)` it multiplies.
    osd_terms: [([(f64, usize); 15], usize); 12],
    /// OpenSubdiv's scale, applied last: 1/12, 1/6, 1 or 1/2.
    scale: f64,
}

impl Derivative {
    /// The `(ds, dt)` derivative.
    const fn new(ds: usize, dt: usize) -> Derivative {
        let (twelve_scale, scale) = match (ds, dt) {
            (0, 0) => (1.0, 1.0 / 12.0),
            (1, 0) | (0, 1) => (2.0, 1.0 / 6.0),
            (1, 1) => (6.0, 0.5),
            _ => (12.0, 1.0),
        };
        let mut monomials = [(0.0, 0, 0); 15];
        let mut j = 0;
        while j < 15 {
            let (a, b) = MONOMIALS[j];
            if a >= ds && b >= dt {
                monomials[j] = (falling(a, ds) * falling(b, dt), a - ds, b - dt);
            }
            j += 1;
        }
        let mut terms = [([(0.0, 0); 15], 0); 12];
        let mut osd_terms = [([(0.0, 0); 15], 0); 12];
        let mut i = 0;
        while i < 12 {
            let mut j = 0;
            while j < 15 {
                let c = BOX_SPLINE[i][j];
                let (a, b) = MONOMIALS[j];
                if c != 0 && a >= ds && b >= dt {
                    let (list, n) = &mut terms[i];
                    list[*n] = (c as f64, j);
                    *n += 1;
                    let d = c as f64 * (falling(a, ds) * falling(b, dt)) / twelve_scale;
                    let (list, n) = &mut osd_terms[i];
                    list[*n] = (d, monomial_index(a - ds, b - dt));
                    *n += 1;
                }
                j += 1;
            }
            i += 1;
        }
        Derivative {
            monomials,
            terms,
            osd_terms,
            scale,
        }
    }
}

/// `[body with I = 0, …, body with I = 11]`: an expression per point of the
/// box spline, each compiled with the point's index `I` a constant.
macro_rules! per_point {
    ($i:ident => $body:expr) => {
        per_point!(@ $i => $body; 0 1 2 3 4 5 6 7 8 9 10 11)
    };
    (@ $i:ident => $body:expr; $($k:literal)*) => {
        [$({
            const $i: usize = $k;
            $body
        }),*]
    };
}

/// The `(DS, DT)` derivative as a constant, so that each weight's sum is
/// compiled with its coefficients and its monomials known.
struct Of<const DS: usize, const DT: usize>;

impl<const DS: usize, const DT: usize> Of<DS, DT> {
    const D: Derivative = Derivative::new(DS, DT);

    /// Twelve times the native weight of point `I`: its terms summed in
    /// monomial order.
    #[inline(always)]
    fn native<const I: usize>(m: &[f64; 15]) -> f64 {
        let (list, n) = const { Self::D.terms[I] };
        let mut sum = -0.0;
        for &(c, j) in &list[..n] {
            sum += c * m[j];
        }
        sum
    }

    /// The weights of all twelve points from the powers of `s` and `t`.
    #[inline(always)]
    fn native_all(ps: &[f64; 5], pt: &[f64; 5], w: &mut [f64; 12]) {
        // (Loops, not `map`: an array's `map` was an out-of-line call.)
        let monomials = const { Self::D.monomials };
        let mut m = [0.0; 15];
        for (x, &(factor, a, b)) in m.iter_mut().zip(&monomials) {
            *x = factor * ps[a] * pt[b];
        }
        let all = per_point!(I => Self::native::<I>(&m));
        // Divided side by side (vector divisions).
        for (out, x) in w.iter_mut().zip(all) {
            *out = x / 12.0;
        }
    }

    /// OpenSubdiv's weight of point `I` from its monomials `m`: the first
    /// term, then each next one added, times the scale.
    #[inline(always)]
    fn osd<R: Real, const I: usize>(m: &[R; 15]) -> R {
        let (list, n) = const { Self::D.osd_terms[I] };
        if n == 0 {
            return R::ZERO;
        }
        let mut sum = R::from_f64(list[0].0) * m[list[0].1];
        for &(c, j) in &list[1..n] {
            sum += R::from_f64(c) * m[j];
        }
        R::from_f64(const { Self::D.scale }) * sum
    }

    /// OpenSubdiv's weights of all twelve points from the monomials.
    #[inline(always)]
    fn osd_all<R: Real>(m: &[R; 15], w: &mut [R; 12]) {
        *w = per_point!(I => Self::osd::<R, I>(m));
    }
}

/// The weights of the box spline's twelve points for the `(ds, dt)`
/// derivative at `(s, t)`: each point's nonzero terms `c * m` summed in
/// monomial order, `m` the derivative of the monomial (its factor times the
/// powers of `s` and `t`, each `x.powi(k)`), the sum divided by twelve.
/// Each sum is compiled with its terms known ([`Of`]): the derivative is
/// chosen once, not per term.
pub(super) fn box_spline(s: f64, t: f64, ds: usize, dt: usize, w: &mut [f64; 12]) {
    let ps = [1.0, s, s.powi(2), s.powi(3), s.powi(4)];
    let pt = [1.0, t, t.powi(2), t.powi(3), t.powi(4)];
    match (ds, dt) {
        (0, 0) => Of::<0, 0>::native_all(&ps, &pt, w),
        (1, 0) => Of::<1, 0>::native_all(&ps, &pt, w),
        (0, 1) => Of::<0, 1>::native_all(&ps, &pt, w),
        (2, 0) => Of::<2, 0>::native_all(&ps, &pt, w),
        (1, 1) => Of::<1, 1>::native_all(&ps, &pt, w),
        _ => Of::<0, 2>::native_all(&ps, &pt, w),
    }
}

/// [`box_spline`] in OpenSubdiv's operation order
/// (`evalBoxSplineTriDerivWeights`), in `R`: the monomials built from one
/// another as OpenSubdiv builds them, each weight a sum over its nonzero
/// terms in monomial order — the constant first, then `c * m` for integer
/// coefficients `c` — times a scale applied last, the nearest `R` to 1/12
/// for positions, to 1/6 for first derivatives, 1 for `ss` and `tt` and
/// 1/2 for `st`. The coefficients are [`BOX_SPLINE`]'s, differentiated and
/// divided by twelve times that scale.
pub(super) fn box_spline_osd<R: Real>(s: R, t: R, ds: usize, dt: usize, w: &mut [R; 12]) {
    let (ss, st, tt) = (s * s, s * t, t * t);
    let (sss, sst, stt, ttt) = (ss * s, st * s, st * t, tt * t);
    let m = [
        R::ONE,
        s,
        t,
        ss,
        st,
        tt,
        sss,
        sst,
        stt,
        ttt,
        sss * s,
        sst * s,
        ss * tt,
        stt * t,
        ttt * t,
    ];
    match (ds, dt) {
        (0, 0) => Of::<0, 0>::osd_all(&m, w),
        (1, 0) => Of::<1, 0>::osd_all(&m, w),
        (0, 1) => Of::<0, 1>::osd_all(&m, w),
        (2, 0) => Of::<2, 0>::osd_all(&m, w),
        (1, 1) => Of::<1, 1>::osd_all(&m, w),
        _ => Of::<0, 2>::osd_all(&m, w),
    }
}

/// A phantom point beyond the boundary, extrapolated as `a + b - c` from
/// three points of the patch.
type Phantom = (usize, [usize; 3]);

/// Folds a phantom point's weight into the points it is extrapolated from
/// (the additions and the subtraction in OpenSubdiv's order).
fn fold<R: Real>(w: &mut [R], (phantom, [a, b, c]): Phantom) {
    let x = w[phantom];
    w[a] += x;
    w[b] += x;
    w[c] -= x;
    w[phantom] = R::ZERO;
}

/// Folds the weights of the box spline's phantom points into the points
/// they are extrapolated from, as the patch's 5-bit boundary mask says: the
/// low three bits name boundary edges (edge 0 from point 4 to 5, edge 1 from
/// 5 to 8, edge 2 from 8 to 4) — or, when the high bits are 1, boundary
/// vertices (4, 5, 8) instead; when they are 2, the edge bits come with the
/// vertex opposite each edge on the boundary too.
///
/// Each of the three points beyond a boundary edge continues the row along
/// it: the middle one as `b1 + b2 - i` for the edge's ends `b1`, `b2` and
/// the interior point `i` across it; the outer ones reflect across the
/// edge's end (`2 b - i` where the neighbouring edge is a boundary too, else
/// `b + b' - i'` with the points one row in). Beyond a boundary vertex the
/// two points are reflected across it likewise.
pub(super) fn fold_box_spline_phantoms<R: Real>(mask: u32, w: &mut [R]) {
    if mask == 0 {
        return;
    }
    let (high, low) = ((mask >> 3) & 3, mask & 7);
    let (edges, vertices) = match high {
        1 => (0, low),
        2 => (low, ((low & 1) << 2) | (low >> 1)),
        _ => (low, 0),
    };
    let edge = |k: u32| edges & (1 << k) != 0;
    if edge(0) {
        let first = if edge(2) { [4, 4, 8] } else { [4, 3, 7] };
        let last = if edge(1) { [5, 5, 8] } else { [5, 6, 9] };
        for p in [(0, first), (1, [4, 5, 8]), (2, last)] {
            fold(w, p);
        }
    }
    if edge(1) {
        let first = if edge(0) { [5, 5, 4] } else { [5, 2, 1] };
        let last = if edge(2) { [8, 8, 4] } else { [8, 10, 7] };
        for p in [(6, first), (9, [5, 8, 4]), (11, last)] {
            fold(w, p);
        }
    }
    if edge(2) {
        let first = if edge(1) { [8, 8, 5] } else { [8, 11, 9] };
        let last = if edge(0) { [4, 4, 5] } else { [4, 0, 1] };
        for p in [(10, first), (7, [8, 4, 5]), (3, last)] {
            fold(w, p);
        }
    }
    let around: [[Phantom; 2]; 3] = [
        [(3, [4, 7, 8]), (0, [4, 1, 5])],
        [(2, [5, 1, 4]), (6, [5, 9, 8])],
        [(11, [8, 9, 5]), (10, [8, 7, 4])],
    ];
    for (k, pair) in around.into_iter().enumerate() {
        if vertices & (1 << k) != 0 {
            pair.into_iter().for_each(|p| fold(w, p));
        }
    }
}

/// Index of the quartic Bézier triangle's point `p(i, j, k)` (powers of
/// `s`, `t` and `1 - s - t`), numbered row by row from `t = 0`.
fn bezier_index(i: usize, j: usize) -> usize {
    const ROW: [usize; 5] = [0, 5, 9, 12, 14];
    ROW[j] + i
}

/// The `(ds, dt)` derivative of the Bernstein polynomial
/// `n! / (i! j! k!) s^i t^j w^k` with `w = 1 - s - t`: each derivative in
/// `s` is `n` times the difference of the degree-`n - 1` polynomials with
/// `i` and with `k` lowered (in `t`: `j` and `k`).
fn bernstein(n: i32, [i, j, k]: [i32; 3], ds: usize, dt: usize, powers: &[[f64; 5]; 3]) -> f64 {
    if i < 0 || j < 0 || k < 0 {
        return 0.0;
    }
    if ds > 0 {
        let a = bernstein(n - 1, [i - 1, j, k], ds - 1, dt, powers);
        let b = bernstein(n - 1, [i, j, k - 1], ds - 1, dt, powers);
        return f64::from(n) * (a - b);
    }
    if dt > 0 {
        let a = bernstein(n - 1, [i, j - 1, k], ds, dt - 1, powers);
        let b = bernstein(n - 1, [i, j, k - 1], ds, dt - 1, powers);
        return f64::from(n) * (a - b);
    }
    const FACTORIAL: [f64; 5] = [1.0, 1.0, 2.0, 6.0, 24.0];
    let (i, j, k) = (i as usize, j as usize, k as usize);
    FACTORIAL[n as usize] / (FACTORIAL[i] * FACTORIAL[j] * FACTORIAL[k])
        * powers[0][i]
        * powers[1][j]
        * powers[2][k]
}

/// For each of the Gregory triangle's 18 points: the Bézier point it stands
/// for, and which rational factor scales it (`None` for the twelve boundary
/// points). Points come five per corner (corner, the edge points after and
/// before it, the two face points), corners in order, then the three
/// mid-edge points of the quartic boundaries.
const GREGORY_TRI: [((usize, usize), Option<usize>); 18] = [
    ((0, 0), None),
    ((1, 0), None),
    ((0, 1), None),
    ((1, 1), Some(0)),
    ((1, 1), Some(1)),
    ((4, 0), None),
    ((3, 1), None),
    ((3, 0), None),
    ((2, 1), Some(2)),
    ((2, 1), Some(3)),
    ((0, 4), None),
    ((0, 3), None),
    ((1, 3), None),
    ((1, 2), Some(4)),
    ((1, 2), Some(5)),
    ((2, 0), None),
    ((2, 2), None),
    ((0, 2), None),
];

/// The weights of the quartic Gregory triangle's 18 points for the
/// `(ds, dt)` derivative at `(s, t)`: the quartic Bézier triangle whose
/// three interior points blend each corner's two face points rationally —
/// near corner 0 in proportion `s : t`, near corner 1 `t : w`, near corner
/// 2 `w : s` (the first face point's share first; at the corner itself the
/// first takes all). Derivatives hold the blend at the location's values,
/// as OpenSubdiv computes them.
pub(super) fn gregory_triangle(s: f64, t: f64, ds: usize, dt: usize, w: &mut [f64]) {
    let r = 1.0 - s - t;
    let mut powers = [[1.0; 5]; 3];
    for (row, x) in powers.iter_mut().zip([s, t, r]) {
        for e in 1..5 {
            row[e] = row[e - 1] * x;
        }
    }
    let ratio = |a: f64, b: f64| {
        if a + b > 0.0 {
            [a / (a + b), b / (a + b)]
        } else {
            [1.0, 0.0]
        }
    };
    let [g0, g1] = ratio(s, t);
    let [g2, g3] = ratio(t, r);
    let [g4, g5] = ratio(r, s);
    let blends = [g0, g1, g2, g3, g4, g5];
    let mut bezier = [0.0; 15];
    for j in 0..5 {
        for i in 0..5 - j {
            let k = 4 - i - j;
            bezier[bezier_index(i, j)] =
                bernstein(4, [i as i32, j as i32, k as i32], ds, dt, &powers);
        }
    }
    for (out, ((i, j), blend)) in w.iter_mut().zip(GREGORY_TRI) {
        let b = bezier[bezier_index(i, j)];
        *out = match blend {
            Some(g) => b * blends[g],
            None => b,
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Central differences of the position weights against the analytic
    /// derivatives, at a point inside the triangle.
    fn check_derivatives(at: impl Fn(f64, f64, usize, usize) -> Vec<f64>) {
        let (s, t, h) = (0.23, 0.41, 1e-5);
        let n = at(s, t, 0, 0).len();
        for (ds, dt, step) in [(1, 0, (h, 0.0)), (0, 1, (0.0, h))] {
            let plus = at(s + step.0, t + step.1, 0, 0);
            let minus = at(s - step.0, t - step.1, 0, 0);
            let exact = at(s, t, ds, dt);
            for i in 0..n {
                let numeric = (plus[i] - minus[i]) / (2.0 * h);
                assert!((numeric - exact[i]).abs() < 1e-6, "{ds}{dt} {i}");
            }
            // Second derivatives from the first.
            for (ds2, dt2, step2) in [(1, 0, (h, 0.0)), (0, 1, (0.0, h))] {
                let plus = at(s + step2.0, t + step2.1, ds, dt);
                let minus = at(s - step2.0, t - step2.1, ds, dt);
                let exact = at(s, t, ds + ds2, dt + dt2);
                for i in 0..n {
                    let numeric = (plus[i] - minus[i]) / (2.0 * h);
                    assert!((numeric - exact[i]).abs() < 1e-5, "{i}");
                }
            }
        }
    }

    #[test]
    fn box_spline_is_a_partition_of_unity_with_consistent_derivatives() {
        let mut w = [0.0; 12];
        for (s, t) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.2, 0.3)] {
            box_spline(s, t, 0, 0, &mut w);
            assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-15);
            for (ds, dt) in [(1, 0), (0, 1), (2, 0), (1, 1), (0, 2)] {
                box_spline(s, t, ds, dt, &mut w);
                assert!(w.iter().sum::<f64>().abs() < 1e-14);
            }
        }
        // At a corner of a regular patch: the Loop limit mask of a
        // valence-6 vertex, 1/2 on the vertex and 1/12 on each neighbour.
        box_spline(0.0, 0.0, 0, 0, &mut w);
        let expected = [1.0, 1.0, 0.0, 1.0, 6.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0];
        for (a, b) in w.iter().zip(expected) {
            assert!((a - b / 12.0).abs() < 1e-15);
        }
        check_derivatives(|s, t, ds, dt| {
            let mut w = [0.0; 12];
            box_spline(s, t, ds, dt, &mut w);
            w.to_vec()
        });
    }

    #[test]
    fn gregory_triangle_is_a_quartic_bezier_triangle() {
        let mut w = [0.0; 18];
        // The corners interpolate their corner points.
        for ((s, t), corner) in [((0.0, 0.0), 0), ((1.0, 0.0), 5), ((0.0, 1.0), 10)] {
            gregory_triangle(s, t, 0, 0, &mut w);
            for (i, x) in w.iter().enumerate() {
                assert_eq!(*x, if i == corner { 1.0 } else { 0.0 });
            }
        }
        // At the centre every blend is 1/2: an interior Bézier weight
        // 12 s^2 t w = 4/27 split in halves.
        let third = 1.0 / 3.0;
        gregory_triangle(third, third, 0, 0, &mut w);
        assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        assert!((w[3] - 2.0 / 27.0).abs() < 1e-15 && (w[4] - 2.0 / 27.0).abs() < 1e-15);
        // Mid-edge point of edge 0 (p(2, 0, 2)): 6 s^2 w^2.
        gregory_triangle(0.5, 0.0, 0, 0, &mut w);
        assert!((w[15] - 6.0 / 16.0).abs() < 1e-15);
        // With each pair of face points taken as one point, the patch is
        // the polynomial Bézier triangle, whose derivatives are exact.
        check_derivatives(|s, t, ds, dt| {
            let mut w = vec![0.0; 18];
            gregory_triangle(s, t, ds, dt, &mut w);
            for pair in [3, 8, 13] {
                w[pair] += w[pair + 1];
                w[pair + 1] = 0.0;
            }
            w
        });
    }

    /// A boundary edge's phantom points folded in keep the partition of
    /// unity and leave the phantoms without weight.
    #[test]
    fn folded_phantoms_keep_a_partition_of_unity() {
        for mask in 1..32 {
            let mut w = [0.0; 12];
            box_spline(0.3, 0.2, 0, 0, &mut w);
            fold_box_spline_phantoms(mask, &mut w);
            assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-14, "{mask}");
        }
        let mut w = [0.0; 12];
        box_spline(0.3, 0.2, 0, 0, &mut w);
        fold_box_spline_phantoms(1, &mut w);
        assert_eq!(&w[..3], &[0.0; 3]);
    }
}
