//! The inputs and outputs of the shim's evaluations at (ptex face, u, v)
//! locations (`sdv_patches_evaluate_points`, `sdv_cpu_patches_evaluate`):
//! points checked as whole points of a width, the locations split into the
//! three arrays the C ABI takes, and the zeroed output columns the shim
//! writes into.

use super::shim::to_i32;
use crate::alloc::try_vec;
use crate::error::{Buffer, Error, Result};
use crate::patches::{Derivatives, Partials, SurfaceSamples};
use crate::real::Real;

/// One evaluation call's arrays.
pub(super) struct AtLocations<R> {
    /// Values per point (and per evaluated value).
    pub(super) width: usize,
    /// `width` as the shim takes it.
    pub(super) width_i32: i32,
    /// Whole points given.
    pub(super) points: usize,
    /// Each location's ptex face (beyond `i32`: `i32::MAX`, which the shim
    /// refuses as a face that does not exist).
    pub(super) faces: Vec<i32>,
    /// Each location's u.
    pub(super) us: Vec<f64>,
    /// Each location's v.
    pub(super) vs: Vec<f64>,
    /// The values, then ∂u, ∂v, ∂uu, ∂uv, ∂vv: `width` values per
    /// location for those asked for (zeros, or what an earlier evaluation
    /// left: the shim overwrites them), empty for the others.
    columns: [Vec<R>; 6],
}

impl<R: Real> AtLocations<R> {
    /// The arrays for evaluating `locations` over `points_len` values of
    /// points of `width`, with `derivatives`. Refused: `width` 0 or beyond
    /// `i32`, values not a whole number of points, outputs too large.
    /// The output columns reuse `reuse`'s memory where it is large
    /// enough (an earlier evaluation's values, given back).
    pub(super) fn new(
        points_len: usize,
        width: usize,
        locations: &[(u32, f64, f64)],
        derivatives: Derivatives,
        mut reuse: Partials<R>,
    ) -> Result<Self> {
        if width == 0 {
            return Err(Error::ZeroWidth);
        }
        if !points_len.is_multiple_of(width) {
            return Err(Error::NotWholeElements {
                buffer: Buffer::Source,
                len: points_len,
                width,
            });
        }
        let width_i32 = to_i32(width, "width")?;
        let n = locations.len();
        let len = n.checked_mul(width).ok_or(Error::TooLarge {
            what: "evaluated values",
            count: usize::MAX,
            bits: usize::BITS,
        })?;
        let (mut faces, mut us, mut vs) = (try_vec(0i32, n)?, try_vec(0.0, n)?, try_vec(0.0, n)?);
        for (i, &(f, u, v)) in locations.iter().enumerate() {
            faces[i] = i32::try_from(f).unwrap_or(i32::MAX);
            us[i] = u;
            vs[i] = v;
        }
        reuse.reuse_for(derivatives.columns(), len)?;
        let columns = reuse.into_columns();
        Ok(AtLocations {
            width,
            width_i32,
            points: points_len / width,
            faces,
            us,
            vs,
            columns,
        })
    }

    /// The locations' count.
    pub(super) fn len(&self) -> usize {
        self.faces.len()
    }

    /// The output columns as the shim takes them: null for a column not
    /// asked for (or, with no locations, any column: the shim writes
    /// nothing then).
    pub(super) fn outputs(&mut self) -> [*mut R; 6] {
        self.columns.each_mut().map(|c| {
            if c.is_empty() {
                std::ptr::null_mut()
            } else {
                c.as_mut_ptr()
            }
        })
    }

    /// The values the shim wrote.
    pub(super) fn finish(self) -> SurfaceSamples<R> {
        SurfaceSamples {
            width: self.width,
            values: Partials::from_columns(self.columns),
        }
    }
}
