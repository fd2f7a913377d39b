//! Many locations at once (`patches::evaluate_data`): a batch is evaluated
//! in ptex-face order, on the pool's threads, yet every value is the one
//! the location gets alone, in the caller's order, and an error names the
//! first bad location in the caller's order.

use subdiv::patches::{
    self, Derivatives, PatchData, PatchMap, PatchOptions, PatchTable, PatchType,
};
use subdiv::ptex::PtexIndices;
use subdiv::refiner::{AdaptiveRefiner, Refiner};
use subdiv::{BoundaryInterpolation, Error, Mesh, Options, Real, Scheme, shapes};

/// A mesh with quads, triangles and extraordinary vertices, refined and
/// its patch table (Gregory end caps) built.
fn setup(mesh: &Mesh) -> (AdaptiveRefiner, PatchTable) {
    setup_with(mesh, &Options::default())
}

/// [`setup`] under `options`.
fn setup_with(mesh: &Mesh, options: &Options) -> (AdaptiveRefiner, PatchTable) {
    let options_ = options;
    let options = PatchOptions::new().max_isolation(3);
    let adaptive = Refiner::new(mesh, options_)
        .unwrap()
        .refine_adaptive(options.refine_adaptive_options(), &[])
        .unwrap();
    let table = adaptive.patch_table(&options, &[]).unwrap();
    (adaptive, table)
}

/// `count` pseudo-random locations on faces that have patches, in no
/// order.
fn scattered(table: &PatchTable, map: &PatchMap, count: usize) -> Vec<(u32, f64, f64)> {
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut out = Vec::new();
    while out.len() < count {
        let l = ((next() * table.ptex_faces as f64) as u32, next(), next());
        if map.find_patch(l.0, l.1, l.2).is_some() {
            out.push(l);
        }
    }
    out
}

/// Each location evaluated alone (a batch of one is evaluated as given).
fn one_by_one<R: Real>(
    map: &PatchMap,
    table: &PatchTable,
    points: &[R],
    width: usize,
    locations: &[(u32, f64, f64)],
    derivatives: Derivatives,
) -> Vec<Vec<R>> {
    let mut columns = vec![Vec::new(); 6];
    for &l in locations {
        let s = patches::evaluate_data(
            map,
            table,
            PatchData::Vertex,
            points,
            width,
            &[l],
            derivatives,
        )
        .unwrap();
        let v = s.values;
        for (c, kind) in columns
            .iter_mut()
            .zip([v.point, v.du, v.dv, v.duu, v.duv, v.dvv])
        {
            c.extend(kind);
        }
    }
    columns
}

/// Each of `locations` evaluated in one batch, on each number of
/// `threads`, gets the value it gets alone, bit for bit: the same sums,
/// only in another order of locations.
fn batches_match_alone<R: Real>(
    map: &PatchMap,
    table: &PatchTable,
    points: &[R],
    width: usize,
    locations: &[(u32, f64, f64)],
    threads: &[usize],
) {
    for derivatives in [Derivatives::None, Derivatives::First, Derivatives::Second] {
        let alone = one_by_one(map, table, points, width, locations, derivatives);
        for &threads in threads {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let s = pool
                .install(|| {
                    patches::evaluate_with(map, table, points, width, locations, derivatives)
                })
                .unwrap();
            let v = s.values;
            for (kind, (got, want)) in [v.point, v.du, v.dv, v.duu, v.duv, v.dvv]
                .iter()
                .zip(&alone)
                .enumerate()
            {
                assert_eq!(got.len(), want.len());
                let differ = got
                    .iter()
                    .zip(want)
                    .position(|(a, b)| a.to_f64().to_bits() != b.to_f64().to_bits());
                assert_eq!(
                    differ, None,
                    "width {width}, {derivatives:?}, {threads} threads, kind {kind}"
                );
            }
        }
    }
}

/// Whether a batch of locations on `table` with `points` is evaluated in
/// face order: when the data it reads do not stay in the caches (more than
/// the 2 MiB below which locations are evaluated as given).
fn in_face_order<R>(table: &PatchTable, points: &[R]) -> bool {
    let patches: usize = table
        .arrays
        .iter()
        .map(|a| a.control_vertices.len() * 4 + a.params.len() * 8)
        .sum();
    std::mem::size_of_val(points) + patches > 2 << 20
}

/// Data of widths 3 (positions, summed in registers) and 4 (any other
/// width) at `mesh`'s vertices.
fn bases(mesh: &Mesh) -> (Vec<f64>, Vec<f64>) {
    let base4 = mesh
        .positions
        .iter()
        .flat_map(|p| [p.x, p.y, p.z, p.x * p.y - p.z])
        .collect();
    (mesh.flat_positions::<f64>(), base4)
}

/// The meshes batches are tried on: one whose data stay in the caches
/// (locations evaluated as given, in stretches side by side on several
/// threads) and one past them (in face order).
const MESHES: [(u32, u32, bool); 2] = [(12, 10, false), (24, 20, true)];

#[test]
fn a_batch_gives_each_location_its_own_value_in_order() {
    for (u, v, face_order) in MESHES {
        a_batch_gives_each_location_its_own_value(shapes::torus_mixed(u, v), face_order);
    }
}

fn a_batch_gives_each_location_its_own_value(mesh: Mesh, face_order: bool) {
    let (adaptive, table) = setup(&mesh);
    let map = PatchMap::new(&table);
    let locations = scattered(&table, &map, 20_000);
    let (base3, base4) = bases(&mesh);
    for (width, base) in [(3, &base3), (4, &base4)] {
        let points = adaptive.patch_points(&table, width, base).unwrap();
        assert_eq!(in_face_order(&table, &points), face_order);
        batches_match_alone(&map, &table, &points, width, &locations, &[1, 2, 3]);
    }
}

/// Points in `f32` (as OpenSubdiv's evaluators take them): a batch gives
/// each location its own value too, in the given order and in face order
/// (the larger mesh), and positions (width 3, summed in `f64` and rounded
/// once) are the `f64` values of the same points rounded, bit for bit.
#[test]
fn f32_points_give_each_location_its_own_value() {
    for (u, v, face_order) in [(12, 10, false), (40, 32, true)] {
        let mesh = shapes::torus_mixed(u, v);
        let (adaptive, table) = setup(&mesh);
        let map = PatchMap::new(&table);
        let locations = scattered(&table, &map, 20_000);
        let (base3, base4) = bases(&mesh);
        for (width, base) in [(3, &base3), (4, &base4)] {
            let points: Vec<f32> = adaptive
                .patch_points(&table, width, base)
                .unwrap()
                .iter()
                .map(|&x| x as f32)
                .collect();
            assert_eq!(in_face_order(&table, &points), face_order);
            batches_match_alone(&map, &table, &points, width, &locations, &[1, 2]);
            if width != 3 {
                continue;
            }
            let widened: Vec<f64> = points.iter().map(|&x| f64::from(x)).collect();
            for derivatives in [Derivatives::First, Derivatives::Second] {
                let narrow =
                    patches::evaluate_with(&map, &table, &points, 3, &locations, derivatives)
                        .unwrap()
                        .values;
                let wide =
                    patches::evaluate_with(&map, &table, &widened, 3, &locations, derivatives)
                        .unwrap()
                        .values;
                for (got, want) in [
                    (&narrow.point, &wide.point),
                    (&narrow.du, &wide.du),
                    (&narrow.dvv, &wide.dvv),
                ] {
                    assert_eq!(got.len(), want.len());
                    assert!(got.iter().zip(want).all(|(&a, &b)| a == b as f32));
                }
            }
        }
    }
}

/// Under Loop, a batch computes each regular patch's polynomial once for
/// all its locations, a location alone its own patch's: the same values,
/// bit for bit, boundary patches (their phantom points folded in)
/// included.
#[test]
fn loop_patches_give_each_location_its_own_value() {
    let mesh = shapes::triangulate(&shapes::grid(14, 12));
    let options = Options::default()
        .with_scheme(Scheme::Loop)
        .with_boundary(BoundaryInterpolation::EdgeOnly);
    let (adaptive, table) = setup_with(&mesh, &options);
    assert!(
        table
            .arrays
            .iter()
            .any(|a| a.patch_type == PatchType::Loop && a.params.iter().any(|p| p.boundary() != 0)),
        "no boundary box-spline patches"
    );
    let map = PatchMap::new(&table);
    let locations = scattered(&table, &map, 5_000);
    let points = adaptive
        .patch_points(&table, 3, &mesh.flat_positions::<f64>())
        .unwrap();
    batches_match_alone(&map, &table, &points, 3, &locations, &[1, 2]);
}

#[test]
fn a_batch_reports_its_first_bad_location() {
    for (u, v, face_order) in MESHES {
        a_batch_reports_its_first_bad(shapes::torus_mixed(u, v), face_order);
    }
}

fn a_batch_reports_its_first_bad(mut mesh: Mesh, face_order: bool) {
    // Two holes: the later hole's face comes first in face order.
    mesh.holes.extend([7, 40]);
    let (adaptive, table) = setup(&mesh);
    let map = PatchMap::new(&table);
    let points = adaptive
        .patch_points(&table, 3, &mesh.flat_positions::<f64>())
        .unwrap();
    assert_eq!(in_face_order(&table, &points), face_order);
    // The (first) ptex faces of the holes.
    let ptex = PtexIndices::new(&Refiner::new(&mesh, &Options::default()).unwrap()).unwrap();
    let (early, late) = (ptex.face_id(7).unwrap(), ptex.face_id(40).unwrap());
    assert!(map.find_patch(early, 0.5, 0.5).is_none());
    assert!(map.find_patch(late, 0.5, 0.5).is_none());
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let mut locations = scattered(&table, &map, 10_000);
        locations[100] = (late, 0.5, 0.5);
        locations[6000] = (early, 0.25, 0.5);
        // In the second stretch of 8,192 (evaluated beside the first).
        locations[9000] = (early, 0.75, 0.5);
        let e = pool
            .install(|| {
                patches::evaluate_with(&map, &table, &points, 3, &locations, Derivatives::First)
            })
            .unwrap_err();
        assert!(
            matches!(e, Error::NoPatchAt { face, .. } if face == late),
            "{threads} threads: {e}"
        );
        // A location off its face is refused before any is evaluated.
        locations[50] = (0, 1.5, 0.5);
        let e = pool
            .install(|| {
                patches::evaluate_with(&map, &table, &points, 3, &locations, Derivatives::None)
            })
            .unwrap_err();
        assert!(matches!(e, Error::Location { face: 0, .. }), "{e}");
    }
}

/// Outputs reused from call to call (`evaluate_data_into`): every value
/// is overwritten — the columns filled with NaN first, longer than
/// needed, give the values a fresh evaluation gives, bit for bit, in
/// given and in face order, on one and two threads; columns not asked
/// for are emptied; a failing call leaves `out` empty.
#[test]
fn reused_outputs_are_overwritten_whole() {
    for (u, v, face_order) in MESHES {
        let mesh = shapes::torus_mixed(u, v);
        let (adaptive, table) = setup(&mesh);
        let map = PatchMap::new(&table);
        let locations = scattered(&table, &map, 12_000);
        let (base3, base4) = bases(&mesh);
        for (width, base) in [(3, &base3), (4, &base4)] {
            let points = adaptive.patch_points(&table, width, base).unwrap();
            assert_eq!(in_face_order(&table, &points), face_order);
            for threads in [1, 2] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                let stale = vec![f64::NAN; 15_000 * width];
                let mut out = patches::SurfaceSamples {
                    width: 7,
                    values: patches::Partials {
                        point: stale.clone(),
                        du: stale.clone(),
                        dv: stale.clone(),
                        duu: stale.clone(),
                        duv: stale.clone(),
                        dvv: stale,
                    },
                };
                for (count, derivatives) in [
                    (12_000, Derivatives::First),
                    (7_000, Derivatives::Second),
                    (9_000, Derivatives::None),
                ] {
                    let at = &locations[..count];
                    pool.install(|| {
                        patches::evaluate_data_into(
                            patches::Evaluation::OpenSubdiv,
                            &map,
                            &table,
                            PatchData::Vertex,
                            &points,
                            width,
                            at,
                            derivatives,
                            &mut out,
                        )
                    })
                    .unwrap();
                    let fresh =
                        patches::evaluate_with(&map, &table, &points, width, at, derivatives)
                            .unwrap();
                    assert_eq!(out.width, width);
                    let bits = |s: &patches::SurfaceSamples| {
                        let v = &s.values;
                        [&v.point, &v.du, &v.dv, &v.duu, &v.duv, &v.dvv]
                            .map(|c| c.iter().map(|x| x.to_bits()).collect::<Vec<_>>())
                    };
                    assert_eq!(
                        bits(&out),
                        bits(&fresh),
                        "width {width}, {threads} threads, {derivatives:?}"
                    );
                    assert_eq!(out.values.point.len(), count * width);
                    assert_eq!(out.values.du.is_empty(), derivatives == Derivatives::None);
                }
                let bad = [(0, 0.5, 0.5), (0, 0.5, 1.5)];
                let e = patches::evaluate_data_into(
                    patches::Evaluation::OpenSubdiv,
                    &map,
                    &table,
                    PatchData::Vertex,
                    &points,
                    width,
                    &bad,
                    Derivatives::First,
                    &mut out,
                )
                .unwrap_err();
                assert!(matches!(e, Error::Location { face: 0, .. }), "{e}");
                assert!(out.values.point.is_empty() && out.values.du.is_empty());
            }
        }
    }
}
