//! The `subdiv` binary, run as a user runs it.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn subdiv(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_subdiv"))
        .args(args)
        .output()
        .expect("run subdiv")
}

fn tmp(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    let _ = std::fs::remove_file(&path);
    path
}

fn write(name: &str, text: &str) -> PathBuf {
    let path = tmp(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

const QUAD_GRID: &str = "\
v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0.5\nv 2 1 0\nv 0 2 0\nv 1 2 0\nv 2 2 0\n\
f 1 2 5 4\nf 2 3 6 5\nf 4 5 8 7\nf 5 6 9 8\n";

#[test]
fn native_engine_writes_the_same_file_as_opensubdiv() {
    let native = tmp("native-out.obj");
    let osd = tmp("native-osd-out.obj");
    // The grid with a UV per vertex (`f a/a ...`): the native engine writes
    // `-o` without --limit from the last level only.
    let mut with_uvs: String = QUAD_GRID
        .lines()
        .filter(|l| l.starts_with("v "))
        .map(|l| format!("{l}\nvt{}\n", &l[1..l.rfind(' ').unwrap()]))
        .collect();
    for l in QUAD_GRID.lines().filter(|l| l.starts_with("f ")) {
        let corners: Vec<String> = l[2..].split(' ').map(|i| format!("{i}/{i}")).collect();
        with_uvs += &format!("f {}\n", corners.join(" "));
    }
    let holed = format!("{QUAD_GRID}t hole 1/0/0 3\n");
    for (name, text, extra, faces) in [
        ("native.obj", QUAD_GRID, &[][..], 256),
        ("native-uv.obj", &with_uvs, &["--precision", "f32"][..], 256),
        ("native-hole.obj", &holed, &["--faces-first"][..], 192),
    ] {
        let input = write(name, text);
        for (engine, out) in [("native", &native), ("osd", &osd)] {
            let mut args = vec![
                "refine",
                input.to_str().unwrap(),
                "--level",
                "3",
                "--engine",
                engine,
                "-o",
                out.to_str().unwrap(),
            ];
            args.extend(extra);
            let o = subdiv(&args);
            assert!(o.status.success(), "{name} {engine}: {}", stderr(&o));
        }
        let (a, b) = (
            std::fs::read_to_string(&native).unwrap(),
            std::fs::read_to_string(&osd).unwrap(),
        );
        assert_eq!(a.lines().filter(|l| l.starts_with("f ")).count(), faces);
        if name == "native-uv.obj" {
            assert_eq!(a.lines().filter(|l| l.starts_with("vt ")).count(), 289);
        }
        assert_eq!(a, b, "{name}: native and OpenSubdiv output differ");
    }
    let input = write("native.obj", QUAD_GRID);
    // The same for limit positions.
    for (engine, out) in [("native", &native), ("osd", &osd)] {
        let o = subdiv(&[
            "refine",
            input.to_str().unwrap(),
            "--level",
            "2",
            "--limit",
            "--engine",
            engine,
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{engine} --limit: {}", stderr(&o));
    }
    let (a, b) = (
        std::fs::read_to_string(&native).unwrap(),
        std::fs::read_to_string(&osd).unwrap(),
    );
    assert_eq!(a, b, "native and OpenSubdiv limit output differ");
}

#[test]
fn compare_reports_agreement_and_json() {
    let input = write("compare.obj", QUAD_GRID);
    let o = subdiv(&["compare", input.to_str().unwrap(), "--levels", "1..3"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    assert!(text.contains("the engines agree"), "{text}");
    assert_eq!(
        text.lines()
            .filter(|l| l.trim_end().ends_with(" ok"))
            .count(),
        3,
        "{text}"
    );
    let o = subdiv(&[
        "compare",
        input.to_str().unwrap(),
        "--levels",
        "2",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(json["agrees"], true);
    assert_eq!(json["levels"][0]["level"], 2);
    assert_eq!(json["levels"][0]["native_counts"][0], 81);
    let o = subdiv(&["compare", input.to_str().unwrap(), "--levels", "3..1"]);
    assert_eq!(o.status.code(), Some(2), "clap refuses an empty range");
}

#[test]
fn malformed_obj_names_file_and_line() {
    let input = write("bad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 zero\nf 1 2 3\n");
    let out = tmp("bad-out.obj");
    let o = subdiv(&[
        "refine",
        input.to_str().unwrap(),
        "--engine",
        "osd",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(err.contains("bad.obj:3:"), "{err}");
    assert!(!out.exists());
}

#[test]
fn bad_index_and_bad_tag_are_errors() {
    let input = write("range.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 4\n");
    let o = subdiv(&["refine", input.to_str().unwrap(), "--engine", "osd"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("range.obj:4:"), "{}", stderr(&o));

    let text = format!("{QUAD_GRID}t interpolateboundary 1/0/0 7\n");
    let input = write("tag.obj", &text);
    let o = subdiv(&["refine", input.to_str().unwrap(), "--engine", "osd"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("tag.obj:14:"), "{}", stderr(&o));
}

#[test]
fn summary_without_output() {
    let input = write("summary.obj", QUAD_GRID);
    let o = subdiv(&[
        "refine",
        input.to_str().unwrap(),
        "--engine",
        "osd",
        "--level",
        "2",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let s = stdout(&o);
    // 3x3 vertices -> 5x5 -> 9x9; 4 faces -> 16 -> 64.
    assert!(s.contains("vertices 9→25→81, faces 4→16→64"), "{s}");
    assert_eq!(s.lines().count(), 1);
}

#[test]
fn crease_without_edge_warns_or_fails_under_strict() {
    let text = format!("{QUAD_GRID}t crease 2/1/0 0 8 3.0\n");
    let input = write("diag.obj", &text);
    let o = subdiv(&["refine", input.to_str().unwrap(), "--engine", "osd"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("share no edge"), "{}", stderr(&o));
    let out = tmp("diag-out.obj");
    let o = subdiv(&[
        "refine",
        input.to_str().unwrap(),
        "--engine",
        "osd",
        "--strict",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("share no edge"), "{}", stderr(&o));
    assert!(!out.exists());
}

#[test]
fn output_obj_in_opensubdiv_order_with_holes_left_out() {
    let text = format!("{QUAD_GRID}t hole 1/0/0 3\n");
    let input = write("hole.obj", &text);
    let out = tmp("hole-out.obj");
    let o = subdiv(&[
        "refine",
        input.to_str().unwrap(),
        "--engine",
        "osd",
        "--level",
        "1",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&out).unwrap();
    let v: Vec<&str> = text.lines().filter(|l| l.starts_with("v ")).collect();
    let f: Vec<&str> = text.lines().filter(|l| l.starts_with("f ")).collect();
    assert_eq!(v.len(), 25);
    assert_eq!(f.len(), 12, "the 4 children of the hole are left out");
    // Vertex 0 is a boundary corner (edge-only): (1/8)(1,0,0) + (6/8)(0,0,0) + (1/8)(0,1,0).
    assert_eq!(v[0], "v 0.125 0.125 0");
    // The first child face of face 0 [1 2 5 4]: vertex-child 1, edge (1,2), face point, edge (4,1).
    assert_eq!(f[0], "f 1 14 10 17");
}

#[test]
fn precision_and_limit_change_the_numbers() {
    let input = write("prec.obj", QUAD_GRID);
    let a = tmp("prec64.obj");
    let b = tmp("prec32.obj");
    let c = tmp("limit.obj");
    for (out, extra) in [
        (&a, vec![]),
        (&b, vec!["--precision", "f32"]),
        (&c, vec!["--limit"]),
    ] {
        let mut args = vec![
            "refine",
            input.to_str().unwrap(),
            "--engine",
            "osd",
            "--level",
            "1",
            "-o",
            out.to_str().unwrap(),
        ];
        args.extend(extra);
        let o = subdiv(&args);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    let line = |p: &Path, n: usize| {
        std::fs::read_to_string(p)
            .unwrap()
            .lines()
            .nth(n)
            .unwrap()
            .to_string()
    };
    // Vertex 4 (the bump at 0.5) after one level: (Q + 2R + S) / 4 with
    // Q = mean of four face points, R = mean of four edge midpoints.
    // z: Q = 0.125, R = 0.25, S = 0.5 -> (0.125 + 0.5 + 0.5) / 4 = 0.28125.
    assert_eq!(line(&a, 4), "v 1 1 0.28125");
    assert_eq!(line(&b, 4), "v 1 1 0.28125");
    assert_ne!(
        line(&c, 4),
        line(&a, 4),
        "limit positions differ from refined ones"
    );
    // A bump of 0.3 gives inexact values: 17 significant digits in f64, 9 in f32.
    let input = write("prec-inexact.obj", &QUAD_GRID.replace("1 1 0.5", "1 1 0.3"));
    for (out, prec, digits) in [(&a, "f64", 17), (&b, "f32", 9)] {
        let args = [
            "refine",
            input.to_str().unwrap(),
            "--engine",
            "osd",
            "--level",
            "1",
            "--precision",
            prec,
            "-o",
            out.to_str().unwrap(),
        ];
        let o = subdiv(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let z = line(out, 4).rsplit(' ').next().unwrap().to_string();
        let significant = z.replace('.', "").trim_start_matches('0').len();
        assert_eq!(significant, digits, "{prec}: {z}");
        let expected = 0.3 * 9.0 / 16.0;
        assert!((z.parse::<f64>().unwrap() - expected).abs() < 1e-7, "{z}");
    }
}

#[test]
fn builtin_shapes_and_version() {
    let o = subdiv(&["version"]);
    assert!(o.status.success());
    #[cfg(feature = "osd")]
    assert!(stdout(&o).contains("OpenSubdiv 3.5.0"), "{}", stdout(&o));
    let o = subdiv(&["demo"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("vertices 8→26→98, faces 6→24→96"),
        "{}",
        stdout(&o)
    );
    let o = subdiv(&["refine", "--builtin", "nope", "--engine", "osd"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("unknown built-in shape"));
    let o = subdiv(&[
        "refine",
        "--builtin",
        "cube",
        "--engine",
        "osd",
        "--level",
        "11",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("level 11"), "{}", stderr(&o));
}
