//! The 12 points of a Loop (quartic box-spline) end cap (`convertToLoop` in
//! `far/loopPatchBuilder.cpp`): a box-spline triangle cannot keep the limit
//! point and tangents of an irregular corner and its boundary curves at
//! once, so OpenSubdiv fits one to the Gregory triangle instead — the
//! fifteen points of its quartic Bézier form (one face point of each pair
//! standing for the pair) through a fixed 12 × 15 least-squares matrix.
//! Every row is dense over the source points.

use super::loop_gregory::GregoryTriangle;
use super::matrix::Matrix;
use super::source::SourcePatch;
use crate::real::Real;

/// The Gregory triangle's rows standing for the quartic Bézier points
/// `Q0..Q14`: corners, edge points, the one face point of each pair kept,
/// and the mid-edge points.
const BEZIER_ROWS: [usize; 15] = [0, 1, 15, 7, 5, 2, 4, 8, 6, 17, 14, 16, 11, 12, 10];

/// OpenSubdiv's Bézier-to-box-spline fit, one row per box-spline point and
/// one column per Bézier point, in single precision as it writes them.
#[allow(clippy::excessive_precision, clippy::approx_constant)]
const FIT: [[f32; 15]; 12] = [
    [
        8.214411, 7.571190, -7.690082, 2.237840, -1.118922, -16.428828, 0.666666, 0.666666,
        2.237835, 6.309870, 0.666666, -1.690100, -0.428812, -0.428805, 0.214407,
    ],
    [
        -0.304687, 0.609374, 6.752593, 0.609374, -0.304687, 0.609378, -3.333333, -3.333333,
        0.609378, -1.247389, -3.333333, -1.247389, 3.276037, 3.276037, -1.638020,
    ],
    [
        -1.118922, 2.237840, -7.690082, 7.571190, 8.214411, 2.237835, 0.666666, 0.666666,
        -16.428828, -1.690100, 0.666666, 6.309870, -0.428805, -0.428812, 0.214407,
    ],
    [
        8.214411, -16.428828, 6.309870, -0.428812, 0.214407, 7.571190, 0.666666, 0.666666,
        -0.428805, -7.690082, 0.666666, -1.690100, 2.237840, 2.237835, -1.118922,
    ],
    [
        -0.813368, 1.626735, -0.773435, -1.039929, 0.519965, 1.626735, 0.666666, 0.666666,
        -1.039930, -0.773435, 0.666666, 1.226558, -1.039929, -1.039930, 0.519965,
    ],
    [
        0.519965, -1.039929, -0.773435, 1.626735, -0.813368, -1.039930, 0.666666, 0.666666,
        1.626735, 1.226558, 0.666666, -0.773435, -1.039930, -1.039929, 0.519965,
    ],
    [
        0.214407, -0.428812, 6.309870, -16.428828, 8.214411, -0.428805, 0.666666, 0.666666,
        7.571190, -1.690100, 0.666666, -7.690082, 2.237835, 2.237840, -1.118922,
    ],
    [
        -0.304687, 0.609378, -1.247389, 3.276037, -1.638020, 0.609374, -3.333333, -3.333333,
        3.276037, 6.752593, -3.333333, -1.247389, 0.609374, 0.609378, -0.304687,
    ],
    [
        0.519965, -1.039930, 1.226558, -1.039930, 0.519965, -1.039929, 0.666666, 0.666666,
        -1.039929, -0.773435, 0.666666, -0.773435, 1.626735, 1.626735, -0.813368,
    ],
    [
        -1.638020, 3.276037, -1.247389, 0.609378, -0.304687, 3.276037, -3.333333, -3.333333,
        0.609374, -1.247389, -3.333333, 6.752593, 0.609378, 0.609374, -0.304687,
    ],
    [
        -1.118922, 2.237835, -1.690100, -0.428805, 0.214407, 2.237840, 0.666666, 0.666666,
        -0.428812, -7.690082, 0.666666, 6.309870, 7.571190, -16.428828, 8.214411,
    ],
    [
        0.214407, -0.428805, -1.690100, 2.237835, -1.118922, -0.428812, 0.666666, 0.666666,
        2.237840, 6.309870, 0.666666, -7.690082, -16.428828, 7.571190, 8.214411,
    ],
];

/// The change-of-basis matrix from `patch`'s points to a box-spline
/// triangle, into `m` (`gregory` holds the Gregory triangle it is fitted
/// to).
pub(super) fn convert_into<R: Real>(
    patch: &SourcePatch,
    m: &mut Matrix<R>,
    gregory: &mut Matrix<R>,
) {
    GregoryTriangle::<R>::new(patch).convert_into(gregory);
    let n = gregory.columns;
    m.reset(&[n; 12], n);
    for (out, fit) in m.rows.iter_mut().zip(&FIT) {
        out.columns.iter_mut().enumerate().for_each(|(i, c)| *c = i);
        for (&g, &k) in BEZIER_ROWS.iter().zip(fit) {
            let k = R::from_f32(k);
            let Some(row) = gregory.rows.get(g) else {
                continue;
            };
            // Columns past the source points land in the next row, which
            // is cleared before it is written, in OpenSubdiv: dropped.
            for (&i, &w) in row.columns.iter().zip(&row.weights) {
                if let Some(x) = out.weights.get_mut(i) {
                    *x += k * w;
                }
            }
        }
    }
}
