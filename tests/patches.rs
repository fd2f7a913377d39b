//! Tensor-product B-spline patches: splitting against analytic evaluation.

mod support;

use glam::{DVec2, DVec3};
use subdiv::curve::{self, CurveError, CurveScheme};
use subdiv::patch::{ControlGrid, Direction, PatchError};
use support::{TOPOLOGIES, wavy};

#[test]
fn counts_open_and_periodic() {
    for degree in [2, 3] {
        for (cu, cv) in TOPOLOGIES {
            let g = wavy(5, 6, degree, cu, cv, 1);
            let r = g.refine().unwrap();
            let expect = |n: usize, closed: bool| if closed { 2 * n } else { 2 * n - degree };
            assert_eq!((r.nu(), r.nv()), (expect(5, cu), expect(6, cv)));
            assert_eq!(r.points().len(), r.nu() * r.nv());
            let r3 = g.refine_levels(3).unwrap();
            let mut n = (5, 6);
            for _ in 0..3 {
                n = (expect(n.0, cu), expect(n.1, cv));
            }
            assert_eq!((r3.nu(), r3.nv()), n);
        }
    }
}

#[test]
fn splitting_is_the_curve_rule_along_u_then_v() {
    for degree in [2, 3] {
        for (cu, cv) in TOPOLOGIES {
            let g = wavy(5, 4, degree, cu, cv, 2);
            let r = g.refine().unwrap();
            // Rows first, by the curve rule...
            let rows: Vec<Vec<DVec3>> = (0..g.nv())
                .map(|j| curve::bspline(g.row(j), degree, cu).unwrap())
                .collect();
            // ...then columns.
            for i in 0..r.nu() {
                let column: Vec<DVec3> = rows.iter().map(|row| row[i]).collect();
                let refined = curve::bspline(&column, degree, cv).unwrap();
                for (j, &p) in refined.iter().enumerate() {
                    assert_eq!(r.point(i, j), p);
                }
            }
            // Columns first gives the same grid (the rules commute) up to rounding.
            let cols: Vec<Vec<DVec3>> = (0..g.nu())
                .map(|i| {
                    let c: Vec<DVec3> = (0..g.nv()).map(|j| g.point(i, j)).collect();
                    curve::bspline(&c, degree, cv).unwrap()
                })
                .collect();
            for j in 0..r.nv() {
                let row: Vec<DVec3> = cols.iter().map(|c| c[j]).collect();
                for (i, &p) in curve::bspline(&row, degree, cu).unwrap().iter().enumerate() {
                    assert!((r.point(i, j) - p).length() < 1e-15);
                }
            }
        }
    }
}

#[test]
fn biquadratic_split_is_the_tensor_product_of_chaikin_weights() {
    // Integer heights keep everything exact: 9/16, 3/16, 3/16, 1/16.
    let g = ControlGrid::from_fn(4, 3, 2, false, false, |i, j| {
        DVec3::new(i as f64, j as f64, ((i * 7 + j * 3) % 5) as f64)
    })
    .unwrap();
    let r = g.refine().unwrap();
    assert_eq!((r.nu(), r.nv()), (6, 4));
    for j in 0..g.nv() - 1 {
        for i in 0..g.nu() - 1 {
            let p = |a: usize, b: usize| g.point(i + a, j + b);
            let near = |a: usize, b: usize| {
                let (fa, fb) = (a, b);
                p(fa, fb) * (9.0 / 16.0)
                    + p(1 - fa, fb) * (3.0 / 16.0)
                    + p(fa, 1 - fb) * (3.0 / 16.0)
                    + p(1 - fa, 1 - fb) * (1.0 / 16.0)
            };
            for (a, b) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                assert_eq!(
                    r.point(2 * i + a, 2 * j + b),
                    near(a, b),
                    "cell ({i}, {j}) corner ({a}, {b})"
                );
            }
        }
    }
}

#[test]
fn evaluation_at_knots_uses_the_hand_derived_masks() {
    // Bicubic at integer parameters: the tensor product of (1, 4, 1) / 6.
    let g = wavy(6, 5, 3, false, false, 3);
    for (s, t) in [(0usize, 0usize), (1, 2), (3, 1), (3, 2)] {
        let w = [1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0];
        let mut expected = DVec3::ZERO;
        for (b, wb) in w.iter().enumerate() {
            for (a, wa) in w.iter().enumerate() {
                expected += g.point(s + a, t + b) * (wa * wb);
            }
        }
        let got = g.eval(s as f64, t as f64).unwrap();
        assert!((got - expected).length() < 1e-14, "({s}, {t})");
    }
    // Biquadratic at integer parameters: the average of four points.
    let g = wavy(5, 5, 2, true, false, 4);
    for (s, t) in [(0usize, 0usize), (4, 1), (2, 3)] {
        let p = |a: usize, b: usize| g.point((s + a) % 5, t + b);
        let expected = (p(0, 0) + p(1, 0) + p(0, 1) + p(1, 1)) / 4.0;
        assert!((g.eval(s as f64, t as f64).unwrap() - expected).length() < 1e-14);
    }
    // The centre of a biquadratic span: (1, 6, 1) / 8 in each direction.
    let w = [1.0 / 8.0, 6.0 / 8.0, 1.0 / 8.0];
    let mut expected = DVec3::ZERO;
    for (b, wb) in w.iter().enumerate() {
        for (a, wa) in w.iter().enumerate() {
            expected += g.point(1 + a, 2 + b) * (wa * wb);
        }
    }
    assert!((g.eval(1.5, 2.5).unwrap() - expected).length() < 1e-14);
}

#[test]
fn linear_data_is_reproduced_at_the_greville_abscissae() {
    // Σ_i (i - (d-1)/2) N_d(s + d - i) = s: a grid of points (i, j, 2i - j + 1)
    // gives the plane S(s, t) = (g_s, g_t, 2 g_s - g_t + 1) with g = param + (d-1)/2.
    for degree in [2, 3] {
        let g = ControlGrid::from_fn(6, 5, degree, false, false, |i, j| {
            DVec3::new(i as f64, j as f64, 2.0 * i as f64 - j as f64 + 1.0)
        })
        .unwrap();
        let shift = (degree as f64 - 1.0) / 2.0;
        let ([_, s1], [_, t1]) = g.domain();
        for k in 0..=10 {
            let (s, t) = (s1 * k as f64 / 10.0, t1 * (10 - k) as f64 / 10.0);
            let (x, y) = (s + shift, t + shift);
            let p = g.eval(s, t).unwrap();
            assert!((p - DVec3::new(x, y, 2.0 * x - y + 1.0)).length() < 1e-13);
        }
    }
}

#[test]
fn refined_grids_describe_the_same_surface_at_twice_the_parameters() {
    for degree in [2, 3] {
        for (cu, cv) in TOPOLOGIES {
            let g = wavy(6, 5, degree, cu, cv, 10 + degree as u64);
            let ([_, s1], [_, t1]) = g.domain();
            for k in 1..=3u32 {
                let r = g.refine_levels(k).unwrap();
                let scale = f64::from(1u32 << k);
                assert_eq!(r.domain(), ([0.0, s1 * scale], [0.0, t1 * scale]));
                for a in 0..=24 {
                    for b in 0..=24 {
                        let (s, t) = (s1 * a as f64 / 24.0, t1 * b as f64 / 24.0);
                        let (p, q) = (g.eval(s, t).unwrap(), r.eval(s * scale, t * scale).unwrap());
                        assert!(
                            (p - q).length() < 1e-12,
                            "degree {degree} closed ({cu}, {cv}) k={k} ({s}, {t})"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn refinement_converges_to_the_evaluated_surface() {
    // After k levels each control point is within O(4^-k) of the surface at its
    // Greville parameters: the largest distance falls by a factor of 4 a level.
    for degree in [2, 3] {
        for (cu, cv) in TOPOLOGIES {
            let g = wavy(6, 6, degree, cu, cv, 20 + degree as u64);
            let ([_, s1], [_, t1]) = g.domain();
            let mut errors = Vec::new();
            let mut r = g.clone();
            for k in 0..=6u32 {
                if k > 0 {
                    r = r.refine().unwrap();
                }
                let scale = f64::from(1u32 << k);
                let mut max: f64 = 0.0;
                for j in 0..r.nv() {
                    for i in 0..r.nu() {
                        let (s, t) = r.greville(i, j);
                        let (mut s, mut t) = (s / scale, t / scale);
                        if cu {
                            s = s.rem_euclid(s1);
                        }
                        if cv {
                            t = t.rem_euclid(t1);
                        }
                        if !(0.0..=s1).contains(&s) || !(0.0..=t1).contains(&t) {
                            continue;
                        }
                        let d = (r.point(i, j) - g.eval(s, t).unwrap()).length();
                        max = max.max(d);
                    }
                }
                errors.push(max);
            }
            for k in 3..errors.len() {
                let ratio = errors[k - 1] / errors[k];
                assert!(
                    (3.6..=4.4).contains(&ratio),
                    "degree {degree} closed ({cu}, {cv}): errors {errors:?}"
                );
            }
            assert!(errors[6] < 2e-3, "{errors:?}");
        }
    }
}

#[test]
fn periodic_directions_wrap() {
    let g = wavy(5, 4, 3, true, true, 30);
    for (s, t) in [(0.3, 0.7), (4.9, 3.1), (2.0, 0.0)] {
        let p = g.eval(s, t).unwrap();
        for (ds, dt) in [(5.0, 0.0), (0.0, 4.0), (-10.0, -8.0)] {
            assert!((g.eval(s + ds, t + dt).unwrap() - p).length() < 1e-13);
        }
    }
    let mesh = g.to_mesh();
    assert_eq!(mesh.face_count(), 20);
    assert!(mesh.validate().is_ok());
    let open = wavy(5, 4, 3, false, false, 30).to_mesh();
    assert_eq!(open.face_count(), 12);
    assert_eq!(open.face(0), &[0, 1, 6, 5]);
}

#[test]
fn two_dimensional_grids_work_too() {
    let g = ControlGrid::<DVec2>::from_fn(4, 4, 2, false, false, |i, j| {
        DVec2::new(i as f64 + 0.1 * j as f64, j as f64)
    })
    .unwrap();
    let r = g.refine_levels(2).unwrap();
    assert!((g.eval(1.0, 0.5).unwrap() - r.eval(4.0, 2.0).unwrap()).length() < 1e-14);
}

#[test]
fn bad_grids_are_typed_errors() {
    let p = vec![DVec3::ZERO; 12];
    assert_eq!(
        ControlGrid::new(p.clone(), 5, 3, 3, false, false),
        Err(PatchError::WrongPointCount {
            nu: 5,
            nv: 3,
            got: 12
        })
    );
    assert_eq!(
        ControlGrid::new(p.clone(), 4, 3, 3, false, false),
        Err(PatchError::Curve {
            direction: Direction::V,
            source: CurveError::TooFewPoints {
                scheme: "bspline",
                closed: false,
                needed: 4,
                got: 3
            }
        })
    );
    assert!(ControlGrid::new(p.clone(), 4, 3, 3, false, true).is_ok());
    assert!(matches!(
        ControlGrid::new(p.clone(), 2, 6, 2, true, false),
        Err(PatchError::Curve {
            direction: Direction::U,
            ..
        })
    ));
    assert_eq!(
        ControlGrid::new(p.clone(), 4, 3, 0, true, true),
        Err(PatchError::BadDegree(0))
    );
    let mut bad = p.clone();
    bad[7].z = f64::NAN;
    assert_eq!(
        ControlGrid::new(bad, 4, 3, 2, false, false),
        Err(PatchError::NonFinitePoint { i: 3, j: 1 })
    );
    let g = ControlGrid::bicubic(vec![DVec3::ONE; 20], 5, 4, false, false).unwrap();
    assert_eq!(g.domain(), ([0.0, 2.0], [0.0, 1.0]));
    assert!(g.eval(2.0, 1.0).is_ok());
    assert!(matches!(
        g.eval(2.1, 0.0),
        Err(PatchError::Curve {
            direction: Direction::U,
            source: CurveError::ParameterOutOfRange { .. }
        })
    ));
    assert!(g.eval(0.0, f64::NAN).is_err());
    assert_eq!(g.refine_levels(40), Err(PatchError::TooManyPoints));
    assert_eq!(
        ControlGrid::from_fn(usize::MAX, 2, 2, false, false, |_, _| DVec3::ZERO),
        Err(PatchError::TooManyPoints)
    );
    assert_eq!(
        PatchError::Curve {
            direction: Direction::V,
            source: CurveError::TooFewPoints {
                scheme: "bspline",
                closed: false,
                needed: 4,
                got: 3
            }
        }
        .to_string(),
        "along v: bspline on an open polygon needs at least 4 points, got 3"
    );
    // The curve module agrees on the count rule.
    assert_eq!(CurveScheme::bspline(3).refined_len(5, false), 7);
}
