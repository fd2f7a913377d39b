//! A [`Table`] filled by appending, for outputs whose length is known only
//! once they are built (stencil tables: a patch table's local points, the
//! stencil factory's rows level by level): the values
//! live in a table from the start — a huge-page map from 2 MiB, recycled
//! memory where the pool has some — so the finished output is that table,
//! not a vector copied into one or left on 4 KiB pages.
//!
//! A vector of tens of megabytes is a map of its own under glibc, faulted
//! in page by page every time it is built and unmapped when dropped; a
//! table takes one fault per 2 MiB and goes back to the pool.

use super::Table;
use bytemuck::Pod;

/// Values appended to a table with room for more ([`Growing::finish`]
/// gives the table of exactly those values).
pub(crate) struct Growing<T: Pod + Send> {
    /// The values so far, then room: only the first `len` are written.
    table: Table<T>,
    len: usize,
}

impl<T: Pod + Send> Growing<T> {
    /// Room for `capacity` values, an estimate: the map's pages that are
    /// never written cost nothing, and when that much memory cannot be had
    /// it starts with none and grows as values come. Only growth past what
    /// the values need unwinds with an
    /// [`AllocFailure`](crate::alloc::AllocFailure), as tables do.
    pub(crate) fn with_capacity(capacity: usize) -> Self {
        let table = crate::alloc::or_none(|| Table::for_overwrite(capacity))
            .unwrap_or_else(|| Table::for_overwrite(0));
        Growing { table, len: 0 }
    }

    /// The values of `table`, with room for no more until they grow.
    pub(crate) fn from_table(table: Table<T>) -> Self {
        let len = table.len();
        Growing { table, len }
    }

    /// Room for `total` values in all (nothing when there is already), an
    /// estimate as [`Growing::with_capacity`]'s: when it cannot be had the
    /// values stay where they are and grow as they come.
    pub(crate) fn reserve_total(&mut self, total: usize) {
        if self.table.len() < total {
            let _ = crate::alloc::or_none(|| self.move_to(total));
        }
    }

    /// Values appended so far.
    #[inline]
    pub(crate) fn len(&self) -> usize {
        self.len
    }

    /// The values appended so far.
    #[inline]
    pub(crate) fn as_slice(&self) -> &[T] {
        &self.table[..self.len]
    }

    /// Appends `value`.
    #[inline(always)]
    pub(crate) fn push(&mut self, value: T) {
        self.spare(1)[0] = value;
        self.len += 1;
    }

    /// Appends a copy of `values`.
    #[inline(always)]
    pub(crate) fn extend_from_slice(&mut self, values: &[T]) {
        self.spare(values.len()).copy_from_slice(values);
        self.len += values.len();
    }

    /// Appends the values of `values`, each mapped by `f`, in one pass over
    /// a slice of the right length.
    #[inline(always)]
    pub(crate) fn extend_mapped<S: Copy>(&mut self, values: &[S], f: impl Fn(S) -> T) {
        for (slot, &v) in self.spare(values.len()).iter_mut().zip(values) {
            *slot = f(v);
        }
        self.len += values.len();
    }

    /// The next `n` slots, room made for them first.
    #[inline(always)]
    fn spare(&mut self, n: usize) -> &mut [T] {
        if self.table.len() - self.len < n {
            self.grow(n);
        }
        &mut self.table[self.len..self.len + n]
    }

    /// Moves the values into a table twice as long (or long enough for
    /// `n` more); when twice as long cannot be had, into one just long
    /// enough, which unwinds if that cannot be had either.
    #[cold]
    #[inline(never)]
    fn grow(&mut self, n: usize) {
        let needed = self.len + n;
        let doubled = (2 * self.table.len()).max(needed).max(64);
        if crate::alloc::or_none(|| self.move_to(doubled)).is_none() {
            self.move_to(needed);
        }
    }

    /// Moves the values into a table of `capacity` values.
    fn move_to(&mut self, capacity: usize) {
        let mut bigger = Table::for_overwrite(capacity);
        bigger[..self.len].copy_from_slice(&self.table[..self.len]);
        self.table = bigger;
    }

    /// The table of the values appended.
    pub(crate) fn finish(mut self) -> Table<T> {
        self.table.truncate(self.len);
        self.table
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Past its estimate and across the size where tables become maps,
    /// the values come out as pushed.
    #[test]
    fn grows_past_its_estimate_and_keeps_every_value() {
        let mut g = Growing::<u32>::with_capacity(3);
        let n = 1_500_000u32;
        for i in 0..n {
            if i % 3 == 0 {
                g.extend_mapped(&[i], |x| x);
            } else {
                g.push(i);
            }
        }
        assert_eq!(g.len(), n as usize);
        assert_eq!(g.as_slice()[..4], [0, 1, 2, 3]);
        let t = g.finish();
        assert!(t.is_mapped() || std::env::var("SUBDIV_HUGE_PAGES").as_deref() == Ok("0"));
        assert!(t.iter().copied().eq(0..n));
        assert!(Growing::<f64>::with_capacity(0).finish().is_empty());
    }

    /// An estimate no machine can hold is only an estimate: the values
    /// still come, in memory grown as they do.
    #[test]
    fn an_estimate_too_large_to_allocate_is_not_an_error() {
        let mut g = Growing::<u64>::with_capacity(usize::MAX / 16);
        g.push(1);
        g.reserve_total(usize::MAX / 16);
        g.extend_from_slice(&[2, 3]);
        assert_eq!(&*g.finish(), &[1, 2, 3]);
    }
}
