//! The `report` subcommand.

use clap::Args;
#[cfg(feature = "osd")]
use std::io::{IsTerminal as _, Write as _};
use std::path::PathBuf;

use crate::Failure;
use crate::args::{parse_levels, parse_tolerance};

#[derive(Args)]
pub(crate) struct ReportArgs {
    /// OBJ files (with OpenSubdiv `t` tags) or USD stages (each subdivision
    /// mesh an input) to report on; without them, the embedded set (cube,
    /// torus, creases, pole, holes, UV seams, four boxes, Loop, bilinear,
    /// non-manifold).
    #[arg(value_name = "INPUT.obj|INPUT.usd")]
    pub(crate) inputs: Vec<PathBuf>,
    /// USD inputs: the mesh prims to report on (repeatable; `*` within a
    /// path segment, `**` across segments); default every mesh.
    #[arg(long = "prim", value_name = "PATH")]
    pub(crate) prims: Vec<String>,
    /// Directory for report.md, report.html and figures/.
    #[arg(long, value_name = "DIR", default_value = "report")]
    pub(crate) out: PathBuf,
    /// Levels to compare and benchmark: `A..B` (inclusive) or a single level
    /// [default: 1..4, with --quick 1..2].
    #[arg(long, value_parser = parse_levels)]
    pub(crate) levels: Option<(u32, u32)>,
    /// Fewer option sets (one option varied at a time), levels 1..2, shorter benchmarks.
    #[arg(long)]
    pub(crate) quick: bool,
    /// Largest accepted deviation, relative to the bounding-box diagonal.
    #[arg(long, default_value = "1e-6", allow_negative_numbers = true, value_parser = parse_tolerance)]
    pub(crate) tolerance: f64,
    /// Every combination of the options that apply, for every input: without
    /// it, inputs too large to run them all in about a minute (a production
    /// asset) get one option varied at a time, or only their own options.
    #[arg(long)]
    pub(crate) all_options: bool,
}

#[cfg(not(feature = "osd"))]
pub(crate) fn report(_args: &ReportArgs) -> Result<(), Failure> {
    Err(Failure::Unavailable(
        "the report compares with OpenSubdiv: rebuild with the default feature `osd`".into(),
    ))
}

/// `subdiv report`: conformance and benchmarks on the embedded set or on OBJ files.
#[cfg(feature = "osd")]
pub(crate) fn report(args: &ReportArgs) -> Result<(), Failure> {
    use super::inputs::{embedded_inputs, read_inputs};
    use super::run::{run, steps};
    use super::settings::Settings;
    use crate::args::print_warnings;
    let mut settings = Settings::new(args.quick);
    if let Some((a, b)) = args.levels {
        settings.first_level = a;
        settings.last_level = b;
    }
    settings.tolerance = args.tolerance;
    settings.all_options = args.all_options;
    let inputs = if args.inputs.is_empty() {
        embedded_inputs()
    } else {
        let mut v = Vec::with_capacity(args.inputs.len());
        for path in &args.inputs {
            let name = path.display().to_string();
            let read =
                read_inputs(path, &args.prims).map_err(|e| Failure::from(e).in_input(&name))?;
            if read.is_empty() {
                return Err(Failure::Message(format!(
                    "{name}: no subdivision mesh to report on"
                )));
            }
            for (input, warnings) in read {
                print_warnings(
                    &name,
                    warnings
                        .iter()
                        .map(|(line, key, text)| (*line, key.as_str(), text.clone())),
                );
                v.push(input);
            }
        }
        v
    };
    let total = steps(&inputs, &settings);
    let bar = indicatif::ProgressBar::new(total);
    // The bar draws only on a terminal; elsewhere (a pipeline's log) one
    // line per step says how far the report is.
    let lines = !std::io::stderr().is_terminal();
    let mut step = 0;
    bar.set_style(
        indicatif::ProgressStyle::with_template("{elapsed:>4} [{bar:30}] {pos}/{len} {wide_msg}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    let result = run(&inputs, &settings, |msg| {
        step += 1;
        if lines {
            eprintln!("subdiv report: [{step}/{total}] {msg}");
        }
        bar.set_message(msg.to_string());
        bar.inc(1);
    });
    bar.finish_and_clear();
    let rep = result?;
    rep.write(&args.out)?;
    // The files are written; a closed stdout (`| head`) is not an error.
    let mut out = std::io::stdout().lock();
    let _ = write!(out, "{}", rep.summary_text()).and_then(|()| {
        writeln!(
            out,
            "wrote {} and {}",
            args.out.join("report.md").display(),
            args.out.join("report.html").display()
        )
    });
    if rep.conforms() {
        Ok(())
    } else {
        Err(Failure::Differ)
    }
}
