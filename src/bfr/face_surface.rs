//! One base face's limit surface as an object, the way OpenSubdiv 3.5's
//! `Bfr::RefinerSurfaceFactory` builds a `Bfr::Surface`
//! ([`SurfaceFactory`], [`Surface`]): whether it is valid, regular or
//! linear, its control points (the mesh vertices it depends on, in Bfr's
//! order), its number of patch points, and its limit stencils — the weights
//! of those control points at any (u, v) of the face's parameterization,
//! with derivatives.
//!
//! How a surface is built, as Bfr builds it:
//! - under the bilinear scheme, the face itself (linear: its corners; an
//!   n-gon is split into quads at its centre and edge midpoints);
//! - a face whose neighbourhood is regular (the refiner's tags say so, or
//!   its corners' valences and sharpness do) is one B-spline patch (16
//!   points) or box-spline patch (12 points, Loop);
//! - any other face gets a control hull (see `hull.rs`): the vertices of
//!   the faces around its corners, with the sharpness that matters, refined
//!   adaptively about the face alone (`approx_level_sharp` around sharp
//!   features, `approx_level_smooth` around smooth ones), and evaluated
//!   through that refinement's patches — Gregory patches at the last level.

use super::corner::{Corner, CornerTag, Subset};
use super::hull::hull;
use super::parameterization::Parameterization;
use super::regular::{shortcut_points, subset_mask, subset_points};
use super::surfaces::SurfaceOptions;
use crate::alloc;
use crate::error::{Element, Error, Result};
use crate::mesh::Mesh;
use crate::options::{
    AdaptiveOptions, BoundaryInterpolation, CreasingMethod, FVarLinearInterpolation, Options,
    Scheme, TriangleSubdivision,
};
use crate::patches::basis::{BasisBuffer, evaluate_basis_into};
use crate::patches::limit_stencils::stencils_at;
use crate::patches::{
    Derivatives, EndCapType, LimitStencilOptions, Partials, PatchData, PatchMap, PatchOptions,
    PatchParam, PatchTable, PatchType, SurfaceSamples, evaluate_basis, evaluate_data,
};
use crate::refiner::adaptive::{Features, Tag, base_features};
use crate::refiner::{AdaptiveRefiner, Refiner};
use crate::rules::Rule;
use crate::stencil::StencilTable;
use crate::topology::Level;
use crate::topology::fvar::ChannelLevel;
use rustc_hash::FxHashMap;
use std::sync::{Arc, Mutex};

/// The deepest approximation level (OpenSubdiv's adaptive limit).
const MAX_APPROX_LEVEL: u32 = 10;

/// Builds the surfaces of a mesh's base faces (`Bfr::RefinerSurfaceFactory`,
/// caching off).
#[derive(Debug)]
pub struct SurfaceFactory {
    refiner: Refiner,
    features: Vec<Features>,
    surface: SurfaceOptions,
    /// The refined hulls built so far, by topology (Bfr's topology cache:
    /// faces whose hulls match share one refinement).
    cache: Mutex<FxHashMap<HullKey, Arc<Irregular>>>,
}

/// What makes two control hulls refine alike: their faces, sharpness and
/// options.
#[derive(Debug, PartialEq, Eq, Hash)]
struct HullKey {
    offsets: Vec<u32>,
    faces: Vec<u32>,
    creases: Vec<([u32; 2], u32)>,
    corners: Vec<(u32, u32)>,
    options: Options,
}

impl HullKey {
    fn new(mesh: &Mesh, options: &Options) -> HullKey {
        HullKey {
            offsets: mesh.face_offsets.clone(),
            faces: mesh.face_vertices.clone(),
            creases: mesh
                .creases
                .iter()
                .map(|c| (c.vertices, c.sharpness.to_bits()))
                .collect(),
            corners: mesh
                .corners
                .iter()
                .map(|c| (c.vertex, c.sharpness.to_bits()))
                .collect(),
            options: *options,
        }
    }
}

/// A face's neighbourhood as Bfr first sorts it.
enum Neighbourhood {
    /// No limit surface (a hole, a degenerate face, a smooth boundary under
    /// boundary interpolation "none", a non-triangle next to a Loop face).
    Invalid(Parameterization),
    /// The bilinear scheme.
    Linear(Parameterization),
    /// Regular by the refiner's tags.
    Shortcut(Parameterization),
    /// Anything else: its corners and their vertex subsets.
    Corners {
        param: Parameterization,
        corners: Vec<Corner>,
        subsets: Vec<Subset>,
    },
}

/// Whether channel `chan` has the vertex topology around base face `face`
/// (`FVarLevel::doesFaceFVarTopologyMatch`: none of the face's values is
/// on a seam, boundary or other mismatch).
fn fvar_topology_matches(base: &Level, chan: &ChannelLevel, face: usize) -> bool {
    let values = chan.face_values_of(base, face);
    base.face_verts(face)
        .iter()
        .zip(values)
        .all(|(&v, &value)| {
            let v = v as usize;
            let tags = chan.vertex_value_tags(v);
            (0..chan.vertex_value_count(v))
                .find(|&s| chan.vertex_value(v, s) == value)
                .is_none_or(|s| !tags[s].is_mismatch())
        })
}

/// How a surface is represented.
#[derive(Debug)]
enum Form {
    /// No limit surface.
    Invalid,
    /// The face itself: bilinear (or linear, a triangle under Loop) when
    /// `regular`, else split into quads at its centre.
    Linear { regular: bool },
    /// One regular patch with this boundary mask.
    Regular { patch: PatchType, mask: u16 },
    /// The patches of an adaptive refinement of the face's control hull
    /// (shared by the faces whose hulls have the same topology).
    Irregular(Arc<Irregular>),
}

#[derive(Debug)]
struct Irregular {
    refiner: AdaptiveRefiner,
    table: PatchTable,
    map: PatchMap,
    /// The refined vertices' stencils over the hull's vertices.
    refined: StencilTable,
    /// The hull's vertices.
    base: usize,
    /// For each of the table's local points, its place among Bfr's patch
    /// points (Bfr numbers the end caps' points patch by patch, level by
    /// level).
    local_order: Vec<usize>,
}

/// One base face's limit surface (`Bfr::Surface<double>`).
#[derive(Debug)]
pub struct Surface {
    face: usize,
    param: Parameterization,
    control_points: Vec<u32>,
    patch_points: usize,
    form: Form,
}

impl SurfaceFactory {
    /// The factory of `mesh`'s surfaces under `options`, with Bfr's
    /// approximation levels from `surface` (levels beyond 10 are refused,
    /// as OpenSubdiv's adaptive refinement goes no deeper).
    pub fn new(mesh: &Mesh, options: &Options, surface: &SurfaceOptions) -> Result<Self> {
        for level in [surface.approx_level_smooth, surface.approx_level_sharp] {
            if level > MAX_APPROX_LEVEL {
                return Err(Error::Level {
                    level,
                    reason: crate::error::LevelRefusal::TooDeep {
                        max: MAX_APPROX_LEVEL,
                    },
                });
            }
        }
        let refiner = Refiner::new(mesh, options)?;
        let features = base_features(&refiner.levels[0], options.scheme);
        Ok(SurfaceFactory {
            refiner,
            features,
            surface: *surface,
            cache: Mutex::new(FxHashMap::default()),
        })
    }

    /// The number of base faces.
    pub fn face_count(&self) -> usize {
        self.refiner.levels[0].face_count()
    }

    /// Whether base face `face` has a limit surface
    /// (`FaceHasLimitSurface`: not a hole nor degenerate, no smooth
    /// boundary under boundary interpolation "none", no non-triangle next
    /// to a Loop face); false for faces that do not exist.
    pub fn has_limit_surface(&self, face: usize) -> bool {
        matches!(
            self.neighbourhood(face),
            Ok(Neighbourhood::Linear(_)
                | Neighbourhood::Shortcut(_)
                | Neighbourhood::Corners { .. })
        )
    }

    fn scheme(&self) -> Scheme {
        self.refiner.options.scheme
    }

    fn reg_size(&self) -> usize {
        if self.scheme() == Scheme::Loop { 3 } else { 4 }
    }

    /// What Bfr needs to know of a face's neighbourhood before building any
    /// of its surfaces (`SurfaceFactory::populateAllSurfaces` up to the
    /// surfaces themselves).
    fn neighbourhood(&self, face: usize) -> Result<Neighbourhood> {
        let base = &self.refiner.levels[0];
        if face >= base.face_count() {
            return Err(Error::NoSuchElement {
                element: Element::Face,
                index: face,
                level: 0,
                count: base.face_count(),
            });
        }
        let size = base.face_verts(face).len();
        let param = Parameterization::new(self.scheme(), size)?;
        if size < 3 || base.is_hole(face) {
            return Ok(Neighbourhood::Invalid(param));
        }
        if self.scheme() == Scheme::Bilinear {
            return Ok(Neighbourhood::Linear(param));
        }
        if self.shortcut_regular(base, face) {
            return Ok(Neighbourhood::Shortcut(param));
        }
        match self.corners(face) {
            Some((corners, subsets)) => Ok(Neighbourhood::Corners {
                param,
                corners,
                subsets,
            }),
            None => Ok(Neighbourhood::Invalid(param)),
        }
    }

    /// The corners of a face and their vertex subsets, sharpened by the
    /// boundary interpolation rule; `None` if the face has no limit surface
    /// (`faceHasLimitNeighborhood`).
    fn corners(&self, face: usize) -> Option<(Vec<Corner>, Vec<Subset>)> {
        let base = &self.refiner.levels[0];
        let size = base.face_verts(face).len();
        let corners: Vec<Corner> = (0..size)
            .map(|k| Corner::new(base, face, k, self.reg_size()))
            .collect();
        let options = self.refiner.options;
        let topology = corners
            .iter()
            .fold(CornerTag::default(), |t, c| t.or(c.tag));
        let reject_smooth_boundaries = options.boundary == BoundaryInterpolation::None;
        let reject_irregular = self.reg_size() == 3;
        if (reject_smooth_boundaries && topology.boundary_non_sharp)
            || (reject_irregular && topology.irregular_sizes)
        {
            return None;
        }
        let subsets = corners
            .iter()
            .map(|c| {
                let mut s = c.subset();
                if s.is_boundary()
                    && !s.is_sharp()
                    && options.boundary == BoundaryInterpolation::EdgeAndCorner
                    && c.face_count() == 1
                {
                    s.sharpen();
                }
                s
            })
            .collect();
        Some((corners, subsets))
    }

    /// The vertex surface of base face `face` (`InitVertexSurface`): holes
    /// and faces without a limit surface give an invalid surface.
    pub fn vertex_surface(&self, face: usize) -> Result<Surface> {
        let base = &self.refiner.levels[0];
        match self.neighbourhood(face)? {
            Neighbourhood::Invalid(param) => Ok(Surface::invalid(face, param)),
            Neighbourhood::Linear(param) => Ok(self.linear(face, param, base.face_verts(face))),
            Neighbourhood::Shortcut(param) => {
                let (control_points, mask) = shortcut_points(base, face, |f| base.face_verts(f));
                Ok(self.regular(face, param, control_points, mask))
            }
            Neighbourhood::Corners {
                param,
                corners,
                subsets,
            } => self.nonlinear(face, param, &corners, &subsets),
        }
    }

    /// The surface of face-varying channel `channel` over base face `face`
    /// (`InitFaceVaryingSurface`): linear where the channel is (the
    /// bilinear scheme, `FVarLinearInterpolation::All`), else built as the
    /// vertex surface is, over the channel's topology — its seams bound the
    /// corners' subsets, sharpened by the channel's linear-interpolation
    /// option. Control points are the channel's values.
    pub fn fvar_surface(&self, face: usize, channel: usize) -> Result<Surface> {
        let base = &self.refiner.levels[0];
        let count = self.refiner.fvar.len();
        let chan = self
            .refiner
            .fvar
            .get(channel)
            .and_then(|levels| levels.first())
            .ok_or(Error::NoSuchChannel { channel, count })?;
        let values = |f: usize| chan.face_values_of(base, f);
        let neighbourhood = self.neighbourhood(face)?;
        let linear = self.scheme() == Scheme::Bilinear
            || self.refiner.options.fvar == FVarLinearInterpolation::All;
        let (param, corners, subsets) = match neighbourhood {
            Neighbourhood::Invalid(param) => return Ok(Surface::invalid(face, param)),
            Neighbourhood::Linear(param) => return Ok(self.linear(face, param, values(face))),
            Neighbourhood::Shortcut(param) | Neighbourhood::Corners { param, .. } if linear => {
                return Ok(self.linear(face, param, values(face)));
            }
            Neighbourhood::Shortcut(param) => {
                if fvar_topology_matches(base, chan, face) {
                    let (control_points, mask) = shortcut_points(base, face, values);
                    return Ok(self.regular(face, param, control_points, mask));
                }
                match self.corners(face) {
                    Some((corners, subsets)) => (param, corners, subsets),
                    None => return Ok(Surface::invalid(face, param)),
                }
            }
            Neighbourhood::Corners {
                param,
                corners,
                subsets,
            } => (param, corners, subsets),
        };
        let fvar = self.refiner.options.fvar;
        let fcorners: Vec<Corner> = corners.iter().map(|c| c.with_values(values)).collect();
        let fsubsets: Vec<Subset> = fcorners
            .iter()
            .zip(&subsets)
            .map(|(c, vertex)| {
                let mut s = c.fvar_subset(vertex);
                if s.is_boundary() && !s.is_sharp() {
                    c.sharpen_fvar(&mut s, vertex, fvar);
                }
                s
            })
            .collect();
        self.nonlinear(face, param, &fcorners, &fsubsets)
    }

    /// A regular patch's surface.
    fn regular(
        &self,
        face: usize,
        param: Parameterization,
        control_points: Vec<u32>,
        mask: u16,
    ) -> Surface {
        let patch = if self.reg_size() == 4 {
            PatchType::Regular
        } else {
            PatchType::Loop
        };
        Surface {
            face,
            param,
            patch_points: control_points.len(),
            control_points,
            form: Form::Regular { patch, mask },
        }
    }

    /// The surface of a face from its corners (vertex indices or a
    /// channel's values) and their subsets: one regular patch where they
    /// allow it, else the patches of its control hull.
    fn nonlinear(
        &self,
        face: usize,
        param: Parameterization,
        corners: &[Corner],
        subsets: &[Subset],
    ) -> Result<Surface> {
        let tag = subsets
            .iter()
            .fold(CornerTag::default(), |t, s| t.or(s.tag));
        if is_regular(subsets, tag, self.reg_size()) {
            let control_points = subset_points(corners, subsets);
            return Ok(self.regular(face, param, control_points, subset_mask(subsets)));
        }
        let options = self.refiner.options;
        let hull = hull(corners, subsets, tag);
        let local = Options {
            boundary: BoundaryInterpolation::EdgeOnly,
            fvar: FVarLinearInterpolation::All,
            creasing: if tag.semi_sharp_edges || tag.semi_sharp {
                options.creasing
            } else {
                CreasingMethod::Uniform
            },
            triangles: if options.scheme == Scheme::Catmark && tag.irregular_sizes {
                options.triangles
            } else {
                TriangleSubdivision::Catmark
            },
            ..options
        };
        let key = HullKey::new(&hull.mesh, &local);
        let cached = self
            .cache
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
            .get(&key)
            .cloned();
        let irregular = match cached {
            Some(irregular) => irregular,
            None => {
                let built = Arc::new(self.irregular(&hull.mesh, &local)?);
                self.cache
                    .lock()
                    .unwrap_or_else(|poisoned| poisoned.into_inner())
                    .entry(key)
                    .or_insert(built)
                    .clone()
            }
        };
        let (base_count, refined) = {
            let r = &irregular.refiner;
            let mut refined = 0;
            for l in 1..=r.max_level() {
                refined += r.level_counts(l)?.vertices;
            }
            (r.level_counts(0)?.vertices, refined)
        };
        let end_caps = irregular.local_order.len();
        Ok(Surface {
            face,
            param,
            control_points: hull.control_points,
            patch_points: base_count + refined + end_caps,
            form: Form::Irregular(irregular),
        })
    }

    /// The varying surface of base face `face` (`InitVaryingSurface`):
    /// linear over the face's vertices under every scheme.
    pub fn varying_surface(&self, face: usize) -> Result<Surface> {
        let base = &self.refiner.levels[0];
        Ok(match self.neighbourhood(face)? {
            Neighbourhood::Invalid(param) => Surface::invalid(face, param),
            Neighbourhood::Linear(param)
            | Neighbourhood::Shortcut(param)
            | Neighbourhood::Corners { param, .. } => {
                self.linear(face, param, base.face_verts(face))
            }
        })
    }

    /// The linear surface of a face (`assignLinearSurface`).
    fn linear(&self, face: usize, param: Parameterization, verts: &[u32]) -> Surface {
        let regular = verts.len() == self.reg_size();
        Surface {
            face,
            param,
            control_points: verts.to_vec(),
            patch_points: if regular {
                verts.len()
            } else {
                2 * verts.len() + 1
            },
            form: Form::Linear { regular },
        }
    }

    /// The refiner's shortcut: a face whose corners' tags make its patch
    /// regular (`getFaceNeighborhoodVertexIndicesIfRegular`).
    fn shortcut_regular(&self, base: &Level, face: usize) -> bool {
        let verts = base.face_verts(face);
        if verts.len() != self.reg_size() {
            return false;
        }
        let tags: Vec<Tag> = verts
            .iter()
            .map(|&v| Tag::of(base, &self.features, v as usize))
            .collect();
        let f = tags.iter().fold(Tag::default(), |a, &b| a.or(b));
        if f.features.xordinary
            || f.non_manifold
            || f.features.incid_irreg_face
            || f.semi_sharp
            || f.semi_sharp_edges
            || f.features.inf_irregular
        {
            return false;
        }
        if !f.boundary {
            return !(f.inf_sharp || f.inf_sharp_edges);
        }
        verts.iter().zip(&tags).all(|(&v, t)| {
            let rule = base.vertex_tag(v as usize).rule();
            if !t.boundary {
                rule == Rule::Smooth
            } else if base.vertex_faces_of(v as usize).len() == 1 {
                rule == Rule::Corner
            } else {
                rule == Rule::Crease
            }
        })
    }

    /// The adaptive refinement of a control hull about its first face and
    /// its patches (`Bfr::PatchTreeBuilder`).
    fn irregular(&self, hull: &Mesh, options: &Options) -> Result<Irregular> {
        let refiner = Refiner::new(hull, options)?;
        let mut primary = self.surface.approx_level_sharp;
        let mut secondary = self.surface.approx_level_smooth.min(primary);
        if secondary == 0 && root_needs_refinement(&refiner) {
            primary = primary.max(1);
            secondary = 1;
        }
        let adaptive = AdaptiveOptions::new(primary)
            .secondary(secondary)
            .inf_sharp_patch(true);
        let refiner = refiner.refine_adaptive(adaptive, &[0])?;
        let mut patch_options = PatchOptions::new()
            .end_caps(EndCapType::GregoryBasis)
            .inf_sharp_patch(true)
            .max_isolation(primary)
            .double_precision(true);
        patch_options.legacy_sharp_corner_patches = false;
        patch_options.share_end_cap_points = false;
        let table = refiner.patch_table(&patch_options, &[0])?;
        let map = PatchMap::new(&table);
        let local_order = bfr_local_order(&refiner, &table)?;
        let refined = refiner.refined_vertex_stencils()?;
        let base = refiner.level_counts(0)?.vertices;
        Ok(Irregular {
            refiner,
            table,
            map,
            refined,
            base,
            local_order,
        })
    }
}

/// Where each local point of `table` (an end-capped table of the patches
/// under one base face, unshared points) goes among Bfr's patch points:
/// after the refinement's vertices, the end caps' points patch by patch in
/// Bfr's order — level by level, faces in index order, which is the
/// table's depth-first order sorted stably by depth.
fn bfr_local_order(refiner: &AdaptiveRefiner, table: &PatchTable) -> Result<Vec<usize>> {
    let mut vertices = 0;
    for l in 0..=refiner.max_level() {
        vertices += refiner.level_counts(l)?.vertices;
    }
    let mut caps: Vec<(u32, &[u32])> = Vec::new();
    for array in &table.arrays {
        if !matches!(
            array.patch_type,
            PatchType::GregoryBasis | PatchType::GregoryTriangle
        ) {
            continue;
        }
        let n = array.patch_type.control_vertices();
        for (p, param) in array.params.iter().enumerate() {
            caps.push((param.depth(), &array.control_vertices[p * n..(p + 1) * n]));
        }
    }
    caps.sort_by_key(|&(depth, _)| depth);
    // Unshared points: each belongs to exactly one patch, so every slot
    // is written once (identity where none would be, defensively).
    let mut order: Vec<usize> = (vertices..vertices + table.local_points).collect();
    let mut next = vertices;
    for (_, cvs) in caps {
        for &cv in cvs {
            if let Some(slot) = (cv as usize)
                .checked_sub(vertices)
                .and_then(|i| order.get_mut(i))
            {
                *slot = next;
            }
            next += 1;
        }
    }
    debug_assert_eq!(next, vertices + table.local_points);
    Ok(order)
}

/// Whether the corners' subsets make one regular patch
/// (`FaceSurface::isRegular`).
fn is_regular(subsets: &[Subset], tag: CornerTag, reg_size: usize) -> bool {
    if tag.sharp_edges() || tag.semi_sharp || tag.irregular_sizes {
        return false;
    }
    let interior = if reg_size == 4 { 4 } else { 6 };
    if !tag.boundary {
        return !tag.inf_sharp && subsets.iter().all(|s| s.total == interior);
    }
    subsets.iter().all(|s| {
        if s.is_sharp() {
            s.total == 1
        } else if s.is_boundary() {
            s.total == interior / 2
        } else {
            s.total == interior
        }
    })
}

/// Whether the hull's face cannot be one patch of its base level
/// (`PatchTreeBuilder::rootFaceNeedsRefinement`).
fn root_needs_refinement(refiner: &Refiner) -> bool {
    let level = &refiner.levels[0];
    let features = base_features(level, refiner.options.scheme);
    let verts = level.face_verts(0);
    let tags: Vec<Tag> = verts
        .iter()
        .map(|&v| Tag::of(level, &features, v as usize))
        .collect();
    let f = tags.iter().fold(Tag::default(), |a, &b| a.or(b));
    if f.features.incid_irreg_face {
        return true;
    }
    let dart = crate::refiner::adaptive::DART;
    if f.rule & dart != 0
        && f.features.inf_irregular
        && tags.iter().any(|t| t.rule & dart != 0 && t.inf_sharp_edges)
    {
        return true;
    }
    if f.features.xordinary {
        let n = verts.len();
        return verts.iter().zip(&tags).any(|(&v, t)| {
            let valence = level.vertex_faces_of(v as usize).len();
            t.features.xordinary
                && !t.boundary
                && !t.inf_sharp_edges
                && (valence == 2 || (valence == 3 && n == 3))
        });
    }
    false
}

/// The four weights of a sub-face of a split n-gon turned into the weights
/// of the n-gon's vertices: origin, next, any other, previous
/// (`transformLinearQuadWeightsToStencil`).
fn split_weights(w: [f64; 4], n: usize) -> [f64; 4] {
    let (origin, next, center, prev) = (w[0], w[1] * 0.5, w[2] / n as f64, w[3] * 0.5);
    [
        center + next + prev + origin,
        center + next,
        center,
        center + prev,
    ]
}

impl Surface {
    /// A surface without a limit.
    fn invalid(face: usize, param: Parameterization) -> Surface {
        Surface {
            face,
            param,
            control_points: Vec::new(),
            patch_points: 0,
            form: Form::Invalid,
        }
    }

    /// The base face.
    pub fn face(&self) -> usize {
        self.face
    }

    /// `IsValid`: the face has a limit surface.
    pub fn is_valid(&self) -> bool {
        !matches!(self.form, Form::Invalid)
    }

    /// `IsRegular`: one regular patch (or a linear face of the scheme's
    /// regular size).
    pub fn is_regular(&self) -> bool {
        match self.form {
            Form::Regular { .. } => true,
            Form::Linear { regular } => regular,
            _ => false,
        }
    }

    /// `IsLinear`: the bilinear scheme's surface.
    pub fn is_linear(&self) -> bool {
        matches!(self.form, Form::Linear { .. })
    }

    /// `GetControlPointIndices`: the mesh vertices the surface depends on,
    /// in Bfr's order (empty for an invalid surface).
    pub fn control_points(&self) -> &[u32] {
        &self.control_points
    }

    /// `GetNumPatchPoints`: the control points and the points Bfr computes
    /// from them to evaluate the surface (0 for an invalid surface).
    pub fn patch_point_count(&self) -> usize {
        self.patch_points
    }

    /// `GetParameterization`.
    pub fn parameterization(&self) -> Parameterization {
        self.param
    }

    /// `EvaluateStencil`: for each of `coords`, the weights of the control
    /// points (in [`Surface::control_points`]' order) giving the surface's
    /// value and the derivatives asked for there.
    ///
    /// Refused ([`Error::OffFace`], naming the face): coordinates off the
    /// face's domain, and any coordinate of a surface without a limit.
    pub fn evaluate_stencil(
        &self,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<Vec<Partials>> {
        let mut out = Vec::new();
        alloc::reserve(&mut out, coords.len())?;
        if let Some(&uv) = coords
            .iter()
            .find(|&&uv| !self.is_valid() || !self.param.contains(uv, 1e-9))
        {
            return Err(self.off_face(uv));
        }
        match &self.form {
            Form::Invalid => {}
            Form::Linear { regular: true } => {
                let patch = if self.control_points.len() == 4 {
                    PatchType::Quads
                } else {
                    PatchType::Triangles
                };
                for &uv in coords {
                    let [u, v] = self.clamped(uv);
                    out.push(evaluate_basis(
                        patch,
                        PatchParam::default(),
                        u,
                        v,
                        derivatives,
                    )?);
                }
            }
            Form::Linear { regular: false } => {
                for &uv in coords {
                    out.push(self.split_stencil(uv, derivatives)?);
                }
            }
            Form::Regular { patch, mask } => {
                let param = PatchParam::new(0, 0, 0, 0, false, *mask, 0, true);
                for &uv in coords {
                    let [u, v] = self.clamped(uv);
                    out.push(evaluate_basis(*patch, param, u, v, derivatives)?);
                }
            }
            Form::Irregular(irregular) => {
                let locations = self.locations(coords)?;
                let options = LimitStencilOptions::new()
                    .first_derivatives(derivatives != Derivatives::None)
                    .second_derivatives(derivatives == Derivatives::Second);
                let stencils = stencils_at(
                    &irregular.table,
                    irregular.base,
                    &irregular.refined,
                    &locations,
                    &options,
                )?;
                let n = self.control_points.len();
                for s in 0..stencils.len() {
                    let range = stencils.offsets[s] as usize
                        ..stencils.offsets[s] as usize + stencils.sizes[s] as usize;
                    let w = &stencils.weights;
                    let dense = |column: &[f64]| -> Result<Vec<f64>> {
                        if column.is_empty() {
                            return Ok(Vec::new());
                        }
                        let mut d = alloc::try_vec(0.0, n)?;
                        for k in range.clone() {
                            d[stencils.indices[k] as usize] += column[k];
                        }
                        Ok(d)
                    };
                    out.push(Partials {
                        point: dense(&w.point)?,
                        du: dense(&w.du)?,
                        dv: dense(&w.dv)?,
                        duu: dense(&w.duu)?,
                        duv: dense(&w.duv)?,
                        dvv: dense(&w.dvv)?,
                    });
                }
            }
        }
        Ok(out)
    }

    fn clamped(&self, [u, v]: [f64; 2]) -> [f64; 2] {
        let (u, v) = (u.clamp(0.0, 1.0), v.clamp(0.0, 1.0));
        if self.param.kind() == super::ParameterizationType::Triangle && u + v > 1.0 {
            let excess = (u + v - 1.0) / 2.0;
            [u - excess, v - excess]
        } else {
            [u, v]
        }
    }

    /// The stencil of a split n-gon of the bilinear scheme
    /// (`evalMultiLinearStencils`).
    fn split_stencil(&self, uv: [f64; 2], derivatives: Derivatives) -> Result<Partials> {
        let (sub, [s, t]) = self.param.coord_to_subface(uv, true)?;
        let n = self.control_points.len();
        let w = evaluate_basis(
            PatchType::Quads,
            PatchParam::default(),
            s.clamp(0.0, 1.0),
            t.clamp(0.0, 1.0),
            derivatives,
        )?;
        let spread = |column: &[f64], scale: f64| -> Vec<f64> {
            if column.is_empty() {
                return Vec::new();
            }
            let q = split_weights(
                [column[0], column[1], column[2], column[3]].map(|x| x * scale),
                n,
            );
            (0..n)
                .map(|i| {
                    if i == sub {
                        q[0]
                    } else if i == (sub + 1) % n {
                        q[1]
                    } else if i == (sub + n - 1) % n {
                        q[3]
                    } else {
                        q[2]
                    }
                })
                .collect()
        };
        let zeros = |column: &[f64]| vec![0.0; if column.is_empty() { 0 } else { n }];
        Ok(Partials {
            point: spread(&w.point, 1.0),
            du: spread(&w.du, 2.0),
            dv: spread(&w.dv, 2.0),
            duu: zeros(&w.duu),
            duv: spread(&w.duv, 4.0),
            dvv: zeros(&w.dvv),
        })
    }

    /// `PreparePatchPoints` (with `GatherControlPoints`): the surface's
    /// patch points from the mesh's points (`width` values per mesh
    /// vertex), in Bfr's order — the control points, then for a split
    /// n-gon its centre and edge midpoints, for an irregular surface every
    /// vertex of its hull's refinement level by level and the points of its
    /// end caps; [`Surface::patch_point_count`] of them.
    pub fn patch_points(&self, points: &[f64], width: usize) -> Result<Vec<f64>> {
        self.check_points(points, width)?;
        let mut out = Vec::new();
        alloc::reserve(&mut out, self.patch_points.saturating_mul(width))?;
        for &cv in &self.control_points {
            out.extend_from_slice(&points[cv as usize * width..(cv as usize + 1) * width]);
        }
        match &self.form {
            Form::Linear { regular: false } => {
                let n = self.control_points.len();
                let mut centre = vec![0.0; width];
                for i in 0..n {
                    for (c, &x) in centre.iter_mut().zip(&out[i * width..(i + 1) * width]) {
                        *c += x;
                    }
                }
                centre.iter_mut().for_each(|c| *c /= n as f64);
                out.extend_from_slice(&centre);
                for i in 0..n {
                    let j = (i + 1) % n;
                    for k in 0..width {
                        out.push(0.5 * (out[i * width + k] + out[j * width + k]));
                    }
                }
            }
            Form::Irregular(irregular) => {
                let native = irregular
                    .refiner
                    .patch_points(&irregular.table, width, &out)?;
                let vertices = native.len() / width - irregular.local_order.len();
                out = native[..vertices * width].to_vec();
                out.resize(native.len(), 0.0);
                for (i, &to) in irregular.local_order.iter().enumerate() {
                    let from = (vertices + i) * width;
                    out[to * width..(to + 1) * width].copy_from_slice(&native[from..from + width]);
                }
            }
            _ => {}
        }
        Ok(out)
    }

    /// `Evaluate` over patch points from [`Surface::patch_points`] (`width`
    /// values each): the surface's values and the derivatives asked for at
    /// `coords`.
    pub fn evaluate_patch_points(
        &self,
        patch_points: &[f64],
        width: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        if width == 0 {
            return Err(Error::ZeroWidth);
        }
        let expected = self.patch_points.saturating_mul(width);
        if patch_points.len() != expected {
            return Err(Error::BufferLength {
                buffer: crate::error::Buffer::Base,
                expected,
                got: patch_points.len(),
            });
        }
        if let Form::Irregular(irregular) = &self.form {
            let vertices = self.patch_points - irregular.local_order.len();
            let mut native = patch_points[..vertices * width].to_vec();
            native.resize(patch_points.len(), 0.0);
            for (i, &from) in irregular.local_order.iter().enumerate() {
                let to = (vertices + i) * width;
                native[to..to + width]
                    .copy_from_slice(&patch_points[from * width..(from + 1) * width]);
            }
            let locations = self.locations(coords)?;
            return evaluate_data(
                &irregular.map,
                &irregular.table,
                PatchData::Vertex,
                &native,
                width,
                &locations,
                derivatives,
            );
        }
        // The other forms' stencils weigh the control points, which lead
        // the patch points.
        let identity: Vec<u32> = (0..self.control_points.len() as u32).collect();
        self.apply_stencils(&identity, patch_points, width, coords, derivatives)
    }

    fn check_points(&self, points: &[f64], width: usize) -> Result<()> {
        if width == 0 {
            return Err(Error::ZeroWidth);
        }
        if let Some(&v) = self
            .control_points
            .iter()
            .find(|&&v| (v as usize + 1).saturating_mul(width) > points.len())
        {
            return Err(Error::BufferLength {
                buffer: crate::error::Buffer::Base,
                expected: (v as usize + 1).saturating_mul(width),
                got: points.len(),
            });
        }
        Ok(())
    }

    /// The ptex locations of the hull's first face at `coords`.
    fn locations(&self, coords: &[[f64; 2]]) -> Result<Vec<(u32, f64, f64)>> {
        let mut locations = Vec::new();
        alloc::reserve(&mut locations, coords.len())?;
        for &uv in coords {
            if !self.is_valid() || !self.param.contains(uv, 1e-9) {
                return Err(self.off_face(uv));
            }
            let (sub, [s, t]) = if self.param.has_subfaces() {
                self.param.coord_to_subface(uv, true)?
            } else {
                (0, uv)
            };
            locations.push((sub as u32, s.clamp(0.0, 1.0), t.clamp(0.0, 1.0)));
        }
        Ok(locations)
    }

    fn off_face(&self, [u, v]: [f64; 2]) -> Error {
        Error::OffFace {
            face: self.face,
            u,
            v,
            domain: if self.is_valid() {
                self.param.domain()
            } else {
                "no limit surface"
            },
        }
    }

    /// `Evaluate` over the mesh's points (`width` values per mesh vertex):
    /// the surface's values and the derivatives asked for at `coords`, its
    /// stencils applied to its control points.
    pub fn evaluate(
        &self,
        points: &[f64],
        width: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        self.check_points(points, width)?;
        match self.form {
            Form::Irregular(_) => {
                // Through the patch points: cheaper than a stencil per
                // coordinate once there are more than a few.
                let patch_points = self.patch_points(points, width)?;
                self.evaluate_patch_points(&patch_points, width, coords, derivatives)
            }
            Form::Regular { patch, mask } => {
                self.evaluate_regular(patch, mask, points, width, coords, derivatives)
            }
            _ => self.apply_stencils(&self.control_points, points, width, coords, derivatives),
        }
    }

    /// A regular patch evaluated coordinate by coordinate, its basis
    /// weights applied to its control points without a stencil per
    /// coordinate.
    fn evaluate_regular(
        &self,
        patch: PatchType,
        mask: u16,
        points: &[f64],
        width: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        if let Some(&uv) = coords.iter().find(|&&uv| !self.param.contains(uv, 1e-9)) {
            return Err(self.off_face(uv));
        }
        let kinds = match derivatives {
            Derivatives::None => 1,
            Derivatives::First => 3,
            Derivatives::Second => 6,
        };
        let len = coords.len().saturating_mul(width);
        let mut columns: [Vec<f64>; 6] = Default::default();
        for column in columns.iter_mut().take(kinds) {
            *column = alloc::try_vec(0.0, len)?;
        }
        let param = PatchParam::new(0, 0, 0, 0, false, mask, 0, true);
        let mut buf: BasisBuffer = [[0.0; 20]; 6];
        for (i, &uv) in coords.iter().enumerate() {
            let [u, v] = self.clamped(uv);
            let n = evaluate_basis_into(patch, param, u, v, derivatives, None, &mut buf)?;
            for (column, weights) in columns.iter_mut().zip(&buf).take(kinds) {
                let out = &mut column[i * width..(i + 1) * width];
                for (&cv, &w) in self.control_points.iter().zip(&weights[..n]) {
                    let p = &points[cv as usize * width..(cv as usize + 1) * width];
                    for (o, &x) in out.iter_mut().zip(p) {
                        *o += w * x;
                    }
                }
            }
        }
        Ok(SurfaceSamples {
            width,
            values: Partials::from_columns(columns),
        })
    }

    /// The stencils at `coords` applied to `points`, the stencils' weights
    /// going to the points at `indices`.
    fn apply_stencils(
        &self,
        indices: &[u32],
        points: &[f64],
        width: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        let stencils = self.evaluate_stencil(coords, derivatives)?;
        let mut columns: [Vec<f64>; 6] = Default::default();
        for s in &stencils {
            let parts = [&s.point, &s.du, &s.dv, &s.duu, &s.duv, &s.dvv];
            for (col, weights) in columns.iter_mut().zip(parts) {
                if weights.is_empty() {
                    continue;
                }
                let start = col.len();
                col.resize(start + width, 0.0);
                for (&cv, &w) in indices.iter().zip(weights) {
                    let p = &points[cv as usize * width..(cv as usize + 1) * width];
                    for (o, &x) in col[start..].iter_mut().zip(p) {
                        *o += w * x;
                    }
                }
            }
        }
        Ok(SurfaceSamples {
            width,
            values: Partials::from_columns(columns),
        })
    }
}
