//! Catmull-Clark limit position and the two edge points along the patch's
//! edges, as weights of a corner's ring (`Far::CatmarkLimits`, the formulae
//! OpenSubdiv's end caps use — not `Sdc`'s limit masks: the tangent scale
//! differs). Intermediate values are `f64` and cast to the weight type
//! where OpenSubdiv casts them, so `f32` weights come out bit for bit.

use crate::real::Real;
use std::f64::consts::PI;

/// The eigenvalue scale of the tangents at an interior vertex of
/// `valence` (OpenSubdiv's table up to 29, its formula beyond).
fn coefficient(valence: usize) -> f64 {
    // OpenSubdiv's literals digit for digit (they round to the same f64s).
    #[allow(clippy::excessive_precision)]
    const TABLE: [f64; 30] = [
        0.0,
        0.0,
        0.0,
        8.1281572906372312e-01,
        0.5,
        3.6364406329142801e-01,
        2.8751379706077085e-01,
        2.3868786685851678e-01,
        2.0454364190756097e-01,
        1.7922903958061159e-01,
        1.5965737079986253e-01,
        1.4404233443011302e-01,
        1.3127568415883017e-01,
        1.2063172212675841e-01,
        1.1161437506676930e-01,
        1.0387245516114274e-01,
        9.7150019090724835e-02,
        9.1255917505950648e-02,
        8.6044378511602668e-02,
        8.1402211336798411e-02,
        7.7240129516184072e-02,
        7.3486719751997026e-02,
        7.0084157479797987e-02,
        6.6985104030725440e-02,
        6.4150420569810074e-02,
        6.1547457638637268e-02,
        5.9148757447233989e-02,
        5.6931056818776957e-02,
        5.4874512279256417e-02,
        5.2962091433796134e-02,
    ];
    if let Some(&c) = TABLE.get(valence) {
        return c;
    }
    let inv = 1.0 / valence as f64;
    let cos_t = (2.0 * PI * inv).cos();
    let divisor = (cos_t + 5.0) + ((cos_t + 9.0) * (cos_t + 1.0)).sqrt();
    16.0 * inv / divisor
}

/// Weights of the vertex (entry 0) and its ring (`1 + 2 * valence`
/// entries) for the limit point `p` of an interior vertex and, when
/// asked, the edge points `ep`, `em` along the edges leading and trailing
/// face `face_in_ring` (`ComputeInteriorPointWeights`).
pub(super) fn interior<R: Real>(valence: usize, face_in_ring: usize, edges: bool) -> [Vec<R>; 3] {
    let width = 1 + 2 * valence;
    let f = valence as f64;
    let one_over_valence = 1.0 / f;
    let one_over_plus5 = 1.0 / (f + 5.0);
    let p_coeff = one_over_valence * one_over_plus5;
    let tan_coeff = coefficient(valence) * 0.5 * one_over_plus5;
    let face_angle = 2.0 * PI * one_over_valence;
    let mut p = vec![R::ZERO; width];
    let mut tan = vec![R::ZERO; width];
    p[0] = R::from_f64(f * one_over_plus5);
    for i in 0..valence {
        p[1 + 2 * i] = R::from_f64(p_coeff * 4.0);
        p[2 + 2 * i] = R::from_f64(p_coeff);
        if edges {
            let prev = (i + valence - 1) % valence;
            let next = (i + 1) % valence;
            let c = tan_coeff * (face_angle * i as f64).cos();
            tan[1 + 2 * prev] += R::from_f64(c * 2.0);
            tan[2 + 2 * prev] += R::from_f64(c);
            tan[1 + 2 * i] += R::from_f64(c * 4.0);
            tan[2 + 2 * i] += R::from_f64(c);
            tan[1 + 2 * next] += R::from_f64(c * 2.0);
        }
    }
    if !edges {
        return [p, Vec::new(), Vec::new()];
    }
    let ep_offset = 2 * ((valence - face_in_ring % valence) % valence);
    let em_offset = 2 * ((2 * valence - face_in_ring % valence - 1) % valence);
    let (mut ep, mut em) = (vec![p[0]; width], vec![p[0]; width]);
    for i in 1..width {
        let wrap = |k: usize| if k >= width { k - (width - 1) } else { k };
        ep[i] = p[i] + tan[wrap(i + ep_offset)];
        em[i] = p[i] + tan[wrap(i + em_offset)];
    }
    [p, ep, em]
}

/// Weights of the vertex and its boundary ring (`2 * valence` entries:
/// the vertex, then the ring from the leading boundary edge) for the limit
/// point and, when asked, the edge points of face `face_in_ring`
/// (`ComputeBoundaryPointWeights`); `valence` counts edges.
pub(super) fn boundary<R: Real>(valence: usize, face_in_ring: usize, edges: bool) -> [Vec<R>; 3] {
    let faces = valence.saturating_sub(1).max(1);
    let face_angle = PI / faces as f64;
    let width = 2 * valence;
    let n = width - 1;
    let mut p = vec![R::ZERO; width];
    p[0] = R::from_f64(4.0 / 6.0);
    p[1] = R::from_f64(1.0 / 6.0);
    p[n] = R::from_f64(1.0 / 6.0);
    if !edges {
        return [p, Vec::new(), Vec::new()];
    }
    let (t1, tn) = (1.0 / 6.0, -1.0 / 6.0);
    let mut tan = vec![R::ZERO; width];
    let k = faces as f64;
    let theta = face_angle;
    let (c, s) = (theta.cos(), theta.sin());
    let div3 = 1.0 / 3.0;
    let div3kc = 1.0 / (3.0 * k + c);
    let gamma = -4.0 * s * div3kc;
    let alpha_0k = -((1.0 + 2.0 * c) * (1.0 + c).sqrt()) * div3kc / (1.0 - c).sqrt();
    let beta_0 = s * div3kc;
    tan[0] = R::from_f64(gamma * div3);
    tan[1] = R::from_f64(alpha_0k * div3);
    tan[2] = R::from_f64(beta_0 * div3);
    tan[n] = R::from_f64(alpha_0k * div3);
    for i in 1..valence.saturating_sub(1) {
        let sin_i = (theta * i as f64).sin();
        let sin_i1 = (theta * (i + 1) as f64).sin();
        let alpha = 4.0 * sin_i * div3kc;
        let beta = (sin_i + sin_i1) * div3kc;
        tan[1 + 2 * i] = R::from_f64(alpha * div3);
        tan[2 + 2 * i] = R::from_f64(beta * div3);
    }
    let edge_point = |on_boundary: bool, end: usize, edge: usize| -> Vec<R> {
        let mut e = vec![R::ZERO; width];
        if on_boundary {
            e[0] = R::from_f64(2.0 / 3.0);
            e[end] = R::from_f64(1.0 / 3.0);
            return e;
        }
        let angle = face_angle * edge as f64;
        let (cos_a, sin_a) = (angle.cos(), angle.sin());
        for (x, &t) in e.iter_mut().zip(&tan) {
            *x = R::from_f64(t.to_f64() * sin_a);
        }
        e[0] += p[0];
        e[1] += p[1] + R::from_f64(t1 * cos_a);
        e[n] += p[n] + R::from_f64(tn * cos_a);
        e
    };
    let ep = edge_point(face_in_ring == 0, 1, face_in_ring);
    let em = edge_point(face_in_ring + 1 == faces, n, (face_in_ring + 1) % valence);
    [p, ep, em]
}
