//! Stencil tables: every refined (or limit) vertex as a weighted sum of base
//! vertices, built by running the refinement masks on sparse rows.

use super::kernel::{Cache, Scratch, takes_smooth_mask};
use super::limit::LimitMasks;
use super::rows::{RowBuilder, Rows, RowsView};
use super::{Block, Kind, Refiner, Source, opposite_vertex};
use crate::error::{Buffer, Error, Result};
use crate::options::{Scheme, TriangleSubdivision};
use crate::real::Real;
use crate::stencil::{LimitStencilTable, StencilTable, StencilTableF32};
use crate::topology::{Around, Growing, LevelSlices, Table};

impl<T: Real> RowBuilder<T> {
    /// Builds the row of a child vertex whose refinement terms are `terms`
    /// (each term a row of `prev`, the parent level, `None` for the base
    /// level, whose rows are the identity; or of `faces`, the face points of
    /// the child level, the first of them child vertex `f0`), appended to
    /// `out` with the rows before it once enough wait
    /// ([`RowBuilder::flush`]).
    fn child_row(
        &mut self,
        out: &mut Rows<T>,
        terms: &[(Source, T)],
        prev: Option<RowsView<'_, T>>,
        faces: RowsView<'_, T>,
        f0: u32,
    ) {
        // At most as many terms as the rows merged have in all, bounded
        // without reading them: the widest row of either level per term.
        let widest = prev.map_or(1, |p| p.widest).max(faces.widest).max(1);
        let mut row = self.open_row(terms.len().saturating_mul(widest));
        for &(source, w) in terms {
            // As OpenSubdiv's stencil builder, skip terms of zero weight
            // (crease and boundary masks have them): they add nothing, but
            // would put their vertices earlier in the row and so change the
            // order in which the row is applied.
            if w == T::ZERO {
                continue;
            }
            match (source, prev) {
                (Source::Parent(p), Some(prev)) => row.add_row(prev.get(p), w),
                // The base level's row of `p` is `p` with weight one.
                (Source::Parent(p), None) => row.add_row((&[p], &[T::ONE]), w),
                (Source::Child(c), _) => row.add_row(faces.get(c - f0), w),
            }
        }
        let len = row.len;
        if self.close(len) {
            self.flush(out);
        }
    }
}

/// What building rows needs besides the rows: the merging of terms, the
/// masks' scratch and the cache of smooth masks.
type Workspace<T> = (RowBuilder<T>, Scratch<T>, Cache<T>);

/// A fresh [`Workspace`] for rows over `base` base vertices.
fn workspace<T: Real>(base: usize) -> Workspace<T> {
    (RowBuilder::new(base), Scratch::new(), Cache::new())
}

impl Refiner {
    /// The terms of the edge point of parent edge `e` (vertex data), as
    /// [`Refiner::edge_terms`] gives them: the mask of a smooth edge
    /// between two faces taken from `cache`, as the interpolation kernel
    /// takes it (the same weights in the same order), any other edge's
    /// computed.
    fn cached_edge_terms<T: Real>(
        &self,
        level: usize,
        e: usize,
        (parent, around): (&LevelSlices<'_>, &Around<'_>),
        cache: &mut Cache<T>,
        s: &mut Scratch<T>,
    ) {
        let derived;
        let faces = if around.derives() {
            derived = around.edge_faces(e);
            derived.as_slice()
        } else {
            parent.edge_faces_of(e)
        };
        let tri_smooth = self.options.scheme == Scheme::Catmark
            && self.options.triangles == TriangleSubdivision::Smooth;
        let is_tri = |f: u32| tri_smooth && parent.face_vertices.count(f as usize) == 3;
        let weights = match faces {
            &[a, b] if parent.edge_sharpness_at(e) <= 0.0 => {
                cache.smooth_edge(&self.rules, [is_tri(a), is_tri(b)])
            }
            _ => None,
        };
        let Some(w) = weights else {
            return self.step(level).edge_terms(Kind::Vertex, e, faces, s);
        };
        let r = &self.refinements[level - 1];
        let ev = parent.edge_vertices[e];
        s.terms.clear();
        s.terms.push((Source::Parent(ev[0]), w.ends[0]));
        s.terms.push((Source::Parent(ev[1]), w.ends[1]));
        for (&f, &fw) in faces.iter().zip(w.faces.iter().flatten()) {
            s.terms.push(if w.centers {
                (Source::Child(r.face_child(f as usize)), fw)
            } else {
                (Source::Parent(opposite_vertex(parent, f as usize, e)), fw)
            });
        }
    }

    /// The terms of the child of parent vertex `v` (vertex data), as
    /// [`Refiner::vertex_terms`] gives them: a smooth vertex's mask taken
    /// from `cache` by its valence, as the interpolation kernel takes it,
    /// any other vertex's computed.
    fn cached_vertex_terms<T: Real>(
        &self,
        level: usize,
        v: usize,
        (parent, around): (&LevelSlices<'_>, &Around<'_>),
        cache: &mut Cache<T>,
        s: &mut Scratch<T>,
    ) {
        // Derived relations go into the scratch's buffer, taken out while
        // the terms are written into the scratch; stored ones are read in
        // place.
        let mut buf = None;
        let (faces, edges) = if around.derives() {
            around.vertex_faces_and_edges(v, buf.insert(std::mem::take(&mut s.hood)))
        } else {
            (parent.vertex_faces_of(v), parent.vertex_edges_of(v))
        };
        if takes_smooth_mask(parent.vertex_tag(v).rule(), faces.len(), edges.len()) {
            let r = &self.refinements[level - 1];
            let m = cache.smooth_vertex(&self.rules, faces.len());
            s.terms.clear();
            for (&f, &w) in faces.iter().zip(&m.face) {
                s.terms.push((Source::Child(r.face_child(f as usize)), w));
            }
            for (&e, &w) in edges.iter().zip(&m.edge) {
                let far = parent.other_vertex(e as usize, v as u32);
                s.terms.push((Source::Parent(far), w));
            }
            s.terms.push((Source::Parent(v as u32), m.vertex[0]));
        } else {
            self.step(level)
                .vertex_terms(Kind::Vertex, v, faces, edges, s);
        }
        if let Some(buf) = buf {
            s.hood = buf;
        }
    }
}

/// Rows per parallel task of stencil construction (at least).
const PAR_ROWS: usize = 1 << 16;

/// The rows of the child vertices of one level, from the rows of the level
/// above (`prev`; `None` for the base level's identity).
struct Children<'a, T> {
    refiner: &'a Refiner,
    level: usize,
    prev: Option<RowsView<'a, T>>,
    /// The first face point.
    f0: u32,
}

impl<T: Real> Children<'_, T> {
    /// Appends to `out` the rows of the child vertices of the parent
    /// elements `range` of kind `block`, reading the face points' rows in
    /// `faces`: all of them by the time it returns.
    fn block(
        &self,
        block: Block,
        range: std::ops::Range<usize>,
        faces: RowsView<'_, T>,
        (builder, scratch, cache): &mut Workspace<T>,
        out: &mut Rows<T>,
    ) {
        let r = self.refiner;
        match block {
            Block::Faces => r.walk_block(
                Kind::Vertex,
                self.level,
                block,
                range,
                scratch,
                |_, terms| builder.child_row(out, terms, self.prev, faces, self.f0),
            ),
            Block::Edges => {
                let parent = r.levels[self.level - 1].slices();
                let around = r.around(self.level - 1);
                for e in range {
                    r.cached_edge_terms(self.level, e, (&parent, &around), cache, scratch);
                    builder.child_row(out, &scratch.terms, self.prev, faces, self.f0);
                }
            }
            Block::Vertices => {
                let parent = r.levels[self.level - 1].slices();
                let around = r.around(self.level - 1);
                for v in range {
                    r.cached_vertex_terms(self.level, v, (&parent, &around), cache, scratch);
                    builder.child_row(out, &scratch.terms, self.prev, faces, self.f0);
                }
            }
        }
        // The rows still waiting: the block's rows are all in `out` when
        // it returns.
        builder.flush(out);
    }

    /// The rows of a whole block in parallel chunks, each with its own
    /// builder.
    fn block_chunks(&self, block: Block, count: usize, faces: RowsView<'_, T>) -> Vec<Rows<T>> {
        use rayon::prelude::*;
        let chunk = PAR_ROWS.max(count.div_ceil(4 * rayon::current_num_threads()));
        let base = self.refiner.levels[0].vertex_count;
        (0..count.div_ceil(chunk))
            .into_par_iter()
            .map_init(
                || workspace(base),
                |work, k| {
                    let range = k * chunk..((k + 1) * chunk).min(count);
                    let mut out = Rows::with_rows(range.len());
                    out.expect(range.len() as f64 * self.terms_per_row(block, faces));
                    self.block(block, range, faces, work, &mut out);
                    out
                },
            )
            .collect()
    }

    /// About how many terms the rows of `block` have, from the rows they
    /// merge (an estimate: in a regular mesh a face point merges four
    /// rows of the level above, edge and vertex points about twice a face
    /// point's terms).
    fn terms_per_row(&self, block: Block, faces: RowsView<'_, T>) -> f64 {
        let above = self.prev.map_or(1.0, |p| p.average());
        match block {
            Block::Faces => 4.0 * above + 1.0,
            Block::Edges | Block::Vertices => 2.0 * faces.average().max(above) + 4.0,
        }
    }

    /// All the rows, each block in parallel chunks, then gathered in vertex
    /// order.
    fn in_parallel(&self, nf: usize, blocks: [(u32, Block, usize); 3]) -> Rows<T> {
        let none = Rows::with_rows(0);
        let faces = Rows::concat(&self.block_chunks(Block::Faces, nf, none.view()));
        let mut parts: Vec<Rows<T>> = Vec::new();
        let mut order = Vec::new();
        for (_, block, count) in blocks {
            if block == Block::Faces {
                order.push(None);
            } else {
                let chunks = self.block_chunks(block, count, faces.view());
                order.push(Some(parts.len()..parts.len() + chunks.len()));
                parts.extend(chunks);
            }
        }
        let mut all: Vec<&Rows<T>> = Vec::new();
        for o in order {
            match o {
                None => all.push(&faces),
                Some(range) => all.extend(&parts[range]),
            }
        }
        Rows::concat(&all)
    }
}

impl Refiner {
    /// The stencil rows of the vertices of `level` (at least 1) over the
    /// base vertices, in vertex order.
    fn rows_of_level<T: Real>(&self, level: usize) -> Rows<T> {
        let prev = (level > 1).then(|| self.rows_of_level::<T>(level - 1));
        let prev = prev.as_ref().map(Rows::view);
        let parent = &self.levels[level - 1];
        let r = &self.refinements[level - 1];
        let nf = if r.has_face_points() {
            parent.face_count()
        } else {
            0
        };
        let mut blocks = [
            (r.first_vertex_from_faces, Block::Faces, nf),
            (r.first_vertex_from_edges, Block::Edges, parent.edge_count()),
            (
                r.first_vertex_from_vertices,
                Block::Vertices,
                parent.vertex_count,
            ),
        ];
        blocks.sort_unstable_by_key(|b| b.0);
        let rows = Children {
            refiner: self,
            level,
            prev,
            f0: r.first_vertex_from_faces,
        };
        if rayon::current_num_threads() > 1 && self.levels[level].vertex_count > 2 * PAR_ROWS {
            return rows.in_parallel(nf, blocks);
        }
        let mut work = workspace(self.levels[0].vertex_count);
        // The face points first: the edge and vertex points read them.
        let none = Rows::with_rows(0);
        let mut faces = Rows::with_rows(nf);
        faces.expect(nf as f64 * rows.terms_per_row(Block::Faces, none.view()));
        rows.block(Block::Faces, 0..nf, none.view(), &mut work, &mut faces);
        // Then the three blocks in the order of their child vertices.
        let mut out = Rows::with_rows(self.levels[level].vertex_count);
        let others = self.levels[level].vertex_count - nf;
        out.expect(
            faces.indices.len() as f64
                + others as f64 * rows.terms_per_row(Block::Edges, faces.view()),
        );
        for (first, block, count) in blocks {
            debug_assert_eq!(out.len(), first as usize);
            if block == Block::Faces {
                out.append(&faces);
            } else {
                rows.block(block, 0..count, faces.view(), &mut work, &mut out);
            }
        }
        out
    }

    /// The identity rows of the base level.
    fn base_rows<T: Real>(&self) -> Rows<T> {
        let base = self.levels[0].vertex_count;
        Rows {
            offsets: Growing::from_table((0..=base as u32).collect()),
            indices: Growing::from_table((0..base as u32).collect()),
            weights: Growing::from_table(Table::filled(T::ONE, base)),
            base_count: base,
            widest: usize::from(base > 0),
        }
    }

    /// The rows of the last level (the room [`Rows::expect`] reserved and
    /// no row used is pages never written).
    fn last_rows<T: Real>(&self) -> Rows<T> {
        match self.levels.len() - 1 {
            0 => self.base_rows(),
            last => self.rows_of_level(last),
        }
    }

    /// The stencil table mapping base vertices to the vertices of the last
    /// level (as `Far::StencilTableFactory` with vertex interpolation and no
    /// intermediate levels). Weights are computed in `f64`.
    pub fn stencil_table(&self) -> Result<StencilTable> {
        crate::alloc::guard(None, || Ok(self.last_rows::<f64>().into_table()))
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
        crate::alloc::guard(None, || {
            let rows = self.last_rows::<f32>();
            Ok(StencilTableF32::from_checked_parts(
                rows.offsets.finish(),
                rows.indices.finish(),
                rows.weights.finish(),
                rows.base_count,
            ))
        })
    }

    /// Stencils of the limit positions and both tangents at the vertices of
    /// the last level, from base vertices.
    pub fn limit_stencil_table(&self) -> Result<LimitStencilTable> {
        crate::alloc::guard(None, || {
            let last = self.levels.len() - 1;
            if !self.levels[last].has_full_topology() {
                return Err(crate::Error::NeedsFullTopology);
            }
            let last_rows = self.last_rows::<f64>();
            let rows = last_rows.view();
            let level = &self.levels[last];
            let mut builder = RowBuilder::new(self.levels[0].vertex_count);
            let mut tables = [0, 1, 2].map(|_| Rows::<f64>::with_rows(level.vertex_count));
            let mut masks = LimitMasks::<f64>::new();
            for v in 0..level.vertex_count {
                let has_masks = masks.compute(self, level, v, true);
                for (k, out) in tables.iter_mut().enumerate() {
                    if has_masks {
                        let mask = masks.masks()[k];
                        let me = v as u32;
                        let terms = masks
                            .face_points
                            .iter()
                            .zip(&mask.face)
                            .chain(masks.edge_points.iter().zip(&mask.edge))
                            .chain([(&me, &mask.vertex[0])]);
                        let bound = terms.clone().map(|(&p, _)| rows.get(p).0.len()).sum();
                        builder.open(bound);
                        for (&p, &w) in terms {
                            builder.add_row(rows.get(p), w);
                        }
                    } else {
                        let row = rows.get(v as u32);
                        builder.open(row.0.len());
                        if k == 0 {
                            builder.add_row(row, 1.0);
                        }
                    }
                    builder.end_row(out);
                }
            }
            let [positions, du, dv] = tables.map(Rows::into_table);
            Ok(LimitStencilTable { positions, du, dv })
        })
    }
}

/// One refinement step of a [`FactorizedStencils`]: the terms of every child
/// vertex, in OpenSubdiv's order of computation — face points, edge points,
/// vertex points, each a contiguous block of child indices — over the parent
/// level or over the face points computed before them: one numbering, the
/// parent's vertices then this step's face points.
#[derive(Debug, Clone, PartialEq, Default)]
struct Step<T> {
    /// `rows + 1` offsets into `source` and `weight`.
    offsets: Vec<u32>,
    /// Source of each term: parent vertex `s` below `parent_count`, else
    /// face point `s - parent_count` (child vertex `blocks[0].0` plus that).
    source: Vec<u32>,
    /// Number of vertices of the parent level.
    parent_count: usize,
    /// Weight of each term.
    weight: Vec<T>,
    /// Number of vertices of the child level.
    child_count: usize,
    /// First child index and row count of the face, edge and vertex blocks.
    blocks: [(usize, usize); 3],
}

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
        // Two scratch levels used in turn (tables from the pool: a frame
        // applied after another faults none of their pages in again); the
        // first step reads `base` and the last writes `out` directly. Every
        // row of a level is written.
        crate::alloc::guard(None, || {
            let (mut even, mut odd) = (Table::<T>::new(), Table::<T>::new());
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
                    // The level before last dropped first, so that its
                    // map can be the new one's.
                    *write = Table::new();
                    *write = Table::for_overwrite(step.child_count * width);
                    apply_step(step, width, src, write);
                }
            }
            Ok(())
        })
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
    if width == 3 {
        return padded_step(step, src, [faces, edges, verts]);
    }
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

/// The values a step's term `s` reads: parent vertex `s` of `src`, or
/// (from `pc`, the parent's vertex count, on) face point `s - pc` of
/// `faces`.
#[inline(always)]
fn source_row<'a, T>(s: u32, src: &'a [T], faces: &'a [T], pc: usize, width: usize) -> &'a [T] {
    let s = s as usize;
    let (data, i) = if s < pc { (src, s) } else { (faces, s - pc) };
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
    let pc = step.parent_count;
    let rows = |first: usize, out: &mut [T]| {
        for (r, o) in out.chunks_exact_mut(W).enumerate() {
            let r = first + r;
            let (a, b) = (step.offsets[r] as usize, step.offsets[r + 1] as usize);
            let mut acc = [T::ZERO; W];
            for (&s, &w) in step.source[a..b].iter().zip(&step.weight[a..b]) {
                for (x, &v) in acc.iter_mut().zip(source_row(s, src, faces, pc, W)) {
                    *x += v * w;
                }
            }
            o.copy_from_slice(&acc);
        }
    };
    in_chunks(out, W, first_row, rows);
}

/// [`apply_step`] for three components: the parent's values and then the
/// face points, each padded to four lanes, in one table the terms index
/// directly (one load of a whole vertex per term, no choice between two
/// arrays); the sums are those of [`step_rows`], component by component in
/// the same order. `out` is the child level's face, edge and vertex blocks.
fn padded_step<T: crate::Real>(step: &Step<T>, src: &[T], out: [&mut [T]; 3]) {
    let [faces, edges, verts] = out;
    let pc = step.parent_count;
    let nf = step.blocks[0].1;
    let mut values = Table::<[T; 4]>::for_overwrite(pc + nf);
    for (v, x) in values[..pc].iter_mut().zip(src.chunks_exact(3)) {
        *v = [x[0], x[1], x[2], T::ZERO];
    }
    let row = |values: &[[T; 4]], r: usize| {
        let (a, b) = (step.offsets[r] as usize, step.offsets[r + 1] as usize);
        let mut acc = [T::ZERO; 4];
        for (&s, &w) in step.source[a..b].iter().zip(&step.weight[a..b]) {
            let v = values[s as usize];
            for k in 0..4 {
                acc[k] += v[k] * w;
            }
        }
        acc
    };
    // Face points (over parents only) into their padded rows...
    {
        let (parents, points) = values.split_at_mut(pc);
        let parents: &[[T; 4]] = parents;
        let points: &mut [T] = bytemuck::cast_slice_mut(points);
        in_chunks(points, 4, 0, |first, chunk| {
            let chunk: &mut [[T; 4]] = bytemuck::cast_slice_mut(chunk);
            for (r, o) in chunk.iter_mut().enumerate() {
                *o = row(parents, first + r);
            }
        });
    }
    // ... and out; then edge and vertex points over both.
    for (o, v) in faces.chunks_exact_mut(3).zip(&values[pc..]) {
        o.copy_from_slice(&v[..3]);
    }
    let values: &[[T; 4]] = &values;
    for (first_row, out) in [(nf, edges), (nf + step.blocks[1].1, verts)] {
        in_chunks(out, 3, first_row, |first, chunk| {
            for (r, o) in chunk.chunks_exact_mut(3).enumerate() {
                o.copy_from_slice(&row(values, first + r)[..3]);
            }
        });
    }
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
    let pc = step.parent_count;
    let rows = |first: usize, out: &mut [T]| {
        for (r, o) in out.chunks_exact_mut(width).enumerate() {
            let r = first + r;
            o.fill(T::ZERO);
            let (a, b) = (step.offsets[r] as usize, step.offsets[r + 1] as usize);
            for (&s, &w) in step.source[a..b].iter().zip(&step.weight[a..b]) {
                for (x, &v) in o.iter_mut().zip(source_row(s, src, faces, pc, width)) {
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
                let (pc, f0) = (parent.vertex_count as u32, r.first_vertex_from_faces);
                let mut step = Step {
                    parent_count: parent.vertex_count,
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
                            // Only face points are read as children.
                            Source::Child(i) => pc + (i - f0),
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
