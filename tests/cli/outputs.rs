//! Where `subdiv` writes, as a pipeline uses it: through symlinks, to
//! standard output (`-o -`, `/dev/stdout`), never over its own input, with
//! errors that name the output as typed — and no temporary file left behind
//! when the job is killed with SIGTERM, SIGINT or SIGHUP part-way through a
//! large write.

use crate::support::{
    file_names as names, obj_text, scratch, stderr, stdout, subdiv, subdiv_bin, write,
};
use std::path::Path;
use subdiv::shapes;

#[cfg(unix)]
#[test]
fn a_symlink_is_written_through_and_the_input_is_never_the_output() {
    use std::os::unix::fs::symlink;
    let dir = scratch("outputs-symlink");
    let input = write(&dir, "in.obj", &obj_text(&shapes::cube()));
    let target = write(&dir, "target.obj", "old\n");
    let link = dir.join("link.obj");
    symlink("target.obj", &link).unwrap();
    let o = subdiv(&[
        "refine",
        input.to_str().unwrap(),
        "--level",
        "1",
        "-o",
        link.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // The link is still a link, and its target holds the refined cube.
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    let text = std::fs::read_to_string(&target).unwrap();
    assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 24);
    assert_eq!(names(&dir), ["in.obj", "link.obj", "target.obj"]);

    // -o naming the input, directly, by another spelling or through a link:
    // a usage error, and the input is untouched.
    let before = std::fs::read(&input).unwrap();
    let to_input = dir.join("to-input.obj");
    symlink("in.obj", &to_input).unwrap();
    let spelled = dir.join(".").join("in.obj");
    for out in [&input, &spelled, &to_input] {
        let o = subdiv(&[
            "refine",
            input.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert!(
            stderr(&o).contains("names the input file")
                && stderr(&o).contains("choose another output"),
            "{}",
            stderr(&o)
        );
    }
    assert_eq!(std::fs::read(&input).unwrap(), before);
    // The same for curve.
    let points = write(&dir, "points.txt", "0 0\n1 1\n2 0\n");
    let o = subdiv(&[
        "curve",
        points.to_str().unwrap(),
        "--scheme",
        "chaikin",
        "-o",
        points.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&points).unwrap(), "0 0\n1 1\n2 0\n");
}

#[test]
fn dash_and_dev_stdout_write_to_standard_output() {
    let dir = scratch("outputs-stdout");
    for out in ["-", "/dev/stdout"] {
        if out.starts_with("/dev") && !Path::new(out).exists() {
            continue;
        }
        let o = subdiv(&["refine", "--builtin", "cube", "--level", "1", "-o", out]);
        assert!(o.status.success(), "{out}: {}", stderr(&o));
        let text = stdout(&o);
        assert_eq!(
            text.lines().filter(|l| l.starts_with("v ")).count(),
            26,
            "{out}"
        );
        assert_eq!(
            text.lines().filter(|l| l.starts_with("f ")).count(),
            24,
            "{out}"
        );
    }
    let points = write(&dir, "points.txt", "0 0\n1 2\n3 2\n4 0\n");
    let o = subdiv(&[
        "curve",
        points.to_str().unwrap(),
        "--scheme",
        "jarek",
        "--level",
        "0",
        "-o",
        "-",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stdout(&o), "0 0\n1 2\n3 2\n4 0\n");
    assert_eq!(names(&dir), ["points.txt"]);
}

#[test]
fn output_errors_name_the_output_as_typed() {
    let dir = scratch("outputs-errors");
    let existing = dir.join("existing");
    std::fs::create_dir(&existing).unwrap();
    let as_dir = format!("{}/", existing.display());
    let missing = dir.join("missing/deeper/o.obj");
    let cases = [
        (
            as_dir.clone(),
            format!("subdiv: error: {as_dir}: it is a directory\n"),
        ),
        (
            missing.display().to_string(),
            format!(
                "subdiv: error: {}: the directory {} does not exist\n",
                missing.display(),
                dir.join("missing/deeper").display()
            ),
        ),
    ];
    for (out, message) in cases {
        let o = subdiv(&["refine", "--builtin", "cube", "-o", &out]);
        assert_eq!(o.status.code(), Some(1), "{out}");
        // Named as typed: neither the input's name in front nor a temporary path.
        assert_eq!(stderr(&o), message);
    }
    assert_eq!(names(&dir), ["existing"]);
    assert!(names(&existing).is_empty());
}

/// Starts `subdiv ARGS`, waits until its temporary output file appears in
/// `dir`, stops it there, sends `signal`, and lets it go on; returns how it
/// ended. The write is large (about 100 MB for refine) so that it is still
/// under way when it is stopped; the test fails, rather than passing
/// vacuously, if it was not.
#[cfg(unix)]
fn kill_during_write(args: &[&str], dir: &Path, signal: &str) -> std::process::ExitStatus {
    use std::process::{Command, Stdio};
    use std::time::{Duration, Instant};
    let mut child = Command::new(subdiv_bin())
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let pid = child.id().to_string();
    let kill = |sig: &str| {
        let ok = Command::new("kill")
            .args([format!("-{sig}").as_str(), &pid])
            .status()
            .unwrap()
            .success();
        assert!(ok, "kill -{sig} {pid}");
    };
    let temporary = || names(dir).into_iter().find(|n| n.ends_with(".tmp"));
    let start = Instant::now();
    loop {
        if temporary().is_some() {
            kill("STOP");
            break;
        }
        if let Some(status) = child.try_wait().unwrap() {
            panic!("{args:?} ended ({status}) before its temporary file was seen");
        }
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "no temporary file in {dir:?}"
        );
        std::thread::sleep(Duration::from_millis(2));
    }
    // Stopped while writing: the temporary file is there, the output is not.
    assert!(temporary().is_some(), "{:?}", names(dir));
    kill(signal);
    kill("CONT");
    child.wait().unwrap()
}

#[cfg(unix)]
#[test]
fn signals_during_a_large_write_leave_no_temporary_file() {
    use std::os::unix::process::ExitStatusExt;
    // refine: 40,000 quads to level 3, 2.6 million faces.
    let dir = scratch("outputs-signal-refine");
    let mut grid = shapes::grid(200, 200);
    grid.fvar_channels.clear();
    let input = write(&dir, "grid.obj", &obj_text(&grid));
    let out = dir.join("out.obj");
    for (engine, signal, number) in [("native", "TERM", 15), ("native", "HUP", 1)]
        .into_iter()
        .chain(cfg!(feature = "osd").then_some(("osd", "INT", 2)))
    {
        let args = [
            "refine",
            input.to_str().unwrap(),
            "--level",
            "3",
            "--engine",
            engine,
            "-o",
            out.to_str().unwrap(),
        ];
        let status = kill_during_write(&args, &dir, signal);
        // Ended by the signal itself, as a shell expects (128 + N there).
        assert_eq!(
            status.signal(),
            Some(number),
            "{engine}, SIG{signal}: {status}"
        );
        assert_whole_or_absent(&dir, "grid.obj", "out.obj", |text| {
            text.lines().filter(|l| l.starts_with("f ")).count() == 40_000 * 64
        });
        let _ = std::fs::remove_file(&out);
    }
    // curve: Chaikin to about two million points.
    let dir = scratch("outputs-signal-curve");
    let points = write(&dir, "points.txt", "0 0\n1 2\n3 2\n4 0\n");
    let out = dir.join("curve.txt");
    let args = [
        "curve",
        points.to_str().unwrap(),
        "--scheme",
        "chaikin",
        "--level",
        "19",
        "-o",
        out.to_str().unwrap(),
    ];
    let status = kill_during_write(&args, &dir, "INT");
    assert_eq!(status.signal(), Some(2), "{status}");
    let corners = [
        glam::DVec2::ZERO,
        glam::DVec2::new(1.0, 2.0),
        glam::DVec2::new(3.0, 2.0),
        glam::DVec2::new(4.0, 0.0),
    ];
    let n = subdiv::curve::refine(&corners, subdiv::curve::CurveScheme::Chaikin, false, 19)
        .unwrap()
        .len();
    assert_whole_or_absent(&dir, "points.txt", "curve.txt", |text| {
        text.lines().count() == n && text.ends_with('\n')
    });
}

/// After a signal: no temporary file in `dir`, only `input` — or also
/// `output`, whole (`whole` says so), if the signal reached the process only
/// after the rename (the handler sets its flag at once, so in practice the
/// output is abandoned: the rename waits for the end of a long write).
#[cfg(unix)]
fn assert_whole_or_absent(dir: &Path, input: &str, output: &str, whole: impl Fn(&str) -> bool) {
    let left = names(dir);
    if left == [input] {
        return;
    }
    let mut expected = vec![input.to_string(), output.to_string()];
    expected.sort();
    assert_eq!(left, expected, "a temporary file was left behind");
    let text = std::fs::read_to_string(dir.join(output)).unwrap();
    assert!(whole(&text), "{output} appeared half-written");
}
