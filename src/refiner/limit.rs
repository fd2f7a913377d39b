//! Limit positions and tangents at the vertices of the last level
//! (OpenSubdiv's `PrimvarRefiner::Limit`).

use super::Refiner;
use crate::error::{Buffer, Error, Result};
use crate::output::LimitData;
use crate::real::Real;
use crate::rules::{Mask, VertexNeighborhood};
use crate::topology::Level;

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
        let smooth = matches!(rule, crate::rules::Rule::Smooth | crate::rules::Rule::Dart)
            && faces.len() == edges.len();
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

    /// Limit values and both tangents at the vertices of the last level, from
    /// data at that level (`PrimvarRefiner::Limit`). Works at any level,
    /// including 0; like OpenSubdiv, it needs the last level refined with
    /// `full_topology_in_last_level`. Parallel over blocks of vertices in
    /// the current rayon pool.
    pub fn limit<T: Real>(&self, width: usize, src: &[T]) -> Result<LimitData<T>> {
        crate::alloc::guard(None, || {
            use rayon::prelude::*;
            let level = self.check_limit_source(width, src)?;
            let n = level.vertex_count * width;
            let mut out = LimitData {
                positions: crate::alloc::vec_or_unwind(T::ZERO, n),
                du: crate::alloc::vec_or_unwind(T::ZERO, n),
                dv: crate::alloc::vec_or_unwind(T::ZERO, n),
            };
            let block = BLOCK * width;
            out.positions
                .par_chunks_mut(block)
                .zip(out.du.par_chunks_mut(block))
                .zip(out.dv.par_chunks_mut(block))
                .enumerate()
                .for_each(|(b, ((pos, du), dv))| {
                    let mut masks = LimitMasks::<T>::new();
                    let rows = pos
                        .chunks_exact_mut(width)
                        .zip(du.chunks_exact_mut(width))
                        .zip(dv.chunks_exact_mut(width));
                    for (k, ((p, d1), d2)) in rows.enumerate() {
                        let v = b * BLOCK + k;
                        if !masks.compute(self, level, v, true) {
                            p.copy_from_slice(&src[v * width..(v + 1) * width]);
                            continue;
                        }
                        if apply_three(&masks, v, width, src, [&mut *p, &mut *d1, &mut *d2]) {
                            continue;
                        }
                        let [mp, m1, m2] = masks.masks();
                        apply(mp, &masks, v, width, src, p);
                        apply(m1, &masks, v, width, src, d1);
                        apply(m2, &masks, v, width, src, d2);
                    }
                });
            Ok(out)
        })
    }

    /// Limit values only, at the vertices of the last level (parallel as
    /// [`limit`](Self::limit)).
    pub fn limit_positions<T: Real>(&self, width: usize, src: &[T]) -> Result<Vec<T>> {
        crate::alloc::guard(None, || {
            use rayon::prelude::*;
            let level = self.check_limit_source(width, src)?;
            let mut out = crate::alloc::vec_or_unwind(T::ZERO, level.vertex_count * width);
            out.par_chunks_mut(BLOCK * width)
                .enumerate()
                .for_each(|(b, out)| {
                    let mut masks = LimitMasks::<T>::new();
                    for (k, p) in out.chunks_exact_mut(width).enumerate() {
                        let v = b * BLOCK + k;
                        if !masks.compute(self, level, v, false) {
                            p.copy_from_slice(&src[v * width..(v + 1) * width]);
                            continue;
                        }
                        apply(masks.masks()[0], &masks, v, width, src, p);
                    }
                });
            Ok(out)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Options, UniformOptions, shapes};

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
