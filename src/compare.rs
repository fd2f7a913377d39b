//! Vertex-by-vertex comparison of two refinements (typically native against
//! OpenSubdiv): counts, face-vertex lists, sharpness, holes, positions and
//! face-varying data, level by level ([`compare`]); and table by table, to
//! the first differing element, of single levels ([`first_topology_difference`]),
//! their relations ([`first_relations_difference`]), their parent-to-child
//! maps ([`first_child_maps_difference`]) and positions
//! ([`compare_positions`]), which [`compare_adaptive`] applies to two
//! feature-adaptive refinements ([`AdaptiveLevel`]).

use crate::output::{ChildMaps, LevelRelations, LevelTopology, Refinement};
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
    let first_face_difference = first_face_difference(ta, tb);
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

/// The first face whose vertex list differs, or the first face one side
/// lacks.
fn first_face_difference(a: &LevelTopology, b: &LevelTopology) -> Option<usize> {
    (0..a.face_count().max(b.face_count()))
        .find(|&f| f >= a.face_count() || f >= b.face_count() || a.face(f) != b.face(f))
}

/// Where two tables first differ: the table's name (a field name of
/// [`LevelTopology`], [`LevelRelations`] or [`ChildMaps`], or `vertex_count`,
/// `edge_count`) and the index of the first differing element. For tables
/// of one entry per element that is the entry; for tables of lists per
/// element (a face's vertices, an edge's faces, a parent face's children)
/// it is the element whose list differs. When one side has fewer
/// elements, the index is the first element it lacks.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TableDifference {
    /// The table.
    pub table: &'static str,
    /// The first differing element.
    pub index: usize,
}

impl std::fmt::Display for TableDifference {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} [{}]", self.table, self.index)
    }
}

/// The first index at which `a` and `b` differ by `eq`, or the shorter
/// length when one is a prefix of the other.
fn first_index<T>(a: &[T], b: &[T], eq: impl Fn(&T, &T) -> bool) -> Option<usize> {
    let n = a.len().min(b.len());
    (0..n)
        .find(|&i| !eq(&a[i], &b[i]))
        .or((a.len() != b.len()).then_some(n))
}

/// The first of several tables that differ, checked in order.
struct First(Option<TableDifference>);

impl First {
    fn set(&mut self, table: &'static str, index: Option<usize>) -> &mut Self {
        if self.0.is_none() {
            self.0 = index.map(|index| TableDifference { table, index });
        }
        self
    }

    fn count(&mut self, table: &'static str, a: usize, b: usize) -> &mut Self {
        self.set(table, (a != b).then_some(a.min(b)))
    }

    fn table<T: PartialEq>(&mut self, table: &'static str, a: &[T], b: &[T]) -> &mut Self {
        if self.0.is_some() {
            return self;
        }
        self.set(table, first_index(a, b, |x, y| x == y))
    }

    /// Floats, bit for bit.
    fn floats(&mut self, table: &'static str, a: &[f32], b: &[f32]) -> &mut Self {
        if self.0.is_some() {
            return self;
        }
        self.set(table, first_index(a, b, |x, y| x.to_bits() == y.to_bits()))
    }

    /// Lists per element: `members` in the ranges of `offsets` (a leading 0
    /// and one final entry); the index is the element whose list differs.
    fn lists<T: PartialEq>(
        &mut self,
        table: &'static str,
        (oa, ma): (&[u32], &[T]),
        (ob, mb): (&[u32], &[T]),
    ) -> &mut Self {
        if self.0.is_some() {
            return self;
        }
        fn list<'a, T>(o: &[u32], m: &'a [T], i: usize) -> Option<&'a [T]> {
            let (start, end) = (*o.get(i)? as usize, *o.get(i + 1)? as usize);
            m.get(start..end)
        }
        let (na, nb) = (oa.len().saturating_sub(1), ob.len().saturating_sub(1));
        let index = (0..na.max(nb)).find(|&i| {
            i >= na || i >= nb || list(oa, ma, i).is_none() || list(oa, ma, i) != list(ob, mb, i)
        });
        self.set(table, index)
    }
}

/// The first difference between two levels' topologies: counts, faces
/// (their vertex lists), edge-vertices, edge and vertex sharpness (bit for
/// bit), holes, then face-varying channels (`fvar`: the channel whose
/// topology differs). `None` when they are equal.
pub fn first_topology_difference(a: &LevelTopology, b: &LevelTopology) -> Option<TableDifference> {
    let mut first = vertex_topology_difference(a, b);
    first.set("fvar", first_index(&a.fvar, &b.fvar, |x, y| x == y));
    first.0
}

/// [`first_topology_difference`] without the face-varying channels.
fn vertex_topology_difference(a: &LevelTopology, b: &LevelTopology) -> First {
    let mut first = First(None);
    first
        .count("vertex_count", a.vertex_count, b.vertex_count)
        .count("edge_count", a.edge_count, b.edge_count)
        .set("face_vertices", first_face_difference(a, b))
        .table("edge_vertices", &a.edge_vertices, &b.edge_vertices)
        .floats("edge_sharpness", &a.edge_sharpness, &b.edge_sharpness)
        .floats("vertex_sharpness", &a.vertex_sharpness, &b.vertex_sharpness)
        .table("face_holes", &a.face_holes, &b.face_holes);
    first
}

/// The first difference between two levels' relations, rules and tags,
/// table by table in [`LevelRelations`]' field order. `None` when equal.
pub fn first_relations_difference(
    a: &LevelRelations,
    b: &LevelRelations,
) -> Option<TableDifference> {
    let mut first = First(None);
    first
        .table("face_edges", &a.face_edges, &b.face_edges)
        .lists(
            "edge_faces",
            (&a.edge_face_offsets, &a.edge_faces),
            (&b.edge_face_offsets, &b.edge_faces),
        )
        .lists(
            "edge_face_local",
            (&a.edge_face_offsets, &a.edge_face_local),
            (&b.edge_face_offsets, &b.edge_face_local),
        )
        .lists(
            "vertex_faces",
            (&a.vertex_face_offsets, &a.vertex_faces),
            (&b.vertex_face_offsets, &b.vertex_faces),
        )
        .lists(
            "vertex_face_local",
            (&a.vertex_face_offsets, &a.vertex_face_local),
            (&b.vertex_face_offsets, &b.vertex_face_local),
        )
        .lists(
            "vertex_edges",
            (&a.vertex_edge_offsets, &a.vertex_edges),
            (&b.vertex_edge_offsets, &b.vertex_edges),
        )
        .lists(
            "vertex_edge_local",
            (&a.vertex_edge_offsets, &a.vertex_edge_local),
            (&b.vertex_edge_offsets, &b.vertex_edge_local),
        )
        .table("vertex_rules", &a.vertex_rules, &b.vertex_rules)
        .table("vertex_boundary", &a.vertex_boundary, &b.vertex_boundary)
        .table("vertex_corner", &a.vertex_corner, &b.vertex_corner)
        .table(
            "vertex_valence_regular",
            &a.vertex_valence_regular,
            &b.vertex_valence_regular,
        )
        .table(
            "vertex_non_manifold",
            &a.vertex_non_manifold,
            &b.vertex_non_manifold,
        )
        .table("vertex_inf_sharp", &a.vertex_inf_sharp, &b.vertex_inf_sharp)
        .table(
            "vertex_semi_sharp",
            &a.vertex_semi_sharp,
            &b.vertex_semi_sharp,
        )
        .table(
            "edge_non_manifold",
            &a.edge_non_manifold,
            &b.edge_non_manifold,
        )
        .table("edge_boundary", &a.edge_boundary, &b.edge_boundary)
        .table("edge_inf_sharp", &a.edge_inf_sharp, &b.edge_inf_sharp)
        .table("edge_semi_sharp", &a.edge_semi_sharp, &b.edge_semi_sharp);
    first.0
}

/// The first difference between two levels' parent-to-child maps, table by
/// table in [`ChildMaps`]' field order (the children of a parent face as
/// one list per face). `None` when equal.
pub fn first_child_maps_difference(a: &ChildMaps, b: &ChildMaps) -> Option<TableDifference> {
    let mut first = First(None);
    first
        .lists(
            "face_child_faces",
            (&a.face_child_face_offsets, &a.face_child_faces),
            (&b.face_child_face_offsets, &b.face_child_faces),
        )
        .lists(
            "face_child_edges",
            (&a.face_child_edge_offsets, &a.face_child_edges),
            (&b.face_child_edge_offsets, &b.face_child_edges),
        )
        .table("edge_child_edges", &a.edge_child_edges, &b.edge_child_edges)
        .table(
            "face_child_vertex",
            &a.face_child_vertex,
            &b.face_child_vertex,
        )
        .table(
            "edge_child_vertex",
            &a.edge_child_vertex,
            &b.edge_child_vertex,
        )
        .table(
            "vertex_child_vertex",
            &a.vertex_child_vertex,
            &b.vertex_child_vertex,
        )
        .table(
            "child_face_parent_face",
            &a.child_face_parent_face,
            &b.child_face_parent_face,
        );
    first.0
}

/// How two lists of positions compare.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PositionComparison {
    /// The first position whose coordinates differ in any bit (or the first
    /// one side lacks); `None` when the lists are identical bit for bit.
    pub first_difference: Option<usize>,
    /// The largest distance between corresponding positions (infinite when
    /// the lengths differ or a distance is NaN).
    pub max_deviation: f64,
    /// Where the largest distance is.
    pub worst: Option<usize>,
}

impl PositionComparison {
    /// Whether the positions are identical bit for bit.
    pub fn identical(&self) -> bool {
        self.first_difference.is_none()
    }
}

/// Compares two lists of positions bit for bit, and measures their largest
/// difference.
pub fn compare_positions(a: &[DVec3], b: &[DVec3]) -> PositionComparison {
    let bits = |p: &DVec3| p.to_array().map(f64::to_bits);
    let first_difference = first_index(a, b, |x, y| bits(x) == bits(y));
    let mut max_deviation = if a.len() == b.len() {
        0.0
    } else {
        f64::INFINITY
    };
    let mut worst = None;
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        let d = (*x - *y).length();
        let d = if d.is_nan() { f64::INFINITY } else { d };
        if d > max_deviation {
            max_deviation = d;
            worst = Some(i);
        }
    }
    PositionComparison {
        first_difference,
        max_deviation,
        worst,
    }
}

/// One level of a feature-adaptive refinement with everything
/// [`compare_adaptive`] compares: collected by
/// [`crate::refiner::AdaptiveRefiner::adaptive_levels`] (and with the `osd`
/// feature by `osd::TopologyRefiner::adaptive_levels`).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct AdaptiveLevel {
    /// The level's topology.
    pub topology: LevelTopology,
    /// Its relations, rules and tags.
    pub relations: LevelRelations,
    /// How it maps to the next level; `None` for the deepest level.
    pub child_maps: Option<ChildMaps>,
    /// Positions, interpolated from the base level's in `f64`, level by level.
    pub positions: Vec<DVec3>,
}

/// How one level of two adaptive refinements compares.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct AdaptiveLevelComparison {
    /// The level.
    pub level: u32,
    /// Vertex, edge and face counts of both sides: `[a, b]`.
    pub counts: [[usize; 3]; 2],
    /// The first table that differs, in order: the topology (without
    /// face-varying channels, which the native engine does not refine
    /// sparsely yet), the relations, the child maps to the next level;
    /// `None` when all agree.
    pub first_difference: Option<TableDifference>,
    /// The positions.
    pub positions: PositionComparison,
}

impl AdaptiveLevelComparison {
    /// Whether the level's topology, relations and child maps are equal.
    pub fn topology_equal(&self) -> bool {
        self.first_difference.is_none()
    }

    /// Whether the topology agrees and positions are identical bit for bit.
    pub fn identical(&self) -> bool {
        self.topology_equal() && self.positions.identical()
    }
}

/// Compares two feature-adaptive refinements level by level (as many
/// levels as the deeper one has; a level only one side has is a difference
/// in `vertex_count` at index 0). The face-varying topology is not compared.
pub fn compare_adaptive(a: &[AdaptiveLevel], b: &[AdaptiveLevel]) -> Vec<AdaptiveLevelComparison> {
    let empty = AdaptiveLevel::default();
    (0..a.len().max(b.len()))
        .map(|l| {
            let (x, y) = (a.get(l).unwrap_or(&empty), b.get(l).unwrap_or(&empty));
            let counts = |t: &AdaptiveLevel| {
                [
                    t.topology.vertex_count,
                    t.topology.edge_count,
                    t.topology.face_count(),
                ]
            };
            let missing = (l >= a.len() || l >= b.len()).then_some(TableDifference {
                table: "vertex_count",
                index: 0,
            });
            let first_difference = missing
                .or_else(|| vertex_topology_difference(&x.topology, &y.topology).0)
                .or_else(|| first_relations_difference(&x.relations, &y.relations))
                .or_else(|| match (&x.child_maps, &y.child_maps) {
                    (Some(p), Some(q)) => first_child_maps_difference(p, q),
                    (None, None) => None,
                    _ => Some(TableDifference {
                        table: "child_face_parent_face",
                        index: 0,
                    }),
                });
            AdaptiveLevelComparison {
                level: l as u32,
                counts: [counts(x), counts(y)],
                first_difference,
                positions: compare_positions(&x.positions, &y.positions),
            }
        })
        .collect()
}
