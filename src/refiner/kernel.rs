//! The interpolation kernel: one level of vertex data, with the masks of
//! regular elements (smooth interior edges and vertices, the vast majority
//! after a level or two) computed once per shape of neighbourhood and reused.
//!
//! Weights come from the same rules as the general path and terms are added
//! in the same order, so results are bit-identical to it (and to OpenSubdiv).

use super::{Kind, Refiner, Source, opposite_vertex};
use crate::options::{Scheme, TriangleSubdivision};
use crate::real::Real;
use crate::rules::{EdgeNeighborhood, Mask, Rule, VertexNeighborhood};
use crate::topology::Level;

/// Scratch buffers for computing the terms of one child vertex.
pub(crate) struct Scratch<T> {
    pub mask: Mask<T>,
    pub terms: Vec<(Source, T)>,
    pub face_sizes: Vec<u32>,
    pub edge_sharpness: Vec<f32>,
    pub child_edge_sharpness: Vec<f32>,
}

impl<T: Real> Scratch<T> {
    pub fn new() -> Self {
        Scratch {
            mask: Mask::new(),
            terms: Vec::with_capacity(32),
            face_sizes: Vec::new(),
            edge_sharpness: Vec::new(),
            child_edge_sharpness: Vec::new(),
        }
    }
}

/// Widths handled on the stack; wider data takes the general path.
const MAX_WIDTH: usize = 16;

trait Width: Copy {
    fn get(self) -> usize;
}

#[derive(Clone, Copy)]
struct Fixed<const W: usize>;

impl<const W: usize> Width for Fixed<W> {
    #[inline(always)]
    fn get(self) -> usize {
        W
    }
}

#[derive(Clone, Copy)]
struct Dynamic(usize);

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
        dst[c..c + width].copy_from_slice(&acc);
    });
}

/// Masks of regular neighbourhoods, computed on first use.
struct Cache<T> {
    face: Vec<Option<T>>,
    edge: [Option<Mask<T>>; 4],
    vertex: Vec<Option<Mask<T>>>,
}

impl<T: Real> Cache<T> {
    fn new() -> Self {
        Cache {
            face: Vec::new(),
            edge: [None, None, None, None],
            vertex: Vec::new(),
        }
    }

    fn face_weight(&mut self, r: &Refiner, n: usize) -> T {
        if self.face.len() <= n {
            self.face.resize(n + 1, None);
        }
        *self.face[n].get_or_insert_with(|| {
            let mut m = Mask::new();
            r.rules.face_vertex_mask::<T>(n, &mut m);
            m.vertex[0]
        })
    }

    /// The smooth mask of an edge between two faces; `tri` says which are
    /// triangles under the smooth-triangle rule.
    fn smooth_edge(&mut self, r: &Refiner, tri: [bool; 2]) -> &Mask<T> {
        let key = tri[0] as usize | (tri[1] as usize) << 1;
        self.edge[key].get_or_insert_with(|| {
            let sizes = [if tri[0] { 3 } else { 4 }, if tri[1] { 3 } else { 4 }];
            let hood = EdgeNeighborhood {
                sharpness: 0.0,
                face_sizes: &sizes,
            };
            let mut m = Mask::new();
            r.rules
                .edge_vertex_mask(&hood, Rule::Smooth, Rule::Smooth, &mut m);
            m
        })
    }

    /// The smooth mask of an interior vertex with `n` faces and `n` edges.
    fn smooth_vertex(&mut self, r: &Refiner, n: usize) -> &Mask<T> {
        if self.vertex.len() <= n {
            self.vertex.resize(n + 1, None);
        }
        self.vertex[n].get_or_insert_with(|| {
            let zeros = vec![0.0f32; n];
            let hood = VertexNeighborhood {
                sharpness: 0.0,
                edge_sharpness: &zeros,
                face_count: n,
                child_sharpness: 0.0,
                child_edge_sharpness: &zeros,
            };
            let mut m = Mask::new();
            r.rules
                .vertex_vertex_mask(&hood, Rule::Smooth, Rule::Smooth, &mut m);
            m
        })
    }
}

#[inline(always)]
fn add<T: Real, W: Width>(acc: &mut [T; MAX_WIDTH], data: &[T], i: u32, w: T, width: W) {
    let n = width.get();
    let row = &data[i as usize * n..i as usize * n + n];
    for k in 0..n {
        acc[k] += row[k] * w;
    }
}

/// Writes the first `width` values of `acc` to `slot` (`width` values long).
/// The width is read from `W` here, not captured from the caller: a
/// captured length turns the copy into a call to `memcpy` and keeps `acc` in
/// memory instead of registers.
#[inline(always)]
fn store<T: Real, W: Width>(slot: &mut [T], acc: &[T; MAX_WIDTH], width: W) {
    let n = width.get();
    slot[..n].copy_from_slice(&acc[..n]);
}

/// Child vertices per parallel task.
const CHUNK: usize = 4096;

/// The three ranges of child vertices — of parent vertices, faces and edges —
/// as disjoint mutable slices of `dst`, in that order.
fn split_children<'a, T>(
    dst: &'a mut [T],
    refinement: &crate::topology::Refinement,
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

    // Face points: the parent face's vertices.
    par_children(face_points, n, |f, slot, cache, _| {
        let verts = parent.face_verts(f);
        let w = cache.face_weight(r, verts.len());
        let mut acc = zero;
        for &v in verts {
            add(&mut acc, src, v, w, width);
        }
        store(slot, &acc, width);
    });
    // Edge and vertex points read face points (children of faces) only.
    let face_points: &[T] = face_points;
    let add_source = |acc: &mut [T; MAX_WIDTH], source: Source, w: T| match source {
        Source::Parent(i) => add(acc, src, i, w, width),
        Source::Child(i) => add(acc, face_points, i - first_face_point, w, width),
    };

    // Edge points.
    // Empty edge sharpness: every parent edge is smooth (what
    // `Level::edge_sharpness_at` reads, tested once here).
    let has_sharpness = !parent.edge_sharpness.is_empty();
    par_children(edge_points, n, |e, slot, cache, scratch| {
        let faces = parent.edge_faces_of(e);
        let smooth = faces.len() == 2 && (!has_sharpness || parent.edge_sharpness[e] <= 0.0);
        let mut acc = zero;
        let ev = parent.edge_vertices[e];
        if smooth {
            let tri = [
                tri_smooth && parent.face_vertices.count(faces[0] as usize) == 3,
                tri_smooth && parent.face_vertices.count(faces[1] as usize) == 3,
            ];
            let mask = cache.smooth_edge(r, tri);
            add(&mut acc, src, ev[0], mask.vertex[0], width);
            add(&mut acc, src, ev[1], mask.vertex[1], width);
            if mask.face_weights_for_centers {
                for (&f, &w) in faces.iter().zip(&mask.face) {
                    add(&mut acc, face_points, f, w, width);
                }
            } else {
                for (&f, &w) in faces.iter().zip(&mask.face) {
                    add(
                        &mut acc,
                        src,
                        opposite_vertex(parent, f as usize, e),
                        w,
                        width,
                    );
                }
            }
        } else {
            r.edge_terms(Kind::Vertex, level, e, scratch);
            for &(source, w) in &scratch.terms {
                add_source(&mut acc, source, w);
            }
        }
        store(slot, &acc, width);
    });

    // Vertex points.
    // Empty vertex tags: every parent vertex is smooth (what
    // `Level::vertex_tag` reads, tested once here).
    let has_tags = !parent.vertex_tags.is_empty();
    par_children(vertex_points, n, |v, slot, cache, scratch| {
        let faces = parent.vertex_faces_of(v);
        let edges = parent.vertex_edges_of(v);
        let rule = if has_tags {
            parent.vertex_tags[v].rule()
        } else {
            Rule::Smooth
        };
        let smooth = matches!(rule, Rule::Smooth | Rule::Dart)
            && faces.len() == edges.len()
            && !edges.is_empty();
        let mut acc = zero;
        if smooth {
            let mask = cache.smooth_vertex(r, faces.len());
            for (&f, &w) in faces.iter().zip(&mask.face) {
                add(&mut acc, face_points, f, w, width);
            }
            for (&e, &w) in edges.iter().zip(&mask.edge) {
                add(
                    &mut acc,
                    src,
                    parent.other_vertex(e as usize, v as u32),
                    w,
                    width,
                );
            }
            add(&mut acc, src, v as u32, mask.vertex[0], width);
        } else {
            r.vertex_terms(Kind::Vertex, level, v, scratch);
            for &(source, w) in &scratch.terms {
                add_source(&mut acc, source, w);
            }
        }
        store(slot, &acc, width);
    });
}
