//! The Python exceptions and the mapping of the library's typed errors onto
//! them: every [`subdiv::Error`] becomes an exception carrying the same
//! message as its Rust `Display`.

use pyo3::create_exception;
use pyo3::exceptions::{PyOSError, PyTypeError, PyValueError};
use pyo3::prelude::*;

create_exception!(
    _subdiv,
    SubdivError,
    PyValueError,
    "Base class of every error subdiv raises (a ValueError)."
);
create_exception!(
    _subdiv,
    MeshError,
    SubdivError,
    "An invalid mesh: bad indices, shapes, sizes or values (the Rust MeshError's message)."
);
create_exception!(
    _subdiv,
    ObjError,
    SubdivError,
    "A malformed OBJ file or text, naming the file and line."
);
create_exception!(
    _subdiv,
    LevelError,
    SubdivError,
    "A refinement level refused before anything is allocated (too deep, too large, out of memory)."
);
create_exception!(
    _subdiv,
    OsdError,
    SubdivError,
    "The osd engine refused the input or is not in this build."
);

/// The exception for a library error, with the library's message.
pub fn to_py(error: subdiv::Error) -> PyErr {
    use subdiv::Error as E;
    let message = error.to_string();
    match error {
        E::Mesh(_) | E::EmptyMesh | E::NotTriangles { .. } | E::UnpairedSmoothVertex { .. } => {
            MeshError::new_err(message)
        }
        E::Obj(_) => ObjError::new_err(message),
        E::Level { .. } | E::TooLarge { .. } | E::OutOfMemory { .. } => {
            LevelError::new_err(message)
        }
        E::Osd(_) | E::OsdUnavailable => OsdError::new_err(message),
        // Arrays the OBJ writer refuses before writing anything are the
        // caller's values, not the file system's fault.
        E::Io { source, .. } if source.kind() == std::io::ErrorKind::InvalidInput => {
            SubdivError::new_err(message)
        }
        E::Io { .. } => PyOSError::new_err(message),
        _ => SubdivError::new_err(message),
    }
}

/// A mesh error, as the library reports it from a refinement
/// (`invalid mesh: ...`).
pub fn mesh_error(error: subdiv::MeshError) -> PyErr {
    to_py(subdiv::Error::from(error))
}

/// An unknown option name (`ParseNameError`'s message, listing the names).
pub fn name_error(error: subdiv::ParseNameError) -> PyErr {
    SubdivError::new_err(error.to_string())
}

/// A Python value of the wrong type (a dtype, a non-array).
pub fn type_error(message: String) -> PyErr {
    PyTypeError::new_err(message)
}

/// Registers the exception classes on the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("SubdivError", py.get_type::<SubdivError>())?;
    m.add("MeshError", py.get_type::<MeshError>())?;
    m.add("ObjError", py.get_type::<ObjError>())?;
    m.add("LevelError", py.get_type::<LevelError>())?;
    m.add("OsdError", py.get_type::<OsdError>())?;
    Ok(())
}
