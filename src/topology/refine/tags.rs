//! The sharpness, tags and holes of a child level, propagated from its parent
//! — OpenSubdiv's `Refinement::propagateComponentTags` and
//! `Refinement::subdivideSharpnessValues` (`vtr/refinement.cpp`): tags are
//! inherited, sharpness decays by the creasing method, and the rules of
//! vertices whose semi-sharp features decayed are recomputed.

use super::Split;
use crate::options::{CreasingMethod, Options};
use crate::rules::{Rule, SHARPNESS_INFINITE, crease};
use crate::topology::{EdgeTag, Level, Table, VertexTag};

/// The sharpness and tags of a child level, propagated from its parent; built
/// alongside (and independently of) the child's relations.
pub(crate) struct ChildTags {
    pub(super) edge_sharpness: Table<f32>,
    pub(super) vertex_sharpness: Table<f32>,
    pub(super) edge_tags: Table<EdgeTag>,
    pub(super) vertex_tags: Table<VertexTag>,
}

impl ChildTags {
    /// A minimal child stores no edge sharpness or tags. Like sharpness, the
    /// tag tables stay empty while every tag is the default: a parent storing
    /// no tags (a smooth closed mesh) passes none on, and tags that decay
    /// back to the default are dropped.
    pub(super) fn new(
        parent: &Level,
        r: &Split,
        options: &Options,
        vertex_count: usize,
        num_edges: usize,
        minimal: bool,
    ) -> Self {
        // The propagation works on a level holding just these tables; they
        // stay empty unless a value other than the default is set.
        let mut child = Level {
            depth: parent.depth + 1,
            vertex_count,
            num_edges,
            ..Level::default()
        };
        propagate_tags(parent, &mut child, r, !minimal);
        subdivide_sharpness(parent, &mut child, r, options.creasing, !minimal);
        child.drop_default_tags();
        ChildTags {
            edge_sharpness: child.edge_sharpness,
            vertex_sharpness: child.vertex_sharpness,
            edge_tags: child.edge_tags,
            vertex_tags: child.vertex_tags,
        }
    }
}

/// Each child face inherits its parent's hole flag. Children come in parent
/// order: one per parent corner (quad split) or four per triangle (Loop).
/// Empty (no hole) when the parent stores no hole flags or its holes have
/// no children.
pub(super) fn child_holes(parent: &Level, child_faces: usize, four_per_face: bool) -> Vec<bool> {
    if parent.face_holes.is_empty() {
        return Vec::new();
    }
    let mut holes = crate::alloc::vec_or_unwind(false, child_faces);
    let mut any = false;
    for (f, _) in parent.face_holes.iter().enumerate().filter(|(_, h)| **h) {
        let range = if four_per_face {
            4 * f..4 * f + 4
        } else {
            parent.face_vertices.range(f)
        };
        any |= !range.is_empty();
        holes[range].fill(true);
    }
    if any { holes } else { Vec::new() }
}

/// Child tags: faces inherit holes (done by the caller), edge halves inherit
/// their parent edge's tags, edges inside faces are smooth, face points are
/// smooth, edge points take their rule from the parent edge, and children of
/// vertices inherit their parent's tags. Edge tags are stored when
/// `store_edges` (not in a minimal child).
///
/// Default edge tags give default child tags, so a parent storing no edge
/// (vertex) tags skips the pass over its edges (vertices), and the child's
/// tables are allocated only by a tag other than the default.
fn propagate_tags(parent: &Level, child: &mut Level, r: &Split, store_edges: bool) {
    for (e, &t) in parent.edge_tags.iter().enumerate() {
        if store_edges {
            child.set_edge_tag(r.edge_child_edge(e, 0) as usize, t);
            child.set_edge_tag(r.edge_child_edge(e, 1) as usize, t);
        }
        child.set_vertex_tag(r.edge_child(e) as usize, edge_point_tag(t));
    }
    for (v, &tag) in parent.vertex_tags.iter().enumerate() {
        child.set_vertex_tag(r.vertex_child(v) as usize, tag);
    }
}

/// The tags of the point of an edge tagged `t`: its boundary and
/// non-manifold flags, its sharp edges, and the crease rule when the edge is
/// sharp.
pub(super) fn edge_point_tag(t: EdgeTag) -> VertexTag {
    let sharp = t.semi_sharp() || t.inf_sharp();
    let mut tag = VertexTag::default();
    tag.set_non_manifold(t.non_manifold());
    tag.set_boundary(t.boundary());
    tag.set_semi_sharp_edges(t.semi_sharp());
    tag.set_inf_sharp_edges(t.inf_sharp());
    tag.set_rule(if sharp { Rule::Crease } else { Rule::Smooth });
    tag
}

/// The sharpness of child `c` of parent vertex `v` (whose tags it
/// inherited): infinite stays infinite, semi-sharp decays and loses its tag
/// once smooth.
pub(super) fn vertex_point_sharpness(parent: &Level, child: &mut Level, v: usize, c: usize) {
    let tag = child.vertex_tag(c);
    if tag.inf_sharp() {
        child.set_vertex_sharpness(c, SHARPNESS_INFINITE);
    } else if tag.semi_sharp() {
        let s = crease::subdivide_vertex_sharpness(parent.vertex_sharpness_at(v));
        child.set_vertex_sharpness(c, s);
        if !crease::is_sharp(s) {
            child.update_vertex_tag(c, |t| t.set_semi_sharp(false));
        }
    }
}

/// The sharpness and tags of child edge `j` of parent edge `e` (the half at
/// the parent's end vertex `j`): inherited tags, sharpness decayed by the
/// creasing method, semi-sharpness dropped once it reaches zero.
pub fn child_edge(
    parent: &Level,
    e: usize,
    j: usize,
    method: CreasingMethod,
    around: &mut Vec<f32>,
) -> (f32, EdgeTag) {
    let mut tag = parent.edge_tag(e);
    if tag.inf_sharp() {
        return (SHARPNESS_INFINITE, tag);
    }
    if !tag.semi_sharp() {
        return (0.0, tag);
    }
    let ps = parent.edge_sharpness_at(e);
    let s = match method {
        CreasingMethod::Uniform => crease::subdivide_uniform_sharpness(ps),
        CreasingMethod::Chaikin => {
            let pv = parent.edge_vertices[e][j] as usize;
            around.clear();
            around.extend(
                parent
                    .vertex_edges_of(pv)
                    .iter()
                    .map(|&x| parent.edge_sharpness_at(x as usize)),
            );
            crease::subdivide_edge_sharpness_at_vertex(method, ps, around)
        }
    };
    if !crease::is_sharp(s) {
        tag.set_semi_sharp(false);
    }
    (s, tag)
}

/// The sharpness of every edge of a child level (edges inside parent faces
/// are smooth): what a minimal last level does not store.
pub fn child_edge_sharpness(
    parent: &Level,
    r: &Split,
    method: CreasingMethod,
    child_edges: usize,
) -> Vec<f32> {
    let mut out = crate::alloc::vec_or_unwind(0.0, child_edges);
    if parent.edge_sharpness.is_empty() {
        // Every parent edge is smooth, so are its halves.
        return out;
    }
    let mut around = Vec::new();
    for e in 0..parent.edge_count() {
        for j in 0..2 {
            out[r.edge_child_edge(e, j) as usize] = child_edge(parent, e, j, method, &mut around).0;
        }
    }
    out
}

/// Edge and vertex sharpness of the child level, then the rules of child
/// vertices whose neighbourhood was semi-sharp. A minimal child (not
/// `store_edges`) stores no edge sharpness or tags: they are recomputed where
/// the rules need them.
///
/// Sharp and semi-sharp tags go with stored sharpness (a value other than
/// 0.0), so a parent storing no edge (vertex) sharpness has no sharp edges
/// (vertices) and the passes over them are skipped; the child's tables are
/// allocated only by a value other than 0.0.
fn subdivide_sharpness(
    parent: &Level,
    child: &mut Level,
    r: &Split,
    method: CreasingMethod,
    store_edges: bool,
) {
    let sharp_edges = !parent.edge_sharpness.is_empty();
    let sharp_vertices = !parent.vertex_sharpness.is_empty();
    if !sharp_edges && !sharp_vertices {
        return;
    }
    let mut around = Vec::new();
    if store_edges && sharp_edges {
        for e in 0..parent.edge_count() {
            let t = parent.edge_tag(e);
            if !t.semi_sharp() && !t.inf_sharp() {
                continue;
            }
            for j in 0..2 {
                let c = r.edge_child_edge(e, j) as usize;
                let (s, tag) = child_edge(parent, e, j, method, &mut around);
                child.set_edge_sharpness(c, s);
                child.set_edge_tag(c, tag);
            }
        }
    }
    let edge_semi = |e: usize, j: usize, around: &mut Vec<f32>, child: &Level| -> EdgeTag {
        if store_edges {
            child.edge_tag(r.edge_child_edge(e, j) as usize)
        } else {
            child_edge(parent, e, j, method, around).1
        }
    };
    if sharp_vertices {
        for v in 0..parent.vertex_count {
            vertex_point_sharpness(parent, child, v, r.vertex_child(v) as usize);
        }
    }
    // Edge points of semi-sharp edges: Crease while a half stays sharp.
    if sharp_edges {
        for e in 0..parent.edge_count() {
            let c = r.edge_child(e) as usize;
            if !child.vertex_tag(c).semi_sharp_edges() {
                continue;
            }
            let count = (0..2)
                .filter(|&j| edge_semi(e, j, &mut around, child).semi_sharp())
                .count();
            child.update_vertex_tag(c, |tag| {
                tag.set_semi_sharp_edges(count > 0);
                tag.set_rule(crease::vertex_rule_from_sharp_edge_count(0.0, count));
            });
        }
    }
    // Children of vertices whose semi-sharp features may have decayed.
    for v in 0..parent.vertex_count {
        let p = parent.vertex_tag(v);
        if !p.semi_sharp() && !p.semi_sharp_edges() {
            continue;
        }
        let c = r.vertex_child(v) as usize;
        let decayed = p.semi_sharp() && !child.vertex_tag(c).semi_sharp();
        if p.semi_sharp_edges() || decayed {
            // The child's edges are the halves of the parent's edges at this
            // vertex (found through the parent: the child level may be minimal).
            let (mut inf, mut semi) = (0, 0);
            for (&e, &l) in parent
                .vertex_edges_of(v)
                .iter()
                .zip(parent.vertex_edge_locals(v))
            {
                let t = edge_semi(e as usize, l as usize, &mut around, child);
                inf += t.inf_sharp() as usize;
                semi += t.semi_sharp() as usize;
            }
            child.update_vertex_tag(c, |tag| {
                tag.set_semi_sharp_edges(semi > 0);
                if !tag.semi_sharp() && !tag.inf_sharp() {
                    tag.set_rule(crease::vertex_rule_from_sharp_edge_count(0.0, inf + semi));
                }
            });
        }
    }
}
