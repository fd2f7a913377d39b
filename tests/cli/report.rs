//! `subdiv report`, run as a user runs it: on a small OBJ file, on the
//! embedded set (quick), and on a corrupted file.

use crate::support::{scratch, stderr, stdout, subdiv};
use std::path::PathBuf;
use std::process::Output;

/// A tagged quad mesh with UVs split along a seam, a semi-sharp crease and a
/// corner: every kind of option applies to it.
const SHAPE: &str = "\
# a small test shape
v 0 0 0
v 1 0 0
v 2 0 0.2
v 0 1 0
v 1 1 0.5
v 2 1 0
v 0 2 0.1
v 1 2 0
v 2 2 0
vt 0 0
vt 0.5 0
vt 1 0
vt 0 0.5
vt 0.5 0.5
vt 1 0.5
vt 0 1
vt 0.5 1
vt 1 1
vt 0.6 0.5
vt 0.6 1
f 1/1 2/2 5/5 4/4
f 2/2 3/3 6/6 5/5
f 4/4 5/10 8/11 7/7
f 5/5 6/6 9/9 8/8
t crease 2/1/0 2 5 1.5
t corner 1/1/0 1 2.0
t interpolateboundary 1/0/0 2
";

/// Runs the report into a fresh directory; returns the output, report.md and report.html.
fn run_report(name: &str, extra: &[&str]) -> (Output, String, String, PathBuf) {
    let dir = scratch(&format!("report-{name}"));
    let out = dir.join("out");
    let mut args = vec!["report", "--quick", "--out", out.to_str().unwrap()];
    args.extend_from_slice(extra);
    let o = subdiv(&args);
    let md = std::fs::read_to_string(out.join("report.md")).unwrap_or_default();
    let html = std::fs::read_to_string(out.join("report.html")).unwrap_or_default();
    (o, md, html, out)
}

/// The page stands alone: no URL anywhere, no script, stylesheet link or image.
fn assert_self_contained(html: &str) {
    for bad in [
        "http://", "https://", "<script", "<link", "<img", "@import", "url(//",
    ] {
        assert!(!html.contains(bad), "report.html contains {bad:?}");
    }
    assert!(html.starts_with("<!DOCTYPE html>"));
    assert!(html.contains("<style>"));
    assert!(html.trim_end().ends_with("</html>"));
}

#[test]
fn report_on_an_obj_file() {
    let dir = scratch("report-obj-input");
    let shape = dir.join("seam-crease.obj");
    std::fs::write(&shape, SHAPE).unwrap();
    let (o, md, html, out) = run_report("obj", &[shape.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "stderr: {}", stderr(&o));
    // Standard error is not a terminal here: one progress line per step,
    // numbered, the last one the total.
    let err = stderr(&o);
    let steps: Vec<&str> = err
        .lines()
        .filter(|l| l.starts_with("subdiv report: ["))
        .collect();
    let total = steps.len();
    assert!(total > 3, "{err}");
    for (k, line) in steps.iter().enumerate() {
        let prefix = format!("subdiv report: [{}/{total}] ", k + 1);
        assert!(line.starts_with(&prefix), "{line:?} in\n{err}");
    }
    assert!(steps[total - 3].contains("timing level 2"), "{err}");
    assert!(steps[total - 2].contains(": limit surface"), "{err}");
    assert!(
        steps[total - 1].contains("tessellated limit surface"),
        "{err}"
    );
    // The small shape gets the quick run's sets, and the report says so.
    assert!(md.contains("one option varied at a time"), "{md}");
    let summary = stdout(&o);
    assert!(summary.contains("seam-crease.obj"), "{summary}");
    assert!(summary.contains("CONFORMS"), "{summary}");
    for doc in [&md, &html] {
        assert!(doc.contains("seam-crease.obj"));
        assert!(doc.contains("CONFORMS"));
        assert!(
            doc.contains("Limit surface (patch tables at isolation 3"),
            "{doc}"
        );
        assert!(doc.contains("tables identical"), "{doc}");
        assert!(doc.contains("0 (bit-identical)"));
        assert!(!doc.contains("http"), "an external resource or link");
    }
    assert_self_contained(&html);
    // Five inline SVGs: deviation plot, time plot, picture of the shape,
    // picture of the limit surface (16 quads per ptex face: this shape's
    // four faces are quads without holes, 25 locations each), picture of
    // the Bfr tessellation (4 faces at rate 4, two triangles per quad).
    assert_eq!(html.matches("<svg").count(), 5);
    assert!(html.contains("128 facets at rate 4"), "{html}");
    assert!(html.contains("deviation from OpenSubdiv (log scale)"));
    assert!(html.contains("refine + positions: median time"));
    assert!(html.contains("native level 2, coloured by deviation"));
    assert!(html.contains("limit surface, coloured by deviation"));
    assert!(
        html.contains("64 quads between 100 evaluated locations"),
        "{html}"
    );
    // The options that apply to this mesh were varied: boundary, creasing,
    // triangles (none here), face-varying modes.
    for mode in ["corners-only", "boundaries", "chaikin", "edge-and-corner"] {
        assert!(md.contains(mode), "{mode} not compared");
    }
    // The Markdown's figures exist as files.
    for kind in ["deviation", "time", "shape", "limit"] {
        let f = out
            .join("figures")
            .join(format!("01-seam-crease-obj-{kind}.svg"));
        assert!(md.contains(&format!("figures/01-seam-crease-obj-{kind}.svg")));
        assert!(std::fs::read_to_string(&f).unwrap().starts_with("<svg"));
    }
    // No temporary files left behind.
    for entry in std::fs::read_dir(&out).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        assert!(!name.ends_with(".tmp"), "{name}");
    }
}

#[test]
fn report_on_the_embedded_set() {
    let (o, md, html, _) = run_report("embedded", &[]);
    assert_eq!(o.status.code(), Some(0), "stderr: {}", stderr(&o));
    let names = [
        "cube",
        "torus",
        "creased-box",
        "pole",
        "holes",
        "cube-uv",
        "grid-uv-regions",
        "four-boxes",
        "icosahedron",
        "bilinear-prism",
        "fin",
    ];
    let summary = stdout(&o);
    for name in names {
        assert!(summary.contains(name), "{name} not in the summary");
        assert!(
            md.contains(&format!("## {name}")),
            "{name} not in report.md"
        );
        assert!(
            html.contains(&format!("<section id=\"input-{name}\">")),
            "{name} not in report.html"
        );
    }
    assert_self_contained(&html);
    assert!(!md.contains("http"));
    // Three figures per input, the limit surface's and the Bfr
    // tessellation's: every embedded input has both.
    let limit = html
        .matches("<title>limit surface, coloured by deviation</title>")
        .count();
    assert_eq!(limit, names.len(), "limit-surface pictures");
    let tessellated = html
        .matches("<title>tessellated limit surface (Bfr), coloured by deviation</title>")
        .count();
    assert_eq!(tessellated, names.len(), "tessellation pictures");
    assert!(
        md.contains("Tessellated limit surface (Bfr, rate 4"),
        "{md}"
    );
    assert!(!md.contains("DIFFERS"), "{md}");
    assert_eq!(
        html.matches("<svg").count(),
        3 * names.len() + limit + tessellated
    );
    assert!(html.contains("class=\"verdict pass\""));
    assert!(html.contains("OpenSubdiv"));
    assert!(html.contains("Machine"));
    // Loop on the icosahedron, bilinear, and all six face-varying modes on the UV meshes.
    for needle in ["| loop |", "| bilinear |", "| corners-plus2 |", "| none |"] {
        assert!(md.contains(needle), "{needle} not compared");
    }
}

#[test]
fn a_corrupted_obj_is_an_error_with_file_and_line() {
    let dir = scratch("report-corrupted");
    let bad = dir.join("bad.obj");
    std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nv 1 oops 0\nf 1 2 3\n").unwrap();
    let (o, _, html, out) = run_report("corrupted-out", &[bad.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(err.contains("bad.obj:3"), "{err}");
    assert!(html.is_empty() && !out.join("report.html").exists());

    // A face naming a missing vertex: also line-numbered.
    std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 4\n").unwrap();
    let o = subdiv(&[
        "report",
        "--quick",
        "--out",
        out.to_str().unwrap(),
        bad.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("bad.obj:4"), "{}", stderr(&o));

    // A missing file.
    let missing = dir.join("missing.obj");
    let o = subdiv(&[
        "report",
        "--quick",
        "--out",
        out.to_str().unwrap(),
        missing.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("missing.obj"));

    // A bad level range is refused by the parser.
    let o = subdiv(&["report", "--levels", "3..1"]);
    assert_eq!(o.status.code(), Some(2));
}

/// `bench --processes-only` on a user's file: the whole processes at levels
/// 1 and 2 (native on one thread and as typed, `--engine osd`, the C++
/// program against OpenSubdiv, each with its peak memory) and the OBJ
/// reader, nothing measured in process; bench.json holds the same runs.
#[test]
fn bench_processes_only_on_an_obj_file() {
    let dir = scratch("bench-processes-only");
    let shape = dir.join("seam-crease.obj");
    std::fs::write(&shape, SHAPE).unwrap();
    let out = dir.join("bench");
    let o = subdiv(&[
        "bench",
        shape.to_str().unwrap(),
        "--processes-only",
        "--quick",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    assert!(!text.contains("| input | scheme |"), "{text}");
    for level in [1, 2] {
        let head = format!("Whole process, seam-crease.obj at level {level}, no output file");
        let at = text.find(&head).unwrap_or_else(|| panic!("{text}"));
        let block: Vec<&str> = text[at..].lines().skip(1).take(4).collect();
        let programs = [
            "subdiv refine --engine native, 1 thread(s): ",
            "subdiv refine --engine native, every core",
            "subdiv refine --engine osd: ",
            "C++ program against OpenSubdiv: ",
        ];
        // Every core is a second native run only where there are several.
        let programs: Vec<&str> = programs
            .into_iter()
            .filter(|p| !p.contains("every core") || block[1].contains("every core"))
            .collect();
        for (line, program) in block.iter().zip(&programs) {
            assert!(line.trim_start().starts_with(program), "{line}\n{text}");
            assert!(line.contains(" ms, peak memory "), "{line}");
        }
    }
    assert!(text.contains("OBJ reader (seam-crease.obj"), "{text}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("bench.json")).unwrap()).unwrap();
    let runs = json["whole_process"].as_array().unwrap();
    assert_eq!(runs.len(), 2);
    assert_eq!(
        (runs[0]["level"].as_u64(), runs[1]["level"].as_u64()),
        (Some(1), Some(2))
    );
    assert!(json["rows"].as_array().unwrap().is_empty());
    assert!(!out.join("time-per-level.svg").exists());
    // Only one kind of run at a time.
    let o = subdiv(&["bench", "--processes-only", "--adaptive-only"]);
    assert_eq!(o.status.code(), Some(2));
}
