//! The in-process comparisons of `subdiv bench`.

use super::adaptive::adaptive_rows;
use super::parallel::{
    PARALLEL_COUNT, PARALLEL_LEVEL, deformed_frames, frames_row, many_meshes, meshes_row,
};
use super::results::{AloneRow, BenchReport, Row};
use super::timing::{interleaved, machine_description, measure_bandwidth};
use crate::Failure;
use std::hint::black_box;
use subdiv::options::UniformOptions;
use subdiv::shapes::BenchShape;
use subdiv::{Mesh, Result, osd, refiner};

/// Runs every comparison on `inputs` (the parallel-use section too, when
/// there are some), then the adaptive rows on `adaptive_inputs`, then the
/// tessellation rows on `tessellation_inputs`; `progress` is called once
/// per step with a description.
pub fn run(
    inputs: &[BenchShape],
    adaptive_inputs: &[BenchShape],
    tessellation_inputs: &[&BenchShape],
    quick: bool,
    threads: usize,
    mut progress: impl FnMut(&str),
) -> Result<BenchReport, Failure> {
    // Each repetition runs both engines twice (see `interleaved`).
    let reps = if quick { 3 } else { 5 };
    let mut rows = Vec::new();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.max(1))
        .build()
        .map_err(|e| Failure::Message(format!("cannot start {threads} threads: {e}")))?;
    let bandwidth = pool.install(measure_bandwidth);
    let mut stencil_bandwidth = None;
    let mut osd_alone = Vec::new();
    for input in inputs {
        let options = input.options;
        let base = input.mesh.flat_positions::<f32>();
        // Meshes with face-varying channels (UVs) have them refined too, as
        // a renderer's pipeline does.
        let uvs = !input.mesh.fvar_channels.is_empty();
        let combined = if uvs {
            "topology + positions + UVs"
        } else {
            "topology + positions"
        };
        let label = |task: &str, level: u32| {
            format!("{} {} L{level}: {task}", input.name, input.options.scheme)
        };
        for level in 1..=input.max_level {
            progress(&label(combined, level));
            let uniform = UniformOptions::new(level);
            let mut vertices = 0;
            let opensubdiv = || {
                let mut r = osd::TopologyRefiner::new(&input.mesh, &options).expect("osd refiner");
                r.refine_uniform(uniform).expect("osd refinement");
                black_box(r.interpolate_all(3, &base).expect("osd positions"));
                black_box(osd_uvs(&r, &input.mesh, level));
            };
            let (native, osd) = pool.install(|| {
                interleaved(
                    reps,
                    || {
                        let mut r =
                            refiner::Refiner::new(&input.mesh, &options).expect("native refiner");
                        r.refine_uniform(uniform).expect("native refinement");
                        let p = r.interpolate_all(3, &base).expect("native positions");
                        vertices = p.last().map_or(0, |l| l.len() / 3);
                        black_box(p);
                        black_box(native_uvs(&r, &input.mesh, level));
                    },
                    opensubdiv,
                )
            });
            if level == input.max_level {
                progress(&label("OpenSubdiv alone", level));
                // The same warm-up and repetitions as above, with nothing
                // run in the native engine's place.
                let alone = pool.install(|| interleaved(reps, opensubdiv, || {}).0);
                osd_alone.push(AloneRow {
                    input: input.name.clone(),
                    scheme: input.options.scheme.to_string(),
                    level,
                    alone,
                    interleaved: osd,
                });
            }
            rows.push(Row {
                input: input.name.clone(),
                scheme: input.options.scheme.to_string(),
                level,
                task: combined.into(),
                native,
                osd,
                vertices,
            });
        }
        // Separate tasks at the deepest level.
        let level = input.max_level;
        let uniform = UniformOptions::new(level);
        let mut n = refiner::Refiner::new(&input.mesh, &options)?;
        n.refine_uniform(uniform)?;
        let mut o = osd::TopologyRefiner::new(&input.mesh, &options)?;
        o.refine_uniform(uniform)?;
        let vertices = n.level_counts(level)?.vertices;
        let mut push = |task: &str, (native, osd): (f64, f64)| {
            rows.push(Row {
                input: input.name.clone(),
                scheme: input.options.scheme.to_string(),
                level,
                task: task.into(),
                native,
                osd,
                vertices,
            })
        };
        progress(&label("base topology", level));
        push(
            "base topology",
            pool.install(|| {
                interleaved(
                    reps,
                    || {
                        drop(black_box(
                            refiner::Refiner::new(&input.mesh, &options).expect("native"),
                        ))
                    },
                    || {
                        drop(black_box(
                            osd::TopologyRefiner::new(&input.mesh, &options).expect("osd"),
                        ))
                    },
                )
            }),
        );
        progress(&label("topology refinement", level));
        push(
            "topology refinement",
            pool.install(|| {
                interleaved(
                    reps,
                    || {
                        let mut r = refiner::Refiner::new(&input.mesh, &options).expect("native");
                        r.refine_uniform(uniform).expect("native");
                        black_box(r);
                    },
                    || {
                        let mut r = osd::TopologyRefiner::new(&input.mesh, &options).expect("osd");
                        r.refine_uniform(uniform).expect("osd");
                        black_box(r);
                    },
                )
            }),
        );
        progress(&label("positions (f32)", level));
        push(
            "positions (f32)",
            pool.install(|| {
                interleaved(
                    reps,
                    || drop(black_box(n.interpolate_all(3, &base).expect("native"))),
                    || drop(black_box(o.interpolate_all(3, &base).expect("osd"))),
                )
            }),
        );
        if uvs {
            progress(&label("UVs (f32)", level));
            push(
                "UVs (f32)",
                pool.install(|| {
                    interleaved(
                        reps,
                        || drop(black_box(native_uvs(&n, &input.mesh, level))),
                        || drop(black_box(osd_uvs(&o, &input.mesh, level))),
                    )
                }),
            );
        }
        progress(&label("limit (f32)", level));
        let full = uniform.full_topology(true);
        let mut nf = refiner::Refiner::new(&input.mesh, &options)?;
        nf.refine_uniform(full)?;
        let mut of = osd::TopologyRefiner::new(&input.mesh, &options)?;
        of.refine_uniform(full)?;
        let last = nf.interpolate_all(3, &base)?.pop().unwrap_or_default();
        push(
            "limit (f32)",
            pool.install(|| {
                interleaved(
                    reps,
                    || drop(black_box(nf.limit(3, &last).expect("native"))),
                    || drop(black_box(of.limit(3, &last).expect("osd"))),
                )
            }),
        );
        // Both tables in f32: OpenSubdiv's evaluator builds its float
        // StencilTableFactory's table, the one it applies.
        progress(&label("stencil table (f32)", level));
        push(
            "stencil table (f32)",
            pool.install(|| {
                interleaved(
                    reps.min(3),
                    || drop(black_box(n.stencil_table_f32().expect("native"))),
                    || drop(black_box(osd::StencilEvaluator::new(&o).expect("osd"))),
                )
            }),
        );
        progress(&label("stencil apply", level));
        // The same stencils on both sides: the native table is built in f32
        // as OpenSubdiv's float StencilTableFactory builds the one its
        // evaluator applies (same rows, same weights, so the results are equal
        // bit for bit: tests/stencil_apply.rs), and both are applied to the
        // same f32 frame, width 3, in the same thread pool.
        let table = n.stencil_table_f32()?;
        let evaluator = osd::StencilEvaluator::new(&o)?;
        let mut out_n = vec![0f32; table.len() * 3];
        let mut out_o = vec![0f32; evaluator.len() * 3];
        let times = pool.install(|| {
            interleaved(
                reps * 5,
                || table.apply_into(3, &base, &mut out_n).expect("native"),
                || evaluator.eval_into(3, &base, &mut out_o).expect("osd"),
            )
        });
        // Bytes each pass has to move, counted once: per term a 4-byte index
        // and a 4-byte weight; per stencil its offset (native) or size
        // (OpenSubdiv's CpuEvalStencils reads sizes only); the source frame
        // once (it stays in cache while the terms stream by: counting it per
        // term would inflate the rate) and the results. The 16-byte-aligned
        // copy of the sources the native pass makes is extra work, not
        // counted.
        let frame = (base.len() + out_n.len()) * 4;
        let bytes = (table.term_count() * 8 + (table.len() + 1) * 4 + frame) as f64;
        let osd_bytes = (table.term_count() * 8 + evaluator.len() * 4 + frame) as f64;
        let rates = (bytes / times.0, osd_bytes / times.1);
        // BenchReport the input where the native pass moves the fewest bytes per
        // second, so that the bandwidth target holds for every input.
        if stencil_bandwidth.is_none_or(|(slowest, _)| rates.0 < slowest) {
            stencil_bandwidth = Some(rates);
        }
        push("stencil apply (f32)", times);
        progress(&label("factorized stencil apply", level));
        let factorized = n.factorized_stencils::<f32>()?;
        let mut out_f = vec![0f32; factorized.len() * 3];
        let times = pool.install(|| {
            interleaved(
                reps * 5,
                || factorized.apply_into(3, &base, &mut out_f).expect("native"),
                || evaluator.eval_into(3, &base, &mut out_o).expect("osd"),
            )
        });
        push("factorized stencil apply (f32)", times);
    }
    // After the uniform rows, so that those run as they did before the
    // adaptive rows existed.
    let mut adaptive = Vec::new();
    for input in adaptive_inputs {
        let locations = super::adaptive::LOCATIONS / if quick { 10 } else { 1 };
        adaptive.extend(adaptive_rows(&pool, input, reps, locations, &mut progress)?);
    }
    let mut tessellation = Vec::new();
    for &input in tessellation_inputs {
        tessellation.extend(super::tessellation::tessellation_rows(
            &pool,
            input,
            reps,
            &mut progress,
        )?);
    }
    let mut parallel = Vec::new();
    if let Some(first) = inputs.first() {
        progress(&format!(
            "parallel use: {PARALLEL_COUNT} frames of {}",
            first.name
        ));
        let frames = deformed_frames(&first.mesh, PARALLEL_COUNT);
        parallel.push(frames_row(&pool, first, &frames, PARALLEL_LEVEL, reps)?);
    }
    if !inputs.is_empty() {
        progress(&format!("parallel use: {PARALLEL_COUNT} meshes"));
        parallel.push(meshes_row(
            &pool,
            &many_meshes(PARALLEL_COUNT, quick),
            PARALLEL_LEVEL,
            reps,
        )?);
    }
    Ok(BenchReport {
        date: crate::date::today(),
        machine: machine_description(),
        threads,
        bandwidth,
        rows,
        stencil_bandwidth,
        parallel,
        osd_alone,
        adaptive,
        tessellation,
        whole_process: Vec::new(),
        obj_writer: None,
        obj_reader: Vec::new(),
        skipped: Vec::new(),
    })
}

/// Every face-varying channel of `mesh` refined to `level` in f32, level by
/// level, with `step` — either engine's `interpolate_face_varying`.
fn uvs(
    mesh: &Mesh,
    level: u32,
    step: impl Fn(usize, u32, usize, &[f32]) -> Result<Vec<f32>>,
) -> Vec<Vec<f32>> {
    let mut out = Vec::new();
    for (c, ch) in mesh.fvar_channels.iter().enumerate() {
        let mut values: Vec<f32> = ch.values.iter().map(|&x| x as f32).collect();
        for l in 1..=level {
            values = step(c, l, ch.width, &values).expect("UVs");
        }
        out.push(values);
    }
    out
}

/// Every face-varying channel of `mesh` refined to `level` in f32 by the
/// native engine's whole-refinement call (the last level kept, in a table
/// from its pool), the result [`uvs`] gives level by level.
fn native_uvs(r: &refiner::Refiner, mesh: &Mesh, level: u32) -> Vec<subdiv::Values<f32>> {
    debug_assert_eq!(level, r.max_level());
    mesh.fvar_channels
        .iter()
        .enumerate()
        .map(|(c, ch)| {
            let base: Vec<f32> = ch.values.iter().map(|&x| x as f32).collect();
            r.interpolate_face_varying_last(c, ch.width, &base)
                .expect("UVs")
        })
        .collect()
}

/// [`uvs`] by OpenSubdiv.
fn osd_uvs(r: &osd::TopologyRefiner, mesh: &Mesh, level: u32) -> Vec<Vec<f32>> {
    uvs(mesh, level, |c, l, w, v| {
        r.interpolate_face_varying(c, l, w, v)
    })
}
