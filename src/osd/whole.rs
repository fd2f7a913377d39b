//! A whole refinement through OpenSubdiv in one call: [`refine`].

use super::TopologyRefiner;
use crate::alloc::collect_n;
use crate::error::Result;
use crate::limits::{check_level, check_precision};
use crate::mesh::Mesh;
use crate::options::Options;
use crate::options::Request;
use crate::output::{Limit, Refinement};
use crate::real::{Precision, Real};
use glam::DVec3;

fn flatten<T: Real>(points: &[DVec3]) -> Vec<T> {
    let flat = points
        .iter()
        .flat_map(|p| [T::from_f64(p.x), T::from_f64(p.y), T::from_f64(p.z)]);
    collect_n(3 * points.len(), flat)
}

fn unflatten<T: Real>(data: &[T]) -> Vec<DVec3> {
    let points = data
        .chunks_exact(3)
        .map(|c| DVec3::new(c[0].to_f64(), c[1].to_f64(), c[2].to_f64()));
    collect_n(data.len() / 3, points)
}

fn widen<T: Real>(data: &[T]) -> Vec<f64> {
    collect_n(data.len(), data.iter().map(|v| v.to_f64()))
}

fn narrow<T: Real>(data: &[f64]) -> Vec<T> {
    collect_n(data.len(), data.iter().map(|&v| T::from_f64(v)))
}

/// Refines a mesh uniformly with OpenSubdiv as `request` says (a
/// [`UniformOptions`](crate::UniformOptions) is a request in `f64` without limits): the topology,
/// positions and face-varying values of every level, and with
/// `request.limit` the limit positions, tangents and face-varying values at
/// the last level (which then keeps its full topology). The same as
/// [`crate::refiner::refine`], through OpenSubdiv.
pub fn refine(mesh: &Mesh, options: &Options, request: impl Into<Request>) -> Result<Refinement> {
    crate::alloc::guard(None, || {
        let request = request.into();
        match request.precision {
            Precision::F32 => refine_typed::<f32>(mesh, options, &request),
            Precision::F64 => refine_typed::<f64>(mesh, options, &request),
        }
    })
}

fn refine_typed<T: Real>(mesh: &Mesh, options: &Options, request: &Request) -> Result<Refinement> {
    let (uniform, limit) = (request.effective_uniform(), request.limit);
    check_level(mesh, options, uniform.level)?;
    let mut refiner = TopologyRefiner::new(mesh, options)?;
    // After the validation in `TopologyRefiner::new`: the mesh's own errors first.
    check_precision(mesh, request.precision)?;
    refiner.refine_uniform(uniform)?;
    let levels = (0..=uniform.level)
        .map(|l| refiner.level(l))
        .collect::<Result<Vec<_>>>()?;
    let raw_positions = refiner.interpolate_all(3, &flatten::<T>(&mesh.positions))?;
    let fvar_widths: Vec<usize> = mesh.fvar_channels.iter().map(|c| c.width).collect();
    let mut raw_fvar: Vec<Vec<Vec<T>>> = vec![
        mesh.fvar_channels
            .iter()
            .map(|c| narrow::<T>(&c.values))
            .collect(),
    ];
    for level in 1..=uniform.level {
        let prev = raw_fvar.last().expect("non-empty");
        let next = fvar_widths
            .iter()
            .enumerate()
            .map(|(c, &w)| refiner.interpolate_face_varying(c, level, w, &prev[c]))
            .collect::<Result<Vec<_>>>()?;
        raw_fvar.push(next);
    }
    let limit = if limit {
        let last = raw_positions.last().expect("non-empty");
        let data = refiner.limit(3, last)?;
        let last_fvar = raw_fvar.last().expect("non-empty");
        let fvar_values = fvar_widths
            .iter()
            .enumerate()
            .map(|(c, &w)| {
                refiner
                    .limit_face_varying(c, w, &last_fvar[c])
                    .map(|v| widen(&v))
            })
            .collect::<Result<Vec<_>>>()?;
        Some(Limit {
            positions: unflatten(&data.positions),
            du: unflatten(&data.du),
            dv: unflatten(&data.dv),
            fvar_values,
        })
    } else {
        None
    };
    Ok(Refinement {
        options: *options,
        uniform,
        precision: T::PRECISION,
        levels,
        positions: raw_positions.iter().map(|p| unflatten(p)).collect(),
        fvar_widths,
        fvar_values: raw_fvar
            .iter()
            .map(|lv| lv.iter().map(|c| widen(c)).collect())
            .collect(),
        limit,
    })
}
