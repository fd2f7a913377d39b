//! `subdiv patches` and `subdiv eval`: OpenSubdiv's patch table of a mesh
//! (`Far::PatchTableFactory`) as a summary or JSON, and the limit surface at
//! (ptex face, u, v) locations (`Far::PatchMap` and `EvaluateBasis`), by
//! the native engine (the default) or OpenSubdiv's (`--engine osd`).

use clap::Args;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use subdiv::patches::{
    Derivatives, EndCapType, Evaluation, PatchData, PatchMap, PatchOptions, PatchTable,
    SurfaceSamples,
};
use subdiv::{Engine, Precision};

use crate::Failure;
use crate::args::{MeshArgs, parse, parse_level};
use crate::output::write_output;

/// A location: ptex face, u, v.
type Location = (u32, f64, f64);

/// The mesh, the options of the patch table and the engine, shared by
/// `patches` and `eval`.
#[derive(Args)]
pub(crate) struct PatchArgs {
    #[command(flatten)]
    pub(crate) mesh: MeshArgs,
    /// Adaptive isolation level (0..=10; PatchTableFactory's maxIsolationLevel).
    #[arg(long, value_name = "N", default_value = "4", value_parser = parse_level,
          allow_negative_numbers = true)]
    pub(crate) isolation: u32,
    /// End caps around extraordinary features: none, bilinear, bspline, gregory-basis
    /// (OpenSubdiv's default) or legacy-gregory.
    #[arg(long, value_name = "TYPE", default_value = "gregory-basis", value_parser = crate::args::parse::<EndCapType>)]
    pub(crate) end_caps: EndCapType,
    /// Single-crease patches (useSingleCreasePatch).
    #[arg(long)]
    pub(crate) single_crease: bool,
    /// Infinitely sharp patches (useInfSharpPatch).
    #[arg(long)]
    pub(crate) inf_sharp: bool,
    /// Local points (end-cap stencils) in double precision (patchPrecisionDouble;
    /// f32 by default, as OpenSubdiv's).
    #[arg(long)]
    pub(crate) double: bool,
    /// The engine that builds and evaluates the table: native (identical tables to
    /// OpenSubdiv's, every scheme and end-cap type) or osd.
    #[arg(long, default_value = "native", value_parser = parse::<Engine>)]
    pub(crate) engine: Engine,
}

/// `subdiv patches`: the patch table's summary, and its arrays as JSON.
#[derive(Args)]
pub(crate) struct PatchesArgs {
    #[command(flatten)]
    pub(crate) patch: PatchArgs,
    /// Write the arrays as JSON: {"arrays": [{"type", "num_patches", "cvs", "params",
    /// "sharpness"}, ...], "num_local_points"}.
    #[arg(long, value_name = "OUT.json")]
    pub(crate) json: Option<PathBuf>,
}

/// `subdiv eval`: the limit surface at locations.
#[derive(Args)]
pub(crate) struct EvalArgs {
    #[command(flatten)]
    pub(crate) patch: PatchArgs,
    /// Locations, one per line; `#` starts a comment. `--surface patches`: PTEX_FACE U V
    /// (ptex faces as Far::PtexIndices numbers them; U and V in [0, 1]); `--surface bfr`:
    /// FACE U V (a base face and (u, v) in Bfr's parameterization of it).
    #[arg(long, value_name = "LOCATIONS.txt")]
    pub(crate) at: PathBuf,
    /// Also print the first derivatives: x y z dx/du dy/du dz/du dx/dv dy/dv dz/dv.
    #[arg(long)]
    pub(crate) derivatives: bool,
    /// Evaluate the exact limit surface where OpenSubdiv's EvaluateBasis departs from it:
    /// single-crease patches with their sharpness (semi-sharp, as OpenSubdiv's GPU
    /// shaders), derivatives under non-quad faces with respect to the ptex face's own
    /// (u, v). Native engine, `--surface patches` only.
    #[arg(long)]
    pub(crate) exact_limit: bool,
    /// Where locations live: `patches` (ptex faces of the patch table) or `bfr` (base
    /// faces in Bfr's parameterization: FACE U V, U and V over the unit square, the
    /// unit triangle under Loop, or the sub-face tiles of an n-gon).
    #[arg(long, value_name = "KIND", default_value = "patches", value_parser = ["patches", "bfr"])]
    pub(crate) surface: String,
    #[command(flatten)]
    pub(crate) bfr: crate::tessellate::SurfaceArgs,
    /// Output file (`-` or absent: standard output).
    #[arg(short, long, value_name = "OUT.txt")]
    pub(crate) output: Option<PathBuf>,
}

impl PatchArgs {
    fn options(&self) -> Result<PatchOptions, Failure> {
        if self.isolation > 10 {
            return Err(Failure::Usage(format!(
                "--isolation {}: OpenSubdiv isolates 10 levels at most",
                self.isolation
            )));
        }
        if self.mesh.precision != Precision::F64 {
            return Err(Failure::Usage(
                "--precision: patch tables are evaluated in f64".into(),
            ));
        }
        Ok(PatchOptions::new()
            .max_isolation(self.isolation)
            .end_caps(self.end_caps)
            .single_crease_patch(self.single_crease)
            .inf_sharp_patch(self.inf_sharp)
            .double_precision(self.double))
    }

    fn end_cap_name(&self) -> &'static str {
        end_cap_name(self.end_caps)
    }
}

/// How the summaries name an end-cap type.
pub(crate) fn end_cap_name(end_caps: EndCapType) -> &'static str {
    match end_caps {
        EndCapType::None => "no",
        EndCapType::BilinearBasis => "bilinear",
        EndCapType::BSplineBasis => "B-spline",
        EndCapType::GregoryBasis => "Gregory basis",
        EndCapType::LegacyGregory => "legacy Gregory",
    }
}

/// The input refined adaptively, and its patch table, by either engine.
struct Built {
    name: String,
    scheme: subdiv::Scheme,
    mesh: subdiv::Mesh,
    tables: Tables,
}

/// The refinement and the table of the engine asked for.
enum Tables {
    Native {
        refiner: subdiv::refiner::AdaptiveRefiner,
        table: PatchTable,
    },
    #[cfg(feature = "osd")]
    Osd {
        refiner: subdiv::osd::TopologyRefiner,
        table: subdiv::osd::OsdPatchTable,
    },
}

impl Built {
    fn table(&self) -> &PatchTable {
        match &self.tables {
            Tables::Native { table, .. } => table,
            #[cfg(feature = "osd")]
            Tables::Osd { table, .. } => table.table(),
        }
    }

    fn engine(&self) -> &'static str {
        match &self.tables {
            Tables::Native { .. } => "native",
            #[cfg(feature = "osd")]
            Tables::Osd { .. } => "osd",
        }
    }

    /// The limit surface at `locations` (positions, and derivatives when
    /// asked).
    fn evaluate(
        &self,
        locations: &[Location],
        derivatives: Derivatives,
        evaluation: Evaluation,
    ) -> Result<SurfaceSamples, subdiv::Error> {
        let base = self.mesh.flat_positions::<f64>();
        match &self.tables {
            Tables::Native { refiner, table } => {
                let points = refiner.patch_points(table, 3, &base)?;
                subdiv::patches::evaluate_data_as(
                    evaluation,
                    &PatchMap::new(table),
                    table,
                    PatchData::Vertex,
                    &points,
                    3,
                    locations,
                    derivatives,
                )
            }
            #[cfg(feature = "osd")]
            Tables::Osd { refiner, table } => {
                table.evaluate(refiner, 3, &base, locations, derivatives)
            }
        }
    }
}

fn build(args: &PatchArgs) -> Result<Built, Failure> {
    let options = args.options()?;
    let (name, mesh, mesh_options) = crate::args::load(&args.mesh)?;
    let in_input = |e: subdiv::Error| Failure::from(e).in_input(&name);
    let adaptive = options
        .refine_adaptive_options()
        .faces_first(args.mesh.faces_first);
    let tables = match args.engine {
        Engine::Native => {
            let refiner = subdiv::refiner::Refiner::new(&mesh, &mesh_options)
                .and_then(|r| r.refine_adaptive(adaptive, &[]))
                .map_err(in_input)?;
            let table = refiner.patch_table(&options, &[]).map_err(in_input)?;
            Tables::Native { refiner, table }
        }
        #[cfg(feature = "osd")]
        Engine::Osd => {
            let mut refiner =
                subdiv::osd::TopologyRefiner::new(&mesh, &mesh_options).map_err(in_input)?;
            refiner.refine_adaptive(adaptive, &[]).map_err(in_input)?;
            let table = refiner.patch_table(&options, &[]).map_err(in_input)?;
            Tables::Osd { refiner, table }
        }
        #[cfg(not(feature = "osd"))]
        Engine::Osd => return Err(Failure::from(subdiv::Error::OsdUnavailable)),
    };
    Ok(Built {
        name,
        scheme: mesh_options.scheme,
        mesh,
        tables,
    })
}

/// `subdiv patches`.
pub(crate) fn patches(args: &PatchesArgs) -> Result<(), Failure> {
    let b = build(&args.patch)?;
    let t = b.table();
    let arrays: Vec<String> = t
        .arrays
        .iter()
        .map(|a| format!("{} {}", a.patch_type.name(), a.len()))
        .collect();
    println!(
        "{}: {} patches ({}, isolation {}, {} end caps): {} patches in {} arrays: {}; {} local points",
        b.name,
        b.scheme,
        b.engine(),
        args.patch.isolation,
        args.patch.end_cap_name(),
        t.patch_count(),
        t.arrays.len(),
        arrays.join(", "),
        t.local_points
    );
    if let Some(path) = &args.json {
        write_json(path, args.patch.mesh.input.as_deref(), t)?;
    }
    Ok(())
}

fn write_json(
    path: &Path,
    input: Option<&Path>,
    t: &subdiv::patches::PatchTable,
) -> Result<(), Failure> {
    #[derive(serde::Serialize)]
    struct ArrayJson<'a> {
        #[serde(rename = "type")]
        ty: &'static str,
        num_patches: usize,
        cvs: Vec<&'a [u32]>,
        params: Vec<[u32; 2]>,
        sharpness: &'a [f32],
    }
    #[derive(serde::Serialize)]
    struct File<'a> {
        arrays: Vec<ArrayJson<'a>>,
        num_local_points: usize,
    }
    let file = File {
        arrays: t
            .arrays
            .iter()
            .map(|a| ArrayJson {
                ty: a.patch_type.name(),
                num_patches: a.len(),
                cvs: (0..a.len()).map(|p| a.patch_vertices(p)).collect(),
                params: a.params.iter().map(|p| [p.field0, p.field1]).collect(),
                sharpness: &a.sharpness,
            })
            .collect(),
        num_local_points: t.local_points,
    };
    write_output(path, input, |w| {
        let mut w = std::io::BufWriter::new(w);
        serde_json::to_writer(&mut w, &file).map_err(std::io::Error::other)?;
        w.write_all(b"\n")?;
        w.flush()
    })
}

/// The locations of a file: `FACE U V` per line, `#` comments; errors
/// name the file and line. `unit`: U and V must lie in [0, 1] (ptex
/// faces), else only be finite (Bfr's domains are checked per face).
fn read_locations(path: &Path, unit: bool) -> Result<Vec<(usize, Location)>, Failure> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        Failure::Message(format!(
            "{}: cannot read the locations: {e}",
            path.display()
        ))
    })?;
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line_no = i + 1;
        let content = line.split('#').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        let bad = |what: String| Failure::Message(format!("{}:{line_no}: {what}", path.display()));
        let fields: Vec<&str> = content.split_whitespace().collect();
        let [face, u, v] = fields[..] else {
            return Err(bad(format!(
                "expected {} U V, found {} fields",
                if unit { "PTEX_FACE" } else { "FACE" },
                fields.len()
            )));
        };
        let face: u32 = face.parse().map_err(|_| {
            let what = if unit {
                "ptex face index"
            } else {
                "face index"
            };
            bad(format!("'{face}' is not a {what}"))
        })?;
        let coord = |s: &str, name: &str| -> Result<f64, Failure> {
            match s.parse::<f64>() {
                Ok(x) if (0.0..=1.0).contains(&x) || (!unit && x.is_finite()) => Ok(x),
                Ok(x) if unit => Err(bad(format!("{name} = {x} is not in [0, 1]"))),
                Ok(x) => Err(bad(format!("{name} = {x} is not a finite number"))),
                Err(_) => Err(bad(format!("'{s}' is not a number ({name})"))),
            }
        };
        out.push((line_no, (face, coord(u, "u")?, coord(v, "v")?)));
    }
    Ok(out)
}

/// `subdiv eval`.
pub(crate) fn eval(args: &EvalArgs) -> Result<(), Failure> {
    if args.bfr.global {
        return Err(Failure::Usage(
            "--global is for `subdiv tessellate`: `eval --surface bfr` evaluates each \
             face's own surface, as Bfr builds it"
                .into(),
        ));
    }
    if args.exact_limit && args.surface == "bfr" {
        return Err(Failure::Usage(
            "--exact-limit: Bfr's surfaces are the limit already; the option is for \
             --surface patches"
                .into(),
        ));
    }
    if args.exact_limit && args.patch.engine != Engine::Native {
        return Err(Failure::Usage(
            "--exact-limit: OpenSubdiv's EvaluateBasis has no exact-limit mode; \
             use --engine native"
                .into(),
        ));
    }
    if args.surface == "bfr" {
        return eval_bfr(args);
    }
    let locations = read_locations(&args.at, true)?;
    let b = build(&args.patch)?;
    let ptex_faces = b.table().ptex_faces;
    // A location off the mesh or in a hole is an error naming its line.
    let at = |line: usize, what: String| {
        Failure::Message(format!("{}:{line}: {what}", args.at.display()))
    };
    if let Some(&(line, (face, ..))) = locations
        .iter()
        .find(|(_, (face, ..))| *face as usize >= ptex_faces)
    {
        return Err(at(
            line,
            format!(
                "ptex face {face} does not exist ({} has {ptex_faces})",
                b.name
            ),
        ));
    }
    let points: Vec<Location> = locations.iter().map(|&(_, l)| l).collect();
    let derivatives = if args.derivatives {
        Derivatives::First
    } else {
        Derivatives::None
    };
    let evaluation = if args.exact_limit {
        Evaluation::ExactLimit
    } else {
        Evaluation::OpenSubdiv
    };
    let s = match b.evaluate(&points, derivatives, evaluation) {
        Ok(s) => s,
        Err(subdiv::Error::NoPatchAt { face, u, v }) => {
            let line = locations
                .iter()
                .find(|(_, l)| *l == (face, u, v))
                .map_or(0, |&(line, _)| line);
            return Err(at(
                line,
                format!("ptex face {face} at ({u}, {v}) is in a hole: no surface there"),
            ));
        }
        Err(e) => return Err(Failure::from(e).in_input(&b.name)),
    };
    write_samples(args, &s)
}

/// Writes one line per location: x y z, and the first derivatives when asked.
fn write_samples(args: &EvalArgs, s: &SurfaceSamples) -> Result<(), Failure> {
    let path = args.output.clone().unwrap_or_else(|| PathBuf::from("-"));
    write_output(&path, args.patch.mesh.input.as_deref(), |w| {
        let mut w = std::io::BufWriter::new(w);
        let v = &s.values;
        for i in 0..v.point.len() / 3 {
            let mut row: Vec<f64> = v.point[3 * i..3 * i + 3].to_vec();
            if args.derivatives {
                row.extend_from_slice(&v.du[3 * i..3 * i + 3]);
                row.extend_from_slice(&v.dv[3 * i..3 * i + 3]);
            }
            let text: Vec<String> = row.iter().map(|x| format!("{x:.16e}")).collect();
            writeln!(w, "{}", text.join(" "))?;
        }
        w.flush()
    })
}

/// `subdiv eval --surface bfr`: base faces in Bfr's parameterization.
fn eval_bfr(args: &EvalArgs) -> Result<(), Failure> {
    let locations = read_locations(&args.at, false)?;
    let (name, mesh, options) = crate::args::load(&args.patch.mesh)?;
    // Locations are evaluated on the surfaces Bfr itself builds, face by
    // face (index-exact with OpenSubdiv's Bfr): the native default.
    let surfaces = args.bfr.build(args.patch.engine, &name, &mesh, &options)?;
    let derivatives = if args.derivatives {
        Derivatives::First
    } else {
        Derivatives::None
    };
    let at = |line: usize, what: String| {
        Failure::Message(format!("{}:{line}: {what}", args.at.display()))
    };
    let mut out = SurfaceSamples {
        width: 3,
        ..SurfaceSamples::default()
    };
    // Consecutive locations on one face are evaluated together.
    let mut i = 0;
    while i < locations.len() {
        let face = locations[i].1.0 as usize;
        let run = locations[i..]
            .iter()
            .take_while(|(_, l)| l.0 as usize == face)
            .count();
        let (line, _) = locations[i];
        if face >= mesh.face_count() {
            return Err(at(
                line,
                format!(
                    "face {face} does not exist ({name} has {})",
                    mesh.face_count()
                ),
            ));
        }
        if !surfaces.has_surface(face) {
            let why = if mesh.holes.contains(&(face as u32)) {
                "a hole".to_string()
            } else {
                "Bfr finds no limit neighbourhood for it: a degenerate face, a face on a \
                 boundary under --boundary none, or under the Loop scheme a face beside a \
                 non-triangle"
                    .to_string()
            };
            return Err(at(
                line,
                format!("face {face} has no limit surface ({why})"),
            ));
        }
        // Every engine's locations checked against the face's domain here,
        // each refusal naming its line.
        let param = subdiv::bfr::Parameterization::new(surfaces.scheme(), mesh.face(face).len())
            .map_err(|e| at(line, e.to_string()))?;
        if let Some(&(line, (_, u, v))) = locations[i..i + run]
            .iter()
            .find(|(_, l)| !param.contains([l.1, l.2], 1e-9))
        {
            let e = subdiv::Error::OffFace {
                face,
                u,
                v,
                domain: param.domain(),
            };
            return Err(at(line, e.to_string()));
        }
        let coords: Vec<[f64; 2]> = locations[i..i + run]
            .iter()
            .map(|(_, l)| [l.1, l.2])
            .collect();
        let s = surfaces
            .evaluate(face, &coords, derivatives)
            .map_err(|e| match e {
                subdiv::Error::OffFace { u, v, .. } => {
                    let line = locations[i..i + run]
                        .iter()
                        .find(|(_, l)| l.1 == u && l.2 == v)
                        .map_or(line, |&(line, _)| line);
                    at(line, e.to_string())
                }
                e => Failure::from(e).in_input(&name),
            })?;
        out.values.point.extend_from_slice(&s.values.point);
        out.values.du.extend_from_slice(&s.values.du);
        out.values.dv.extend_from_slice(&s.values.dv);
        i += run;
    }
    write_samples(args, &out)
}
