//! The native engine: refine topology once, then interpolate any number of
//! primvar sets against it — the native counterpart of OpenSubdiv's
//! `Far::TopologyRefiner` and `Far::PrimvarRefiner`.
//!
//! ```
//! use subdiv::{refiner::Refiner, shapes, Options, UniformOptions};
//! let cube = shapes::cube();
//! let mut refiner = Refiner::new(&cube, &Options::default())?;
//! refiner.refine_uniform(UniformOptions::new(2))?;
//! let positions = refiner.refine_positions(&cube.positions)?;
//! assert_eq!(positions[2].len(), 98);
//! # Ok::<(), subdiv::Error>(())
//! ```

use crate::error::{Buffer, Error, Result};
use crate::limits::check_level_counts;
use crate::mesh::{Mesh, MeshWarning};
use crate::options::{Options, Scheme, UniformOptions};
use crate::output::Values;
use crate::real::Real;
use crate::rules::{EdgeNeighborhood, Rule, SchemeRules, VertexNeighborhood, crease};
use crate::topology::fvar::ChannelLevel;
pub(crate) use crate::topology::fvar::Children;
use crate::topology::{
    Build, Level, LevelSlices, Split, Table, build_base_level, fvar, refine_level,
};

pub mod adaptive;
mod fvar_fast;
pub(crate) mod fvar_interp;
#[cfg(test)]
mod fvar_paths_tests;
mod queries;
mod whole;
use glam::{DVec3, Vec3};

pub(crate) mod kernel;
mod limit;
mod rows;
mod stencil_factory;

pub use adaptive::AdaptiveRefiner;
pub(crate) use kernel::{Scratch, accumulate};
pub use queries::Faces;
pub use stencil_factory::FactorizedStencils;
pub use whole::{refine, refine_last};
pub(crate) use whole::{refine_last_owned, refine_last_with};

/// The vertex of face `f` opposite edge `e` (Loop's edge-point face weights).
#[inline(always)]
pub(crate) fn opposite_vertex(level: &LevelSlices<'_>, f: usize, e: usize) -> u32 {
    if let &[a, b, c] = level.face_verts(f)
        && a != b
        && b != c
        && a != c
    {
        // Three distinct corners: edge `e` joins two of them, and the third
        // is what remains of the five once the pairs cancel. No search for
        // the edge in the face (whose branch is a coin toss per face).
        let [u, v] = level.edge_vertices[e];
        return a ^ b ^ c ^ u ^ v;
    }
    let f_edges = level.face_edges_of(f);
    let k = f_edges.iter().position(|&x| x as usize == e).unwrap_or(0);
    level.face_verts(f)[(k + 2) % f_edges.len()]
}

/// Where a mask term reads its value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Source {
    /// A vertex of the parent level.
    Parent(u32),
    /// A vertex of the child level computed earlier (a face point).
    Child(u32),
}

/// Receives each child vertex (or face-varying value) and its mask terms,
/// weights in `T` (`f64` unless named).
pub(crate) type Emit<'a, T = f64> = dyn FnMut(u32, &[(Source, T)]) + 'a;

/// The three kinds of parent element a child vertex comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Block {
    /// Face points.
    Faces,
    /// Edge points.
    Edges,
    /// Vertex points.
    Vertices,
}

/// Kinds of primvar interpolation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    Vertex,
    Varying,
}

/// A mesh's topology refined natively, level by level.
#[derive(Debug, Clone)]
pub struct Refiner {
    pub(crate) options: Options,
    pub(crate) rules: SchemeRules,
    pub(crate) levels: Vec<Level>,
    pub(crate) refinements: Vec<Split>,
    pub(crate) uniform: Option<UniformOptions>,
    /// Face-varying topology: `fvar[channel][level]`.
    pub(crate) fvar: Vec<Vec<ChannelLevel>>,
    warnings: Vec<MeshWarning>,
}

impl Refiner {
    /// Builds the base level of a mesh (validated first; a mesh without faces
    /// is [`Error::EmptyMesh`], as in the `osd` engine).
    /// A [`Mesh::left_handed`] mesh is read as OpenSubdiv reads it
    /// ([`Mesh::right_handed`]).
    pub fn new(mesh: &Mesh, options: &Options) -> Result<Refiner> {
        crate::alloc::guard(None, || {
            let validation = mesh.validate()?;
            let mesh = &*mesh.right_handed();
            if options.scheme == Scheme::Loop
                && let Some((face, size)) = mesh
                    .faces()
                    .map(<[u32]>::len)
                    .enumerate()
                    .find(|&(_, n)| n != 3)
            {
                return Err(Error::NotTriangles {
                    scheme: Scheme::Loop,
                    face,
                    corners: size,
                });
            }
            if mesh.face_count() == 0 {
                return Err(Error::EmptyMesh);
            }
            let base = build_base_level(mesh, options);
            if let Some(v) = crate::topology::unpaired_smooth_vertex(&base) {
                return Err(Error::UnpairedSmoothVertex {
                    level: 0,
                    vertex: v,
                });
            }
            let fvar = mesh
                .fvar_channels
                .iter()
                .map(|c| {
                    vec![fvar::build_base(
                        &base,
                        options,
                        c.value_count(),
                        &c.indices,
                    )]
                })
                .collect();
            Ok(Refiner {
                options: *options,
                rules: SchemeRules::new(options),
                levels: vec![base],
                refinements: Vec::new(),
                uniform: None,
                fvar,
                warnings: validation.warnings,
            })
        })
    }

    /// Warnings found while validating the mesh.
    pub fn warnings(&self) -> &[MeshWarning] {
        &self.warnings
    }

    /// The options the refiner was built with.
    pub fn options(&self) -> &Options {
        &self.options
    }

    /// Refines uniformly to `uniform.level`, discarding any earlier refinement.
    pub fn refine_uniform(&mut self, uniform: UniformOptions) -> Result<()> {
        let result = crate::alloc::guard(Some(uniform.level), || self.refine_levels(uniform));
        if result.is_err() {
            // Nothing half-refined stays behind: back to the base level.
            self.levels.truncate(1);
            self.refinements.clear();
            for channel in &mut self.fvar {
                channel.truncate(1);
            }
            self.uniform = None;
        }
        result
    }

    /// [`Refiner::refine_uniform`]'s work; on an error the caller resets.
    fn refine_levels(&mut self, uniform: UniformOptions) -> Result<()> {
        let base = &self.levels[0];
        check_level_counts(
            base.face_count(),
            base.face_vertices.members.len(),
            self.options.scheme,
            uniform.level,
        )?;
        self.levels.truncate(1);
        self.refinements.clear();
        for channel in &mut self.fvar {
            channel.truncate(1);
        }
        for level in 1..=uniform.level {
            let parent = self.levels.last().expect("base level");
            // Like OpenSubdiv, the last level gets only what interpolation
            // needs unless full topology is asked for (and the vertex-faces
            // that face-varying refinement reads).
            let (r, child) = refine_level(
                parent,
                &self.options,
                uniform.order_vertices_from_faces_first,
                Build::for_level(
                    level as usize,
                    uniform.level as usize,
                    !uniform.full_topology_in_last_level,
                    !self.fvar.is_empty(),
                    parent,
                ),
            );
            let around = queries::around(
                &self.levels,
                &self.refinements,
                level as usize - 1,
                self.options.scheme,
            );
            for channel in &mut self.fvar {
                let parent_fvar = channel.last().expect("base channel");
                let child_fvar = fvar::refine(around, &child, &r, None, parent_fvar, &self.options);
                channel.push(child_fvar);
            }
            self.refinements.push(r);
            self.levels.push(child);
        }
        self.check_unpaired_smooth()?;
        self.uniform = Some(uniform);
        Ok(())
    }

    /// Catmull-Clark's smooth masks need a vertex's faces and edges to pair
    /// up; a vertex named twice by a face can break that and become smooth when
    /// its semi-sharp features decay. OpenSubdiv aborts on it; refuse it.
    fn check_unpaired_smooth(&self) -> Result<()> {
        if self.options.scheme != Scheme::Catmark {
            return Ok(());
        }
        (0..self.refinements.len()).try_for_each(|l| self.check_unpaired_smooth_step(l))
    }

    /// [`Refiner::check_unpaired_smooth`] for the step from level `l` to `l + 1`.
    fn check_unpaired_smooth_step(&self, l: usize) -> Result<()> {
        if self.options.scheme != Scheme::Catmark {
            return Ok(());
        }
        let (p, c) = (&self.levels[l], &self.levels[l + 1]);
        check_unpaired_smooth_step(p, c, &self.refinements[l], l)
    }

    fn check_buffers<T>(&self, level: u32, width: usize, src: &[T], dst: &[T]) -> Result<()> {
        crate::limits::check_interpolation_call(level, self.max_level(), width)?;
        let (n_src, n_dst) = (
            self.levels[level as usize - 1].vertex_count,
            self.levels[level as usize].vertex_count,
        );
        for (buffer, expected, got) in [
            (Buffer::Source, n_src * width, src.len()),
            (Buffer::Destination, n_dst * width, dst.len()),
        ] {
            if got != expected {
                return Err(Error::BufferLength {
                    buffer,
                    expected,
                    got,
                });
            }
        }
        Ok(())
    }

    /// Interpolates vertex data of `width` components from level `level - 1`
    /// to `level` (`PrimvarRefiner::Interpolate`).
    pub fn interpolate<T: Real>(&self, level: u32, width: usize, src: &[T]) -> Result<Vec<T>> {
        crate::alloc::guard(Some(level), || {
            let n = self.internal_level(level)?.vertex_count;
            let mut dst = crate::alloc::vec_or_unwind(T::ZERO, n * width);
            self.interpolate_into(level, width, src, &mut dst)?;
            Ok(dst)
        })
    }

    /// [`Refiner::interpolate`] into a [`Table`]: memory from the pool of
    /// dropped tables when large ([`crate::topology::release_table_pool`]),
    /// not cleared first, since every value is written.
    fn interpolate_table<T: Real>(&self, level: u32, width: usize, src: &[T]) -> Result<Table<T>> {
        let n = self.internal_level(level)?.vertex_count;
        let mut dst = Table::for_overwrite(n * width);
        self.interpolate_into(level, width, src, &mut dst)?;
        Ok(dst)
    }

    /// As [`Refiner::interpolate`], into a caller's buffer (no allocation per frame).
    pub fn interpolate_into<T: Real>(
        &self,
        level: u32,
        width: usize,
        src: &[T],
        dst: &mut [T],
    ) -> Result<()> {
        crate::alloc::guard(Some(level), || {
            self.check_buffers(level, width, src, dst)?;
            self.interpolate_level(Kind::Vertex, level as usize, width, src, dst);
            Ok(())
        })
    }

    /// Interpolates varying data (linearly) from level `level - 1` to `level`
    /// (`PrimvarRefiner::InterpolateVarying`).
    pub fn interpolate_varying<T: Real>(
        &self,
        level: u32,
        width: usize,
        src: &[T],
    ) -> Result<Vec<T>> {
        crate::alloc::guard(Some(level), || {
            let n = self.internal_level(level)?.vertex_count;
            let mut dst = crate::alloc::vec_or_unwind(T::ZERO, n * width);
            self.check_buffers(level, width, src, &dst)?;
            self.interpolate_level(Kind::Varying, level as usize, width, src, &mut dst);
            Ok(dst)
        })
    }

    /// Interpolates vertex data through every level: `result[l]` is level `l`,
    /// as [`Values`] (they dereference to a slice; `.to_vec()` copies them
    /// out). Levels of 2 MiB and more live in huge-page maps that return to a
    /// pool when dropped, so refining the next frame or mesh reuses their
    /// memory without page faults ([`crate::release_buffer_pool`]).
    ///
    /// ```
    /// use subdiv::{refiner::Refiner, shapes, Options, UniformOptions};
    /// let cube = shapes::cube();
    /// let mut r = Refiner::new(&cube, &Options::default())?;
    /// r.refine_uniform(UniformOptions::new(2))?;
    /// let base: Vec<f32> = cube.positions.iter().flat_map(|p| p.as_vec3().to_array()).collect();
    /// let levels = r.interpolate_all(3, &base)?;
    /// assert_eq!(levels.len(), 3);
    /// assert_eq!(levels[0], base);
    /// assert_eq!(levels[2].len(), 3 * r.level_counts(2)?.vertices);
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn interpolate_all<T: Real>(&self, width: usize, base: &[T]) -> Result<Vec<Values<T>>> {
        crate::alloc::guard(None, || {
            let mut out = vec![Values(Table::from_slice(base))];
            for level in 1..=self.max_level() {
                let next = self.interpolate_table(level, width, out.last().expect("non-empty"))?;
                out.push(Values(next));
            }
            Ok(out)
        })
    }

    /// Interpolates vertex data through every level and returns the last
    /// level's only, holding no more than two levels at a time — what a
    /// caller that wants just the refined result needs (OpenSubdiv's
    /// tutorials keep a buffer for every level). The values come as
    /// [`Values`], which dereference to a slice: a large last level lives in
    /// memory advised for huge pages.
    ///
    /// ```
    /// use subdiv::{refiner::Refiner, shapes, Options, UniformOptions};
    /// let cube = shapes::cube();
    /// let mut r = Refiner::new(&cube, &Options::default())?;
    /// r.refine_uniform(UniformOptions::new(3))?;
    /// let base: Vec<f64> = cube.positions.iter().flat_map(|p| p.to_array()).collect();
    /// let last = r.interpolate_last(3, &base)?;
    /// assert_eq!(&last, r.interpolate_all(3, &base)?.last().unwrap());
    /// # Ok::<(), subdiv::Error>(())
    /// ```
    pub fn interpolate_last<T: Real>(&self, width: usize, base: &[T]) -> Result<Values<T>> {
        crate::alloc::guard(None, || {
            // Level 1 reads `base` where it is: no copy of it.
            let mut current: Option<Table<T>> = None;
            for level in 1..=self.max_level() {
                let src = current.as_deref().unwrap_or(base);
                current = Some(self.interpolate_table(level, width, src)?);
            }
            Ok(Values(current.unwrap_or_else(|| Table::from_slice(base))))
        })
    }

    /// Positions of every level, from base positions, in `f64`.
    pub fn refine_positions(&self, base: &[DVec3]) -> Result<Vec<Vec<DVec3>>> {
        let flat: Vec<f64> = base.iter().flat_map(|p| p.to_array()).collect();
        Ok(self
            .interpolate_all(3, &flat)?
            .into_iter()
            .map(|l| {
                let points = l.chunks_exact(3).map(|c| DVec3::new(c[0], c[1], c[2]));
                crate::alloc::collect_n(l.len() / 3, points)
            })
            .collect())
    }

    /// Positions of every level, from base positions, in `f32`.
    pub fn refine_positions_f32(&self, base: &[Vec3]) -> Result<Vec<Vec<Vec3>>> {
        let flat: Vec<f32> = base.iter().flat_map(|p| p.to_array()).collect();
        Ok(self
            .interpolate_all(3, &flat)?
            .into_iter()
            .map(|l| {
                let points = l.chunks_exact(3).map(|c| Vec3::new(c[0], c[1], c[2]));
                crate::alloc::collect_n(l.len() / 3, points)
            })
            .collect())
    }

    /// One level of interpolation, in OpenSubdiv's order: face points, edge
    /// points, then vertex points, each accumulated term by term in the same
    /// order as `PrimvarRefiner` (so `f64` results agree to the last bits).
    fn interpolate_level<T: Real>(
        &self,
        kind: Kind,
        level: usize,
        width: usize,
        src: &[T],
        dst: &mut [T],
    ) {
        kernel::interpolate(self, kind, level, width, src, dst);
    }

    /// Calls `emit(child, terms)` for every child vertex of `level`, in the
    /// order OpenSubdiv computes them (face points, edge points, vertex
    /// points), with the weighted terms in OpenSubdiv's accumulation order.
    /// A term names a parent vertex, or a child vertex emitted earlier (the
    /// face points that Catmull-Clark edge and vertex points use).
    pub(crate) fn walk_masks<T: Real>(
        &self,
        kind: Kind,
        level: usize,
        mut emit: impl FnMut(u32, &[(Source, T)]),
    ) {
        let parent = &self.levels[level - 1];
        let r = &self.refinements[level - 1];
        let face_points = if r.has_face_points() {
            parent.face_count()
        } else {
            0
        };
        let mut scratch = Scratch::<T>::new();
        for (block, count) in [
            (Block::Faces, face_points),
            (Block::Edges, parent.edge_count()),
            (Block::Vertices, parent.vertex_count),
        ] {
            self.walk_block(kind, level, block, 0..count, &mut scratch, &mut emit);
        }
    }

    /// As [`Refiner::walk_masks`] for the child vertices of the parent
    /// elements `range` of one kind (`block`), in order.
    pub(crate) fn walk_block<T: Real>(
        &self,
        kind: Kind,
        level: usize,
        block: Block,
        range: std::ops::Range<usize>,
        scratch: &mut Scratch<T>,
        mut emit: impl FnMut(u32, &[(Source, T)]),
    ) {
        let r = &self.refinements[level - 1];
        match block {
            Block::Faces => {
                for f in range {
                    self.face_terms(level, f, scratch);
                    emit(r.face_child(f), &scratch.terms);
                }
            }
            Block::Edges => {
                for e in range {
                    self.edge_terms(kind, level, e, scratch);
                    emit(r.edge_child(e), &scratch.terms);
                }
            }
            Block::Vertices => {
                for v in range {
                    self.vertex_terms(kind, level, v, scratch);
                    emit(r.vertex_child(v), &scratch.terms);
                }
            }
        }
    }

    /// The step from level `level - 1` to `level`, as the masks read it.
    fn step(&self, level: usize) -> Step<'_, Split> {
        Step {
            rules: &self.rules,
            creasing: self.options.creasing,
            parent: &self.levels[level - 1],
            child: &self.levels[level],
            children: &self.refinements[level - 1],
        }
    }

    /// The terms of the face point of parent face `f` (level `level - 1`).
    pub(crate) fn face_terms<T: Real>(&self, level: usize, f: usize, s: &mut Scratch<T>) {
        face_terms(&self.rules, &self.levels[level - 1], f, s);
    }

    /// The terms of the edge point of parent edge `e`.
    pub(crate) fn edge_terms<T: Real>(
        &self,
        kind: Kind,
        level: usize,
        e: usize,
        s: &mut Scratch<T>,
    ) {
        let faces = self.edge_faces_of(level - 1, e);
        self.step(level).edge_terms(kind, e, faces.as_slice(), s);
    }

    /// The terms of the child of parent vertex `v`: face weights, then edge
    /// weights, then the vertex.
    pub(crate) fn vertex_terms<T: Real>(
        &self,
        kind: Kind,
        level: usize,
        v: usize,
        s: &mut Scratch<T>,
    ) {
        let step = self.step(level);
        if kind == Kind::Varying {
            return step.vertex_terms(kind, v, &[], &[], s);
        }
        let mut buf = std::mem::take(&mut s.hood);
        let (faces, edges) = self.vertex_hood(level - 1, v, &mut buf);
        step.vertex_terms(kind, v, faces, edges, s);
        s.hood = buf;
    }
}

/// The terms of the face point of face `f` of `parent`.
pub(crate) fn face_terms<T: Real>(
    rules: &SchemeRules,
    parent: &Level,
    f: usize,
    s: &mut Scratch<T>,
) {
    let verts = parent.face_verts(f);
    rules.face_vertex_mask(verts.len(), &mut s.mask);
    s.terms.clear();
    s.terms.extend(
        verts
            .iter()
            .zip(&s.mask.vertex)
            .map(|(&v, &w)| (Source::Parent(v), w)),
    );
}

/// One refinement step as the masks read it: the rules, the two levels and
/// the numbering of the children.
pub(crate) struct Step<'a, C> {
    pub rules: &'a SchemeRules,
    pub creasing: crate::options::CreasingMethod,
    pub parent: &'a Level,
    pub child: &'a Level,
    pub children: &'a C,
}

impl<C: Children> Step<'_, C> {
    /// The terms of the edge point of parent edge `e`, whose faces are
    /// `faces`.
    pub(crate) fn edge_terms<T: Real>(
        &self,
        kind: Kind,
        e: usize,
        faces: &[u32],
        s: &mut Scratch<T>,
    ) {
        let (parent, r) = (self.parent, self.children);
        let ev = parent.edge_vertices[e];
        s.terms.clear();
        if kind == Kind::Varying {
            let half = T::from_f64(0.5);
            s.terms
                .extend([(Source::Parent(ev[0]), half), (Source::Parent(ev[1]), half)]);
            return;
        }
        s.face_sizes.clear();
        s.face_sizes.extend(
            faces
                .iter()
                .map(|&f| parent.face_vertices.count(f as usize) as u32),
        );
        let sharpness = parent.edge_sharpness_at(e);
        let hood = EdgeNeighborhood {
            sharpness,
            face_sizes: &s.face_sizes,
        };
        let p_rule = if sharpness > 0.0 {
            Rule::Crease
        } else {
            Rule::Smooth
        };
        let c_rule = self.child.vertex_tag(r.edge_child(e) as usize).rule();
        self.rules
            .edge_vertex_mask(&hood, p_rule, c_rule, &mut s.mask);
        s.terms.push((Source::Parent(ev[0]), s.mask.vertex[0]));
        s.terms.push((Source::Parent(ev[1]), s.mask.vertex[1]));
        if s.mask.face_weights_for_centers {
            for (&f, &w) in faces.iter().zip(&s.mask.face) {
                s.terms.push((Source::Child(r.face_child(f as usize)), w));
            }
        } else {
            // Loop: the face's vertex opposite the edge.
            for (&f, &w) in faces.iter().zip(&s.mask.face) {
                s.terms.push((
                    Source::Parent(opposite_vertex(&parent.slices(), f as usize, e)),
                    w,
                ));
            }
        }
    }

    /// The terms of the child of parent vertex `v`, whose faces and edges
    /// are `faces` and `edges` (unread for varying data): face weights, then
    /// edge weights, then the vertex.
    pub(crate) fn vertex_terms<T: Real>(
        &self,
        kind: Kind,
        v: usize,
        faces: &[u32],
        edges: &[u32],
        s: &mut Scratch<T>,
    ) {
        let (parent, child, r) = (self.parent, self.child, self.children);
        let c = r.vertex_child(v) as usize;
        s.terms.clear();
        if kind == Kind::Varying {
            s.terms.push((Source::Parent(v as u32), T::ONE));
            return;
        }
        s.edge_sharpness.clear();
        s.edge_sharpness
            .extend(edges.iter().map(|&e| parent.edge_sharpness_at(e as usize)));
        s.child_edge_sharpness.resize(edges.len(), 0.0);
        crease::subdivide_edge_sharpnesses_around_vertex(
            self.creasing,
            &s.edge_sharpness,
            &mut s.child_edge_sharpness,
        );
        let hood = VertexNeighborhood {
            sharpness: parent.vertex_sharpness_at(v),
            edge_sharpness: &s.edge_sharpness,
            face_count: faces.len(),
            child_sharpness: child.vertex_sharpness_at(c),
            child_edge_sharpness: &s.child_edge_sharpness,
        };
        let p_rule = parent.vertex_tag(v).rule();
        let c_rule = child.vertex_tag(c).rule();
        self.rules
            .vertex_vertex_mask(&hood, p_rule, c_rule, &mut s.mask);
        for (&f, &w) in faces.iter().zip(&s.mask.face) {
            s.terms.push((Source::Child(r.face_child(f as usize)), w));
        }
        for (&e, &w) in edges.iter().zip(&s.mask.edge) {
            s.terms
                .push((Source::Parent(parent.other_vertex(e as usize, v as u32)), w));
        }
        s.terms.push((Source::Parent(v as u32), s.mask.vertex[0]));
    }
}

/// Refuses a vertex of `p` (level `l`) whose faces and edges do not pair up
/// (a face names it twice) and that is smooth in `p` or in `c`, its child
/// after step `r` ([`Error::UnpairedSmoothVertex`]): Catmull-Clark's smooth
/// masks cannot weigh it (OpenSubdiv aborts). Vertices without a child (a
/// sparse step) are never interpolated from and pass.
pub(crate) fn check_unpaired_smooth_step<C: Children>(
    p: &Level,
    c: &Level,
    r: &C,
    l: usize,
) -> Result<()> {
    let smooth = |rule: Rule| matches!(rule, Rule::Smooth | Rule::Dart);
    for v in 0..p.vertex_count {
        if p.vertex_faces.count(v) == p.vertex_edges.count(v) {
            continue;
        }
        let child = r.vertex_child(v);
        if child == crate::INVALID_INDEX {
            continue;
        }
        if smooth(p.vertex_tag(v).rule()) || smooth(c.vertex_tag(child as usize).rule()) {
            return Err(Error::UnpairedSmoothVertex {
                level: l as u32,
                vertex: v,
            });
        }
    }
    Ok(())
}
