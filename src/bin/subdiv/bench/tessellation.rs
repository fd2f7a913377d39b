//! The tessellation section of `subdiv bench` (issue #25): the limit
//! surface of the Catmull-Clark tori tessellated the Bfr way at rates 4 and
//! 16 (the production-like mesh at rate 4) — the native `MeshSurfaces::new` + `bfr::tessellate` against
//! OpenSubdiv's `Bfr::RefinerSurfaceFactory`, `Surface` and `Tessellation`
//! in one C++ loop (bfr tutorial 2_2's, `osd::bfr::tessellate_mesh`) — with
//! triangles per second.

use super::results::{Row, TessellationRow};
use super::timing::interleaved;
use crate::Failure;
use std::hint::black_box;
use subdiv::bfr::{MeshSurfaces, SurfaceOptions, TessellateOptions, tessellate};
use subdiv::shapes::BenchShape;
use subdiv::{Scheme, osd};

/// The rates of the rows.
pub const RATES: [u32; 2] = [4, 16];

/// The inputs of the section: of the standard set (`standard`), the tori
/// (Catmull-Clark, and the triangle torus under Loop), with their UVs
/// (face-varying channel 0, linear or smooth), and the production-like
/// mesh (creases, holes, n-gons, a UV channel with seams); else every
/// input given.
pub fn tessellation_inputs(inputs: &[BenchShape], standard: bool) -> Vec<&BenchShape> {
    inputs
        .iter()
        .filter(|i| {
            !standard
                || match i.options.scheme {
                    Scheme::Catmark => {
                        i.name.starts_with("torus") || i.name.starts_with("production")
                    }
                    Scheme::Loop => i.name.starts_with("torus"),
                    Scheme::Bilinear => false,
                }
        })
        .collect()
}

/// Inputs with this many faces or more are tessellated at the first rate
/// only, once (the production-like mesh: seconds a tessellation).
pub const BIG_INPUT: usize = 100_000;

/// The rates `input` is tessellated at: [`RATES`], the first only for an
/// input of [`BIG_INPUT`] faces or more.
pub fn tessellation_rates(input: &BenchShape) -> &'static [u32] {
    if input.mesh.face_count() >= BIG_INPUT {
        &RATES[..1]
    } else {
        &RATES
    }
}

/// The rows of `input` at [`tessellation_rates`] (once for big inputs). Both
/// engines tessellate once first (not timed): the meshes must have the
/// same facets and points within 1e-9 of the mesh's size, or the rows are
/// refused.
pub fn tessellation_rows(
    pool: &rayon::ThreadPool,
    input: &BenchShape,
    reps: usize,
    mut progress: impl FnMut(&str),
) -> Result<Vec<TessellationRow>, Failure> {
    let so = SurfaceOptions::default();
    let mut rows = Vec::new();
    let rates = tessellation_rates(input);
    let reps = if rates.len() < RATES.len() { 1 } else { reps };
    for &rate in rates {
        let tess = TessellateOptions {
            rate,
            uvs: true,
            ..TessellateOptions::default()
        };
        let native = || -> subdiv::Result<subdiv::bfr::TessellatedMesh> {
            let surfaces = MeshSurfaces::new(&input.mesh, &input.options, &so)?;
            tessellate(&input.mesh, &surfaces, &tess)
        };
        let opensubdiv = || osd::bfr::tessellate_mesh(&input.mesh, &input.options, &so, &tess);
        let (a, b) = (pool.install(native)?, opensubdiv()?);
        let size = 1.0
            + input
                .mesh
                .positions
                .iter()
                .fold(0.0f64, |m, p| m.max(p.abs().max_element()));
        let differ = a.face_vertices != b.face_vertices
            || a.positions.len() != b.positions.len()
            || a.positions
                .iter()
                .zip(&b.positions)
                .any(|(p, q)| p.distance(*q) > 1e-9 * size);
        if differ {
            return Err(Failure::Message(format!(
                "tessellation benchmark refused on {} (rate {rate}): the engines' meshes differ, so their times would not measure the same work",
                input.name
            )));
        }
        let triangles = a
            .face_offsets
            .windows(2)
            .map(|w| (w[1] - w[0]) as usize - 2)
            .sum();
        let task = format!(
            "tessellation (rate {rate}{})",
            if tess.uvs && !input.mesh.fvar_channels.is_empty() {
                ", UVs"
            } else {
                ""
            }
        );
        progress(&format!("{} {}: {task}", input.name, input.options.scheme));
        let (n, o) = pool.install(|| {
            interleaved(
                reps,
                || drop(black_box(native().expect("native"))),
                || drop(black_box(opensubdiv().expect("osd"))),
            )
        });
        rows.push(TessellationRow {
            rate,
            triangles,
            row: Row {
                input: input.name.clone(),
                scheme: input.options.scheme.to_string(),
                level: 0,
                task,
                native: n,
                osd: o,
                vertices: a.positions.len(),
            },
        });
    }
    Ok(rows)
}
