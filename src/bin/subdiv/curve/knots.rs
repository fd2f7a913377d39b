//! `subdiv curve --knots`: a B-spline or NURBS curve over a knot vector
//! (`subdiv::nurbs`): knot insertion, sampling, and its picture with the
//! knots marked.
//!
//! ```text
//! subdiv curve IN.txt --degree D --knots K0,...,Km [--weights W0,...,Wn] [--closed]
//!              [--insert T1,T2,... | --samples N] [-o OUT.txt|OUT.svg]
//! ```
//!
//! Text output: after `--insert` (or without `--insert` and `--samples`: the
//! curve as given), the control polygon one point per line at 17 significant
//! digits, after a `# knots k0 k1 ...` line and, for a rational curve, a
//! `# weights w0 w1 ...` line (the points are Euclidean); points files read
//! these comment lines back as comments. With `--closed` the knots are the
//! break points `s0..sn` of one period and the points the `n` distinct ones,
//! as `--knots` and the input take them. `--samples N`: the `N` curve points
//! alone.

use subdiv::curve::Point;
use subdiv::io::number::format_g;
use subdiv::io::points::{Points, format_points, read_points};
use subdiv::io::svg::{self, Layer, Projection};
use subdiv::nurbs::{NurbsCurve, NurbsError};

use super::{CurveArgs, is_svg, write_text};
use crate::Failure;

/// A comma-separated list of numbers (`--knots`, `--weights`, `--insert`).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct NumberList(pub(crate) Vec<f64>);

/// Parses `1,2.5,-3e-1` (spaces around the commas allowed). NaN and
/// infinities parse; the curve refuses them with a typed error.
pub(crate) fn parse_list(s: &str) -> Result<NumberList, String> {
    if s.trim().is_empty() {
        return Err("an empty list (give comma-separated numbers)".into());
    }
    s.split(',')
        .map(|field| {
            let field = field.trim();
            if field.is_empty() {
                Err(format!("an empty value in '{s}'"))
            } else {
                field
                    .parse::<f64>()
                    .map_err(|_| format!("'{field}' is not a number"))
            }
        })
        .collect::<Result<Vec<f64>, String>>()
        .map(NumberList)
}

/// What the command was doing when the library refused.
#[derive(Clone, Copy)]
enum Stage {
    Build,
    Insert,
    Sample,
}

/// The library's error, worded with the option it concerns.
fn explain(e: NurbsError, stage: Stage, args: &CurveArgs, points: usize, degree: usize) -> Failure {
    let input = args.input.display();
    let text = match (stage, &e) {
        (Stage::Insert, _) => format!("--insert: {e}"),
        (Stage::Sample, _) => format!("--samples: {e}"),
        (_, NurbsError::BadDegree { .. }) => format!("--degree: {e}"),
        (_, NurbsError::TooFewPoints { .. } | NurbsError::NonFinitePoint { .. }) => {
            format!("{input}: {e}")
        }
        (_, NurbsError::WrongKnotCount { expected, got }) if args.closed => format!(
            "--knots: {got} break point{} given, {expected} needed for {points} distinct points of a closed curve (--closed)",
            plural(*got)
        ),
        (_, NurbsError::WrongKnotCount { expected, got }) => format!(
            "--knots: {got} knot{} given, {expected} needed for {points} points of degree {degree}",
            plural(*got)
        ),
        (_, NurbsError::WrongWeightCount { expected, got }) => format!(
            "--weights: {got} weight{} given, {expected} needed (one per {}control point)",
            plural(*got),
            if args.closed { "distinct " } else { "" }
        ),
        (_, NurbsError::BadWeight { .. } | NurbsError::WeightedOverflow { .. }) => {
            format!("--weights: {e}")
        }
        _ => format!("--knots: {e}"),
    };
    Failure::Message(text)
}

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}

/// `subdiv curve --knots ...`.
pub(crate) fn curve(args: &CurveArgs) -> Result<(), Failure> {
    let (Some(knots), Some(degree)) = (&args.knots, args.degree) else {
        return Err(Failure::Usage(
            "give --scheme, or --knots with --degree".into(),
        ));
    };
    if let Some(n) = args.samples
        && n < 2
    {
        return Err(Failure::Usage(format!(
            "--samples: {n} asked for; at least 2 are needed (the domain's two ends)"
        )));
    }
    let file = read_points(&args.input).map_err(|e| Failure::Message(e.to_string()))?;
    match file.points {
        Points::Planar(p) => run(p, &knots.0, degree, args),
        Points::Spatial(p) => run(p, &knots.0, degree, args),
    }
}

fn run<P: Point>(
    points: Vec<P>,
    knots: &[f64],
    degree: usize,
    args: &CurveArgs,
) -> Result<(), Failure> {
    let count = points.len();
    let weights = args.weights.as_ref().map(|w| w.0.clone());
    let given = if args.closed {
        NurbsCurve::closed(points, degree, knots.to_vec(), weights)
    } else {
        NurbsCurve::new(points, degree, knots.to_vec(), weights)
    }
    .map_err(|e| explain(e, Stage::Build, args, count, degree))?;
    let inserted = args.insert.as_ref().map(|t| t.0.as_slice());
    let curve = match inserted {
        Some(ts) => given
            .insert_many(ts)
            .map_err(|e| explain(e, Stage::Insert, args, count, degree))?,
        None => given.clone(),
    };
    let samples = args
        .samples
        .map(|n| curve.sample(n))
        .transpose()
        .map_err(|e| explain(e, Stage::Sample, args, count, degree))?;
    match &args.output {
        Some(path) if is_svg(path) => {
            let text = picture(args, &given, &curve, inserted, samples.as_deref())
                .map_err(|e| explain(e, Stage::Sample, args, count, degree))?;
            crate::output::write_output(path, Some(&args.input), |w| w.write_all(text.as_bytes()))
        }
        output => {
            let text = match &samples {
                Some(s) => format_points(s),
                None => polygon_text(&curve),
            };
            write_text(output.as_deref(), &args.input, &text)
        }
    }
}

/// The control polygon with its `# knots` (and `# weights`) line: the
/// distinct points and the break points of a closed curve.
fn polygon_text<P: Point>(curve: &NurbsCurve<P>) -> String {
    let closed = curve.is_closed();
    let knots = if closed {
        curve.knots().breaks()
    } else {
        curve.knots().as_slice()
    };
    let mut out = String::from("# knots");
    push_numbers(&mut out, knots);
    if let Some(w) = curve.distinct_weights() {
        out.push_str("\n# weights");
        push_numbers(&mut out, w);
    }
    out.push('\n');
    out.push_str(&format_points(curve.distinct_points()));
    out
}

fn push_numbers(out: &mut String, values: &[f64]) {
    for &x in values {
        out.push(' ');
        format_g(x, 17, out);
    }
}

/// At most six values, `%g`-style, for a legend or a title.
fn short_list(values: &[f64]) -> String {
    let mut out = String::new();
    for (i, &x) in values.iter().take(6).enumerate() {
        if i > 0 {
            out.push_str(", ");
        }
        format_g(x, 6, &mut out);
    }
    if values.len() > 6 {
        out.push_str(&format!(", … ({} in all)", values.len()));
    }
    out
}

/// The SVG figure: the given control polygon, the one after the insertions,
/// the curve sampled densely, the samples asked for, and the knots.
fn picture<P: Point>(
    args: &CurveArgs,
    given: &NurbsCurve<P>,
    curve: &NurbsCurve<P>,
    inserted: Option<&[f64]>,
    samples: Option<&[P]>,
) -> Result<String, NurbsError> {
    let closed = curve.is_closed();
    let name = args.input.file_name().map_or_else(
        || args.input.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let kind = if curve.is_rational() {
        "NURBS curve"
    } else {
        "B-spline curve"
    };
    let title = format!(
        "{name}: {}{kind} of degree {}",
        if closed { "closed " } else { "" },
        curve.degree()
    );
    let given_label = format!("control polygon ({} points)", given.distinct_points().len());
    let inserted_label = inserted.map(|ts| {
        format!(
            "after inserting {} ({} points)",
            short_list(ts),
            curve.distinct_points().len()
        )
    });
    let dense = svg::dense_samples(curve)?;
    let curve_label = svg::curve_label(curve);
    let samples_label = samples.map(|s| format!("{} samples", s.len()));
    let mut layers = vec![Layer {
        label: &given_label,
        points: given.distinct_points(),
        closed,
    }];
    if let Some(label) = &inserted_label {
        layers.push(Layer {
            label,
            points: curve.distinct_points(),
            closed,
        });
    }
    layers.push(Layer {
        label: &curve_label,
        points: &dense,
        closed: false,
    });
    if let (Some(label), Some(points)) = (&samples_label, samples) {
        layers.push(Layer {
            label,
            points,
            closed: false,
        });
    }
    Ok(svg::curve_knots_svg(
        &title,
        &layers,
        &svg::knot_marks(curve)?,
        &Projection::for_points::<P>(),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_parse_with_signs_spaces_and_exponents() {
        assert_eq!(
            parse_list("-3,-2.5, 1e-3 ,4"),
            Ok(NumberList(vec![-3.0, -2.5, 1e-3, 4.0]))
        );
        assert_eq!(parse_list("7"), Ok(NumberList(vec![7.0])));
        assert_eq!(parse_list("1,x"), Err("'x' is not a number".into()));
        assert_eq!(parse_list("1,,2"), Err("an empty value in '1,,2'".into()));
        assert_eq!(parse_list("1,"), Err("an empty value in '1,'".into()));
        assert!(parse_list(" ").is_err());
        assert!(parse_list("nan").is_ok_and(|l| l.0[0].is_nan()));
    }

    #[test]
    fn short_lists_stop_after_six_values() {
        assert_eq!(short_list(&[2.8]), "2.8");
        assert_eq!(
            short_list(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]),
            "1, 2, 3, 4, 5, 6, … (7 in all)"
        );
    }
}
