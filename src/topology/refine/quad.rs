//! The quad split of Catmull-Clark and bilinear: every face of `n` sides
//! into `n` quads — child faces and edges, and the faces and edges around
//! each child vertex — as OpenSubdiv's `Vtr::QuadRefinement`
//! (`vtr/quadRefinement.cpp`) numbers and orders them.

use super::derive::vertex_relations_derivable;
use super::relations::{
    Sink, TableWriter, fill_vertex_relations, vertex_child_relations, vertex_relation_writers,
};
use super::tags::{ChildTags, child_holes};
use super::{Build, ChildRelations, Parts, Split, assemble_child, carve_by_faces, next, prev};
use crate::options::Options;
use crate::topology::{Level, Relation, Table};
use rayon::prelude::*;

/// Quad split (Catmull-Clark and bilinear): the children of face `f` with
/// `n` vertices are its `n` corner quads (child `j` at corner `j`, numbered
/// as that face corner); child edges are the `n` inside each face, then two
/// per parent edge. What [`refine_level`](super::refine_level) does for
/// these schemes, building what `build` says.
pub(super) fn refine_quads(
    parent: &Level,
    options: &Options,
    faces_first: bool,
    build: Build,
) -> (Split, Level) {
    let (minimal, locals) = build.parts();
    let r = Split::new(parent, faces_first, true);
    let derive = !minimal && !locals && vertex_relations_derivable(parent);
    let (ne, nf) = (parent.edge_count(), parent.face_count());
    let corners = r.parent_corners;
    let child_faces = corners;
    let child_edges = corners + 2 * ne;
    let child_vertices = r.child_vertex_count();

    // Face-vertices and face-edges of the child quads, in parallel over
    // chunks of parent faces: each chunk writes its own corners' children.
    let faces_part = || {
        // Every member is written below (debug builds poison them first).
        let mut face_vertices = Relation::uniform_for_overwrite(child_faces, 4);
        let mut face_edges = if minimal {
            Table::new()
        } else {
            Table::for_overwrite(child_faces * 4)
        };
        let fv_chunks = carve_by_faces(&mut face_vertices.members, parent, 4);
        let fe_chunks = if minimal {
            Vec::new()
        } else {
            carve_by_faces(&mut face_edges, parent, 4)
        };
        if minimal {
            fv_chunks.into_par_iter().for_each(|(faces, fv_out)| {
                split_quad_faces(parent, &r, faces, fv_out, None);
            });
        } else {
            fv_chunks
                .into_par_iter()
                .zip(fe_chunks)
                .for_each(|((faces, fv_out), (_, fe_out))| {
                    split_quad_faces(parent, &r, faces, fv_out, Some(fe_out));
                });
        }
        (face_vertices, face_edges)
    };

    // Everything but the face-vertices is skipped for a minimal last level.
    // Edge relations and vertex relations are built side by side.
    let relations_part = || -> ChildRelations {
        if minimal {
            return Default::default();
        }
        let edges_part = || {
            // Edge-vertices: face edges join the face point to an edge point; edge
            // halves join the edge point to an end vertex's child.
            // Both kinds are pushed in the order of their indices (corners
            // of faces, then two halves per parent edge).
            let mut edge_vertices = crate::topology::table_pool::vec_with_capacity(child_edges);
            for f in 0..nf {
                let fc = r.face_child(f);
                edge_vertices.extend(
                    parent
                        .face_edges_of(f)
                        .iter()
                        .map(|&e| [fc, r.edge_child(e as usize)]),
                );
            }
            debug_assert_eq!(edge_vertices.len(), r.edge_child_edge(0, 0) as usize);
            for (e, ev) in parent.edge_vertices.iter().enumerate() {
                let c = r.edge_child(e);
                edge_vertices.push([c, r.vertex_child(ev[0] as usize)]);
                edge_vertices.push([c, r.vertex_child(ev[1] as usize)]);
            }
            let edge_vertices = Table::from(edge_vertices);

            if derive {
                return (edge_vertices, Relation::default(), Table::new());
            }
            // Edge-faces: two per edge inside a face, then the parent edge's
            // faces for each half.
            let mut ef = TableWriter::new(
                child_edges,
                2 * corners + 2 * parent.edge_faces.members.len(),
                // Edges inside a face have two faces, halves their parent's.
                (parent.edge_faces.uniform_size() == Some(2)).then_some(2),
                locals,
            );
            for f in 0..nf {
                let base = parent.face_vertices.start(f);
                let n = parent.face_vertices.count(f);
                for j in 0..n {
                    let jn = next(j, n);
                    ef.push((base + j) as u32, if n == 4 { jn } else { 1 } as u16);
                    ef.push(
                        (base + jn) as u32,
                        if n == 4 { (jn + 2) & 3 } else { 2 } as u16,
                    );
                    ef.end_element();
                }
            }
            for e in 0..ne {
                let ev = parent.edge_vertices[e];
                for j in 0..2 {
                    for (f, k) in parent.edge_faces_at(e) {
                        let n = parent.face_vertices.count(f);
                        let of_edge = if ev[0] == ev[1] {
                            j
                        } else {
                            (parent.face_verts(f)[k] != ev[j]) as usize
                        };
                        let mut in_face = k + of_edge;
                        if in_face == n {
                            in_face = 0;
                        }
                        let local = if n == 4 {
                            k
                        } else if of_edge == 1 {
                            3
                        } else {
                            0
                        };
                        ef.push(
                            (parent.face_vertices.start(f) + in_face) as u32,
                            local as u16,
                        );
                    }
                    ef.end_element();
                }
            }
            let (edge_faces, ef_local) = ef.finish();
            (edge_vertices, edge_faces, ef_local)
        };
        let vertices_part = || {
            if derive {
                return Default::default();
            }
            let ef_members = parent.edge_faces.members.len();
            let (vf, ve) = vertex_relation_writers(
                parent,
                &r,
                parent.vertex_faces.members.len() + corners + 2 * ef_members,
                parent.vertex_edges.members.len() + corners + 2 * ne + ef_members,
                locals,
            );
            let (faces, ve) = quad_vertex_relations(parent, &r, vf, ve);
            (faces, ve.finish())
        };
        let (
            (edge_vertices, edge_faces, ef_local),
            ((vertex_faces, vertex_face_local), (vertex_edges, vertex_edge_local)),
        ) = rayon::join(edges_part, vertices_part);
        ChildRelations {
            edge_vertices,
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
    let ((face_vertices, face_edges), (relations, tags)) =
        rayon::join(faces_part, || rayon::join(relations_part, tags_part));

    let child = assemble_child(
        parent,
        tags,
        Parts {
            vertex_count: child_vertices,
            face_vertices,
            face_edges,
            relations,
            num_edges: child_edges,
            face_holes: child_holes(parent, child_faces, false),
            derived_relations: derive,
            max_valence: parent.max_valence.max(4).max(2 + parent.max_edge_faces),
        },
    );
    (r, child)
}

/// The vertex-faces (into `vf`) and vertex-edges (into `ve`) of every child
/// vertex of the quad split, in the order of the child vertices: a face
/// point has one face and one edge per corner, an edge point two faces per
/// parent face and two edges more, a vertex's child its corners' faces and
/// its edges' halves.
fn quad_vertex_relations<E: Sink>(
    parent: &Level,
    r: &Split,
    vf: TableWriter,
    ve: E,
) -> ((Relation, Table<u16>), E) {
    let face_children = |vf: &mut TableWriter, ve: &mut E| {
        for f in 0..parent.face_count() {
            quad_face_child(parent, f, vf, ve);
            vf.end_element();
            ve.end_element();
        }
    };
    let edge_children = |vf: &mut TableWriter, ve: &mut E| {
        let mut edge_list = Vec::with_capacity(8);
        for e in 0..parent.edge_count() {
            quad_edge_child(parent, r, e, vf, ve, &mut edge_list);
            vf.end_element();
            ve.end_element();
        }
    };
    let vertex_children = |vf: &mut TableWriter, ve: &mut E| {
        for v in 0..parent.vertex_count {
            quad_vertex_child(parent, r, v, vf, ve);
            vf.end_element();
            ve.end_element();
        }
    };
    fill_vertex_relations(r, vf, ve, face_children, edge_children, vertex_children)
}

/// The child quads of parent faces `faces` (a contiguous range), written
/// into `fv_out` (and `fe_out` unless the child is minimal): the children of
/// the range's corners, four values each.
fn split_quad_faces(
    parent: &Level,
    r: &Split,
    faces: std::ops::Range<usize>,
    fv_out: &mut [u32],
    mut fe_out: Option<&mut [u32]>,
) {
    let first = parent.face_vertices.start(faces.start);
    for f in faces {
        let base = parent.face_vertices.start(f);
        let verts = parent.face_verts(f);
        let edges = parent.face_edges_of(f);
        let n = verts.len();
        let fc = r.face_child(f);
        let quad = <&[u32; 4]>::try_from(verts)
            .ok()
            .zip(<&[u32; 4]>::try_from(edges).ok());
        if let Some((verts, edges)) = quad {
            // Quads, the common case: the same values, written a whole
            // face (four children) at a time.
            let at = 4 * (base - first);
            split_quad(
                parent,
                r,
                (base, fc),
                verts,
                edges,
                &mut fv_out[at..at + 16],
                fe_out.as_deref_mut().map(|fe| &mut fe[at..at + 16]),
            );
            continue;
        }
        for j in 0..n {
            let jp = prev(j, n);
            let c = base + j - first;
            let (e_prev, e_next) = (edges[jp] as usize, edges[j] as usize);
            let corner = verts[j];
            let v4 = [
                r.vertex_child(corner as usize),
                r.edge_child(e_next),
                fc,
                r.edge_child(e_prev),
            ];
            // A child of a quad keeps the parent's orientation: its corner
            // vertex sits at position j. Children of other faces start there.
            let rot = if n == 4 { j } else { 0 };
            for (k, &v) in v4.iter().enumerate() {
                fv_out[4 * c + (rot + k) % 4] = v;
            }
            if let Some(fe_out) = fe_out.as_deref_mut() {
                let e4 = corner_child_edges(parent, r, corner, [e_prev, e_next], base, j, jp);
                for (k, &e) in e4.iter().enumerate() {
                    fe_out[4 * c + (rot + k) % 4] = e;
                }
            }
        }
    }
}

/// The four children of a quad whose first corner is `base` and whose face
/// point is child vertex `fc` (`fv_out` and `fe_out` hold 16 values each):
/// what [`split_quad_faces`] writes for any face, with the face size known.
#[inline(always)]
fn split_quad(
    parent: &Level,
    r: &Split,
    (base, fc): (usize, u32),
    verts: &[u32; 4],
    edges: &[u32; 4],
    fv_out: &mut [u32],
    fe_out: Option<&mut [u32]>,
) {
    let vc = verts.map(|v| r.vertex_child(v as usize));
    let ec = edges.map(|e| r.edge_child(e as usize));
    // Child j keeps the parent's orientation: its corner vertex at position j.
    let mut fv = [0u32; 16];
    for j in 0..4 {
        let jp = (j + 3) & 3;
        let v4 = [vc[j], ec[j], fc, ec[jp]];
        for (k, &v) in v4.iter().enumerate() {
            fv[4 * j + ((j + k) & 3)] = v;
        }
    }
    fv_out.copy_from_slice(&fv);
    if let Some(fe_out) = fe_out {
        let mut fe = [0u32; 16];
        for j in 0..4 {
            let jp = (j + 3) & 3;
            let e4 = corner_child_edges(
                parent,
                r,
                verts[j],
                [edges[jp] as usize, edges[j] as usize],
                base,
                j,
                jp,
            );
            for (k, &e) in e4.iter().enumerate() {
                fe[4 * j + ((j + k) & 3)] = e;
            }
        }
        fe_out.copy_from_slice(&fe);
    }
}

/// The edges of the child of face corner `j` (vertex `corner`, between
/// face edges `[e_prev, e_next]`; `jp` is the corner before, `base` the
/// face's first corner), in the order of the child's vertices from the
/// corner: the half of `e_next` at the corner, the two edges inside the
/// face, the half of `e_prev` at the corner.
#[inline(always)]
fn corner_child_edges(
    parent: &Level,
    r: &Split,
    corner: u32,
    [e_prev, e_next]: [usize; 2],
    base: usize,
    j: usize,
    jp: usize,
) -> [u32; 4] {
    let ev_prev = parent.edge_vertices[e_prev];
    let ev_next = parent.edge_vertices[e_next];
    // Of a degenerate edge (both ends the same vertex), the corner takes the
    // first half of the edge leaving it and the second of the edge reaching it.
    let in_prev = if ev_prev[0] != ev_prev[1] {
        (ev_prev[0] != corner) as usize
    } else {
        1
    };
    let in_next = if ev_next[0] != ev_next[1] {
        (ev_next[0] != corner) as usize
    } else {
        0
    };
    [
        r.edge_child_edge(e_next, in_next),
        (base + j) as u32,
        (base + jp) as u32,
        r.edge_child_edge(e_prev, in_prev),
    ]
}

/// Quad split: the face point of parent face `f` has one child face and one
/// child edge per corner.
#[inline(always)]
pub(super) fn quad_face_child(parent: &Level, f: usize, vf: &mut impl Sink, ve: &mut impl Sink) {
    let base = parent.face_vertices.start(f);
    let n = parent.face_vertices.count(f);
    for j in 0..n {
        vf.push(
            (base + j) as u32,
            if n == 4 { (j + 2) & 3 } else { 2 } as u16,
        );
        ve.push((base + prev(j, n)) as u32, 0);
    }
}

/// Quad split: the edge point of parent edge `e` has two child faces per
/// parent face, and the two halves of `e` and an edge inside each face.
#[inline(always)]
pub(super) fn quad_edge_child(
    parent: &Level,
    r: &Split,
    e: usize,
    vf: &mut impl Sink,
    ve: &mut impl Sink,
    edge_list: &mut Vec<(u32, u16)>,
) {
    let ev = parent.edge_vertices[e];
    // The two halves first, then the edges inside each face; after the
    // first face the edges are rotated into counter-clockwise order.
    edge_list.clear();
    edge_list.push((r.edge_child_edge(e, 0), 0u16));
    edge_list.push((r.edge_child_edge(e, 1), 0u16));
    for (i, (f, k)) in parent.edge_faces_at(e).enumerate() {
        let n = parent.face_vertices.count(f);
        let base = parent.face_vertices.start(f) as u32;
        let (c0, c1) = (k, next(k, n));
        vf.push(base + c1 as u32, if n == 4 { c0 } else { 3 } as u16);
        vf.push(base + c0 as u32, if n == 4 { c1 } else { 1 } as u16);
        edge_list.push((base + k as u32, 1));
        if i == 0 {
            if ev[0] != ev[1] && parent.face_verts(f)[k] == ev[0] {
                edge_list.swap(0, 1);
            }
            edge_list.swap(1, 2);
        }
    }
    for &(m, l) in edge_list.iter() {
        ve.push(m, l);
    }
}

/// Quad split: a vertex's child sits in the child face at its corner — at
/// the same position in a child of a quad, first in other children.
#[inline(always)]
pub(super) fn quad_vertex_child(
    parent: &Level,
    r: &Split,
    v: usize,
    vf: &mut impl Sink,
    ve: &mut impl Sink,
) {
    vertex_child_relations(parent, r, v, vf, ve, |f, k| {
        let n = parent.face_vertices.count(f as usize);
        let local = if n == 4 { k } else { 0 };
        (
            parent.face_vertices.start(f as usize) as u32 + k as u32,
            local,
        )
    });
}
