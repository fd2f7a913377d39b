//! One way to drive either engine: an [`Engine`] value and one [`Request`]
//! (both defined with the other options in [`crate::options`]); this module
//! dispatches them to the native refiner or to the OpenSubdiv bridge.
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
use crate::options::UniformOptions;
use crate::options::{Engine, Options, Request};
use crate::output::{LevelCounts, Refinement};
use crate::real::{Precision, Real};
use std::borrow::Cow;

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
    /// [`Error::OsdUnavailable`](crate::Error::OsdUnavailable).
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
                Err(crate::Error::OsdUnavailable)
            }
        }
    }

    /// The cheapest complete refinement: the topology of every level, the
    /// positions and every face-varying channel interpolated to the last
    /// level (in `request`'s precision), returning every level's counts.
    /// Nothing else is kept (the native engine releases each level, and its
    /// channels' levels, once the next exists); limits are not computed.
    /// This is what `subdiv refine` does without an output file.
    pub fn refine_counts(
        self,
        mesh: &Mesh,
        options: &Options,
        request: impl Into<Request>,
    ) -> Result<Vec<LevelCounts>> {
        self.counts(Cow::Borrowed(mesh), options, request.into())
    }

    /// [`Engine::refine_counts`], consuming the mesh: the native engine
    /// drops its faces, tags and channel indices once the base level is
    /// built and its positions once level 1 has been interpolated, which
    /// lowers the peak memory of a program that needs the mesh no more
    /// (`subdiv refine` without an output file). The same counts.
    ///
    /// ```
    /// use subdiv::{Engine, Options, Request, shapes};
    /// let torus = shapes::torus(8, 6);
    /// let borrowed = Engine::Native.refine_counts(&torus, &Options::default(), Request::new(2))?;
    /// let owned = Engine::Native.refine_counts_owned(torus, &Options::default(), Request::new(2))?;
    /// assert_eq!(owned, borrowed);
    /// assert_eq!(owned[2].faces, 48 * 16);
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn refine_counts_owned(
        self,
        mesh: Mesh,
        options: &Options,
        request: impl Into<Request>,
    ) -> Result<Vec<LevelCounts>> {
        self.counts(Cow::Owned(mesh), options, request.into())
    }

    fn counts(
        self,
        mesh: Cow<'_, Mesh>,
        options: &Options,
        request: Request,
    ) -> Result<Vec<LevelCounts>> {
        let uniform = request.uniform;
        if request.precision == Precision::F32 {
            // The mesh's own errors come first (a value that is not finite
            // is one); then the values f32 cannot hold.
            mesh.validate()?;
            crate::limits::check_precision(&mesh, request.precision)?;
        }
        match (self, request.precision) {
            (Engine::Native, Precision::F64) => native_counts::<f64>(mesh, options, uniform),
            (Engine::Native, Precision::F32) => native_counts::<f32>(mesh, options, uniform),
            #[cfg(feature = "osd")]
            (Engine::Osd, Precision::F64) => osd_counts::<f64>(&mesh, options, uniform),
            #[cfg(feature = "osd")]
            (Engine::Osd, Precision::F32) => osd_counts::<f32>(&mesh, options, uniform),
            #[cfg(not(feature = "osd"))]
            (Engine::Osd, _) => {
                let _ = (mesh, options, uniform);
                Err(crate::Error::OsdUnavailable)
            }
        }
    }
}

/// [`Engine::refine_counts`] natively: levels released as they go (and an
/// owned mesh as soon as nothing reads it).
fn native_counts<T: Real>(
    mesh: Cow<'_, Mesh>,
    options: &Options,
    uniform: UniformOptions,
) -> Result<Vec<LevelCounts>> {
    let (counts, ..) = match mesh {
        Cow::Owned(mesh) => crate::refiner::refine_last_owned::<T>(mesh, options, uniform)?,
        Cow::Borrowed(mesh) => {
            let base = mesh.positions_as::<T>();
            let channels = !mesh.fvar_channels.is_empty();
            crate::refiner::refine_last_with(mesh, options, uniform, 3, &base, channels)?
        }
    };
    Ok(counts)
}

/// [`Engine::refine_counts`] by OpenSubdiv.
#[cfg(feature = "osd")]
fn osd_counts<T: Real>(
    mesh: &Mesh,
    options: &Options,
    uniform: UniformOptions,
) -> Result<Vec<LevelCounts>> {
    let mut r = crate::osd::TopologyRefiner::new(mesh, options)?;
    r.refine_uniform(uniform)?;
    drop(r.interpolate_last(3, &mesh.positions_as::<T>())?);
    for (c, channel) in mesh.fvar_channels.iter().enumerate() {
        let mut values = channel.values_as::<T>();
        for level in 1..=uniform.level {
            values = r.interpolate_face_varying(c, level, channel.width, &values)?;
        }
    }
    (0..=uniform.level).map(|l| r.level_counts(l)).collect()
}
