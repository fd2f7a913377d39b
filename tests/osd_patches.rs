//! Patch tables through the bridge (`Far::PatchTableFactory`,
//! `Far::PatchMap`, `PatchTable::EvaluateBasis`): hand-derived counts and
//! bicubic B-spline weights, the patches tiling every ptex face, the basis a
//! partition of unity, the limit surface at a face's corners equal to the
//! native engine's limit positions, uniform tables over the last level, and
//! every refusal before OpenSubdiv sees the input.
#![cfg(feature = "osd")]

use subdiv::patches::{
    Derivatives, EndCapType, PatchHandle, PatchMap, PatchOptions, PatchType, evaluate_basis,
};
use subdiv::refiner::Refiner;
use subdiv::{Error, Mesh, Options, Scheme, UniformOptions, osd, shapes};

fn adaptive(mesh: &Mesh, options: &PatchOptions) -> (osd::TopologyRefiner, osd::OsdPatchTable) {
    let mut r = osd::TopologyRefiner::new(mesh, &Options::default()).unwrap();
    r.refine_adaptive(options.refine_adaptive_options(), &[])
        .unwrap();
    let t = r.patch_table(options, &[]).unwrap();
    (r, t)
}

fn total_vertices(r: &osd::TopologyRefiner) -> usize {
    (0..=r.max_level())
        .map(|l| r.level_counts(l).unwrap().vertices)
        .sum()
}

/// The cube isolated to depth 2: each face splits into 16 patches; the
/// four touching a corner (valence 3, extraordinary) are Gregory basis end
/// caps of 20 points, the other twelve regular B-spline patches.
#[test]
fn cube_patches_by_hand() {
    let cube = shapes::cube();
    let unshared = PatchOptions {
        share_end_cap_points: false,
        ..PatchOptions::new().max_isolation(2)
    };
    for options in [PatchOptions::new().max_isolation(2), unshared] {
        let (r, patches) = adaptive(&cube, &options);
        let t = patches.table();
        assert_eq!(r.max_level(), 2);
        assert!(t.feature_adaptive);
        assert_eq!(t.ptex_faces, 6);
        assert_eq!(t.arrays.len(), 2);
        assert_eq!(t.arrays[0].patch_type, PatchType::Regular);
        assert_eq!(t.arrays[0].len(), 6 * 12);
        assert_eq!(t.arrays[1].patch_type, PatchType::GregoryBasis);
        assert_eq!(t.arrays[1].len(), 6 * 4);
        if options.share_end_cap_points {
            // Neighbouring end caps share points.
            assert!(t.local_points < 24 * 20);
        } else {
            assert_eq!(t.local_points, 24 * 20);
        }
        let points = total_vertices(&r) + t.local_points;
        for a in &t.arrays {
            assert_eq!(
                a.control_vertices.len(),
                a.len() * a.patch_type.control_vertices()
            );
            assert!(a.control_vertices.iter().all(|&v| (v as usize) < points));
            for p in &a.params {
                assert_eq!(p.depth(), 2);
                assert!(!p.non_quad_root());
                assert_eq!(p.boundary(), 0);
                assert_eq!(p.is_regular(), a.patch_type == PatchType::Regular);
            }
            // No single-crease patches asked for.
            assert!(a.sharpness.iter().all(|&s| s == 0.0));
        }
        // Gregory basis points are local points, after the refined vertices.
        assert!(
            t.arrays[1]
                .control_vertices
                .iter()
                .all(|&v| v as usize >= total_vertices(&r))
        );
        // The local points' stencils: one per local point, weights summing
        // to 1 (affine combinations of refined vertices).
        let s = patches.local_point_stencils().unwrap();
        assert_eq!(s.len(), t.local_points);
        for i in 0..s.len() {
            let (idx, w) = s.row(i);
            assert!(idx.iter().all(|&v| (v as usize) < total_vertices(&r)));
            assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-5);
        }
    }
}

/// The patches of every ptex face tile its unit square exactly once: the
/// areas (4^-depth, or 4^-(depth-1) under a non-quad root whose sub-faces
/// are the ptex faces) sum to 1 and no two patches overlap.
#[test]
fn patches_tile_every_ptex_face() {
    let mut creased = shapes::cube();
    creased.add_crease(0, 1, 2.5);
    creased.add_corner(6, 10.0);
    for (name, mesh) in [
        ("cube", shapes::cube()),
        ("creased", creased),
        ("pole-5", shapes::pole(5)),
        ("prism-6", shapes::prism(6)),
        ("torus-mixed", shapes::torus_mixed(6, 4)),
    ] {
        for options in [
            PatchOptions::new().max_isolation(3),
            PatchOptions::new()
                .max_isolation(2)
                .single_crease_patch(true)
                .end_caps(EndCapType::BSplineBasis),
        ] {
            let (_, patches) = adaptive(&mesh, &options);
            let t = patches.table();
            let mut cells: Vec<std::collections::HashSet<(u32, u32, u32)>> =
                vec![Default::default(); t.ptex_faces];
            let mut area = vec![0.0f64; t.ptex_faces];
            for a in &t.arrays {
                for p in &a.params {
                    let d = p.depth() - p.non_quad_root() as u32;
                    area[p.face_id() as usize] += 0.25f64.powi(d as i32);
                    assert!(
                        cells[p.face_id() as usize].insert((d, p.u(), p.v())),
                        "{name}: two patches at {p:?}"
                    );
                    assert!(p.u() < 1 << d && p.v() < 1 << d, "{name}: {p:?}");
                }
            }
            for (f, a) in area.iter().enumerate() {
                assert_eq!(*a, 1.0, "{name}: ptex face {f} covered {a}");
            }
        }
    }
}

/// The uniform cubic B-spline basis at `s`, and its derivative.
fn bspline(s: f64) -> ([f64; 4], [f64; 4]) {
    let t = 1.0 - s;
    (
        [
            t * t * t / 6.0,
            (3.0 * s * s * s - 6.0 * s * s + 4.0) / 6.0,
            (-3.0 * s * s * s + 3.0 * s * s + 3.0 * s + 1.0) / 6.0,
            s * s * s / 6.0,
        ],
        [
            -t * t / 2.0,
            (3.0 * s * s - 4.0 * s) / 2.0,
            (-3.0 * s * s + 2.0 * s + 1.0) / 2.0,
            s * s / 2.0,
        ],
    )
}

/// A regular interior patch's weights are the tensor product of the cubic
/// B-spline basis (weight `4 j + i` for basis `i` in u and `j` in v), its
/// derivatives scaled by 2^depth from the patch's square to the ptex face's.
#[test]
fn regular_weights_are_the_bicubic_bspline_basis() {
    let (_, patches) = adaptive(&shapes::cube(), &PatchOptions::new().max_isolation(2));
    let t = patches.table();
    let regular = &t.arrays[0];
    let mut checked = 0;
    for (k, p) in regular.params.iter().enumerate() {
        let scale = (1u32 << p.depth()) as f64;
        for (s, tt) in [(0.0, 0.0), (0.5, 0.5), (0.25, 0.75), (1.0, 0.3)] {
            // The location in the ptex face.
            let u = (p.u() as f64 + s) / scale;
            let v = (p.v() as f64 + tt) / scale;
            let w = patches
                .evaluate_basis(PatchHandle { array: 0, patch: k }, u, v, Derivatives::First)
                .unwrap();
            let ((bu, du), (bv, dv)) = (bspline(s), bspline(tt));
            for j in 0..4 {
                for i in 0..4 {
                    let n = 4 * j + i;
                    assert!((w.point[n] - bu[i] * bv[j]).abs() < 1e-15, "{p:?} {s} {tt}");
                    assert!((w.du[n] - scale * du[i] * bv[j]).abs() < 1e-14);
                    assert!((w.dv[n] - scale * bu[i] * dv[j]).abs() < 1e-14);
                }
            }
            checked += 1;
        }
    }
    assert_eq!(checked, 72 * 4);
}

/// At any location, the position weights sum to 1 and every derivative's
/// to 0, for every patch type the tables hold (regular, Gregory basis,
/// Loop, Gregory triangle, bilinear end caps).
#[test]
fn basis_is_a_partition_of_unity() {
    let cases = [
        (shapes::cube(), Scheme::Catmark, EndCapType::GregoryBasis),
        (shapes::pole(5), Scheme::Catmark, EndCapType::BilinearBasis),
        (
            shapes::icosahedron(),
            Scheme::Loop,
            EndCapType::GregoryBasis,
        ),
        (
            shapes::icosahedron(),
            Scheme::Loop,
            EndCapType::BSplineBasis,
        ),
    ];
    let mut types = std::collections::HashSet::new();
    for (mesh, scheme, caps) in cases {
        let options = PatchOptions::new().max_isolation(2).end_caps(caps);
        let mut r =
            osd::TopologyRefiner::new(&mesh, &Options::default().with_scheme(scheme)).unwrap();
        r.refine_adaptive(options.refine_adaptive_options(), &[])
            .unwrap();
        let patches = r.patch_table(&options, &[]).unwrap();
        for (a, array) in patches.table().arrays.iter().enumerate() {
            types.insert(array.patch_type);
            for (k, p) in array.params.iter().enumerate() {
                let scale = (1u32 << (p.depth() - p.non_quad_root() as u32)) as f64;
                let (u, v) = ((p.u() as f64 + 0.3) / scale, (p.v() as f64 + 0.2) / scale);
                let w = patches
                    .evaluate_basis(
                        PatchHandle { array: a, patch: k },
                        u,
                        v,
                        Derivatives::Second,
                    )
                    .unwrap();
                let sum = |x: &[f64]| x.iter().sum::<f64>();
                assert!(
                    (sum(&w.point) - 1.0).abs() < 1e-12,
                    "{:?}",
                    array.patch_type
                );
                for d in [&w.du, &w.dv, &w.duu, &w.duv, &w.dvv] {
                    assert!(sum(d).abs() < 1e-9, "{:?}: {}", array.patch_type, sum(d));
                }
            }
        }
    }
    for ty in [
        PatchType::Regular,
        PatchType::GregoryBasis,
        PatchType::Loop,
        PatchType::GregoryTriangle,
        PatchType::Quads,
    ] {
        assert!(types.contains(&ty), "{ty:?} not exercised");
    }
}

/// The limit surface at the corners of every base face is the limit
/// position of that base vertex: OpenSubdiv's patches (double-precision
/// local points) against the native engine's limit masks, on smooth closed
/// meshes with extraordinary vertices and n-gons (whose corner `k` is the
/// origin of ptex sub-face `k`). The native limit is taken after one
/// uniform level (at the vertex's child): `PrimvarRefiner::Limit`'s masks,
/// which the native engine reproduces, assume quads around the vertex, so
/// at level 0 they are off next to n-gons and triangles. Not on infinitely
/// sharp creases: Gregory end caps approximate the surface there (the dart
/// of a creased cube is 1.7% of its size off), as OpenSubdiv documents.
#[test]
fn face_corners_are_native_limit_positions() {
    for (name, mesh) in [
        ("cube", shapes::cube()),
        ("torus", shapes::torus(6, 4)),
        ("prism-5", shapes::prism(5)),
        ("pole-6", shapes::pole(6)),
    ] {
        let options = PatchOptions::new().max_isolation(4).double_precision(true);
        let (r, patches) = adaptive(&mesh, &options);
        let mut native = Refiner::new(&mesh, &Options::default()).unwrap();
        let ptex = subdiv::PtexIndices::new(&native).unwrap();
        native
            .refine_uniform(UniformOptions::new(1).full_topology(true))
            .unwrap();
        let base = mesh.flat_positions::<f64>();
        let mut locations = Vec::new();
        let mut expected_vertex = Vec::new();
        for (f, face) in mesh.faces().enumerate() {
            let first = ptex.face_id(f).unwrap();
            for (k, &v) in face.iter().enumerate() {
                locations.push(if face.len() == 4 {
                    let (u, v) = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)][k];
                    (first, u, v)
                } else {
                    (first + k as u32, 0.0, 0.0)
                });
                expected_vertex.push(v as usize);
            }
        }
        let samples = patches
            .evaluate(&r, 3, &base, &locations, Derivatives::None)
            .unwrap();
        let level1 = native.interpolate_all(3, &base).unwrap().pop().unwrap();
        let limit = native.limit_positions(3, &level1).unwrap();
        let child = native.child_maps(0).unwrap().vertex_child_vertex;
        for (i, &v) in expected_vertex.iter().enumerate() {
            let c1 = child[v] as usize;
            for c in 0..3 {
                let (a, b) = (samples.values.point[3 * i + c], limit[3 * c1 + c]);
                assert!((a - b).abs() < 1e-12, "{name}: vertex {v}: {a} vs {b}");
            }
        }
    }
}

/// Uniform tables: the last level's faces as bilinear quads over the base
/// vertices followed by the last level's (`includeBaseLevelIndices`, the
/// default: intermediate levels are not counted), or as triangles, two per
/// quad.
#[test]
fn uniform_tables_hold_the_last_level() {
    let cube = shapes::cube();
    let mut r = osd::TopologyRefiner::new(&cube, &Options::default()).unwrap();
    r.refine_uniform(UniformOptions::new(2)).unwrap();
    let patches = r.patch_table(&PatchOptions::new(), &[]).unwrap();
    let t = patches.table();
    assert!(!t.feature_adaptive);
    assert_eq!(t.arrays.len(), 1);
    assert_eq!(t.arrays[0].patch_type, PatchType::Quads);
    let level2 = r.level(2).unwrap();
    let offset = 8;
    let expected: Vec<u32> = level2.face_vertices.iter().map(|&v| v + offset).collect();
    assert_eq!(t.arrays[0].control_vertices, expected);
    let tri = PatchOptions {
        triangulate_quads: true,
        ..PatchOptions::new()
    };
    let t = r.patch_table(&tri, &[]).unwrap();
    assert_eq!(t.table().arrays[0].patch_type, PatchType::Triangles);
    assert_eq!(t.table().arrays[0].len(), 2 * 96);
}

/// Everything the bridge refuses, with the error that names it.
#[test]
fn refusals() {
    let mut cube = shapes::cube();
    cube.holes.push(5);
    let options = PatchOptions::new().max_isolation(2);
    let (r, patches) = adaptive(&cube, &options);
    assert!(matches!(
        r.patch_table(&PatchOptions::new().max_isolation(11), &[]),
        Err(Error::Level { level: 11, .. })
    ));
    let fvar = PatchOptions {
        fvar_tables: true,
        fvar_channels: vec![0],
        ..options.clone()
    };
    assert!(matches!(
        r.patch_table(&fvar, &[]),
        Err(Error::NoSuchChannel {
            channel: 0,
            count: 0
        })
    ));
    assert!(matches!(
        r.patch_table(&options, &[6]),
        Err(Error::NoSuchElement { index: 6, .. })
    ));
    assert!(matches!(
        patches.find_patch(6, 0.5, 0.5),
        Err(Error::NoSuchPtexFace { face: 6, count: 6 })
    ));
    for bad in [-0.1, 1.5, f64::NAN] {
        assert!(matches!(
            patches.find_patch(0, bad, 0.5),
            Err(Error::Location {
                coordinate: "u",
                ..
            })
        ));
    }
    // The hole has no patch.
    assert_eq!(patches.find_patch(5, 0.5, 0.5).unwrap(), None);
    let base = cube.flat_positions::<f64>();
    assert!(matches!(
        patches.evaluate(&r, 3, &base, &[(5, 0.5, 0.5)], Derivatives::None),
        Err(Error::NoPatchAt { face: 5, .. })
    ));
    assert!(
        patches
            .evaluate(&r, 3, &base[..21], &[(0, 0.5, 0.5)], Derivatives::None)
            .is_err()
    );
    let arrays = patches.table().arrays.len();
    assert!(matches!(
        patches.evaluate_basis(
            PatchHandle {
                array: arrays,
                patch: 0
            },
            0.5,
            0.5,
            Derivatives::None
        ),
        Err(Error::NoSuchPatch { .. })
    ));
    assert!(matches!(
        patches.evaluate_basis(
            PatchHandle {
                array: 0,
                patch: 10_000
            },
            0.5,
            0.5,
            Derivatives::None
        ),
        Err(Error::NoSuchPatch { patch: 10_000, .. })
    ));

    // Legacy Gregory patches: Catmull-Clark only, and no basis.
    let legacy = PatchOptions::new()
        .max_isolation(2)
        .end_caps(EndCapType::LegacyGregory);
    let (r, patches) = adaptive(&shapes::cube(), &legacy);
    let t = patches.table();
    let g = t
        .arrays
        .iter()
        .position(|a| a.patch_type == PatchType::Gregory)
        .expect("legacy Gregory patches");
    assert!(!t.quad_offsets.is_empty() && !t.vertex_valences.is_empty());
    assert!(matches!(
        patches.evaluate_basis(
            PatchHandle { array: g, patch: 0 },
            0.1,
            0.1,
            Derivatives::None
        ),
        Err(Error::Osd(_))
    ));
    drop(r);
    let mut r = osd::TopologyRefiner::new(
        &shapes::icosahedron(),
        &Options::default().with_scheme(Scheme::Loop),
    )
    .unwrap();
    r.refine_adaptive(legacy.refine_adaptive_options(), &[])
        .unwrap();
    assert!(matches!(r.patch_table(&legacy, &[]), Err(Error::Osd(_))));

    // A face that uses a vertex twice: OpenSubdiv's patch builders overrun.
    let mut degenerate = shapes::cube();
    degenerate.add_face(&[0, 1, 1, 2]);
    let mut r = osd::TopologyRefiner::new(&degenerate, &Options::default()).unwrap();
    r.refine_adaptive(options.refine_adaptive_options(), &[])
        .unwrap();
    assert!(matches!(
        r.patch_table(&options, &[]),
        Err(Error::Osd(subdiv::OsdError {
            kind: subdiv::OsdErrorKind::Unsafe,
            ..
        }))
    ));
    // Legacy Gregory end caps over a level that is not all quads (nothing
    // refined at isolation 0).
    let mut r = osd::TopologyRefiner::new(&shapes::pyramid(4), &Options::default()).unwrap();
    r.refine_adaptive(
        legacy.clone().max_isolation(0).refine_adaptive_options(),
        &[],
    )
    .unwrap();
    assert_eq!(r.max_level(), 0);
    assert!(matches!(
        r.patch_table(&legacy.clone().max_isolation(0), &[]),
        Err(Error::Osd(subdiv::OsdError {
            kind: subdiv::OsdErrorKind::Unsafe,
            ..
        }))
    ));

    // Legacy Gregory patches below the last level (a secondary level under
    // the isolation level leaves the crease's irregular patches at level 1).
    let mut creased = shapes::cube();
    creased.add_crease(0, 1, 10.0);
    let mut r = osd::TopologyRefiner::new(&creased, &Options::default()).unwrap();
    r.refine_adaptive(
        legacy
            .clone()
            .max_isolation(3)
            .refine_adaptive_options()
            .secondary(1),
        &[],
    )
    .unwrap();
    assert!(matches!(
        r.patch_table(&legacy.clone().max_isolation(3), &[]),
        Err(Error::Osd(subdiv::OsdError {
            kind: subdiv::OsdErrorKind::Unsafe,
            ..
        }))
    ));
    // The same options without the secondary level build the table.
    let mut r = osd::TopologyRefiner::new(&creased, &Options::default()).unwrap();
    r.refine_adaptive(
        legacy.clone().max_isolation(3).refine_adaptive_options(),
        &[],
    )
    .unwrap();
    assert!(r.patch_table(&legacy.clone().max_isolation(3), &[]).is_ok());

    // B-spline end caps around an interior vertex of valence 2 (two
    // triangles folded onto each other): refused; Gregory end caps build.
    let mut pillow = Mesh {
        positions: shapes::tetrahedron().positions,
        ..Mesh::default()
    };
    pillow.add_face(&[0, 1, 2]);
    pillow.add_face(&[2, 1, 0]);
    let bspline = PatchOptions::new()
        .max_isolation(2)
        .end_caps(EndCapType::BSplineBasis);
    let mut r = osd::TopologyRefiner::new(&pillow, &Options::default()).unwrap();
    r.refine_adaptive(bspline.refine_adaptive_options(), &[])
        .unwrap();
    assert!(matches!(
        r.patch_table(&bspline, &[]),
        Err(Error::Osd(subdiv::OsdError {
            kind: subdiv::OsdErrorKind::Unsafe,
            ..
        }))
    ));
    assert!(
        r.patch_table(&bspline.clone().end_caps(EndCapType::GregoryBasis), &[])
            .is_ok()
    );

    // Patches of a face adaptive refinement was not given are undefined.
    let mut r = osd::TopologyRefiner::new(&shapes::cube(), &Options::default()).unwrap();
    r.refine_adaptive(options.refine_adaptive_options(), &[0, 1])
        .unwrap();
    assert!(r.patch_table(&options, &[0]).is_ok());
    assert!(matches!(r.patch_table(&options, &[2]), Err(Error::Osd(_))));
}

/// The native basis (`patches::evaluate_basis`) against OpenSubdiv's
/// `EvaluateBasis<double>` on every patch of tables with regular B-spline
/// patches (boundary masks of every kind, single-crease and sharp-corner
/// patches), Gregory basis and bilinear end caps, uniform bilinear quads and
/// triangles, Loop box-spline patches (boundary edges and vertices) and
/// Gregory triangles, at locations inside, on the edges and at the corners
/// of each patch: every weight and derivative within 1e-12 of OpenSubdiv's
/// (relative to the derivative's 2^depth scale; the two differ only in
/// rounding: the same polynomials written differently).
#[test]
fn native_basis_matches_opensubdiv() {
    let mut grid = shapes::grid(3, 2);
    grid.add_crease(1, 2, 1.5);
    let mut creased = shapes::cube();
    creased.add_crease(0, 1, 2.5);
    let mut types = std::collections::HashSet::new();
    let mut loop_masks = std::collections::BTreeSet::new();
    let mut compared = 0;
    let mut check = |patches: &osd::OsdPatchTable| {
        for (a, array) in patches.table().arrays.iter().enumerate() {
            if !array.patch_type.is_evaluable() {
                continue;
            }
            types.insert(array.patch_type);
            for (k, p) in array.params.iter().enumerate() {
                if array.patch_type == PatchType::Loop {
                    loop_masks.insert(p.boundary());
                }
                let scale = (1u32 << (p.depth() - p.non_quad_root() as u32)) as f64;
                for (s, t) in [(0.0, 0.0), (1.0, 1.0), (0.5, 0.0), (0.3, 0.7), (0.9, 0.15)] {
                    let (u, v) = ((p.u() as f64 + s) / scale, (p.v() as f64 + t) / scale);
                    let (u, v) = (u.min(1.0), v.min(1.0));
                    let theirs = patches
                        .evaluate_basis(
                            PatchHandle { array: a, patch: k },
                            u,
                            v,
                            Derivatives::Second,
                        )
                        .unwrap();
                    let mine =
                        evaluate_basis(array.patch_type, *p, u, v, Derivatives::Second).unwrap();
                    let d = (1u32 << p.depth()) as f64;
                    for (name, x, y, unit) in [
                        ("point", &mine.point, &theirs.point, 1.0),
                        ("du", &mine.du, &theirs.du, d),
                        ("dv", &mine.dv, &theirs.dv, d),
                        ("duu", &mine.duu, &theirs.duu, d * d),
                        ("duv", &mine.duv, &theirs.duv, d * d),
                        ("dvv", &mine.dvv, &theirs.dvv, d * d),
                    ] {
                        assert_eq!(x.len(), y.len());
                        for (i, (a, b)) in x.iter().zip(y.iter()).enumerate() {
                            assert!(
                                (a - b).abs() <= 1e-12 * unit,
                                "{:?} {p:?} at ({u}, {v}): {name}[{i}] {a} vs {b}",
                                array.patch_type
                            );
                        }
                    }
                    compared += 1;
                }
            }
        }
    };
    for (mesh, options) in [
        (shapes::cube(), PatchOptions::new().max_isolation(3)),
        (
            creased.clone(),
            PatchOptions::new()
                .max_isolation(3)
                .single_crease_patch(true),
        ),
        (grid.clone(), PatchOptions::new().max_isolation(2)),
        (
            shapes::pole(5),
            PatchOptions::new()
                .max_isolation(2)
                .end_caps(EndCapType::BilinearBasis),
        ),
        (
            shapes::prism(5),
            PatchOptions::new()
                .max_isolation(2)
                .end_caps(EndCapType::BSplineBasis),
        ),
    ] {
        let mut r = osd::TopologyRefiner::new(&mesh, &Options::default()).unwrap();
        r.refine_adaptive(options.refine_adaptive_options(), &[])
            .unwrap();
        check(&r.patch_table(&options, &[]).unwrap());
    }
    // Loop tables: box-spline patches with boundary edges and vertices
    // (open triangle meshes, creases), Gregory triangles at extraordinary
    // vertices and as the B-spline end caps' Loop patches.
    let loop_options = Options::default()
        .with_scheme(Scheme::Loop)
        .with_boundary(subdiv::BoundaryInterpolation::EdgeAndCorner);
    // Regular triangular lattices (each cell split by the same diagonal):
    // 6 × 6 cells with a crease across, and a strip one cell high, whose
    // triangles have an edge on one boundary and the opposite vertex on the
    // other.
    let lattice = |nx: u32, ny: u32| {
        let mut mesh = Mesh::default();
        for j in 0..=ny {
            for i in 0..=nx {
                mesh.positions.push(glam::DVec3::new(
                    f64::from(i) + 0.5 * f64::from(j),
                    f64::from(j),
                    f64::from((i * j) % 3) * 0.2,
                ));
            }
        }
        let row = nx + 1;
        for j in 0..ny {
            for i in 0..nx {
                let v = j * row + i;
                mesh.add_face(&[v, v + 1, v + row + 1]);
                mesh.add_face(&[v, v + row + 1, v + row]);
            }
        }
        mesh
    };
    let mut creased = lattice(6, 6);
    creased.add_crease(9, 17, 2.0);
    for mesh in [
        shapes::icosahedron(),
        shapes::triangulate(&shapes::cube()),
        creased,
        lattice(8, 1),
        shapes::octahedron(),
        shapes::tetrahedron(),
    ] {
        for options in [
            PatchOptions::new().max_isolation(2),
            PatchOptions::new()
                .max_isolation(3)
                .end_caps(EndCapType::BSplineBasis),
        ] {
            let mut r = osd::TopologyRefiner::new(&mesh, &loop_options).unwrap();
            r.refine_adaptive(options.refine_adaptive_options(), &[])
                .unwrap();
            check(&r.patch_table(&options, &[]).unwrap());
        }
    }
    for tri in [false, true] {
        let mut r = osd::TopologyRefiner::new(&shapes::pole(5), &Options::default()).unwrap();
        r.refine_uniform(UniformOptions::new(2)).unwrap();
        let options = PatchOptions {
            triangulate_quads: tri,
            ..PatchOptions::new()
        };
        check(&r.patch_table(&options, &[]).unwrap());
    }
    for ty in [
        PatchType::Regular,
        PatchType::GregoryBasis,
        PatchType::Quads,
        PatchType::Triangles,
        PatchType::Loop,
        PatchType::GregoryTriangle,
    ] {
        assert!(types.contains(&ty), "{ty:?} not compared");
    }
    // Every kind of boundary mask of a Loop patch: edges, vertices, and
    // edges with the opposite vertex.
    for high in 0..3 {
        assert!(loop_masks.iter().any(|m| m >> 3 == high), "{loop_masks:?}");
    }
    assert!(compared > 1000, "{compared}");
    // What the native basis refuses.
    let p = subdiv::patches::PatchParam::default();
    assert!(matches!(
        evaluate_basis(PatchType::Gregory, p, 0.5, 0.5, Derivatives::None),
        Err(Error::NotYetSupported(_))
    ));
    assert!(matches!(
        evaluate_basis(PatchType::Regular, p, 1.5, 0.5, Derivatives::None),
        Err(Error::Location {
            coordinate: "u",
            ..
        })
    ));
}

/// The native `PatchMap` finds the patch OpenSubdiv's `FindPatch` finds, on
/// a grid of locations of every ptex face (multiples of 1/16, so 0, ½ and 1
/// and the edges between patches of every depth up to 4 included, where the
/// quadtree's ≥ decides), on quad and Loop tables, adaptive (non-quad roots,
/// holes, selected faces) and uniform.
#[test]
fn native_patch_map_matches_find_patch() {
    let mut holed = shapes::prism(5);
    holed.holes.push(2);
    let mut tables = Vec::new();
    for (mesh, scheme, options, faces) in [
        (
            shapes::cube(),
            Scheme::Catmark,
            PatchOptions::new().max_isolation(3),
            vec![],
        ),
        (
            holed,
            Scheme::Catmark,
            PatchOptions::new().max_isolation(2),
            vec![],
        ),
        (
            shapes::pole(5),
            Scheme::Catmark,
            PatchOptions::new().max_isolation(3),
            vec![0, 2],
        ),
        (
            shapes::icosahedron(),
            Scheme::Loop,
            PatchOptions::new().max_isolation(3),
            vec![],
        ),
        (
            shapes::tetrahedron(),
            Scheme::Loop,
            PatchOptions::new().max_isolation(2),
            vec![1],
        ),
    ] {
        let mut r =
            osd::TopologyRefiner::new(&mesh, &Options::default().with_scheme(scheme)).unwrap();
        r.refine_adaptive(options.refine_adaptive_options(), &faces)
            .unwrap();
        tables.push(r.patch_table(&options, &faces).unwrap());
    }
    for scheme in [Scheme::Catmark, Scheme::Loop] {
        let mesh = if scheme == Scheme::Loop {
            shapes::icosahedron()
        } else {
            shapes::pole(5)
        };
        let mut r =
            osd::TopologyRefiner::new(&mesh, &Options::default().with_scheme(scheme)).unwrap();
        r.refine_uniform(UniformOptions::new(2)).unwrap();
        tables.push(r.patch_table(&PatchOptions::new(), &[]).unwrap());
    }
    let mut found = 0;
    for patches in &tables {
        let map = PatchMap::new(patches.table());
        for face in 0..patches.table().ptex_faces as u32 {
            for i in 0..=16 {
                for j in 0..=16 {
                    let (u, v) = (i as f64 / 16.0, j as f64 / 16.0);
                    let theirs = patches.find_patch(face, u, v).unwrap();
                    assert_eq!(map.find_patch(face, u, v), theirs, "face {face} ({u}, {v})");
                    found += theirs.is_some() as usize;
                }
            }
        }
    }
    assert!(found > 10_000, "{found}");
}

/// `OsdPatchTable::evaluate_points` (one call, far tutorial 5_1's loop) over
/// the native engine's points gives OpenSubdiv's own evaluation bit for bit
/// (the refined points and local points are identical), the native
/// evaluation to 1e-12, and refuses what it cannot evaluate.
#[test]
fn evaluate_points_is_the_tutorial_loop() {
    use subdiv::patches;
    let mut mesh = shapes::cube();
    mesh.holes.push(4);
    let options = PatchOptions::new().max_isolation(3).double_precision(true);
    let native = Refiner::new(&mesh, &Options::default())
        .unwrap()
        .refine_adaptive(options.refine_adaptive_options(), &[])
        .unwrap();
    let (r, t) = {
        let mut r = osd::TopologyRefiner::new(&mesh, &Options::default()).unwrap();
        r.refine_adaptive(options.refine_adaptive_options(), &[])
            .unwrap();
        let t = r.patch_table(&options, &[]).unwrap();
        (r, t)
    };
    let table = native.patch_table(&options, &[]).unwrap();
    let base = mesh.flat_positions::<f64>();
    let points = native.patch_points(&table, 3, &base).unwrap();
    let locations: Vec<(u32, f64, f64)> = [0u32, 1, 2, 3, 5]
        .iter()
        .flat_map(|&f| [(f, 0.1, 0.9), (f, 0.5, 0.5), (f, 1.0, 0.0), (f, 0.75, 0.3)])
        .collect();
    for d in [Derivatives::None, Derivatives::First, Derivatives::Second] {
        let one_call = t.evaluate_points(&points, 3, &locations, d).unwrap();
        let per_location = t.evaluate(&r, 3, &base, &locations, d).unwrap();
        assert_eq!(one_call, per_location, "{d:?}");
        let mine = patches::evaluate(&table, &points, 3, &locations, d).unwrap();
        for (a, b) in [
            (&mine.values.point, &one_call.values.point),
            (&mine.values.du, &one_call.values.du),
            (&mine.values.dvv, &one_call.values.dvv),
        ] {
            assert_eq!(a.len(), b.len());
            assert!(a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12));
        }
    }
    // Face 4 is a hole: the error names the location.
    let e = t
        .evaluate_points(
            &points,
            3,
            &[(0, 0.5, 0.5), (4, 0.5, 0.5)],
            Derivatives::None,
        )
        .unwrap_err();
    assert!(e.to_string().contains("location 1 is in a hole"), "{e}");
    assert!(
        t.evaluate_points(&points, 3, &[(6, 0.5, 0.5)], Derivatives::None)
            .is_err()
    );
    assert!(
        t.evaluate_points(&points, 3, &[(0, 1.5, 0.5)], Derivatives::None)
            .is_err()
    );
    assert!(
        t.evaluate_points(&points[..30], 3, &locations, Derivatives::None)
            .is_err()
    );
    assert!(
        t.evaluate_points(&points, 0, &locations, Derivatives::None)
            .is_err()
    );
}
