//! One way to drive either engine: an [`Engine`] value and one [`Request`].
//!
//! ```
//! use subdiv::{Engine, Options, Precision, Request, shapes};
//! let cube = shapes::cube();
//! let request = Request::new(2).precision(Precision::F32).limit(true);
//! let native = Engine::Native.refine(&cube, &Options::default(), request)?;
//! assert_eq!(native.last_level().face_count(), 96);
//! assert!(native.limit.is_some());
//! # #[cfg(feature = "osd")] {
//! let osd = Engine::Osd.refine(&cube, &Options::default(), request)?;
//! assert_eq!(osd.levels, native.levels);
//! # }
//! # Ok::<(), subdiv::Error>(())
//! ```

use crate::error::Result;
use crate::mesh::Mesh;
use crate::names::impl_named;
use crate::options::{Options, UniformOptions};
use crate::output::{LevelCounts, Refinement};
use crate::real::Precision;

/// Which refiner does the work.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Engine {
    /// The pure-Rust engine ([`crate::refiner`]).
    #[default]
    Native,
    /// OpenSubdiv through the C++ bridge ([`crate::osd`], feature `osd`).
    Osd,
}

impl_named!(Engine, "engine", { Native => "native", Osd => "osd" });

/// What to compute in one uniform refinement: the uniform options (level,
/// vertex order, full topology), the precision of the interpolation, and
/// whether limit values are evaluated at the last level.
///
/// `Request::new(level)` is OpenSubdiv's default uniform refinement in `f64`
/// without limits; a [`UniformOptions`] converts into a request of its own.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub struct Request {
    /// Level, vertex order and last-level topology.
    pub uniform: UniformOptions,
    /// The precision primvars are interpolated in.
    pub precision: Precision,
    /// Evaluate limit positions, tangents and face-varying values at the last
    /// level (the last level then keeps its full topology, as OpenSubdiv
    /// requires).
    pub limit: bool,
}

impl Request {
    /// Refine `level` levels with OpenSubdiv's defaults, in `f64`, no limit.
    pub fn new(level: u32) -> Request {
        UniformOptions::new(level).into()
    }

    /// This request with other uniform options.
    pub fn uniform(mut self, uniform: UniformOptions) -> Request {
        self.uniform = uniform;
        self
    }

    /// This request in another precision.
    pub fn precision(mut self, precision: Precision) -> Request {
        self.precision = precision;
        self
    }

    /// This request with (or without) limit evaluation.
    pub fn limit(mut self, limit: bool) -> Request {
        self.limit = limit;
        self
    }

    /// This request with child vertices ordered from faces first.
    pub fn faces_first(mut self, yes: bool) -> Request {
        self.uniform = self.uniform.faces_first(yes);
        self
    }

    /// The uniform options the engines refine with: those asked for, with
    /// full topology in the last level when limits are evaluated.
    pub fn effective_uniform(&self) -> UniformOptions {
        if self.limit {
            self.uniform.full_topology(true)
        } else {
            self.uniform
        }
    }
}

impl From<UniformOptions> for Request {
    fn from(uniform: UniformOptions) -> Request {
        Request {
            uniform,
            precision: Precision::F64,
            limit: false,
        }
    }
}

impl Engine {
    /// Whether this build has the engine (`Osd` needs the feature `osd`).
    pub fn is_available(self) -> bool {
        match self {
            Engine::Native => true,
            Engine::Osd => cfg!(feature = "osd"),
        }
    }

    /// Refines `mesh` as `request` says: the topology and interpolated
    /// positions and face-varying values of every level, and limits when
    /// asked. An engine this build lacks is
    /// [`Error::EngineUnavailable`](crate::Error::EngineUnavailable).
    pub fn refine(
        self,
        mesh: &Mesh,
        options: &Options,
        request: impl Into<Request>,
    ) -> Result<Refinement> {
        let request = request.into();
        match self {
            Engine::Native => crate::refiner::refine(mesh, options, request),
            #[cfg(feature = "osd")]
            Engine::Osd => crate::osd::refine(mesh, options, request),
            #[cfg(not(feature = "osd"))]
            Engine::Osd => {
                let _ = (mesh, options, request);
                Err(crate::Error::EngineUnavailable { engine: self })
            }
        }
    }

    /// The cheapest complete refinement: the topology of every level and the
    /// positions interpolated to the last level (in `request`'s precision),
    /// returning every level's counts. Nothing else is kept (the native
    /// engine releases each level once the next exists); face-varying
    /// channels and limits are not computed. This is what `subdiv refine`
    /// does without an output file.
    pub fn refine_counts(
        self,
        mesh: &Mesh,
        options: &Options,
        request: impl Into<Request>,
    ) -> Result<Vec<LevelCounts>> {
        let request = request.into();
        let uniform = request.uniform;
        match self {
            Engine::Native => {
                use crate::refiner::refine_last;
                Ok(match request.precision {
                    Precision::F64 => {
                        refine_last(mesh, options, uniform, 3, &mesh.flat_positions::<f64>())?.0
                    }
                    Precision::F32 => {
                        refine_last(mesh, options, uniform, 3, &mesh.flat_positions::<f32>())?.0
                    }
                })
            }
            #[cfg(feature = "osd")]
            Engine::Osd => {
                let mut r = crate::osd::TopologyRefiner::new(mesh, options)?;
                r.refine_uniform(uniform)?;
                match request.precision {
                    Precision::F64 => drop(r.interpolate_last(3, &mesh.flat_positions::<f64>())?),
                    Precision::F32 => drop(r.interpolate_last(3, &mesh.flat_positions::<f32>())?),
                }
                (0..=uniform.level).map(|l| r.level_counts(l)).collect()
            }
            #[cfg(not(feature = "osd"))]
            Engine::Osd => {
                let _ = (mesh, options, uniform);
                Err(crate::Error::EngineUnavailable { engine: self })
            }
        }
    }
}
