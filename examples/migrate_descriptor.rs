//! Migration guide (docs/MIGRATING.md), row 1: `Far::TopologyDescriptor` →
//! `subdiv::Mesh`.
//!
//! Builds OpenSubdiv's tutorial cube from the same flat arrays a
//! `TopologyDescriptor` points to, adds a crease, a corner, a hole and a UV
//! channel, validates it, shows what happens to bad input, and reads
//! clockwise faces as `isLeftHanded` does. With the `osd` feature, both engines refine the mesh and
//! must agree bit for bit.
//!
//! Run with `cargo run --example migrate_descriptor`.

use glam::DVec3;
use subdiv::refiner::Refiner;
use subdiv::{FVarChannel, Mesh, MeshError, MeshWarning, Options, UniformOptions};

// [descriptor-fn]
/// The arrays of a `Far::TopologyDescriptor`, as a `Mesh`: `positions` are
/// your vertex data (numVertices = their count), `num_verts_per_face` is
/// numVertsPerFace (numFaces = its length), `vert_indices_per_face` is
/// vertIndicesPerFace.
fn mesh_from_descriptor(
    positions: Vec<DVec3>,
    num_verts_per_face: &[u32],
    vert_indices_per_face: &[u32],
) -> Mesh {
    let mut mesh = Mesh {
        positions,
        ..Mesh::default()
    };
    let mut start = 0;
    for &n in num_verts_per_face {
        mesh.add_face(&vert_indices_per_face[start..start + n as usize]);
        start += n as usize;
    }
    mesh
}
// [end]

/// The tutorial cube written clockwise, as a left-handed application keeps
/// it: each face's first corner, then its other corners in reverse order.
fn clockwise(mesh: &Mesh) -> Mesh {
    let mut left = mesh.clone();
    for w in mesh.face_offsets.windows(2) {
        left.face_vertices[w[0] as usize + 1..w[1] as usize].reverse();
    }
    left
}

/// The cube of OpenSubdiv's `far_tutorial_0`.
fn tutorial_cube() -> Mesh {
    // [descriptor-use]
    let positions = vec![
        DVec3::new(-0.5, -0.5, 0.5),
        DVec3::new(0.5, -0.5, 0.5),
        DVec3::new(-0.5, 0.5, 0.5),
        DVec3::new(0.5, 0.5, 0.5),
        DVec3::new(-0.5, 0.5, -0.5),
        DVec3::new(0.5, 0.5, -0.5),
        DVec3::new(-0.5, -0.5, -0.5),
        DVec3::new(0.5, -0.5, -0.5),
    ];
    let verts_per_face = [4, 4, 4, 4, 4, 4];
    let vert_indices = [
        0, 1, 3, 2, 2, 3, 5, 4, 4, 5, 7, 6, 6, 7, 1, 0, 1, 7, 5, 3, 6, 0, 2, 4,
    ];
    let mesh = mesh_from_descriptor(positions, &verts_per_face, &vert_indices);
    // [end]
    mesh
}

/// Limit normals (`du × dv`) at the vertices of level 2, and the positions.
fn limit_normals(mesh: &Mesh) -> Result<(Vec<DVec3>, Vec<DVec3>), subdiv::Error> {
    let mut refiner = Refiner::new(mesh, &Options::default())?;
    refiner.refine_uniform(UniformOptions::new(2).full_topology(true))?;
    let base: Vec<f64> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
    let last = refiner.interpolate_all(3, &base)?.pop().expect("level 2");
    let limit = refiner.limit(3, &last)?;
    let v = |s: &[f64]| -> Vec<DVec3> { s.chunks_exact(3).map(DVec3::from_slice).collect() };
    let normals = v(&limit.du)
        .into_iter()
        .zip(v(&limit.dv))
        .map(|(du, dv)| du.cross(dv))
        .collect();
    Ok((v(&limit.positions), normals))
}

fn main() -> Result<(), subdiv::Error> {
    let mut mesh = tutorial_cube();

    // [tags]
    // creaseVertexIndexPairs + creaseWeights
    let crease_pairs = [0, 1, 1, 3];
    let crease_weights = [2.5, 2.5];
    for (pair, &w) in crease_pairs.chunks_exact(2).zip(&crease_weights) {
        mesh.add_crease(pair[0], pair[1], w);
    }
    // cornerVertexIndices + cornerWeights
    mesh.add_corner(7, 10.0); // >= 10 is infinitely sharp (SHARPNESS_INFINITE)
    // holeIndices
    mesh.holes = vec![4];
    // fvarChannels[0]: numValues and valueIndices -- and, unlike the
    // descriptor, the values themselves (numValues = values.len() / width).
    mesh.fvar_channels.push(FVarChannel {
        width: 2,
        values: vec![
            0.375, 0.0, 0.625, 0.0, 0.375, 0.25, 0.625, 0.25, 0.375, 0.5, 0.625, 0.5, 0.375, 0.75,
            0.625, 0.75, 0.375, 1.0, 0.625, 1.0, 0.875, 0.0, 0.875, 0.25, 0.125, 0.0, 0.125, 0.25,
        ],
        indices: vec![
            0, 1, 3, 2, 2, 3, 5, 4, 4, 5, 7, 6, 6, 7, 9, 8, 1, 10, 11, 3, 12, 0, 2, 13,
        ],
    });
    // [end]

    // [validate]
    let validation = mesh.validate()?; // Err(MeshError) names the face, corner and index
    for warning in &validation.warnings {
        eprintln!("warning: {warning}");
    }
    // [end]
    assert!(validation.warnings.is_empty());
    println!(
        "descriptor cube: {} vertices, {} faces, {} creases, {} corner, hole {:?}, {} UV values",
        mesh.vertex_count(),
        mesh.face_count(),
        mesh.creases.len(),
        mesh.corners.len(),
        mesh.holes,
        mesh.fvar_channels[0].value_count()
    );

    // Bad input that OpenSubdiv does not check (an out-of-range face-vertex
    // index) or only warns about (an out-of-range corner) is an error here.
    let mut bad = mesh.clone();
    bad.face_vertices[5] = 8;
    assert_eq!(
        bad.validate(),
        Err(MeshError::VertexOutOfRange {
            face: 1,
            corner: 1,
            index: 8,
            count: 8
        })
    );
    println!("out-of-range index: {}", bad.validate().unwrap_err());
    let mut bad = mesh.clone();
    bad.add_corner(99, 1.0);
    assert!(matches!(
        bad.validate(),
        Err(MeshError::CornerVertexOutOfRange { vertex: 99, .. })
    ));
    // A crease between two vertices that share no edge: a warning in both
    // libraries (OpenSubdiv ignores it), an error with `validate_strict`.
    let mut diagonal = mesh.clone();
    diagonal.add_crease(0, 3, 1.0);
    let warnings = diagonal.validate()?.warnings;
    assert!(matches!(
        warnings[..],
        [MeshWarning::CreaseWithoutEdge {
            crease: 2,
            v0: 0,
            v1: 3
        }]
    ));
    assert!(diagonal.validate_strict().is_err());
    println!("crease on a diagonal: warning \"{}\"", warnings[0]);

    // isLeftHanded: clockwise faces.
    let right = tutorial_cube();
    let mut left = clockwise(&right);
    let (points, inward) = limit_normals(&left)?; // clockwise taken as counter-clockwise
    assert!(points.iter().zip(&inward).all(|(p, n)| p.dot(*n) < 0.0));
    // [left-handed]
    left.left_handed = true; // desc.isLeftHanded = true
    // [end]
    assert_eq!(*left.right_handed(), right); // how both engines read it
    let (points, outward) = limit_normals(&left)?;
    assert!(points.iter().zip(&outward).all(|(p, n)| p.dot(*n) > 0.0));
    println!(
        "left-handed input: {} limit normals point inward as given, outward with left_handed",
        points.len()
    );
    #[cfg(feature = "osd")]
    {
        let uniform = UniformOptions::new(2);
        let options = Options::default();
        let native = subdiv::refiner::refine(&left, &options, uniform)?;
        assert_eq!(native, subdiv::osd::refine(&left, &options, uniform)?);
        assert_eq!(native, subdiv::osd::refine(&right, &options, uniform)?);
    }

    #[cfg(feature = "osd")]
    {
        // Both engines, same mesh: identical topology, positions and UVs.
        let uniform = UniformOptions::new(3);
        let options = Options::shape_file_defaults();
        let native = subdiv::refiner::refine(&mesh, &options, uniform)?;
        let osd = subdiv::osd::refine(&mesh, &options, uniform)?;
        assert_eq!(native, osd);
        println!(
            "level 3: {} vertices, {} faces ({} holes), {} UV values: native == OpenSubdiv bit for bit",
            native.last_level().vertex_count,
            native.last_level().face_count(),
            native
                .last_level()
                .face_holes
                .iter()
                .filter(|&&h| h)
                .count(),
            native.last_level().fvar[0].value_count
        );
    }
    #[cfg(not(feature = "osd"))]
    println!("(built without the `osd` feature: the OpenSubdiv comparison is skipped)");
    Ok(())
}
