//! Stencil tables in every mode of `Far::StencilTableFactory::Options`
//! ([`StencilOptions`]), on adaptive and uniform refiners.
//!
//! One generic builder serves both: it walks each level's child vertices in
//! OpenSubdiv's order with their refinement terms (the same terms primvar
//! interpolation accumulates: [`AdaptiveRefiner::walk_level`] over the sparse
//! maps, [`Refiner::walk_masks`] over a uniform split) and merges them into
//! rows as OpenSubdiv's `Far::internal::StencilBuilder` does:
//!
//! * the vertices of all levels are numbered one after the other (base
//!   vertices, then level 1, ...); a term naming a vertex below the
//!   builder's "coarse" count is added as it is (weight `w`), any other is
//!   replaced by that vertex's row, each entry weighted `row weight * w`;
//! * factorized, the coarse vertices are the base vertices and the parent
//!   level is read at its global number, so every row ends up over the base;
//!   not factorized, every vertex before the level being built is coarse and
//!   the parent level is read from number 0, so a level's rows are over the
//!   previous level's own numbering;
//! * a face point that an edge or vertex point reads (a child vertex) is
//!   always replaced by its row;
//! * within a row, an index already present has the product added to its
//!   weight, a new one is appended: indices in order of first contribution,
//!   weights accumulated in the order the terms come (`0 + x * w` for the
//!   first, `+= x * w` for later ones: [`RowBuilder`]);
//! * mask terms of weight zero are skipped; entries of a row being copied
//!   are not (none is zero: refinement weights are positive).
//!
//! With the same terms in the same order, every product and sum is the one
//! OpenSubdiv computes, so indices and weights agree bit for bit. The work is
//! linear in the size of the rows built (a slot per coarse vertex instead of
//! OpenSubdiv's search of the row).

use super::AdaptiveRefiner;
use crate::error::{Error, Result};
use crate::real::Real;
use crate::refiner::fvar_interp::fvar_terms;
use crate::refiner::rows::{RowBuilder, Rows};
use crate::refiner::{Emit, Kind, Refiner, Source};
use crate::stencil::{StencilInterpolation, StencilOptions, StencilRows, StencilTable};

/// The position of a child whose row is not built (yet).
const NOT_BUILT: u32 = u32::MAX;

/// A refinement whose levels the builder walks: its vertices, or the
/// values of one face-varying channel ([`Channel`]); mask weights in `T`.
trait Levels<T> {
    /// Number of vertices (values) of `level`.
    fn vertex_count(&self, level: usize) -> usize;
    /// `emit(child, terms)` for every child vertex (value) of `level` (at
    /// least 1), in OpenSubdiv's order.
    fn walk(&self, kind: Kind, level: usize, emit: &mut Emit<'_, T>);
}

/// The values of face-varying channel `channel` of a refinement: the rows
/// `InterpolateFaceVarying` builds when its primvars are stencils.
struct Channel<'a, L> {
    refinement: &'a L,
    channel: usize,
}

impl<T: Real> Levels<T> for Channel<'_, AdaptiveRefiner> {
    fn vertex_count(&self, level: usize) -> usize {
        self.refinement.fvar[self.channel][level].value_count()
    }
    fn walk(&self, _: Kind, level: usize, emit: &mut Emit<'_, T>) {
        fvar_terms(&self.refinement.fvar_step(self.channel, level), emit);
    }
}

impl<T: Real> Levels<T> for Channel<'_, Refiner> {
    fn vertex_count(&self, level: usize) -> usize {
        self.refinement.fvar[self.channel][level].value_count()
    }
    fn walk(&self, _: Kind, level: usize, emit: &mut Emit<'_, T>) {
        fvar_terms(&self.refinement.fvar_step(self.channel, level), emit);
    }
}

impl<T: Real> Levels<T> for AdaptiveRefiner {
    fn vertex_count(&self, level: usize) -> usize {
        self.levels[level].vertex_count
    }
    fn walk(&self, kind: Kind, level: usize, emit: &mut Emit<'_, T>) {
        self.walk_level(kind, level, emit);
    }
}

impl<T: Real> Levels<T> for Refiner {
    fn vertex_count(&self, level: usize) -> usize {
        self.levels[level].vertex_count
    }
    fn walk(&self, kind: Kind, level: usize, emit: &mut Emit<'_, T>) {
        self.walk_masks(kind, level, emit);
    }
}

/// The table `options` ask for (checked, up to level `last`): over the
/// refinement's vertices, or over the values of the face-varying channel
/// they name.
fn table<T: Real>(
    vertices: &dyn Levels<T>,
    values: &dyn Levels<T>,
    options: &StencilOptions,
    last: usize,
) -> Result<StencilTable> {
    let levels = match options.interpolation {
        StencilInterpolation::FaceVarying => values,
        _ => vertices,
    };
    crate::alloc::guard(None, || {
        build(levels, options, last, levels.vertex_count(0))
    })
}

/// The rows of the vertices of `level` in vertex order, from the terms of
/// its child vertices; `prev` holds the rows of level `level - 1` when they
/// replace parent terms (factorized, below level 1).
fn level_rows<T: Real>(
    refinement: &dyn Levels<T>,
    kind: Kind,
    level: usize,
    prev: Option<&Rows<T>>,
    builder: &mut RowBuilder<T>,
) -> Result<Rows<T>> {
    let count = refinement.vertex_count(level);
    let prev = prev.map(Rows::view);
    // Rows in the order they are built, and the position of each child's.
    let mut built = Rows::with_rows(count);
    let mut position = vec![NOT_BUILT; count];
    let mut failed = None;
    refinement.walk(kind, level, &mut |child, terms| {
        if failed.is_some() {
            return;
        }
        let view = built.view();
        // A face point of this level: its row, built earlier (read by
        // position); a parent vertex: its row (factorized) or itself.
        let row_of = |source: Source| match (source, prev) {
            (Source::Child(c), _) => view.get(position[c as usize]),
            (Source::Parent(p), Some(prev)) => prev.get(p),
            (Source::Parent(_), None) => (&[][..], &[][..]),
        };
        let bound = terms.iter().map(|&(s, _)| row_of(s).0.len().max(1)).sum();
        builder.open(bound);
        for &(source, w) in terms {
            if w == T::ZERO {
                continue;
            }
            match (source, prev) {
                // A coarse vertex: as it is.
                (Source::Parent(p), None) => builder.add_row((&[p], &[T::ONE]), w),
                _ => builder.add_row(row_of(source), w),
            }
        }
        let terms = built.terms() + builder.len();
        if u32::try_from(terms).is_err() {
            failed = Some(Error::TooLarge {
                what: "stencil terms",
                count: terms,
                bits: 32,
            });
            return;
        }
        position[child as usize] = built.len() as u32;
        builder.end_row(&mut built);
    });
    if let Some(e) = failed {
        return Err(e);
    }
    // Back to vertex order.
    let mut rows = Rows::with_rows(count);
    rows.expect(built.terms() as f64);
    let view = built.view();
    for &r in &position {
        let (indices, weights) = if r == NOT_BUILT {
            (&[][..], &[][..])
        } else {
            view.get(r)
        };
        rows.push_row(indices, weights);
    }
    Ok(rows)
}

/// The table of `options` over `levels` levels of `refinement` (checked by
/// [`StencilOptions::check`]), whose base level has `base` vertices.
fn build<T: Real>(
    refinement: &dyn Levels<T>,
    options: &StencilOptions,
    last: usize,
    base: usize,
) -> Result<StencilTable> {
    let kind = match options.interpolation {
        StencilInterpolation::Varying => Kind::Varying,
        _ => Kind::Vertex,
    };
    let control = options.generate_control_vertices;
    let factorize = options.factorize_intermediate_levels;
    if last == 0 && !control {
        return Ok(StencilTable::default());
    }
    let widest = (0..last)
        .map(|l| refinement.vertex_count(l))
        .max()
        .unwrap_or(base);
    let mut builder = RowBuilder::new(widest.max(base));
    let mut levels: Vec<Rows<T>> = Vec::with_capacity(last);
    for level in 1..=last {
        let prev = (factorize && level > 1).then(|| &levels[level - 2]);
        let rows = level_rows(refinement, kind, level, prev, &mut builder)?;
        levels.push(rows);
    }
    // Room for the rows asked for; weights widened to the table's f64
    // (exactly).
    let (rows, terms) = levels
        .iter()
        .fold((base, base), |(r, t), l| (r + l.len(), t + l.terms()));
    let mut table = StencilRows::with_capacity(rows, terms);
    let mut push = |idx: &[u32], w: &[T]| table.push_mapped(idx, |i| i, w, |x| x.to_f64());
    // OpenSubdiv's numbering: base rows, then each level's. Control rows
    // come first when asked for; then the rows from `first` on.
    let identity = !factorize && !options.generate_intermediate_levels;
    if control || identity {
        for i in 0..base as u32 {
            push(&[i], &[T::ONE]);
        }
    }
    let from = if options.generate_intermediate_levels || identity {
        0
    } else {
        last.saturating_sub(1)
    };
    for rows in &levels[from..] {
        let view = rows.view();
        for r in 0..rows.len() {
            let (i, w) = view.get(r as u32);
            push(i, w);
        }
    }
    if u32::try_from(table.terms()).is_err() {
        return Err(Error::TooLarge {
            what: "stencil terms",
            count: table.terms(),
            bits: 32,
        });
    }
    Ok(table.finish())
}

impl AdaptiveRefiner {
    /// The stencil table `options` describe
    /// (`Far::StencilTableFactory::Create(refiner, options)` after
    /// `RefineAdaptive`): rows for the vertices of the sparse levels, in the
    /// order and over the vertices [`StencilOptions`] explains, with
    /// OpenSubdiv's indices and weights bit for bit.
    ///
    /// Refused: `max_level` beyond 15 ([`Error::Level`]), the combination
    /// OpenSubdiv 3.5 cannot build ([`Error::StencilOptions`]), a missing
    /// face-varying channel ([`Error::NoSuchChannel`]).
    ///
    /// ```
    /// use subdiv::{refiner::Refiner, shapes, AdaptiveOptions, Options};
    /// use subdiv::stencil::StencilOptions;
    /// let cube = shapes::cube();
    /// let adaptive = Refiner::new(&cube, &Options::default())?
    ///     .refine_adaptive(AdaptiveOptions::new(2), &[])?;
    /// let all = adaptive.stencil_table_with(&StencilOptions::new().control_vertices(true))?;
    /// let counts: usize = (0..=2).map(|l| adaptive.level_counts(l).unwrap().vertices).sum();
    /// assert_eq!(all.len(), counts);
    /// assert_eq!(all.row(0), (&[0u32][..], &[1.0][..])); // a control vertex
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn stencil_table_with(&self, options: &StencilOptions) -> Result<StencilTable> {
        self.stencil_table_in::<f64>(options)
    }

    /// [`AdaptiveRefiner::stencil_table_with`] with its weights computed in
    /// `T` (`StencilTableFactoryReal<T>`), widened to `f64`.
    pub(crate) fn stencil_table_in<T: Real>(
        &self,
        options: &StencilOptions,
    ) -> Result<StencilTable> {
        let channels = self.fvar_channel_count();
        let last = options.check(self.max_level(), channels)?;
        let channel = Channel {
            refinement: self,
            channel: options.fvar_channel,
        };
        table::<T>(self, &channel, options, last as usize)
    }
}

impl Refiner {
    /// The stencil table `options` describe
    /// (`Far::StencilTableFactory::Create(refiner, options)` after
    /// `RefineUniform`), with OpenSubdiv's rows, indices and weights bit for
    /// bit; see [`StencilOptions`] for the rows. [`Refiner::stencil_table`]
    /// remains the fast (parallel) path for the last level's vertex stencils.
    ///
    /// Refused: `max_level` beyond 15 ([`Error::Level`]), the combination
    /// OpenSubdiv 3.5 cannot build ([`Error::StencilOptions`]), a missing
    /// face-varying channel ([`Error::NoSuchChannel`]).
    ///
    /// ```
    /// use subdiv::{refiner::Refiner, shapes, Options, UniformOptions};
    /// use subdiv::stencil::StencilOptions;
    /// let cube = shapes::cube();
    /// let mut r = Refiner::new(&cube, &Options::default())?;
    /// r.refine_uniform(UniformOptions::new(2))?;
    /// let last = r.stencil_table_with(&StencilOptions::new().intermediate_levels(false))?;
    /// assert_eq!(last, r.stencil_table()?);
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn stencil_table_with(&self, options: &StencilOptions) -> Result<StencilTable> {
        self.stencil_table_in::<f64>(options)
    }

    /// [`Refiner::stencil_table_with`] with its weights computed in `T`
    /// (`StencilTableFactoryReal<T>`), widened to `f64`.
    pub(crate) fn stencil_table_in<T: Real>(
        &self,
        options: &StencilOptions,
    ) -> Result<StencilTable> {
        let last = options.check(self.max_level(), self.fvar.len())?;
        let channel = Channel {
            refinement: self,
            channel: options.fvar_channel,
        };
        table::<T>(self, &channel, options, last as usize)
    }
}
