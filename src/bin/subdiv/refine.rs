//! `subdiv refine`: refine a mesh and write its last level (or a summary).

use clap::Args;
use std::path::{Path, PathBuf};
use std::time::Instant;
use subdiv::io::{ObjOutput, UvOutput};
use subdiv::{
    Engine, Error, LevelRefusal, Mesh, Options, Precision, Refinement, Request, UniformOptions,
    Values,
};

use crate::Failure;
use crate::adaptive::AdaptiveArgs;
use crate::args::{Loaded, MeshArgs, SchemeArg, load, load_all, parse, parse_level};
use crate::output::write_output;

#[derive(Args)]
pub(crate) struct RefineArgs {
    #[command(flatten)]
    pub(crate) mesh: MeshArgs,
    /// Output file: OBJ (one mesh), or a .usda layer with every mesh at its
    /// prim's path; without it nothing is written and a summary is printed.
    #[arg(
        short,
        long,
        value_name = "OUT.obj|OUT.usda",
        conflicts_with = "adaptive"
    )]
    pub(crate) output: Option<PathBuf>,
    /// Refinement level (0..=10).
    #[arg(long, default_value = "2", value_parser = parse_level, allow_negative_numbers = true,
          conflicts_with = "adaptive")]
    pub(crate) level: u32,
    #[command(flatten)]
    pub(crate) adaptive: AdaptiveArgs,
    /// With --adaptive: write every level (counts, faces with holes, positions) as JSON.
    #[arg(long, value_name = "OUT.json", requires = "adaptive")]
    pub(crate) levels_json: Option<PathBuf>,
    /// Refinement engine: native or osd.
    #[arg(long, default_value = "native", value_parser = parse::<Engine>)]
    pub(crate) engine: Engine,
    /// Write limit positions (and limit face-varying values) instead of refined ones.
    #[arg(long, conflicts_with = "adaptive")]
    pub(crate) limit: bool,
    /// Doo-Sabin corner weights: original or centroid (with --scheme doo-sabin).
    #[arg(long, value_name = "WEIGHTS", conflicts_with = "adaptive", value_parser = parse::<subdiv::doo_sabin::Weights>)]
    pub(crate) doo_sabin_weights: Option<subdiv::doo_sabin::Weights>,
    /// Doo-Sabin boundary rule: open or chaikin (with --scheme doo-sabin).
    #[arg(long, value_name = "RULE", conflicts_with = "adaptive", value_parser = parse::<subdiv::doo_sabin::Boundary>)]
    pub(crate) doo_sabin_boundary: Option<subdiv::doo_sabin::Boundary>,
    /// Print the process's peak memory (bytes) on stderr at the end (for `subdiv bench`).
    #[arg(long, hide = true)]
    pub(crate) peak_memory: bool,
}

/// Vertex and face counts of every level of a refinement.
pub(crate) fn refinement_counts(r: &Refinement) -> Vec<(usize, usize)> {
    r.levels
        .iter()
        .map(|l| (l.vertex_count, l.face_count()))
        .collect()
}

pub(crate) fn summary(
    name: &str,
    engine: Engine,
    options: &Options,
    precision: Precision,
    counts: &[(usize, usize)],
    limit: bool,
    seconds: f64,
) -> String {
    let join = |f: fn(&(usize, usize)) -> usize| {
        counts
            .iter()
            .map(|c| f(c).to_string())
            .collect::<Vec<_>>()
            .join("→")
    };
    format!(
        "{name}: {} level {} ({}, {}): vertices {}, faces {}{}; {:.3} ms",
        options.scheme,
        counts.len().saturating_sub(1),
        engine,
        precision,
        join(|c| c.0),
        join(|c| c.1),
        if limit { ", limit evaluated" } else { "" },
        seconds * 1e3
    )
}

/// How many faces of `level` are holes (left out of every output): the
/// children of the base level's holes (tagged, or on a boundary that
/// `BoundaryInterpolation::None` leaves out), one per corner in a quad split
/// and four per triangle in a Loop split, then four per face at each level.
/// Zero without holes; computed only when the mesh can have some.
pub(crate) fn hole_faces(mesh: &Mesh, options: &Options, level: u32) -> Result<usize, Failure> {
    use subdiv::{BoundaryInterpolation, Scheme};
    if mesh.holes.is_empty() && options.boundary != BoundaryInterpolation::None {
        return Ok(0);
    }
    // The base level's holes: the tagged faces, and with no boundary
    // interpolation (but for bilinear) the faces at the boundary, which only
    // the base level's topology tells.
    let mut is_hole = vec![false; mesh.face_count()];
    if options.boundary == BoundaryInterpolation::None && options.scheme != Scheme::Bilinear {
        // The base level's flags, borrowed (`Refiner::level` would copy
        // every table of the level).
        let r = subdiv::refiner::Refiner::new(mesh, options)?;
        if let Some(holes) = r.faces(0)?.holes {
            is_hole.copy_from_slice(holes);
        }
    } else {
        for &f in &mesh.holes {
            if let Some(h) = is_hole.get_mut(f as usize) {
                *h = true;
            }
        }
    }
    let holes = (0..mesh.face_count())
        .filter(|&f| is_hole[f])
        .map(|f| mesh.face(f));
    Ok(match level {
        0 => holes.count(),
        _ => {
            let split = |face: &[u32]| match options.scheme {
                Scheme::Loop => 4,
                _ => face.len(),
            };
            let first: usize = holes.map(split).sum();
            first << (2 * (level - 1))
        }
    })
}

/// The summary's note on holes: how many of the last level's faces an
/// output would leave out.
fn holes_note(holes: usize) -> String {
    match holes {
        0 => String::new(),
        n => format!(" ({n} of the last level's faces are holes: outputs leave them out)"),
    }
}

pub(crate) fn refine(args: &RefineArgs) -> Result<(), Failure> {
    if let (Some(_), Some(SchemeArg::DooSabin)) = (args.adaptive.adaptive, args.mesh.scheme) {
        return Err(Failure::Usage(
            "--adaptive does not apply to --scheme doo-sabin (catmark and bilinear; loop with --engine osd)".into(),
        ));
    }
    if args.mesh.scheme == Some(SchemeArg::DooSabin) {
        return refine_doo_sabin(args);
    }
    if args.doo_sabin_weights.is_some() || args.doo_sabin_boundary.is_some() {
        return Err(Failure::Usage(
            "--doo-sabin-weights and --doo-sabin-boundary need --scheme doo-sabin".into(),
        ));
    }
    let usda = args.output.as_deref().is_some_and(crate::usd::is_usda);
    let mut inputs = load_all(&args.mesh)?;
    if usda || inputs.len() != 1 {
        return refine_all(args, &inputs, usda);
    }
    let Loaded {
        name,
        mesh,
        options,
        ..
    } = inputs.remove(0);
    // Every error from here on names the input (unless it names its own file).
    match args.adaptive.adaptive {
        Some(level) => {
            args.adaptive.check_selected_faces(&name, &mesh)?;
            crate::adaptive::refine_adaptive(args, level, &name, &mesh, &options)
        }
        None => refine_loaded(args, &name, mesh, &options),
    }
    .map_err(|f| f.in_input(&name))?;
    if args.peak_memory {
        eprintln!("peak_memory_bytes {}", peak_memory().unwrap_or(0));
    }
    Ok(())
}

/// `refine` on several meshes (the prims of a USD stage), or into a `.usda`
/// layer: each refined in turn, a summary line each, or all written as one
/// layer.
fn refine_all(args: &RefineArgs, inputs: &[Loaded], usda: bool) -> Result<(), Failure> {
    let file = args
        .mesh
        .input
        .as_deref()
        .map_or(String::new(), |p| p.display().to_string());
    if inputs.is_empty() {
        return Err(Failure::Message(format!(
            "{file}: no subdivision mesh to refine (see the notes above)"
        )));
    }
    if args.adaptive.adaptive.is_some() {
        return Err(Failure::Usage(format!(
            "--adaptive refines one mesh and {file} has {}: choose it with --prim PATH",
            inputs.len()
        )));
    }
    if let (Some(path), false) = (&args.output, usda) {
        return Err(Failure::Usage(format!(
            "-o {} holds one mesh and {file} has {}: choose one with --prim PATH, or write them all to a .usda file",
            path.display(),
            inputs.len()
        )));
    }
    let request = Request::new(args.level)
        .faces_first(args.mesh.faces_first)
        .precision(args.mesh.precision)
        .limit(args.limit);
    let mut refined = Vec::with_capacity(inputs.len());
    for input in inputs {
        let run = || -> Result<Refinement, Error> {
            subdiv::check_level(&input.mesh, &input.options, args.level)?;
            subdiv::check_precision(&input.mesh, args.mesh.precision)?;
            args.engine.refine(&input.mesh, &input.options, request)
        };
        let start = Instant::now();
        let r = run().map_err(|e| Failure::from(e).in_input(&input.name))?;
        if !usda {
            outln!(
                "{}{}",
                summary(
                    &input.name,
                    args.engine,
                    &r.options,
                    r.precision,
                    &refinement_counts(&r),
                    r.limit.is_some(),
                    start.elapsed().as_secs_f64()
                ),
                holes_note(r.last_level().face_holes.iter().filter(|&&h| h).count())
            );
        }
        // Kept only for the layer: a summary needs none of it.
        if usda {
            refined.push((input, r));
        }
    }
    if let Some(path) = &args.output {
        crate::usd::write_refinements(path, args.mesh.input.as_deref(), &refined)?;
    }
    if args.peak_memory {
        eprintln!("peak_memory_bytes {}", peak_memory().unwrap_or(0));
    }
    Ok(())
}

/// `refine` on a loaded mesh.
fn refine_loaded(
    args: &RefineArgs,
    name: &str,
    mesh: Mesh,
    options: &Options,
) -> Result<(), Failure> {
    let options = *options;
    let request = Request::new(args.level)
        .faces_first(args.mesh.faces_first)
        .precision(args.mesh.precision)
        .limit(args.limit);
    subdiv::check_level(&mesh, &options, args.level)?;
    subdiv::check_precision(&mesh, args.mesh.precision)?;
    let start = Instant::now();
    let precision = args.mesh.precision;
    if args.output.is_none() && !args.limit {
        // Counted before the refinement, which consumes the mesh (and
        // outside its time; its errors after the refinement's).
        let holes = hole_faces(&mesh, &options, args.level);
        let start = Instant::now();
        let counts: Vec<(usize, usize)> = args
            .engine
            .refine_counts_owned(mesh, &options, request)?
            .iter()
            .map(|c| (c.vertices, c.faces))
            .collect();
        let seconds = start.elapsed().as_secs_f64();
        let holes = holes?;
        outln!(
            "{}{}",
            summary(
                name,
                args.engine,
                &options,
                precision,
                &counts,
                false,
                seconds
            ),
            holes_note(holes)
        );
    } else if let (Engine::Native, false, Some(path)) = (args.engine, args.limit, &args.output) {
        let input = args.mesh.input.as_deref();
        write_native_last(path, input, &mesh, &options, request.uniform, precision)?;
    } else {
        let r = args.engine.refine(&mesh, &options, request)?;
        let seconds = start.elapsed().as_secs_f64();
        match &args.output {
            Some(path) => write_refinement(path, args.mesh.input.as_deref(), &r)?,
            None => outln!(
                "{}{}",
                summary(
                    name,
                    args.engine,
                    &r.options,
                    r.precision,
                    &refinement_counts(&r),
                    r.limit.is_some(),
                    seconds
                ),
                holes_note(r.last_level().face_holes.iter().filter(|&&h| h).count())
            ),
        }
    }
    Ok(())
}

/// The process's peak resident memory, from /proc/self/status.
pub(crate) fn peak_memory() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    Some(line.split_whitespace().nth(1)?.parse::<u64>().ok()? * 1024)
}

/// `refine -o` natively without `--limit`: only the last level's positions
/// and face-varying values are kept (each level's data is dropped once the
/// next exists) and the last level's faces are written straight from the
/// refiner, instead of [`subdiv::Engine::refine`]'s copies of every
/// level. The file is the same, byte for byte.
pub(crate) fn write_native_last(
    path: &Path,
    input: Option<&Path>,
    mesh: &Mesh,
    options: &Options,
    uniform: UniformOptions,
    precision: Precision,
) -> Result<(), Failure> {
    fn last_values<T: subdiv::Real>(
        r: &subdiv::refiner::Refiner,
        mesh: &Mesh,
    ) -> subdiv::Result<(Values<T>, Option<Vec<T>>)> {
        let positions = r.interpolate_last(3, &mesh.positions_as::<T>())?;
        // Only the first face-varying channel is written.
        let uv = match mesh.fvar_channels.first() {
            Some(channel) => {
                let mut values: Vec<T> = channel.values_as();
                for level in 1..=r.max_level() {
                    values = r.interpolate_face_varying(0, level, channel.width, &values)?;
                }
                Some(values)
            }
            None => None,
        };
        Ok((positions, uv))
    }
    let mut r = subdiv::refiner::Refiner::new(mesh, options)?;
    r.refine_uniform(uniform)?;
    let (positions, uv_values) = match precision {
        Precision::F64 => last_values::<f64>(&r, mesh)?,
        Precision::F32 => {
            // A copy as large as the level: allocated fallibly.
            let widen = |v: &[f32]| -> Result<Vec<f64>, Error> {
                let mut out = Vec::new();
                out.try_reserve_exact(v.len())
                    .map_err(|_| Error::OutOfMemory {
                        bytes: v.len() * size_of::<f64>(),
                        level: Some(uniform.level),
                    })?;
                out.extend(v.iter().map(|&x| f64::from(x)));
                Ok(out)
            };
            let (positions, uv) = last_values::<f32>(&r, mesh)?;
            let uv = match uv {
                Some(uv) => Some(widen(&uv)?),
                None => None,
            };
            (Values::from(widen(&positions)?), uv)
        }
    };
    let faces = r.faces(uniform.level)?;
    let uv = match (
        &uv_values,
        faces.fvar_face_values.first(),
        mesh.fvar_channels.first(),
    ) {
        (Some(values), Some(face_values), Some(channel)) => Some(UvOutput {
            width: channel.width,
            values,
            face_values,
        }),
        _ => None,
    };
    let data = ObjOutput {
        // Flat f64 triples are DVec3s: no second copy of the positions.
        positions: bytemuck::cast_slice(&positions[..]),
        face_offsets: &faces.offsets,
        face_vertices: faces.vertices,
        holes: faces.holes,
        uv,
        normals: None,
        precision,
    };
    write_output(path, input, |w| subdiv::io::write_obj_to(w, &data))
}

/// Writes the last level (or its limit) in OpenSubdiv's order; holes are left
/// out. `input`, the file read, is refused as the output.
pub(crate) fn write_refinement(
    path: &Path,
    input: Option<&Path>,
    r: &Refinement,
) -> Result<(), Failure> {
    let level = r.last_level();
    let (positions, uv_values) = match &r.limit {
        Some(limit) => (
            limit.positions.as_slice(),
            limit.fvar_values.first().map(Vec::as_slice),
        ),
        None => (r.last_positions(), r.last_fvar(0)),
    };
    let uv = match (uv_values, level.fvar.first(), r.fvar_widths.first()) {
        (Some(values), Some(fvar), Some(&width)) => Some(UvOutput {
            width,
            values,
            face_values: &fvar.face_values,
        }),
        _ => None,
    };
    let data = ObjOutput {
        positions,
        face_offsets: &level.face_offsets,
        face_vertices: &level.face_vertices,
        holes: Some(&level.face_holes),
        uv,
        normals: None,
        precision: r.precision,
    };
    write_output(path, input, |w| subdiv::io::write_obj_to(w, &data))
}

/// `subdiv refine --scheme doo-sabin`: the native Doo-Sabin refiner.
pub(crate) fn refine_doo_sabin(args: &RefineArgs) -> Result<(), Failure> {
    if args.engine == Engine::Osd {
        return Err(Failure::Unavailable(
            "OpenSubdiv has no Doo-Sabin scheme: --scheme doo-sabin needs --engine native".into(),
        ));
    }
    if args.limit {
        return Err(Failure::Unavailable(
            "doo-sabin has no limit evaluation (--limit)".into(),
        ));
    }
    if args.mesh.precision != Precision::F64 {
        return Err(Failure::Unavailable(
            "doo-sabin computes in f64 only (--precision f32)".into(),
        ));
    }
    let m = &args.mesh;
    for (given, flag) in [
        (m.boundary.is_some(), "--boundary"),
        (m.fvar.is_some(), "--fvar"),
        (m.creasing.is_some(), "--creasing"),
        (m.triangles.is_some(), "--triangles"),
        (m.faces_first, "--faces-first"),
    ] {
        if given {
            return Err(Failure::Usage(format!(
                "{flag} does not apply to --scheme doo-sabin (see --doo-sabin-weights and --doo-sabin-boundary)"
            )));
        }
    }
    if args.level > subdiv::MAX_LEVEL {
        return Err(Error::Level {
            level: args.level,
            reason: LevelRefusal::TooDeep {
                max: subdiv::MAX_LEVEL,
            },
        }
        .into());
    }
    let (name, mesh, _) = load(&args.mesh)?;
    if !mesh.creases.is_empty()
        || !mesh.corners.is_empty()
        || !mesh.holes.is_empty()
        || !mesh.fvar_channels.is_empty()
    {
        let msg =
            format!("{name}: doo-sabin ignores creases, corners, holes and texture coordinates");
        if args.mesh.strict {
            return Err(Failure::Message(format!("{msg} (--strict)")));
        }
        eprintln!("subdiv: warning: {msg}");
    }
    let options = subdiv::doo_sabin::DooSabinOptions {
        weights: args.doo_sabin_weights.unwrap_or_default(),
        boundary: args.doo_sabin_boundary.unwrap_or_default(),
    };
    let start = Instant::now();
    let levels = subdiv::doo_sabin::refine(&mesh, &options, args.level)
        .map_err(|e| Failure::Message(format!("{name}: {e}")))?;
    let seconds = start.elapsed().as_secs_f64();
    let last = levels.last().unwrap_or(&mesh);
    match &args.output {
        Some(path) => write_output(path, args.mesh.input.as_deref(), |w| {
            subdiv::io::write_mesh_obj_to(w, last, Precision::F64)
        })?,
        None => {
            let counts = |f: fn(&Mesh) -> usize| {
                levels
                    .iter()
                    .map(|l| f(l).to_string())
                    .collect::<Vec<_>>()
                    .join("→")
            };
            outln!(
                "{name}: doo-sabin ({}, {} boundary) level {} (native, f64): vertices {}, faces {}; {:.3} ms",
                options.weights,
                options.boundary,
                args.level,
                counts(Mesh::vertex_count),
                counts(Mesh::face_count),
                seconds * 1e3
            );
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use subdiv::{BoundaryInterpolation, Scheme, shapes};

    /// The summary's hole count, computed without refining, is the number
    /// of hole faces a refinement's last level has, on every corpus mesh
    /// with holes or a boundary, under every boundary option and scheme.
    #[test]
    fn hole_faces_count_the_last_levels_holes() {
        let mut with_holes = 0;
        for (name, mesh) in shapes::corpus() {
            for &scheme in mesh.applicable_schemes() {
                for boundary in [
                    BoundaryInterpolation::None,
                    BoundaryInterpolation::EdgeOnly,
                    BoundaryInterpolation::EdgeAndCorner,
                ] {
                    let options = Options::default()
                        .with_scheme(scheme)
                        .with_boundary(boundary);
                    for level in 0..=2 {
                        let Ok(r) = Engine::Native.refine(&mesh, &options, Request::new(level))
                        else {
                            continue;
                        };
                        let expected = r.last_level().face_holes.iter().filter(|&&h| h).count();
                        let got = hole_faces(&mesh, &options, level).unwrap();
                        assert_eq!(got, expected, "{name} {scheme} {boundary} level {level}");
                        with_holes += (expected > 0 && scheme != Scheme::Bilinear) as usize;
                    }
                }
            }
        }
        assert!(with_holes > 20, "{with_holes}");
    }
}
