//! Stencil tables: each refined (or limit) value as a weighted sum of base values.

use crate::error::{Error, Result};

/// A stencil table in compressed-sparse-row form: row `i` is
/// `sum(weights[k] * base[indices[k]])` for `k` in `offsets[i]..offsets[i] + sizes[i]`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct StencilTable {
    /// Number of weights of each stencil.
    pub sizes: Vec<u32>,
    /// Start of each stencil in `indices` and `weights`.
    pub offsets: Vec<u32>,
    /// Base-vertex index of each weight.
    pub indices: Vec<u32>,
    /// The weights.
    pub weights: Vec<f64>,
}

impl StencilTable {
    /// Number of stencils (rows).
    pub fn len(&self) -> usize {
        self.sizes.len()
    }

    /// Whether the table has no stencil.
    pub fn is_empty(&self) -> bool {
        self.sizes.is_empty()
    }

    /// The indices and weights of stencil `i`.
    ///
    /// # Panics
    /// If `i >= len()`.
    pub fn row(&self, i: usize) -> (&[u32], &[f64]) {
        let a = self.offsets[i] as usize;
        let b = a + self.sizes[i] as usize;
        (&self.indices[a..b], &self.weights[a..b])
    }

    /// Applies the table to base data of `width` components per vertex, in
    /// parallel over the stencils (rayon's global pool).
    ///
    /// ```
    /// use subdiv::{refiner::Refiner, shapes, Options, UniformOptions};
    /// let cube = shapes::cube();
    /// let mut r = Refiner::new(&cube, &Options::default())?;
    /// r.refine_uniform(UniformOptions::new(2))?;
    /// let table = r.stencil_table()?;
    /// let frame: Vec<f64> = cube.positions.iter().flat_map(|p| (*p * 2.0).to_array()).collect();
    /// let refined = table.apply_par(3, &frame)?;
    /// assert_eq!(refined, table.apply(3, &frame)?);
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn apply_par(&self, width: usize, base: &[f64]) -> Result<Vec<f64>> {
        use rayon::prelude::*;
        self.check_apply(width, base)?;
        let mut out = vec![0.0; self.len() * width];
        out.par_chunks_mut(width * 256)
            .enumerate()
            .for_each(|(block, chunk)| {
                for (k, dst) in chunk.chunks_exact_mut(width).enumerate() {
                    self.apply_row(block * 256 + k, width, base, dst);
                }
            });
        Ok(out)
    }

    /// As [`StencilTable::apply_par`] for `f32` data (weights rounded to `f32`
    /// as they are applied), into a caller's buffer: the per-frame path.
    pub fn apply_par_f32_into(&self, width: usize, base: &[f32], out: &mut [f32]) -> Result<()> {
        use rayon::prelude::*;
        let count = base.len().checked_div(width).unwrap_or(0);
        if width == 0 || base.len() % width != 0 || out.len() != self.len() * width {
            return Err(Error::InvalidArgument(format!(
                "buffers of {} and {} values do not fit {} stencils of width {width}",
                base.len(),
                out.len(),
                self.len()
            )));
        }
        if self.indices.iter().any(|&v| v as usize >= count) {
            return Err(Error::InvalidArgument(format!(
                "the stencils refer to base vertices beyond the {count} given"
            )));
        }
        const BLOCK: usize = 1024;
        out.par_chunks_mut(width * BLOCK)
            .enumerate()
            .for_each(|(block, chunk)| {
                for (k, dst) in chunk.chunks_exact_mut(width).enumerate() {
                    dst.fill(0.0);
                    let (idx, w) = self.row(block * BLOCK + k);
                    for (&v, &w) in idx.iter().zip(w) {
                        let v = v as usize * width;
                        let w = w as f32;
                        for (d, s) in dst.iter_mut().zip(&base[v..v + width]) {
                            *d += w * s;
                        }
                    }
                }
            });
        Ok(())
    }

    /// Checks that `base` fits the table; returns its vertex count.
    fn check_apply(&self, width: usize, base: &[f64]) -> Result<usize> {
        if width == 0 || base.len() % width != 0 {
            return Err(Error::InvalidArgument(format!(
                "base data of {} values is not a whole number of {width}-wide elements",
                base.len()
            )));
        }
        let count = base.len() / width;
        if let Some(&v) = self.indices.iter().max() {
            if v as usize >= count {
                return Err(Error::InvalidArgument(format!(
                    "the stencils refer to base vertex {v}, but only {count} were given"
                )));
            }
        }
        Ok(count)
    }

    #[inline]
    fn apply_row(&self, i: usize, width: usize, base: &[f64], dst: &mut [f64]) {
        let (idx, w) = self.row(i);
        for (&v, &w) in idx.iter().zip(w) {
            let v = v as usize * width;
            for (d, s) in dst.iter_mut().zip(&base[v..v + width]) {
                *d += w * s;
            }
        }
    }

    /// Applies the table to base data of `width` components per vertex.
    pub fn apply(&self, width: usize, base: &[f64]) -> Result<Vec<f64>> {
        self.check_apply(width, base)?;
        let mut out = vec![0.0; self.len() * width];
        for (i, dst) in out.chunks_exact_mut(width).enumerate() {
            self.apply_row(i, width, base, dst);
        }
        Ok(out)
    }
}

/// Stencils for limit positions and both tangents at the vertices of one level.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LimitStencilTable {
    /// Limit position stencils.
    pub positions: StencilTable,
    /// First-tangent stencils.
    pub du: StencilTable,
    /// Second-tangent stencils.
    pub dv: StencilTable,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn apply_weights() {
        let t = StencilTable {
            sizes: vec![2, 1],
            offsets: vec![0, 2],
            indices: vec![0, 1, 1],
            weights: vec![0.25, 0.75, 1.0],
        };
        let out = t.apply(2, &[0.0, 4.0, 8.0, 0.0]).unwrap();
        assert_eq!(out, vec![6.0, 1.0, 8.0, 0.0]);
        assert!(t.apply(2, &[0.0, 1.0]).is_err());
    }
}
