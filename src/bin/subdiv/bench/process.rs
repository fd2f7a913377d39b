//! Whole programs timed interleaved: `subdiv refine` and the C++ driver.

use super::timing::median;
use crate::refine::write_output;
use std::time::Instant;
use subdiv::shapes::BenchShape;
use subdiv::{Options, Precision, UniformOptions};

/// The median wall time of one program run by [`interleaved_processes`],
/// and the peak memory it reported.
#[derive(Debug, Clone, PartialEq)]
pub struct ProcessRun {
    /// Median seconds from start to exit.
    pub seconds: f64,
    /// The last `peak_memory_bytes N` line the program wrote to standard
    /// error (`subdiv refine --peak-memory`, the C++ driver), or 0.
    pub peak_bytes: u64,
}

/// Runs whole programs `reps` times each, interleaved: every repetition runs
/// each program once, starting one further along the list each time, so that
/// the machine's drift over the minutes falls on all of them alike. Returns
/// each program's median time and reported peak memory, in the order given.
/// A program that cannot start or exits unsuccessfully is an error naming it.
pub fn interleaved_processes(
    programs: &mut [(String, std::process::Command)],
    reps: usize,
) -> Result<Vec<ProcessRun>, String> {
    let count = programs.len();
    let mut times = vec![Vec::with_capacity(reps); count];
    let mut peaks = vec![0u64; count];
    for rep in 0..reps.max(1) {
        for k in 0..count {
            let i = (rep + k) % count;
            let (name, command) = &mut programs[i];
            let start = Instant::now();
            let out = command
                .output()
                .map_err(|e| format!("{name} could not start: {e}"))?;
            let elapsed = start.elapsed().as_secs_f64();
            if !out.status.success() {
                return Err(format!("{name} failed ({})", out.status));
            }
            times[i].push(elapsed);
            if let Some(v) = String::from_utf8_lossy(&out.stderr)
                .lines()
                .find_map(|l| l.strip_prefix("peak_memory_bytes "))
            {
                peaks[i] = v.trim().parse().unwrap_or(0);
            }
        }
    }
    Ok(times
        .iter_mut()
        .zip(peaks)
        .map(|(t, peak_bytes)| ProcessRun {
            seconds: median(t),
            peak_bytes,
        })
        .collect())
}

/// The OBJ writer's speed on the deepest level of `input` (what `subdiv
/// refine -o` writes), against the 200 MB/s target: the best of three writes.
pub(crate) fn obj_writer_rate(input: &BenchShape) -> String {
    let options = Options::default().with_scheme(input.scheme);
    let uniform = UniformOptions::new(input.max_level);
    let r = match subdiv::refiner::refine(&input.mesh, &options, uniform) {
        Ok(r) => r,
        Err(e) => return format!("\nOBJ writer: skipped ({e})\n"),
    };
    let dir = match tempfile::tempdir() {
        Ok(d) => d,
        Err(e) => return format!("\nOBJ writer: skipped: no temporary directory ({e})\n"),
    };
    let path = dir.path().join("out.obj");
    let mut best = f64::MAX;
    for _ in 0..3 {
        let t = Instant::now();
        if write_output(&path, &r).is_err() {
            return "\nOBJ writer: skipped (the temporary file could not be written)\n".into();
        }
        best = best.min(t.elapsed().as_secs_f64());
    }
    let bytes = std::fs::metadata(&path).map_or(0, |m| m.len());
    let rate = bytes as f64 / best / 1e6;
    format!(
        "\nOBJ writer ({}, level {}, f64 positions, {:.0} MB): {:.0} MB/s (target 200 MB/s) {}\n",
        input.name,
        input.max_level,
        bytes as f64 / 1e6,
        rate,
        if rate >= 200.0 { "met" } else { "NOT MET" }
    )
}

/// Whole-process time and peak memory: `subdiv refine` (native and osd) and,
/// when a C++ compiler is available, an equivalent C++ program against
/// OpenSubdiv (the driver in cpp/osd_driver.cpp, embedded in this binary).
pub(crate) fn whole_process(input: &BenchShape, quick: bool, threads: usize) -> String {
    use std::fmt::Write as _;
    use std::process::Command;
    let mut s = String::from(
        "\nWhole process, level 4, no output file (OpenSubdiv is single-threaded; medians of interleaved runs):\n",
    );
    let dir = match tempfile::tempdir() {
        Ok(d) => d,
        Err(e) => return format!("{s}  skipped: no temporary directory ({e})\n"),
    };
    let obj = dir.path().join("input.obj");
    if let Err(e) = subdiv::io::write_mesh_obj(&obj, &input.mesh, Precision::F64) {
        return format!("{s}  skipped: {e}\n");
    }
    let exe = match std::env::current_exe() {
        Ok(e) => e,
        Err(e) => return format!("{s}  skipped: {e}\n"),
    };
    let driver_src = dir.path().join("osd_driver.cpp");
    let driver = dir.path().join("osd_driver");
    let have_driver = std::fs::write(&driver_src, include_str!("../../../../cpp/osd_driver.cpp"))
        .is_ok()
        && Command::new("g++")
            .args(["-std=c++14", "-O2"])
            .arg(&driver_src)
            .args(["-losdCPU", "-o"])
            .arg(&driver)
            .output()
            .is_ok_and(|o| o.status.success());
    // Nine runs of each program: on this kind of virtual machine a process
    // now and then finds its fresh memory handed back to the host and takes
    // 2-4x its usual time, and once three of five such runs made the median
    // (160 ms where the runs before and after gave 54-66 ms).
    let reps = if quick { 3 } else { 9 };
    // Every core, as `subdiv refine` runs when typed as the target names it.
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let refine = |engine: &str, threads: Option<usize>| {
        let mut c = Command::new(&exe);
        c.arg("refine")
            .arg(&obj)
            .args(["--level", "4", "--engine", engine, "--peak-memory"]);
        match threads {
            Some(n) => c.env("RAYON_NUM_THREADS", n.max(1).to_string()),
            None => c.env_remove("RAYON_NUM_THREADS"),
        };
        c
    };
    let threads = threads.max(1);
    // Each program's place in the list, kept as it is pushed.
    let mut programs = vec![(
        format!("subdiv refine --engine native, {threads} thread(s)"),
        refine("native", Some(threads)),
    )];
    let typed_at = if threads != cores {
        programs.push((
            format!("subdiv refine --engine native, every core ({cores})"),
            refine("native", None),
        ));
        programs.len() - 1
    } else {
        0
    };
    let osd_at = programs.len();
    programs.push(("subdiv refine --engine osd".into(), refine("osd", None)));
    let cpp_at = have_driver.then(|| {
        let mut c = Command::new(&driver);
        c.arg(&obj).arg("-").args(["--level", "4"]);
        programs.push(("C++ program against OpenSubdiv".into(), c));
        programs.len() - 1
    });
    let medians: Vec<(f64, u64)> = match interleaved_processes(&mut programs, reps) {
        Ok(runs) => runs
            .into_iter()
            .map(|r| (r.seconds, r.peak_bytes))
            .collect(),
        Err(e) => return format!("{s}  skipped: {e}\n"),
    };
    for ((name, _), (t, peak)) in programs.iter().zip(&medians) {
        let _ = write!(s, "  {name}: {:.1} ms", t * 1e3);
        if *peak > 0 {
            let _ = write!(s, ", peak memory {:.0} MiB", *peak as f64 / 1048576.0);
        }
        s.push('\n');
    }
    let (native, typed, osd) = (medians[0], medians[typed_at], medians[osd_at]);
    if native.1 > 0 && osd.1 > 0 {
        let _ = writeln!(
            s,
            "  peak memory native / subdiv --engine osd: {:.2}",
            native.1 as f64 / osd.1 as f64
        );
    }
    let Some(cpp) = cpp_at.map(|i| medians[i]) else {
        s.push_str("  C++ program: skipped (g++ or libosd-dev not available)\n");
        return s;
    };
    if typed_at != 0 {
        let _ = writeln!(
            s,
            "  speed-up over the C++ program with {threads} thread(s): {:.2}x",
            cpp.0 / native.0
        );
    }
    // The target names the command as a user types it: every core.
    let ratio = cpp.0 / typed.0;
    let _ = writeln!(
        s,
        "  whole-process speed-up of `subdiv refine torus.obj --level 4` ({cores} threads, its default) over the C++ program: {ratio:.2}x (target 3x) {}",
        if ratio >= 3.0 { "met" } else { "NOT MET" }
    );
    let peak = native.1.max(typed.1);
    if peak > 0 && cpp.1 > 0 {
        let ratio = peak as f64 / cpp.1 as f64;
        let _ = writeln!(
            s,
            "  peak memory native (the larger of its runs) / C++ program: {ratio:.2} (target 0.6) {}",
            if ratio <= 0.6 { "met" } else { "NOT MET" }
        );
    }
    s
}
