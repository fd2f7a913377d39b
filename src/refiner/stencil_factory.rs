//! Stencil tables: every refined (or limit) vertex as a weighted sum of base
//! vertices, built by running the refinement masks on sparse rows.

use super::limit::LimitMasks;
use super::{Kind, Refiner, Source};
use crate::error::{Buffer, Error, Result};
use crate::real::Real;
use crate::stencil::{LimitStencilTable, StencilTable, StencilTableF32};

/// Sparse rows under construction, merged through a dense scratch array.
struct RowBuilder<T> {
    dense: Vec<T>,
    touched: Vec<u32>,
    seen: Vec<bool>,
}

impl<T: Real> RowBuilder<T> {
    fn new(base: usize) -> Self {
        RowBuilder {
            dense: vec![T::ZERO; base],
            touched: Vec::new(),
            seen: vec![false; base],
        }
    }

    /// Adds `w` times a row: each weight becomes `dense += x * w`, as
    /// OpenSubdiv's stencil builder accumulates (in the row's precision).
    fn add_row(&mut self, indices: &[u32], weights: &[T], w: T) {
        for (&i, &x) in indices.iter().zip(weights) {
            let iu = i as usize;
            if !self.seen[iu] {
                self.seen[iu] = true;
                self.touched.push(i);
            }
            self.dense[iu] += x * w;
        }
    }

    /// Moves the accumulated row to the end of `indices` and `weights`, in
    /// order of first contribution.
    fn finish(&mut self, indices: &mut Vec<u32>, weights: &mut Vec<T>) {
        for &i in &self.touched {
            let iu = i as usize;
            indices.push(i);
            weights.push(self.dense[iu]);
            self.dense[iu] = T::ZERO;
            self.seen[iu] = false;
        }
        self.touched.clear();
    }
}

impl RowBuilder<f64> {
    /// Moves the accumulated row into `table`.
    fn finish_into(&mut self, table: &mut StencilTable) {
        table.offsets.push(table.indices.len() as u32);
        table.sizes.push(self.touched.len() as u32);
        self.finish(&mut table.indices, &mut table.weights);
    }
}

/// Rows stored in the order they are produced (`offsets` has one entry more
/// than there are rows), with a map from vertex to row.
struct Rows<T> {
    offsets: Vec<u32>,
    indices: Vec<u32>,
    weights: Vec<T>,
    row_of: Vec<u32>,
}

impl<T: Real> Rows<T> {
    fn get(&self, v: u32) -> (&[u32], &[T]) {
        let r = self.row_of[v as usize] as usize;
        let (a, b) = (self.offsets[r] as usize, self.offsets[r + 1] as usize);
        (&self.indices[a..b], &self.weights[a..b])
    }

    /// Number of vertices.
    fn len(&self) -> usize {
        self.row_of.len()
    }

    /// Number of terms over all rows.
    fn terms(&self) -> usize {
        self.indices.len()
    }
}

impl Rows<f64> {
    /// The same rows in vertex order.
    fn into_table(self) -> StencilTable {
        let mut out = StencilTable {
            sizes: Vec::with_capacity(self.len()),
            offsets: Vec::with_capacity(self.len()),
            indices: Vec::with_capacity(self.terms()),
            weights: Vec::with_capacity(self.terms()),
        };
        for v in 0..self.len() as u32 {
            let (i, w) = self.get(v);
            out.offsets.push(out.indices.len() as u32);
            out.sizes.push(i.len() as u32);
            out.indices.extend_from_slice(i);
            out.weights.extend_from_slice(w);
        }
        out
    }
}

impl Refiner {
    fn rows_of_level<T: Real>(&self, level: usize) -> Rows<T> {
        let base = self.levels[0].vertex_count;
        if level == 0 {
            return Rows {
                offsets: (0..=base as u32).collect(),
                indices: (0..base as u32).collect(),
                weights: vec![T::ONE; base],
                row_of: (0..base as u32).collect(),
            };
        }
        let prev = self.rows_of_level::<T>(level - 1);
        let n = self.levels[level].vertex_count;
        let mut rows = Rows {
            offsets: Vec::with_capacity(n + 1),
            indices: Vec::new(),
            weights: Vec::new(),
            row_of: vec![0; n],
        };
        rows.offsets.push(0);
        let mut builder = RowBuilder::<T>::new(base);
        self.walk_masks::<T>(Kind::Vertex, level, |child, terms| {
            for &(source, w) in terms {
                // As OpenSubdiv's stencil builder, skip terms of zero weight
                // (crease and boundary masks have them): they add nothing,
                // but would put their vertices earlier in the row and so
                // change the order in which the row is applied.
                if w == T::ZERO {
                    continue;
                }
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
            rows.row_of[child as usize] = (rows.offsets.len() - 1) as u32;
            builder.finish(&mut rows.indices, &mut rows.weights);
            rows.offsets.push(rows.indices.len() as u32);
        });
        rows
    }

    /// The stencil table mapping base vertices to the vertices of the last
    /// level (as `Far::StencilTableFactory` with vertex interpolation and no
    /// intermediate levels). Weights are computed in `f64`.
    pub fn stencil_table(&self) -> Result<StencilTable> {
        crate::alloc::guard(None, || {
            Ok(self
                .rows_of_level::<f64>(self.levels.len() - 1)
                .into_table())
        })
    }

    /// The same stencils with weights computed in `f32` all along, as
    /// OpenSubdiv's float `Far::StencilTableFactory` computes them (same
    /// masks, same products, same order of accumulation), in the layout
    /// [`StencilTableF32::apply_into`] applies fastest: applied to `f32` data,
    /// it gives `Osd::CpuEvaluator::EvalStencils`' results bit for bit.
    ///
    /// ```
    /// use subdiv::{refiner::Refiner, shapes, Options, UniformOptions};
    /// let torus = shapes::torus_triangles(6, 4);
    /// let mut r = Refiner::new(&torus, &Options::default())?;
    /// r.refine_uniform(UniformOptions::new(2))?;
    /// let stencils = r.stencil_table_f32()?;
    /// assert_eq!(stencils.len(), r.stencil_table()?.len());
    /// let base: Vec<f32> = torus.positions.iter().flat_map(|p| p.as_vec3().to_array()).collect();
    /// let refined = stencils.apply(3, &base)?;
    /// let by_levels = r.interpolate_all(3, &base)?.pop().unwrap();
    /// let off = refined.iter().zip(&by_levels).map(|(a, b)| (a - b).abs()).fold(0.0, f32::max);
    /// assert!(off < 1e-5); // the same points, up to f32 rounding
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn stencil_table_f32(&self) -> Result<StencilTableF32> {
        let rows = self.rows_of_level::<f32>(self.levels.len() - 1);
        let mut out = StencilTableF32::with_capacity(rows.len(), rows.terms());
        for v in 0..rows.len() as u32 {
            let (i, w) = rows.get(v);
            out.push_row(i, w.iter().copied());
        }
        Ok(out)
    }

    /// Stencils of the limit positions and both tangents at the vertices of
    /// the last level, from base vertices.
    pub fn limit_stencil_table(&self) -> Result<LimitStencilTable> {
        crate::alloc::guard(None, || {
            let last = self.levels.len() - 1;
            if !self.levels[last].has_full_topology() {
                return Err(crate::Error::NeedsFullTopology);
            }
            let rows = self.rows_of_level::<f64>(last);
            let level = &self.levels[last];
            let base = self.levels[0].vertex_count;
            let mut builders = [
                RowBuilder::<f64>::new(base),
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
                        let mask = masks.masks()[k];
                        for (&p, &w) in masks.face_points.iter().zip(&mask.face) {
                            let (i, x) = rows.get(p);
                            builder.add_row(i, x, w);
                        }
                        for (&p, &w) in masks.edge_points.iter().zip(&mask.edge) {
                            let (i, x) = rows.get(p);
                            builder.add_row(i, x, w);
                        }
                        let (i, x) = rows.get(v as u32);
                        builder.add_row(i, x, mask.vertex[0]);
                    } else if k == 0 {
                        let (i, x) = rows.get(v as u32);
                        builder.add_row(i, x, 1.0);
                    }
                    builder.finish_into(table);
                }
            }
            Ok(out)
        })
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
        if width == 0 {
            return Err(Error::ZeroWidth);
        }
        for (buffer, expected, got) in [
            (Buffer::Base, self.base_count * width, base.len()),
            (Buffer::Output, self.len() * width, out.len()),
        ] {
            if got != expected {
                return Err(Error::BufferLength {
                    buffer,
                    expected,
                    got,
                });
            }
        }
        if self.steps.is_empty() {
            out.copy_from_slice(base);
            return Ok(());
        }
        // Two scratch levels used in turn; the first step reads `base` and
        // the last writes `out` directly.
        let (mut even, mut odd): (Vec<T>, Vec<T>) = (Vec::new(), Vec::new());
        for (k, step) in self.steps.iter().enumerate() {
            let (write, read) = if k % 2 == 0 {
                (&mut even, &odd)
            } else {
                (&mut odd, &even)
            };
            let src: &[T] = if k == 0 { base } else { read };
            if k + 1 == self.steps.len() {
                apply_step(step, width, src, out);
            } else {
                write.clear();
                write.resize(step.child_count * width, T::ZERO);
                apply_step(step, width, src, write);
            }
        }
        Ok(())
    }
}

/// One step: face-point rows first (they only read the parent), then edge
/// and vertex rows, which may read face points. Rows are independent within
/// a phase and write disjoint blocks, so each phase runs in parallel (in
/// chunks of rows, unless the current rayon pool has one thread).
fn apply_step<T: crate::Real>(step: &Step<T>, width: usize, src: &[T], dst: &mut [T]) {
    let [(f0, nf), (e0, ne), (v0, nv)] = step.blocks;
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
    let phase = |first_row: usize, faces: &[T], out: &mut [T]| match width {
        1 => step_rows::<1, T>(step, first_row, src, faces, out),
        2 => step_rows::<2, T>(step, first_row, src, faces, out),
        3 => step_rows::<3, T>(step, first_row, src, faces, out),
        4 => step_rows::<4, T>(step, first_row, src, faces, out),
        _ => step_rows_any(step, width, first_row, src, faces, out),
    };
    phase(0, &[], faces);
    let faces: &[T] = faces;
    phase(nf, faces, edges);
    phase(nf + ne, faces, verts);
}

/// The values a step's term `s` reads: a parent vertex of `src`, or (with
/// [`CHILD_BIT`]) a face point of this step, `faces` holding those from
/// child vertex `f0` on.
#[inline(always)]
fn source_row<'a, T>(s: u32, src: &'a [T], faces: &'a [T], f0: usize, width: usize) -> &'a [T] {
    let (data, i) = if s & CHILD_BIT != 0 {
        (faces, (s & !CHILD_BIT) as usize - f0)
    } else {
        (src, s as usize)
    };
    &data[i * width..i * width + width]
}

/// Rows `first_row..` of a step into `out` (whole rows of `W` values), in
/// parallel chunks.
fn step_rows<const W: usize, T: crate::Real>(
    step: &Step<T>,
    first_row: usize,
    src: &[T],
    faces: &[T],
    out: &mut [T],
) {
    let f0 = step.blocks[0].0;
    let rows = |first: usize, out: &mut [T]| {
        for (r, o) in out.chunks_exact_mut(W).enumerate() {
            let r = first + r;
            let (a, b) = (step.offsets[r] as usize, step.offsets[r + 1] as usize);
            let mut acc = [T::ZERO; W];
            for (&s, &w) in step.source[a..b].iter().zip(&step.weight[a..b]) {
                for (x, &v) in acc.iter_mut().zip(source_row(s, src, faces, f0, W)) {
                    *x += v * w;
                }
            }
            o.copy_from_slice(&acc);
        }
    };
    in_chunks(out, W, first_row, rows);
}

/// As [`step_rows`] for any width.
fn step_rows_any<T: crate::Real>(
    step: &Step<T>,
    width: usize,
    first_row: usize,
    src: &[T],
    faces: &[T],
    out: &mut [T],
) {
    let f0 = step.blocks[0].0;
    let rows = |first: usize, out: &mut [T]| {
        for (r, o) in out.chunks_exact_mut(width).enumerate() {
            let r = first + r;
            o.fill(T::ZERO);
            let (a, b) = (step.offsets[r] as usize, step.offsets[r + 1] as usize);
            for (&s, &w) in step.source[a..b].iter().zip(&step.weight[a..b]) {
                for (x, &v) in o.iter_mut().zip(source_row(s, src, faces, f0, width)) {
                    *x += v * w;
                }
            }
        }
    };
    in_chunks(out, width, first_row, rows);
}

/// Calls `rows(first_row, chunk)` over `out` in chunks of rows of `width`
/// values, in parallel when there is enough work and more than one thread.
fn in_chunks<T: crate::Real>(
    out: &mut [T],
    width: usize,
    first_row: usize,
    rows: impl Fn(usize, &mut [T]) + Sync,
) {
    use rayon::prelude::*;
    const GRAIN: usize = 4096;
    if out.len() <= GRAIN * width || rayon::current_num_threads() == 1 {
        rows(first_row, out);
    } else {
        out.par_chunks_mut(GRAIN * width)
            .enumerate()
            .for_each(|(c, chunk)| rows(first_row + c * GRAIN, chunk));
    }
}

impl Refiner {
    /// The refinement to the last level as per-level stencils in `T`: apply
    /// it to new base positions (animation frames) without recomputing masks.
    pub fn factorized_stencils<T: crate::Real>(&self) -> Result<FactorizedStencils<T>> {
        crate::alloc::guard(None, || {
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
        })
    }
}
