//! `subdiv curve`: refine or flatten a curve given as points, or (with
//! `--knots`, in [`knots`]) insert knots into a B-spline or NURBS curve and
//! sample it.

mod knots;

use clap::Args;
use std::path::{Path, PathBuf};
use subdiv::curve::{CurveScheme, Point};

use crate::Failure;
use crate::output::write_output;

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum CurveSchemeArg {
    /// Chaikin's corner cutting (the quadratic B-spline).
    Chaikin,
    /// Uniform B-spline refinement of degree --degree (the averaging algorithm).
    Bspline,
    /// The interpolating four-point scheme.
    FourPoint,
    /// Jarek's curve, half way between the cubic B-spline and the four-point scheme.
    Jarek,
}

#[derive(Args)]
#[command(after_help = "\
Examples:
  subdiv curve polygon.txt --scheme chaikin --level 3 -o chaikin.svg
  subdiv curve points.txt --degree 3 --knots=-3,-2,-1,0,1,2,3,4,5,6 --insert 2.8
  subdiv curve square.txt --degree 2 --knots 0,0,0,1,1,2,2,3,3,4,4,4 \\
               --weights 1,0.7071,1,0.7071,1,0.7071,1,0.7071,1 --samples 100
  subdiv curve square.txt --degree 2 --knots 0,0,0,1,1,2,2,3,3,4,4,4 [...] -o circle.svg

With --knots and neither --insert nor --samples, the control polygon is written
as given, after its `# knots` line. Errors exit 1 and name the option; options
that do not go together are usage errors (exit 2).")]
pub(crate) struct CurveArgs {
    /// Input points: one per line, 2 or 3 numbers separated by spaces; `#` starts a comment.
    #[arg(value_name = "INPUT.txt")]
    pub(crate) input: PathBuf,
    /// Curve scheme (not with --knots).
    #[arg(long, value_enum, required_unless_present = "knots")]
    pub(crate) scheme: Option<CurveSchemeArg>,
    /// B-spline degree: 1 to 15 with --scheme bspline [default: 3]; the
    /// degree of the curve with --knots (required there).
    #[arg(long, value_name = "D", value_parser = parse_degree)]
    pub(crate) degree: Option<usize>,
    /// Four-point tension w (--scheme four-point only) [default: 1/16]; any finite
    /// value; 0 < w < 0.15 gives smooth curves.
    #[arg(long, value_name = "W", allow_negative_numbers = true)]
    pub(crate) tension: Option<f64>,
    /// The polygon is closed (its last point joins its first); with --knots,
    /// the curve is periodic and --knots gives the n + 1 break points s0..sn of
    /// one period for its n distinct points.
    #[arg(long)]
    pub(crate) closed: bool,
    /// Refinement levels [default: 1].
    #[arg(long, value_name = "N", conflicts_with = "tolerance")]
    pub(crate) level: Option<u32>,
    /// Flatten the limit curve (chaikin, bspline) into a polyline within EPS of it.
    #[arg(long, value_name = "EPS", allow_negative_numbers = true, value_parser = parse_eps)]
    pub(crate) tolerance: Option<f64>,
    /// The knots of a B-spline or NURBS curve of degree --degree: n + d + 2
    /// non-decreasing numbers for n + 1 points, comma-separated; negative
    /// values as `--knots=-3,-2,-1,0,...` or `--knots -3,-2,-1,0,...`.
    #[arg(
        long,
        value_name = "K0,K1,...",
        value_parser = knots::parse_list,
        allow_hyphen_values = true,
        requires = "degree",
        conflicts_with_all = ["scheme", "level", "tolerance", "tension"],
        help_heading = "B-splines and NURBS (--knots)"
    )]
    pub(crate) knots: Option<knots::NumberList>,
    /// With --knots: the weights of a rational curve (NURBS), one positive
    /// number per control point (per distinct point with --closed).
    #[arg(
        long,
        value_name = "W0,W1,...",
        value_parser = knots::parse_list,
        allow_hyphen_values = true,
        requires = "knots",
        help_heading = "B-splines and NURBS (--knots)"
    )]
    pub(crate) weights: Option<knots::NumberList>,
    /// With --knots: insert these knots, each once, in order (a repeated value
    /// inserts again), and write the new control polygon after a `# knots`
    /// line (and a `# weights` line for a rational curve).
    #[arg(
        long,
        value_name = "T1,T2,...",
        value_parser = knots::parse_list,
        allow_hyphen_values = true,
        requires = "knots",
        conflicts_with = "samples",
        help_heading = "B-splines and NURBS (--knots)"
    )]
    pub(crate) insert: Option<knots::NumberList>,
    /// With --knots: write N ≥ 2 curve points at parameters spaced uniformly
    /// over the domain [k_D, k_{m-D}], both ends included.
    #[arg(
        long,
        value_name = "N",
        requires = "knots",
        help_heading = "B-splines and NURBS (--knots)"
    )]
    pub(crate) samples: Option<usize>,
    /// Output: `.svg` draws the control polygon and each level in its own
    /// colour (with --knots: the control polygon, the curve and its knots), any
    /// other name gets the points as text; without it the text goes to stdout.
    #[arg(short, long, value_name = "OUT.txt|OUT.svg")]
    pub(crate) output: Option<PathBuf>,
}

/// `--degree`: 1 or more (the schemes' own ceiling is checked with the scheme).
fn parse_degree(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(0) => Err("a degree is 1 or more; 0 is not".into()),
        Ok(d) => Ok(d),
        Err(_) => Err(format!("'{s}' is not a degree (1 or more)")),
    }
}

/// `--tolerance` of `subdiv curve`: a finite distance greater than 0.
fn parse_eps(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(t) if t.is_finite() && t > 0.0 => Ok(t),
        Ok(t) => Err(format!(
            "the tolerance must be a finite distance greater than 0; {t} is not"
        )),
        Err(_) => Err(format!("'{s}' is not a number")),
    }
}

/// `subdiv curve`: refine or flatten a curve given as one point per line.
pub(crate) fn curve(args: &CurveArgs) -> Result<(), Failure> {
    let message = |e: &dyn std::fmt::Display| Failure::Message(e.to_string());
    let Some(scheme_arg) = args.scheme else {
        return knots::curve(args);
    };
    let scheme = match scheme_arg {
        CurveSchemeArg::Chaikin => CurveScheme::Chaikin,
        CurveSchemeArg::Bspline => CurveScheme::BSpline {
            degree: args.degree.unwrap_or(3),
        },
        CurveSchemeArg::FourPoint => CurveScheme::FourPoint {
            tension: args.tension.unwrap_or(subdiv::curve::DEFAULT_TENSION),
        },
        CurveSchemeArg::Jarek => CurveScheme::Jarek,
    };
    if args.degree.is_some() && scheme_arg != CurveSchemeArg::Bspline {
        return Err(Failure::Usage(format!(
            "--degree applies to --scheme bspline only ({} is not a B-spline of a chosen degree)",
            scheme.name()
        )));
    }
    if args.tension.is_some() && scheme_arg != CurveSchemeArg::FourPoint {
        return Err(Failure::Usage(
            "--tension applies to --scheme four-point only".into(),
        ));
    }
    // A degree or tension out of range, or --tolerance with a scheme that
    // has no closed-form limit, is a misused option (exit 2).
    let usage = |e: subdiv::curve::CurveError| Failure::Usage(e.to_string());
    scheme.check().map_err(usage)?;
    if args.tolerance.is_some() && scheme.limit_degree().is_none() {
        return Err(usage(subdiv::curve::CurveError::NoClosedFormLimit {
            scheme: scheme.name(),
        }));
    }
    let file = subdiv::io::points::read_points(&args.input).map_err(|e| message(&e))?;
    file.require(&scheme, args.closed)
        .map_err(|e| message(&e))?;
    match &file.points {
        subdiv::io::points::Points::Planar(p) => run_curve(p, scheme, args),
        subdiv::io::points::Points::Spatial(p) => run_curve(p, scheme, args),
    }
}

pub(crate) fn run_curve<P: Point>(
    points: &[P],
    scheme: CurveScheme,
    args: &CurveArgs,
) -> Result<(), Failure> {
    let fail =
        |e: subdiv::curve::CurveError| Failure::Message(format!("{}: {e}", args.input.display()));
    let shape = if args.closed { "closed" } else { "open" };
    let input_name = args.input.file_name().map_or_else(
        || args.input.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    // The polygons to draw (label, points, closed) and the result.
    let (layers, title): (Vec<(String, Vec<P>, bool)>, String) = match args.tolerance {
        Some(eps) => {
            let line = subdiv::curve::flatten(points, scheme, args.closed, eps).map_err(fail)?;
            (
                vec![
                    (
                        format!("control polygon ({} points)", points.len()),
                        points.to_vec(),
                        args.closed,
                    ),
                    (
                        format!(
                            "limit curve flattened to {eps:e} ({} points)",
                            line.points.len()
                        ),
                        line.points,
                        args.closed,
                    ),
                ],
                format!("{input_name}: {scheme}, {shape}, flattened to {eps:e}"),
            )
        }
        None => {
            let levels = args.level.unwrap_or(1);
            let all =
                subdiv::curve::refine_levels(points, scheme, args.closed, levels).map_err(fail)?;
            (
                all.into_iter()
                    .enumerate()
                    .map(|(k, l)| {
                        let label = if k == 0 {
                            format!("control polygon ({} points)", l.len())
                        } else {
                            format!("level {k} ({} points)", l.len())
                        };
                        (label, l, args.closed)
                    })
                    .collect(),
                format!(
                    "{input_name}: {scheme}, {shape}, {levels} level{}",
                    if levels == 1 { "" } else { "s" }
                ),
            )
        }
    };
    let result = layers.last().map_or(&[][..], |l| l.1.as_slice());
    match &args.output {
        Some(path) if is_svg(path) => {
            let drawn: Vec<subdiv::io::svg::Layer<'_, P>> = layers
                .iter()
                .map(|(label, points, closed)| subdiv::io::svg::Layer {
                    label,
                    points,
                    closed: *closed,
                })
                .collect();
            let svg = subdiv::io::svg::curve_svg(
                &title,
                &drawn,
                &subdiv::io::svg::Projection::for_points::<P>(),
            );
            write_output(path, Some(&args.input), |w| w.write_all(svg.as_bytes()))?;
        }
        _ => write_text(
            args.output.as_deref(),
            &args.input,
            &subdiv::io::points::format_points(result),
        )?,
    }
    Ok(())
}

/// Whether `path` names an SVG file (by its extension).
pub(crate) fn is_svg(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("svg"))
}

/// Writes `text` to `output` (atomically, or stdout for `-`), or to stdout
/// without one; `input` is refused as the output.
pub(crate) fn write_text(output: Option<&Path>, input: &Path, text: &str) -> Result<(), Failure> {
    let output = output.unwrap_or(Path::new("-"));
    write_output(output, Some(input), |w| w.write_all(text.as_bytes()))
}
