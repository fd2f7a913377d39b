//! OpenSubdiv's `Bfr::Tessellation` and `Bfr::Parameterization` through the
//! bridge (`cpp/bfr.cpp`), read back whole so that native tessellation
//! patterns and face parameterizations can be compared with OpenSubdiv's.
//!
//! A face is given by its [`Scheme`] and size. What OpenSubdiv itself holds
//! invalid comes back as a value saying so (`is_valid` false: a
//! non-triangle under Loop); what would make it read or write out of
//! bounds, divide by zero, overflow an int or allocate without bound is an
//! [`Error::Osd`](crate::Error::Osd) before OpenSubdiv sees it: a face size
//! outside 3..=65535 (kind `Refused`) or, under a quad scheme, of 65026 or
//! more (kind `Unsafe`: OpenSubdiv's sub-face grid width wraps to 0), a rate
//! count outside 1..=N+2, a rate below 1 (OpenSubdiv would only hold the
//! tessellation invalid, but the bridge refuses it), a facet size other than
//! 3 or 4, a pattern of more than [`MAX_COORDS`] coordinates or
//! [`MAX_FACETS`] facets, an index out of range.
//!
//! OpenSubdiv's limit surfaces (`Bfr::RefinerSurfaceFactory` and
//! `Bfr::Surface`) are in [`bfr_surface`](super::bfr_surface); its
//! [`Surfaces`] and [`SurfaceInfo`] are re-exported here, as is
//! [`tessellate_mesh`] from [`bfr_mesh`](super::bfr_mesh): a whole mesh
//! tessellated watertight by OpenSubdiv in one C++ call.
//!
//! ```
//! use subdiv::{Scheme, osd::bfr};
//! let t = bfr::tessellate(Scheme::Catmark, 4, &[2], false, 3)?;
//! assert_eq!((t.num_boundary_coords, t.num_interior_coords), (8, 1));
//! assert_eq!(t.coords_f64[8], [0.5, 0.5]);
//! assert_eq!(t.num_facets(), 8);
//! # Ok::<(), subdiv::Error>(())
//! ```

pub use crate::osd::bfr_mesh::tessellate_mesh;
pub use crate::osd::bfr_surface::{SurfaceInfo, Surfaces};

use super::ERR_LEN;
use super::ffi;
use super::shim::{ErrBuf, internal, to_i32, with_shim_type};
use crate::alloc::try_vec;
use crate::error::Result;
use crate::options::Scheme;
use crate::real::{Precision, Real};
use std::ptr::{NonNull, null, null_mut};

/// The most coordinates a tessellation through the bridge may have (2^24):
/// OpenSubdiv counts them in `int` (a quad at its largest rate, 32767, has
/// 2^30 of them; a large polygon's count overflows), and a pattern beyond
/// this bound takes gigabytes read back in both precisions.
pub const MAX_COORDS: usize = ffi::SDV_BFR_MAX_COORDS as usize;

/// The most facets a tessellation through the bridge may have (2^25; a
/// triangulated disc has fewer than two facets per coordinate).
pub const MAX_FACETS: usize = ffi::SDV_BFR_MAX_FACETS as usize;

/// OpenSubdiv's `Bfr::Tessellation` of one face, read back whole.
///
/// For an invalid tessellation (`is_valid` false) every other field is
/// empty or zero, except `face_size` and `facet_size`, the ones asked for.
#[derive(Debug, Clone, PartialEq)]
pub struct OsdTessellation {
    /// `IsValid`.
    pub is_valid: bool,
    /// `IsUniform`.
    pub is_uniform: bool,
    /// The face's size, as asked for.
    pub face_size: usize,
    /// `GetRates`: as many as were given, outer rates first, then inner ones,
    /// each clamped to 32767 as OpenSubdiv clamps them; where fewer than the
    /// face size were given, the rates OpenSubdiv infers for the first edges.
    pub rates: Vec<i32>,
    /// `GetNumBoundaryCoords`.
    pub num_boundary_coords: usize,
    /// `GetNumInteriorCoords`.
    pub num_interior_coords: usize,
    /// `GetCoords<double>`: the boundary coordinates (counter-clockwise from
    /// the first vertex), then the interior ones.
    pub coords_f64: Vec<[f64; 2]>,
    /// `GetCoords<float>`, as computed in `float`.
    pub coords_f32: Vec<[f32; 2]>,
    /// The number of indices per facet (`GetFacetSize`): 3 or 4.
    pub facet_size: usize,
    /// `GetFacets`, `facet_size` indices per facet; a triangle among
    /// 4-index facets has OpenSubdiv's `-1` as its fourth.
    pub facets: Vec<i32>,
    /// `GetNumEdgeCoords` of every edge (edge `i` runs from vertex `i` to
    /// `i + 1`).
    pub num_edge_coords: Vec<usize>,
    /// `GetEdgeCoords<double>` of every edge: its coordinates without its
    /// end vertices.
    pub edge_coords_f64: Vec<Vec<[f64; 2]>>,
    /// `GetEdgeCoords<float>` of every edge.
    pub edge_coords_f32: Vec<Vec<[f32; 2]>>,
    /// `GetVertexCoord<double>` of every vertex.
    pub vertex_coords: Vec<[f64; 2]>,
}

impl OsdTessellation {
    /// `GetNumCoords`: boundary and interior coordinates.
    pub fn num_coords(&self) -> usize {
        self.num_boundary_coords + self.num_interior_coords
    }

    /// `GetNumFacets`.
    pub fn num_facets(&self) -> usize {
        self.facets.len().checked_div(self.facet_size).unwrap_or(0)
    }

    /// The indices of facet `i` (`facet_size` of them). Panics when `i` is
    /// not below [`OsdTessellation::num_facets`].
    pub fn facet(&self, i: usize) -> &[i32] {
        &self.facets[i * self.facet_size..(i + 1) * self.facet_size]
    }
}

/// One of the three overloads of `Tessellation::TransformFacetCoordIndices`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FacetTransform<'a> {
    /// `(facets, commonOffset)`: every index (not a triangle's `-1`) offset.
    Offset(i32),
    /// `(facets, boundaryIndices, interiorOffset)`: boundary coordinate `i`
    /// becomes `boundary[i]` (one entry per boundary coordinate), interior
    /// indices are offset.
    BoundaryOffset {
        /// The new index of every boundary coordinate.
        boundary: &'a [i32],
        /// Added to every interior coordinate's index.
        interior_offset: i32,
    },
    /// `(facets, boundaryIndices, interiorIndices)`: boundary coordinate `i`
    /// becomes `boundary[i]`, interior coordinate `j` (counted from the
    /// first interior one) `interior[j]`.
    BoundaryInterior {
        /// The new index of every boundary coordinate.
        boundary: &'a [i32],
        /// The new index of every interior coordinate.
        interior: &'a [i32],
    },
}

/// An OpenSubdiv `Bfr::Tessellation`, owned.
struct Handle(NonNull<ffi::sdv_tessellation>);

impl Drop for Handle {
    fn drop(&mut self) {
        // SAFETY: created by sdv_tessellation_create, freed once here.
        unsafe { ffi::sdv_tessellation_destroy(self.0.as_ptr()) }
    }
}

impl Handle {
    fn new(
        scheme: Scheme,
        face_size: usize,
        rates: &[i32],
        preserve_quads: bool,
        facet_size: usize,
    ) -> Result<Handle> {
        let n = to_i32(face_size, "face size")?;
        let facet = to_i32(facet_size, "facet size")?;
        let mut raw: *mut ffi::sdv_tessellation = null_mut();
        let mut err = ErrBuf::new();
        // SAFETY: `rates` outlives the call and its length is passed; `raw`
        // is written by the shim.
        err.run(|e| unsafe {
            ffi::sdv_tessellation_create(
                scheme.code(),
                n,
                rates.as_ptr(),
                rates.len(),
                preserve_quads.into(),
                facet,
                &mut raw,
                e,
                ERR_LEN,
            )
        })?;
        NonNull::new(raw)
            .map(Handle)
            .ok_or_else(|| internal("the shim returned no tessellation"))
    }

    fn counts(&self) -> Result<ffi::sdv_tess_counts> {
        let mut c = ffi::sdv_tess_counts {
            is_valid: 0,
            is_uniform: 0,
            face_size: 0,
            num_rates: 0,
            num_boundary_coords: 0,
            num_interior_coords: 0,
            num_facets: 0,
            facet_size: 0,
            num_edge_coords: 0,
        };
        let mut err = ErrBuf::new();
        // SAFETY: the handle is live; `c` is written by the shim.
        err.run(|e| unsafe { ffi::sdv_tessellation_counts(self.0.as_ptr(), &mut c, e, ERR_LEN) })?;
        Ok(c)
    }
}

fn count(n: i32) -> Result<usize> {
    usize::try_from(n).map_err(|_| internal("negative count"))
}

/// OpenSubdiv's tessellation of a `face_size`-sided face under `scheme`
/// (`Bfr::Tessellation(Parameterization(scheme, face_size), rates,
/// Options().SetFacetSize(facet_size).PreserveQuads(preserve_quads))`),
/// read back whole: validity, rates, counts, coordinates in `f64` and `f32`,
/// facets, every edge's coordinates and every vertex's.
///
/// `rates` holds, for an N-sided face, 1 (one inner rate: uniform), 2 (a
/// quad's two inner rates), N (one per edge, inner rates inferred), N + 1
/// (and one inner rate) or N + 2 (and a quad's two inner rates) rates;
/// OpenSubdiv reads other counts up to N + 2 as well (a count below N other
/// than a quad's 2 is one uniform rate, the rest ignored).
///
/// A non-triangle under Loop gives an invalid tessellation (`is_valid`
/// false). Refused ([`Error::Osd`](crate::Error::Osd), see the [module
/// documentation](self)): a face size outside 3..=65535 or beyond 65025
/// under a quad scheme, a rate count outside 1..=N+2, a rate below 1, a
/// facet size other than 3 or 4, more than [`MAX_COORDS`] coordinates or
/// [`MAX_FACETS`] facets (counted with OpenSubdiv's clamp of rates to
/// 32767).
///
/// ```
/// use subdiv::{Scheme, osd::bfr};
/// let t = bfr::tessellate(Scheme::Loop, 3, &[1], false, 4)?;
/// assert_eq!((t.num_coords(), t.facets.clone()), (3, vec![0, 1, 2, -1]));
/// assert!(!bfr::tessellate(Scheme::Loop, 4, &[1], false, 3)?.is_valid);
/// assert!(bfr::tessellate(Scheme::Catmark, 4, &[0], false, 3).is_err());
/// # Ok::<(), subdiv::Error>(())
/// ```
pub fn tessellate(
    scheme: Scheme,
    face_size: usize,
    rates: &[i32],
    preserve_quads: bool,
    facet_size: usize,
) -> Result<OsdTessellation> {
    let h = Handle::new(scheme, face_size, rates, preserve_quads, facet_size)?;
    let c = h.counts()?;
    let mut out = OsdTessellation {
        is_valid: c.is_valid != 0,
        is_uniform: c.is_uniform != 0,
        face_size,
        rates: Vec::new(),
        num_boundary_coords: count(c.num_boundary_coords)?,
        num_interior_coords: count(c.num_interior_coords)?,
        coords_f64: Vec::new(),
        coords_f32: Vec::new(),
        facet_size,
        facets: Vec::new(),
        num_edge_coords: Vec::new(),
        edge_coords_f64: Vec::new(),
        edge_coords_f32: Vec::new(),
        vertex_coords: Vec::new(),
    };
    if !out.is_valid {
        return Ok(out);
    }
    if count(c.face_size)? != face_size || count(c.facet_size)? != facet_size {
        return Err(internal(
            "OpenSubdiv's tessellation has another face or facet size",
        ));
    }
    let coords = out.num_coords();
    let edge_total = count(c.num_edge_coords)?;
    let mut rates = try_vec(0i32, count(c.num_rates)?)?;
    let mut coords_f64 = try_vec(0f64, 2 * coords)?;
    let mut coords_f32 = try_vec(0f32, 2 * coords)?;
    let mut facets = try_vec(0i32, count(c.num_facets)? * facet_size)?;
    let mut edge_counts = try_vec(0i32, face_size)?;
    let mut edge_f64 = try_vec(0f64, 2 * edge_total)?;
    let mut edge_f32 = try_vec(0f32, 2 * edge_total)?;
    let mut vertex = try_vec(0f64, 2 * face_size)?;
    let data = ffi::sdv_tess_data {
        rates: ffi::sdv_ibuf {
            data: rates.as_mut_ptr(),
            cap: rates.len(),
        },
        coords_f64: coords_f64.as_mut_ptr(),
        coords_f64_cap: coords_f64.len(),
        coords_f32: coords_f32.as_mut_ptr(),
        coords_f32_cap: coords_f32.len(),
        facets: ffi::sdv_ibuf {
            data: facets.as_mut_ptr(),
            cap: facets.len(),
        },
        edge_coord_counts: ffi::sdv_ibuf {
            data: edge_counts.as_mut_ptr(),
            cap: edge_counts.len(),
        },
        edge_coords_f64: edge_f64.as_mut_ptr(),
        edge_coords_f64_cap: edge_f64.len(),
        edge_coords_f32: edge_f32.as_mut_ptr(),
        edge_coords_f32_cap: edge_f32.len(),
        vertex_coords: vertex.as_mut_ptr(),
        vertex_coords_cap: vertex.len(),
    };
    let mut err = ErrBuf::new();
    // SAFETY: the handle is live; every buffer has the capacity passed
    // beside it, which the shim checks against the tessellation's counts.
    err.run(|e| unsafe { ffi::sdv_tessellation_data(h.0.as_ptr(), &data, e, ERR_LEN) })?;
    let pairs64 = |v: &[f64]| v.chunks_exact(2).map(|p| [p[0], p[1]]).collect::<Vec<_>>();
    let pairs32 = |v: &[f32]| v.chunks_exact(2).map(|p| [p[0], p[1]]).collect::<Vec<_>>();
    let mut at = 0;
    for &k in &edge_counts {
        let k = count(k)?;
        if at + k > edge_total {
            return Err(internal("edge coordinates do not match their counts"));
        }
        out.num_edge_coords.push(k);
        out.edge_coords_f64
            .push(pairs64(&edge_f64[2 * at..2 * (at + k)]));
        out.edge_coords_f32
            .push(pairs32(&edge_f32[2 * at..2 * (at + k)]));
        at += k;
    }
    out.rates = rates;
    out.coords_f64 = pairs64(&coords_f64);
    out.coords_f32 = pairs32(&coords_f32);
    out.facets = facets;
    out.vertex_coords = pairs64(&vertex);
    Ok(out)
}

/// The facets of the tessellation [`tessellate`] builds from the same
/// inputs, transformed by OpenSubdiv's `TransformFacetCoordIndices`
/// overload `transform`. Empty for an invalid tessellation (it has no
/// facets; the maps are not read).
///
/// Refused, besides [`tessellate`]'s refusals: a boundary map that is not
/// one index per boundary coordinate, an interior map that is not one per
/// interior coordinate, and (kind `Unsafe`) an offset that overflows an
/// `i32` when added to the largest coordinate index it applies to.
///
/// ```
/// use subdiv::{Scheme, osd::bfr::{self, FacetTransform}};
/// let f = bfr::transform_facets(Scheme::Loop, 3, &[1], false, 3, FacetTransform::Offset(10))?;
/// assert_eq!(f, vec![10, 11, 12]);
/// # Ok::<(), subdiv::Error>(())
/// ```
pub fn transform_facets(
    scheme: Scheme,
    face_size: usize,
    rates: &[i32],
    preserve_quads: bool,
    facet_size: usize,
    transform: FacetTransform<'_>,
) -> Result<Vec<i32>> {
    let h = Handle::new(scheme, face_size, rates, preserve_quads, facet_size)?;
    let c = h.counts()?;
    if c.is_valid == 0 {
        return Ok(Vec::new());
    }
    let mut facets = try_vec(0i32, count(c.num_facets)? * facet_size)?;
    let (kind, offset, boundary, interior): (u32, i32, &[i32], &[i32]) = match transform {
        FacetTransform::Offset(o) => (ffi::SDV_FACETS_OFFSET, o, &[], &[]),
        FacetTransform::BoundaryOffset {
            boundary,
            interior_offset,
        } => (
            ffi::SDV_FACETS_BOUNDARY_OFFSET,
            interior_offset,
            boundary,
            &[],
        ),
        FacetTransform::BoundaryInterior { boundary, interior } => {
            (ffi::SDV_FACETS_BOUNDARY_INTERIOR, 0, boundary, interior)
        }
    };
    let ptr = |s: &[i32]| if s.is_empty() { null() } else { s.as_ptr() };
    let mut err = ErrBuf::new();
    // SAFETY: the handle is live and owned here (the shim's transformation
    // takes it mutably); the maps outlive the call with their lengths
    // passed, and `facets` has the capacity passed, which the shim checks.
    err.run(|e| unsafe {
        ffi::sdv_tessellation_transform_facets(
            h.0.as_ptr(),
            kind as i32,
            offset,
            ptr(boundary),
            boundary.len(),
            ptr(interior),
            interior.len(),
            facets.as_mut_ptr(),
            facets.len(),
            e,
            ERR_LEN,
        )
    })?;
    Ok(facets)
}

/// The kinds of `Bfr::Parameterization` (`Parameterization::Type`): the
/// native type, so the two engines' answers compare directly.
pub use crate::bfr::ParameterizationType;

/// OpenSubdiv's `Bfr::Parameterization(scheme, face_size)`, with batched
/// queries: each sends any number of inputs to OpenSubdiv in one call.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OsdParameterization {
    /// The scheme.
    pub scheme: Scheme,
    /// The face's size, as asked for (OpenSubdiv's `GetFaceSize` is 0 for
    /// an invalid parameterization).
    pub face_size: usize,
    /// `IsValid`.
    pub is_valid: bool,
    /// `GetType` (for an invalid one, what OpenSubdiv stores: `Triangle`
    /// under Loop).
    pub kind: ParameterizationType,
    /// `HasSubFaces`.
    pub has_sub_faces: bool,
}

/// The inputs and outputs of one batch of `n` queries: for each query one
/// index, one `t`, two reals in, one index out and two reals out, as its kind
/// uses them (the others empty).
struct Query<'a, T> {
    kind: u32,
    n: usize,
    index: &'a [i32],
    t: &'a [T],
    uv_in: &'a [T],
    index_out: &'a mut [i32],
    uv_out: &'a mut [T],
}

fn or_null<T>(s: &[T]) -> *const T {
    if s.is_empty() { null() } else { s.as_ptr() }
}

fn or_null_mut<T>(s: &mut [T]) -> *mut T {
    if s.is_empty() {
        null_mut()
    } else {
        s.as_mut_ptr()
    }
}

impl<T> Query<'_, T> {
    /// Every non-empty buffer has exactly the length `n` queries use (empty
    /// ones go to the shim as null pointers, which it refuses where the
    /// kind needs them).
    fn check(&self) -> Result<()> {
        let n = self.n;
        let fits = |len: usize, per: usize| len == 0 || Some(len) == n.checked_mul(per);
        if fits(self.index.len(), 1)
            && fits(self.t.len(), 1)
            && fits(self.uv_in.len(), 2)
            && fits(self.index_out.len(), 1)
            && fits(self.uv_out.len(), 2)
        {
            Ok(())
        } else {
            Err(internal(
                "parameterization query buffers do not match the query count",
            ))
        }
    }
}

/// The shim's parameterization queries of one real type; private.
trait BfrReal: Sized {
    fn query(scheme: i32, face_size: i32, q: Query<'_, Self>, err: &mut ErrBuf) -> i32;
}

macro_rules! impl_bfr_real {
    ($t:ty, $f:ident) => {
        impl BfrReal for $t {
            fn query(scheme: i32, face_size: i32, q: Query<'_, Self>, err: &mut ErrBuf) -> i32 {
                if q.check().is_err() {
                    return ffi::SDV_ERR_CAPACITY;
                }
                // SAFETY: every non-null pointer comes from a buffer of the
                // length `n` queries read or write (checked above); the shim
                // refuses null ones the kind needs, and touches nothing else.
                unsafe {
                    ffi::$f(
                        scheme,
                        face_size,
                        q.kind as i32,
                        q.n,
                        or_null(q.index),
                        or_null(q.t),
                        or_null(q.uv_in),
                        or_null_mut(q.index_out),
                        or_null_mut(q.uv_out),
                        err.ptr(),
                        ERR_LEN,
                    )
                }
            }
        }
    };
}

impl_bfr_real!(f32, sdv_parameterization_query_f32);
impl_bfr_real!(f64, sdv_parameterization_query_f64);

impl OsdParameterization {
    /// `Bfr::Parameterization(scheme, face_size)`: its validity, type and
    /// sub-faces. A non-triangle under Loop is invalid (`is_valid` false).
    /// Refused: a face size outside 3..=65535, and under a quad scheme
    /// beyond 65025 (kind `Unsafe`: OpenSubdiv's sub-face grid width wraps
    /// to 0 and its coordinates divide by it).
    ///
    /// ```
    /// use subdiv::{Scheme, osd::bfr::{OsdParameterization, ParameterizationType}};
    /// let p = OsdParameterization::new(Scheme::Catmark, 5)?;
    /// assert_eq!(p.kind, ParameterizationType::QuadSubfaces);
    /// assert_eq!(p.vertex_coords::<f64>(&[4])?, vec![[1.0, 1.0]]);
    /// assert!(!OsdParameterization::new(Scheme::Loop, 4)?.is_valid);
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn new(scheme: Scheme, face_size: usize) -> Result<Self> {
        let n = to_i32(face_size, "face size")?;
        let mut info = ffi::sdv_param_info {
            is_valid: 0,
            type_: 0,
            has_sub_faces: 0,
            face_size: 0,
        };
        let mut err = ErrBuf::new();
        // SAFETY: `info` is written by the shim.
        err.run(|e| unsafe {
            ffi::sdv_parameterization_info(scheme.code(), n, &mut info, e, ERR_LEN)
        })?;
        let kind = match info.type_ {
            0 => ParameterizationType::Quad,
            1 => ParameterizationType::Triangle,
            2 => ParameterizationType::QuadSubfaces,
            _ => return Err(internal("unknown parameterization type")),
        };
        Ok(OsdParameterization {
            scheme,
            face_size,
            is_valid: info.is_valid != 0,
            kind,
            has_sub_faces: info.has_sub_faces != 0,
        })
    }

    fn run<T: Real>(&self, q: Query<'_, T>) -> Result<()> {
        q.check()?;
        // Out of i32's range: refused by the shim as beyond 65535.
        let face_size = i32::try_from(self.face_size).unwrap_or(i32::MAX);
        let mut err = ErrBuf::new();
        let status = with_shim_type!(T, |S| S::query(
            self.scheme.code(),
            face_size,
            Query::<S> {
                kind: q.kind,
                n: q.n,
                index: q.index,
                t: bytemuck::cast_slice(q.t),
                uv_in: bytemuck::cast_slice(q.uv_in),
                index_out: q.index_out,
                uv_out: bytemuck::cast_slice_mut(q.uv_out),
            },
            &mut err,
        ));
        err.check(status)
    }

    fn indices(values: impl Iterator<Item = usize>, what: &'static str) -> Result<Vec<i32>> {
        values.map(|v| to_i32(v, what)).collect()
    }

    /// `GetVertexCoord` of each of `vertices`. Refused: an invalid
    /// parameterization, a vertex beyond the face.
    pub fn vertex_coords<T: Real>(&self, vertices: &[usize]) -> Result<Vec<[T; 2]>> {
        let index = Self::indices(vertices.iter().copied(), "vertex index")?;
        let mut uv = try_vec([T::ZERO; 2], vertices.len())?;
        self.run::<T>(Query {
            kind: ffi::SDV_PARAM_VERTEX_COORD,
            n: vertices.len(),
            index: &index,
            t: &[],
            uv_in: &[],
            index_out: &mut [],
            uv_out: bytemuck::cast_slice_mut(&mut uv),
        })?;
        Ok(uv)
    }

    /// `GetEdgeCoord(edge, t)` of each `(edge, t)`. Refused: an invalid
    /// parameterization, an edge beyond the face, `t` not finite or beyond
    /// ±2^20.
    pub fn edge_coords<T: Real>(&self, edges: &[(usize, T)]) -> Result<Vec<[T; 2]>> {
        let index = Self::indices(edges.iter().map(|e| e.0), "edge index")?;
        let t: Vec<T> = edges.iter().map(|e| e.1).collect();
        let mut uv = try_vec([T::ZERO; 2], edges.len())?;
        self.run::<T>(Query {
            kind: ffi::SDV_PARAM_EDGE_COORD,
            n: edges.len(),
            index: &index,
            t: &t,
            uv_in: &[],
            index_out: &mut [],
            uv_out: bytemuck::cast_slice_mut(&mut uv),
        })?;
        Ok(uv)
    }

    /// `GetCenterCoord`. Refused: an invalid parameterization.
    pub fn center_coord<T: Real>(&self) -> Result<[T; 2]> {
        let mut uv = [T::ZERO; 2];
        self.run::<T>(Query {
            kind: ffi::SDV_PARAM_CENTER_COORD,
            n: 1,
            index: &[],
            t: &[],
            uv_in: &[],
            index_out: &mut [],
            uv_out: &mut uv,
        })?;
        Ok(uv)
    }

    /// `GetSubFace` of each coordinate (0 for every one without sub-faces;
    /// for coordinates off the face, whatever OpenSubdiv computes, possibly
    /// negative or beyond the face). Refused: an invalid parameterization, a
    /// coordinate not finite or beyond ±2^20.
    pub fn sub_faces<T: Real>(&self, coords: &[[T; 2]]) -> Result<Vec<i32>> {
        let mut out = try_vec(0i32, coords.len())?;
        self.run::<T>(Query {
            kind: ffi::SDV_PARAM_SUB_FACE,
            n: coords.len(),
            index: &[],
            t: &[],
            uv_in: bytemuck::cast_slice(coords),
            index_out: &mut out,
            uv_out: &mut [],
        })?;
        Ok(out)
    }

    /// `ConvertCoordToSubFace` (or, `normalized`,
    /// `ConvertCoordToNormalizedSubFace`) of each coordinate: its sub-face
    /// and the coordinate in it. Refused: an invalid parameterization, one
    /// without sub-faces, a coordinate not finite or beyond ±2^20.
    pub fn coords_to_sub_faces<T: Real>(
        &self,
        coords: &[[T; 2]],
        normalized: bool,
    ) -> Result<Vec<(i32, [T; 2])>> {
        let mut faces = try_vec(0i32, coords.len())?;
        let mut uv = try_vec([T::ZERO; 2], coords.len())?;
        self.run::<T>(Query {
            kind: if normalized {
                ffi::SDV_PARAM_COORD_TO_NORMALIZED_SUB_FACE
            } else {
                ffi::SDV_PARAM_COORD_TO_SUB_FACE
            },
            n: coords.len(),
            index: &[],
            t: &[],
            uv_in: bytemuck::cast_slice(coords),
            index_out: &mut faces,
            uv_out: bytemuck::cast_slice_mut(&mut uv),
        })?;
        Ok(faces.into_iter().zip(uv).collect())
    }

    /// `ConvertSubFaceToCoord` (or, `normalized`,
    /// `ConvertNormalizedSubFaceToCoord`) of each (sub-face, coordinate in
    /// it). Refused: an invalid parameterization, one without sub-faces, a
    /// sub-face beyond the face, a coordinate not finite or beyond ±2^20.
    pub fn sub_faces_to_coords<T: Real>(
        &self,
        sub: &[(usize, [T; 2])],
        normalized: bool,
    ) -> Result<Vec<[T; 2]>> {
        let index = Self::indices(sub.iter().map(|s| s.0), "sub-face index")?;
        let uv_in: Vec<[T; 2]> = sub.iter().map(|s| s.1).collect();
        let mut uv = try_vec([T::ZERO; 2], sub.len())?;
        self.run::<T>(Query {
            kind: if normalized {
                ffi::SDV_PARAM_NORMALIZED_SUB_FACE_TO_COORD
            } else {
                ffi::SDV_PARAM_SUB_FACE_TO_COORD
            },
            n: sub.len(),
            index: &index,
            t: &[],
            uv_in: bytemuck::cast_slice(&uv_in),
            index_out: &mut [],
            uv_out: bytemuck::cast_slice_mut(&mut uv),
        })?;
        Ok(uv)
    }
}
