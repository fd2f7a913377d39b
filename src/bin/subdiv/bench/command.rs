//! The `bench` subcommand.

use clap::Args;
use std::path::PathBuf;
#[cfg(feature = "osd")]
use subdiv::Error;

use crate::Failure;

#[derive(Args)]
pub(crate) struct BenchArgs {
    /// OBJ files or USD stages to benchmark (each with its own options: the
    /// OBJ's tags, each USD prim's attributes; levels 1-3); without them, the
    /// generated tori, grid and production-like mesh of the standard benchmark.
    #[arg(value_name = "INPUT.obj|STAGE.usd")]
    pub(crate) inputs: Vec<PathBuf>,
    /// USD inputs: the mesh prims to benchmark (repeatable; `*` within a
    /// path segment, `**` across segments); default every mesh.
    #[arg(long = "prim", value_name = "PATH")]
    pub(crate) prims: Vec<String>,
    /// Smaller inputs and fewer repetitions.
    #[arg(long)]
    pub(crate) quick: bool,
    /// Only the adaptive rows (feature-adaptive refinement at isolation 3
    /// and 6): no uniform rows, parallel use, whole processes or OBJ writer.
    #[arg(long, conflicts_with = "tessellation_only")]
    pub(crate) adaptive_only: bool,
    /// Only the tessellation rows (each input's limit surface tessellated
    /// the Bfr way at rates 4 and 16; at rate 4 once for inputs of 100,000
    /// faces or more).
    #[arg(long)]
    pub(crate) tessellation_only: bool,
    /// Only the whole processes (`subdiv refine` against the C++ program
    /// on the same OBJ file: time and peak memory) and the OBJ reader and
    /// writer: no in-process rows. Inputs given are each run at levels 1
    /// and 2; the standard ones as in the full benchmark.
    #[arg(long, conflicts_with_all = ["adaptive_only", "tessellation_only"])]
    pub(crate) processes_only: bool,
    /// Threads for the native engine.
    #[arg(long, default_value_t = 1)]
    pub(crate) threads: usize,
    /// Write bench.md, bench.json and SVG plots into this directory.
    #[arg(long, value_name = "DIR")]
    pub(crate) out: Option<PathBuf>,
}

#[cfg(not(feature = "osd"))]
pub(crate) fn bench(_args: &BenchArgs) -> Result<(), Failure> {
    Err(Failure::Unavailable(
        "benchmarks compare with OpenSubdiv: rebuild with the default feature `osd`".into(),
    ))
}

#[cfg(feature = "osd")]
pub(crate) fn bench(args: &BenchArgs) -> Result<(), Failure> {
    let inputs = if args.inputs.is_empty() {
        subdiv::shapes::bench_shapes(args.quick)
    } else {
        let mut v = Vec::new();
        for path in &args.inputs {
            let name = path.display().to_string();
            let read = crate::report::read_inputs(path, &args.prims)
                .map_err(|e| Failure::from(e).in_input(&name))?;
            for (input, warnings) in read {
                crate::args::print_warnings(
                    &name,
                    warnings
                        .iter()
                        .map(|(line, key, text)| (*line, key.as_str(), text.clone())),
                );
                v.push(subdiv::shapes::BenchShape {
                    name: input.name,
                    mesh: input.mesh,
                    options: input.options,
                    max_level: 3,
                });
            }
        }
        if v.is_empty() {
            return Err(Failure::Message(
                "no subdivision mesh to benchmark in the inputs".into(),
            ));
        }
        v
    };
    let standard = args.inputs.is_empty();
    let adaptive_inputs = if args.tessellation_only || args.processes_only {
        Vec::new()
    } else {
        super::adaptive::adaptive_inputs(&inputs, standard, args.quick)
    };
    let tessellation_inputs = if args.adaptive_only || args.processes_only {
        Vec::new()
    } else {
        super::tessellation::tessellation_inputs(&inputs, standard)
    };
    let all_inputs = &inputs;
    let inputs: &[subdiv::shapes::BenchShape] =
        if args.adaptive_only || args.tessellation_only || args.processes_only {
            &[]
        } else {
            all_inputs
        };
    // The whole processes: on the standard inputs, the first (the quad
    // torus) at level 4 and the big ones refined at most two levels in
    // process (the grid, the production-like mesh) at levels 1 and 2, as
    // production assets are refined; with `--processes-only`, the inputs
    // given at levels 1 and 2. Then the OBJ reader on the big inputs (the
    // inputs given), and on the standard inputs the writer on the first.
    let processes = !(args.adaptive_only || args.tessellation_only);
    let (runs, readers) = if !processes {
        (Vec::new(), Vec::new())
    } else if standard {
        // With 100,000 faces or more at full size (`--quick` divides the
        // face counts by 16).
        let scale = if args.quick { 16 } else { 1 };
        let big: Vec<&subdiv::shapes::BenchShape> = all_inputs
            .iter()
            .filter(|i| i.max_level <= 2 && i.mesh.face_count() * scale >= 100_000)
            .collect();
        let mut runs = vec![(&all_inputs[0], 4)];
        runs.extend(big.iter().flat_map(|&i| [(i, 1), (i, 2)]));
        (runs, big)
    } else if args.processes_only {
        let runs = all_inputs.iter().flat_map(|i| [(i, 1), (i, 2)]).collect();
        (runs, all_inputs.iter().collect())
    } else {
        (Vec::new(), Vec::new())
    };
    // Per input: one step per level and eight tasks (nine with UVs); then
    // the two parallel-use steps; then two adaptive steps per isolation
    // level and adaptive input, and two limit-surface steps per adaptive
    // input; then one tessellation step per rate and input.
    let steps: u64 = inputs
        .iter()
        .map(|i| i.max_level as u64 + 8 + u64::from(!i.mesh.fvar_channels.is_empty()))
        .sum::<u64>()
        + if inputs.is_empty() { 0 } else { 2 }
        + 2 * (super::adaptive::ISOLATION_LEVELS.len() * adaptive_inputs.len()) as u64
        + 2 * adaptive_inputs.len() as u64
        + tessellation_inputs
            .iter()
            .map(|i| super::tessellation::tessellation_rates(i).len() as u64)
            .sum::<u64>()
        + (runs.len() + readers.len() + usize::from(standard && !runs.is_empty())) as u64;
    let bar = indicatif::ProgressBar::new(steps);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{bar:30} {pos}/{len} {msg}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    // One step done: its name shown, the bar moved on.
    let progress = |msg: String| {
        bar.set_message(msg);
        bar.inc(1);
    };
    let mut report = super::run::run(
        inputs,
        &adaptive_inputs,
        &tessellation_inputs,
        args.quick,
        args.threads,
        |msg| progress(msg.to_string()),
    )?;
    if !runs.is_empty() {
        let dir = tempfile::tempdir()
            .map_err(|e| Failure::Message(format!("no temporary directory ({e})")))?;
        let driver = super::process::compile_driver(dir.path());
        for (input, level) in runs {
            progress(format!("{}: whole process, level {level}", input.name));
            match super::process::whole_process(
                input,
                level,
                args.quick,
                args.threads,
                driver.as_deref(),
            ) {
                Ok(w) => report.whole_process.push(w),
                Err(e) => report
                    .skipped
                    .push(format!("whole process, {} level {level}: {e}", input.name)),
            }
        }
        for input in readers {
            progress(format!("{}: OBJ reader", input.name));
            match super::process::obj_reader_rate(input, args.threads) {
                Ok(o) => report.obj_reader.push(o),
                Err(e) => report
                    .skipped
                    .push(format!("OBJ reader, {}: {e}", input.name)),
            }
        }
        // (Not on the inputs given: it refines to level 3 in memory.)
        if standard {
            progress(format!("{}: OBJ writer", all_inputs[0].name));
            match super::process::obj_writer_rate(&all_inputs[0]) {
                Ok(o) => report.obj_writer = Some(o),
                Err(e) => report.skipped.push(format!("OBJ writer: {e}")),
            }
        }
    }
    bar.finish_and_clear();
    let text = report.markdown();
    outln!("{text}");
    if let Some(dir) = &args.out {
        let io = |e: std::io::Error| {
            Failure::Error(Error::Io {
                path: dir.clone(),
                source: e,
            })
        };
        std::fs::create_dir_all(dir).map_err(io)?;
        let json = serde_json::to_string_pretty(&report)
            .map_err(|e| Failure::Message(format!("cannot encode the report: {e}")))?;
        let mut files = vec![("bench.md", text.clone()), ("bench.json", json)];
        // The plots draw the uniform rows (none with --adaptive-only or
        // --tessellation-only).
        if !report.rows.is_empty() {
            files.push(("time-per-level.svg", report.svg_time_per_level()));
            files.push(("rate-vs-bandwidth.svg", report.svg_rate_vs_bandwidth()));
        }
        for (name, body) in files {
            std::fs::write(dir.join(name), body).map_err(io)?;
        }
        outln!("wrote {}", dir.display());
    }
    Ok(())
}
