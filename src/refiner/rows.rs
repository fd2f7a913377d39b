//! Stencil rows level by level, shared by the stencil factories of uniform
//! and adaptive refiners: [`Rows`], rows in compressed form appended into
//! tables, and [`RowBuilder`], which merges the terms of one row as
//! OpenSubdiv's stencil builder does before appending it whole.

use crate::real::Real;
use crate::stencil::StencilTable;
use crate::topology::{Growing, Table};

/// Stencil rows in vertex order: row `v` is `offsets[v]..offsets[v + 1]` of
/// `indices` (base vertices) and `weights`, appended into tables
/// ([`Growing`]): a level's rows are tens to hundreds of megabytes, on huge
/// pages and recycled by the pool rather than faulted in anew.
pub(super) struct Rows<T: Real> {
    pub(super) offsets: Growing<u32>,
    pub(super) indices: Growing<u32>,
    pub(super) weights: Growing<T>,
    /// One more than the largest index (0 without terms).
    pub(super) base_count: usize,
    /// The most terms in a row (0 without rows).
    pub(super) widest: usize,
}

/// [`Rows`] as slices, read through their tables once (for the loops that
/// merge rows).
#[derive(Clone, Copy)]
pub(super) struct RowsView<'a, T> {
    pub(super) offsets: &'a [u32],
    pub(super) indices: &'a [u32],
    pub(super) weights: &'a [T],
    /// The most terms in a row (0 without rows).
    pub(super) widest: usize,
}

impl<'a, T> RowsView<'a, T> {
    /// Row `v`: its base vertices and their weights.
    #[inline]
    pub(super) fn get(&self, v: u32) -> (&'a [u32], &'a [T]) {
        let (a, b) = (
            self.offsets[v as usize] as usize,
            self.offsets[v as usize + 1] as usize,
        );
        (&self.indices[a..b], &self.weights[a..b])
    }

    /// Average terms per row (1 without rows).
    pub(super) fn average(&self) -> f64 {
        match self.offsets.len().saturating_sub(1) {
            0 => 1.0,
            n => self.indices.len() as f64 / n as f64,
        }
    }
}

impl<T: Real> Rows<T> {
    /// No rows yet, with room for the offsets of `rows` rows.
    pub(super) fn with_rows(rows: usize) -> Self {
        let mut offsets = Growing::with_capacity(rows + 1);
        offsets.push(0);
        Rows {
            offsets,
            indices: Growing::with_capacity(0),
            weights: Growing::with_capacity(0),
            base_count: 0,
            widest: 0,
        }
    }

    /// The rows so far as slices.
    #[inline]
    pub(super) fn view(&self) -> RowsView<'_, T> {
        RowsView {
            offsets: self.offsets.as_slice(),
            indices: self.indices.as_slice(),
            weights: self.weights.as_slice(),
            widest: self.widest,
        }
    }

    /// Terms appended so far.
    pub(super) fn terms(&self) -> usize {
        self.indices.len()
    }

    /// Appends a row of `indices` and `weights` (as many), copied as they
    /// are. Unwinds as [`Rows::check_terms`] does.
    pub(super) fn push_row(&mut self, indices: &[u32], weights: &[T]) {
        self.check_terms(indices.len());
        for &i in indices {
            self.base_count = self.base_count.max(i as usize + 1);
        }
        self.indices.extend_from_slice(indices);
        self.weights.extend_from_slice(weights);
        self.offsets.push(self.indices.len() as u32);
        self.widest = self.widest.max(indices.len());
    }

    /// Number of rows.
    pub(super) fn len(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Unwinds to [`crate::alloc::guard`] when `terms` more terms would
    /// outgrow the table's `u32` offsets (the arrays grow as they are
    /// appended to, unwinding likewise when memory runs out).
    #[inline]
    pub(super) fn check_terms(&self, terms: usize) {
        check_total::<T>(self.indices.len() + terms);
    }

    /// Room for about `terms` terms, asked for once rather than found by
    /// doubling the arrays (each doubling copies them): an estimate, as
    /// pages reserved and never written cost nothing.
    pub(super) fn expect(&mut self, terms: f64) {
        let terms = terms.min(u32::MAX as f64) as usize;
        self.indices.reserve_total(terms);
        self.weights.reserve_total(terms);
    }

    /// Appends the rows of `other`.
    pub(super) fn append(&mut self, other: &Rows<T>) {
        self.check_terms(other.indices.len());
        let shift = self.indices.len() as u32;
        self.offsets
            .extend_mapped(&other.offsets.as_slice()[1..], |o| o + shift);
        self.indices.extend_from_slice(other.indices.as_slice());
        self.weights.extend_from_slice(other.weights.as_slice());
        self.base_count = self.base_count.max(other.base_count);
        self.widest = self.widest.max(other.widest);
    }

    /// The rows of `parts` one after the other, copied in parallel.
    pub(super) fn concat<R: std::borrow::Borrow<Rows<T>> + Sync>(parts: &[R]) -> Rows<T> {
        use rayon::prelude::*;
        let rows: usize = parts.iter().map(|p| p.borrow().len()).sum();
        let terms: usize = parts.iter().map(|p| p.borrow().indices.len()).sum();
        check_total::<T>(terms);
        let mut offsets = Table::<u32>::for_overwrite(rows + 1);
        let mut indices = Table::<u32>::for_overwrite(terms);
        let mut weights = Table::<T>::for_overwrite(terms);
        offsets[0] = 0;
        // Each part's slices of the three arrays.
        let mut slices = Vec::with_capacity(parts.len());
        let (mut o, mut i, mut w) = (&mut offsets[1..], &mut indices[..], &mut weights[..]);
        let mut shift = 0u32;
        for p in parts {
            let p = p.borrow();
            let (oh, ot) = std::mem::take(&mut o).split_at_mut(p.len());
            let (ih, it) = std::mem::take(&mut i).split_at_mut(p.indices.len());
            let (wh, wt) = std::mem::take(&mut w).split_at_mut(p.indices.len());
            slices.push((p.view(), shift, oh, ih, wh));
            (o, i, w) = (ot, it, wt);
            shift += p.indices.len() as u32;
        }
        slices.into_par_iter().for_each(|(p, shift, o, i, w)| {
            for (d, &s) in o.iter_mut().zip(&p.offsets[1..]) {
                *d = s + shift;
            }
            i.copy_from_slice(p.indices);
            w.copy_from_slice(p.weights);
        });
        Rows {
            offsets: Growing::from_table(offsets),
            indices: Growing::from_table(indices),
            weights: Growing::from_table(weights),
            base_count: parts
                .iter()
                .map(|p| p.borrow().base_count)
                .max()
                .unwrap_or(0),
            widest: parts.iter().map(|p| p.borrow().widest).max().unwrap_or(0),
        }
    }
}

/// Unwinds to [`crate::alloc::guard`] when a table of `total` terms
/// would outgrow its `u32` offsets.
#[inline]
fn check_total<T>(total: usize) {
    if u32::try_from(total).is_err() {
        crate::alloc::fail(total.saturating_mul(size_of::<u32>() + size_of::<T>()));
    }
}

impl Rows<f64> {
    /// The rows as a table with sizes and offsets (no copy of the terms).
    pub(super) fn into_table(self) -> StencilTable {
        let sizes = self
            .offsets
            .as_slice()
            .windows(2)
            .map(|w| w[1] - w[0])
            .collect();
        let mut offsets = self.offsets.finish();
        offsets.truncate(offsets.len() - 1);
        StencilTable {
            sizes,
            offsets,
            indices: self.indices.finish(),
            weights: self.weights.finish(),
        }
    }
}

/// Builds rows at the end of a [`Rows`], merging the terms of each row by
/// coarse vertex (a base vertex, for rows factorized down to the base
/// level) in order of first contribution, as OpenSubdiv's stencil builder
/// does: each weight is `0 + x * w` for its first term and `+= x * w` for
/// the next ones, in the row's precision.
///
/// A row's weights are summed in a dense accumulator, one per base vertex
/// (zero outside the open row), and its vertices listed in order of first
/// contribution at the end of the builder's own buffers (which stay in
/// cache); closing the row moves its sums beside them and zeroes them
/// again. Each term then takes the same branch-free steps, new to the row
/// or not, and its sum is addressed by its vertex, not through a position
/// looked up first (a chain of two dependent loads per term, which bound
/// the merge when the row's position was kept per vertex instead). The
/// sums are the same: `0 + x * w` for a first term, `+= x * w` after.
/// Finished rows wait in the buffers to be appended to the table in one
/// copy per block of rows ([`RowBuilder::flush`]): appending each short
/// row to the table on its own cost more than merging it.
pub(super) struct RowBuilder<T> {
    /// Each base vertex's sum in the open row and whether it is in it.
    acc: Vec<Sum<T>>,
    /// The finished rows not yet appended (their first `filled` entries),
    /// then the open row (its first `len` entries after them), then room.
    indices: Vec<u32>,
    weights: Vec<T>,
    filled: usize,
    len: usize,
    /// Where each finished row not yet appended ends in the buffers.
    ends: Vec<u32>,
    /// One more than the largest index of those rows (0 without terms).
    base_count: usize,
    /// The most terms in one of those rows.
    widest: usize,
}

/// Terms of finished rows after which [`RowBuilder::end_pending`]'s callers
/// append them to their table (128 KiB of indices: a cache-sized block,
/// many rows per copy).
const PENDING_TERMS: usize = 1 << 15;

impl<T: Real> RowBuilder<T> {
    /// A builder for rows over `base` base vertices (none in a row).
    /// Unwinds to [`crate::alloc::guard`] when memory runs out.
    pub(super) fn new(base: usize) -> Self {
        RowBuilder {
            acc: crate::alloc::vec_or_unwind(Sum::EMPTY, base),
            indices: Vec::new(),
            weights: Vec::new(),
            filled: 0,
            len: 0,
            ends: Vec::new(),
            base_count: 0,
            widest: 0,
        }
    }

    /// Starts a row of at most `bound` terms (a bound beyond the base
    /// vertices is taken as their number: a row has each at most once).
    /// Unwinds to [`crate::alloc::guard`] when the buffer cannot hold it.
    #[inline]
    pub(super) fn open(&mut self, bound: usize) {
        // One more than the row can hold: each term writes its vertex one
        // past the row's end before it is known to be new.
        let needed = self.filled + bound.min(self.acc.len()) + 1;
        if self.indices.len() < needed {
            self.grow(needed);
        }
        self.len = 0;
    }

    /// Makes the buffers at least `needed` terms long (twice as long as
    /// they were, so that growing is rare), unwinding when memory runs
    /// out.
    #[cold]
    #[inline(never)]
    fn grow(&mut self, needed: usize) {
        let target = needed.max(2 * self.indices.len()).max(256);
        let more = target - self.indices.len();
        if self.indices.try_reserve(more).is_err() || self.weights.try_reserve(more).is_err() {
            crate::alloc::fail(target.saturating_mul(size_of::<u32>() + size_of::<T>()));
        }
        self.indices.resize(target, 0);
        self.weights.resize(target, T::ZERO);
    }

    /// Adds `w` times a row to the open row.
    #[inline(always)]
    pub(super) fn add_row(&mut self, row: (&[u32], &[T]), w: T) {
        let mut open = OpenRow {
            acc: &mut self.acc,
            indices: &mut self.indices[self.filled..],
            len: self.len,
        };
        open.add_row(row, w);
        self.len = open.len;
    }

    /// Starts a row of at most `bound` terms, as [`RowBuilder::open`], and
    /// gives it to be built through its own slices (no buffer sliced per
    /// row added); [`RowBuilder::close`] ends it.
    #[inline(always)]
    pub(super) fn open_row(&mut self, bound: usize) -> OpenRow<'_, T> {
        self.open(bound);
        OpenRow {
            acc: &mut self.acc,
            indices: &mut self.indices[self.filled..],
            len: 0,
        }
    }

    /// Closes a row [`RowBuilder::open_row`] gave and `len` terms long, as
    /// [`RowBuilder::end_pending`].
    #[inline(always)]
    pub(super) fn close(&mut self, len: usize) -> bool {
        self.len = len;
        self.end_pending()
    }

    /// Terms in the open row so far.
    pub(super) fn len(&self) -> usize {
        self.len
    }

    /// Closes the open row, which waits in the buffers to be appended by
    /// [`RowBuilder::flush`]; `true` when enough rows wait that it is time.
    #[inline]
    pub(super) fn end_pending(&mut self) -> bool {
        let end = self.filled + self.len;
        let row = self.indices[self.filled..end]
            .iter()
            .zip(&mut self.weights[self.filled..end]);
        for (&i, w) in row {
            let i = i as usize;
            *w = std::mem::replace(&mut self.acc[i], Sum::EMPTY).sum;
            self.base_count = self.base_count.max(i + 1);
        }
        self.widest = self.widest.max(self.len);
        self.filled = end;
        self.ends.push(end as u32);
        end >= PENDING_TERMS
    }

    /// Appends the finished rows waiting in the buffers to `out`. Unwinds as
    /// [`Rows::check_terms`] does.
    pub(super) fn flush(&mut self, out: &mut Rows<T>) {
        out.check_terms(self.filled);
        let shift = out.indices.len() as u32;
        out.indices.extend_from_slice(&self.indices[..self.filled]);
        out.weights.extend_from_slice(&self.weights[..self.filled]);
        out.offsets.extend_mapped(&self.ends, |e| e + shift);
        out.base_count = out.base_count.max(self.base_count);
        out.widest = out.widest.max(self.widest);
        self.filled = 0;
        self.ends.clear();
        self.base_count = 0;
        self.widest = 0;
    }

    /// Closes the open row and appends it (with any rows waiting) to `out`.
    pub(super) fn end_row(&mut self, out: &mut Rows<T>) {
        self.end_pending();
        self.flush(out);
    }
}

/// A base vertex's sum in the open row of a [`RowBuilder`], beside the
/// mark of whether it is in the row (one cache line for both).
#[derive(Clone, Copy)]
pub(super) struct Sum<T> {
    sum: T,
    absent: bool,
}

impl<T: Real> Sum<T> {
    /// Not in the row: zero, which a first term adds to.
    const EMPTY: Sum<T> = Sum {
        sum: T::ZERO,
        absent: true,
    };
}

/// A row being built at the end of a [`RowBuilder`]'s buffers: its
/// vertices there, its sums in the builder's accumulator.
pub(super) struct OpenRow<'b, T> {
    acc: &'b mut [Sum<T>],
    indices: &'b mut [u32],
    /// Its terms so far.
    pub(super) len: usize,
}

impl<T: Real> OpenRow<'_, T> {
    /// Adds `w` times a row to this one.
    #[inline(always)]
    pub(super) fn add_row(&mut self, row: (&[u32], &[T]), w: T) {
        let mut len = self.len;
        for (&i, &x) in row.0.iter().zip(row.1) {
            let a = &mut self.acc[i as usize];
            // Written whether new or not: a vertex already in the row is
            // overwritten by the next new one (the buffer has room for
            // one more than the row).
            self.indices[len] = i;
            len += usize::from(a.absent);
            *a = Sum {
                sum: a.sum + x * w,
                absent: false,
            };
        }
        self.len = len;
    }
}
