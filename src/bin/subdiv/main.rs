//! The `subdiv` command-line tool.

use clap::{Parser, Subcommand};
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;
use subdiv::{Engine, Error, Options, Request};

/// `println!` that ends the process quietly when stdout is closed (a pipe
/// into `head`), instead of panicking on the broken pipe.
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::print_line(format_args!($($arg)*))
    };
}

pub(crate) fn print_line(args: std::fmt::Arguments<'_>) {
    use std::io::Write as _;
    let mut out = std::io::stdout().lock();
    if let Err(e) = writeln!(out, "{args}") {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            std::process::exit(0);
        }
        eprintln!("subdiv: cannot write to standard output: {e}");
        std::process::exit(1);
    }
}

mod adaptive;
mod args;
mod bench;
mod compare;
#[cfg(feature = "osd")]
mod compare_patches;
mod curve;
#[cfg(feature = "osd")]
mod date;
mod output;
mod patches;
mod refine;
mod report;
mod tessellate;
mod usd;

use bench::BenchArgs;
use compare::CompareArgs;
use curve::CurveArgs;
use refine::{RefineArgs, refinement_counts, summary};
use report::ReportArgs;

#[derive(Parser)]
#[command(
    name = "subdiv",
    version,
    about = "Subdivision surfaces, identical to OpenSubdiv index by index"
)]
pub(crate) struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
pub(crate) enum Command {
    /// Refine a mesh uniformly and write the last level as OBJ, or feature-adaptively
    /// (--adaptive) and print or write (--levels-json) every level.
    Refine(RefineArgs),
    /// Refine with both engines and compare them level by level, vertex by vertex.
    Compare(CompareArgs),
    /// Build the patch table of a mesh (PatchTableFactory after RefineAdaptive) and print
    /// its arrays, or write them as JSON (--json).
    Patches(patches::PatchesArgs),
    /// Evaluate the limit surface at (ptex face, u, v) locations (PatchMap::FindPatch and
    /// EvaluateBasis), with first derivatives on request.
    Eval(patches::EvalArgs),
    /// Tessellate every base face's limit surface (Bfr's patterns, a uniform rate or a rate
    /// per edge) into one watertight OBJ with UVs and, on request, normals.
    Tessellate(tessellate::TessellateArgs),
    /// Refine a curve (one point per line) with Chaikin, B-spline, four-point or Jarek's scheme,
    /// or insert knots into a B-spline or NURBS curve and sample it (--knots).
    Curve(CurveArgs),
    /// Benchmark the native engine against OpenSubdiv, side by side in the same run.
    Bench(BenchArgs),
    /// The main job: compare native against OpenSubdiv on a set of inputs for every
    /// option that applies, benchmark both, and write report.md and report.html.
    Report(ReportArgs),
    /// The main job on the built-in cube: refine it to level 2 with every available engine.
    Demo,
    /// Print the versions of subdiv and of the OpenSubdiv it is built against.
    Version,
}

/// Why the tool stopped, and so its exit status.
///
/// Exit statuses (README, "Exit status"): 0 success, [`Failure::Error`] and
/// [`Failure::Message`] 1, [`Failure::Usage`] 2 (as clap's own usage
/// errors), [`Failure::Differ`] 3, [`Failure::Unavailable`] 4.
#[derive(Debug)]
pub(crate) enum Failure {
    /// A real error (bad input, I/O, memory, an engine failing): exit 1.
    Error(Error),
    /// A command line that does not make sense: exit 2.
    Usage(String),
    /// `compare` or `report` found a difference (already reported): exit 3.
    Differ,
    /// A feature this build or engine does not offer (the osd engine not
    /// built, a scheme OpenSubdiv lacks, an input OpenSubdiv would overrun
    /// its buffers on): exit 4.
    Unavailable(String),
    /// An error already worded (naming its input): exit 1.
    Message(String),
}

impl Failure {
    /// The failure of a command on input `name`: an error that does not name
    /// a file of its own gets the input's name in front.
    pub(crate) fn in_input(self, name: &str) -> Failure {
        match self {
            Failure::Error(e @ (Error::Io { .. } | Error::Obj(_))) => Failure::Error(e),
            #[cfg(feature = "usd")]
            Failure::Error(e @ Error::Usd(_)) => Failure::Error(e),
            Failure::Error(e) => Failure::Message(format!("{name}: {e}")),
            Failure::Unavailable(m) => Failure::Unavailable(format!("{name}: {m}")),
            other => other,
        }
    }
}

impl From<Error> for Failure {
    fn from(e: Error) -> Self {
        match e {
            Error::OsdUnavailable | Error::NotYetSupported(_) => {
                Failure::Unavailable(e.to_string())
            }
            Error::Osd(ref osd) if osd.kind == subdiv::OsdErrorKind::Unsafe => {
                Failure::Unavailable(e.to_string())
            }
            e => Failure::Error(e),
        }
    }
}

/// On SIGINT, SIGTERM or SIGHUP, removes the temporary files of the outputs
/// being written (their final names never appear half-written) and ends the
/// process as the signal would have (a parent sees the signal). Returns the
/// flag the signal handler sets at once: from then on no output is renamed
/// into place ([`subdiv::io::atomic::abandon_when`]).
fn remove_temporary_files_on_signals() -> Arc<AtomicBool> {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let ending = Arc::new(AtomicBool::new(false));
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
        return ending; // no handler: the default behaviour, temporary files included
    };
    // Only with the thread below to end the process: a flag alone would
    // replace the signals' default action.
    for signal in [SIGINT, SIGTERM, SIGHUP] {
        let _ = signal_hook::flag::register(signal, Arc::clone(&ending));
    }
    subdiv::io::atomic::abandon_when(Arc::clone(&ending));
    std::thread::spawn(move || {
        if let Some(signal) = signals.forever().next() {
            subdiv::io::atomic::remove_pending();
            let _ = signal_hook::low_level::emulate_default_handler(signal);
            std::process::exit(128 + signal);
        }
    });
    ending
}

fn main() -> ExitCode {
    let ending = remove_temporary_files_on_signals();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Refine(args) => refine::refine(&args),
        Command::Compare(args) => compare::compare(&args),
        Command::Patches(args) => patches::patches(&args),
        Command::Eval(args) => patches::eval(&args),
        Command::Tessellate(args) => tessellate::tessellate(&args),
        Command::Curve(args) => curve::curve(&args),
        Command::Bench(args) => bench::bench(&args),
        Command::Report(args) => report::report(&args),
        Command::Demo => demo(),
        Command::Version => {
            version();
            Ok(())
        }
    };
    if ending.load(Ordering::SeqCst) {
        // A signal came: its thread ends the process as the signal would
        // (an output abandoned because of it is not an error to report).
        loop {
            std::thread::park();
        }
    }
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Error(e)) => {
            eprintln!("subdiv: error: {e}");
            ExitCode::from(1)
        }
        Err(Failure::Usage(msg)) => {
            eprintln!("subdiv: usage error: {msg}");
            ExitCode::from(2)
        }
        Err(Failure::Unavailable(msg)) => {
            eprintln!("subdiv: not available: {msg}");
            ExitCode::from(4)
        }
        Err(Failure::Differ) => ExitCode::from(3),
        Err(Failure::Message(msg)) => {
            eprintln!("subdiv: error: {msg}");
            ExitCode::from(1)
        }
    }
}

pub(crate) fn version() {
    outln!("subdiv {}", env!("CARGO_PKG_VERSION"));
    #[cfg(feature = "osd")]
    outln!("OpenSubdiv {}", subdiv::osd::version());
    #[cfg(not(feature = "osd"))]
    outln!("OpenSubdiv bridge: not built (feature `osd` is off)");
}

pub(crate) fn demo() -> Result<(), Failure> {
    version();
    let mesh = subdiv::shapes::cube();
    let options = Options::shape_file_defaults();
    let mut ran = 0;
    for &engine in Engine::ALL {
        let start = Instant::now();
        match engine
            .refine(&mesh, &options, Request::new(2))
            .map_err(Failure::from)
        {
            Ok(r) => {
                outln!(
                    "{}",
                    summary(
                        "builtin:cube",
                        engine,
                        &r.options,
                        r.precision,
                        &refinement_counts(&r),
                        r.limit.is_some(),
                        start.elapsed().as_secs_f64()
                    )
                );
                ran += 1;
            }
            Err(Failure::Unavailable(msg)) => {
                outln!("builtin:cube ({engine}): skipped: {msg}")
            }
            Err(e) => return Err(e),
        }
    }
    if ran == 0 {
        return Err(Failure::Unavailable(
            "no engine is available in this build".into(),
        ));
    }
    Ok(())
}
