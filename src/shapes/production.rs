//! A production-like mesh: what film and game assets look like to a
//! subdivision engine, generated in code at any size — mostly quads, with
//! triangle pairs and hexagons mixed in, crease chains (semi-sharp and
//! infinitely sharp), sharp corners, holes, and a UV channel with seams.

use crate::mesh::{FVarChannel, Mesh, SHARPNESS_INFINITE};
use glam::DVec3;
use std::f64::consts::TAU;

/// A closed torus of `nu × nv` cells laid out like a production asset
/// (`nu` is rounded up to a multiple of 8, both are at least 8):
///
/// * cells `(i, j)` with `i % 4 == 0` and `j % 3 == 0` merge with their
///   neighbour along u into a hexagon; cells with `(i + 2j) % 5 == 0` (not
///   merged) are split into two triangles; the rest are quads — about 1.1
///   faces per cell;
/// * a ring of semi-sharp edges (sharpness 2.5) at `j = nv / 4`, and a chain
///   of infinitely sharp edges along `i = 4·⌊nu/12⌋ + 2` over half the rings
///   (the chain's ends are darts);
/// * sharp corners (sharpness 3) at a sparse lattice of vertices;
/// * three holes, each a single face, spread over the mesh;
/// * one UV channel (width 2) unwrapped as two islands, split at
///   `i = nu / 2` and at the torus's own seams `i = 0` and `j = 0`: the
///   vertices along those lines carry two or four UV values.
///
/// `production(560, 480)` has about 300,000 faces.
pub fn production(nu: u32, nv: u32) -> Mesh {
    let nu = nu.max(8).next_multiple_of(8);
    let nv = nv.max(8);
    let mut mesh = Mesh::default();
    for j in 0..nv {
        let b = TAU * j as f64 / nv as f64;
        for i in 0..nu {
            let a = TAU * i as f64 / nu as f64;
            // A little relief so that refined positions are not all on a torus.
            let r = 1.0 + (0.35 + 0.02 * (7.0 * a).sin()) * b.cos();
            mesh.positions
                .push(DVec3::new(r * a.cos(), r * a.sin(), 0.35 * b.sin()));
        }
    }
    let at = |i: u32, j: u32| (j % nv) * nu + (i % nu);
    // UV values: two islands of (columns × (nv + 1)) values, indexed by the
    // unwrapped lattice column and row of a corner.
    let half = nu / 2;
    let width = half + 1;
    let mut uv = Vec::with_capacity(2 * 2 * (width * (nv + 1)) as usize);
    for island in 0..2 {
        for row in 0..=nv {
            for c in 0..=half {
                let col = island * half + c;
                uv.push(col as f64 / nu as f64 * 0.96 + island as f64 * 0.04);
                uv.push(row as f64 / nv as f64);
            }
        }
    }
    let uv_at = |cell: u32, col: u32, row: u32| {
        let island = u32::from(cell >= half);
        island * width * (nv + 1) + row * width + (col - island * half)
    };
    let mut uv_indices = Vec::new();
    let mut face = |mesh: &mut Mesh, cell: u32, corners: &[(u32, u32)]| {
        let vertices: Vec<u32> = corners.iter().map(|&(i, j)| at(i, j)).collect();
        mesh.add_face(&vertices);
        uv_indices.extend(corners.iter().map(|&(i, j)| uv_at(cell, i, j)));
    };
    for j in 0..nv {
        let mut i = 0;
        while i < nu {
            let (i1, j1) = (i + 1, j + 1);
            if i % 4 == 0 && j % 3 == 0 {
                let i2 = i + 2;
                face(
                    &mut mesh,
                    i,
                    &[(i, j), (i1, j), (i2, j), (i2, j1), (i1, j1), (i, j1)],
                );
                i += 2;
                continue;
            }
            if (i + 2 * j) % 5 == 0 {
                face(&mut mesh, i, &[(i, j), (i1, j), (i1, j1)]);
                face(&mut mesh, i, &[(i, j), (i1, j1), (i, j1)]);
            } else {
                face(&mut mesh, i, &[(i, j), (i1, j), (i1, j1), (i, j1)]);
            }
            i += 1;
        }
    }
    mesh.fvar_channels.push(FVarChannel {
        width: 2,
        values: uv,
        indices: uv_indices,
    });
    let ring = nv / 4;
    for i in 0..nu {
        mesh.add_crease(at(i, ring), at(i + 1, ring), 2.5);
    }
    let column = 4 * (nu / 12) + 2;
    for j in nv / 4..3 * nv / 4 {
        mesh.add_crease(at(column, j), at(column, j + 1), SHARPNESS_INFINITE);
    }
    for j in (5..nv).step_by(23) {
        for i in (3..nu).step_by(29) {
            mesh.add_corner(at(i, j), 3.0);
        }
    }
    let faces = mesh.face_count() as u32;
    mesh.holes = vec![faces / 7, faces / 2 + 3, faces - faces / 6];
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    #[test]
    fn the_mix_the_tags_and_the_seams_are_there() {
        let m = production(40, 24);
        assert!(m.validate().unwrap().warnings.is_empty());
        let mut sizes = HashMap::new();
        for f in m.faces() {
            *sizes.entry(f.len()).or_insert(0) += 1;
        }
        // 40 × 24 cells: 8 rings of 10 hexagons (two cells each), and a fifth
        // of the other 800 cells split into triangle pairs.
        assert_eq!(sizes[&6], 80);
        assert_eq!(
            sizes[&3] + sizes[&4] + 2 * sizes[&6],
            40 * 24 + sizes[&3] / 2
        );
        assert!(sizes[&3] > 250 && sizes[&3] < 400, "{sizes:?}");
        assert_eq!(m.holes.len(), 3);
        assert_eq!(m.creases.len(), 40 + 12);
        assert!(!m.corners.is_empty());
        // Closed: every edge has two faces.
        let mut edges = HashMap::new();
        for f in m.faces() {
            for k in 0..f.len() {
                let (a, b) = (f[k], f[(k + 1) % f.len()]);
                *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            }
        }
        assert!(edges.values().all(|&n| n == 2));
        // Seams: the vertices on i = 0 and i = nu/2 have two UV values (four
        // where they meet j = 0), the others one.
        let ch = &m.fvar_channels[0];
        let mut values: HashMap<u32, std::collections::BTreeSet<u32>> = HashMap::new();
        for (&v, &x) in m.face_vertices.iter().zip(&ch.indices) {
            values.entry(v).or_default().insert(x);
        }
        let count = |i: u32, j: u32| values[&(j * 40 + i)].len();
        assert_eq!((count(0, 5), count(20, 5), count(7, 5)), (2, 2, 1));
        assert_eq!((count(0, 0), count(20, 0), count(7, 0)), (4, 4, 2));
        // The same UV value is never shared by two vertices.
        let mut owner = HashMap::new();
        for (&v, &x) in m.face_vertices.iter().zip(&ch.indices) {
            assert_eq!(*owner.entry(x).or_insert(v), v);
        }
    }

    #[test]
    fn the_full_size_has_about_300k_faces() {
        let faces = production(560, 480).face_count();
        assert!((280_000..320_000).contains(&faces), "{faces}");
    }
}
