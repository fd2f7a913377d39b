//! The OpenSubdiv bridge against hand-derived Catmull-Clark values, and its
//! error handling.
#![cfg(feature = "osd")]

use approx::assert_abs_diff_eq;
use glam::DVec3;
use subdiv::compare::bbox_diagonal;
use subdiv::osd::{self, TopologyRefiner};
use subdiv::{
    BoundaryInterpolation, Buffer, Error, FVarLinearInterpolation, Mesh, MeshError, Options,
    OsdError, OsdErrorKind, Precision, Scheme, UniformOptions, shapes,
};

fn refine1(mesh: &Mesh, options: &Options) -> Vec<DVec3> {
    osd::refine(mesh, options, UniformOptions::new(1))
        .unwrap()
        .positions[1]
        .clone()
}

fn assert_point(actual: DVec3, expected: DVec3) {
    assert!(
        (actual - expected).length() < 1e-15,
        "expected {expected:?}, got {actual:?} (off by {:e})",
        (actual - expected).length()
    );
}

#[test]
fn version_is_3_5() {
    assert_eq!(osd::version(), "3.5.0");
    assert_eq!(osd::version_number(), 30500);
}

/// Cube corners at ±0.5. After one level, in OpenSubdiv's default order,
/// children of the 8 vertices come first, then the 6 face points, then the 12
/// edge points (edges numbered by first appearance walking the faces).
#[test]
fn cube_face_edge_and_vertex_points_by_hand() {
    let cube = shapes::cube();
    let p = refine1(&cube, &Options::default());
    assert_eq!(p.len(), 8 + 6 + 12);
    // Face point of face 0 (z = -0.5): its centroid.
    assert_point(p[8], DVec3::new(0.0, 0.0, -0.5));
    // Edge 0 runs from vertex 0 (-.5,-.5,-.5) to vertex 3 (-.5,.5,-.5) and
    // borders face 0 (centroid (0,0,-.5)) and face 5 (centroid (-.5,0,0)):
    // (v0 + v3 + f0 + f5) / 4.
    assert_point(p[14], DVec3::new(-0.375, 0.0, -0.375));
    // Vertex 0 has valence 3: (Q + 2R + (n-3)S)/n with Q the mean face point
    // (-1/6 each), R the mean edge midpoint (-1/3 each): -5/18 each.
    assert_point(p[0], DVec3::splat(-5.0 / 18.0));
}

#[test]
fn cube_topology_level_one() {
    let mut r = TopologyRefiner::new(&shapes::cube(), &Options::default()).unwrap();
    r.refine_uniform(UniformOptions::new(1).full_topology(true))
        .unwrap();
    let l0 = r.level(0).unwrap();
    assert_eq!(
        (l0.vertex_count, l0.edge_count, l0.face_count()),
        (8, 12, 6)
    );
    // Edges in order of first appearance: face 0 = [0,3,2,1] gives edges
    // {0,3} {3,2} {2,1} {1,0}; face 1 = [4,5,6,7] the next four.
    let sorted = |e: [u32; 2]| if e[0] < e[1] { e } else { [e[1], e[0]] };
    let first: Vec<[u32; 2]> = l0.edge_vertices[..8].iter().map(|&e| sorted(e)).collect();
    assert_eq!(
        first,
        vec![
            [0, 3],
            [2, 3],
            [1, 2],
            [0, 1],
            [4, 5],
            [5, 6],
            [6, 7],
            [4, 7]
        ]
    );
    let l1 = r.level(1).unwrap();
    assert_eq!(
        (l1.vertex_count, l1.edge_count, l1.face_count()),
        (26, 48, 24)
    );
    // Child j of a quad keeps the parent's orientation, starting at corner j's
    // vertex-child: face 0 = [0,3,2,1] gives child 0 = [0, e(0,3), f0, e(1,0)].
    assert_eq!(l1.face(0), &[0, 14, 8, 17]);
    assert_eq!(l1.face(1), &[14, 3, 15, 8]);
}

#[test]
fn faces_first_ordering() {
    let mut r = TopologyRefiner::new(&shapes::cube(), &Options::default()).unwrap();
    r.refine_uniform(UniformOptions::new(1).faces_first(true))
        .unwrap();
    let base: Vec<f64> = shapes::cube()
        .positions
        .iter()
        .flat_map(|p| p.to_array())
        .collect();
    let p = r.interpolate(1, 3, &base).unwrap();
    // Face points first (face 0's centroid), then edges, then vertices.
    assert_eq!(&p[0..3], &[0.0, 0.0, -0.5]);
    assert_eq!(&p[18..21], &[-0.375, 0.0, -0.375]);
    let v = 18 + 36;
    for c in &p[v..v + 3] {
        assert_abs_diff_eq!(*c, -5.0 / 18.0, epsilon = 1e-15);
    }
}

/// A unit quad: its corner is a boundary vertex with two boundary edges.
#[test]
fn boundary_corner_edge_only_vs_edge_and_corner() {
    let quad = Mesh::from_faces(
        vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
        &[&[0, 1, 2, 3]],
    );
    // Edge-only: the boundary crease rule (1/8, 6/8, 1/8) over its neighbours.
    let edge_only = refine1(
        &quad,
        &Options::default().with_boundary(BoundaryInterpolation::EdgeOnly),
    );
    assert_point(edge_only[0], DVec3::new(0.125, 0.125, 0.0));
    // Edge-and-corner: a vertex with one face is a sharp corner and stays put.
    let corner = refine1(
        &quad,
        &Options::default().with_boundary(BoundaryInterpolation::EdgeAndCorner),
    );
    assert_point(corner[0], DVec3::ZERO);
    // Boundary edge points are midpoints in both modes.
    assert_point(edge_only[5], DVec3::new(0.5, 0.0, 0.0));
}

/// A 2×2 grid with bumps off the middle row and an infinitely sharp crease
/// along that row (vertices 3-4-5, all at y = 1, z = 0).
#[test]
fn infinitely_sharp_crease_keeps_vertices_on_the_crease() {
    let mut mesh = shapes::grid(2, 2);
    mesh.fvar_channels.clear();
    for (i, p) in mesh.positions.iter_mut().enumerate() {
        if !(3..=5).contains(&i) {
            p.z = if i % 2 == 0 { 1.0 } else { -0.5 };
        }
    }
    mesh.positions[4].x = 1.2; // not collinear: checks the weights, not just the line
    mesh.add_crease(3, 4, 10.0);
    mesh.add_crease(4, 5, 10.0);
    let opts = Options::default().with_boundary(BoundaryInterpolation::EdgeOnly);
    let r = osd::refine(&mesh, &opts, UniformOptions::new(3)).unwrap();
    // Level 1: crease vertex rule (v3 + 6 v4 + v5) / 8.
    let p1 = &r.positions[1];
    let expected = (mesh.positions[3] + 6.0 * mesh.positions[4] + mesh.positions[5]) / 8.0;
    assert_point(p1[4], expected);
    // Every level: every vertex on the crease stays in the plane z = 0, y = 1,
    // whatever the bumps around it.
    let sharp_level = &r.levels[3];
    let on_crease: Vec<usize> = (0..sharp_level.vertex_count)
        .filter(|&v| sharp_level.vertex_sharpness[v] >= 10.0 || r.positions[3][v].y == 1.0)
        .collect();
    assert!(
        on_crease.len() >= 17,
        "expected the refined crease, found {}",
        on_crease.len()
    );
    for &v in &on_crease {
        let p = r.positions[3][v];
        assert!(
            p.z.abs() < 1e-15 && (p.y - 1.0).abs() < 1e-15,
            "vertex {v} left the crease: {p:?}"
        );
    }
}

#[test]
fn semi_sharp_crease_decays_by_one_per_level() {
    let mut mesh = shapes::cube();
    mesh.add_crease(0, 1, 2.5);
    let mut r = TopologyRefiner::new(&mesh, &Options::default()).unwrap();
    r.refine_uniform(UniformOptions::new(3).full_topology(true))
        .unwrap();
    let max_sharpness = |l: u32| {
        r.level(l)
            .unwrap()
            .edge_sharpness
            .iter()
            .cloned()
            .fold(0.0f32, f32::max)
    };
    assert_eq!(max_sharpness(0), 2.5);
    assert_eq!(max_sharpness(1), 1.5);
    assert_eq!(max_sharpness(2), 0.5);
    assert_eq!(max_sharpness(3), 0.0);
}

#[test]
fn f32_and_f64_agree() {
    let torus = shapes::torus(12, 8);
    let opts = Options::default();
    let a = osd::refine(
        &torus,
        &opts,
        subdiv::Request::from(UniformOptions::new(3)).precision(Precision::F32),
    )
    .unwrap();
    let b = osd::refine(&torus, &opts, subdiv::Request::from(UniformOptions::new(3))).unwrap();
    assert_eq!(a.levels, b.levels);
    let diag = bbox_diagonal(&b.positions[3]);
    let worst = a.positions[3]
        .iter()
        .zip(&b.positions[3])
        .map(|(x, y)| (*x - *y).length())
        .fold(0.0, f64::max);
    assert!(worst < 1e-6 * diag, "f32 vs f64 differ by {worst:e}");
    assert!(worst > 0.0, "f32 should actually differ from f64 somewhere");
}

#[test]
fn face_varying_seams_and_holes() {
    let mesh = shapes::cube_with_uvs();
    let r = osd::refine(&mesh, &Options::default(), UniformOptions::new(1)).unwrap();
    // Every face owns its four corner values: 4 corners + 4 edges + 1 centre each.
    assert_eq!(r.levels[1].fvar[0].value_count, 6 * 9);
    let uv = r.last_fvar(0).unwrap();
    // With linear ("all") interpolation face 2's centre value is (2.5, 0.5);
    // find it through face 2's first child, whose third corner is the face point.
    let child = 2 * 4;
    let corner = r.levels[1].face_offsets[child] as usize + 2;
    let value = r.levels[1].fvar[0].face_values[corner] as usize;
    assert_eq!(&uv[2 * value..2 * value + 2], &[2.5, 0.5]);

    let mut grid = shapes::grid(3, 3);
    grid.holes.push(4);
    let r = osd::refine(
        &grid,
        &Options::shape_file_defaults(),
        UniformOptions::new(1),
    )
    .unwrap();
    let holes: Vec<usize> = r.levels[1]
        .face_holes
        .iter()
        .enumerate()
        .filter(|(_, h)| **h)
        .map(|(i, _)| i)
        .collect();
    assert_eq!(holes, vec![16, 17, 18, 19]);
}

#[test]
fn varying_is_linear() {
    let cube = shapes::cube();
    let mut r = TopologyRefiner::new(&cube, &Options::default()).unwrap();
    r.refine_uniform(UniformOptions::new(1)).unwrap();
    let base: Vec<f64> = cube.positions.iter().flat_map(|p| p.to_array()).collect();
    let v = r.interpolate_varying(1, 3, &base).unwrap();
    assert_eq!(&v[0..3], &base[0..3]); // vertex children keep their value
    assert_eq!(&v[14 * 3..15 * 3], &[-0.5, 0.0, -0.5]); // edge 0: midpoint
}

#[test]
fn stencils_reproduce_interpolation_and_limit() {
    let mut mesh = shapes::torus(8, 6);
    mesh.add_crease(0, 1, 1.5);
    let mut r = TopologyRefiner::new(&mesh, &Options::default()).unwrap();
    r.refine_uniform(UniformOptions::new(2).full_topology(true))
        .unwrap();
    let base: Vec<f64> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
    let levels = r.interpolate_all(3, &base).unwrap();

    let table = r.stencil_table().unwrap();
    assert_eq!(table.len(), r.level_counts(2).unwrap().vertices);
    for i in 0..table.len() {
        let sum: f64 = table.row(i).1.iter().sum();
        assert_abs_diff_eq!(sum, 1.0, epsilon = 1e-12);
    }
    let applied = table.apply(3, &base).unwrap();
    for (a, b) in applied.iter().zip(&levels[2]) {
        assert_abs_diff_eq!(*a, *b, epsilon = 1e-12);
    }

    let limit = r.limit(3, &levels[2]).unwrap();
    let ls = r.limit_stencil_table().unwrap();
    for (table, expected) in [
        (&ls.positions, &limit.positions),
        (&ls.du, &limit.du),
        (&ls.dv, &limit.dv),
    ] {
        let applied = table.apply(3, &base).unwrap();
        for (a, b) in applied.iter().zip(expected.iter()) {
            assert_abs_diff_eq!(*a, *b, epsilon = 1e-12);
        }
    }
    for i in 0..ls.positions.len() {
        assert_abs_diff_eq!(
            ls.positions.row(i).1.iter().sum::<f64>(),
            1.0,
            epsilon = 1e-12
        );
        assert_abs_diff_eq!(ls.du.row(i).1.iter().sum::<f64>(), 0.0, epsilon = 1e-12);
    }
}

#[test]
fn limit_needs_full_topology_and_right_lengths() {
    let cube = shapes::cube();
    let mut r = TopologyRefiner::new(&cube, &Options::default()).unwrap();
    r.refine_uniform(UniformOptions::new(1)).unwrap();
    let src = vec![0.0f64; 26 * 3];
    assert!(matches!(r.limit(3, &src), Err(Error::NeedsFullTopology)));
    r.refine_uniform(UniformOptions::new(1).full_topology(true))
        .unwrap();
    assert!(r.limit(3, &src).is_ok());
    assert!(matches!(
        r.limit(3, &src[..10]),
        Err(Error::BufferLength {
            expected: 78,
            got: 10,
            ..
        })
    ));
    assert!(matches!(
        r.interpolate(1, 3, &[0.0f32; 5]),
        Err(Error::BufferLength {
            buffer: Buffer::Source,
            expected: 24,
            got: 5
        })
    ));
    assert!(matches!(
        r.interpolate(2, 3, &[0.0f32; 24]),
        Err(Error::NoSuchLevel {
            level: 2,
            first: 1,
            last: 1
        })
    ));
    assert!(matches!(
        r.interpolate_face_varying(0, 1, 2, &[0.0f64; 2]),
        Err(Error::NoSuchChannel {
            channel: 0,
            count: 0
        })
    ));
    // The limit of a sphere-like closed cube lies inside the control hull.
    let levels = r
        .interpolate_all(
            3,
            &cube
                .positions
                .iter()
                .flat_map(|p| p.to_array())
                .collect::<Vec<_>>(),
        )
        .unwrap();
    let lim = r.limit(3, &levels[1]).unwrap();
    assert!(lim.positions.iter().all(|c| c.abs() < 0.5));
}

#[test]
fn errors_not_crashes() {
    let mut bad = shapes::cube();
    bad.face_vertices[5] = 99;
    assert!(matches!(
        TopologyRefiner::new(&bad, &Options::default()),
        Err(Error::Mesh(MeshError::VertexOutOfRange {
            face: 1,
            corner: 1,
            index: 99,
            count: 8
        }))
    ));
    // The shim's own checks, without Rust's validation in front of them.
    let err = TopologyRefiner::new_unvalidated(&bad, &Options::default()).unwrap_err();
    assert!(
        matches!(&err, Error::Osd(OsdError { kind: OsdErrorKind::Refused, message: m }) if m.contains("vertex index 99 is out of range")),
        "{err}"
    );
    let mut bad = shapes::cube();
    bad.add_corner(8, 1.0);
    let err = TopologyRefiner::new_unvalidated(&bad, &Options::default()).unwrap_err();
    assert!(
        matches!(&err, Error::Osd(OsdError { kind: OsdErrorKind::Refused, message: m }) if m.contains("corner 0")),
        "{err}"
    );
    let mut bad = shapes::cube_with_uvs();
    bad.fvar_channels[0].indices[3] = 1000;
    let err = TopologyRefiner::new_unvalidated(&bad, &Options::default()).unwrap_err();
    assert!(
        matches!(&err, Error::Osd(OsdError { kind: OsdErrorKind::Refused, message: m }) if m.contains("value index 1000")),
        "{err}"
    );

    let err = TopologyRefiner::new(
        &shapes::cube(),
        &Options::default().with_scheme(Scheme::Loop),
    )
    .unwrap_err();
    assert!(
        matches!(&err, Error::Osd(OsdError { kind: OsdErrorKind::Refused, message: m }) if m.contains("Loop scheme needs triangles")),
        "{err}"
    );

    let mut r = TopologyRefiner::new(&shapes::cube(), &Options::default()).unwrap();
    assert!(matches!(
        r.refine_uniform(UniformOptions::new(16)),
        Err(Error::Level { level: 16, .. })
    ));
    assert!(matches!(
        r.level(1),
        Err(Error::NoSuchLevel {
            level: 1,
            first: 0,
            last: 0
        })
    ));
}

#[test]
fn crease_without_edge_is_reported() {
    let mut mesh = shapes::cube();
    mesh.add_crease(0, 6, 2.0); // a body diagonal
    let r = TopologyRefiner::new(&mesh, &Options::default()).unwrap();
    assert!(
        r.warnings().iter().any(|w| w.contains("share no edge")),
        "{:?}",
        r.warnings()
    );
    // Ignored by OpenSubdiv: same result as without the crease.
    let a = osd::refine(&mesh, &Options::default(), UniformOptions::new(2)).unwrap();
    let b = osd::refine(&shapes::cube(), &Options::default(), UniformOptions::new(2)).unwrap();
    assert_eq!(a.positions, b.positions);
}

#[test]
fn loop_and_bilinear() {
    let tet = shapes::tetrahedron();
    let r = osd::refine(
        &tet,
        &Options::default().with_scheme(Scheme::Loop),
        UniformOptions::new(1),
    )
    .unwrap();
    // Loop: 4 vertex children + 6 edge children, 16 triangles.
    assert_eq!(
        (r.levels[1].vertex_count, r.levels[1].face_count()),
        (10, 16)
    );
    // Interior Loop edge point: 3/8 (a + b) + 1/8 (c + d). Edge 0 = {0,1},
    // opposite vertices 3 (face 0) and 2 (face 1).
    let p = &tet.positions;
    assert_point(
        r.positions[1][4],
        0.375 * (p[0] + p[1]) + 0.125 * (p[2] + p[3]),
    );
    // Bilinear: face points are centroids, vertices stay.
    let cube = shapes::cube();
    let b = osd::refine(
        &cube,
        &Options::default().with_scheme(Scheme::Bilinear),
        UniformOptions::new(1),
    )
    .unwrap();
    assert_eq!(&b.positions[1][..8], &cube.positions[..]);
    assert_point(b.positions[1][8], DVec3::new(0.0, 0.0, -0.5));
}

#[test]
fn fvar_modes_change_boundary_values() {
    let grid = shapes::grid(2, 2);
    let all = osd::refine(
        &grid,
        &Options::shape_file_defaults(),
        UniformOptions::new(1),
    )
    .unwrap();
    let smooth = osd::refine(
        &grid,
        &Options::shape_file_defaults().with_fvar(FVarLinearInterpolation::None),
        UniformOptions::new(1),
    )
    .unwrap();
    // Same topology, linear values are the positions' uv; smooth ones move in.
    assert_eq!(all.levels[1].fvar, smooth.levels[1].fvar);
    assert_ne!(all.last_fvar(0), smooth.last_fvar(0));
    // Linear: the centre vertex (uv 0.5, 0.5) keeps its value.
    let v = all.levels[1]
        .face_vertices
        .iter()
        .position(|&v| v == 4)
        .unwrap();
    let value = all.levels[1].fvar[0].face_values[v] as usize;
    assert_eq!(
        &all.last_fvar(0).unwrap()[2 * value..2 * value + 2],
        &[0.5, 0.5]
    );
}

#[test]
fn refiner_is_send_and_sync() {
    fn assert_send_sync<T: Send + Sync>() {}
    assert_send_sync::<TopologyRefiner>();
    let torus = shapes::torus(10, 6);
    let mut r = TopologyRefiner::new(&torus, &Options::default()).unwrap();
    r.refine_uniform(UniformOptions::new(2)).unwrap();
    let base: Vec<f64> = torus.positions.iter().flat_map(|p| p.to_array()).collect();
    let expected = r.interpolate_all(3, &base).unwrap();
    std::thread::scope(|s| {
        let handles: Vec<_> = (0..4)
            .map(|_| s.spawn(|| r.interpolate_all(3, &base).unwrap()))
            .collect();
        for h in handles {
            assert_eq!(h.join().unwrap(), expected);
        }
    });
}

/// OpenSubdiv's LimitFaceVarying on an unrefined level reads a value's tag by
/// its value index: a value numbered beyond the level's per-vertex values
/// (found by fuzzing: a heap overflow under AddressSanitizer) is refused by
/// the shim with an error naming it; the native engine computes the limit.
#[test]
fn base_level_fvar_limit_with_values_beyond_the_vertex_values_is_refused() {
    let mut mesh = subdiv::shapes::grid(1, 1);
    mesh.fvar_channels = vec![subdiv::FVarChannel {
        width: 1,
        values: vec![0.0, 0.25, 0.5, 0.75, 1.0, 2.0, 3.0, 4.0],
        indices: vec![7, 6, 5, 4],
    }];
    let options = Options::shape_file_defaults().with_scheme(subdiv::Scheme::Catmark);
    let uniform = UniformOptions::new(0);
    let err = osd::refine(&mesh, &options, subdiv::Request::from(uniform).limit(true)).unwrap_err();
    let msg = err.to_string();
    assert!(
        msg.contains("value 7 of face 0 is beyond the 4 per-vertex values"),
        "{msg}"
    );
    assert!(
        subdiv::refiner::refine(&mesh, &options, subdiv::Request::from(uniform).limit(true))
            .is_ok()
    );
    // Refined once, the values are renumbered and OpenSubdiv's limit is fine.
    assert!(
        osd::refine(
            &mesh,
            &options,
            subdiv::Request::from(UniformOptions::new(1)).limit(true)
        )
        .is_ok()
    );
}

/// In range but numbered otherwise than OpenSubdiv numbers a vertex's values
/// (vertex by vertex, each vertex's distinct values in the order they first
/// appear around it), an unrefined channel's values make LimitFaceVarying
/// read another value's tags (found by the limit_nonmanifold fuzz target:
/// a seam value on a face-varying boundary given the corner rule, 0.52
/// instead of the crease limit 0.515). The bridge refuses it as unsafe; the
/// native engine gives the crease limit (1/6, 2/3, 1/6 in f32 weights, as
/// OpenSubdiv's).
#[test]
fn base_level_fvar_limit_with_values_numbered_otherwise_is_refused() {
    let mut mesh = Mesh {
        positions: vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(0.5, 1.0, 0.0),
            DVec3::new(0.5, -1.0, 0.0),
        ],
        ..Mesh::default()
    };
    mesh.add_face(&[0, 1, 2]);
    mesh.add_face(&[0, 2, 3]);
    mesh.add_face(&[0, 1, 3]);
    // One value per face corner (a seam everywhere), numbered corner by corner.
    let uv = [
        (0.0, 0.0),
        (1.01, 0.0),
        (0.52, 1.0),
        (0.03, 0.0),
        (0.54, 1.0),
        (0.55, -1.0),
        (0.06, 0.0),
        (1.07, 0.0),
        (0.58, -1.0),
    ];
    mesh.fvar_channels = vec![subdiv::FVarChannel {
        width: 2,
        values: uv.iter().flat_map(|&(u, v)| [u, v]).collect(),
        indices: (0..9).collect(),
    }];
    let options = Options::shape_file_defaults()
        .with_scheme(Scheme::Loop)
        .with_fvar(FVarLinearInterpolation::None);
    let request = subdiv::Request::from(UniformOptions::new(0)).limit(true);
    let Err(err) = osd::refine(&mesh, &options, request) else {
        panic!("the bridge let OpenSubdiv evaluate");
    };
    assert!(
        matches!(&err, Error::Osd(OsdError { kind: OsdErrorKind::Unsafe, message })
            if message.starts_with("face-varying channel 0: value 3 (vertex 0) is OpenSubdiv's per-vertex value 1 ")),
        "{err:?}"
    );
    let native = subdiv::refiner::refine(&mesh, &options, request).unwrap();
    let limit = &native.limit.as_ref().unwrap().fvar_values[0];
    // Value 2 (vertex 2, face 0) lies on the channel's boundary between
    // value 1 (vertex 1) and value 0 (vertex 0).
    let (sixth, two_thirds) = (f64::from(1.0f32 / 6.0), f64::from(2.0f32 / 3.0));
    let crease = 1.01 * sixth + 0.0 * sixth + 0.52 * two_thirds;
    assert!(
        (limit[4] - crease).abs() < 1e-15,
        "{} vs {crease}",
        limit[4]
    );
    // Refined once, the values are OpenSubdiv's own numbering: evaluated, equal.
    let request = subdiv::Request::from(UniformOptions::new(1)).limit(true);
    let a = subdiv::refiner::refine(&mesh, &options, request).unwrap();
    let b = osd::refine(&mesh, &options, request).unwrap();
    let (a, b) = (
        &a.limit.unwrap().fvar_values[0],
        &b.limit.unwrap().fvar_values[0],
    );
    let d = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(d < 1e-15, "refined once: {d:e}");
    // Vertex 0's three values numbered 0, 1, 2 in each of the six orders
    // over its faces: only the order in which OpenSubdiv meets them around
    // the vertex (not their order as numbers) passes vertex 0's check.
    let request = subdiv::Request::from(UniformOptions::new(0)).limit(true);
    let mut passed = 0;
    for p in [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ] {
        let ch = &mut mesh.fvar_channels[0];
        ch.indices = vec![p[0], 3, 4, p[1], 5, 6, p[2], 7, 8];
        let refused_at_0 = match osd::refine(&mesh, &options, request) {
            Err(Error::Osd(OsdError { message, .. })) => message.contains("(vertex 0)"),
            _ => false,
        };
        passed += usize::from(!refused_at_0);
    }
    assert_eq!(passed, 1, "one order of vertex 0's values is OpenSubdiv's");
}

/// The masks OpenSubdiv 3.5's `PrimvarRefiner::Limit` would write at each
/// vertex of the last level, re-derived here from the native engine's
/// topology and rules (the same as OpenSubdiv's, index by index) and from
/// Sdc's limit masks: (edge weights, face weights) of the position mask and
/// of the tangent masks. Catmull-Clark: smooth/dart vertices use their face
/// count for both (two faces: corner masks), creases their edges (tangents
/// also their faces), corners no neighbour (tangents their edges); Loop: edge
/// weights only; bilinear: corner masks (tangents: two edges).
fn limit_mask_counts(
    scheme: Scheme,
    rule: subdiv::rules::Rule,
    edges: usize,
    faces: usize,
) -> [(usize, usize); 2] {
    use subdiv::rules::Rule;
    let smooth = matches!(rule, Rule::Smooth | Rule::Dart);
    match scheme {
        Scheme::Bilinear => [(0, 0), (2, 0)],
        Scheme::Loop if smooth => [(faces, 0), (faces, 0)],
        Scheme::Loop if rule == Rule::Crease => [(edges, 0), (edges, 0)],
        Scheme::Loop => [(0, 0), (edges, 0)],
        Scheme::Catmark if smooth && faces != 2 => [(faces, faces), (faces, faces)],
        Scheme::Catmark if rule == Rule::Crease => [(edges, 0), (edges, faces)],
        Scheme::Catmark => [(0, 0), (edges, 0)],
    }
}

/// Whether `Limit` with tangents would overrun its buffers on `n`'s last
/// level: a mask with more edge or face weights than the level's maximum
/// valence M, or more neighbours than its index buffer of 1 + 2M holds. M is
/// OpenSubdiv's computed value: the base level's largest face, vertex-face or
/// vertex-edge count, then at each level at least 4 (6 for triangle splits)
/// and 2 + the base's largest edge-face count (twice that for triangles).
fn limit_overruns(n: &subdiv::refiner::Refiner, scheme: Scheme) -> Option<usize> {
    let base = n.level(0).unwrap();
    let hoods: Vec<(Vec<u32>, Vec<u32>)> = (0..base.vertex_count)
        .map(|v| n.vertex_faces_and_edges(0, v).unwrap())
        .collect();
    let mut m = hoods
        .iter()
        .map(|(f, e)| f.len().max(e.len()))
        .chain(base.faces().map(<[u32]>::len))
        .max()
        .unwrap();
    let edge_faces = (0..base.edge_count)
        .map(|e| n.edge_faces(0, e).unwrap().len())
        .max()
        .unwrap();
    let (regular, factor) = if scheme == Scheme::Loop {
        (6, 2)
    } else {
        (4, 1)
    };
    for _ in 0..n.max_level() {
        m = m.max(regular).max(2 + factor * edge_faces);
    }
    let last = n.max_level();
    (0..n.level_counts(last).unwrap().vertices).find(|&v| {
        let (faces, edges) = n.vertex_faces_and_edges(last, v).unwrap();
        if edges.is_empty() {
            return false;
        }
        let (rule, _) = n.vertex_rule(last, v).unwrap();
        let masks = limit_mask_counts(scheme, rule, edges.len(), faces.len());
        let gathers_faces = masks.iter().any(|&(_, f)| f > 0);
        let indices = edges.len() + if gathers_faces { faces.len() } else { 0 };
        indices > 1 + 2 * m || masks.iter().any(|&(e, f)| e > m || f > m)
    })
}

/// OpenSubdiv 3.5's `PrimvarRefiner::Limit` sizes its masks by a computed
/// maximum valence, and a non-manifold vertex can have more faces than that:
/// with 14 pages on one spine it wrote past its buffer (a crash), with 13 it
/// gave wrong limits. The bridge refuses exactly the refinements whose masks
/// overrun (`OsdErrorKind::Unsafe`, before OpenSubdiv is called), and every
/// limit it does evaluate equals the native engine's. Run under
/// AddressSanitizer by scripts/asan.sh.
#[test]
fn limit_is_refused_exactly_where_opensubdiv_overruns_its_masks() {
    let (mut refused, mut evaluated) = (0, 0);
    for (pages, corners) in [2, 3, 4, 6, 8, 12, 13, 14, 15, 20]
        .into_iter()
        .flat_map(|p| [(p, 3), (p, 4)])
    {
        let mesh = shapes::book(pages, corners);
        let schemes: &[Scheme] = if corners == 3 {
            &[Scheme::Catmark, Scheme::Loop, Scheme::Bilinear]
        } else {
            &[Scheme::Catmark, Scheme::Bilinear]
        };
        for &scheme in schemes {
            for level in 0..=3 {
                let ctx = format!("{pages} pages of {corners} corners, {scheme}, level {level}");
                let options = Options::shape_file_defaults().with_scheme(scheme);
                let uniform = UniformOptions::new(level).full_topology(true);
                let mut n = subdiv::refiner::Refiner::new(&mesh, &options).unwrap();
                n.refine_uniform(uniform).unwrap();
                let mut o = TopologyRefiner::new(&mesh, &options).unwrap();
                o.refine_uniform(uniform).unwrap();
                let base: Vec<f64> = mesh.flat_positions();
                let last = o.interpolate_last(3, &base).unwrap();
                let overrun = limit_overruns(&n, scheme);
                match (o.limit(3, &last), overrun) {
                    (Err(Error::Osd(e)), Some(v)) => {
                        assert_eq!(e.kind, OsdErrorKind::Unsafe, "{ctx}: {e}");
                        assert!(
                            e.message
                                .starts_with(&format!("vertex {v} of level {level} ")),
                            "{ctx}: {e}"
                        );
                        refused += 1;
                    }
                    (Ok(lo), None) => {
                        let ln = n.limit(3, &last).unwrap();
                        for (a, b) in [
                            (&ln.positions, &lo.positions),
                            (&ln.du, &lo.du),
                            (&ln.dv, &lo.dv),
                        ] {
                            let d = a
                                .iter()
                                .zip(b)
                                .map(|(x, y)| (x - y).abs())
                                .fold(0.0, f64::max);
                            assert!(
                                d < 1e-12,
                                "{ctx}: native and OpenSubdiv limits differ by {d:e}"
                            );
                        }
                        evaluated += 1;
                    }
                    (result, predicted) => {
                        panic!(
                            "{ctx}: predicted overrun {predicted:?}, bridge gave {:?}",
                            result.err()
                        )
                    }
                }
                // Limit stencils run the same masks.
                assert_eq!(
                    o.limit_stencil_table().is_err(),
                    overrun.is_some(),
                    "{ctx}: limit stencils"
                );
            }
        }
    }
    assert!(
        refused >= 20 && evaluated >= 60,
        "refused {refused}, evaluated {evaluated}"
    );
}

/// Sdc's Catmull-Clark vertex rule weighs each edge and face of a smooth
/// vertex by `1 / (valence * valence)` computed in a 32-bit int: from 46,341
/// faces the product overflows and OpenSubdiv 3.5 puts the vertex far from
/// its place. The bridge refuses exactly those refinements
/// (`OsdErrorKind::Unsafe`): a wheel of 46,341 triangles under Catmull-Clark,
/// in vertex interpolation and stencils; not 46,340, not the same valence at
/// a boundary (crease rule), not Loop. The native engine puts the centre of
/// a regular planar wheel on itself (its edge and face points are symmetric
/// about it).
#[test]
fn catmark_vertex_rule_is_refused_past_46340_faces() {
    let catmark = Options::shape_file_defaults();
    for (n, refused) in [(46_340, false), (46_341, true)] {
        let wheel = shapes::wheel(n);
        let native = subdiv::refiner::refine(&wheel, &catmark, UniformOptions::new(1)).unwrap();
        // Children of vertices come first (OpenSubdiv's default order).
        let centre = native.positions[1][0];
        assert!(
            (centre - DVec3::new(0.5, 0.25, 0.0)).length() < 1e-12,
            "{n}: {centre:?}"
        );
        let osd_result = osd::refine(&wheel, &catmark, UniformOptions::new(1));
        let mut o = TopologyRefiner::new(&wheel, &catmark).unwrap();
        o.refine_uniform(UniformOptions::new(1)).unwrap();
        let stencils = o.stencil_table();
        if refused {
            let Err(err) = osd_result else {
                panic!("{n} faces: the bridge let OpenSubdiv refine");
            };
            assert!(
                matches!(&err, Error::Osd(OsdError { kind: OsdErrorKind::Unsafe, message })
                    if message.starts_with("vertex 0 of level 0 has 46341 faces")),
                "{err:?}"
            );
            assert!(matches!(
                stencils,
                Err(Error::Osd(OsdError {
                    kind: OsdErrorKind::Unsafe,
                    ..
                }))
            ));
            // Varying interpolation is linear: no vertex rule, no refusal.
            let base: Vec<f64> = wheel.flat_positions();
            assert!(o.interpolate_varying(1, 3, &base).is_ok());
        } else {
            assert_eq!(osd_result.unwrap().positions, native.positions, "{n}");
            assert!(stencils.is_ok());
        }
        // Loop weighs in floating point: compared, equal.
        let loop_options = catmark.with_scheme(Scheme::Loop);
        let a = subdiv::refiner::refine(&wheel, &loop_options, UniformOptions::new(1)).unwrap();
        let b = osd::refine(&wheel, &loop_options, UniformOptions::new(1)).unwrap();
        assert_eq!(a.positions, b.positions, "{n}, loop");
    }
    // At a boundary the same valence takes the crease rule: refined, equal.
    let fan = shapes::fan(46_341, 3.0);
    let a = subdiv::refiner::refine(&fan, &catmark, UniformOptions::new(1)).unwrap();
    let b = osd::refine(&fan, &catmark, UniformOptions::new(1)).unwrap();
    assert_eq!(a.positions, b.positions, "boundary fan");
}
