//! The tags and sharpness of a sparse child level (`Refinement::
//! propagateComponentTags`, `subdivideSharpnessValues` and
//! `reclassifySemisharpVertices` in `vtr/refinement.cpp`), over the
//! children that exist.

use super::{SparseSplit, valid};
use crate::options::Options;
use crate::rules::crease;
use crate::topology::refine::tags::{child_edge, edge_point_tag, vertex_point_sharpness};
use crate::topology::tags::{EdgeTag, VertexTag};
use crate::topology::{Level, Table};

/// Child tags (`Refinement::propagateComponentTags`): halves of edges
/// inherit their parent's tags, edges inside faces and face points are
/// smooth, edge points take their tags from the parent edge, vertex points
/// inherit their parent's.
pub(super) fn propagate_tags(parent: &Level, child: &mut Level, s: &SparseSplit) {
    let (edge_tags, vertex_tags): (&[EdgeTag], &[VertexTag]) =
        (&parent.edge_tags, &parent.vertex_tags);
    let default_point = edge_point_tag(EdgeTag::default());
    if edge_tags.is_empty() && vertex_tags.is_empty() && default_point == VertexTag::default() {
        // Every tag the default, the child's too (its tables stay empty).
        return;
    }
    // Written through slices, whole tables (emptied again by
    // `Level::drop_default_tags` if every tag is the default).
    let mut child_edges = if edge_tags.is_empty() {
        Table::new()
    } else {
        Table::<EdgeTag>::zeroed(child.num_edges)
    };
    let mut child_vertices = Table::<VertexTag>::zeroed(child.vertex_count);
    let (ce, cv): (&mut [EdgeTag], &mut [VertexTag]) = (&mut child_edges, &mut child_vertices);
    for (e, halves) in s.edge_child_edges.iter().enumerate() {
        let t = edge_tags.get(e).copied().unwrap_or_default();
        if !ce.is_empty() {
            for &c in halves {
                if valid(c) {
                    ce[c as usize] = t;
                }
            }
        }
        let c = s.edge_child_vertex[e];
        if valid(c) {
            cv[c as usize] = edge_point_tag(t);
        }
    }
    if !vertex_tags.is_empty() {
        for (&t, &c) in vertex_tags.iter().zip(s.vertex_child_vertex.iter()) {
            if valid(c) {
                cv[c as usize] = t;
            }
        }
    }
    child.edge_tags = child_edges;
    child.vertex_tags = child_vertices;
}

/// Edge and vertex sharpness of the child, then the rules of child vertices
/// whose neighbourhood was semi-sharp (`Refinement::subdivideSharpnessValues`
/// and `reclassifySemisharpVertices`). An incomplete edge point may miss a
/// half: it is a crease when the half it has is semi-sharp.
pub(super) fn subdivide_sharpness(
    parent: &Level,
    child: &mut Level,
    s: &SparseSplit,
    options: &Options,
) {
    let mut around = Vec::new();
    for (e, halves) in s.edge_child_edges.iter().enumerate() {
        let t = parent.edge_tag(e);
        if !t.semi_sharp() && !t.inf_sharp() {
            continue;
        }
        for (j, &c) in halves.iter().enumerate() {
            if valid(c) {
                let (sharpness, tag) = child_edge(parent, e, j, options.creasing, &mut around);
                child.set_edge_sharpness(c as usize, sharpness);
                child.set_edge_tag(c as usize, tag);
            }
        }
    }
    for (v, &c) in s.vertex_child_vertex.iter().enumerate() {
        if valid(c) {
            vertex_point_sharpness(parent, child, v, c as usize);
        }
    }
    for (e, &c) in s.edge_child_vertex.iter().enumerate() {
        if !valid(c) || !child.vertex_tag(c as usize).semi_sharp_edges() {
            continue;
        }
        let semi = |h: u32| valid(h) && child.edge_tag(h as usize).semi_sharp();
        let [h0, h1] = s.edge_child_edges[e];
        let rule = if s.child_vertex_incomplete(c as usize) {
            if semi(h0) || semi(h1) {
                crate::rules::Rule::Crease
            } else {
                crate::rules::Rule::Smooth
            }
        } else {
            crease::vertex_rule_from_sharp_edge_count(0.0, semi(h0) as usize + semi(h1) as usize)
        };
        let any = semi(h0) || semi(h1);
        child.update_vertex_tag(c as usize, |t| {
            t.set_semi_sharp_edges(any);
            t.set_rule(rule);
        });
    }
    for (v, &c) in s.vertex_child_vertex.iter().enumerate() {
        if !valid(c) {
            continue;
        }
        let p = parent.vertex_tag(v);
        if !p.semi_sharp() && !p.semi_sharp_edges() {
            continue;
        }
        let c = c as usize;
        let decayed = p.semi_sharp() && !child.vertex_tag(c).semi_sharp();
        if p.semi_sharp_edges() || decayed {
            let (mut inf, mut semi) = (0, 0);
            for &ce in child.vertex_edges_of(c) {
                let t = child.edge_tag(ce as usize);
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
