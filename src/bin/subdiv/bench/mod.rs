//! Side-by-side benchmarks of the native engine and OpenSubdiv, measured in
//! the same process and the same run (interleaved repetitions, medians), as
//! `subdiv bench` prints and writes them.

#[cfg(feature = "osd")]
mod adaptive;
mod command;
#[cfg(feature = "osd")]
mod parallel;
#[cfg(feature = "osd")]
mod process;
#[cfg(feature = "osd")]
mod render;
#[cfg(feature = "osd")]
pub(crate) mod results;
#[cfg(feature = "osd")]
mod run;
#[cfg(feature = "osd")]
mod tessellation;
#[cfg(all(test, feature = "osd"))]
mod tests;
#[cfg(feature = "osd")]
pub(crate) mod timing;

pub(crate) use command::{BenchArgs, bench};
