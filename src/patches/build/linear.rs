//! The corners of a linear end cap — a bilinear quad (`LinearConverter` in
//! `far/catmarkPatchBuilder.cpp`) or a linear triangle (`convertToLinear`
//! in `far/loopPatchBuilder.cpp`): each corner's limit position (the
//! scheme's limit weights of its ring), or the corner itself where it is
//! sharp.

use super::matrix::Matrix;
use super::source::SourcePatch;
use super::{limits, loop_limits};
use crate::real::Real;

/// The change-of-basis matrix from `patch`'s points to its linear patch's
/// corners (four of a quad, three of a triangle, whose limits are Loop's),
/// into `m`.
pub(super) fn convert_into<R: Real>(patch: &SourcePatch, m: &mut Matrix<R>) {
    let tri = patch.size == 3;
    let mut sizes = [0usize; 4];
    let sizes = &mut sizes[..patch.size.min(4)];
    for (c, size) in sizes.iter_mut().enumerate() {
        let corner = &patch.corners[c];
        *size = if corner.sharp {
            1
        } else if corner.boundary {
            3
        } else {
            1 + patch.ring_size(c)
        };
    }
    m.reset(sizes, patch.points);
    let mut has_val2_interior = false;
    for (c, row) in m.rows.iter_mut().enumerate() {
        let corner = &patch.corners[c];
        if corner.sharp {
            row.set(0, c, R::ONE);
            // Loop's converter counts a sharp corner's valence 2 too.
            has_val2_interior |= tri && corner.val2_interior;
            continue;
        }
        let ring = patch.ring(c);
        let point = |i: usize| {
            if i == 0 {
                c
            } else {
                ring.get(i - 1).copied().unwrap_or(c)
            }
        };
        if corner.boundary {
            let valence = 1 + corner.faces;
            let [w, _, _] = if tri {
                loop_limits::boundary::<R>(valence, corner.patch_face, false)
            } else {
                limits::boundary::<R>(valence, corner.patch_face, false)
            };
            let n = ring.len();
            let at = |i: usize| w.get(i).copied().unwrap_or(R::ZERO);
            row.set(0, point(0), at(0));
            row.set(1, point(1), at(1));
            row.set(2, point(n), at(n));
        } else {
            let [w, _, _] = if tri {
                loop_limits::interior::<R>(corner.faces, corner.patch_face, false)
            } else {
                limits::interior::<R>(corner.faces, corner.patch_face, false)
            };
            for (i, &x) in w.iter().enumerate() {
                row.set(i, point(i), x);
            }
        }
        has_val2_interior |= corner.val2_interior;
    }
    if has_val2_interior {
        m.merge_repeated_corners();
    }
}
