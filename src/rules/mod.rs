//! The subdivision rules themselves, free of any mesh: given a small
//! neighbourhood (face sizes, sharpness values, counts), compute the weights
//! ("masks") that make a child vertex out of parent vertices — the
//! counterpart of OpenSubdiv's `Sdc` layer.
//!
//! A topology driver gathers each neighbourhood, calls the [`SchemeRules`]
//! method for the kind of child vertex, and applies the [`Mask`] it gets back.
//! The weights are bit-for-bit those of OpenSubdiv 3.5's `Sdc::Scheme` when it
//! fills masks of `PrimvarRefinerReal<T>` (whose mask weights have type `T`).
//!
//! # Applying masks (what each weight multiplies)
//!
//! The order matters for reproducing OpenSubdiv to the last bit:
//!
//! * **face point** ([`SchemeRules::face_vertex_mask`]): `mask.vertex[i]` times
//!   the face's `i`-th vertex, in face order.
//! * **edge point** ([`SchemeRules::edge_vertex_mask`]): `mask.vertex[0]` and
//!   `[1]` times the edge's two vertices (edge order), then `mask.face[i]`
//!   times, for the edge's `i`-th face, either that face's child face point
//!   (`face_weights_for_centers`, Catmull-Clark) or the face's vertex two
//!   places after the edge's position in the face (Loop: the vertex opposite
//!   the edge).
//! * **vertex point** ([`SchemeRules::vertex_vertex_mask`]): first
//!   `mask.face[i]` times the child face point of the vertex's `i`-th face
//!   (always face centres when present), then `mask.edge[i]` times the other
//!   vertex of the vertex's `i`-th edge, then `mask.vertex[0]` times the vertex
//!   itself.
//! * **limit** ([`SchemeRules::vertex_limit_masks`]): first `face[i]` times the
//!   vertex two places after the vertex in its `i`-th face (the diagonal
//!   vertex of a quad; `face_weights_for_centers` is false), then `edge[i]`
//!   times the other vertex of the `i`-th edge, then `vertex[0]` times the
//!   vertex itself. The two tangent masks always have the same lengths.
//!
//! Only the first `len()` weights of each `Vec` are meaningful; lengths can be
//! smaller than the valence (e.g. a corner mask has no edge weights).

pub mod crease;

mod bilinear;
mod catmark;
mod loop_scheme;

use crate::options::{CreasingMethod, Options, Scheme, TriangleSubdivision};
use crate::real::Real;

/// Sharpness of a smooth edge or vertex.
pub const SHARPNESS_SMOOTH: f32 = 0.0;

/// Sharpness from which an edge or vertex is infinitely sharp.
pub const SHARPNESS_INFINITE: f32 = 10.0;

/// Which refinement rule applies at a vertex (OpenSubdiv's `Sdc::Crease::Rule`,
/// without its "unknown": callers always know the rule).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Rule {
    /// No sharp edge and no vertex sharpness.
    Smooth,
    /// Exactly one sharp edge: refined like a smooth vertex.
    Dart,
    /// Exactly two sharp edges: refined along the curve they form.
    Crease,
    /// Three or more sharp edges, or a sharp vertex: does not move.
    Corner,
}

/// Weights of one mask, reused between calls: once the `Vec`s are large
/// enough, computing a mask allocates nothing.
///
/// See the [module documentation](self) for what each weight multiplies.
#[derive(Debug, Clone, Default)]
pub struct Mask<T> {
    /// Weights of the vertex itself (a vertex or limit mask: one), or of the
    /// edge's two end vertices, or of the face's vertices.
    pub vertex: Vec<T>,
    /// Weights of the far ends of the vertex's incident edges.
    pub edge: Vec<T>,
    /// Weights per incident face: of its child face point when
    /// `face_weights_for_centers`, otherwise of one of its vertices.
    pub face: Vec<T>,
    /// Whether `face` weights apply to the faces' child face points.
    pub face_weights_for_centers: bool,
}

fn zeroed<T: Real>(v: &mut Vec<T>, len: usize) {
    v.clear();
    v.resize(len, T::ZERO);
}

impl<T: Real> Mask<T> {
    /// An empty mask.
    pub fn new() -> Self {
        Mask {
            vertex: Vec::new(),
            edge: Vec::new(),
            face: Vec::new(),
            face_weights_for_centers: false,
        }
    }

    /// Sets the number of each kind of weight, all zero, and clears
    /// `face_weights_for_centers`. Allocates only to grow past the capacity.
    pub fn reset(&mut self, vertices: usize, edges: usize, faces: usize) {
        zeroed(&mut self.vertex, vertices);
        zeroed(&mut self.edge, edges);
        zeroed(&mut self.face, faces);
        self.face_weights_for_centers = false;
    }

    /// The sum of all the weights (1 for a refinement or limit position mask,
    /// 0 for a tangent mask), summed vertex, edge then face weights.
    pub fn sum(&self) -> T {
        let mut s = T::ZERO;
        for &w in self.vertex.iter().chain(&self.edge).chain(&self.face) {
            s += w;
        }
        s
    }
}

/// An edge about to get its child vertex.
#[derive(Debug, Clone, Copy)]
pub struct EdgeNeighborhood<'a> {
    /// The parent edge's sharpness.
    pub sharpness: f32,
    /// The sizes of the faces incident to the edge, in the edge's face order:
    /// one entry per face (its length is the edge's face count).
    pub face_sizes: &'a [u32],
}

/// A vertex about to get its child vertex, or whose limit is wanted.
#[derive(Debug, Clone, Copy)]
pub struct VertexNeighborhood<'a> {
    /// The parent vertex's own sharpness.
    pub sharpness: f32,
    /// Parent sharpness of each incident edge, in vertex-edge order; its length
    /// is the number of incident edges.
    pub edge_sharpness: &'a [f32],
    /// Number of incident faces.
    pub face_count: usize,
    /// Sharpness of the vertex's child vertex (next level). Only read by
    /// [`SchemeRules::vertex_vertex_mask`] when the parent and child rules differ.
    pub child_sharpness: f32,
    /// Sharpness of each child edge at the child vertex, in the same order as
    /// `edge_sharpness`: what
    /// [`subdivide_edge_sharpnesses_around_vertex`](crease::subdivide_edge_sharpnesses_around_vertex)
    /// gives (the child level's edge sharpness is equivalent). Only read by
    /// [`SchemeRules::vertex_vertex_mask`] when the parent and child rules
    /// differ; may be empty otherwise (and for limit masks).
    pub child_edge_sharpness: &'a [f32],
}

impl VertexNeighborhood<'_> {
    /// Number of incident edges.
    #[inline]
    pub fn edge_count(&self) -> usize {
        self.edge_sharpness.len()
    }
}

/// A vertex mask of one of the three simple kinds, held in closed form so
/// that two of them can be blended without a second weight buffer.
#[derive(Debug, Clone, Copy)]
enum VertexMaskKind<T> {
    /// The vertex stays where it is.
    Corner,
    /// 3/4 on the vertex, 1/8 on each of two edges (of `edges`).
    Crease { edges: usize, ends: [usize; 2] },
    /// The same weight on every edge and (if any) face.
    Smooth {
        valence: usize,
        vertex: T,
        edge: T,
        face: Option<T>,
    },
}

impl<T: Real> VertexMaskKind<T> {
    fn vertex_weight(&self) -> T {
        match *self {
            VertexMaskKind::Corner => T::ONE,
            VertexMaskKind::Crease { .. } => T::from_f64(0.75),
            VertexMaskKind::Smooth { vertex, .. } => vertex,
        }
    }

    fn edge_count(&self) -> usize {
        match *self {
            VertexMaskKind::Corner => 0,
            VertexMaskKind::Crease { edges, .. } => edges,
            VertexMaskKind::Smooth { valence, .. } => valence,
        }
    }

    fn edge_weight(&self, i: usize) -> T {
        match *self {
            VertexMaskKind::Corner => T::ZERO,
            VertexMaskKind::Crease { ends, .. } => {
                if i == ends[0] || i == ends[1] {
                    T::from_f64(0.125)
                } else {
                    T::ZERO
                }
            }
            VertexMaskKind::Smooth { edge, .. } => edge,
        }
    }

    fn face_count(&self) -> usize {
        match *self {
            VertexMaskKind::Smooth {
                valence,
                face: Some(_),
                ..
            } => valence,
            _ => 0,
        }
    }

    fn face_weight(&self) -> T {
        match *self {
            VertexMaskKind::Smooth { face: Some(f), .. } => f,
            _ => T::ZERO,
        }
    }

    fn write(&self, mask: &mut Mask<T>) {
        mask.reset(1, self.edge_count(), self.face_count());
        mask.vertex[0] = self.vertex_weight();
        for (i, w) in mask.edge.iter_mut().enumerate() {
            *w = self.edge_weight(i);
        }
        let f = self.face_weight();
        for w in &mut mask.face {
            *w = f;
        }
        // Only Catmull-Clark's smooth mask has face weights, on face points.
        mask.face_weights_for_centers = self.face_count() > 0;
    }

    /// `mask = parent_weight · mask + child_weight · self`, where `mask` holds
    /// the parent's mask. The child mask has at least the parent's weights;
    /// a kind of weight the parent lacks is taken from the child alone.
    fn blend_into(&self, mask: &mut Mask<T>, parent_weight: T, child_weight: T) {
        mask.vertex[0] = parent_weight * mask.vertex[0] + child_weight * self.vertex_weight();

        let edges = self.edge_count();
        if edges > 0 {
            if mask.edge.is_empty() {
                mask.edge.resize(edges, T::ZERO);
                for (i, w) in mask.edge.iter_mut().enumerate() {
                    *w = child_weight * self.edge_weight(i);
                }
            } else {
                for (i, w) in mask.edge.iter_mut().enumerate().take(edges) {
                    *w = parent_weight * *w + child_weight * self.edge_weight(i);
                }
            }
        }

        let faces = self.face_count();
        if faces > 0 {
            let f = self.face_weight();
            if mask.face.is_empty() {
                mask.face.resize(faces, child_weight * f);
                mask.face_weights_for_centers = true;
            } else {
                for w in mask.face.iter_mut().take(faces) {
                    *w = parent_weight * *w + child_weight * f;
                }
            }
        }
    }
}

/// The masks of one scheme under one set of options.
///
/// Of the options, only the scheme and [`TriangleSubdivision`] change masks;
/// the [`CreasingMethod`] changes sharpness (and, through it, the fractional
/// weights of [`vertex_vertex_mask`](Self::vertex_vertex_mask)); boundary
/// interpolation is the driver's business (boundary edges are infinitely
/// sharp; with `EdgeAndCorner`, vertices with a single face are infinitely
/// sharp too).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SchemeRules {
    scheme: Scheme,
    creasing: CreasingMethod,
    triangles: TriangleSubdivision,
}

impl SchemeRules {
    /// The rules of `options.scheme` under `options`.
    pub fn new(options: &Options) -> Self {
        SchemeRules {
            scheme: options.scheme,
            creasing: options.creasing,
            triangles: options.triangles,
        }
    }

    /// The scheme.
    pub fn scheme(&self) -> Scheme {
        self.scheme
    }

    /// The creasing method.
    pub fn creasing(&self) -> CreasingMethod {
        self.creasing
    }

    /// Face point: `1/n` on each of the face's `n` vertices (every scheme; Loop
    /// never makes face points but the mask is defined all the same).
    pub fn face_vertex_mask<T: Real>(&self, face_size: usize, mask: &mut Mask<T>) {
        mask.reset(face_size, 0, 0);
        let w = T::ONE / T::from_f64(face_size as f64);
        for v in &mut mask.vertex {
            *v = w;
        }
    }

    /// Edge point.
    ///
    /// `parent_rule` is [`Rule::Smooth`] for a smooth parent edge (sharpness
    /// `<= 0`) and [`Rule::Crease`] for a sharp one; `child_rule` is the rule of
    /// the child vertex, i.e. the number of its two child edges still sharp
    /// mapped through [`crease::vertex_rule_from_sharp_edge_count`] (Smooth,
    /// Dart or Crease), and Crease for an infinitely sharp edge.
    ///
    /// * smooth parent → the scheme's smooth mask;
    /// * sharp parent, child crease → the midpoint `1/2, 1/2`;
    /// * sharp parent, any other child rule (Dart included, which Chaikin
    ///   creasing can produce) → with `s` the parent sharpness, `s` times the
    ///   midpoint plus `1 - s` times the smooth mask. `s` is not clamped, as in
    ///   OpenSubdiv (see [`crease::fractional_weight_at_edge`]).
    ///
    /// Bilinear always gives the midpoint. `mask.vertex`: the two end vertices;
    /// `mask.face`: one weight per incident face — Catmull-Clark: on the face's
    /// face point (`face_weights_for_centers`), Loop: on the face's vertex
    /// opposite the edge.
    pub fn edge_vertex_mask<T: Real>(
        &self,
        e: &EdgeNeighborhood,
        parent_rule: Rule,
        child_rule: Rule,
        mask: &mut Mask<T>,
    ) {
        if self.scheme == Scheme::Bilinear {
            crease_edge_mask(mask);
            return;
        }
        if parent_rule == Rule::Smooth {
            self.smooth_edge_mask(e, mask);
            return;
        }
        if child_rule == Rule::Crease {
            crease_edge_mask(mask);
            return;
        }
        // The crease of the parent fades into the smooth child.
        self.smooth_edge_mask(e, mask);
        let p = T::from_f32(e.sharpness);
        let c = T::ONE - p;
        let half = T::from_f64(0.5);
        for w in &mut mask.vertex {
            *w = p * half + c * *w;
        }
        for w in &mut mask.face {
            *w *= c;
        }
    }

    fn smooth_edge_mask<T: Real>(&self, e: &EdgeNeighborhood, mask: &mut Mask<T>) {
        match self.scheme {
            Scheme::Catmark => catmark::smooth_edge_mask(e.face_sizes, self.triangles, mask),
            Scheme::Loop => loop_scheme::smooth_edge_mask(e.face_sizes.len(), mask),
            Scheme::Bilinear => crease_edge_mask(mask),
        }
    }

    /// Vertex point.
    ///
    /// `parent_rule` is the parent vertex's rule and `child_rule` its child
    /// vertex's rule (both from [`crease::vertex_rule`] or the driver's tags).
    ///
    /// * parent Smooth or Dart → the smooth mask, whatever the child rule;
    /// * parent Crease → 3/4 on the vertex and 1/8 on each of the two edges
    ///   given by [`crease::crease_ends`] of the parent edge sharpness;
    /// * parent Corner → the vertex itself;
    /// * if the child rule differs, the child's mask (crease ends taken from
    ///   `child_edge_sharpness`; Dart counts as smooth) is blended in:
    ///   `w · parent + (1 - w) · child` with `w` from
    ///   [`crease::fractional_weight_at_vertex`].
    ///
    /// Bilinear always keeps the vertex. `mask.vertex`: 1 weight;
    /// `mask.edge`: per incident edge; `mask.face`: per incident face
    /// (Catmull-Clark smooth only, on face points).
    pub fn vertex_vertex_mask<T: Real>(
        &self,
        v: &VertexNeighborhood,
        parent_rule: Rule,
        child_rule: Rule,
        mask: &mut Mask<T>,
    ) {
        if self.scheme == Scheme::Bilinear {
            VertexMaskKind::<T>::Corner.write(mask);
            return;
        }
        let parent = match parent_rule {
            Rule::Smooth | Rule::Dart => {
                self.smooth_vertex_kind::<T>(v.face_count).write(mask);
                return;
            }
            Rule::Crease => VertexMaskKind::Crease {
                edges: v.edge_count(),
                ends: crease::crease_ends(v.edge_sharpness),
            },
            Rule::Corner => VertexMaskKind::Corner,
        };
        parent.write(mask);
        if child_rule == parent_rule {
            return;
        }
        let child = match child_rule {
            Rule::Smooth | Rule::Dart => self.smooth_vertex_kind::<T>(v.face_count),
            Rule::Crease => VertexMaskKind::Crease {
                edges: v.edge_count(),
                ends: crease::crease_ends(v.child_edge_sharpness),
            },
            Rule::Corner => VertexMaskKind::Corner,
        };
        let child_edges = match self.creasing {
            CreasingMethod::Uniform => None,
            CreasingMethod::Chaikin => Some(v.child_edge_sharpness),
        };
        let w = crease::fractional_weight_at_vertex(
            v.sharpness,
            v.child_sharpness,
            v.edge_sharpness,
            child_edges,
        );
        let p = T::from_f32(w);
        child.blend_into(mask, p, T::ONE - p);
    }

    fn smooth_vertex_kind<T: Real>(&self, valence: usize) -> VertexMaskKind<T> {
        match self.scheme {
            Scheme::Catmark => {
                let (vertex, edge) = catmark::smooth_vertex_weights(valence);
                VertexMaskKind::Smooth {
                    valence,
                    vertex,
                    edge,
                    face: Some(edge),
                }
            }
            Scheme::Loop => {
                let (vertex, edge) = loop_scheme::smooth_vertex_weights(valence);
                VertexMaskKind::Smooth {
                    valence,
                    vertex,
                    edge,
                    face: None,
                }
            }
            Scheme::Bilinear => VertexMaskKind::Corner,
        }
    }

    /// Limit position and the two limit tangents at a vertex of the last
    /// level, for the vertex's `rule` at that level (OpenSubdiv's
    /// `ComputeVertexLimitMask`). For a crease, the crease edges are found from
    /// `v.edge_sharpness` (semi-sharp edges count as sharp); the child fields
    /// of `v` are not read.
    ///
    /// Tangent conventions (OpenSubdiv's): the first tangent points along the
    /// vertex's first edge (for a crease: along the first crease edge, away
    /// from the second), the second lies in the tangent plane so that
    /// `tan1 × tan2` is the normal (for a crease or boundary: pointing across
    /// the faces between the two crease edges). Magnitudes are not normalised
    /// and follow OpenSubdiv's scale factors (see each scheme). Tangent
    /// weights sum to zero; both tangent masks have the same lengths.
    pub fn vertex_limit_masks<T: Real>(
        &self,
        v: &VertexNeighborhood,
        rule: Rule,
        pos: &mut Mask<T>,
        tan1: &mut Mask<T>,
        tan2: &mut Mask<T>,
    ) {
        self.vertex_limit_position_mask(v, rule, pos);
        match self.scheme {
            Scheme::Bilinear => bilinear::limit_tangents(tan1, tan2),
            Scheme::Catmark => match rule {
                Rule::Smooth | Rule::Dart => catmark::smooth_limit_tangents(v, tan1, tan2),
                Rule::Crease => {
                    let ends = crease::crease_ends(v.edge_sharpness);
                    catmark::crease_limit_tangents(v, ends, tan1, tan2);
                }
                Rule::Corner => catmark::corner_limit_tangents(v.edge_count(), tan1, tan2),
            },
            Scheme::Loop => match rule {
                Rule::Smooth | Rule::Dart => loop_scheme::smooth_limit_tangents(v, tan1, tan2),
                Rule::Crease => {
                    let ends = crease::crease_ends(v.edge_sharpness);
                    loop_scheme::crease_limit_tangents(v, ends, tan1, tan2);
                }
                Rule::Corner => loop_scheme::corner_limit_tangents(v.edge_count(), tan1, tan2),
            },
        }
    }

    /// Limit position only (see [`vertex_limit_masks`](Self::vertex_limit_masks)).
    ///
    /// * Corner (and Bilinear, always): the vertex itself;
    /// * Crease: 2/3 on the vertex, 1/6 on each crease edge (both schemes);
    /// * Smooth/Dart: the scheme's limit stencil — Catmull-Clark: with `n`
    ///   faces, `1/(n(n+5))` per face (on the face's diagonal vertex), four
    ///   times that per edge, the rest on the vertex (valence 4: 1/36, 1/9,
    ///   4/9; valence 2: the vertex itself); Loop: with `n` faces, 1/12 per
    ///   neighbour and 1/2 on the vertex when `n = 6`, otherwise
    ///   `1/(n + 3/(8w))` per neighbour with `w` Loop's refinement edge weight
    ///   `(5/8 - (3/8 + cos(2π/n)/4)²)/n`, the rest on the vertex.
    pub fn vertex_limit_position_mask<T: Real>(
        &self,
        v: &VertexNeighborhood,
        rule: Rule,
        pos: &mut Mask<T>,
    ) {
        if self.scheme == Scheme::Bilinear {
            corner_limit_mask(pos);
            return;
        }
        match rule {
            Rule::Smooth | Rule::Dart => match self.scheme {
                Scheme::Catmark => catmark::smooth_limit_mask(v.face_count, pos),
                _ => loop_scheme::smooth_limit_mask(v.face_count, pos),
            },
            Rule::Crease => {
                let ends = crease::crease_ends(v.edge_sharpness);
                crease_limit_mask(v.edge_count(), ends, pos);
            }
            Rule::Corner => corner_limit_mask(pos),
        }
    }
}

/// The midpoint of the edge.
fn crease_edge_mask<T: Real>(mask: &mut Mask<T>) {
    mask.reset(2, 0, 0);
    let half = T::from_f64(0.5);
    mask.vertex[0] = half;
    mask.vertex[1] = half;
}

/// The vertex itself, as its limit.
fn corner_limit_mask<T: Real>(pos: &mut Mask<T>) {
    pos.reset(1, 0, 0);
    pos.vertex[0] = T::ONE;
}

/// The limit of a uniform cubic B-spline along the crease: 1/6, 2/3, 1/6
/// (Catmull-Clark and Loop alike: both refine creases with 1/8, 3/4, 1/8).
fn crease_limit_mask<T: Real>(edges: usize, ends: [usize; 2], pos: &mut Mask<T>) {
    pos.reset(1, edges, 0);
    pos.vertex[0] = T::from_f64(4.0 / 6.0);
    let e = T::from_f64(1.0 / 6.0);
    pos.edge[ends[0]] = e;
    pos.edge[ends[1]] = e;
}

#[cfg(test)]
mod tests;
