//! Native basis functions of patches (`Far::PatchTable::EvaluateBasis`):
//! the weights of a patch's control points at a location of its ptex face,
//! with first and second derivatives, for bicubic B-spline patches (with
//! the phantom points of boundary edges), 20-point Gregory patches,
//! bilinear and linear patches, and Loop's quartic box-spline and 18-point
//! Gregory triangle patches (`triangle_basis.rs`).
//!
//! Parameterization, as OpenSubdiv's: a patch of depth `d` covers the square
//! `[u, u + 1] × [v, v + 1] / 2^(d - n)` of its ptex face (`n` 1 under a
//! non-quad root, whose sub-faces are the ptex faces); the basis is
//! evaluated at the location mapped to `[0, 1]²` and its derivatives are
//! scaled by `2^d` per order (for non-quad roots that is twice the
//! derivative in the ptex square, as OpenSubdiv does). Triangles in the
//! upper half of their parent's square are rotated by 180°: their
//! coordinates are reflected and their odd-order derivatives negated.
//!
//! Precision: the basis is computed in the precision of the weights asked
//! for ([`evaluate_basis_in`]), as OpenSubdiv's `EvaluatePatchBasis<REAL>`.
//! In `f32` the curves (B-spline, Bézier), the Gregory blends and Loop's
//! box spline follow OpenSubdiv's operation order (`Order`), so that
//! `f32` weights are its `float` weights bit for bit; in `f64` they keep
//! the native formulas (within 1e-12 of `EvaluatePatchBasis<double>`,
//! `tests/osd_patches.rs`). Gregory triangle patches and the exact limit's
//! single-crease patches are evaluated in `f64` and rounded to `f32`.

use super::exact::single_crease;
use super::{Derivatives, Partials, PatchParam, PatchType, triangle_basis};
use crate::error::{Error, Result};
use crate::real::{Precision, Real};

/// The uniform cubic B-spline basis at `t` and its first and second
/// derivatives, each of the four functions `N_i` written as the polynomial
/// in `t` that the knot intervals give it.
pub(crate) fn bspline(t: f64) -> [[f64; 4]; 3] {
    let (t2, t3) = (t * t, t * t * t);
    let c = 1.0 - t;
    [
        [
            c * c * c / 6.0,
            (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0,
            (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0,
            t3 / 6.0,
        ],
        [
            -0.5 * c * c,
            1.5 * t2 - 2.0 * t,
            -1.5 * t2 + t + 0.5,
            0.5 * t2,
        ],
        [c, 3.0 * t - 2.0, 1.0 - 3.0 * t, t],
    ]
}

/// The cubic Bernstein polynomials at `t` and their first and second
/// derivatives.
pub(crate) fn bezier(t: f64) -> [[f64; 4]; 3] {
    let c = 1.0 - t;
    [
        [c * c * c, 3.0 * t * c * c, 3.0 * t * t * c, t * t * t],
        [
            -3.0 * c * c,
            3.0 * c * (c - 2.0 * t),
            3.0 * t * (2.0 * c - t),
            3.0 * t * t,
        ],
        [
            6.0 * c,
            6.0 * (3.0 * t - 2.0),
            6.0 * (1.0 - 3.0 * t),
            6.0 * t,
        ],
    ]
}

/// [`bspline`] in OpenSubdiv's operation order (`evalBSplineCurve`): each
/// function as a polynomial in `t`, `t²` and `t³` scaled by the nearest
/// `REAL` to 1/6 last.
fn bspline_osd<R: Real>(t: R) -> [[R; 4]; 3] {
    let c = |x: f64| R::from_f64(x);
    let one6th = c(1.0 / 6.0);
    let (t2, one) = (t * t, R::ONE);
    let t3 = t * t2;
    [
        [
            one6th * (one - c(3.0) * (t - t2) - t3),
            one6th * (c(4.0) - c(6.0) * t2 + c(3.0) * t3),
            one6th * (one + c(3.0) * (t + t2 - t3)),
            one6th * t3,
        ],
        [
            c(-0.5) * t2 + t - c(0.5),
            c(1.5) * t2 - c(2.0) * t,
            c(-1.5) * t2 + t + c(0.5),
            c(0.5) * t2,
        ],
        [-t + one, c(3.0) * t - c(2.0), c(-3.0) * t + one, t],
    ]
}

/// [`bezier`] in OpenSubdiv's operation order (`evalBezierCurve`).
fn bezier_osd<R: Real>(t: R) -> [[R; 4]; 3] {
    let c = |x: f64| R::from_f64(x);
    let (t2, tc) = (t * t, R::ONE - t);
    let tc2 = tc * tc;
    [
        [tc2 * tc, tc2 * t * c(3.0), t2 * tc * c(3.0), t2 * t],
        [
            c(-3.0) * tc2,
            c(9.0) * t2 - c(12.0) * t + c(3.0),
            c(-9.0) * t2 + c(6.0) * t,
            c(3.0) * t2,
        ],
        [
            c(6.0) * tc,
            c(18.0) * t - c(12.0),
            c(-18.0) * t + c(6.0),
            c(6.0) * t,
        ],
    ]
}

/// Whose operation order the curves and Gregory blends follow: the native
/// formulas (the `f64` basis, unchanged) or OpenSubdiv's (the `f32` basis,
/// so that it is OpenSubdiv's `float` basis bit for bit).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Order {
    /// The native formulas, in `f64`.
    Native,
    /// OpenSubdiv's expressions, in `R`.
    OpenSubdiv,
}

impl Order {
    /// The order of the basis in precision `R`.
    fn of<R: Real>() -> Order {
        match R::PRECISION {
            Precision::F64 => Order::Native,
            Precision::F32 => Order::OpenSubdiv,
        }
    }
}

/// A curve basis in `R`: the native `f64` formulas (`native`, rounded to
/// `R`) or OpenSubdiv's operation order in `R` (`osd`).
fn curve<R: Real>(
    t: R,
    order: Order,
    native: fn(f64) -> [[f64; 4]; 3],
    osd: fn(R) -> [[R; 4]; 3],
) -> [[R; 4]; 3] {
    match order {
        Order::Native => {
            // (Loops, not `map`: an array's `map` was an out-of-line call.)
            let mut rounded = [[R::ZERO; 4]; 3];
            for (to, from) in rounded.iter_mut().zip(native(t.to_f64())) {
                for (x, y) in to.iter_mut().zip(from) {
                    *x = R::from_f64(y);
                }
            }
            rounded
        }
        Order::OpenSubdiv => osd(t),
    }
}

/// The pair `(g, 1 - g)` of a Gregory face-point blend `g = num / den`,
/// `num` itself where `den` vanishes (at a corner, where `num` is 0 too):
/// in OpenSubdiv's order `num` times the reciprocal of `den`.
fn blend<R: Real>(num: R, den: R, order: Order) -> (R, R) {
    let g = if den <= R::ZERO {
        num
    } else {
        match order {
            Order::Native => num / den,
            Order::OpenSubdiv => num * (R::ONE / den),
        }
    };
    (g, R::ONE - g)
}

/// Weights of the six tables (position, ∂s, ∂t, ∂ss, ∂st, ∂tt) of `n`
/// points; a table not asked for is empty.
type Tables<'a, R = f64> = [&'a mut [R]; 6];

/// The orders of derivative `(in s, in t)` of the six tables.
pub(crate) const ORDERS: [(usize, usize); 6] = [(0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2)];

/// Room for the weights of any patch (20 points at most) in each table.
pub(crate) type BasisBuffer<R = f64> = [[R; 20]; 6];

/// Folds the weights of the phantom points beyond the boundary edges of a
/// B-spline patch into the points they are extrapolated from: a phantom
/// point is `2 p - q` for `p` the point next to it and `q` the one after,
/// so `p` gains twice its weight, `q` loses it, and the phantom keeps none.
/// Edge 0 is the row `t = 0` (points 0-3), 1 the column `s = 1` (3, 7, 11,
/// 15), 2 the row `t = 1` (12-15), 3 the column `s = 0` (0, 4, 8, 12).
fn fold_phantoms<R: Real>(boundary: u32, w: &mut [R]) {
    // For each edge: the phantom, its neighbour and the next point, as
    // (first index, step along the edge).
    let edges: [([usize; 3], usize); 4] = [
        ([0, 4, 8], 1),
        ([3, 2, 1], 4),
        ([12, 8, 4], 1),
        ([0, 1, 2], 4),
    ];
    for (k, ([phantom, near, far], step)) in edges.into_iter().enumerate() {
        if boundary & (1 << k) == 0 {
            continue;
        }
        for i in 0..4 {
            fold_phantom(w, [phantom, near, far].map(|j| j + i * step));
        }
    }
}

/// Folds the weight of one phantom point (`2 p - q`, `p` its near point and
/// `q` the far one) into the points it is extrapolated from.
#[inline(always)]
fn fold_phantom<R: Real>(w: &mut [R], [phantom, near, far]: [usize; 3]) {
    let x = w[phantom];
    w[far] -= x;
    w[near] += x + x;
    w[phantom] = R::ZERO;
}

/// Where a location of a ptex face lies in a patch: its coordinates (`s`,
/// `t`) in the patch's unit square, the patch's share of the ptex face as
/// a power of two (`scale`) and whether the patch is a triangle rotated by
/// 180° (its coordinates then reflected).
struct PatchCoords<R> {
    s: R,
    t: R,
    scale: R,
    rotated: bool,
}

impl<R: Real> PatchCoords<R> {
    /// (`u`, `v`) of the ptex face in the patch of `param`, a triangular
    /// patch when `triangular`.
    #[inline(always)]
    fn of(param: PatchParam, u: R, v: R, triangular: bool) -> Self {
        let depth = param.depth();
        // (A non-quad root at depth 0 cannot come from OpenSubdiv; as the
        // words are public, it is taken as depth 0 rather than
        // underflowing.)
        let scale = R::from_f64(f64::from(
            1u32 << depth.saturating_sub(u32::from(param.non_quad_root())),
        ));
        let (pu, pv) = (
            R::from_f64(f64::from(param.u())),
            R::from_f64(f64::from(param.v())),
        );
        let rotated = triangular && param.u() + param.v() >= 1 << depth;
        let (s, t) = if rotated {
            let corner = R::from_f64(f64::from(1u32 << depth));
            (corner - pu - u * scale, corner - pv - v * scale)
        } else {
            (u * scale - pu, v * scale - pv)
        };
        PatchCoords {
            s,
            t,
            scale,
            rotated,
        }
    }

    /// The factor of first derivatives with respect to the ptex face:
    /// 2^depth as OpenSubdiv scales them, the patch's share of the ptex face
    /// for the exact limit (`exact`); negated on a rotated triangle.
    #[inline(always)]
    fn first_factor(&self, param: PatchParam, exact: bool) -> R {
        let sign = if self.rotated { -R::ONE } else { R::ONE };
        sign * if exact {
            self.scale
        } else {
            R::from_f64(f64::from(1u32 << param.depth()))
        }
    }
}

/// A bicubic B-spline patch (16 points, row by row from `t = 0`).
fn regular<R: Real>(s: R, t: R, boundary: u32, order: Order, out: &mut Tables<R>) {
    let (bs, bt) = (
        curve(s, order, bspline, bspline_osd),
        curve(t, order, bspline, bspline_osd),
    );
    // (order in s, order in t) of each table.
    for (table, (os, ot)) in out.iter_mut().zip(ORDERS) {
        if table.is_empty() {
            continue;
        }
        for row in 0..4 {
            for col in 0..4 {
                table[4 * row + col] = bs[os][col] * bt[ot][row];
            }
        }
        if boundary != 0 {
            fold_phantoms(boundary, table);
        }
    }
}

/// The crease edge and sharpness of a regular patch evaluated as the exact
/// limit with sharpness `exact`: a single-crease patch (a positive
/// sharpness) names its crease edge in its boundary mask. `None` for a
/// patch evaluated as a plain B-spline patch.
pub(crate) fn crease_of(param: PatchParam, exact: Option<f32>) -> Option<(u32, f64)> {
    exact
        .filter(|&sharpness| sharpness > 0.0 && param.boundary().count_ones() == 1)
        .map(|sharpness| (param.boundary().trailing_zeros(), f64::from(sharpness)))
}

/// A bicubic B-spline patch's basis as its two curves, in `f64`: at
/// (`u`, `v`) of its ptex face, the four functions in s and in t and their
/// first derivatives, the phantom points of the boundary edges folded into
/// each curve (a fold along a row acts on t alone, along a column on s
/// alone, so the folded curves' products are [`regular`]'s folded
/// weights), and the factor of the first derivatives (2^depth as
/// OpenSubdiv scales them; with `exact`, the patch's share of the ptex
/// face, as [`evaluate_basis_into`] scales them for the exact limit). For
/// evaluating a patch as two passes of curve sums (each row of control
/// points summed in s, the rows then in t): fewer products than the
/// sixteen weights per table, the same surface to rounding. `u` and `v`
/// must lie in [0, 1].
#[inline(always)]
pub(crate) fn regular_curves(
    param: PatchParam,
    u: f64,
    v: f64,
    exact: bool,
) -> ([[f64; 4]; 2], [[f64; 4]; 2], f64) {
    let at = PatchCoords::of(param, u, v, false);
    let [bs0, bs1, _] = bspline(at.s);
    let [bt0, bt1, _] = bspline(at.t);
    let (mut bs, mut bt) = ([bs0, bs1], [bt0, bt1]);
    // For each edge: the curve it folds (0 for s, 1 for t) and its
    // phantom, near and far functions.
    let folds: [(usize, [usize; 3]); 4] = [
        (1, [0, 1, 2]),
        (0, [3, 2, 1]),
        (1, [3, 2, 1]),
        (0, [0, 1, 2]),
    ];
    for (k, (curve, phantom)) in folds.into_iter().enumerate() {
        if param.boundary() & (1 << k) != 0 {
            let curves = if curve == 0 { &mut bs } else { &mut bt };
            curves.iter_mut().for_each(|c| fold_phantom(c, phantom));
        }
    }
    (bs, bt, at.first_factor(param, exact))
}

/// A bilinear quad (corners counter-clockwise from `(0, 0)`).
fn bilinear<R: Real>(s: R, t: R, out: &mut Tables<R>) {
    let (one, zero) = (R::ONE, R::ZERO);
    let (sc, tc) = (one - s, one - t);
    let tables: [[R; 4]; 6] = [
        [sc * tc, s * tc, s * t, sc * t],
        [-tc, tc, t, -t],
        [-sc, -s, s, sc],
        [zero; 4],
        [one, -one, one, -one],
        [zero; 4],
    ];
    for (table, w) in out.iter_mut().zip(tables) {
        if !table.is_empty() {
            table.copy_from_slice(&w);
        }
    }
}

/// A linear triangle (corners at `(0, 0)`, `(1, 0)`, `(0, 1)`).
fn linear_triangle<R: Real>(s: R, t: R, out: &mut Tables<R>) {
    let (one, zero) = (R::ONE, R::ZERO);
    let tables: [[R; 3]; 6] = [
        [one - s - t, s, t],
        [-one, one, zero],
        [-one, zero, one],
        [zero; 3],
        [zero; 3],
        [zero; 3],
    ];
    for (table, w) in out.iter_mut().zip(tables) {
        if !table.is_empty() {
            table.copy_from_slice(&w);
        }
    }
}

/// Fills each table asked for with `basis(s, t, ds, dt, table)` at its
/// order of derivative.
fn triangles(s: f64, t: f64, out: &mut Tables, basis: impl Fn(f64, f64, usize, usize, &mut [f64])) {
    for (table, (ds, dt)) in out.iter_mut().zip(ORDERS) {
        if !table.is_empty() {
            basis(s, t, ds, dt, table);
        }
    }
}

/// Fills the tables `out` asks for with a basis only computed in `f64`
/// (`fill`): in place when `R` is `f64`, otherwise into `f64` tables of
/// the same lengths whose weights are then rounded to `R`.
fn in_f64<R: Real>(out: &mut Tables<R>, fill: impl FnOnce(&mut Tables)) {
    if R::PRECISION == Precision::F64 {
        // `R` is `f64`: the casts cannot fail.
        let mut tables: Tables = out
            .each_mut()
            .map(|t| bytemuck::try_cast_slice_mut(t).unwrap_or_default());
        fill(&mut tables);
        return;
    }
    let mut buf: BasisBuffer = [[0.0; 20]; 6];
    let mut k = 0;
    let mut tables: Tables = buf.each_mut().map(|b| {
        let len = out[k].len();
        k += 1;
        &mut b[..len]
    });
    fill(&mut tables);
    for (dst, src) in out.iter_mut().zip(&tables) {
        for (d, &x) in dst.iter_mut().zip(src.iter()) {
            *d = R::from_f64(x);
        }
    }
}

/// A 20-point Gregory patch. Its points come in groups of five per corner
/// (corners counter-clockwise from `(0, 0)`): the corner point, the edge
/// points after and before it (`e+`, `e-`), and the two face points (`f+`,
/// `f-`). It is the bicubic Bézier patch whose twelve boundary points are
/// the corner and edge points and whose four interior points blend each
/// corner's two face points rationally: near corner `i`, the face point
/// across the edge the parameter runs along counts in proportion to the
/// distance from the other edge. Derivatives are those of the Bézier patch
/// with the blend held at the location's values, as OpenSubdiv (and its GPU
/// shaders) compute them.
fn gregory<R: Real>(s: R, t: R, order: Order, out: &mut Tables<R>) {
    // Bézier (column, row) of each boundary point, by Gregory index.
    const BOUNDARY: [(usize, (usize, usize)); 12] = [
        (0, (0, 0)),
        (1, (1, 0)),
        (2, (0, 1)),
        (5, (3, 0)),
        (6, (3, 1)),
        (7, (2, 0)),
        (10, (3, 3)),
        (11, (2, 3)),
        (12, (3, 2)),
        (15, (0, 3)),
        (16, (0, 2)),
        (17, (1, 3)),
    ];
    // Interior Bézier point of each corner, its face points (`f+`, `f-`),
    // and their blends.
    type Interior<R> = ((usize, usize), [usize; 2], (R, R));
    let (sc, tc) = (R::ONE - s, R::ONE - t);
    let interior: [Interior<R>; 4] = [
        ((1, 1), [3, 4], blend(s, s + t, order)),
        ((2, 1), [8, 9], blend(t, sc + t, order)),
        ((2, 2), [13, 14], blend(sc, sc + tc, order)),
        ((1, 2), [18, 19], blend(tc, s + tc, order)),
    ];
    let (bs, bt) = (
        curve(s, order, bezier, bezier_osd),
        curve(t, order, bezier, bezier_osd),
    );
    for (table, (os, ot)) in out.iter_mut().zip(ORDERS) {
        if table.is_empty() {
            continue;
        }
        for (i, (col, row)) in BOUNDARY {
            table[i] = bs[os][col] * bt[ot][row];
        }
        for ((col, row), [plus, minus], (g, gc)) in interior {
            let b = bs[os][col] * bt[ot][row];
            table[plus] = b * g;
            table[minus] = b * gc;
        }
    }
}

/// The weights of the control points of a patch of type `patch_type` with
/// parameterization `param` at (`u`, `v`) of its ptex face — the
/// native `Far::PatchTable::EvaluateBasis` — with the derivatives asked
/// for (with respect to the ptex face's u and v, scaled as OpenSubdiv
/// scales them; see the module documentation).
///
/// Refused: u or v outside [0, 1] ([`Error::Location`]); a type without a
/// basis (legacy Gregory, points, lines: [`Error::NotYetSupported`], naming
/// it — OpenSubdiv has none either).
///
/// ```
/// use subdiv::patches::{evaluate_basis, Derivatives, PatchParam, PatchType};
/// // A regular interior patch covering a whole ptex face, at its centre:
/// // the tensor product of the cubic B-spline basis at 1/2.
/// let w = evaluate_basis(PatchType::Regular, PatchParam::default(), 0.5, 0.5, Derivatives::None)?;
/// let b = [1.0 / 48.0, 23.0 / 48.0, 23.0 / 48.0, 1.0 / 48.0];
/// assert!((w.point[5] - b[1] * b[1]).abs() < 1e-15);
/// assert!((w.point.iter().sum::<f64>() - 1.0).abs() < 1e-15);
/// # Ok::<(), subdiv::Error>(())
/// ```
pub fn evaluate_basis(
    patch_type: PatchType,
    param: PatchParam,
    u: f64,
    v: f64,
    derivatives: Derivatives,
) -> Result<Partials> {
    evaluate_basis_partials(patch_type, param, u, v, derivatives, None)
}

/// [`evaluate_basis`] in precision `R`, as OpenSubdiv's
/// `PatchTable::EvaluateBasis<REAL>`: the location and the weights in `R`.
/// In `f32` the weights of B-spline, Gregory, bilinear, Loop box-spline
/// and linear triangle patches are OpenSubdiv's `float` weights bit for bit
/// (its operation order; see the module documentation); those of Gregory
/// triangle patches are the `f64` weights rounded. In `f64` it is
/// [`evaluate_basis`]. Errors as [`evaluate_basis`]'s.
///
/// ```
/// use subdiv::patches::{evaluate_basis_in, Derivatives, PatchParam, PatchType};
/// let w = evaluate_basis_in::<f32>(PatchType::Regular, PatchParam::default(), 0.5, 0.5, Derivatives::First)?;
/// // The corner B-spline weight at 1/2 is 1/48 in each direction, here as
/// // OpenSubdiv's float code computes it: 1/6 rounded to f32, times 1/8.
/// let b0 = (1.0f64 / 6.0) as f32 * 0.125;
/// assert_eq!(w.point[0], b0 * b0);
/// assert_ne!(w.point[0], (1.0f64 / 2304.0) as f32); // not the f64 weight rounded
/// assert_eq!(w.du.len(), 16);
/// # Ok::<(), subdiv::Error>(())
/// ```
pub fn evaluate_basis_in<R: Real>(
    patch_type: PatchType,
    param: PatchParam,
    u: R,
    v: R,
    derivatives: Derivatives,
) -> Result<Partials<R>> {
    evaluate_basis_partials(patch_type, param, u, v, derivatives, None)
}

/// [`evaluate_basis`] as `Partials`, OpenSubdiv's way (`exact` `None`) or
/// the exact limit's with the patch's single-crease sharpness
/// ([`evaluate_basis_into`]).
pub(crate) fn evaluate_basis_partials<R: Real>(
    patch_type: PatchType,
    param: PatchParam,
    u: R,
    v: R,
    derivatives: Derivatives,
    exact: Option<f32>,
) -> Result<Partials<R>> {
    let mut buf: BasisBuffer<R> = [[R::ZERO; 20]; 6];
    let n = evaluate_basis_into(patch_type, param, u, v, derivatives, exact, &mut buf)?;
    let first = derivatives != Derivatives::None;
    let second = derivatives == Derivatives::Second;
    let take = |k: usize, on: bool| if on { buf[k][..n].to_vec() } else { Vec::new() };
    Ok(Partials {
        point: take(0, true),
        du: take(1, first),
        dv: take(2, first),
        duu: take(3, second),
        duv: take(4, second),
        dvv: take(5, second),
    })
}

/// [`evaluate_basis`] into `buf` (position, ∂u, ∂v, ∂uu, ∂uv, ∂vv: the
/// first 1, 3 or 6 tables as `derivatives` asks), without allocating;
/// returns the patch's number of control points. `exact`: `None` for
/// OpenSubdiv's basis, or the patch's single-crease sharpness (0 for
/// patches that are not single-crease ones) for the exact limit's
/// (`exact.rs`: the crease honoured, derivatives with respect to the ptex
/// face even under non-quad faces).
pub(crate) fn evaluate_basis_into<R: Real>(
    patch_type: PatchType,
    param: PatchParam,
    u: R,
    v: R,
    derivatives: Derivatives,
    exact: Option<f32>,
    buf: &mut BasisBuffer<R>,
) -> Result<usize> {
    let order = Order::of::<R>();
    evaluate_basis_ordered(patch_type, param, u, v, derivatives, exact, order, buf)
}

/// The error of a location (`u`, `v`) outside the unit square.
#[inline(always)]
fn check_unit(param: PatchParam, u: f64, v: f64) -> Result<()> {
    for (coordinate, value) in [("u", u), ("v", v)] {
        if !(0.0..=1.0).contains(&value) {
            return Err(Error::Location {
                face: param.face_id(),
                coordinate,
                value,
            });
        }
    }
    Ok(())
}

/// Where (`u`, `v`) of the ptex face lies in the triangular patch of
/// `param`: its coordinates (`s`, `t`) in the patch and the factor of first
/// derivatives with respect to the ptex face (the `exact` limit's or
/// OpenSubdiv's, as [`evaluate_basis_into`] scales them), or the error of a
/// location outside the unit square.
#[inline(always)]
pub(crate) fn triangle_coords(
    param: PatchParam,
    u: f64,
    v: f64,
    exact: bool,
) -> Result<(f64, f64, f64)> {
    check_unit(param, u, v)?;
    let at = PatchCoords::of(param, u, v, true);
    Ok((at.s, at.t, at.first_factor(param, exact)))
}

/// [`evaluate_basis_into`] with the curves and blends in `order` (the
/// tests check OpenSubdiv's order in `f64` against `EvaluateBasis<double>`).
#[allow(clippy::too_many_arguments)]
pub(crate) fn evaluate_basis_ordered<R: Real>(
    patch_type: PatchType,
    param: PatchParam,
    u: R,
    v: R,
    derivatives: Derivatives,
    exact: Option<f32>,
    order: Order,
    buf: &mut BasisBuffer<R>,
) -> Result<usize> {
    check_unit(param, u.to_f64(), v.to_f64())?;
    let triangular = matches!(
        patch_type,
        PatchType::Triangles | PatchType::Loop | PatchType::GregoryTriangle
    );
    let at = PatchCoords::of(param, u, v, triangular);
    let (s, t) = (at.s, at.t);
    let n = patch_type.control_vertices().min(20);
    let kinds = match derivatives {
        Derivatives::None => 1,
        Derivatives::First => 3,
        Derivatives::Second => 6,
    };
    {
        // The tables asked for, `n` weights each, the others empty (an
        // array literal: `each_mut().map` was an out-of-line call per
        // location).
        let [b0, b1, b2, b3, b4, b5] = buf;
        fn cut<R>(b: &mut [R; 20], len: usize) -> &mut [R] {
            &mut b[..len]
        }
        let len = |k: usize| if k < kinds { n } else { 0 };
        let mut tables: Tables<R> = [
            &mut b0[..n],
            cut(b1, len(1)),
            cut(b2, len(2)),
            cut(b3, len(3)),
            cut(b4, len(4)),
            cut(b5, len(5)),
        ];
        let crease = crease_of(param, exact);
        match patch_type {
            PatchType::Regular => match crease {
                Some((edge, sharpness)) => in_f64(&mut tables, |tables| {
                    single_crease(s.to_f64(), t.to_f64(), edge, sharpness, tables);
                }),
                None => regular(s, t, param.boundary(), order, &mut tables),
            },
            PatchType::GregoryBasis => gregory(s, t, order, &mut tables),
            PatchType::Quads => bilinear(s, t, &mut tables),
            PatchType::Triangles => linear_triangle(s, t, &mut tables),
            PatchType::Loop if order == Order::OpenSubdiv => {
                for (table, (ds, dt)) in tables.iter_mut().zip(ORDERS) {
                    // (A table asked for has the patch's twelve weights.)
                    if let Some(w) = table.first_chunk_mut::<12>() {
                        triangle_basis::box_spline_osd(s, t, ds, dt, w);
                        triangle_basis::fold_box_spline_phantoms(param.boundary(), w);
                    }
                }
            }
            PatchType::Loop => {
                // In `f64` on the stack, then rounded to `R` (a copy when
                // `R` is `f64`).
                let (s, t) = (s.to_f64(), t.to_f64());
                for (table, (ds, dt)) in tables.iter_mut().zip(ORDERS) {
                    if !table.is_empty() {
                        let mut w = [0.0; 12];
                        triangle_basis::box_spline(s, t, ds, dt, &mut w);
                        triangle_basis::fold_box_spline_phantoms(param.boundary(), &mut w);
                        for (d, x) in table.iter_mut().zip(w) {
                            *d = R::from_f64(x);
                        }
                    }
                }
            }
            PatchType::GregoryTriangle => in_f64(&mut tables, |tables| {
                triangles(
                    s.to_f64(),
                    t.to_f64(),
                    tables,
                    triangle_basis::gregory_triangle,
                );
            }),
            _ => {
                return Err(Error::NotYetSupported(
                    "a basis for legacy Gregory patches, points or lines (OpenSubdiv has none either)",
                ));
            }
        }
    }
    // Derivatives with respect to the ptex face: 2^depth per order as
    // OpenSubdiv scales them, the patch's share of the ptex face for the
    // exact limit; a rotated triangle flips the sign of odd orders.
    // OpenSubdiv's EvaluatePatchBasis multiplies its second orders by the
    // sign as well (`derivSign * d1Scale * d1Scale`, d1Scale signed
    // already), negating them on rotated triangles: reproduced by default,
    // not in the exact limit.
    let sign = if at.rotated { -R::ONE } else { R::ONE };
    let d1 = at.first_factor(param, exact.is_some());
    let d2 = if exact.is_some() {
        d1 * d1
    } else {
        sign * d1 * d1
    };
    for (k, table) in buf.iter_mut().enumerate().take(kinds).skip(1) {
        let factor = if k < 3 { d1 } else { d2 };
        // A factor of 1 changes nothing (and reading back the weights just
        // written, in wider loads than they were stored with, stalls).
        if factor != R::ONE {
            table[..n].iter_mut().for_each(|x| *x *= factor);
        }
    }
    Ok(n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::patches::{PatchArray, PatchMap, PatchTable};

    /// `evaluate_basis_in::<f64>` is `evaluate_basis` bit for bit; in `f32`
    /// a B-spline patch's weights are the products of OpenSubdiv's `float`
    /// curve expressions (`evalBSplineCurve`), not the `f64` ones rounded.
    #[test]
    fn basis_in_each_precision() {
        let p = PatchParam::default();
        for ty in [
            PatchType::Regular,
            PatchType::GregoryBasis,
            PatchType::Quads,
            PatchType::Triangles,
            PatchType::Loop,
            PatchType::GregoryTriangle,
        ] {
            for (u, v) in [(0.3, 0.7), (0.0, 0.0), (0.05, 0.95), (1.0, 0.5)] {
                let a = evaluate_basis(ty, p, u, v, Derivatives::Second).unwrap();
                let b = evaluate_basis_in::<f64>(ty, p, u, v, Derivatives::Second).unwrap();
                assert_eq!(a, b, "{ty:?} at ({u}, {v})");
            }
        }
        let curve = |t: f32| {
            let (t2, t3) = (t * t, t * t * t);
            let sixth = (1.0f64 / 6.0) as f32;
            [
                sixth * (1.0 - 3.0 * (t - t2) - t3),
                sixth * (4.0 - 6.0 * t2 + 3.0 * t3),
                sixth * (1.0 + 3.0 * (t + t2 - t3)),
                sixth * t3,
            ]
        };
        let (s, t) = (0.3f32, 0.7f32);
        let w = evaluate_basis_in(PatchType::Regular, p, s, t, Derivatives::None).unwrap();
        let (bs, bt) = (curve(s), curve(t));
        for (k, &x) in w.point.iter().enumerate() {
            assert_eq!(x, bs[k % 4] * bt[k / 4]);
        }
        // The f64 weights rounded differ from them.
        let wide = evaluate_basis(
            PatchType::Regular,
            p,
            0.3f32.into(),
            0.7f32.into(),
            Derivatives::None,
        )
        .unwrap();
        let rounded = wide
            .point
            .iter()
            .zip(&w.point)
            .filter(|&(&a, &b)| a as f32 != b)
            .count();
        assert!(rounded > 0);
    }

    /// OpenSubdiv's operation order (the `f32` basis's) evaluated in `f64`
    /// is `EvaluateBasis<double>` bit for bit on B-spline patches, Gregory
    /// basis end caps and Loop box-spline patches (boundary masks
    /// included), with second derivatives, at locations of every ptex face
    /// of the corpus' quad and triangle meshes: the expressions are
    /// OpenSubdiv's, so in `f32` they are its `float` ones. (Measured: 11,313
    /// interior B-spline, 3,575 Gregory, 4,599 interior box-spline and
    /// 3,026 boundary evaluations.)
    #[cfg(feature = "osd")]
    #[test]
    fn opensubdiv_order_is_evaluate_basis_bit_for_bit() {
        use crate::osd::TopologyRefiner;
        use crate::patches::PatchOptions;
        use crate::{BoundaryInterpolation, Scheme};
        let (mut regular, mut gregory, mut boundary, mut loops) = (0, 0, 0, 0);
        for (name, mesh) in crate::shapes::corpus() {
            let sizes = || mesh.face_offsets.windows(2).map(|w| w[1] - w[0]);
            let scheme = if sizes().all(|n| n == 4) {
                Scheme::Catmark
            } else if sizes().all(|n| n == 3) {
                Scheme::Loop
            } else {
                continue;
            };
            let options = PatchOptions::new().max_isolation(2);
            let sdc = crate::Options::default()
                .with_scheme(scheme)
                .with_boundary(BoundaryInterpolation::EdgeOnly);
            let mut r = TopologyRefiner::new(&mesh, &sdc).unwrap();
            r.refine_adaptive(options.refine_adaptive_options(), &[])
                .unwrap();
            let Ok(table) = r.patch_table(&options, &[]) else {
                continue;
            };
            let coordinates = [0.0, 0.013, 0.2371, 0.5, 0.618, 0.9437, 1.0];
            for face in 0..table.table().ptex_faces as u32 {
                for u in coordinates {
                    for v in coordinates {
                        // Triangles: their parameters only (u + v <= 1).
                        if scheme == Scheme::Loop && u + v > 1.0 {
                            continue;
                        }
                        let Some(h) = table.find_patch(face, u, v).unwrap() else {
                            continue;
                        };
                        let array = &table.table().arrays[h.array];
                        // Gregory triangles keep the native basis.
                        if array.patch_type == PatchType::GregoryTriangle {
                            continue;
                        }
                        let param = array.params[h.patch];
                        let theirs = table.evaluate_basis(h, u, v, Derivatives::Second).unwrap();
                        let mut buf: BasisBuffer = [[0.0; 20]; 6];
                        let n = evaluate_basis_ordered(
                            array.patch_type,
                            param,
                            u,
                            v,
                            Derivatives::Second,
                            None,
                            Order::OpenSubdiv,
                            &mut buf,
                        )
                        .unwrap();
                        let columns = [
                            &theirs.point,
                            &theirs.du,
                            &theirs.dv,
                            &theirs.duu,
                            &theirs.duv,
                            &theirs.dvv,
                        ];
                        let bits = |w: &[f64]| w.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                        for (k, column) in columns.into_iter().enumerate() {
                            assert_eq!(
                                bits(&buf[k][..n]),
                                bits(column),
                                "{name}: {:?} at ({face}, {u}, {v}), table {k}",
                                array.patch_type
                            );
                        }
                        match array.patch_type {
                            _ if param.boundary() != 0 => boundary += 1,
                            PatchType::Regular => regular += 1,
                            PatchType::GregoryBasis => gregory += 1,
                            PatchType::Loop => loops += 1,
                            _ => {}
                        }
                    }
                }
            }
        }
        assert!(
            regular > 1000 && gregory > 1000 && boundary > 100 && loops > 1000,
            "{regular} {gregory} {boundary} {loops}"
        );
    }

    /// Parameter words OpenSubdiv never writes (a non-quad root at depth
    /// 0, the largest fields) are evaluated and located without a panic.
    #[test]
    fn any_param_words_are_safe() {
        for field1 in [1 << 4, u32::MAX, 0] {
            let p = PatchParam {
                field0: u32::MAX,
                field1,
            };
            for ty in [
                PatchType::Regular,
                PatchType::GregoryBasis,
                PatchType::Triangles,
            ] {
                let w = evaluate_basis(ty, p, 1.0, 0.0, Derivatives::Second).unwrap();
                assert_eq!(w.point.len(), ty.control_vertices());
            }
            for varying in [PatchType::Quads, PatchType::Triangles] {
                let table = PatchTable {
                    arrays: vec![PatchArray {
                        patch_type: PatchType::Regular,
                        control_vertices: vec![0; 16],
                        params: vec![p],
                        sharpness: vec![0.0],
                        varying_vertices: Vec::new(),
                    }],
                    varying_patch_type: varying,
                    ..PatchTable::default()
                };
                let map = PatchMap::new(&table);
                let _ = map.find_patch(p.face_id(), 0.5, 1.0);
            }
        }
    }
}
