//! OpenSubdiv's far tutorial 5_3 ("limit stencils at locations") with the
//! native engine, run with the tutorial's defaults: a unit cube refined
//! adaptively to level 2 (infinitely sharp patches, Gregory basis end
//! caps), limit stencils at five locations of each face — its middle and
//! near each corner, at the tutorial's `f32` coordinates — applied to the
//! cube's points, and each face drawn as a fan of four triangles around
//! its middle, printed as the same OBJ text. OpenSubdiv's program builds
//! the stencils from a patch table of its own options, in `f32`;
//! `location_stencils` builds the same patches (the cube has no boundary,
//! where the tutorial's `generateLegacySharpCornerPatches = false` would
//! matter) and, asked for `f32`, every weight in `f32` as OpenSubdiv's
//! `LimitStencilTableFactory` does (the refined stencils, the local
//! points, the basis, the sums), applied here in `f32` as the tutorial
//! applies them (`tests/far_tutorials.rs` holds the output to OpenSubdiv's
//! program, `cpp/far_tutorials.cpp`).
//!
//! ```sh
//! cargo run --example far_tutorial_5_3 > limit.obj
//! ```

use glam::DVec3;
use std::fmt::Write as _;
use subdiv::patches::{LimitStencilOptions, LocationStencils, PatchOptions};
use subdiv::ptex::PtexIndices;
use subdiv::refiner::Refiner;
use subdiv::{BoundaryInterpolation, Mesh, Options, Precision};

/// The tutorial's cube.
fn cube() -> Mesh {
    let corners = [
        [-0.5, -0.5, -0.5],
        [-0.5, 0.5, -0.5],
        [-0.5, 0.5, 0.5],
        [-0.5, -0.5, 0.5],
        [0.5, -0.5, -0.5],
        [0.5, 0.5, -0.5],
        [0.5, 0.5, 0.5],
        [0.5, -0.5, 0.5],
    ];
    Mesh::from_faces(
        corners.iter().map(|&c| DVec3::from_array(c)).collect(),
        &[
            &[0, 3, 2, 1],
            &[4, 5, 6, 7],
            &[0, 4, 7, 3],
            &[1, 2, 6, 5],
            &[0, 1, 5, 4],
            &[3, 7, 6, 2],
        ],
    )
}

fn main() -> Result<(), subdiv::Error> {
    print!("{}", run()?);
    Ok(())
}

/// The tutorial's limit stencils (`f32` weights), at its locations; with
/// first derivatives when `derivatives` (the tutorial computes none).
pub fn stencils(derivatives: bool) -> Result<LocationStencils, subdiv::Error> {
    let mesh = cube();
    let options = Options::default().with_boundary(BoundaryInterpolation::EdgeAndCorner);
    let patch_options = PatchOptions {
        legacy_sharp_corner_patches: false,
        varying_tables: false,
        fvar_tables: false,
        ..PatchOptions::new().max_isolation(2).inf_sharp_patch(true)
    };
    let refiner = Refiner::new(&mesh, &options)?;
    let ptex = PtexIndices::new(&refiner)?;
    let refiner = refiner.refine_adaptive(patch_options.refine_adaptive_options(), &[])?;

    // Five locations per quad, in the tutorial's f32: the middle, then
    // near each corner.
    let s: [f32; 5] = [0.5, 0.05, 0.95, 0.95, 0.05];
    let t: [f32; 5] = [0.5, 0.05, 0.05, 0.95, 0.95];
    let mut locations = Vec::new();
    for face in 0..mesh.face_count() {
        let ptex_face = ptex.face_id(face)?;
        locations.extend((0..5).map(|i| (ptex_face, f64::from(s[i]), f64::from(t[i]))));
    }
    // In f32; the tutorial asks for positions only
    // (`generate1stDerivatives = false`).
    let stencil_options = LimitStencilOptions::new()
        .first_derivatives(derivatives)
        .precision(Precision::F32);
    refiner.location_stencils(&locations, &stencil_options)
}

/// The tutorial's output.
pub fn run() -> Result<String, subdiv::Error> {
    let mesh = cube();
    let stencils = stencils(false)?;
    // `UpdateValues` in f32, as the tutorial's: each stencil's terms in
    // order (the weights f32 values, widened to f64).
    let base = mesh.flat_positions::<f32>();
    let mut limit = Vec::with_capacity(stencils.len());
    for (&offset, &size) in stencils.offsets.iter().zip(&stencils.sizes) {
        let terms = offset as usize..(offset + size) as usize;
        let mut p = [0.0f32; 3];
        for (&i, &w) in stencils.indices[terms.clone()]
            .iter()
            .zip(&stencils.weights.point[terms])
        {
            for (k, x) in p.iter_mut().enumerate() {
                *x += w as f32 * base[3 * i as usize + k];
            }
        }
        limit.push(p);
    }

    let mut out = String::from("g base_mesh\n");
    for p in &limit {
        let _ = writeln!(out, "v {:.6} {:.6} {:.6}", p[0], p[1], p[2]);
    }
    for face in 0..mesh.face_count() {
        let centre = 5 * face + 1;
        for k in 0..4 {
            let _ = writeln!(
                out,
                "f {centre} {} {}",
                centre + 1 + k,
                centre + 1 + (k + 1) % 4
            );
        }
    }
    Ok(out)
}
