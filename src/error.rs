//! The crate's error types.

use crate::mesh::{MAX_VALENCE, MeshError};
use std::path::PathBuf;
use thiserror::Error;

/// Any error of the `subdiv` crate.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum Error {
    /// The mesh is invalid.
    #[error("invalid mesh: {0}")]
    Mesh(#[from] MeshError),
    /// An OBJ file could not be read.
    #[error(transparent)]
    Obj(#[from] ObjError),
    /// The mesh has no faces, so there is nothing to refine. Both engines
    /// refuse it, before OpenSubdiv is involved.
    #[error("the mesh has no faces: there is nothing to refine")]
    EmptyMesh,
    /// OpenSubdiv (through the bridge) refused or failed.
    #[error("OpenSubdiv: {0}")]
    Osd(String),
    /// A refinement level outside `0..=MAX_LEVEL`, or one whose output would not fit.
    #[error("refinement level {level} refused: {reason}")]
    Level {
        /// The requested level.
        level: u32,
        /// Why it is refused.
        reason: String,
    },
    /// A call whose arguments do not fit the refiner (wrong buffer length, missing channel...).
    #[error("invalid argument: {0}")]
    InvalidArgument(String),
    /// The requested feature is not available in this build or engine.
    #[error("not available: {0}")]
    Unavailable(String),
    /// Reading or writing a file failed.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
}

/// Shorthand for `Result<T, subdiv::Error>`.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// An error reading an OBJ file, with the file and the 1-based line.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{}:{line}: {kind}", file.display())]
pub struct ObjError {
    /// The file name (`<memory>` for in-memory input).
    pub file: PathBuf,
    /// 1-based line number; 0 when the problem is not tied to one line.
    pub line: usize,
    /// What is wrong.
    pub kind: ObjErrorKind,
}

/// What is wrong in an OBJ file.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum ObjErrorKind {
    /// A statement that cannot be parsed (bad number, missing field...).
    #[error("syntax error: {0}")]
    Syntax(String),
    /// A face refers to an element that does not exist.
    #[error("{what} index {index} is out of range ({count} defined so far)")]
    IndexOutOfRange {
        /// "vertex" or "texture coordinate".
        what: &'static str,
        /// The index as written in the file (1-based or negative).
        index: i64,
        /// How many such elements were defined at that point.
        count: usize,
    },
    /// A face with fewer than three corners.
    #[error("face has {0} corners; a face needs at least 3")]
    FaceTooSmall(usize),
    /// A face with more corners than OpenSubdiv supports ([`MAX_VALENCE`]).
    #[error("face has {0} corners; at most {MAX_VALENCE} are supported")]
    FaceTooLarge(usize),
    /// Some face corners have texture coordinates and others do not.
    #[error("texture coordinates must be given for every corner of every face or for none: {0}")]
    InconsistentTexcoords(String),
    /// A coordinate is NaN or infinite.
    #[error("non-finite coordinate {0}")]
    NonFinite(String),
    /// A malformed OpenSubdiv `t` tag.
    #[error("bad '{tag}' tag: {message}")]
    BadTag {
        /// The tag name.
        tag: String,
        /// What is wrong with it.
        message: String,
    },
    /// A tag names a vertex or face that does not exist.
    #[error("'{tag}' tag names {what} {index}, which does not exist ({count} in the file)")]
    TagOutOfRange {
        /// The tag name.
        tag: String,
        /// "vertex" or "face".
        what: &'static str,
        /// The index in the tag.
        index: i64,
        /// How many exist.
        count: usize,
    },
    /// The file could not be read.
    #[error("cannot read: {0}")]
    Io(String),
}
