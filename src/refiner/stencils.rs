//! Stencil tables: every refined (or limit) vertex as a weighted sum of base
//! vertices, built by running the refinement masks on sparse rows.

use super::limit::LimitMasks;
use super::{Kind, Refiner, Source};
use crate::error::Result;
use crate::stencil::{LimitStencilTable, StencilTable};

/// Sparse rows under construction, merged through a dense scratch array.
struct RowBuilder {
    dense: Vec<f64>,
    touched: Vec<u32>,
    seen: Vec<bool>,
}

impl RowBuilder {
    fn new(base: usize) -> Self {
        RowBuilder {
            dense: vec![0.0; base],
            touched: Vec::new(),
            seen: vec![false; base],
        }
    }

    fn add_row(&mut self, indices: &[u32], weights: &[f64], w: f64) {
        for (&i, &x) in indices.iter().zip(weights) {
            let iu = i as usize;
            if !self.seen[iu] {
                self.seen[iu] = true;
                self.touched.push(i);
            }
            self.dense[iu] += x * w;
        }
    }

    /// Moves the accumulated row into `table`, in order of first contribution.
    fn finish_into(&mut self, table: &mut StencilTable) {
        table.offsets.push(table.indices.len() as u32);
        table.sizes.push(self.touched.len() as u32);
        for &i in &self.touched {
            let iu = i as usize;
            table.indices.push(i);
            table.weights.push(self.dense[iu]);
            self.dense[iu] = 0.0;
            self.seen[iu] = false;
        }
        self.touched.clear();
    }
}

/// Rows stored in the order they are produced, with a map from vertex to row.
struct Rows {
    table: StencilTable,
    row_of: Vec<u32>,
}

impl Rows {
    fn get(&self, v: u32) -> (&[u32], &[f64]) {
        self.table.row(self.row_of[v as usize] as usize)
    }

    /// The same rows in vertex order.
    fn into_table(self) -> StencilTable {
        let mut out = StencilTable::default();
        for &r in &self.row_of {
            let (i, w) = self.table.row(r as usize);
            out.offsets.push(out.indices.len() as u32);
            out.sizes.push(i.len() as u32);
            out.indices.extend_from_slice(i);
            out.weights.extend_from_slice(w);
        }
        out
    }
}

impl Refiner {
    fn rows_of_level(&self, level: usize) -> Rows {
        let base = self.levels[0].vertex_count;
        if level == 0 {
            let table = StencilTable {
                sizes: vec![1; base],
                offsets: (0..base as u32).collect(),
                indices: (0..base as u32).collect(),
                weights: vec![1.0; base],
            };
            return Rows {
                table,
                row_of: (0..base as u32).collect(),
            };
        }
        let prev = self.rows_of_level(level - 1);
        let n = self.levels[level].vertex_count;
        let mut rows = Rows {
            table: StencilTable::default(),
            row_of: vec![0; n],
        };
        let mut builder = RowBuilder::new(base);
        self.walk_masks::<f64>(Kind::Vertex, level, |child, terms| {
            for &(source, w) in terms {
                match source {
                    Source::Parent(p) => {
                        let (i, x) = prev.get(p);
                        builder.add_row(i, x, w);
                    }
                    Source::Child(c) => {
                        let (i, x) = rows.get(c);
                        builder.add_row(i, x, w);
                    }
                }
            }
            rows.row_of[child as usize] = rows.table.sizes.len() as u32;
            builder.finish_into(&mut rows.table);
        });
        rows
    }

    /// The stencil table mapping base vertices to the vertices of the last
    /// level (as `Far::StencilTableFactory` with vertex interpolation and no
    /// intermediate levels). Weights are computed in `f64`.
    pub fn stencil_table(&self) -> Result<StencilTable> {
        Ok(self.rows_of_level(self.levels.len() - 1).into_table())
    }

    /// Stencils of the limit positions and both tangents at the vertices of
    /// the last level, from base vertices.
    pub fn limit_stencil_table(&self) -> Result<LimitStencilTable> {
        let last = self.levels.len() - 1;
        if !self.levels[last].has_full_topology() {
            return Err(crate::Error::InvalidArgument(
                "limit stencils need full topology in the last level (refine with full_topology_in_last_level)".into(),
            ));
        }
        let rows = self.rows_of_level(last).into_table();
        let level = &self.levels[last];
        let base = self.levels[0].vertex_count;
        let mut builders = [
            RowBuilder::new(base),
            RowBuilder::new(base),
            RowBuilder::new(base),
        ];
        let mut out = LimitStencilTable::default();
        let mut masks = LimitMasks::<f64>::new();
        for v in 0..level.vertex_count {
            let has_masks = masks.compute(self, level, v, true);
            let tables = [&mut out.positions, &mut out.du, &mut out.dv];
            for (k, (builder, table)) in builders.iter_mut().zip(tables).enumerate() {
                if has_masks {
                    let mask = [&masks.pos, &masks.tan1, &masks.tan2][k];
                    for (&p, &w) in masks.face_points.iter().zip(&mask.face) {
                        let (i, x) = rows.row(p as usize);
                        builder.add_row(i, x, w);
                    }
                    for (&p, &w) in masks.edge_points.iter().zip(&mask.edge) {
                        let (i, x) = rows.row(p as usize);
                        builder.add_row(i, x, w);
                    }
                    let (i, x) = rows.row(v);
                    builder.add_row(i, x, mask.vertex[0]);
                } else if k == 0 {
                    let (i, x) = rows.row(v);
                    builder.add_row(i, x, 1.0);
                }
                builder.finish_into(table);
            }
        }
        Ok(out)
    }
}

/// One refinement step of a [`FactorizedStencils`]: the terms of every child
/// vertex, in OpenSubdiv's order of computation — face points, edge points,
/// vertex points, each a contiguous block of child indices — over the parent
/// level or (high bit set) over the face points computed before them.
#[derive(Debug, Clone, PartialEq, Default)]
struct Step<T> {
    /// `rows + 1` offsets into `source` and `weight`.
    offsets: Vec<u32>,
    /// Source of each term: a parent vertex, or (high bit set) a child vertex.
    source: Vec<u32>,
    /// Weight of each term.
    weight: Vec<T>,
    /// Number of vertices of the child level.
    child_count: usize,
    /// First child index and row count of the face, edge and vertex blocks.
    blocks: [(usize, usize); 3],
}

const CHILD_BIT: u32 = 1 << 31;

/// The refinement to the last level as a product of sparse per-level
/// stencils: the masks of every level recorded once, in `T`, then applied to
/// any number of frames without recomputing them.
///
/// Applying it gives exactly the result of [`Refiner::interpolate_all`] in the
/// same precision (same weights, same order of accumulation), with far fewer
/// terms than a flat [`StencilTable`], whose stencils grow with every level.
///
/// ```
/// use subdiv::{refiner::Refiner, shapes, Options, UniformOptions};
/// let torus = shapes::torus(8, 6);
/// let mut r = Refiner::new(&torus, &Options::default())?;
/// r.refine_uniform(UniformOptions::new(3))?;
/// let stencils = r.factorized_stencils::<f32>()?;
/// let base: Vec<f32> = torus.positions.iter().flat_map(|p| p.as_vec3().to_array()).collect();
/// let mut out = vec![0.0; stencils.len() * 3];
/// stencils.apply_into(3, &base, &mut out)?;
/// assert_eq!(out, r.interpolate_all(3, &base)?.pop().unwrap());
/// # Ok::<(), subdiv::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FactorizedStencils<T> {
    base_count: usize,
    steps: Vec<Step<T>>,
}

impl<T: crate::Real> FactorizedStencils<T> {
    /// Number of vertices of the last level (rows of the whole product).
    pub fn len(&self) -> usize {
        self.steps.last().map_or(self.base_count, |s| s.child_count)
    }

    /// Whether the last level has no vertex.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Number of weights stored over all levels.
    pub fn term_count(&self) -> usize {
        self.steps.iter().map(|s| s.weight.len()).sum()
    }

    /// Applies the stencils to base data of `width` components per vertex,
    /// writing the last level into `out`; the faces and the rest of each level
    /// are computed in parallel (rayon).
    pub fn apply_into(&self, width: usize, base: &[T], out: &mut [T]) -> Result<()> {
        if width == 0 || base.len() != self.base_count * width || out.len() != self.len() * width {
            return Err(crate::Error::InvalidArgument(format!(
                "buffers of {} and {} values do not fit {} base and {} refined vertices of width {width}",
                base.len(),
                out.len(),
                self.base_count,
                self.len()
            )));
        }
        if self.steps.is_empty() {
            out.copy_from_slice(base);
            return Ok(());
        }
        let mut src: Vec<T> = base.to_vec();
        let mut tmp: Vec<T> = Vec::new();
        for (k, step) in self.steps.iter().enumerate() {
            let last = k + 1 == self.steps.len();
            if !last {
                tmp.clear();
                tmp.resize(step.child_count * width, T::ZERO);
            }
            let dst: &mut [T] = if last { &mut *out } else { &mut tmp };
            apply_step(step, width, &src, dst);
            if !last {
                std::mem::swap(&mut src, &mut tmp);
            }
        }
        Ok(())
    }
}

/// One step: face-point rows first (they only read the parent), then edge
/// and vertex rows, which may read face points. Rows are independent within
/// a phase and write disjoint blocks, so each phase runs in parallel.
fn apply_step<T: crate::Real>(step: &Step<T>, width: usize, src: &[T], dst: &mut [T]) {
    use rayon::prelude::*;
    const GRAIN: usize = 2048;
    let [(f0, nf), (e0, ne), (v0, nv)] = step.blocks;
    let row = |r: usize, faces: &[T], out: &mut [T]| {
        out.fill(T::ZERO);
        let (a, b) = (step.offsets[r] as usize, step.offsets[r + 1] as usize);
        for (&s, &w) in step.source[a..b].iter().zip(&step.weight[a..b]) {
            let (data, i) = if s & CHILD_BIT != 0 {
                (faces, (s & !CHILD_BIT) as usize - f0)
            } else {
                (src, s as usize)
            };
            for (x, &v) in out.iter_mut().zip(&data[i * width..i * width + width]) {
                *x += v * w;
            }
        }
    };
    dst[f0 * width..(f0 + nf) * width]
        .par_chunks_mut(width)
        .with_min_len(GRAIN)
        .enumerate()
        .for_each(|(k, out)| row(k, &[], out));
    // Split the child level into its three blocks to read the face points
    // while writing the edge and vertex points.
    let mut blocks: Vec<(usize, usize, usize)> = vec![(f0, nf, 0), (e0, ne, 1), (v0, nv, 2)];
    blocks.sort_unstable();
    let mut parts: [&mut [T]; 3] = [&mut [], &mut [], &mut []];
    let mut rest = dst;
    let mut at = 0;
    for &(start, count, which) in &blocks {
        let (_, tail) = rest.split_at_mut((start - at) * width);
        let (block, tail) = tail.split_at_mut(count * width);
        parts[which] = block;
        rest = tail;
        at = start + count;
    }
    let [faces, edges, verts] = parts;
    let faces: &[T] = faces;
    edges
        .par_chunks_mut(width)
        .with_min_len(GRAIN)
        .enumerate()
        .for_each(|(k, out)| row(nf + k, faces, out));
    verts
        .par_chunks_mut(width)
        .with_min_len(GRAIN)
        .enumerate()
        .for_each(|(k, out)| row(nf + ne + k, faces, out));
}

impl Refiner {
    /// The refinement to the last level as per-level stencils in `T`: apply
    /// it to new base positions (animation frames) without recomputing masks.
    pub fn factorized_stencils<T: crate::Real>(&self) -> Result<FactorizedStencils<T>> {
        let mut steps = Vec::with_capacity(self.levels.len() - 1);
        for level in 1..self.levels.len() {
            let r = &self.refinements[level - 1];
            let parent = &self.levels[level - 1];
            let nf = if r.has_face_points() {
                parent.face_count()
            } else {
                0
            };
            let mut step = Step {
                child_count: self.levels[level].vertex_count,
                blocks: [
                    (r.first_vertex_from_faces as usize, nf),
                    (r.first_vertex_from_edges as usize, parent.edge_count()),
                    (r.first_vertex_from_vertices as usize, parent.vertex_count),
                ],
                offsets: vec![0],
                ..Step::default()
            };
            self.walk_masks::<T>(Kind::Vertex, level, |_child, terms| {
                for &(source, w) in terms {
                    step.source.push(match source {
                        Source::Parent(i) => i,
                        Source::Child(i) => i | CHILD_BIT,
                    });
                    step.weight.push(w);
                }
                step.offsets.push(step.source.len() as u32);
            });
            steps.push(step);
        }
        Ok(FactorizedStencils {
            base_count: self.levels[0].vertex_count,
            steps,
        })
    }
}
