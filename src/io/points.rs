//! Points files: one point per line, 2 or 3 numbers, `#` starts a comment —
//! what `subdiv curve` reads and writes.

use crate::classic::curve::{CurveScheme, Point};
use crate::io::number::format_g;
use crate::io::obj::escape;
use glam::{DVec2, DVec3};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Points read from a text file: all 2-D or all 3-D.
#[derive(Debug, Clone, PartialEq)]
pub enum Points {
    /// Two numbers per line.
    Planar(Vec<DVec2>),
    /// Three numbers per line.
    Spatial(Vec<DVec3>),
}

impl Points {
    /// The number of points.
    pub fn len(&self) -> usize {
        match self {
            Points::Planar(p) => p.len(),
            Points::Spatial(p) => p.len(),
        }
    }

    /// Whether there are no points.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// A points file: the points and where they are.
#[derive(Debug, Clone, PartialEq)]
pub struct PointsFile {
    /// The file name (`<memory>` for in-memory text).
    pub file: PathBuf,
    /// The points.
    pub points: Points,
    /// The 1-based line of each point.
    pub lines: Vec<usize>,
    /// The number of lines in the file.
    pub line_count: usize,
}

impl PointsFile {
    /// Checks that there are enough points for `scheme` on an open or closed
    /// polygon; the error names the last line of the file.
    pub fn require(&self, scheme: &CurveScheme, closed: bool) -> Result<(), PointsError> {
        let needed = scheme.min_points(closed);
        let got = self.points.len();
        if got < needed {
            return Err(PointsError {
                file: self.file.clone(),
                line: self.line_count.max(1),
                kind: PointsErrorKind::TooFewPoints {
                    got,
                    needed,
                    scheme: scheme.name(),
                    closed,
                },
            });
        }
        Ok(())
    }
}

/// An error in a points file, with the file and the 1-based line
/// (`FILE:LINE: what`, or `FILE: what` when no line is concerned).
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{}{}: {kind}", file.display(), if *.line > 0 { format!(":{line}") } else { String::new() })]
pub struct PointsError {
    /// The file name.
    pub file: PathBuf,
    /// The 1-based line (0 when the file could not be read).
    pub line: usize,
    /// What is wrong.
    pub kind: PointsErrorKind,
}

/// What is wrong in a points file.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum PointsErrorKind {
    /// A line with 1 or more than 3 numbers.
    #[error("a point needs 2 or 3 numbers, this line has {0}")]
    WrongCount(usize),
    /// A line whose dimension differs from the first point's.
    #[error(
        "a {found}-D point after {expected}-D points (the first point is on line {first_line})"
    )]
    MixedDimensions {
        /// The dimension of the first point.
        expected: usize,
        /// This line's dimension.
        found: usize,
        /// The line of the first point.
        first_line: usize,
    },
    /// A field that is not a number (as written; the message escapes its
    /// control characters).
    #[error("'{}' is not a number", escape(.0))]
    NotANumber(String),
    /// A number that is NaN or infinite.
    #[error("'{}' is not a finite number", escape(.0))]
    NonFinite(String),
    /// The file ends with fewer points than the scheme needs.
    #[error("the input ends after {got} point{}; {scheme} on {} polygon needs at least {needed}", if *.got == 1 { "" } else { "s" }, if *.closed { "a closed" } else { "an open" })]
    TooFewPoints {
        /// The number of points read.
        got: usize,
        /// The fewest accepted.
        needed: usize,
        /// The scheme's name.
        scheme: &'static str,
        /// Whether the polygon is closed.
        closed: bool,
    },
    /// Bytes that are not UTF-8, outside a comment ([`read_points`]).
    #[error("invalid UTF-8 at column {column} (byte 0x{byte:02X}): a points file must be text")]
    InvalidUtf8 {
        /// The 1-based byte offset of the invalid sequence in its line.
        column: usize,
        /// Its first byte.
        byte: u8,
    },
    /// The file could not be read.
    #[error("cannot read: {0}")]
    Io(String),
}

/// Parses points, one per line: 2 or 3 numbers separated by white space; `#`
/// starts a comment; blank lines are skipped. Every point must have the
/// dimension of the first.
///
/// ```
/// use std::path::Path;
/// use subdiv::io::points::{parse_points, Points};
/// let f = parse_points("# a triangle\n0 0\n1 0  # comment\n\n0 1\n", Path::new("t.txt"))?;
/// assert_eq!(f.points.len(), 3);
/// assert_eq!(f.lines, [2, 3, 5]);
/// assert!(matches!(f.points, Points::Planar(_)));
/// let e = parse_points("0 0\n1 0 0\n", Path::new("t.txt")).unwrap_err();
/// assert_eq!(e.to_string(), "t.txt:2: a 3-D point after 2-D points (the first point is on line 1)");
/// # Ok::<(), subdiv::io::points::PointsError>(())
/// ```
pub fn parse_points(text: &str, file: &Path) -> Result<PointsFile, PointsError> {
    // A UTF-8 byte-order mark, as some editors write, is not a point.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let error = |line: usize, kind| PointsError {
        file: file.to_path_buf(),
        line,
        kind,
    };
    let mut planar = Vec::new();
    let mut spatial = Vec::new();
    let mut lines = Vec::new();
    let mut first: Option<(usize, usize)> = None; // (dimension, line)
    let mut line_count = 0;
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        line_count = line;
        let content = raw.split('#').next().unwrap_or("");
        let mut coords = Vec::with_capacity(3);
        for field in content.split_whitespace() {
            let x: f64 = field
                .parse()
                .map_err(|_| error(line, PointsErrorKind::NotANumber(field.to_string())))?;
            if !x.is_finite() {
                return Err(error(line, PointsErrorKind::NonFinite(field.to_string())));
            }
            coords.push(x);
        }
        match coords.len() {
            0 => continue,
            2 | 3 => {}
            k => return Err(error(line, PointsErrorKind::WrongCount(k))),
        }
        let dim = coords.len();
        match first {
            None => first = Some((dim, line)),
            Some((expected, first_line)) if expected != dim => {
                return Err(error(
                    line,
                    PointsErrorKind::MixedDimensions {
                        expected,
                        found: dim,
                        first_line,
                    },
                ));
            }
            Some(_) => {}
        }
        if dim == 2 {
            planar.push(DVec2::new(coords[0], coords[1]));
        } else {
            spatial.push(DVec3::new(coords[0], coords[1], coords[2]));
        }
        lines.push(line);
    }
    let points = match first {
        Some((3, _)) => Points::Spatial(spatial),
        _ => Points::Planar(planar),
    };
    Ok(PointsFile {
        file: file.to_path_buf(),
        points,
        lines,
        line_count,
    })
}

/// Reads a points file ([`parse_points`]).
///
/// Failing to read the file is a [`PointsErrorKind::Io`] error on line 0.
/// The text must be UTF-8 outside comments: the first invalid UTF-8 sequence
/// before a `#` is a [`PointsErrorKind::InvalidUtf8`] error naming its line
/// and column (bytes in comments are ignored, as everything after `#` is).
pub fn read_points(path: &Path) -> Result<PointsFile, PointsError> {
    let error = |line: usize, kind| PointsError {
        file: path.to_path_buf(),
        line,
        kind,
    };
    let bytes = std::fs::read(path).map_err(|e| error(0, PointsErrorKind::Io(e.to_string())))?;
    // Lines as `str::lines` counts them; '#' and '\n' never occur inside a
    // multi-byte UTF-8 sequence, so splitting the bytes at them is safe.
    for (index, line) in bytes.split(|&b| b == b'\n').enumerate() {
        let content = line.split(|&b| b == b'#').next().unwrap_or_default();
        if let Err(e) = std::str::from_utf8(content) {
            let at = e.valid_up_to();
            return Err(error(
                index + 1,
                PointsErrorKind::InvalidUtf8 {
                    column: at + 1,
                    byte: content[at],
                },
            ));
        }
    }
    parse_points(&String::from_utf8_lossy(&bytes), path)
}

/// The points as text, one per line, every coordinate with 17 significant
/// digits (C's `%.17g`, which reads back exactly).
///
/// ```
/// use glam::DVec2;
/// assert_eq!(subdiv::io::points::format_points(&[DVec2::new(0.1, -2.0)]), "0.10000000000000001 -2\n");
/// ```
pub fn format_points<P: Point>(points: &[P]) -> String {
    let mut out = String::with_capacity(points.len() * 20 * P::DIM);
    for p in points {
        for (i, x) in p.coords().into_iter().enumerate() {
            if i > 0 {
                out.push(' ');
            }
            format_g(x, 17, &mut out);
        }
        out.push('\n');
    }
    out
}

/// Writes [`format_points`] to `path` atomically (a temporary file in the
/// same directory, renamed at the end).
pub fn write_points<P: Point>(path: &Path, points: &[P]) -> Result<(), crate::Error> {
    crate::io::atomic::write_bytes(path, format_points(points).as_bytes())
}
