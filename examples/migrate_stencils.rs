//! Migration guide (docs/MIGRATING.md), row 7: `Far::StencilTableFactory`
//! (+ `UpdateValues`, `Osd::CpuEvaluator::EvalStencils`) →
//! `Refiner::stencil_table` → `StencilTable::apply` / `apply_par`, and
//! `Refiner::stencil_table_f32` → `StencilTableF32::apply_into`, and
//! `StencilTableFactory::Options` → `Refiner::stencil_table_with`.
//!
//! Builds the table once, animates a few frames with it, and checks it
//! against refining level by level; with the `osd` feature, against
//! OpenSubdiv's own table and its `CpuEvaluator`.
//!
//! Run with `cargo run --example migrate_stencils`.

use subdiv::refiner::Refiner;
use subdiv::{Error, Options, UniformOptions, shapes};

/// Row `r` as a map from base vertex to weight (the order of a row's terms is
/// not part of the contract).
#[cfg(feature = "osd")]
fn row_map(table: &subdiv::StencilTable, r: usize) -> std::collections::BTreeMap<u32, f64> {
    let mut map = std::collections::BTreeMap::new();
    let (indices, weights) = table.row(r);
    for (&i, &w) in indices.iter().zip(weights) {
        *map.entry(i).or_insert(0.0) += w;
    }
    map
}

fn main() -> Result<(), Error> {
    let mut mesh = shapes::torus(8, 6);
    mesh.add_crease(0, 1, 2.0);
    let options = Options::default();

    // [stencils]
    let mut refiner = Refiner::new(&mesh, &options)?;
    refiner.refine_uniform(UniformOptions::new(3))?;
    // StencilTableFactory::Create with generateIntermediateLevels = false:
    // one stencil per vertex of the last level, over the base vertices.
    let table = refiner.stencil_table()?;
    let (indices, weights) = table.row(0); // GetStencil(0): GetVertexIndices(), GetWeights()
    // [end]
    println!(
        "{} stencils over {} base vertices, {} weights; stencil 0: {} terms",
        table.len(),
        mesh.vertex_count(),
        table.weights.len(),
        indices.len()
    );
    assert_eq!(table.len(), refiner.level(3)?.vertex_count);
    assert!((weights.iter().sum::<f64>() - 1.0).abs() < 1e-12);

    let base: Vec<f64> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
    let refined = refiner.interpolate_all(3, &base)?.pop().expect("level 3");
    let table32 = refiner.stencil_table_f32()?; // a float StencilTable
    let mut frame32 = vec![0.0f32; table.len() * 3];
    for frame in 0..3 {
        let t = frame as f64 * 0.1;
        let moved: Vec<f64> = base
            .chunks_exact(3)
            .flat_map(|p| [p[0] + t, p[1] * (1.0 + t), p[2]])
            .collect();
        // [apply]
        let out = table.apply(3, &moved)?; // UpdateValues(src, dst)
        let out_par = table.apply_par(3, &moved)?; // the same, on rayon's pool
        let moved32: Vec<f32> = moved.iter().map(|&x| x as f32).collect();
        table32.apply_into(3, &moved32, &mut frame32)?; // EvalStencils into a float buffer
        // [end]
        assert_eq!(out, out_par);
        assert!(
            out.iter()
                .zip(&frame32)
                .all(|(a, &b)| (a - b as f64).abs() < 1e-5)
        );
        if frame == 0 {
            // Applying the stencils equals refining level by level (to rounding).
            let d = out
                .iter()
                .zip(&refined)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(d < 1e-12, "{d}");
            println!("frame 0: stencils vs level-by-level refinement: max difference {d:.1e}");
        }
    }
    println!("3 frames: apply == apply_par bit for bit; f32 path within 1e-5");

    #[cfg(feature = "osd")]
    {
        let mut osd = subdiv::osd::TopologyRefiner::new(&mesh, &options)?;
        osd.refine_uniform(UniformOptions::new(3))?;
        let theirs = osd.stencil_table()?; // StencilTableFactoryReal<double>
        assert_eq!(theirs.len(), table.len());
        for r in 0..table.len() {
            let (a, b) = (row_map(&table, r), row_map(&theirs, r));
            assert!(
                a.keys().eq(b.keys()),
                "stencil {r}: different base vertices"
            );
            assert!(
                a.values()
                    .zip(b.values())
                    .all(|(x, y)| (x - y).abs() <= 1e-12)
            );
        }
        // OpenSubdiv's production path: a float StencilTable applied by
        // Osd::CpuEvaluator::EvalStencils.
        let evaluator = subdiv::osd::StencilEvaluator::new(&osd)?;
        let base32: Vec<f32> = base.iter().map(|&x| x as f32).collect();
        let osd_frame = evaluator.eval(3, &base32)?;
        table32.apply_into(3, &base32, &mut frame32)?;
        // Same terms in the same order, weights computed in f32 as
        // OpenSubdiv's float factory computes them: the same bits.
        assert_eq!(osd_frame, frame32);
        println!(
            "stencil tables: native == OpenSubdiv row by row (weights within 1e-12); \
             f32 frame == CpuEvaluator::EvalStencils bit for bit"
        );
    }
    face_varying_table()?;
    #[cfg(not(feature = "osd"))]
    println!("(built without the `osd` feature: the OpenSubdiv comparison is skipped)");
    Ok(())
}

/// `StencilTableFactory::Options`: a face-varying table of every level with
/// the control values, applied to the UVs of a cube; with `osd`, identical to
/// OpenSubdiv's (indices and weights bit for bit).
fn face_varying_table() -> Result<(), Error> {
    use subdiv::stencil::StencilOptions;
    let mesh = shapes::cube_with_uvs();
    let options = Options::default();
    // [stencil-options]
    let mut refiner = Refiner::new(&mesh, &options)?;
    refiner.refine_uniform(UniformOptions::new(2))?;
    let uv_options = StencilOptions::new()
        .face_varying(0) // interpolationMode = INTERPOLATE_FACE_VARYING, fvarChannel = 0
        .control_vertices(true) // generateControlVerts = true
        .intermediate_levels(true); // generateIntermediateLevels = true (the default)
    let uv_table = refiner.stencil_table_with(&uv_options)?; // StencilTableFactory::Create(*refiner, options)
    let uv = &mesh.fvar_channels[0];
    let all_uvs = uv_table.apply(uv.width, &uv.values)?; // every level's UVs, level 0 first
    // [end]
    let mut levels = vec![uv.values.clone()];
    for level in 1..=2 {
        let next =
            refiner.interpolate_face_varying(0, level, uv.width, &levels[level as usize - 1])?;
        levels.push(next);
    }
    let by_level = levels.concat();
    assert_eq!(all_uvs.len(), by_level.len());
    let d = all_uvs
        .iter()
        .zip(&by_level)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(d < 1e-12, "{d}");
    println!(
        "face-varying table: {} rows (UVs of levels 0-2), applied == level by level to {d:.1e}",
        uv_table.len()
    );
    #[cfg(feature = "osd")]
    {
        let mut osd = subdiv::osd::TopologyRefiner::new(&mesh, &options)?;
        osd.refine_uniform(UniformOptions::new(2))?;
        assert_eq!(osd.stencil_table_with(&uv_options)?, uv_table);
        println!("face-varying table: native == OpenSubdiv (indices and weights bit for bit)");
    }
    Ok(())
}
