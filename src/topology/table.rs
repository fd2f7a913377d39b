//! Flat tables of plain values; the very large ones live in memory advised
//! for transparent huge pages.
//!
//! Refining a mesh writes hundreds of megabytes of fresh tables at deep
//! levels. With 4 KiB pages, the first touch of each page is a kernel page
//! fault. A [`Table`] of 32 MiB or more is an anonymous memory map
//! advised with `MADV_HUGEPAGE` (through `memmap2`), so the kernel fills it
//! with 2 MiB pages: one fault where there were 512. Smaller tables are
//! ordinary `Vec`s. Where the advice is not available the map still works
//! with ordinary pages.

use bytemuck::Pod;
use std::fmt;
use std::ops::{Deref, DerefMut};

/// Tables of at least this many bytes are memory maps advised for huge
/// pages, unless `SUBDIV_HUGE_PAGES` says otherwise.
///
/// 32 MiB is where the C allocator stops reusing its heap: glibc serves any
/// larger block with a fresh map of its own (its map threshold never rises
/// above 32 MiB on 64-bit), unmapped again when freed, so every refinement
/// faults such a table in anew whatever we do. The only choice left there is
/// the page size, and 2 MiB pages take 512 times fewer faults. A smaller
/// table stays a `Vec`: the heap hands back memory a previous refinement
/// already faulted in, which no fresh map can beat.
const MAP_BYTES: usize = 32 << 20;

/// With `SUBDIV_HUGE_PAGES=1`, tables from this size on are maps.
const MAP_BYTES_ALL: usize = 2 << 20;

/// The size of a transparent huge page on x86-64 and most aarch64 kernels.
const HUGE_PAGE: usize = 2 << 20;

/// The smallest table that is a huge-page map: `MAP_BYTES` by default,
/// 2 MiB with the environment variable `SUBDIV_HUGE_PAGES=1`, none with
/// `SUBDIV_HUGE_PAGES=0` (read once).
fn map_threshold() -> usize {
    static THRESHOLD: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
    *THRESHOLD.get_or_init(|| {
        match std::env::var_os("SUBDIV_HUGE_PAGES")
            .as_deref()
            .and_then(|v| v.to_str())
        {
            Some("1") => MAP_BYTES_ALL,
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
/// fault. A table of 32 MiB or more is an anonymous memory
/// map advised with `MADV_HUGEPAGE` (transparent huge pages: one fault where
/// there were 512); smaller tables are ordinary `Vec`s, which the allocator
/// can serve from memory already faulted in. The environment variable
/// `SUBDIV_HUGE_PAGES=1` maps every table from 2 MiB on, and
/// `SUBDIV_HUGE_PAGES=0` none (docs/PERFORMANCE.md has the measurements).
///
/// ```
/// use subdiv::topology::Table;
/// let mut t: Table<u32> = Table::zeroed(4);
/// t[2] = 7;
/// assert_eq!(&t[..], &[0, 0, 7, 0]);
/// let big: Table<u32> = Table::filled(1, 9 << 20); // 36 MiB: a huge-page map
/// assert_eq!(big.iter().map(|&x| x as u64).sum::<u64>(), 9 << 20);
/// ```
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
        let bytes = len.saturating_mul(size_of::<T>());
        if bytes >= threshold {
            // A whole number of huge pages: the kernel then aligns the map
            // on a huge-page boundary, so every part of it can use them.
            let mapped = bytes.div_ceil(HUGE_PAGE) * HUGE_PAGE;
            if let Ok(map) = memmap2::MmapOptions::new().len(mapped).map_anon() {
                // Only advice: without transparent huge pages the map keeps
                // ordinary pages.
                #[cfg(target_os = "linux")]
                let _ = map.advise(memmap2::Advice::HugePage);
                return Table {
                    repr: Repr::Map { map, len },
                };
            }
        }
        Table {
            repr: Repr::Vec(vec![T::zeroed(); len]),
        }
    }

    /// `len` copies of `value`.
    pub fn filled(value: T, len: usize) -> Self {
        let mut t = Self::zeroed(len);
        if bytemuck::bytes_of(&value).iter().any(|&b| b != 0) {
            t.fill(value);
        }
        t
    }

    /// A table holding a copy of `values`.
    pub fn from_slice(values: &[T]) -> Self {
        let mut t = Self::zeroed(values.len());
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

    /// Whether the table lives in a memory map (32 MiB or more; 2 MiB
    /// or more with `SUBDIV_HUGE_PAGES=1`).
    pub fn is_mapped(&self) -> bool {
        matches!(self.repr, Repr::Map { .. })
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
        for threshold in [MAP_BYTES_ALL, MAP_BYTES, usize::MAX] {
            for len in [0, 3, MAP_BYTES_ALL / 4 + 5, MAP_BYTES / 4 + 5] {
                let mut t: Table<u32> = Table::zeroed_in(len, threshold);
                assert!(t.iter().all(|&x| x == 0));
                t.fill(9);
                assert_eq!(t.len(), len);
                assert_eq!(t.is_mapped(), len * 4 >= threshold);
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
            let pairs: Table<[u32; 2]> = Table::zeroed_in(MAP_BYTES / 8, threshold);
            assert_eq!(pairs.is_mapped(), MAP_BYTES >= threshold);
            assert!(pairs.iter().all(|p| *p == [0, 0]));
        }
        let f: Table<f32> = Table::filled(0.5, 10);
        assert!(f.iter().all(|&x| x == 0.5));
        let v: Table<u16> = (0..5u16).collect();
        assert_eq!(&v[..], &[0, 1, 2, 3, 4]);
    }
}
