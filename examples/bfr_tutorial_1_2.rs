//! OpenSubdiv's bfr tutorial 1_2, natively: every base face tessellated
//! with a `Tessellation` pattern at a uniform rate, its coordinates
//! evaluated on the face's limit surface, faces written separately.
//!
//! `cargo run --example bfr_tutorial_1_2 [INPUT.obj] [-o OUT.obj] [-res N]
//! [-quads]` (rate 5 by default). Checked: every point against OpenSubdiv's
//! Bfr (feature `osd`), and the points along an edge shared by two faces
//! against each other (the patterns agree along shared edges).

#[path = "bfr/common.rs"]
mod common;

use std::collections::HashMap;
use subdiv::bfr::{FacetSize, Tessellation, TessellationOptions};

fn main() {
    let args = common::Args::parse();
    let rate = args.number("-res", 5.0) as u32;
    let quads = args.has("-quads");
    let (mesh, options) = args.mesh();
    let mut surfaces = common::Surfaces::new(&mesh, &options);
    let tess_options = TessellationOptions {
        preserve_quads: quads,
        facet_size: if quads {
            FacetSize::Four
        } else {
            FacetSize::Three
        },
    };
    let mut obj = common::Obj::default();
    // The points along each base edge, from its lower vertex.
    let mut edges: HashMap<(u32, u32), Vec<glam::DVec3>> = HashMap::new();
    for face in 0..mesh.face_count() {
        if !surfaces.native.has_surface(face) {
            continue;
        }
        let param = surfaces
            .native
            .parameterization(face)
            .expect("parameterization");
        let pattern = Tessellation::uniform(param, rate, tess_options).expect("pattern");
        let coords = pattern.coords::<f64>().expect("coords");
        let s = surfaces.evaluate(face, &coords);
        let first = obj.points(&s);
        obj.facets(
            &pattern.facets().expect("facets"),
            pattern.facet_size(),
            first,
        );
        // Boundary points: rate per edge, counter-clockwise from vertex 0.
        let fv = mesh.face(face);
        for e in 0..fv.len() {
            let (a, b) = (fv[e], fv[(e + 1) % fv.len()]);
            let at = |k: usize| {
                obj.positions
                    [first as usize + (e * rate as usize + k) % pattern.num_boundary_coords()]
            };
            let mut line: Vec<glam::DVec3> = (0..=rate as usize).map(at).collect();
            if a > b {
                line.reverse();
            }
            let seen = edges
                .entry((a.min(b), a.max(b)))
                .or_insert_with(|| line.clone());
            for (p, q) in seen.iter().zip(&line) {
                assert!((*p - *q).length() < 1e-12, "edge {a}-{b}: faces disagree");
            }
        }
    }
    obj.write(args.output.as_deref());
    println!(
        "{}; {} shared edges agree point by point",
        surfaces.summary(),
        edges.len()
    );
}
