//! [`TopologyRefiner`]: OpenSubdiv's `Far::TopologyRefiner` and
//! `Far::PrimvarRefiner`, owned and called safely.

use super::ffi;
use super::shim::{ErrBuf, ShimReal, check_length, internal, to_i32, with_shim_type};
use super::{ERR_LEN, SDV_FACE_VARYING, SDV_VARYING, SDV_VERTEX};
use crate::alloc::try_vec;
use crate::error::{Buffer, Error, OsdError, OsdErrorKind, Result};
use crate::mesh::Mesh;
use crate::options::{AdaptiveOptions, Options, UniformOptions};
use crate::output::LimitData;
use crate::output::{FVarTopology, LevelCounts, LevelTopology};
use crate::real::{Precision, Real};
use std::ffi::CStr;
use std::os::raw::c_char;
use std::ptr::NonNull;

/// An OpenSubdiv `Far::TopologyRefiner`, owned.
#[derive(Debug)]
pub struct TopologyRefiner {
    pub(super) raw: NonNull<ffi::sdv_refiner>,
    pub(super) base_vertices: usize,
    pub(super) base_faces: usize,
    pub(super) base_corners: usize,
    pub(super) options: Options,
    pub(super) fvar_channels: usize,
    pub(super) uniform: Option<UniformOptions>,
    /// The options of an adaptive refinement (`refine_adaptive`), if any.
    pub(super) adaptive: Option<AdaptiveOptions>,
    /// OpenSubdiv's ptex indices of the base level, read on first use.
    pub(super) ptex: std::sync::OnceLock<crate::ptex::PtexIndices>,
    pub(super) warnings: Vec<String>,
}

// SAFETY: the refiner is only mutated through `&mut self` (refine_uniform,
// refine_adaptive); every `&self` call is a read-only use of OpenSubdiv's
// TopologyRefiner, which OpenSubdiv supports from several threads, the shim
// keeps its error capture in thread-local storage, and it builds its ptex
// indices once under std::call_once.
unsafe impl Send for TopologyRefiner {}
// SAFETY: see above.
unsafe impl Sync for TopologyRefiner {}

impl Drop for TopologyRefiner {
    fn drop(&mut self) {
        // SAFETY: `raw` came from sdv_refiner_create and is freed exactly once.
        unsafe { ffi::sdv_refiner_destroy(self.raw.as_ptr()) }
    }
}

impl TopologyRefiner {
    /// Builds OpenSubdiv's refiner for a mesh (level 0 only).
    ///
    /// The mesh is validated first ([`Mesh::validate`]), and a mesh without
    /// faces is [`Error::EmptyMesh`], as in the native engine; the shim checks
    /// every index again before OpenSubdiv sees it. Warnings of either are
    /// kept in [`TopologyRefiner::warnings`].
    pub fn new(mesh: &Mesh, options: &Options) -> Result<TopologyRefiner> {
        let validation = mesh.validate()?;
        if mesh.face_count() == 0 {
            return Err(Error::EmptyMesh);
        }
        Self::build(
            mesh,
            options,
            validation
                .warnings
                .iter()
                .map(ToString::to_string)
                .collect(),
        )
    }

    /// Builds the refiner without validating the mesh in Rust first, relying on
    /// the shim's own range checks (which still refuse every bad index). This
    /// exists to test those checks; prefer [`TopologyRefiner::new`].
    #[doc(hidden)]
    pub fn new_unvalidated(mesh: &Mesh, options: &Options) -> Result<TopologyRefiner> {
        if mesh.face_offsets.first() != Some(&0)
            || mesh.face_offsets.windows(2).any(|w| w[1] < w[0])
            || mesh.face_offsets.last().map(|&l| l as usize) != Some(mesh.face_vertices.len())
            || mesh
                .fvar_channels
                .iter()
                .any(|c| c.width == 0 || c.indices.len() != mesh.face_vertices.len())
        {
            return Err(Error::Osd(OsdError {
                kind: OsdErrorKind::Refused,
                message: "malformed face offsets or face-varying channel".into(),
            }));
        }
        Self::build(mesh, options, Vec::new())
    }

    fn build(mesh: &Mesh, options: &Options, warnings: Vec<String>) -> Result<TopologyRefiner> {
        let face_sizes: Vec<i32> = mesh.face_sizes().into_iter().map(|s| s as i32).collect();
        let face_vertices: Vec<i32> = mesh.face_vertices.iter().map(|&v| v as i32).collect();
        let crease_pairs: Vec<i32> = mesh
            .creases
            .iter()
            .flat_map(|c| [c.vertices[0] as i32, c.vertices[1] as i32])
            .collect();
        let crease_sharpness: Vec<f32> = mesh.creases.iter().map(|c| c.sharpness).collect();
        let corner_vertices: Vec<i32> = mesh.corners.iter().map(|c| c.vertex as i32).collect();
        let corner_sharpness: Vec<f32> = mesh.corners.iter().map(|c| c.sharpness).collect();
        let holes: Vec<i32> = mesh.holes.iter().map(|&f| f as i32).collect();
        let fvar_indices: Vec<Vec<i32>> = mesh
            .fvar_channels
            .iter()
            .map(|c| c.indices.iter().map(|&i| i as i32).collect())
            .collect();
        let mut channels = Vec::with_capacity(mesh.fvar_channels.len());
        for (c, idx) in mesh.fvar_channels.iter().zip(&fvar_indices) {
            channels.push(ffi::sdv_fvar_channel {
                num_values: to_i32(c.value_count(), "face-varying values")?,
                value_indices: idx.as_ptr(),
            });
        }
        let desc = ffi::sdv_mesh_desc {
            num_vertices: to_i32(mesh.vertex_count(), "vertices")?,
            num_faces: to_i32(mesh.face_count(), "faces")?,
            face_sizes: face_sizes.as_ptr(),
            face_vertices: face_vertices.as_ptr(),
            num_creases: to_i32(mesh.creases.len(), "creases")?,
            crease_vertex_pairs: crease_pairs.as_ptr(),
            crease_sharpness: crease_sharpness.as_ptr(),
            num_corners: to_i32(mesh.corners.len(), "corners")?,
            corner_vertices: corner_vertices.as_ptr(),
            corner_sharpness: corner_sharpness.as_ptr(),
            num_holes: to_i32(holes.len(), "holes")?,
            holes: holes.as_ptr(),
            num_fvar_channels: to_i32(channels.len(), "face-varying channels")?,
            fvar_channels: channels.as_ptr(),
            is_left_handed: i32::from(mesh.left_handed),
        };
        let opts = ffi::sdv_options {
            scheme: options.scheme.code(),
            boundary: options.boundary.code(),
            fvar: options.fvar.code(),
            creasing: options.creasing.code(),
            triangles: options.triangles.code(),
        };
        let mut raw: *mut ffi::sdv_refiner = std::ptr::null_mut();
        let mut err = ErrBuf::new();
        // SAFETY: every pointer in `desc` points into a Vec that outlives the
        // call, with the lengths the counts state (the shim copies what it keeps).
        let status = unsafe { ffi::sdv_refiner_create(&desc, &opts, &mut raw, err.ptr(), ERR_LEN) };
        err.check(status)?;
        let raw = NonNull::new(raw).ok_or_else(|| internal("the shim returned no refiner"))?;
        let mut refiner = TopologyRefiner {
            raw,
            base_vertices: mesh.vertex_count(),
            base_faces: mesh.face_count(),
            base_corners: mesh.face_vertices.len(),
            options: *options,
            fvar_channels: mesh.fvar_channels.len(),
            uniform: None,
            adaptive: None,
            ptex: std::sync::OnceLock::new(),
            warnings,
        };
        refiner.warnings.extend(refiner.osd_warnings());
        Ok(refiner)
    }

    fn osd_warnings(&self) -> Vec<String> {
        let mut needed = 0usize;
        // SAFETY: a null buffer asks only for the size.
        unsafe {
            ffi::sdv_refiner_warnings(self.raw.as_ptr(), std::ptr::null_mut(), 0, &mut needed)
        };
        let mut buf = vec![0 as c_char; needed.max(1)];
        // SAFETY: the buffer holds `needed` bytes, as the shim asked.
        unsafe {
            ffi::sdv_refiner_warnings(self.raw.as_ptr(), buf.as_mut_ptr(), buf.len(), &mut needed)
        };
        // SAFETY: the shim NUL-terminates within the buffer.
        let text = unsafe { CStr::from_ptr(buf.as_ptr()) }
            .to_string_lossy()
            .into_owned();
        text.lines()
            .filter(|l| !l.is_empty())
            .map(|l| format!("OpenSubdiv: {l}"))
            .collect()
    }

    /// Warnings about the mesh: ours (from validation) and OpenSubdiv's.
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// The options the refiner was built with.
    pub fn options(&self) -> &Options {
        &self.options
    }

    /// Number of vertices of the base mesh.
    pub fn base_vertex_count(&self) -> usize {
        self.base_vertices
    }

    /// Number of face corners of the base mesh.
    pub fn base_corner_count(&self) -> usize {
        self.base_corners
    }

    /// Refines uniformly to `uniform.level` (any earlier refinement, uniform
    /// or adaptive, is discarded first).
    pub fn refine_uniform(&mut self, uniform: UniformOptions) -> Result<()> {
        // Validate the level ourselves: OpenSubdiv would silently wrap it, and
        // refuse sizes that cannot fit before anything is allocated.
        crate::limits::check_level_counts(
            self.base_faces,
            self.base_corners,
            self.options.scheme,
            uniform.level,
        )?;
        let mut err = ErrBuf::new();
        self.uniform = None;
        self.adaptive = None;
        // SAFETY: `raw` is live and uniquely borrowed.
        let status = unsafe {
            ffi::sdv_refiner_refine_uniform(
                self.raw.as_ptr(),
                uniform.level as i32,
                uniform.order_vertices_from_faces_first as i32,
                uniform.full_topology_in_last_level as i32,
                err.ptr(),
                ERR_LEN,
            )
        };
        err.check(status)?;
        self.uniform = Some(uniform);
        Ok(())
    }

    /// The options of the last uniform refinement, if the refiner is refined
    /// uniformly.
    pub fn uniform_options(&self) -> Option<UniformOptions> {
        self.uniform
    }

    /// The options of the adaptive refinement, if the refiner is refined
    /// adaptively ([`TopologyRefiner::refine_adaptive`]).
    pub fn adaptive_options(&self) -> Option<AdaptiveOptions> {
        self.adaptive
    }

    /// The deepest refined level (0 before refinement; after adaptive
    /// refinement possibly less than the isolation level).
    pub fn max_level(&self) -> u32 {
        // SAFETY: `raw` is live.
        unsafe { ffi::sdv_refiner_max_level(self.raw.as_ptr()).max(0) as u32 }
    }

    /// Number of face-varying channels.
    pub fn fvar_channel_count(&self) -> usize {
        self.fvar_channels
    }

    /// Element counts of `level`.
    pub fn level_counts(&self, level: u32) -> Result<LevelCounts> {
        if level > self.max_level() {
            return Err(Error::NoSuchLevel {
                level,
                first: 0,
                last: self.max_level(),
            });
        }
        let mut c = ffi::sdv_level_counts {
            vertices: 0,
            edges: 0,
            faces: 0,
            face_vertices: 0,
            full_topology: 0,
        };
        let mut err = ErrBuf::new();
        // SAFETY: `raw` is live; `c` is a valid output struct.
        let status = unsafe {
            ffi::sdv_level_counts_get(self.raw.as_ptr(), level as i32, &mut c, err.ptr(), ERR_LEN)
        };
        err.check(status)?;
        Ok(LevelCounts {
            vertices: c.vertices as usize,
            edges: c.edges as usize,
            faces: c.faces as usize,
            face_vertices: c.face_vertices as usize,
            full_topology: c.full_topology != 0,
        })
    }

    /// The whole topology of `level`, face-varying channels included.
    pub fn level(&self, level: u32) -> Result<LevelTopology> {
        crate::alloc::guard(Some(level), || {
            let counts = self.level_counts(level)?;
            let r = self.raw.as_ptr();
            let l = level as i32;
            let mut err = ErrBuf::new();

            let mut sizes = try_vec(0i32, counts.faces)?;
            let mut verts = try_vec(0i32, counts.face_vertices)?;
            // SAFETY: each buffer is passed with its true length; the shim checks
            // the lengths against its counts before writing.
            err.run(|e| unsafe {
                ffi::sdv_level_faces(
                    r,
                    l,
                    sizes.as_mut_ptr(),
                    sizes.len(),
                    verts.as_mut_ptr(),
                    verts.len(),
                    e,
                    ERR_LEN,
                )
            })?;
            let mut edges = try_vec(
                0i32,
                if counts.full_topology {
                    2 * counts.edges
                } else {
                    0
                },
            )?;
            if counts.full_topology {
                // SAFETY: as above.
                err.run(|e| unsafe {
                    ffi::sdv_level_edge_vertices(r, l, edges.as_mut_ptr(), edges.len(), e, ERR_LEN)
                })?;
            }
            let mut edge_sharpness = try_vec(0f32, counts.edges)?;
            // SAFETY: as above.
            err.run(|e| unsafe {
                ffi::sdv_level_edge_sharpness(
                    r,
                    l,
                    edge_sharpness.as_mut_ptr(),
                    edge_sharpness.len(),
                    e,
                    ERR_LEN,
                )
            })?;
            let mut vertex_sharpness = try_vec(0f32, counts.vertices)?;
            // SAFETY: as above.
            err.run(|e| unsafe {
                ffi::sdv_level_vertex_sharpness(
                    r,
                    l,
                    vertex_sharpness.as_mut_ptr(),
                    vertex_sharpness.len(),
                    e,
                    ERR_LEN,
                )
            })?;
            let mut holes = try_vec(0u8, counts.faces)?;
            // SAFETY: as above.
            err.run(|e| unsafe {
                ffi::sdv_level_face_holes(r, l, holes.as_mut_ptr(), holes.len(), e, ERR_LEN)
            })?;

            let mut fvar = Vec::with_capacity(self.fvar_channels);
            for channel in 0..self.fvar_channels as i32 {
                let mut value_count = 0i32;
                // SAFETY: as above.
                err.run(|e| unsafe {
                    ffi::sdv_level_fvar_value_count(r, l, channel, &mut value_count, e, ERR_LEN)
                })?;
                let mut values = try_vec(0i32, counts.face_vertices)?;
                // SAFETY: as above.
                err.run(|e| unsafe {
                    ffi::sdv_level_fvar_face_values(
                        r,
                        l,
                        channel,
                        values.as_mut_ptr(),
                        values.len(),
                        e,
                        ERR_LEN,
                    )
                })?;
                fvar.push(FVarTopology {
                    value_count: value_count as usize,
                    face_values: values.into_iter().map(|v| v as u32).collect(),
                });
            }

            let mut face_offsets = Vec::new();
            crate::alloc::reserve(&mut face_offsets, counts.faces + 1)?;
            face_offsets.push(0u32);
            let mut acc = 0u32;
            for s in &sizes {
                acc += *s as u32;
                face_offsets.push(acc);
            }
            Ok(LevelTopology {
                vertex_count: counts.vertices,
                edge_count: counts.edges,
                face_offsets,
                face_vertices: verts.into_iter().map(|v| v as u32).collect(),
                edge_vertices: crate::alloc::collect_n(
                    edges.len() / 2,
                    edges.chunks_exact(2).map(|e| [e[0] as u32, e[1] as u32]),
                ),
                edge_sharpness,
                vertex_sharpness,
                face_holes: holes.into_iter().map(|h| h != 0).collect(),
                fvar,
            })
        })
    }

    /// The number of values of face-varying `channel` at `level`.
    fn fvar_value_count(&self, level: u32, channel: usize) -> Result<usize> {
        let mut count = 0i32;
        let mut err = ErrBuf::new();
        let channel = to_i32(channel, "face-varying channels")?;
        // SAFETY: the refiner is live; the shim range-checks level and channel.
        err.run(|e| unsafe {
            ffi::sdv_level_fvar_value_count(
                self.raw.as_ptr(),
                level as i32,
                channel,
                &mut count,
                e,
                ERR_LEN,
            )
        })?;
        Ok(count.max(0) as usize)
    }

    fn interpolate_kind<T: Real>(
        &self,
        kind: i32,
        channel: usize,
        level: u32,
        width: usize,
        src: &[T],
    ) -> Result<Vec<T>> {
        crate::limits::check_interpolation_call(level, self.max_level(), width)?;
        // Element counts of the level read from and the level written.
        let (from, to) = if kind == SDV_FACE_VARYING {
            if channel >= self.fvar_channels {
                return Err(Error::NoSuchChannel {
                    channel,
                    count: self.fvar_channels,
                });
            }
            (
                self.fvar_value_count(level - 1, channel)?,
                self.fvar_value_count(level, channel)?,
            )
        } else {
            (
                self.level_counts(level - 1)?.vertices,
                self.level_counts(level)?.vertices,
            )
        };
        let buffer = if kind == SDV_FACE_VARYING {
            Buffer::FaceVaryingSource
        } else {
            Buffer::Source
        };
        check_length(buffer, from * width, src.len())?;
        let mut dst = try_vec(T::default(), to * width)?;
        let mut err = ErrBuf::new();
        let (channel, width) = (
            to_i32(channel, "face-varying channels")?,
            to_i32(width, "primvar components")?,
        );
        let status = with_shim_type!(T, |S| S::interpolate(
            self,
            kind,
            channel,
            level as i32,
            width,
            bytemuck::cast_slice(src),
            bytemuck::cast_slice_mut(&mut dst),
            &mut err,
        ));
        err.check(status)?;
        Ok(dst)
    }

    /// Interpolates vertex data of `width` components from level `level - 1`
    /// to `level` (`PrimvarRefiner::Interpolate`).
    pub fn interpolate<T: Real>(&self, level: u32, width: usize, src: &[T]) -> Result<Vec<T>> {
        self.interpolate_kind(SDV_VERTEX, 0, level, width, src)
    }

    /// Interpolates varying data (linearly) from level `level - 1` to `level`
    /// (`PrimvarRefiner::InterpolateVarying`).
    pub fn interpolate_varying<T: Real>(
        &self,
        level: u32,
        width: usize,
        src: &[T],
    ) -> Result<Vec<T>> {
        self.interpolate_kind(SDV_VARYING, 0, level, width, src)
    }

    /// Interpolates the values of face-varying `channel` from level `level - 1`
    /// to `level` (`PrimvarRefiner::InterpolateFaceVarying`).
    pub fn interpolate_face_varying<T: Real>(
        &self,
        channel: usize,
        level: u32,
        width: usize,
        src: &[T],
    ) -> Result<Vec<T>> {
        self.interpolate_kind(SDV_FACE_VARYING, channel, level, width, src)
    }

    /// Interpolates vertex data through every level: `result[l]` is level `l`
    /// (`result[0]` is a copy of `base`).
    pub fn interpolate_all<T: Real>(&self, width: usize, base: &[T]) -> Result<Vec<Vec<T>>> {
        let mut out = vec![base.to_vec()];
        for level in 1..=self.max_level() {
            let next = self.interpolate(level, width, out.last().expect("non-empty"))?;
            out.push(next);
        }
        Ok(out)
    }

    /// Interpolates vertex data through every level and returns the last
    /// level's only, holding no more than two levels at a time.
    pub fn interpolate_last<T: Real>(&self, width: usize, base: &[T]) -> Result<Vec<T>> {
        let mut current = base.to_vec();
        for level in 1..=self.max_level() {
            current = self.interpolate(level, width, &current)?;
        }
        Ok(current)
    }

    /// Limit values and both tangents at the vertices of the last level, from
    /// data at that level (`PrimvarRefiner::Limit`). Needs full topology in the
    /// last level (or no refinement at all).
    pub fn limit<T: Real>(&self, width: usize, src: &[T]) -> Result<LimitData<T>> {
        if width == 0 {
            return Err(Error::ZeroWidth);
        }
        let last = self.level_counts(self.max_level())?;
        if self.max_level() > 0 && !last.full_topology {
            return Err(Error::NeedsFullTopology);
        }
        let n = last.vertices * width;
        check_length(Buffer::Source, n, src.len())?;
        let (mut positions, mut du, mut dv) = (
            try_vec(T::default(), n)?,
            try_vec(T::default(), n)?,
            try_vec(T::default(), n)?,
        );
        let mut err = ErrBuf::new();
        let width = to_i32(width, "primvar components")?;
        let status = with_shim_type!(T, |S| S::limit(
            self,
            width,
            bytemuck::cast_slice(src),
            [
                bytemuck::cast_slice_mut(&mut positions),
                bytemuck::cast_slice_mut(&mut du),
                bytemuck::cast_slice_mut(&mut dv),
            ],
            &mut err,
        ));
        err.check(status)?;
        // The vectors become the values without a copy.
        Ok(LimitData {
            positions: positions.into(),
            du: du.into(),
            dv: dv.into(),
        })
    }

    /// Limit values of face-varying `channel` at the last level
    /// (`PrimvarRefiner::LimitFaceVarying`).
    pub fn limit_face_varying<T: Real>(
        &self,
        channel: usize,
        width: usize,
        src: &[T],
    ) -> Result<Vec<T>> {
        if channel >= self.fvar_channels {
            return Err(Error::NoSuchChannel {
                channel,
                count: self.fvar_channels,
            });
        }
        if width == 0 {
            return Err(Error::ZeroWidth);
        }
        if self.max_level() > 0 && !self.level_counts(self.max_level())?.full_topology {
            return Err(Error::NeedsFullTopology);
        }
        let n = self.fvar_value_count(self.max_level(), channel)? * width;
        check_length(Buffer::FaceVaryingSource, n, src.len())?;
        let mut dst = try_vec(T::default(), n)?;
        let mut err = ErrBuf::new();
        let (channel, width) = (
            to_i32(channel, "face-varying channels")?,
            to_i32(width, "primvar components")?,
        );
        let status = with_shim_type!(T, |S| S::limit_fvar(
            self,
            channel,
            width,
            bytemuck::cast_slice(src),
            bytemuck::cast_slice_mut(&mut dst),
            &mut err,
        ));
        err.check(status)?;
        Ok(dst)
    }
}
