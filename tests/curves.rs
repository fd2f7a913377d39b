//! Subdivision curves against hand-derived values and analytic curves, and
//! points files. (`subdiv curve` is tested in `tests/cli/curve.rs`.)

mod support;

use glam::{DVec2, DVec3};
use std::path::Path;
use subdiv::curve::{
    self, BSplineCurve, CurveError, CurveScheme, DEFAULT_TENSION, MAX_DEGREE, Point, bspline_basis,
    flatness_bound,
};
use subdiv::io::points::{Points, PointsErrorKind};
use support::Rng;

// ---------------------------------------------------------------------------
// helpers
// ---------------------------------------------------------------------------

/// Small integer points: every operation of the schemes on them is exact.
fn int_points(n: usize, seed: u64) -> Vec<DVec2> {
    let mut rng = Rng(seed);
    (0..n)
        .map(|_| DVec2::new((rng.next() * 50.0).round(), (rng.next() * 50.0).round()))
        .collect()
}

fn binom(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

const ALL_SCHEMES: [CurveScheme; 8] = [
    CurveScheme::Chaikin,
    CurveScheme::BSpline { degree: 1 },
    CurveScheme::BSpline { degree: 2 },
    CurveScheme::BSpline { degree: 3 },
    CurveScheme::BSpline { degree: 4 },
    CurveScheme::BSpline { degree: 5 },
    CurveScheme::FourPoint {
        tension: DEFAULT_TENSION,
    },
    CurveScheme::Jarek,
];

// ---------------------------------------------------------------------------
// counts and conventions
// ---------------------------------------------------------------------------

#[test]
fn counts_follow_the_conventions_for_every_scheme_degree_and_level() {
    for scheme in ALL_SCHEMES {
        for closed in [false, true] {
            let n0 = scheme.min_points(closed) + 2;
            let p = int_points(n0, 7);
            let levels = curve::refine_levels(&p, scheme, closed, 4).unwrap();
            assert_eq!(levels.len(), 5);
            let mut n = n0;
            for (k, level) in levels.iter().enumerate() {
                assert_eq!(level.len(), n, "{scheme} closed={closed} level {k}");
                n = if closed {
                    2 * n
                } else {
                    match scheme {
                        CurveScheme::Chaikin => 2 * n - 2,
                        CurveScheme::BSpline { degree } => 2 * n - degree,
                        _ => 2 * n - 1,
                    }
                };
            }
        }
    }
}

#[test]
fn chaikin_hand_values_open_and_closed() {
    let p = [
        DVec2::new(0.0, 0.0),
        DVec2::new(4.0, 0.0),
        DVec2::new(4.0, 4.0),
    ];
    let open = curve::chaikin(&p, false).unwrap();
    assert_eq!(
        open,
        [
            DVec2::new(1.0, 0.0),
            DVec2::new(3.0, 0.0),
            DVec2::new(4.0, 1.0),
            DVec2::new(4.0, 3.0),
        ]
    );
    let closed = curve::chaikin(&p, true).unwrap();
    assert_eq!(&closed[..4], &open[..]);
    // The closing edge P2 → P0: Q2 = 3/4 (4,4) + 1/4 (0,0), R2 = 1/4 (4,4) + 3/4 (0,0).
    assert_eq!(&closed[4..], &[DVec2::new(3.0, 3.0), DVec2::new(1.0, 1.0)]);
}

#[test]
fn bspline_is_the_binomial_mask_for_degrees_1_to_5() {
    // Lane-Riesenfeld: one level of degree d is the mask C(d+1, k) / 2^d:
    // b[m] = Σ_j C(d+1, m + d - 2j) / 2^d P[j] (indices mod n when closed).
    for degree in 1..=5 {
        for closed in [false, true] {
            let n = 7;
            let p = int_points(n, degree as u64 * 13 + closed as u64);
            let b = curve::bspline(&p, degree, closed).unwrap();
            for (m, &got) in b.iter().enumerate() {
                let mut expected = DVec2::ZERO;
                for j in -(n as i64)..2 * n as i64 {
                    let k = m as i64 + degree as i64 - 2 * j;
                    if !(0..=degree as i64 + 1).contains(&k) {
                        continue;
                    }
                    let pj = if closed {
                        p[j.rem_euclid(n as i64) as usize]
                    } else if (0..n as i64).contains(&j) {
                        p[j as usize]
                    } else {
                        panic!("open degree {degree}: point {m} needs P[{j}]");
                    };
                    expected += pj * (binom(degree + 1, k as usize) / (1u64 << degree) as f64);
                }
                assert_eq!(got, expected, "degree {degree} closed={closed} point {m}");
            }
        }
    }
}

#[test]
fn bspline_degree_2_is_chaikin_and_degree_1_inserts_midpoints() {
    for closed in [false, true] {
        let p = int_points(6, 99);
        let a = curve::refine(&p, CurveScheme::Chaikin, closed, 3).unwrap();
        let b = curve::refine(&p, CurveScheme::bspline(2), closed, 3).unwrap();
        assert_eq!(a, b);
        let lin = curve::bspline(&p, 1, closed).unwrap();
        for (j, &pj) in p.iter().enumerate() {
            assert_eq!(lin[2 * j], pj);
            if 2 * j + 1 < lin.len() {
                assert_eq!(lin[2 * j + 1], (pj + p[(j + 1) % p.len()]) / 2.0);
            }
        }
    }
}

#[test]
fn cubic_bspline_vertex_and_edge_rules() {
    // Closed: b[2j] = M[j], b[2j+1] = (P[j] + 6 P[j+1] + P[j+2]) / 8.
    let p = int_points(5, 3);
    let n = p.len();
    let b = curve::bspline(&p, 3, true).unwrap();
    for j in 0..n {
        let (p0, p1, p2) = (p[j], p[(j + 1) % n], p[(j + 2) % n]);
        assert_eq!(b[2 * j], (p0 + p1) / 2.0);
        assert_eq!(b[2 * j + 1], (p0 + p1 * 6.0 + p2) / 8.0);
    }
    // Open: the same without the wrap, 2n - 3 points from M[0] to M[n-2].
    let b = curve::bspline(&p, 3, false).unwrap();
    assert_eq!(b.len(), 2 * n - 3);
    assert_eq!(b[0], (p[0] + p[1]) / 2.0);
    assert_eq!(b[1], (p[0] + p[1] * 6.0 + p[2]) / 8.0);
    assert_eq!(b[2 * n - 4], (p[n - 2] + p[n - 1]) / 2.0);
}

#[test]
fn four_point_hand_values_ghosts_and_interpolation() {
    let p = [
        DVec2::new(0.0, 0.0),
        DVec2::new(16.0, 0.0),
        DVec2::new(32.0, 16.0),
        DVec2::new(48.0, 16.0),
    ];
    let q = curve::four_point(&p, DEFAULT_TENSION, false).unwrap();
    assert_eq!(q.len(), 7);
    // E0 with the ghost P[-1] = 2 P0 - P1 = (-16, 0):
    // (-(-16, 0) + 9 (0, 0) + 9 (16, 0) - (32, 16)) / 16 = (128, -16) / 16.
    assert_eq!(q[1], DVec2::new(8.0, -1.0));
    assert_eq!(q[3], DVec2::new(24.0, 8.0));
    // E2 with the ghost P[4] = 2 P3 - P2 = (64, 16).
    assert_eq!(q[5], DVec2::new(40.0, 17.0));
    let closed = curve::four_point(&p, DEFAULT_TENSION, true).unwrap();
    assert_eq!(closed.len(), 8);
    // E3 between P3 and P0: (-P2 + 9 P3 + 9 P0 - P1) / 16 = (384, 128) / 16.
    assert_eq!(closed[7], DVec2::new(24.0, 8.0));
    // Interpolation: the old points stay, level after level.
    for closed in [false, true] {
        let p = int_points(6, 5);
        let mut cur = p.clone();
        for _ in 0..4 {
            let next = curve::four_point(&cur, DEFAULT_TENSION, closed).unwrap();
            for (i, &pi) in cur.iter().enumerate() {
                assert_eq!(next[2 * i], pi);
            }
            cur = next;
        }
    }
}

#[test]
fn four_point_reproduces_cubics_and_tension_zero_is_linear() {
    // Points on the cubic (t, t³ - 2t) at integers: every inserted point away
    // from the ghosts lies on the cubic at the half-integer.
    let f = |t: f64| DVec2::new(t, t * t * t - 2.0 * t);
    let p: Vec<DVec2> = (0..8).map(|i| f(i as f64)).collect();
    let q = curve::four_point(&p, DEFAULT_TENSION, false).unwrap();
    for i in 1..p.len() - 2 {
        assert_eq!(q[2 * i + 1], f(i as f64 + 0.5), "E[{i}]");
    }
    let lin = curve::four_point(&p, 0.0, true).unwrap();
    assert_eq!(lin, curve::bspline(&p, 1, true).unwrap());
    // Two points: the ghosts continue the line, the result is the segment's midpoint.
    let two = curve::four_point(&[DVec2::ZERO, DVec2::new(2.0, 4.0)], 0.25, false).unwrap();
    assert_eq!(
        two,
        [DVec2::ZERO, DVec2::new(1.0, 2.0), DVec2::new(2.0, 4.0)]
    );
}

#[test]
fn jarek_hand_values_and_kept_end_points() {
    let p = [
        DVec2::new(0.0, 0.0),
        DVec2::new(16.0, 0.0),
        DVec2::new(16.0, 16.0),
        DVec2::new(0.0, 16.0),
    ];
    let q = curve::jarek(&p, true).unwrap();
    // Midpoints (8,0) (16,8) (8,16) (0,8). P0 moves a quarter of the way to
    // ((0,8) + (8,0)) / 2 = (4,4): (1,1). M0 moves by ((8,0) - (8,8)) / 8 = (0,-1).
    assert_eq!(
        q,
        [
            DVec2::new(1.0, 1.0),
            DVec2::new(8.0, -1.0),
            DVec2::new(15.0, 1.0),
            DVec2::new(17.0, 8.0),
            DVec2::new(15.0, 15.0),
            DVec2::new(8.0, 17.0),
            DVec2::new(1.0, 15.0),
            DVec2::new(-1.0, 8.0),
        ]
    );
    let open = curve::jarek(&p, false).unwrap();
    assert_eq!(open.len(), 7);
    assert_eq!(open[0], p[0]);
    assert_eq!(open[6], p[3]);
    // M0 with the ghost midpoint M[-1] = ((-16,0) + (0,0)) / 2 = (-8,0):
    // (8,0) + ((8,0) - ((-8,0) + (16,8)) / 2) / 8 = (8,0) + (4,-4) / 8.
    assert_eq!(open[1], DVec2::new(8.5, -0.5));
    assert_eq!(open[2], q[2]);
    // The ends stay at every level, for random input too.
    let r = {
        let mut rng = Rng(11);
        (0..5).map(|_| rng.v3(3.0)).collect::<Vec<_>>()
    };
    let fine = curve::refine(&r, CurveScheme::Jarek, false, 5).unwrap();
    assert_eq!(fine[0], r[0]);
    assert_eq!(fine[fine.len() - 1], r[4]);
}

#[test]
fn jarek_is_half_way_between_the_cubic_bspline_and_the_four_point_scheme() {
    let mut rng = Rng(21);
    let p: Vec<DVec3> = (0..9).map(|_| rng.v3(3.0)).collect();
    let j = curve::jarek(&p, true).unwrap();
    let f = curve::four_point(&p, DEFAULT_TENSION, true).unwrap();
    let b = curve::bspline(&p, 3, true).unwrap();
    // The cubic B-spline output starts at M0; rotate it to start at P0's new position.
    let m = b.len();
    for k in 0..m {
        let bk = b[(k + m - 1) % m];
        let half = (bk + f[k]) * 0.5;
        assert!((j[k] - half).length() < 1e-14, "point {k}");
    }
}

#[test]
fn linear_data_stays_linear_in_every_scheme() {
    // Equally spaced collinear points: every scheme keeps them on the line with
    // half the spacing (open polygons thanks to the ghost points).
    let p: Vec<DVec2> = (0..6)
        .map(|i| DVec2::new(i as f64, 2.0 * i as f64))
        .collect();
    for scheme in [
        CurveScheme::four_point(),
        CurveScheme::Jarek,
        CurveScheme::bspline(1),
    ] {
        let q = curve::refine_once(&p, scheme, false).unwrap();
        for (k, &x) in q.iter().enumerate() {
            assert_eq!(
                x,
                DVec2::new(k as f64 / 2.0, k as f64),
                "{scheme} point {k}"
            );
        }
    }
}

// ---------------------------------------------------------------------------
// B-spline basis and evaluation
// ---------------------------------------------------------------------------

/// The Cox-de Boor recurrence for the cardinal B-spline, independent of the
/// truncated powers: N_0 = [0 ≤ x < 1], N_d(x) = (x N_{d-1}(x) + (d+1-x) N_{d-1}(x-1)) / d.
fn cox_de_boor(d: usize, x: f64) -> f64 {
    if d == 0 {
        return if (0.0..1.0).contains(&x) { 1.0 } else { 0.0 };
    }
    (x * cox_de_boor(d - 1, x) + (d as f64 + 1.0 - x) * cox_de_boor(d - 1, x - 1.0)) / d as f64
}

#[test]
fn basis_matches_cox_de_boor_and_hand_values() {
    for d in 0..=8 {
        for i in 0..=400 {
            let x = -0.5 + (d as f64 + 2.0) * i as f64 / 400.0;
            let (a, b) = (bspline_basis(d, x), cox_de_boor(d, x));
            assert!((a - b).abs() < 1e-13, "N_{d}({x}) = {a}, Cox-de Boor {b}");
        }
    }
    assert_eq!(bspline_basis(3, 1.0), 1.0 / 6.0);
    assert_eq!(bspline_basis(3, 3.0), 1.0 / 6.0);
    assert!((bspline_basis(3, 2.0) - 2.0 / 3.0).abs() < 1e-16);
    assert_eq!(bspline_basis(2, 1.0), 0.5);
    assert_eq!(bspline_basis(2, 0.5), 0.125);
    assert_eq!(bspline_basis(4, -1e-9), 0.0);
    assert_eq!(bspline_basis(4, 5.0), 0.0);
    assert_eq!(bspline_basis(4, f64::NAN), 0.0);
    // Partition of unity.
    for d in 1..=MAX_DEGREE {
        let x = 0.3721;
        let sum: f64 = (0..=d).map(|k| bspline_basis(d, x + k as f64)).sum();
        assert!((sum - 1.0).abs() < 1e-10, "degree {d}: {sum}");
    }
}

fn check_refinement_identity<P: Point>(points: &[P], degree: usize, closed: bool) {
    let c0 = BSplineCurve::new(points.to_vec(), degree, closed).unwrap();
    let (_, s_max) = c0.domain();
    for k in 1..=4u32 {
        let refined = curve::refine(points, CurveScheme::BSpline { degree }, closed, k).unwrap();
        let ck = BSplineCurve::new(refined, degree, closed).unwrap();
        assert_eq!(ck.domain().1, s_max * f64::from(1u32 << k));
        let scale = f64::from(1u32 << k);
        for i in 0..=500 {
            let s = s_max * i as f64 / 500.0;
            let (a, b) = (c0.eval(s).unwrap(), ck.eval(s * scale).unwrap());
            assert!(
                (a - b).length() < 1e-12,
                "degree {degree} closed={closed} k={k} s={s}: {a:?} vs {b:?}"
            );
        }
    }
}

#[test]
fn after_k_levels_the_polygon_controls_the_same_curve_at_half_the_knot_spacing() {
    let mut rng = Rng(2024);
    for degree in 1..=5 {
        for closed in [false, true] {
            let p2: Vec<DVec2> = (0..degree + 4).map(|_| rng.v2(3.0)).collect();
            check_refinement_identity(&p2, degree, closed);
            let p3: Vec<DVec3> = (0..degree + 3).map(|_| rng.v3(3.0)).collect();
            check_refinement_identity(&p3, degree, closed);
        }
    }
}

#[test]
fn segment_bezier_points_of_a_cubic_and_evaluation_agree() {
    let mut rng = Rng(8);
    let p: Vec<DVec2> = (0..6).map(|_| rng.v2(3.0)).collect();
    let c = BSplineCurve::new(p.clone(), 3, false).unwrap();
    let b = c.segment_bezier(1).unwrap();
    assert!(c.segment_bezier(3).is_none());
    let close = |a: DVec2, b: DVec2| (a - b).length() < 1e-14;
    assert!(close(b[0], (p[1] + p[2] * 4.0 + p[3]) / 6.0));
    assert!(close(b[1], (p[2] * 2.0 + p[3]) / 3.0));
    assert!(close(b[2], (p[2] + p[3] * 2.0) / 3.0));
    assert!(close(b[3], (p[2] + p[3] * 4.0 + p[4]) / 6.0));
    for degree in 1..=5 {
        for closed in [false, true] {
            let p: Vec<DVec3> = (0..degree + 3).map(|_| rng.v3(3.0)).collect();
            let c = BSplineCurve::new(p, degree, closed).unwrap();
            for seg in 0..c.segment_count() {
                let bez = c.segment_bezier(seg).unwrap();
                for i in 0..=20 {
                    let t = i as f64 / 20.0;
                    let mut sum = DVec3::ZERO;
                    for (k, &bk) in bez.iter().enumerate() {
                        sum += bk
                            * (binom(degree, k)
                                * t.powi(k as i32)
                                * (1.0 - t).powi((degree - k) as i32));
                    }
                    let e = c.eval(seg as f64 + t).unwrap();
                    assert!(
                        (sum - e).length() < 1e-13,
                        "degree {degree} seg {seg} t {t}"
                    );
                }
            }
        }
    }
}

#[test]
fn closed_curves_are_periodic_and_open_ones_refuse_outside_parameters() {
    let mut rng = Rng(5);
    let p: Vec<DVec2> = (0..5).map(|_| rng.v2(3.0)).collect();
    let closed = BSplineCurve::new(p.clone(), 3, true).unwrap();
    for s in [0.0, 0.3, 2.7, 4.99] {
        let a = closed.eval(s).unwrap();
        assert!((a - closed.eval(s + 5.0).unwrap()).length() < 1e-13);
        assert!((a - closed.eval(s - 10.0).unwrap()).length() < 1e-13);
    }
    let open = BSplineCurve::new(p, 3, false).unwrap();
    assert_eq!(open.domain(), (0.0, 2.0));
    assert!(open.eval(2.0).is_ok());
    for s in [-1e-9, 2.000001, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            open.eval(s),
            Err(CurveError::ParameterOutOfRange { .. })
        ));
    }
    assert!(closed.eval(f64::NAN).is_err());
}

#[test]
fn chaikin_limit_is_the_parabolas_between_edge_midpoints() {
    // The limit of Chaikin's polygon is, between the midpoints M[i] and M[i+1]
    // of consecutive edges, the parabola with control point P[i+1]:
    // (1-t)² M[i] + 2t(1-t) P[i+1] + t² M[i+1]. The edge midpoints of the
    // polygon after k levels lie on it at t = frac(a / 2^k).
    let mut rng = Rng(77);
    for closed in [false, true] {
        let p: Vec<DVec2> = (0..7).map(|_| rng.v2(3.0)).collect();
        let n = p.len();
        let parabola = |i: usize, t: f64| {
            let m0 = (p[i % n] + p[(i + 1) % n]) / 2.0;
            let m1 = (p[(i + 1) % n] + p[(i + 2) % n]) / 2.0;
            m0 * ((1.0 - t) * (1.0 - t)) + p[(i + 1) % n] * (2.0 * t * (1.0 - t)) + m1 * (t * t)
        };
        let mut previous_error = f64::INFINITY;
        for k in 1..=7u32 {
            let q = curve::refine(&p, CurveScheme::Chaikin, closed, k).unwrap();
            let m = q.len();
            let scale = f64::from(1u32 << k);
            let edges = if closed { m } else { m - 1 };
            for a in 0..edges {
                let mid = (q[a] + q[(a + 1) % m]) / 2.0;
                let s = a as f64 / scale;
                let (i, t) = (s.floor() as usize, s - s.floor());
                assert!(
                    (mid - parabola(i, t)).length() < 1e-13,
                    "closed={closed} k={k} midpoint {a}"
                );
            }
            // The polygon's own points converge quadratically: the point of
            // level k nearest to parameter s sits |C''| h² / 8 off the curve.
            let error = (0..m)
                .filter_map(|a| {
                    let mut s = (a as f64 - 0.5) / scale; // Greville abscissa
                    let max = if closed { n as f64 } else { (n - 2) as f64 };
                    if closed {
                        s = s.rem_euclid(max);
                    }
                    (0.0..max).contains(&s).then(|| {
                        let (i, t) = (s.floor() as usize, s - s.floor());
                        (q[a] - parabola(i, t)).length()
                    })
                })
                .fold(0.0, f64::max);
            if k > 1 {
                let ratio = previous_error / error;
                assert!(
                    (3.99..=4.01).contains(&ratio),
                    "closed={closed} k={k}: ratio {ratio}"
                );
            }
            previous_error = error;
        }
    }
}

// ---------------------------------------------------------------------------
// flattening
// ---------------------------------------------------------------------------

/// Checks a flattened polyline against the analytic curve by dense sampling:
/// every chord is within `eps` of its arc parametrically, and every sampled
/// curve point is within `eps` of the polyline.
fn check_flattening<P: Point>(c: &BSplineCurve<P>, eps: f64) -> usize {
    let line = c.flatten(eps).unwrap();
    assert_eq!(line.points.len(), line.params.len());
    assert_eq!(line.closed, c.is_closed());
    let (_, s_max) = c.domain();
    let mut pts = line.points.clone();
    let mut params = line.params.clone();
    if line.closed {
        pts.push(pts[0]);
        params.push(s_max);
    } else {
        assert_eq!(*params.last().unwrap(), s_max);
    }
    assert_eq!(params[0], 0.0);
    let slack = 1e-12;
    for (w, q) in params.windows(2).zip(pts.windows(2)) {
        let (s0, s1) = (w[0], w[1]);
        assert!(s1 > s0);
        // The points are the curve's.
        assert!((q[0] - c.eval(s0).unwrap()).length() < 1e-12);
        for i in 0..=64 {
            let t = i as f64 / 64.0;
            let curve_point = c.eval(s0 + t * (s1 - s0)).unwrap();
            let chord_point = q[0] * (1.0 - t) + q[1] * t;
            let d = (curve_point - chord_point).length();
            assert!(d <= eps + slack, "chord [{s0}, {s1}] t={t}: {d} > {eps}");
        }
    }
    // Hausdorff, curve → polyline, with nearest points.
    let distance_to_polyline = |x: P| {
        pts.windows(2)
            .map(|q| {
                let (a, b) = (q[0], q[1]);
                let ab = b - a;
                let t = if ab.dot(ab) > 0.0 {
                    ((x - a).dot(ab) / ab.dot(ab)).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                (x - (a + ab * t)).length()
            })
            .fold(f64::INFINITY, f64::min)
    };
    for i in 0..=2000 {
        let s = s_max * i as f64 / 2000.0;
        let d = distance_to_polyline(c.eval(s).unwrap());
        assert!(d <= eps + slack, "s={s}: {d} > {eps}");
    }
    line.points.len()
}

#[test]
fn flattening_stays_within_the_tolerance_of_the_analytic_curve() {
    let mut rng = Rng(31);
    for degree in 1..=5 {
        for closed in [false, true] {
            let p2: Vec<DVec2> = (0..degree + 4).map(|_| rng.v2(3.0)).collect();
            let p3: Vec<DVec3> = (0..degree + 4).map(|_| rng.v3(3.0)).collect();
            let c2 = BSplineCurve::new(p2, degree, closed).unwrap();
            let c3 = BSplineCurve::new(p3, degree, closed).unwrap();
            let mut last = 0;
            for eps in [0.5, 0.1, 0.01, 1e-3] {
                let count = check_flattening(&c2, eps);
                assert!(count >= last, "a finer tolerance gives more points");
                last = count;
                check_flattening(&c3, eps);
            }
            if degree == 1 {
                // Lines: the polyline is the control polygon.
                assert_eq!(c2.flatten(1e-6).unwrap().points, c2.points());
            }
        }
    }
}

#[test]
fn chaikin_flattening_uses_as_few_points_as_midpoint_splitting_allows() {
    // For a parabola the bound is exact: segment i, with second difference
    // D = |M[i] - 2 P[i+1] + M[i+1]|, deviates by D / 4 from its chord and by
    // D / 4^(k+1) after k halvings, everywhere alike. So segment i needs
    // exactly 2^k pieces, k the least with D / 4^(k+1) <= eps.
    let mut rng = Rng(4);
    for closed in [false, true] {
        let p: Vec<DVec2> = (0..8).map(|_| rng.v2(3.0)).collect();
        let n = p.len();
        let segments = if closed { n } else { n - 2 };
        for eps in [0.3, 0.05, 0.007, 4e-4] {
            let mut expected = usize::from(!closed);
            for i in 0..segments {
                let m0 = (p[i] + p[(i + 1) % n]) / 2.0;
                let m1 = (p[(i + 1) % n] + p[(i + 2) % n]) / 2.0;
                let d = (m0 - p[(i + 1) % n] * 2.0 + m1).length();
                let mut k = 0;
                while d / 4f64.powi(k + 1) > eps {
                    k += 1;
                }
                // Not at a threshold, where rounding could decide.
                assert!((d / 4f64.powi(k + 1) / eps - 1.0).abs() > 1e-9);
                expected += 1 << k;
            }
            let line = curve::flatten(&p, CurveScheme::Chaikin, closed, eps).unwrap();
            assert_eq!(line.points.len(), expected, "closed={closed} eps={eps}");
            check_flattening(&BSplineCurve::new(p.clone(), 2, closed).unwrap(), eps);
        }
    }
}

#[test]
fn flatness_bound_is_exact_for_quadratics_and_bounds_cubics() {
    let b = [DVec2::ZERO, DVec2::new(1.0, 2.0), DVec2::new(2.0, 0.0)];
    // B(1/2) - L(1/2) = (b1 - (b0 + b2) / 2) / 2 = (0, 1).
    assert_eq!(flatness_bound(&b), 1.0);
    let mut rng = Rng(12);
    for _ in 0..50 {
        let c: Vec<DVec3> = (0..4).map(|_| rng.v3(3.0)).collect();
        let bound = flatness_bound(&c);
        let mut max: f64 = 0.0;
        for i in 0..=1000 {
            let t = i as f64 / 1000.0;
            let u = 1.0 - t;
            let p = c[0] * (u * u * u)
                + c[1] * (3.0 * u * u * t)
                + c[2] * (3.0 * u * t * t)
                + c[3] * (t * t * t);
            max = max.max((p - (c[0] * u + c[3] * t)).length());
        }
        assert!(max <= bound + 1e-15, "{max} > {bound}");
    }
    assert_eq!(flatness_bound(&[DVec2::ZERO, DVec2::ONE]), 0.0);
}

#[test]
fn flattening_errors_are_typed() {
    let p = [DVec2::ZERO, DVec2::new(1.0, 1.0), DVec2::new(2.0, 0.0)];
    for eps in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            curve::flatten(&p, CurveScheme::Chaikin, false, eps),
            Err(CurveError::BadTolerance(_))
        ));
    }
    for scheme in [CurveScheme::four_point(), CurveScheme::Jarek] {
        assert_eq!(
            curve::flatten(&p, scheme, false, 0.1),
            Err(CurveError::NoClosedFormLimit {
                scheme: scheme.name()
            })
        );
    }
    // Below the rounding error of the coordinates: refused, no endless loop.
    let big = [
        DVec2::new(1e6, 0.0),
        DVec2::new(1e6 + 1.0, 1.0),
        DVec2::new(1e6 + 2.0, 0.0),
    ];
    assert!(matches!(
        curve::flatten(&big, CurveScheme::Chaikin, false, 1e-300),
        Err(CurveError::ToleranceTooSmall { .. }) | Err(CurveError::TooManyPoints)
    ));
    assert!(matches!(
        curve::flatten(&p, CurveScheme::bspline(3), false, 0.1),
        Err(CurveError::TooFewPoints { needed: 4, .. })
    ));
}

// ---------------------------------------------------------------------------
// huge coordinates and tensions
// ---------------------------------------------------------------------------

/// 2^k, exactly.
fn pow2(k: i32) -> f64 {
    f64::from_bits(((1023 + k) as u64) << 52)
}

#[test]
fn midpoints_of_huge_coordinates_do_not_overflow() {
    let m = f64::MAX;
    let p = [DVec2::new(m, -m), DVec2::new(m, -m), DVec2::new(m, 0.0)];
    assert_eq!(
        curve::bspline(&p, 1, true).unwrap(),
        [
            p[0],
            DVec2::new(m, -m),
            p[1],
            DVec2::new(m, -m / 2.0),
            p[2],
            DVec2::new(m, -m / 2.0),
        ]
    );
    // The averaging schemes are exactly homogeneous: near f64::MAX (where
    // P[i] + P[i+1] overflows) they give, bit for bit, the refinement of the
    // small polygon scaled up.
    let scale = pow2(1017);
    for closed in [false, true] {
        let small = int_points(9, 21);
        let big: Vec<DVec2> = small.iter().map(|&q| q * scale).collect();
        for scheme in [
            CurveScheme::Chaikin,
            CurveScheme::bspline(1),
            CurveScheme::bspline(2),
            CurveScheme::bspline(3),
            CurveScheme::bspline(5),
        ] {
            let want: Vec<DVec2> = curve::refine(&small, scheme, closed, 3)
                .unwrap()
                .into_iter()
                .map(|q| q * scale)
                .collect();
            assert_eq!(
                curve::refine(&big, scheme, closed, 3).unwrap(),
                want,
                "{scheme} closed={closed}"
            );
        }
    }
}

#[test]
fn overflowing_levels_are_refused_whole() {
    // P1 + P2 overflows in E1, the fourth point of level 1.
    let p = [
        DVec2::ZERO,
        DVec2::new(1.7e308, 0.0),
        DVec2::new(1.7e308, 0.0),
        DVec2::ZERO,
    ];
    let overflow = CurveError::Overflow {
        scheme: CurveScheme::four_point(),
        level: 1,
        index: 3,
    };
    assert_eq!(
        curve::four_point(&p, DEFAULT_TENSION, false),
        Err(overflow.clone())
    );
    assert_eq!(
        curve::refine(&p, CurveScheme::four_point(), false, 2),
        Err(overflow.clone())
    );
    assert_eq!(
        curve::refine_once(&p, CurveScheme::four_point(), false),
        Err(overflow.clone())
    );
    assert_eq!(
        overflow.to_string(),
        "level 1 of four-point overflows: its point 3 would have a coordinate beyond the \
         range of f64 (the coordinates or the tension are too large)"
    );
    // Jarek bulges its midpoints out: M1 = 1.7e308 moves out by 1/16 of it.
    let jarek = curve::jarek(&p, true).unwrap_err();
    assert_eq!(
        jarek,
        CurveError::Overflow {
            scheme: CurveScheme::Jarek,
            level: 1,
            index: 3
        }
    );
    assert_eq!(
        jarek.to_string(),
        "level 1 of jarek overflows: its point 3 would have a coordinate beyond the \
         range of f64 (the coordinates are too large)"
    );
    // A huge tension on small points: at once, or after a level that still fits.
    let zigzag = [
        DVec2::ZERO,
        DVec2::new(1.0, 2.0),
        DVec2::new(3.0, 2.0),
        DVec2::new(4.0, 0.0),
    ];
    for (tension, level) in [(1e308, 1), (1e300, 2), (-1e200, 2)] {
        let scheme = CurveScheme::FourPoint { tension };
        assert_eq!(scheme.check(), Ok(()));
        assert_eq!(
            curve::refine(&zigzag, scheme, false, 3),
            Err(CurveError::Overflow {
                scheme,
                level,
                index: 1
            }),
            "tension {tension}"
        );
    }
    assert_eq!(
        curve::refine(&zigzag, CurveScheme::FourPoint { tension: 1e300 }, false, 3)
            .unwrap_err()
            .to_string(),
        "level 2 of four-point with tension 1e300 overflows: its point 1 would have a \
         coordinate beyond the range of f64 (the coordinates or the tension are too large)"
    );
    // Whatever is returned is finite.
    for tension in [1e10, -1e10, 0.25, -0.5] {
        let scheme = CurveScheme::FourPoint { tension };
        let all = curve::refine_levels(&zigzag, scheme, true, 4).unwrap();
        assert!(all.iter().flatten().all(|q| q.is_finite()), "{tension}");
    }
}

#[test]
fn huge_curves_flatten_as_their_scaled_down_copies() {
    // |b0 - 2 b1 + b2| / 4, although its square overflows.
    let b = [DVec2::ZERO, DVec2::new(0.0, 4e200), DVec2::ZERO];
    assert_eq!(flatness_bound(&b), 2e200);
    let scale = pow2(900);
    for (scheme, closed) in [
        (CurveScheme::Chaikin, false),
        (CurveScheme::bspline(3), true),
    ] {
        let small = int_points(7, 3);
        let big: Vec<DVec2> = small.iter().map(|&q| q * scale).collect();
        let want: Vec<DVec2> = curve::flatten(&small, scheme, closed, 0.01)
            .unwrap()
            .points
            .into_iter()
            .map(|q| q * scale)
            .collect();
        let got = curve::flatten(&big, scheme, closed, 0.01 * scale).unwrap();
        assert_eq!(got.points, want, "{scheme}");
    }
}

#[test]
fn huge_curves_are_drawn_like_their_scaled_down_copies() {
    use subdiv::io::svg::{Layer, Projection, curve_svg};
    let small = int_points(6, 8);
    let svg = |scale: f64| {
        let p: Vec<DVec2> = small.iter().map(|&q| q * scale).collect();
        let levels = curve::refine_levels(&p, CurveScheme::Chaikin, true, 2).unwrap();
        let layers: Vec<Layer<'_, DVec2>> = levels
            .iter()
            .map(|l| Layer {
                label: "level",
                points: l,
                closed: true,
            })
            .collect();
        curve_svg("huge", &layers, &Projection::PLAN)
    };
    // Beyond 1e300 the figure is drawn at 2^-64 of its size: the picture of
    // the small polygon, not every point at the centre (or NaN).
    let huge = svg(pow2(1017));
    assert_eq!(huge, svg(pow2(1017 - 64)));
    assert_eq!(huge, svg(1.0));
    assert!(!huge.contains("NaN") && !huge.contains("inf"), "{huge}");
}

// ---------------------------------------------------------------------------
// errors
// ---------------------------------------------------------------------------

#[test]
fn bad_input_is_a_typed_error_never_a_panic() {
    for scheme in ALL_SCHEMES {
        for closed in [false, true] {
            let needed = scheme.min_points(closed);
            for n in 0..needed {
                let p = int_points(n, 1);
                assert_eq!(
                    curve::refine(&p, scheme, closed, 1),
                    Err(CurveError::TooFewPoints {
                        scheme: scheme.name(),
                        closed,
                        needed,
                        got: n
                    }),
                    "{scheme} closed={closed} n={n}"
                );
            }
            assert!(curve::refine(&int_points(needed, 1), scheme, closed, 3).is_ok());
        }
    }
    let p = int_points(20, 2);
    for degree in [0, MAX_DEGREE + 1, usize::MAX] {
        assert_eq!(
            curve::bspline(&p, degree, true),
            Err(CurveError::BadDegree { degree })
        );
    }
    assert!(curve::bspline(&p, MAX_DEGREE, false).is_ok());
    assert!(matches!(
        curve::four_point(&p, f64::NAN, true),
        Err(CurveError::BadTension(_))
    ));
    let mut bad = p.clone();
    bad[3].y = f64::INFINITY;
    assert_eq!(
        curve::chaikin(&bad, false),
        Err(CurveError::NonFinitePoint { index: 3 })
    );
    assert_eq!(
        curve::refine(&p, CurveScheme::Jarek, true, 40),
        Err(CurveError::TooManyPoints)
    );
    assert_eq!(
        curve::refine(&p, CurveScheme::Jarek, true, u32::MAX),
        Err(CurveError::TooManyPoints)
    );
    assert!(BSplineCurve::new(p[..3].to_vec(), 3, false).is_err());
    assert_eq!(
        CurveError::TooFewPoints {
            scheme: "chaikin",
            closed: false,
            needed: 3,
            got: 2
        }
        .to_string(),
        "chaikin on an open polygon needs at least 3 points, got 2"
    );
    // Level 0 is the input.
    assert_eq!(curve::refine(&p, CurveScheme::Chaikin, true, 0).unwrap(), p);
}

// ---------------------------------------------------------------------------
// text files
// ---------------------------------------------------------------------------

#[test]
fn points_text_round_trips_exactly_at_17_digits() {
    let mut rng = Rng(3);
    let p: Vec<DVec3> = (0..50).map(|_| rng.v3(3.0) * 1e-3).collect();
    let text = subdiv::io::points::format_points(&p);
    let back = subdiv::io::points::parse_points(&text, Path::new("x")).unwrap();
    assert_eq!(back.points, Points::Spatial(p));
    assert_eq!(
        subdiv::io::points::format_points(&[DVec2::new(0.1, 1e20), DVec2::new(-0.0, 1.5)]),
        "0.10000000000000001 1e+20\n-0 1.5\n"
    );
}

#[test]
fn points_errors_escape_control_characters() {
    // A field that would clear the terminal: kept as written in the kind,
    // escaped in the message (as are backslashes).
    let e =
        subdiv::io::points::parse_points("0 0\n1 \u{1b}[2J\\\n", Path::new("t.txt")).unwrap_err();
    assert_eq!(e.kind, PointsErrorKind::NotANumber("\u{1b}[2J\\".into()));
    assert_eq!(e.to_string(), "t.txt:2: '\\u{1b}[2J\\\\' is not a number");
    assert!(!e.to_string().chars().any(char::is_control));
}

#[test]
fn points_parse_errors_name_the_line() {
    let f = Path::new("in.txt");
    let kind = |text: &str| {
        let e = subdiv::io::points::parse_points(text, f).unwrap_err();
        (e.line, e.kind)
    };
    assert_eq!(kind("0 0\n1\n"), (2, PointsErrorKind::WrongCount(1)));
    assert_eq!(kind("# c\n0 0 0 0\n"), (2, PointsErrorKind::WrongCount(4)));
    assert_eq!(
        kind("0 0\n\n1 1 1\n"),
        (
            3,
            PointsErrorKind::MixedDimensions {
                expected: 2,
                found: 3,
                first_line: 1
            }
        )
    );
    assert_eq!(
        kind("0 0\n1 y\n"),
        (2, PointsErrorKind::NotANumber("y".into()))
    );
    assert_eq!(
        kind("0 nan\n"),
        (1, PointsErrorKind::NonFinite("nan".into()))
    );
    let e = subdiv::io::points::parse_points("0 0\n1,2\n", f).unwrap_err();
    assert_eq!(e.to_string(), "in.txt:2: '1,2' is not a number");
    let ok = subdiv::io::points::parse_points("  1e3\t-2  # x y\n#\n\n3 4#\n", f).unwrap();
    assert_eq!(
        ok.points,
        Points::Planar(vec![DVec2::new(1e3, -2.0), DVec2::new(3.0, 4.0)])
    );
    assert_eq!(ok.line_count, 4);
    let e = ok.require(&CurveScheme::Chaikin, false).unwrap_err();
    assert_eq!(
        e.to_string(),
        "in.txt:4: the input ends after 2 points; chaikin on an open polygon needs at least 3"
    );
    assert!(ok.require(&CurveScheme::Jarek, false).is_ok());
}
