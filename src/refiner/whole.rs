//! Whole refinements in one call: [`refine`] (every level, every primvar,
//! limits) and [`refine_last`] (the smallest footprint for the last level).

use super::{Kind, Refiner};
use crate::alloc::collect_n;
use crate::error::{Buffer, Error, Result};
use crate::limits::{check_level, check_precision};
use crate::mesh::Mesh;
use crate::options::Request;
use crate::options::Scheme;
use crate::options::{Options, UniformOptions};
use crate::output::{LevelCounts, Limit, Refinement, Values};
use crate::real::Precision;
use crate::real::Real;
use crate::topology::{Build, Level, Table, fvar, refine_level};
use glam::{DVec3, Vec3};
use std::borrow::Cow;

/// Refines `mesh` to `uniform.level` and interpolates `base` (vertex data of
/// `width` components per base vertex) along the way, releasing each level's
/// topology and data as soon as the next level's data exists: the smallest
/// memory footprint for "just the last level's values". Returns the element
/// counts of every level and the last level's values as [`Values`] (equal to
/// [`Refiner::interpolate_last`] after [`Refiner::refine_uniform`]).
/// Face-varying channels of `mesh` are not refined.
///
/// ```
/// use subdiv::{refiner, shapes, Options, UniformOptions};
/// let torus = shapes::torus(8, 6);
/// let base: Vec<f32> = torus.positions.iter().flat_map(|p| p.as_vec3().to_array()).collect();
/// let (counts, last) = refiner::refine_last(&torus, &Options::default(), UniformOptions::new(3), 3, &base)?;
/// assert_eq!(counts.len(), 4);
/// assert_eq!(last.len(), 3 * counts[3].vertices);
/// # Ok::<(), subdiv::Error>(())
/// ```
pub fn refine_last<T: Real>(
    mesh: &Mesh,
    options: &Options,
    uniform: UniformOptions,
    width: usize,
    base: &[T],
) -> Result<(Vec<LevelCounts>, Values<T>)> {
    let (counts, values, _) = refine_last_with(mesh, options, uniform, width, base, false)?;
    Ok((counts, values))
}

/// Every level's counts, the last level's vertex values and each channel's
/// last-level values.
pub(crate) type LastLevel<T> = (Vec<LevelCounts>, Values<T>, Vec<Table<T>>);

/// [`refine_last`], and with `channels` also every face-varying channel of
/// `mesh` refined and interpolated level by level (in `T`, each level's
/// channel topology released with the level): the channels' last-level
/// values, in channel order.
pub(crate) fn refine_last_with<T: Real>(
    mesh: &Mesh,
    options: &Options,
    uniform: UniformOptions,
    width: usize,
    base: &[T],
    channels: bool,
) -> Result<LastLevel<T>> {
    crate::alloc::guard(Some(uniform.level), || {
        let first = First::new(mesh, options, uniform, channels)?;
        if width == 0 {
            return Err(Error::ZeroWidth);
        }
        if base.len() != first.r.levels[0].vertex_count * width {
            return Err(Error::BufferLength {
                buffer: Buffer::Base,
                expected: first.r.levels[0].vertex_count * width,
                got: base.len(),
            });
        }
        first.refine(uniform, width, Cow::Borrowed(base))
    })
}

/// [`refine_last_with`] on the mesh's own positions with every channel,
/// consuming the mesh: its faces, tags and channel indices are dropped
/// once the base level is built, and its positions once level 1 has been
/// interpolated from them, so none of it is left at the peak of a
/// refinement to level 2 or deeper (and only the positions at level 1).
pub(crate) fn refine_last_owned<T: Real>(
    mesh: Mesh,
    options: &Options,
    uniform: UniformOptions,
) -> Result<LastLevel<T>> {
    crate::alloc::guard(Some(uniform.level), || {
        let first = First::new(&mesh, options, uniform, true)?;
        let base = mesh.into_flat_positions::<T>();
        first.refine(uniform, 3, Cow::Owned(base))
    })
}

/// A whole refinement's start: the base level, and each channel's base
/// values and width when the channels are refined.
struct First<T> {
    r: Refiner,
    channels: Vec<(Vec<T>, usize)>,
}

impl<T: Real> First<T> {
    fn new(
        mesh: &Mesh,
        options: &Options,
        uniform: UniformOptions,
        channels: bool,
    ) -> Result<Self> {
        check_level(mesh, options, uniform.level)?;
        let mut r = Refiner::new(mesh, options)?;
        let channels = if channels {
            mesh.fvar_channels
                .iter()
                .map(|c| (c.values_as(), c.width))
                .collect()
        } else {
            r.fvar.clear();
            Vec::new()
        };
        Ok(First { r, channels })
    }

    /// Refines to `uniform.level`, interpolating `base` (`width` values per
    /// vertex) and the channels level by level, each level released once
    /// nothing reads it.
    fn refine(
        self,
        uniform: UniformOptions,
        width: usize,
        mut base: Cow<'_, [T]>,
    ) -> Result<LastLevel<T>> {
        let First { mut r, channels } = self;
        let (values, widths): (Vec<Vec<T>>, Vec<usize>) = channels.into_iter().unzip();
        let mut fvar_values: Vec<Table<T>> = values.into_iter().map(Table::from).collect();
        let mut counts = vec![r.level_counts(0)?];
        // Level 1 reads `base` where it is: no copy of it.
        let mut data: Option<Table<T>> = None;
        for level in 1..=uniform.level as usize {
            // The grandparent is read while this level is interpolated only
            // when the parent derives its relations from it: otherwise it
            // goes before the child is built, lowering the peak by a level.
            if level >= 2 && !r.levels[level - 1].derived_relations {
                release(&mut r, level - 2);
            }
            let (refinement, child) = refine_level(
                &r.levels[level - 1],
                &r.options,
                uniform.order_vertices_from_faces_first,
                Build::for_level(
                    level,
                    uniform.level as usize,
                    !uniform.full_topology_in_last_level,
                    !r.fvar.is_empty(),
                    &r.levels[level - 1],
                ),
            );
            let around =
                super::queries::around(&r.levels, &r.refinements, level - 1, r.options.scheme);
            // Only the last level's values are returned: its channels'
            // corners are not built.
            let last = level == uniform.level as usize;
            for channel in &mut r.fvar {
                let parent = channel.last().expect("the parent level's channel");
                let next = if last {
                    fvar::refine_values_only(around, &child, &refinement, parent, &r.options)
                } else {
                    fvar::refine(around, &child, &refinement, None, parent, &r.options)
                };
                channel.push(next);
            }
            r.refinements.push(refinement);
            r.levels.push(child);
            r.check_unpaired_smooth_step(level - 1)?;
            counts.push(r.level_counts(level as u32)?);
            // The last split is done: what only splitting read goes before
            // the channels' values take their room, the rest after them.
            let parent = &mut r.levels[level - 1];
            let split_only = last && r.options.scheme != Scheme::Loop && !parent.derived_relations;
            if split_only {
                parent.release_face_edges();
            }
            // The channels first, while the parent's vertex values are still
            // the smaller ones: then the parent's channel topology and values
            // go before this level's vertex values take their room.
            for (c, values) in fvar_values.iter_mut().enumerate() {
                let w = widths[c];
                // A pooled table: memory the pool keeps serves it, or is
                // handed back before it is faulted in.
                let mut next = Table::for_overwrite(r.fvar[c][level].value_count() * w);
                r.interpolate_face_varying_into(c, level as u32, w, values, &mut next)?;
                std::mem::replace(values, next).free();
                // The next level's channel is split from this level's; the
                // last level's is not read again either.
                r.fvar[c][level - 1] = Default::default();
                if last {
                    r.fvar[c][level] = Default::default();
                }
            }
            // The channels interpolated: what only they read goes before
            // the last level's values take their room.
            if split_only {
                r.levels[level - 1].release_split_tables();
            }
            // Built as OpenSubdiv builds them and counted, the last
            // level's faces go before its values take their room.
            if last {
                r.levels[level].release_faces();
            }
            let mut next = Table::for_overwrite(r.levels[level].vertex_count * width);
            let src = data.as_deref().unwrap_or(&base);
            r.interpolate_level(Kind::Vertex, level, width, src, &mut next);
            // The parent's values are not read again, and no later table of
            // this refinement is small enough to reuse their memory: it goes
            // back to the system at once (the pool would keep it resident
            // under the allocations that follow). Owned base values likewise.
            if let Some(parent_values) = data.replace(next) {
                parent_values.free();
            }
            base = Cow::Borrowed(&[]);
            // Nothing reads the grandparent any more (when the parent derives
            // its vertex relations from it, they were read from it while
            // interpolating this level): only this local refiner held it.
            if level >= 2 {
                release(&mut r, level - 2);
            }
        }
        let last = data.unwrap_or_else(|| Table::from_slice(&base));
        Ok((counts, Values(last), fvar_values))
    }
}

/// Drops level `l`'s topology and its channels' (their slots stay, empty).
fn release(r: &mut Refiner, l: usize) {
    r.levels[l] = Level::default();
    for channel in &mut r.fvar {
        channel[l] = Default::default();
    }
}

/// Refines a mesh uniformly with the native engine as `request` says (a
/// [`UniformOptions`] is a request in `f64` without limits): the topology,
/// positions and face-varying values of every level, and limit values at
/// the last level when asked. [`crate::Engine::refine`] does the same with
/// either engine.
///
/// ```
/// use subdiv::{refiner, shapes, Options, Precision, Request, UniformOptions};
/// let cube = shapes::cube();
/// let r = refiner::refine(&cube, &Options::default(), UniformOptions::new(2))?;
/// assert_eq!(r.positions[2].len(), 98);
/// let with_limit = refiner::refine(&cube, &Options::default(), Request::new(1).limit(true))?;
/// assert_eq!(with_limit.limit.unwrap().positions.len(), 26);
/// # Ok::<(), subdiv::Error>(())
/// ```
pub fn refine(mesh: &Mesh, options: &Options, request: impl Into<Request>) -> Result<Refinement> {
    crate::alloc::guard(None, || {
        let request = request.into();
        let (precision, limit) = (request.precision, request.limit);
        // Limit evaluation needs the last level's full topology, as in OpenSubdiv.
        let uniform = request.effective_uniform();
        check_level(mesh, options, uniform.level)?;
        let mut refiner = Refiner::new(mesh, options)?;
        // After the validation in `Refiner::new`: the mesh's own errors first.
        check_precision(mesh, precision)?;
        refiner.refine_uniform(uniform)?;
        let levels = (0..=uniform.level)
            .map(|l| refiner.level(l))
            .collect::<Result<Vec<_>>>()?;
        let positions = match precision {
            Precision::F64 => refiner.refine_positions(&mesh.positions)?,
            Precision::F32 => {
                let base: Vec<Vec3> = mesh.positions.iter().map(|p| p.as_vec3()).collect();
                refiner
                    .refine_positions_f32(&base)?
                    .into_iter()
                    .map(|l| collect_n(l.len(), l.iter().map(|p| p.as_dvec3())))
                    .collect()
            }
        };
        let fvar_widths: Vec<usize> = mesh.fvar_channels.iter().map(|c| c.width).collect();
        let fvar_values = match precision {
            Precision::F64 => refine_fvar::<f64>(&refiner, mesh)?,
            Precision::F32 => refine_fvar::<f32>(&refiner, mesh)?,
        };
        let limit = if limit {
            let last_points = positions.last().expect("level 0");
            let last: Vec<f64> = collect_n(
                3 * last_points.len(),
                last_points.iter().flat_map(|p| p.to_array()),
            );
            let data = match precision {
                Precision::F64 => refiner.limit(3, &last)?,
                Precision::F32 => {
                    let narrow: Vec<f32> = collect_n(last.len(), last.iter().map(|&x| x as f32));
                    let d = refiner.limit(3, &narrow)?;
                    let widen = |v: crate::output::Values<f32>| {
                        let wide: Vec<f64> = collect_n(v.len(), v.iter().map(|&x| f64::from(x)));
                        crate::output::Values::from(wide)
                    };
                    crate::output::LimitData {
                        positions: widen(d.positions),
                        du: widen(d.du),
                        dv: widen(d.dv),
                    }
                }
            };
            let points = |v: &[f64]| {
                collect_n(
                    v.len() / 3,
                    v.chunks_exact(3).map(|c| DVec3::new(c[0], c[1], c[2])),
                )
            };
            Some(Limit {
                positions: points(&data.positions),
                du: points(&data.du),
                dv: points(&data.dv),
                fvar_values: limit_fvar(
                    &refiner,
                    mesh,
                    precision,
                    fvar_values.last().expect("level 0"),
                )?,
            })
        } else {
            None
        };
        Ok(Refinement {
            options: *options,
            uniform,
            precision,
            levels,
            positions,
            fvar_widths,
            fvar_values,
            limit,
        })
    })
}

/// Limit values of every face-varying channel, from the last level's values.
fn limit_fvar(
    refiner: &Refiner,
    mesh: &Mesh,
    precision: Precision,
    last: &[Vec<f64>],
) -> Result<Vec<Vec<f64>>> {
    mesh.fvar_channels
        .iter()
        .enumerate()
        .map(|(c, ch)| match precision {
            Precision::F64 => refiner.limit_face_varying(c, ch.width, &last[c]),
            Precision::F32 => {
                let narrow: Vec<f32> = collect_n(last[c].len(), last[c].iter().map(|&x| x as f32));
                let limit = refiner.limit_face_varying(c, ch.width, &narrow)?;
                Ok(collect_n(limit.len(), limit.into_iter().map(f64::from)))
            }
        })
        .collect()
}

/// Face-varying values of every level and channel (`[level][channel]`), in `T`.
fn refine_fvar<T: Real>(refiner: &Refiner, mesh: &Mesh) -> Result<Vec<Vec<Vec<f64>>>> {
    let mut current: Vec<Vec<T>> = mesh.fvar_channels.iter().map(|c| c.values_as()).collect();
    let widen = |data: &[Vec<T>]| {
        data.iter()
            .map(|c| collect_n(c.len(), c.iter().map(|v| v.to_f64())))
            .collect()
    };
    let mut out = vec![widen(&current)];
    for level in 1..=refiner.max_level() {
        current = mesh
            .fvar_channels
            .iter()
            .enumerate()
            .map(|(c, ch)| refiner.interpolate_face_varying(c, level, ch.width, &current[c]))
            .collect::<Result<Vec<_>>>()?;
        out.push(widen(&current));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    /// With its channels, `refine_last_with` (levels and channel levels
    /// released as it goes) gives the counts, positions and face-varying
    /// values of a refiner that keeps every level, bit for bit.
    #[test]
    fn last_level_channels_equal_a_full_refinement() {
        let mut checked = 0;
        for (name, mesh) in shapes::corpus() {
            if mesh.fvar_channels.is_empty() {
                continue;
            }
            for fvar in [
                crate::FVarLinearInterpolation::None,
                crate::FVarLinearInterpolation::CornersPlus1,
                crate::FVarLinearInterpolation::All,
            ] {
                let options = Options::default().with_fvar(fvar);
                let uniform = UniformOptions::new(3);
                let base = mesh.flat_positions::<f64>();
                let (counts, last, channels) =
                    refine_last_with(&mesh, &options, uniform, 3, &base, true).unwrap();
                let mut r = Refiner::new(&mesh, &options).unwrap();
                r.refine_uniform(uniform).unwrap();
                for (l, c) in counts.iter().enumerate() {
                    assert_eq!(*c, r.level_counts(l as u32).unwrap(), "{name} level {l}");
                }
                assert_eq!(last.0, r.interpolate_last(3, &base).unwrap().0, "{name}");
                assert_eq!(channels.len(), mesh.fvar_channels.len());
                for (c, (values, channel)) in channels.iter().zip(&mesh.fvar_channels).enumerate() {
                    let mut expected = channel.values.clone();
                    for level in 1..=3 {
                        expected = r
                            .interpolate_face_varying(c, level, channel.width, &expected)
                            .unwrap();
                    }
                    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                    assert_eq!(bits(values), bits(&expected), "{name} {fvar:?} channel {c}");
                }
                checked += 1;
            }
        }
        assert!(checked >= 9, "{checked}");
    }
}
