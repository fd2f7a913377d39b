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
//!
//! How a surface is evaluated is `surface_eval.rs`'s concern.

use super::corner::{Corner, CornerTag, Subset};
use super::hull::hull;
use super::parameterization::Parameterization;
use super::plans::{MIN_HULL_COORDS, MIN_REGULAR_COORDS, PLAN_BUDGET, Plans};
use super::regular::{points_at, shortcut_corners, shortcut_points, subset_mask, subset_points};
use super::surface_eval::apply_regular;
use super::surfaces::SurfaceOptions;
use crate::error::{Element, Error, Result};
use crate::mesh::Mesh;
use crate::options::{
    AdaptiveOptions, BoundaryInterpolation, CreasingMethod, FVarLinearInterpolation, Options,
    Scheme, TriangleSubdivision,
};
use crate::patches::{Derivatives, EndCapType, PatchMap, PatchOptions, PatchTable, PatchType};
use crate::refiner::adaptive::{Features, Tag, base_features};
use crate::refiner::{AdaptiveRefiner, Refiner};
use crate::rules::Rule;
use crate::stencil::{StencilRows, StencilTable};
use crate::topology::Level;
use crate::topology::fvar::ChannelLevel;
use rustc_hash::FxHashMap;
use std::sync::atomic::AtomicUsize;
use std::sync::{Arc, Mutex};

/// The boundary masks of a B-spline patch (one bit per edge).
const BSPLINE_MASKS: usize = 16;

/// The boundary masks of a box-spline patch (`encodeTriBoundaryMask`: two
/// bits of kind above three of edges or vertices, the kind at most 2).
const BOX_SPLINE_MASKS: usize = 24;

/// The deepest approximation level (OpenSubdiv's adaptive limit).
const MAX_APPROX_LEVEL: u32 = 10;

/// Builds the surfaces of a mesh's base faces (`Bfr::RefinerSurfaceFactory`,
/// with its topology cache: faces whose control hulls match share one
/// refinement).
#[derive(Debug)]
pub struct SurfaceFactory {
    refiner: Refiner,
    features: Vec<Features>,
    surface: SurfaceOptions,
    /// The refined hulls built so far, by topology (Bfr's topology cache:
    /// faces whose hulls match share one refinement).
    cache: Mutex<FxHashMap<HullKey, Arc<Irregular>>>,
    /// The bytes of evaluation plans the hulls may still keep.
    plan_budget: Arc<AtomicUsize>,
    /// Regular faces' evaluation plans: B-spline patches by boundary mask
    /// (4 bits: [`BSPLINE_MASKS`]), then box-spline patches by boundary
    /// mask (5 bits, up to 23: [`BOX_SPLINE_MASKS`]).
    regular_plans: Vec<Arc<Plans>>,
    /// Per base face, whether it has a limit surface that the refiner's
    /// shortcut makes regular (not a hole, not bilinear, of the regular
    /// size): a mesher asks for each face's validity, vertex and
    /// face-varying surfaces, so it is found once for all faces.
    shortcut: Vec<bool>,
}

/// A face that the refiner's shortcut makes a regular patch: where its
/// points sit in the base level's face-vertex list
/// ([`shortcut_corners`]), their number and the boundary mask.
pub(super) struct Shortcut {
    face: usize,
    corners: [u32; 16],
    len: usize,
    mask: u16,
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
pub(super) enum Form {
    /// No limit surface.
    Invalid,
    /// The face itself: bilinear (or linear, a triangle under Loop) when
    /// `regular`, else split into quads at its centre.
    Linear { regular: bool },
    /// One regular patch with this boundary mask, and the evaluation plans
    /// of its kind.
    Regular {
        patch: PatchType,
        mask: u16,
        plans: Arc<Plans>,
    },
    /// The patches of an adaptive refinement of the face's control hull
    /// (shared by the faces whose hulls have the same topology).
    Irregular(Arc<Irregular>),
}

#[derive(Debug)]
pub(super) struct Irregular {
    pub(super) refiner: AdaptiveRefiner,
    pub(super) table: PatchTable,
    pub(super) map: PatchMap,
    /// The refined vertices' stencils over the hull's vertices.
    pub(super) refined: StencilTable,
    /// The hull's vertices.
    pub(super) base: usize,
    /// The table's local points' stencils over the hull's vertices (the
    /// local points' own stencils composed with `refined`): with `refined`,
    /// every patch point as a stencil of the control points, as Bfr's
    /// patch tree holds them.
    pub(super) locals: StencilTable,
    /// For each of the table's local points, its place among Bfr's patch
    /// points (Bfr numbers the end caps' points patch by patch, level by
    /// level).
    pub(super) local_order: Vec<usize>,
    /// The hull's evaluation plans (`plans.rs`).
    pub(super) plans: Plans,
}

/// A surface's control points: inline up to a regular patch's 16 (no
/// allocation for regular and linear surfaces, which a mesher builds face
/// after face), else on the heap.
#[derive(Debug, Clone)]
pub(super) enum ControlPoints {
    Inline { len: u8, points: [u32; 16] },
    Heap(Vec<u32>),
}

impl ControlPoints {
    /// A copy of `points`.
    pub(super) fn from_slice(points: &[u32]) -> ControlPoints {
        if points.len() <= 16 {
            let mut inline = [0; 16];
            inline[..points.len()].copy_from_slice(points);
            ControlPoints::Inline {
                len: points.len() as u8,
                points: inline,
            }
        } else {
            ControlPoints::Heap(points.to_vec())
        }
    }
}

impl std::ops::Deref for ControlPoints {
    type Target = [u32];
    fn deref(&self) -> &[u32] {
        match self {
            ControlPoints::Inline { len, points } => &points[..usize::from(*len)],
            ControlPoints::Heap(points) => points,
        }
    }
}

impl From<Vec<u32>> for ControlPoints {
    fn from(points: Vec<u32>) -> ControlPoints {
        ControlPoints::Heap(points)
    }
}

/// One base face's limit surface (`Bfr::Surface<double>`).
#[derive(Debug)]
pub struct Surface {
    pub(super) face: usize,
    pub(super) param: Parameterization,
    pub(super) control_points: ControlPoints,
    pub(super) patch_points: usize,
    pub(super) form: Form,
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
        let budget = Arc::new(AtomicUsize::new(PLAN_BUDGET));
        let mut factory = SurfaceFactory {
            features,
            surface: *surface,
            cache: Mutex::new(FxHashMap::default()),
            regular_plans: (0..BSPLINE_MASKS + BOX_SPLINE_MASKS)
                .map(|_| Arc::new(Plans::new(budget.clone(), MIN_REGULAR_COORDS)))
                .collect(),
            plan_budget: budget,
            shortcut: Vec::new(),
            refiner,
        };
        factory.shortcut = factory.shortcut_faces()?;
        Ok(factory)
    }

    /// Per base face, whether the refiner's shortcut makes it a regular
    /// patch ([`SurfaceFactory::shortcut_regular`]) — false for holes,
    /// faces of another size and the bilinear scheme. A face whose corners
    /// carry no tag at all (interior, smooth, regular valence, no sharpness)
    /// is regular without combining its corners' tags.
    fn shortcut_faces(&self) -> Result<Vec<bool>> {
        let base = &self.refiner.levels[0];
        let mut plain = Vec::new();
        crate::alloc::reserve(&mut plain, base.vertex_count)?;
        plain.extend((0..base.vertex_count).map(|v| {
            let t = Tag::of(base, &self.features, v);
            let f = t.features;
            !(f.xordinary
                || f.incid_irreg_face
                || f.inf_irregular
                || t.non_manifold
                || t.boundary
                || t.semi_sharp
                || t.semi_sharp_edges
                || t.inf_sharp
                || t.inf_sharp_edges)
        }));
        let mut shortcut = Vec::new();
        crate::alloc::reserve(&mut shortcut, base.face_count())?;
        let (bilinear, size) = (self.scheme() == Scheme::Bilinear, self.reg_size());
        shortcut.extend((0..base.face_count()).map(|f| {
            let verts = base.face_verts(f);
            !bilinear
                && verts.len() == size
                && !base.is_hole(f)
                && (verts.iter().all(|&v| plain[v as usize]) || self.shortcut_regular(base, f))
        }));
        Ok(shortcut)
    }

    /// The number of base faces.
    pub fn face_count(&self) -> usize {
        self.refiner.levels[0].face_count()
    }

    /// The parameterization of base face `face` (`GetFaceParameterization`),
    /// without building its surface.
    pub fn parameterization(&self, face: usize) -> Result<Parameterization> {
        let base = &self.refiner.levels[0];
        if face >= base.face_count() {
            return Err(Error::NoSuchElement {
                element: Element::Face,
                index: face,
                level: 0,
                count: base.face_count(),
            });
        }
        Parameterization::new(self.scheme(), base.face_verts(face).len())
    }

    /// Whether base face `face` has a limit surface
    /// (`FaceHasLimitSurface`: not a hole nor degenerate, no smooth
    /// boundary under boundary interpolation "none", no non-triangle next
    /// to a Loop face); false for faces that do not exist.
    pub fn has_limit_surface(&self, face: usize) -> bool {
        // (A face the shortcut makes regular has one.)
        self.shortcut.get(face).is_some_and(|&s| s)
            || matches!(
                self.neighbourhood(face),
                Ok(Neighbourhood::Linear(_)
                    | Neighbourhood::Shortcut(_)
                    | Neighbourhood::Corners { .. })
            )
    }

    fn scheme(&self) -> Scheme {
        self.refiner.options.scheme
    }

    /// The base level's edges (the edge of each face corner, each edge's
    /// vertices) when every pair of vertices has one edge: no vertex is
    /// non-manifold (degenerate edges and edges twice in a face get one
    /// edge per instance, and tag their vertices).
    pub(super) fn base_edges(&self) -> Option<(&[u32], &[[u32; 2]])> {
        let base = &self.refiner.levels[0];
        if (0..base.vertex_count).any(|v| base.vertex_tag(v).non_manifold()) {
            return None;
        }
        Some((&base.face_edges, &base.edge_vertices))
    }

    fn reg_size(&self) -> usize {
        if self.scheme() == Scheme::Loop { 3 } else { 4 }
    }

    /// What Bfr needs to know of a face's neighbourhood before building any
    /// of its surfaces (`SurfaceFactory::populateAllSurfaces` up to the
    /// surfaces themselves).
    fn neighbourhood(&self, face: usize) -> Result<Neighbourhood> {
        // (Refuses a face that does not exist.)
        let param = self.parameterization(face)?;
        let base = &self.refiner.levels[0];
        if param.face_size() < 3 || base.is_hole(face) {
            return Ok(Neighbourhood::Invalid(param));
        }
        if self.scheme() == Scheme::Bilinear {
            return Ok(Neighbourhood::Linear(param));
        }
        if self.shortcut[face] {
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

    /// Where the points of base face `face`'s B-spline patch sit when the
    /// refiner's shortcut makes it one (a quad under Catmull-Clark), for
    /// [`SurfaceFactory::evaluate_shortcut_into`] and
    /// [`SurfaceFactory::evaluate_fvar_shortcut_into`] to share.
    pub(super) fn shortcut(&self, face: usize) -> Option<Shortcut> {
        if !self.shortcut.get(face).is_some_and(|&s| s) {
            return None;
        }
        let (corners, len, mask) = shortcut_corners(&self.refiner.levels[0], face);
        Some(Shortcut {
            face,
            corners,
            len,
            mask,
        })
    }

    /// The vertex surface of base face `face` (`InitVertexSurface`): holes
    /// and faces without a limit surface give an invalid surface.
    pub fn vertex_surface(&self, face: usize) -> Result<Surface> {
        let base = &self.refiner.levels[0];
        match self.neighbourhood(face)? {
            Neighbourhood::Invalid(param) => Ok(Surface::invalid(face, param)),
            Neighbourhood::Linear(param) => Ok(self.linear(face, param, base.face_verts(face))),
            Neighbourhood::Shortcut(param) => {
                let (points, len, mask) = shortcut_points(base, face, &base.face_vertices.members);
                Ok(self.regular(face, param, &points[..len], mask))
            }
            Neighbourhood::Corners {
                param,
                corners,
                subsets,
            } => self.nonlinear(face, param, &corners, &subsets),
        }
    }

    /// The vertex surface of base face `face` (points of 3 values in
    /// `points`) evaluated at `coords` into `out` without building it, when
    /// the refiner's shortcut makes it a regular patch (B-spline or box
    /// spline) and its kind keeps a plan for `coords` (`plans.rs`): the plan
    /// applied straight to the shortcut's 16 or 12 points, as
    /// [`Surface::evaluate_into`] would. `None`
    /// otherwise: the caller builds the surface.
    /// `shortcut` is [`SurfaceFactory::shortcut`]'s for `face`.
    pub(super) fn evaluate_shortcut_into(
        &self,
        shortcut: &Shortcut,
        points: &[f64],
        coords: &[[f64; 2]],
        derivatives: Derivatives,
        out: &mut [&mut [f64]],
    ) -> Option<()> {
        if out.len() != derivatives.columns() || out.iter().any(|c| c.len() != 3 * coords.len()) {
            return None;
        }
        let base = &self.refiner.levels[0];
        let (control, len) = (
            points_at(&shortcut.corners, &base.face_vertices.members),
            shortcut.len,
        );
        let control = &control[..len];
        if control.iter().any(|&v| 3 * (v as usize + 1) > points.len()) {
            return None;
        }
        let plan = self.shortcut_plan(shortcut, coords, derivatives)?;
        apply_regular(&plan, control, points, 3.into(), out).then_some(())
    }

    /// The kept plan of `shortcut`'s kind of patch (B-spline or box spline,
    /// and its boundary mask) at `coords`, when it is dense over the
    /// patch's points.
    fn shortcut_plan(
        &self,
        shortcut: &Shortcut,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Option<Arc<crate::patches::LocationStencils>> {
        let kind = match shortcut.len {
            16 => shortcut.mask as usize,
            12 => BSPLINE_MASKS + shortcut.mask as usize,
            _ => return None,
        };
        let plan = self.regular_plans.get(kind)?.kept(coords, derivatives)?;
        (plan.locations.len() == coords.len() && plan.indices.len() == shortcut.len * coords.len())
            .then_some(plan)
    }

    /// [`SurfaceFactory::evaluate_shortcut_into`] for face-varying channel
    /// `channel` (its `values`, `width` each, at most 3): when its surface
    /// over `face` is the B-spline patch of the refiner's shortcut (the
    /// channel matches the vertex topology around the face, as
    /// [`SurfaceFactory::fvar_surface`] asks) and a plan for `coords` is
    /// kept.
    /// `shortcut` is [`SurfaceFactory::shortcut`]'s for the face.
    pub(super) fn evaluate_fvar_shortcut_into(
        &self,
        shortcut: &Shortcut,
        channel: usize,
        values: &[f64],
        width: usize,
        coords: &[[f64; 2]],
        out: &mut [f64],
    ) -> Option<()> {
        let linear = self.scheme() == Scheme::Bilinear
            || self.refiner.options.fvar == FVarLinearInterpolation::All;
        if linear || !(1..=3).contains(&width) || out.len() != width * coords.len() {
            return None;
        }
        let base = &self.refiner.levels[0];
        let chan = self.refiner.fvar.get(channel)?.first()?;
        if !fvar_topology_matches(base, chan, shortcut.face) {
            return None;
        }
        let (control, len) = (
            points_at(&shortcut.corners, chan.face_values()),
            shortcut.len,
        );
        let control = &control[..len];
        if control
            .iter()
            .any(|&v| width * (v as usize + 1) > values.len())
        {
            return None;
        }
        let plan = self.shortcut_plan(shortcut, coords, Derivatives::None)?;
        apply_regular(&plan, control, values, width.into(), &mut [out]).then_some(())
    }

    /// [`SurfaceFactory::fvar_surface`] of the options' default channel
    /// ([`SurfaceOptions::default_fvar_channel`]:
    /// `InitFaceVaryingSurface` without a channel).
    pub fn default_fvar_surface(&self, face: usize) -> Result<Surface> {
        self.fvar_surface(face, self.surface.default_fvar_channel)
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
                    let (points, len, mask) = shortcut_points(base, face, chan.face_values());
                    return Ok(self.regular(face, param, &points[..len], mask));
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
        control_points: &[u32],
        mask: u16,
    ) -> Surface {
        let (patch, plans) = if self.reg_size() == 4 {
            (PatchType::Regular, 0)
        } else {
            (PatchType::Loop, BSPLINE_MASKS)
        };
        Surface {
            face,
            param,
            patch_points: control_points.len(),
            control_points: ControlPoints::from_slice(control_points),
            form: Form::Regular {
                patch,
                mask,
                plans: self.regular_plans[plans + mask as usize].clone(),
            },
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
            return Ok(self.regular(face, param, &control_points, subset_mask(subsets)));
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
        // Without caching, every face's neighbourhood is refined anew.
        let key = self
            .surface
            .caching
            .then(|| HullKey::new(&hull.mesh, &local));
        let cached = key.as_ref().and_then(|key| {
            self.cache
                .lock()
                .unwrap_or_else(|poisoned| poisoned.into_inner())
                .get(key)
                .cloned()
        });
        let irregular = match (cached, key) {
            (Some(irregular), _) => irregular,
            (None, None) => Arc::new(self.irregular(&hull.mesh, &local)?),
            (None, Some(key)) => {
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
            control_points: hull.control_points.into(),
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
            control_points: ControlPoints::from_slice(verts),
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
        let mut tags = [Tag::default(); 4];
        for (t, &v) in tags.iter_mut().zip(verts) {
            *t = Tag::of(base, &self.features, v as usize);
        }
        let tags = &tags[..verts.len()];
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
        verts.iter().zip(tags).all(|(&v, t)| {
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
        let locals = over_base(&table.local_point_stencils, &refined, base)?;
        Ok(Irregular {
            refiner,
            table,
            map,
            refined,
            base,
            locals,
            local_order,
            plans: Plans::new(self.plan_budget.clone(), MIN_HULL_COORDS),
        })
    }
}

/// The stencils of `stencils` (over points whose own stencils over `base`
/// control points are `points`) over the control points themselves.
fn over_base(stencils: &StencilTable, points: &StencilTable, base: usize) -> Result<StencilTable> {
    let mut out = StencilRows::with_capacity(stencils.len(), stencils.indices.len());
    let mut dense = vec![0.0; base];
    for s in 0..stencils.len() {
        let (indices, weights) = stencils.row(s);
        for (&i, &w) in indices.iter().zip(weights) {
            if (i as usize) >= points.len() {
                return Err(Error::StencilOutOfRange {
                    index: i as usize,
                    count: points.len(),
                });
            }
            let (pi, pw) = points.row(i as usize);
            for (&j, &x) in pi.iter().zip(pw) {
                let d = dense.get_mut(j as usize).ok_or(Error::StencilOutOfRange {
                    index: j as usize,
                    count: base,
                })?;
                *d += w * x;
            }
        }
        out.begin_row();
        for (j, x) in dense.iter_mut().enumerate() {
            if *x != 0.0 {
                out.term(j as u32, *x);
                *x = 0.0;
            }
        }
        out.end_row();
    }
    Ok(out.finish())
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
