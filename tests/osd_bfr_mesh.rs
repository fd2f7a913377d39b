//! A whole mesh tessellated by OpenSubdiv's Bfr in one C++ call
//! (`subdiv::osd::bfr::tessellate_mesh`) against the native mesher
//! (`subdiv::bfr::tessellate` over `LimitSurfaces`): the same mesh, index
//! for index, positions, normals and texture coordinates within 1e-9 of
//! the bounding box's diagonal (Catmull-Clark, bilinear and Loop), Loop
//! meshes watertight;
//! every refusal before OpenSubdiv sees the input. Run it under Valgrind:
//! `valgrind --error-exitcode=1 target/debug/deps/osd_bfr_mesh-*`.
#![cfg(feature = "osd")]

use glam::DVec3;
use std::collections::HashMap;
use subdiv::bfr::{
    FaceSurfaces, FacetSize, LimitSurfaces, MAX_RATE, MeshSurfaces, SurfaceOptions,
    TessellateOptions, TessellatedMesh, Tessellation, TessellationOptions, tessellate,
};
use subdiv::osd::bfr::tessellate_mesh;
use subdiv::patches::Derivatives;
use subdiv::{
    BoundaryInterpolation, Error, FVarLinearInterpolation, Mesh, Options, OsdError, OsdErrorKind,
    Scheme, shapes,
};

fn refused<T: std::fmt::Debug>(r: subdiv::Result<T>, kind: OsdErrorKind, needles: &[&str]) {
    match r {
        Err(Error::Osd(OsdError { kind: k, message })) => {
            assert_eq!(k, kind, "{message}");
            for needle in needles {
                assert!(message.contains(needle), "{message:?} lacks {needle:?}");
            }
        }
        other => panic!("expected a {kind:?} refusal mentioning {needles:?}, got {other:?}"),
    }
}

fn diagonal(points: &[DVec3]) -> f64 {
    let (lo, hi) = points.iter().fold(
        (DVec3::splat(f64::MAX), DVec3::splat(f64::MIN)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    (hi - lo).length()
}

/// The sine of the angle between the native surface's du and dv at point
/// `i` of `t` (the native mesher's output): the conditioning of its normal.
/// The point's face is the first whose facets use it (the face that created
/// it), its coordinate the one of that face's pattern evaluating to it.
fn tangent_sine(
    mesh: &Mesh,
    surfaces: &LimitSurfaces,
    tess: &TessellateOptions,
    t: &TessellatedMesh,
    i: usize,
) -> f64 {
    let facet = (0..t.facet_faces.len())
        .find(|&k| {
            t.face_vertices[t.face_offsets[k] as usize..t.face_offsets[k + 1] as usize]
                .contains(&(i as u32))
        })
        .unwrap();
    let face = t.facet_faces[facet] as usize;
    let fv = mesh.face(face);
    let rates: Vec<u32> = (0..fv.len())
        .map(|k| match tess.edge_length {
            None => tess.rate,
            Some(l) => {
                let d = mesh.positions[fv[k] as usize]
                    .distance(mesh.positions[fv[(k + 1) % fv.len()] as usize]);
                (1.0 + (d / l).floor()).min(f64::from(MAX_RATE)) as u32
            }
        })
        .collect();
    let options = TessellationOptions {
        preserve_quads: tess.quads,
        facet_size: if tess.quads {
            FacetSize::Four
        } else {
            FacetSize::Three
        },
    };
    let pattern =
        Tessellation::new(surfaces.parameterization(face).unwrap(), &rates, options).unwrap();
    let coords = pattern.coords::<f64>().unwrap();
    let s = surfaces
        .evaluate(face, &coords, Derivatives::First)
        .unwrap();
    let v = &s.values;
    let k = (0..coords.len())
        .min_by(|&a, &b| {
            let d =
                |k: usize| DVec3::from_slice(&v.point[3 * k..3 * k + 3]).distance(t.positions[i]);
            d(a).total_cmp(&d(b))
        })
        .unwrap();
    let du = DVec3::from_slice(&v.du[3 * k..3 * k + 3]);
    let dv = DVec3::from_slice(&v.dv[3 * k..3 * k + 3]);
    du.cross(dv).length() / (du.length() * dv.length())
}

/// Asserts that two meshes are the same: indices equal, positions and
/// texture coordinates within 1e-9 of their bounding boxes' diagonals,
/// normals within 1e-9 where they are well conditioned (where du and dv
/// are nearly parallel, rounding differences of 1e-16 in the derivatives
/// grow as 1 / sin(du, dv): the normal is allowed 1e-13 / sin). Returns
/// the number of ill-conditioned normals that differed by more than 1e-9.
fn assert_same_with(
    label: &str,
    native: &TessellatedMesh,
    osd: &TessellatedMesh,
    sine: &mut dyn FnMut(usize) -> f64,
) -> usize {
    assert_eq!(
        native.face_offsets, osd.face_offsets,
        "{label}: face offsets"
    );
    assert_eq!(
        native.face_vertices, osd.face_vertices,
        "{label}: face vertices"
    );
    assert_eq!(native.facet_faces, osd.facet_faces, "{label}: facet faces");
    assert_eq!(native.uv_indices, osd.uv_indices, "{label}: uv indices");
    assert_eq!(
        native.positions.len(),
        osd.positions.len(),
        "{label}: points"
    );
    assert_eq!(native.normals.len(), osd.normals.len(), "{label}: normals");
    assert_eq!(native.uvs.len(), osd.uvs.len(), "{label}: uvs");
    let tol = 1e-9 * diagonal(&native.positions).max(1.0);
    for (i, (a, b)) in native.positions.iter().zip(&osd.positions).enumerate() {
        assert!(
            (*a - *b).abs().max_element() <= tol,
            "{label}: point {i}: {a} vs {b}"
        );
    }
    let mut ill = 0;
    for (i, (a, b)) in native.normals.iter().zip(&osd.normals).enumerate() {
        let d = (*a - *b).abs().max_element();
        if d > 1e-9 {
            let sin = sine(i);
            assert!(
                d <= 1e-13 / sin,
                "{label}: normal {i}: {a} vs {b} (sin(du, dv) {sin:e})"
            );
            ill += 1;
        }
    }
    let uv_points: Vec<DVec3> = native
        .uvs
        .chunks_exact(2)
        .map(|p| DVec3::new(p[0], p[1], 0.0))
        .collect();
    let uv_tol = 1e-9 * diagonal(&uv_points).max(1.0);
    for (i, (a, b)) in native.uvs.iter().zip(&osd.uvs).enumerate() {
        assert!((a - b).abs() <= uv_tol, "{label}: uv {i}: {a} vs {b}");
    }
    ill
}

/// As [`assert_same_with`], for meshes without normals.
fn assert_same(label: &str, native: &TessellatedMesh, osd: &TessellatedMesh) {
    assert!(native.normals.is_empty());
    assert_same_with(label, native, osd, &mut |_| unreachable!());
}

/// Every facet edge, directed, counted.
fn directed_edges(t: &TessellatedMesh) -> HashMap<(u32, u32), u32> {
    let mut edges = HashMap::new();
    for w in t.face_offsets.windows(2) {
        let f = &t.face_vertices[w[0] as usize..w[1] as usize];
        for i in 0..f.len() {
            *edges.entry((f[i], f[(i + 1) % f.len()])).or_insert(0) += 1;
        }
    }
    edges
}

fn assert_closed(t: &TessellatedMesh, label: &str) {
    let edges = directed_edges(t);
    for (&(a, b), &count) in &edges {
        let back = edges.get(&(b, a)).copied().unwrap_or(0);
        assert_eq!((count, back), (1, 1), "{label}: edge {a}-{b}");
    }
}

/// The tessellation options of the sweep: rates 1, 3 and 8, with and
/// without quads, normals and UVs, and rates from edge lengths.
fn sweep(diag: f64) -> Vec<TessellateOptions> {
    let mut out = Vec::new();
    for rate in [1, 3, 8] {
        for (quads, normals, uvs) in [
            (false, false, false),
            (true, true, true),
            (false, true, true),
            (true, false, false),
        ] {
            out.push(TessellateOptions {
                rate,
                edge_length: None,
                quads,
                normals,
                uvs,
            });
        }
    }
    for (l, quads) in [(diag / 7.0, false), (diag / 3.0, true)] {
        out.push(TessellateOptions {
            rate: 1,
            edge_length: Some(l),
            quads,
            normals: true,
            uvs: true,
        });
    }
    out
}

/// Every sweep option on `mesh` under `options`, both ways; returns the
/// number of comparisons.
fn compare(label: &str, mesh: &Mesh, options: &Options) -> usize {
    compare_surfaces(label, mesh, options, false)
}

/// [`compare`], the native mesher over the per-face `MeshSurfaces` when
/// `per_face`, else over the whole-mesh `LimitSurfaces`.
fn compare_surfaces(label: &str, mesh: &Mesh, options: &Options, per_face: bool) -> usize {
    let surface = SurfaceOptions::default();
    let native_surfaces = LimitSurfaces::new(mesh, options, &surface)
        .unwrap_or_else(|e| panic!("{label}: native surfaces: {e}"));
    let per_face_surfaces = MeshSurfaces::new(mesh, options, &surface)
        .unwrap_or_else(|e| panic!("{label}: per-face surfaces: {e}"));
    let surfaces: &dyn FaceSurfaces = if per_face {
        &per_face_surfaces
    } else {
        &native_surfaces
    };
    let mut n = 0;
    for tess in sweep(diagonal(&mesh.positions)) {
        let what = format!("{label} {tess:?}");
        let native =
            tessellate(mesh, surfaces, &tess).unwrap_or_else(|e| panic!("{what}: native: {e}"));
        let osd = tessellate_mesh(mesh, options, &surface, &tess)
            .unwrap_or_else(|e| panic!("{what}: OpenSubdiv: {e}"));
        let ill = assert_same_with(&what, &native, &osd, &mut |i| {
            tangent_sine(mesh, &native_surfaces, &tess, &native, i)
        });
        if ill > 0 {
            println!("{what}: {ill} ill-conditioned normals differ by more than 1e-9");
        }
        if tess.uvs && !mesh.fvar_channels.is_empty() {
            assert!(!osd.uvs.is_empty(), "{what}: no uvs");
            assert_eq!(osd.uv_indices.len(), osd.face_vertices.len(), "{what}");
        }
        assert_eq!(
            osd.normals.len(),
            if tess.normals { osd.positions.len() } else { 0 }
        );
        n += 1;
    }
    n
}

fn edge_only() -> Options {
    Options::default().with_boundary(BoundaryInterpolation::EdgeOnly)
}

#[test]
fn simple_shapes_match_the_native_mesher() {
    let closed = Options::default();
    compare("cube", &shapes::cube(), &closed);
    compare("pyramid-5", &shapes::pyramid(5), &closed);
    compare("torus 8x6", &shapes::torus(8, 6), &closed);
    // UVs: the native surfaces evaluate linear face-varying data (the
    // default, FVarLinearInterpolation::All) and bilinear meshes.
    compare("cube with uvs", &shapes::cube_with_uvs(), &closed);
    compare(
        "cube with uvs, bilinear",
        &shapes::cube_with_uvs(),
        &closed.with_scheme(Scheme::Bilinear),
    );
    compare(
        "torus with uvs",
        &shapes::with_torus_uvs(shapes::torus_mixed(6, 4), 6, 4),
        &closed,
    );
}

#[test]
fn meshes_with_holes_and_boundaries_match_the_native_mesher() {
    let mut cube = shapes::cube();
    cube.holes.push(1);
    compare("cube with a hole", &cube, &Options::default());
    compare("cube with a hole, edge-only", &cube, &edge_only());
    let mut grid = shapes::grid(4, 4);
    grid.holes.extend([5, 6, 15]);
    compare("grid with holes, edge-only", &grid, &edge_only());
    compare(
        "grid with holes, edge-and-corner",
        &grid,
        &Options::default().with_boundary(BoundaryInterpolation::EdgeAndCorner),
    );
    // Boundary interpolation None: the boundary faces have no surface, in
    // both.
    let t = tessellate_mesh(
        &grid,
        &Options::default(),
        &SurfaceOptions::default(),
        &TessellateOptions::default(),
    )
    .unwrap();
    assert_eq!(
        t.facet_faces
            .iter()
            .collect::<std::collections::BTreeSet<_>>(),
        [9u32, 10].iter().collect()
    );
    compare("grid with holes, no boundary", &grid, &Options::default());
}

/// Every shape of the corpus (n-gons, poles, boundaries, creases, corners,
/// holes, non-manifold features, UV seams) under both boundary rules that
/// keep boundary faces. Non-manifold shapes have smooth boundary corners of
/// one face under EdgeOnly, where du and dv are parallel (sin < 1e-14): their
/// normals are rounding noise in both engines, and allowed to differ.
#[test]
fn the_corpus_matches_the_native_mesher() {
    let mut done = 0;
    for (name, mesh) in shapes::corpus() {
        for options in [
            edge_only(),
            Options::default().with_boundary(BoundaryInterpolation::EdgeAndCorner),
        ] {
            done += compare(&name, &mesh, &options);
        }
    }
    assert!(done > 1800, "{done} comparisons");
}

/// The per-face surfaces (`MeshSurfaces`, whose regular faces skip
/// building a surface: the refiner's shortcut and a kept plan, positions
/// and texture coordinates sharing the shortcut's points) in the mesher
/// against Bfr's: linear and smooth UVs, channels of 1, 2 and 3
/// components, boundaries and the production-like shape under USD's
/// defaults.
#[test]
fn per_face_surfaces_match_bfr_in_the_mesher() {
    use FVarLinearInterpolation as F;
    let torus = shapes::with_torus_uvs(shapes::torus(8, 6), 8, 6);
    // The channel widened to 3 components and narrowed to 1.
    let with_width = |mesh: &Mesh, width: usize| {
        let mut mesh = mesh.clone();
        let c = &mut mesh.fvar_channels[0];
        c.values = c
            .values
            .chunks_exact(2)
            .flat_map(|uv| [uv[0], uv[1], uv[0] - 2.0 * uv[1]][..width].to_vec())
            .collect();
        c.width = width;
        mesh
    };
    let mut done = 0;
    for fvar in [F::All, F::CornersPlus1, F::None] {
        let options = Options::default().with_fvar(fvar);
        for width in [1, 2, 3] {
            let label = format!("torus 8x6, {width}-component channel, {fvar:?}");
            done += compare_surfaces(&label, &with_width(&torus, width), &options, true);
        }
    }
    let mut grid = shapes::grid(6, 5);
    assert!(!grid.fvar_channels.is_empty());
    grid.holes.push(7);
    done += compare_surfaces("grid with a hole", &grid, &edge_only(), true);
    let usd = Options::default()
        .with_boundary(BoundaryInterpolation::EdgeAndCorner)
        .with_fvar(F::CornersPlus1);
    done += compare_surfaces("production", &shapes::production(8, 6), &usd, true);
    assert_eq!(done, 11 * 14);
}

/// The production-like shape again with USD's defaults, its UVs smooth
/// (face-varying corners-plus-one): the native surfaces evaluate them over
/// non-linear face-varying patches, and the whole mesh, UVs included,
/// equals Bfr's.
#[test]
fn smooth_uvs_match_bfr() {
    let mesh = shapes::production(8, 6);
    let usd = Options::default()
        .with_boundary(BoundaryInterpolation::EdgeAndCorner)
        .with_fvar(FVarLinearInterpolation::CornersPlus1);
    let surface = SurfaceOptions::default();
    let native_surfaces = LimitSurfaces::new(&mesh, &usd, &surface).unwrap();
    for rate in [1, 3, 8] {
        let tess = TessellateOptions {
            rate,
            uvs: true,
            ..TessellateOptions::default()
        };
        let osd = tessellate_mesh(&mesh, &usd, &surface, &tess).unwrap();
        let native = tessellate(&mesh, &native_surfaces, &tess).unwrap();
        assert!(!native.uvs.is_empty());
        assert_same(
            &format!("production, USD defaults, rate {rate}"),
            &native,
            &osd,
        );
    }
}

/// Loop meshes: the native mesher against Bfr's on the icosahedron and
/// every all-triangle shape of the corpus (boundaries, creases, holes), and
/// the icosahedron's tessellation counted and checked watertight.
#[test]
fn loop_meshes_match_and_tessellate_watertight() {
    let mesh = shapes::icosahedron();
    let loop_ = Options::default().with_scheme(Scheme::Loop);
    let mut done = compare("icosahedron, Loop", &mesh, &loop_);
    for (name, mesh) in shapes::corpus() {
        if mesh.faces().all(|f| f.len() == 3) {
            for boundary in [
                BoundaryInterpolation::EdgeOnly,
                BoundaryInterpolation::EdgeAndCorner,
            ] {
                let options = loop_.with_boundary(boundary);
                done += compare(&format!("{name}, Loop"), &mesh, &options);
            }
        }
    }
    assert!(done > 100, "{done} comparisons");
    for rate in [1u32, 3, 8] {
        for quads in [false, true] {
            let tess = TessellateOptions {
                rate,
                quads,
                normals: true,
                ..TessellateOptions::default()
            };
            let t = tessellate_mesh(&mesh, &loop_, &SurfaceOptions::default(), &tess).unwrap();
            let r = rate as usize;
            // 12 vertices, r - 1 points inside each of 30 edges, (r-1)(r-2)/2
            // inside each of 20 triangles; r^2 triangles per face.
            assert_eq!(
                t.positions.len(),
                12 + 30 * (r - 1) + 20 * (r - 1) * r.saturating_sub(2) / 2
            );
            assert_eq!(t.facet_faces.len(), 20 * r * r);
            assert!(t.face_offsets.windows(2).all(|w| w[1] - w[0] == 3));
            assert_closed(&t, &format!("icosahedron, Loop, rate {rate}"));
            // Convex and centred at the origin: normals point outwards.
            assert!(
                t.positions
                    .iter()
                    .zip(&t.normals)
                    .all(|(p, n)| p.dot(*n) > 0.0)
            );
        }
    }
}

#[test]
fn closed_meshes_stay_closed() {
    for (label, mesh) in [
        ("torus", shapes::torus(8, 6)),
        ("torus mixed", shapes::torus_mixed(6, 4)),
        ("pyramid", shapes::pyramid(7)),
    ] {
        for edge_length in [None, Some(0.3)] {
            let tess = TessellateOptions {
                rate: 5,
                edge_length,
                quads: true,
                ..TessellateOptions::default()
            };
            let t = tessellate_mesh(
                &mesh,
                &Options::default(),
                &SurfaceOptions::default(),
                &tess,
            )
            .unwrap();
            assert_closed(&t, label);
        }
    }
}

#[test]
fn refusals_come_before_opensubdiv() {
    let cube = shapes::cube();
    let o = Options::default();
    let s = SurfaceOptions::default();
    let t = TessellateOptions::default();
    let with = |tess: TessellateOptions| tessellate_mesh(&cube, &o, &s, &tess);
    refused(
        with(TessellateOptions { rate: 0, ..t }),
        OsdErrorKind::Refused,
        &["rate 0"],
    );
    refused(
        with(TessellateOptions { rate: 40_000, ..t }),
        OsdErrorKind::Refused,
        &["rate 40000", "32767"],
    );
    for l in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        refused(
            with(TessellateOptions {
                edge_length: Some(l),
                ..t
            }),
            OsdErrorKind::Refused,
            &["edge length"],
        );
    }
    refused(
        tessellate_mesh(
            &cube,
            &o,
            &SurfaceOptions {
                approx_level_smooth: 11,
                approx_level_sharp: 11,
                ..SurfaceOptions::default()
            },
            &t,
        ),
        OsdErrorKind::Refused,
        &["approximation level 11"],
    );
    // One face's pattern beyond 2^24 coordinates.
    refused(
        with(TessellateOptions { rate: 5000, ..t }),
        OsdErrorKind::Refused,
        &["face 0", "2^24"],
    );
    // The mesh beyond 2^25 points, refused before any surface is built.
    let torus = shapes::torus(100, 100);
    let start = std::time::Instant::now();
    refused(
        tessellate_mesh(&torus, &o, &s, &TessellateOptions { rate: 60, ..t }),
        OsdErrorKind::Refused,
        &["points", "2^25"],
    );
    assert!(start.elapsed().as_secs_f64() < 5.0);
    // Edge-length rates capped at 32767, then the pattern's bound.
    refused(
        with(TessellateOptions {
            edge_length: Some(1e-9),
            ..t
        }),
        OsdErrorKind::Refused,
        &["2^24"],
    );
}

/// OpenSubdiv's regression shape `catmark_val2_interior` with creases:
/// two hexagons sharing three edges (see tests/osd_bfr_surface.rs).
fn val2_interior(creased: bool) -> Mesh {
    let mut m = Mesh::from_faces(
        [
            [-0.5, 0.0, -1.75],
            [0.0, 0.0, -1.75],
            [0.0, -0.5, -1.75],
            [0.5, 0.0, -1.75],
            [-0.5, 0.0, -0.75],
            [0.0, 0.0, -0.75],
            [0.0, -0.5, -0.75],
            [0.5, 0.0, -0.75],
        ]
        .into_iter()
        .map(DVec3::from_array)
        .collect(),
        &[&[0, 1, 2, 6, 5, 4], &[7, 5, 6, 2, 1, 3]],
    );
    if creased {
        m.add_crease(1, 2, 5.0);
        m.add_crease(2, 6, 5.0);
        m.add_crease(6, 5, 5.0);
    }
    m
}

#[test]
fn faces_the_surfaces_bridge_refuses_refuse_the_mesh() {
    let o = edge_only();
    let s = SurfaceOptions::default();
    let t = TessellateOptions::default();
    refused(
        tessellate_mesh(&val2_interior(true), &o, &s, &t),
        OsdErrorKind::Unsafe,
        &[
            "face 0: its corner vertex",
            "interior vertex of valence 2",
            "3.5.1",
        ],
    );
    // Without the creases, or bilinear, nothing is refused.
    assert!(tessellate_mesh(&val2_interior(false), &o, &s, &t).is_ok());
    assert!(
        tessellate_mesh(
            &val2_interior(true),
            &o.with_scheme(Scheme::Bilinear),
            &s,
            &t
        )
        .is_ok()
    );
    // As holes, the faces are never built: nothing to refuse.
    let mut holes = val2_interior(true);
    holes.holes.extend([0, 1]);
    let m = tessellate_mesh(&holes, &o, &s, &t).unwrap();
    assert!(m.positions.is_empty() && m.facet_faces.is_empty());
    assert_eq!(m.face_offsets[..], [0]);
    // Smooth UVs go through the same builder (any corner may bound the
    // channel at a seam): a closed pillow of two quads, every vertex
    // interior of valence 2, one edge creased, is refused with them only.
    let mut pillow = Mesh::from_faces(
        [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ]
        .into_iter()
        .map(DVec3::from_array)
        .collect(),
        &[&[0, 1, 2, 3], &[3, 2, 1, 0]],
    );
    pillow.add_crease(0, 1, 2.0);
    pillow.fvar_channels.push(subdiv::FVarChannel {
        width: 2,
        values: pillow.positions.iter().flat_map(|p| [p.x, p.y]).collect(),
        indices: pillow.face_vertices.clone(),
    });
    let smooth = Options::default().with_fvar(FVarLinearInterpolation::None);
    let no_uvs = TessellateOptions { uvs: false, ..t };
    assert!(tessellate_mesh(&pillow, &smooth, &s, &no_uvs).is_ok());
    refused(
        tessellate_mesh(&pillow, &smooth, &s, &t),
        OsdErrorKind::Unsafe,
        &["face 0: its corner vertex", "face-varying subsets"],
    );
    let linear = Options::default().with_fvar(FVarLinearInterpolation::All);
    assert!(tessellate_mesh(&pillow, &linear, &s, &t).is_ok());
}
