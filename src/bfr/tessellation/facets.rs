//! The facets of the three kinds of pattern, ring by ring, and their counts.
//!
//! Coordinates are numbered ring by ring from the boundary inward (see
//! `coords.rs`), so a ring's facets are strips between the ring starting at
//! `coord0` and the next one. The boundary ring's strips are uniform where
//! an edge's rate equals the inner rate (with a single triangle at a corner
//! next to a non-uniform edge) and general strips elsewhere; every ring
//! inside is uniform.

use super::strip::{FacetSink, Strip};

/// The parity of `x`.
fn odd(x: i64) -> bool {
    x & 1 != 0
}

/// Quads of the unit square.
pub(super) mod quad {
    use super::*;

    /// Facets of a uniform pattern at rate `res`.
    pub(in super::super) fn uniform_count(res: i64, triangulate: bool) -> i64 {
        (res * res) << i64::from(triangulate)
    }

    /// Facets of a 1 × M strip.
    pub(in super::super) fn segmented_count(inner: [i64; 2], triangulate: bool) -> i64 {
        (inner[0] * inner[1]) << i64::from(triangulate)
    }

    /// Facets of a general strip between `outer` and `inner` edges.
    fn non_uniform_edge_count(outer: i64, inner: i64) -> i64 {
        let n = outer.max(inner - 2);
        n + i64::from(!odd(n) && (odd(outer) || odd(inner)))
    }

    /// Facets of a non-uniform pattern (inner rates both above 1).
    pub(in super::super) fn non_uniform_count(
        outer: &[i64],
        inner: [i64; 2],
        triangulate: bool,
    ) -> i64 {
        let (u, v) = (inner[0], inner[1]);
        let (inner_u, inner_v) = (u - 2, v - 2);
        let interior = inner_u * inner_v;
        let rows = [inner_u, inner_v, inner_u, inner_v];
        if triangulate {
            return interior * 2 + (0..4).map(|e| rows[e] + outer[e]).sum::<i64>();
        }
        let res = [u, v, u, v];
        let uniform: Vec<bool> = (0..4).map(|e| outer[e] == res[e]).collect();
        let boundary: i64 = (0..4)
            .map(|e| {
                if uniform[e] {
                    // The leading corner, each inner edge, and a triangle at
                    // the trailing corner when it is not uniform.
                    let next = (e + 1) % 4;
                    rows[e] + 1 + i64::from(!(uniform[next] && uniform[e]))
                } else {
                    non_uniform_edge_count(outer[e], res[e])
                }
            })
            .sum();
        interior + boundary
    }

    /// One ring `u_res` × `v_res` edges starting at `coord0`, joined to the
    /// ring inside it.
    fn interior_ring(u_res: i32, v_res: i32, coord0: i32, triangulate: bool, sink: &mut FacetSink) {
        let total = u_res * v_res;
        if total == 0 {
            return;
        }
        if total == 1 {
            sink.quad(
                [coord0, coord0 + 1, coord0 + 2, coord0 + 3],
                i32::from(triangulate),
            );
            return;
        }
        if u_res == 1 || v_res == 1 {
            single_strip(u_res, v_res, coord0, triangulate, sink);
            return;
        }
        let (inner_u, inner_v) = (u_res - 2, v_res - 2);
        let outer_start = coord0;
        let inner_start = coord0 + 2 * (u_res + v_res);
        let mut s = Strip {
            quads: true,
            triangulate,
            outer_edges: u_res,
            outer_first: outer_start,
            outer_prev: inner_start - 1,
            outer_last: outer_start + u_res,
            inner_edges: inner_u,
            inner_first: inner_start,
            inner_last: inner_start + inner_u,
            ..Strip::default()
        };
        s.uniform_quads(sink);

        s.outer_edges = v_res;
        s.outer_first += u_res;
        s.outer_prev = s.outer_first - 1;
        s.outer_last = s.outer_first + v_res;
        s.inner_edges = inner_v;
        s.inner_first = s.inner_last;
        s.inner_last += inner_v;
        s.uniform_quads(sink);

        s.outer_edges = u_res;
        s.outer_first += v_res;
        s.outer_prev = s.outer_first - 1;
        s.outer_last = s.outer_first + u_res;
        s.inner_edges = inner_u;
        s.inner_reversed = inner_v == 0;
        s.inner_first = s.inner_last;
        s.inner_last += if s.inner_reversed { -inner_u } else { inner_u };
        s.uniform_quads(sink);

        s.outer_edges = v_res;
        s.outer_first += u_res;
        s.outer_prev = s.outer_first - 1;
        s.outer_last = outer_start;
        s.inner_edges = inner_v;
        s.inner_reversed = inner_u == 0;
        s.inner_first = s.inner_last;
        s.inner_last = inner_start;
        s.uniform_quads(sink);
    }

    /// The single row of quads filling a ring one edge wide.
    fn single_strip(u_res: i32, v_res: i32, coord0: i32, triangulate: bool, sink: &mut FacetSink) {
        let mut s = Strip {
            quads: true,
            triangulate,
            inner_reversed: true,
            include_last: true,
            ..Strip::default()
        };
        if u_res > 1 {
            s.outer_edges = u_res;
            s.inner_edges = u_res - 2;
            s.outer_first = coord0;
            s.outer_last = coord0 + u_res;
            s.inner_last = s.outer_last + 2;
            s.inner_first = s.outer_last + u_res;
            s.outer_prev = s.inner_first + 1;
        } else {
            s.outer_edges = v_res;
            s.inner_edges = v_res - 2;
            s.outer_prev = coord0;
            s.outer_first = coord0 + 1;
            s.outer_last = s.outer_first + v_res;
            s.inner_last = s.outer_last + 2;
            s.inner_first = s.outer_last + v_res;
        }
        s.uniform_quads(sink);
    }

    /// The boundary ring of a non-uniform pattern.
    fn boundary_ring(
        outer: &[i32],
        u_res: i32,
        v_res: i32,
        boundary: i32,
        triangulate: bool,
        sink: &mut FacetSink,
    ) {
        let res = [u_res, v_res, u_res, v_res];
        let uniform: Vec<bool> = (0..4).map(|e| outer[e] == res[e]).collect();
        let corner = |c: usize| uniform[c] && uniform[(c + 3) % 4];
        let (inner_u, inner_v) = (u_res - 2, v_res - 2);
        let inner_start = boundary;
        let mut s = Strip {
            quads: true,
            triangulate,
            ..Strip::default()
        };
        for e in 0..4 {
            s.outer_edges = outer[e];
            if e == 0 {
                s.outer_first = 0;
                s.outer_prev = inner_start - 1;
                s.outer_last = outer[0];
                s.inner_first = inner_start;
            } else {
                s.outer_first = s.outer_last;
                s.outer_prev = s.outer_first - 1;
                s.outer_last += outer[e];
                s.inner_first = s.inner_last;
            }
            let inner_edges = if e % 2 == 0 { inner_u } else { inner_v };
            s.inner_edges = inner_edges;
            // A degenerate inner ring runs back along itself.
            s.inner_reversed = match e {
                2 => inner_v == 0,
                3 => inner_u == 0,
                _ => false,
            };
            s.inner_last = match e {
                0 => inner_start + inner_u,
                3 => inner_start,
                _ => {
                    s.inner_first
                        + if s.inner_reversed {
                            -inner_edges
                        } else {
                            inner_edges
                        }
                }
            };
            if e == 3 {
                s.outer_last = 0;
            }
            if uniform[e] {
                s.split_first = !corner(e);
                s.split_last = !corner((e + 1) % 4);
                s.uniform_quads(sink);
            } else {
                s.split_first = true;
                s.split_last = true;
                s.non_uniform(sink);
            }
        }
    }

    /// A uniform pattern at rate `res` (> 1).
    pub(in super::super) fn uniform(mut res: i32, triangulate: bool, sink: &mut FacetSink) {
        let rings = (res + 1) / 2;
        let mut coord0 = 0;
        for _ in 0..rings {
            interior_ring(res, res, coord0, triangulate, sink);
            coord0 += 4 * res;
            res -= 2;
        }
    }

    /// A 1 × M (or M × 1) pattern without interior points.
    pub(in super::super) fn segmented(inner: [i32; 2], triangulate: bool, sink: &mut FacetSink) {
        single_strip(inner[0], inner[1], 0, triangulate, sink);
    }

    /// A non-uniform pattern (inner rates both above 1).
    pub(in super::super) fn non_uniform(
        outer: &[i32],
        inner: [i32; 2],
        boundary: i32,
        triangulate: bool,
        sink: &mut FacetSink,
    ) {
        let (mut u, mut v) = (inner[0], inner[1]);
        boundary_ring(outer, u, v, boundary, triangulate, sink);
        let rings = (u.min(v) + 1) / 2;
        let mut coord0 = boundary;
        for _ in 1..rings {
            u = (u - 2).max(0);
            v = (v - 2).max(0);
            interior_ring(u, v, coord0, triangulate, sink);
            coord0 += 2 * (u + v);
        }
    }
}

/// Triangles of the unit triangle (Loop).
pub(super) mod tri {
    use super::*;

    /// Facets of a uniform pattern at rate `res`.
    pub(in super::super) fn uniform_count(res: i64) -> i64 {
        res * res
    }

    /// Facets of a non-uniform pattern (inner rate above 2).
    pub(in super::super) fn non_uniform_count(outer: &[i64], inner: i64) -> i64 {
        let inner_edges = inner - 3;
        let interior = if inner_edges > 0 {
            uniform_count(inner_edges)
        } else {
            0
        };
        interior + outer.iter().map(|&o| inner_edges + o).sum::<i64>()
    }

    /// One ring of `res` edges per side starting at `coord0`, joined to the
    /// ring inside it.
    fn interior_ring(res: i32, c: i32, sink: &mut FacetSink) {
        match res {
            ..=0 => {}
            1 => sink.tri(c, c + 1, c + 2),
            2 => {
                sink.tri(c, c + 1, c + 5);
                sink.tri(c + 2, c + 3, c + 1);
                sink.tri(c + 4, c + 5, c + 3);
                sink.tri(c + 1, c + 3, c + 5);
            }
            _ => {
                let inner_edges = res - 3;
                let inner_start = c + 3 * res;
                let mut s = Strip {
                    inner_edges,
                    outer_edges: res,
                    outer_first: c,
                    outer_last: c + res,
                    outer_prev: inner_start - 1,
                    inner_first: inner_start,
                    inner_last: inner_start + inner_edges,
                    ..Strip::default()
                };
                s.uniform_tris(sink);
                s.outer_first += res;
                s.outer_last += res;
                s.outer_prev = s.outer_first - 1;
                s.inner_first += inner_edges;
                s.inner_last += inner_edges;
                s.uniform_tris(sink);
                s.outer_first += res;
                s.outer_last = c;
                s.outer_prev = s.outer_first - 1;
                s.inner_first += inner_edges;
                s.inner_last = inner_start;
                s.uniform_tris(sink);
            }
        }
    }

    /// The boundary ring of a non-uniform pattern.
    fn boundary_ring(outer: &[i32], inner: i32, boundary: i32, sink: &mut FacetSink) {
        let uniform: Vec<bool> = (0..3).map(|e| outer[e] == inner).collect();
        let corner = |c: usize| uniform[c] && uniform[(c + 2) % 3];
        let inner_edges = inner - 3;
        let mut s = Strip {
            inner_edges,
            ..Strip::default()
        };
        for e in 0..3 {
            s.outer_edges = outer[e];
            if e == 0 {
                s.outer_first = 0;
                s.outer_last = outer[0];
                s.outer_prev = boundary - 1;
                s.inner_first = boundary;
                s.inner_last = boundary + inner_edges;
            } else {
                s.outer_first = s.outer_last;
                s.outer_last = if e == 2 { 0 } else { s.outer_last + outer[e] };
                s.outer_prev = s.outer_first - 1;
                s.inner_first = s.inner_last;
                s.inner_last = if e == 2 {
                    boundary
                } else {
                    s.inner_last + inner_edges
                };
            }
            if uniform[e] {
                s.split_first = !corner(e);
                s.split_last = !corner((e + 1) % 3);
                s.uniform_tris(sink);
            } else {
                s.split_first = true;
                s.split_last = true;
                s.non_uniform(sink);
            }
        }
    }

    /// A uniform pattern at rate `res` (> 1).
    pub(in super::super) fn uniform(mut res: i32, sink: &mut FacetSink) {
        let rings = 1 + res / 3;
        let mut coord0 = 0;
        for _ in 0..rings {
            interior_ring(res, coord0, sink);
            coord0 += 3 * res;
            res -= 3;
        }
    }

    /// A non-uniform pattern (inner rate above 2).
    pub(in super::super) fn non_uniform(
        outer: &[i32],
        mut inner: i32,
        boundary: i32,
        sink: &mut FacetSink,
    ) {
        boundary_ring(outer, inner, boundary, sink);
        let rings = 1 + inner / 3;
        let mut coord0 = boundary;
        for _ in 1..rings {
            inner -= 3;
            interior_ring(inner, coord0, sink);
            coord0 += 3 * inner;
        }
    }
}

/// Quadrilateral sub-faces of an n-gon (quad schemes).
pub(super) mod qsub {
    use super::*;

    /// Facets of a uniform pattern of an `n`-gon at rate `res`.
    pub(in super::super) fn uniform_count(n: i64, res: i64, triangulate: bool) -> i64 {
        let h = res / 2;
        let quads = (h + i64::from(odd(res))) * h * n;
        let centre = if odd(res) {
            if n == 3 { 1 } else { n }
        } else {
            0
        };
        (quads << i64::from(triangulate)) + centre
    }

    /// Facets of a non-uniform pattern (inner rate above 1).
    pub(in super::super) fn non_uniform_count(outer: &[i64], inner: i64, triangulate: bool) -> i64 {
        let n = outer.len();
        let inner_edges = inner - 2;
        let interior = if inner_edges > 0 {
            uniform_count(n as i64, inner_edges, triangulate)
        } else {
            0
        };
        let boundary: i64 = (0..n)
            .map(|i| {
                if triangulate {
                    inner_edges + outer[i]
                } else if outer[i] == inner {
                    inner_edges + 1 + i64::from(inner != outer[(i + 1) % n])
                } else {
                    let e = inner_edges.max(outer[i]);
                    e + i64::from(!odd(e) && (odd(inner_edges) || odd(outer[i])))
                }
            })
            .sum();
        interior + boundary
    }

    /// The facets of the innermost ring (rate 1): a triangle, or a fan
    /// around the centre.
    fn center(n: i32, c: i32, sink: &mut FacetSink) {
        if n == 3 {
            sink.tri(c, c + 1, c + 2);
        } else {
            sink.fan(n, c);
        }
    }

    /// One ring of `res` edges per side starting at `coord0`, joined to the
    /// ring inside it.
    fn interior_ring(n: i32, res: i32, coord0: i32, triangulate: bool, sink: &mut FacetSink) {
        if res < 1 {
            return;
        }
        if res == 1 {
            center(n, coord0, sink);
            return;
        }
        let inner_res = res - 2;
        let inner_ring = coord0 + n * res;
        let mut s = Strip {
            quads: true,
            triangulate,
            outer_edges: res,
            inner_edges: inner_res,
            ..Strip::default()
        };
        for e in 0..n {
            s.outer_first = coord0 + e * res;
            s.inner_first = inner_ring + e * inner_res;
            s.outer_prev = if e > 0 { s.outer_first } else { inner_ring } - 1;
            if e < n - 1 {
                s.outer_last = s.outer_first + res;
                s.inner_last = s.inner_first + inner_res;
            } else {
                s.outer_last = coord0;
                s.inner_last = inner_ring;
            }
            s.uniform_quads(sink);
        }
    }

    /// The boundary ring of a non-uniform pattern.
    fn boundary_ring(
        outer: &[i32],
        inner: i32,
        boundary: i32,
        triangulate: bool,
        sink: &mut FacetSink,
    ) {
        let n = outer.len();
        let mut s = Strip {
            quads: true,
            triangulate,
            inner_edges: (inner - 2).max(0),
            ..Strip::default()
        };
        for e in 0..n {
            s.outer_edges = outer[e];
            if e > 0 {
                s.outer_first = s.outer_last;
                s.outer_prev = s.outer_first - 1;
                s.inner_first = s.inner_last;
            } else {
                s.outer_first = 0;
                s.outer_prev = boundary - 1;
                s.inner_first = boundary;
            }
            if e < n - 1 {
                s.outer_last = s.outer_first + s.outer_edges;
                s.inner_last = s.inner_first + s.inner_edges;
            } else {
                s.outer_last = 0;
                s.inner_last = boundary;
            }
            if outer[e] == inner && inner > 1 {
                s.split_first = outer[(e + n - 1) % n] != inner;
                s.split_last = outer[(e + 1) % n] != inner;
                s.uniform_quads(sink);
            } else {
                s.split_first = true;
                s.split_last = true;
                s.non_uniform(sink);
            }
        }
    }

    /// A uniform pattern of an `n`-gon at rate `res`.
    pub(in super::super) fn uniform(n: i32, mut res: i32, triangulate: bool, sink: &mut FacetSink) {
        if res == 1 {
            center(n, 0, sink);
            return;
        }
        let rings = (res + 1) / 2;
        let mut coord0 = 0;
        for _ in 0..rings {
            interior_ring(n, res, coord0, triangulate, sink);
            coord0 += n * res;
            res -= 2;
        }
    }

    /// A non-uniform pattern (inner rate above 1).
    pub(in super::super) fn non_uniform(
        outer: &[i32],
        mut inner: i32,
        boundary: i32,
        triangulate: bool,
        sink: &mut FacetSink,
    ) {
        let n = outer.len() as i32;
        boundary_ring(outer, inner, boundary, triangulate, sink);
        let rings = (inner + 1) / 2;
        let mut coord0 = boundary;
        for _ in 1..rings {
            inner = (inner - 2).max(0);
            interior_ring(n, inner, coord0, triangulate, sink);
            coord0 += n * inner;
        }
    }
}
