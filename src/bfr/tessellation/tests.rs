//! The patterns' own properties, without OpenSubdiv (which
//! `tests/bfr_tessellation.rs` compares them with): hand-derived small
//! patterns, and over every face size, uniform and random edge rates, both
//! facet sizes: facets in range and using every coordinate, every boundary
//! segment on exactly one facet and every other edge on two facets in
//! opposite directions (a watertight, consistently oriented disc), the
//! facets' (u, v) areas summing to the domain's, and the edge coordinates
//! equal to the boundary's bit for bit.

use super::*;
use crate::bfr::MAX_FACE_SIZE;
use crate::options::Scheme;
use std::collections::HashMap;

fn opts(size: FacetSize, preserve_quads: bool) -> TessellationOptions {
    TessellationOptions {
        preserve_quads,
        facet_size: size,
    }
}

#[test]
fn a_quad_at_rate_two_by_hand() {
    let p = Parameterization::new(Scheme::Catmark, 4).unwrap();
    let t = Tessellation::uniform(p, 2, TessellationOptions::default()).unwrap();
    let coords = t.coords::<f64>().unwrap();
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
    assert_eq!(coords, expected);
    // One quad per corner, split along the diagonal from its first corner.
    let facets = t.facets().unwrap();
    assert_eq!(
        facets,
        [
            0, 1, 8, 8, 7, 0, 2, 3, 8, 8, 1, 2, 4, 5, 8, 8, 3, 4, 6, 7, 8, 8, 5, 6
        ]
    );
    let q = Tessellation::uniform(p, 2, opts(FacetSize::Four, true)).unwrap();
    assert_eq!(
        q.facets().unwrap(),
        [0, 1, 8, 7, 2, 3, 8, 1, 4, 5, 8, 3, 6, 7, 8, 5]
    );
    // Rate 1: the quad itself, or two triangles.
    let one = Tessellation::uniform(p, 1, opts(FacetSize::Four, true)).unwrap();
    assert_eq!(one.facets().unwrap(), [0, 1, 2, 3]);
    let one = Tessellation::uniform(p, 1, opts(FacetSize::Four, false)).unwrap();
    assert_eq!(one.facets().unwrap(), [0, 1, 2, -1, 2, 3, 0, -1]);
}

#[test]
fn a_pentagon_at_rate_one_is_a_fan_and_rates_are_inferred() {
    let p = Parameterization::new(Scheme::Catmark, 5).unwrap();
    let t = Tessellation::uniform(p, 1, TessellationOptions::default()).unwrap();
    assert_eq!((t.num_boundary_coords(), t.num_interior_coords()), (5, 1));
    // Sub-face corners: tiles 3 wide.
    let c = t.coords::<f64>().unwrap();
    assert_eq!(
        c,
        [
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [0.0, 1.0],
            [1.0, 1.0],
            [0.5, 0.5]
        ]
    );
    assert_eq!(
        t.facets().unwrap(),
        [0, 1, 5, 1, 2, 5, 2, 3, 5, 3, 4, 5, 4, 0, 5]
    );
    // Five edge rates: the inner rate is their mean, rounded down.
    let t = Tessellation::new(p, &[1, 2, 3, 4, 6], TessellationOptions::default()).unwrap();
    assert_eq!(t.inner_rates(), [3, 3]);
    assert!(!t.is_uniform());
    assert_eq!(t.rates(), [1, 2, 3, 4, 6]);
    // A quad's inner rates average opposite edges; two rates are inner ones.
    let q = Parameterization::new(Scheme::Catmark, 4).unwrap();
    let t = Tessellation::new(q, &[2, 3, 5, 8], TessellationOptions::default()).unwrap();
    assert_eq!(t.inner_rates(), [3, 5]);
    let t = Tessellation::new(q, &[4, 1], TessellationOptions::default()).unwrap();
    assert_eq!(t.edge_rates(), [4, 1, 4, 1]);
    assert_eq!((t.num_interior_coords(), t.num_facets()), (0, 8));
    let t = Tessellation::new(q, &[3, 3, 3, 3, 5, 7], TessellationOptions::default()).unwrap();
    assert_eq!(
        (t.inner_rates(), t.rates()),
        ([5, 7], vec![3, 3, 3, 3, 5, 7])
    );
    // Clamped like OpenSubdiv's.
    let t = Tessellation::uniform(q, 100_000, TessellationOptions::default()).unwrap();
    assert_eq!(t.rates(), [MAX_RATE]);
}

#[test]
fn refusals() {
    let q = Parameterization::new(Scheme::Catmark, 4).unwrap();
    let o = TessellationOptions::default();
    assert!(matches!(
        Tessellation::new(q, &[], o),
        Err(Error::Tessellation { .. })
    ));
    assert!(matches!(
        Tessellation::new(q, &[2, 0, 2, 2], o),
        Err(Error::Tessellation { .. })
    ));
    let big = Parameterization::new(Scheme::Catmark, MAX_FACE_SIZE).unwrap();
    let e = Tessellation::uniform(big, MAX_RATE, o).unwrap_err();
    assert!(e.to_string().contains("32-bit"), "{e}");
    assert!(Parameterization::new(Scheme::Catmark, 2).is_err());
    assert!(Parameterization::new(Scheme::Loop, 5).is_err());
    assert!(Parameterization::new(Scheme::Bilinear, MAX_FACE_SIZE + 1).is_err());
    let t = Tessellation::uniform(q, 3, o).unwrap();
    assert!(t.edge_coords::<f64>(4).is_err());
    let mut f = t.facets().unwrap();
    let before = f.clone();
    let short = vec![0; t.num_boundary_coords() - 1];
    let map = CoordIndexMap::Boundary {
        boundary: &short,
        interior_offset: 0,
    };
    assert!(t.transform_facet_coord_indices(&mut f, map).is_err());
    assert!(
        t.transform_facet_coord_indices(&mut f, CoordIndexMap::Offset(i32::MAX))
            .is_err()
    );
    assert_eq!(f, before);
}

#[test]
fn transforms_renumber_boundary_and_interior() {
    let p = Parameterization::new(Scheme::Catmark, 6).unwrap();
    let t = Tessellation::new(p, &[2, 3, 4, 5, 1, 2], opts(FacetSize::Four, true)).unwrap();
    let f = t.facets().unwrap();
    let nb = t.num_boundary_coords() as i32;
    let boundary: Vec<i32> = (0..nb).map(|i| 1000 - i).collect();
    let interior: Vec<i32> = (0..t.num_interior_coords() as i32)
        .map(|i| 5000 + 3 * i)
        .collect();
    let expect = |i: i32, inner: &dyn Fn(i32) -> i32| match i {
        -1 => -1,
        i if i < nb => 1000 - i,
        i => inner(i),
    };
    let mut a = f.clone();
    t.transform_facet_coord_indices(&mut a, CoordIndexMap::Offset(7))
        .unwrap();
    assert!(
        a.iter()
            .zip(&f)
            .all(|(&x, &y)| if y < 0 { x == -1 } else { x == y + 7 })
    );
    let mut b = f.clone();
    let map = CoordIndexMap::Boundary {
        boundary: &boundary,
        interior_offset: 10,
    };
    t.transform_facet_coord_indices(&mut b, map).unwrap();
    assert!(b.iter().zip(&f).all(|(&x, &y)| x == expect(y, &|i| i + 10)));
    let mut c = f.clone();
    let map = CoordIndexMap::Explicit {
        boundary: &boundary,
        interior: &interior,
    };
    t.transform_facet_coord_indices(&mut c, map).unwrap();
    assert!(
        c.iter()
            .zip(&f)
            .all(|(&x, &y)| x == expect(y, &|i| 5000 + 3 * (i - nb)))
    );
    assert!(f.contains(&-1) && f.iter().any(|&i| i >= nb));
}

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

/// Every rate set the tests sweep for an `n`-sided face.
fn rate_sets(n: usize, seed: u64) -> Vec<Vec<u32>> {
    let mut sets: Vec<Vec<u32>> = (1..=16).map(|r| vec![r]).collect();
    let mut rng = Rng(seed | 1);
    for _ in 0..60 {
        let count = match rng.below(5) {
            0 => n,
            1 => n + 1,
            2 if n == 4 => 2,
            3 if n == 4 => 6,
            _ => n,
        };
        let top = if rng.below(4) == 0 { 3 } else { 12 };
        sets.push((0..count).map(|_| 1 + rng.below(top)).collect());
    }
    sets
}

/// Checks the pattern's topology and, for the square and triangle, its area.
fn check(t: &Tessellation) {
    let label = format!("{t:?}");
    let size = t.facet_size();
    let facets = t.facets().unwrap();
    assert_eq!(facets.len(), t.num_facets() * size, "{label}");
    let coords = t.coords::<f64>().unwrap();
    assert_eq!(coords.len(), t.num_coords(), "{label}");
    let mut used = vec![false; coords.len()];
    let mut edges: HashMap<(i32, i32), i32> = HashMap::new();
    let mut area = 0.0;
    for f in facets.chunks(size) {
        let corners: Vec<i32> = f.iter().copied().filter(|&i| i >= 0).collect();
        assert!(corners.len() >= 3, "{label}: {f:?}");
        for (k, &i) in corners.iter().enumerate() {
            assert!((i as usize) < coords.len(), "{label}: {f:?}");
            used[i as usize] = true;
            let j = corners[(k + 1) % corners.len()];
            *edges.entry((i, j)).or_default() += 1;
            let ([u0, v0], [u1, v1]) = (coords[i as usize], coords[j as usize]);
            area += 0.5 * (u0 * v1 - u1 * v0);
        }
    }
    assert!(
        used.iter().all(|&u| u),
        "{label}: a coordinate no facet uses"
    );
    let nb = t.num_boundary_coords() as i32;
    for (&(i, j), &count) in &edges {
        let boundary = i < nb && j == (i + 1) % nb;
        let back = edges.get(&(j, i)).copied().unwrap_or(0);
        if boundary {
            assert_eq!((count, back), (1, 0), "{label}: boundary edge {i}-{j}");
        } else {
            assert_eq!((count, back), (1, 1), "{label}: edge {i}-{j}");
        }
    }
    for i in 0..nb {
        assert!(
            edges.contains_key(&(i, (i + 1) % nb)),
            "{label}: boundary segment {i} missing"
        );
    }
    let domain = match t.parameterization().kind() {
        ParameterizationType::Quad => Some(1.0),
        ParameterizationType::Triangle => Some(0.5),
        ParameterizationType::QuadSubfaces => None,
    };
    if let Some(domain) = domain {
        assert!((area - domain).abs() < 1e-9, "{label}: area {area}");
    }
    // Edge coordinates are the boundary's, bit for bit.
    let boundary = t.boundary_coords::<f32>().unwrap();
    let mut at = 0;
    for e in 0..t.face_size() {
        let inside = t.edge_coords::<f32>(e).unwrap();
        assert_eq!(inside.len(), t.num_edge_coords(e).unwrap());
        assert_eq!(
            boundary[at],
            t.vertex_coord::<f32>(e).unwrap(),
            "{label}: vertex {e}"
        );
        assert_eq!(
            inside[..],
            boundary[at + 1..at + 1 + inside.len()],
            "{label}: edge {e}"
        );
        at += 1 + inside.len();
    }
}

#[test]
fn every_pattern_is_a_watertight_oriented_disc() {
    let mut cases = 0;
    for (scheme, sizes) in [(Scheme::Catmark, 3..=9), (Scheme::Loop, 3..=3)] {
        for n in sizes {
            let p = Parameterization::new(scheme, n).unwrap();
            for rates in rate_sets(n, 17 * n as u64) {
                for (size, keep) in [
                    (FacetSize::Three, false),
                    (FacetSize::Four, false),
                    (FacetSize::Four, true),
                ] {
                    check(&Tessellation::new(p, &rates, opts(size, keep)).unwrap());
                    cases += 1;
                }
            }
        }
    }
    assert_eq!(cases, (7 + 1) * 76 * 3);
}
