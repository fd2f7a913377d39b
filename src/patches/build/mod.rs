//! Native patch tables (`Far::PatchTableFactory::Create` on a feature-
//! adaptive refinement): which faces of which levels are patches, in
//! OpenSubdiv's order; regular patches with their control vertices,
//! boundary masks and single-crease sharpness; the [`PatchParam`] words;
//! end caps (Gregory, B-spline and bilinear basis; under Loop, Gregory
//! triangles, box-spline and linear triangles) with their local points and
//! stencils, and the legacy Gregory end caps with their quad-offset and
//! valence tables — each as OpenSubdiv 3.5 builds it.
//!
//! # Files
//! * this file: options, the patches in order, the arrays;
//! * `corners.rs`: the corner tags and what they make of a patch (regular,
//!   boundary mask, single crease);
//! * `points.rs`: the control vertices of regular patches;
//! * `legacy.rs`: the legacy Gregory tables;
//! * `source.rs` (the source patch, quad or triangle), `matrix.rs`,
//!   `local.rs`: what every end cap shares — its source points, its
//!   change-of-basis matrix, its local points;
//! * `limits.rs`, `gregory.rs`, `bspline.rs`: Catmull-Clark's limit
//!   weights, Gregory and B-spline end caps;
//! * `loop_limits.rs`, `loop_gregory.rs`, `box_spline.rs`: Loop's limit
//!   weights, Gregory-triangle and box-spline end caps;
//! * `linear.rs`: bilinear quads and linear triangles;
//! * `placement.rs`: the patches' parameters, ptex faces, maximum valence;
//! * `uniform.rs`: tables of uniformly refined topologies;
//! * `fvar.rs`: the face-varying channels of a table, linear face-varying
//!   patches;
//! * `fvar_patches.rs`: non-linear face-varying patches (regular patches
//!   and end caps over each channel's own topology, with the channel's
//!   local points) — the topology inspections above read a channel's
//!   topology when given one.

mod box_spline;
mod bspline;
mod corners;
mod fvar;
mod fvar_patches;
mod gregory;
mod legacy;
mod limits;
mod linear;
mod local;
mod loop_gregory;
mod loop_limits;
mod matrix;
mod placement;
mod points;
mod source;
mod uniform;
mod view;

use super::{EndCapType, PatchArray, PatchOptions, PatchParam, PatchTable, PatchType};
use crate::error::{Error, LevelRefusal, Result};
use crate::options::Scheme;
use crate::real::Real;
use crate::refiner::AdaptiveRefiner;
use crate::refiner::adaptive::Features;
use crate::topology::Level;
use crate::topology::refine::sparse::SparseSplit;
use local::LocalPoints;
use rustc_hash::FxHashMap;

/// The stencil entries reserved per end-cap point: more than the points
/// of a Gregory end cap have on average (7.5 on the bench's inputs, where
/// neighbours share a third of them; room reserved and never written is
/// never touched, so never paid for).
const END_CAP_ENTRIES: usize = 10;

/// The deepest isolation `PatchTableFactory::Options` holds (4 bits).
const MAX_ISOLATION: u32 = 10;

/// The refinement being read and the options that shape its patches.
pub(super) struct Builder<'a> {
    levels: &'a [Level],
    steps: &'a [SparseSplit],
    features: &'a [Vec<Features>],
    /// The scheme's regular face size: 4, or 3 under Loop.
    reg: usize,
    /// Bilinear: every patch is the face itself.
    linear: bool,
    /// `useInfSharpPatch`: infinitely sharp features stay in regular patches.
    inf_sharp_patch: bool,
    /// `generateLegacySharpCornerPatches`: smooth boundary corners are
    /// taken as sharp.
    sharp_corners: bool,
    /// Whether a base face is not of the regular size.
    irregular_base_faces: bool,
    /// The face-varying channels to build patches for.
    fvar: Vec<fvar::Channel<'a>>,
    /// Whether their patches are linear (`isFVarChannelLinear`).
    fvar_linear: bool,
}

/// One patch: a face of a level.
#[derive(Debug, Clone, Copy)]
struct Patch {
    level: usize,
    face: usize,
}

impl AdaptiveRefiner {
    /// The patch table of this refinement (`Far::PatchTableFactory::
    /// Create`), built natively: the same arrays, patch order, control
    /// vertices, [`PatchParam`] words and single-crease sharpness as
    /// OpenSubdiv 3.5's, for the patches of `selected_faces` (every face
    /// when empty).
    ///
    /// The native engine builds every table of Catmull-Clark, Loop and
    /// bilinear topologies (every end-cap type — under Loop Gregory
    /// triangles, box-spline or linear triangles —, with the local points'
    /// vertex and varying stencils in `f32` or `f64`), with face-varying
    /// patches: linear ones (`generateFVarLegacyLinearPatches`, OpenSubdiv's
    /// default, or a channel interpolated linearly everywhere: each patch's
    /// face in the channel), or the channel's own regular patches and end
    /// caps with their local points' stencils.
    ///
    /// Refused: an isolation level beyond 10 ([`Error::Level`]), a selected
    /// face or face-varying channel that does not exist, more face-varying
    /// channels listed than the refiner has; and, as the `osd`
    /// engine refuses them, legacy Gregory end caps under another scheme
    /// than Catmull-Clark, or with an irregular patch above the last level,
    /// a face of the last level that is not a quad or a non-manifold vertex
    /// there ([`Error::PatchOptions`]).
    ///
    /// ```
    /// use subdiv::{patches::{EndCapType, PatchOptions, PatchType}, refiner::Refiner, shapes, Options};
    /// // A 4x4 grid of quads, isolated to level 2 with its boundary and
    /// // corners: every patch is regular (no end caps needed).
    /// let refiner = Refiner::new(&shapes::grid(4, 4), &Options::default())?;
    /// let options = PatchOptions::new().max_isolation(2);
    /// let adaptive = refiner.refine_adaptive(options.refine_adaptive_options(), &[])?;
    /// let table = adaptive.patch_table(&options, &[])?;
    /// assert_eq!(table.arrays.len(), 1);
    /// assert_eq!(table.arrays[0].patch_type, PatchType::Regular);
    /// assert!(table.arrays[0].params.iter().all(|p| p.is_regular()));
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn patch_table(
        &self,
        options: &PatchOptions,
        selected_faces: &[u32],
    ) -> Result<PatchTable> {
        let (levels, steps, features) = self.parts();
        if options.max_isolation_level > MAX_ISOLATION {
            return Err(Error::Level {
                level: options.max_isolation_level,
                reason: LevelRefusal::TooDeep { max: MAX_ISOLATION },
            });
        }
        let channels = self.fvar_channel_count();
        if let Some(&c) = options.fvar_channels.iter().find(|&&c| c >= channels) {
            return Err(Error::NoSuchChannel {
                channel: c,
                count: channels,
            });
        }
        let base = &levels[0];
        crate::refiner::adaptive::check_selected_faces(base, selected_faces)?;
        let requested = fvar::requested(options, channels)?;
        let fvar_linear = fvar::is_linear(options, self.options().fvar);
        if !requested.is_empty() && !fvar_linear {
            fvar::check_listed(options, channels)?;
        }
        let scheme = self.options().scheme;
        let legacy = options.end_cap_type == EndCapType::LegacyGregory;
        if legacy && scheme != Scheme::Catmark {
            return Err(Error::PatchOptions {
                reason: "legacy Gregory end caps exist for Catmull-Clark only".into(),
            });
        }
        let reg = if scheme == Scheme::Loop { 3 } else { 4 };
        let b = Builder {
            levels,
            steps,
            features,
            reg,
            linear: scheme == Scheme::Bilinear,
            inf_sharp_patch: options.inf_sharp_patch,
            sharp_corners: options.legacy_sharp_corner_patches,
            irregular_base_faces: (0..base.face_count())
                .any(|f| base.face_vertices.count(f) != reg),
            fvar: requested
                .iter()
                .enumerate()
                .map(|(k, &c)| {
                    let regularity = (k < channels).then(|| self.fvar_levels(k));
                    fvar::Channel::new(c, self.fvar_levels(c), regularity)
                })
                .collect(),
            fvar_linear,
        };
        crate::alloc::guard(None, || b.build(options, selected_faces, scheme))
    }
}

impl Builder<'_> {
    fn max_level(&self) -> usize {
        self.levels.len() - 1
    }

    /// `PatchBuilder::IsFaceAPatch`: not a hole; in the base level, not
    /// next to an irregular face (bilinear: of the regular size); in later
    /// levels, complete.
    fn is_patch(&self, level: usize, f: usize) -> bool {
        let l = &self.levels[level];
        if l.is_hole(f) {
            return false;
        }
        if level == 0 {
            return if self.linear {
                l.face_vertices.count(f) == self.reg
            } else {
                !l.face_verts(f)
                    .iter()
                    .any(|&v| self.features[0][v as usize].incid_irreg_face)
            };
        }
        if self.reg == 4 {
            let features = &self.features[level];
            !l.face_verts(f)
                .iter()
                .any(|&v| features[v as usize].incomplete)
        } else {
            let step = &self.steps[level - 1];
            step.selection.face(step.child_face_parent[f] as usize)
        }
    }

    /// `PatchBuilder::IsFaceALeaf`: not selected for further refinement.
    fn is_leaf(&self, level: usize, f: usize) -> bool {
        level >= self.max_level() || !self.steps[level].selection.face(f)
    }

    /// The patches in OpenSubdiv's order: level by level, or depth first
    /// under each selected base face.
    fn identify(&self, selected: &[u32]) -> Vec<Patch> {
        let mut patches = Vec::new();
        if selected.is_empty() {
            for (level, l) in self.levels.iter().enumerate() {
                for face in 0..l.face_count() {
                    if self.is_patch(level, face) && self.is_leaf(level, face) {
                        patches.push(Patch { level, face });
                    }
                }
            }
        } else {
            let mut stack = Vec::new();
            for &f in selected {
                stack.push(Patch {
                    level: 0,
                    face: f as usize,
                });
                while let Some(p) = stack.pop() {
                    if self.is_leaf(p.level, p.face) {
                        if self.is_patch(p.level, p.face) {
                            patches.push(p);
                        }
                        continue;
                    }
                    let children = self.child_faces(p.level, p.face);
                    // Depth first, children in order: pushed in reverse.
                    for &c in children.iter().rev() {
                        if c != crate::INVALID_INDEX {
                            stack.push(Patch {
                                level: p.level + 1,
                                face: c as usize,
                            });
                        }
                    }
                }
            }
        }
        patches
    }

    /// The child faces of face `f` of `level` (invalid where not refined).
    fn child_faces(&self, level: usize, f: usize) -> &[u32] {
        let step = &self.steps[level];
        let range = if step.triangles {
            4 * f..4 * f + 4
        } else {
            self.levels[level].face_vertices.range(f)
        };
        &step.face_child_faces[range]
    }

    fn build(
        &self,
        options: &PatchOptions,
        selected: &[u32],
        scheme: Scheme,
    ) -> Result<PatchTable> {
        if options.patch_precision_double {
            self.build_in::<f64>(options, selected, scheme)
        } else {
            self.build_in::<f32>(options, selected, scheme)
        }
    }

    /// The table with end-cap weights computed in `R`.
    fn build_in<R: Real>(
        &self,
        options: &PatchOptions,
        selected: &[u32],
        scheme: Scheme,
    ) -> Result<PatchTable> {
        let patches = self.identify(selected);
        // Each level's relations as slices (not for bilinear patches, the
        // faces themselves).
        let views: Vec<view::LevelView> = if self.linear {
            Vec::new()
        } else {
            (0..self.levels.len())
                .map(|level| view::LevelView::new(self, level))
                .collect()
        };
        // Whether each patch is regular, and the boundary mask of a regular
        // one, from one reading of its corners' tags.
        let (regular, masks): (Vec<bool>, Vec<u16>) = patches
            .iter()
            .map(|p| {
                if views.get(p.level).is_some_and(|v| v.plain_face(p.face)) {
                    return (true, 0);
                }
                let tags = self.corner_tags(p.level, p.face, None);
                let regular = self.is_regular_with(p.level, p.face, None, &tags);
                let mask = if regular {
                    self.boundary_mask_with(p.level, p.face, None, &tags)
                } else {
                    0
                };
                (regular, mask)
            })
            .unzip();
        let legacy = options.end_cap_type == EndCapType::LegacyGregory;
        let (regular_type, linear_type) = match scheme {
            Scheme::Catmark => (PatchType::Regular, PatchType::Quads),
            Scheme::Loop => (PatchType::Loop, PatchType::Triangles),
            Scheme::Bilinear => (PatchType::Quads, PatchType::Quads),
        };
        let irregular_type = match (options.end_cap_type, scheme) {
            (EndCapType::BilinearBasis, _) => linear_type,
            (EndCapType::GregoryBasis, Scheme::Loop) => PatchType::GregoryTriangle,
            (EndCapType::GregoryBasis, _) => PatchType::GregoryBasis,
            (EndCapType::LegacyGregory, _) => PatchType::Gregory,
            (EndCapType::BSplineBasis | EndCapType::None, _) => regular_type,
        };
        let mut offsets = Vec::with_capacity(self.levels.len() + 1);
        offsets.push(0u32);
        for l in self.levels {
            let last = *offsets.last().expect("first offset");
            offsets.push(last + l.vertex_count as u32);
        }
        let ptex = self.ptex_first();
        let mut reg_array = PatchArray::new(regular_type);
        let mut irregular = PatchArray::new(irregular_type);
        let mut interior = PatchArray::new(PatchType::Gregory);
        let mut boundary = PatchArray::new(PatchType::GregoryBoundary);
        let mut legacy_faces = legacy::Faces::default();
        let mut local = LocalPoints::<R>::new(
            *offsets.last().expect("total"),
            options.share_end_cap_points,
            irregular_type == regular_type,
            options.varying_tables && options.varying_local_points,
            self.levels.len(),
        );
        // Room for every patch's entries, so that the arrays never move.
        let irregulars = regular.iter().filter(|&&r| !r).count();
        let regulars = patches.len() - irregulars;
        let varying = options.varying_tables;
        if legacy {
            interior.reserve(irregulars, 4, varying);
        } else {
            let (rows, entries) = (irregular_type.control_vertices(), END_CAP_ENTRIES);
            local.reserve(irregulars, rows, rows * entries);
            if irregular_type == regular_type {
                reg_array.reserve(irregulars, rows, varying);
            } else {
                irregular.reserve(irregulars, rows, varying);
            }
        }
        reg_array.reserve(regulars, regular_type.control_vertices(), varying);
        // OpenSubdiv keeps these from patch to patch: an irregular patch
        // takes the sharpness of the last regular one before it, and a
        // legacy Gregory patch its parameter boundary mask too.
        let mut param_boundary = 0u16;
        let mut sharpness = 0f32;
        // The end caps' matrices, each made once per source patch, and
        // their source points' storage, reused from patch to patch.
        let mut conversions = Conversions::<R>::default();
        let mut spare = matrix::Matrix::<R>::default();
        let (mut sources, mut ring) = (Vec::new(), Vec::new());
        // Each face-varying channel's values, by array (regular, irregular,
        // legacy interior and boundary), put in table order at the end.
        let mut fvar_values: Vec<[Vec<u32>; 4]> =
            self.fvar.iter().map(|_| Default::default()).collect();
        // Each patch's array and vertex parameter, for non-linear channels.
        let nonlinear_fvar = !self.fvar_linear && !self.fvar.is_empty();
        let kept_per_patch = if nonlinear_fvar { patches.len() } else { 0 };
        let mut slots = Vec::with_capacity(kept_per_patch);
        let mut vertex_params = Vec::with_capacity(kept_per_patch);
        let mut walk = placement::QuadWalk::default();
        for ((p, &is_regular), &mask) in patches.iter().zip(&regular).zip(&masks) {
            let offset = offsets[p.level];
            let slot;
            let array = if is_regular {
                param_boundary = mask;
                sharpness = 0.0;
                if options.single_crease_patch
                    && mask == 0
                    && (p.level as u32) < options.max_isolation_level
                    && let Some((s, edge)) = self.single_crease(p.level, p.face)
                {
                    sharpness = s.min((options.max_isolation_level - p.level as u32) as f32);
                    param_boundary = 1 << edge;
                }
                self.regular_points_onto(
                    (p.level, p.face),
                    mask,
                    views.get(p.level),
                    offset,
                    &mut reg_array.control_vertices,
                );
                slot = 0;
                &mut reg_array
            } else if legacy {
                let corners = self.composite(p.level, p.face);
                legacy_faces.add(p.face, corners.boundary);
                slot = if corners.boundary { 3 } else { 2 };
                let a = if corners.boundary {
                    &mut boundary
                } else {
                    &mut interior
                };
                let verts = self.levels[p.level].face_verts(p.face);
                a.control_vertices.extend(verts.iter().map(|&v| v + offset));
                a
            } else {
                param_boundary = 0;
                let spans = self.corner_spans(p.level, p.face, None);
                let source = self.source_patch(p.level, p.face, &spans);
                let (matrix, numbering) = conversions.of(source, |s, m| {
                    Self::convert(irregular_type, s, m, &mut spare);
                });
                self.source_points_into(
                    p.level,
                    p.face,
                    &spans,
                    numbering,
                    None,
                    &mut sources,
                    &mut ring,
                );
                // Irregular patches share the regular array when their
                // types agree.
                let (s, a) = if irregular_type == regular_type {
                    (0, &mut reg_array)
                } else {
                    (1, &mut irregular)
                };
                local.append(
                    self,
                    p.level,
                    p.face,
                    matrix,
                    irregular_type,
                    &sources,
                    offset,
                    None,
                    &mut a.control_vertices,
                );
                slot = s;
                a
            };
            array.sharpness.push(if options.single_crease_patch {
                sharpness
            } else {
                0.0
            });
            let param = self.param_with(
                &mut walk,
                p.level,
                p.face,
                &ptex,
                is_regular,
                param_boundary,
            );
            array.params.push(param);
            if nonlinear_fvar {
                slots.push(slot);
                vertex_params.push(param);
            }
            // The varying patch: the face's own vertices.
            let topology = &self.levels[p.level];
            if options.varying_tables {
                let verts = topology.face_verts(p.face);
                array
                    .varying_vertices
                    .extend(verts.iter().map(|&v| v + offset));
            }
            // The linear face-varying patches: the face in each channel.
            if self.fvar_linear {
                for (ch, parts) in self.fvar.iter().zip(&mut fvar_values) {
                    let at = ch.offsets[p.level];
                    parts[slot].extend(ch.face(topology, p.level, p.face, at));
                }
            }
        }
        let local_points = local.count();
        let (stencils, varying) = local.finish();
        let mut table = PatchTable {
            arrays: Vec::new(),
            local_points,
            local_points_varying: varying.len(),
            local_point_stencils: stencils,
            local_point_varying_stencils: varying,
            max_valence: self.max_valence(),
            ptex_faces: *ptex.last().unwrap_or(&0) as usize,
            quad_offsets: Vec::new(),
            vertex_valences: Vec::new(),
            feature_adaptive: true,
            varying_patch_type: linear_type,
            fvar_channels: Vec::new(),
        };
        // OpenSubdiv fills the valence table whenever legacy Gregory end caps
        // are asked for, irregular patches or not.
        if legacy {
            self.check_legacy(&patches, &regular)?;
            table.quad_offsets = self.quad_offsets(&legacy_faces);
            table.vertex_valences =
                self.vertex_valences(table.max_valence, offsets[self.max_level()]);
        }
        let all = [reg_array, irregular, interior, boundary];
        let kept: Vec<usize> = (0..all.len()).filter(|&i| !all[i].is_empty()).collect();
        if nonlinear_fvar {
            // Each patch's index in the table: its array's first, then its
            // place in the array.
            let mut first = [0usize; 4];
            let mut at = 0;
            for &i in &kept {
                first[i] = at;
                at += all[i].len();
            }
            let index: Vec<usize> = slots
                .iter()
                .map(|&s| {
                    let i = first[s];
                    first[s] += 1;
                    i
                })
                .collect();
            let vertex = fvar_patches::VertexPatches {
                patches: &patches,
                regular: &regular,
                params: &vertex_params,
                index: &index,
            };
            let types = fvar_patches::Types {
                regular: regular_type,
                irregular: irregular_type,
            };
            table.fvar_channels = self.nonlinear_fvar(options, &vertex, types);
            table.arrays = all.into_iter().filter(|a| !a.is_empty()).collect();
            return Ok(table);
        }
        table.fvar_channels = self
            .fvar
            .iter()
            .zip(fvar_values)
            .map(|(ch, parts)| {
                let values = kept
                    .iter()
                    .flat_map(|&i| parts[i].iter().copied())
                    .collect();
                let params = kept
                    .iter()
                    .flat_map(|&i| all[i].params.iter().copied())
                    .collect();
                fvar::Channel::finish(ch.channel, linear_type, values, params)
            })
            .collect();
        table.arrays = all.into_iter().filter(|a| !a.is_empty()).collect();
        Ok(table)
    }
}

/// The change-of-basis matrices of end caps already made, by source
/// patch (the matrix and the numbering of the source points depend on
/// nothing else, and a mesh has few kinds of irregular patches).
struct Conversions<R> {
    index: FxHashMap<source::SourcePatch, usize>,
    made: Vec<(matrix::Matrix<R>, source::Numbering)>,
}

impl<R> Default for Conversions<R> {
    fn default() -> Self {
        Conversions {
            index: FxHashMap::default(),
            made: Vec::new(),
        }
    }
}

impl<R: Real> Conversions<R> {
    /// The matrix and numbering of `source`, made by `convert` (into an
    /// empty matrix) the first time.
    fn of(
        &mut self,
        source: source::SourcePatch,
        convert: impl FnOnce(&source::SourcePatch, &mut matrix::Matrix<R>),
    ) -> (&matrix::Matrix<R>, &source::Numbering) {
        let k = match self.index.get(&source) {
            Some(&k) => k,
            None => {
                let mut m = matrix::Matrix::default();
                convert(&source, &mut m);
                let numbering = source.numbering();
                self.made.push((m, numbering));
                self.index.insert(source, self.made.len() - 1);
                self.made.len() - 1
            }
        };
        let (m, n) = &self.made[k];
        (m, n)
    }
}

impl PatchArray {
    /// Room for `patches` more patches of `cvs` control vertices (and
    /// varying vertices when `varying`). Only a hint: what cannot be
    /// reserved is left to grow as it is pushed.
    fn reserve(&mut self, patches: usize, cvs: usize, varying: bool) {
        let _ = self.control_vertices.try_reserve(patches * cvs);
        let _ = self.params.try_reserve(patches);
        let _ = self.sharpness.try_reserve(patches);
        if varying {
            let _ = self.varying_vertices.try_reserve(patches * 4);
        }
    }

    fn new(patch_type: PatchType) -> PatchArray {
        PatchArray {
            patch_type,
            control_vertices: Vec::new(),
            params: Vec::new(),
            sharpness: Vec::new(),
            varying_vertices: Vec::new(),
        }
    }
}
