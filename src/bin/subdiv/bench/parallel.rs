//! The parallel-use section: many frames of one mesh, many meshes.

use super::results::{ParallelRow, Row};
use super::timing::interleaved;
use crate::Failure;
use std::hint::black_box;
use subdiv::mesh::Mesh;
use subdiv::options::{Options, Scheme, UniformOptions};
use subdiv::shapes::BenchShape;
use subdiv::{Result, osd, refiner, shapes};

/// Frames and meshes in the parallel-use section of [`run`].
pub const PARALLEL_COUNT: usize = 16;

/// The level the parallel-use section refines to.
pub const PARALLEL_LEVEL: u32 = 3;

/// `count` frames of animated positions for `mesh` (flat `f32`, 3 per
/// vertex): each frame twists the mesh about the z axis and runs a wave
/// along it, with amplitudes relative to its size and a phase that advances
/// frame by frame.
pub fn deformed_frames(mesh: &Mesh, count: usize) -> Vec<Vec<f32>> {
    let size = subdiv::compare::bbox_diagonal(&mesh.positions).max(f64::MIN_POSITIVE);
    (0..count)
        .map(|k| {
            let phase = std::f64::consts::TAU * (k as f64 + 1.0) / count as f64;
            mesh.positions
                .iter()
                .flat_map(|p| {
                    let angle = 0.5 * phase.sin() * p.z / size;
                    let (s, c) = angle.sin_cos();
                    let wave =
                        0.02 * size * (4.0 * p.x / size * std::f64::consts::TAU + phase).sin();
                    [
                        (c * p.x - s * p.y) as f32,
                        (s * p.x + c * p.y) as f32,
                        (p.z + wave) as f32,
                    ]
                })
                .collect()
        })
        .collect()
}

/// `count` different meshes for the parallel-use section: tori of growing
/// size, in turn quads (Catmull-Clark), quads and triangle pairs
/// (Catmull-Clark) and triangles (Loop); `quick` shrinks them.
pub fn many_meshes(count: usize, quick: bool) -> Vec<BenchShape> {
    let d = if quick { 4 } else { 1 };
    (0..count as u32)
        .map(|i| {
            let (nu, nv) = ((24 + 6 * i) / d, (16 + 4 * i) / d);
            let (kind, mesh, scheme) = match i % 3 {
                0 => ("quads", shapes::torus(nu, nv), Scheme::Catmark),
                1 => ("mixed", shapes::torus_mixed(nu, nv), Scheme::Catmark),
                _ => ("triangles", shapes::torus_triangles(nu, nv), Scheme::Loop),
            };
            BenchShape {
                name: format!("torus {nu}x{nv} {kind}"),
                mesh,
                options: Options::default().with_scheme(scheme),
                max_level: PARALLEL_LEVEL,
            }
        })
        .collect()
}

/// The first value where two results differ, or their lengths, for errors.
pub(crate) fn first_difference(native: &[f32], osd: &[f32]) -> Option<String> {
    if native.len() != osd.len() {
        return Some(format!(
            "{} values natively, {} in OpenSubdiv",
            native.len(),
            osd.len()
        ));
    }
    native
        .iter()
        .zip(osd)
        .position(|(a, b)| a.to_bits() != b.to_bits())
        .map(|i| {
            format!(
                "value {i}: {} natively, {} in OpenSubdiv",
                native[i], osd[i]
            )
        })
}

pub(crate) fn differ(what: &str, difference: String) -> Failure {
    Failure::Message(format!(
        "parallel-use benchmark refused: the engines' {what} differ ({difference}), so their times would not measure the same work"
    ))
}

/// [`interleaved`] over a batch: each side maps every job with rayon inside
/// `pool` and collects the results (each engine's own buffer type).
pub(crate) fn interleaved_batches<J: Sync, A: Send, B: Send>(
    pool: &rayon::ThreadPool,
    reps: usize,
    jobs: &[J],
    native: impl Fn(&J) -> A + Sync,
    osd: impl Fn(&J) -> B + Sync,
) -> (f64, f64) {
    use rayon::prelude::*;
    pool.install(|| {
        interleaved(
            reps,
            || drop(black_box(jobs.par_iter().map(&native).collect::<Vec<A>>())),
            || drop(black_box(jobs.par_iter().map(&osd).collect::<Vec<B>>())),
        )
    })
}

/// Many frames of one topology: both engines refine `input`'s topology to
/// `level` once (not timed), check that the first frame's refined positions
/// are equal bit for bit, then interpolate every frame to the last level
/// (`interpolate_last`, `f32`), the frames spread over `pool` with rayon
/// (`par_iter`) for both engines: each one's `Refiner` is `Sync`, shared by
/// the threads, as a user animating a mesh would use it. Medians of `reps`
/// interleaved repetitions of the whole batch.
pub fn frames_row(
    pool: &rayon::ThreadPool,
    input: &BenchShape,
    frames: &[Vec<f32>],
    level: u32,
    reps: usize,
) -> Result<ParallelRow, Failure> {
    let options = input.options;
    let uniform = UniformOptions::new(level);
    let mut n = refiner::Refiner::new(&input.mesh, &options)?;
    n.refine_uniform(uniform)?;
    let mut o = osd::TopologyRefiner::new(&input.mesh, &options)?;
    o.refine_uniform(uniform)?;
    if let Some(frame) = frames.first() {
        let (a, b) = (n.interpolate_last(3, frame)?, o.interpolate_last(3, frame)?);
        if let Some(d) = first_difference(&a, &b) {
            return Err(differ("positions of the first frame", d));
        }
    }
    let (native, osd) = interleaved_batches(
        pool,
        reps,
        frames,
        |f| n.interpolate_last(3, f).expect("native"),
        |f| o.interpolate_last(3, f).expect("osd"),
    );
    Ok(ParallelRow {
        unit: "frames".into(),
        count: frames.len(),
        row: Row {
            input: format!("{}, {} frames", input.name, frames.len()),
            scheme: input.options.scheme.to_string(),
            level,
            task: format!("frames ({}, level {level})", frames.len()),
            native,
            osd,
            vertices: frames.len() * n.level_counts(level)?.vertices,
        },
    })
}

/// Many meshes: each of `meshes` gets its own `Refiner`, refined to `level`
/// with its positions interpolated to the last level (`f32`), the meshes
/// spread over `pool` with rayon for both engines (OpenSubdiv's refiners are
/// independent objects; the bridge keeps its messages per thread). Every
/// mesh's result is checked equal bit for bit between the engines first (not
/// timed). Medians of `reps` interleaved repetitions of the whole batch.
pub fn meshes_row(
    pool: &rayon::ThreadPool,
    meshes: &[BenchShape],
    level: u32,
    reps: usize,
) -> Result<ParallelRow, Failure> {
    let uniform = UniformOptions::new(level);
    let jobs: Vec<(&Mesh, Options, Vec<f32>)> = meshes
        .iter()
        .map(|m| (&m.mesh, m.options, m.mesh.flat_positions::<f32>()))
        .collect();
    let native_one =
        |(mesh, options, base): &(&Mesh, Options, Vec<f32>)| -> Result<subdiv::Values<f32>> {
            let mut r = refiner::Refiner::new(mesh, options)?;
            r.refine_uniform(uniform)?;
            r.interpolate_last(3, base)
        };
    let osd_one = |(mesh, options, base): &(&Mesh, Options, Vec<f32>)| -> Result<Vec<f32>> {
        let mut r = osd::TopologyRefiner::new(mesh, options)?;
        r.refine_uniform(uniform)?;
        r.interpolate_last(3, base)
    };
    let mut vertices = 0;
    for (job, input) in jobs.iter().zip(meshes) {
        let a = native_one(job)?;
        if let Some(d) = first_difference(&a, &osd_one(job)?) {
            return Err(differ(&format!("positions of {}", input.name), d));
        }
        vertices += a.len() / 3;
    }
    let (native, osd) = interleaved_batches(
        pool,
        reps,
        &jobs,
        |j| native_one(j).expect("native"),
        |j| osd_one(j).expect("osd"),
    );
    let mut schemes: Vec<String> = Vec::new();
    for m in meshes {
        let s = m.options.scheme.to_string();
        if !schemes.contains(&s) {
            schemes.push(s);
        }
    }
    let input = match (meshes.first(), meshes.last()) {
        (Some(a), Some(b)) if meshes.len() > 1 => {
            format!("{} meshes, {} to {}", meshes.len(), a.name, b.name)
        }
        (Some(a), _) => a.name.clone(),
        _ => "no meshes".into(),
    };
    Ok(ParallelRow {
        unit: "meshes".into(),
        count: meshes.len(),
        row: Row {
            input,
            scheme: schemes.join("+"),
            level,
            task: format!("meshes ({}, level {level})", meshes.len()),
            native,
            osd,
            vertices,
        },
    })
}
