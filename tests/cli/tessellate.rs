//! `subdiv tessellate` and `subdiv eval --surface bfr`: the OBJ written is
//! the library's watertight mesh (counts of the patterns, every edge on two
//! facets of a closed shape, normals and UVs as asked), both engines agree,
//! and refusals name their line or option.

use crate::engines;
use crate::support::{obj_text, scratch, stderr, subdiv, write};
use std::collections::HashMap;
use subdiv::shapes;

/// The `v`, `vt`, `vn` lines and the faces (0-based position indices) of an OBJ.
struct Obj {
    v: Vec<[f64; 3]>,
    vt: usize,
    vn: Vec<[f64; 3]>,
    faces: Vec<Vec<usize>>,
    corners_with_uv: usize,
}

fn read_obj(text: &str) -> Obj {
    let mut obj = Obj {
        v: Vec::new(),
        vt: 0,
        vn: Vec::new(),
        faces: Vec::new(),
        corners_with_uv: 0,
    };
    let triple = |f: &[&str]| {
        [
            f[1].parse().unwrap(),
            f[2].parse().unwrap(),
            f[3].parse().unwrap(),
        ]
    };
    for line in text.lines() {
        let f: Vec<&str> = line.split(' ').collect();
        match f[0] {
            "v" => obj.v.push(triple(&f)),
            "vn" => obj.vn.push(triple(&f)),
            "vt" => obj.vt += 1,
            "f" => {
                let corners: Vec<&str> = f[1..].to_vec();
                obj.corners_with_uv += corners
                    .iter()
                    .filter(|c| c.split('/').nth(1).is_some_and(|t| !t.is_empty()))
                    .count();
                obj.faces.push(
                    corners
                        .iter()
                        .map(|c| c.split('/').next().unwrap().parse::<usize>().unwrap() - 1)
                        .collect(),
                );
            }
            other => panic!("unexpected line {other:?}"),
        }
    }
    obj
}

fn tessellate(input: &str, engine: &str, extra: &[&str]) -> Obj {
    // Each run its own output, beside the input.
    static RUNS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let run = RUNS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let out = std::path::Path::new(input).with_file_name(format!("out-{engine}-{run}.obj"));
    let mut args = vec![
        "tessellate",
        input,
        "--engine",
        engine,
        "-o",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let o = subdiv(&args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    read_obj(&std::fs::read_to_string(&out).unwrap())
}

/// Every edge of a closed surface on exactly two faces, in opposite directions.
fn assert_closed(obj: &Obj) {
    let mut edges: HashMap<(usize, usize), u32> = HashMap::new();
    for f in &obj.faces {
        for i in 0..f.len() {
            *edges.entry((f[i], f[(i + 1) % f.len()])).or_default() += 1;
        }
    }
    for (&(a, b), &n) in &edges {
        assert_eq!(
            (n, edges.get(&(b, a)).copied()),
            (1, Some(1)),
            "edge {a}-{b}"
        );
    }
}

#[test]
fn the_cube_tessellates_into_a_closed_mesh_on_every_engine() {
    let dir = scratch("cli-tessellate-cube");
    let input = write(&dir, "cube.obj", &obj_text(&shapes::cube()));
    let input = input.to_str().unwrap();
    let mut first: Option<Obj> = None;
    for &engine in engines() {
        for (rate, quads) in [("1", false), ("3", false), ("8", true)] {
            let r: usize = rate.parse().unwrap();
            let mut extra = vec!["--rate", rate, "--normals"];
            if quads {
                extra.push("--quads");
            }
            let obj = tessellate(input, engine, &extra);
            assert_eq!(
                obj.v.len(),
                8 + 12 * (r - 1) + 6 * (r - 1) * (r - 1),
                "{engine} rate {r}"
            );
            assert_eq!(obj.faces.len(), 6 * r * r * if quads { 1 } else { 2 });
            assert_eq!(obj.vn.len(), obj.v.len());
            assert_eq!(obj.vt, 0);
            assert_closed(&obj);
            if r == 3 {
                match &first {
                    None => first = Some(obj),
                    Some(f) => {
                        // The engines agree point by point.
                        for (a, b) in f.v.iter().zip(&obj.v) {
                            for k in 0..3 {
                                assert!((a[k] - b[k]).abs() < 1e-12, "{a:?} {b:?}");
                            }
                        }
                    }
                }
            }
        }
    }
    // Native surfaces from one refinement of the whole mesh agree too.
    let obj = tessellate(input, "native", &["--rate", "3", "--normals", "--global"]);
    assert_closed(&obj);
    let f = first.unwrap();
    assert_eq!(f.v.len(), obj.v.len());
    for (a, b) in f.v.iter().zip(&obj.v) {
        for k in 0..3 {
            assert!((a[k] - b[k]).abs() < 1e-12, "{a:?} {b:?}");
        }
    }
}

/// A Loop mesh (the icosahedron): counts of the triangle patterns, closed,
/// and the engines agree point by point at rates 1, 3 and 8.
#[test]
fn loop_meshes_tessellate_on_every_engine() {
    let dir = scratch("cli-tessellate-loop");
    let input = write(&dir, "ico.obj", &obj_text(&shapes::icosahedron()));
    let input = input.to_str().unwrap();
    for rate in ["1", "3", "8"] {
        let r: usize = rate.parse().unwrap();
        let mut first: Option<Obj> = None;
        for &engine in engines() {
            let obj = tessellate(input, engine, &["--scheme", "loop", "--rate", rate]);
            // 12 vertices, r - 1 points inside each of 30 edges, the
            // (r - 1)(r - 2) / 2 inside each of 20 triangles.
            assert_eq!(
                obj.v.len(),
                12 + 30 * (r - 1) + 20 * (r - 1) * r.saturating_sub(2) / 2,
                "{engine} rate {r}"
            );
            assert_eq!(obj.faces.len(), 20 * r * r);
            assert_closed(&obj);
            match &first {
                None => first = Some(obj),
                Some(f) => {
                    for (a, b) in f.v.iter().zip(&obj.v) {
                        for k in 0..3 {
                            assert!((a[k] - b[k]).abs() < 1e-9, "{a:?} {b:?}");
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn uvs_come_with_every_corner_and_edge_lengths_set_rates() {
    let dir = scratch("cli-tessellate-uv");
    let input = write(&dir, "cube.obj", &obj_text(&shapes::cube_with_uvs()));
    let obj = tessellate(input.to_str().unwrap(), "native", &["--rate", "2"]);
    // Each face has its own texture coordinates: (2 + 1)^2 per face.
    assert_eq!(obj.vt, 6 * 9);
    assert_eq!(obj.corners_with_uv, obj.faces.len() * 3);
    // The cube's edges are 1 long: 1 + floor(1 / 0.3) = 4 segments per edge.
    let obj = tessellate(input.to_str().unwrap(), "native", &["--edge-length", "0.3"]);
    assert_eq!(obj.v.len(), 8 + 12 * 3 + 6 * 9);
    assert_closed(&obj);
}

#[test]
fn refusals_name_the_option_or_line() {
    let dir = scratch("cli-tessellate-refusals");
    let mut cube = shapes::cube();
    cube.holes.push(2);
    let input = write(&dir, "cube.obj", &obj_text(&cube));
    let input = input.to_str().unwrap();
    let o = subdiv(&["tessellate", input, "--rate", "0", "-o", "-"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--rate"), "{}", stderr(&o));
    // A hole is left out: 5 faces at rate 1, an open box.
    let obj = tessellate(input, "native", &["--rate", "1"]);
    assert_eq!(obj.faces.len(), 5 * 2);
    for (text, message) in [
        ("0 0.5\n", "at.txt:1: expected FACE U V, found 2 fields"),
        (
            "\n0 1.5 0.5\n",
            "at.txt:2: (u, v) = (1.5, 0.5) is outside base face 0's parameterization",
        ),
        ("7 0.5 0.5\n", "at.txt:1: face 7 does not exist"),
        (
            "0 0 0\n2 0.5 0.5\n",
            "at.txt:2: face 2 has no limit surface",
        ),
    ] {
        let at = write(&dir, "at.txt", text);
        let o = subdiv(&[
            "eval",
            input,
            "--surface",
            "bfr",
            "--at",
            at.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(1), "{text:?}");
        assert!(stderr(&o).contains(message), "{text:?}: {}", stderr(&o));
    }
    // `--global` (the whole mesh's refinement) is for tessellation only.
    let at = write(&dir, "at.txt", "0 0.5 0.5\n");
    let o = subdiv(&[
        "eval",
        input,
        "--surface",
        "bfr",
        "--global",
        "--at",
        at.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--global"), "{}", stderr(&o));
}

#[test]
fn eval_bfr_gives_the_limit_points_of_the_base_vertices() {
    let dir = scratch("cli-eval-bfr");
    let mesh = shapes::cube();
    let input = write(&dir, "cube.obj", &obj_text(&mesh));
    // Each face's corner 0: the limit position of its first vertex.
    let text: String = (0..6).map(|f| format!("{f} 0 0\n")).collect();
    let at = write(&dir, "at.txt", &text);
    let limit = subdiv::refiner::Refiner::new(&mesh, &subdiv::Options::shape_file_defaults())
        .unwrap()
        .limit_positions(3, &mesh.flat_positions::<f64>())
        .unwrap();
    for &engine in engines() {
        let out = dir.join(format!("{engine}.txt"));
        let o = subdiv(&[
            "eval",
            input.to_str().unwrap(),
            "--surface",
            "bfr",
            "--engine",
            engine,
            "--at",
            at.to_str().unwrap(),
            "--derivatives",
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let rows: Vec<Vec<f64>> = std::fs::read_to_string(&out)
            .unwrap()
            .lines()
            .map(|l| l.split(' ').map(|x| x.parse().unwrap()).collect())
            .collect();
        assert_eq!(rows.len(), 6);
        for (f, row) in rows.iter().enumerate() {
            assert_eq!(row.len(), 9);
            let v = mesh.face(f)[0] as usize;
            for k in 0..3 {
                assert!(
                    (row[k] - limit[3 * v + k]).abs() < 1e-12,
                    "{engine} face {f}: {row:?}"
                );
            }
        }
    }
}

/// Smooth UVs (face-varying corners-plus-one) come from both engines, the
/// same: every corner with its texture coordinate, 9 per face of the cube
/// at rate 2.
#[test]
fn smooth_uvs_come_from_every_engine() {
    let dir = scratch("cli-tessellate-smooth-uv");
    let input = write(&dir, "cube.obj", &obj_text(&shapes::cube_with_uvs()));
    for &engine in engines() {
        let obj = tessellate(
            input.to_str().unwrap(),
            engine,
            &["--fvar", "corners-plus1", "--rate", "2"],
        );
        assert_eq!(obj.vt, 6 * 9, "{engine}");
        assert_eq!(obj.corners_with_uv, obj.faces.len() * 3, "{engine}");
    }
}

/// `bench --tessellation-only` on a user's mesh: only the tessellation
/// rows, both rates, the input named, the meshes checked equal first.
#[cfg(feature = "osd")]
#[test]
fn bench_tessellates_the_inputs_given() {
    let dir = scratch("cli-bench-tessellation");
    let input = write(&dir, "cube.obj", &obj_text(&shapes::cube()));
    let o = subdiv(&[
        "bench",
        input.to_str().unwrap(),
        "--tessellation-only",
        "--quick",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = crate::support::stdout(&o);
    let rows: Vec<&str> = text.lines().filter(|l| l.contains("cube.obj")).collect();
    assert_eq!(rows.len(), 2, "{text}");
    assert!(rows[0].contains("tessellation (rate 4)"), "{text}");
    assert!(rows[1].contains("tessellation (rate 16)"), "{text}");
    // 6 faces: 2 r² triangles each.
    assert!(rows[1].contains("| 3072 |"), "{text}");
    assert!(!text.contains("topology + positions"), "{text}");
    let o = subdiv(&["bench", "--tessellation-only", "--adaptive-only"]);
    assert_eq!(o.status.code(), Some(2));
}

/// OpenSubdiv's regression shape `catmark_val2_interior` with creases: two
/// hexagons folded onto each other, where Debian's 3.5.0 Bfr reads
/// uninitialised memory (fixed in 3.5.1, docs/CONFORMANCE.md).
const VAL2_CREASED: &str = "v -0.5 0 -1.75\nv 0 0 -1.75\nv 0 -0.5 -1.75\nv 0.5 0 -1.75\n\
    v -0.5 0 -0.75\nv 0 0 -0.75\nv 0 -0.5 -0.75\nv 0.5 0 -0.75\n\
    f 1 2 3 7 6 5\nf 8 6 7 3 2 4\n\
    t crease 2/1/0 1 2 5\nt crease 2/1/0 2 6 5\nt crease 2/1/0 6 5 5\n";

/// A face the OpenSubdiv bridge refuses is an error of the whole command on
/// that engine — never a face silently left out of the mesh or reported as
/// a hole — while the native engine tessellates and evaluates it.
#[test]
fn faces_opensubdiv_gets_wrong_are_refused_not_dropped() {
    let dir = scratch("cli-tessellate-val2");
    let input = write(&dir, "val2.obj", VAL2_CREASED);
    let input = input.to_str().unwrap();
    let at = write(&dir, "at.txt", "0 0.5 0.5\n1 0.1 0.1\n");
    let at = at.to_str().unwrap();
    for &engine in engines() {
        let out = dir.join(format!("{engine}.obj"));
        let t = subdiv(&[
            "tessellate",
            input,
            "--boundary",
            "edge-only",
            "--rate",
            "3",
            "--engine",
            engine,
            "-o",
            out.to_str().unwrap(),
        ]);
        let e = subdiv(&[
            "eval",
            input,
            "--surface",
            "bfr",
            "--boundary",
            "edge-only",
            "--engine",
            engine,
            "--at",
            at,
        ]);
        if engine == "native" {
            assert!(t.status.success(), "{}", stderr(&t));
            // Both hexagons, 30 triangles each at rate 3 (Bfr's n-gon pattern).
            assert_eq!(
                read_obj(&std::fs::read_to_string(&out).unwrap())
                    .faces
                    .len(),
                60
            );
            assert!(e.status.success(), "{}", stderr(&e));
        } else {
            for o in [&t, &e] {
                assert!(!o.status.success());
                let message = stderr(o);
                for needle in ["face 0", "interior vertex of valence 2", "3.5.1"] {
                    assert!(message.contains(needle), "{message}");
                }
                assert!(!message.contains("hole"), "{message}");
            }
            assert!(!out.exists(), "no output written");
        }
    }
}

/// `eval --surface bfr`: a location off its face names its line on every
/// engine, and a face without a surface says why.
#[test]
fn eval_bfr_refusals_name_their_line_on_every_engine() {
    let dir = scratch("cli-eval-bfr-refusals");
    let mut grid = shapes::grid(3, 3);
    grid.holes.push(4);
    let input = write(&dir, "grid.obj", &obj_text(&grid));
    let input = input.to_str().unwrap();
    for &engine in engines() {
        let run = |text: &str, extra: &[&str]| {
            let at = write(&dir, "at.txt", text);
            let mut args = vec!["eval", input, "--surface", "bfr", "--engine", engine];
            args.extend_from_slice(extra);
            args.extend(["--at", at.to_str().unwrap()]);
            let o = subdiv(&args);
            assert_eq!(
                o.status.code(),
                Some(1),
                "{engine} {text:?}: {}",
                stderr(&o)
            );
            stderr(&o)
        };
        let edge = ["--boundary", "edge-only"];
        let message = run("0 0.5 0.5\n3 0.25 0.75\n3 1.25 0.5\n", &edge);
        assert!(
            message.contains("at.txt:3: (u, v) = (1.25, 0.5) is outside base face 3's parameterization (the unit square)"),
            "{engine}: {message}"
        );
        let message = run("1 0.5 0.5\n", &["--boundary", "none"]);
        assert!(
            message.contains(
                "at.txt:1: face 1 has no limit surface (Bfr finds no limit neighbourhood"
            ),
            "{engine}: {message}"
        );
        let message = run("\n4 0.5 0.5\n", &edge);
        assert!(
            message.contains("at.txt:2: face 4 has no limit surface (a hole)"),
            "{engine}: {message}"
        );
    }
}
