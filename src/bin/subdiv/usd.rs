//! USD inputs and outputs of the commands: a stage's subdivision meshes read
//! as inputs (one per prim), refined meshes written as a `.usda` layer.

use std::path::Path;
use subdiv::Refinement;

use crate::Failure;
use crate::args::{Loaded, MeshArgs};

/// Whether `path` names a `.usda` output.
pub(crate) fn is_usda(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("usda"))
}

/// The selected subdivision meshes of the stage at `path`: every prim a
/// [`Loaded`] named `FILE:PRIM`, its options the prim's under the command
/// line's. The stage's warnings are printed (an error with `--strict`), and
/// so are the prims it skips (`subdivisionScheme = "none"`, no faces).
#[cfg(feature = "usd")]
pub(crate) fn load(args: &MeshArgs, path: &Path) -> Result<Vec<Loaded>, Failure> {
    use subdiv::io::usd::{UsdReadOptions, read_usd};
    let read = UsdReadOptions {
        time: args.time,
        lenient: args.lenient,
        prims: args.prims.clone(),
    };
    let stage = read_usd(path, &read)?;
    let file = path.display().to_string();
    if let (true, Some(w)) = (args.strict, stage.warnings.first()) {
        return Err(Failure::Message(format!(
            "{file}: {w} (a warning; --strict makes it an error)"
        )));
    }
    crate::args::print_warnings(
        &file,
        stage
            .warnings
            .iter()
            .map(|w| (0, w.message.as_str(), w.to_string())),
    );
    for skipped in &stage.skipped {
        eprintln!(
            "subdiv: note: {file}: {} skipped: {}",
            skipped.prim, skipped.reason
        );
    }
    Ok(stage
        .meshes
        .into_iter()
        .map(|m| {
            let mut options = m.options;
            crate::args::override_options(args, &mut options);
            Loaded {
                name: format!("{file}:{}", m.path),
                mesh: m.mesh,
                options,
                prim: Some((m.path, m.fvar_names)),
            }
        })
        .collect())
}

/// Without the `usd` feature: refused.
#[cfg(not(feature = "usd"))]
pub(crate) fn load(_args: &MeshArgs, path: &Path) -> Result<Vec<Loaded>, Failure> {
    Err(Failure::Unavailable(format!(
        "{}: this build reads no USD (rebuild with the default feature `usd`)",
        path.display()
    )))
}

/// Writes refinements as one `.usda` layer: each at its prim's path (an
/// OBJ or built-in input at `/Mesh`), `subdivisionScheme = "none"`, its
/// face-varying channels under their primvar names; limit positions and
/// values when the refinement evaluated them.
#[cfg(feature = "usd")]
pub(crate) fn write_refinements(
    path: &Path,
    input: Option<&Path>,
    refined: &[(&Loaded, Refinement)],
) -> Result<(), Failure> {
    use subdiv::io::usd::{UsdMeshOut, write_usda_to};
    let outs: Vec<UsdMeshOut<'_>> = refined
        .iter()
        .map(|(loaded, r)| {
            let (prim, names) = match &loaded.prim {
                Some((prim, names)) => (prim.as_str(), names.as_slice()),
                None => ("/Mesh", &[][..]),
            };
            let mut out = UsdMeshOut::from_refinement(prim, r, names);
            if let Some(limit) = &r.limit {
                out.positions = &limit.positions;
                for (channel, values) in out.fvar.iter_mut().zip(&limit.fvar_values) {
                    channel.values = values;
                }
            }
            out
        })
        .collect();
    let precision = refined
        .first()
        .map_or(subdiv::Precision::F64, |(_, r)| r.precision);
    crate::output::write_output(path, input, |w| write_usda_to(w, &outs, precision))
}

/// Without the `usd` feature: refused.
#[cfg(not(feature = "usd"))]
pub(crate) fn write_refinements(
    path: &Path,
    _input: Option<&Path>,
    _refined: &[(&Loaded, Refinement)],
) -> Result<(), Failure> {
    Err(Failure::Unavailable(format!(
        "{}: this build writes no USD (rebuild with the default feature `usd`)",
        path.display()
    )))
}
