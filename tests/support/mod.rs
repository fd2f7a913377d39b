//! What the integration tests share: running the `subdiv` binary, scratch
//! directories, a deterministic random generator, OBJ text of generated
//! meshes, random control grids, the corpus of malformed files
//! ([`malformed`]) and random meshes for property tests ([`strategies`]).
//!
//! Each test crate includes it with `mod support;` (`#[path =
//! "../support/mod.rs"] mod support;` from a crate in a folder, like
//! `tests/cli/`) and uses what it needs; the rest is dead code there.

#![allow(dead_code)]

pub mod malformed;
pub mod strategies;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Output;
use std::sync::Mutex;
use subdiv::patch::ControlGrid;
use subdiv::{Mesh, Precision};

/// The `subdiv` binary that Cargo built for this test run.
#[cfg(feature = "cli")]
pub fn subdiv_bin() -> &'static Path {
    Path::new(env!("CARGO_BIN_EXE_subdiv"))
}

/// Runs `subdiv ARGS...` and waits for it.
#[cfg(feature = "cli")]
pub fn subdiv(args: &[&str]) -> Output {
    std::process::Command::new(subdiv_bin())
        .args(args)
        .output()
        .expect("run subdiv")
}

/// Runs `subdiv refine INPUT --engine ENGINE ARGS... -o OUT`, the way most
/// CLI tests refine a file into a file.
#[cfg(feature = "cli")]
pub fn refine_to(input: &Path, engine: &str, out: &Path, args: &[&str]) -> Output {
    let mut all = vec!["refine", input.to_str().unwrap(), "--engine", engine];
    all.extend_from_slice(args);
    all.extend_from_slice(&["-o", out.to_str().unwrap()]);
    subdiv(&all)
}

/// A command's standard output as text (invalid UTF-8 replaced).
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// A command's standard error as text (invalid UTF-8 replaced).
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A fresh, empty directory for one test: `NAME` under this test crate's
/// folder of Cargo's target temporary directory, emptied if an earlier run
/// left it behind. It stays after the test, for a look at what was written.
///
/// # Panics
///
/// If `NAME` was already handed out in this test process: two tests (or two
/// cases of one test) sharing a directory would see each other's files.
pub fn scratch(name: &str) -> PathBuf {
    static TAKEN: Mutex<BTreeSet<String>> = Mutex::new(BTreeSet::new());
    let fresh = TAKEN
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .insert(name.to_string());
    assert!(fresh, "the scratch directory {name:?} is used twice");
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(env!("CARGO_CRATE_NAME"))
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir)
        .unwrap_or_else(|e| panic!("cannot create {}: {e}", dir.display()));
    dir
}

/// The names of the files in `dir`, sorted.
pub fn file_names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("cannot list {}: {e}", dir.display()))
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// Writes `text` to the file `name` in `dir`; returns its path.
pub fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
    path
}

/// A mesh as OBJ text, written by the library's writer
/// ([`subdiv::io::mesh_to_obj_string`], 17 significant digits): `v` lines,
/// `vt` lines of face-varying channel 0, one `f` line per face (holes
/// included) in the mesh's order, then `t crease 2/1/0` per crease, one
/// `t corner` and one `t hole` line. Numbers are `%.17g`, so a value such as
/// 0.5 or 2 is written as in a hand-made file (`0.5`, `2`) and every value
/// reads back exactly. Option tags are not part of a mesh: append them.
pub fn obj_text(mesh: &Mesh) -> String {
    subdiv::io::mesh_to_obj_string(mesh, Precision::F64)
}

/// A small deterministic generator (xorshift64*): the same seed gives the
/// same sequence on every run, so randomized tests check the same cases.
pub struct Rng(pub u64);

impl Rng {
    /// The next value, in [-1, 1).
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let x = self.0.wrapping_mul(0x2545_F491_4F6C_DD1D);
        (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    /// A point with coordinates in [-scale, scale).
    pub fn v2(&mut self, scale: f64) -> glam::DVec2 {
        glam::DVec2::new(self.next() * scale, self.next() * scale)
    }

    /// A point with coordinates in [-scale, scale).
    pub fn v3(&mut self, scale: f64) -> glam::DVec3 {
        glam::DVec3::new(
            self.next() * scale,
            self.next() * scale,
            self.next() * scale,
        )
    }
}

/// The four ways a control grid can be open or closed in u and in v.
pub const TOPOLOGIES: [(bool, bool); 4] =
    [(false, false), (true, false), (false, true), (true, true)];

/// A wavy `nu` × `nv` control grid of the given degree, closed in u and/or v:
/// x and y along the indices, a random height in [-1, 1) from `seed`.
pub fn wavy(nu: usize, nv: usize, degree: usize, cu: bool, cv: bool, seed: u64) -> ControlGrid {
    let mut rng = Rng(seed);
    let heights: Vec<f64> = (0..nu * nv).map(|_| rng.next()).collect();
    ControlGrid::from_fn(nu, nv, degree, cu, cv, |i, j| {
        glam::DVec3::new(i as f64, j as f64, heights[j * nu + i])
    })
    .unwrap()
}

/// Coordinates spread over a face's Bfr domain: its vertices, points on
/// its edges, its centre and points inside (and on the edges of) every
/// sub-face.
pub fn bfr_sample_coords(p: &subdiv::bfr::Parameterization) -> Vec<[f64; 2]> {
    let n = p.face_size();
    let mut c = Vec::new();
    for k in 0..n {
        c.push(p.vertex_coord::<f64>(k));
        c.push(p.edge_coord::<f64>(k, 0.3));
    }
    c.push(p.center_coord::<f64>());
    if p.has_subfaces() {
        for k in 0..n {
            for st in [[0.37, 0.61], [1.0, 0.0], [1.0, 1.0]] {
                c.push(p.subface_to_coord(k, st, true).unwrap());
            }
        }
    } else {
        c.extend([[0.37, 0.21], [0.21, 0.37], [1e-3, 1e-3]]);
    }
    c
}
