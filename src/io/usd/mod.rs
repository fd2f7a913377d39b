//! USD stages in, refined meshes out (feature `usd`).
//!
//! [`read_usd`] opens a `.usda`, `.usdc` or `.usdz` file through the
//! pure-Rust `openusd` crate, composes the stage (sublayers, references,
//! payloads, inherits, variants, as that crate resolves them) and turns every
//! selected `Mesh` prim into a [`Mesh`] with its [`Options`], mapping each
//! attribute the way USD's own OpenSubdiv adapter (`pxOsd`, used by Storm)
//! does:
//!
//! | USD attribute | here |
//! | --- | --- |
//! | `points`, `faceVertexCounts`, `faceVertexIndices` | [`Mesh::positions`], [`Mesh::face_offsets`], [`Mesh::face_vertices`] |
//! | `orientation` (`rightHanded`, `leftHanded`) | [`Mesh::left_handed`] |
//! | `subdivisionScheme` (`catmullClark`, `loop`, `bilinear`; fallback `catmullClark`) | [`Options::scheme`]; `none`: not read, listed in [`UsdStage::skipped`] |
//! | `interpolateBoundary` (`none`, `edgeOnly`, `edgeAndCorner`; fallback `edgeAndCorner`) | [`Options::boundary`] (`edgeAndCorner` for bilinear meshes, whatever is authored) |
//! | `faceVaryingLinearInterpolation` (`none`, `cornersOnly`, `cornersPlus1`, `cornersPlus2`, `boundaries`, `all`; fallback `cornersPlus1`) | [`Options::fvar`] |
//! | `triangleSubdivisionRule` (`catmullClark`, `smooth`; fallback `catmullClark`) | [`Options::triangles`] |
//! | (none) | [`Options::creasing`] is uniform |
//! | `creaseIndices`, `creaseLengths`, `creaseSharpnesses` | [`Mesh::creases`], one per crease edge |
//! | `cornerIndices`, `cornerSharpnesses` | [`Mesh::corners`] |
//! | `holeIndices` | [`Mesh::holes`] |
//! | face-varying primvars | [`Mesh::fvar_channels`], named in [`UsdMesh::fvar_names`] |
//! | vertex and varying primvars | [`UsdMesh::primvars`] |
//!
//! These fallbacks are `UsdGeomMesh`'s, not the OBJ shape files' (edge-only
//! boundaries, face-varying `all`). Text layers may use the older type names
//! Pixar's parser still accepts (`PointFloat[]`, `PointIndex[]`, `Vec3f[]`,
//! `ColorFloat[]` and the rest of Sdf's legacy types): they are read as
//! their current names (`point3f[]`, `int[]`, `float3[]`, `color3f[]`).
//!
//! [`write_usda`] writes refined meshes back as a `.usda` layer with the same
//! prim paths, `subdivisionScheme = "none"` and their face-varying primvars.
//!
//! ```
//! use subdiv::io::usd::{read_usd, write_usda, UsdMeshOut, UsdReadOptions};
//! use subdiv::{Engine, Precision, Request};
//! # let dir = tempfile::tempdir()?;
//! let input = dir.path().join("quad.usda");
//! std::fs::write(&input, r#"#usda 1.0
//! def Mesh "Quad" {
//!     point3f[] points = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
//!     int[] faceVertexCounts = [4]
//!     int[] faceVertexIndices = [0, 1, 2, 3]
//! }
//! "#)?;
//! let stage = read_usd(&input, &UsdReadOptions::default())?;
//! let quad = &stage.meshes[0];
//! assert_eq!(quad.path, "/Quad");
//! let refined = Engine::Native.refine(&quad.mesh, &quad.options, Request::new(2))?;
//! let out = UsdMeshOut::from_refinement(&quad.path, &refined, &quad.fvar_names);
//! write_usda(&dir.path().join("refined.usda"), &[out], Precision::F64)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod glob;
mod legacy;
mod mesh;
mod primvars;
mod read;
mod resolver;
mod text;
mod time;
mod values;
mod write;

pub use read::read_usd;
pub use write::{UsdFVarOut, UsdMeshOut, UsdPrimvarOut, write_usda, write_usda_to};

use crate::mesh::Mesh;
use crate::options::Options;
use std::fmt;

/// What [`read_usd`] reads, and how.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct UsdReadOptions {
    /// The time code the attributes are read at, as USD resolves values:
    /// `None` reads each attribute's default value (an attribute with time
    /// samples but no default value then has none, with a warning); `Some(t)`
    /// reads the sample at `t`, the first or last sample before or after
    /// them all, and between two samples interpolates floating-point arrays
    /// linearly, bit for bit as USD's `GfLerp` does (points, `float` and
    /// `double` primvars; half-precision ones are held), holding the earlier
    /// sample of everything else (topology, creases, tokens).
    pub time: Option<f64>,
    /// Drop a malformed crease or corner, with a [`UsdWarning`], instead of
    /// failing — as USD's renderer does (`pxOsd` skips crease edges and
    /// corners whose vertex does not exist, and every crease or every corner
    /// when their sharpnesses do not match them in number). Every other
    /// malformed attribute is still an error.
    pub lenient: bool,
    /// Which meshes to read: prim path patterns, any of which selects a
    /// prim; empty reads every mesh. A pattern starts with `/`; `*` matches
    /// any run of characters within one path segment, `**` any run across
    /// segments (`/**/Body` matches `/Body` and `/A/B/Body`), `?` one
    /// character within a segment.
    pub prims: Vec<String>,
}

/// The subdivision meshes of a USD stage ([`read_usd`]).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct UsdStage {
    /// The selected `Mesh` prims that are subdivided, in traversal order
    /// (depth first, children in the stage's order).
    pub meshes: Vec<UsdMesh>,
    /// The selected `Mesh` prims that are not read, and why
    /// (`subdivisionScheme = "none"`, no faces).
    pub skipped: Vec<UsdSkipped>,
    /// What was questionable but accepted: creases and corners dropped in
    /// lenient mode, crease edges that do not exist, attributes with time
    /// samples but no default value read at the default time, primvars
    /// ignored, composition errors (a
    /// reference that does not resolve), prim patterns that matched nothing.
    pub warnings: Vec<UsdWarning>,
}

/// One subdivision mesh of a USD stage.
#[derive(Debug, Clone, PartialEq)]
pub struct UsdMesh {
    /// The prim's path (`/World/Body`).
    pub path: String,
    /// The mesh, validated ([`Mesh::validate`]); `left_handed` when the
    /// prim's `orientation` is `leftHanded`.
    pub mesh: Mesh,
    /// The prim's subdivision options (creasing is always uniform).
    pub options: Options,
    /// The primvar names (without `primvars:`) of [`Mesh::fvar_channels`],
    /// channel by channel: `st` first when it is face-varying, or else the
    /// only two-component face-varying primvar (such as `st_faceVarying`),
    /// then the other face-varying primvars by name.
    pub fvar_names: Vec<String>,
    /// The vertex and varying primvars, by name (constant and uniform ones
    /// are not read).
    pub primvars: Vec<UsdPrimvar>,
}

/// A vertex or varying primvar of a mesh ([`UsdMesh::primvars`]).
#[derive(Debug, Clone, PartialEq)]
pub struct UsdPrimvar {
    /// The name without `primvars:` (`displayColor`).
    pub name: String,
    /// [`UsdInterpolation::Vertex`] or [`UsdInterpolation::Varying`].
    pub interpolation: UsdInterpolation,
    /// Values per point: the components of the value type times the
    /// primvar's `elementSize`.
    pub width: usize,
    /// `width` values per point of the mesh (indexed primvars flattened).
    pub values: Vec<f64>,
}

/// A primvar's interpolation (`UsdGeomPrimvar`'s tokens).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum UsdInterpolation {
    /// One value for the whole prim.
    Constant,
    /// One value per face.
    Uniform,
    /// One value per point, interpolated linearly.
    Varying,
    /// One value per point, interpolated by the subdivision scheme.
    Vertex,
    /// One value per face corner.
    FaceVarying,
}

impl UsdInterpolation {
    /// Every interpolation, in the order of USD's documentation.
    pub const ALL: &'static [UsdInterpolation] = &[
        UsdInterpolation::Constant,
        UsdInterpolation::Uniform,
        UsdInterpolation::Varying,
        UsdInterpolation::Vertex,
        UsdInterpolation::FaceVarying,
    ];

    /// USD's token (`faceVarying`).
    pub fn token(self) -> &'static str {
        match self {
            UsdInterpolation::Constant => "constant",
            UsdInterpolation::Uniform => "uniform",
            UsdInterpolation::Varying => "varying",
            UsdInterpolation::Vertex => "vertex",
            UsdInterpolation::FaceVarying => "faceVarying",
        }
    }

    /// The interpolation of a USD token, if it is one.
    pub fn from_token(token: &str) -> Option<UsdInterpolation> {
        UsdInterpolation::ALL
            .iter()
            .copied()
            .find(|i| i.token() == token)
    }
}

impl fmt::Display for UsdInterpolation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.token())
    }
}

/// A selected `Mesh` prim that [`read_usd`] does not read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UsdSkipped {
    /// The prim's path.
    pub prim: String,
    /// Why (`subdivisionScheme is "none": not subdivided`).
    pub reason: String,
}

/// Something questionable but accepted while reading a stage.
///
/// Displayed as `PRIM.ATTRIBUTE: message`, `PRIM: message` or `message`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UsdWarning {
    /// The prim's path; empty when no prim is concerned.
    pub prim: String,
    /// The attribute's name; empty when no attribute is concerned.
    pub attribute: String,
    /// What was accepted, and what was done about it.
    pub message: String,
}

impl fmt::Display for UsdWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (self.prim.is_empty(), self.attribute.is_empty()) {
            (true, true) => {}
            (false, true) => write!(f, "{}: ", self.prim)?,
            (true, false) => write!(f, "{}: ", self.attribute)?,
            (false, false) => write!(f, "{}.{}: ", self.prim, self.attribute)?,
        }
        f.write_str(&self.message)
    }
}

/// Whether `name` is a USD identifier: a letter or `_`, then letters,
/// digits and `_` (Unicode letters and digits included, as USD 24.03 and
/// later accept them).
pub(super) fn is_identifier(name: &str) -> bool {
    let mut chars = name.chars();
    chars.next().is_some_and(|c| c == '_' || c.is_alphabetic())
        && chars.all(|c| c == '_' || c.is_alphanumeric())
}

/// Whether `name` is a primvar name (without `primvars:`): identifiers
/// joined by `:`, not ending in `:indices` (the name of a primvar's
/// indices).
pub(super) fn is_primvar_name(name: &str) -> bool {
    !name.ends_with(":indices") && name.split(':').all(is_identifier)
}
