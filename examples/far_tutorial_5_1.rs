//! OpenSubdiv's far tutorial 5_1 ("limit surface evaluation using patch
//! tables") with the native engine: the same pyramid (four triangles around
//! a quad, its base edges creased to 3), refined adaptively to level 3,
//! its patch table with Gregory basis end caps and infinitely sharp
//! patches in double precision, and 200 samples per ptex face at the
//! tutorial's pseudo-random (s, t) — glibc's `rand()` after
//! `srand(2147483647)` — printed as the same Maya MEL script, number for
//! number (`tests/far_tutorials.rs` holds it to OpenSubdiv's program,
//! `cpp/far_tutorials.cpp`).
//!
//! ```sh
//! cargo run --example far_tutorial_5_1 > limit.mel
//! ```

use glam::DVec3;
use subdiv::patches::{self, Derivatives, EndCapType, PatchOptions};
use subdiv::refiner::Refiner;
use subdiv::{BoundaryInterpolation, Crease, Mesh, Options};

/// glibc's `rand()` (the default TYPE_3 additive feedback generator:
/// `r[i] = r[i - 3] + r[i - 31]`, seeded by the Park-Miller generator, the
/// first 310 values dropped, the low bit shifted out), so that the samples
/// are the tutorial's.
struct GlibcRand {
    ring: Vec<u32>,
}

impl GlibcRand {
    /// `srand(seed)`.
    fn new(seed: u32) -> GlibcRand {
        let mut r: Vec<u32> = Vec::with_capacity(34 + 310);
        let mut word = if seed == 0 { 1 } else { seed as i32 };
        r.push(word as u32);
        for _ in 1..31 {
            // 16807 * word mod (2^31 - 1), by Schrage's method as glibc.
            let (hi, lo) = (word / 127_773, word % 127_773);
            word = 16_807 * lo - 2_836 * hi;
            if word < 0 {
                word += 2_147_483_647;
            }
            r.push(word as u32);
        }
        for i in 31..34 {
            r.push(r[i - 31]);
        }
        let mut g = GlibcRand { ring: r };
        for _ in 0..310 {
            g.step();
        }
        g
    }

    fn step(&mut self) -> u32 {
        let n = self.ring.len();
        let next = self.ring[n - 31].wrapping_add(self.ring[n - 3]);
        self.ring.push(next);
        if self.ring.len() > 64 {
            self.ring.drain(..self.ring.len() - 34);
        }
        next
    }

    /// `rand()`: 0..=2^31 - 1.
    fn rand(&mut self) -> u32 {
        self.step() >> 1
    }
}

fn main() -> Result<(), subdiv::Error> {
    print!("{}", run()?);
    Ok(())
}

/// The tutorial's output (tests/far_tutorials.rs compares it with
/// OpenSubdiv's program, `cpp/far_tutorials.cpp`).
pub fn run() -> Result<String, subdiv::Error> {
    // The tutorial's mesh: a pyramid, base edges creased to 3.
    let positions = vec![
        DVec3::new(0.0, 0.0, 2.0),
        DVec3::new(0.0, -2.0, 0.0),
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::new(0.0, 2.0, 0.0),
        DVec3::new(-2.0, 0.0, 0.0),
    ];
    let mut mesh = Mesh::from_faces(
        positions,
        &[
            &[0, 1, 2],
            &[0, 2, 3],
            &[0, 3, 4],
            &[0, 4, 1],
            &[4, 3, 2, 1],
        ],
    );
    for vertices in [[4, 3], [3, 2], [2, 1], [1, 4]] {
        mesh.creases.push(Crease {
            vertices,
            sharpness: 3.0,
        });
    }
    let options = Options::default().with_boundary(BoundaryInterpolation::EdgeOnly);

    // Patch options first; the adaptive refinement follows from them.
    let patch_options = PatchOptions {
        varying_tables: false,
        ..PatchOptions::new()
            .max_isolation(3)
            .double_precision(true)
            .inf_sharp_patch(true)
            .end_caps(EndCapType::GregoryBasis)
    };
    let refiner = Refiner::new(&mesh, &options)?
        .refine_adaptive(patch_options.refine_adaptive_options(), &[])?;
    let table = refiner.patch_table(&patch_options, &[])?;

    // Every level's vertices, then the local points.
    let points = refiner.patch_points(&table, 3, &mesh.flat_positions())?;

    // 200 samples on each ptex face.
    let per_face = 200;
    let mut rng = GlibcRand::new(2_147_483_647);
    let rand_max = f64::from(i32::MAX);
    let mut locations = Vec::with_capacity(per_face * table.ptex_faces);
    for face in 0..table.ptex_faces as u32 {
        for _ in 0..per_face {
            let s = f64::from(rng.rand()) / rand_max;
            let t = f64::from(rng.rand()) / rand_max;
            locations.push((face, s, t));
        }
    }
    let samples = patches::evaluate(&table, &points, 3, &locations, Derivatives::First)?;
    let v = &samples.values;

    // The tutorial's MEL script: particles at the limit points, streaks
    // along the two derivatives.
    let n = locations.len();
    let triple =
        |x: &[f64], i: usize| format!("{:.6} {:.6} {:.6}", x[3 * i], x[3 * i + 1], x[3 * i + 2]);
    let mut out = String::new();
    out.push_str("file -f -new;\n");
    for (name, derivative) in [("deriv1", &v.du), ("deriv2", &v.dv)] {
        out.push_str(&format!("particle -n {name} "));
        for i in 0..n {
            out.push_str(&format!("-p {}\n", triple(&v.point, i)));
        }
        out.push_str(";\n");
        out.push_str(&format!("setAttr \"{name}.particleRenderType\" 6;\n"));
        out.push_str(&format!(
            "setAttr \"{name}.velocity\" -type \"vectorArray\" {n} "
        ));
        for i in 0..n {
            out.push_str(&format!("{}\n", triple(derivative, i)));
        }
        out.push_str(";\n");
    }
    out.push_str("currentTime -edit `currentTime -q`;\n");
    out.push_str("select deriv1Shape deriv2Shape;\n");
    Ok(out)
}
