//! Primvars on sparse levels — `Far::PrimvarRefiner::Interpolate` and
//! `InterpolateVarying` after `RefineAdaptive`: every child vertex that
//! exists gets the same mask as in uniform refinement (the parent level is
//! whole around it), accumulated in the same order, so results are
//! bit-identical to OpenSubdiv's.

use super::AdaptiveRefiner;
use super::kernel::{interpolate_sparse, walk_sparse};
use crate::error::{Buffer, Error, Result};
use crate::options::{Scheme, TriangleSubdivision};
use crate::real::Real;
use crate::refiner::fvar_interp::{FVarStep, fvar_call_levels, fvar_level};
use crate::refiner::{Kind, Source, Step, accumulate};
use crate::topology::refine::sparse::SparseSplit;
use glam::DVec3;

impl AdaptiveRefiner {
    /// Interpolates vertex data of `width` components from level `level - 1`
    /// to `level` (`PrimvarRefiner::Interpolate`).
    pub fn interpolate<T: Real>(&self, level: u32, width: usize, src: &[T]) -> Result<Vec<T>> {
        self.interpolate_kind(Kind::Vertex, level, width, src)
    }

    /// Interpolates varying data (linearly) from level `level - 1` to
    /// `level` (`PrimvarRefiner::InterpolateVarying`).
    pub fn interpolate_varying<T: Real>(
        &self,
        level: u32,
        width: usize,
        src: &[T],
    ) -> Result<Vec<T>> {
        self.interpolate_kind(Kind::Varying, level, width, src)
    }

    /// Interpolates the values of face-varying `channel` (`width`
    /// components each) from level `level - 1` to `level`
    /// (`PrimvarRefiner::InterpolateFaceVarying`): `src` holds the channel's
    /// values at `level - 1` (at level 0 the mesh's own), the result its
    /// values at `level`, numbered as [`AdaptiveRefiner::level`] reports the
    /// channel's face values.
    pub fn interpolate_face_varying<T: Real>(
        &self,
        channel: usize,
        level: u32,
        width: usize,
        src: &[T],
    ) -> Result<Vec<T>> {
        let (_, cf) = fvar_call_levels(
            &self.fvar,
            channel,
            level,
            self.max_level(),
            width,
            src.len(),
        )?;
        crate::alloc::guard(Some(level), || {
            let mut dst = crate::alloc::vec_or_unwind(T::ZERO, cf.value_count() * width);
            fvar_level(
                &self.fvar_step(channel, level as usize),
                width,
                src,
                &mut dst,
            );
            Ok(dst)
        })
    }

    /// The step of face-varying `channel` from level `level - 1` to `level`.
    pub(super) fn fvar_step(&self, channel: usize, level: usize) -> FVarStep<'_, SparseSplit> {
        FVarStep {
            rules: &self.rules,
            options: &self.options,
            parent: crate::topology::Around::stored(&self.levels[level - 1]),
            child: &self.levels[level],
            r: &self.steps[level - 1],
            pf: &self.fvar[channel][level - 1],
            cf: &self.fvar[channel][level],
            fast: None,
        }
    }

    /// Positions of every level, from the base positions, interpolated level
    /// by level in `f64`.
    pub fn refine_positions(&self, base: &[DVec3]) -> Result<Vec<Vec<DVec3>>> {
        let mut levels = vec![base.to_vec()];
        for level in 1..=self.max_level() {
            let flat: &[f64] = bytemuck::cast_slice(&levels[level as usize - 1]);
            let next = self.interpolate(level, 3, flat)?;
            levels.push(
                next.chunks_exact(3)
                    .map(|c| DVec3::new(c[0], c[1], c[2]))
                    .collect(),
            );
        }
        Ok(levels)
    }

    fn interpolate_kind<T: Real>(
        &self,
        kind: Kind,
        level: u32,
        width: usize,
        src: &[T],
    ) -> Result<Vec<T>> {
        crate::limits::check_interpolation_call(level, self.max_level(), width)?;
        let (parent, child) = (
            &self.levels[level as usize - 1],
            &self.levels[level as usize],
        );
        if src.len() != parent.vertex_count * width {
            return Err(Error::BufferLength {
                buffer: Buffer::Source,
                expected: parent.vertex_count * width,
                got: src.len(),
            });
        }
        crate::alloc::guard(Some(level), || {
            let mut dst = crate::alloc::vec_or_unwind(T::ZERO, child.vertex_count * width);
            if kind == Kind::Vertex {
                let step = Step {
                    rules: &self.rules,
                    creasing: self.options.creasing,
                    parent,
                    child,
                    children: &self.steps[level as usize - 1],
                };
                let tri_smooth = self.options.scheme == Scheme::Catmark
                    && self.options.triangles == TriangleSubdivision::Smooth;
                interpolate_sparse(&step, tri_smooth, width, src, &mut dst);
                return Ok(dst);
            }
            let mut acc = vec![T::ZERO; width];
            self.walk_level(kind, level as usize, |c, terms: &[(Source, T)]| {
                accumulate(terms, src, &mut dst, &mut acc, c);
            });
            Ok(dst)
        })
    }

    /// Calls `emit(child, terms)` for every child vertex of `level` (at
    /// least 1), as [`walk_sparse`] does for its step.
    pub(super) fn walk_level<T: Real>(
        &self,
        kind: Kind,
        level: usize,
        emit: impl FnMut(u32, &[(Source, T)]),
    ) {
        let step = Step {
            rules: &self.rules,
            creasing: self.options.creasing,
            parent: &self.levels[level - 1],
            child: &self.levels[level],
            children: &self.steps[level - 1],
        };
        walk_sparse(kind, &step, emit);
    }
}
