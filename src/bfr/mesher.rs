//! A watertight mesh of the limit surface: every base face tessellated and
//! the patterns stitched along shared edges and corners ([`tessellate`]).
//!
//! Faces are visited in index order (holes and faces without a limit
//! surface skipped). A face's pattern has its boundary points first: the
//! point at each corner belongs to the base vertex, the points inside each
//! edge to the base edge, and the first face that uses one creates and
//! evaluates it — later faces reuse it, walking the edge's points backwards
//! when they traverse the edge the other way (so non-manifold and
//! inconsistently oriented edges stay watertight), as OpenSubdiv's bfr
//! tutorial 2_2 does. A rate per base edge keeps neighbours' edges in step.
//! Interior points are the face's own. Evaluation runs face by face in
//! parallel once every point has its face.

use crate::Table;
use crate::alloc;
use crate::bfr::{FacetSize, Parameterization, Tessellation, TessellationOptions};
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::options::Scheme;
use crate::patches::{Derivatives, SurfaceSamples};
use glam::DVec3;
use rayon::prelude::*;
use rustc_hash::FxHashMap;

/// The limit surfaces of a mesh's base faces, evaluated in Bfr's
/// parameterization: what [`tessellate`] needs of an engine.
pub trait FaceSurfaces: Sync {
    /// The subdivision scheme (for the faces' parameterizations).
    fn scheme(&self) -> Scheme;
    /// Whether base face `face` has a limit surface (not a hole, not a face
    /// Bfr finds no limit for).
    fn has_surface(&self, face: usize) -> bool;
    /// Positions at `coords` of `face`, with the derivatives asked for.
    fn evaluate(
        &self,
        face: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples>;
    /// Face-varying channel `channel` at `coords` of `face`.
    fn evaluate_fvar(
        &self,
        face: usize,
        channel: usize,
        coords: &[[f64; 2]],
    ) -> Result<SurfaceSamples>;
    /// [`FaceSurfaces::evaluate`] written into `out`: one slice per kind
    /// of value asked for (the positions, then ∂u and ∂v with first
    /// derivatives), 3 values per coordinate, every value overwritten. By
    /// default a copy of what `evaluate` returns.
    fn evaluate_into(
        &self,
        face: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
        out: &mut [&mut [f64]],
    ) -> Result<()> {
        self.evaluate(face, coords, derivatives)?
            .values
            .copy_into(out)
    }
    /// [`FaceSurfaces::evaluate_into`] and, for face-varying channel
    /// `channel`, [`FaceSurfaces::evaluate_fvar_into`] at `fvar_coords`
    /// into `fvar_out`, in one call: an engine may share what the two have
    /// in common (the face's neighbourhood). By default the two calls.
    fn evaluate_with_fvar_into(
        &self,
        face: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
        out: &mut [&mut [f64]],
        (channel, fvar_coords, fvar_out): (usize, &[[f64; 2]], &mut [f64]),
    ) -> Result<()> {
        self.evaluate_into(face, coords, derivatives, out)?;
        self.evaluate_fvar_into(face, channel, fvar_coords, fvar_out)
    }
    /// The base mesh's edges as the engine numbers them, when it has them
    /// and each pair of vertices has one edge: the edge of every face corner
    /// (from the corner to the next, in the order of the right-handed
    /// mesh's face vertices) and each edge's two vertices. `None` (the
    /// default) lets [`tessellate`] find them itself.
    fn base_edges(&self) -> Option<(&[u32], &[[u32; 2]])> {
        None
    }
    /// [`FaceSurfaces::evaluate_fvar`] written into `out` (the channel's
    /// width per coordinate, every value overwritten). By default a copy of
    /// what `evaluate_fvar` returns.
    fn evaluate_fvar_into(
        &self,
        face: usize,
        channel: usize,
        coords: &[[f64; 2]],
        out: &mut [f64],
    ) -> Result<()> {
        self.evaluate_fvar(face, channel, coords)?
            .values
            .copy_into(&mut [out])
    }
}

impl FaceSurfaces for crate::bfr::LimitSurfaces {
    fn scheme(&self) -> Scheme {
        crate::bfr::LimitSurfaces::scheme(self)
    }
    fn has_surface(&self, face: usize) -> bool {
        crate::bfr::LimitSurfaces::has_surface(self, face)
    }
    fn evaluate(
        &self,
        face: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Result<SurfaceSamples> {
        crate::bfr::LimitSurfaces::evaluate(self, face, coords, derivatives)
    }
    fn evaluate_fvar(
        &self,
        face: usize,
        channel: usize,
        coords: &[[f64; 2]],
    ) -> Result<SurfaceSamples> {
        crate::bfr::LimitSurfaces::evaluate_fvar(self, face, channel, coords, Derivatives::None)
    }
}

/// How [`tessellate`] samples the faces.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TessellateOptions {
    /// The rate of every edge (at least 1), unless `edge_length` is set.
    pub rate: u32,
    /// A tessellation interval in object space: each base edge's rate is 1
    /// plus its control edge's length over this, rounded down (as bfr
    /// tutorial 2_1 computes it from the control hull; at most
    /// [`MAX_RATE`](crate::bfr::MAX_RATE)).
    pub edge_length: Option<f64>,
    /// Keep quads where the patterns have them (else triangles only).
    pub quads: bool,
    /// Compute unit normals from the first derivatives.
    pub normals: bool,
    /// Evaluate face-varying channel 0 as texture coordinates, when the mesh
    /// has one.
    pub uvs: bool,
}

impl Default for TessellateOptions {
    fn default() -> Self {
        TessellateOptions {
            rate: 4,
            edge_length: None,
            quads: false,
            normals: false,
            uvs: true,
        }
    }
}

/// A tessellated limit surface: an indexed polygon mesh.
///
/// Its arrays are [`Table`]s (slices to read): the large ones live in
/// memory maps that go back to a pool when the mesh is dropped, so the next
/// tessellation (the next frame, the next mesh) writes into memory the
/// kernel has already faulted in ([`crate::release_buffer_pool`] hands it
/// back).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TessellatedMesh {
    /// The points of the surface.
    pub positions: Table<DVec3>,
    /// Unit normals, one per point (empty unless asked for; zero where the
    /// surface is degenerate).
    pub normals: Table<DVec3>,
    /// Face offsets into `face_vertices` (one more than the facets).
    pub face_offsets: Table<u32>,
    /// The facets' points, counter-clockwise.
    pub face_vertices: Table<u32>,
    /// Texture coordinates, 2 per value (empty without UVs).
    pub uvs: Table<f64>,
    /// One texture-coordinate index per facet corner (empty without UVs).
    /// Each face has its own, so UV seams stay seams.
    pub uv_indices: Table<u32>,
    /// The base face each facet tessellates.
    pub facet_faces: Table<u32>,
}

/// A tessellation pattern shared by every face of the same size and rates:
/// its coordinates and facets (pattern indices, `-1` padding a short
/// facet), computed once.
struct Pattern {
    /// The rate of each edge (their number: the face's size).
    rates: Vec<u32>,
    tess: Tessellation,
    coords: Vec<[f64; 2]>,
    facets: Vec<i32>,
    /// Facet corners that are not padding.
    corners: usize,
}

/// One face's share of the work.
struct FacePlan {
    face: usize,
    /// Index of its pattern.
    pattern: u32,
    /// Where its mesh point of each of the pattern's coordinates are in
    /// the planned points.
    points: std::ops::Range<usize>,
    /// Where the coordinates (indices into the pattern) this face
    /// evaluates are in the planned owned coordinates.
    owned: std::ops::Range<usize>,
}

/// Tessellates every base face of `mesh` with a limit surface in
/// `surfaces` into one watertight mesh.
///
/// A [`Mesh::left_handed`] mesh is tessellated as the surfaces read it
/// ([`Mesh::right_handed`]): facets come out counter-clockwise.
///
/// Refused: a rate of 0, an edge length that is not positive and finite, a
/// mesh whose tessellation has more points than 32-bit indices hold.
pub fn tessellate(
    mesh: &Mesh,
    surfaces: &dyn FaceSurfaces,
    options: &TessellateOptions,
) -> Result<TessellatedMesh> {
    let mesh = &*mesh.right_handed();
    if options.rate == 0 {
        return Err(Error::Tessellation {
            reason: "the tessellation rate is 0; rates start at 1".into(),
        });
    }
    if let Some(l) = options.edge_length
        && !(l.is_finite() && l > 0.0)
    {
        return Err(Error::Tessellation {
            reason: format!("edge length {l} is not a positive number"),
        });
    }
    let tess_options = TessellationOptions {
        preserve_quads: options.quads,
        facet_size: if options.quads {
            FacetSize::Four
        } else {
            FacetSize::Three
        },
    };
    let scheme = surfaces.scheme();

    // The rate of the edge from vertex `a` to `b`.
    let rate_of = |a: u32, b: u32| match options.edge_length {
        None => options.rate,
        Some(l) => {
            let len = mesh.positions[a as usize].distance(mesh.positions[b as usize]);
            (1.0 + (len / l).floor()).min(f64::from(crate::bfr::MAX_RATE)) as u32
        }
    };
    // The base edges and the edge of every face corner (from the corner to
    // the next): the engine's when it has them and they are this mesh's,
    // else found by vertex pair, in order of first use.
    let (corner_edge, edge_rate) = match surfaces
        .base_edges()
        .and_then(|(corners, ends)| engine_edges(mesh, corners, ends))
    {
        Some((corners, ends)) => {
            let mut edge_rate: Vec<u32> = Vec::new();
            alloc::reserve(&mut edge_rate, ends.len())?;
            edge_rate.extend(ends.iter().map(|&[a, b]| rate_of(a, b)));
            (std::borrow::Cow::Borrowed(corners), edge_rate)
        }
        None => {
            let mut edges: FxHashMap<(u32, u32), u32> = FxHashMap::default();
            edges.reserve(mesh.face_vertices.len() / 2);
            let mut edge_rate: Vec<u32> = Vec::new();
            alloc::reserve(&mut edge_rate, mesh.face_vertices.len() / 2)?;
            let mut corner_edge: Vec<u32> = Vec::new();
            alloc::reserve(&mut corner_edge, mesh.face_vertices.len())?;
            for f in 0..mesh.face_count() {
                let fv = mesh.face(f);
                for (i, &a) in fv.iter().enumerate() {
                    let b = fv[(i + 1) % fv.len()];
                    let next = edge_rate.len() as u32;
                    let e = *edges.entry((a.min(b), a.max(b))).or_insert(next);
                    if e == next {
                        edge_rate.push(rate_of(a, b));
                    }
                    corner_edge.push(e);
                }
            }
            (std::borrow::Cow::Owned(corner_edge), edge_rate)
        }
    };

    // Plan: every face's pattern and the points it creates.
    let mut vertex_point: Vec<u32> = alloc::try_vec(u32::MAX, mesh.positions.len())?;
    // First point and start vertex of each edge's inner points.
    let mut edge_points: Vec<(u32, u32)> = alloc::try_vec((u32::MAX, 0), edge_rate.len())?;
    let mut next: u64 = 0;
    let mut plans = Vec::new();
    alloc::reserve(&mut plans, mesh.face_count())?;
    // Every face's points and owned coordinates, face after face.
    let mut all_points: Vec<u32> = Vec::new();
    let mut all_owned: Vec<u32> = Vec::new();
    let mut patterns: Vec<Pattern> = Vec::new();
    // By the face's rates (one per edge: its size too).
    let mut pattern_of: FxHashMap<Vec<u32>, u32> = FxHashMap::default();
    let mut take = |count: usize| -> Result<u32> {
        let first = next;
        next += count as u64;
        if next > u32::MAX as u64 {
            return Err(Error::TooLarge {
                what: "tessellated points",
                count: next as usize,
                bits: 32,
            });
        }
        Ok(first as u32)
    };
    // First every face's pattern (and the room its points take), then its
    // points: the arrays are reserved once.
    let mut rates: Vec<u32> = Vec::new();
    let mut room = 0usize;
    for f in 0..mesh.face_count() {
        if !surfaces.has_surface(f) {
            continue;
        }
        let n = mesh.face(f).len();
        let face_edges = &corner_edge[mesh.face_offsets[f] as usize..][..n];
        rates.clear();
        rates.extend(face_edges.iter().map(|&e| edge_rate[e as usize]));
        // The previous face's pattern when the rates are the same (at a
        // uniform rate, nearly every face): no hashing.
        let last = plans.last().map(|p: &FacePlan| p.pattern);
        let pattern = match last.filter(|&p| patterns[p as usize].rates == rates) {
            Some(p) => p,
            None => match pattern_of.get(rates.as_slice()) {
                Some(&p) => p,
                None => {
                    let param = Parameterization::new(scheme, n)?;
                    let tess = Tessellation::new(param, &rates, tess_options)?;
                    let facets = tess.facets()?;
                    patterns.push(Pattern {
                        rates: rates.clone(),
                        coords: tess.coords::<f64>()?,
                        corners: facets.iter().filter(|&&c| c >= 0).count(),
                        facets,
                        tess,
                    });
                    let p = (patterns.len() - 1) as u32;
                    pattern_of.insert(rates.clone(), p);
                    p
                }
            },
        };
        room = room.saturating_add(patterns[pattern as usize].tess.num_coords());
        plans.push(FacePlan {
            face: f,
            pattern,
            points: 0..0,
            owned: 0..0,
        });
    }
    alloc::reserve(&mut all_points, room)?;
    alloc::reserve(&mut all_owned, room)?;
    for plan in &mut plans {
        let fv = mesh.face(plan.face);
        let n = fv.len();
        let face_edges = &corner_edge[mesh.face_offsets[plan.face] as usize..][..n];
        let tess = &patterns[plan.pattern as usize].tess;
        let (points_start, owned_start) = (all_points.len(), all_owned.len());
        let (points, owned) = (&mut all_points, &mut all_owned);
        // The index in this face's points of the next one pushed.
        let here = |points: &Vec<u32>| (points.len() - points_start) as u32;
        for i in 0..n {
            let a = fv[i];
            if vertex_point[a as usize] == u32::MAX {
                vertex_point[a as usize] = take(1)?;
                owned.push(here(points));
            }
            points.push(vertex_point[a as usize]);
            let e = face_edges[i] as usize;
            let inner = edge_rate[e] as usize - 1;
            if edge_points[e].0 == u32::MAX {
                edge_points[e] = (take(inner)?, a);
                let first = here(points);
                owned.extend((0..inner as u32).map(|k| first + k));
            }
            let (first, start) = edge_points[e];
            if start == a {
                points.extend((0..inner as u32).map(|k| first + k));
            } else {
                points.extend((0..inner as u32).rev().map(|k| first + k));
            }
        }
        let interior = take(tess.num_interior_coords())?;
        owned.extend(here(points)..tess.num_coords() as u32);
        points.extend((0..tess.num_interior_coords() as u32).map(|k| interior + k));
        plan.points = points_start..all_points.len();
        plan.owned = owned_start..all_owned.len();
    }
    let total = next as usize;
    let pattern = |p: &FacePlan| &patterns[p.pattern as usize];

    let derivs = if options.normals {
        Derivatives::First
    } else {
        Derivatives::None
    };
    let uvs = options.uvs && !mesh.fvar_channels.is_empty();
    let uv_width = mesh.fvar_channels.first().map_or(0, |c| c.width).max(1);
    // Where each face's facets, facet corners and texture coordinates (one
    // per pattern coordinate: each face has its own) start in the outputs.
    let mut starts: Vec<Starts> = Vec::new();
    alloc::reserve(&mut starts, plans.len() + 1)?;
    let mut at = Starts::default();
    for plan in &plans {
        starts.push(at);
        let p = pattern(plan);
        at.facet += p.tess.num_facets() as u64;
        at.corner += p.corners as u64;
        at.uv += if uvs { p.coords.len() as u64 } else { 0 };
    }
    if at.corner > u32::MAX as u64 || at.uv > u32::MAX as u64 {
        return Err(Error::TooLarge {
            what: "tessellated facet corners",
            count: at.corner.max(at.uv) as usize,
            bits: 32,
        });
    }
    starts.push(at);
    let (facets, corners) = (at.facet as usize, at.corner as usize);

    // Every output written once, face by face in parallel, into tables
    // that may hold stale values (recycled maps): each face's points (its
    // own ones, a contiguous range taken in order while planning it), its
    // facets with the pattern's coordinates replaced by the face's points,
    // its texture coordinates.
    let face_points = |p: &FacePlan| &all_points[p.points.clone()];
    let face_owned = |p: &FacePlan| &all_owned[p.owned.clone()];
    debug_assert!(plans.iter().all(|p| {
        let (points, owned) = (face_points(p), face_owned(p));
        owned
            .iter()
            .enumerate()
            .all(|(k, &c)| points[c as usize] == points[owned[0] as usize] + k as u32)
    }));
    let mut out = TessellatedMesh {
        positions: Table::for_overwrite(total),
        normals: Table::for_overwrite(if options.normals { total } else { 0 }),
        face_offsets: Table::for_overwrite(facets + 1),
        face_vertices: Table::for_overwrite(corners),
        uvs: Table::for_overwrite(2 * at.uv as usize),
        uv_indices: Table::for_overwrite(if uvs { corners } else { 0 }),
        facet_faces: Table::for_overwrite(facets),
    };
    out.face_offsets[0] = 0;
    // Each face's share of every output, cut in one pass.
    let mut outputs: Vec<FaceOutputs<'_>> = Vec::new();
    alloc::reserve(&mut outputs, plans.len())?;
    {
        let mut position = &mut out.positions[..];
        let mut normal = &mut out.normals[..];
        let mut uv = &mut out.uvs[..];
        let mut offset = &mut out.face_offsets[1..];
        let mut facet_face = &mut out.facet_faces[..];
        let mut corner = &mut out.face_vertices[..];
        let mut uv_index = &mut out.uv_indices[..];
        for (i, plan) in plans.iter().enumerate() {
            let (s, e) = (&starts[i], &starts[i + 1]);
            let owned = plan.owned.len();
            let facets = (e.facet - s.facet) as usize;
            let corners = (e.corner - s.corner) as usize;
            outputs.push(FaceOutputs {
                position: cut(&mut position, owned),
                normal: cut(&mut normal, if options.normals { owned } else { 0 }),
                uv: cut(&mut uv, 2 * (e.uv - s.uv) as usize),
                offset: cut(&mut offset, facets),
                facet_face: cut(&mut facet_face, facets),
                corner: cut(&mut corner, corners),
                uv_index: cut(&mut uv_index, if uvs { corners } else { 0 }),
            });
        }
    }
    plans
        .par_iter()
        .zip(&starts[..plans.len()])
        .zip(outputs)
        .try_for_each_init(
            Scratch::default,
            |scratch: &mut Scratch, ((plan, start), out)| -> Result<()> {
                let pattern = pattern(plan);
                let coords = &pattern.coords;
                // Every coordinate when the face owns them all (from the
                // first face on, most faces own their interior only).
                let own: &[[f64; 2]] = if plan.owned.len() == coords.len() {
                    coords
                } else {
                    scratch.own.clear();
                    scratch
                        .own
                        .extend(face_owned(plan).iter().map(|&k| coords[k as usize]));
                    &scratch.own
                };
                // Positions straight into the output; the derivatives (for
                // normals) into scratch columns; texture coordinates (2D:
                // the first two components) straight into the output when
                // the channel is 2D.
                let position: &mut [f64] = bytemuck::cast_slice_mut(&mut *out.position);
                if options.normals {
                    let len = 3 * own.len();
                    scratch.du.resize(len, 0.0);
                    scratch.dv.resize(len, 0.0);
                }
                let mut columns = [position, &mut scratch.du[..], &mut scratch.dv[..]];
                let columns = &mut columns[..if options.normals { 3 } else { 1 }];
                let uv: Option<&mut [f64]> = match (uvs, uv_width) {
                    (false, _) => None,
                    (true, 2) => Some(&mut *out.uv),
                    (true, _) => {
                        scratch.uv.resize(uv_width * coords.len(), 0.0);
                        Some(&mut scratch.uv)
                    }
                };
                match uv {
                    Some(uv) => surfaces.evaluate_with_fvar_into(
                        plan.face,
                        own,
                        derivs,
                        columns,
                        (0, coords, uv),
                    )?,
                    None => surfaces.evaluate_into(plan.face, own, derivs, columns)?,
                }
                if options.normals {
                    for ((n, du), dv) in out
                        .normal
                        .iter_mut()
                        .zip(scratch.du.chunks_exact(3))
                        .zip(scratch.dv.chunks_exact(3))
                    {
                        *n = DVec3::from_slice(du)
                            .cross(DVec3::from_slice(dv))
                            .normalize_or_zero();
                    }
                }
                if uvs && uv_width != 2 {
                    for (value, dst) in scratch.uv.chunks(uv_width).zip(out.uv.chunks_mut(2)) {
                        dst[0] = value[0];
                        dst[1] = value.get(1).copied().unwrap_or(0.0);
                    }
                }
                write_facets(pattern, plan.face, face_points(plan), start, out);
                Ok(())
            },
        )?;
    Ok(out)
}

/// An engine's base edges (`corners`: the edge of each face corner,
/// `ends`: each edge's vertices) if they are `mesh`'s: one edge per corner,
/// joining the corner to the next.
fn engine_edges<'a>(
    mesh: &Mesh,
    corners: &'a [u32],
    ends: &'a [[u32; 2]],
) -> Option<(&'a [u32], &'a [[u32; 2]])> {
    if corners.len() != mesh.face_vertices.len() {
        return None;
    }
    for f in 0..mesh.face_count() {
        let fv = mesh.face(f);
        let edges = corners.get(mesh.face_offsets[f] as usize..)?;
        for (i, (&a, &e)) in fv.iter().zip(edges).enumerate() {
            let b = fv[if i + 1 == fv.len() { 0 } else { i + 1 }];
            let [x, y] = *ends.get(e as usize)?;
            if !(x == a && y == b || x == b && y == a) {
                return None;
            }
        }
    }
    Some((corners, ends))
}

/// A thread's scratch space while it evaluates faces.
#[derive(Default)]
struct Scratch {
    /// The coordinates a face owns.
    own: Vec<[f64; 2]>,
    /// ∂u and ∂v at them (for normals).
    du: Vec<f64>,
    dv: Vec<f64>,
    /// Texture coordinates of a channel wider than 2.
    uv: Vec<f64>,
}

/// Where one face's outputs start: its first facet, facet corner and
/// texture coordinate.
#[derive(Debug, Clone, Copy, Default)]
struct Starts {
    facet: u64,
    corner: u64,
    uv: u64,
}

/// One face's share of the outputs.
struct FaceOutputs<'a> {
    position: &'a mut [DVec3],
    normal: &'a mut [DVec3],
    uv: &'a mut [f64],
    /// Its facets' end offsets (the mesh's `face_offsets` after the first).
    offset: &'a mut [u32],
    facet_face: &'a mut [u32],
    corner: &'a mut [u32],
    uv_index: &'a mut [u32],
}

/// Writes the facets of `face`: `pattern`'s, its coordinates replaced by
/// the face's `points` (and by its own texture coordinates, from
/// `start.uv`).
fn write_facets(
    pattern: &Pattern,
    face: usize,
    points: &[u32],
    start: &Starts,
    out: FaceOutputs<'_>,
) {
    let size = pattern.tess.facet_size();
    let face = face as u32;
    let uv_base = start.uv as u32;
    out.facet_face.fill(face);
    if pattern.corners == pattern.facets.len() {
        // No padding: every facet has `size` corners.
        for (dst, &c) in out.corner.iter_mut().zip(&pattern.facets) {
            *dst = points[c as usize];
        }
        for (dst, &c) in out.uv_index.iter_mut().zip(&pattern.facets) {
            *dst = uv_base + c as u32;
        }
        let first = start.corner as u32;
        for (k, dst) in out.offset.iter_mut().enumerate() {
            *dst = first + (k as u32 + 1) * size as u32;
        }
        return;
    }
    let mut corner = 0;
    for (facet, offset) in pattern.facets.chunks_exact(size).zip(out.offset.iter_mut()) {
        for &c in facet.iter().filter(|&&c| c >= 0) {
            out.corner[corner] = points[c as usize];
            if let Some(dst) = out.uv_index.get_mut(corner) {
                *dst = uv_base + c as u32;
            }
            corner += 1;
        }
        *offset = (start.corner + corner as u64) as u32;
    }
}

/// The first `n` values of `slice` (which has them), `slice` left with
/// the rest.
fn cut<'a, T>(slice: &mut &'a mut [T], n: usize) -> &'a mut [T] {
    let (piece, rest) = std::mem::take(slice).split_at_mut(n);
    *slice = rest;
    piece
}
