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
//! Smaller tables are ordinary `Vec`s. (OpenSubdiv keeps its tables in
//! `std::vector`s: this has no counterpart there.)

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
/// ([`release_buffer_pool`](crate::release_buffer_pool)); smaller tables are ordinary `Vec`s. The
/// environment variable `SUBDIV_HUGE_PAGES=0` makes every table a `Vec`
/// (docs/PERFORMANCE.md has the measurements).
pub struct Table<T: Pod> {
    repr: Repr<T>,
}

enum Repr<T> {
    Vec(Vec<T>),
    Map { map: memmap2::MmapMut, len: usize },
}

impl<T: Pod> Table<T> {
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
            None => Table {
                repr: Repr::Vec(crate::alloc::vec_or_unwind(T::zeroed(), len)),
            },
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
            None => Table {
                repr: Repr::Vec(crate::alloc::vec_or_unwind(T::zeroed(), len)),
            },
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
        if let Some(map) = pool::take(mapped) {
            return Some((
                Table {
                    repr: Repr::Map { map, len },
                },
                false,
            ));
        }
        let map = memmap2::MmapOptions::new().len(mapped).map_anon().ok()?;
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
            None => Table {
                repr: Repr::Vec(crate::alloc::vec_or_unwind(value, len)),
            },
        }
    }

    /// A table holding a copy of `values`.
    pub fn from_slice(values: &[T]) -> Self {
        let mut t = Self::for_overwrite(values.len());
        t.copy_from_slice(values);
        t
    }

    /// Shortens the table to its first `len` values (nothing when it holds
    /// no more); a map keeps its memory.
    pub(crate) fn truncate(&mut self, len: usize) {
        match &mut self.repr {
            Repr::Vec(v) => v.truncate(len),
            Repr::Map { len: l, .. } => *l = (*l).min(len),
        }
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

    /// Drops the table and hands its memory back to the system at once (a
    /// map is unmapped, not kept by the pool): for a buffer no table of the
    /// same run is likely to reuse, such as the text of an input file.
    pub(crate) fn free(mut self) {
        // The map is dropped here (unmapped); `Drop` then finds a vector.
        drop(std::mem::replace(&mut self.repr, Repr::Vec(Vec::new())));
    }
}

impl<T: Pod> Drop for Table<T> {
    /// A map goes back to the pool for the next table of its size.
    fn drop(&mut self) {
        if let Repr::Map { map, .. } = std::mem::replace(&mut self.repr, Repr::Vec(Vec::new())) {
            pool::give(map);
        }
    }
}

/// Releases the memory of dropped tables that is kept for reuse
/// (transparent huge-page maps of 2 MiB and more), and returns how many bytes
/// that was.
///
/// Dropping a large [`Table`] keeps its map, up to 256 MiB in all, so that
/// the next refinement of a similar mesh (the next frame, the next mesh of a
/// batch) reuses memory already faulted in instead of taking a kernel page
/// fault for every page anew. A program that refines once and goes on to
/// other work can hand that memory back to the system with this call
/// (public as [`crate::release_buffer_pool`]).
pub fn release_table_pool() -> usize {
    pool::release()
}

/// The maps of dropped tables, kept for the next tables of their size.
mod pool {
    use memmap2::MmapMut;
    use std::sync::{Mutex, MutexGuard};

    /// At most this many bytes of maps are kept.
    const POOL_BYTES: usize = 256 << 20;

    /// Kept maps, oldest first.
    pub(super) struct Pool {
        maps: Vec<MmapMut>,
        bytes: usize,
        cap: usize,
    }

    impl Pool {
        pub(super) const fn new(cap: usize) -> Self {
            Pool {
                maps: Vec::new(),
                bytes: 0,
                cap,
            }
        }

        /// The smallest kept map of at least `bytes` and at most twice
        /// that (a larger one would leave most of itself idle).
        pub(super) fn take(&mut self, bytes: usize) -> Option<MmapMut> {
            let (i, _) = self
                .maps
                .iter()
                .enumerate()
                .filter(|(_, m)| m.len() >= bytes && m.len() / 2 <= bytes)
                .min_by_key(|(_, m)| m.len())?;
            let map = self.maps.remove(i);
            self.bytes -= map.len();
            Some(map)
        }

        /// Keeps `map` and returns the oldest maps that no longer fit under
        /// the cap (all of `map` itself when it is larger than the cap).
        #[must_use]
        pub(super) fn give(&mut self, map: MmapMut) -> Vec<MmapMut> {
            if map.len() > self.cap {
                return vec![map];
            }
            self.bytes += map.len();
            self.maps.push(map);
            let mut evicted = Vec::new();
            while self.bytes > self.cap {
                let old = self.maps.remove(0);
                self.bytes -= old.len();
                evicted.push(old);
            }
            evicted
        }

        /// Every kept map, and their total length; the pool is left empty.
        pub(super) fn drain(&mut self) -> (Vec<MmapMut>, usize) {
            let bytes = std::mem::take(&mut self.bytes);
            (std::mem::take(&mut self.maps), bytes)
        }

        #[cfg(test)]
        pub(super) fn bytes(&self) -> usize {
            self.bytes
        }
    }

    static POOL: Mutex<Pool> = Mutex::new(Pool::new(POOL_BYTES));

    fn lock() -> MutexGuard<'static, Pool> {
        // The pool is consistent between statements: a panic elsewhere while
        // it was held leaves nothing half done.
        POOL.lock().unwrap_or_else(|e| e.into_inner())
    }

    pub(super) fn take(bytes: usize) -> Option<MmapMut> {
        lock().take(bytes)
    }

    pub(super) fn give(map: MmapMut) {
        let evicted = lock().give(map);
        // Unmapped outside the lock.
        drop(evicted);
    }

    pub(super) fn release() -> usize {
        let (maps, bytes) = lock().drain();
        drop(maps);
        bytes
    }
}

impl<T: Pod> Default for Table<T> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Pod> Deref for Table<T> {
    type Target = [T];
    #[inline]
    fn deref(&self) -> &[T] {
        self.as_slice()
    }
}

impl<T: Pod> DerefMut for Table<T> {
    #[inline]
    fn deref_mut(&mut self) -> &mut [T] {
        self.as_mut_slice()
    }
}

impl<T: Pod> Clone for Table<T> {
    fn clone(&self) -> Self {
        match &self.repr {
            Repr::Vec(v) => Table {
                repr: Repr::Vec(v.clone()),
            },
            Repr::Map { .. } => Self::from_slice(self),
        }
    }
}

impl<T: Pod + PartialEq> PartialEq for Table<T> {
    fn eq(&self, other: &Self) -> bool {
        self.as_slice() == other.as_slice()
    }
}

impl<T: Pod + Eq> Eq for Table<T> {}

impl<T: Pod + PartialEq> PartialEq<[T]> for Table<T> {
    fn eq(&self, other: &[T]) -> bool {
        self.as_slice() == other
    }
}

impl<T: Pod + PartialEq> PartialEq<Vec<T>> for Table<T> {
    fn eq(&self, other: &Vec<T>) -> bool {
        self.as_slice() == other.as_slice()
    }
}

impl<T: Pod + PartialEq> PartialEq<Table<T>> for Vec<T> {
    fn eq(&self, other: &Table<T>) -> bool {
        self.as_slice() == other.as_slice()
    }
}

impl<T: Pod + fmt::Debug> fmt::Debug for Table<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

impl<T: Pod> From<Vec<T>> for Table<T> {
    /// Keeps the vector as it is (no copy, ordinary pages).
    fn from(v: Vec<T>) -> Self {
        Table { repr: Repr::Vec(v) }
    }
}

impl<T: Pod> FromIterator<T> for Table<T> {
    fn from_iter<I: IntoIterator<Item = T>>(iter: I) -> Self {
        Vec::from_iter(iter).into()
    }
}

impl<'a, T: Pod> IntoIterator for &'a Table<T> {
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

    fn map(bytes: usize) -> memmap2::MmapMut {
        memmap2::MmapOptions::new().len(bytes).map_anon().unwrap()
    }

    #[test]
    fn pool_takes_the_best_fit_and_evicts_the_oldest() {
        const M: usize = HUGE_PAGE;
        let mut p = pool::Pool::new(10 * M);
        assert!(p.give(map(4 * M)).is_empty());
        assert!(p.give(map(2 * M)).is_empty());
        assert!(p.give(map(3 * M)).is_empty());
        assert_eq!(p.bytes(), 9 * M);
        // Nothing large enough.
        assert!(p.take(5 * M).is_none());
        // The smallest that fits, not the first.
        assert_eq!(p.take(2 * M).map(|m| m.len()), Some(2 * M));
        // No map more than twice the request: 4 MiB is too big for 1 MiB.
        assert!(p.take(M).is_none());
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
}
