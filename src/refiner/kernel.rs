//! The interpolation kernel: one level of vertex data, with the masks of
//! regular elements (smooth interior edges and vertices, the vast majority
//! after a level or two) computed once per shape of neighbourhood and reused.
//!
//! Weights come from the same rules as the general path and terms are added
//! in the same order, so results are bit-identical to it (and to OpenSubdiv).

use super::{Kind, Refiner, Source, opposite_vertex};
use crate::options::{Scheme, TriangleSubdivision};
use crate::real::Real;
use crate::rules::{EdgeNeighborhood, Mask, Rule, SchemeRules, VertexNeighborhood};
use crate::topology::refine::{
    derive_edge_faces, derive_half_edge_faces, derive_half_edge_wings, derive_inner_edge_wings,
    derive_quad_edge_faces_in_order, derive_smooth_hood,
};
use crate::topology::{AroundBuf, Level};

/// Scratch buffers for computing the terms of one child vertex.
pub(crate) struct Scratch<T> {
    pub mask: Mask<T>,
    pub terms: Vec<(Source, T)>,
    pub face_sizes: Vec<u32>,
    pub edge_sharpness: Vec<f32>,
    pub child_edge_sharpness: Vec<f32>,
    /// A vertex's relations where its level derives them.
    pub hood: AroundBuf,
    /// The parent edge whose halves' faces were derived last, and those
    /// faces (the two halves are consecutive child edges).
    pub halves: (usize, [[u32; 2]; 2]),
    /// The same for the vertices opposite the halves under Loop's split
    /// (`None`: not derivable).
    pub wings: (usize, Option<[[u32; 2]; 2]>),
    /// The parent face of the last edge inside a face whose faces were
    /// derived (edges come in order: the next is likely in the same face).
    pub face: usize,
}

impl Refiner {
    /// The faces and edges around vertex `v` of level `level`, in their
    /// stored order: read from the level, or derived from the level before
    /// into `buf` where the level left them out
    /// ([`Level::derived_relations`]).
    #[inline(always)]
    pub(crate) fn vertex_hood<'a>(
        &'a self,
        level: usize,
        v: usize,
        buf: &'a mut AroundBuf,
    ) -> (&'a [u32], &'a [u32]) {
        let l = &self.levels[level];
        if !l.derived_relations {
            return (l.vertex_faces_of(v), l.vertex_edges_of(v));
        }
        self.around(level).vertex_faces_and_edges(v, buf)
    }
}

impl<T: Real> Scratch<T> {
    pub fn new() -> Self {
        Scratch {
            mask: Mask::new(),
            terms: Vec::with_capacity(32),
            face_sizes: Vec::new(),
            edge_sharpness: Vec::new(),
            child_edge_sharpness: Vec::new(),
            hood: AroundBuf::default(),
            halves: (usize::MAX, [[0; 2]; 2]),
            wings: (usize::MAX, None),
            face: 0,
        }
    }
}

/// Widths handled on the stack; wider data takes the general path.
pub(super) const MAX_WIDTH: usize = 16;

pub(super) trait Width: Copy {
    fn get(self) -> usize;
}

#[derive(Clone, Copy)]
pub(super) struct Fixed<const W: usize>;

impl<const W: usize> Width for Fixed<W> {
    #[inline(always)]
    fn get(self) -> usize {
        W
    }
}

#[derive(Clone, Copy)]
pub(super) struct Dynamic(pub(super) usize);

impl Width for Dynamic {
    #[inline(always)]
    fn get(self) -> usize {
        self.0
    }
}

/// Interpolates level `level` from `src` (level - 1) into `dst`.
pub(crate) fn interpolate<T: Real>(
    r: &Refiner,
    kind: Kind,
    level: usize,
    width: usize,
    src: &[T],
    dst: &mut [T],
) {
    if kind != Kind::Vertex || width > MAX_WIDTH {
        return general(r, kind, level, width, src, dst);
    }
    match width {
        1 => run(r, level, Fixed::<1>, src, dst),
        2 => run(r, level, Fixed::<2>, src, dst),
        3 => run(r, level, Fixed::<3>, src, dst),
        4 => run(r, level, Fixed::<4>, src, dst),
        w => run(r, level, Dynamic(w), src, dst),
    }
}

/// Term-by-term interpolation of every child vertex through the general rules.
fn general<T: Real>(r: &Refiner, kind: Kind, level: usize, width: usize, src: &[T], dst: &mut [T]) {
    let mut acc = vec![T::ZERO; width];
    r.walk_masks::<T>(kind, level, |child, terms| {
        accumulate(terms, src, dst, &mut acc, child);
    });
}

/// Writes child `child` of `dst` as the sum of `terms` in their order (a
/// parent's value from `src`, a child's from `dst`), through `acc`, one row
/// of the data's width.
pub(crate) fn accumulate<T: Real>(
    terms: &[(Source, T)],
    src: &[T],
    dst: &mut [T],
    acc: &mut [T],
    child: u32,
) {
    let width = acc.len();
    acc.fill(T::ZERO);
    for &(source, w) in terms {
        let (data, i): (&[T], u32) = match source {
            Source::Parent(i) => (src, i),
            Source::Child(i) => (&*dst, i),
        };
        let row = &data[i as usize * width..(i as usize + 1) * width];
        for (a, &s) in acc.iter_mut().zip(row) {
            *a += s * w;
        }
    }
    let c = child as usize * width;
    dst[c..c + width].copy_from_slice(acc);
}

/// The mask of a smooth edge between two faces: the weights of its ends and
/// of its two faces (none under the bilinear rule), which apply to their
/// face points or, when not `centers`, to the faces' vertices opposite the
/// edge (Loop).
#[derive(Clone, Copy)]
pub(super) struct EdgeWeights<T> {
    pub ends: [T; 2],
    pub faces: Option<[T; 2]>,
    pub centers: bool,
}

/// Whether a vertex with `rule`, `faces` faces and `edges` edges is refined
/// by the cached smooth mask of its valence ([`Cache::smooth_vertex`]): a
/// smooth or dart vertex whose faces and edges pair up. Vertex, sparse and
/// face-varying passes all decide by this.
#[inline(always)]
pub(super) fn takes_smooth_mask(rule: Rule, faces: usize, edges: usize) -> bool {
    matches!(rule, Rule::Smooth | Rule::Dart) && faces == edges && edges > 0
}

/// Masks of regular neighbourhoods, computed on first use.
pub(super) struct Cache<T> {
    face: Vec<Option<T>>,
    /// Indexed by which of the two faces are triangles; `None` until filled.
    edge: [Option<Option<EdgeWeights<T>>>; 4],
    /// Indexed by valence; an entry without a vertex weight is not filled.
    vertex: Vec<Mask<T>>,
}

impl<T: Real> Cache<T> {
    pub(super) fn new() -> Self {
        Cache {
            face: Vec::new(),
            edge: [None; 4],
            vertex: Vec::new(),
        }
    }

    #[inline(always)]
    pub(super) fn face_weight(&mut self, rules: &SchemeRules, n: usize) -> T {
        match self.face.get(n) {
            Some(&Some(w)) => w,
            _ => self.fill_face_weight(rules, n),
        }
    }

    #[cold]
    #[inline(never)]
    fn fill_face_weight(&mut self, rules: &SchemeRules, n: usize) -> T {
        if self.face.len() <= n {
            self.face.resize(n + 1, None);
        }
        *self.face[n].get_or_insert_with(|| {
            let mut m = Mask::new();
            rules.face_vertex_mask::<T>(n, &mut m);
            m.vertex[0]
        })
    }

    /// The weights of a smooth edge between two faces; `tri` says which
    /// are triangles under the smooth-triangle rule. `None` for a mask of
    /// another shape (then the general path computes the edge). A
    /// reference into the cache, not a copy: a copy came back through the
    /// stack in 4-byte halves read back as 8-byte pairs, a
    /// store-forwarding stall on every edge point.
    #[inline(always)]
    pub(super) fn smooth_edge(
        &mut self,
        rules: &SchemeRules,
        tri: [bool; 2],
    ) -> Option<&EdgeWeights<T>> {
        let key = tri[0] as usize | (tri[1] as usize) << 1;
        if self.edge[key].is_none() {
            self.fill_smooth_edge(rules, key, tri);
        }
        self.edge[key].as_ref().and_then(Option::as_ref)
    }

    #[cold]
    #[inline(never)]
    fn fill_smooth_edge(&mut self, rules: &SchemeRules, key: usize, tri: [bool; 2]) {
        let sizes = [if tri[0] { 3 } else { 4 }, if tri[1] { 3 } else { 4 }];
        let hood = EdgeNeighborhood {
            sharpness: 0.0,
            face_sizes: &sizes,
        };
        let mut m = Mask::new();
        rules.edge_vertex_mask(&hood, Rule::Smooth, Rule::Smooth, &mut m);
        let weights = (|| {
            Some(EdgeWeights {
                ends: <[T; 2]>::try_from(&m.vertex[..]).ok()?,
                faces: match m.face.len() {
                    0 => None,
                    _ => Some(<[T; 2]>::try_from(&m.face[..]).ok()?),
                },
                centers: m.face_weights_for_centers,
            })
        })();
        self.edge[key] = Some(weights);
    }

    /// The smooth mask of an interior vertex with `n` faces and `n` edges.
    #[inline(always)]
    pub(super) fn smooth_vertex(&mut self, rules: &SchemeRules, n: usize) -> &Mask<T> {
        // A filled mask has its vertex weight; the empty ones are unfilled.
        if self.vertex.get(n).is_none_or(|m| m.vertex.is_empty()) {
            self.fill_smooth_vertex(rules, n);
        }
        &self.vertex[n]
    }

    #[cold]
    #[inline(never)]
    fn fill_smooth_vertex(&mut self, rules: &SchemeRules, n: usize) {
        if self.vertex.len() <= n {
            self.vertex.resize_with(n + 1, Mask::new);
        }
        let zeros = vec![0.0f32; n];
        let hood = VertexNeighborhood {
            sharpness: 0.0,
            edge_sharpness: &zeros,
            face_count: n,
            child_sharpness: 0.0,
            child_edge_sharpness: &zeros,
        };
        rules.vertex_vertex_mask(&hood, Rule::Smooth, Rule::Smooth, &mut self.vertex[n]);
    }
}

#[inline(always)]
pub(super) fn add<T: Real, W: Width>(acc: &mut [T; MAX_WIDTH], data: &[T], i: u32, w: T, width: W) {
    let n = width.get();
    let row = &data[i as usize * n..i as usize * n + n];
    for k in 0..n {
        acc[k] += row[k] * w;
    }
}

/// The sum of `terms` (an irregular child vertex), reading parent vertices
/// from `src` and face points from `face_points` (child vertex
/// `first_face_point` first). Cold, out of line and returning the sum by
/// value: the irregular path's loop stays out of the regular path's code.
#[cold]
#[inline(never)]
pub(super) fn sum_terms<T: Real, W: Width>(
    terms: &[(Source, T)],
    src: &[T],
    face_points: &[T],
    first_face_point: u32,
    width: W,
) -> [T; MAX_WIDTH] {
    let mut acc = [T::ZERO; MAX_WIDTH];
    for &(source, w) in terms {
        match source {
            Source::Parent(i) => add(&mut acc, src, i, w, width),
            Source::Child(i) => add(&mut acc, face_points, i - first_face_point, w, width),
        }
    }
    acc
}

/// A smooth vertex's neighbourhood as its mask reads it: its faces (whose
/// face points it weighs) and the far ends of its edges, `far(k)` for edge
/// `k` — read through the parent's edges, or derived with the faces.
struct SmoothVertex<'a, T, F> {
    v: usize,
    faces: &'a [u32],
    edges: usize,
    far: F,
    mask: &'a Mask<T>,
}

impl<T: Real, F: Fn(usize) -> u32> SmoothVertex<'_, T, F> {
    /// Adds the terms of the vertex's child, in mask order: its faces' face
    /// points, its edges' far ends, itself; the usual valences in unrolled
    /// loops (no trip counts).
    #[inline(always)]
    fn sum<W: Width>(&self, acc: &mut [T; MAX_WIDTH], src: &[T], face_points: &[T], width: W) {
        let done = match self.faces.len() {
            3 => self.add_fixed::<3, W>(acc, src, face_points, width),
            4 => self.add_fixed::<4, W>(acc, src, face_points, width),
            5 => self.add_fixed::<5, W>(acc, src, face_points, width),
            6 => self.add_fixed::<6, W>(acc, src, face_points, width),
            _ => false,
        };
        if !done {
            self.add(acc, src, face_points, width);
        }
    }

    /// Adds the terms of the vertex's child, in mask order.
    #[inline(always)]
    fn add<W: Width>(&self, acc: &mut [T; MAX_WIDTH], src: &[T], face_points: &[T], width: W) {
        for (&f, &w) in self.faces.iter().zip(&self.mask.face) {
            add(acc, face_points, f, w, width);
        }
        for (k, &w) in self.mask.edge.iter().take(self.edges).enumerate() {
            add(acc, src, (self.far)(k), w, width);
        }
        add(acc, src, self.v as u32, self.mask.vertex[0], width);
    }

    /// As [`add`](Self::add) for a vertex of `N` faces and edges whose mask
    /// weighs `N` edges and `N` face points or none (Loop): the same terms in
    /// the same order. False, with nothing added, for any other shape.
    #[inline(always)]
    fn add_fixed<const N: usize, W: Width>(
        &self,
        acc: &mut [T; MAX_WIDTH],
        src: &[T],
        face_points: &[T],
        width: W,
    ) -> bool {
        let (Ok(faces), Ok(edge_weights)) = (
            <&[u32; N]>::try_from(self.faces),
            <&[T; N]>::try_from(&self.mask.edge[..]),
        ) else {
            return false;
        };
        if self.edges != N {
            return false;
        }
        if let Ok(face_weights) = <&[T; N]>::try_from(&self.mask.face[..]) {
            for k in 0..N {
                add(acc, face_points, faces[k], face_weights[k], width);
            }
        } else if !self.mask.face.is_empty() {
            return false;
        }
        for (k, &w) in edge_weights.iter().enumerate() {
            add(acc, src, (self.far)(k), w, width);
        }
        add(acc, src, self.v as u32, self.mask.vertex[0], width);
        true
    }
}

/// The smooth mask of an interior vertex of valence `N` in fixed arrays:
/// the weights of its `N` face points (none under Loop), of its `N` edges'
/// far ends and of itself, added in the order of
/// [`SmoothVertex::add_fixed`]. Hoisted out of the vertex pass for the
/// regular valence of a level whose relations are derived (4 for quads, 6
/// for Loop), so that the usual vertex reads no mask cache.
#[derive(Clone, Copy)]
struct Regular<T, const N: usize> {
    face: Option<[T; N]>,
    edge: [T; N],
    vertex: T,
}

impl<T: Real, const N: usize> Regular<T, N> {
    /// The mask from the rules; `None` for a mask of another shape.
    fn new(r: &Refiner) -> Option<Self> {
        let mut cache = Cache::<T>::new();
        let m = cache.smooth_vertex(&r.rules, N);
        Some(Regular {
            face: match m.face.len() {
                0 => None,
                _ => Some(<[T; N]>::try_from(&m.face[..]).ok()?),
            },
            edge: <[T; N]>::try_from(&m.edge[..]).ok()?,
            vertex: *m.vertex.first()?,
        })
    }

    /// The vertex point of `v` from its faces' face points and its edges'
    /// far ends.
    #[inline(always)]
    fn sum<W: Width>(
        &self,
        v: usize,
        faces: &[u32; N],
        fars: &[u32; N],
        src: &[T],
        face_points: &[T],
        width: W,
    ) -> [T; MAX_WIDTH] {
        let mut acc = [T::ZERO; MAX_WIDTH];
        if let Some(fw) = self.face {
            for k in 0..N {
                add(&mut acc, face_points, faces[k], fw[k], width);
            }
        }
        for (&far, &w) in fars.iter().zip(&self.edge) {
            add(&mut acc, src, far, w, width);
        }
        add(&mut acc, src, v as u32, self.vertex, width);
        acc
    }
}

/// The point of a smooth edge between two faces: its ends `ev` (from
/// `src`) weighted `ends`, then one term per face — its face point, or under
/// Loop the vertex opposite the edge — read at `at` from `sides`.
#[inline(always)]
fn smooth_edge_point<T: Real, W: Width>(
    src: &[T],
    ev: [u32; 2],
    ends: [T; 2],
    sides: &[T],
    at: [u32; 2],
    weights: [T; 2],
    width: W,
) -> [T; MAX_WIDTH] {
    let mut acc = [T::ZERO; MAX_WIDTH];
    add(&mut acc, src, ev[0], ends[0], width);
    add(&mut acc, src, ev[1], ends[1], width);
    add(&mut acc, sides, at[0], weights[0], width);
    add(&mut acc, sides, at[1], weights[1], width);
    acc
}

/// Writes the first `width` values of `acc` to `slot` (`width` values long).
/// The width is read from `W` here, not captured from the caller: a
/// captured length turns the copy into a call to `memcpy` and keeps `acc` in
/// memory instead of registers.
#[inline(always)]
pub(super) fn store<T: Real, W: Width>(slot: &mut [T], acc: &[T; MAX_WIDTH], width: W) {
    let n = width.get();
    slot[..n].copy_from_slice(&acc[..n]);
}

/// What was derived for both halves of the parent edge of child edge
/// `half` (`half / 2`; the halves are consecutive child edges): `cached`
/// when it holds that edge's, else derived by `derive` and cached for the
/// other half. The value is returned as computed, not read back from the
/// cache: a pair stored as four words and read back as two is not forwarded
/// from the store buffer, a stall on every other edge.
#[inline(always)]
fn halves_of<P: Copy>(cached: &mut (usize, P), half: usize, derive: impl FnOnce(usize) -> P) -> P {
    let e = half / 2;
    if cached.0 == e {
        return cached.1;
    }
    let pair = derive(e);
    *cached = (e, pair);
    pair
}

/// Half `half % 2` of a pair (a select, not an indexed load).
#[inline(always)]
fn pick(pair: [[u32; 2]; 2], half: usize) -> [u32; 2] {
    if half.is_multiple_of(2) {
        pair[0]
    } else {
        pair[1]
    }
}

/// Child vertices per parallel task.
const CHUNK: usize = 4096;

/// The three ranges of child vertices — of parent vertices, faces and edges —
/// as disjoint mutable slices of `dst`, in that order.
fn split_children<'a, T>(
    dst: &'a mut [T],
    refinement: &crate::topology::Split,
    width: usize,
) -> [&'a mut [T]; 3] {
    let [nv, ne, nf] = refinement.parent_counts;
    let mut parts: [(usize, usize, usize); 3] = [
        (refinement.first_vertex_from_vertices as usize, nv, 0),
        (refinement.first_vertex_from_faces as usize, nf, 1),
        (refinement.first_vertex_from_edges as usize, ne, 2),
    ];
    parts.sort_unstable();
    let mut out: [&mut [T]; 3] = [&mut [], &mut [], &mut []];
    let mut rest = dst;
    let mut at = 0;
    for (start, len, slot) in parts {
        let (_, tail) = rest.split_at_mut((start - at) * width);
        let (part, tail) = tail.split_at_mut(len * width);
        out[slot] = part;
        rest = tail;
        at = start + len;
    }
    out
}

/// Calls `body(index, slot, cache, scratch)` for every child vertex of one
/// kind — `out` holds their values, `width` each — in parallel over chunks,
/// each chunk with its own mask cache and scratch buffers.
fn par_children<T: Real>(
    out: &mut [T],
    width: usize,
    body: impl Fn(usize, &mut [T], &mut Cache<T>, &mut Scratch<T>) + Sync,
) {
    use rayon::prelude::*;
    out.par_chunks_mut(CHUNK * width)
        .enumerate()
        .for_each(|(chunk, out)| {
            let mut cache = Cache::<T>::new();
            let mut scratch = Scratch::<T>::new();
            for (k, slot) in out.chunks_exact_mut(width).enumerate() {
                body(chunk * CHUNK + k, slot, &mut cache, &mut scratch);
            }
        });
}

fn run<T: Real, W: Width + Send + Sync>(
    r: &Refiner,
    level: usize,
    width: W,
    src: &[T],
    dst: &mut [T],
) {
    let parent: &Level = &r.levels[level - 1];
    let refinement = &r.refinements[level - 1];
    let scheme = r.options.scheme;
    let tri_smooth =
        scheme == Scheme::Catmark && r.options.triangles == TriangleSubdivision::Smooth;
    let zero = [T::ZERO; MAX_WIDTH];
    let n = width.get();
    let [vertex_points, face_points, edge_points] = split_children(dst, refinement, n);
    let first_face_point = refinement.first_vertex_from_faces;
    // The parent's relations as slices, read through their tables once.
    let ps = parent.slices();
    let (edge_sharpness, vertex_tags) = (ps.edge_sharpness, ps.vertex_tags);

    // Face points: the parent face's vertices.
    par_children(face_points, n, |f, slot, cache, _| {
        let acc = face_point(ps.face_verts(f), cache, &r.rules, src, width);
        store(slot, &acc, width);
    });
    // Edge and vertex points read face points (children of faces) only.
    let face_points: &[T] = face_points;
    // Sums the terms of an irregular child vertex (in `scratch.terms`).
    let irregular =
        |scratch: &Scratch<T>| sum_terms(&scratch.terms, src, face_points, first_face_point, width);

    // Edge points.
    // Empty edge sharpness: every parent edge is smooth (what
    // `Level::edge_sharpness_at` reads, tested once here).
    let has_sharpness = !edge_sharpness.is_empty();
    // A level whose relations are derived (every vertex smooth, every edge
    // between two faces): its edges' faces, and its vertices' faces and far
    // ends, derived from the level before.
    let grand_slices = parent
        .derived_relations
        .then(|| r.levels[level - 2].slices());
    let derived = grand_slices
        .as_ref()
        .map(|g| (g, &r.refinements[level - 2]));
    let triangles = scheme == Scheme::Loop;
    // Loop's smooth edge: its ends and the vertices opposite it, which a
    // derived level gives without reading its faces.
    let loop_edge = if triangles {
        Cache::<T>::new()
            .smooth_edge(&r.rules, [false, false])
            .and_then(|w| match w.faces {
                Some(faces) if !w.centers => Some((w.ends, faces)),
                _ => None,
            })
    } else {
        None
    };
    // Catmull-Clark on a derived level without sharp edges: every edge is
    // smooth between two quads, so one mask serves them all (what the
    // general closure below finds in its cache edge by edge, with the same
    // terms in the same order).
    let quad_edge = if !triangles && !has_sharpness && derived.is_some() {
        Cache::<T>::new()
            .smooth_edge(&r.rules, [false, false])
            .and_then(|w| match w.faces {
                Some(faces) if w.centers => Some((w.ends, faces)),
                _ => None,
            })
    } else {
        None
    };
    if let (Some((ends, face_weights)), Some((grand, gr))) = (quad_edge, derived) {
        par_children(edge_points, n, |e, slot, _, scratch| {
            let faces = match e.checked_sub(gr.parent_corners) {
                Some(i) => pick(
                    halves_of(&mut scratch.halves, i, |e| {
                        derive_half_edge_faces(grand, false, e)
                    }),
                    i,
                ),
                None => derive_quad_edge_faces_in_order(grand, gr, e, &mut scratch.face),
            };
            let ev = ps.edge_vertices[e];
            let acc = smooth_edge_point(src, ev, ends, face_points, faces, face_weights, width);
            store(slot, &acc, width);
        });
    } else {
        par_children(edge_points, n, |e, slot, cache, scratch| {
            if let (Some((ends, opposite)), Some((grand, gr))) = (loop_edge, derived)
                && (!has_sharpness || edge_sharpness[e] <= 0.0)
            {
                let wings = match e.checked_sub(gr.parent_corners) {
                    Some(i) => halves_of(&mut scratch.wings, i, |e| {
                        derive_half_edge_wings(grand, gr, e)
                    })
                    .map(|h| pick(h, i)),
                    None => derive_inner_edge_wings(grand, gr, e),
                };
                if let Some(wings) = wings {
                    let ev = ps.edge_vertices[e];
                    let acc = smooth_edge_point(src, ev, ends, src, wings, opposite, width);
                    store(slot, &acc, width);
                    return;
                }
            }
            let derived_faces;
            let faces: &[u32] = match derived {
                Some((grand, gr)) => {
                    derived_faces = match e.checked_sub(gr.parent_corners) {
                        // A half of a parent edge: both halves derived at once.
                        Some(i) => pick(
                            halves_of(&mut scratch.halves, i, |e| {
                                derive_half_edge_faces(grand, triangles, e)
                            }),
                            i,
                        ),
                        None if triangles => derive_edge_faces(grand, gr, true, e),
                        None => derive_quad_edge_faces_in_order(grand, gr, e, &mut scratch.face),
                    };
                    &derived_faces
                }
                None => ps.edge_faces_of(e),
            };
            let smooth = faces.len() == 2 && (!has_sharpness || edge_sharpness[e] <= 0.0);
            let weights = if smooth {
                cache.smooth_edge(
                    &r.rules,
                    [
                        tri_smooth && ps.face_verts(faces[0] as usize).len() == 3,
                        tri_smooth && ps.face_verts(faces[1] as usize).len() == 3,
                    ],
                )
            } else {
                None
            };
            // Each branch stores its own sum: an accumulator shared with
            // the irregular path's returned array lived on the stack, its
            // lanes written apart and read back whole (a store-forwarding
            // stall on every edge point).
            if let Some(w) = weights {
                let mut acc = zero;
                let ev = ps.edge_vertices[e];
                add(&mut acc, src, ev[0], w.ends[0], width);
                add(&mut acc, src, ev[1], w.ends[1], width);
                if let Some(fw) = w.faces {
                    for k in 0..2 {
                        let f = faces[k];
                        if w.centers {
                            add(&mut acc, face_points, f, fw[k], width);
                        } else {
                            let far = opposite_vertex(&ps, f as usize, e);
                            add(&mut acc, src, far, fw[k], width);
                        }
                    }
                }
                store(slot, &acc, width);
            } else {
                r.edge_terms(Kind::Vertex, level, e, scratch);
                store(slot, &irregular(scratch), width);
            }
        });
    }

    // Vertex points.
    // Empty vertex tags: every parent vertex is smooth (what
    // `Level::vertex_tag` reads, tested once here).
    let has_tags = !vertex_tags.is_empty();
    let around = r.around(level - 1);
    let (quad4, loop6) = match derived {
        Some(_) if triangles => (None, Regular::<T, 6>::new(r)),
        Some(_) => (Regular::<T, 4>::new(r), None),
        None => (None, None),
    };
    par_children(vertex_points, n, |v, slot, cache, scratch| {
        if let Some((grand, gr)) = derived {
            let (mut faces, mut fars) = ([0u32; 8], [0u32; 8]);
            if let Some(count) = derive_smooth_hood(grand, gr, triangles, v, &mut faces, &mut fars)
            {
                if let (4, Some(m), Some(f), Some(e)) =
                    (count, quad4, faces.first_chunk(), fars.first_chunk())
                {
                    store(slot, &m.sum(v, f, e, src, face_points, width), width);
                    return;
                }
                if let (6, Some(m), Some(f), Some(e)) =
                    (count, loop6, faces.first_chunk(), fars.first_chunk())
                {
                    store(slot, &m.sum(v, f, e, src, face_points, width), width);
                    return;
                }
                let mut acc = zero;
                SmoothVertex {
                    v,
                    faces: &faces[..count],
                    edges: count,
                    far: |k: usize| fars[k],
                    mask: cache.smooth_vertex(&r.rules, count),
                }
                .sum(&mut acc, src, face_points, width);
                store(slot, &acc, width);
                return;
            }
        }
        // A derived level's relations go into the scratch's buffer, taken
        // out while the terms below may use the scratch (and put back at
        // the end); a stored level's are read in place, nothing moved.
        let mut hood = None;
        let (faces, edges) = match derived {
            Some(_) => {
                around.vertex_faces_and_edges(v, hood.insert(std::mem::take(&mut scratch.hood)))
            }
            None => (ps.vertex_faces_of(v), ps.vertex_edges_of(v)),
        };
        let rule = if has_tags {
            vertex_tags[v].rule()
        } else {
            Rule::Smooth
        };
        let smooth = takes_smooth_mask(rule, faces.len(), edges.len());
        // Each branch stores its own sum, as the edge points' do.
        if smooth {
            let mut acc = zero;
            SmoothVertex {
                v,
                faces,
                edges: edges.len(),
                far: |k: usize| ps.other_vertex(edges[k] as usize, v as u32),
                mask: cache.smooth_vertex(&r.rules, faces.len()),
            }
            .sum(&mut acc, src, face_points, width);
            store(slot, &acc, width);
        } else {
            r.vertex_terms(Kind::Vertex, level, v, scratch);
            store(slot, &irregular(scratch), width);
        }
        if let Some(hood) = hood {
            scratch.hood = hood;
        }
    });
}

/// The face point of a face with vertices `verts`: their average, quads
/// (every face after the first level) in an unrolled loop.
#[inline(always)]
pub(super) fn face_point<T: Real, W: Width>(
    verts: &[u32],
    cache: &mut Cache<T>,
    rules: &SchemeRules,
    src: &[T],
    width: W,
) -> [T; MAX_WIDTH] {
    let w = cache.face_weight(rules, verts.len());
    let mut acc = [T::ZERO; MAX_WIDTH];
    if let Ok(quad) = <&[u32; 4]>::try_from(verts) {
        for &v in quad {
            add(&mut acc, src, v, w, width);
        }
    } else {
        for &v in verts {
            add(&mut acc, src, v, w, width);
        }
    }
    acc
}
