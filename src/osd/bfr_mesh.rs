//! A whole mesh tessellated by OpenSubdiv's Bfr in one C++ call
//! (`cpp/bfr_mesh.cpp`): what a C++ program over OpenSubdiv runs to mesh a
//! limit surface watertight (the approach of OpenSubdiv's bfr tutorial 2_2),
//! with the rules of the native mesher [`crate::bfr::tessellate`], so that
//! the two can be compared point for point and timed against each other
//! ([`tessellate_mesh`]).
//!
//! The C++ side builds one `Bfr::RefinerSurfaceFactory<>` over OpenSubdiv's
//! refiner of the mesh (approximation levels from [`SurfaceOptions`],
//! default face-varying channel 0, its topology cache off — as in
//! [`Surfaces`](super::bfr_surface::Surfaces): the cache is keyed by a
//! 64-bit hash alone) and visits the faces in index order on one thread,
//! reusing one `Bfr::Surface<double>` (and one for texture coordinates):
//! - a face is skipped when `InitVertexSurface` (`InitSurfaces` with
//!   channel 0 when UVs are asked for) finds no limit surface: holes, and
//!   faces Bfr finds none for;
//! - its `Bfr::Tessellation` has one rate per edge: [`TessellateOptions::rate`],
//!   or with [`TessellateOptions::edge_length`] `L` each base edge's
//!   `1 + floor(|control edge| / L)`, at most 32,767; facet size 4 and
//!   `PreserveQuads` with [`TessellateOptions::quads`], else 3;
//! - each base vertex's point is created and evaluated
//!   (`Surface::Evaluate`) by the first face using it, each base edge's
//!   `rate - 1` inner points by the first face using the edge, in that
//!   face's direction — later faces walk them backwards when they traverse
//!   the edge the other way (base edges are told apart by their unordered
//!   pair of vertices, so non-manifold and inconsistently oriented edges
//!   stay watertight) — then the face's interior points;
//! - normals ([`TessellateOptions::normals`]) are `normalize(du × dv)`, zero
//!   where that is degenerate; texture coordinates ([`TessellateOptions::uvs`],
//!   when the mesh has a face-varying channel) are channel 0 evaluated at
//!   every coordinate of every face (`InitFaceVaryingSurface`'s surface),
//!   its first two components, each face indexing its own;
//! - facets are renumbered with `TransformFacetCoordIndices`, a triangle's
//!   `-1` among quads dropped.
//!
//! The result is the native mesher's [`TessellatedMesh`], index for index
//! (`tests/osd_bfr_mesh.rs` checks that over the corpus). Unlike the native
//! limit surfaces, Bfr's take Loop meshes, approximation levels of 0 and
//! face-varying channels interpolated smoothly.
//!
//! # Refused before OpenSubdiv sees them
//! As [`Error::Osd`](crate::Error::Osd) of kind `Refused` unless noted, all
//! before the first surface is built:
//! - what [`TopologyRefiner::new`] refuses; approximation levels beyond 10;
//! - a rate outside 1..=32,767 (OpenSubdiv clamps rates to 32,767), an edge
//!   length that is not positive and finite;
//! - every face that is not a hole which [`Surfaces`](super::bfr_surface::Surfaces)
//!   refuses to evaluate, for its vertex surface and, with UVs, its
//!   face-varying one (kind `Unsafe`: more than
//!   [`MAX_FACE_SIZE`](super::bfr_surface::MAX_FACE_SIZE) vertices, a corner
//!   of more than [`MAX_VALENCE`](super::bfr_surface::MAX_VALENCE) faces,
//!   OpenSubdiv 3.5.0's valence-2 fault) — the whole mesh, not just the face;
//! - a face whose pattern has more than [`MAX_COORDS`](super::bfr::MAX_COORDS)
//!   coordinates or [`MAX_FACETS`](super::bfr::MAX_FACETS) facets, as
//!   [`bfr::tessellate`](super::bfr::tessellate) refuses it;
//! - a mesh whose tessellation has more than [`MAX_POINTS`] points,
//!   [`MAX_FACETS`] facets or, with UVs, [`MAX_UVS`] texture coordinates
//!   (counted in 64 bits over every face but the holes, before any surface
//!   is built). The native mesher goes up to 2^31 points.
//!
//! OpenSubdiv's errors while building a surface are kind `Failed`.
//!
//! ```
//! use subdiv::bfr::{SurfaceOptions, TessellateOptions};
//! use subdiv::{Options, osd::bfr::tessellate_mesh, shapes};
//! let cube = shapes::cube();
//! let tess = TessellateOptions { rate: 3, quads: true, ..TessellateOptions::default() };
//! let t = tessellate_mesh(&cube, &Options::default(), &SurfaceOptions::default(), &tess)?;
//! // 8 corners, 2 points inside each of 12 edges, 4 inside each of 6 faces.
//! assert_eq!(t.positions.len(), 8 + 12 * 2 + 6 * 4);
//! assert_eq!(t.face_offsets.len() - 1, 6 * 9);
//! # Ok::<(), subdiv::Error>(())
//! ```

use super::ERR_LEN;
use super::TopologyRefiner;
use super::ffi;
use super::shim::{ErrBuf, internal};
use crate::Table;
use crate::bfr::{SurfaceOptions, TessellateOptions, TessellatedMesh};
use crate::error::Result;
use crate::mesh::Mesh;
use crate::options::Options;
use std::ptr::{NonNull, null, null_mut};

/// The most points a tessellated mesh through the bridge may have (2^25).
pub const MAX_POINTS: usize = ffi::SDV_BFR_MESH_MAX_POINTS as usize;

/// The most facets a tessellated mesh through the bridge may have (2^26).
pub const MAX_FACETS: usize = ffi::SDV_BFR_MESH_MAX_FACETS as usize;

/// The most texture coordinates a tessellated mesh through the bridge may
/// have (2^26; each face has its own, one per pattern coordinate).
pub const MAX_UVS: usize = ffi::SDV_BFR_MESH_MAX_UVS as usize;

/// The tessellated mesh the shim holds, owned.
struct Handle(NonNull<ffi::sdv_bfr_mesh>);

impl Drop for Handle {
    fn drop(&mut self) {
        // SAFETY: created by sdv_bfr_mesh_create, freed once here.
        unsafe { ffi::sdv_bfr_mesh_destroy(self.0.as_ptr()) }
    }
}

fn saturating_i32(n: u32) -> i32 {
    i32::try_from(n).unwrap_or(i32::MAX)
}

fn out_ptr<T>(v: &mut [T]) -> *mut T {
    if v.is_empty() {
        null_mut()
    } else {
        v.as_mut_ptr()
    }
}

/// `mesh` tessellated by OpenSubdiv's Bfr in one C++ call, with the native
/// mesher's rules: the same [`TessellatedMesh`] as
/// [`crate::bfr::tessellate`]`(mesh, &LimitSurfaces::new(mesh, options, surface)?, tess)`
/// gives, computed by OpenSubdiv alone (see the [module documentation](self)
/// for what it runs and what it refuses).
pub fn tessellate_mesh(
    mesh: &Mesh,
    options: &Options,
    surface: &SurfaceOptions,
    tess: &TessellateOptions,
) -> Result<TessellatedMesh> {
    let refiner = TopologyRefiner::new(mesh, options)?;
    let positions: &[f64] = bytemuck::cast_slice(&mesh.positions);
    let uv = mesh.fvar_channels.first().filter(|_| tess.uvs);
    let input = ffi::sdv_bfr_mesh_input {
        positions: if positions.is_empty() {
            null()
        } else {
            positions.as_ptr()
        },
        num_vertices: mesh.positions.len(),
        // Never null for a channel (an empty Vec's pointer is dangling,
        // and the shim reads none of its values then): null means no UVs.
        uvs: uv.map_or(null(), |c| c.values.as_ptr()),
        num_uv_values: uv.map_or(0, |c| c.value_count()),
        uv_width: uv.map_or(0, |c| i32::try_from(c.width).unwrap_or(i32::MAX)),
        approx_level_smooth: saturating_i32(surface.approx_level_smooth),
        approx_level_sharp: saturating_i32(surface.approx_level_sharp),
        rate: saturating_i32(tess.rate),
        use_edge_length: tess.edge_length.is_some().into(),
        edge_length: tess.edge_length.unwrap_or(0.0),
        quads: tess.quads.into(),
        normals: tess.normals.into(),
    };
    let mut raw: *mut ffi::sdv_bfr_mesh = null_mut();
    let mut err = ErrBuf::new();
    // SAFETY: the refiner is live; `positions` holds num_vertices * 3 reals
    // and `uvs` (when not null) num_uv_values * uv_width, both borrowed
    // from `mesh` for the call; `raw` is written by the shim.
    err.run(|e| unsafe {
        ffi::sdv_bfr_mesh_create(refiner.raw.as_ptr(), &input, &mut raw, e, ERR_LEN)
    })?;
    let handle = NonNull::new(raw)
        .map(Handle)
        .ok_or_else(|| internal("the shim returned no tessellated mesh"))?;
    let mut c = ffi::sdv_bfr_mesh_counts {
        num_points: 0,
        num_normals: 0,
        num_facets: 0,
        num_face_vertices: 0,
        num_uvs: 0,
        num_uv_indices: 0,
    };
    // SAFETY: the handle is live; `c` is written by the shim.
    unsafe { ffi::sdv_bfr_mesh_counts_get(handle.0.as_ptr(), &mut c) };
    // Every value is written by the shim (it checks the counts first).
    let mut out = TessellatedMesh {
        positions: Table::for_overwrite(c.num_points),
        normals: Table::for_overwrite(c.num_normals),
        face_offsets: Table::for_overwrite(c.num_facets + 1),
        face_vertices: Table::for_overwrite(c.num_face_vertices),
        uvs: Table::for_overwrite(2 * c.num_uvs),
        uv_indices: Table::for_overwrite(c.num_uv_indices),
        facet_faces: Table::for_overwrite(c.num_facets),
    };
    let positions: &mut [f64] = bytemuck::cast_slice_mut(&mut out.positions);
    let normals: &mut [f64] = bytemuck::cast_slice_mut(&mut out.normals);
    let data = ffi::sdv_bfr_mesh_data {
        positions_cap: positions.len(),
        positions: out_ptr(positions),
        normals_cap: normals.len(),
        normals: out_ptr(normals),
        face_offsets_cap: out.face_offsets.len(),
        face_offsets: out_ptr(&mut out.face_offsets),
        face_vertices_cap: out.face_vertices.len(),
        face_vertices: out_ptr(&mut out.face_vertices),
        uvs_cap: out.uvs.len(),
        uvs: out_ptr(&mut out.uvs),
        uv_indices_cap: out.uv_indices.len(),
        uv_indices: out_ptr(&mut out.uv_indices),
        facet_faces_cap: out.facet_faces.len(),
        facet_faces: out_ptr(&mut out.facet_faces),
    };
    // SAFETY: the handle is live; every buffer holds the capacity passed
    // beside it, which the shim checks against the mesh's counts before it
    // writes anything.
    err.run(|e| unsafe { ffi::sdv_bfr_mesh_read(handle.0.as_ptr(), &data, e, ERR_LEN) })?;
    Ok(out)
}
