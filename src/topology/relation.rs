//! A compressed relation ([`Relation`]): the members of every element
//! concatenated, with their offsets stored or implicit — what OpenSubdiv's
//! `Vtr::Level` keeps as counts, offsets and indices per relation.

use super::Table;

/// Where the members of each element of a [`Relation`] start.
#[derive(Debug, Clone)]
pub enum Offsets {
    /// `len` elements of `size` members each: element `i` starts at
    /// `i * size`, and no table is stored (the faces of every refined
    /// Catmull-Clark or Loop level).
    Uniform {
        /// Number of elements.
        len: usize,
        /// Members per element.
        size: usize,
    },
    /// The start of every element, plus one final entry.
    Table(Table<u32>),
}

impl Default for Offsets {
    fn default() -> Self {
        Offsets::Uniform { len: 0, size: 0 }
    }
}

/// A compressed relation: the members of element `i` are
/// `members[start(i)..start(i + 1)]`.
#[derive(Debug, Clone, Default)]
pub struct Relation {
    /// Where each element starts.
    pub offsets: Offsets,
    /// The members, concatenated.
    pub members: Table<u32>,
}

impl PartialEq for Relation {
    fn eq(&self, other: &Self) -> bool {
        self.len() == other.len()
            && self.members == other.members
            && (0..=self.len()).all(|i| self.start(i) == other.start(i))
    }
}

impl Eq for Relation {}

/// A [`Relation`] read through its tables once: its offsets and members as
/// plain slices, for loops that look up many elements (each access to a
/// [`Table`] otherwise matches on its representation).
#[derive(Debug, Clone, Copy)]
pub(crate) struct RelationView<'a> {
    /// Every element's size, or where each starts (plus one final entry).
    starts: Starts<'a>,
    /// The members, concatenated.
    pub(crate) members: &'a [u32],
    /// Number of elements.
    len: usize,
}

/// Where the elements of a [`RelationView`] start.
#[derive(Debug, Clone, Copy)]
enum Starts<'a> {
    Uniform(usize),
    Table(&'a [u32]),
}

impl<'a> RelationView<'a> {
    /// Where the members of element `i` are in `members`.
    #[inline(always)]
    pub(crate) fn range(&self, i: usize) -> std::ops::Range<usize> {
        match self.starts {
            Starts::Uniform(size) => i * size..(i + 1) * size,
            Starts::Table(t) => t[i] as usize..t[i + 1] as usize,
        }
    }

    /// The members of element `i`.
    #[inline(always)]
    pub(crate) fn get(&self, i: usize) -> &'a [u32] {
        &self.members[self.range(i)]
    }

    /// Where element `i`'s members start in `members`.
    #[inline(always)]
    pub(crate) fn start(&self, i: usize) -> usize {
        match self.starts {
            Starts::Uniform(size) => i * size,
            Starts::Table(t) => t[i] as usize,
        }
    }

    /// Number of members of element `i`.
    #[inline(always)]
    pub(crate) fn count(&self, i: usize) -> usize {
        match self.starts {
            Starts::Uniform(size) => size,
            Starts::Table(t) => (t[i + 1] - t[i]) as usize,
        }
    }

    /// Number of elements.
    #[inline(always)]
    pub(crate) fn len(&self) -> usize {
        self.len
    }

    /// The element whose members hold position `member` of `members`.
    #[inline(always)]
    pub(crate) fn element_of(&self, member: usize) -> usize {
        match self.starts {
            Starts::Uniform(size) => member / size,
            Starts::Table(t) => t.partition_point(|&o| o as usize <= member) - 1,
        }
    }

    /// The members of element `i`, or `None` past the last element.
    #[inline(always)]
    pub(crate) fn try_get(&self, i: usize) -> Option<&'a [u32]> {
        match self.starts {
            Starts::Uniform(n) => self.members.get(n * i..n * i + n),
            Starts::Table(t) => self
                .members
                .get(*t.get(i)? as usize..*t.get(i + 1)? as usize),
        }
    }

    /// Where element `i`'s members start if it has `n` of them; `None`
    /// for another size (or, with stored offsets, past the last element).
    #[inline(always)]
    pub(crate) fn start_if_sized(&self, i: usize, n: usize) -> Option<usize> {
        match self.starts {
            Starts::Uniform(size) => (size == n).then_some(n * i),
            Starts::Table(t) => {
                let (s, e) = (*t.get(i)? as usize, *t.get(i + 1)? as usize);
                (e.checked_sub(s) == Some(n)).then_some(s)
            }
        }
    }
}

impl Relation {
    /// An empty relation over no elements.
    #[cfg(test)]
    pub fn new() -> Self {
        Relation::default()
    }

    /// The relation as slices ([`RelationView`]).
    #[inline(always)]
    pub(crate) fn view(&self) -> RelationView<'_> {
        RelationView {
            starts: match &self.offsets {
                Offsets::Uniform { size, .. } => Starts::Uniform(*size),
                Offsets::Table(t) => Starts::Table(t),
            },
            members: &self.members,
            len: self.len(),
        }
    }

    /// A relation from its offsets (`count + 1`) and members.
    pub fn from_parts(offsets: Table<u32>, members: Table<u32>) -> Self {
        Relation {
            offsets: Offsets::Table(offsets),
            members,
        }
    }

    /// A relation where every element has `size` members (zeroed), with
    /// implicit offsets.
    #[cfg(test)]
    pub fn uniform(count: usize, size: usize) -> Self {
        Relation {
            offsets: Offsets::Uniform { len: count, size },
            members: Table::zeroed(count * size),
        }
    }

    /// As [`Relation::uniform`], with members for the caller to write, every
    /// one ([`Table::for_overwrite`]: not cleared first).
    pub(crate) fn uniform_for_overwrite(count: usize, size: usize) -> Self {
        Relation {
            offsets: Offsets::Uniform { len: count, size },
            members: Table::for_overwrite(count * size),
        }
    }

    /// Number of elements.
    #[inline]
    pub fn len(&self) -> usize {
        match &self.offsets {
            Offsets::Uniform { len, .. } => *len,
            Offsets::Table(t) => t.len().saturating_sub(1),
        }
    }

    /// Whether there is no element.
    #[cfg(test)]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Where element `i`'s members start (`i == len()`: the end of the last).
    #[inline(always)]
    pub fn start(&self, i: usize) -> usize {
        match &self.offsets {
            Offsets::Uniform { size, .. } => i * size,
            Offsets::Table(t) => t[i] as usize,
        }
    }

    /// The range of element `i`'s members.
    #[inline(always)]
    pub fn range(&self, i: usize) -> std::ops::Range<usize> {
        match &self.offsets {
            Offsets::Uniform { size, .. } => i * size..(i + 1) * size,
            Offsets::Table(t) => t[i] as usize..t[i + 1] as usize,
        }
    }

    /// The members of element `i`.
    #[inline(always)]
    pub fn get(&self, i: usize) -> &[u32] {
        &self.members[self.range(i)]
    }

    /// Number of members of element `i`.
    #[inline(always)]
    pub fn count(&self, i: usize) -> usize {
        match &self.offsets {
            Offsets::Uniform { size, .. } => *size,
            Offsets::Table(t) => (t[i + 1] - t[i]) as usize,
        }
    }

    /// The member count of every element when it is the same for all and the
    /// offsets are implicit.
    #[inline]
    pub fn uniform_size(&self) -> Option<usize> {
        match self.offsets {
            Offsets::Uniform { size, .. } => Some(size),
            Offsets::Table(_) => None,
        }
    }

    /// The same relation with implicit offsets when every element has the
    /// same number of members.
    pub fn compact(self) -> Self {
        match &self.offsets {
            Offsets::Table(t) if t.len() > 1 => {
                let size = (t[1] - t[0]) as usize;
                // Size 0 stays a table: `element_of` divides by the size.
                if size > 0 && t[0] == 0 && t.windows(2).all(|w| (w[1] - w[0]) as usize == size) {
                    Relation {
                        offsets: Offsets::Uniform {
                            len: t.len() - 1,
                            size,
                        },
                        members: self.members,
                    }
                } else {
                    self
                }
            }
            _ => self,
        }
    }

    /// The element whose members include position `member` of `members`.
    pub fn element_of(&self, member: usize) -> usize {
        match &self.offsets {
            Offsets::Uniform { size, .. } => member / size,
            Offsets::Table(t) => t.partition_point(|&o| o as usize <= member) - 1,
        }
    }

    /// The offsets as a slice: borrowed when stored, built when implicit.
    pub fn offsets_slice(&self) -> std::borrow::Cow<'_, [u32]> {
        match &self.offsets {
            // Allocated fallibly (unwinding to `alloc::guard`): a level's
            // offsets are as large as its faces.
            Offsets::Uniform { len, size } => {
                crate::alloc::collect_n(*len + 1, (0..=*len).map(|i| (i * size) as u32)).into()
            }
            Offsets::Table(t) => std::borrow::Cow::Borrowed(&t[..]),
        }
    }

    /// The offsets as an owned vector, allocated fallibly (unwinding to
    /// `alloc::guard`).
    pub fn offsets_vec(&self) -> Vec<u32> {
        match self.offsets_slice() {
            std::borrow::Cow::Owned(v) => v,
            std::borrow::Cow::Borrowed(s) => crate::alloc::copied(s),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn implicit_offsets_read_like_a_table() {
        let members: Table<u32> = (0..12).collect::<Vec<u32>>().into();
        let stored = Relation::from_parts(vec![0, 4, 8, 12].into(), members.clone());
        let compact = stored.clone().compact();
        assert_eq!(compact.uniform_size(), Some(4));
        assert!(stored.uniform_size().is_none());
        assert_eq!(compact, stored);
        for r in [&stored, &compact] {
            assert_eq!(r.len(), 3);
            assert_eq!(r.get(1), &[4, 5, 6, 7]);
            assert_eq!(r.count(2), 4);
            assert_eq!((r.start(2), r.start(3)), (8, 12));
            assert_eq!(r.element_of(7), 1);
            assert_eq!(r.element_of(8), 2);
            assert_eq!(&*r.offsets_slice(), &[0, 4, 8, 12]);
        }
        // Mixed sizes keep their table; the two forms of different sizes differ.
        let mixed = Relation::from_parts(vec![0, 3, 7].into(), (0..7).collect::<Vec<u32>>().into());
        let mixed = mixed.compact();
        assert!(mixed.uniform_size().is_none());
        assert_eq!(mixed.element_of(3), 1);
        assert_ne!(Relation::uniform(2, 3), Relation::uniform(3, 2));
        assert_eq!(Relation::uniform(2, 3).members.len(), 6);
        assert!(Relation::new().is_empty());
        // Elements without members keep their table (no division by zero).
        let empty = Relation::from_parts(vec![0, 0, 0].into(), Table::new()).compact();
        assert!(empty.uniform_size().is_none());
        assert_eq!((empty.len(), empty.count(1)), (2, 0));
    }
}
