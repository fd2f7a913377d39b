//! The corpus of malformed files (`tests/malformed/`) and the error each one
//! must give: its line, its kind and its message. The library tests
//! (`tests/malformed.rs`) read them; the CLI tests (`tests/cli/malformed.rs`)
//! run `subdiv` on them.

use std::path::{Path, PathBuf};
use subdiv::ObjErrorKind;
use subdiv::curve::CurveScheme;
use subdiv::io::points::PointsErrorKind;

/// The path of a file of the corpus (of the folder itself for `""`).
pub fn file(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/malformed")
        .join(name)
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
pub fn obj_errors() -> Vec<(&'static str, usize, ObjErrorKind, &'static str)> {
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
            bad_tag(
                "corner",
                "sharpness 1 '1e39' is beyond the range of f32 (about ±3.4e38)",
            ),
            "bad 'corner' tag: sharpness 1 '1e39' is beyond the range of f32 (about ±3.4e38)",
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

/// Curve files `parse_points` refuses: file, line, kind, message after `FILE:LINE: `.
pub fn curve_errors() -> Vec<(&'static str, usize, PointsErrorKind, &'static str)> {
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

/// Files with too few points: (file, scheme flags, closed, points, needed,
/// line named, message after `FILE:LINE: `).
#[allow(clippy::type_complexity)]
pub fn curve_too_few() -> Vec<(
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
