//! The base level's lookups, kept O(1) at high valences and in large faces:
//! per-vertex edge lists in insertion order ([`Slots`]); the edge joining two
//! vertices ([`EdgeFinder`]) — the first one made, as OpenSubdiv's
//! `Vtr::Level::findEdge` returns it by scanning the vertex's edges; and a
//! vertex's first corner in a face ([`FirstCorners`]).
//!
//! A scan is what OpenSubdiv does and is the fastest for ordinary valences
//! and faces, but it makes a vertex with `n` edges, or a face with `n`
//! corners, cost `n²` (a fan of 50,000 triangles, or one 65,535-gon, took
//! seconds); past [`SCAN_LIMIT`] edges at a vertex, or corners in a face, a
//! map answers the same question in O(1).

use std::collections::HashMap;
use std::collections::hash_map::Entry;

pub(super) const NONE: u32 = u32::MAX;

/// Edges a vertex, or corners a face, may have before they are mapped
/// instead of scanned.
pub(super) const SCAN_LIMIT: u32 = 32;

/// Per-element lists in insertion order, each in its own slice of one flat
/// array whose room per element is known up front (the edges of a vertex
/// are at most twice its corners): appending and scanning touch one
/// contiguous run.
pub(super) struct Slots {
    /// Start of each element's room (`elements + 1` values).
    start: Vec<u32>,
    /// How many values each element has.
    pub(super) count: Vec<u32>,
    values: Vec<u32>,
}

impl Slots {
    /// Lists with room `room(i)` for element `i`.
    pub(super) fn new(elements: usize, room: impl Fn(usize) -> u32) -> Self {
        let mut start = crate::alloc::vec_or_unwind(0u32, elements + 1);
        for i in 0..elements {
            start[i + 1] = start[i] + room(i);
        }
        Slots {
            values: crate::alloc::vec_or_unwind(NONE, start[elements] as usize),
            start,
            count: crate::alloc::vec_or_unwind(0, elements),
        }
    }

    /// Appends `value` to the list of `element` (which has room for it).
    #[inline(always)]
    pub(super) fn append(&mut self, element: usize, value: u32) {
        let c = &mut self.count[element];
        self.values[(self.start[element] + *c) as usize] = value;
        *c += 1;
    }

    /// The list of `element`.
    #[inline(always)]
    pub(super) fn get(&self, element: usize) -> &[u32] {
        let s = self.start[element] as usize;
        &self.values[s..s + self.count[element] as usize]
    }

    /// The lists as a relation.
    pub(super) fn into_relation(self) -> super::Relation {
        let n = self.count.len();
        let mut offsets = crate::alloc::with_capacity(n + 1);
        offsets.push(0u32);
        let mut at = 0;
        for &c in &self.count {
            at += c;
            offsets.push(at);
        }
        let mut members = crate::alloc::with_capacity(at as usize);
        for e in 0..n {
            members.extend_from_slice(self.get(e));
        }
        super::Relation::from_parts(offsets.into(), members.into()).compact()
    }
}

/// The edge joining two vertices, among the edges made so far: the first one
/// made (the first match in the vertex's [`Slots`] list), found by a scan
/// for vertices with at most [`SCAN_LIMIT`] edges and by a map beyond.
#[derive(Default)]
pub(super) struct EdgeFinder {
    /// For each vertex past the limit: the other end of each of its edges →
    /// the first edge made between them.
    maps: HashMap<u32, HashMap<u32, u32>>,
}

impl EdgeFinder {
    /// The first edge made between `v0` and `v1` (`v0 != v1`), if any.
    #[inline(always)]
    pub(super) fn find(
        &self,
        vertex_edges: &Slots,
        edge_vertices: &[[u32; 2]],
        v0: u32,
        v1: u32,
    ) -> Option<u32> {
        if vertex_edges.count[v0 as usize] > SCAN_LIMIT {
            return self.find_mapped(v0, v1);
        }
        vertex_edges.get(v0 as usize).iter().copied().find(|&e| {
            let ev = edge_vertices[e as usize];
            ev[0] == v1 || ev[1] == v1
        })
    }

    /// [`find`](Self::find) at a vertex past the limit (which has a map).
    #[cold]
    #[inline(never)]
    fn find_mapped(&self, v0: u32, v1: u32) -> Option<u32> {
        self.maps.get(&v0).and_then(|map| map.get(&v1).copied())
    }

    /// Records edge `e`, just appended to both its ends' lists.
    #[inline(always)]
    pub(super) fn added(&mut self, vertex_edges: &Slots, edge_vertices: &[[u32; 2]], e: u32) {
        let [a, b] = edge_vertices[e as usize];
        if vertex_edges.count[a as usize] > SCAN_LIMIT {
            self.note(vertex_edges, edge_vertices, a, b, e);
        }
        if b != a && vertex_edges.count[b as usize] > SCAN_LIMIT {
            self.note(vertex_edges, edge_vertices, b, a, e);
        }
    }

    /// Records edge `e` from `v` to `other` at a vertex past the limit,
    /// mapping the vertex's edges when it has just passed it.
    #[cold]
    #[inline(never)]
    fn note(
        &mut self,
        vertex_edges: &Slots,
        edge_vertices: &[[u32; 2]],
        v: u32,
        other: u32,
        e: u32,
    ) {
        if let Some(map) = self.maps.get_mut(&v) {
            reserve_one(map);
            map.entry(other).or_insert(e);
            return;
        }
        // The vertex passes the limit: map its edges so far, first ones kept.
        let mut map = HashMap::new();
        if map.try_reserve(2 * SCAN_LIMIT as usize).is_err() {
            crate::alloc::fail(2 * SCAN_LIMIT as usize * 12);
        }
        for &f in vertex_edges.get(v as usize) {
            let [x, y] = edge_vertices[f as usize];
            reserve_one(&mut map);
            if let Entry::Vacant(slot) = map.entry(if x == v { y } else { x }) {
                slot.insert(f);
            }
        }
        reserve_one(&mut self.maps);
        self.maps.insert(v, map);
    }
}

/// Room for one more entry, or an unwinding allocation failure.
fn reserve_one<K: Eq + std::hash::Hash, V>(map: &mut HashMap<K, V>) {
    if map.try_reserve(1).is_err() {
        crate::alloc::fail(map.len().saturating_mul(2 * std::mem::size_of::<(K, V)>()));
    }
}

/// Where a vertex first occurs in a face (the face's size when it does not):
/// a scan of faces of at most [`SCAN_LIMIT`] corners, a map (made on first
/// use) for larger ones. At most [`FirstCorners::KEPT`] maps are kept (the
/// callers walk the vertices in order, so a large face's vertices come
/// together): memory stays bounded on meshes of many large faces.
#[derive(Default)]
pub(super) struct FirstCorners {
    maps: HashMap<u32, HashMap<u32, u32>>,
}

impl FirstCorners {
    /// How many faces' maps are kept at most.
    const KEPT: usize = 16;

    /// The first corner of `f` (with vertices `verts`) at vertex `v`.
    #[inline(always)]
    pub(super) fn get(&mut self, f: u32, verts: &[u32], v: u32) -> usize {
        if verts.len() <= SCAN_LIMIT as usize {
            return verts.iter().position(|&x| x == v).unwrap_or(verts.len());
        }
        self.get_mapped(f, verts, v)
    }

    /// [`get`](Self::get) in a face past the limit.
    #[cold]
    #[inline(never)]
    fn get_mapped(&mut self, f: u32, verts: &[u32], v: u32) -> usize {
        if self.maps.len() >= Self::KEPT && !self.maps.contains_key(&f) {
            self.maps.clear();
        }
        let map = match self.maps.entry(f) {
            Entry::Occupied(slot) => slot.into_mut(),
            Entry::Vacant(slot) => {
                let mut map = HashMap::new();
                if map.try_reserve(verts.len()).is_err() {
                    crate::alloc::fail(verts.len().saturating_mul(16));
                }
                for (i, &x) in verts.iter().enumerate() {
                    map.entry(x).or_insert(i as u32);
                }
                slot.insert(map)
            }
        };
        map.get(&v).map_or(verts.len(), |&i| i as usize)
    }
}
