//! The limit surface of every base face, evaluated in Bfr's parameterization
//! ([`LimitSurfaces`]).
//!
//! OpenSubdiv's `Bfr::RefinerSurfaceFactory` builds each face's surface from
//! its neighbourhood: a regular patch where the face is regular, else the
//! patches of an adaptive refinement of the face alone — isolated to
//! `approxLevelSharp` around sharp features and `approxLevelSmooth` around
//! smooth ones, infinitely sharp features as patches, single creases
//! refined, Gregory patches at the last level. The limit surface over a face
//! depends on its neighbourhood alone, so the same patches come out of one
//! adaptive refinement of the whole mesh with those options: that is what
//! the native engine builds here, once for every face, and evaluates through
//! its [`PatchMap`], mapping Bfr's (u, v) to ptex faces (a sub-face of an
//! n-gon is its ptex face, in normalized coordinates). Derivatives are with
//! respect to those ptex coordinates, as Bfr's are. Smooth corners are not
//! approximated by sharp ones (Bfr's patch builder does not; the patch
//! table's legacy sharp-corner patches are off).
//!
//! Face-varying data is evaluated over the same patches where the channels
//! are interpolated linearly (`FVarLinearInterpolation::All`, and every
//! channel under the bilinear scheme); smooth channels get surfaces of their
//! own, the non-linear face-varying patches of a second refinement that
//! isolates their features too (`considerFVarChannels`), as Bfr builds a
//! face-varying surface from the channel's topology.

use crate::alloc;
use crate::bfr::Parameterization;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::options::{FVarLinearInterpolation, Options, Scheme};
use crate::patches::{
    self, Derivatives, EndCapType, PatchData, PatchMap, PatchOptions, PatchTable, SurfaceSamples,
};
use crate::ptex::PtexIndices;
use crate::refiner::{AdaptiveRefiner, Refiner};

/// Options of the surfaces (`Bfr::SurfaceFactory::Options`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct SurfaceOptions {
    /// How deep smooth irregular features are refined (2).
    pub approx_level_smooth: u32,
    /// How deep sharp irregular features are refined (6).
    pub approx_level_sharp: u32,
    /// The face-varying channel of
    /// [`SurfaceFactory::default_fvar_surface`](crate::bfr::SurfaceFactory::default_fvar_surface)
    /// (`SetDefaultFVarID`; 0).
    pub default_fvar_channel: usize,
    /// Whether a factory keeps the refined neighbourhood of each topology
    /// of irregular face it has built, for the faces that share it
    /// (`EnableCaching`; on). The native cache is keyed by the whole
    /// topology, not by a hash; OpenSubdiv's own cache stays off in the
    /// bridge (`osd::bfr_surface`). Either way the surfaces are the same.
    pub caching: bool,
}

impl SurfaceOptions {
    /// The default options with approximation levels `smooth` and `sharp`.
    pub const fn with_levels(smooth: u32, sharp: u32) -> Self {
        SurfaceOptions {
            approx_level_smooth: smooth,
            approx_level_sharp: sharp,
            default_fvar_channel: 0,
            caching: true,
        }
    }
}

impl Default for SurfaceOptions {
    fn default() -> Self {
        SurfaceOptions::with_levels(2, 6)
    }
}

/// The limit surfaces of a mesh's base faces, natively.
#[derive(Debug)]
pub struct LimitSurfaces {
    scheme: Scheme,
    face_sizes: Vec<u32>,
    holes: Vec<bool>,
    ptex: PtexIndices,
    table: PatchTable,
    map: PatchMap,
    points: Vec<f64>,
    /// Per face-varying channel: its patch points and its width.
    fvar: Vec<(Vec<f64>, usize)>,
    /// The patches of channels interpolated smoothly (a refinement that
    /// isolated their features too), when the mesh has such channels; the
    /// vertex patches serve linear ones.
    fvar_map: Option<(PatchMap, PatchTable)>,
}

impl LimitSurfaces {
    /// The surfaces of `mesh`'s faces under `options`.
    ///
    /// Not native yet ([`Error::NotYetSupported`]): approximation levels of
    /// 0 (Bfr then refines some faces once regardless). Loop meshes get
    /// box-spline patches and Gregory triangles.
    pub fn new(mesh: &Mesh, options: &Options, surface: &SurfaceOptions) -> Result<Self> {
        let sharp = surface.approx_level_sharp;
        let smooth = surface.approx_level_smooth.min(sharp);
        if smooth == 0 {
            return Err(Error::NotYetSupported(
                "Bfr surfaces with an approximation level of 0",
            ));
        }
        let refiner = Refiner::new(mesh, options)?;
        let ptex = PtexIndices::new(&refiner)?;
        let adaptive_options = crate::AdaptiveOptions::new(sharp)
            .secondary(smooth)
            .inf_sharp_patch(true);
        let mut patch_options = PatchOptions::new()
            .end_caps(EndCapType::GregoryBasis)
            .inf_sharp_patch(true)
            .max_isolation(sharp)
            .double_precision(true);
        patch_options.legacy_sharp_corner_patches = false;
        patch_options.fvar_tables = !mesh.fvar_channels.is_empty();
        let adaptive: AdaptiveRefiner = refiner.refine_adaptive(adaptive_options, &[])?;
        let table = adaptive.patch_table(&patch_options, &[])?;
        let points = adaptive.patch_points(&table, 3, &mesh.flat_positions())?;
        let linear_fvar =
            options.scheme == Scheme::Bilinear || options.fvar == FVarLinearInterpolation::All;
        // Channels interpolated smoothly have surfaces of their own: the
        // patches of a refinement isolating their features too, as Bfr's
        // face-varying surfaces are built from the channel's topology.
        let smooth_fvar = if linear_fvar || mesh.fvar_channels.is_empty() {
            None
        } else {
            let adaptive = Refiner::new(mesh, options)?
                .refine_adaptive(adaptive_options.consider_fvar(true), &[])?;
            let fvar_options = PatchOptions {
                fvar_legacy_linear_patches: false,
                ..patch_options.clone()
            };
            let table = adaptive.patch_table(&fvar_options, &[])?;
            Some((adaptive, table))
        };
        let mut fvar = Vec::new();
        for (k, channel) in mesh.fvar_channels.iter().enumerate() {
            let (adaptive, table) = match &smooth_fvar {
                Some((a, t)) => (a, t),
                None => (&adaptive, &table),
            };
            let values = adaptive.patch_data_points(
                table,
                PatchData::FaceVarying(k),
                channel.width,
                &channel.values,
            )?;
            fvar.push((values, channel.width));
        }
        let fvar_map = smooth_fvar.map(|(_, table)| (PatchMap::new(&table), table));
        let mut holes = alloc::try_vec(false, mesh.face_count())?;
        for &h in &mesh.holes {
            if let Some(slot) = holes.get_mut(h as usize) {
                *slot = true;
            }
        }
        Ok(LimitSurfaces {
            scheme: options.scheme,
            face_sizes: mesh.face_sizes(),
            holes,
            ptex,
            map: PatchMap::new(&table),
            table,
            points,
            fvar,
            fvar_map,
        })
    }

    /// The subdivision scheme.
    pub fn scheme(&self) -> Scheme {
        self.scheme
    }

    /// The number of base faces.
    pub fn face_count(&self) -> usize {
        self.face_sizes.len()
    }

    /// Whether base face `face` has a limit surface (holes do not, nor
    /// faces the patches do not cover).
    pub fn has_surface(&self, face: usize) -> bool {
        self.face_sizes.get(face).is_some_and(|_| {
            !self.holes[face]
                && self
                    .ptex
                    .face_id(face)
                    .is_ok_and(|p| self.map.find_patch(p, 0.5, 0.5).is_some())
        })
    }

    /// The parameterization of base face `face`.
    pub fn parameterization(&self, face: usize) -> Result<Parameterization> {
        let size = self.face_size(face)?;
        Parameterization::new(self.scheme, size)
    }

    fn face_size(&self, face: usize) -> Result<usize> {
        self.face_sizes
            .get(face)
            .map(|&s| s as usize)
            .ok_or(Error::NoSuchElement {
                element: crate::error::Element::Face,
                index: face,
                level: 0,
                count: self.face_sizes.len(),
            })
    }

    /// The positions (3 components each) of `face`'s limit surface at
    /// `coords` in its parameterization, with the derivatives asked for.
    pub fn evaluate(
        &self,
        face: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        self.evaluate_data(face, PatchData::Vertex, coords, derivatives)
    }

    /// Face-varying channel `channel`'s values over `face` at `coords`.
    pub fn evaluate_fvar(
        &self,
        face: usize,
        channel: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        self.evaluate_data(face, PatchData::FaceVarying(channel), coords, derivatives)
    }

    fn evaluate_data(
        &self,
        face: usize,
        data: PatchData,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        let param = self.parameterization(face)?;
        let (points, width) = match data {
            PatchData::FaceVarying(k) => match self.fvar.get(k) {
                Some((points, width)) => (&points[..], *width),
                None => {
                    return Err(Error::NoSuchChannel {
                        channel: k,
                        count: self.fvar.len(),
                    });
                }
            },
            _ => (&self.points[..], 3),
        };
        let first = self.ptex.face_id(face)?;
        let mut locations = Vec::new();
        alloc::reserve(&mut locations, coords.len())?;
        for &uv in coords {
            if !param.contains(uv, 1e-9) {
                return Err(Error::OffFace {
                    face,
                    u: uv[0],
                    v: uv[1],
                    domain: param.domain(),
                });
            }
            let (sub, [s, t]) = if param.has_subfaces() {
                param.coord_to_subface(uv, true)?
            } else {
                (0, uv)
            };
            // Bfr's sub-face coordinates may stray just outside [0, 1].
            locations.push((first + sub as u32, s.clamp(0.0, 1.0), t.clamp(0.0, 1.0)));
        }
        let (map, table) = match (&data, &self.fvar_map) {
            (PatchData::FaceVarying(_), Some((map, table))) => (map, table),
            _ => (&self.map, &self.table),
        };
        patches::evaluate_data(map, table, data, points, width, &locations, derivatives)
    }
}
