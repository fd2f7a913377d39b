//! Migration guide (docs/MIGRATING.md), row 8: `Far::LimitStencilTableFactory`
//! → `Refiner::limit_stencil_table`.
//!
//! OpenSubdiv's factory evaluates the limit surface at arbitrary (ptex face,
//! s, t) locations through patch tables; so does
//! `AdaptiveRefiner::location_stencils`. This example shows both that and
//! the stencils at the vertices of the last uniformly refined level
//! (`Refiner::limit_stencil_table`): every location whose parameters are
//! multiples of 1/2^n on a quad face is a vertex of level n, found by
//! walking the child faces. It checks the vertex stencils against
//! `Refiner::limit`, the walk against the bilinear scheme, the limit on a
//! regular face against the bicubic B-spline patch evaluated from its
//! definition, and the location stencils against the same B-spline and
//! (with `osd`) OpenSubdiv's.
//!
//! Run with `cargo run --example migrate_limit_stencils`.

use glam::DVec3;
use subdiv::patches::LimitStencilOptions;
use subdiv::refiner::Refiner;
use subdiv::{AdaptiveOptions, Error, Mesh, Options, Scheme, UniformOptions, shapes};

// [locate]
/// The vertex of level `level` at parameter `(u, v)` of quad face `face` of
/// level 0 (corner 0 at (0, 0), corner 1 at (1, 0), corner 3 at (0, 1)), for
/// `u` and `v` multiples of 1/2^level, on a Catmull-Clark or bilinear refiner.
///
/// Child face `k` of face `f` is face `face_offsets[f] + k` of the next level;
/// it covers the quarter at corner `k` and keeps corner `k` in position `k`.
fn vertex_at(refiner: &Refiner, level: u32, face: usize, u: f64, v: f64) -> Result<u32, Error> {
    let (mut f, mut u, mut v) = (face, u, v);
    for l in 0..level {
        let parent = refiner.level(l)?;
        assert_eq!(parent.face(f).len(), 4, "a quad face");
        let (right, top) = (u > 0.5, v > 0.5);
        let k = match (right, top) {
            (false, false) => 0,
            (true, false) => 1,
            (true, true) => 2,
            (false, true) => 3,
        };
        f = parent.face_offsets[f] as usize + k;
        u = 2.0 * u - f64::from(u8::from(right));
        v = 2.0 * v - f64::from(u8::from(top));
    }
    let corner = match (u, v) {
        (0.0, 0.0) => 0,
        (1.0, 0.0) => 1,
        (1.0, 1.0) => 2,
        (0.0, 1.0) => 3,
        _ => panic!("({u}, {v}) is not a multiple of 1/2^{level}"),
    };
    Ok(refiner.level(level)?.face(f)[corner])
}
// [end]

/// The uniform cubic B-spline basis functions at `t` in [0, 1].
fn basis(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [
        s * s * s / 6.0,
        (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0,
        (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0,
        t * t * t / 6.0,
    ]
}

/// Their derivatives.
fn basis_derivative(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [
        -s * s / 2.0,
        1.5 * t * t - 2.0 * t,
        (-3.0 * t * t + 2.0 * t + 1.0) / 2.0,
        t * t / 2.0,
    ]
}

fn flat(points: &[DVec3]) -> Vec<f64> {
    points.iter().flat_map(|p| p.to_array()).collect()
}

fn point(data: &[f64], v: u32) -> DVec3 {
    DVec3::from_slice(&data[v as usize * 3..v as usize * 3 + 3])
}

fn main() -> Result<(), Error> {
    // An 8 × 8 grid, bumped so the surface is not flat.
    let (nx, ny) = (8u32, 8u32);
    let mut mesh: Mesh = shapes::grid(nx, ny);
    mesh.fvar_channels.clear();
    for p in &mut mesh.positions {
        p.z = (0.7 * p.x).sin() * (0.5 * p.y).cos() + 0.05 * p.x * p.y;
    }
    let base = flat(&mesh.positions);
    let options = Options::shape_file_defaults();
    let level = 2;

    // [limit-stencils]
    let mut refiner = Refiner::new(&mesh, &options)?;
    refiner.refine_uniform(UniformOptions::new(level).full_topology(true))?;
    let stencils = refiner.limit_stencil_table()?; // one row per vertex of the last level
    let limit = stencils.positions.apply(3, &base)?; // LimitStencilTable::UpdateValues
    let du = stencils.du.apply(3, &base)?; // LimitStencilTable::UpdateDerivs
    let dv = stencils.dv.apply(3, &base)?;
    // [end]

    // The stencils reproduce Refiner::limit applied to the refined positions.
    let last = refiner
        .interpolate_all(3, &base)?
        .pop()
        .expect("last level");
    let direct = refiner.limit(3, &last)?;
    let diff = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
    };
    let d = diff(&limit, &direct.positions)
        .max(diff(&du, &direct.du))
        .max(diff(&dv, &direct.dv));
    assert!(d < 1e-12, "{d}");
    println!(
        "{} limit stencils (position, du, dv) == Refiner::limit to {d:.1e}",
        stencils.positions.len()
    );

    // The walk finds the right vertex: with the bilinear scheme (same child
    // numbering) the vertex at (u, v) is the bilinear point of the face.
    let mut bilinear = Refiner::new(&mesh, &options.with_scheme(Scheme::Bilinear))?;
    bilinear.refine_uniform(UniformOptions::new(level).full_topology(true))?;
    let flat_points = bilinear
        .interpolate_all(3, &base)?
        .pop()
        .expect("last level");

    // A regular face, two rings away from the boundary: its limit surface is
    // the bicubic B-spline patch of its 4 × 4 neighbourhood.
    let (i, j) = (3u32, 4u32);
    let face = (j * nx + i) as usize;
    let at = |a: u32, b: u32| mesh.positions[(b * (nx + 1) + a) as usize];
    let corners = mesh
        .face(face)
        .iter()
        .map(|&c| mesh.positions[c as usize])
        .collect::<Vec<_>>();
    let steps = 1 << level;
    let (mut worst, mut worst_normal) = (0.0f64, 0.0f64);
    for a in 0..=steps {
        for b in 0..=steps {
            let (u, v) = (a as f64 / steps as f64, b as f64 / steps as f64);
            // [location-use]
            let vertex = vertex_at(&refiner, level, face, u, v)?;
            let p = point(&limit, vertex); // the limit at (face, u, v)
            let normal = point(&du, vertex).cross(point(&dv, vertex)).normalize();
            // [end]
            let bilinear_point = corners[0] * (1.0 - u) * (1.0 - v)
                + corners[1] * u * (1.0 - v)
                + corners[2] * u * v
                + corners[3] * (1.0 - u) * v;
            assert!((point(&flat_points, vertex) - bilinear_point).length() < 1e-12);
            let (bu, bv) = (basis(u), basis(v));
            let (du_basis, dv_basis) = (basis_derivative(u), basis_derivative(v));
            let (mut spline, mut spline_du, mut spline_dv) =
                (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
            for r in 0..4 {
                for c in 0..4 {
                    let control = at(i + c as u32 - 1, j + r as u32 - 1);
                    spline += control * (bu[c] * bv[r]);
                    spline_du += control * (du_basis[c] * bv[r]);
                    spline_dv += control * (bu[c] * dv_basis[r]);
                }
            }
            worst = worst.max((p - spline).length());
            // The tangents are PrimvarRefiner::Limit's (scaled, along the
            // vertex's own edges), not d/du and d/dv; their normal is the
            // surface normal.
            let spline_normal = spline_du.cross(spline_dv).normalize();
            worst_normal = worst_normal.max((normal - spline_normal).length());
        }
    }
    assert!(worst < 1e-12, "{worst}");
    assert!(worst_normal < 1e-12, "{worst_normal}");
    println!(
        "face {face} at the {} locations (k/{steps}, l/{steps}): limit == bicubic B-spline to {worst:.1e}, \
         normals to {worst_normal:.1e}",
        (steps + 1) * (steps + 1)
    );

    // Stencils at arbitrary locations, as LimitStencilTableFactory builds
    // them: adaptive refinement, a patch table, the stencil of each
    // (ptex face, u, v) over the base vertices (an all-quad mesh: the ptex
    // face is the face). On the regular face they are the bicubic B-spline,
    // derivatives included (true d/du and d/dv here).
    let locations: Vec<(u32, f64, f64)> = (0..=4)
        .flat_map(|a| (0..=4).map(move |b| (face as u32, a as f64 / 4.0, b as f64 / 7.0)))
        .collect();
    // [location-stencils]
    let adaptive = Refiner::new(&mesh, &options)?.refine_adaptive(AdaptiveOptions::new(3), &[])?;
    let at_locations = adaptive.location_stencils(&locations, &LimitStencilOptions::new())?;
    let values = at_locations.apply(3, &base)?; // UpdateValues, UpdateDerivs
    // values.point, values.du, values.dv: 3 per location
    // [end]
    let mut worst_at = 0.0f64;
    for (k, &(_, u, v)) in locations.iter().enumerate() {
        let (bu, bv) = (basis(u), basis(v));
        let (du_basis, dv_basis) = (basis_derivative(u), basis_derivative(v));
        let (mut spline, mut spline_du, mut spline_dv) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
        for r in 0..4 {
            for c in 0..4 {
                let control = at(i + c as u32 - 1, j + r as u32 - 1);
                spline += control * (bu[c] * bv[r]);
                spline_du += control * (du_basis[c] * bv[r]);
                spline_dv += control * (bu[c] * dv_basis[r]);
            }
        }
        let k = k as u32;
        worst_at = worst_at
            .max((point(&values.point, k) - spline).length())
            .max((point(&values.du, k) - spline_du).length())
            .max((point(&values.dv, k) - spline_dv).length());
    }
    assert!(worst_at < 1e-12, "{worst_at}");
    println!(
        "{} location stencils on face {face}: limit and d/du, d/dv == bicubic B-spline to {worst_at:.1e}",
        at_locations.len()
    );

    #[cfg(feature = "osd")]
    {
        // OpenSubdiv's stencils at the same locations: same terms.
        let mut osd = subdiv::osd::TopologyRefiner::new(&mesh, &options)?;
        osd.refine_adaptive(AdaptiveOptions::new(3), &[])?;
        let theirs = osd.location_stencils(&locations, &LimitStencilOptions::new())?;
        assert_eq!(
            (&theirs.sizes, &theirs.indices),
            (&at_locations.sizes, &at_locations.indices)
        );
        let d = diff(&theirs.weights.point, &at_locations.weights.point)
            .max(diff(&theirs.weights.du, &at_locations.weights.du));
        assert!(d < 1e-12, "{d}");
        println!("OpenSubdiv's location stencils: same terms, weights to {d:.1e}");
    }

    #[cfg(feature = "osd")]
    {
        // OpenSubdiv's limit masks (PrimvarRefiner::Limit on stencils) agree.
        let mut osd = subdiv::osd::TopologyRefiner::new(&mesh, &options)?;
        osd.refine_uniform(UniformOptions::new(level).full_topology(true))?;
        let theirs = osd.limit_stencil_table()?;
        let d = diff(&theirs.positions.apply(3, &base)?, &limit)
            .max(diff(&theirs.du.apply(3, &base)?, &du))
            .max(diff(&theirs.dv.apply(3, &base)?, &dv));
        assert!(d < 1e-12, "{d}");
        println!("OpenSubdiv's limit stencils at the same vertices: same values to {d:.1e}");
    }
    #[cfg(not(feature = "osd"))]
    println!("(built without the `osd` feature: the OpenSubdiv comparison is skipped)");
    Ok(())
}
