//! B-splines and NURBS over knot vectors: the circle, the basis, derivatives
//! against finite differences and polynomials, knot insertion and refinement
//! (Yamaguchi's example, Chaikin and the averaging scheme as special cases),
//! Bézier decomposition, splitting, closed curves, surfaces and the uniform
//! control grids, typed errors, and property tests.

mod support;

use glam::{DVec2, DVec3};
use proptest::prelude::*;
use subdiv::curve::{self, BSplineCurve, bspline_basis};
use subdiv::nurbs::{KnotVector, NurbsCurve, NurbsError, NurbsSurface};
use subdiv::patch::{ControlGrid, Direction};
use support::{Rng, TOPOLOGIES, wavy};

// ---------------------------------------------------------------------------
// helpers
// ---------------------------------------------------------------------------

const H: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// The unit circle as a rational quadratic: nine control points on the unit
/// square's corners and edge midpoints, knots 0,0,0,1,1,2,2,3,3,4,4,4,
/// weights alternating 1 and √2/2.
fn circle() -> NurbsCurve<DVec2> {
    let p = [
        (1., 0.),
        (1., 1.),
        (0., 1.),
        (-1., 1.),
        (-1., 0.),
        (-1., -1.),
        (0., -1.),
        (1., -1.),
        (1., 0.),
    ]
    .iter()
    .map(|&(x, y)| DVec2::new(x, y))
    .collect();
    let w = vec![1.0, H, 1.0, H, 1.0, H, 1.0, H, 1.0];
    let knots = vec![0., 0., 0., 1., 1., 2., 2., 3., 3., 4., 4., 4.];
    NurbsCurve::new(p, 2, knots, Some(w)).unwrap()
}

/// `count + 1` parameters spread over `[a, b]`, ends included.
fn params((a, b): (f64, f64), count: usize) -> impl Iterator<Item = f64> {
    (0..=count).map(move |i| {
        if i == count {
            b
        } else {
            a + (b - a) * i as f64 / count as f64
        }
    })
}

/// The largest distance between two curves over the first one's domain.
fn curve_gap(a: &NurbsCurve<DVec2>, b: &NurbsCurve<DVec2>) -> f64 {
    params(a.domain(), 200)
        .chain(a.knots().breaks().iter().copied())
        .map(|t| (a.eval(t).unwrap() - b.eval(t).unwrap()).length())
        .fold(0.0, f64::max)
}

fn assert_close(a: DVec2, b: DVec2, tol: f64, what: &str) {
    assert!((a - b).length() <= tol, "{what}: {a} vs {b}");
}

// ---------------------------------------------------------------------------
// the circle
// ---------------------------------------------------------------------------

#[test]
fn the_circle_has_radius_one_before_and_after_insertions() {
    let c = circle();
    let radius_error = |c: &NurbsCurve<DVec2>| {
        params(c.domain(), 4000)
            .map(|t| (c.eval(t).unwrap().length() - 1.0).abs())
            .fold(0.0, f64::max)
    };
    assert!(radius_error(&c) < 1e-12);
    // Quarter points are exact.
    assert_eq!(c.eval(0.0).unwrap(), DVec2::X);
    assert_close(c.eval(1.0).unwrap(), DVec2::Y, 1e-15, "C(1)");
    assert_close(c.eval(2.0).unwrap(), -DVec2::X, 1e-15, "C(2)");
    let variants = [
        c.insert(0.5).unwrap(),
        c.insert(1.0).unwrap(), // multiplicity 3 = d + 1 at an interior knot
        c.insert_many(&[0.25, 0.25, 2.7, 3.999, 1e-9]).unwrap(),
        c.insert_times(3.5, 3).unwrap(),
        c.refine_knots(&[0.1, 0.2, 0.3, 1.5, 2.5, 3.5, 3.5])
            .unwrap(),
    ];
    for v in &variants {
        assert!(radius_error(v) < 1e-12);
        assert!(curve_gap(&c, v) < 1e-14);
        assert_eq!(v.domain(), (0.0, 4.0));
    }
    // Tangents are perpendicular to the radius, curvature is 1.
    for t in params((0.0, 4.0), 97) {
        let d = c.derivatives(t).unwrap();
        assert!(d.point.dot(d.first).abs() < 1e-13);
        let kappa = d.first.perp_dot(d.second) / d.first.length().powi(3);
        assert!((kappa - 1.0).abs() < 1e-12, "curvature {kappa} at {t}");
    }
    // Four quarter arcs, each a rational quadratic Bézier curve.
    let segments = c.to_bezier().unwrap();
    assert_eq!(segments.len(), 4);
    for s in &segments {
        assert_eq!(s.weights.as_deref(), Some(&[1.0, H, 1.0][..]));
        for t in params((s.start, s.end), 50) {
            assert!((s.eval(t).length() - 1.0).abs() < 1e-12);
            assert_close(s.eval(t), c.eval(t).unwrap(), 1e-14, "segment");
        }
    }
}

// ---------------------------------------------------------------------------
// basis functions
// ---------------------------------------------------------------------------

/// Random knot vectors of degree 1-5, clamped or not, with repeated knots.
fn random_knots(rng: &mut Rng, degree: usize, points: usize, clamped: bool) -> KnotVector {
    let m = points + degree;
    let mut knots = vec![rng.next() * 3.0];
    let mut run = 1;
    for k in 1..=m {
        let forced_repeat = clamped && (k <= degree || k > m - degree);
        let forced_gap = k == degree + 1 || (clamped && k == m - degree);
        let repeat = forced_repeat || (!forced_gap && run < degree && rng.next() < -0.6);
        let last = knots[k - 1];
        knots.push(if repeat {
            last
        } else {
            last + 0.1 + rng.next().abs() * 2.0
        });
        run = if repeat { run + 1 } else { 1 };
    }
    KnotVector::new(knots, degree).unwrap()
}

#[test]
fn the_basis_is_a_non_negative_partition_of_unity() {
    let mut rng = Rng(7);
    for degree in 1..=5 {
        for clamped in [false, true] {
            for _ in 0..10 {
                let points = degree + 1 + (rng.next().abs() * 6.0) as usize;
                let k = random_knots(&mut rng, degree, points, clamped);
                for t in params(k.domain(), 300).chain(k.breaks().iter().copied()) {
                    let (span, n) = k.basis(t).unwrap();
                    assert_eq!(n.len(), degree + 1);
                    assert!(n.iter().all(|&x| x >= 0.0), "{n:?}");
                    assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-14);
                    // The same values straight from the Cox–de Boor recursion,
                    // and zero for every other basis function.
                    for i in 0..k.control_count() {
                        let direct = k.basis_function(i, t).unwrap();
                        let expected = if i + degree >= span && i <= span {
                            n[i + degree - span]
                        } else {
                            0.0
                        };
                        assert!((direct - expected).abs() < 1e-14, "N_{i},{degree}({t})");
                    }
                }
            }
        }
    }
}

#[test]
fn uniform_knots_give_the_truncated_power_cardinal_basis() {
    // Knots u_k = k - d: N_{i,d}(t) = N_d(t - u_i) = N_d(t + d - i).
    for degree in 1..=7 {
        let k = KnotVector::uniform(degree + 5, degree).unwrap();
        for t in params(k.domain(), 173) {
            for i in 0..k.control_count() {
                let expected = bspline_basis(degree, t + degree as f64 - i as f64);
                let got = k.basis_function(i, t).unwrap();
                assert!(
                    (got - expected).abs() < 1e-13,
                    "d={degree} i={i} t={t}: {got} vs {expected}"
                );
            }
        }
    }
}

#[test]
fn basis_derivatives_match_finite_differences_and_bernstein_polynomials() {
    let mut rng = Rng(11);
    for degree in 1..=5 {
        let k = random_knots(&mut rng, degree, degree + 4, false);
        let breaks = k.breaks().to_vec();
        for w in breaks.windows(2).filter(|w| w[1] > w[0]) {
            for f in [0.2, 0.5, 0.8] {
                let t = w[0] + f * (w[1] - w[0]);
                let (span, d) = k.basis_derivatives(t, 3).unwrap();
                let h = 1e-5;
                let (_, lo) = k.basis(t - h).unwrap();
                let (_, hi) = k.basis(t + h).unwrap();
                let (_, mid) = k.basis(t).unwrap();
                assert_eq!(d[0], mid);
                for j in 0..=degree {
                    let fd1 = (hi[j] - lo[j]) / (2.0 * h);
                    assert!(
                        (d[1][j] - fd1).abs() < 1e-6 * (1.0 + d[1][j].abs()),
                        "span {span}"
                    );
                }
                let h = 1e-4;
                let (_, lo) = k.basis(t - h).unwrap();
                let (_, hi) = k.basis(t + h).unwrap();
                for j in 0..=degree {
                    let fd2 = (hi[j] - 2.0 * mid[j] + lo[j]) / (h * h);
                    assert!((d[2][j] - fd2).abs() < 1e-4 * (1.0 + d[2][j].abs()));
                }
                // Derivatives of a partition of unity sum to zero.
                for dq in &d[1..] {
                    let scale: f64 = dq.iter().map(|x| x.abs()).sum::<f64>() + 1.0;
                    assert!(dq.iter().sum::<f64>().abs() < 1e-12 * scale);
                }
            }
        }
    }
    // Bernstein: B_{j,3}(t) = C(3,j) t^j (1-t)^(3-j); its derivatives in closed form.
    let k = KnotVector::new(vec![0., 0., 0., 0., 1., 1., 1., 1.], 3).unwrap();
    for t in params((0.0, 1.0), 20) {
        let (_, d) = k.basis_derivatives(t, 4).unwrap();
        let s = 1.0 - t;
        let b = [s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t];
        let b1 = [
            -3.0 * s * s,
            3.0 * s * s - 6.0 * t * s,
            6.0 * t * s - 3.0 * t * t,
            3.0 * t * t,
        ];
        let b2 = [6.0 * s, -12.0 * s + 6.0 * t, 6.0 * s - 12.0 * t, 6.0 * t];
        let b3 = [-6.0, 18.0, -18.0, 6.0];
        for j in 0..4 {
            assert!((d[0][j] - b[j]).abs() < 1e-15);
            assert!((d[1][j] - b1[j]).abs() < 1e-14);
            assert!((d[2][j] - b2[j]).abs() < 1e-13);
            assert!((d[3][j] - b3[j]).abs() < 1e-12);
            assert_eq!(d[4][j], 0.0);
        }
    }
}

// ---------------------------------------------------------------------------
// curve derivatives
// ---------------------------------------------------------------------------

#[test]
fn curve_derivatives_are_those_of_the_polynomial() {
    // C(t) = a + b t + c t² + e t³ as a cubic Bézier curve: P0 = a,
    // P1 = a + b/3, P2 = a + 2b/3 + c/3, P3 = a + b + c + e; then knots
    // inserted, so that it is a B-spline over an unclamped-looking interior.
    let (a, b, c, e) = (
        DVec2::new(1.0, -2.0),
        DVec2::new(0.5, 3.0),
        DVec2::new(-4.0, 1.5),
        DVec2::new(2.0, -1.0),
    );
    let p = vec![a, a + b / 3.0, a + b * (2.0 / 3.0) + c / 3.0, a + b + c + e];
    let bez = NurbsCurve::new(p, 3, vec![0., 0., 0., 0., 1., 1., 1., 1.], None).unwrap();
    let spline = bez.insert_many(&[0.3, 0.3, 0.55, 0.9]).unwrap();
    for curve in [&bez, &spline] {
        for t in params((0.0, 1.0), 40) {
            let d = curve.derivatives(t).unwrap();
            let exact = a + b * t + c * (t * t) + e * (t * t * t);
            let exact1 = b + c * (2.0 * t) + e * (3.0 * t * t);
            let exact2 = c * 2.0 + e * (6.0 * t);
            assert_close(curve.eval(t).unwrap(), exact, 1e-14, "point");
            assert_close(d.point, exact, 1e-14, "point from the basis");
            assert_close(d.first, exact1, 1e-12, "first");
            assert_close(d.second, exact2, 1e-11, "second");
        }
    }
}

#[test]
fn curve_derivatives_match_central_differences() {
    let mut rng = Rng(23);
    for degree in 1..=5 {
        for rational in [false, true] {
            let knots = random_knots(&mut rng, degree, degree + 5, degree % 2 == 0);
            let n = knots.control_count();
            let points: Vec<DVec2> = (0..n).map(|_| rng.v2(5.0)).collect();
            let weights = rational.then(|| (0..n).map(|_| 0.3 + 2.0 * rng.next().abs()).collect());
            let c = NurbsCurve::new(points, degree, knots.as_slice().to_vec(), weights).unwrap();
            let breaks = c.knots().breaks().to_vec();
            for w in breaks.windows(2).filter(|w| w[1] - w[0] > 0.05) {
                for f in [0.25, 0.5, 0.75] {
                    let t = w[0] + f * (w[1] - w[0]);
                    let d = c.derivatives(t).unwrap();
                    let at = |t: f64| c.eval(t).unwrap();
                    assert_close(d.point, at(t), 1e-13, "point");
                    let h = 1e-6;
                    let fd1 = (at(t + h) - at(t - h)) / (2.0 * h);
                    assert!(
                        (d.first - fd1).length() < 1e-6 * (1.0 + d.first.length()),
                        "d={degree} rational={rational}"
                    );
                    let h = 1e-4;
                    let fd2 = (at(t + h) - at(t) * 2.0 + at(t - h)) / (h * h);
                    assert!(
                        (d.second - fd2).length() < 1e-4 * (1.0 + d.second.length()),
                        "second d={degree} rational={rational}: {} vs {fd2}",
                        d.second
                    );
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------
// knot insertion: Yamaguchi, Chaikin, the averaging scheme
// ---------------------------------------------------------------------------

/// Yamaguchi, *Curves and Surfaces in Computer Aided Geometric Design*,
/// Example 6.10: a knot inserted at t = 2.8 into a cubic B-spline, with the
/// coefficients α = 0.933, 0.6, 0.267 (exactly 14/15, 3/5, 4/15) and
/// Q3 = (1 − 0.933)(30, 50) + 0.933 (40, 55) = (39.33, 54.67),
/// Q4 = 0.4 (40, 55) + 0.6 (60, 20) = (52, 34),
/// Q5 = (1 − 0.267)(60, 20) + 0.267 (80, 90) = (65.34, 38.69).
///
/// Reconstruction. Boehm's rule is `Q_i = (1 − α_i) P_{i−1} + α_i P_i` with
/// `α_i = (t − u_i) / (u_{i+3} − u_i)`, so the printed blends name
/// P2 = (30, 50), P3 = (40, 55), P4 = (60, 20), P5 = (80, 90), and the
/// affected points Q3..Q5 put t in the span k = 5: `u_5 ≤ 2.8 < u_6`. With
/// integer knots, `u_5 = 2`, `u_6 = 3`; then `α_5 = 0.8 / (u_8 − 2) = 4/15`
/// gives `u_8 = 5`, `α_4 = (2.8 − u_4) / (u_7 − u_4) = 3/5` gives `u_4 = 1`,
/// `u_7 = 4`, and `α_3 = (2.8 − u_3) / (3 − u_3) = 14/15` gives `u_3 = 0`.
/// So `u_3..u_8 = 0..5`: the integer knots `u_k = k − 3`, the crate's uniform
/// cubic ([`KnotVector::uniform`]) with six control points P0..P5 (the
/// fewest that have a span 5) and domain [0, 3]. The knots `u_0..u_2`,
/// `u_9` and the points P0, P1 do not enter the example (they take the
/// uniform values −3..−1, 6 and two arbitrary points).
#[test]
fn yamaguchi_example_6_10() {
    let p = vec![
        DVec2::new(0.0, 10.0),
        DVec2::new(10.0, 40.0),
        DVec2::new(30.0, 50.0),
        DVec2::new(40.0, 55.0),
        DVec2::new(60.0, 20.0),
        DVec2::new(80.0, 90.0),
    ];
    let knots = KnotVector::uniform(6, 3).unwrap();
    assert_eq!(
        knots.as_slice(),
        [-3., -2., -1., 0., 1., 2., 3., 4., 5., 6.]
    );
    let c = NurbsCurve::from_knot_vector(p.clone(), knots.clone(), None).unwrap();

    let (span, alpha) = knots.insertion_coefficients(2.8).unwrap();
    assert_eq!(span, 5);
    for (a, exact) in alpha.iter().zip([14.0 / 15.0, 3.0 / 5.0, 4.0 / 15.0]) {
        assert!((a - exact).abs() < 1e-15);
    }
    let rounded: Vec<f64> = alpha
        .iter()
        .map(|a| (a * 1000.0).round() / 1000.0)
        .collect();
    assert_eq!(rounded, [0.933, 0.6, 0.267]);

    // The exact α: Q3 = (118/3, 164/3), Q4 = (52, 34), Q5 = (196/3, 116/3).
    let q = c.insert(2.8).unwrap();
    assert_eq!(q.points().len(), 7);
    assert_eq!(
        q.knots().as_slice(),
        [-3., -2., -1., 0., 1., 2., 2.8, 3., 4., 5., 6.]
    );
    assert_eq!(&q.points()[..3], &p[..3]);
    assert_eq!(q.points()[6], p[5]);
    assert_close(
        q.points()[3],
        DVec2::new(118.0 / 3.0, 164.0 / 3.0),
        1e-12,
        "Q3",
    );
    assert_close(q.points()[4], DVec2::new(52.0, 34.0), 1e-12, "Q4");
    assert_close(
        q.points()[5],
        DVec2::new(196.0 / 3.0, 116.0 / 3.0),
        1e-12,
        "Q5",
    );

    // The printed values come from the rounded α, to their two decimals.
    let blend = |i: usize, a: f64| p[i - 1] * (1.0 - a) + p[i] * a;
    let printed = [(39.33, 54.67), (52.0, 34.0), (65.34, 38.69)];
    for (j, &(x, y)) in printed.iter().enumerate() {
        let v = blend(3 + j, rounded[j]);
        assert!(
            (v.x - x).abs() <= 0.005 + 1e-9 && (v.y - y).abs() <= 0.005 + 1e-9,
            "Q{}: {v}",
            3 + j
        );
    }
    // The exact values print as Q3 and Q4 do; Q5 differs in the second
    // decimal (65.33, 38.67) because of the rounding of α_5.
    assert!(curve_gap(&c, &q) < 1e-12);
}

/// The midpoints of the domain's spans of a uniform curve.
fn domain_midpoints(c: &NurbsCurve<DVec2>) -> Vec<f64> {
    c.knots()
        .breaks()
        .windows(2)
        .map(|w| 0.5 * (w[0] + w[1]))
        .collect()
}

#[test]
fn inserting_every_midpoint_of_a_uniform_quadratic_is_chaikin() {
    let mut rng = Rng(3);
    for n in [3usize, 4, 7] {
        let p: Vec<DVec2> = (0..n).map(|_| rng.v2(5.0)).collect();
        // Closed: Q_j = Chaikin's j-th point for every j.
        let closed =
            NurbsCurve::from_bspline(&BSplineCurve::new(p.clone(), 2, true).unwrap()).unwrap();
        let refined = closed.insert_many(&domain_midpoints(&closed)).unwrap();
        let chaikin = curve::chaikin(&p, true).unwrap();
        assert_eq!(refined.distinct_points().len(), 2 * n);
        for (j, (&q, &b)) in refined.distinct_points().iter().zip(&chaikin).enumerate() {
            assert_close(q, b, 1e-14, &format!("closed n={n} j={j}"));
        }
        let half: Vec<f64> = (0..=2 * n).map(|k| k as f64 / 2.0).collect();
        assert_eq!(refined.knots().breaks(), half.as_slice());
        // Open: 2n - 2 points, Q_j = Chaikin's j-th point for 1 ≤ j ≤ 2n - 4;
        // Q_0 = P_0 and Q_{2n-3} = P_{n-1}.
        let open =
            NurbsCurve::from_bspline(&BSplineCurve::new(p.clone(), 2, false).unwrap()).unwrap();
        let refined = open.insert_many(&domain_midpoints(&open)).unwrap();
        let chaikin = curve::chaikin(&p, false).unwrap();
        let q = refined.points();
        assert_eq!(q.len(), chaikin.len());
        assert_eq!((q[0], q[2 * n - 3]), (p[0], p[n - 1]));
        for j in 1..=2 * n - 4 {
            assert_close(q[j], chaikin[j], 1e-14, &format!("open n={n} j={j}"));
        }
        assert!(curve_gap(&open, &refined) < 1e-14);
    }
}

#[test]
fn inserting_every_midpoint_of_a_uniform_spline_is_one_averaging_level() {
    // Degree d: closed, all 2n points equal; open, 2n - d points, equal for
    // d - 1 ≤ j ≤ 2n - 2d. The scheme's open polygon is the same curve over
    // the knots (k - d) / 2.
    let mut rng = Rng(5);
    for degree in 1..=5 {
        for n in [degree.max(3), degree + 4] {
            let p: Vec<DVec2> = (0..n).map(|_| rng.v2(5.0)).collect();
            let b = curve::bspline(&p, degree, true).unwrap();
            let closed =
                NurbsCurve::from_bspline(&BSplineCurve::new(p.clone(), degree, true).unwrap())
                    .unwrap();
            let refined = closed.refine_knots(&domain_midpoints(&closed)).unwrap();
            assert!(refined.is_closed());
            assert_eq!(refined.distinct_points().len(), b.len());
            for (j, (&q, &bj)) in refined.distinct_points().iter().zip(&b).enumerate() {
                assert_close(q, bj, 1e-13, &format!("closed d={degree} n={n} j={j}"));
            }
            if n < degree + 1 {
                continue;
            }
            let b = curve::bspline(&p, degree, false).unwrap();
            let open =
                NurbsCurve::from_bspline(&BSplineCurve::new(p.clone(), degree, false).unwrap())
                    .unwrap();
            let refined = open.refine_knots(&domain_midpoints(&open)).unwrap();
            assert_eq!(refined.points().len(), 2 * n - degree);
            assert_eq!(b.len(), 2 * n - degree);
            for (j, &bj) in b
                .iter()
                .enumerate()
                .take(2 * n - 2 * degree + 1)
                .skip(degree - 1)
            {
                assert_close(
                    refined.points()[j],
                    bj,
                    1e-13,
                    &format!("open d={degree} n={n} j={j}"),
                );
            }
            if degree > 1 {
                assert!(
                    (refined.points()[0] - b[0]).length() > 1e-6,
                    "the ends differ"
                );
            }
            let half: Vec<f64> = (0..=2 * n)
                .map(|k| (k as f64 - degree as f64) / 2.0)
                .collect();
            let scheme = NurbsCurve::new(b.clone(), degree, half, None).unwrap();
            assert_eq!(scheme.domain(), open.domain());
            assert!(curve_gap(&open, &scheme) < 1e-13);
            assert!(curve_gap(&open, &refined) < 1e-13);
        }
    }
}

// ---------------------------------------------------------------------------
// refinement, Bézier decomposition, splitting
// ---------------------------------------------------------------------------

#[test]
fn refinement_equals_sequential_insertion_at_ends_and_repeated_knots() {
    let mut rng = Rng(31);
    for degree in 1..=5 {
        for clamped in [false, true] {
            let knots = random_knots(&mut rng, degree, degree + 4, clamped);
            let n = knots.control_count();
            let points: Vec<DVec2> = (0..n).map(|_| rng.v2(5.0)).collect();
            let c = NurbsCurve::from_knot_vector(points, knots, None).unwrap();
            let (a, b) = c.domain();
            let mut ts: Vec<f64> = c.to_open().knots().bezier_knots_for_test();
            ts.extend([a + 0.3 * (b - a), a + 0.3 * (b - a), a + 0.71 * (b - a)]);
            let all_at_once = c.refine_knots(&ts).unwrap();
            let mut sorted = ts.clone();
            sorted.sort_by(f64::total_cmp);
            let one_by_one = c.insert_many(&sorted).unwrap();
            assert_eq!(all_at_once.knots(), one_by_one.knots());
            for (x, y) in all_at_once.points().iter().zip(one_by_one.points()) {
                assert_close(*x, *y, 1e-12, &format!("d={degree} clamped={clamped}"));
            }
            assert!(curve_gap(&c, &all_at_once) < 1e-12);
        }
    }
}

/// The knots that raise every domain knot to multiplicity d.
trait BezierKnots {
    fn bezier_knots_for_test(&self) -> Vec<f64>;
}

impl BezierKnots for KnotVector {
    fn bezier_knots_for_test(&self) -> Vec<f64> {
        let mut xs = Vec::new();
        let mut last = f64::NAN;
        for &u in self.breaks() {
            if u != last {
                let have = self.multiplicity(u);
                xs.extend(std::iter::repeat_n(u, self.degree().saturating_sub(have)));
                last = u;
            }
        }
        xs
    }
}

#[test]
fn bezier_segments_and_split_pieces_reproduce_the_curve() {
    let mut rng = Rng(41);
    for degree in 1..=5 {
        for (clamped, rational) in [(false, false), (true, false), (false, true), (true, true)] {
            let knots = random_knots(&mut rng, degree, degree + 5, clamped);
            let n = knots.control_count();
            let points: Vec<DVec2> = (0..n).map(|_| rng.v2(5.0)).collect();
            let weights = rational.then(|| (0..n).map(|_| 0.3 + rng.next().abs()).collect());
            let c = NurbsCurve::from_knot_vector(points, knots, weights).unwrap();
            let spans = c
                .knots()
                .breaks()
                .windows(2)
                .filter(|w| w[1] > w[0])
                .count();
            let segments = c.to_bezier().unwrap();
            assert_eq!(segments.len(), spans);
            for s in &segments {
                assert_eq!(s.points.len(), degree + 1);
                for t in params((s.start, s.end), 20) {
                    assert_close(s.eval(t), c.eval(t).unwrap(), 1e-12, "bezier");
                }
            }
            let (a, b) = c.domain();
            for f in [0.1, 0.5, 0.93] {
                let t = a + f * (b - a);
                let (left, right) = c.split(t).unwrap();
                assert_eq!(left.domain(), (a, t));
                assert_eq!(right.domain(), (t, b));
                assert_close(
                    *left.points().last().unwrap(),
                    c.eval(t).unwrap(),
                    1e-12,
                    "left end",
                );
                assert_close(right.points()[0], c.eval(t).unwrap(), 1e-12, "right start");
                for s in params((a, t), 30) {
                    assert_close(left.eval(s).unwrap(), c.eval(s).unwrap(), 1e-12, "left");
                }
                for s in params((t, b), 30) {
                    assert_close(right.eval(s).unwrap(), c.eval(s).unwrap(), 1e-12, "right");
                }
            }
        }
    }
}

#[test]
fn high_degrees_keep_the_shape_too() {
    let mut rng = Rng(43);
    for degree in 6..=10 {
        for clamped in [false, true] {
            let knots = random_knots(&mut rng, degree, degree + 4, clamped);
            let n = knots.control_count();
            let points: Vec<DVec2> = (0..n).map(|_| rng.v2(5.0)).collect();
            let weights = Some((0..n).map(|_| 0.5 + rng.next().abs()).collect());
            let c = NurbsCurve::from_knot_vector(points, knots, weights).unwrap();
            let (a, b) = c.domain();
            // The domain's end too, where it is a simple knot (unclamped).
            let end = if clamped { a + 0.9 * (b - a) } else { b };
            let ts = [
                a + 0.31 * (b - a),
                a + 0.31 * (b - a),
                end,
                a + 0.8 * (b - a),
            ];
            let one_by_one = c.insert_many(&ts).unwrap();
            let at_once = c.refine_knots(&ts).unwrap();
            assert!(curve_gap(&c, &one_by_one) < 1e-11, "d={degree}");
            assert!(curve_gap(&c, &at_once) < 1e-11, "d={degree}");
            for s in c.to_bezier().unwrap() {
                for t in params((s.start, s.end), 10) {
                    assert_close(s.eval(t), c.eval(t).unwrap(), 1e-11, "bezier");
                }
            }
            let (left, right) = c.split(a + 0.5 * (b - a)).unwrap();
            assert!(curve_gap(&left, &c) < 1e-11 && curve_gap(&right, &c) < 1e-11);
        }
    }
}

// ---------------------------------------------------------------------------
// closed curves
// ---------------------------------------------------------------------------

#[test]
fn closed_curves_are_periodic_and_stay_closed_under_insertion() {
    let mut rng = Rng(53);
    for degree in 1..=5 {
        let n = degree.max(2) + 2;
        let p: Vec<DVec3> = (0..n).map(|_| rng.v3(5.0)).collect();
        let mut breaks = vec![0.5];
        for _ in 0..n {
            let last = *breaks.last().unwrap();
            breaks.push(last + 0.2 + rng.next().abs());
        }
        let w: Vec<f64> = (0..n).map(|_| 0.5 + rng.next().abs()).collect();
        let c = NurbsCurve::closed(p.clone(), degree, breaks.clone(), Some(w.clone())).unwrap();
        assert!(c.is_closed());
        assert_eq!(c.points().len(), n + degree);
        assert_eq!(&c.points()[n..], &p[..degree]);
        assert_eq!(c.distinct_weights(), Some(w.as_slice()));
        let period = breaks[n] - breaks[0];
        assert_eq!(c.knots().period(), Some(period));
        for t in params(c.domain(), 40) {
            let x = c.eval(t).unwrap();
            assert!((c.eval(t + period).unwrap() - x).length() < 1e-11);
            assert!((c.eval(t - 3.0 * period).unwrap() - x).length() < 1e-11);
        }
        // Smooth across the seam: C^(d-1) at s_0 = s_n.
        let (a, b) = c.domain();
        let (da, db) = (c.derivatives(a).unwrap(), c.derivatives(b).unwrap());
        assert!((da.point - db.point).length() < 1e-12);
        if degree >= 2 {
            assert!((da.first - db.first).length() < 1e-9 * (1.0 + da.first.length()));
        }
        let mut q = c.clone();
        for (k, t) in [
            breaks[0],
            0.5 * (breaks[1] + breaks[2]),
            breaks[n] - 1e-3,
            breaks[2],
            7.0 * period + 0.9,
        ]
        .into_iter()
        .enumerate()
        {
            q = q.insert(t).unwrap();
            assert!(q.is_closed());
            assert_eq!(q.distinct_points().len(), n + k + 1);
            assert_eq!(q.points().len(), n + k + 1 + degree);
            assert_eq!(&q.points()[n + k + 1..], &q.points()[..degree]);
            let distinct = q.distinct_points().len();
            assert_eq!(
                &q.weights().unwrap()[distinct..],
                &q.weights().unwrap()[..degree]
            );
            assert_eq!(q.domain(), c.domain());
            for t in params(c.domain(), 60) {
                assert!(
                    (q.eval(t).unwrap() - c.eval(t).unwrap()).length() < 1e-11,
                    "d={degree} k={k}"
                );
            }
        }
        // The open representation is the same curve; splitting opens it.
        let open = c.to_open();
        assert!(!open.is_closed());
        let (left, right) = c.split(a + 0.4 * period).unwrap();
        assert!(!left.is_closed() && !right.is_closed());
        assert!((left.eval(a).unwrap() - open.eval(a).unwrap()).length() < 1e-12);
        assert!((right.eval(b).unwrap() - c.eval(b).unwrap()).length() < 1e-12);
        assert_eq!(c.to_bezier().unwrap().len(), n);
    }
}

// ---------------------------------------------------------------------------
// surfaces
// ---------------------------------------------------------------------------

#[test]
fn control_grids_evaluate_as_surfaces_over_uniform_knots() {
    for degree in [1, 2, 3, 4] {
        for (cu, cv) in TOPOLOGIES {
            let g = wavy(6, 5, degree, cu, cv, 100 + degree as u64);
            let s = NurbsSurface::from_control_grid(&g).unwrap();
            let ([s0, s1], [t0, t1]) = g.domain();
            assert_eq!(s.domain(), ((s0, s1), (t0, t1)));
            for a in 0..=17 {
                for b in 0..=13 {
                    let (u, v) = (
                        s0 + (s1 - s0) * a as f64 / 17.0,
                        t0 + (t1 - t0) * b as f64 / 13.0,
                    );
                    let (p, q) = (g.eval(u, v).unwrap(), s.eval(u, v).unwrap());
                    assert!(
                        (p - q).length() < 1e-13,
                        "d={degree} ({cu}, {cv}) at ({u}, {v})"
                    );
                }
            }
        }
    }
}

#[test]
fn control_grid_refinement_is_midpoint_insertion_in_u_and_v() {
    // Closed directions: every refined point; open ones: indices d-1..=2n-2d.
    for degree in [2, 3] {
        for (cu, cv) in TOPOLOGIES {
            let g = wavy(6, 5, degree, cu, cv, 200 + degree as u64);
            let r = g.refine().unwrap();
            let s = NurbsSurface::from_control_grid(&g).unwrap();
            let mid = |d: Direction| -> Vec<f64> {
                s.knots(d)
                    .breaks()
                    .windows(2)
                    .map(|w| 0.5 * (w[0] + w[1]))
                    .collect()
            };
            let fine = s
                .refine_knots(Direction::U, &mid(Direction::U))
                .unwrap()
                .refine_knots(Direction::V, &mid(Direction::V))
                .unwrap();
            let range = |n: usize, closed: bool| {
                if closed {
                    0..2 * n
                } else {
                    degree - 1..2 * n - 2 * degree + 1
                }
            };
            let mut worst: f64 = 0.0;
            for j in range(g.nv(), cv) {
                for i in range(g.nu(), cu) {
                    let d = (fine.point(i, j).unwrap() - r.point(i, j)).length();
                    worst = worst.max(d);
                }
            }
            assert!(worst < 1e-14, "d={degree} ({cu}, {cv}): {worst}");
            // The whole refined grid is the same surface at twice the parameters.
            let rs = NurbsSurface::from_control_grid(&r).unwrap();
            let ((u0, u1), (v0, v1)) = s.domain();
            for a in 0..=9 {
                for b in 0..=9 {
                    let (u, v) = (
                        u0 + (u1 - u0) * a as f64 / 9.0,
                        v0 + (v1 - v0) * b as f64 / 9.0,
                    );
                    let p = s.eval(u, v).unwrap();
                    assert!((fine.eval(u, v).unwrap() - p).length() < 1e-13);
                    assert!((rs.eval(2.0 * u, 2.0 * v).unwrap() - p).length() < 1e-13);
                }
            }
        }
    }
}

/// A rational cylinder of radius 1: the circle along u, a line along v.
fn cylinder() -> NurbsSurface<DVec3> {
    let c = circle();
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for z in [0.0, 2.0] {
        for (p, w) in c.points().iter().zip(c.weights().unwrap()) {
            points.push(p.extend(z));
            weights.push(*w);
        }
    }
    NurbsSurface::new(
        points,
        9,
        2,
        c.knots().clone(),
        KnotVector::new(vec![0.0, 0.0, 1.0, 1.0], 1).unwrap(),
        Some(weights),
    )
    .unwrap()
}

#[test]
fn surface_operations_keep_the_shape() {
    let cyl = cylinder();
    let mut rng = Rng(61);
    let knots_v = KnotVector::new(vec![0., 0., 0., 0.4, 1.1, 2., 2., 2.], 2).unwrap();
    let points: Vec<DVec3> = (0..7 * 5).map(|_| rng.v3(5.0)).collect();
    let weights: Vec<f64> = (0..7 * 5).map(|_| 0.5 + rng.next().abs()).collect();
    let knots_u = KnotVector::new(vec![-1., 0., 0.5, 1., 1., 2.5, 3., 3.2, 4., 5., 6.], 3).unwrap();
    let random = NurbsSurface::new(points, 7, 5, knots_u, knots_v, Some(weights)).unwrap();
    for s in [&cyl, &random] {
        let ((u0, u1), (v0, v1)) = s.domain();
        let at = |f: f64, g: f64| (u0 + f * (u1 - u0), v0 + g * (v1 - v0));
        let variants = vec![
            s.insert(Direction::U, at(0.37, 0.0).0).unwrap(),
            s.insert(Direction::V, at(0.0, 0.61).1).unwrap(),
            s.refine_knots(Direction::U, &[at(0.1, 0.).0, at(0.1, 0.).0, at(0.8, 0.).0])
                .unwrap()
                .refine_knots(Direction::V, &[at(0., 0.2).1, at(0., 0.9).1])
                .unwrap(),
        ];
        for v in &variants {
            for a in 0..=12 {
                for b in 0..=12 {
                    let (u, w) = at(a as f64 / 12.0, b as f64 / 12.0);
                    assert!((v.eval(u, w).unwrap() - s.eval(u, w).unwrap()).length() < 1e-12);
                }
            }
        }
        for direction in [Direction::U, Direction::V] {
            let (lo, hi) = s
                .split(
                    direction,
                    if direction == Direction::U {
                        at(0.45, 0.).0
                    } else {
                        at(0., 0.45).1
                    },
                )
                .unwrap();
            for (piece, (pu0, pu1), (pv0, pv1)) in [&lo, &hi].map(|p| {
                let (du, dv) = p.domain();
                (p, du, dv)
            }) {
                for a in 0..=6 {
                    for b in 0..=6 {
                        let u = pu0 + (pu1 - pu0) * a as f64 / 6.0;
                        let w = pv0 + (pv1 - pv0) * b as f64 / 6.0;
                        assert!(
                            (piece.eval(u, w).unwrap() - s.eval(u, w).unwrap()).length() < 1e-12
                        );
                    }
                }
            }
        }
        let patches = s.to_bezier().unwrap();
        let spans = |k: &KnotVector| k.breaks().windows(2).filter(|w| w[1] > w[0]).count();
        assert_eq!(
            patches.len(),
            spans(s.knots(Direction::U)) * spans(s.knots(Direction::V))
        );
        for p in &patches {
            for (f, g) in [(0.0, 0.0), (0.3, 0.8), (1.0, 0.5), (1.0, 1.0)] {
                let u = p.u.0 + f * (p.u.1 - p.u.0);
                let w = p.v.0 + g * (p.v.1 - p.v.0);
                assert!((p.eval(u, w) - s.eval(u, w).unwrap()).length() < 1e-12);
            }
        }
    }
    // The cylinder has radius 1 everywhere.
    for a in 0..=40 {
        for b in 0..=4 {
            let p = cyl.eval(4.0 * a as f64 / 40.0, b as f64 / 4.0).unwrap();
            assert!((p.truncate().length() - 1.0).abs() < 1e-12);
            assert!((p.z - 2.0 * b as f64 / 4.0).abs() < 1e-14);
        }
    }
}

#[test]
fn surface_derivatives_match_central_differences() {
    let mut rng = Rng(71);
    let knots_u = KnotVector::new(vec![0., 0., 0., 0., 0.7, 1.5, 2., 2., 2., 2.], 3).unwrap();
    let knots_v = KnotVector::new(vec![-2., -1., 0., 1., 2.5, 3., 4.], 2).unwrap();
    for rational in [false, true] {
        let points: Vec<DVec3> = (0..6 * 4).map(|_| rng.v3(5.0)).collect();
        let weights = rational.then(|| (0..6 * 4).map(|_| 0.4 + rng.next().abs()).collect());
        let s = NurbsSurface::new(points, 6, 4, knots_u.clone(), knots_v.clone(), weights).unwrap();
        for (u, v) in [(0.3, 0.5), (1.1, 1.7), (1.8, 2.2), (0.9, 0.2)] {
            let d = s.derivatives(u, v).unwrap();
            let f = |u: f64, v: f64| s.eval(u, v).unwrap();
            assert!((d.point - f(u, v)).length() < 1e-13);
            let h = 1e-6;
            let du = (f(u + h, v) - f(u - h, v)) / (2.0 * h);
            let dv = (f(u, v + h) - f(u, v - h)) / (2.0 * h);
            assert!(
                (d.du - du).length() < 1e-6 * (1.0 + du.length()),
                "du {rational}"
            );
            assert!(
                (d.dv - dv).length() < 1e-6 * (1.0 + dv.length()),
                "dv {rational}"
            );
            let h = 1e-4;
            let duu = (f(u + h, v) - f(u, v) * 2.0 + f(u - h, v)) / (h * h);
            let dvv = (f(u, v + h) - f(u, v) * 2.0 + f(u, v - h)) / (h * h);
            let duv = (f(u + h, v + h) - f(u + h, v - h) - f(u - h, v + h) + f(u - h, v - h))
                / (4.0 * h * h);
            assert!(
                (d.duu - duu).length() < 1e-4 * (1.0 + duu.length()),
                "duu {rational}"
            );
            assert!(
                (d.dvv - dvv).length() < 1e-4 * (1.0 + dvv.length()),
                "dvv {rational}"
            );
            assert!(
                (d.duv - duv).length() < 1e-4 * (1.0 + duv.length()),
                "duv {rational}"
            );
        }
    }
    // The cylinder: ∂S/∂v is the axis direction, |∂S/∂u| × curvature radius 1.
    let cyl = cylinder();
    let d = cyl.derivatives(0.4, 0.3).unwrap();
    assert!((d.dv - DVec3::new(0.0, 0.0, 2.0)).length() < 1e-14);
    assert!(d.duv.length() < 1e-14 && d.dvv.length() < 1e-14);
    assert!(d.point.truncate().dot(d.du.truncate()).abs() < 1e-13);
}

// ---------------------------------------------------------------------------
// errors
// ---------------------------------------------------------------------------

#[test]
fn bad_input_gives_typed_errors() {
    let p3 = vec![DVec2::ZERO, DVec2::X, DVec2::Y];
    let k = |v: &[f64]| v.to_vec();
    assert_eq!(
        NurbsCurve::new(p3.clone(), 0, k(&[0., 1., 2., 3.]), None),
        Err(NurbsError::BadDegree { degree: 0 })
    );
    assert_eq!(
        NurbsCurve::new(p3.clone(), 3, k(&[0.; 7]), None),
        Err(NurbsError::TooFewPoints {
            degree: 3,
            closed: false,
            needed: 4,
            got: 3
        })
    );
    assert_eq!(
        NurbsCurve::new(p3.clone(), 2, k(&[0., 0., 0., 1., 1.]), None),
        Err(NurbsError::WrongKnotCount {
            expected: 6,
            got: 5
        })
    );
    assert_eq!(
        NurbsCurve::new(p3.clone(), 2, k(&[0., 0., 2., 1., 3., 3.]), None),
        Err(NurbsError::DecreasingKnots {
            index: 3,
            previous: 2.0,
            value: 1.0
        })
    );
    assert_eq!(
        NurbsCurve::new(p3.clone(), 1, k(&[0., 1., 1., 1., 2.]), None),
        Err(NurbsError::MultiplicityTooHigh {
            knot: 1.0,
            multiplicity: 3,
            max: 2
        })
    );
    assert!(matches!(
        NurbsCurve::new(p3.clone(), 2, k(&[0., 0., 0., f64::NAN, 1., 1.]), None),
        Err(NurbsError::NonFiniteKnot { index: 3, value }) if value.is_nan()
    ));
    assert!(matches!(
        NurbsCurve::new(p3.clone(), 2, k(&[0., 0., 0., f64::INFINITY, 1., 1.]), None),
        Err(NurbsError::NonFiniteKnot { index: 3, .. })
    ));
    assert_eq!(
        NurbsCurve::new(p3.clone(), 1, k(&[-1e308, -1e308, 0.0, 1e308, 1e308]), None),
        Err(NurbsError::KnotRangeTooWide {
            first: -1e308,
            last: 1e308
        })
    );
    assert_eq!(
        NurbsCurve::new(p3.clone(), 1, k(&[0., 1., 1., 1.5, 2.]), None).map(|c| c.domain()),
        Ok((1.0, 1.5))
    );
    assert_eq!(
        NurbsCurve::new(vec![DVec2::ZERO, DVec2::X], 1, k(&[0., 1., 1., 2.]), None),
        Err(NurbsError::EmptyDomain {
            start: 1.0,
            end: 1.0
        })
    );
    let mut bad = p3.clone();
    bad[1].y = f64::NAN;
    assert_eq!(
        NurbsCurve::new(bad, 2, k(&[0., 0., 0., 1., 1., 1.]), None),
        Err(NurbsError::NonFinitePoint { index: 1 })
    );
    let bern = k(&[0., 0., 0., 1., 1., 1.]);
    assert_eq!(
        NurbsCurve::new(p3.clone(), 2, bern.clone(), Some(vec![1.0, 1.0])),
        Err(NurbsError::WrongWeightCount {
            expected: 3,
            got: 2
        })
    );
    for (w, index) in [(0.0, 2), (-1.0, 0), (f64::INFINITY, 1)] {
        let mut weights = vec![1.0; 3];
        weights[index] = w;
        assert_eq!(
            NurbsCurve::new(p3.clone(), 2, bern.clone(), Some(weights)),
            Err(NurbsError::BadWeight { index, weight: w })
        );
    }
    assert!(matches!(
        NurbsCurve::new(p3.clone(), 2, bern.clone(), Some(vec![1.0, f64::NAN, 1.0])),
        Err(NurbsError::BadWeight { index: 1, .. })
    ));
    assert_eq!(
        NurbsCurve::new(
            vec![DVec2::ZERO, DVec2::splat(1e300), DVec2::X],
            2,
            bern.clone(),
            Some(vec![1.0, 1e10, 1.0])
        ),
        Err(NurbsError::WeightedOverflow { index: 1 })
    );

    let c = NurbsCurve::new(p3.clone(), 2, bern.clone(), None).unwrap();
    for t in [-0.1, 1.5, f64::NAN, f64::INFINITY] {
        let e = c.eval(t).unwrap_err();
        assert!(
            matches!(
                e,
                NurbsError::OutsideDomain {
                    start: 0.0,
                    end: 1.0,
                    ..
                }
            ),
            "{e}"
        );
        assert!(c.derivatives(t).is_err() && c.insert(t).is_err() && c.knots().basis(t).is_err());
    }
    assert_eq!(
        c.insert(0.0),
        Err(NurbsError::MultiplicityTooHigh {
            knot: 0.0,
            multiplicity: 4,
            max: 3
        })
    );
    assert_eq!(
        c.insert(0.5).unwrap().insert_times(0.5, 3),
        Err(NurbsError::MultiplicityTooHigh {
            knot: 0.5,
            multiplicity: 4,
            max: 3
        })
    );
    assert!(matches!(
        c.refine_knots(&[0.2, 0.2, 0.2, 0.2]),
        Err(NurbsError::MultiplicityTooHigh {
            multiplicity: 4,
            ..
        })
    ));
    for t in [0.0, 1.0, 2.0] {
        assert_eq!(
            c.split(t),
            Err(NurbsError::SplitNotInterior {
                t,
                start: 0.0,
                end: 1.0
            })
        );
    }
    assert_eq!(
        c.knots().basis_function(3, 0.5),
        Err(NurbsError::NoSuchBasisFunction { index: 3, count: 3 })
    );
    assert_eq!(
        c.sample(usize::MAX),
        Err(NurbsError::TooManyPoints {
            max: curve::MAX_POINTS
        })
    );
    assert_eq!(c.sample(0).unwrap(), Vec::<DVec2>::new());
    assert_eq!(c.sample(1).unwrap(), vec![DVec2::ZERO]);
    assert_eq!(
        c.sample(3).unwrap(),
        vec![DVec2::ZERO, DVec2::new(0.5, 0.25), DVec2::Y]
    );

    // Closed curves.
    assert_eq!(
        NurbsCurve::closed(p3.clone(), 4, k(&[0., 1., 2., 3.]), None),
        Err(NurbsError::TooFewPoints {
            degree: 4,
            closed: true,
            needed: 4,
            got: 3
        })
    );
    assert_eq!(
        NurbsCurve::closed(p3.clone(), 2, k(&[0., 1., 2.]), None),
        Err(NurbsError::WrongKnotCount {
            expected: 4,
            got: 3
        })
    );
    assert_eq!(
        NurbsCurve::closed(p3.clone(), 2, k(&[1., 1., 1., 1.]), None),
        Err(NurbsError::EmptyDomain {
            start: 1.0,
            end: 1.0
        })
    );
    // s_3 = 1 is the image of s_0 = 0: the periodic sequence …, 0 (= s_2 - T),
    // 0, 0, 1, 1, … has 0 three times, more than d + 1 = 2.
    assert!(matches!(
        NurbsCurve::closed(p3.clone(), 1, k(&[0., 0., 1., 1.]), None),
        Err(NurbsError::MultiplicityTooHigh {
            multiplicity: 3,
            max: 2,
            ..
        })
    ));
    let closed = NurbsCurve::closed(p3.clone(), 2, k(&[0., 1., 2., 3.]), None).unwrap();
    assert!(closed.eval(1e9 + 0.5).is_ok());
    assert!(matches!(
        closed.eval(f64::NAN),
        Err(NurbsError::OutsideDomain { .. })
    ));
    assert!(matches!(
        closed.split(3.0),
        Err(NurbsError::SplitNotInterior { .. })
    ));

    // Surfaces.
    let ku = KnotVector::clamped(3, 2).unwrap();
    let kv = KnotVector::clamped(2, 1).unwrap();
    assert_eq!(
        NurbsSurface::new(vec![DVec3::ZERO; 5], 3, 2, ku.clone(), kv.clone(), None),
        Err(NurbsError::WrongPointCount {
            nu: 3,
            nv: 2,
            got: 5
        })
    );
    assert_eq!(
        NurbsSurface::new(vec![DVec3::ZERO; 6], 2, 3, ku.clone(), kv.clone(), None),
        Err(NurbsError::WrongKnotCount {
            expected: 5,
            got: 6
        }
        .along_for_test(Direction::U))
    );
    let s = NurbsSurface::new(vec![DVec3::ZERO; 6], 3, 2, ku, kv, None).unwrap();
    assert_eq!(
        s.eval(0.5, 1.5),
        Err(NurbsError::OutsideDomain {
            t: 1.5,
            start: 0.0,
            end: 1.0
        }
        .along_for_test(Direction::V))
    );
    assert!(matches!(
        s.insert(Direction::V, 1.0),
        Err(NurbsError::Surface {
            direction: Direction::V,
            ..
        })
    ));
    let g = ControlGrid::new(vec![DVec3::ZERO; 9], 3, 3, 5, true, true).unwrap();
    assert_eq!(
        NurbsSurface::from_control_grid(&g),
        Err(NurbsError::TooFewPoints {
            degree: 5,
            closed: true,
            needed: 5,
            got: 3
        }
        .along_for_test(Direction::U))
    );
    assert_eq!(
        s.eval(0.5, 1.5).unwrap_err().to_string(),
        "along v: parameter 1.5 is outside the domain [0, 1]"
    );
}

trait Along {
    fn along_for_test(self, direction: Direction) -> NurbsError;
}

impl Along for NurbsError {
    fn along_for_test(self, direction: Direction) -> NurbsError {
        NurbsError::Surface {
            direction,
            source: Box::new(self),
        }
    }
}

// ---------------------------------------------------------------------------
// property tests
// ---------------------------------------------------------------------------

/// A random curve: degree 1-5, d + 1 to d + 6 points, clamped or not, knots
/// repeated up to d times inside, rational or not.
fn arb_curve() -> impl Strategy<Value = NurbsCurve<DVec2>> {
    (
        1usize..=5,
        0usize..6,
        any::<bool>(),
        any::<bool>(),
        any::<u64>(),
    )
        .prop_map(|(degree, extra, clamped, rational, seed)| {
            let mut rng = Rng(seed | 1);
            let knots = random_knots(&mut rng, degree, degree + 1 + extra, clamped);
            let n = knots.control_count();
            let points = (0..n).map(|_| rng.v2(5.0)).collect();
            let weights = rational.then(|| (0..n).map(|_| 0.2 + 4.0 * rng.next().abs()).collect());
            NurbsCurve::from_knot_vector(points, knots, weights).unwrap()
        })
}

/// Insertion parameters: a fraction of the domain, or (when `pick` is set)
/// an existing knot, to exercise repeated knots and the domain's ends.
fn pick_parameter(c: &NurbsCurve<DVec2>, f: f64, pick: Option<usize>) -> f64 {
    let (a, b) = c.domain();
    match pick {
        Some(i) => {
            let breaks = c.knots().breaks();
            breaks[i % breaks.len()]
        }
        None => a + f * (b - a),
    }
}

fn scale(c: &NurbsCurve<DVec2>) -> f64 {
    c.points().iter().map(|p| p.length()).fold(1.0, f64::max)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(192))]

    #[test]
    fn insertions_keep_the_shape(
        c in arb_curve(),
        inserts in prop::collection::vec((0.0f64..=1.0, prop::option::of(0usize..20)), 1..=4),
    ) {
        let d = c.degree();
        let mut cur = c.clone();
        let mut inserted = Vec::new();
        for (f, pick) in inserts {
            let t = pick_parameter(&c, f, pick);
            let result = cur.insert(t);
            if cur.knots().multiplicity(t) + 1 > d + 1 {
                let is_multiplicity_error = matches!(result, Err(NurbsError::MultiplicityTooHigh { .. }));
                prop_assert!(is_multiplicity_error);
                continue;
            }
            let next = result.unwrap();
            prop_assert_eq!(next.knots().knot_count(), cur.knots().knot_count() + 1);
            prop_assert_eq!(next.points().len(), cur.points().len() + 1);
            prop_assert!(next.knots().as_slice().windows(2).all(|w| w[0] <= w[1]));
            prop_assert_eq!(next.domain(), c.domain());
            prop_assert_eq!(next.knots().multiplicity(t), cur.knots().multiplicity(t) + 1);
            cur = next;
            inserted.push(t);
        }
        let tol = 1e-11 * scale(&c);
        for t in params(c.domain(), 64).chain(c.knots().breaks().iter().copied()) {
            let (p, q) = (c.eval(t).unwrap(), cur.eval(t).unwrap());
            prop_assert!((p - q).length() <= tol, "t={} {} vs {}", t, p, q);
        }
        // Refinement with the same knots at once equals the sequence.
        let refined = c.refine_knots(&inserted).unwrap();
        prop_assert_eq!(refined.knots(), cur.knots());
        for (p, q) in refined.points().iter().zip(cur.points()) {
            prop_assert!((*p - *q).length() <= tol);
        }
        if let (Some(w1), Some(w2)) = (refined.weights(), cur.weights()) {
            for (a, b) in w1.iter().zip(w2) {
                prop_assert!((a - b).abs() <= 1e-12 * a.abs().max(1.0));
            }
        }
    }

    #[test]
    fn bezier_and_split_keep_the_shape(c in arb_curve(), f in 0.01f64..0.99) {
        let tol = 1e-11 * scale(&c);
        for s in c.to_bezier().unwrap() {
            for t in params((s.start, s.end), 8) {
                prop_assert!((s.eval(t) - c.eval(t).unwrap()).length() <= tol);
            }
        }
        let (a, b) = c.domain();
        let t = a + f * (b - a);
        let (left, right) = c.split(t).unwrap();
        for s in params((a, t), 10) {
            prop_assert!((left.eval(s).unwrap() - c.eval(s).unwrap()).length() <= tol);
        }
        for s in params((t, b), 10) {
            prop_assert!((right.eval(s).unwrap() - c.eval(s).unwrap()).length() <= tol);
        }
    }

    #[test]
    fn closed_insertions_keep_the_shape(
        degree in 1usize..=5,
        extra in 0usize..4,
        seed in any::<u64>(),
        rational in any::<bool>(),
        ts in prop::collection::vec(-10.0f64..10.0, 1..=4),
    ) {
        let mut rng = Rng(seed | 1);
        let n = degree.max(2) + extra;
        let points: Vec<DVec2> = (0..n).map(|_| rng.v2(5.0)).collect();
        let mut breaks = vec![rng.next()];
        for _ in 0..n {
            let last = *breaks.last().unwrap();
            breaks.push(last + 0.1 + rng.next().abs());
        }
        let weights = rational.then(|| (0..n).map(|_| 0.3 + rng.next().abs()).collect());
        let c = NurbsCurve::closed(points, degree, breaks, weights).unwrap();
        let q = c.insert_many(&ts).unwrap();
        prop_assert!(q.is_closed());
        prop_assert_eq!(q.distinct_points().len(), n + ts.len());
        prop_assert_eq!(&q.points()[n + ts.len()..], &q.points()[..degree]);
        let r = c.refine_knots(&ts).unwrap();
        prop_assert_eq!(r.knots().breaks().len(), q.knots().breaks().len());
        let tol = 1e-11 * scale(&c);
        for t in params(c.domain(), 50) {
            let p = c.eval(t).unwrap();
            prop_assert!((q.eval(t).unwrap() - p).length() <= tol);
            prop_assert!((r.eval(t).unwrap() - p).length() <= tol);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// Broken inputs are refused with the variant that names the break.
    #[test]
    fn bad_input_is_refused_with_its_variant(
        c in arb_curve(),
        which in 0usize..4,
        at in any::<prop::sample::Index>(),
    ) {
        let (d, points, knots) = (c.degree(), c.points().to_vec(), c.knots().as_slice().to_vec());
        match which {
            0 => {
                // A knot made smaller than its predecessor.
                let index = 1 + at.index(knots.len() - 1);
                let mut bad = knots.clone();
                bad[index] = bad[index - 1] - 0.5;
                let e = NurbsCurve::new(points, d, bad.clone(), None).unwrap_err();
                let first = (1..bad.len()).find(|&i| bad[i] < bad[i - 1]).unwrap();
                prop_assert_eq!(e, NurbsError::DecreasingKnots { index: first, previous: bad[first - 1], value: bad[first] });
            }
            1 => {
                // One knot too many or too few.
                let mut bad = knots.clone();
                if at.index(2) == 0 { bad.pop(); } else { bad.push(bad[bad.len() - 1] + 1.0); }
                let e = NurbsCurve::new(points.clone(), d, bad.clone(), None).unwrap_err();
                prop_assert_eq!(e, NurbsError::WrongKnotCount { expected: points.len() + d + 1, got: bad.len() });
            }
            2 => {
                // A non-positive weight.
                let index = at.index(points.len());
                let mut w = vec![1.0; points.len()];
                w[index] = -(index as f64);
                let e = NurbsCurve::new(points, d, knots, Some(w.clone())).unwrap_err();
                prop_assert_eq!(e, NurbsError::BadWeight { index, weight: w[index] });
            }
            _ => {
                // A parameter outside the domain.
                let (start, end) = c.domain();
                let t = if at.index(2) == 0 { start - 1e-9 - at.index(5) as f64 } else { end + 1e-9 };
                prop_assert_eq!(c.eval(t).unwrap_err(), NurbsError::OutsideDomain { t, start, end });
            }
        }
    }
}
