//! Migration guide (docs/MIGRATING.md), section 12: a USD renderer's
//! subdivision (`UsdGeomMesh` → `PxOsdMeshTopology` → OpenSubdiv) →
//! `subdiv::io::usd`.
//!
//! Writes a small stage (a creased, holed, left-handed quad grid with an
//! indexed `st` and one unsubdivided prim), reads it with `read_usd`, checks
//! the options USD's fallbacks give, refines every mesh and writes the result
//! back as a `.usda` layer. With the `osd` feature, both engines refine each
//! prim and must agree bit for bit.
//!
//! Run with `cargo run --example migrate_usd`.

#[cfg(feature = "usd")]
fn main() -> Result<(), Box<dyn std::error::Error>> {
    use subdiv::io::usd::{UsdMeshOut, UsdReadOptions, read_usd, write_usda};
    use subdiv::{BoundaryInterpolation, Engine, FVarLinearInterpolation, Precision, Request};

    let dir = tempfile::tempdir()?;
    let path = dir.path().join("scene.usda");
    std::fs::write(&path, STAGE)?;

    // [read]
    let stage = read_usd(&path, &UsdReadOptions::default())?;
    for skipped in &stage.skipped {
        println!("{}: {}", skipped.prim, skipped.reason); // subdivisionScheme = "none"
    }
    for warning in &stage.warnings {
        eprintln!("warning: {warning}");
    }
    let mut refined = Vec::new();
    for usd_mesh in &stage.meshes {
        // usd_mesh.options: the prim's tokens, USD's fallbacks where unauthored
        let r = Engine::Native.refine(&usd_mesh.mesh, &usd_mesh.options, Request::new(2))?;
        refined.push((usd_mesh, r));
    }
    let layer: Vec<UsdMeshOut<'_>> = refined
        .iter()
        .map(|(m, r)| UsdMeshOut::from_refinement(&m.path, r, &m.fvar_names))
        .collect();
    write_usda(&dir.path().join("refined.usda"), &layer, Precision::F64)?;
    // [end]

    assert_eq!(stage.skipped.len(), 1);
    let grid = &stage.meshes[0];
    assert_eq!(grid.path, "/World/Grid");
    // Unauthored: USD's fallbacks, not OpenSubdiv's shape-file conventions.
    assert_eq!(grid.options.boundary, BoundaryInterpolation::EdgeAndCorner);
    assert_eq!(grid.options.fvar, FVarLinearInterpolation::CornersPlus1);
    assert!(grid.mesh.left_handed);
    assert_eq!(grid.mesh.creases.len(), 2, "one crease chain of two edges");
    assert_eq!(grid.mesh.holes, vec![3]);
    assert_eq!(grid.fvar_names, vec!["st".to_string()]);
    let (_, r) = &refined[0];
    println!(
        "{}: level 2: {} vertices, {} faces, {} st values",
        grid.path,
        r.last_level().vertex_count,
        r.last_level().face_count(),
        r.last_fvar(0).map_or(0, |v| v.len() / 2)
    );
    let back = read_usd(&dir.path().join("refined.usda"), &UsdReadOptions::default())?;
    assert!(
        back.meshes.is_empty(),
        "refined meshes are not subdivided again"
    );
    assert_eq!(back.skipped.len(), 1);

    #[cfg(feature = "osd")]
    for (m, native) in &refined {
        let osd = Engine::Osd.refine(&m.mesh, &m.options, Request::new(2))?;
        assert_eq!(*native, osd, "{}", m.path);
        println!("{}: native == OpenSubdiv bit for bit", m.path);
    }
    Ok(())
}

#[cfg(not(feature = "usd"))]
fn main() {
    println!("migrate_usd needs the `usd` feature (on by default)");
}

/// A 3×3 grid written clockwise (`leftHanded`), a crease chain, a hole and
/// an indexed `st` with a seam; and a prim that is not subdivided.
#[cfg(feature = "usd")]
const STAGE: &str = r#"#usda 1.0
def Xform "World" {
    def Mesh "Grid" {
        uniform token orientation = "leftHanded"
        point3f[] points = [(0,0,0), (1,0,0), (2,0,0), (3,0,0), (0,1,0), (1,1,0.5), (2,1,0.5), (3,1,0),
                            (0,2,0), (1,2,0.5), (2,2,0.5), (3,2,0), (0,3,0), (1,3,0), (2,3,0), (3,3,0)]
        int[] faceVertexCounts = [4, 4, 4, 4, 4, 4, 4, 4, 4]
        int[] faceVertexIndices = [0, 4, 5, 1,  1, 5, 6, 2,  2, 6, 7, 3,
                                   4, 8, 9, 5,  5, 9, 10, 6,  6, 10, 11, 7,
                                   8, 12, 13, 9,  9, 13, 14, 10,  10, 14, 15, 11]
        int[] creaseIndices = [5, 6, 10]
        int[] creaseLengths = [3]
        float[] creaseSharpnesses = [2.5]
        int[] holeIndices = [3]
        texCoord2f[] primvars:st = [(0,0), (1,0), (1,1), (0,1), (0.5,0.5)] (interpolation = "faceVarying")
        int[] primvars:st:indices = [0, 3, 2, 1,  0, 3, 2, 1,  0, 3, 2, 1,
                                     0, 3, 2, 1,  0, 3, 4, 1,  0, 3, 2, 1,
                                     0, 3, 2, 1,  0, 3, 2, 1,  0, 3, 2, 1]
    }
    def Mesh "Card" {
        uniform token subdivisionScheme = "none"
        point3f[] points = [(0,0,1), (1,0,1), (1,1,1), (0,1,1)]
        int[] faceVertexCounts = [4]
        int[] faceVertexIndices = [0, 1, 2, 3]
    }
}
"#;
