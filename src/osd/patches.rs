//! Patch tables through the bridge: `Far::PatchTableFactory::Create`,
//! `Far::PatchMap::FindPatch` and `Far::PatchTable::EvaluateBasis`, and
//! limit-surface evaluation at (ptex face, u, v) built on them as
//! OpenSubdiv's far tutorials do it.

use super::ERR_LEN;
use super::TopologyRefiner;
use super::at_locations::AtLocations;
use super::ffi;
use super::shim::{ErrBuf, check_length, internal, to_i32};
use crate::alloc::try_vec;
use crate::error::{Buffer, Element, Error, LevelRefusal, Result};
use crate::patches::{
    Derivatives, FVarPatches, Partials, PatchArray, PatchHandle, PatchOptions, PatchParam,
    PatchTable, PatchType, SurfaceSamples,
};
use crate::stencil::StencilTable;
use std::ptr::NonNull;

/// A patch table built by OpenSubdiv, with the `Far::PatchMap` that
/// locates points in it. The table's contents are read once
/// ([`OsdPatchTable::table`]); locating and basis evaluation call
/// OpenSubdiv.
pub struct OsdPatchTable {
    pub(super) raw: NonNull<ffi::sdv_patches>,
    table: PatchTable,
    options: PatchOptions,
}

// SAFETY: after creation the C++ patch table and patch map are only read
// (FindPatch and EvaluateBasis are const and keep no state), which
// OpenSubdiv allows from several threads; the handle is freed once, on drop.
unsafe impl Send for OsdPatchTable {}
// SAFETY: as above: every method takes `&self` and only reads.
unsafe impl Sync for OsdPatchTable {}

impl Drop for OsdPatchTable {
    fn drop(&mut self) {
        // SAFETY: created by sdv_patches_create, freed once here.
        unsafe { ffi::sdv_patches_destroy(self.raw.as_ptr()) }
    }
}

fn flag(b: bool) -> i32 {
    b.into()
}

impl TopologyRefiner {
    /// OpenSubdiv's patch table of this refiner
    /// (`Far::PatchTableFactory::Create(refiner, options, selectedFaces)`),
    /// after adaptive refinement (feature-adaptive patches) or uniform
    /// refinement (the last level's faces as bilinear `QUADS` or
    /// `TRIANGLES`). `selected_faces` restricts the patches to those base
    /// faces (empty: all).
    ///
    /// Refused before OpenSubdiv sees them: a maximum isolation level above
    /// 10 ([`Error::Level`]), a face-varying channel the mesh lacks
    /// ([`Error::NoSuchChannel`]), a selected face out of range
    /// ([`Error::NoSuchElement`]); through the shim ([`Error::Osd`]): legacy
    /// Gregory end caps on a scheme other than Catmull-Clark, a selected face
    /// that adaptive refinement was not given (OpenSubdiv leaves its patches
    /// undefined), and the inputs OpenSubdiv 3.5 overruns its buffers on
    /// (kind `Unsafe`; docs/CONFORMANCE.md): a face repeating a vertex,
    /// B-spline end caps at an interior vertex of valence 2, Loop end caps
    /// on a base triangle left unrefined with two interior vertices of
    /// valence 2 (two triangles folded onto each other), Gregory or bilinear
    /// end caps where a patch at an interior vertex of valence 2 may gather
    /// 64 source points or more (OpenSubdiv then writes one past them),
    /// legacy Gregory end caps with an irregular patch above the last level,
    /// a non-quad or a non-manifold vertex in it.
    ///
    /// ```
    /// use subdiv::{osd, patches::{PatchOptions, PatchType}, shapes, Options};
    /// let mut r = osd::TopologyRefiner::new(&shapes::cube(), &Options::default())?;
    /// let options = PatchOptions::new().max_isolation(2);
    /// r.refine_adaptive(options.refine_adaptive_options(), &[])?;
    /// let patches = r.patch_table(&options, &[])?;
    /// let t = patches.table();
    /// assert_eq!(t.arrays[0].patch_type, PatchType::Regular);
    /// assert_eq!(t.arrays[1].patch_type, PatchType::GregoryBasis);
    /// assert_eq!(t.patch_count(), 96); // 6 faces, 16 patches each at depth 2
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn patch_table(
        &self,
        options: &PatchOptions,
        selected_faces: &[u32],
    ) -> Result<OsdPatchTable> {
        let mut out = self.create_patch_table(options, selected_faces)?;
        out.table = out.read()?;
        Ok(out)
    }

    /// Builds OpenSubdiv's patch table (`PatchTableFactory::Create`) and
    /// its `PatchMap`, and drops them without reading them back: what the
    /// two cost, the benchmark's reference for the native factory. Refused
    /// as [`TopologyRefiner::patch_table`].
    pub fn build_patch_table(&self, options: &PatchOptions, selected_faces: &[u32]) -> Result<()> {
        self.create_patch_table(options, selected_faces).map(drop)
    }

    /// The table built by OpenSubdiv, not read yet.
    fn create_patch_table(
        &self,
        options: &PatchOptions,
        selected_faces: &[u32],
    ) -> Result<OsdPatchTable> {
        if options.max_isolation_level > 10 {
            return Err(Error::Level {
                level: options.max_isolation_level,
                reason: LevelRefusal::TooDeep { max: 10 },
            });
        }
        // No list: every channel, as OpenSubdiv's default (-1) asks.
        let every: Vec<usize> = (0..self.fvar_channels).collect();
        let listed = if options.fvar_tables && options.fvar_channels.is_empty() {
            &every
        } else {
            &options.fvar_channels
        };
        let channels = listed
            .iter()
            .map(|&c| {
                if c >= self.fvar_channels {
                    Err(Error::NoSuchChannel {
                        channel: c,
                        count: self.fvar_channels,
                    })
                } else {
                    to_i32(c, "face-varying channel")
                }
            })
            .collect::<Result<Vec<i32>>>()?;
        let faces = selected_faces
            .iter()
            .map(|&f| {
                if f as usize >= self.base_faces {
                    Err(Error::NoSuchElement {
                        element: Element::Face,
                        index: f as usize,
                        level: 0,
                        count: self.base_faces,
                    })
                } else {
                    Ok(f as i32)
                }
            })
            .collect::<Result<Vec<i32>>>()?;
        let o = ffi::sdv_patch_options {
            end_cap_type: options.end_cap_type as i32,
            share_end_cap_patch_points: flag(options.share_end_cap_points),
            generate_all_levels: flag(options.generate_all_levels),
            include_base_level_indices: flag(options.include_base_level_indices),
            include_fvar_base_level_indices: flag(options.include_fvar_base_level_indices),
            triangulate_quads: flag(options.triangulate_quads),
            use_single_crease_patch: flag(options.single_crease_patch),
            use_inf_sharp_patch: flag(options.inf_sharp_patch),
            max_isolation_level: options.max_isolation_level as i32,
            generate_varying_tables: flag(options.varying_tables),
            generate_varying_local_points: flag(options.varying_local_points),
            generate_fvar_tables: flag(options.fvar_tables),
            patch_precision_double: flag(options.patch_precision_double),
            fvar_patch_precision_double: flag(options.fvar_patch_precision_double),
            generate_fvar_legacy_linear_patches: flag(options.fvar_legacy_linear_patches),
            generate_legacy_sharp_corner_patches: flag(options.legacy_sharp_corner_patches),
        };
        let mut raw: *mut ffi::sdv_patches = std::ptr::null_mut();
        let mut err = ErrBuf::new();
        // SAFETY: the refiner is live; `o`, `channels` and `faces` outlive
        // the call and their lengths are passed; `raw` is written by the shim.
        err.run(|e| unsafe {
            ffi::sdv_patches_create(
                self.raw.as_ptr(),
                &o,
                channels.as_ptr(),
                channels.len(),
                faces.as_ptr(),
                faces.len(),
                &mut raw,
                e,
                ERR_LEN,
            )
        })?;
        let raw = NonNull::new(raw).ok_or_else(|| internal("the shim returned no patch table"))?;
        Ok(OsdPatchTable {
            raw,
            table: PatchTable::default(),
            options: options.clone(),
        })
    }
}

impl OsdPatchTable {
    /// The table's contents: arrays, control vertices, [`PatchParam`]s,
    /// sharpness, local-point counts and the legacy Gregory tables.
    pub fn table(&self) -> &PatchTable {
        &self.table
    }

    /// Reads the whole table from OpenSubdiv.
    fn read(&self) -> Result<PatchTable> {
        let mut err = ErrBuf::new();
        let mut c = ffi::sdv_patch_counts {
            num_arrays: 0,
            num_patches: 0,
            num_control_vertices: 0,
            num_local_points: 0,
            num_local_points_varying: 0,
            max_valence: 0,
            num_ptex_faces: 0,
            num_quad_offsets: 0,
            num_valence_entries: 0,
            feature_adaptive: 0,
            varying_type: 0,
            num_varying_vertices: 0,
            num_fvar_channels: 0,
        };
        // SAFETY: the table is live; `c` is written by the shim.
        err.run(|e| unsafe { ffi::sdv_patches_counts(self.raw.as_ptr(), &mut c, e, ERR_LEN) })?;
        let count = |n: i32| usize::try_from(n).map_err(|_| internal("negative count"));
        let (patches, cv_total) = (count(c.num_patches)?, count(c.num_control_vertices)?);
        let mut cvs = try_vec(0i32, cv_total)?;
        let mut params = try_vec(0u32, 2 * patches)?;
        let mut sharpness = try_vec(0f32, patches)?;
        let mut quad = try_vec(0u32, count(c.num_quad_offsets)?)?;
        let mut valence = try_vec(0i32, count(c.num_valence_entries)?)?;
        let mut varying = try_vec(0i32, count(c.num_varying_vertices)?)?;
        let tables = ffi::sdv_patch_tables {
            cvs: ffi::sdv_ibuf {
                data: cvs.as_mut_ptr(),
                cap: cvs.len(),
            },
            params: params.as_mut_ptr(),
            params_cap: params.len(),
            sharpness: sharpness.as_mut_ptr(),
            sharpness_cap: sharpness.len(),
            quad_offsets: quad.as_mut_ptr(),
            quad_offsets_cap: quad.len(),
            valence: ffi::sdv_ibuf {
                data: valence.as_mut_ptr(),
                cap: valence.len(),
            },
            varying: ffi::sdv_ibuf {
                data: varying.as_mut_ptr(),
                cap: varying.len(),
            },
        };
        // SAFETY: every buffer has the capacity passed beside it, which the
        // shim checks against the table's sizes.
        err.run(|e| unsafe { ffi::sdv_patches_tables(self.raw.as_ptr(), &tables, e, ERR_LEN) })?;
        let varying_type = PatchType::from_code(c.varying_type)
            .ok_or_else(|| internal("unknown varying patch type"))?;
        // Varying vertices per patch, when the table has them.
        let per_patch = if varying.is_empty() {
            0
        } else {
            varying_type.control_vertices()
        };
        if varying.len() != per_patch * patches {
            return Err(internal("varying vertices do not match the patches"));
        }
        let mut arrays = Vec::new();
        let (mut cv_at, mut patch_at) = (0usize, 0usize);
        for a in 0..c.num_arrays {
            let (mut ty, mut n, mut ncv) = (0i32, 0i32, 0i32);
            // SAFETY: the table is live; the outputs are written by the shim.
            err.run(|e| unsafe {
                ffi::sdv_patches_array(self.raw.as_ptr(), a, &mut ty, &mut n, &mut ncv, e, ERR_LEN)
            })?;
            let patch_type = PatchType::from_code(ty)
                .ok_or_else(|| internal(&format!("unknown patch type {ty}")))?;
            let (n, ncv) = (count(n)?, count(ncv)?);
            if ncv != patch_type.control_vertices()
                || cv_at + n * ncv > cvs.len()
                || patch_at + n > patches
            {
                return Err(internal("patch arrays do not match their tables"));
            }
            arrays.push(PatchArray {
                patch_type,
                control_vertices: cvs[cv_at..cv_at + n * ncv]
                    .iter()
                    .map(|&v| v as u32)
                    .collect(),
                params: params[2 * patch_at..2 * (patch_at + n)]
                    .chunks_exact(2)
                    .map(|w| PatchParam {
                        field0: w[0],
                        field1: w[1],
                    })
                    .collect(),
                sharpness: sharpness[patch_at..patch_at + n].to_vec(),
                varying_vertices: varying[per_patch * patch_at..per_patch * (patch_at + n)]
                    .iter()
                    .map(|&v| v as u32)
                    .collect(),
            });
            cv_at += n * ncv;
            patch_at += n;
        }
        Ok(PatchTable {
            arrays,
            local_points: count(c.num_local_points)?,
            local_points_varying: count(c.num_local_points_varying)?,
            local_point_stencils: self.local_stencils(0)?,
            local_point_varying_stencils: self.local_stencils(1)?,
            max_valence: count(c.max_valence)?,
            ptex_faces: count(c.num_ptex_faces)?,
            quad_offsets: quad,
            vertex_valences: valence,
            feature_adaptive: c.feature_adaptive != 0,
            varying_patch_type: varying_type,
            fvar_channels: (0..count(c.num_fvar_channels)?)
                .map(|k| self.fvar_patches(k))
                .collect::<Result<_>>()?,
        })
    }

    /// Face-varying patch channel `k` of the table.
    fn fvar_patches(&self, k: usize) -> Result<FVarPatches> {
        let mut err = ErrBuf::new();
        let mut info = ffi::sdv_fvar_patches {
            regular_type: 0,
            irregular_type: 0,
            stride: 0,
            num_values: 0,
            num_params: 0,
        };
        let channel = to_i32(k, "face-varying patch channel")?;
        // SAFETY: the table is live; null outputs ask for the sizes only.
        err.run(|e| unsafe {
            ffi::sdv_patches_fvar(
                self.raw.as_ptr(),
                channel,
                &mut info,
                std::ptr::null_mut(),
                0,
                std::ptr::null_mut(),
                0,
                e,
                ERR_LEN,
            )
        })?;
        let count = |n: i32| usize::try_from(n).map_err(|_| internal("negative count"));
        let mut values = try_vec(0i32, count(info.num_values)?)?;
        let mut params = try_vec(0u32, 2 * count(info.num_params)?)?;
        // SAFETY: both buffers have the capacities passed, which the shim
        // checks.
        err.run(|e| unsafe {
            ffi::sdv_patches_fvar(
                self.raw.as_ptr(),
                channel,
                &mut info,
                values.as_mut_ptr(),
                values.len(),
                params.as_mut_ptr(),
                params.len(),
                e,
                ERR_LEN,
            )
        })?;
        let ty = |code: i32| {
            PatchType::from_code(code).ok_or_else(|| internal("unknown face-varying patch type"))
        };
        Ok(FVarPatches {
            channel: if self.options.fvar_channels.is_empty() {
                k
            } else {
                self.options.fvar_channels[k]
            },
            regular_type: ty(info.regular_type)?,
            irregular_type: ty(info.irregular_type)?,
            stride: count(info.stride)?,
            local_point_stencils: self.local_stencils(2 + channel)?,
            values: values.into_iter().map(|v| v as u32).collect(),
            params: params
                .chunks_exact(2)
                .map(|w| PatchParam {
                    field0: w[0],
                    field1: w[1],
                })
                .collect(),
        })
    }

    /// The stencils of the local points over the refined vertices (every
    /// level, base first; `GetLocalPointStencilTable`), weights as `f64`
    /// (computed in `f32` unless the options asked for double precision).
    pub fn local_point_stencils(&self) -> Result<StencilTable> {
        self.local_stencils(0)
    }

    /// The varying local points' stencils
    /// (`GetLocalPointVaryingStencilTable`).
    pub fn local_point_varying_stencils(&self) -> Result<StencilTable> {
        self.local_stencils(1)
    }

    fn local_stencils(&self, kind: i32) -> Result<StencilTable> {
        let mut raw: *mut ffi::sdv_stencils = std::ptr::null_mut();
        let mut err = ErrBuf::new();
        // SAFETY: the table is live; `raw` is written by the shim.
        err.run(|e| unsafe {
            ffi::sdv_patches_local_stencils(self.raw.as_ptr(), kind, &mut raw, e, ERR_LEN)
        })?;
        super::stencils::take_stencils(raw)
    }

    /// The patch at (ptex face `face`, `u`, `v`) (`PatchMap::FindPatch`), or
    /// `None` where no patch covers it (a hole). Refused: a face that is not
    /// a ptex face ([`Error::NoSuchPtexFace`]), u or v outside [0, 1] ([`Error::Location`]).
    pub fn find_patch(&self, face: u32, u: f64, v: f64) -> Result<Option<PatchHandle>> {
        self.check_location(face, u, v)?;
        let (mut found, mut array, mut patch) = (0i32, 0i32, 0i32);
        let mut err = ErrBuf::new();
        // SAFETY: the table is live; the outputs are written by the shim.
        err.run(|e| unsafe {
            ffi::sdv_patches_find(
                self.raw.as_ptr(),
                face as i32,
                u,
                v,
                &mut found,
                &mut array,
                &mut patch,
                e,
                ERR_LEN,
            )
        })?;
        Ok((found != 0).then_some(PatchHandle {
            array: array as usize,
            patch: patch as usize,
        }))
    }

    fn check_location(&self, face: u32, u: f64, v: f64) -> Result<()> {
        if face as usize >= self.table.ptex_faces {
            return Err(Error::NoSuchPtexFace {
                face: face as usize,
                count: self.table.ptex_faces,
            });
        }
        for (name, x) in [("u", u), ("v", v)] {
            if !(0.0..=1.0).contains(&x) {
                return Err(Error::Location {
                    face,
                    coordinate: name,
                    value: x,
                });
            }
        }
        Ok(())
    }

    /// The weights of `patch`'s control vertices at (`u`, `v`) of its ptex
    /// face (`PatchTable::EvaluateBasis<double>`), with the derivatives
    /// asked for (scaled to the ptex face's parameterization as OpenSubdiv
    /// scales them). Refused: a patch that does not exist
    /// ([`Error::NoSuchPatch`]), a type without a basis (legacy Gregory:
    /// [`Error::Osd`]), u or v outside [0, 1].
    pub fn evaluate_basis(
        &self,
        patch: PatchHandle,
        u: f64,
        v: f64,
        derivatives: Derivatives,
    ) -> Result<Partials> {
        let missing = |patches| Error::NoSuchPatch {
            array: patch.array,
            patch: patch.patch,
            arrays: self.table.arrays.len(),
            patches,
        };
        let array = self.table.arrays.get(patch.array).ok_or(missing(0))?;
        if patch.patch >= array.len() {
            return Err(missing(array.len()));
        }
        let face = array.params[patch.patch].face_id();
        self.check_location(face, u, v)?;
        const MAX: usize = 20;
        let mut w = [[0f64; MAX]; 6];
        let [p, du, dv, duu, duv, dvv] = &mut w;
        let first = derivatives != Derivatives::None;
        let second = derivatives == Derivatives::Second;
        let ptr = |b: &mut [f64; MAX], on: bool| {
            if on {
                b.as_mut_ptr()
            } else {
                std::ptr::null_mut()
            }
        };
        let ptrs = [
            p.as_mut_ptr(),
            ptr(du, first),
            ptr(dv, first),
            ptr(duu, second),
            ptr(duv, second),
            ptr(dvv, second),
        ];
        let mut err = ErrBuf::new();
        // SAFETY: the table is live; each non-null output holds MAX weights,
        // the capacity passed (the shim checks it covers every basis).
        err.run(|e| unsafe {
            ffi::sdv_patches_evaluate_basis(
                self.raw.as_ptr(),
                patch.array as i32,
                patch.patch as i32,
                u,
                v,
                ptrs[0],
                ptrs[1],
                ptrs[2],
                ptrs[3],
                ptrs[4],
                ptrs[5],
                MAX,
                e,
                ERR_LEN,
            )
        })?;
        let n = array.patch_type.control_vertices();
        let take = |b: &[f64; MAX], on: bool| if on { b[..n].to_vec() } else { Vec::new() };
        Ok(Partials {
            point: w[0][..n].to_vec(),
            du: take(&w[1], first),
            dv: take(&w[2], first),
            duu: take(&w[3], second),
            duv: take(&w[4], second),
            dvv: take(&w[5], second),
        })
    }

    /// The limit surface at `locations` (ptex face, u, v) for data of
    /// `width` components at the points this table's control vertices
    /// index (`points`: every level's vertices, base first, then the local
    /// points — `AdaptiveRefiner::patch_points` gives them natively), in
    /// one call into OpenSubdiv: for each location `PatchMap::FindPatch`,
    /// `PatchTable::EvaluateBasis<double>` and the weighted sum of the
    /// patch's control points, far tutorial 5_1's loop. The benchmark's
    /// reference for native evaluation.
    ///
    /// Refused: `width` 0, `points` not a whole number of points or too few
    /// for the table, a location outside the mesh or its unit square or on
    /// a hole (an error naming the location's index), a table with patches
    /// without a basis (legacy Gregory).
    pub fn evaluate_points(
        &self,
        points: &[f64],
        width: usize,
        locations: &[(u32, f64, f64)],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        let mut out = SurfaceSamples::default();
        self.evaluate_points_into(points, width, locations, derivatives, &mut out)?;
        Ok(out)
    }

    /// [`Self::evaluate_points`] into `out`, reusing its columns' memory (as a
    /// program calling OpenSubdiv keeps its output buffers from one call
    /// to the next); on error `out` is left empty.
    pub fn evaluate_points_into(
        &self,
        points: &[f64],
        width: usize,
        locations: &[(u32, f64, f64)],
        derivatives: Derivatives,
        out: &mut SurfaceSamples,
    ) -> Result<()> {
        let reuse = std::mem::take(&mut out.values);
        let mut at = AtLocations::new(points.len(), width, locations, derivatives, reuse)?;
        let outs = at.outputs();
        let mut err = ErrBuf::new();
        // SAFETY: the table is live; `points` holds `at.points` points of
        // `width` values; the location arrays hold `at.len()` entries and
        // every non-null output `at.len() * width` values, as passed.
        err.run(|e| unsafe {
            ffi::sdv_patches_evaluate_points(
                self.raw.as_ptr(),
                points.as_ptr(),
                at.points,
                at.width_i32,
                at.faces.as_ptr(),
                at.us.as_ptr(),
                at.vs.as_ptr(),
                at.len(),
                outs[0],
                outs[1],
                outs[2],
                outs[3],
                outs[4],
                outs[5],
                e,
                ERR_LEN,
            )
        })?;
        *out = at.finish();
        Ok(())
    }

    /// The limit surface at `locations` (ptex face, u, v) for vertex data of
    /// `width` components given at the base vertices (`base`), as
    /// OpenSubdiv's far tutorials 5_1 and 5_2 compute it: the data refined
    /// through every level of `refiner` (the refiner this table was built
    /// from), the local points from their stencils, then for each location
    /// `FindPatch` and `EvaluateBasis` and the weighted sum of the patch's
    /// control points.
    ///
    /// Refused: a location outside the mesh or its unit square, or on a
    /// hole ([`Error::NoPatchAt`]); a patch without a basis (legacy
    /// Gregory); `base` not one value per base vertex.
    ///
    /// ```
    /// use subdiv::{osd, patches::{Derivatives, PatchOptions}, shapes, Options};
    /// let mesh = shapes::cube();
    /// let mut r = osd::TopologyRefiner::new(&mesh, &Options::default())?;
    /// let options = PatchOptions::new().max_isolation(3).double_precision(true);
    /// r.refine_adaptive(options.refine_adaptive_options(), &[])?;
    /// let patches = r.patch_table(&options, &[])?;
    /// let base: Vec<f64> = mesh.flat_positions();
    /// let s = patches.evaluate(&r, 3, &base, &[(0, 0.5, 0.5)], Derivatives::First)?;
    /// assert_eq!((s.values.point.len(), s.values.du.len()), (3, 3));
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn evaluate(
        &self,
        refiner: &TopologyRefiner,
        width: usize,
        base: &[f64],
        locations: &[(u32, f64, f64)],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        if width == 0 {
            return Err(Error::ZeroWidth);
        }
        check_length(Buffer::Base, refiner.base_vertices * width, base.len())?;
        let levels = refiner.interpolate_all(width, base)?;
        // Adaptive tables index every level, base first. Uniform ones index
        // the base level when asked to (`includeBaseLevelIndices`), then the
        // levels they hold patches of: the last, or every refined level
        // (`generateAllLevels`).
        let mut points: Vec<f64> = if self.table.feature_adaptive {
            levels.concat()
        } else {
            let mut p = Vec::new();
            if self.options.include_base_level_indices {
                p.extend_from_slice(base);
            }
            if self.options.generate_all_levels {
                levels.iter().skip(1).for_each(|l| p.extend_from_slice(l));
            } else if let Some(last) = levels.last() {
                p.extend_from_slice(last);
            }
            p
        };
        if self.table.local_points > 0 {
            let local = self.local_point_stencils()?.apply(width, &points)?;
            points.extend_from_slice(&local);
        }
        let mut out = Partials::default();
        let first = derivatives != Derivatives::None;
        let second = derivatives == Derivatives::Second;
        for &(face, u, v) in locations {
            let handle = self
                .find_patch(face, u, v)?
                .ok_or(Error::NoPatchAt { face, u, v })?;
            let w = self.evaluate_basis(handle, u, v, derivatives)?;
            let cvs = self.table.arrays[handle.array].patch_vertices(handle.patch);
            let sum = |weights: &[f64], into: &mut Vec<f64>| -> Result<()> {
                let start = into.len();
                into.resize(start + width, 0.0);
                for (&cv, &wt) in cvs.iter().zip(weights) {
                    let row = points
                        .get(cv as usize * width..(cv as usize + 1) * width)
                        .ok_or_else(|| internal("a patch names a point that does not exist"))?;
                    for (o, &x) in into[start..].iter_mut().zip(row) {
                        *o += wt * x;
                    }
                }
                Ok(())
            };
            sum(&w.point, &mut out.point)?;
            if first {
                sum(&w.du, &mut out.du)?;
                sum(&w.dv, &mut out.dv)?;
            }
            if second {
                sum(&w.duu, &mut out.duu)?;
                sum(&w.duv, &mut out.duv)?;
                sum(&w.dvv, &mut out.dvv)?;
            }
        }
        Ok(SurfaceSamples { width, values: out })
    }
}
