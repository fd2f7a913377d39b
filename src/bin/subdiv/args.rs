//! Arguments shared by the subcommands: the input mesh, its options, level ranges.

use clap::Args;
use std::path::{Path, PathBuf};
use std::str::FromStr;
use subdiv::io::ShapeFile;
use subdiv::{
    BoundaryInterpolation, CreasingMethod, Error, FVarLinearInterpolation, Mesh, Options,
    ParseNameError, Precision, Scheme, TriangleSubdivision,
};

use crate::Failure;

/// `--scheme`: one of OpenSubdiv's schemes, or Doo-Sabin (native engine only).
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum SchemeArg {
    /// An OpenSubdiv scheme: both engines.
    Osd(Scheme),
    /// Doo-Sabin: the native engine only (`subdiv::doo_sabin`).
    DooSabin,
}

impl FromStr for SchemeArg {
    type Err = ParseNameError;
    fn from_str(s: &str) -> Result<Self, ParseNameError> {
        if s == "doo-sabin" {
            return Ok(SchemeArg::DooSabin);
        }
        // OpenSubdiv's schemes, with doo-sabin added to the list.
        s.parse::<Scheme>().map(SchemeArg::Osd).map_err(|mut e| {
            e.expected.push("doo-sabin");
            e
        })
    }
}

/// The input mesh and the subdivision options, shared by `refine` and `compare`.
#[derive(Args)]
pub(crate) struct MeshArgs {
    /// Input OBJ file (with OpenSubdiv `t` tags) or USD stage (.usd, .usda,
    /// .usdc, .usdz: its subdivision meshes); see --builtin for generated shapes.
    #[arg(required_unless_present = "builtin", conflicts_with = "builtin")]
    pub(crate) input: Option<PathBuf>,
    /// Use a generated shape instead of a file: cube, cube-uv, grid, torus, tetrahedron.
    #[arg(long, value_name = "NAME")]
    pub(crate) builtin: Option<String>,
    /// USD input: the mesh prims to read (repeatable; `*` within a path
    /// segment, `**` across segments, `?` one character); default every mesh.
    #[arg(long = "prim", value_name = "PATH")]
    pub(crate) prims: Vec<String>,
    /// USD input: read attributes at time code T, as USD resolves them
    /// (points and float primvars interpolated between samples, the rest
    /// held), instead of their default values.
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    pub(crate) time: Option<f64>,
    /// USD input: drop a malformed crease or corner with a warning instead of
    /// failing, as USD's renderer does.
    #[arg(long)]
    pub(crate) lenient: bool,
    /// Subdivision scheme (default: catmark; a USD mesh's subdivisionScheme).
    #[arg(long, value_parser = parse::<SchemeArg>)]
    pub(crate) scheme: Option<SchemeArg>,
    /// Vertex boundary interpolation (overrides the file's tag).
    #[arg(long, value_parser = parse::<BoundaryInterpolation>)]
    pub(crate) boundary: Option<BoundaryInterpolation>,
    /// Face-varying linear interpolation (overrides the file's tag).
    #[arg(long, value_parser = parse::<FVarLinearInterpolation>)]
    pub(crate) fvar: Option<FVarLinearInterpolation>,
    /// Creasing method (overrides the file's tag).
    #[arg(long, value_parser = parse::<CreasingMethod>)]
    pub(crate) creasing: Option<CreasingMethod>,
    /// Catmull-Clark triangle weights (overrides the file's tag).
    #[arg(long, value_parser = parse::<TriangleSubdivision>)]
    pub(crate) triangles: Option<TriangleSubdivision>,
    /// Floating-point precision of the interpolation.
    #[arg(long, default_value = "f64", value_parser = parse::<Precision>)]
    pub(crate) precision: Precision,
    /// Order child vertices from faces first (OpenSubdiv's orderVerticesFromFacesFirst).
    #[arg(long)]
    pub(crate) faces_first: bool,
    /// Treat every warning (unknown tag, crease without edge...) as an error.
    #[arg(long)]
    pub(crate) strict: bool,
}

pub(crate) fn parse_levels(s: &str) -> Result<(u32, u32), String> {
    let bad = || format!("'{s}' is not a level or a range A..B of levels");
    let (a, b) = match s.split_once("..") {
        Some((a, b)) => (
            a.trim().parse().map_err(|_| bad())?,
            b.trim()
                .trim_start_matches('=')
                .parse()
                .map_err(|_| bad())?,
        ),
        None => {
            let l = s.trim().parse().map_err(|_| bad())?;
            (l, l)
        }
    };
    if a > b {
        return Err(format!("the range {s} is empty"));
    }
    if b > subdiv::MAX_LEVEL {
        return Err(format!(
            "level {b} is deeper than the supported {}",
            subdiv::MAX_LEVEL
        ));
    }
    Ok((a, b))
}

/// `--tolerance`: a finite number, zero or more.
pub(crate) fn parse_tolerance(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(t) if t.is_finite() && t >= 0.0 => Ok(t),
        Ok(t) => Err(format!(
            "the tolerance must be a finite number, 0 or more; {t} is not"
        )),
        Err(_) => Err(format!("'{s}' is not a number")),
    }
}

/// `--level`: 0 to [`subdiv::MAX_LEVEL`].
pub(crate) fn parse_level(s: &str) -> Result<u32, String> {
    let max = subdiv::MAX_LEVEL;
    match s.trim().parse::<i64>() {
        Ok(l) if (0..=i64::from(max)).contains(&l) => Ok(l as u32),
        Ok(l) if l < 0 => Err(format!("a level is 0 or more; {l} is not")),
        Ok(l) => Err(format!("level {l} is deeper than the supported {max}")),
        Err(_) => Err(format!("'{s}' is not a level (0 to {max})")),
    }
}

/// Prints the warnings of one input: each distinct message at most
/// [`REPEATS`] times, then how many more lines said the same.
pub(crate) fn print_warnings<'a>(
    name: &str,
    warnings: impl IntoIterator<Item = (usize, &'a str, String)>,
) {
    let mut seen: Vec<(&str, usize, usize)> = Vec::new();
    for (line, key, text) in warnings {
        match seen.iter_mut().find(|(k, _, _)| *k == key) {
            Some((_, count, _)) if *count >= REPEATS => *count += 1,
            Some((_, count, _)) => {
                *count += 1;
                eprintln!("subdiv: warning: {name}: {text}");
            }
            None => {
                seen.push((key, 1, line));
                eprintln!("subdiv: warning: {name}: {text}");
            }
        }
    }
    for (key, count, first) in seen {
        if count > REPEATS {
            eprintln!(
                "subdiv: warning: {name}: {} more lines like line {first} ({key})",
                count - REPEATS
            );
        }
    }
}

/// How often one warning is printed before it is counted instead.
const REPEATS: usize = 5;

/// A named option value, for clap (`value_parser = parse::<T>`).
pub(crate) fn parse<T: FromStr<Err = ParseNameError>>(s: &str) -> Result<T, String> {
    s.parse().map_err(|e: ParseNameError| e.to_string())
}

/// One mesh to work on: an OBJ file, a built-in shape or a prim of a USD stage.
pub(crate) struct Loaded {
    /// How messages name it: the file (`FILE:PRIM` for a USD prim) or `builtin:NAME`.
    pub(crate) name: String,
    /// The mesh.
    pub(crate) mesh: Mesh,
    /// Its options: the file's (OBJ tags, USD attributes) under the command line's.
    pub(crate) options: Options,
    /// For a USD prim: its path and its face-varying channels' primvar names.
    pub(crate) prim: Option<(String, Vec<String>)>,
}

/// Whether `path` names a USD file (by its extension).
pub(crate) fn is_usd(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| ["usd", "usda", "usdc", "usdz"].contains(&e.to_ascii_lowercase().as_str()))
}

/// Loads the single mesh a command works on: [`load_all`], which must give
/// exactly one (a USD stage with several subdivision meshes needs `--prim`).
pub(crate) fn load(args: &MeshArgs) -> Result<(String, Mesh, Options), Failure> {
    let mut all = load_all(args)?;
    if all.len() == 1 {
        let one = all.remove(0);
        return Ok((one.name, one.mesh, one.options));
    }
    let file = args
        .input
        .as_deref()
        .map_or(String::new(), |p| p.display().to_string());
    if all.is_empty() {
        return Err(Failure::Message(format!(
            "{file}: no subdivision mesh to read (see the notes above)"
        )));
    }
    let prims: Vec<&str> = all
        .iter()
        .filter_map(|l| l.prim.as_ref())
        .map(|p| p.0.as_str())
        .collect();
    Err(Failure::Usage(format!(
        "{file} has {} subdivision meshes ({}); this command takes one: choose it with --prim PATH",
        all.len(),
        prims.join(", ")
    )))
}

/// Loads every mesh of the input: an OBJ file (its tags over the shape-file
/// defaults), a built-in shape, or the selected subdivision meshes of a USD
/// stage (their attributes with USD's fallbacks); the command line's
/// options over each.
pub(crate) fn load_all(args: &MeshArgs) -> Result<Vec<Loaded>, Failure> {
    if let Some(path) = args.input.as_deref().filter(|p| is_usd(p)) {
        return crate::usd::load(args, path);
    }
    if !args.prims.is_empty() || args.time.is_some() || args.lenient {
        return Err(Failure::Usage(
            "--prim, --time and --lenient apply to USD inputs (.usd, .usda, .usdc, .usdz)".into(),
        ));
    }
    let (name, mesh, options) = load_obj(args)?;
    Ok(vec![Loaded {
        name,
        mesh,
        options,
        prim: None,
    }])
}

/// Loads an OBJ file (tags applied over the shape-file defaults) or a built-in shape.
fn load_obj(args: &MeshArgs) -> Result<(String, Mesh, Options), Failure> {
    let (name, shape) = match (&args.input, &args.builtin) {
        (Some(path), _) => (
            path.display().to_string(),
            subdiv::io::read_obj(path).map_err(Error::from)?,
        ),
        (None, Some(name)) => {
            let mesh = subdiv::shapes::by_name(name).ok_or_else(|| {
                Failure::Usage(format!(
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
    if let (true, Some(w)) = (args.strict, shape.warnings.first()) {
        return Err(Failure::Message(format!(
            "{name}:{}: {} (a warning; --strict makes it an error)",
            w.line, w.message
        )));
    }
    print_warnings(
        &name,
        shape
            .warnings
            .iter()
            .map(|w| (w.line, w.message.as_str(), w.to_string())),
    );
    let validation = if args.strict {
        shape.mesh.validate_strict()
    } else {
        shape.mesh.validate()
    }
    .map_err(|e| Failure::Message(format!("{name}: invalid mesh: {e}")))?;
    let texts: Vec<String> = validation
        .warnings
        .iter()
        .map(ToString::to_string)
        .collect();
    print_warnings(&name, texts.iter().map(|t| (0, t.as_str(), t.clone())));
    let mut options = shape.options();
    override_options(args, &mut options);
    Ok((name, shape.mesh, options))
}

/// The command line's options over a file's.
pub(crate) fn override_options(args: &MeshArgs, options: &mut Options) {
    if let Some(SchemeArg::Osd(scheme)) = args.scheme {
        options.scheme = scheme;
    }
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
}
