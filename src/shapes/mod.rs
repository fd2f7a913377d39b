//! Meshes generated in code: the built-in inputs of the CLI, the tests and the benches.

mod production;

pub use production::production;

use crate::mesh::{FVarChannel, Mesh};
use crate::options::{BoundaryInterpolation, FVarLinearInterpolation, Options, Scheme};
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

/// The same unit cube as [`cube`], numbered as OpenSubdiv's Far tutorials
/// number it (`far_tutorial_0`): vertices (-½,-½,½), (½,-½,½), (-½,½,½),
/// (½,½,½), (-½,½,-½), (½,½,-½), (-½,-½,-½), (½,-½,-½), and the faces z+,
/// y+, z-, y-, x+, x-. Creases and corners written for OpenSubdiv's cube
/// (as in the conformance tests) name the same vertices on it.
pub fn tutorial_cube() -> Mesh {
    mesh(
        &[
            [-0.5, -0.5, 0.5],
            [0.5, -0.5, 0.5],
            [-0.5, 0.5, 0.5],
            [0.5, 0.5, 0.5],
            [-0.5, 0.5, -0.5],
            [0.5, 0.5, -0.5],
            [-0.5, -0.5, -0.5],
            [0.5, -0.5, -0.5],
        ],
        &[
            &[0, 1, 3, 2], // z+
            &[2, 3, 5, 4], // y+
            &[4, 5, 7, 6], // z-
            &[6, 7, 1, 0], // y-
            &[1, 7, 5, 3], // x+
            &[6, 0, 2, 4], // x-
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

/// A closed torus of `nu` × `nv` cells where quads and pairs of triangles
/// alternate like a checkerboard (a mixed mesh for Catmull-Clark).
pub fn torus_mixed(nu: u32, nv: u32) -> Mesh {
    let quads = torus(nu, nv);
    let mut mesh = Mesh {
        positions: quads.positions.clone(),
        ..Mesh::default()
    };
    for (i, f) in quads.faces().enumerate() {
        let (u, v) = (i as u32 % nu, i as u32 / nu);
        if (u + v) % 2 == 0 {
            mesh.add_face(f);
        } else {
            mesh.add_face(&[f[0], f[1], f[2]]);
            mesh.add_face(&[f[0], f[2], f[3]]);
        }
    }
    mesh
}

/// A closed torus of `nu` × `nv` cells, each split into two triangles (for Loop).
pub fn torus_triangles(nu: u32, nv: u32) -> Mesh {
    let quads = torus(nu, nv);
    let mut mesh = Mesh {
        positions: quads.positions.clone(),
        ..Mesh::default()
    };
    for f in quads.faces() {
        mesh.add_face(&[f[0], f[1], f[2]]);
        mesh.add_face(&[f[0], f[2], f[3]]);
    }
    mesh
}

/// `mesh` — [`torus`], [`torus_mixed`] or [`torus_triangles`] of `nu` ×
/// `nv` cells (both at least 3) — with the torus unwrapped onto the unit
/// square as its one face-varying channel: (`nu` + 1) × (`nv` + 1) UVs, two
/// seam loops (the rings through vertex 0, which has four values; the other
/// vertices of a seam have two), as a texture artist would cut a torus.
pub fn with_torus_uvs(mut mesh: Mesh, nu: u32, nv: u32) -> Mesh {
    let mut values = Vec::with_capacity(2 * (nu as usize + 1) * (nv as usize + 1));
    for j in 0..=nv {
        for i in 0..=nu {
            values.extend([i as f64 / nu as f64, j as f64 / nv as f64]);
        }
    }
    // A face's cell: the lowest ring of its vertices, or the last one when
    // the face closes the torus (its vertices are on rings 0 and n - 1).
    let cell = |rings: &mut dyn Iterator<Item = u32>, n: u32| {
        let (lo, hi) = rings.fold((u32::MAX, 0), |(lo, hi), r| (lo.min(r), hi.max(r)));
        if hi - lo > 1 { n - 1 } else { lo }
    };
    let mut indices = Vec::with_capacity(mesh.face_vertices.len());
    for f in mesh.faces() {
        let ci = cell(&mut f.iter().map(|&v| v % nu), nu);
        let cj = cell(&mut f.iter().map(|&v| v / nu), nv);
        for &v in f {
            let (i, j) = (v % nu, v / nu);
            let (di, dj) = (u32::from(i != ci), u32::from(j != cj));
            indices.push((cj + dj) * (nu + 1) + ci + di);
        }
    }
    mesh.fvar_channels = vec![FVarChannel {
        width: 2,
        values,
        indices,
    }];
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

/// One input of the benchmarks (`subdiv bench`, `cargo bench`): a mesh, the
/// options to refine it with (its scheme among them) and the deepest level.
#[derive(Debug, Clone)]
pub struct BenchShape {
    /// Short name.
    pub name: String,
    /// The mesh.
    pub mesh: Mesh,
    /// The options: the scheme, and for the production-like input the
    /// boundary and face-varying interpolation USD assets default to.
    pub options: Options,
    /// Deepest level to refine.
    pub max_level: u32,
}

/// The standard benchmark inputs: a 100×100 quad torus, an 80×80 torus of
/// alternating quads and triangle pairs, a 100×50 triangle torus
/// (Catmull-Clark and Loop), a 1000×1000 quad grid refined one level, and
/// the production-like mesh of [`production`] (560 × 480 cells, 291,200
/// faces, one UV channel) refined two levels with USD's defaults (boundary
/// edge-and-corner, face-varying corners-plus-1), and the four tori again
/// with UVs ([`with_torus_uvs`]) refined two levels with the same defaults.
/// `quick` shrinks them.
pub fn bench_shapes(quick: bool) -> Vec<BenchShape> {
    let d = if quick { 4 } else { 1 };
    let input = |name: &str, mesh: Mesh, scheme: Scheme, max_level: u32| BenchShape {
        name: name.to_string(),
        mesh,
        options: Options::default().with_scheme(scheme),
        max_level,
    };
    let mut grid = grid(1000 / d, 1000 / d);
    grid.fvar_channels.clear();
    let (pu, pv) = (560 / d, 480 / d);
    let usd = Options::default()
        .with_boundary(BoundaryInterpolation::EdgeAndCorner)
        .with_fvar(FVarLinearInterpolation::CornersPlus1);
    let mut shapes = vec![
        input(
            &format!("torus {0}x{0} quads", 100 / d),
            torus(100 / d, 100 / d),
            Scheme::Catmark,
            4,
        ),
        input(
            &format!("torus {0}x{0} mixed", 80 / d),
            torus_mixed(80 / d, 80 / d),
            Scheme::Catmark,
            4,
        ),
        input(
            &format!("torus {}x{} triangles", 100 / d, 50 / d),
            torus_triangles(100 / d, 50 / d),
            Scheme::Catmark,
            4,
        ),
        input(
            &format!("torus {}x{} triangles", 100 / d, 50 / d),
            torus_triangles(100 / d, 50 / d),
            Scheme::Loop,
            4,
        ),
        input(
            &format!("grid {0}x{0} quads", 1000 / d),
            grid,
            Scheme::Catmark,
            1,
        ),
        BenchShape {
            name: format!("production {pu}x{pv} with UVs"),
            mesh: production(pu, pv),
            options: usd,
            max_level: 2,
        },
    ];
    // Every torus again with its UVs (two seam loops), refined as assets
    // are: two levels, USD's defaults.
    let with_uvs: Vec<BenchShape> = shapes[..4]
        .iter()
        .map(|t| {
            let (nu, nv) = if t.name.contains("mixed") {
                (80 / d, 80 / d)
            } else if t.name.contains("triangles") {
                (100 / d, 50 / d)
            } else {
                (100 / d, 100 / d)
            };
            BenchShape {
                name: format!("{} with UVs", t.name),
                mesh: with_torus_uvs(t.mesh.clone(), nu, nv),
                options: usd.with_scheme(t.options.scheme),
                max_level: 2,
            }
        })
        .collect();
    shapes.extend(with_uvs);
    shapes
}

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

    /// Every face of the unwrapped tori maps onto one cell of the unit
    /// square, corner by corner; vertex 0 has four values, the other seam
    /// vertices two, every other vertex one.
    #[test]
    fn torus_uvs_unwrap_every_cell_with_two_seams() {
        let (nu, nv) = (5, 4);
        for mesh in [torus(nu, nv), torus_mixed(nu, nv), torus_triangles(nu, nv)] {
            let m = with_torus_uvs(mesh, nu, nv);
            assert!(m.validate().unwrap().warnings.is_empty());
            let uv = &m.fvar_channels[0];
            assert_eq!(uv.values.len(), 2 * 6 * 5);
            let mut values_of = vec![std::collections::BTreeSet::new(); m.vertex_count()];
            for (f, face) in m.faces().enumerate() {
                let corners =
                    &uv.indices[m.face_offsets[f] as usize..m.face_offsets[f + 1] as usize];
                let at = |k: usize| {
                    [
                        uv.values[2 * corners[k] as usize],
                        uv.values[2 * corners[k] as usize + 1],
                    ]
                };
                // The corners' UVs span one cell, and each sits where its
                // vertex sits on the torus (mod the seams).
                let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
                for k in 0..face.len() {
                    let [u, v] = at(k);
                    lo = [lo[0].min(u), lo[1].min(v)];
                    hi = [hi[0].max(u), hi[1].max(v)];
                    let (i, j) = (face[k] % nu, face[k] / nu);
                    assert_eq!((u * nu as f64).round() as u32 % nu, i);
                    assert_eq!((v * nv as f64).round() as u32 % nv, j);
                    values_of[face[k] as usize].insert(corners[k]);
                }
                assert!((hi[0] - lo[0] - 1.0 / nu as f64).abs() < 1e-12, "face {f}");
                assert!((hi[1] - lo[1] - 1.0 / nv as f64).abs() < 1e-12, "face {f}");
            }
            for (v, values) in values_of.iter().enumerate() {
                let (i, j) = (v as u32 % nu, v as u32 / nu);
                let expected =
                    1 + usize::from(i == 0) + usize::from(j == 0) + usize::from(i == 0 && j == 0);
                assert_eq!(values.len(), expected, "vertex {v}");
            }
        }
    }

    #[test]
    fn tutorial_cube_and_octahedron_are_closed() {
        for (name, m, vertices, faces) in [
            ("tutorial cube", tutorial_cube(), 8, 6),
            ("octahedron", octahedron(), 6, 8),
        ] {
            assert!(m.validate().unwrap().warnings.is_empty(), "{name}");
            assert_eq!((m.vertex_count(), m.face_count()), (vertices, faces));
            // Closed and consistently oriented: each directed edge once, its reverse once.
            let mut directed = std::collections::HashSet::new();
            for f in m.faces() {
                for j in 0..f.len() {
                    assert!(directed.insert((f[j], f[(j + 1) % f.len()])), "{name}");
                }
            }
            assert!(
                directed.iter().all(|&(a, b)| directed.contains(&(b, a))),
                "{name}"
            );
        }
        // The same cube as `cube`, numbered differently.
        let mut a: Vec<[i64; 3]> = cube()
            .positions
            .iter()
            .map(|p| (*p * 2.0).as_i64vec3().to_array())
            .collect();
        let mut b: Vec<[i64; 3]> = tutorial_cube()
            .positions
            .iter()
            .map(|p| (*p * 2.0).as_i64vec3().to_array())
            .collect();
        a.sort_unstable();
        b.sort_unstable();
        assert_eq!(a, b);
    }
}

/// A mesh from a list of points and faces given as slices.
fn mesh(points: &[[f64; 3]], faces: &[&[u32]]) -> Mesh {
    Mesh::from_faces(
        points.iter().map(|&p| DVec3::from_array(p)).collect(),
        faces,
    )
}

/// A square pyramid whose base is an `n`-gon (n ≥ 3): one n-gon and n triangles.
pub fn pyramid(n: u32) -> Mesh {
    let mut m = Mesh::default();
    for i in 0..n {
        let a = TAU * i as f64 / n as f64;
        m.positions.push(DVec3::new(a.cos(), a.sin(), 0.0));
    }
    m.positions.push(DVec3::new(0.1, -0.05, 1.2));
    let base: Vec<u32> = (0..n).rev().collect();
    m.add_face(&base);
    for i in 0..n {
        m.add_face(&[i, (i + 1) % n, n]);
    }
    m
}

/// A closed prism over a regular `n`-gon: two n-gon caps and n quads.
pub fn prism(n: u32) -> Mesh {
    let mut m = Mesh::default();
    for z in [0.0, 1.0] {
        for i in 0..n {
            let a = TAU * i as f64 / n as f64 + 0.1 * z;
            m.positions.push(DVec3::new(a.cos(), a.sin(), z));
        }
    }
    let bottom: Vec<u32> = (0..n).rev().collect();
    let top: Vec<u32> = (n..2 * n).collect();
    m.add_face(&bottom);
    m.add_face(&top);
    for i in 0..n {
        let j = (i + 1) % n;
        m.add_face(&[i, j, n + j, n + i]);
    }
    m
}

/// A closed "pole": an `n`-valent vertex at the top of a cone of quads and
/// triangles, closed by an n-gon at the bottom.
pub fn pole(n: u32) -> Mesh {
    let mut m = Mesh::default();
    m.positions.push(DVec3::new(0.0, 0.0, 1.0));
    for ring in 1..=2 {
        for i in 0..n {
            let a = TAU * i as f64 / n as f64 + 0.05 * ring as f64;
            let r = 0.5 * ring as f64;
            m.positions.push(DVec3::new(
                r * a.cos(),
                r * a.sin(),
                1.0 - 0.4 * ring as f64,
            ));
        }
    }
    let ring = |k: u32, i: u32| 1 + (k - 1) * n + (i % n);
    for i in 0..n {
        m.add_face(&[0, ring(1, i), ring(1, i + 1)]);
        m.add_face(&[ring(1, i), ring(2, i), ring(2, i + 1), ring(1, i + 1)]);
    }
    let bottom: Vec<u32> = (0..n).rev().map(|i| ring(2, i)).collect();
    m.add_face(&bottom);
    m
}

/// An open fan of `n` triangles around a centre vertex (a boundary vertex of
/// valence `n + 1`), spanning `angle` radians.
pub fn fan(n: u32, angle: f64) -> Mesh {
    let mut m = Mesh::default();
    m.positions.push(DVec3::ZERO);
    for i in 0..=n {
        let a = angle * i as f64 / n as f64;
        m.positions
            .push(DVec3::new(a.cos(), a.sin(), 0.1 * (i % 2) as f64));
    }
    for i in 0..n {
        m.add_face(&[0, i + 1, i + 2]);
    }
    m
}

/// A closed fan ("wheel") of `n` triangles around a centre vertex at
/// (0.5, 0.25, 0): an interior, smooth vertex of valence `n`, on a unit ring
/// in the z = 0 plane (`n` at least 3).
pub fn wheel(n: u32) -> Mesh {
    let centre = DVec3::new(0.5, 0.25, 0.0);
    let mut m = Mesh::default();
    m.positions.push(centre);
    for i in 0..n {
        let a = std::f64::consts::TAU * f64::from(i) / f64::from(n);
        m.positions.push(centre + DVec3::new(a.cos(), a.sin(), 0.0));
    }
    for i in 0..n {
        m.add_face(&[0, i + 1, (i + 1) % n + 1]);
    }
    m
}

/// Four disjoint cubes of different sizes in one mesh (several connected
/// components, like OpenSubdiv's "four boxes" regression shape).
pub fn four_boxes() -> Mesh {
    let mut m = Mesh::default();
    let c = cube();
    for (k, (offset, scale)) in [
        (DVec3::new(-1.5, -1.5, 0.0), 1.0),
        (DVec3::new(1.5, -1.5, 0.0), 0.8),
        (DVec3::new(-1.5, 1.5, 0.0), 1.2),
        (DVec3::new(1.5, 1.5, 0.3), 0.6),
    ]
    .into_iter()
    .enumerate()
    {
        let base = (8 * k) as u32;
        m.positions
            .extend(c.positions.iter().map(|p| *p * scale + offset));
        for f in c.faces() {
            let shifted: Vec<u32> = f.iter().map(|v| v + base).collect();
            m.add_face(&shifted);
        }
    }
    m
}

/// A regular icosahedron (20 triangles), for Loop.
pub fn icosahedron() -> Mesh {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    mesh(
        &[
            [-1.0, t, 0.0],
            [1.0, t, 0.0],
            [-1.0, -t, 0.0],
            [1.0, -t, 0.0],
            [0.0, -1.0, t],
            [0.0, 1.0, t],
            [0.0, -1.0, -t],
            [0.0, 1.0, -t],
            [t, 0.0, -1.0],
            [t, 0.0, 1.0],
            [-t, 0.0, -1.0],
            [-t, 0.0, 1.0],
        ],
        &[
            &[0, 11, 5],
            &[0, 5, 1],
            &[0, 1, 7],
            &[0, 7, 10],
            &[0, 10, 11],
            &[1, 5, 9],
            &[5, 11, 4],
            &[11, 10, 2],
            &[10, 7, 6],
            &[7, 1, 8],
            &[3, 9, 4],
            &[3, 4, 2],
            &[3, 2, 6],
            &[3, 6, 8],
            &[3, 8, 9],
            &[4, 9, 5],
            &[2, 4, 11],
            &[6, 2, 10],
            &[8, 6, 7],
            &[9, 8, 1],
        ],
    )
}

/// A regular octahedron (8 triangles, every vertex of valence 4): the
/// vertices ±x, ±y, ±z in that order (+x, -x, +y, -y, +z, -z), the four
/// faces around +z first. A closed triangle mesh for Loop, or for
/// Catmull-Clark's treatment of triangles.
pub fn octahedron() -> Mesh {
    mesh(
        &[
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
        ],
        &[
            &[0, 2, 4],
            &[2, 1, 4],
            &[1, 3, 4],
            &[3, 0, 4],
            &[2, 0, 5],
            &[1, 2, 5],
            &[3, 1, 5],
            &[0, 3, 5],
        ],
    )
}

/// A "book": `pages` faces hinged on one edge (vertices 0 and 1), each a
/// triangle (`corners == 3`) or a quad (`corners == 4`, any other value
/// counts as 4), fanned around the spine. With three or more pages the spine
/// is non-manifold, so both engines make it infinitely sharp; its refined
/// edge points have `2 × pages` faces, which is what overruns OpenSubdiv
/// 3.5's limit masks from about 13 pages on.
pub fn book(pages: u32, corners: u32) -> Mesh {
    let mut m = Mesh::default();
    m.positions.push(DVec3::ZERO);
    m.positions.push(DVec3::X);
    for p in 0..pages {
        let a = TAU * p as f64 / pages.max(1) as f64;
        let out = DVec3::new(0.0, a.cos(), a.sin());
        if corners == 3 {
            m.positions.push(DVec3::new(0.5, 0.0, 0.0) + out);
            m.add_face(&[0, 1, 2 + p]);
        } else {
            m.positions.push(DVec3::X + out);
            m.positions.push(out);
            m.add_face(&[0, 1, 2 + 2 * p, 3 + 2 * p]);
        }
    }
    m
}

/// Three quads sharing one edge (a non-manifold "fin") plus a quad on each side.
pub fn fin() -> Mesh {
    mesh(
        &[
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 0.0, 0.0],
            [-1.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 1.0, 1.0],
            [2.0, 0.0, 0.1],
            [2.0, 1.0, 0.1],
        ],
        &[&[0, 2, 3, 1], &[1, 5, 4, 0], &[0, 1, 7, 6], &[2, 8, 9, 3]],
    )
}

/// Two quads sharing a single vertex (a "bowtie") and a third quad hanging off one of them.
pub fn bowtie() -> Mesh {
    mesh(
        &[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.2],
            [-1.0, 0.0, 0.0],
            [-1.0, -1.0, 0.0],
            [0.0, -1.0, -0.2],
            [2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
        ],
        &[&[0, 1, 2, 3], &[0, 4, 5, 6], &[1, 7, 8, 2]],
    )
}

/// A grid with a vertex whose faces wind inconsistently, a degenerate face
/// (a repeated vertex) and a face repeating an edge: the non-manifold input
/// OpenSubdiv still accepts.
pub fn inconsistent() -> Mesh {
    let mut m = grid(3, 2);
    m.fvar_channels.clear();
    // Flip face 1's winding.
    let r = m.face_offsets[1] as usize..m.face_offsets[2] as usize;
    m.face_vertices[r].reverse();
    // A degenerate quad (vertex 0 twice) on top of face 0.
    m.positions.push(DVec3::new(0.5, -0.7, 0.3));
    let extra = (m.positions.len() - 1) as u32;
    m.add_face(&[0, extra, 1, 0]);
    m
}

/// Splits every quad of a mesh into two triangles (other faces are kept), for Loop.
pub fn triangulate(mesh: &Mesh) -> Mesh {
    let mut out = Mesh {
        positions: mesh.positions.clone(),
        ..Mesh::default()
    };
    for (i, f) in mesh.faces().enumerate() {
        if f.len() == 4 {
            // Alternate the diagonal for a less regular pattern.
            if i % 2 == 0 {
                out.add_face(&[f[0], f[1], f[2]]);
                out.add_face(&[f[0], f[2], f[3]]);
            } else {
                out.add_face(&[f[0], f[1], f[3]]);
                out.add_face(&[f[1], f[2], f[3]]);
            }
        } else {
            out.add_face(f);
        }
    }
    out.creases = mesh.creases.clone();
    out.corners = mesh.corners.clone();
    out
}

/// As [`triangulate`], keeping the face-varying channels (split the same way).
pub fn triangulate_with_uvs(mesh: &Mesh) -> Mesh {
    let mut out = triangulate(mesh);
    for ch in &mesh.fvar_channels {
        let mut indices = Vec::with_capacity(out.face_vertices.len());
        for (i, (f, range)) in mesh.faces().zip(mesh.face_offsets.windows(2)).enumerate() {
            let vals = &ch.indices[range[0] as usize..range[1] as usize];
            if f.len() == 4 {
                if i % 2 == 0 {
                    indices.extend([vals[0], vals[1], vals[2], vals[0], vals[2], vals[3]]);
                } else {
                    indices.extend([vals[0], vals[1], vals[3], vals[1], vals[2], vals[3]]);
                }
            } else {
                indices.extend_from_slice(vals);
            }
        }
        out.fvar_channels.push(crate::mesh::FVarChannel {
            width: ch.width,
            values: ch.values.clone(),
            indices,
        });
    }
    out.holes.clear();
    out
}

/// The conformance corpus: every shape with a name, covering the cases
/// OpenSubdiv distinguishes (n-gons, poles, boundaries, creases, corners,
/// holes, non-manifold features, UV seams). Triangle-only shapes are marked
/// so Loop can be run on them too.
pub fn corpus() -> Vec<(String, Mesh)> {
    let mut out: Vec<(String, Mesh)> = Vec::new();
    let mut push = |name: String, m: Mesh| out.push((name, m));
    push("cube".into(), cube());
    push("cube-uv".into(), cube_with_uvs());
    push("torus".into(), torus(8, 6));
    push("tetrahedron".into(), tetrahedron());
    push("icosahedron".into(), icosahedron());
    push("four-boxes".into(), four_boxes());
    for n in 3..=12 {
        push(format!("prism-{n}"), prism(n));
    }
    for n in [3, 4, 5, 6, 8] {
        push(format!("pyramid-{n}"), pyramid(n));
    }
    for n in 3..=12 {
        push(format!("pole-{n}"), pole(n));
    }
    push("grid-4x3".into(), grid(4, 3));
    push("grid-1x1".into(), grid(1, 1));
    for n in [1, 2, 3, 5] {
        push(format!("fan-{n}"), fan(n, 2.5));
    }
    push("fan-closed-5".into(), {
        let mut m = fan(5, TAU * 5.0 / 6.0);
        m.add_face(&[0, 6, 1]);
        m
    });
    // Creases of every kind of sharpness on a cube.
    for &s in &[0.0f32, 0.3, 0.5, 1.0, 1.5, 2.0, 2.7, 3.0, 4.25, 9.99, 10.0] {
        let mut m = cube();
        m.add_crease(0, 1, s);
        m.add_crease(1, 2, s * 0.5);
        m.add_crease(1, 5, s);
        push(format!("cube-crease-{s}"), m);
    }
    // A crease loop around a torus and a chain ending inside the mesh (darts).
    push("torus-crease-loop".into(), {
        let mut m = torus(8, 6);
        for i in 0..8 {
            m.add_crease(i, (i + 1) % 8, 2.5);
        }
        m
    });
    push("torus-dart-chain".into(), {
        let mut m = torus(8, 6);
        m.add_crease(9, 10, 10.0);
        m.add_crease(10, 11, 1.5);
        m.add_crease(11, 19, 0.8);
        m
    });
    push("grid-crease-chain".into(), {
        let mut m = grid(4, 4);
        m.add_crease(6, 7, 3.0);
        m.add_crease(7, 8, 1.25);
        m.add_crease(7, 12, 10.0);
        m
    });
    for &s in &[0.5f32, 1.0, 2.5, 10.0] {
        let mut m = cube();
        m.add_corner(0, s);
        m.add_corner(6, s * 0.3);
        m.add_crease(0, 1, 1.0);
        push(format!("cube-corner-{s}"), m);
    }
    push("grid-corners".into(), {
        let mut m = grid(3, 3);
        m.add_corner(5, 2.0);
        m.add_corner(0, 10.0);
        m
    });
    push("grid-holes".into(), {
        let mut m = grid(4, 4);
        m.holes.extend([5, 6, 15]);
        m
    });
    push("cube-hole".into(), {
        let mut m = cube();
        m.holes.push(1);
        m
    });
    push("tri-grid".into(), triangulate(&grid(4, 3)));
    push("tri-torus-crease".into(), {
        let mut m = triangulate(&torus(8, 6));
        for i in 0..8 {
            m.add_crease(i, (i + 1) % 8, 1.75);
        }
        m.add_corner(20, 2.5);
        m
    });
    push("tri-grid-creases".into(), {
        let mut m = grid(4, 4);
        m.add_crease(6, 7, 3.0);
        m.add_crease(7, 8, 0.5);
        m.add_crease(7, 12, 10.0);
        m.add_corner(18, 1.5);
        triangulate(&m)
    });
    push("tri-grid-holes".into(), {
        let mut m = triangulate(&grid(4, 4));
        m.holes.extend([3, 10, 17]);
        m
    });
    push("fin".into(), fin());
    push("bowtie".into(), bowtie());
    push("inconsistent".into(), inconsistent());
    push("crease-without-edge".into(), {
        let mut m = cube();
        m.add_crease(0, 6, 3.0);
        m
    });
    // The benchmark's production-like mesh, small: n-gons, triangle pairs,
    // semi-sharp and infinite creases, corners, holes and UV seams at once.
    push("production".into(), production(16, 9));
    out
}

#[cfg(test)]
mod corpus_tests {
    use super::*;

    #[test]
    fn corpus_is_valid() {
        let corpus = corpus();
        assert!(corpus.len() > 60);
        for (name, m) in &corpus {
            m.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
        }
    }
}
