//! OpenSubdiv's Bfr limit surfaces through the bridge
//! (`subdiv::osd::bfr_surface::Surfaces`): values checked against formulas
//! and exact limit positions, control points in Bfr's documented order,
//! limit stencils against evaluation, every refusal before OpenSubdiv sees
//! the input, and a sweep of the corpus (run it under Valgrind:
//! `valgrind --error-exitcode=1 target/debug/deps/osd_bfr_surface-*`).
#![cfg(feature = "osd")]

mod support;

use glam::DVec3;
use subdiv::bfr::{FaceSurfaces, Parameterization, ParameterizationType, SurfaceOptions};
use subdiv::osd::bfr_surface::{SurfaceInfo, Surfaces};
use subdiv::patches::{Derivatives, Partials, SurfaceSamples};
use subdiv::refiner::Refiner;
use subdiv::{BoundaryInterpolation, Error, Mesh, Options, OsdError, OsdErrorKind, Scheme, shapes};

fn surfaces(mesh: &Mesh, options: &Options) -> Surfaces {
    Surfaces::new(mesh, options, &SurfaceOptions::default()).unwrap()
}

/// The error's kind, and its message containing every one of `needles`.
fn refused<T: std::fmt::Debug>(r: subdiv::Result<T>, kind: OsdErrorKind, needles: &[&str]) {
    match r {
        Err(Error::Osd(OsdError { kind: k, message })) => {
            assert_eq!(k, kind, "{message}");
            for needle in needles {
                assert!(message.contains(needle), "{message:?} lacks {needle:?}");
            }
        }
        other => panic!("expected a {kind:?} refusal mentioning {needles:?}, got {other:?}"),
    }
}

fn close(a: &[f64], b: &[f64], tol: f64, what: &str) {
    assert_eq!(a.len(), b.len(), "{what}: lengths");
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        assert!((x - y).abs() <= tol, "{what}[{i}]: {x} vs {y}");
    }
}

/// A 5 × 5 grid of quads, bent out of its plane so that no coordinate is
/// linear in (u, v).
fn bent_grid() -> Mesh {
    let mut m = shapes::grid(5, 5);
    for p in &mut m.positions {
        let (x, y) = (p.x, p.y);
        *p = DVec3::new(
            x + 0.05 * (2.0 * y).sin(),
            y + 0.07 * (1.3 * x).cos(),
            0.3 * (0.9 * x).sin() * (0.7 * y + 0.2).cos() + 0.1 * x * y,
        );
    }
    m
}

/// The uniform cubic B-spline basis and its first two derivatives at t.
fn bspline(t: f64) -> [[f64; 4]; 3] {
    let s = 1.0 - t;
    [
        [
            s * s * s / 6.0,
            (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0,
            (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0,
            t * t * t / 6.0,
        ],
        [
            -s * s / 2.0,
            (3.0 * t * t - 4.0 * t) / 2.0,
            (-3.0 * t * t + 2.0 * t + 1.0) / 2.0,
            t * t / 2.0,
        ],
        [s, 3.0 * t - 2.0, -3.0 * t + 1.0, t],
    ]
}

#[test]
fn regular_interior_quad_is_the_bicubic_bspline_of_its_16_points() {
    let mesh = bent_grid();
    let s = surfaces(&mesh, &Options::default());
    let nx = 5u32;
    let at = |i: u32, j: u32| j * (nx + 1) + i;
    // Face (i, j) = (2, 1): interior, every corner of valence 4.
    let (i, j) = (2u32, 1u32);
    let face = (j * nx + i) as usize;
    let info = s.face_info(face).unwrap();
    assert!(info.valid && info.regular && !info.linear, "{info:?}");
    assert_eq!(info.kind, ParameterizationType::Quad);
    assert_eq!(info.patch_points, 16);
    // Bfr's order: the 4 x 4 points row by row (v), each row along u, from
    // the point diagonally before the face's first vertex; the face's
    // corners are points 5, 6, 10, 9.
    let expected: Vec<u32> = (0..16)
        .map(|k| at(i + (k % 4) - 1, j + (k / 4) - 1))
        .collect();
    assert_eq!(info.control_points, expected);
    let fv = mesh.face(face);
    assert_eq!(
        [
            info.control_points[5],
            info.control_points[6],
            info.control_points[10],
            info.control_points[9]
        ],
        [fv[0], fv[1], fv[2], fv[3]]
    );

    let coords = [
        [0.0, 0.0],
        [1.0, 0.0],
        [1.0, 1.0],
        [0.25, 0.6],
        [0.5, 0.5],
        [0.9, 0.15],
    ];
    let got = s.evaluate(face, &coords, Derivatives::Second).unwrap();
    assert_eq!(got.width, 3);
    for (k, &[u, v]) in coords.iter().enumerate() {
        let (bu, bv) = (bspline(u), bspline(v));
        // (d/du order, d/dv order) of each column.
        let orders = [(0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2)];
        let columns = [
            &got.values.point,
            &got.values.du,
            &got.values.dv,
            &got.values.duu,
            &got.values.duv,
            &got.values.dvv,
        ];
        for ((du, dv), column) in orders.into_iter().zip(columns) {
            let mut want = DVec3::ZERO;
            for r in 0..4 {
                for c in 0..4 {
                    want += bu[du][c] * bv[dv][r] * mesh.positions[expected[4 * r + c] as usize];
                }
            }
            close(
                &column[3 * k..3 * k + 3],
                &want.to_array(),
                1e-12,
                &format!("({u}, {v}) d{du}{dv}"),
            );
        }
    }
}

/// The limit positions of the base vertices, natively.
fn limit_positions(mesh: &Mesh, options: &Options) -> Vec<f64> {
    Refiner::new(mesh, options)
        .unwrap()
        .limit_positions::<f64>(3, &mesh.flat_positions::<f64>())
        .unwrap()
        .into_vec()
}

/// At each face's vertex coordinates the surface passes through its
/// vertices' limit positions.
fn corners_are_limit_positions(mesh: &Mesh, options: &Options) {
    let s = surfaces(mesh, options);
    let limit = limit_positions(mesh, options);
    let mut checked = 0;
    for face in 0..mesh.face_count() {
        let fv = mesh.face(face);
        let param = Parameterization::new(options.scheme, fv.len()).unwrap();
        let coords: Vec<[f64; 2]> = (0..fv.len()).map(|k| param.vertex_coord(k)).collect();
        let got = s.evaluate(face, &coords, Derivatives::None).unwrap();
        for (k, &v) in fv.iter().enumerate() {
            let v = v as usize;
            close(
                &got.values.point[3 * k..3 * k + 3],
                &limit[3 * v..3 * v + 3],
                1e-12,
                &format!("face {face} corner {k}"),
            );
            checked += 1;
        }
    }
    assert!(checked >= mesh.face_count() * 3);
}

#[test]
fn cube_corners_are_limit_positions() {
    let cube = shapes::cube();
    corners_are_limit_positions(&cube, &Options::default());
    // Corner (0, 0) of the bottom face is vertex 0, pulled inside the
    // cube towards its centre.
    let s = surfaces(&cube, &Options::default());
    let p = s.evaluate(0, &[[0.0, 0.0]], Derivatives::None).unwrap();
    let limit = limit_positions(&cube, &Options::default());
    close(&p.values.point, &limit[0..3], 1e-12, "bottom face (0, 0)");
    assert!(p.values.point.iter().all(|&x| x > -0.5 && x < -0.2));
}

/// Base-level limit masks hold where every face is of the scheme's
/// regular size (at a vertex of an n-gon they need a refinement first) and
/// every vertex is smooth with smooth edges, on an infinitely sharp crease
/// curve or an infinitely sharp corner (semi-sharp features and darts need
/// refinement too).
#[test]
fn creased_and_loop_corners_are_limit_positions() {
    let mut creased = shapes::cube();
    for (a, b) in [(0, 3), (3, 2), (2, 1), (1, 0)] {
        creased.add_crease(a, b, 10.0);
    }
    creased.add_corner(6, 10.0);
    corners_are_limit_positions(&creased, &Options::default());
    corners_are_limit_positions(&shapes::torus(8, 6), &Options::default());
    corners_are_limit_positions(
        &shapes::icosahedron(),
        &Options::default().with_scheme(Scheme::Loop),
    );
}

#[test]
fn face_info_describes_the_surfaces() {
    let cube = surfaces(&shapes::cube(), &Options::default());
    let info = cube.face_info(1).unwrap();
    // Every corner has valence 3: an irregular surface of the face and its
    // neighbours' vertices (all 8), with points computed beyond them.
    assert!(info.valid && !info.regular && !info.linear, "{info:?}");
    let mut cps = info.control_points.clone();
    cps.sort_unstable();
    assert_eq!(cps, (0..8).collect::<Vec<u32>>());
    assert!(info.patch_points > 8);
    assert_eq!(&info.control_points[..4], shapes::cube().face(1));

    let pent = shapes::pyramid(5);
    let info = surfaces(&pent, &Options::default()).face_info(0).unwrap();
    assert_eq!(info.kind, ParameterizationType::QuadSubfaces);
    assert!(info.valid && !info.regular);

    let bilinear = Options::default().with_scheme(Scheme::Bilinear);
    let s = surfaces(&pent, &bilinear);
    let info = s.face_info(0).unwrap();
    assert_eq!(
        info,
        SurfaceInfo {
            valid: true,
            regular: false,
            linear: true,
            control_points: pent.face(0).to_vec(),
            // The N points, the centre and the N edge midpoints.
            patch_points: 11,
            kind: ParameterizationType::QuadSubfaces,
        }
    );
    let tri = surfaces(
        &shapes::icosahedron(),
        &Options::default().with_scheme(Scheme::Loop),
    );
    let info = tri.face_info(0).unwrap();
    // Every vertex has valence 5: irregular.
    assert!(info.valid && !info.regular && info.kind == ParameterizationType::Triangle);

    let mut holes = shapes::grid(4, 4);
    holes.holes.push(5);
    let s = surfaces(&holes, &Options::default());
    let info = s.face_info(5).unwrap();
    assert!(!info.valid && info.control_points.is_empty() && info.patch_points == 0);
    assert_eq!(info.kind, ParameterizationType::Quad);
    assert!(!s.has_surface(5) && s.has_surface(6));
    assert_eq!(s.face_count(), 16);
    assert_eq!(FaceSurfaces::scheme(&s), Scheme::Catmark);
}

fn apply(weights: &[f64], points: &[u32], mesh: &Mesh) -> [f64; 3] {
    assert_eq!(weights.len(), points.len());
    let mut p = DVec3::ZERO;
    for (&w, &v) in weights.iter().zip(points) {
        p += w * mesh.positions[v as usize];
    }
    p.to_array()
}

/// The stencils at `coords` sum to 1 (derivatives to 0) and, applied to
/// the control points, give the evaluation.
fn stencils_match_evaluation(mesh: &Mesh, options: &Options, face: usize, coords: &[[f64; 2]]) {
    let s = surfaces(mesh, options);
    let info = s.face_info(face).unwrap();
    let stencils = s
        .evaluate_stencil(face, coords, Derivatives::Second)
        .unwrap();
    let eval = s.evaluate(face, coords, Derivatives::Second).unwrap();
    assert_eq!(stencils.len(), coords.len());
    for (k, st) in stencils.iter().enumerate() {
        let columns = [&st.point, &st.du, &st.dv, &st.duu, &st.duv, &st.dvv];
        let values = [
            &eval.values.point,
            &eval.values.du,
            &eval.values.dv,
            &eval.values.duu,
            &eval.values.duv,
            &eval.values.dvv,
        ];
        for (c, (weights, value)) in columns.into_iter().zip(values).enumerate() {
            let sum: f64 = weights.iter().sum();
            let want = if c == 0 { 1.0 } else { 0.0 };
            assert!(
                (sum - want).abs() < 1e-10,
                "face {face} coord {k} column {c}: sum {sum}"
            );
            close(
                &apply(weights, &info.control_points, mesh),
                &value[3 * k..3 * k + 3],
                1e-10,
                &format!("face {face} coord {k} column {c}"),
            );
        }
    }
    // Fewer columns when fewer derivatives are asked for.
    let first = s
        .evaluate_stencil(face, coords, Derivatives::First)
        .unwrap();
    assert!(first[0].duu.is_empty() && first[0].du.len() == info.control_points.len());
    close(
        &first[0].dv,
        &stencils[0].dv,
        0.0,
        "first-derivative stencils",
    );
    let none = s.evaluate_stencil(face, coords, Derivatives::None).unwrap();
    assert!(none[0].du.is_empty());
    close(&none[0].point, &stencils[0].point, 0.0, "position stencils");
}

#[test]
fn stencils_sum_to_one_and_reproduce_evaluation() {
    let quad = [[0.0, 0.0], [0.3, 0.7], [1.0, 1.0], [0.5, 0.0]];
    stencils_match_evaluation(&bent_grid(), &Options::default(), 7, &quad);
    stencils_match_evaluation(&shapes::cube(), &Options::default(), 2, &quad);
    let mut creased = shapes::cube();
    creased.add_crease(0, 1, 2.5);
    stencils_match_evaluation(&creased, &Options::default(), 2, &quad);
    // Sub-faces 0 and 3 of a pentagon, and a Loop triangle.
    let pent = [[0.0, 0.0], [0.2, 0.3], [1.25, 0.5], [0.1, 1.2]];
    stencils_match_evaluation(&shapes::pyramid(5), &Options::default(), 0, &pent);
    stencils_match_evaluation(
        &shapes::pyramid(5),
        &Options::default().with_scheme(Scheme::Bilinear),
        0,
        &pent,
    );
    stencils_match_evaluation(
        &shapes::icosahedron(),
        &Options::default().with_scheme(Scheme::Loop),
        3,
        &[[0.0, 0.0], [0.2, 0.3], [0.5, 0.5], [0.0, 1.0]],
    );
}

/// OpenSubdiv's `EvalSubPatchStencils` writes no ∂²/∂v² weights (and
/// ∂²/∂v² ones as ∂²/∂u∂v) when a face's irregular surface is one regular
/// interior patch: here a semi-sharp edge at a corner makes the surface
/// irregular to Bfr, and with approximation levels of 0 the face is not
/// refined, so Far's patch of it is regular. The bridge computes those two
/// columns from the surface's evaluation.
#[test]
fn second_derivative_stencils_of_a_single_regular_irregular_patch() {
    let mut mesh = bent_grid();
    // Face 12 = (2, 2) has corners 14, 15, 21, 20; edge 14-8 is below it.
    mesh.add_crease(14, 8, 1.0);
    let flat = SurfaceOptions {
        approx_level_smooth: 0,
        approx_level_sharp: 0,
        ..SurfaceOptions::default()
    };
    let s = Surfaces::new(&mesh, &Options::default(), &flat).unwrap();
    let info = s.face_info(12).unwrap();
    assert!(
        info.valid && !info.regular && info.control_points.len() == 16,
        "{info:?}"
    );
    let coords = [[0.3, 0.6], [0.0, 1.0], [0.8, 0.1]];
    let stencils = s
        .evaluate_stencil(12, &coords, Derivatives::Second)
        .unwrap();
    let eval = s.evaluate(12, &coords, Derivatives::Second).unwrap();
    for (k, st) in stencils.iter().enumerate() {
        for (weights, value, what) in [
            (&st.duv, &eval.values.duv, "duv"),
            (&st.dvv, &eval.values.dvv, "dvv"),
        ] {
            let got = apply(weights, &info.control_points, &mesh);
            close(
                &got,
                &value[3 * k..3 * k + 3],
                1e-10,
                &format!("coord {k} {what}"),
            );
            assert!(
                got.iter().any(|x| x.abs() > 1e-3),
                "coord {k} {what}: {got:?}"
            );
            assert!(weights.iter().sum::<f64>().abs() < 1e-10);
        }
    }
}

#[test]
fn face_varying_and_varying_data() {
    // The grid's UVs are its positions scaled: a linear function, which
    // every surface reproduces.
    let mesh = shapes::grid(4, 3);
    let opts = Options::default().with_boundary(BoundaryInterpolation::EdgeOnly);
    let s = surfaces(&mesh, &opts);
    let coords = [[0.0, 0.0], [0.5, 0.25], [1.0, 1.0]];
    let face = 5; // (1, 1)
    let uv = s
        .evaluate_fvar(face, 0, &coords, Derivatives::First)
        .unwrap();
    assert_eq!(uv.width, 2);
    let want = |u: f64, v: f64| [(1.0 + u) / 4.0, (1.0 + v) / 3.0];
    for (k, &[u, v]) in coords.iter().enumerate() {
        close(&uv.values.point[2 * k..2 * k + 2], &want(u, v), 1e-12, "uv");
        close(
            &uv.values.du[2 * k..2 * k + 2],
            &[0.25, 0.0],
            1e-12,
            "d uv / du",
        );
        close(
            &uv.values.dv[2 * k..2 * k + 2],
            &[0.0, 1.0 / 3.0],
            1e-12,
            "d uv / dv",
        );
    }
    // The varying surface is bilinear over the face's corners.
    let bent = bent_grid();
    let s = surfaces(&bent, &Options::default());
    let fv = bent.face(7);
    let [a, b, c, d] = [0, 1, 2, 3].map(|k| bent.positions[fv[k] as usize]);
    let got = s.evaluate_varying(7, &[[0.3, 0.8]]).unwrap();
    let want = a * 0.7 * 0.2 + b * 0.3 * 0.2 + c * 0.3 * 0.8 + d * 0.7 * 0.8;
    close(&got.values.point, &want.to_array(), 1e-12, "varying");
    assert!(got.values.du.is_empty());
    // The trait's face-varying evaluation has no derivatives.
    let t: &dyn FaceSurfaces = &s;
    let uv = t.evaluate_fvar(7, 0, &[[0.5, 0.5]]).unwrap();
    assert!(uv.values.du.is_empty() && uv.values.point.len() == 2);
    refused(
        s.evaluate_fvar(7, 0, &[[0.5, 1.5]], Derivatives::None),
        OsdErrorKind::Refused,
        &["off face 7's domain"],
    );
    assert!(matches!(
        s.evaluate_fvar(7, 1, &[[0.5, 0.5]], Derivatives::None),
        Err(Error::NoSuchChannel {
            channel: 1,
            count: 1
        })
    ));
}

#[test]
fn refusals() {
    let grid = surfaces(&bent_grid(), &Options::default());
    let ok = |s: &Surfaces, face, c: [f64; 2]| s.evaluate(face, &[c], Derivatives::First).is_ok();
    // The unit square, with 1e-9 of slack.
    assert!(ok(&grid, 7, [-5e-10, 1.0 + 5e-10]));
    for c in [[1.1, 0.5], [-0.01, 0.5], [0.5, 1.0 + 2e-9], [-2e-9, 0.0]] {
        refused(
            grid.evaluate(7, &[[0.5, 0.5], c], Derivatives::None),
            OsdErrorKind::Refused,
            &["coordinate 1", "off face 7's domain", "the unit square"],
        );
    }
    for c in [
        [f64::NAN, 0.5],
        [0.5, f64::INFINITY],
        [f64::NEG_INFINITY, 0.0],
    ] {
        refused(
            grid.evaluate(7, &[c], Derivatives::None),
            OsdErrorKind::Refused,
            &["coordinate 0", "not finite"],
        );
    }
    refused(
        grid.evaluate(25, &[[0.5, 0.5]], Derivatives::None),
        OsdErrorKind::Refused,
        &["face 25 does not exist"],
    );
    refused(
        grid.face_info(usize::MAX),
        OsdErrorKind::Refused,
        &["does not exist"],
    );
    refused(
        grid.evaluate_stencil(25, &[[0.5, 0.5]], Derivatives::None),
        OsdErrorKind::Refused,
        &["face 25 does not exist"],
    );
    refused(
        grid.evaluate_stencil(7, &[[0.5, 1.5]], Derivatives::None),
        OsdErrorKind::Refused,
        &["off face 7's domain"],
    );
    assert!(!grid.has_surface(25));
    let none = grid.evaluate(7, &[], Derivatives::Second).unwrap();
    assert!(none.values.point.is_empty() && none.values.dvv.is_empty());
    assert!(
        grid.evaluate_stencil(7, &[], Derivatives::First)
            .unwrap()
            .is_empty()
    );

    // The unit triangle.
    let ico = surfaces(
        &shapes::icosahedron(),
        &Options::default().with_scheme(Scheme::Loop),
    );
    assert!(ok(&ico, 0, [0.5, 0.5 + 5e-10]));
    for c in [[0.6, 0.41], [-0.1, 0.2], [1.2, 0.0]] {
        refused(
            ico.evaluate(0, &[c], Derivatives::None),
            OsdErrorKind::Refused,
            &["the unit triangle"],
        );
    }

    // A pentagon's sub-faces: tiles (0, 0), (1, 0), (2, 0), (0, 1), (1, 1)
    // of a grid 3 wide, each tile's [0, 0.5]^2 corner.
    let pent = surfaces(&shapes::pyramid(5), &Options::default());
    for c in [
        [0.0, 0.0],
        [0.5, 0.5],
        [2.5, 0.5],
        [1.5, 1.5],
        [1.0 - 1e-10, 0.2],
        [2.2, 0.4],
    ] {
        assert!(ok(&pent, 0, c), "{c:?}");
    }
    // In a tile's gap, on tile (2, 1) (sub-face 5 of 5: OpenSubdiv would
    // index past its sub-faces), beyond the grid's width, negative.
    for c in [
        [0.6, 0.1],
        [0.1, 0.7],
        [2.2, 1.2],
        [3.1, 0.0],
        [5.0, 5.0],
        [-0.5, 0.0],
        [1e300, 0.0],
    ] {
        refused(
            pent.evaluate(0, &[c], Derivatives::None),
            OsdErrorKind::Refused,
            &["sub-faces"],
        );
    }

    // Holes have no limit surface.
    let mut holes = shapes::grid(4, 4);
    holes.holes.push(5);
    let s = surfaces(&holes, &Options::default());
    refused(
        s.evaluate(5, &[[0.5, 0.5]], Derivatives::None),
        OsdErrorKind::Refused,
        &["face 5 has no vertex limit surface"],
    );
    refused(
        s.evaluate_stencil(5, &[[0.5, 0.5]], Derivatives::None),
        OsdErrorKind::Refused,
        &["no vertex limit surface"],
    );
    refused(
        s.evaluate_fvar(5, 0, &[[0.5, 0.5]], Derivatives::None),
        OsdErrorKind::Refused,
        &["face 5 has no face-varying limit surface"],
    );
    // Boundary faces under boundary interpolation "none" have none either.
    assert!(!s.has_surface(0));
    assert!(!s.face_info(0).unwrap().valid);

    // Approximation levels beyond 10.
    for (smooth, sharp) in [(2, 11), (11, 6), (u32::MAX, 6)] {
        refused(
            Surfaces::new(
                &shapes::cube(),
                &Options::default(),
                &SurfaceOptions {
                    approx_level_smooth: smooth,
                    approx_level_sharp: sharp,
                    ..SurfaceOptions::default()
                },
            ),
            OsdErrorKind::Refused,
            &["approximation level"],
        );
    }
    // Level 0 is OpenSubdiv's: it refines irregular faces once regardless.
    let coarse = Surfaces::new(
        &shapes::cube(),
        &Options::default(),
        &SurfaceOptions {
            approx_level_smooth: 0,
            approx_level_sharp: 0,
            ..SurfaceOptions::default()
        },
    )
    .unwrap();
    assert!(
        coarse
            .evaluate(0, &[[0.5, 0.5]], Derivatives::Second)
            .is_ok()
    );
}

/// OpenSubdiv's regression shape `catmark_val2_interior`, shape 8: two
/// hexagons sharing three edges, so two of their vertices are interior
/// vertices of valence 2, the others on the boundary; OpenSubdiv 3.5.1
/// added the creases that expose 3.5.0's fault.
fn val2_interior(creased: bool) -> Mesh {
    let mut m = Mesh::from_faces(
        [
            [-0.5, 0.0, -1.75],
            [0.0, 0.0, -1.75],
            [0.0, -0.5, -1.75],
            [0.5, 0.0, -1.75],
            [-0.5, 0.0, -0.75],
            [0.0, 0.0, -0.75],
            [0.0, -0.5, -0.75],
            [0.5, 0.0, -0.75],
        ]
        .into_iter()
        .map(DVec3::from_array)
        .collect(),
        &[&[0, 1, 2, 6, 5, 4], &[7, 5, 6, 2, 1, 3]],
    );
    if creased {
        m.add_crease(1, 2, 5.0);
        m.add_crease(2, 6, 5.0);
        m.add_crease(6, 5, 5.0);
    }
    m
}

#[test]
fn valence_two_faces_with_creases_are_refused() {
    let opts = Options::default().with_boundary(BoundaryInterpolation::EdgeOnly);
    let s = surfaces(&val2_interior(true), &opts);
    for face in 0..2 {
        let needles = [
            format!("face {face}: its corner vertex"),
            "interior vertex of valence 2".into(),
            "3.5.1".into(),
        ];
        let needles: Vec<&str> = needles.iter().map(String::as_str).collect();
        refused(s.face_info(face), OsdErrorKind::Unsafe, &needles);
        refused(
            s.evaluate(face, &[[0.2, 0.2]], Derivatives::None),
            OsdErrorKind::Unsafe,
            &needles,
        );
        refused(
            s.evaluate_stencil(face, &[[0.2, 0.2]], Derivatives::None),
            OsdErrorKind::Unsafe,
            &needles,
        );
        assert!(!s.has_surface(face));
        // The varying surface is linear: no irregular patch is built.
        assert!(s.evaluate_varying(face, &[[0.2, 0.2]]).is_ok());
    }
    // The vertex named is one of the two of valence 2.
    match s.face_info(0) {
        Err(Error::Osd(OsdError { message, .. })) => {
            assert!(
                message.contains("corner vertex 2 ") || message.contains("corner vertex 6 "),
                "{message}"
            )
        }
        other => panic!("{other:?}"),
    }
    // Without the creases the fault is not reached: both faces evaluate,
    // and symmetrically (the shape is symmetric under x -> -x, z -> -2.5 - z).
    let s = surfaces(&val2_interior(false), &opts);
    let a = s.evaluate(0, &[[0.25, 0.25]], Derivatives::None).unwrap();
    let b = s.evaluate(1, &[[0.25, 0.25]], Derivatives::None).unwrap();
    let (pa, pb) = (&a.values.point, &b.values.point);
    close(
        &[pa[0], pa[1], pa[2]],
        &[-pb[0], pb[1], -2.5 - pb[2]],
        1e-12,
        "mirror",
    );
    assert!(s.face_info(0).unwrap().valid);
    // Bilinear: linear surfaces, nothing refused.
    let s = surfaces(
        &val2_interior(true),
        &Options::default().with_scheme(Scheme::Bilinear),
    );
    assert!(s.face_info(0).unwrap().linear);

    // A face-varying surface of a non-linear channel is built by the same
    // builder (any corner may bound the channel at a seam): refused; a
    // linear channel is not.
    let mut mesh = val2_interior(true);
    mesh.fvar_channels.push(subdiv::FVarChannel {
        width: 2,
        values: mesh.positions.iter().flat_map(|p| [p.x, p.z]).collect(),
        indices: mesh.face_vertices.clone(),
    });
    let smooth_uvs = opts.with_fvar(subdiv::FVarLinearInterpolation::None);
    let s = surfaces(&mesh, &smooth_uvs);
    refused(
        s.evaluate_fvar(1, 0, &[[0.2, 0.2]], Derivatives::None),
        OsdErrorKind::Unsafe,
        &["face 1: its corner vertex", "face-varying subsets"],
    );
    let s = surfaces(&mesh, &opts.with_fvar(subdiv::FVarLinearInterpolation::All));
    let uv = s
        .evaluate_fvar(1, 0, &[[0.0, 0.0]], Derivatives::None)
        .unwrap();
    close(
        &uv.values.point,
        &[0.5, -0.75],
        1e-12,
        "linear uv at vertex 7",
    );
}

#[test]
fn surfaces_are_send_and_sync_and_agree_across_threads() {
    fn send_sync<T: Send + Sync>() {}
    send_sync::<Surfaces>();
    let mesh = shapes::torus(8, 6);
    let s = surfaces(&mesh, &Options::default());
    let coords = [[0.1, 0.2], [0.7, 0.4]];
    let one: Vec<SurfaceSamples> = (0..mesh.face_count())
        .map(|f| s.evaluate(f, &coords, Derivatives::First).unwrap())
        .collect();
    std::thread::scope(|scope| {
        let handles: Vec<_> = (0..4)
            .map(|t| {
                let (s, one) = (&s, &one);
                scope.spawn(move || {
                    for f in (t..one.len()).step_by(4) {
                        assert_eq!(s.evaluate(f, &coords, Derivatives::First).unwrap(), one[f]);
                    }
                })
            })
            .collect();
        for h in handles {
            h.join().unwrap();
        }
    });
}

fn finite(samples: &Partials) -> bool {
    [
        &samples.point,
        &samples.du,
        &samples.dv,
        &samples.duu,
        &samples.duv,
        &samples.dvv,
    ]
    .iter()
    .all(|c| c.iter().all(|x| x.is_finite()))
}

/// Every face of every corpus shape under several options: what the
/// bridge builds evaluates to finite values, its stencils sum to 1, and
/// only holes and faces without a limit surface are invalid. The test to
/// run under Valgrind.
#[test]
fn corpus_sweep() {
    let catmark = Options::default().with_boundary(BoundaryInterpolation::EdgeOnly);
    let mut faces = 0;
    for (name, mesh) in shapes::corpus() {
        let mut modes = vec![
            ("default", Options::default()),
            ("edge-only", catmark),
            ("bilinear", catmark.with_scheme(Scheme::Bilinear)),
        ];
        if mesh.faces().all(|f| f.len() == 3) {
            modes.push(("loop", catmark.with_scheme(Scheme::Loop)));
        }
        for (mode, opts) in modes {
            let s = surfaces(&mesh, &opts);
            for face in 0..mesh.face_count() {
                let what = format!("{name} {mode} face {face}");
                let info = s.face_info(face).unwrap_or_else(|e| panic!("{what}: {e}"));
                let param = Parameterization::new(opts.scheme, mesh.face(face).len()).unwrap();
                assert_eq!(info.kind, param.kind(), "{what}");
                if !info.valid {
                    assert!(
                        mesh.holes.contains(&(face as u32))
                            || opts.boundary == BoundaryInterpolation::None,
                        "{what}: no surface"
                    );
                    continue;
                }
                faces += 1;
                let coords = support::bfr_sample_coords(&param);
                let eval = s
                    .evaluate(face, &coords, Derivatives::Second)
                    .unwrap_or_else(|e| panic!("{what}: {e}"));
                assert!(finite(&eval.values), "{what}");
                let varying = s.evaluate_varying(face, &coords).unwrap();
                assert!(finite(&varying.values), "{what}");
                for (channel, c) in mesh.fvar_channels.iter().enumerate() {
                    let fvar = s
                        .evaluate_fvar(face, channel, &coords, Derivatives::First)
                        .unwrap();
                    assert_eq!(fvar.values.point.len(), coords.len() * c.width);
                    assert!(finite(&fvar.values), "{what} channel {channel}");
                }
                let stencils = s
                    .evaluate_stencil(face, &coords[..3], Derivatives::Second)
                    .unwrap();
                for (k, st) in stencils.iter().enumerate() {
                    assert!(finite(st), "{what}");
                    let sum: f64 = st.point.iter().sum();
                    assert!(
                        (sum - 1.0).abs() < 1e-9,
                        "{what} coord {k}: stencil sum {sum}"
                    );
                    close(
                        &apply(&st.point, &info.control_points, &mesh),
                        &eval.values.point[3 * k..3 * k + 3],
                        1e-9,
                        &what,
                    );
                }
            }
        }
    }
    assert!(faces > 2000, "{faces}");
}
