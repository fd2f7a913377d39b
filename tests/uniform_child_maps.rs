//! Parent/child queries on uniformly refined native refiners
//! (`Refiner::child_maps`): a few entries derived by hand, and, with the
//! `osd` feature, the whole maps against OpenSubdiv's after
//! `RefineUniform` on the corpus (Catmull-Clark, bilinear, Loop on the
//! triangle meshes), levels 1 to 3, both vertex orders.

use subdiv::refiner::Refiner;
use subdiv::{Error, INVALID_INDEX, Mesh, Options, Scheme, UniformOptions, shapes};

fn refined(mesh: &Mesh, options: &Options, uniform: UniformOptions) -> Refiner {
    let mut r = Refiner::new(mesh, options).unwrap();
    r.refine_uniform(uniform).unwrap();
    r
}

#[test]
fn cube_by_hand() {
    let cube = shapes::cube();
    let r = refined(&cube, &Options::default(), UniformOptions::new(2));
    let m = r.child_maps(0).unwrap();
    // 6 quads: 24 child faces, consecutive from 4 f in corner order.
    assert_eq!(
        m.face_child_face_offsets,
        (0..=6).map(|f| 4 * f).collect::<Vec<u32>>()
    );
    assert_eq!(m.face_child_faces, (0..24).collect::<Vec<u32>>());
    assert_eq!(m.face_child_edges, (0..24).collect::<Vec<u32>>());
    assert_eq!(m.face_child_edge_offsets, m.face_child_face_offsets);
    for f in 0..6u32 {
        assert_eq!(m.child_face_parent_face[4 * f as usize..][..4], [f; 4]);
    }
    // Vertices first: 8 vertex children, then 6 face points, then 12 edge points.
    assert_eq!(m.vertex_child_vertex, (0..8).collect::<Vec<u32>>());
    assert_eq!(m.face_child_vertex, (8..14).collect::<Vec<u32>>());
    assert_eq!(m.edge_child_vertex, (14..26).collect::<Vec<u32>>());
    // After the 24 interior edges, two per parent edge, end 0 first.
    assert_eq!(m.edge_child_edges[0], [24, 25]);
    assert_eq!(m.edge_child_edges[11], [46, 47]);
    // Level 1 -> 2: 24 quads, 48 edges, 26 vertices.
    let m1 = r.child_maps(1).unwrap();
    assert_eq!(m1.face_child_faces.len(), 96);
    assert_eq!(m1.edge_child_edges[47], [96 + 94, 96 + 95]);
    assert_eq!(m1.face_child_vertex[0], 26);
    assert_eq!(m1.edge_child_vertex[0], 26 + 24);
    // No level past the last one, nor on an unrefined refiner.
    assert!(matches!(r.child_maps(2), Err(Error::NoSuchLevel { .. })));
    let base = Refiner::new(&cube, &Options::default()).unwrap();
    assert!(matches!(base.child_maps(0), Err(Error::NoSuchLevel { .. })));
}

#[test]
fn faces_first_and_polygons_by_hand() {
    // A quad and a triangle sharing an edge: 5 vertices, 6 edges, 7 corners.
    let mut mesh = Mesh::default();
    for (x, y) in [(0., 0.), (1., 0.), (1., 1.), (0., 1.), (2., 0.5)] {
        mesh.positions.push(glam::DVec3::new(x, y, 0.0));
    }
    mesh.add_face(&[0, 1, 2, 3]);
    mesh.add_face(&[1, 4, 2]);
    let r = refined(
        &mesh,
        &Options::default(),
        UniformOptions::new(1).faces_first(true),
    );
    let m = r.child_maps(0).unwrap();
    assert_eq!(m.face_child_face_offsets, [0, 4, 7]);
    assert_eq!(m.face_child_faces, (0..7).collect::<Vec<u32>>());
    assert_eq!(m.child_face_parent_face, [0, 0, 0, 0, 1, 1, 1]);
    // Faces first: face points 0..2, edge points 2..8, vertex points 8..13.
    assert_eq!(m.face_child_vertex, [0, 1]);
    assert_eq!(m.edge_child_vertex, (2..8).collect::<Vec<u32>>());
    assert_eq!(m.vertex_child_vertex, (8..13).collect::<Vec<u32>>());
    assert_eq!(m.edge_child_edges[0], [7, 8]);
}

#[test]
fn loop_by_hand() {
    let ico = shapes::icosahedron();
    let r = refined(
        &ico,
        &Options::default().with_scheme(Scheme::Loop),
        UniformOptions::new(1),
    );
    let m = r.child_maps(0).unwrap();
    // Four child faces per triangle (the middle one last), three interior
    // edges, no face points.
    assert_eq!(m.face_child_face_offsets.len(), 21);
    assert_eq!(m.face_child_face_offsets[20], 80);
    assert_eq!(m.face_child_faces[4 * 7..][..4], [28, 29, 30, 31]);
    assert_eq!(m.face_child_edge_offsets[7], 21);
    assert_eq!(m.face_child_edges.len(), 60);
    assert!(m.face_child_vertex.iter().all(|&v| v == INVALID_INDEX));
    assert_eq!(m.child_face_parent_face[31], 7);
    // 12 vertex points, then 30 edge points; 60 interior edges, then 2 per edge.
    assert_eq!(m.vertex_child_vertex, (0..12).collect::<Vec<u32>>());
    assert_eq!(m.edge_child_vertex, (12..42).collect::<Vec<u32>>());
    assert_eq!(m.edge_child_edges[29], [118, 119]);
}

#[cfg(feature = "osd")]
#[test]
fn corpus_matches_opensubdiv() {
    use subdiv::osd;
    let mut compared = [0usize; 3];
    for (name, mesh) in shapes::corpus() {
        for scheme in [Scheme::Catmark, Scheme::Bilinear, Scheme::Loop] {
            let options = Options::shape_file_defaults().with_scheme(scheme);
            // Loop refuses non-triangles (tested elsewhere).
            let Ok(native) = Refiner::new(&mesh, &options) else {
                continue;
            };
            for level in 1..=3 {
                for faces_first in [false, true] {
                    let uniform = UniformOptions::new(level).faces_first(faces_first);
                    let mut native = native.clone();
                    if native.refine_uniform(uniform).is_err() {
                        // Refused (a vertex named twice by a face): OpenSubdiv
                        // would abort. Tested elsewhere.
                        continue;
                    }
                    let mut theirs = osd::TopologyRefiner::new(&mesh, &options).unwrap();
                    theirs.refine_uniform(uniform).unwrap();
                    for l in 0..level {
                        assert_eq!(
                            native.child_maps(l).unwrap(),
                            theirs.child_maps(l).unwrap(),
                            "{name} {scheme:?} level {l} of {level}, faces first {faces_first}"
                        );
                        compared[scheme.code() as usize] += 1;
                    }
                    assert!(native.child_maps(level).is_err());
                }
            }
        }
    }
    assert!(
        compared.iter().all(|&n| n > 20),
        "maps compared per scheme: {compared:?}"
    );
}
