//! OpenSubdiv's feature-adaptive refinement through the bridge, against
//! counts and child maps derived by hand from OpenSubdiv's sparse rules: a
//! selected face refines whole (its vertices and edges are selected too); an
//! unselected face gets the child face at each selected corner, with the
//! two interior child edges beside it and its face point; an unselected edge
//! gets the child edge at each selected end and its edge point; only a
//! selected vertex gets a child vertex. Children are numbered parent by
//! parent, vertices from vertices first, then faces, then edges.
//! Also the level relations, and ptex indices (native against OpenSubdiv).
#![cfg(feature = "osd")]

use glam::DVec3;
use subdiv::osd::TopologyRefiner;
use subdiv::ptex::PtexIndices;
use subdiv::refiner::Refiner;
use subdiv::rules::Rule;
use subdiv::{
    AdaptiveOptions, BoundaryInterpolation, ChildMaps, Element, Error, FVarLinearInterpolation,
    INVALID_INDEX, LevelRefusal, Mesh, Options, Scheme, UniformOptions, shapes,
};

fn options(scheme: Scheme) -> Options {
    Options {
        scheme,
        ..Options::default()
    }
}

fn adaptive(mesh: &Mesh, scheme: Scheme, isolation: u32, faces: &[u32]) -> TopologyRefiner {
    let mut r = TopologyRefiner::new(mesh, &options(scheme)).unwrap();
    r.refine_adaptive(AdaptiveOptions::new(isolation), faces)
        .unwrap();
    r
}

/// (vertices, edges, faces) of a level.
fn counts(r: &TopologyRefiner, level: u32) -> (usize, usize, usize) {
    let c = r.level_counts(level).unwrap();
    assert!(c.full_topology, "adaptive level {level} has full topology");
    (c.vertices, c.edges, c.faces)
}

fn valid(v: &[u32]) -> usize {
    v.iter().filter(|&&i| i != INVALID_INDEX).count()
}

/// What holds for the child maps of any refinement: the valid children of
/// each kind are exactly the child level's elements, each once, and every
/// child face names its parent.
fn check_maps(r: &TopologyRefiner, level: u32) -> ChildMaps {
    let m = r.child_maps(level).unwrap();
    let (pv, pe, pf) = counts(r, level);
    let (cv, ce, cf) = counts(r, level + 1);
    assert_eq!(m.face_child_face_offsets.len(), pf + 1);
    assert_eq!(m.face_child_edge_offsets.len(), pf + 1);
    assert_eq!(
        (
            m.edge_child_edges.len(),
            m.face_child_vertex.len(),
            m.edge_child_vertex.len(),
            m.vertex_child_vertex.len(),
        ),
        (pe, pf, pe, pv)
    );
    let permutation = |mut ids: Vec<u32>, n: usize, what: &str| {
        ids.retain(|&i| i != INVALID_INDEX);
        ids.sort_unstable();
        assert_eq!(ids, (0..n as u32).collect::<Vec<_>>(), "{what}");
    };
    permutation(m.face_child_faces.clone(), cf, "child faces");
    let mut edges = m.face_child_edges.clone();
    edges.extend(m.edge_child_edges.iter().flatten());
    permutation(edges, ce, "child edges");
    let mut verts = m.face_child_vertex.clone();
    verts.extend(&m.edge_child_vertex);
    verts.extend(&m.vertex_child_vertex);
    permutation(verts, cv, "child vertices");
    assert_eq!(m.child_face_parent_face.len(), cf);
    for f in 0..pf {
        let range =
            m.face_child_face_offsets[f] as usize..m.face_child_face_offsets[f + 1] as usize;
        for &c in &m.face_child_faces[range] {
            if c != INVALID_INDEX {
                assert_eq!(m.child_face_parent_face[c as usize], f as u32);
            }
        }
    }
    m
}

/// The cube's 8 vertices all have valence 3: every face has an
/// extraordinary vertex, so isolation 1 refines all of them: level 1 is the
/// uniform level 1 (8 vertex points + 6 face points + 12 edge points; 12 × 2
/// split edges + 6 × 4 interior edges; 6 × 4 faces), with every child.
#[test]
fn cube_isolation_1_is_the_uniform_first_level() {
    let r = adaptive(&shapes::cube(), Scheme::Catmark, 1, &[]);
    assert_eq!(r.max_level(), 1);
    assert_eq!(r.adaptive_options(), Some(AdaptiveOptions::new(1)));
    assert_eq!(r.uniform_options(), None);
    assert_eq!(counts(&r, 1), (26, 48, 24));
    let m = check_maps(&r, 0);
    assert_eq!(valid(&m.face_child_faces), 24);
    assert_eq!(m.face_child_faces.len(), 24);
    assert_eq!(m.face_child_edges.len(), 24);
    assert_eq!(valid(&m.face_child_edges), 24);
    assert!(
        m.edge_child_edges
            .iter()
            .flatten()
            .all(|&e| e != INVALID_INDEX)
    );
    assert_eq!(valid(&m.face_child_vertex), 6);
    assert_eq!(valid(&m.edge_child_vertex), 12);
    assert_eq!(valid(&m.vertex_child_vertex), 8);
    // Vertices from vertices first: vertex v's child is v, then face points.
    assert_eq!(m.vertex_child_vertex, (0..8).collect::<Vec<u32>>());
    assert_eq!(m.face_child_vertex, (8..14).collect::<Vec<u32>>());
    assert_eq!(m.edge_child_vertex, (14..26).collect::<Vec<u32>>());
    // With faces first: face points, edge points, vertex points.
    let mut r = TopologyRefiner::new(&shapes::cube(), &Options::default()).unwrap();
    r.refine_adaptive(AdaptiveOptions::new(1).faces_first(true), &[])
        .unwrap();
    let m = check_maps(&r, 0);
    assert_eq!(m.face_child_vertex, (0..6).collect::<Vec<u32>>());
    assert_eq!(m.edge_child_vertex, (6..18).collect::<Vec<u32>>());
    assert_eq!(m.vertex_child_vertex, (18..26).collect::<Vec<u32>>());
}

/// Each level-1 quad has one corner at a cube vertex's child (valence 3), so
/// isolation 2 selects all 24 and level 2 is whole too (98, 192, 96).
///
/// At level 2 only the 24 faces at those 8 corners are selected. In one
/// level-1 face (corners X at the cube vertex, edge points E1, E2, face point
/// P; 2 × 2 children) the selected vertices are X', the midpoints of XE1 and
/// XE2 and the centre c: the child at X refines whole (4 faces), those at
/// E1 and E2 have two selected corners (2 faces each), the one at P one
/// (c: 1 face): 9 level-3 faces per level-1 face, 216 in all.
/// Vertices: selected ones 8 + 24 (XE midpoints) + 24 (centres) = 56; edge
/// points on the 96 edges at the centres and the 48 halves of the 24 XE
/// edges (all touch a midpoint) = 144; face points of all 96 level-2 faces
/// (each has a selected corner): 296. Edges: interior ones per level-1 face
/// 4 + 3 + 3 + 2 = 12 (two adjacent selected corners give three, one gives
/// two): 288; split edges per level-1 face: 2 + 2 (centre to XE midpoints,
/// selected) + 1 + 1 (centre to the EP midpoints) = 6, and per XE edge 2 + 1:
/// 144 + 72 = 216; 504 in all.
#[test]
fn cube_isolation_2_and_3_by_hand() {
    let r = adaptive(&shapes::cube(), Scheme::Catmark, 2, &[]);
    assert_eq!(r.max_level(), 2);
    assert_eq!(counts(&r, 2), (98, 192, 96));
    let m = check_maps(&r, 1);
    assert_eq!(valid(&m.face_child_faces), 96);

    let r = adaptive(&shapes::cube(), Scheme::Catmark, 3, &[]);
    assert_eq!(r.max_level(), 3);
    assert_eq!(counts(&r, 2), (98, 192, 96));
    assert_eq!(counts(&r, 3), (296, 504, 216));
    let m = check_maps(&r, 2);
    assert_eq!(valid(&m.vertex_child_vertex), 56);
    assert_eq!(valid(&m.edge_child_vertex), 144);
    assert_eq!(valid(&m.face_child_vertex), 96);
    // Per level-2 face: 4, 2, 2 or 1 children; 24 faces of each kind.
    let mut per_face = [0usize; 5];
    for w in m.face_child_face_offsets.windows(2) {
        per_face[valid(&m.face_child_faces[w[0] as usize..w[1] as usize])] += 1;
    }
    assert_eq!(per_face, [0, 24, 48, 0, 24]);
    // Level 3 keeps the full topology the limit needs.
    let base: Vec<f64> = shapes::cube().flat_positions();
    let last = r.interpolate_last(3, &base).unwrap();
    let limit = r.limit(3, &last).unwrap();
    assert_eq!(limit.positions.len(), 296 * 3);
}

/// A regular torus has no feature: nothing is selected and OpenSubdiv stops
/// at level 0, whatever the isolation level.
#[test]
fn regular_torus_stops_at_level_0() {
    let r = adaptive(&shapes::torus(8, 6), Scheme::Catmark, 3, &[]);
    assert_eq!(r.max_level(), 0);
    assert!(matches!(
        r.child_maps(0),
        Err(Error::NoSuchLevel { level: 0, .. })
    ));
    // Nothing refined, so, as in OpenSubdiv, the refiner may refine again.
    let mut r = r;
    r.refine_adaptive(AdaptiveOptions::new(2), &[]).unwrap();
    assert_eq!(r.max_level(), 0);
}

/// One edge of sharpness 1 on a regular torus: its two (dart) end vertices
/// select their faces, a 2 × 3 block (12 vertices, 17 edges). Level 1: 24
/// faces of the block, and in the ring of 14 faces around it the 4 corner
/// faces touch one selected vertex (1 face) and the 10 others two (2
/// faces): 48 faces; vertices 12 + 20 face points + 31 edge points (17 in
/// the block, 14 leaving it) = 63; edges 24 + 4 × 2 + 10 × 3 interior ones
/// and 17 × 2 + 14 split ones = 110. The crease decays to 0 at level 1,
/// nothing is left to isolate, and refinement stops below isolation 3.
#[test]
fn semi_sharp_edge_stops_early() {
    let mut torus = shapes::torus(8, 8);
    let (a, b) = (torus.face_vertices[0], torus.face_vertices[1]);
    torus.add_crease(a, b, 1.0);
    let r = adaptive(&torus, Scheme::Catmark, 3, &[]);
    assert_eq!(r.max_level(), 1);
    assert_eq!(counts(&r, 1), (63, 110, 48));
    let m = check_maps(&r, 0);
    assert_eq!(valid(&m.vertex_child_vertex), 12);
    assert_eq!(valid(&m.face_child_vertex), 20);
    let rel = r.relations(0).unwrap();
    let darts = rel
        .vertex_rules
        .iter()
        .filter(|&&r| r == Rule::Dart)
        .count();
    assert_eq!(darts, 2);
    assert_eq!(rel.edge_semi_sharp.iter().filter(|&&s| s).count(), 1);
}

/// Loop on an icosahedron (every vertex of valence 5): isolation 1 refines
/// everything: 12 + 30 vertices, 30 × 2 + 20 × 3 edges, 80 faces; Loop has no
/// face points.
#[test]
fn loop_icosahedron_isolation_1() {
    let r = adaptive(&shapes::icosahedron(), Scheme::Loop, 1, &[]);
    assert_eq!(counts(&r, 1), (42, 120, 80));
    let m = check_maps(&r, 0);
    assert!(m.face_child_vertex.iter().all(|&v| v == INVALID_INDEX));
    assert_eq!(valid(&m.face_child_faces), 80);
    assert_eq!(valid(&m.face_child_edges), 60);
}

/// A unit quad A = (0 1 4 3) beside a triangle T = (1 2 4):
///
/// ```text
/// 3 ---- 4
/// |  A  / \
/// |    / T \
/// 0 - 1 --- 2
/// ```
fn quad_and_triangle() -> Mesh {
    Mesh::from_faces(
        vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
        ],
        &[&[0, 1, 4, 3], &[1, 2, 4]],
    )
}

/// Bilinear: RefineAdaptive refines the irregular faces only, one level,
/// whatever the isolation level (0 included). T is selected (vertices 1, 2,
/// 4; edges 12, 24, 41). A gets the children at its corners 1 and 2 (vertices
/// 1 and 4), the interior edges 0, 1, 2 around them and its face point;
/// edge 01 its half at 1, edge 43 its half at 4, edge 30 nothing.
#[test]
fn bilinear_refines_only_the_triangle_and_its_neighbourhood() {
    let mesh = quad_and_triangle();
    for isolation in [0, 1, 3] {
        let r = adaptive(&mesh, Scheme::Bilinear, isolation, &[]);
        assert_eq!(r.max_level(), 1, "isolation {isolation}");
        // Vertices: 3 vertex points, 2 face points, 5 edge points.
        // Edges: 3 + 3 interior, 3 × 2 + 1 + 1 split. Faces: 2 + 3.
        assert_eq!(counts(&r, 1), (10, 14, 5));
    }
    let r = adaptive(&mesh, Scheme::Bilinear, 1, &[]);
    let m = check_maps(&r, 0);
    // Child faces in parent order: A's corners 1, 2 then T's three.
    assert_eq!(m.face_child_face_offsets, vec![0, 4, 7]);
    assert_eq!(
        m.face_child_faces,
        vec![INVALID_INDEX, 0, 1, INVALID_INDEX, 2, 3, 4]
    );
    assert_eq!(m.child_face_parent_face, vec![0, 0, 1, 1, 1]);
    assert_eq!(m.face_child_edges, vec![0, 1, 2, INVALID_INDEX, 3, 4, 5]);
    // Vertex points of 1, 2, 4 first; face points of A and T; then edges.
    assert_eq!(
        m.vertex_child_vertex,
        vec![INVALID_INDEX, 0, 1, INVALID_INDEX, 2]
    );
    assert_eq!(m.face_child_vertex, vec![3, 4]);
    let level0 = r.level(0).unwrap();
    let edge = |a: u32, b: u32| {
        level0
            .edge_vertices
            .iter()
            .position(|&[x, y]| (x, y) == (a, b) || (x, y) == (b, a))
            .unwrap()
    };
    // Edge points numbered in edge order over the edges that have one.
    let with_point = [edge(0, 1), edge(1, 4), edge(4, 3), edge(1, 2), edge(2, 4)];
    let mut sorted = with_point;
    sorted.sort_unstable();
    for (k, &e) in sorted.iter().enumerate() {
        assert_eq!(m.edge_child_vertex[e], 5 + k as u32);
    }
    assert_eq!(m.edge_child_vertex[edge(3, 0)], INVALID_INDEX);
    // Split edges after the 6 interior ones, in edge order; end 0 first.
    let end_child = |a: u32, b: u32| {
        let e = edge(a, b);
        let first = level0.edge_vertices[e][0] == a;
        m.edge_child_edges[e][if first { 0 } else { 1 }]
    };
    assert_eq!(end_child(0, 1), INVALID_INDEX);
    assert_ne!(end_child(1, 0), INVALID_INDEX);
    assert_ne!(end_child(4, 3), INVALID_INDEX);
    assert_eq!(end_child(3, 4), INVALID_INDEX);
    assert_eq!(m.edge_child_edges[edge(3, 0)], [INVALID_INDEX; 2]);
    let mut split: Vec<u32> = m.edge_child_edges.iter().flatten().copied().collect();
    split.retain(|&e| e != INVALID_INDEX);
    assert_eq!(split, (6..14).collect::<Vec<u32>>());

    // Bilinear positions: vertex points stay, face points are the mean of
    // the corners, edge points the midpoints.
    let base: Vec<f64> = mesh.flat_positions();
    let p1 = r.interpolate(1, 3, &base).unwrap();
    let at = |i: u32| DVec3::from_slice(&p1[3 * i as usize..3 * i as usize + 3]);
    assert_eq!(at(0), DVec3::new(1.0, 0.0, 0.0));
    assert_eq!(at(1), DVec3::new(2.0, 0.0, 0.0));
    assert_eq!(at(2), DVec3::new(1.0, 1.0, 0.0));
    assert_eq!(at(3), DVec3::new(0.5, 0.5, 0.0));
    assert!((at(4) - DVec3::new(4.0 / 3.0, 1.0 / 3.0, 0.0)).length() < 1e-15);
    for (v, e) in [
        (edge(0, 1), [0.5, 0.0]),
        (edge(1, 4), [1.0, 0.5]),
        (edge(4, 3), [0.5, 1.0]),
        (edge(1, 2), [1.5, 0.0]),
        (edge(2, 4), [1.5, 0.5]),
    ] {
        assert_eq!(at(m.edge_child_vertex[v]), DVec3::new(e[0], e[1], 0.0));
    }
    // Varying data is linear too: the same values.
    assert_eq!(r.interpolate_varying(1, 3, &base).unwrap(), p1);
    // The level's faces: A's two quads, then T's three.
    let level1 = r.level(1).unwrap();
    assert_eq!(level1.face_offsets, vec![0, 4, 8, 12, 16, 20]);
}

/// Selecting cube face 0 alone at isolation 1: its 4 children; each of the 4
/// faces beside it has two selected corners (2 children); the opposite face
/// none. Vertices 4 + 5 face points + 8 edge points (face 0's 4 edges and the
/// 4 leaving its corners); edges 4 + 4 × 3 interior, 4 × 2 + 4 split.
#[test]
fn selected_faces_limit_the_first_level() {
    let cube = shapes::cube();
    let r = adaptive(&cube, Scheme::Catmark, 1, &[0]);
    assert_eq!(counts(&r, 1), (17, 28, 12));
    let m = check_maps(&r, 0);
    let face0: Vec<u32> = cube.faces().next().unwrap().to_vec();
    for (f, verts) in cube.faces().enumerate() {
        let children = &m.face_child_faces[4 * f..4 * f + 4];
        let shared = verts.iter().filter(|v| face0.contains(v)).count();
        match shared {
            4 => assert_eq!(valid(children), 4),
            2 => assert_eq!(valid(children), 2),
            0 => {
                assert_eq!(valid(children), 0);
                assert_eq!(m.face_child_vertex[f], INVALID_INDEX);
            }
            n => panic!("a cube face shares {n} vertices with another"),
        }
    }
    // Listing a face twice changes nothing; selecting all six is isolation 1.
    let twice = adaptive(&cube, Scheme::Catmark, 1, &[0, 0]);
    assert_eq!(twice.child_maps(0).unwrap(), m);
    let all = adaptive(&cube, Scheme::Catmark, 1, &[0, 1, 2, 3, 4, 5]);
    assert_eq!(counts(&all, 1), (26, 48, 24));
    // Deeper levels select from every face of the level before.
    let r = adaptive(&cube, Scheme::Catmark, 2, &[0]);
    assert_eq!(r.max_level(), 2);
}

/// A hole is never selected, but its corners are selected by its
/// neighbours, so it gets a child (a hole) at every corner.
#[test]
fn holes_are_not_selected_but_neighboured() {
    let mut cube = shapes::cube();
    cube.holes.push(0);
    let r = adaptive(&cube, Scheme::Catmark, 1, &[]);
    assert_eq!(counts(&r, 1), (26, 48, 24));
    let holes = r.level(1).unwrap().face_holes;
    assert_eq!(holes.iter().filter(|&&h| h).count(), 4);
    // Selecting only the hole selects nothing.
    let r = adaptive(&cube, Scheme::Catmark, 1, &[0]);
    assert_eq!(r.max_level(), 0);
}

#[test]
fn refusals_come_before_opensubdiv() {
    let cube = shapes::cube();
    let fresh = || TopologyRefiner::new(&cube, &Options::default()).unwrap();
    let mut r = fresh();
    assert!(matches!(
        r.refine_adaptive(AdaptiveOptions::new(16), &[]),
        Err(Error::Level {
            level: 16,
            reason: LevelRefusal::TooDeep { max: 10 }
        })
    ));
    assert!(matches!(
        r.refine_adaptive(AdaptiveOptions::new(11), &[]),
        Err(Error::Level { level: 11, .. })
    ));
    assert!(matches!(
        r.refine_adaptive(AdaptiveOptions::new(2).secondary(16), &[]),
        Err(Error::Level {
            level: 16,
            reason: LevelRefusal::TooDeep { max: 15 }
        })
    ));
    assert!(matches!(
        r.refine_adaptive(AdaptiveOptions::new(1), &[2, 6]),
        Err(Error::NoSuchElement {
            element: Element::Face,
            index: 6,
            level: 0,
            count: 6
        })
    ));
    assert!(matches!(
        r.refine_adaptive(AdaptiveOptions::new(1), &[u32::MAX]),
        Err(Error::NoSuchElement { .. })
    ));
    // Nothing was refined by the refusals.
    assert_eq!(r.max_level(), 0);
    assert_eq!(r.adaptive_options(), None);
    // Secondary level 0: from level 1 on, extraordinary vertices are no
    // longer isolated, and the cube has nothing else: nothing is refined.
    r.refine_adaptive(AdaptiveOptions::new(1).secondary(0), &[])
        .unwrap();
    assert_eq!(r.max_level(), 0);
    // A refinement that stopped at level 0 left no level: OpenSubdiv
    // refines again; one that made levels is refused.
    r.refine_adaptive(AdaptiveOptions::new(1), &[]).unwrap();
    assert_eq!(r.max_level(), 1);
    assert!(matches!(
        r.refine_adaptive(AdaptiveOptions::new(1), &[]),
        Err(Error::AlreadyRefined { level: 1 })
    ));
    let mut z = fresh();
    z.refine_uniform(UniformOptions::new(0)).unwrap();
    z.refine_adaptive(AdaptiveOptions::new(1), &[]).unwrap();
    assert_eq!(z.level_counts(1).unwrap().faces, 24);
    let mut a = fresh();
    a.refine_adaptive(AdaptiveOptions::new(1), &[]).unwrap();
    assert!(matches!(
        a.refine_adaptive(AdaptiveOptions::new(1), &[]),
        Err(Error::AlreadyRefined { level: 1 })
    ));
    let mut u = fresh();
    u.refine_uniform(UniformOptions::new(2)).unwrap();
    assert!(matches!(
        u.refine_adaptive(AdaptiveOptions::new(1), &[]),
        Err(Error::AlreadyRefined { level: 2 })
    ));
    // A uniform refinement replaces an adaptive one.
    r.refine_uniform(UniformOptions::new(2)).unwrap();
    assert_eq!(r.adaptive_options(), None);
    assert_eq!(r.level_counts(2).unwrap().faces, 96);
    // Child maps need a level below the last.
    assert!(matches!(
        r.child_maps(2),
        Err(Error::NoSuchLevel { level: 2, .. })
    ));
}

/// Every option field reaches OpenSubdiv: with `useInfSharpPatch` an
/// infinitely sharp regular crease needs no isolation.
#[test]
fn inf_sharp_patch_option_is_passed_on() {
    // A 4 × 4 grid under edge-and-corner boundaries: boundary vertices are
    // regular creases and corners (one face), the interior is regular.
    let mut grid = shapes::grid(4, 4);
    grid.fvar_channels.clear();
    // An infinitely sharp (10: OpenSubdiv's infinity) line along the middle row of vertices: regular
    // creases inside, and where it meets the boundary regular corners (two
    // sharp sectors of one face): features only without the option.
    for i in 0..4 {
        grid.add_crease(5 * 2 + i, 5 * 2 + i + 1, 10.0);
    }
    let options = Options {
        boundary: BoundaryInterpolation::EdgeAndCorner,
        ..Options::default()
    };
    let run = |o: AdaptiveOptions| {
        let mut r = TopologyRefiner::new(&grid, &options).unwrap();
        r.refine_adaptive(o, &[]).unwrap();
        r.max_level()
    };
    assert_eq!(run(AdaptiveOptions::new(2)), 2);
    assert_eq!(run(AdaptiveOptions::new(2).inf_sharp_patch(true)), 0);
}

/// The relations of the cube by hand, and their consistency.
#[test]
fn relations_of_the_cube() {
    let mut cube = shapes::cube();
    let r = TopologyRefiner::new(&cube, &Options::default()).unwrap();
    let rel = r.relations(0).unwrap();
    let top = r.level(0).unwrap();
    assert_eq!(rel.face_edges.len(), 24);
    assert_eq!(
        rel.edge_face_offsets,
        (0..=12).map(|e| 2 * e).collect::<Vec<u32>>()
    );
    assert_eq!(
        rel.vertex_face_offsets,
        (0..=8).map(|v| 3 * v).collect::<Vec<u32>>()
    );
    assert_eq!(
        rel.vertex_edge_offsets,
        (0..=8).map(|v| 3 * v).collect::<Vec<u32>>()
    );
    assert!(rel.vertex_rules.iter().all(|&r| r == Rule::Smooth));
    // Valence 3 is extraordinary for Catmull-Clark.
    assert!(rel.vertex_valence_regular.iter().all(|&b| !b));
    for flags in [
        &rel.vertex_boundary,
        &rel.vertex_corner,
        &rel.vertex_non_manifold,
        &rel.vertex_inf_sharp,
        &rel.vertex_semi_sharp,
        &rel.edge_boundary,
        &rel.edge_non_manifold,
        &rel.edge_inf_sharp,
        &rel.edge_semi_sharp,
    ] {
        assert!(flags.iter().all(|&b| !b));
    }
    check_relations(&r, 0);
    // Level 1 of a uniform refinement with full topology: face and edge
    // points have valence 4.
    let mut u = TopologyRefiner::new(&cube, &Options::default()).unwrap();
    u.refine_uniform(UniformOptions::new(1).full_topology(true))
        .unwrap();
    let rel1 = u.relations(1).unwrap();
    assert_eq!(
        rel1.vertex_valence_regular.iter().filter(|&&b| b).count(),
        18
    );
    check_relations(&u, 1);
    // Without full topology the last level keeps no relations.
    let mut u = TopologyRefiner::new(&cube, &Options::default()).unwrap();
    u.refine_uniform(UniformOptions::new(1)).unwrap();
    assert!(matches!(
        u.relations(1),
        Err(Error::NoFullTopology { level: 1 })
    ));
    assert!(u.relations(0).is_ok());
    assert!(matches!(
        u.relations(2),
        Err(Error::NoSuchLevel { level: 2, .. })
    ));

    // Sharp features: an edge of sharpness 2 (its ends become darts), a
    // corner of sharpness 3 at another vertex.
    let [a, b] = top.edge_vertices[0];
    cube.add_crease(a, b, 2.0);
    let c = (0..8).find(|v| *v != a && *v != b).unwrap();
    cube.add_corner(c, 3.0);
    let r = TopologyRefiner::new(&cube, &Options::default()).unwrap();
    let rel = r.relations(0).unwrap();
    assert_eq!(
        (rel.vertex_rules[a as usize], rel.vertex_rules[b as usize]),
        (Rule::Dart, Rule::Dart)
    );
    assert_eq!(rel.vertex_rules[c as usize], Rule::Corner);
    assert!(rel.vertex_semi_sharp[c as usize]);
    assert!(rel.edge_semi_sharp[0]);
    assert_eq!(rel.edge_semi_sharp.iter().filter(|&&s| s).count(), 1);
}

/// Boundaries and non-manifold edges: a 2 × 2 grid's corners have one face,
/// its boundary edges are infinitely sharp; the fin's shared edge has three
/// faces.
#[test]
fn relations_of_boundaries_and_fins() {
    let mut grid = shapes::grid(2, 2);
    grid.fvar_channels.clear();
    let corners = Options {
        boundary: BoundaryInterpolation::EdgeAndCorner,
        ..Options::default()
    };
    let r = TopologyRefiner::new(&grid, &corners).unwrap();
    let rel = r.relations(0).unwrap();
    let corners: Vec<usize> = (0..9).filter(|&v| rel.vertex_corner[v]).collect();
    assert_eq!(corners, vec![0, 2, 6, 8]);
    assert_eq!(rel.vertex_boundary.iter().filter(|&&b| b).count(), 8);
    assert!(!rel.vertex_boundary[4] && rel.vertex_valence_regular[4]);
    assert_eq!(rel.edge_boundary.iter().filter(|&&b| b).count(), 8);
    assert_eq!(rel.edge_boundary, rel.edge_inf_sharp);
    assert_eq!(rel.vertex_rules[0], Rule::Corner);
    assert_eq!(rel.vertex_rules[1], Rule::Crease);
    assert_eq!(rel.vertex_rules[4], Rule::Smooth);
    check_relations(&r, 0);

    let r = TopologyRefiner::new(&shapes::fin(), &Options::default()).unwrap();
    let rel = r.relations(0).unwrap();
    let top = r.level(0).unwrap();
    let e01 = top
        .edge_vertices
        .iter()
        .position(|&e| e == [0, 1] || e == [1, 0])
        .unwrap();
    assert!(rel.edge_non_manifold[e01]);
    let n = rel.edge_face_offsets[e01 + 1] - rel.edge_face_offsets[e01];
    assert_eq!(n, 3);
    assert!(rel.vertex_non_manifold[0] && rel.vertex_non_manifold[1]);
    assert_eq!(rel.edge_non_manifold.iter().filter(|&&b| b).count(), 1);
    check_relations(&r, 0);

    // An adaptive level's relations.
    let r = adaptive(&shapes::cube(), Scheme::Catmark, 3, &[]);
    check_relations(&r, 3);
}

/// Each relation and its local indices say the same as the face-vertices.
fn check_relations(r: &TopologyRefiner, level: u32) {
    let top = r.level(level).unwrap();
    let rel = r.relations(level).unwrap();
    let face = |f: usize| {
        &top.face_vertices[top.face_offsets[f] as usize..top.face_offsets[f + 1] as usize]
    };
    let face_edges =
        |f: usize| &rel.face_edges[top.face_offsets[f] as usize..top.face_offsets[f + 1] as usize];
    for f in 0..top.face_offsets.len() - 1 {
        let (vs, es) = (face(f), face_edges(f));
        for j in 0..vs.len() {
            let [a, b] = top.edge_vertices[es[j] as usize];
            let (u, v) = (vs[j], vs[(j + 1) % vs.len()]);
            assert!((a, b) == (u, v) || (a, b) == (v, u), "face {f} edge {j}");
        }
    }
    for e in 0..top.edge_count {
        let range = rel.edge_face_offsets[e] as usize..rel.edge_face_offsets[e + 1] as usize;
        for (&f, &k) in rel.edge_faces[range.clone()]
            .iter()
            .zip(&rel.edge_face_local[range])
        {
            assert_eq!(face_edges(f as usize)[k as usize], e as u32);
        }
    }
    for v in 0..top.vertex_count {
        let range = rel.vertex_face_offsets[v] as usize..rel.vertex_face_offsets[v + 1] as usize;
        for (&f, &k) in rel.vertex_faces[range.clone()]
            .iter()
            .zip(&rel.vertex_face_local[range])
        {
            assert_eq!(face(f as usize)[k as usize], v as u32);
        }
        let range = rel.vertex_edge_offsets[v] as usize..rel.vertex_edge_offsets[v + 1] as usize;
        for (&e, &k) in rel.vertex_edges[range.clone()]
            .iter()
            .zip(&rel.vertex_edge_local[range])
        {
            assert_eq!(top.edge_vertices[e as usize][k as usize], v as u32);
        }
    }
}

/// The ptex faces of a square pyramid under Catmull-Clark by hand: the
/// square base is one ptex face, each triangle three.
#[test]
fn ptex_of_a_pyramid_by_hand() {
    let mesh = shapes::pyramid(4);
    let native = PtexIndices::new(&Refiner::new(&mesh, &Options::default()).unwrap()).unwrap();
    let osd = TopologyRefiner::new(&mesh, &Options::default()).unwrap();
    let ptex = osd.ptex_indices().unwrap();
    assert_eq!(ptex, native);
    assert_eq!(ptex.num_faces(), 13);
    let ids: Vec<u32> = (0..5).map(|f| ptex.face_id(f).unwrap()).collect();
    assert_eq!(ids, vec![0, 1, 4, 7, 10]);
    // Triangle 1 = (0 1 4): quadrant 0 sits at vertex 0, between edge 01
    // (shared with the base) and edge 40 (shared with triangle 4 = (3 0 4),
    // where it is edge 1: that triangle's quadrant 1, at vertex 0, has its
    // edge 0 there).
    let adj = osd.ptex_adjacency(1, 0).unwrap();
    assert_eq!(adj.faces[1..3], [2, 3]);
    assert_eq!(adj.edges[1..3], [2, 1]);
    // Edge 01 is the base (3 2 1 0)'s edge 2.
    assert_eq!((adj.faces[0], adj.edges[0]), (0, 2));
    assert_eq!((adj.faces[3], adj.edges[3]), (11, 0));
    // The base (3 2 1 0): its edge 0 (3-2) borders triangle 3 = (2 3 4),
    // whose quadrant after that edge (its 1) has its edge 3 there.
    let adj = osd.ptex_adjacency(0, 0).unwrap();
    assert_eq!((adj.faces[0], adj.edges[0]), (8, 3));
    // Refusals: a quad has one ptex face; faces out of range.
    assert!(matches!(
        osd.ptex_adjacency(0, 1),
        Err(Error::NoSuchElement { .. })
    ));
    assert!(matches!(
        osd.ptex_adjacency(1, 3),
        Err(Error::NoSuchElement { .. })
    ));
    assert!(matches!(
        osd.ptex_adjacency(5, 0),
        Err(Error::NoSuchElement { index: 5, .. })
    ));
    assert!(matches!(ptex.face_id(5), Err(Error::NoSuchElement { .. })));
}

/// Native ptex indices and adjacency equal OpenSubdiv's on every face and
/// quadrant: quads, triangles, n-gons, boundaries, non-manifold edges and
/// vertices, holes; Catmull-Clark, bilinear and Loop.
#[test]
fn ptex_native_equals_opensubdiv() {
    let mut holed = shapes::grid(3, 3);
    holed.holes.push(4);
    let mut holed_pole = shapes::pole(5);
    holed_pole.holes.extend([0, 3]);
    let quad_meshes = vec![
        ("cube", shapes::cube()),
        ("grid", shapes::grid(3, 2)),
        ("holed grid", holed),
        ("torus mixed", shapes::torus_mixed(4, 4)),
        ("pyramid", shapes::pyramid(5)),
        ("prism", shapes::prism(6)),
        ("pole", shapes::pole(5)),
        ("holed pole", holed_pole),
        ("fan", shapes::fan(4, 2.0)),
        ("book", shapes::book(4, 4)),
        ("triangle book", shapes::book(3, 3)),
        ("fin", shapes::fin()),
        ("bowtie", shapes::bowtie()),
        ("inconsistent", shapes::inconsistent()),
        ("four boxes", shapes::four_boxes()),
        ("quad and triangle", quad_and_triangle()),
    ];
    let tri_meshes = vec![
        ("icosahedron", shapes::icosahedron()),
        ("octahedron", shapes::octahedron()),
        ("tetrahedron", shapes::tetrahedron()),
        ("torus triangles", shapes::torus_triangles(4, 3)),
        (
            "triangulated grid",
            shapes::triangulate(&shapes::grid(3, 2)),
        ),
        ("fan", shapes::fan(5, 3.0)),
        ("wheel", shapes::wheel(6)),
        ("triangle book", shapes::book(5, 3)),
        (
            "triangulated bowtie",
            shapes::triangulate(&shapes::bowtie()),
        ),
    ];
    let mut checked = 0;
    for (scheme, meshes) in [
        (Scheme::Catmark, &quad_meshes),
        (Scheme::Bilinear, &quad_meshes),
        (Scheme::Loop, &tri_meshes),
    ] {
        for (name, mesh) in meshes {
            let o = options(scheme);
            let native_refiner = Refiner::new(mesh, &o).unwrap();
            let native = PtexIndices::new(&native_refiner).unwrap();
            let osd = TopologyRefiner::new(mesh, &o).unwrap();
            assert_eq!(osd.ptex_indices().unwrap(), native, "{name} {scheme:?}");
            for f in 0..mesh.face_count() {
                let quadrants = native.face_ptex_count(f).unwrap();
                for q in 0..quadrants {
                    assert_eq!(
                        native.adjacency(&native_refiner, f, q).unwrap(),
                        osd.ptex_adjacency(f, q).unwrap(),
                        "{name} {scheme:?} face {f} quadrant {q}"
                    );
                    checked += 1;
                }
                assert!(native.adjacency(&native_refiner, f, quadrants).is_err());
            }
        }
    }
    assert!(checked > 300, "{checked}");
}

/// Every per-level query of the refiner works on sparse levels: whole
/// levels, vertex, varying and face-varying interpolation, limits (their
/// incomplete vertices keep their refined values), and stencil tables with
/// one stencil per last-level vertex.
#[test]
fn per_level_queries_work_on_sparse_levels() {
    let mesh = shapes::cube_with_uvs();
    let o = Options {
        fvar: FVarLinearInterpolation::None,
        ..Options::default()
    };
    let mut r = TopologyRefiner::new(&mesh, &o).unwrap();
    r.refine_adaptive(AdaptiveOptions::new(3), &[0]).unwrap();
    assert_eq!(r.max_level(), 3);
    let base: Vec<f64> = mesh.flat_positions();
    let all = r.interpolate_all(3, &base).unwrap();
    for level in 0..=3 {
        let top = r.level(level).unwrap();
        assert_eq!(all[level as usize].len(), 3 * top.vertex_count);
        assert_eq!(top.edge_vertices.len(), top.edge_count);
        assert_eq!(
            r.interpolate_varying(level.max(1), 3, &all[level.max(1) as usize - 1])
                .unwrap()
                .len(),
            all[level.max(1) as usize].len()
        );
    }
    let channel = &mesh.fvar_channels[0];
    let mut uv = channel.values.clone();
    for level in 1..=3 {
        uv = r.interpolate_face_varying(0, level, 2, &uv).unwrap();
        assert_eq!(uv.len(), 2 * r.level(level).unwrap().fvar[0].value_count);
    }
    let last = &all[3];
    let limit = r.limit(3, last).unwrap();
    assert_eq!(limit.positions.len(), last.len());
    assert_eq!(r.limit_face_varying(0, 2, &uv).unwrap().len(), uv.len());
    let vertices = r.level_counts(3).unwrap().vertices;
    assert_eq!(r.stencil_table().unwrap().len(), vertices);
    assert_eq!(r.limit_stencil_table().unwrap().positions.len(), vertices);
    // The refined stencils reproduce the interpolated last level.
    let table = r.stencil_table().unwrap();
    for (s, chunk) in last.chunks_exact(3).enumerate() {
        let range = table.offsets[s] as usize..(table.offsets[s] + table.sizes[s]) as usize;
        let mut p = DVec3::ZERO;
        for (&i, &w) in table.indices[range.clone()]
            .iter()
            .zip(&table.weights[range])
        {
            p += mesh.positions[i as usize] * w;
        }
        assert!(
            (p - DVec3::from_slice(chunk)).length() < 1e-12,
            "vertex {s}"
        );
    }
}

/// `useSingleCreasePatch`: a ring of edges of sharpness 2 around a regular
/// torus gives every face beside it exactly one semi-sharp edge, between
/// regular crease vertices: a single-crease patch, left unrefined with the
/// option. Without it those faces are selected while the crease is
/// semi-sharp: sharpness 2 at level 0 and 1 at level 1, 0 from level 2 on,
/// so refinement stops at level 2 under isolation 3.
#[test]
fn single_crease_patch_option_is_passed_on() {
    let mut torus = shapes::torus(8, 6);
    for i in 0..8 {
        torus.add_crease(i, (i + 1) % 8, 2.0);
    }
    let run = |o: AdaptiveOptions| {
        let mut r = TopologyRefiner::new(&torus, &Options::default()).unwrap();
        r.refine_adaptive(o, &[]).unwrap();
        r.max_level()
    };
    assert_eq!(run(AdaptiveOptions::new(3)), 2);
    assert_eq!(run(AdaptiveOptions::new(3).single_crease_patch(true)), 0);
}
