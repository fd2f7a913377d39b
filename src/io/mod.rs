//! Reading and writing meshes as files.
//!
//! The only format is OBJ, extended with the `t` tag lines of OpenSubdiv's
//! shape files (creases, corners, holes and subdivision options); see [`obj`].

pub mod atomic;
pub mod obj;
pub mod svg;

pub use obj::{
    ObjOutput, ObjWarning, ShapeFile, ShapeTags, UvOutput, format_g, mesh_to_obj_string, parse_obj,
    read_obj, write_mesh_obj, write_mesh_obj_to, write_obj, write_obj_to,
};
