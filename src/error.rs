//! The crate's error types.

use crate::mesh::{MAX_VALENCE, MeshError};
use crate::options::Scheme;
use crate::real::Precision;
use std::fmt;
use std::path::PathBuf;
use thiserror::Error;

/// Any error of the `subdiv` crate. Every variant carries the values a
/// caller needs to act on it; none is a bare message.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum Error {
    /// The mesh is invalid.
    #[error("invalid mesh: {0}")]
    Mesh(#[from] MeshError),
    /// An OBJ file could not be read.
    #[error(transparent)]
    Obj(#[from] ObjError),
    /// A USD file could not be read, or one of its meshes is malformed
    /// (feature `usd`). Boxed, so that `Error` stays small.
    #[cfg(feature = "usd")]
    #[error(transparent)]
    Usd(Box<UsdError>),
    /// The mesh has no faces, so there is nothing to refine. Both engines
    /// refuse it, before OpenSubdiv is involved.
    #[error("the mesh has no faces: there is nothing to refine")]
    EmptyMesh,
    /// A refinement level refused before anything is allocated.
    #[error("refinement level {level} refused: {reason}")]
    Level {
        /// The requested level.
        level: u32,
        /// Why it is refused.
        reason: LevelRefusal,
    },
    /// A face that is not a triangle under a scheme that needs triangles (Loop).
    #[error("face {face} has {corners} vertices; the {scheme} scheme needs triangles")]
    NotTriangles {
        /// The scheme.
        scheme: Scheme,
        /// The base face.
        face: usize,
        /// Its number of vertices.
        corners: usize,
    },
    /// A smooth vertex whose faces and edges do not pair up (a face names it
    /// twice), which OpenSubdiv cannot refine.
    #[error(
        "vertex {vertex} of level {level} is smooth but its faces and edges do not pair up \
         (a face names it twice): OpenSubdiv cannot refine it"
    )]
    UnpairedSmoothVertex {
        /// The level (0 for the base mesh).
        level: u32,
        /// The vertex.
        vertex: usize,
    },
    /// A level that is not among those the call can use.
    #[error("level {level} is not refined (the levels here are {first}..={last})")]
    NoSuchLevel {
        /// The level asked for.
        level: u32,
        /// The first level the call accepts.
        first: u32,
        /// The last refined level.
        last: u32,
    },
    /// A vertex, edge or face index beyond a level's count.
    #[error("{element} {index} does not exist (level {level} has {count})")]
    NoSuchElement {
        /// What kind of element.
        element: Element,
        /// The index asked for.
        index: usize,
        /// The level.
        level: u32,
        /// How many such elements the level has.
        count: usize,
    },
    /// A ptex face the mesh does not have (patch tables and limit
    /// evaluation locate points by ptex face, `Far::PtexIndices`).
    #[error("ptex face {face} does not exist (the mesh has {count})")]
    NoSuchPtexFace {
        /// The ptex face asked for.
        face: usize,
        /// How many the mesh has.
        count: usize,
    },
    /// A patch a patch table does not have.
    #[error(
        "patch {patch} of array {array} does not exist (the table has {arrays} arrays, that one {patches} patches)"
    )]
    NoSuchPatch {
        /// The array asked for.
        array: usize,
        /// The patch asked for in it.
        patch: usize,
        /// How many arrays the table has.
        arrays: usize,
        /// How many patches the array has (0 when it does not exist).
        patches: usize,
    },
    /// A location no patch covers (a hole).
    #[error("no patch covers ptex face {face} at ({u}, {v}): the face is a hole")]
    NoPatchAt {
        /// The ptex face.
        face: u32,
        /// The location's u.
        u: f64,
        /// The location's v.
        v: f64,
    },
    /// A parametric location outside its face's unit square.
    #[error("location on ptex face {face}: {coordinate} = {value} is not in [0, 1]")]
    Location {
        /// The ptex face.
        face: u32,
        /// `"u"` or `"v"`.
        coordinate: &'static str,
        /// The value given.
        value: f64,
    },
    /// A location outside its base face's Bfr parameterization
    /// ([`crate::bfr::Parameterization::contains`]).
    #[error("(u, v) = ({u}, {v}) is outside base face {face}'s parameterization ({domain})")]
    OffFace {
        /// The base face.
        face: usize,
        /// The location's u.
        u: f64,
        /// The location's v.
        v: f64,
        /// The domain, in words.
        domain: &'static str,
    },
    /// A face-varying channel the mesh does not have.
    #[error("face-varying channel {channel} does not exist (the mesh has {count})")]
    NoSuchChannel {
        /// The channel asked for.
        channel: usize,
        /// How many the mesh has.
        count: usize,
    },
    /// A primvar width of zero.
    #[error("primvar width must be at least 1")]
    ZeroWidth,
    /// A point descriptor whose stride is smaller than its size
    /// ([`crate::bfr::PointDescriptor`]): its points would overlap.
    #[error("point stride {stride} is smaller than the point size {size}")]
    Stride {
        /// Values per point.
        size: usize,
        /// Values from one point to the next.
        stride: usize,
    },
    /// A buffer whose length does not fit the call.
    #[error("{buffer} buffer has {got} values, expected {expected}")]
    BufferLength {
        /// Which buffer.
        buffer: Buffer,
        /// The length the call needs.
        expected: usize,
        /// The length given.
        got: usize,
    },
    /// A buffer whose length is not a multiple of the element width.
    #[error("{buffer} buffer has {len} values, not a whole number of {width}-wide elements")]
    NotWholeElements {
        /// Which buffer.
        buffer: Buffer,
        /// The length given.
        len: usize,
        /// The element width.
        width: usize,
    },
    /// Something OpenSubdiv does that the native engine does not do yet.
    #[error("not supported by the native engine yet: {0}")]
    NotYetSupported(&'static str),
    /// Patch-table options this refinement cannot be given (legacy Gregory
    /// end caps under another scheme than Catmull-Clark, or on a last level
    /// they cannot describe), with the reason.
    #[error("no patch table with these options: {reason}")]
    PatchOptions {
        /// Why, naming the level and element concerned.
        reason: String,
    },
    /// A face Bfr cannot parameterize, or a sub-face query of a face without
    /// sub-faces ([`crate::bfr::Parameterization`]).
    #[error("no parameterization of a {face_size}-sided face: {reason}")]
    Parameterization {
        /// The face's number of vertices.
        face_size: usize,
        /// Why, naming the scheme, vertex or sub-face concerned.
        reason: String,
    },
    /// Tessellation rates or options OpenSubdiv's `Bfr::Tessellation` holds
    /// invalid, or a coordinate-index map that does not fit the pattern
    /// ([`crate::bfr::Tessellation`]).
    #[error("tessellation refused: {reason}")]
    Tessellation {
        /// Why, naming the rate or index concerned.
        reason: String,
    },
    /// Limit evaluation without full topology in the last level.
    #[error(
        "limit evaluation needs full topology in the last level \
         (refine with full_topology_in_last_level, as OpenSubdiv requires)"
    )]
    NeedsFullTopology,
    /// A stencil names a base vertex beyond the data given.
    #[error("the stencils refer to base vertex {index}, but only {count} were given")]
    StencilOutOfRange {
        /// The largest base vertex the stencils name.
        index: usize,
        /// How many base vertices were given.
        count: usize,
    },
    /// Stencil options refused before anything is built: a combination
    /// OpenSubdiv 3.5 cannot build safely ([`crate::stencil::StencilOptions`]).
    #[error("stencil options refused: {reason}")]
    StencilOptions {
        /// Why.
        reason: &'static str,
    },
    /// A stencil table whose parts do not fit together.
    #[error("malformed stencil table: {0}")]
    MalformedStencils(StencilFault),
    /// A count beyond what a table or OpenSubdiv's indices can hold.
    #[error("{count} {what} do not fit {bits}-bit indices")]
    TooLarge {
        /// What is counted.
        what: &'static str,
        /// How many there are.
        count: usize,
        /// The width of the indices.
        bits: u32,
    },
    /// The OpenSubdiv engine was asked for, but this build has no bridge
    /// (the feature `osd` is off).
    #[error("the osd engine is not in this build (rebuild with the default feature `osd`)")]
    OsdUnavailable,
    /// OpenSubdiv (through the bridge) refused or failed.
    #[error(transparent)]
    Osd(#[from] OsdError),
    /// A value of the mesh that the requested precision cannot hold (beyond
    /// `f32`'s range, about 3.4e38): refining it in `f32` would give
    /// infinities.
    #[error(
        "{what} {index} has the value {value:e}, beyond the range of {precision}; refine in f64"
    )]
    BeyondPrecision {
        /// What holds the value: "vertex" or "face-varying value".
        what: &'static str,
        /// Its index.
        index: usize,
        /// The value.
        value: f64,
        /// The precision asked for.
        precision: Precision,
    },
    /// A large buffer could not be allocated (the machine's memory, `ulimit
    /// -v` or a cgroup limit): nothing was aborted, the process goes on.
    #[error(
        "out of memory{}: {bytes} bytes could not be allocated",
        level.map_or(String::new(), |l| format!(" refining level {l}"))
    )]
    OutOfMemory {
        /// The size of the allocation that failed.
        bytes: usize,
        /// The level being refined or interpolated, when known.
        level: Option<u32>,
    },
    /// Reading or writing a file failed.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// A refinement asked of a refiner that was already refined, which
    /// OpenSubdiv's adaptive refinement refuses: build a new refiner.
    #[error(
        "the refiner is already refined (to level {level}): adaptive refinement needs an unrefined refiner"
    )]
    AlreadyRefined {
        /// The refiner's deepest level.
        level: u32,
    },
    /// Relations asked of a level that does not store them: a uniform last
    /// level refined without full topology keeps its face-vertices only.
    #[error(
        "level {level} was refined without full topology: it keeps no edge or vertex relations \
         (refine with full_topology_in_last_level)"
    )]
    NoFullTopology {
        /// The level.
        level: u32,
    },
}

/// Why a refinement level is refused ([`Error::Level`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum LevelRefusal {
    /// Deeper than [`MAX_LEVEL`](crate::MAX_LEVEL).
    TooDeep {
        /// The deepest supported level.
        max: u32,
    },
    /// More face corners than 32-bit indices address.
    TooManyCorners {
        /// The estimated number of face corners at the level.
        corners: f64,
    },
    /// More memory than this machine has available.
    OutOfMemory {
        /// The estimated bytes needed.
        needed: f64,
        /// The bytes available.
        available: u64,
    },
}

impl fmt::Display for LevelRefusal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            LevelRefusal::TooDeep { max } => write!(f, "the deepest supported level is {max}"),
            LevelRefusal::TooManyCorners { corners } => write!(
                f,
                "the level has about {corners:.3e} face corners, more than 32-bit indices address"
            ),
            LevelRefusal::OutOfMemory { needed, available } => write!(
                f,
                "the level needs about {}, more than the {} available",
                Size(needed),
                Size(available as f64)
            ),
        }
    }
}

/// Bytes for a message: in GiB from 1 GiB, else in MiB (or KiB), so that
/// a small amount never reads "0.0 GiB".
struct Size(f64);

impl fmt::Display for Size {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (bytes, mut unit) = (self.0, 1024.0 * 1024.0 * 1024.0);
        for name in ["GiB", "MiB"] {
            if bytes >= unit {
                return write!(f, "{:.1} {name}", bytes / unit);
            }
            unit /= 1024.0;
        }
        write!(f, "{:.1} KiB", bytes / unit)
    }
}

/// A kind of topological element.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Element {
    /// A vertex.
    Vertex,
    /// An edge.
    Edge,
    /// A face.
    Face,
}

impl fmt::Display for Element {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Element::Vertex => "vertex",
            Element::Edge => "edge",
            Element::Face => "face",
        })
    }
}

/// The role of a buffer passed to a call ([`Error::BufferLength`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Buffer {
    /// Primvar values of the level interpolated from.
    Source,
    /// Primvar values of the level interpolated to.
    Destination,
    /// Face-varying values of the level interpolated from.
    FaceVaryingSource,
    /// Values at the base vertices (stencil or whole-refinement input).
    Base,
    /// Output values (one per stencil or refined vertex).
    Output,
}

impl fmt::Display for Buffer {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Buffer::Source => "source primvar",
            Buffer::Destination => "destination primvar",
            Buffer::FaceVaryingSource => "source face-varying",
            Buffer::Base => "base data",
            Buffer::Output => "output",
        })
    }
}

/// What is inconsistent in a stencil table ([`Error::MalformedStencils`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum StencilFault {
    /// A row's offset and size reach past the indices or weights.
    #[error("row {row} lies outside the table's indices and weights")]
    RowOutOfRange {
        /// The row.
        row: usize,
    },
    /// As many rows' sizes as offsets are needed.
    #[error("{sizes} sizes but {offsets} offsets")]
    SizesAndOffsets {
        /// Number of sizes.
        sizes: usize,
        /// Number of offsets.
        offsets: usize,
    },
    /// Indices and weights of different lengths.
    #[error("{indices} indices but {weights} weights")]
    IndicesAndWeights {
        /// Number of indices.
        indices: usize,
        /// Number of weights.
        weights: usize,
    },
    /// Offsets that do not start at 0.
    #[error("offsets must start at 0")]
    FirstOffset,
    /// Offsets that decrease.
    #[error("offsets must not decrease (offset {index})")]
    DecreasingOffsets {
        /// The first offset smaller than the one before.
        index: usize,
    },
    /// A last offset that is not the number of terms.
    #[error("the last offset must be the number of terms")]
    LastOffset,
}

/// OpenSubdiv (or the bridge in front of it) refused an input or failed.
/// The message is OpenSubdiv's or the bridge's own text.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("OpenSubdiv: {message}")]
pub struct OsdError {
    /// What happened.
    pub kind: OsdErrorKind,
    /// The bridge's or OpenSubdiv's message.
    pub message: String,
}

/// What kind of failure an [`OsdError`] is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum OsdErrorKind {
    /// The bridge refused an input before OpenSubdiv saw it (an index out of
    /// range, a count that does not fit).
    Refused,
    /// OpenSubdiv reported an error, or threw.
    Failed,
    /// OpenSubdiv 3.5 would read or write out of bounds, or overflow an
    /// integer, on this input (a known fault of the library:
    /// `PrimvarRefiner::Limit`'s masks at high-valence non-manifold vertices,
    /// the Catmull-Clark vertex rule beyond 46,340 faces at a vertex), so the
    /// bridge refused it. The native engine handles such inputs.
    Unsafe,
    /// The bridge and OpenSubdiv disagree on a size or returned no object
    /// (a defect, not an input problem).
    Internal,
}

/// Shorthand for `Result<T, subdiv::Error>`.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// An error reading an OBJ file, with the file and the 1-based line.
///
/// Displayed as `FILE:LINE: what`, or `FILE: what` when no line is concerned
/// (line 0: the file cannot be read, for instance).
#[derive(Debug, Clone, PartialEq, Error)]
pub struct ObjError {
    /// The file name (`<memory>` for in-memory input).
    pub file: PathBuf,
    /// 1-based line number; 0 when the problem is not tied to one line.
    pub line: usize,
    /// What is wrong.
    pub kind: ObjErrorKind,
}

impl fmt::Display for ObjError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            0 => write!(f, "{}: {}", self.file.display(), self.kind),
            line => write!(f, "{}:{line}: {}", self.file.display(), self.kind),
        }
    }
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

/// An error reading a USD file ([`crate::io::usd`]): the file, the prim and
/// the attribute concerned, and what is wrong.
///
/// Displayed as `FILE: PRIM.ATTRIBUTE: what` (the attribute's USD path), or
/// `FILE: PRIM: what` when no attribute is concerned, or `FILE: what` when
/// no prim is (the file cannot be opened or parsed, a prim pattern is bad).
#[cfg(feature = "usd")]
#[derive(Debug, Clone, PartialEq, Error)]
pub struct UsdError {
    /// The file named by the caller.
    pub file: PathBuf,
    /// The prim's path (`/World/Body`); empty when no prim is concerned.
    pub prim: String,
    /// The attribute's name on the prim (`creaseIndices`,
    /// `primvars:st:indices`); empty when no attribute is concerned.
    pub attribute: String,
    /// What is wrong.
    pub kind: UsdErrorKind,
}

#[cfg(feature = "usd")]
impl fmt::Display for UsdError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: ", self.file.display())?;
        match (self.prim.is_empty(), self.attribute.is_empty()) {
            (true, true) => {}
            (false, true) => write!(f, "{}: ", self.prim)?,
            (true, false) => write!(f, "{}: ", self.attribute)?,
            (false, false) => write!(f, "{}.{}: ", self.prim, self.attribute)?,
        }
        write!(f, "{}", self.kind)
    }
}

#[cfg(feature = "usd")]
impl From<UsdError> for Error {
    fn from(e: UsdError) -> Error {
        Error::Usd(Box::new(e))
    }
}

/// What is wrong in a USD file ([`UsdError`]).
#[cfg(feature = "usd")]
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum UsdErrorKind {
    /// The file cannot be opened, parsed or composed; the message is the
    /// USD library's.
    #[error("cannot read the stage: {0}")]
    Open(String),
    /// A prim pattern ([`UsdReadOptions::prims`](crate::io::usd::UsdReadOptions::prims))
    /// that cannot match a prim path.
    #[error("prim pattern {pattern:?} {reason}")]
    Pattern {
        /// The pattern.
        pattern: String,
        /// Why it is refused.
        reason: &'static str,
    },
    /// An attribute the mesh needs has no value (not authored, blocked, or
    /// only time samples read at the default time).
    #[error(
        "has no value{}, but the mesh has {faces} faces",
        if *time_samples { " at the default time (it has time samples: read at a time)" } else { "" }
    )]
    Missing {
        /// The mesh's number of faces.
        faces: usize,
        /// Whether it has time samples (and was read at the default time).
        time_samples: bool,
    },
    /// A value of another type than the attribute can hold.
    #[error("holds a value of type {found}, expected {expected}")]
    WrongType {
        /// The types the reader accepts.
        expected: &'static str,
        /// The type found (the USD library's name of the value).
        found: String,
    },
    /// A token that is not one of the attribute's allowed tokens.
    #[error("unknown token {token:?} (expected one of {allowed})")]
    UnknownToken {
        /// The token found.
        token: String,
        /// The allowed tokens, in words.
        allowed: &'static str,
    },
    /// An index that names no element.
    #[error("element {position} is {index}, out of range: there are {count} {of}")]
    IndexOutOfRange {
        /// The element's position in the array.
        position: usize,
        /// The index it holds.
        index: i64,
        /// How many elements it can name.
        count: usize,
        /// What it names (`points`, `faces`, `values`).
        of: &'static str,
    },
    /// A count below zero.
    #[error("element {position} is {count}: a count cannot be negative")]
    NegativeCount {
        /// The element's position in the array.
        position: usize,
        /// The count it holds.
        count: i64,
    },
    /// `faceVertexCounts` does not add up to the length of `faceVertexIndices`.
    #[error("the face sizes add up to {sum}, but faceVertexIndices has {indices} elements")]
    FaceVertexCounts {
        /// The sum of the face sizes.
        sum: u64,
        /// The length of `faceVertexIndices`.
        indices: usize,
    },
    /// `creaseLengths` does not add up to the length of `creaseIndices`.
    #[error("the crease lengths add up to {sum}, but creaseIndices has {indices} elements")]
    CreaseLengths {
        /// The sum of the crease lengths.
        sum: u64,
        /// The length of `creaseIndices`.
        indices: usize,
    },
    /// A crease of fewer than two vertices (no edge).
    #[error("crease {crease} has length {length}; a crease needs at least 2 vertices")]
    CreaseTooShort {
        /// The crease.
        crease: usize,
        /// Its length.
        length: i64,
    },
    /// `creaseSharpnesses` has neither one value per crease nor one per
    /// crease edge.
    #[error(
        "has {found} values; expected {creases} (one per crease) or {edges} (one per crease edge)"
    )]
    CreaseSharpnessCount {
        /// The number of sharpness values.
        found: usize,
        /// The number of creases.
        creases: usize,
        /// The number of crease edges.
        edges: usize,
    },
    /// `cornerSharpnesses` has not one value per element of `cornerIndices`.
    #[error("has {found} values for {corners} corners")]
    CornerSharpnessCount {
        /// The number of sharpness values.
        found: usize,
        /// The number of corner indices.
        corners: usize,
    },
    /// A primvar (or its indices) with the wrong number of elements for its
    /// interpolation.
    #[error("has {found} elements; {interpolation} interpolation needs {expected}")]
    PrimvarCount {
        /// The primvar's interpolation token.
        interpolation: &'static str,
        /// The number of elements found.
        found: usize,
        /// The number expected.
        expected: usize,
    },
    /// A primvar's `elementSize` below 1, or that does not divide its values.
    #[error("elementSize {element_size} does not fit its {values} values")]
    ElementSize {
        /// The `elementSize` metadata.
        element_size: i64,
        /// The number of values (array elements).
        values: usize,
    },
    /// More elements than 32-bit indices address.
    #[error("has {count} {what}, more than 32-bit indices address")]
    TooLarge {
        /// What is counted.
        what: &'static str,
        /// How many there are.
        count: usize,
    },
    /// The mesh the attributes describe is invalid ([`Mesh::validate`](crate::Mesh::validate)).
    #[error("invalid mesh: {0}")]
    Mesh(MeshError),
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A refusal's sizes read in the unit that shows them: never "0.0 GiB".
    #[test]
    fn refusals_name_sizes_in_a_readable_unit() {
        let refusal = |needed: f64, available: u64| {
            LevelRefusal::OutOfMemory { needed, available }.to_string()
        };
        assert_eq!(
            refusal(150.0 * (1u64 << 30) as f64, 3 << 29),
            "the level needs about 150.0 GiB, more than the 1.5 GiB available"
        );
        assert_eq!(
            refusal((200 << 20) as f64, 90 << 20),
            "the level needs about 200.0 MiB, more than the 90.0 MiB available"
        );
        assert_eq!(
            refusal(1536.0, 0),
            "the level needs about 1.5 KiB, more than the 0.0 KiB available"
        );
    }
}
