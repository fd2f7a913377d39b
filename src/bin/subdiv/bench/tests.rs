//! The parallel-use section of `subdiv bench` on tiny inputs: its rows are
//! there, with positive times, after the engines' results were checked
//! equal; and the runner of its whole-process section. Structure only:
//! nothing here asserts a timing beyond a program's own sleep.
use super::results::{AloneRow, BenchReport};
use crate::bench;
use subdiv::shapes::BenchShape;
use subdiv::{Scheme, shapes};

pub(crate) fn pool() -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap()
}

#[test]
pub(crate) fn deformed_frames_are_distinct_and_finite() {
    let torus = shapes::torus(6, 4);
    let frames = bench::deformed_frames(&torus, 4);
    assert_eq!(frames.len(), 4);
    for (i, f) in frames.iter().enumerate() {
        assert_eq!(f.len(), 3 * torus.positions.len());
        assert!(f.iter().all(|v| v.is_finite()));
        assert!(frames[i + 1..].iter().all(|g| g != f), "frame {i} repeats");
    }
}

#[test]
pub(crate) fn parallel_rows_on_tiny_inputs() {
    let pool = pool();
    let input = BenchShape {
        name: "torus 6x4 quads".into(),
        mesh: shapes::torus(6, 4),
        scheme: Scheme::Catmark,
        max_level: 2,
    };
    let frames = bench::deformed_frames(&input.mesh, 3);
    // frames_row refines once and checks the first frame bit for bit against
    // OpenSubdiv before timing: Ok means the check passed.
    let f = bench::frames_row(&pool, &input, &frames, 2, 1).unwrap();
    assert_eq!((f.unit.as_str(), f.count), ("frames", 3));
    assert_eq!(f.row.task, "frames (3, level 2)");
    assert_eq!(f.row.level, 2);
    // Level 2 of a 6x4 torus: 24 faces -> 96 -> 384, as many vertices.
    assert_eq!(f.row.vertices, 3 * 384);

    let meshes = bench::many_meshes(4, true);
    assert_eq!(meshes.len(), 4);
    let schemes: Vec<Scheme> = meshes.iter().map(|m| m.scheme).collect();
    assert_eq!(
        schemes,
        [
            Scheme::Catmark,
            Scheme::Catmark,
            Scheme::Loop,
            Scheme::Catmark
        ]
    );
    let m = bench::meshes_row(&pool, &meshes, 2, 1).unwrap();
    assert_eq!((m.unit.as_str(), m.count), ("meshes", 4));
    assert_eq!(m.row.task, "meshes (4, level 2)");
    assert_eq!(m.row.scheme, "catmark+loop");
    assert!(m.row.vertices > 0);

    for p in [&f, &m] {
        assert!(p.row.native > 0.0 && p.row.osd > 0.0, "{p:?}");
        let (rn, ro) = p.rates();
        assert!(rn > 0.0 && ro > 0.0);
    }

    let report = BenchReport {
        machine: "test".into(),
        threads: 2,
        bandwidth: 1e9,
        rows: Vec::new(),
        stencil_bandwidth: None,
        parallel: vec![f, m],
        osd_alone: vec![AloneRow {
            input: "torus".into(),
            scheme: "loop".into(),
            level: 4,
            alone: 0.0875,
            interleaved: 0.0894,
        }],
    };
    let text = report.markdown("today");
    assert!(text.contains("| frames (3, level 2) |"), "{text}");
    assert!(text.contains("| meshes (4, level 2) |"), "{text}");
    assert!(text.contains("Parallel use (2 thread(s)"), "{text}");
    assert!(
        text.contains("- torus (loop, level 4): alone 87.5 ms, interleaved 89.4 ms"),
        "{text}"
    );
    assert!(
        text.contains("frames/s") && text.contains("meshes/s"),
        "{text}"
    );
    let json = serde_json::to_value(&report).unwrap();
    assert_eq!(json["parallel"][0]["task"], "frames (3, level 2)");
    assert_eq!(json["parallel"][1]["count"], 4);
    assert_eq!(json["osd_alone"][0]["alone"], 0.0875);
    // The plots filter on the other tasks and still render.
    assert!(report.svg_time_per_level().ends_with("</svg>\n"));
    assert!(report.svg_rate_vs_bandwidth().ends_with("</svg>\n"));
}

/// The whole-process runner keeps each program's results with it whatever
/// the order it ran them in, reads the peak memory each reports, and names a
/// program that fails.
#[test]
fn whole_processes_run_interleaved_and_keep_their_results() {
    use std::process::Command;
    let shell = |script: &str| {
        let mut c = Command::new("sh");
        c.args(["-c", script]);
        c
    };
    let mut programs = vec![
        (
            "slow".to_string(),
            shell("sleep 0.2; echo peak_memory_bytes 7 >&2"),
        ),
        (
            "middle".to_string(),
            shell("echo peak_memory_bytes 2000000 >&2"),
        ),
        ("fast".to_string(), shell("echo peak_memory_bytes 5 >&2")),
    ];
    let runs = bench::interleaved_processes(&mut programs, 3).unwrap();
    assert_eq!(runs.len(), 3);
    assert_eq!(runs[0].peak_bytes, 7);
    assert!(runs[0].seconds >= 0.2, "{runs:?}");
    assert_eq!(runs[1].peak_bytes, 2_000_000, "{runs:?}");
    assert!(runs[1].seconds > 0.0);
    assert_eq!(runs[2].peak_bytes, 5);
    assert!(runs[2].seconds < runs[0].seconds, "{runs:?}");

    let mut failing = vec![
        ("fine".to_string(), shell("true")),
        ("broken".to_string(), shell("exit 3")),
    ];
    let e = bench::interleaved_processes(&mut failing, 2).unwrap_err();
    assert!(e.to_string().contains("broken failed"), "{e}");
    let mut missing = vec![("absent".to_string(), Command::new("/nonexistent/program"))];
    let e = bench::interleaved_processes(&mut missing, 1).unwrap_err();
    assert!(e.to_string().contains("absent could not start"), "{e}");
}
