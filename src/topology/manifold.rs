//! The base level's relations for a mesh whose edges are all manifold —
//! the common case, built without an edge search.
//!
//! [`super::base`] builds the level as OpenSubdiv's factory does: faces
//! walked in order, each edge looked up among its first vertex's edges so
//! far, then every vertex's faces and edges reordered by a walk from face to
//! face through the edges' faces. On a mesh where every edge has one or two
//! faces, of opposite windings, no edge is degenerate and no vertex occurs
//! twice in a face, the same level follows from each vertex's corners alone:
//!
//! 1. the corners of every vertex, in corner order (a counting sort): its
//!    faces as OpenSubdiv lists them before ordering;
//! 2. at each vertex, the half-edge leaving it at one corner is the twin of
//!    the one arriving at it at the corner whose previous vertex is the
//!    first one's next vertex (a match among the vertex's few corners). The
//!    same matching orders the corners around the vertex (the walk), counts
//!    its edges and finds whatever makes the mesh fall outside this case;
//! 3. edges numbered in corner order, each at its first half-edge (one
//!    without a twin, or before its twin), with their faces and positions;
//! 4. each vertex's faces, edges and local indices written in walk order.
//!
//! When a vertex shows anything else (a non-manifold or degenerate edge, a
//! vertex twice in a face), [`manifold_topology`] declines (hands the
//! faces back) and the general build runs instead. Vertices whose faces cannot be ordered (two
//! fans meeting at a vertex, an isolated vertex) are handled here as there:
//! faces in corner order, edges in the order they were numbered, tagged
//! non-manifold by the caller.

use super::base::vertex_blocks;
use super::{Level, Relation, Table};
use std::ops::Range;

const NONE: u32 = u32::MAX;

/// Vertices with at most this many corners are matched by comparing every
/// pair of corners; more by sorting.
const PAIRWISE: usize = 32;

/// Where each corner (a position in the face-vertex list) sits: its face,
/// and the neighbouring corners within that face.
trait Corners: Sync {
    /// The face of corner `c`.
    fn face(&self, c: usize) -> usize;
    /// The first corner of face `f`.
    fn start(&self, f: usize) -> usize;
    /// One past the last corner of face `f`.
    fn end(&self, f: usize) -> usize;
    /// The corner after `c` in its face.
    #[inline(always)]
    fn next(&self, c: usize) -> usize {
        let f = self.face(c);
        if c + 1 == self.end(f) {
            self.start(f)
        } else {
            c + 1
        }
    }
    /// The corner before `c` in its face.
    #[inline(always)]
    fn prev(&self, c: usize) -> usize {
        let f = self.face(c);
        if c == self.start(f) {
            self.end(f) - 1
        } else {
            c - 1
        }
    }
}

/// Faces of `N` corners each.
struct Uniform<const N: usize>;

impl<const N: usize> Corners for Uniform<N> {
    #[inline(always)]
    fn face(&self, c: usize) -> usize {
        c / N
    }
    #[inline(always)]
    fn start(&self, f: usize) -> usize {
        f * N
    }
    #[inline(always)]
    fn end(&self, f: usize) -> usize {
        f * N + N
    }
    #[inline(always)]
    fn next(&self, c: usize) -> usize {
        if (c + 1).is_multiple_of(N) {
            c + 1 - N
        } else {
            c + 1
        }
    }
    #[inline(always)]
    fn prev(&self, c: usize) -> usize {
        if c.is_multiple_of(N) {
            c + N - 1
        } else {
            c - 1
        }
    }
}

/// Faces of any sizes: each corner's face in a table.
struct Mixed<'a> {
    face: &'a [u32],
    offsets: &'a [u32],
}

impl Corners for Mixed<'_> {
    #[inline(always)]
    fn face(&self, c: usize) -> usize {
        self.face[c] as usize
    }
    #[inline(always)]
    fn start(&self, f: usize) -> usize {
        self.offsets[f] as usize
    }
    #[inline(always)]
    fn end(&self, f: usize) -> usize {
        self.offsets[f + 1] as usize
    }
}

/// The base level's relations (everything but tags and sharpness) when
/// every edge of the mesh is manifold, or `face_vertices` back (nothing
/// built) when one is not; the vertices whose faces could not be ordered
/// come second, in increasing order, for the caller to tag.
/// `face_vertices` is the level's copy of the mesh's faces (validated), `nv`
/// its vertex count; the last pass writes the vertices' relations in blocks
/// of `block` vertices on the pool's threads
/// ([`vertex_blocks`](super::base::vertex_blocks)).
pub(super) fn manifold_topology(
    face_vertices: Relation,
    nv: usize,
    block: usize,
) -> Result<(Level, Vec<u32>), Relation> {
    let built = match face_vertices.uniform_size() {
        Some(4) => build(&face_vertices, nv, &Uniform::<4>, 4, block),
        Some(3) => build(&face_vertices, nv, &Uniform::<3>, 3, block),
        _ => {
            let offsets = face_vertices.offsets_slice();
            let mut face: Table<u32> = Table::for_overwrite(face_vertices.members.len());
            let mut largest = 0;
            for (f, w) in offsets.windows(2).enumerate() {
                face[w[0] as usize..w[1] as usize].fill(f as u32);
                largest = largest.max(w[1] - w[0]);
            }
            let corners = Mixed {
                face: &face,
                offsets: &offsets,
            };
            build(&face_vertices, nv, &corners, largest as usize, block)
        }
    };
    match built {
        Some((mut level, failed)) => {
            level.face_vertices = face_vertices;
            Ok((level, failed))
        }
        None => Err(face_vertices),
    }
}

/// [`manifold_topology`] with the faces addressed by `corners`; `largest` is
/// the size of the largest face.
fn build<C: Corners>(
    face_vertices: &Relation,
    nv: usize,
    corners: &C,
    largest: usize,
    block: usize,
) -> Option<(Level, Vec<u32>)> {
    let fv: &[u32] = &face_vertices.members;
    let nc = fv.len();
    let nf = face_vertices.len();

    // 1. Each vertex's corners in corner order: counted, summed, scattered.
    let mut vf_offsets: Table<u32> = Table::zeroed(nv + 1);
    {
        let counts: &mut [u32] = &mut vf_offsets;
        for &v in fv {
            counts[v as usize + 1] += 1;
        }
        let mut sum = 0;
        for x in counts.iter_mut() {
            sum += *x;
            *x = sum;
        }
    }
    let mut vertex_corners: Table<u32> = Table::for_overwrite(nc);
    {
        let mut fill = crate::alloc::copied(&vf_offsets[..nv]);
        let out: &mut [u32] = &mut vertex_corners;
        for (c, &v) in fv.iter().enumerate() {
            let slot = &mut fill[v as usize];
            out[*slot as usize] = c as u32;
            *slot += 1;
        }
    }

    // 2. Twins, walk order, edge counts per vertex.
    let mut twin: Table<u32> = Table::for_overwrite(nc);
    let mut ve_offsets: Table<u32> = Table::for_overwrite(nv + 1);
    let mut failed = Vec::new();
    let mut paired = 0usize;
    let mut max_valence = largest;
    {
        let offsets: &[u32] = &vf_offsets;
        let twin: &mut [u32] = &mut twin;
        let ve_offsets: &mut [u32] = &mut ve_offsets;
        let vertex_corners: &mut [u32] = &mut vertex_corners;
        let (mut room, mut sorted) = (Vec::new(), Vec::new());
        ve_offsets[0] = 0;
        let mut edges_so_far = 0u32;
        for v in 0..nv {
            let at = &mut vertex_corners[offsets[v] as usize..offsets[v + 1] as usize];
            let k = at.len();
            let entries = load(&mut room, v as u32, at, fv, corners)?;
            let boundary = pair(entries, &mut sorted)?;
            for i in 0..k {
                let t = entries[i].twin;
                twin[entries[i].c as usize] = if t == NONE {
                    NONE
                } else {
                    corners.prev(entries[t as usize].c as usize) as u32
                };
            }
            let edges = k + boundary;
            edges_so_far += edges as u32;
            ve_offsets[v + 1] = edges_so_far;
            paired += k - boundary;
            max_valence = max_valence.max(edges);
            if !walk(entries, boundary, at) {
                failed.push(v as u32);
            }
        }
    }

    // 3. Edges in corner order, with their faces.
    let ne = nc - paired / 2;
    let mut face_edges: Table<u32> = Table::for_overwrite(nc);
    let mut edge_vertices: Table<[u32; 2]> = Table::for_overwrite(ne);
    let mut ef_offsets: Table<u32> = Table::for_overwrite(ne + 1);
    let mut edge_faces: Table<u32> = Table::for_overwrite(nc);
    let mut edge_face_local: Table<u16> = Table::for_overwrite(nc);
    {
        let twin: &[u32] = &twin;
        let face_edges: &mut [u32] = &mut face_edges;
        let edge_vertices: &mut [[u32; 2]] = &mut edge_vertices;
        let ef_offsets: &mut [u32] = &mut ef_offsets;
        let edge_faces: &mut [u32] = &mut edge_faces;
        let edge_face_local: &mut [u16] = &mut edge_face_local;
        ef_offsets[0] = 0;
        let (mut e, mut at) = (0usize, 0usize);
        for f in 0..nf {
            let (start, end) = (corners.start(f), corners.end(f));
            for c in start..end {
                let t = twin[c];
                if t == NONE || t as usize > c {
                    face_edges[c] = e as u32;
                    let next = if c + 1 == end { start } else { c + 1 };
                    edge_vertices[e] = [fv[c], fv[next]];
                    edge_faces[at] = f as u32;
                    edge_face_local[at] = (c - start) as u16;
                    at += 1;
                    if t != NONE {
                        let g = corners.face(t as usize);
                        edge_faces[at] = g as u32;
                        edge_face_local[at] = (t as usize - corners.start(g)) as u16;
                        at += 1;
                    }
                    e += 1;
                    ef_offsets[e] = at as u32;
                } else {
                    face_edges[c] = face_edges[t as usize];
                }
            }
        }
        debug_assert_eq!((e, at), (ne, nc));
    }

    // 4. Each vertex's faces and edges in walk order, with local indices.
    let nve = ve_offsets[nv] as usize;
    let mut vf_members: Table<u32> = Table::for_overwrite(nc);
    let mut vf_local: Table<u16> = Table::for_overwrite(nc);
    let mut ve_members: Table<u32> = Table::for_overwrite(nve);
    let mut ve_local: Table<u16> = Table::for_overwrite(nve);
    {
        let relations = Relations {
            corners,
            face_edges: &face_edges,
            twin: &twin,
            edge_vertices: &edge_vertices,
        };
        let blocks = vertex_blocks(nv, rayon::current_num_threads(), block);
        let (mut vfm, mut vfl): (&mut [u32], &mut [u16]) = (&mut vf_members, &mut vf_local);
        let (mut vem, mut vel): (&mut [u32], &mut [u16]) = (&mut ve_members, &mut ve_local);
        let mut parts = Vec::with_capacity(blocks.len());
        for range in blocks {
            let faces = (vf_offsets[range.end] - vf_offsets[range.start]) as usize;
            let edges = (ve_offsets[range.end] - ve_offsets[range.start]) as usize;
            let (a, rest_a) = std::mem::take(&mut vfm).split_at_mut(faces);
            let (b, rest_b) = std::mem::take(&mut vfl).split_at_mut(faces);
            let (c, rest_c) = std::mem::take(&mut vem).split_at_mut(edges);
            let (d, rest_d) = std::mem::take(&mut vel).split_at_mut(edges);
            (vfm, vfl, vem, vel) = (rest_a, rest_b, rest_c, rest_d);
            let tables = VertexTables {
                faces: a,
                face_local: b,
                edges: c,
                edge_local: d,
            };
            parts.push((range, tables));
        }
        let write = |(range, tables): (Range<usize>, VertexTables)| {
            relations.write_block(
                range,
                (&vf_offsets, &ve_offsets),
                &vertex_corners,
                &failed,
                tables,
            )
        };
        if parts.len() == 1 {
            parts.into_iter().for_each(write);
        } else {
            use rayon::prelude::*;
            parts.into_par_iter().for_each(write);
        }
    }
    drop((vertex_corners, twin));

    let level = Level {
        depth: 0,
        vertex_count: nv,
        // The caller's, moved in by `manifold_topology`.
        face_vertices: Relation::default(),
        face_edges,
        edge_vertices,
        edge_faces: Relation::from_parts(ef_offsets, edge_faces).compact(),
        edge_face_local,
        vertex_faces: Relation::from_parts(vf_offsets, vf_members),
        vertex_face_local: vf_local,
        vertex_edges: Relation::from_parts(ve_offsets, ve_members).compact(),
        vertex_edge_local: ve_local,
        derived_relations: false,
        num_edges: ne,
        edge_sharpness: Table::new(),
        vertex_sharpness: Table::new(),
        edge_tags: Table::new(),
        vertex_tags: Table::new(),
        face_holes: Vec::new(),
        max_edge_faces: if paired > 0 { 2 } else { usize::from(ne > 0) },
        max_valence,
    };
    Some((level, failed))
}

/// One corner of a vertex and what is found from it: its corner `c`, the next vertex `n` and the previous vertex `p` in that face; the
/// corner (of the same vertex) whose arriving half-edge is the twin of this
/// one's leaving half-edge (`twin`), and its inverse (`succ`: the next
/// corner of the walk around the vertex).
#[derive(Clone, Copy, Default)]
struct Entry {
    c: u32,
    n: u32,
    p: u32,
    twin: u32,
    succ: u32,
}

/// Reads the corners `at` of vertex `v` into `room` (grown as needed,
/// reused from vertex to vertex), twins unknown; `None` at a degenerate
/// edge or when `v` occurs twice in a face.
#[inline(always)]
fn load<'a, C: Corners>(
    room: &'a mut Vec<Entry>,
    v: u32,
    at: &[u32],
    fv: &[u32],
    corners: &C,
) -> Option<&'a mut [Entry]> {
    if room.len() < at.len() {
        room.resize(at.len(), Entry::default());
    }
    let entries = &mut room[..at.len()];
    let mut last = NONE;
    for (entry, &c) in entries.iter_mut().zip(at) {
        let c = c as usize;
        // A vertex's corners in one face are next to each other in its list.
        let f = corners.face(c) as u32;
        let (n, p) = (fv[corners.next(c)], fv[corners.prev(c)]);
        if n == v || p == v || f == last {
            return None;
        }
        last = f;
        *entry = Entry {
            c: c as u32,
            n,
            p,
            twin: NONE,
            succ: NONE,
        };
    }
    Some(entries)
}

/// Matches each leaving half-edge of a vertex's corners with the arriving
/// one of the same edge (`twin`, and its inverse `succ`); returns how many
/// leaving half-edges have no twin (as many arriving ones have none), or
/// `None` when two leave or two arrive along the same edge (a non-manifold
/// edge, or faces of opposite windings) or one face holds both.
#[inline(always)]
fn pair(entries: &mut [Entry], sorted: &mut Vec<(u32, u32)>) -> Option<usize> {
    let k = entries.len();
    if k <= PAIRWISE {
        for i in 0..k {
            let (n, p) = (entries[i].n, entries[i].p);
            if entries[..i].iter().any(|e| e.n == n || e.p == p) {
                return None;
            }
            for j in 0..k {
                if entries[j].p == n {
                    entries[i].twin = j as u32;
                    entries[j].succ = i as u32;
                }
            }
        }
    } else {
        pair_sorted(entries, sorted)?;
    }
    let mut unpaired = 0;
    for (i, entry) in entries.iter().enumerate() {
        if entry.twin == i as u32 {
            return None;
        }
        unpaired += usize::from(entry.twin == NONE);
    }
    Some(unpaired)
}

/// [`pair`] at a vertex of many corners: leaving and arriving neighbours
/// sorted, then merged.
#[cold]
fn pair_sorted(entries: &mut [Entry], sorted: &mut Vec<(u32, u32)>) -> Option<()> {
    let k = entries.len();
    sorted.clear();
    sorted.extend(entries.iter().enumerate().map(|(i, e)| (e.n, i as u32)));
    sorted.extend(entries.iter().enumerate().map(|(i, e)| (e.p, i as u32)));
    let (by_n, by_p) = sorted.split_at_mut(k);
    by_n.sort_unstable();
    by_p.sort_unstable();
    if by_n.windows(2).any(|w| w[0].0 == w[1].0) || by_p.windows(2).any(|w| w[0].0 == w[1].0) {
        return None;
    }
    let (mut a, mut b) = (0, 0);
    while a < k && b < k {
        match by_n[a].0.cmp(&by_p[b].0) {
            std::cmp::Ordering::Less => a += 1,
            std::cmp::Ordering::Greater => b += 1,
            std::cmp::Ordering::Equal => {
                let (i, j) = (by_n[a].1, by_p[b].1);
                entries[i as usize].twin = j;
                entries[j as usize].succ = i;
                a += 1;
                b += 1;
            }
        }
    }
    Some(())
}

/// Writes the vertex's corners into `at` in the order of OpenSubdiv's walk:
/// an interior vertex from its first corner, a boundary vertex from the
/// corner whose leaving edge is a boundary edge, each next corner the one
/// whose leaving edge arrives at the vertex in the current face. `false`
/// (`at` left in corner order) when the walk cannot cover every corner (two
/// fans at one vertex, no face).
#[inline(always)]
fn walk(entries: &[Entry], unpaired: usize, at: &mut [u32]) -> bool {
    let k = entries.len();
    let start = match unpaired {
        _ if k == 0 => return false,
        0 => 0,
        1 => match entries.iter().position(|e| e.twin == NONE) {
            Some(i) => i as u32,
            None => return false,
        },
        _ => return false,
    };
    // Checked before anything is written.
    let mut s = start;
    for m in 0..k {
        if s == NONE || (m > 0 && s == start) {
            return false;
        }
        s = entries[s as usize].succ;
    }
    let mut s = start;
    for slot in at.iter_mut() {
        *slot = entries[s as usize].c;
        s = entries[s as usize].succ;
    }
    true
}

/// A vertex's parts of the vertex-face and vertex-edge tables.
struct VertexTables<'a> {
    faces: &'a mut [u32],
    face_local: &'a mut [u16],
    edges: &'a mut [u32],
    edge_local: &'a mut [u16],
}

/// What writing a vertex's relations reads.
struct Relations<'a, C> {
    corners: &'a C,
    face_edges: &'a [u32],
    twin: &'a [u32],
    edge_vertices: &'a [[u32; 2]],
}

impl<C: Corners> Relations<'_, C> {
    /// Writes the relations of the vertices of `range` into their parts of
    /// the tables (`t`): faces and edges in walk order, or as numbered for
    /// the vertices of `failed` (every vertex that could not be ordered, in
    /// increasing order). `offsets` are the vertex-face and vertex-edge
    /// offsets, `vertex_corners` each vertex's corners in walk order.
    fn write_block(
        &self,
        range: Range<usize>,
        (vf, ve): (&[u32], &[u32]),
        vertex_corners: &[u32],
        failed: &[u32],
        t: VertexTables,
    ) {
        let (fbase, ebase) = (vf[range.start] as usize, ve[range.start] as usize);
        let first = failed.partition_point(|&x| (x as usize) < range.start);
        let mut failed_at = failed[first..].iter().copied().peekable();
        let mut scratch = Vec::new();
        for v in range {
            let fr = vf[v] as usize..vf[v + 1] as usize;
            let er = ve[v] as usize..ve[v + 1] as usize;
            let tables = VertexTables {
                faces: &mut t.faces[fr.start - fbase..fr.end - fbase],
                face_local: &mut t.face_local[fr.start - fbase..fr.end - fbase],
                edges: &mut t.edges[er.start - ebase..er.end - ebase],
                edge_local: &mut t.edge_local[er.start - ebase..er.end - ebase],
            };
            let at = &vertex_corners[fr];
            if failed_at.next_if_eq(&(v as u32)).is_none() {
                self.write_ordered(at, tables);
            } else {
                self.write_unordered(v as u32, at, tables, &mut scratch);
            }
        }
    }

    /// Writes the relations of a vertex whose corners `at` are in walk
    /// order: faces, the vertex's place in each, the edge leaving it in
    /// each face and, at a boundary vertex, the last face's arriving edge.
    /// An edge starts at the vertex unless its other face comes first
    /// (the edge was numbered there, from the other end).
    #[inline]
    fn write_ordered(&self, at: &[u32], t: VertexTables) {
        let k = at.len();
        let boundary = t.edges.len() > k;
        let face_of = |c: u32| self.corners.face(c as usize);
        let mut before = if boundary {
            usize::MAX
        } else {
            face_of(at[k - 1])
        };
        for (m, &c) in at.iter().enumerate() {
            let c = c as usize;
            let f = self.corners.face(c);
            t.faces[m] = f as u32;
            t.face_local[m] = (c - self.corners.start(f)) as u16;
            t.edges[m] = self.face_edges[c];
            t.edge_local[m] = u16::from(before != usize::MAX && f > before);
            before = f;
        }
        if boundary {
            let c = self.corners.prev(at[k - 1] as usize);
            t.edges[k] = self.face_edges[c];
            t.edge_local[k] = 1;
        }
    }

    /// Writes the relations of vertex `v` whose faces cannot be ordered:
    /// faces in corner order (`at`), edges in the order they were numbered.
    #[cold]
    fn write_unordered(&self, v: u32, at: &[u32], t: VertexTables, edges: &mut Vec<u32>) {
        edges.clear();
        for (m, &c) in at.iter().enumerate() {
            let c = c as usize;
            let f = self.corners.face(c);
            t.faces[m] = f as u32;
            t.face_local[m] = (c - self.corners.start(f)) as u16;
            edges.push(self.face_edges[c]);
            let arriving = self.corners.prev(c);
            if self.twin[arriving] == NONE {
                edges.push(self.face_edges[arriving]);
            }
        }
        edges.sort_unstable();
        debug_assert_eq!(edges.len(), t.edges.len());
        for (m, &e) in edges.iter().enumerate() {
            t.edges[m] = e;
            t.edge_local[m] = u16::from(self.edge_vertices[e as usize][1] == v);
        }
    }
}
