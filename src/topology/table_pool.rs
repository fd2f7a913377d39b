//! The memory of dropped [`Table`](super::Table)s, kept for the next
//! tables of about its size: the maps of large tables (2 MiB and more) and
//! the vectors of tables from 64 KiB up.
//!
//! Freed to the C allocator, a block of that size goes back to the system
//! too often (glibc unmaps blocks above its map threshold and trims the top
//! of its heap), so the next table of the next refinement takes a page fault
//! for every 4 KiB page of it, and the kernel zeroes each page first. On an
//! adaptive refinement of the production-like benchmark mesh those faults
//! were a third of the time (docs/PERFORMANCE.md). Kept here, the memory
//! stays the process's, already faulted in. Blocks under 64 KiB come from
//! the allocator's own free lists, which reuse them without faults.
//!
//! Kept maps never raise the process's peak: the pool counts the bytes of
//! the maps in use and keeps the highest that in-use and kept bytes have
//! reached together. A fresh map that would carry them past it first
//! unmaps kept maps, the oldest first, until the total stays at that mark
//! or at what is in use, whichever is higher. So the maps' share of the
//! peak is what the tables in use needed at once; and a refinement done
//! again (the next frame, the bench's repetitions) stays under its first
//! run's mark and keeps every map it can reuse. (Without this, a level
//! dropped before a larger one is built stayed resident under it: 180 MB
//! of the 1000×1000 grid's peak at level 2.)

use memmap2::MmapMut;
use std::any::{Any, TypeId};
use std::sync::{Mutex, MutexGuard};

/// At most this many bytes of maps are kept. Enough for the tables of an
/// adaptive refinement to isolation 6 of the benchmark's meshes (a
/// one-thread driver's peak: 0.37-0.63 GB): with 256 MiB, its deeper
/// levels took fresh maps in every refinement, the kernel zeroing their
/// pages (10-18% of the samples on the mixed torus).
/// Kept maps never raise the peak (above); what a process holds after its
/// tables are dropped is at most its own peak of tables, and
/// [`release_buffer_pool`](crate::release_buffer_pool) hands it back.
const MAP_POOL_BYTES: usize = 1 << 30;

/// At most this many bytes of vectors are kept.
const VEC_POOL_BYTES: usize = 128 << 20;

/// Vectors of fewer bytes are not kept.
const SMALLEST_VEC: usize = 64 << 10;

/// Something kept: a map, or a table's vector.
pub(super) trait Kept {
    /// The bytes it holds.
    fn bytes(&self) -> usize;
}

impl Kept for MmapMut {
    fn bytes(&self) -> usize {
        self.len()
    }
}

/// A dropped table's vector, of any element type.
pub(super) struct KeptVec {
    ty: TypeId,
    bytes: usize,
    vec: Box<dyn Any + Send>,
}

impl Kept for KeptVec {
    fn bytes(&self) -> usize {
        self.bytes
    }
}

/// Kept memory, oldest first, at most `cap` bytes of it.
pub(super) struct Pool<K> {
    kept: Vec<K>,
    bytes: usize,
    cap: usize,
}

impl<K: Kept> Pool<K> {
    pub(super) const fn new(cap: usize) -> Self {
        Pool {
            kept: Vec::new(),
            bytes: 0,
            cap,
        }
    }

    /// The smallest kept item `fits` accepts of at least `bytes` and at
    /// most twice that (a larger one would leave most of itself idle).
    pub(super) fn take(&mut self, bytes: usize, fits: impl Fn(&K) -> bool) -> Option<K> {
        let (i, _) = self
            .kept
            .iter()
            .enumerate()
            .filter(|(_, k)| k.bytes() >= bytes && k.bytes() / 2 <= bytes && fits(k))
            .min_by_key(|(_, k)| k.bytes())?;
        let k = self.kept.remove(i);
        self.bytes -= k.bytes();
        Some(k)
    }

    /// Keeps `k` and returns the oldest items that no longer fit under
    /// the cap (`k` itself when it is larger than the cap).
    #[must_use]
    pub(super) fn give(&mut self, k: K) -> Vec<K> {
        if k.bytes() > self.cap {
            return vec![k];
        }
        self.bytes += k.bytes();
        self.kept.push(k);
        let mut evicted = Vec::new();
        while self.bytes > self.cap {
            let old = self.kept.remove(0);
            self.bytes -= old.bytes();
            evicted.push(old);
        }
        evicted
    }

    /// The oldest kept items holding at least `bytes` between them (all
    /// of them when they hold less), taken out of the pool.
    #[must_use]
    pub(super) fn evict(&mut self, bytes: usize) -> Vec<K> {
        let mut freed = 0;
        let count = self
            .kept
            .iter()
            .take_while(|k| {
                let more = freed < bytes;
                freed += k.bytes();
                more
            })
            .count();
        let evicted: Vec<K> = self.kept.drain(..count).collect();
        self.bytes -= evicted.iter().map(Kept::bytes).sum::<usize>();
        evicted
    }

    /// Every kept item, and their total bytes; the pool is left empty.
    pub(super) fn drain(&mut self) -> (Vec<K>, usize) {
        let bytes = std::mem::take(&mut self.bytes);
        (std::mem::take(&mut self.kept), bytes)
    }

    #[cfg(test)]
    pub(super) fn bytes(&self) -> usize {
        self.bytes
    }
}

/// The kept maps, and the bytes of maps in use (in tables) beside them.
pub(super) struct Maps {
    kept: Pool<MmapMut>,
    /// Bytes of the maps tables hold.
    in_use: usize,
    /// The most bytes of maps in use and kept together so far.
    high: usize,
}

impl Maps {
    pub(super) const fn new(cap: usize) -> Self {
        Maps {
            kept: Pool::new(cap),
            in_use: 0,
            high: 0,
        }
    }

    /// A kept map of at least `bytes` (at most twice that), now in use.
    pub(super) fn take(&mut self, bytes: usize) -> Option<MmapMut> {
        let map = self.kept.take(bytes, |_| true)?;
        self.in_use += map.len();
        Some(map)
    }

    /// Counts a fresh map of `bytes` in use, and returns the kept maps to
    /// unmap so that in-use and kept bytes stay at the mark they reached
    /// before or at what is now in use, whichever is higher.
    #[must_use]
    pub(super) fn fresh(&mut self, bytes: usize) -> Vec<MmapMut> {
        self.in_use += bytes;
        let limit = self.high.max(self.in_use);
        let over = (self.in_use + self.kept.bytes).saturating_sub(limit);
        let evicted = self.kept.evict(over);
        self.high = limit;
        evicted
    }

    /// Takes back a map a table no longer uses; returns the kept maps that
    /// no longer fit under the cap.
    #[must_use]
    pub(super) fn give(&mut self, map: MmapMut) -> Vec<MmapMut> {
        self.in_use = self.in_use.saturating_sub(map.len());
        self.kept.give(map)
    }

    /// Counts a map unmapped by its table as no longer in use.
    pub(super) fn forget(&mut self, bytes: usize) {
        self.in_use = self.in_use.saturating_sub(bytes);
    }

    #[cfg(test)]
    pub(super) fn bytes(&self) -> (usize, usize) {
        (self.in_use, self.kept.bytes)
    }
}

static MAPS: Mutex<Maps> = Mutex::new(Maps::new(MAP_POOL_BYTES));
static VECS: Mutex<Pool<KeptVec>> = Mutex::new(Pool::new(VEC_POOL_BYTES));

fn lock<P>(pool: &'static Mutex<P>) -> MutexGuard<'static, P> {
    // A pool is consistent between statements: a panic elsewhere while it
    // was held leaves nothing half done.
    pool.lock().unwrap_or_else(|e| e.into_inner())
}

/// A kept map of at least `bytes` (at most twice that).
pub(super) fn take_map(bytes: usize) -> Option<MmapMut> {
    lock(&MAPS).take(bytes)
}

/// A fresh anonymous map of `bytes` (zeros), kept maps unmapped first as
/// far as the peak needs (the module's notes); `None` when the system
/// refuses it.
pub(super) fn fresh_map(bytes: usize) -> Option<MmapMut> {
    let evicted = lock(&MAPS).fresh(bytes);
    // Unmapped outside the lock, before the new map is faulted in.
    drop(evicted);
    // A map the system refuses is asked for again once the kept maps are
    // handed back (under an address-space limit they can be what is in
    // the way). A map that would leave too little for the small
    // allocations after it is refused too
    // ([`crate::alloc::headroom_after`]).
    let map_anon = || memmap2::MmapOptions::new().len(bytes).map_anon().ok();
    let map = map_anon()
        .or_else(|| (release() > 0).then(map_anon).flatten())
        .filter(|_| crate::alloc::headroom_after(bytes));
    if map.is_none() {
        lock(&MAPS).forget(bytes);
    }
    map
}

/// Keeps a dropped table's map. Under an address-space or data-size limit
/// (`ulimit -v`, `ulimit -d`) nothing is kept: kept memory counts against
/// the limit, and the small allocations after a large one, which Rust
/// cannot make fallible, found no room (an abort in about 1 run in 100 at
/// one limit of the CLI's memory-limit test).
pub(super) fn give_map(map: MmapMut) {
    if crate::limits::address_space_limited() {
        unmap(map);
        return;
    }
    let evicted = lock(&MAPS).give(map);
    // Unmapped outside the lock.
    drop(evicted);
}

/// Unmaps a table's map now instead of keeping it.
pub(super) fn unmap(map: MmapMut) {
    lock(&MAPS).forget(map.len());
    drop(map);
}

/// A kept vector of `T` with room for `len` values (at most twice that), of
/// whatever length and contents its last table left.
pub(super) fn take_vec<T: Send + 'static>(len: usize) -> Option<Vec<T>> {
    let bytes = len.checked_mul(size_of::<T>())?;
    if bytes < SMALLEST_VEC {
        return None;
    }
    let ty = TypeId::of::<T>();
    let kept = lock(&VECS).take(bytes, |k| k.ty == ty)?;
    kept.vec.downcast::<Vec<T>>().ok().map(|v| *v)
}

/// An empty vector with room for at least `capacity` values to be pushed:
/// a dropped table's vector when one of about that size is kept (its
/// memory already faulted in), else a new one (unwinding as
/// [`crate::alloc::with_capacity`] does when memory runs out).
pub(super) fn vec_with_capacity<T: Send + 'static>(capacity: usize) -> Vec<T> {
    match take_vec::<T>(capacity) {
        Some(mut vec) => {
            vec.clear();
            vec
        }
        None => crate::alloc::with_capacity(capacity),
    }
}

/// Keeps a dropped table's vector (from 64 KiB of room up; nothing under an
/// address-space limit, as [`give_map`]).
pub(super) fn give_vec<T: Send + 'static>(vec: Vec<T>) {
    let bytes = vec.capacity().saturating_mul(size_of::<T>());
    if bytes < SMALLEST_VEC || crate::limits::address_space_limited() {
        return;
    }
    let kept = KeptVec {
        ty: TypeId::of::<T>(),
        bytes,
        vec: Box::new(vec),
    };
    let evicted = lock(&VECS).give(kept);
    // Freed outside the lock.
    drop(evicted);
}

/// Hands every kept map and vector back; returns their bytes.
pub(super) fn release() -> usize {
    let (maps, map_bytes) = lock(&MAPS).kept.drain();
    let (vecs, vec_bytes) = lock(&VECS).drain();
    drop((maps, vecs));
    map_bytes + vec_bytes
}
