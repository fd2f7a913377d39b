//! `subdiv refine --adaptive` and `subdiv compare --adaptive`: level counts
//! derived by hand, `--levels-json` against the library bit for bit and
//! between engines, the engines compared, and the refusals. Tests that need
//! OpenSubdiv are marked; the others run in every build.

use crate::engines;
use crate::support::{obj_text, scratch, stderr, stdout, subdiv, write};
use std::path::Path;
use subdiv::refiner::Refiner;
use subdiv::{AdaptiveOptions, Crease, Mesh, Options, shapes};

/// The cube's counts at isolation 3, by hand: all 8 corners are
/// extraordinary (valence 3) and every face of levels 0 and 1 touches one,
/// so levels 1 and 2 are whole (26/48/24 and 98/192/96); level 3 refines
/// the 3 faces at each corner (12 children) plus, of the faces around that
/// patch, the children next to it: 2 in each of the 6 sharing an edge with
/// it, 1 in each of the 3 touching it at a corner: 8 × (12 + 12 + 3) = 216
/// faces (as the library's `refiner::adaptive` documents).
const CUBE_3: &str = "vertices 8→26→98→296, edges 12→48→192→504, faces 6→24→96→216";

/// Runs `subdiv refine INPUT ARGS...`.
fn refine(input: &Path, args: &[&str]) -> std::process::Output {
    let mut all = vec!["refine", input.to_str().unwrap()];
    all.extend_from_slice(args);
    subdiv(&all)
}

/// The cube with a crease of sharpness 2.5 along its edge 0-1 and face 5 a hole.
fn creased_cube_with_hole() -> Mesh {
    let mut m = shapes::cube();
    m.creases.push(Crease {
        vertices: [0, 1],
        sharpness: 2.5,
    });
    m.holes.push(5);
    m
}

#[test]
fn refine_adaptive_reports_every_levels_counts() {
    let dir = scratch("adaptive-cube-counts");
    let cube = write(&dir, "cube.obj", &obj_text(&shapes::cube()));
    for engine in engines() {
        let o = refine(&cube, &["--adaptive", "3", "--engine", engine]);
        assert!(o.status.success(), "{engine}: {}", stderr(&o));
        let text = stdout(&o);
        assert!(text.contains(CUBE_3), "{engine}: {text}");
        assert!(text.contains(&format!("adaptive level 3 ({engine}, f64)")));
        assert!(!text.contains("stopped"), "{text}");
    }
    // A torus has no feature: nothing is selected at level 1.
    let torus = write(&dir, "torus.obj", &obj_text(&shapes::torus(8, 6)));
    for engine in engines() {
        let o = refine(&torus, &["--adaptive", "2", "--engine", engine]);
        assert!(o.status.success(), "{engine}: {}", stderr(&o));
        let text = stdout(&o);
        assert!(
            text.contains(
                "vertices 48, edges 96, faces 48; stopped at level 0 of 2: level 1 selected no face"
            ),
            "{engine}: {text}"
        );
    }
}

/// The numbers of the `positions` arrays of a `--levels-json` text, level
/// by level, read with Rust's correctly rounded parser (serde_json's
/// default float parser is not: it may be one unit in the last place off).
fn json_positions(text: &str) -> Vec<Vec<[f64; 3]>> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(start) = rest.find("\"positions\":[") {
        rest = &rest[start + "\"positions\":[".len()..];
        let end = rest.find("]]").map_or(0, |e| e + 1);
        let numbers: Vec<f64> = rest[..end]
            .split(',')
            .map(|n| n.trim_matches(|c| c == '[' || c == ']'))
            .filter(|n| !n.is_empty())
            .map(|n| n.parse::<f64>().unwrap_or_else(|e| panic!("{n}: {e}")))
            .collect();
        out.push(
            numbers
                .chunks_exact(3)
                .map(|c| [c[0], c[1], c[2]])
                .collect(),
        );
        rest = &rest[end..];
    }
    out
}

#[test]
fn levels_json_is_the_librarys_refinement_bit_for_bit() {
    let dir = scratch("adaptive-levels-json");
    let mesh = creased_cube_with_hole();
    let input = write(&dir, "creased.obj", &obj_text(&mesh));
    let out = dir.join("levels.json");
    let o = refine(
        &input,
        &["--adaptive", "3", "--levels-json", out.to_str().unwrap()],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("levels 0..3"), "{}", stdout(&o));
    let text = std::fs::read_to_string(&out).unwrap();
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    // The file's options are the shape-file defaults, as `refine` reads them.
    let adaptive = Refiner::new(&mesh, &Options::shape_file_defaults())
        .unwrap()
        .refine_adaptive(AdaptiveOptions::new(3), &[])
        .unwrap();
    let expected = adaptive.refine_positions(&mesh.positions).unwrap();
    let levels = json["levels"].as_array().unwrap();
    assert_eq!(levels.len(), 4);
    let positions = json_positions(&text);
    assert_eq!(positions.len(), 4);
    for (l, level) in levels.iter().enumerate() {
        let topology = adaptive.level(l as u32).unwrap();
        assert_eq!(level["vertices"], topology.vertex_count, "level {l}");
        assert_eq!(level["edges"], topology.edge_count, "level {l}");
        assert_eq!(level["faces"], topology.face_count(), "level {l}");
        let faces: Vec<Vec<u32>> = serde_json::from_value(level["face_vertices"].clone()).unwrap();
        assert_eq!(
            faces,
            topology.faces().map(<[u32]>::to_vec).collect::<Vec<_>>()
        );
        let holes: Vec<usize> = serde_json::from_value(level["holes"].clone()).unwrap();
        let expected_holes: Vec<usize> = (0..topology.face_count())
            .filter(|&f| topology.face_holes[f])
            .collect();
        assert_eq!(holes, expected_holes, "level {l}");
        assert!(!holes.is_empty(), "the hole's children stay, as holes");
        let bits = |p: &[[f64; 3]]| {
            p.iter()
                .flat_map(|v| v.map(f64::to_bits))
                .collect::<Vec<_>>()
        };
        let mine: Vec<[f64; 3]> = expected[l].iter().map(|p| p.to_array()).collect();
        assert_eq!(bits(&positions[l]), bits(&mine), "positions of level {l}");
    }
    // Level 1's positions are not all trivially short numbers.
    assert!(text.contains("0.2777777777777778"), "{}", &text[..400]);
    // Only the file was written: no temporary file stays.
    assert_eq!(
        crate::support::file_names(&dir),
        ["creased.obj", "levels.json"]
    );
}

#[cfg(feature = "osd")]
#[test]
fn native_and_opensubdiv_write_the_same_levels_json() {
    let dir = scratch("adaptive-json-engines");
    let input = write(&dir, "creased.obj", &obj_text(&creased_cube_with_hole()));
    for extra in [
        &[][..],
        &["--faces-first", "--select-faces", "0,2,5"][..],
        &["--single-crease", "--secondary", "1"][..],
        &["--inf-sharp", "--boundary", "none"][..],
    ] {
        let mut files = Vec::new();
        for engine in ["native", "osd"] {
            let out = dir.join(format!("{engine}.json"));
            let mut args = vec![
                "--adaptive",
                "4",
                "--engine",
                engine,
                "--levels-json",
                out.to_str().unwrap(),
            ];
            args.extend_from_slice(extra);
            let o = refine(&input, &args);
            assert!(o.status.success(), "{engine} {extra:?}: {}", stderr(&o));
            files.push(std::fs::read(&out).unwrap());
        }
        assert!(files[0].len() > 1000);
        assert!(files[0] == files[1], "{extra:?}: the engines' JSON differ");
    }
}

#[cfg(feature = "osd")]
#[test]
fn compare_adaptive_finds_the_engines_identical() {
    let dir = scratch("adaptive-compare");
    let corpus = shapes::corpus();
    for name in ["cube", "pyramid-5", "four-boxes", "grid-4x3"] {
        let mesh = &corpus.iter().find(|(n, _)| n == name).unwrap().1;
        let input = write(&dir, &format!("{name}.obj"), &obj_text(mesh));
        for extra in [&[][..], &["--single-crease", "--secondary", "2"][..]] {
            let mut args = vec!["compare", input.to_str().unwrap(), "--adaptive", "3"];
            args.extend_from_slice(extra);
            let o = subdiv(&args);
            assert_eq!(o.status.code(), Some(0), "{name}: {}", stderr(&o));
            let text = stdout(&o);
            assert!(
                text.contains("the engines agree (bit for bit)"),
                "{name}: {text}"
            );
            assert!(!text.contains("DIFFERENT"), "{name}: {text}");
        }
    }
    let cube = dir.join("cube.obj");
    let o = subdiv(&[
        "compare",
        cube.to_str().unwrap(),
        "--adaptive",
        "3",
        "--json",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let json: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(json["identical"], true);
    assert_eq!(json["agrees"], true);
    assert_eq!(json["native_deepest_level"], 3);
    assert_eq!(json["levels"][3]["native_counts"][2], 216);
    assert_eq!(
        json["levels"][3]["first_difference"],
        serde_json::Value::Null
    );
}

#[test]
fn adaptive_usage_errors_name_the_problem() {
    let dir = scratch("adaptive-usage");
    let cube = write(&dir, "cube.obj", &obj_text(&shapes::cube()));
    let out = dir.join("out.obj");
    let json = dir.join("out.json");
    let cases: [(&[&str], &[&str]); 9] = [
        (
            &["--adaptive", "2", "--level", "1"],
            &["--adaptive", "--level"],
        ),
        (
            &["--adaptive", "11"],
            &["level 11 is deeper than the supported 10"],
        ),
        (
            &["--adaptive", "2", "--select-faces", "0,7"],
            &["--select-faces", "face 7", "6 faces"],
        ),
        (
            &["--adaptive", "2", "--select-faces", "x"],
            &["--select-faces"],
        ),
        (
            &["--adaptive", "2", "-o", out.to_str().unwrap()],
            &["--adaptive", "--output"],
        ),
        (&["--adaptive", "2", "--limit"], &["--adaptive", "--limit"]),
        (
            &["--adaptive", "2", "--precision", "f32"],
            &["--adaptive", "--precision"],
        ),
        (
            &["--adaptive", "2", "--secondary", "16"],
            &["secondary level is 0 to 15"],
        ),
        (&["--levels-json", json.to_str().unwrap()], &["--adaptive"]),
    ];
    for (args, words) in cases {
        let o = refine(&cube, args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        let err = stderr(&o);
        for w in words {
            assert!(err.contains(w), "{args:?}: {w:?} not in {err}");
        }
    }
    let o = subdiv(&[
        "compare",
        cube.to_str().unwrap(),
        "--adaptive",
        "2",
        "--levels",
        "1..2",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--levels"), "{}", stderr(&o));
    let o = refine(&cube, &["--adaptive", "2", "--scheme", "doo-sabin"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("doo-sabin"), "{}", stderr(&o));
    // Nothing was written.
    assert_eq!(crate::support::file_names(&dir), ["cube.obj"]);
}

/// Loop, and the features of a non-linear face-varying channel, refine
/// adaptively in both engines, identically.
#[test]
fn loop_and_face_varying_features() {
    let dir = scratch("adaptive-loop");
    let ico = write(&dir, "ico.obj", &obj_text(&shapes::icosahedron()));
    let json = |engine: &str| {
        let out = dir.join(format!("ico-{engine}.json"));
        let o = refine(
            &ico,
            &[
                "--engine",
                engine,
                "--scheme",
                "loop",
                "--adaptive",
                "3",
                "--levels-json",
                out.to_str().unwrap(),
            ],
        );
        assert!(o.status.success(), "{}", stderr(&o));
        std::fs::read(out).unwrap()
    };
    let native = json("native");
    let levels: serde_json::Value = serde_json::from_slice(&native).unwrap();
    // 12 patches of 5 + 5 + 10 triangles with 4, 3 and 1 children
    // (native_adaptive.rs derives it).
    assert_eq!(levels["levels"][3]["faces"], 540);
    if cfg!(feature = "osd") {
        assert_eq!(native, json("osd"));
        let o = subdiv(&[
            "compare",
            ico.to_str().unwrap(),
            "--scheme",
            "loop",
            "--adaptive",
            "3",
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
    }

    // Face-varying features of a non-linear channel (`--consider-fvar`):
    // both engines isolate the same faces.
    let uvs = write(&dir, "uvs.obj", &obj_text(&shapes::cube_with_uvs()));
    let fvar_json = |engine: &str| {
        let out = dir.join(format!("uvs-{engine}.json"));
        let o = refine(
            &uvs,
            &[
                "--engine",
                engine,
                "--fvar",
                "none",
                "--adaptive",
                "3",
                "--consider-fvar",
                "--levels-json",
                out.to_str().unwrap(),
            ],
        );
        assert!(o.status.success(), "{}", stderr(&o));
        std::fs::read(out).unwrap()
    };
    let native = fvar_json("native");
    if cfg!(feature = "osd") {
        assert_eq!(native, fvar_json("osd"));
    }
}

/// Without the `osd` feature, OpenSubdiv's adaptive refinement is "not
/// available" (exit 4), for `refine --engine osd` and for `compare`.
#[cfg(not(feature = "osd"))]
#[test]
fn without_opensubdiv_adaptive_osd_is_unavailable() {
    let dir = scratch("adaptive-no-osd");
    let cube = write(&dir, "cube.obj", &obj_text(&shapes::cube()));
    for args in [
        &[
            "refine",
            cube.to_str().unwrap(),
            "--engine",
            "osd",
            "--adaptive",
            "2",
        ][..],
        &["compare", cube.to_str().unwrap(), "--adaptive", "2"][..],
    ] {
        let o = subdiv(args);
        assert_eq!(o.status.code(), Some(4), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains("not available"), "{}", stderr(&o));
    }
}
