//! `subdiv refine` (and `version`, `demo`, built-in shapes): output files,
//! summaries, precision, limit positions, holes, tags and their errors.
//! Tests that refine with `--engine osd` need the `osd` feature; errors found
//! before any refinement are the same without it.

use crate::support::{refine_to, scratch, stderr, stdout, subdiv, write};
use crate::{engines, quad_grid};
// Used by the tests that refine with OpenSubdiv only.
#[cfg(feature = "osd")]
use {crate::quad_grid_mesh, crate::support::obj_text, std::path::Path, subdiv::FVarChannel};

#[cfg(feature = "osd")]
#[test]
fn native_engine_writes_the_same_file_as_opensubdiv() {
    let dir = scratch("refine-native-vs-osd");
    let native = dir.join("native-out.obj");
    let osd = dir.join("native-osd-out.obj");
    // The grid with a UV per vertex (`f a/a ...`, the UV being the vertex's
    // x y): the native engine writes `-o` without --limit from the last level only.
    let mut with_uvs = quad_grid_mesh();
    with_uvs.fvar_channels.push(FVarChannel {
        width: 2,
        values: with_uvs.positions.iter().flat_map(|p| [p.x, p.y]).collect(),
        indices: with_uvs.face_vertices.clone(),
    });
    let mut holed = quad_grid_mesh();
    holed.holes.push(3);
    for (name, mesh, extra, faces) in [
        ("native.obj", quad_grid_mesh(), &[][..], 256),
        ("native-uv.obj", with_uvs, &["--precision", "f32"][..], 256),
        ("native-hole.obj", holed, &["--faces-first"][..], 192),
    ] {
        let input = write(&dir, name, &obj_text(&mesh));
        for (engine, out) in [("native", &native), ("osd", &osd)] {
            let mut args = vec!["--level", "3"];
            args.extend(extra);
            let o = refine_to(&input, engine, out, &args);
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
    let input = dir.join("native.obj");
    // The same for limit positions.
    for (engine, out) in [("native", &native), ("osd", &osd)] {
        let o = refine_to(&input, engine, out, &["--level", "2", "--limit"]);
        assert!(o.status.success(), "{engine} --limit: {}", stderr(&o));
    }
    let (a, b) = (
        std::fs::read_to_string(&native).unwrap(),
        std::fs::read_to_string(&osd).unwrap(),
    );
    assert_eq!(a, b, "native and OpenSubdiv limit output differ");
}

#[test]
fn malformed_obj_names_file_and_line() {
    let dir = scratch("refine-malformed-obj");
    let input = write(&dir, "bad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 zero\nf 1 2 3\n");
    let out = dir.join("bad-out.obj");
    let o = refine_to(&input, "osd", &out, &[]);
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(err.contains("bad.obj:3:"), "{err}");
    assert!(!out.exists());
}

#[test]
fn bad_index_and_bad_tag_are_errors() {
    let dir = scratch("refine-bad-index-and-tag");
    let input = write(&dir, "range.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 4\n");
    let o = subdiv(&["refine", input.to_str().unwrap(), "--engine", "osd"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("range.obj:4:"), "{}", stderr(&o));

    let text = format!("{}t interpolateboundary 1/0/0 7\n", quad_grid());
    let input = write(&dir, "tag.obj", &text);
    let o = subdiv(&["refine", input.to_str().unwrap(), "--engine", "osd"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("tag.obj:14:"), "{}", stderr(&o));
}

#[cfg(feature = "osd")]
#[test]
fn summary_without_output() {
    let dir = scratch("refine-summary");
    let input = write(&dir, "summary.obj", &quad_grid());
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

#[cfg(feature = "osd")]
#[test]
fn crease_without_edge_warns_or_fails_under_strict() {
    let dir = scratch("refine-crease-without-edge");
    let text = format!("{}t crease 2/1/0 0 8 3.0\n", quad_grid());
    let input = write(&dir, "diag.obj", &text);
    let o = subdiv(&["refine", input.to_str().unwrap(), "--engine", "osd"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("share no edge"), "{}", stderr(&o));
    let out = dir.join("diag-out.obj");
    let o = refine_to(&input, "osd", &out, &["--strict"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("share no edge"), "{}", stderr(&o));
    assert!(!out.exists());
}

#[cfg(feature = "osd")]
#[test]
fn output_obj_in_opensubdiv_order_with_holes_left_out() {
    let dir = scratch("refine-holes-left-out");
    let text = format!("{}t hole 1/0/0 3\n", quad_grid());
    let input = write(&dir, "hole.obj", &text);
    let out = dir.join("hole-out.obj");
    let o = refine_to(&input, "osd", &out, &["--level", "1"]);
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

#[cfg(feature = "osd")]
#[test]
fn precision_and_limit_change_the_numbers() {
    let dir = scratch("refine-precision-and-limit");
    let input = write(&dir, "prec.obj", &quad_grid());
    let a = dir.join("prec64.obj");
    let b = dir.join("prec32.obj");
    let c = dir.join("limit.obj");
    for (out, extra) in [
        (&a, vec![]),
        (&b, vec!["--precision", "f32"]),
        (&c, vec!["--limit"]),
    ] {
        let mut args = vec!["--level", "1"];
        args.extend(extra);
        let o = refine_to(&input, "osd", out, &args);
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
    let mut inexact = quad_grid_mesh();
    inexact.positions[4].z = 0.3;
    let input = write(&dir, "prec-inexact.obj", &obj_text(&inexact));
    for (out, prec, digits) in [(&a, "f64", 17), (&b, "f32", 9)] {
        let o = refine_to(&input, "osd", out, &["--level", "1", "--precision", prec]);
        assert!(o.status.success(), "{}", stderr(&o));
        let z = line(out, 4).rsplit(' ').next().unwrap().to_string();
        let significant = z.replace('.', "").trim_start_matches('0').len();
        assert_eq!(significant, digits, "{prec}: {z}");
        let expected = 0.3 * 9.0 / 16.0;
        assert!((z.parse::<f64>().unwrap() - expected).abs() < 1e-7, "{z}");
    }
}

/// `--peak-memory` (hidden; the whole-process benchmark reads it): one
/// `peak_memory_bytes N` line on stderr, N the process's peak resident memory.
#[test]
fn peak_memory_is_printed_on_stderr() {
    let dir = scratch("refine-peak-memory");
    let input = write(&dir, "grid.obj", &quad_grid());
    for engine in engines() {
        let o = subdiv(&[
            "refine",
            input.to_str().unwrap(),
            "--level",
            "2",
            "--engine",
            engine,
            "--peak-memory",
        ]);
        assert!(o.status.success(), "{engine}: {}", stderr(&o));
        let err = stderr(&o);
        let values: Vec<u64> = err
            .lines()
            .filter_map(|l| l.strip_prefix("peak_memory_bytes "))
            .map(|n| n.parse().unwrap_or_else(|e| panic!("{engine}: {n:?}: {e}")))
            .collect();
        assert_eq!(values.len(), 1, "{engine}: {err}");
        assert!(values[0] > 1 << 20, "{engine}: {} bytes", values[0]);
        // The summary still goes to stdout, and nothing else to stderr.
        assert!(stdout(&o).contains("vertices 9→25→81"), "{}", stdout(&o));
        assert_eq!(err.lines().count(), 1, "{engine}: {err}");
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
    // Usage errors exit 2.
    let o = subdiv(&["refine", "--builtin", "nope", "--engine", "osd"]);
    assert_eq!(o.status.code(), Some(2));
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
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("level 11 is deeper than the supported 10"),
        "{}",
        stderr(&o)
    );
}
