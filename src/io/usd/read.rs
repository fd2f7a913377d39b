//! [`read_usd`]: open and compose the stage, select its `Mesh` prims, read
//! each one ([`super::mesh`]).

use super::glob::Pattern;
use super::mesh::{Outcome, read_mesh};
use super::resolver::LayerResolver;
use super::values::{Context, library};
use super::{UsdReadOptions, UsdSkipped, UsdStage, UsdWarning};
use crate::error::{Error, UsdError, UsdErrorKind};
use openusd::usd;
use std::path::Path;

/// Reads the subdivision meshes of the USD stage at `path` (`.usda`,
/// `.usdc`, `.usdz`, or `.usd` in either encoding).
///
/// The stage is composed as the `openusd` crate composes it (sublayers,
/// references, payloads — all loaded —, inherits, specializes, variant
/// selections), with legacy type names read as their current ones (see the
/// [module documentation](super)). Prims are visited as USD's default
/// traversal does — active, loaded, defined, not abstract (`class` prims and
/// what is under them are left out) — entering instances (their prims are
/// read at their instance-proxy paths). Every `Mesh` prim that
/// [`UsdReadOptions::prims`] selects is read, with its attributes at
/// [`UsdReadOptions::time`]; attributes that are not mesh attributes are
/// ignored, as USD ignores them.
///
/// # Errors
///
/// [`Error::Usd`] naming the file, and where it applies the prim and the
/// attribute: the file cannot be opened, parsed or composed
/// ([`UsdErrorKind::Open`]; so is a layer that is not a regular file, or
/// that has a prim name or a path Pixar's USD refuses — a name that is not
/// an identifier, a path with characters no path has —, or brackets nested
/// deeper than the limits below), a prim pattern is not absolute ([`UsdErrorKind::Pattern`]),
/// or a selected mesh is malformed — an
/// index out of range, counts that do not add up, sharpnesses that do not
/// match their creases or corners, an unknown token, a primvar with the
/// wrong number of values for its interpolation, or a mesh that
/// [`Mesh::validate`](crate::Mesh::validate) refuses. With
/// [`UsdReadOptions::lenient`], malformed creases and corners are dropped
/// with a warning instead.
///
/// The stage is read on a thread of its own with a 64 MiB stack (reserved,
/// not committed), as the USD library recurses once per level of nesting of
/// the text it parses; nesting deeper than 256 levels (8 for `[`) is
/// refused as unreadable.
pub fn read_usd(path: &Path, options: &UsdReadOptions) -> Result<UsdStage, Error> {
    let (file, opts) = (path.to_path_buf(), options.clone());
    let worker = std::thread::Builder::new()
        .name("usd-reader".to_string())
        .stack_size(READER_STACK)
        .spawn(move || read_stage(&file, &opts));
    match worker {
        Ok(handle) => handle
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic)),
        Err(e) => Err(Error::from(UsdError {
            file: path.to_path_buf(),
            prim: String::new(),
            attribute: String::new(),
            kind: UsdErrorKind::Open(format!("cannot start the reading thread: {e}")),
        })),
    }
}

/// The stack of the thread [`read_usd`] reads on: the `openusd` crate
/// parses and composes recursively, a level of stack per level of nesting
/// (some 20 KiB in a debug build), up to
/// [`MAX_NESTING`](super::text::MAX_NESTING) levels. Reserved, not
/// committed: only what is used is backed by memory.
const READER_STACK: usize = 64 << 20;

/// [`read_usd`], on the calling thread.
fn read_stage(path: &Path, options: &UsdReadOptions) -> Result<UsdStage, Error> {
    let file_error = |kind| {
        Error::from(UsdError {
            file: path.to_path_buf(),
            prim: String::new(),
            attribute: String::new(),
            kind,
        })
    };
    let patterns = options
        .prims
        .iter()
        .map(|text| {
            Pattern::new(text).map_err(|reason| {
                file_error(UsdErrorKind::Pattern {
                    pattern: text.clone(),
                    reason,
                })
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    if let Some(time) = options.time.filter(|t| !t.is_finite()) {
        let message = format!("the time {time} is not a finite number");
        return Err(file_error(UsdErrorKind::Open(message)));
    }
    let open_error = |e| file_error(library(e));
    let path_text = path
        .to_str()
        .ok_or_else(|| file_error(UsdErrorKind::Open("the path is not valid UTF-8".into())))?;
    // The library opens what its resolver finds: say plainly when that is
    // nothing.
    if let Err(e) = std::fs::metadata(path) {
        return Err(file_error(UsdErrorKind::Open(e.to_string())));
    }
    let stage = usd::Stage::builder()
        .resolver(LayerResolver::new())
        .interpolation_type(usd::InterpolationType::Held)
        .open(path_text)
        .map_err(open_error)?;

    let mut prim_paths = Vec::new();
    stage
        .traverse(usd::PrimPredicate::DEFAULT_PROXIES, |p| {
            prim_paths.push(p.clone())
        })
        .map_err(open_error)?;

    let mut result = UsdStage::default();
    let mut matched = vec![false; patterns.len()];
    for prim_path in prim_paths {
        let prim = stage.prim(prim_path.clone());
        let is_mesh = prim
            .type_name()
            .map_err(open_error)?
            .is_some_and(|t| t.as_str() == "Mesh");
        if !is_mesh {
            continue;
        }
        let text = prim_path.as_str().to_string();
        if !patterns.is_empty() {
            let mut selected = false;
            for (pattern, hit) in patterns.iter().zip(&mut matched) {
                if pattern.matches(&text) {
                    *hit = true;
                    selected = true;
                }
            }
            if !selected {
                continue;
            }
        }
        let mut ctx = Context {
            file: path,
            prim_path: text,
            prim,
            time: options.time,
            lenient: options.lenient,
            warnings: Vec::new(),
        };
        let outcome = read_mesh(&mut ctx)?;
        result.warnings.append(&mut ctx.warnings);
        match outcome {
            Outcome::Mesh(mesh) => result.meshes.push(*mesh),
            Outcome::Skipped(reason) => result.skipped.push(UsdSkipped {
                prim: ctx.prim_path,
                reason,
            }),
        }
    }

    for error in stage.composition_errors() {
        result.warnings.push(UsdWarning {
            prim: String::new(),
            attribute: String::new(),
            message: format!("composition: {error}"),
        });
    }
    for (pattern, _) in patterns.iter().zip(&matched).filter(|(_, hit)| !**hit) {
        result.warnings.push(UsdWarning {
            prim: String::new(),
            attribute: String::new(),
            message: format!("prim pattern {:?} matches no Mesh prim", pattern.text()),
        });
    }
    Ok(result)
}
