//! The ports of OpenSubdiv's far tutorials 5_1, 5_2 and 5_3
//! (`examples/far_tutorial_5_*.rs`) against OpenSubdiv's programs
//! (`cpp/far_tutorials.cpp`, compiled against libosdCPU; it prints what the
//! tutorials print, byte for byte, checked against the tutorials built
//! from OpenSubdiv's sources on 2026-11-28): the same lines, words and
//! numbers — 5_1 (double precision, like the tutorial), 5_2 and 5_3 (in
//! `f32`, like the tutorials) identical; and 5_3's limit stencils
//! (`far_tutorials 5_3_weights`) OpenSubdiv's `float` weights bit for bit.
#![cfg(feature = "osd")]

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

#[path = "../examples/far_tutorial_5_1.rs"]
#[allow(dead_code)]
mod tutorial_5_1;
#[path = "../examples/far_tutorial_5_2.rs"]
#[allow(dead_code)]
mod tutorial_5_2;
#[path = "../examples/far_tutorial_5_3.rs"]
#[allow(dead_code)]
mod tutorial_5_3;

const SOURCE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/cpp/far_tutorials.cpp");

/// OpenSubdiv's tutorials, compiled once per test run.
fn reference() -> &'static Path {
    static EXE: OnceLock<PathBuf> = OnceLock::new();
    EXE.get_or_init(|| {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR"));
        std::fs::create_dir_all(dir).expect("create CARGO_TARGET_TMPDIR");
        let exe = dir.join("far_tutorials");
        // Built under a per-process name, then renamed: a test process
        // running at the same time never sees a half-written executable.
        let tmp = dir.join(format!("far_tutorials.{}.tmp", std::process::id()));
        let out = Command::new("g++")
            .args(["-std=c++14", "-O2", SOURCE, "-losdCPU", "-o"])
            .arg(&tmp)
            .output()
            .expect("run g++ (is it installed?)");
        assert!(
            out.status.success(),
            "compiling {SOURCE} failed:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
        std::fs::rename(&tmp, &exe).expect("install the reference tutorials");
        exe
    })
}

/// What OpenSubdiv's tutorial `name` prints.
fn osd(name: &str) -> String {
    let out = Command::new(reference()).arg(name).output().unwrap();
    assert!(out.status.success(), "far_tutorials {name}: {}", out.status);
    String::from_utf8(out.stdout).unwrap()
}

/// The largest difference between the numbers of `ours` and `theirs`,
/// which must have the same lines and the same words where a word is not
/// a number with a decimal point.
fn compare(ours: &str, theirs: &str) -> f64 {
    let (a, b): (Vec<&str>, Vec<&str>) = (ours.lines().collect(), theirs.lines().collect());
    assert_eq!(a.len(), b.len(), "line counts");
    let mut largest = 0.0f64;
    for (n, (x, y)) in a.iter().zip(&b).enumerate() {
        let (wx, wy): (Vec<&str>, Vec<&str>) = (x.split(' ').collect(), y.split(' ').collect());
        assert_eq!(wx.len(), wy.len(), "line {}: {x:?} against {y:?}", n + 1);
        for (p, q) in wx.iter().zip(&wy) {
            match (p.contains('.'), p.parse::<f64>(), q.parse::<f64>()) {
                (true, Ok(p), Ok(q)) => largest = largest.max((p - q).abs()),
                _ => assert_eq!(p, q, "line {}: {x:?} against {y:?}", n + 1),
            }
        }
    }
    largest
}

#[test]
fn tutorial_5_1_prints_the_same_script() {
    let ours = tutorial_5_1::run().unwrap();
    let theirs = osd("5_1");
    // 13 ptex faces (the quad and three per triangle), 200 samples each,
    // two particle sets of positions and velocities, 9 other lines.
    assert_eq!(ours.lines().count(), 13 * 200 * 4 + 9);
    let e = compare(&ours, &theirs);
    assert_eq!(ours, theirs, "largest difference {e:e}");
}

/// 5_2 computes in f32 as the tutorial does: the refined levels, the local
/// points, the basis weights (`evaluate_basis_in::<f32>`, in OpenSubdiv's
/// operation order) and the sums, each OpenSubdiv's bit for bit.
#[test]
fn tutorial_5_2_prints_the_same_tessellation() {
    let ours = tutorial_5_2::run().unwrap();
    let theirs = osd("5_2");
    // 10 groups, 6,000 faces: 5 vertices and 4 triangles each.
    assert_eq!(ours.lines().count(), 10 + 6000 * 9);
    let e = compare(&ours, &theirs);
    assert_eq!(ours, theirs, "largest difference {e:e}");
}

/// 5_3 computes in f32 as the tutorial does: the limit stencils with
/// every weight in f32 (`LimitStencilOptions::precision`, as
/// `LimitStencilTableFactory<float>`), applied in f32.
#[test]
fn tutorial_5_3_prints_the_same_limit_points() {
    let ours = tutorial_5_3::run().unwrap();
    let theirs = osd("5_3");
    assert_eq!(ours.lines().count(), 1 + 30 + 24);
    let e = compare(&ours, &theirs);
    assert_eq!(ours, theirs, "largest difference {e:e}");
}

/// The stencils of 5_3 themselves, with first derivatives: OpenSubdiv's
/// `float` weights bit for bit, position, du and dv, term by term.
#[test]
fn tutorial_5_3_stencil_weights_are_opensubdivs_floats() {
    let stencils = tutorial_5_3::stencils(true).unwrap();
    let w = &stencils.weights;
    let bits = |x: f64| (x as f32).to_bits();
    let mut ours = String::new();
    for (s, (&offset, &size)) in stencils.offsets.iter().zip(&stencils.sizes).enumerate() {
        ours.push_str(&format!("{s}:"));
        for k in offset as usize..(offset + size) as usize {
            // Each weight an f32 value, widened exactly.
            for x in [w.point[k], w.du[k], w.dv[k]] {
                assert_eq!(f64::from(x as f32), x);
            }
            ours.push_str(&format!(
                " {}={:08x},{:08x},{:08x}",
                stencils.indices[k],
                bits(w.point[k]),
                bits(w.du[k]),
                bits(w.dv[k])
            ));
        }
        ours.push('\n');
    }
    let theirs = osd("5_3_weights");
    // 30 stencils of the cube's 8 vertices.
    assert_eq!(theirs.lines().count(), 30);
    assert_eq!(stencils.indices.len(), 240);
    assert_eq!(ours, theirs);
}
