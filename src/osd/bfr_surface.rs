//! OpenSubdiv's Bfr limit surfaces through the bridge (`cpp/bfr_surface.cpp`):
//! a `Bfr::RefinerSurfaceFactory<>` over OpenSubdiv's refiner of the mesh,
//! and a `Bfr::Surface<double>` built for one base face per call, evaluated
//! at all the call's coordinates at once ([`Surfaces`]).
//!
//! Coordinates are in the face's `Bfr::Parameterization`
//! ([`crate::bfr::Parameterization`]): the unit square for a quad of a quad
//! scheme, the unit triangle for a Loop triangle, and for any other face of
//! a quad scheme its sub-faces — a half-unit square at the corner of one
//! unit tile per vertex. Derivatives are with respect to those coordinates
//! (a sub-face's normalized ones for smooth n-gons; linear n-gons, under
//! the bilinear scheme and for linear face-varying data, take them in the
//! sub-face's own, twice as large — OpenSubdiv's convention).
//!
//! # Refused before OpenSubdiv sees them
//! As [`Error::Osd`] of kind `Refused` unless noted:
//! - a face or face-varying channel out of range, and a face without a
//!   limit surface (a hole; a face OpenSubdiv's `InitVertexSurface` returns
//!   false for, such as a boundary face under boundary interpolation
//!   `None`) when it is evaluated ([`Surfaces::face_info`] reports those as
//!   `valid: false` instead);
//! - coordinates that are not finite, or off the face's domain by more than
//!   1e-9: outside the unit square or triangle, or for an n-gon not on one
//!   of its sub-faces in the tile OpenSubdiv picks for it (its sub-face
//!   conversion takes the integer parts as the tile, the next tile where a
//!   fraction exceeds 0.75, and indexes the sub-faces' patches with that
//!   tile unchecked: a coordinate off the grid reads out of bounds);
//! - approximation levels beyond 10 (the patches of a face's refined
//!   neighbourhood hold 10 bits of u and v);
//! - kind `Unsafe`: a face of more than [`MAX_FACE_SIZE`] vertices, or with
//!   a corner vertex of more than [`MAX_VALENCE`] faces (Bfr keeps both in
//!   `short`s, and wraps);
//! - kind `Unsafe`: under a non-linear scheme, a face with an interior
//!   corner of valence 2 (two faces folded onto each other), a boundary or
//!   non-manifold corner and a sharp interior edge at one of its corners —
//!   for face-varying surfaces of non-linear channels without the boundary
//!   condition, as seams bound them. On such faces OpenSubdiv 3.5.0's
//!   `IrregularPatchBuilder::sharpenBoundaryControlEdges` writes the
//!   sharpened boundary edges over the sharp edges it gathered instead of
//!   after them, yet counts both, so the face's local refiner reads crease
//!   vertex indices from memory never written and looks edges up with
//!   them, out of bounds (fixed in 3.5.1, commit 51eb6a04). The test is
//!   conservative: it refuses some faces the fault spares.
//! - kind `Unsafe`: under a non-linear scheme, a face with an interior
//!   corner of valence 2 whose edge there is infinitely sharp (a dart) or,
//!   for face-varying surfaces, a seam. Beside such a corner a Gregory
//!   patch's ring names one source point past the patch's count, which
//!   `PatchTreeBuilder::getIrregularPatchConversion` writes past the end of
//!   its vector and reads back as a control point it is not (still so in
//!   3.6.0; docs/CONFORMANCE.md).
//!
//! # OpenSubdiv's caching and threads
//! The factory's topology cache is off: it is keyed by a 64-bit hash alone
//! (a collision would give a face another topology's patch, whose stencils
//! are sized for other control points) and is not thread-safe. Without it
//! the factory is only read, so [`Surfaces`] is `Send` and `Sync`, and every
//! call builds the face's surface anew.
//!
//! # A slip of OpenSubdiv's corrected
//! `PatchTree::EvalSubPatchStencils` (3.5.0 and after) passes its ∂²/∂u∂v
//! output twice, for ∂²/∂u∂v and ∂²/∂v², when an irregular surface is a
//! single regular interior patch: the ∂²/∂v² weights stay unwritten. The
//! bridge detects that and computes those two columns by evaluating the
//! surface on the control points' unit vectors — the stencil's definition.
//!
//! ```
//! use subdiv::{Options, bfr::SurfaceOptions, osd::bfr_surface::Surfaces, patches::Derivatives, shapes};
//! let cube = shapes::cube();
//! let s = Surfaces::new(&cube, &Options::default(), &SurfaceOptions::default())?;
//! let info = s.face_info(0)?;
//! assert!(info.valid && !info.regular);
//! let at = s.evaluate(0, &[[0.5, 0.5]], Derivatives::First)?;
//! assert_eq!((at.width, at.values.point.len(), at.values.du.len()), (3, 3, 3));
//! assert!(s.evaluate(0, &[[1.5, 0.5]], Derivatives::None).is_err());
//! # Ok::<(), subdiv::Error>(())
//! ```

use super::ERR_LEN;
use super::TopologyRefiner;
use super::ffi;
use super::shim::{ErrBuf, internal};
use crate::alloc::try_vec;
use crate::bfr::{FaceSurfaces, ParameterizationType, SurfaceOptions};
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::options::{Options, Scheme};
use crate::patches::{Derivatives, Partials, SurfaceSamples};
use std::ptr::{NonNull, null, null_mut};

/// The largest face the bridge builds a surface for (32,767 vertices): Bfr
/// keeps a face's size in a `short`.
pub const MAX_FACE_SIZE: usize = ffi::SDV_BFR_MAX_SURFACE_FACE_SIZE as usize;

/// The most faces a corner vertex of a face may have (16,383): Bfr keeps a
/// vertex's face count in a `short`, and numbers the 2 × valence face-edges
/// of a non-manifold vertex in `short`s.
pub const MAX_VALENCE: usize = ffi::SDV_BFR_MAX_SURFACE_VALENCE as usize;

const VERTEX: i32 = ffi::SDV_SURFACE_VERTEX as i32;
const VARYING: i32 = ffi::SDV_SURFACE_VARYING as i32;
const FACE_VARYING: i32 = ffi::SDV_SURFACE_FACE_VARYING as i32;

/// An OpenSubdiv `Bfr::RefinerSurfaceFactory<>`, owned.
#[derive(Debug)]
struct Handle(NonNull<ffi::sdv_surfaces>);

// SAFETY: the factory is only read after construction (its cache is off),
// it reads the refiner, which is only read too, and the shim keeps
// OpenSubdiv's error capture in thread-local storage.
unsafe impl Send for Handle {}
// SAFETY: see above.
unsafe impl Sync for Handle {}

impl Drop for Handle {
    fn drop(&mut self) {
        // SAFETY: created by sdv_surfaces_create, freed once here (before
        // the refiner it reads: see `Surfaces`' field order).
        unsafe { ffi::sdv_surfaces_destroy(self.0.as_ptr()) }
    }
}

/// The limit surfaces of a mesh's base faces as OpenSubdiv's Bfr builds
/// them (`Bfr::RefinerSurfaceFactory<>` and `Bfr::Surface<double>`), with
/// the mesh's positions and face-varying values to evaluate them on.
///
/// See the [module documentation](self) for what is refused and why.
#[derive(Debug)]
pub struct Surfaces {
    // Declared before `refiner`, so dropped first: the factory refers to it.
    handle: Handle,
    refiner: TopologyRefiner,
    scheme: Scheme,
    positions: Vec<f64>,
    /// Per face-varying channel: its values and width.
    fvar: Vec<(Vec<f64>, usize)>,
}

/// One face's surface, as `Bfr::Surface` describes it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SurfaceInfo {
    /// `IsValid`: the face has a limit surface (false for holes and faces
    /// OpenSubdiv finds none for; every other field is then empty or false
    /// but `kind`).
    pub valid: bool,
    /// `IsRegular`: a single regular patch (under Catmull-Clark a bicubic
    /// B-spline patch of 16 control points; also a linear face of the
    /// scheme's regular size).
    pub regular: bool,
    /// `IsLinear`: the bilinear scheme (or linear face-varying data).
    pub linear: bool,
    /// `GetControlPointIndices`: the mesh vertices the surface depends on,
    /// in Bfr's order (for a regular Catmull-Clark patch, the 4 × 4 grid row
    /// by row from the corner before the face's first vertex, with a
    /// boundary's missing points replaced by a duplicate).
    pub control_points: Vec<u32>,
    /// `GetNumPatchPoints`: the control points and the points computed from
    /// them to evaluate the surface.
    pub patch_points: usize,
    /// The type of `GetParameterization` (for an invalid surface, of the
    /// face's parameterization).
    pub kind: ParameterizationType,
}

fn index_i32(i: usize) -> i32 {
    // Beyond i32: refused by the shim as out of range (it counts in i32).
    i32::try_from(i).unwrap_or(i32::MAX)
}

fn columns(derivatives: Derivatives) -> (usize, i32) {
    match derivatives {
        Derivatives::None => (1, 0),
        Derivatives::First => (3, 1),
        Derivatives::Second => (6, 2),
    }
}

/// `out`'s pointer for the shim: null when empty (a count-only call).
fn out_ptr(out: &mut [f64]) -> *mut f64 {
    if out.is_empty() {
        null_mut()
    } else {
        out.as_mut_ptr()
    }
}

fn flat(coords: &[[f64; 2]]) -> *const f64 {
    let flat: &[f64] = bytemuck::cast_slice(coords);
    if flat.is_empty() {
        null()
    } else {
        flat.as_ptr()
    }
}

impl Surfaces {
    /// The surfaces of `mesh`'s faces under `options`, with
    /// `SurfaceFactory::Options` `SetApproxLevelSmooth` and
    /// `SetApproxLevelSharp` from `surface` and default face-varying channel
    /// 0 (caching off). The mesh is validated and OpenSubdiv's refiner built
    /// as [`TopologyRefiner::new`] does; approximation levels beyond 10 are
    /// refused.
    pub fn new(mesh: &Mesh, options: &Options, surface: &SurfaceOptions) -> Result<Self> {
        let refiner = TopologyRefiner::new(mesh, options)?;
        let level = |l: u32| i32::try_from(l).unwrap_or(i32::MAX);
        let mut raw: *mut ffi::sdv_surfaces = null_mut();
        let mut err = ErrBuf::new();
        // SAFETY: the refiner is live (it is moved into the result, its
        // C++ object stays put); `raw` is written by the shim.
        err.run(|e| unsafe {
            ffi::sdv_surfaces_create(
                refiner.raw.as_ptr(),
                level(surface.approx_level_smooth),
                level(surface.approx_level_sharp),
                &mut raw,
                e,
                ERR_LEN,
            )
        })?;
        let handle = NonNull::new(raw)
            .map(Handle)
            .ok_or_else(|| internal("the shim returned no surface factory"))?;
        Ok(Surfaces {
            handle,
            refiner,
            scheme: options.scheme,
            positions: mesh.flat_positions(),
            fvar: mesh
                .fvar_channels
                .iter()
                .map(|c| (c.values.clone(), c.width))
                .collect(),
        })
    }

    /// The subdivision scheme.
    pub fn scheme(&self) -> Scheme {
        self.scheme
    }

    /// The number of base faces (`GetNumFaces`).
    pub fn face_count(&self) -> usize {
        // SAFETY: the handle is live.
        let n = unsafe { ffi::sdv_surfaces_face_count(self.handle.0.as_ptr()) };
        usize::try_from(n).unwrap_or(0)
    }

    /// OpenSubdiv's refiner the surfaces are built over (its base level).
    pub fn refiner(&self) -> &TopologyRefiner {
        &self.refiner
    }

    /// Whether `face` has a vertex limit surface (`InitVertexSurface`
    /// succeeds); false for a face out of range or refused.
    pub fn has_surface(&self, face: usize) -> bool {
        self.face_info(face).is_ok_and(|i| i.valid)
    }

    fn info(
        &self,
        face: usize,
        kind: i32,
        channel: i32,
        points: &mut [i32],
    ) -> Result<ffi::sdv_surface_info> {
        let mut info = ffi::sdv_surface_info {
            is_valid: 0,
            is_regular: 0,
            is_linear: 0,
            num_control_points: 0,
            num_patch_points: 0,
            param_type: 0,
            face_size: 0,
        };
        let mut err = ErrBuf::new();
        // SAFETY: the handle is live; `info` and `points` (with its length)
        // are written by the shim, which writes no more than that length.
        err.run(|e| unsafe {
            ffi::sdv_surface_info_get(
                self.handle.0.as_ptr(),
                index_i32(face),
                kind,
                channel,
                &mut info,
                if points.is_empty() {
                    null_mut()
                } else {
                    points.as_mut_ptr()
                },
                points.len(),
                e,
                ERR_LEN,
            )
        })?;
        Ok(info)
    }

    /// The vertex surface of `face` (`InitVertexSurface`): whether it is
    /// valid, regular, linear, its control points, patch point count and
    /// parameterization. A hole is `valid: false`; a face out of range and
    /// the faces refused (see the [module documentation](self)) are errors.
    pub fn face_info(&self, face: usize) -> Result<SurfaceInfo> {
        self.surface_info(face, VERTEX, 0)
    }

    /// The surface of face-varying channel `channel` over `face`
    /// (`InitFaceVaryingSurface`), as [`Surfaces::face_info`] describes the
    /// vertex surface; its control points are the channel's values.
    pub fn fvar_face_info(&self, face: usize, channel: usize) -> Result<SurfaceInfo> {
        self.check_channel(channel)?;
        self.surface_info(face, FACE_VARYING, index_i32(channel))
    }

    fn check_channel(&self, channel: usize) -> Result<()> {
        if channel < self.fvar.len() {
            Ok(())
        } else {
            Err(Error::NoSuchChannel {
                channel,
                count: self.fvar.len(),
            })
        }
    }

    fn surface_info(&self, face: usize, kind: i32, channel: i32) -> Result<SurfaceInfo> {
        let mut points = vec![0i32; 64];
        let mut info = self.info(face, kind, channel, &mut points)?;
        let count = usize::try_from(info.num_control_points)
            .map_err(|_| internal("negative control point count"))?;
        if count > points.len() {
            points = try_vec(0i32, count)?;
            info = self.info(face, kind, channel, &mut points)?;
            if usize::try_from(info.num_control_points) != Ok(count) {
                return Err(internal("the face's surface changed between two calls"));
            }
        }
        let kind = match info.param_type {
            0 => ParameterizationType::Quad,
            1 => ParameterizationType::Triangle,
            2 => ParameterizationType::QuadSubfaces,
            _ => return Err(internal("unknown parameterization type")),
        };
        let control_points = points[..count]
            .iter()
            .map(|&p| u32::try_from(p).map_err(|_| internal("negative control point")))
            .collect::<Result<Vec<u32>>>()?;
        Ok(SurfaceInfo {
            valid: info.is_valid != 0,
            regular: info.is_regular != 0,
            linear: info.is_linear != 0,
            control_points,
            patch_points: usize::try_from(info.num_patch_points)
                .map_err(|_| internal("negative patch point count"))?,
            kind,
        })
    }

    #[allow(clippy::too_many_arguments)]
    fn run(
        &self,
        face: usize,
        kind: i32,
        channel: i32,
        points: &[f64],
        width: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        let (ncols, code) = columns(derivatives);
        let len = coords
            .len()
            .checked_mul(width)
            .ok_or_else(|| internal("output size overflows"))?;
        let mut cols: [Vec<f64>; 6] = Default::default();
        for col in cols.iter_mut().take(ncols) {
            *col = try_vec(0.0, len)?;
        }
        let mut out = [null_mut::<f64>(); 6];
        for (ptr, col) in out.iter_mut().zip(cols.iter_mut()).take(ncols) {
            if !col.is_empty() {
                *ptr = col.as_mut_ptr();
            }
        }
        let eval = ffi::sdv_surface_eval {
            kind,
            channel,
            points: if points.is_empty() {
                null()
            } else {
                points.as_ptr()
            },
            num_points: points.len() / width.max(1),
            width: i32::try_from(width).unwrap_or(i32::MAX),
            uv: flat(coords),
            n: coords.len(),
            derivatives: code,
            out,
            cap: len,
        };
        let mut err = ErrBuf::new();
        // SAFETY: the handle is live; `points` holds num_points * width
        // reals and `uv` 2 * n; each non-null output holds `cap` reals. The
        // shim checks the counts against the surface before reading or
        // writing.
        err.run(|e| unsafe {
            ffi::sdv_surface_evaluate(self.handle.0.as_ptr(), index_i32(face), &eval, e, ERR_LEN)
        })?;
        Ok(SurfaceSamples {
            width,
            values: Partials::from_columns(cols),
        })
    }

    /// The positions (3 components each) of `face`'s limit surface at
    /// `coords` in its parameterization, with the derivatives asked for
    /// (`InitVertexSurface`, `PreparePatchPoints` from the mesh's positions,
    /// `Evaluate` at every coordinate in one call).
    pub fn evaluate(
        &self,
        face: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        self.run(face, VERTEX, 0, &self.positions, 3, coords, derivatives)
    }

    /// Face-varying channel `channel`'s values over `face` at `coords`
    /// (`InitFaceVaryingSurface`), the channel's width each.
    pub fn evaluate_fvar(
        &self,
        face: usize,
        channel: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        let (values, width) = self.fvar.get(channel).ok_or(Error::NoSuchChannel {
            channel,
            count: self.fvar.len(),
        })?;
        self.run(
            face,
            FACE_VARYING,
            index_i32(channel),
            values,
            *width,
            coords,
            derivatives,
        )
    }

    /// The positions interpolated as varying data (`InitVaryingSurface`:
    /// linear over the face) at `coords`, 3 components each.
    pub fn evaluate_varying(&self, face: usize, coords: &[[f64; 2]]) -> Result<SurfaceSamples> {
        self.run(
            face,
            VARYING,
            0,
            &self.positions,
            3,
            coords,
            Derivatives::None,
        )
    }

    /// `PreparePatchPoints` of `face`'s vertex surface from the mesh's
    /// positions: its `GetNumPatchPoints` points, 3 reals each, in Bfr's
    /// order.
    pub fn patch_points(&self, face: usize) -> Result<Vec<f64>> {
        self.prepared(face, VERTEX, 0, &self.positions, 3)
    }

    /// `PreparePatchPoints` of face-varying channel `channel`'s surface
    /// over `face` from the channel's values: the channel's width each.
    pub fn fvar_patch_points(&self, face: usize, channel: usize) -> Result<Vec<f64>> {
        self.check_channel(channel)?;
        let (values, width) = &self.fvar[channel];
        self.prepared(face, FACE_VARYING, index_i32(channel), values, *width)
    }

    fn prepared(
        &self,
        face: usize,
        kind: i32,
        channel: i32,
        points: &[f64],
        width: usize,
    ) -> Result<Vec<f64>> {
        let eval = ffi::sdv_surface_eval {
            kind,
            channel,
            points: if points.is_empty() {
                null()
            } else {
                points.as_ptr()
            },
            num_points: points.len() / width.max(1),
            width: i32::try_from(width).unwrap_or(i32::MAX),
            uv: null(),
            n: 0,
            derivatives: 0,
            out: [null_mut(); 6],
            cap: 0,
        };
        let call = |out: &mut [f64]| -> Result<usize> {
            let mut count = 0i32;
            let mut err = ErrBuf::new();
            // SAFETY: the handle is live; `eval.points` holds num_points *
            // width reals; `out` is null (count only) or holds its length,
            // which the shim checks against what it writes.
            err.run(|e| unsafe {
                ffi::sdv_surface_patch_points(
                    self.handle.0.as_ptr(),
                    index_i32(face),
                    &eval,
                    out_ptr(out),
                    out.len(),
                    &mut count,
                    e,
                    ERR_LEN,
                )
            })?;
            usize::try_from(count).map_err(|_| internal("negative patch point count"))
        };
        let n = call(&mut [])?;
        let mut out = try_vec(
            0.0,
            n.checked_mul(width)
                .ok_or_else(|| internal("too many patch points"))?,
        )?;
        if call(&mut out)? != n {
            return Err(internal(
                "the surface's patch point count changed between two calls",
            ));
        }
        Ok(out)
    }

    /// The limit stencils of `face`'s vertex surface at `coords`
    /// (`Surface::EvaluateStencil`): one [`Partials`] per coordinate, each
    /// column asked for holding one weight per control point, in the order
    /// of [`SurfaceInfo::control_points`]. Applied to those points'
    /// positions they give [`Surfaces::evaluate`]'s values.
    pub fn evaluate_stencil(
        &self,
        face: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<Vec<Partials>> {
        self.stencils(face, VERTEX, 0, coords, derivatives)
    }

    /// The limit stencils of face-varying channel `channel`'s surface over
    /// `face` at `coords`: weights of its control points (the channel's
    /// values, in the order of [`Surfaces::fvar_face_info`]).
    pub fn evaluate_fvar_stencil(
        &self,
        face: usize,
        channel: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<Vec<Partials>> {
        self.check_channel(channel)?;
        self.stencils(face, FACE_VARYING, index_i32(channel), coords, derivatives)
    }

    fn stencils(
        &self,
        face: usize,
        kind: i32,
        channel: i32,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<Vec<Partials>> {
        let (ncols, code) = columns(derivatives);
        let call = |out: &mut [f64]| -> Result<usize> {
            let mut count = 0i32;
            let mut err = ErrBuf::new();
            // SAFETY: the handle is live; `uv` holds 2 * n reals; `out` is
            // null (count only) or holds its length, which the shim checks
            // against what it writes.
            err.run(|e| unsafe {
                ffi::sdv_surface_stencils(
                    self.handle.0.as_ptr(),
                    index_i32(face),
                    kind,
                    channel,
                    flat(coords),
                    coords.len(),
                    code,
                    out_ptr(out),
                    out.len(),
                    &mut count,
                    e,
                    ERR_LEN,
                )
            })?;
            usize::try_from(count).map_err(|_| internal("negative control point count"))
        };
        let ncp = call(&mut [])?;
        let row = ncols * ncp;
        let total = coords
            .len()
            .checked_mul(row)
            .ok_or_else(|| internal("stencil size overflows"))?;
        if total == 0 {
            return Ok(vec![Partials::default(); coords.len()]);
        }
        let mut weights = try_vec(0.0, total)?;
        if call(&mut weights)? != ncp {
            return Err(internal("the face's surface changed between two calls"));
        }
        Ok(weights
            .chunks_exact(row)
            .map(|w| {
                let mut cols: [Vec<f64>; 6] = Default::default();
                for (c, col) in cols.iter_mut().enumerate().take(ncols) {
                    *col = w[c * ncp..(c + 1) * ncp].to_vec();
                }
                Partials::from_columns(cols)
            })
            .collect())
    }
}

impl FaceSurfaces for Surfaces {
    fn scheme(&self) -> Scheme {
        self.scheme
    }
    /// A face the bridge refuses (a Bfr fault of OpenSubdiv 3.5.0) counts
    /// as one with a surface here, so that the mesher evaluates it and
    /// fails with the refusal instead of leaving the face out.
    fn has_surface(&self, face: usize) -> bool {
        match self.face_info(face) {
            Ok(info) => info.valid,
            Err(Error::Osd(_)) => face < self.face_count(),
            Err(_) => false,
        }
    }
    fn evaluate(
        &self,
        face: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        Surfaces::evaluate(self, face, coords, derivatives)
    }
    fn evaluate_fvar(
        &self,
        face: usize,
        channel: usize,
        coords: &[[f64; 2]],
    ) -> Result<SurfaceSamples> {
        Surfaces::evaluate_fvar(self, face, channel, coords, Derivatives::None)
    }
}
