//! Tensor-product uniform B-spline surfaces: biquadratic and bicubic (or any
//! degree) control grids, open or periodic in each direction, refined by
//! splitting and evaluated analytically.
//!
//! A [`ControlGrid`] holds `nu × nv` control points, row-major: point `(i, j)`
//! (`i` along u, `j` along v) is `points[j * nu + i]`. Its surface is
//!
//! ```text
//! S(s, t) = Σ_i Σ_j P[i, j] N_d(s + d - i) N_d(t + d - j)
//! ```
//!
//! with the parametrisation of [`BSplineCurve`](crate::curve::BSplineCurve) in
//! each direction: `s ∈ [0, nu - d]` when u is open, `[0, nu)` (periodic) when
//! it is closed, and likewise `t`. One level of [`ControlGrid::refine`] applies
//! the curve rule ([`crate::curve::bspline`]) to every row
//! (along u), then to every column of the result (along v); the refined grid
//! describes the same surface at twice the parameters:
//! `S_refined(2s, 2t) = S(s, t)`.
//!
//! ```
//! use glam::DVec3;
//! use subdiv::patch::ControlGrid;
//!
//! let grid = ControlGrid::from_fn(4, 4, 3, false, false, |i, j| {
//!     DVec3::new(i as f64, j as f64, ((i * j) % 3) as f64)
//! })?;
//! let fine = grid.refine()?;
//! assert_eq!((fine.nu(), fine.nv()), (5, 5));           // 2n - d in each open direction
//! let (a, b) = (grid.eval(0.25, 0.75)?, fine.eval(0.5, 1.5)?);
//! assert!((a - b).length() < 1e-12);
//! # Ok::<(), subdiv::patch::PatchError>(())
//! ```

use crate::curve::{self, CurveError, CurveScheme, MAX_DEGREE, MAX_POINTS, Point, bspline_basis};
use crate::mesh::Mesh;
use glam::DVec3;
use std::fmt;
use thiserror::Error;

/// A parameter direction of a grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// Along rows: the index `i`, the parameter `s`.
    U,
    /// Along columns: the index `j`, the parameter `t`.
    V,
}

impl fmt::Display for Direction {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Direction::U => "u",
            Direction::V => "v",
        })
    }
}

/// Why a control grid was refused.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum PatchError {
    /// The number of points is not `nu × nv`.
    #[error("a {nu} × {nv} grid needs {} points, got {got}", nu.saturating_mul(*nv))]
    WrongPointCount {
        /// Points along u.
        nu: usize,
        /// Points along v.
        nv: usize,
        /// The number of points given.
        got: usize,
    },
    /// A degree outside `1..=MAX_DEGREE`.
    #[error("B-spline degree {0} is not supported (expected 1 to {MAX_DEGREE})")]
    BadDegree(usize),
    /// A direction's rows or columns are refused by the curve rule (too few points...).
    #[error("along {direction}: {source}")]
    Curve {
        /// The direction.
        direction: Direction,
        /// The curve error.
        #[source]
        source: CurveError,
    },
    /// A control point with a NaN or infinite coordinate.
    #[error("control point ({i}, {j}) has a non-finite coordinate")]
    NonFinitePoint {
        /// Index along u.
        i: usize,
        /// Index along v.
        j: usize,
    },
    /// The refined grid would have more than [`MAX_POINTS`] points.
    #[error("the refined grid would have more than {MAX_POINTS} points")]
    TooManyPoints,
}

/// A uniform B-spline control grid of one degree in both directions, open or
/// periodic in each (see the [module documentation](self)).
#[derive(Debug, Clone, PartialEq)]
pub struct ControlGrid<P: Point = DVec3> {
    points: Vec<P>,
    nu: usize,
    nv: usize,
    degree: usize,
    closed_u: bool,
    closed_v: bool,
}

impl<P: Point> ControlGrid<P> {
    /// A grid of `nu × nv` points (row-major, `points[j * nu + i]`) of degree
    /// `degree`, closed (periodic) or open along u and v. Each open direction
    /// needs `degree + 1` points, each closed one 3.
    pub fn new(
        points: Vec<P>,
        nu: usize,
        nv: usize,
        degree: usize,
        closed_u: bool,
        closed_v: bool,
    ) -> Result<Self, PatchError> {
        if !(1..=MAX_DEGREE).contains(&degree) {
            return Err(PatchError::BadDegree(degree));
        }
        if nu.checked_mul(nv) != Some(points.len()) {
            return Err(PatchError::WrongPointCount {
                nu,
                nv,
                got: points.len(),
            });
        }
        let scheme = CurveScheme::BSpline { degree };
        for (direction, n, closed) in [(Direction::U, nu, closed_u), (Direction::V, nv, closed_v)] {
            let needed = scheme.min_points(closed);
            if n < needed {
                return Err(PatchError::Curve {
                    direction,
                    source: CurveError::TooFewPoints {
                        scheme: scheme.name(),
                        closed,
                        needed,
                        got: n,
                    },
                });
            }
        }
        if let Some(k) = points.iter().position(|p| !p.is_finite()) {
            return Err(PatchError::NonFinitePoint {
                i: k % nu,
                j: k / nu,
            });
        }
        Ok(ControlGrid {
            points,
            nu,
            nv,
            degree,
            closed_u,
            closed_v,
        })
    }

    /// A biquadratic grid ([`new`](Self::new) with degree 2).
    pub fn biquadratic(
        points: Vec<P>,
        nu: usize,
        nv: usize,
        closed_u: bool,
        closed_v: bool,
    ) -> Result<Self, PatchError> {
        Self::new(points, nu, nv, 2, closed_u, closed_v)
    }

    /// A bicubic grid ([`new`](Self::new) with degree 3).
    pub fn bicubic(
        points: Vec<P>,
        nu: usize,
        nv: usize,
        closed_u: bool,
        closed_v: bool,
    ) -> Result<Self, PatchError> {
        Self::new(points, nu, nv, 3, closed_u, closed_v)
    }

    /// A grid whose point `(i, j)` is `f(i, j)`.
    pub fn from_fn(
        nu: usize,
        nv: usize,
        degree: usize,
        closed_u: bool,
        closed_v: bool,
        f: impl Fn(usize, usize) -> P,
    ) -> Result<Self, PatchError> {
        let count = nu.checked_mul(nv).filter(|&c| c <= MAX_POINTS);
        let Some(count) = count else {
            return Err(PatchError::TooManyPoints);
        };
        let mut points = Vec::with_capacity(count);
        for j in 0..nv {
            for i in 0..nu {
                points.push(f(i, j));
            }
        }
        Self::new(points, nu, nv, degree, closed_u, closed_v)
    }

    /// Points along u.
    pub fn nu(&self) -> usize {
        self.nu
    }

    /// Points along v.
    pub fn nv(&self) -> usize {
        self.nv
    }

    /// The degree in both directions.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// Whether the grid is periodic along u.
    pub fn closed_u(&self) -> bool {
        self.closed_u
    }

    /// Whether the grid is periodic along v.
    pub fn closed_v(&self) -> bool {
        self.closed_v
    }

    /// All points, row-major.
    pub fn points(&self) -> &[P] {
        &self.points
    }

    /// Point `(i, j)`.
    ///
    /// # Panics
    ///
    /// If `i >= nu` or `j >= nv`.
    pub fn point(&self, i: usize, j: usize) -> P {
        assert!(i < self.nu && j < self.nv, "({i}, {j}) is outside the grid");
        self.points[j * self.nu + i]
    }

    /// Row `j` of control points (the control polygon of a curve along u).
    ///
    /// # Panics
    ///
    /// If `j >= nv`.
    pub fn row(&self, j: usize) -> &[P] {
        &self.points[j * self.nu..(j + 1) * self.nu]
    }

    /// The parameter domains `([s0, s1], [t0, t1])`.
    pub fn domain(&self) -> ([f64; 2], [f64; 2]) {
        let span = |n: usize, closed: bool| {
            if closed {
                n as f64
            } else {
                (n - self.degree) as f64
            }
        };
        (
            [0.0, span(self.nu, self.closed_u)],
            [0.0, span(self.nv, self.closed_v)],
        )
    }

    /// One level of splitting: the curve rule along u (every row), then along v
    /// (every column). The result has `2nu - d` (open) or `2nu` (closed) points
    /// along u, likewise along v, and `refined.eval(2s, 2t) = self.eval(s, t)`.
    pub fn refine(&self) -> Result<Self, PatchError> {
        let scheme = CurveScheme::BSpline {
            degree: self.degree,
        };
        let nu2 = scheme.refined_len(self.nu, self.closed_u);
        let nv2 = scheme.refined_len(self.nv, self.closed_v);
        if nu2.checked_mul(nv2).is_none_or(|c| c > MAX_POINTS) {
            return Err(PatchError::TooManyPoints);
        }
        let d = self.degree;
        let mut rows = Vec::with_capacity(nu2 * self.nv);
        for j in 0..self.nv {
            rows.extend(curve::bspline_step(self.row(j), d, self.closed_u));
        }
        let mut points = vec![P::ZERO; nu2 * nv2];
        let mut column = Vec::with_capacity(self.nv);
        for i in 0..nu2 {
            column.clear();
            column.extend((0..self.nv).map(|j| rows[j * nu2 + i]));
            for (j, p) in curve::bspline_step(&column, d, self.closed_v)
                .into_iter()
                .enumerate()
            {
                points[j * nu2 + i] = p;
            }
        }
        Ok(ControlGrid {
            points,
            nu: nu2,
            nv: nv2,
            degree: d,
            closed_u: self.closed_u,
            closed_v: self.closed_v,
        })
    }

    /// `levels` levels of [`refine`](Self::refine).
    pub fn refine_levels(&self, levels: u32) -> Result<Self, PatchError> {
        let mut grid = self.clone();
        for _ in 0..levels {
            grid = grid.refine()?;
        }
        Ok(grid)
    }

    /// The Greville parameters `(s, t)` of point `(i, j)`: `(i - (d-1)/2, j - (d-1)/2)`,
    /// the parameters the point approaches under refinement.
    pub fn greville(&self, i: usize, j: usize) -> (f64, f64) {
        let shift = (self.degree as f64 - 1.0) / 2.0;
        (i as f64 - shift, j as f64 - shift)
    }

    /// The surface point at `(s, t)`. A periodic direction takes any finite
    /// parameter; an open one refuses a parameter outside its domain.
    pub fn eval(&self, s: f64, t: f64) -> Result<P, PatchError> {
        let (i0, su) =
            locate(s, self.nu, self.degree, self.closed_u).map_err(|source| PatchError::Curve {
                direction: Direction::U,
                source,
            })?;
        let (j0, tv) =
            locate(t, self.nv, self.degree, self.closed_v).map_err(|source| PatchError::Curve {
                direction: Direction::V,
                source,
            })?;
        let d = self.degree;
        let wu: Vec<f64> = (0..=d)
            .map(|a| bspline_basis(d, su + (d - a) as f64))
            .collect();
        let mut sum = P::ZERO;
        for b in 0..=d {
            let wv = bspline_basis(d, tv + (d - b) as f64);
            let j = (j0 + b) % self.nv;
            let mut row = P::ZERO;
            for (a, &w) in wu.iter().enumerate() {
                row = row + self.points[j * self.nu + (i0 + a) % self.nu] * w;
            }
            sum = sum + row * wv;
        }
        Ok(sum)
    }
}

impl ControlGrid<DVec3> {
    /// The control grid as a quad mesh: vertex `j * nu + i` is point `(i, j)`,
    /// face `(i, j)` is `[(i, j), (i+1, j), (i+1, j+1), (i, j+1)]` (counter-clockwise
    /// when u runs along x and v along y), wrapping in periodic directions;
    /// faces in row-major order.
    pub fn to_mesh(&self) -> Mesh {
        let fu = if self.closed_u { self.nu } else { self.nu - 1 };
        let fv = if self.closed_v { self.nv } else { self.nv - 1 };
        let mut mesh = Mesh {
            positions: self.points.clone(),
            ..Mesh::default()
        };
        let idx = |i: usize, j: usize| ((j % self.nv) * self.nu + i % self.nu) as u32;
        for j in 0..fv {
            for i in 0..fu {
                mesh.add_face(&[idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)]);
            }
        }
        mesh
    }
}

/// The first control index of the span containing `s` and the local parameter.
fn locate(s: f64, n: usize, d: usize, closed: bool) -> Result<(usize, f64), CurveError> {
    if closed {
        let max = n as f64;
        if !s.is_finite() {
            return Err(CurveError::ParameterOutOfRange { s, min: 0.0, max });
        }
        let u = s.rem_euclid(max);
        let i = (u.floor() as usize).min(n - 1);
        Ok((i, u - i as f64))
    } else {
        let max = (n - d) as f64;
        if !(s >= 0.0 && s <= max) {
            return Err(CurveError::ParameterOutOfRange { s, min: 0.0, max });
        }
        let i = (s.floor() as usize).min(n - d - 1);
        Ok((i, s - i as f64))
    }
}
