//! Limit positions and tangents at the vertices of the last level
//! (OpenSubdiv's `PrimvarRefiner::Limit`).

use super::Refiner;
use crate::error::{Buffer, Error, Result};
use crate::options::Scheme;
use crate::output::{LimitData, Values};
use crate::real::Real;
use crate::rules::{Mask, Rule, VertexNeighborhood};
use crate::topology::refine::{Split, derive_limit_ring};
use crate::topology::{Level, Table};

/// The limit masks of one vertex, with the vertices they apply to.
pub(crate) struct LimitMasks<T> {
    pos: Mask<T>,
    tan1: Mask<T>,
    tan2: Mask<T>,
    /// The far end of each incident edge.
    pub edge_points: Vec<u32>,
    /// The vertex two places after this one in each incident face.
    pub face_points: Vec<u32>,
    edge_sharpness: Vec<f32>,
    /// Masks of smooth interior vertices by valence: they depend on nothing else.
    smooth: Vec<Option<[Mask<T>; 3]>>,
    /// The valence whose smooth masks apply to the last computed vertex, if
    /// it was smooth (then `pos`, `tan1` and `tan2` are not written).
    smooth_valence: Option<usize>,
}

impl<T: Real> LimitMasks<T> {
    pub fn new() -> Self {
        LimitMasks {
            pos: Mask::new(),
            tan1: Mask::new(),
            tan2: Mask::new(),
            edge_points: Vec::new(),
            face_points: Vec::new(),
            edge_sharpness: Vec::new(),
            smooth: Vec::new(),
            smooth_valence: None,
        }
    }

    /// The position, first and second tangent masks of the last vertex
    /// computed (the tangent masks only when it was computed with tangents).
    #[inline]
    pub fn masks(&self) -> [&Mask<T>; 3] {
        match self
            .smooth_valence
            .and_then(|n| self.smooth.get(n)?.as_ref())
        {
            Some([p, t1, t2]) => [p, t1, t2],
            None => [&self.pos, &self.tan1, &self.tan2],
        }
    }

    /// Computes the masks of vertex `v` of `level`; false for a vertex with no
    /// edge, whose limit is itself with zero tangents.
    pub fn compute(&mut self, refiner: &Refiner, level: &Level, v: usize, tangents: bool) -> bool {
        let edges = level.vertex_edges_of(v);
        if edges.is_empty() {
            return false;
        }
        let faces = level.vertex_faces_of(v);
        let rule = level.vertex_tag(v).rule();
        let smooth = matches!(rule, Rule::Smooth | Rule::Dart) && faces.len() == edges.len();
        let n = faces.len();
        self.smooth_valence = smooth.then_some(n);
        // A smooth vertex's masks depend on its valence alone: the
        // neighbourhood is only read when they are not cached yet.
        if !smooth || self.smooth.get(n).is_none_or(Option::is_none) {
            self.edge_sharpness.clear();
            self.edge_sharpness
                .extend(edges.iter().map(|&e| level.edge_sharpness_at(e as usize)));
            let hood = VertexNeighborhood {
                sharpness: level.vertex_sharpness_at(v),
                edge_sharpness: &self.edge_sharpness,
                face_count: n,
                child_sharpness: level.vertex_sharpness_at(v),
                child_edge_sharpness: &[],
            };
            if smooth {
                if self.smooth.len() <= n {
                    self.smooth.resize(n + 1, None);
                }
                let (mut p, mut t1, mut t2) = (Mask::new(), Mask::new(), Mask::new());
                refiner
                    .rules
                    .vertex_limit_masks(&hood, rule, &mut p, &mut t1, &mut t2);
                self.smooth[n] = Some([p, t1, t2]);
            } else if tangents {
                refiner.rules.vertex_limit_masks(
                    &hood,
                    rule,
                    &mut self.pos,
                    &mut self.tan1,
                    &mut self.tan2,
                );
            } else {
                refiner
                    .rules
                    .vertex_limit_position_mask(&hood, rule, &mut self.pos);
            }
        }
        self.edge_points.clear();
        self.edge_points.extend(
            edges
                .iter()
                .map(|&e| level.other_vertex(e as usize, v as u32)),
        );
        self.face_points.clear();
        let [pos, tan1, _] = self.masks();
        if !pos.face.is_empty() || (tangents && !tan1.face.is_empty()) {
            for (&f, &k) in faces.iter().zip(level.vertex_face_locals(v)) {
                let verts = level.face_verts(f as usize);
                self.face_points.push(verts[(k as usize + 2) % verts.len()]);
            }
        }
        true
    }
}

/// Accumulates `mask` over `src` rows of `width` values into `out`: faces,
/// then edges, then the vertex.
fn apply<T: Real>(
    mask: &Mask<T>,
    masks: &LimitMasks<T>,
    v: usize,
    width: usize,
    src: &[T],
    out: &mut [T],
) {
    match width {
        1 => apply_fixed::<T, 1>(mask, masks, v, src, out),
        2 => apply_fixed::<T, 2>(mask, masks, v, src, out),
        3 => apply_fixed::<T, 3>(mask, masks, v, src, out),
        4 => apply_fixed::<T, 4>(mask, masks, v, src, out),
        _ => {
            out.fill(T::ZERO);
            accumulate(mask, masks, v, src, out);
        }
    }
}

/// [`apply`] for `W` values per vertex, summed in registers (the same terms
/// in the same order).
#[inline(always)]
fn apply_fixed<T: Real, const W: usize>(
    mask: &Mask<T>,
    masks: &LimitMasks<T>,
    v: usize,
    src: &[T],
    out: &mut [T],
) {
    let mut acc = [T::ZERO; W];
    accumulate(mask, masks, v, src, &mut acc);
    out[..W].copy_from_slice(&acc);
}

/// Adds the terms of `mask` to `acc` (one vertex's values): faces, then
/// edges, then the vertex.
#[inline(always)]
fn accumulate<T: Real>(mask: &Mask<T>, masks: &LimitMasks<T>, v: usize, src: &[T], acc: &mut [T]) {
    let width = acc.len();
    let mut add = |i: u32, w: T| {
        let row = &src[i as usize * width..(i as usize + 1) * width];
        for (a, &s) in acc.iter_mut().zip(row) {
            *a += s * w;
        }
    };
    for (&i, &w) in masks.face_points.iter().zip(&mask.face) {
        add(i, w);
    }
    for (&i, &w) in masks.edge_points.iter().zip(&mask.edge) {
        add(i, w);
    }
    add(v as u32, mask.vertex[0]);
}

/// The three masks applied in one pass over their common sources when they
/// have the same terms (each output still sums its terms in the same order,
/// so the results are those of three separate passes); false otherwise.
fn apply_three<T: Real>(
    masks: &LimitMasks<T>,
    v: usize,
    width: usize,
    src: &[T],
    out: [&mut [T]; 3],
) -> bool {
    let [mp, m1, m2] = masks.masks();
    let same =
        |a: &Mask<T>, b: &Mask<T>| a.face.len() == b.face.len() && a.edge.len() == b.edge.len();
    if !same(mp, m1) || !same(mp, m2) || mp.face.len() != masks.face_points.len() {
        return false;
    }
    match width {
        1 => apply_three_fixed::<T, 1>([mp, m1, m2], masks, v, src, out),
        2 => apply_three_fixed::<T, 2>([mp, m1, m2], masks, v, src, out),
        3 => apply_three_fixed::<T, 3>([mp, m1, m2], masks, v, src, out),
        4 => apply_three_fixed::<T, 4>([mp, m1, m2], masks, v, src, out),
        _ => return false,
    }
    true
}

/// [`apply_three`] for `W` values per vertex.
#[inline(always)]
fn apply_three_fixed<T: Real, const W: usize>(
    [mp, m1, m2]: [&Mask<T>; 3],
    masks: &LimitMasks<T>,
    v: usize,
    src: &[T],
    [op, o1, o2]: [&mut [T]; 3],
) {
    let (mut p, mut d1, mut d2) = ([T::ZERO; W], [T::ZERO; W], [T::ZERO; W]);
    let mut add = |i: u32, (wp, w1, w2): (T, T, T)| {
        let row: &[T; W] = src[i as usize * W..(i as usize + 1) * W]
            .try_into()
            .expect("a row of W values");
        for k in 0..W {
            p[k] += row[k] * wp;
            d1[k] += row[k] * w1;
            d2[k] += row[k] * w2;
        }
    };
    let weights = |a: &[T], b: &[T], c: &[T], j: usize| (a[j], b[j], c[j]);
    for (j, &i) in masks.face_points.iter().enumerate() {
        add(i, weights(&mp.face, &m1.face, &m2.face, j));
    }
    for (j, &i) in masks.edge_points.iter().enumerate() {
        add(i, weights(&mp.edge, &m1.edge, &m2.edge, j));
    }
    add(v as u32, weights(&mp.vertex, &m1.vertex, &m2.vertex, 0));
    op[..W].copy_from_slice(&p);
    o1[..W].copy_from_slice(&d1);
    o2[..W].copy_from_slice(&d2);
}

/// Vertices per parallel task of limit evaluation.
const BLOCK: usize = 2048;

/// The largest valence whose smooth vertices take the one-pass path
/// ([`Evaluator::smooth`]); the neighbours of a vertex of higher valence are
/// gathered in vectors ([`LimitMasks`]).
const MAX_SMOOTH_VALENCE: usize = 32;

/// The limit masks of a smooth interior vertex of one valence (they depend on
/// the valence alone), interleaved for one pass over its neighbours: the
/// weights of the position, first and second tangent for each face point,
/// then for each edge point, then for the vertex.
struct SmoothMasks<T> {
    face: Vec<[T; 3]>,
    edge: Vec<[T; 3]>,
    vertex: [T; 3],
}

/// What a valence's smooth masks are, once computed.
enum Smooth<T> {
    /// Not computed yet.
    Unknown,
    /// Masks whose terms do not line up (a valence-2 vertex: no position
    /// terms, two tangent ones): the general path applies them.
    General,
    /// Masks the one-pass path applies.
    Fused(SmoothMasks<T>),
}

/// The masks of one valence as [`Smooth`] holds them.
fn smooth_masks<T: Real>(rules: &crate::rules::SchemeRules, n: usize) -> Smooth<T> {
    let edge_sharpness = vec![0.0; n];
    let hood = VertexNeighborhood {
        sharpness: 0.0,
        edge_sharpness: &edge_sharpness,
        face_count: n,
        child_sharpness: 0.0,
        child_edge_sharpness: &[],
    };
    let (mut p, mut t1, mut t2) = (Mask::new(), Mask::new(), Mask::new());
    rules.vertex_limit_masks(&hood, Rule::Smooth, &mut p, &mut t1, &mut t2);
    let lined_up = [&p, &t1, &t2].iter().all(|m| {
        m.vertex.len() == 1 && m.edge.len() == n && (m.face.len() == n || m.face.is_empty())
    }) && p.face.len() == t1.face.len()
        && p.face.len() == t2.face.len();
    if !lined_up {
        return Smooth::General;
    }
    let zip = |a: &[T], b: &[T], c: &[T]| -> Vec<[T; 3]> {
        a.iter()
            .zip(b)
            .zip(c)
            .map(|((&a, &b), &c)| [a, b, c])
            .collect()
    };
    Smooth::Fused(SmoothMasks {
        face: zip(&p.face, &t1.face, &t2.face),
        edge: zip(&p.edge, &t1.edge, &t2.edge),
        vertex: [p.vertex[0], t1.vertex[0], t2.vertex[0]],
    })
}

/// The neighbours of a smooth interior vertex: the vertex opposite it in each
/// face (when its masks weigh faces) and the far end of each edge.
struct Ring {
    faces: [u32; MAX_SMOOTH_VALENCE],
    edges: [u32; MAX_SMOOTH_VALENCE],
    n: usize,
}

/// Limit evaluation of the vertices of one block: the masks it has computed
/// and its scratch buffers.
struct Evaluator<'a, T> {
    refiner: &'a Refiner,
    level: &'a Level,
    /// The level before, how it was split and whether into triangles, when
    /// the level has one (with its relations).
    parent: Option<(&'a Level, &'a Split, bool)>,
    /// Smooth masks by valence.
    smooth: Vec<Smooth<T>>,
    /// The general path's masks and neighbours.
    general: LimitMasks<T>,
}

impl<'a, T: Real> Evaluator<'a, T> {
    fn new(refiner: &'a Refiner, level: &'a Level) -> Self {
        let depth = refiner.levels.len() - 1;
        let parent = depth
            .checked_sub(1)
            .map(|p| &refiner.levels[p])
            .filter(|p| {
                // Bilinear limit masks take the general path anyway.
                refiner.options.scheme != Scheme::Bilinear
                    && p.has_local_indices()
                    && p.edge_vertices.len() == p.num_edges
            })
            .zip(refiner.refinements.get(depth.wrapping_sub(1)))
            .map(|(p, split)| (p, split, refiner.options.scheme == Scheme::Loop));
        Evaluator {
            refiner,
            level,
            parent,
            smooth: Vec::new(),
            general: LimitMasks::new(),
        }
    }

    /// The masks of vertex `v` when it is a smooth interior vertex (rule
    /// smooth or dart, manifold) of valence at most [`MAX_SMOOTH_VALENCE`]
    /// whose masks line up, with its neighbours then in `ring`; `None` sends
    /// it down the general path.
    ///
    /// Under a parent level the neighbours come from the parent element the
    /// vertex is the child of ([`derive_limit_ring`]): its tables are a
    /// quarter of the size of the level's and read nearly in order, where
    /// the level's face-vertices would be read all over.
    #[inline(always)]
    fn smooth(&mut self, v: usize, ring: &mut Ring) -> Option<&SmoothMasks<T>> {
        let tag = self.level.vertex_tag(v);
        if !matches!(tag.rule(), Rule::Smooth | Rule::Dart) || tag.non_manifold() {
            return None;
        }
        let derived = self.parent.and_then(|(parent, split, triangles)| {
            derive_limit_ring(
                parent,
                split,
                triangles,
                v,
                &mut ring.faces,
                &mut ring.edges,
            )
        });
        let n = match derived {
            Some(n) => n,
            None => self.ring_from_level(v, ring)?,
        };
        ring.n = n;
        if self.smooth.len() <= n {
            self.smooth.resize_with(n + 1, || Smooth::Unknown);
        }
        if let Smooth::Unknown = self.smooth[n] {
            self.smooth[n] = smooth_masks(&self.refiner.rules, n);
        }
        match &self.smooth[n] {
            Smooth::Fused(masks) => Some(masks),
            _ => None,
        }
    }

    /// The neighbours of smooth vertex `v` read from the level: `None` when
    /// it has not as many edges as faces, or more than
    /// [`MAX_SMOOTH_VALENCE`].
    ///
    /// Around such a vertex OpenSubdiv orders edge `i` as the edge leading
    /// out of face `i` (`Vtr::Level::orderVertexFacesAndEdges`: from the
    /// vertex to the next vertex of the face), so the far ends of the edges
    /// come from the face rows read for the opposite vertices, and the edges
    /// themselves are not read.
    fn ring_from_level(&self, v: usize, ring: &mut Ring) -> Option<usize> {
        let level = self.level;
        let faces = level.vertex_faces_of(v);
        let n = faces.len();
        if n > MAX_SMOOTH_VALENCE || level.vertex_edges.count(v) != n {
            return None;
        }
        let locals = level.vertex_face_locals(v);
        let rows = ring.faces.iter_mut().zip(ring.edges.iter_mut());
        for ((opposite, next), (&f, &k)) in rows.zip(faces.iter().zip(locals)) {
            let verts = level.face_verts(f as usize);
            let (k, size) = (k as usize, verts.len());
            *opposite = verts[(k + 2) % size];
            *next = verts[(k + 1) % size];
        }
        Some(n)
    }

    /// Limit values of the vertices of one block from `first` on: `K` = 3
    /// outputs (position and both tangents) or 1 (position), rows of `W`
    /// values.
    fn block<const W: usize, const K: usize>(
        &mut self,
        first: usize,
        src: &[T],
        mut out: [&mut [T]; K],
    ) {
        let mut ring = Ring {
            faces: [0; MAX_SMOOTH_VALENCE],
            edges: [0; MAX_SMOOTH_VALENCE],
            n: 0,
        };
        let count = out[0].len() / W;
        for k in 0..count {
            let v = first + k;
            let rows = k * W..(k + 1) * W;
            if let Some(masks) = self.smooth(v, &mut ring) {
                let sums = sum_smooth::<T, W, K>(masks, &ring, v, src);
                for (o, sum) in out.iter_mut().zip(&sums) {
                    o[rows.clone()].copy_from_slice(sum);
                }
                continue;
            }
            let mut rows = out.each_mut().map(|o| &mut o[rows.clone()]);
            self.general(v, W, src, &mut rows);
        }
    }

    /// Limit values of vertex `v` through its own masks (`rows`: the position,
    /// then both tangents if asked for).
    fn general(&mut self, v: usize, width: usize, src: &[T], rows: &mut [&mut [T]]) {
        let tangents = rows.len() == 3;
        let masks = &mut self.general;
        if !masks.compute(self.refiner, self.level, v, tangents) {
            rows[0].copy_from_slice(&src[v * width..(v + 1) * width]);
            for row in &mut rows[1..] {
                row.fill(T::ZERO);
            }
            return;
        }
        if let [p, d1, d2] = rows
            && apply_three(masks, v, width, src, [&mut **p, &mut **d1, &mut **d2])
        {
            return;
        }
        for (mask, row) in masks.masks().into_iter().zip(rows.iter_mut()) {
            apply(mask, masks, v, width, src, row);
        }
    }
}

/// The `K` limit values (position, then tangents) of smooth vertex `v`, rows
/// of `W` values: one pass over its neighbours, each output summing its terms
/// in OpenSubdiv's order (faces, then edges, then the vertex).
#[inline(always)]
fn sum_smooth<T: Real, const W: usize, const K: usize>(
    masks: &SmoothMasks<T>,
    ring: &Ring,
    v: usize,
    src: &[T],
) -> [[T; W]; K] {
    let mut acc = [[T::ZERO; W]; K];
    let mut add = |i: u32, w: &[T; 3]| {
        let i = i as usize;
        let row: &[T; W] = src[i * W..(i + 1) * W].try_into().expect("W values");
        for (a, &w) in acc.iter_mut().zip(w) {
            for (a, &x) in a.iter_mut().zip(row) {
                *a += x * w;
            }
        }
    };
    let n = ring.n;
    for (&i, w) in ring.faces[..n.min(masks.face.len())]
        .iter()
        .zip(&masks.face)
    {
        add(i, w);
    }
    for (&i, w) in ring.edges[..n].iter().zip(&masks.edge) {
        add(i, w);
    }
    add(v as u32, &masks.vertex);
    acc
}

impl Refiner {
    fn check_limit_source<T>(&self, width: usize, src: &[T]) -> Result<&Level> {
        let level = self.levels.last().expect("base level");
        if !level.has_full_topology() {
            return Err(Error::NeedsFullTopology);
        }
        if width == 0 {
            return Err(Error::ZeroWidth);
        }
        if src.len() != level.vertex_count * width {
            return Err(Error::BufferLength {
                buffer: Buffer::Source,
                expected: level.vertex_count * width,
                got: src.len(),
            });
        }
        Ok(level)
    }

    /// Limit values of the vertices of `level` into `out` (position, then both
    /// tangents when `K` = 3), in parallel blocks of [`BLOCK`] vertices.
    fn limit_into<T: Real, const K: usize>(
        &self,
        level: &Level,
        width: usize,
        src: &[T],
        out: [&mut [T]; K],
    ) {
        use rayon::prelude::*;
        // The outputs have the same length: as many chunks each.
        let mut chunks = out.map(|o| o.chunks_mut(BLOCK * width));
        let blocks: Vec<[&mut [T]; K]> = (0..level.vertex_count.div_ceil(BLOCK))
            .map(|_| chunks.each_mut().map(|c| c.next().unwrap_or_default()))
            .collect();
        blocks.into_par_iter().enumerate().for_each(|(b, out)| {
            let mut ev = Evaluator::new(self, level);
            let first = b * BLOCK;
            match width {
                1 => ev.block::<1, K>(first, src, out),
                2 => ev.block::<2, K>(first, src, out),
                3 => ev.block::<3, K>(first, src, out),
                4 => ev.block::<4, K>(first, src, out),
                _ => {
                    let mut out = out;
                    let count = out[0].len() / width;
                    for k in 0..count {
                        let mut rows: Vec<&mut [T]> = out
                            .iter_mut()
                            .map(|o| &mut o[k * width..(k + 1) * width])
                            .collect();
                        ev.general(first + k, width, src, &mut rows);
                    }
                }
            }
        });
    }

    /// Limit values and both tangents at the vertices of the last level, from
    /// data at that level (`PrimvarRefiner::Limit`). Works at any level,
    /// including 0; like OpenSubdiv, it needs the last level refined with
    /// `full_topology_in_last_level`. Parallel over blocks of vertices in
    /// the current rayon pool; the buffers are [`Values`],
    /// written once (a large one recycled from the buffer pool).
    pub fn limit<T: Real>(&self, width: usize, src: &[T]) -> Result<LimitData<T>> {
        crate::alloc::guard(None, || {
            let level = self.check_limit_source(width, src)?;
            let n = level.vertex_count * width;
            let mut out = LimitData {
                positions: Values(Table::for_overwrite(n)),
                du: Values(Table::for_overwrite(n)),
                dv: Values(Table::for_overwrite(n)),
            };
            self.limit_into(
                level,
                width,
                src,
                [&mut *out.positions, &mut *out.du, &mut *out.dv],
            );
            Ok(out)
        })
    }

    /// Limit values only, at the vertices of the last level (parallel as
    /// [`limit`](Self::limit)).
    pub fn limit_positions<T: Real>(&self, width: usize, src: &[T]) -> Result<Values<T>> {
        crate::alloc::guard(None, || {
            let level = self.check_limit_source(width, src)?;
            let mut out = Values(Table::for_overwrite(level.vertex_count * width));
            self.limit_into(level, width, src, [&mut *out]);
            Ok(out)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Options, UniformOptions, shapes};

    /// The neighbours of smooth vertices derived from the parent level are
    /// those read from the level, in the same order, on every corpus mesh
    /// under every scheme, boundary mode and vertex order, at levels 1 to 3;
    /// and read from the level, edge `i`'s far end is the vertex after the
    /// vertex in face `i`.
    #[test]
    fn derived_rings_are_the_level_rings() {
        use crate::BoundaryInterpolation;
        let (mut derived, mut read) = (0, 0);
        for (name, mut mesh) in shapes::corpus() {
            mesh.fvar_channels.clear();
            for &scheme in mesh.applicable_schemes() {
                for boundary in [BoundaryInterpolation::EdgeOnly, BoundaryInterpolation::None] {
                    for faces_first in [false, true] {
                        let options = Options::default()
                            .with_scheme(scheme)
                            .with_boundary(boundary);
                        let Ok(mut r) = Refiner::new(&mesh, &options) else {
                            continue;
                        };
                        for level in 0..=3 {
                            let uniform = UniformOptions::new(level)
                                .full_topology(true)
                                .faces_first(faces_first);
                            if r.refine_uniform(uniform).is_err() {
                                break;
                            }
                            let last = r.levels.last().unwrap();
                            let mut ev = Evaluator::<f64>::new(&r, last);
                            for v in 0..last.vertex_count {
                                let ctx = format!(
                                    "{name} {scheme} {boundary:?} {faces_first} level {level} vertex {v}"
                                );
                                let mut from_level = Ring {
                                    faces: [0; MAX_SMOOTH_VALENCE],
                                    edges: [0; MAX_SMOOTH_VALENCE],
                                    n: 0,
                                };
                                let tag = last.vertex_tag(v);
                                if !matches!(tag.rule(), Rule::Smooth | Rule::Dart)
                                    || tag.non_manifold()
                                {
                                    continue;
                                }
                                let Some(n) = ev.ring_from_level(v, &mut from_level) else {
                                    continue;
                                };
                                read += 1;
                                let edges = last.vertex_edges_of(v);
                                for (j, &e) in edges.iter().enumerate() {
                                    let far = last.other_vertex(e as usize, v as u32);
                                    assert_eq!(from_level.edges[j], far, "{ctx}: edge {j}");
                                }
                                let Some((p, split, tri)) = ev.parent else {
                                    continue;
                                };
                                let mut ring = Ring {
                                    faces: [0; MAX_SMOOTH_VALENCE],
                                    edges: [0; MAX_SMOOTH_VALENCE],
                                    n: 0,
                                };
                                let Some(m) = derive_limit_ring(
                                    p,
                                    split,
                                    tri,
                                    v,
                                    &mut ring.faces,
                                    &mut ring.edges,
                                ) else {
                                    continue;
                                };
                                derived += 1;
                                assert_eq!(m, n, "{ctx}: valence");
                                assert_eq!(ring.edges[..n], from_level.edges[..n], "{ctx}: edges");
                                if !tri {
                                    assert_eq!(
                                        ring.faces[..n],
                                        from_level.faces[..n],
                                        "{ctx}: faces"
                                    );
                                }
                                // The smooth path takes it.
                                assert!(ev.smooth(v, &mut ring).is_some() || n <= 2, "{ctx}");
                            }
                        }
                    }
                }
            }
        }
        assert!(
            derived > 10_000 && read > derived,
            "{derived} derived, {read} read"
        );
    }

    /// The one-pass application of the three masks gives the bits of three
    /// separate passes, at every width it handles, on every corpus mesh.
    #[test]
    fn three_masks_in_one_pass_are_three_passes() {
        let mut fused = 0;
        for (name, mesh) in shapes::corpus() {
            let mut r = Refiner::new(&mesh, &Options::default()).unwrap();
            if r.refine_uniform(UniformOptions::new(1).full_topology(true))
                .is_err()
            {
                continue;
            }
            let level = r.levels.last().unwrap();
            for width in 1..=4 {
                let src: Vec<f64> = (0..level.vertex_count * width)
                    .map(|i| ((i * 7919) % 1000) as f64 / 97.0 - 3.0)
                    .collect();
                let mut masks = LimitMasks::<f64>::new();
                for v in 0..level.vertex_count {
                    if !masks.compute(&r, level, v, true) {
                        continue;
                    }
                    let mut one = vec![vec![f64::NAN; width]; 3];
                    let [a, b, c] = &mut one[..] else {
                        unreachable!()
                    };
                    if !apply_three(&masks, v, width, &src, [a, b, c]) {
                        continue;
                    }
                    fused += 1;
                    for (k, mask) in masks.masks().into_iter().enumerate() {
                        let mut three = vec![f64::NAN; width];
                        apply(mask, &masks, v, width, &src, &mut three);
                        let bits = |x: &[f64]| x.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                        assert_eq!(bits(&one[k]), bits(&three), "{name} vertex {v} mask {k}");
                    }
                }
            }
        }
        assert!(fused > 1000, "{fused} vertices through the one-pass path");
    }
}
