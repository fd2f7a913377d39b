//! Hand-derived expectations for the masks of every scheme.

use super::*;
use crate::options::{CreasingMethod, Options, Scheme, TriangleSubdivision};

fn rules(scheme: Scheme) -> SchemeRules {
    SchemeRules::new(&Options::default().with_scheme(scheme))
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-15 * b.abs().max(1.0)
}

#[track_caller]
fn assert_weights(actual: &[f64], expected: &[f64]) {
    assert_eq!(actual.len(), expected.len(), "{actual:?} vs {expected:?}");
    for (a, e) in actual.iter().zip(expected) {
        assert!(close(*a, *e), "{actual:?} vs {expected:?}");
    }
}

/// A vertex with `edges.len()` edges and `faces` faces, its child as given.
fn hood<'a>(
    sharpness: f32,
    edges: &'a [f32],
    faces: usize,
    child_sharpness: f32,
    child_edges: &'a [f32],
) -> VertexNeighborhood<'a> {
    VertexNeighborhood {
        sharpness,
        edge_sharpness: edges,
        face_count: faces,
        child_sharpness,
        child_edge_sharpness: child_edges,
    }
}

/// An interior smooth vertex of valence `n` (no sharpness anywhere).
fn smooth_hood(zeros: &[f32]) -> VertexNeighborhood<'_> {
    hood(0.0, zeros, zeros.len(), 0.0, zeros)
}

#[test]
fn mask_reuse_and_reset() {
    let mut m = Mask::<f64>::new();
    m.reset(3, 5, 7);
    assert_eq!((m.vertex.len(), m.edge.len(), m.face.len()), (3, 5, 7));
    m.edge[2] = 4.0;
    m.face_weights_for_centers = true;
    let cap = m.edge.capacity();
    m.reset(1, 4, 0);
    assert_eq!(m.edge, vec![0.0; 4]);
    assert!(!m.face_weights_for_centers);
    assert_eq!(m.edge.capacity(), cap);
}

#[test]
fn face_points() {
    let mut m = Mask::<f64>::new();
    for scheme in [Scheme::Catmark, Scheme::Bilinear, Scheme::Loop] {
        rules(scheme).face_vertex_mask(5, &mut m);
        assert_weights(&m.vertex, &[0.2; 5]);
        assert!(m.edge.is_empty() && m.face.is_empty());
    }
}

#[test]
fn catmark_smooth_vertex() {
    let r = rules(Scheme::Catmark);
    let mut m = Mask::<f64>::new();
    let zeros = [0.0f32; 7];
    for n in [3usize, 4, 5, 7] {
        let v = smooth_hood(&zeros[..n]);
        r.vertex_vertex_mask(&v, Rule::Smooth, Rule::Smooth, &mut m);
        let nn = (n * n) as f64;
        assert_weights(&m.vertex, &[(n as f64 - 2.0) / n as f64]);
        assert_weights(&m.edge, &vec![1.0 / nn; n]);
        assert_weights(&m.face, &vec![1.0 / nn; n]);
        assert!(m.face_weights_for_centers);
        assert!(close(m.sum(), 1.0));
        // A dart refines like a smooth vertex.
        let mut d = Mask::<f64>::new();
        r.vertex_vertex_mask(&v, Rule::Dart, Rule::Dart, &mut d);
        assert_eq!((&d.vertex, &d.edge, &d.face), (&m.vertex, &m.edge, &m.face));
    }
}

#[test]
fn crease_and_corner_vertices() {
    let mut m = Mask::<f64>::new();
    for scheme in [Scheme::Catmark, Scheme::Loop] {
        let r = rules(scheme);
        // The crease edges anywhere among the edges, infinitely or semi-sharp.
        let cases: [(&[f32], usize, [usize; 2]); 4] = [
            (&[10.0, 0.0, 0.0, 10.0], 3, [0, 3]),
            (&[0.0, 2.0, 0.0, 0.0, 3.0, 0.0], 6, [1, 4]),
            (&[0.0, 0.0, 10.0, 10.0], 4, [2, 3]),
            (&[5.0, 0.0, 10.0], 2, [0, 2]),
        ];
        for (edges, faces, ends) in cases {
            let v = hood(0.0, edges, faces, 0.0, &[]);
            assert_eq!(crease::vertex_rule(0.0, edges), Rule::Crease);
            r.vertex_vertex_mask(&v, Rule::Crease, Rule::Crease, &mut m);
            let mut expected = vec![0.0; edges.len()];
            expected[ends[0]] = 0.125;
            expected[ends[1]] = 0.125;
            assert_weights(&m.vertex, &[0.75]);
            assert_weights(&m.edge, &expected);
            assert!(m.face.is_empty() && !m.face_weights_for_centers);
        }
        let v = hood(10.0, &[10.0, 10.0, 10.0], 3, 10.0, &[10.0, 10.0, 10.0]);
        r.vertex_vertex_mask(&v, Rule::Corner, Rule::Corner, &mut m);
        assert_weights(&m.vertex, &[1.0]);
        assert!(m.edge.is_empty() && m.face.is_empty());
    }
}

#[test]
fn catmark_edges() {
    let r = rules(Scheme::Catmark);
    let mut m = Mask::<f64>::new();
    let quads = EdgeNeighborhood {
        sharpness: 0.0,
        face_sizes: &[4, 4],
    };
    r.edge_vertex_mask(&quads, Rule::Smooth, Rule::Smooth, &mut m);
    assert_weights(&m.vertex, &[0.25, 0.25]);
    assert_weights(&m.face, &[0.25, 0.25]);
    assert!(m.face_weights_for_centers && m.edge.is_empty());

    let sharp = EdgeNeighborhood {
        sharpness: 10.0,
        face_sizes: &[4, 4],
    };
    r.edge_vertex_mask(&sharp, Rule::Crease, Rule::Crease, &mut m);
    assert_weights(&m.vertex, &[0.5, 0.5]);
    assert!(m.face.is_empty() && !m.face_weights_for_centers);

    // Semi-sharp 0.3 decays to smooth: 0.3 · (1/2, 1/2) + 0.7 · smooth, i.e.
    // vertices 0.15 + 0.175 = 0.325, faces 0.7 · 0.25 = 0.175.
    let semi = EdgeNeighborhood {
        sharpness: 0.3,
        face_sizes: &[4, 4],
    };
    r.edge_vertex_mask(&semi, Rule::Crease, Rule::Smooth, &mut m);
    let s = 0.3f32 as f64;
    let expected_v = s * 0.5 + (1.0 - s) * 0.25;
    assert_weights(&m.vertex, &[expected_v, expected_v]);
    assert_weights(&m.face, &[(1.0 - s) * 0.25, (1.0 - s) * 0.25]);
    assert!((m.vertex[0] - 0.325).abs() < 1e-7 && (m.face[0] - 0.175).abs() < 1e-7);
    assert!(close(m.sum(), 1.0));
    // A Dart child (one child edge still sharp, Chaikin) blends the same way.
    let mut d = Mask::<f64>::new();
    r.edge_vertex_mask(&semi, Rule::Crease, Rule::Dart, &mut d);
    assert_eq!((&d.vertex, &d.face), (&m.vertex, &m.face));
    // Semi-sharp 2.5 stays a crease.
    let semi = EdgeNeighborhood {
        sharpness: 2.5,
        face_sizes: &[4, 4],
    };
    r.edge_vertex_mask(&semi, Rule::Crease, Rule::Crease, &mut m);
    assert_weights(&m.vertex, &[0.5, 0.5]);

    // Non-manifold edge with three faces: 1/4 per vertex, 1/6 per face point.
    let three = EdgeNeighborhood {
        sharpness: 0.0,
        face_sizes: &[4, 4, 3],
    };
    r.edge_vertex_mask(&three, Rule::Smooth, Rule::Smooth, &mut m);
    assert_weights(&m.vertex, &[0.25, 0.25]);
    assert_weights(&m.face, &[0.5 / 3.0; 3]);
}

#[test]
fn catmark_smooth_triangles() {
    // "Smooth triangle" rule: a triangle's face weight is 0.47, any other face
    // 0.25; the edge point takes their mean f for both face points and
    // (1 - 2f)/2 for both end vertices:
    // * two triangles: f = 0.47, v = (1 - 0.94)/2 = 0.03;
    // * triangle and quad (or pentagon): f = (0.47 + 0.25)/2 = 0.36,
    //   v = (1 - 0.72)/2 = 0.14.
    let smooth = SchemeRules::new(&Options::default().with_triangles(TriangleSubdivision::Smooth));
    let plain = rules(Scheme::Catmark);
    let mut m = Mask::<f64>::new();
    let cases: [(&[u32], f64, f64); 5] = [
        (&[3, 3], 0.03, 0.47),
        (&[3, 4], 0.14, 0.36),
        (&[5, 3], 0.14, 0.36),
        (&[4, 4], 0.25, 0.25),
        (&[4, 6], 0.25, 0.25),
    ];
    for (sizes, v, f) in cases {
        let e = EdgeNeighborhood {
            sharpness: 0.0,
            face_sizes: sizes,
        };
        smooth.edge_vertex_mask(&e, Rule::Smooth, Rule::Smooth, &mut m);
        for (a, b) in m.vertex.iter().zip([v, v]) {
            assert!((a - b).abs() < 1e-15, "{sizes:?}: {:?}", m.vertex);
        }
        for (a, b) in m.face.iter().zip([f, f]) {
            assert!((a - b).abs() < 1e-15, "{sizes:?}: {:?}", m.face);
        }
        assert!(m.face_weights_for_centers);
        assert!(close(m.sum(), 1.0));
        // Without the option, triangles get the plain weights.
        plain.edge_vertex_mask(&e, Rule::Smooth, Rule::Smooth, &mut m);
        assert_weights(&m.vertex, &[0.25, 0.25]);
        assert_weights(&m.face, &[0.25, 0.25]);
    }
    // The option only concerns manifold edges: three faces with a triangle.
    let e = EdgeNeighborhood {
        sharpness: 0.0,
        face_sizes: &[3, 3, 3],
    };
    smooth.edge_vertex_mask(&e, Rule::Smooth, Rule::Smooth, &mut m);
    assert_weights(&m.vertex, &[0.25, 0.25]);
    // Exact values: 0.47 is rounded to T first, then combined in T.
    let e = EdgeNeighborhood {
        sharpness: 0.0,
        face_sizes: &[3, 4],
    };
    let mut m32 = Mask::<f32>::new();
    smooth.edge_vertex_mask(&e, Rule::Smooth, Rule::Smooth, &mut m32);
    let f = 0.5f32 * (0.47f32 + 0.25);
    assert_eq!(m32.face, [f, f]);
    assert_eq!(m32.vertex[0], 0.5f32 * (1.0 - 2.0 * f));
}

#[test]
fn semi_sharp_vertex_blending() {
    let r = rules(Scheme::Catmark);
    let mut m = Mask::<f64>::new();

    // Valence 4, edges 0 and 2 semi-sharp (0.5 and 0.3): a crease that
    // becomes smooth in the child (both decay to 0). Fractional weight
    // w = (0.5 + 0.3)/2 = 0.4 for the parent's crease mask, 0.6 for the
    // child's smooth mask:
    //   vertex     0.4 · 3/4 + 0.6 · 1/2  = 0.3 + 0.3     = 0.6
    //   edges 0, 2 0.4 · 1/8 + 0.6 · 1/16 = 0.05 + 0.0375 = 0.0875
    //   edges 1, 3             0.6 · 1/16                 = 0.0375
    //   faces                  0.6 · 1/16                 = 0.0375
    // which sums to 0.6 + 0.175 + 0.075 + 0.15 = 1.
    let edges = [0.5f32, 0.0, 0.3, 0.0];
    let child = [0.0f32; 4];
    let v = hood(0.0, &edges, 4, 0.0, &child);
    assert_eq!(crease::vertex_rule(0.0, &edges), Rule::Crease);
    assert_eq!(crease::vertex_rule(0.0, &child), Rule::Smooth);
    r.vertex_vertex_mask(&v, Rule::Crease, Rule::Smooth, &mut m);
    let w = ((0.5f32 + 0.3f32) / 2.0) as f64;
    let c = 1.0 - w;
    assert!((w - 0.4).abs() < 1e-7);
    assert_weights(&m.vertex, &[w * 0.75 + c * 0.5]);
    let (a, b) = (w * 0.125 + c * 0.0625, c * 0.0625);
    assert_weights(&m.edge, &[a, b, a, b]);
    assert_weights(&m.face, &[c * 0.0625; 4]);
    assert!(m.face_weights_for_centers);
    assert!((m.vertex[0] - 0.6).abs() < 1e-7 && (m.edge[0] - 0.0875).abs() < 1e-8);
    assert!(close(m.sum(), 1.0));
    // Same under Chaikin (no edge > 1 involved).
    let chaikin = SchemeRules::new(&Options::default().with_creasing(CreasingMethod::Chaikin));
    let mut m2 = Mask::<f64>::new();
    chaikin.vertex_vertex_mask(&v, Rule::Crease, Rule::Smooth, &mut m2);
    assert_eq!(
        (&m.vertex, &m.edge, &m.face),
        (&m2.vertex, &m2.edge, &m2.face)
    );

    // A boundary vertex (two infinitely sharp edges) with vertex sharpness 0.5:
    // Corner in the parent, Crease in the child; only the vertex transitions,
    // w = 0.5:  vertex 0.5 · 1 + 0.5 · 3/4 = 0.875, crease edges 0.5 · 1/8.
    let edges = [10.0f32, 0.0, 10.0];
    let v = hood(0.5, &edges, 2, 0.0, &edges);
    r.vertex_vertex_mask(&v, Rule::Corner, Rule::Crease, &mut m);
    assert_weights(&m.vertex, &[0.875]);
    assert_weights(&m.edge, &[0.0625, 0.0, 0.0625]);
    assert!(m.face.is_empty());

    // Three sharp edges make a corner; with sharpness 0.5, 2 and 2 the child
    // is a crease along the two edges of (now) sharpness 1. Uniform creasing:
    // only the 0.5 edge transitions, w = 0.5; the child's crease ends are
    // edges 1 and 3:  vertex 0.5 + 0.375 = 0.875, edges 1, 3: 0.0625.
    let edges = [0.5f32, 2.0, 0.0, 2.0];
    let child = [0.0f32, 1.0, 0.0, 1.0];
    let v = hood(0.0, &edges, 4, 0.0, &child);
    assert_eq!(crease::vertex_rule(0.0, &edges), Rule::Corner);
    r.vertex_vertex_mask(&v, Rule::Corner, Rule::Crease, &mut m);
    assert_weights(&m.vertex, &[0.875]);
    assert_weights(&m.edge, &[0.0, 0.0625, 0.0, 0.0625]);

    // Corner to smooth, Loop: three edges of 0.25 at a valence-6 vertex.
    // w = 0.25:  vertex 0.25 + 0.75 · 5/8, edges 0.75 · 1/16.
    let l = rules(Scheme::Loop);
    let edges = [0.25f32, 0.0, 0.25, 0.0, 0.25, 0.0];
    let v = hood(0.0, &edges, 6, 0.0, &[0.0; 6]);
    l.vertex_vertex_mask(&v, Rule::Corner, Rule::Smooth, &mut m);
    assert_weights(&m.vertex, &[0.25 + 0.75 * 0.625]);
    assert_weights(&m.edge, &[0.75 * 0.0625; 6]);
    assert!(m.face.is_empty() && !m.face_weights_for_centers);
    assert!(close(m.sum(), 1.0));
}

#[test]
fn chaikin_edge_extrapolation() {
    // Under Chaikin an edge of 1.2 can lose its sharpness at one end; the
    // parent weight is then 1.2 (not clamped): vertices 1.2 · 1/2 - 0.2 · 1/4
    // = 0.55, faces -0.2 · 1/4 = -0.05.
    let r = SchemeRules::new(&Options::default().with_creasing(CreasingMethod::Chaikin));
    let mut m = Mask::<f64>::new();
    let e = EdgeNeighborhood {
        sharpness: 1.2,
        face_sizes: &[4, 4],
    };
    r.edge_vertex_mask(&e, Rule::Crease, Rule::Dart, &mut m);
    let s = 1.2f32 as f64;
    assert_weights(&m.vertex, &[s * 0.5 + (1.0 - s) * 0.25; 2]);
    assert_weights(&m.face, &[(1.0 - s) * 0.25; 2]);
    assert!((m.vertex[0] - 0.55).abs() < 1e-7 && (m.face[0] + 0.05).abs() < 1e-7);
}

#[test]
fn loop_masks() {
    let r = rules(Scheme::Loop);
    let mut m = Mask::<f64>::new();
    let zeros = [0.0f32; 7];

    // Regular: 5/8 and 1/16 per neighbour.
    r.vertex_vertex_mask(
        &smooth_hood(&zeros[..6]),
        Rule::Smooth,
        Rule::Smooth,
        &mut m,
    );
    assert_weights(&m.vertex, &[0.625]);
    assert_weights(&m.edge, &[0.0625; 6]);
    assert!(m.face.is_empty());

    // Valence 3: cos(2π/3) = -1/2, so 3/8 + cos/4 = 1/4 and the neighbour
    // weight is (5/8 - 1/16)/3 = 3/16, the vertex 1 - 9/16 = 7/16.
    r.vertex_vertex_mask(
        &smooth_hood(&zeros[..3]),
        Rule::Smooth,
        Rule::Smooth,
        &mut m,
    );
    assert!((m.vertex[0] - 7.0 / 16.0).abs() < 1e-15);
    for &e in &m.edge {
        assert!((e - 3.0 / 16.0).abs() < 1e-15);
    }
    assert!(close(m.sum(), 1.0));

    // Valence 5 and 7: Loop's formula.
    for n in [5usize, 7] {
        r.vertex_vertex_mask(
            &smooth_hood(&zeros[..n]),
            Rule::Smooth,
            Rule::Smooth,
            &mut m,
        );
        let beta = 0.375 + 0.25 * (2.0 * std::f64::consts::PI / n as f64).cos();
        let w = (0.625 - beta * beta) / n as f64;
        assert!(
            (m.edge[0] - w).abs() < 1e-15 && (m.vertex[0] - (1.0 - n as f64 * w)).abs() < 1e-15
        );
    }

    // Crease.
    let edges = [10.0f32, 0.0, 0.0, 10.0];
    r.vertex_vertex_mask(
        &hood(0.0, &edges, 3, 0.0, &[]),
        Rule::Crease,
        Rule::Crease,
        &mut m,
    );
    assert_weights(&m.vertex, &[0.75]);
    assert_weights(&m.edge, &[0.125, 0.0, 0.0, 0.125]);

    // Edges: 3/8 per end, 1/8 per opposite vertex (not face centres).
    let e = EdgeNeighborhood {
        sharpness: 0.0,
        face_sizes: &[3, 3],
    };
    r.edge_vertex_mask(&e, Rule::Smooth, Rule::Smooth, &mut m);
    assert_weights(&m.vertex, &[0.375, 0.375]);
    assert_weights(&m.face, &[0.125, 0.125]);
    assert!(!m.face_weights_for_centers);
    let e = EdgeNeighborhood {
        sharpness: 0.0,
        face_sizes: &[3, 3, 3],
    };
    r.edge_vertex_mask(&e, Rule::Smooth, Rule::Smooth, &mut m);
    assert_weights(&m.face, &[0.125 * (2.0 / 3.0); 3]);
    let e = EdgeNeighborhood {
        sharpness: 10.0,
        face_sizes: &[3],
    };
    r.edge_vertex_mask(&e, Rule::Crease, Rule::Crease, &mut m);
    assert_weights(&m.vertex, &[0.5, 0.5]);
    assert!(m.face.is_empty());
}

#[test]
fn bilinear_masks() {
    let r = rules(Scheme::Bilinear);
    let mut m = Mask::<f64>::new();
    let e = EdgeNeighborhood {
        sharpness: 0.0,
        face_sizes: &[4, 4],
    };
    r.edge_vertex_mask(&e, Rule::Smooth, Rule::Smooth, &mut m);
    assert_weights(&m.vertex, &[0.5, 0.5]);
    assert!(m.face.is_empty() && m.edge.is_empty());
    let zeros = [0.0f32; 4];
    r.vertex_vertex_mask(&smooth_hood(&zeros), Rule::Smooth, Rule::Smooth, &mut m);
    assert_weights(&m.vertex, &[1.0]);
    assert!(m.face.is_empty() && m.edge.is_empty());

    let (mut p, mut t1, mut t2) = (Mask::new(), Mask::new(), Mask::new());
    for rule in [Rule::Smooth, Rule::Crease, Rule::Corner] {
        let edges = [10.0f32, 0.0, 0.0, 10.0];
        r.vertex_limit_masks(
            &hood(0.0, &edges, 3, 0.0, &[]),
            rule,
            &mut p,
            &mut t1,
            &mut t2,
        );
        assert_weights(&p.vertex, &[1.0]);
        assert!(p.edge.is_empty() && p.face.is_empty());
        // Tangents along the first two edges, exactly two edge weights.
        assert_weights(&t1.vertex, &[-1.0]);
        assert_weights(&t1.edge, &[1.0, 0.0]);
        assert_weights(&t2.vertex, &[-1.0]);
        assert_weights(&t2.edge, &[0.0, 1.0]);
    }
}

/// Checks the shared invariants of a limit: position sums to 1, tangents to
/// 0, both tangent masks have the same lengths, no face centres.
#[track_caller]
fn check_limit(p: &Mask<f64>, t1: &Mask<f64>, t2: &Mask<f64>) {
    assert!(close(p.sum(), 1.0), "{p:?}");
    assert!(t1.sum().abs() < 1e-14, "{t1:?}");
    assert!(t2.sum().abs() < 1e-14, "{t2:?}");
    assert_eq!(t1.edge.len(), t2.edge.len());
    assert_eq!(t1.face.len(), t2.face.len());
    assert!(!p.face_weights_for_centers && !t1.face_weights_for_centers);
}

#[test]
fn catmark_limits() {
    let r = rules(Scheme::Catmark);
    let (mut p, mut t1, mut t2) = (Mask::<f64>::new(), Mask::new(), Mask::new());

    // Regular interior: 4/9, 1/9 per edge, 1/36 per face (diagonal vertex).
    let zeros = [0.0f32; 8];
    r.vertex_limit_masks(
        &smooth_hood(&zeros[..4]),
        Rule::Smooth,
        &mut p,
        &mut t1,
        &mut t2,
    );
    assert_weights(&p.vertex, &[4.0 / 9.0]);
    assert_weights(&p.edge, &[1.0 / 9.0; 4]);
    assert_weights(&p.face, &[1.0 / 36.0; 4]);
    // Tangents: tan1 along edge 0 (towards e0, away from e2), tan2 along
    // edge 1, both scaled by 4 in the edges and 1 in the faces (OpenSubdiv's
    // unnormalised convention; face i lies between edges i and i+1).
    assert_weights(&t1.vertex, &[0.0]);
    assert_weights(&t1.edge, &[4.0, 0.0, -4.0, 0.0]);
    assert_weights(&t1.face, &[1.0, -1.0, -1.0, 1.0]);
    assert_weights(&t2.edge, &[0.0, 4.0, 0.0, -4.0]);
    assert_weights(&t2.face, &[1.0, 1.0, -1.0, -1.0]);
    check_limit(&p, &t1, &t2);

    // Valence 3: faces 1/(3·8) = 1/24, edges 4/24 = 1/6, vertex 1 - 3·5/24 = 3/8.
    r.vertex_limit_masks(
        &smooth_hood(&zeros[..3]),
        Rule::Smooth,
        &mut p,
        &mut t1,
        &mut t2,
    );
    assert_weights(&p.vertex, &[0.375]);
    assert_weights(&p.edge, &[1.0 / 6.0; 3]);
    assert_weights(&p.face, &[1.0 / 24.0; 3]);
    check_limit(&p, &t1, &t2);
    // tan2 is tan1 rotated by one edge.
    assert_eq!(t2.edge, [t1.edge[2], t1.edge[0], t1.edge[1]]);
    assert_eq!(t2.face, [t1.face[2], t1.face[0], t1.face[1]]);
    assert!(close(t1.edge[0], 4.0));

    for n in [5usize, 6, 8] {
        r.vertex_limit_masks(
            &smooth_hood(&zeros[..n]),
            Rule::Dart,
            &mut p,
            &mut t1,
            &mut t2,
        );
        check_limit(&p, &t1, &t2);
        assert_eq!((p.edge.len(), p.face.len(), t1.face.len()), (n, n, n));
    }

    // Valence 2 (two faces sharing two edges): the vertex itself, corner tangents.
    r.vertex_limit_masks(
        &smooth_hood(&zeros[..2]),
        Rule::Smooth,
        &mut p,
        &mut t1,
        &mut t2,
    );
    assert_weights(&p.vertex, &[1.0]);
    assert_weights(&t1.edge, &[1.0, 0.0]);
    assert_weights(&t2.edge, &[0.0, 1.0]);
    check_limit(&p, &t1, &t2);

    // Regular boundary (3 edges, 2 faces, crease edges 0 and 2): 2/3, 1/6.
    let edges = [10.0f32, 0.0, 10.0];
    let v = hood(0.0, &edges, 2, 0.0, &[]);
    r.vertex_limit_masks(&v, Rule::Crease, &mut p, &mut t1, &mut t2);
    assert_weights(&p.vertex, &[2.0 / 3.0]);
    assert_weights(&p.edge, &[1.0 / 6.0, 0.0, 1.0 / 6.0]);
    assert!(p.face.is_empty());
    // tan1 = (e0 - e2)/2, tan2 the cubic B-spline cross derivative.
    assert_weights(&t1.edge, &[0.5, 0.0, -0.5]);
    assert_weights(&t1.face, &[0.0, 0.0]);
    assert_weights(&t2.vertex, &[-4.0 / 6.0]);
    assert_weights(&t2.edge, &[-1.0 / 6.0, 4.0 / 6.0, -1.0 / 6.0]);
    assert_weights(&t2.face, &[1.0 / 6.0, 1.0 / 6.0]);
    check_limit(&p, &t1, &t2);

    // Boundary corner with one face (EdgeAndCorner makes it a Corner; as a
    // Crease it uses the single-face rule).
    let edges = [10.0f32, 10.0];
    let v = hood(0.0, &edges, 1, 0.0, &[]);
    r.vertex_limit_masks(&v, Rule::Crease, &mut p, &mut t1, &mut t2);
    assert_weights(&p.edge, &[1.0 / 6.0, 1.0 / 6.0]);
    assert_weights(&t2.vertex, &[-6.0]);
    assert_weights(&t2.edge, &[3.0, 3.0]);
    assert_weights(&t2.face, &[0.0]);
    check_limit(&p, &t1, &t2);
    r.vertex_limit_masks(&v, Rule::Corner, &mut p, &mut t1, &mut t2);
    assert_weights(&p.vertex, &[1.0]);
    assert_weights(&t1.vertex, &[-1.0]);
    assert_weights(&t1.edge, &[1.0, 0.0]);
    assert_weights(&t2.edge, &[0.0, 1.0]);
    assert!(t1.face.is_empty());
    check_limit(&p, &t1, &t2);

    // Irregular boundaries and an interior crease with the span in the middle.
    for (edges, faces) in [
        (&[10.0f32, 0.0, 0.0, 10.0][..], 3),
        (&[10.0, 0.0, 0.0, 0.0, 0.0, 10.0][..], 5),
        (&[0.0, 10.0, 0.0, 0.0, 0.0, 2.0][..], 6),
    ] {
        r.vertex_limit_masks(
            &hood(0.0, edges, faces, 0.0, &[]),
            Rule::Crease,
            &mut p,
            &mut t1,
            &mut t2,
        );
        check_limit(&p, &t1, &t2);
        assert_eq!((t1.edge.len(), t1.face.len()), (edges.len(), faces));
    }
    // Interior crease over edges 1 and 5 of 6: faces 1..=4 are in the span.
    assert_eq!(t2.face[0], 0.0);
    assert_eq!(t2.face[5], 0.0);
    assert!(t2.face[1] > 0.0 && t2.edge[0] == 0.0);
}

#[test]
fn loop_limits() {
    let r = rules(Scheme::Loop);
    let (mut p, mut t1, mut t2) = (Mask::<f64>::new(), Mask::new(), Mask::new());
    let zeros = [0.0f32; 8];

    // Regular: 1/2 and 1/12 per neighbour; tangents cos/sin of 60° steps.
    r.vertex_limit_masks(
        &smooth_hood(&zeros[..6]),
        Rule::Smooth,
        &mut p,
        &mut t1,
        &mut t2,
    );
    assert_weights(&p.vertex, &[0.5]);
    assert_weights(&p.edge, &[1.0 / 12.0; 6]);
    assert!(p.face.is_empty());
    let h = 3f64.sqrt() / 2.0;
    assert_weights(&t1.edge, &[1.0, 0.5, -0.5, -1.0, -0.5, 0.5]);
    assert_weights(&t2.edge, &[0.0, h, h, 0.0, -h, -h]);
    check_limit(&p, &t1, &t2);
    assert_eq!(loop_scheme_root3(), 3f64.sqrt());

    // Irregular: 1/(n + 3/(8w)) per neighbour, w the refinement weight.
    for n in [3usize, 4, 5, 7] {
        r.vertex_limit_masks(
            &smooth_hood(&zeros[..n]),
            Rule::Smooth,
            &mut p,
            &mut t1,
            &mut t2,
        );
        let beta = 0.375 + 0.25 * (2.0 * std::f64::consts::PI / n as f64).cos();
        let w = (0.625 - beta * beta) / n as f64;
        assert!((p.edge[0] - 1.0 / (n as f64 + 3.0 / (8.0 * w))).abs() < 1e-15);
        check_limit(&p, &t1, &t2);
    }
    // Valence 3: w = 3/16, so 1/(3 + 2) = 1/5 per neighbour, 2/5 on the vertex.
    r.vertex_limit_position_mask(&smooth_hood(&zeros[..3]), Rule::Smooth, &mut p);
    assert!((p.edge[0] - 0.2).abs() < 1e-15 && (p.vertex[0] - 0.4).abs() < 1e-15);

    // Boundaries: 2/3 and 1/6; tangents scaled by 1.5 along and by OpenSubdiv's
    // factors across (regular: √3 (e1 + e2 - v) - √3/2 (e0 + e3)).
    let edges = [10.0f32, 0.0, 0.0, 10.0];
    r.vertex_limit_masks(
        &hood(0.0, &edges, 3, 0.0, &[]),
        Rule::Crease,
        &mut p,
        &mut t1,
        &mut t2,
    );
    assert_weights(&p.vertex, &[2.0 / 3.0]);
    assert_weights(&p.edge, &[1.0 / 6.0, 0.0, 0.0, 1.0 / 6.0]);
    assert_weights(&t1.edge, &[1.5, 0.0, 0.0, -1.5]);
    let r3 = 3f64.sqrt();
    assert_weights(&t2.vertex, &[-r3]);
    assert_weights(&t2.edge, &[-r3 / 2.0, r3, r3, -r3 / 2.0]);
    check_limit(&p, &t1, &t2);
    for edges in [
        &[10.0f32, 10.0][..],
        &[10.0, 0.0, 10.0],
        &[10.0, 0.0, 0.0, 0.0, 0.0, 10.0],
    ] {
        let v = hood(0.0, edges, edges.len() - 1, 0.0, &[]);
        r.vertex_limit_masks(&v, Rule::Crease, &mut p, &mut t1, &mut t2);
        check_limit(&p, &t1, &t2);
    }
    // Corner: 3 (e0 - v), 3 (e1 - v).
    let edges = [10.0f32, 0.0, 10.0];
    r.vertex_limit_masks(
        &hood(10.0, &edges, 2, 0.0, &[]),
        Rule::Corner,
        &mut p,
        &mut t1,
        &mut t2,
    );
    assert_weights(&p.vertex, &[1.0]);
    assert_weights(&t1.vertex, &[-3.0]);
    assert_weights(&t1.edge, &[3.0, 0.0, 0.0]);
    assert_weights(&t2.edge, &[0.0, 3.0, 0.0]);
    check_limit(&p, &t1, &t2);
}

fn loop_scheme_root3() -> f64 {
    // The constant the Loop tangents use must be the double nearest √3.
    let r = rules(Scheme::Loop);
    let (mut p, mut t1, mut t2) = (Mask::<f64>::new(), Mask::new(), Mask::new());
    let edges = [10.0f32, 0.0, 0.0, 10.0];
    r.vertex_limit_masks(
        &hood(0.0, &edges, 3, 0.0, &[]),
        Rule::Crease,
        &mut p,
        &mut t1,
        &mut t2,
    );
    t2.edge[1]
}

/// Every kind of mask in f32 and f64: the same weights to f32 precision.
#[test]
fn f32_and_f64_agree() {
    let zeros = [0.0f32; 9];
    let mut hoods: Vec<(VertexNeighborhood, Rule, Rule)> = Vec::new();
    for n in 2..=9 {
        hoods.push((smooth_hood(&zeros[..n]), Rule::Smooth, Rule::Smooth));
    }
    let semi = [0.5f32, 0.0, 0.3, 0.0, 0.0];
    hoods.push((
        hood(0.0, &semi, 5, 0.0, &zeros[..5]),
        Rule::Crease,
        Rule::Smooth,
    ));
    let corner = [0.7f32, 2.0, 0.0, 2.5, 0.0];
    let corner_child = [0.0f32, 1.0, 0.0, 1.5, 0.0];
    hoods.push((
        hood(0.0, &corner, 5, 0.0, &corner_child),
        Rule::Corner,
        Rule::Crease,
    ));
    let boundary = [10.0f32, 0.0, 0.0, 0.0, 10.0];
    hoods.push((
        hood(0.4, &boundary, 4, 0.0, &boundary),
        Rule::Corner,
        Rule::Crease,
    ));

    for scheme in [Scheme::Catmark, Scheme::Loop, Scheme::Bilinear] {
        for triangles in [TriangleSubdivision::Catmark, TriangleSubdivision::Smooth] {
            let r = SchemeRules::new(
                &Options::default()
                    .with_scheme(scheme)
                    .with_triangles(triangles),
            );
            let mut masks32 = Vec::new();
            let mut masks64 = Vec::new();
            for (v, pr, cr) in &hoods {
                let (mut a, mut b) = (Mask::<f32>::new(), Mask::<f64>::new());
                r.vertex_vertex_mask(v, *pr, *cr, &mut a);
                r.vertex_vertex_mask(v, *pr, *cr, &mut b);
                masks32.push(a);
                masks64.push(b);
                let rule = if *pr == Rule::Corner && scheme != Scheme::Bilinear {
                    *cr
                } else {
                    *pr
                };
                let mut m32 = [Mask::<f32>::new(), Mask::new(), Mask::new()];
                let mut m64 = [Mask::<f64>::new(), Mask::new(), Mask::new()];
                let [p, t1, t2] = &mut m32;
                r.vertex_limit_masks(v, rule, p, t1, t2);
                let [p, t1, t2] = &mut m64;
                r.vertex_limit_masks(v, rule, p, t1, t2);
                masks32.extend(m32);
                masks64.extend(m64);
            }
            for sizes in [&[4u32, 4][..], &[3, 3], &[3, 4], &[4, 4, 4], &[5]] {
                for (s, pr, cr) in [
                    (0.0f32, Rule::Smooth, Rule::Smooth),
                    (0.3, Rule::Crease, Rule::Smooth),
                    (1.3, Rule::Crease, Rule::Dart),
                    (10.0, Rule::Crease, Rule::Crease),
                ] {
                    let e = EdgeNeighborhood {
                        sharpness: s,
                        face_sizes: sizes,
                    };
                    let (mut a, mut b) = (Mask::<f32>::new(), Mask::<f64>::new());
                    r.edge_vertex_mask(&e, pr, cr, &mut a);
                    r.edge_vertex_mask(&e, pr, cr, &mut b);
                    masks32.push(a);
                    masks64.push(b);
                }
            }
            for n in 3..=7 {
                let (mut a, mut b) = (Mask::<f32>::new(), Mask::<f64>::new());
                r.face_vertex_mask(n, &mut a);
                r.face_vertex_mask(n, &mut b);
                masks32.push(a);
                masks64.push(b);
            }
            for (a, b) in masks32.iter().zip(&masks64) {
                assert_eq!(a.face_weights_for_centers, b.face_weights_for_centers);
                for (x, y) in [
                    (&a.vertex, &b.vertex),
                    (&a.edge, &b.edge),
                    (&a.face, &b.face),
                ] {
                    assert_eq!(x.len(), y.len(), "{a:?} vs {b:?}");
                    for (&x, &y) in x.iter().zip(y.iter()) {
                        let tol = 4.0 * f32::EPSILON as f64 * y.abs().max(1.0);
                        assert!((x as f64 - y).abs() <= tol, "{scheme}: {a:?} vs {b:?}");
                    }
                }
            }
        }
    }
}

/// Bit patterns printed by OpenSubdiv 3.5's own `Sdc::Scheme` for the same
/// neighbourhoods (a small C++ program filling `PrimvarRefinerReal<T>`-style
/// masks), where rounding is least obvious: irregular tangents computed in
/// double, Loop weights rounded to `f32`, a blended semi-sharp vertex.
#[test]
fn bit_exact_against_opensubdiv() {
    fn bits64(m: &[f64]) -> Vec<u64> {
        m.iter().map(|w| w.to_bits()).collect()
    }
    fn bits32(m: &[f32]) -> Vec<u32> {
        m.iter().map(|w| w.to_bits()).collect()
    }
    let cc = rules(Scheme::Catmark);
    let lp = rules(Scheme::Loop);
    let zeros = [0.0f32; 7];

    // Catmull-Clark, smooth valence 5, f64: position and first tangent.
    let (mut p, mut t1, mut t2) = (Mask::<f64>::new(), Mask::new(), Mask::new());
    cc.vertex_limit_masks(
        &smooth_hood(&zeros[..5]),
        Rule::Smooth,
        &mut p,
        &mut t1,
        &mut t2,
    );
    assert_eq!(bits64(&p.vertex), [0x3fe0000000000000]);
    assert_eq!(bits64(&p.edge), [0x3fb47ae147ae147b; 5]);
    assert_eq!(bits64(&p.face), [0x3f947ae147ae147b; 5]);
    assert_eq!(bits64(&t1.vertex), [0]);
    assert_eq!(
        bits64(&t1.edge),
        [
            0x4010000000000000,
            0x3ff3c6ef372fe950,
            0xc009e3779b97f4a7,
            0xc009e3779b97f4a9,
            0x3ff3c6ef372fe94c
        ]
    );
    assert_eq!(
        bits64(&t1.face),
        [
            0x3ff17448e81f2687,
            0xbfdaaaee8257878d,
            0xbff5931a8f128947,
            0xbfdaaaee82578794,
            0x3ff17448e81f2686
        ]
    );

    // Catmull-Clark boundary with 4 faces (Biermann's cross tangent), f32.
    let edges = [10.0f32, 0.0, 0.0, 0.0, 10.0];
    let (mut p, mut t1, mut t2) = (Mask::<f32>::new(), Mask::new(), Mask::new());
    cc.vertex_limit_masks(
        &hood(0.0, &edges, 4, 0.0, &[]),
        Rule::Crease,
        &mut p,
        &mut t1,
        &mut t2,
    );
    assert_eq!(bits32(&t2.vertex), [0xbe435248]);
    assert_eq!(
        bits32(&t2.edge),
        [0xbec93edb, 0x3e435248, 0x3e8a1cf4, 0x3e435248, 0xbec93edb]
    );
    assert_eq!(
        bits32(&t2.face),
        [0x3d435248, 0x3debc618, 0x3debc618, 0x3d435248]
    );

    // Loop, smooth valence 5 vertex point, f32.
    let mut m = Mask::<f32>::new();
    lp.vertex_vertex_mask(
        &smooth_hood(&zeros[..5]),
        Rule::Smooth,
        Rule::Smooth,
        &mut m,
    );
    assert_eq!(bits32(&m.vertex), [0x3f145c55]);
    assert_eq!(bits32(&m.edge), [0x3dac3911; 5]);

    // Loop, smooth valence 7 limit position, f64.
    let mut p = Mask::<f64>::new();
    lp.vertex_limit_position_mask(&smooth_hood(&zeros[..7]), Rule::Smooth, &mut p);
    assert_eq!(bits64(&p.vertex), [0x3fe0b583258302b8]);
    assert_eq!(bits64(&p.edge), [0x3fb179b342d7fce4; 7]);

    // Catmull-Clark, crease of 0.5 and 0.3 fading into a smooth valence-5 vertex, f32.
    let edges = [0.5f32, 0.0, 0.3, 0.0, 0.0];
    let v = hood(0.0, &edges, 5, 0.0, &[0.0; 5]);
    let mut m = Mask::<f32>::new();
    cc.vertex_vertex_mask(&v, Rule::Crease, Rule::Smooth, &mut m);
    assert_eq!(bits32(&m.vertex), [0x3f28f5c3]);
    assert_eq!(
        bits32(&m.edge),
        [0x3d978d50, 0x3cc49ba6, 0x3d978d50, 0x3cc49ba6, 0x3cc49ba6]
    );
    assert_eq!(bits32(&m.face), [0x3cc49ba6; 5]);
}
