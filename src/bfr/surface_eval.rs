//! Evaluating one face's surface ([`Surface`]): its limit stencils
//! (`EvaluateStencil`), its patch points (`PreparePatchPoints`) and its
//! values and derivatives at (u, v) of its parameterization (`Evaluate`),
//! for each form a surface takes — linear, one regular patch, or the
//! patches of its control hull's refinement.

use super::ParameterizationType;
use super::face_surface::{Form, Surface};
use super::parameterization::Parameterization;
use crate::alloc;
use crate::error::{Error, Result};
use crate::patches::basis::{BasisBuffer, evaluate_basis_into};
use crate::patches::limit_stencils::stencils_at;
use crate::patches::{
    Derivatives, LimitStencilOptions, Partials, PatchData, PatchParam, PatchType, SurfaceSamples,
    evaluate_basis, evaluate_data,
};

/// The four weights of a sub-face of a split n-gon turned into the weights
/// of the n-gon's vertices: origin, next, any other, previous
/// (`transformLinearQuadWeightsToStencil`).
fn split_weights(w: [f64; 4], n: usize) -> [f64; 4] {
    let (origin, next, center, prev) = (w[0], w[1] * 0.5, w[2] / n as f64, w[3] * 0.5);
    [
        center + next + prev + origin,
        center + next,
        center,
        center + prev,
    ]
}

impl Surface {
    /// A surface without a limit.
    pub(super) fn invalid(face: usize, param: Parameterization) -> Surface {
        Surface {
            face,
            param,
            control_points: Vec::new(),
            patch_points: 0,
            form: Form::Invalid,
        }
    }

    /// The base face.
    pub fn face(&self) -> usize {
        self.face
    }

    /// `IsValid`: the face has a limit surface.
    pub fn is_valid(&self) -> bool {
        !matches!(self.form, Form::Invalid)
    }

    /// `IsRegular`: one regular patch (or a linear face of the scheme's
    /// regular size).
    pub fn is_regular(&self) -> bool {
        match self.form {
            Form::Regular { .. } => true,
            Form::Linear { regular } => regular,
            _ => false,
        }
    }

    /// `IsLinear`: the bilinear scheme's surface.
    pub fn is_linear(&self) -> bool {
        matches!(self.form, Form::Linear { .. })
    }

    /// `GetControlPointIndices`: the mesh vertices the surface depends on,
    /// in Bfr's order (empty for an invalid surface).
    pub fn control_points(&self) -> &[u32] {
        &self.control_points
    }

    /// `GetNumPatchPoints`: the control points and the points Bfr computes
    /// from them to evaluate the surface (0 for an invalid surface).
    pub fn patch_point_count(&self) -> usize {
        self.patch_points
    }

    /// `GetParameterization`.
    pub fn parameterization(&self) -> Parameterization {
        self.param
    }

    /// `EvaluateStencil`: for each of `coords`, the weights of the control
    /// points (in [`Surface::control_points`]' order) giving the surface's
    /// value and the derivatives asked for there.
    ///
    /// Refused ([`Error::OffFace`], naming the face): coordinates off the
    /// face's domain, and any coordinate of a surface without a limit.
    pub fn evaluate_stencil(
        &self,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<Vec<Partials>> {
        let mut out = Vec::new();
        alloc::reserve(&mut out, coords.len())?;
        if let Some(&uv) = coords
            .iter()
            .find(|&&uv| !self.is_valid() || !self.param.contains(uv, 1e-9))
        {
            return Err(self.off_face(uv));
        }
        match &self.form {
            Form::Invalid => {}
            Form::Linear { regular: true } => {
                let patch = if self.control_points.len() == 4 {
                    PatchType::Quads
                } else {
                    PatchType::Triangles
                };
                for &uv in coords {
                    let [u, v] = self.clamped(uv);
                    out.push(evaluate_basis(
                        patch,
                        PatchParam::default(),
                        u,
                        v,
                        derivatives,
                    )?);
                }
            }
            Form::Linear { regular: false } => {
                for &uv in coords {
                    out.push(self.split_stencil(uv, derivatives)?);
                }
            }
            Form::Regular { patch, mask } => {
                let param = PatchParam::new(0, 0, 0, 0, false, *mask, 0, true);
                for &uv in coords {
                    let [u, v] = self.clamped(uv);
                    out.push(evaluate_basis(*patch, param, u, v, derivatives)?);
                }
            }
            Form::Irregular(irregular) => {
                let locations = self.locations(coords)?;
                let options = LimitStencilOptions::new()
                    .first_derivatives(derivatives != Derivatives::None)
                    .second_derivatives(derivatives == Derivatives::Second);
                let stencils = stencils_at(
                    &irregular.table,
                    irregular.base,
                    &irregular.refined,
                    &locations,
                    &options,
                )?;
                let n = self.control_points.len();
                for s in 0..stencils.len() {
                    let range = stencils.offsets[s] as usize
                        ..stencils.offsets[s] as usize + stencils.sizes[s] as usize;
                    let w = &stencils.weights;
                    let dense = |column: &[f64]| -> Result<Vec<f64>> {
                        if column.is_empty() {
                            return Ok(Vec::new());
                        }
                        let mut d = alloc::try_vec(0.0, n)?;
                        for k in range.clone() {
                            d[stencils.indices[k] as usize] += column[k];
                        }
                        Ok(d)
                    };
                    out.push(Partials {
                        point: dense(&w.point)?,
                        du: dense(&w.du)?,
                        dv: dense(&w.dv)?,
                        duu: dense(&w.duu)?,
                        duv: dense(&w.duv)?,
                        dvv: dense(&w.dvv)?,
                    });
                }
            }
        }
        Ok(out)
    }

    fn clamped(&self, [u, v]: [f64; 2]) -> [f64; 2] {
        let (u, v) = (u.clamp(0.0, 1.0), v.clamp(0.0, 1.0));
        if self.param.kind() == ParameterizationType::Triangle && u + v > 1.0 {
            let excess = (u + v - 1.0) / 2.0;
            [u - excess, v - excess]
        } else {
            [u, v]
        }
    }

    /// The stencil of a split n-gon of the bilinear scheme
    /// (`evalMultiLinearStencils`).
    fn split_stencil(&self, uv: [f64; 2], derivatives: Derivatives) -> Result<Partials> {
        let (sub, [s, t]) = self.param.coord_to_subface(uv, true)?;
        let n = self.control_points.len();
        let w = evaluate_basis(
            PatchType::Quads,
            PatchParam::default(),
            s.clamp(0.0, 1.0),
            t.clamp(0.0, 1.0),
            derivatives,
        )?;
        let spread = |column: &[f64], scale: f64| -> Vec<f64> {
            if column.is_empty() {
                return Vec::new();
            }
            let q = split_weights(
                [column[0], column[1], column[2], column[3]].map(|x| x * scale),
                n,
            );
            (0..n)
                .map(|i| {
                    if i == sub {
                        q[0]
                    } else if i == (sub + 1) % n {
                        q[1]
                    } else if i == (sub + n - 1) % n {
                        q[3]
                    } else {
                        q[2]
                    }
                })
                .collect()
        };
        let zeros = |column: &[f64]| vec![0.0; if column.is_empty() { 0 } else { n }];
        Ok(Partials {
            point: spread(&w.point, 1.0),
            du: spread(&w.du, 2.0),
            dv: spread(&w.dv, 2.0),
            duu: zeros(&w.duu),
            duv: spread(&w.duv, 4.0),
            dvv: zeros(&w.dvv),
        })
    }

    /// `PreparePatchPoints` (with `GatherControlPoints`): the surface's
    /// patch points from the mesh's points (`width` values per mesh
    /// vertex), in Bfr's order — the control points, then for a split
    /// n-gon its centre and edge midpoints, for an irregular surface every
    /// vertex of its hull's refinement level by level and the points of its
    /// end caps; [`Surface::patch_point_count`] of them.
    pub fn patch_points(&self, points: &[f64], width: usize) -> Result<Vec<f64>> {
        self.check_points(points, width)?;
        let mut out = Vec::new();
        alloc::reserve(&mut out, self.patch_points.saturating_mul(width))?;
        for &cv in &self.control_points {
            out.extend_from_slice(&points[cv as usize * width..(cv as usize + 1) * width]);
        }
        match &self.form {
            Form::Linear { regular: false } => {
                let n = self.control_points.len();
                let mut centre = vec![0.0; width];
                for i in 0..n {
                    for (c, &x) in centre.iter_mut().zip(&out[i * width..(i + 1) * width]) {
                        *c += x;
                    }
                }
                centre.iter_mut().for_each(|c| *c /= n as f64);
                out.extend_from_slice(&centre);
                for i in 0..n {
                    let j = (i + 1) % n;
                    for k in 0..width {
                        out.push(0.5 * (out[i * width + k] + out[j * width + k]));
                    }
                }
            }
            Form::Irregular(irregular) => {
                let native = irregular
                    .refiner
                    .patch_points(&irregular.table, width, &out)?;
                let vertices = native.len() / width - irregular.local_order.len();
                out = native[..vertices * width].to_vec();
                out.resize(native.len(), 0.0);
                for (i, &to) in irregular.local_order.iter().enumerate() {
                    let from = (vertices + i) * width;
                    out[to * width..(to + 1) * width].copy_from_slice(&native[from..from + width]);
                }
            }
            _ => {}
        }
        Ok(out)
    }

    /// `Evaluate` over patch points from [`Surface::patch_points`] (`width`
    /// values each): the surface's values and the derivatives asked for at
    /// `coords`.
    pub fn evaluate_patch_points(
        &self,
        patch_points: &[f64],
        width: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        if width == 0 {
            return Err(Error::ZeroWidth);
        }
        let expected = self.patch_points.saturating_mul(width);
        if patch_points.len() != expected {
            return Err(Error::BufferLength {
                buffer: crate::error::Buffer::Base,
                expected,
                got: patch_points.len(),
            });
        }
        if let Form::Irregular(irregular) = &self.form {
            let vertices = self.patch_points - irregular.local_order.len();
            let mut native = patch_points[..vertices * width].to_vec();
            native.resize(patch_points.len(), 0.0);
            for (i, &from) in irregular.local_order.iter().enumerate() {
                let to = (vertices + i) * width;
                native[to..to + width]
                    .copy_from_slice(&patch_points[from * width..(from + 1) * width]);
            }
            let locations = self.locations(coords)?;
            return evaluate_data(
                &irregular.map,
                &irregular.table,
                PatchData::Vertex,
                &native,
                width,
                &locations,
                derivatives,
            );
        }
        // The other forms' stencils weigh the control points, which lead
        // the patch points.
        let identity: Vec<u32> = (0..self.control_points.len() as u32).collect();
        self.apply_stencils(&identity, patch_points, width, coords, derivatives)
    }

    fn check_points(&self, points: &[f64], width: usize) -> Result<()> {
        if width == 0 {
            return Err(Error::ZeroWidth);
        }
        if let Some(&v) = self
            .control_points
            .iter()
            .find(|&&v| (v as usize + 1).saturating_mul(width) > points.len())
        {
            return Err(Error::BufferLength {
                buffer: crate::error::Buffer::Base,
                expected: (v as usize + 1).saturating_mul(width),
                got: points.len(),
            });
        }
        Ok(())
    }

    /// The ptex locations of the hull's first face at `coords`.
    fn locations(&self, coords: &[[f64; 2]]) -> Result<Vec<(u32, f64, f64)>> {
        let mut locations = Vec::new();
        alloc::reserve(&mut locations, coords.len())?;
        for &uv in coords {
            if !self.is_valid() || !self.param.contains(uv, 1e-9) {
                return Err(self.off_face(uv));
            }
            let (sub, [s, t]) = if self.param.has_subfaces() {
                self.param.coord_to_subface(uv, true)?
            } else {
                (0, uv)
            };
            locations.push((sub as u32, s.clamp(0.0, 1.0), t.clamp(0.0, 1.0)));
        }
        Ok(locations)
    }

    fn off_face(&self, [u, v]: [f64; 2]) -> Error {
        Error::OffFace {
            face: self.face,
            u,
            v,
            domain: if self.is_valid() {
                self.param.domain()
            } else {
                "no limit surface"
            },
        }
    }

    /// `Evaluate` over the mesh's points (`width` values per mesh vertex):
    /// the surface's values and the derivatives asked for at `coords`, its
    /// stencils applied to its control points.
    pub fn evaluate(
        &self,
        points: &[f64],
        width: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        self.check_points(points, width)?;
        match self.form {
            Form::Irregular(_) => {
                // Through the patch points: cheaper than a stencil per
                // coordinate once there are more than a few.
                let patch_points = self.patch_points(points, width)?;
                self.evaluate_patch_points(&patch_points, width, coords, derivatives)
            }
            Form::Regular { patch, mask } => {
                self.evaluate_regular(patch, mask, points, width, coords, derivatives)
            }
            _ => self.apply_stencils(&self.control_points, points, width, coords, derivatives),
        }
    }

    /// A regular patch evaluated coordinate by coordinate, its basis
    /// weights applied to its control points without a stencil per
    /// coordinate.
    fn evaluate_regular(
        &self,
        patch: PatchType,
        mask: u16,
        points: &[f64],
        width: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        if let Some(&uv) = coords.iter().find(|&&uv| !self.param.contains(uv, 1e-9)) {
            return Err(self.off_face(uv));
        }
        let kinds = match derivatives {
            Derivatives::None => 1,
            Derivatives::First => 3,
            Derivatives::Second => 6,
        };
        let len = coords.len().saturating_mul(width);
        let mut columns: [Vec<f64>; 6] = Default::default();
        for column in columns.iter_mut().take(kinds) {
            *column = alloc::try_vec(0.0, len)?;
        }
        let param = PatchParam::new(0, 0, 0, 0, false, mask, 0, true);
        let mut buf: BasisBuffer = [[0.0; 20]; 6];
        for (i, &uv) in coords.iter().enumerate() {
            let [u, v] = self.clamped(uv);
            let n = evaluate_basis_into(patch, param, u, v, derivatives, None, &mut buf)?;
            for (column, weights) in columns.iter_mut().zip(&buf).take(kinds) {
                let out = &mut column[i * width..(i + 1) * width];
                for (&cv, &w) in self.control_points.iter().zip(&weights[..n]) {
                    let p = &points[cv as usize * width..(cv as usize + 1) * width];
                    for (o, &x) in out.iter_mut().zip(p) {
                        *o += w * x;
                    }
                }
            }
        }
        Ok(SurfaceSamples {
            width,
            values: Partials::from_columns(columns),
        })
    }

    /// The stencils at `coords` applied to `points`, the stencils' weights
    /// going to the points at `indices`.
    fn apply_stencils(
        &self,
        indices: &[u32],
        points: &[f64],
        width: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        let stencils = self.evaluate_stencil(coords, derivatives)?;
        let mut columns: [Vec<f64>; 6] = Default::default();
        for s in &stencils {
            let parts = [&s.point, &s.du, &s.dv, &s.duu, &s.duv, &s.dvv];
            for (col, weights) in columns.iter_mut().zip(parts) {
                if weights.is_empty() {
                    continue;
                }
                let start = col.len();
                col.resize(start + width, 0.0);
                for (&cv, &w) in indices.iter().zip(weights) {
                    let p = &points[cv as usize * width..(cv as usize + 1) * width];
                    for (o, &x) in col[start..].iter_mut().zip(p) {
                        *o += w * x;
                    }
                }
            }
        }
        Ok(SurfaceSamples {
            width,
            values: Partials::from_columns(columns),
        })
    }
}
