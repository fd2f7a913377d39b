//! Catmull-Clark masks (OpenSubdiv's `Scheme<SCHEME_CATMARK>`).
//!
//! Weights are computed in `T`, like OpenSubdiv's `Weight` type, except where
//! OpenSubdiv computes in `double` and rounds once at the end (irregular
//! tangents), which is reproduced by computing in `f64` and converting last.

use super::{Mask, VertexNeighborhood};
use crate::options::TriangleSubdivision;
use crate::real::Real;
use std::f64::consts::PI;

/// Weight of a triangle's face point in the "smooth triangle" edge rule.
const SMOOTH_TRIANGLE_FACE_WEIGHT: f64 = 0.470;

/// Smooth edge point: 1/4 per end vertex, the other half shared by the
/// incident faces' face points (1/4 each for a manifold edge, `1/(2n)` each for
/// `n` faces).
///
/// With [`TriangleSubdivision::Smooth`], an edge with exactly two faces of
/// which at least one is a triangle uses instead a face weight
/// `f = (f0 + f1)/2`, where `fi` is 0.47 for a triangle and 1/4 for any other
/// face size, and a vertex weight `(1 - 2f)/2`: two triangles give 0.47 and
/// 0.03, a triangle and a quad (or any other polygon) 0.36 and 0.14.
pub(super) fn smooth_edge_mask<T: Real>(
    face_sizes: &[u32],
    triangles: TriangleSubdivision,
    mask: &mut Mask<T>,
) {
    let faces = face_sizes.len();
    mask.reset(2, 0, faces);
    mask.face_weights_for_centers = true;

    let quarter = T::from_f64(0.25);
    let use_triangle_rule = triangles == TriangleSubdivision::Smooth
        && faces == 2
        && (face_sizes[0] == 3 || face_sizes[1] == 3);

    if use_triangle_rule {
        let tri = T::from_f64(SMOOTH_TRIANGLE_FACE_WEIGHT);
        let f0 = if face_sizes[0] == 3 { tri } else { quarter };
        let f1 = if face_sizes[1] == 3 { tri } else { quarter };
        let half = T::from_f64(0.5);
        let f = half * (f0 + f1);
        let v = half * (T::ONE - T::from_f64(2.0) * f);
        mask.vertex[0] = v;
        mask.vertex[1] = v;
        mask.face[0] = f;
        mask.face[1] = f;
        return;
    }

    mask.vertex[0] = quarter;
    mask.vertex[1] = quarter;
    let f = if faces == 2 {
        quarter
    } else {
        T::from_f64(0.5) / T::from_f64(faces as f64)
    };
    for w in &mut mask.face {
        *w = f;
    }
}

/// Smooth vertex point of valence `n` (number of faces): `(n-2)/n` on the
/// vertex and `1/n²` on each edge's far vertex and each face point.
/// Returns (vertex weight, edge weight = face weight).
pub(super) fn smooth_vertex_weights<T: Real>(valence: usize) -> (T, T) {
    let n = T::from_f64(valence as f64);
    let vertex = T::from_f64(valence as f64 - 2.0) / n;
    let edge = T::ONE / T::from_f64((valence * valence) as f64);
    (vertex, edge)
}

/// Smooth limit position with `n` faces (`n` edges).
pub(super) fn smooth_limit_mask<T: Real>(valence: usize, pos: &mut Mask<T>) {
    if valence == 2 {
        // Two faces sharing two edges: the limit is taken to be the vertex.
        pos.reset(1, 0, 0);
        pos.vertex[0] = T::ONE;
        return;
    }
    pos.reset(1, valence, valence);
    let (vertex, edge, face) = if valence == 4 {
        (
            T::from_f64(4.0 / 9.0),
            T::from_f64(1.0 / 9.0),
            T::from_f64(1.0 / 36.0),
        )
    } else {
        let n = T::from_f64(valence as f64);
        let face = T::ONE / (n * (n + T::from_f64(5.0)));
        let edge = T::from_f64(4.0) * face;
        (T::ONE - n * (edge + face), edge, face)
    };
    pos.vertex[0] = vertex;
    pos.edge.fill(edge);
    pos.face.fill(face);
}

/// Corner tangents: the first and second edges' directions (`e0 - v`,
/// `e1 - v`), with zero weights on any other edge. No face weights.
pub(super) fn corner_limit_tangents<T: Real>(edges: usize, tan1: &mut Mask<T>, tan2: &mut Mask<T>) {
    // A vertex has at least two edges; with fewer, the weights past the count
    // are dropped, as OpenSubdiv's count says.
    tan1.reset(1, edges.max(2), 0);
    tan2.reset(1, edges.max(2), 0);
    tan1.vertex[0] = -T::ONE;
    tan1.edge[0] = T::ONE;
    tan2.vertex[0] = -T::ONE;
    tan2.edge[1] = T::ONE;
    tan1.edge.truncate(edges);
    tan2.edge.truncate(edges);
}

/// Smooth tangents with `n` faces. Valence 4: the regular bicubic
/// derivatives scaled by 4 (edges `±4`, faces `±1`, vertex 0); valence 2:
/// corner tangents; otherwise the eigenvector tangents — edge `i`:
/// `4·cos(2πi/n)`, face `i`: `(cos(2πi/n) + cos(2π(i+1)/n)) / (4λ - 1)` with
/// λ the subdominant eigenvalue. The second tangent is the first rotated by
/// one edge (edge/face `i` of tan2 = edge/face `i-1` of tan1).
pub(super) fn smooth_limit_tangents<T: Real>(
    v: &VertexNeighborhood,
    tan1: &mut Mask<T>,
    tan2: &mut Mask<T>,
) {
    let n = v.face_count;
    if n == 2 {
        corner_limit_tangents(v.edge_count(), tan1, tan2);
        return;
    }
    tan1.reset(1, n, n);
    tan2.reset(1, n, n);
    if n == 4 {
        let four = T::from_f64(4.0);
        let one = T::ONE;
        tan1.edge.copy_from_slice(&[four, T::ZERO, -four, T::ZERO]);
        tan1.face.copy_from_slice(&[one, -one, -one, one]);
        tan2.edge.copy_from_slice(&[T::ZERO, four, T::ZERO, -four]);
        tan2.face.copy_from_slice(&[one, one, -one, -one]);
        return;
    }
    let theta = 2.0 * PI / n as f64;
    let cos_theta = theta.cos();
    let cos_half = (theta * 0.5).cos();
    let lambda =
        (5.0 / 16.0) + (1.0 / 16.0) * (cos_theta + cos_half * (2.0 * (9.0 + cos_theta)).sqrt());
    let edge_scale = 4.0;
    let face_scale = 1.0 / (4.0 * lambda - 1.0);
    for i in 0..n {
        let ci = (i as f64 * theta).cos();
        let cj = ((i + 1) as f64 * theta).cos();
        tan1.edge[i] = T::from_f64(edge_scale * ci);
        tan1.face[i] = T::from_f64(face_scale * (ci + cj));
    }
    for i in 0..n {
        let j = (i + n - 1) % n;
        tan2.edge[i] = tan1.edge[j];
        tan2.face[i] = tan1.face[j];
    }
}

/// Crease (and boundary) tangents. The first tangent runs along the crease:
/// `(e[c0] - e[c1]) / 2`. The second crosses the faces from the first crease
/// edge `c0` counter-clockwise to the second `c1`:
/// * one face between them: `-6 v + 3 e[c0] + 3 e[c1]`;
/// * two faces (the regular boundary): the B-spline cross derivative,
///   vertex `-4/6`, crease edges `-1/6`, middle edge `4/6`, the two faces'
///   diagonal vertices `1/6`;
/// * more: the formulae of Biermann et al. with `k` faces and `θ = π/k`.
///
/// Weights outside the span are zero.
pub(super) fn crease_limit_tangents<T: Real>(
    v: &VertexNeighborhood,
    ends: [usize; 2],
    tan1: &mut Mask<T>,
    tan2: &mut Mask<T>,
) {
    let edges = v.edge_count();
    let faces = v.face_count;
    let [c0, c1] = ends;

    tan1.reset(1, edges, faces);
    tan1.edge[c0] = T::from_f64(0.5);
    tan1.edge[c1] = T::from_f64(-0.5);

    // The face and edge buffers may have to hold the span even when the
    // counts are smaller (an inconsistent neighbourhood); size for it and
    // trim to the counts at the end.
    tan2.reset(1, edges.max(c1 + 1), faces.max(c1 + 1));
    let interior = c1 as isize - c0 as isize - 1;
    if interior == 1 {
        tan2.vertex[0] = T::from_f64(-4.0 / 6.0);
        tan2.edge[c0] = T::from_f64(-1.0 / 6.0);
        tan2.edge[c0 + 1] = T::from_f64(4.0 / 6.0);
        tan2.edge[c1] = T::from_f64(-1.0 / 6.0);
        tan2.face[c0] = T::from_f64(1.0 / 6.0);
        tan2.face[c0 + 1] = T::from_f64(1.0 / 6.0);
    } else if interior > 1 {
        let k = (interior + 1) as f64;
        let theta = PI / k;
        let cos_theta = theta.cos();
        let sin_theta = theta.sin();
        let denom = 1.0 / (k * (3.0 + cos_theta));
        let r = (cos_theta + 1.0) / sin_theta;
        let vertex = 4.0 * r * (cos_theta - 1.0);
        let crease = -r * (1.0 + 2.0 * cos_theta);

        tan2.vertex[0] = T::from_f64(vertex * denom);
        tan2.edge[c0] = T::from_f64(crease * denom);
        tan2.edge[c1] = T::from_f64(crease * denom);
        tan2.face[c0] = T::from_f64(sin_theta * denom);

        let mut sin_next = sin_theta;
        let mut i = 1usize;
        while (i as f64) < k {
            let sin_i = sin_next;
            sin_next = ((i + 1) as f64 * theta).sin();
            tan2.edge[c0 + i] = T::from_f64((4.0 * sin_i) * denom);
            tan2.face[c0 + i] = T::from_f64((sin_i + sin_next) * denom);
            i += 1;
        }
    } else {
        tan2.vertex[0] = T::from_f64(-6.0);
        tan2.edge[c0] = T::from_f64(3.0);
        tan2.edge[c1] = T::from_f64(3.0);
        tan2.face[c0] = T::ZERO;
    }
    tan2.edge.truncate(edges);
    tan2.face.truncate(faces);
}
