//! `refine --adaptive` and `compare --adaptive`: feature-adaptive refinement
//! (OpenSubdiv's `RefineAdaptive`) with either engine, its level counts, its
//! levels as JSON, and the two engines compared table by table.

use clap::Args;
use glam::DVec3;
use std::io::Write as _;
use std::path::Path;
use std::time::Instant;
use subdiv::compare::{AdaptiveLevel, AdaptiveLevelComparison};
use subdiv::{AdaptiveOptions, Engine, Error, LevelTopology, Mesh, Options};

use crate::Failure;
use crate::args::parse_level;
use crate::output::write_output;

/// The adaptive refinement's flags, shared by `refine` and `compare`.
#[derive(Args)]
pub(crate) struct AdaptiveArgs {
    /// Refine feature-adaptively (OpenSubdiv's RefineAdaptive) to isolation level N
    /// (0..=10) instead of uniformly. Conflicts with --precision (positions are
    /// interpolated in f64); with `refine`, also with --level, --limit and -o (a
    /// sparse deepest level is no closed mesh: use --levels-json); with `compare`,
    /// with --levels.
    #[arg(long, value_name = "N", value_parser = parse_level, allow_negative_numbers = true,
          conflicts_with = "precision")]
    pub(crate) adaptive: Option<u32>,
    /// Secondary level (0..=15, default 15): below it, fewer features are isolated.
    #[arg(long, value_name = "M", value_parser = parse_secondary, requires = "adaptive",
          allow_negative_numbers = true)]
    pub(crate) secondary: Option<u32>,
    /// Leave faces with a single semi-sharp crease unrefined (useSingleCreasePatch).
    #[arg(long, requires = "adaptive")]
    pub(crate) single_crease: bool,
    /// Leave infinitely sharp features that patches represent unrefined (useInfSharpPatch).
    #[arg(long, requires = "adaptive")]
    pub(crate) inf_sharp: bool,
    /// Also isolate the features of non-linear face-varying channels (considerFVarChannels).
    #[arg(long, requires = "adaptive")]
    pub(crate) consider_fvar: bool,
    /// Refine only around these base faces at the first level (all when absent).
    #[arg(
        long,
        value_name = "I,J,...",
        value_delimiter = ',',
        requires = "adaptive"
    )]
    pub(crate) select_faces: Vec<u32>,
}

/// `--secondary`: 0 to 15 (OpenSubdiv's 4-bit field).
fn parse_secondary(s: &str) -> Result<u32, String> {
    match s.trim().parse::<i64>() {
        Ok(l) if (0..=15).contains(&l) => Ok(l as u32),
        Ok(l) => Err(format!("the secondary level is 0 to 15; {l} is not")),
        Err(_) => Err(format!("'{s}' is not a level (0 to 15)")),
    }
}

impl AdaptiveArgs {
    /// The adaptive options for isolation `level`.
    pub(crate) fn options(&self, level: u32, faces_first: bool) -> AdaptiveOptions {
        AdaptiveOptions::new(level)
            .secondary(self.secondary.unwrap_or(15))
            .single_crease_patch(self.single_crease)
            .inf_sharp_patch(self.inf_sharp)
            .consider_fvar(self.consider_fvar)
            .faces_first(faces_first)
    }

    /// Refuses a selected face the mesh does not have (a usage error, naming it).
    pub(crate) fn check_selected_faces(&self, name: &str, mesh: &Mesh) -> Result<(), Failure> {
        let count = mesh.face_count();
        match self.select_faces.iter().find(|&&f| f as usize >= count) {
            Some(f) => Err(Failure::Usage(format!(
                "--select-faces: face {f} does not exist: {name} has {count} faces (0 to {})",
                count.saturating_sub(1)
            ))),
            None => Ok(()),
        }
    }

    /// The options as the summary and `compare` print them.
    pub(crate) fn describe(&self, level: u32) -> String {
        let mut s = format!("adaptive level {level}");
        if let Some(m) = self.secondary {
            s += &format!(", secondary {m}");
        }
        for (on, flag) in [
            (self.single_crease, "single-crease"),
            (self.inf_sharp, "inf-sharp"),
            (self.consider_fvar, "consider-fvar"),
        ] {
            if on {
                s += ", ";
                s += flag;
            }
        }
        if !self.select_faces.is_empty() {
            s += &format!(", {} selected faces", self.select_faces.len());
        }
        s
    }
}

/// The levels of an adaptive refinement and their positions, from one engine.
pub(crate) struct Levels {
    pub(crate) topology: Vec<LevelTopology>,
    pub(crate) positions: Vec<Vec<DVec3>>,
}

/// Refines `mesh` adaptively with `engine` and interpolates its positions
/// level by level in f64.
pub(crate) fn refine_levels(
    engine: Engine,
    mesh: &Mesh,
    options: &Options,
    adaptive: AdaptiveOptions,
    faces: &[u32],
) -> Result<Levels, Error> {
    match engine {
        Engine::Native => {
            let r =
                subdiv::refiner::Refiner::new(mesh, options)?.refine_adaptive(adaptive, faces)?;
            Ok(Levels {
                topology: (0..=r.max_level())
                    .map(|l| r.level(l))
                    .collect::<Result<_, _>>()?,
                positions: r.refine_positions(&mesh.positions)?,
            })
        }
        #[cfg(feature = "osd")]
        Engine::Osd => {
            let mut r = subdiv::osd::TopologyRefiner::new(mesh, options)?;
            r.refine_adaptive(adaptive, faces)?;
            let mut flat: Vec<f64> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
            let mut levels = Levels {
                topology: Vec::new(),
                positions: Vec::new(),
            };
            for l in 0..=r.max_level() {
                if l > 0 {
                    flat = r.interpolate(l, 3, &flat)?;
                }
                levels.topology.push(r.level(l)?);
                levels.positions.push(
                    flat.chunks_exact(3)
                        .map(|c| DVec3::new(c[0], c[1], c[2]))
                        .collect(),
                );
            }
            Ok(levels)
        }
        #[allow(unreachable_patterns)]
        _ => Err(Error::OsdUnavailable),
    }
}

/// The note on a refinement that stopped above the isolation level.
pub(crate) fn stop_note(deepest: u32, level: u32) -> String {
    if deepest < level {
        format!(
            "; stopped at level {deepest} of {level}: level {} selected no face",
            deepest + 1
        )
    } else {
        String::new()
    }
}

/// One level of `--levels-json`.
#[derive(serde::Serialize)]
struct LevelJson<'a> {
    vertices: usize,
    edges: usize,
    faces: usize,
    face_vertices: Vec<&'a [u32]>,
    holes: Vec<usize>,
    positions: &'a [[f64; 3]],
}

/// `--levels-json`: every level's counts, faces (holes included; `holes`
/// lists them) and positions, numbers in their shortest round-trip form.
pub(crate) fn write_levels_json(
    path: &Path,
    input: Option<&Path>,
    levels: &Levels,
) -> Result<(), Failure> {
    for (l, p) in levels.positions.iter().enumerate() {
        if let Some(v) = p.iter().position(|p| !p.is_finite()) {
            return Err(Failure::Message(format!(
                "vertex {v} of level {l} is not finite: JSON cannot hold it"
            )));
        }
    }
    #[derive(serde::Serialize)]
    struct File<'a> {
        levels: Vec<LevelJson<'a>>,
    }
    let file = File {
        levels: levels
            .topology
            .iter()
            .zip(&levels.positions)
            .map(|(t, p)| LevelJson {
                vertices: t.vertex_count,
                edges: t.edge_count,
                faces: t.face_count(),
                face_vertices: t.faces().collect(),
                holes: (0..t.face_count()).filter(|&f| t.face_holes[f]).collect(),
                positions: bytemuck::cast_slice(p),
            })
            .collect(),
    };
    write_output(path, input, |w| {
        let mut w = std::io::BufWriter::new(w);
        serde_json::to_writer(&mut w, &file).map_err(std::io::Error::other)?;
        w.write_all(b"\n")?;
        w.flush()
    })
}

/// `refine --adaptive N`: the summary of every level, and `--levels-json`.
pub(crate) fn refine_adaptive(
    args: &crate::refine::RefineArgs,
    level: u32,
    name: &str,
    mesh: &Mesh,
    options: &Options,
) -> Result<(), Failure> {
    let adaptive = args.adaptive.options(level, args.mesh.faces_first);
    let start = Instant::now();
    let levels = refine_levels(
        args.engine,
        mesh,
        options,
        adaptive,
        &args.adaptive.select_faces,
    )?;
    let seconds = start.elapsed().as_secs_f64();
    let deepest = levels.topology.len().saturating_sub(1) as u32;
    let join = |f: fn(&LevelTopology) -> usize| {
        levels
            .topology
            .iter()
            .map(|t| f(t).to_string())
            .collect::<Vec<_>>()
            .join("→")
    };
    let line = format!(
        "{name}: {} {} ({}, f64): levels 0..{deepest}: vertices {}, edges {}, faces {}{}; {:.3} ms",
        options.scheme,
        args.adaptive.describe(level),
        args.engine,
        join(|t| t.vertex_count),
        join(|t| t.edge_count),
        join(LevelTopology::face_count),
        stop_note(deepest, level),
        seconds * 1e3
    );
    match &args.levels_json {
        Some(path) => {
            write_levels_json(path, args.mesh.input.as_deref(), &levels)?;
            // The JSON on standard output: the summary goes to standard error.
            if path == Path::new("-") {
                eprintln!("{line}");
            } else {
                outln!("{line}");
            }
        }
        None => outln!("{line}"),
    }
    Ok(())
}

/// One level of `compare --adaptive`, as printed and as JSON.
#[derive(serde::Serialize)]
struct AdaptiveRow {
    level: u32,
    /// Vertices, edges, faces.
    native_counts: [usize; 3],
    osd_counts: [usize; 3],
    /// `table[index]` of the first difference in topology, relations or child maps.
    first_difference: Option<String>,
    positions_identical: bool,
    first_differing_vertex: Option<usize>,
    max_abs_deviation: f64,
    max_rel_deviation: f64,
    worst_vertex: Option<usize>,
    agrees: bool,
}

/// Collects one engine's adaptive levels for the comparison.
fn engine_levels(
    engine: Engine,
    mesh: &Mesh,
    options: &Options,
    adaptive: AdaptiveOptions,
    faces: &[u32],
) -> Result<Vec<AdaptiveLevel>, Error> {
    match engine {
        Engine::Native => subdiv::refiner::Refiner::new(mesh, options)?
            .refine_adaptive(adaptive, faces)?
            .adaptive_levels(&mesh.positions),
        #[cfg(feature = "osd")]
        Engine::Osd => {
            let mut r = subdiv::osd::TopologyRefiner::new(mesh, options)?;
            r.refine_adaptive(adaptive, faces)?;
            r.adaptive_levels(&mesh.positions)
        }
        #[allow(unreachable_patterns)]
        _ => Err(Error::OsdUnavailable),
    }
}

/// `compare --adaptive N`: both engines' adaptive refinements, level by
/// level and table by table; exits 3 (`Failure::Differ`) when they differ.
pub(crate) fn compare_adaptive(
    args: &crate::compare::CompareArgs,
    level: u32,
) -> Result<(), Failure> {
    let (name, mesh, options) = crate::args::load(&args.mesh)?;
    args.adaptive.check_selected_faces(&name, &mesh)?;
    let adaptive = args.adaptive.options(level, args.mesh.faces_first);
    let faces = &args.adaptive.select_faces;
    let both = || -> Result<_, Error> {
        // OpenSubdiv first: a build without it says so before any work.
        let osd = engine_levels(Engine::Osd, &mesh, &options, adaptive, faces)?;
        let native = engine_levels(Engine::Native, &mesh, &options, adaptive, faces)?;
        Ok((native, osd))
    };
    let (native, osd) = both().map_err(|e| Failure::from(e).in_input(&name))?;
    let rows: Vec<AdaptiveRow> = subdiv::compare::compare_adaptive(&native, &osd)
        .iter()
        .map(|c: &AdaptiveLevelComparison| {
            let diag = osd
                .get(c.level as usize)
                .map_or(0.0, |l| subdiv::compare::bbox_diagonal(&l.positions));
            let abs = c.positions.max_deviation;
            let rel = if diag > 0.0 { abs / diag } else { abs };
            AdaptiveRow {
                level: c.level,
                native_counts: c.counts[0],
                osd_counts: c.counts[1],
                first_difference: c.first_difference.as_ref().map(ToString::to_string),
                positions_identical: c.positions.identical(),
                first_differing_vertex: c.positions.first_difference,
                max_abs_deviation: abs,
                max_rel_deviation: rel,
                worst_vertex: c.positions.worst,
                agrees: c.topology_equal() && rel <= args.tolerance,
            }
        })
        .collect();
    let agrees = rows.iter().all(|r| r.agrees);
    let identical = rows.iter().all(|r| r.agrees && r.positions_identical);
    let deepest = |l: &[AdaptiveLevel]| l.len().saturating_sub(1) as u32;
    let options_text = format!(
        "{}, {}",
        crate::compare::describe_options(&options, args.mesh.faces_first),
        args.adaptive.describe(level)
    );
    if args.json {
        #[derive(serde::Serialize)]
        struct Report<'a> {
            input: &'a str,
            options: &'a str,
            precision: &'a str,
            tolerance: f64,
            native_deepest_level: u32,
            osd_deepest_level: u32,
            levels: Vec<AdaptiveRow>,
            identical: bool,
            agrees: bool,
        }
        let report = Report {
            input: &name,
            options: &options_text,
            precision: "f64",
            tolerance: args.tolerance,
            native_deepest_level: deepest(&native),
            osd_deepest_level: deepest(&osd),
            levels: rows,
            identical,
            agrees,
        };
        let text = serde_json::to_string_pretty(&report)
            .map_err(|e| Failure::Message(format!("cannot encode the report: {e}")))?;
        outln!("{text}");
    } else {
        outln!(
            "{name}: {options_text} (f64), tolerance {:e} of the bounding-box diagonal{}",
            args.tolerance,
            stop_note(deepest(&native).min(deepest(&osd)), level)
        );
        outln!(
            "face-varying channels are not compared (the native engine does not refine them sparsely yet)"
        );
        outln!(
            "level  vertices (native/osd)  edges (native/osd)  faces (native/osd)  first difference  positions  result"
        );
        for r in &rows {
            let positions = match (r.positions_identical, r.first_differing_vertex) {
                (true, _) => "bit-identical".to_string(),
                (false, Some(v)) => format!(
                    "vertex {v} differs; max abs {:.3e} (vertex {}), rel {:.3e}",
                    r.max_abs_deviation,
                    r.worst_vertex.map_or("-".to_string(), |w| w.to_string()),
                    r.max_rel_deviation
                ),
                (false, None) => "differ".to_string(),
            };
            outln!(
                "{:>5}  {:>21}  {:>18}  {:>18}  {:>16}  {}  {}",
                r.level,
                format!("{}/{}", r.native_counts[0], r.osd_counts[0]),
                format!("{}/{}", r.native_counts[1], r.osd_counts[1]),
                format!("{}/{}", r.native_counts[2], r.osd_counts[2]),
                r.first_difference.as_deref().unwrap_or("-"),
                positions,
                if r.agrees { "ok" } else { "DIFFERENT" }
            );
        }
        if let Some(r) = rows.iter().find(|r| !r.agrees) {
            match &r.first_difference {
                Some(d) => outln!("first difference: level {}, {d}", r.level),
                None => outln!(
                    "first difference: level {}, positions [{}] (the largest at vertex {})",
                    r.level,
                    r.first_differing_vertex
                        .map_or("-".to_string(), |v| v.to_string()),
                    r.worst_vertex.map_or("-".to_string(), |w| w.to_string())
                ),
            }
        }
        outln!(
            "{}",
            match (agrees, identical) {
                (true, true) => "the engines agree (bit for bit)",
                (true, false) => "the engines agree (within the tolerance)",
                _ => "the engines DIFFER",
            }
        );
    }
    if agrees { Ok(()) } else { Err(Failure::Differ) }
}
