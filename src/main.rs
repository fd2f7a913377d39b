//! The `subdiv` command-line tool.

use clap::{Args, Parser, Subcommand};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;
use subdiv::io::{ObjOutput, ShapeFile, UvOutput};
use subdiv::{
    BoundaryInterpolation, CreasingMethod, Error, FVarLinearInterpolation, Mesh, Options,
    Precision, Refinement, Scheme, TriangleSubdivision, UniformOptions,
};

#[derive(Parser)]
#[command(
    name = "subdiv",
    version,
    about = "Subdivision surfaces, identical to OpenSubdiv index by index"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Refine a mesh uniformly and write the last level as OBJ.
    Refine(RefineArgs),
    /// The main job on the built-in cube: refine it to level 2 with every available engine.
    Demo,
    /// Print the versions of subdiv and of the OpenSubdiv it is built against.
    Version,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum Engine {
    /// The pure-Rust engine.
    Native,
    /// OpenSubdiv through the C++ bridge.
    Osd,
}

#[derive(Args)]
struct RefineArgs {
    /// Input OBJ file (with OpenSubdiv `t` tags); see --builtin for generated shapes.
    #[arg(required_unless_present = "builtin", conflicts_with = "builtin")]
    input: Option<PathBuf>,
    /// Use a generated shape instead of a file: cube, cube-uv, grid, torus, tetrahedron.
    #[arg(long, value_name = "NAME")]
    builtin: Option<String>,
    /// Output OBJ file; without it nothing is written and a summary is printed.
    #[arg(short, long, value_name = "OUT.obj")]
    output: Option<PathBuf>,
    /// Refinement level (0..=10).
    #[arg(long, default_value_t = 2)]
    level: u32,
    /// Subdivision scheme.
    #[arg(long, default_value = "catmark", value_parser = parse::<Scheme>)]
    scheme: Scheme,
    /// Refinement engine.
    #[arg(long, value_enum, default_value = "native")]
    engine: Engine,
    /// Vertex boundary interpolation (overrides the file's tag).
    #[arg(long, value_parser = parse::<BoundaryInterpolation>)]
    boundary: Option<BoundaryInterpolation>,
    /// Face-varying linear interpolation (overrides the file's tag).
    #[arg(long, value_parser = parse::<FVarLinearInterpolation>)]
    fvar: Option<FVarLinearInterpolation>,
    /// Creasing method (overrides the file's tag).
    #[arg(long, value_parser = parse::<CreasingMethod>)]
    creasing: Option<CreasingMethod>,
    /// Catmull-Clark triangle weights (overrides the file's tag).
    #[arg(long, value_parser = parse::<TriangleSubdivision>)]
    triangles: Option<TriangleSubdivision>,
    /// Write limit positions (and limit face-varying values) instead of refined ones.
    #[arg(long)]
    limit: bool,
    /// Floating-point precision of the interpolation.
    #[arg(long, default_value = "f64", value_parser = parse::<Precision>)]
    precision: Precision,
    /// Treat every warning (unknown tag, crease without edge...) as an error.
    #[arg(long)]
    strict: bool,
}

fn parse<T: std::str::FromStr<Err = String>>(s: &str) -> Result<T, String> {
    s.parse()
}

/// Why the tool stopped.
enum Failure {
    /// A real error: exit 1.
    Error(Error),
    /// A feature this build does not offer yet: exit 2.
    Unavailable(String),
}

impl From<Error> for Failure {
    fn from(e: Error) -> Self {
        Failure::Error(e)
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Refine(args) => refine(&args),
        Command::Demo => demo(),
        Command::Version => {
            version();
            Ok(())
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Error(e)) => {
            eprintln!("subdiv: error: {e}");
            ExitCode::from(1)
        }
        Err(Failure::Unavailable(msg)) => {
            eprintln!("subdiv: {msg}");
            ExitCode::from(2)
        }
    }
}

fn version() {
    println!("subdiv {}", env!("CARGO_PKG_VERSION"));
    #[cfg(feature = "osd")]
    println!("OpenSubdiv {}", subdiv::osd::version());
    #[cfg(not(feature = "osd"))]
    println!("OpenSubdiv bridge: not built (feature `osd` is off)");
}

/// Loads the input: a file (tags applied over the shape-file defaults) or a built-in shape.
fn load(args: &RefineArgs) -> Result<(String, Mesh, Options), Failure> {
    let (name, shape) = match (&args.input, &args.builtin) {
        (Some(path), _) => (
            path.display().to_string(),
            subdiv::io::read_obj(path).map_err(Error::from)?,
        ),
        (None, Some(name)) => {
            let mesh = subdiv::shapes::by_name(name).ok_or_else(|| {
                Error::InvalidArgument(format!(
                    "unknown built-in shape '{name}' (known: {})",
                    subdiv::shapes::NAMES.join(", ")
                ))
            })?;
            (
                format!("builtin:{name}"),
                ShapeFile {
                    mesh,
                    tags: Default::default(),
                    warnings: Vec::new(),
                },
            )
        }
        (None, None) => unreachable!("clap requires an input or --builtin"),
    };
    for w in &shape.warnings {
        if args.strict {
            return Err(Error::InvalidArgument(format!("{name}: {w} (--strict)")).into());
        }
        eprintln!("subdiv: warning: {name}: {w}");
    }
    let validation = if args.strict {
        shape.mesh.validate_strict()
    } else {
        shape.mesh.validate()
    }
    .map_err(Error::from)?;
    for w in &validation.warnings {
        eprintln!("subdiv: warning: {name}: {w}");
    }
    let mut options = shape.options();
    options.scheme = args.scheme;
    if let Some(b) = args.boundary {
        options.boundary = b;
    }
    if let Some(f) = args.fvar {
        options.fvar = f;
    }
    if let Some(c) = args.creasing {
        options.creasing = c;
    }
    if let Some(t) = args.triangles {
        options.triangles = t;
    }
    Ok((name, shape.mesh, options))
}

fn run_engine(
    engine: Engine,
    mesh: &Mesh,
    options: &Options,
    uniform: UniformOptions,
    precision: Precision,
    limit: bool,
) -> Result<Refinement, Failure> {
    match engine {
        Engine::Native => Err(Failure::Unavailable(
            "the native engine is not implemented yet; use --engine osd".into(),
        )),
        #[cfg(feature = "osd")]
        Engine::Osd => Ok(subdiv::osd::refine_with(
            mesh, options, uniform, precision, limit,
        )?),
        #[cfg(not(feature = "osd"))]
        Engine::Osd => {
            let _ = (mesh, options, uniform, precision, limit);
            Err(Failure::Unavailable(
                "this build has no OpenSubdiv bridge (rebuild with the default feature `osd`)"
                    .into(),
            ))
        }
    }
}

fn engine_name(engine: Engine) -> &'static str {
    match engine {
        Engine::Native => "native",
        Engine::Osd => "osd",
    }
}

fn summary(name: &str, engine: Engine, r: &Refinement, seconds: f64) -> String {
    let counts = |f: fn(&subdiv::LevelTopology) -> usize| {
        r.levels
            .iter()
            .map(|l| f(l).to_string())
            .collect::<Vec<_>>()
            .join("→")
    };
    format!(
        "{name}: {} level {} ({}, {}): vertices {}, faces {}{}; {:.3} ms",
        r.options.scheme,
        r.uniform.level,
        engine_name(engine),
        r.precision,
        counts(|l| l.vertex_count),
        counts(|l| l.face_count()),
        if r.limit.is_some() {
            ", limit evaluated"
        } else {
            ""
        },
        seconds * 1e3
    )
}

fn refine(args: &RefineArgs) -> Result<(), Failure> {
    let (name, mesh, options) = load(args)?;
    let uniform = UniformOptions::new(args.level);
    subdiv::refinement::check_level(&mesh, &options, args.level)?;
    let start = Instant::now();
    let r = run_engine(
        args.engine,
        &mesh,
        &options,
        uniform,
        args.precision,
        args.limit,
    )?;
    let seconds = start.elapsed().as_secs_f64();
    match &args.output {
        Some(path) => write_output(path, &r)?,
        None => println!("{}", summary(&name, args.engine, &r, seconds)),
    }
    Ok(())
}

/// Writes the last level (or its limit) in OpenSubdiv's order; holes are left out.
fn write_output(path: &Path, r: &Refinement) -> Result<(), Failure> {
    let level = r.last_level();
    let (positions, uv_values) = match &r.limit {
        Some(limit) => (
            limit.positions.as_slice(),
            limit.fvar_values.first().map(Vec::as_slice),
        ),
        None => (r.last_positions(), r.last_fvar(0)),
    };
    let uv = match (uv_values, level.fvar.first(), r.fvar_widths.first()) {
        (Some(values), Some(fvar), Some(&width)) => Some(UvOutput {
            width,
            values,
            face_values: &fvar.face_values,
        }),
        _ => None,
    };
    let data = ObjOutput {
        positions,
        face_offsets: &level.face_offsets,
        face_vertices: &level.face_vertices,
        holes: Some(&level.face_holes),
        uv,
        precision: r.precision,
    };
    subdiv::io::write_obj(path, &data)?;
    Ok(())
}

fn demo() -> Result<(), Failure> {
    version();
    let mesh = subdiv::shapes::cube();
    let options = Options::shape_file_defaults();
    let mut ran = 0;
    for engine in [Engine::Native, Engine::Osd] {
        let start = Instant::now();
        match run_engine(
            engine,
            &mesh,
            &options,
            UniformOptions::new(2),
            Precision::F64,
            false,
        ) {
            Ok(r) => {
                println!(
                    "{}",
                    summary("builtin:cube", engine, &r, start.elapsed().as_secs_f64())
                );
                ran += 1;
            }
            Err(Failure::Unavailable(msg)) => {
                println!("builtin:cube ({}): skipped: {msg}", engine_name(engine))
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
