//! Every base face's limit surface the way OpenSubdiv's Bfr builds it, one
//! face at a time ([`MeshSurfaces`]): a [`SurfaceFactory`] with the mesh's
//! positions and face-varying values, each face's [`Surface`] built when
//! it is evaluated — index-exact with `Bfr::RefinerSurfaceFactory`
//! (control points, patch points, stencils), where [`LimitSurfaces`]
//! evaluates one adaptive refinement of the whole mesh instead.
//!
//! [`LimitSurfaces`]: crate::bfr::LimitSurfaces

use super::face_surface::{Shortcut, Surface, SurfaceFactory};
use super::mesher::FaceSurfaces;
use super::parameterization::Parameterization;
use super::surfaces::SurfaceOptions;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::options::{Options, Scheme};
use crate::patches::{Derivatives, SurfaceSamples};

/// The surfaces of a mesh's base faces, built face by face as Bfr builds
/// them, with the data to evaluate them on.
#[derive(Debug)]
pub struct MeshSurfaces {
    factory: SurfaceFactory,
    scheme: Scheme,
    points: Vec<f64>,
    /// Per face-varying channel: its values and width.
    fvar: Vec<(Vec<f64>, usize)>,
}

impl MeshSurfaces {
    /// The surfaces of `mesh`'s faces under `options`, approximated as
    /// `surface` says (approximation levels 0 to 10).
    pub fn new(mesh: &Mesh, options: &Options, surface: &SurfaceOptions) -> Result<Self> {
        Ok(MeshSurfaces {
            factory: SurfaceFactory::new(mesh, options, surface)?,
            scheme: options.scheme,
            points: mesh.flat_positions(),
            fvar: mesh
                .fvar_channels
                .iter()
                .map(|c| (c.values.clone(), c.width))
                .collect(),
        })
    }

    /// The factory the surfaces come from.
    pub fn factory(&self) -> &SurfaceFactory {
        &self.factory
    }

    /// The subdivision scheme.
    pub fn scheme(&self) -> Scheme {
        self.scheme
    }

    /// The number of base faces.
    pub fn face_count(&self) -> usize {
        self.factory.face_count()
    }

    /// Whether base face `face` has a limit surface.
    pub fn has_surface(&self, face: usize) -> bool {
        self.factory.has_limit_surface(face)
    }

    /// The parameterization of base face `face`.
    pub fn parameterization(&self, face: usize) -> Result<Parameterization> {
        self.factory.parameterization(face)
    }

    /// The positions (3 components each) of `face`'s limit surface at
    /// `coords` in its parameterization, with the derivatives asked for.
    pub fn evaluate(
        &self,
        face: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        let surface = self.factory.vertex_surface(face)?;
        surface.evaluate(&self.points, 3, coords, derivatives)
    }

    /// Face-varying channel `channel`'s values over `face` at `coords`.
    pub fn evaluate_fvar(
        &self,
        face: usize,
        channel: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        let (values, width) = self.fvar.get(channel).ok_or(Error::NoSuchChannel {
            channel,
            count: self.fvar.len(),
        })?;
        let surface: Surface = self.factory.fvar_surface(face, channel)?;
        surface.evaluate(values, *width, coords, derivatives)
    }
}

impl FaceSurfaces for MeshSurfaces {
    fn scheme(&self) -> Scheme {
        self.scheme
    }
    fn has_surface(&self, face: usize) -> bool {
        MeshSurfaces::has_surface(self, face)
    }
    fn evaluate(
        &self,
        face: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        MeshSurfaces::evaluate(self, face, coords, derivatives)
    }
    fn evaluate_fvar(
        &self,
        face: usize,
        channel: usize,
        coords: &[[f64; 2]],
    ) -> Result<SurfaceSamples> {
        MeshSurfaces::evaluate_fvar(self, face, channel, coords, Derivatives::None)
    }
    fn evaluate_into(
        &self,
        face: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
        out: &mut [&mut [f64]],
    ) -> Result<()> {
        let shortcut = self.factory.shortcut(face);
        self.positions_into(face, shortcut.as_ref(), coords, derivatives, out)
    }
    fn evaluate_with_fvar_into(
        &self,
        face: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
        out: &mut [&mut [f64]],
        (channel, fvar_coords, fvar_out): (usize, &[[f64; 2]], &mut [f64]),
    ) -> Result<()> {
        // The regular patch's points found once for both.
        let shortcut = self.factory.shortcut(face);
        self.positions_into(face, shortcut.as_ref(), coords, derivatives, out)?;
        self.fvar_into(face, shortcut.as_ref(), channel, fvar_coords, fvar_out)
    }
    fn base_edges(&self) -> Option<(&[u32], &[[u32; 2]])> {
        self.factory.base_edges()
    }
    fn evaluate_fvar_into(
        &self,
        face: usize,
        channel: usize,
        coords: &[[f64; 2]],
        out: &mut [f64],
    ) -> Result<()> {
        let shortcut = self.factory.shortcut(face);
        self.fvar_into(face, shortcut.as_ref(), channel, coords, out)
    }
}

impl MeshSurfaces {
    /// [`FaceSurfaces::evaluate_into`], `shortcut` the face's
    /// ([`SurfaceFactory::shortcut`]).
    fn positions_into(
        &self,
        face: usize,
        shortcut: Option<&Shortcut>,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
        out: &mut [&mut [f64]],
    ) -> Result<()> {
        // A regular face whose plan is kept: no surface built.
        if shortcut.is_some_and(|s| {
            self.factory
                .evaluate_shortcut_into(s, &self.points, coords, derivatives, out)
                .is_some()
        }) {
            return Ok(());
        }
        let surface = self.factory.vertex_surface(face)?;
        surface.evaluate_into(&self.points, 3.into(), coords, derivatives, out)
    }

    /// [`FaceSurfaces::evaluate_fvar_into`], `shortcut` the face's.
    fn fvar_into(
        &self,
        face: usize,
        shortcut: Option<&Shortcut>,
        channel: usize,
        coords: &[[f64; 2]],
        out: &mut [f64],
    ) -> Result<()> {
        let (values, width) = self.fvar.get(channel).ok_or(Error::NoSuchChannel {
            channel,
            count: self.fvar.len(),
        })?;
        // A regular face whose plan is kept: no surface built.
        if shortcut.is_some_and(|s| {
            self.factory
                .evaluate_fvar_shortcut_into(s, channel, values, *width, coords, out)
                .is_some()
        }) {
            return Ok(());
        }
        let surface: Surface = self.factory.fvar_surface(face, channel)?;
        surface.evaluate_into(
            values,
            (*width).into(),
            coords,
            Derivatives::None,
            &mut [out],
        )
    }
}
