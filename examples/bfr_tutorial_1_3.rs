//! OpenSubdiv's bfr tutorial 1_3, natively: tutorial 1_2 with face-varying
//! UVs evaluated on each face (face-varying surfaces) and written as `vt`.
//!
//! `cargo run --example bfr_tutorial_1_3 [INPUT.obj] [-o OUT.obj] [-res N]`
//! (a cube with UVs by default). Checked: positions and UVs against
//! OpenSubdiv's Bfr (feature `osd`); on the cube each face's UVs span its
//! square of the unwrap bilinearly (linear face-varying interpolation).

#[path = "bfr/common.rs"]
mod common;

use subdiv::bfr::{Tessellation, TessellationOptions};

fn main() {
    let args = common::Args::parse();
    let rate = args.number("-res", 5.0) as u32;
    let (mesh, options) = args.mesh();
    assert!(!mesh.fvar_channels.is_empty(), "the mesh has no UVs");
    let mut surfaces = common::Surfaces::new(&mesh, &options);
    let mut obj = common::Obj::default();
    let channel = &mesh.fvar_channels[0];
    for face in 0..mesh.face_count() {
        if !surfaces.native.has_surface(face) {
            continue;
        }
        let param = surfaces
            .native
            .parameterization(face)
            .expect("parameterization");
        let pattern =
            Tessellation::uniform(param, rate, TessellationOptions::default()).expect("pattern");
        let coords = pattern.coords::<f64>().expect("coords");
        let s = surfaces.evaluate(face, &coords);
        let uv = surfaces.evaluate_uv(face, &coords);
        // A quad's UVs, interpolated linearly ("all"), are the bilinear
        // blend of its corners' values.
        if mesh.face(face).len() == 4 && options.fvar == subdiv::FVarLinearInterpolation::All {
            let corner = |k: usize| {
                let i =
                    channel.indices[mesh.face_offsets[face] as usize + k] as usize * channel.width;
                [channel.values[i], channel.values[i + 1]]
            };
            for (c, [u, v]) in coords.iter().enumerate() {
                for d in 0..2 {
                    let expected = (1.0 - u) * (1.0 - v) * corner(0)[d]
                        + u * (1.0 - v) * corner(1)[d]
                        + u * v * corner(2)[d]
                        + (1.0 - u) * v * corner(3)[d];
                    let got = uv.values.point[c * channel.width + d];
                    assert!(
                        (got - expected).abs() < 1e-12,
                        "face {face}: uv {got} against {expected}"
                    );
                }
            }
        }
        let first = obj.points(&s);
        for value in uv.values.point.chunks(channel.width) {
            obj.uvs.extend_from_slice(&value[..2]);
        }
        obj.facets(
            &pattern.facets().expect("facets"),
            pattern.facet_size(),
            first,
        );
    }
    obj.write(args.output.as_deref());
    println!("{} (positions and UVs)", surfaces.summary());
}
