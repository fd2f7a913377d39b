//! Limit stencils at locations (`LocationStencils`, OpenSubdiv's
//! `LimitStencilTableFactory` with `LocationArray`s): the native engine
//! against OpenSubdiv over the corpus — same locations with stencils, same
//! sizes, same base vertices term by term, weights within 1e-12 — and the
//! stencils against what they stand for: applied to the base positions they
//! give the limit surface `patches::evaluate` computes, and on a regular
//! grid the bicubic B-spline's weights by formula.
#![cfg(feature = "osd")]

use subdiv::patches::{self, Derivatives, LimitStencilOptions, LocationStencils, PatchOptions};
use subdiv::refiner::Refiner;
use subdiv::stencil::StencilInterpolation;
use subdiv::{
    AdaptiveOptions, BoundaryInterpolation, Error, Mesh, Options, Scheme, UniformOptions, osd,
    shapes,
};

/// Locations on every ptex face: corners, edges, inside.
fn locations(ptex_faces: usize) -> Vec<(u32, f64, f64)> {
    let at = [0.0, 0.3, 0.5, 1.0];
    let mut out = Vec::new();
    for f in 0..ptex_faces as u32 {
        for &u in &at {
            for &v in &at {
                out.push((f, u, v));
            }
        }
    }
    out
}

/// Two tables equal in everything but rounding: same locations, sizes,
/// offsets and indices, weights within `tol`.
fn same(a: &LocationStencils, b: &LocationStencils, case: &str) {
    assert_eq!(a.control_vertices, b.control_vertices, "{case}");
    assert_eq!(a.locations, b.locations, "{case}");
    assert_eq!(a.sizes, b.sizes, "{case}");
    assert_eq!(a.offsets, b.offsets, "{case}");
    assert_eq!(a.indices, b.indices, "{case}");
    let (wa, wb) = (&a.weights, &b.weights);
    for (name, x, y) in [
        ("point", &wa.point, &wb.point),
        ("du", &wa.du, &wb.du),
        ("dv", &wa.dv, &wb.dv),
        ("duu", &wa.duu, &wb.duu),
        ("duv", &wa.duv, &wb.duv),
        ("dvv", &wa.dvv, &wb.dvv),
    ] {
        assert_eq!(x.len(), y.len(), "{case}: {name}");
        for (i, (p, q)) in x.iter().zip(y).enumerate() {
            assert!(
                (p - q).abs() <= 1e-12,
                "{case}: {name} weight {i}: {p} vs {q}"
            );
        }
    }
}

fn ptex_faces(mesh: &Mesh, options: &Options) -> usize {
    let r = Refiner::new(mesh, options).unwrap();
    subdiv::PtexIndices::new(&r).unwrap().num_faces()
}

#[test]
fn adaptive_corpus_matches_opensubdiv() {
    let (mut tables, mut stencils, mut holes, mut loop_tables) = (0, 0, 0, 0);
    for (name, mesh) in shapes::corpus() {
        for scheme in [Scheme::Catmark, Scheme::Bilinear, Scheme::Loop] {
            for boundary in [
                BoundaryInterpolation::EdgeOnly,
                BoundaryInterpolation::EdgeAndCorner,
            ] {
                let options = Options::shape_file_defaults()
                    .with_scheme(scheme)
                    .with_boundary(boundary);
                let Ok(native) = Refiner::new(&mesh, &options) else {
                    continue;
                };
                let mut locs = locations(ptex_faces(&mesh, &options));
                if scheme == Scheme::Loop {
                    // A triangle's parameters: u + v <= 1. (Beyond it,
                    // second derivatives on Gregory triangles, extrapolated
                    // and scaled by 4^depth, round differently by up to
                    // 7e-12 at (1, 0.3).)
                    locs.retain(|&(_, u, v)| u + v <= 1.0);
                }
                for (isolation, inf_sharp) in [(1, false), (3, false), (2, true)] {
                    let ao = AdaptiveOptions::new(isolation).inf_sharp_patch(inf_sharp);
                    let Ok(mine) = native.clone().refine_adaptive(ao, &[]) else {
                        continue;
                    };
                    let mut theirs = osd::TopologyRefiner::new(&mesh, &options).unwrap();
                    theirs.refine_adaptive(ao, &[]).unwrap();
                    for o in [
                        LimitStencilOptions::new().first_derivatives(false),
                        LimitStencilOptions::new(),
                        LimitStencilOptions::new().second_derivatives(true),
                        LimitStencilOptions::new().interpolation(StencilInterpolation::Varying),
                        LimitStencilOptions::new().interpolation(StencilInterpolation::FaceVarying),
                    ] {
                        let case = format!("{name} {options:?} {ao:?} {o:?}");
                        let b = match theirs.location_stencils(&locs, &o) {
                            Ok(b) => b,
                            // Refused by the bridge (faces repeating a vertex).
                            Err(Error::Osd(_)) => continue,
                            Err(e) => panic!("{case}: {e}"),
                        };
                        let a = match mine.location_stencils(&locs, &o) {
                            Ok(a) => a,
                            Err(e) => panic!("{case}: {e}"),
                        };
                        same(&a, &b, &case);
                        tables += 1;
                        loop_tables += usize::from(scheme == Scheme::Loop);
                        stencils += a.len();
                        holes += locs.len() - a.len();
                    }
                }
            }
        }
    }
    eprintln!(
        "{tables} tables ({loop_tables} Loop), {stencils} stencils, {holes} locations in holes"
    );
    assert!(tables > 300 && stencils > 100_000 && holes > 0 && loop_tables > 100);
}

#[test]
fn uniform_corpus_matches_opensubdiv() {
    let mut tables = 0;
    for (name, mesh) in shapes::corpus() {
        for scheme in [Scheme::Catmark, Scheme::Loop, Scheme::Bilinear] {
            let options = Options::shape_file_defaults().with_scheme(scheme);
            let Ok(native) = Refiner::new(&mesh, &options) else {
                continue;
            };
            let locs = locations(ptex_faces(&mesh, &options));
            for level in [1, 2] {
                let mut mine = native.clone();
                mine.refine_uniform(UniformOptions::new(level)).unwrap();
                let mut theirs = osd::TopologyRefiner::new(&mesh, &options).unwrap();
                theirs.refine_uniform(UniformOptions::new(level)).unwrap();
                for o in [
                    LimitStencilOptions::new(),
                    LimitStencilOptions::new()
                        .second_derivatives(true)
                        .interpolation(StencilInterpolation::Varying),
                    LimitStencilOptions::new().interpolation(StencilInterpolation::FaceVarying),
                ] {
                    let case = format!("{name} {options:?} level {level} {o:?}");
                    if o.interpolation == StencilInterpolation::FaceVarying
                        && mesh.fvar_channels.is_empty()
                    {
                        continue;
                    }
                    let b = theirs.location_stencils(&locs, &o).expect(&case);
                    let a = mine.location_stencils(&locs, &o).expect(&case);
                    same(&a, &b, &case);
                    tables += 1;
                }
            }
        }
    }
    assert!(tables > 300, "{tables}");
}

/// Applied to the base positions, the stencils give the limit surface the
/// patch table evaluates from refined and local points.
#[test]
fn applied_stencils_are_the_limit_surface() {
    let mut compared = 0;
    for (name, mesh) in shapes::corpus() {
        let options = Options::shape_file_defaults();
        let Ok(r) = Refiner::new(&mesh, &options) else {
            continue;
        };
        let po = PatchOptions::new().max_isolation(3).double_precision(true);
        let Ok(a) = r.refine_adaptive(po.refine_adaptive_options(), &[]) else {
            continue;
        };
        let Ok(table) = a.patch_table(&po, &[]) else {
            continue;
        };
        let base = mesh.flat_positions::<f64>();
        let points = a.patch_points(&table, 3, &base).unwrap();
        let locs = locations(table.ptex_faces);
        let o = LimitStencilOptions::new().second_derivatives(true);
        let s = a.location_stencils(&locs, &o).unwrap();
        let applied = s.apply(3, &base).unwrap();
        let found: Vec<_> = s.locations.iter().map(|&i| locs[i]).collect();
        let direct = patches::evaluate(&table, &points, 3, &found, Derivatives::Second).unwrap();
        let d = &direct.values;
        for (what, x, y) in [
            ("point", &applied.point, &d.point),
            ("du", &applied.du, &d.du),
            ("dvv", &applied.dvv, &d.dvv),
        ] {
            for (p, q) in x.iter().zip(y) {
                assert!((p - q).abs() < 1e-9, "{name} {what}: {p} vs {q}");
            }
        }
        compared += found.len();
    }
    assert!(compared > 10_000, "{compared}");
}

/// On a regular patch the stencil is the bicubic B-spline's tensor product,
/// by formula: at (u, v) the weight of control point (i, j) of the 4×4
/// neighbourhood is b_i(u) b_j(v).
#[test]
fn regular_patch_weights_by_formula() {
    // A closed torus of quads, all regular: every face is one B-spline
    // patch over its 4×4 neighbourhood.
    let (nu, nv) = (8u32, 6u32);
    let mesh = shapes::torus(nu, nv);
    let mut r = osd::TopologyRefiner::new(&mesh, &Options::default()).unwrap();
    r.refine_adaptive(AdaptiveOptions::new(2), &[]).unwrap();
    let native = Refiner::new(&mesh, &Options::default())
        .unwrap()
        .refine_adaptive(AdaptiveOptions::new(2), &[])
        .unwrap();
    let b = |t: f64| {
        let s = 1.0 - t;
        [
            s * s * s / 6.0,
            (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0,
            (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0,
            t * t * t / 6.0,
        ]
    };
    let (u, v) = (0.25, 0.625);
    let o = LimitStencilOptions::new().first_derivatives(false);
    let s = native.location_stencils(&[(0, u, v)], &o).unwrap();
    same(&s, &r.location_stencils(&[(0, u, v)], &o).unwrap(), "torus");
    assert_eq!(s.sizes, [16]);
    // The 16 weights are the products of the two cubic bases, in some
    // order: compare them sorted.
    let mut want: Vec<f64> = b(u).iter().flat_map(|&x| b(v).map(|y| x * y)).collect();
    let mut got = s.weights.point.clone();
    want.sort_by(f64::total_cmp);
    got.sort_by(f64::total_cmp);
    for (g, w) in got.iter().zip(&want) {
        assert!((g - w).abs() < 1e-14, "{got:?} vs {want:?}");
    }
}

#[test]
fn holes_have_no_stencil_and_bad_locations_are_refused() {
    // A 4×4 grid with face 5 a hole (boundary edges kept: with OpenSubdiv's
    // default of no boundary interpolation, faces at the boundary are holes
    // too).
    let mut mesh = shapes::grid(4, 4);
    mesh.holes = vec![5];
    let options = Options::default().with_boundary(BoundaryInterpolation::EdgeOnly);
    let native = Refiner::new(&mesh, &options)
        .unwrap()
        .refine_adaptive(AdaptiveOptions::new(2), &[])
        .unwrap();
    let mut theirs = osd::TopologyRefiner::new(&mesh, &options).unwrap();
    theirs
        .refine_adaptive(AdaptiveOptions::new(2), &[])
        .unwrap();
    let o = LimitStencilOptions::new();
    let locs = [(4, 0.5, 0.5), (5, 0.5, 0.5), (6, 0.1, 0.9)];
    let a = native.location_stencils(&locs, &o).unwrap();
    same(&a, &theirs.location_stencils(&locs, &o).unwrap(), "holes");
    assert_eq!(a.locations, [0, 2]);
    for bad in [(16, 0.5, 0.5), (0, 1.5, 0.5), (0, 0.5, f64::NAN)] {
        assert!(
            matches!(
                native.location_stencils(&[bad], &o),
                Err(Error::NoSuchPtexFace { .. } | Error::Location { .. })
            ),
            "{bad:?}"
        );
        assert!(
            matches!(theirs.location_stencils(&[bad], &o), Err(Error::Osd(_))),
            "{bad:?}"
        );
    }
    // An unrefined uniform refiner: refused by both (OpenSubdiv's table of
    // level 0 has its patches unset).
    let unrefined = Refiner::new(&mesh, &options).unwrap();
    assert!(matches!(
        unrefined.location_stencils(&locs, &o),
        Err(Error::PatchOptions { .. })
    ));
    let theirs0 = osd::TopologyRefiner::new(&mesh, &options).unwrap();
    assert!(matches!(
        theirs0.location_stencils(&locs, &o),
        Err(Error::Osd(_))
    ));
    // Face-varying stencils after a refinement that considered the
    // channels, over OpenSubdiv's non-linear face-varying patches: refused
    // (OpenSubdiv 3.5 reads uninitialised weights there; the bridge
    // refuses them too).
    let fvar = o.interpolation(StencilInterpolation::FaceVarying);
    assert!(!mesh.fvar_channels.is_empty());
    // (A channel interpolated linearly everywhere, OpenSubdiv's default,
    // keeps linear patches: take USD's corners-plus-one.)
    let smooth_uvs = options.with_fvar(subdiv::FVarLinearInterpolation::CornersPlus1);
    let considered = Refiner::new(&mesh, &smooth_uvs)
        .unwrap()
        .refine_adaptive(AdaptiveOptions::new(2).consider_fvar(true), &[])
        .unwrap();
    assert!(matches!(
        considered.location_stencils(&locs, &fvar),
        Err(Error::NotYetSupported(_))
    ));
    // A channel the mesh lacks.
    assert!(matches!(
        native.location_stencils(&locs, &fvar.fvar_channel(3)),
        Err(Error::NoSuchChannel { .. })
    ));
}

/// Varying and face-varying stencils through the bridge, under a smooth
/// face-varying rule: OpenSubdiv builds them over the corpus, and they are
/// affine — each stencil's position weights sum to 1, its derivative
/// weights to 0 — except face-varying ones after a refinement that
/// considered the channels (its non-linear face-varying patches), which the
/// bridge refuses: OpenSubdiv reads uninitialised weights there and its
/// stencils do not sum to 1 (Valgrind; a stencil of the production-like
/// shape summed to 1.9e-5).
#[test]
fn bridge_varying_and_face_varying_stencils_are_affine() {
    let (mut checked, mut refused) = (0, 0);
    for (name, mesh) in shapes::corpus() {
        if mesh.fvar_channels.is_empty() {
            continue;
        }
        for (scheme, consider) in [
            (Scheme::Catmark, false),
            (Scheme::Bilinear, false),
            (Scheme::Loop, false),
            (Scheme::Catmark, true),
            (Scheme::Loop, true),
        ] {
            let options = Options::shape_file_defaults()
                .with_scheme(scheme)
                .with_fvar(subdiv::FVarLinearInterpolation::CornersPlus1);
            if Refiner::new(&mesh, &options).is_err() {
                continue;
            }
            let locs = locations(ptex_faces(&mesh, &options));
            let mut theirs = osd::TopologyRefiner::new(&mesh, &options).unwrap();
            let ao = AdaptiveOptions::new(2).consider_fvar(consider);
            if theirs.refine_adaptive(ao, &[]).is_err() {
                continue;
            }
            for interpolation in [
                StencilInterpolation::Varying,
                StencilInterpolation::FaceVarying,
            ] {
                let o = LimitStencilOptions::new()
                    .interpolation(interpolation)
                    .second_derivatives(true);
                let case = format!("{name} {scheme:?} {ao:?} {interpolation:?}");
                let s = match theirs.location_stencils(&locs, &o) {
                    Err(Error::Osd(e))
                        if consider && interpolation == StencilInterpolation::FaceVarying =>
                    {
                        assert_eq!(e.kind, subdiv::OsdErrorKind::Unsafe, "{case}");
                        refused += 1;
                        continue;
                    }
                    Ok(s) => s,
                    Err(Error::Osd(_)) => continue,
                    Err(e) => panic!("{case}: {e}"),
                };
                assert!(!s.is_empty(), "{case}");
                for i in 0..s.len() {
                    let t = s.offsets[i] as usize..(s.offsets[i] + s.sizes[i]) as usize;
                    let sum = |w: &[f64]| w[t.clone()].iter().sum::<f64>();
                    let w = &s.weights;
                    assert!(
                        (sum(&w.point) - 1.0).abs() < 1e-12,
                        "{case} stencil {i}: {} ({} terms)",
                        sum(&w.point),
                        s.sizes[i]
                    );
                    for d in [&w.du, &w.dv, &w.duu, &w.duv, &w.dvv] {
                        assert!(
                            sum(d).abs() < 1e-9,
                            "{case} stencil {i}: {} {}",
                            sum(&w.point),
                            sum(d)
                        );
                    }
                }
                checked += 1;
            }
        }
    }
    assert!(checked > 10 && refused > 0, "{checked} {refused}");
}

/// Varying and face-varying values evaluated from a patch table
/// (`patches::evaluate_data` over `patch_data_points`) are what the location
/// stencils of the same data give (which are OpenSubdiv's, above): values
/// and first derivatives within 1e-12 of the data's size.
#[test]
fn evaluated_primvars_match_their_location_stencils() {
    use subdiv::patches::{PatchData, PatchMap};
    let mut compared = 0;
    for (name, mesh) in shapes::corpus() {
        if mesh.fvar_channels.is_empty() {
            continue;
        }
        let options = Options::shape_file_defaults();
        let Ok(r) = Refiner::new(&mesh, &options) else {
            continue;
        };
        let mut po = PatchOptions::new().max_isolation(2).double_precision(true);
        po.fvar_tables = true;
        let a = r
            .refine_adaptive(po.refine_adaptive_options(), &[])
            .unwrap();
        let table = a.patch_table(&po, &[]).unwrap();
        let map = PatchMap::new(&table);
        let locs = locations(table.ptex_faces);
        let uv = &mesh.fvar_channels[0];
        for (data, interpolation, width, base) in [
            (
                PatchData::Varying,
                StencilInterpolation::Varying,
                3,
                mesh.flat_positions::<f64>(),
            ),
            (
                PatchData::FaceVarying(0),
                StencilInterpolation::FaceVarying,
                uv.width,
                uv.values.clone(),
            ),
        ] {
            let o = LimitStencilOptions::new().interpolation(interpolation);
            let stencils = a.location_stencils(&locs, &o).unwrap();
            let found: Vec<_> = stencils.locations.iter().map(|&i| locs[i]).collect();
            let want = stencils.apply(width, &base).unwrap();
            let points = a.patch_data_points(&table, data, width, &base).unwrap();
            let got = patches::evaluate_data(
                &map,
                &table,
                data,
                &points,
                width,
                &found,
                Derivatives::First,
            )
            .unwrap()
            .values;
            let size = base.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            for (what, x, y) in [
                ("value", &got.point, &want.point),
                ("du", &got.du, &want.du),
                ("dv", &got.dv, &want.dv),
            ] {
                assert_eq!(x.len(), y.len(), "{name} {data:?} {what}");
                for (p, q) in x.iter().zip(y) {
                    assert!(
                        (p - q).abs() <= 1e-12 * size,
                        "{name} {data:?} {what}: {p} vs {q}"
                    );
                }
            }
            compared += found.len();
        }
    }
    assert!(compared > 1_000, "{compared}");
}
