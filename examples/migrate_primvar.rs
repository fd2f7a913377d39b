//! Migration guide (docs/MIGRATING.md), row 6: `Far::PrimvarRefiner` →
//! `Refiner::interpolate`, `interpolate_varying`, `interpolate_face_varying`,
//! `limit`, `limit_face_varying`.
//!
//! OpenSubdiv's primvar classes (`Clear()` / `AddWithWeight()`) become flat
//! slices of any width, in `f32` or `f64`. The example interpolates positions
//! and colours interleaved (width 7), checks that this equals interpolating
//! them apart, and with the `osd` feature checks every call against
//! OpenSubdiv's `PrimvarRefiner` in both precisions.
//!
//! Run with `cargo run --example migrate_primvar`.

use glam::DVec3;
use subdiv::refiner::Refiner;
use subdiv::{Error, Options, Real, UniformOptions, shapes};

/// A vertex colour per base vertex (RGBA).
fn colour(v: usize) -> [f64; 4] {
    [v as f64 / 8.0, 1.0 - v as f64 / 8.0, (v % 2) as f64, 1.0]
}

// [generic]
/// Refines any primvar of `width` components, in f32 or f64, to the last level.
fn to_last_level<T: Real>(refiner: &Refiner, width: usize, base: &[T]) -> Result<Vec<T>, Error> {
    let mut data = base.to_vec();
    for level in 1..=refiner.max_level() {
        data = refiner.interpolate(level, width, &data)?;
    }
    Ok(data)
}
// [end]

fn main() -> Result<(), Error> {
    let mut mesh = shapes::cube_with_uvs();
    mesh.add_crease(0, 1, 1.5);
    let options = Options::shape_file_defaults();

    let mut refiner = Refiner::new(&mesh, &options)?;
    refiner.refine_uniform(UniformOptions::new(2).full_topology(true))?;

    // [interleaved]
    // struct Vertex { float x, y, z, r, g, b, a; void Clear(); void AddWithWeight(...); }
    // becomes 7 numbers per vertex in one flat slice:
    let width = 7;
    let mut base: Vec<f64> = Vec::with_capacity(mesh.vertex_count() * width);
    for (v, p) in mesh.positions.iter().enumerate() {
        base.extend_from_slice(&p.to_array());
        base.extend_from_slice(&colour(v));
    }
    let level1 = refiner.interpolate(1, width, &base)?; // Interpolate(1, src, dst)
    let level2 = refiner.interpolate(2, width, &level1)?; // Interpolate(2, src, dst)
    // [end]
    assert_eq!(level2.len(), 98 * width);

    // Interleaving changes nothing: each component is interpolated alone.
    let positions: Vec<f64> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
    let colours: Vec<f64> = (0..mesh.vertex_count()).flat_map(colour).collect();
    let p2 = to_last_level(&refiner, 3, &positions)?;
    let c2 = to_last_level(&refiner, 4, &colours)?;
    for v in 0..98 {
        assert_eq!(level2[v * 7..v * 7 + 3], p2[v * 3..v * 3 + 3]);
        assert_eq!(level2[v * 7 + 3..v * 7 + 7], c2[v * 4..v * 4 + 4]);
    }
    println!("width 7 (position + colour) == width 3 and width 4 apart, bit for bit");

    // [all-levels]
    let every_level = refiner.interpolate_all(3, &positions)?; // [level 0, level 1, level 2], f64
    let as_points = refiner.refine_positions(&mesh.positions)?; // Vec<Vec<DVec3>>, per level
    let positions32: Vec<f32> = positions.iter().map(|&x| x as f32).collect();
    let in_f32 = refiner.interpolate_all(3, &positions32)?; // PrimvarRefinerReal<float>
    // [end]
    assert_eq!(every_level[2], p2);
    assert_eq!(as_points[2][5], DVec3::from_slice(&p2[15..18]));
    assert!(
        in_f32[2]
            .iter()
            .zip(&p2)
            .all(|(&a, &b)| (a as f64 - b).abs() < 1e-6)
    );

    // [varying]
    let varying = refiner.interpolate_varying(1, 4, &colours)?; // InterpolateVarying(1, src, dst)
    // [end]
    // Varying data is interpolated linearly: a face point is the average of its face.
    let face0 = mesh.face(0);
    let average: f64 = face0.iter().map(|&v| colour(v as usize)[0]).sum::<f64>() / 4.0;
    assert_eq!(varying[8 * 4], average); // level 1 vertex 8: the point of face 0

    // [face-varying]
    let uv = &mesh.fvar_channels[0];
    // InterpolateFaceVarying(level, src, dst, channel): channel 0, width 2
    let uv1 = refiner.interpolate_face_varying(0, 1, 2, &uv.values)?;
    let uv2 = refiner.interpolate_face_varying(0, 2, 2, &uv1)?;
    // [end]
    assert_eq!(uv2.len(), refiner.level(2)?.fvar[0].value_count * 2);

    // [limit]
    // Needs full topology in the last level, as in OpenSubdiv.
    let limit = refiner.limit(3, &p2)?; // Limit(src, dstPos, dstTan1, dstTan2)
    let (positions_at_limit, du, dv) = (&limit.positions, &limit.du, &limit.dv);
    let positions_only = refiner.limit_positions(3, &p2)?; // Limit(src, dstPos)
    let uv_limit = refiner.limit_face_varying(0, 2, &uv2)?; // LimitFaceVarying(src, dst, 0)
    // [end]
    assert_eq!(&positions_only, positions_at_limit);
    assert_eq!(du.len(), dv.len());
    assert_eq!(uv_limit.len(), uv2.len());
    println!(
        "limit of level-2 vertex 0: {:?}, du {:?}, dv {:?}",
        &positions_at_limit[0..3],
        &du[0..3],
        &dv[0..3]
    );

    #[cfg(feature = "osd")]
    {
        let mut osd = subdiv::osd::TopologyRefiner::new(&mesh, &options)?;
        osd.refine_uniform(UniformOptions::new(2).full_topology(true))?;
        // f64: every call bit for bit.
        assert_eq!(osd.interpolate(1, width, &base)?, level1);
        assert_eq!(osd.interpolate(2, width, &level1)?, level2);
        assert_eq!(osd.interpolate_varying(1, 4, &colours)?, varying);
        assert_eq!(osd.interpolate_face_varying(0, 1, 2, &uv.values)?, uv1);
        assert_eq!(osd.interpolate_face_varying(0, 2, 2, &uv1)?, uv2);
        assert_eq!(osd.limit_face_varying(0, 2, &uv2)?, uv_limit);
        let osd_limit = osd.limit(3, &p2)?;
        let close = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-12);
        assert!(close(&osd_limit.positions, &limit.positions));
        assert!(close(&osd_limit.du, &limit.du));
        assert!(close(&osd_limit.dv, &limit.dv));
        // f32: the same, weights computed in f32 as PrimvarRefinerReal<float> does.
        let base32: Vec<f32> = base.iter().map(|&x| x as f32).collect();
        let native32 = refiner.interpolate_all(width, &base32)?;
        assert_eq!(osd.interpolate_all(width, &base32)?, native32);
        let colours32: Vec<f32> = colours.iter().map(|&x| x as f32).collect();
        assert_eq!(
            osd.interpolate_varying(1, 4, &colours32)?,
            refiner.interpolate_varying(1, 4, &colours32)?
        );
        let uv32: Vec<f32> = uv.values.iter().map(|&x| x as f32).collect();
        assert_eq!(
            osd.interpolate_face_varying(0, 1, 2, &uv32)?,
            refiner.interpolate_face_varying(0, 1, 2, &uv32)?
        );
        let p32: Vec<f32> = native32[2]
            .chunks_exact(7)
            .flat_map(|v| v[0..3].to_vec())
            .collect();
        let (n, o) = (refiner.limit(3, &p32)?, osd.limit(3, &p32)?);
        let close32 = |a: &[f32], b: &[f32]| a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-6);
        assert!(close32(&n.positions, &o.positions) && close32(&n.du, &o.du));
        println!(
            "interpolate, varying, face-varying (f64 and f32), limit face-varying (f64): \
             native == OpenSubdiv bit for bit; limit and tangents within 1e-12 (f64), 1e-6 (f32)"
        );
    }
    #[cfg(not(feature = "osd"))]
    println!("(built without the `osd` feature: the OpenSubdiv comparison is skipped)");
    Ok(())
}
