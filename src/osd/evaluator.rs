//! OpenSubdiv's CPU evaluator through the bridge: `Osd::CpuPatchTable` and
//! `Osd::CpuEvaluator::EvalPatches`, the batch limit evaluation that
//! Blender's and USD's evaluators call. Osd's evaluators read and write
//! `f32` only, so this is the reference for native evaluation in `f32`
//! ([`crate::patches::evaluate_with`] over `f32` points).

use super::ERR_LEN;
use super::OsdPatchTable;
use super::at_locations::AtLocations;
use super::ffi;
use super::shim::{ErrBuf, internal};
use crate::error::Result;
use crate::patches::{Derivatives, SurfaceSamples};
use std::marker::PhantomData;
use std::ptr::NonNull;

/// An `Osd::CpuPatchTable` made of an [`OsdPatchTable`] (its arrays,
/// control-vertex indices and parameters copied as OpenSubdiv's CPU
/// evaluator reads them), which locates points through that table's
/// `Far::PatchMap`.
pub struct OsdCpuPatchTable<'a> {
    raw: NonNull<ffi::sdv_cpu_patches>,
    /// The table it was made of, whose `PatchMap` finds the locations:
    /// borrowed, as the C++ object points to it.
    table: PhantomData<&'a OsdPatchTable>,
}

// SAFETY: after creation the C++ table is only read (EvalPatches is static
// and keeps no state; FindPatch is const), which OpenSubdiv allows from
// several threads; the handle is freed once, on drop.
unsafe impl Send for OsdCpuPatchTable<'_> {}
// SAFETY: as above: every method takes `&self` and only reads.
unsafe impl Sync for OsdCpuPatchTable<'_> {}

impl Drop for OsdCpuPatchTable<'_> {
    fn drop(&mut self) {
        // SAFETY: created by sdv_cpu_patches_create, freed once here.
        unsafe { ffi::sdv_cpu_patches_destroy(self.raw.as_ptr()) }
    }
}

impl OsdPatchTable {
    /// OpenSubdiv's CPU evaluator's copy of this table
    /// (`Osd::CpuPatchTable::Create`), for [`OsdCpuPatchTable::evaluate`].
    ///
    /// ```
    /// use subdiv::{osd, patches::{Derivatives, PatchOptions}, refiner::Refiner, shapes, Options};
    /// let mesh = shapes::cube();
    /// let options = PatchOptions::new().max_isolation(2);
    /// let mut theirs = osd::TopologyRefiner::new(&mesh, &Options::default())?;
    /// theirs.refine_adaptive(options.refine_adaptive_options(), &[])?;
    /// let table = theirs.patch_table(&options, &[])?;
    /// // Every level's vertices and the local points, natively, in f32.
    /// let mine = Refiner::new(&mesh, &Options::default())?
    ///     .refine_adaptive(options.refine_adaptive_options(), &[])?;
    /// let points = mine.patch_points(table.table(), 3, &mesh.flat_positions())?;
    /// let points: Vec<f32> = points.iter().map(|&x| x as f32).collect();
    /// let cpu = table.cpu_patch_table()?;
    /// let s = cpu.evaluate(&points, 3, &[(0, 0.5, 0.5)], Derivatives::First)?;
    /// assert!(s.values.point[2].abs() < 0.5); // the centre of a face, inside the cube
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn cpu_patch_table(&self) -> Result<OsdCpuPatchTable<'_>> {
        let mut raw = std::ptr::null_mut();
        let mut err = ErrBuf::new();
        // SAFETY: the table is live (and outlives the result, which borrows
        // it); `raw` receives a new handle or stays null on error.
        err.run(|e| unsafe {
            ffi::sdv_cpu_patches_create(self.raw.as_ptr(), &mut raw, e, ERR_LEN)
        })?;
        let raw = NonNull::new(raw).ok_or_else(|| internal("no CPU patch table returned"))?;
        Ok(OsdCpuPatchTable {
            raw,
            table: PhantomData,
        })
    }
}

impl OsdCpuPatchTable<'_> {
    /// The limit surface at `locations` (ptex face, u, v) for data of
    /// `width` components at the points the table's control vertices index
    /// (`points`: every level's vertices, then the local points), as
    /// OpenSubdiv's evaluators compute it, in `f32`: each location's patch
    /// found by `Far::PatchMap::FindPatch` into an `Osd::PatchCoord` (u and
    /// v rounded to `f32`), then one `Osd::CpuEvaluator::EvalPatches` call.
    /// The benchmark's second reference for native evaluation (in `f32`).
    ///
    /// Refused: `width` 0, `points` not a whole number of points or too few
    /// for the table, a location outside the mesh or its unit square or on
    /// a hole (an error naming the location's index), a table with patches
    /// without a basis (legacy Gregory).
    pub fn evaluate(
        &self,
        points: &[f32],
        width: usize,
        locations: &[(u32, f64, f64)],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples<f32>> {
        let mut out = SurfaceSamples::default();
        self.evaluate_into(points, width, locations, derivatives, &mut out)?;
        Ok(out)
    }

    /// [`Self::evaluate`] into `out`, reusing its columns' memory (as a
    /// program calling OpenSubdiv keeps its output buffers from one call
    /// to the next); on error `out` is left empty.
    pub fn evaluate_into(
        &self,
        points: &[f32],
        width: usize,
        locations: &[(u32, f64, f64)],
        derivatives: Derivatives,
        out: &mut SurfaceSamples<f32>,
    ) -> Result<()> {
        let reuse = std::mem::take(&mut out.values);
        let mut at = AtLocations::new(points.len(), width, locations, derivatives, reuse)?;
        let outs = at.outputs();
        let mut err = ErrBuf::new();
        // SAFETY: the table and the one it was made of are live; `points`
        // holds `at.points` points of `width` values; the location arrays
        // hold `at.len()` entries and every non-null output
        // `at.len() * width` values, as passed.
        err.run(|e| unsafe {
            ffi::sdv_cpu_patches_evaluate(
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
}
