//! OpenSubdiv's bfr tutorial 1_1, natively: the limit surface of every base
//! face evaluated at its corners and centre and written as a fan of
//! triangles with normals.
//!
//! `cargo run --example bfr_tutorial_1_1 [INPUT.obj] [-o OUT.obj]` (a cube
//! without an input). Every point is checked against OpenSubdiv's
//! `Bfr::Surface::Evaluate` (feature `osd`), and the corners of faces
//! sharing a vertex against each other: the limit surface is continuous.

#[path = "bfr/common.rs"]
mod common;

use std::collections::HashMap;

fn main() {
    let args = common::Args::parse();
    let (mesh, options) = args.mesh();
    let mut surfaces = common::Surfaces::new(&mesh, &options);
    let mut obj = common::Obj::default();
    let mut corner_points: HashMap<u32, glam::DVec3> = HashMap::new();
    for face in 0..mesh.face_count() {
        if !surfaces.native.has_surface(face) {
            continue; // holes (and faces without a limit surface)
        }
        let param = surfaces
            .native
            .parameterization(face)
            .expect("parameterization");
        let n = param.face_size();
        // The corners, then the centre.
        let mut coords: Vec<[f64; 2]> = (0..n).map(|i| param.vertex_coord(i)).collect();
        coords.push(param.center_coord());
        let s = surfaces.evaluate(face, &coords);
        let first = obj.points(&s);
        for (i, &v) in mesh.face(face).iter().enumerate() {
            let p = obj.positions[first as usize + i];
            let seen = *corner_points.entry(v).or_insert(p);
            assert!((seen - p).length() < 1e-12, "vertex {v}: faces disagree");
        }
        let fan: Vec<i32> = (0..n as i32)
            .flat_map(|i| [i, (i + 1) % n as i32, n as i32])
            .collect();
        obj.facets(&fan, 3, first);
    }
    obj.write(args.output.as_deref());
    println!(
        "{}; corners continuous across {} vertices",
        surfaces.summary(),
        corner_points.len()
    );
}
