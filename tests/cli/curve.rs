//! `subdiv curve`: every scheme against the library at 17 digits, text and
//! SVG output files, flattening to a tolerance, refusals, and no inf or NaN.

use crate::support::{scratch, stderr, stdout, subdiv, write};
use glam::DVec2;
use std::path::Path;
use subdiv::curve::{self, CurveScheme};
use subdiv::io::points::Points;

const ZIGZAG: &str = "# a zigzag\n0 0\n1 2\n3 2   # the top\n4 0\n";

#[test]
fn chaikin_prints_the_refined_points() {
    let dir = scratch("curve-chaikin");
    let input = write(&dir, "zigzag.txt", ZIGZAG);
    let o = subdiv(&["curve", input.to_str().unwrap(), "--scheme", "chaikin"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        stdout(&o),
        "0.25 0.5\n0.75 1.5\n1.5 2\n2.5 2\n3.25 1.5\n3.75 0.5\n"
    );
}

#[test]
fn every_scheme_matches_the_library_at_17_digits() {
    let dir = scratch("curve-every-scheme");
    let text = "0.1 0.2 0.3\n1.7 -2.2 0\n3.3 2.9 1e-3\n4 0.5 -1\n5.5 1 2\n";
    let input = write(&dir, "spatial.txt", text);
    let p = match subdiv::io::points::parse_points(text, Path::new("x"))
        .unwrap()
        .points
    {
        Points::Spatial(p) => p,
        other => panic!("{other:?}"),
    };
    let cases: [(&[&str], CurveScheme); 5] = [
        (&["--scheme", "chaikin"], CurveScheme::Chaikin),
        (&["--scheme", "bspline"], CurveScheme::bspline(3)),
        (
            &["--scheme", "bspline", "--degree", "4"],
            CurveScheme::bspline(4),
        ),
        (&["--scheme", "four-point"], CurveScheme::four_point()),
        (&["--scheme", "jarek"], CurveScheme::Jarek),
    ];
    for (flags, scheme) in cases {
        for closed in [false, true] {
            let mut args = vec!["curve", input.to_str().unwrap(), "--level", "3"];
            args.extend_from_slice(flags);
            if closed {
                args.push("--closed");
            }
            let o = subdiv(&args);
            assert!(o.status.success(), "{args:?}: {}", stderr(&o));
            let expected = curve::refine(&p, scheme, closed, 3).unwrap();
            assert_eq!(
                stdout(&o),
                subdiv::io::points::format_points(&expected),
                "{args:?}"
            );
        }
    }
    // Default: one level.
    let o = subdiv(&["curve", input.to_str().unwrap(), "--scheme", "jarek"]);
    assert_eq!(stdout(&o).lines().count(), 9);
    // Tension.
    let o = subdiv(&[
        "curve",
        input.to_str().unwrap(),
        "--scheme",
        "four-point",
        "--tension",
        "0",
    ]);
    let expected = curve::refine(&p, CurveScheme::bspline(1), false, 1).unwrap();
    assert_eq!(stdout(&o), subdiv::io::points::format_points(&expected));
}

#[test]
fn writes_text_and_svg_files_atomically() {
    let dir = scratch("curve-output-files");
    let input = write(&dir, "zigzag-out.txt", ZIGZAG);
    let out = dir.join("refined.txt");
    let o = subdiv(&[
        "curve",
        input.to_str().unwrap(),
        "--scheme",
        "bspline",
        "--degree",
        "2",
        "--closed",
        "--level",
        "2",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stdout(&o), "");
    let text = std::fs::read_to_string(&out).unwrap();
    assert_eq!(text.lines().count(), 16);
    let svg_path = dir.join("refined.svg");
    let o = subdiv(&[
        "curve",
        input.to_str().unwrap(),
        "--scheme",
        "four-point",
        "--level",
        "3",
        "-o",
        svg_path.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let svg = std::fs::read_to_string(&svg_path).unwrap();
    assert!(svg.starts_with("<svg"));
    assert!(svg.trim_end().ends_with("</svg>"));
    // The control polygon and three levels, each in its own colour.
    assert_eq!(svg.matches("<polyline").count(), 4);
    for label in [
        "control polygon (4 points)",
        "level 1 (7 points)",
        "level 2 (13 points)",
        "level 3 (25 points)",
    ] {
        assert!(svg.contains(label), "{label}");
    }
    for k in 0..4 {
        assert!(svg.contains(subdiv::io::svg::layer_color(k)));
    }
    // No temporary file is left behind.
    for entry in std::fs::read_dir(&dir).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        assert!(!name.ends_with(".tmp"), "{name}");
    }
}

#[test]
fn tolerance_flattens_chaikin_and_bspline_only() {
    let dir = scratch("curve-tolerance");
    let input = write(&dir, "zigzag-flat.txt", ZIGZAG);
    let p = [
        DVec2::new(0.0, 0.0),
        DVec2::new(1.0, 2.0),
        DVec2::new(3.0, 2.0),
        DVec2::new(4.0, 0.0),
    ];
    for (scheme, name) in [
        (CurveScheme::Chaikin, "chaikin"),
        (CurveScheme::bspline(3), "bspline"),
    ] {
        let o = subdiv(&[
            "curve",
            input.to_str().unwrap(),
            "--scheme",
            name,
            "--tolerance",
            "0.001",
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let expected = curve::flatten(&p, scheme, false, 1e-3).unwrap();
        assert_eq!(
            stdout(&o),
            subdiv::io::points::format_points(&expected.points)
        );
    }
    let svg = dir.join("flat.svg");
    let o = subdiv(&[
        "curve",
        input.to_str().unwrap(),
        "--scheme",
        "chaikin",
        "--closed",
        "--tolerance",
        "0.01",
        "-o",
        svg.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&svg).unwrap();
    assert_eq!(text.matches("<polygon").count(), 2);
    assert!(text.contains("flattened to 1e-2"));
    for scheme in ["four-point", "jarek"] {
        let o = subdiv(&[
            "curve",
            input.to_str().unwrap(),
            "--scheme",
            scheme,
            "--tolerance",
            "0.01",
        ]);
        assert_eq!(o.status.code(), Some(2));
        assert!(
            stderr(&o).contains("no closed-form limit curve"),
            "{}",
            stderr(&o)
        );
    }
    for eps in ["0", "-1", "nan"] {
        let o = subdiv(&[
            "curve",
            input.to_str().unwrap(),
            "--scheme",
            "chaikin",
            "--tolerance",
            eps,
        ]);
        assert_eq!(o.status.code(), Some(2), "{eps}");
        assert!(
            stderr(&o).contains("the tolerance must be a finite distance greater than 0"),
            "{}",
            stderr(&o)
        );
    }
    // --level and --tolerance exclude each other (a usage error).
    let o = subdiv(&[
        "curve",
        input.to_str().unwrap(),
        "--scheme",
        "chaikin",
        "--tolerance",
        "0.1",
        "--level",
        "2",
    ]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn malformed_input_is_an_error_naming_the_line() {
    let dir = scratch("curve-malformed-input");
    let cases: [(&str, &str, &[&str], &str); 9] = [
        (
            "one.txt",
            "0 0\n# x\n5\n",
            &["jarek"],
            "one.txt:3: a point needs 2 or 3 numbers, this line has 1",
        ),
        (
            "four.txt",
            "0 0 0\n1 1 1 1\n",
            &["jarek"],
            "four.txt:2: a point needs 2 or 3 numbers, this line has 4",
        ),
        (
            "mixed.txt",
            "0 0\n1 1\n2 2 2\n",
            &["jarek"],
            "mixed.txt:3: a 3-D point after 2-D points (the first point is on line 1)",
        ),
        (
            "word.txt",
            "0 0\n1 one\n",
            &["jarek"],
            "word.txt:2: 'one' is not a number",
        ),
        (
            "inf.txt",
            "0 0\n1 inf\n",
            &["jarek"],
            "inf.txt:2: 'inf' is not a finite number",
        ),
        (
            "few-chaikin.txt",
            "0 0\n1 1\n",
            &["chaikin"],
            "few-chaikin.txt:2: the input ends after 2 points; chaikin on an open polygon needs at least 3",
        ),
        (
            "few-bspline.txt",
            "0 0\n1 1\n2 0\n3 1\n\n",
            &["bspline", "--degree", "4"],
            "few-bspline.txt:5: the input ends after 4 points; bspline on an open polygon needs at least 5",
        ),
        (
            "few-closed.txt",
            "0 0\n1 1\n",
            &["four-point", "--closed"],
            "few-closed.txt:2: the input ends after 2 points; four-point on a closed polygon needs at least 3",
        ),
        (
            "empty.txt",
            "# nothing\n",
            &["jarek"],
            "empty.txt:1: the input ends after 0 points; jarek on an open polygon needs at least 2",
        ),
    ];
    for (name, text, flags, message) in cases {
        let input = write(&dir, name, text);
        let out = dir.join(format!("{name}.out.txt"));
        let mut args = vec![
            "curve",
            input.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--scheme",
        ];
        args.extend_from_slice(flags);
        let o = subdiv(&args);
        assert_eq!(o.status.code(), Some(1), "{name}");
        let err = stderr(&o);
        assert!(err.contains(message), "{name}: {err}");
        assert!(!out.exists(), "{name}: no output on error");
    }
}

#[test]
fn bad_options_are_errors() {
    let dir = scratch("curve-bad-options");
    let input = write(&dir, "zigzag-opts.txt", ZIGZAG);
    let run = |flags: &[&str]| {
        let mut args = vec!["curve", input.to_str().unwrap()];
        args.extend_from_slice(flags);
        subdiv(&args)
    };
    // Misused options are usage errors (exit 2) ...
    let o = run(&["--scheme", "bspline", "--degree", "0"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("'--degree <D>': a degree is 1 or more; 0 is not"));
    let o = run(&["--scheme", "bspline", "--degree", "16"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("usage error: B-spline degree 16 is not supported"));
    let o = run(&["--scheme", "chaikin", "--degree", "2"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--degree applies to --scheme bspline only"));
    let o = run(&["--scheme", "jarek", "--tension", "0.1"]);
    assert_eq!(o.status.code(), Some(2));
    let o = run(&["--scheme", "four-point", "--tension", "nan"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("tension NaN is not a finite number"));
    let o = run(&["--scheme", "jarek", "--tolerance", "0.01"]);
    assert_eq!(o.status.code(), Some(2));
    // ... and a result too large to make is an error (exit 1).
    let o = run(&["--scheme", "four-point", "--level", "60"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("more than"), "{}", stderr(&o));
    let o = run(&["--scheme", "cubic"]);
    assert_eq!(o.status.code(), Some(2));
    let o = subdiv(&["curve", "/nonexistent/points.txt", "--scheme", "chaikin"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("/nonexistent/points.txt"));
    // Level 0 writes the input back.
    let o = run(&["--scheme", "jarek", "--level", "0"]);
    assert_eq!(stdout(&o), "0 0\n1 2\n3 2\n4 0\n");
}

#[test]
fn never_prints_inf_or_nan() {
    let dir = scratch("curve-no-inf-or-nan");
    let huge = write(
        &dir,
        "huge.txt",
        "1.7e308 1.7e308\n1.7e308 -1.7e308\n-1.7e308 1.7e308\n1.7e308 1.6e308\n",
    );
    let zigzag = write(&dir, "zigzag-tension.txt", ZIGZAG);
    let mut cases: Vec<(&Path, Vec<&str>)> = Vec::new();
    for flags in [
        &["chaikin"][..],
        &["bspline"],
        &["bspline", "--degree", "1"],
        &["four-point"],
        &["jarek"],
    ] {
        for closed in [false, true] {
            let mut f = flags.to_vec();
            if closed {
                f.push("--closed");
            }
            cases.push((&huge, f));
        }
    }
    for tension in ["1e308", "1e300", "-1e300", "1e20"] {
        cases.push((&zigzag, vec!["four-point", "--tension", tension]));
    }
    for (input, flags) in cases {
        let mut args = vec!["curve", input.to_str().unwrap(), "--level", "4", "--scheme"];
        args.extend(&flags);
        let o = subdiv(&args);
        let (out, err) = (stdout(&o), stderr(&o));
        let lower = out.to_lowercase();
        assert!(
            !lower.contains("inf") && !lower.contains("nan"),
            "{flags:?}"
        );
        match o.status.code() {
            Some(0) => assert!(!out.is_empty(), "{flags:?}"),
            Some(1) => {
                assert!(out.is_empty(), "{flags:?}");
                assert!(
                    err.starts_with(&format!("subdiv: error: {}: level ", input.display()))
                        && err.contains(" overflows: its point "),
                    "{flags:?}: {err}"
                );
            }
            code => panic!("{flags:?}: exit {code:?}: {err}"),
        }
    }
    // The averaging schemes take any finite coordinates.
    let o = subdiv(&[
        "curve",
        huge.to_str().unwrap(),
        "--scheme",
        "bspline",
        "--level",
        "4",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = subdiv(&[
        "curve",
        zigzag.to_str().unwrap(),
        "--scheme",
        "four-point",
        "--tension",
        "1e308",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr(&o),
        format!(
            "subdiv: error: {}: level 1 of four-point with tension 1e308 overflows: its point 1 \
             would have a coordinate beyond the range of f64 (the coordinates or the tension are \
             too large)\n",
            zigzag.display()
        )
    );
}
