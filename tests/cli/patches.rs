//! `subdiv patches` and `subdiv eval` with both engines: the summary and
//! JSON against the library's patch tables (native and OpenSubdiv's, which
//! are identical), evaluated points against the library's evaluation;
//! every refusal names its line or option.

use crate::support::{obj_text, scratch, stderr, stdout, subdiv, write};
use subdiv::patches::{Derivatives, PatchOptions};
use subdiv::{Options, osd, shapes};

fn cube_table(isolation: u32) -> (osd::TopologyRefiner, osd::OsdPatchTable) {
    let options = PatchOptions::new().max_isolation(isolation);
    let mut r =
        osd::TopologyRefiner::new(&shapes::cube(), &Options::shape_file_defaults()).unwrap();
    r.refine_adaptive(options.refine_adaptive_options(), &[])
        .unwrap();
    let t = r.patch_table(&options, &[]).unwrap();
    (r, t)
}

#[test]
fn patches_summary_and_json_are_the_librarys_table() {
    let dir = scratch("cli-patches-json");
    let input = write(&dir, "cube.obj", &obj_text(&shapes::cube()));
    let (_, table) = cube_table(2);
    let t = table.table();
    for engine in ["native", "osd"] {
        let json = dir.join(format!("cube-{engine}.json"));
        let out = subdiv(&[
            "patches",
            input.to_str().unwrap(),
            "--isolation",
            "2",
            "--engine",
            engine,
            "--json",
            json.to_str().unwrap(),
        ]);
        assert!(out.status.success(), "{}", stderr(&out));
        // Isolation 2: 16 patches per face, the 4 at the corners Gregory end caps.
        assert!(
        stdout(&out).contains(&format!("({engine}, isolation 2, Gregory basis end caps): 96 patches in 2 arrays: REGULAR 72, GREGORY_BASIS 24")),
        "{}",
        stdout(&out)
    );
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        assert_eq!(v["num_local_points"], t.local_points);
        let arrays = v["arrays"].as_array().unwrap();
        assert_eq!(arrays.len(), t.arrays.len());
        for (j, a) in arrays.iter().zip(&t.arrays) {
            assert_eq!(j["type"], a.patch_type.name());
            assert_eq!(j["num_patches"], a.len());
            for (p, cvs) in j["cvs"].as_array().unwrap().iter().enumerate() {
                let cvs: Vec<u32> = serde_json::from_value(cvs.clone()).unwrap();
                assert_eq!(cvs, a.patch_vertices(p));
            }
            for (p, param) in j["params"].as_array().unwrap().iter().enumerate() {
                let [f0, f1]: [u32; 2] = serde_json::from_value(param.clone()).unwrap();
                assert_eq!((f0, f1), (a.params[p].field0, a.params[p].field1));
            }
            assert_eq!(j["sharpness"].as_array().unwrap().len(), a.len());
        }
    }
    // Loop end caps are native: the tetrahedron's table (every patch
    // irregular, Gregory triangles with their local points) is
    // OpenSubdiv's.
    let tet = write(&dir, "tet.obj", &obj_text(&shapes::tetrahedron()));
    let tables = ["native", "osd"].map(|engine| {
        let json = dir.join(format!("tet-{engine}.json"));
        let out = subdiv(&[
            "patches",
            tet.to_str().unwrap(),
            "--scheme",
            "loop",
            "--engine",
            engine,
            "--json",
            json.to_str().unwrap(),
        ]);
        assert!(out.status.success(), "{engine}: {}", stderr(&out));
        std::fs::read_to_string(&json).unwrap()
    });
    assert_eq!(tables[0], tables[1]);
    assert!(tables[0].contains("GREGORY_TRIANGLE"), "{}", tables[0]);
}

#[test]
fn eval_prints_the_librarys_points_and_derivatives() {
    let dir = scratch("cli-eval");
    let input = write(&dir, "cube.obj", &obj_text(&shapes::cube()));
    let at = write(
        &dir,
        "at.txt",
        "# ptex face, u, v\n0 0.5 0.5\n\n3 0.25 1 # on an edge\n5 0 0\n",
    );
    let run = |engine: &str| -> Vec<Vec<f64>> {
        let out_path = dir.join(format!("out-{engine}.txt"));
        let out = subdiv(&[
            "eval",
            input.to_str().unwrap(),
            "--at",
            at.to_str().unwrap(),
            "--derivatives",
            "--engine",
            engine,
            "-o",
            out_path.to_str().unwrap(),
        ]);
        assert!(out.status.success(), "{}", stderr(&out));
        let text = std::fs::read_to_string(&out_path).unwrap();
        text.lines()
            .map(|l| l.split(' ').map(|x| x.parse().unwrap()).collect())
            .collect()
    };
    let rows = run("osd");
    assert_eq!(rows.len(), 3);
    // The native engine: its own table (identical), refinement, local
    // points and basis, within rounding of OpenSubdiv's.
    let native = run("native");
    assert_eq!(native.len(), 3);
    for (n, o) in native.iter().flatten().zip(rows.iter().flatten()) {
        assert!((n - o).abs() < 1e-12, "{native:?} against {rows:?}");
    }
    let (r, table) = cube_table(4);
    let base = shapes::cube().flat_positions::<f64>();
    let s = table
        .evaluate(
            &r,
            3,
            &base,
            &[(0, 0.5, 0.5), (3, 0.25, 1.0), (5, 0.0, 0.0)],
            Derivatives::First,
        )
        .unwrap();
    for (i, row) in rows.iter().enumerate() {
        assert_eq!(row.len(), 9);
        let expected: Vec<f64> = [&s.values.point, &s.values.du, &s.values.dv]
            .iter()
            .flat_map(|v| v[3 * i..3 * i + 3].to_vec())
            .collect();
        // 17 significant digits: the same f64s.
        assert_eq!(row, &expected);
    }
    // The centre of a cube face lies on the face's axis, by symmetry,
    // inside the cube (the limit surface shrinks from the cage).
    let centre = &rows[0][..3];
    let axis = (0..3)
        .max_by(|&a, &b| centre[a].abs().total_cmp(&centre[b].abs()))
        .unwrap();
    for (c, x) in centre.iter().enumerate() {
        if c == axis {
            assert!(x.abs() > 0.35 && x.abs() < 0.5, "{centre:?}");
        } else {
            assert!(x.abs() < 1e-9, "{centre:?}");
        }
    }
}

#[test]
fn eval_refusals_name_the_line() {
    let dir = scratch("cli-eval-refusals");
    let mut cube = shapes::cube();
    cube.holes.push(2);
    let input = write(&dir, "cube.obj", &obj_text(&cube));
    for (text, message) in [
        (
            "0 0.5\n",
            "at.txt:1: expected PTEX_FACE U V, found 2 fields",
        ),
        ("\n# c\n0 0.5 1.5\n", "at.txt:3: v = 1.5 is not in [0, 1]"),
        ("6 0.5 0.5\n", "at.txt:1: ptex face 6 does not exist"),
        (
            "0 0 0\n2 0.5 0.5\n",
            "at.txt:2: ptex face 2 at (0.5, 0.5) is in a hole",
        ),
        ("x 0 0\n", "at.txt:1: 'x' is not a ptex face index"),
    ] {
        let at = write(&dir, "at.txt", text);
        let out = subdiv(&[
            "eval",
            input.to_str().unwrap(),
            "--at",
            at.to_str().unwrap(),
        ]);
        assert_eq!(out.status.code(), Some(1), "{text:?}");
        assert!(stderr(&out).contains(message), "{text:?}: {}", stderr(&out));
    }
    // Loop's end caps and bases are native (no refusal any more): a
    // tetrahedron, every vertex irregular, evaluates as OpenSubdiv
    // evaluates it.
    let tet = write(&dir, "tet.obj", &obj_text(&shapes::tetrahedron()));
    let at = write(&dir, "at.txt", "0 0.5 0.25\n");
    let [native, osd] = ["native", "osd"].map(|engine| {
        let out = subdiv(&[
            "eval",
            tet.to_str().unwrap(),
            "--at",
            at.to_str().unwrap(),
            "--scheme",
            "loop",
            "--engine",
            engine,
        ]);
        assert!(out.status.success(), "{engine}: {}", stderr(&out));
        stdout(&out)
            .split_whitespace()
            .map(|x| x.parse::<f64>().unwrap())
            .collect::<Vec<_>>()
    });
    assert_eq!(native.len(), 3);
    for (a, b) in native.iter().zip(&osd) {
        assert!((a - b).abs() <= 1e-12, "{native:?} against {osd:?}");
    }
    let out = subdiv(&["patches", input.to_str().unwrap(), "--end-caps", "round"]);
    assert_eq!(out.status.code(), Some(2));
    let out = subdiv(&["patches", input.to_str().unwrap(), "--precision", "f32"]);
    assert_eq!(out.status.code(), Some(2));
}

/// `subdiv compare --patches`: identical tables and the same limit surface
/// on a creased mesh with every end-cap type (text and JSON), its options
/// passed through (`--adaptive N` the isolation, `--single-crease`), and
/// a Loop mesh with Gregory-triangle end caps.
#[test]
fn compare_patches_reports_identical_tables() {
    let dir = scratch("cli-compare-patches");
    let mut mesh = shapes::cube();
    mesh.creases.push(subdiv::Crease {
        vertices: [0, 1],
        sharpness: 2.5,
    });
    let input = write(&dir, "creased.obj", &obj_text(&mesh));
    for end_caps in ["gregory-basis", "bspline", "bilinear", "legacy-gregory"] {
        let out = subdiv(&[
            "compare",
            input.to_str().unwrap(),
            "--patches",
            "--adaptive",
            "3",
            "--single-crease",
            "--end-caps",
            end_caps,
        ]);
        assert!(out.status.success(), "{end_caps}: {}", stderr(&out));
        let text = stdout(&out);
        assert!(text.contains("patches (isolation 3,"), "{text}");
        assert!(text.contains("patch tables: identical ("), "{text}");
        assert!(text.contains("the engines agree"), "{text}");
        if end_caps != "legacy-gregory" {
            assert!(text.contains("limit surface at 150 locations"), "{text}");
        }
    }
    let out = subdiv(&["compare", input.to_str().unwrap(), "--patches", "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let v: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    assert_eq!(v["isolation"], 4);
    assert_eq!(v["end_caps"], "Gregory basis");
    assert_eq!(v["tables_identical"], true);
    assert_eq!(v["first_difference"], serde_json::Value::Null);
    assert!(v["relative_position_deviation"].as_f64().unwrap() <= 1e-12);
    assert_eq!(v["local_points"][0], v["local_points"][1]);
    let tet = write(&dir, "tet.obj", &obj_text(&shapes::tetrahedron()));
    let out = subdiv(&[
        "compare",
        tet.to_str().unwrap(),
        "--patches",
        "--scheme",
        "loop",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(text.contains("GREGORY_TRIANGLE"), "{text}");
    assert!(text.contains("the engines agree"), "{text}");
    // --end-caps needs --patches; --patches does not take --levels.
    let out = subdiv(&["compare", input.to_str().unwrap(), "--end-caps", "bspline"]);
    assert_eq!(out.status.code(), Some(2));
    let out = subdiv(&[
        "compare",
        input.to_str().unwrap(),
        "--patches",
        "--levels",
        "1..2",
    ]);
    assert_eq!(out.status.code(), Some(2));
}

/// `--double`: local points in double precision (patchPrecisionDouble), as
/// the library computes them; near an extraordinary corner the limit moves
/// by the `f32` stencils' rounding.
#[test]
fn eval_double_uses_double_precision_local_points() {
    use subdiv::patches;
    use subdiv::refiner::Refiner;
    let dir = scratch("cli-eval-double");
    let input = write(&dir, "cube.obj", &obj_text(&shapes::cube()));
    let at = write(&dir, "at.txt", "3 0.01 0.99\n");
    let run = |extra: &[&str]| -> Vec<f64> {
        let mut args = vec![
            "eval",
            input.to_str().unwrap(),
            "--at",
            at.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let out = subdiv(&args);
        assert!(out.status.success(), "{}", stderr(&out));
        stdout(&out)
            .split_whitespace()
            .map(|x| x.parse().unwrap())
            .collect()
    };
    let (single, double) = (run(&[]), run(&["--double"]));
    let mesh = shapes::cube();
    let po = PatchOptions::new().max_isolation(4).double_precision(true);
    let r = Refiner::new(&mesh, &Options::shape_file_defaults())
        .unwrap()
        .refine_adaptive(po.refine_adaptive_options(), &[])
        .unwrap();
    let t = r.patch_table(&po, &[]).unwrap();
    let points = r.patch_points(&t, 3, &mesh.flat_positions()).unwrap();
    let s = patches::evaluate(&t, &points, 3, &[(3, 0.01, 0.99)], Derivatives::None).unwrap();
    assert_eq!(double, s.values.point);
    assert!(single.iter().zip(&double).any(|(a, b)| a != b));
    assert!(
        single
            .iter()
            .zip(&double)
            .all(|(a, b)| (a - b).abs() < 1e-6)
    );
}

/// `subdiv eval --exact-limit`: on a creased cube with single-crease
/// patches, the semi-sharp crease the table without them isolates (where
/// the default, OpenSubdiv's `EvaluateBasis`, evaluates it infinitely
/// sharp); refused with the osd engine and with Bfr's surfaces.
#[test]
fn eval_exact_limit_honours_single_crease_sharpness() {
    let dir = scratch("cli-eval-exact");
    let mut cube = shapes::cube();
    cube.add_crease(0, 1, 2.7);
    cube.add_crease(1, 5, 2.7);
    let input = write(&dir, "cube.obj", &obj_text(&cube));
    let mut locations = String::new();
    for face in 0..6 {
        for (u, v) in [(0.1, 0.5), (0.5, 0.9), (0.95, 0.05), (0.5, 0.5)] {
            locations.push_str(&format!("{face} {u} {v}\n"));
        }
    }
    let at = write(&dir, "at.txt", &locations);
    let run = |extra: &[&str]| -> Vec<f64> {
        let mut args = vec![
            "eval",
            input.to_str().unwrap(),
            "--at",
            at.to_str().unwrap(),
            "--derivatives",
        ];
        args.extend_from_slice(extra);
        let out = subdiv(&args);
        assert!(out.status.success(), "{extra:?}: {}", stderr(&out));
        stdout(&out)
            .split_whitespace()
            .map(|x| x.parse().unwrap())
            .collect()
    };
    let isolated = run(&[]);
    let exact = run(&["--single-crease", "--exact-limit"]);
    let default = run(&["--single-crease"]);
    assert_eq!(isolated.len(), 24 * 9);
    let largest = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
    };
    assert!(
        largest(&exact, &isolated) < 1e-13,
        "{exact:?}\n{isolated:?}"
    );
    assert!(largest(&default, &isolated) > 1e-3);
    for (extra, code) in [
        (&["--exact-limit", "--engine", "osd"][..], 2),
        (&["--exact-limit", "--surface", "bfr"][..], 2),
    ] {
        let mut args = vec![
            "eval",
            input.to_str().unwrap(),
            "--at",
            at.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let out = subdiv(&args);
        assert_eq!(out.status.code(), Some(code), "{extra:?}");
        assert!(stderr(&out).contains("--exact-limit"), "{}", stderr(&out));
    }
}
