//! Face-varying interpolation: refining the values of one channel from a
//! level to the next with the scheme's masks, adapted to the channel's own
//! topology (the counterpart of `PrimvarRefiner::InterpolateFaceVarying`).
//!
//! Where the channel follows the vertex topology it is refined exactly like
//! vertex data, except that every neighbour's value is read through the
//! channel (a neighbouring vertex may carry several values). Elsewhere:
//!
//! * a point on a split (or linear) edge is the midpoint of the edge's two
//!   values as seen from one incident face — one such value per face;
//! * a vertex value tagged as a corner is copied;
//! * a crease value takes 3/4 of itself and 1/8 of each of the values at the
//!   two ends of its span; a semi-sharp value blends the corner and crease
//!   masks by the fractional weight of the sharpness that decays;
//! * with linear interpolation (option `All`, or the bilinear scheme), face
//!   points average the face's values, edge points are midpoints and
//!   vertex values are copied.
//!
//! Every value is accumulated term by term in the same order as OpenSubdiv,
//! from zero, so `f64` results agree to the last bit. Smooth edges and
//! vertices where the channel follows the vertex topology (nearly all of a
//! UV channel) take their masks from the vertex kernel's cache of regular
//! masks instead of the rules; widths up to 4 are computed with the width
//! known at compile time, wider values in blocks of 16 columns.

use super::fvar_fast::Fast;
use super::kernel::{Cache, MAX_WIDTH, takes_smooth_mask};
use super::{Emit, Refiner, Source};
use crate::error::{Buffer, Error, Result};
use crate::options::{Options, Scheme, TriangleSubdivision};
use crate::output;
use crate::real::Real;
use crate::rules::{EdgeNeighborhood, Mask, Rule, SchemeRules, VertexNeighborhood, crease};
use crate::topology::fvar::{ChannelLevel, Children, missing};
use crate::topology::{Around, AroundBuf, Level, Split, Table};

/// The columns one pass computes of values `stride` wide: `count` of them
/// from `offset` (every column, for the usual widths).
trait Cols: Copy + Send + Sync {
    fn stride(self) -> usize;
    fn offset(self) -> usize;
    fn count(self) -> usize;
}

/// All `W` columns, the width known at compile time.
#[derive(Clone, Copy)]
struct Whole<const W: usize>;

impl<const W: usize> Cols for Whole<W> {
    #[inline(always)]
    fn stride(self) -> usize {
        W
    }
    #[inline(always)]
    fn offset(self) -> usize {
        0
    }
    #[inline(always)]
    fn count(self) -> usize {
        W
    }
}

/// Up to [`MAX_WIDTH`] columns of wider values.
#[derive(Clone, Copy)]
struct Block {
    stride: usize,
    offset: usize,
    count: usize,
}

impl Cols for Block {
    #[inline(always)]
    fn stride(self) -> usize {
        self.stride
    }
    #[inline(always)]
    fn offset(self) -> usize {
        self.offset
    }
    #[inline(always)]
    fn count(self) -> usize {
        self.count
    }
}

/// `acc += w · data[i]`, column by column.
#[inline(always)]
fn add<T: Real, C: Cols>(acc: &mut [T; MAX_WIDTH], data: &[T], i: u32, w: T, cols: C) {
    let start = i as usize * cols.stride() + cols.offset();
    let row = &data[start..start + cols.count()];
    for k in 0..cols.count() {
        acc[k] += row[k] * w;
    }
}

/// Writes `acc` into row `i` of `dst`.
#[inline(always)]
fn put<T: Real, C: Cols>(dst: &mut [T], i: u32, acc: &[T; MAX_WIDTH], cols: C) {
    let start = i as usize * cols.stride() + cols.offset();
    dst[start..start + cols.count()].copy_from_slice(&acc[..cols.count()]);
}

/// Loop: the value at the corner of face `f` opposite edge `e` (corner
/// `k + 2` of a triangle whose edge `k` it is; a comparison, not a division).
#[inline(always)]
fn opposite_value(pf: &ChannelLevel, parent: &Level, f: usize, e: usize) -> u32 {
    let k = parent
        .face_edges_of(f)
        .iter()
        .position(|&x| x as usize == e)
        .unwrap_or(0);
    let values = pf.face_values_of(parent, f);
    let j = k + 2;
    values[if j >= values.len() {
        j - values.len()
    } else {
        j
    }]
}

impl Refiner {
    /// Interpolates the values of face-varying `channel` (`width` components
    /// each) from level `level - 1` to `level`.
    ///
    /// `src` holds the channel's values at `level - 1` (at level 0, the
    /// mesh's own values); the result holds
    /// `width × (value count at level)` components, numbered as
    /// [`Refiner::level`] reports the channel's face values.
    pub fn interpolate_face_varying<T: Real>(
        &self,
        channel: usize,
        level: u32,
        width: usize,
        src: &[T],
    ) -> Result<Vec<T>> {
        crate::alloc::guard(Some(level), || {
            let n = self.fvar_output_len(channel, level, width, src.len())?;
            let mut dst = crate::alloc::vec_or_unwind(T::ZERO, n);
            self.interpolate_fvar_level(channel, level as usize, width, src, &mut dst);
            Ok(dst)
        })
    }

    /// As [`Refiner::interpolate_face_varying`], into a caller's buffer of
    /// `width × (value count at level)` components (every one is written).
    pub fn interpolate_face_varying_into<T: Real>(
        &self,
        channel: usize,
        level: u32,
        width: usize,
        src: &[T],
        dst: &mut [T],
    ) -> Result<()> {
        crate::alloc::guard(Some(level), || {
            let expected = self.fvar_output_len(channel, level, width, src.len())?;
            if dst.len() != expected {
                return Err(Error::BufferLength {
                    buffer: Buffer::Destination,
                    expected,
                    got: dst.len(),
                });
            }
            self.interpolate_fvar_level(channel, level as usize, width, src, dst);
            Ok(())
        })
    }

    /// Interpolates face-varying `channel` through every level from the
    /// mesh's values `base` (`width` components each): `result[l]` is level
    /// `l` (`result[0]` a copy of `base`), numbered as [`Refiner::level`]
    /// reports the channel's face values. As [`Refiner::interpolate_all`],
    /// the levels come as [`output::Values`], large ones in huge-page maps recycled
    /// when dropped.
    ///
    /// ```
    /// use subdiv::{refiner::Refiner, shapes, Options, UniformOptions};
    /// let mesh = shapes::with_torus_uvs(shapes::torus(8, 6), 8, 6);
    /// let mut r = Refiner::new(&mesh, &Options::default())?;
    /// r.refine_uniform(UniformOptions::new(2))?;
    /// let base: Vec<f32> = mesh.fvar_channels[0].values.iter().map(|&x| x as f32).collect();
    /// let levels = r.interpolate_face_varying_all(0, 2, &base)?;
    /// let one = r.interpolate_face_varying(0, 1, 2, &base)?;
    /// assert_eq!(levels[1], one);
    /// assert_eq!(levels[2], r.interpolate_face_varying(0, 2, 2, &one)?);
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn interpolate_face_varying_all<T: Real>(
        &self,
        channel: usize,
        width: usize,
        base: &[T],
    ) -> Result<Vec<output::Values<T>>> {
        crate::alloc::guard(None, || {
            let mut out = vec![output::Values(Table::from_slice(base))];
            for level in 1..=self.max_level() {
                let src = out.last().expect("non-empty");
                let next = self.interpolate_fvar_table(channel, level, width, src)?;
                out.push(output::Values(next));
            }
            Ok(out)
        })
    }

    /// Interpolates face-varying `channel` through every level and returns
    /// the last level's values only, holding no more than two levels at a
    /// time (as [`Refiner::interpolate_last`] does for vertex data).
    pub fn interpolate_face_varying_last<T: Real>(
        &self,
        channel: usize,
        width: usize,
        base: &[T],
    ) -> Result<output::Values<T>> {
        crate::alloc::guard(None, || {
            // Level 1 reads `base` where it is: no copy of it.
            let mut current: Option<Table<T>> = None;
            for level in 1..=self.max_level() {
                let src = current.as_deref().unwrap_or(base);
                current = Some(self.interpolate_fvar_table(channel, level, width, src)?);
            }
            match current {
                Some(values) => Ok(output::Values(values)),
                None => {
                    // Nothing refined: the base values back, checked all the same.
                    let levels = self.fvar.get(channel).ok_or(Error::NoSuchChannel {
                        channel,
                        count: self.fvar.len(),
                    })?;
                    let expected = levels[0].value_count() * width;
                    if base.len() != expected {
                        return Err(Error::BufferLength {
                            buffer: Buffer::FaceVaryingSource,
                            expected,
                            got: base.len(),
                        });
                    }
                    Ok(output::Values(Table::from_slice(base)))
                }
            }
        })
    }

    /// One level of one channel into a table from the pool (written once).
    fn interpolate_fvar_table<T: Real>(
        &self,
        channel: usize,
        level: u32,
        width: usize,
        src: &[T],
    ) -> Result<Table<T>> {
        let n = self.fvar_output_len(channel, level, width, src.len())?;
        let mut dst = Table::for_overwrite(n);
        self.interpolate_fvar_level(channel, level as usize, width, src, &mut dst);
        Ok(dst)
    }

    /// The length of the values of `channel` at `level` (`width` components
    /// each), once the call's channel, level, width and source length
    /// (`src_len`) are checked.
    fn fvar_output_len(
        &self,
        channel: usize,
        level: u32,
        width: usize,
        src_len: usize,
    ) -> Result<usize> {
        let (_, child) =
            fvar_call_levels(&self.fvar, channel, level, self.max_level(), width, src_len)?;
        Ok(child.value_count() * width)
    }

    /// One level of one channel.
    pub(super) fn interpolate_fvar_level<T: Real>(
        &self,
        channel: usize,
        level: usize,
        width: usize,
        src: &[T],
        dst: &mut [T],
    ) {
        let fast = self.fvar_by_vertex_kernel(channel, level, width, src, dst);
        let step = FVarStep {
            fast: fast.as_ref(),
            ..self.fvar_step(channel, level)
        };
        fvar_level(&step, width, src, dst);
    }

    /// The step of face-varying `channel` from level `level - 1` to `level`.
    pub(crate) fn fvar_step(&self, channel: usize, level: usize) -> FVarStep<'_, Split> {
        FVarStep {
            rules: &self.rules,
            options: &self.options,
            parent: self.around(level - 1),
            child: &self.levels[level],
            r: &self.refinements[level - 1],
            pf: &self.fvar[channel][level - 1],
            cf: &self.fvar[channel][level],
            fast: None,
        }
    }
}

/// The channel's levels `level - 1` and `level` for interpolating `src_len`
/// values `width` wide, or the error naming what is wrong with the call: a
/// channel, level or width that does not exist, or a source of the wrong
/// length. `channels[c][l]` is channel `c` at level `l`.
pub(crate) fn fvar_call_levels(
    channels: &[Vec<ChannelLevel>],
    channel: usize,
    level: u32,
    max_level: u32,
    width: usize,
    src_len: usize,
) -> Result<(&ChannelLevel, &ChannelLevel)> {
    let levels = channels.get(channel).ok_or(Error::NoSuchChannel {
        channel,
        count: channels.len(),
    })?;
    crate::limits::check_interpolation_call(level, max_level, width)?;
    let (parent, child) = (&levels[level as usize - 1], &levels[level as usize]);
    if src_len != parent.value_count() * width {
        return Err(Error::BufferLength {
            buffer: Buffer::FaceVaryingSource,
            expected: parent.value_count() * width,
            got: src_len,
        });
    }
    Ok((parent, child))
}

/// What one level's face-varying interpolation reads: the rules and
/// options, the two levels, how the step numbers the children (uniformly or
/// sparsely), and the channel at both levels.
pub(crate) struct FVarStep<'a, R> {
    pub rules: &'a SchemeRules,
    pub options: &'a Options,
    /// The parent level, its relations stored or derived.
    pub parent: Around<'a>,
    pub child: &'a Level,
    pub r: &'a R,
    pub pf: &'a ChannelLevel,
    pub cf: &'a ChannelLevel,
    /// With the children the vertex kernel computed
    /// (`Refiner::fvar_by_vertex_kernel`), the elements whose children are
    /// left: the pass computes only those.
    pub fast: Option<&'a Fast>,
}

/// One level of one channel: face points, edge points, vertex points. The
/// usual widths are computed whole, wider values in blocks of columns (each
/// block a full pass: the masks are linear).
pub(crate) fn fvar_level<T: Real, R: Children + Sync>(
    step: &FVarStep<'_, R>,
    width: usize,
    src: &[T],
    dst: &mut [T],
) {
    match width {
        1 => fvar_pass(step, Whole::<1>, src, dst),
        2 => fvar_pass(step, Whole::<2>, src, dst),
        3 => fvar_pass(step, Whole::<3>, src, dst),
        4 => fvar_pass(step, Whole::<4>, src, dst),
        _ => {
            for offset in (0..width).step_by(MAX_WIDTH) {
                let cols = Block {
                    stride: width,
                    offset,
                    count: (width - offset).min(MAX_WIDTH),
                };
                fvar_pass(step, cols, src, dst);
            }
        }
    }
}

/// Columns `cols` of one level of one channel: the face points, then the
/// edge points and the vertex points (which read the face points), each kind
/// in parallel over chunks of parent elements after a uniform split (see
/// [`Pass`]), in one run after a sparse one.
fn fvar_pass<T: Real, C: Cols, R: Children + Sync>(
    step: &FVarStep<'_, R>,
    cols: C,
    src: &[T],
    dst: &mut [T],
) {
    let cf = step.cf;
    let pass = Pass::new(step);
    let blocks = step.r.vertex_runs(step.parent.level);
    // The values of each kind of child vertex are one run of `dst`.
    let run = |(first, count, _): (u32, usize, usize)| {
        let (a, b) = (first as usize, first as usize + count);
        (cf.vertex_value_offset(a), cf.vertex_value_offset(b))
    };
    let mut runs = [
        (run(blocks[0]), 0),
        (run(blocks[1]), 1),
        (run(blocks[2]), 2),
    ];
    runs.sort_unstable();
    let stride = cols.stride();
    let mut parts: [Out<T>; 3] = [Out::empty(), Out::empty(), Out::empty()];
    let mut rest = dst;
    let mut at = 0;
    for ((start, end), kind) in runs {
        let (_, tail) = rest.split_at_mut((start - at) as usize * stride);
        let (part, tail) = tail.split_at_mut((end - start) as usize * stride);
        parts[kind] = Out {
            data: part,
            base: start,
        };
        rest = tail;
        at = end;
    }
    let [mut faces, mut edges, mut vertices] = parts;
    if let Some(left) = step.fast {
        // Only what the vertex kernel left, in one run.
        fn each(list: &[u32]) -> impl Iterator<Item = usize> + '_ {
            list.iter().map(|&x| x as usize)
        }
        pass.face_points(
            each(&left.faces),
            &mut Values::new(src, View::empty(), faces.reborrow(), cols),
        );
        let faces = faces.view();
        pass.edge_points(
            each(&left.edges),
            &mut Values::new(src, faces, edges.reborrow(), cols),
        );
        pass.vertex_points(
            each(&left.vertices),
            &mut Values::new(src, faces, vertices.reborrow(), cols),
        );
        return;
    }
    let chunks = |kind: usize| Chunks {
        first: blocks[kind].0,
        parents: blocks[kind].2,
        uniform: !R::SPARSE,
    };
    in_chunks(cf, chunks(0), faces.reborrow(), stride, |range, out| {
        pass.face_points(range, &mut Values::new(src, View::empty(), out, cols))
    });
    let faces = faces.view();
    in_chunks(cf, chunks(1), edges, stride, |range, out| {
        pass.edge_points(range, &mut Values::new(src, faces, out, cols))
    });
    in_chunks(cf, chunks(2), vertices, stride, |range, out| {
        pass.vertex_points(range, &mut Values::new(src, faces, out, cols))
    });
}

/// The terms of every value of one level of one channel, in OpenSubdiv's
/// order (face points, edge points, vertex points, each by parent element,
/// a vertex's values in sibling order): `emit(value, terms)`, each term
/// reading a value of the parent level or a face point's value of the
/// child level, with the weights the interpolation multiplies it by. Every
/// value of the channel at the child level comes once.
pub(crate) fn fvar_terms<T: Real, R: Children>(step: &FVarStep<'_, R>, emit: &mut Emit<'_, T>) {
    let pass = Pass::<T, R>::new(step);
    let blocks = step.r.vertex_runs(step.parent.level);
    let mut sink = Terms {
        terms: Vec::new(),
        emit,
    };
    pass.face_points(0..blocks[0].2, &mut sink);
    pass.edge_points(0..blocks[1].2, &mut sink);
    pass.vertex_points(0..blocks[2].2, &mut sink);
}

/// What the pass does with each value's terms, in the order it finds them:
/// accumulates them ([`Values`]) or hands them on ([`Terms`]).
trait Sink<T> {
    /// Adds `w` times value `x` of the parent level to the value being
    /// built.
    fn parent(&mut self, x: u32, w: T);
    /// Adds `w` times value `x` of the child level (a face point's, built
    /// earlier) to the value being built.
    fn centre(&mut self, x: u32, w: T);
    /// The value being built is value `x` of the child level; the next
    /// starts from zero.
    fn finish(&mut self, x: u32);
}

/// Accumulates columns `cols` of each value and writes it into `out`.
struct Values<'a, 'o, T, C> {
    acc: [T; MAX_WIDTH],
    src: &'a [T],
    faces: View<'a, T>,
    out: Out<'o, T>,
    cols: C,
}

impl<'a, 'o, T: Real, C: Cols> Values<'a, 'o, T, C> {
    fn new(src: &'a [T], faces: View<'a, T>, out: Out<'o, T>, cols: C) -> Self {
        Values {
            acc: [T::ZERO; MAX_WIDTH],
            src,
            faces,
            out,
            cols,
        }
    }
}

impl<T: Real, C: Cols> Sink<T> for Values<'_, '_, T, C> {
    #[inline(always)]
    fn parent(&mut self, x: u32, w: T) {
        add(&mut self.acc, self.src, x, w, self.cols);
    }
    #[inline(always)]
    fn centre(&mut self, x: u32, w: T) {
        add(
            &mut self.acc,
            self.faces.data,
            x - self.faces.base,
            w,
            self.cols,
        );
    }
    #[inline(always)]
    fn finish(&mut self, x: u32) {
        put(self.out.data, x - self.out.base, &self.acc, self.cols);
        self.acc = [T::ZERO; MAX_WIDTH];
    }
}

/// Collects each value's terms and hands them to `emit`.
struct Terms<'e, 'f, T> {
    terms: Vec<(Source, T)>,
    emit: &'e mut Emit<'f, T>,
}

impl<T: Real> Sink<T> for Terms<'_, '_, T> {
    fn parent(&mut self, x: u32, w: T) {
        self.terms.push((Source::Parent(x), w));
    }
    fn centre(&mut self, x: u32, w: T) {
        self.terms.push((Source::Child(x), w));
    }
    fn finish(&mut self, x: u32) {
        (self.emit)(x, &self.terms);
        self.terms.clear();
    }
}

/// The parent elements of one kind whose children [`in_chunks`] computes.
struct Chunks {
    /// The first child.
    first: u32,
    /// How many parents of the kind.
    parents: usize,
    /// Whether parent `first + i` has child `first + i` (a uniform split),
    /// so that chunks of parents are chunks of children.
    uniform: bool,
}

/// Values of a run of child vertices being written: `data` holds values
/// `base..` of the level.
struct Out<'a, T> {
    data: &'a mut [T],
    base: u32,
}

impl<'a, T> Out<'a, T> {
    fn empty() -> Self {
        Out {
            data: &mut [],
            base: 0,
        }
    }

    fn reborrow(&mut self) -> Out<'_, T> {
        Out {
            data: self.data,
            base: self.base,
        }
    }

    fn view(self) -> View<'a, T> {
        View {
            data: self.data,
            base: self.base,
        }
    }
}

/// Values of a run of child vertices already computed: values `base..`.
#[derive(Clone, Copy)]
struct View<'a, T> {
    data: &'a [T],
    base: u32,
}

impl<T> View<'_, T> {
    fn empty() -> Self {
        View { data: &[], base: 0 }
    }
}

/// Calls `body(elements, out)` on chunks of the parent elements of
/// `chunks` (their children's values in `out`), in parallel when the
/// current rayon pool has more than one thread and the split is uniform.
fn in_chunks<T: Real>(
    cf: &ChannelLevel,
    chunks: Chunks,
    out: Out<'_, T>,
    stride: usize,
    body: impl Fn(std::ops::Range<usize>, Out<'_, T>) + Sync,
) {
    use rayon::prelude::*;
    const CHUNK: usize = 4096;
    let (first, count) = (chunks.first, chunks.parents);
    if count <= CHUNK || rayon::current_num_threads() == 1 || !chunks.uniform {
        body(0..count, out);
        return;
    }
    let mut chunks = Vec::with_capacity(count.div_ceil(CHUNK));
    let mut rest = out;
    for start in (0..count).step_by(CHUNK) {
        let end = (start + CHUNK).min(count);
        let values = cf.vertex_value_offset(first as usize + end) - rest.base;
        let (data, tail) = rest.data.split_at_mut(values as usize * stride);
        chunks.push((
            start..end,
            Out {
                data,
                base: rest.base,
            },
        ));
        rest = Out {
            data: tail,
            base: rest.base + values,
        };
    }
    chunks
        .into_par_iter()
        .for_each(|(range, out)| body(range, out));
}

/// One pass of one level of one channel, its terms going to a [`Sink`]. Where the
/// channel follows the vertex topology and the element is smooth, the masks
/// come from the kernel's cache of regular masks, as for vertex data;
/// elsewhere from the rules, element by element.
struct Pass<'a, T, R> {
    rules: &'a SchemeRules,
    options: &'a Options,
    parent: &'a Level,
    /// `parent` with its relations, stored or derived.
    around: Around<'a>,
    child: &'a Level,
    r: &'a R,
    pf: &'a ChannelLevel,
    cf: &'a ChannelLevel,
    linear: bool,
    tri_smooth: bool,
    weights: std::marker::PhantomData<T>,
}

impl<'a, T: Real, R: Children> Pass<'a, T, R> {
    fn new(step: &FVarStep<'a, R>) -> Self {
        let scheme = step.rules.scheme();
        Pass {
            rules: step.rules,
            options: step.options,
            parent: step.parent.level,
            around: step.parent,
            child: step.child,
            r: step.r,
            pf: step.pf,
            cf: step.cf,
            linear: step.pf.is_linear() || scheme == Scheme::Bilinear,
            tri_smooth: scheme == Scheme::Catmark
                && step.options.triangles == TriangleSubdivision::Smooth,
            weights: std::marker::PhantomData,
        }
    }

    /// The value (of the child level) of the face point of parent face `f`.
    #[inline(always)]
    fn centre(&self, f: u32) -> u32 {
        self.cf
            .vertex_value_offset(self.r.face_child(f as usize) as usize)
    }

    /// Face points (none with Loop's split): the average of the face's values.
    fn face_points(&self, faces: impl Iterator<Item = usize>, sink: &mut impl Sink<T>) {
        let (parent, r, pf, cf) = (self.parent, self.r, self.pf, self.cf);
        let mut cache = Cache::<T>::new();
        for f in faces {
            if missing::<R>(r.face_child(f)) {
                continue;
            }
            let values = pf.face_values_of(parent, f);
            let w = cache.face_weight(self.rules, values.len());
            for &x in values {
                sink.parent(x, w);
            }
            sink.finish(cf.vertex_value_offset(r.face_child(f) as usize));
        }
    }

    /// Edge points; `faces` holds the face points.
    fn edge_points(&self, edges: impl Iterator<Item = usize>, sink: &mut impl Sink<T>) {
        let (parent, child, r, pf, cf) = (self.parent, self.child, self.r, self.pf, self.cf);
        let mut cache = Cache::<T>::new();
        let mut mask = Mask::<T>::new();
        let half = T::from_f64(0.5);
        let mut face_sizes = Vec::new();
        for e in edges {
            let c = r.edge_child(e);
            if missing::<R>(c) {
                continue;
            }
            let c = c as usize;
            let first = cf.vertex_value_offset(c);
            if cf.vertex_value_tags(c)[0].is_mismatch() {
                // One midpoint per value, from the face the value comes from.
                for i in 0..cf.vertex_value_count(c) {
                    let [a, b] = pf.edge_face_values(&self.around, e, i);
                    sink.parent(a, half);
                    sink.parent(b, half);
                    sink.finish(first + i as u32);
                }
                continue;
            }
            let e_faces = self.around.edge_faces(e);
            let e_faces = e_faces.as_slice();
            let [a, b] = pf.edge_face_values(&self.around, e, 0);
            if self.linear {
                sink.parent(a, half);
                sink.parent(b, half);
                sink.finish(first);
                continue;
            }
            let s = parent.edge_sharpness_at(e);
            let smooth = match e_faces {
                &[f0, f1] if s <= 0.0 => cache.smooth_edge(
                    self.rules,
                    [
                        self.tri_smooth && parent.face_vertices.count(f0 as usize) == 3,
                        self.tri_smooth && parent.face_vertices.count(f1 as usize) == 3,
                    ],
                ),
                _ => None,
            };
            if let Some(w) = smooth {
                // The kernel's smooth edge: the weights and terms the rules
                // give below, in the same order.
                sink.parent(a, w.ends[0]);
                sink.parent(b, w.ends[1]);
                if let Some(fw) = w.faces {
                    for (&f, fw) in e_faces.iter().zip(fw) {
                        if w.centers {
                            sink.centre(self.centre(f), fw);
                        } else {
                            let x = opposite_value(pf, parent, f as usize, e);
                            sink.parent(x, fw);
                        }
                    }
                }
                sink.finish(first);
                continue;
            }
            face_sizes.clear();
            face_sizes.extend(
                e_faces
                    .iter()
                    .map(|&f| parent.face_vertices.count(f as usize) as u32),
            );
            let hood = EdgeNeighborhood {
                sharpness: s,
                face_sizes: &face_sizes,
            };
            let p_rule = if s > 0.0 { Rule::Crease } else { Rule::Smooth };
            self.rules
                .edge_vertex_mask(&hood, p_rule, child.vertex_tag(c).rule(), &mut mask);
            sink.parent(a, mask.vertex[0]);
            sink.parent(b, mask.vertex[1]);
            for (&f, &w) in e_faces.iter().zip(&mask.face) {
                if mask.face_weights_for_centers {
                    sink.centre(self.centre(f), w);
                } else {
                    // Loop: the value at the face's corner opposite the edge.
                    sink.parent(opposite_value(pf, parent, f as usize, e), w);
                }
            }
            sink.finish(first);
        }
    }

    /// Vertex points; `faces` holds the face points.
    fn vertex_points(&self, vertices: impl Iterator<Item = usize>, sink: &mut impl Sink<T>) {
        let (parent, child, r, pf, cf) = (self.parent, self.child, self.r, self.pf, self.cf);
        let options = self.options;
        let mut cache = Cache::<T>::new();
        let mut mask = Mask::<T>::new();
        let mut edge_sharpness = Vec::new();
        let mut child_edge_sharpness = Vec::new();
        let mut edge_values = Vec::new();
        let mut buf = AroundBuf::default();
        let corner_weight = T::from_f64(0.75);
        let end_weight = T::from_f64(0.125);
        for v in vertices {
            let c = r.vertex_child(v);
            if missing::<R>(c) {
                continue;
            }
            let c = c as usize;
            let first = cf.vertex_value_offset(c);
            let c_tags = cf.vertex_value_tags(c);
            if !c_tags[0].is_mismatch() {
                let own = pf.vertex_value(v, 0);
                if self.linear {
                    sink.parent(own, T::ONE);
                    sink.finish(first);
                    continue;
                }
                let hood = self.around.vertex_hood(v, &mut buf);
                let (edges, v_faces) = (hood.edges, hood.faces);
                let p_rule = parent.vertex_tag(v).rule();
                let m = if takes_smooth_mask(p_rule, v_faces.len(), edges.len()) {
                    // The kernel's smooth vertex (as the rules give it).
                    cache.smooth_vertex(self.rules, v_faces.len())
                } else {
                    edge_sharpness.clear();
                    edge_sharpness
                        .extend(edges.iter().map(|&e| parent.edge_sharpness_at(e as usize)));
                    child_edge_sharpness.resize(edges.len(), 0.0);
                    crease::subdivide_edge_sharpnesses_around_vertex(
                        options.creasing,
                        &edge_sharpness,
                        &mut child_edge_sharpness,
                    );
                    let hood = VertexNeighborhood {
                        sharpness: parent.vertex_sharpness_at(v),
                        edge_sharpness: &edge_sharpness,
                        face_count: v_faces.len(),
                        child_sharpness: child.vertex_sharpness_at(c),
                        child_edge_sharpness: &child_edge_sharpness,
                    };
                    let c_rule = child.vertex_tag(c).rule();
                    self.rules
                        .vertex_vertex_mask(&hood, p_rule, c_rule, &mut mask);
                    &mask
                };
                for (&f, &w) in v_faces.iter().zip(&m.face) {
                    sink.centre(self.centre(f), w);
                }
                if !m.edge.is_empty() {
                    pf.vertex_edge_values(&self.around, &hood, v, &mut edge_values);
                    for (&x, &w) in edge_values.iter().zip(&m.edge) {
                        sink.parent(x, w);
                    }
                }
                sink.parent(own, m.vertex[0]);
                sink.finish(first);
                continue;
            }
            // Each value on its own: a corner, a crease, or a corner decaying
            // into a crease.
            let p_tags = pf.vertex_value_tags(v);
            let hood = self.around.vertex_hood(v, &mut buf);
            for (s, &tag) in c_tags.iter().enumerate() {
                let own = pf.vertex_value(v, s);
                if self.linear || tag.is_corner() {
                    sink.parent(own, T::ONE);
                } else {
                    let [e0, e1] = pf.crease_end_values(parent, &hood, v, s);
                    let (mut vw, mut ew) = (corner_weight, end_weight);
                    if p_tags[s].is_semi_sharp() {
                        // A value sharpened by its sibling decays with it.
                        let from = if p_tags[s].is_dep_sharp() {
                            (s == 0) as usize
                        } else {
                            s
                        };
                        let w = pf.fractional_weight(
                            (parent, child),
                            &hood,
                            v,
                            from,
                            c,
                            options.creasing,
                        );
                        let corner = T::from_f32(w);
                        let crease = T::ONE - corner;
                        vw = crease * corner_weight + corner;
                        ew = crease * end_weight;
                    }
                    sink.parent(e0, ew);
                    sink.parent(e1, ew);
                    sink.parent(own, vw);
                }
                sink.finish(first + s as u32);
            }
        }
    }
}

impl Refiner {
    /// Limit values of face-varying `channel` at the last level, from its
    /// values at that level (`PrimvarRefiner::LimitFaceVarying`): the vertex
    /// limit mask where the channel is continuous, the crease limit (2/3 and
    /// 1/6, 1/6 along the channel's boundary) or the value itself (corners)
    /// where it is split, and the values unchanged for a linear channel.
    pub fn limit_face_varying<T: Real>(
        &self,
        channel: usize,
        width: usize,
        src: &[T],
    ) -> Result<Vec<T>> {
        crate::alloc::guard(None, || {
            let levels = self.fvar.get(channel).ok_or(Error::NoSuchChannel {
                channel,
                count: self.fvar.len(),
            })?;
            if width == 0 {
                return Err(Error::ZeroWidth);
            }
            let level = self.levels.last().expect("base level");
            if !level.has_full_topology() {
                return Err(Error::NeedsFullTopology);
            }
            let fvar = levels.last().expect("base channel");
            if src.len() != fvar.value_count() * width {
                return Err(Error::BufferLength {
                    buffer: Buffer::FaceVaryingSource,
                    expected: fvar.value_count() * width,
                    got: src.len(),
                });
            }
            let mut dst = crate::alloc::vec_or_unwind(T::ZERO, src.len());
            let mut acc = vec![T::ZERO; width];
            let mut mask = crate::rules::Mask::<T>::new();
            let mut edge_sharpness = Vec::new();
            let mut edge_values = Vec::new();
            let around = Around::stored(level);
            let mut buf = AroundBuf::default();
            let row = |i: u32| &src[i as usize * width..(i as usize + 1) * width];
            let add = |acc: &mut [T], r: &[T], w: T| {
                for (a, &s) in acc.iter_mut().zip(r) {
                    *a += s * w;
                }
            };
            // OpenSubdiv writes these two weights as single-precision literals.
            let sixth = T::from_f32(1.0f32 / 6.0f32);
            let two_thirds = T::from_f32(2.0f32 / 3.0f32);
            for v in 0..level.vertex_count {
                let count = fvar.vertex_value_count(v);
                let hood = around.vertex_hood(v, &mut buf);
                let edges = hood.edges;
                let store = |dst: &mut [T], value: u32, acc: &[T]| {
                    let i = value as usize * width;
                    dst[i..i + width].copy_from_slice(acc);
                };
                if edges.is_empty() || fvar.is_linear() {
                    for s in 0..count {
                        let value = fvar.vertex_value(v, s);
                        store(&mut dst, value, row(value));
                    }
                    continue;
                }
                let tags = fvar.vertex_value_tags(v);
                if !tags[0].is_mismatch() {
                    edge_sharpness.clear();
                    edge_sharpness
                        .extend(edges.iter().map(|&e| level.edge_sharpness_at(e as usize)));
                    let faces = hood.faces;
                    let v_hood = crate::rules::VertexNeighborhood {
                        sharpness: level.vertex_sharpness_at(v),
                        edge_sharpness: &edge_sharpness,
                        face_count: faces.len(),
                        child_sharpness: level.vertex_sharpness_at(v),
                        child_edge_sharpness: &[],
                    };
                    self.rules.vertex_limit_position_mask(
                        &v_hood,
                        level.vertex_tag(v).rule(),
                        &mut mask,
                    );
                    let value = fvar.vertex_value(v, 0);
                    acc.fill(T::ZERO);
                    if !mask.face.is_empty() {
                        for ((&f, &k), &w) in faces.iter().zip(hood.face_locals).zip(&mask.face) {
                            let values = fvar.face_values_of(level, f as usize);
                            add(&mut acc, row(values[(k as usize + 2) % values.len()]), w);
                        }
                    }
                    if !mask.edge.is_empty() {
                        fvar.vertex_edge_values(&around, &hood, v, &mut edge_values);
                        for (&ev, &w) in edge_values.iter().zip(&mask.edge) {
                            add(&mut acc, row(ev), w);
                        }
                    }
                    add(&mut acc, row(value), mask.vertex[0]);
                    store(&mut dst, value, &acc);
                } else {
                    for (s, tag) in tags.iter().enumerate().take(count) {
                        let value = fvar.vertex_value(v, s);
                        if tag.is_corner() {
                            store(&mut dst, value, row(value));
                        } else {
                            let [a, b] = fvar.crease_end_values(level, &hood, v, s);
                            acc.fill(T::ZERO);
                            add(&mut acc, row(a), sixth);
                            add(&mut acc, row(b), sixth);
                            add(&mut acc, row(value), two_thirds);
                            store(&mut dst, value, &acc);
                        }
                    }
                }
            }
            Ok(dst)
        })
    }
}
