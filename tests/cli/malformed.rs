//! The malformed corpus (`tests/malformed/`, [`crate::support::malformed`])
//! through the command line: `subdiv refine` and `subdiv curve` exit 1 with
//! `subdiv: error: FILE:LINE: message` on stderr and leave no output file
//! (nor a temporary one) behind; absurd levels are refused before anything
//! is allocated; a mesh OpenSubdiv would assert on never aborts the process.
//! What the library says of each file is tested in `tests/malformed.rs`.

use crate::engines;
use crate::support::malformed::{curve_errors, curve_too_few, file, obj_errors};
use crate::support::{obj_text, refine_to, scratch, stderr, subdiv, write};
use std::path::Path;
use std::process::Output;
use subdiv::shapes;

/// Asserts that a command failed with exit status 1 and wrote nothing into `dir`.
fn assert_failed_cleanly(o: &Output, dir: &Path, what: &str) {
    assert_eq!(o.status.code(), Some(1), "{what}: {}", stderr(o));
    let left: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert!(left.is_empty(), "{what}: files left behind: {left:?}");
}

#[test]
fn refine_names_file_and_line_and_writes_nothing() {
    for (name, line, _, message) in obj_errors() {
        let path = file(name);
        for engine in engines() {
            let dir = scratch(&format!("malformed-refine-{name}-{engine}"));
            let out = dir.join("out.obj");
            let o = refine_to(&path, engine, &out, &[]);
            assert_failed_cleanly(&o, &dir, &format!("{name} ({engine})"));
            assert_eq!(
                stderr(&o),
                format!("subdiv: error: {}:{line}: {message}\n", path.display()),
                "{name} ({engine})"
            );
        }
    }
    // `compare` reads the same way.
    let path = file("tag_boundary_unknown_value.obj");
    let o = subdiv(&["compare", path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).starts_with(&format!("subdiv: error: {}:6: ", path.display())),
        "{}",
        stderr(&o)
    );
}

#[test]
fn refuses_unusable_files_and_writes_nothing() {
    for name in ["empty.obj", "comments_only.obj"] {
        let path = file(name);
        for engine in engines() {
            let dir = scratch(&format!("malformed-unusable-{name}-{engine}"));
            let out = dir.join("out.obj");
            let o = refine_to(&path, engine, &out, &[]);
            assert_failed_cleanly(&o, &dir, &format!("{name} ({engine})"));
        }
    }
    let path = file("tag_unknown.obj");
    let dir = scratch("malformed-strict-unknown-tag");
    let out = dir.join("out.obj");
    let o = subdiv(&[
        "refine",
        path.to_str().unwrap(),
        "--strict",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_failed_cleanly(&o, &dir, "--strict with an unknown tag");
    assert!(
        stderr(&o).contains("unknown tag 'foo'") && stderr(&o).contains("tag_unknown.obj:7: "),
        "{}",
        stderr(&o)
    );
    // Without --strict: a warning naming the line, and the output.
    let o = subdiv(&[
        "refine",
        path.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.exists());
    assert!(stderr(&o).contains("line 7: unknown tag 'foo'"));
}

#[test]
fn names_the_file_of_unusable_input() {
    // The same message from both engines.
    let message = "the mesh has no faces: there is nothing to refine";
    for name in ["empty.obj", "comments_only.obj"] {
        let path = file(name);
        for engine in engines() {
            let o = subdiv(&["refine", path.to_str().unwrap(), "--engine", engine]);
            assert_eq!(o.status.code(), Some(1));
            assert_eq!(
                stderr(&o),
                format!("subdiv: error: {}: {message}\n", path.display()),
                "{name} ({engine})"
            );
        }
    }
}

#[test]
fn names_the_line_of_a_face_too_large() {
    let path = file("face_70000_corners.obj");
    for engine in engines() {
        let o = subdiv(&["refine", path.to_str().unwrap(), "--engine", engine]);
        assert_eq!(o.status.code(), Some(1));
        let want = format!("subdiv: error: {}:5: ", path.display());
        assert!(
            stderr(&o).starts_with(&want),
            "({engine}): wanted '{want}...', got {}",
            stderr(&o)
        );
        assert_eq!(
            stderr(&o),
            format!("{want}face has 70000 corners; at most 65535 are supported\n")
        );
    }
}

#[test]
fn strict_warning_is_file_colon_line() {
    let path = file("tag_unknown.obj");
    let o = subdiv(&["refine", path.to_str().unwrap(), "--strict"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).starts_with(&format!("subdiv: error: {}:7: ", path.display())),
        "{}",
        stderr(&o)
    );
}

#[test]
fn curve_names_file_and_line_and_writes_nothing() {
    let mut cases: Vec<(&str, Vec<&str>, usize, &str)> = curve_errors()
        .into_iter()
        .map(|(name, line, _, message)| (name, vec!["--scheme", "chaikin"], line, message))
        .collect();
    for (name, _, flags, _, _, _, line, message) in curve_too_few() {
        cases.push((name, flags.to_vec(), line, message));
    }
    for (name, flags, line, message) in cases {
        let path = file(name);
        for output in ["out.txt", "out.svg"] {
            let dir = scratch(&format!(
                "malformed-curve-{name}-{}-{output}",
                flags.join("")
            ));
            let out = dir.join(output);
            let mut args = vec!["curve", path.to_str().unwrap()];
            args.extend(&flags);
            args.extend(["-o", out.to_str().unwrap()]);
            let o = subdiv(&args);
            assert_failed_cleanly(&o, &dir, &format!("{name} {flags:?} -> {output}"));
            assert_eq!(
                stderr(&o),
                format!("subdiv: error: {}:{line}: {message}\n", path.display()),
                "{name} {flags:?}"
            );
        }
    }
}

#[test]
fn binary_curve_file_is_refused() {
    let path = file("curve_binary_garbage.txt");
    let dir = scratch("malformed-curve-binary");
    let out = dir.join("out.txt");
    let o = subdiv(&[
        "curve",
        path.to_str().unwrap(),
        "--scheme",
        "chaikin",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_failed_cleanly(&o, &dir, "binary curve file");
}

/// MemAvailable of /proc/meminfo in bytes.
fn available_memory() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    Some(line.split_whitespace().nth(1)?.parse::<f64>().ok()? * 1024.0)
}

#[test]
fn absurd_levels_are_refused_before_allocating() {
    // Level 11 of anything.
    for engine in engines() {
        let dir = scratch(&format!("malformed-level11-{engine}"));
        let out = dir.join("out.obj");
        let o = subdiv(&[
            "refine",
            "--builtin",
            "cube",
            "--engine",
            engine,
            "--level",
            "11",
            "-o",
            out.to_str().unwrap(),
        ]);
        // A usage error (exit 2), refused while parsing the arguments.
        assert_eq!(o.status.code(), Some(2), "{engine}: {}", stderr(&o));
        assert!(
            stderr(&o).contains(
                "invalid value '11' for '--level <LEVEL>': level 11 is deeper than the supported 10"
            ),
            "{}",
            stderr(&o)
        );
        assert!(
            std::fs::read_dir(&dir).unwrap().next().is_none(),
            "{engine}"
        );
    }

    // 1900 quads: level 10 needs more than 32-bit indices; level 9 fits them
    // (about 2e9 face corners) but needs about 140 GiB.
    let dir = scratch("malformed-big-levels");
    let mut grid = shapes::grid(50, 38);
    grid.fvar_channels.clear();
    let input = write(&dir, "grid.obj", &obj_text(&grid));
    for engine in engines() {
        let o = subdiv(&[
            "refine",
            input.to_str().unwrap(),
            "--engine",
            engine,
            "--level",
            "10",
        ]);
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        // The error names the input, then the refusal.
        assert_eq!(
            stderr(&o),
            format!(
                "subdiv: error: {}: refinement level 10 refused: the level has about \
                 7.969e9 face corners, more than 32-bit indices address\n",
                input.display()
            )
        );
        if available_memory().is_some_and(|m| m < 1.0e11) {
            let o = subdiv(&[
                "refine",
                input.to_str().unwrap(),
                "--engine",
                engine,
                "--level",
                "9",
            ]);
            assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
            let err = stderr(&o);
            // Refused by the estimate (the message says so), not by an
            // allocation failing part-way.
            assert!(
                err.starts_with(&format!(
                    "subdiv: error: {}: refinement level 9 refused: the level needs about ",
                    input.display()
                )) && err.contains(" GiB, more than the "),
                "{err}"
            );
        }
    }
}

/// A face naming a vertex twice can leave it "smooth" with unpaired faces
/// and edges; OpenSubdiv's own assertion would abort on it. The bridge refuses
/// the mesh before OpenSubdiv sees it (`tests/malformed.rs`), so the CLI exits 1.
#[cfg(feature = "osd")]
#[test]
fn repeated_vertex_does_not_abort_subdiv_refine() {
    let path = file("osd_abort_repeated_vertex.obj");
    // In a child process: an abort must not take the test binary down.
    let dir = scratch("malformed-repeated-vertex");
    let out = dir.join("out.obj");
    let o = refine_to(&path, "osd", &out, &["--level", "1"]);
    assert!(
        matches!(o.status.code(), Some(1)),
        "subdiv refine --engine osd died: {:?}\n{}",
        o.status,
        stderr(&o)
    );
}

/// A semi-sharp corner or crease hides the unpaired vertex until its
/// sharpness decays; the check runs at every level, so both engines refuse
/// it (exit 1) instead of OpenSubdiv's assertion aborting the process.
#[cfg(feature = "osd")]
#[test]
fn repeated_vertex_with_decaying_sharpness_does_not_abort() {
    for name in [
        "osd_abort_repeated_vertex_semisharp.obj",
        "osd_abort_repeated_vertex_creases.obj",
    ] {
        let path = file(name);
        for level in ["1", "2", "3"] {
            for extra in [&[][..], &["--limit"][..]] {
                // In a child process: an abort must not take the test binary down.
                let mut args = vec![
                    "refine",
                    path.to_str().unwrap(),
                    "--engine",
                    "osd",
                    "--level",
                    level,
                ];
                args.extend(extra);
                let o = subdiv(&args);
                assert!(
                    matches!(o.status.code(), Some(1)) && stderr(&o).contains("do not pair up"),
                    "{name} level {level} {extra:?}: subdiv refine --engine osd died: {:?}\n{}",
                    o.status,
                    stderr(&o)
                );
            }
        }
    }
}
