//! The coordinates of the three kinds of pattern, ring by ring.
//!
//! The boundary ring comes first — counter-clockwise from vertex 0, each
//! edge's points from its first vertex up to (not including) the next — then
//! each interior ring inward, each from its corner nearest vertex 0, then
//! the centre when there is one. Points along a row are accumulated (`u +=
//! du`), not multiplied out, and every constant is formed in the same
//! precision as OpenSubdiv forms it, so the coordinates are OpenSubdiv's bit
//! for bit in `f32` and `f64`.

use crate::bfr::parameterization::{half, small};
use crate::bfr::{Parameterization, parameterization};
use crate::real::Real;

/// Appends `n` points from (u, v) stepping by (du, dv).
fn line<R: Real>(out: &mut Vec<[R; 2]>, n: i32, mut u: R, mut v: R, du: R, dv: R) {
    for _ in 0..n {
        out.push([u, v]);
        u += du;
        v += dv;
    }
}

/// 1 / `rate` in `R`.
fn step<R: Real>(rate: i32) -> R {
    R::ONE / small::<R>(rate as usize)
}

/// A polygon's sides: each edge's first corner and its direction (the
/// next corner minus it).
type Sides = [([f64; 2], [f64; 2])];

/// The unit square's sides, counter-clockwise from (0, 0).
const SQUARE: [([f64; 2], [f64; 2]); 4] = [
    ([0.0, 0.0], [1.0, 0.0]),
    ([1.0, 0.0], [0.0, 1.0]),
    ([1.0, 1.0], [-1.0, 0.0]),
    ([0.0, 1.0], [0.0, -1.0]),
];

/// The unit triangle's sides, counter-clockwise from (0, 0).
const TRIANGLE: [([f64; 2], [f64; 2]); 3] = [
    ([0.0, 0.0], [1.0, 0.0]),
    ([1.0, 0.0], [-1.0, 1.0]),
    ([0.0, 1.0], [0.0, -1.0]),
];

/// The points inside edge `edge` of `sides` at rate `res` (its ends
/// excluded): from the corner plus one step. (A step of `dt` times -1, 0 or
/// 1 added to 0 or 1 is exactly OpenSubdiv's `dt`, `1 - dt` and so on.)
fn side_edge<R: Real>(sides: &Sides, edge: usize, res: i32, out: &mut Vec<[R; 2]>) {
    let ([u, v], [a, b]) = sides[edge];
    let dt = step::<R>(res);
    let (du, dv) = (dt * R::from_f64(a), dt * R::from_f64(b));
    line(
        out,
        res - 1,
        R::from_f64(u) + du,
        R::from_f64(v) + dv,
        du,
        dv,
    );
}

/// The boundary ring of `sides` at rates `rates`: each edge from its
/// corner, stepping by 1 / its rate.
fn side_boundary<R: Real>(sides: &Sides, rates: &[i32], out: &mut Vec<[R; 2]>) {
    for (&([u, v], [a, b]), &rate) in sides.iter().zip(rates) {
        let dt = step::<R>(rate);
        line(
            out,
            rate,
            R::from_f64(u),
            R::from_f64(v),
            dt * R::from_f64(a),
            dt * R::from_f64(b),
        );
    }
}

/// Coordinates of the unit square.
pub(super) mod quad {
    use super::*;

    /// The points inside edge `edge` at rate `res` (its ends excluded).
    pub(in super::super) fn edge<R: Real>(edge: usize, res: i32, out: &mut Vec<[R; 2]>) {
        side_edge(&SQUARE, edge, res, out);
    }

    /// The boundary ring at rates `rates`.
    pub(in super::super) fn boundary<R: Real>(rates: &[i32], out: &mut Vec<[R; 2]>) {
        side_boundary(&SQUARE, rates, out);
    }

    /// The interior rings of inner rates `uv_res`.
    pub(in super::super) fn interior<R: Real>(uv_res: [i32; 2], out: &mut Vec<[R; 2]>) {
        let rings = (uv_res[0] / 2).min(uv_res[1] / 2);
        let (du, dv) = (step::<R>(uv_res[0]), step::<R>(uv_res[1]));
        let (mut u, mut v) = (du, dv);
        let (mut u_res, mut v_res) = (uv_res[0] - 2, uv_res[1] - 2);
        let zero = R::ZERO;
        for _ in 0..rings {
            if u_res > 0 && v_res > 0 {
                let (u1, v1) = (R::ONE - u, R::ONE - v);
                line(out, u_res, u, v, du, zero);
                line(out, v_res, u1, v, zero, dv);
                line(out, u_res, u1, v1, -du, zero);
                line(out, v_res, u, v1, zero, -dv);
            } else if u_res > 0 {
                line(out, u_res + 1, u, v, du, zero);
            } else if v_res > 0 {
                line(out, v_res + 1, u, v, zero, dv);
            } else {
                out.push([half::<R>(), half::<R>()]);
            }
            u_res -= 2;
            v_res -= 2;
            u += du;
            v += dv;
        }
    }
}

/// Coordinates of the unit triangle.
pub(super) mod tri {
    use super::*;

    /// The points inside edge `edge` at rate `res` (its ends excluded).
    pub(in super::super) fn edge<R: Real>(edge: usize, res: i32, out: &mut Vec<[R; 2]>) {
        side_edge(&TRIANGLE, edge, res, out);
    }

    /// The boundary ring at rates `rates`.
    pub(in super::super) fn boundary<R: Real>(rates: &[i32], out: &mut Vec<[R; 2]>) {
        side_boundary(&TRIANGLE, rates, out);
    }

    /// The interior rings of inner rate `res`.
    pub(in super::super) fn interior<R: Real>(res: i32, out: &mut Vec<[R; 2]>) {
        let rings = res / 3;
        let dt = step::<R>(res);
        let (mut u, mut v) = (dt, dt);
        let mut ring_res = res - 3;
        let (zero, two) = (R::ZERO, R::from_f64(2.0));
        for _ in 0..rings {
            if ring_res == 0 {
                out.push(parameterization::center(
                    crate::bfr::ParameterizationType::Triangle,
                ));
            } else {
                let (u1, v1) = (R::ONE - u * two, R::ONE - v * two);
                line(out, ring_res, u, v, dt, zero);
                line(out, ring_res, u1, v, -dt, dt);
                line(out, ring_res, u, v1, zero, -dt);
            }
            ring_res -= 3;
            u += dt;
            v += dt;
        }
    }
}

/// Coordinates of quadrilateral sub-faces.
pub(super) mod qsub {
    use super::*;

    /// The points of one ring's edge `edge` at rate `res`, offset `origin`
    /// into the tiles: the first half along the lower side of the edge's
    /// tile, the second half (one more when the count is odd, so that it
    /// starts exactly on the next tile) down the left side of the next tile.
    #[allow(clippy::too_many_arguments)]
    fn ring_edge<R: Real>(
        p: &Parameterization,
        edge: usize,
        res: i32,
        first: bool,
        last: bool,
        origin: R,
        dt: R,
        out: &mut Vec<[R; 2]>,
    ) {
        let n0 = (res - 1) / 2;
        let n1 = (res - 1) - n0;
        let zero = R::ZERO;
        if first || n0 > 0 {
            let [u0, v0] = p.vertex_coord::<R>(edge);
            if first {
                out.push([u0 + origin, v0 + origin]);
            }
            if n0 > 0 {
                line(out, n0, u0 + origin + dt, v0 + origin, dt, zero);
            }
        }
        if n1 > 0 || last {
            let [u1, v1] = p.vertex_coord::<R>((edge + 1) % p.face_size());
            if n1 > 0 {
                let h = half::<R>();
                let start = if res & 1 != 0 { h - h * dt } else { h };
                line(out, n1, u1 + origin, v1 + start, zero, -dt);
            }
            if last {
                out.push([u1 + origin, v1 + origin]);
            }
        }
    }

    /// The points inside edge `edge` at rate `res` (its ends excluded).
    pub(in super::super) fn edge<R: Real>(
        p: &Parameterization,
        edge: usize,
        res: i32,
        out: &mut Vec<[R; 2]>,
    ) {
        ring_edge(p, edge, res, false, false, R::ZERO, step(res), out);
    }

    /// The boundary ring at rates `rates`.
    pub(in super::super) fn boundary<R: Real>(
        p: &Parameterization,
        rates: &[i32],
        out: &mut Vec<[R; 2]>,
    ) {
        for (e, &rate) in rates.iter().enumerate() {
            ring_edge(p, e, rate, true, false, R::ZERO, step(rate), out);
        }
    }

    /// The interior rings of inner rate `res`.
    pub(in super::super) fn interior<R: Real>(
        p: &Parameterization,
        res: i32,
        out: &mut Vec<[R; 2]>,
    ) {
        let rings = res / 2;
        let dt = step::<R>(res);
        let mut t = dt;
        let mut ring_res = res - 2;
        let n = p.face_size();
        for _ in 0..rings {
            if ring_res == 0 {
                out.push([half::<R>(), half::<R>()]);
            } else if ring_res == 1 {
                // One point per corner, and the centre unless a triangle.
                for corner in 0..n {
                    let [u, v] = p.vertex_coord::<R>(corner);
                    out.push([u + t, v + t]);
                }
                if n != 3 {
                    out.push([half::<R>(), half::<R>()]);
                }
            } else {
                for e in 0..n {
                    ring_edge(p, e, ring_res, true, false, t, dt, out);
                }
            }
            ring_res -= 2;
            t += dt;
        }
    }
}
