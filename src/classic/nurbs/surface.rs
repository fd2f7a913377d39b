//! Tensor-product B-spline and NURBS surfaces over knot vectors in u and v.

use super::curve::quotient_rule;
use super::hom::{Hom, de_casteljau, homogeneous, split_hom, weighted};
use super::insert::{refine_line, split_cut};
use super::{KnotVector, NurbsError};
use crate::curve::{MAX_POINTS, Point};
use crate::patch::{ControlGrid, Direction};
use glam::DVec3;

/// A tensor-product surface
/// `S(u, v) = Σ_i Σ_j w_ij P_ij N_{i,d}(u) N_{j,e}(v) / Σ_i Σ_j w_ij N_{i,d}(u) N_{j,e}(v)`
/// on `[u_d, u_{m-d}] × [v_e, v_{q-e}]`, with a knot vector (and degree) in
/// each direction, optionally rational.
///
/// The control points are row-major like [`ControlGrid`]'s: point `(i, j)`
/// (`i` along u, `j` along v) is `points()[j * nu() + i]`. A direction with a
/// [periodic](KnotVector::periodic) knot vector is closed: its rows (or
/// columns) are stored wrapped, the last `d` repeating the first `d`.
#[derive(Debug, Clone, PartialEq)]
pub struct NurbsSurface<P: Point = DVec3> {
    points: Vec<P>,
    weights: Option<Vec<f64>>,
    hom: Vec<Hom<P>>,
    nu: usize,
    nv: usize,
    knots_u: KnotVector,
    knots_v: KnotVector,
}

/// A surface point with its partial derivatives up to the second order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceDerivatives<P> {
    /// `S(u, v)`.
    pub point: P,
    /// `∂S/∂u`.
    pub du: P,
    /// `∂S/∂v`.
    pub dv: P,
    /// `∂²S/∂u²`.
    pub duu: P,
    /// `∂²S/∂u∂v`.
    pub duv: P,
    /// `∂²S/∂v²`.
    pub dvv: P,
}

/// One polynomial (or rational) piece of a surface in tensor-product Bézier form.
#[derive(Debug, Clone, PartialEq)]
pub struct BezierPatch<P> {
    /// The `(d + 1) × (e + 1)` control points, row-major: `(i, j)` at `j * (d + 1) + i`.
    pub points: Vec<P>,
    /// Their weights, for a rational surface.
    pub weights: Option<Vec<f64>>,
    /// The parameter interval along u.
    pub u: (f64, f64),
    /// The parameter interval along v.
    pub v: (f64, f64),
    /// The degree along u, `d`.
    pub degree_u: usize,
    /// The degree along v, `e`.
    pub degree_v: usize,
}

impl<P: Point> BezierPatch<P> {
    /// The patch at the surface parameters `(u, v)` (de Casteljau's
    /// algorithm along u on every row, then along v; parameters outside the
    /// intervals extrapolate the polynomials).
    pub fn eval(&self, u: f64, v: f64) -> P {
        let s = (u - self.u.0) / (self.u.1 - self.u.0);
        let t = (v - self.v.0) / (self.v.1 - self.v.0);
        let h = weighted(&self.points, self.weights.as_deref());
        let column = h
            .chunks(self.degree_u + 1)
            .map(|row| de_casteljau(row.to_vec(), s))
            .collect();
        de_casteljau(column, t).point(self.weights.is_some())
    }
}

impl<P: Point> NurbsSurface<P> {
    /// The surface with `nu × nv` control points (row-major), the knot
    /// vectors `knots_u` and `knots_v` (`nu` and `nv` are the distinct counts
    /// of a periodic direction, wrapped here) and optional weights, one per point.
    pub fn new(
        points: Vec<P>,
        nu: usize,
        nv: usize,
        knots_u: KnotVector,
        knots_v: KnotVector,
        weights: Option<Vec<f64>>,
    ) -> Result<Self, NurbsError> {
        if nu.checked_mul(nv) != Some(points.len()) {
            return Err(NurbsError::WrongPointCount {
                nu,
                nv,
                got: points.len(),
            });
        }
        for (direction, n, knots) in [(Direction::U, nu, &knots_u), (Direction::V, nv, &knots_v)] {
            if knots.distinct_control_count() != n {
                let (d, count) = (knots.degree(), knots.distinct_control_count());
                let error = if knots.is_periodic() {
                    NurbsError::WrongKnotCount {
                        expected: n + 1,
                        got: count + 1,
                    }
                } else {
                    NurbsError::WrongKnotCount {
                        expected: n + d + 1,
                        got: knots.knot_count(),
                    }
                };
                return Err(error.along(direction));
            }
        }
        let hom = homogeneous(&points, weights.as_deref())?;
        let wrap_u = knots_u.is_periodic().then(|| knots_u.degree());
        let wrap_v = knots_v.is_periodic().then(|| knots_v.degree());
        let su = nu + wrap_u.unwrap_or(0);
        let sv = nv + wrap_v.unwrap_or(0);
        if su.saturating_mul(sv) > MAX_POINTS {
            return Err(NurbsError::TooManyPoints { max: MAX_POINTS });
        }
        // The points and weights as given; the homogeneous form for the algorithms.
        Ok(NurbsSurface {
            points: wrap_grid(points, nu, wrap_u, wrap_v),
            weights: weights.map(|w| wrap_grid(w, nu, wrap_u, wrap_v)),
            hom: wrap_grid(hom, nu, wrap_u, wrap_v),
            nu: su,
            nv: sv,
            knots_u,
            knots_v,
        })
    }

    /// The uniform grid of [`crate::patch`] as a surface over knot vectors,
    /// with the same parameters: an open direction gets the knots
    /// `u_k = k - d` ([`KnotVector::uniform`]), a periodic one the break
    /// points `0, 1, …, n` ([`KnotVector::periodic_uniform`], which needs
    /// `n ≥ max(d, 2)`), so that `surface.eval(s, t) = grid.eval(s, t)`.
    pub fn from_control_grid(grid: &ControlGrid<P>) -> Result<Self, NurbsError> {
        let d = grid.degree();
        let axis = |direction, n, closed| {
            if closed {
                KnotVector::periodic_uniform(n, d)
            } else {
                KnotVector::uniform(n, d)
            }
            .map_err(|e| e.along(direction))
        };
        let knots_u = axis(Direction::U, grid.nu(), grid.closed_u())?;
        let knots_v = axis(Direction::V, grid.nv(), grid.closed_v())?;
        Self::new(
            grid.points().to_vec(),
            grid.nu(),
            grid.nv(),
            knots_u,
            knots_v,
            None,
        )
    }

    fn from_hom(
        hom: Vec<Hom<P>>,
        nu: usize,
        nv: usize,
        knots_u: KnotVector,
        knots_v: KnotVector,
        rational: bool,
    ) -> Self {
        let (points, weights) = split_hom(&hom, rational);
        NurbsSurface {
            points,
            weights,
            hom,
            nu,
            nv,
            knots_u,
            knots_v,
        }
    }

    /// Stored control points along u (wrapped in a periodic direction).
    pub fn nu(&self) -> usize {
        self.nu
    }

    /// Stored control points along v (wrapped in a periodic direction).
    pub fn nv(&self) -> usize {
        self.nv
    }

    /// All control points, row-major.
    pub fn points(&self) -> &[P] {
        &self.points
    }

    /// Control point `(i, j)`, or `None` outside the grid.
    pub fn point(&self, i: usize, j: usize) -> Option<P> {
        (i < self.nu && j < self.nv).then(|| self.points[j * self.nu + i])
    }

    /// The weights of a rational surface, row-major.
    pub fn weights(&self) -> Option<&[f64]> {
        self.weights.as_deref()
    }

    /// Whether the surface has weights.
    pub fn is_rational(&self) -> bool {
        self.weights.is_some()
    }

    /// The knot vector along `direction`.
    pub fn knots(&self, direction: Direction) -> &KnotVector {
        match direction {
            Direction::U => &self.knots_u,
            Direction::V => &self.knots_v,
        }
    }

    /// The domain `((u_d, u_{m-d}), (v_e, v_{q-e}))`.
    pub fn domain(&self) -> ((f64, f64), (f64, f64)) {
        (self.knots_u.domain(), self.knots_v.domain())
    }

    /// The surface in its open representation in both directions.
    pub fn to_open(&self) -> Self {
        NurbsSurface {
            knots_u: self.knots_u.to_open(),
            knots_v: self.knots_v.to_open(),
            ..self.clone()
        }
    }

    /// Both parameters checked (or reduced, in a periodic direction) and their spans.
    fn locate(&self, u: f64, v: f64) -> Result<[(usize, f64); 2], NurbsError> {
        let mut out = [(0, 0.0); 2];
        for (slot, (direction, knots, t)) in out.iter_mut().zip([
            (Direction::U, &self.knots_u, u),
            (Direction::V, &self.knots_v, v),
        ]) {
            let t = knots.reduce(t).map_err(|e| e.along(direction))?;
            *slot = (knots.span_of(t), t);
        }
        Ok(out)
    }

    /// `Σ_a Σ_b bu[a] bv[b] (w P)_{ku-d+a, kv-e+b}`.
    fn combine(&self, ku: usize, kv: usize, bu: &[f64], bv: &[f64]) -> Hom<P> {
        let (d, e) = (self.knots_u.degree(), self.knots_v.degree());
        let mut sum = Hom::ZERO;
        for (b, &wv) in bv.iter().enumerate() {
            let row = &self.hom[(kv - e + b) * self.nu + ku - d..][..=d];
            let partial = row
                .iter()
                .zip(bu)
                .fold(Hom::ZERO, |acc, (&h, &wu)| acc + h * wu);
            sum = sum + partial * wv;
        }
        sum
    }

    /// The surface point at `(u, v)`. An open direction refuses a parameter
    /// outside its domain; a periodic one takes any finite value.
    pub fn eval(&self, u: f64, v: f64) -> Result<P, NurbsError> {
        let [(ku, u), (kv, v)] = self.locate(u, v)?;
        let bu = self.knots_u.basis_table(ku, u).pop().unwrap_or_default();
        let bv = self.knots_v.basis_table(kv, v).pop().unwrap_or_default();
        Ok(self.combine(ku, kv, &bu, &bv).point(self.is_rational()))
    }

    /// The point and its partial derivatives up to the second order: the
    /// homogeneous `A_kl = ∂^{k+l} (Σ w P N N) / ∂u^k ∂v^l` and `w_kl`, then
    /// for a rational surface the quotient rule (`S_u = (A_u - w_u S) / w`,
    /// `S_uu = (A_uu - 2 w_u S_u - w_uu S) / w`,
    /// `S_uv = (A_uv - w_u S_v - w_v S_u - w_uv S) / w`, likewise in v).
    pub fn derivatives(&self, u: f64, v: f64) -> Result<SurfaceDerivatives<P>, NurbsError> {
        let [(ku, u), (kv, v)] = self.locate(u, v)?;
        let du = self.knots_u.derivatives_at(ku, u, 2);
        let dv = self.knots_v.derivatives_at(kv, v, 2);
        let a = |k: usize, l: usize| self.combine(ku, kv, &du[k], &dv[l]);
        let (a00, a10, a01) = (a(0, 0), a(1, 0), a(0, 1));
        let (a20, a11, a02) = (a(2, 0), a(1, 1), a(0, 2));
        let along_u = quotient_rule(a00, a10, a20, self.is_rational());
        let along_v = quotient_rule(a00, a01, a02, self.is_rational());
        let duv = if self.is_rational() {
            let s = along_u.point;
            (a11.p - along_v.first * a10.w - along_u.first * a01.w - s * a11.w) * (1.0 / a00.w)
        } else {
            a11.p
        };
        Ok(SurfaceDerivatives {
            point: along_u.point,
            du: along_u.first,
            dv: along_v.first,
            duu: along_u.second,
            duv,
            dvv: along_v.second,
        })
    }

    /// Every row (`U`: the lines along u) or column (`V`) through `f`; the
    /// new counts `(nu, nv)`.
    fn map_lines(
        &self,
        direction: Direction,
        f: impl Fn(&[Hom<P>]) -> Vec<Hom<P>>,
    ) -> (Vec<Hom<P>>, usize, usize) {
        match direction {
            Direction::U => {
                let rows: Vec<Vec<Hom<P>>> = self.hom.chunks(self.nu).map(&f).collect();
                let nu = rows.first().map_or(0, Vec::len);
                (rows.concat(), nu, self.nv)
            }
            Direction::V => {
                let columns: Vec<Vec<Hom<P>>> = (0..self.nu)
                    .map(|i| {
                        let column: Vec<Hom<P>> =
                            (0..self.nv).map(|j| self.hom[j * self.nu + i]).collect();
                        f(&column)
                    })
                    .collect();
                let nv = columns.first().map_or(0, Vec::len);
                let hom = (0..nv)
                    .flat_map(|j| columns.iter().map(move |c| c[j]))
                    .collect();
                (hom, self.nu, nv)
            }
        }
    }

    /// This surface with new control points and a new knot vector along `direction`.
    fn rebuilt(
        &self,
        direction: Direction,
        knots: KnotVector,
        (hom, nu, nv): (Vec<Hom<P>>, usize, usize),
    ) -> Self {
        let (knots_u, knots_v) = match direction {
            Direction::U => (knots, self.knots_v.clone()),
            Direction::V => (self.knots_u.clone(), knots),
        };
        Self::from_hom(hom, nu, nv, knots_u, knots_v, self.is_rational())
    }

    /// The knot count along the other direction times `extra` more lines
    /// along `direction` must stay within [`MAX_POINTS`].
    fn check_growth(&self, direction: Direction, extra: usize) -> Result<(), NurbsError> {
        let (along, across) = match direction {
            Direction::U => (self.nu, self.nv),
            Direction::V => (self.nv, self.nu),
        };
        match along.checked_add(extra).and_then(|a| a.checked_mul(across)) {
            Some(c) if c <= MAX_POINTS => Ok(()),
            _ => Err(NurbsError::TooManyPoints { max: MAX_POINTS }),
        }
    }

    /// The same surface with the knot `t` inserted once along `direction`
    /// (Boehm's algorithm on every row or column; periodic directions keep
    /// their periodic form).
    pub fn insert(&self, direction: Direction, t: f64) -> Result<Self, NurbsError> {
        self.check_growth(direction, 1)?;
        let ins = self
            .knots(direction)
            .insertion(t)
            .map_err(|e| e.along(direction))?;
        let lines = self.map_lines(direction, |line| ins.apply(line));
        Ok(self.rebuilt(direction, ins.knots().clone(), lines))
    }

    /// The knots `ts` inserted along `direction` all at once (A5.4 on every
    /// row or column; one at a time, in increasing order, in a periodic direction).
    pub fn refine_knots(&self, direction: Direction, ts: &[f64]) -> Result<Self, NurbsError> {
        let knots = self.knots(direction);
        self.check_growth(direction, ts.len())?;
        if knots.is_periodic() {
            let mut sorted = ts.to_vec();
            sorted.sort_by(f64::total_cmp);
            return sorted
                .iter()
                .try_fold(self.clone(), |s, &t| s.insert(direction, t));
        }
        let xs = knots.check_refinement(ts).map_err(|e| e.along(direction))?;
        if xs.is_empty() {
            return Ok(self.clone());
        }
        let lines = self.map_lines(direction, |line| refine_line(knots, &xs, line));
        Ok(self.rebuilt(direction, knots.merged(&xs), lines))
    }

    /// The surface split at `t` along `direction` into the pieces below and
    /// above `t`, by inserting `t` up to multiplicity `d` in that direction
    /// (the pieces are open in it). `t` must lie strictly inside the domain.
    pub fn split(&self, direction: Direction, t: f64) -> Result<(Self, Self), NurbsError> {
        let knots = self.knots(direction);
        let (start, end) = knots.domain();
        let reduced = knots.reduce(t).unwrap_or(f64::NAN);
        if !(reduced > start && reduced < end) {
            return Err(NurbsError::SplitNotInterior { t, start, end }.along(direction));
        }
        let mut open = self.clone();
        match direction {
            Direction::U => open.knots_u = open.knots_u.to_open(),
            Direction::V => open.knots_v = open.knots_v.to_open(),
        }
        let have = open.knots(direction).multiplicity(reduced);
        let need = knots.degree().saturating_sub(have);
        let full = open.refine_knots(direction, &vec![reduced; need])?;
        let (left, count, right, first) = split_cut(full.knots(direction), reduced);
        let low = full.map_lines(direction, |line| line[..count].to_vec());
        let high = full.map_lines(direction, |line| line[first..].to_vec());
        Ok((
            full.rebuilt(direction, left, low),
            full.rebuilt(direction, right, high),
        ))
    }

    /// The surface as Bézier patches, one per pair of non-empty spans of the
    /// two domains, row-major in the spans (u fastest), by inserting every
    /// knot of both domains up to full multiplicity (periodic directions:
    /// one period).
    pub fn to_bezier(&self) -> Result<Vec<BezierPatch<P>>, NurbsError> {
        let open = self.to_open();
        let xu = open.knots_u.bezier_knots();
        let xv = open.knots_v.bezier_knots();
        let full = open
            .refine_knots(Direction::U, &xu)?
            .refine_knots(Direction::V, &xv)?;
        let (d, e) = (full.knots_u.degree(), full.knots_v.degree());
        let mut patches = Vec::new();
        for (lv, v0, v1) in full.knots_v.bezier_pieces() {
            for &(lu, u0, u1) in &full.knots_u.bezier_pieces() {
                let index = |i: usize, j: usize| (lv - e + j) * full.nu + lu - d + i;
                let grid = |k: usize| (k % (d + 1), k / (d + 1));
                let count = (d + 1) * (e + 1);
                patches.push(BezierPatch {
                    points: (0..count)
                        .map(|k| {
                            let (i, j) = grid(k);
                            full.points[index(i, j)]
                        })
                        .collect(),
                    weights: full.weights.as_ref().map(|w| {
                        (0..count)
                            .map(|k| {
                                let (i, j) = grid(k);
                                w[index(i, j)]
                            })
                            .collect()
                    }),
                    u: (u0, u1),
                    v: (v0, v1),
                    degree_u: d,
                    degree_v: e,
                });
            }
        }
        Ok(patches)
    }
}

/// A row-major grid with `nu` points a row, its rows extended by their first
/// `wrap_u` points and then its first `wrap_v` rows appended (periodic directions).
fn wrap_grid<T: Copy>(
    grid: Vec<T>,
    nu: usize,
    wrap_u: Option<usize>,
    wrap_v: Option<usize>,
) -> Vec<T> {
    let mut grid = match wrap_u {
        Some(d) => grid
            .chunks(nu)
            .flat_map(|row| row.iter().chain(&row[..d]).copied())
            .collect(),
        None => grid,
    };
    if let Some(e) = wrap_v {
        let row = nu + wrap_u.unwrap_or(0);
        grid.extend_from_within(..e * row);
    }
    grid
}
