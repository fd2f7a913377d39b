//! Migration guide (docs/MIGRATING.md), row 4:
//! `TopologyRefiner::RefineUniform(UniformOptions)` → `Refiner::refine_uniform`.
//!
//! Shows both child-vertex orders and the last level's reduced topology, the
//! level limit, and re-refinement; with the `osd` feature, every combination
//! of the two flags gives the same topology in both engines.
//!
//! Run with `cargo run --example migrate_refine_uniform`.

use glam::DVec3;
use subdiv::refiner::Refiner;
use subdiv::{Error, MAX_LEVEL, Options, UniformOptions, shapes};

fn main() -> Result<(), Error> {
    let mesh = shapes::cube();

    // [refine-uniform]
    let mut refiner = Refiner::new(&mesh, &Options::default())?;
    refiner.refine_uniform(
        UniformOptions::new(2) // UniformOptions(2)
            .faces_first(true) // orderVerticesFromFacesFirst = true
            .full_topology(true), // fullTopologyInLastLevel = true
    )?;
    assert_eq!(refiner.max_level(), 2); // GetMaxLevel()
    // [end]
    let level2 = refiner.level(2)?;
    assert_eq!(level2.edge_vertices.len(), level2.edge_count); // full topology
    println!(
        "level 2 with full topology: {} vertices, {} edges (all with their vertices), {} faces",
        level2.vertex_count,
        level2.edge_count,
        level2.face_count()
    );

    // Child vertex order. Default: children of vertices, then of faces, then
    // of edges. Faces first: faces, edges, vertices.
    let level1 = |uniform: UniformOptions| -> Result<Vec<DVec3>, Error> {
        let mut r = Refiner::new(&mesh, &Options::default())?;
        r.refine_uniform(uniform)?;
        Ok(r.refine_positions(&mesh.positions)?.swap_remove(1))
    };
    let centroid = |f: usize| -> DVec3 {
        let face = mesh.face(f);
        face.iter()
            .map(|&v| mesh.positions[v as usize])
            .sum::<DVec3>()
            / face.len() as f64
    };
    let default_order = level1(UniformOptions::new(1))?;
    let faces_first = level1(UniformOptions::new(1).faces_first(true))?;
    for f in 0..mesh.face_count() {
        assert_eq!(faces_first[f], centroid(f)); // vertices 0..6: face points
        assert_eq!(default_order[mesh.vertex_count() + f], centroid(f)); // after the 8 vertex points
    }
    assert_eq!(faces_first[6..18], default_order[14..26]); // the 12 edge points
    assert_eq!(faces_first[18..26], default_order[0..8]); // the 8 vertex points
    println!(
        "level 1, default order: vertex points 0..8, face points 8..14, edge points 14..26; \
         faces first: face points 0..6"
    );

    // Without full topology the last level has no edge-vertex table (like
    // OpenSubdiv, which skips it); the counts are still there.
    refiner.refine_uniform(UniformOptions::new(2))?; // replaces the earlier refinement
    let last = refiner.level(2)?;
    assert!(last.edge_vertices.is_empty());
    assert_eq!(last.edge_count, 192);
    assert!(refiner.limit(3, &[0.0; 98 * 3]).is_err()); // limit needs full topology
    println!(
        "level 2 without full topology: edge count {}, no edge vertices",
        last.edge_count
    );

    // [max-level]
    match refiner.refine_uniform(UniformOptions::new(16)) {
        Err(Error::Level { level, reason }) => println!("level {level} refused: {reason}"),
        other => panic!("expected a level error, got {other:?}"),
    }
    // [end]
    assert_eq!(MAX_LEVEL, 10);
    assert!(
        refiner
            .refine_uniform(UniformOptions::new(MAX_LEVEL + 1))
            .is_err()
    );

    #[cfg(feature = "osd")]
    {
        for faces_first in [false, true] {
            for full in [false, true] {
                let uniform = UniformOptions::new(3)
                    .faces_first(faces_first)
                    .full_topology(full);
                let mut native = Refiner::new(&mesh, &Options::default())?;
                native.refine_uniform(uniform)?;
                let mut osd = subdiv::osd::TopologyRefiner::new(&mesh, &Options::default())?;
                osd.refine_uniform(uniform)?;
                for l in 0..=3 {
                    assert_eq!(native.level(l)?, osd.level(l)?, "{uniform:?} level {l}");
                }
                let base: Vec<f64> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
                assert_eq!(
                    native.interpolate_all(3, &base)?,
                    osd.interpolate_all(3, &base)?
                );
            }
        }
        println!("faces-first × full-topology: native == OpenSubdiv at every level, bit for bit");
    }
    #[cfg(not(feature = "osd"))]
    println!("(built without the `osd` feature: the OpenSubdiv comparison is skipped)");
    Ok(())
}
