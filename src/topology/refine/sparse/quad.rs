//! The sparse quad split (Catmull-Clark, bilinear): which children of a face
//! are created (`QuadRefinement::markSparseFaceChildren`) and the child
//! level's relations (`QuadRefinement::populate*Relation`), children that
//! were not created left out.

use super::{FaceMarks, Filler, MARKED, Selection, SparseSplit, Topology, VertexParent, valid};
use crate::topology::refine::{next, prev};
use crate::topology::{Level, Relation, Table};

/// Everything of a selected face; of any other, the child face at each
/// selected corner, the two inner edges beside it and the face point.
pub(super) fn mark_faces(parent: &Level, sel: &Selection, edge_transitional: &[bool]) -> FaceMarks {
    let (nf, corners) = (parent.face_count(), parent.face_vertices.members.len());
    // Faces: everything of a selected face; of any other, the child face at
    // each selected corner, the two inner edges beside it and the face point.
    let mut face_child_faces = vec![0u32; corners];
    let mut face_child_edges = vec![0u32; corners];
    let mut face_child_vertex = vec![0u32; nf];
    let mut face_transitional = vec![0u8; nf];
    for f in 0..nf {
        let range = parent.face_vertices.range(f);
        let n = range.len();
        let verts = parent.face_verts(f);
        if sel.face(f) {
            face_child_faces[range.clone()].fill(MARKED);
            face_child_edges[range].fill(MARKED);
            face_child_vertex[f] = MARKED;
            continue;
        }
        let mut marked = false;
        for (j, &v) in verts.iter().enumerate() {
            if sel.vertex(v as usize) {
                face_child_faces[range.start + j] = MARKED;
                face_child_edges[range.start + j] = MARKED;
                face_child_edges[range.start + prev(j, n)] = MARKED;
                marked = true;
            }
        }
        if marked {
            face_child_vertex[f] = MARKED;
            let edges = parent.face_edges_of(f);
            face_transitional[f] = if n <= 4 {
                edges
                    .iter()
                    .enumerate()
                    .map(|(j, &e)| (edge_transitional[e as usize] as u8) << j)
                    .fold(0, |a, b| a | b)
            } else {
                edges.iter().any(|&e| edge_transitional[e as usize]) as u8
            };
        }
    }

    FaceMarks {
        child_faces: face_child_faces,
        child_edges: face_child_edges,
        child_vertex: face_child_vertex,
        transitional: face_transitional,
    }
}

/// The relations of the child level.
pub(super) fn topology(parent: &Level, s: &SparseSplit) -> Topology {
    let nf = s.child_face_parent.len();
    let ne = s.child_edge_parent.len();
    let nv = s.child_vertex_parent.len();
    // Face-vertices and face-edges.
    let mut face_vertices = Relation::uniform_for_overwrite(nf, 4);
    let mut face_edges = Table::zeroed(4 * nf);
    for f in 0..parent.face_count() {
        let range = parent.face_vertices.range(f);
        let n = range.len();
        let (verts, edges) = (parent.face_verts(f), parent.face_edges_of(f));
        for j in 0..n {
            let c = s.face_child_faces[range.start + j];
            if !valid(c) {
                continue;
            }
            let jp = prev(j, n);
            let (e_prev, e_next) = (edges[jp] as usize, edges[j] as usize);
            let corner = verts[j];
            let vs = [
                s.vertex_child_vertex[corner as usize],
                s.edge_child_vertex[e_next],
                s.face_child_vertex[f],
                s.edge_child_vertex[e_prev],
            ];
            let [p0, p1] = parent.edge_vertices[e_prev];
            let in_prev = if p0 != p1 { (p0 != corner) as usize } else { 1 };
            let [n0, n1] = parent.edge_vertices[e_next];
            let in_next = if n0 != n1 { (n0 != corner) as usize } else { 0 };
            let es = [
                s.edge_child_edges[e_next][in_next],
                s.face_child_edges[range.start + j],
                s.face_child_edges[range.start + jp],
                s.edge_child_edges[e_prev][in_prev],
            ];
            // A quad's children keep its orientation: the corner's child
            // sits at position j.
            let rot = if n == 4 { j } else { 0 };
            let (cv, ce) = (c as usize * 4, c as usize * 4);
            for k in 0..4 {
                face_vertices.members[cv + (rot + k) % 4] = vs[k];
                face_edges[ce + (rot + k) % 4] = es[k];
            }
        }
    }

    // Edge-vertices and edge-faces, child edges in index order: those
    // inside faces, then the halves of edges.
    let mut edge_vertices = Table::<[u32; 2]>::zeroed(ne);
    let mut edge_faces = Filler::new(ne, 4 * nf);
    for f in 0..parent.face_count() {
        let range = parent.face_vertices.range(f);
        let n = range.len();
        let edges = parent.face_edges_of(f);
        for (j, &edge) in edges.iter().enumerate() {
            let c = s.face_child_edges[range.start + j];
            if !valid(c) {
                continue;
            }
            edge_vertices[c as usize] =
                [s.face_child_vertex[f], s.edge_child_vertex[edge as usize]];
            let jn = next(j, n);
            let here = s.face_child_faces[range.start + j];
            if valid(here) {
                edge_faces.push(here, if n == 4 { jn } else { 1 });
            }
            let there = s.face_child_faces[range.start + jn];
            if valid(there) {
                edge_faces.push(there, if n == 4 { (jn + 2) & 3 } else { 2 });
            }
            edge_faces.end();
        }
    }
    super::edge_halves(
        parent,
        s,
        &mut edge_vertices,
        &mut edge_faces,
        |pf, in_face, of_edge| {
            let range = parent.face_vertices.range(pf);
            let n = range.len();
            let local = if n == 4 {
                in_face
            } else if of_edge == 1 {
                3
            } else {
                0
            };
            (
                s.face_child_faces[range.start + (in_face + of_edge) % n],
                local,
            )
        },
    );

    // Vertex-faces and vertex-edges, child vertices in index order.
    let mut vertex_faces = Filler::new(nv, 4 * nf);
    let mut vertex_edges = Filler::new(nv, 2 * ne);
    for (c, &p) in s.child_vertex_parent.iter().enumerate() {
        debug_assert_eq!(vertex_faces.offsets.len(), c + 1);
        match p {
            VertexParent::Face(f) => {
                let range = parent.face_vertices.range(f as usize);
                let n = range.len();
                for j in 0..n {
                    let cf = s.face_child_faces[range.start + j];
                    if valid(cf) {
                        vertex_faces.push(cf, if n == 4 { (j + 2) & 3 } else { 2 });
                    }
                    let lead = s.face_child_edges[range.start + prev(j, n)];
                    if valid(lead) {
                        vertex_edges.push(lead, 0);
                    }
                }
            }
            VertexParent::Edge(e) => {
                let e = e as usize;
                let ends = parent.edge_vertices[e];
                for &half in &s.edge_child_edges[e] {
                    if valid(half) {
                        vertex_edges.push(half, 0);
                    }
                }
                let first = vertex_edges.offsets[c] as usize;
                let faces = parent.edge_faces_of(e);
                for (i, (&pf, &in_face)) in faces.iter().zip(parent.edge_face_locals(e)).enumerate()
                {
                    let (pf, in_face) = (pf as usize, in_face as usize);
                    let range = parent.face_vertices.range(pf);
                    let n = range.len();
                    let (c0, c1) = (in_face, next(in_face, n));
                    let f1 = s.face_child_faces[range.start + c1];
                    if valid(f1) {
                        vertex_faces.push(f1, if n == 4 { c0 } else { 3 });
                    }
                    let f0 = s.face_child_faces[range.start + c0];
                    if valid(f0) {
                        vertex_faces.push(f0, if n == 4 { c1 } else { 1 });
                    }
                    let inner = s.face_child_edges[range.start + in_face];
                    if valid(inner) {
                        vertex_edges.push(inner, 1);
                        // Order [half, inner edge of the first face, half, ...],
                        // the halves as the edge runs in that face.
                        if i == 0 && vertex_edges.members.len() - first == 3 {
                            let m = &mut vertex_edges.members[first..];
                            let l = &mut vertex_edges.locals[first..];
                            if ends[0] != ends[1] && parent.face_verts(pf)[in_face] == ends[0] {
                                m.swap(0, 1);
                                l.swap(0, 1);
                            }
                            m.swap(1, 2);
                            l.swap(1, 2);
                        }
                    }
                }
            }
            VertexParent::Vertex(v) => {
                super::vertex_point(
                    parent,
                    s,
                    v as usize,
                    (&mut vertex_faces, &mut vertex_edges),
                    |pf, k| {
                        let range = parent.face_vertices.range(pf);
                        let local = if range.len() == 4 { k } else { 0 };
                        (s.face_child_faces[range.start + k], local)
                    },
                );
            }
        }
        vertex_faces.end();
        vertex_edges.end();
    }

    Topology {
        face_vertices,
        face_edges,
        edge_vertices,
        edge_faces,
        vertex_faces,
        vertex_edges,
    }
}
