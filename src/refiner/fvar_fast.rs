//! Face-varying interpolation through the vertex kernel where the channel
//! follows the vertex topology.
//!
//! Away from seams a channel's values are refined exactly as vertex data
//! would be: OpenSubdiv's `InterpolateFaceVarying` uses the vertex's own
//! masks for a value whose topology matches the vertex's, reading the same
//! neighbours in the same order. So the values of such a neighbourhood can
//! come from the vertex kernel (hoisted masks, derived relations, fixed
//! width, parallel passes) run on the channel's values gathered one per
//! vertex, bit for bit what the face-varying pass computes.
//!
//! Which children qualify is decided from the parent's faces: a face is
//! *clean* when each of its corners uses its vertex's first value (sibling
//! 0), and a vertex is clean when all its faces are. A child qualifies when
//! everything its mask reads is clean and its own value is not mismatched:
//!
//! * a face point: its face is clean (it averages the face's values);
//! * an edge point: both ends of the edge are clean (then so are the edge's
//!   faces, whose face points and, under Loop, opposite corners it reads);
//! * a vertex point: the vertex is clean (its faces' points, the far ends
//!   of its edges and its own value are then first siblings).
//!
//! The kernel writes the children one row per vertex at the front of the
//! destination, and the rows then move to their values' places (a child's
//! first value is at or after its own index); the face-varying pass then
//! computes only the other children, over every row they own.

use super::Refiner;
use super::kernel::{self, MAX_WIDTH};
use crate::options::Scheme;
use crate::real::Real;
use crate::refiner::Kind;
use crate::topology::Table;
use crate::topology::fvar::ChannelLevel;

/// The parent elements whose children the vertex kernel has not computed:
/// what the face-varying pass has left to do.
pub(crate) struct Fast {
    /// Faces whose face points are left.
    pub(super) faces: Vec<u32>,
    /// Edges whose edge points are left.
    pub(super) edges: Vec<u32>,
    /// Vertices whose children are left.
    pub(super) vertices: Vec<u32>,
}

/// Below this share of clean faces the face-varying pass alone is cheaper.
const MIN_CLEAN_SHARE: f64 = 0.5;

impl Refiner {
    /// Computes, with the vertex kernel, the values of face-varying
    /// `channel` at `level` (from `src` at `level - 1`, `width` columns)
    /// that follow the vertex topology, writing them into `dst`; returns
    /// the elements whose children are left, or `None` (nothing written)
    /// when the channel is linear (or the scheme bilinear), too wide for the
    /// kernel, or mostly seams.
    pub(super) fn fvar_by_vertex_kernel<T: Real>(
        &self,
        channel: usize,
        level: usize,
        width: usize,
        src: &[T],
        dst: &mut [T],
    ) -> Option<Fast> {
        let parent = &self.levels[level - 1];
        let split = &self.refinements[level - 1];
        let pf: &ChannelLevel = &self.fvar[channel][level - 1];
        let cf: &ChannelLevel = &self.fvar[channel][level];
        // Taken on several threads too: the face-varying pass in parallel
        // chunks was slower there (2026-12-02, two threads, level 2, best
        // of 20: the UV tori 2.4-3.4 ms through the pass against 1.6-2.4
        // this way, the Loop torus's 2.4 against 1.7; the production-like
        // mesh, best of 5, 61-109 against 54-67 ms; on one thread this way
        // 1.8-2.5 and 82-104 ms).
        if pf.is_linear() || self.options.scheme == Scheme::Bilinear || width > MAX_WIDTH {
            return None;
        }
        let nf = parent.face_count();
        // The faces that are not clean (their face points are left to the
        // face-varying pass) and the vertices around them.
        let unclean = pf.faces_off_first_values(parent);
        if ((nf - unclean.len()) as f64) < MIN_CLEAN_SHARE * nf as f64 {
            return None;
        }
        let mut clean_vertices = crate::alloc::vec_or_unwind(true, parent.vertex_count);
        for &f in &unclean {
            for &v in parent.face_verts(f as usize) {
                clean_vertices[v as usize] = false;
            }
        }
        // The channel's values one per parent vertex (its first sibling),
        // refined as vertex data into the front of `dst`, one row per child
        // vertex...
        let mut by_vertex = Table::for_overwrite(parent.vertex_count * width);
        for (v, row) in by_vertex.chunks_exact_mut(width).enumerate() {
            let x = pf.vertex_value(v, 0) as usize * width;
            row.copy_from_slice(&src[x..x + width]);
        }
        let child_count = self.levels[level].vertex_count;
        kernel::interpolate(
            self,
            Kind::Vertex,
            level,
            width,
            &by_vertex,
            &mut dst[..child_count * width],
        );
        // Not read again: its room goes back (to the pool) before the rest
        // of this pass.
        drop(by_vertex);
        // ... then moved to their values' rows: from the last, since a
        // child's first value is at or after its own index (siblings only
        // add rows), every row is read before it is overwritten.
        match width {
            1 => spread::<T, 1>(cf, child_count, dst),
            2 => spread::<T, 2>(cf, child_count, dst),
            3 => spread::<T, 3>(cf, child_count, dst),
            4 => spread::<T, 4>(cf, child_count, dst),
            _ => {
                for c in (0..child_count).rev() {
                    let to = cf.vertex_value_offset(c) as usize * width;
                    dst.copy_within(c * width..(c + 1) * width, to);
                }
            }
        }
        // What the kernel got wrong (children reading another sibling, or
        // whose own value is mismatched) is left to the face-varying pass.
        // A child's value is mismatched where its parent's is: an edge point
        // on a split or linear edge, a vertex's child when the vertex's
        // value is.
        debug_assert_eq!(pf.edge_tags().len(), parent.edge_count());
        let left = Fast {
            faces: if split.has_face_points() {
                unclean
            } else {
                Vec::new()
            },
            // (Per-edge and per-vertex tables, one entry each.)
            edges: select(
                pf.edge_tags().iter().zip(parent.edge_vertices.iter()),
                |(t, &[a, b])| {
                    t.is_mismatch()
                        || t.is_linear()
                        || !clean_vertices[a as usize]
                        || !clean_vertices[b as usize]
                },
            ),
            vertices: select(
                clean_vertices.iter().zip(pf.first_value_tags()),
                |(&clean, t)| !clean || t.is_mismatch(),
            ),
        };
        Some(left)
    }
}

/// The indices of the elements of `items` for which `pred` holds, in
/// order.
fn select<I: Iterator>(items: I, mut pred: impl FnMut(I::Item) -> bool) -> Vec<u32> {
    let mut out = Vec::new();
    for (i, item) in items.enumerate() {
        if pred(item) {
            out.push(i as u32);
        }
    }
    out
}

/// Moves rows `0..child_count` of `dst` (`W` values each) to the rows of
/// their children's first values.
fn spread<T: Real, const W: usize>(cf: &ChannelLevel, child_count: usize, dst: &mut [T]) {
    for c in (0..child_count).rev() {
        let to = cf.vertex_value_offset(c) as usize;
        if to == c {
            // No sibling before this child: neither before any earlier one.
            break;
        }
        let row: [T; W] = std::array::from_fn(|k| dst[c * W + k]);
        dst[to * W..to * W + W].copy_from_slice(&row);
    }
}
