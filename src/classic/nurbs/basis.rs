//! B-spline basis functions by the Cox–de Boor recursion, and their derivatives.
//!
//! `N_{i,0}(t) = 1` on the span `[u_i, u_{i+1})` (the last non-empty span of
//! the domain is closed on the right) and 0 elsewhere;
//!
//! ```text
//! N_{i,p}(t) = (t - u_i) / (u_{i+p} - u_i) · N_{i,p-1}(t)
//!            + (u_{i+p+1} - t) / (u_{i+p+1} - u_{i+1}) · N_{i+1,p-1}(t)
//! ```
//!
//! with `0/0 = 0`; and the derivatives
//!
//! ```text
//! N'_{i,p}(t) = p · ( N_{i,p-1}(t) / (u_{i+p} - u_i) - N_{i+1,p-1}(t) / (u_{i+p+1} - u_{i+1}) ).
//! ```
//!
//! On the span `k` only `N_{k-d,d} … N_{k,d}` are non-zero, and every
//! denominator the triangular scheme meets there is positive (it spans
//! `[u_k, u_{k+1}]`), so no special case is needed.

use super::{KnotVector, NurbsError};

impl KnotVector {
    /// The `d + 1` basis functions that can be non-zero at `t`:
    /// `(k, [N_{k-d,d}(t), …, N_{k,d}(t)])` with `k` the [span](Self::span)
    /// of `t`. They are non-negative and sum to 1 (to rounding).
    ///
    /// ```
    /// use subdiv::nurbs::KnotVector;
    /// // The quadratic Bernstein polynomials: (1 - t)², 2t(1 - t), t².
    /// let k = KnotVector::new(vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], 2)?;
    /// assert_eq!(k.basis(0.5)?, (2, vec![0.25, 0.5, 0.25]));
    /// # Ok::<(), subdiv::nurbs::NurbsError>(())
    /// ```
    pub fn basis(&self, t: f64) -> Result<(usize, Vec<f64>), NurbsError> {
        let t = self.reduce(t)?;
        let k = self.span_of(t);
        let mut all = self.basis_table(k, t);
        Ok((k, all.pop().unwrap_or_default()))
    }

    /// The derivatives of orders `0..=order` of the `d + 1` basis functions
    /// non-zero at `t`: `(k, ders)` with `ders[q][j] = N^{(q)}_{k-d+j,d}(t)`.
    /// Orders above `d` are zero.
    ///
    /// ```
    /// use subdiv::nurbs::KnotVector;
    /// // Bernstein: d/dt (1 - t)² = -2(1 - t), d/dt 2t(1 - t) = 2 - 4t, d/dt t² = 2t.
    /// let k = KnotVector::new(vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], 2)?;
    /// let (_, d) = k.basis_derivatives(0.25, 2)?;
    /// assert_eq!(d[1], [-1.5, 1.0, 0.5]);
    /// assert_eq!(d[2], [2.0, -4.0, 2.0]);
    /// # Ok::<(), subdiv::nurbs::NurbsError>(())
    /// ```
    pub fn basis_derivatives(
        &self,
        t: f64,
        order: usize,
    ) -> Result<(usize, Vec<Vec<f64>>), NurbsError> {
        let t = self.reduce(t)?;
        let k = self.span_of(t);
        Ok((k, self.derivatives_at(k, t, order)))
    }

    /// One basis function `N_{i,d}(t)`, straight from the Cox–de Boor
    /// recursion (with `0/0 = 0`) over the knots `u_i..=u_{i+d+1}`: zero
    /// outside its support. The same values as [`basis`](Self::basis),
    /// computed independently of it.
    ///
    /// ```
    /// use subdiv::nurbs::KnotVector;
    /// let k = KnotVector::uniform(4, 1)?;          // knots -1, 0, 1, 2, 3, 4
    /// assert_eq!(k.basis_function(0, 0.25)?, 0.75); // the hat on [-1, 1]
    /// assert_eq!(k.basis_function(1, 0.25)?, 0.25); // the hat on [0, 2]
    /// assert_eq!(k.basis_function(3, 0.25)?, 0.0);
    /// # Ok::<(), subdiv::nurbs::NurbsError>(())
    /// ```
    pub fn basis_function(&self, i: usize, t: f64) -> Result<f64, NurbsError> {
        let count = self.control_count();
        if i >= count {
            return Err(NurbsError::NoSuchBasisFunction { index: i, count });
        }
        let t = self.reduce(t)?;
        let k = self.span_of(t);
        let (d, u) = (self.degree(), self.as_slice());
        // Degree 0 on the spans i..=i+d: only the span of t is 1.
        let mut n: Vec<f64> = (i..=i + d)
            .map(|j| if j == k { 1.0 } else { 0.0 })
            .collect();
        for p in 1..=d {
            for j in 0..=d - p {
                let a = i + j;
                let left = if u[a + p] > u[a] {
                    (t - u[a]) / (u[a + p] - u[a]) * n[j]
                } else {
                    0.0
                };
                let right = if u[a + p + 1] > u[a + 1] {
                    (u[a + p + 1] - t) / (u[a + p + 1] - u[a + 1]) * n[j + 1]
                } else {
                    0.0
                };
                n[j] = left + right;
            }
        }
        Ok(n[0])
    }

    /// The non-zero basis functions of every degree `0..=d` on the span `k`:
    /// `table[p][j] = N_{k-p+j,p}(t)`.
    pub(crate) fn basis_table(&self, k: usize, t: f64) -> Vec<Vec<f64>> {
        let (d, u) = (self.degree(), self.as_slice());
        let mut table = Vec::with_capacity(d + 1);
        table.push(vec![1.0]);
        for p in 1..=d {
            let prev = &table[p - 1];
            let mut cur = vec![0.0; p + 1];
            for (j, c) in cur.iter_mut().enumerate() {
                let i = k + j - p;
                // N_{i,p-1} is prev[j - 1], N_{i+1,p-1} is prev[j].
                if j >= 1 {
                    *c += (t - u[i]) / (u[i + p] - u[i]) * prev[j - 1];
                }
                if j < p {
                    *c += (u[i + p + 1] - t) / (u[i + p + 1] - u[i + 1]) * prev[j];
                }
            }
            table.push(cur);
        }
        table
    }

    /// `ders[q][j] = N^{(q)}_{k-d+j,d}(t)` for `q = 0..=order` on the span `k`.
    pub(crate) fn derivatives_at(&self, k: usize, t: f64, order: usize) -> Vec<Vec<f64>> {
        let (d, u) = (self.degree(), self.as_slice());
        let table = self.basis_table(k, t);
        let mut ders = Vec::with_capacity(order + 1);
        for q in 0..=order {
            if q > d {
                ders.push(vec![0.0; d + 1]);
                continue;
            }
            // The q-th derivative of degree d from the values of degree d - q,
            // raising the degree (and the order of derivative) one at a time.
            let mut a = table[d - q].clone();
            for p in d - q + 1..=d {
                let mut b = vec![0.0; p + 1];
                for (j, c) in b.iter_mut().enumerate() {
                    let i = k + j - p;
                    if j >= 1 {
                        *c += a[j - 1] / (u[i + p] - u[i]);
                    }
                    if j < p {
                        *c -= a[j] / (u[i + p + 1] - u[i + 1]);
                    }
                    *c *= p as f64;
                }
                a = b;
            }
            ders.push(a);
        }
        ders
    }
}
