//! The exact limit surface where OpenSubdiv's `Far::PatchTable::EvaluateBasis`
//! departs from it ([`Evaluation::ExactLimit`]):
//!
//! * **Single-crease patches honour their sharpness.** OpenSubdiv marks the
//!   crease edge in the patch's boundary mask and `EvaluateBasis` treats it
//!   as a boundary (an infinitely sharp crease), whatever the sharpness.
//!   Here the crease is semi-sharp, as OpenSubdiv's GPU shaders
//!   (`OSD_PATCH_ENABLE_SINGLE_CREASE` in `osd/glslPatchCommon.glsl`)
//!   evaluate it: across the crease the patch is cut into three spans at
//!   `1 - 2^-⌊S⌋` and `1 - 2^-⌈S⌉` from the far edge (`S` the patch's
//!   sharpness); far from the crease the surface is the infinitely sharp
//!   one (the boundary B-spline), nearest the crease the polynomial that
//!   `⌊S⌋` sharp steps followed by smooth ones leave, blended with the
//!   `⌈S⌉` one by the fraction of `S`, and in the middle span the `⌊S⌋`
//!   polynomial blended with the infinitely sharp one. Along the crease the
//!   patch stays the uniform B-spline.
//! * **Derivatives are with respect to the ptex face's own (u, v)**: a
//!   patch under a non-quad base face covers `1 / 2^(d - 1)` of its ptex
//!   face (the sub-face), so its derivatives are scaled by `2^(d - 1)` per
//!   order, not `2^d` as `EvaluateBasis` scales them. Patches of quad faces
//!   are scaled as OpenSubdiv scales them.
//!
//! Every other patch type, and every other patch, is evaluated as
//! OpenSubdiv evaluates it.
//!
//! Why this is the limit: with sharpness `S` an integer, subdivision
//! applies the crease rules `S` times, then smooth rules. After `k ≤ S`
//! sharp steps the sub-patches not touching the crease are B-spline
//! patches of points that sharp refinement of the infinitely sharp crease
//! gives too, so the span `[0, 1 - 2^-S]` is the infinitely sharp surface;
//! the last span is the B-spline of the points `S` sharp steps leave there.
//! A fractional sharpness `S = ⌊S⌋ + r` makes step `⌈S⌉` blend the sharp and
//! smooth rules by `r`, which is linear in the points: the surface is `(1 -
//! r)` times the `⌊S⌋` surface plus `r` times the `⌈S⌉` one.

use super::basis::bezier;
use super::{
    Derivatives, Partials, PatchData, PatchHandle, PatchParam, PatchTable, PatchType, basis,
};
use crate::error::Result;

/// How a patch table's patches are evaluated: as OpenSubdiv's
/// `EvaluateBasis` evaluates them (the default: the conformance tests
/// compare it with OpenSubdiv), or as the limit surface (single-crease
/// patches with their sharpness, derivatives under non-quad faces with
/// respect to the ptex face's own parameters; see
/// [`evaluate_basis_exact`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Evaluation {
    /// OpenSubdiv's `EvaluateBasis`, departures included.
    #[default]
    OpenSubdiv,
    /// The exact limit surface.
    ExactLimit,
}

/// Conversion of the four B-spline points across an infinitely sharp crease
/// at the far end (`t = 1`) to the four Bézier points of the span: row `i`
/// the weights of Bézier point `i`.
const INF_SHARP: [[f64; 4]; 4] = [
    [1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0, 0.0],
    [0.0, 4.0 / 6.0, 2.0 / 6.0, 0.0],
    [0.0, 2.0 / 6.0, 4.0 / 6.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
];

/// The Bézier points of the span nearest a crease of integer sharpness `k`
/// at the far end, after `k` sharp steps and smooth ones, as weights of the
/// four B-spline points across the crease (with `σ = 2^k`; `k = 0` is the
/// uniform B-spline's conversion).
fn semi_sharp(k: f64) -> [[f64; 4]; 4] {
    let s = k.exp2();
    let (s2, s3) = (s * s, s * s * s);
    let d = 6.0 * s;
    [
        [
            1.0 / 6.0,
            (s + 1.0 + 3.0 * s2 - s3) / d,
            (7.0 * s - 2.0 - 6.0 * s2 + 2.0 * s3) / d,
            (1.0 - s) * (s - 1.0) * (s - 1.0) / d,
        ],
        [
            0.0,
            (1.0 + s) * (1.0 + s) / d,
            (6.0 * s - 2.0 - 2.0 * s2) / d,
            (s - 1.0) * (s - 1.0) / d,
        ],
        [0.0, (1.0 + s) / d, (6.0 * s - 2.0) / d, (1.0 - s) / d],
        [0.0, 1.0 / d, (6.0 * s - 2.0) / d, 1.0 / d],
    ]
}

/// `(1 - r) a + r b`, entry by entry.
fn mix(a: &[[f64; 4]; 4], b: &[[f64; 4]; 4], r: f64) -> [[f64; 4]; 4] {
    std::array::from_fn(|i| std::array::from_fn(|k| (1.0 - r) * a[i][k] + r * b[i][k]))
}

/// The weights of four B-spline points across a crease of sharpness
/// `sharpness` at the far end (`x = 1`), at `x`, with their first and
/// second derivatives. Sharpness 0 (or less) is the uniform B-spline.
pub(crate) fn across_crease(x: f64, sharpness: f64) -> [[f64; 4]; 3] {
    let matrix = if sharpness > 0.0 {
        let (floor, ceil) = (sharpness.floor(), sharpness.ceil());
        let r = sharpness - floor;
        let lower = semi_sharp(floor);
        if x <= 1.0 - (-floor).exp2() {
            INF_SHARP
        } else if x <= 1.0 - (-ceil).exp2() {
            mix(&lower, &INF_SHARP, r)
        } else {
            mix(&lower, &semi_sharp(ceil), r)
        }
    } else {
        semi_sharp(0.0)
    };
    let b = bezier(x);
    std::array::from_fn(|order| {
        std::array::from_fn(|k| (0..4).map(|i| b[order][i] * matrix[i][k]).sum())
    })
}

/// The 16 weights of a single-crease patch (points row by row from `t =
/// 0`) whose crease is edge `edge` (0 the row `t = 0`, 1 the column `s =
/// 1`, 2 the row `t = 1`, 3 the column `s = 0`), at (`s`, `t`) of the
/// patch, into the tables asked for (position, ∂s, ∂t, ∂ss, ∂st, ∂tt; an
/// empty table is not asked for). Derivatives are with respect to the
/// patch's own parameters.
pub(crate) fn single_crease(s: f64, t: f64, edge: u32, sharpness: f64, out: &mut [&mut [f64]; 6]) {
    // The crease at x = 1 of the axis across it: reversed (x = 1 - the
    // parameter, points in the opposite order, odd derivatives negated)
    // when the crease is at the parameter's 0.
    let across = |p: f64, reversed: bool| -> [[f64; 4]; 3] {
        if !reversed {
            return across_crease(p, sharpness);
        }
        let w = across_crease(1.0 - p, sharpness);
        std::array::from_fn(|order| {
            let sign = if order == 1 { -1.0 } else { 1.0 };
            std::array::from_fn(|k| sign * w[order][3 - k])
        })
    };
    let (ws, wt) = match edge {
        0 => (basis::bspline(s), across(t, true)),
        1 => (across(s, false), basis::bspline(t)),
        2 => (basis::bspline(s), across(t, false)),
        _ => (across(s, true), basis::bspline(t)),
    };
    for (table, (os, ot)) in out.iter_mut().zip(basis::ORDERS) {
        if table.is_empty() {
            continue;
        }
        for row in 0..4 {
            for col in 0..4 {
                table[4 * row + col] = ws[os][col] * wt[ot][row];
            }
        }
    }
}

/// [`evaluate_basis`](super::evaluate_basis) of the exact limit surface
/// ([`Evaluation::ExactLimit`]): `sharpness` is the patch's single-crease
/// sharpness (the table's `PatchArray::sharpness`; 0 for every patch that
/// is not a single-crease patch). A regular patch with a positive
/// sharpness is a single-crease patch whose boundary mask names its crease
/// edge (as OpenSubdiv's factory marks it); its crease is evaluated
/// semi-sharp. Derivatives are with respect to the ptex face's (u, v),
/// sub-faces of non-quad faces included. Errors as
/// [`evaluate_basis`](super::evaluate_basis)'s.
///
/// ```
/// use subdiv::patches::{evaluate_basis, evaluate_basis_exact, Derivatives, PatchParam, PatchType};
/// // A single-crease patch of depth 1, its crease along edge 1 (s = 1),
/// // sharpness 2: up to s = 1 - 2^-2 of the patch (u = 0.375 of the ptex
/// // face) it is the infinitely sharp surface, the boundary B-spline
/// // OpenSubdiv's `EvaluateBasis` evaluates everywhere.
/// let p = PatchParam::new(0, 0, 0, 1, false, 0b0010, 0, true);
/// let sharp = evaluate_basis(PatchType::Regular, p, 0.3, 0.4, Derivatives::None)?;
/// let exact = evaluate_basis_exact(PatchType::Regular, p, 2.0, 0.3, 0.4, Derivatives::None)?;
/// assert!(sharp.point.iter().zip(&exact.point).all(|(a, b)| (a - b).abs() < 1e-15));
/// // Nearer the crease they part.
/// let sharp = evaluate_basis(PatchType::Regular, p, 0.45, 0.4, Derivatives::None)?;
/// let exact = evaluate_basis_exact(PatchType::Regular, p, 2.0, 0.45, 0.4, Derivatives::None)?;
/// assert!(sharp.point.iter().zip(&exact.point).any(|(a, b)| (a - b).abs() > 1e-3));
/// # Ok::<(), subdiv::Error>(())
/// ```
pub fn evaluate_basis_exact(
    patch_type: PatchType,
    param: PatchParam,
    sharpness: f32,
    u: f64,
    v: f64,
    derivatives: Derivatives,
) -> Result<Partials> {
    basis::evaluate_basis_partials(patch_type, param, u, v, derivatives, Some(sharpness))
}

/// What `evaluate_basis_into` is given for `evaluation` at patch `handle`
/// of `table` for `data`: `None` for OpenSubdiv's basis; for the exact
/// limit, the single-crease sharpness of a vertex patch (0 when the table
/// has none, and for varying and face-varying patches, which are never
/// single-crease patches). `handle` has been checked by `patch_of`.
pub(crate) fn exact_sharpness(
    evaluation: Evaluation,
    table: &PatchTable,
    data: PatchData,
    handle: PatchHandle,
) -> Option<f32> {
    match (evaluation, data) {
        (Evaluation::OpenSubdiv, _) => None,
        (Evaluation::ExactLimit, PatchData::Vertex) => Some(
            table
                .arrays
                .get(handle.array)
                .and_then(|a| a.sharpness.get(handle.patch))
                .copied()
                .unwrap_or(0.0),
        ),
        (Evaluation::ExactLimit, _) => Some(0.0),
    }
}
