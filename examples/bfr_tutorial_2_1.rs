//! OpenSubdiv's bfr tutorial 2_1, natively: a rate per edge of each face,
//! 1 + the edge's length over a tessellation interval (rounded down, at
//! most `-max`), the length measured between the limit surface's corners
//! (or the control hull's with `-hull`); the interval defaults to the
//! longest control edge over the maximum rate.
//!
//! `cargo run --example bfr_tutorial_2_1 [INPUT.obj] [-o OUT.obj] [-length L]
//! [-max M] [-hull] [-quads]`. Checked: points against OpenSubdiv's Bfr
//! (feature `osd`), and that two faces sharing an edge chose the same rate
//! for it (the lengths are measured between shared points).

#[path = "bfr/common.rs"]
mod common;

use std::collections::HashMap;
use subdiv::bfr::{FacetSize, Tessellation, TessellationOptions};

fn main() {
    let args = common::Args::parse();
    let max_rate = args.number("-max", 10.0) as u32;
    let hull = args.has("-hull");
    let quads = args.has("-quads");
    let (mesh, options) = args.mesh();
    let longest = mesh
        .faces()
        .flat_map(|f| (0..f.len()).map(move |i| (f[i], f[(i + 1) % f.len()])))
        .map(|(a, b)| mesh.positions[a as usize].distance(mesh.positions[b as usize]))
        .fold(0.0f64, f64::max);
    let interval = args.number("-length", 0.0);
    let interval = if interval > 0.0 {
        interval
    } else {
        longest / f64::from(max_rate)
    };
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
    let mut rates_seen: HashMap<(u32, u32), u32> = HashMap::new();
    for face in 0..mesh.face_count() {
        if !surfaces.native.has_surface(face) {
            continue;
        }
        let param = surfaces
            .native
            .parameterization(face)
            .expect("parameterization");
        let fv = mesh.face(face);
        let n = fv.len();
        let corners: Vec<glam::DVec3> = if hull {
            fv.iter().map(|&v| mesh.positions[v as usize]).collect()
        } else {
            let coords: Vec<[f64; 2]> = (0..n).map(|i| param.vertex_coord(i)).collect();
            let s = surfaces.evaluate(face, &coords);
            s.values
                .point
                .chunks(3)
                .map(glam::DVec3::from_slice)
                .collect()
        };
        let rates: Vec<u32> = (0..n)
            .map(|i| {
                let length = corners[i].distance(corners[(i + 1) % n]);
                (1 + (length / interval) as u32).min(max_rate)
            })
            .collect();
        for (i, &rate) in rates.iter().enumerate() {
            let (a, b) = (fv[i], fv[(i + 1) % n]);
            let seen = *rates_seen.entry((a.min(b), a.max(b))).or_insert(rate);
            assert_eq!(seen, rate, "edge {a}-{b}: faces chose different rates");
        }
        let pattern = Tessellation::new(param, &rates, tess_options).expect("pattern");
        let coords = pattern.coords::<f64>().expect("coords");
        let s = surfaces.evaluate(face, &coords);
        let first = obj.points(&s);
        obj.facets(
            &pattern.facets().expect("facets"),
            pattern.facet_size(),
            first,
        );
    }
    obj.write(args.output.as_deref());
    println!(
        "{}; interval {interval:.6}, rates 1..{} on {} edges",
        surfaces.summary(),
        rates_seen.values().max().copied().unwrap_or(0),
        rates_seen.len()
    );
}
