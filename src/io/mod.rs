//! Files in and out: meshes as OBJ with the `t` tag lines of OpenSubdiv's
//! shape files (creases, corners, holes and subdivision options; [`obj`]),
//! the subdivision meshes of USD stages and refined meshes back as `.usda`
//! (`usd`, feature `usd`),
//! curves as points files ([`points`]), pictures as SVG ([`svg`]); numbers
//! written exactly as C's `%.17g` ([`number`]) and every output file written
//! atomically ([`atomic`]).

pub mod atomic;
pub mod number;
pub mod obj;
pub mod points;
pub mod svg;
#[cfg(feature = "usd")]
pub mod usd;

pub use number::format_g;
pub use obj::{
    ObjOutput, ObjWarning, ShapeFile, ShapeTags, UvOutput, mesh_to_obj_string, parse_obj,
    parse_obj_chunked, parse_obj_general, parse_obj_streamed, read_obj, write_mesh_obj,
    write_mesh_obj_to, write_obj, write_obj_to,
};
#[cfg(feature = "usd")]
pub use usd::{UsdMesh, UsdMeshOut, UsdReadOptions, UsdStage, read_usd, write_usda};
