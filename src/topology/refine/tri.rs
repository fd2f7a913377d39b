//! Loop's triangle split: every triangle into four — child faces and edges,
//! and the faces and edges around each child vertex — as OpenSubdiv's
//! `Vtr::TriRefinement` (`vtr/triRefinement.cpp`) numbers and orders them.

use super::derive::vertex_relations_derivable;
use super::relations::{
    Sink, TableWriter, fill_vertex_relations, vertex_child_relations, vertex_relation_writers,
};
use super::tags::{ChildTags, child_holes};
use super::{Build, ChildRelations, FACE_CHUNK, Parts, Split, assemble_child};
use crate::options::Options;
use crate::topology::{Level, Relation, Table};
use rayon::prelude::*;

/// Triangle split (Loop): child faces `4f..4f+4` of triangle `f` are the three
/// corner triangles (child `j` at corner `j`) and the middle one; child edges
/// are the three inside each face, then two per parent edge.
pub(super) fn refine_triangles(
    parent: &Level,
    options: &Options,
    faces_first: bool,
    build: Build,
) -> (Split, Level) {
    let (minimal, locals) = build.parts();
    let r = Split::new(parent, faces_first, false);
    let derive = !minimal && !locals && vertex_relations_derivable(parent);
    let (ne, nf) = (parent.edge_count(), parent.face_count());
    let corners = r.parent_corners;
    let child_faces = 4 * nf;
    let child_edges = corners + 2 * ne;
    let child_vertices = r.child_vertex_count();
    let inner_edge = |f: usize, j: usize| (3 * f + j) as u32;

    // Child triangles (and the edges inside each parent face), in parallel
    // over chunks of parent triangles; then the halves of parent edges.
    let faces_part = || {
        // Every member is written below (debug builds poison them first).
        let mut face_vertices = Relation::uniform_for_overwrite(child_faces, 3);
        // A minimal last level needs neither face-edges nor edge-vertices.
        let (mut face_edges, mut edge_vertices) = if minimal {
            (Table::new(), Table::new())
        } else {
            (
                Table::for_overwrite(child_faces * 3),
                Table::for_overwrite(child_edges),
            )
        };
        let split =
            |f0: usize, fv_out: &mut [u32], mut rest: Option<(&mut [u32], &mut [[u32; 2]])>| {
                for (i, tris_out) in fv_out.chunks_exact_mut(12).enumerate() {
                    let f = f0 + i;
                    let fv = parent.face_verts(f);
                    let fe = parent.face_edges_of(f);
                    let ep = |j: usize| r.edge_child(fe[j] as usize);
                    let vp = |j: usize| r.vertex_child(fv[j] as usize);
                    let tris = [
                        [vp(0), ep(0), ep(2)],
                        [ep(0), vp(1), ep(1)],
                        [ep(2), ep(1), vp(2)],
                        [ep(1), ep(2), ep(0)],
                    ];
                    tris_out.copy_from_slice(tris.as_flattened());
                    let Some((fe_out, ev_out)) = rest.as_mut() else {
                        continue;
                    };
                    // The halves of each face edge, ordered along the face's direction.
                    let mut halves = [[0u32; 2]; 3];
                    for (i, h) in halves.iter_mut().enumerate() {
                        let e = fe[i] as usize;
                        let ev = parent.edge_vertices[e];
                        let reversed = (ev[0] != ev[1] && fv[i] != ev[0]) as usize;
                        *h = [
                            r.edge_child_edge(e, reversed),
                            r.edge_child_edge(e, 1 - reversed),
                        ];
                    }
                    let edges = [
                        [halves[0][0], inner_edge(f, 0), halves[2][1]],
                        [halves[0][1], halves[1][0], inner_edge(f, 1)],
                        [inner_edge(f, 2), halves[1][1], halves[2][0]],
                        [inner_edge(f, 2), inner_edge(f, 0), inner_edge(f, 1)],
                    ];
                    fe_out[12 * i..12 * i + 12].copy_from_slice(edges.as_flattened());
                    ev_out[3 * i..3 * i + 3].copy_from_slice(&[
                        [ep(0), ep(2)],
                        [ep(1), ep(0)],
                        [ep(2), ep(1)],
                    ]);
                }
            };
        const CHUNK: usize = FACE_CHUNK;
        if minimal {
            face_vertices
                .members
                .par_chunks_mut(12 * CHUNK)
                .enumerate()
                .for_each(|(k, fv_out)| split(k * CHUNK, fv_out, None));
        } else {
            let (inner, halves) = edge_vertices.split_at_mut(corners);
            face_vertices
                .members
                .par_chunks_mut(12 * CHUNK)
                .zip(face_edges.par_chunks_mut(12 * CHUNK))
                .zip(inner.par_chunks_mut(3 * CHUNK))
                .enumerate()
                .for_each(|(k, ((fv_out, fe_out), ev_out))| {
                    split(k * CHUNK, fv_out, Some((fe_out, ev_out)))
                });
            for e in 0..ne {
                let ev = parent.edge_vertices[e];
                for j in 0..2 {
                    halves[2 * e + j] = [r.edge_child(e), r.vertex_child(ev[j] as usize)];
                }
            }
        }
        (face_vertices, face_edges, edge_vertices)
    };

    // Everything but the face-vertices is skipped for a minimal last level.
    let relations_part = || -> ChildRelations {
        if minimal {
            return Default::default();
        }
        let edges_part = || {
            if derive {
                return (Relation::default(), Table::new());
            }
            // Edge-faces.
            let mut ef = TableWriter::new(
                child_edges,
                2 * corners + 2 * parent.edge_faces.members.len(),
                // Edges inside a face have two faces, halves their parent's.
                (parent.edge_faces.uniform_size() == Some(2)).then_some(2),
                locals,
            );
            for f in 0..nf {
                for j in 0..3 {
                    let l = ((j + 1) % 3) as u16;
                    ef.push((4 * f + j) as u32, l);
                    ef.push((4 * f + 3) as u32, l);
                    ef.end_element();
                }
            }
            for e in 0..ne {
                let ev = parent.edge_vertices[e];
                for j in 0..2 {
                    for (f, k) in parent.edge_faces_at(e) {
                        let of_edge = if ev[0] == ev[1] {
                            j
                        } else {
                            (parent.face_verts(f)[k] != ev[j]) as usize
                        };
                        let in_face = (k + of_edge) % 3;
                        ef.push((4 * f + in_face) as u32, k as u16);
                    }
                    ef.end_element();
                }
            }
            ef.finish()
        };
        let vertices_part = || {
            if derive {
                return Default::default();
            }
            let ef_members = parent.edge_faces.members.len();
            let (vf, ve) = vertex_relation_writers(
                parent,
                &r,
                parent.vertex_faces.members.len() + 3 * ef_members,
                parent.vertex_edges.members.len() + 2 * ne + 2 * ef_members,
                locals,
            );
            let (faces, ve) = triangle_vertex_relations(parent, &r, vf, ve);
            (faces, ve.finish())
        };
        let (
            (edge_faces, ef_local),
            ((vertex_faces, vertex_face_local), (vertex_edges, vertex_edge_local)),
        ) = rayon::join(edges_part, vertices_part);
        ChildRelations {
            edge_vertices: Table::new(),
            edge_faces,
            edge_face_local: ef_local,
            vertex_faces,
            vertex_face_local,
            vertex_edges,
            vertex_edge_local,
        }
    };
    // Edge sharpness and tags are stored unless the child is minimal.
    let bare = build == Build::Minimal;
    let tags_part = || ChildTags::new(parent, &r, options, child_vertices, child_edges, bare);
    let ((face_vertices, face_edges, edge_vertices), (mut relations, tags)) =
        rayon::join(faces_part, || rayon::join(relations_part, tags_part));
    // The triangle split writes edge-vertices with the faces.
    relations.edge_vertices = edge_vertices;

    let child = assemble_child(
        parent,
        tags,
        Parts {
            vertex_count: child_vertices,
            face_vertices,
            face_edges,
            relations,
            num_edges: child_edges,
            face_holes: child_holes(parent, child_faces, true),
            derived_relations: derive,
            max_valence: parent.max_valence.max(6).max(2 + 2 * parent.max_edge_faces),
        },
    );
    (r, child)
}

/// Triangle split: the edge point of parent edge `e` has three child
/// The vertex-faces (into `vf`) and vertex-edges (into `ve`) of every child
/// vertex of the triangle split, in the order of the child vertices: an
/// edge point has three child triangles and two inner edges per parent
/// face, and two halves; a vertex's child its corners' triangles and its
/// edges' halves.
fn triangle_vertex_relations<E: Sink>(
    parent: &Level,
    r: &Split,
    vf: TableWriter,
    ve: E,
) -> ((Relation, Table<u16>), E) {
    let edge_children = |vf: &mut TableWriter, ve: &mut E| {
        for e in 0..parent.edge_count() {
            triangle_edge_child(parent, r, e, vf, ve);
            vf.end_element();
            ve.end_element();
        }
    };
    let vertex_children = |vf: &mut TableWriter, ve: &mut E| {
        for v in 0..parent.vertex_count {
            triangle_vertex_child(parent, r, v, vf, ve);
            vf.end_element();
            ve.end_element();
        }
    };
    fill_vertex_relations(r, vf, ve, |_, _| {}, edge_children, vertex_children)
}

/// triangles and two inner edges per parent face, and the two halves.
#[inline(always)]
pub(super) fn triangle_edge_child(
    parent: &Level,
    r: &Split,
    e: usize,
    vf: &mut impl Sink,
    ve: &mut impl Sink,
) {
    let inner_edge = |f: usize, j: usize| (3 * f + j) as u32;
    let ev = parent.edge_vertices[e];
    let mut last_half = None;
    for (i, (f, k)) in parent.edge_faces_at(e).enumerate() {
        // Leading, middle and trailing child triangles around the edge point.
        for (child, local) in [((k + 1) % 3, k), (3, (k + 2) % 3), (k, (k + 1) % 3)] {
            vf.push((4 * f + child) as u32, local as u16);
        }
        if i == 0 {
            let reversed = ev[0] != ev[1] && parent.face_verts(f)[k] != ev[0];
            let (first, second) = if reversed { (0, 1) } else { (1, 0) };
            ve.push(r.edge_child_edge(e, first), 0);
            last_half = Some(r.edge_child_edge(e, second));
        }
        ve.push(inner_edge(f, (k + 1) % 3), 1);
        ve.push(inner_edge(f, k), 0);
        if let Some(h) = last_half.take() {
            ve.push(h, 0);
        }
    }
}

/// Triangle split: a vertex's child sits in the corner triangle of each face.
#[inline(always)]
pub(super) fn triangle_vertex_child(
    parent: &Level,
    r: &Split,
    v: usize,
    vf: &mut impl Sink,
    ve: &mut impl Sink,
) {
    vertex_child_relations(parent, r, v, vf, ve, |f, k| (4 * f + k as u32, k));
}
