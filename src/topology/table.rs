//! Flat tables of plain values; the large ones live in memory advised for
//! transparent huge pages and are recycled when dropped.
//!
//! Refining a mesh writes hundreds of megabytes of fresh tables at deep
//! levels. With 4 KiB pages, the first touch of each page is a kernel page
//! fault. A [`Table`] of 2 MiB or more is an anonymous memory map advised
//! with `MADV_HUGEPAGE` (through `memmap2`), so the kernel fills it with
//! 2 MiB pages: one fault where there were 512. Where the advice is not
//! available the map still works with ordinary pages. A dropped map goes to
//! a pool (256 MiB at most) that serves the next table of its size, so a
//! program that refines again — the next frame, the next mesh — writes into
//! memory already faulted in ([`release_table_pool`] hands it back).
//! Smaller tables are ordinary `Vec`s, and from 64 KiB up a dropped one is
//! kept too (128 MiB at most), for the next table of its type and about its
//! size (`table_pool.rs`). (OpenSubdiv keeps its tables in `std::vector`s:
//! this has no counterpart there.)

use super::table_pool;
use bytemuck::Pod;
use std::fmt;
use std::ops::{Deref, DerefMut};

/// Tables of at least this many bytes are memory maps advised for huge
/// pages, unless `SUBDIV_HUGE_PAGES=0`.
///
/// Left to the C allocator, large blocks are fresh memory too often: glibc
/// serves blocks above its map threshold (128 KiB to 32 MiB, raised as
/// blocks are freed) with maps of their own, unmapped when freed, and a
/// worker thread's arena that needs room for a block of tens of megabytes
/// takes a new 64 MiB heap and deletes it again when the block is freed —
/// on two threads, 7,500-14,000 page faults per level-4 refinement of the
/// benchmark's tori (docs/PERFORMANCE.md). The pool keeps such memory ours.
const MAP_BYTES: usize = 2 << 20;

/// The size of a transparent huge page on x86-64 and most aarch64 kernels.
const HUGE_PAGE: usize = 2 << 20;

/// The smallest table that is a huge-page map: `MAP_BYTES`, or none with the
/// environment variable `SUBDIV_HUGE_PAGES=0` (read once).
fn map_threshold() -> usize {
    static THRESHOLD: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
    *THRESHOLD.get_or_init(|| {
        match std::env::var_os("SUBDIV_HUGE_PAGES")
            .as_deref()
            .and_then(|v| v.to_str())
        {
            Some("0") => usize::MAX,
            _ => MAP_BYTES,
        }
    })
}

/// A fixed-length table of plain values (`u32`, `[u32; 2]`, `f32`, tags…)
/// that dereferences to a slice.
///
/// Refining a mesh writes hundreds of megabytes of fresh tables at deep
/// levels; with 4 KiB pages the first touch of every page is a kernel page
/// fault. A table of 2 MiB or more is an anonymous memory map advised with
/// `MADV_HUGEPAGE` (transparent huge pages: one fault where there were 512),
/// and when dropped its map is kept for the next table of its size
/// ([`release_buffer_pool`](crate::release_buffer_pool)); smaller tables are
/// ordinary `Vec`s, kept likewise from 64 KiB up. The environment variable
/// `SUBDIV_HUGE_PAGES=0` makes every table a `Vec` (docs/PERFORMANCE.md has
/// the measurements).
pub struct Table<T: Pod + Send> {
    repr: Repr<T>,
}

enum Repr<T> {
    Vec(Vec<T>),
    Map { map: memmap2::MmapMut, len: usize },
}

impl<T: Pod + Send> Table<T> {
    /// An empty table.
    pub const fn new() -> Self {
        Table {
            repr: Repr::Vec(Vec::new()),
        }
    }

    /// `len` zeroed values (zero bits: `0`, `0.0`, default tags).
    pub fn zeroed(len: usize) -> Self {
        Self::zeroed_in(len, map_threshold())
    }

    /// [`Table::zeroed`], in a huge-page map when at least `threshold`
    /// bytes long.
    fn zeroed_in(len: usize, threshold: usize) -> Self {
        match Self::mapped(len, threshold) {
            Some((mut t, fresh)) => {
                if !fresh {
                    t.fill(T::zeroed());
                }
                t
            }
            None => Self::heap(len, Some(T::zeroed())),
        }
    }

    /// A vector table of `len` values: a kept vector of a dropped table
    /// when the pool has one (already faulted in), else a new one. With
    /// `fill` every value is set to it; without, a kept vector's values are
    /// what its last table left.
    fn heap(len: usize, fill: Option<T>) -> Self {
        let vec = match table_pool::take_vec::<T>(len) {
            Some(mut v) => {
                match fill {
                    Some(x) => {
                        v.clear();
                        v.resize(len, x);
                    }
                    // Values past the kept length written, no others.
                    None if v.len() < len => v.resize(len, T::zeroed()),
                    None => v.truncate(len),
                }
                v
            }
            None => crate::alloc::vec_or_unwind(fill.unwrap_or_else(T::zeroed), len),
        };
        Table {
            repr: Repr::Vec(vec),
        }
    }

    /// `len` values for the caller to overwrite, every one of them: their
    /// contents are unspecified (zeros, or what a dropped table left in the
    /// memory it handed back). Nothing is cleared first, so a recycled map
    /// costs neither page faults nor a pass over its memory.
    pub(crate) fn for_overwrite(len: usize) -> Self {
        #[allow(unused_mut)]
        let mut t = match Self::mapped(len, map_threshold()) {
            Some((t, _)) => t,
            None => Self::heap(len, None),
        };
        // Debug builds (the test suite) poison the values, all bits set (NaN
        // for floats, out of range for indices), so that a value the caller
        // fails to write shows in every test, not only on recycled memory.
        #[cfg(debug_assertions)]
        bytemuck::cast_slice_mut::<T, u8>(&mut t).fill(0xff);
        t
    }

    /// A map for `len` values when they take at least `threshold` bytes:
    /// one the pool kept (`false`: its contents are stale) or a fresh one
    /// (`true`: zeros). `None` below the threshold or when the system
    /// refuses a map.
    fn mapped(len: usize, threshold: usize) -> Option<(Self, bool)> {
        let bytes = len.checked_mul(size_of::<T>())?;
        if bytes < threshold || bytes == 0 {
            return None;
        }
        // A whole number of huge pages: the kernel then aligns the map
        // on a huge-page boundary, so every part of it can use them.
        let mapped = bytes.div_ceil(HUGE_PAGE) * HUGE_PAGE;
        if let Some(map) = table_pool::take_map(mapped) {
            return Some((
                Table {
                    repr: Repr::Map { map, len },
                },
                false,
            ));
        }
        let map = table_pool::fresh_map(mapped)?;
        // Only advice: without transparent huge pages the map keeps
        // ordinary pages.
        #[cfg(target_os = "linux")]
        let _ = map.advise(memmap2::Advice::HugePage);
        Some((
            Table {
                repr: Repr::Map { map, len },
            },
            true,
        ))
    }

    /// `len` copies of `value`.
    pub fn filled(value: T, len: usize) -> Self {
        let zero = bytemuck::bytes_of(&value).iter().all(|&b| b == 0);
        match Self::mapped(len, map_threshold()) {
            Some((mut t, fresh)) => {
                // A fresh map is zeros already.
                if !(fresh && zero) {
                    t.fill(value);
                }
                t
            }
            None => Self::heap(len, Some(value)),
        }
    }

    /// A table holding a copy of `values`.
    pub fn from_slice(values: &[T]) -> Self {
        let mut t = Self::for_overwrite(values.len());
        t.copy_from_slice(values);
        t
    }

    /// The values as a slice.
    #[inline]
    pub fn as_slice(&self) -> &[T] {
        match &self.repr {
            Repr::Vec(v) => v,
            Repr::Map { map, len } => bytemuck::cast_slice(&map[..*len * size_of::<T>()]),
        }
    }

    /// The values as a mutable slice.
    #[inline]
    pub fn as_mut_slice(&mut self) -> &mut [T] {
        match &mut self.repr {
            Repr::Vec(v) => v,
            Repr::Map { map, len } => bytemuck::cast_slice_mut(&mut map[..*len * size_of::<T>()]),
        }
    }

    /// Whether the table lives in a memory map (2 MiB or more, unless
    /// `SUBDIV_HUGE_PAGES=0`).
    pub fn is_mapped(&self) -> bool {
        matches!(self.repr, Repr::Map { .. })
    }

    /// Shortens the table to its first `len` values (nothing when it is
    /// no longer). A map keeps its memory (the pool takes it back whole).
    pub(crate) fn truncate(&mut self, len: usize) {
        match &mut self.repr {
            Repr::Vec(v) => v.truncate(len),
            Repr::Map { len: l, .. } => *l = (*l).min(len),
        }
    }

    /// The values as a vector: the table's own vector, or a copy of a map
    /// (which goes back to the pool).
    pub fn into_vec(mut self) -> Vec<T> {
        match std::mem::replace(&mut self.repr, Repr::Vec(Vec::new())) {
            Repr::Vec(v) => v,
            Repr::Map { map, len } => {
                let v = bytemuck::cast_slice(&map[..len * size_of::<T>()]).to_vec();
                table_pool::give_map(map);
                v
            }
        }
    }

    /// Drops the table and hands its memory back to the system at once (a
    /// map is unmapped, not kept by the pool): for a buffer no table of the
    /// same run is likely to reuse, such as the text of an input file.
    pub(crate) fn free(mut self) {
        // The map is unmapped here; `Drop` then finds a vector.
        match std::mem::replace(&mut self.repr, Repr::Vec(Vec::new())) {
            Repr::Map { map, .. } => table_pool::unmap(map),
            Repr::Vec(vec) => drop(vec),
        }
    }
}

impl<T: Pod + Send> Drop for Table<T> {
    /// A map or a vector (from 64 KiB up) goes back to the pool for the
    /// next table of its size.
    fn drop(&mut self) {
        match std::mem::replace(&mut self.repr, Repr::Vec(Vec::new())) {
            Repr::Map { map, .. } => table_pool::give_map(map),
            Repr::Vec(vec) => table_pool::give_vec(vec),
        }
    }
}

/// Releases the memory of dropped tables that is kept for reuse
/// (transparent huge-page maps of 2 MiB and more, vectors from 64 KiB up),
/// and returns how many bytes that was.
///
/// Dropping a large [`Table`] keeps its map, up to 256 MiB in all, and a
/// smaller one its vector, up to 128 MiB, so that the next refinement of a
/// similar mesh (the next frame, the next mesh of a batch, the next level)
/// reuses memory already faulted in instead of taking a kernel page fault
/// for every page anew. A program that refines once and goes on to
/// other work can hand that memory back to the system with this call
/// (public as [`crate::release_buffer_pool`]).
pub fn release_table_pool() -> usize {
    table_pool::release()
}

impl<T: Pod + Send> Default for Table<T> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Pod + Send> Deref for Table<T> {
    type Target = [T];
    #[inline]
    fn deref(&self) -> &[T] {
        self.as_slice()
    }
}

impl<T: Pod + Send> DerefMut for Table<T> {
    #[inline]
    fn deref_mut(&mut self) -> &mut [T] {
        self.as_mut_slice()
    }
}

impl<T: Pod + Send> Clone for Table<T> {
    fn clone(&self) -> Self {
        match &self.repr {
            Repr::Vec(v) => Table {
                repr: Repr::Vec(v.clone()),
            },
            Repr::Map { .. } => Self::from_slice(self),
        }
    }
}

impl<T: Pod + Send + PartialEq> PartialEq for Table<T> {
    fn eq(&self, other: &Self) -> bool {
        self.as_slice() == other.as_slice()
    }
}

impl<T: Pod + Send + Eq> Eq for Table<T> {}

impl<T: Pod + Send + PartialEq> PartialEq<[T]> for Table<T> {
    fn eq(&self, other: &[T]) -> bool {
        self.as_slice() == other
    }
}

impl<T: Pod + Send + PartialEq> PartialEq<Vec<T>> for Table<T> {
    fn eq(&self, other: &Vec<T>) -> bool {
        self.as_slice() == other.as_slice()
    }
}

impl<T: Pod + Send + PartialEq> PartialEq<Table<T>> for Vec<T> {
    fn eq(&self, other: &Table<T>) -> bool {
        self.as_slice() == other.as_slice()
    }
}

impl<T: Pod + Send + fmt::Debug> fmt::Debug for Table<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

impl<T: Pod + Send> From<Vec<T>> for Table<T> {
    /// Keeps the vector as it is (no copy, ordinary pages).
    fn from(v: Vec<T>) -> Self {
        Table { repr: Repr::Vec(v) }
    }
}

impl<T: Pod + Send> FromIterator<T> for Table<T> {
    fn from_iter<I: IntoIterator<Item = T>>(iter: I) -> Self {
        Vec::from_iter(iter).into()
    }
}

impl<'a, T: Pod + Send> IntoIterator for &'a Table<T> {
    type Item = &'a T;
    type IntoIter = std::slice::Iter<'a, T>;
    fn into_iter(self) -> Self::IntoIter {
        self.as_slice().iter()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_and_large_tables_behave_alike() {
        const BIG: usize = 32 << 20;
        for threshold in [MAP_BYTES, BIG, usize::MAX] {
            for len in [0, 3, MAP_BYTES / 4 + 5, BIG / 4 + 5] {
                let mut t: Table<u32> = Table::zeroed_in(len, threshold);
                assert!(t.iter().all(|&x| x == 0));
                t.fill(9);
                assert_eq!(t.len(), len);
                assert_eq!(t.is_mapped(), len > 0 && len * 4 >= threshold);
                assert!(t.iter().all(|&x| x == 9));
                if len > 0 {
                    t[len - 1] = 1;
                    assert_eq!(t[len - 1], 1);
                }
                // A vector's copy is a vector; a map's is laid out by the
                // process's own threshold.
                let c = t.clone();
                assert_eq!(c, t);
                assert_eq!(c.is_mapped(), t.is_mapped() && len * 4 >= map_threshold());
            }
            let pairs: Table<[u32; 2]> = Table::zeroed_in(BIG / 8, threshold);
            assert_eq!(pairs.is_mapped(), BIG >= threshold);
            assert!(pairs.iter().all(|p| *p == [0, 0]));
        }
        let f: Table<f32> = Table::filled(0.5, 10);
        assert!(f.iter().all(|&x| x == 0.5));
        let v: Table<u16> = (0..5u16).collect();
        assert_eq!(&v[..], &[0, 1, 2, 3, 4]);
    }

    /// Whatever memory a zeroed table gets — fresh, or a dropped table's
    /// from the pool — it reads zeros; a table for overwriting has its full
    /// length, poisoned in debug builds.
    #[test]
    fn recycled_tables_are_cleared_when_zeroed() {
        for len in [MAP_BYTES / 4, 3 * MAP_BYTES / 4 + 7] {
            let mut t: Table<u32> = Table::zeroed(len);
            t.fill(9);
            drop(t);
            let z: Table<u32> = Table::zeroed(len);
            assert_eq!(z.len(), len);
            assert!(z.iter().all(|&x| x == 0));
            let mut z = z;
            z.fill(9);
            drop(z);
            let f: Table<u32> = Table::filled(0, len);
            assert!(f.len() == len && f.iter().all(|&x| x == 0));
            drop(f);
            let f: Table<u32> = Table::filled(5, len);
            assert!(f.len() == len && f.iter().all(|&x| x == 5));
            let copy = Table::from_slice(&f);
            assert_eq!(copy, f);
            drop((f, copy));
            let w: Table<f32> = Table::for_overwrite(len);
            assert_eq!(w.len(), len);
            if cfg!(debug_assertions) {
                assert!(w.iter().all(|x| x.is_nan()));
            }
        }
    }

    /// A dropped vector table's memory serves the next table of its type
    /// and about its size, zeroed or left as it was as asked.
    #[test]
    fn dropped_vector_tables_are_reused() {
        // A type of this test's own: no other test takes its vectors.
        #[derive(Clone, Copy, PartialEq, Debug, bytemuck::Pod, bytemuck::Zeroable)]
        #[repr(C)]
        struct Only([u32; 2]);
        // 160 KB: a vector (under 2 MiB), kept when dropped (64 KiB up).
        let len = 20_000;
        let t = Table::filled(Only([7, 7]), len);
        assert!(!t.is_mapped());
        let memory = t.as_ptr();
        drop(t);
        // At least half the kept room: the kept vector, zeroed.
        let z = Table::<Only>::zeroed(len / 2 + 1);
        assert_eq!(z.as_ptr(), memory);
        assert!(z.len() == len / 2 + 1 && z.iter().all(|x| *x == Only([0, 0])));
        drop(z);
        let w = Table::<Only>::for_overwrite(len);
        assert_eq!((w.as_ptr(), w.len()), (memory, len));
        drop(w);
        // Less than half: a vector of its own.
        let small = Table::<Only>::for_overwrite(len / 2 - 1);
        assert_ne!(small.as_ptr(), memory);
        assert!(release_table_pool() >= len * 8);
    }

    fn map(bytes: usize) -> memmap2::MmapMut {
        memmap2::MmapOptions::new().len(bytes).map_anon().unwrap()
    }

    #[test]
    fn pool_takes_the_best_fit_and_evicts_the_oldest() {
        const M: usize = HUGE_PAGE;
        let mut p = table_pool::Pool::new(10 * M);
        assert!(p.give(map(4 * M)).is_empty());
        assert!(p.give(map(2 * M)).is_empty());
        assert!(p.give(map(3 * M)).is_empty());
        assert_eq!(p.bytes(), 9 * M);
        // Nothing large enough.
        assert!(p.take(5 * M, |_| true).is_none());
        // The smallest that fits, not the first.
        assert_eq!(p.take(2 * M, |_| true).map(|m| m.len()), Some(2 * M));
        // No map more than twice the request: 4 MiB is too big for 1 MiB.
        assert!(p.take(M, |_| true).is_none());
        assert_eq!(p.bytes(), 7 * M);
        // Over the cap: the oldest (4 MiB) goes, then a map larger than the
        // cap is never kept.
        let evicted = p.give(map(5 * M));
        assert_eq!(
            evicted.iter().map(|m| m.len()).collect::<Vec<_>>(),
            vec![4 * M]
        );
        assert_eq!(p.bytes(), 8 * M);
        assert_eq!(p.give(map(11 * M)).len(), 1);
        let (maps, bytes) = p.drain();
        assert_eq!((maps.len(), bytes, p.bytes()), (2, 8 * M, 0));
    }

    /// Kept maps never carry the maps' total past the most that was in use
    /// at once: a fresh map beyond that mark unmaps kept ones first, the
    /// oldest first; one under it keeps them all.
    #[test]
    fn kept_maps_never_raise_the_peak() {
        const M: usize = HUGE_PAGE;
        let mut p = table_pool::Maps::new(100 * M);
        // Three tables in use (9 MiB), then two of them dropped: kept.
        assert!(p.fresh(4 * M).is_empty());
        assert!(p.fresh(3 * M).is_empty());
        assert!(p.fresh(2 * M).is_empty());
        assert!(p.give(map(4 * M)).is_empty());
        assert!(p.give(map(3 * M)).is_empty());
        assert_eq!(p.bytes(), (2 * M, 7 * M));
        // 9 MiB reached before: a fresh 5 MiB (14 in all) unmaps the
        // oldest kept maps until the total is back at 9: the 4 MiB one
        // (13 in all) and then the 3 MiB one.
        let evicted = p.fresh(5 * M);
        assert_eq!(
            evicted.iter().map(|m| m.len()).collect::<Vec<_>>(),
            vec![4 * M, 3 * M]
        );
        assert_eq!(p.bytes(), (7 * M, 0));
        // The same again, now from kept maps: nothing fresh, nothing
        // unmapped, and a fresh map under the mark keeps what is kept.
        assert!(p.give(map(5 * M)).is_empty());
        assert_eq!(p.take(4 * M).map(|m| m.len()), Some(5 * M));
        assert!(p.give(map(2 * M)).is_empty());
        assert!(p.fresh(M).is_empty());
        assert_eq!(p.bytes(), (6 * M, 2 * M));
        // A table unmapped by its owner is no longer in use.
        p.forget(6 * M);
        assert_eq!(p.bytes(), (0, 2 * M));
    }
}
