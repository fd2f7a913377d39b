//! Patch tables of a uniformly refined topology
//! (`PatchTableBuilder::BuildUniformPolygons`): one array per level kept
//! (the last, or every refined level with `generate_all_levels`), one
//! linear patch per face that is not a hole — its vertices, numbered after
//! the base level's when `include_base_level_indices` — or two triangles
//! per quad with `triangulate_quads`, and the [`PatchParam`] that places
//! the face in its ptex face.

use super::fvar::Channel;
use super::{PatchArray, PatchOptions, PatchParam, PatchTable, PatchType};
use crate::error::Result;
use crate::options::Scheme;
use crate::refiner::Refiner;
use crate::topology::Level;

impl Refiner {
    /// The patch table of this uniformly refined topology
    /// (`Far::PatchTableFactory::Create` on a `RefineUniform`ed refiner):
    /// bilinear quads (`QUADS`) or triangles (`TRIANGLES`: Loop, or
    /// `triangulate_quads`) of the last level, or of every refined level
    /// with `generate_all_levels`, as OpenSubdiv 3.5 builds them — the same
    /// arrays, control vertices and [`PatchParam`] words. The options read
    /// are `generate_all_levels`, `include_base_level_indices`,
    /// `triangulate_quads` and, for face-varying patches (each face in the
    /// channel, with its parameter), `fvar_tables`, `fvar_channels` and
    /// `include_fvar_base_level_indices`.
    ///
    /// ```
    /// use subdiv::{patches::{PatchOptions, PatchType}, refiner::Refiner, shapes, Options, UniformOptions};
    /// let mut refiner = Refiner::new(&shapes::cube(), &Options::default())?;
    /// refiner.refine_uniform(UniformOptions::new(2))?;
    /// let table = refiner.patch_table(&PatchOptions::new())?;
    /// assert_eq!(table.arrays.len(), 1);
    /// assert_eq!(table.arrays[0].patch_type, PatchType::Quads);
    /// assert_eq!(table.arrays[0].len(), 6 * 16);
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn patch_table(&self, options: &PatchOptions) -> Result<PatchTable> {
        let requested = super::fvar::requested(options, self.fvar.len())?;
        crate::alloc::guard(None, || Ok(uniform_table(self, options, &requested)))
    }
}

/// [`Refiner::patch_table`]'s table, with face-varying patches for
/// `channels`.
fn uniform_table(r: &Refiner, options: &PatchOptions, channels: &[usize]) -> PatchTable {
    let levels = &r.levels;
    let scheme = r.options.scheme;
    let reg = if scheme == Scheme::Loop { 3 } else { 4 };
    let triangulate = options.triangulate_quads && reg == 4;
    let linear = if scheme == Scheme::Loop {
        PatchType::Triangles
    } else {
        PatchType::Quads
    };
    let patch_type = if triangulate {
        PatchType::Triangles
    } else {
        linear
    };
    let max = levels.len() - 1;
    let first = if options.generate_all_levels { 1 } else { max };
    let ptex = ptex_first(&levels[0], reg);
    let place = super::placement::Placement {
        levels,
        reg,
        ptex: &ptex,
    };
    let mut arrays = Vec::new();
    let mut offset = if options.include_base_level_indices {
        levels[0].vertex_count as u32
    } else {
        0
    };
    // Each face-varying channel, its values so far and the offset of the
    // current level's values.
    let mut fvar: Vec<(Channel, Vec<u32>, u32)> = channels
        .iter()
        .map(|&c| {
            let ch = Channel::new(c, &r.fvar[c], None);
            let first = if options.include_fvar_base_level_indices {
                ch.value_count(0) as u32
            } else {
                0
            };
            (ch, Vec::new(), first)
        })
        .collect();
    // An unrefined topology: one array of the base faces that OpenSubdiv
    // sizes but never fills (vertices 0, parameters 0); none when every
    // refined level is asked for.
    if max == 0 && first == 0 {
        let l = &levels[0];
        let n = (0..l.face_count()).filter(|&f| !l.is_hole(f)).count() * (1 + triangulate as usize);
        arrays.push(PatchArray {
            patch_type,
            control_vertices: vec![0; n * patch_type.control_vertices()],
            params: vec![PatchParam::default(); n],
            sharpness: vec![0.0; n],
            varying_vertices: Vec::new(),
        });
        for (_, values, _) in &mut fvar {
            values.resize(n * patch_type.control_vertices(), 0);
        }
    }
    for level in 1..=max {
        let l = &levels[level];
        if level >= first {
            let mut a = PatchArray {
                patch_type,
                control_vertices: Vec::new(),
                params: Vec::new(),
                sharpness: Vec::new(),
                varying_vertices: Vec::new(),
            };
            for f in (0..l.face_count()).filter(|&f| !l.is_hole(f)) {
                let verts = l.face_verts(f);
                a.control_vertices.extend(verts.iter().map(|&v| v + offset));
                let param = place.param(
                    level,
                    f,
                    |l, c| parent_of(&levels[l - 1], c, reg),
                    true,
                    0,
                    0,
                );
                a.params.push(param);
                for (ch, values, at) in &mut fvar {
                    values.extend(ch.face(l, level, f, *at));
                }
                if triangulate {
                    let n = a.control_vertices.len();
                    let (v0, v2) = (a.control_vertices[n - 4], a.control_vertices[n - 2]);
                    a.control_vertices.extend([v0, v2]);
                    a.params.push(param);
                    for (_, values, _) in &mut fvar {
                        let n = values.len();
                        let (v0, v2) = (values[n - 4], values[n - 2]);
                        values.extend([v0, v2]);
                    }
                }
            }
            a.sharpness = vec![0.0; a.params.len()];
            arrays.push(a);
        }
        if options.generate_all_levels {
            offset += l.vertex_count as u32;
            for (ch, _, at) in &mut fvar {
                *at += ch.value_count(level) as u32;
            }
        }
    }
    // Every patch's face-varying parameter is its own.
    let params: Vec<PatchParam> = arrays
        .iter()
        .flat_map(|a| a.params.iter().copied())
        .collect();
    let fvar_channels = fvar
        .into_iter()
        .map(|(ch, values, _)| Channel::finish(ch.channel, patch_type, values, params.clone()))
        .collect();
    PatchTable {
        arrays,
        fvar_channels,
        max_valence: max_valence(levels, reg),
        ptex_faces: *ptex.last().unwrap_or(&0) as usize,
        feature_adaptive: false,
        varying_patch_type: linear,
        ..PatchTable::default()
    }
}

/// The first ptex face of each base face, and the total last.
fn ptex_first(base: &Level, reg: usize) -> Vec<u32> {
    let mut first = Vec::with_capacity(base.face_count() + 1);
    let mut id = 0u32;
    for f in 0..base.face_count() {
        first.push(id);
        let n = base.face_vertices.count(f);
        id += if n == reg { 1 } else { n as u32 };
    }
    first.push(id);
    first
}

/// OpenSubdiv's bound on the valence of every level (see the adaptive
/// builder's): the base level's, then the regular valence and two more than
/// the most faces at a parent's edge (doubled for triangles).
fn max_valence(levels: &[Level], reg: usize) -> usize {
    let tri = reg == 3;
    levels[..levels.len() - 1]
        .iter()
        .fold(levels[0].max_valence, |bound, parent| {
            let edge = if tri {
                2 * parent.max_edge_faces
            } else {
                parent.max_edge_faces
            };
            bound.max(if tri { 6 } else { 4 }).max(2 + edge)
        })
}

/// The parent of child face `child` and its place among the parent's
/// children: uniform refinement numbers every face's children together, a
/// face of `n` corners having `n` (quads) or every triangle 4 (Loop).
fn parent_of(parent_level: &Level, child: usize, reg: usize) -> (usize, usize) {
    if reg == 3 {
        return (child / 4, child % 4);
    }
    let offsets = parent_level.face_vertices.offsets_slice();
    // The children of face p start at offsets[p]: find the last start at
    // or before the child.
    let p = offsets
        .partition_point(|&o| o as usize <= child)
        .saturating_sub(1);
    (p, child - offsets[p] as usize)
}
