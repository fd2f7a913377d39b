//! The vertex tags a feature-adaptive selection reads beyond those refinement
//! keeps ([`crate::topology::VertexTag`]): extraordinary, incomplete,
//! incident to an irregular face, on an infinitely sharp crease, infinitely
//! sharp and irregular — the `_xordinary`, `_incomplete`, `_incidIrregFace`,
//! `_infSharpCrease` and `_infIrregular` bits of OpenSubdiv's `Vtr::Level::VTag`,
//! set on the base level by `TopologyRefinerFactoryBase` and passed to each
//! child by `Vtr::Refinement::populateVertexTagVectors`.

use crate::options::Scheme;
use crate::rules::{Rule, crease};
use crate::topology::Level;
use crate::topology::refine::sparse::{SparseSplit, VertexParent};

/// The feature bits of one vertex.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct Features {
    /// Its valence is not the scheme's regular one (interior or boundary).
    pub xordinary: bool,
    /// Only part of its neighbourhood exists (a neighbour in a sparse level).
    pub incomplete: bool,
    /// A face of the base level around it is not of the scheme's regular size.
    pub incid_irreg_face: bool,
    /// Its infinitely sharp edges make it a crease.
    pub inf_sharp_crease: bool,
    /// Its infinitely sharp features are not those of a regular patch.
    pub inf_irregular: bool,
}

/// The regular size of a face: 3 under Loop, 4 otherwise.
pub(crate) fn regular_face_size(scheme: Scheme) -> usize {
    if scheme == Scheme::Loop { 3 } else { 4 }
}

/// The regular valence of an interior vertex: 6 under Loop, 4 otherwise.
fn regular_valence(scheme: Scheme) -> usize {
    if scheme == Scheme::Loop { 6 } else { 4 }
}

/// The features of every vertex of the base level.
pub(crate) fn base_features(level: &Level, scheme: Scheme) -> Vec<Features> {
    let reg_face = regular_face_size(scheme);
    let reg_valence = regular_valence(scheme);
    let irregular_faces = (0..level.face_count()).any(|f| level.face_vertices.count(f) != reg_face);
    (0..level.vertex_count)
        .map(|v| {
            let tag = level.vertex_tag(v);
            let faces = level.vertex_faces_of(v);
            let edges = level.vertex_edges_of(v);
            let xordinary = if tag.non_manifold() || tag.corner() {
                false
            } else if tag.boundary() {
                faces.len() != reg_valence / 2
            } else {
                faces.len() != reg_valence
            };
            let inf_edges = edges
                .iter()
                .filter(|&&e| level.edge_tag(e as usize).inf_sharp())
                .count();
            let mut inf_sharp_crease = false;
            let mut inf_irregular = tag.inf_sharp() || tag.inf_sharp_edges();
            if tag.inf_sharp_edges() {
                let sharpness = if tag.inf_sharp() {
                    level.vertex_sharpness_at(v)
                } else {
                    0.0
                };
                match crease::vertex_rule_from_sharp_edge_count(sharpness, inf_edges) {
                    Rule::Crease => {
                        inf_sharp_crease = true;
                        if !xordinary && !tag.non_manifold() {
                            inf_irregular = if tag.boundary() {
                                false
                            } else {
                                // A regular crease splits the ring in two
                                // halves: opposite edges equally sharp.
                                let inf = |k: usize| level.edge_tag(edges[k] as usize).inf_sharp();
                                if reg_valence == 4 {
                                    inf(0) != inf(2)
                                } else {
                                    inf(0) != inf(3) || inf(1) != inf(4)
                                }
                            };
                        }
                    }
                    // A regular corner: every edge sharp, not a smooth corner.
                    Rule::Corner
                        if inf_edges == edges.len() && (edges.len() > 2 || tag.inf_sharp()) =>
                    {
                        inf_irregular = false;
                    }
                    _ => {}
                }
            }
            let incid_irreg_face = irregular_faces
                && faces
                    .iter()
                    .any(|&f| level.face_vertices.count(f as usize) != reg_face);
            Features {
                xordinary,
                incomplete: false,
                incid_irreg_face,
                inf_sharp_crease,
                inf_irregular,
            }
        })
        .collect()
}

/// The features of every vertex of a child level from those of its parent:
/// face points are regular (but extraordinary when they split a base face of
/// irregular size), edge points take the infinitely sharp features of their
/// edge, vertex points inherit theirs (no longer next to an irregular base
/// face), and the children of components that were not selected are
/// incomplete.
pub(crate) fn child_features(
    parent: &Level,
    parent_features: &[Features],
    split: &SparseSplit,
    scheme: Scheme,
) -> Vec<Features> {
    let reg_face = regular_face_size(scheme);
    split
        .child_vertex_parent
        .iter()
        .map(|&p| {
            let incomplete = p.incomplete();
            let mut f = match p.get() {
                VertexParent::Face(f) => Features {
                    xordinary: parent.depth == 0
                        && parent.face_vertices.count(f as usize) != reg_face,
                    ..Features::default()
                },
                VertexParent::Edge(e) => {
                    let t = parent.edge_tag(e as usize);
                    Features {
                        inf_sharp_crease: t.inf_sharp(),
                        inf_irregular: t.inf_sharp() && t.non_manifold(),
                        ..Features::default()
                    }
                }
                VertexParent::Vertex(v) => Features {
                    incid_irreg_face: false,
                    ..parent_features[v as usize]
                },
            };
            f.incomplete |= incomplete;
            f
        })
        .collect()
}
