//! Sharpness arithmetic and vertex rules: the part of the subdivision rules
//! that does not depend on the scheme (OpenSubdiv's `Sdc::Crease`).
//!
//! Everything here works on `f32` sharpness with `f32` arithmetic, exactly as
//! OpenSubdiv stores and decays sharpness, so that the same values (and hence
//! the same rules and fractional weights) come out at every level.
//!
//! Conventions:
//! * a sharpness `<= 0` is smooth, `>= 10` is infinitely sharp, anything in
//!   between is semi-sharp;
//! * subdividing a semi-sharp value lowers it by one level; a value that drops
//!   to zero or below becomes exactly `0.0`; infinite values become exactly
//!   `10.0` (see [`subdivide_uniform_sharpness`]);
//! * edge and vertex sharpness slices are in the vertex's edge order.

use super::{Rule, SHARPNESS_INFINITE, SHARPNESS_SMOOTH};
use crate::options::CreasingMethod;

/// Whether `s` is smooth: zero or negative.
#[inline]
pub fn is_smooth(s: f32) -> bool {
    s <= SHARPNESS_SMOOTH
}

/// Whether `s` is sharp at all: strictly positive (semi-sharp or infinite).
#[inline]
pub fn is_sharp(s: f32) -> bool {
    s > SHARPNESS_SMOOTH
}

/// Whether `s` is infinitely sharp: `>= SHARPNESS_INFINITE` (10).
#[inline]
pub fn is_infinite(s: f32) -> bool {
    s >= SHARPNESS_INFINITE
}

/// Whether `s` is semi-sharp: strictly between smooth and infinite.
#[inline]
pub fn is_semi_sharp(s: f32) -> bool {
    SHARPNESS_SMOOTH < s && s < SHARPNESS_INFINITE
}

/// Sharpness one level down under uniform decay: smooth stays `0`, infinite
/// becomes exactly `10`, a value above one loses one, anything else becomes `0`.
///
/// ```
/// use subdiv::rules::crease::subdivide_uniform_sharpness as decay;
/// assert_eq!(decay(2.5), 1.5);
/// assert_eq!(decay(0.7), 0.0);
/// assert_eq!(decay(10.0), 10.0);
/// ```
#[inline]
pub fn subdivide_uniform_sharpness(s: f32) -> f32 {
    if is_smooth(s) {
        SHARPNESS_SMOOTH
    } else if is_infinite(s) {
        SHARPNESS_INFINITE
    } else if s > 1.0 {
        s - 1.0
    } else {
        SHARPNESS_SMOOTH
    }
}

/// Sharpness of a vertex's child vertex. Vertex sharpness always decays
/// uniformly, whatever the creasing method.
#[inline]
pub fn subdivide_vertex_sharpness(s: f32) -> f32 {
    subdivide_uniform_sharpness(s)
}

/// Sum and count of the semi-sharp values in `values` (summed in order, in `f32`).
fn semi_sharp_sum(values: &[f32]) -> (f32, usize) {
    values
        .iter()
        .filter(|&&s| is_semi_sharp(s))
        .fold((0.0f32, 0usize), |(sum, n), &s| (sum + s, n + 1))
}

/// Chaikin's decay of one semi-sharp edge, given the sum and count of all the
/// semi-sharp edges (this one included) around the vertex the child edge ends at.
#[inline]
fn chaikin_decay(s: f32, semi_sum: f32, semi_count: usize) -> f32 {
    let blended = if semi_count > 1 {
        // Three quarters of the edge's own value, one quarter of the mean of
        // the other semi-sharp edges at the vertex.
        let others = (semi_sum - s) / (semi_count - 1) as f32;
        0.75 * s + 0.25 * others
    } else {
        s
    };
    let child = blended - 1.0;
    if is_sharp(child) {
        child
    } else {
        SHARPNESS_SMOOTH
    }
}

/// Sharpness of the child edge of an edge at one of its end vertices.
///
/// `incident_edge_sharpness` is the (parent) sharpness of every edge at that
/// end vertex, the edge itself included. Under [`CreasingMethod::Uniform`], or
/// when the vertex has fewer than two edges, this is the uniform decay. Under
/// Chaikin, a semi-sharp edge first moves a quarter of the way towards the mean
/// of the *other* semi-sharp edges at the vertex, then loses one.
pub fn subdivide_edge_sharpness_at_vertex(
    method: CreasingMethod,
    edge_sharpness: f32,
    incident_edge_sharpness: &[f32],
) -> f32 {
    if method == CreasingMethod::Uniform || incident_edge_sharpness.len() < 2 {
        return subdivide_uniform_sharpness(edge_sharpness);
    }
    if is_smooth(edge_sharpness) {
        return SHARPNESS_SMOOTH;
    }
    if is_infinite(edge_sharpness) {
        return SHARPNESS_INFINITE;
    }
    let (sum, count) = semi_sharp_sum(incident_edge_sharpness);
    chaikin_decay(edge_sharpness, sum, count)
}

/// Sharpness of every child edge at a vertex's child vertex, from the parent
/// sharpness of the vertex's edges (same order; `child.len()` must equal
/// `parent.len()`).
///
/// Gives the same values as [`subdivide_edge_sharpness_at_vertex`] per edge,
/// except that under Chaikin with no semi-sharp edge around the vertex the
/// values are copied unchanged (so a sharpness above 10 stays above 10 rather
/// than becoming 10) — the classification of every value is the same.
pub fn subdivide_edge_sharpnesses_around_vertex(
    method: CreasingMethod,
    parent: &[f32],
    child: &mut [f32],
) {
    assert_eq!(
        parent.len(),
        child.len(),
        "one child sharpness per parent edge"
    );
    if method == CreasingMethod::Uniform || parent.len() < 2 {
        for (c, &p) in child.iter_mut().zip(parent) {
            *c = subdivide_uniform_sharpness(p);
        }
        return;
    }
    let (sum, count) = semi_sharp_sum(parent);
    if count == 0 {
        child.copy_from_slice(parent);
        return;
    }
    for (c, &p) in child.iter_mut().zip(parent) {
        *c = if is_smooth(p) {
            SHARPNESS_SMOOTH
        } else if is_infinite(p) {
            SHARPNESS_INFINITE
        } else {
            chaikin_decay(p, sum, count)
        };
    }
}

/// The rule of a vertex given how many of its edges are sharp: a sharp vertex
/// is a corner; otherwise 0 sharp edges → smooth, 1 → dart, 2 → crease,
/// 3 or more → corner.
#[inline]
pub fn vertex_rule_from_sharp_edge_count(vertex_sharpness: f32, sharp_edges: usize) -> Rule {
    if is_sharp(vertex_sharpness) {
        return Rule::Corner;
    }
    match sharp_edges {
        0 => Rule::Smooth,
        1 => Rule::Dart,
        2 => Rule::Crease,
        _ => Rule::Corner,
    }
}

/// Short name of [`vertex_rule_from_sharp_edge_count`].
#[inline]
pub fn rule_from_count(vertex_sharpness: f32, sharp_edges: usize) -> Rule {
    vertex_rule_from_sharp_edge_count(vertex_sharpness, sharp_edges)
}

/// The rule of a vertex from its own sharpness and the sharpness of its edges
/// (OpenSubdiv's `DetermineVertexVertexRule`): semi-sharp and infinitely sharp
/// edges count alike. See [`vertex_rule_from_sharp_edge_count`].
pub fn vertex_rule(vertex_sharpness: f32, edge_sharpness: &[f32]) -> Rule {
    if is_sharp(vertex_sharpness) {
        return Rule::Corner;
    }
    let sharp = edge_sharpness.iter().filter(|&&s| is_sharp(s)).count();
    vertex_rule_from_sharp_edge_count(vertex_sharpness, sharp)
}

/// The weight of the parent's mask when the rule of a vertex changes between
/// a parent vertex and its child (OpenSubdiv's `ComputeFractionalWeightAtVertex`);
/// the child's mask gets one minus this.
///
/// It is the mean of the parent sharpness of every feature that "transitions"
/// (sharp in the parent, smooth in the child), clamped to at most 1, or 0 if
/// nothing transitions. The vertex transitions when it is sharp and
/// `child_vertex_sharpness` is smooth. For the edges:
/// * with `child_edge_sharpness = Some(child)` (OpenSubdiv's Chaikin path),
///   an edge transitions when its parent value is sharp and its child value is
///   smooth;
/// * with `None` (OpenSubdiv's path for uniform creasing), an edge transitions
///   when its parent value is sharp and at most 1.
///
/// Under uniform creasing both criteria agree, so passing the child values is
/// always correct; `None` is only correct under uniform creasing.
pub fn fractional_weight_at_vertex(
    parent_vertex_sharpness: f32,
    child_vertex_sharpness: f32,
    parent_edge_sharpness: &[f32],
    child_edge_sharpness: Option<&[f32]>,
) -> f32 {
    let mut count = 0u32;
    let mut sum = 0.0f32;
    if is_sharp(parent_vertex_sharpness) && is_smooth(child_vertex_sharpness) {
        count = 1;
        sum = parent_vertex_sharpness;
    }
    match child_edge_sharpness {
        None => {
            for &p in parent_edge_sharpness {
                if is_sharp(p) && p <= 1.0 {
                    sum += p;
                    count += 1;
                }
            }
        }
        Some(child) => {
            debug_assert_eq!(child.len(), parent_edge_sharpness.len());
            for (&p, &c) in parent_edge_sharpness.iter().zip(child) {
                if is_sharp(p) && is_smooth(c) {
                    sum += p;
                    count += 1;
                }
            }
        }
    }
    if count == 0 {
        return 0.0;
    }
    let w = sum / count as f32;
    if w > 1.0 { 1.0 } else { w }
}

/// The weight of the crease (midpoint) mask in the child vertex of an edge,
/// the smooth mask getting one minus it — what OpenSubdiv's edge-vertex mask
/// does when a sharp edge's child is no longer a crease.
///
/// `child_sharpness` is the smaller of the two child edges' sharpness (the
/// child vertex is a crease only if both child edges stay sharp). Returns 0 for
/// a smooth parent, 1 when the child is still sharp, and otherwise the parent
/// sharpness itself, **not clamped**: under Chaikin creasing an edge sharper
/// than 1 can lose its sharpness at one end in a single step, and OpenSubdiv
/// then extrapolates with a weight above 1 (and a negative smooth weight).
pub fn fractional_weight_at_edge(parent_sharpness: f32, child_sharpness: f32) -> f32 {
    if is_smooth(parent_sharpness) {
        0.0
    } else if is_sharp(child_sharpness) {
        1.0
    } else {
        parent_sharpness
    }
}

/// The two edges whose 1/8 weights make a crease vertex's mask: the first
/// sharp edge in vertex-edge order and the last one (OpenSubdiv's
/// `GetSharpEdgePairOfCrease`). With exactly two sharp edges these are those
/// two; with more (which only a caller forcing the crease rule can produce)
/// the outermost two win, whatever their sharpness; with a single sharp edge
/// both ends are that edge.
///
/// # Panics
///
/// If no value in `edge_sharpness` is sharp (a crease needs sharp edges;
/// OpenSubdiv's behaviour is undefined there).
pub fn crease_ends(edge_sharpness: &[f32]) -> [usize; 2] {
    let first = edge_sharpness.iter().position(|&s| is_sharp(s));
    let last = edge_sharpness.iter().rposition(|&s| is_sharp(s));
    match (first, last) {
        (Some(a), Some(b)) => [a, b],
        _ => panic!("crease rule at a vertex without sharp edges: {edge_sharpness:?}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use CreasingMethod::{Chaikin, Uniform};

    #[test]
    fn classification() {
        assert!(is_smooth(0.0) && is_smooth(-1.0) && !is_smooth(0.01));
        assert!(is_sharp(0.01) && is_sharp(10.0) && !is_sharp(0.0));
        assert!(is_infinite(10.0) && is_infinite(12.0) && !is_infinite(9.99));
        assert!(is_semi_sharp(0.5) && is_semi_sharp(9.99));
        assert!(!is_semi_sharp(0.0) && !is_semi_sharp(10.0));
    }

    #[test]
    fn uniform_decay() {
        assert_eq!(subdivide_uniform_sharpness(2.5), 1.5);
        assert_eq!(subdivide_uniform_sharpness(0.7), 0.0);
        assert_eq!(subdivide_uniform_sharpness(1.0), 0.0);
        assert_eq!(subdivide_uniform_sharpness(10.0), 10.0);
        assert_eq!(subdivide_uniform_sharpness(25.0), 10.0);
        assert_eq!(subdivide_uniform_sharpness(-3.0), 0.0);
        assert_eq!(subdivide_vertex_sharpness(3.25), 2.25);
        // Uniform creasing ignores the neighbours.
        assert_eq!(
            subdivide_edge_sharpness_at_vertex(Uniform, 2.0, &[2.0, 1.0, 0.0]),
            1.0
        );
        let mut c = [9.0; 4];
        subdivide_edge_sharpnesses_around_vertex(Uniform, &[2.5, 0.7, 10.0, 0.0], &mut c);
        assert_eq!(c, [1.5, 0.0, 10.0, 0.0]);
    }

    #[test]
    fn chaikin_two_semi_sharp_edges() {
        // Edges at the vertex: 2 (the one subdivided), 1 (semi-sharp), one
        // smooth and one infinite edge, which do not take part in the average.
        // For the edge of sharpness 2: the mean of the other semi-sharp edges
        // is 1, so 3/4·2 + 1/4·1 = 1.75, minus one level: 0.75.
        // For the edge of sharpness 1: 3/4·1 + 1/4·2 = 1.25, minus one: 0.25.
        let around = [2.0, 0.0, 1.0, 10.0];
        assert_eq!(
            subdivide_edge_sharpness_at_vertex(Chaikin, 2.0, &around),
            0.75
        );
        assert_eq!(
            subdivide_edge_sharpness_at_vertex(Chaikin, 1.0, &around),
            0.25
        );
        assert_eq!(
            subdivide_edge_sharpness_at_vertex(Chaikin, 10.0, &around),
            10.0
        );
        assert_eq!(
            subdivide_edge_sharpness_at_vertex(Chaikin, 0.0, &around),
            0.0
        );
        let mut child = [0.0; 4];
        subdivide_edge_sharpnesses_around_vertex(Chaikin, &around, &mut child);
        assert_eq!(child, [0.75, 0.0, 0.25, 10.0]);
    }

    #[test]
    fn chaikin_special_cases() {
        // A single semi-sharp edge decays uniformly.
        assert_eq!(
            subdivide_edge_sharpness_at_vertex(Chaikin, 2.5, &[2.5, 0.0, 10.0]),
            1.5
        );
        // A lone edge at the vertex (fewer than two edges) decays uniformly.
        assert_eq!(
            subdivide_edge_sharpness_at_vertex(Chaikin, 0.5, &[0.5]),
            0.0
        );
        // Three semi-sharp edges 3, 1, 0.5: for the 3, others average 0.75,
        // 3/4·3 + 1/4·0.75 = 2.4375 → 1.4375; for the 1: others 1.75,
        // 0.75 + 0.4375 = 1.1875 → 0.1875; for the 0.5: others 2,
        // 0.375 + 0.5 = 0.875 → smooth.
        let around = [3.0, 1.0, 0.5];
        let mut child = [0.0; 3];
        subdivide_edge_sharpnesses_around_vertex(Chaikin, &around, &mut child);
        assert_eq!(child, [1.4375, 0.1875, 0.0]);
        for (i, &s) in around.iter().enumerate() {
            assert_eq!(
                subdivide_edge_sharpness_at_vertex(Chaikin, s, &around),
                child[i]
            );
        }
        // A semi-sharp edge sharper than 1 can vanish in one step: 1.2 next to
        // 0.1 gives 0.9 + 0.025 - 1 < 0.
        assert_eq!(
            subdivide_edge_sharpness_at_vertex(Chaikin, 1.2, &[1.2, 0.1]),
            0.0
        );
        // No semi-sharp edge: values are copied.
        let mut child = [0.0; 3];
        subdivide_edge_sharpnesses_around_vertex(Chaikin, &[0.0, 12.0, 0.0], &mut child);
        assert_eq!(child, [0.0, 12.0, 0.0]);
    }

    #[test]
    fn rules() {
        assert_eq!(vertex_rule(0.0, &[0.0, 0.0, 0.0, 0.0]), Rule::Smooth);
        assert_eq!(vertex_rule(0.0, &[0.0, 0.5, 0.0, 0.0]), Rule::Dart);
        assert_eq!(vertex_rule(0.0, &[10.0, 0.0, 0.3, 0.0]), Rule::Crease);
        assert_eq!(vertex_rule(0.0, &[10.0, 1.0, 0.3, 0.0]), Rule::Corner);
        assert_eq!(vertex_rule(0.0, &[1.0, 1.0, 1.0, 1.0]), Rule::Corner);
        assert_eq!(vertex_rule(0.5, &[0.0, 0.0, 0.0, 0.0]), Rule::Corner);
        assert_eq!(vertex_rule(10.0, &[]), Rule::Corner);
        assert_eq!(vertex_rule_from_sharp_edge_count(0.0, 2), Rule::Crease);
        assert_eq!(vertex_rule_from_sharp_edge_count(0.0, 7), Rule::Corner);
    }

    #[test]
    fn fractional_weights() {
        // Two semi-sharp edges 0.3 and 0.5 decay to zero: mean 0.4.
        let p = [0.3, 0.0, 0.5, 0.0];
        assert_eq!(fractional_weight_at_vertex(0.0, 0.0, &p, None), 0.4);
        assert_eq!(
            fractional_weight_at_vertex(0.0, 0.0, &p, Some(&[0.0; 4])),
            0.4
        );
        // Uniform: an edge of 2 does not transition (it becomes 1); the vertex
        // sharpness 0.6 does: mean of 0.6 and 0.3 = 0.45.
        let p = [2.0, 0.3, 0.0];
        let w = fractional_weight_at_vertex(0.6, 0.0, &p, None);
        assert_eq!(w, (0.6f32 + 0.3) / 2.0);
        assert_eq!(
            fractional_weight_at_vertex(0.6, 0.0, &p, Some(&[1.0, 0.0, 0.0])),
            w
        );
        // Chaikin: edges 1.2 and 0.1 both vanish (0.9 + 0.025 - 1 < 0 and
        // 0.075 + 0.3 - 1 < 0); the 1.2 counts with its full value: mean 0.65.
        // Under the uniform criterion only the 0.1 would count.
        let p = [1.2, 0.1, 0.0];
        let w = fractional_weight_at_vertex(0.0, 0.0, &p, Some(&[0.0, 0.0, 0.0]));
        assert_eq!(w, (1.2f32 + 0.1) / 2.0);
        assert_eq!(fractional_weight_at_vertex(0.0, 0.0, &p, None), 0.1);
        // A mean above 1 is clamped to 1.
        let w = fractional_weight_at_vertex(0.0, 0.0, &[1.2, 0.0, 10.0], Some(&[0.0, 0.0, 10.0]));
        assert_eq!(w, 1.0);
        // Nothing transitions.
        assert_eq!(
            fractional_weight_at_vertex(0.0, 0.0, &[10.0, 0.0], None),
            0.0
        );
        // Edges.
        assert_eq!(fractional_weight_at_edge(0.0, 0.0), 0.0);
        assert_eq!(fractional_weight_at_edge(0.3, 0.0), 0.3);
        assert_eq!(fractional_weight_at_edge(2.0, 1.0), 1.0);
        assert_eq!(fractional_weight_at_edge(1.2, 0.0), 1.2);
    }

    #[test]
    fn crease_end_choice() {
        assert_eq!(crease_ends(&[0.0, 10.0, 0.0, 2.0]), [1, 3]);
        assert_eq!(crease_ends(&[1.0, 0.0, 0.0, 0.5]), [0, 3]);
        // More than two sharp edges: the outermost two, not the sharpest.
        assert_eq!(crease_ends(&[0.2, 10.0, 10.0, 0.3, 0.0]), [0, 3]);
        assert_eq!(crease_ends(&[0.0, 0.5, 0.0]), [1, 1]);
    }

    #[test]
    #[should_panic(expected = "without sharp edges")]
    fn crease_ends_need_a_sharp_edge() {
        crease_ends(&[0.0, 0.0, 0.0]);
    }
}
