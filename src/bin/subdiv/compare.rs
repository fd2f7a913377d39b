//! `subdiv compare`: both engines, level by level.

use clap::Args;
use subdiv::{Engine, Error, Request};

use crate::Failure;
use crate::adaptive::AdaptiveArgs;
use crate::args::{MeshArgs, SchemeArg, load_all, parse_levels, parse_tolerance};

#[derive(Args)]
pub(crate) struct CompareArgs {
    #[command(flatten)]
    pub(crate) mesh: MeshArgs,
    /// Levels to compare: `A..B` (inclusive) or a single level.
    #[arg(long, default_value = "1..4", value_parser = parse_levels, conflicts_with = "adaptive")]
    pub(crate) levels: (u32, u32),
    #[command(flatten)]
    pub(crate) adaptive: AdaptiveArgs,
    /// Largest accepted deviation, relative to the bounding-box diagonal.
    #[arg(long, default_value = "1e-6", allow_negative_numbers = true, value_parser = parse_tolerance)]
    pub(crate) tolerance: f64,
    /// Print the report as JSON.
    #[arg(long)]
    pub(crate) json: bool,
    /// Compare the engines' patch tables (patch by patch) and the limit surface
    /// each evaluates at a grid of locations on every ptex face; isolation from
    /// --adaptive N (4 without).
    #[arg(long, conflicts_with = "levels")]
    pub(crate) patches: bool,
    /// End caps of the compared patch tables (with --patches): none, bilinear,
    /// bspline, gregory-basis (OpenSubdiv's default) or legacy-gregory.
    #[arg(long, value_name = "TYPE", default_value = "gregory-basis", requires = "patches",
          value_parser = crate::args::parse::<subdiv::patches::EndCapType>)]
    pub(crate) end_caps: subdiv::patches::EndCapType,
}

/// One level of `subdiv compare`, as printed and as JSON.
#[derive(serde::Serialize)]
pub(crate) struct CompareRow {
    pub(crate) level: u32,
    pub(crate) native_counts: [usize; 4],
    pub(crate) osd_counts: [usize; 4],
    pub(crate) first_differing_face: Option<usize>,
    pub(crate) topology_equal: bool,
    pub(crate) max_abs_deviation: f64,
    pub(crate) max_rel_deviation: f64,
    pub(crate) worst_vertex: Option<usize>,
    pub(crate) fvar_deviation: f64,
    pub(crate) agrees: bool,
}

#[derive(serde::Serialize)]
pub(crate) struct CompareReport {
    pub(crate) input: String,
    pub(crate) options: String,
    pub(crate) precision: &'static str,
    pub(crate) tolerance: f64,
    pub(crate) levels: Vec<CompareRow>,
    pub(crate) agrees: bool,
}

pub(crate) fn compare(args: &CompareArgs) -> Result<(), Failure> {
    if args.mesh.scheme == Some(SchemeArg::DooSabin) {
        return Err(Failure::Unavailable(
            "compare needs both engines and OpenSubdiv has no Doo-Sabin scheme; use `subdiv refine --scheme doo-sabin`".into(),
        ));
    }
    if args.patches {
        #[cfg(feature = "osd")]
        return crate::compare_patches::compare_patches(args);
        #[cfg(not(feature = "osd"))]
        return Err(Failure::from(Error::OsdUnavailable));
    }
    if let Some(level) = args.adaptive.adaptive {
        return crate::adaptive::compare_adaptive(args, level);
    }
    let inputs = load_all(&args.mesh)?;
    let usd = args.mesh.input.as_deref().is_some_and(crate::args::is_usd);
    if inputs.is_empty() {
        return Err(Failure::Message(format!(
            "{}: no subdivision mesh to compare (see the notes above)",
            args.mesh
                .input
                .as_deref()
                .map_or(String::new(), |p| p.display().to_string())
        )));
    }
    let mut reports = Vec::with_capacity(inputs.len());
    for input in &inputs {
        reports.push(compare_one(args, &input.name, &input.mesh, &input.options)?);
    }
    let agrees = reports.iter().all(|r| r.agrees);
    if args.json {
        // A USD stage gives a list, one report per prim.
        let text = if usd {
            serde_json::to_string_pretty(&reports)
        } else {
            serde_json::to_string_pretty(&reports[0])
        }
        .map_err(|e| Failure::Message(format!("cannot encode the report: {e}")))?;
        outln!("{text}");
    } else {
        for report in &reports {
            print_report(report, args.tolerance);
        }
        if reports.len() > 1 {
            let differ = reports.iter().filter(|r| !r.agrees).count();
            outln!(
                "{} meshes compared: {}",
                reports.len(),
                match differ {
                    0 => "the engines agree on every one".to_string(),
                    n => format!("the engines DIFFER on {n}"),
                }
            );
        }
    }
    if agrees { Ok(()) } else { Err(Failure::Differ) }
}

/// Both engines on one mesh, level by level.
fn compare_one(
    args: &CompareArgs,
    name: &str,
    mesh: &subdiv::Mesh,
    options: &subdiv::Options,
) -> Result<CompareReport, Failure> {
    let (first, last) = args.levels;
    // Every error from here on names the input (unless it names its own file).
    let refine = || -> Result<_, Error> {
        subdiv::check_level(mesh, options, last)?;
        subdiv::check_precision(mesh, args.mesh.precision)?;
        let request = Request::new(last)
            .faces_first(args.mesh.faces_first)
            .precision(args.mesh.precision);
        let native = Engine::Native.refine(mesh, options, request)?;
        let osd = Engine::Osd.refine(mesh, options, request)?;
        Ok((native, osd))
    };
    let (native, osd) = refine().map_err(|e| Failure::from(e).in_input(name))?;
    let rows: Vec<CompareRow> = subdiv::compare::compare(&native, &osd)
        .into_iter()
        .filter(|c| c.level >= first)
        .map(|c| CompareRow {
            level: c.level,
            native_counts: c.counts[0],
            osd_counts: c.counts[1],
            first_differing_face: c.first_face_difference,
            topology_equal: c.topology_equal(),
            max_abs_deviation: c.max_position_deviation,
            max_rel_deviation: c.relative_position_deviation,
            worst_vertex: c.worst_vertex,
            fvar_deviation: c.max_fvar_deviation,
            agrees: c.agrees(args.tolerance),
        })
        .collect();
    let agrees = rows.iter().all(|r| r.agrees);
    Ok(CompareReport {
        input: name.to_string(),
        options: describe_options(options, args.mesh.faces_first),
        precision: args.mesh.precision.name(),
        tolerance: args.tolerance,
        levels: rows,
        agrees,
    })
}

/// One mesh's comparison as text.
fn print_report(report: &CompareReport, tolerance: f64) {
    outln!(
        "{}: {} ({}), tolerance {:e} of the bounding-box diagonal",
        report.input,
        report.options,
        report.precision,
        tolerance
    );
    outln!(
        "level  vertices (native/osd)  faces (native/osd)  first diff face  max abs dev  max rel dev  fvar dev  result"
    );
    for r in &report.levels {
        outln!(
            "{:>5}  {:>21}  {:>18}  {:>15}  {:>11.3e}  {:>11.3e}  {:>8.2e}  {}",
            r.level,
            format!("{}/{}", r.native_counts[0], r.osd_counts[0]),
            format!("{}/{}", r.native_counts[2], r.osd_counts[2]),
            r.first_differing_face
                .map_or("-".to_string(), |f| f.to_string()),
            r.max_abs_deviation,
            r.max_rel_deviation,
            r.fvar_deviation,
            if r.agrees { "ok" } else { "DIFFERENT" }
        );
    }
    outln!(
        "{}",
        if report.agrees {
            "the engines agree"
        } else {
            "the engines DIFFER"
        }
    );
}

/// The options a comparison ran with, as its report names them.
pub(crate) fn describe_options(options: &subdiv::Options, faces_first: bool) -> String {
    format!(
        "{} boundary={} fvar={} creasing={} triangles={}{}",
        options.scheme,
        options.boundary,
        options.fvar,
        options.creasing,
        options.triangles,
        if faces_first { " faces-first" } else { "" }
    )
}
