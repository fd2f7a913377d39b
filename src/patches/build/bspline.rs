//! The 16 points of a B-spline end cap (`BSplineConverter` in
//! `far/catmarkPatchBuilder.cpp`): around one isolated irregular interior
//! corner, the patch keeps nine source points and fits seven new ones to
//! the corner's limit point and edge points; elsewhere the Gregory patch's
//! points are turned into B-spline ones (a dense matrix over the source
//! points).

use super::gregory::Gregory;
use super::limits;
use super::matrix::Matrix;
use super::source::SourcePatch;
use crate::real::Real;

/// The change-of-basis matrix from `patch`'s points to a B-spline patch,
/// into `m` (`gregory` holds the Gregory points it is made from).
pub(super) fn convert_into<R: Real>(
    patch: &SourcePatch,
    m: &mut Matrix<R>,
    gregory: &mut Matrix<R>,
) {
    let converter = Gregory::<R>::new(patch);
    match converter.isolated_corner() {
        Some(corner) => irregular_corner(patch, corner, m),
        None => {
            converter.convert_into(gregory);
            from_gregory(gregory, m);
        }
    }
}

/// From Gregory (Bézier) points to B-spline ones: each B-spline point a
/// fixed combination of a corner's, an edge's or the interior's Gregory
/// points (`convertFromGregory`).
fn from_gregory<R: Real>(g: &Matrix<R>, b: &mut Matrix<R>) {
    const CORNER: [f32; 9] = [49.0, -42.0, -42.0, 36.0, -14.0, -14.0, 12.0, 12.0, 4.0];
    const EDGE: [f32; 6] = [-14.0, 12.0, 7.0, -6.0, 4.0, -2.0];
    const INTERIOR: [f32; 4] = [4.0, -2.0, -2.0, 1.0];
    const P: [[usize; 9]; 4] = [
        [3, 1, 2, 0, 8, 18, 7, 16, 13],
        [8, 6, 7, 5, 3, 13, 12, 1, 18],
        [13, 11, 12, 10, 18, 8, 17, 6, 3],
        [18, 16, 17, 15, 13, 3, 2, 11, 8],
    ];
    const EP: [[usize; 6]; 4] = [
        [3, 1, 8, 7, 18, 13],
        [8, 6, 13, 12, 3, 18],
        [13, 11, 18, 17, 8, 3],
        [18, 16, 3, 2, 13, 8],
    ];
    const EM: [[usize; 6]; 4] = [
        [3, 2, 18, 16, 8, 13],
        [8, 7, 3, 1, 13, 18],
        [13, 12, 8, 6, 18, 3],
        [18, 17, 13, 11, 3, 8],
    ];
    const F: [[usize; 4]; 4] = [
        [3, 8, 18, 13],
        [8, 13, 3, 18],
        [13, 18, 8, 3],
        [18, 3, 13, 8],
    ];
    let rows: [(&[usize], &[f32]); 16] = [
        (&P[0], &CORNER),
        (&EP[0], &EDGE),
        (&EM[1], &EDGE),
        (&P[1], &CORNER),
        (&EM[0], &EDGE),
        (&F[0], &INTERIOR),
        (&F[1], &INTERIOR),
        (&EP[1], &EDGE),
        (&EP[3], &EDGE),
        (&F[3], &INTERIOR),
        (&F[2], &INTERIOR),
        (&EM[2], &EDGE),
        (&P[3], &CORNER),
        (&EM[3], &EDGE),
        (&EP[2], &EDGE),
        (&P[2], &CORNER),
    ];
    let n = g.columns;
    b.reset(&[n; 16], n);
    for (out, (sources, coefficients)) in b.rows.iter_mut().zip(rows) {
        out.columns.iter_mut().enumerate().for_each(|(i, c)| *c = i);
        for (&s, &c) in sources.iter().zip(coefficients) {
            let c = R::from_f32(c);
            let Some(row) = g.rows.get(s) else { continue };
            for (&i, &w) in row.columns.iter().zip(&row.weights) {
                if let Some(x) = out.weights.get_mut(i) {
                    *x += c * w;
                }
            }
        }
    }
}

/// The B-spline patch around an isolated irregular interior corner
/// (`convertIrregularCorner`): seven points `X` computed from the corner's
/// ring and its limit point and edge points, the other nine the source
/// points themselves.
fn irregular_corner<R: Real>(patch: &SourcePatch, corner: usize, m: &mut Matrix<R>) {
    const X_ROWS: [[usize; 7]; 4] = [
        [0, 1, 4, 2, 8, 3, 12],
        [3, 7, 2, 11, 1, 15, 0],
        [15, 14, 11, 13, 7, 12, 3],
        [12, 8, 13, 4, 14, 0, 15],
    ];
    const EXTERIOR_ROWS: [[usize; 5]; 4] = [
        [7, 11, 15, 14, 13],
        [14, 13, 12, 8, 4],
        [8, 4, 0, 1, 2],
        [1, 2, 3, 7, 11],
    ];
    let c = &patch.corners[corner];
    let valence = c.faces.max(1);
    let face = c.patch_face % valence;
    let width = 1 + 2 * valence;
    let [wp, wep, wem] = limits::interior::<R>(valence, face, true);
    let x_rows = X_ROWS[corner];
    let mut sizes = [1usize; 16];
    for (k, &r) in x_rows.iter().enumerate() {
        sizes[r] = if k >= 5 { width + 1 } else { width };
    }
    m.reset(&sizes, patch.points);
    for row in &mut m.rows {
        if row.len() == 1 {
            row.weights[0] = R::ONE;
        }
    }
    let (plus1, plus2, minus1) = (
        (face + 1) % valence,
        (face + 2) % valence,
        (face + valence - 1) % valence,
    );
    let p0 = 0;
    let p1 = 1 + 2 * face;
    let p2 = p1 + 1;
    let p3 = 1 + 2 * plus1;
    let p15 = p3 + 1;
    let p4 = 1 + 2 * plus2;
    let p6 = 1 + 2 * minus1;
    let p7 = p6 + 1;
    let (p8, p14) = (width, width);
    let f = |x: f32| R::from_f32(x);
    let mut x: [Vec<R>; 7] =
        std::array::from_fn(|k| vec![R::ZERO; if k >= 5 { width + 1 } else { width }]);
    for (k, v) in [
        (p0, 16.0),
        (p1, 8.0),
        (p2, 2.0),
        (p3, 4.0),
        (p6, 1.0),
        (p7, 2.0),
    ] {
        x[1][k] = f(v);
    }
    for (k, v) in [
        (p0, 16.0),
        (p3, 8.0),
        (p2, 2.0),
        (p1, 4.0),
        (p4, 1.0),
        (p15, 2.0),
    ] {
        x[2][k] = f(v);
    }
    for (k, v) in [
        (p0, 8.0),
        (p1, 4.0),
        (p2, 1.0),
        (p3, 2.0),
        (p6, 2.0),
        (p7, 4.0),
    ] {
        x[3][k] = f(v);
    }
    for (k, v) in [
        (p0, 8.0),
        (p3, 4.0),
        (p2, 1.0),
        (p1, 2.0),
        (p4, 2.0),
        (p15, 4.0),
    ] {
        x[4][k] = f(v);
    }
    x[5][p6] = f(-1.0);
    x[5][p8] = f(1.0);
    x[6][p4] = f(-1.0);
    x[6][p14] = f(1.0);
    for (k, v) in [(p0, 16.0), (p1, 4.0), (p2, 1.0), (p3, 4.0)] {
        x[0][k] = f(v);
    }
    let third = R::from_f64(1.0 / 3.0);
    let at = |w: &[R], i: usize| w.get(i).copied().unwrap_or(R::ZERO);
    #[allow(clippy::needless_range_loop)] // the seven rows at once, as OpenSubdiv
    for i in 0..width {
        let (ep, em, p) = (at(&wep, i), at(&wem, i), at(&wp, i));
        x[1][i] = (f(36.0) * ep - x[1][i]) * third;
        x[2][i] = (f(36.0) * em - x[2][i]) * third;
        x[3][i] = -ep * f(6.0) + x[3][i] * third;
        x[4][i] = -em * f(6.0) + x[4][i] * third;
        x[5][i] = x[5][i] + x[1][i];
        x[6][i] = x[6][i] + x[2][i];
        x[0][i] = p * f(36.0) - x[0][i] - (x[2][i] + x[1][i]) * f(4.0) - (x[3][i] + x[4][i]);
    }
    // The columns: the corner, its ring, and for X5 and X6 one point
    // beyond it; the other rows are single source points.
    let mut ring = vec![corner];
    ring.extend(patch.ring(corner));
    let points = patch.points;
    let mut beyond = [0usize; 16];
    let first = ring.get(p7).copied().unwrap_or(0) + 1;
    for (next, b) in (first..).zip(beyond.iter_mut().skip(8)) {
        *b = if next < points {
            next
        } else {
            next + 4 - points
        };
    }
    for (k, (&r, weights)) in x_rows.iter().zip(&x).enumerate() {
        let row = &mut m.rows[r];
        for (i, &w) in weights.iter().enumerate() {
            let column = if i < width {
                ring.get(i).copied().unwrap_or(0)
            } else if k == 5 {
                beyond[8]
            } else {
                beyond[14]
            };
            row.set(i, column, w);
        }
    }
    for (r, column) in [(5, 0), (6, 1), (9, 3), (10, 2)] {
        m.rows[r].columns[0] = column;
    }
    for (r, b) in EXTERIOR_ROWS[corner].iter().zip(9..14) {
        m.rows[*r].columns[0] = beyond[b];
    }
}
