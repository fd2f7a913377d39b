//! The exact-limit evaluation (`Evaluation::ExactLimit`) against the limit
//! surface: single-crease patches with their sharpness agree with tables
//! that isolate the crease instead, where OpenSubdiv's `EvaluateBasis`
//! (the default) departs; the crease blending weights by hand; derivatives
//! under non-quad faces with respect to the ptex face.

use subdiv::patches::{
    self, Derivatives, Evaluation, LimitStencilOptions, PatchData, PatchMap, PatchOptions,
    PatchParam, PatchTable, PatchType, SurfaceSamples,
};
use subdiv::refiner::Refiner;
use subdiv::{Mesh, Options, shapes};

/// `mesh`'s table and points at `isolation`, single-crease patches or not.
fn table(mesh: &Mesh, isolation: u32, single_crease: bool) -> (PatchTable, Vec<f64>) {
    let options = PatchOptions::new()
        .max_isolation(isolation)
        .single_crease_patch(single_crease);
    let adaptive = Refiner::new(mesh, &Options::default())
        .unwrap()
        .refine_adaptive(options.refine_adaptive_options(), &[])
        .unwrap();
    let table = adaptive.patch_table(&options, &[]).unwrap();
    let points = adaptive
        .patch_points(&table, 3, &mesh.flat_positions())
        .unwrap();
    (table, points)
}

fn eval(
    (table, points): &(PatchTable, Vec<f64>),
    evaluation: Evaluation,
    locations: &[(u32, f64, f64)],
    derivatives: Derivatives,
) -> SurfaceSamples {
    let map = PatchMap::new(table);
    patches::evaluate_data_as(
        evaluation,
        &map,
        table,
        PatchData::Vertex,
        points,
        3,
        locations,
        derivatives,
    )
    .unwrap()
}

/// 25 locations per ptex face (a 5 × 5 grid including the edges).
fn grid(ptex_faces: usize) -> Vec<(u32, f64, f64)> {
    let mut out = Vec::new();
    for f in 0..ptex_faces as u32 {
        for i in 0..5 {
            for j in 0..5 {
                out.push((f, f64::from(i) / 4.0, f64::from(j) / 4.0));
            }
        }
    }
    out
}

fn diagonal(mesh: &Mesh) -> f64 {
    let p = mesh.flat_positions::<f64>();
    let mut lo = [f64::MAX; 3];
    let mut hi = [f64::MIN; 3];
    for v in p.chunks(3) {
        for k in 0..3 {
            lo[k] = lo[k].min(v[k]);
            hi[k] = hi[k].max(v[k]);
        }
    }
    (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt()
}

fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

fn corpus(name: &str) -> Mesh {
    shapes::corpus()
        .into_iter()
        .find(|(n, _)| n == name)
        .map(|(_, m)| m)
        .unwrap()
}

/// Single-crease patches evaluated exactly are the crease the table
/// without them isolates, at the same isolation level: positions and
/// derivatives agree to rounding (measured 2026-11-28, 25 locations per
/// ptex face including the edges: at most 1.7e-16 of the bounding-box
/// diagonal in positions, 6.7e-16 in derivatives), where OpenSubdiv's
/// `EvaluateBasis` (the default) departs by 2.6e-3 to 2.2e-2 (5.9e-3 on `cube-crease-9.99`).
#[test]
fn exact_single_crease_patches_are_the_isolated_crease() {
    for (name, departs) in [
        ("cube-crease-4.25", 2e-2),
        ("cube-crease-2.7", 1e-2),
        ("cube-crease-3", 1e-2),
        ("cube-crease-9.99", 5e-3),
        ("torus-crease-loop", 2e-3),
    ] {
        let mesh = corpus(name);
        let d = diagonal(&mesh);
        let crease = table(&mesh, 4, true);
        let singles = crease
            .0
            .arrays
            .iter()
            .flat_map(|a| &a.sharpness)
            .filter(|&&s| s > 0.0);
        assert!(
            singles.count() >= 8,
            "{name}: single-crease patches expected"
        );
        let isolated = table(&mesh, 4, false);
        let at = grid(crease.0.ptex_faces);
        let want = eval(&isolated, Evaluation::OpenSubdiv, &at, Derivatives::First);
        let exact = eval(&crease, Evaluation::ExactLimit, &at, Derivatives::First);
        let default = eval(&crease, Evaluation::OpenSubdiv, &at, Derivatives::First);
        let v = &exact.values;
        for (what, got, want) in [
            ("positions", &v.point, &want.values.point),
            ("du", &v.du, &want.values.du),
            ("dv", &v.dv, &want.values.dv),
        ] {
            let e = largest_difference(got, want) / d;
            assert!(e < 1e-14, "{name}: exact {what} depart by {e:e}");
        }
        let e = largest_difference(&default.values.point, &want.values.point) / d;
        assert!(e > departs, "{name}: the default departs by {e:e} only");
    }
}

/// Where isolation 4 resolves the crease (sharpness at most 4), the exact
/// option is the limit surface: within 2.3e-11 of the diagonal of
/// isolation 8 (measured; the local points' f32 stencils), the default
/// 2.6e-3 to 1.5e-2 away.
#[test]
fn where_isolation_resolves_the_crease_the_exact_option_is_the_limit() {
    for name in ["cube-crease-2.7", "cube-crease-3", "torus-crease-loop"] {
        let mesh = corpus(name);
        let d = diagonal(&mesh);
        let crease = table(&mesh, 4, true);
        let at = grid(crease.0.ptex_faces);
        let limit = eval(
            &table(&mesh, 8, false),
            Evaluation::OpenSubdiv,
            &at,
            Derivatives::None,
        );
        let exact = eval(&crease, Evaluation::ExactLimit, &at, Derivatives::None);
        let default = eval(&crease, Evaluation::OpenSubdiv, &at, Derivatives::None);
        let e = largest_difference(&exact.values.point, &limit.values.point) / d;
        assert!(e < 1e-10, "{name}: exact departs by {e:e}");
        let e = largest_difference(&default.values.point, &limit.values.point) / d;
        assert!(e > 2e-3, "{name}: the default departs by {e:e} only");
    }
}

/// The weights of a single-crease patch at depth 0 (the whole ptex face),
/// its crease along edge 1 (`s = 1`): rows of B-spline weights in `t`
/// times the weights across the crease in `s`.
fn crease_weights(sharpness: f32, s: f64, t: f64) -> Vec<f64> {
    let p = PatchParam::new(0, 0, 0, 0, false, 0b0010, 0, true);
    patches::evaluate_basis_exact(PatchType::Regular, p, sharpness, s, t, Derivatives::None)
        .unwrap()
        .point
}

/// The uniform cubic B-spline weights at `t`.
fn bspline(t: f64) -> [f64; 4] {
    let c = 1.0 - t;
    [
        c * c * c / 6.0,
        (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0,
        (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0,
        t * t * t / 6.0,
    ]
}

/// `across` (weights of the four columns) times the B-spline rows at `t`.
fn tensor(across: [f64; 4], t: f64) -> Vec<f64> {
    let rows = bspline(t);
    (0..16).map(|i| across[i % 4] * rows[i / 4]).collect()
}

fn assert_close(got: &[f64], want: &[f64], tolerance: f64, what: &str) {
    let e = largest_difference(got, want);
    assert!(e <= tolerance, "{what}: {e:e} off\n{got:?}\n{want:?}");
}

/// The crease blending weights, derived by hand from the subdivision rules
/// across a crease (the crease vertex kept by the sharp rule, the edge
/// points across it midpoints, the smooth vertex rule `(1, 6, 1) / 8`).
#[test]
fn crease_weights_by_hand() {
    let t = 0.3;
    // Sharpness near 0: the smooth B-spline (no phantom points).
    for s in [0.0, 0.4, 0.8, 1.0] {
        assert_close(
            &crease_weights(1e-7, s, t),
            &tensor(bspline(s), t),
            1e-6,
            "sharpness 0+",
        );
    }
    // Sharpness 10 (beyond any depth limit): up to 1 - 2^-10 the
    // infinitely sharp crease — the boundary B-spline along that edge,
    // the phantom column 2 P2 - P1 folded in: what `EvaluateBasis` gives.
    let p = PatchParam::new(0, 0, 0, 0, false, 0b0010, 0, true);
    for s in [0.0, 0.5, 0.9, 0.999] {
        let sharp =
            patches::evaluate_basis(PatchType::Regular, p, s, t, Derivatives::None).unwrap();
        let b = bspline(s);
        let folded = [b[0], b[1] - b[3], b[2] + 2.0 * b[3], 0.0];
        assert_close(&sharp.point, &tensor(folded, t), 1e-15, "boundary B-spline");
        assert_close(
            &crease_weights(10.0, s, t),
            &sharp.point,
            1e-15,
            "sharpness 10",
        );
    }
    // Sharpness 1: one sharp step, then smooth. The level-1 points across
    // the crease, as weights of P0..P3: P1' = (P0 + 6 P1 + P2) / 8, the
    // edge point (P1 + P2) / 2, the crease vertex P2, the edge point
    // (P2 + P3) / 2; the half of the patch nearest the crease is their
    // B-spline.
    let level1 = [
        [1.0 / 8.0, 6.0 / 8.0, 1.0 / 8.0, 0.0],
        [0.0, 0.5, 0.5, 0.0],
        [0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 0.5, 0.5],
    ];
    for x in [0.0, 0.25, 0.5, 1.0] {
        let b = bspline(x);
        let across: [f64; 4] = std::array::from_fn(|k| (0..4).map(|i| b[i] * level1[i][k]).sum());
        let s = 0.5 + 0.5 * x;
        assert_close(
            &crease_weights(1.0, s, t),
            &tensor(across, t),
            1e-15,
            "sharpness 1",
        );
    }
    // On the crease itself: (P1 + 10 P2 + P3) / 12.
    assert_close(
        &crease_weights(1.0, 1.0, t),
        &tensor([0.0, 1.0 / 12.0, 10.0 / 12.0, 1.0 / 12.0], t),
        1e-15,
        "sharpness 1 on the crease",
    );
    // The first half is the infinitely sharp surface.
    assert_close(
        &crease_weights(1.0, 0.3, t),
        &crease_weights(10.0, 0.3, t),
        1e-15,
        "first half",
    );
    // A fractional sharpness blends the two integer ones linearly.
    for s in [0.2, 0.6, 0.8, 1.0] {
        let (w1, w2) = (crease_weights(1.0, s, t), crease_weights(2.0, s, t));
        let mixed: Vec<f64> = w1
            .iter()
            .zip(&w2)
            .map(|(a, b)| 0.75 * a + 0.25 * b)
            .collect();
        assert_close(&crease_weights(1.25, s, t), &mixed, 1e-15, "sharpness 1.25");
    }
    // The crease on the other edges: the same weights, rotated.
    let w = crease_weights(1.5, 0.8, t);
    for (edge, u, v) in [(0u16, t, 0.2), (2, t, 0.8), (3, 0.2, t)] {
        let p = PatchParam::new(0, 0, 0, 0, false, 1 << edge, 0, true);
        let r = patches::evaluate_basis_exact(PatchType::Regular, p, 1.5, u, v, Derivatives::None)
            .unwrap()
            .point;
        // Point (col, row) of edge 1's layout for each point of this one.
        let want: Vec<f64> = (0..16)
            .map(|i| {
                let (col, row) = (i % 4, i / 4);
                match edge {
                    0 => w[4 * col + (3 - row)],
                    2 => w[4 * col + row],
                    _ => w[4 * row + (3 - col)],
                }
            })
            .collect();
        assert_close(&r, &want, 1e-15, "rotated crease");
    }
}

/// Derivatives under a non-quad face: OpenSubdiv's are twice those in the
/// ptex square; the exact option's are the ptex square's, as central
/// differences of the positions confirm.
#[test]
fn derivatives_under_non_quad_faces_are_the_ptex_faces() {
    let mesh = corpus("prism-5");
    let t = table(&mesh, 3, false);
    let map = PatchMap::new(&t.0);
    // Ptex faces of the pentagons: patches with a non-quad root.
    let sub: Vec<u32> = (0..t.0.ptex_faces as u32)
        .filter(|&f| {
            let h = map.find_patch(f, 0.4, 0.3).unwrap();
            t.0.arrays[h.array].params[h.patch].non_quad_root()
        })
        .collect();
    assert_eq!(sub.len(), 10);
    let h = 1e-6;
    for &f in &sub {
        let (u, v) = (0.4, 0.3);
        let at = [
            (f, u, v),
            (f, u + h, v),
            (f, u - h, v),
            (f, u, v + h),
            (f, u, v - h),
        ];
        let exact = eval(&t, Evaluation::ExactLimit, &at, Derivatives::First);
        let default = eval(&t, Evaluation::OpenSubdiv, &at, Derivatives::First);
        let p = &exact.values.point;
        for k in 0..3 {
            let du = (p[3 + k] - p[6 + k]) / (2.0 * h);
            let dv = (p[9 + k] - p[12 + k]) / (2.0 * h);
            assert!(
                (exact.values.du[k] - du).abs() < 1e-6,
                "du {} vs {du}",
                exact.values.du[k]
            );
            assert!(
                (exact.values.dv[k] - dv).abs() < 1e-6,
                "dv {} vs {dv}",
                exact.values.dv[k]
            );
            assert_eq!(default.values.du[k], 2.0 * exact.values.du[k]);
            assert_eq!(default.values.dv[k], 2.0 * exact.values.dv[k]);
        }
        assert_eq!(default.values.point, exact.values.point);
    }
}

/// Limit stencils at locations with the exact option: their derivative
/// weights under a non-quad face are half OpenSubdiv's (their tables have
/// no single-crease patches), positions unchanged; under quads the same.
#[test]
fn location_stencils_take_the_option() {
    let mesh = corpus("prism-5");
    let adaptive = Refiner::new(&mesh, &Options::default())
        .unwrap()
        .refine_adaptive(subdiv::AdaptiveOptions::new(3), &[])
        .unwrap();
    let at = grid(
        adaptive
            .patch_table(&PatchOptions::new().max_isolation(3), &[])
            .unwrap()
            .ptex_faces,
    );
    let base = mesh.flat_positions::<f64>();
    let [default, exact] = [Evaluation::OpenSubdiv, Evaluation::ExactLimit].map(|e| {
        let o = LimitStencilOptions::new().evaluation(e);
        let s = adaptive.location_stencils(&at, &o).unwrap();
        assert_eq!(s.len(), at.len());
        s.apply(3, &base).unwrap()
    });
    assert_eq!(default.point, exact.point);
    let ptex =
        subdiv::PtexIndices::new(&Refiner::new(&mesh, &Options::default()).unwrap()).unwrap();
    let (mut halved, mut same) = (0, 0);
    for (i, &(face, ..)) in at.iter().enumerate() {
        // The pentagons' sub-faces are the ptex faces of the non-quad faces.
        let non_quad = (0..mesh.face_count()).any(|f| {
            ptex.face_ptex_count(f).unwrap() > 1
                && (ptex.face_id(f).unwrap()..ptex.face_id(f).unwrap() + 5).contains(&face)
        });
        for k in 3 * i..3 * i + 3 {
            for (d, e) in [(&default.du, &exact.du), (&default.dv, &exact.dv)] {
                if non_quad {
                    assert_eq!(d[k], 2.0 * e[k]);
                } else {
                    assert_eq!(d[k], e[k]);
                }
            }
        }
        if non_quad { halved += 1 } else { same += 1 }
    }
    assert_eq!((halved, same), (10 * 25, 5 * 25));
}

/// On Loop patches the exact limit's second derivatives are those of the
/// positions (central differences), rotated sub-triangles included — where
/// OpenSubdiv's `EvaluatePatchBasis` (the default) negates them.
#[test]
fn second_derivatives_on_rotated_triangles_are_the_positions() {
    let mesh = shapes::icosahedron();
    let options = PatchOptions::new().max_isolation(3);
    let opts = Options::default().with_scheme(subdiv::Scheme::Loop);
    let adaptive = Refiner::new(&mesh, &opts)
        .unwrap()
        .refine_adaptive(options.refine_adaptive_options(), &[])
        .unwrap();
    let table = adaptive.patch_table(&options, &[]).unwrap();
    let points = adaptive
        .patch_points(&table, 3, &mesh.flat_positions())
        .unwrap();
    let t = (table, points);
    let h = 1e-4;
    let (mut rotated_seen, mut worst) = (0, 0.0f64);
    for face in 0..mesh.face_count() as u32 {
        for &(u, v) in &[(0.3, 0.4), (0.45, 0.3), (0.2, 0.2), (0.35, 0.35)] {
            let at = |du: f64, dv: f64| {
                eval(
                    &t,
                    Evaluation::ExactLimit,
                    &[(face, u + du, v + dv)],
                    Derivatives::First,
                )
            };
            let exact = eval(
                &t,
                Evaluation::ExactLimit,
                &[(face, u, v)],
                Derivatives::Second,
            );
            let default = eval(
                &t,
                Evaluation::OpenSubdiv,
                &[(face, u, v)],
                Derivatives::Second,
            );
            let (up, um) = (at(h, 0.0), at(-h, 0.0));
            let (vp, vm) = (at(0.0, h), at(0.0, -h));
            for k in 0..3 {
                let duu = (up.values.du[k] - um.values.du[k]) / (2.0 * h);
                let dvv = (vp.values.dv[k] - vm.values.dv[k]) / (2.0 * h);
                worst = worst
                    .max((exact.values.duu[k] - duu).abs())
                    .max((exact.values.dvv[k] - dvv).abs());
                if (default.values.duu[k] + exact.values.duu[k]).abs() < 1e-9
                    && exact.values.duu[k].abs() > 1e-3
                {
                    rotated_seen += 1;
                }
            }
        }
    }
    assert!(worst < 1e-5, "second derivatives off by {worst:e}");
    assert!(rotated_seen > 0, "no rotated sub-triangle sampled");
}
