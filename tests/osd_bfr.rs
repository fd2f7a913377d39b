//! OpenSubdiv's `Bfr::Tessellation` and `Bfr::Parameterization` through the
//! bridge: hand-derived patterns and coordinates, the rates OpenSubdiv
//! infers and clamps, the three facet transformations, batched
//! parameterization queries in both precisions, and every refusal before
//! OpenSubdiv sees the input.
#![cfg(feature = "osd")]

use subdiv::osd::bfr::{
    self, FacetTransform, MAX_COORDS, OsdParameterization, OsdTessellation, ParameterizationType,
};
use subdiv::{Error, OsdError, OsdErrorKind, Scheme};

fn tess(scheme: Scheme, n: usize, rates: &[i32], quads: bool, facet: usize) -> OsdTessellation {
    bfr::tessellate(scheme, n, rates, quads, facet)
        .unwrap_or_else(|e| panic!("{scheme} {n} {rates:?}: {e}"))
}

/// The error's kind, and its message containing `needle`.
fn refused<T: std::fmt::Debug>(r: subdiv::Result<T>, kind: OsdErrorKind, needle: &str) {
    match r {
        Err(Error::Osd(OsdError { kind: k, message })) => {
            assert_eq!(k, kind, "{message}");
            assert!(message.contains(needle), "{message:?} lacks {needle:?}");
        }
        other => panic!("expected a {kind:?} refusal mentioning {needle:?}, got {other:?}"),
    }
}

/// Twice the signed area of triangle (a, b, c).
fn area2(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
}

/// Every facet indexes existing coordinates (a 4-index triangle ends in
/// -1), every coordinate is used, and over a quad or triangle domain the
/// facets are counter-clockwise and tile it (total area 1 or 1/2).
fn check_facets(t: &OsdTessellation, domain_area: Option<f64>) {
    let n = t.num_coords() as i32;
    let mut used = vec![false; n as usize];
    let mut area = 0.0;
    for i in 0..t.num_facets() {
        let f = t.facet(i);
        let len = if t.facet_size == 4 && f[3] == -1 {
            3
        } else {
            t.facet_size
        };
        for &k in &f[..len] {
            assert!((0..n).contains(&k), "facet {i} {f:?}");
            used[k as usize] = true;
        }
        let c = |k: i32| t.coords_f64[k as usize];
        let mut a = area2(c(f[0]), c(f[1]), c(f[2]));
        if len == 4 {
            a += area2(c(f[0]), c(f[2]), c(f[3]));
        }
        if domain_area.is_some() {
            assert!(a > 0.0, "facet {i} {f:?} is not counter-clockwise");
        }
        area += a / 2.0;
    }
    assert!(used.iter().all(|&u| u), "a coordinate no facet uses");
    if let Some(expected) = domain_area {
        assert!((area - expected).abs() < 1e-12, "area {area}");
    }
}

/// The boundary is, edge after edge, the edge's first vertex then its edge
/// coordinates, bit for bit; f32 coordinates are the f64 ones to f32 accuracy.
fn check_boundary(t: &OsdTessellation) {
    let mut expected = Vec::new();
    for e in 0..t.face_size {
        expected.push(t.vertex_coords[e]);
        assert_eq!(t.edge_coords_f64[e].len(), t.num_edge_coords[e]);
        assert_eq!(t.edge_coords_f32[e].len(), t.num_edge_coords[e]);
        expected.extend_from_slice(&t.edge_coords_f64[e]);
        for (a, b) in t.edge_coords_f32[e].iter().zip(&t.edge_coords_f64[e]) {
            assert!((a[0] as f64 - b[0]).abs() < 1e-5 && (a[1] as f64 - b[1]).abs() < 1e-5);
        }
    }
    assert_eq!(&t.coords_f64[..t.num_boundary_coords], &expected[..]);
    assert_eq!(t.coords_f32.len(), t.coords_f64.len());
    for (a, b) in t.coords_f32.iter().zip(&t.coords_f64) {
        assert!((a[0] as f64 - b[0]).abs() < 1e-5 && (a[1] as f64 - b[1]).abs() < 1e-5);
    }
}

#[test]
fn quad_at_rate_2() {
    let t = tess(Scheme::Catmark, 4, &[2], false, 3);
    assert!(t.is_valid && t.is_uniform);
    assert_eq!(t.rates, vec![2]);
    assert_eq!((t.num_boundary_coords, t.num_interior_coords), (8, 1));
    let expected = [
        [0.0, 0.0],
        [0.5, 0.0],
        [1.0, 0.0],
        [1.0, 0.5],
        [1.0, 1.0],
        [0.5, 1.0],
        [0.0, 1.0],
        [0.0, 0.5],
        [0.5, 0.5],
    ];
    assert_eq!(t.coords_f64, expected);
    let expected32: Vec<[f32; 2]> = expected
        .iter()
        .map(|c| [c[0] as f32, c[1] as f32])
        .collect();
    assert_eq!(t.coords_f32, expected32);
    assert_eq!(t.num_edge_coords, vec![1; 4]);
    assert_eq!(
        t.edge_coords_f64,
        vec![
            vec![[0.5, 0.0]],
            vec![[1.0, 0.5]],
            vec![[0.5, 1.0]],
            vec![[0.0, 0.5]]
        ]
    );
    assert_eq!(
        t.vertex_coords,
        vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
    );
    // Four quads, each cut in two.
    assert_eq!((t.facet_size, t.num_facets()), (3, 8));
    check_facets(&t, Some(1.0));
    check_boundary(&t);

    // Quads kept: four of them, each with the centre.
    let q = tess(Scheme::Catmark, 4, &[2], true, 4);
    assert_eq!((q.facet_size, q.num_facets()), (4, 4));
    for i in 0..4 {
        assert!(
            q.facet(i).contains(&8) && !q.facet(i).contains(&-1),
            "{:?}",
            q.facet(i)
        );
    }
    check_facets(&q, Some(1.0));
    // Four-index facets without preserved quads: triangles padded with -1.
    let p = tess(Scheme::Catmark, 4, &[2], false, 4);
    assert_eq!(p.num_facets(), 8);
    for i in 0..8 {
        assert_eq!(p.facet(i)[..3], t.facet(i)[..]);
        assert_eq!(p.facet(i)[3], -1);
    }
    // Preserving quads needs 4-index facets: with 3 it is ignored.
    assert_eq!(tess(Scheme::Catmark, 4, &[2], true, 3), t);
}

#[test]
fn triangles_at_rate_1() {
    let t = tess(Scheme::Loop, 3, &[1], false, 3);
    assert!(t.is_valid && t.is_uniform);
    assert_eq!(t.coords_f64, vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
    assert_eq!((t.num_boundary_coords, t.num_interior_coords), (3, 0));
    assert_eq!(t.facets, vec![0, 1, 2]);
    assert_eq!(t.num_edge_coords, vec![0; 3]);
    assert_eq!(
        tess(Scheme::Loop, 3, &[1], true, 4).facets,
        vec![0, 1, 2, -1]
    );
    // A Catmull-Clark triangle (quad sub-faces) at rate 1 is one triangle too.
    let c = tess(Scheme::Catmark, 3, &[1], false, 3);
    assert_eq!(c.coords_f64, vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
    assert_eq!(c.facets, vec![0, 1, 2]);
}

#[test]
fn pentagon_at_rate_1_is_a_fan_around_the_centre() {
    let t = tess(Scheme::Catmark, 5, &[1], false, 3);
    assert_eq!((t.num_boundary_coords, t.num_interior_coords), (5, 1));
    // Sub-face grid 3 wide: vertex i at (i % 3, i / 3).
    assert_eq!(
        t.coords_f64,
        vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [0.0, 1.0],
            [1.0, 1.0],
            [0.5, 0.5]
        ]
    );
    assert_eq!(t.facets, vec![0, 1, 5, 1, 2, 5, 2, 3, 5, 3, 4, 5, 4, 0, 5]);
    check_facets(&t, None);
    check_boundary(&t);
}

#[test]
fn triangle_centre_is_computed_in_float() {
    // Rate 3: one interior coordinate, the centre, 1.0f / 3.0f in both.
    let t = tess(Scheme::Loop, 3, &[3], false, 3);
    assert_eq!((t.num_boundary_coords, t.num_interior_coords), (9, 1));
    let third = (1.0f32 / 3.0) as f64;
    assert_eq!(t.coords_f64[9], [third, third]);
    assert_ne!(third, 1.0 / 3.0);
    assert_eq!(t.num_facets(), 9);
    check_facets(&t, Some(0.5));
    check_boundary(&t);
}

#[test]
fn rates_inferred_and_clamped() {
    // Two inner rates of a quad: outer rates 3, 2, 3, 2.
    let t = tess(Scheme::Catmark, 4, &[3, 2], false, 3);
    assert!(!t.is_uniform);
    assert_eq!(t.rates, vec![3, 2]);
    assert_eq!(t.num_edge_coords, vec![2, 1, 2, 1]);
    assert_eq!((t.num_boundary_coords, t.num_interior_coords), (10, 2));
    check_facets(&t, Some(1.0));
    check_boundary(&t);
    // A 3 x 1 strip: no interior coordinate ("segmented").
    let s = tess(Scheme::Catmark, 4, &[3, 1, 3, 1], false, 3);
    assert_eq!(
        (s.num_boundary_coords, s.num_interior_coords, s.num_facets()),
        (8, 0, 6)
    );
    check_facets(&s, Some(1.0));
    // Two rates for a pentagon: one uniform rate, the second ignored, and
    // GetRates gives the first twice.
    let p = tess(Scheme::Catmark, 5, &[2, 7], false, 3);
    assert!(p.is_uniform);
    assert_eq!(p.rates, vec![2, 2]);
    assert_eq!(
        p,
        OsdTessellation {
            rates: vec![2, 2],
            ..tess(Scheme::Catmark, 5, &[2, 2], false, 3)
        }
    );
    // N + 2 rates for a pentagon: only a quad has two inner rates.
    let p = tess(Scheme::Catmark, 5, &[1, 1, 1, 1, 1, 3, 9], false, 3);
    assert_eq!(p.rates, vec![1, 1, 1, 1, 1, 3, 3]);
    // Rates are clamped to 32767: one long edge, a fan of its 32770
    // boundary coordinates around the centre.
    let c = tess(Scheme::Catmark, 4, &[40000, 1, 1, 1], false, 3);
    assert_eq!(c.rates, vec![32767, 1, 1, 1]);
    assert_eq!(
        (c.num_boundary_coords, c.num_interior_coords, c.num_facets()),
        (32770, 1, 32770)
    );
    check_facets(&c, Some(1.0));
}

#[test]
fn boundary_is_vertices_and_edge_coords_everywhere() {
    for (scheme, n) in [
        (Scheme::Catmark, 4),
        (Scheme::Bilinear, 4),
        (Scheme::Loop, 3),
        (Scheme::Catmark, 3),
        (Scheme::Catmark, 5),
        (Scheme::Bilinear, 7),
        (Scheme::Catmark, 11),
    ] {
        let mut cases: Vec<Vec<i32>> = (1..=9).map(|r| vec![r]).collect();
        cases.push((1..=n as i32).collect());
        cases.push((1..=n as i32).chain([4]).collect());
        cases.push((0..n as i32).map(|i| 5 - i % 3).chain([6]).collect());
        for rates in &cases {
            for (quads, facet) in [(false, 3), (true, 4), (false, 4)] {
                let t = tess(scheme, n, rates, quads, facet);
                assert!(t.is_valid);
                check_boundary(&t);
                let domain = match n {
                    4 if scheme != Scheme::Loop => Some(1.0),
                    3 if scheme == Scheme::Loop => Some(0.5),
                    _ => None,
                };
                check_facets(&t, domain);
            }
        }
    }
}

#[test]
fn invalid_faces_come_back_invalid() {
    let t = tess(Scheme::Loop, 4, &[2], false, 3);
    assert!(!t.is_valid);
    assert!(t.coords_f64.is_empty() && t.facets.is_empty() && t.rates.is_empty());
    assert_eq!(t.num_coords(), 0);
    assert!(
        bfr::transform_facets(Scheme::Loop, 5, &[2], false, 3, FacetTransform::Offset(1))
            .unwrap()
            .is_empty()
    );
    let p = OsdParameterization::new(Scheme::Loop, 4).unwrap();
    assert!(!p.is_valid && !p.has_sub_faces);
    refused(
        p.vertex_coords::<f64>(&[0]),
        OsdErrorKind::Refused,
        "invalid",
    );
    // Loop's non-triangles beyond 65025 are merely invalid.
    assert!(!tess(Scheme::Loop, 65030, &[1], false, 3).is_valid);
}

#[test]
fn facet_transformations() {
    let (scheme, n, rates) = (Scheme::Catmark, 4, [3, 2, 3, 4]);
    let t = tess(scheme, n, &rates, true, 4);
    let nb = t.num_boundary_coords;
    assert!(t.facets.contains(&-1), "some triangles among the quads");
    let map = |f: &dyn Fn(i32) -> i32| -> Vec<i32> {
        t.facets
            .iter()
            .map(|&k| if k < 0 { k } else { f(k) })
            .collect()
    };
    let run = |x| bfr::transform_facets(scheme, n, &rates, true, 4, x).unwrap();
    assert_eq!(run(FacetTransform::Offset(100)), map(&|k| k + 100));
    let boundary: Vec<i32> = (0..nb as i32).map(|i| 1000 - i).collect();
    let interior: Vec<i32> = (0..t.num_interior_coords as i32)
        .map(|i| 7 * i + 5000)
        .collect();
    assert_eq!(
        run(FacetTransform::BoundaryOffset {
            boundary: &boundary,
            interior_offset: 50
        }),
        map(&|k| if (k as usize) < nb {
            boundary[k as usize]
        } else {
            k + 50
        })
    );
    assert_eq!(
        run(FacetTransform::BoundaryInterior {
            boundary: &boundary,
            interior: &interior
        }),
        map(&|k| if (k as usize) < nb {
            boundary[k as usize]
        } else {
            interior[k as usize - nb]
        })
    );
    // Three-index facets: every index transformed.
    let f = bfr::transform_facets(Scheme::Loop, 3, &[1], false, 3, FacetTransform::Offset(-3));
    assert_eq!(f.unwrap(), vec![-3, -2, -1]);
    // Refusals: maps of the wrong length, offsets that overflow.
    let short = &boundary[1..];
    refused(
        bfr::transform_facets(
            scheme,
            n,
            &rates,
            true,
            4,
            FacetTransform::BoundaryOffset {
                boundary: short,
                interior_offset: 0,
            },
        ),
        OsdErrorKind::Refused,
        "boundary index map",
    );
    refused(
        bfr::transform_facets(
            scheme,
            n,
            &rates,
            true,
            4,
            FacetTransform::BoundaryInterior {
                boundary: &boundary,
                interior: &[],
            },
        ),
        OsdErrorKind::Refused,
        "interior index map",
    );
    refused(
        bfr::transform_facets(
            scheme,
            n,
            &rates,
            true,
            4,
            FacetTransform::Offset(i32::MAX - 5),
        ),
        OsdErrorKind::Unsafe,
        "overflows",
    );
    let last = t.num_coords() as i32 - 1;
    assert!(
        bfr::transform_facets(
            scheme,
            n,
            &rates,
            true,
            4,
            FacetTransform::Offset(i32::MAX - last)
        )
        .is_ok()
    );
}

#[test]
fn parameterizations_by_hand() {
    let quad = OsdParameterization::new(Scheme::Catmark, 4).unwrap();
    assert!(quad.is_valid && !quad.has_sub_faces);
    assert_eq!(quad.kind, ParameterizationType::Quad);
    assert_eq!(
        quad.vertex_coords::<f64>(&[0, 1, 2, 3]).unwrap(),
        vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
    );
    assert_eq!(
        quad.edge_coords(&[(2, 0.25f64), (3, 0.25)]).unwrap(),
        vec![[0.75, 1.0], [0.0, 0.75]]
    );
    assert_eq!(quad.center_coord::<f32>().unwrap(), [0.5, 0.5]);
    assert_eq!(quad.sub_faces(&[[0.9f64, 0.9]]).unwrap(), vec![0]);

    let tri = OsdParameterization::new(Scheme::Loop, 3).unwrap();
    assert_eq!(tri.kind, ParameterizationType::Triangle);
    assert_eq!(
        tri.edge_coords(&[(1, 0.25f64)]).unwrap(),
        vec![[0.75, 0.25]]
    );
    let third = (1.0f32 / 3.0) as f64;
    assert_eq!(tri.center_coord::<f64>().unwrap(), [third, third]);

    // A pentagon: five quad sub-faces on a grid 3 wide.
    let p = OsdParameterization::new(Scheme::Catmark, 5).unwrap();
    assert!(p.is_valid && p.has_sub_faces);
    assert_eq!(p.kind, ParameterizationType::QuadSubfaces);
    let verts = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [0.0, 1.0], [1.0, 1.0]];
    assert_eq!(p.vertex_coords::<f64>(&[0, 1, 2, 3, 4]).unwrap(), verts);
    assert_eq!(p.vertex_coords::<f32>(&[4]).unwrap(), vec![[1.0f32, 1.0]]);
    // Along an edge: away from vertex i up to the middle, then down into vertex i + 1's sub-face.
    assert_eq!(
        p.edge_coords(&[(0, 0.25f64), (0, 0.75), (4, 0.75)])
            .unwrap(),
        vec![[0.25, 0.0], [1.0, 0.25], [0.0, 0.25]]
    );
    assert_eq!(
        p.sub_faces(&[
            [0.25f64, 0.25],
            [1.25, 0.25],
            [2.3, 0.4],
            [0.2, 1.3],
            [1.1, 1.1],
            [0.9, 0.1]
        ])
        .unwrap(),
        vec![0, 1, 2, 3, 4, 1]
    );
    assert_eq!(
        p.coords_to_sub_faces(&[[1.25f64, 0.375]], true).unwrap(),
        vec![(1, [0.5, 0.75])]
    );
    assert_eq!(
        p.coords_to_sub_faces(&[[1.25f64, 0.375]], false).unwrap(),
        vec![(1, [0.25, 0.375])]
    );
    // Slightly left of sub-face 1: its tile, a negative local u.
    let (f, [u, v]) = p.coords_to_sub_faces(&[[0.875f64, 0.125]], false).unwrap()[0];
    assert_eq!((f, u, v), (1, -0.125, 0.125));
    assert_eq!(
        p.sub_faces_to_coords(&[(3, [0.5f64, 1.0])], true).unwrap(),
        vec![[0.25, 1.5]]
    );
    assert_eq!(
        p.sub_faces_to_coords(&[(3, [0.5f32, 1.0])], false).unwrap(),
        vec![[0.5f32, 2.0]]
    );

    // Thousands of points in one call, round trips in both precisions.
    let pts: Vec<[f64; 2]> = (0..5000)
        .map(|i| {
            let s = i % 5;
            let (a, b) = ((i / 5 % 31) as f64 / 64.0, (i / 155 % 31) as f64 / 64.0);
            [verts[s][0] + a, verts[s][1] + b]
        })
        .collect();
    let subs = p.coords_to_sub_faces(&pts, true).unwrap();
    for (i, &(s, _)) in subs.iter().enumerate() {
        assert_eq!(s, (i % 5) as i32);
    }
    let back: Vec<(usize, [f64; 2])> = subs.iter().map(|&(s, uv)| (s as usize, uv)).collect();
    assert_eq!(p.sub_faces_to_coords(&back, true).unwrap(), pts);
    let pts32: Vec<[f32; 2]> = pts.iter().map(|c| [c[0] as f32, c[1] as f32]).collect();
    let subs32 = p.coords_to_sub_faces(&pts32, false).unwrap();
    let back32: Vec<(usize, [f32; 2])> = subs32.iter().map(|&(s, uv)| (s as usize, uv)).collect();
    assert_eq!(p.sub_faces_to_coords(&back32, false).unwrap(), pts32);

    // The largest face a quad scheme parameterizes safely: a grid 255 wide.
    let big = OsdParameterization::new(Scheme::Catmark, 65025).unwrap();
    assert!(big.is_valid);
    assert_eq!(
        big.vertex_coords::<f64>(&[65024]).unwrap(),
        vec![[254.0, 254.0]]
    );
}

#[test]
fn refusals() {
    use OsdErrorKind::{Refused, Unsafe};
    let q = |n, rates: &[i32], facet| bfr::tessellate(Scheme::Catmark, n, rates, false, facet);
    refused(q(4, &[0], 3), Refused, "rate 0 is 0");
    refused(q(4, &[2, 2, -1, 2], 3), Refused, "rate 2 is -1");
    refused(q(2, &[1], 3), Refused, "face size 2");
    refused(q(70000, &[1], 3), Refused, "face size 70000");
    refused(q(4, &[], 3), Refused, "0 rates");
    refused(q(4, &[1; 7], 3), Refused, "7 rates");
    refused(q(4, &[1], 5), Refused, "facet size 5");
    // A quad at 10^6 (clamped to 32767): about 2^30 coordinates.
    refused(q(4, &[1_000_000], 3), Refused, "coordinates");
    refused(q(4, &[i32::MAX], 3), Refused, "coordinates");
    // Inner rates drive the interior: one large inner rate suffices.
    refused(q(4, &[1, 1, 1, 1, 20000], 3), Refused, "coordinates");
    // A large polygon at a modest rate.
    refused(q(60000, &[40], 3), Refused, "coordinates");
    // Just inside the bound: a quad at rate 4095 has 4096^2 coordinates.
    let t = q(4, &[4095], 3).unwrap();
    assert_eq!(t.num_coords(), 4096 * 4096);
    assert!(t.num_coords() <= MAX_COORDS);
    refused(q(4, &[4096], 3), Refused, "coordinates");
    // The sub-face grid width wraps to 0 in its unsigned char.
    refused(q(65026, &[1], 3), Unsafe, "unsigned char");
    refused(
        OsdParameterization::new(Scheme::Bilinear, 65535),
        Unsafe,
        "unsigned char",
    );
    refused(
        OsdParameterization::new(Scheme::Catmark, 1),
        Refused,
        "face size 1",
    );

    let p = OsdParameterization::new(Scheme::Catmark, 5).unwrap();
    refused(
        p.vertex_coords::<f64>(&[5]),
        Refused,
        "vertex 5 does not exist",
    );
    refused(
        p.edge_coords(&[(0, 0.5f64), (7, 0.5)]),
        Refused,
        "query 1: edge 7",
    );
    refused(p.edge_coords(&[(0, f64::NAN)]), Refused, "not finite");
    refused(p.sub_faces(&[[1e9f64, 0.0]]), Refused, "beyond");
    refused(
        p.sub_faces_to_coords(&[(5, [0.0f32, 0.0])], true),
        Refused,
        "sub-face 5",
    );
    let quad = OsdParameterization::new(Scheme::Catmark, 4).unwrap();
    refused(
        quad.coords_to_sub_faces(&[[0.5f64, 0.5]], false),
        Refused,
        "no sub-faces",
    );
    refused(
        quad.sub_faces_to_coords(&[(0, [0.5f64, 0.5])], true),
        Refused,
        "no sub-faces",
    );
}
