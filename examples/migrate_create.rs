//! Migration guide (docs/MIGRATING.md), row 3:
//! `TopologyRefinerFactory<TopologyDescriptor>::Create` → `Refiner::new`.
//!
//! Where OpenSubdiv returns a null pointer and reports through the
//! `Far::Error` callback, `Refiner::new` returns a typed `subdiv::Error`.
//! The example feeds both engines the same good and bad meshes: they must
//! accept and refuse the same ones, and build the same base level.
//!
//! Run with `cargo run --example migrate_create`.

use subdiv::refiner::Refiner;
use subdiv::{Error, Mesh, MeshError, Options, Scheme, shapes};

fn main() -> Result<(), Error> {
    let mesh = shapes::cube();
    let options = Options::default();

    // [create]
    let refiner = Refiner::new(&mesh, &options)?; // validates the mesh first
    for warning in refiner.warnings() {
        eprintln!("warning: {warning}"); // what Far's warning callback would print
    }
    // [end]
    assert!(refiner.warnings().is_empty());
    assert_eq!(refiner.max_level(), 0);
    let base = refiner.level(0)?;
    println!(
        "base level: {} vertices, {} edges, {} faces",
        base.vertex_count,
        base.edge_count,
        base.face_count()
    );

    // [errors]
    let mut quads_for_loop = shapes::cube();
    quads_for_loop.add_crease(0, 1, 1.0);
    match Refiner::new(&quads_for_loop, &options.with_scheme(Scheme::Loop)) {
        Ok(_) => unreachable!("Loop needs triangles"),
        Err(Error::NotTriangles { face, corners, .. }) => {
            println!("refused: face {face} has {corners} corners")
        }
        Err(other) => return Err(other),
    }
    let mut bad_index = shapes::cube();
    bad_index.face_vertices[0] = 42;
    match Refiner::new(&bad_index, &options) {
        Err(Error::Mesh(MeshError::VertexOutOfRange { face, corner, .. })) => {
            println!("refused: face {face} corner {corner} names a vertex that does not exist")
        }
        other => panic!("expected an invalid-mesh error, got {other:?}"),
    }
    // [end]

    // Both engines accept and refuse the same meshes.
    let mut diagonal_crease = shapes::cube();
    diagonal_crease.add_crease(0, 2, 1.0); // no such edge: a warning
    let cases: Vec<(&str, Mesh, Options)> = vec![
        ("cube", shapes::cube(), options),
        ("cube, crease on a diagonal", diagonal_crease, options),
        (
            "tetrahedron, Loop",
            shapes::tetrahedron(),
            options.with_scheme(Scheme::Loop),
        ),
        (
            "cube, Loop",
            shapes::cube(),
            options.with_scheme(Scheme::Loop),
        ),
        ("bad vertex index", bad_index, options),
        ("no faces", Mesh::default(), options),
    ];
    for (name, mesh, options) in &cases {
        let native = Refiner::new(mesh, options);
        match &native {
            Ok(r) => println!("{name}: accepted, {} warning(s)", r.warnings().len()),
            Err(e) => println!("{name}: refused ({e})"),
        }
        #[cfg(feature = "osd")]
        {
            let osd = subdiv::osd::TopologyRefiner::new(mesh, options);
            assert_eq!(native.is_ok(), osd.is_ok(), "{name}");
            if let (Ok(n), Ok(o)) = (&native, &osd) {
                assert_eq!(n.level(0)?, o.level(0)?, "{name}");
                assert_eq!(n.warnings().is_empty(), o.warnings().is_empty(), "{name}");
                for w in o.warnings() {
                    println!("    osd engine: {w}");
                }
            }
            if let Err(e) = &osd {
                println!("    osd engine: {e}");
            }
        }
    }
    #[cfg(feature = "osd")]
    println!("both engines accept and refuse the same meshes, with identical base levels");
    #[cfg(not(feature = "osd"))]
    println!("(built without the `osd` feature: the OpenSubdiv comparison is skipped)");
    Ok(())
}
