//! OBJ reading (with OpenSubdiv shape-file tags) and writing.

use glam::DVec3;
use std::path::{Path, PathBuf};
use subdiv::io::{
    ObjOutput, ShapeFile, ShapeTags, UvOutput, format_g, mesh_to_obj_string, parse_obj, read_obj,
    write_mesh_obj, write_obj, write_obj_to,
};
use subdiv::{
    BoundaryInterpolation, Corner, Crease, CreasingMethod, Error, FVarChannel,
    FVarLinearInterpolation, Mesh, ObjError, ObjErrorKind, Options, Precision, TriangleSubdivision,
};

fn parse(text: &str) -> Result<ShapeFile, ObjError> {
    parse_obj(text, Path::new("<memory>"))
}

fn parse_ok(text: &str) -> ShapeFile {
    parse(text).unwrap_or_else(|e| panic!("{e}"))
}

/// The line and kind of the error `text` must produce.
fn error_of(text: &str) -> (usize, ObjErrorKind) {
    match parse(text) {
        Ok(_) => panic!("parsed without error:\n{text}"),
        Err(e) => {
            assert_eq!(e.file, Path::new("<memory>"));
            (e.line, e.kind)
        }
    }
}

/// `text`'s error, which must be a `BadTag` for `tag` on `line`; returns its message.
fn bad_tag(text: &str, line: usize, tag: &str) -> String {
    match error_of(text) {
        (l, ObjErrorKind::BadTag { tag: t, message }) if l == line && t == tag => message,
        other => panic!("expected a bad '{tag}' tag on line {line}, got {other:?}"),
    }
}

const SQUARE: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
const QUAD: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";

/// A unit cube written with relative indices for half of its faces, and UVs.
const CUBE: &str = "\
# a cube
o cube
mtllib cube.mtl
v -0.5 -0.5 0.5
v 0.5 -0.5 0.5
v -0.5 0.5 0.5
v 0.5 0.5 0.5
v -0.5 0.5 -0.5
v 0.5 0.5 -0.5
v -0.5 -0.5 -0.5
v 0.5 -0.5 -0.5 1.0
vt 0.375 0
vt 0.625 0
vt 0.375 0.25
vt 0.625 0.25
vt 0.375 0.5
vt 0.625 0.5
vt 0.375 0.75
vt 0.625 0.75
vt 0.375 1
vt 0.625 1
vt 0.875 0
vt 0.875 0.25
vt 0.125 0
vt 0.125 0.25 0
vn 0 0 1
g faces
usemtl default
s off
f 1/1/1 2/2/1 4/4/1 3/3/1
f 3/3 4/4 6/6 5/5
f -4/-10 -3/-9 -1/-7 -2/-8
f 7/7 8/8 2/10 1/9
f -7/-13 -1/-4 -3/-3 -5/-11
f 7/13 1/1 3/3 5/14
";

#[test]
fn cube_with_relative_indices_and_uvs() {
    let shape = parse_ok(CUBE);
    let m = &shape.mesh;
    assert_eq!(m.positions.len(), 8);
    assert_eq!(m.positions[0], DVec3::new(-0.5, -0.5, 0.5));
    assert_eq!(m.positions[7], DVec3::new(0.5, -0.5, -0.5));
    assert_eq!(m.face_offsets, [0, 4, 8, 12, 16, 20, 24]);
    #[rustfmt::skip]
    assert_eq!(m.face_vertices, [
        0, 1, 3, 2,
        2, 3, 5, 4,
        4, 5, 7, 6,
        6, 7, 1, 0,
        1, 7, 5, 3,
        6, 0, 2, 4,
    ]);
    assert_eq!(m.fvar_channels.len(), 1);
    let uv = &m.fvar_channels[0];
    assert_eq!(uv.width, 2);
    assert_eq!(uv.values.len(), 28);
    assert_eq!(&uv.values[..4], [0.375, 0.0, 0.625, 0.0]);
    assert_eq!(&uv.values[26..], [0.125, 0.25]);
    #[rustfmt::skip]
    assert_eq!(uv.indices, [
        0, 1, 3, 2,
        2, 3, 5, 4,
        4, 5, 7, 6,
        6, 7, 9, 8,
        1, 10, 11, 3,
        12, 0, 2, 13,
    ]);
    assert!(m.creases.is_empty() && m.corners.is_empty() && m.holes.is_empty());
    assert_eq!(shape.tags, ShapeTags::default());
    assert_eq!(shape.options(), Options::shape_file_defaults());
    assert!(shape.warnings.is_empty(), "{:?}", shape.warnings);
    assert!(m.validate().unwrap().warnings.is_empty());
}

#[test]
fn crlf_comments_and_trailing_whitespace_are_tolerated() {
    let text =
        "\u{feff}v 0 0 0 \r\nv 1 0 0\t\r\n\r\n  # comment\r\nv 1 1 0 # inline\r\nf 1 2 3   \r\n";
    let shape = parse_ok(text);
    assert_eq!(shape.mesh.positions.len(), 3);
    assert_eq!(shape.mesh.face_vertices, [0, 1, 2]);
    assert!(shape.warnings.is_empty());
}

#[test]
fn vertices_stay_in_file_order_even_when_unused() {
    let shape = parse_ok("v 9 9 9\nv 0 0 0\nv 1 0 0\nv 1 1 0\nf 4 3 2\nv 5 5 5\n");
    assert_eq!(shape.mesh.positions.len(), 5);
    assert_eq!(shape.mesh.positions[0], DVec3::splat(9.0));
    assert_eq!(shape.mesh.positions[4], DVec3::splat(5.0));
    assert_eq!(shape.mesh.face_vertices, [3, 2, 1]);
}

#[test]
fn vt_lines_without_face_uvs_give_no_channel() {
    let shape = parse_ok(&format!("vt 0 0\nvt 1 0\n{QUAD}"));
    assert!(shape.mesh.fvar_channels.is_empty());
    let shape = parse_ok(&format!(
        "vn 0 0 1\n{}",
        QUAD.replace("f 1 2 3 4", "f 1//1 2//1 3//-1 4//1")
    ));
    assert!(shape.mesh.fvar_channels.is_empty());
    assert_eq!(shape.mesh.face_vertices, [0, 1, 2, 3]);
}

#[test]
fn normals_are_ignored_and_vertex_colours_accepted() {
    // Normal indices are ignored as OpenSubdiv ignores them (no `vn` needed),
    // but they must still be integers.
    let shape = parse_ok("v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 1 1 0 0 0 1\nf 1//7 2//7 3//-9\n");
    assert_eq!(shape.mesh.positions[2], DVec3::new(1.0, 1.0, 0.0));
    assert_eq!(shape.mesh.face_vertices, [0, 1, 2]);
    assert!(shape.mesh.fvar_channels.is_empty());
    match error_of(&format!("{SQUARE}f 1//1 2//n 3//1\n")) {
        (5, ObjErrorKind::Syntax(m)) => assert!(m.contains("normal index 'n'"), "{m}"),
        other => panic!("{other:?}"),
    }
    match error_of("v 0 0 0 1 1\n") {
        (1, ObjErrorKind::Syntax(m)) => assert!(m.contains("found 5 values"), "{m}"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn crease_tags_are_vertex_chains() {
    let shape = parse_ok(&format!(
        "t crease 3/1/0 0 1 2 2.5\n{QUAD}t crease 4/3/0 3 2 1 0 1 2 10\nt crease 2/1/0 0 3 0.25\n"
    ));
    let c = |a, b, sharpness| Crease {
        vertices: [a, b],
        sharpness,
    };
    assert_eq!(
        shape.mesh.creases,
        [
            c(0, 1, 2.5),
            c(1, 2, 2.5),
            c(3, 2, 1.0),
            c(2, 1, 2.0),
            c(1, 0, 10.0),
            c(0, 3, 0.25),
        ]
    );
    assert!(shape.warnings.is_empty());
}

#[test]
fn corner_and_hole_tags() {
    let shape = parse_ok(&format!(
        "{QUAD}f 1 3 4\nt corner 2/1/0 0 2 4.5\nt corner 2/2/0 1 3 1.5 10\nt hole 2/0/0 1 0\n"
    ));
    assert_eq!(
        shape.mesh.corners,
        [
            Corner {
                vertex: 0,
                sharpness: 4.5
            },
            Corner {
                vertex: 2,
                sharpness: 4.5
            },
            Corner {
                vertex: 1,
                sharpness: 1.5
            },
            Corner {
                vertex: 3,
                sharpness: 10.0
            },
        ]
    );
    assert_eq!(shape.mesh.holes, [1, 0]);
}

#[test]
fn option_tags() {
    let boundary = |code: i64| {
        parse_ok(&format!("{QUAD}t interpolateboundary 1/0/0 {code}\n"))
            .tags
            .boundary
    };
    assert_eq!(boundary(0), Some(BoundaryInterpolation::None));
    assert_eq!(boundary(1), Some(BoundaryInterpolation::EdgeAndCorner));
    assert_eq!(boundary(2), Some(BoundaryInterpolation::EdgeOnly));

    use FVarLinearInterpolation as F;
    let expected = [
        F::None,
        F::CornersOnly,
        F::CornersPlus1,
        F::CornersPlus2,
        F::Boundaries,
        F::All,
    ];
    for (code, want) in expected.into_iter().enumerate() {
        let shape = parse_ok(&format!(
            "{QUAD}t facevaryinginterpolateboundary 1/0/0 {code}\n"
        ));
        assert_eq!(shape.tags.fvar, Some(want));
    }

    let creasing = |s: &str| {
        parse_ok(&format!("{QUAD}t creasemethod 0/0/1 {s}\n"))
            .tags
            .creasing
    };
    assert_eq!(creasing("normal"), Some(CreasingMethod::Uniform));
    assert_eq!(creasing("chaikin"), Some(CreasingMethod::Chaikin));

    let triangles = |s: &str| {
        parse_ok(&format!("{QUAD}t smoothtriangles 0/0/1 {s}\n"))
            .tags
            .triangles
    };
    assert_eq!(triangles("catmark"), Some(TriangleSubdivision::Catmark));
    assert_eq!(triangles("smooth"), Some(TriangleSubdivision::Smooth));

    let shape = parse_ok(&format!(
        "{QUAD}t interpolateboundary 1/0/0 1\nt creasemethod 0/0/1 chaikin\n\
         t smoothtriangles 0/0/1 smooth\nt facevaryinginterpolateboundary 1/0/0 1\n"
    ));
    assert_eq!(
        shape.tags,
        ShapeTags {
            boundary: Some(BoundaryInterpolation::EdgeAndCorner),
            fvar: Some(F::CornersOnly),
            creasing: Some(CreasingMethod::Chaikin),
            triangles: Some(TriangleSubdivision::Smooth),
        }
    );
    let options = shape.options();
    assert_eq!(options.scheme, Options::shape_file_defaults().scheme);
    assert_eq!(options.boundary, BoundaryInterpolation::EdgeAndCorner);
    assert_eq!(options.fvar, F::CornersOnly);
    assert_eq!(options.creasing, CreasingMethod::Chaikin);
    assert_eq!(options.triangles, TriangleSubdivision::Smooth);

    // Absent tags leave the shape-file defaults (edge-only boundaries), not Sdc's.
    let partial = parse_ok(&format!("{QUAD}t creasemethod 0/0/1 chaikin\n")).options();
    assert_eq!(partial.boundary, BoundaryInterpolation::EdgeOnly);
    assert_eq!(partial.fvar, FVarLinearInterpolation::All);
    assert_eq!(partial.creasing, CreasingMethod::Chaikin);
}

#[test]
fn a_repeated_option_tag_wins_with_a_warning() {
    let shape = parse_ok(&format!(
        "{QUAD}t interpolateboundary 1/0/0 0\nt interpolateboundary 1/0/0 2\n"
    ));
    assert_eq!(shape.tags.boundary, Some(BoundaryInterpolation::EdgeOnly));
    assert_eq!(shape.warnings.len(), 1);
    assert_eq!(shape.warnings[0].line, 7);
    assert!(
        shape.warnings[0].message.contains("line 6"),
        "{}",
        shape.warnings[0]
    );
}

#[test]
fn unknown_statements_and_tags_are_warnings_with_lines() {
    let shape = parse_ok(&format!(
        "{QUAD}t facevaryingpropagatecorners 1/0/0 1\nvp 0.5\nl 1 2\np 3\ncstype bezier\n"
    ));
    let lines: Vec<usize> = shape.warnings.iter().map(|w| w.line).collect();
    assert_eq!(lines, [6, 7, 8, 9, 10]);
    assert!(
        shape.warnings[0]
            .message
            .contains("unknown tag 'facevaryingpropagatecorners'")
    );
    assert!(shape.warnings[1].message.contains("'vp'"));
    assert!(shape.warnings.iter().all(|w| w.ignored));
    assert_eq!(
        shape.warnings[0].to_string(),
        "line 6: unknown tag 'facevaryingpropagatecorners'; the line is ignored"
    );
    // The geometry is unaffected.
    assert_eq!(shape.mesh.face_vertices, [0, 1, 2, 3]);
    assert_eq!(shape.tags, ShapeTags::default());
}

#[test]
fn syntax_errors_name_the_field_and_line() {
    match error_of("v 0 0 0\nv 1 abc 0\n") {
        (2, ObjErrorKind::Syntax(m)) => assert!(m.contains("y 'abc'"), "{m}"),
        other => panic!("{other:?}"),
    }
    match error_of("vt 0.5 v\n") {
        (1, ObjErrorKind::Syntax(m)) => assert!(m.contains("v 'v'"), "{m}"),
        other => panic!("{other:?}"),
    }
    match error_of("v 0 0\n") {
        (1, ObjErrorKind::Syntax(m)) => assert!(m.contains("found 2 values"), "{m}"),
        other => panic!("{other:?}"),
    }
    match error_of(&format!("{QUAD}f 1 2 x\n")) {
        (6, ObjErrorKind::Syntax(m)) => assert!(m.contains("corner 3 'x'"), "{m}"),
        other => panic!("{other:?}"),
    }
    match error_of(&format!("{QUAD}f 1 2/ 3\n")) {
        (6, ObjErrorKind::Syntax(m)) => assert!(m.contains("corner 2"), "{m}"),
        other => panic!("{other:?}"),
    }
    match error_of(&format!("{QUAD}f 1 2 3/1/1/1\n")) {
        (6, ObjErrorKind::Syntax(m)) => assert!(m.contains("corner 3"), "{m}"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn non_finite_coordinates_are_errors() {
    assert!(
        matches!(error_of("v 0 0 0\nv 0 nan 0\n"), (2, ObjErrorKind::NonFinite(m)) if m.contains("y = nan"))
    );
    assert!(matches!(
        error_of("v inf 0 0\n"),
        (1, ObjErrorKind::NonFinite(_))
    ));
    assert!(matches!(
        error_of("v 1e999 0 0\n"),
        (1, ObjErrorKind::NonFinite(_))
    ));
    assert!(matches!(
        error_of("vt 0 -infinity\n"),
        (1, ObjErrorKind::NonFinite(_))
    ));
}

#[test]
fn face_index_errors() {
    let oor = |what, index, count| ObjErrorKind::IndexOutOfRange { what, index, count };
    assert_eq!(
        error_of(&format!("{QUAD}f 1 0 2\n")),
        (6, oor("vertex", 0, 4))
    );
    assert_eq!(
        error_of(&format!("{QUAD}f 1 2 5\n")),
        (6, oor("vertex", 5, 4))
    );
    assert_eq!(
        error_of(&format!("{QUAD}f 1 2 -5\n")),
        (6, oor("vertex", -5, 4))
    );
    // Relative indices count only the vertices defined before the face.
    assert_eq!(
        error_of("v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n"),
        (3, oor("vertex", -3, 2))
    );
    assert_eq!(
        error_of(&format!("vt 0 0\nvt 1 0\n{SQUARE}f 1/1 2/2 3/3\n")),
        (7, oor("texture coordinate", 3, 2))
    );
    assert_eq!(
        error_of(&format!("vt 0 0\n{SQUARE}f 1/1 2/0 3/1\n")),
        (6, oor("texture coordinate", 0, 1))
    );
}

#[test]
fn faces_need_three_corners() {
    assert_eq!(
        error_of(&format!("{QUAD}f 1 2\n")),
        (6, ObjErrorKind::FaceTooSmall(2))
    );
    assert_eq!(
        error_of(&format!("{QUAD}\nf\n")),
        (7, ObjErrorKind::FaceTooSmall(0))
    );
}

#[test]
fn texture_coordinates_must_be_all_or_nothing() {
    let uvs = "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
    // The second face lacks what the first has.
    let text = format!("{uvs}{SQUARE}f 1/1 2/2 3/3\nf 1 3 4\n");
    assert!(matches!(
        error_of(&text),
        (10, ObjErrorKind::InconsistentTexcoords(_))
    ));
    // The second face has what the first lacks.
    let text = format!("{uvs}{SQUARE}f 1 2 3\nf 1/1 3/3 4/4\n");
    assert!(matches!(
        error_of(&text),
        (10, ObjErrorKind::InconsistentTexcoords(_))
    ));
    // Mixed within one face.
    let text = format!("{uvs}{SQUARE}f 1/1 2 3/3\n");
    match error_of(&text) {
        (9, ObjErrorKind::InconsistentTexcoords(m)) => assert!(m.contains("corner 2"), "{m}"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn malformed_tags() {
    // Wrong counts: announced and given argument numbers differ.
    let m = bad_tag(&format!("{QUAD}t crease 2/1/0 0 1\n"), 6, "crease");
    assert!(m.contains("3 arguments but 2"), "{m}");
    bad_tag(&format!("{QUAD}t crease 2/1/0 0 1 1.0 7\n"), 6, "crease");
    bad_tag(&format!("{QUAD}t crease 2/1 0 1 1.0\n"), 6, "crease");
    bad_tag(&format!("{QUAD}t crease\n"), 6, "crease");
    bad_tag(&format!("{QUAD}t crease 2/1/0 0 x 1.0\n"), 6, "crease");
    bad_tag(&format!("{QUAD}t crease 2/1/0 0 1 sharp\n"), 6, "crease");
    // A crease needs two vertices.
    let m = bad_tag(&format!("{QUAD}t crease 1/1/0 0 1.0\n"), 6, "crease");
    assert!(m.contains("at least 2 vertices"), "{m}");
    // Sharpness count must be 1 or one per edge.
    let m = bad_tag(&format!("{QUAD}t crease 3/3/0 0 1 2 1 2 3\n"), 6, "crease");
    assert!(m.contains("found 3"), "{m}");
    bad_tag(&format!("{QUAD}t crease 2/0/0 0 1\n"), 6, "crease");
    bad_tag(&format!("{QUAD}t corner 3/2/0 0 1 2 1 2\n"), 6, "corner");
    bad_tag(&format!("{QUAD}t crease 2/1/0 0 1 inf\n"), 6, "crease");
    bad_tag(&format!("{QUAD}t corner 1/1/0 0 nan\n"), 6, "corner");
    bad_tag(&format!("{QUAD}t hole 1/1/0 0 1.0\n"), 6, "hole");
    // Option tags: wrong shape or unknown value.
    let m = bad_tag(
        &format!("{QUAD}t interpolateboundary 1/0/0 3\n"),
        6,
        "interpolateboundary",
    );
    assert!(m.contains("unknown value 3"), "{m}");
    bad_tag(
        &format!("{QUAD}t interpolateboundary 2/0/0 1 1\n"),
        6,
        "interpolateboundary",
    );
    bad_tag(
        &format!("{QUAD}t facevaryinginterpolateboundary 1/0/0 6\n"),
        6,
        "facevaryinginterpolateboundary",
    );
    let m = bad_tag(
        &format!("{QUAD}t creasemethod 0/0/1 smooth\n"),
        6,
        "creasemethod",
    );
    assert!(m.contains("'smooth'"), "{m}");
    bad_tag(
        &format!("{QUAD}t creasemethod 1/0/0 1\n"),
        6,
        "creasemethod",
    );
    bad_tag(
        &format!("{QUAD}t smoothtriangles 0/0/1 loop\n"),
        6,
        "smoothtriangles",
    );
    assert!(matches!(
        error_of(&format!("{QUAD}t\n")),
        (6, ObjErrorKind::Syntax(_))
    ));
}

#[test]
fn tag_indices_are_checked_against_the_whole_file() {
    let oor = |tag: &str, what, index, count| ObjErrorKind::TagOutOfRange {
        tag: tag.to_string(),
        what,
        index,
        count,
    };
    // Reported at the tag's own line even though more lines follow.
    assert_eq!(
        error_of(&format!("{QUAD}t crease 2/1/0 3 5 1.0\nv 2 2 2\nf 1 2 3\n")),
        (6, oor("crease", "vertex", 5, 5))
    );
    // A tag may name vertices and faces defined after it.
    let shape = parse_ok(&format!(
        "t crease 2/1/0 0 4 1.0\nt hole 1/0/0 1\n{QUAD}v 2 2 2\nf 1 2 5\n"
    ));
    assert_eq!(
        shape.mesh.creases,
        [Crease {
            vertices: [0, 4],
            sharpness: 1.0
        }]
    );
    assert_eq!(shape.mesh.holes, [1]);
    assert_eq!(
        error_of(&format!("{QUAD}t corner 2/1/0 1 -1 1.0\n")),
        (6, oor("corner", "vertex", -1, 4))
    );
    assert_eq!(
        error_of(&format!("{QUAD}t hole 1/0/0 1\n")),
        (6, oor("hole", "face", 1, 1))
    );
}

#[test]
fn errors_display_file_and_line() {
    let e = parse_obj(&format!("{QUAD}f 1 2\n"), Path::new("shapes/x.obj")).unwrap_err();
    assert_eq!(
        e.to_string(),
        "shapes/x.obj:6: face has 2 corners; a face needs at least 3"
    );
}

#[test]
fn read_obj_reports_io_errors_on_line_zero() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("missing.obj");
    let e = read_obj(&path).unwrap_err();
    assert_eq!((e.file.as_path(), e.line), (path.as_path(), 0));
    assert!(matches!(e.kind, ObjErrorKind::Io(_)));

    let good = dir.path().join("cube.obj");
    std::fs::write(&good, CUBE).unwrap();
    assert_eq!(read_obj(&good).unwrap(), parse_ok(CUBE));
}

/// A mesh with every kind of data: odd numbers, creases, corners, holes, UVs.
fn tagged_mesh() -> Mesh {
    let positions = vec![
        DVec3::new(0.1, -0.0, 1.0 / 3.0),
        DVec3::new(1e-7, 2.5e20, -7.0),
        DVec3::new(std::f64::consts::PI, 1e-300, 123456.789),
        DVec3::new(-0.5, 0.2, 0.30000000000000004),
        DVec3::new(5e-324, -1e16, 2.0 / 3.0),
    ];
    let mut mesh = Mesh::from_faces(positions, &[&[0, 1, 2, 3], &[1, 4, 2], &[0, 3, 4]]);
    mesh.add_crease(0, 1, 2.5);
    mesh.add_crease(1, 2, 0.1);
    mesh.add_corner(3, 10.0);
    mesh.add_corner(4, 1.0 / 3.0);
    mesh.holes = vec![2, 0];
    mesh.fvar_channels = vec![FVarChannel {
        width: 2,
        values: vec![0.0, 0.0, 1.0, 0.1, 0.7, 1.0 / 7.0, -0.25, 1e-9],
        indices: vec![0, 1, 2, 3, 1, 3, 2, 0, 3, 2],
    }];
    mesh
}

#[test]
fn mesh_round_trips_through_obj_text() {
    let mesh = tagged_mesh();
    let text = mesh_to_obj_string(&mesh, Precision::F64);
    let shape = parse_ok(&text);
    assert_eq!(shape.mesh, mesh, "{text}");
    assert!(shape.warnings.is_empty());
    assert!(
        text.contains("\nt crease 2/1/0 1 2 0.100000001\n"),
        "{text}"
    );
    assert!(
        text.contains("\nt corner 2/2/0 3 4 10 0.333333343\n"),
        "{text}"
    );
    assert!(text.ends_with("\nt hole 2/0/0 2 0\n"), "{text}");
    assert!(
        text.starts_with("v 0.10000000000000001 -0 0.33333333333333331\n"),
        "{text}"
    );

    // Without UVs, faces are plain vertex lists.
    let mut plain = mesh.clone();
    plain.fvar_channels.clear();
    let text = mesh_to_obj_string(&plain, Precision::F64);
    assert!(text.contains("\nf 1 2 3 4\nf 2 5 3\nf 1 4 5\n"), "{text}");
    assert_eq!(parse_ok(&text).mesh, plain);

    // F32 rounds every coordinate to f32.
    let text = mesh_to_obj_string(&plain, Precision::F32);
    let back = parse_ok(&text).mesh;
    for (a, b) in back.positions.iter().zip(&plain.positions) {
        assert_eq!(a.as_vec3(), b.as_vec3());
    }
    assert!(text.starts_with("v 0.100000001 -0 0.333333343\n"), "{text}");
}

#[test]
fn mesh_round_trips_through_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("mesh.obj");
    let mesh = tagged_mesh();
    write_mesh_obj(&path, &mesh, Precision::F64).unwrap();
    assert_eq!(read_obj(&path).unwrap().mesh, mesh);
}

#[test]
fn writer_output_is_exact() {
    let positions = [
        DVec3::new(0.0, 0.5, 1.0),
        DVec3::new(0.1, 1e-5, -2.0),
        DVec3::ZERO,
        DVec3::X,
    ];
    let offsets = [0, 3, 6, 10];
    let vertices = [0, 1, 2, 2, 1, 3, 0, 1, 3, 2];
    let values = [0.0, 1.0, 0.25, 2.0 / 3.0, 1.0, 1e20];
    let face_values = [0, 1, 2, 2, 1, 0, 0, 1, 2, 0];
    let holes = [false, true, false];
    let data = ObjOutput {
        positions: &positions,
        face_offsets: &offsets,
        face_vertices: &vertices,
        holes: Some(&holes),
        uv: Some(UvOutput {
            width: 2,
            values: &values,
            face_values: &face_values,
        }),
        normals: None,
        precision: Precision::F64,
    };
    let mut out = Vec::new();
    write_obj_to(&mut out, &data).unwrap();
    assert_eq!(
        String::from_utf8(out).unwrap(),
        "v 0 0.5 1\n\
         v 0.10000000000000001 1.0000000000000001e-05 -2\n\
         v 0 0 0\n\
         v 1 0 0\n\
         vt 0 1\n\
         vt 0.25 0.66666666666666663\n\
         vt 1 1e+20\n\
         f 1/1 2/2 3/3\n\
         f 1/1 2/2 4/3 3/1\n"
    );

    let values3 = [0.0, 1.0, 0.25, 2.0 / 3.0, 1.0, 1e20, 0.5, -0.5, 3.0];
    let data = ObjOutput {
        holes: None,
        uv: Some(UvOutput {
            width: 3,
            values: &values3,
            face_values: &face_values,
        }),
        precision: Precision::F32,
        ..data
    };
    let mut out = Vec::new();
    write_obj_to(&mut out, &data).unwrap();
    assert_eq!(
        String::from_utf8(out).unwrap(),
        "v 0 0.5 1\n\
         v 0.100000001 9.99999975e-06 -2\n\
         v 0 0 0\n\
         v 1 0 0\n\
         vt 0 1 0.25\n\
         vt 0.666666687 1 1.00000002e+20\n\
         vt 0.5 -0.5 3\n\
         f 1/1 2/2 3/3\n\
         f 3/3 2/2 4/1\n\
         f 1/1 2/2 4/3 3/1\n"
    );
}

#[test]
fn writer_refuses_malformed_input_before_writing() {
    let positions = [DVec3::ZERO; 3];
    let base = ObjOutput {
        positions: &positions,
        face_offsets: &[0, 3],
        face_vertices: &[0, 1, 2],
        holes: None,
        uv: None,
        normals: None,
        precision: Precision::F64,
    };
    let bad = [
        ObjOutput {
            face_offsets: &[0, 4],
            ..base
        },
        ObjOutput {
            face_offsets: &[0, 3, 2],
            ..base
        },
        ObjOutput {
            holes: Some(&[false, true]),
            ..base
        },
        ObjOutput {
            uv: Some(UvOutput {
                width: 2,
                values: &[0.0; 3],
                face_values: &[0; 3],
            }),
            ..base
        },
        ObjOutput {
            uv: Some(UvOutput {
                width: 0,
                values: &[],
                face_values: &[0; 3],
            }),
            ..base
        },
        ObjOutput {
            uv: Some(UvOutput {
                width: 2,
                values: &[0.0; 2],
                face_values: &[0; 2],
            }),
            ..base
        },
    ];
    for data in &bad {
        let mut out = Vec::new();
        let e = write_obj_to(&mut out, data).unwrap_err();
        assert_eq!(e.kind(), std::io::ErrorKind::InvalidInput);
        assert!(out.is_empty());
    }
}

#[test]
fn format_g_matches_c_printf() {
    let g = |x: f64, p: usize| {
        let mut s = String::from(">");
        format_g(x, p, &mut s);
        s
    };
    assert_eq!(g(0.1, 17), ">0.10000000000000001");
    assert_eq!(g(1.0, 17), ">1");
    assert_eq!(g(1e-5, 17), ">1.0000000000000001e-05");
    assert_eq!(g(123456.789, 17), ">123456.789");
    assert_eq!(g(1e20, 17), ">1e+20");
    assert_eq!(g(1.5e20, 17), ">1.5e+20");
    assert_eq!(g(-0.0, 17), ">-0");
    assert_eq!(g(0.5, 17), ">0.5");
    assert_eq!(g(2.0 / 3.0, 17), ">0.66666666666666663");
    assert_eq!(g(f64::from(0.1f32), 9), ">0.100000001");
    assert_eq!(g(-123.0, 2), ">-1.2e+02");
    assert_eq!(g(1e100, 17), ">1e+100");
}

/// Every file in the directory, for checking that no temporary file is left.
fn dir_entries(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    v.sort();
    v
}

fn triangle_output(positions: &[DVec3]) -> ObjOutput<'_> {
    ObjOutput {
        positions,
        face_offsets: &[0, 3],
        face_vertices: &[0, 1, 2],
        holes: None,
        uv: None,
        normals: None,
        precision: Precision::F64,
    }
}

#[test]
fn normals_are_written_as_vn_and_named_by_each_corner() {
    let positions = [DVec3::ZERO, DVec3::X, DVec3::Y];
    let normals = [DVec3::Z; 3];
    let data = ObjOutput {
        normals: Some(&normals),
        ..triangle_output(&positions)
    };
    let mut out = Vec::new();
    write_obj_to(&mut out, &data).unwrap();
    assert_eq!(
        String::from_utf8(out).unwrap(),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\nf 1//1 2//2 3//3\n"
    );
    let uv = UvOutput {
        width: 2,
        values: &[0.0, 0.0, 1.0, 0.0],
        face_values: &[0, 1, 0],
    };
    let data = ObjOutput {
        uv: Some(uv),
        ..data
    };
    let mut out = Vec::new();
    write_obj_to(&mut out, &data).unwrap();
    assert!(
        String::from_utf8(out)
            .unwrap()
            .ends_with("f 1/1/1 2/2/2 3/1/3\n")
    );
    let short = ObjOutput {
        normals: Some(&normals[..2]),
        ..triangle_output(&positions)
    };
    assert!(write_obj_to(&mut Vec::new(), &short).is_err());
}

#[test]
fn write_obj_into_a_missing_directory_fails_and_creates_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("no/such/dir");
    let path = missing.join("out.obj");
    let positions = [DVec3::ZERO, DVec3::X, DVec3::Y];
    match write_obj(&path, &triangle_output(&positions)) {
        Err(Error::Io { path: p, .. }) => assert_eq!(p, path),
        other => panic!("{other:?}"),
    }
    assert!(!missing.exists());
    assert!(dir_entries(dir.path()).is_empty());
}

#[test]
fn write_obj_replaces_an_existing_file_atomically() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("out.obj");
    std::fs::write(&path, "old content\n").unwrap();
    let positions = [DVec3::ZERO, DVec3::X, DVec3::Y];
    write_obj(&path, &triangle_output(&positions)).unwrap();
    assert_eq!(
        std::fs::read_to_string(&path).unwrap(),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
    );
    assert_eq!(dir_entries(dir.path()), std::slice::from_ref(&path));

    // A failed write leaves the previous file untouched and no temporary file.
    let bad = ObjOutput {
        holes: Some(&[]),
        ..triangle_output(&positions)
    };
    match write_obj(&path, &bad) {
        Err(Error::Io { path: p, source }) => {
            assert_eq!(p, path);
            assert_eq!(source.kind(), std::io::ErrorKind::InvalidInput);
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(
        std::fs::read_to_string(&path).unwrap(),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
    );
    assert_eq!(dir_entries(dir.path()), std::slice::from_ref(&path));

    // The file gets the permissions of a plain `File::create`, not a
    // temporary file's private 0600.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let plain = dir.path().join("plain");
        std::fs::File::create(&plain).unwrap();
        let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode(&path), mode(&plain));
    }
}

/// Cross-checks the reader against `tobj` on a generated file in which every
/// vertex and UV is used, and first used in file order, so that `tobj`'s
/// renumbering by first use is the identity.
#[test]
fn reader_agrees_with_tobj() {
    let (nx, ny) = (7usize, 5usize);
    // Grid faces over grid points `j * (nx + 1) + i`, some split in two triangles.
    let point = |i: usize, j: usize| j * (nx + 1) + i;
    let mut faces: Vec<Vec<usize>> = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let q = [
                point(i, j),
                point(i + 1, j),
                point(i + 1, j + 1),
                point(i, j + 1),
            ];
            if (i * j) % 4 == 1 {
                faces.push(vec![q[0], q[1], q[2]]);
                faces.push(vec![q[0], q[2], q[3]]);
            } else {
                faces.push(q.to_vec());
            }
        }
    }
    // Number the points in order of first use, and write them in that order.
    let mut number = vec![usize::MAX; (nx + 1) * (ny + 1)];
    let mut order = Vec::new();
    for &p in faces.iter().flatten() {
        if number[p] == usize::MAX {
            number[p] = order.len();
            order.push(p);
        }
    }
    assert_eq!(order.len(), number.len(), "every point is used");
    let mut text = String::new();
    for &p in &order {
        let (i, j) = (p % (nx + 1), p / (nx + 1));
        // Values exact in f32, so that both readers' roundings agree.
        let (x, y, z) = (
            i as f64 * 0.375 - 1.0,
            j as f64 * 0.25 + 0.5,
            ((i * 7 + j * 3) % 11) as f64 / 8.0,
        );
        text.push_str(&format!("v {x} {y} {z}\n"));
        text.push_str(&format!("vt {} {}\n", i as f64 / 8.0, j as f64 / 16.0));
    }
    let count = order.len() as i64;
    for (f, face) in faces.iter().enumerate() {
        text.push('f');
        for &p in face {
            let index = number[p] as i64 + 1;
            // Every third face with relative indices.
            let index = if f % 3 == 0 { index - count - 1 } else { index };
            text.push_str(&format!(" {index}/{index}"));
        }
        text.push('\n');
    }
    let ours = parse_ok(&text).mesh;
    assert_eq!(ours.face_count(), faces.len());

    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("grid.obj");
    std::fs::write(&path, &text).unwrap();
    let options = tobj::LoadOptions {
        single_index: false,
        triangulate: false,
        ..Default::default()
    };
    let (models, _) = tobj::load_obj(&path, &options).unwrap();
    assert_eq!(models.len(), 1);
    let theirs = &models[0].mesh;

    assert_eq!(ours.face_sizes(), theirs.face_arities);
    assert_eq!(ours.face_vertices, theirs.indices);
    let uv = &ours.fvar_channels[0];
    assert_eq!(uv.indices, theirs.texcoord_indices);
    let positions: Vec<f32> = ours
        .positions
        .iter()
        .flat_map(|p| p.as_vec3().to_array())
        .collect();
    assert_eq!(positions, theirs.positions);
    let texcoords: Vec<f32> = uv.values.iter().map(|&v| v as f32).collect();
    assert_eq!(texcoords, theirs.texcoords);
    // And our own expectation, independently of tobj.
    let expected: Vec<u32> = faces.iter().flatten().map(|&p| number[p] as u32).collect();
    assert_eq!(ours.face_vertices, expected);
    assert_eq!(uv.indices, expected);
}
