//! The interpolation kernel of sparse levels: vertex data of the child
//! vertices a sparse step created, with the masks of smooth faces, edges and
//! vertices cached per shape as the uniform kernel (`refiner/kernel.rs`)
//! caches them, the others through the general terms — the same weights and
//! terms in the same order, so bit-identical to OpenSubdiv.

use crate::real::Real;
use crate::refiner::kernel::{
    Cache, Dynamic, Fixed, MAX_WIDTH, Width, add, face_point, store, sum_terms, takes_smooth_mask,
};
use crate::refiner::{Kind, Scratch, Source, Step, accumulate, face_terms, opposite_vertex};
use crate::rules::{Mask, Rule};
use crate::topology::LevelSlices;
use crate::topology::refine::sparse::SparseSplit;

/// One sparse level of vertex data (feature-adaptive refinement): the child
/// vertices `split` created, in its numbering, from `src` (the parent
/// level's) into `dst`. As [`run`] on a uniform level: the masks of smooth
/// faces, edges and vertices cached per shape, the others through the
/// general terms of `step`; the same weights and terms in the same order as
/// [`crate::refiner::adaptive`]'s walk, so the results are bit-identical to
/// it (and to OpenSubdiv). Serial.
pub(super) fn interpolate_sparse<T: Real>(
    step: &Step<'_, SparseSplit>,
    tri_smooth: bool,
    width: usize,
    src: &[T],
    dst: &mut [T],
) {
    match width {
        1 => run_sparse(step, tri_smooth, Fixed::<1>, src, dst),
        2 => run_sparse(step, tri_smooth, Fixed::<2>, src, dst),
        3 => run_sparse(step, tri_smooth, Fixed::<3>, src, dst),
        4 => run_sparse(step, tri_smooth, Fixed::<4>, src, dst),
        w if w <= MAX_WIDTH => run_sparse(step, tri_smooth, Dynamic(w), src, dst),
        w => {
            let mut acc = vec![T::ZERO; w];
            walk_sparse::<T>(Kind::Vertex, step, |c, terms| {
                accumulate(terms, src, dst, &mut acc, c)
            });
        }
    }
}

/// Calls `emit(child, terms)` for every child vertex a sparse step created,
/// in OpenSubdiv's order — face points, edge points, then vertex points,
/// each in parent order — with the terms of `kind` in OpenSubdiv's
/// accumulation order (as [`crate::refiner::Refiner::walk_masks`] on uniform
/// levels).
pub(super) fn walk_sparse<T: Real>(
    kind: Kind,
    step: &Step<'_, SparseSplit>,
    mut emit: impl FnMut(u32, &[(Source, T)]),
) {
    let (parent, split) = (step.parent, step.children);
    let mut s = Scratch::<T>::new();
    for (f, &c) in split.face_child_vertex.iter().enumerate() {
        if c != crate::INVALID_INDEX {
            face_terms(step.rules, parent, f, &mut s);
            emit(c, &s.terms);
        }
    }
    for (e, &c) in split.edge_child_vertex.iter().enumerate() {
        if c != crate::INVALID_INDEX {
            step.edge_terms(kind, e, parent.edge_faces_of(e), &mut s);
            emit(c, &s.terms);
        }
    }
    for (v, &c) in split.vertex_child_vertex.iter().enumerate() {
        if c != crate::INVALID_INDEX {
            let (faces, edges) = (parent.vertex_faces_of(v), parent.vertex_edges_of(v));
            step.vertex_terms(kind, v, faces, edges, &mut s);
            emit(c, &s.terms);
        }
    }
}

fn run_sparse<T: Real, W: Width>(
    step: &Step<'_, SparseSplit>,
    tri_smooth: bool,
    width: W,
    src: &[T],
    dst: &mut [T],
) {
    let (parent, split, rules) = (step.parent, step.children, step.rules);
    let sl = parent.slices();
    let face_child: &[u32] = &split.face_child_vertex;
    let n = width.get();
    let zero = [T::ZERO; MAX_WIDTH];
    let mut cache = Cache::<T>::new();
    let mut scratch = Scratch::<T>::new();
    let slot = |c: u32| c as usize * n..c as usize * n + n;
    // Face points: the parent face's vertices.
    for (f, &c) in face_child.iter().enumerate() {
        if c == crate::INVALID_INDEX {
            continue;
        }
        let acc = face_point(sl.face_verts(f), &mut cache, rules, src, width);
        store(&mut dst[slot(c)], &acc, width);
    }
    // Edge points: smooth edges between two faces through the cached mask,
    // the others term by term. Face points are read from `dst` by their
    // child index (no offset: `first_face_point` 0).
    let edge_sharpness: &[f32] = &parent.edge_sharpness;
    let has_sharpness = !edge_sharpness.is_empty();
    for (e, &c) in split.edge_child_vertex.iter().enumerate() {
        if c == crate::INVALID_INDEX {
            continue;
        }
        let faces = sl.edge_faces_of(e);
        let smooth = faces.len() == 2 && (!has_sharpness || edge_sharpness[e] <= 0.0);
        let weights = if smooth {
            cache.smooth_edge(
                rules,
                [
                    tri_smooth && sl.face_vertices.range(faces[0] as usize).len() == 3,
                    tri_smooth && sl.face_vertices.range(faces[1] as usize).len() == 3,
                ],
            )
        } else {
            None
        };
        let acc = if let Some(w) = weights {
            let mut acc = zero;
            let ev = sl.edge_vertices[e];
            add(&mut acc, src, ev[0], w.ends[0], width);
            add(&mut acc, src, ev[1], w.ends[1], width);
            if let Some(fw) = w.faces {
                for k in 0..2 {
                    let f = faces[k] as usize;
                    if w.centers {
                        add(&mut acc, dst, face_child[f], fw[k], width);
                    } else {
                        let far = opposite_vertex(&sl, f, e);
                        add(&mut acc, src, far, fw[k], width);
                    }
                }
            }
            acc
        } else {
            step.edge_terms(Kind::Vertex, e, faces, &mut scratch);
            sum_terms(&scratch.terms, src, dst, 0, width)
        };
        store(&mut dst[slot(c)], &acc, width);
    }
    // Vertex points: smooth and dart vertices through the cached mask of
    // their valence, the others term by term.
    let vertex_tags = &parent.vertex_tags[..];
    let has_tags = !vertex_tags.is_empty();
    for (v, &c) in split.vertex_child_vertex.iter().enumerate() {
        if c == crate::INVALID_INDEX {
            continue;
        }
        let (faces, edges) = (sl.vertex_faces_of(v), sl.vertex_edges_of(v));
        let rule = if has_tags {
            vertex_tags[v].rule()
        } else {
            Rule::Smooth
        };
        let smooth = takes_smooth_mask(rule, faces.len(), edges.len());
        let acc = if smooth {
            let mut acc = zero;
            SmoothSparseVertex {
                v,
                faces,
                edges,
                parent: sl,
                face_child,
                mask: cache.smooth_vertex(rules, faces.len()),
            }
            .sum(&mut acc, src, dst, width);
            acc
        } else {
            step.vertex_terms(Kind::Vertex, v, faces, edges, &mut scratch);
            sum_terms(&scratch.terms, src, dst, 0, width)
        };
        store(&mut dst[slot(c)], &acc, width);
    }
}

/// A smooth vertex of a sparse parent level: its faces' face points (read
/// through the step's face-child map), its edges' far ends, itself.
struct SmoothSparseVertex<'a, T> {
    v: usize,
    faces: &'a [u32],
    edges: &'a [u32],
    parent: LevelSlices<'a>,
    face_child: &'a [u32],
    mask: &'a Mask<T>,
}

impl<T: Real> SmoothSparseVertex<'_, T> {
    /// Adds the terms of the vertex's child in mask order, as
    /// `Step::vertex_terms` lists them.
    #[inline(always)]
    fn sum<W: Width>(&self, acc: &mut [T; MAX_WIDTH], src: &[T], dst: &[T], width: W) {
        for (&f, &w) in self.faces.iter().zip(&self.mask.face) {
            add(acc, dst, self.face_child[f as usize], w, width);
        }
        for (&e, &w) in self.edges.iter().zip(&self.mask.edge) {
            add(
                acc,
                src,
                self.parent.other_vertex(e as usize, self.v as u32),
                w,
                width,
            );
        }
        add(acc, src, self.v as u32, self.mask.vertex[0], width);
    }
}
