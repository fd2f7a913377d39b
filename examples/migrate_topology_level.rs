//! Migration guide (docs/MIGRATING.md), row 5: `Far::TopologyLevel` queries →
//! `Refiner::level(l)` → `LevelTopology`.
//!
//! Reads every query `far_tutorial`-style code makes, checks the tables
//! against each other (Euler characteristic, edge lookup), and with the `osd`
//! feature checks that both engines report identical levels.
//!
//! Run with `cargo run --example migrate_topology_level`.

use subdiv::refiner::Refiner;
use subdiv::{Error, LevelTopology, Options, UniformOptions, shapes};

// [fvar-values]
/// `GetFaceFVarValues(f, channel)`: the channel's value indices of face `f`.
fn face_fvar_values(level: &LevelTopology, f: usize, channel: usize) -> &[u32] {
    let corners = level.face_offsets[f] as usize..level.face_offsets[f + 1] as usize;
    &level.fvar[channel].face_values[corners]
}
// [end]

fn main() -> Result<(), Error> {
    let mut mesh = shapes::cube_with_uvs();
    mesh.add_crease(0, 1, 2.0);
    mesh.add_corner(6, 3.0);
    mesh.holes.push(5);
    let mut refiner = Refiner::new(&mesh, &Options::shape_file_defaults())?;
    refiner.refine_uniform(UniformOptions::new(2).full_topology(true))?;

    // [queries]
    let level = refiner.level(1)?; // Far::TopologyLevel const & level = refiner->GetLevel(1);
    let nv = level.vertex_count; // level.GetNumVertices()
    let ne = level.edge_count; // level.GetNumEdges()
    let nf = level.face_count(); // level.GetNumFaces()
    let nfv = level.face_vertices.len(); // level.GetNumFaceVertices()
    let face = level.face(3); // level.GetFaceVertices(3)
    let [v0, v1] = level.edge_vertices[0]; // level.GetEdgeVertices(0)
    let crease = level.edge_sharpness[0]; // level.GetEdgeSharpness(0)
    let corner = level.vertex_sharpness[6]; // level.GetVertexSharpness(6)
    let hole = level.face_holes[20]; // level.IsFaceHole(20)
    let nuv = level.fvar[0].value_count; // level.GetNumFVarValues(0)
    let uvs = face_fvar_values(&level, 3, 0); // level.GetFaceFVarValues(3, 0)
    // [end]
    println!(
        "level 1: {nv} vertices, {ne} edges, {nf} faces, {nfv} face-vertices, {nuv} UV values"
    );
    println!(
        "face 3 = {face:?} (UV indices {uvs:?}); edge 0 = ({v0}, {v1}) sharpness {crease}; \
         vertex 6 sharpness {corner}; face 20 hole: {hole}"
    );
    assert_eq!((nv, ne, nf, nfv), (26, 48, 24, 96));
    assert_eq!(crease, 0.0); // edge 0 of level 1 is a smooth interior edge
    // The crease (2.0 at level 0) loses one per level (uniform creasing): its
    // two child edges have sharpness 1.0.
    assert_eq!(
        level.edge_sharpness.iter().filter(|&&s| s == 1.0).count(),
        2
    );
    assert_eq!(level.edge_sharpness.iter().filter(|&&s| s > 0.0).count(), 2);
    assert_eq!(corner, 2.0); // the child of vertex 6 is vertex 6 (vertex points come first)
    assert!(hole); // children of hole face 5 are faces 20..24
    assert_eq!(face.len(), uvs.len());

    for l in 0..=refiner.max_level() {
        let t = refiner.level(l)?;
        // A closed surface of genus 0: V - E + F = 2 at every level.
        assert_eq!(
            t.vertex_count as i64 - t.edge_count as i64 + t.face_count() as i64,
            2
        );
        // Each face's UV indices are in range of the level's UV values.
        assert!(
            t.fvar[0]
                .face_values
                .iter()
                .all(|&i| (i as usize) < t.fvar[0].value_count)
        );
        println!(
            "level {l}: {} vertices, {} edges, {} faces, {} holes, {} UV values",
            t.vertex_count,
            t.edge_count,
            t.face_count(),
            t.face_holes.iter().filter(|&&h| h).count(),
            t.fvar[0].value_count
        );
    }

    // [relations]
    // The other relations (native engine), level by level through the refiner,
    // which derives them where a level leaves them out (the level before a
    // minimal last level). GetVertexFaces(0), GetVertexEdges(0):
    let (vertex_faces, vertex_edges) = refiner.vertex_faces_and_edges(1, 0)?;
    let edge_faces = refiner.edge_faces(1, 0)?; // GetEdgeFaces(0)
    let face_edges = refiner.face_edges(1, 3)?; // GetFaceEdges(3)
    let edge = refiner.find_edge(1, v0, v1)?; // FindEdge(v0, v1), None for INDEX_INVALID
    let (rule, boundary) = refiner.vertex_rule(1, 0)?; // GetVertexRule(0), IsVertexBoundary(0)
    // [end]
    println!(
        "vertex 0: faces {vertex_faces:?}, edges {vertex_edges:?}, boundary {boundary}, rule {rule:?}; \
         edge 0: faces {edge_faces:?}; face 3: edges {face_edges:?}"
    );
    assert_eq!(edge, Some(0));
    for (e, &[a, b]) in level.edge_vertices.iter().enumerate() {
        assert_eq!(refiner.find_edge(1, a, b)?, Some(e as u32));
        assert_eq!(refiner.find_edge(1, b, a)?, Some(e as u32));
    }
    assert_eq!(vertex_faces.len(), 3); // a cube corner
    assert!(
        vertex_edges
            .iter()
            .all(|&e| level.edge_vertices[e as usize].contains(&0))
    );

    #[cfg(feature = "osd")]
    {
        let mut osd = subdiv::osd::TopologyRefiner::new(&mesh, &Options::shape_file_defaults())?;
        osd.refine_uniform(UniformOptions::new(2).full_topology(true))?;
        for l in 0..=2 {
            assert_eq!(refiner.level(l)?, osd.level(l)?);
        }
        println!("every LevelTopology table: native == OpenSubdiv at levels 0-2");
    }
    #[cfg(not(feature = "osd"))]
    println!("(built without the `osd` feature: the OpenSubdiv comparison is skipped)");
    Ok(())
}
