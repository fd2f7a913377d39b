//! Meshes generated in code: the built-in inputs of the CLI, the tests and the benches.

use crate::mesh::{FVarChannel, Mesh};
use glam::DVec3;
use std::f64::consts::TAU;

/// The unit cube centred at the origin: 8 vertices, 6 quads, outward-facing.
pub fn cube() -> Mesh {
    let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z) - DVec3::splat(0.5);
    Mesh::from_faces(
        vec![
            p(0.0, 0.0, 0.0),
            p(1.0, 0.0, 0.0),
            p(1.0, 1.0, 0.0),
            p(0.0, 1.0, 0.0),
            p(0.0, 0.0, 1.0),
            p(1.0, 0.0, 1.0),
            p(1.0, 1.0, 1.0),
            p(0.0, 1.0, 1.0),
        ],
        &[
            &[0, 3, 2, 1], // bottom (z = 0), facing -z
            &[4, 5, 6, 7], // top
            &[0, 1, 5, 4], // front (y = 0)
            &[1, 2, 6, 5], // right
            &[2, 3, 7, 6], // back
            &[3, 0, 4, 7], // left
        ],
    )
}

/// The cube with a face-varying UV channel: each face maps to its own unit
/// square, so the channel splits along every edge of the cube.
pub fn cube_with_uvs() -> Mesh {
    let mut mesh = cube();
    let mut values = Vec::new();
    let mut indices = Vec::new();
    for f in 0..mesh.face_count() {
        let base = (values.len() / 2) as u32;
        let x0 = f as f64;
        values.extend_from_slice(&[x0, 0.0, x0 + 1.0, 0.0, x0 + 1.0, 1.0, x0, 1.0]);
        indices.extend((0..4).map(|j| base + j));
    }
    mesh.fvar_channels.push(FVarChannel {
        width: 2,
        values,
        indices,
    });
    mesh
}

/// An open grid of `nx` × `ny` unit quads in the z = 0 plane, with per-vertex UVs.
pub fn grid(nx: u32, ny: u32) -> Mesh {
    let mut mesh = Mesh::default();
    let mut uv = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            mesh.positions.push(DVec3::new(i as f64, j as f64, 0.0));
            uv.extend_from_slice(&[i as f64 / nx as f64, j as f64 / ny as f64]);
        }
    }
    let at = |i: u32, j: u32| j * (nx + 1) + i;
    for j in 0..ny {
        for i in 0..nx {
            mesh.add_face(&[at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    let indices = mesh.face_vertices.clone();
    mesh.fvar_channels.push(FVarChannel {
        width: 2,
        values: uv,
        indices,
    });
    mesh
}

/// A closed torus of `nu` × `nv` quads (major radius 1, minor radius 0.35).
pub fn torus(nu: u32, nv: u32) -> Mesh {
    let mut mesh = Mesh::default();
    for j in 0..nv {
        let b = TAU * j as f64 / nv as f64;
        for i in 0..nu {
            let a = TAU * i as f64 / nu as f64;
            let r = 1.0 + 0.35 * b.cos();
            mesh.positions
                .push(DVec3::new(r * a.cos(), r * a.sin(), 0.35 * b.sin()));
        }
    }
    let at = |i: u32, j: u32| (j % nv) * nu + (i % nu);
    for j in 0..nv {
        for i in 0..nu {
            mesh.add_face(&[at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    mesh
}

/// A regular tetrahedron (4 triangles), for the Loop scheme.
pub fn tetrahedron() -> Mesh {
    Mesh::from_faces(
        vec![
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(-1.0, -1.0, 1.0),
            DVec3::new(-1.0, 1.0, -1.0),
            DVec3::new(1.0, -1.0, -1.0),
        ],
        &[&[0, 1, 3], &[0, 2, 1], &[0, 3, 2], &[1, 2, 3]],
    )
}

/// The built-in shapes by name, as the CLI knows them.
pub fn by_name(name: &str) -> Option<Mesh> {
    Some(match name {
        "cube" => cube(),
        "cube-uv" => cube_with_uvs(),
        "grid" => grid(4, 4),
        "torus" => torus(16, 8),
        "tetrahedron" => tetrahedron(),
        _ => return None,
    })
}

/// Names accepted by [`by_name`].
pub const NAMES: &[&str] = &["cube", "cube-uv", "grid", "torus", "tetrahedron"];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shapes_are_valid_and_closed_where_expected() {
        for name in NAMES {
            let m = by_name(name).unwrap();
            assert!(m.validate().unwrap().warnings.is_empty(), "{name}");
        }
        let t = torus(6, 4);
        assert_eq!((t.vertex_count(), t.face_count()), (24, 24));
        // Closed: every edge is used exactly twice, once in each direction.
        let mut directed = std::collections::HashSet::new();
        for f in t.faces() {
            for j in 0..f.len() {
                assert!(directed.insert((f[j], f[(j + 1) % f.len()])));
            }
        }
        for &(a, b) in &directed {
            assert!(directed.contains(&(b, a)));
        }
    }
}
