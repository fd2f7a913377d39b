//! Large allocations that fail with an error instead of aborting.
//!
//! Rust aborts the process when an ordinary allocation fails. The engine's
//! large buffers (topology tables, primvar and limit buffers, refinement
//! results) are allocated fallibly instead: a refinement that runs out of
//! memory — under `ulimit -v`, a cgroup limit or a full machine — returns
//! [`Error::OutOfMemory`] naming the size, and leaves the process running.
//!
//! Topology tables are built deep inside the refiner, which does not thread
//! errors through every table it fills; a table that cannot get its memory
//! unwinds with an [`AllocFailure`] (without the panic hook: nothing is
//! printed), and [`guard`] at the public entry points turns it back into the
//! error. Every other payload keeps unwinding.

use crate::error::{Error, Result};
use std::panic::{AssertUnwindSafe, catch_unwind, resume_unwind};

/// The payload a failed large allocation unwinds with.
pub(crate) struct AllocFailure {
    /// The bytes that could not be allocated.
    pub(crate) bytes: usize,
}

/// Unwinds with an [`AllocFailure`] of `bytes`, to be caught by [`guard`].
pub(crate) fn fail(bytes: usize) -> ! {
    resume_unwind(Box::new(AllocFailure { bytes }))
}

/// Runs `f`, turning an [`AllocFailure`] raised inside it into
/// [`Error::OutOfMemory`] (with `level`, the level being refined or read, when
/// there is one).
pub(crate) fn guard<R>(level: Option<u32>, f: impl FnOnce() -> Result<R>) -> Result<R> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(result) => result,
        Err(payload) => match payload.downcast::<AllocFailure>() {
            Ok(failure) => Err(Error::OutOfMemory {
                bytes: failure.bytes,
                level,
            }),
            Err(other) => resume_unwind(other),
        },
    }
}

/// Runs `f`, giving `None` when an [`AllocFailure`] is raised inside it:
/// for memory asked for on an estimate, where doing without is an option.
/// Every other payload keeps unwinding.
pub(crate) fn or_none<R>(f: impl FnOnce() -> R) -> Option<R> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(r) => Some(r),
        Err(payload) => match payload.downcast::<AllocFailure>() {
            Ok(_) => None,
            Err(other) => resume_unwind(other),
        },
    }
}

/// `len` copies of `value` in a vector allocated fallibly.
pub(crate) fn try_vec<T: Clone>(value: T, len: usize) -> Result<Vec<T>> {
    let mut v = Vec::new();
    reserve(&mut v, len)?;
    v.resize(len, value);
    Ok(v)
}

/// `len` zeros in a vector allocated fallibly and zeroed by the allocator
/// (`calloc`): a large one is fresh pages, zero already, that the caller's
/// writes fault in — no pass writing zeros over it first, as
/// [`try_vec`]'s fill makes. For outputs every element of which is written
/// anyway.
pub(crate) fn try_zeroed<T: bytemuck::Zeroable>(len: usize) -> Result<Vec<T>> {
    let bytes = len.saturating_mul(size_of::<T>());
    let error = || Error::OutOfMemory { bytes, level: None };
    let v = bytemuck::allocation::try_zeroed_vec(len).map_err(|()| error())?;
    if !headroom_after(bytes) {
        return Err(error());
    }
    Ok(v)
}

/// Reserves room for `additional` more elements, fallibly: an error when
/// the room cannot be had, or when a large reservation would leave too
/// little for the small allocations after it ([`headroom_after`]).
pub(crate) fn reserve<T>(v: &mut Vec<T>, additional: usize) -> Result<()> {
    let bytes = additional.saturating_mul(size_of::<T>());
    let error = || Error::OutOfMemory { bytes, level: None };
    let had = v.capacity();
    v.try_reserve_exact(additional).map_err(|_| error())?;
    // Only memory newly allocated is checked.
    if v.capacity() != had && !headroom_after(bytes) {
        // The room given back: the caller fails, and others may go on.
        v.shrink_to_fit();
        return Err(error());
    }
    Ok(())
}

/// Address space kept free after a large allocation, for the small ones
/// (masks, buffers, the thread pool's jobs) that Rust cannot make
/// fallible: they abort the process when they fail.
const HEADROOM: usize = 16 << 20;

/// Allocations from this size check [`HEADROOM`] after them.
const CHECKED: usize = 1 << 20;

/// Whether, after an allocation of `bytes` that succeeded, [`HEADROOM`]
/// bytes can still be allocated — an anonymous map asked of the system
/// and unmapped at once, which touches no page (asked of the C allocator
/// instead, the probe raised glibc's map threshold, so that freed tables
/// below it stayed resident in its heap: 14 MB more at the peak of the
/// production-like mesh's level 1 on two threads) — the tables kept for
/// reuse released first if need be. Under an address-space limit (`ulimit -v`) a large
/// table that takes nearly all that is left would otherwise succeed, and
/// the next small allocation abort; with this check the large one fails
/// instead, with a typed error ([`Error::OutOfMemory`]). Small allocations
/// (under [`CHECKED`]) are not checked.
pub(crate) fn headroom_after(bytes: usize) -> bool {
    let probe = || memmap2::MmapOptions::new().len(HEADROOM).map_anon().is_ok();
    bytes < CHECKED || probe() || (crate::topology::release_table_pool() > 0 && probe())
}

/// A vector of `len` copies of `value`, or an unwinding [`AllocFailure`]:
/// for code under a [`guard`] that cannot return an error.
pub(crate) fn vec_or_unwind<T: Clone>(value: T, len: usize) -> Vec<T> {
    match try_vec(value, len) {
        Ok(v) => v,
        Err(_) => fail(len.saturating_mul(size_of::<T>())),
    }
}

/// Collects `iter`, expected to yield about `len` items, into a vector whose
/// room for `len` is allocated fallibly ([`AllocFailure`] on failure): for
/// the large per-level copies made under a [`guard`].
pub(crate) fn collect_n<T>(len: usize, iter: impl IntoIterator<Item = T>) -> Vec<T> {
    let mut v = Vec::new();
    if reserve(&mut v, len).is_err() {
        fail(len.saturating_mul(size_of::<T>()));
    }
    v.extend(iter);
    v
}

/// An empty vector with room for `capacity` elements, allocated fallibly
/// ([`AllocFailure`] on failure).
pub(crate) fn with_capacity<T>(capacity: usize) -> Vec<T> {
    collect_n(capacity, std::iter::empty())
}

/// A copy of `values` allocated fallibly ([`collect_n`]).
pub(crate) fn copied<T: Copy>(values: &[T]) -> Vec<T> {
    collect_n(values.len(), values.iter().copied())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failures_become_errors_and_other_panics_go_on() {
        let oom = guard(Some(3), || -> Result<()> { fail(1 << 40) }).unwrap_err();
        assert!(matches!(oom, Error::OutOfMemory { bytes, level: Some(3) } if bytes == 1 << 40));
        assert_eq!(
            oom.to_string(),
            "out of memory refining level 3: 1099511627776 bytes could not be allocated"
        );
        // An allocation no machine has: an error, not an abort.
        let huge = try_vec(0u64, usize::MAX / 16).unwrap_err();
        assert!(
            matches!(huge, Error::OutOfMemory { level: None, .. }),
            "{huge}"
        );
        // The same through the allocator's zeroed allocation.
        let huge = try_zeroed::<u64>(usize::MAX / 16).unwrap_err();
        assert!(
            matches!(huge, Error::OutOfMemory { level: None, .. }),
            "{huge}"
        );
        // Zeros, large (fresh pages) and small.
        for len in [0, 5, 3 << 20] {
            let zeros = try_zeroed::<f64>(len).unwrap();
            assert_eq!(zeros.len(), len);
            assert!(zeros.iter().all(|&x| x.to_bits() == 0));
        }
        let caught = catch_unwind(|| guard(None, || -> Result<()> { panic!("not ours") }));
        assert!(caught.is_err());
        assert_eq!(guard(None, || Ok(7)).unwrap(), 7);
        assert!(or_none(|| -> u8 { fail(1 << 40) }).is_none());
        assert_eq!(or_none(|| 7), Some(7));
        assert!(catch_unwind(|| or_none(|| panic!("not ours"))).is_err());
    }
}
