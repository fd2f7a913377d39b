//! The base level's lookups, kept O(1) at high valences and in large faces:
//! per-vertex edge lists in insertion order ([`Chains`]); the edge joining two
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

/// Appends to per-element lists kept as singly linked chains in flat arrays,
/// preserving insertion order (needed to find edges as OpenSubdiv does).
pub(super) struct Chains {
    head: Vec<u32>,
    tail: Vec<u32>,
    /// How many values each element has.
    pub(super) count: Vec<u32>,
    next: Vec<u32>,
    value: Vec<u32>,
}

impl Chains {
    #[inline]
    pub(super) fn new(elements: usize, capacity: usize) -> Self {
        Chains {
            head: crate::alloc::vec_or_unwind(NONE, elements),
            tail: crate::alloc::vec_or_unwind(NONE, elements),
            count: crate::alloc::vec_or_unwind(0, elements),
            next: crate::alloc::with_capacity(capacity),
            value: crate::alloc::with_capacity(capacity),
        }
    }

    #[inline]
    pub(super) fn push_element(&mut self) {
        self.head.push(NONE);
        self.tail.push(NONE);
        self.count.push(0);
    }

    #[inline]
    pub(super) fn append(&mut self, element: usize, value: u32) {
        let node = self.value.len() as u32;
        self.value.push(value);
        self.next.push(NONE);
        match self.tail[element] {
            NONE => self.head[element] = node,
            t => self.next[t as usize] = node,
        }
        self.tail[element] = node;
        self.count[element] += 1;
    }

    #[inline]
    pub(super) fn iter(&self, element: usize) -> impl Iterator<Item = u32> + '_ {
        let mut node = self.head[element];
        std::iter::from_fn(move || {
            if node == NONE {
                return None;
            }
            let v = self.value[node as usize];
            node = self.next[node as usize];
            Some(v)
        })
    }

    #[inline]
    pub(super) fn last(&self, element: usize) -> Option<u32> {
        match self.tail[element] {
            NONE => None,
            t => Some(self.value[t as usize]),
        }
    }

    /// The lists as a relation.
    pub(super) fn into_relation(self) -> super::Relation {
        let mut offsets = crate::alloc::with_capacity(self.head.len() + 1);
        let mut members = crate::alloc::with_capacity(self.value.len());
        offsets.push(0);
        for e in 0..self.head.len() {
            members.extend(self.iter(e));
            offsets.push(members.len() as u32);
        }
        super::Relation::from_parts(offsets.into(), members.into()).compact()
    }
}

/// The edge joining two vertices, among the edges made so far: the first one
/// made (the first match in the vertex's [`Chains`] list), found by a scan
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
        vertex_edges: &Chains,
        edge_vertices: &[[u32; 2]],
        v0: u32,
        v1: u32,
    ) -> Option<u32> {
        if vertex_edges.count[v0 as usize] > SCAN_LIMIT {
            return self.find_mapped(v0, v1);
        }
        vertex_edges.iter(v0 as usize).find(|&e| {
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
    pub(super) fn added(&mut self, vertex_edges: &Chains, edge_vertices: &[[u32; 2]], e: u32) {
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
        vertex_edges: &Chains,
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
        for f in vertex_edges.iter(v as usize) {
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
