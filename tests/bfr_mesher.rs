//! The watertight mesher (`bfr::tessellate`) over the native limit
//! surfaces: closed meshes stay closed (every edge on two facets, in
//! opposite directions), the points at base vertices are the limit
//! positions OpenSubdiv's `PrimvarRefiner::Limit` gives (computed by the
//! native refiner), and the counts are those of the patterns.

use std::collections::HashMap;
use subdiv::bfr::{LimitSurfaces, SurfaceOptions, TessellateOptions, TessellatedMesh, tessellate};
use subdiv::refiner::Refiner;
use subdiv::{Mesh, Options, shapes};

/// Every directed edge of the facets, counted.
fn directed_edges(t: &TessellatedMesh) -> HashMap<(u32, u32), u32> {
    let mut edges = HashMap::new();
    for w in t.face_offsets.windows(2) {
        let f = &t.face_vertices[w[0] as usize..w[1] as usize];
        for i in 0..f.len() {
            *edges.entry((f[i], f[(i + 1) % f.len()])).or_insert(0) += 1;
        }
    }
    edges
}

fn assert_closed(t: &TessellatedMesh, label: &str) {
    for (&(a, b), &count) in &directed_edges(t) {
        let back = directed_edges(t).get(&(b, a)).copied().unwrap_or(0);
        assert_eq!((count, back), (1, 1), "{label}: edge {a}-{b}");
    }
}

fn surfaces(mesh: &Mesh) -> LimitSurfaces {
    LimitSurfaces::new(mesh, &Options::default(), &SurfaceOptions::default()).unwrap()
}

#[test]
fn a_cube_tessellates_into_a_closed_mesh_through_its_limit_points() {
    let mesh = shapes::cube();
    let s = surfaces(&mesh);
    for (rate, quads) in [(1, false), (3, false), (3, true), (8, true)] {
        let options = TessellateOptions {
            rate,
            quads,
            normals: true,
            ..TessellateOptions::default()
        };
        let t = tessellate(&mesh, &s, &options).unwrap();
        let r = rate as usize;
        // 8 corners, (r - 1) points inside each of 12 edges, (r - 1)^2 inside each face.
        assert_eq!(t.positions.len(), 8 + 12 * (r - 1) + 6 * (r - 1) * (r - 1));
        let facets_per_face = if quads { r * r } else { 2 * r * r };
        assert_eq!(t.face_offsets.len() - 1, 6 * facets_per_face);
        assert_closed(&t, &format!("cube at rate {rate}"));
        // Normals point outwards on a convex shape centred at the origin.
        assert!(
            t.positions
                .iter()
                .zip(&t.normals)
                .all(|(p, n)| p.dot(*n) > 0.0)
        );
    }
    // The corners are the limit positions of the base vertices.
    let t = tessellate(
        &mesh,
        &s,
        &TessellateOptions {
            rate: 1,
            ..Default::default()
        },
    )
    .unwrap();
    let limit = Refiner::new(&mesh, &Options::default())
        .unwrap()
        .limit_positions(3, &mesh.flat_positions::<f64>())
        .unwrap();
    // Corners get their points in the order the faces first use them.
    let mut order = Vec::new();
    for &v in &mesh.face_vertices {
        if !order.contains(&v) {
            order.push(v);
        }
    }
    assert_eq!(t.positions.len(), order.len());
    for (p, &b) in t.positions.iter().zip(&order) {
        let b = b as usize;
        let expected = [limit[3 * b], limit[3 * b + 1], limit[3 * b + 2]];
        for k in 0..3 {
            assert!(
                (p[k] - expected[k]).abs() < 1e-12,
                "vertex {b}: {p:?} vs {expected:?}"
            );
        }
    }
}
