//! Exhausted memory is an error, never an abort: `subdiv` under address-space
//! limits (`ulimit -v`) that make its refinements run out of memory at
//! different points, with both engines and with limits and UVs (the
//! face-varying and limit paths allocate the most). Every run ends with exit
//! 0 or 1, and every failure is the typed "out of memory" or "refused"
//! error, never Rust's "memory allocation of N bytes failed" abort (exit 134).
//! (Unix only: `ulimit` in `sh`.)

use crate::support::{scratch, subdiv_bin};
use std::process::Command;

#[test]
fn exhausted_memory_is_an_error_not_an_abort() {
    let dir = scratch("memory-limits");
    let out = dir.join("out.obj");
    let out = out.to_str().unwrap();
    let subdiv = subdiv_bin().display();
    let commands = [
        format!("{subdiv} refine --builtin cube-uv --level 7 --limit -o {out}"),
        format!("{subdiv} refine --builtin cube-uv --level 7 --limit --engine osd -o {out}"),
        format!("{subdiv} compare --builtin cube-uv --levels 7"),
    ];
    let (mut ok, mut out_of_memory) = (0, 0);
    // Every 20 MB: a small allocation after a large one that took nearly
    // all the room left aborted at one limit in a few dozen runs before
    // large allocations kept headroom (`alloc::headroom_after`).
    for kib in (60_000..=400_000).step_by(20_000) {
        for command in &commands {
            // `--engine osd` and `compare` need OpenSubdiv.
            let osd = command.contains("--engine osd") || command.contains(" compare ");
            if osd && !cfg!(feature = "osd") {
                continue;
            }
            let run = Command::new("sh")
                .arg("-c")
                .arg(format!("ulimit -v {kib} && exec {command}"))
                .env("RAYON_NUM_THREADS", "2")
                .output()
                .unwrap();
            let stderr = String::from_utf8_lossy(&run.stderr);
            let ctx = format!("ulimit -v {kib}; {command}: {:?}\n{stderr}", run.status);
            assert!(!stderr.contains("memory allocation of"), "{ctx}");
            match run.status.code() {
                Some(0) => ok += 1,
                Some(1) => {
                    assert!(
                        stderr.contains("out of memory") || stderr.contains("refused"),
                        "{ctx}"
                    );
                    out_of_memory += 1;
                }
                _ => panic!("{ctx}"),
            }
        }
    }
    // The limits span both outcomes: the failure path was exercised.
    assert!(
        ok > 0 && out_of_memory > 0,
        "ok {ok}, out of memory {out_of_memory}"
    );
}
