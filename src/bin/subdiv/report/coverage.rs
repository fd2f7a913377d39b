//! How much of the option space a report covers for one input, chosen by
//! the input's size: every combination of the options that apply for the
//! usual test meshes, fewer sets — down to the mesh's own options — for a
//! production asset, whose every combination would take hours.

use super::inputs::{Input, option_sets};
use super::settings::Settings;
use subdiv::options::{Options, Scheme};

/// The work one input may take without `--all-options`: the faces of the
/// deepest compared level, summed over the option sets. About a minute on
/// one core with both engines, their limits and the benchmarks.
pub const WORK_BUDGET: f64 = 2.5e7;

/// Which option sets an input is compared with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Coverage {
    /// Every combination of the options that apply.
    Every,
    /// The mesh's own options, then one option varied at a time.
    OneAtATime,
    /// The mesh's own options only.
    Own,
}

impl Coverage {
    /// What the report says was run.
    pub fn describe(self) -> &'static str {
        match self {
            Coverage::Every => "every combination of the options that apply",
            Coverage::OneAtATime => "one option varied at a time",
            Coverage::Own => "the mesh's own options only",
        }
    }
}

/// The faces of level `level` of `mesh` under `scheme`: an n-gon splits into
/// n quads and every quad into 4 (Catmull-Clark, bilinear); a triangle into
/// 4 (Loop).
pub fn faces_at(input: &Input, scheme: Scheme, level: u32) -> f64 {
    let mesh = &input.mesh;
    if level == 0 {
        return mesh.face_count() as f64;
    }
    let first = match scheme {
        Scheme::Loop => 4.0 * mesh.face_count() as f64,
        _ => mesh.face_vertices.len() as f64,
    };
    first * 4f64.powi(level as i32 - 1)
}

/// The coverage and option sets for `input`: every combination (one
/// option varied at a time with `--quick`) while it fits [`WORK_BUDGET`],
/// then fewer; every combination whatever the size with `--all-options`.
pub fn choose(input: &Input, settings: &Settings) -> (Coverage, Vec<Options>) {
    if settings.all_options {
        return (Coverage::Every, option_sets(input, false));
    }
    let work = faces_at(input, input.options.scheme, settings.last_level);
    let fits = |sets: &[Options]| sets.len() as f64 * work <= WORK_BUDGET;
    if !settings.quick {
        let every = option_sets(input, false);
        if fits(&every) {
            return (Coverage::Every, every);
        }
    }
    let one = option_sets(input, true);
    if fits(&one) {
        return (Coverage::OneAtATime, one);
    }
    (Coverage::Own, vec![input.options])
}
