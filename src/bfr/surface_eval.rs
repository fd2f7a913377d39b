//! Evaluating one face's surface ([`Surface`]): its limit stencils
//! (`EvaluateStencil`), its patch points (`PreparePatchPoints`) and its
//! values and derivatives at (u, v) of its parameterization (`Evaluate`),
//! for each form a surface takes — linear, one regular patch, or the
//! patches of its control hull's refinement.

use super::ParameterizationType;
use super::bspline_eval;
use super::face_surface::{ControlPoints, Form, Irregular, Surface};
use super::parameterization::Parameterization;
use crate::alloc;
use crate::error::{Error, Result};
use crate::patches::basis::{BasisBuffer, evaluate_basis_into};
use crate::patches::limit_stencils::stencils_at;
use crate::patches::{
    Derivatives, LimitStencilOptions, LocationStencils, Partials, PatchData, PatchParam, PatchType,
    SurfaceSamples, evaluate_basis, evaluate_data,
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
            control_points: ControlPoints::from_slice(&[]),
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
            &Form::Regular { patch, mask, .. } => {
                let param = PatchParam::new(0, 0, 0, 0, false, mask, 0, true);
                for &uv in coords {
                    let [u, v] = self.clamped(uv);
                    out.push(evaluate_basis(patch, param, u, v, derivatives)?);
                }
            }
            Form::Irregular(irregular) => {
                let locations = self.locations(coords)?;
                let stencils = stencils_at(
                    &irregular.table,
                    irregular.base,
                    &irregular.refined,
                    &locations,
                    &stencil_options(derivatives),
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
    /// patch points from the mesh's points (laid out as `points` says: a
    /// width, or a [`PointDescriptor`] for interleaved data), in Bfr's order
    /// — the control points, then for a split n-gon its centre and edge
    /// midpoints, for an irregular surface every vertex of its hull's
    /// refinement level by level and the points of its end caps;
    /// [`Surface::patch_point_count`] of them, packed (`size` values each).
    pub fn patch_points(
        &self,
        points: &[f64],
        layout: impl Into<PointDescriptor>,
    ) -> Result<Vec<f64>> {
        let layout = layout.into();
        self.check_points(points, layout)?;
        let width = layout.size;
        let mut out = self.control_values(points, layout)?;
        alloc::reserve(
            &mut out,
            self.patch_points.saturating_sub(self.control_points.len()) * width,
        )?;
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
                let native = native_patch_points(irregular, width, &out)?;
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

    /// `Evaluate` over patch points from [`Surface::patch_points`] (laid
    /// out as `patch_points` says): the surface's values and the
    /// derivatives asked for at `coords`, `size` values each.
    pub fn evaluate_patch_points(
        &self,
        patch_points: &[f64],
        layout: impl Into<PointDescriptor>,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        let layout = layout.into();
        layout.check()?;
        let expected = layout.span(self.patch_points);
        if patch_points.len() < expected
            || (layout.stride == layout.size && patch_points.len() != expected)
        {
            return Err(Error::BufferLength {
                buffer: crate::error::Buffer::Base,
                expected,
                got: patch_points.len(),
            });
        }
        if let Form::Irregular(irregular) = &self.form {
            let width = layout.size;
            let vertices = self.patch_points - irregular.local_order.len();
            let mut native = Vec::new();
            alloc::reserve(&mut native, self.patch_points.saturating_mul(width))?;
            for i in 0..vertices {
                native.extend_from_slice(layout.point(patch_points, i));
            }
            for &from in &irregular.local_order {
                native.extend_from_slice(layout.point(patch_points, from));
            }
            return self.evaluate_irregular(irregular, &native, width, coords, derivatives);
        }
        // The other forms' stencils weigh the control points, which lead
        // the patch points.
        let identity: Vec<u32> = (0..self.control_points.len() as u32).collect();
        match self.form {
            Form::Regular { patch, mask, .. } => {
                fresh_samples(layout.size, coords.len(), derivatives, |out| {
                    self.evaluate_regular(patch, mask, &identity, patch_points, layout, coords, out)
                })
            }
            _ => self.apply_stencils(&identity, patch_points, layout, coords, derivatives),
        }
    }

    /// The control points' values (`layout.size` each, packed) from the
    /// mesh's `points`, which [`Surface::check_points`] accepted.
    fn control_values(&self, points: &[f64], layout: PointDescriptor) -> Result<Vec<f64>> {
        let mut control = Vec::new();
        alloc::reserve(
            &mut control,
            self.control_points.len().saturating_mul(layout.size),
        )?;
        for &cv in self.control_points.iter() {
            control.extend_from_slice(layout.point(points, cv as usize));
        }
        Ok(control)
    }

    fn check_points(&self, points: &[f64], layout: PointDescriptor) -> Result<()> {
        layout.check()?;
        if let Some(&v) = self.control_points.iter().max()
            && layout.span(v as usize + 1) > points.len()
        {
            return Err(Error::BufferLength {
                buffer: crate::error::Buffer::Base,
                expected: layout.span(v as usize + 1),
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

    /// `Evaluate` over the mesh's points (laid out as `points` says: a
    /// width, or a [`PointDescriptor`] for interleaved data): the surface's
    /// values and the derivatives asked for at `coords`, `size` values
    /// each, its stencils applied to its control points.
    pub fn evaluate(
        &self,
        points: &[f64],
        layout: impl Into<PointDescriptor>,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        let layout = layout.into();
        self.check_points(points, layout)?;
        let fresh = |fill: &dyn Fn(&mut [&mut [f64]]) -> Result<()>| {
            fresh_samples(layout.size, coords.len(), derivatives, fill)
        };
        // The forms that compute their own samples return them as they are
        // (written into columns of their own they would be copied).
        match &self.form {
            Form::Irregular(irregular) => {
                match self.irregular(irregular, points, layout, coords, derivatives)? {
                    Irregularly::Plan(plan) => {
                        fresh(&|out| self.apply_plan(&plan, points, layout, out))
                    }
                    Irregularly::Samples(samples) => Ok(samples),
                }
            }
            Form::Regular { .. } | Form::Linear { regular: true } => {
                fresh(&|out| self.evaluate_into(points, layout, coords, derivatives, out))
            }
            _ => self.apply_stencils(&self.control_points, points, layout, coords, derivatives),
        }
    }

    /// An irregular surface at `coords`: the plan of its hull at these
    /// coordinates when there is one (`plans.rs`: other faces of the hull
    /// were evaluated there), else its values through the patch points (in
    /// the table's order; cheaper than a stencil per coordinate once there
    /// are more than a few).
    fn irregular(
        &self,
        irregular: &Irregular,
        points: &[f64],
        layout: PointDescriptor,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<Irregularly> {
        let plan = irregular.plans.get(coords, derivatives, || {
            let locations = self.locations(coords)?;
            stencils_at(
                &irregular.table,
                irregular.base,
                &irregular.refined,
                &locations,
                &stencil_options(derivatives),
            )
        })?;
        if let Some(plan) = plan {
            return Ok(Irregularly::Plan(plan));
        }
        let width = layout.size;
        let control = self.control_values(points, layout)?;
        let native = native_patch_points(irregular, width, &control)?;
        self.evaluate_irregular(irregular, &native, width, coords, derivatives)
            .map(Irregularly::Samples)
    }

    /// An irregular surface at `coords` through its own patch table, from
    /// its patch points in the table's order (`native`, `width` values each).
    fn evaluate_irregular(
        &self,
        irregular: &Irregular,
        native: &[f64],
        width: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        let locations = self.locations(coords)?;
        evaluate_data(
            &irregular.map,
            &irregular.table,
            PatchData::Vertex,
            native,
            width,
            &locations,
            derivatives,
        )
    }

    /// [`Surface::evaluate`] written into `out`: one slice per kind of
    /// value asked for (the value, then ∂u and ∂v, then ∂uu, ∂uv and ∂vv:
    /// `derivatives.columns()` of them), each `layout.size` values per
    /// coordinate, every value overwritten (whatever the slices held).
    pub(crate) fn evaluate_into(
        &self,
        points: &[f64],
        layout: PointDescriptor,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
        out: &mut [&mut [f64]],
    ) -> Result<()> {
        self.check_points(points, layout)?;
        let len = coords.len().saturating_mul(layout.size);
        if out.len() != derivatives.columns() || out.iter().any(|c| c.len() != len) {
            return Err(Error::BufferLength {
                buffer: crate::error::Buffer::Output,
                expected: len,
                got: out.first().map_or(0, |c| c.len()),
            });
        }
        match &self.form {
            Form::Irregular(irregular) => {
                match self.irregular(irregular, points, layout, coords, derivatives)? {
                    Irregularly::Plan(plan) => self.apply_plan(&plan, points, layout, out),
                    Irregularly::Samples(samples) => samples.values.copy_into(out),
                }
            }
            Form::Regular { patch, mask, plans } => {
                let (patch, mask) = (*patch, *mask);
                // The basis weights at these coordinates, once another
                // face of the kind was evaluated there (`plans.rs`).
                let plan = plans.get(coords, derivatives, || {
                    self.regular_plan(patch, mask, coords, derivatives)
                })?;
                match plan {
                    // A regular patch's plan: 16 (B-spline) or 12 (box
                    // spline) weights per coordinate, the control points in
                    // order (`regular_plan`).
                    Some(plan)
                        if matches!(
                            (patch, self.control_points.len()),
                            (PatchType::Regular, 16) | (PatchType::Loop, 12)
                        ) && plan.locations.len() == coords.len()
                            && plan.indices.len() == self.control_points.len() * coords.len() =>
                    {
                        if apply_regular(&plan, &self.control_points, points, layout, out) {
                            Ok(())
                        } else {
                            self.apply_plan(&plan, points, layout, out)
                        }
                    }
                    Some(plan) => self.apply_plan(&plan, points, layout, out),
                    None => self.evaluate_regular(
                        patch,
                        mask,
                        &self.control_points,
                        points,
                        layout,
                        coords,
                        out,
                    ),
                }
            }
            Form::Linear { regular: true } => {
                let patch = if self.control_points.len() == 4 {
                    PatchType::Quads
                } else {
                    PatchType::Triangles
                };
                self.evaluate_regular(patch, 0, &self.control_points, points, layout, coords, out)
            }
            _ => {
                let samples =
                    self.apply_stencils(&self.control_points, points, layout, coords, derivatives)?;
                samples.values.copy_into(out)
            }
        }
    }

    /// A single patch (`patch`, boundary `mask`) over the points at
    /// `indices`, evaluated coordinate by coordinate without a stencil per
    /// coordinate: a B-spline patch as a tensor product
    /// (`bspline_eval.rs`), any other through its basis weights.
    #[allow(clippy::too_many_arguments)]
    fn evaluate_regular(
        &self,
        patch: PatchType,
        mask: u16,
        indices: &[u32],
        points: &[f64],
        layout: PointDescriptor,
        coords: &[[f64; 2]],
        columns: &mut [&mut [f64]],
    ) -> Result<()> {
        if let Some(&uv) = coords.iter().find(|&&uv| !self.param.contains(uv, 1e-9)) {
            return Err(self.off_face(uv));
        }
        let width = layout.size;
        if patch == PatchType::Regular && indices.len() == 16 {
            let mut gathered = alloc::try_vec(0.0, 16 * width)?;
            for (dst, &cv) in gathered.chunks_exact_mut(width).zip(indices) {
                dst.copy_from_slice(layout.point(points, cv as usize));
            }
            bspline_eval::evaluate(
                &gathered,
                width,
                mask,
                coords,
                |uv| self.clamped(uv),
                columns,
            );
        } else if patch == PatchType::Quads && indices.len() == 4 {
            let p = |i: usize| layout.point(points, indices[i] as usize);
            let (p0, p1, p2, p3) = (p(0), p(1), p(2), p(3));
            for (i, &uv) in coords.iter().enumerate() {
                let [u, v] = self.clamped(uv);
                let (uc, vc) = (1.0 - u, 1.0 - v);
                // Weights of the corners for the value, ∂u, ∂v and ∂uv
                // (the second derivatives in one direction are 0).
                let weights = [
                    [uc * vc, u * vc, u * v, uc * v],
                    [-vc, vc, v, -v],
                    [-uc, -u, u, uc],
                    [0.0; 4],
                    [1.0, -1.0, 1.0, -1.0],
                    [0.0; 4],
                ];
                for (column, w) in columns.iter_mut().zip(&weights) {
                    let out = &mut column[i * width..(i + 1) * width];
                    for (k, o) in out.iter_mut().enumerate() {
                        *o = w[0] * p0[k] + w[1] * p1[k] + w[2] * p2[k] + w[3] * p3[k];
                    }
                }
            }
        } else {
            let derivatives = match columns.len() {
                1 => Derivatives::None,
                3 => Derivatives::First,
                _ => Derivatives::Second,
            };
            let param = PatchParam::new(0, 0, 0, 0, false, mask, 0, true);
            let mut buf: BasisBuffer = [[0.0; 20]; 6];
            for column in columns.iter_mut() {
                column.fill(0.0);
            }
            for (i, &uv) in coords.iter().enumerate() {
                let [u, v] = self.clamped(uv);
                let n = evaluate_basis_into(patch, param, u, v, derivatives, None, &mut buf)?;
                for (column, weights) in columns.iter_mut().zip(&buf) {
                    let out = &mut column[i * width..(i + 1) * width];
                    for (&cv, &w) in indices.iter().zip(&weights[..n]) {
                        for (o, &x) in out.iter_mut().zip(layout.point(points, cv as usize)) {
                            *o += w * x;
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// The evaluation plan of a regular patch at `coords`: at each, its
    /// basis weights (`EvaluatePatchBasis`) over its control points.
    fn regular_plan(
        &self,
        patch: PatchType,
        mask: u16,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<LocationStencils> {
        if let Some(&uv) = coords.iter().find(|&&uv| !self.param.contains(uv, 1e-9)) {
            return Err(self.off_face(uv));
        }
        let kinds = derivatives.columns();
        let param = PatchParam::new(0, 0, 0, 0, false, mask, 0, true);
        let n = patch.control_vertices();
        let mut plan = LocationStencils {
            control_vertices: n,
            ..LocationStencils::default()
        };
        let mut columns: [Vec<f64>; 6] = Default::default();
        let mut buf: BasisBuffer = [[0.0; 20]; 6];
        for (i, &uv) in coords.iter().enumerate() {
            let [u, v] = self.clamped(uv);
            let n = evaluate_basis_into(patch, param, u, v, derivatives, None, &mut buf)?;
            plan.locations.push(i);
            plan.offsets.push(plan.indices.len() as u32);
            plan.sizes.push(n as u32);
            plan.indices.extend(0..n as u32);
            for (column, weights) in columns.iter_mut().zip(&buf).take(kinds) {
                column.extend_from_slice(&weights[..n]);
            }
        }
        plan.weights = Partials::from_columns(columns);
        Ok(plan)
    }

    /// An evaluation plan (stencils over the control points at each
    /// coordinate, in order) applied to the mesh's `points`, into
    /// `columns` (one per kind of value, as many as the plan has).
    fn apply_plan(
        &self,
        plan: &LocationStencils,
        points: &[f64],
        layout: PointDescriptor,
        columns: &mut [&mut [f64]],
    ) -> Result<()> {
        match layout.size {
            1 => self.apply_plan_n::<1>(plan, points, layout, columns),
            2 => self.apply_plan_n::<2>(plan, points, layout, columns),
            3 => self.apply_plan_n::<3>(plan, points, layout, columns),
            _ => {
                let width = layout.size;
                let control = self.control_values(points, layout)?;
                for (column, weights) in columns.iter_mut().zip(plan.weights.kinds()) {
                    column.fill(0.0);
                    for (s, &at) in plan.locations.iter().enumerate() {
                        let terms =
                            plan.offsets[s] as usize..(plan.offsets[s] + plan.sizes[s]) as usize;
                        let dst = &mut column[at * width..(at + 1) * width];
                        for (&i, &wt) in plan.indices[terms.clone()].iter().zip(&weights[terms]) {
                            let p = &control[i as usize * width..(i as usize + 1) * width];
                            for (d, &x) in dst.iter_mut().zip(p) {
                                *d += wt * x;
                            }
                        }
                    }
                }
                Ok(())
            }
        }
    }

    /// [`Surface::apply_plan`] for points of `N` values, summed in
    /// registers, the control points gathered on the stack when they are
    /// few.
    fn apply_plan_n<const N: usize>(
        &self,
        plan: &LocationStencils,
        points: &[f64],
        layout: PointDescriptor,
        columns: &mut [&mut [f64]],
    ) -> Result<()> {
        const ON_STACK: usize = 32;
        let n = self.control_points.len();
        let gather = |dst: &mut [[f64; N]]| {
            for (d, &cv) in dst.iter_mut().zip(self.control_points.iter()) {
                d.copy_from_slice(layout.point(points, cv as usize));
            }
        };
        let mut stack = [[0.0; N]; ON_STACK];
        let heap;
        let control: &[[f64; N]] = if n <= ON_STACK {
            gather(&mut stack[..n]);
            &stack[..n]
        } else {
            let mut h = alloc::try_vec([0.0; N], n)?;
            gather(&mut h);
            heap = h;
            &heap
        };
        for (column, weights) in columns.iter_mut().zip(plan.weights.kinds()) {
            apply_terms::<N>(plan, weights, control, column);
        }
        Ok(())
    }

    /// The stencils at `coords` applied to `points`, the stencils' weights
    /// going to the points at `indices`.
    fn apply_stencils(
        &self,
        indices: &[u32],
        points: &[f64],
        layout: PointDescriptor,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        let width = layout.size;
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
                    for (o, &x) in col[start..]
                        .iter_mut()
                        .zip(layout.point(points, cv as usize))
                    {
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

/// [`apply_dense`] for the widths (1 to 3) and patches (16 or 12 points)
/// it is compiled for; `false` (nothing written) for any other.
#[inline]
pub(super) fn apply_regular(
    plan: &LocationStencils,
    control_points: &[u32],
    points: &[f64],
    layout: PointDescriptor,
    columns: &mut [&mut [f64]],
) -> bool {
    let (cvs, out) = (control_points, columns);
    match (layout.size, cvs.len()) {
        (1, 16) => apply_dense::<1, 16>(plan, cvs, points, layout, out),
        (2, 16) => apply_dense::<2, 16>(plan, cvs, points, layout, out),
        (3, 16) => apply_dense::<3, 16>(plan, cvs, points, layout, out),
        (1, 12) => apply_dense::<1, 12>(plan, cvs, points, layout, out),
        (2, 12) => apply_dense::<2, 12>(plan, cvs, points, layout, out),
        (3, 12) => apply_dense::<3, 12>(plan, cvs, points, layout, out),
        _ => return false,
    }
    true
}

/// A regular patch's plan (`P` weights per coordinate over the `P`
/// control points in order, coordinates in order: 16 for a B-spline
/// patch, 12 for a box spline) applied to points of `N` values
/// (`control_points` the patch's `P` indices into `points`):
/// [`apply_terms`] without the indices, the same sums in the same order.
fn apply_dense<const N: usize, const P: usize>(
    plan: &LocationStencils,
    control_points: &[u32],
    points: &[f64],
    layout: PointDescriptor,
    columns: &mut [&mut [f64]],
) {
    let mut control = [[0.0; N]; P];
    for (d, &cv) in control.iter_mut().zip(control_points) {
        d.copy_from_slice(layout.point(points, cv as usize));
    }
    for (column, weights) in columns.iter_mut().zip(plan.weights.kinds()) {
        for (w, out) in weights.chunks_exact(P).zip(column.chunks_exact_mut(N)) {
            let mut acc = [0.0; N];
            for (&wt, p) in w.iter().zip(&control) {
                for k in 0..N {
                    acc[k] += wt * p[k];
                }
            }
            out.copy_from_slice(&acc);
        }
    }
}

/// A plan's stencils with `weights` (one kind) applied to `control`
/// into `column`, summed in registers; a coordinate no stencil is for
/// gets zeros.
fn apply_terms<const N: usize>(
    plan: &LocationStencils,
    weights: &[f64],
    control: &[[f64; N]],
    column: &mut [f64],
) {
    if plan.locations.len() * N != column.len() {
        column.fill(0.0);
    }
    for (s, &at) in plan.locations.iter().enumerate() {
        let terms = plan.offsets[s] as usize..(plan.offsets[s] + plan.sizes[s]) as usize;
        let mut acc = [0.0; N];
        for (&i, &wt) in plan.indices[terms.clone()].iter().zip(&weights[terms]) {
            let p = &control[i as usize];
            for k in 0..N {
                acc[k] += wt * p[k];
            }
        }
        column[at * N..(at + 1) * N].copy_from_slice(&acc);
    }
}

/// How [`Surface::irregular`] evaluates: a plan to apply, or the values.
enum Irregularly {
    Plan(std::sync::Arc<LocationStencils>),
    Samples(SurfaceSamples),
}

/// Zeroed columns for `coords.len()` values of `width` and each kind
/// `derivatives` asks for, evaluated by `fill` into samples.
fn fresh_samples(
    width: usize,
    coords: usize,
    derivatives: Derivatives,
    fill: impl FnOnce(&mut [&mut [f64]]) -> Result<()>,
) -> Result<SurfaceSamples> {
    let len = coords.saturating_mul(width);
    let mut columns: [Vec<f64>; 6] = Default::default();
    for column in columns.iter_mut().take(derivatives.columns()) {
        *column = alloc::try_vec(0.0, len)?;
    }
    let mut out: Vec<&mut [f64]> = columns
        .iter_mut()
        .take(derivatives.columns())
        .map(|c| &mut c[..])
        .collect();
    fill(&mut out)?;
    Ok(SurfaceSamples {
        width,
        values: Partials::from_columns(columns),
    })
}

/// Limit stencils with the derivatives asked for.
fn stencil_options(derivatives: Derivatives) -> LimitStencilOptions {
    LimitStencilOptions::new()
        .first_derivatives(derivatives != Derivatives::None)
        .second_derivatives(derivatives == Derivatives::Second)
}

/// The points an irregular surface's patch table indexes — its hull's
/// vertices, every refined vertex level by level, then the table's local
/// points — from the hull's control points (`width` values each): the
/// stencils of all of them over the control points applied, as Bfr's patch
/// tree applies its stencil matrix.
fn native_patch_points(irregular: &Irregular, width: usize, control: &[f64]) -> Result<Vec<f64>> {
    let (refined, locals) = (&irregular.refined, &irregular.locals);
    let mut out = alloc::try_vec(0.0, (refined.len() + locals.len()).saturating_mul(width))?;
    let (head, tail) = out.split_at_mut(refined.len() * width);
    refined.apply_rows_into(0, width, control, head);
    locals.apply_rows_into(0, width, control, tail);
    Ok(out)
}

/// How a buffer of points is laid out (`Bfr::Surface::PointDescriptor`):
/// `size` values per point, the first values of consecutive points
/// `stride` apart — interleaved data (a position inside a larger vertex
/// record) without copying it out. A width converts into a packed
/// descriptor (stride = size).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PointDescriptor {
    /// Values per point (at least 1).
    pub size: usize,
    /// Values from one point to the next (at least `size`).
    pub stride: usize,
}

impl PointDescriptor {
    /// Packed points of `size` values.
    pub const fn new(size: usize) -> Self {
        PointDescriptor { size, stride: size }
    }

    /// Points of `size` values, `stride` apart.
    pub const fn with_stride(size: usize, stride: usize) -> Self {
        PointDescriptor { size, stride }
    }

    /// Refuses a size of 0 and a stride smaller than the size.
    fn check(self) -> Result<()> {
        if self.size == 0 {
            return Err(Error::ZeroWidth);
        }
        if self.stride < self.size {
            return Err(Error::Stride {
                size: self.size,
                stride: self.stride,
            });
        }
        Ok(())
    }

    /// The values `count` points span (the last one's stride not needed).
    fn span(self, count: usize) -> usize {
        match count {
            0 => 0,
            n => (n - 1)
                .saturating_mul(self.stride)
                .saturating_add(self.size),
        }
    }

    /// Point `i` of `points` (which [`PointDescriptor::span`] covers).
    fn point(self, points: &[f64], i: usize) -> &[f64] {
        &points[i * self.stride..][..self.size]
    }
}

impl From<usize> for PointDescriptor {
    fn from(size: usize) -> Self {
        PointDescriptor::new(size)
    }
}
