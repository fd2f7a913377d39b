//! The `subdiv` binary, run as a user runs it: one module per subcommand
//! (`refine`, `compare`, `curve`, `report`, `patches` and `eval`; `adaptive` for `--adaptive`), B-spline and NURBS curves
//! through `curve --knots` (and against an independent implementation from
//! the definitions: `curve_reference.rs`), Doo-Sabin through `refine`, every file of the
//! malformed corpus through `refine` and `curve`, exhausted memory under
//! `ulimit -v`, where outputs go (links, `-o -`, signals during a write:
//! `outputs.rs`) and what a hostile user tries (`hostile.rs`).
//!
//! Each test writes into its own directory ([`support::scratch`]). The
//! library's side of these features is tested in the crates beside this
//! folder (`curves.rs`, `doo_sabin.rs`, `malformed.rs`, ...).

#[path = "../support/mod.rs"]
mod support;

mod adaptive;
// `compare` and the report compare the two engines: they need OpenSubdiv.
#[cfg(feature = "osd")]
mod compare;
mod curve;
mod curve_knots;
mod curve_reference;
mod doo_sabin;
mod hostile;
mod malformed;
// `ulimit` in `sh`.
#[cfg(unix)]
mod memory_limits;
mod outputs;
// Patch tables come from OpenSubdiv today.
#[cfg(feature = "osd")]
mod patches;
mod refine;
#[cfg(feature = "osd")]
mod report;
mod tessellate;
// USD stages need the `usd` feature.
#[cfg(feature = "usd")]
mod usd;

use subdiv::{Mesh, shapes};

/// The engines of this build: the native one, and OpenSubdiv with the `osd` feature.
fn engines() -> &'static [&'static str] {
    if cfg!(feature = "osd") {
        &["native", "osd"]
    } else {
        &["native"]
    }
}

/// A 2 × 2 grid of unit quads in the z = 0 plane whose centre vertex (4) is
/// raised to z = 0.5; no UVs.
fn quad_grid_mesh() -> Mesh {
    let mut m = shapes::grid(2, 2);
    m.fvar_channels.clear();
    m.positions[4].z = 0.5;
    m
}

/// [`quad_grid_mesh`] as OBJ text: 9 `v` lines, then 4 `f` lines.
fn quad_grid() -> String {
    support::obj_text(&quad_grid_mesh())
}

/// The tests name lines of files built on the grid's text (a tag appended
/// is on line 14): the text is the one a hand-written file would have.
#[test]
fn the_quad_grid_is_nine_vertices_then_four_faces() {
    assert_eq!(
        quad_grid(),
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0.5\nv 2 1 0\nv 0 2 0\nv 1 2 0\nv 2 2 0\n\
         f 1 2 5 4\nf 2 3 6 5\nf 4 5 8 7\nf 5 6 9 8\n"
    );
}
