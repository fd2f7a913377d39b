//! OpenSubdiv's bfr tutorial 2_2, natively: a watertight tessellation of
//! the whole mesh — points at base vertices and along base edges evaluated
//! once, by the first face using them, and shared — which is
//! `subdiv::bfr::tessellate`.
//!
//! `cargo run --example bfr_tutorial_2_2 [INPUT.obj] [-o OUT.obj] [-res N]
//! [-quads]`. Checked: the result's open edges are the segments of the
//! mesh's own boundary edges (no cracks), and the mesh
//! equals the one tessellated from OpenSubdiv's Bfr surfaces (feature
//! `osd`).

#[path = "bfr/common.rs"]
mod common;

use std::collections::HashMap;
use subdiv::bfr::{TessellateOptions, tessellate};

fn main() {
    let args = common::Args::parse();
    let (mesh, options) = args.mesh();
    let surfaces = common::Surfaces::new(&mesh, &options);
    let tess = TessellateOptions {
        rate: args.number("-res", 5.0) as u32,
        quads: args.has("-quads"),
        normals: true,
        ..TessellateOptions::default()
    };
    let t = tessellate(&mesh, &surfaces.native, &tess).expect("tessellate");
    // Undirected edges of the result and of the mesh: the result's open
    // edges lie on the mesh's own boundary edges, no others (no cracks).
    let count = |faces: &mut dyn Iterator<Item = &[u32]>| {
        let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
        for f in faces {
            for i in 0..f.len() {
                let (a, b) = (f[i], f[(i + 1) % f.len()]);
                *edges.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        edges.values().filter(|&&c| c == 1).count()
    };
    let mut faces = t
        .face_offsets
        .windows(2)
        .map(|w| &t.face_vertices[w[0] as usize..w[1] as usize]);
    let open = count(&mut faces);
    let mesh_open = count(&mut mesh.faces());
    assert_eq!(
        open,
        mesh_open * tess.rate as usize,
        "cracks: {open} open edges"
    );
    #[cfg(feature = "osd")]
    {
        let theirs =
            tessellate(&mesh, &surfaces.osd, &tess).expect("tessellate over OpenSubdiv's surfaces");
        assert_eq!(t.face_vertices, theirs.face_vertices);
        for (p, q) in t.positions.iter().zip(&theirs.positions) {
            assert!((*p - *q).length() < 1e-9, "{p} against {q}");
        }
        println!("the same mesh from OpenSubdiv's Bfr surfaces");
    }
    let obj = common::Obj {
        positions: t.positions.to_vec(),
        normals: t.normals.to_vec(),
        offsets: t.face_offsets.to_vec(),
        corners: t.face_vertices.to_vec(),
        ..Default::default()
    };
    obj.write(args.output.as_deref());
    println!("watertight: {open} open edges, all on the mesh's own {mesh_open} boundary edges");
}
