//! Patch tables: the limit surface as OpenSubdiv's `Far::PatchTable`
//! describes it — arrays of patches (regular B-spline, Loop box-spline,
//! Gregory, bilinear...), each with its control vertices, its
//! [`PatchParam`] and its single-crease sharpness — and the options of
//! `Far::PatchTableFactory` ([`PatchOptions`]).
//!
//! The types here are plain data shared by the engines. Both build them
//! from a feature-adaptive refinement — natively
//! ([`AdaptiveRefiner::patch_table`](crate::refiner::AdaptiveRefiner::patch_table),
//! identical to OpenSubdiv's tables for Catmull-Clark and bilinear meshes
//! with every end-cap type, and for Loop meshes whose patches are all
//! regular) and through the bridge (`osd::TopologyRefiner::patch_table`).
//! The native engine locates (ptex face, u, v) in them ([`PatchMap`]),
//! evaluates the basis of their patches ([`evaluate_basis`]: B-spline,
//! Gregory, bilinear and linear patches) and the limit surface at
//! locations ([`evaluate`], over
//! [`AdaptiveRefiner::patch_points`](crate::refiner::AdaptiveRefiner::patch_points)).
//!
//! # Files
//! * this file: the types and options;
//! * `build/`: the native patch-table factory;
//! * `param.rs`, `map.rs`, `basis.rs`, `eval.rs`: parameterization, patch
//!   lookup, basis functions, evaluation at locations;
//! * `exact.rs`: the exact limit where OpenSubdiv's evaluation departs
//!   from it ([`Evaluation::ExactLimit`]: semi-sharp single-crease
//!   patches, derivatives under non-quad faces);
//! * `limit_stencils.rs`: limit stencils at locations
//!   ([`LocationStencils`], `LimitStencilTableFactory`).

pub(crate) mod basis;
mod build;
mod eval;
mod exact;
pub(crate) mod limit_stencils;
mod locations;
mod loop_poly;
mod map;
mod param;
mod triangle_basis;

use crate::stencil::StencilTable;

pub use basis::{evaluate_basis, evaluate_basis_in};
pub use eval::{
    PatchData, evaluate, evaluate_data, evaluate_data_as, evaluate_data_into, evaluate_with,
};
pub use exact::{Evaluation, evaluate_basis_exact};
pub use limit_stencils::{LimitStencilOptions, LocationStencils};
pub use map::PatchMap;
pub use param::PatchParam;

/// `Far::PatchDescriptor::Type`, with OpenSubdiv's numbering.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum PatchType {
    /// `NON_PATCH`: undefined.
    #[default]
    NonPatch = 0,
    /// `POINTS`.
    Points = 1,
    /// `LINES`.
    Lines = 2,
    /// `QUADS`: bilinear quads (uniform tables, bilinear end caps).
    Quads = 3,
    /// `TRIANGLES`: linear triangles.
    Triangles = 4,
    /// `LOOP`: regular Loop box-spline triangle (12 control vertices).
    Loop = 5,
    /// `REGULAR`: regular bicubic B-spline (16 control vertices).
    Regular = 6,
    /// `GREGORY`: legacy Gregory patch (4 control vertices and the quad
    /// offset and valence tables).
    Gregory = 7,
    /// `GREGORY_BOUNDARY`: legacy Gregory boundary patch.
    GregoryBoundary = 8,
    /// `GREGORY_BASIS`: Gregory patch of 20 local points.
    GregoryBasis = 9,
    /// `GREGORY_TRIANGLE`: triangular Gregory patch of 18 local points.
    GregoryTriangle = 10,
}

impl PatchType {
    /// Every type, in OpenSubdiv's order.
    pub const ALL: [PatchType; 11] = [
        PatchType::NonPatch,
        PatchType::Points,
        PatchType::Lines,
        PatchType::Quads,
        PatchType::Triangles,
        PatchType::Loop,
        PatchType::Regular,
        PatchType::Gregory,
        PatchType::GregoryBoundary,
        PatchType::GregoryBasis,
        PatchType::GregoryTriangle,
    ];

    /// The type of OpenSubdiv's code `code`, if there is one.
    pub fn from_code(code: i32) -> Option<PatchType> {
        usize::try_from(code)
            .ok()
            .and_then(|i| Self::ALL.get(i).copied())
    }

    /// OpenSubdiv's code.
    pub fn code(self) -> i32 {
        self as i32
    }

    /// OpenSubdiv's name of the type (`"REGULAR"`, `"GREGORY_BASIS"`, ...).
    pub fn name(self) -> &'static str {
        match self {
            PatchType::NonPatch => "NON_PATCH",
            PatchType::Points => "POINTS",
            PatchType::Lines => "LINES",
            PatchType::Quads => "QUADS",
            PatchType::Triangles => "TRIANGLES",
            PatchType::Loop => "LOOP",
            PatchType::Regular => "REGULAR",
            PatchType::Gregory => "GREGORY",
            PatchType::GregoryBoundary => "GREGORY_BOUNDARY",
            PatchType::GregoryBasis => "GREGORY_BASIS",
            PatchType::GregoryTriangle => "GREGORY_TRIANGLE",
        }
    }

    /// Control vertices of a patch of this type
    /// (`PatchDescriptor::GetNumControlVertices`).
    pub fn control_vertices(self) -> usize {
        match self {
            PatchType::NonPatch => 0,
            PatchType::Points => 1,
            PatchType::Lines => 2,
            PatchType::Quads | PatchType::Gregory | PatchType::GregoryBoundary => 4,
            PatchType::Triangles => 3,
            PatchType::Loop => 12,
            PatchType::Regular => 16,
            PatchType::GregoryBasis => 20,
            PatchType::GregoryTriangle => 18,
        }
    }

    /// Whether `PatchTable::EvaluateBasis` has a basis for the type (not
    /// for the legacy Gregory patches, points or lines).
    pub fn is_evaluable(self) -> bool {
        matches!(
            self,
            PatchType::Quads
                | PatchType::Triangles
                | PatchType::Loop
                | PatchType::Regular
                | PatchType::GregoryBasis
                | PatchType::GregoryTriangle
        )
    }
}

/// `PatchTableFactory::Options::EndCapType`: how patches around
/// extraordinary features are approximated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum EndCapType {
    /// `ENDCAP_NONE` ("unspecified": OpenSubdiv then builds B-spline end
    /// caps).
    None = 0,
    /// `ENDCAP_BILINEAR_BASIS`: linear patches.
    BilinearBasis = 1,
    /// `ENDCAP_BSPLINE_BASIS`: B-spline patches approximating the surface.
    BSplineBasis = 2,
    /// `ENDCAP_GREGORY_BASIS`: Gregory patches (OpenSubdiv's default).
    #[default]
    GregoryBasis = 3,
    /// `ENDCAP_LEGACY_GREGORY`: OpenSubdiv 2's Gregory patches
    /// (Catmull-Clark only; not evaluable by `EvaluateBasis`).
    LegacyGregory = 4,
}

crate::names::impl_named!(EndCapType, "end-cap type", {
    None => "none",
    BilinearBasis => "bilinear",
    BSplineBasis => "bspline",
    GregoryBasis => "gregory-basis",
    LegacyGregory => "legacy-gregory",
});

/// `Far::PatchTableFactory::Options`, every field, with OpenSubdiv 3.5's
/// defaults ([`PatchOptions::new`]), and the face-varying channels to build
/// tables for.
///
/// ```
/// use subdiv::patches::{EndCapType, PatchOptions};
/// let o = PatchOptions::new().end_caps(EndCapType::BSplineBasis).single_crease_patch(true);
/// assert_eq!(o.max_isolation_level, 10);
/// assert!(o.legacy_sharp_corner_patches && o.include_base_level_indices);
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PatchOptions {
    /// `endCapType` (Gregory basis).
    pub end_cap_type: EndCapType,
    /// `shareEndCapPatchPoints` (true).
    pub share_end_cap_points: bool,
    /// `generateAllLevels` (false; uniform tables only).
    pub generate_all_levels: bool,
    /// `includeBaseLevelIndices` (true; uniform tables only).
    pub include_base_level_indices: bool,
    /// `includeFVarBaseLevelIndices` (false; uniform tables only).
    pub include_fvar_base_level_indices: bool,
    /// `triangulateQuads` (false; uniform tables only).
    pub triangulate_quads: bool,
    /// `useSingleCreasePatch` (false).
    pub single_crease_patch: bool,
    /// `useInfSharpPatch` (false).
    pub inf_sharp_patch: bool,
    /// `maxIsolationLevel` (10).
    pub max_isolation_level: u32,
    /// `generateVaryingTables` (true).
    pub varying_tables: bool,
    /// `generateVaryingLocalPoints` (true).
    pub varying_local_points: bool,
    /// `generateFVarTables` (false).
    pub fvar_tables: bool,
    /// `patchPrecisionDouble` (false: local-point stencils in `f32`).
    pub patch_precision_double: bool,
    /// `fvarPatchPrecisionDouble` (false).
    pub fvar_patch_precision_double: bool,
    /// `generateFVarLegacyLinearPatches` (true).
    pub fvar_legacy_linear_patches: bool,
    /// `generateLegacySharpCornerPatches` (true).
    pub legacy_sharp_corner_patches: bool,
    /// `fvarChannelIndices`: the face-varying channels with tables when
    /// `fvar_tables` is set; empty means every channel (OpenSubdiv's
    /// `numFVarChannels = -1`, its default).
    pub fvar_channels: Vec<usize>,
}

impl Default for PatchOptions {
    fn default() -> Self {
        PatchOptions {
            end_cap_type: EndCapType::GregoryBasis,
            share_end_cap_points: true,
            generate_all_levels: false,
            include_base_level_indices: true,
            include_fvar_base_level_indices: false,
            triangulate_quads: false,
            single_crease_patch: false,
            inf_sharp_patch: false,
            max_isolation_level: 10,
            varying_tables: true,
            varying_local_points: true,
            fvar_tables: false,
            patch_precision_double: false,
            fvar_patch_precision_double: false,
            fvar_legacy_linear_patches: true,
            legacy_sharp_corner_patches: true,
            fvar_channels: Vec::new(),
        }
    }
}

impl PatchOptions {
    /// OpenSubdiv 3.5's defaults (`PatchTableFactory::Options()`).
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets `endCapType`.
    pub fn end_caps(mut self, end_caps: EndCapType) -> Self {
        self.end_cap_type = end_caps;
        self
    }

    /// Sets `useSingleCreasePatch`.
    pub fn single_crease_patch(mut self, yes: bool) -> Self {
        self.single_crease_patch = yes;
        self
    }

    /// Sets `useInfSharpPatch`.
    pub fn inf_sharp_patch(mut self, yes: bool) -> Self {
        self.inf_sharp_patch = yes;
        self
    }

    /// Sets `maxIsolationLevel`.
    pub fn max_isolation(mut self, level: u32) -> Self {
        self.max_isolation_level = level;
        self
    }

    /// Sets `patchPrecisionDouble` (and `fvarPatchPrecisionDouble`).
    pub fn double_precision(mut self, yes: bool) -> Self {
        self.patch_precision_double = yes;
        self.fvar_patch_precision_double = yes;
        self
    }

    /// The adaptive refinement these options call for
    /// (`GetRefineAdaptiveOptions`): isolation level, single-crease and
    /// infinitely-sharp patches, face-varying channels considered when
    /// non-linear face-varying tables are asked for.
    pub fn refine_adaptive_options(&self) -> crate::AdaptiveOptions {
        crate::AdaptiveOptions::new(self.max_isolation_level)
            .single_crease_patch(self.single_crease_patch)
            .inf_sharp_patch(self.inf_sharp_patch)
            .consider_fvar(self.fvar_tables && !self.fvar_legacy_linear_patches)
    }
}

/// One array of patches of one type.
#[derive(Debug, Clone, PartialEq)]
pub struct PatchArray {
    /// The type of every patch of the array.
    pub patch_type: PatchType,
    /// Control vertices of each patch, patch after patch
    /// ([`PatchType::control_vertices`] each): indices into the vertices of
    /// every level one after the other (base level first), then the local
    /// points.
    pub control_vertices: Vec<u32>,
    /// The [`PatchParam`] of each patch.
    pub params: Vec<PatchParam>,
    /// Each patch's single-crease sharpness (0 where none).
    pub sharpness: Vec<f32>,
    /// The varying patch of each patch (`GetPatchArrayVaryingVertices`):
    /// the vertices of the patch's face, indexed as `control_vertices`
    /// ([`PatchTable::varying_patch_type`]'s count per patch: 4, or 3 under
    /// Loop), in adaptive tables built with `generateVaryingTables`; empty
    /// otherwise.
    pub varying_vertices: Vec<u32>,
}

impl PatchArray {
    /// Number of patches.
    pub fn len(&self) -> usize {
        self.params.len()
    }

    /// Whether the array has no patch.
    pub fn is_empty(&self) -> bool {
        self.params.is_empty()
    }

    /// The control vertices of patch `patch`.
    pub fn patch_vertices(&self, patch: usize) -> &[u32] {
        let n = self.patch_type.control_vertices();
        &self.control_vertices[patch * n..(patch + 1) * n]
    }

    /// The varying vertices of patch `patch` (`GetPatchVaryingVertices`;
    /// empty without varying tables).
    pub fn patch_varying_vertices(&self, patch: usize) -> &[u32] {
        let n = self.varying_vertices.len() / self.len().max(1);
        self.varying_vertices
            .get(patch * n..(patch + 1) * n)
            .unwrap_or(&[])
    }
}

/// A patch table (`Far::PatchTable`): its arrays and the tables beside them.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PatchTable {
    /// The patch arrays, in OpenSubdiv's order.
    pub arrays: Vec<PatchArray>,
    /// Local points (end-cap points) after the refined vertices
    /// (`GetNumLocalPoints`).
    pub local_points: usize,
    /// Varying local points (`GetNumLocalPointsVarying`).
    pub local_points_varying: usize,
    /// The stencil of each local point over the refined vertices (every
    /// level, base first; `GetLocalPointStencilTable`), weights widened to
    /// `f64` from the table's precision; empty without local points.
    pub local_point_stencils: StencilTable,
    /// The varying local points' stencils (`GetLocalPointVaryingStencilTable`;
    /// each the patch corner the point follows).
    pub local_point_varying_stencils: StencilTable,
    /// Largest valence of the base level (`GetMaxValence`).
    pub max_valence: usize,
    /// Ptex faces of the base level (`GetNumPtexFaces`).
    pub ptex_faces: usize,
    /// Legacy Gregory quad offsets (`GetQuadOffsetsTable`; empty otherwise).
    pub quad_offsets: Vec<u32>,
    /// Legacy Gregory vertex valence table (`GetVertexValenceTable`; empty
    /// otherwise).
    pub vertex_valences: Vec<i32>,
    /// Whether the table comes from adaptive refinement
    /// (`IsFeatureAdaptive`).
    pub feature_adaptive: bool,
    /// The type of the varying patches (`GetVaryingPatchDescriptor`):
    /// `TRIANGLES` for Loop, whose ptex faces [`PatchMap`] divides into
    /// triangles, `QUADS` otherwise.
    pub varying_patch_type: PatchType,
    /// The face-varying patch channels (`generateFVarTables`), one per
    /// channel asked for, in that order.
    pub fvar_channels: Vec<FVarPatches>,
}

impl PatchTable {
    /// Number of patches in all arrays (`GetNumPatchesTotal`).
    pub fn patch_count(&self) -> usize {
        self.arrays.iter().map(PatchArray::len).sum()
    }

    /// The index of a patch among all the table's patches, array after
    /// array (OpenSubdiv's `PatchHandle::patchIndex`).
    pub fn patch_index(&self, handle: PatchHandle) -> usize {
        let before: usize = self.arrays[..handle.array.min(self.arrays.len())]
            .iter()
            .map(PatchArray::len)
            .sum();
        before + handle.patch
    }
}

/// One face-varying channel of a patch table (OpenSubdiv's face-varying
/// patch channel): for every patch of the table, in table order, the patch
/// in the channel's own topology — its values (indices of the channel's
/// values of every level, base first, as the vertex patches index
/// vertices) and its [`PatchParam`]. Linear channels (OpenSubdiv's default
/// `generateFVarLegacyLinearPatches`, or a channel interpolated linearly
/// everywhere) have a linear patch over each patch's face: its corner
/// values, the vertex patch's parameter. Other channels have patches over
/// their own topology: regular where the channel is regular around the
/// face, end caps of the table's end-cap type elsewhere (whose points are
/// the channel's local points, after its values), each parameter with the
/// channel's boundary and regular bits.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FVarPatches {
    /// The refiner's channel.
    pub channel: usize,
    /// `GetFVarPatchDescriptorRegular`.
    pub regular_type: PatchType,
    /// `GetFVarPatchDescriptorIrregular`.
    pub irregular_type: PatchType,
    /// Values per patch in [`FVarPatches::values`] (`GetFVarValueStride`).
    pub stride: usize,
    /// The values of every patch, `stride` per patch (`GetFVarValues`).
    pub values: Vec<u32>,
    /// The parameter of every patch (`GetFVarPatchParams`).
    pub params: Vec<PatchParam>,
    /// The stencil of each of the channel's local points (the points of
    /// its end caps, numbered after the channel's values of every level)
    /// over those values (`GetLocalPointFaceVaryingStencilTable`), weights
    /// widened to `f64` from `fvarPatchPrecisionDouble`'s precision; empty
    /// for linear channels.
    pub local_point_stencils: StencilTable,
}

impl FVarPatches {
    /// The values of patch `patch` (an index over the whole table:
    /// [`PatchTable::patch_index`]), as many as its type has
    /// (`GetPatchFVarValues`).
    pub fn patch_values(&self, patch: usize) -> &[u32] {
        let ty = match self.params.get(patch) {
            Some(p) if !p.is_regular() => self.irregular_type,
            _ => self.regular_type,
        };
        let start = patch * self.stride;
        let n = ty.control_vertices().min(self.stride);
        self.values.get(start..start + n).unwrap_or(&[])
    }

    /// The type of patch `patch`'s face-varying patch.
    pub fn patch_type(&self, patch: usize) -> PatchType {
        match self.params.get(patch) {
            Some(p) if !p.is_regular() => self.irregular_type,
            _ => self.regular_type,
        }
    }
}

/// A patch: its array and its index in the array.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct PatchHandle {
    /// The array.
    pub array: usize,
    /// The patch's index in its array.
    pub patch: usize,
}

/// Which derivatives to evaluate besides the position.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Derivatives {
    /// Positions only.
    #[default]
    None,
    /// Positions and first derivatives.
    First,
    /// Positions, first and second derivatives.
    Second,
}

impl Derivatives {
    /// How many of the six columns (values, ∂u, ∂v, ∂uu, ∂uv, ∂vv) these
    /// derivatives fill: 1, 3 or 6.
    pub(crate) fn columns(self) -> usize {
        match self {
            Derivatives::None => 1,
            Derivatives::First => 3,
            Derivatives::Second => 6,
        }
    }
}

/// Values with their partial derivatives with respect to a ptex face's u
/// and v, each list empty when not asked for: the weights of a patch's
/// control vertices at one location (`EvaluateBasis`), or the limit
/// surface's values at a list of locations ([`SurfaceSamples`]); in
/// `f64` unless `R` names another precision ([`evaluate_basis_in`]).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Partials<R = f64> {
    /// The values themselves.
    pub point: Vec<R>,
    /// ∂/∂u.
    pub du: Vec<R>,
    /// ∂/∂v.
    pub dv: Vec<R>,
    /// ∂²/∂u².
    pub duu: Vec<R>,
    /// ∂²/∂u∂v.
    pub duv: Vec<R>,
    /// ∂²/∂v².
    pub dvv: Vec<R>,
}

impl<R> Partials<R> {
    /// The six columns in their order: values, ∂/∂u, ∂/∂v, ∂²/∂u²,
    /// ∂²/∂u∂v, ∂²/∂v² (those not computed empty).
    pub(crate) fn from_columns(columns: [Vec<R>; 6]) -> Partials<R> {
        let [point, du, dv, duu, duv, dvv] = columns;
        Partials {
            point,
            du,
            dv,
            duu,
            duv,
            dvv,
        }
    }

    /// The six columns in their order, as [`Partials::from_columns`] takes
    /// them (the bridge's evaluations reuse them).
    #[cfg(feature = "osd")]
    pub(crate) fn into_columns(self) -> [Vec<R>; 6] {
        [self.point, self.du, self.dv, self.duu, self.duv, self.dvv]
    }

    /// Makes the columns ready for `len` values of each of the first
    /// `kinds` kinds, every one of which the caller then overwrites: a
    /// column too small for them becomes fresh zeros from the allocator
    /// (faulted in as written), one large enough keeps its memory and
    /// values (only the values past its old length are set), the columns
    /// not asked for are emptied (their memory kept).
    pub(crate) fn reuse_for(&mut self, kinds: usize, len: usize) -> crate::error::Result<()>
    where
        R: crate::real::Real,
    {
        for (k, column) in self.columns_mut().into_iter().enumerate() {
            if k >= kinds {
                column.clear();
            } else if column.capacity() < len {
                *column = crate::alloc::try_zeroed(len)?;
            } else {
                column.resize(len, R::ZERO);
            }
        }
        Ok(())
    }

    /// The six columns in their order, as in [`Partials::from_columns`],
    /// to write into.
    pub(crate) fn columns_mut(&mut self) -> [&mut Vec<R>; 6] {
        [
            &mut self.point,
            &mut self.du,
            &mut self.dv,
            &mut self.duu,
            &mut self.duv,
            &mut self.dvv,
        ]
    }
}

impl Partials {
    /// Copies the kinds of values there are `columns` for (values, ∂u,
    /// ∂v, ...) into them; refused when a length differs.
    pub(crate) fn copy_into(&self, columns: &mut [&mut [f64]]) -> crate::error::Result<()> {
        for (column, from) in columns.iter_mut().zip(self.kinds()) {
            if column.len() != from.len() {
                return Err(crate::error::Error::BufferLength {
                    buffer: crate::error::Buffer::Output,
                    expected: from.len(),
                    got: column.len(),
                });
            }
            column.copy_from_slice(from);
        }
        Ok(())
    }

    /// The six columns in their order, as in [`Partials::from_columns`].
    pub(crate) fn kinds(&self) -> [&[f64]; 6] {
        [
            &self.point,
            &self.du,
            &self.dv,
            &self.duu,
            &self.duv,
            &self.dvv,
        ]
    }
}

/// Values of the limit surface at a list of locations, `width` components
/// each, location after location, with the derivatives asked for; in
/// `f64` unless `R` names another precision (points given in `f32`,
/// [`evaluate_data_as`]).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SurfaceSamples<R = f64> {
    /// Components per value.
    pub width: usize,
    /// The values and derivatives.
    pub values: Partials<R>,
}
