//! Migration guide (docs/MIGRATING.md), "Checking your migration":
//! `subdiv::compare::compare` on the native engine against the OpenSubdiv
//! bridge, the library form of `subdiv compare`.
//!
//! Run with `cargo run --example migrate_compare` (the comparison needs the
//! `osd` feature; without it the example only refines natively).

use subdiv::{Engine, Error, Options, Request, shapes};

fn main() -> Result<(), Error> {
    let mut mesh = shapes::cube_with_uvs();
    mesh.add_crease(0, 1, 1.5);
    mesh.add_corner(6, 10.0);
    let options = Options::shape_file_defaults();
    // One request (level 3, f64, limits) for either engine.
    let request = Request::new(3).limit(true);
    let native = Engine::Native.refine(&mesh, &options, request)?;
    println!(
        "native: level 3 has {} vertices; limit evaluated: {}",
        native.last_level().vertex_count,
        native.limit.is_some()
    );

    #[cfg(feature = "osd")]
    {
        // [compare]
        let osd = Engine::Osd.refine(&mesh, &options, request)?;
        for level in subdiv::compare::compare(&native, &osd) {
            println!(
                "level {}: topology equal {}, max position deviation {:e} (relative {:e}), \
                 face-varying {:e}, limit {:?}",
                level.level,
                level.topology_equal(),
                level.max_position_deviation,
                level.relative_position_deviation,
                level.max_fvar_deviation,
                level.limit_deviation
            );
            assert!(level.agrees(1e-12));
        }
        // [end]
        assert!(
            subdiv::compare::compare(&native, &osd)
                .iter()
                .all(|l| l.agrees(0.0))
        );
        println!("native == OpenSubdiv at every level, limit included: bit for bit");
    }
    #[cfg(not(feature = "osd"))]
    println!("(built without the `osd` feature: the OpenSubdiv comparison is skipped)");
    Ok(())
}
