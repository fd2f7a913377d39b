//! Exact-math checks of the native engine that need no OpenSubdiv: limit
//! positions against the analytic uniform B-spline and box-spline surfaces,
//! invariance of the limit under refinement, and affine invariance.

use glam::{DMat3, DVec3};
use subdiv::{
    BoundaryInterpolation, Mesh, Options, Scheme, UniformOptions, refiner::Refiner, shapes,
};

/// The uniform cubic B-spline basis from its truncated-power definition:
/// N(t) = (1/6) Σ_{k=0..4} (-1)^k C(4,k) (t - k + 2)_+^3, centred at 0.
fn cubic_bspline(t: f64) -> f64 {
    let binom = [1.0, 4.0, 6.0, 4.0, 1.0];
    (0..5)
        .map(|k| {
            let x = t - k as f64 + 2.0;
            let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
            sign * binom[k] * if x > 0.0 { x * x * x } else { 0.0 }
        })
        .sum::<f64>()
        / 6.0
}

fn cubic_bspline_derivative(t: f64) -> f64 {
    let h = 1e-6;
    (cubic_bspline(t + h) - cubic_bspline(t - h)) / (2.0 * h)
}

/// A torus-like closed grid of `n × n` quads with irregular (random-looking but
/// fixed) control points: every vertex is regular (valence 4).
fn periodic_grid(n: u32) -> (Mesh, Vec<Vec<DVec3>>) {
    let mut mesh = shapes::torus(n, n);
    let mut grid = vec![vec![DVec3::ZERO; n as usize]; n as usize];
    for j in 0..n {
        for i in 0..n {
            let k = (j * n + i) as usize;
            let wobble = DVec3::new(
                ((k * 37) % 11) as f64,
                ((k * 53) % 7) as f64,
                ((k * 17) % 5) as f64,
            ) * 0.01;
            mesh.positions[k] += wobble;
            grid[j as usize][i as usize] = mesh.positions[k];
        }
    }
    (mesh, grid)
}

/// The bicubic B-spline surface of a periodic control grid at (u, v), in
/// units of the control spacing, and its two partial derivatives.
fn bicubic(grid: &[Vec<DVec3>], u: f64, v: f64) -> (DVec3, DVec3, DVec3) {
    let n = grid.len() as i64;
    let (mut s, mut su, mut sv) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
    let (iu, iv) = (u.floor() as i64, v.floor() as i64);
    for b in iv - 2..=iv + 2 {
        for a in iu - 2..=iu + 2 {
            let p = grid[b.rem_euclid(n) as usize][a.rem_euclid(n) as usize];
            let (nu, nv) = (cubic_bspline(u - a as f64), cubic_bspline(v - b as f64));
            s += p * nu * nv;
            su += p * cubic_bspline_derivative(u - a as f64) * nv;
            sv += p * nu * cubic_bspline_derivative(v - b as f64);
        }
    }
    (s, su, sv)
}

#[test]
fn bspline_basis_from_the_definition() {
    // Known values: N(0) = 4/6, N(±1) = 1/6, N(±2) = 0, N(1/2) = 23/48.
    assert!((cubic_bspline(0.0) - 4.0 / 6.0).abs() < 1e-15);
    assert!((cubic_bspline(1.0) - 1.0 / 6.0).abs() < 1e-15);
    assert!((cubic_bspline(-1.0) - 1.0 / 6.0).abs() < 1e-15);
    assert!(cubic_bspline(2.0).abs() < 1e-15);
    assert!((cubic_bspline(0.5) - 23.0 / 48.0).abs() < 1e-15);
}

/// On a closed regular quad grid the Catmull-Clark limit surface is the
/// uniform bicubic B-spline surface: the limit position of every vertex of
/// level k equals the surface evaluated at that vertex's dyadic parameter.
#[test]
fn catmark_limit_is_the_bicubic_bspline() {
    let n = 8;
    let (mesh, grid) = periodic_grid(n);
    let mut r = Refiner::new(&mesh, &Options::default()).unwrap();
    for level in 0..=3u32 {
        r.refine_uniform(UniformOptions::new(level).full_topology(true))
            .unwrap();
        let positions = r.refine_positions(&mesh.positions).unwrap();
        let last: Vec<f64> = positions[level as usize]
            .iter()
            .flat_map(|p| p.to_array())
            .collect();
        let limit = r.limit(3, &last).unwrap();
        // Children of base vertices keep their parameters; the limit there is
        // S(i, j) for base vertex (i, j), at every level.
        for j in 0..n as usize {
            for i in 0..n as usize {
                let (s, su, sv) = bicubic(&grid, i as f64, j as f64);
                let v = j * n as usize + i; // children of vertices come first, in order
                let p = DVec3::new(
                    limit.positions[3 * v],
                    limit.positions[3 * v + 1],
                    limit.positions[3 * v + 2],
                );
                assert!(
                    (p - s).length() < 1e-12,
                    "level {level} vertex ({i},{j}): {p} vs {s}"
                );
                let du = DVec3::from_slice(&limit.du[3 * v..]);
                let dv = DVec3::from_slice(&limit.dv[3 * v..]);
                let normal = du.cross(dv).normalize();
                let expected = su.cross(sv).normalize();
                assert!(
                    normal.dot(expected).abs() > 1.0 - 1e-8,
                    "level {level} normal at ({i},{j})"
                );
            }
        }
        // Face points of level 0 sit at (i + 1/2, j + 1/2).
        if level >= 1 {
            let face_point_limit = {
                let mut r1 = Refiner::new(&mesh, &Options::default()).unwrap();
                r1.refine_uniform(UniformOptions::new(1).full_topology(true))
                    .unwrap();
                let p1 = r1.refine_positions(&mesh.positions).unwrap();
                let flat: Vec<f64> = p1[1].iter().flat_map(|p| p.to_array()).collect();
                r1.limit(3, &flat).unwrap()
            };
            for f in 0..(n * n) as usize {
                let (i, j) = (f % n as usize, f / n as usize);
                let (s, _, _) = bicubic(&grid, i as f64 + 0.5, j as f64 + 0.5);
                let v = (n * n) as usize + f;
                let p = DVec3::from_slice(&face_point_limit.positions[3 * v..]);
                assert!((p - s).length() < 1e-12, "face point ({i},{j}): {p} vs {s}");
            }
        }
    }
}

/// A closed regular triangle grid (every vertex of valence 6).
fn periodic_triangles(n: u32) -> Mesh {
    let mut mesh = Mesh::default();
    for j in 0..n {
        for i in 0..n {
            let k = (j * n + i) as f64;
            mesh.positions
                .push(DVec3::new(i as f64, j as f64, (k * 0.37).sin() * 0.2));
        }
    }
    let at = |i: u32, j: u32| (j % n) * n + (i % n);
    for j in 0..n {
        for i in 0..n {
            mesh.add_face(&[at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            mesh.add_face(&[at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    mesh
}

/// The Loop limit surface of a regular triangle grid is the quartic
/// three-direction box spline M_{222}; at lattice points it takes the value
/// 1/2 at the point and 1/12 at each of its six lattice neighbours (the
/// values follow from its definition as the convolution of three hat
/// directions; they sum to 1).
#[test]
fn loop_limit_is_the_quartic_box_spline() {
    let n = 8;
    let mesh = periodic_triangles(n);
    let options = Options::default().with_scheme(Scheme::Loop);
    let r = Refiner::new(&mesh, &options).unwrap();
    let flat: Vec<f64> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
    let limit = r.limit(3, &flat).unwrap();
    let at = |i: i64, j: i64| {
        mesh.positions[(j.rem_euclid(n as i64) * n as i64 + i.rem_euclid(n as i64)) as usize]
    };
    for j in 0..n as i64 {
        for i in 0..n as i64 {
            let neighbours = [(1, 0), (1, 1), (0, 1), (-1, 0), (-1, -1), (0, -1)];
            let expected = at(i, j) * 0.5
                + neighbours
                    .iter()
                    .map(|&(a, b)| at(i + a, j + b))
                    .sum::<DVec3>()
                    / 12.0;
            let v = (j * n as i64 + i) as usize;
            let p = DVec3::from_slice(&limit.positions[3 * v..]);
            assert!(
                (p - expected).length() < 1e-14,
                "({i},{j}): {p} vs {expected}"
            );
        }
    }
}

/// The limit surface does not change under refinement: the limit of a
/// vertex's child equals the limit of the vertex, at every level, for every
/// scheme and with creases, corners and boundaries. (Catmull-Clark limit
/// masks assume quads around the vertex, so the reference is level 1, where
/// every face is a quad.)
#[test]
fn limit_is_invariant_under_refinement() {
    let mut creased = shapes::grid(4, 4);
    creased.fvar_channels.clear();
    creased.add_crease(6, 7, 10.0);
    creased.add_crease(7, 8, 10.0);
    creased.add_corner(12, 10.0);
    for (mesh, options) in [
        (shapes::pole(5), Options::default()),
        (
            creased,
            Options::default().with_boundary(BoundaryInterpolation::EdgeAndCorner),
        ),
        (
            shapes::icosahedron(),
            Options::default().with_scheme(Scheme::Loop),
        ),
        (
            shapes::triangulate(&shapes::torus(6, 5)),
            Options::default().with_scheme(Scheme::Loop),
        ),
    ] {
        let mut r = Refiner::new(&mesh, &options).unwrap();
        let flat: Vec<f64> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
        r.refine_uniform(UniformOptions::new(1).full_topology(true))
            .unwrap();
        let level1 = r.interpolate_all(3, &flat).unwrap().pop().unwrap();
        let base_limit = r.limit(3, &level1).unwrap().positions;
        for level in 2..=4 {
            r.refine_uniform(UniformOptions::new(level).full_topology(true))
                .unwrap();
            let last = r.interpolate_all(3, &flat).unwrap().pop().unwrap();
            let limit = r.limit(3, &last).unwrap().positions;
            // In the default order the first vertices are the base vertices' descendants.
            for k in 0..flat.len() {
                assert!(
                    (limit[k] - base_limit[k]).abs() < 1e-12,
                    "{options:?} level {level}: {} vs {}",
                    limit[k],
                    base_limit[k]
                );
            }
        }
    }
}

/// Refining an affinely transformed mesh equals transforming the refined
/// mesh (subdivision weights sum to one), for every scheme and the limit.
#[test]
fn affine_invariance() {
    let m = DMat3::from_cols(
        DVec3::new(1.3, 0.2, -0.4),
        DVec3::new(-0.5, 0.9, 0.1),
        DVec3::new(0.3, 0.7, 1.1),
    );
    let t = DVec3::new(4.0, -2.5, 7.25);
    let map = |p: DVec3| m * p + t;
    for (mesh, scheme) in [
        (shapes::prism(5), Scheme::Catmark),
        (shapes::prism(7), Scheme::Bilinear),
        (shapes::icosahedron(), Scheme::Loop),
    ] {
        let mut creased = mesh.clone();
        creased.add_crease(0, 1, 1.5);
        let options = Options::default().with_scheme(scheme);
        let mut r = Refiner::new(&creased, &options).unwrap();
        r.refine_uniform(UniformOptions::new(3)).unwrap();
        let a = r
            .refine_positions(&creased.positions)
            .unwrap()
            .pop()
            .unwrap();
        let moved: Vec<DVec3> = creased.positions.iter().map(|&p| map(p)).collect();
        let b = r.refine_positions(&moved).unwrap().pop().unwrap();
        for (x, y) in a.iter().zip(&b) {
            assert!(
                (map(*x) - *y).length() < 1e-12,
                "{scheme}: {} vs {}",
                map(*x),
                y
            );
        }
    }
}
