//! Refine a creased cube with OpenSubdiv through the bridge, then print the
//! first refined vertices and the stencil of one of them.
//!
//! Run with `cargo run --example osd_refine`.

use subdiv::{Options, UniformOptions, osd, shapes};

fn main() -> Result<(), subdiv::Error> {
    let mut cube = shapes::cube();
    cube.add_crease(0, 1, 2.0); // a semi-sharp edge
    cube.add_corner(6, 10.0); // an infinitely sharp corner

    // One call: topology of every level plus interpolated positions.
    let refined = osd::refine(
        &cube,
        &Options::shape_file_defaults(),
        UniformOptions::new(2),
    )?;
    let last = refined.last_level();
    println!(
        "level 2: {} vertices, {} faces",
        last.vertex_count,
        last.face_count()
    );
    for (i, p) in refined.last_positions().iter().take(4).enumerate() {
        println!("  v{i} = {p:.6}");
    }

    // The same through the refiner handle: refine once, interpolate many frames.
    let mut refiner = osd::TopologyRefiner::new(&cube, &Options::shape_file_defaults())?;
    refiner.refine_uniform(UniformOptions::new(2))?;
    let stencils = refiner.stencil_table()?;
    let (indices, weights) = stencils.row(0);
    println!("stencil of v0: {indices:?} with weights {weights:?}");
    Ok(())
}
