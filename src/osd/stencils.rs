//! OpenSubdiv's stencil tables (`Far::StencilTableFactory`,
//! `Far::LimitStencilTableFactory`) and its CPU evaluator.

use super::TopologyRefiner;
use super::ffi;
use super::shim::{ErrBuf, internal, to_i32};
use super::{ERR_LEN, SDV_STENCIL_LIMIT, SDV_STENCIL_REFINED};
use crate::alloc::try_vec;
use crate::error::{Buffer, Error, Result};
use crate::patches::{LimitStencilOptions, LocationStencils, Partials};
use crate::stencil::{LimitStencilTable, StencilOptions, StencilTable};
use crate::topology::Table;
use std::ptr::NonNull;

impl TopologyRefiner {
    fn stencils(&self, kind: i32) -> Result<StencilTable> {
        // SAFETY: the refiner is live; `out` is written by the shim.
        self.take_stencils(|out, e| unsafe {
            ffi::sdv_stencils_create(self.raw.as_ptr(), kind, out, e, ERR_LEN)
        })
    }

    /// A table created by `create(out, err)` (a shim call that writes the
    /// new table into `out`), copied out and freed.
    fn take_stencils(
        &self,
        create: impl FnOnce(*mut *mut ffi::sdv_stencils, *mut std::os::raw::c_char) -> i32,
    ) -> Result<StencilTable> {
        let mut raw: *mut ffi::sdv_stencils = std::ptr::null_mut();
        let mut err = ErrBuf::new();
        err.run(|e| create(&mut raw, e))?;
        take_stencils(raw)
    }
}

impl TopologyRefiner {
    /// OpenSubdiv's stencil table (`Far::StencilTableFactory`, vertex
    /// interpolation, last level only) mapping base vertices to the vertices of
    /// the last level.
    pub fn stencil_table(&self) -> Result<StencilTable> {
        self.stencils(SDV_STENCIL_REFINED)
    }

    /// OpenSubdiv's stencil table for `options`
    /// (`Far::StencilTableFactoryReal<double>::Create(refiner, options)`, every
    /// field passed on), after uniform or adaptive refinement; see
    /// [`StencilOptions`] for the rows it holds.
    ///
    /// Refused before OpenSubdiv sees anything: `max_level` beyond 15
    /// ([`Error::Level`]), a face-varying channel the mesh lacks
    /// ([`Error::NoSuchChannel`]), control vertices with neither intermediate
    /// levels nor factorization on a refined refiner
    /// ([`Error::StencilOptions`]; OpenSubdiv 3.5 loops and writes out of
    /// bounds on it), and what the bridge refuses for every stencil table
    /// (Catmull-Clark vertex masks beyond 46,340 faces at a vertex).
    ///
    /// ```
    /// use subdiv::{osd, shapes, Options, UniformOptions};
    /// use subdiv::stencil::StencilOptions;
    /// let mut r = osd::TopologyRefiner::new(&shapes::cube(), &Options::default())?;
    /// r.refine_uniform(UniformOptions::new(2))?;
    /// let levels = r.stencil_table_with(&StencilOptions::new())?;
    /// assert_eq!(levels.len(), 26 + 98); // levels 1 and 2
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn stencil_table_with(&self, options: &StencilOptions) -> Result<StencilTable> {
        options.check(self.max_level(), self.fvar_channels)?;
        let int = |v: usize, what| to_i32(v, what);
        let o = ffi::sdv_stencil_options {
            interpolation: options.interpolation.code(),
            fvar_channel: int(options.fvar_channel, "face-varying channel")?,
            generate_offsets: options.generate_offsets.into(),
            generate_control_verts: options.generate_control_vertices.into(),
            generate_intermediate_levels: options.generate_intermediate_levels.into(),
            factorize_intermediate_levels: options.factorize_intermediate_levels.into(),
            max_level: int(options.max_level as usize, "stencil max level")?,
        };
        // SAFETY: the refiner is live, `o` outlives the call; `out` is
        // written by the shim.
        self.take_stencils(|out, e| unsafe {
            ffi::sdv_stencils_create_with(self.raw.as_ptr(), &o, out, e, ERR_LEN)
        })
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
                sizes: Table::from_slice(&all.sizes[rows.clone()]),
                offsets: all.offsets[rows].iter().map(|o| o - start as u32).collect(),
                indices: Table::from_slice(&all.indices[start..end]),
                weights: Table::from_slice(&all.weights[start..end]),
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
        let mut dst = try_vec(0f32, self.stencils * width)?;
        self.eval_into(width, src, &mut dst)?;
        Ok(dst)
    }
}

/// A stencil table the shim created, freed on drop.
struct Owned(NonNull<ffi::sdv_stencils>);

impl Drop for Owned {
    fn drop(&mut self) {
        // SAFETY: created by the shim, freed once.
        unsafe { ffi::sdv_stencils_destroy(self.0.as_ptr()) }
    }
}

impl Owned {
    fn new(raw: *mut ffi::sdv_stencils) -> Result<Owned> {
        NonNull::new(raw)
            .map(Owned)
            .ok_or_else(|| internal("the shim returned no stencil table"))
    }

    /// Its rows, indices and weights.
    fn export(&self) -> Result<StencilTable> {
        let mut err = ErrBuf::new();
        let (mut rows, mut nnz) = (0usize, 0usize);
        // SAFETY: the table is live.
        unsafe { ffi::sdv_stencils_size(self.0.as_ptr(), &mut rows, &mut nnz) };
        let mut sizes = try_vec(0i32, rows)?;
        let mut offsets = try_vec(0i32, rows)?;
        let mut indices = try_vec(0i32, nnz)?;
        let mut weights = try_vec(0f64, nnz)?;
        // SAFETY: the buffers have the capacities passed, which the shim checks.
        err.run(|e| unsafe {
            ffi::sdv_stencils_export(
                self.0.as_ptr(),
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
            weights: weights.into(),
        })
    }

    /// The derivative weights of kind `kind` (0..4: du, dv, duu, duv, dvv)
    /// of a limit stencil table; empty when not generated.
    fn derivative(&self, kind: i32) -> Result<Vec<f64>> {
        let mut err = ErrBuf::new();
        let mut len = 0usize;
        // SAFETY: the table is live; a null output only asks for the length.
        err.run(|e| unsafe {
            ffi::sdv_stencils_derivative(
                self.0.as_ptr(),
                kind,
                std::ptr::null_mut(),
                0,
                &mut len,
                e,
                ERR_LEN,
            )
        })?;
        let mut out = try_vec(0f64, len)?;
        // SAFETY: `out` holds `len` values, the capacity passed and checked.
        err.run(|e| unsafe {
            ffi::sdv_stencils_derivative(
                self.0.as_ptr(),
                kind,
                out.as_mut_ptr(),
                out.len(),
                &mut len,
                e,
                ERR_LEN,
            )
        })?;
        Ok(out)
    }
}

/// The stencil table the shim created at `raw` (freed here whatever
/// happens), read into a [`StencilTable`].
pub(super) fn take_stencils(raw: *mut ffi::sdv_stencils) -> Result<StencilTable> {
    Owned::new(raw)?.export()
}

impl TopologyRefiner {
    /// OpenSubdiv's limit stencils at `locations` (ptex face, u, v):
    /// `Far::LimitStencilTableFactoryReal<double>::Create(refiner,
    /// locations, nullptr, nullptr, options)` — the factory building its own
    /// refined-vertex stencils and Gregory-end-capped patch table — after
    /// uniform or adaptive refinement, in every interpolation mode. One
    /// stencil per location outside holes, in order
    /// ([`LocationStencils::locations`]).
    ///
    /// Refused before OpenSubdiv sees anything: a ptex face out of range, a
    /// coordinate outside [0, 1], a face-varying channel the mesh lacks, a
    /// refiner adaptively refined around selected faces only (the other
    /// faces' patches are undefined), faces repeating a vertex after
    /// adaptive refinement, a Loop base triangle left unrefined with two
    /// interior vertices of valence 2 and a patch at an interior vertex of
    /// valence 2 that may gather 64 source points or more (as for patch
    /// tables), face-varying stencils after adaptive refinement that
    /// considered the face-varying channels (OpenSubdiv 3.5 reads
    /// uninitialised local-point weights there and returns wrong stencils:
    /// found by Valgrind), and the Catmull-Clark vertex masks that overflow
    /// (as for every stencil table).
    ///
    /// ```
    /// use subdiv::patches::LimitStencilOptions;
    /// use subdiv::{osd, shapes, AdaptiveOptions, Options};
    /// let mut r = osd::TopologyRefiner::new(&shapes::cube(), &Options::default())?;
    /// r.refine_adaptive(AdaptiveOptions::new(3), &[])?;
    /// let s = r.location_stencils(&[(0, 0.5, 0.5)], &LimitStencilOptions::new())?;
    /// assert_eq!((s.sizes.clone(), s.locations.clone()), (vec![8], vec![0]));
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn location_stencils(
        &self,
        locations: &[(u32, f64, f64)],
        options: &LimitStencilOptions,
    ) -> Result<LocationStencils> {
        let n = locations.len();
        let mut faces = try_vec(0i32, n)?;
        let mut us = try_vec(0f64, n)?;
        let mut vs = try_vec(0f64, n)?;
        for (i, &(f, u, v)) in locations.iter().enumerate() {
            faces[i] = to_i32(f as usize, "ptex face")?;
            us[i] = u;
            vs[i] = v;
        }
        let mut found = try_vec(0i32, n)?;
        let o = ffi::sdv_limit_stencil_options {
            interpolation: options.interpolation.code(),
            fvar_channel: to_i32(options.fvar_channel, "face-varying channel")?,
            first_derivatives: options.first_derivatives.into(),
            second_derivatives: options.second_derivatives.into(),
        };
        let mut raw: *mut ffi::sdv_stencils = std::ptr::null_mut();
        let mut err = ErrBuf::new();
        // SAFETY: the refiner is live; the four location arrays hold `n`
        // entries each; `raw` receives a new table.
        err.run(|e| unsafe {
            ffi::sdv_limit_stencils_create(
                self.raw.as_ptr(),
                &o,
                faces.as_ptr(),
                us.as_ptr(),
                vs.as_ptr(),
                n,
                found.as_mut_ptr(),
                &mut raw,
                e,
                ERR_LEN,
            )
        })?;
        let owned = Owned::new(raw)?;
        let table = owned.export()?;
        let [du, dv, duu, duv, dvv] = [0, 1, 2, 3, 4].map(|k| owned.derivative(k));
        // SAFETY: the table is live.
        let controls = unsafe { ffi::sdv_stencils_controls(owned.0.as_ptr()) };
        Ok(LocationStencils {
            control_vertices: controls.max(0) as usize,
            locations: (0..n).filter(|&i| found[i] != 0).collect(),
            sizes: table.sizes.into_vec(),
            offsets: table.offsets.into_vec(),
            indices: table.indices.into_vec(),
            weights: Partials {
                point: table.weights.into_vec(),
                du: du?,
                dv: dv?,
                duu: duu?,
                duv: duv?,
                dvv: dvv?,
            },
        })
    }
}
