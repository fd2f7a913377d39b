//! Side-by-side benchmarks of the native engine and OpenSubdiv, measured in
//! the same process and the same run (interleaved repetitions, medians), as
//! `subdiv bench` prints and writes them.

use crate::mesh::Mesh;
use crate::options::{Options, Scheme, UniformOptions};
use crate::topology::Table;
use crate::{Result, osd, refiner, shapes};
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::Instant;

/// One input of the benchmark: a mesh and the scheme to refine it with.
#[derive(Debug, Clone)]
pub struct BenchInput {
    /// Short name.
    pub name: String,
    /// The mesh.
    pub mesh: Mesh,
    /// The subdivision scheme.
    pub scheme: Scheme,
    /// Deepest level to refine.
    pub max_level: u32,
}

/// The default inputs: a 100×100 quad torus, an 80×80 torus of alternating
/// quads and triangle pairs, a 100×50 triangle torus (Catmull-Clark and Loop)
/// and a 1000×1000 quad grid refined one level. `quick` shrinks them.
pub fn default_inputs(quick: bool) -> Vec<BenchInput> {
    let d = if quick { 4 } else { 1 };
    let input = |name: &str, mesh: Mesh, scheme: Scheme, max_level: u32| BenchInput {
        name: name.to_string(),
        mesh,
        scheme,
        max_level,
    };
    let mut grid = shapes::grid(1000 / d, 1000 / d);
    grid.fvar_channels.clear();
    vec![
        input(
            &format!("torus {0}x{0} quads", 100 / d),
            shapes::torus(100 / d, 100 / d),
            Scheme::Catmark,
            4,
        ),
        input(
            &format!("torus {0}x{0} mixed", 80 / d),
            shapes::torus_mixed(80 / d, 80 / d),
            Scheme::Catmark,
            4,
        ),
        input(
            &format!("torus {}x{} triangles", 100 / d, 50 / d),
            shapes::torus_triangles(100 / d, 50 / d),
            Scheme::Catmark,
            4,
        ),
        input(
            &format!("torus {}x{} triangles", 100 / d, 50 / d),
            shapes::torus_triangles(100 / d, 50 / d),
            Scheme::Loop,
            4,
        ),
        input(
            &format!("grid {0}x{0} quads", 1000 / d),
            grid,
            Scheme::Catmark,
            1,
        ),
    ]
}

/// One comparison: the same work done by both engines.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Row {
    /// The input.
    pub input: String,
    /// The scheme.
    pub scheme: String,
    /// The level.
    pub level: u32,
    /// What was measured.
    pub task: String,
    /// Median native time, seconds.
    pub native: f64,
    /// Median OpenSubdiv time, seconds.
    pub osd: f64,
    /// Vertices produced (for rates).
    pub vertices: usize,
}

impl Row {
    /// OpenSubdiv's time over the native time (above 1: native is faster).
    pub fn speedup(&self) -> f64 {
        self.osd / self.native
    }
}

/// OpenSubdiv's deepest "topology + positions" time measured twice: with no
/// native run in between, and interleaved with the native engine (the time
/// in [`Report::rows`]). Both engines share the process's C allocator, so
/// each can leave the other's heap warmer or colder; the pair shows whether
/// the reference in the table runs as it does on its own.
#[derive(Debug, Clone, serde::Serialize)]
pub struct AloneRow {
    /// The input.
    pub input: String,
    /// The scheme.
    pub scheme: String,
    /// The level.
    pub level: u32,
    /// Median OpenSubdiv time alone, seconds.
    pub alone: f64,
    /// Median OpenSubdiv time interleaved with the native engine, seconds.
    pub interleaved: f64,
}

/// A whole benchmark run.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Report {
    /// When and where it ran.
    pub machine: String,
    /// Native threads used.
    pub threads: usize,
    /// Memory copy bandwidth measured with `threads` threads, bytes per
    /// second.
    pub bandwidth: f64,
    /// All comparisons.
    pub rows: Vec<Row>,
    /// Stencil apply: native and OpenSubdiv bytes moved per second, on the
    /// input where the native rate is lowest.
    pub stencil_bandwidth: Option<(f64, f64)>,
    /// Parallel use of the library: many frames of one topology
    /// ([`frames_row`]) and many meshes ([`meshes_row`]), both engines over
    /// the same pool of `threads` threads.
    pub parallel: Vec<ParallelRow>,
    /// OpenSubdiv alone against OpenSubdiv interleaved, per input.
    pub osd_alone: Vec<AloneRow>,
}

/// One comparison of the parallel-use section.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ParallelRow {
    /// What the batch is made of: "frames" or "meshes".
    pub unit: String,
    /// How many frames or meshes the batch has.
    pub count: usize,
    /// The times of the whole batch (`vertices` counts every frame's or
    /// mesh's refined vertices).
    #[serde(flatten)]
    pub row: Row,
}

impl ParallelRow {
    /// Frames or meshes per second: natively, and in OpenSubdiv.
    pub fn rates(&self) -> (f64, f64) {
        let n = self.count as f64;
        (n / self.row.native, n / self.row.osd)
    }
}

/// Runs `a` and `b` alternately (the order swapping every repetition) and
/// returns their median times in seconds.
///
/// Every timed run comes right after an untimed run of the same closure, as
/// criterion's warm-up does: both engines share this process's allocator,
/// and without it each engine would be timed in the heap the other just left
/// (OpenSubdiv's frees trim the heap the native engine then faults in again,
/// and the reverse), which measures their interaction more than either. The
/// order still alternates, so the drift of this machine cancels out.
pub fn interleaved(reps: usize, mut a: impl FnMut(), mut b: impl FnMut()) -> (f64, f64) {
    let (mut ta, mut tb) = (Vec::with_capacity(reps), Vec::with_capacity(reps));
    for i in 0..reps.max(1) {
        let time = |f: &mut dyn FnMut()| {
            f();
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64()
        };
        if i % 2 == 0 {
            ta.push(time(&mut a));
            tb.push(time(&mut b));
        } else {
            tb.push(time(&mut b));
            ta.push(time(&mut a));
        }
    }
    (median(&mut ta), median(&mut tb))
}

/// The median wall time of one program run by [`interleaved_processes`],
/// and the peak memory it reported.
#[derive(Debug, Clone, PartialEq)]
pub struct ProcessRun {
    /// Median seconds from start to exit.
    pub seconds: f64,
    /// The last `peak_memory_bytes N` line the program wrote to standard
    /// error (`subdiv refine --peak-memory`, the C++ driver), or 0.
    pub peak_bytes: u64,
}

/// Runs whole programs `reps` times each, interleaved: every repetition runs
/// each program once, starting one further along the list each time, so that
/// the machine's drift over the minutes falls on all of them alike. Returns
/// each program's median time and reported peak memory, in the order given.
/// A program that cannot start or exits unsuccessfully is an error naming it.
pub fn interleaved_processes(
    programs: &mut [(String, std::process::Command)],
    reps: usize,
) -> Result<Vec<ProcessRun>> {
    let count = programs.len();
    let mut times = vec![Vec::with_capacity(reps); count];
    let mut peaks = vec![0u64; count];
    for rep in 0..reps.max(1) {
        for k in 0..count {
            let i = (rep + k) % count;
            let (name, command) = &mut programs[i];
            let start = Instant::now();
            let out = command.output().map_err(|e| {
                crate::Error::InvalidArgument(format!("{name} could not start: {e}"))
            })?;
            let elapsed = start.elapsed().as_secs_f64();
            if !out.status.success() {
                return Err(crate::Error::InvalidArgument(format!(
                    "{name} failed ({})",
                    out.status
                )));
            }
            times[i].push(elapsed);
            if let Some(v) = String::from_utf8_lossy(&out.stderr)
                .lines()
                .find_map(|l| l.strip_prefix("peak_memory_bytes "))
            {
                peaks[i] = v.trim().parse().unwrap_or(0);
            }
        }
    }
    Ok(times
        .iter_mut()
        .zip(peaks)
        .map(|(t, peak_bytes)| ProcessRun {
            seconds: median(t),
            peak_bytes,
        })
        .collect())
}

/// A named series of (level, native seconds, OpenSubdiv seconds).
type Series = (String, Vec<(u32, f64, f64)>);

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

/// This machine's memory bandwidth: the best of a few copies of a 256 MiB
/// buffer, counting bytes read plus bytes written, split between the threads
/// of the current rayon pool (run it in the pool whose rates it is compared
/// with: one thread cannot draw all of a machine's bandwidth).
pub fn measure_bandwidth() -> f64 {
    use rayon::prelude::*;
    let n = 32 << 20; // 32 Mi f64 = 256 MiB
    let src = vec![1.0f64; n];
    let mut dst = vec![0.0f64; n];
    let part = n.div_ceil(rayon::current_num_threads());
    let mut best = f64::MAX;
    for _ in 0..5 {
        let t = Instant::now();
        dst.par_chunks_mut(part)
            .zip(src.par_chunks(part))
            .for_each(|(d, s)| d.copy_from_slice(black_box(s)));
        best = best.min(t.elapsed().as_secs_f64());
        black_box(&dst);
    }
    (2 * n * 8) as f64 / best
}

/// Runs every comparison on `inputs`; `progress` is called once per step
/// with a description.
pub fn run(
    inputs: &[BenchInput],
    quick: bool,
    threads: usize,
    mut progress: impl FnMut(&str),
) -> Result<Report> {
    // Each repetition runs both engines twice (see `interleaved`).
    let reps = if quick { 3 } else { 5 };
    let mut rows = Vec::new();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.max(1))
        .build()
        .map_err(|e| {
            crate::Error::InvalidArgument(format!("cannot start {threads} threads: {e}"))
        })?;
    let bandwidth = pool.install(measure_bandwidth);
    let mut stencil_bandwidth = None;
    let mut osd_alone = Vec::new();
    for input in inputs {
        let options = Options::default().with_scheme(input.scheme);
        let base = input.mesh.flat_positions::<f32>();
        let label =
            |task: &str, level: u32| format!("{} {} L{level}: {task}", input.name, input.scheme);
        for level in 1..=input.max_level {
            progress(&label("topology + positions", level));
            let uniform = UniformOptions::new(level);
            let mut vertices = 0;
            let opensubdiv = || {
                let mut r = osd::Refiner::new(&input.mesh, &options).expect("osd refiner");
                r.refine_uniform(uniform).expect("osd refinement");
                black_box(r.interpolate_all(3, &base).expect("osd positions"));
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
                    scheme: input.scheme.to_string(),
                    level,
                    alone,
                    interleaved: osd,
                });
            }
            rows.push(Row {
                input: input.name.clone(),
                scheme: input.scheme.to_string(),
                level,
                task: "topology + positions".into(),
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
        let mut o = osd::Refiner::new(&input.mesh, &options)?;
        o.refine_uniform(uniform)?;
        let vertices = n.internal_level(level)?.vertex_count;
        let mut push = |task: &str, (native, osd): (f64, f64)| {
            rows.push(Row {
                input: input.name.clone(),
                scheme: input.scheme.to_string(),
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
                            osd::Refiner::new(&input.mesh, &options).expect("osd"),
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
                        let mut r = osd::Refiner::new(&input.mesh, &options).expect("osd");
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
        progress(&label("limit (f32)", level));
        let full = uniform.full_topology(true);
        let mut nf = refiner::Refiner::new(&input.mesh, &options)?;
        nf.refine_uniform(full)?;
        let mut of = osd::Refiner::new(&input.mesh, &options)?;
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
        progress(&label("stencil table", level));
        push(
            "stencil table",
            pool.install(|| {
                interleaved(
                    reps.min(3),
                    || drop(black_box(n.stencil_table().expect("native"))),
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
        // Report the input where the native pass moves the fewest bytes per
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
    let mut parallel = Vec::new();
    if let Some(first) = inputs.first() {
        progress(&format!(
            "parallel use: {PARALLEL_COUNT} frames of {}",
            first.name
        ));
        let frames = deformed_frames(&first.mesh, PARALLEL_COUNT);
        parallel.push(frames_row(&pool, first, &frames, PARALLEL_LEVEL, reps)?);
    }
    progress(&format!("parallel use: {PARALLEL_COUNT} meshes"));
    parallel.push(meshes_row(
        &pool,
        &many_meshes(PARALLEL_COUNT, quick),
        PARALLEL_LEVEL,
        reps,
    )?);
    Ok(Report {
        machine: machine_description(),
        threads,
        bandwidth,
        rows,
        stencil_bandwidth,
        parallel,
        osd_alone,
    })
}

/// Frames and meshes in the parallel-use section of [`run`].
pub const PARALLEL_COUNT: usize = 16;

/// The level the parallel-use section refines to.
pub const PARALLEL_LEVEL: u32 = 3;

/// `count` frames of animated positions for `mesh` (flat `f32`, 3 per
/// vertex): each frame twists the mesh about the z axis and runs a wave
/// along it, with amplitudes relative to its size and a phase that advances
/// frame by frame.
pub fn deformed_frames(mesh: &Mesh, count: usize) -> Vec<Vec<f32>> {
    let size = crate::compare::bbox_diagonal(&mesh.positions).max(f64::MIN_POSITIVE);
    (0..count)
        .map(|k| {
            let phase = std::f64::consts::TAU * (k as f64 + 1.0) / count as f64;
            mesh.positions
                .iter()
                .flat_map(|p| {
                    let angle = 0.5 * phase.sin() * p.z / size;
                    let (s, c) = angle.sin_cos();
                    let wave =
                        0.02 * size * (4.0 * p.x / size * std::f64::consts::TAU + phase).sin();
                    [
                        (c * p.x - s * p.y) as f32,
                        (s * p.x + c * p.y) as f32,
                        (p.z + wave) as f32,
                    ]
                })
                .collect()
        })
        .collect()
}

/// `count` different meshes for the parallel-use section: tori of growing
/// size, in turn quads (Catmull-Clark), quads and triangle pairs
/// (Catmull-Clark) and triangles (Loop); `quick` shrinks them.
pub fn many_meshes(count: usize, quick: bool) -> Vec<BenchInput> {
    let d = if quick { 4 } else { 1 };
    (0..count as u32)
        .map(|i| {
            let (nu, nv) = ((24 + 6 * i) / d, (16 + 4 * i) / d);
            let (kind, mesh, scheme) = match i % 3 {
                0 => ("quads", shapes::torus(nu, nv), Scheme::Catmark),
                1 => ("mixed", shapes::torus_mixed(nu, nv), Scheme::Catmark),
                _ => ("triangles", shapes::torus_triangles(nu, nv), Scheme::Loop),
            };
            BenchInput {
                name: format!("torus {nu}x{nv} {kind}"),
                mesh,
                scheme,
                max_level: PARALLEL_LEVEL,
            }
        })
        .collect()
}

/// The first value where two results differ, or their lengths, for errors.
fn first_difference(native: &[f32], osd: &[f32]) -> Option<String> {
    if native.len() != osd.len() {
        return Some(format!(
            "{} values natively, {} in OpenSubdiv",
            native.len(),
            osd.len()
        ));
    }
    native
        .iter()
        .zip(osd)
        .position(|(a, b)| a.to_bits() != b.to_bits())
        .map(|i| {
            format!(
                "value {i}: {} natively, {} in OpenSubdiv",
                native[i], osd[i]
            )
        })
}

fn differ(what: &str, difference: String) -> crate::Error {
    crate::Error::InvalidArgument(format!(
        "parallel-use benchmark refused: the engines' {what} differ ({difference}), so their times would not measure the same work"
    ))
}

/// [`interleaved`] over a batch: each side maps every job with rayon inside
/// `pool` and collects the results (each engine's own buffer type).
fn interleaved_batches<J: Sync, A: Send, B: Send>(
    pool: &rayon::ThreadPool,
    reps: usize,
    jobs: &[J],
    native: impl Fn(&J) -> A + Sync,
    osd: impl Fn(&J) -> B + Sync,
) -> (f64, f64) {
    use rayon::prelude::*;
    pool.install(|| {
        interleaved(
            reps,
            || drop(black_box(jobs.par_iter().map(&native).collect::<Vec<A>>())),
            || drop(black_box(jobs.par_iter().map(&osd).collect::<Vec<B>>())),
        )
    })
}

/// Many frames of one topology: both engines refine `input`'s topology to
/// `level` once (not timed), check that the first frame's refined positions
/// are equal bit for bit, then interpolate every frame to the last level
/// (`interpolate_last`, `f32`), the frames spread over `pool` with rayon
/// (`par_iter`) for both engines: each one's `Refiner` is `Sync`, shared by
/// the threads, as a user animating a mesh would use it. Medians of `reps`
/// interleaved repetitions of the whole batch.
pub fn frames_row(
    pool: &rayon::ThreadPool,
    input: &BenchInput,
    frames: &[Vec<f32>],
    level: u32,
    reps: usize,
) -> Result<ParallelRow> {
    let options = Options::default().with_scheme(input.scheme);
    let uniform = UniformOptions::new(level);
    let mut n = refiner::Refiner::new(&input.mesh, &options)?;
    n.refine_uniform(uniform)?;
    let mut o = osd::Refiner::new(&input.mesh, &options)?;
    o.refine_uniform(uniform)?;
    if let Some(frame) = frames.first() {
        let (a, b) = (n.interpolate_last(3, frame)?, o.interpolate_last(3, frame)?);
        if let Some(d) = first_difference(&a, &b) {
            return Err(differ("positions of the first frame", d));
        }
    }
    let (native, osd) = interleaved_batches(
        pool,
        reps,
        frames,
        |f| n.interpolate_last(3, f).expect("native"),
        |f| o.interpolate_last(3, f).expect("osd"),
    );
    Ok(ParallelRow {
        unit: "frames".into(),
        count: frames.len(),
        row: Row {
            input: format!("{}, {} frames", input.name, frames.len()),
            scheme: input.scheme.to_string(),
            level,
            task: format!("frames ({}, level {level})", frames.len()),
            native,
            osd,
            vertices: frames.len() * n.internal_level(level)?.vertex_count,
        },
    })
}

/// Many meshes: each of `meshes` gets its own `Refiner`, refined to `level`
/// with its positions interpolated to the last level (`f32`), the meshes
/// spread over `pool` with rayon for both engines (OpenSubdiv's refiners are
/// independent objects; the bridge keeps its messages per thread). Every
/// mesh's result is checked equal bit for bit between the engines first (not
/// timed). Medians of `reps` interleaved repetitions of the whole batch.
pub fn meshes_row(
    pool: &rayon::ThreadPool,
    meshes: &[BenchInput],
    level: u32,
    reps: usize,
) -> Result<ParallelRow> {
    let uniform = UniformOptions::new(level);
    let jobs: Vec<(&Mesh, Options, Vec<f32>)> = meshes
        .iter()
        .map(|m| {
            (
                &m.mesh,
                Options::default().with_scheme(m.scheme),
                m.mesh.flat_positions::<f32>(),
            )
        })
        .collect();
    let native_one = |(mesh, options, base): &(&Mesh, Options, Vec<f32>)| -> Result<Table<f32>> {
        let mut r = refiner::Refiner::new(mesh, options)?;
        r.refine_uniform(uniform)?;
        r.interpolate_last(3, base)
    };
    let osd_one = |(mesh, options, base): &(&Mesh, Options, Vec<f32>)| -> Result<Vec<f32>> {
        let mut r = osd::Refiner::new(mesh, options)?;
        r.refine_uniform(uniform)?;
        r.interpolate_last(3, base)
    };
    let mut vertices = 0;
    for (job, input) in jobs.iter().zip(meshes) {
        let a = native_one(job)?;
        if let Some(d) = first_difference(&a, &osd_one(job)?) {
            return Err(differ(&format!("positions of {}", input.name), d));
        }
        vertices += a.len() / 3;
    }
    let (native, osd) = interleaved_batches(
        pool,
        reps,
        &jobs,
        |j| native_one(j).expect("native"),
        |j| osd_one(j).expect("osd"),
    );
    let mut schemes: Vec<String> = Vec::new();
    for m in meshes {
        let s = m.scheme.to_string();
        if !schemes.contains(&s) {
            schemes.push(s);
        }
    }
    let input = match (meshes.first(), meshes.last()) {
        (Some(a), Some(b)) if meshes.len() > 1 => {
            format!("{} meshes, {} to {}", meshes.len(), a.name, b.name)
        }
        (Some(a), _) => a.name.clone(),
        _ => "no meshes".into(),
    };
    Ok(ParallelRow {
        unit: "meshes".into(),
        count: meshes.len(),
        row: Row {
            input,
            scheme: schemes.join("+"),
            level,
            task: format!("meshes ({}, level {level})", meshes.len()),
            native,
            osd,
            vertices,
        },
    })
}

/// The date, processor and core count, for reports.
pub fn machine_description() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_string())
        })
        .unwrap_or_else(|| "unknown processor".into());
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    format!("{cpu}, {cores} cores, OpenSubdiv {}", osd::version())
}

impl Report {
    /// The report as a Markdown table.
    pub fn markdown(&self, date: &str) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "Measured {date} on {} ({} native thread(s)); memory bandwidth {:.1} GB/s (a copy on as many threads).\n",
            self.machine,
            self.threads,
            self.bandwidth / 1e9
        );
        let _ = writeln!(
            s,
            "| input | scheme | level | task | native ms | OpenSubdiv ms | speed-up |"
        );
        let _ = writeln!(s, "| --- | --- | ---: | --- | ---: | ---: | ---: |");
        for r in self.rows.iter().chain(self.parallel.iter().map(|p| &p.row)) {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {:.2} | {:.2} | {:.2}x |",
                r.input,
                r.scheme,
                r.level,
                r.task,
                r.native * 1e3,
                r.osd * 1e3,
                r.speedup()
            );
        }
        if let Some((n, o)) = self.stencil_bandwidth {
            let _ = writeln!(
                s,
                "\nStencil apply moves {:.1} GB/s natively ({:.0}% of the measured bandwidth) and {:.1} GB/s in OpenSubdiv.",
                n / 1e9,
                100.0 * n / self.bandwidth,
                o / 1e9
            );
        }
        if !self.osd_alone.is_empty() {
            let _ = writeln!(
                s,
                "\nOpenSubdiv's deepest topology + positions alone (back to back, no native run in between) and as measured above (interleaved with the native engine; both share the C allocator):"
            );
            for a in &self.osd_alone {
                let _ = writeln!(
                    s,
                    "- {} ({}, level {}): alone {:.1} ms, interleaved {:.1} ms",
                    a.input,
                    a.scheme,
                    a.level,
                    a.alone * 1e3,
                    a.interleaved * 1e3
                );
            }
        }
        if !self.parallel.is_empty() {
            let _ = writeln!(
                s,
                "\nParallel use ({} thread(s); each engine's batch spread over the same rayon pool: one shared refiner for the frames, one refiner per mesh; results checked equal bit for bit before timing):",
                self.threads
            );
            for p in &self.parallel {
                let (r, (rn, ro)) = (&p.row, p.rates());
                let _ = writeln!(
                    s,
                    "- {} ({}, level {}): native {:.1} ms ({:.0} {unit}/s), OpenSubdiv {:.1} ms ({:.0} {unit}/s), {:.2}x",
                    r.input,
                    r.scheme,
                    r.level,
                    r.native * 1e3,
                    rn,
                    r.osd * 1e3,
                    ro,
                    r.speedup(),
                    unit = p.unit,
                );
            }
        }
        s
    }

    /// An SVG line chart of "topology + positions" time per level, native
    /// against OpenSubdiv, one pair of lines per input.
    pub fn svg_time_per_level(&self) -> String {
        let series: Vec<Series> = {
            let mut out: Vec<Series> = Vec::new();
            for r in self
                .rows
                .iter()
                .filter(|r| r.task == "topology + positions")
            {
                let key = format!("{} {}", r.input, r.scheme);
                match out.iter_mut().find(|(k, _)| *k == key) {
                    Some((_, v)) => v.push((r.level, r.native, r.osd)),
                    None => out.push((key, vec![(r.level, r.native, r.osd)])),
                }
            }
            out
        };
        let max = self
            .rows
            .iter()
            .filter(|r| r.task == "topology + positions")
            .map(|r| r.native.max(r.osd))
            .fold(1e-6, f64::max);
        let (w, h, left, bottom) = (640.0, 360.0, 60.0, 40.0);
        let x = |l: u32| left + (l as f64 - 1.0) / 3.0 * (w - left - 20.0);
        let y = |t: f64| h - bottom - (t / max) * (h - bottom - 20.0);
        let colors = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e"];
        let mut s = format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="11">"#
        );
        let _ = write!(
            s,
            r#"<rect width="{w}" height="{h}" fill="white"/><line x1="{left}" y1="{}" x2="{}" y2="{}" stroke="black"/><line x1="{left}" y1="20" x2="{left}" y2="{}" stroke="black"/>"#,
            h - bottom,
            w - 20.0,
            h - bottom,
            h - bottom
        );
        for l in 1..=4 {
            let _ = write!(
                s,
                r#"<text x="{}" y="{}" text-anchor="middle">level {l}</text>"#,
                x(l),
                h - bottom + 16.0
            );
        }
        let _ = write!(s, r#"<text x="8" y="14">ms (max {:.1})</text>"#, max * 1e3);
        for (i, (name, pts)) in series.iter().enumerate() {
            let c = colors[i % colors.len()];
            for (osd, dash) in [(false, ""), (true, r#" stroke-dasharray="5,4""#)] {
                let path: Vec<String> = pts
                    .iter()
                    .map(|&(l, n, o)| format!("{:.1},{:.1}", x(l), y(if osd { o } else { n })))
                    .collect();
                let _ = write!(
                    s,
                    r#"<polyline fill="none" stroke="{c}" stroke-width="2"{dash} points="{}"/>"#,
                    path.join(" ")
                );
            }
            let _ = write!(
                s,
                r#"<text x="{}" y="{}" fill="{c}">{name} (solid: native, dashed: OpenSubdiv)</text>"#,
                left + 10.0,
                32.0 + 14.0 * i as f64
            );
        }
        s.push_str("</svg>\n");
        s
    }

    /// An SVG bar chart of refined vertices per second at the deepest level
    /// against the rate the measured memory bandwidth would allow for the
    /// bytes each refined vertex needs (its f32 position written once).
    pub fn svg_rate_vs_bandwidth(&self) -> String {
        let rows: Vec<&Row> = self
            .rows
            .iter()
            .filter(|r| r.task == "positions (f32)")
            .collect();
        let bound = self.bandwidth / 12.0;
        let max = rows
            .iter()
            .map(|r| (r.vertices as f64 / r.native).max(r.vertices as f64 / r.osd))
            .fold(bound, f64::max);
        let (w, bar) = (640.0, 18.0);
        let h = 40.0 + rows.len() as f64 * 2.0 * (bar + 4.0) + 30.0;
        let scale = |v: f64| (v / max) * (w - 260.0);
        let mut s = format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="11"><rect width="{w}" height="{h}" fill="white"/>"#
        );
        let _ = write!(
            s,
            r#"<text x="8" y="16">refined vertices per second (positions, f32); line: bandwidth bound {:.2e}/s</text>"#,
            bound
        );
        let mut yy = 30.0;
        for r in rows {
            for (who, t, c) in [("native", r.native, "#1f77b4"), ("osd", r.osd, "#d62728")] {
                let rate = r.vertices as f64 / t;
                let _ = write!(
                    s,
                    r#"<text x="8" y="{}">{} {} {who}</text><rect x="250" y="{yy}" width="{:.1}" height="{bar}" fill="{c}"/><text x="{:.1}" y="{}">{:.2e}</text>"#,
                    yy + 13.0,
                    r.input,
                    r.scheme,
                    scale(rate),
                    254.0 + scale(rate),
                    yy + 13.0,
                    rate
                );
                yy += bar + 4.0;
            }
        }
        let bx = 250.0 + scale(bound);
        let _ = write!(
            s,
            r#"<line x1="{bx:.1}" y1="24" x2="{bx:.1}" y2="{yy}" stroke="black" stroke-dasharray="3,3"/></svg>"#
        );
        s.push('\n');
        s
    }
}
