//! [`StencilRows`]: a [`StencilTable`] built row by row, its arrays filled
//! by appending into tables ([`Growing`]) so the finished table's arrays are
//! huge-page maps when large, not vectors copied into them.

use super::StencilTable;
use crate::topology::Growing;

/// A stencil table being built, one row after the other (each row's
/// offset the terms before it).
pub(crate) struct StencilRows {
    sizes: Growing<u32>,
    offsets: Growing<u32>,
    indices: Growing<u32>,
    weights: Growing<f64>,
}

impl StencilRows {
    /// Room for about `rows` rows of `terms` terms in all (an estimate:
    /// more can be appended).
    pub(crate) fn with_capacity(rows: usize, terms: usize) -> Self {
        StencilRows {
            sizes: Growing::with_capacity(rows),
            offsets: Growing::with_capacity(rows),
            indices: Growing::with_capacity(terms),
            weights: Growing::with_capacity(terms),
        }
    }

    /// Terms appended so far.
    pub(crate) fn terms(&self) -> usize {
        self.indices.len()
    }

    /// Appends a row of the terms `columns` and `weights` (as many), each
    /// column mapped to its index by `index` and each weight to `f64` by
    /// `weight`.
    #[inline(always)]
    pub(crate) fn push_mapped<C: Copy, W: Copy>(
        &mut self,
        columns: &[C],
        index: impl Fn(C) -> u32,
        weights: &[W],
        weight: impl Fn(W) -> f64,
    ) {
        debug_assert_eq!(columns.len(), weights.len());
        self.offsets.push(self.indices.len() as u32);
        self.sizes.push(columns.len() as u32);
        self.indices.extend_mapped(columns, index);
        self.weights.extend_mapped(weights, weight);
    }

    /// Starts a row whose terms are appended one by one ([`StencilRows::term`])
    /// and which [`StencilRows::end_row`] ends.
    pub(crate) fn begin_row(&mut self) {
        self.offsets.push(self.indices.len() as u32);
    }

    /// Appends a term to the row begun last.
    #[inline]
    pub(crate) fn term(&mut self, index: u32, weight: f64) {
        self.indices.push(index);
        self.weights.push(weight);
    }

    /// Ends the row begun last: its size is the terms appended since.
    pub(crate) fn end_row(&mut self) {
        let start = self.offsets.as_slice().last().copied().unwrap_or(0);
        self.sizes.push(self.indices.len() as u32 - start);
    }

    /// The table.
    pub(crate) fn finish(self) -> StencilTable {
        StencilTable {
            sizes: self.sizes.finish(),
            offsets: self.offsets.finish(),
            indices: self.indices.finish(),
            weights: self.weights.finish(),
        }
    }
}
