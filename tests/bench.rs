//! The parallel-use section of `subdiv bench` on tiny inputs: its rows are
//! there, with positive times, after the engines' results were checked
//! equal. Structure only: nothing here asserts a timing.
#![cfg(feature = "osd")]

use subdiv::bench::{self, BenchInput, Report};
use subdiv::{Scheme, shapes};

fn pool() -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap()
}

#[test]
fn deformed_frames_are_distinct_and_finite() {
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
fn parallel_rows_on_tiny_inputs() {
    let pool = pool();
    let input = BenchInput {
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

    let report = Report {
        machine: "test".into(),
        threads: 2,
        bandwidth: 1e9,
        rows: Vec::new(),
        stencil_bandwidth: None,
        parallel: vec![f, m],
    };
    let text = report.markdown("today");
    assert!(text.contains("| frames (3, level 2) |"), "{text}");
    assert!(text.contains("| meshes (4, level 2) |"), "{text}");
    assert!(text.contains("Parallel use (2 thread(s)"), "{text}");
    assert!(
        text.contains("frames/s") && text.contains("meshes/s"),
        "{text}"
    );
    let json = serde_json::to_value(&report).unwrap();
    assert_eq!(json["parallel"][0]["task"], "frames (3, level 2)");
    assert_eq!(json["parallel"][1]["count"], 4);
    // The plots filter on the other tasks and still render.
    assert!(report.svg_time_per_level().ends_with("</svg>\n"));
    assert!(report.svg_rate_vs_bandwidth().ends_with("</svg>\n"));
}
