//! `subdiv.Options` and the other names the command line uses (engine,
//! precision), parsed by the library's own `Named` mechanism so that the
//! names and the error messages are the CLI's.

use crate::errors::name_error;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use subdiv::{
    BoundaryInterpolation, CreasingMethod, Engine, FVarLinearInterpolation, Named, Precision,
    Scheme, TriangleSubdivision,
};

/// Parses a name of `T` (`"catmark"`, `"edge-only"`, `"osd"`, `"f32"`...).
pub fn parse<T: Named>(text: &str) -> PyResult<T> {
    T::from_name(text).map_err(name_error)
}

/// Every name of `T`, in declaration order.
fn names<T: Named>() -> Vec<&'static str> {
    T::ALL.iter().map(|v| v.name()).collect()
}

/// Subdivision options, with the names of ``subdiv refine``'s flags.
///
/// ``Options(scheme="catmark", boundary="edge-only", fvar="all",
/// creasing="uniform", triangles="catmark")`` — the defaults are OpenSubdiv's
/// shape-file conventions, which ``subdiv refine`` uses for an OBJ file
/// without tags. ``Options.sdc_defaults()`` is ``Sdc::Options()`` instead
/// (boundary ``none``). ``Options.CHOICES`` lists the names of each field.
/// An unknown name raises ``SubdivError`` listing the accepted ones.
#[pyclass(frozen, eq, hash, module = "subdiv")]
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct Options {
    /// The library's options.
    pub inner: subdiv::Options,
}

#[pymethods]
impl Options {
    #[new]
    #[pyo3(signature = (scheme="catmark", boundary="edge-only", fvar="all", creasing="uniform", triangles="catmark"))]
    fn new(
        scheme: &str,
        boundary: &str,
        fvar: &str,
        creasing: &str,
        triangles: &str,
    ) -> PyResult<Options> {
        Ok(Options {
            inner: subdiv::Options {
                scheme: parse::<Scheme>(scheme)?,
                boundary: parse::<BoundaryInterpolation>(boundary)?,
                fvar: parse::<FVarLinearInterpolation>(fvar)?,
                creasing: parse::<CreasingMethod>(creasing)?,
                triangles: parse::<TriangleSubdivision>(triangles)?,
            },
        })
    }

    /// OpenSubdiv's ``Sdc::Options()``: boundary ``none``, the rest as the defaults.
    #[staticmethod]
    fn sdc_defaults() -> Options {
        Options {
            inner: subdiv::Options::default(),
        }
    }

    /// The accepted names of every field, and of ``engine`` and ``precision``.
    #[classattr]
    #[allow(non_snake_case)]
    fn CHOICES(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("scheme", names::<Scheme>())?;
        d.set_item("boundary", names::<BoundaryInterpolation>())?;
        d.set_item("fvar", names::<FVarLinearInterpolation>())?;
        d.set_item("creasing", names::<CreasingMethod>())?;
        d.set_item("triangles", names::<TriangleSubdivision>())?;
        d.set_item("engine", names::<Engine>())?;
        d.set_item("precision", names::<Precision>())?;
        Ok(d)
    }

    /// The scheme: ``catmark``, ``loop`` or ``bilinear``.
    #[getter]
    fn scheme(&self) -> &'static str {
        self.inner.scheme.name()
    }

    /// Vertex boundary interpolation: ``none``, ``edge-only`` or ``edge-and-corner``.
    #[getter]
    fn boundary(&self) -> &'static str {
        self.inner.boundary.name()
    }

    /// Face-varying linear interpolation: ``none``, ``corners-only``,
    /// ``corners-plus1``, ``corners-plus2``, ``boundaries`` or ``all``.
    #[getter]
    fn fvar(&self) -> &'static str {
        self.inner.fvar.name()
    }

    /// Creasing method: ``uniform`` or ``chaikin``.
    #[getter]
    fn creasing(&self) -> &'static str {
        self.inner.creasing.name()
    }

    /// Catmull-Clark weights on triangles: ``catmark`` or ``smooth``.
    #[getter]
    fn triangles(&self) -> &'static str {
        self.inner.triangles.name()
    }

    /// These options with some fields replaced (keyword arguments of the constructor).
    #[pyo3(signature = (*, scheme=None, boundary=None, fvar=None, creasing=None, triangles=None))]
    fn replace(
        &self,
        scheme: Option<&str>,
        boundary: Option<&str>,
        fvar: Option<&str>,
        creasing: Option<&str>,
        triangles: Option<&str>,
    ) -> PyResult<Options> {
        let mut o = self.inner;
        if let Some(s) = scheme {
            o.scheme = parse(s)?;
        }
        if let Some(s) = boundary {
            o.boundary = parse(s)?;
        }
        if let Some(s) = fvar {
            o.fvar = parse(s)?;
        }
        if let Some(s) = creasing {
            o.creasing = parse(s)?;
        }
        if let Some(s) = triangles {
            o.triangles = parse(s)?;
        }
        Ok(Options { inner: o })
    }

    fn __repr__(&self) -> String {
        format!(
            "subdiv.Options(scheme={:?}, boundary={:?}, fvar={:?}, creasing={:?}, triangles={:?})",
            self.scheme(),
            self.boundary(),
            self.fvar(),
            self.creasing(),
            self.triangles()
        )
    }
}

/// The library options of an optional `Options` argument (the shape-file
/// defaults when it is `None`, as `subdiv refine` without tags).
pub fn or_default(options: Option<&Options>) -> subdiv::Options {
    options.map_or_else(subdiv::Options::shape_file_defaults, |o| o.inner)
}
