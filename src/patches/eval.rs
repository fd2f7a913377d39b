//! The limit surface at (ptex face, u, v) locations from a patch table, the
//! native way (OpenSubdiv's far tutorials 5_1 and 5_2): the data refined
//! through every level and the local points from their stencils
//! ([`AdaptiveRefiner::patch_points`]), then for each location the patch
//! that covers it ([`PatchMap`]), its basis ([`evaluate_basis`]) and the
//! weighted sum of its control points ([`evaluate`]). A bicubic B-spline
//! patch's positions and first derivatives are summed as two passes of
//! curves instead (each row of control points along s, then the rows
//! along t): with first derivatives 132 multiply-adds against the 192 of
//! sixteen weights per table and their sums, and no weights written and
//! read back. A regular Loop patch's are summed from its polynomial's
//! coefficients ([`LoopPolynomial`]), computed once per patch. Both give
//! the same surface to rounding (within 1e-12 of OpenSubdiv's, as every
//! evaluation is: `tests/native_patches.rs`).

use super::basis::{BasisBuffer, crease_of, evaluate_basis_into, regular_curves, triangle_coords};
use super::exact::exact_sharpness;
use super::loop_poly::{LoopPolynomial, loop_points, loop_polynomials};
use super::map::Found;
use super::{
    Derivatives, Evaluation, PatchHandle, PatchMap, PatchParam, PatchTable, PatchType,
    SurfaceSamples,
};
use crate::error::{Buffer, Error, Result};
use crate::real::Real;
use crate::refiner::AdaptiveRefiner;

/// Which primvar a table's patches are evaluated for: vertex data over the
/// patches themselves (`EvaluateBasis`), varying data over each patch's
/// varying patch (`EvaluateBasisVarying`: the patch's face, bilinear; a
/// uniform table's own linear patches), or the values of the table's
/// face-varying channel `k` (`table.fvar_channels[k]`,
/// `EvaluateBasisFaceVarying`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PatchData {
    /// Vertex data.
    #[default]
    Vertex,
    /// Varying data.
    Varying,
    /// Face-varying channel `k` of the table (not of the refiner).
    FaceVarying(usize),
}

/// The patch `handle` names in `table` for `data`: its type, parameter and
/// control points (vertices, varying vertices or face-varying values).
/// Errors: a handle of another table, a table without varying patches or
/// without that face-varying channel.
pub(crate) fn patch_of(
    table: &PatchTable,
    data: PatchData,
    handle: PatchHandle,
) -> Result<(PatchType, PatchParam, &[u32])> {
    let missing = |patches| Error::NoSuchPatch {
        array: handle.array,
        patch: handle.patch,
        arrays: table.arrays.len(),
        patches,
    };
    let array = table.arrays.get(handle.array).ok_or_else(|| missing(0))?;
    let param = *array
        .params
        .get(handle.patch)
        .ok_or_else(|| missing(array.len()))?;
    let vertex = || {
        let n = array.patch_type.control_vertices();
        let cvs = array
            .control_vertices
            .get(handle.patch * n..(handle.patch + 1) * n)
            .ok_or_else(|| missing(array.len()))?;
        Ok((array.patch_type, param, cvs))
    };
    match data {
        PatchData::Vertex => vertex(),
        // A uniform table's linear patches are their own varying patches.
        PatchData::Varying if !table.feature_adaptive => vertex(),
        PatchData::Varying => {
            let cvs = array.patch_varying_vertices(handle.patch);
            if cvs.is_empty() {
                return Err(Error::PatchOptions {
                    reason:
                        "the table has no varying patches (built without generateVaryingTables)"
                            .into(),
                });
            }
            Ok((table.varying_patch_type, param, cvs))
        }
        PatchData::FaceVarying(k) => {
            let Some(channel) = table.fvar_channels.get(k) else {
                return Err(Error::NoSuchChannel {
                    channel: k,
                    count: table.fvar_channels.len(),
                });
            };
            let i = table.patch_index(handle);
            let param = *channel.params.get(i).ok_or_else(|| missing(array.len()))?;
            Ok((channel.patch_type(i), param, channel.patch_values(i)))
        }
    }
}

impl AdaptiveRefiner {
    /// The points `table`'s control vertices index, for data of `width`
    /// components given at the base vertices (`base`): every level's
    /// vertices, base first, interpolated level by level, then the local
    /// points from their stencils (`ComputeLocalPointValues`).
    ///
    /// Refused: `width` 0, `base` not one value per base vertex, a table
    /// whose local points name vertices this refinement does not have.
    pub fn patch_points(&self, table: &PatchTable, width: usize, base: &[f64]) -> Result<Vec<f64>> {
        if width == 0 {
            return Err(Error::ZeroWidth);
        }
        let expected = self.level_counts(0)?.vertices.saturating_mul(width);
        if base.len() != expected {
            return Err(Error::BufferLength {
                buffer: Buffer::Base,
                expected,
                got: base.len(),
            });
        }
        let mut points = base.to_vec();
        let mut level = base.to_vec();
        for l in 1..=self.max_level() {
            level = self.interpolate(l, width, &level)?;
            points.extend_from_slice(&level);
        }
        if !table.local_point_stencils.is_empty() {
            let local = table.local_point_stencils.apply(width, &points)?;
            points.extend_from_slice(&local);
        }
        Ok(points)
    }

    /// The points `table`'s patches for `data` index, from the data at the
    /// base level (`base`, `width` components per base vertex, or per value
    /// of the face-varying channel): for vertex data
    /// [`AdaptiveRefiner::patch_points`]; for varying data every level's
    /// varying values (linear interpolation) and the varying local points;
    /// for face-varying channel `k` of the table every level's values of
    /// the refiner's channel it holds, base first, then the channel's local
    /// points (non-linear face-varying patches' end caps) from their
    /// stencils.
    pub fn patch_data_points(
        &self,
        table: &PatchTable,
        data: PatchData,
        width: usize,
        base: &[f64],
    ) -> Result<Vec<f64>> {
        if data == PatchData::Vertex {
            return self.patch_points(table, width, base);
        }
        let channel = match data {
            PatchData::FaceVarying(k) => Some(
                table
                    .fvar_channels
                    .get(k)
                    .ok_or(Error::NoSuchChannel {
                        channel: k,
                        count: table.fvar_channels.len(),
                    })?
                    .channel,
            ),
            _ => None,
        };
        // A table of another refinement may name a channel this one lacks.
        if let Some(c) = channel.filter(|&c| c >= self.fvar_channel_count()) {
            return Err(Error::NoSuchChannel {
                channel: c,
                count: self.fvar_channel_count(),
            });
        }
        if width == 0 {
            return Err(Error::ZeroWidth);
        }
        let count = match channel {
            Some(c) => self.fvar_levels(c)[0].value_count(),
            None => self.level_counts(0)?.vertices,
        };
        if base.len() != count.saturating_mul(width) {
            return Err(Error::BufferLength {
                buffer: Buffer::Base,
                expected: count.saturating_mul(width),
                got: base.len(),
            });
        }
        let mut points = base.to_vec();
        let mut level = base.to_vec();
        for l in 1..=self.max_level() {
            level = match channel {
                Some(c) => self.interpolate_face_varying(c, l, width, &level)?,
                None => self.interpolate_varying(l, width, &level)?,
            };
            points.extend_from_slice(&level);
        }
        let local = match data {
            PatchData::FaceVarying(k) => {
                table.fvar_channels.get(k).map(|c| &c.local_point_stencils)
            }
            _ => Some(&table.local_point_varying_stencils),
        };
        if let Some(stencils) = local.filter(|s| !s.is_empty()) {
            let local = stencils.apply(width, &points)?;
            points.extend_from_slice(&local);
        }
        Ok(points)
    }
}

/// The limit surface of `table` at `locations` (ptex face, u, v), for
/// data of `width` components at the points its control vertices index
/// (`points`, as [`AdaptiveRefiner::patch_points`] or
/// `osd::OsdPatchTable`'s refined data give them), with the derivatives
/// asked for.
///
/// `points` in `f64` or `f32` (`R`), the values in the same precision:
/// `f32` points (as OpenSubdiv's `Osd::CpuEvaluator::EvalPatches` takes
/// them) are weighed and summed in `f64` and each value rounded once, so
/// that positions are the `f64` evaluation of the same points, rounded.
///
/// Refused: a location outside the mesh's ptex faces
/// ([`Error::NoSuchPtexFace`]) or its unit square ([`Error::Location`]),
/// on a hole ([`Error::NoPatchAt`]); a patch without a native basis
/// ([`Error::NotYetSupported`]); `points` too short for the table.
///
/// ```
/// use subdiv::{patches::{self, Derivatives, PatchOptions}, refiner::Refiner, shapes, Options};
/// let mesh = shapes::cube();
/// let options = PatchOptions::new().max_isolation(3);
/// let adaptive = Refiner::new(&mesh, &Options::default())?
///     .refine_adaptive(options.refine_adaptive_options(), &[])?;
/// let table = adaptive.patch_table(&options, &[])?;
/// let points = adaptive.patch_points(&table, 3, &mesh.flat_positions())?;
/// let s = patches::evaluate(&table, &points, 3, &[(0, 0.5, 0.5)], Derivatives::First)?;
/// // The centre of a cube's face: on the face's axis, inside the cube.
/// let p = &s.values.point;
/// assert!(p[0].abs() < 1e-6 && p[1].abs() < 1e-6 && p[2].abs() < 0.5);
/// # Ok::<(), subdiv::Error>(())
/// ```
pub fn evaluate<R: Real>(
    table: &PatchTable,
    points: &[R],
    width: usize,
    locations: &[(u32, f64, f64)],
    derivatives: Derivatives,
) -> Result<SurfaceSamples<R>> {
    evaluate_with(
        &PatchMap::new(table),
        table,
        points,
        width,
        locations,
        derivatives,
    )
}

/// [`evaluate`] with `table`'s [`PatchMap`] built once by the caller, for
/// evaluating the same table again and again (each frame's points, say)
/// without rebuilding it. A map of another table gives wrong patches or
/// [`Error::NoSuchPatch`], never a panic.
pub fn evaluate_with<R: Real>(
    map: &PatchMap,
    table: &PatchTable,
    points: &[R],
    width: usize,
    locations: &[(u32, f64, f64)],
    derivatives: Derivatives,
) -> Result<SurfaceSamples<R>> {
    evaluate_data(
        map,
        table,
        PatchData::Vertex,
        points,
        width,
        locations,
        derivatives,
    )
}

/// [`evaluate_with`] for any primvar ([`PatchData`]): varying data over the
/// varying patches and points, face-varying values over a face-varying
/// channel's patches and values ([`AdaptiveRefiner::patch_data_points`]).
///
/// ```
/// use subdiv::patches::{self, Derivatives, PatchData, PatchMap, PatchOptions};
/// use subdiv::{refiner::Refiner, shapes, Options};
/// let mesh = shapes::cube_with_uvs();
/// let mut options = PatchOptions::new().max_isolation(3);
/// options.fvar_tables = true; // OpenSubdiv's linear face-varying patches
/// let adaptive = Refiner::new(&mesh, &Options::default())?
///     .refine_adaptive(options.refine_adaptive_options(), &[])?;
/// let table = adaptive.patch_table(&options, &[])?;
/// let uvs = PatchData::FaceVarying(0);
/// let points = adaptive.patch_data_points(&table, uvs, 2, &mesh.fvar_channels[0].values)?;
/// let map = PatchMap::new(&table);
/// let s = patches::evaluate_data(&map, &table, uvs, &points, 2, &[(0, 0.5, 0.5)], Derivatives::None)?;
/// assert_eq!(s.values.point.len(), 2); // the UV at the centre of ptex face 0
/// # Ok::<(), subdiv::Error>(())
/// ```
pub fn evaluate_data<R: Real>(
    map: &PatchMap,
    table: &PatchTable,
    data: PatchData,
    points: &[R],
    width: usize,
    locations: &[(u32, f64, f64)],
    derivatives: Derivatives,
) -> Result<SurfaceSamples<R>> {
    evaluate_data_as(
        Evaluation::OpenSubdiv,
        map,
        table,
        data,
        points,
        width,
        locations,
        derivatives,
    )
}

/// [`evaluate_data`] as `evaluation` asks: OpenSubdiv's `EvaluateBasis`
/// (what [`evaluate_data`] does) or the exact limit surface
/// ([`Evaluation::ExactLimit`]: single-crease patches with their
/// sharpness, derivatives under non-quad faces with respect to the ptex
/// face; see [`evaluate_basis_exact`](super::evaluate_basis_exact)).
/// Varying and face-varying patches are never single-crease patches: for
/// them only the derivatives' scale differs.
///
/// ```
/// use subdiv::patches::{self, Derivatives, Evaluation, PatchData, PatchMap, PatchOptions};
/// use subdiv::{refiner::Refiner, shapes, Options};
/// let mut mesh = shapes::cube();
/// mesh.add_crease(0, 1, 2.5);
/// let options = PatchOptions::new().max_isolation(3).single_crease_patch(true);
/// let adaptive = Refiner::new(&mesh, &Options::default())?
///     .refine_adaptive(options.refine_adaptive_options(), &[])?;
/// let table = adaptive.patch_table(&options, &[])?;
/// let points = adaptive.patch_points(&table, 3, &mesh.flat_positions())?;
/// let map = PatchMap::new(&table);
/// let at = [(0, 0.5, 0.5)];
/// let s = patches::evaluate_data_as(Evaluation::ExactLimit, &map, &table, PatchData::Vertex,
///     &points, 3, &at, Derivatives::First)?;
/// assert_eq!(s.values.du.len(), 3);
/// # Ok::<(), subdiv::Error>(())
/// ```
#[allow(clippy::too_many_arguments)]
pub fn evaluate_data_as<R: Real>(
    evaluation: Evaluation,
    map: &PatchMap,
    table: &PatchTable,
    data: PatchData,
    points: &[R],
    width: usize,
    locations: &[(u32, f64, f64)],
    derivatives: Derivatives,
) -> Result<SurfaceSamples<R>> {
    let mut out = SurfaceSamples::default();
    evaluate_data_into(
        evaluation,
        map,
        table,
        data,
        points,
        width,
        locations,
        derivatives,
        &mut out,
    )?;
    Ok(out)
}

/// [`evaluate_data_as`] into `out`, reusing its columns' memory: what
/// evaluating again and again needs (each frame's points, each batch of
/// samples), as OpenSubdiv's `EvalPatches` writes into the caller's
/// buffers. A fresh column of millions of values is fresh memory, each of
/// its pages a kernel page fault when first written (a million
/// locations on the benchmark's quad torus, positions and first
/// derivatives in `f32`: about 90 ms into fresh columns, 65 ms into
/// reused ones); a reused one was faulted in by the call before. Every
/// value of `out` is overwritten: the columns asked for are resized to
/// the locations' values, the others emptied (their memory kept).
///
/// On error `out` is emptied (its columns keep their memory), so a
/// failed call never leaves values of an earlier one looking like its
/// own.
///
/// ```
/// use subdiv::patches::{self, Derivatives, Evaluation, PatchData, PatchMap, PatchOptions, SurfaceSamples};
/// use subdiv::{refiner::Refiner, shapes, Options};
/// let mesh = shapes::cube();
/// let options = PatchOptions::new().max_isolation(2);
/// let adaptive = Refiner::new(&mesh, &Options::default())?
///     .refine_adaptive(options.refine_adaptive_options(), &[])?;
/// let table = adaptive.patch_table(&options, &[])?;
/// let map = PatchMap::new(&table);
/// let mut out = SurfaceSamples::default();
/// for scale in [1.0, 2.0] {
///     let base: Vec<f64> = mesh.flat_positions::<f64>().iter().map(|x| x * scale).collect();
///     let points = adaptive.patch_points(&table, 3, &base)?;
///     patches::evaluate_data_into(Evaluation::OpenSubdiv, &map, &table, PatchData::Vertex,
///         &points, 3, &[(0, 0.5, 0.5)], Derivatives::First, &mut out)?;
///     assert_eq!((out.values.point.len(), out.values.du.len()), (3, 3));
///     assert!(out.values.duu.is_empty());
/// }
/// // Scaled by two: the centre of face 0 twice as far along its axis.
/// let once = patches::evaluate(&table, &adaptive.patch_points(&table, 3, &mesh.flat_positions())?,
///     3, &[(0, 0.5, 0.5)], Derivatives::None)?;
/// assert_eq!(out.values.point[2], 2.0 * once.values.point[2]);
/// # Ok::<(), subdiv::Error>(())
/// ```
#[allow(clippy::too_many_arguments)]
pub fn evaluate_data_into<R: Real>(
    evaluation: Evaluation,
    map: &PatchMap,
    table: &PatchTable,
    data: PatchData,
    points: &[R],
    width: usize,
    locations: &[(u32, f64, f64)],
    derivatives: Derivatives,
    out: &mut SurfaceSamples<R>,
) -> Result<()> {
    let mut evaluate = || -> Result<()> {
        if width == 0 {
            return Err(Error::ZeroWidth);
        }
        let kinds = derivatives.columns();
        let len = locations.len().checked_mul(width).ok_or(Error::TooLarge {
            what: "evaluated values",
            count: usize::MAX,
            bits: usize::BITS,
        })?;
        // Every location checked first, in order: an error names the first
        // bad one, whatever order they are evaluated in.
        for &(face, u, v) in locations {
            check_location(table, face, u, v)?;
        }
        out.width = width;
        out.values.reuse_for(kinds, len)?;
        let loop_polynomials = if width == 3 && kinds <= 3 {
            loop_polynomials(table, data, points, locations.len())
        } else {
            Vec::new()
        };
        let evaluator = Evaluator {
            evaluation,
            map,
            table,
            data,
            points,
            width,
            derivatives,
            loop_polynomials,
        };
        let mut asked: Vec<&mut [R]> = out
            .values
            .columns_mut()
            .into_iter()
            .take(kinds)
            .map(|c| c.as_mut_slice())
            .collect();
        super::locations::evaluate_all(&evaluator, locations, &mut asked)
    };
    let done = evaluate();
    if done.is_err() {
        out.width = width;
        for column in out.values.columns_mut() {
            column.clear();
        }
    }
    done
}

/// What evaluating locations one after another keeps between them: the
/// basis buffer, and the polynomial of the last regular Loop patch
/// evaluated (for one evaluator: the handle names the patch of its table
/// and data).
pub(crate) struct EvalScratch {
    basis: BasisBuffer,
    loop_patch: Option<(PatchHandle, LoopPolynomial)>,
}

impl Default for EvalScratch {
    fn default() -> Self {
        EvalScratch {
            basis: [[0.0; 20]; 6],
            loop_patch: None,
        }
    }
}

/// What evaluating one location needs: the table, its map, the data and
/// how to evaluate.
pub(crate) struct Evaluator<'a, R> {
    evaluation: Evaluation,
    map: &'a PatchMap,
    table: &'a PatchTable,
    data: PatchData,
    points: &'a [R],
    /// Values per point.
    pub(crate) width: usize,
    derivatives: Derivatives,
    /// The regular Loop patches' polynomials by array, when computed
    /// beforehand ([`loop_polynomials`]).
    loop_polynomials: Vec<Vec<LoopPolynomial>>,
}

impl<R: Real> Evaluator<'_, R> {
    /// The bytes of data locations read: the points, the patches' control
    /// vertices (or values) and parameters.
    pub(crate) fn data_bytes(&self) -> usize {
        let patches: usize = self
            .table
            .arrays
            .iter()
            .map(|a| a.control_vertices.len() * 4 + a.params.len() * 8)
            .sum();
        std::mem::size_of_val(self.points) + patches
    }

    /// The number of ptex faces locations are on.
    pub(crate) fn ptex_faces(&self) -> usize {
        self.table.ptex_faces
    }

    /// The patch covering (`face`, `u`, `v`) ([`PatchMap::find_patch`]),
    /// [`Found::NONE`] on a hole.
    #[inline]
    pub(crate) fn locate(&self, (face, u, v): (u32, f64, f64)) -> Found {
        self.map.find(face, u, v)
    }

    /// Reads the data of the patches of `handles` that the evaluation of
    /// their locations reads first (the precomputed Loop polynomials), so
    /// that its cache misses overlap with other work.
    #[inline]
    pub(crate) fn touch(&self, handles: &[Found]) {
        if self.loop_polynomials.is_empty() {
            return;
        }
        let mut sum = 0.0;
        for h in handles.iter().filter_map(|f| f.handle()) {
            if let Some(p) = self
                .loop_polynomials
                .get(h.array)
                .and_then(|a| a.get(h.patch))
            {
                sum += p.touch();
            }
        }
        std::hint::black_box(sum);
    }

    /// Evaluates the limit at (`face`, `u`, `v`), a location
    /// [`check_location`] accepted whose patch is `found` (as
    /// [`Evaluator::locate`] found it), into value `i` of each of `columns`
    /// (one per kind of value asked for, `width` reals per value).
    #[inline]
    pub(crate) fn at(
        &self,
        (face, u, v): (u32, f64, f64),
        found: Found,
        i: usize,
        scratch: &mut EvalScratch,
        columns: &mut [&mut [R]],
    ) -> Result<()> {
        let (table, points, width) = (self.table, self.points, self.width);
        // (let-else, not `ok_or`: an error built and dropped per location
        // cost 7-9% of the evaluation.)
        let Some(handle) = found.handle() else {
            return Err(Error::NoPatchAt { face, u, v });
        };
        // A map of another table names patches this one may not have.
        let (patch_type, param, cvs) = patch_of(table, self.data, handle)?;
        let exact = exact_sharpness(self.evaluation, table, self.data, handle);
        // A B-spline patch (not a single crease's exact limit) of
        // positions, with or without first derivatives: as two passes of
        // curve sums ([`regular_curves`]).
        if let (PatchType::Regular, None, 3, [point, rest @ ..]) =
            (patch_type, crease_of(param, exact), width, &mut *columns)
            && matches!(rest.len(), 0 | 2)
            && cvs.len() >= 16
        {
            let (bs, bt, d1) = regular_curves(param, u, v, exact.is_some());
            let [p, du, dv] = regular_sums(points, &cvs[..16], (&bs, &bt), !rest.is_empty())?;
            let (du, dv) = (du.map(|x| x * d1), dv.map(|x| x * d1));
            put3(point, rest, i, [p, du, dv]);
            return Ok(());
        }
        // A regular Loop patch of positions, with or without first
        // derivatives: from its polynomial ([`LoopPolynomial`]), computed
        // beforehand or kept from the location before.
        if let (PatchType::Loop, 3, [point, rest @ ..]) = (patch_type, width, &mut *columns)
            && matches!(rest.len(), 0 | 2)
            && cvs.len() >= 12
        {
            let (s, t, d1) = triangle_coords(param, u, v, exact.is_some())?;
            let known = self
                .loop_polynomials
                .get(handle.array)
                .and_then(|polys| polys.get(handle.patch));
            let poly = match (known, &scratch.loop_patch) {
                (Some(poly), _) => poly,
                (None, Some((h, poly))) if *h == handle => poly,
                (None, _) => {
                    let poly = LoopPolynomial::of(&loop_points(points, cvs)?, param.boundary());
                    &scratch.loop_patch.insert((handle, poly)).1
                }
            };
            put3(point, rest, i, poly.evaluate(s, t, !rest.is_empty(), d1));
            return Ok(());
        }
        let buf = &mut scratch.basis;
        let n = evaluate_basis_into(patch_type, param, u, v, self.derivatives, exact, buf)?;
        // Every control point's values, once per table asked for; points
        // of width 3 (positions) summed in registers, in the same order:
        // with first derivatives, the three sums in one pass over the
        // points (nine independent sums rather than three passes of three).
        if let ([point, du, dv], 3) = (&mut *columns, width) {
            let mut acc = [[0.0f64; 3]; 3];
            let [wp, wu, wv] = [0, 1, 2].map(|k| &buf[k][..n]);
            for (k, &cv) in cvs.iter().enumerate().take(n) {
                let row = point3(points, cv)?;
                for (a, w) in acc.iter_mut().zip([wp[k], wu[k], wv[k]]) {
                    a[0] += w * row[0];
                    a[1] += w * row[1];
                    a[2] += w * row[2];
                }
            }
            for (out, a) in [point, du, dv].into_iter().zip(&acc) {
                store3(out, i, a);
            }
            return Ok(());
        }
        if width == 3 {
            for (out, weights) in columns.iter_mut().zip(buf.iter()) {
                let mut acc = [0.0f64; 3];
                for (&cv, &w) in cvs.iter().zip(&weights[..n]) {
                    let row = point3(points, cv)?;
                    acc[0] += w * row[0];
                    acc[1] += w * row[1];
                    acc[2] += w * row[2];
                }
                store3(out, i, &acc);
            }
            return Ok(());
        }
        for (out, weights) in columns.iter_mut().zip(buf.iter()) {
            let dst = &mut out[i * width..(i + 1) * width];
            dst.fill(R::ZERO);
            for (&cv, &w) in cvs.iter().zip(&weights[..n]) {
                let end = (cv as usize + 1).saturating_mul(width);
                let Some(row) = points.get(end - width..end) else {
                    return Err(Error::BufferLength {
                        buffer: Buffer::Source,
                        expected: end,
                        got: points.len(),
                    });
                };
                // (In `f64`, `*o += w * x`; in `f32`, each sum rounded.)
                for (o, &x) in dst.iter_mut().zip(row) {
                    *o = R::from_f64(o.to_f64() + w * x.to_f64());
                }
            }
        }
        Ok(())
    }
}

/// Writes value `i` (width 3) of `point`, and of `rest` when it holds the
/// first derivatives' columns (du, dv): the three values of `values`.
#[inline(always)]
fn put3<R: Real>(point: &mut [R], rest: &mut [&mut [R]], i: usize, values: [[f64; 3]; 3]) {
    let [p, du, dv] = values;
    store3(point, i, &p);
    if let [d_u, d_v] = rest {
        store3(d_u, i, &du);
        store3(d_v, i, &dv);
    }
}

/// Writes `value` as value `i` (width 3) of `out`, rounded to `R`.
#[inline(always)]
fn store3<R: Real>(out: &mut [R], i: usize, value: &[f64; 3]) {
    out[i * 3..i * 3 + 3].copy_from_slice(&value.map(R::from_f64));
}

/// A bicubic B-spline patch at one location from its curves ([`regular_curves`]'s
/// `bs` and `bt`): each row of control points (`cvs`, row by row from
/// t = 0) summed along s by `bs[0]` (and, when `first` asks for first
/// derivatives, by `bs[1]`), and the rows' sums added up along t as each
/// row is done — the point by `bt[0]`, the derivative in s from the rows'
/// `bs[1]` sums by `bt[0]`, the one in t from their `bs[0]` sums by
/// `bt[1]` (unscaled, zero without `first`). Each value's products and
/// sums in the same order as summing all the rows first: the same bits;
/// the rows are not stored and read back.
#[inline(always)]
fn regular_sums<R: Real>(
    points: &[R],
    cvs: &[u32],
    (bs, bt): (&[[f64; 4]; 2], &[[f64; 4]; 2]),
    first: bool,
) -> Result<[[f64; 3]; 3]> {
    let mut out = [[0.0f64; 3]; 3];
    for (r, row) in cvs.chunks_exact(4).enumerate() {
        let (mut p, mut d) = ([0.0f64; 3], [0.0f64; 3]);
        for (k, &cv) in row.iter().enumerate() {
            let x = point3(points, cv)?;
            let (w, dw) = (bs[0][k], bs[1][k]);
            for c in 0..3 {
                p[c] += w * x[c];
                d[c] += dw * x[c];
            }
        }
        for c in 0..3 {
            out[0][c] += bt[0][r] * p[c];
        }
        if first {
            for c in 0..3 {
                out[1][c] += bt[0][r] * d[c];
                out[2][c] += bt[1][r] * p[c];
            }
        }
    }
    Ok(out)
}

/// The three values of control point `cv` in `points` (width 3), in
/// `f64`, or the error naming the buffer too short for it.
#[inline(always)]
pub(super) fn point3<R: Real>(points: &[R], cv: u32) -> Result<[f64; 3]> {
    let row = point_of(points, cv)?;
    Ok([row[0].to_f64(), row[1].to_f64(), row[2].to_f64()])
}

/// The three values of control point `cv` in `points` (width 3), or the
/// error naming the buffer too short for it.
#[inline(always)]
pub(super) fn point_of<R>(points: &[R], cv: u32) -> Result<&[R]> {
    let start = cv as usize * 3;
    // (let-else: no error built unless it is returned.)
    let Some(row) = points.get(start..start + 3) else {
        return Err(Error::BufferLength {
            buffer: Buffer::Source,
            expected: start + 3,
            got: points.len(),
        });
    };
    Ok(row)
}

/// Location (`face`, `u`, `v`) on a ptex face of `table`, its coordinates in
/// [0, 1], or the error naming what is wrong with it.
pub(crate) fn check_location(table: &PatchTable, face: u32, u: f64, v: f64) -> Result<()> {
    if face as usize >= table.ptex_faces {
        return Err(Error::NoSuchPtexFace {
            face: face as usize,
            count: table.ptex_faces,
        });
    }
    for (coordinate, value) in [("u", u), ("v", v)] {
        if !(0.0..=1.0).contains(&value) {
            return Err(Error::Location {
                face,
                coordinate,
                value,
            });
        }
    }
    Ok(())
}
