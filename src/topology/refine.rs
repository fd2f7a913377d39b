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

use super::{EdgeTag, Level, Offsets, Relation, Table, VertexTag};
use crate::options::{CreasingMethod, Options, Scheme};
use crate::rules::{Rule, SHARPNESS_INFINITE, crease};
use rayon::prelude::*;

/// The parent-to-child numbering of one refinement step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Split {
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

impl Split {
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
        Split {
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

/// How much of a child level [`refine_level`] builds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Build {
    /// Every relation, with local indices: a level that is refined further
    /// into a full level, or that face-varying channels or limit evaluation
    /// read.
    Full,
    /// Every relation but the positions of edges and vertices within their
    /// faces (`edge_face_local` and `vertex_face_local` stay empty): a level
    /// whose only child is a minimal last level. Interpolation does not read
    /// them; only building a full child, face-varying refinement and limit
    /// evaluation do. `vertex_edge_local` stays when the parent has
    /// sharpness: the decay of semi-sharp features into the child reads it.
    /// Where the parent is smooth everywhere (no sharpness, no tags, two
    /// faces on every edge), the vertex-faces, vertex-edges and edge-faces
    /// are left out too and derived from the parent when interpolation reads
    /// them ([`Level::derived_relations`]).
    Relations,
    /// Only the face-vertices (with sharpness, tags and holes): what a last
    /// level needs for interpolation, as OpenSubdiv builds it unless asked
    /// for full topology.
    Minimal,
}

impl Build {
    /// What level `level` of a refinement to `last` builds, when the last
    /// level is `minimal` or not.
    pub fn for_level(level: usize, last: usize, minimal: bool) -> Build {
        if level == last && minimal {
            Build::Minimal
        } else if level + 1 == last && minimal {
            Build::Relations
        } else {
            Build::Full
        }
    }
}

/// Splits `parent` once — Catmull-Clark and bilinear: every face into quads;
/// Loop: every triangle into four — and returns the child level with as
/// much topology as `build` says, its sharpness and tags.
pub fn refine_level(
    parent: &Level,
    options: &Options,
    faces_first: bool,
    build: Build,
) -> (Split, Level) {
    let minimal = build == Build::Minimal;
    let locals = build == Build::Full;
    if options.scheme == Scheme::Loop {
        return refine_triangles(parent, options, faces_first, minimal, locals);
    }
    let r = Split::new(parent, faces_first, true);
    let derive = build == Build::Relations && vertex_relations_derivable(parent);
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
            let mut edge_vertices = Vec::with_capacity(child_edges);
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
            // Vertex-faces and vertex-edges, per child vertex, by origin: a
            // face point has one face and one edge per corner, an edge point
            // two faces per parent face and two edges more.
            let ef_members = parent.edge_faces.members.len();
            let (vf, ve) = vertex_relation_writers(
                parent,
                &r,
                parent.vertex_faces.members.len() + corners + 2 * ef_members,
                parent.vertex_edges.members.len() + corners + 2 * ne + ef_members,
                locals,
            );
            let face_children = |vf: &mut TableWriter, ve: &mut TableWriter| {
                for f in 0..nf {
                    quad_face_child(parent, f, vf, ve);
                    vf.end_element();
                    ve.end_element();
                }
            };
            let edge_children = |vf: &mut TableWriter, ve: &mut TableWriter| {
                let mut edge_list = Vec::with_capacity(8);
                for e in 0..ne {
                    quad_edge_child(parent, &r, e, vf, ve, &mut edge_list);
                    vf.end_element();
                    ve.end_element();
                }
            };
            let vertex_children = |vf: &mut TableWriter, ve: &mut TableWriter| {
                for v in 0..parent.vertex_count {
                    quad_vertex_child(parent, &r, v, vf, ve);
                    vf.end_element();
                    ve.end_element();
                }
            };
            fill_vertex_relations(&r, vf, ve, face_children, edge_children, vertex_children)
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
    let tags_part = || ChildTags::new(parent, &r, options, child_vertices, child_edges, minimal);
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

/// Parent faces per parallel task.
const FACE_CHUNK: usize = 2048;

/// Splits `out`, holding `per_corner` values for every parent face corner,
/// into chunks of consecutive parent faces: (face range, its values).
fn carve_by_faces<'a, T>(
    out: &'a mut [T],
    parent: &Level,
    per_corner: usize,
) -> Vec<(std::ops::Range<usize>, &'a mut [T])> {
    let nf = parent.face_count();
    let faces = &parent.face_vertices;
    let mut chunks = Vec::with_capacity(nf.div_ceil(FACE_CHUNK));
    let mut rest = out;
    let mut f0 = 0;
    while f0 < nf {
        let f1 = (f0 + FACE_CHUNK).min(nf);
        let len = (faces.start(f1) - faces.start(f0)) * per_corner;
        let (chunk, tail) = std::mem::take(&mut rest).split_at_mut(len);
        chunks.push((f0..f1, chunk));
        rest = tail;
        f0 = f1;
    }
    chunks
}

/// Triangle split (Loop): child faces `4f..4f+4` of triangle `f` are the three
/// corner triangles (child `j` at corner `j`) and the middle one; child edges
/// are the three inside each face, then two per parent edge.
fn refine_triangles(
    parent: &Level,
    options: &Options,
    faces_first: bool,
    minimal: bool,
    locals: bool,
) -> (Split, Level) {
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
            // Vertex-faces and vertex-edges: an edge point has three child
            // triangles and two inner edges per parent face, and two halves.
            let ef_members = parent.edge_faces.members.len();
            let (vf, ve) = vertex_relation_writers(
                parent,
                &r,
                parent.vertex_faces.members.len() + 3 * ef_members,
                parent.vertex_edges.members.len() + 2 * ne + 2 * ef_members,
                locals,
            );
            let edge_children = |vf: &mut TableWriter, ve: &mut TableWriter| {
                for e in 0..ne {
                    triangle_edge_child(parent, &r, e, vf, ve);
                    vf.end_element();
                    ve.end_element();
                }
            };
            let vertex_children = |vf: &mut TableWriter, ve: &mut TableWriter| {
                for v in 0..parent.vertex_count {
                    triangle_vertex_child(parent, &r, v, vf, ve);
                    vf.end_element();
                    ve.end_element();
                }
            };
            fill_vertex_relations(&r, vf, ve, |_, _| {}, edge_children, vertex_children)
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
    let tags_part = || ChildTags::new(parent, &r, options, child_vertices, child_edges, minimal);
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

/// The relations of a full child level beyond its faces (all empty in a
/// minimal one).
#[derive(Default)]
struct ChildRelations {
    edge_vertices: Table<[u32; 2]>,
    edge_faces: Relation,
    edge_face_local: Table<u16>,
    vertex_faces: Relation,
    vertex_face_local: Table<u16>,
    vertex_edges: Relation,
    vertex_edge_local: Table<u16>,
}

/// The tables of a child level built by a split, before tags and sharpness.
struct Parts {
    vertex_count: usize,
    face_vertices: Relation,
    face_edges: Table<u32>,
    relations: ChildRelations,
    num_edges: usize,
    face_holes: Vec<bool>,
    /// Vertex relations left out, derived from the parent when read.
    derived_relations: bool,
    max_valence: usize,
}

/// The sharpness and tags of a child level, propagated from its parent; built
/// alongside (and independently of) the child's relations.
pub(crate) struct ChildTags {
    edge_sharpness: Table<f32>,
    vertex_sharpness: Table<f32>,
    edge_tags: Table<EdgeTag>,
    vertex_tags: Table<VertexTag>,
}

impl ChildTags {
    /// A minimal child stores no edge sharpness or tags. Like sharpness, the
    /// tag tables stay empty while every tag is the default: a parent storing
    /// no tags (a smooth closed mesh) passes none on, and tags that decay
    /// back to the default are dropped.
    fn new(
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

/// The child level from its tables and its tags. A minimal level keeps only
/// face-vertices, vertex sharpness and tags.
fn assemble_child(parent: &Level, tags: ChildTags, p: Parts) -> Level {
    Level {
        depth: parent.depth + 1,
        vertex_count: p.vertex_count,
        face_vertices: p.face_vertices,
        face_edges: p.face_edges,
        edge_vertices: p.relations.edge_vertices,
        edge_faces: p.relations.edge_faces,
        edge_face_local: p.relations.edge_face_local,
        vertex_faces: p.relations.vertex_faces,
        vertex_face_local: p.relations.vertex_face_local,
        vertex_edges: p.relations.vertex_edges,
        vertex_edge_local: p.relations.vertex_edge_local,
        num_edges: p.num_edges,
        edge_sharpness: tags.edge_sharpness,
        vertex_sharpness: tags.vertex_sharpness,
        edge_tags: tags.edge_tags,
        vertex_tags: tags.vertex_tags,
        face_holes: p.face_holes,
        derived_relations: p.derived_relations,
        max_edge_faces: parent.max_edge_faces.max(2),
        max_valence: p.max_valence,
    }
}

/// Each child face inherits its parent's hole flag. Children come in parent
/// order: one per parent corner (quad split) or four per triangle (Loop).
/// Empty (no hole) when the parent stores no hole flags or its holes have
/// no children.
fn child_holes(parent: &Level, child_faces: usize, four_per_face: bool) -> Vec<bool> {
    if parent.face_holes.is_empty() {
        return Vec::new();
    }
    let mut holes = vec![false; child_faces];
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

/// The writers of a child level's vertex-faces and vertex-edges (`vf` and
/// `ve` members in all), filled one child vertex after the other by
/// [`fill_vertex_relations`]. Vertex-face local indices are kept when
/// `locals`; which end of its edges a vertex is, when `locals` too or when
/// the parent has sharpness: building a minimal child reads it only in the
/// sharpness decay, and only at semi-sharp features, which the child can
/// have only if its parent has sharpness (it decays; it never appears).
fn vertex_relation_writers(
    parent: &Level,
    r: &Split,
    vf: usize,
    ve: usize,
    locals: bool,
) -> (TableWriter, TableWriter) {
    let n = r.child_vertex_count();
    let edge_ends =
        locals || !parent.edge_sharpness.is_empty() || !parent.vertex_sharpness.is_empty();
    (
        TableWriter::new(n, vf, None, locals),
        TableWriter::new(n, ve, None, edge_ends),
    )
}

/// A child level's vertex-faces and vertex-edges, with their local indices:
/// the children of parent faces, edges and vertices — each filler closing
/// one element of both writers per child, in the order of its parents — are
/// written in the order of the child vertices' indices.
fn fill_vertex_relations(
    r: &Split,
    mut vf: TableWriter,
    mut ve: TableWriter,
    mut face_children: impl FnMut(&mut TableWriter, &mut TableWriter),
    mut edge_children: impl FnMut(&mut TableWriter, &mut TableWriter),
    mut vertex_children: impl FnMut(&mut TableWriter, &mut TableWriter),
) -> ((Relation, Table<u16>), (Relation, Table<u16>)) {
    let mut origins = [
        (r.first_vertex_from_faces, 0),
        (r.first_vertex_from_edges, 1),
        (r.first_vertex_from_vertices, 2),
    ];
    // Equal starts only come with empty ranges; the order then does not matter.
    origins.sort_unstable();
    for (_, origin) in origins {
        match origin {
            0 => face_children(&mut vf, &mut ve),
            1 => edge_children(&mut vf, &mut ve),
            _ => vertex_children(&mut vf, &mut ve),
        }
    }
    (vf.finish(), ve.finish())
}

/// Where the members of one child vertex's relations go, with their local
/// indices: a [`TableWriter`] building a level, or a buffer of members
/// deriving one vertex's relations on demand ([`derive_vertex_relations`]).
trait Sink {
    fn push(&mut self, member: u32, local: u16);
}

impl Sink for TableWriter {
    #[inline(always)]
    fn push(&mut self, member: u32, local: u16) {
        TableWriter::push(self, member, local);
    }
}

impl Sink for Vec<u32> {
    #[inline(always)]
    fn push(&mut self, member: u32, _: u16) {
        Vec::push(self, member);
    }
}

/// The vertex-faces and vertex-edges of the child of parent vertex `v`: the
/// child faces at the vertex's corners (`child_face(f, k)` gives the child
/// of face `f` at corner `k` and the vertex's position in it) and the halves
/// of its edges at its end (where the child vertex is end 1).
#[inline(always)]
fn vertex_child_relations(
    parent: &Level,
    r: &Split,
    v: usize,
    vf: &mut impl Sink,
    ve: &mut impl Sink,
    child_face: impl Fn(u32, u16) -> (u32, u16),
) {
    for (&f, &k) in parent
        .vertex_faces_of(v)
        .iter()
        .zip(parent.vertex_face_locals(v))
    {
        let (member, local) = child_face(f, k);
        vf.push(member, local);
    }
    for (&e, &l) in parent
        .vertex_edges_of(v)
        .iter()
        .zip(parent.vertex_edge_locals(v))
    {
        ve.push(r.edge_child_edge(e as usize, l as usize), 1);
    }
}

/// Quad split: the face point of parent face `f` has one child face and one
/// child edge per corner.
#[inline(always)]
fn quad_face_child(parent: &Level, f: usize, vf: &mut impl Sink, ve: &mut impl Sink) {
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
fn quad_edge_child(
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
fn quad_vertex_child(parent: &Level, r: &Split, v: usize, vf: &mut impl Sink, ve: &mut impl Sink) {
    vertex_child_relations(parent, r, v, vf, ve, |f, k| {
        let n = parent.face_vertices.count(f as usize);
        let local = if n == 4 { k } else { 0 };
        (
            parent.face_vertices.start(f as usize) as u32 + k as u32,
            local,
        )
    });
}

/// Triangle split: the edge point of parent edge `e` has three child
/// triangles and two inner edges per parent face, and the two halves.
#[inline(always)]
fn triangle_edge_child(
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
fn triangle_vertex_child(
    parent: &Level,
    r: &Split,
    v: usize,
    vf: &mut impl Sink,
    ve: &mut impl Sink,
) {
    vertex_child_relations(parent, r, v, vf, ve, |f, k| (4 * f + k as u32, k));
}

/// Whether a child of `parent` built as [`Build::Relations`] can leave out
/// its vertex-faces, vertex-edges and edge-faces, to be derived from
/// `parent` when read ([`derive_vertex_relations`], [`derive_edge_faces`]):
/// `parent` has its local indices, no
/// sharpness and no tags (every vertex smooth and manifold, no boundary),
/// and two faces on every edge. Then every vertex of the child is smooth
/// with as many faces as edges, every edge has two faces, and nothing but
/// interpolating the minimal last level reads these relations.
fn vertex_relations_derivable(parent: &Level) -> bool {
    parent.has_local_indices()
        && parent.vertex_tags.is_empty()
        && parent.edge_tags.is_empty()
        && parent.edge_sharpness.is_empty()
        && parent.vertex_sharpness.is_empty()
        && parent.edge_faces.uniform_size() == Some(2)
}

/// The faces and edges of vertex `c` of a level split from `parent` by `r`
/// (`triangles`: Loop's triangle split; otherwise the quad split), in the
/// order the level would store them, for a level built without them
/// ([`Level::derived_relations`]). `edge_list` is scratch space.
pub(crate) fn derive_vertex_relations(
    parent: &Level,
    r: &Split,
    triangles: bool,
    c: usize,
    (faces, edges, edge_list): (&mut Vec<u32>, &mut Vec<u32>, &mut Vec<(u32, u16)>),
) {
    faces.clear();
    edges.clear();
    let [nv, ne, nf] = r.parent_counts;
    let from = |first: u32, count: usize| c.checked_sub(first as usize).filter(|&i| i < count);
    if let Some(f) = from(r.first_vertex_from_faces, nf) {
        quad_face_child(parent, f, faces, edges);
    } else if let Some(e) = from(r.first_vertex_from_edges, ne) {
        if triangles {
            triangle_edge_child(parent, r, e, faces, edges);
        } else {
            quad_edge_child(parent, r, e, faces, edges, edge_list);
        }
    } else if let Some(v) = from(r.first_vertex_from_vertices, nv) {
        if triangles {
            triangle_vertex_child(parent, r, v, faces, edges);
        } else {
            quad_vertex_child(parent, r, v, faces, edges);
        }
    }
}

/// [`derive_vertex_relations`] as the interpolation kernel reads it: the
/// faces of vertex `c` into `faces` and the far ends of its edges (vertices
/// of the child level, in the same order as the edges) into `fars`, without
/// reading the child level. Returns how many, or `None` when they are more
/// than `N` (then derive the relations themselves). Only for levels whose
/// vertex relations are derived: every edge of `parent` has two faces.
#[inline(always)]
pub(crate) fn derive_smooth_hood<const N: usize>(
    parent: &Level,
    r: &Split,
    triangles: bool,
    c: usize,
    faces: &mut [u32; N],
    fars: &mut [u32; N],
) -> Option<usize> {
    let [nv, ne, nf] = r.parent_counts;
    let from = |first: u32, count: usize| c.checked_sub(first as usize).filter(|&i| i < count);
    if let Some(f) = from(r.first_vertex_from_faces, nf) {
        // Quad split: a child face per corner, an edge to each edge point.
        let base = parent.face_vertices.start(f) as u32;
        let edges = parent.face_edges_of(f);
        let n = edges.len();
        if n > N {
            return None;
        }
        for j in 0..n {
            faces[j] = base + j as u32;
            fars[j] = r.edge_child(edges[prev(j, n)] as usize);
        }
        Some(n)
    } else if let Some(e) = from(r.first_vertex_from_edges, ne) {
        let ev = parent.edge_vertices[e];
        let mut at = parent.edge_faces_at(e);
        let (Some((f0, k0)), Some((f1, k1))) = (at.next(), at.next()) else {
            return None;
        };
        if triangles {
            // Three child triangles per face; the half at the first face's
            // leading end, the inner edges to the face's other edge points
            // (inner edge `j` of a face joins the points of its edges `j`
            // and `j - 1`), then the other half.
            if 6 > N {
                return None;
            }
            let ep = |f: usize, j: usize| r.edge_child(parent.face_edges_of(f)[j % 3] as usize);
            for (i, (f, k)) in [(f0, k0), (f1, k1)].into_iter().enumerate() {
                let t = 4 * f as u32;
                faces[3 * i..3 * i + 3].copy_from_slice(&[
                    t + ((k + 1) % 3) as u32,
                    t + 3,
                    t + k as u32,
                ]);
            }
            let reversed = ev[0] != ev[1] && parent.face_verts(f0)[k0] != ev[0];
            let (first, second) = if reversed { (0, 1) } else { (1, 0) };
            fars[..6].copy_from_slice(&[
                r.vertex_child(ev[first] as usize),
                ep(f0, k0 + 1),
                ep(f0, k0 + 2),
                r.vertex_child(ev[second] as usize),
                ep(f1, k1 + 1),
                ep(f1, k1 + 2),
            ]);
            Some(6)
        } else {
            if 4 > N {
                return None;
            }
            let (n0, n1) = (
                parent.face_vertices.count(f0),
                parent.face_vertices.count(f1),
            );
            let (b0, b1) = (
                parent.face_vertices.start(f0) as u32,
                parent.face_vertices.start(f1) as u32,
            );
            faces[..4].copy_from_slice(&[
                b0 + next(k0, n0) as u32,
                b0 + k0 as u32,
                b1 + next(k1, n1) as u32,
                b1 + k1 as u32,
            ]);
            // The halves around the first face's inner edge, the end met
            // first in that face's order first.
            let swapped = ev[0] != ev[1] && parent.face_verts(f0)[k0] == ev[0];
            let (a, b) = if swapped { (1, 0) } else { (0, 1) };
            fars[..4].copy_from_slice(&[
                r.vertex_child(ev[a] as usize),
                r.face_child(f0),
                r.vertex_child(ev[b] as usize),
                r.face_child(f1),
            ]);
            Some(4)
        }
    } else if let Some(v) = from(r.first_vertex_from_vertices, nv) {
        let vfaces = parent.vertex_faces_of(v);
        let vedges = parent.vertex_edges_of(v);
        let n = vfaces.len();
        if n > N || vedges.len() != n {
            return None;
        }
        for (j, (&f, &k)) in vfaces.iter().zip(parent.vertex_face_locals(v)).enumerate() {
            faces[j] = if triangles {
                4 * f + k as u32
            } else {
                parent.face_vertices.start(f as usize) as u32 + k as u32
            };
        }
        for (j, &e) in vedges.iter().enumerate() {
            fars[j] = r.edge_child(e as usize);
        }
        Some(n)
    } else {
        None
    }
}

/// The two faces of edge `c` of a level split from `parent` by `r`
/// (`triangles`: Loop's triangle split), in the order the level would store
/// them, for a level built without its edge-faces
/// ([`Level::derived_relations`]: every edge of `parent` has two faces, so
/// every child edge has two).
#[inline(always)]
pub(crate) fn derive_edge_faces(parent: &Level, r: &Split, triangles: bool, c: usize) -> [u32; 2] {
    if let Some(i) = c.checked_sub(r.parent_corners) {
        derive_half_edge_faces(parent, triangles, i / 2)[i % 2]
    } else if triangles {
        // Inner edge `j` of triangle `f`: its corner triangle `j` and the
        // middle one.
        let (f, j) = (c / 3, c % 3);
        [(4 * f + j) as u32, (4 * f + 3) as u32]
    } else {
        // Edge `j` inside face `f`: its children `j` and `j + 1`.
        let f = parent.face_vertices.element_of(c);
        let (base, n) = (parent.face_vertices.start(f), parent.face_vertices.count(f));
        let j = c - base;
        [(base + j) as u32, (base + next(j, n)) as u32]
    }
}

/// The faces of both halves of parent edge `e` ([`derive_edge_faces`] of
/// child edges `2e` and `2e + 1` after the edges inside faces): in each of
/// the edge's two faces, the child at the corner of the half's end.
#[inline(always)]
pub(crate) fn derive_half_edge_faces(parent: &Level, triangles: bool, e: usize) -> [[u32; 2]; 2] {
    let ev = parent.edge_vertices[e];
    let mut out = [[0; 2]; 2];
    for (i, (f, k)) in parent.edge_faces_at(e).take(2).enumerate() {
        // The corners of the edge's ends in the face: `k` and the next,
        // ends 0 and 1 in that order unless the face runs the other way.
        let flip = ev[0] != ev[1] && parent.face_verts(f)[k] != ev[0];
        let (at_k, at_next) = if triangles {
            ((4 * f + k) as u32, (4 * f + (k + 1) % 3) as u32)
        } else {
            let (base, n) = (parent.face_vertices.start(f), parent.face_vertices.count(f));
            ((base + k) as u32, (base + next(k, n)) as u32)
        };
        put_by_end(&mut out, i, flip, [at_k, at_next]);
    }
    out
}

/// Stores the values at a face's corners `k` and `k + 1`
/// (`[at_k, at_next]`) as face `i`'s entries of the halves of ends 0 and 1
/// of an edge (swapped when the face runs against the edge).
#[inline(always)]
fn put_by_end(out: &mut [[u32; 2]; 2], i: usize, flip: bool, [at_k, at_next]: [u32; 2]) {
    let (end0, end1) = if flip {
        (at_next, at_k)
    } else {
        (at_k, at_next)
    };
    out[0][i] = end0;
    out[1][i] = end1;
}

/// Loop's triangle split, a level built without its edge-faces
/// ([`Level::derived_relations`]): the vertex opposite child edge `c` in
/// each of its two faces, in the order of [`derive_edge_faces`], read from
/// `parent` alone (the child's face-vertices are not read). `None` when a
/// parent face involved has an edge twice: then a child triangle repeats a
/// corner, and the opposite vertex is found by searching its edges.
#[inline(always)]
pub(crate) fn derive_inner_edge_wings(parent: &Level, r: &Split, c: usize) -> Option<[u32; 2]> {
    // Inner edge `j` of triangle `f` joins the points of its edges `j` and
    // `j - 1`: corner `j` is opposite it in the corner triangle, the point
    // of edge `j + 1` in the middle one.
    let (f, j) = (c / 3, c % 3);
    let edges = <&[u32; 3]>::try_from(parent.face_edges_of(f)).ok()?;
    if !distinct(edges) {
        return None;
    }
    Some([
        r.vertex_child(parent.face_verts(f)[j] as usize),
        r.edge_child(edges[(j + 1) % 3] as usize),
    ])
}

/// [`derive_inner_edge_wings`] for both halves of parent edge `e` (child
/// edges `2e` and `2e + 1` after the inner edges), in the order of
/// [`derive_half_edge_faces`]: in the corner triangle of a half's end, the
/// point of the face's other edge at that corner.
#[inline(always)]
pub(crate) fn derive_half_edge_wings(parent: &Level, r: &Split, e: usize) -> Option<[[u32; 2]; 2]> {
    let ev = parent.edge_vertices[e];
    let mut out = [[0; 2]; 2];
    for (i, (f, k)) in parent.edge_faces_at(e).take(2).enumerate() {
        let edges = <&[u32; 3]>::try_from(parent.face_edges_of(f)).ok()?;
        if !distinct(edges) {
            return None;
        }
        // Edge `k` runs from corner `k` to corner `k + 1`; the edge before
        // it meets corner `k`, the one after it corner `k + 1`.
        let at_k = r.edge_child(edges[(k + 2) % 3] as usize);
        let at_next = r.edge_child(edges[(k + 1) % 3] as usize);
        let flip = ev[0] != ev[1] && parent.face_verts(f)[k] != ev[0];
        put_by_end(&mut out, i, flip, [at_k, at_next]);
    }
    Some(out)
}

/// Whether a triangle's three edges are three different edges.
#[inline(always)]
fn distinct(edges: &[u32; 3]) -> bool {
    edges[0] != edges[1] && edges[1] != edges[2] && edges[0] != edges[2]
}

/// Fills a relation with known totals element by element: members and their
/// local indices pushed in order, each element closed by `end_element`. With
/// a `uniform` size (every element has that many members) no offsets are
/// stored.
///
/// The values are pushed into vectors reserved at their final size rather
/// than written into zeroed tables: nothing is written twice (a zeroed
/// allocation that reuses freed memory is cleared first).
struct TableWriter {
    starts: Starts,
    members: Vec<u32>,
    locals: Option<Vec<u16>>,
    /// The element and member counts given to `new` (checked by `finish`).
    expected: (usize, usize),
}

/// Where the elements of a [`TableWriter`] start.
enum Starts {
    /// The offsets written so far, starting with 0.
    Table(Vec<u32>),
    /// Every element has `size` members; `ended` elements are closed.
    Uniform {
        len: usize,
        size: usize,
        ended: usize,
    },
}

impl TableWriter {
    fn new(elements: usize, members: usize, uniform: Option<usize>, locals: bool) -> Self {
        TableWriter {
            starts: match uniform {
                Some(size) => Starts::Uniform {
                    len: elements,
                    size,
                    ended: 0,
                },
                None => {
                    let mut offsets = Vec::with_capacity(elements + 1);
                    offsets.push(0);
                    Starts::Table(offsets)
                }
            },
            members: Vec::with_capacity(members),
            locals: locals.then(|| Vec::with_capacity(members)),
            expected: (elements, members),
        }
    }

    #[inline]
    fn push(&mut self, member: u32, local: u16) {
        self.members.push(member);
        if let Some(locals) = &mut self.locals {
            locals.push(local);
        }
    }

    #[inline]
    fn end_element(&mut self) {
        match &mut self.starts {
            Starts::Table(offsets) => offsets.push(self.members.len() as u32),
            Starts::Uniform { size, ended, .. } => {
                *ended += 1;
                debug_assert_eq!(self.members.len(), *ended * *size);
            }
        }
    }

    fn finish(self) -> (Relation, Table<u16>) {
        let offsets = match self.starts {
            Starts::Table(offsets) => Offsets::Table(offsets.into()),
            Starts::Uniform { len, size, ended } => {
                debug_assert_eq!(ended, len);
                Offsets::Uniform { len, size }
            }
        };
        let relation = Relation {
            offsets,
            members: self.members.into(),
        };
        debug_assert_eq!((relation.len(), relation.members.len()), self.expected);
        debug_assert_eq!(relation.start(relation.len()), relation.members.len());
        (relation, self.locals.unwrap_or_default().into())
    }
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
        let sharp = t.semi_sharp() || t.inf_sharp();
        let mut tag = VertexTag::default();
        tag.set_non_manifold(t.non_manifold());
        tag.set_boundary(t.boundary());
        tag.set_semi_sharp_edges(t.semi_sharp());
        tag.set_inf_sharp_edges(t.inf_sharp());
        tag.set_rule(if sharp { Rule::Crease } else { Rule::Smooth });
        child.set_vertex_tag(r.edge_child(e) as usize, tag);
    }
    for (v, &tag) in parent.vertex_tags.iter().enumerate() {
        child.set_vertex_tag(r.vertex_child(v) as usize, tag);
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
    let mut out = vec![0.0; child_edges];
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
            let c = r.vertex_child(v) as usize;
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
