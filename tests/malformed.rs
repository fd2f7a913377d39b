//! Malformed input, through the library and through the command line.
//!
//! Every file of `tests/malformed/` gets exactly the error asserted here: its
//! kind, its line and its message. `subdiv refine` and `subdiv curve` exit 1
//! with `FILE:LINE: message` on stderr and leave no output file (nor a
//! temporary one) behind. The OpenSubdiv bridge refuses every malformed mesh
//! itself, even without Rust's validation in front of it. Absurd levels are
//! refused before anything is allocated, and the native refiner can be
//! shared by threads.
//!
//! Tests marked `#[ignore = "bug: ..."]` state the behaviour that is wanted
//! and fails today (run them with `cargo test --test malformed -- --ignored`).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};
use subdiv::curve::CurveScheme;
use subdiv::io::points::PointsErrorKind;
use subdiv::io::read_obj;
use subdiv::refiner::{self, Refiner};
use subdiv::{Error, MeshError, ObjErrorKind, Options, Scheme, UniformOptions, shapes};

fn malformed(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/malformed")
        .join(name)
}

fn subdiv(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_subdiv"))
        .args(args)
        .output()
        .expect("run subdiv")
}

/// A fresh, empty directory for one command's output.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("malformed")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Asserts that a command failed with exit status 1 and wrote nothing into `dir`.
fn assert_failed_cleanly(o: &Output, dir: &Path, what: &str) {
    assert_eq!(o.status.code(), Some(1), "{what}: {}", stderr(o));
    let left: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert!(left.is_empty(), "{what}: files left behind: {left:?}");
}

fn engines() -> &'static [&'static str] {
    if cfg!(feature = "osd") {
        &["native", "osd"]
    } else {
        &["native"]
    }
}

fn syntax(s: &str) -> ObjErrorKind {
    ObjErrorKind::Syntax(s.into())
}

fn bad_tag(tag: &str, message: &str) -> ObjErrorKind {
    ObjErrorKind::BadTag {
        tag: tag.into(),
        message: message.into(),
    }
}

fn tag_out_of_range(tag: &str, what: &'static str, index: i64, count: usize) -> ObjErrorKind {
    ObjErrorKind::TagOutOfRange {
        tag: tag.into(),
        what,
        index,
        count,
    }
}

fn out_of_range(what: &'static str, index: i64, count: usize) -> ObjErrorKind {
    ObjErrorKind::IndexOutOfRange { what, index, count }
}

/// The OBJ files that `read_obj` refuses: file, line, kind, message after `FILE:LINE: `.
fn obj_errors() -> Vec<(&'static str, usize, ObjErrorKind, &'static str)> {
    vec![
        (
            "bad_number.obj",
            5,
            syntax("'v' statement: z 'zero' is not a number"),
            "syntax error: 'v' statement: z 'zero' is not a number",
        ),
        (
            "bad_face_index.obj",
            5,
            syntax("face corner 3 'x': vertex index 'x' is not an integer"),
            "syntax error: face corner 3 'x': vertex index 'x' is not an integer",
        ),
        (
            "index_zero.obj",
            5,
            out_of_range("vertex", 0, 4),
            "vertex index 0 is out of range (4 defined so far)",
        ),
        (
            "index_out_of_range.obj",
            5,
            out_of_range("vertex", 5, 4),
            "vertex index 5 is out of range (4 defined so far)",
        ),
        (
            "negative_out_of_range.obj",
            5,
            out_of_range("vertex", -5, 4),
            "vertex index -5 is out of range (4 defined so far)",
        ),
        (
            "texcoord_out_of_range.obj",
            7,
            out_of_range("texture coordinate", 3, 2),
            "texture coordinate index 3 is out of range (2 defined so far)",
        ),
        (
            "face_two_corners.obj",
            5,
            ObjErrorKind::FaceTooSmall(2),
            "face has 2 corners; a face needs at least 3",
        ),
        (
            "face_no_corners.obj",
            5,
            ObjErrorKind::FaceTooSmall(0),
            "face has 0 corners; a face needs at least 3",
        ),
        // The limit of mesh validation (OpenSubdiv's), found by the reader
        // itself so that the error names the face's line.
        (
            "face_70000_corners.obj",
            5,
            ObjErrorKind::FaceTooLarge(70000),
            "face has 70000 corners; at most 65535 are supported",
        ),
        (
            "mixed_vt_in_face.obj",
            8,
            ObjErrorKind::InconsistentTexcoords(
                "corner 2 of this face has none but its corner 1 has one".into(),
            ),
            "texture coordinates must be given for every corner of every face or for none: \
             corner 2 of this face has none but its corner 1 has one",
        ),
        (
            "mixed_vt_across_faces.obj",
            10,
            ObjErrorKind::InconsistentTexcoords(
                "corner 1 of this face has none but the first face corner (line 8) has one".into(),
            ),
            "texture coordinates must be given for every corner of every face or for none: \
             corner 1 of this face has none but the first face corner (line 8) has one",
        ),
        (
            "nan_coordinate.obj",
            2,
            ObjErrorKind::NonFinite("y = nan in a 'v' statement".into()),
            "non-finite coordinate y = nan in a 'v' statement",
        ),
        (
            "inf_coordinate.obj",
            3,
            ObjErrorKind::NonFinite("z = -inf in a 'v' statement".into()),
            "non-finite coordinate z = -inf in a 'v' statement",
        ),
        (
            "overflow_coordinate.obj",
            2,
            ObjErrorKind::NonFinite("x = 1e999 in a 'v' statement".into()),
            "non-finite coordinate x = 1e999 in a 'v' statement",
        ),
        (
            "nan_texcoord.obj",
            5,
            ObjErrorKind::NonFinite("v = NaN in a 'vt' statement".into()),
            "non-finite coordinate v = NaN in a 'vt' statement",
        ),
        // Invalid UTF-8 is replaced; the NUL and \x01 of the field are escaped.
        (
            "binary_garbage.obj",
            5,
            syntax("'v' statement: x '\\0\\u{1}' is not a number"),
            "syntax error: 'v' statement: x '\\0\\u{1}' is not a number",
        ),
        // Terminal escape sequences (a window title, clearing the screen) and
        // a backslash are escaped: no message carries a control character.
        (
            "terminal_escapes.obj",
            5,
            syntax("'v' statement: z '\\u{1b}]0;pwned\\u{7}\\u{1b}[2J\\\\' is not a number"),
            "syntax error: 'v' statement: z '\\u{1b}]0;pwned\\u{7}\\u{1b}[2J\\\\' is not a number",
        ),
        // CRLF: the error is on the right line and the message has no '\r'.
        (
            "crlf.obj",
            6,
            bad_tag("crease", "float argument 1 'soft' is not a number"),
            "bad 'crease' tag: float argument 1 'soft' is not a number",
        ),
        // CR alone does not end a line: the whole file is one 'v' statement.
        (
            "cr_only.obj",
            1,
            syntax("a 'v' statement needs x y z [w] (or x y z r g b), found 15 values"),
            "syntax error: a 'v' statement needs x y z [w] (or x y z r g b), found 15 values",
        ),
        // Huge counts in a tag header are compared with the arguments, never allocated.
        (
            "huge_tag_count.obj",
            6,
            bad_tag(
                "crease",
                "the counts 999999999/0/0 announce 999999999 arguments but 0 follow",
            ),
            "bad 'crease' tag: the counts 999999999/0/0 announce 999999999 arguments but 0 follow",
        ),
        (
            "overflowing_tag_count.obj",
            6,
            bad_tag(
                "corner",
                "the counts 18446744073709551615/1/0 announce too many arguments but 2 follow",
            ),
            "bad 'corner' tag: the counts 18446744073709551615/1/0 announce too many arguments but 2 follow",
        ),
        // Every malformed form of a `t` tag.
        (
            "tag_no_name.obj",
            6,
            syntax("a 't' statement needs a tag name"),
            "syntax error: a 't' statement needs a tag name",
        ),
        (
            "tag_no_counts.obj",
            6,
            bad_tag(
                "crease",
                "the argument counts 'ints/floats/strings' are missing",
            ),
            "bad 'crease' tag: the argument counts 'ints/floats/strings' are missing",
        ),
        (
            "tag_two_counts.obj",
            6,
            bad_tag(
                "crease",
                "the argument counts must be written 'ints/floats/strings', found '2/1'",
            ),
            "bad 'crease' tag: the argument counts must be written 'ints/floats/strings', found '2/1'",
        ),
        (
            "tag_four_counts.obj",
            6,
            bad_tag(
                "crease",
                "the argument counts must be written 'ints/floats/strings', found '2/1/0/0'",
            ),
            "bad 'crease' tag: the argument counts must be written 'ints/floats/strings', found '2/1/0/0'",
        ),
        (
            "tag_count_not_a_number.obj",
            6,
            bad_tag(
                "crease",
                "the argument counts must be written 'ints/floats/strings', found 'two/1/0'",
            ),
            "bad 'crease' tag: the argument counts must be written 'ints/floats/strings', found 'two/1/0'",
        ),
        (
            "tag_negative_count.obj",
            6,
            bad_tag(
                "corner",
                "the argument counts must be written 'ints/floats/strings', found '-1/1/0'",
            ),
            "bad 'corner' tag: the argument counts must be written 'ints/floats/strings', found '-1/1/0'",
        ),
        (
            "tag_count_beyond_usize.obj",
            6,
            bad_tag(
                "hole",
                "the argument counts must be written 'ints/floats/strings', found '99999999999999999999/0/0'",
            ),
            "bad 'hole' tag: the argument counts must be written 'ints/floats/strings', found '99999999999999999999/0/0'",
        ),
        (
            "tag_huge_count.obj",
            6,
            bad_tag(
                "crease",
                "the counts 999999999/0/0 announce 999999999 arguments but 0 follow",
            ),
            "bad 'crease' tag: the counts 999999999/0/0 announce 999999999 arguments but 0 follow",
        ),
        (
            "tag_too_few_arguments.obj",
            6,
            bad_tag(
                "crease",
                "the counts 2/1/0 announce 3 arguments but 2 follow",
            ),
            "bad 'crease' tag: the counts 2/1/0 announce 3 arguments but 2 follow",
        ),
        (
            "tag_too_many_arguments.obj",
            6,
            bad_tag(
                "crease",
                "the counts 2/1/0 announce 3 arguments but 4 follow",
            ),
            "bad 'crease' tag: the counts 2/1/0 announce 3 arguments but 4 follow",
        ),
        (
            "tag_bad_integer.obj",
            6,
            bad_tag("crease", "integer argument 2 'one' is not an integer"),
            "bad 'crease' tag: integer argument 2 'one' is not an integer",
        ),
        (
            "tag_float_integer.obj",
            6,
            bad_tag("hole", "integer argument 1 '0.5' is not an integer"),
            "bad 'hole' tag: integer argument 1 '0.5' is not an integer",
        ),
        (
            "tag_bad_float.obj",
            6,
            bad_tag("crease", "float argument 1 'soft' is not a number"),
            "bad 'crease' tag: float argument 1 'soft' is not a number",
        ),
        (
            "tag_nan_sharpness.obj",
            6,
            bad_tag("crease", "sharpness 1 'nan' is not a finite number"),
            "bad 'crease' tag: sharpness 1 'nan' is not a finite number",
        ),
        (
            "tag_f32_overflow_sharpness.obj",
            6,
            bad_tag("corner", "sharpness 1 '1e39' is not a finite number"),
            "bad 'corner' tag: sharpness 1 '1e39' is not a finite number",
        ),
        (
            "tag_crease_with_string.obj",
            6,
            bad_tag("crease", "takes no string arguments, found 1"),
            "bad 'crease' tag: takes no string arguments, found 1",
        ),
        (
            "tag_crease_one_vertex.obj",
            6,
            bad_tag("crease", "needs a chain of at least 2 vertices, found 1"),
            "bad 'crease' tag: needs a chain of at least 2 vertices, found 1",
        ),
        (
            "tag_crease_wrong_sharpness_count.obj",
            6,
            bad_tag(
                "crease",
                "3 vertices make 2 edges: give 1 sharpness for all or 2 (one per edge), found 3",
            ),
            "bad 'crease' tag: 3 vertices make 2 edges: give 1 sharpness for all or 2 (one per edge), found 3",
        ),
        (
            "tag_crease_two_sharpness_one_edge.obj",
            6,
            bad_tag("crease", "needs 1 sharpness, found 2"),
            "bad 'crease' tag: needs 1 sharpness, found 2",
        ),
        (
            "tag_crease_no_sharpness.obj",
            6,
            bad_tag("crease", "needs 1 sharpness, found 0"),
            "bad 'crease' tag: needs 1 sharpness, found 0",
        ),
        (
            "tag_corner_no_vertex.obj",
            6,
            bad_tag("corner", "names no vertex"),
            "bad 'corner' tag: names no vertex",
        ),
        (
            "tag_corner_wrong_sharpness_count.obj",
            6,
            bad_tag(
                "corner",
                "give 1 sharpness for all 2 vertices or one each, found 3",
            ),
            "bad 'corner' tag: give 1 sharpness for all 2 vertices or one each, found 3",
        ),
        (
            "tag_hole_with_float.obj",
            6,
            bad_tag("hole", "takes only face indices (n/0/0), found 1/1/0"),
            "bad 'hole' tag: takes only face indices (n/0/0), found 1/1/0",
        ),
        (
            "tag_hole_no_face.obj",
            6,
            bad_tag("hole", "names no face"),
            "bad 'hole' tag: names no face",
        ),
        (
            "tag_boundary_unknown_value.obj",
            6,
            bad_tag(
                "interpolateboundary",
                "unknown value 7: expected 0 (none), 1 (edge and corner) or 2 (edge only)",
            ),
            "bad 'interpolateboundary' tag: unknown value 7: expected 0 (none), 1 (edge and corner) or 2 (edge only)",
        ),
        (
            "tag_boundary_two_values.obj",
            6,
            bad_tag(
                "interpolateboundary",
                "expects 1/0/0 arguments, found 2/0/0",
            ),
            "bad 'interpolateboundary' tag: expects 1/0/0 arguments, found 2/0/0",
        ),
        (
            "tag_boundary_as_string.obj",
            6,
            bad_tag(
                "interpolateboundary",
                "expects 1/0/0 arguments, found 0/0/1",
            ),
            "bad 'interpolateboundary' tag: expects 1/0/0 arguments, found 0/0/1",
        ),
        (
            "tag_fvar_unknown_value.obj",
            6,
            bad_tag(
                "facevaryinginterpolateboundary",
                "unknown value 6: expected 0 (none) to 5 (all)",
            ),
            "bad 'facevaryinginterpolateboundary' tag: unknown value 6: expected 0 (none) to 5 (all)",
        ),
        (
            "tag_fvar_negative_value.obj",
            6,
            bad_tag(
                "facevaryinginterpolateboundary",
                "unknown value -1: expected 0 (none) to 5 (all)",
            ),
            "bad 'facevaryinginterpolateboundary' tag: unknown value -1: expected 0 (none) to 5 (all)",
        ),
        (
            "tag_creasemethod_unknown.obj",
            6,
            bad_tag(
                "creasemethod",
                "unknown value 'smooth': expected 'normal' or 'chaikin'",
            ),
            "bad 'creasemethod' tag: unknown value 'smooth': expected 'normal' or 'chaikin'",
        ),
        (
            "tag_creasemethod_as_int.obj",
            6,
            bad_tag("creasemethod", "expects 0/0/1 arguments, found 1/0/0"),
            "bad 'creasemethod' tag: expects 0/0/1 arguments, found 1/0/0",
        ),
        (
            "tag_smoothtriangles_unknown.obj",
            6,
            bad_tag(
                "smoothtriangles",
                "unknown value 'loop': expected 'catmark' or 'smooth'",
            ),
            "bad 'smoothtriangles' tag: unknown value 'loop': expected 'catmark' or 'smooth'",
        ),
        // Tags naming vertices or faces that do not exist: checked once the
        // whole file is read, reported on the tag's own line.
        (
            "tag_crease_missing_vertex.obj",
            6,
            tag_out_of_range("crease", "vertex", 9, 4),
            "'crease' tag names vertex 9, which does not exist (4 in the file)",
        ),
        (
            "tag_corner_negative_vertex.obj",
            6,
            tag_out_of_range("corner", "vertex", -1, 4),
            "'corner' tag names vertex -1, which does not exist (4 in the file)",
        ),
        (
            "tag_hole_missing_face.obj",
            6,
            tag_out_of_range("hole", "face", 1, 1),
            "'hole' tag names face 1, which does not exist (1 in the file)",
        ),
        (
            "tag_early_missing_vertex.obj",
            1,
            tag_out_of_range("corner", "vertex", 4, 4),
            "'corner' tag names vertex 4, which does not exist (4 in the file)",
        ),
    ]
}

#[test]
fn the_corpus_is_complete() {
    // Every file of tests/malformed/ is asserted somewhere in this file.
    let source = include_str!("malformed.rs");
    for entry in std::fs::read_dir(malformed("")).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        assert!(
            source.contains(&format!("\"{name}\"")),
            "tests/malformed/{name} is not asserted in tests/malformed.rs"
        );
    }
}

#[test]
fn every_malformed_obj_gets_its_exact_error() {
    for (name, line, kind, message) in obj_errors() {
        let path = malformed(name);
        let err = read_obj(&path).expect_err(name);
        assert_eq!(err.file, path, "{name}");
        assert_eq!((err.line, &err.kind), (line, &kind), "{name}");
        assert_eq!(
            err.to_string(),
            format!("{}:{line}: {message}", path.display()),
            "{name}"
        );
        assert!(!err.to_string().contains('\r'), "{name}");
        assert!(
            !err.to_string().chars().any(char::is_control),
            "{name}: a control character in {:?}",
            err.to_string()
        );
        // Through the crate's error type as well.
        let err = Error::from(err);
        assert!(matches!(&err, Error::Obj(e) if e.line == line), "{name}");
    }
}

#[test]
fn cli_refine_names_file_and_line_and_writes_nothing() {
    for (name, line, _, message) in obj_errors() {
        let path = malformed(name);
        for engine in engines() {
            let dir = scratch(&format!("refine-{name}-{engine}"));
            let out = dir.join("out.obj");
            let o = subdiv(&[
                "refine",
                path.to_str().unwrap(),
                "--engine",
                engine,
                "-o",
                out.to_str().unwrap(),
            ]);
            assert_failed_cleanly(&o, &dir, &format!("{name} ({engine})"));
            assert_eq!(
                stderr(&o),
                format!("subdiv: error: {}:{line}: {message}\n", path.display()),
                "{name} ({engine})"
            );
        }
    }
    // `compare` reads the same way.
    let path = malformed("tag_boundary_unknown_value.obj");
    let o = subdiv(&["compare", path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).starts_with(&format!("subdiv: error: {}:6: ", path.display())),
        "{}",
        stderr(&o)
    );
}

/// Files that read without a syntax error but are no usable mesh.
#[test]
fn readable_but_unusable_files() {
    // Empty, or nothing but comments: an empty mesh, refused by both engines
    // with the same error, before OpenSubdiv sees it.
    for name in ["empty.obj", "comments_only.obj"] {
        let shape = read_obj(&malformed(name)).unwrap();
        assert_eq!(shape.mesh.vertex_count(), 0, "{name}");
        assert_eq!(shape.mesh.face_count(), 0, "{name}");
        assert!(shape.warnings.is_empty(), "{name}");
        assert!(shape.mesh.validate().is_ok(), "{name}");
        let err =
            refiner::refine(&shape.mesh, &shape.options(), UniformOptions::new(1)).unwrap_err();
        assert!(matches!(err, Error::EmptyMesh), "{name}: {err:?}");
        assert_eq!(
            err.to_string(),
            "the mesh has no faces: there is nothing to refine"
        );
        #[cfg(feature = "osd")]
        {
            let err = subdiv::osd::refine(&shape.mesh, &shape.options(), UniformOptions::new(1))
                .unwrap_err();
            assert!(matches!(err, Error::EmptyMesh), "{name}: {err:?}");
        }
    }
    // A face of 70000 corners (face_70000_corners.obj is refused by the
    // reader): validation refuses it too, as OpenSubdiv supports 65535.
    let shape = {
        let mut mesh = subdiv::Mesh {
            positions: vec![glam::DVec3::ZERO, glam::DVec3::X, glam::DVec3::Y],
            ..subdiv::Mesh::default()
        };
        mesh.face_vertices = (0..70000).map(|i| i % 3).collect();
        mesh.face_offsets = vec![0, 70000];
        subdiv::io::ShapeFile {
            mesh,
            tags: Default::default(),
            warnings: Vec::new(),
        }
    };
    assert_eq!(shape.mesh.face_sizes(), [70000]);
    let expected = MeshError::FaceTooLarge {
        face: 0,
        size: 70000,
    };
    assert_eq!(shape.mesh.validate(), Err(expected.clone()));
    let err = refiner::refine(&shape.mesh, &shape.options(), UniformOptions::new(1)).unwrap_err();
    assert!(matches!(&err, Error::Mesh(e) if *e == expected), "{err:?}");
    assert_eq!(
        err.to_string(),
        "invalid mesh: face 0 has 70000 vertices; at most 65535 are supported"
    );
    #[cfg(feature = "osd")]
    {
        let err =
            subdiv::osd::refine(&shape.mesh, &shape.options(), UniformOptions::new(1)).unwrap_err();
        assert!(matches!(&err, Error::Mesh(e) if *e == expected), "{err:?}");
        // The shim's own check, without Rust's validation in front of it.
        let err = subdiv::osd::TopologyRefiner::new_unvalidated(&shape.mesh, &shape.options())
            .unwrap_err();
        assert!(
            matches!(&err, Error::Osd(subdiv::OsdError { kind: subdiv::OsdErrorKind::Refused, message })
                if message == "face 0 has 70000 vertices; at most 65535 are supported"),
            "{err:?}"
        );
    }
    // Unknown tags are warnings (with their line); --strict makes them errors.
    let shape = read_obj(&malformed("tag_unknown.obj")).unwrap();
    assert_eq!(shape.warnings.len(), 1);
    assert_eq!(shape.warnings[0].line, 7);
    assert_eq!(
        shape.warnings[0].message,
        "unknown tag 'foo'; the line is ignored"
    );
    assert_eq!(
        shape.mesh.creases.len(),
        1,
        "a tag before the vertices it names"
    );
}

#[test]
fn cli_refuses_unusable_files_and_writes_nothing() {
    for name in ["empty.obj", "comments_only.obj"] {
        let path = malformed(name);
        for engine in engines() {
            let dir = scratch(&format!("unusable-{name}-{engine}"));
            let out = dir.join("out.obj");
            let o = subdiv(&[
                "refine",
                path.to_str().unwrap(),
                "--engine",
                engine,
                "-o",
                out.to_str().unwrap(),
            ]);
            assert_failed_cleanly(&o, &dir, &format!("{name} ({engine})"));
        }
    }
    let path = malformed("tag_unknown.obj");
    let dir = scratch("strict-unknown-tag");
    let out = dir.join("out.obj");
    let o = subdiv(&[
        "refine",
        path.to_str().unwrap(),
        "--strict",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_failed_cleanly(&o, &dir, "--strict with an unknown tag");
    assert!(
        stderr(&o).contains("unknown tag 'foo'") && stderr(&o).contains("tag_unknown.obj:7: "),
        "{}",
        stderr(&o)
    );
    // Without --strict: a warning naming the line, and the output.
    let o = subdiv(&[
        "refine",
        path.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.exists());
    assert!(stderr(&o).contains("line 7: unknown tag 'foo'"));
}

#[test]
fn cli_names_the_file_of_unusable_input() {
    // The same message from both engines.
    let message = "the mesh has no faces: there is nothing to refine";
    for name in ["empty.obj", "comments_only.obj"] {
        let path = malformed(name);
        for engine in engines() {
            let o = subdiv(&["refine", path.to_str().unwrap(), "--engine", engine]);
            assert_eq!(o.status.code(), Some(1));
            assert_eq!(
                stderr(&o),
                format!("subdiv: error: {}: {message}\n", path.display()),
                "{name} ({engine})"
            );
        }
    }
}

#[test]
fn cli_names_the_line_of_a_face_too_large() {
    let path = malformed("face_70000_corners.obj");
    for engine in engines() {
        let o = subdiv(&["refine", path.to_str().unwrap(), "--engine", engine]);
        assert_eq!(o.status.code(), Some(1));
        let want = format!("subdiv: error: {}:5: ", path.display());
        assert!(
            stderr(&o).starts_with(&want),
            "({engine}): wanted '{want}...', got {}",
            stderr(&o)
        );
        assert_eq!(
            stderr(&o),
            format!("{want}face has 70000 corners; at most 65535 are supported\n")
        );
    }
}

#[test]
fn cli_strict_warning_is_file_colon_line() {
    let path = malformed("tag_unknown.obj");
    let o = subdiv(&["refine", path.to_str().unwrap(), "--strict"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).starts_with(&format!("subdiv: error: {}:7: ", path.display())),
        "{}",
        stderr(&o)
    );
}

// ---------------------------------------------------------------------------
// Curves
// ---------------------------------------------------------------------------

/// Curve files `parse_points` refuses: file, line, kind, message after `FILE:LINE: `.
fn curve_errors() -> Vec<(&'static str, usize, PointsErrorKind, &'static str)> {
    vec![
        (
            "curve_one_number.txt",
            2,
            PointsErrorKind::WrongCount(1),
            "a point needs 2 or 3 numbers, this line has 1",
        ),
        (
            "curve_four_numbers.txt",
            3,
            PointsErrorKind::WrongCount(4),
            "a point needs 2 or 3 numbers, this line has 4",
        ),
        (
            "curve_mixed_dimensions.txt",
            4,
            PointsErrorKind::MixedDimensions {
                expected: 2,
                found: 3,
                first_line: 1,
            },
            "a 3-D point after 2-D points (the first point is on line 1)",
        ),
        (
            "curve_not_a_number.txt",
            2,
            PointsErrorKind::NotANumber("one".into()),
            "'one' is not a number",
        ),
        (
            "curve_comma.txt",
            2,
            PointsErrorKind::NotANumber("1,5".into()),
            "'1,5' is not a number",
        ),
        (
            "curve_nan.txt",
            3,
            PointsErrorKind::NonFinite("NaN".into()),
            "'NaN' is not a finite number",
        ),
        (
            "curve_overflow.txt",
            2,
            PointsErrorKind::NonFinite("1e400".into()),
            "'1e400' is not a finite number",
        ),
        (
            "curve_crlf.txt",
            3,
            PointsErrorKind::NotANumber("x".into()),
            "'x' is not a number",
        ),
        // Bytes that are not UTF-8 (outside a comment): their line and column.
        (
            "curve_binary_garbage.txt",
            3,
            PointsErrorKind::InvalidUtf8 {
                column: 1,
                byte: 0xFF,
            },
            "invalid UTF-8 at column 1 (byte 0xFF): a points file must be text",
        ),
    ]
}

#[test]
fn every_malformed_curve_gets_its_exact_error() {
    for (name, line, kind, message) in curve_errors() {
        let path = malformed(name);
        let err = subdiv::io::points::read_points(&path).expect_err(name);
        assert_eq!(err.file, path, "{name}");
        assert_eq!((err.line, &err.kind), (line, &kind), "{name}");
        assert_eq!(
            err.to_string(),
            format!("{}:{line}: {message}", path.display()),
            "{name}"
        );
        assert!(!err.to_string().chars().any(char::is_control), "{name}");
    }
}

/// Files with too few points: (file, scheme flags, closed, points, needed,
/// line named, message after `FILE:LINE: `).
#[allow(clippy::type_complexity)]
fn curve_too_few() -> Vec<(
    &'static str,
    CurveScheme,
    &'static [&'static str],
    bool,
    usize,
    usize,
    usize,
    &'static str,
)> {
    vec![
        (
            "curve_too_few_points.txt",
            CurveScheme::Chaikin,
            &["--scheme", "chaikin"],
            false,
            2,
            3,
            4,
            "the input ends after 2 points; chaikin on an open polygon needs at least 3",
        ),
        (
            "curve_too_few_points.txt",
            CurveScheme::BSpline { degree: 5 },
            &["--scheme", "bspline", "--degree", "5"],
            false,
            2,
            6,
            4,
            "the input ends after 2 points; bspline on an open polygon needs at least 6",
        ),
        (
            "curve_too_few_points.txt",
            CurveScheme::Jarek,
            &["--scheme", "jarek", "--closed"],
            true,
            2,
            3,
            4,
            "the input ends after 2 points; jarek on a closed polygon needs at least 3",
        ),
        (
            "curve_empty.txt",
            CurveScheme::four_point(),
            &["--scheme", "four-point"],
            false,
            0,
            2,
            1,
            "the input ends after 0 points; four-point on an open polygon needs at least 2",
        ),
    ]
}

#[test]
fn too_few_points_name_the_last_line() {
    for (name, scheme, _, closed, got, needed, line, message) in curve_too_few() {
        let path = malformed(name);
        let file = subdiv::io::points::read_points(&path).unwrap();
        assert_eq!(file.points.len(), got, "{name}");
        let err = file.require(&scheme, closed).unwrap_err();
        assert_eq!(err.line, line, "{name} {scheme}");
        assert_eq!(
            err.kind,
            PointsErrorKind::TooFewPoints {
                got,
                needed,
                scheme: scheme.name(),
                closed
            }
        );
        assert_eq!(
            err.to_string(),
            format!("{}:{line}: {message}", path.display())
        );
    }
}

#[test]
fn cli_curve_names_file_and_line_and_writes_nothing() {
    let mut cases: Vec<(&str, Vec<&str>, usize, &str)> = curve_errors()
        .into_iter()
        .map(|(name, line, _, message)| (name, vec!["--scheme", "chaikin"], line, message))
        .collect();
    for (name, _, flags, _, _, _, line, message) in curve_too_few() {
        cases.push((name, flags.to_vec(), line, message));
    }
    for (name, flags, line, message) in cases {
        let path = malformed(name);
        for output in ["out.txt", "out.svg"] {
            let dir = scratch(&format!("curve-{name}-{}-{output}", flags.join("")));
            let out = dir.join(output);
            let mut args = vec!["curve", path.to_str().unwrap()];
            args.extend(&flags);
            args.extend(["-o", out.to_str().unwrap()]);
            let o = subdiv(&args);
            assert_failed_cleanly(&o, &dir, &format!("{name} {flags:?} -> {output}"));
            assert_eq!(
                stderr(&o),
                format!("subdiv: error: {}:{line}: {message}\n", path.display()),
                "{name} {flags:?}"
            );
        }
    }
}

#[test]
fn binary_curve_file_is_refused() {
    let path = malformed("curve_binary_garbage.txt");
    let err = subdiv::io::points::read_points(&path).unwrap_err();
    assert_eq!(err.line, 3);
    assert_eq!(
        err.kind,
        PointsErrorKind::InvalidUtf8 {
            column: 1,
            byte: 0xFF
        }
    );
    let dir = scratch("curve-binary");
    let out = dir.join("out.txt");
    let o = subdiv(&[
        "curve",
        path.to_str().unwrap(),
        "--scheme",
        "chaikin",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_failed_cleanly(&o, &dir, "binary curve file");
}

#[test]
fn binary_curve_file_names_its_line() {
    let path = malformed("curve_binary_garbage.txt");
    let err = subdiv::io::points::read_points(&path).unwrap_err();
    assert_eq!(err.line, 3, "{err}");
    assert!(
        err.to_string()
            .starts_with(&format!("{}:3: ", path.display())),
        "{err}"
    );
}

// ---------------------------------------------------------------------------
// Levels and threads
// ---------------------------------------------------------------------------

/// A grid of `nx` × `ny` quads as OBJ text.
fn grid_obj(nx: usize, ny: usize) -> String {
    let mut s = String::new();
    for j in 0..=ny {
        for i in 0..=nx {
            s.push_str(&format!("v {i} {j} 0\n"));
        }
    }
    for j in 0..ny {
        for i in 0..nx {
            let v = |i: usize, j: usize| j * (nx + 1) + i + 1;
            s.push_str(&format!(
                "f {} {} {} {}\n",
                v(i, j),
                v(i + 1, j),
                v(i + 1, j + 1),
                v(i, j + 1)
            ));
        }
    }
    s
}

/// MemAvailable of /proc/meminfo in bytes.
fn available_memory() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    Some(line.split_whitespace().nth(1)?.parse::<f64>().ok()? * 1024.0)
}

#[test]
fn absurd_levels_are_refused_before_allocating() {
    // Level 11 of anything.
    for engine in engines() {
        let dir = scratch(&format!("level11-{engine}"));
        let out = dir.join("out.obj");
        let o = subdiv(&[
            "refine",
            "--builtin",
            "cube",
            "--engine",
            engine,
            "--level",
            "11",
            "-o",
            out.to_str().unwrap(),
        ]);
        assert_failed_cleanly(&o, &dir, engine);
        assert_eq!(
            stderr(&o),
            "subdiv: error: refinement level 11 refused: the deepest supported level is 10\n"
        );
    }
    let err = refiner::refine(
        &shapes::cube(),
        &Options::default(),
        UniformOptions::new(11),
    )
    .unwrap_err();
    assert!(matches!(err, Error::Level { level: 11, .. }), "{err:?}");
    let mut r = Refiner::new(&shapes::cube(), &Options::default()).unwrap();
    assert!(matches!(
        r.refine_uniform(UniformOptions::new(u32::MAX)),
        Err(Error::Level { .. })
    ));

    // 1900 quads: level 10 needs more than 32-bit indices; level 9 fits them
    // (about 2e9 face corners) but needs about 140 GiB.
    let dir = scratch("big-levels");
    let input = dir.join("grid.obj");
    std::fs::write(&input, grid_obj(50, 38)).unwrap();
    for engine in engines() {
        let start = Instant::now();
        let o = subdiv(&[
            "refine",
            input.to_str().unwrap(),
            "--engine",
            engine,
            "--level",
            "10",
        ]);
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        assert_eq!(
            stderr(&o),
            "subdiv: error: refinement level 10 refused: the level has about \
             7.969e9 face corners, more than 32-bit indices address\n"
        );
        if available_memory().is_some_and(|m| m < 1.0e11) {
            let o = subdiv(&[
                "refine",
                input.to_str().unwrap(),
                "--engine",
                engine,
                "--level",
                "9",
            ]);
            assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
            let err = stderr(&o);
            assert!(
                err.starts_with(
                    "subdiv: error: refinement level 9 refused: the level needs about "
                ) && err.contains(" GiB, more than the "),
                "{err}"
            );
        }
        assert!(
            start.elapsed() < Duration::from_secs(20),
            "refused only after {:?}",
            start.elapsed()
        );
    }
}

#[test]
fn native_refiner_is_shared_by_threads() {
    fn assert_send_sync<T: Send + Sync>() {}
    assert_send_sync::<Refiner>();
    for (mesh, options) in [
        (shapes::torus(10, 6), Options::default()),
        (
            shapes::triangulate_with_uvs(&shapes::cube_with_uvs()),
            Options::shape_file_defaults().with_scheme(Scheme::Loop),
        ),
    ] {
        let mut r = Refiner::new(&mesh, &options).unwrap();
        r.refine_uniform(UniformOptions::new(3).full_topology(true))
            .unwrap();
        let base: Vec<f64> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
        let single: Vec<f32> = base.iter().map(|&x| x as f32).collect();
        let run = |r: &Refiner| {
            let levels = r.interpolate_all(3, &base).unwrap();
            let last = levels.last().unwrap().clone();
            let narrow = r.interpolate_all(3, &single).unwrap();
            let limit = r.limit(3, &last).unwrap();
            let stencils = r.stencil_table().unwrap();
            let topology = r.level(3).unwrap();
            let fvar: Vec<Vec<f64>> = mesh
                .fvar_channels
                .iter()
                .enumerate()
                .map(|(c, ch)| {
                    let mut v = ch.values.clone();
                    for level in 1..=3 {
                        v = r.interpolate_face_varying(c, level, ch.width, &v).unwrap();
                    }
                    v
                })
                .collect();
            (levels, narrow, limit, stencils, topology, fvar)
        };
        let expected = run(&r);
        let shared = &r;
        std::thread::scope(|s| {
            let handles: Vec<_> = (0..6).map(|_| s.spawn(|| run(shared))).collect();
            for h in handles {
                let got = h.join().unwrap();
                // Bit for bit: the same floating-point operations in the same order.
                assert!(got == expected, "a thread got a different result");
            }
        });
        // Moved to another thread, too.
        let moved = std::thread::scope(|s| s.spawn(move || run(&r)).join().unwrap());
        assert!(moved == expected);
    }
}

// ---------------------------------------------------------------------------
// The OpenSubdiv bridge
// ---------------------------------------------------------------------------

#[cfg(feature = "osd")]
mod osd_bridge {
    use super::*;
    use glam::DVec3;
    use subdiv::osd;
    use subdiv::{Buffer, FVarChannel, Mesh, OsdError, OsdErrorKind};

    fn quad() -> Mesh {
        Mesh::from_faces(
            vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
            &[&[0, 1, 2, 3]],
        )
    }

    fn uv(indices: Vec<u32>) -> FVarChannel {
        FVarChannel {
            width: 2,
            values: vec![0.0; 8],
            indices,
        }
    }

    /// Malformed meshes: what the shim says without Rust's validation, and
    /// what `osd::TopologyRefiner::new` (validating first) says.
    #[test]
    fn the_shim_refuses_every_malformed_mesh() {
        type Edit = fn(&mut Mesh);
        let cases: Vec<(Edit, &str, MeshError)> = vec![
            (
                (|m: &mut Mesh| m.face_vertices[1] = u32::MAX) as Edit,
                "face 0 corner 1: vertex index -1 is out of range (4 vertices)",
                MeshError::VertexOutOfRange {
                    face: 0,
                    corner: 1,
                    index: u32::MAX,
                    count: 4,
                },
            ),
            (
                (|m: &mut Mesh| m.face_vertices[1] = i32::MAX as u32) as Edit,
                "face 0 corner 1: vertex index 2147483647 is out of range (4 vertices)",
                MeshError::VertexOutOfRange {
                    face: 0,
                    corner: 1,
                    index: i32::MAX as u32,
                    count: 4,
                },
            ),
            (
                (|m: &mut Mesh| m.add_face(&[0, 1])) as Edit,
                "face 1 has 2 vertices; at least 3 are needed",
                MeshError::FaceTooSmall { face: 1, size: 2 },
            ),
            (
                (|m: &mut Mesh| m.add_face(&[])) as Edit,
                "face 1 has 0 vertices; at least 3 are needed",
                MeshError::FaceTooSmall { face: 1, size: 0 },
            ),
            (
                (|m: &mut Mesh| m.add_crease(0, 7, 1.0)) as Edit,
                "crease 0: vertex 7 is out of range (4 vertices)",
                MeshError::CreaseVertexOutOfRange {
                    crease: 0,
                    vertex: 7,
                    count: 4,
                },
            ),
            (
                (|m: &mut Mesh| m.add_crease(0, 1, f32::NAN)) as Edit,
                "crease 0: sharpness is not finite",
                MeshError::BadSharpness {
                    what: "crease 0".into(),
                    value: f32::NAN,
                },
            ),
            (
                (|m: &mut Mesh| m.add_corner(4, 1.0)) as Edit,
                "corner 0: vertex 4 is out of range (4 vertices)",
                MeshError::CornerVertexOutOfRange {
                    corner: 0,
                    vertex: 4,
                    count: 4,
                },
            ),
            (
                (|m: &mut Mesh| m.holes.push(u32::MAX)) as Edit,
                "hole 0: face -1 is out of range (1 faces)",
                MeshError::HoleOutOfRange {
                    hole: 0,
                    face: u32::MAX,
                    count: 1,
                },
            ),
            (
                (|m: &mut Mesh| m.fvar_channels.push(uv(vec![0, 1, 2, 4]))) as Edit,
                "face-varying channel 0: value index 4 at face corner 3 is out of range (4 values)",
                MeshError::BadFVarChannel {
                    channel: 0,
                    problem:
                        "face 0 corner 3: value index 4 is out of range (the channel has 4 values)"
                            .into(),
                },
            ),
            (
                (|m: &mut Mesh| m.fvar_channels.push(uv(vec![0, 1, 2]))) as Edit,
                "malformed face offsets or face-varying channel",
                MeshError::BadFVarChannel {
                    channel: 0,
                    problem: "3 value indices for 4 face corners".into(),
                },
            ),
            (
                (|m: &mut Mesh| m.face_offsets = vec![0, 5]) as Edit,
                "malformed face offsets or face-varying channel",
                MeshError::BadOffsets("the last offset is 5 but there are 4 face vertices".into()),
            ),
            (
                (|m: &mut Mesh| m.face_offsets.clear()) as Edit,
                "malformed face offsets or face-varying channel",
                MeshError::BadOffsets("the first offset must be 0".into()),
            ),
        ];
        for (edit, shim_message, mesh_error) in cases {
            let mut mesh = quad();
            edit(&mut mesh);
            let options = Options::default();
            let err = osd::TopologyRefiner::new_unvalidated(&mesh, &options).unwrap_err();
            assert!(
                matches!(&err, Error::Osd(OsdError { kind: OsdErrorKind::Refused, message })
                    if message == shim_message),
                "{shim_message}: {err:?}"
            );
            let err = osd::TopologyRefiner::new(&mesh, &options).unwrap_err();
            // Display, not ==: a NaN sharpness is not equal to itself.
            assert!(
                matches!(&err, Error::Mesh(e) if e.to_string() == mesh_error.to_string()),
                "{mesh_error}: {err:?}"
            );
            let err = refiner::refine(&mesh, &options, UniformOptions::new(1)).unwrap_err();
            assert!(
                matches!(&err, Error::Mesh(e) if e.to_string() == mesh_error.to_string()),
                "native, {mesh_error}: {err:?}"
            );
        }
        // No faces (with or without vertices): refused as by the native
        // engine, before OpenSubdiv; the shim refuses it as well.
        let points_only = Mesh {
            positions: vec![DVec3::ZERO; 3],
            ..Mesh::default()
        };
        for mesh in [Mesh::default(), points_only] {
            let err = osd::TopologyRefiner::new(&mesh, &Options::default()).unwrap_err();
            assert!(matches!(err, Error::EmptyMesh), "{err:?}");
            let err = Refiner::new(&mesh, &Options::default()).unwrap_err();
            assert!(matches!(err, Error::EmptyMesh), "native: {err:?}");
            let err =
                osd::TopologyRefiner::new_unvalidated(&mesh, &Options::default()).unwrap_err();
            assert!(
                matches!(&err, Error::Osd(OsdError { kind: OsdErrorKind::Refused, message })
                    if message == "the mesh has no faces: there is nothing to refine"),
                "{err:?}"
            );
        }
    }

    /// Wrong buffers and levels are refused by the bridge, not passed on.
    #[test]
    fn the_bridge_refuses_wrong_arguments() {
        let cube = shapes::cube_with_uvs();
        let mut r = osd::TopologyRefiner::new(&cube, &Options::default()).unwrap();
        assert!(matches!(
            r.refine_uniform(UniformOptions::new(11)),
            Err(Error::Level { level: 11, .. })
        ));
        r.refine_uniform(UniformOptions::new(2)).unwrap();
        let base: Vec<f64> = cube.positions.iter().flat_map(|p| p.to_array()).collect();
        let no_level = |level| Error::NoSuchLevel {
            level,
            first: 1,
            last: 2,
        };
        let short = |got| Error::BufferLength {
            buffer: Buffer::Source,
            expected: 24,
            got,
        };
        for (level, width, len, expected) in [
            (0, 3, 24, no_level(0)),
            (3, 3, 24, no_level(3)),
            (1, 0, 0, Error::ZeroWidth),
            (1, 3, 23, short(23)),
            (1, 3, 25, short(25)),
        ] {
            let src = vec![0.0f64; len];
            let err = r.interpolate(level, width, &src).unwrap_err();
            assert_eq!(
                format!("{err:?}"),
                format!("{expected:?}"),
                "level {level} width {width} len {len}"
            );
        }
        assert!(r.interpolate(1, 3, &base).is_ok());
        assert!(
            r.interpolate_face_varying::<f64>(1, 1, 2, &[0.0; 28])
                .is_err()
        );
        assert!(
            r.interpolate_face_varying::<f64>(0, 1, 2, &[0.0; 3])
                .is_err()
        );
        assert!(
            r.limit::<f64>(3, &base).is_err(),
            "limit needs the last level's data"
        );
        assert!(r.level(3).is_err());
        let e = osd::StencilEvaluator::new(&r).unwrap();
        let src = vec![0.0f32; 8 * 3];
        assert!(e.eval(3, &src).is_ok());
        assert!(e.eval(3, &src[..23]).is_err());
        assert!(e.eval(0, &src).is_err());
    }

    /// The malformed files through the bridge: every one refused with a typed error.
    #[test]
    fn malformed_files_through_the_bridge() {
        for (name, line, _, _) in obj_errors() {
            let err = read_obj(&malformed(name)).unwrap_err();
            assert_eq!(err.line, line);
        }
        for name in ["empty.obj", "comments_only.obj"] {
            let shape = read_obj(&malformed(name)).unwrap();
            for level in 0..=2 {
                assert!(
                    osd::refine(&shape.mesh, &shape.options(), UniformOptions::new(level)).is_err(),
                    "{name} level {level}"
                );
            }
            let _ =
                osd::TopologyRefiner::new_unvalidated(&shape.mesh, &shape.options()).unwrap_err();
        }
    }

    /// A face naming a vertex twice can leave it "smooth" with unpaired faces
    /// and edges; OpenSubdiv's own assertion would abort on it. Both engines
    /// refuse the mesh with the same typed error, and the CLI exits 1.
    #[test]
    fn repeated_vertex_does_not_abort_the_bridge() {
        let path = malformed("osd_abort_repeated_vertex.obj");
        let shape = read_obj(&path).unwrap();
        assert!(shape.mesh.validate().is_ok());
        let native = refiner::refine(&shape.mesh, &shape.options(), UniformOptions::new(1));
        let err = native
            .expect_err("native must refuse an unpaired smooth vertex")
            .to_string();
        assert!(err.contains("vertex 3") && err.contains("pair up"), "{err}");
        let bridge = subdiv::osd::refine(&shape.mesh, &shape.options(), UniformOptions::new(1));
        let err = bridge
            .expect_err("the bridge must refuse it before OpenSubdiv asserts")
            .to_string();
        assert!(err.contains("vertex 3") && err.contains("pair up"), "{err}");
        // In a child process: an abort must not take the test binary down.
        let dir = scratch("repeated-vertex");
        let out = dir.join("out.obj");
        let o = subdiv(&[
            "refine",
            path.to_str().unwrap(),
            "--engine",
            "osd",
            "--level",
            "1",
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(
            matches!(o.status.code(), Some(1)),
            "subdiv refine --engine osd died: {:?}\n{}",
            o.status,
            stderr(&o)
        );
    }

    /// A semi-sharp corner or crease hides the unpaired vertex until its
    /// sharpness decays; the check runs at every level, so both engines refuse
    /// it (exit 1) instead of OpenSubdiv's assertion aborting the process.
    #[test]
    fn repeated_vertex_with_decaying_sharpness_does_not_abort() {
        for name in [
            "osd_abort_repeated_vertex_semisharp.obj",
            "osd_abort_repeated_vertex_creases.obj",
        ] {
            let path = malformed(name);
            for level in ["1", "2", "3"] {
                for extra in [&[][..], &["--limit"][..]] {
                    // In a child process: an abort must not take the test binary down.
                    let mut args = vec![
                        "refine",
                        path.to_str().unwrap(),
                        "--engine",
                        "osd",
                        "--level",
                        level,
                    ];
                    args.extend(extra);
                    let o = subdiv(&args);
                    assert!(
                        matches!(o.status.code(), Some(1)) && stderr(&o).contains("do not pair up"),
                        "{name} level {level} {extra:?}: subdiv refine --engine osd died: {:?}\n{}",
                        o.status,
                        stderr(&o)
                    );
                }
            }
        }
    }

    #[test]
    fn level_zero_reports_the_base_edges_like_opensubdiv() {
        let cube = shapes::cube();
        let options = Options::default();
        let native = refiner::refine(&cube, &options, UniformOptions::new(0)).unwrap();
        let osd = osd::refine(&cube, &options, UniformOptions::new(0)).unwrap();
        assert_eq!(osd.levels[0].edge_vertices.len(), 12);
        assert_eq!(native.levels[0].edge_vertices, osd.levels[0].edge_vertices);
        for c in subdiv::compare::compare(&native, &osd) {
            assert!(
                c.agrees(1e-12),
                "level {}: tags equal {}",
                c.level,
                c.tags_equal
            );
        }
    }
}
