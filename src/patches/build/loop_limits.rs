//! Loop limit position and the two edge points along the patch's edges, as
//! weights of a corner's ring (`Far::LoopLimits`): unlike the Catmull-Clark
//! end caps' own formulae, these start from `Sdc`'s Loop limit masks
//! ([`SchemeRules::vertex_limit_masks`], the position and the two tangents)
//! and move a point along the tangent towards each edge. Weights are
//! `[vertex, ring...]`, `1 + valence` of them, in the weight type `R`.

use crate::options::{Options, Scheme};
use crate::real::Real;
use crate::rules::{
    Mask, Rule, SHARPNESS_INFINITE, SHARPNESS_SMOOTH, SchemeRules, VertexNeighborhood,
};
use std::f64::consts::PI;

/// The position and tangent masks of a vertex of `faces` faces and `edges`
/// edges under `rule`, each as `1 + edges` weights (vertex first).
fn masks<R: Real>(faces: usize, edges: usize, rule: Rule) -> [Vec<R>; 3] {
    // A boundary vertex's first and last edges are its crease.
    let mut sharpness = vec![SHARPNESS_SMOOTH; edges];
    if rule == Rule::Crease {
        if let Some(first) = sharpness.first_mut() {
            *first = SHARPNESS_INFINITE;
        }
        if let Some(last) = sharpness.last_mut() {
            *last = SHARPNESS_INFINITE;
        }
    }
    let v = VertexNeighborhood {
        sharpness: SHARPNESS_SMOOTH,
        edge_sharpness: &sharpness,
        face_count: faces,
        child_sharpness: SHARPNESS_SMOOTH,
        child_edge_sharpness: &[],
    };
    let rules = SchemeRules::new(&Options::default().with_scheme(Scheme::Loop));
    let (mut p, mut t1, mut t2) = (Mask::new(), Mask::new(), Mask::new());
    rules.vertex_limit_masks(&v, rule, &mut p, &mut t1, &mut t2);
    [p, t1, t2].map(|m| {
        let mut w = vec![R::ZERO; 1 + edges];
        w[0] = m.vertex.first().copied().unwrap_or(R::ZERO);
        for (x, &e) in w[1..].iter_mut().zip(&m.edge) {
            *x = e;
        }
        w
    })
}

/// `t2` rotated so that its first edge weight lands on ring entry
/// `first_edge` (OpenSubdiv's two `memcpy`s).
fn rotated<R: Real>(t2: &[R], first_edge: usize) -> Vec<R> {
    let valence = t2.len() - 1;
    let n1 = first_edge.min(valence);
    let n2 = valence - n1;
    let mut w = Vec::with_capacity(t2.len());
    w.push(t2[0]);
    w.extend_from_slice(&t2[1 + n2..]);
    w.extend_from_slice(&t2[1..1 + n2]);
    w
}

/// Weights of the limit point `p` of an interior vertex of `valence` and,
/// when asked, the edge points `ep`, `em` along the edges leading and
/// trailing face `face_in_ring` (`ComputeInteriorPointWeights`).
pub(super) fn interior<R: Real>(valence: usize, face_in_ring: usize, edges: bool) -> [Vec<R>; 3] {
    let valence = valence.max(1);
    let [p, t1, _] = masks::<R>(valence, valence, Rule::Smooth);
    if !edges {
        return [p, Vec::new(), Vec::new()];
    }
    // The first tangent scaled by the subdominant eigenvalue (with the
    // normalisations of the mask and of a cubic's point), added to the
    // limit point: the point along the first edge, rotated to each edge.
    let theta = 2.0 * PI / valence as f64;
    let scale = R::from_f64((3.0 + 2.0 * theta.cos()) / (6.0 * valence as f64));
    let along: Vec<R> = p.iter().zip(&t1).map(|(&p, &t)| p + t * scale).collect();
    let ep = rotated(&along, face_in_ring);
    let em = rotated(&along, (face_in_ring + 1) % valence);
    [p, ep, em]
}

/// Weights of the limit point of a boundary vertex of `valence` edges
/// (`valence - 1` faces; its ring from the leading boundary edge) and,
/// when asked, the edge points of face `face_in_ring`
/// (`ComputeBoundaryPointWeights`): along a boundary edge 2/3 and 1/3,
/// elsewhere the limit point moved along the boundary tangent and the
/// tangent across it, turned towards the edge.
pub(super) fn boundary<R: Real>(valence: usize, face_in_ring: usize, edges: bool) -> [Vec<R>; 3] {
    let valence = valence.max(2);
    let [p, _, t2] = masks::<R>(valence - 1, valence, Rule::Crease);
    if !edges {
        return [p, Vec::new(), Vec::new()];
    }
    let width = valence + 1;
    let leading = R::from_f64(1.0 / 6.0);
    let trailing = -R::from_f64(1.0 / 6.0);
    let t2_scale = R::from_f64(1.0 / 24.0);
    let face_angle = R::from_f64(PI / (valence - 1) as f64);
    let edge_point = |on_edge: Option<usize>, edge: usize| -> Vec<R> {
        let mut e = vec![R::ZERO; width];
        if let Some(end) = on_edge {
            e[0] = R::from_f64(2.0 / 3.0);
            e[end] = R::from_f64(1.0 / 3.0);
            return e;
        }
        let angle = face_angle * R::from_f64(edge as f64);
        let (cos_a, sin_a) = (angle.cos(), angle.sin());
        for (x, &t) in e.iter_mut().zip(&t2) {
            *x = t2_scale * t * sin_a;
        }
        e[0] += p[0];
        e[1] += p[1] + leading * cos_a;
        e[valence] += p[valence] + trailing * cos_a;
        e
    };
    // OpenSubdiv compares the trailing face with the edge count, so `em` is
    // never the boundary form (its weights along a boundary edge are
    // replaced by the converters anyway).
    let ep = edge_point((face_in_ring == 0).then_some(1), face_in_ring);
    let em = edge_point(
        (face_in_ring == valence - 1).then_some(valence),
        (face_in_ring + 1) % valence,
    );
    [p, ep, em]
}
