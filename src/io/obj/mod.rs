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
//! ([`ObjError`](crate::ObjError)). Harmless oddities — unknown statements, `l` and `p`
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

use crate::mesh::Mesh;
use crate::options::{
    BoundaryInterpolation, CreasingMethod, FVarLinearInterpolation, Options, TriangleSubdivision,
};
use std::fmt;

mod chunks;
mod fast;
mod read;
mod write;

pub(crate) use read::escape;
pub use read::{parse_obj, parse_obj_chunked, parse_obj_general, parse_obj_streamed, read_obj};
pub use write::{
    ObjOutput, UvOutput, mesh_to_obj_string, write_mesh_obj, write_mesh_obj_to, write_obj,
    write_obj_to,
};

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
    /// What was questionable.
    pub message: String,
    /// Whether the line was skipped (an unknown statement or tag, an
    /// unsupported element); otherwise it was read.
    pub ignored: bool,
}

impl fmt::Display for ObjWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: {}", self.line, self.message)?;
        if self.ignored {
            f.write_str("; the line is ignored")?;
        }
        Ok(())
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
