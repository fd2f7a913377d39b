//! Loop's sparse triangle split: which children of a triangle are created
//! (`TriRefinement::markSparseFaceChildren`) and the child level's relations
//! (`TriRefinement::populate*Relation`), children that were not created left
//! out. A triangle splits into three corner triangles (child `j` at corner
//! `j`) and a middle one (child 3); its three inner edges are the middle
//! triangle's (edge `j` opposite corner `j`); there is no face point.

use super::child::{self, Filler, Fills, Room, Topology};
use super::views::Numbering;
use super::{FaceMarks, MARKED, Selection, SparseSplit, VertexParent, valid};
use crate::topology::{Level, Relation, Table};

/// Everything of a selected triangle; of any other with a selected corner,
/// the corner triangle and the inner edge opposite it at each selected
/// corner, and the middle triangle with all three inner edges when one of
/// its edges is transitional.
pub(super) fn mark_faces(parent: &Level, sel: &Selection, edge_transitional: &[bool]) -> FaceMarks {
    let nf = parent.face_count();
    let mut child_faces = Table::<u32>::zeroed(4 * nf);
    let mut child_edges = Table::<u32>::zeroed(parent.face_vertices.members.len());
    let mut transitional = Table::<u8>::zeroed(nf);
    for f in 0..nf {
        let edges = parent.face_vertices.range(f);
        if sel.face(f) {
            child_faces[4 * f..4 * f + 4].fill(MARKED);
            child_edges[edges].fill(MARKED);
            continue;
        }
        let verts = parent.face_verts(f);
        if !verts.iter().any(|&v| sel.vertex(v as usize)) {
            continue;
        }
        transitional[f] = parent
            .face_edges_of(f)
            .iter()
            .enumerate()
            .map(|(j, &e)| (edge_transitional[e as usize] as u8) << j)
            .fold(0, |a, b| a | b);
        if transitional[f] != 0 {
            child_faces[4 * f + 3] = MARKED;
            child_edges[edges.clone()].fill(MARKED);
        }
        for (j, &v) in verts.iter().enumerate() {
            if sel.vertex(v as usize) {
                child_faces[4 * f + j] = MARKED;
                child_edges[edges.start + j] = MARKED;
            }
        }
    }
    FaceMarks {
        child_faces,
        child_edges,
        child_vertex: Table::new(),
        transitional,
    }
}

/// The relations of the child level.
pub(super) fn topology(parent: &Level, s: &SparseSplit) -> Topology {
    let room = Room::transposes(s.child_face_parent.len(), 3, s.child_edge_parent.len());
    child::fill_in(room, |room| fill(parent, s, room))
}

/// [`topology`] with the filled relations in `room`, or the room they
/// need.
fn fill(parent: &Level, s: &SparseSplit, room: Room) -> Result<Topology, Room> {
    let nf = s.child_face_parent.len();
    let ne = s.child_edge_parent.len();
    let nv = s.child_vertex_parent.len();
    let mut fills = Fills::new(ne, nv, room);
    let [mut edge_faces, mut vertex_faces, mut vertex_edges] = fills.fillers();
    let (pv, numbering) = (parent.slices(), Numbering::of(s));
    let mut face_vertices = Relation::uniform_for_overwrite(nf, 3);
    let mut face_edges = Table::zeroed(3 * nf);
    let mut edge_vertices = Table::<[u32; 2]>::zeroed(ne);

    // Faces, and the inner edges in index order (parent face order).
    for f in 0..parent.face_count() {
        let (verts, edges) = (parent.face_verts(f), parent.face_edges_of(f));
        let children = &s.face_child_faces[4 * f..4 * f + 4];
        let inner = &s.face_child_edges[parent.face_vertices.range(f)];
        let ep = |k: usize| s.edge_child_vertex[edges[k] as usize];
        let vp = |k: usize| s.vertex_child_vertex[verts[k] as usize];
        // The halves of each edge of the face, in the face's direction.
        let halves = |k: usize| {
            let e = edges[k] as usize;
            let [a, b] = parent.edge_vertices[e];
            let reversed = a != b && verts[k] != a;
            let h = s.edge_child_edges[e];
            [h[reversed as usize], h[!reversed as usize]]
        };
        let (h0, h1, h2) = (halves(0), halves(1), halves(2));
        let child_verts = [
            [vp(0), ep(0), ep(2)],
            [ep(0), vp(1), ep(1)],
            [ep(2), ep(1), vp(2)],
            [ep(1), ep(2), ep(0)],
        ];
        let child_edges = [
            [h0[0], inner[0], h2[1]],
            [h0[1], h1[0], inner[1]],
            [inner[2], h1[1], h2[0]],
            [inner[2], inner[0], inner[1]],
        ];
        for (k, &c) in children.iter().enumerate() {
            if valid(c) {
                let c = c as usize;
                face_vertices.members[3 * c..3 * c + 3].copy_from_slice(&child_verts[k]);
                face_edges[3 * c..3 * c + 3].copy_from_slice(&child_edges[k]);
            }
        }
        let inner_ends = [[ep(0), ep(2)], [ep(1), ep(0)], [ep(2), ep(1)]];
        for (j, &c) in inner.iter().enumerate() {
            if !valid(c) {
                continue;
            }
            edge_vertices[c as usize] = inner_ends[j];
            for cf in [children[j], children[3]] {
                if valid(cf) {
                    edge_faces.push(cf, (j + 1) % 3);
                }
            }
            edge_faces.end();
        }
    }

    // The halves of edges.
    child::edge_halves(
        pv,
        numbering,
        &mut edge_vertices,
        &mut edge_faces,
        |pf, in_face| parent.face_verts(pf)[in_face],
        |pf, in_face, of_edge| {
            (
                s.face_child_faces[4 * pf + (in_face + of_edge) % 3],
                in_face,
            )
        },
    );

    // Vertex-faces and vertex-edges, child vertices in index order.
    for &p in s.child_vertex_parent.iter() {
        match p.get() {
            VertexParent::Edge(e) => {
                let e = e as usize;
                let ends = parent.edge_vertices[e];
                let halves = s.edge_child_edges[e];
                let faces = parent.edge_faces_of(e);
                for (i, (&pf, &in_face)) in faces.iter().zip(parent.edge_face_locals(e)).enumerate()
                {
                    let (pf, k) = (pf as usize, in_face as usize);
                    let children = &s.face_child_faces[4 * pf..4 * pf + 4];
                    // Leading corner triangle, middle, trailing corner triangle.
                    for (child, local) in [((k + 1) % 3, k), (3, (k + 2) % 3), (k, (k + 1) % 3)] {
                        if valid(children[child]) {
                            vertex_faces.push(children[child], local);
                        }
                    }
                    let inner = &s.face_child_edges[parent.face_vertices.range(pf)];
                    let (mut first, mut last) = (crate::INVALID_INDEX, crate::INVALID_INDEX);
                    if i == 0 {
                        let reversed = ends[0] != ends[1] && parent.face_verts(pf)[k] != ends[0];
                        first = halves[!reversed as usize];
                        last = halves[reversed as usize];
                    }
                    for (edge, local) in [
                        (first, 0),
                        (inner[(k + 1) % 3], 1),
                        (inner[k], 0),
                        (last, 0),
                    ] {
                        if valid(edge) {
                            vertex_edges.push(edge, local);
                        }
                    }
                }
            }
            VertexParent::Vertex(v) => {
                child::vertex_point(
                    pv,
                    numbering,
                    v as usize,
                    (&mut vertex_faces, &mut vertex_edges),
                    |pf, k| (s.face_child_faces[4 * pf + k], k),
                );
            }
            VertexParent::Face(_) => unreachable!("Loop's split has no face points"),
        }
        vertex_faces.end();
        vertex_edges.end();
    }
    let done = [edge_faces, vertex_faces, vertex_edges].map(Filler::finish);
    fills.topology(done, face_vertices, face_edges, edge_vertices)
}
