//! Native per-face Bfr surfaces (`subdiv::bfr::SurfaceFactory`) against
//! OpenSubdiv's `Bfr::RefinerSurfaceFactory` through the bridge: for every
//! face of every corpus shape under several options, and of random grids
//! and polygon soups, vertex, varying and face-varying surfaces with the
//! same validity, regularity, linearity, control points (index by index)
//! and patch-point count, patch points (`PreparePatchPoints`) and limit
//! stencils within 1e-12 of OpenSubdiv's.
#![cfg(feature = "osd")]

mod support;

use proptest::prelude::*;
use subdiv::bfr::{PointDescriptor, Surface, SurfaceFactory, SurfaceOptions};
use subdiv::osd::bfr_surface::{SurfaceInfo, Surfaces};
use subdiv::patches::{Derivatives, EndCapType, Partials, PatchOptions, PatchType};
use subdiv::{BoundaryInterpolation, Mesh, Options, Scheme, shapes};

fn columns(p: &Partials) -> [&[f64]; 6] {
    [&p.point, &p.du, &p.dv, &p.duu, &p.duv, &p.dvv]
}

/// The tolerance of stencil column `column` whose weights are `weights`:
/// 1e-12 of the largest weight (at least 1), times 2^(order × (depth − 3))
/// past depth 3 — derivatives of patches deep in a refinement scale
/// rounding by 2^depth per order (measured: 5.8e-11 relative for a second
/// derivative at depth 10; 2.7e-12, 3.6e-12 and, on a Loop face-varying
/// surface with an infinitely sharp corner under Chaikin creasing,
/// 5.6e-12 at depth 5).
fn tolerance(weights: &[f64], column: usize, approx: SurfaceOptions) -> f64 {
    let scale = weights.iter().fold(1.0f64, |m, w| m.max(w.abs()));
    let order = [0, 1, 1, 2, 2, 2][column];
    let depth = approx.approx_level_sharp.saturating_sub(3) as i32;
    1e-12 * scale * 2f64.powi(order * depth)
}

/// Both engines' surface factories, or `None` where both refuse the mesh.
fn factories(
    name: &str,
    mesh: &Mesh,
    opts: &Options,
    approx: SurfaceOptions,
) -> Option<(Surfaces, SurfaceFactory)> {
    match (
        Surfaces::new(mesh, opts, &approx),
        SurfaceFactory::new(mesh, opts, &approx),
    ) {
        (Ok(o), Ok(n)) => Some((o, n)),
        (Err(_), Err(_)) => None,
        (o, n) => panic!("{name}: osd {:?} vs native {:?}", o.err(), n.err()),
    }
}

/// The native surface `s` is described as OpenSubdiv's `info`: validity,
/// regularity, linearity, control points and patch-point count. Returns
/// whether it is valid.
fn same_description(what: &str, s: &Surface, info: &SurfaceInfo) -> bool {
    assert_eq!(s.is_valid(), info.valid, "{what}: valid");
    if !info.valid {
        return false;
    }
    assert_eq!(s.is_regular(), info.regular, "{what}: regular");
    assert_eq!(s.is_linear(), info.linear, "{what}: linear");
    assert_eq!(
        s.control_points(),
        &info.control_points[..],
        "{what}: control points"
    );
    assert_eq!(
        s.patch_point_count(),
        info.patch_points,
        "{what}: patch points"
    );
    true
}

/// Stencils at `coords`, native and OpenSubdiv's, agree within
/// [`tolerance`].
fn same_stencils(
    what: &str,
    coords: &[[f64; 2]],
    ours: &[Partials],
    theirs: &[Partials],
    approx: SurfaceOptions,
) {
    assert_eq!(ours.len(), theirs.len(), "{what}");
    for (k, (a, b)) in ours.iter().zip(theirs).enumerate() {
        for (c, (x, y)) in columns(a).iter().zip(columns(b)).enumerate() {
            assert_eq!(x.len(), y.len(), "{what} coord {k} column {c}");
            let tol = tolerance(y, c, approx);
            for (i, (p, q)) in x.iter().zip(y.iter()).enumerate() {
                assert!(
                    (p - q).abs() <= tol,
                    "{what} at {:?} column {c} weight {i}: {p} vs {q}",
                    coords[k]
                );
            }
        }
    }
}

/// Compares the faces of `mesh` under `opts`; returns how many faces were
/// compared.
fn compare(name: &str, mesh: &Mesh, opts: &Options, approx: SurfaceOptions) -> usize {
    let Some((osd, native)) = factories(name, mesh, opts, approx) else {
        return 0;
    };
    let mut compared = 0;
    for face in 0..mesh.face_count() {
        let what = format!("{name} {opts:?} {approx:?} face {face}");
        let info = match osd.face_info(face) {
            Ok(i) => i,
            // Refused by the bridge (OpenSubdiv 3.5.0 faults).
            Err(_) => continue,
        };
        let s = native
            .vertex_surface(face)
            .unwrap_or_else(|e| panic!("{what}: {e}"));
        if !same_description(&what, &s, &info) {
            continue;
        }
        let coords = support::bfr_sample_coords(&s.parameterization());
        patch_points_match_evaluation(&what, mesh, &osd, face, &s, &coords);
        let varying = native.varying_surface(face).unwrap();
        assert!(varying.is_linear(), "{what}");
        let points = mesh.flat_positions::<f64>();
        let ours = varying
            .evaluate(&points, 3, &coords, Derivatives::None)
            .unwrap();
        let theirs = osd.evaluate_varying(face, &coords).unwrap();
        let scale = points.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        for (p, q) in ours.values.point.iter().zip(&theirs.values.point) {
            assert!((p - q).abs() <= 1e-12 * scale, "{what} varying: {p} vs {q}");
        }
        let ours = s.evaluate_stencil(&coords, Derivatives::Second).unwrap();
        if !info.regular && info.patch_points == info.control_points.len() {
            // OpenSubdiv's fault (see CONFORMANCE.md): the stencils of one
            // regular patch at the hull's base level come in the patch's
            // order, not the control points'. Compare with its evaluation.
            single_patch_matches_evaluation(&what, mesh, &osd, face, &s, &coords);
            compared += 1;
            continue;
        }
        let theirs = osd
            .evaluate_stencil(face, &coords, Derivatives::Second)
            .unwrap();
        same_stencils(&what, &coords, &ours, &theirs, approx);
        compared += 1;
    }
    compared
}

/// The surface's patch points: as many as counted, the control points
/// first, OpenSubdiv's `PreparePatchPoints` within 1e-12, and evaluating
/// them gives what evaluating the mesh's points does and OpenSubdiv's
/// values — folded faces (every corner of valence 2) included.
fn patch_points_match_evaluation(
    what: &str,
    mesh: &Mesh,
    osd: &Surfaces,
    face: usize,
    s: &Surface,
    coords: &[[f64; 2]],
) {
    let points = mesh.flat_positions::<f64>();
    let patch = s.patch_points(&points, 3).unwrap();
    assert_eq!(patch.len(), 3 * s.patch_point_count(), "{what}");
    let scale = points.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    let theirs = osd.patch_points(face).unwrap();
    assert_eq!(patch.len(), theirs.len(), "{what}");
    for (i, (p, q)) in patch.iter().zip(&theirs).enumerate() {
        assert!(
            (p - q).abs() <= 1e-12 * scale,
            "{what}: patch point {} component {}: {p} vs {q}",
            i / 3,
            i % 3
        );
    }
    for (k, &cv) in s.control_points().iter().enumerate() {
        assert_eq!(
            &patch[3 * k..3 * k + 3],
            &points[3 * cv as usize..3 * cv as usize + 3]
        );
    }
    let a = s
        .evaluate_patch_points(&patch, 3, coords, Derivatives::Second)
        .unwrap();
    let b = s.evaluate(&points, 3, coords, Derivatives::Second).unwrap();
    interleaved_data_evaluates_alike(what, s, &points, &patch, coords, &b);
    let theirs = osd.evaluate(face, coords, Derivatives::Second).unwrap();
    for (c, ((x, y), z)) in columns(&a.values)
        .iter()
        .zip(columns(&b.values))
        .zip(columns(&theirs.values))
        .enumerate()
    {
        let tol = 1e-9 * scale * 4f64.powi([0, 1, 1, 2, 2, 2][c]);
        for ((p, q), r) in x.iter().zip(y).zip(z) {
            assert!((p - q).abs() <= tol, "{what} column {c}: {p} vs {q}");
            assert!(
                (p - r).abs() <= tol,
                "{what} column {c} vs OpenSubdiv: {p} vs {r}"
            );
        }
    }
}

/// The mesh's points and the patch points interleaved with other data (a
/// point descriptor with a stride, `Bfr::Surface::PointDescriptor`): the
/// same patch points (bit for bit) and values as packed ones give; a stride
/// below the size and a buffer too short for the last control point
/// refused.
fn interleaved_data_evaluates_alike(
    what: &str,
    s: &Surface,
    points: &[f64],
    patch: &[f64],
    coords: &[[f64; 2]],
    packed: &subdiv::patches::SurfaceSamples,
) {
    // Records of 5 values, the point at 1..4: [id, x, y, z, weight].
    let interleave = |points: &[f64], stride: usize| -> Vec<f64> {
        points
            .chunks_exact(3)
            .enumerate()
            .flat_map(|(i, p)| {
                let mut r = vec![-(i as f64); stride];
                r[1..4].copy_from_slice(p);
                r
            })
            .collect()
    };
    let records = interleave(points, 5);
    let layout = PointDescriptor::with_stride(3, 5);
    let ours = s
        .evaluate(&records[1..], layout, coords, Derivatives::Second)
        .unwrap();
    // Not bit for bit: a face evaluated again at the same coordinates may
    // go through an evaluation plan (src/bfr/plans.rs) the first time did
    // not.
    let scale = points.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    for (c, (x, y)) in columns(&ours.values)
        .iter()
        .zip(columns(&packed.values))
        .enumerate()
    {
        assert_eq!(x.len(), y.len(), "{what}: interleaved points, column {c}");
        // (As the evaluation paths are compared below: second derivatives
        // at approximation level 10 differ by ~2e-11 relative.)
        let tol = 1e-9 * scale * 4f64.powi([0, 1, 1, 2, 2, 2][c]);
        for (p, q) in x.iter().zip(y) {
            assert!(
                (p - q).abs() <= tol,
                "{what}: interleaved points, column {c}: {p} vs {q}"
            );
        }
    }
    assert_eq!(
        s.patch_points(&records[1..], layout).unwrap(),
        patch,
        "{what}"
    );
    let patch_records = interleave(patch, 6);
    let ours = s
        .evaluate_patch_points(
            &patch_records[1..patch_records.len() - 2],
            PointDescriptor::with_stride(3, 6),
            coords,
            Derivatives::Second,
        )
        .unwrap();
    let from_patch = s
        .evaluate_patch_points(patch, 3, coords, Derivatives::Second)
        .unwrap();
    assert_eq!(ours, from_patch, "{what}: interleaved patch points");
    let overlapping = PointDescriptor::with_stride(3, 2);
    assert!(matches!(
        s.evaluate(points, overlapping, coords, Derivatives::None),
        Err(subdiv::Error::Stride { size: 3, stride: 2 })
    ));
    if let Some(&last) = s.control_points().iter().max() {
        let short = &records[1..5 * last as usize + 3];
        assert!(matches!(
            s.evaluate(short, layout, coords, Derivatives::None),
            Err(subdiv::Error::BufferLength { .. })
        ));
    }
}

/// The native stencils of `face` applied to the mesh's positions against
/// OpenSubdiv's evaluation there.
fn single_patch_matches_evaluation(
    what: &str,
    mesh: &Mesh,
    osd: &Surfaces,
    face: usize,
    s: &Surface,
    coords: &[[f64; 2]],
) {
    let points = mesh.flat_positions::<f64>();
    let ours = s.evaluate(&points, 3, coords, Derivatives::Second).unwrap();
    let theirs = osd.evaluate(face, coords, Derivatives::Second).unwrap();
    let scale = points.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    for (c, (x, y)) in columns(&ours.values)
        .iter()
        .zip(columns(&theirs.values))
        .enumerate()
    {
        assert_eq!(x.len(), y.len(), "{what} column {c}");
        for (p, q) in x.iter().zip(y) {
            assert!(
                (p - q).abs() <= 1e-12 * scale,
                "{what} column {c}: {p} vs {q}"
            );
        }
    }
    // OpenSubdiv's stencils are a permutation of the native ones.
    let theirs = osd
        .evaluate_stencil(face, coords, Derivatives::None)
        .unwrap();
    let ours = s.evaluate_stencil(coords, Derivatives::None).unwrap();
    for (a, b) in ours.iter().zip(&theirs) {
        let mut a = a.point.clone();
        let mut b = b.point.clone();
        a.sort_by(f64::total_cmp);
        b.sort_by(f64::total_cmp);
        for (p, q) in a.iter().zip(&b) {
            assert!((p - q).abs() <= 1e-12, "{what}: not a permutation");
        }
    }
}

#[test]
fn corpus_faces_match_opensubdiv() {
    let edge_only = Options::default().with_boundary(BoundaryInterpolation::EdgeOnly);
    let mut compared = 0;
    for (name, mesh) in shapes::corpus() {
        let mut modes = vec![
            Options::default(),
            edge_only,
            edge_only.with_scheme(Scheme::Bilinear),
        ];
        if mesh.faces().all(|f| f.len() == 3) {
            modes.push(edge_only.with_scheme(Scheme::Loop));
        }
        for opts in modes {
            compared += compare(&name, &mesh, &opts, SurfaceOptions::default());
        }
    }
    eprintln!("{compared} faces compared");
    assert!(compared > 2000, "{compared}");
}

/// Every boundary interpolation, Chaikin creasing, smooth triangles and
/// approximation levels from 0 to 10 (smooth above sharp included).
#[test]
fn options_and_approximation_levels_match_opensubdiv() {
    let levels = [(0, 0), (1, 3), (2, 6), (3, 1), (0, 4), (10, 10)];
    let option_sets = [
        Options::default().with_boundary(BoundaryInterpolation::None),
        Options::default().with_boundary(BoundaryInterpolation::EdgeAndCorner),
        Options::default().with_creasing(subdiv::CreasingMethod::Chaikin),
        Options::default().with_triangles(subdiv::TriangleSubdivision::Smooth),
    ];
    let mut compared = 0;
    for (name, mesh) in shapes::corpus() {
        if mesh.face_count() > 200 {
            continue;
        }
        let loop_too = mesh.faces().all(|f| f.len() == 3);
        for (i, (smooth, sharp)) in levels.into_iter().enumerate() {
            let approx = SurfaceOptions {
                approx_level_smooth: smooth,
                approx_level_sharp: sharp,
                ..SurfaceOptions::default()
            };
            let mut opts = option_sets[i % option_sets.len()];
            if loop_too && i % 2 == 1 {
                opts = opts.with_scheme(Scheme::Loop);
            }
            compared += compare(&name, &mesh, &opts, approx);
        }
    }
    eprintln!("{compared} faces compared");
    assert!(compared > 2000, "{compared}");
}

/// A generated mesh named compactly for failure messages: its faces,
/// creases, corners and holes.
fn describe(mesh: &Mesh) -> String {
    let faces: Vec<&[u32]> = mesh.faces().collect();
    let creases: Vec<_> = mesh
        .creases
        .iter()
        .map(|c| (c.vertices, c.sharpness))
        .collect();
    let corners: Vec<_> = mesh
        .corners
        .iter()
        .map(|c| (c.vertex, c.sharpness))
        .collect();
    format!(
        "faces {faces:?} creases {creases:?} corners {corners:?} holes {:?}",
        mesh.holes
    )
}

/// Compares a random mesh's faces, triangulated for Loop, naming the mesh
/// compactly in failures.
fn compare_random(mesh: Mesh, opts: Options, smooth: u32, sharp: u32) {
    let mesh = if opts.scheme == Scheme::Loop {
        support::strategies::triangulated(mesh)
    } else {
        mesh
    };
    let approx = SurfaceOptions {
        approx_level_smooth: smooth,
        approx_level_sharp: sharp,
        ..SurfaceOptions::default()
    };
    let name = format!("random {}", describe(&mesh));
    compare(&name, &mesh, &opts, approx);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 150, .. ProptestConfig::default() })]

    /// Random grids with holes, triangles, hexagons, creases and corners,
    /// options and approximation levels.
    #[test]
    fn random_grids_match_opensubdiv(
        mesh in support::strategies::structured(),
        opts in support::strategies::options(),
        smooth in 0u32..5,
        sharp in 0u32..7,
    ) {
        compare_random(mesh, opts, smooth, sharp);
    }

    /// Random polygon soups: non-manifold edges, bowties, repeated
    /// vertices, inconsistent winding.
    #[test]
    fn random_soups_match_opensubdiv(
        mesh in support::strategies::soup(),
        opts in support::strategies::options(),
        smooth in 0u32..5,
        sharp in 0u32..7,
    ) {
        compare_random(mesh, opts, smooth, sharp);
    }
}

/// Compares the face-varying surfaces of every channel of `mesh` under
/// `opts`; returns the number of surfaces compared.
fn compare_fvar(name: &str, mesh: &Mesh, opts: &Options, approx: SurfaceOptions) -> usize {
    let Some((osd, native)) = factories(name, mesh, opts, approx) else {
        return 0;
    };
    let mut compared = 0;
    for (channel, c) in mesh.fvar_channels.iter().enumerate() {
        for face in 0..mesh.face_count() {
            let what = format!("{name} {opts:?} {approx:?} channel {channel} face {face}");
            let Ok(info) = osd.fvar_face_info(face, channel) else {
                continue;
            };
            let s = native
                .fvar_surface(face, channel)
                .unwrap_or_else(|e| panic!("{what}: {e}"));
            if !same_description(&what, &s, &info) {
                continue;
            }
            compared += 1;
            if !info.regular && info.patch_points == info.control_points.len() {
                continue;
            }
            let scale = c.values.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            let ours = s.patch_points(&c.values, c.width).unwrap();
            let theirs = osd.fvar_patch_points(face, channel).unwrap();
            assert_eq!(ours.len(), theirs.len(), "{what}");
            for (i, (p, q)) in ours.iter().zip(&theirs).enumerate() {
                assert!(
                    (p - q).abs() <= 1e-12 * scale,
                    "{what}: patch point value {i}: {p} vs {q}"
                );
            }
            let coords = support::bfr_sample_coords(&s.parameterization());
            let ours = s.evaluate_stencil(&coords, Derivatives::Second).unwrap();
            let theirs = osd
                .evaluate_fvar_stencil(face, channel, &coords, Derivatives::Second)
                .unwrap();
            same_stencils(&what, &coords, &ours, &theirs, approx);
        }
    }
    compared
}

/// Face-varying surfaces of every corpus shape with a channel, in all six
/// linear-interpolation modes, every boundary rule, Catmull-Clark, bilinear
/// and Loop.
#[test]
fn face_varying_surfaces_match_opensubdiv() {
    use subdiv::FVarLinearInterpolation as F;
    let mut compared = 0;
    for (name, mesh) in shapes::corpus() {
        if mesh.fvar_channels.is_empty() {
            continue;
        }
        let triangles = mesh.faces().all(|f| f.len() == 3);
        for (i, fvar) in F::ALL.iter().enumerate() {
            let boundary = BoundaryInterpolation::ALL[i % 3];
            let mut schemes = vec![Scheme::Catmark];
            if i == 0 {
                schemes.push(Scheme::Bilinear);
            }
            if triangles {
                schemes.push(Scheme::Loop);
            }
            for scheme in schemes {
                let opts = Options::default()
                    .with_scheme(scheme)
                    .with_boundary(boundary)
                    .with_fvar(*fvar);
                compared += compare_fvar(&name, &mesh, &opts, SurfaceOptions::default());
            }
        }
    }
    eprintln!("{compared} face-varying surfaces compared");
    assert!(compared > 1000, "{compared}");
}

/// `mesh` with a two-component channel whose seams split it into islands:
/// face `f` takes island `islands[f % len]`, and a vertex has one value
/// per island around it.
fn with_seams(mut mesh: Mesh, islands: &[u8]) -> Mesh {
    let nv = mesh.positions.len() as u32;
    let mut indices = Vec::new();
    for (f, face) in mesh.faces().enumerate() {
        let island = u32::from(islands[f % islands.len()]);
        indices.extend(face.iter().map(|&v| v + island * nv));
    }
    let values = (0..3 * nv)
        .flat_map(|i| {
            let p = mesh.positions[(i % nv) as usize];
            [p.x + f64::from(i / nv), p.y * 0.5 - f64::from(i / nv)]
        })
        .collect();
    mesh.fvar_channels.push(subdiv::FVarChannel {
        width: 2,
        values,
        indices,
    });
    mesh
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 120, .. ProptestConfig::default() })]

    /// Random grids (and soups) with a seamed channel, every
    /// linear-interpolation mode.
    #[test]
    fn random_face_varying_surfaces_match_opensubdiv(
        structured in support::strategies::structured(),
        soup in support::strategies::soup(),
        use_soup in any::<bool>(),
        islands in prop::collection::vec(0u8..3, 1..7),
        opts in support::strategies::options(),
        fvar in prop::sample::select(subdiv::FVarLinearInterpolation::ALL),
        smooth in 0u32..4,
        sharp in 0u32..6,
    ) {
        let mesh = if use_soup { soup } else { structured };
        let mesh = if opts.scheme == Scheme::Loop {
            support::strategies::triangulated(mesh)
        } else {
            mesh
        };
        let mesh = with_seams(mesh, &islands);
        let name = format!("random islands {islands:?} {}", describe(&mesh));
        let approx = SurfaceOptions {
            approx_level_smooth: smooth,
            approx_level_sharp: sharp,
            ..SurfaceOptions::default()
        };
        compare_fvar(&name, &mesh, &opts.with_fvar(fvar), approx);
    }
}

/// Where the whole-mesh `LimitSurfaces` depart from OpenSubdiv's Bfr (the
/// production shape's UV corner at vertex 5 under CornersOnly and
/// CornersPlus1, docs/CONFORMANCE.md), the per-face `MeshSurfaces` agree:
/// values and first derivatives of the channel within 1e-12.
#[test]
fn mesh_surfaces_agree_where_the_global_ones_depart() {
    use subdiv::FVarLinearInterpolation as F;
    let (_, mesh) = shapes::corpus()
        .into_iter()
        .find(|(n, _)| n == "production")
        .expect("the corpus' production shape");
    for fvar in [F::CornersOnly, F::CornersPlus1] {
        let opts = Options::default()
            .with_boundary(BoundaryInterpolation::EdgeAndCorner)
            .with_fvar(fvar);
        let so = SurfaceOptions::default();
        let ours = subdiv::bfr::MeshSurfaces::new(&mesh, &opts, &so).unwrap();
        let theirs = Surfaces::new(&mesh, &opts, &so).unwrap();
        for face in [140, 141, 142] {
            let p = ours.parameterization(face).unwrap();
            let coords = support::bfr_sample_coords(&p);
            let a = ours
                .evaluate_fvar(face, 0, &coords, Derivatives::First)
                .unwrap();
            let b = theirs
                .evaluate_fvar(face, 0, &coords, Derivatives::First)
                .unwrap();
            for (c, (x, y)) in columns(&a.values)
                .iter()
                .zip(columns(&b.values))
                .enumerate()
            {
                assert_eq!(x.len(), y.len());
                for (p, q) in x.iter().zip(y) {
                    assert!(
                        (p - q).abs() < 1e-12,
                        "{fvar:?} face {face} column {c}: {p} vs {q}"
                    );
                }
            }
        }
    }
}

/// Faces that share a control hull (or regular faces with the same
/// boundary mask) and are evaluated at the same coordinates — a
/// tessellation pattern, face after face, as the mesher does — go through
/// an evaluation plan from the second such face on (`src/bfr/plans.rs`):
/// the values and derivatives stay those of the surface's own patch
/// points, for vertex and face-varying surfaces alike.
#[test]
fn evaluation_plans_give_the_patch_points_values() {
    use subdiv::FVarLinearInterpolation as F;
    use subdiv::bfr::{Tessellation, TessellationOptions};
    let mut planned = 0;
    for (name, mesh) in shapes::corpus() {
        let opts = Options::default().with_fvar(F::CornersPlus1);
        let Ok(factory) = SurfaceFactory::new(&mesh, &opts, &SurfaceOptions::default()) else {
            continue;
        };
        let points = mesh.flat_positions::<f64>();
        let scale = points.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        for face in 0..mesh.face_count() {
            let mut surfaces = vec![(factory.vertex_surface(face).unwrap(), &points, 3)];
            if let Some(c) = mesh.fvar_channels.first() {
                surfaces.push((factory.fvar_surface(face, 0).unwrap(), &c.values, c.width));
            }
            for (s, data, width) in surfaces {
                if !s.is_valid() || s.is_linear() {
                    continue;
                }
                let pattern =
                    Tessellation::uniform(s.parameterization(), 5, TessellationOptions::default())
                        .unwrap();
                let coords = pattern.coords::<f64>().unwrap();
                let patch = s.patch_points(data, width).unwrap();
                let expected = s
                    .evaluate_patch_points(&patch, width, &coords, Derivatives::Second)
                    .unwrap();
                // Twice: the second time at the latest from a plan.
                for _ in 0..2 {
                    let got = s
                        .evaluate(data, width, &coords, Derivatives::Second)
                        .unwrap();
                    for (c, (x, y)) in columns(&got.values)
                        .iter()
                        .zip(columns(&expected.values))
                        .enumerate()
                    {
                        assert_eq!(x.len(), y.len());
                        let tol = 1e-11 * scale * 4f64.powi([0, 1, 1, 2, 2, 2][c]);
                        for (p, q) in x.iter().zip(y) {
                            assert!(
                                (p - q).abs() <= tol,
                                "{name} face {face} column {c}: {p} vs {q}"
                            );
                        }
                    }
                }
                planned += 1;
            }
        }
    }
    assert!(planned > 500, "{planned}");
}

/// Found by `random_grids_match_opensubdiv`: a hexagon with an infinitely
/// sharp dart of valence 2 (vertex 15, its faces folded onto each other
/// along two edges). Beside it a Gregory patch's corner ring names one
/// source point past the patch's count; OpenSubdiv's Bfr writes it past the
/// end of its vector and reads it back as a control point, so the bridge
/// refuses the face. Far's `PatchTableFactory` reads it back from its
/// buffer, and the native surface follows Far: its patch points are the
/// base points, the refined points and then the local points OpenSubdiv's
/// Far builds on the face's control hull (Bfr's `IrregularPatchBuilder`
/// hull, one level as approximation level 0 asks).
#[test]
fn valence2_dart_follows_far_where_bfr_overruns() {
    let mut mesh = Mesh::default();
    for j in 0..4 {
        for i in 0..6 {
            let wobble = 0.01 * f64::from((i * 7 + j * 3) % 5);
            mesh.positions.push(glam::DVec3::new(
                f64::from(i) + wobble,
                f64::from(j),
                wobble,
            ));
        }
    }
    let faces: [&[u32]; 11] = [
        &[1, 2, 8, 7],
        &[2, 3, 9, 8],
        &[3, 4, 10, 9],
        &[4, 5, 11, 10],
        &[6, 7, 8, 14, 13, 12],
        &[8, 9, 10, 16, 15, 14],
        &[10, 11, 17, 16],
        &[12, 13, 19, 18],
        &[13, 14, 20, 19],
        &[14, 15, 16, 22, 21, 20],
        &[16, 17, 23, 22],
    ];
    for f in faces {
        mesh.add_face(f);
    }
    mesh.add_crease(16, 15, 10.0);
    let opts = Options::default().with_boundary(BoundaryInterpolation::None);
    let approx = SurfaceOptions {
        approx_level_smooth: 0,
        approx_level_sharp: 0,
        ..SurfaceOptions::default()
    };
    let (osd, native) = factories("dart", &mesh, &opts, approx).unwrap();
    match osd.face_info(5) {
        Err(subdiv::Error::Osd(e)) => {
            assert_eq!(e.kind, subdiv::OsdErrorKind::Unsafe, "{e}");
            assert!(e.message.contains("valence 2"), "{e}");
        }
        other => panic!("face 5: {other:?}"),
    }
    // Its neighbours without the dart stay compared.
    assert!(osd.face_info(1).is_ok());
    let s = native.vertex_surface(5).unwrap();
    let hull_cvs = [
        8, 9, 10, 16, 15, 14, 7, 1, 2, 3, 4, 5, 11, 17, 23, 22, 21, 20, 19, 13, 12, 6,
    ];
    assert_eq!(s.control_points(), &hull_cvs[..]);
    let points = mesh.flat_positions::<f64>();
    let patch = s.patch_points(&points, 3).unwrap();

    let hull_faces: [&[u32]; 10] = [
        &[0, 1, 2, 3, 4, 5],
        &[0, 6, 7, 8],
        &[0, 8, 9, 1],
        &[1, 9, 10, 2],
        &[2, 10, 11, 12],
        &[2, 12, 13, 3],
        &[3, 13, 14, 15],
        &[3, 15, 16, 17, 5, 4],
        &[5, 17, 18, 19],
        &[5, 19, 20, 21, 6, 0],
    ];
    let hull_positions = hull_cvs.iter().map(|&v| mesh.positions[v as usize]);
    let mut hull = Mesh::from_faces(hull_positions.collect(), &hull_faces);
    hull.add_crease(3, 4, 10.0);
    let hull_opts = Options::default().with_boundary(BoundaryInterpolation::EdgeOnly);
    let mut far = subdiv::osd::TopologyRefiner::new(&hull, &hull_opts).unwrap();
    far.refine_adaptive(
        subdiv::AdaptiveOptions::new(1)
            .secondary(1)
            .inf_sharp_patch(true),
        &[0],
    )
    .unwrap();
    let mut po = PatchOptions::new()
        .end_caps(EndCapType::GregoryBasis)
        .inf_sharp_patch(true)
        .max_isolation(1)
        .double_precision(true);
    po.legacy_sharp_corner_patches = false;
    po.share_end_cap_points = false;
    let table = far.patch_table(&po, &[0]).unwrap();
    let table = table.table();
    let levels = far
        .interpolate_all(3, &hull.flat_positions::<f64>())
        .unwrap();
    let refined: Vec<f64> = levels.concat();
    let vertices = refined.len() / 3;
    // Base and refined points first, in the refiner's order.
    let scale = points.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    assert!(patch.len() > refined.len());
    for (i, (p, q)) in patch.iter().zip(&refined).enumerate() {
        assert!(
            (p - q).abs() <= 1e-12 * scale,
            "point {}: {p} vs {q}",
            i / 3
        );
    }
    // Then the Gregory patches of the hexagon's six sub-faces (ptex faces
    // 0..6 at depth 1), their points in patch order.
    let mut far_locals = Vec::new();
    for array in &table.arrays {
        if array.patch_type != PatchType::GregoryBasis {
            continue;
        }
        let n = array.patch_type.control_vertices();
        for (p, param) in array.params.iter().enumerate() {
            if param.face_id() >= 6 || param.depth() != 1 {
                continue;
            }
            for &cv in &array.control_vertices[p * n..(p + 1) * n] {
                let (indices, weights) = table.local_point_stencils.row(cv as usize - vertices);
                let mut x = [0.0; 3];
                for (&i, &w) in indices.iter().zip(weights) {
                    for (k, x) in x.iter_mut().enumerate() {
                        *x += w * refined[3 * i as usize + k];
                    }
                }
                far_locals.extend(x);
            }
        }
    }
    assert_eq!(far_locals.len(), 6 * 20 * 3);
    assert_eq!(patch.len(), refined.len() + far_locals.len());
    for (i, (p, q)) in patch[refined.len()..].iter().zip(&far_locals).enumerate() {
        assert!(
            (p - q).abs() <= 1e-12 * scale,
            "local point {} component {}: {p} vs {q}",
            i / 3,
            i % 3
        );
    }
}

/// `SurfaceOptions::caching` off refines every irregular face's
/// neighbourhood anew and changes nothing: the same control points and
/// patch points, the same values (within rounding: without the cache no
/// face shares another's evaluation plans); `default_fvar_surface` is the surface of
/// the options' default channel, and an absent default channel is refused.
#[test]
fn caching_and_the_default_channel_change_nothing_else() {
    let mut faces = 0;
    for (name, mesh) in shapes::corpus() {
        let opts = Options::default()
            .with_boundary(BoundaryInterpolation::EdgeOnly)
            .with_fvar(subdiv::FVarLinearInterpolation::CornersPlus1);
        let cached = SurfaceFactory::new(&mesh, &opts, &SurfaceOptions::default()).unwrap();
        let fresh = SurfaceFactory::new(
            &mesh,
            &opts,
            &SurfaceOptions {
                caching: false,
                ..SurfaceOptions::default()
            },
        )
        .unwrap();
        let points = mesh.flat_positions::<f64>();
        for face in 0..mesh.face_count() {
            let (a, b) = (
                cached.vertex_surface(face).unwrap(),
                fresh.vertex_surface(face).unwrap(),
            );
            assert_eq!(a.control_points(), b.control_points(), "{name} face {face}");
            assert_eq!(
                a.patch_point_count(),
                b.patch_point_count(),
                "{name} face {face}"
            );
            if !a.is_valid() {
                continue;
            }
            let coords = support::bfr_sample_coords(&a.parameterization());
            let (x, y) = (
                a.evaluate(&points, 3, &coords, Derivatives::Second)
                    .unwrap(),
                b.evaluate(&points, 3, &coords, Derivatives::Second)
                    .unwrap(),
            );
            // (A cached neighbourhood's faces go through its evaluation
            // plans: the same values but for rounding.)
            let scale = points.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            for (c, (p, q)) in columns(&x.values)
                .iter()
                .zip(columns(&y.values))
                .enumerate()
            {
                let tol = 1e-11 * scale * 4f64.powi([0, 1, 1, 2, 2, 2][c]);
                assert!(
                    p.iter().zip(q).all(|(s, t)| (s - t).abs() <= tol),
                    "{name} face {face} column {c}"
                );
            }
            if !mesh.fvar_channels.is_empty() {
                let (d, e) = (
                    cached.default_fvar_surface(face).unwrap(),
                    cached.fvar_surface(face, 0).unwrap(),
                );
                assert_eq!(d.control_points(), e.control_points(), "{name} face {face}");
            }
            faces += 1;
        }
    }
    assert!(faces > 1000, "{faces}");
    // The default channel is the options' (here one the mesh lacks).
    let cube = shapes::cube_with_uvs();
    let second = SurfaceFactory::new(
        &cube,
        &Options::default(),
        &SurfaceOptions {
            default_fvar_channel: 1,
            ..SurfaceOptions::default()
        },
    )
    .unwrap();
    assert!(matches!(
        second.default_fvar_surface(0),
        Err(subdiv::Error::NoSuchChannel { channel: 1, .. })
    ));
}

/// Box-spline patches of every boundary kind evaluated through the plans
/// their kind keeps: a triangulated grid (boundary triangles with one
/// boundary edge, their third vertex inside) and a strip of triangles
/// (every vertex on the boundary, one boundary edge each: the mask kind of
/// `encodeTriBoundaryMask` with edge and vertex bits). Every face's values
/// are its own patch's, however many faces of other kinds came first.
#[test]
fn box_spline_boundary_kinds_keep_their_own_plans() {
    use subdiv::bfr::{Tessellation, TessellationOptions};
    let mut mesh = shapes::triangulate(&shapes::grid(4, 3));
    mesh.fvar_channels.clear();
    let n = 8u32;
    let bottom = mesh.positions.len() as u32;
    let top = bottom + n + 1;
    for row in 0..2 {
        for i in 0..=n {
            let z = 0.1 * f64::from((i * 7 + row * 3) % 5);
            mesh.positions
                .push(glam::DVec3::new(f64::from(i), 5.0 + f64::from(row), z));
        }
    }
    for i in 0..n {
        mesh.add_face(&[bottom + i, bottom + i + 1, top + i + 1]);
        mesh.add_face(&[bottom + i, top + i + 1, top + i]);
    }
    let opts = Options::default()
        .with_scheme(Scheme::Loop)
        .with_boundary(BoundaryInterpolation::EdgeOnly);
    let factory = SurfaceFactory::new(&mesh, &opts, &SurfaceOptions::default()).unwrap();
    let points = mesh.flat_positions::<f64>();
    let mut regular = 0;
    for face in 0..mesh.face_count() {
        let s = factory.vertex_surface(face).unwrap();
        if !s.is_valid() || !s.is_regular() {
            continue;
        }
        regular += 1;
        let pattern =
            Tessellation::uniform(s.parameterization(), 5, TessellationOptions::default()).unwrap();
        let coords = pattern.coords::<f64>().unwrap();
        let patch = s.patch_points(&points, 3).unwrap();
        let expected = s
            .evaluate_patch_points(&patch, 3, &coords, Derivatives::First)
            .unwrap();
        for _ in 0..2 {
            let got = s.evaluate(&points, 3, &coords, Derivatives::First).unwrap();
            for (c, (x, y)) in columns(&got.values)
                .iter()
                .zip(columns(&expected.values))
                .enumerate()
            {
                for (p, q) in x.iter().zip(y) {
                    assert!((p - q).abs() <= 1e-11, "face {face} column {c}: {p} vs {q}");
                }
            }
        }
    }
    assert!(regular >= 20, "{regular}");
}
