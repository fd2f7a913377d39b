//! Loop masks (OpenSubdiv's `Scheme<SCHEME_LOOP>`).
//!
//! Loop has no face points: face weights of edge masks apply to the vertex of
//! each face opposite the edge (`face_weights_for_centers` is false), and
//! vertex masks have no face weights. Irregular weights are computed in `f64`
//! and converted to `T` the way OpenSubdiv does (in double, rounding once).

use super::{Mask, VertexNeighborhood};
use crate::real::Real;
use std::f64::consts::PI;

/// √3, to the precision OpenSubdiv writes it.
const ROOT3: f64 = 1.732_050_807_568_877_3;

/// Smooth edge point: 3/8 per end vertex, 1/8 per opposite vertex (for a
/// non-manifold edge with `n` faces, `1/8 · 2/n` each).
pub(super) fn smooth_edge_mask<T: Real>(faces: usize, mask: &mut Mask<T>) {
    mask.reset(2, 0, faces);
    let v = T::from_f64(0.375);
    let mut f = T::from_f64(0.125);
    mask.vertex[0] = v;
    mask.vertex[1] = v;
    if faces != 2 {
        f *= T::from_f64(2.0) / T::from_f64(faces as f64);
    }
    mask.face.fill(f);
}

/// Loop's `β`-style edge weight of an interior vertex of valence `n`:
/// `(5/8 - (3/8 + cos(2π/n)/4)²) / n`, computed in `f64`.
fn irregular_edge_weight(valence: usize) -> f64 {
    let n = valence as f64;
    let inv = 1.0 / n;
    let cos_theta = (PI * 2.0 * inv).cos();
    let beta = 0.25 * cos_theta + 0.375;
    (0.625 - beta * beta) * inv
}

/// Smooth vertex point of valence `n`: 1/16 per neighbour and 5/8 on the
/// vertex when `n = 6`; otherwise Loop's weight
/// `w = (5/8 - (3/8 + cos(2π/n)/4)²) / n` per neighbour and `1 - n·w` on the
/// vertex (with `w` already rounded to `T`). Returns (vertex, edge).
pub(super) fn smooth_vertex_weights<T: Real>(valence: usize) -> (T, T) {
    if valence == 6 {
        return (T::from_f64(0.625), T::from_f64(0.0625));
    }
    let edge = T::from_f64(irregular_edge_weight(valence));
    let vertex = T::from_f64(1.0 - edge.to_f64() * valence as f64);
    (vertex, edge)
}

/// Smooth limit position with `n` faces: 1/2 on the vertex and 1/12 per
/// neighbour when `n = 6`; otherwise `1 / (n + 3/(8w))` per neighbour, with
/// `w` the refinement edge weight above, and the rest on the vertex.
pub(super) fn smooth_limit_mask<T: Real>(valence: usize, pos: &mut Mask<T>) {
    pos.reset(1, valence, 0);
    let (vertex, edge) = if valence == 6 {
        (T::from_f64(0.5), T::from_f64(1.0 / 12.0))
    } else {
        let n = valence as f64;
        let gamma = irregular_edge_weight(valence);
        let edge = T::from_f64(1.0 / (n + 3.0 / (8.0 * gamma)));
        (T::from_f64(1.0 - edge.to_f64() * n), edge)
    };
    pos.vertex[0] = vertex;
    pos.edge.fill(edge);
}

/// Corner tangents: `3 (e0 - v)` and `3 (e1 - v)` (OpenSubdiv scales corner
/// tangents by 3 to match the magnitude of the interior ones).
pub(super) fn corner_limit_tangents<T: Real>(edges: usize, tan1: &mut Mask<T>, tan2: &mut Mask<T>) {
    tan1.reset(1, edges.max(2), 0);
    tan2.reset(1, edges.max(2), 0);
    let three = T::from_f64(3.0);
    tan1.vertex[0] = -three;
    tan1.edge[0] = three;
    tan2.vertex[0] = -three;
    tan2.edge[1] = three;
    tan1.edge.truncate(edges);
    tan2.edge.truncate(edges);
}

/// Crease (and boundary) tangents. Along the crease: `1.5 (e[c0] - e[c1])`.
/// Across, over the `m` interior edges from `c0` counter-clockwise to `c1`:
/// * `m = 0`: `-6 v + 3 e[c0] + 3 e[c1]`;
/// * `m = 1`: `3 (e[c0+1] - v)`;
/// * `m = 2` (regular): `√3 (e[c0+1] + e[c0+2] - v) - √3/2 (e[c0] + e[c1])`;
/// * `m > 2`: with `θ = π/(m+1)`, `-3 sin θ` on both crease edges and
///   `6 (1 - cos θ) sin(iθ)` on interior edge `i`, none on the vertex.
pub(super) fn crease_limit_tangents<T: Real>(
    v: &VertexNeighborhood,
    ends: [usize; 2],
    tan1: &mut Mask<T>,
    tan2: &mut Mask<T>,
) {
    let edges = v.edge_count();
    let [c0, c1] = ends;

    tan1.reset(1, edges, 0);
    tan1.edge[c0] = T::from_f64(1.5);
    tan1.edge[c1] = T::from_f64(-1.5);

    tan2.reset(1, edges, 0);
    let interior = c1 as isize - c0 as isize - 1;
    if interior == 2 {
        let root3 = T::from_f64(ROOT3);
        let root3_by_2 = T::from_f64(root3.to_f64() * 0.5);
        tan2.vertex[0] = -root3;
        tan2.edge[c0] = -root3_by_2;
        tan2.edge[c1] = -root3_by_2;
        tan2.edge[c0 + 1] = root3;
        tan2.edge[c0 + 2] = root3;
    } else if interior > 2 {
        let m = interior as usize;
        let theta = PI / (m + 1) as f64;
        tan2.vertex[0] = T::ZERO;
        let crease = T::from_f64(-3.0 * theta.sin());
        tan2.edge[c0] = crease;
        tan2.edge[c1] = crease;
        let coeff = -3.0 * 2.0 * (theta.cos() - 1.0);
        for i in 1..=m {
            tan2.edge[c0 + i] = T::from_f64(coeff * (i as f64 * theta).sin());
        }
    } else if interior == 1 {
        let three = T::from_f64(3.0);
        tan2.vertex[0] = -three;
        tan2.edge[c0] = T::ZERO;
        tan2.edge[c1] = T::ZERO;
        tan2.edge[c0 + 1] = three;
    } else {
        let three = T::from_f64(3.0);
        tan2.vertex[0] = T::from_f64(-6.0);
        tan2.edge[c0] = three;
        tan2.edge[c1] = three;
    }
}

/// Smooth tangents with `n` faces: edge `i` gets `cos(2πi/n)` in the first
/// tangent and `sin(2πi/n)` in the second (valence 6 written out exactly:
/// `1, 1/2, -1/2, -1, -1/2, 1/2` and `0, √3/2, √3/2, 0, -√3/2, -√3/2`); no
/// vertex or face weights.
pub(super) fn smooth_limit_tangents<T: Real>(
    v: &VertexNeighborhood,
    tan1: &mut Mask<T>,
    tan2: &mut Mask<T>,
) {
    let n = v.face_count;
    tan1.reset(1, n, 0);
    tan2.reset(1, n, 0);
    if n == 6 {
        let one = T::ONE;
        let half = T::from_f64(0.5);
        let r = T::from_f64(0.5 * ROOT3);
        tan1.edge
            .copy_from_slice(&[one, half, -half, -one, -half, half]);
        tan2.edge.copy_from_slice(&[T::ZERO, r, r, T::ZERO, -r, -r]);
        return;
    }
    let alpha = 2.0 * PI / n as f64;
    for i in 0..n {
        let a = alpha * i as f64;
        tan1.edge[i] = T::from_f64(a.cos());
        tan2.edge[i] = T::from_f64(a.sin());
    }
}
