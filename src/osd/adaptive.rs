//! Feature-adaptive refinement (`Far::TopologyRefiner::RefineAdaptive`) and
//! the per-level queries it calls for: the parent-to-child maps of a level
//! ([`ChildMaps`]), its full relations ([`LevelRelations`]), and
//! `Far::PtexIndices` ([`PtexIndices`]).

use super::ERR_LEN;
use super::TopologyRefiner;
use super::ffi;
use super::shim::{ErrBuf, internal, to_i32};
use crate::alloc::try_vec;
use crate::compare::AdaptiveLevel;
use crate::error::{Element, Error, LevelRefusal, Result};
use crate::options::{AdaptiveOptions, MAX_LEVEL};
use crate::output::{ChildMaps, INVALID_INDEX, LevelRelations};
use crate::ptex::{PtexAdjacency, PtexIndices};
use crate::rules::Rule;
use glam::DVec3;

/// The deepest secondary level: OpenSubdiv stores it in 4 bits.
const MAX_SECONDARY_LEVEL: u32 = 15;

/// An output buffer of `n` `i32`s and its description for the shim.
fn ibuf(v: &mut [i32]) -> ffi::sdv_ibuf {
    ffi::sdv_ibuf {
        data: v.as_mut_ptr(),
        cap: v.len(),
    }
}

fn bbuf(v: &mut [u8]) -> ffi::sdv_bbuf {
    ffi::sdv_bbuf {
        data: v.as_mut_ptr(),
        cap: v.len(),
    }
}

/// OpenSubdiv's index (-1 for none) as the crate's ([`INVALID_INDEX`]).
fn index(i: i32) -> u32 {
    if i < 0 { INVALID_INDEX } else { i as u32 }
}

/// Offsets (a leading 0 and running sums) from per-element counts.
fn offsets(counts: &[i32]) -> Vec<u32> {
    let mut out = Vec::with_capacity(counts.len() + 1);
    let mut acc = 0u32;
    out.push(0);
    for &c in counts {
        acc += c.max(0) as u32;
        out.push(acc);
    }
    out
}

fn local(v: Vec<i32>) -> Vec<u16> {
    v.into_iter()
        .map(|i| i.clamp(0, u16::MAX as i32) as u16)
        .collect()
}

impl TopologyRefiner {
    /// Refines adaptively (`Far::TopologyRefiner::RefineAdaptive`): only the
    /// faces around features a regular patch cannot represent are refined,
    /// level by level down to `options.isolation_level`, with every field of
    /// `options` passed on. `selected_faces` restricts the first level's
    /// selection to those base faces; empty means every face (as in
    /// OpenSubdiv). Every level, the last included, has full topology.
    ///
    /// OpenSubdiv stops as soon as a level selects nothing, so
    /// [`TopologyRefiner::max_level`] can be below the isolation level, and
    /// 0 (a mesh without features). Under the bilinear scheme only
    /// irregular (non-quad) faces are refined, one level, whatever the
    /// isolation level. Hole faces are never selected.
    ///
    /// Refused before OpenSubdiv sees anything: a refiner already refined
    /// (uniformly or adaptively: [`Error::AlreadyRefined`]), an isolation
    /// level above [`MAX_LEVEL`] or a secondary level above 15
    /// ([`Error::Level`]), a base level whose first uniform level would not
    /// fit (as [`crate::check_level`] at level 1, an upper bound of the first
    /// adaptive level), a selected face out of range
    /// ([`Error::NoSuchElement`]).
    ///
    /// ```
    /// use subdiv::{osd, shapes, AdaptiveOptions, Options};
    /// let mut refiner = osd::TopologyRefiner::new(&shapes::cube(), &Options::default())?;
    /// refiner.refine_adaptive(AdaptiveOptions::new(1), &[])?;
    /// // Every cube vertex is extraordinary: level 1 is whole.
    /// assert_eq!(refiner.level_counts(1)?.faces, 24);
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn refine_adaptive(
        &mut self,
        options: AdaptiveOptions,
        selected_faces: &[u32],
    ) -> Result<()> {
        // As OpenSubdiv: refused once levels exist (a uniform refinement to
        // level 0, or an adaptive one that selected nothing, leaves none).
        if self.max_level() > 0 {
            return Err(Error::AlreadyRefined {
                level: self.max_level(),
            });
        }
        if options.isolation_level > MAX_LEVEL {
            return Err(Error::Level {
                level: options.isolation_level,
                reason: LevelRefusal::TooDeep { max: MAX_LEVEL },
            });
        }
        if options.secondary_level > MAX_SECONDARY_LEVEL {
            return Err(Error::Level {
                level: options.secondary_level,
                reason: LevelRefusal::TooDeep {
                    max: MAX_SECONDARY_LEVEL,
                },
            });
        }
        // The first adaptive level is at most the uniform level 1 (all faces
        // selected); deeper levels grow with the features, not the mesh, so
        // the uniform estimate of a deeper level would refuse meshes that
        // adaptive refinement handles.
        crate::limits::check_level_counts(
            self.base_faces,
            self.base_corners,
            self.options.scheme,
            1,
        )?;
        if let Some(&face) = selected_faces
            .iter()
            .find(|&&f| f as usize >= self.base_faces)
        {
            return Err(Error::NoSuchElement {
                element: Element::Face,
                index: face as usize,
                level: 0,
                count: self.base_faces,
            });
        }
        let faces: Vec<i32> = selected_faces.iter().map(|&f| f as i32).collect();
        let opts = ffi::sdv_adaptive_options {
            isolation_level: options.isolation_level as i32,
            secondary_level: options.secondary_level as i32,
            single_crease_patch: options.use_single_crease_patch as i32,
            inf_sharp_patch: options.use_inf_sharp_patch as i32,
            consider_fvar_channels: options.consider_fvar_channels as i32,
            faces_first: options.order_vertices_from_faces_first as i32,
        };
        let mut err = ErrBuf::new();
        let r = self.raw.as_ptr();
        // SAFETY: `raw` is live and uniquely borrowed; `faces` holds
        // `faces.len()` indices, each checked in range above (and again by
        // the shim).
        err.run(|e| unsafe {
            ffi::sdv_refiner_refine_adaptive(r, &opts, faces.as_ptr(), faces.len(), e, ERR_LEN)
        })?;
        self.adaptive = Some(options);
        self.uniform = None;
        Ok(())
    }

    /// Refuses a level without a next one.
    fn check_parent_level(&self, level: u32) -> Result<()> {
        if level >= self.max_level() {
            return Err(Error::NoSuchLevel {
                level,
                first: 0,
                last: self.max_level().saturating_sub(1),
            });
        }
        Ok(())
    }

    /// How the components of `level` map to those of `level + 1`
    /// (`Far::TopologyLevel`'s child queries on `level`, and
    /// `GetFaceParentFace` on `level + 1`), for `level < max_level()`,
    /// uniform or adaptive. A child that sparse refinement did not create is
    /// [`INVALID_INDEX`]; under Loop every face child vertex is.
    pub fn child_maps(&self, level: u32) -> Result<ChildMaps> {
        self.check_parent_level(level)?;
        crate::alloc::guard(Some(level), || {
            let parent = self.level_counts(level)?;
            let child = self.level_counts(level + 1)?;
            let r = self.raw.as_ptr();
            let l = level as i32;
            let mut err = ErrBuf::new();
            let (mut n_faces, mut n_edges) = (0i32, 0i32);
            // SAFETY: `raw` is live; both outputs are valid.
            err.run(|e| unsafe {
                ffi::sdv_level_child_sizes(r, l, &mut n_faces, &mut n_edges, e, ERR_LEN)
            })?;
            let mut face_child_face_counts = try_vec(0i32, parent.faces)?;
            let mut face_child_faces = try_vec(0i32, n_faces.max(0) as usize)?;
            let mut face_child_edge_counts = try_vec(0i32, parent.faces)?;
            let mut face_child_edges = try_vec(0i32, n_edges.max(0) as usize)?;
            let mut edge_child_edges = try_vec(0i32, 2 * parent.edges)?;
            let mut face_child_vertex = try_vec(0i32, parent.faces)?;
            let mut edge_child_vertex = try_vec(0i32, parent.edges)?;
            let mut vertex_child_vertex = try_vec(0i32, parent.vertices)?;
            let mut child_face_parent_face = try_vec(0i32, child.faces)?;
            let out = ffi::sdv_child_maps {
                face_child_face_counts: ibuf(&mut face_child_face_counts),
                face_child_faces: ibuf(&mut face_child_faces),
                face_child_edge_counts: ibuf(&mut face_child_edge_counts),
                face_child_edges: ibuf(&mut face_child_edges),
                edge_child_edges: ibuf(&mut edge_child_edges),
                face_child_vertex: ibuf(&mut face_child_vertex),
                edge_child_vertex: ibuf(&mut edge_child_vertex),
                vertex_child_vertex: ibuf(&mut vertex_child_vertex),
                child_face_parent_face: ibuf(&mut child_face_parent_face),
            };
            // SAFETY: every buffer of `out` points into a Vec above with its
            // true length as capacity; the shim checks each against its counts.
            err.run(|e| unsafe { ffi::sdv_level_child_maps(r, l, &out, e, ERR_LEN) })?;
            let map = |v: Vec<i32>| v.into_iter().map(index).collect::<Vec<u32>>();
            Ok(ChildMaps {
                face_child_face_offsets: offsets(&face_child_face_counts),
                face_child_faces: map(face_child_faces),
                face_child_edge_offsets: offsets(&face_child_edge_counts),
                face_child_edges: map(face_child_edges),
                edge_child_edges: edge_child_edges
                    .chunks_exact(2)
                    .map(|c| [index(c[0]), index(c[1])])
                    .collect(),
                face_child_vertex: map(face_child_vertex),
                edge_child_vertex: map(edge_child_vertex),
                vertex_child_vertex: map(vertex_child_vertex),
                child_face_parent_face: map(child_face_parent_face),
            })
        })
    }

    /// The relations of `level` (`Far::TopologyLevel`'s relation queries
    /// and vertex and edge tags). Needs a level with full topology: every
    /// level but a uniform last level refined without
    /// `full_topology_in_last_level` ([`Error::NoFullTopology`]).
    pub fn relations(&self, level: u32) -> Result<LevelRelations> {
        crate::alloc::guard(Some(level), || {
            let counts = self.level_counts(level)?;
            if !counts.full_topology {
                return Err(Error::NoFullTopology { level });
            }
            let r = self.raw.as_ptr();
            let l = level as i32;
            let mut err = ErrBuf::new();
            let (mut ef, mut vf, mut ve) = (0i32, 0i32, 0i32);
            // SAFETY: `raw` is live; the outputs are valid.
            err.run(|e| unsafe {
                ffi::sdv_level_relation_sizes(r, l, &mut ef, &mut vf, &mut ve, e, ERR_LEN)
            })?;
            let (ef, vf, ve) = (ef.max(0) as usize, vf.max(0) as usize, ve.max(0) as usize);
            let mut face_edges = try_vec(0i32, counts.face_vertices)?;
            let mut edge_face_counts = try_vec(0i32, counts.edges)?;
            let mut edge_faces = try_vec(0i32, ef)?;
            let mut edge_face_local = try_vec(0i32, ef)?;
            let mut vertex_face_counts = try_vec(0i32, counts.vertices)?;
            let mut vertex_faces = try_vec(0i32, vf)?;
            let mut vertex_face_local = try_vec(0i32, vf)?;
            let mut vertex_edge_counts = try_vec(0i32, counts.vertices)?;
            let mut vertex_edges = try_vec(0i32, ve)?;
            let mut vertex_edge_local = try_vec(0i32, ve)?;
            let mut vertex_rule = try_vec(0i32, counts.vertices)?;
            let mut vertex_flags = try_vec(0u8, counts.vertices)?;
            let mut edge_flags = try_vec(0u8, counts.edges)?;
            let out = ffi::sdv_relations {
                face_edges: ibuf(&mut face_edges),
                edge_face_counts: ibuf(&mut edge_face_counts),
                edge_faces: ibuf(&mut edge_faces),
                edge_face_local: ibuf(&mut edge_face_local),
                vertex_face_counts: ibuf(&mut vertex_face_counts),
                vertex_faces: ibuf(&mut vertex_faces),
                vertex_face_local: ibuf(&mut vertex_face_local),
                vertex_edge_counts: ibuf(&mut vertex_edge_counts),
                vertex_edges: ibuf(&mut vertex_edges),
                vertex_edge_local: ibuf(&mut vertex_edge_local),
                vertex_rule: ibuf(&mut vertex_rule),
                vertex_flags: bbuf(&mut vertex_flags),
                edge_flags: bbuf(&mut edge_flags),
            };
            // SAFETY: every buffer of `out` points into a Vec above with its
            // true length as capacity; the shim checks each against its counts.
            err.run(|e| unsafe { ffi::sdv_level_relations(r, l, &out, e, ERR_LEN) })?;
            let vertex_rules = vertex_rule
                .iter()
                .map(|&code| match code {
                    ffi::SDV_RULE_SMOOTH => Ok(Rule::Smooth),
                    ffi::SDV_RULE_DART => Ok(Rule::Dart),
                    ffi::SDV_RULE_CREASE => Ok(Rule::Crease),
                    ffi::SDV_RULE_CORNER => Ok(Rule::Corner),
                    _ => Err(internal("OpenSubdiv gave a vertex no rule")),
                })
                .collect::<Result<Vec<Rule>>>()?;
            let flags = |v: &[u8], bit: i32| v.iter().map(|&f| f as i32 & bit != 0).collect();
            let ids = |v: Vec<i32>| v.into_iter().map(index).collect::<Vec<u32>>();
            Ok(LevelRelations {
                face_edges: ids(face_edges),
                edge_face_offsets: offsets(&edge_face_counts),
                edge_faces: ids(edge_faces),
                edge_face_local: local(edge_face_local),
                vertex_face_offsets: offsets(&vertex_face_counts),
                vertex_faces: ids(vertex_faces),
                vertex_face_local: local(vertex_face_local),
                vertex_edge_offsets: offsets(&vertex_edge_counts),
                vertex_edges: ids(vertex_edges),
                vertex_edge_local: local(vertex_edge_local),
                vertex_rules,
                vertex_boundary: flags(&vertex_flags, ffi::SDV_VTX_BOUNDARY as i32),
                vertex_corner: flags(&vertex_flags, ffi::SDV_VTX_CORNER as i32),
                vertex_valence_regular: flags(&vertex_flags, ffi::SDV_VTX_VALENCE_REGULAR as i32),
                vertex_non_manifold: flags(&vertex_flags, ffi::SDV_VTX_NON_MANIFOLD as i32),
                vertex_inf_sharp: flags(&vertex_flags, ffi::SDV_VTX_INF_SHARP as i32),
                vertex_semi_sharp: flags(&vertex_flags, ffi::SDV_VTX_SEMI_SHARP as i32),
                edge_non_manifold: flags(&edge_flags, ffi::SDV_EDGE_NON_MANIFOLD as i32),
                edge_boundary: flags(&edge_flags, ffi::SDV_EDGE_BOUNDARY as i32),
                edge_inf_sharp: flags(&edge_flags, ffi::SDV_EDGE_INF_SHARP as i32),
                edge_semi_sharp: flags(&edge_flags, ffi::SDV_EDGE_SEMI_SHARP as i32),
            })
        })
    }

    /// Every level with what [`crate::compare::compare_adaptive`] compares:
    /// topology (face-varying channels included), relations, child maps and
    /// the positions interpolated from `base` (the base level's, one per
    /// vertex) level by level in `f64`. Every level needs full topology (as
    /// after [`TopologyRefiner::refine_adaptive`]; else
    /// [`Error::NoFullTopology`]).
    pub fn adaptive_levels(&self, base: &[DVec3]) -> Result<Vec<AdaptiveLevel>> {
        let mut flat: Vec<f64> = base.iter().flat_map(|p| p.to_array()).collect();
        let mut out = Vec::new();
        for level in 0..=self.max_level() {
            if level > 0 {
                flat = self.interpolate(level, 3, &flat)?;
            }
            out.push(AdaptiveLevel {
                topology: self.level(level)?,
                relations: self.relations(level)?,
                child_maps: match level < self.max_level() {
                    true => Some(self.child_maps(level)?),
                    false => None,
                },
                positions: flat
                    .chunks_exact(3)
                    .map(|c| DVec3::new(c[0], c[1], c[2]))
                    .collect(),
            });
        }
        Ok(out)
    }

    /// OpenSubdiv's ptex faces of the base mesh (`Far::PtexIndices`: the
    /// number of ptex faces and the first of every base face).
    pub fn ptex_indices(&self) -> Result<PtexIndices> {
        self.ptex().cloned()
    }

    /// The ptex indices, read from OpenSubdiv once (the base level never
    /// changes).
    fn ptex(&self) -> Result<&PtexIndices> {
        if let Some(p) = self.ptex.get() {
            return Ok(p);
        }
        let mut ids = try_vec(0i32, self.base_faces + 1)?;
        let mut err = ErrBuf::new();
        let r = self.raw.as_ptr();
        // SAFETY: `raw` is live; `ids` holds `ids.len()` elements, which the
        // shim checks against the base face count plus one.
        err.run(|e| unsafe { ffi::sdv_ptex_face_ids(r, ids.as_mut_ptr(), ids.len(), e, ERR_LEN) })?;
        let ptex = PtexIndices::from_first(
            ids.into_iter().map(|i| i.max(0) as u32).collect(),
            self.options.scheme,
        );
        // Another thread may have set it meanwhile: the same values.
        Ok(self.ptex.get_or_init(|| ptex))
    }

    /// OpenSubdiv's ptex adjacency of ptex face `quadrant` of base face
    /// `face` (`Far::PtexIndices::GetAdjacency`): `quadrant` is 0 for a
    /// regular face, `0..n` for an irregular face of `n` corners; anything
    /// else is refused ([`Error::NoSuchElement`]) before OpenSubdiv, which
    /// only asserts it, sees it.
    pub fn ptex_adjacency(&self, face: usize, quadrant: usize) -> Result<PtexAdjacency> {
        if face >= self.base_faces {
            return Err(Error::NoSuchElement {
                element: Element::Face,
                index: face,
                level: 0,
                count: self.base_faces,
            });
        }
        let ptex = self.ptex()?;
        let count = ptex.face_ptex_count(face)?;
        if quadrant >= count {
            return Err(Error::NoSuchElement {
                element: Element::Face,
                index: ptex.face_id(face)? as usize + quadrant,
                level: 0,
                count: ptex.num_faces(),
            });
        }
        let (mut faces, mut edges) = ([0i32; 4], [0i32; 4]);
        let mut err = ErrBuf::new();
        let r = self.raw.as_ptr();
        let (f, q) = (to_i32(face, "faces")?, to_i32(quadrant, "ptex faces")?);
        // SAFETY: `raw` is live; both outputs hold four elements.
        err.run(|e| unsafe {
            ffi::sdv_ptex_adjacency(r, f, q, faces.as_mut_ptr(), edges.as_mut_ptr(), e, ERR_LEN)
        })?;
        Ok(PtexAdjacency {
            faces: faces.map(index),
            edges: edges.map(|e| e.max(0) as u32),
        })
    }
}
