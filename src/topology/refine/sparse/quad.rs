//! The sparse quad split (Catmull-Clark, bilinear): which children of a face
//! are created (`QuadRefinement::markSparseFaceChildren`) and the child
//! level's relations (`QuadRefinement::populate*Relation`), children that
//! were not created left out.

use super::child::{self, Filler, Fills, Room, Topology};
use super::views::{Faces, Numbering};
use super::{FaceMarks, MARKED, Selection, SparseSplit, VertexParent, valid};
use crate::topology::LevelSlices;
use crate::topology::refine::{next, prev};
use crate::topology::{Level, Relation, Table};

/// Everything of a selected face; of any other, the child face at each
/// selected corner, the two inner edges beside it and the face point.
pub(super) fn mark_faces(parent: &Level, sel: &Selection, edge_transitional: &[bool]) -> FaceMarks {
    if parent.face_vertices.uniform_size() == Some(4) {
        mark_faces_of::<true>(parent, sel, edge_transitional)
    } else {
        mark_faces_of::<false>(parent, sel, edge_transitional)
    }
}

/// [`mark_faces`], `QUADS` when every parent face is a quad with implicit
/// offsets (every level the quad split refined).
fn mark_faces_of<const QUADS: bool>(
    parent: &Level,
    sel: &Selection,
    edge_transitional: &[bool],
) -> FaceMarks {
    let faces = Faces::<QUADS>::of(parent);
    let (nf, corners) = (parent.face_count(), parent.face_vertices.members.len());
    // Faces: everything of a selected face; of any other, the child face at
    // each selected corner, the two inner edges beside it and the face point.
    // Every mark is written, marked or not (the tables are not cleared
    // first).
    let mut face_child_faces = Table::<u32>::for_overwrite(corners);
    let mut face_child_edges = Table::<u32>::for_overwrite(corners);
    let mut face_child_vertex = Table::<u32>::for_overwrite(nf);
    let mut face_transitional = Table::<u8>::zeroed(nf);
    let (child_faces, child_edges, child_vertex, transitional): (
        &mut [u32],
        &mut [u32],
        &mut [u32],
        &mut [u8],
    ) = (
        &mut face_child_faces,
        &mut face_child_edges,
        &mut face_child_vertex,
        &mut face_transitional,
    );
    for f in 0..nf {
        let range = faces.range(f);
        let n = range.len();
        let verts = &faces.verts[range.clone()];
        if sel.face(f) {
            child_faces[range.clone()].fill(MARKED);
            child_edges[range].fill(MARKED);
            child_vertex[f] = MARKED;
            continue;
        }
        let mut marked = false;
        for (j, &v) in verts.iter().enumerate() {
            let here = sel.vertex(v as usize);
            // The inner edge towards edge `j` lies beside corners `j` and
            // `j + 1`.
            let beside = here || sel.vertex(verts[next(j, n)] as usize);
            child_faces[range.start + j] = here as u32 * MARKED;
            child_edges[range.start + j] = beside as u32 * MARKED;
            marked |= here;
        }
        child_vertex[f] = marked as u32 * MARKED;
        if marked {
            let edges = &faces.edges[range];
            transitional[f] = if n <= 4 {
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
    if parent.face_vertices.uniform_size() == Some(4) {
        topology_of::<true>(parent, s)
    } else {
        topology_of::<false>(parent, s)
    }
}

/// [`topology`], `QUADS` when every parent face is a quad with implicit
/// offsets: a face's corners without its offsets, its size a constant.
fn topology_of<const QUADS: bool>(parent: &Level, split: &SparseSplit) -> Topology {
    let room = Room::transposes(
        split.child_face_parent.len(),
        4,
        split.child_edge_parent.len(),
    );
    child::fill_in(room, |room| fill::<QUADS>(parent, split, room))
}

/// [`topology_of`] with the filled relations in `room`, or the room they
/// need.
fn fill<const QUADS: bool>(
    parent: &Level,
    split: &SparseSplit,
    room: Room,
) -> Result<Topology, Room> {
    let faces = Faces::<QUADS>::of(parent);
    let nf = split.child_face_parent.len();
    let ne = split.child_edge_parent.len();
    let nv = split.child_vertex_parent.len();
    let (pv, s) = (parent.slices(), Numbering::of(split));
    let mut fills = Fills::new(ne, nv, room);
    let [mut edge_faces, mut vertex_faces, mut vertex_edges] = fills.fillers();
    // Face-vertices and face-edges.
    let mut face_vertices = Relation::uniform_for_overwrite(nf, 4);
    let mut face_edges = Table::for_overwrite(4 * nf);
    {
        let child_verts: &mut [u32] = &mut face_vertices.members;
        let child_edges: &mut [u32] = &mut face_edges;
        for f in 0..parent.face_count() {
            let range = faces.range(f);
            let n = range.len();
            let (verts, edges) = (&faces.verts[range.clone()], &faces.edges[range.clone()]);
            let children = &s.face_child_faces[range.clone()];
            let inner = &s.face_child_edges[range];
            for j in 0..n {
                let c = children[j];
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
                let [p0, p1] = pv.edge_vertices[e_prev];
                let in_prev = if p0 != p1 { (p0 != corner) as usize } else { 1 };
                let [n0, n1] = pv.edge_vertices[e_next];
                let in_next = if n0 != n1 { (n0 != corner) as usize } else { 0 };
                let es = [
                    s.edge_child_edges[e_next][in_next],
                    inner[j],
                    inner[jp],
                    s.edge_child_edges[e_prev][in_prev],
                ];
                // A quad's children keep its orientation: the corner's child
                // sits at position j.
                let rot = if n == 4 { j } else { 0 };
                let cv = &mut child_verts[c as usize * 4..c as usize * 4 + 4];
                let ce = &mut child_edges[c as usize * 4..c as usize * 4 + 4];
                for k in 0..4 {
                    cv[(rot + k) & 3] = vs[k];
                    ce[(rot + k) & 3] = es[k];
                }
            }
        }
    }

    // Edge-vertices and edge-faces, child edges in index order: those
    // inside faces, then the halves of edges.
    let mut edge_vertices = Table::<[u32; 2]>::for_overwrite(ne);
    let inner_edge_vertices: &mut [[u32; 2]] = &mut edge_vertices;
    for f in 0..parent.face_count() {
        let range = faces.range(f);
        let n = range.len();
        let edges = &faces.edges[range.clone()];
        let children = &s.face_child_faces[range.clone()];
        let inner = &s.face_child_edges[range];
        for (j, &edge) in edges.iter().enumerate() {
            let c = inner[j];
            if !valid(c) {
                continue;
            }
            inner_edge_vertices[c as usize] =
                [s.face_child_vertex[f], s.edge_child_vertex[edge as usize]];
            let jn = next(j, n);
            let here = children[j];
            if valid(here) {
                edge_faces.push(here, if n == 4 { jn } else { 1 });
            }
            let there = children[jn];
            if valid(there) {
                edge_faces.push(there, if n == 4 { (jn + 2) & 3 } else { 2 });
            }
            edge_faces.end();
        }
    }
    // Vertex-faces and vertex-edges, child vertices in index order.
    // The halves' edge-vertices and edge-faces are written in the same pass
    // over the parent's edges as the edge points' faces and edges (both in
    // parent edge order, the halves after the edges inside faces, the edge
    // points one contiguous block of child vertices): one walk of the
    // edges' faces instead of two.
    let mut c = 0;
    while c < nv {
        debug_assert_eq!(vertex_faces.elements(), c);
        match s.child_vertex_parent[c].get() {
            VertexParent::Face(f) => {
                let range = faces.range(f as usize);
                let n = range.len();
                let children = &s.face_child_faces[range.clone()];
                let inner = &s.face_child_edges[range];
                for j in 0..n {
                    let cf = children[j];
                    if valid(cf) {
                        vertex_faces.push(cf, if n == 4 { (j + 2) & 3 } else { 2 });
                    }
                    let lead = inner[prev(j, n)];
                    if valid(lead) {
                        vertex_edges.push(lead, 0);
                    }
                }
            }
            VertexParent::Edge(_) => {
                let points = edges_and_edge_points(
                    pv,
                    s,
                    faces,
                    &mut edge_vertices,
                    &mut edge_faces,
                    (&mut vertex_faces, &mut vertex_edges),
                );
                debug_assert!(
                    s.child_vertex_parent[c..c + points]
                        .iter()
                        .all(|p| matches!(p.get(), VertexParent::Edge(_)))
                );
                c += points;
                continue;
            }
            VertexParent::Vertex(v) => {
                child::vertex_point(
                    pv,
                    s,
                    v as usize,
                    (&mut vertex_faces, &mut vertex_edges),
                    |pf, k| {
                        let range = faces.range(pf);
                        let local = if range.len() == 4 { k } else { 0 };
                        (s.face_child_faces[range.start + k], local)
                    },
                );
            }
        }
        vertex_faces.end();
        vertex_edges.end();
        c += 1;
    }

    let done = [edge_faces, vertex_faces, vertex_edges].map(Filler::finish);
    fills.topology(done, face_vertices, face_edges, edge_vertices)
}

/// One pass over the parent's edges, in order: the edge-vertices and
/// edge-faces of each half that exists, then the faces and edges of the
/// edge point (every edge point: one exists exactly where a half does).
/// Returns the number of edge points ended.
fn edges_and_edge_points<const QUADS: bool>(
    parent: LevelSlices<'_>,
    s: Numbering<'_>,
    faces: Faces<'_, QUADS>,
    edge_vertices: &mut Table<[u32; 2]>,
    edge_faces: &mut Filler<'_>,
    (vertex_faces, vertex_edges): (&mut Filler<'_>, &mut Filler<'_>),
) -> usize {
    let child_edge_vertices: &mut [[u32; 2]] = edge_vertices;
    let half_face = |pf: usize, k: usize, j: usize, ends: [u32; 2]| {
        let range = faces.range(pf);
        let n = range.len();
        let end = child::half_end(ends, j, faces.verts[range.start + k]);
        let (corner, local) = if end == 0 {
            (k, if n == 4 { k } else { 0 })
        } else {
            (next(k, n), if n == 4 { k } else { 3 })
        };
        (s.face_child_faces[range.start + corner], local)
    };
    let mut points = 0;
    for e in 0..s.edge_child_edges.len() {
        // The halves (`edge_halves`).
        if !child::halves_of_edge(parent, s, e, child_edge_vertices, edge_faces, &half_face) {
            continue;
        }
        let (halves, ends) = (s.edge_child_edges[e], parent.edge_vertices[e]);
        let point = s.edge_child_vertex[e];
        let (pfaces, locals) = parent.edge_faces(e);
        // The edge point.
        debug_assert!(valid(point));
        // Its edges: [half, inner edge of the first face, half, inner
        // edges of the other faces], the halves as the edge runs in the
        // first face, when both halves and that inner edge exist; else the
        // halves that exist, then the inner edges. Chosen before pushing:
        // pushing and then swapping members just stored makes loads wait
        // on stores they cannot be forwarded from.
        let both = valid(halves[0]) && valid(halves[1]);
        if !both {
            for &half in &halves {
                if valid(half) {
                    vertex_edges.push(half, 0);
                }
            }
        }
        for (i, (&pf, &in_face)) in pfaces.iter().zip(locals).enumerate() {
            let (pf, in_face) = (pf as usize, in_face as usize);
            let range = faces.range(pf);
            let n = range.len();
            let (c0, c1) = (in_face, next(in_face, n));
            let children = &s.face_child_faces[range.clone()];
            let f1 = children[c1];
            if valid(f1) {
                vertex_faces.push(f1, if n == 4 { c0 } else { 3 });
            }
            let f0 = children[c0];
            if valid(f0) {
                vertex_faces.push(f0, if n == 4 { c1 } else { 1 });
            }
            let inner = s.face_child_edges[range.start + in_face];
            if i == 0 && both {
                if valid(inner) {
                    let against = ends[0] != ends[1] && faces.corner(pf, in_face) == ends[0];
                    let (a, b) = if against {
                        (halves[1], halves[0])
                    } else {
                        (halves[0], halves[1])
                    };
                    vertex_edges.push(a, 0);
                    vertex_edges.push(inner, 1);
                    vertex_edges.push(b, 0);
                } else {
                    vertex_edges.push(halves[0], 0);
                    vertex_edges.push(halves[1], 0);
                }
            } else if valid(inner) {
                vertex_edges.push(inner, 1);
            }
        }
        if both && pfaces.is_empty() {
            vertex_edges.push(halves[0], 0);
            vertex_edges.push(halves[1], 0);
        }
        vertex_faces.end();
        vertex_edges.end();
        points += 1;
    }
    points
}
