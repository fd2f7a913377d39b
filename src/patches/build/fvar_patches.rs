//! Non-linear face-varying patches: for every patch of the table, the patch
//! over one channel's own topology, as `PatchTableFactory` builds it when
//! `generateFVarLegacyLinearPatches` is off and the channel is not
//! interpolated linearly everywhere.
//!
//! Each patch is regular where the channel's values around its face are
//! (the corners' vertex tags combined with the channel's value tags, edges
//! the channel is split across taken as boundaries), with the channel's
//! values as control points; otherwise it is an end cap of the table's
//! end-cap type over the channel's values — the same source patch (the
//! corners' spans cut where the channel is) and converters as the vertex
//! end caps — whose points are the channel's own local points, with their
//! stencils over the channel's values (`GetLocalPointFaceVaryingStencilTable`).
//!
//! OpenSubdiv's details kept here:
//! * where the channel's topology matches the face's (no value of the face
//!   is mismatched) and both precisions agree, the vertex patch's findings
//!   are reused: its regularity, boundary mask, corner spans and parameter
//!   boundary bits (single-crease bits included);
//! * otherwise regularity is asked of the refiner's channel numbered as the
//!   channel's place in the table (`IsPatchRegular` is passed that index);
//! * the face-varying parameter boundary bits are one state shared by every
//!   channel and patch, kept where an irregular patch has no local points
//!   (legacy Gregory end caps: those patches' values stay 0).

use super::local::LocalPoints;
use super::matrix::Matrix;
use super::{Builder, Patch, box_spline, bspline, gregory, linear, loop_gregory};
use crate::patches::{EndCapType, FVarPatches, PatchOptions, PatchParam, PatchType};
use crate::real::Real;
use crate::topology::fvar::ChannelLevel;

/// What the non-linear channels of a table are built from: the patches in
/// OpenSubdiv's order with, for each, its vertex patch's regularity and
/// parameter and its index in the table.
pub(super) struct VertexPatches<'p> {
    pub patches: &'p [Patch],
    pub regular: &'p [bool],
    pub params: &'p [PatchParam],
    pub index: &'p [usize],
}

/// The types of a table's patches.
#[derive(Clone, Copy)]
pub(super) struct Types {
    pub regular: PatchType,
    pub irregular: PatchType,
}

impl Builder<'_> {
    /// The change-of-basis matrix of an end cap of type `ty` over `source`.
    pub(super) fn convert<R: Real>(
        ty: PatchType,
        source: &super::source::SourcePatch,
        matrix: &mut Matrix<R>,
        spare: &mut Matrix<R>,
    ) {
        match ty {
            PatchType::Quads | PatchType::Triangles => linear::convert_into(source, matrix),
            PatchType::Regular => bspline::convert_into(source, matrix, spare),
            PatchType::Loop => box_spline::convert_into(source, matrix, spare),
            PatchType::GregoryTriangle => {
                loop_gregory::GregoryTriangle::<R>::new(source).convert_into(matrix)
            }
            _ => gregory::Gregory::<R>::new(source).convert_into(matrix),
        }
    }

    /// The non-linear face-varying channels of a table (stencil weights in
    /// `fvarPatchPrecisionDouble`'s precision).
    pub(super) fn nonlinear_fvar(
        &self,
        options: &PatchOptions,
        vertex: &VertexPatches,
        types: Types,
    ) -> Vec<FVarPatches> {
        if options.fvar_patch_precision_double {
            self.nonlinear_fvar_in::<f64>(options, vertex, types)
        } else {
            self.nonlinear_fvar_in::<f32>(options, vertex, types)
        }
    }

    fn nonlinear_fvar_in<F: Real>(
        &self,
        options: &PatchOptions,
        vertex: &VertexPatches,
        types: Types,
    ) -> Vec<FVarPatches> {
        let legacy = options.end_cap_type == EndCapType::LegacyGregory;
        // Legacy Gregory end caps leave the irregular type unspecified: the
        // regular one.
        let irregular_type = if legacy {
            types.regular
        } else {
            types.irregular
        };
        let stride = types
            .regular
            .control_vertices()
            .max(irregular_type.control_vertices());
        let same_precision = options.patch_precision_double == options.fvar_patch_precision_double;
        let count = vertex.patches.len();
        let mut out: Vec<FVarPatches> = self
            .fvar
            .iter()
            .map(|ch| FVarPatches {
                channel: ch.channel,
                regular_type: types.regular,
                irregular_type,
                stride,
                values: vec![0; count * stride],
                params: vec![PatchParam::default(); count],
                local_point_stencils: Default::default(),
            })
            .collect();
        let mut local: Vec<LocalPoints<F>> = self
            .fvar
            .iter()
            .map(|ch| {
                LocalPoints::new(
                    ch.total_values(),
                    options.share_end_cap_points,
                    irregular_type == types.regular,
                    false,
                    self.levels.len(),
                )
            })
            .collect();
        let (mut matrix, mut spare) = (Matrix::<F>::default(), Matrix::<F>::default());
        // `fvarPatchInfo.paramBoundaryMask`: one for every channel.
        let mut param_boundary = 0u16;
        // One end cap's points, the storage reused.
        let mut cvs = Vec::new();
        for (k, p) in vertex.patches.iter().enumerate() {
            let vparam = vertex.params[k];
            let at = vertex.index[k];
            for ((ch, table), local) in self.fvar.iter().zip(&mut out).zip(&mut local) {
                let fv = ch.level(p.level);
                let matches = same_precision && !self.face_mismatched(p, fv);
                let (regular, view, boundary) = if matches {
                    (vertex.regular[k], None, vparam.boundary() as u16)
                } else {
                    let regular = self.is_regular(p.level, p.face, ch.regularity_level(p.level));
                    if regular {
                        param_boundary = self.boundary_mask(p.level, p.face, Some(fv));
                    } else if !legacy {
                        param_boundary = 0;
                    }
                    (regular, Some(fv), param_boundary)
                };
                let offset = ch.offsets[p.level];
                let values = &mut table.values[at * stride..(at + 1) * stride];
                if regular {
                    let mask = self.boundary_mask(p.level, p.face, view);
                    let cvs = self.regular_points(p.level, p.face, mask, Some(fv));
                    for (slot, &v) in values.iter_mut().zip(cvs.iter()) {
                        *slot = v.wrapping_add(offset);
                    }
                } else if !legacy {
                    let spans = self.corner_spans(p.level, p.face, view);
                    let source = self.source_patch(p.level, p.face, &spans);
                    Self::convert(irregular_type, &source, &mut matrix, &mut spare);
                    let sources = self.source_points(p.level, p.face, &spans, &source, Some(fv));
                    cvs.clear();
                    local.append(
                        self,
                        p.level,
                        p.face,
                        &matrix,
                        irregular_type,
                        &sources,
                        offset,
                        Some(fv),
                        &mut cvs,
                    );
                    for (slot, &v) in values.iter_mut().zip(&cvs) {
                        *slot = v;
                    }
                }
                table.params[at] = PatchParam::new(
                    vparam.face_id(),
                    vparam.u() as u16,
                    vparam.v() as u16,
                    vparam.depth() as u16,
                    vparam.non_quad_root(),
                    boundary,
                    vparam.transition() as u16,
                    regular,
                );
            }
        }
        for (table, local) in out.iter_mut().zip(local) {
            table.local_point_stencils = local.finish().0;
        }
        out
    }

    /// Whether a value of patch `p`'s face is mismatched in channel `fv`
    /// (`doesFaceFVarTopologyMatch` false).
    fn face_mismatched(&self, p: &Patch, fv: &ChannelLevel) -> bool {
        let l = &self.levels[p.level];
        (0..l.face_vertices.count(p.face))
            .any(|k| super::corners::value_tag(Some(fv), l, p.face, k).is_mismatch())
    }
}
