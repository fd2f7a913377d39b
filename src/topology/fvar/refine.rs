//! A face-varying channel split into the next level, inheriting its parent's
//! topology rather than analysing it again — OpenSubdiv's
//! `Vtr::FVarRefinement` (`vtr/fvarRefinement.cpp`).

use super::{ChannelLevel, ValueTag};
use crate::options::{CreasingMethod, Options, Scheme};
use crate::output::INVALID_INDEX;
use crate::rules::crease;
use crate::topology::refine::sparse::SparseSplit;
use crate::topology::{Around, AroundBuf, Level, Split, Table};

/// How a refinement step numbers the children of its parent: uniformly
/// ([`Split`]: every child exists) or sparsely ([`SparseSplit`]: a child not
/// created is [`INVALID_INDEX`], and some that exist are incomplete). Read by
/// face-varying refinement and interpolation and by the refiner's masks
/// (`crate::refiner::Step`).
pub trait Children {
    /// Whether children may be missing or incomplete.
    const SPARSE: bool;
    /// The face point of parent face `f`.
    fn face_child(&self, f: usize) -> u32;
    /// The edge point of parent edge `e`.
    fn edge_child(&self, e: usize) -> u32;
    /// The vertex point of parent vertex `v`.
    fn vertex_child(&self, v: usize) -> u32;
    /// The half of parent edge `e` at its end `j`.
    fn edge_child_edge(&self, e: usize, j: usize) -> u32;
    /// Whether parent faces have face points (not under Loop).
    fn has_face_points(&self) -> bool;
    /// Whether child vertex `c` has its whole neighbourhood in the child.
    fn complete(&self, c: usize) -> bool;
    /// The child vertices of the parent's faces, edges and vertices: for
    /// each kind, the first child, how many children, and how many parents
    /// of that kind (each kind's children are consecutive).
    fn vertex_runs(&self, parent: &Level) -> [(u32, usize, usize); 3];
}

impl Children for Split {
    const SPARSE: bool = false;
    #[inline(always)]
    fn face_child(&self, f: usize) -> u32 {
        Split::face_child(self, f)
    }
    #[inline(always)]
    fn edge_child(&self, e: usize) -> u32 {
        Split::edge_child(self, e)
    }
    #[inline(always)]
    fn vertex_child(&self, v: usize) -> u32 {
        Split::vertex_child(self, v)
    }
    #[inline(always)]
    fn edge_child_edge(&self, e: usize, j: usize) -> u32 {
        Split::edge_child_edge(self, e, j)
    }
    #[inline(always)]
    fn has_face_points(&self) -> bool {
        Split::has_face_points(self)
    }
    #[inline(always)]
    fn complete(&self, _c: usize) -> bool {
        true
    }
    fn vertex_runs(&self, parent: &Level) -> [(u32, usize, usize); 3] {
        let nf = if self.has_face_points() {
            parent.face_count()
        } else {
            0
        };
        let (ne, nv) = (parent.edge_count(), parent.vertex_count);
        [
            (self.first_vertex_from_faces, nf, nf),
            (self.first_vertex_from_edges, ne, ne),
            (self.first_vertex_from_vertices, nv, nv),
        ]
    }
}

impl Children for SparseSplit {
    const SPARSE: bool = true;
    #[inline]
    fn face_child(&self, f: usize) -> u32 {
        self.face_child_vertex
            .get(f)
            .copied()
            .unwrap_or(INVALID_INDEX)
    }
    #[inline]
    fn edge_child(&self, e: usize) -> u32 {
        self.edge_child_vertex[e]
    }
    #[inline]
    fn vertex_child(&self, v: usize) -> u32 {
        self.vertex_child_vertex[v]
    }
    #[inline]
    fn edge_child_edge(&self, e: usize, j: usize) -> u32 {
        self.edge_child_edges[e][j]
    }
    #[inline]
    fn has_face_points(&self) -> bool {
        !self.triangles
    }
    #[inline]
    fn complete(&self, c: usize) -> bool {
        !self.child_vertex_incomplete(c)
    }
    fn vertex_runs(&self, _parent: &Level) -> [(u32, usize, usize); 3] {
        [
            &self.face_child_vertex,
            &self.edge_child_vertex,
            &self.vertex_child_vertex,
        ]
        .map(|children| {
            let mut valid = children.iter().filter(|&&c| c != INVALID_INDEX);
            let first = valid.next();
            let count = first.map_or(0, |_| 1 + valid.count());
            (first.copied().unwrap_or(0), count, children.len())
        })
    }
}

/// Whether child `c` was not created (only in a sparse step).
#[inline(always)]
pub(crate) fn missing<R: Children>(c: u32) -> bool {
    R::SPARSE && c == INVALID_INDEX
}

/// How the faces of a level split: the one scheme-dependent ingredient of
/// face-varying refinement.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum FaceSplit {
    /// Catmull-Clark and bilinear: a face of `n` sides into `n` quads, child
    /// `j` of face `f` numbered `offsets[f] + j`; an edge point lies in two
    /// children of each face of its edge.
    Quads,
    /// Loop: a triangle into four, children of face `f` numbered `4f..4f+4`;
    /// an edge point lies in three children of each face of its edge.
    Triangles,
}

impl FaceSplit {
    fn of(scheme: Scheme) -> Self {
        match scheme {
            Scheme::Loop => FaceSplit::Triangles,
            Scheme::Catmark | Scheme::Bilinear => FaceSplit::Quads,
        }
    }

    /// Children of one parent face around the point of one of its edges.
    fn child_faces_per_edge_face(self) -> usize {
        match self {
            FaceSplit::Quads => 2,
            FaceSplit::Triangles => 3,
        }
    }

    /// The parent face of a child face of a uniform split.
    fn parent_face(self, parent: &Level, child_face: u32) -> u32 {
        match self {
            FaceSplit::Quads => parent.face_vertices.element_of(child_face as usize) as u32,
            FaceSplit::Triangles => child_face / 4,
        }
    }
}

/// Refines a channel from `parent_fvar` (on `parent`) to `child`, which
/// `parent` was split into with the numbering `r` — uniform or sparse: only
/// the children that exist get values, and as in OpenSubdiv the crease ends
/// of an incomplete edge point stay unset (nothing refines it further).
/// `child_face_parent` gives a child face's parent face in a sparse step.
/// `parent`'s relations are read stored or derived ([`Around`]).
pub(crate) fn refine<R: Children>(
    around: Around,
    child: &Level,
    r: &R,
    child_face_parent: Option<&[u32]>,
    parent_fvar: &ChannelLevel,
    options: &Options,
) -> ChannelLevel {
    split_channel(
        around,
        child,
        r,
        child_face_parent,
        parent_fvar,
        options,
        true,
    )
}

/// [`refine()`] into a uniformly split last level whose values are
/// interpolated but whose faces nothing reads (a refinement that returns
/// only the last level's values): the channel without its corners' values
/// ([`ChannelLevel::face_values`] empty), which interpolation does not
/// read — a table as large as the level's face-vertices neither built nor
/// kept.
pub(crate) fn refine_values_only<R: Children>(
    around: Around,
    child: &Level,
    r: &R,
    parent_fvar: &ChannelLevel,
    options: &Options,
) -> ChannelLevel {
    split_channel(around, child, r, None, parent_fvar, options, false)
}

/// [`refine()`], with the corners' values when `with_corners` says so.
fn split_channel<R: Children>(
    around: Around,
    child: &Level,
    r: &R,
    child_face_parent: Option<&[u32]>,
    parent_fvar: &ChannelLevel,
    options: &Options,
    with_corners: bool,
) -> ChannelLevel {
    let parent = around.level;
    let p = parent_fvar;
    let split = FaceSplit::of(options.scheme);
    let mode = p.mode;
    let (nv, ne, nf) = (
        parent.vertex_count,
        parent.edge_count(),
        parent.face_count(),
    );
    let ncv = child.vertex_count;

    // Values per child vertex: one per face point; one per edge point, or one
    // per incident face across a split edge; as many per vertex child as its
    // parent had when mismatched.
    // Each child's count is written at `value_offsets[c + 1]`, then summed
    // in place into the offsets (a child not created counts 0).
    let mut value_offsets = Table::<u32>::zeroed(ncv + 1);
    if r.has_face_points() {
        for f in 0..nf {
            let c = r.face_child(f);
            if !missing::<R>(c) {
                value_offsets[c as usize + 1] = 1;
            }
        }
    }
    for e in 0..ne {
        let c = r.edge_child(e);
        if missing::<R>(c) {
            continue;
        }
        value_offsets[c as usize + 1] = if p.edge_tags[e].is_mismatch() {
            around.edge_face_count(e).max(1) as u32
        } else {
            1
        };
    }
    for v in 0..nv {
        let c = r.vertex_child(v);
        if missing::<R>(c) {
            continue;
        }
        let matches = !p.value_tags[p.value_offsets[v] as usize].is_mismatch();
        value_offsets[c as usize + 1] = if matches {
            1
        } else {
            p.vertex_value_count(v) as u32
        };
    }
    let mut total = 0u32;
    for x in &mut value_offsets[1..] {
        total += *x;
        *x = total;
    }
    let total = total as usize;
    let count = |offsets: &[u32], c: usize| (offsets[c + 1] - offsets[c]) as usize;

    // A minimal last level keeps no vertex-faces: its face values come
    // straight from the parent's faces, and — nothing refines it further —
    // it keeps no siblings, edge tags or crease spans. A level that derives
    // its relations keeps no vertex-faces either: its face values come from
    // the parent's faces too, and its siblings are read from them when it is
    // refined ([`ChannelLevel::corner_sibling`]).
    let with_siblings = child.vertex_faces.len() == child.vertex_count;
    let last = !with_siblings && !child.derived_relations;
    // Sparse levels are built whole.
    debug_assert!(!R::SPARSE || with_siblings);
    let mut fvar = ChannelLevel {
        mode,
        value_count: total,
        face_values: Table::new(),
        edge_tags: if last {
            Table::new()
        } else {
            Table::zeroed(child.edge_count())
        },
        value_offsets,
        face_siblings: if with_siblings {
            Table::zeroed(child.vertex_faces.members.len())
        } else {
            Table::new()
        },
        value_indices: Table::new(),
        value_tags: Table::zeroed(total),
        crease_ends: if mode.has_crease_ends() && !last {
            Table::zeroed(total)
        } else {
            Table::new()
        },
    };

    // Siblings of the faces around child vertices with several values.
    for e in (0..ne).filter(|_| with_siblings) {
        if !p.edge_tags[e].is_mismatch() {
            continue;
        }
        let e_faces = around.edge_faces(e);
        let e_faces = e_faces.as_slice();
        if e_faces.len() < 2 {
            continue;
        }
        let c = r.edge_child(e);
        if missing::<R>(c) {
            continue;
        }
        let range = child.vertex_faces.range(c as usize);
        for (slot, &cf) in fvar.face_siblings[range.clone()]
            .iter_mut()
            .zip(&child.vertex_faces.members[range])
        {
            let pf = match child_face_parent {
                Some(parents) => parents[cf as usize],
                None => split.parent_face(parent, cf),
            };
            if let Some(j) = e_faces.iter().rposition(|&f| f == pf) {
                *slot = j as u16;
            }
        }
    }
    let mut buf = AroundBuf::default();
    for v in 0..nv {
        let c = r.vertex_child(v);
        if missing::<R>(c) {
            continue;
        }
        let c = c as usize;
        if count(&fvar.value_offsets, c) > 1 && with_siblings {
            let range = child.vertex_faces.range(c);
            let hood = around.vertex_hood(v, &mut buf);
            let corners = hood.faces.iter().zip(hood.face_locals);
            for (i, (slot, (&f, &k))) in fvar.face_siblings[range]
                .iter_mut()
                .zip(corners)
                .enumerate()
            {
                *slot = p.corner_sibling(parent, v, f as usize, k as usize, i);
            }
        }
    }

    // Edge tags: edges inside faces are continuous, halves of an edge inherit.
    for e in (0..ne).filter(|_| !last) {
        for j in 0..2 {
            let c = r.edge_child_edge(e, j);
            if !missing::<R>(c) {
                fvar.edge_tags[c as usize] = p.edge_tags[e];
            }
        }
    }

    // Value tags. Face points match; edge points of split or linear edges are
    // creases (corners with linear boundaries); vertex children inherit.
    let split_edge_tag = if mode.has_crease_ends() {
        ValueTag::default()
            .with(ValueTag::MISMATCH)
            .with(ValueTag::CREASE)
    } else {
        ValueTag::default().with(ValueTag::MISMATCH)
    };
    for e in 0..ne {
        let t = p.edge_tags[e];
        let c = r.edge_child(e);
        if (t.is_mismatch() || t.is_linear()) && !missing::<R>(c) {
            let c = c as usize;
            let range = fvar.value_offsets[c] as usize..fvar.value_offsets[c + 1] as usize;
            fvar.value_tags[range].fill(split_edge_tag);
        }
    }
    for v in 0..nv {
        let c = r.vertex_child(v);
        if missing::<R>(c) {
            continue;
        }
        let c = c as usize;
        let o = fvar.value_offsets[c] as usize;
        let n = count(&fvar.value_offsets, c);
        let po = p.value_offsets[v] as usize;
        fvar.value_tags[o..o + n].copy_from_slice(&p.value_tags[po..po + n]);
    }

    if mode.has_crease_ends() && !last {
        // An edge point's value i spans the children of the edge's face i.
        let per_face = split.child_faces_per_edge_face();
        for e in 0..ne {
            let c = r.edge_child(e);
            if missing::<R>(c) || !r.complete(c as usize) {
                continue;
            }
            let c = c as usize;
            let o = fvar.value_offsets[c] as usize;
            if !fvar.value_tags[o].is_mismatch() {
                continue;
            }
            for i in 0..count(&fvar.value_offsets, c) {
                if !fvar.value_tags[o + i].is_inf_sharp() {
                    let start = i * per_face;
                    fvar.crease_ends[o + i] = [start as u16, (start + per_face - 1) as u16];
                }
            }
        }
        // A vertex's child keeps its faces in the same order: same spans.
        for v in 0..nv {
            let c = r.vertex_child(v);
            if missing::<R>(c) || !r.complete(c as usize) {
                continue;
            }
            let c = c as usize;
            let o = fvar.value_offsets[c] as usize;
            if !fvar.value_tags[o].is_mismatch() {
                continue;
            }
            let po = p.value_offsets[v] as usize;
            for i in 0..count(&fvar.value_offsets, c) {
                if !fvar.value_tags[o + i].is_inf_sharp() {
                    fvar.crease_ends[o + i] = p.crease_ends[po + i];
                }
            }
        }
    }
    if mode.has_crease_ends() {
        reclassify_semi_sharp(around, child, r, p, &mut fvar, options.creasing);
    }

    // Face values: each corner's vertex value, offset by its sibling.
    fvar.face_values = if !with_corners {
        Table::new()
    } else if total > ncv && !with_siblings {
        face_values_from_parent(around, child, r, split, p, &fvar.value_offsets)
    } else if total > ncv {
        let mut values = first_values(child, &fvar.value_offsets);
        for c in (0..ncv).filter(|&c| count(&fvar.value_offsets, c) > 1) {
            let range = child.vertex_faces.range(c);
            for i in range {
                let s = fvar.face_siblings[i];
                if s != 0 {
                    let f = child.vertex_faces.members[i] as usize;
                    let corner = child.face_vertices.start(f) + child.vertex_face_local[i] as usize;
                    values[corner] += s as u32;
                }
            }
        }
        values
    } else {
        let corners = &child.face_vertices.members;
        let mut values = Table::for_overwrite(corners.len());
        values.copy_from_slice(corners);
        values
    };
    fvar
}

/// Every corner of `child` with its vertex's first value.
fn first_values(child: &Level, offsets: &[u32]) -> Table<u32> {
    let corners = &child.face_vertices.members;
    let mut values = Table::for_overwrite(corners.len());
    for (x, &v) in values.iter_mut().zip(corners.iter()) {
        *x = offsets[v as usize];
    }
    values
}

/// The values of the corners of a uniformly split child level that keeps no
/// vertex-faces, from its parent's: every corner takes its vertex's first
/// value, but a vertex child takes the sibling its parent corner took (the
/// child keeps its parent's faces and their siblings), and the point of a
/// split edge in the children of the edge's face `i` takes sibling `i`
/// (the last position of that face among the edge's faces, as
/// [`refine`] numbers them through the child's vertex-faces).
fn face_values_from_parent<R: Children>(
    around: Around,
    child: &Level,
    r: &R,
    split: FaceSplit,
    p: &ChannelLevel,
    offsets: &[u32],
) -> Table<u32> {
    let parent = around.level;
    let mut values = first_values(child, offsets);
    // Where the children of parent face `f`'s corner `k` and of its edge
    // `k` lie among the child corners: the vertex child's corner, and the
    // (child corner) positions of the edge point.
    let fv = &parent.face_vertices;
    let vertex_corner = |f: usize, k: usize| -> usize {
        match split {
            FaceSplit::Quads => {
                let n = fv.count(f);
                let child_face = fv.start(f) + k;
                4 * child_face + if n == 4 { k } else { 0 }
            }
            FaceSplit::Triangles => 3 * (4 * f + k) + k,
        }
    };
    // Siblings are added to the first value corner by corner, once per
    // incidence, as OpenSubdiv numbers them through the child's
    // vertex-faces: where a degenerate face makes a vertex list a face
    // twice, the corner gets both siblings, as in OpenSubdiv.
    let edge_corners = |f: usize, k: usize| -> ([usize; 3], usize) {
        match split {
            FaceSplit::Quads => {
                let n = fv.count(f);
                let k1 = if k + 1 == n { 0 } else { k + 1 };
                let (rot, rot1) = if n == 4 { (k, k1) } else { (0, 0) };
                let (a, b) = (fv.start(f) + k, fv.start(f) + k1);
                ([4 * a + (rot + 1) % 4, 4 * b + (rot1 + 3) % 4, 0], 2)
            }
            FaceSplit::Triangles => {
                // Edge k's point in the corner children k and k + 1 and in
                // the middle child ([E1, E2, E0]).
                let t = 4 * f;
                let at = match k {
                    0 => [3 * t + 1, 3 * (t + 1), 3 * (t + 3) + 2],
                    1 => [3 * (t + 1) + 2, 3 * (t + 2) + 1, 3 * (t + 3)],
                    _ => [3 * t + 2, 3 * (t + 2), 3 * (t + 3) + 1],
                };
                (at, 3)
            }
        }
    };
    let mut buf = AroundBuf::default();
    for v in 0..parent.vertex_count {
        // Only a child with several values: a parent vertex whose first
        // value is not tagged mismatched passes one value on, whatever its
        // count (degenerate faces can give it several).
        let c = r.vertex_child(v) as usize;
        if offsets[c + 1] - offsets[c] < 2 {
            continue;
        }
        let hood = around.vertex_hood(v, &mut buf);
        for (i, (&f, &k)) in hood.faces.iter().zip(hood.face_locals).enumerate() {
            let s = p.corner_sibling(parent, v, f as usize, k as usize, i);
            values[vertex_corner(f as usize, k as usize)] += u32::from(s);
        }
    }
    for e in 0..parent.edge_count() {
        if !p.edge_tags[e].is_mismatch() {
            continue;
        }
        let faces = around.edge_faces(e);
        let faces = faces.as_slice();
        if faces.len() < 2 {
            continue;
        }
        for (i, &f) in faces.iter().enumerate() {
            let k = around.edge_face(e, i).1;
            let j = faces.iter().rposition(|&g| g == f).unwrap_or(0) as u32;
            let (at, n) = edge_corners(f as usize, k);
            for &corner in &at[..n] {
                values[corner] += j;
            }
        }
    }
    values
}

/// Turns semi-sharp values of vertex children into creases once no
/// semi-sharp edge is left inside their span (or the vertex lost all its
/// semi-sharp features).
fn reclassify_semi_sharp<R: Children>(
    around: Around,
    child: &Level,
    r: &R,
    p: &ChannelLevel,
    fvar: &mut ChannelLevel,
    creasing: CreasingMethod,
) {
    let parent = around.level;
    for v in 0..parent.vertex_count {
        let c = r.vertex_child(v);
        if missing::<R>(c) || !r.complete(c as usize) {
            continue;
        }
        let c = c as usize;
        let range = fvar.value_offsets[c] as usize..fvar.value_offsets[c + 1] as usize;
        if !fvar.value_tags[range.start].is_mismatch() {
            continue;
        }
        let ptag = parent.vertex_tag(v);
        if !ptag.semi_sharp() && !ptag.semi_sharp_edges() {
            continue;
        }
        let ctag = child.vertex_tag(c);
        if ctag.semi_sharp() || ctag.inf_sharp() {
            continue;
        }
        if !ctag.semi_sharp_edges() {
            for t in &mut fvar.value_tags[range] {
                if t.is_semi_sharp() {
                    *t = t.into_crease();
                }
            }
            continue;
        }
        let mut buf = AroundBuf::default();
        let hood = around.vertex_hood(v, &mut buf);
        let c_edges = super::child_vertex_edge_sharpness((parent, child), &hood, c, creasing);
        let p_first = p.value_offsets[v] as usize;
        let semi = |k: usize| crease::is_semi_sharp(c_edges[k]);
        for i in range.clone() {
            let t = fvar.value_tags[i];
            if !t.is_semi_sharp() || t.is_dep_sharp() {
                continue;
            }
            // The child's span is its parent value's (the same faces).
            let [start, end] = p.crease_ends[p_first + (i - range.start)];
            let (start, end) = (start as usize, end as usize);
            let still = if end > start {
                (start + 1..=end).any(semi)
            } else if start > end {
                (start + 1..c_edges.len()).any(semi) || (0..=end).any(semi)
            } else {
                false
            };
            if !still {
                fvar.value_tags[i] = t.into_crease();
            }
        }
        // A dependency on a value that is no longer semi-sharp is dropped.
        if range.len() == 2 && p.mode.dependent_sharpness {
            let (a, b) = (
                fvar.value_tags[range.start],
                fvar.value_tags[range.start + 1],
            );
            let clear = |t: ValueTag| ValueTag(t.0 & !ValueTag::DEP_SHARP);
            if a.is_dep_sharp() && !b.is_semi_sharp() {
                fvar.value_tags[range.start] = clear(a);
            } else if b.is_dep_sharp() && !a.is_semi_sharp() {
                fvar.value_tags[range.start + 1] = clear(b);
            }
        }
    }
}
