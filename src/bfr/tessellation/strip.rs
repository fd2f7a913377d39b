//! Facets between two concentric rings of coordinates, and the sink they are
//! written to.
//!
//! Every tessellation pattern is a set of concentric rings of coordinates
//! (the boundary first, then inward). The facets between one ring and the
//! next are made strip by strip, one strip per edge of the outer ring:
//!
//! ```text
//!   outer_prev ─── inner_first ··· inner ··· inner_last ─── outer_last+1
//!       │                                                        │
//!   outer_first ── outer_first+1 ········· outer_first+n-1 ── outer_last
//! ```
//!
//! A ring wraps around, so the first and last points of either row need not
//! follow from their neighbours' indices: the strip is given them. Uniform
//! strips (the inner row has two fewer edges for quads, three for
//! triangles) are regular rows of quads or a saw-tooth of triangles; other
//! strips walk both rows in step along a common integer parameter and pick,
//! facet by facet, the most vertical edge — keeping quads, when asked, where
//! they are not too slanted, and mirroring the first half's choices in the
//! second so the strip is symmetric. These choices are OpenSubdiv's
//! (`Bfr::Tessellation`), so the facets are the same, index by index.

/// The facets of a pattern as they are made: `size` indices each, a
/// triangle among 4-index facets padded with -1 (as OpenSubdiv pads it).
pub(super) struct FacetSink {
    pub(super) indices: Vec<i32>,
    pub(super) size: usize,
}

impl FacetSink {
    /// Appends triangle (a, b, c).
    pub(super) fn tri(&mut self, a: i32, b: i32, c: i32) {
        self.indices.extend_from_slice(&[a, b, c]);
        if self.size == 4 {
            self.indices.push(-1);
        }
    }

    /// Appends quad (a, b, c, d) as a quad (`sign` 0), or as two triangles
    /// split along the diagonal from `a` (`sign` > 0) or from `b` (< 0).
    pub(super) fn quad(&mut self, [a, b, c, d]: [i32; 4], sign: i32) {
        if sign == 0 {
            debug_assert_eq!(self.size, 4, "a quad among triangles");
            self.indices.extend_from_slice(&[a, b, c, d]);
        } else if sign > 0 {
            self.tri(a, b, c);
            self.tri(c, d, a);
        } else {
            self.tri(c, d, b);
            self.tri(a, b, d);
        }
    }

    /// Appends the `n` triangles joining the ring of `n` coordinates from
    /// `start` to the centre coordinate `start + n`.
    pub(super) fn fan(&mut self, n: i32, start: i32) {
        for i in 1..=n {
            let next = if i < n { i } else { 0 };
            self.tri(start + i - 1, start + next, start + n);
        }
    }

    /// The number of facets so far.
    pub(super) fn len(&self) -> usize {
        self.indices.len() / self.size
    }

    /// Whether facet `index` is a quad.
    fn is_quad(&self, index: usize) -> bool {
        self.size == 4 && self.indices[index * 4 + 3] >= 0
    }
}

/// One strip of facets between an outer and an inner row of coordinates.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Strip {
    /// Quads (else triangles) are the strip's natural facets.
    pub(super) quads: bool,
    /// Quads are split into triangles.
    pub(super) triangulate: bool,
    /// The inner row runs backwards (a degenerate inner ring).
    pub(super) inner_reversed: bool,
    /// The first facet belongs to another strip.
    pub(super) exclude_first: bool,
    /// The first corner is a single triangle.
    pub(super) split_first: bool,
    /// The last corner is a single triangle.
    pub(super) split_last: bool,
    /// The last corner's quad is made by this strip.
    pub(super) include_last: bool,
    /// Edges of the outer row.
    pub(super) outer_edges: i32,
    /// Edges of the inner row between its first and last points.
    pub(super) inner_edges: i32,
    /// Index of the outer row's first point.
    pub(super) outer_first: i32,
    /// Index of the outer row's last point.
    pub(super) outer_last: i32,
    /// Index of the outer ring's point before the first (the inner corner).
    pub(super) outer_prev: i32,
    /// Index of the inner row's first point.
    pub(super) inner_first: i32,
    /// Index of the inner row's last point.
    pub(super) inner_last: i32,
}

impl Strip {
    /// The quad strip of a uniform edge: the inner row has two edges fewer
    /// than the outer. Its quads split toward the strip's middle from both
    /// ends when triangulated.
    pub(super) fn uniform_quads(&self, sink: &mut FacetSink) {
        debug_assert!(self.quads && self.inner_edges == self.outer_edges - 2);
        let sign = i32::from(self.triangulate);
        let (out0, in0) = (self.outer_first, self.inner_first);
        if self.split_first {
            sink.tri(out0, out0 + 1, in0);
        } else if !self.exclude_first {
            sink.quad([out0, out0 + 1, in0, self.outer_prev], sign);
        }
        let step = if self.inner_reversed { -1 } else { 1 };
        let mut outer = out0 + 1;
        let mut inner = in0;
        for i in 1..=self.inner_edges {
            let half_sign = if i > self.inner_edges / 2 {
                -sign
            } else {
                sign
            };
            let next_inner = if i < self.inner_edges {
                inner + step
            } else {
                self.inner_last
            };
            sink.quad([outer, outer + 1, next_inner, inner], half_sign);
            outer += 1;
            inner += step;
        }
        if self.split_last {
            sink.tri(outer, self.outer_last, self.inner_last);
        } else if self.include_last {
            sink.quad(
                [outer, self.outer_last, self.outer_last + 1, self.inner_last],
                -sign,
            );
        }
    }

    /// The saw-tooth of triangles of a uniform triangular edge: the inner
    /// row has three edges fewer than the outer.
    pub(super) fn uniform_tris(&self, sink: &mut FacetSink) {
        debug_assert!(!self.quads && !self.exclude_first && !self.include_last);
        let (out0, in0) = (self.outer_first, self.inner_first);
        if self.split_first {
            sink.tri(out0, out0 + 1, in0);
        } else {
            sink.tri(out0, out0 + 1, self.outer_prev);
            sink.tri(in0, self.outer_prev, out0 + 1);
        }
        sink.tri(out0 + 1, out0 + 2, in0);
        // Below inner edge i: a triangle on it, then one on the outer edge.
        for i in 1..=self.inner_edges {
            let (outer, inner) = (out0 + 1 + i, in0 + i - 1);
            let next_inner = if i < self.inner_edges {
                inner + 1
            } else {
                self.inner_last
            };
            sink.tri(next_inner, inner, outer);
            sink.tri(outer, outer + 1, next_inner);
        }
        if self.split_last {
            let outer = out0 + 2 + self.inner_edges;
            sink.tri(outer, self.outer_last, self.inner_last);
        }
    }

    /// The general strip between rows of unrelated resolutions (both ends
    /// split). Both rows are parameterized over `[0, M·N]` (M inner and N
    /// outer edges, a triangular inner row offset by half an edge); each
    /// facet advances along the outer row, the inner row or both (a quad).
    pub(super) fn non_uniform(&self, sink: &mut FacetSink) {
        debug_assert!(self.split_first && self.split_last);
        let m = self.inner_edges + if self.quads { 2 } else { 3 };
        let n = self.outer_edges;
        let (dt_outer, dt_inner) = (m, n);
        let (dt_min, dt_max) = (dt_inner.min(dt_outer), dt_inner.max(dt_outer));
        // The steepest "vertical" edge a kept quad may have.
        let slope_max = if dt_max / 2 < dt_min {
            dt_min - 1
        } else {
            dt_max / 2
        };

        let t_outer_last = dt_outer * n;
        let t_outer_middle = t_outer_last / 2;
        let (t_inner_offset, t_inner_last) = if self.quads {
            (0, dt_inner * (m - 1))
        } else {
            let offset = dt_inner / 2;
            (offset, dt_inner * (m - 1) + offset - dt_inner)
        };
        let step = if self.inner_reversed { -1 } else { 1 };

        // The two current points of each row: parameter and coordinate index.
        let (mut t_outer0, mut c_outer0) = (0, self.outer_first);
        let (mut t_outer1, mut c_outer1) = (
            dt_outer,
            if n == 1 {
                self.outer_last
            } else {
                self.outer_first + 1
            },
        );
        let (mut t_inner0, mut c_inner0) = (t_inner_offset + dt_inner, self.inner_first);
        let mut t_inner1 = t_inner0 + if self.inner_edges != 0 { dt_inner } else { 0 };
        let mut c_inner1 = if self.inner_edges == 1 {
            self.inner_last
        } else {
            self.inner_first + step
        };

        let keep_quads = self.quads && !self.triangulate;
        let odd = |x: i32| x & 1 != 0;
        let expected = if keep_quads {
            let larger = self.inner_edges.max(self.outer_edges);
            // A symmetric middle facet when either side is odd.
            larger + i32::from(!odd(larger) && (odd(self.inner_edges) || odd(self.outer_edges)))
        } else {
            self.inner_edges + self.outer_edges
        };
        let leading = expected / 2;
        let middle_count = expected & 1;
        let middle = if middle_count != 0 { leading } else { -1 };
        let middle_quad = keep_quads && odd(self.outer_edges) && odd(self.inner_edges);
        let base = sink.len();

        for facet in 0..expected {
            let (mut tri_outer, mut tri_inner, mut quad) = (false, false, false);
            if facet == middle {
                if middle_quad {
                    quad = true;
                } else if odd(self.outer_edges) {
                    tri_outer = true;
                } else {
                    tri_inner = true;
                }
            } else if t_inner1 == t_inner0 {
                tri_outer = true;
            } else if t_outer1 == t_outer0 {
                tri_inner = true;
            } else {
                if keep_quads {
                    quad = if facet >= leading {
                        // Mirror the first half's facet.
                        let mirrored = leading - 1 - (facet - leading - middle_count);
                        sink.is_quad(base + mirrored as usize)
                    } else if t_inner1 > t_outer_middle || t_outer1 > t_outer_middle {
                        false
                    } else {
                        (t_outer1 - t_inner1).abs() <= slope_max
                    };
                }
                if !quad {
                    // The diagonal spanning the shorter interval (ties
                    // broken by the side of the middle, for symmetry).
                    let to_outer1 = t_outer1 - t_inner0;
                    let to_inner1 = t_inner1 - t_outer0;
                    let use_outer = if to_outer1 == to_inner1 {
                        t_outer1 > t_outer_middle
                    } else {
                        to_outer1 < to_inner1
                    };
                    tri_outer = use_outer;
                    tri_inner = !use_outer;
                }
            }

            if tri_outer {
                sink.tri(c_outer0, c_outer1, c_inner0);
            } else if tri_inner {
                sink.tri(c_inner1, c_inner0, c_outer0);
            } else {
                sink.quad([c_outer0, c_outer1, c_inner1, c_inner0], 0);
            }

            if tri_outer || quad {
                t_outer0 = t_outer1;
                c_outer0 = c_outer1;
                t_outer1 += dt_outer;
                c_outer1 += 1;
                if t_outer1 >= t_outer_last {
                    t_outer1 = t_outer_last;
                    c_outer1 = self.outer_last;
                }
            }
            if tri_inner || quad {
                t_inner0 = t_inner1;
                c_inner0 = c_inner1;
                t_inner1 += dt_inner;
                c_inner1 += step;
                if t_inner1 >= t_inner_last {
                    t_inner1 = t_inner_last;
                    c_inner1 = self.inner_last;
                }
            }
        }
    }
}
