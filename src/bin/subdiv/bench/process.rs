//! Whole programs timed interleaved: `subdiv refine` and the C++ driver.

use super::results::{ObjReaderRate, ObjWriterRate, ProgramKind, ProgramResult, WholeProcess};
use super::timing::median;
use crate::refine::write_refinement;
use std::time::Instant;
use subdiv::shapes::BenchShape;
use subdiv::{Precision, UniformOptions};

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
/// refine -o` writes): the best of three writes of the refined level.
pub(crate) fn obj_writer_rate(input: &BenchShape) -> Result<ObjWriterRate, String> {
    let options = input.options;
    let uniform = UniformOptions::new(input.max_level);
    let r = subdiv::refiner::refine(&input.mesh, &options, uniform).map_err(|e| e.to_string())?;
    let dir = tempfile::tempdir().map_err(|e| format!("no temporary directory ({e})"))?;
    let path = dir.path().join("out.obj");
    let mut best = f64::MAX;
    for _ in 0..3 {
        let t = Instant::now();
        write_refinement(&path, None, &r).map_err(|_| "the temporary file could not be written")?;
        best = best.min(t.elapsed().as_secs_f64());
    }
    Ok(ObjWriterRate {
        input: input.name.clone(),
        level: input.max_level,
        bytes: std::fs::metadata(&path).map_or(0, |m| m.len()),
        seconds: best,
    })
}

/// The OBJ reader's speed on `input` written as an OBJ file with its tags
/// and UVs (what `subdiv refine INPUT.obj` reads): the best of three reads
/// on one thread and on `threads` threads, each checked to give the mesh's
/// faces and positions back.
pub(crate) fn obj_reader_rate(input: &BenchShape, threads: usize) -> Result<ObjReaderRate, String> {
    let dir = tempfile::tempdir().map_err(|e| format!("no temporary directory ({e})"))?;
    let path = dir.path().join("input.obj");
    subdiv::io::write_mesh_obj(&path, &input.mesh, Precision::F64).map_err(|e| e.to_string())?;
    let best = |threads: usize| -> Result<f64, String> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| e.to_string())?;
        let mut best = f64::MAX;
        for _ in 0..3 {
            let t = Instant::now();
            let shape = pool
                .install(|| subdiv::io::read_obj(&path))
                .map_err(|e| e.to_string())?;
            best = best.min(t.elapsed().as_secs_f64());
            let same = shape.mesh.face_vertices == input.mesh.face_vertices
                && shape.mesh.positions == input.mesh.positions;
            if !same {
                return Err("the file read back is not the mesh written".into());
            }
        }
        Ok(best)
    };
    let threads = threads.max(1);
    Ok(ObjReaderRate {
        input: input.name.clone(),
        bytes: std::fs::metadata(&path).map_or(0, |m| m.len()),
        seconds_one_thread: best(1)?,
        threads,
        seconds: best(threads)?,
    })
}

/// The C++ program of the whole-process rows (cpp/osd_driver.cpp,
/// embedded in this binary) compiled into `dir` against OpenSubdiv, once
/// per benchmark: its path, or `None` when g++ or libosd-dev is missing
/// (the rows then leave it out).
pub(crate) fn compile_driver(dir: &std::path::Path) -> Option<std::path::PathBuf> {
    let driver_src = dir.join("osd_driver.cpp");
    let driver = dir.join("osd_driver");
    let compiled = std::fs::write(&driver_src, include_str!("../../../../cpp/osd_driver.cpp"))
        .is_ok()
        && std::process::Command::new("g++")
            .args(["-std=c++14", "-O2"])
            .arg(&driver_src)
            .args(["-losdCPU", "-o"])
            .arg(&driver)
            .output()
            .is_ok_and(|o| o.status.success());
    compiled.then_some(driver)
}

/// Whole-process time and peak memory at `level` of `input` (written as an
/// OBJ file with its tags and UVs, refined with its options, UVs included),
/// no output file: `subdiv refine` natively (on `threads` threads, and as
/// typed on every core when that differs), with `--engine osd`, and, with
/// `driver` ([`compile_driver`]), an equivalent C++ program against
/// OpenSubdiv. Medians of interleaved runs.
pub(crate) fn whole_process(
    input: &BenchShape,
    level: u32,
    quick: bool,
    threads: usize,
    driver: Option<&std::path::Path>,
) -> Result<WholeProcess, String> {
    use std::process::Command;
    let dir = tempfile::tempdir().map_err(|e| format!("no temporary directory ({e})"))?;
    let obj = dir.path().join("input.obj");
    subdiv::io::write_mesh_obj(&obj, &input.mesh, Precision::F64).map_err(|e| e.to_string())?;
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    // Nine runs of each program: on this kind of virtual machine a process
    // now and then finds its fresh memory handed back to the host and takes
    // 2-4x its usual time, and once three of five such runs made the median
    // (160 ms where the runs before and after gave 54-66 ms).
    // Five on the big inputs, whose runs take seconds and vary less.
    let reps = if quick {
        3
    } else if input.mesh.face_count() > 100_000 {
        5
    } else {
        9
    };
    let o = &input.options;
    let level_arg = level.to_string();
    // The input's options, spelled the same for `subdiv refine` and the
    // driver.
    let options = [
        "--level",
        &level_arg,
        "--scheme",
        o.scheme.name(),
        "--boundary",
        o.boundary.name(),
        "--fvar",
        o.fvar.name(),
        "--creasing",
        o.creasing.name(),
        "--triangles",
        o.triangles.name(),
    ];
    // Every core, as `subdiv refine` runs when typed.
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let refine = |engine: &str, threads: Option<usize>| {
        let mut c = Command::new(&exe);
        c.arg("refine")
            .arg(&obj)
            .args(options)
            .args(["--engine", engine, "--peak-memory"]);
        match threads {
            Some(n) => c.env("RAYON_NUM_THREADS", n.max(1).to_string()),
            None => c.env_remove("RAYON_NUM_THREADS"),
        };
        c
    };
    let threads = threads.max(1);
    let mut programs = vec![(
        ProgramKind::Native,
        format!("subdiv refine --engine native, {threads} thread(s)"),
        refine("native", Some(threads)),
    )];
    if threads != cores {
        programs.push((
            ProgramKind::NativeAsTyped,
            format!("subdiv refine --engine native, every core ({cores})"),
            refine("native", None),
        ));
    }
    programs.push((
        ProgramKind::Osd,
        "subdiv refine --engine osd".into(),
        refine("osd", None),
    ));
    if let Some(driver) = driver {
        let mut c = Command::new(driver);
        c.arg(&obj).arg("-").args(options);
        programs.push((ProgramKind::Cpp, "C++ program against OpenSubdiv".into(), c));
    }
    let mut named: Vec<(String, Command)> = programs
        .iter_mut()
        .map(|(_, name, c)| (name.clone(), std::mem::replace(c, Command::new("true"))))
        .collect();
    let runs = interleaved_processes(&mut named, reps)?;
    Ok(WholeProcess {
        input: input.name.clone(),
        level,
        threads,
        cores,
        programs: programs
            .into_iter()
            .zip(runs)
            .map(|((kind, name, _), run)| ProgramResult {
                kind,
                name,
                seconds: run.seconds,
                peak_bytes: run.peak_bytes,
            })
            .collect(),
    })
}
