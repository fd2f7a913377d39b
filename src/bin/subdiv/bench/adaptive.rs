//! The adaptive section of `subdiv bench`: feature-adaptive refinement
//! (`Refiner::refine_adaptive` against OpenSubdiv's `RefineAdaptive`) at
//! isolation levels 3 and 6, and at isolation 3 the limit surface: patch
//! tables (`AdaptiveRefiner::patch_table` against
//! `PatchTableFactory::Create`) and evaluation at many locations
//! (`patches::evaluate` against far tutorial 5_1's `FindPatch` +
//! `EvaluateBasis` loop).

use super::results::{AdaptiveRow, Row};
use super::timing::interleaved;
use crate::Failure;
use std::hint::black_box;
use subdiv::options::{AdaptiveOptions, BoundaryInterpolation, FVarLinearInterpolation, Options};
use subdiv::patches::{self, Derivatives, PatchMap, PatchOptions, SurfaceSamples};
use subdiv::refiner::{AdaptiveRefiner, Refiner};
use subdiv::shapes::BenchShape;
use subdiv::{Result, osd, shapes};

/// The isolation levels of the adaptive rows.
pub const ISOLATION_LEVELS: [u32; 2] = [3, 6];

/// The isolation level of the patch-table and evaluation rows.
const PATCH_ISOLATION: u32 = 3;

/// Locations evaluated per repetition of the evaluation row (the bench
/// passes one tenth with `--quick`).
pub const LOCATIONS: usize = 1_000_000;

/// The inputs of the adaptive rows: every input refined more than two
/// levels (the tori of the standard inputs: the quad torus and Loop's
/// triangle torus are regular everywhere, so adaptive refinement refines
/// nothing on them and only their topology row is measured), then, with the
/// standard inputs, a creased mesh rich in extraordinary vertices:
/// [`shapes::production`] at 96 × 80 cells (8,448 faces; 24 × 20 with
/// `quick`) — valence-3 and valence-5 vertices around its hexagons and
/// triangle pairs, a semi-sharp crease ring, an infinitely sharp chain with
/// dart ends, sharp corners and holes — with USD's default options as the
/// standard production-like input.
pub fn adaptive_inputs(inputs: &[BenchShape], standard: bool, quick: bool) -> Vec<BenchShape> {
    let mut out: Vec<BenchShape> = inputs.iter().filter(|i| i.max_level > 2).cloned().collect();
    if standard {
        let d = if quick { 4 } else { 1 };
        let (nu, nv) = (96 / d, 80 / d);
        out.push(BenchShape {
            name: format!("production {nu}x{nv} with UVs"),
            mesh: shapes::production(nu, nv),
            options: Options::default()
                .with_boundary(BoundaryInterpolation::EdgeAndCorner)
                .with_fvar(FVarLinearInterpolation::CornersPlus1),
            max_level: 6,
        });
    }
    out
}

/// Every level's positions (`f32`, width 3) from `base`, level by level
/// (`AdaptiveRefiner::interpolate`); `result[0]` is `base`.
fn native_levels(r: &AdaptiveRefiner, base: &[f32]) -> Result<Vec<Vec<f32>>> {
    let mut out = vec![base.to_vec()];
    for level in 1..=r.max_level() {
        let next = r.interpolate(level, 3, out.last().expect("non-empty"))?;
        out.push(next);
    }
    Ok(out)
}

/// Rows of `input` at each of [`ISOLATION_LEVELS`] (and at
/// [`PATCH_ISOLATION`] the limit-surface rows of `limit_rows`, evaluating
/// `locations` locations): "adaptive topology
/// (isolation N)" (`Refiner::new` and `refine_adaptive` against
/// `TopologyRefinerFactory::Create` and `RefineAdaptive`, as the topology
/// refinement rows include the base level) and "adaptive positions (f32,
/// isolation N)" (every refined level's positions from the base level's,
/// level by level: `AdaptiveRefiner::interpolate` against
/// `PrimvarRefiner::Interpolate`). Both engines refine once first (not
/// timed): the levels they reach and every level's positions must be equal
/// bit for bit, or the rows are refused. The positions row is left out
/// when nothing was refined (a mesh without features).
pub fn adaptive_rows(
    pool: &rayon::ThreadPool,
    input: &BenchShape,
    reps: usize,
    locations: usize,
    mut progress: impl FnMut(&str),
) -> Result<Vec<AdaptiveRow>, Failure> {
    let options = input.options;
    let base = input.mesh.flat_positions::<f32>();
    let mut rows = Vec::new();
    for isolation in ISOLATION_LEVELS {
        let adaptive = AdaptiveOptions::new(isolation);
        let native_refine = || -> Result<AdaptiveRefiner> {
            Refiner::new(&input.mesh, &options)?.refine_adaptive(adaptive, &[])
        };
        let osd_refine = || -> Result<osd::TopologyRefiner> {
            let mut r = osd::TopologyRefiner::new(&input.mesh, &options)?;
            r.refine_adaptive(adaptive, &[])?;
            Ok(r)
        };
        let (n, o) = (native_refine()?, osd_refine()?);
        let refused = |what: String| {
            Failure::Message(format!(
                "adaptive benchmark refused on {} (isolation {isolation}): {what}, so their times would not measure the same work",
                input.name
            ))
        };
        if n.max_level() != o.max_level() {
            return Err(refused(format!(
                "the engines refined {} and {} levels",
                n.max_level(),
                o.max_level()
            )));
        }
        let levels = native_levels(&n, &base)?;
        let reference = o.interpolate_all(3, &base)?;
        for (l, (a, b)) in levels.iter().zip(&reference).enumerate() {
            if let Some(d) = super::parallel::first_difference(a, b) {
                return Err(refused(format!("the positions of level {l} differ ({d})")));
            }
        }
        let vertices = levels[1..].iter().map(|l| l.len() / 3).sum();
        let row = |task: String, (native, osd): (f64, f64)| AdaptiveRow {
            isolation,
            max_level: n.max_level(),
            row: Row {
                input: input.name.clone(),
                scheme: options.scheme.to_string(),
                level: isolation,
                task,
                native,
                osd,
                vertices,
            },
        };
        let task = format!("adaptive topology (isolation {isolation})");
        progress(&format!("{} {}: {task}", input.name, options.scheme));
        rows.push(row(
            task,
            pool.install(|| {
                interleaved(
                    reps,
                    || drop(black_box(native_refine().expect("native"))),
                    || drop(black_box(osd_refine().expect("osd"))),
                )
            }),
        ));
        let task = format!("adaptive positions (f32, isolation {isolation})");
        progress(&format!("{} {}: {task}", input.name, options.scheme));
        if n.max_level() > 0 {
            rows.push(row(
                task,
                pool.install(|| {
                    interleaved(
                        reps,
                        || drop(black_box(native_levels(&n, &base).expect("native"))),
                        || drop(black_box(o.interpolate_all(3, &base).expect("osd"))),
                    )
                }),
            ));
        }
        if isolation == PATCH_ISOLATION {
            let limit = limit_rows(pool, input, (&n, &o), reps, locations, &mut progress, &row)?;
            rows.extend(limit);
        }
    }
    Ok(rows)
}

/// The limit-surface rows of `input` refined to [`PATCH_ISOLATION`] by both
/// engines (`n`, `o`), with OpenSubdiv's default patch options (Gregory
/// basis end caps): "patch table + PatchMap" (`AdaptiveRefiner::patch_table`
/// and `PatchMap::new` against `PatchTableFactory::Create` and `PatchMap`'s
/// constructor) and "limit evaluation (N locations, positions + first
/// derivatives)" at pseudo-random (ptex face, u, v) off the holes, both
/// engines reading the same points (every level's vertices and the local
/// points, computed once, not timed). The tables must be identical and the
/// values agree to 1e-9 of the mesh's size before timing, or the rows are
/// refused; a table or a basis the native engine does not build yet (none
/// with these options) leaves both rows or the second out.
fn limit_rows(
    pool: &rayon::ThreadPool,
    input: &BenchShape,
    (n, o): (&AdaptiveRefiner, &osd::TopologyRefiner),
    reps: usize,
    count: usize,
    progress: &mut impl FnMut(&str),
    row: &dyn Fn(String, (f64, f64)) -> AdaptiveRow,
) -> Result<Vec<AdaptiveRow>, Failure> {
    let po = PatchOptions::new().max_isolation(PATCH_ISOLATION);
    let table = match n.patch_table(&po, &[]) {
        Ok(t) => t,
        Err(subdiv::Error::NotYetSupported(_)) => return Ok(Vec::new()),
        Err(e) => return Err(e.into()),
    };
    let theirs = o.patch_table(&po, &[])?;
    let refused = |what: &str| {
        Failure::Message(format!(
            "limit benchmark refused on {}: {what}, so their times would not measure the same work",
            input.name
        ))
    };
    if table != *theirs.table() {
        return Err(refused("the patch tables differ"));
    }
    let mut rows = Vec::new();
    let task = format!("patch table + PatchMap (isolation {PATCH_ISOLATION})");
    progress(&format!("{} {}: {task}", input.name, input.options.scheme));
    rows.push(row(
        task,
        pool.install(|| {
            interleaved(
                reps,
                || {
                    let t = n.patch_table(&po, &[]).expect("native");
                    drop(black_box(PatchMap::new(&t)));
                },
                || o.build_patch_table(&po, &[]).expect("osd"),
            )
        }),
    ));
    let base = input.mesh.flat_positions::<f64>();
    let points = n.patch_points(&table, 3, &base)?;
    let map = PatchMap::new(&table);
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let faces = table.ptex_faces.max(1) as f64;
    let mut locations = Vec::with_capacity(count);
    while locations.len() < count && table.ptex_faces > 0 {
        let location = ((next() * faces) as u32, next(), next());
        if map.find_patch(location.0, location.1, location.2).is_some() {
            locations.push(location);
        }
    }
    let size = 1.0 + base.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let count = locations.len();
    let task = format!(
        "limit evaluation ({count} locations, positions + first derivatives, isolation {PATCH_ISOLATION})"
    );
    progress(&format!("{} {}: {task}", input.name, input.options.scheme));
    // The map built once, as OpenSubdiv's is with its table.
    let times = pool.install(|| {
        evaluation_times(
            reps,
            1e-9 * size,
            &refused,
            |out| evaluate_native(&map, &table, &points, &locations, out),
            |out| theirs.evaluate_points_into(&points, 3, &locations, Derivatives::First, out),
        )
    });
    // A basis not native (none with these options): no evaluation rows.
    let Some(times) = times? else {
        return Ok(rows);
    };
    rows.push(row(task, times));
    // The same locations in f32, against OpenSubdiv's CPU evaluator
    // (`Osd::CpuEvaluator::EvalPatches`, float only): the points rounded to
    // f32 once, not timed; each side finds its patches in the timed call
    // and writes into the outputs of its call before (as `EvalPatches`
    // writes into its caller's buffers).
    let points32: Vec<f32> = points.iter().map(|&x| x as f32).collect();
    let cpu = theirs.cpu_patch_table()?;
    let task = format!(
        "limit evaluation in f32 against EvalPatches ({count} locations, positions + first derivatives, isolation {PATCH_ISOLATION})"
    );
    progress(&format!("{} {}: {task}", input.name, input.options.scheme));
    let times = pool.install(|| {
        evaluation_times(
            reps,
            F32_AGREEMENT * size,
            &refused,
            |out| evaluate_native(&map, &table, &points32, &locations, out),
            |out| cpu.evaluate_into(&points32, 3, &locations, Derivatives::First, out),
        )
    });
    match times? {
        Some(times) => rows.push(row(task, times)),
        None => return Err(refused("the f32 evaluation has no native basis")),
    }
    Ok(rows)
}

/// The native evaluation of the benchmark's rows: positions and first
/// derivatives at `locations`, OpenSubdiv's way, into `out`.
fn evaluate_native<R: subdiv::Real>(
    map: &PatchMap,
    table: &patches::PatchTable,
    points: &[R],
    locations: &[(u32, f64, f64)],
    out: &mut SurfaceSamples<R>,
) -> Result<()> {
    patches::evaluate_data_into(
        patches::Evaluation::OpenSubdiv,
        map,
        table,
        patches::PatchData::Vertex,
        points,
        3,
        locations,
        Derivatives::First,
        out,
    )
}

/// The native and OpenSubdiv times (interleaved medians of `reps`) of one
/// limit evaluation, each side writing into its own outputs of the call
/// before (a program evaluating again and again keeps its buffers), after
/// checking that their values (positions and first derivatives) are at
/// most `bound` apart; `None` when the native engine has no basis for a
/// patch (`NotYetSupported`), `refused`'s error when the values differ.
fn evaluation_times<R: subdiv::Real>(
    reps: usize,
    bound: f64,
    refused: &dyn Fn(&str) -> Failure,
    native: impl Fn(&mut SurfaceSamples<R>) -> Result<()>,
    osd: impl Fn(&mut SurfaceSamples<R>) -> Result<()>,
) -> std::result::Result<Option<(f64, f64)>, Failure> {
    let mut mine = SurfaceSamples::default();
    match native(&mut mine) {
        Ok(()) => {}
        Err(subdiv::Error::NotYetSupported(_)) => return Ok(None),
        Err(e) => return Err(e.into()),
    }
    let mut osds = SurfaceSamples::default();
    osd(&mut osds)?;
    for (a, b) in [
        (&mine.values.point, &osds.values.point),
        (&mine.values.du, &osds.values.du),
        (&mine.values.dv, &osds.values.dv),
    ] {
        let apart = |x: R, y: R| (x.to_f64() - y.to_f64()).abs() > bound;
        if a.len() != b.len() || a.iter().zip(b).any(|(&x, &y)| apart(x, y)) {
            return Err(refused(&format!(
                "the limit surfaces evaluated in {} differ by more than {bound:e}",
                R::PRECISION
            )));
        }
    }
    Ok(Some(interleaved(
        reps,
        || {
            native(&mut mine).expect("native");
            black_box(&mine);
        },
        || {
            osd(&mut osds).expect("osd");
            black_box(&osds);
        },
    )))
}

/// How far apart (times the mesh's size) the two engines' values in `f32`
/// may be: OpenSubdiv's evaluator weighs and sums in `f32`, the native
/// engine in `f64` rounded once, so they differ by `f32` rounding of the
/// sums (derivatives of deep patches scaled up by 2^depth with it). The
/// benchmark's tori differ by up to 3.4e-6 (`tests/osd_evaluator.rs`).
const F32_AGREEMENT: f64 = 1e-5;
