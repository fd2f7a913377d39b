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
//! Face-varying data is evaluated as Bfr does for channels interpolated
//! linearly (`FVarLinearInterpolation::All`, and every channel under the
//! bilinear scheme); smooth face-varying surfaces are not native yet.

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
}

impl Default for SurfaceOptions {
    fn default() -> Self {
        SurfaceOptions {
            approx_level_smooth: 2,
            approx_level_sharp: 6,
        }
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
    /// Per face-varying channel: its patch points, when Bfr interpolates
    /// it linearly (else `None`), and its width.
    fvar: Vec<(Option<Vec<f64>>, usize)>,
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
        let mut fvar = Vec::new();
        for (k, channel) in mesh.fvar_channels.iter().enumerate() {
            let values = if linear_fvar {
                Some(adaptive.patch_data_points(
                    &table,
                    PatchData::FaceVarying(k),
                    channel.width,
                    &channel.values,
                )?)
            } else {
                None
            };
            fvar.push((values, channel.width));
        }
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
                Some((Some(points), width)) => (&points[..], *width),
                Some((None, _)) => {
                    return Err(Error::NotYetSupported(
                        "Bfr face-varying surfaces of channels not interpolated linearly",
                    ));
                }
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
        patches::evaluate_data(
            &self.map,
            &self.table,
            data,
            points,
            width,
            &locations,
            derivatives,
        )
    }
}
