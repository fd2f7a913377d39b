//! Migration guide (docs/MIGRATING.md), row 9:
//! `TopologyRefiner::RefineAdaptive(AdaptiveOptions)` → `Refiner::refine_adaptive`,
//! with the parent/child queries of `Far::TopologyLevel` and `Far::PtexIndices`.
//!
//! Refines a creased cube feature-adaptively, walks a face's children, and
//! interpolates positions level by level; with the `osd` feature, the same
//! calls on OpenSubdiv give identical levels, maps and positions (bit for bit).
//!
//! Run with `cargo run --example migrate_refine_adaptive`.

use subdiv::refiner::Refiner;
use subdiv::{AdaptiveOptions, Error, INVALID_INDEX, Options, PtexIndices, shapes};

fn main() -> Result<(), Error> {
    let mut mesh = shapes::cube();
    mesh.add_crease(0, 1, 2.0);

    // [refine-adaptive]
    let refiner = Refiner::new(&mesh, &Options::default())?;
    let ptex = PtexIndices::new(&refiner)?; // Far::PtexIndices(*refiner)
    let adaptive = refiner.refine_adaptive(
        AdaptiveOptions::new(4) // AdaptiveOptions(4)
            .single_crease_patch(true), // useSingleCreasePatch = true
        &[], // selectedFaces: all
    )?;
    let maps = adaptive.child_maps(2)?; // level 2's GetFaceChildFaces, ...
    let positions = adaptive.refine_positions(&mesh.positions)?; // PrimvarRefiner::Interpolate
    // [end]
    println!("ptex faces: {}", ptex.num_faces());
    for level in 0..=adaptive.max_level() {
        let c = adaptive.level_counts(level)?;
        println!(
            "level {level}: {} vertices, {} edges, {} faces",
            c.vertices, c.edges, c.faces
        );
    }
    let refined = maps
        .face_child_faces
        .iter()
        .filter(|&&c| c != INVALID_INDEX)
        .count();
    println!(
        "level 2 -> 3: {refined} child faces of {} corners",
        maps.face_child_faces.len()
    );
    assert_eq!(positions.len() as u32, adaptive.max_level() + 1);
    assert!(refined < maps.face_child_faces.len()); // sparse

    #[cfg(feature = "osd")]
    {
        let mut theirs = subdiv::osd::TopologyRefiner::new(&mesh, &Options::default())?;
        theirs.refine_adaptive(AdaptiveOptions::new(4).single_crease_patch(true), &[])?;
        assert_eq!(theirs.max_level(), adaptive.max_level());
        assert_eq!(theirs.ptex_indices()?.num_faces(), ptex.num_faces());
        let mut flat: Vec<f64> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
        for level in 1..=adaptive.max_level() {
            assert_eq!(
                theirs.level(level)?.face_vertices,
                adaptive.level(level)?.face_vertices
            );
            flat = theirs.interpolate(level, 3, &flat)?;
            let ours: Vec<f64> = positions[level as usize]
                .iter()
                .flat_map(|p| p.to_array())
                .collect();
            assert_eq!(flat, ours, "level {level}");
        }
        assert_eq!(theirs.child_maps(2)?, maps);
        println!("OpenSubdiv: identical levels, child maps and positions");
    }
    Ok(())
}
