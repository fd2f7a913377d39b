//! The conformance and performance report (`subdiv report`): the native
//! engine against OpenSubdiv on a set of inputs, for every scheme and option
//! that applies, with benchmarks, written as Markdown and as a self-contained
//! HTML page (inline CSS and inline SVG plots and pictures).
//!
//! For each [`Input`], [`run`]:
//!
//! - refines the mesh with both engines ([`subdiv::Engine::refine`]) for
//!   the option sets [`coverage::choose`] picks by the input's size (every
//!   combination of [`option_sets`] for the usual test meshes, down to the
//!   mesh's own options for a production asset; all with `--all-options`) and
//!   compares them level by level ([`crate::compare::compare`]): topology,
//!   positions relative to the bounding-box diagonal, face-varying values;
//!   then evaluates the limit at the last level with both and compares limit
//!   positions, tangents and face-varying values;
//! - times "refine + positions" (topology refinement and `f64` position
//!   interpolation of every level) per level with the input's own options,
//!   both engines interleaved, medians ([`bench::interleaved`]), the native
//!   engine on one thread;
//! - draws the native refined shape, each face coloured by how far its
//!   vertices are from OpenSubdiv's;
//! - compares the limit surface through both engines' patch tables, and
//!   tessellates it the Bfr way over both engines' surfaces
//!   ([`tessellated`]), each drawn coloured by deviation.
//!
//! ```no_run
//! use subdiv::report::{self, Settings};
//! let inputs = report::embedded_inputs();
//! let rep = report::run(&inputs, &Settings::new(true), |_| {})?;
//! rep.write(std::path::Path::new("report"))?;
//! assert!(rep.conforms());
//! # Ok::<(), subdiv::Error>(())
//! ```

mod command;
#[cfg(feature = "osd")]
mod coverage;
#[cfg(feature = "osd")]
mod files;
#[cfg(feature = "osd")]
mod format;
#[cfg(feature = "osd")]
mod html;
#[cfg(feature = "osd")]
mod inputs;
#[cfg(feature = "osd")]
mod markdown;
#[cfg(feature = "osd")]
mod picture;
#[cfg(feature = "osd")]
mod plot;
#[cfg(feature = "osd")]
mod results;
#[cfg(feature = "osd")]
mod run;
#[cfg(feature = "osd")]
mod settings;
#[cfg(feature = "osd")]
mod tessellated;
#[cfg(all(test, feature = "osd"))]
mod tests;

pub(crate) use command::{ReportArgs, report};
#[cfg(feature = "osd")]
pub(crate) use inputs::read_inputs;
