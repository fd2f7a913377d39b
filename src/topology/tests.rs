//! Tests of the levels a refinement builds: which tables each level stores
//! (sharpness, tags, holes, relations), and that what it leaves out reads
//! the same as what a full level stores.

use super::{EdgeTag, VertexTag};
use crate::mesh::Mesh;
use crate::options::{BoundaryInterpolation, CreasingMethod, Options, UniformOptions};
use crate::refiner::Refiner;
use crate::rules::{Rule, crease};
use crate::shapes;

/// `mesh` refined to `depth` under each scheme that applies, with full
/// topology in the last level or not.
fn refiners(mesh: &Mesh, depth: u32, full: bool) -> Vec<Refiner> {
    refiners_with(mesh, depth, full, BoundaryInterpolation::None)
}

/// [`refiners`] with another boundary interpolation.
fn refiners_with(
    mesh: &Mesh,
    depth: u32,
    full: bool,
    boundary: BoundaryInterpolation,
) -> Vec<Refiner> {
    mesh.applicable_schemes()
        .iter()
        .map(|&scheme| {
            let options = Options::default()
                .with_scheme(scheme)
                .with_boundary(boundary)
                .with_creasing(CreasingMethod::Uniform);
            let mut r = Refiner::new(mesh, &options).unwrap();
            r.refine_uniform(UniformOptions::new(depth).full_topology(full))
                .unwrap();
            r
        })
        .collect()
}

/// Which of edge sharpness, vertex sharpness and holes each level
/// stores, after checking that the accessors read what
/// `Refiner::level` reports.
fn stored(r: &Refiner) -> Vec<[bool; 3]> {
    (0..=r.max_level())
        .map(|l| {
            let level = r.internal_level(l).unwrap();
            let topo = r.level(l).unwrap();
            assert_eq!(topo.edge_sharpness.len(), level.edge_count());
            assert_eq!(topo.vertex_sharpness.len(), level.vertex_count);
            assert_eq!(topo.face_holes.len(), level.face_count());
            if level.has_full_topology() {
                for (e, &s) in topo.edge_sharpness.iter().enumerate() {
                    assert_eq!(level.edge_sharpness_at(e).to_bits(), s.to_bits());
                }
            }
            for (v, &s) in topo.vertex_sharpness.iter().enumerate() {
                assert_eq!(level.vertex_sharpness_at(v).to_bits(), s.to_bits());
            }
            for (f, &h) in topo.face_holes.iter().enumerate() {
                assert_eq!(level.is_hole(f), h);
            }
            [
                !level.edge_sharpness.is_empty(),
                !level.vertex_sharpness.is_empty(),
                !level.face_holes.is_empty(),
            ]
        })
        .collect()
}

/// Which of edge tags and vertex tags each level of `r` stores, after
/// checking the tags read through the accessors: the same vertex tags at
/// every level as `full` (the same refinement with full topology in its
/// last level), the same edge tags where `r` keeps them, and at full
/// levels tags that match the topology and sharpness (boundary edges and
/// vertices, sharp flags, rules from the sharp edge count).
fn stored_tags(r: &Refiner, full: &Refiner) -> Vec<[bool; 2]> {
    (0..=r.max_level())
        .map(|l| {
            let (level, f) = (
                r.internal_level(l).unwrap(),
                full.internal_level(l).unwrap(),
            );
            for v in 0..level.vertex_count {
                assert_eq!(level.vertex_tag(v), f.vertex_tag(v), "level {l} vertex {v}");
            }
            if level.has_full_topology() {
                for e in 0..level.edge_count() {
                    let tag = level.edge_tag(e);
                    assert_eq!(tag, f.edge_tag(e), "level {l} edge {e}");
                    let faces = r.edge_faces(l, e).unwrap().len();
                    assert_eq!(tag.boundary(), faces < 2);
                    let s = level.edge_sharpness_at(e);
                    assert_eq!(tag.inf_sharp(), crease::is_infinite(s));
                    assert_eq!(tag.semi_sharp(), crease::is_sharp(s) && !tag.inf_sharp());
                }
                for v in 0..level.vertex_count {
                    let tag = level.vertex_tag(v);
                    let (_, around) = r.vertex_faces_and_edges(l, v).unwrap();
                    let edges = around.iter().map(|&e| level.edge_tag(e as usize));
                    let sharp = edges.clone().filter(|t| t.inf_sharp() || t.semi_sharp());
                    let s = level.vertex_sharpness_at(v);
                    assert_eq!(tag.boundary(), edges.clone().any(|t| t.boundary()));
                    assert_eq!(tag.inf_sharp(), crease::is_infinite(s));
                    assert_eq!(
                        tag.semi_sharp_edges(),
                        edges.clone().any(|t| t.semi_sharp())
                    );
                    assert_eq!(tag.inf_sharp_edges(), edges.clone().any(|t| t.inf_sharp()));
                    assert_eq!(
                        tag.rule(),
                        crease::vertex_rule_from_sharp_edge_count(s, sharp.count()),
                        "level {l} vertex {v}"
                    );
                }
            }
            [!level.edge_tags.is_empty(), !level.vertex_tags.is_empty()]
        })
        .collect()
}

/// [`stored_tags`] of each refinement of `mesh` to level 3, with and
/// without full topology in the last level, by scheme.
fn stored_tags_by_scheme(
    mesh: &Mesh,
    boundary: BoundaryInterpolation,
) -> Vec<(bool, Vec<[bool; 2]>)> {
    let full = refiners_with(mesh, 3, true, boundary);
    [false, true]
        .into_iter()
        .flat_map(|f| {
            let full = &full;
            refiners_with(mesh, 3, f, boundary)
                .into_iter()
                .zip(full)
                .map(move |(r, rf)| (f, stored_tags(&r, rf)))
        })
        .collect()
}

#[test]
fn smooth_closed_levels_store_no_tags() {
    for mesh in [shapes::torus(6, 5), shapes::torus_triangles(6, 5)] {
        for (_, stored) in stored_tags_by_scheme(&mesh, BoundaryInterpolation::None) {
            assert_eq!(stored, vec![[false; 2]; 4]);
        }
        for r in refiners(&mesh, 2, true) {
            let level = r.internal_level(1).unwrap();
            assert_eq!(level.vertex_tag(0), VertexTag::default());
            assert_eq!(level.vertex_tag(0).rule(), Rule::Smooth);
            assert_eq!(level.edge_tag(0), EdgeTag::default());
        }
    }
}

#[test]
fn boundaries_creases_corners_and_darts_store_tags() {
    // Boundaries (and their corners) stay at every level; a minimal last
    // level (none with face-varying data) stores no edge tags.
    let mut grid = shapes::grid(3, 2);
    grid.fvar_channels.clear();
    for boundary in [
        BoundaryInterpolation::None,
        BoundaryInterpolation::EdgeAndCorner,
    ] {
        for (full, stored) in stored_tags_by_scheme(&grid, boundary) {
            assert_eq!(
                stored,
                [[true, true], [true, true], [true, true], [full, true]]
            );
        }
    }
    for r in refiners_with(&grid, 1, true, BoundaryInterpolation::EdgeAndCorner) {
        let level = r.internal_level(0).unwrap();
        assert!(level.edge_tag(0).boundary() && level.edge_tag(0).inf_sharp());
        let corner = level.vertex_tag(0);
        assert!(corner.corner() && corner.boundary() && corner.inf_sharp());
        assert_eq!(corner.rule(), Rule::Corner);
        assert_eq!(level.vertex_tag(1).rule(), Rule::Crease);
        assert_eq!(level.vertex_tag(5).rule(), Rule::Smooth);
    }
    // A crease of 2 and a corner of 1.5 decay to 0 after two levels:
    // their tags go back to the default and are not stored.
    for mut mesh in [shapes::torus(6, 5), shapes::torus_triangles(6, 5)] {
        mesh.add_crease(0, 1, 2.0);
        mesh.add_corner(10, 1.5);
        for (_, stored) in stored_tags_by_scheme(&mesh, BoundaryInterpolation::None) {
            assert_eq!(stored, [[true, true], [true, true], [false; 2], [false; 2]]);
        }
        for r in refiners(&mesh, 1, true) {
            let level = r.internal_level(0).unwrap();
            assert_eq!(level.vertex_tag(0).rule(), Rule::Dart);
            assert!(level.vertex_tag(0).semi_sharp_edges());
            assert_eq!(level.vertex_tag(10).rule(), Rule::Corner);
            assert!(level.vertex_tag(10).semi_sharp());
            assert!(
                level
                    .edge_tag(level.find_edge(0, 1).unwrap() as usize)
                    .semi_sharp()
            );
        }
        // An infinitely sharp crease (darts at its ends) stays.
        mesh.add_crease(0, 1, crate::rules::SHARPNESS_INFINITE);
        for (full, stored) in stored_tags_by_scheme(&mesh, BoundaryInterpolation::None) {
            assert_eq!(
                stored,
                [[true, true], [true, true], [true, true], [full, true]]
            );
        }
    }
}

/// The values above 0.
fn sharp(values: &[f32]) -> Vec<f32> {
    values.iter().copied().filter(|&s| s > 0.0).collect()
}

#[test]
fn vertex_edge_ends_are_kept_where_sharpness_decays_into_a_minimal_level() {
    // A crease of 3 is still 1 at level 2 and decays while level 3 is
    // built (minimal): level 2 keeps which end of its edges each vertex
    // is, and the positions equal those of a full refinement.
    for mut mesh in [shapes::torus(6, 5), shapes::torus_triangles(6, 5)] {
        mesh.add_crease(0, 1, 3.0);
        mesh.add_corner(10, 2.5);
        let base = mesh.flat_positions::<f64>();
        let minimal = refiners(&mesh, 3, false);
        let full = refiners(&mesh, 3, true);
        for (m, f) in minimal.iter().zip(&full) {
            let level2 = m.internal_level(2).unwrap();
            assert_eq!(
                level2.vertex_edge_local.len(),
                level2.vertex_edges.members.len()
            );
            assert!(!level2.has_local_indices());
            assert_eq!(
                m.interpolate_all(3, &base).unwrap(),
                f.interpolate_all(3, &base).unwrap()
            );
        }
    }
}

#[test]
fn the_level_before_a_minimal_last_level_keeps_no_face_local_indices() {
    for mesh in [shapes::torus(6, 4), shapes::torus_triangles(6, 4)] {
        for full in [false, true] {
            for r in refiners(&mesh, 3, full) {
                let kept: Vec<bool> = (0..=3)
                    .map(|l| r.internal_level(l).unwrap().has_local_indices())
                    .collect();
                // Smooth meshes: level 2 keeps its vertex-edge ends
                // only if something reads them (a full level 3).
                let level2 = r.internal_level(2).unwrap();
                assert_eq!(level2.vertex_edge_local.is_empty(), !full);
                if full {
                    assert_eq!(kept, [true; 4]);
                } else {
                    // Level 3 is minimal: nothing to keep, trivially true.
                    assert_eq!(kept, [true, true, false, true]);
                    assert!(level2.vertex_face_local.is_empty());
                    assert!(level2.edge_face_local.is_empty());
                }
            }
        }
    }
}

/// The level before a minimal last level of a smooth closed mesh leaves
/// out its vertex relations and edge-faces; derived from its parent,
/// they are the ones a full level stores, element by element, in both
/// vertex orders and under every scheme. With sharpness in the parent,
/// they are stored.
#[test]
fn derived_relations_equal_the_stored_ones() {
    let mut buf = super::AroundBuf::default();
    let meshes = [
        shapes::torus(6, 5),
        shapes::torus_mixed(6, 4),
        shapes::torus_triangles(6, 5),
    ];
    let mut derived_levels = 0;
    for mesh in meshes {
        for &scheme in mesh.applicable_schemes() {
            for faces_first in [false, true] {
                for depth in 2..=3 {
                    let options = Options::default().with_scheme(scheme);
                    let uniform = UniformOptions::new(depth).faces_first(faces_first);
                    let mut minimal = Refiner::new(&mesh, &options).unwrap();
                    minimal.refine_uniform(uniform).unwrap();
                    let mut full = Refiner::new(&mesh, &options).unwrap();
                    full.refine_uniform(uniform.full_topology(true)).unwrap();
                    let l = depth as usize - 1;
                    let (derived, stored) = (&minimal.levels[l], &full.levels[l]);
                    assert!(derived.derived_relations, "{scheme:?} L{depth}");
                    assert!(derived.vertex_faces.is_empty() && derived.vertex_edges.is_empty());
                    assert!(derived.has_full_topology());
                    assert!(!stored.derived_relations);
                    derived_levels += 1;
                    let triangles = scheme == crate::options::Scheme::Loop;
                    let (grand, r) = (&minimal.levels[l - 1].slices(), &minimal.refinements[l - 1]);
                    for v in 0..stored.vertex_count {
                        let (faces, edges) = minimal.vertex_hood(l, v, &mut buf);
                        assert_eq!(faces, stored.vertex_faces_of(v), "{scheme:?} L{depth} v{v}");
                        assert_eq!(edges, stored.vertex_edges_of(v), "{scheme:?} L{depth} v{v}");
                        // The kernel's form: faces and far ends, up to 8.
                        let (mut f, mut far) = ([0; 8], [0; 8]);
                        let n = super::refine::derive_smooth_hood(
                            grand, r, triangles, v, &mut f, &mut far,
                        )
                        .expect("valence up to 8");
                        assert_eq!(&f[..n], faces, "{scheme:?} L{depth} v{v}");
                        let fars: Vec<u32> = edges
                            .iter()
                            .map(|&e| stored.other_vertex(e as usize, v as u32))
                            .collect();
                        assert_eq!(&far[..n], &fars[..], "{scheme:?} L{depth} v{v}");
                    }
                    // The public accessors, on the derived level.
                    let (faces, edges) = minimal.vertex_faces_and_edges(l as u32, 7).unwrap();
                    assert_eq!(
                        (&faces[..], &edges[..]),
                        (stored.vertex_faces_of(7), stored.vertex_edges_of(7))
                    );
                    for (e, &[a, b]) in stored.edge_vertices.iter().enumerate() {
                        assert_eq!(minimal.find_edge(l as u32, a, b).unwrap(), Some(e as u32));
                        assert_eq!(minimal.find_edge(l as u32, b, a).unwrap(), Some(e as u32));
                    }
                    assert!(derived.edge_faces.is_empty());
                    for e in 0..stored.edge_count() {
                        let faces = super::refine::derive_edge_faces(grand, r, triangles, e);
                        assert_eq!(
                            &faces[..],
                            stored.edge_faces_of(e),
                            "{scheme:?} L{depth} e{e}"
                        );
                        assert_eq!(minimal.edge_faces(l as u32, e).unwrap(), faces);
                        if triangles {
                            // The vertices opposite the edge in its faces.
                            let wings = match e.checked_sub(r.parent_corners) {
                                Some(i) => super::refine::derive_half_edge_wings(grand, r, i / 2)
                                    .map(|h| h[i % 2]),
                                None => super::refine::derive_inner_edge_wings(grand, r, e),
                            };
                            let opposite = faces.map(|f| {
                                crate::refiner::opposite_vertex(&stored.slices(), f as usize, e)
                            });
                            assert_eq!(wings, Some(opposite), "{scheme:?} L{depth} e{e}");
                        }
                    }
                    assert!(minimal.edge_faces(l as u32, stored.edge_count()).is_err());
                    let count = stored.vertex_count;
                    assert!(minimal.vertex_faces_and_edges(l as u32, count).is_err());
                    assert!(minimal.find_edge(l as u32, 0, count as u32).is_err());
                }
            }
        }
    }
    assert_eq!(derived_levels, 2 * 2 * (2 + 2 + 3));
    // A semi-sharp crease in the parent: the relations are stored.
    let mut mesh = shapes::torus(6, 5);
    mesh.add_crease(0, 1, 3.0);
    for r in refiners(&mesh, 3, false) {
        assert!(!r.levels[2].derived_relations);
        assert!(!r.levels[2].vertex_faces.is_empty());
    }
}

/// With a face-varying channel, the level before a minimal last one
/// derives its relations too when its parent is smooth everywhere: read
/// through [`Around`](super::Around) — local indices included — they are the
/// ones a full level stores, and so are the channel's face values and each
/// corner's sibling; with a crease in the parent, the level stores them.
#[test]
fn channels_read_derived_relations_as_stored() {
    let meshes = [
        shapes::with_torus_uvs(shapes::torus(6, 5), 6, 5),
        shapes::with_torus_uvs(shapes::torus_mixed(6, 4), 6, 4),
        shapes::with_torus_uvs(shapes::torus_triangles(6, 5), 6, 5),
    ];
    let (mut a, mut b) = (super::AroundBuf::default(), super::AroundBuf::default());
    let mut derived_levels = 0;
    for mesh in meshes {
        for &scheme in mesh.applicable_schemes() {
            for depth in 2..=3 {
                let options = Options::default().with_scheme(scheme);
                let uniform = UniformOptions::new(depth);
                let mut minimal = Refiner::new(&mesh, &options).unwrap();
                minimal.refine_uniform(uniform).unwrap();
                let mut full = Refiner::new(&mesh, &options).unwrap();
                full.refine_uniform(uniform.full_topology(true)).unwrap();
                let l = depth as usize - 1;
                assert!(minimal.levels[l].derived_relations, "{scheme:?} L{depth}");
                derived_levels += 1;
                let (derived, stored) = (minimal.around(l), full.around(l));
                let level = stored.level;
                for v in 0..level.vertex_count {
                    let (d, s) = (
                        derived.vertex_hood(v, &mut a),
                        stored.vertex_hood(v, &mut b),
                    );
                    assert_eq!(d.faces, s.faces, "{scheme:?} L{depth} v{v}");
                    assert_eq!(d.face_locals, s.face_locals, "{scheme:?} L{depth} v{v}");
                    assert_eq!(d.edges, s.edges, "{scheme:?} L{depth} v{v}");
                    assert_eq!(d.edge_locals, s.edge_locals, "{scheme:?} L{depth} v{v}");
                }
                for e in 0..level.edge_count() {
                    assert_eq!(derived.edge_face_count(e), stored.edge_face_count(e));
                    for i in 0..2 {
                        assert_eq!(derived.edge_face(e, i), stored.edge_face(e, i), "e{e}");
                    }
                }
                let (dc, sc) = (&minimal.fvar[0][l], &full.fvar[0][l]);
                assert_eq!(dc.face_values(), sc.face_values(), "{scheme:?} L{depth}");
                let mut mismatched = 0;
                for v in 0..level.vertex_count {
                    let hood = stored.vertex_hood(v, &mut b);
                    for (i, (&f, &k)) in hood.faces.iter().zip(hood.face_locals).enumerate() {
                        let (f, k) = (f as usize, k as usize);
                        let s = sc.corner_sibling(level, v, f, k, i);
                        assert_eq!(s, sc.vertex_face_siblings(level, v)[i]);
                        assert_eq!(dc.corner_sibling(level, v, f, k, i), s, "v{v} f{f}");
                        mismatched += usize::from(s > 0);
                    }
                }
                assert!(mismatched > 0, "{scheme:?} L{depth}: no seam read");
            }
        }
    }
    assert_eq!(derived_levels, 2 * (2 + 2 + 3));
    // A semi-sharp crease in the parent: the relations are stored.
    let mut mesh = shapes::with_torus_uvs(shapes::torus(6, 5), 6, 5);
    mesh.add_crease(0, 1, 3.0);
    for r in refiners(&mesh, 3, false) {
        assert!(!r.levels[2].derived_relations);
        assert!(r.levels[2].has_local_indices());
    }
}

#[test]
fn smooth_closed_levels_store_no_sharpness_or_holes() {
    for mesh in [shapes::torus(6, 5), shapes::torus_triangles(6, 5)] {
        for full in [false, true] {
            for r in refiners(&mesh, 3, full) {
                assert_eq!(stored(&r), vec![[false; 3]; 4], "{:?}", r.options.scheme);
                assert!(r.internal_level(3).unwrap().has_full_topology() == full);
            }
        }
    }
}

#[test]
fn sharpness_is_stored_until_it_decays_to_zero() {
    for mut mesh in [shapes::torus(6, 5), shapes::torus_triangles(6, 5)] {
        mesh.add_crease(0, 1, 2.0);
        mesh.add_corner(10, 1.5);
        mesh.holes.push(5);
        for full in [false, true] {
            for r in refiners(&mesh, 3, full) {
                let scheme = r.options.scheme;
                // A crease of 2 decays to 1, then 0; a corner of 1.5 to
                // 0.5, then 0; children of holes are holes.
                let expected = [[true, true, true], [true, true, true], [false, false, true]];
                assert_eq!(
                    stored(&r),
                    [expected[0], expected[1], expected[2], expected[2]],
                    "{scheme:?} full {full}"
                );
                let l1 = r.level(1).unwrap();
                assert_eq!(sharp(&l1.edge_sharpness), [1.0, 1.0], "{scheme:?}");
                assert_eq!(sharp(&l1.vertex_sharpness), [0.5], "{scheme:?}");
            }
        }
        // A minimal last level stores no edge sharpness; `Refiner::level`
        // recomputes it from the parent.
        for r in refiners(&mesh, 1, false) {
            assert!(r.internal_level(1).unwrap().edge_sharpness.is_empty());
            assert_eq!(sharp(&r.level(1).unwrap().edge_sharpness), [1.0, 1.0]);
        }
    }
}
