//! Relations derived on demand from the parent: a level built as
//! [`Build::Relations`](super::Build::Relations) from a parent smooth
//! everywhere leaves out its vertex-faces, vertex-edges and edge-faces
//! ([`Level::derived_relations`]), and the refiner (its interpolation kernel
//! above all) reads them from here, computed from the parent element by
//! element in the order the level would have stored them. OpenSubdiv always
//! stores them: this has no counterpart there. The derivations the kernel
//! calls per child read the parent through its [`LevelSlices`], taken once
//! per pass, rather than through its tables.

use super::quad::{quad_edge_child, quad_face_child, quad_vertex_child};
use super::tri::{triangle_edge_child, triangle_vertex_child};
use super::{Split, next, prev};
use crate::topology::{Level, LevelSlices};

/// Whether a child of `parent` built as
/// [`Build::Relations`](super::Build::Relations) can leave out its
/// vertex-faces, vertex-edges and edge-faces, to be derived from `parent`
/// when read ([`derive_vertex_relations`], [`derive_edge_faces`]): `parent`
/// has its local indices, no sharpness and no tags (every vertex smooth and
/// manifold, no boundary), and two faces on every edge. Then every vertex of the child is smooth
/// with as many faces as edges, every edge has two faces, and nothing but
/// interpolating the minimal last level reads these relations.
pub(super) fn vertex_relations_derivable(parent: &Level) -> bool {
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
    parent: &LevelSlices<'_>,
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

/// The neighbours the limit masks of a smooth interior vertex weigh, for
/// vertex `c` of a level split from `parent` by `r` (`triangles`: Loop's
/// triangle split, otherwise the quad split), read from `parent` alone: the
/// far end of each of its edges into `fars`, and under the quad split the
/// vertex opposite `c` in each of its faces into `opposite`, both in the
/// order the level stores its edges and faces. Returns how many, or `None`
/// where the parent element's neighbourhood is not the ordinary one (a
/// parent edge without exactly two distinct faces or with one vertex at
/// both ends, a parent vertex with more faces or edges than `N` or not as
/// many of each), there to be read from the level itself.
///
/// In the child quad of parent face `f` at its corner `j`, the vertex
/// opposite the corner's vertex point is the face point, and the points of
/// the face's edges `j` and `j - 1` are opposite each other.
#[inline(always)]
pub(crate) fn derive_limit_ring<const N: usize>(
    parent: &Level,
    r: &Split,
    triangles: bool,
    c: usize,
    opposite: &mut [u32; N],
    fars: &mut [u32; N],
) -> Option<usize> {
    let [nv, ne, nf] = r.parent_counts;
    let from = |first: u32, count: usize| c.checked_sub(first as usize).filter(|&i| i < count);
    if let Some(v) = from(r.first_vertex_from_vertices, nv) {
        // The child's faces and edges are the children of the vertex's, in
        // their order.
        let vfaces = parent.vertex_faces_of(v);
        let vedges = parent.vertex_edges_of(v);
        let n = vfaces.len();
        if n > N || vedges.len() != n {
            return None;
        }
        if !triangles {
            for (o, &f) in opposite.iter_mut().zip(vfaces) {
                *o = r.face_child(f as usize);
            }
        }
        for (far, &e) in fars.iter_mut().zip(vedges) {
            *far = r.edge_child(e as usize);
        }
        Some(n)
    } else if let Some(e) = from(r.first_vertex_from_edges, ne) {
        let ev = parent.edge_vertices[e];
        let faces = parent.edge_faces_of(e);
        let &[f0, f1] = faces else {
            return None;
        };
        if ev[0] == ev[1] || f0 == f1 {
            return None;
        }
        let locals = parent.edge_face_locals(e);
        let (f0, k0, f1, k1) = (
            f0 as usize,
            locals[0] as usize,
            f1 as usize,
            locals[1] as usize,
        );
        if triangles {
            // As derive_smooth_hood orders them.
            if 6 > N {
                return None;
            }
            let ep = |f: usize, j: usize| r.edge_child(parent.face_edges_of(f)[j % 3] as usize);
            let reversed = parent.face_verts(f0)[k0] != ev[0];
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
            // The faces are the children at corners k0 + 1 and k0 of f0,
            // then k1 + 1 and k1 of f1 (derive_smooth_hood).
            let (e0, e1) = (parent.face_edges_of(f0), parent.face_edges_of(f1));
            let (n0, n1) = (e0.len(), e1.len());
            opposite[..4].copy_from_slice(&[
                r.edge_child(e0[next(k0, n0)] as usize),
                r.edge_child(e0[prev(k0, n0)] as usize),
                r.edge_child(e1[next(k1, n1)] as usize),
                r.edge_child(e1[prev(k1, n1)] as usize),
            ]);
            let swapped = parent.face_verts(f0)[k0] == ev[0];
            let (a, b) = if swapped { (1, 0) } else { (0, 1) };
            fars[..4].copy_from_slice(&[
                r.vertex_child(ev[a] as usize),
                r.face_child(f0),
                r.vertex_child(ev[b] as usize),
                r.face_child(f1),
            ]);
            Some(4)
        }
    } else if let Some(f) = from(r.first_vertex_from_faces, nf) {
        // Quad split: the child at corner j is the face's child face j,
        // its edge j leads to the point of the face's edge j - 1.
        let verts = parent.face_verts(f);
        let edges = parent.face_edges_of(f);
        let n = edges.len();
        if n > N || verts.len() != n {
            return None;
        }
        for j in 0..n {
            opposite[j] = r.vertex_child(verts[j] as usize);
            fars[j] = r.edge_child(edges[prev(j, n)] as usize);
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
pub(crate) fn derive_edge_faces(
    parent: &LevelSlices<'_>,
    r: &Split,
    triangles: bool,
    c: usize,
) -> [u32; 2] {
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
        inner_quad_edge_faces(parent, f, c)
    }
}

/// The two faces of child edge `c` inside parent face `f` of a quad split:
/// its children `j` and `j + 1`, for the face's edge `j`.
#[inline(always)]
fn inner_quad_edge_faces(parent: &LevelSlices<'_>, f: usize, c: usize) -> [u32; 2] {
    let (base, n) = (parent.face_vertices.start(f), parent.face_vertices.count(f));
    let j = c - base;
    [(base + j) as u32, (base + next(j, n)) as u32]
}

/// [`derive_edge_faces`] of child edge `c` of a quad split, for edges met in
/// order: the parent face of an edge inside a face is looked for first in
/// `hint` (the face of the edge before, updated) and the face after it,
/// searched for only when neither holds it (faces of mixed sizes).
#[inline(always)]
pub(crate) fn derive_quad_edge_faces_in_order(
    parent: &LevelSlices<'_>,
    r: &Split,
    c: usize,
    hint: &mut usize,
) -> [u32; 2] {
    if c >= r.parent_corners {
        return derive_edge_faces(parent, r, false, c);
    }
    let fv = &parent.face_vertices;
    let holds = |f: usize| f < fv.len() && c >= fv.start(f) && c < fv.start(f) + fv.count(f);
    let f = if holds(*hint) {
        *hint
    } else if holds(*hint + 1) {
        *hint + 1
    } else {
        fv.element_of(c)
    };
    *hint = f;
    inner_quad_edge_faces(parent, f, c)
}

/// The faces of both halves of parent edge `e` ([`derive_edge_faces`] of
/// child edges `2e` and `2e + 1` after the edges inside faces): in each of
/// the edge's two faces, the child at the corner of the half's end.
#[inline(always)]
pub(crate) fn derive_half_edge_faces(
    parent: &LevelSlices<'_>,
    triangles: bool,
    e: usize,
) -> [[u32; 2]; 2] {
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
pub(crate) fn derive_inner_edge_wings(
    parent: &LevelSlices<'_>,
    r: &Split,
    c: usize,
) -> Option<[u32; 2]> {
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
pub(crate) fn derive_half_edge_wings(
    parent: &LevelSlices<'_>,
    r: &Split,
    e: usize,
) -> Option<[[u32; 2]; 2]> {
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
