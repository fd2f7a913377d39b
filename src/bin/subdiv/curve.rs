//! `subdiv curve`: refine or flatten a curve given as points.

use clap::Args;
use std::io::Write as _;
use std::path::PathBuf;
use subdiv::curve::{CurveScheme, Point};

use crate::Failure;

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
pub(crate) struct CurveArgs {
    /// Input points: one per line, 2 or 3 numbers separated by spaces; `#` starts a comment.
    #[arg(value_name = "INPUT.txt")]
    pub(crate) input: PathBuf,
    /// Curve scheme.
    #[arg(long, value_enum)]
    pub(crate) scheme: CurveSchemeArg,
    /// B-spline degree, 1 to 15 (--scheme bspline only) [default: 3].
    #[arg(long, value_name = "D")]
    pub(crate) degree: Option<usize>,
    /// Four-point tension w (--scheme four-point only) [default: 1/16]; any finite
    /// value; 0 < w < 0.15 gives smooth curves.
    #[arg(long, value_name = "W", allow_negative_numbers = true)]
    pub(crate) tension: Option<f64>,
    /// The polygon is closed (its last point joins its first).
    #[arg(long)]
    pub(crate) closed: bool,
    /// Refinement levels [default: 1].
    #[arg(long, value_name = "N", conflicts_with = "tolerance")]
    pub(crate) level: Option<u32>,
    /// Flatten the limit curve (chaikin, bspline) into a polyline within EPS of it.
    #[arg(long, value_name = "EPS", allow_negative_numbers = true)]
    pub(crate) tolerance: Option<f64>,
    /// Output: `.svg` draws the control polygon and each level in its own colour,
    /// any other name gets the points as text; without it the text goes to stdout.
    #[arg(short, long, value_name = "OUT.txt|OUT.svg")]
    pub(crate) output: Option<PathBuf>,
}

/// `subdiv curve`: refine or flatten a curve given as one point per line.
pub(crate) fn curve(args: &CurveArgs) -> Result<(), Failure> {
    let message = |e: &dyn std::fmt::Display| Failure::Message(e.to_string());
    let scheme = match args.scheme {
        CurveSchemeArg::Chaikin => CurveScheme::Chaikin,
        CurveSchemeArg::Bspline => CurveScheme::BSpline {
            degree: args.degree.unwrap_or(3),
        },
        CurveSchemeArg::FourPoint => CurveScheme::FourPoint {
            tension: args.tension.unwrap_or(subdiv::curve::DEFAULT_TENSION),
        },
        CurveSchemeArg::Jarek => CurveScheme::Jarek,
    };
    if args.degree.is_some() && args.scheme != CurveSchemeArg::Bspline {
        return Err(Failure::Message(format!(
            "--degree applies to --scheme bspline only ({} is not a B-spline of a chosen degree)",
            scheme.name()
        )));
    }
    if args.tension.is_some() && args.scheme != CurveSchemeArg::FourPoint {
        return Err(Failure::Message(
            "--tension applies to --scheme four-point only".into(),
        ));
    }
    scheme.check().map_err(|e| message(&e))?;
    if args.tolerance.is_some() && scheme.limit_degree().is_none() {
        return Err(message(&subdiv::curve::CurveError::NoClosedFormLimit {
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
        Some(path)
            if path
                .extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("svg")) =>
        {
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
            subdiv::io::svg::write_svg(path, &svg)?;
        }
        Some(path) => subdiv::io::points::write_points(path, result)?,
        None => {
            let text = subdiv::io::points::format_points(result);
            let mut out = std::io::stdout().lock();
            out.write_all(text.as_bytes())
                .and_then(|()| out.flush())
                .map_err(|e| Failure::Message(format!("cannot write to stdout: {e}")))?;
        }
    }
    Ok(())
}
