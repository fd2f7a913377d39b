//! Where a patch lies: its [`PatchParam`] (`PatchBuilder::
//! ComputePatchParam`, the walk up to its base face), the ptex faces of the
//! base level and the table's maximum valence.

use super::Builder;
use crate::patches::PatchParam;
use crate::topology::Level;

impl Builder<'_> {
    /// `TopologyRefiner::GetMaxValence`: the base level's largest valence
    /// or face, then for each refined level OpenSubdiv's bound (at least
    /// the regular valence, and two more than the most faces at an edge of
    /// the parent, doubled for triangles) rather than the level's own.
    pub(super) fn max_valence(&self) -> usize {
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
    pub(super) fn ptex_first(&self) -> Vec<u32> {
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

    /// [`Builder::param`] through `walk`, which remembers the last face
    /// placed at each level: under the quad split (Catmull-Clark and
    /// bilinear), where a face's place is its parent's doubled plus its
    /// quadrant, siblings share their parent's walk (patches come face by
    /// face, siblings together). The same words as the walk up.
    pub(super) fn param_with(
        &self,
        walk: &mut QuadWalk,
        level: usize,
        f: usize,
        ptex: &[u32],
        regular: bool,
        boundary: u16,
    ) -> PatchParam {
        if self.reg != 4
            || level == 0
            || level >= MAX_DEPTH
            || self.steps[..level].iter().any(|s| s.triangles)
        {
            return self.param(level, f, ptex, regular, boundary);
        }
        let place = self.quad_place(walk, level, f);
        let transition = if level < self.max_level() {
            self.steps[level].face_transitional[f]
        } else {
            0
        };
        let mut ptex_face = ptex.get(place.base as usize).copied().unwrap_or(0);
        if place.irregular_base {
            ptex_face += place.first_child;
        }
        PatchParam::new(
            ptex_face,
            place.u as u16,
            place.v as u16,
            level as u16,
            place.irregular_base,
            boundary,
            u16::from(transition),
            regular,
        )
    }

    /// The place of face `f` of `level` (at least 1) under the quad split,
    /// from its parent's (remembered in `walk`, or placed first).
    fn quad_place(&self, walk: &mut QuadWalk, level: usize, f: usize) -> Place {
        if walk.last.len() < self.levels.len() {
            walk.last = vec![None; self.levels.len()];
        }
        // The chain of faces up to the first one remembered (or the base).
        let mut chain = [(0usize, 0usize); MAX_DEPTH];
        let mut depth = 0;
        let mut child = f;
        let mut i = level;
        let mut place = loop {
            if i == 0 {
                break Place {
                    base: child as u32,
                    irregular_base: self.levels[0].face_vertices.count(child) != self.reg,
                    first_child: 0,
                    u: 0,
                    v: 0,
                };
            }
            if let Some((face, p)) = walk.last[i]
                && face as usize == child
            {
                break p;
            }
            let parent = self.steps[i - 1].child_face_parent[child] as usize;
            chain[depth] = (child, parent);
            depth += 1;
            child = parent;
            i -= 1;
        };
        // Down again: each child's quadrant in its parent.
        for &(child, parent) in chain[..depth].iter().rev() {
            i += 1;
            let k = self
                .child_faces(i - 1, parent)
                .iter()
                .position(|&c| c as usize == child)
                .unwrap_or(0);
            place = if i == 1 && place.irregular_base {
                Place {
                    first_child: k as u32,
                    ..place
                }
            } else {
                let (du, dv) = QUADRANT[k & 3];
                Place {
                    u: 2 * place.u + du,
                    v: 2 * place.v + dv,
                    ..place
                }
            };
            walk.last[i] = Some((child as u32, place));
        }
        place
    }

    /// `PatchBuilder::ComputePatchParam`: the patch's place in its ptex
    /// face, found by walking up to its base face.
    pub(super) fn param(
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

/// The deepest walk [`Builder::param_with`] remembers (more than any
/// table's 10 levels).
const MAX_DEPTH: usize = 16;

/// The (u, v) offset of each quadrant of a quad split, by child.
const QUADRANT: [(u32, u32); 4] = [(0, 0), (1, 0), (1, 1), (0, 1)];

/// Where a face of the quad split lies: its base face (and, under a
/// non-quad base face, which of its children it descends from) and its
/// place in the ptex face at its own depth.
#[derive(Debug, Clone, Copy)]
struct Place {
    base: u32,
    irregular_base: bool,
    first_child: u32,
    u: u32,
    v: u32,
}

/// The last face placed at each level ([`Builder::param_with`]).
#[derive(Debug, Default)]
pub(super) struct QuadWalk {
    last: Vec<Option<(u32, Place)>>,
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
