//! The control points of a face whose limit surface is one regular patch,
//! in Bfr's order (`Bfr::RegularPatchBuilder`, and the refiner's shortcut
//! `RefinerSurfaceFactory::getFaceNeighborhoodVertexIndicesIfRegular`).
//!
//! A bicubic B-spline patch has 16 points, row by row from the corner
//! before the face's first vertex (the face's vertices are points 5, 6, 10
//! and 9); a quartic box-spline patch has 12 (the triangle's vertices are
//! 4, 5 and 8). Points missing on a boundary are replaced by a duplicate
//! and the boundary mask says which: the shortcut duplicates point 5, the
//! general builder the nearest corner.

use super::corner::{Corner, Subset};
use crate::topology::Level;

/// A missing point, before the duplicate replaces it.
const MISSING: i64 = -1;

/// Bfr's boundary mask of a triangle (`encodeTriBoundaryMask`): edge bits
/// and vertex bits in one 5-bit word.
fn tri_mask(edges: u16, verts: u16) -> u16 {
    let (upper, lower) = if verts == 0 {
        (0, edges)
    } else if edges == 0 {
        (1, verts)
    } else if verts == 7 && matches!(edges, 1 | 2 | 4) {
        (2, edges)
    } else {
        (0, edges)
    };
    (upper << 3) | lower
}

/// The boundary mask of a patch's points (`GetBoundaryMask`), `MISSING`
/// where a point does not exist.
fn mask_of(points: &[i64]) -> u16 {
    let m = |i: usize| u16::from(points[i] < 0);
    if points.len() == 16 {
        m(1) | m(7) << 1 | m(14) << 2 | m(8) << 3
    } else {
        let edges = m(1) | m(9) << 1 | m(7) << 2;
        let verts = (m(0) | m(3)) | (m(2) | m(6)) << 1 | (m(10) | m(11)) << 2;
        tri_mask(edges, verts)
    }
}

/// Where the points of base face `face` sit if the refiner's tags make its
/// patch regular: for each of the shortcut's points, the position in the
/// level's face-vertex list of a face corner at that point (missing ones
/// replaced by point 5's: the face's first vertex in a quad's patch, its
/// second in a triangle's; the first 16 or 12 of the array), their number
/// and the boundary mask. The corners, not the vertices, so that a
/// face-varying channel whose topology matches the vertices' around the
/// face reads its values at the same corners ([`shortcut_points`]).
pub(crate) fn shortcut_corners(level: &Level, face: usize) -> ([u32; 16], usize, u16) {
    if let Some(corners) = interior_quad_corners(level, face) {
        return (corners, 16, 0);
    }
    if let Some(corners) = interior_triangle_corners(level, face) {
        return (corners, 12, 0);
    }
    let fverts = level.face_verts(face);
    let quad = fverts.len() == 4;
    let len = if quad { 16 } else { 12 };
    let mut all = [MISSING; 16];
    let p = &mut all[..len];
    let n = fverts.len();
    let start = |f: u32| level.face_vertices.range(f as usize).start;
    for (i, &v) in fverts.iter().enumerate() {
        let v = v as usize;
        let corner = if quad { QUAD[i] } else { TRI[i] };
        let vfaces = level.vertex_faces_of(v);
        let locals = level.vertex_face_locals(v);
        // (Local indices are below `n` and `d` below 4: one subtraction
        // at most instead of a division. The faces around a regular
        // patch's corners all have `n` vertices.)
        let wrap = |i: usize, n: usize| if i >= n { i - n } else { i };
        let at = |k: usize, d: usize| -> i64 {
            let i = usize::from(locals[k]) + d;
            (start(vfaces[k]) + if i >= n { wrap(i - n, n) } else { i }) as i64
        };
        let mine = vfaces.iter().position(|&f| f as usize == face).unwrap_or(0);
        let reg = if quad { 4 } else { 6 };
        if vfaces.len() == reg {
            let opp = wrap(mine + reg / 2, reg);
            if quad {
                let (first, l) = (start(vfaces[opp]) as i64, usize::from(locals[opp]));
                for (d, &slot) in corner.iter().enumerate() {
                    p[slot] = first + ((l + d) & 3) as i64;
                }
            } else {
                let next = wrap(opp + 1, reg);
                p[corner[0]] = at(opp, 0);
                p[corner[1]] = at(opp, 1);
                p[corner[2]] = at(opp, 2);
                p[corner[3]] = at(next, 2);
            }
        } else if vfaces.len() == 1 {
            p[corner[0]] = at(0, 0);
        } else if quad {
            if mine == 0 {
                p[corner[0]] = at(1, 0);
                p[corner[1]] = at(1, 3);
            } else {
                p[corner[0]] = at(0, 0);
                p[corner[3]] = at(0, 1);
            }
        } else if mine == 0 {
            p[corner[0]] = at(2, 0);
            p[corner[1]] = at(2, 2);
        } else if mine == 1 {
            p[corner[0]] = at(0, 0);
            p[corner[3]] = at(0, 1);
        } else {
            p[corner[0]] = at(0, 0);
            p[corner[2]] = at(0, 1);
            p[corner[3]] = at(0, 2);
        }
    }
    let mask = mask_of(p);
    // Point 5 for triangles too (their second vertex), as Bfr does.
    let phantom = p[5];
    let mut corners = [0u32; 16];
    for (dst, &x) in corners.iter_mut().zip(p.iter()) {
        *dst = if x < 0 { phantom } else { x } as u32;
    }
    (corners, len, mask)
}

/// A B-spline patch's points at each corner of its quad: the opposite
/// face's corners, from the one at the quad's vertex on.
const QUAD: [[usize; 4]; 4] = [[5, 4, 0, 1], [6, 2, 3, 7], [10, 11, 15, 14], [9, 13, 12, 8]];

/// A box-spline patch's points at each corner of its triangle: the
/// opposite face's three corners, from the one at the triangle's vertex
/// on, and the far corner of the face after it.
const TRI: [[usize; 4]; 3] = [[4, 3, 0, 1], [5, 2, 6, 9], [8, 11, 10, 7]];

/// [`shortcut_corners`] of a quad whose vertices all have four faces (of a
/// shortcut face: interior and regular), the case of nearly every face of
/// a quad mesh: no point is missing, the mask is 0. `None` for any other
/// face.
fn interior_quad_corners(level: &Level, face: usize) -> Option<[u32; 16]> {
    let fverts = level.face_verts(face);
    if fverts.len() != 4 {
        return None;
    }
    let mut p = [0u32; 16];
    for (&v, slots) in fverts.iter().zip(&QUAD) {
        let vfaces = level.vertex_faces_of(v as usize);
        if vfaces.len() != 4 {
            return None;
        }
        let mine = vfaces.iter().position(|&f| f as usize == face)?;
        let opp = (mine + 2) & 3;
        let first = level.face_vertices.range(vfaces[opp] as usize).start;
        let l = usize::from(level.vertex_face_locals(v as usize)[opp]);
        for (d, &slot) in slots.iter().enumerate() {
            p[slot] = (first + ((l + d) & 3)) as u32;
        }
    }
    Some(p)
}

/// [`shortcut_corners`] of a triangle whose vertices all have six faces
/// (of a shortcut face: interior and regular), the case of nearly every
/// face of a Loop mesh: no point is missing, the mask is 0 (the first 12
/// of the array). At each corner, the opposite face's three corners from
/// the one at the corner's vertex on, and the far corner of the face after
/// it. `None` for any other face.
fn interior_triangle_corners(level: &Level, face: usize) -> Option<[u32; 16]> {
    let fverts = level.face_verts(face);
    if fverts.len() != 3 {
        return None;
    }
    // Corner `d` on from local corner `l` of a triangle (`l`, `d` below 3).
    let wrap = |l: u16, d: usize| {
        let i = usize::from(l) + d;
        if i >= 3 { i - 3 } else { i }
    };
    let mut p = [0u32; 16];
    for (&v, slots) in fverts.iter().zip(&TRI) {
        let vfaces = level.vertex_faces_of(v as usize);
        if vfaces.len() != 6 {
            return None;
        }
        let locals = level.vertex_face_locals(v as usize);
        let mine = vfaces.iter().position(|&f| f as usize == face)?;
        let opp = if mine >= 3 { mine - 3 } else { mine + 3 };
        let next = if opp == 5 { 0 } else { opp + 1 };
        let (first, l) = (
            level.face_vertices.range(vfaces[opp] as usize).start,
            locals[opp],
        );
        let next_first = level.face_vertices.range(vfaces[next] as usize).start;
        p[slots[0]] = (first + wrap(l, 0)) as u32;
        p[slots[1]] = (first + wrap(l, 1)) as u32;
        p[slots[2]] = (first + wrap(l, 2)) as u32;
        p[slots[3]] = (next_first + wrap(locals[next], 2)) as u32;
    }
    Some(p)
}

/// The points of base face `face` if the refiner's tags make its patch
/// regular ([`shortcut_corners`]), their number and the boundary mask.
/// `values` holds an index per face corner, in the layout of the level's
/// face-vertex list: its vertices, or a face-varying channel's values.
pub(crate) fn shortcut_points(
    level: &Level,
    face: usize,
    values: &[u32],
) -> ([u32; 16], usize, u16) {
    let (corners, len, mask) = shortcut_corners(level, face);
    (points_at(&corners, values), len, mask)
}

/// `values` at `corners` (positions in the face-vertex list).
#[inline]
pub(crate) fn points_at(corners: &[u32; 16], values: &[u32]) -> [u32; 16] {
    let mut points = [0u32; 16];
    for (dst, &c) in points.iter_mut().zip(corners) {
        *dst = values[c as usize];
    }
    points
}

/// The boundary mask of a regular patch from its corners' subsets
/// (`RegularPatchBuilder`'s constructor).
pub(crate) fn subset_mask(subsets: &[Subset]) -> u16 {
    if !subsets.iter().any(Subset::is_boundary) {
        return 0;
    }
    let edge = |c: &Subset| u16::from(c.is_boundary() && c.before == 0);
    let edges = subsets
        .iter()
        .enumerate()
        .fold(0, |m, (i, c)| m | edge(c) << i);
    if subsets.len() == 4 {
        edges
    } else {
        let verts = subsets
            .iter()
            .enumerate()
            .fold(0, |m, (i, c)| m | u16::from(c.is_boundary()) << i);
        tri_mask(edges, verts)
    }
}

/// The points of a regular patch from its corners
/// (`RegularPatchBuilder::GatherControlVertexIndices`).
pub(crate) fn subset_points(corners: &[Corner], subsets: &[Subset]) -> Vec<u32> {
    let boundary = subsets.iter().any(Subset::is_boundary);
    if corners.len() == 4 {
        let mut p = [0u32; 16];
        const SLOTS: [[usize; 4]; 4] =
            [[5, 4, 0, 1], [6, 2, 3, 7], [10, 11, 15, 14], [9, 13, 12, 8]];
        for (i, (c, s)) in corners.iter().zip(subsets).enumerate() {
            let slots = SLOTS[i];
            if !boundary {
                let f = c.face(c.after(2));
                for (d, &slot) in slots.iter().enumerate() {
                    p[slot] = f[d];
                }
                continue;
            }
            let here = c.face_in_ring;
            let other = if !s.is_boundary() {
                c.after(2)
            } else if s.after > 0 {
                c.next(here).unwrap_or(here)
            } else if s.before > 0 {
                c.before(1)
            } else {
                here
            };
            let f = c.face(other);
            let phantom = f[0];
            p[slots[0]] = f[0];
            if !s.is_boundary() {
                p[slots[1]] = f[1];
                p[slots[2]] = f[2];
                p[slots[3]] = f[3];
            } else {
                p[slots[1]] = if s.after > 0 { f[3] } else { phantom };
                p[slots[2]] = phantom;
                p[slots[3]] = if s.before > 0 { f[1] } else { phantom };
            }
        }
        p.to_vec()
    } else {
        let mut p = [0u32; 12];
        // Per corner: the corner's point, then the points filled from its
        // faces (the interior case's order).
        const SLOTS: [[usize; 4]; 3] = [[4, 7, 3, 0], [5, 1, 2, 6], [8, 9, 11, 10]];
        for (i, (c, s)) in corners.iter().zip(subsets).enumerate() {
            let slots = SLOTS[i];
            if !s.is_boundary() {
                let a = c.after(2);
                let f = c.face(a);
                let g = c.face(c.next(a).unwrap_or(a));
                p[slots[0]] = f[0];
                p[slots[1]] = f[1];
                p[slots[2]] = f[2];
                p[slots[3]] = g[2];
                continue;
            }
            let other = if s.total == 1 {
                c.face_in_ring
            } else if s.before == 0 {
                c.after(2)
            } else if s.after == 0 {
                c.before(2)
            } else {
                c.next(c.face_in_ring).unwrap_or(c.face_in_ring)
            };
            let f = c.face(other);
            let phantom = f[0];
            p[slots[0]] = f[0];
            p[slots[1]] = if s.after > 0 { f[3 - s.after] } else { phantom };
            p[slots[2]] = if s.after == 2 { f[2] } else { phantom };
            p[slots[3]] = if s.before == 2 { f[1] } else { phantom };
        }
        p.to_vec()
    }
}
