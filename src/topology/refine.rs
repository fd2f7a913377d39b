//! Splitting one level into the next, in OpenSubdiv's order.
//!
//! Children are numbered by where they come from:
//!
//! * child **faces**: parent face `f` with `n` vertices gives `n` quads
//!   (child `j` at corner `j`), numbered in parent face order;
//! * child **edges**: first the `n` edges inside each parent face (edge `j`
//!   joins the face point to the point of face-edge `j`), then two per parent
//!   edge (child `j` holds the end vertex `j`);
//! * child **vertices**: by default the children of vertices, then of faces,
//!   then of edges; with `order_vertices_from_faces_first`, faces, edges,
//!   then vertices.

use super::{EdgeTag, Level, Relation, VertexTag};
use crate::options::{CreasingMethod, Options, Scheme};
use crate::rules::{Rule, SHARPNESS_INFINITE, crease};

/// The parent-to-child numbering of one refinement step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Refinement {
    /// Number of parent vertices, edges, and faces with a face point (0 for Loop).
    pub parent_counts: [usize; 3],
    /// Number of parent face corners.
    pub parent_corners: usize,
    /// Index of the first child vertex of a parent vertex.
    pub first_vertex_from_vertices: u32,
    /// Index of the first child vertex of a parent face.
    pub first_vertex_from_faces: u32,
    /// Index of the first child vertex of a parent edge.
    pub first_vertex_from_edges: u32,
}

impl Refinement {
    /// Numbering for a parent level, default or faces-first vertex order.
    pub fn new(parent: &Level, faces_first: bool, face_points: bool) -> Self {
        let (nv, ne) = (parent.vertex_count, parent.edge_count());
        // Loop's triangle split has no face points.
        let nf = if face_points { parent.face_count() } else { 0 };
        let (fv, ff, fe) = if faces_first {
            ((nf + ne) as u32, 0, nf as u32)
        } else {
            (0, nv as u32, (nv + nf) as u32)
        };
        Refinement {
            parent_counts: [nv, ne, nf],
            parent_corners: parent.face_vertices.members.len(),
            first_vertex_from_vertices: fv,
            first_vertex_from_faces: ff,
            first_vertex_from_edges: fe,
        }
    }

    /// The child vertex of parent vertex `v`.
    #[inline]
    pub fn vertex_child(&self, v: usize) -> u32 {
        self.first_vertex_from_vertices + v as u32
    }

    /// Whether parent faces get a child vertex (false for Loop's triangle split).
    #[inline]
    pub fn has_face_points(&self) -> bool {
        self.parent_counts[2] > 0
    }

    /// The child vertex (face point) of parent face `f`.
    #[inline]
    pub fn face_child(&self, f: usize) -> u32 {
        self.first_vertex_from_faces + f as u32
    }

    /// The child vertex (edge point) of parent edge `e`.
    #[inline]
    pub fn edge_child(&self, e: usize) -> u32 {
        self.first_vertex_from_edges + e as u32
    }

    /// The child edge of parent edge `e` at its end `j`.
    #[inline]
    pub fn edge_child_edge(&self, e: usize, j: usize) -> u32 {
        (self.parent_corners + 2 * e + j) as u32
    }

    /// Number of child vertices.
    pub fn child_vertex_count(&self) -> usize {
        self.parent_counts.iter().sum()
    }
}

#[inline]
fn prev(j: usize, n: usize) -> usize {
    if j == 0 { n - 1 } else { j - 1 }
}

#[inline]
fn next(j: usize, n: usize) -> usize {
    if j + 1 == n { 0 } else { j + 1 }
}

/// Splits `parent` once — Catmull-Clark and bilinear: every face into quads;
/// Loop: every triangle into four — and returns the child level with all
/// relations, sharpness and tags.
///
/// With `minimal`, only the face-vertices of the child are built (with its
/// sharpness, tags and holes): what a last level needs for interpolation,
/// as OpenSubdiv builds it unless asked for full topology.
pub fn refine_level(
    parent: &Level,
    options: &Options,
    faces_first: bool,
    minimal: bool,
) -> (Refinement, Level) {
    if options.scheme == Scheme::Loop {
        return refine_triangles(parent, options, faces_first, minimal);
    }
    let r = Refinement::new(parent, faces_first, true);
    let (nv, ne, nf) = (
        parent.vertex_count,
        parent.edge_count(),
        parent.face_count(),
    );
    let corners = r.parent_corners;
    let child_faces = corners;
    let child_edges = corners + 2 * ne;
    let child_vertices = r.child_vertex_count();

    // Face-vertices and face-edges of the child quads.
    let mut face_vertices = Relation::uniform(child_faces, 4);
    let mut face_edges = if minimal {
        Vec::new()
    } else {
        vec![0u32; child_faces * 4]
    };
    for f in 0..nf {
        let base = parent.face_vertices.offsets[f] as usize;
        let verts = parent.face_verts(f);
        let edges = parent.face_edges_of(f);
        let n = verts.len();
        let fc = r.face_child(f);
        for j in 0..n {
            let jp = prev(j, n);
            let c = base + j;
            let (e_prev, e_next) = (edges[jp] as usize, edges[j] as usize);
            let corner = verts[j];
            let ev_prev = parent.edge_vertices[e_prev];
            let ev_next = parent.edge_vertices[e_next];
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
            let v4 = [
                r.vertex_child(corner as usize),
                r.edge_child(e_next),
                fc,
                r.edge_child(e_prev),
            ];
            let e4 = [
                r.edge_child_edge(e_next, in_next),
                (base + j) as u32,
                (base + jp) as u32,
                r.edge_child_edge(e_prev, in_prev),
            ];
            // A child of a quad keeps the parent's orientation: its corner
            // vertex sits at position j. Children of other faces start there.
            let rot = if n == 4 { j } else { 0 };
            for (k, &v) in v4.iter().enumerate() {
                face_vertices.members[4 * c + (rot + k) % 4] = v;
            }
            if !minimal {
                for (k, &e) in e4.iter().enumerate() {
                    face_edges[4 * c + (rot + k) % 4] = e;
                }
            }
        }
    }

    // Everything but the face-vertices is skipped for a minimal last level.
    let (
        edge_vertices,
        ef_offsets,
        ef_members,
        ef_local,
        vf_offsets,
        vf_members,
        vf_local,
        ve_offsets,
        ve_members,
        ve_local,
    ) = if minimal {
        Default::default()
    } else {
        // Edge-vertices: face edges join the face point to an edge point; edge
        // halves join the edge point to an end vertex's child.
        let mut edge_vertices = vec![[0u32; 2]; child_edges];
        for f in 0..nf {
            let base = parent.face_vertices.offsets[f] as usize;
            for (j, &e) in parent.face_edges_of(f).iter().enumerate() {
                edge_vertices[base + j] = [r.face_child(f), r.edge_child(e as usize)];
            }
        }
        for e in 0..ne {
            let ev = parent.edge_vertices[e];
            for j in 0..2 {
                edge_vertices[r.edge_child_edge(e, j) as usize] =
                    [r.edge_child(e), r.vertex_child(ev[j] as usize)];
            }
        }

        // Edge-faces.
        let mut ef_offsets = Vec::with_capacity(child_edges + 1);
        let mut ef_members = Vec::with_capacity(2 * corners + 2 * parent.edge_faces.members.len());
        let mut ef_local = Vec::with_capacity(ef_members.capacity());
        ef_offsets.push(0u32);
        for f in 0..nf {
            let base = parent.face_vertices.offsets[f] as usize;
            let n = parent.face_vertices.count(f);
            for j in 0..n {
                let jn = next(j, n);
                ef_members.push((base + j) as u32);
                ef_local.push(if n == 4 { jn } else { 1 } as u16);
                ef_members.push((base + jn) as u32);
                ef_local.push(if n == 4 { (jn + 2) & 3 } else { 2 } as u16);
                ef_offsets.push(ef_members.len() as u32);
            }
        }
        for e in 0..ne {
            let ev = parent.edge_vertices[e];
            for j in 0..2 {
                for (&f, &k) in parent
                    .edge_faces_of(e)
                    .iter()
                    .zip(parent.edge_face_locals(e))
                {
                    let (f, k) = (f as usize, k as usize);
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
                    ef_members.push(parent.face_vertices.offsets[f] + in_face as u32);
                    ef_local.push(if n == 4 {
                        k
                    } else if of_edge == 1 {
                        3
                    } else {
                        0
                    } as u16);
                }
                ef_offsets.push(ef_members.len() as u32);
            }
        }

        // Vertex-faces and vertex-edges, per child vertex, grouped by origin.
        let mut vf_count = vec![0u32; child_vertices];
        let mut ve_count = vec![0u32; child_vertices];
        for v in 0..nv {
            let c = r.vertex_child(v) as usize;
            vf_count[c] = parent.vertex_faces.count(v) as u32;
            ve_count[c] = parent.vertex_edges.count(v) as u32;
        }
        for f in 0..nf {
            let c = r.face_child(f) as usize;
            vf_count[c] = parent.face_vertices.count(f) as u32;
            ve_count[c] = parent.face_vertices.count(f) as u32;
        }
        for e in 0..ne {
            let c = r.edge_child(e) as usize;
            vf_count[c] = 2 * parent.edge_faces.count(e) as u32;
            ve_count[c] = 2 + parent.edge_faces.count(e) as u32;
        }
        let vf_offsets = prefix_sums(&vf_count);
        let ve_offsets = prefix_sums(&ve_count);
        let mut vf_members = vec![0u32; *vf_offsets.last().unwrap() as usize];
        let mut vf_local = vec![0u16; vf_members.len()];
        let mut ve_members = vec![0u32; *ve_offsets.last().unwrap() as usize];
        let mut ve_local = vec![0u16; ve_members.len()];

        for f in 0..nf {
            let c = r.face_child(f) as usize;
            let base = parent.face_vertices.offsets[f] as usize;
            let n = parent.face_vertices.count(f);
            let (o, oe) = (vf_offsets[c] as usize, ve_offsets[c] as usize);
            for j in 0..n {
                vf_members[o + j] = (base + j) as u32;
                vf_local[o + j] = if n == 4 { (j + 2) & 3 } else { 2 } as u16;
                ve_members[oe + j] = (base + prev(j, n)) as u32;
                ve_local[oe + j] = 0;
            }
        }
        let mut edge_list: Vec<(u32, u16)> = Vec::with_capacity(8);
        for e in 0..ne {
            let c = r.edge_child(e) as usize;
            let ev = parent.edge_vertices[e];
            let (mut o, oe) = (vf_offsets[c] as usize, ve_offsets[c] as usize);
            // The two halves first, then the edges inside each face; after the
            // first face the edges are rotated into counter-clockwise order.
            edge_list.clear();
            edge_list.push((r.edge_child_edge(e, 0), 0u16));
            edge_list.push((r.edge_child_edge(e, 1), 0u16));
            for (i, (&f, &k)) in parent
                .edge_faces_of(e)
                .iter()
                .zip(parent.edge_face_locals(e))
                .enumerate()
            {
                let (f, k) = (f as usize, k as usize);
                let n = parent.face_vertices.count(f);
                let base = parent.face_vertices.offsets[f];
                let (c0, c1) = (k, next(k, n));
                vf_members[o] = base + c1 as u32;
                vf_local[o] = if n == 4 { c0 } else { 3 } as u16;
                vf_members[o + 1] = base + c0 as u32;
                vf_local[o + 1] = if n == 4 { c1 } else { 1 } as u16;
                o += 2;
                edge_list.push((base + k as u32, 1));
                if i == 0 {
                    if ev[0] != ev[1] && parent.face_verts(f)[k] == ev[0] {
                        edge_list.swap(0, 1);
                    }
                    edge_list.swap(1, 2);
                }
            }
            for (i, &(m, l)) in edge_list.iter().enumerate() {
                ve_members[oe + i] = m;
                ve_local[oe + i] = l;
            }
        }
        for v in 0..nv {
            let c = r.vertex_child(v) as usize;
            let (o, oe) = (vf_offsets[c] as usize, ve_offsets[c] as usize);
            for (i, (&f, &k)) in parent
                .vertex_faces_of(v)
                .iter()
                .zip(parent.vertex_face_locals(v))
                .enumerate()
            {
                let n = parent.face_vertices.count(f as usize);
                vf_members[o + i] = parent.face_vertices.offsets[f as usize] + k as u32;
                vf_local[o + i] = if n == 4 { k } else { 0 };
            }
            for (i, (&e, &l)) in parent
                .vertex_edges_of(v)
                .iter()
                .zip(parent.vertex_edge_locals(v))
                .enumerate()
            {
                ve_members[oe + i] = r.edge_child_edge(e as usize, l as usize);
                ve_local[oe + i] = 1;
            }
        }
        (
            edge_vertices,
            ef_offsets,
            ef_members,
            ef_local,
            vf_offsets,
            vf_members,
            vf_local,
            ve_offsets,
            ve_members,
            ve_local,
        )
    };

    let child = assemble_child(
        parent,
        &r,
        options,
        Parts {
            vertex_count: child_vertices,
            face_vertices,
            face_edges,
            edge_vertices,
            edge_faces: Relation {
                offsets: ef_offsets,
                members: ef_members,
            },
            edge_face_local: ef_local,
            vertex_faces: Relation {
                offsets: vf_offsets,
                members: vf_members,
            },
            vertex_face_local: vf_local,
            vertex_edges: Relation {
                offsets: ve_offsets,
                members: ve_members,
            },
            vertex_edge_local: ve_local,
            num_edges: child_edges,
            face_holes: parent
                .face_holes
                .iter()
                .enumerate()
                .flat_map(|(f, &h)| std::iter::repeat_n(h, parent.face_vertices.count(f)))
                .collect(),
            max_valence: parent.max_valence.max(4).max(2 + parent.max_edge_faces),
        },
        minimal,
    );
    (r, child)
}

/// Triangle split (Loop): child faces `4f..4f+4` of triangle `f` are the three
/// corner triangles (child `j` at corner `j`) and the middle one; child edges
/// are the three inside each face, then two per parent edge.
fn refine_triangles(
    parent: &Level,
    options: &Options,
    faces_first: bool,
    minimal: bool,
) -> (Refinement, Level) {
    let r = Refinement::new(parent, faces_first, false);
    let (nv, ne, nf) = (
        parent.vertex_count,
        parent.edge_count(),
        parent.face_count(),
    );
    let corners = r.parent_corners;
    let child_faces = 4 * nf;
    let child_edges = corners + 2 * ne;
    let child_vertices = r.child_vertex_count();
    let inner_edge = |f: usize, j: usize| (3 * f + j) as u32;

    let mut face_vertices = Relation::uniform(child_faces, 3);
    // A minimal last level needs neither face-edges nor edge-vertices.
    let (mut face_edges, mut edge_vertices) = if minimal {
        (Vec::new(), Vec::new())
    } else {
        (vec![0u32; child_faces * 3], vec![[0u32; 2]; child_edges])
    };
    for f in 0..nf {
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
        for (k, tri) in tris.iter().enumerate() {
            face_vertices.members[3 * (4 * f + k)..3 * (4 * f + k) + 3].copy_from_slice(tri);
        }
        if minimal {
            continue;
        }
        for (k, e) in edges.iter().enumerate() {
            face_edges[3 * (4 * f + k)..3 * (4 * f + k) + 3].copy_from_slice(e);
        }
        edge_vertices[3 * f] = [ep(0), ep(2)];
        edge_vertices[3 * f + 1] = [ep(1), ep(0)];
        edge_vertices[3 * f + 2] = [ep(2), ep(1)];
    }
    if !minimal {
        for e in 0..ne {
            let ev = parent.edge_vertices[e];
            for j in 0..2 {
                edge_vertices[r.edge_child_edge(e, j) as usize] =
                    [r.edge_child(e), r.vertex_child(ev[j] as usize)];
            }
        }
    }

    // Everything but the face-vertices is skipped for a minimal last level.
    let (
        ef_offsets,
        ef_members,
        ef_local,
        vf_offsets,
        vf_members,
        vf_local,
        ve_offsets,
        ve_members,
        ve_local,
    ) = if minimal {
        Default::default()
    } else {
        // Edge-faces.
        let mut ef_offsets = Vec::with_capacity(child_edges + 1);
        let mut ef_members = Vec::with_capacity(2 * corners + 2 * parent.edge_faces.members.len());
        let mut ef_local = Vec::with_capacity(ef_members.capacity());
        ef_offsets.push(0u32);
        for f in 0..nf {
            for j in 0..3 {
                let l = ((j + 1) % 3) as u16;
                ef_members.extend([(4 * f + j) as u32, (4 * f + 3) as u32]);
                ef_local.extend([l, l]);
                ef_offsets.push(ef_members.len() as u32);
            }
        }
        for e in 0..ne {
            let ev = parent.edge_vertices[e];
            for j in 0..2 {
                for (&f, &k) in parent
                    .edge_faces_of(e)
                    .iter()
                    .zip(parent.edge_face_locals(e))
                {
                    let (f, k) = (f as usize, k as usize);
                    let of_edge = if ev[0] == ev[1] {
                        j
                    } else {
                        (parent.face_verts(f)[k] != ev[j]) as usize
                    };
                    let in_face = (k + of_edge) % 3;
                    ef_members.push((4 * f + in_face) as u32);
                    ef_local.push(k as u16);
                }
                ef_offsets.push(ef_members.len() as u32);
            }
        }

        // Vertex-faces and vertex-edges.
        let mut vf_count = vec![0u32; child_vertices];
        let mut ve_count = vec![0u32; child_vertices];
        for v in 0..nv {
            let c = r.vertex_child(v) as usize;
            vf_count[c] = parent.vertex_faces.count(v) as u32;
            ve_count[c] = parent.vertex_edges.count(v) as u32;
        }
        for e in 0..ne {
            let c = r.edge_child(e) as usize;
            vf_count[c] = 3 * parent.edge_faces.count(e) as u32;
            ve_count[c] = 2 + 2 * parent.edge_faces.count(e) as u32;
        }
        let vf_offsets = prefix_sums(&vf_count);
        let ve_offsets = prefix_sums(&ve_count);
        let mut vf_members = vec![0u32; *vf_offsets.last().unwrap() as usize];
        let mut vf_local = vec![0u16; vf_members.len()];
        let mut ve_members = vec![0u32; *ve_offsets.last().unwrap() as usize];
        let mut ve_local = vec![0u16; ve_members.len()];
        for e in 0..ne {
            let c = r.edge_child(e) as usize;
            let ev = parent.edge_vertices[e];
            let (mut o, mut oe) = (vf_offsets[c] as usize, ve_offsets[c] as usize);
            let mut last_half = None;
            for (i, (&f, &k)) in parent
                .edge_faces_of(e)
                .iter()
                .zip(parent.edge_face_locals(e))
                .enumerate()
            {
                let (f, k) = (f as usize, k as usize);
                // Leading, middle and trailing child triangles around the edge point.
                for (child, local) in [((k + 1) % 3, k), (3, (k + 2) % 3), (k, (k + 1) % 3)] {
                    vf_members[o] = (4 * f + child) as u32;
                    vf_local[o] = local as u16;
                    o += 1;
                }
                if i == 0 {
                    let reversed = ev[0] != ev[1] && parent.face_verts(f)[k] != ev[0];
                    let (first, second) = if reversed { (0, 1) } else { (1, 0) };
                    ve_members[oe] = r.edge_child_edge(e, first);
                    ve_local[oe] = 0;
                    oe += 1;
                    last_half = Some(r.edge_child_edge(e, second));
                }
                ve_members[oe] = inner_edge(f, (k + 1) % 3);
                ve_local[oe] = 1;
                ve_members[oe + 1] = inner_edge(f, k);
                ve_local[oe + 1] = 0;
                oe += 2;
                if let Some(h) = last_half.take() {
                    ve_members[oe] = h;
                    ve_local[oe] = 0;
                    oe += 1;
                }
            }
        }
        for v in 0..nv {
            let c = r.vertex_child(v) as usize;
            let (o, oe) = (vf_offsets[c] as usize, ve_offsets[c] as usize);
            for (i, (&f, &k)) in parent
                .vertex_faces_of(v)
                .iter()
                .zip(parent.vertex_face_locals(v))
                .enumerate()
            {
                vf_members[o + i] = 4 * f + k as u32;
                vf_local[o + i] = k;
            }
            for (i, (&e, &l)) in parent
                .vertex_edges_of(v)
                .iter()
                .zip(parent.vertex_edge_locals(v))
                .enumerate()
            {
                ve_members[oe + i] = r.edge_child_edge(e as usize, l as usize);
                ve_local[oe + i] = 1;
            }
        }
        (
            ef_offsets, ef_members, ef_local, vf_offsets, vf_members, vf_local, ve_offsets,
            ve_members, ve_local,
        )
    };

    let child = assemble_child(
        parent,
        &r,
        options,
        Parts {
            vertex_count: child_vertices,
            face_vertices,
            face_edges,
            edge_vertices,
            edge_faces: Relation {
                offsets: ef_offsets,
                members: ef_members,
            },
            edge_face_local: ef_local,
            vertex_faces: Relation {
                offsets: vf_offsets,
                members: vf_members,
            },
            vertex_face_local: vf_local,
            vertex_edges: Relation {
                offsets: ve_offsets,
                members: ve_members,
            },
            vertex_edge_local: ve_local,
            num_edges: child_edges,
            face_holes: parent.face_holes.iter().flat_map(|&h| [h; 4]).collect(),
            max_valence: parent.max_valence.max(6).max(2 + 2 * parent.max_edge_faces),
        },
        minimal,
    );
    (r, child)
}

/// The tables of a child level built by a split, before tags and sharpness.
struct Parts {
    vertex_count: usize,
    face_vertices: Relation,
    face_edges: Vec<u32>,
    edge_vertices: Vec<[u32; 2]>,
    edge_faces: Relation,
    edge_face_local: Vec<u16>,
    vertex_faces: Relation,
    vertex_face_local: Vec<u16>,
    vertex_edges: Relation,
    vertex_edge_local: Vec<u16>,
    num_edges: usize,
    face_holes: Vec<bool>,
    max_valence: usize,
}

/// The child level from its tables: tags and sharpness propagated from the
/// parent. A minimal level keeps only face-vertices, vertex sharpness and tags.
fn assemble_child(
    parent: &Level,
    r: &Refinement,
    options: &Options,
    p: Parts,
    minimal: bool,
) -> Level {
    let mut child = Level {
        depth: parent.depth + 1,
        vertex_count: p.vertex_count,
        face_vertices: p.face_vertices,
        face_edges: if minimal { Vec::new() } else { p.face_edges },
        edge_vertices: if minimal { Vec::new() } else { p.edge_vertices },
        edge_faces: p.edge_faces,
        edge_face_local: p.edge_face_local,
        vertex_faces: p.vertex_faces,
        vertex_face_local: p.vertex_face_local,
        vertex_edges: p.vertex_edges,
        vertex_edge_local: p.vertex_edge_local,
        num_edges: p.num_edges,
        edge_sharpness: if minimal {
            Vec::new()
        } else {
            vec![0.0; p.num_edges]
        },
        vertex_sharpness: vec![0.0; p.vertex_count],
        edge_tags: if minimal {
            Vec::new()
        } else {
            vec![EdgeTag::default(); p.num_edges]
        },
        vertex_tags: vec![VertexTag::default(); p.vertex_count],
        face_holes: p.face_holes,
        max_edge_faces: parent.max_edge_faces.max(2),
        max_valence: p.max_valence,
    };
    propagate_tags(parent, &mut child, r);
    subdivide_sharpness(parent, &mut child, r, options.creasing);
    child
}

fn prefix_sums(counts: &[u32]) -> Vec<u32> {
    let mut offsets = Vec::with_capacity(counts.len() + 1);
    offsets.push(0u32);
    let mut acc = 0;
    for &c in counts {
        acc += c;
        offsets.push(acc);
    }
    offsets
}

/// Child tags: faces inherit holes (done by the caller), edge halves inherit
/// their parent edge's tags, edges inside faces are smooth, face points are
/// smooth, edge points take their rule from the parent edge, and children of
/// vertices inherit their parent's tags.
fn propagate_tags(parent: &Level, child: &mut Level, r: &Refinement) {
    let store_edges = !child.edge_tags.is_empty();
    for e in 0..parent.edge_count() {
        let t = parent.edge_tags[e];
        if store_edges {
            child.edge_tags[r.edge_child_edge(e, 0) as usize] = t;
            child.edge_tags[r.edge_child_edge(e, 1) as usize] = t;
        }
        let sharp = t.semi_sharp || t.inf_sharp;
        child.vertex_tags[r.edge_child(e) as usize] = VertexTag {
            non_manifold: t.non_manifold,
            boundary: t.boundary,
            semi_sharp_edges: t.semi_sharp,
            inf_sharp_edges: t.inf_sharp,
            rule: if sharp { Rule::Crease } else { Rule::Smooth },
            ..VertexTag::default()
        };
    }
    for v in 0..parent.vertex_count {
        child.vertex_tags[r.vertex_child(v) as usize] = parent.vertex_tags[v];
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
    let mut tag = parent.edge_tags[e];
    if tag.inf_sharp {
        return (SHARPNESS_INFINITE, tag);
    }
    if !tag.semi_sharp {
        return (0.0, tag);
    }
    let ps = parent.edge_sharpness[e];
    let s = match method {
        CreasingMethod::Uniform => crease::subdivide_uniform_sharpness(ps),
        CreasingMethod::Chaikin => {
            let pv = parent.edge_vertices[e][j] as usize;
            around.clear();
            around.extend(
                parent
                    .vertex_edges_of(pv)
                    .iter()
                    .map(|&x| parent.edge_sharpness[x as usize]),
            );
            crease::subdivide_edge_sharpness_at_vertex(method, ps, around)
        }
    };
    if !crease::is_sharp(s) {
        tag.semi_sharp = false;
    }
    (s, tag)
}

/// The sharpness of every edge of a child level (edges inside parent faces
/// are smooth): what a minimal last level does not store.
pub fn child_edge_sharpness(
    parent: &Level,
    r: &Refinement,
    method: CreasingMethod,
    child_edges: usize,
) -> Vec<f32> {
    let mut out = vec![0.0; child_edges];
    let mut around = Vec::new();
    for e in 0..parent.edge_count() {
        for j in 0..2 {
            out[r.edge_child_edge(e, j) as usize] = child_edge(parent, e, j, method, &mut around).0;
        }
    }
    out
}

/// Edge and vertex sharpness of the child level, then the rules of child
/// vertices whose neighbourhood was semi-sharp. A minimal child stores no
/// edge sharpness or tags: they are recomputed where the rules need them.
fn subdivide_sharpness(parent: &Level, child: &mut Level, r: &Refinement, method: CreasingMethod) {
    let mut around = Vec::new();
    let store_edges = !child.edge_tags.is_empty();
    if store_edges {
        for e in 0..parent.edge_count() {
            if !parent.edge_tags[e].semi_sharp && !parent.edge_tags[e].inf_sharp {
                continue;
            }
            for j in 0..2 {
                let c = r.edge_child_edge(e, j) as usize;
                let (s, tag) = child_edge(parent, e, j, method, &mut around);
                child.edge_sharpness[c] = s;
                child.edge_tags[c] = tag;
            }
        }
    }
    let edge_semi = |e: usize, j: usize, around: &mut Vec<f32>, child: &Level| -> EdgeTag {
        if store_edges {
            child.edge_tags[r.edge_child_edge(e, j) as usize]
        } else {
            child_edge(parent, e, j, method, around).1
        }
    };
    for v in 0..parent.vertex_count {
        let c = r.vertex_child(v) as usize;
        let tag = &mut child.vertex_tags[c];
        if tag.inf_sharp {
            child.vertex_sharpness[c] = SHARPNESS_INFINITE;
        } else if tag.semi_sharp {
            let s = crease::subdivide_vertex_sharpness(parent.vertex_sharpness[v]);
            child.vertex_sharpness[c] = s;
            if !crease::is_sharp(s) {
                tag.semi_sharp = false;
            }
        }
    }
    // Edge points of semi-sharp edges: Crease while a half stays sharp.
    for e in 0..parent.edge_count() {
        let c = r.edge_child(e) as usize;
        if !child.vertex_tags[c].semi_sharp_edges {
            continue;
        }
        let count = (0..2)
            .filter(|&j| edge_semi(e, j, &mut around, child).semi_sharp)
            .count();
        let tag = &mut child.vertex_tags[c];
        tag.semi_sharp_edges = count > 0;
        tag.rule = crease::vertex_rule_from_sharp_edge_count(0.0, count);
    }
    // Children of vertices whose semi-sharp features may have decayed.
    for v in 0..parent.vertex_count {
        let p = parent.vertex_tags[v];
        if !p.semi_sharp && !p.semi_sharp_edges {
            continue;
        }
        let c = r.vertex_child(v) as usize;
        let decayed = p.semi_sharp && !child.vertex_tags[c].semi_sharp;
        if p.semi_sharp_edges || decayed {
            // The child's edges are the halves of the parent's edges at this
            // vertex (found through the parent: the child level may be minimal).
            let (mut inf, mut semi) = (0, 0);
            for (&e, &l) in parent
                .vertex_edges_of(v)
                .iter()
                .zip(parent.vertex_edge_locals(v))
            {
                let t = edge_semi(e as usize, l as usize, &mut around, child);
                inf += t.inf_sharp as usize;
                semi += t.semi_sharp as usize;
            }
            let tag = &mut child.vertex_tags[c];
            tag.semi_sharp_edges = semi > 0;
            if !tag.semi_sharp && !tag.inf_sharp {
                tag.rule = crease::vertex_rule_from_sharp_edge_count(0.0, inf + semi);
            }
        }
    }
}
