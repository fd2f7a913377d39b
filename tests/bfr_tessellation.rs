//! Native `bfr::Tessellation` and `bfr::Parameterization` against
//! OpenSubdiv's `Bfr` through the bridge, pattern by pattern: faces of 3 to
//! 8 sides (and larger n-gons) under every scheme, uniform rates 1-16 and
//! random rate sets of every accepted count (1, 2, N, N+1, N+2), triangles,
//! 4-index facets and kept quads — identical rates, uniformity, counts,
//! coordinates bit for bit in `f32` and `f64`, facets index by index, edge
//! and vertex coordinates, and the three facet transformations; sub-face
//! conversions bit for bit.
#![cfg(feature = "osd")]

use subdiv::Scheme;
use subdiv::bfr::{CoordIndexMap, FacetSize, Parameterization, Tessellation, TessellationOptions};
use subdiv::osd::bfr::{self as osd_bfr, FacetTransform, OsdParameterization};

/// A small deterministic generator (xorshift).
struct Rng(u64);
impl Rng {
    fn below(&mut self, n: u32) -> u32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 % u64::from(n)) as u32
    }
}

/// Uniform rates 1..=16 and random sets of every accepted count.
fn rate_sets(n: usize, rng: &mut Rng) -> Vec<Vec<u32>> {
    let mut sets: Vec<Vec<u32>> = (1..=16).map(|r| vec![r]).collect();
    for _ in 0..40 {
        let count = match rng.below(5) {
            0 => 2,
            1 => n + 1,
            2 => n + 2,
            _ => n,
        };
        let top = [2, 4, 9, 16][rng.below(4) as usize];
        sets.push((0..count).map(|_| 1 + rng.below(top)).collect());
    }
    // Edge rates equal but for one, and a uniform set given per edge.
    sets.push((0..n).map(|i| if i == 1 { 5 } else { 4 }).collect());
    sets.push(vec![6; n + 1]);
    sets
}

const OPTIONS: [(FacetSize, bool); 3] = [
    (FacetSize::Three, false),
    (FacetSize::Four, false),
    (FacetSize::Four, true),
];

fn compare(scheme: Scheme, n: usize, rates: &[u32], size: FacetSize, quads: bool) {
    let label = format!("{scheme} {n}-gon, rates {rates:?}, {size:?}, quads {quads}");
    let irates: Vec<i32> = rates.iter().map(|&r| r as i32).collect();
    let theirs = osd_bfr::tessellate(scheme, n, &irates, quads, size.indices())
        .unwrap_or_else(|e| panic!("{label}: {e}"));
    let param = Parameterization::new(scheme, n);
    if !theirs.is_valid {
        assert!(param.is_err(), "{label}: OpenSubdiv finds it invalid");
        return;
    }
    let options = TessellationOptions {
        preserve_quads: quads,
        facet_size: size,
    };
    let ours = Tessellation::new(param.unwrap(), rates, options).unwrap();
    let our_rates: Vec<i32> = ours.rates().iter().map(|&r| r as i32).collect();
    assert_eq!(our_rates, theirs.rates, "{label}: rates");
    assert_eq!(ours.is_uniform(), theirs.is_uniform, "{label}: uniform");
    assert_eq!(
        ours.num_boundary_coords(),
        theirs.num_boundary_coords,
        "{label}"
    );
    assert_eq!(
        ours.num_interior_coords(),
        theirs.num_interior_coords,
        "{label}"
    );
    assert_eq!(
        ours.coords::<f64>().unwrap(),
        theirs.coords_f64,
        "{label}: f64 coords"
    );
    assert_eq!(
        ours.coords::<f32>().unwrap(),
        theirs.coords_f32,
        "{label}: f32 coords"
    );
    let facets = ours.facets().unwrap();
    assert_eq!(ours.facet_size(), theirs.facet_size, "{label}");
    assert_eq!(
        ours.num_facets(),
        facets.len() / ours.facet_size(),
        "{label}: count"
    );
    assert_eq!(facets, theirs.facets, "{label}: facets");
    for e in 0..n {
        assert_eq!(ours.num_edge_coords(e).unwrap(), theirs.num_edge_coords[e]);
        assert_eq!(
            ours.edge_coords::<f64>(e).unwrap(),
            theirs.edge_coords_f64[e],
            "{label}: edge {e}"
        );
        assert_eq!(
            ours.edge_coords::<f32>(e).unwrap(),
            theirs.edge_coords_f32[e],
            "{label}: edge {e}"
        );
        assert_eq!(
            ours.vertex_coord::<f64>(e).unwrap(),
            theirs.vertex_coords[e],
            "{label}: vertex {e}"
        );
    }
}

#[test]
fn patterns_equal_opensubdiv_for_every_face_size_rate_and_facet_option() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut cases = 0;
    for (scheme, sizes) in [
        (Scheme::Catmark, vec![3, 4, 5, 6, 7, 8, 13]),
        (Scheme::Bilinear, vec![4, 5]),
        (Scheme::Loop, vec![3, 4]),
    ] {
        for n in sizes {
            for rates in rate_sets(n, &mut rng) {
                for (size, quads) in OPTIONS {
                    compare(scheme, n, &rates, size, quads);
                    cases += 1;
                }
            }
        }
    }
    assert!(cases > 1500, "{cases}");
}

#[test]
fn facet_transformations_equal_opensubdiv() {
    for (n, rates) in [(4, vec![3, 5, 2, 7]), (5, vec![4]), (3, vec![2, 6, 3, 5])] {
        for (size, quads) in OPTIONS {
            let p = Parameterization::new(Scheme::Catmark, n).unwrap();
            let options = TessellationOptions {
                preserve_quads: quads,
                facet_size: size,
            };
            let t = Tessellation::new(p, &rates, options).unwrap();
            let irates: Vec<i32> = rates.iter().map(|&r| r as i32).collect();
            let nb = t.num_boundary_coords() as i32;
            let boundary: Vec<i32> = (0..nb).map(|i| 900 - 2 * i).collect();
            let interior: Vec<i32> = (0..t.num_interior_coords() as i32)
                .map(|i| 10_000 + i * i)
                .collect();
            let maps = [
                (CoordIndexMap::Offset(42), FacetTransform::Offset(42)),
                (
                    CoordIndexMap::Boundary {
                        boundary: &boundary,
                        interior_offset: -3,
                    },
                    FacetTransform::BoundaryOffset {
                        boundary: &boundary,
                        interior_offset: -3,
                    },
                ),
                (
                    CoordIndexMap::Explicit {
                        boundary: &boundary,
                        interior: &interior,
                    },
                    FacetTransform::BoundaryInterior {
                        boundary: &boundary,
                        interior: &interior,
                    },
                ),
            ];
            for (ours, theirs) in maps {
                let mut facets = t.facets().unwrap();
                t.transform_facet_coord_indices(&mut facets, ours).unwrap();
                let expected = osd_bfr::transform_facets(
                    Scheme::Catmark,
                    n,
                    &irates,
                    quads,
                    size.indices(),
                    theirs,
                )
                .unwrap();
                assert_eq!(facets, expected, "{n}-gon {rates:?} {size:?} {quads}");
            }
        }
    }
}

#[test]
fn parameterizations_equal_opensubdiv_bit_for_bit() {
    let mut rng = Rng(12345);
    for (scheme, n) in [
        (Scheme::Catmark, 3),
        (Scheme::Catmark, 4),
        (Scheme::Catmark, 5),
        (Scheme::Catmark, 7),
        (Scheme::Bilinear, 12),
        (Scheme::Catmark, 40),
        (Scheme::Loop, 3),
    ] {
        let ours = Parameterization::new(scheme, n).unwrap();
        let theirs = OsdParameterization::new(scheme, n).unwrap();
        assert_eq!(ours.kind(), theirs.kind, "{scheme} {n}");
        assert_eq!(ours.has_subfaces(), theirs.has_sub_faces);
        let vertices: Vec<usize> = (0..n).collect();
        let ours_v: Vec<[f64; 2]> = vertices.iter().map(|&v| ours.vertex_coord(v)).collect();
        assert_eq!(ours_v, theirs.vertex_coords::<f64>(&vertices).unwrap());
        let edges: Vec<(usize, f32)> = (0..200)
            .map(|_| {
                (
                    rng.below(n as u32) as usize,
                    rng.below(1001) as f32 / 1000.0,
                )
            })
            .collect();
        let ours_e: Vec<[f32; 2]> = edges.iter().map(|&(e, t)| ours.edge_coord(e, t)).collect();
        assert_eq!(
            ours_e,
            theirs.edge_coords::<f32>(&edges).unwrap(),
            "{scheme} {n}"
        );
        assert_eq!(
            ours.center_coord::<f64>(),
            theirs.center_coord::<f64>().unwrap()
        );
        assert_eq!(
            ours.center_coord::<f32>(),
            theirs.center_coord::<f32>().unwrap()
        );
        if !ours.has_subfaces() {
            continue;
        }
        // Points on the face: a random sub-face and a point inside it.
        let inside: Vec<[f64; 2]> = (0..300)
            .map(|_| {
                let sub = rng.below(n as u32) as usize;
                let s = [
                    rng.below(1001) as f64 / 1000.0,
                    rng.below(1001) as f64 / 1000.0,
                ];
                ours.subface_to_coord(sub, s, true).unwrap()
            })
            .collect();
        let subs: Vec<i32> = inside.iter().map(|&uv| ours.subface(uv) as i32).collect();
        assert_eq!(subs, theirs.sub_faces(&inside).unwrap(), "{n}");
        for normalized in [false, true] {
            let ours_c: Vec<(i32, [f64; 2])> = inside
                .iter()
                .map(|&uv| {
                    let (s, c) = ours.coord_to_subface(uv, normalized).unwrap();
                    (s as i32, c)
                })
                .collect();
            assert_eq!(
                ours_c,
                theirs.coords_to_sub_faces(&inside, normalized).unwrap()
            );
            let back: Vec<(usize, [f64; 2])> =
                ours_c.iter().map(|&(s, c)| (s as usize, c)).collect();
            let ours_b: Vec<[f64; 2]> = back
                .iter()
                .map(|&(s, c)| ours.subface_to_coord(s, c, normalized).unwrap())
                .collect();
            assert_eq!(
                ours_b,
                theirs.sub_faces_to_coords(&back, normalized).unwrap()
            );
        }
    }
}
