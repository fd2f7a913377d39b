//! The adaptive section of `subdiv bench`: feature-adaptive refinement
//! (`Refiner::refine_adaptive` against OpenSubdiv's `RefineAdaptive`) at
//! isolation levels 3 and 6.

use super::results::{AdaptiveRow, Row};
use super::timing::interleaved;
use crate::Failure;
use std::hint::black_box;
use subdiv::options::{AdaptiveOptions, BoundaryInterpolation, FVarLinearInterpolation, Options};
use subdiv::refiner::{AdaptiveRefiner, Refiner};
use subdiv::shapes::BenchShape;
use subdiv::{Result, osd, shapes};

/// The isolation levels of the adaptive rows.
pub const ISOLATION_LEVELS: [u32; 2] = [3, 6];

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

/// Rows of `input` at each of [`ISOLATION_LEVELS`]: "adaptive topology
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
    }
    Ok(rows)
}
