//! Bilinear masks (OpenSubdiv's `Scheme<SCHEME_BILINEAR>`).
//!
//! Everything is linear: face points are face centres, edge points midpoints,
//! vertex points the vertices themselves, and the limit of a vertex is the
//! vertex. Those masks are written by [`SchemeRules`](super::SchemeRules)
//! itself; only the tangents are particular to this scheme.

use super::Mask;
use crate::real::Real;

/// Limit tangents: ambiguous for a piecewise-linear surface, so OpenSubdiv
/// takes the directions of the vertex's first two edges, `e0 - v` and
/// `e1 - v`. Both masks have exactly two edge weights, whatever the valence.
pub(super) fn limit_tangents<T: Real>(tan1: &mut Mask<T>, tan2: &mut Mask<T>) {
    tan1.reset(1, 2, 0);
    tan2.reset(1, 2, 0);
    tan1.vertex[0] = -T::ONE;
    tan1.edge[0] = T::ONE;
    tan2.vertex[0] = -T::ONE;
    tan2.edge[1] = T::ONE;
}
