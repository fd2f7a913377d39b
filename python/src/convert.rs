//! numpy arrays in and out, with no per-element Python work: inputs are
//! read in place when contiguous (copied once otherwise), outputs take over
//! the vectors the library returns (no copy).

use crate::errors::{SubdivError, type_error};
use glam::DVec3;
use numpy::ndarray::Array1;
use numpy::{
    Element, PyArray1, PyArray2, PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArray,
    PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use std::borrow::Cow;

/// A float array as given: `float32` or `float64`, read in place.
pub enum Floats<'py> {
    /// `float32` values.
    F32(PyReadonlyArrayDyn<'py, f32>),
    /// `float64` values.
    F64(PyReadonlyArrayDyn<'py, f64>),
}

impl Floats<'_> {
    /// The array's shape.
    pub fn shape(&self) -> &[usize] {
        match self {
            Floats::F32(a) => a.shape(),
            Floats::F64(a) => a.shape(),
        }
    }

    /// The values in `f64`, row-major (copied: the library's meshes own `f64`s).
    pub fn to_f64(&self) -> Vec<f64> {
        match self {
            Floats::F32(a) => a.as_array().iter().map(|&v| f64::from(v)).collect(),
            Floats::F64(a) => match a.as_slice() {
                Ok(s) => s.to_vec(),
                Err(_) => a.as_array().iter().copied().collect(),
            },
        }
    }
}

/// The values of a readonly array, in place when contiguous.
pub fn slice_of<'a, T: Element + Copy>(a: &'a PyReadonlyArrayDyn<'_, T>) -> Cow<'a, [T]> {
    match a.as_slice() {
        Ok(s) => Cow::Borrowed(s),
        Err(_) => Cow::Owned(a.as_array().iter().copied().collect()),
    }
}

/// `obj` as a numpy array: arrays as they are, anything else (lists,
/// tuples) through `numpy.asarray(obj, dtype)`.
fn as_array<'py>(obj: &Bound<'py, PyAny>, dtype: &str) -> PyResult<Bound<'py, PyUntypedArray>> {
    if let Ok(a) = obj.cast::<PyUntypedArray>() {
        return Ok(a.clone());
    }
    let numpy = obj.py().import("numpy")?;
    let converted = numpy.call_method1("asarray", (obj, dtype)).map_err(|e| {
        type_error(format!(
            "cannot read an array of {dtype} from the value: {e}"
        ))
    })?;
    Ok(converted.cast_into::<PyUntypedArray>()?)
}

/// An array another Rust extension holds mutably borrowed.
fn borrow_error(e: numpy::BorrowError) -> PyErr {
    SubdivError::new_err(format!("the array cannot be read: {e}"))
}

fn dtype_name(a: &Bound<'_, PyUntypedArray>) -> String {
    a.dtype().to_string()
}

/// A `float32` or `float64` array; any other dtype is a `TypeError` naming `what`.
pub fn floats<'py>(obj: &Bound<'py, PyAny>, what: &str) -> PyResult<Floats<'py>> {
    let a = as_array(obj, "float64")?;
    if let Ok(a) = a.cast::<PyArrayDyn<f64>>() {
        return Ok(Floats::F64(a.try_readonly().map_err(borrow_error)?));
    }
    if let Ok(a) = a.cast::<PyArrayDyn<f32>>() {
        return Ok(Floats::F32(a.try_readonly().map_err(borrow_error)?));
    }
    Err(type_error(format!(
        "{what} must be a float32 or float64 array, not {}",
        dtype_name(&a)
    )))
}

/// Requires `shape` to be `(N, width)` (or `(N,)` when `width` is `None`);
/// returns `N`.
pub fn check_shape(shape: &[usize], width: Option<usize>, what: &str) -> PyResult<usize> {
    let ok = match (width, shape) {
        (Some(w), [_, c]) => *c == w,
        (None, [_]) => true,
        _ => false,
    };
    if !ok {
        let expected = match width {
            Some(w) => format!("(N, {w})"),
            None => "(N,)".to_string(),
        };
        return Err(SubdivError::new_err(format!(
            "{what} must have the shape {expected}, not {shape:?}"
        )));
    }
    Ok(shape[0])
}

/// `(N, 3)` positions (float32 or float64) as the library's points.
pub fn positions(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<DVec3>> {
    let points = floats(obj, what)?;
    check_shape(points.shape(), Some(3), what)?;
    Ok(points
        .to_f64()
        .chunks_exact(3)
        .map(|c| DVec3::new(c[0], c[1], c[2]))
        .collect())
}

/// A one-dimensional integer array as `u32`s.
pub fn int_vector(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<u32>> {
    let (values, shape) = ints(obj, what)?;
    check_shape(&shape, None, what)?;
    Ok(values)
}

/// Face offsets from face sizes, which must add up to the `corners` face indices.
pub fn face_offsets(counts: &[u32], corners: usize) -> PyResult<Vec<u32>> {
    let sum: u64 = counts.iter().map(|&c| u64::from(c)).sum();
    if sum != corners as u64 {
        return Err(crate::errors::MeshError::new_err(format!(
            "face_counts add up to {sum} face corners but face_indices has {corners}"
        )));
    }
    let mut offsets = Vec::with_capacity(counts.len() + 1);
    let mut total = 0u32;
    offsets.push(0);
    for &c in counts {
        // Saturating: a sum beyond `u32` is refused by the mesh's validation
        // (OpenSubdiv's indices are 32-bit), with its own message.
        total = total.saturating_add(c);
        offsets.push(total);
    }
    Ok(offsets)
}

/// Reads an integer array of any of numpy's integer dtypes into `u32`s,
/// refusing negative and too large values by position.
macro_rules! read_ints {
    ($a:expr, $what:expr, $($t:ty),+) => {{
        $(
            if let Ok(a) = $a.cast::<PyArrayDyn<$t>>() {
                let a = a.try_readonly().map_err(borrow_error)?;
                let shape = a.shape().to_vec();
                let mut out = Vec::with_capacity(a.len());
                for (i, &v) in a.as_array().iter().enumerate() {
                    match u32::try_from(v) {
                        Ok(v) => out.push(v),
                        Err(_) => {
                            return Err(crate::errors::MeshError::new_err(format!(
                                "{}[{i}] is {v}: an index must be in 0..=4294967295",
                                $what
                            )))
                        }
                    }
                }
                return Ok((out, shape));
            }
        )+
    }};
}

/// An integer array (int8 to int64, unsigned too) as `u32`s with its
/// shape; any other dtype is a `TypeError` naming `what`.
pub fn ints(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<(Vec<u32>, Vec<usize>)> {
    let a = as_array(obj, "int64")?;
    read_ints!(a, what, i32, i64, u32, u64, i16, u16, i8, u8);
    Err(type_error(format!(
        "{what} must be an integer array (int32 or int64), not {}",
        dtype_name(&a)
    )))
}

/// `(N, 3)` `float64` positions, taking over `points` (no copy).
pub fn points_f64(py: Python<'_>, points: Vec<DVec3>) -> PyResult<Bound<'_, PyArray2<f64>>> {
    let n = points.len();
    let flat: Vec<f64> = match bytemuck::allocation::try_cast_vec(points) {
        Ok(flat) => flat,
        Err((_, points)) => points.iter().flat_map(|p| p.to_array()).collect(),
    };
    rows(py, flat, n, 3)
}

/// `(N, 3)` `float32` positions from `f64` ones (refinements in `f32` keep
/// their values widened; narrowing them back is exact).
pub fn points_f32<'py>(py: Python<'py>, points: &[DVec3]) -> PyResult<Bound<'py, PyArray2<f32>>> {
    let flat: Vec<f32> = points.iter().flat_map(|p| p.as_vec3().to_array()).collect();
    rows(py, flat, points.len(), 3)
}

/// A `(rows, width)` array taking over `flat` (`rows * width` values).
pub fn rows<T: Element>(
    py: Python<'_>,
    flat: Vec<T>,
    n: usize,
    width: usize,
) -> PyResult<Bound<'_, PyArray2<T>>> {
    PyArray1::from_vec(py, flat).reshape([n, width])
}

/// A flat buffer of `width`-wide values as a `(len / width, width)` array.
pub fn values<T: Element>(
    py: Python<'_>,
    flat: Vec<T>,
    width: usize,
) -> PyResult<Bound<'_, PyArray2<T>>> {
    let width = width.max(1);
    let n = flat.len() / width;
    let mut flat = flat;
    flat.truncate(n * width);
    rows(py, flat, n, width)
}

/// `int32` indices, taking over `indices` (no copy; the library keeps every
/// index below 2^31, as OpenSubdiv does).
pub fn indices(py: Python<'_>, indices: Vec<u32>) -> Bound<'_, PyArray1<i32>> {
    let signed: Vec<i32> = match bytemuck::allocation::try_cast_vec(indices) {
        Ok(signed) => signed,
        Err((_, indices)) => indices.iter().map(|&i| i as i32).collect(),
    };
    PyArray1::from_vec(py, signed)
}

/// Face sizes (`int32`) from face offsets.
pub fn face_counts<'py>(py: Python<'py>, offsets: &[u32]) -> Bound<'py, PyArray1<i32>> {
    let counts: Vec<i32> = offsets
        .windows(2)
        .map(|w| w[1].saturating_sub(w[0]) as i32)
        .collect();
    PyArray1::from_vec(py, counts)
}

/// A one-dimensional array taking over `v`.
pub fn vector<T: Element>(py: Python<'_>, v: Vec<T>) -> Bound<'_, PyArray1<T>> {
    PyArray1::from_owned_array(py, Array1::from_vec(v))
}
