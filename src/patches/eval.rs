//! The limit surface at (ptex face, u, v) locations from a patch table, the
//! native way (OpenSubdiv's far tutorials 5_1 and 5_2): the data refined
//! through every level and the local points from their stencils
//! ([`AdaptiveRefiner::patch_points`]), then for each location the patch
//! that covers it ([`PatchMap`]), its basis ([`evaluate_basis`]) and the
//! weighted sum of its control points ([`evaluate`]).

use super::{Derivatives, Partials, PatchMap, PatchTable, SurfaceSamples, evaluate_basis};
use crate::error::{Buffer, Error, Result};
use crate::refiner::AdaptiveRefiner;

impl AdaptiveRefiner {
    /// The points `table`'s control vertices index, for data of `width`
    /// components given at the base vertices (`base`): every level's
    /// vertices, base first, interpolated level by level, then the local
    /// points from their stencils (`ComputeLocalPointValues`).
    ///
    /// Refused: `width` 0, `base` not one value per base vertex, a table
    /// whose local points name vertices this refinement does not have.
    pub fn patch_points(&self, table: &PatchTable, width: usize, base: &[f64]) -> Result<Vec<f64>> {
        if width == 0 {
            return Err(Error::ZeroWidth);
        }
        let expected = self.level_counts(0)?.vertices * width;
        if base.len() != expected {
            return Err(Error::BufferLength {
                buffer: Buffer::Base,
                expected,
                got: base.len(),
            });
        }
        let mut points = base.to_vec();
        let mut level = base.to_vec();
        for l in 1..=self.max_level() {
            level = self.interpolate(l, width, &level)?;
            points.extend_from_slice(&level);
        }
        if !table.local_point_stencils.is_empty() {
            let local = table.local_point_stencils.apply(width, &points)?;
            points.extend_from_slice(&local);
        }
        Ok(points)
    }
}

/// The limit surface of `table` at `locations` (ptex face, u, v), for
/// data of `width` components at the points its control vertices index
/// (`points`, as [`AdaptiveRefiner::patch_points`] or
/// `osd::OsdPatchTable`'s refined data give them), with the derivatives
/// asked for.
///
/// Refused: a location outside the mesh's ptex faces
/// ([`Error::NoSuchPtexFace`]) or its unit square ([`Error::Location`]),
/// on a hole ([`Error::NoPatchAt`]); a patch without a native basis
/// ([`Error::NotYetSupported`]); `points` too short for the table.
///
/// ```
/// use subdiv::{patches::{self, Derivatives, PatchOptions}, refiner::Refiner, shapes, Options};
/// let mesh = shapes::cube();
/// let options = PatchOptions::new().max_isolation(3);
/// let adaptive = Refiner::new(&mesh, &Options::default())?
///     .refine_adaptive(options.refine_adaptive_options(), &[])?;
/// let table = adaptive.patch_table(&options, &[])?;
/// let points = adaptive.patch_points(&table, 3, &mesh.flat_positions())?;
/// let s = patches::evaluate(&table, &points, 3, &[(0, 0.5, 0.5)], Derivatives::First)?;
/// // The centre of a cube's face: on the face's axis, inside the cube.
/// let p = &s.values.point;
/// assert!(p[0].abs() < 1e-6 && p[1].abs() < 1e-6 && p[2].abs() < 0.5);
/// # Ok::<(), subdiv::Error>(())
/// ```
pub fn evaluate(
    table: &PatchTable,
    points: &[f64],
    width: usize,
    locations: &[(u32, f64, f64)],
    derivatives: Derivatives,
) -> Result<SurfaceSamples> {
    if width == 0 {
        return Err(Error::ZeroWidth);
    }
    let map = PatchMap::new(table);
    let mut out = Partials::default();
    let first = derivatives != Derivatives::None;
    let second = derivatives == Derivatives::Second;
    for &(face, u, v) in locations {
        if face as usize >= table.ptex_faces {
            return Err(Error::NoSuchPtexFace {
                face: face as usize,
                count: table.ptex_faces,
            });
        }
        for (coordinate, value) in [("u", u), ("v", v)] {
            if !(0.0..=1.0).contains(&value) {
                return Err(Error::Location {
                    face,
                    coordinate,
                    value,
                });
            }
        }
        let handle = map
            .find_patch(face, u, v)
            .ok_or(Error::NoPatchAt { face, u, v })?;
        let array = &table.arrays[handle.array];
        let w = evaluate_basis(
            array.patch_type,
            array.params[handle.patch],
            u,
            v,
            derivatives,
        )?;
        let cvs = array.patch_vertices(handle.patch);
        let sum = |weights: &[f64], into: &mut Vec<f64>| -> Result<()> {
            let start = into.len();
            into.resize(start + width, 0.0);
            for (&cv, &wt) in cvs.iter().zip(weights) {
                let at = cv as usize * width;
                let row = points.get(at..at + width).ok_or(Error::BufferLength {
                    buffer: Buffer::Source,
                    expected: at + width,
                    got: points.len(),
                })?;
                for (o, &x) in into[start..].iter_mut().zip(row) {
                    *o += wt * x;
                }
            }
            Ok(())
        };
        sum(&w.point, &mut out.point)?;
        if first {
            sum(&w.du, &mut out.du)?;
            sum(&w.dv, &mut out.dv)?;
        }
        if second {
            sum(&w.duu, &mut out.duu)?;
            sum(&w.duv, &mut out.duv)?;
            sum(&w.dvv, &mut out.dvv)?;
        }
    }
    Ok(SurfaceSamples { width, values: out })
}
