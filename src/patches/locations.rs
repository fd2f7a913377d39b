//! Evaluating many locations at once: in ptex-face order, on the pool's
//! threads.
//!
//! Locations given in no particular order (a renderer's samples, a
//! scatterer's points) visit the patch map, the patch arrays and the
//! control points at random: most of the time goes to cache misses.
//! Evaluated face after face, neighbouring locations share their patch's
//! data. Each location's value is computed exactly as alone (the same
//! sums in the same order); only the order of the locations changes, and
//! the results are written back in the caller's order.

use super::eval::{EvalScratch, Evaluator};
use super::map::Found;
use crate::alloc::try_vec;
use crate::error::Result;
use crate::real::Real;
use rayon::prelude::*;

/// The fewest locations evaluated in face order (fewer are evaluated as
/// given).
const ORDERED_FROM: usize = 4096;

/// The most bytes of data a table's locations may read (points, control
/// vertices, patch parameters) for them to be evaluated as given: data
/// that stays in the caches gains nothing from the face order, which then
/// costs its gathers and scatters. 1,000,000 random locations, positions
/// and first derivatives, one thread of an EPYC with 1 MiB of L2 per core
/// and 32 MiB of L3: an unrefined 10,000-face torus (1 MiB of data) 160 ms
/// in face order, 136 ms as given; mixed tori at isolation 3 with 0.8,
/// 1.8, 3.2, 5.1 and 7.9 MiB of data 181, 180, 182, 181 and 181 ms in face
/// order, 146, 166, 192, 240 and 256 ms as given.
const CACHED_BYTES: usize = 2 << 20;

/// Locations per task on several threads.
const CHUNK: usize = 8192;

/// Evaluates `locations` (each accepted by `check_location`) into
/// `columns` (one per kind of value, `evaluator.width` reals per
/// location). An error is the first location's error in the caller's
/// order.
pub(super) fn evaluate_all<R: Real>(
    evaluator: &Evaluator<'_, R>,
    locations: &[(u32, f64, f64)],
    columns: &mut [&mut [R]],
) -> Result<()> {
    if locations.len() < ORDERED_FROM
        || evaluator.data_bytes() <= CACHED_BYTES
        || u32::try_from(locations.len()).is_err()
    {
        return in_given_order(evaluator, locations, columns);
    }
    match in_face_order(evaluator, locations, columns) {
        Ok(()) => Ok(()),
        // The first error in the caller's order, not in face order.
        Err(_) => in_given_order(evaluator, locations, columns),
    }
}

/// Each location in turn; on several threads, stretches of
/// [`CHUNK`] locations side by side, each into its own stretch of the
/// columns (an error is then looked for again in order, so that it is the
/// first location's).
fn in_given_order<R: Real>(
    evaluator: &Evaluator<'_, R>,
    locations: &[(u32, f64, f64)],
    columns: &mut [&mut [R]],
) -> Result<()> {
    let width = evaluator.width;
    let each =
        |locations: &[(u32, f64, f64)], buf: &mut EvalScratch, mut stretch: Vec<&mut [R]>| {
            evaluate_run(evaluator, locations, buf, &mut stretch)
        };
    if rayon::current_num_threads() > 1 && locations.len() >= ORDERED_FROM {
        // Each task's stretch of every column.
        let tasks = locations.len().div_ceil(CHUNK);
        let mut stretches: Vec<Vec<&mut [R]>> = (0..tasks).map(|_| Vec::new()).collect();
        for column in columns.iter_mut() {
            for (task, piece) in stretches.iter_mut().zip(column.chunks_mut(CHUNK * width)) {
                task.push(piece);
            }
        }
        let done = locations
            .par_chunks(CHUNK)
            .zip(stretches)
            .try_for_each_init(EvalScratch::default, |buf, (locations, stretch)| {
                each(locations, buf, stretch)
            });
        if done.is_ok() {
            return Ok(());
        }
    }
    let mut buf = EvalScratch::default();
    each(
        locations,
        &mut buf,
        columns.iter_mut().map(|c| &mut c[..]).collect(),
    )
}

/// Locations whose patches are found together before any is evaluated.
const BATCH: usize = 8;

/// Evaluates `locations` in order into values 0, 1, … of `columns`, the
/// patches of a batch of [`BATCH`] found (and their data touched,
/// [`Evaluator::touch`]) first, in a loop of their own: the map's nodes
/// and the patches' data of neighbouring locations are then read side by
/// side, not each after the previous location's evaluation. The first
/// error is the first failing location's.
fn evaluate_run<R: Real>(
    evaluator: &Evaluator<'_, R>,
    locations: &[(u32, f64, f64)],
    buf: &mut EvalScratch,
    columns: &mut [&mut [R]],
) -> Result<()> {
    for (b, batch) in locations.chunks(BATCH).enumerate() {
        let mut handles = [Found::NONE; BATCH];
        for (handle, &location) in handles.iter_mut().zip(batch) {
            *handle = evaluator.locate(location);
        }
        evaluator.touch(&handles);
        for (j, (&location, &handle)) in batch.iter().zip(&handles).enumerate() {
            evaluator.at(location, handle, b * BATCH + j, buf, columns)?;
        }
    }
    Ok(())
}

/// The indices of `locations` sorted by ptex face (a counting sort; in the
/// given order within a face). Faces are below `faces`.
fn face_order(locations: &[(u32, f64, f64)], faces: usize) -> Result<Vec<u32>> {
    let mut next = try_vec(0u32, faces + 1)?;
    for &(face, _, _) in locations {
        next[face as usize + 1] += 1;
    }
    for f in 1..next.len() {
        next[f] += next[f - 1];
    }
    let mut order = try_vec(0u32, locations.len())?;
    for (i, &(face, _, _)) in locations.iter().enumerate() {
        let slot = &mut next[face as usize];
        order[*slot as usize] = i as u32;
        *slot += 1;
    }
    Ok(order)
}

/// Face after face, a stretch of the face order at a time: its locations
/// gathered, evaluated into a stretch of sorted columns, the values then
/// put in the caller's order. (Gathering and scattering in tight loops of
/// their own keeps many cache misses in flight; inside the evaluation
/// they came one at a time.) On one thread each stretch is scattered as
/// it is done; on several, the stretches go into sorted copies of the
/// columns in parallel, gathered back afterwards.
fn in_face_order<R: Real>(
    evaluator: &Evaluator<'_, R>,
    locations: &[(u32, f64, f64)],
    columns: &mut [&mut [R]],
) -> Result<()> {
    let order = face_order(locations, evaluator.ptex_faces())?;
    let width = evaluator.width;
    let kinds = columns.len();
    let evaluate =
        |indices: &[u32], scratch: &mut Scratch, stretch: &mut [&mut [R]]| -> Result<()> {
            scratch.locations.clear();
            scratch
                .locations
                .extend(indices.iter().map(|&i| locations[i as usize]));
            evaluate_run(evaluator, &scratch.locations, &mut scratch.buf, stretch)
        };
    if rayon::current_num_threads() <= 1 {
        let mut scratch = Scratch::default();
        let mut sorted: Vec<Vec<R>> = Vec::new();
        for _ in 0..kinds {
            sorted.push(try_vec(R::ZERO, CHUNK.min(order.len()) * width)?);
        }
        for indices in order.chunks(CHUNK) {
            let mut stretch: Vec<&mut [R]> = sorted
                .iter_mut()
                .map(|c| &mut c[..indices.len() * width])
                .collect();
            evaluate(indices, &mut scratch, &mut stretch)?;
            for (column, from) in columns.iter_mut().zip(&stretch) {
                move_values(width, from, |k| k, column, |k| indices[k] as usize);
            }
        }
        return Ok(());
    }
    let mut sorted = Vec::new();
    for column in columns.iter() {
        sorted.push(try_vec(R::ZERO, column.len())?);
    }
    // Each task's stretch of every sorted column.
    let tasks = order.len().div_ceil(CHUNK);
    let mut stretches: Vec<Vec<&mut [R]>> = (0..tasks).map(|_| Vec::new()).collect();
    for column in sorted.iter_mut() {
        for (task, piece) in stretches.iter_mut().zip(column.chunks_mut(CHUNK * width)) {
            task.push(piece);
        }
    }
    order
        .par_chunks(CHUNK)
        .zip(stretches)
        .try_for_each_init(Scratch::default, |scratch, (indices, mut stretch)| {
            evaluate(indices, scratch, &mut stretch)
        })?;
    // Where each location's values are in the sorted columns.
    let mut rank = try_vec(0u32, order.len())?;
    for (k, &i) in order.iter().enumerate() {
        rank[i as usize] = k as u32;
    }
    for (column, from) in columns.iter_mut().zip(&sorted) {
        column
            .par_chunks_mut(CHUNK * width)
            .zip(rank.par_chunks(CHUNK))
            .for_each(|(dst, ranks)| {
                move_values(width, from, |k| ranks[k] as usize, dst, |k| k);
            });
    }
    Ok(())
}

/// A task's scratch space: its stretch's locations and what evaluating
/// them keeps between locations.
#[derive(Default)]
struct Scratch {
    locations: Vec<(u32, f64, f64)>,
    buf: EvalScratch,
}

/// Copies `to.len() / width` values of `width` reals: value `from_at(k)`
/// of `from` to value `to_at(k)` of `to`, for each `k`. Small widths
/// are copied as fixed-size arrays (a copy of a slice of run-time length
/// is a call to `memcpy` per value).
fn move_values<R: Copy>(
    width: usize,
    from: &[R],
    from_at: impl Fn(usize) -> usize,
    to: &mut [R],
    to_at: impl Fn(usize) -> usize,
) {
    fn fixed<R: Copy, const N: usize>(
        from: &[R],
        from_at: impl Fn(usize) -> usize,
        to: &mut [R],
        to_at: impl Fn(usize) -> usize,
        count: usize,
    ) {
        for k in 0..count {
            let (f, t) = (from_at(k) * N, to_at(k) * N);
            let value: [R; N] = std::array::from_fn(|c| from[f + c]);
            to[t..t + N].copy_from_slice(&value);
        }
    }
    let count = from.len().min(to.len()) / width;
    match width {
        1 => fixed::<R, 1>(from, from_at, to, to_at, count),
        2 => fixed::<R, 2>(from, from_at, to, to_at, count),
        3 => fixed::<R, 3>(from, from_at, to, to_at, count),
        4 => fixed::<R, 4>(from, from_at, to, to_at, count),
        _ => {
            for k in 0..count {
                let (f, t) = (from_at(k) * width, to_at(k) * width);
                to[t..t + width].copy_from_slice(&from[f..f + width]);
            }
        }
    }
}
