//! `subdiv curve --knots`: B-spline and NURBS curves through the binary, as a
//! user runs it — Yamaguchi's insertion, the rational circle, the `# knots`
//! and `# weights` lines read back, negative knots, closed curves, SVG
//! output, and the errors with their messages and exit codes.

use crate::support::{scratch, stderr, stdout, subdiv, write};
use std::path::{Path, PathBuf};

/// Runs `subdiv curve INPUT ARGS...` and returns its stdout, asserting success.
fn curve(input: &Path, args: &[&str]) -> String {
    let mut all = vec!["curve", input.to_str().unwrap()];
    all.extend_from_slice(args);
    let o = subdiv(&all);
    assert!(o.status.success(), "{all:?}: {}", stderr(&o));
    stdout(&o)
}

/// Runs `subdiv curve INPUT ARGS... -o OUT` (OUT the file `out` beside the
/// input), asserting success and nothing on stdout; returns OUT and its text.
fn curve_to_file(input: &Path, args: &[&str], out: &str) -> (PathBuf, String) {
    let path = input.with_file_name(out);
    let mut all = args.to_vec();
    all.extend_from_slice(&["-o", path.to_str().unwrap()]);
    assert!(curve(input, &all).is_empty(), "{all:?}: text on stdout");
    let text = std::fs::read_to_string(&path).unwrap();
    (path, text)
}

/// Runs `subdiv curve INPUT ARGS...`, expecting failure with `code`; returns stderr.
fn curve_fails(input: &Path, args: &[&str], code: i32) -> String {
    let mut all = vec!["curve", input.to_str().unwrap()];
    all.extend_from_slice(args);
    let o = subdiv(&all);
    assert_eq!(o.status.code(), Some(code), "{all:?}: {}", stderr(&o));
    assert!(stdout(&o).is_empty(), "{all:?}");
    stderr(&o)
}

/// The numbers of each non-comment line.
fn points(text: &str) -> Vec<Vec<f64>> {
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| l.split(' ').map(|x| x.parse().unwrap()).collect())
        .collect()
}

/// The numbers after `# NAME` on the line that starts with it.
fn header(text: &str, name: &str) -> Option<Vec<f64>> {
    let prefix = format!("# {name} ");
    text.lines()
        .find_map(|l| l.strip_prefix(&prefix))
        .map(|rest| rest.split(' ').map(|x| x.parse().unwrap()).collect())
}

/// `1,2,3` from numbers at 17 significant digits (what a user would paste back).
pub(crate) fn list(values: &[f64]) -> String {
    values
        .iter()
        .map(|x| format!("{x:?}"))
        .collect::<Vec<_>>()
        .join(",")
}

fn close(a: &[f64], b: &[f64], tol: f64) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
}

/// Yamaguchi's Example 6.10 (see `tests/nurbs.rs` for the reconstruction):
/// P2..P5 = (30,50), (40,55), (60,20), (80,90) with two arbitrary points
/// before them, the uniform knots u_k = k - 3, a knot inserted at 2.8.
const YAMAGUCHI: &str = "# P0..P5\n0 10\n10 40\n30 50\n40 55\n60 20\n80 90\n";
const YAMAGUCHI_KNOTS: &str = "-3,-2,-1,0,1,2,3,4,5,6";
/// The example's insertion, with `--knots K` as two arguments.
const YAMAGUCHI_INSERT: [&str; 6] = [
    "--degree",
    "3",
    "--knots",
    YAMAGUCHI_KNOTS,
    "--insert",
    "2.8",
];

#[test]
fn yamaguchi_example_6_10_through_the_cli() {
    let dir = scratch("curve-knots-yamaguchi");
    let input = write(&dir, "yamaguchi.txt", YAMAGUCHI);
    let knots_arg = format!("--knots={YAMAGUCHI_KNOTS}");
    let text = curve(&input, &["--degree", "3", &knots_arg, "--insert", "2.8"]);
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("# knots -3 -2 -1 0 1 2 2.7999999999999998 3 4 5 6"),
        "{text}"
    );
    let q = points(&text);
    assert_eq!(q.len(), 7);
    // Q0..Q2 and Q6 are P0..P2 and P5; Q3..Q5 are Boehm's blends with
    // α = 14/15, 3/5, 4/15.
    for (i, p) in [
        (0, [0.0, 10.0]),
        (1, [10.0, 40.0]),
        (2, [30.0, 50.0]),
        (6, [80.0, 90.0]),
    ] {
        assert_eq!(q[i], p, "Q{i}");
    }
    let expected = [
        [118.0 / 3.0, 164.0 / 3.0],
        [52.0, 34.0],
        [196.0 / 3.0, 116.0 / 3.0],
    ];
    for (i, e) in expected.iter().enumerate() {
        assert!(close(&q[3 + i], e, 1e-12), "Q{}: {:?}", 3 + i, q[3 + i]);
    }
    // The printed values, rounded as Yamaguchi prints Q3 and Q4.
    assert_eq!(
        format!("({:.2}, {:.2})", q[3][0], q[3][1]),
        "(39.33, 54.67)"
    );
    assert_eq!(format!("({:.0}, {:.0})", q[4][0], q[4][1]), "(52, 34)");
    // `--knots -3,...` (a separate argument) gives the same file.
    let spaced = curve(&input, &YAMAGUCHI_INSERT);
    assert_eq!(spaced, text);
}

#[test]
fn negative_knots_and_parameters_in_both_forms() {
    let dir = scratch("curve-knots-negative");
    // The Yamaguchi curve shifted by -3: domain [-3, 0].
    let input = write(&dir, "shifted.txt", YAMAGUCHI);
    let knots = "-6,-5,-4,-3,-2,-1,0,1,2,3";
    let forms: [&[&str]; 4] = [
        &["--knots=-6,-5,-4,-3,-2,-1,0,1,2,3", "--insert=-0.2"],
        &["--knots", knots, "--insert", "-0.2"],
        &["--knots", knots, "--insert=-0.2"],
        &["--knots=-6,-5,-4,-3,-2,-1,0,1,2,3", "--insert", "-0.2"],
    ];
    let outputs: Vec<String> = forms
        .iter()
        .map(|f| {
            let mut args = vec!["--degree", "3"];
            args.extend_from_slice(f);
            curve(&input, &args)
        })
        .collect();
    assert!(outputs.iter().all(|o| o == &outputs[0]));
    let q = points(&outputs[0]);
    assert!(close(&q[3], &[118.0 / 3.0, 164.0 / 3.0], 1e-12), "{q:?}");
    assert_eq!(
        header(&outputs[0], "knots").unwrap(),
        [-6., -5., -4., -3., -2., -1., -0.2, 0., 1., 2., 3.]
    );
    // Spaces after the commas, inside one argument.
    let spaced = curve(
        &input,
        &[
            "--degree",
            "3",
            "--knots",
            "-6, -5, -4, -3, -2, -1, 0, 1, 2, 3",
            "--insert",
            "-0.2",
        ],
    );
    assert_eq!(spaced, outputs[0]);
}

#[test]
fn inserting_repeats_and_keeps_the_order() {
    let dir = scratch("curve-knots-repeats");
    let input = write(&dir, "repeat.txt", YAMAGUCHI);
    let text = curve(
        &input,
        &[
            "--degree",
            "3",
            "--knots",
            YAMAGUCHI_KNOTS,
            "--insert",
            "2.5,0.5,2.5",
        ],
    );
    assert_eq!(
        header(&text, "knots").unwrap(),
        [-3., -2., -1., 0., 0.5, 1., 2., 2.5, 2.5, 3., 4., 5., 6.]
    );
    assert_eq!(points(&text).len(), 9);
    assert!(header(&text, "weights").is_none());
    // Without --insert or --samples: the curve as given, with its knots line.
    let same = curve(&input, &["--degree", "3", "--knots", YAMAGUCHI_KNOTS]);
    assert_eq!(
        same,
        "# knots -3 -2 -1 0 1 2 3 4 5 6\n0 10\n10 40\n30 50\n40 55\n60 20\n80 90\n"
    );
}

const H: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// The unit circle's nine control points (the last repeats the first).
const SQUARE: &str = "1 0\n1 1\n0 1\n-1 1\n-1 0\n-1 -1\n0 -1\n1 -1\n1 0\n";
const CIRCLE_KNOTS: &str = "0,0,0,1,1,2,2,3,3,4,4,4";

fn circle_weights() -> String {
    list(&[1.0, H, 1.0, H, 1.0, H, 1.0, H, 1.0])
}

/// The circle's `--degree`, `--knots` and `--weights` (`weights` from
/// [`circle_weights`]), then `extra`.
fn circle_args<'a>(weights: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec![
        "--degree",
        "2",
        "--knots",
        CIRCLE_KNOTS,
        "--weights",
        weights,
    ];
    args.extend_from_slice(extra);
    args
}

#[test]
fn the_rational_circle_samples_lie_on_the_unit_circle() {
    let dir = scratch("curve-knots-circle");
    let input = write(&dir, "square.txt", SQUARE);
    let weights = circle_weights();
    for n in [2usize, 9, 100, 1001] {
        let count = n.to_string();
        let text = curve(&input, &circle_args(&weights, &["--samples", &count]));
        let p = points(&text);
        assert_eq!(p.len(), n);
        assert!(header(&text, "knots").is_none(), "samples come alone");
        for q in &p {
            let r = q[0].hypot(q[1]);
            assert!((r - 1.0).abs() < 1e-12, "n = {n}: {q:?} at radius {r}");
        }
        // Both ends of the domain [0, 4]: the first control point.
        assert_eq!(p[0], [1.0, 0.0]);
        assert!(close(&p[n - 1], &[1.0, 0.0], 1e-15));
    }
    // Nine samples at t = 0, 0.5, 1, ...: the points at 0°, 45°, 90°, ...
    let text = curve(&input, &circle_args(&weights, &["--samples", "9"]));
    for (k, q) in points(&text).iter().enumerate() {
        let a = std::f64::consts::FRAC_PI_4 * k as f64;
        assert!(close(q, &[a.cos(), a.sin()], 1e-12), "sample {k}: {q:?}");
    }
}

#[test]
fn knots_and_weights_lines_read_back_as_input() {
    let dir = scratch("curve-knots-read-back");
    let input = write(&dir, "square-insert.txt", SQUARE);
    let weights = circle_weights();
    let (out, text) = curve_to_file(
        &input,
        &circle_args(&weights, &["--insert", "0.5,2.25,2.25"]),
        "circle-inserted.txt",
    );
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines[0].starts_with("# knots "), "{text}");
    assert!(lines[1].starts_with("# weights "), "{text}");
    let knots = header(&text, "knots").unwrap();
    let w = header(&text, "weights").unwrap();
    assert_eq!(
        knots,
        [
            0., 0., 0., 0.5, 1., 1., 2., 2., 2.25, 2.25, 3., 3., 4., 4., 4.
        ]
    );
    assert_eq!(w.len(), 12);
    assert_eq!(points(&text).len(), 12);
    // Boehm at 0.5 between P0 (w 1) and P1 (w √2/2): weight (1 + √2/2) / 2.
    assert!((w[1] - (1.0 + H) / 2.0).abs() < 1e-15, "{w:?}");
    // The library reads the file, comment lines and all.
    let file = subdiv::io::points::read_points(&out).unwrap();
    assert_eq!(file.points.len(), 12);
    assert_eq!(file.lines[0], 3);
    // The written curve, given back with its own knots and weights, is the
    // same circle: samples at radius 1, and an empty insertion writes the
    // same file again.
    let (k, w) = (list(&knots), list(&w));
    let samples = curve(
        &out,
        &[
            "--degree",
            "2",
            "--knots",
            &k,
            "--weights",
            &w,
            "--samples",
            "257",
        ],
    );
    for q in points(&samples) {
        assert!((q[0].hypot(q[1]) - 1.0).abs() < 1e-12, "{q:?}");
    }
    let again = curve(&out, &["--degree", "2", "--knots", &k, "--weights", &w]);
    assert_eq!(again, text);
}

#[test]
fn closed_curves_take_the_break_points_of_one_period() {
    let dir = scratch("curve-knots-closed");
    // The circle as a closed curve: 8 distinct points, break points
    // 0,1,1,2,2,3,3,4,4 (the last two are 4 = s_7 and its image s_8 = s_0 + T).
    let input = write(
        &dir,
        "octagon.txt",
        "1 0\n1 1\n0 1\n-1 1\n-1 0\n-1 -1\n0 -1\n1 -1\n",
    );
    let w = list(&[1.0, H, 1.0, H, 1.0, H, 1.0, H]);
    let base = [
        "--closed",
        "--degree",
        "2",
        "--knots",
        "0,1,1,2,2,3,3,4,4",
        "--weights",
        &w,
    ];
    let mut args = base.to_vec();
    args.extend_from_slice(&["--samples", "64"]);
    for q in points(&curve(&input, &args)) {
        assert!((q[0].hypot(q[1]) - 1.0).abs() < 1e-12, "{q:?}");
    }
    let mut args = base.to_vec();
    args.extend_from_slice(&["--insert", "0.5,6.5"]); // 6.5 is 2.5 in the period [0, 4]
    let text = curve(&input, &args);
    assert_eq!(
        header(&text, "knots").unwrap(),
        [0., 0.5, 1., 1., 2., 2., 2.5, 3., 3., 4., 4.]
    );
    assert_eq!(header(&text, "weights").unwrap().len(), 10);
    assert_eq!(points(&text).len(), 10);
    let knots = args_list(&text, "knots");
    let weights = args_list(&text, "weights");
    let out = write(&dir, "octagon-inserted.txt", &text);
    let samples = curve(
        &out,
        &[
            "--closed",
            "--degree",
            "2",
            "--knots",
            &knots,
            "--weights",
            &weights,
            "--samples",
            "33",
        ],
    );
    for q in points(&samples) {
        assert!((q[0].hypot(q[1]) - 1.0).abs() < 1e-12, "{q:?}");
    }
}

fn args_list(text: &str, name: &str) -> String {
    list(&header(text, name).unwrap())
}

#[test]
fn spatial_points_and_the_samples_ends() {
    let dir = scratch("curve-knots-spatial");
    let input = write(&dir, "helix.txt", "0 0 0\n1 0 1\n1 1 2\n0 1 3\n0 0 4\n");
    let text = curve(
        &input,
        &[
            "--degree",
            "2",
            "--knots",
            "0,0,0,1,2,3,3,3",
            "--samples",
            "5",
        ],
    );
    let p = points(&text);
    assert_eq!(p.len(), 5);
    assert!(p.iter().all(|q| q.len() == 3));
    // Clamped: the ends are the first and last control points.
    assert_eq!(p[0], [0.0, 0.0, 0.0]);
    assert_eq!(p[4], [0.0, 0.0, 4.0]);
    // The middle sample, t = 1.5: half way in the span [1, 2], where the
    // quadratic blends P1, P2, P3 with 1/8, 6/8, 1/8.
    assert!(close(&p[2], &[0.875, 0.875, 2.0], 1e-15), "{:?}", p[2]);
}

/// A crude well-formedness check: every start tag is closed, in order.
fn balanced(svg: &str) -> bool {
    let mut stack: Vec<&str> = Vec::new();
    let mut rest = svg;
    while let Some(open) = rest.find('<') {
        let Some(len) = rest[open..].find('>') else {
            return false;
        };
        let tag = &rest[open + 1..open + len];
        rest = &rest[open + len + 1..];
        if let Some(name) = tag.strip_prefix('/') {
            if stack.pop() != Some(name.trim()) {
                return false;
            }
        } else if !tag.ends_with('/') {
            stack.push(tag.split_whitespace().next().unwrap_or(""));
        }
    }
    stack.is_empty()
}

#[test]
fn svg_draws_the_polygons_the_curve_and_its_knots() {
    let dir = scratch("curve-knots-svg");
    let input = write(&dir, "yamaguchi-svg.txt", YAMAGUCHI);
    let (_, svg) = curve_to_file(&input, &YAMAGUCHI_INSERT, "yamaguchi.svg");
    assert!(svg.starts_with("<svg"), "{svg}");
    assert!(svg.trim_end().ends_with("</svg>"));
    assert!(balanced(&svg), "{svg}");
    for text in [
        "yamaguchi-svg.txt: B-spline curve of degree 3",
        "control polygon (6 points)",
        "after inserting 2.8 (7 points)",
        "curve (degree 3)",
        "knots: C(t) at the 5 distinct knots of the domain",
        "<g class=\"knots\">",
        ">2.8</text>",
    ] {
        assert!(svg.contains(text), "{text} missing from\n{svg}");
    }
    // Two polygons and the curve, then one diamond per knot 0, 1, 2, 2.8, 3
    // and the legend's.
    assert_eq!(svg.matches("<polyline").count(), 3);
    assert_eq!(svg.matches("<path").count(), 6);

    // The circle with --samples: the samples are a layer of their own.
    let input = write(&dir, "square-svg.txt", SQUARE);
    let w = circle_weights();
    let (_, svg) = curve_to_file(&input, &circle_args(&w, &["--samples", "12"]), "circle.svg");
    assert!(balanced(&svg));
    for text in [
        "NURBS curve of degree 2",
        "curve (degree 2, rational)",
        "12 samples",
        "0 (×3), 4 (×3)",
        "1 (×2)",
    ] {
        assert!(svg.contains(text), "{text} missing from\n{svg}");
    }
}

#[test]
fn errors_name_the_option_and_exit_1() {
    let dir = scratch("curve-knots-errors");
    let input = write(&dir, "errors.txt", YAMAGUCHI);
    let cases: &[(&[&str], &str)] = &[
        (
            &["--degree", "3", "--knots", "-3,-2,-1,0,1,2,3,4,5"],
            "subdiv: error: --knots: 9 knots given, 10 needed for 6 points of degree 3\n",
        ),
        (
            &["--degree", "3", "--knots", "0,1,2,3,5,4,6,7,8,9"],
            "subdiv: error: --knots: knot 5 (4) is smaller than knot 4 (5): knots must not decrease\n",
        ),
        (
            &["--degree", "2", "--knots", "0,0,0,1,1,1,1,2,2"],
            "subdiv: error: --knots: knot 1 has multiplicity 4, more than degree + 1 = 3\n",
        ),
        (
            &["--degree", "3", "--knots", "0,1,2,3,nan,5,6,7,8,9"],
            "subdiv: error: --knots: knot 4 is not a finite number (NaN)\n",
        ),
        (
            &[
                "--degree",
                "3",
                "--knots",
                YAMAGUCHI_KNOTS,
                "--weights",
                "1,1,1",
            ],
            "subdiv: error: --weights: 3 weights given, 6 needed (one per control point)\n",
        ),
        (
            &[
                "--degree",
                "3",
                "--knots",
                YAMAGUCHI_KNOTS,
                "--weights",
                "1,1,-1,1,1,1",
            ],
            "subdiv: error: --weights: weight 2 is -1; weights must be positive finite numbers\n",
        ),
        (
            &["--degree", "3", "--knots", YAMAGUCHI_KNOTS, "--insert", "7"],
            "subdiv: error: --insert: parameter 7 is outside the domain [0, 3]\n",
        ),
        (
            &[
                "--degree",
                "3",
                "--knots",
                YAMAGUCHI_KNOTS,
                "--insert",
                "2,2,2,2",
            ],
            "subdiv: error: --insert: knot 2 has multiplicity 5, more than degree + 1 = 4\n",
        ),
        (
            &["--degree", "6", "--knots", "0,1,2,3,4,5,6,7,8,9,10,11,12"],
            "subdiv: error: ERRORS: an open curve of degree 6 needs at least 7 control points, got 6\n",
        ),
        (
            &["--closed", "--degree", "3", "--knots", "0,1,2,3,4,5"],
            "subdiv: error: --knots: 6 break points given, 7 needed for 6 distinct points of a closed curve (--closed)\n",
        ),
        (
            &[
                "--closed",
                "--degree",
                "3",
                "--knots",
                "0,1,2,3,4,5,6",
                "--weights",
                "1,1",
            ],
            "subdiv: error: --weights: 2 weights given, 6 needed (one per distinct control point)\n",
        ),
    ];
    for (args, message) in cases {
        let out = dir.join("not-written.txt");
        let mut all = args.to_vec();
        all.extend_from_slice(&["-o", out.to_str().unwrap()]);
        let err = curve_fails(&input, &all, 1);
        let expected = message.replace("ERRORS", &input.display().to_string());
        assert_eq!(err, expected, "{args:?}");
        assert!(!out.exists(), "{args:?}: no output on error");
    }
    // A malformed input file: its line, as for the schemes.
    let bad = write(&dir, "bad-line.txt", "0 0\n1 x\n");
    let err = curve_fails(&bad, &["--degree", "1", "--knots", "0,1,2,3"], 1);
    assert!(err.contains("bad-line.txt:2: 'x' is not a number"), "{err}");
}

#[test]
fn options_that_do_not_go_together_are_usage_errors() {
    let dir = scratch("curve-knots-usage");
    let input = write(&dir, "usage.txt", YAMAGUCHI);
    let k = YAMAGUCHI_KNOTS;
    let cases: &[(&[&str], &str)] = &[
        (
            &[
                "--degree",
                "3",
                "--knots",
                k,
                "--insert",
                "1",
                "--samples",
                "5",
            ],
            "'--insert <T1,T2,...>' cannot be used with '--samples <N>'",
        ),
        (
            &["--degree", "3", "--knots", k, "--scheme", "chaikin"],
            "'--knots <K0,K1,...>' cannot be used with '--scheme <SCHEME>'",
        ),
        (
            &["--degree", "3", "--knots", k, "--level", "2"],
            "'--knots <K0,K1,...>' cannot be used with '--level <N>'",
        ),
        (
            &["--degree", "3", "--knots", k, "--tolerance", "0.1"],
            "'--knots <K0,K1,...>' cannot be used with '--tolerance <EPS>'",
        ),
        (&["--knots", k], "--degree <D>"),
        (&["--degree", "3", "--insert", "1"], "--knots <K0,K1,...>"),
        (&["--degree", "3", "--samples", "4"], "--knots <K0,K1,...>"),
        (&[], "--scheme <SCHEME>"),
        (
            &["--degree", "3", "--knots", "-3,-2,x"],
            "invalid value '-3,-2,x' for '--knots <K0,K1,...>': 'x' is not a number",
        ),
        (
            &["--degree", "3", "--knots", "1,,2"],
            "an empty value in '1,,2'",
        ),
        (
            &["--degree", "3", "--knots", k, "--knots", k],
            "cannot be used multiple times",
        ),
        (
            &["--degree", "3", "--knots", k, "--samples", "1"],
            "--samples: 1 asked for; at least 2 are needed (the domain's two ends)",
        ),
        (
            &["--degree", "0", "--knots", "0,1,2,3,4,5"],
            "invalid value '0' for '--degree <D>': a degree is 1 or more; 0 is not",
        ),
    ];
    for (args, message) in cases {
        let err = curve_fails(&input, args, 2);
        assert!(err.contains(message), "{args:?}: {err}");
    }
}

#[test]
fn help_documents_the_knot_options() {
    let o = subdiv(&["curve", "--help"]);
    assert!(o.status.success());
    let help = stdout(&o);
    for text in [
        "--knots <K0,K1,...>",
        "--weights <W0,W1,...>",
        "--insert <T1,T2,...>",
        "--samples <N>",
        "--knots=-3,-2,-1,0,...",
        "break points",
    ] {
        assert!(help.contains(text), "{text} missing from\n{help}");
    }
}
