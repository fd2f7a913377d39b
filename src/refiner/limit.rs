//! Limit positions and tangents at the vertices of the last level
//! (OpenSubdiv's `PrimvarRefiner::Limit`).

use super::Refiner;
use crate::error::{Error, Result};
use crate::real::Real;
use crate::refinement::LimitData;
use crate::rules::{Mask, VertexNeighborhood};
use crate::topology::Level;

/// The limit masks of one vertex, with the vertices they apply to.
pub(crate) struct LimitMasks<T> {
    pub pos: Mask<T>,
    pub tan1: Mask<T>,
    pub tan2: Mask<T>,
    /// The far end of each incident edge.
    pub edge_points: Vec<u32>,
    /// The vertex two places after this one in each incident face.
    pub face_points: Vec<u32>,
    edge_sharpness: Vec<f32>,
    /// Masks of smooth interior vertices by valence: they depend on nothing else.
    smooth: Vec<Option<[Mask<T>; 3]>>,
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
        }
    }

    /// Computes the masks of vertex `v` of `level`; false for a vertex with no
    /// edge, whose limit is itself with zero tangents.
    pub fn compute(&mut self, refiner: &Refiner, level: &Level, v: usize, tangents: bool) -> bool {
        let edges = level.vertex_edges_of(v);
        if edges.is_empty() {
            return false;
        }
        self.edge_sharpness.clear();
        self.edge_sharpness
            .extend(edges.iter().map(|&e| level.edge_sharpness_at(e as usize)));
        let faces = level.vertex_faces_of(v);
        let hood = VertexNeighborhood {
            sharpness: level.vertex_sharpness_at(v),
            edge_sharpness: &self.edge_sharpness,
            face_count: faces.len(),
            child_sharpness: level.vertex_sharpness_at(v),
            child_edge_sharpness: &[],
        };
        let rule = level.vertex_tag(v).rule();
        let smooth = matches!(rule, crate::rules::Rule::Smooth | crate::rules::Rule::Dart)
            && faces.len() == edges.len();
        if smooth {
            let n = faces.len();
            if self.smooth.len() <= n {
                self.smooth.resize(n + 1, None);
            }
            if self.smooth[n].is_none() {
                let (mut p, mut t1, mut t2) = (Mask::new(), Mask::new(), Mask::new());
                refiner
                    .rules
                    .vertex_limit_masks(&hood, rule, &mut p, &mut t1, &mut t2);
                self.smooth[n] = Some([p, t1, t2]);
            }
            if let Some([p, t1, t2]) = &self.smooth[n] {
                self.pos.clone_from(p);
                if tangents {
                    self.tan1.clone_from(t1);
                    self.tan2.clone_from(t2);
                }
            }
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
        self.edge_points.clear();
        self.edge_points.extend(
            edges
                .iter()
                .map(|&e| level.other_vertex(e as usize, v as u32)),
        );
        self.face_points.clear();
        if !self.pos.face.is_empty() || (tangents && !self.tan1.face.is_empty()) {
            for (&f, &k) in faces.iter().zip(level.vertex_face_locals(v)) {
                let verts = level.face_verts(f as usize);
                self.face_points.push(verts[(k as usize + 2) % verts.len()]);
            }
        }
        true
    }
}

/// Accumulates `mask` over `src` rows: faces, then edges, then the vertex.
fn apply<T: Real>(
    mask: &Mask<T>,
    masks: &LimitMasks<T>,
    v: usize,
    width: usize,
    src: &[T],
    out: &mut [T],
) {
    out.fill(T::ZERO);
    let mut add = |i: u32, w: T| {
        let row = &src[i as usize * width..(i as usize + 1) * width];
        for (o, &s) in out.iter_mut().zip(row) {
            *o += s * w;
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

impl Refiner {
    fn check_limit_source<T>(&self, width: usize, src: &[T]) -> Result<&Level> {
        let level = self.levels.last().expect("base level");
        if !level.has_full_topology() {
            return Err(Error::InvalidArgument(
                "limit evaluation needs full topology in the last level \
                 (refine with full_topology_in_last_level, as OpenSubdiv requires)"
                    .into(),
            ));
        }
        if width == 0 {
            return Err(Error::InvalidArgument(
                "primvar width must be at least 1".into(),
            ));
        }
        if src.len() != level.vertex_count * width {
            return Err(Error::InvalidArgument(format!(
                "source primvar buffer has {} values, expected {} ({} vertices of level {} × {width})",
                src.len(),
                level.vertex_count * width,
                level.vertex_count,
                self.max_level()
            )));
        }
        Ok(level)
    }

    /// Limit values and both tangents at the vertices of the last level, from
    /// data at that level (`PrimvarRefiner::Limit`). Works at any level,
    /// including 0; like OpenSubdiv, it needs the last level refined with
    /// `full_topology_in_last_level`.
    pub fn limit<T: Real>(&self, width: usize, src: &[T]) -> Result<LimitData<T>> {
        let level = self.check_limit_source(width, src)?;
        let n = level.vertex_count * width;
        let mut out = LimitData {
            positions: vec![T::ZERO; n],
            du: vec![T::ZERO; n],
            dv: vec![T::ZERO; n],
        };
        let mut masks = LimitMasks::<T>::new();
        for v in 0..level.vertex_count {
            let range = v * width..(v + 1) * width;
            if !masks.compute(self, level, v, true) {
                out.positions[range.clone()].copy_from_slice(&src[range]);
                continue;
            }
            apply(
                &masks.pos,
                &masks,
                v,
                width,
                src,
                &mut out.positions[range.clone()],
            );
            apply(
                &masks.tan1,
                &masks,
                v,
                width,
                src,
                &mut out.du[range.clone()],
            );
            apply(&masks.tan2, &masks, v, width, src, &mut out.dv[range]);
        }
        Ok(out)
    }

    /// Limit values only, at the vertices of the last level.
    pub fn limit_positions<T: Real>(&self, width: usize, src: &[T]) -> Result<Vec<T>> {
        let level = self.check_limit_source(width, src)?;
        let mut out = vec![T::ZERO; level.vertex_count * width];
        let mut masks = LimitMasks::<T>::new();
        for v in 0..level.vertex_count {
            let range = v * width..(v + 1) * width;
            if !masks.compute(self, level, v, false) {
                out[range.clone()].copy_from_slice(&src[range]);
                continue;
            }
            apply(&masks.pos, &masks, v, width, src, &mut out[range]);
        }
        Ok(out)
    }
}
