//! `subdiv refine --scheme doo-sabin`: the summary, the output file against
//! the library, and what the scheme refuses.

use crate::support::{scratch, stderr, stdout, subdiv};
use subdiv::doo_sabin::{self, Boundary, DooSabinOptions, Weights};

#[test]
fn refine_doo_sabin() {
    let dir = scratch("doo-sabin-refine");
    let o = subdiv(&[
        "refine",
        "--builtin",
        "cube",
        "--scheme",
        "doo-sabin",
        "--level",
        "3",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let line = stdout(&o);
    assert!(
        line.starts_with(
            "builtin:cube: doo-sabin (original, open boundary) level 3 (native, f64): vertices 8→24→96→384, faces 6→26→98→386;"
        ),
        "{line}"
    );
    let out = dir.join("cube-ds.obj");
    let o = subdiv(&[
        "refine",
        "--builtin",
        "cube",
        "--scheme",
        "doo-sabin",
        "--doo-sabin-weights",
        "centroid",
        "--doo-sabin-boundary",
        "chaikin",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let read = subdiv::io::read_obj(&out).unwrap().mesh;
    let opts = DooSabinOptions {
        weights: Weights::Centroid,
        boundary: Boundary::Chaikin,
    };
    let expected = doo_sabin::refine(&subdiv::shapes::cube(), &opts, 2).unwrap();
    assert_eq!(
        read.positions, expected[2].positions,
        "17 digits read back exactly"
    );
    assert_eq!(read.face_vertices, expected[2].face_vertices);
    assert_eq!(read.face_offsets, expected[2].face_offsets);
}

#[test]
fn doo_sabin_refusals() {
    let run = |extra: &[&str]| {
        let mut args = vec!["refine", "--builtin", "cube", "--scheme", "doo-sabin"];
        args.extend_from_slice(extra);
        subdiv(&args)
    };
    // What no engine offers exits 4 (not available); misused flags exit 2.
    let o = run(&["--engine", "osd"]);
    assert_eq!(o.status.code(), Some(4));
    assert!(
        stderr(&o).contains("OpenSubdiv has no Doo-Sabin scheme"),
        "{}",
        stderr(&o)
    );
    let o = run(&["--limit"]);
    assert_eq!(o.status.code(), Some(4));
    assert!(stderr(&o).contains("doo-sabin has no limit evaluation"));
    let o = run(&["--precision", "f32"]);
    assert_eq!(o.status.code(), Some(4));
    let o = run(&["--boundary", "edge-only"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("--boundary does not apply"),
        "{}",
        stderr(&o)
    );
    let o = run(&["--level", "11"]);
    assert_eq!(o.status.code(), Some(2));
    let o = run(&["--doo-sabin-weights", "heavy"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("expected one of: original, centroid"));
    let o = subdiv(&["compare", "--builtin", "cube", "--scheme", "doo-sabin"]);
    assert_eq!(o.status.code(), Some(4));
    assert!(stderr(&o).contains("OpenSubdiv has no Doo-Sabin scheme"));
    // The Doo-Sabin options need the scheme.
    let o = subdiv(&[
        "refine",
        "--builtin",
        "cube",
        "--doo-sabin-weights",
        "centroid",
    ]);
    assert_eq!(o.status.code(), Some(2));
    // The OpenSubdiv schemes are unchanged, and the error lists doo-sabin.
    let o = subdiv(&["refine", "--builtin", "cube"]);
    assert!(o.status.success());
    assert!(stdout(&o).contains("catmark level 2"), "{}", stdout(&o));
    let o = subdiv(&["refine", "--builtin", "cube", "--scheme", "loop"]);
    assert!(!o.status.success() || stdout(&o).contains("loop level 2"));
    let o = subdiv(&["refine", "--builtin", "cube", "--scheme", "butterfly"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("expected one of: bilinear, catmark, loop, doo-sabin"),
        "{}",
        stderr(&o)
    );
    // Tags and UVs are ignored with a warning; --strict refuses them.
    let o = subdiv(&["refine", "--builtin", "cube-uv", "--scheme", "doo-sabin"]);
    assert!(o.status.success());
    assert!(stderr(&o).contains("doo-sabin ignores"), "{}", stderr(&o));
    let o = subdiv(&[
        "refine",
        "--builtin",
        "cube-uv",
        "--scheme",
        "doo-sabin",
        "--strict",
    ]);
    assert_eq!(o.status.code(), Some(1));
}
