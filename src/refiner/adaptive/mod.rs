//! Feature-adaptive refinement — the native counterpart of OpenSubdiv's
//! `Far::TopologyRefiner::RefineAdaptive` (`far/topologyRefiner.cpp`): each
//! level refines only the faces around features a regular patch cannot
//! represent, down to the isolation level, with the neighbourhood those
//! faces need (the sparse splits of `topology/refine/sparse/`); every level
//! keeps full topology and explicit parent-to-child maps.
//!
//! ```
//! use subdiv::{refiner::Refiner, shapes, AdaptiveOptions, Options, INVALID_INDEX};
//! // A cube: every corner is extraordinary (three faces), and every face of
//! // levels 0 and 1 touches one, so levels 1 and 2 are whole; level 3 refines
//! // the 3 faces at each of the 8 corners (96 children) and, of the 9 faces
//! // around each such patch, the corners next to it (15 children per patch).
//! let cube = shapes::cube();
//! let refiner = Refiner::new(&cube, &Options::default())?;
//! let adaptive = refiner.refine_adaptive(AdaptiveOptions::new(3), &[])?;
//! assert_eq!(adaptive.max_level(), 3);
//! assert_eq!(adaptive.level_counts(2)?.faces, 96);
//! assert_eq!(adaptive.level_counts(3)?.faces, 8 * (3 * 4 + 6 * 2 + 3));
//! let maps = adaptive.child_maps(2)?;
//! assert!(!maps.face_child_vertex.contains(&INVALID_INDEX)); // every face has a neighbour selected
//! assert!(maps.face_child_faces.contains(&INVALID_INDEX));
//! # Ok::<(), subdiv::Error>(())
//! ```
//!
//! # Files
//! * this file: the driver and the queries;
//! * `features.rs`: the vertex tags the selection reads beyond those
//!   refinement keeps (extraordinary, incomplete, ...), on the base level
//!   and passed from level to level;
//! * `select.rs`: which faces a level selects (face-varying features
//!   included);
//! * `interpolate.rs`: vertex, varying and face-varying primvars level by
//!   level; `kernel.rs`: the vertex-data kernel of sparse levels (smooth
//!   masks cached per shape);
//! * `stencils.rs`: stencil tables in every mode of
//!   `StencilTableFactory::Options` (face-varying ones not yet).
//!
//! Face-varying channels refine with the levels and interpolate on them,
//! and with `consider_fvar_channels` their own boundary features select
//! faces too.

mod features;
mod interpolate;
mod kernel;
mod select;
mod stencils;
mod vtag;

use super::Refiner;
use crate::compare::AdaptiveLevel;
use crate::error::{Element, Error, LevelRefusal, Result};
use crate::options::{AdaptiveOptions, MAX_LEVEL, Options, Scheme};
use crate::output::{ChildMaps, FVarTopology, LevelCounts, LevelRelations, LevelTopology};
use crate::rules::SchemeRules;
use crate::topology::Level;
use crate::topology::fvar::ChannelLevel;
use crate::topology::refine::sparse::{Selection, SparseSplit, refine_sparse};
pub(crate) use features::Features;
pub(crate) use features::base_features;
use features::{child_features, regular_face_size};
use glam::DVec3;
use select::{FeatureMask, face_is_selected};
pub(crate) use vtag::{CORNER, CREASE, DART, Tag};

/// The deepest secondary level OpenSubdiv's 4-bit field holds (15: none).
const MAX_SECONDARY_LEVEL: u32 = 15;

/// A topology refined feature-adaptively: sparse levels with their
/// parent-to-child maps ([`Refiner::refine_adaptive`]).
#[derive(Debug, Clone)]
pub struct AdaptiveRefiner {
    options: Options,
    adaptive: AdaptiveOptions,
    rules: SchemeRules,
    levels: Vec<Level>,
    steps: Vec<SparseSplit>,
    features: Vec<Vec<Features>>,
    /// Face-varying topology: `fvar[channel][level]`, refined sparsely
    /// with the levels.
    fvar: Vec<Vec<ChannelLevel>>,
}

impl Refiner {
    /// Refines feature-adaptively (`TopologyRefiner::RefineAdaptive`): level
    /// by level, only the faces around extraordinary vertices, irregular
    /// faces and the sharp features a regular patch cannot represent, down
    /// to `adaptive.isolation_level` (fewer features past
    /// `adaptive.secondary_level`). `selected_faces` restricts the first
    /// level to those base faces (all when empty); holes are never refined.
    /// Refining stops early when a level selects nothing. Bilinear meshes
    /// refine only their non-quads, one level.
    ///
    /// Refused as OpenSubdiv refuses: a refiner already refined
    /// ([`Error::AlreadyRefined`]); and, before anything is refined, an
    /// isolation level beyond [`MAX_LEVEL`] or a secondary level beyond 15
    /// ([`Error::Level`]) and a selected face out of range
    /// ([`Error::NoSuchElement`]).
    pub fn refine_adaptive(
        self,
        adaptive: AdaptiveOptions,
        selected_faces: &[u32],
    ) -> Result<AdaptiveRefiner> {
        if self.max_level() > 0 {
            return Err(Error::AlreadyRefined {
                level: self.max_level(),
            });
        }
        for (level, max) in [
            (adaptive.isolation_level, MAX_LEVEL),
            (adaptive.secondary_level, MAX_SECONDARY_LEVEL),
        ] {
            if level > max {
                return Err(Error::Level {
                    level,
                    reason: LevelRefusal::TooDeep { max },
                });
            }
        }
        let base = &self.levels[0];
        // The first level is at most uniform level 1; deeper ones grow with
        // the features, not the mesh (as the osd engine checks).
        crate::limits::check_level_counts(
            base.face_count(),
            base.face_vertices.members.len(),
            self.options.scheme,
            1,
        )?;
        check_selected_faces(base, selected_faces)?;
        crate::alloc::guard(Some(adaptive.isolation_level), || {
            self.refine_sparse_levels(adaptive, selected_faces)
        })
    }

    /// [`Refiner::refine_adaptive`]'s levels, once its arguments are checked.
    fn refine_sparse_levels(
        self,
        adaptive: AdaptiveOptions,
        selected: &[u32],
    ) -> Result<AdaptiveRefiner> {
        let Refiner {
            options,
            mut levels,
            mut fvar,
            ..
        } = self;
        for channel in &mut fvar {
            channel.truncate(1);
        }
        levels.truncate(1);
        let scheme = options.scheme;
        let reg = regular_face_size(scheme);
        let base = &levels[0];
        let nonlinear = scheme != Scheme::Bilinear;
        let shallow = adaptive.secondary_level.min(adaptive.isolation_level);
        let irregular_faces = (0..base.face_count()).any(|f| base.face_vertices.count(f) != reg);
        let deepest = if nonlinear {
            adaptive.isolation_level
        } else {
            irregular_faces as u32
        };
        let mut more = FeatureMask::new(&adaptive, reg);
        // Face-varying features count only where a channel is not linear.
        more.fvar_features &= nonlinear
            && !fvar.is_empty()
            && options.fvar != crate::options::FVarLinearInterpolation::All;
        let less = if shallow < deepest {
            more.reduced(&adaptive)
        } else {
            more
        };
        let mut features = vec![base_features(base, scheme)];
        let mut steps = Vec::new();
        for i in 1..=deepest {
            let parent = levels.last().expect("base level");
            let mask = if i <= shallow { &more } else { &less };
            let channels: Vec<&ChannelLevel> = fvar
                .iter()
                .map(|c| c.last().expect("the parent level's channel"))
                .collect();
            let selects = |f: usize| {
                !parent.is_hole(f)
                    && if nonlinear {
                        face_is_selected(parent, &features[i as usize - 1], &channels, f, mask, reg)
                    } else {
                        parent.face_vertices.count(f) != reg
                    }
            };
            let mut selection = Selection::new(parent);
            let mut consider = |f: usize| {
                if selects(f) {
                    selection.select_face(parent, f);
                }
            };
            if i == 1 && !selected.is_empty() {
                selected.iter().for_each(|&f| consider(f as usize));
            } else if let Some(prev) = steps.last().filter(|s: &&SparseSplit| !s.triangles) {
                // Past the first level of the quad split, only the children
                // of selected faces can have features to isolate.
                select::children_of_selected(prev).for_each(consider);
                debug_assert!(
                    (0..parent.face_count()).all(|f| selection.face(f) || !selects(f)),
                    "a face outside the children of selected faces has features"
                );
            } else {
                (0..parent.face_count()).for_each(consider);
            }
            if selection.is_empty() {
                break;
            }
            let (split, child) = refine_sparse(
                parent,
                &options,
                selection,
                adaptive.order_vertices_from_faces_first,
            );
            features.push(child_features(
                parent,
                &features[i as usize - 1],
                &split,
                scheme,
            ));
            for channel in &mut fvar {
                let parent_fvar = channel.last().expect("base channel");
                let parents = Some(split.child_face_parent.as_slice());
                let child_fvar = crate::topology::fvar::refine(
                    crate::topology::Around::stored(parent),
                    &child,
                    &split,
                    parents,
                    parent_fvar,
                    &options,
                );
                channel.push(child_fvar);
            }
            steps.push(split);
            levels.push(child);
        }
        let refined = AdaptiveRefiner {
            rules: SchemeRules::new(&options),
            options,
            adaptive,
            levels,
            steps,
            features,
            fvar,
        };
        refined.check_unpaired_smooth()?;
        Ok(refined)
    }
}

/// Refuses a selected base face that does not exist
/// ([`Error::NoSuchElement`]).
pub(crate) fn check_selected_faces(base: &Level, selected: &[u32]) -> Result<()> {
    match selected.iter().find(|&&f| f as usize >= base.face_count()) {
        Some(&f) => Err(Error::NoSuchElement {
            element: Element::Face,
            index: f as usize,
            level: 0,
            count: base.face_count(),
        }),
        None => Ok(()),
    }
}

impl AdaptiveRefiner {
    /// Catmull-Clark's smooth masks need a vertex's faces and edges to pair
    /// up; a vertex named twice by a face can break that and be smooth, or
    /// become smooth as semi-sharp features decay. OpenSubdiv aborts on it
    /// (the osd engine refuses it): refuse it too. Vertices without a child
    /// are never interpolated from.
    fn check_unpaired_smooth(&self) -> Result<()> {
        if self.options.scheme != Scheme::Catmark {
            return Ok(());
        }
        for (l, step) in self.steps.iter().enumerate() {
            let (p, c) = (&self.levels[l], &self.levels[l + 1]);
            super::check_unpaired_smooth_step(p, c, step, l)?;
        }
        Ok(())
    }

    /// The levels, the splits between them and the features of every
    /// level's vertices (for the patch-table builder).
    pub(crate) fn parts(&self) -> (&[Level], &[SparseSplit], &[Vec<Features>]) {
        (&self.levels, &self.steps, &self.features)
    }

    /// The options the topology was built with.
    pub fn options(&self) -> &Options {
        &self.options
    }

    /// The adaptive options it was refined with.
    pub fn adaptive_options(&self) -> &AdaptiveOptions {
        &self.adaptive
    }

    /// Number of face-varying channels of the mesh.
    pub fn fvar_channel_count(&self) -> usize {
        self.fvar.len()
    }

    /// Face-varying channel `channel` at every level (for the patch-table
    /// builder).
    pub(crate) fn fvar_levels(&self, channel: usize) -> &[ChannelLevel] {
        &self.fvar[channel]
    }

    /// The deepest level refined: at most the isolation level, less when a
    /// level selected nothing.
    pub fn max_level(&self) -> u32 {
        (self.levels.len() - 1) as u32
    }

    fn internal_level(&self, level: u32) -> Result<&Level> {
        self.levels
            .get(level as usize)
            .ok_or_else(|| Error::NoSuchLevel {
                level,
                first: 0,
                last: self.max_level(),
            })
    }

    /// Element counts of `level`.
    pub fn level_counts(&self, level: u32) -> Result<LevelCounts> {
        Ok(super::queries::counts_of(self.internal_level(level)?))
    }

    /// The topology of `level` as OpenSubdiv reports it (every level of an
    /// adaptive refinement has full topology).
    pub fn level(&self, level: u32) -> Result<LevelTopology> {
        let l = self.internal_level(level)?;
        crate::alloc::guard(Some(level), || {
            let fvar = self
                .fvar
                .iter()
                .map(|channel| FVarTopology {
                    value_count: channel[level as usize].value_count(),
                    face_values: channel[level as usize].face_values().to_vec(),
                })
                .collect();
            Ok(super::queries::topology_of(l, true, fvar, Vec::new))
        })
    }

    /// The relations, rules and tags of `level` (`Far::TopologyLevel`'s
    /// relation and tag queries).
    pub fn relations(&self, level: u32) -> Result<LevelRelations> {
        let l = self.internal_level(level)?;
        let features = &self.features[level as usize];
        crate::alloc::guard(Some(level), || {
            let offsets = |r: &crate::topology::Relation| r.offsets_vec();
            let vertex = |f: &dyn Fn(usize) -> bool| (0..l.vertex_count).map(f).collect();
            let edge = |f: &dyn Fn(usize) -> bool| (0..l.edge_count()).map(f).collect();
            Ok(LevelRelations {
                face_edges: l.face_edges.to_vec(),
                edge_faces: l.edge_faces.members.to_vec(),
                edge_face_offsets: offsets(&l.edge_faces),
                edge_face_local: l.edge_face_local.to_vec(),
                vertex_faces: l.vertex_faces.members.to_vec(),
                vertex_face_offsets: offsets(&l.vertex_faces),
                vertex_face_local: l.vertex_face_local.to_vec(),
                vertex_edges: l.vertex_edges.members.to_vec(),
                vertex_edge_offsets: offsets(&l.vertex_edges),
                vertex_edge_local: l.vertex_edge_local.to_vec(),
                vertex_rules: (0..l.vertex_count)
                    .map(|v| l.vertex_tag(v).rule())
                    .collect(),
                vertex_boundary: vertex(&|v| l.vertex_tag(v).boundary()),
                vertex_corner: vertex(&|v| l.vertex_faces.count(v) == 1),
                vertex_valence_regular: vertex(&|v| {
                    !features[v].xordinary || l.vertex_faces.count(v) == 1
                }),
                vertex_non_manifold: vertex(&|v| l.vertex_tag(v).non_manifold()),
                vertex_inf_sharp: vertex(&|v| l.vertex_tag(v).inf_sharp()),
                vertex_semi_sharp: vertex(&|v| l.vertex_tag(v).semi_sharp()),
                edge_non_manifold: edge(&|e| l.edge_tag(e).non_manifold()),
                edge_boundary: edge(&|e| l.edge_tag(e).boundary()),
                edge_inf_sharp: edge(&|e| l.edge_tag(e).inf_sharp()),
                edge_semi_sharp: edge(&|e| l.edge_tag(e).semi_sharp()),
            })
        })
    }

    /// How the components of `level` map to those of `level + 1`, with
    /// [`crate::INVALID_INDEX`] for the children not created
    /// (`TopologyLevel::GetFaceChildFaces` and friends).
    pub fn child_maps(&self, level: u32) -> Result<ChildMaps> {
        let s = self.steps.get(level as usize).ok_or(Error::NoSuchLevel {
            level,
            first: 0,
            last: self.max_level().saturating_sub(1),
        })?;
        let parent = &self.levels[level as usize];
        let offsets = parent.face_vertices.offsets_vec();
        let face_offsets = if s.triangles {
            (0..=parent.face_count() as u32).map(|f| 4 * f).collect()
        } else {
            offsets.clone()
        };
        Ok(ChildMaps {
            face_child_faces: s.face_child_faces.to_vec(),
            face_child_face_offsets: face_offsets,
            face_child_edges: s.face_child_edges.to_vec(),
            face_child_edge_offsets: offsets,
            edge_child_edges: s.edge_child_edges.to_vec(),
            // Loop's split has no face points: every one is invalid.
            face_child_vertex: if s.triangles {
                vec![crate::INVALID_INDEX; parent.face_count()]
            } else {
                s.face_child_vertex.to_vec()
            },
            edge_child_vertex: s.edge_child_vertex.to_vec(),
            vertex_child_vertex: s.vertex_child_vertex.to_vec(),
            child_face_parent_face: s.child_face_parent.to_vec(),
        })
    }

    /// Every level with what [`crate::compare::compare_adaptive`] compares:
    /// topology, relations, child maps and the positions interpolated from
    /// `base` (the base level's, one per vertex) level by level in `f64`.
    pub fn adaptive_levels(&self, base: &[DVec3]) -> Result<Vec<AdaptiveLevel>> {
        let positions = self.refine_positions(base)?;
        (0..=self.max_level())
            .zip(positions)
            .map(|(level, positions)| {
                Ok(AdaptiveLevel {
                    topology: self.level(level)?,
                    relations: self.relations(level)?,
                    child_maps: match level < self.max_level() {
                        true => Some(self.child_maps(level)?),
                        false => None,
                    },
                    positions,
                })
            })
            .collect()
    }

    /// Whether base face or level face `f` of `level` was selected for
    /// refinement into the next level (its children are complete).
    pub fn is_face_selected(&self, level: u32, f: usize) -> Result<bool> {
        let s = self.steps.get(level as usize).ok_or(Error::NoSuchLevel {
            level,
            first: 0,
            last: self.max_level().saturating_sub(1),
        })?;
        let count = self.levels[level as usize].face_count();
        if f >= count {
            return Err(Error::NoSuchElement {
                element: Element::Face,
                index: f,
                level,
                count,
            });
        }
        Ok(s.selection.face(f))
    }

    /// Whether vertex `v` of `level` is extraordinary (OpenSubdiv's
    /// `_xordinary` tag: `!TopologyLevel::IsVertexValenceRegular` except at
    /// corners).
    pub fn is_vertex_extraordinary(&self, level: u32, v: usize) -> Result<bool> {
        let features = self
            .features
            .get(level as usize)
            .ok_or(Error::NoSuchLevel {
                level,
                first: 0,
                last: self.max_level(),
            })?;
        features
            .get(v)
            .map(|f| f.xordinary)
            .ok_or(Error::NoSuchElement {
                element: Element::Vertex,
                index: v,
                level,
                count: features.len(),
            })
    }
}
