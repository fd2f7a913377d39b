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
//! * this file: options, the patches in order, the arrays and parameters;
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
//! * `uniform.rs`: tables of uniformly refined topologies;
//! * `fvar.rs`: linear face-varying patches.
//!
//! Not yet native: non-linear face-varying patches
//! (`generateFVarLegacyLinearPatches` off, the channel not linear); a table
//! that would need them is refused with [`Error::NotYetSupported`].

mod box_spline;
mod bspline;
mod corners;
mod fvar;
mod gregory;
mod legacy;
mod limits;
mod linear;
mod local;
mod loop_gregory;
mod loop_limits;
mod matrix;
mod points;
mod source;
mod uniform;

use super::{EndCapType, PatchArray, PatchOptions, PatchParam, PatchTable, PatchType};
use crate::error::{Error, LevelRefusal, Result};
use crate::options::Scheme;
use crate::real::Real;
use crate::refiner::AdaptiveRefiner;
use crate::refiner::adaptive::Features;
use crate::topology::Level;
use crate::topology::refine::sparse::SparseSplit;
use local::LocalPoints;

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
    /// The face-varying channels to build (linear) patches for.
    fvar: Vec<fvar::Channel<'a>>,
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
    /// patches of linear channels (`generateFVarLegacyLinearPatches`,
    /// OpenSubdiv's default, or a channel interpolated linearly everywhere:
    /// each patch's face in the channel); non-linear face-varying patches
    /// are [`Error::NotYetSupported`] — the `osd` engine builds them.
    ///
    /// Refused: an isolation level beyond 10 ([`Error::Level`]), a selected
    /// face or face-varying channel that does not exist; and, as the `osd`
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
        if !requested.is_empty() {
            fvar::check_linear(options, self.options().fvar)?;
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
                .map(|&c| fvar::Channel::new(c, self.fvar_levels(c)))
                .collect(),
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
            !self.composite(level, f).features.incomplete
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
        let regular: Vec<bool> = patches
            .iter()
            .map(|p| self.is_regular(p.level, p.face))
            .collect();
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
        // OpenSubdiv keeps these from patch to patch: an irregular patch
        // takes the sharpness of the last regular one before it, and a
        // legacy Gregory patch its parameter boundary mask too.
        let mut param_boundary = 0u16;
        let mut sharpness = 0f32;
        // The end caps' matrices, their storage reused from patch to patch.
        let (mut matrix, mut spare) = (
            matrix::Matrix::<R>::default(),
            matrix::Matrix::<R>::default(),
        );
        // Each face-varying channel's values, by array (regular, irregular,
        // legacy interior and boundary), put in table order at the end.
        let mut fvar_values: Vec<[Vec<u32>; 4]> =
            self.fvar.iter().map(|_| Default::default()).collect();
        for (p, &is_regular) in patches.iter().zip(&regular) {
            let offset = offsets[p.level];
            let slot;
            let array = if is_regular {
                let mask = self.boundary_mask(p.level, p.face);
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
                let cvs = self.regular_points(p.level, p.face, mask);
                reg_array
                    .control_vertices
                    .extend(cvs.iter().map(|&v| v + offset));
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
                let spans = self.corner_spans(p.level, p.face);
                let source = self.source_patch(p.level, p.face, &spans);
                match irregular_type {
                    PatchType::Quads | PatchType::Triangles => {
                        linear::convert_into(&source, &mut matrix)
                    }
                    PatchType::Regular => bspline::convert_into(&source, &mut matrix, &mut spare),
                    PatchType::Loop => box_spline::convert_into(&source, &mut matrix, &mut spare),
                    PatchType::GregoryTriangle => {
                        loop_gregory::GregoryTriangle::<R>::new(&source).convert_into(&mut matrix)
                    }
                    _ => gregory::Gregory::<R>::new(&source).convert_into(&mut matrix),
                }
                let sources = self.source_points(p.level, p.face, &spans, &source);
                let cvs = local.append(
                    self,
                    p.level,
                    p.face,
                    &matrix,
                    irregular_type,
                    &sources,
                    offset,
                );
                // Irregular patches share the regular array when their
                // types agree.
                if irregular_type == regular_type {
                    reg_array.control_vertices.extend(cvs);
                    slot = 0;
                    &mut reg_array
                } else {
                    irregular.control_vertices.extend(cvs);
                    slot = 1;
                    &mut irregular
                }
            };
            array.sharpness.push(if options.single_crease_patch {
                sharpness
            } else {
                0.0
            });
            array
                .params
                .push(self.param(p.level, p.face, &ptex, is_regular, param_boundary));
            // The varying patch: the face's own vertices.
            let topology = &self.levels[p.level];
            if options.varying_tables {
                let verts = topology.face_verts(p.face);
                array
                    .varying_vertices
                    .extend(verts.iter().map(|&v| v + offset));
            }
            // The linear face-varying patches: the face in each channel.
            for (ch, parts) in self.fvar.iter().zip(&mut fvar_values) {
                let at = ch.offsets[p.level];
                parts[slot].extend(ch.face(topology, p.level, p.face, at));
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

    /// `TopologyRefiner::GetMaxValence`: the base level's largest valence
    /// or face, then for each refined level OpenSubdiv's bound (at least
    /// the regular valence, and two more than the most faces at an edge of
    /// the parent, doubled for triangles) rather than the level's own.
    fn max_valence(&self) -> usize {
        let tri = self.reg == 3;
        self.levels[..self.max_level()]
            .iter()
            .fold(self.levels[0].max_valence, |bound, parent| {
                let edge = if tri {
                    2 * parent.max_edge_faces
                } else {
                    parent.max_edge_faces
                };
                bound.max(if tri { 6 } else { 4 }).max(2 + edge)
            })
    }

    /// The first ptex face of every base face, and the total last.
    fn ptex_first(&self) -> Vec<u32> {
        let base = &self.levels[0];
        let mut first = Vec::with_capacity(base.face_count() + 1);
        let mut id = 0u32;
        for f in 0..base.face_count() {
            first.push(id);
            let n = base.face_vertices.count(f);
            id += if n == self.reg { 1 } else { n as u32 };
        }
        first.push(id);
        first
    }

    /// `PatchBuilder::ComputePatchParam`: the patch's place in its ptex
    /// face, found by walking up to its base face.
    fn param(
        &self,
        level: usize,
        f: usize,
        ptex: &[u32],
        regular: bool,
        boundary: u16,
    ) -> PatchParam {
        let parent_of = |l: usize, child: usize| {
            let parent = self.steps[l - 1].child_face_parent[child] as usize;
            let k = self
                .child_faces(l - 1, parent)
                .iter()
                .position(|&c| c as usize == child)
                .unwrap_or(0);
            (parent, k)
        };
        let transition = if level < self.max_level() {
            self.steps[level].face_transitional[f]
        } else {
            0
        };
        let place = Placement {
            levels: self.levels,
            reg: self.reg,
            ptex,
        };
        place.param(
            level,
            f,
            parent_of,
            regular,
            boundary,
            u16::from(transition),
        )
    }
}

/// What locating a face in its ptex face needs: every level's faces, the
/// scheme's regular face size and the first ptex face of each base face.
pub(super) struct Placement<'a> {
    pub levels: &'a [Level],
    pub reg: usize,
    pub ptex: &'a [u32],
}

impl Placement<'_> {
    /// The [`PatchParam`] of face `f` of `level`, walking up through
    /// `parent_of(level, face)` (the parent in the level above and the
    /// face's place among its children): a quad's `k`-th child in its
    /// `k`-th quadrant, a triangle's middle child turned over, a non-quad
    /// base face's children its ptex faces.
    pub fn param(
        &self,
        level: usize,
        f: usize,
        parent_of: impl Fn(usize, usize) -> (usize, usize),
        regular: bool,
        boundary: u16,
        transition: u16,
    ) -> PatchParam {
        let (mut u, mut v, mut ofs) = (0i32, 0i32, 1i32);
        let mut irregular_base = self.levels[level].face_vertices.count(f) != self.reg;
        let mut rotated = false;
        let mut child_in_parent = 0usize;
        let mut child = f;
        for i in (1..=level).rev() {
            let (parent, k) = parent_of(i, child);
            child_in_parent = k;
            irregular_base = self.levels[i - 1].face_vertices.count(parent) != self.reg;
            if self.reg == 3 {
                // The middle triangle turns the parameterization over.
                match (k, rotated) {
                    (1, false) => u += ofs,
                    (2, false) => v += ofs,
                    (3, false) => {
                        u -= ofs;
                        v -= ofs;
                        rotated = true;
                    }
                    (1, true) => u -= ofs,
                    (2, true) => v -= ofs,
                    (3, true) => {
                        u += ofs;
                        v += ofs;
                        rotated = false;
                    }
                    _ => {}
                }
                ofs <<= 1;
            } else if !irregular_base {
                match k {
                    1 => u += ofs,
                    2 => {
                        u += ofs;
                        v += ofs;
                    }
                    3 => v += ofs,
                    _ => {}
                }
                ofs <<= 1;
            }
            child = parent;
        }
        if rotated {
            u += ofs;
            v += ofs;
        }
        let mut ptex_face = self.ptex[child];
        if irregular_base {
            ptex_face += child_in_parent as u32;
        }
        PatchParam::new(
            ptex_face,
            u as u16,
            v as u16,
            level as u16,
            irregular_base,
            boundary,
            transition,
            regular,
        )
    }
}

impl PatchArray {
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
