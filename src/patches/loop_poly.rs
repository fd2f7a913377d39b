//! Regular Loop patches of positions evaluated from their polynomial.
//!
//! A regular Loop patch is Stam's quartic box spline over its twelve
//! points: each point's weight is a polynomial in `(s, t)` of the fifteen
//! monomials of degree at most four ([`BOX_SPLINE`]). Summing the points
//! under those weights is the same as summing the monomials under
//! coefficients made of the points, `C_j = Σ_i B_ij X_i / 12`: once the
//! coefficients are known, a location costs 15 products for its position
//! and 10 more for each first derivative, where the weights cost about 240
//! products and the sum 108. The coefficients depend on the patch only:
//! computed for every patch before a large batch of locations
//! ([`loop_polynomials`], the table this module builds), else kept
//! from one location to the next of the same patch (in face order,
//! [`super::locations`]). They are taken relative to the patch's first
//! corner (point 4):
//! every coefficient but the constant one is then made of differences of
//! nearby points, not of their absolute positions, which keeps the
//! derivatives of small deep patches accurate.
//!
//! The values are within rounding of the weighted sums (the tests compare
//! them with OpenSubdiv's `EvaluateBasis` sums); a location gets the same
//! bits whether it is evaluated alone or among others, as the coefficients
//! of a patch are always computed the same way.

use super::eval::{PatchData, patch_of, point3};
use super::triangle_basis::{BOX_SPLINE, fold_box_spline_phantoms};
use super::{PatchHandle, PatchTable, PatchType};
use crate::error::Result;
use crate::real::Real;
use rayon::prelude::*;

/// A point's value: `[x, y, z]`.
type P3 = [f64; 3];

/// Column `J` of [`BOX_SPLINE`] (monomial `J`'s coefficient in each
/// point's weight) as a constant, so that its sum is compiled with its
/// zeros left out.
struct Column<const J: usize>;

impl<const J: usize> Column<J> {
    const B: [f64; 12] = {
        let mut out = [0.0; 12];
        let mut i = 0;
        while i < 12 {
            out[i] = BOX_SPLINE[i][J] as f64;
            i += 1;
        }
        out
    };

    /// Twelve times coefficient `J`: `Σ_i B_iJ d_i`.
    #[inline(always)]
    fn sum(d: &[P3; 12]) -> P3 {
        let mut acc = [0.0; 3];
        for (i, di) in d.iter().enumerate() {
            let b = Self::B[i];
            if b != 0.0 {
                axpy(&mut acc, b, di);
            }
        }
        acc
    }
}

/// `acc += a * x`.
#[inline(always)]
fn axpy(acc: &mut P3, a: f64, x: &P3) {
    acc[0] += a * x[0];
    acc[1] += a * x[1];
    acc[2] += a * x[2];
}

/// The patch's first corner, whose value the coefficients are relative to.
const ORIGIN: usize = 4;

/// A regular Loop patch's limit surface as a polynomial: its value at
/// `(s, t)` is `origin + Σ_j m_j(s, t) c[j]`, `m_j` the monomials in the
/// order of [`BOX_SPLINE`]'s columns (1, s, t, s², st, t², s³, s²t, st²,
/// t³, s⁴, s³t, s²t², st³, t⁴). Aligned to a cache line: its 384 bytes
/// then span six lines, not seven (read at random, one location each).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(64))]
pub(crate) struct LoopPolynomial {
    origin: P3,
    c: [P3; 15],
}

impl LoopPolynomial {
    /// The zero polynomial (a placeholder to be overwritten).
    pub(crate) const ZERO: LoopPolynomial = LoopPolynomial {
        origin: [0.0; 3],
        c: [[0.0; 3]; 15],
    };

    /// The polynomial of the patch with `points` (its twelve points in the
    /// box spline's order) and `boundary` (its `PatchParam` boundary mask:
    /// the phantom points folded into the others as OpenSubdiv folds their
    /// weights).
    pub(crate) fn of(points: &[P3; 12], boundary: u32) -> Self {
        let origin = points[ORIGIN];
        let d: [P3; 12] = std::array::from_fn(|i| {
            let p = points[i];
            [p[0] - origin[0], p[1] - origin[1], p[2] - origin[2]]
        });
        let mut c = if boundary == 0 {
            [
                Column::<0>::sum(&d),
                Column::<1>::sum(&d),
                Column::<2>::sum(&d),
                Column::<3>::sum(&d),
                Column::<4>::sum(&d),
                Column::<5>::sum(&d),
                Column::<6>::sum(&d),
                Column::<7>::sum(&d),
                Column::<8>::sum(&d),
                Column::<9>::sum(&d),
                Column::<10>::sum(&d),
                Column::<11>::sum(&d),
                Column::<12>::sum(&d),
                Column::<13>::sum(&d),
                Column::<14>::sum(&d),
            ]
        } else {
            // Each monomial's column of weights folded as the weights are.
            let mut c = [[0.0f64; 3]; 15];
            for (j, cj) in c.iter_mut().enumerate() {
                let mut column: [f64; 12] = std::array::from_fn(|i| BOX_SPLINE[i][j] as f64);
                fold_box_spline_phantoms(boundary, &mut column);
                for (&w, di) in column.iter().zip(&d) {
                    axpy(cj, w, di);
                }
            }
            c
        };
        for cj in &mut c {
            for x in cj.iter_mut() {
                *x /= 12.0;
            }
        }
        LoopPolynomial { origin, c }
    }

    /// One value from each cache line the polynomial spans, summed: reading
    /// the polynomials of a batch of locations before evaluating any lets
    /// their cache misses overlap.
    #[inline(always)]
    pub(crate) fn touch(&self) -> f64 {
        let c = &self.c;
        self.origin[0] + c[1][2] + c[4][1] + c[7][0] + c[9][2] + c[12][1] + c[14][2]
    }

    /// The position at `(s, t)`, and with `first` its derivatives with
    /// respect to `s` and `t` times `d1` (else zeros). Always inlined: out
    /// of line (as the compiler chose once evaluation came in `f32` and
    /// `f64`), its 72 bytes of result came back through the stack, and the
    /// Loop torus's million locations took 107 ms instead of 89.
    #[inline(always)]
    pub(crate) fn evaluate(&self, s: f64, t: f64, first: bool, d1: f64) -> [P3; 3] {
        let c = &self.c;
        let (ss, st, tt) = (s * s, s * t, t * t);
        let (sss, sst, stt, ttt) = (ss * s, ss * t, s * tt, tt * t);
        let mut p = self.origin;
        for k in 0..3 {
            p[k] += c[0][k];
        }
        for (m, cj) in [
            s,
            t,
            ss,
            st,
            tt,
            sss,
            sst,
            stt,
            ttt,
            ss * ss,
            sss * t,
            ss * tt,
            s * ttt,
            tt * tt,
        ]
        .iter()
        .zip(&c[1..])
        {
            axpy(&mut p, *m, cj);
        }
        if !first {
            return [p, [0.0; 3], [0.0; 3]];
        }
        // The monomials' derivatives, their zeros left out.
        let mut du = c[1];
        for (m, j) in [
            (2.0 * s, 3),
            (t, 4),
            (3.0 * ss, 6),
            (2.0 * st, 7),
            (tt, 8),
            (4.0 * sss, 10),
            (3.0 * sst, 11),
            (2.0 * stt, 12),
            (ttt, 13),
        ] {
            axpy(&mut du, m, &c[j]);
        }
        let mut dv = c[2];
        for (m, j) in [
            (s, 4),
            (2.0 * t, 5),
            (ss, 7),
            (2.0 * st, 8),
            (3.0 * tt, 9),
            (sss, 11),
            (2.0 * sst, 12),
            (3.0 * stt, 13),
            (4.0 * ttt, 14),
        ] {
            axpy(&mut dv, m, &c[j]);
        }
        [p, du.map(|x| x * d1), dv.map(|x| x * d1)]
    }
}

/// The most bytes [`loop_polynomials`] may take.
const LOOP_POLYNOMIAL_BYTES: usize = 64 << 20;

/// The polynomial of every regular Loop patch of `table` for `data` over
/// `points` (width 3), by array (empty for the other arrays), when
/// evaluating `locations` locations reads each patch at least once on
/// average and they take at most [`LOOP_POLYNOMIAL_BYTES`]: each patch's
/// polynomial is then computed once, whatever order the locations come in.
/// None otherwise, or when memory for them cannot be had or a patch names a
/// point `points` lacks (its locations then compute their patch's
/// polynomial themselves, and report that error). The values are the same
/// either way.
pub(super) fn loop_polynomials<R: Real>(
    table: &PatchTable,
    data: PatchData,
    points: &[R],
    locations: usize,
) -> Vec<Vec<LoopPolynomial>> {
    let is_loop = |array: usize| {
        matches!(
            patch_of(table, data, PatchHandle { array, patch: 0 }),
            Ok((PatchType::Loop, ..))
        )
    };
    let patches: usize = (0..table.arrays.len())
        .filter(|&a| is_loop(a))
        .map(|a| table.arrays[a].len())
        .sum();
    if patches == 0
        || patches > locations
        || patches.saturating_mul(size_of::<LoopPolynomial>()) > LOOP_POLYNOMIAL_BYTES
    {
        return Vec::new();
    }
    let mut out = Vec::new();
    for a in 0..table.arrays.len() {
        if !is_loop(a) {
            out.push(Vec::new());
            continue;
        }
        let Ok(mut polys) = crate::alloc::try_vec(LoopPolynomial::ZERO, table.arrays[a].len())
        else {
            return Vec::new();
        };
        let made = polys
            .par_iter_mut()
            .enumerate()
            .try_for_each(|(patch, poly)| -> Option<()> {
                let (_, param, cvs) =
                    patch_of(table, data, PatchHandle { array: a, patch }).ok()?;
                let cvs = cvs.get(..12)?;
                *poly = LoopPolynomial::of(&loop_points(points, cvs).ok()?, param.boundary());
                Some(())
            });
        if made.is_none() {
            return Vec::new();
        }
        out.push(polys);
    }
    out
}

/// The values of a Loop patch's twelve control points `cvs` (at least
/// twelve) in `points` (width 3), in `f64`, or the error naming the buffer
/// too short for one.
pub(super) fn loop_points<R: Real>(points: &[R], cvs: &[u32]) -> Result<[[f64; 3]; 12]> {
    let mut at = [[0.0f64; 3]; 12];
    for (p, &cv) in at.iter_mut().zip(cvs) {
        *p = point3(points, cv)?;
    }
    Ok(at)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::patches::triangle_basis::box_spline;

    /// Twelve points of a wavy sheet far from the origin.
    fn points() -> [P3; 12] {
        std::array::from_fn(|i| {
            let x = i as f64 * 0.37 + 100.0;
            [
                x,
                (i * i) as f64 * 0.11 - 50.0,
                (i as f64 * 1.7).sin() + 7.0,
            ]
        })
    }

    /// The weighted sums of the box spline's weights.
    fn summed(points: &[P3; 12], boundary: u32, s: f64, t: f64, ds: usize, dt: usize) -> P3 {
        let mut w = [0.0; 12];
        box_spline(s, t, ds, dt, &mut w);
        fold_box_spline_phantoms(boundary, &mut w);
        let mut out = [0.0; 3];
        for (wi, p) in w.iter().zip(points) {
            for k in 0..3 {
                out[k] += wi * p[k];
            }
        }
        out
    }

    #[test]
    fn the_polynomial_is_the_weighted_sum_of_the_points() {
        let pts = points();
        for boundary in [0, 1, 2, 4, 3, 7, 8 | 1, 8 | 5, 16 | 2, 16 | 6] {
            let poly = LoopPolynomial::of(&pts, boundary);
            for (s, t) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.25, 0.5), (0.6, 0.1)] {
                let [p, du, dv] = poly.evaluate(s, t, true, 2.0);
                for (got, (ds, dt), scale) in
                    [(p, (0, 0), 1.0), (du, (1, 0), 2.0), (dv, (0, 1), 2.0)]
                {
                    let want = summed(&pts, boundary, s, t, ds, dt);
                    for k in 0..3 {
                        assert!(
                            (got[k] - scale * want[k]).abs() < 1e-12,
                            "boundary {boundary} at ({s}, {t}), derivative {ds}{dt}: {} against {}",
                            got[k],
                            scale * want[k]
                        );
                    }
                }
            }
            let [p, du, dv] = poly.evaluate(0.3, 0.3, false, 2.0);
            assert_eq!((du, dv), ([0.0; 3], [0.0; 3]));
            let want = summed(&pts, boundary, 0.3, 0.3, 0, 0);
            assert!((0..3).all(|k| (p[k] - want[k]).abs() < 1e-12));
        }
    }

    #[test]
    fn the_corners_of_a_flat_regular_patch_are_its_limit_points() {
        // A regular planar grid of triangles: the limit of a vertex of a
        // flat regular mesh is the vertex itself, and the derivatives are
        // the grid's edge vectors.
        let grid = |i: f64, j: f64| [i + 0.5 * j, j * 0.75f64.sqrt(), 0.0];
        let rows: [(f64, &[f64]); 4] = [
            (-1.0, &[0.0, 1.0, 2.0]),
            (0.0, &[-1.0, 0.0, 1.0, 2.0]),
            (1.0, &[-1.0, 0.0, 1.0]),
            (2.0, &[-1.0, 0.0]),
        ];
        let pts: Vec<P3> = rows
            .iter()
            .flat_map(|&(j, is)| is.iter().map(move |&i| grid(i, j)))
            .collect();
        let pts: [P3; 12] = pts.try_into().expect("twelve points");
        let poly = LoopPolynomial::of(&pts, 0);
        let [p, du, dv] = poly.evaluate(0.0, 0.0, true, 1.0);
        let close = |a: P3, b: P3| (0..3).all(|k| (a[k] - b[k]).abs() < 1e-14);
        assert!(close(p, grid(0.0, 0.0)), "{p:?}");
        assert!(close(du, [1.0, 0.0, 0.0]), "{du:?}");
        assert!(close(dv, grid(0.0, 1.0)), "{dv:?}");
        let [p, ..] = poly.evaluate(1.0 / 3.0, 1.0 / 3.0, false, 1.0);
        assert!(close(p, grid(1.0 / 3.0, 1.0 / 3.0)), "{p:?}");
    }
}
