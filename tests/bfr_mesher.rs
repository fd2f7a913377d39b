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

/// Watertight on open meshes too, through the per-face surfaces the CLI
/// uses: on every corpus shape (boundaries, holes, a fin, a bowtie,
/// inconsistent winding, n-gons, creases) at uniform rates, each base
/// edge's `rate` pieces are used by exactly as many facets as the edge
/// has tessellated faces — once along a boundary or a hole, twice inside,
/// three times along the fin — and every edge inside a face twice: no
/// crack, no T-junction, no point duplicated along an edge.
#[test]
fn open_meshes_tessellate_without_cracks() {
    use subdiv::BoundaryInterpolation;
    use subdiv::bfr::MeshSurfaces;
    let options = Options::default().with_boundary(BoundaryInterpolation::EdgeOnly);
    let mut checked = 0;
    for (name, mesh) in shapes::corpus() {
        let options = if mesh.faces().all(|f| f.len() == 3) && name.starts_with("tri") {
            options.with_scheme(subdiv::Scheme::Loop)
        } else {
            options
        };
        let s = MeshSurfaces::new(&mesh, &options, &SurfaceOptions::default())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        for (rate, quads) in [(1, false), (3, false), (4, true)] {
            let t = tessellate(
                &mesh,
                &s,
                &TessellateOptions {
                    rate,
                    quads,
                    ..TessellateOptions::default()
                },
            )
            .unwrap();
            let label = format!("{name} rate {rate} quads {quads}");
            // The base faces tessellated, and their edges' face counts
            // (a face with a vertex twice, which folds onto its own edges,
            // left out with its facets).
            let degenerate = |f: u32| {
                let fv = mesh.face(f as usize);
                (1..fv.len()).any(|i| fv[..i].contains(&fv[i]))
            };
            let mut faces: Vec<u32> = t.facet_faces.to_vec();
            faces.dedup();
            faces.retain(|&f| !degenerate(f));
            let mut base: HashMap<(u32, u32), usize> = HashMap::new();
            for &f in &faces {
                let fv = mesh.face(f as usize);
                for i in 0..fv.len() {
                    let (a, b) = (fv[i], fv[(i + 1) % fv.len()]);
                    *base.entry((a.min(b), a.max(b))).or_insert(0) += 1;
                }
            }
            let mut uses: HashMap<(u32, u32), usize> = HashMap::new();
            for (k, w) in t.face_offsets.windows(2).enumerate() {
                if degenerate(t.facet_faces[k]) {
                    continue;
                }
                let f = &t.face_vertices[w[0] as usize..w[1] as usize];
                for i in 0..f.len() {
                    let (a, b) = (f[i], f[(i + 1) % f.len()]);
                    *uses.entry((a.min(b), a.max(b))).or_insert(0) += 1;
                }
            }
            // Pieces of the tessellation used k times, against base edges
            // with k faces (k = 2 also counts the edges inside faces).
            let count = |map: &HashMap<(u32, u32), usize>, k: usize| {
                map.values().filter(|&&n| n == k).count()
            };
            let most = base.values().copied().max().unwrap_or(0);
            assert!(uses.values().all(|&n| n <= most.max(2)), "{label}");
            for k in (1..=most).filter(|&k| k != 2) {
                assert_eq!(
                    count(&uses, k),
                    rate as usize * count(&base, k),
                    "{label}: pieces used {k} times"
                );
            }
            checked += 1;
        }
    }
    assert!(checked > 100, "{checked}");
}
