//! OBJ files with OpenSubdiv's shape-file tags: a reader and a writer.
//!
//! # Reading
//!
//! [`read_obj`] and [`parse_obj`] read the subset of Wavefront OBJ that
//! OpenSubdiv's shape files use — `v`, `vt`, `vn` and `f` statements — plus
//! the `t` tag lines that carry creases, corners, holes and subdivision
//! options:
//!
//! ```text
//! v 0 0 0                           # positions, in file order (w ignored)
//! vt 0 0                            # UVs: face-varying channel 0
//! f 1/1 2/2 3/3 -1/-1               # 1-based or negative (relative) indices
//! t crease 3/1/0 0 1 2 4.0          # a vertex chain; 0-based; 1 sharpness or one per edge
//! t corner 2/2/0 0 3 10 2.5         # vertices; 1 sharpness or one per vertex
//! t hole 1/0/0 5                    # faces, 0-based
//! t interpolateboundary 1/0/0 1     # 0 none, 1 edge-and-corner, 2 edge-only
//! t facevaryinginterpolateboundary 1/0/0 4   # FVarLinearInterpolation code 0..=5
//! t creasemethod 0/0/1 chaikin      # "normal" (uniform) or "chaikin"
//! t smoothtriangles 0/0/1 smooth    # "catmark" or "smooth"
//! ```
//!
//! A tag is `t NAME nI/nF/nS`, then exactly `nI` integers, `nF` floats and
//! `nS` strings. Tags index the vertices and faces of the whole file (0-based),
//! wherever they appear; an index is checked once everything has been read,
//! and an error still names the tag's own line.
//!
//! `vn` lines and the normal indices of face corners are ignored, as
//! OpenSubdiv ignores them (a normal index must still be an integer). `v` may
//! carry a `w` or, as a common extension, an RGB colour, both ignored.
//!
//! Every error names its file, its 1-based line and what is wrong
//! ([`ObjError`]). Harmless oddities — unknown statements, `l` and `p`
//! elements, unknown tags — become [`ObjWarning`]s, never silent misreadings.
//!
//! ## Why not `tobj`
//!
//! The crate depends on `tobj`, but this reader does not use it: `tobj`
//! renumbers vertices in order of first use by a face and drops the unused
//! ones, and it reports no line numbers. In a shape file the vertices must stay
//! in FILE order — the `t` tags index them, and OpenSubdiv's output order
//! follows the base vertex order — so a small line-based parser is needed. The
//! tests cross-check it against `tobj` on files where both orders agree.
//!
//! # Writing
//!
//! [`write_obj_to`] and [`write_obj`] write positions, optional UVs and faces
//! (skipping holes) with every number formatted exactly as C's
//! `printf("%.17g")` (or `"%.9g"` of the value rounded to `f32`) would, so the
//! output is byte-identical to a C++ tool's and `f64` values survive the round
//! trip exactly. [`write_obj`] is atomic: the file appears complete or not at
//! all. [`write_mesh_obj`] and [`mesh_to_obj_string`] write a whole [`Mesh`]
//! including its tags, so that [`parse_obj`] gives the same mesh back.

use crate::error::{Error, ObjError, ObjErrorKind};
use crate::mesh::{Corner, Crease, FVarChannel, MAX_VALENCE, Mesh};
use crate::options::{
    BoundaryInterpolation, CreasingMethod, FVarLinearInterpolation, Options, TriangleSubdivision,
};
use crate::real::Precision;
use glam::DVec3;
use std::borrow::Cow;
use std::fmt;
use std::io::{self, BufWriter, Write};
use std::path::Path;
use std::str::SplitAsciiWhitespace;

// ---------------------------------------------------------------------------
// Reader types
// ---------------------------------------------------------------------------

/// The subdivision options set by a shape file's `t` tags; `None` where the
/// file has no such tag.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ShapeTags {
    /// From `t interpolateboundary 1/0/0 N` (0 none, 1 edge-and-corner, 2 edge-only).
    pub boundary: Option<BoundaryInterpolation>,
    /// From `t facevaryinginterpolateboundary 1/0/0 N` (the `Sdc` code, 0..=5).
    pub fvar: Option<FVarLinearInterpolation>,
    /// From `t creasemethod 0/0/1 normal|chaikin`.
    pub creasing: Option<CreasingMethod>,
    /// From `t smoothtriangles 0/0/1 catmark|smooth`.
    pub triangles: Option<TriangleSubdivision>,
}

impl ShapeTags {
    /// `base` with every option that a tag sets replaced by the tag's value.
    ///
    /// ```
    /// use subdiv::io::ShapeTags;
    /// use subdiv::{BoundaryInterpolation, Options};
    /// let tags = ShapeTags { boundary: Some(BoundaryInterpolation::None), ..ShapeTags::default() };
    /// let options = tags.apply(Options::shape_file_defaults());
    /// assert_eq!(options.boundary, BoundaryInterpolation::None);
    /// assert_eq!(options.fvar, Options::shape_file_defaults().fvar);
    /// ```
    pub fn apply(&self, base: Options) -> Options {
        Options {
            scheme: base.scheme,
            boundary: self.boundary.unwrap_or(base.boundary),
            fvar: self.fvar.unwrap_or(base.fvar),
            creasing: self.creasing.unwrap_or(base.creasing),
            triangles: self.triangles.unwrap_or(base.triangles),
        }
    }
}

/// A questionable but accepted line of an OBJ file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ObjWarning {
    /// 1-based line number.
    pub line: usize,
    /// What was questionable and what was done about it.
    pub message: String,
}

impl fmt::Display for ObjWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: {}", self.line, self.message)
    }
}

/// The content of an OBJ shape file: the mesh with its tags, the option tags,
/// and the warnings met while reading.
#[derive(Debug, Clone, PartialEq)]
pub struct ShapeFile {
    /// The mesh, with vertices in file order, creases, corners, holes and
    /// (when the faces use `vt`) the UVs as face-varying channel 0.
    pub mesh: Mesh,
    /// The option tags.
    pub tags: ShapeTags,
    /// Accepted oddities, in file order.
    pub warnings: Vec<ObjWarning>,
}

impl ShapeFile {
    /// The options the file asks for: its tags over [`Options::shape_file_defaults`].
    pub fn options(&self) -> Options {
        self.tags.apply(Options::shape_file_defaults())
    }
}

// ---------------------------------------------------------------------------
// Reader
// ---------------------------------------------------------------------------

/// Reads an OBJ shape file.
///
/// Failing to read the file is an [`ObjErrorKind::Io`] error on line 0. Bytes
/// that are not UTF-8 are replaced (they can only matter inside a number, where
/// they are a syntax error), and a leading byte-order mark is skipped.
pub fn read_obj(path: &Path) -> Result<ShapeFile, ObjError> {
    let bytes = std::fs::read(path).map_err(|e| ObjError {
        file: path.to_path_buf(),
        line: 0,
        kind: ObjErrorKind::Io(e.to_string()),
    })?;
    let text: Cow<'_, str> = String::from_utf8_lossy(&bytes);
    parse_obj(&text, path)
}

/// Parses the text of an OBJ shape file; `file` only names it in errors
/// (use `Path::new("<memory>")` for in-memory text).
///
/// ```
/// use std::path::Path;
/// use subdiv::io::parse_obj;
/// let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nt crease 2/1/0 0 1 10\n";
/// let shape = parse_obj(text, Path::new("<memory>"))?;
/// assert_eq!(shape.mesh.face_vertices, [0, 1, 2, 3]);
/// assert_eq!(shape.mesh.creases[0].vertices, [0, 1]);
/// # Ok::<(), subdiv::ObjError>(())
/// ```
pub fn parse_obj(text: &str, file: &Path) -> Result<ShapeFile, ObjError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let error = |line: usize, kind: ObjErrorKind| ObjError {
        file: file.to_path_buf(),
        line,
        kind,
    };
    let mut parser = Parser::default();
    for (i, line) in text.lines().enumerate() {
        parser
            .statement(i + 1, line)
            .map_err(|kind| error(i + 1, kind))?;
    }
    parser.finish().map_err(|(line, kind)| error(line, kind))
}

/// A `crease`, `corner` or `hole` tag, kept until every vertex and face is known.
struct ElementTag {
    line: usize,
    kind: ElementKind,
    ints: Vec<i64>,
    floats: Vec<f32>,
}

#[derive(Clone, Copy, PartialEq)]
enum ElementKind {
    Crease,
    Corner,
    Hole,
}

impl ElementKind {
    fn name(self) -> &'static str {
        match self {
            ElementKind::Crease => "crease",
            ElementKind::Corner => "corner",
            ElementKind::Hole => "hole",
        }
    }
}

/// The line-by-line state of [`parse_obj`].
#[derive(Default)]
struct Parser {
    mesh: Mesh,
    uv_values: Vec<f64>,
    uv_indices: Vec<u32>,
    /// Whether face corners carry texture coordinates, and the line of the
    /// first face corner, which decided it.
    uv_mode: Option<(bool, usize)>,
    tags: ShapeTags,
    /// The line of the last tag setting each option of [`ShapeTags`], in field order.
    option_lines: [usize; 4],
    element_tags: Vec<ElementTag>,
    warnings: Vec<ObjWarning>,
}

/// At most this many characters of a field are quoted in a message.
const QUOTE_LIMIT: usize = 40;

/// Text from a file made safe for a message: control characters and other
/// unprintable ones are escaped as Rust writes them (`\0`, `\t`, `\u{1b}`...)
/// and `\` is written `\\`, so that a message can never carry a terminal
/// escape sequence or a line break. Quotes are kept as they are.
pub(crate) fn escape(text: &str) -> Cow<'_, str> {
    let plain = |c: char| c == '\'' || c == '"' || c.escape_debug().len() == 1;
    if text.chars().all(plain) {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if plain(c) {
            out.push(c);
        } else {
            out.extend(c.escape_debug());
        }
    }
    Cow::Owned(out)
}

/// A field of the file for a message: at most [`QUOTE_LIMIT`] characters of
/// it (then `...`), [`escape`]d.
fn quote(field: &str) -> Cow<'_, str> {
    match field.char_indices().nth(QUOTE_LIMIT) {
        Some((end, _)) => Cow::Owned(format!("{}...", escape(&field[..end]))),
        None => escape(field),
    }
}

fn syntax(message: String) -> ObjErrorKind {
    ObjErrorKind::Syntax(message)
}

/// Parses a coordinate named `name` of a `statement`, which must be a finite number.
fn coordinate(field: &str, statement: &str, name: &str) -> Result<f64, ObjErrorKind> {
    let value: f64 = field.parse().map_err(|_| {
        syntax(format!(
            "'{statement}' statement: {name} '{}' is not a number",
            quote(field)
        ))
    })?;
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ObjErrorKind::NonFinite(format!(
            "{name} = {} in a '{statement}' statement",
            quote(field)
        )))
    }
}

/// The 0-based index of a 1-based or negative (relative) OBJ index among
/// `count` elements defined so far.
fn resolve(index: i64, count: usize, what: &'static str) -> Result<u32, ObjErrorKind> {
    let out_of_range = || ObjErrorKind::IndexOutOfRange { what, index, count };
    let zero_based = if index > 0 {
        let i = (index - 1) as u64;
        if i >= count as u64 {
            return Err(out_of_range());
        }
        i
    } else if index < 0 {
        let back = index.unsigned_abs();
        if back > count as u64 {
            return Err(out_of_range());
        }
        count as u64 - back
    } else {
        return Err(out_of_range());
    };
    u32::try_from(zero_based).map_err(|_| {
        syntax(format!(
            "{what} index {index} does not fit the 32-bit indices of a mesh"
        ))
    })
}

impl Parser {
    fn warn(&mut self, line: usize, message: String) {
        self.warnings.push(ObjWarning { line, message });
    }

    /// Reads one line.
    fn statement(&mut self, line: usize, text: &str) -> Result<(), ObjErrorKind> {
        let text = match text.find('#') {
            Some(i) => &text[..i],
            None => text,
        };
        let mut fields = text.split_ascii_whitespace();
        let Some(keyword) = fields.next() else {
            return Ok(());
        };
        match keyword {
            "v" => self.vertex(fields),
            "vt" => self.texcoord(fields),
            "vn" => Ok(()),
            "f" => self.face(line, fields),
            "t" => self.tag(line, fields),
            "o" | "g" | "s" | "usemtl" | "mtllib" => Ok(()),
            "l" | "p" => {
                let what = if keyword == "l" { "line" } else { "point" };
                self.warn(
                    line,
                    format!("'{keyword}' ({what}) elements are not supported; the line is ignored"),
                );
                Ok(())
            }
            _ => {
                self.warn(
                    line,
                    format!(
                        "unknown statement '{}'; the line is ignored",
                        quote(keyword)
                    ),
                );
                Ok(())
            }
        }
    }

    /// `v x y z [w]`, also accepting the common `v x y z r g b` colour extension.
    fn vertex(&mut self, fields: SplitAsciiWhitespace<'_>) -> Result<(), ObjErrorKind> {
        let mut raw = [""; 6];
        let mut n = 0;
        for field in fields {
            if n < raw.len() {
                raw[n] = field;
            }
            n += 1;
        }
        let names: &[&str] = match n {
            3 => &["x", "y", "z"],
            4 => &["x", "y", "z", "w"],
            6 => &["x", "y", "z", "red", "green", "blue"],
            _ => {
                return Err(syntax(format!(
                    "a 'v' statement needs x y z [w] (or x y z r g b), found {n} values"
                )));
            }
        };
        let mut xyz = [0.0; 3];
        for (i, name) in names.iter().enumerate() {
            let value = coordinate(raw[i], "v", name)?;
            if i < 3 {
                xyz[i] = value;
            }
        }
        self.mesh.positions.push(DVec3::from_array(xyz));
        Ok(())
    }

    /// `vt u v [w]`.
    fn texcoord(&mut self, fields: SplitAsciiWhitespace<'_>) -> Result<(), ObjErrorKind> {
        let mut uv = [0.0; 2];
        let mut n = 0;
        for field in fields {
            if n < 3 {
                let value = coordinate(field, "vt", ["u", "v", "w"][n])?;
                if n < 2 {
                    uv[n] = value;
                }
            }
            n += 1;
        }
        if !(2..=3).contains(&n) {
            return Err(syntax(format!(
                "a 'vt' statement needs u v [w], found {n} values"
            )));
        }
        self.uv_values.extend_from_slice(&uv);
        Ok(())
    }

    /// `f v v/vt v//vn v/vt/vn ...`.
    fn face(&mut self, line: usize, fields: SplitAsciiWhitespace<'_>) -> Result<(), ObjErrorKind> {
        let size = fields.clone().count();
        if size < 3 {
            return Err(ObjErrorKind::FaceTooSmall(size));
        }
        if size > MAX_VALENCE {
            return Err(ObjErrorKind::FaceTooLarge(size));
        }
        let vertex_count = self.mesh.positions.len();
        let uv_count = self.uv_values.len() / 2;
        for (k, field) in fields.enumerate() {
            let corner = k + 1;
            let mut parts = field.split('/');
            let v = parts.next().unwrap_or("");
            let vt = parts.next();
            let vn = parts.next();
            if parts.next().is_some() {
                return Err(syntax(format!(
                    "face corner {corner} '{}' has more than three '/'-separated indices",
                    quote(field)
                )));
            }
            let index = |text: &str, what: &str| -> Result<i64, ObjErrorKind> {
                if text.is_empty() {
                    return Err(syntax(format!(
                        "face corner {corner} '{}': the {what} index is missing",
                        quote(field)
                    )));
                }
                text.parse().map_err(|_| {
                    syntax(format!(
                        "face corner {corner} '{}': {what} index '{}' is not an integer",
                        quote(field),
                        quote(text)
                    ))
                })
            };
            let vertex = resolve(index(v, "vertex")?, vertex_count, "vertex")?;
            let uv = match (vt, vn) {
                (None, _) => None,
                (Some(""), Some(_)) => None,
                (Some(t), _) => Some(resolve(
                    index(t, "texture coordinate")?,
                    uv_count,
                    "texture coordinate",
                )?),
            };
            if let Some(n) = vn {
                // Normals are ignored, as OpenSubdiv ignores them: the index
                // must be an integer, but is not checked against the `vn` count.
                index(n, "normal")?;
            }
            self.check_uv_mode(line, corner, uv.is_some())?;
            self.mesh.face_vertices.push(vertex);
            if let Some(t) = uv {
                self.uv_indices.push(t);
            }
        }
        let end = u32::try_from(self.mesh.face_vertices.len())
            .map_err(|_| syntax("too many face corners for 32-bit indices".into()))?;
        self.mesh.face_offsets.push(end);
        Ok(())
    }

    /// Either every face corner has a texture coordinate, or none has.
    fn check_uv_mode(
        &mut self,
        line: usize,
        corner: usize,
        has_uv: bool,
    ) -> Result<(), ObjErrorKind> {
        let (mode, first_line) = *self.uv_mode.get_or_insert((has_uv, line));
        if mode == has_uv {
            return Ok(());
        }
        let this = if has_uv {
            "has a texture coordinate"
        } else {
            "has none"
        };
        let first = if mode { "has one" } else { "has none" };
        Err(ObjErrorKind::InconsistentTexcoords(if first_line == line {
            format!("corner {corner} of this face {this} but its corner 1 {first}")
        } else {
            format!(
                "corner {corner} of this face {this} but the first face corner (line {first_line}) {first}"
            )
        }))
    }

    /// `t NAME nI/nF/nS ints... floats... strings...`.
    fn tag(
        &mut self,
        line: usize,
        mut fields: SplitAsciiWhitespace<'_>,
    ) -> Result<(), ObjErrorKind> {
        let Some(name) = fields.next() else {
            return Err(syntax("a 't' statement needs a tag name".into()));
        };
        let bad = |message: String| ObjErrorKind::BadTag {
            tag: quote(name).into_owned(),
            message,
        };
        let Some(counts) = fields.next() else {
            return Err(bad(
                "the argument counts 'ints/floats/strings' are missing".into()
            ));
        };
        let parse_counts = || -> Option<[usize; 3]> {
            let mut it = counts.split('/');
            let c = [
                it.next()?.parse().ok()?,
                it.next()?.parse().ok()?,
                it.next()?.parse().ok()?,
            ];
            it.next().is_none().then_some(c)
        };
        let [ni, nf, ns] = parse_counts().ok_or_else(|| {
            bad(format!(
                "the argument counts must be written 'ints/floats/strings', found '{}'",
                quote(counts)
            ))
        })?;
        let args: Vec<&str> = fields.collect();
        let announced = ni.checked_add(nf).and_then(|n| n.checked_add(ns));
        if announced != Some(args.len()) {
            return Err(bad(format!(
                "the counts {counts} announce {} arguments but {} follow",
                announced.map_or_else(|| "too many".to_string(), |n| n.to_string()),
                args.len()
            )));
        }
        let ints = args[..ni]
            .iter()
            .enumerate()
            .map(|(i, s)| {
                s.parse::<i64>().map_err(|_| {
                    bad(format!(
                        "integer argument {} '{}' is not an integer",
                        i + 1,
                        quote(s)
                    ))
                })
            })
            .collect::<Result<Vec<i64>, _>>()?;
        let float_args = &args[ni..ni + nf];
        let floats = float_args
            .iter()
            .enumerate()
            .map(|(i, s)| {
                s.parse::<f32>().map_err(|_| {
                    bad(format!(
                        "float argument {} '{}' is not a number",
                        i + 1,
                        quote(s)
                    ))
                })
            })
            .collect::<Result<Vec<f32>, _>>()?;
        let strings = &args[ni + nf..];
        let shape = |want: [usize; 3]| -> Result<(), ObjErrorKind> {
            if [ni, nf, ns] == want {
                Ok(())
            } else {
                Err(bad(format!(
                    "expects {}/{}/{} arguments, found {counts}",
                    want[0], want[1], want[2]
                )))
            }
        };
        let sharpness_ok = |floats: &[f32]| -> Result<(), ObjErrorKind> {
            match floats.iter().position(|s| !s.is_finite()) {
                Some(i) => Err(bad(format!(
                    "sharpness {} '{}' is not a finite number",
                    i + 1,
                    quote(float_args[i])
                ))),
                None => Ok(()),
            }
        };
        let kind = match name {
            "crease" => {
                if ns != 0 {
                    return Err(bad(format!("takes no string arguments, found {ns}")));
                }
                if ni < 2 {
                    return Err(bad(format!(
                        "needs a chain of at least 2 vertices, found {ni}"
                    )));
                }
                let edges = ni - 1;
                if nf != 1 && nf != edges {
                    return Err(bad(if edges == 1 {
                        format!("needs 1 sharpness, found {nf}")
                    } else {
                        format!(
                            "{ni} vertices make {edges} edges: give 1 sharpness for all or {edges} (one per edge), found {nf}"
                        )
                    }));
                }
                sharpness_ok(&floats)?;
                ElementKind::Crease
            }
            "corner" => {
                if ns != 0 {
                    return Err(bad(format!("takes no string arguments, found {ns}")));
                }
                if ni < 1 {
                    return Err(bad("names no vertex".into()));
                }
                if nf != 1 && nf != ni {
                    return Err(bad(format!(
                        "give 1 sharpness for all {ni} vertices or one each, found {nf}"
                    )));
                }
                sharpness_ok(&floats)?;
                ElementKind::Corner
            }
            "hole" => {
                if nf != 0 || ns != 0 {
                    return Err(bad(format!(
                        "takes only face indices (n/0/0), found {counts}"
                    )));
                }
                if ni < 1 {
                    return Err(bad("names no face".into()));
                }
                ElementKind::Hole
            }
            "interpolateboundary" => {
                shape([1, 0, 0])?;
                let value = match ints[0] {
                    0 => BoundaryInterpolation::None,
                    1 => BoundaryInterpolation::EdgeAndCorner,
                    2 => BoundaryInterpolation::EdgeOnly,
                    v => {
                        return Err(bad(format!(
                            "unknown value {v}: expected 0 (none), 1 (edge and corner) or 2 (edge only)"
                        )));
                    }
                };
                self.set_option(0, line, name);
                self.tags.boundary = Some(value);
                return Ok(());
            }
            "facevaryinginterpolateboundary" => {
                shape([1, 0, 0])?;
                let value = FVarLinearInterpolation::from_code(ints[0]).ok_or_else(|| {
                    bad(format!(
                        "unknown value {}: expected 0 (none) to 5 (all)",
                        ints[0]
                    ))
                })?;
                self.set_option(1, line, name);
                self.tags.fvar = Some(value);
                return Ok(());
            }
            "creasemethod" => {
                shape([0, 0, 1])?;
                let value = match strings[0] {
                    "normal" => CreasingMethod::Uniform,
                    "chaikin" => CreasingMethod::Chaikin,
                    s => {
                        return Err(bad(format!(
                            "unknown value '{}': expected 'normal' or 'chaikin'",
                            quote(s)
                        )));
                    }
                };
                self.set_option(2, line, name);
                self.tags.creasing = Some(value);
                return Ok(());
            }
            "smoothtriangles" => {
                shape([0, 0, 1])?;
                let value = match strings[0] {
                    "catmark" => TriangleSubdivision::Catmark,
                    "smooth" => TriangleSubdivision::Smooth,
                    s => {
                        return Err(bad(format!(
                            "unknown value '{}': expected 'catmark' or 'smooth'",
                            quote(s)
                        )));
                    }
                };
                self.set_option(3, line, name);
                self.tags.triangles = Some(value);
                return Ok(());
            }
            _ => {
                self.warn(
                    line,
                    format!("unknown tag '{}'; the line is ignored", quote(name)),
                );
                return Ok(());
            }
        };
        self.element_tags.push(ElementTag {
            line,
            kind,
            ints,
            floats,
        });
        Ok(())
    }

    /// Records the line of an option tag, warning when it overrides an earlier one.
    fn set_option(&mut self, slot: usize, line: usize, name: &str) {
        let previous = std::mem::replace(&mut self.option_lines[slot], line);
        if previous != 0 {
            self.warn(
                line,
                format!("this '{name}' tag overrides the one at line {previous}"),
            );
        }
    }

    /// Resolves the element tags and assembles the result.
    fn finish(mut self) -> Result<ShapeFile, (usize, ObjErrorKind)> {
        let vertex_count = self.mesh.positions.len();
        let face_count = self.mesh.face_count();
        for tag in &self.element_tags {
            let (what, count) = match tag.kind {
                ElementKind::Hole => ("face", face_count),
                _ => ("vertex", vertex_count),
            };
            let mut indices = Vec::with_capacity(tag.ints.len());
            for &index in &tag.ints {
                if index < 0 || index as u64 >= count as u64 {
                    return Err((
                        tag.line,
                        ObjErrorKind::TagOutOfRange {
                            tag: tag.kind.name().to_string(),
                            what,
                            index,
                            count,
                        },
                    ));
                }
                indices.push(index as u32);
            }
            let sharpness = |i: usize| {
                if tag.floats.len() == 1 {
                    tag.floats[0]
                } else {
                    tag.floats[i]
                }
            };
            match tag.kind {
                ElementKind::Crease => {
                    self.mesh
                        .creases
                        .extend(indices.windows(2).enumerate().map(|(i, pair)| Crease {
                            vertices: [pair[0], pair[1]],
                            sharpness: sharpness(i),
                        }));
                }
                ElementKind::Corner => {
                    self.mesh
                        .corners
                        .extend(indices.iter().enumerate().map(|(i, &vertex)| Corner {
                            vertex,
                            sharpness: sharpness(i),
                        }));
                }
                ElementKind::Hole => self.mesh.holes.extend_from_slice(&indices),
            }
        }
        if let Some((true, _)) = self.uv_mode {
            self.mesh.fvar_channels = vec![FVarChannel {
                width: 2,
                values: self.uv_values,
                indices: self.uv_indices,
            }];
        }
        Ok(ShapeFile {
            mesh: self.mesh,
            tags: self.tags,
            warnings: self.warnings,
        })
    }
}

// ---------------------------------------------------------------------------
// Number formatting
// ---------------------------------------------------------------------------

/// The most significant digits [`format_g`] produces.
const MAX_SIGNIFICANT: usize = 40;

/// Room for one formatted number (at most 48 bytes with 40 digits).
const NUMBER_CAPACITY: usize = 64;

/// A fixed-size byte buffer, so that formatting a number allocates nothing.
struct NumberBuf {
    bytes: [u8; NUMBER_CAPACITY],
    len: usize,
}

impl NumberBuf {
    fn new() -> Self {
        NumberBuf {
            bytes: [0; NUMBER_CAPACITY],
            len: 0,
        }
    }

    fn push(&mut self, b: u8) {
        self.bytes[self.len] = b;
        self.len += 1;
    }

    fn extend(&mut self, s: &[u8]) {
        self.bytes[self.len..self.len + s.len()].copy_from_slice(s);
        self.len += s.len();
    }

    fn as_bytes(&self) -> &[u8] {
        &self.bytes[..self.len]
    }
}

impl fmt::Write for NumberBuf {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        if self.len + s.len() > NUMBER_CAPACITY {
            return Err(fmt::Error);
        }
        self.extend(s.as_bytes());
        Ok(())
    }
}

/// Where [`g_format`] puts its bytes.
trait ByteSink {
    fn push(&mut self, b: u8);
    fn extend(&mut self, s: &[u8]);
}

impl ByteSink for NumberBuf {
    fn push(&mut self, b: u8) {
        NumberBuf::push(self, b);
    }

    fn extend(&mut self, s: &[u8]) {
        NumberBuf::extend(self, s);
    }
}

impl ByteSink for Vec<u8> {
    fn push(&mut self, b: u8) {
        Vec::push(self, b);
    }

    fn extend(&mut self, s: &[u8]) {
        self.extend_from_slice(s);
    }
}

/// `10^k` for every `k` whose power fits in 128 bits.
const POW10: [u128; 39] = {
    let mut t = [1u128; 39];
    let mut k = 1;
    while k < 39 {
        t[k] = t[k - 1] * 10;
        k += 1;
    }
    t
};

/// The `p` significant decimal digits of `x` (finite, positive) rounded to
/// nearest with ties to even, as an integer of exactly `p` digits, and the
/// decimal exponent of the first digit: `x ≈ digits × 10^(exp + 1 - p)`.
///
/// Exact integer arithmetic: with `x = m × 2^e`, the digits are
/// `m × 2^e × 10^s` rounded for the scale `s` that leaves `p` digits, computed
/// in 128 bits. `None` where that does not fit (magnitudes beyond about
/// `1e±21` for 17 digits) or for more than 19 digits: the caller then uses
/// the standard library's (slower) exact formatting.
fn exact_digits(x: f64, p: u32) -> Option<(u64, i32)> {
    if !(1..=19).contains(&p) {
        return None;
    }
    let bits = x.to_bits();
    let (biased, fraction) = ((bits >> 52) as i32 & 0x7ff, bits & ((1 << 52) - 1));
    let (m, e) = match biased {
        0 => (fraction, -1074),
        _ => (fraction | 1 << 52, biased - 1075),
    };
    if m == 0 {
        return None;
    }
    // 2^b <= x < 2^(b + 1), so the decimal exponent is floor(b log10 2) or
    // one more (78913 / 2^18 is log10 2 rounded down, exact enough here).
    let b = e + 63 - m.leading_zeros() as i32;
    let mut exp = (b * 78913) >> 18;
    let limit = POW10[p as usize] as u64;
    for _ in 0..3 {
        let n = scaled_round(m, e, p as i32 - 1 - exp)?;
        if n >= limit {
            exp += 1;
        } else if n < limit / 10 {
            exp -= 1;
        } else {
            return Some((n, exp));
        }
    }
    None
}

/// `m × 2^e × 10^s` rounded to the nearest integer, ties to even, when the
/// computation fits in 128 bits and the result in 64.
fn scaled_round(m: u64, e: i32, s: i32) -> Option<u64> {
    let ten = |k: i32| POW10.get(k.unsigned_abs() as usize).copied();
    // Numerator m × 2^max(e, 0) × 10^max(s, 0).
    let mut num = u128::from(m);
    if s > 0 {
        num = num.checked_mul(ten(s)?)?;
    }
    if e > 0 {
        if num.leading_zeros() <= e as u32 {
            return None;
        }
        num <<= e;
    }
    let (q, round_up) = if s >= 0 {
        // Denominator 2^max(-e, 0): a shift.
        let shift = (-e).max(0) as u32;
        if shift == 0 {
            (num, false)
        } else if shift >= 127 {
            return None;
        } else {
            let q = num >> shift;
            let r = num & ((1u128 << shift) - 1);
            let half = 1u128 << (shift - 1);
            (q, r > half || (r == half && q & 1 == 1))
        }
    } else {
        // Denominator 2^max(-e, 0) × 10^-s.
        let mut den = ten(s)?;
        if e < 0 {
            if den.leading_zeros() <= (-e) as u32 {
                return None;
            }
            den <<= -e;
        }
        let (q, r) = (num / den, num % den);
        let rest = den - r;
        (q, r > rest || (r == rest && q & 1 == 1))
    };
    u64::try_from(q + u128::from(round_up)).ok()
}

/// Appends `x` formatted like C's `printf("%.*g", significant, x)` (glibc).
fn g_format(x: f64, significant: usize, out: &mut impl ByteSink) {
    use fmt::Write as _;
    let p = significant.clamp(1, MAX_SIGNIFICANT);
    if x.is_sign_negative() {
        out.push(b'-');
    }
    if x.is_nan() {
        out.extend(b"nan");
        return;
    }
    if x.is_infinite() {
        out.extend(b"inf");
        return;
    }
    if x == 0.0 {
        out.push(b'0');
        return;
    }
    // The p significant digits and the exponent X of `%.{p-1}e`: from exact
    // integer arithmetic where it fits, else from Rust's `{:.N e}`, which is
    // correctly rounded too (ties to even on exact ties, as glibc).
    let mut digits = NumberBuf::new();
    let exp = if let Some((n, exp)) = exact_digits(x.abs(), p as u32) {
        let mut text = itoa::Buffer::new();
        digits.extend(text.format(n).as_bytes());
        exp
    } else {
        let mut sci = NumberBuf::new();
        write!(sci, "{:.*e}", p - 1, x.abs()).expect("a formatted number fits in 64 bytes");
        let sci = sci.as_bytes();
        let e = sci
            .iter()
            .position(|&c| c == b'e')
            .expect("exponential format has an 'e'");
        digits.push(sci[0]);
        if e > 1 {
            digits.extend(&sci[2..e]);
        }
        let (exp_negative, exp_digits) = match sci[e + 1] {
            b'-' => (true, &sci[e + 2..]),
            _ => (false, &sci[e + 1..]),
        };
        let magnitude = exp_digits
            .iter()
            .fold(0i32, |acc, &c| acc * 10 + i32::from(c - b'0'));
        if exp_negative { -magnitude } else { magnitude }
    };
    let digits = digits.as_bytes();
    let (first, rest) = (digits[0], &digits[1..]);
    // Without '#', %g removes trailing zeros of the fraction (and a bare '.').
    let mut kept = rest.len();
    while kept > 0 && rest[kept - 1] == b'0' {
        kept -= 1;
    }
    if exp < -4 || exp >= p as i32 {
        out.push(first);
        if kept > 0 {
            out.push(b'.');
            out.extend(&rest[..kept]);
        }
        out.push(b'e');
        out.push(if exp < 0 { b'-' } else { b'+' });
        let magnitude = exp.unsigned_abs();
        if magnitude < 10 {
            out.push(b'0');
        }
        let mut buf = itoa::Buffer::new();
        out.extend(buf.format(magnitude).as_bytes());
    } else if exp >= 0 {
        // 0 <= exp < p: the integer part has exp + 1 <= p digits.
        let int_rest = exp as usize;
        out.push(first);
        out.extend(&rest[..int_rest]);
        if kept > int_rest {
            out.push(b'.');
            out.extend(&rest[int_rest..kept]);
        }
    } else {
        out.extend(b"0.");
        for _ in 0..(-exp - 1) {
            out.push(b'0');
        }
        out.push(first);
        out.extend(&rest[..kept]);
    }
}

/// Appends `x` formatted exactly like C's `printf("%.*g", significant, x)`.
///
/// `significant` is clamped to `1..=40` (C treats 0 as 1). Scientific notation
/// is used when the decimal exponent is below -4 or at least `significant`;
/// trailing zeros and a trailing `.` are removed; the exponent has a sign and at
/// least two digits; `-0.0` gives `-0`, and non-finite values give `inf`,
/// `-inf` and `nan` as glibc does.
///
/// ```
/// use subdiv::io::format_g;
/// let mut s = String::new();
/// format_g(0.1, 17, &mut s);
/// s.push(' ');
/// format_g(1e20, 17, &mut s);
/// s.push(' ');
/// format_g(0.1f32 as f64, 9, &mut s);
/// assert_eq!(s, "0.10000000000000001 1e+20 0.100000001");
/// ```
pub fn format_g(x: f64, significant: usize, out: &mut String) {
    let mut buf = NumberBuf::new();
    g_format(x, significant, &mut buf);
    out.push_str(std::str::from_utf8(buf.as_bytes()).expect("formatted numbers are ASCII"));
}

fn push_u64(n: u64, out: &mut Vec<u8>) {
    let mut buf = itoa::Buffer::new();
    out.extend_from_slice(buf.format(n).as_bytes());
}

// ---------------------------------------------------------------------------
// Writer
// ---------------------------------------------------------------------------

/// What [`write_obj_to`] writes: positions, faces and optional UVs, borrowed.
#[derive(Debug, Clone, Copy)]
pub struct ObjOutput<'a> {
    /// Vertex positions, written as `v` lines.
    pub positions: &'a [DVec3],
    /// Start of each face in `face_vertices`, plus one final entry.
    pub face_offsets: &'a [u32],
    /// 0-based vertex indices of all faces, concatenated.
    pub face_vertices: &'a [u32],
    /// One flag per face; faces flagged `true` are left out.
    pub holes: Option<&'a [bool]>,
    /// Face-varying values written as `vt` lines and `v/vt` face corners.
    pub uv: Option<UvOutput<'a>>,
    /// `F64` writes `%.17g` (exact); `F32` rounds to `f32` and writes `%.9g`.
    pub precision: Precision,
}

/// Face-varying values for [`ObjOutput::uv`].
#[derive(Debug, Clone, Copy)]
pub struct UvOutput<'a> {
    /// Components per value; every component goes on the value's `vt` line.
    pub width: usize,
    /// The values, `width` components each, flattened.
    pub values: &'a [f64],
    /// 0-based value index of every face corner, parallel to `face_vertices`.
    pub face_values: &'a [u32],
}

fn invalid(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, message)
}

/// Checks the shape of an [`ObjOutput`], so that writing cannot panic.
fn check_output(data: &ObjOutput<'_>) -> io::Result<()> {
    let corners = data.face_vertices.len();
    if let Some(i) = data
        .face_offsets
        .windows(2)
        .position(|w| w[1] < w[0] || w[1] as usize > corners)
    {
        return Err(invalid(format!(
            "face offsets {} and {} ({} and {}) are decreasing or beyond the {corners} face vertices",
            i,
            i + 1,
            data.face_offsets[i],
            data.face_offsets[i + 1]
        )));
    }
    if let Some(&first) = data.face_offsets.first() {
        if first as usize > corners {
            return Err(invalid(format!(
                "face offset 0 ({first}) is beyond the {corners} face vertices"
            )));
        }
    }
    let faces = data.face_offsets.len().saturating_sub(1);
    if let Some(holes) = data.holes {
        if holes.len() != faces {
            return Err(invalid(format!(
                "{} hole flags for {faces} faces",
                holes.len()
            )));
        }
    }
    if let Some(uv) = &data.uv {
        if uv.width == 0 || uv.values.len() % uv.width != 0 {
            return Err(invalid(format!(
                "{} UV components do not make values of width {}",
                uv.values.len(),
                uv.width
            )));
        }
        if uv.face_values.len() != corners {
            return Err(invalid(format!(
                "{} UV indices for {corners} face corners",
                uv.face_values.len()
            )));
        }
    }
    Ok(())
}

/// Bytes gathered before they are handed to the writer.
const CHUNK: usize = 1 << 16;

/// Formats numbers at a fixed precision into a reusable buffer.
struct LineWriter<W: Write> {
    out: BufWriter<W>,
    buf: Vec<u8>,
    single: bool,
}

impl<W: Write> LineWriter<W> {
    fn new(out: W, precision: Precision) -> Self {
        LineWriter {
            out: BufWriter::with_capacity(CHUNK, out),
            buf: Vec::with_capacity(CHUNK + 1024),
            single: matches!(precision, Precision::F32),
        }
    }

    fn number(&mut self, x: f64) {
        if self.single {
            g_format(f64::from(x as f32), 9, &mut self.buf);
        } else {
            g_format(x, 17, &mut self.buf);
        }
    }

    /// Ends a line, handing the buffer over when it is full.
    fn end_line(&mut self) -> io::Result<()> {
        self.buf.push(b'\n');
        if self.buf.len() >= CHUNK {
            self.out.write_all(&self.buf)?;
            self.buf.clear();
        }
        Ok(())
    }

    fn finish(mut self) -> io::Result<()> {
        self.out.write_all(&self.buf)?;
        self.out.flush()
    }
}

/// Writes positions, UVs and faces as OBJ text.
///
/// Writes `v x y z` for every position, `vt` with all `width` components for
/// every UV value, and an `f` line per face that is not a hole, with 1-based
/// `v/vt` corners (plain `v` without UVs). Numbers are formatted as C's
/// `%.17g` ([`Precision::F64`]) or `%.9g` of the value rounded to `f32`
/// ([`Precision::F32`]); see [`format_g`].
///
/// Malformed input (decreasing offsets, a hole flag count or UV index count
/// that does not match) is an [`io::ErrorKind::InvalidInput`] error before
/// anything is written. Indices themselves are written as given.
pub fn write_obj_to<W: Write>(out: W, data: &ObjOutput<'_>) -> io::Result<()> {
    check_output(data)?;
    let mut w = LineWriter::new(out, data.precision);
    for p in data.positions {
        w.buf.push(b'v');
        for c in p.to_array() {
            w.buf.push(b' ');
            w.number(c);
        }
        w.end_line()?;
    }
    if let Some(uv) = &data.uv {
        for value in uv.values.chunks_exact(uv.width) {
            w.buf.extend_from_slice(b"vt");
            for &c in value {
                w.buf.push(b' ');
                w.number(c);
            }
            w.end_line()?;
        }
    }
    for (f, range) in data.face_offsets.windows(2).enumerate() {
        if data.holes.is_some_and(|holes| holes[f]) {
            continue;
        }
        let (start, end) = (range[0] as usize, range[1] as usize);
        w.buf.push(b'f');
        for i in start..end {
            w.buf.push(b' ');
            push_u64(u64::from(data.face_vertices[i]) + 1, &mut w.buf);
            if let Some(uv) = &data.uv {
                w.buf.push(b'/');
                push_u64(u64::from(uv.face_values[i]) + 1, &mut w.buf);
            }
        }
        w.end_line()?;
    }
    w.finish()
}

/// Writes an OBJ file atomically: the text goes to a temporary file in the
/// same directory, which then replaces `path`. On any error `path` is left
/// untouched and the temporary file is removed.
///
/// Any failure is an [`Error::Io`] naming `path`.
pub fn write_obj(path: &Path, data: &ObjOutput<'_>) -> Result<(), Error> {
    super::atomic::write_with(path, |file| write_obj_to(file, data))
}

/// Writes a [`Mesh`] as OBJ text with its tags, so that [`parse_obj`] reads
/// the same mesh back (exactly, with [`Precision::F64`]).
///
/// Writes the positions, face-varying channel 0 as `vt` when its width is 2
/// (other channels are not written), every face (holes included), then one
/// `t crease 2/1/0 a b s` line per crease, one `t corner` line for all corners
/// and one `t hole` line for all holes. Sharpness is written with 9 significant
/// digits, which is exact for `f32`. Option tags are not written.
pub fn write_mesh_obj_to<W: Write>(
    mut out: W,
    mesh: &Mesh,
    precision: Precision,
) -> io::Result<()> {
    let uv = mesh
        .fvar_channels
        .first()
        .filter(|channel| channel.width == 2)
        .map(|channel| UvOutput {
            width: 2,
            values: &channel.values,
            face_values: &channel.indices,
        });
    let data = ObjOutput {
        positions: &mesh.positions,
        face_offsets: &mesh.face_offsets,
        face_vertices: &mesh.face_vertices,
        holes: None,
        uv,
        precision,
    };
    write_obj_to(&mut out, &data)?;
    let mut buf = Vec::new();
    let sharpness = |s: f32, buf: &mut Vec<u8>| {
        g_format(f64::from(s), 9, buf);
    };
    for crease in &mesh.creases {
        buf.extend_from_slice(b"t crease 2/1/0 ");
        push_u64(crease.vertices[0].into(), &mut buf);
        buf.push(b' ');
        push_u64(crease.vertices[1].into(), &mut buf);
        buf.push(b' ');
        sharpness(crease.sharpness, &mut buf);
        buf.push(b'\n');
    }
    if !mesh.corners.is_empty() {
        let n = mesh.corners.len() as u64;
        buf.extend_from_slice(b"t corner ");
        push_u64(n, &mut buf);
        buf.push(b'/');
        push_u64(n, &mut buf);
        buf.extend_from_slice(b"/0");
        for corner in &mesh.corners {
            buf.push(b' ');
            push_u64(corner.vertex.into(), &mut buf);
        }
        for corner in &mesh.corners {
            buf.push(b' ');
            sharpness(corner.sharpness, &mut buf);
        }
        buf.push(b'\n');
    }
    if !mesh.holes.is_empty() {
        buf.extend_from_slice(b"t hole ");
        push_u64(mesh.holes.len() as u64, &mut buf);
        buf.extend_from_slice(b"/0/0");
        for &face in &mesh.holes {
            buf.push(b' ');
            push_u64(face.into(), &mut buf);
        }
        buf.push(b'\n');
    }
    out.write_all(&buf)?;
    out.flush()
}

/// [`write_mesh_obj_to`] into a `String`.
///
/// # Panics
///
/// If the mesh's face offsets or face-varying channel 0 are malformed
/// (which [`Mesh::validate`] reports).
pub fn mesh_to_obj_string(mesh: &Mesh, precision: Precision) -> String {
    let mut out = Vec::new();
    if let Err(e) = write_mesh_obj_to(&mut out, mesh, precision) {
        panic!("cannot write the mesh as OBJ: {e}");
    }
    String::from_utf8(out).expect("OBJ output is ASCII")
}

/// [`write_mesh_obj_to`] into a file, atomically as [`write_obj`] does.
pub fn write_mesh_obj(path: &Path, mesh: &Mesh, precision: Precision) -> Result<(), Error> {
    super::atomic::write_with(path, |file| write_mesh_obj_to(file, mesh, precision))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn g(x: f64, p: usize) -> String {
        let mut s = String::new();
        format_g(x, p, &mut s);
        s
    }

    #[test]
    fn format_g_matches_printf() {
        // Expectations from C/Python `'%.17g' % x` and `'%.9g' % x`.
        let cases: &[(f64, usize, &str)] = &[
            (0.1, 17, "0.10000000000000001"),
            (1.0, 17, "1"),
            (1e-5, 17, "1.0000000000000001e-05"),
            (123456.789, 17, "123456.789"),
            (1e20, 17, "1e+20"),
            (-0.0, 17, "-0"),
            (0.0, 17, "0"),
            (0.5, 17, "0.5"),
            (2.0 / 3.0, 17, "0.66666666666666663"),
            (1e16, 17, "10000000000000000"),
            (1e17, 17, "1e+17"),
            (100.0, 17, "100"),
            (1e-4, 17, "0.0001"),
            (9.999_999_999_999_999e-5, 17, "9.9999999999999991e-05"),
            (9.999_999_999_999_999e-5, 3, "0.0001"),
            (-1.5e-300, 17, "-1.5000000000000001e-300"),
            (5e-324, 17, "4.9406564584124654e-324"),
            (f64::MAX, 17, "1.7976931348623157e+308"),
            (123456789.0, 3, "1.23e+08"),
            (100.0, 1, "1e+02"),
            (0.125, 2, "0.12"),
            (2.5, 1, "2"),
            (0.3125, 3, "0.312"),
            (f64::INFINITY, 17, "inf"),
            (f64::NEG_INFINITY, 17, "-inf"),
            (f64::NAN, 17, "nan"),
            (0.1f32 as f64, 9, "0.100000001"),
            (1e-5f32 as f64, 9, "9.99999975e-06"),
            (123456789.0f32 as f64, 9, "123456792"),
            (f32::MAX as f64, 9, "3.40282347e+38"),
        ];
        for &(x, p, want) in cases {
            assert_eq!(g(x, p), want, "{x:e} with {p} digits");
        }
        assert_eq!(g(0.5, 0), "0.5", "0 digits behaves as 1");
    }

    /// The digits and exponent of `{:.(p-1)e}`, the standard library's
    /// correctly rounded formatting (the fallback of `exact_digits`).
    fn std_digits(x: f64, p: u32) -> (u64, i32) {
        let s = format!("{:.*e}", p as usize - 1, x);
        let (mantissa, exp) = s.split_once('e').unwrap();
        (
            mantissa.replace('.', "").parse().unwrap(),
            exp.parse().unwrap(),
        )
    }

    #[test]
    fn exact_digits_equal_the_standard_library() {
        // A xorshift stream of bit patterns: every exponent, and values in
        // the ranges coordinates take.
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let (mut fast, mut total) = (0, 0);
        let mut check = |x: f64, p: u32| {
            if !x.is_finite() || x <= 0.0 {
                return;
            }
            total += 1;
            if let Some(got) = exact_digits(x, p) {
                fast += 1;
                assert_eq!(got, std_digits(x, p), "{x:e} with {p} digits");
            }
        };
        for _ in 0..200_000 {
            let bits = next();
            let p = (bits % 19) as u32 + 1;
            check(f64::from_bits(bits >> 1), p);
            let unit = (bits >> 11) as f64 / (1u64 << 53) as f64;
            check(unit * 200.0, 17);
            check(unit * 1e-3, 17);
            check(f64::from(unit as f32 * 50.0), 9);
        }
        // Exact ties at every precision: (2n + 1) / 2 × 10^t, rounded to
        // even by both.
        for p in 1..=17u32 {
            for t in -3..=3 {
                for n in [1u64, 2, 12, 125, 9, 99_999, 1 << 40] {
                    let n = n % 10u64.pow(p).max(1);
                    let x = (2 * n + 1) as f64 / 2.0 * 10f64.powi(t);
                    check(x, p);
                    check(x.next_up(), p);
                    check(x.next_down(), p);
                }
            }
        }
        // Powers of ten and their neighbours (the exponent's estimate).
        for k in -30..=30 {
            let x = 10f64.powi(k);
            for p in [1, 9, 15, 16, 17] {
                check(x, p);
                check(x.next_up(), p);
                check(x.next_down(), p);
                check(x * 9.999_999_999_999_999, p);
            }
        }
        assert!(fast * 2 > total, "the fast path took {fast} of {total}");
    }

    #[test]
    fn format_g_round_trips_every_f64_it_writes() {
        let mut x = 1.0e-310_f64;
        while x < 1.0e300 {
            for v in [x, -x, x * 1.000_000_1, x / 3.0] {
                let s = g(v, 17);
                assert_eq!(s.parse::<f64>().unwrap().to_bits(), v.to_bits(), "{s}");
            }
            x *= 7.3;
        }
    }

    #[test]
    fn resolve_counts_relative_indices_from_the_end() {
        assert_eq!(resolve(1, 3, "vertex"), Ok(0));
        assert_eq!(resolve(3, 3, "vertex"), Ok(2));
        assert_eq!(resolve(-1, 3, "vertex"), Ok(2));
        assert_eq!(resolve(-3, 3, "vertex"), Ok(0));
        for bad in [0, 4, -4, i64::MIN, i64::MAX] {
            assert_eq!(
                resolve(bad, 3, "vertex"),
                Err(ObjErrorKind::IndexOutOfRange {
                    what: "vertex",
                    index: bad,
                    count: 3
                })
            );
        }
    }

    #[test]
    fn long_fields_are_shortened_in_messages() {
        let long = "x".repeat(100);
        assert_eq!(quote(&long).len(), QUOTE_LIMIT + 3);
        assert_eq!(quote("abc"), "abc");
    }

    #[test]
    fn quoted_fields_escape_control_characters() {
        assert!(matches!(
            quote("plain 'text' \"é\" \u{fffd}"),
            Cow::Borrowed(_)
        ));
        assert_eq!(quote("\u{1b}[2J"), "\\u{1b}[2J");
        assert_eq!(quote("a\tb\0\r\u{7f}"), "a\\tb\\0\\r\\u{7f}");
        assert_eq!(quote("back\\slash"), "back\\\\slash");
        assert_eq!(quote("\u{202e}rtl"), "\\u{202e}rtl");
        // The limit counts the field's characters, before escaping.
        let long = "\u{1b}".repeat(100);
        assert_eq!(
            quote(&long),
            format!("{}...", "\\u{1b}".repeat(QUOTE_LIMIT))
        );
        // Warnings quote the same way.
        let shape = parse_obj("\u{1b}]0;title\u{7} 1 2\n", Path::new("<memory>")).unwrap();
        assert_eq!(
            shape.warnings[0].message,
            "unknown statement '\\u{1b}]0;title\\u{7}'; the line is ignored"
        );
    }
}
