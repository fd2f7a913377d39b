//! Timing helpers: interleaved medians, the memory bandwidth, the machine.

use std::hint::black_box;
use std::time::Instant;
use subdiv::osd;
/// Runs `a` and `b` alternately (the order swapping every repetition) and
/// returns their median times in seconds.
///
/// Every timed run comes right after an untimed run of the same closure, as
/// criterion's warm-up does: both engines share this process's allocator,
/// and without it each engine would be timed in the heap the other just left
/// (OpenSubdiv's frees trim the heap the native engine then faults in again,
/// and the reverse), which measures their interaction more than either. The
/// order still alternates, so the drift of this machine cancels out.
pub(crate) fn interleaved(reps: usize, mut a: impl FnMut(), mut b: impl FnMut()) -> (f64, f64) {
    let (mut ta, mut tb) = (Vec::with_capacity(reps), Vec::with_capacity(reps));
    for i in 0..reps.max(1) {
        let time = |f: &mut dyn FnMut()| {
            f();
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64()
        };
        if i % 2 == 0 {
            ta.push(time(&mut a));
            tb.push(time(&mut b));
        } else {
            tb.push(time(&mut b));
            ta.push(time(&mut a));
        }
    }
    (median(&mut ta), median(&mut tb))
}

pub(crate) fn median(v: &mut [f64]) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

/// This machine's memory bandwidth: the best of a few copies of a 256 MiB
/// buffer, counting bytes read plus bytes written, split between the threads
/// of the current rayon pool (run it in the pool whose rates it is compared
/// with: one thread cannot draw all of a machine's bandwidth).
pub fn measure_bandwidth() -> f64 {
    use rayon::prelude::*;
    let n = 32 << 20; // 32 Mi f64 = 256 MiB
    let src = vec![1.0f64; n];
    let mut dst = vec![0.0f64; n];
    let part = n.div_ceil(rayon::current_num_threads());
    let mut best = f64::MAX;
    for _ in 0..5 {
        let t = Instant::now();
        dst.par_chunks_mut(part)
            .zip(src.par_chunks(part))
            .for_each(|(d, s)| d.copy_from_slice(black_box(s)));
        best = best.min(t.elapsed().as_secs_f64());
        black_box(&dst);
    }
    (2 * n * 8) as f64 / best
}

/// The date, processor and core count, for reports.
pub(crate) fn machine_description() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_string())
        })
        .unwrap_or_else(|| "unknown processor".into());
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    format!("{cpu}, {cores} cores, OpenSubdiv {}", osd::version())
}
