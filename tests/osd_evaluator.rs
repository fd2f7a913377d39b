//! Limit evaluation in `f32`: the native engine over `f32` points against
//! OpenSubdiv's CPU evaluator (`Osd::CpuPatchTable`,
//! `Osd::CpuEvaluator::EvalPatches`, float only) through the bridge.
//!
//! The native engine reads `f32` points, weighs and sums them in `f64` and
//! rounds each value once: its `f32` values are exactly its `f64` values of
//! the same points rounded, and they differ from OpenSubdiv's, which
//! weighs and sums in `f32`, by OpenSubdiv's own rounding. The bounds used
//! below are about five to ten times the largest differences measured on
//! the corpus: 1.9e-6 of the mesh's size for positions and first
//! derivatives, 9.2e-5 for second derivatives (Loop's Gregory triangles at
//! depth 3, whose second derivatives are scaled by 4^3); on the
//! benchmark's tori, 3.4e-6 for first derivatives.
#![cfg(feature = "osd")]

use subdiv::patches::{self, Derivatives, EndCapType, PatchMap, PatchOptions, PatchTable};
use subdiv::refiner::{AdaptiveRefiner, Refiner};
use subdiv::{Error, Mesh, Options, Scheme, osd, shapes};

/// The largest difference between the native `f32` values (positions,
/// first derivatives) and OpenSubdiv's, times the mesh's size.
const F32_BOUND: f64 = 1e-5;

/// The same for second derivatives.
const F32_BOUND_SECOND: f64 = 1e-3;

fn size(mesh: &Mesh) -> f64 {
    mesh.positions
        .iter()
        .fold(0.0f64, |m, p| m.max(p.abs().max_element()))
        .max(1.0)
}

/// Both engines refined adaptively under `options` and `po`, the native
/// patch table and OpenSubdiv's (None when either engine refuses).
fn both(
    mesh: &Mesh,
    options: &Options,
    po: &PatchOptions,
) -> Option<(AdaptiveRefiner, PatchTable, osd::OsdPatchTable)> {
    let native = Refiner::new(mesh, options)
        .ok()?
        .refine_adaptive(po.refine_adaptive_options(), &[])
        .unwrap();
    let mut theirs = osd::TopologyRefiner::new(mesh, options).unwrap();
    theirs
        .refine_adaptive(po.refine_adaptive_options(), &[])
        .unwrap();
    let (Ok(mine), Ok(osds)) = (native.patch_table(po, &[]), theirs.patch_table(po, &[])) else {
        return None;
    };
    Some((native, mine, osds))
}

/// Locations on every ptex face: corners, edges' middles and inside points
/// (on triangles, u + v ≤ 1).
fn locations(ptex_faces: usize, triangles: bool) -> Vec<(u32, f64, f64)> {
    let mut out = Vec::new();
    for face in 0..ptex_faces as u32 {
        for u in [0.0, 0.3, 0.5, 1.0] {
            for v in [0.0, 0.3, 0.5, 1.0] {
                if !triangles || u + v <= 1.0 {
                    out.push((face, u, v));
                }
            }
        }
    }
    out
}

/// Over the corpus, both schemes with patches, Gregory and B-spline end
/// caps, and every set of derivatives: the native `f32` evaluation is the
/// native `f64` evaluation rounded once (bit for bit), and within
/// [`F32_BOUND`] of `EvalPatches`; both refuse the same holes.
#[test]
fn native_f32_evaluation_matches_eval_patches() {
    let mut compared = 0usize;
    for (name, mesh) in shapes::corpus() {
        for scheme in [Scheme::Catmark, Scheme::Loop] {
            let options = Options::shape_file_defaults().with_scheme(scheme);
            for end_caps in [EndCapType::GregoryBasis, EndCapType::BSplineBasis] {
                let po = PatchOptions::new().max_isolation(3).end_caps(end_caps);
                let Some((native, mine, osds)) = both(&mesh, &options, &po) else {
                    continue;
                };
                assert_eq!(&mine, osds.table(), "{name} {scheme:?} {end_caps:?}");
                let cpu = osds.cpu_patch_table().unwrap();
                let points = native
                    .patch_points(&mine, 3, &mesh.flat_positions::<f64>())
                    .unwrap();
                let points32: Vec<f32> = points.iter().map(|&x| x as f32).collect();
                let widened: Vec<f64> = points32.iter().map(|&x| f64::from(x)).collect();
                let map = PatchMap::new(&mine);
                let at = locations(mine.ptex_faces, scheme == Scheme::Loop);
                for derivatives in [Derivatives::None, Derivatives::First, Derivatives::Second] {
                    let case = format!("{name} {scheme:?} {end_caps:?} {derivatives:?}");
                    let a = patches::evaluate_with(&map, &mine, &points32, 3, &at, derivatives);
                    let b = cpu.evaluate(&points32, 3, &at, derivatives);
                    let wide = patches::evaluate_with(&map, &mine, &widened, 3, &at, derivatives);
                    let (a, b, wide) = match (a, b, wide) {
                        (Ok(a), Ok(b), Ok(wide)) => (a, b, wide),
                        (Err(Error::NoPatchAt { .. }), Err(Error::Osd(e)), Err(_))
                            if e.message.contains("is in a hole") =>
                        {
                            continue;
                        }
                        (a, b, _) => panic!("{case}: native {a:?}, osd {b:?}"),
                    };
                    for (what, x, y, w) in [
                        (
                            "point",
                            &a.values.point,
                            &b.values.point,
                            &wide.values.point,
                        ),
                        ("du", &a.values.du, &b.values.du, &wide.values.du),
                        ("dv", &a.values.dv, &b.values.dv, &wide.values.dv),
                        ("duu", &a.values.duu, &b.values.duu, &wide.values.duu),
                        ("duv", &a.values.duv, &b.values.duv, &wide.values.duv),
                        ("dvv", &a.values.dvv, &b.values.dvv, &wide.values.dvv),
                    ] {
                        assert_eq!(x.len(), y.len(), "{case}: {what}");
                        assert_eq!(x.len(), w.len(), "{case}: {what}");
                        let second = what.len() == 3;
                        let bound = size(&mesh) * if second { F32_BOUND_SECOND } else { F32_BOUND };
                        for (k, ((&p, &q), &r)) in x.iter().zip(y).zip(w).enumerate() {
                            assert_eq!(
                                p, r as f32,
                                "{case}: {what} {k}: not the f64 value rounded"
                            );
                            assert!(
                                f64::from((p - q).abs()) <= bound,
                                "{case}: {what} {k} of location {:?}: {p} against {q}",
                                at[k / 3]
                            );
                        }
                    }
                    compared += at.len();
                }
            }
        }
    }
    assert!(compared > 10_000, "{compared}");
}

/// Data of other widths (the general path: products summed in `f64`, each
/// sum rounded to `f32`) agree with `EvalPatches` too.
#[test]
fn other_widths_match_eval_patches() {
    let mesh = shapes::torus_mixed(6, 5);
    let po = PatchOptions::new().max_isolation(2);
    let (native, table, osds) = both(&mesh, &Options::default(), &po).unwrap();
    let cpu = osds.cpu_patch_table().unwrap();
    let at = locations(table.ptex_faces, false);
    for width in [1usize, 2, 4, 5] {
        // Position-like data of `width` components per base vertex.
        let base: Vec<f64> = mesh
            .positions
            .iter()
            .flat_map(|p| (0..width).map(move |c| p[c % 3] * (1.0 + c as f64)))
            .collect();
        let points = native.patch_points(&table, width, &base).unwrap();
        let points32: Vec<f32> = points.iter().map(|&x| x as f32).collect();
        let a = patches::evaluate(&table, &points32, width, &at, Derivatives::First).unwrap();
        let b = cpu
            .evaluate(&points32, width, &at, Derivatives::First)
            .unwrap();
        let bound = F32_BOUND * 6.0 * size(&mesh);
        for (x, y) in [
            (&a.values.point, &b.values.point),
            (&a.values.du, &b.values.du),
            (&a.values.dv, &b.values.dv),
        ] {
            assert_eq!(x.len(), at.len() * width);
            assert_eq!(x.len(), y.len());
            for (p, q) in x.iter().zip(y) {
                assert!(
                    f64::from((p - q).abs()) <= bound,
                    "width {width}: {p} against {q}"
                );
            }
        }
    }
}

/// What `EvalPatches` would read or write out of bounds on is refused
/// before OpenSubdiv sees it, the error naming it; legacy Gregory patches
/// (no basis) are refused.
#[test]
fn eval_patches_refusals() {
    let mut mesh = shapes::cube();
    mesh.holes.push(4);
    let po = PatchOptions::new().max_isolation(2);
    let (native, table, osds) = both(&mesh, &Options::default(), &po).unwrap();
    let cpu = osds.cpu_patch_table().unwrap();
    let points: Vec<f32> = native
        .patch_points(&table, 3, &mesh.flat_positions::<f64>())
        .unwrap()
        .iter()
        .map(|&x| x as f32)
        .collect();
    let ok = [(0u32, 0.5, 0.5)];
    assert_eq!(
        cpu.evaluate(&points, 3, &ok, Derivatives::First)
            .unwrap()
            .values
            .du
            .len(),
        3
    );
    let message = |r: Result<_, Error>| r.unwrap_err().to_string();
    let hole = [(0, 0.5, 0.5), (4, 0.5, 0.5)];
    assert!(
        message(cpu.evaluate(&points, 3, &hole, Derivatives::None))
            .contains("location 1 is in a hole")
    );
    assert!(
        message(cpu.evaluate(&points, 3, &[(6, 0.5, 0.5)], Derivatives::None))
            .contains("ptex face 6")
    );
    assert!(
        message(cpu.evaluate(&points, 3, &[(0, 1.5, 0.5)], Derivatives::None)).contains("u 1.5")
    );
    assert!(
        message(cpu.evaluate(&points, 3, &[(0, 0.5, f64::NAN)], Derivatives::None)).contains("v")
    );
    assert!(
        message(cpu.evaluate(&points[..30], 3, &ok, Derivatives::None)).contains("beyond the 10")
    );
    assert!(matches!(
        cpu.evaluate(&points, 0, &ok, Derivatives::None),
        Err(Error::ZeroWidth)
    ));
    assert!(matches!(
        cpu.evaluate(&points[..31], 3, &ok, Derivatives::None),
        Err(Error::NotWholeElements { .. })
    ));
    // No locations: nothing evaluated, nothing refused.
    let none = cpu.evaluate(&points, 3, &[], Derivatives::Second).unwrap();
    assert!(none.values.point.is_empty() && none.values.dvv.is_empty());

    // Legacy Gregory patches have no basis.
    let legacy = PatchOptions::new()
        .max_isolation(2)
        .end_caps(EndCapType::LegacyGregory);
    let mut r = osd::TopologyRefiner::new(&shapes::cube(), &Options::default()).unwrap();
    r.refine_adaptive(legacy.refine_adaptive_options(), &[])
        .unwrap();
    let t = r.patch_table(&legacy, &[]).unwrap();
    let cpu = t.cpu_patch_table().unwrap();
    let many = vec![0.0f32; 3 * 10_000];
    let e = message(cpu.evaluate(&many, 3, &ok, Derivatives::None));
    assert!(e.contains("cannot be evaluated"), "{e}");
}

/// Uniform tables (the last level's faces as bilinear `QUADS`, or
/// `TRIANGLES` with `triangulate_quads`): `EvalPatches` over them agrees
/// with the native evaluation of the same table.
#[test]
fn uniform_tables_match_eval_patches() {
    let mesh = shapes::torus_mixed(5, 4);
    let mut r = osd::TopologyRefiner::new(&mesh, &Options::default()).unwrap();
    r.refine_uniform(subdiv::UniformOptions::new(2)).unwrap();
    let base = mesh.flat_positions::<f64>();
    let levels = r.interpolate_all(3, &base).unwrap();
    // The base level's indices first (`includeBaseLevelIndices`), then the
    // last level's.
    let points: Vec<f32> = base
        .iter()
        .chain(levels.last().unwrap())
        .map(|&x| x as f32)
        .collect();
    for triangulate_quads in [false, true] {
        let po = PatchOptions {
            triangulate_quads,
            ..PatchOptions::new()
        };
        let osds = r.patch_table(&po, &[]).unwrap();
        let table = osds.table();
        let cpu = osds.cpu_patch_table().unwrap();
        let at = locations(table.ptex_faces, false);
        let a = patches::evaluate(table, &points, 3, &at, Derivatives::First).unwrap();
        let b = cpu.evaluate(&points, 3, &at, Derivatives::First).unwrap();
        for (x, y) in [
            (&a.values.point, &b.values.point),
            (&a.values.du, &b.values.du),
            (&a.values.dv, &b.values.dv),
        ] {
            assert_eq!(x.len(), 3 * at.len());
            assert_eq!(x.len(), y.len());
            for (p, q) in x.iter().zip(y) {
                let bound = F32_BOUND * size(&mesh);
                assert!(
                    f64::from((p - q).abs()) <= bound,
                    "{triangulate_quads}: {p} against {q}"
                );
            }
        }
    }
}

/// The bridge's evaluations into reused outputs (`evaluate_into`,
/// `evaluate_points_into`, as the benchmark times them) overwrite every
/// value: outputs full of NaN, longer than needed, end up bit for bit the
/// fresh call's values; columns not asked for are emptied; a refused call
/// leaves its output empty.
#[test]
fn bridge_evaluations_overwrite_reused_outputs() {
    let mesh = shapes::torus_mixed(6, 5);
    let options = Options::default();
    let po = PatchOptions::new().max_isolation(3);
    let (native, mine, osds) = both(&mesh, &options, &po).unwrap();
    let points = native
        .patch_points(&mine, 3, &mesh.flat_positions::<f64>())
        .unwrap();
    let points32: Vec<f32> = points.iter().map(|&x| x as f32).collect();
    let cpu = osds.cpu_patch_table().unwrap();
    let at = locations(mine.ptex_faces, false);
    fn stale<R: subdiv::Real>(len: usize, nan: R) -> patches::SurfaceSamples<R> {
        let c = vec![nan; len];
        patches::SurfaceSamples {
            width: 5,
            values: patches::Partials {
                point: c.clone(),
                du: c.clone(),
                dv: c.clone(),
                duu: c.clone(),
                duv: c.clone(),
                dvv: c,
            },
        }
    }
    let (mut out64, mut out32) = (
        stale(at.len() * 3 + 17, f64::NAN),
        stale(at.len() * 3 + 17, f32::NAN),
    );
    for derivatives in [Derivatives::First, Derivatives::None, Derivatives::Second] {
        osds.evaluate_points_into(&points, 3, &at, derivatives, &mut out64)
            .unwrap();
        let fresh = osds.evaluate_points(&points, 3, &at, derivatives).unwrap();
        assert_eq!(out64.width, 3);
        let bits64 = |s: &patches::SurfaceSamples| {
            let v = &s.values;
            [&v.point, &v.du, &v.dv, &v.duu, &v.duv, &v.dvv]
                .map(|c| c.iter().map(|x| x.to_bits()).collect::<Vec<_>>())
        };
        assert_eq!(bits64(&out64), bits64(&fresh), "{derivatives:?}");
        cpu.evaluate_into(&points32, 3, &at, derivatives, &mut out32)
            .unwrap();
        let fresh = cpu.evaluate(&points32, 3, &at, derivatives).unwrap();
        let bits32 = |s: &patches::SurfaceSamples<f32>| {
            let v = &s.values;
            [&v.point, &v.du, &v.dv, &v.duu, &v.duv, &v.dvv]
                .map(|c| c.iter().map(|x| x.to_bits()).collect::<Vec<_>>())
        };
        assert_eq!(bits32(&out32), bits32(&fresh), "{derivatives:?}");
        assert_eq!(out32.values.du.is_empty(), derivatives == Derivatives::None);
    }
    let off = [(0, 0.5, 0.5), (u32::MAX, 0.5, 0.5)];
    assert!(
        osds.evaluate_points_into(&points, 3, &off, Derivatives::First, &mut out64)
            .is_err()
    );
    assert!(out64.values.point.is_empty() && out64.values.du.is_empty());
    assert!(
        cpu.evaluate_into(&points32, 3, &off, Derivatives::First, &mut out32)
            .is_err()
    );
    assert!(out32.values.point.is_empty());
}
