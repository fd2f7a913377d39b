//! `Far::PatchMap`: which patch of a table covers a location (ptex face, u,
//! v), found the way OpenSubdiv's quadtree finds it, so that locations on
//! the edges between patches go to the same patch.
//!
//! A ptex face is split into quadrants level by level, each level halving
//! the square: the quadrant of a location is (u ≥ ½, v ≥ ½) of what is left
//! of it, u and v moved into the quadrant. Under Loop the halves are
//! triangles: the corners (u ≥ ½ first, then v ≥ ½) and the middle
//! triangle, which is rotated by 180° and splits the other way round. A
//! patch sits at the quadrant path its parameterization names; the search
//! follows the location's path down until a patch sits there.

use super::{PatchHandle, PatchParam, PatchTable};
use std::collections::BTreeMap;

/// No index.
const NONE: u32 = u32::MAX;

/// A quadrant of a node of the quadtree: the patch sitting there and the
/// node of its sub-quadrants, each if any (`NONE`).
#[derive(Debug, Clone, Copy)]
struct Child {
    array: u32,
    patch: u32,
    node: u32,
}

const EMPTY: Child = Child {
    array: NONE,
    patch: NONE,
    node: NONE,
};

/// Locates (ptex face, u, v) in a patch table (`Far::PatchMap`).
///
/// ```
/// use subdiv::patches::{PatchArray, PatchHandle, PatchMap, PatchParam, PatchTable, PatchType};
/// // One ptex face split into four depth-1 patches, (u, v) = (col, row).
/// let params = (0..4u32).map(|k| PatchParam { field0: 0, field1: ((k % 2) << 22) | ((k / 2) << 12) | 1 });
/// let table = PatchTable {
///     arrays: vec![PatchArray {
///         patch_type: PatchType::Quads,
///         control_vertices: vec![0; 16],
///         params: params.collect(),
///         sharpness: vec![0.0; 4],
///         varying_vertices: Vec::new(),
///     }],
///     ptex_faces: 1,
///     varying_patch_type: PatchType::Quads,
///     ..PatchTable::default()
/// };
/// let map = PatchMap::new(&table);
/// assert_eq!(map.find_patch(0, 0.7, 0.2), Some(PatchHandle { array: 0, patch: 1 }));
/// // On an edge between patches: the upper one, as OpenSubdiv decides.
/// assert_eq!(map.find_patch(0, 0.5, 0.5), Some(PatchHandle { array: 0, patch: 3 }));
/// assert_eq!(map.find_patch(1, 0.5, 0.5), None); // no such ptex face
/// ```
#[derive(Debug, Clone)]
pub struct PatchMap {
    triangular: bool,
    max_depth: u32,
    /// The quadtree below the ptex faces: each node's four quadrants.
    nodes: Vec<[Child; 4]>,
    /// Per ptex face: whether its first quadrant is covered (OpenSubdiv's
    /// test for a face with patches), the patch covering all of it, and
    /// the node of its quadrants (`NONE`: none). Dense over the faces up
    /// to a bound the number of patches sets ([`PatchMap::new`]).
    roots: Vec<Root>,
    /// The roots of faces past `roots` (face ids far beyond the table's
    /// patches: a table built by hand), by face.
    far_roots: BTreeMap<u32, Root>,
}

/// A ptex face's entry of the map ([`PatchMap`]'s `roots`): 16 bytes, so
/// that the roots of many faces share the cache.
#[derive(Debug, Clone, Copy)]
struct Root {
    /// Whether its first quadrant is covered.
    covered: bool,
    /// The patch covering all of it, if any.
    patch: Found,
    /// The node of its quadrants (`NONE`: none).
    node: u32,
}

/// A face without patches.
const NO_ROOT: Root = Root {
    covered: false,
    patch: Found::NONE,
    node: NONE,
};

/// A patch [`PatchMap::find`] found, or none: its array and its index in
/// the array packed into one word (`u64::MAX` for none), which a call
/// returns in a register. (An `Option<PatchHandle>` is three words,
/// returned through memory and read back as wider loads than it was
/// written with: a store-forwarding stall on every location evaluated.)
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Found(u64);

impl Found {
    /// No patch.
    pub(crate) const NONE: Found = Found(u64::MAX);

    /// Patch `patch` of array `array` (neither `u32::MAX`, which the map
    /// never stores).
    #[inline]
    fn new(array: u32, patch: u32) -> Found {
        Found(u64::from(array) << 32 | u64::from(patch))
    }

    /// Its array and its index in the array (both `u32::MAX` for none).
    #[inline]
    fn parts(self) -> (u32, u32) {
        ((self.0 >> 32) as u32, self.0 as u32)
    }

    /// The patch, or `None`.
    #[inline]
    pub(crate) fn handle(self) -> Option<PatchHandle> {
        let (array, patch) = self.parts();
        (self != Found::NONE).then_some(PatchHandle {
            array: array as usize,
            patch: patch as usize,
        })
    }
}

/// The quadrant of (`u`, `v`) in a square halved at `median`, and (`u`,
/// `v`) moved into it.
fn quad_quadrant(median: f64, u: &mut f64, v: &mut f64) -> u64 {
    let right = *u >= median;
    if right {
        *u -= median;
    }
    let top = *v >= median;
    if top {
        *v -= median;
    }
    (u64::from(top) << 1) | u64::from(right)
}

/// The quadrant of (`u`, `v`) in a triangle halved at `median` (`rotated`:
/// the triangle is upside down), and (`u`, `v`) moved into it.
fn tri_quadrant(median: f64, u: &mut f64, v: &mut f64, rotated: &mut bool) -> u64 {
    if !*rotated {
        if *u >= median {
            *u -= median;
            1
        } else if *v >= median {
            *v -= median;
            2
        } else if *u + *v >= median {
            *rotated = true;
            3
        } else {
            0
        }
    } else if *u < median {
        *v -= median;
        1
    } else if *v < median {
        *u -= median;
        2
    } else {
        *u -= median;
        *v -= median;
        if *u + *v < median {
            *rotated = false;
            3
        } else {
            0
        }
    }
}

/// A point inside the triangular patch `p`, in its ptex face: its
/// parameter point (¼, ¼) mapped out of the patch.
fn triangle_interior(p: PatchParam) -> (f64, f64) {
    let depth = p.depth();
    let fraction = 1.0 / f64::from(1u32 << depth.saturating_sub(u32::from(p.non_quad_root())));
    let (pu, pv) = (f64::from(p.u()), f64::from(p.v()));
    if p.u() + p.v() >= 1 << depth {
        let corner = f64::from(1u32 << depth);
        (
            (corner - pu - 0.25) * fraction,
            (corner - pv - 0.25) * fraction,
        )
    } else {
        ((0.25 + pu) * fraction, (0.25 + pv) * fraction)
    }
}

impl PatchMap {
    /// The map of `table`'s patches.
    pub fn new(table: &PatchTable) -> PatchMap {
        let triangular = table.varying_patch_type.control_vertices() == 3;
        let patches: usize = table.arrays.iter().map(|a| a.params.len()).sum();
        // Dense roots for the faces a table's patches can name (every face
        // of a table a factory built), never more than the patches bound:
        // a hand-made table's word may name face 2^28.
        let last = table
            .arrays
            .iter()
            .flat_map(|a| &a.params)
            .map(|p| p.face_id() as usize + 1)
            .max()
            .unwrap_or(0);
        let dense = last.max(table.ptex_faces).min(4 * patches + 64);
        let mut map = PatchMap {
            triangular,
            max_depth: 0,
            nodes: Vec::with_capacity(patches / 2),
            roots: vec![NO_ROOT; dense],
            far_roots: BTreeMap::new(),
        };
        for (a, array) in table.arrays.iter().enumerate() {
            for (k, &p) in array.params.iter().enumerate() {
                let found = Found::new(a as u32, k as u32);
                let (depth, root) = (p.depth(), u32::from(p.non_quad_root()));
                map.max_depth = map.max_depth.max(depth);
                let levels = depth.saturating_sub(root);
                let mut path = 0u64;
                if triangular {
                    let (mut u, mut v) = triangle_interior(p);
                    let (mut median, mut rotated) = (0.5, false);
                    for _ in 0..levels {
                        path = path << 2 | tri_quadrant(median, &mut u, &mut v, &mut rotated);
                        median *= 0.5;
                    }
                } else {
                    for j in root + 1..=depth {
                        let u_bit = u64::from((p.u() >> (depth - j)) & 1);
                        let v_bit = u64::from((p.v() >> (depth - j)) & 1);
                        path = path << 2 | (v_bit << 1) | u_bit;
                    }
                }
                // A root patch fills every quadrant; any other covers the
                // first one when its path starts there.
                let face = p.face_id() as usize;
                let root = map.root_mut(face);
                if levels == 0 || path >> (2 * (levels - 1)) == 0 {
                    root.covered = true;
                }
                if levels == 0 {
                    root.patch = found;
                } else {
                    map.insert(face, levels, path, found);
                }
            }
        }
        map
    }

    /// The entry of ptex face `face`, made when it has none.
    fn root_mut(&mut self, face: usize) -> &mut Root {
        if face < self.roots.len() {
            &mut self.roots[face]
        } else {
            self.far_roots.entry(face as u32).or_insert(NO_ROOT)
        }
    }

    /// A new node without quadrants, its index.
    fn new_node(&mut self) -> u32 {
        self.nodes.push([EMPTY; 4]);
        (self.nodes.len() - 1) as u32
    }

    /// Puts `found` at quadrant path `path` (`levels` levels deep) of ptex
    /// face `face`, in place of any patch there before.
    fn insert(&mut self, face: usize, levels: u32, path: u64, found: Found) {
        let mut node = self.root_mut(face).node;
        if node == NONE {
            node = self.new_node();
            self.root_mut(face).node = node;
        }
        for level in 1..=levels {
            let q = ((path >> (2 * (levels - level))) & 3) as usize;
            if level == levels {
                let child = &mut self.nodes[node as usize][q];
                (child.array, child.patch) = found.parts();
                return;
            }
            let next = self.nodes[node as usize][q].node;
            node = if next == NONE {
                let n = self.new_node();
                self.nodes[node as usize][q].node = n;
                n
            } else {
                next
            };
        }
    }

    /// The patch covering (`u`, `v`) of ptex face `face`
    /// (`PatchMap::FindPatch`), or `None` where there is none (a hole, a
    /// face the table has no patches of). Locations on the edge between
    /// two patches go to the one on the side of larger u (then v), as
    /// OpenSubdiv's quadtree sends them; u and v outside [0, 1] find
    /// nothing.
    pub fn find_patch(&self, face: u32, u: f64, v: f64) -> Option<PatchHandle> {
        self.find(face, u, v).handle()
    }

    /// [`PatchMap::find_patch`], the patch packed into one word.
    #[inline]
    pub(crate) fn find(&self, face: u32, u: f64, v: f64) -> Found {
        if !(0.0..=1.0).contains(&u) || !(0.0..=1.0).contains(&v) {
            return Found::NONE;
        }
        let root = match self.roots.get(face as usize) {
            Some(root) => Some(root),
            None => self.far_roots.get(&face),
        };
        let mut node = match root {
            Some(r) if r.covered && r.patch != Found::NONE => return r.patch,
            Some(r) if r.covered => r.node,
            _ => return Found::NONE,
        };
        let (mut u, mut v) = (u, v);
        let (mut median, mut rotated) = (0.5, false);
        for _ in 0..=self.max_depth {
            let Some(children) = self.nodes.get(node as usize) else {
                return Found::NONE;
            };
            let q = if self.triangular {
                tri_quadrant(median, &mut u, &mut v, &mut rotated)
            } else {
                quad_quadrant(median, &mut u, &mut v)
            };
            median *= 0.5;
            let child = children[q as usize];
            if child.patch != NONE {
                return Found::new(child.array, child.patch);
            }
            node = child.node;
        }
        Found::NONE
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::patches::{PatchArray, PatchType};

    /// A hand-made table whose patches name faces far past their number:
    /// the map stays small (no dense entry per face up to 2^28) and finds
    /// them all.
    #[test]
    fn faces_far_past_the_patches_are_found_without_a_dense_entry_each() {
        let (far, farther) = ((1u32 << 28) - 1, 1u32 << 27);
        // Depth-0 roots (field1 0) and one depth-1 patch in the first
        // quadrant (u = v = 0, depth 1) of `farther`.
        let params = vec![
            PatchParam {
                field0: far,
                field1: 0,
            },
            PatchParam {
                field0: 3,
                field1: 0,
            },
            PatchParam {
                field0: farther,
                field1: 1,
            },
        ];
        let table = PatchTable {
            arrays: vec![PatchArray {
                patch_type: PatchType::Regular,
                control_vertices: vec![0; 16 * params.len()],
                sharpness: vec![0.0; params.len()],
                params,
                varying_vertices: Vec::new(),
            }],
            ..PatchTable::default()
        };
        let map = PatchMap::new(&table);
        assert!(
            map.roots.len() <= 4 * 3 + 64,
            "{} dense roots",
            map.roots.len()
        );
        let handle = |patch| Some(PatchHandle { array: 0, patch });
        assert_eq!(map.find_patch(far, 0.5, 0.5), handle(0));
        assert_eq!(map.find_patch(3, 0.25, 0.75), handle(1));
        assert_eq!(map.find_patch(farther, 0.25, 0.25), handle(2));
        assert_eq!(map.find_patch(farther, 0.75, 0.75), None);
        assert_eq!(map.find_patch(4, 0.5, 0.5), None);
        assert_eq!(map.find_patch(far - 1, 0.5, 0.5), None);
    }
}
