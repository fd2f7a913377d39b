//! Native limit evaluation and stencil tables against OpenSubdiv's
//! `PrimvarRefiner::Limit` and `StencilTableFactory`, over the corpus.
#![cfg(feature = "osd")]

use std::collections::BTreeMap;
use subdiv::compare::bbox_diagonal;
use subdiv::{
    BoundaryInterpolation, Error, Mesh, Options, OsdErrorKind, Scheme, StencilTable,
    UniformOptions, osd, refiner, shapes,
};

fn flat(mesh: &Mesh) -> Vec<f64> {
    mesh.positions.iter().flat_map(|p| p.to_array()).collect()
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

fn rows_equal(a: &StencilTable, b: &StencilTable, tol: f64) -> Result<(), String> {
    if a.len() != b.len() {
        return Err(format!("{} vs {} stencils", a.len(), b.len()));
    }
    for r in 0..a.len() {
        let map = |t: &StencilTable| {
            let mut m = BTreeMap::new();
            let (i, w) = t.row(r);
            for (&i, &w) in i.iter().zip(w) {
                *m.entry(i).or_insert(0.0) += w;
            }
            m.retain(|_, w: &mut f64| w.abs() > 1e-15);
            m
        };
        let (ma, mb) = (map(a), map(b));
        if ma.keys().ne(mb.keys())
            || ma
                .values()
                .zip(mb.values())
                .any(|(x, y)| (x - y).abs() > tol)
        {
            return Err(format!("stencil {r}: native {ma:?} vs osd {mb:?}"));
        }
    }
    Ok(())
}

fn check(name: &str, mesh: &Mesh, options: &Options, level: u32) -> Result<(), String> {
    let ctx = format!("{name} {options:?} level {level}");
    let mut o = osd::TopologyRefiner::new(mesh, options).map_err(|e| format!("{ctx}: {e}"))?;
    o.refine_uniform(UniformOptions::new(level).full_topology(true))
        .map_err(|e| e.to_string())?;
    let mut n = refiner::Refiner::new(mesh, options).map_err(|e| format!("{ctx}: {e}"))?;
    n.refine_uniform(UniformOptions::new(level).full_topology(true))
        .map_err(|e| e.to_string())?;
    let base = flat(mesh);
    let last = o.interpolate_all(3, &base).unwrap().pop().unwrap();
    let scale = bbox_diagonal(&mesh.positions).max(1e-300);
    let tol = 1e-12 * scale;

    // OpenSubdiv 3.5's PrimvarRefiner::Limit sizes each mask's face weights by
    // the level's computed maximum valence; where a non-manifold vertex has
    // more faces than that (a fin's edge point: 3 faces per side) it would
    // write past its masks, so the bridge refuses the level
    // (tests/osd_bridge.rs checks that it refuses exactly those). The native
    // engine computes the intended masks.
    let ln = n.limit(3, &last).unwrap();
    let lo = match o.limit(3, &last) {
        Ok(lo) => lo,
        Err(Error::Osd(e)) if e.kind == OsdErrorKind::Unsafe => {
            if o.limit_stencil_table().is_ok() {
                return Err(format!(
                    "{ctx}: limit stencils evaluated where Limit is refused"
                ));
            }
            return Ok(());
        }
        Err(e) => return Err(format!("{ctx}: OpenSubdiv's limit: {e}")),
    };
    for (what, a, b) in [
        ("position", &ln.positions, &lo.positions),
        ("du", &ln.du, &lo.du),
        ("dv", &ln.dv, &lo.dv),
    ] {
        let d = max_diff(a, b);
        if d > tol * 10.0 {
            return Err(format!("{ctx}: limit {what} differs by {d:e}"));
        }
    }
    let only = n.limit_positions(3, &last).unwrap();
    if max_diff(&only, &lo.positions) > tol {
        return Err(format!("{ctx}: limit positions alone differ"));
    }

    let (so, sn) = (o.stencil_table().unwrap(), n.stencil_table().unwrap());
    rows_equal(&sn, &so, 1e-12).map_err(|e| format!("{ctx}: stencils: {e}"))?;
    let applied = sn.apply(3, &base).unwrap();
    if max_diff(&applied, &last) > tol {
        return Err(format!(
            "{ctx}: applying the stencils differs from refining"
        ));
    }
    for r in 0..sn.len() {
        let s: f64 = sn.row(r).1.iter().sum();
        if (s - 1.0).abs() > 1e-12 {
            return Err(format!("{ctx}: stencil {r} sums to {s}"));
        }
    }
    let (lso, lsn) = (
        o.limit_stencil_table().unwrap(),
        n.limit_stencil_table().unwrap(),
    );
    for (what, a, b) in [
        ("position", &lsn.positions, &lso.positions),
        ("du", &lsn.du, &lso.du),
        ("dv", &lsn.dv, &lso.dv),
    ] {
        rows_equal(a, b, 1e-11).map_err(|e| format!("{ctx}: limit stencils {what}: {e}"))?;
    }
    let applied = lsn.positions.apply(3, &base).unwrap();
    if max_diff(&applied, &lo.positions) > tol * 10.0 {
        return Err(format!(
            "{ctx}: applying the limit stencils differs from the limit"
        ));
    }
    Ok(())
}

#[test]
fn limit_and_stencils_match_opensubdiv() {
    let mut failures = Vec::new();
    let mut checked = 0;
    for (name, mut mesh) in shapes::corpus() {
        mesh.fvar_channels.clear();
        for &scheme in mesh.applicable_schemes() {
            for boundary in [
                BoundaryInterpolation::EdgeOnly,
                BoundaryInterpolation::EdgeAndCorner,
                BoundaryInterpolation::None,
            ] {
                let options = Options::default()
                    .with_scheme(scheme)
                    .with_boundary(boundary);
                let deepest = if mesh.face_count() <= 24 { 4 } else { 3 };
                for level in 0..=deepest {
                    checked += 1;
                    if let Err(e) = check(&name, &mesh, &options, level) {
                        failures.push(e);
                    }
                }
            }
        }
    }
    if !failures.is_empty() {
        let n = failures.len();
        failures.truncate(6);
        panic!("{n} of {checked} cases differ:\n{}", failures.join("\n"));
    }
}

#[test]
fn limit_at_level_zero_and_validation() {
    let cube = shapes::cube();
    let r = refiner::Refiner::new(&cube, &Options::default()).unwrap();
    let lim = r.limit(3, &flat(&cube)).unwrap();
    // Valence-3 corner of a cube: the Catmull-Clark limit is inside the hull,
    // on the diagonal by symmetry.
    let p = &lim.positions[0..3];
    assert!(
        p[0] == p[1] && p[1] == p[2] && p[0] > -0.5 && p[0] < 0.0,
        "{p:?}"
    );
    assert!(r.limit(3, &[0.0; 5]).is_err());
    assert!(r.limit::<f64>(0, &[]).is_err());
}

/// Limit face-varying values (`PrimvarRefiner::LimitFaceVarying`) of every
/// corpus shape with UVs, in every face-varying mode.
#[test]
fn limit_face_varying_matches_opensubdiv() {
    use subdiv::FVarLinearInterpolation;
    let mut failures = Vec::new();
    let mut checked = 0;
    for (name, mesh) in shapes::corpus() {
        if mesh.fvar_channels.is_empty() {
            continue;
        }
        // Loop where splitting the quads leaves only triangles.
        let triangles = shapes::triangulate_with_uvs(&mesh);
        let schemes = [(mesh.clone(), Scheme::Catmark), (triangles, Scheme::Loop)];
        for (mesh, scheme) in schemes
            .into_iter()
            .filter(|(m, s)| *s == Scheme::Catmark || m.faces().all(|f| f.len() == 3))
        {
            for &fvar in FVarLinearInterpolation::ALL {
                for boundary in [
                    BoundaryInterpolation::EdgeOnly,
                    BoundaryInterpolation::EdgeAndCorner,
                ] {
                    let options = Options::default()
                        .with_scheme(scheme)
                        .with_fvar(fvar)
                        .with_boundary(boundary);
                    for level in 1..=3 {
                        checked += 1;
                        let uniform = UniformOptions::new(level);
                        let a = refiner::refine(
                            &mesh,
                            &options,
                            subdiv::Request::from(uniform).limit(true),
                        )
                        .unwrap();
                        let b = osd::refine(
                            &mesh,
                            &options,
                            subdiv::Request::from(uniform).limit(true),
                        )
                        .unwrap();
                        let (la, lb) = (a.limit.unwrap(), b.limit.unwrap());
                        if la.fvar_values != lb.fvar_values {
                            failures.push(format!("{name} {options:?} level {level}"));
                        }
                    }
                }
            }
        }
    }
    assert!(checked > 100);
    assert!(
        failures.is_empty(),
        "{} of {checked} differ: {:?}",
        failures.len(),
        &failures[..failures.len().min(5)]
    );
}

/// Factorized stencils reproduce interpolation exactly, in both precisions,
/// for every scheme and both child orders, at every width (three has its
/// own path).
#[test]
fn factorized_stencils_equal_interpolation() {
    for (name, mut mesh) in shapes::corpus() {
        mesh.fvar_channels.clear();
        for &scheme in mesh.applicable_schemes() {
            for faces_first in [false, true] {
                let options = Options::default()
                    .with_scheme(scheme)
                    .with_boundary(BoundaryInterpolation::EdgeOnly);
                let mut r = refiner::Refiner::new(&mesh, &options).unwrap();
                r.refine_uniform(UniformOptions::new(3).faces_first(faces_first))
                    .unwrap();
                let base = flat(&mesh);
                let fs = r.factorized_stencils::<f64>().unwrap();
                let mut out = vec![0.0; fs.len() * 3];
                fs.apply_into(3, &base, &mut out).unwrap();
                assert_eq!(
                    out,
                    r.interpolate_all(3, &base).unwrap().pop().unwrap(),
                    "{name} {scheme}"
                );
                let base32: Vec<f32> = base.iter().map(|&x| x as f32).collect();
                let fs = r.factorized_stencils::<f32>().unwrap();
                let mut out = vec![0.0f32; fs.len() * 3];
                fs.apply_into(3, &base32, &mut out).unwrap();
                assert_eq!(
                    out,
                    r.interpolate_all(3, &base32).unwrap().pop().unwrap(),
                    "{name} {scheme} f32"
                );
                assert!(fs.apply_into(3, &base32[1..], &mut out).is_err());
                // The other widths take the unpadded path.
                let fs = r.factorized_stencils::<f64>().unwrap();
                for width in [1, 2, 4, 5] {
                    let data: Vec<f64> = base
                        .chunks_exact(3)
                        .flat_map(|p| (0..width).map(move |k| p[k % 3] * (k + 1) as f64))
                        .collect();
                    let mut out = vec![0.0; fs.len() * width];
                    fs.apply_into(width, &data, &mut out).unwrap();
                    assert_eq!(
                        out,
                        r.interpolate_all(width, &data).unwrap().pop().unwrap(),
                        "{name} {scheme} width {width}"
                    );
                }
            }
        }
    }
}

/// Limits of a last level spanning several of the native engine's parallel
/// blocks (2,048 vertices each): equal to OpenSubdiv's bit for bit, on one
/// thread and on two, for a width with a specialised path (3) and one
/// without (5), and `limit_positions` equal to the positions of `limit`.
#[test]
fn limit_in_parallel_blocks_equals_opensubdiv() {
    for (mesh, scheme) in [
        (shapes::torus(24, 20), Scheme::Catmark),
        (shapes::torus_triangles(24, 20), Scheme::Loop),
    ] {
        let options = Options::default().with_scheme(scheme);
        let full = UniformOptions::new(2).full_topology(true);
        let mut n = refiner::Refiner::new(&mesh, &options).unwrap();
        n.refine_uniform(full).unwrap();
        let mut o = osd::TopologyRefiner::new(&mesh, &options).unwrap();
        o.refine_uniform(full).unwrap();
        let count = n.level_counts(2).unwrap().vertices;
        assert!(count > 3 * 2048, "{count} vertices: fewer than four blocks");
        for width in [3, 5] {
            // Per vertex: its position, then extra components derived from it.
            let base: Vec<f64> = mesh
                .positions
                .iter()
                .flat_map(|p| {
                    [p.x, p.y, p.z, p.x * p.y - 0.5, p.z + 2.0]
                        .into_iter()
                        .take(width)
                })
                .collect();
            let last = n.interpolate_all(width, &base).unwrap().pop().unwrap();
            let expected = o.limit(width, &last).unwrap();
            for threads in [1, 2] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                let (got, positions) = pool.install(|| {
                    (
                        n.limit(width, &last).unwrap(),
                        n.limit_positions(width, &last).unwrap(),
                    )
                });
                let ctx = format!("{scheme:?} width {width}, {threads} thread(s)");
                assert!(got.positions == expected.positions, "{ctx}: positions");
                assert!(got.du == expected.du, "{ctx}: du");
                assert!(got.dv == expected.dv, "{ctx}: dv");
                assert!(positions == got.positions, "{ctx}: limit_positions");
            }
        }
    }
}

/// `limit` and `limit_positions` equal OpenSubdiv's `Limit` bit for bit on
/// every corpus shape (every scheme and boundary mode, levels 0 to 2) and on
/// the benchmark's shapes shrunk, in `f32` and `f64`, for the widths with a
/// specialised path (1 to 4) and one without (5): smooth interior vertices
/// of every valence, boundaries, creases, corners, darts and non-manifold
/// vertices all take their own paths.
#[test]
fn limit_is_opensubdiv_bit_for_bit() {
    fn values<T: subdiv::Real>(mesh: &Mesh, width: usize) -> Vec<T> {
        mesh.positions
            .iter()
            .enumerate()
            .flat_map(|(i, p)| {
                [p.x, p.y, p.z, p.x * p.y - 0.5, p.z + i as f64 * 0.25]
                    .into_iter()
                    .take(width)
            })
            .map(T::from_f64)
            .collect()
    }
    fn same<T: subdiv::Real>(a: &[T], b: &[T]) -> bool {
        let bits = |x: &[T]| bytemuck::cast_slice::<T, u8>(x).to_vec();
        bits(a) == bits(b)
    }
    fn check<T: subdiv::Real>(
        ctx: &str,
        n: &refiner::Refiner,
        o: &osd::TopologyRefiner,
        mesh: &Mesh,
        width: usize,
    ) -> Result<bool, String> {
        let base = values::<T>(mesh, width);
        let last = n.interpolate_all(width, &base).unwrap().pop().unwrap();
        let expected = match o.limit(width, &last) {
            Ok(l) => l,
            // Levels OpenSubdiv's Limit would write past its masks on (see
            // `check` above).
            Err(Error::Osd(e)) if e.kind == OsdErrorKind::Unsafe => return Ok(false),
            Err(e) => return Err(format!("{ctx}: OpenSubdiv's limit: {e}")),
        };
        let got = n.limit(width, &last).unwrap();
        let positions = n.limit_positions(width, &last).unwrap();
        for (what, a, b) in [
            ("positions", &got.positions[..], &expected.positions[..]),
            ("du", &got.du[..], &expected.du[..]),
            ("dv", &got.dv[..], &expected.dv[..]),
            ("limit_positions", &positions[..], &expected.positions[..]),
        ] {
            if !same(a, b) {
                return Err(format!("{ctx}: {what} differ"));
            }
        }
        Ok(true)
    }
    let mut inputs: Vec<(String, Mesh, Options)> = Vec::new();
    for (name, mut mesh) in shapes::corpus() {
        mesh.fvar_channels.clear();
        for &scheme in mesh.applicable_schemes() {
            for boundary in [
                BoundaryInterpolation::EdgeOnly,
                BoundaryInterpolation::EdgeAndCorner,
                BoundaryInterpolation::None,
            ] {
                let options = Options::default()
                    .with_scheme(scheme)
                    .with_boundary(boundary);
                inputs.push((name.clone(), mesh.clone(), options));
            }
        }
    }
    for shape in shapes::bench_shapes(true) {
        if shape.mesh.face_count() <= 2000 {
            inputs.push((shape.name, shape.mesh, shape.options));
        }
    }
    let (mut failures, mut checked) = (Vec::new(), 0);
    for (name, mesh, options) in &inputs {
        for level in 0..=2 {
            let full = UniformOptions::new(level).full_topology(true);
            let (Ok(mut n), Ok(mut o)) = (
                refiner::Refiner::new(mesh, options),
                osd::TopologyRefiner::new(mesh, options),
            ) else {
                continue;
            };
            if n.refine_uniform(full).is_err() || o.refine_uniform(full).is_err() {
                continue;
            }
            for width in 1..=5 {
                let ctx = format!("{name} {options:?} level {level} width {width}");
                for result in [
                    check::<f32>(&format!("{ctx} f32"), &n, &o, mesh, width),
                    check::<f64>(&format!("{ctx} f64"), &n, &o, mesh, width),
                ] {
                    match result {
                        Ok(true) => checked += 1,
                        Ok(false) => {}
                        Err(e) => failures.push(e),
                    }
                }
            }
        }
    }
    assert!(checked > 1000, "{checked} cases checked");
    assert!(
        failures.is_empty(),
        "{} of {checked} differ:\n{}",
        failures.len(),
        failures[..failures.len().min(6)].join("\n")
    );
}
