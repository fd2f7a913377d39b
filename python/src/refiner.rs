//! `subdiv.Refiner`: topology refined once, then any number of frames
//! interpolated (limit positions and tangents, face-varying values, stencil
//! tables), with either engine and the GIL released during the work.

use crate::convert::{self, Floats, floats, slice_of};
use crate::errors::to_py;
use crate::mesh::Mesh;
use crate::options::{Options, or_default, parse};
use crate::refine::level_arg;
use numpy::{Element, PyArray1};
use pyo3::prelude::*;
use pyo3::types::PyList;
use subdiv::{Engine, LimitData, Real, StencilTable, UniformOptions};

/// One engine's refiner.
enum Inner {
    Native(subdiv::refiner::Refiner),
    Osd(subdiv::osd::TopologyRefiner),
}

/// Calls the same method on either engine's refiner.
macro_rules! on_engine {
    ($inner:expr, $r:ident => $call:expr) => {
        match $inner {
            Inner::Native($r) => $call,
            Inner::Osd($r) => $call,
        }
    };
}

/// Runs `$body` on the values of a float array, read in place when
/// contiguous, whichever its dtype.
macro_rules! with_floats {
    ($data:expr, $src:ident => $body:expr) => {
        match $data {
            Floats::F64(a) => {
                let $src = slice_of(a);
                $body
            }
            Floats::F32(a) => {
                let $src = slice_of(a);
                $body
            }
        }
    };
}

/// A mesh's topology refined uniformly once, for many frames.
///
/// ``Refiner(mesh, level=2, options=None, engine="native",
/// faces_first=False, full_topology=True)``: the topology is refined when the
/// refiner is made; ``interpolate(points)`` then refines any number of
/// frames of positions (or any per-vertex data) with no topology work.
/// ``full_topology`` keeps the last level's full topology, which ``limit``
/// needs (as OpenSubdiv requires); without it the last level is minimal.
#[pyclass(frozen, module = "subdiv")]
pub struct Refiner {
    inner: Inner,
    engine: Engine,
    level: u32,
    base_vertices: usize,
}

/// A stencil table as CSR arrays: `(data, indices, indptr, (rows, columns))`.
type Csr<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<i32>>,
    Bound<'py, PyArray1<i32>>,
    (usize, usize),
);

/// A level's faces: `(face_counts, face_indices, holes)`.
type Topology<'py> = (
    Bound<'py, PyArray1<i32>>,
    Bound<'py, PyArray1<i32>>,
    Bound<'py, PyArray1<bool>>,
);

/// The rows of `t` laid out one after the other, in row order, as CSR.
fn csr(py: Python<'_>, t: StencilTable, columns: usize) -> Csr<'_> {
    let rows = t.len();
    let mut indptr = Vec::with_capacity(rows + 1);
    indptr.push(0u32);
    let mut contiguous = true;
    for (&offset, &size) in t.offsets.iter().zip(&t.sizes) {
        let start = *indptr.last().unwrap_or(&0);
        contiguous &= offset == start;
        indptr.push(start.saturating_add(size));
    }
    let (indices, weights) =
        if contiguous && t.indices.len() == *indptr.last().unwrap_or(&0) as usize {
            (t.indices.into_vec(), t.weights.into_vec())
        } else {
            let mut indices = Vec::with_capacity(t.indices.len());
            let mut weights = Vec::with_capacity(t.weights.len());
            for i in 0..rows {
                let (idx, w) = t.row(i);
                indices.extend_from_slice(idx);
                weights.extend_from_slice(w);
            }
            (indices, weights)
        };
    (
        convert::vector(py, weights),
        convert::indices(py, indices),
        convert::indices(py, indptr),
        (rows, columns),
    )
}

impl Refiner {
    /// Values of every level from `width`-wide base values.
    fn all_levels<T: Real + Element>(
        &self,
        base: &[T],
        width: usize,
    ) -> subdiv::Result<Vec<Vec<T>>> {
        let mut out = vec![base.to_vec()];
        for level in 1..=self.level {
            let next = on_engine!(&self.inner, r => r.interpolate(level, width, out.last().map_or(&[][..], Vec::as_slice)))?;
            out.push(next);
        }
        Ok(out)
    }

    /// Values of the last level from `width`-wide base values.
    fn last_level<T: Real + Element>(&self, base: &[T], width: usize) -> subdiv::Result<Vec<T>> {
        match &self.inner {
            Inner::Native(r) => r
                .interpolate_last(width, base)
                .map(subdiv::Values::into_vec),
            Inner::Osd(r) => r.interpolate_last(width, base),
        }
    }

    /// Face-varying values of every level from a channel's base values.
    fn all_fvar_levels<T: Real + Element>(
        &self,
        channel: usize,
        base: &[T],
        width: usize,
    ) -> subdiv::Result<Vec<Vec<T>>> {
        let mut out = vec![base.to_vec()];
        for level in 1..=self.level {
            let src = out.last().map_or(&[][..], Vec::as_slice);
            let next = on_engine!(&self.inner, r => r.interpolate_face_varying(channel, level, width, src))?;
            out.push(next);
        }
        Ok(out)
    }
}

/// `levels` as a list of `(n, width)` arrays.
fn level_list<'py, T: Element>(
    py: Python<'py>,
    levels: Vec<Vec<T>>,
    width: usize,
) -> PyResult<Bound<'py, PyList>> {
    let out = PyList::empty(py);
    for values in levels {
        out.append(convert::values(py, values, width)?)?;
    }
    Ok(out)
}

/// The width of `(N, width)` data (at least 1 component).
fn width_of(data: &Floats<'_>, what: &str) -> PyResult<usize> {
    match data.shape() {
        [_, w] if *w > 0 => Ok(*w),
        shape => Err(crate::errors::SubdivError::new_err(format!(
            "{what} must have the shape (N, width) with width >= 1, not {shape:?}"
        ))),
    }
}

#[pymethods]
impl Refiner {
    #[new]
    #[pyo3(signature = (mesh, level=2, options=None, engine="native", faces_first=false, full_topology=true))]
    fn new(
        py: Python<'_>,
        mesh: &Bound<'_, Mesh>,
        level: i64,
        options: Option<&Options>,
        engine: &str,
        faces_first: bool,
        full_topology: bool,
    ) -> PyResult<Refiner> {
        let engine: Engine = parse(engine)?;
        let mesh = &mesh.get().inner;
        let options = or_default(options);
        let level = level_arg(level)?;
        subdiv::check_level(mesh, &options, level).map_err(to_py)?;
        let uniform = UniformOptions::new(level)
            .faces_first(faces_first)
            .full_topology(full_topology);
        let inner = py
            .detach(|| -> subdiv::Result<Inner> {
                Ok(match engine {
                    Engine::Native => {
                        let mut r = subdiv::refiner::Refiner::new(mesh, &options)?;
                        r.refine_uniform(uniform)?;
                        Inner::Native(r)
                    }
                    Engine::Osd => {
                        let mut r = subdiv::osd::TopologyRefiner::new(mesh, &options)?;
                        r.refine_uniform(uniform)?;
                        Inner::Osd(r)
                    }
                })
            })
            .map_err(to_py)?;
        Ok(Refiner {
            inner,
            engine,
            level,
            base_vertices: mesh.vertex_count(),
        })
    }

    /// The engine's name: ``native`` or ``osd``.
    #[getter]
    fn engine(&self) -> &'static str {
        self.engine.name()
    }

    /// The refinement level (the last level's index).
    #[getter]
    fn level(&self) -> u32 {
        self.level
    }

    /// ``(face_counts, face_indices, holes)`` of level ``level`` (int32, int32, bool).
    fn topology<'py>(&self, py: Python<'py>, level: i64) -> PyResult<Topology<'py>> {
        let level = level_arg(level)?;
        let t = on_engine!(&self.inner, r => r.level(level)).map_err(to_py)?;
        Ok((
            convert::face_counts(py, &t.face_offsets),
            convert::indices(py, t.face_vertices),
            convert::vector(py, t.face_holes),
        ))
    }

    /// Number of vertices of every level, from the base to the last.
    fn vertex_counts(&self) -> PyResult<Vec<usize>> {
        (0..=self.level)
            .map(|l| on_engine!(&self.inner, r => r.level_counts(l)).map(|c| c.vertices))
            .collect::<subdiv::Result<_>>()
            .map_err(to_py)
    }

    /// Refines per-vertex data of every level: ``points`` of shape
    /// ``(base vertices, width)`` (float32 or float64, read in place when
    /// contiguous) gives a list of arrays of the same dtype, level 0 first.
    fn interpolate<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyList>> {
        let data = floats(points, "points")?;
        let width = width_of(&data, "points")?;
        with_floats!(&data, src => {
                let levels = py.detach(|| self.all_levels(&src, width)).map_err(to_py)?;
                level_list(py, levels, width)
        })
    }

    /// Refines per-vertex data to the last level only (``interpolate(points)[-1]``).
    fn interpolate_last<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let data = floats(points, "points")?;
        let width = width_of(&data, "points")?;
        Ok(with_floats!(&data, src => {
                let last = py.detach(|| self.last_level(&src, width)).map_err(to_py)?;
                convert::values(py, last, width)?.into_any()
        }))
    }

    /// Refines face-varying values of channel ``channel`` (0: the UVs) through
    /// every level: ``values`` of shape ``(value count, width)``; a list of
    /// arrays, level 0 first, numbered as the levels' ``uv_indices``.
    #[pyo3(signature = (values, channel=0))]
    fn interpolate_face_varying<'py>(
        &self,
        py: Python<'py>,
        values: &Bound<'py, PyAny>,
        channel: usize,
    ) -> PyResult<Bound<'py, PyList>> {
        let data = floats(values, "values")?;
        let width = width_of(&data, "values")?;
        with_floats!(&data, src => {
                let levels = py
                    .detach(|| self.all_fvar_levels(channel, &src, width))
                    .map_err(to_py)?;
                level_list(py, levels, width)
        })
    }

    /// Limit positions and both tangents at the vertices of the last level,
    /// from ``points`` at the last level (``interpolate(base)[-1]``):
    /// ``(positions, du, dv)``, each shaped as ``points``. Needs
    /// ``full_topology=True`` (the default).
    fn limit<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let data = floats(points, "points")?;
        let width = width_of(&data, "points")?;
        fn arrays<'py, T: Real + Element>(
            py: Python<'py>,
            l: LimitData<T>,
            width: usize,
        ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>)> {
            Ok((
                convert::values(py, l.positions.into_vec(), width)?.into_any(),
                convert::values(py, l.du.into_vec(), width)?.into_any(),
                convert::values(py, l.dv.into_vec(), width)?.into_any(),
            ))
        }
        with_floats!(&data, src => {
                let l = py
                    .detach(|| on_engine!(&self.inner, r => r.limit(width, &src)))
                    .map_err(to_py)?;
                arrays(py, l, width)
        })
    }

    /// The stencil table from the base vertices to the last level's, as CSR
    /// arrays ``(data, indices, indptr, shape)``: ``data`` float64 weights,
    /// ``indices`` and ``indptr`` int32, ``shape`` ``(last vertices, base
    /// vertices)`` (``scipy.sparse.csr_matrix((data, indices, indptr), shape)``).
    fn stencil_table<'py>(&self, py: Python<'py>) -> PyResult<Csr<'py>> {
        let t = py
            .detach(|| on_engine!(&self.inner, r => r.stencil_table()))
            .map_err(to_py)?;
        Ok(csr(py, t, self.base_vertices))
    }

    /// Limit stencils at the last level's vertices from the base vertices:
    /// ``(positions, du, dv)``, three CSR tables as ``stencil_table``'s.
    fn limit_stencil_table<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Csr<'py>, Csr<'py>, Csr<'py>)> {
        let t = py
            .detach(|| on_engine!(&self.inner, r => r.limit_stencil_table()))
            .map_err(to_py)?;
        let n = self.base_vertices;
        Ok((csr(py, t.positions, n), csr(py, t.du, n), csr(py, t.dv, n)))
    }

    fn __repr__(&self) -> String {
        format!(
            "subdiv.Refiner(engine={:?}, level={}, base vertices {})",
            self.engine.name(),
            self.level,
            self.base_vertices
        )
    }
}
