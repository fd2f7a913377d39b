//! Stencil tables: each refined (or limit) value as a weighted sum of base values.
//!
//! [`StencilTable`] is the general form (`f64` weights, any row order).
//! [`StencilTableF32`] is the per-frame form, as OpenSubdiv's float
//! `Far::StencilTable`: `f32` weights, rows stored one after the other,
//! checked once when it is built, applied by a kernel specialised for 1 to 4
//! components per vertex. Its results equal `Osd::CpuEvaluator::EvalStencils`
//! on the same table bit for bit (same products, same order of additions, no
//! fused multiply-add).

use crate::error::{Buffer, Error, Result, StencilFault};
use crate::topology::{Growing, Table};
use glam::Vec4;

mod options;
mod rows;
pub use options::{MAX_STENCIL_LEVEL, StencilInterpolation, StencilOptions};
pub(crate) use rows::StencilRows;

/// A stencil table in compressed-sparse-row form: row `i` is
/// `sum(weights[k] * base[indices[k]])` for `k` in `offsets[i]..offsets[i] + sizes[i]`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct StencilTable {
    /// Number of weights of each stencil.
    pub sizes: Table<u32>,
    /// Start of each stencil in `indices` and `weights`.
    pub offsets: Table<u32>,
    /// Base-vertex index of each weight.
    pub indices: Table<u32>,
    /// The weights.
    pub weights: Table<f64>,
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
        self.slices().row(i)
    }

    /// The arrays as slices, read through their tables once (for loops
    /// over the rows).
    #[inline]
    fn slices(&self) -> Slices<'_> {
        Slices {
            sizes: &self.sizes,
            offsets: &self.offsets,
            indices: &self.indices,
            weights: &self.weights,
        }
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
        let mut out = crate::alloc::try_zeroed(self.len() * width)?;
        out.par_chunks_mut(width * 256)
            .enumerate()
            .for_each(|(block, chunk)| self.apply_rows_into(block * 256, width, base, chunk));
        Ok(out)
    }

    /// As [`StencilTable::apply_par`] for `f32` data (weights rounded to `f32`
    /// as they are applied), into a caller's buffer. It reads the `f64`
    /// weights and checks every index on each call: for many frames, convert
    /// the table once with [`StencilTable::to_f32`] and use
    /// [`StencilTableF32::apply_into`], which gives the same values faster.
    ///
    /// ```
    /// use subdiv::{refiner::Refiner, shapes, Options, UniformOptions};
    /// let cube = shapes::cube();
    /// let mut r = Refiner::new(&cube, &Options::default())?;
    /// r.refine_uniform(UniformOptions::new(2))?;
    /// let table = r.stencil_table()?;
    /// let base: Vec<f32> = cube.positions.iter().flat_map(|p| p.as_vec3().to_array()).collect();
    /// let mut out = vec![0.0; table.len() * 3];
    /// table.apply_par_f32_into(3, &base, &mut out)?;
    /// assert_eq!(out, table.to_f32()?.apply(3, &base)?);
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn apply_par_f32_into(&self, width: usize, base: &[f32], out: &mut [f32]) -> Result<()> {
        check_buffers(self.len(), width, base.len(), out.len())?;
        let count = base.len() / width;
        if let Some(&index) = self.indices.iter().max().filter(|&&v| v as usize >= count) {
            return Err(Error::StencilOutOfRange {
                index: index as usize,
                count,
            });
        }
        self.check_rows()?;
        let t = self.slices();
        apply_rows(width, base, out, t.indices.len(), |r| t.row(r));
        Ok(())
    }

    /// The same table with `f32` weights (each rounded to nearest), laid out
    /// for fast repeated application: see [`StencilTableF32`]. The rows keep
    /// their order, indices and weight order.
    ///
    /// ```
    /// use subdiv::{refiner::Refiner, shapes, Options, UniformOptions};
    /// let cube = shapes::cube();
    /// let mut r = Refiner::new(&cube, &Options::default())?;
    /// r.refine_uniform(UniformOptions::new(1))?;
    /// let table = r.stencil_table()?;
    /// let fast = table.to_f32()?;
    /// assert_eq!(fast.len(), table.len());
    /// let (i, w) = fast.row(0);
    /// assert_eq!(i, table.row(0).0);
    /// assert_eq!(w[0], table.row(0).1[0] as f32);
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    ///
    /// A table whose rows lie outside its `indices` or `weights` (built by
    /// hand and left inconsistent), or that has more than `u32::MAX` terms,
    /// is an [`Error::MalformedStencils`] or an [`Error::TooLarge`].
    pub fn to_f32(&self) -> Result<StencilTableF32> {
        self.check_rows()?;
        if self.indices.len() > u32::MAX as usize {
            return Err(Error::TooLarge {
                what: "stencil terms",
                count: self.indices.len(),
                bits: 32,
            });
        }
        let rows = self.slices();
        let mut offsets = Growing::<u32>::with_capacity(self.len() + 1);
        let mut indices = Growing::<u32>::with_capacity(rows.indices.len());
        let mut weights = Growing::<f32>::with_capacity(rows.indices.len());
        let mut base_count = 0;
        offsets.push(0);
        for i in 0..self.len() {
            let (idx, w) = rows.row(i);
            indices.extend_from_slice(idx);
            weights.extend_mapped(w, |w| w as f32);
            offsets.push(indices.len() as u32);
            if let Some(&m) = idx.iter().max() {
                base_count = base_count.max(m as usize + 1);
            }
        }
        Ok(StencilTableF32::from_checked_parts(
            offsets.finish(),
            indices.finish(),
            weights.finish(),
            base_count,
        ))
    }

    /// Checks that every row lies inside `indices` and `weights`.
    fn check_rows(&self) -> Result<()> {
        if self.offsets.len() != self.len() {
            return Err(Error::MalformedStencils(StencilFault::SizesAndOffsets {
                sizes: self.len(),
                offsets: self.offsets.len(),
            }));
        }
        let terms = self.indices.len().min(self.weights.len());
        let (offsets, sizes): (&[u32], &[u32]) = (&self.offsets, &self.sizes);
        if let Some(row) =
            (0..self.len()).find(|&i| offsets[i] as usize + sizes[i] as usize > terms)
        {
            return Err(Error::MalformedStencils(StencilFault::RowOutOfRange {
                row,
            }));
        }
        Ok(())
    }

    /// Checks that `base` fits the table; returns its vertex count.
    fn check_apply(&self, width: usize, base: &[f64]) -> Result<usize> {
        check_base(width, base.len())?;
        let count = base.len() / width;
        if let Some(&v) = self.indices.iter().max()
            && v as usize >= count
        {
            return Err(Error::StencilOutOfRange {
                index: v as usize,
                count,
            });
        }
        Ok(count)
    }

    /// Rows `first..` of the table applied to `base` (`width` values per
    /// vertex) into `out` (whole rows of `width` values): each row's terms
    /// added in order to zero. Widths 1 to 4 are summed in registers (a
    /// run-time width kept every partial sum in memory). An index past
    /// `base` panics: callers check the table against `base` first or build
    /// both together.
    pub(crate) fn apply_rows_into(
        &self,
        first: usize,
        width: usize,
        base: &[f64],
        out: &mut [f64],
    ) {
        fn rows<const W: usize>(t: Slices<'_>, first: usize, base: &[f64], out: &mut [f64]) {
            for (i, dst) in out.chunks_exact_mut(W).enumerate() {
                let (idx, w) = t.row(first + i);
                let mut acc = [0.0f64; W];
                for (&v, &w) in idx.iter().zip(w) {
                    let src = &base[v as usize * W..][..W];
                    for (a, &s) in acc.iter_mut().zip(src) {
                        *a += w * s;
                    }
                }
                dst.copy_from_slice(&acc);
            }
        }
        let t = self.slices();
        match width {
            1 => rows::<1>(t, first, base, out),
            2 => rows::<2>(t, first, base, out),
            3 => rows::<3>(t, first, base, out),
            4 => rows::<4>(t, first, base, out),
            _ => {
                for (i, dst) in out.chunks_exact_mut(width).enumerate() {
                    let (idx, w) = t.row(first + i);
                    dst.fill(0.0);
                    for (&v, &w) in idx.iter().zip(w) {
                        let v = v as usize * width;
                        for (d, s) in dst.iter_mut().zip(&base[v..v + width]) {
                            *d += w * s;
                        }
                    }
                }
            }
        }
    }

    /// Applies the table to base data of `width` components per vertex.
    pub fn apply(&self, width: usize, base: &[f64]) -> Result<Vec<f64>> {
        self.check_apply(width, base)?;
        let mut out = crate::alloc::try_zeroed(self.len() * width)?;
        self.apply_rows_into(0, width, base, &mut out);
        Ok(out)
    }
}

/// A [`StencilTable`]'s arrays as slices.
#[derive(Clone, Copy)]
struct Slices<'a> {
    sizes: &'a [u32],
    offsets: &'a [u32],
    indices: &'a [u32],
    weights: &'a [f64],
}

impl<'a> Slices<'a> {
    /// The indices and weights of stencil `i`.
    #[inline]
    fn row(&self, i: usize) -> (&'a [u32], &'a [f64]) {
        let a = self.offsets[i] as usize;
        let b = a + self.sizes[i] as usize;
        (&self.indices[a..b], &self.weights[a..b])
    }
}

/// A stencil table with `f32` weights, for applying the same stencils to
/// many frames of `f32` data: the counterpart of OpenSubdiv's float
/// `Far::StencilTable` and `Osd::CpuEvaluator::EvalStencils`.
///
/// Rows are stored one after the other: `offsets` has `len() + 1` entries and
/// row `i` is `indices[offsets[i]..offsets[i + 1]]` with the weights at the
/// same positions. A pass reads 8 bytes per term (a `u32` index and an `f32`
/// weight) and 4 per row, and the largest index is known from construction,
/// so applying it checks the buffers in constant time.
///
/// Each output value is accumulated from zero, one product `weight * value`
/// and one addition per term, in the row's order, exactly as
/// `Osd::CpuEvaluator::EvalStencils` does: with the same weights, the results
/// are bit for bit OpenSubdiv's. Build it with
/// [`Refiner::stencil_table_f32`](crate::refiner::Refiner::stencil_table_f32)
/// (weights computed in `f32`, as OpenSubdiv's float stencil factory does) or
/// [`StencilTable::to_f32`] (weights computed in `f64`, then rounded).
///
/// ```
/// use subdiv::{refiner::Refiner, shapes, Options, UniformOptions};
/// let torus = shapes::torus(8, 6);
/// let mut r = Refiner::new(&torus, &Options::default())?;
/// r.refine_uniform(UniformOptions::new(3))?;
/// let stencils = r.stencil_table_f32()?; // once
/// let frame: Vec<f32> = torus.positions.iter().flat_map(|p| p.as_vec3().to_array()).collect();
/// let mut refined = vec![0.0; stencils.len() * 3];
/// stencils.apply_into(3, &frame, &mut refined)?; // per frame
/// assert_eq!(refined.len(), r.level_counts(3)?.vertices * 3);
/// # Ok::<(), subdiv::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct StencilTableF32 {
    offsets: Table<u32>,
    indices: Table<u32>,
    weights: Table<f32>,
    /// One more than the largest index (0 without terms).
    base_count: usize,
}

impl Default for StencilTableF32 {
    fn default() -> Self {
        StencilTableF32 {
            offsets: vec![0].into(),
            indices: Table::new(),
            weights: Table::new(),
            base_count: 0,
        }
    }
}

impl StencilTableF32 {
    /// A table from arrays built consistent by the crate (`offsets` from 0
    /// to `indices.len()`, non-decreasing; `base_count` one more than the
    /// largest index): as [`StencilTableF32::from_parts`] without the checks.
    pub(crate) fn from_checked_parts(
        offsets: Table<u32>,
        indices: Table<u32>,
        weights: Table<f32>,
        base_count: usize,
    ) -> Self {
        debug_assert_eq!(indices.len(), weights.len());
        debug_assert_eq!(offsets.first(), Some(&0));
        debug_assert_eq!(offsets.last().map(|&o| o as usize), Some(indices.len()));
        debug_assert!(offsets.windows(2).all(|w| w[0] <= w[1]));
        debug_assert_eq!(
            base_count,
            indices.iter().max().map_or(0, |&m| m as usize + 1)
        );
        StencilTableF32 {
            offsets,
            indices,
            weights,
            base_count,
        }
    }

    /// A table from its arrays: `offsets` (`rows + 1` non-decreasing values
    /// from 0 to `indices.len()`), the base-vertex `indices` and their
    /// `weights`. Checked once here, so that applying it needs no per-term
    /// validation.
    ///
    /// ```
    /// use subdiv::stencil::StencilTableF32;
    /// // Two rows: 0.25 * v0 + 0.75 * v1, and v1.
    /// let t = StencilTableF32::from_parts(vec![0, 2, 3], vec![0, 1, 1], vec![0.25, 0.75, 1.0])?;
    /// assert_eq!(t.apply(2, &[0.0, 4.0, 8.0, 0.0])?, vec![6.0, 1.0, 8.0, 0.0]);
    /// assert!(StencilTableF32::from_parts(vec![0, 2], vec![0], vec![1.0]).is_err());
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn from_parts(offsets: Vec<u32>, indices: Vec<u32>, weights: Vec<f32>) -> Result<Self> {
        let bad = |fault| Err(Error::MalformedStencils(fault));
        if indices.len() != weights.len() {
            return bad(StencilFault::IndicesAndWeights {
                indices: indices.len(),
                weights: weights.len(),
            });
        }
        if offsets.first() != Some(&0) {
            return bad(StencilFault::FirstOffset);
        }
        if let Some(i) = offsets.windows(2).position(|w| w[0] > w[1]) {
            return bad(StencilFault::DecreasingOffsets { index: i + 1 });
        }
        if offsets.last().map(|&o| o as usize) != Some(indices.len()) {
            return bad(StencilFault::LastOffset);
        }
        let base_count = indices.iter().max().map_or(0, |&m| m as usize + 1);
        Ok(StencilTableF32 {
            offsets: offsets.into(),
            indices: indices.into(),
            weights: weights.into(),
            base_count,
        })
    }

    /// Number of stencils (rows).
    pub fn len(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Whether the table has no stencil.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Number of terms (index and weight pairs) over all rows.
    pub fn term_count(&self) -> usize {
        self.indices.len()
    }

    /// The fewest base vertices the table can be applied to: one more than
    /// its largest index (0 when it has no term).
    pub fn min_base_count(&self) -> usize {
        self.base_count
    }

    /// Start of each row in [`indices`](Self::indices) and
    /// [`weights`](Self::weights), and the end of the last row.
    pub fn offsets(&self) -> &[u32] {
        &self.offsets
    }

    /// The base-vertex index of every term.
    pub fn indices(&self) -> &[u32] {
        &self.indices
    }

    /// The weight of every term.
    pub fn weights(&self) -> &[f32] {
        &self.weights
    }

    /// The indices and weights of stencil `i`.
    ///
    /// # Panics
    /// If `i >= len()`.
    pub fn row(&self, i: usize) -> (&[u32], &[f32]) {
        row_of(&self.offsets, &self.indices, &self.weights, i)
    }

    /// Applies the table to `base`, `width` values per vertex (at least
    /// [`min_base_count`](Self::min_base_count) vertices), writing
    /// `len() * width` values into `out`. Large tables are applied in
    /// parallel by rayon, in the pool the call runs in
    /// (`ThreadPool::install`) or the global one.
    ///
    /// ```
    /// use subdiv::stencil::StencilTableF32;
    /// let t = StencilTableF32::from_parts(vec![0, 2], vec![0, 1], vec![0.5, 0.5])?;
    /// let mut mid = [0.0; 3];
    /// t.apply_into(3, &[0.0, 0.0, 0.0, 2.0, 4.0, 6.0], &mut mid)?;
    /// assert_eq!(mid, [1.0, 2.0, 3.0]);
    /// assert!(t.apply_into(3, &[0.0, 0.0, 0.0], &mut mid).is_err()); // vertex 1 missing
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn apply_into(&self, width: usize, base: &[f32], out: &mut [f32]) -> Result<()> {
        check_buffers(self.len(), width, base.len(), out.len())?;
        let count = base.len() / width;
        if count < self.base_count {
            return Err(Error::StencilOutOfRange {
                index: self.base_count - 1,
                count,
            });
        }
        apply_f32(self, width, base, out);
        Ok(())
    }

    /// As [`apply_into`](Self::apply_into), into a new vector.
    ///
    /// ```
    /// use subdiv::stencil::StencilTableF32;
    /// let t = StencilTableF32::from_parts(vec![0, 1, 3], vec![1, 0, 1], vec![1.0, 0.5, 0.5])?;
    /// assert_eq!(t.apply(1, &[2.0, 4.0])?, vec![4.0, 3.0]);
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn apply(&self, width: usize, base: &[f32]) -> Result<Vec<f32>> {
        let len = self.len().checked_mul(width).ok_or(Error::TooLarge {
            what: "output values",
            count: usize::MAX,
            bits: usize::BITS,
        })?;
        let mut out = crate::alloc::try_zeroed(len)?;
        self.apply_into(width, base, &mut out)?;
        Ok(out)
    }
}

/// Checks that base data of `len` values is whole `width`-wide elements.
fn check_base(width: usize, len: usize) -> Result<()> {
    if width == 0 {
        return Err(Error::ZeroWidth);
    }
    if !len.is_multiple_of(width) {
        return Err(Error::NotWholeElements {
            buffer: Buffer::Base,
            len,
            width,
        });
    }
    Ok(())
}

/// Checks the buffer lengths of an `f32` apply.
fn check_buffers(rows: usize, width: usize, base: usize, out: usize) -> Result<()> {
    check_base(width, base)?;
    let expected = rows.checked_mul(width).ok_or(Error::TooLarge {
        what: "output values",
        count: usize::MAX,
        bits: usize::BITS,
    })?;
    if out != expected {
        return Err(Error::BufferLength {
            buffer: Buffer::Output,
            expected,
            got: out,
        });
    }
    Ok(())
}

/// A weight as stored: `f32`, or `f64` rounded to `f32` as it is applied.
trait Weight: Copy + Sync {
    fn get(self) -> f32;
}

impl Weight for f32 {
    #[inline(always)]
    fn get(self) -> f32 {
        self
    }
}

impl Weight for f64 {
    #[inline(always)]
    fn get(self) -> f32 {
        self as f32
    }
}

/// The values of one vertex with `W` components, held in registers while a
/// stencil is accumulated, and how they are read from the base.
trait Lanes<const W: usize>: Copy {
    /// The element type of the base as the kernel reads it.
    type Src: Sync;
    const ZERO: Self;
    /// Vertex `i` of the base (checked: one comparison per term).
    fn load(src: &[Self::Src], i: u32) -> Self;
    /// `self + w * s`: one rounded product and one rounded sum per component,
    /// as `Osd::CpuEvaluator::EvalStencils`.
    fn add_scaled(self, w: f32, s: Self) -> Self;
    fn store(self) -> [f32; W];
}

impl Lanes<1> for f32 {
    type Src = f32;
    const ZERO: Self = 0.0;
    #[inline(always)]
    fn load(src: &[f32], i: u32) -> Self {
        src[i as usize]
    }
    #[inline(always)]
    fn add_scaled(self, w: f32, s: Self) -> Self {
        self + w * s
    }
    #[inline(always)]
    fn store(self) -> [f32; 1] {
        [self]
    }
}

/// Two or three components (`[f32; 2]`, `[f32; 3]`) read from the caller's
/// base as it is (three: tables with fewer terms than base vertices, and
/// [`StencilTable::apply_par_f32_into`]).
impl<const W: usize> Lanes<W> for [f32; W] {
    type Src = f32;
    const ZERO: Self = [0.0; W];
    #[inline(always)]
    fn load(src: &[f32], i: u32) -> Self {
        let v = i as usize * W;
        let s = &src[v..v + W];
        std::array::from_fn(|k| s[k])
    }
    #[inline(always)]
    fn add_scaled(self, w: f32, s: Self) -> Self {
        std::array::from_fn(|k| self[k] + w * s[k])
    }
    #[inline(always)]
    fn store(self) -> [f32; W] {
        self
    }
}

/// Three components in a 4-lane vector (the fourth is zero and ignored), read
/// from a copy of the base padded to 16 bytes per vertex: one aligned load,
/// one multiply and one add per term.
impl Lanes<3> for Vec4 {
    type Src = Vec4;
    const ZERO: Self = Vec4::ZERO;
    #[inline(always)]
    fn load(src: &[Vec4], i: u32) -> Self {
        src[i as usize]
    }
    #[inline(always)]
    fn add_scaled(self, w: f32, s: Self) -> Self {
        self + Vec4::splat(w) * s
    }
    #[inline(always)]
    fn store(self) -> [f32; 3] {
        self.truncate().to_array()
    }
}

impl Lanes<4> for Vec4 {
    type Src = f32;
    const ZERO: Self = Vec4::ZERO;
    #[inline(always)]
    fn load(src: &[f32], i: u32) -> Self {
        let v = i as usize * 4;
        Vec4::from_slice(&src[v..v + 4])
    }
    #[inline(always)]
    fn add_scaled(self, w: f32, s: Self) -> Self {
        self + Vec4::splat(w) * s
    }
    #[inline(always)]
    fn store(self) -> [f32; 4] {
        self.to_array()
    }
}

/// Stencils per parallel task (about 15 000 terms for level-4 Catmull-Clark
/// stencils).
const BLOCK: usize = 1024;
/// Tables with fewer terms are applied on the calling thread.
const SERIAL_TERMS: usize = 1 << 16;

/// Applies a [`StencilTableF32`] (buffers checked by the caller).
fn apply_f32(t: &StencilTableF32, width: usize, base: &[f32], out: &mut [f32]) {
    let terms = t.term_count();
    let (offsets, indices, weights) = (t.offsets(), t.indices(), t.weights());
    match width {
        1 => in_blocks(out, 1, terms, |first, chunk| {
            block::<1, f32>(t, first, base, chunk)
        }),
        2 => in_blocks(out, 2, terms, |first, chunk| {
            block::<2, [f32; 2]>(t, first, base, chunk)
        }),
        // Pad the base to 16 bytes per vertex when the table reads it at
        // least once per vertex on average: the copy costs less than the
        // loads it saves.
        3 if terms >= base.len() / 3 => {
            let padded = pad3(base, terms);
            in_blocks(out, 3, terms, |first, chunk| {
                block::<3, Vec4>(t, first, &padded, chunk)
            })
        }
        // Few terms over a large base: read it as it is.
        3 => apply_rows(3, base, out, terms, |r| {
            row_of(offsets, indices, weights, r)
        }),
        4 => in_blocks(out, 4, terms, |first, chunk| {
            block::<4, Vec4>(t, first, base, chunk)
        }),
        _ => apply_rows(width, base, out, terms, |r| {
            row_of(offsets, indices, weights, r)
        }),
    }
}

/// Row `i` of a table of rows one after the other (`offsets` with one more
/// entry than rows).
#[inline]
fn row_of<'a>(
    offsets: &[u32],
    indices: &'a [u32],
    weights: &'a [f32],
    i: usize,
) -> (&'a [u32], &'a [f32]) {
    let (a, b) = (offsets[i] as usize, offsets[i + 1] as usize);
    (&indices[a..b], &weights[a..b])
}

/// Applies the rows `row(r)` gives (any layout, weights of any [`Weight`]
/// type) to `base`, `width` values per vertex, into `out`: the path of
/// [`StencilTable::apply_par_f32_into`] and of the widths without a
/// specialised kernel. The caller has checked the buffers: `out` holds whole
/// rows and every index is below `base.len() / width`.
fn apply_rows<'a, Wt: Weight + 'a>(
    width: usize,
    base: &[f32],
    out: &mut [f32],
    terms: usize,
    row: impl Fn(usize) -> (&'a [u32], &'a [Wt]) + Sync,
) {
    fn rows<'a, const W: usize, L: Lanes<W>, Wt: Weight + 'a>(
        src: &[L::Src],
        out: &mut [f32],
        terms: usize,
        row: impl Fn(usize) -> (&'a [u32], &'a [Wt]) + Sync,
    ) {
        in_blocks(out, W, terms, |first, chunk| {
            for (r, dst) in chunk.chunks_exact_mut(W).enumerate() {
                let (idx, w) = row(first + r);
                let mut acc = L::ZERO;
                for (&i, &w) in idx.iter().zip(w) {
                    acc = acc.add_scaled(w.get(), L::load(src, i));
                }
                dst.copy_from_slice(&acc.store());
            }
        });
    }
    match width {
        1 => rows::<1, f32, Wt>(base, out, terms, row),
        2 => rows::<2, [f32; 2], Wt>(base, out, terms, row),
        3 => rows::<3, [f32; 3], Wt>(base, out, terms, row),
        4 => rows::<4, Vec4, Wt>(base, out, terms, row),
        _ => in_blocks(out, width, terms, |first, chunk| {
            for (r, dst) in chunk.chunks_exact_mut(width).enumerate() {
                let (idx, w) = row(first + r);
                dst.fill(0.0);
                for (&i, &w) in idx.iter().zip(w) {
                    let (w, v) = (w.get(), i as usize * width);
                    for (d, &s) in dst.iter_mut().zip(&base[v..v + width]) {
                        *d += w * s;
                    }
                }
            }
        }),
    }
}

/// The base with each 3-component vertex in its own 16-byte vector.
fn pad3(base: &[f32], terms: usize) -> Vec<Vec4> {
    use rayon::prelude::*;
    let pad = |v: &[f32]| Vec4::new(v[0], v[1], v[2], 0.0);
    if terms < SERIAL_TERMS || rayon::current_num_threads() == 1 {
        base.chunks_exact(3).map(pad).collect()
    } else {
        base.par_chunks_exact(3)
            .with_min_len(1 << 12)
            .map(pad)
            .collect()
    }
}

/// Runs `block(first_row, rows)` over `out` (rows of `width` values) in
/// blocks of [`BLOCK`] rows, in parallel unless the work is small or the
/// current rayon pool has a single thread.
fn in_blocks(
    out: &mut [f32],
    width: usize,
    terms: usize,
    block: impl Fn(usize, &mut [f32]) + Sync,
) {
    use rayon::prelude::*;
    if terms < SERIAL_TERMS || rayon::current_num_threads() == 1 {
        block(0, out);
    } else {
        out.par_chunks_mut(BLOCK * width)
            .enumerate()
            .for_each(|(b, chunk)| block(b * BLOCK, chunk));
    }
}

/// The rows of `t` from `first` on into `out` (whole rows of `W` values), one
/// after the other, each term added in the row's order. A plain loop: rows
/// unrolled by size, or two at a time, measured 10-20% slower on the tori
/// once the loop is aligned (`.cargo/config.toml`; docs/PERFORMANCE.md,
/// "Loop alignment").
fn block<const W: usize, L: Lanes<W>>(
    t: &StencilTableF32,
    first: usize,
    src: &[L::Src],
    out: &mut [f32],
) {
    let n = out.len() / W;
    let offsets = &t.offsets[first..=first + n];
    let start = offsets[0] as usize;
    let (mut idx, mut wts) = (&t.indices[start..], &t.weights[start..]);
    for (o, dst) in offsets.windows(2).zip(out.chunks_exact_mut(W)) {
        let n = (o[1] - o[0]) as usize;
        let (i, rest) = idx.split_at(n);
        idx = rest;
        let (w, rest) = wts.split_at(n);
        wts = rest;
        dst.copy_from_slice(&terms::<W, L>(L::ZERO, i, w, src).store());
    }
}

/// `acc` plus the terms, in order.
#[inline(always)]
fn terms<const W: usize, L: Lanes<W>>(mut acc: L, i: &[u32], w: &[f32], src: &[L::Src]) -> L {
    for (&i, &w) in i.iter().zip(w) {
        acc = acc.add_scaled(w, L::load(src, i));
    }
    acc
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
            sizes: vec![2, 1].into(),
            offsets: vec![0, 2].into(),
            indices: vec![0, 1, 1].into(),
            weights: vec![0.25, 0.75, 1.0].into(),
        };
        let out = t.apply(2, &[0.0, 4.0, 8.0, 0.0]).unwrap();
        assert_eq!(out, vec![6.0, 1.0, 8.0, 0.0]);
        assert!(t.apply(2, &[0.0, 1.0]).is_err());
    }
}
