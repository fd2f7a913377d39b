//! The OpenSubdiv engine: a safe wrapper over the C shim in `cpp/`.
//!
//! This is the only module of the crate with `unsafe` code. Every call goes
//! through [`TopologyRefiner`], which owns the C++ `Far::TopologyRefiner` and frees it
//! on drop; slices go in, `Vec`s come out, and every failure is an [`Error`].
//!
//! ```
//! use subdiv::{osd, shapes, Options, UniformOptions};
//! let mesh = shapes::cube();
//! let mut refiner = osd::TopologyRefiner::new(&mesh, &Options::default())?;
//! refiner.refine_uniform(UniformOptions::new(1))?;
//! let level1 = refiner.level(1)?;
//! assert_eq!((level1.vertex_count, level1.face_count()), (26, 24));
//! # Ok::<(), subdiv::Error>(())
//! ```
//!
//! # Threads
//! A [`TopologyRefiner`] is `Send` and `Sync`: every query and interpolation is a
//! read-only use of OpenSubdiv's refiner (as OpenSubdiv itself allows from
//! several threads), and only [`TopologyRefiner::refine_uniform`] mutates it, which
//! needs `&mut self`. OpenSubdiv's error messages are captured per thread.

use crate::error::{Buffer, Error, OsdError, OsdErrorKind, Result};
use crate::limits::check_level;
use crate::mesh::Mesh;
use crate::options::Request;
use crate::options::{Options, UniformOptions};
pub use crate::output::LimitData;
use crate::output::{FVarTopology, LevelTopology};
use crate::output::{Limit, Refinement};
use crate::real::{Precision, Real};
use crate::stencil::{LimitStencilTable, StencilTable};
use glam::DVec3;
use std::ffi::CStr;
use std::os::raw::c_char;
use std::ptr::NonNull;

#[allow(
    non_camel_case_types,
    non_upper_case_globals,
    non_snake_case,
    dead_code,
    missing_docs,
    clippy::all
)]
mod ffi {
    include!(concat!(env!("OUT_DIR"), "/shim_bindings.rs"));
}

const ERR_LEN: usize = 1024;
const SDV_VERTEX: i32 = ffi::SDV_VERTEX as i32;
const SDV_VARYING: i32 = ffi::SDV_VARYING as i32;
const SDV_FACE_VARYING: i32 = ffi::SDV_FACE_VARYING as i32;
const SDV_STENCIL_REFINED: i32 = ffi::SDV_STENCIL_REFINED as i32;
const SDV_STENCIL_LIMIT: i32 = ffi::SDV_STENCIL_LIMIT as i32;

use shim::{ErrBuf, ShimReal};

/// The version of the OpenSubdiv library the bridge was built against, e.g. `"3.5.0"`.
pub fn version() -> String {
    // SAFETY: the shim returns a pointer to a static NUL-terminated string.
    unsafe { CStr::from_ptr(ffi::sdv_osd_version()) }
        .to_string_lossy()
        .into_owned()
}

/// OpenSubdiv's `OPENSUBDIV_VERSION_NUMBER`, e.g. `30500`.
pub fn version_number() -> u32 {
    // SAFETY: a pure function of the shim.
    unsafe { ffi::sdv_osd_version_number() as u32 }
}

mod shim {
    use super::{ERR_LEN, Error, Result, TopologyRefiner, ffi};
    use std::ffi::CStr;
    use std::os::raw::c_char;

    /// An error-message buffer for one shim call.
    pub struct ErrBuf([c_char; ERR_LEN]);

    impl ErrBuf {
        pub fn new() -> Self {
            ErrBuf([0; ERR_LEN])
        }

        pub fn ptr(&mut self) -> *mut c_char {
            self.0.as_mut_ptr()
        }

        /// Runs one shim call with this buffer and turns its status into a `Result`.
        pub fn run(&mut self, call: impl FnOnce(*mut c_char) -> i32) -> Result<()> {
            let status = call(self.ptr());
            self.check(status)
        }

        /// Turns a shim status into a `Result`.
        pub fn check(&self, status: i32) -> Result<()> {
            if status == ffi::SDV_OK {
                return Ok(());
            }
            // SAFETY: the shim always NUL-terminates within ERR_LEN (and the
            // buffer starts zeroed), so the bytes form a valid C string.
            let msg = unsafe { CStr::from_ptr(self.0.as_ptr()) }
                .to_string_lossy()
                .into_owned();
            use crate::error::OsdErrorKind as Kind;
            let (kind, message) = match status {
                ffi::SDV_ERR_INVALID => (Kind::Refused, msg),
                ffi::SDV_ERR_OSD => (Kind::Failed, msg),
                ffi::SDV_ERR_CAPACITY => {
                    (Kind::Internal, format!("internal buffer mismatch: {msg}"))
                }
                _ if msg.is_empty() => (Kind::Internal, format!("shim status {status}")),
                _ => (Kind::Internal, msg),
            };
            Err(Error::Osd(crate::error::OsdError { kind, message }))
        }
    }

    /// The shim's entry points of one real type (`f32`, `f64`); private.
    pub trait ShimReal: Sized {
        #[allow(clippy::too_many_arguments)]
        fn interpolate(
            r: &TopologyRefiner,
            kind: i32,
            channel: i32,
            level: i32,
            width: i32,
            src: &[Self],
            dst: &mut [Self],
            err: &mut ErrBuf,
        ) -> i32;
        fn limit(
            r: &TopologyRefiner,
            width: i32,
            src: &[Self],
            out: [&mut [Self]; 3],
            err: &mut ErrBuf,
        ) -> i32;
        fn limit_fvar(
            r: &TopologyRefiner,
            channel: i32,
            width: i32,
            src: &[Self],
            dst: &mut [Self],
            err: &mut ErrBuf,
        ) -> i32;
    }
}

/// Evaluates `$body` with `$S` standing for the shim's real type of `$T`
/// (`f32` or `f64`, the two types [`Real`] is sealed to), so that `[T]`
/// slices can be cast to `[$S]` for the shim's typed entry points.
macro_rules! with_shim_type {
    ($T:ty, |$S:ident| $body:expr) => {
        match <$T as Real>::PRECISION {
            Precision::F32 => {
                type $S = f32;
                $body
            }
            Precision::F64 => {
                type $S = f64;
                $body
            }
        }
    };
}

macro_rules! impl_real {
    ($t:ty, $interp:ident, $limit:ident, $limit_fvar:ident) => {
        impl ShimReal for $t {
            fn interpolate(
                r: &TopologyRefiner,
                kind: i32,
                channel: i32,
                level: i32,
                width: i32,
                src: &[Self],
                dst: &mut [Self],
                err: &mut ErrBuf,
            ) -> i32 {
                // SAFETY: the raw refiner is live for `r`'s lifetime; the
                // shim checks both lengths against the refiner's counts
                // before reading or writing the buffers.
                unsafe {
                    ffi::$interp(
                        r.raw.as_ptr(),
                        kind,
                        channel,
                        level,
                        width,
                        src.as_ptr(),
                        src.len(),
                        dst.as_mut_ptr(),
                        dst.len(),
                        err.ptr(),
                        ERR_LEN,
                    )
                }
            }
            fn limit(
                r: &TopologyRefiner,
                width: i32,
                src: &[Self],
                out: [&mut [Self]; 3],
                err: &mut ErrBuf,
            ) -> i32 {
                let [pos, t1, t2] = out;
                if t1.len() != pos.len() || t2.len() != pos.len() {
                    return ffi::SDV_ERR_CAPACITY;
                }
                // SAFETY: as above; the three outputs have the same length,
                // which the shim checks against the last level's count.
                unsafe {
                    ffi::$limit(
                        r.raw.as_ptr(),
                        width,
                        src.as_ptr(),
                        src.len(),
                        pos.as_mut_ptr(),
                        t1.as_mut_ptr(),
                        t2.as_mut_ptr(),
                        pos.len(),
                        err.ptr(),
                        ERR_LEN,
                    )
                }
            }
            fn limit_fvar(
                r: &TopologyRefiner,
                channel: i32,
                width: i32,
                src: &[Self],
                dst: &mut [Self],
                err: &mut ErrBuf,
            ) -> i32 {
                // SAFETY: as above.
                unsafe {
                    ffi::$limit_fvar(
                        r.raw.as_ptr(),
                        channel,
                        width,
                        src.as_ptr(),
                        src.len(),
                        dst.as_mut_ptr(),
                        dst.len(),
                        err.ptr(),
                        ERR_LEN,
                    )
                }
            }
        }
    };
}

impl_real!(f32, sdv_interpolate_f32, sdv_limit_f32, sdv_limit_fvar_f32);
impl_real!(f64, sdv_interpolate_f64, sdv_limit_f64, sdv_limit_fvar_f64);

pub use crate::output::LevelCounts;

/// An OpenSubdiv `Far::TopologyRefiner`, owned.
#[derive(Debug)]
pub struct TopologyRefiner {
    raw: NonNull<ffi::sdv_refiner>,
    base_vertices: usize,
    base_faces: usize,
    base_corners: usize,
    options: Options,
    fvar_channels: usize,
    uniform: Option<UniformOptions>,
    warnings: Vec<String>,
}

// SAFETY: the refiner is only mutated through `&mut self` (refine_uniform);
// every `&self` call is a read-only use of OpenSubdiv's TopologyRefiner, which
// OpenSubdiv supports from several threads, and the shim keeps its error
// capture in thread-local storage.
unsafe impl Send for TopologyRefiner {}
// SAFETY: see above.
unsafe impl Sync for TopologyRefiner {}

impl Drop for TopologyRefiner {
    fn drop(&mut self) {
        // SAFETY: `raw` came from sdv_refiner_create and is freed exactly once.
        unsafe { ffi::sdv_refiner_destroy(self.raw.as_ptr()) }
    }
}

fn to_i32(n: usize, what: &'static str) -> Result<i32> {
    i32::try_from(n).map_err(|_| Error::TooLarge {
        what,
        count: n,
        bits: 32,
    })
}

/// Refuses a buffer of `got` values where `expected` are needed.
fn check_length(buffer: Buffer, expected: usize, got: usize) -> Result<()> {
    if got == expected {
        Ok(())
    } else {
        Err(Error::BufferLength {
            buffer,
            expected,
            got,
        })
    }
}

/// A defect of the bridge (an object it should have returned), as an error.
fn internal(message: &str) -> Error {
    Error::Osd(OsdError {
        kind: OsdErrorKind::Internal,
        message: message.to_string(),
    })
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

    /// Refines uniformly to `uniform.level` (any earlier refinement is discarded first).
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

    /// The deepest refined level (0 before refinement).
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
        let counts = self.level_counts(level)?;
        let r = self.raw.as_ptr();
        let l = level as i32;
        let mut err = ErrBuf::new();

        let mut sizes = vec![0i32; counts.faces];
        let mut verts = vec![0i32; counts.face_vertices];
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
        let mut edges = vec![
            0i32;
            if counts.full_topology {
                2 * counts.edges
            } else {
                0
            }
        ];
        if counts.full_topology {
            // SAFETY: as above.
            err.run(|e| unsafe {
                ffi::sdv_level_edge_vertices(r, l, edges.as_mut_ptr(), edges.len(), e, ERR_LEN)
            })?;
        }
        let mut edge_sharpness = vec![0f32; counts.edges];
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
        let mut vertex_sharpness = vec![0f32; counts.vertices];
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
        let mut holes = vec![0u8; counts.faces];
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
            let mut values = vec![0i32; counts.face_vertices];
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

        let mut face_offsets = Vec::with_capacity(counts.faces + 1);
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
            edge_vertices: edges
                .chunks_exact(2)
                .map(|e| [e[0] as u32, e[1] as u32])
                .collect(),
            edge_sharpness,
            vertex_sharpness,
            face_holes: holes.into_iter().map(|h| h != 0).collect(),
            fvar,
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
        if level == 0 || level > self.max_level() {
            return Err(Error::NoSuchLevel {
                level,
                first: 1,
                last: self.max_level(),
            });
        }
        if width == 0 {
            return Err(Error::ZeroWidth);
        }
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
        let mut dst = vec![T::default(); to * width];
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
        let mut out = LimitData {
            positions: vec![T::default(); n],
            du: vec![T::default(); n],
            dv: vec![T::default(); n],
        };
        let mut err = ErrBuf::new();
        let width = to_i32(width, "primvar components")?;
        let status = with_shim_type!(T, |S| S::limit(
            self,
            width,
            bytemuck::cast_slice(src),
            [
                bytemuck::cast_slice_mut(&mut out.positions),
                bytemuck::cast_slice_mut(&mut out.du),
                bytemuck::cast_slice_mut(&mut out.dv),
            ],
            &mut err,
        ));
        err.check(status)?;
        Ok(out)
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
        let mut dst = vec![T::default(); n];
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

    fn stencils(&self, kind: i32) -> Result<StencilTable> {
        let mut raw: *mut ffi::sdv_stencils = std::ptr::null_mut();
        let mut err = ErrBuf::new();
        // SAFETY: `raw` is live; `raw` output is written by the shim.
        err.run(|e| unsafe {
            ffi::sdv_stencils_create(self.raw.as_ptr(), kind, &mut raw, e, ERR_LEN)
        })?;
        let table =
            NonNull::new(raw).ok_or_else(|| internal("the shim returned no stencil table"))?;
        // Free the C++ table whatever happens below.
        struct Owned(NonNull<ffi::sdv_stencils>);
        impl Drop for Owned {
            fn drop(&mut self) {
                // SAFETY: created by sdv_stencils_create, freed once.
                unsafe { ffi::sdv_stencils_destroy(self.0.as_ptr()) }
            }
        }
        let table = Owned(table);
        let (mut rows, mut nnz) = (0usize, 0usize);
        // SAFETY: the table is live.
        unsafe { ffi::sdv_stencils_size(table.0.as_ptr(), &mut rows, &mut nnz) };
        let mut sizes = vec![0i32; rows];
        let mut offsets = vec![0i32; rows];
        let mut indices = vec![0i32; nnz];
        let mut weights = vec![0f64; nnz];
        // SAFETY: the buffers have the capacities passed, which the shim checks.
        err.run(|e| unsafe {
            ffi::sdv_stencils_export(
                table.0.as_ptr(),
                sizes.as_mut_ptr(),
                offsets.as_mut_ptr(),
                indices.as_mut_ptr(),
                weights.as_mut_ptr(),
                rows,
                nnz,
                e,
                ERR_LEN,
            )
        })?;
        Ok(StencilTable {
            sizes: sizes.into_iter().map(|v| v as u32).collect(),
            offsets: offsets.into_iter().map(|v| v as u32).collect(),
            indices: indices.into_iter().map(|v| v as u32).collect(),
            weights,
        })
    }

    /// OpenSubdiv's stencil table (`Far::StencilTableFactory`, vertex
    /// interpolation, last level only) mapping base vertices to the vertices of
    /// the last level.
    pub fn stencil_table(&self) -> Result<StencilTable> {
        self.stencils(SDV_STENCIL_REFINED)
    }

    /// Stencils of the limit positions and tangents at the vertices of the last
    /// level, as `PrimvarRefiner::Limit` computes them from base vertices.
    pub fn limit_stencil_table(&self) -> Result<LimitStencilTable> {
        let all = self.stencils(SDV_STENCIL_LIMIT)?;
        let n = all.len() / 3;
        let block = |b: usize| {
            let rows = b * n..(b + 1) * n;
            let start = all.offsets.get(rows.start).copied().unwrap_or(0) as usize;
            let end = if rows.end < all.len() {
                all.offsets[rows.end] as usize
            } else {
                all.indices.len()
            };
            StencilTable {
                sizes: all.sizes[rows.clone()].to_vec(),
                offsets: all.offsets[rows].iter().map(|o| o - start as u32).collect(),
                indices: all.indices[start..end].to_vec(),
                weights: all.weights[start..end].to_vec(),
            }
        };
        Ok(LimitStencilTable {
            positions: block(0),
            du: block(1),
            dv: block(2),
        })
    }
}

/// OpenSubdiv's production stencil evaluation: a float `Far::StencilTable`
/// for the last level, applied by `Osd::CpuEvaluator::EvalStencils`. Used to
/// measure OpenSubdiv's per-frame cost against [`StencilTable::apply_par`].
#[derive(Debug)]
pub struct StencilEvaluator {
    raw: NonNull<ffi::sdv_evaluator>,
    controls: usize,
    stencils: usize,
}

// SAFETY: the evaluator is immutable after creation; evaluation only reads it.
unsafe impl Send for StencilEvaluator {}
// SAFETY: see above.
unsafe impl Sync for StencilEvaluator {}

impl Drop for StencilEvaluator {
    fn drop(&mut self) {
        // SAFETY: created by sdv_evaluator_create, freed once.
        unsafe { ffi::sdv_evaluator_destroy(self.raw.as_ptr()) }
    }
}

impl StencilEvaluator {
    /// Builds OpenSubdiv's float stencil table for the refiner's last level.
    pub fn new(refiner: &TopologyRefiner) -> Result<Self> {
        let mut raw: *mut ffi::sdv_evaluator = std::ptr::null_mut();
        let mut err = ErrBuf::new();
        // SAFETY: the refiner is live; `raw` receives a new evaluator.
        err.run(|e| unsafe {
            ffi::sdv_evaluator_create(refiner.raw.as_ptr(), &mut raw, e, ERR_LEN)
        })?;
        let raw = NonNull::new(raw).ok_or_else(|| internal("the shim returned no evaluator"))?;
        let (mut controls, mut stencils) = (0i32, 0i32);
        // SAFETY: the evaluator is live.
        unsafe { ffi::sdv_evaluator_counts(raw.as_ptr(), &mut controls, &mut stencils) };
        Ok(StencilEvaluator {
            raw,
            controls: controls as usize,
            stencils: stencils as usize,
        })
    }

    /// Number of stencils (vertices of the last level).
    pub fn len(&self) -> usize {
        self.stencils
    }

    /// Whether the table has no stencil.
    pub fn is_empty(&self) -> bool {
        self.stencils == 0
    }

    /// Applies the stencils to base data of `width` floats per vertex, into `dst`.
    pub fn eval_into(&self, width: usize, src: &[f32], dst: &mut [f32]) -> Result<()> {
        let mut err = ErrBuf::new();
        let w = to_i32(width, "primvar components")?;
        // SAFETY: both lengths are passed and checked by the shim against the
        // table's counts before either buffer is touched.
        err.run(|e| unsafe {
            ffi::sdv_evaluator_eval_f32(
                self.raw.as_ptr(),
                w,
                src.as_ptr(),
                src.len(),
                dst.as_mut_ptr(),
                dst.len(),
                e,
                ERR_LEN,
            )
        })
    }

    /// Applies the stencils to base data of `width` floats per vertex.
    pub fn eval(&self, width: usize, src: &[f32]) -> Result<Vec<f32>> {
        if src.len() != self.controls * width {
            return Err(Error::BufferLength {
                buffer: Buffer::Base,
                expected: self.controls * width,
                got: src.len(),
            });
        }
        let mut dst = vec![0f32; self.stencils * width];
        self.eval_into(width, src, &mut dst)?;
        Ok(dst)
    }
}

fn flatten<T: Real>(points: &[DVec3]) -> Vec<T> {
    points
        .iter()
        .flat_map(|p| [T::from_f64(p.x), T::from_f64(p.y), T::from_f64(p.z)])
        .collect()
}

fn unflatten<T: Real>(data: &[T]) -> Vec<DVec3> {
    data.chunks_exact(3)
        .map(|c| DVec3::new(c[0].to_f64(), c[1].to_f64(), c[2].to_f64()))
        .collect()
}

fn widen<T: Real>(data: &[T]) -> Vec<f64> {
    data.iter().map(|v| v.to_f64()).collect()
}

fn narrow<T: Real>(data: &[f64]) -> Vec<T> {
    data.iter().map(|&v| T::from_f64(v)).collect()
}

/// Refines a mesh uniformly with OpenSubdiv as `request` says (a
/// [`UniformOptions`] is a request in `f64` without limits): the topology,
/// positions and face-varying values of every level, and with
/// `request.limit` the limit positions, tangents and face-varying values at
/// the last level (which then keeps its full topology). The same as
/// [`crate::refiner::refine`], through OpenSubdiv.
pub fn refine(mesh: &Mesh, options: &Options, request: impl Into<Request>) -> Result<Refinement> {
    let request = request.into();
    match request.precision {
        Precision::F32 => refine_typed::<f32>(mesh, options, &request),
        Precision::F64 => refine_typed::<f64>(mesh, options, &request),
    }
}

fn refine_typed<T: Real>(mesh: &Mesh, options: &Options, request: &Request) -> Result<Refinement> {
    let (uniform, limit) = (request.effective_uniform(), request.limit);
    check_level(mesh, options, uniform.level)?;
    let mut refiner = TopologyRefiner::new(mesh, options)?;
    refiner.refine_uniform(uniform)?;
    let levels = (0..=uniform.level)
        .map(|l| refiner.level(l))
        .collect::<Result<Vec<_>>>()?;
    let raw_positions = refiner.interpolate_all(3, &flatten::<T>(&mesh.positions))?;
    let fvar_widths: Vec<usize> = mesh.fvar_channels.iter().map(|c| c.width).collect();
    let mut raw_fvar: Vec<Vec<Vec<T>>> = vec![
        mesh.fvar_channels
            .iter()
            .map(|c| narrow::<T>(&c.values))
            .collect(),
    ];
    for level in 1..=uniform.level {
        let prev = raw_fvar.last().expect("non-empty");
        let next = fvar_widths
            .iter()
            .enumerate()
            .map(|(c, &w)| refiner.interpolate_face_varying(c, level, w, &prev[c]))
            .collect::<Result<Vec<_>>>()?;
        raw_fvar.push(next);
    }
    let limit = if limit {
        let last = raw_positions.last().expect("non-empty");
        let data = refiner.limit(3, last)?;
        let last_fvar = raw_fvar.last().expect("non-empty");
        let fvar_values = fvar_widths
            .iter()
            .enumerate()
            .map(|(c, &w)| {
                refiner
                    .limit_face_varying(c, w, &last_fvar[c])
                    .map(|v| widen(&v))
            })
            .collect::<Result<Vec<_>>>()?;
        Some(Limit {
            positions: unflatten(&data.positions),
            du: unflatten(&data.du),
            dv: unflatten(&data.dv),
            fvar_values,
        })
    } else {
        None
    };
    Ok(Refinement {
        options: *options,
        uniform,
        precision: T::PRECISION,
        levels,
        positions: raw_positions.iter().map(|p| unflatten(p)).collect(),
        fvar_widths,
        fvar_values: raw_fvar
            .iter()
            .map(|lv| lv.iter().map(|c| widen(c)).collect())
            .collect(),
        limit,
    })
}
