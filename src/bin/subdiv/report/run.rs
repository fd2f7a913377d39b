//! Running the report: comparisons, limits and timings.

use super::coverage::{Coverage, choose};
use super::format::options_label;
use super::inputs::{Input, traits};
use super::picture::picture;
use super::results::{InputReport, LevelResult, LimitResult, Picture, Report, SetResult, Timing};
use super::settings::Settings;
use crate::Failure;
use glam::DVec3;
use std::hint::black_box;
use std::time::Instant;
use subdiv::compare::{bbox_diagonal, compare};
use subdiv::mesh::Mesh;
use subdiv::options::{Options, Scheme, UniformOptions};
use subdiv::{Engine, Error, OsdErrorKind, Refinement, Request, Result, check_level, osd, refiner};

/// The steps of a report: per input its option sets, its timed levels,
/// the limit surface and the tessellated surface.
pub fn steps(inputs: &[Input], settings: &Settings) -> u64 {
    inputs
        .iter()
        .map(|i| choose(i, settings).1.len() as u64 + settings.timed_levels().count() as u64 + 2)
        .sum()
}

/// Runs the report: every comparison, benchmark and picture. `progress` is
/// called once per step (see [`steps`]) with a description of the step.
///
/// Invalid meshes and levels too deep for an input are errors before any
/// work; an engine failing on an option set is recorded as a failing case.
pub fn run(
    inputs: &[Input],
    settings: &Settings,
    mut progress: impl FnMut(&str),
) -> std::result::Result<Report, Failure> {
    let start = Instant::now();
    if settings.first_level > settings.last_level {
        return Err(Failure::Usage(format!(
            "the level range {}..{} is empty",
            settings.first_level, settings.last_level
        )));
    }
    if settings.tolerance.is_nan() || settings.tolerance < 0.0 {
        return Err(Failure::Usage(format!(
            "the tolerance {} is not a non-negative number",
            settings.tolerance
        )));
    }
    let mut plans = Vec::with_capacity(inputs.len());
    for input in inputs {
        input
            .mesh
            .validate()
            .map_err(|e| Failure::Message(format!("{}: invalid mesh: {e}", input.name)))?;
        if input.mesh.face_count() == 0 {
            return Err(Failure::from(Error::EmptyMesh).in_input(&input.name));
        }
        let (coverage, sets) = choose(input, settings);
        for o in &sets {
            check_level(&input.mesh, o, settings.last_level)
                .map_err(|e| Failure::from(e).in_input(&input.name))?;
        }
        plans.push((coverage, sets));
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .map_err(|e| Failure::Message(format!("cannot start a thread pool: {e}")))?;
    let mut reports = Vec::with_capacity(inputs.len());
    for (input, (coverage, sets)) in inputs.iter().zip(plans) {
        reports.push(
            run_input(input, coverage, sets, settings, &pool, &mut progress)
                .map_err(|e| Failure::from(e).in_input(&input.name))?,
        );
    }
    Ok(Report {
        date: crate::date::today(),
        machine: crate::bench::timing::machine_description(),
        osd_version: osd::version(),
        subdiv_version: env!("CARGO_PKG_VERSION").to_string(),
        settings: *settings,
        inputs: reports,
        seconds: start.elapsed().as_secs_f64(),
    })
}

pub(crate) fn run_input(
    input: &Input,
    coverage: Coverage,
    sets: Vec<Options>,
    settings: &Settings,
    pool: &rayon::ThreadPool,
    progress: &mut impl FnMut(&str),
) -> Result<InputReport> {
    let t = traits(&input.mesh);
    let mut varied = Vec::new();
    let mut schemes: Vec<Scheme> = sets.iter().map(|o| o.scheme).collect();
    schemes.dedup();
    if schemes.len() > 1 {
        varied.push("scheme");
    }
    for (yes, what) in [
        (t.boundary, "boundary"),
        (t.creases, "creasing"),
        (t.triangles, "triangles"),
        (t.uvs, "face-varying"),
    ] {
        if yes {
            varied.push(what);
        }
    }
    let mut results = Vec::with_capacity(sets.len());
    let mut pictured: Option<(Refinement, Refinement)> = None;
    for (k, options) in sets.iter().enumerate() {
        progress(&format!(
            "{}: {} ({}/{})",
            input.name,
            options_label(options),
            k + 1,
            sets.len()
        ));
        let (result, pair) = compare_set(&input.mesh, options, settings);
        if *options == input.options {
            pictured = pair;
        }
        results.push(result);
    }
    let mut timings = Vec::new();
    for level in settings.timed_levels() {
        progress(&format!("{}: timing level {level}", input.name));
        match pool.install(|| time_level(&input.mesh, &input.options, level, settings.quick)) {
            Ok(t) => timings.push(t),
            // OpenSubdiv cannot refine this input safely: nothing to time
            // side by side (the option sets say why).
            Err(Error::Osd(e)) if e.kind == OsdErrorKind::Unsafe => {}
            Err(e) => return Err(e),
        }
    }
    let picture = match &pictured {
        Some((native, osd)) => picture(input, native, osd, settings.tolerance),
        None => Picture {
            level: 0,
            faces: 0,
            max_deviation: f64::INFINITY,
            svg: String::new(),
        },
    };
    progress(&format!("{}: limit surface", input.name));
    let limit_surface = limit_surface(input, settings.tolerance);
    progress(&format!("{}: tessellated limit surface", input.name));
    let tessellated = super::tessellated::tessellated(input, settings.tolerance);
    Ok(InputReport {
        name: input.name.clone(),
        description: input.description.clone(),
        vertices: input.mesh.vertex_count(),
        faces: input.mesh.face_count(),
        options: input.options,
        varied,
        coverage,
        sets: results,
        timings,
        picture,
        limit_surface,
        tessellated,
    })
}

/// Both engines' patch tables of `input` with its default options and the
/// limit surfaces they evaluate (`subdiv compare --patches`' comparison).
fn limit_surface(input: &Input, tolerance: f64) -> super::results::LimitSurface {
    use super::results::{LIMIT_ISOLATION, LimitSurface};
    let faces = input.mesh.face_count();
    if faces > super::tessellated::MAX_FACES {
        // Both engines' tables and 25 locations per ptex face: minutes and
        // gigabytes on a production mesh; `subdiv compare --patches` does it
        // on request.
        return LimitSurface::NotCompared(format!(
            "{faces} faces, above the report's {} for this comparison; `subdiv compare --patches` compares it",
            super::tessellated::MAX_FACES
        ));
    }
    let po = subdiv::patches::PatchOptions::new().max_isolation(LIMIT_ISOLATION);
    let ao = po.refine_adaptive_options();
    match crate::compare_patches::limit_comparison(&input.mesh, &input.options, &po, ao, &[]) {
        Ok(c) => LimitSurface::Compared {
            patches: c.patches,
            local_points: c.local_points,
            agrees: c.agrees(tolerance),
            first_difference: c.first_difference,
            locations: c.locations,
            deviation: c.relative_position_deviation,
            derivative_deviation: c.relative_derivative_deviation,
            picture: super::picture::limit_picture(&input.name, &c.samples, tolerance),
        },
        Err(e) => LimitSurface::NotCompared(e.to_string()),
    }
}

/// Compares one option set; returns the refinements too (for the picture).
pub(crate) fn compare_set(
    mesh: &Mesh,
    options: &Options,
    settings: &Settings,
) -> (SetResult, Option<(Refinement, Refinement)>) {
    let mut result = SetResult {
        options: *options,
        levels: Vec::new(),
        limit: None,
        error: None,
        limit_refused: None,
        refused: None,
    };
    let both = |limit: bool| -> std::result::Result<(Refinement, Refinement), (Engine, Error)> {
        let request = Request::new(settings.last_level).limit(limit);
        let run = |engine: Engine| {
            engine
                .refine(mesh, options, request)
                .map_err(|e| (engine, e))
        };
        Ok((run(Engine::Native)?, run(Engine::Osd)?))
    };
    let failed = |(engine, e): (Engine, Error), limit: bool| {
        format!(
            "{engine} engine{}: {e}",
            if limit { " (limit)" } else { "" }
        )
    };
    let pair = match both(false) {
        Ok(pair) => pair,
        Err((Engine::Osd, Error::Osd(e))) if e.kind == OsdErrorKind::Unsafe => {
            result.refused = Some(e.message);
            return (result, None);
        }
        Err(e) => {
            result.error = Some(failed(e, false));
            return (result, None);
        }
    };
    let has_uvs = !mesh.fvar_channels.is_empty();
    for c in compare(&pair.0, &pair.1) {
        if c.level < settings.first_level {
            continue;
        }
        result.levels.push(LevelResult {
            level: c.level,
            vertices: c.counts[1][0],
            faces: c.counts[1][2],
            topology_equal: c.topology_equal(),
            position_deviation: c.relative_position_deviation,
            fvar_deviation: has_uvs.then_some(c.max_fvar_deviation),
            agrees: c.agrees(settings.tolerance),
        });
    }
    match both(true) {
        Ok((n, o)) => {
            result.limit = compare_limit(&n, &o, settings.tolerance);
            if result.limit.is_none() {
                result.error = Some("an engine returned no limit".into());
            }
        }
        Err((Engine::Osd, Error::Osd(e))) if e.kind == OsdErrorKind::Unsafe => {
            result.limit_refused = Some(e.message)
        }
        Err(e) => result.error = Some(failed(e, true)),
    }
    (result, Some(pair))
}

pub(crate) fn compare_limit(n: &Refinement, o: &Refinement, tolerance: f64) -> Option<LimitResult> {
    let (ln, lo) = (n.limit.as_ref()?, o.limit.as_ref()?);
    let diag = bbox_diagonal(&lo.positions).max(f64::MIN_POSITIVE);
    let dist = |a: DVec3, b: DVec3| {
        let d = (a - b).length() / diag;
        if d.is_nan() { f64::INFINITY } else { d }
    };
    let mut position = if ln.positions.len() == lo.positions.len() {
        0.0f64
    } else {
        f64::INFINITY
    };
    for (a, b) in ln.positions.iter().zip(&lo.positions) {
        position = position.max(dist(*a, *b));
    }
    let mut tangent = if ln.du.len() == lo.du.len() && ln.dv.len() == lo.dv.len() {
        0.0f64
    } else {
        f64::INFINITY
    };
    for ((a, b), (c, d)) in ln.du.iter().zip(&lo.du).zip(ln.dv.iter().zip(&lo.dv)) {
        tangent = tangent.max(dist(*a, *b)).max(dist(*c, *d));
    }
    let fvar = (!lo.fvar_values.is_empty() || !ln.fvar_values.is_empty()).then(|| {
        let mut worst = if ln.fvar_values.len() == lo.fvar_values.len() {
            0.0f64
        } else {
            f64::INFINITY
        };
        for (x, y) in ln.fvar_values.iter().zip(&lo.fvar_values) {
            if x.len() != y.len() {
                worst = f64::INFINITY;
            }
            for (p, q) in x.iter().zip(y) {
                let d = (p - q).abs();
                worst = worst.max(if d.is_nan() { f64::INFINITY } else { d });
            }
        }
        worst
    });
    let agrees =
        position <= tolerance && tangent <= tolerance && fvar.is_none_or(|f| f <= tolerance);
    Some(LimitResult {
        level: o.uniform.level,
        position_deviation: position,
        tangent_deviation: tangent,
        fvar_deviation: fvar,
        agrees,
    })
}

pub(crate) fn time_level(
    mesh: &Mesh,
    options: &Options,
    level: u32,
    quick: bool,
) -> Result<Timing> {
    let base: Vec<f64> = mesh.flat_positions();
    let uniform = UniformOptions::new(level);
    let native = || -> Result<usize> {
        let mut r = refiner::Refiner::new(mesh, options)?;
        r.refine_uniform(uniform)?;
        let p = r.interpolate_all(3, &base)?;
        Ok(black_box(p).last().map_or(0, |l| l.len()))
    };
    let opensubdiv = || -> Result<usize> {
        let mut r = osd::TopologyRefiner::new(mesh, options)?;
        r.refine_uniform(uniform)?;
        let p = r.interpolate_all(3, &base)?;
        Ok(black_box(p).last().map_or(0, Vec::len))
    };
    // One run of each: errors surface here, and it sizes the repetitions.
    let t0 = Instant::now();
    native()?;
    opensubdiv()?;
    let once = t0.elapsed().as_secs_f64().max(1e-7);
    // Fewer repetitions when one already takes seconds (a production mesh).
    let (budget, min_reps) = if quick || once > 1.0 {
        (0.02, 3)
    } else {
        (0.25, 7)
    };
    let reps = ((budget / once) as usize).clamp(min_reps, 2001) | 1;
    // Warm up (caches, allocator, clock) for a tenth of the budget.
    for _ in 0..reps / 10 {
        let _ = black_box(native());
        let _ = black_box(opensubdiv());
    }
    let (tn, to) = crate::bench::timing::interleaved(
        reps,
        || {
            let _ = black_box(native());
        },
        || {
            let _ = black_box(opensubdiv());
        },
    );
    let faces = osd::refine(mesh, options, uniform)
        .map(|r| r.last_level().face_count())
        .unwrap_or(0);
    Ok(Timing {
        level,
        faces,
        native: tn,
        osd: to,
        reps,
    })
}
