//! Native feature-adaptive refinement with hand-derived expectations: which
//! faces each level refines, the counts of sparse levels, positions on
//! them, and the refusals. (The comparison with OpenSubdiv's
//! `RefineAdaptive`, element by element, is in `adaptive_conformance.rs`.)

use glam::DVec3;
use subdiv::refiner::Refiner;
use subdiv::{
    AdaptiveOptions, Element, Error, FVarLinearInterpolation, INVALID_INDEX, Mesh, Options, Scheme,
    UniformOptions, shapes,
};

fn adaptive(
    mesh: &Mesh,
    options: &Options,
    ao: AdaptiveOptions,
    sel: &[u32],
) -> subdiv::refiner::AdaptiveRefiner {
    Refiner::new(mesh, options)
        .unwrap()
        .refine_adaptive(ao, sel)
        .unwrap()
}

fn counts(a: &subdiv::refiner::AdaptiveRefiner, level: u32) -> (usize, usize, usize) {
    let c = a.level_counts(level).unwrap();
    (c.vertices, c.edges, c.faces)
}

/// The cube's corners are extraordinary (valence 3) and every face of levels
/// 0 and 1 has one, so levels 1 and 2 are whole. At level 2 only the three
/// faces around each of the eight corners have one: each such patch refines
/// its 3 faces (12 children), and of the 9 faces around it, the 6 sharing an
/// edge give 2 children and the 3 sharing a corner 1 (15). Vertices per
/// patch: 7 vertex points, 12 face points, 9 + 9 edge points (its edges and
/// the edges leaving it); edges: 12 + 6·3 + 3·2 inside faces, 9·2 + 9 halves.
#[test]
fn cube_isolates_its_corners() {
    let a = adaptive(
        &shapes::cube(),
        &Options::default(),
        AdaptiveOptions::new(3),
        &[],
    );
    assert_eq!(a.max_level(), 3);
    assert_eq!(counts(&a, 1), (26, 48, 24));
    assert_eq!(counts(&a, 2), (98, 192, 96));
    assert_eq!(counts(&a, 3), (8 * 37, 8 * 63, 8 * 27));
    for level in 0..2 {
        let maps = a.child_maps(level).unwrap();
        assert!(
            !maps.face_child_faces.contains(&INVALID_INDEX),
            "level {level}"
        );
    }
    let maps = a.child_maps(2).unwrap();
    let valid = |v: &[u32]| v.iter().filter(|&&x| x != INVALID_INDEX).count();
    assert_eq!(valid(&maps.face_child_faces), 8 * 27);
    assert_eq!(valid(&maps.vertex_child_vertex), 8 * 7);
    // Each child face's parent maps back to it.
    for (f, w) in maps.face_child_face_offsets.windows(2).enumerate() {
        for &c in &maps.face_child_faces[w[0] as usize..w[1] as usize] {
            if c != INVALID_INDEX {
                assert_eq!(maps.child_face_parent_face[c as usize], f as u32);
            }
        }
    }
    // Deeper isolation keeps refining the 8 corners only.
    let deeper = adaptive(
        &shapes::cube(),
        &Options::default(),
        AdaptiveOptions::new(5),
        &[],
    );
    assert_eq!(deeper.max_level(), 5);
    assert_eq!(counts(&deeper, 4), counts(&deeper, 5));
}

/// Only face 0 of the cube selected: it refines whole (4 children), its
/// four edge-neighbours refine at the two corners they share with it (2
/// each), the opposite face not at all.
#[test]
fn selected_faces_restrict_the_first_level() {
    let a = adaptive(
        &shapes::cube(),
        &Options::default(),
        AdaptiveOptions::new(1),
        &[0],
    );
    assert_eq!(a.level_counts(1).unwrap().faces, 4 + 4 * 2);
    assert!(a.is_face_selected(0, 0).unwrap());
    assert!(!a.is_face_selected(0, 1).unwrap());
    // The same face twice selects it once.
    let twice = adaptive(
        &shapes::cube(),
        &Options::default(),
        AdaptiveOptions::new(1),
        &[0, 0],
    );
    assert_eq!(twice.level_counts(1).unwrap().faces, 12);
}

/// A regular torus has no feature: nothing is refined.
#[test]
fn regular_meshes_stay_unrefined() {
    let a = adaptive(
        &shapes::torus(8, 6),
        &Options::default(),
        AdaptiveOptions::new(4),
        &[],
    );
    assert_eq!(a.max_level(), 0);
    assert!(matches!(a.child_maps(0), Err(Error::NoSuchLevel { .. })));
}

/// Two quads and a triangle in a strip under the bilinear scheme: only the
/// triangle (irregular) refines, one level whatever the isolation; the quad
/// beside it gets the children at the two corners it shares; the far quad
/// none. Bilinear points are averages.
#[test]
fn bilinear_refines_only_non_quads_once() {
    let positions = [(0, 0), (1, 0), (2, 0), (3, 0), (0, 1), (1, 1), (2, 1)]
        .map(|(x, y)| DVec3::new(x as f64, y as f64, 0.0))
        .to_vec();
    let mesh = Mesh::from_faces(positions, &[&[0, 1, 5, 4], &[1, 2, 6, 5], &[2, 3, 6]]);
    let options = Options::shape_file_defaults().with_scheme(Scheme::Bilinear);
    let a = adaptive(&mesh, &options, AdaptiveOptions::new(4), &[]);
    assert_eq!(a.max_level(), 1);
    let maps = a.child_maps(0).unwrap();
    let i = INVALID_INDEX;
    // Vertex points of the selected vertices 2, 3, 6 first, then face
    // points (quad 1, triangle), then edge points in edge order.
    assert_eq!(maps.vertex_child_vertex, [i, i, 0, 1, i, i, 2]);
    assert_eq!(maps.face_child_vertex, [i, 3, 4]);
    assert_eq!(maps.face_child_faces, [i, i, i, i, i, 0, 1, i, 2, 3, 4]);
    assert_eq!(a.level_counts(1).unwrap().faces, 5);
    let positions = a.refine_positions(&mesh.positions).unwrap();
    let level1 = &positions[1];
    assert_eq!(level1.len(), a.level_counts(1).unwrap().vertices);
    assert_eq!(level1[0], mesh.positions[2]);
    assert_eq!(level1[3], DVec3::new(1.5, 0.5, 0.0));
    let third = 1.0 / 3.0;
    assert!((level1[4] - DVec3::new(7.0 * third, third, 0.0)).length() < 1e-15);
    // Every edge point is the midpoint of its edge.
    let level0 = a.level(0).unwrap();
    for (e, &c) in maps.edge_child_vertex.iter().enumerate() {
        if c != i {
            let [v0, v1] = level0.edge_vertices[e];
            let mid = (mesh.positions[v0 as usize] + mesh.positions[v1 as usize]) * 0.5;
            assert_eq!(level1[c as usize], mid, "edge {e}");
        }
    }
}

/// Loop: every vertex of the icosahedron has valence 5 (extraordinary for
/// Loop, whose regular valence is 6), so level 1 is whole: 12 + 30
/// vertices, 2·30 + 3·20 edges, 4·20 triangles, and no face points. Level 2
/// is whole too: the 60 corner triangles of level 1 are selected, and their
/// vertices are all 42, so each middle triangle gets its three corners and
/// (its edges being transitional) its middle. At level 3 only the 5
/// triangles around each of the 12 old vertices are selected (4 children
/// each); of the 15 triangles around such a patch, the 5 sharing an edge
/// with it get 2 corners and the middle (3), the 10 touching it at a corner
/// 1.
#[test]
fn loop_isolates_extraordinary_vertices() {
    let options = Options::default().with_scheme(Scheme::Loop);
    let a = adaptive(
        &shapes::icosahedron(),
        &options,
        AdaptiveOptions::new(3),
        &[],
    );
    assert_eq!(counts(&a, 1), (42, 120, 80));
    assert_eq!(counts(&a, 2), (162, 480, 320));
    let maps = a.child_maps(0).unwrap();
    assert!(maps.face_child_vertex.iter().all(|&v| v == INVALID_INDEX));
    assert_eq!(maps.face_child_faces.len(), 4 * 20);
    assert_eq!(counts(&a, 3).2, 12 * (5 * 4 + 5 * 3 + 10));
}

#[test]
fn refusals() {
    let cube = shapes::cube();
    let options = Options::default();
    let mut refined = Refiner::new(&cube, &options).unwrap();
    refined.refine_uniform(UniformOptions::new(1)).unwrap();
    assert!(matches!(
        refined.refine_adaptive(AdaptiveOptions::new(2), &[]),
        Err(Error::AlreadyRefined { level: 1 })
    ));
    let fresh = || Refiner::new(&cube, &options).unwrap();
    assert!(matches!(
        fresh().refine_adaptive(AdaptiveOptions::new(11), &[]),
        Err(Error::Level { level: 11, .. })
    ));
    assert!(matches!(
        fresh().refine_adaptive(AdaptiveOptions::new(2).secondary(16), &[]),
        Err(Error::Level { level: 16, .. })
    ));
    assert!(matches!(
        fresh().refine_adaptive(AdaptiveOptions::new(2), &[6]),
        Err(Error::NoSuchElement {
            element: Element::Face,
            index: 6,
            ..
        })
    ));
    // Face-varying features: on a regular torus nothing is selected, but a
    // channel split at every edge (each face its own values) has boundary
    // features everywhere, which are isolated when asked, and only when the
    // channel is not linear.
    let seam = {
        let mut m = shapes::torus(8, 6);
        let corners = m.face_vertices.len();
        m.fvar_channels.push(subdiv::FVarChannel {
            width: 2,
            values: (0..2 * corners).map(|x| x as f64).collect(),
            indices: (0..corners as u32).collect(),
        });
        m
    };
    let levels = |fvar: FVarLinearInterpolation, consider: bool| {
        let a = adaptive(
            &seam,
            &Options::shape_file_defaults().with_fvar(fvar),
            AdaptiveOptions::new(2).consider_fvar(consider),
            &[],
        );
        a.max_level()
    };
    assert_eq!(levels(FVarLinearInterpolation::None, false), 0);
    assert!(levels(FVarLinearInterpolation::None, true) > 0);
    assert_eq!(levels(FVarLinearInterpolation::All, true), 0);
    let a = adaptive(&cube, &options, AdaptiveOptions::new(2), &[]);
    assert!(matches!(
        a.interpolate(3, 3, &[0.0; 98 * 3]),
        Err(Error::NoSuchLevel { .. })
    ));
    assert!(matches!(
        a.interpolate(1, 3, &[0.0; 5]),
        Err(Error::BufferLength { .. })
    ));
    assert!(matches!(
        a.interpolate::<f64>(1, 0, &[]),
        Err(Error::ZeroWidth)
    ));
    // The same checks for face-varying values, channel first.
    let uv = adaptive(
        &shapes::cube_with_uvs(),
        &options,
        AdaptiveOptions::new(2),
        &[],
    );
    let values = shapes::cube_with_uvs().fvar_channels[0].values.clone();
    assert!(matches!(
        uv.interpolate_face_varying(1, 1, 2, &values),
        Err(Error::NoSuchChannel {
            channel: 1,
            count: 1
        })
    ));
    assert!(matches!(
        uv.interpolate_face_varying(0, 3, 2, &values),
        Err(Error::NoSuchLevel { level: 3, .. })
    ));
    assert!(matches!(
        uv.interpolate_face_varying(0, 1, 0, &values),
        Err(Error::ZeroWidth)
    ));
    assert!(matches!(
        uv.interpolate_face_varying(0, 1, 2, &values[1..]),
        Err(Error::BufferLength { .. })
    ));
    let level1 = uv.interpolate_face_varying(0, 1, 2, &values).unwrap();
    assert_eq!(level1.len(), 2 * uv.level(1).unwrap().fvar[0].value_count);
}
