//! Doo-Sabin subdivision: weights, topology, the biquadratic B-spline on
//! regular grids, and boundaries. (`subdiv refine --scheme doo-sabin` is
//! tested in `tests/cli/doo_sabin.rs`.)

mod support;

use glam::{DMat3, DVec3};
use std::collections::{HashMap, HashSet};
use subdiv::Mesh;
use subdiv::curve::{self, CurveScheme};
use subdiv::doo_sabin::{self, Boundary, DooSabinError, DooSabinOptions, Weights, corner_weights};
use subdiv::patch::ControlGrid;
use support::Rng;

const ALL_OPTIONS: [DooSabinOptions; 4] = [
    DooSabinOptions {
        weights: Weights::Original,
        boundary: Boundary::Open,
    },
    DooSabinOptions {
        weights: Weights::Centroid,
        boundary: Boundary::Open,
    },
    DooSabinOptions {
        weights: Weights::Original,
        boundary: Boundary::Chaikin,
    },
    DooSabinOptions {
        weights: Weights::Centroid,
        boundary: Boundary::Chaikin,
    },
];

/// Every directed edge of the mesh, with how often it occurs.
fn directed_edges(mesh: &Mesh) -> HashMap<(u32, u32), usize> {
    let mut edges = HashMap::new();
    for face in mesh.faces() {
        for (i, &a) in face.iter().enumerate() {
            *edges.entry((a, face[(i + 1) % face.len()])).or_insert(0) += 1;
        }
    }
    edges
}

/// Checks that the mesh is an oriented manifold: every directed edge occurs
/// once, and its reverse at most once. Returns the boundary edges (no reverse).
fn check_oriented(mesh: &Mesh) -> Vec<(u32, u32)> {
    mesh.validate().unwrap();
    let edges = directed_edges(mesh);
    let mut boundary = Vec::new();
    for (&(a, b), &count) in &edges {
        assert_eq!(count, 1, "directed edge {a}→{b} occurs {count} times");
        assert_ne!(a, b);
        if !edges.contains_key(&(b, a)) {
            boundary.push((a, b));
        }
    }
    boundary.sort_unstable();
    boundary
}

/// The boundary loops of an oriented mesh, each in its direction.
fn boundary_loops(mesh: &Mesh) -> Vec<Vec<u32>> {
    let boundary = check_oriented(mesh);
    let next: HashMap<u32, u32> = boundary.iter().copied().collect();
    assert_eq!(
        next.len(),
        boundary.len(),
        "a vertex starts two boundary edges"
    );
    let mut seen = HashSet::new();
    let mut loops = Vec::new();
    for &(start, _) in &boundary {
        if seen.contains(&start) {
            continue;
        }
        let mut l = vec![start];
        seen.insert(start);
        let mut v = next[&start];
        while v != start {
            assert!(seen.insert(v));
            l.push(v);
            v = next[&v];
        }
        loops.push(l);
    }
    loops
}

/// Whether `a` equals `b` up to a cyclic rotation (same direction), within `tol`.
fn same_cycle(a: &[DVec3], b: &[DVec3], tol: f64) -> bool {
    a.len() == b.len()
        && (0..b.len()).any(|shift| {
            a.iter()
                .enumerate()
                .all(|(i, &p)| (p - b[(i + shift) % b.len()]).length() < tol)
        })
}

/// A grid with random heights, as a control grid and as its quad mesh.
fn grid(nu: usize, nv: usize, seed: u64) -> ControlGrid {
    let mut rng = Rng(seed);
    let h: Vec<f64> = (0..nu * nv).map(|_| rng.next()).collect();
    ControlGrid::from_fn(nu, nv, 2, false, false, |i, j| {
        DVec3::new(
            i as f64 + 0.2 * h[(j * nu + i + 1) % h.len()],
            j as f64,
            h[j * nu + i],
        )
    })
    .unwrap()
}

/// The grid coordinates of Doo-Sabin's output vertices, from those of its
/// input: the corner at vertex (a, b) of the cell with lowest corner (a0, b0)
/// is refined grid point (2 a0 + a - a0, 2 b0 + b - b0).
fn refined_coords(mesh: &Mesh, coords: &[(usize, usize)]) -> Vec<(usize, usize)> {
    let mut out = Vec::with_capacity(mesh.face_vertices.len());
    for face in mesh.faces() {
        let a0 = face.iter().map(|&v| coords[v as usize].0).min().unwrap();
        let b0 = face.iter().map(|&v| coords[v as usize].1).min().unwrap();
        for &v in face {
            let (a, b) = coords[v as usize];
            out.push((a0 + a, b0 + b));
        }
    }
    out
}

/// A face as grid coordinates, rotated to start at its smallest element.
fn normalized(face: impl Iterator<Item = (usize, usize)>) -> Vec<(usize, usize)> {
    let mut f: Vec<_> = face.collect();
    let k = (0..f.len()).min_by_key(|&i| f[i]).unwrap();
    f.rotate_left(k);
    f
}

// ---------------------------------------------------------------------------
// weights
// ---------------------------------------------------------------------------

#[test]
fn corner_weights_hand_values_and_sums() {
    let q = [9.0 / 16.0, 3.0 / 16.0, 1.0 / 16.0, 3.0 / 16.0];
    for w in [Weights::Original, Weights::Centroid] {
        assert_eq!(corner_weights(4, 0, w), q);
        assert_eq!(
            corner_weights(4, 2, w),
            [1.0 / 16.0, 3.0 / 16.0, 9.0 / 16.0, 3.0 / 16.0]
        );
    }
    assert_eq!(
        corner_weights(3, 0, Weights::Original),
        [2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0]
    );
    assert_eq!(
        corner_weights(3, 2, Weights::Centroid),
        [5.0 / 24.0, 5.0 / 24.0, 7.0 / 12.0]
    );
    // A hexagon: α = (n + 5) / 4n and (3 + 2 cos(2πk/6)) / 24: 11/24, 4/24, 2/24, 1/24, 2/24, 4/24.
    assert_eq!(
        corner_weights(6, 0, Weights::Original),
        [
            11.0 / 24.0,
            4.0 / 24.0,
            2.0 / 24.0,
            1.0 / 24.0,
            2.0 / 24.0,
            4.0 / 24.0
        ]
    );
    for n in 3..=12 {
        for i in 0..n {
            let orig = corner_weights(n, i, Weights::Original);
            assert!((orig.iter().sum::<f64>() - 1.0).abs() < 1e-15, "n={n}");
            for (j, &a) in orig.iter().enumerate() {
                let k = (j + n - i) % n;
                let expected = if k == 0 {
                    (n as f64 + 5.0) / (4.0 * n as f64)
                } else {
                    (3.0 + 2.0 * (std::f64::consts::TAU * k as f64 / n as f64).cos())
                        / (4.0 * n as f64)
                };
                assert!((a - expected).abs() < 1e-16, "n={n} i={i} j={j}");
            }
            let cent = corner_weights(n, i, Weights::Centroid);
            assert!((cent.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        }
    }
}

#[test]
fn centroid_corner_points_average_vertex_edge_midpoints_and_centroid() {
    let mut rng = Rng(17);
    for n in 3..=8u32 {
        let positions: Vec<DVec3> = (0..n)
            .map(|_| DVec3::new(rng.next(), rng.next(), rng.next()))
            .collect();
        let face: Vec<u32> = (0..n).collect();
        let mesh = Mesh::from_faces(positions.clone(), &[&face]);
        let opts = DooSabinOptions {
            weights: Weights::Centroid,
            boundary: Boundary::Open,
        };
        let out = doo_sabin::refine_once(&mesh, &opts).unwrap();
        assert_eq!(out.face_count(), 1);
        let c = positions.iter().sum::<DVec3>() / n as f64;
        let n = n as usize;
        for i in 0..n {
            let (p, prev, next) = (
                positions[i],
                positions[(i + n - 1) % n],
                positions[(i + 1) % n],
            );
            let expected = (p + (p + next) / 2.0 + (prev + p) / 2.0 + c) / 4.0;
            assert!((out.positions[i] - expected).length() < 4e-15);
        }
    }
}

#[test]
fn triangles_use_their_own_weights() {
    let tet = subdiv::shapes::tetrahedron();
    let face = tet.face(0).to_vec();
    let p = |k: usize| tet.positions[face[k] as usize];
    for (weights, own, other) in [
        (Weights::Original, 2.0 / 3.0, 1.0 / 6.0),
        (Weights::Centroid, 7.0 / 12.0, 5.0 / 24.0),
    ] {
        let opts = DooSabinOptions {
            weights,
            boundary: Boundary::Open,
        };
        let out = doo_sabin::refine_once(&tet, &opts).unwrap();
        let expected = p(0) * own + p(1) * other + p(2) * other;
        assert!((out.positions[0] - expected).length() < 1e-15, "{weights}");
        // 12 corners; faces: 4 F-triangles, 6 E-quads, 4 V-triangles.
        assert_eq!((out.vertex_count(), out.face_count()), (12, 14));
        check_oriented(&out);
    }
}

// ---------------------------------------------------------------------------
// the regular grid: biquadratic B-spline splitting
// ---------------------------------------------------------------------------

#[test]
fn on_a_regular_quad_grid_one_level_is_biquadratic_splitting() {
    for weights in [Weights::Original, Weights::Centroid] {
        let g = grid(6, 5, 3);
        let mesh = g.to_mesh();
        let opts = DooSabinOptions {
            weights,
            boundary: Boundary::Open,
        };
        let out = doo_sabin::refine_once(&mesh, &opts).unwrap();
        let r = g.refine().unwrap();
        assert_eq!(out.vertex_count(), r.nu() * r.nv());
        assert_eq!(out.face_count(), (r.nu() - 1) * (r.nv() - 1));
        let coords: Vec<(usize, usize)> = (0..g.nv())
            .flat_map(|j| (0..g.nu()).map(move |i| (i, j)))
            .collect();
        let fine = refined_coords(&mesh, &coords);
        // Every refined grid point exactly once, at the split's position.
        let mut hit = HashSet::new();
        for (v, &(i, j)) in fine.iter().enumerate() {
            assert!(hit.insert((i, j)));
            assert!(
                (out.positions[v] - r.point(i, j)).length() < 1e-14,
                "({i}, {j})"
            );
        }
        // The same quads, in the same orientation.
        let ds_faces: HashSet<Vec<(usize, usize)>> = out
            .faces()
            .map(|f| normalized(f.iter().map(|&v| fine[v as usize])))
            .collect();
        let grid_faces: HashSet<Vec<(usize, usize)>> = r
            .to_mesh()
            .faces()
            .map(|f| {
                normalized(
                    f.iter()
                        .map(|&v| (v as usize % r.nu(), v as usize / r.nu())),
                )
            })
            .collect();
        assert_eq!(ds_faces, grid_faces);
    }
}

#[test]
fn on_a_regular_quad_grid_every_level_is_biquadratic_splitting() {
    let g = grid(5, 5, 9);
    let levels = doo_sabin::refine(&g.to_mesh(), &DooSabinOptions::default(), 3).unwrap();
    let mut coords: Vec<(usize, usize)> = (0..g.nv())
        .flat_map(|j| (0..g.nu()).map(move |i| (i, j)))
        .collect();
    let mut r = g.clone();
    for k in 1..=3 {
        coords = refined_coords(&levels[k - 1], &coords);
        r = r.refine().unwrap();
        for (v, &(i, j)) in coords.iter().enumerate() {
            assert!(
                (levels[k].positions[v] - r.point(i, j)).length() < 1e-14,
                "level {k} ({i}, {j})"
            );
        }
    }
    // The limit is the biquadratic surface: level 3 is within 4^-3 of it.
    let ([_, s1], [_, t1]) = g.domain();
    let mut max: f64 = 0.0;
    for j in 0..r.nv() {
        for i in 0..r.nu() {
            let (s, t) = r.greville(i, j);
            let (s, t) = (s / 8.0, t / 8.0);
            if (0.0..=s1).contains(&s) && (0.0..=t1).contains(&t) {
                max = max.max((r.point(i, j) - g.eval(s, t).unwrap()).length());
            }
        }
    }
    assert!(max < 0.02, "{max}");
}

// ---------------------------------------------------------------------------
// closed meshes
// ---------------------------------------------------------------------------

#[test]
fn cube_counts_valences_orientation_and_euler_characteristic() {
    let cube = subdiv::shapes::cube();
    for opts in ALL_OPTIONS {
        let levels = doo_sabin::refine(&cube, &opts, 4).unwrap();
        let counts: Vec<(usize, usize)> = levels
            .iter()
            .map(|m| (m.vertex_count(), m.face_count()))
            .collect();
        assert_eq!(
            counts,
            [(8, 6), (24, 26), (96, 98), (384, 386), (1536, 1538)]
        );
        for (k, m) in levels.iter().enumerate().skip(1) {
            assert!(check_oriented(m).is_empty(), "closed");
            let edges = directed_edges(m).len() / 2;
            assert_eq!(
                m.vertex_count() as i64 - edges as i64 + m.face_count() as i64,
                2,
                "level {k}"
            );
            // Every new vertex is in one F-face, two E-faces and one V-face.
            let mut valence = vec![0; m.vertex_count()];
            for &v in &m.face_vertices {
                valence[v as usize] += 1;
            }
            assert!(valence.iter().all(|&n| n == 4), "level {k}");
        }
        // Level 1: the F-faces first, in face order.
        assert_eq!(levels[1].face(0), &[0, 1, 2, 3]);
        assert_eq!(levels[1].face(5), &[20, 21, 22, 23]);
        // Symmetric about the origin, inside the cube, touching its faces at
        // their centres (the F-faces of the cube's faces stay in their planes).
        for m in &levels[1..] {
            let c = m.positions.iter().sum::<DVec3>() / m.vertex_count() as f64;
            assert!(c.length() < 1e-14);
            let e = m
                .positions
                .iter()
                .map(|p| p.abs().max_element())
                .fold(0.0, f64::max);
            assert_eq!(e, 0.5);
        }
        let corner = levels[4]
            .positions
            .iter()
            .map(|p| p.abs().element_sum())
            .fold(0.0, f64::max);
        assert!(corner < 1.5 - 0.1, "the cube's corners are cut: {corner}");
    }
}

#[test]
fn refinement_is_affine_invariant() {
    let a = DMat3::from_cols(
        DVec3::new(1.2, 0.3, -0.1),
        DVec3::new(-0.4, 0.9, 0.2),
        DVec3::new(0.1, 0.5, 1.7),
    );
    let b = DVec3::new(3.0, -1.0, 0.5);
    for mesh in [
        subdiv::shapes::pole(5),
        subdiv::shapes::prism(7),
        subdiv::shapes::fan(4, 3.0),
    ] {
        for opts in ALL_OPTIONS {
            let moved = Mesh {
                positions: mesh.positions.iter().map(|&p| a * p + b).collect(),
                ..mesh.clone()
            };
            let x = doo_sabin::refine(&mesh, &opts, 2).unwrap();
            let y = doo_sabin::refine(&moved, &opts, 2).unwrap();
            assert_eq!(x[2].face_vertices, y[2].face_vertices);
            for (p, q) in x[2].positions.iter().zip(&y[2].positions) {
                assert!((a * *p + b - *q).length() < 1e-13);
            }
        }
    }
}

// ---------------------------------------------------------------------------
// boundaries
// ---------------------------------------------------------------------------

fn open_cube() -> Mesh {
    let cube = subdiv::shapes::cube();
    let faces: Vec<&[u32]> = cube.faces().filter(|f| f != &[4, 5, 6, 7]).collect();
    Mesh::from_faces(cube.positions.clone(), &faces)
}

#[test]
fn open_boundary_makes_no_faces_along_the_boundary() {
    let opts = DooSabinOptions::default();
    // Open cube: 20 corners; 5 F + 8 interior edges + 4 interior vertices.
    let out = doo_sabin::refine_once(&open_cube(), &opts).unwrap();
    assert_eq!((out.vertex_count(), out.face_count()), (20, 17));
    assert_eq!(boundary_loops(&out).len(), 1);
    // A fan of 4 triangles: 12 corners; 4 F + 3 E, no V (every vertex is on the boundary).
    let out = doo_sabin::refine_once(&subdiv::shapes::fan(4, 3.0), &opts).unwrap();
    assert_eq!((out.vertex_count(), out.face_count()), (12, 7));
    check_oriented(&out);
}

#[test]
fn chaikin_boundary_refines_the_boundary_polygon_by_chaikin() {
    let opts = DooSabinOptions {
        weights: Weights::Original,
        boundary: Boundary::Chaikin,
    };
    for mesh in [
        grid(5, 4, 1).to_mesh(),
        open_cube(),
        subdiv::shapes::fan(5, 4.0),
        subdiv::shapes::fan(3, 1.5),
        subdiv::shapes::grid(1, 1),
    ] {
        let loops0 = boundary_loops(&mesh);
        assert_eq!(loops0.len(), 1);
        let polygon: Vec<DVec3> = loops0[0]
            .iter()
            .map(|&v| mesh.positions[v as usize])
            .collect();
        let levels = doo_sabin::refine(&mesh, &opts, 4).unwrap();
        for (k, m) in levels.iter().enumerate() {
            let loops = boundary_loops(m);
            assert_eq!(loops.len(), 1, "level {k}");
            let got: Vec<DVec3> = loops[0].iter().map(|&v| m.positions[v as usize]).collect();
            let expected = curve::refine(&polygon, CurveScheme::Chaikin, true, k as u32).unwrap();
            assert!(same_cycle(&got, &expected, 1e-14), "level {k}");
        }
        // Counts: corners, plus two points per boundary edge.
        let nc = mesh.face_vertices.len();
        assert_eq!(levels[1].vertex_count(), nc + 2 * polygon.len());
    }
}

#[test]
fn chaikin_boundary_counts_on_a_grid() {
    // 4 × 3 quads: 48 corners + 2 · 14 boundary points; faces: 12 F + 17 interior E
    // + 14 boundary E + 6 interior V + 14 boundary V.
    let mesh = subdiv::shapes::grid(4, 3);
    let opts = DooSabinOptions {
        weights: Weights::Centroid,
        boundary: Boundary::Chaikin,
    };
    let out = doo_sabin::refine_once(&mesh, &opts).unwrap();
    assert_eq!(out.vertex_count(), 48 + 28);
    assert_eq!(out.face_count(), 12 + 17 + 14 + 6 + 14);
    // The corner vertex of the grid: a triangle of its corner point and two boundary points.
    let triangles = out.faces().filter(|f| f.len() == 3).count();
    assert_eq!(triangles, 4);
}

#[test]
fn non_manifold_meshes() {
    for mesh in [
        subdiv::shapes::fin(),
        subdiv::shapes::bowtie(),
        subdiv::shapes::inconsistent(),
    ] {
        // The open rule treats non-manifold edges and vertices like boundaries.
        let levels = doo_sabin::refine(&mesh, &DooSabinOptions::default(), 2).unwrap();
        for m in &levels {
            m.validate().unwrap();
        }
        // The chaikin rule needs a manifold mesh: a typed error, no panic.
        let _ = doo_sabin::refine(
            &mesh,
            &DooSabinOptions {
                weights: Weights::Original,
                boundary: Boundary::Chaikin,
            },
            2,
        );
    }
    let chaikin = DooSabinOptions {
        weights: Weights::Original,
        boundary: Boundary::Chaikin,
    };
    assert_eq!(
        doo_sabin::refine_once(&subdiv::shapes::fin(), &chaikin),
        Err(DooSabinError::NonManifoldEdge {
            a: 0,
            b: 1,
            faces: 3
        })
    );
    assert_eq!(
        doo_sabin::refine_once(&subdiv::shapes::bowtie(), &chaikin),
        Err(DooSabinError::NonManifoldVertex(0))
    );
    // Open: the fin's three faces around edge 0-1 get no E-face there.
    let out = doo_sabin::refine_once(&subdiv::shapes::fin(), &DooSabinOptions::default()).unwrap();
    assert_eq!(out.face_count(), 4 + 1);
}

#[test]
fn invalid_meshes_are_typed_errors() {
    let mut mesh = subdiv::shapes::cube();
    mesh.face_vertices[3] = 99;
    assert!(matches!(
        doo_sabin::refine_once(&mesh, &DooSabinOptions::default()),
        Err(DooSabinError::Mesh(_))
    ));
    let mut mesh = subdiv::shapes::cube();
    mesh.positions[2].x = f64::NAN;
    assert!(matches!(
        doo_sabin::refine(&mesh, &DooSabinOptions::default(), 1),
        Err(DooSabinError::Mesh(_))
    ));
    // An empty mesh refines to an empty mesh.
    let levels = doo_sabin::refine(&Mesh::default(), &DooSabinOptions::default(), 2).unwrap();
    assert!(levels.iter().all(|m| m.face_count() == 0));
    assert_eq!("centroid".parse::<Weights>(), Ok(Weights::Centroid));
    assert_eq!("chaikin".parse::<Boundary>(), Ok(Boundary::Chaikin));
    assert!("smooth".parse::<Boundary>().is_err());
}
