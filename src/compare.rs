//! Vertex-by-vertex comparison of two refinements (typically native against
//! OpenSubdiv): counts, face-vertex lists, sharpness, holes, positions and
//! face-varying data, level by level.

use crate::output::Refinement;
use glam::DVec3;

/// How one level of two refinements compares.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LevelComparison {
    /// The level.
    pub level: u32,
    /// Vertex, edge, face and face-vertex counts of both sides: `[a, b]`.
    pub counts: [[usize; 4]; 2],
    /// The first face whose vertex list differs, if any.
    pub first_face_difference: Option<usize>,
    /// Whether edge-vertices, sharpness and hole flags are equal.
    pub tags_equal: bool,
    /// Largest distance between corresponding positions.
    pub max_position_deviation: f64,
    /// `max_position_deviation` divided by the bounding-box diagonal of side `b`.
    pub relative_position_deviation: f64,
    /// The vertex where the largest deviation occurs.
    pub worst_vertex: Option<usize>,
    /// Whether the face-varying topology (value counts and indices) is equal.
    pub fvar_topology_equal: bool,
    /// Largest difference between corresponding face-varying values.
    pub max_fvar_deviation: f64,
    /// At the last level, when both sides evaluated the limit: the largest
    /// difference of limit positions and tangents, relative to the
    /// bounding-box diagonal (tangents are scaled alike), or of limit
    /// face-varying values (absolute), whichever is larger.
    pub limit_deviation: Option<f64>,
}

impl LevelComparison {
    /// Whether the topology agrees exactly.
    pub fn topology_equal(&self) -> bool {
        self.counts[0] == self.counts[1]
            && self.first_face_difference.is_none()
            && self.tags_equal
            && self.fvar_topology_equal
    }

    /// Whether everything agrees within `tolerance` (relative to the bounding-box diagonal).
    pub fn agrees(&self, tolerance: f64) -> bool {
        self.topology_equal()
            && self.relative_position_deviation <= tolerance
            && self.max_fvar_deviation <= tolerance
            && self.limit_deviation.is_none_or(|d| d <= tolerance)
    }
}

/// The diagonal of the bounding box of `points` (0 when empty).
pub fn bbox_diagonal(points: &[DVec3]) -> f64 {
    let Some(&first) = points.first() else {
        return 0.0;
    };
    let (lo, hi) = points
        .iter()
        .fold((first, first), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
    (hi - lo).length()
}

/// Compares every level the two refinements have in common.
pub fn compare(a: &Refinement, b: &Refinement) -> Vec<LevelComparison> {
    let levels = a.levels.len().min(b.levels.len());
    let mut out: Vec<LevelComparison> = (0..levels).map(|l| compare_level(a, b, l)).collect();
    if let (Some(la), Some(lb), Some(last)) = (&a.limit, &b.limit, out.last_mut()) {
        let diag = bbox_diagonal(&lb.positions).max(f64::MIN_POSITIVE);
        let mut worst = 0.0f64;
        for (x, y) in [
            (&la.positions, &lb.positions),
            (&la.du, &lb.du),
            (&la.dv, &lb.dv),
        ] {
            if x.len() != y.len() {
                worst = f64::INFINITY;
                continue;
            }
            for (p, q) in x.iter().zip(y.iter()) {
                let d = (*p - *q).length();
                worst = if d.is_nan() {
                    f64::INFINITY
                } else {
                    worst.max(d)
                };
            }
        }
        let mut deviation = worst / diag;
        if la.fvar_values.len() != lb.fvar_values.len() {
            deviation = f64::INFINITY;
        }
        for (x, y) in la.fvar_values.iter().zip(&lb.fvar_values) {
            if x.len() != y.len() {
                deviation = f64::INFINITY;
                continue;
            }
            for (p, q) in x.iter().zip(y) {
                let d = (p - q).abs();
                deviation = if d.is_nan() {
                    f64::INFINITY
                } else {
                    deviation.max(d)
                };
            }
        }
        last.limit_deviation = Some(deviation);
    }
    out
}

fn compare_level(a: &Refinement, b: &Refinement, l: usize) -> LevelComparison {
    let (ta, tb) = (&a.levels[l], &b.levels[l]);
    let counts = |t: &crate::LevelTopology| {
        [
            t.vertex_count,
            t.edge_count,
            t.face_count(),
            t.face_vertices.len(),
        ]
    };
    let first_face_difference = (0..ta.face_count().max(tb.face_count()))
        .find(|&f| f >= ta.face_count() || f >= tb.face_count() || ta.face(f) != tb.face(f));
    let tags_equal = ta.edge_vertices == tb.edge_vertices
        && ta.edge_sharpness == tb.edge_sharpness
        && ta.vertex_sharpness == tb.vertex_sharpness
        && ta.face_holes == tb.face_holes;
    let (pa, pb) = (&a.positions[l], &b.positions[l]);
    let mut max_dev = if pa.len() == pb.len() {
        0.0
    } else {
        f64::INFINITY
    };
    let mut worst = None;
    for (i, (x, y)) in pa.iter().zip(pb).enumerate() {
        let d = (*x - *y).length();
        if d > max_dev || d.is_nan() {
            max_dev = if d.is_nan() { f64::INFINITY } else { d };
            worst = Some(i);
        }
    }
    let diag = bbox_diagonal(pb);
    let fvar_topology_equal = ta.fvar == tb.fvar;
    let mut max_fvar = 0.0f64;
    match (a.fvar_values.get(l), b.fvar_values.get(l)) {
        (Some(fa), Some(fb)) if fa.len() == fb.len() => {
            for (ca, cb) in fa.iter().zip(fb) {
                if ca.len() != cb.len() {
                    max_fvar = f64::INFINITY;
                    continue;
                }
                for (x, y) in ca.iter().zip(cb) {
                    let d = (x - y).abs();
                    max_fvar = if d.is_nan() {
                        f64::INFINITY
                    } else {
                        max_fvar.max(d)
                    };
                }
            }
        }
        (None, None) => {}
        _ => max_fvar = f64::INFINITY,
    }
    LevelComparison {
        level: l as u32,
        counts: [counts(ta), counts(tb)],
        first_face_difference,
        tags_equal,
        max_position_deviation: max_dev,
        relative_position_deviation: if diag > 0.0 { max_dev / diag } else { max_dev },
        worst_vertex: worst,
        fvar_topology_equal,
        max_fvar_deviation: max_fvar,
        limit_deviation: None,
    }
}
