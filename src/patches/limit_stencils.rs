//! Limit stencils at arbitrary locations (`Far::LimitStencilTableFactory`
//! with `LocationArray`s): for each (ptex face, u, v), the limit surface's
//! position — and first, optionally second, derivatives — as weights of the
//! base vertices, built as OpenSubdiv builds them.
//!
//! OpenSubdiv's recipe, followed step by step: a stencil table of every
//! refined vertex over the base vertices (control vertices included; every
//! level after adaptive refinement, the last after uniform refinement), the
//! local points of a Gregory-end-capped patch table appended to it,
//! factorized over the base vertices; then for each location the patch
//! `PatchMap` finds, the basis weights `EvaluateBasis` gives, and the sum of
//! the patch's control points' stencils by those weights. Terms merge by
//! base vertex in order of first contribution, and zero weights are skipped
//! exactly where OpenSubdiv's `StencilBuilder` skips them, so the stencils
//! have OpenSubdiv's sizes and indices, term by term. Every stage computes
//! in [`LimitStencilOptions::precision`], as
//! `LimitStencilTableFactoryReal<REAL>` does: in `f32` the weights are
//! OpenSubdiv's `float` ones bit for bit (far tutorial 5_3's, position and
//! derivatives: `tests/far_tutorials.rs`); in `f64` they agree to the
//! native basis functions' rounding (about 1e-16: the native `f64` basis
//! keeps its own operation order).
//! A location in a hole has no stencil, as in OpenSubdiv:
//! [`LocationStencils::locations`] says which location each stencil is for.

use super::basis::{BasisBuffer, evaluate_basis_into};
use super::eval::{PatchData, check_location, patch_of};
use super::exact::exact_sharpness;
use super::{
    Derivatives, EndCapType, Evaluation, Partials, PatchMap, PatchOptions, PatchTable, PatchType,
};
use crate::error::{Buffer, Error, Result, StencilFault};
use crate::real::{Precision, Real};
use crate::refiner::{AdaptiveRefiner, Refiner};
use crate::stencil::{StencilInterpolation, StencilOptions, StencilTable};
use std::borrow::Cow;

/// `LimitStencilTableFactory::Options`, with OpenSubdiv 3.5's defaults
/// ([`LimitStencilOptions::new`]: vertex data, first derivatives, no second
/// derivatives, face-varying channel 0).
///
/// ```
/// use subdiv::patches::LimitStencilOptions;
/// let o = LimitStencilOptions::new().second_derivatives(true);
/// assert!(o.first_derivatives && o.second_derivatives);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub struct LimitStencilOptions {
    /// `interpolationMode` (vertex).
    pub interpolation: StencilInterpolation,
    /// `generate1stDerivatives` (true).
    pub first_derivatives: bool,
    /// `generate2ndDerivatives` (false; implies the first derivatives'
    /// weights too, as in OpenSubdiv).
    pub second_derivatives: bool,
    /// `fvarChannel` (0): the channel of face-varying stencils.
    pub fvar_channel: usize,
    /// How the patches' bases are evaluated: OpenSubdiv's `EvaluateBasis`
    /// (the default) or the exact limit ([`Evaluation::ExactLimit`]: the
    /// derivative weights under non-quad faces with respect to the ptex
    /// face, half OpenSubdiv's first and a quarter its second; the tables
    /// these stencils are built over have no single-crease patches).
    pub evaluation: Evaluation,
    /// The precision every weight is computed in, as
    /// `LimitStencilTableFactoryReal<REAL>` computes them: `f64` (the
    /// default here) or `f32` (OpenSubdiv's `LimitStencilTableFactory`):
    /// the refined vertices' stencils, the patch table's local points
    /// (`patchPrecision` the same), their factorization, the basis
    /// ([`evaluate_basis_in`](super::evaluate_basis_in)) and the sums. The
    /// weights are stored widened to `f64`, exactly.
    pub precision: Precision,
}

impl Default for LimitStencilOptions {
    fn default() -> Self {
        LimitStencilOptions {
            interpolation: StencilInterpolation::Vertex,
            first_derivatives: true,
            second_derivatives: false,
            fvar_channel: 0,
            evaluation: Evaluation::OpenSubdiv,
            precision: Precision::F64,
        }
    }
}

impl LimitStencilOptions {
    /// OpenSubdiv 3.5's defaults.
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets `interpolationMode`.
    pub fn interpolation(mut self, interpolation: StencilInterpolation) -> Self {
        self.interpolation = interpolation;
        self
    }

    /// Sets `generate1stDerivatives`.
    pub fn first_derivatives(mut self, yes: bool) -> Self {
        self.first_derivatives = yes;
        self
    }

    /// Sets `generate2ndDerivatives`.
    pub fn second_derivatives(mut self, yes: bool) -> Self {
        self.second_derivatives = yes;
        self
    }

    /// Sets `fvarChannel`.
    pub fn fvar_channel(mut self, channel: usize) -> Self {
        self.fvar_channel = channel;
        self
    }

    /// Sets how the patches' bases are evaluated
    /// ([`LimitStencilOptions::evaluation`]).
    pub fn evaluation(mut self, evaluation: Evaluation) -> Self {
        self.evaluation = evaluation;
        self
    }

    /// Sets the precision the weights are computed in
    /// ([`LimitStencilOptions::precision`]).
    pub fn precision(mut self, precision: Precision) -> Self {
        self.precision = precision;
        self
    }

    /// The derivatives whose weights the stencils carry.
    pub fn derivatives(&self) -> Derivatives {
        if self.second_derivatives {
            Derivatives::Second
        } else if self.first_derivatives {
            Derivatives::First
        } else {
            Derivatives::None
        }
    }
}

/// Limit stencils at locations (`Far::LimitStencilTable`): stencil `i` is
/// terms `offsets[i]..offsets[i] + sizes[i]` of `indices` (base vertices)
/// with the position weights `weights.point` and, when asked for, the
/// derivative weights `weights.du`, `weights.dv` (and `duu`, `duv`, `dvv`)
/// of the same terms.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LocationStencils {
    /// Base vertices (or base face-varying values) the indices refer to.
    pub control_vertices: usize,
    /// For each stencil, the index of its location in the list given
    /// (locations in holes have none).
    pub locations: Vec<usize>,
    /// Number of terms of each stencil.
    pub sizes: Vec<u32>,
    /// First term of each stencil.
    pub offsets: Vec<u32>,
    /// Base vertex of each term.
    pub indices: Vec<u32>,
    /// The weights of each term: positions in `point`, derivatives in the
    /// other fields (empty when not generated).
    pub weights: Partials,
}

impl LocationStencils {
    /// Number of stencils.
    pub fn len(&self) -> usize {
        self.sizes.len()
    }

    /// Whether there is no stencil.
    pub fn is_empty(&self) -> bool {
        self.sizes.is_empty()
    }

    /// The stencils applied to `base` (`width` values per base vertex): the
    /// limit values at the locations with a stencil, and the derivatives
    /// whose weights the stencils have, stencil after stencil.
    pub fn apply(&self, width: usize, base: &[f64]) -> Result<Partials> {
        if width == 0 {
            return Err(Error::ZeroWidth);
        }
        let expected = self.control_vertices.saturating_mul(width);
        if base.len() != expected {
            return Err(Error::BufferLength {
                buffer: Buffer::Base,
                expected,
                got: base.len(),
            });
        }
        let w = &self.weights;
        let kinds = [&w.point, &w.du, &w.dv, &w.duu, &w.duv, &w.dvv];
        let mut out: [Vec<f64>; 6] = Default::default();
        for (o, k) in out.iter_mut().zip(kinds) {
            if k.is_empty() {
                continue;
            }
            *o = crate::alloc::try_vec(0.0, self.len().saturating_mul(width))?;
            for (s, dst) in o.chunks_exact_mut(width).enumerate() {
                let terms = self.offsets[s] as usize..(self.offsets[s] + self.sizes[s]) as usize;
                for (&i, &wt) in self.indices[terms.clone()].iter().zip(&k[terms]) {
                    let src = base
                        .get(i as usize * width..(i as usize + 1) * width)
                        .ok_or_else(|| Error::BufferLength {
                            buffer: Buffer::Base,
                            expected: (i as usize + 1) * width,
                            got: base.len(),
                        })?;
                    for (d, &x) in dst.iter_mut().zip(src) {
                        *d += wt * x;
                    }
                }
            }
        }
        Ok(Partials::from_columns(out))
    }
}

impl AdaptiveRefiner {
    /// Limit stencils at `locations` (ptex face, u, v) over the base
    /// vertices, as `LimitStencilTableFactory::Create(refiner, locations)`
    /// builds them when given no tables of its own: see the
    /// [module](crate::patches) and [`LocationStencils`]. Locations in holes
    /// get no stencil.
    ///
    /// Errors: a ptex face out of range ([`Error::NoSuchPtexFace`]), a
    /// coordinate outside [0, 1] ([`Error::Location`]), and what building
    /// the patch table refuses. Varying stencils use the table's varying
    /// patches (each patch's face, bilinear), as `EvaluateBasisVarying`
    /// does; face-varying ones the channel's linear patches over the
    /// channel's values (indices of the base level's values). Not native
    /// ([`Error::NotYetSupported`]): face-varying stencils after a
    /// refinement that considered face-varying channels, over the channel's
    /// own non-linear patches with local points — OpenSubdiv 3.5 reads its
    /// single-precision face-varying local points as double there
    /// (uninitialised weights; the bridge refuses it), so there is nothing
    /// to be identical to.
    ///
    /// ```
    /// use subdiv::patches::LimitStencilOptions;
    /// use subdiv::{refiner::Refiner, shapes, AdaptiveOptions, Options};
    /// let cube = shapes::cube();
    /// let r = Refiner::new(&cube, &Options::default())?
    ///     .refine_adaptive(AdaptiveOptions::new(3), &[])?;
    /// let s = r.location_stencils(&[(0, 0.5, 0.5)], &LimitStencilOptions::new())?;
    /// // The centre of a face: a weighted sum of the cube's 8 corners.
    /// assert_eq!(s.sizes, [8]);
    /// let sum: f64 = s.weights.point.iter().sum();
    /// assert!((sum - 1.0).abs() < 1e-12);
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn location_stencils(
        &self,
        locations: &[(u32, f64, f64)],
        options: &LimitStencilOptions,
    ) -> Result<LocationStencils> {
        let adaptive = self.adaptive_options();
        let patch_options = patch_options(
            options,
            adaptive.use_inf_sharp_patch,
            !adaptive.consider_fvar_channels,
            self.fvar_channel_count(),
        )?;
        let table = self.patch_table(&patch_options, &[])?;
        self.location_stencils_over(&table, locations, options)
    }

    /// [`AdaptiveRefiner::location_stencils`] over a patch table of this
    /// refinement built with options of the caller's choosing.
    pub(crate) fn location_stencils_over(
        &self,
        table: &PatchTable,
        locations: &[(u32, f64, f64)],
        options: &LimitStencilOptions,
    ) -> Result<LocationStencils> {
        let base = control_count(
            options,
            self.level_counts(0)?.vertices,
            (0..self.fvar_channel_count()).map(|c| self.fvar_levels(c)[0].value_count()),
        );
        let refined = || {
            let o = refined_options(options, true);
            match options.precision {
                Precision::F64 => self.stencil_table_in::<f64>(&o),
                Precision::F32 => self.stencil_table_in::<f32>(&o),
            }
        };
        at_locations(table, base, refined, locations, options)
    }
}

impl Refiner {
    /// Limit stencils at `locations` after uniform refinement, as
    /// `LimitStencilTableFactory::Create` builds them: over the uniform
    /// patch table of the last level (bilinear quads or linear triangles),
    /// so the "limit" is the last level's piecewise-linear surface, as in
    /// OpenSubdiv. Errors as for
    /// [`AdaptiveRefiner::location_stencils`], and [`Error::PatchOptions`]
    /// before any level is refined (OpenSubdiv's uniform table of level 0
    /// leaves its patches unset); varying stencils use the same linear
    /// patches.
    pub fn location_stencils(
        &self,
        locations: &[(u32, f64, f64)],
        options: &LimitStencilOptions,
    ) -> Result<LocationStencils> {
        if self.max_level() == 0 {
            return Err(unrefined());
        }
        let patch_options = patch_options(options, false, true, self.fvar.len())?;
        let table = self.patch_table(&patch_options)?;
        let base = control_count(
            options,
            self.levels[0].vertex_count,
            self.fvar.iter().map(|c| c[0].value_count()),
        );
        let refined = || {
            let o = refined_options(options, false);
            match options.precision {
                Precision::F64 => self.stencil_table_in::<f64>(&o),
                Precision::F32 => self.stencil_table_in::<f32>(&o),
            }
        };
        at_locations(&table, base, refined, locations, options)
    }
}

/// The base vertices a refinement's stencils are over: the base level's
/// `vertices`, or for face-varying stencils the base values of the channel
/// (`channel_values`: each channel's count; the channel was checked when
/// the patch table was built).
fn control_count(
    options: &LimitStencilOptions,
    vertices: usize,
    mut channel_values: impl Iterator<Item = usize>,
) -> usize {
    match options.interpolation {
        StencilInterpolation::FaceVarying => channel_values.nth(options.fvar_channel).unwrap_or(0),
        _ => vertices,
    }
}

/// The stencils at `locations` from a refinement's patch table `table`, its
/// number of base vertices (or values) `base` and its refined stencils
/// `refined`, asked for once the locations are checked.
fn at_locations(
    table: &PatchTable,
    base: usize,
    refined: impl FnOnce() -> Result<StencilTable>,
    locations: &[(u32, f64, f64)],
    options: &LimitStencilOptions,
) -> Result<LocationStencils> {
    for &(face, u, v) in locations {
        check_location(table, face, u, v)?;
    }
    crate::alloc::guard(None, || build(&refined()?, table, base, locations, options))
}

/// Vertex limit stencils at `locations` from `table` over a refinement of
/// `base` base vertices whose refined vertices' stencils (intermediate
/// levels, control vertices included: [`AdaptiveRefiner::refined_vertex_stencils`])
/// are `refined` — for callers evaluating one table many times.
pub(crate) fn stencils_at(
    table: &PatchTable,
    base: usize,
    refined: &StencilTable,
    locations: &[(u32, f64, f64)],
    options: &LimitStencilOptions,
) -> Result<LocationStencils> {
    for &(face, u, v) in locations {
        check_location(table, face, u, v)?;
    }
    crate::alloc::guard(None, || build(refined, table, base, locations, options))
}

impl AdaptiveRefiner {
    /// The stencils of every refined vertex over the base vertices, as
    /// vertex limit stencils at locations use them.
    pub(crate) fn refined_vertex_stencils(&self) -> Result<StencilTable> {
        self.stencil_table_with(&refined_options(&LimitStencilOptions::new(), true))
    }
}

/// The refusal of limit stencils on an unrefined uniform refiner.
pub(crate) fn unrefined() -> Error {
    Error::PatchOptions {
        reason: "limit stencils after uniform refinement need at least one level: \
                 OpenSubdiv 3.5's uniform patch table of level 0 leaves its patches unset"
            .into(),
    }
}

/// The patch table `LimitStencilTableFactory` builds: the factory's
/// defaults with local points in the stencils' precision, base-level indices,
/// Gregory end caps, varying tables only for varying stencils, the
/// refinement's infinitely-sharp patches, and for face-varying stencils the
/// channel's patches (legacy linear ones when `linear_fvar`: after uniform
/// refinement, or adaptive refinement that did not consider the channels),
/// its values offset past the base level's. `channels` is the refiner's
/// count, which the face-varying channel must be below.
fn patch_options(
    options: &LimitStencilOptions,
    inf_sharp: bool,
    linear_fvar: bool,
    channels: usize,
) -> Result<PatchOptions> {
    let mut o = PatchOptions::new()
        .end_caps(EndCapType::GregoryBasis)
        .inf_sharp_patch(inf_sharp);
    o.patch_precision_double = options.precision == Precision::F64;
    o.include_base_level_indices = true;
    o.varying_tables = options.interpolation == StencilInterpolation::Varying;
    if options.interpolation == StencilInterpolation::FaceVarying {
        if options.fvar_channel >= channels {
            return Err(Error::NoSuchChannel {
                channel: options.fvar_channel,
                count: channels,
            });
        }
        o.fvar_tables = true;
        o.include_fvar_base_level_indices = true;
        o.fvar_channels = vec![options.fvar_channel];
        o.fvar_legacy_linear_patches = linear_fvar;
    }
    Ok(o)
}

/// The refined vertices' stencils `LimitStencilTableFactory` builds: control
/// vertices and offsets, every level after adaptive refinement, the last
/// after uniform refinement.
fn refined_options(options: &LimitStencilOptions, adaptive: bool) -> StencilOptions {
    StencilOptions {
        interpolation: options.interpolation,
        generate_offsets: true,
        generate_control_vertices: true,
        generate_intermediate_levels: adaptive,
        fvar_channel: options.fvar_channel,
        ..StencilOptions::new()
    }
}

/// Stencils over the base vertices merged term by term as OpenSubdiv's
/// `StencilBuilder` merges them (`compactWeights`): a base vertex's first
/// term is stored as it is, later ones are added to it, and a stencil's
/// terms keep the order of their vertices' first contributions. `K` weights
/// per term (position and derivatives).
struct Builder<const K: usize, R> {
    /// Position in the current stencil of each base vertex, or `u32::MAX`.
    slot: Vec<u32>,
    /// First term of the current stencil.
    start: usize,
    offsets: Vec<u32>,
    indices: Vec<u32>,
    weights: [Vec<R>; K],
}

impl<const K: usize, R: Real> Builder<K, R> {
    fn new(base: usize) -> Self {
        Builder {
            slot: crate::alloc::vec_or_unwind(u32::MAX, base),
            start: 0,
            offsets: Vec::new(),
            indices: Vec::new(),
            weights: std::array::from_fn(|_| Vec::new()),
        }
    }

    /// Adds each term of stencil row (`indices`, `weights`) times `w`
    /// (`StencilBuilder::Index::AddWithWeight(StencilReal, ...)`): nothing
    /// when every `w` is zero, no term whose own weight is zero.
    fn add_row(&mut self, indices: &[u32], weights: &[R], w: [R; K]) {
        if w.iter().all(|&x| x == R::ZERO) {
            return;
        }
        // Room for every term of the row, or the unwinding `alloc::guard`
        // turns into an error.
        let n = indices.len();
        if self.indices.try_reserve(n).is_err()
            || self.weights.iter_mut().any(|c| c.try_reserve(n).is_err())
        {
            let terms = self.indices.len().saturating_add(n);
            crate::alloc::fail(terms.saturating_mul(4 + size_of::<R>() * K));
        }
        for (&i, &x) in indices.iter().zip(weights) {
            if x == R::ZERO {
                continue;
            }
            let slot = &mut self.slot[i as usize];
            if *slot == u32::MAX {
                *slot = (self.indices.len() - self.start) as u32;
                self.indices.push(i);
                for (column, &wk) in self.weights.iter_mut().zip(&w) {
                    column.push(wk * x);
                }
            } else {
                let at = self.start + *slot as usize;
                for (column, &wk) in self.weights.iter_mut().zip(&w) {
                    column[at] += wk * x;
                }
            }
        }
    }

    /// Closes the current stencil.
    fn end(&mut self) {
        for &i in &self.indices[self.start..] {
            self.slot[i as usize] = u32::MAX;
        }
        if self.offsets.try_reserve(1).is_err() {
            crate::alloc::fail(self.offsets.len().saturating_mul(8));
        }
        self.offsets.push(self.start as u32);
        self.start = self.indices.len();
    }

    /// The stencil `s` closed so far.
    fn row(&self, s: usize) -> (&[u32], &[R]) {
        let start = self.offsets[s] as usize;
        let end = self
            .offsets
            .get(s + 1)
            .map_or(self.indices.len(), |&o| o as usize);
        (&self.indices[start..end], &self.weights[0][start..end])
    }
}

/// The stencils of every location of `locations` not in a hole, over the
/// `base` base vertices, from the refined vertices' stencils `refined` and
/// `table` (whose local points are appended to them, factorized, as
/// `AppendLocalPointStencilTable` does).
fn build(
    refined: &StencilTable,
    table: &PatchTable,
    base: usize,
    locations: &[(u32, f64, f64)],
    options: &LimitStencilOptions,
) -> Result<LocationStencils> {
    match options.precision {
        Precision::F64 => build_in::<f64>(refined, table, base, locations, options),
        Precision::F32 => build_in::<f32>(refined, table, base, locations, options),
    }
}

/// The weights of a table (`f64`) in `R`: the same slice for `f64`,
/// narrowed (exactly, for weights computed in `R`) otherwise.
fn weights_in<R: Real>(weights: &[f64]) -> Cow<'_, [R]> {
    match (R::PRECISION, bytemuck::try_cast_slice(weights)) {
        (Precision::F64, Ok(same)) => Cow::Borrowed(same),
        _ => Cow::Owned(weights.iter().map(|&x| R::from_f64(x)).collect()),
    }
}

/// [`build`] with every weight computed in `R`.
fn build_in<R: Real>(
    refined: &StencilTable,
    table: &PatchTable,
    base: usize,
    locations: &[(u32, f64, f64)],
    options: &LimitStencilOptions,
) -> Result<LocationStencils> {
    // Varying stencils of an adaptive table use its varying patches (the
    // patches' faces, bilinear) and varying local points; a uniform table's
    // linear patches serve both. Face-varying stencils use the channel's
    // patches, linear: no local points.
    let data = match options.interpolation {
        StencilInterpolation::Vertex => PatchData::Vertex,
        StencilInterpolation::Varying => PatchData::Varying,
        // The table's only channel.
        StencilInterpolation::FaceVarying => PatchData::FaceVarying(0),
    };
    let none = StencilTable::default();
    if let PatchData::FaceVarying(k) = data
        && table
            .fvar_channels
            .get(k)
            .is_some_and(|c| !matches!(c.regular_type, PatchType::Quads | PatchType::Triangles))
    {
        return Err(Error::NotYetSupported(
            "face-varying location stencils over non-linear face-varying patches \
             (OpenSubdiv 3.5 reads uninitialised local-point weights there)",
        ));
    }
    // The local points over the base vertices.
    let mut local = Builder::<1, R>::new(base);
    let lp = match data {
        PatchData::Vertex => &table.local_point_stencils,
        PatchData::Varying if table.feature_adaptive => &table.local_point_varying_stencils,
        _ => &none,
    };
    let (refined_w, lp_w) = (
        weights_in::<R>(&refined.weights),
        weights_in::<R>(&lp.weights),
    );
    for s in 0..lp.len() {
        let (indices, weights) = row(lp, &lp_w, s)?;
        for (&i, &w) in indices.iter().zip(weights) {
            if w != R::ZERO {
                let (ri, rw) = row(refined, &refined_w, i as usize)?;
                local.add_row(ri, rw, [w]);
            }
        }
        local.end();
    }
    let source = |cv: u32| {
        let cv = cv as usize;
        if cv < refined.len() {
            row(refined, &refined_w, cv)
        } else {
            Ok(local.row(cv - refined.len()))
        }
    };
    let at = Locator {
        table,
        map: PatchMap::new(table),
        derivatives: options.derivatives(),
        data,
        evaluation: options.evaluation,
    };
    let (found, offsets, indices, weights) = match options.derivatives() {
        Derivatives::None => at.stencils::<1, R>(base, locations, &source)?,
        Derivatives::First => at.stencils::<3, R>(base, locations, &source)?,
        Derivatives::Second => at.stencils::<6, R>(base, locations, &source)?,
    };
    let ends = offsets
        .iter()
        .skip(1)
        .copied()
        .chain([indices.len() as u32]);
    let sizes = offsets.iter().zip(ends).map(|(&a, b)| b - a).collect();
    Ok(LocationStencils {
        control_vertices: base,
        locations: found,
        sizes,
        offsets,
        indices,
        weights: Partials::from_columns(weights),
    })
}

/// Finds the patch of each location and evaluates its basis.
struct Locator<'a> {
    table: &'a PatchTable,
    map: PatchMap,
    derivatives: Derivatives,
    /// Which patches to evaluate.
    data: PatchData,
    /// OpenSubdiv's basis or the exact limit's.
    evaluation: Evaluation,
}

/// Which locations have a stencil, and the stencils' offsets, indices and
/// six weight columns (those not generated empty).
type Built = (Vec<usize>, Vec<u32>, Vec<u32>, [Vec<f64>; 6]);

impl Locator<'_> {
    /// The stencils with `K` weights per term (position, then derivatives in
    /// `EvaluateBasis`' order), each control point's stencil given by
    /// `source`.
    fn stencils<'s, const K: usize, R: Real>(
        &self,
        base: usize,
        locations: &[(u32, f64, f64)],
        source: &impl Fn(u32) -> Result<(&'s [u32], &'s [R])>,
    ) -> Result<Built> {
        let mut b = Builder::<K, R>::new(base);
        let mut found = Vec::new();
        if found.try_reserve_exact(locations.len()).is_err() {
            crate::alloc::fail(locations.len().saturating_mul(8));
        }
        let mut basis: BasisBuffer<R> = [[R::ZERO; 20]; 6];
        for (n, &(face, u, v)) in locations.iter().enumerate() {
            // The location in `R`, as OpenSubdiv's `LocationArray` holds it.
            let (u, v) = (R::from_f64(u), R::from_f64(v));
            // No patch: a hole, which OpenSubdiv leaves without a stencil.
            let Some(h) = self.map.find_patch(face, u.to_f64(), v.to_f64()) else {
                continue;
            };
            let (patch_type, param, cvs) = patch_of(self.table, self.data, h)?;
            let exact = exact_sharpness(self.evaluation, self.table, self.data, h);
            let count =
                evaluate_basis_into(patch_type, param, u, v, self.derivatives, exact, &mut basis)?;
            for (k, &cv) in cvs.iter().enumerate().take(count) {
                let (indices, weights) = source(cv)?;
                b.add_row(indices, weights, std::array::from_fn(|j| basis[j][k]));
            }
            b.end();
            found.push(n);
        }
        let mut columns = b.weights.into_iter();
        let weights = std::array::from_fn(|_| {
            let column = columns.next().unwrap_or_default();
            column.iter().map(|x| x.to_f64()).collect()
        });
        Ok((found, b.offsets, b.indices, weights))
    }
}

/// Row `i` of a stencil table, or the error naming the point without one
/// (a patch naming a point its tables lack).
fn row<'a, R>(table: &'a StencilTable, weights: &'a [R], i: usize) -> Result<(&'a [u32], &'a [R])> {
    let (Some(&offset), Some(&size)) = (table.offsets.get(i), table.sizes.get(i)) else {
        return Err(Error::StencilOutOfRange {
            index: i,
            count: table.len(),
        });
    };
    let terms = offset as usize..offset as usize + size as usize;
    match (table.indices.get(terms.clone()), weights.get(terms)) {
        (Some(indices), Some(weights)) => Ok((indices, weights)),
        _ => Err(Error::MalformedStencils(StencilFault::RowOutOfRange {
            row: i,
        })),
    }
}
