//! Native `bfr::LimitSurfaces` against OpenSubdiv's `Bfr::Surface`s
//! (`osd::bfr::Surfaces`) over the corpus: the same faces have a limit
//! surface, and at every coordinate of a rate-3 tessellation of every face
//! (its corners, points along its edges and inside; sub-face boundaries of
//! n-gons included) positions agree within 1e-9 of the shape's
//! bounding-box diagonal, first and second derivatives within 1e-7 — under
//! every boundary rule, with Chaikin creasing and smooth triangles, with
//! approximation levels other than the defaults, for Catmull-Clark and
//! bilinear, Loop (Gregory-triangle end caps included); face-varying data
//! of linearly interpolated channels too.
#![cfg(feature = "osd")]

use subdiv::bfr::{FaceSurfaces, LimitSurfaces, SurfaceOptions, Tessellation, TessellationOptions};
use subdiv::patches::{Derivatives, SurfaceSamples};
use subdiv::{
    BoundaryInterpolation, CreasingMethod, FVarLinearInterpolation, Mesh, Options, Scheme,
    TriangleSubdivision, osd, shapes,
};

fn diagonal(mesh: &Mesh) -> f64 {
    let (mut lo, mut hi) = (mesh.positions[0], mesh.positions[0]);
    for p in &mesh.positions {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    (hi - lo).length().max(1e-300)
}

/// The largest difference of each column, relative to `scale`.
fn deviation(a: &SurfaceSamples, b: &SurfaceSamples, scale: f64) -> [f64; 3] {
    let v = (&a.values, &b.values);
    let worst = |x: &[f64], y: &[f64]| {
        assert_eq!(x.len(), y.len());
        x.iter()
            .zip(y)
            .fold(0.0f64, |m, (p, q)| m.max((p - q).abs()))
            / scale
    };
    [
        worst(&v.0.point, &v.1.point),
        worst(&v.0.du, &v.1.du).max(worst(&v.0.dv, &v.1.dv)),
        worst(&v.0.duu, &v.1.duu)
            .max(worst(&v.0.duv, &v.1.duv))
            .max(worst(&v.0.dvv, &v.1.dvv)),
    ]
}

/// Compares every face of `mesh` under `options`; returns the faces compared
/// (0 when the native engine does not build these surfaces yet).
fn compare(name: &str, mesh: &Mesh, options: &Options, so: &SurfaceOptions) -> usize {
    let mut departures = Vec::new();
    let n = compare_with(name, mesh, options, so, &mut departures);
    assert!(departures.is_empty(), "{departures:?}");
    n
}

/// A face-varying surface departing from Bfr's: the case, the face, and
/// the deviation of values and of first derivatives.
type Departure = (String, usize, f64, f64);

/// As [`compare`], collecting face-varying departures instead of failing.
fn compare_with(
    name: &str,
    mesh: &Mesh,
    options: &Options,
    so: &SurfaceOptions,
    fvar_departures: &mut Vec<Departure>,
) -> usize {
    let native = LimitSurfaces::new(mesh, options, so).unwrap_or_else(|e| panic!("{name}: {e}"));
    let theirs = osd::bfr::Surfaces::new(mesh, options, so).unwrap();
    let scale = diagonal(mesh);
    let label = format!("{name} {options:?} {so:?}");
    let mut compared = 0;
    for face in 0..mesh.face_count() {
        let info = theirs.face_info(face).unwrap();
        assert_eq!(native.has_surface(face), info.valid, "{label}: face {face}");
        if !info.valid {
            continue;
        }
        let param = native.parameterization(face).unwrap();
        assert_eq!(param.kind(), info.kind, "{label}: face {face}");
        let t = Tessellation::uniform(param, 3, TessellationOptions::default()).unwrap();
        let coords = t.coords::<f64>().unwrap();
        let a = native.evaluate(face, &coords, Derivatives::Second).unwrap();
        let b = theirs.evaluate(face, &coords, Derivatives::Second).unwrap();
        let [p, d1, d2] = deviation(&a, &b, scale);
        assert!(
            p < 1e-9 && d1 < 1e-7 && d2 < 1e-7,
            "{label}: face {face}: {p:e} {d1:e} {d2:e}"
        );
        for channel in 0..mesh.fvar_channels.len() {
            let a = native
                .evaluate_fvar(face, channel, &coords, Derivatives::First)
                .unwrap();
            let b = theirs
                .evaluate_fvar(face, channel, &coords, Derivatives::First)
                .unwrap();
            let [p, d1, _] = deviation(&a, &b, 1.0);
            if !(p < 1e-9 && d1 < 1e-7) {
                fvar_departures.push((label.clone(), face, p, d1));
            }
        }
        compared += 1;
    }
    compared
}

#[test]
fn native_surfaces_equal_opensubdivs_bfr_over_the_corpus() {
    let mut compared = 0;
    let mut loop_faces = 0;
    let defaults = SurfaceOptions::default();
    for (name, mesh) in shapes::corpus() {
        for boundary in [
            BoundaryInterpolation::None,
            BoundaryInterpolation::EdgeOnly,
            BoundaryInterpolation::EdgeAndCorner,
        ] {
            let schemes: &[Scheme] = if mesh.faces().all(|f| f.len() == 3) {
                &[Scheme::Catmark, Scheme::Loop, Scheme::Bilinear]
            } else {
                &[Scheme::Catmark, Scheme::Bilinear]
            };
            for &scheme in schemes {
                let options = Options::default()
                    .with_scheme(scheme)
                    .with_boundary(boundary)
                    .with_fvar(FVarLinearInterpolation::All);
                let n = compare(&name, &mesh, &options, &defaults);
                if scheme == Scheme::Loop {
                    loop_faces += n;
                }
                compared += n;
            }
        }
        // Other creasing, triangle rule and approximation levels.
        let options = Options::default()
            .with_boundary(BoundaryInterpolation::EdgeAndCorner)
            .with_triangles(TriangleSubdivision::Smooth);
        for so in [
            SurfaceOptions {
                approx_level_smooth: 1,
                approx_level_sharp: 3,
                ..SurfaceOptions::default()
            },
            SurfaceOptions {
                approx_level_smooth: 4,
                approx_level_sharp: 4,
                ..SurfaceOptions::default()
            },
        ] {
            compared += compare(&name, &mesh, &options, &so);
        }
    }
    eprintln!("{compared} faces compared, {loop_faces} of them Loop");
    assert!(compared > 3000, "{compared}");
    assert!(loop_faces > 300, "{loop_faces}");
}

#[test]
fn tessellations_of_both_engines_have_the_same_points() {
    // The watertight mesher over either engine's surfaces: same counts,
    // same points in the same order (each evaluated once, by the first face).
    for (name, mesh) in [
        ("cube", shapes::cube()),
        ("pyramid", shapes::pyramid(5)),
        ("torus", shapes::torus(6, 4)),
    ] {
        let options = Options::shape_file_defaults();
        let so = SurfaceOptions::default();
        let native = LimitSurfaces::new(&mesh, &options, &so).unwrap();
        let theirs = osd::bfr::Surfaces::new(&mesh, &options, &so).unwrap();
        let scale = diagonal(&mesh);
        for (rate, quads) in [(1, false), (3, false), (8, true)] {
            let to = subdiv::bfr::TessellateOptions {
                rate,
                quads,
                normals: true,
                ..Default::default()
            };
            let a = subdiv::bfr::tessellate(&mesh, &native, &to).unwrap();
            let b = subdiv::bfr::tessellate(&mesh, &theirs as &dyn FaceSurfaces, &to).unwrap();
            assert_eq!(a.face_vertices, b.face_vertices, "{name} rate {rate}");
            assert_eq!(a.positions.len(), b.positions.len());
            for (p, q) in a.positions.iter().zip(&b.positions) {
                assert!(
                    (*p - *q).length() < 1e-9 * scale,
                    "{name} rate {rate}: {p} {q}"
                );
            }
        }
    }
}

/// With Chaikin creasing a child edge's sharpness depends on every sharp
/// edge at its vertex, and Bfr's per-face neighbourhoods lack the edges of
/// vertices beyond the face's corners: its surfaces then depart from the
/// mesh's refinement. The native surfaces are the mesh's — they equal
/// OpenSubdiv's own Far patch tables built with Bfr's options — and the
/// departure of OpenSubdiv's Bfr from them is measured here (and in
/// docs/CONFORMANCE.md).
#[test]
fn with_chaikin_creasing_native_surfaces_are_far_s_and_bfr_departs() {
    use subdiv::patches::{EndCapType, PatchOptions};
    let mut worst = (0.0f64, String::new());
    for (name, mesh) in shapes::corpus() {
        if mesh.creases.is_empty() || mesh.faces().any(|f| f.len() != 4) {
            continue;
        }
        let options = Options::default()
            .with_boundary(BoundaryInterpolation::EdgeAndCorner)
            .with_creasing(CreasingMethod::Chaikin);
        let so = SurfaceOptions {
            approx_level_smooth: 1,
            approx_level_sharp: 3,
            ..SurfaceOptions::default()
        };
        let native = LimitSurfaces::new(&mesh, &options, &so).unwrap();
        let bfr = osd::bfr::Surfaces::new(&mesh, &options, &so).unwrap();
        // Far with Bfr's options: the same patches over the whole mesh.
        let mut far = osd::TopologyRefiner::new(&mesh, &options).unwrap();
        let adaptive = subdiv::AdaptiveOptions::new(3)
            .secondary(1)
            .inf_sharp_patch(true);
        far.refine_adaptive(adaptive, &[]).unwrap();
        let mut po = PatchOptions::new()
            .end_caps(EndCapType::GregoryBasis)
            .inf_sharp_patch(true)
            .max_isolation(3)
            .double_precision(true);
        po.legacy_sharp_corner_patches = false;
        let table = far.patch_table(&po, &[]).unwrap();
        let scale = diagonal(&mesh);
        let coords = [[0.0, 0.0], [0.3, 0.7], [0.5, 0.5], [1.0, 0.25], [1.0, 1.0]];
        for face in (0..mesh.face_count()).filter(|&f| native.has_surface(f)) {
            let ours = native.evaluate(face, &coords, Derivatives::First).unwrap();
            // Quads only: ptex face = base face.
            let at: Vec<(u32, f64, f64)> =
                coords.iter().map(|c| (face as u32, c[0], c[1])).collect();
            let theirs = table
                .evaluate(
                    &far,
                    3,
                    &mesh.flat_positions::<f64>(),
                    &at,
                    Derivatives::First,
                )
                .unwrap();
            let [p, d1, _] = deviation(&ours, &theirs, scale);
            assert!(
                p < 1e-12 && d1 < 1e-10,
                "{name} face {face}: Far {p:e} {d1:e}"
            );
            let b = bfr.evaluate(face, &coords, Derivatives::First).unwrap();
            let [p, ..] = deviation(&ours, &b, scale);
            if p > worst.0 {
                worst = (p, format!("{name} face {face}"));
            }
        }
    }
    eprintln!(
        "Bfr departs from the mesh's refinement by up to {:e} of the diagonal ({})",
        worst.0, worst.1
    );
    assert!(worst.0 > 1e-6, "no departure found: {worst:?}");
}

/// Face-varying surfaces in every interpolation mode (smooth channels have
/// surfaces of their own, over the non-linear face-varying patches of a
/// refinement that isolated the channel's features): values and first
/// derivatives at every coordinate of a rate-3 pattern within 1e-9 and
/// 1e-7 of OpenSubdiv's `Bfr::Surface`s, on shapes with UV seams.
#[test]
fn smooth_face_varying_surfaces_equal_bfrs() {
    let mut departures = Vec::new();
    let mut shapes_with_uvs: Vec<(String, Mesh)> = shapes::corpus()
        .into_iter()
        .filter(|(_, m)| !m.fvar_channels.is_empty())
        .collect();
    shapes_with_uvs.push(("cube with uvs".into(), shapes::cube_with_uvs()));
    shapes_with_uvs.push((
        "mixed torus with uvs".into(),
        shapes::with_torus_uvs(shapes::torus_mixed(6, 4), 6, 4),
    ));
    shapes_with_uvs.push(("production 8x6".into(), shapes::production(8, 6)));
    let mut compared = 0;
    for (name, mesh) in &shapes_with_uvs {
        let schemes: &[Scheme] = if mesh.faces().all(|f| f.len() == 3) {
            &[Scheme::Catmark, Scheme::Loop]
        } else {
            &[Scheme::Catmark]
        };
        for &scheme in schemes {
            for &fvar in FVarLinearInterpolation::ALL {
                let options = Options::default()
                    .with_scheme(scheme)
                    .with_boundary(BoundaryInterpolation::EdgeAndCorner)
                    .with_fvar(fvar);
                let so = SurfaceOptions::default();
                compared += compare_with(name, mesh, &options, &so, &mut departures);
            }
        }
    }
    assert!(compared > 1000, "{compared}");
    // The one known departure (docs/CONFORMANCE.md): at vertex 5 of the
    // corpus' production shape, a corner of its UV channel, under
    // CornersOnly and CornersPlus1 the patch at the corner differs —
    // values agree at every sample, first derivatives at the corner itself
    // (0.1 apart) — on the three faces around it, and nowhere else.
    for (label, face, p, d1) in &departures {
        assert!(
            label.starts_with("production Options")
                && (label.contains("CornersOnly") || label.contains("CornersPlus1"))
                && [140, 141, 142].contains(face)
                && *p < 1e-9
                && *d1 < 0.2,
            "{label}: face {face}: {p:e} {d1:e}"
        );
    }
    assert!(departures.len() <= 6, "{departures:?}");
}
