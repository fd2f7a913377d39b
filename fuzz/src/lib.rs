//! The checks behind the fuzz targets of `subdiv`, shared by the targets in
//! `fuzz_targets/` (each is a thin `fuzz_target!` around one function here).
//!
//! Every check feeds arbitrary bytes to the library and asserts that the
//! answer is `Ok` or a typed error of the kind the documentation promises:
//! any panic, abort, sanitizer report or time-out is a bug. Where a cheap
//! oracle exists the results are checked too (round trips, counts, index
//! ranges, stencils against interpolation, limit stencils against limit
//! evaluation, a flattened curve lying on its curve). Sizes are bounded so
//! that one run takes milliseconds.

#[cfg(feature = "osd")]
pub mod bfr;
pub mod limit;

#[cfg(feature = "osd")]
pub use bfr::{check_bfr_pattern, check_bfr_surfaces};

use arbitrary::{Result as AResult, Unstructured};
use glam::DVec3;
use std::path::Path;
use subdiv::curve::{self, BSplineCurve, CurveError, CurveScheme, Point};
use subdiv::io::points::{self as points_io, Points, PointsErrorKind};
use subdiv::io::{
    mesh_to_obj_string, parse_obj, parse_obj_chunked, parse_obj_general, parse_obj_streamed,
};
use subdiv::refiner::{self, Refiner};
use subdiv::{
    AdaptiveOptions, BoundaryInterpolation, CreasingMethod, Error, FVarChannel,
    FVarLinearInterpolation, INVALID_INDEX, Mesh, ObjErrorKind, Options, Precision, Refinement,
    Scheme, TriangleSubdivision, UniformOptions,
};

/// Largest generated mesh: vertices, faces, corners per face.
pub const MAX_VERTICES: usize = 40;
/// Largest number of generated faces.
pub const MAX_FACES: usize = 24;
/// Largest generated face.
pub const MAX_FACE_SIZE: usize = 9;
/// Largest refinement level tried.
pub const MAX_FUZZ_LEVEL: u32 = 3;
/// Largest isolation level tried (beyond it, only levels that must be refused).
pub const MAX_FUZZ_ISOLATION: u32 = 6;

// ---------------------------------------------------------------------------
// Meshes from bytes
// ---------------------------------------------------------------------------

/// A mesh with everything needed to refine it.
#[derive(Debug, Clone)]
pub struct MeshCase {
    /// The mesh (possibly invalid when built with `wild`).
    pub mesh: Mesh,
    /// Subdivision options.
    pub options: Options,
    /// Uniform level, `0..=MAX_FUZZ_LEVEL`.
    pub level: u32,
    /// `orderVerticesFromFacesFirst`.
    pub faces_first: bool,
    /// `fullTopologyInLastLevel`.
    pub full_topology: bool,
    /// Interpolation precision.
    pub precision: Precision,
    /// Evaluate the limit too.
    pub limit: bool,
}

impl MeshCase {
    /// The uniform options of the case.
    pub fn uniform(&self) -> UniformOptions {
        UniformOptions::new(self.level)
            .faces_first(self.faces_first)
            .full_topology(self.full_topology)
    }

    /// Whether every coordinate is small enough that no result can overflow.
    pub fn tame(&self) -> bool {
        self.mesh
            .positions
            .iter()
            .all(|p| p.to_array().iter().all(|c| c.abs() <= 1e6))
            && self
                .mesh
                .fvar_channels
                .iter()
                .all(|c| c.values.iter().all(|v| v.abs() <= 1e6))
    }
}

pub(crate) fn pick<T: Copy>(u: &mut Unstructured<'_>, items: &[T]) -> AResult<T> {
    Ok(*u.choose(items)?)
}

/// A coordinate: mostly small multiples of 1/16; with `wild`, also NaN,
/// infinities, huge, tiny and arbitrary values.
fn coordinate(u: &mut Unstructured<'_>, wild: bool) -> AResult<f64> {
    let b: u8 = u.arbitrary()?;
    Ok(match b {
        0..=239 => (f64::from(b) - 120.0) / 16.0,
        240 if wild => f64::NAN,
        241 if wild => f64::INFINITY,
        242 if wild => f64::NEG_INFINITY,
        243 if wild => 1e300,
        244 if wild => -1e300,
        245 if wild => f64::MIN_POSITIVE,
        246 if wild => f64::from_bits(u.arbitrary()?),
        247 => -0.0,
        _ => 1e-9 * f64::from(b),
    })
}

/// A sharpness: the usual values, negative ones, and (with `wild`) NaN, infinity, anything.
fn sharpness(u: &mut Unstructured<'_>, wild: bool) -> AResult<f32> {
    let b: u8 = u.arbitrary()?;
    Ok(match b % 16 {
        0 => 0.0,
        1 => 0.5,
        2 => 1.0,
        3 => 1.5,
        4 => 2.0,
        5 => 3.25,
        6 => 9.99,
        7 => 10.0,
        8 => 11.0,
        9 => -1.0,
        10 => -0.0,
        11 => 1e-7,
        12 if wild => f32::NAN,
        13 if wild => f32::INFINITY,
        14 if wild => f32::from_bits(u.arbitrary()?),
        _ => 4.75,
    })
}

/// An index below `n`, or (with `wild`, rarely) at or beyond it.
fn index(u: &mut Unstructured<'_>, n: usize, wild: bool) -> AResult<u32> {
    let b: u8 = u.arbitrary()?;
    let n32 = n as u32;
    Ok(match b {
        250..=253 if wild => n32 + u32::from(b - 250),
        254 if wild => i32::MAX as u32,
        255 if wild => u32::MAX,
        _ if n == 0 => 0,
        _ => u32::from(b) % n32,
    })
}

/// Builds a [`MeshCase`]; `wild` also produces invalid meshes (bad indices,
/// tiny faces, non-finite numbers, malformed offsets and channels).
pub fn mesh_case(u: &mut Unstructured<'_>, wild: bool) -> AResult<MeshCase> {
    let options = Options {
        scheme: pick(u, Scheme::ALL)?,
        boundary: pick(u, BoundaryInterpolation::ALL)?,
        fvar: pick(u, FVarLinearInterpolation::ALL)?,
        creasing: pick(u, CreasingMethod::ALL)?,
        triangles: pick(u, TriangleSubdivision::ALL)?,
    };
    let level = u.int_in_range(0..=MAX_FUZZ_LEVEL)?;
    let faces_first: bool = u.arbitrary()?;
    let full_topology: bool = u.arbitrary()?;
    let precision = if u.arbitrary()? {
        Precision::F32
    } else {
        Precision::F64
    };
    let limit: bool = u.arbitrary()?;
    // Loop needs triangles: usually give it some.
    let triangles_only = options.scheme == Scheme::Loop && u.ratio(7u8, 8u8)?;

    let nv = if wild {
        u.int_in_range(0..=MAX_VERTICES)?
    } else {
        u.int_in_range(3..=MAX_VERTICES)?
    };
    let mut mesh = Mesh::default();
    for _ in 0..nv {
        let p = DVec3::new(
            coordinate(u, wild)?,
            coordinate(u, wild)?,
            coordinate(u, wild)?,
        );
        mesh.positions.push(p);
    }
    let nf = if wild {
        u.int_in_range(0..=MAX_FACES)?
    } else {
        u.int_in_range(1..=MAX_FACES)?
    };
    for _ in 0..nf {
        let size = if triangles_only {
            3
        } else if wild {
            u.int_in_range(0..=MAX_FACE_SIZE)?
        } else {
            u.int_in_range(3..=MAX_FACE_SIZE)?
        };
        let mut face = Vec::with_capacity(size);
        for _ in 0..size {
            face.push(index(u, nv, wild)?);
        }
        mesh.add_face(&face);
    }
    let corners = mesh.face_vertices.len();
    // Creases: mostly on edges of the faces, else between any two vertices.
    for _ in 0..u.int_in_range(0..=8)? {
        let on_edge: bool = u.arbitrary()?;
        let pair = if on_edge && corners > 0 {
            let f = index(u, mesh.face_count(), false)? as usize;
            let verts = mesh.face(f);
            if verts.is_empty() {
                [index(u, nv, wild)?, index(u, nv, wild)?]
            } else {
                let k = index(u, verts.len(), false)? as usize;
                [verts[k], verts[(k + 1) % verts.len()]]
            }
        } else {
            [index(u, nv, wild)?, index(u, nv, wild)?]
        };
        mesh.add_crease(pair[0], pair[1], sharpness(u, wild)?);
    }
    for _ in 0..u.int_in_range(0..=4)? {
        mesh.add_corner(index(u, nv, wild)?, sharpness(u, wild)?);
    }
    for _ in 0..u.int_in_range(0..=3)? {
        mesh.holes.push(index(u, mesh.face_count(), wild)?);
    }
    for _ in 0..u.int_in_range(0..=2)? {
        let width = if wild && u.ratio(1u8, 16u8)? {
            pick(u, &[0usize, 4])?
        } else {
            pick(u, &[2usize, 2, 1, 3])?
        };
        let count = u.int_in_range(if wild { 0 } else { 1 }..=nv.max(1) * 2)?;
        let mut values = Vec::with_capacity(count * width);
        for _ in 0..count * width {
            values.push(coordinate(u, wild)?);
        }
        let mut indices = Vec::with_capacity(corners);
        for c in 0..corners {
            // Often the vertex's own index (a seamless channel), else anything.
            let index = if u.arbitrary()? && count > 0 {
                mesh.face_vertices[c] % count as u32
            } else {
                index(u, count, wild)?
            };
            indices.push(index);
        }
        mesh.fvar_channels.push(FVarChannel {
            width,
            values,
            indices,
        });
    }
    // Clockwise faces read as OpenSubdiv's isLeftHanded reads them.
    mesh.left_handed = u.ratio(1u8, 8u8)?;
    if wild && u.ratio(1u8, 32u8)? {
        // Structural damage that only hand-built meshes can have.
        match u.int_in_range(0..=4)? {
            0 => {
                mesh.face_vertices.pop();
            }
            1 => mesh.face_offsets[0] = 1,
            2 => {
                let n = mesh.face_offsets.len();
                if n >= 3 {
                    mesh.face_offsets.swap(1, 2);
                }
            }
            3 => mesh.face_offsets.clear(),
            _ => {
                if let Some(c) = mesh.fvar_channels.first_mut() {
                    c.indices.push(0);
                }
            }
        }
    }
    Ok(MeshCase {
        mesh,
        options,
        level,
        faces_first,
        full_topology,
        precision,
        limit,
    })
}

/// The arguments of one adaptive refinement.
#[derive(Debug, Clone)]
pub struct AdaptiveCase {
    /// Every field of `Far::TopologyRefiner::AdaptiveOptions`.
    pub options: AdaptiveOptions,
    /// The selected base faces (every face when empty).
    pub faces: Vec<u32>,
}

/// Builds an [`AdaptiveCase`] for a mesh of `face_count` faces: isolation
/// `0..=MAX_FUZZ_ISOLATION`, secondary `0..=15`, any flags, a few selected
/// faces (one time in two none); with `wild`, rarely, levels beyond
/// OpenSubdiv's fields and faces out of range, which must be refused.
pub fn adaptive_case(
    u: &mut Unstructured<'_>,
    face_count: usize,
    wild: bool,
) -> AResult<AdaptiveCase> {
    let mut isolation = u.int_in_range(0..=MAX_FUZZ_ISOLATION)?;
    let mut secondary = u.int_in_range(0..=15)?;
    if wild && u.ratio(1u8, 16u8)? {
        isolation = pick(u, &[11, 16, u32::MAX])?;
    }
    if wild && u.ratio(1u8, 16u8)? {
        secondary = pick(u, &[16, 255, u32::MAX])?;
    }
    let flags: u8 = u.arbitrary()?;
    let options = AdaptiveOptions::new(isolation)
        .secondary(secondary)
        .single_crease_patch(flags & 1 != 0)
        .inf_sharp_patch(flags & 2 != 0)
        .consider_fvar(flags & 4 != 0)
        .faces_first(flags & 8 != 0);
    let mut faces = Vec::new();
    if flags & 16 != 0 {
        for _ in 0..u.int_in_range(1..=4)? {
            faces.push(index(u, face_count, wild)?);
        }
    }
    Ok(AdaptiveCase { options, faces })
}

impl Default for AdaptiveCase {
    /// Isolation level 2, every face: what a case runs when the bytes ran out.
    fn default() -> Self {
        AdaptiveCase {
            options: AdaptiveOptions::new(2),
            faces: Vec::new(),
        }
    }
}

// ---------------------------------------------------------------------------
// Refinement checks
// ---------------------------------------------------------------------------

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= 1e-9 * scale
}

/// Largest absolute coordinate plus one: the scale of rounding errors.
fn scale_of(points: &[DVec3]) -> f64 {
    1.0 + points
        .iter()
        .flat_map(|p| p.to_array())
        .fold(0.0_f64, |m, c| m.max(c.abs()))
}

/// Structural invariants of any successful refinement.
pub fn check_refinement(case: &MeshCase, r: &Refinement, engine: &str) {
    let mesh = &case.mesh;
    let n = case.level as usize + 1;
    assert_eq!(r.levels.len(), n, "{engine}: level count");
    assert_eq!(r.positions.len(), n, "{engine}: position levels");
    assert_eq!(r.fvar_values.len(), n, "{engine}: face-varying levels");
    for (l, level) in r.levels.iter().enumerate() {
        assert_eq!(
            r.positions[l].len(),
            level.vertex_count,
            "{engine}: level {l} positions"
        );
        assert_eq!(
            level.face_offsets.len(),
            level.face_count() + 1,
            "{engine}: level {l} offsets"
        );
        assert_eq!(
            level.face_offsets.last().map(|&o| o as usize),
            Some(level.face_vertices.len()),
            "{engine}: level {l} last offset"
        );
        assert!(
            level.face_offsets.windows(2).all(|w| w[0] <= w[1]),
            "{engine}: level {l} offsets decrease"
        );
        if let Some(v) = level
            .face_vertices
            .iter()
            .find(|&&v| v as usize >= level.vertex_count)
        {
            panic!(
                "{engine}: level {l} face vertex {v} >= {}",
                level.vertex_count
            );
        }
        assert_eq!(
            level.fvar.len(),
            mesh.fvar_channels.len(),
            "{engine}: level {l} channels"
        );
        for (c, fv) in level.fvar.iter().enumerate() {
            let width = mesh.fvar_channels[c].width;
            assert_eq!(
                r.fvar_values[l][c].len(),
                fv.value_count * width,
                "{engine}: level {l} channel {c} values"
            );
            assert_eq!(
                fv.face_values.len(),
                level.face_vertices.len(),
                "{engine}: level {l} channel {c} face values"
            );
            if let Some(v) = fv
                .face_values
                .iter()
                .find(|&&v| v as usize >= fv.value_count)
            {
                panic!(
                    "{engine}: level {l} channel {c} value index {v} >= {}",
                    fv.value_count
                );
            }
        }
        if l > 0 {
            let parent = &r.levels[l - 1];
            let expected = match case.options.scheme {
                Scheme::Loop => parent.face_count() * 4,
                _ => parent.face_vertices.len(),
            };
            assert_eq!(
                level.face_count(),
                expected,
                "{engine}: level {l} face count"
            );
        }
        if case.tame() {
            assert!(
                r.positions[l].iter().all(|p| p.is_finite()),
                "{engine}: level {l} has non-finite positions from finite input"
            );
        }
    }
    if case.precision == Precision::F64 {
        assert_eq!(
            r.positions[0], mesh.positions,
            "{engine}: level 0 positions"
        );
    }
    match &r.limit {
        Some(limit) => {
            assert!(case.limit, "{engine}: a limit nobody asked for");
            let nv = r.last_level().vertex_count;
            assert_eq!(limit.positions.len(), nv, "{engine}: limit positions");
            assert_eq!(limit.du.len(), nv, "{engine}: limit du");
            assert_eq!(limit.dv.len(), nv, "{engine}: limit dv");
            assert_eq!(
                limit.fvar_values.len(),
                mesh.fvar_channels.len(),
                "{engine}: limit channels"
            );
        }
        None => assert!(!case.limit, "{engine}: the limit is missing"),
    }
}

/// Is this an error a valid mesh may legitimately get (Loop on non-triangles,
/// a smooth vertex OpenSubdiv cannot refine, an empty mesh, a level too deep,
/// a value beyond f32 in an f32 refinement)?
fn acceptable_for_valid_mesh(e: &Error) -> bool {
    matches!(
        e,
        Error::NotTriangles { .. }
            | Error::UnpairedSmoothVertex { .. }
            | Error::EmptyMesh
            | Error::Level { .. }
            | Error::BeyondPrecision {
                precision: Precision::F32,
                ..
            }
    )
}

/// The native engine on one case: `refiner::refine`, then the `Refiner` API
/// (wrong arguments must be refused, stencils must reproduce interpolation).
pub fn check_native(case: &MeshCase) {
    let mesh = &case.mesh;
    let validation = mesh.validate();
    let result = refiner::refine(
        mesh,
        &case.options,
        subdiv::Request::from(case.uniform())
            .precision(case.precision)
            .limit(case.limit),
    );
    match (&validation, result) {
        (Err(v), Err(Error::Mesh(e))) => assert_eq!(
            v.to_string(),
            e.to_string(),
            "native: not the validation error"
        ),
        (Err(v), Err(e)) => panic!("native: invalid mesh ({v}) refused with another error: {e:?}"),
        (Err(v), Ok(_)) => panic!("native: invalid mesh ({v}) refined"),
        (Ok(_), Err(e)) => assert!(acceptable_for_valid_mesh(&e), "native: valid mesh: {e:?}"),
        (Ok(_), Ok(r)) => check_refinement(case, &r, "native"),
    }
    if validation.is_ok() {
        exercise_native_refiner(case);
    }
}

fn flat(points: &[DVec3]) -> Vec<f64> {
    points.iter().flat_map(|p| p.to_array()).collect()
}

fn exercise_native_refiner(case: &MeshCase) {
    let mesh = &case.mesh;
    let mut r = match Refiner::new(mesh, &case.options) {
        Ok(r) => r,
        Err(e) => {
            assert!(acceptable_for_valid_mesh(&e), "Refiner::new: {e:?}");
            return;
        }
    };
    // A vertex named twice by a face may become smooth at a deeper level:
    // refused with a typed error by both engines (OpenSubdiv would abort).
    if let Err(e) = r.refine_uniform(case.uniform()) {
        let unpaired = matches!(&e, Error::UnpairedSmoothVertex { .. });
        assert!(unpaired, "refine_uniform: {e:?}");
        return;
    }
    let max = r.max_level();
    assert_eq!(max, case.level);
    let base = flat(&mesh.positions);
    // Wrong arguments are refused, not obeyed.
    assert!(r.interpolate::<f64>(0, 3, &base).is_err());
    assert!(r.interpolate::<f64>(max + 1, 3, &base).is_err());
    assert!(r.level(max + 1).is_err());
    if max >= 1 {
        assert!(r.interpolate::<f64>(1, 0, &[]).is_err());
        assert!(r.interpolate::<f64>(1, 3, &base[..base.len() - 1]).is_err());
        assert!(r.interpolate::<f32>(1, 2, &[0.0; 3]).is_err());
        let varying = r
            .interpolate_varying::<f64>(1, 3, &base)
            .expect("varying interpolation");
        assert_eq!(varying.len(), r.level(1).unwrap().vertex_count * 3);
    }
    let levels = r.interpolate_all(3, &base).expect("interpolate_all");
    let last = levels.last().expect("level 0");
    // Stencils reproduce the interpolation.
    let table = r.stencil_table().expect("stencil table");
    assert_eq!(
        table.len() * 3,
        last.len(),
        "one stencil per last-level vertex"
    );
    let applied = table.apply(3, &base).expect("apply stencils");
    if case.tame() {
        let scale = scale_of(&mesh.positions);
        for (i, (a, b)) in applied.iter().zip(last).enumerate() {
            assert!(
                close(*a, *b, scale),
                "stencil value {i}: {a} vs interpolated {b}"
            );
        }
    }
    // Face-varying channels, and wrong channel numbers.
    let channels = mesh.fvar_channels.len();
    for level in 1..=max {
        assert!(
            r.interpolate_face_varying::<f64>(channels, level, 2, &[])
                .is_err()
        );
    }
    let mut fvar_last = Vec::new();
    for (c, ch) in mesh.fvar_channels.iter().enumerate() {
        let mut values = ch.values.clone();
        for level in 1..=max {
            values = r
                .interpolate_face_varying(c, level, ch.width, &values)
                .expect("face-varying interpolation");
        }
        fvar_last.push(values);
    }
    // The lean whole refinements (levels released as they go): the last
    // level's positions bit for bit, every level's counts, and the same
    // counts with the mesh borrowed and consumed.
    let uniform = case.uniform();
    let (counts, lean) =
        refiner::refine_last(mesh, &case.options, uniform, 3, &base).expect("refine_last");
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&lean), bits(last), "refine_last: the last level");
    for (l, c) in counts.iter().enumerate() {
        let full = r.level_counts(l as u32).expect("level counts");
        assert_eq!(
            (c.vertices, c.faces),
            (full.vertices, full.faces),
            "level {l}"
        );
    }
    let request = subdiv::Request::from(uniform);
    let borrowed = subdiv::Engine::Native
        .refine_counts(mesh, &case.options, request)
        .expect("refine_counts");
    let owned = subdiv::Engine::Native
        .refine_counts_owned(mesh.clone(), &case.options, request)
        .expect("refine_counts_owned");
    assert_eq!(owned, borrowed, "refine_counts_owned");
    // The limit, and its stencils.
    match r.limit(3, last) {
        Ok(limit) => {
            let nv = last.len() / 3;
            assert_eq!(limit.positions.len(), nv * 3);
            if let Ok(stencils) = r.limit_stencil_table() {
                let p = stencils.positions.apply(3, &base).expect("limit stencils");
                if case.tame() {
                    let scale = scale_of(&mesh.positions);
                    for (i, (a, b)) in p.iter().zip(&limit.positions).enumerate() {
                        assert!(
                            close(*a, *b, scale),
                            "limit stencil value {i}: {a} vs limit {b}"
                        );
                    }
                }
            }
            for (c, ch) in mesh.fvar_channels.iter().enumerate() {
                r.limit_face_varying(c, ch.width, &fvar_last[c])
                    .expect("limit face-varying values");
            }
        }
        Err(e) => {
            assert!(
                !case.full_topology,
                "limit refused with full topology: {e:?}"
            );
            assert!(matches!(e, Error::NeedsFullTopology), "limit: {e:?}");
        }
    }
}

/// Whether the OpenSubdiv checks should skip this mesh: only when
/// SUBDIV_FUZZ_SKIP_REPEATED=1 is set and some face names a vertex twice.
/// Such meshes made OpenSubdiv abort on its own assertion
/// (sdc/catmarkScheme.h:182, "vertex.GetNumFaces() == vertex.GetNumEdges()");
/// the variable lets a run look past that family of bugs.
pub fn osd_may_abort(mesh: &Mesh) -> bool {
    static SKIP: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    if !*SKIP.get_or_init(|| std::env::var_os("SUBDIV_FUZZ_SKIP_REPEATED").is_some()) {
        return false;
    }
    mesh.faces()
        .any(|f| f.iter().enumerate().any(|(i, v)| f[i + 1..].contains(v)))
}

/// The OpenSubdiv bridge on one case: first without Rust's validation (the
/// shim's own checks must refuse every bad index), then `osd::refine`.
#[cfg(feature = "osd")]
pub fn check_osd(case: &MeshCase) {
    use subdiv::osd;
    let mesh = &case.mesh;
    if osd_may_abort(mesh) {
        return;
    }
    if let Ok(mut r) = osd::TopologyRefiner::new_unvalidated(mesh, &case.options)
        && r.refine_uniform(case.uniform()).is_ok()
    {
        for l in 0..=r.max_level() + 1 {
            let _ = r.level(l);
        }
        let base = flat(&mesh.positions);
        if let Ok(levels) = r.interpolate_all(3, &base) {
            let last = levels.last().expect("level 0");
            let _ = r.limit(3, last);
            let _ = r.limit(3, &last[..last.len().saturating_sub(1)]);
        }
        let _ = r.interpolate::<f32>(1, 3, &[]);
        let _ = r.interpolate_varying::<f64>(case.level, 2, &[0.0; 4]);
        let _ = r.interpolate_face_varying::<f64>(0, 1, 2, &[0.0; 4]);
        let _ = r.stencil_table();
        let _ = r.limit_stencil_table();
        if let Ok(e) = osd::StencilEvaluator::new(&r) {
            let src: Vec<f32> = base.iter().map(|&x| x as f32).collect();
            let _ = e.eval(3, &src);
            let _ = e.eval(3, &src[..src.len().saturating_sub(2)]);
        }
    }
    let validation = mesh.validate();
    let result = osd::refine(
        mesh,
        &case.options,
        subdiv::Request::from(case.uniform())
            .precision(case.precision)
            .limit(case.limit),
    );
    match (&validation, result) {
        (Err(v), Err(Error::Mesh(e))) => assert_eq!(
            v.to_string(),
            e.to_string(),
            "osd: not the validation error"
        ),
        (Err(v), Err(e)) => panic!("osd: invalid mesh ({v}) refused with another error: {e:?}"),
        (Err(v), Ok(_)) => panic!("osd: invalid mesh ({v}) refined"),
        (Ok(_), Err(e)) => assert!(
            acceptable_for_valid_mesh(&e) || matches!(e, Error::Osd(_)),
            "osd: valid mesh: {e:?}"
        ),
        (Ok(_), Ok(r)) => check_refinement(case, &r, "osd"),
    }
}

/// Both engines on a valid case must agree: both refuse, or the same
/// topology and positions within 1e-9 of the bounding-box diagonal.
#[cfg(feature = "osd")]
pub fn check_differential(case: &MeshCase) {
    use subdiv::osd;
    if osd_may_abort(&case.mesh) {
        return;
    }
    let uniform = case.uniform();
    let native = refiner::refine(&case.mesh, &case.options, subdiv::Request::from(uniform));
    let reference = osd::refine(&case.mesh, &case.options, subdiv::Request::from(uniform));
    match (native, reference) {
        (Ok(a), Ok(e)) => {
            for c in subdiv::compare::compare(&a, &e) {
                assert!(
                    c.agrees(1e-9),
                    "engines differ at level {}: counts {:?}, first differing face {:?}, \
                     tags equal {}, fvar topology equal {}, deviation {:e}, fvar deviation {:e}",
                    c.level,
                    c.counts,
                    c.first_face_difference,
                    c.tags_equal,
                    c.fvar_topology_equal,
                    c.relative_position_deviation,
                    c.max_fvar_deviation
                );
            }
        }
        (Err(_), Err(_)) => {}
        (a, e) => panic!(
            "one engine refused: native {:?}, osd {:?}",
            a.err(),
            e.err()
        ),
    }
}

// ---------------------------------------------------------------------------
// Adaptive refinement
// ---------------------------------------------------------------------------

/// Why an adaptive refinement of a mesh that passed validation may be
/// refused: the levels beyond OpenSubdiv's fields, a selected face out of
/// range, a refinement already made, and whatever refuses the base level.
fn acceptable_for_adaptive(e: &Error) -> bool {
    acceptable_for_valid_mesh(e)
        || matches!(
            e,
            Error::NoSuchElement { .. } | Error::AlreadyRefined { .. }
        )
}

/// Structural invariants of the child maps of `level` of an adaptive
/// refinement: every valid child is in range, and every child face names a
/// parent face whose children name it back.
fn check_child_maps(a: &refiner::AdaptiveRefiner, level: u32) {
    let maps = a
        .child_maps(level)
        .expect("child maps below the last level");
    let parent = a.level_counts(level).expect("parent level");
    let child = a.level_counts(level + 1).expect("child level");
    let in_range = |v: &[u32], n: usize, what: &str| {
        if let Some(i) = v.iter().find(|&&i| i != INVALID_INDEX && i as usize >= n) {
            panic!("level {level}: {what} {i} >= {n}");
        }
    };
    assert_eq!(maps.face_child_face_offsets.len(), parent.faces + 1);
    assert_eq!(maps.face_child_edge_offsets.len(), parent.faces + 1);
    assert_eq!(maps.edge_child_edges.len(), parent.edges);
    assert_eq!(maps.face_child_vertex.len(), parent.faces);
    assert_eq!(maps.edge_child_vertex.len(), parent.edges);
    assert_eq!(maps.vertex_child_vertex.len(), parent.vertices);
    assert_eq!(maps.child_face_parent_face.len(), child.faces);
    in_range(&maps.face_child_faces, child.faces, "child face");
    in_range(&maps.face_child_edges, child.edges, "child edge");
    let edge_edges: Vec<u32> = maps.edge_child_edges.iter().flatten().copied().collect();
    in_range(&edge_edges, child.edges, "edge child edge");
    in_range(&maps.face_child_vertex, child.vertices, "face child vertex");
    in_range(&maps.edge_child_vertex, child.vertices, "edge child vertex");
    in_range(
        &maps.vertex_child_vertex,
        child.vertices,
        "vertex child vertex",
    );
    for (c, &p) in maps.child_face_parent_face.iter().enumerate() {
        assert!(
            (p as usize) < parent.faces,
            "level {level}: parent face {p}"
        );
        let (lo, hi) = (
            maps.face_child_face_offsets[p as usize] as usize,
            maps.face_child_face_offsets[p as usize + 1] as usize,
        );
        assert!(
            maps.face_child_faces[lo..hi].contains(&(c as u32)),
            "level {level}: child face {c} not among its parent {p}'s children"
        );
    }
}

/// The kind of a refusal, as far as a caller can tell: the name of the
/// error's variant, where the bridge's `Osd(Refused)` for a non-triangle
/// under Loop and for an unpaired smooth vertex count as the native
/// engine's typed `NotTriangles` and `UnpairedSmoothVertex` (the same
/// conditions, found by the shim).
pub fn refusal_kind(e: &Error) -> String {
    match e {
        Error::Osd(o) if o.message.contains("Loop scheme needs triangles") => "NotTriangles".into(),
        Error::Osd(o) if o.message.contains("do not pair up") => "UnpairedSmoothVertex".into(),
        _ => format!("{e:?}")
            .chars()
            .take_while(|c| c.is_alphanumeric())
            .collect(),
    }
}

/// The native engine's adaptive refinement of one case (`mesh_refine`):
/// `refine_adaptive` is refused with a typed error or gives levels whose
/// queries, child maps, interpolation and stencils hold together; wrong
/// arguments are refused.
pub fn check_native_adaptive(case: &MeshCase, adaptive: &AdaptiveCase) {
    let mesh = &case.mesh;
    let Ok(r) = Refiner::new(mesh, &case.options) else {
        return; // check_native covers the base level
    };
    let ao = adaptive.options;
    let a = match r.refine_adaptive(ao, &adaptive.faces) {
        Ok(a) => a,
        Err(e) => {
            assert!(acceptable_for_adaptive(&e), "refine_adaptive: {e:?}");
            return;
        }
    };
    let max = a.max_level();
    // Bilinear refines its non-quads one level, whatever the isolation level.
    let deepest = match case.options.scheme {
        Scheme::Bilinear => 1,
        _ => ao.isolation_level,
    };
    assert!(max <= deepest, "{max} levels");
    assert!(a.level(max + 1).is_err());
    assert!(a.child_maps(max).is_err());
    assert!(a.relations(max + 1).is_err());
    for level in 0..=max {
        let counts = a.level_counts(level).expect("level counts");
        let topology = a.level(level).expect("level");
        assert_eq!(topology.vertex_count, counts.vertices);
        assert_eq!(topology.face_count(), counts.faces);
        assert!(
            topology
                .face_vertices
                .iter()
                .all(|&v| (v as usize) < counts.vertices),
            "level {level}: face vertex out of range"
        );
        let relations = a.relations(level).expect("relations");
        assert_eq!(relations.face_edges.len(), counts.face_vertices);
        assert_eq!(relations.vertex_rules.len(), counts.vertices);
        if level < max {
            check_child_maps(&a, level);
        }
    }
    let base = flat(&mesh.positions);
    assert!(a.interpolate::<f64>(0, 3, &base).is_err());
    assert!(a.interpolate::<f64>(max + 1, 3, &base).is_err());
    let mut levels = vec![base.clone()];
    let mut varying = base.clone();
    for level in 1..=max {
        assert!(a.interpolate::<f64>(level, 0, &[]).is_err());
        let prev = levels.last().expect("level 0");
        assert!(
            a.interpolate::<f64>(level, 3, &prev[..prev.len() - 1])
                .is_err()
        );
        let next = a.interpolate(level, 3, prev).expect("interpolate");
        let nv = a.level_counts(level).expect("counts").vertices;
        assert_eq!(next.len(), nv * 3);
        varying = a
            .interpolate_varying(level, 3, &varying)
            .expect("interpolate varying");
        assert_eq!(varying.len(), nv * 3);
        let single: Vec<f32> = prev.iter().map(|&x| x as f32).collect();
        let _ = a.interpolate::<f32>(level, 3, &single);
        levels.push(next);
    }
    // Stencils reproduce the interpolation of the last level.
    let options = subdiv::stencil::StencilOptions::new().intermediate_levels(false);
    let table = a.stencil_table_with(&options).expect("stencil table");
    if max > 0 {
        let last = levels.last().expect("level 0");
        assert_eq!(
            table.len() * 3,
            last.len(),
            "one stencil per last-level vertex"
        );
        let applied = table.apply(3, &base).expect("apply stencils");
        if case.tame() {
            let scale = scale_of(&mesh.positions);
            for (i, (x, y)) in applied.iter().zip(last).enumerate() {
                assert!(
                    close(*x, *y, scale),
                    "stencil value {i}: {x} vs interpolated {y}"
                );
            }
        }
    }
}

/// Both engines refine a valid case adaptively (`adaptive_differential`):
/// both refuse with the same kind of error, or every level is the same —
/// topology, relations, child maps, positions and varying data bit for bit,
/// and the stencil tables (vertex and each face-varying channel's).
#[cfg(feature = "osd")]
pub fn check_adaptive_differential(case: &MeshCase, adaptive: &AdaptiveCase) {
    use subdiv::osd;
    let mesh = &case.mesh;
    if osd_may_abort(mesh) {
        return;
    }
    let ao = adaptive.options;
    let faces = &adaptive.faces;
    let native = Refiner::new(mesh, &case.options).and_then(|r| r.refine_adaptive(ao, faces));
    let theirs = osd::TopologyRefiner::new(mesh, &case.options).and_then(|mut r| {
        r.refine_adaptive(ao, faces)?;
        Ok(r)
    });
    let (native, theirs) = match (native, theirs) {
        (Ok(a), Ok(b)) => (a, b),
        (Err(a), Err(b)) => {
            assert_eq!(
                refusal_kind(&a),
                refusal_kind(&b),
                "refused differently: native {a:?}, osd {b:?}"
            );
            return;
        }
        (a, b) => panic!(
            "one engine refused: native {:?}, osd {:?}",
            a.err(),
            b.err()
        ),
    };
    assert_eq!(native.max_level(), theirs.max_level(), "levels refined");
    let mine = native
        .adaptive_levels(&mesh.positions)
        .expect("native levels");
    let osds = theirs.adaptive_levels(&mesh.positions).expect("osd levels");
    for c in subdiv::compare::compare_adaptive(&mine, &osds) {
        assert!(
            c.identical(),
            "engines differ at level {}: counts {:?}, first difference {:?}, positions {:?}",
            c.level,
            c.counts,
            c.first_difference,
            c.positions
        );
    }
    let base = flat(&mesh.positions);
    let (mut a, mut b) = (base.clone(), base);
    for level in 1..=native.max_level() {
        a = native
            .interpolate_varying(level, 3, &a)
            .expect("native varying");
        b = theirs
            .interpolate_varying(level, 3, &b)
            .expect("osd varying");
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&a), bits(&b), "varying data of level {level}");
    }
    // The vertex table, and each face-varying channel's.
    let mut tables = vec![subdiv::stencil::StencilOptions::new()];
    tables.extend(
        (0..mesh.fvar_channels.len())
            .map(|c| subdiv::stencil::StencilOptions::new().face_varying(c)),
    );
    for options in tables {
        match (
            native.stencil_table_with(&options),
            theirs.stencil_table_with(&options),
        ) {
            (Ok(x), Ok(y)) => assert!(x == y, "stencil tables differ: {options:?}"),
            (x, y) => panic!(
                "stencil tables ({options:?}): native {:?}, osd {:?}",
                x.err(),
                y.err()
            ),
        }
    }
    check_osd_patches(&native, &theirs, case, adaptive);
}

/// Limit stencils at a few locations of the first ptex faces (vertex data,
/// first derivatives): where both engines build them, the same stencils
/// term by term, weights within 1e-9; the native engine refuses nothing the
/// bridge builds (Loop tables included).
#[cfg(feature = "osd")]
fn check_location_stencils(
    native: &subdiv::refiner::AdaptiveRefiner,
    theirs: &subdiv::osd::TopologyRefiner,
    adaptive: &AdaptiveCase,
) {
    use subdiv::patches::LimitStencilOptions;
    if !adaptive.faces.is_empty() {
        // The other faces' patches are undefined: the bridge refuses.
        return;
    }
    let ptex = native
        .patch_table(&subdiv::patches::PatchOptions::new(), &[])
        .map_or(0, |t| t.ptex_faces);
    let locations: Vec<(u32, f64, f64)> = (0..ptex.min(6) as u32)
        .flat_map(|f| [(f, 0.25, 0.75), (f, 1.0, 0.0)])
        .collect();
    let o = LimitStencilOptions::new();
    match (
        native.location_stencils(&locations, &o),
        theirs.location_stencils(&locations, &o),
    ) {
        (Ok(a), Ok(b)) => {
            assert_eq!(
                (&a.locations, &a.sizes, &a.indices),
                (&b.locations, &b.sizes, &b.indices),
                "location stencils differ"
            );
            for (x, y) in [
                (&a.weights.point, &b.weights.point),
                (&a.weights.du, &b.weights.du),
            ] {
                for (p, q) in x.iter().zip(y) {
                    assert!((p - q).abs() <= 1e-9, "location stencil weight {p} vs {q}");
                }
            }
        }
        // The bridge refuses what would make OpenSubdiv overrun.
        (_, Err(subdiv::Error::Osd(_))) => {}
        (Err(e), _) => panic!("native location stencils refused: {e}"),
        (Ok(_), Err(e)) => panic!("bridge location stencils failed: {e}"),
    }
}

/// OpenSubdiv's patch table of an adaptive refinement, through the bridge:
/// options derived from the case (every end-cap type, single-crease and
/// infinitely sharp patches as refined, the refinement's selected faces),
/// then patches found and their bases evaluated at three locations of each
/// of the first ptex faces. The table is refused (a face repeating a
/// vertex; legacy Gregory end caps off Catmull-Clark, over non-quads or
/// with irregular patches above the last level; B-spline end caps at an
/// interior vertex of valence 2) or consistent; every basis
/// is a partition of unity; the native `PatchMap` finds the same patches and
/// the native basis gives the same weights (to 1e-12) where it exists.
/// The native table is built first, whatever OpenSubdiv makes of the case,
/// without panicking; where both build one they are identical (local-point
/// stencils bit for bit), and the native limit surface is finite at the
/// same locations.
#[cfg(feature = "osd")]
fn check_osd_patches(
    native: &subdiv::refiner::AdaptiveRefiner,
    theirs: &subdiv::osd::TopologyRefiner,
    case: &MeshCase,
    adaptive: &AdaptiveCase,
) {
    use subdiv::patches::{Derivatives, EndCapType, PatchOptions};
    let ao = adaptive.options;
    let end_caps = [
        EndCapType::None,
        EndCapType::BilinearBasis,
        EndCapType::BSplineBasis,
        EndCapType::GregoryBasis,
        EndCapType::LegacyGregory,
    ][(ao.isolation_level as usize + adaptive.faces.len()) % 5];
    let options = PatchOptions {
        share_end_cap_points: ao.order_vertices_from_faces_first,
        legacy_sharp_corner_patches: !ao.consider_fvar_channels,
        // Face-varying patches: linear ones (OpenSubdiv's default legacy
        // ones) or, every other odd level, the channels' own non-linear
        // patches, their local points in either precision.
        fvar_tables: ao.isolation_level % 2 == 1,
        fvar_legacy_linear_patches: ao.isolation_level % 4 == 1,
        fvar_patch_precision_double: adaptive.faces.len() % 2 == 1,
        ..PatchOptions::new()
            .max_isolation(ao.isolation_level.min(10))
            .end_caps(end_caps)
            .single_crease_patch(ao.use_single_crease_patch)
            .inf_sharp_patch(ao.use_inf_sharp_patch)
    };
    // Faces that use a vertex twice are refused (OpenSubdiv's patch
    // builders overrun on them), and so are legacy Gregory end caps where
    // their tables do not fit and B-spline end caps around interior
    // vertices of valence 2.
    let repeats = case.mesh.faces().any(|f| {
        let mut v = f.to_vec();
        v.sort_unstable();
        v.windows(2).any(|w| w[0] == w[1])
    });
    let mine = native.patch_table(&options, &adaptive.faces);
    let base = case.mesh.flat_positions::<f64>();
    if let Ok((t, points)) = mine.as_ref().map_err(|_| ()).and_then(|t| {
        native
            .patch_points(t, 3, &base)
            .map(|p| (t, p))
            .map_err(|_| ())
    }) {
        let locations: Vec<(u32, f64, f64)> = (0..t.ptex_faces.min(8) as u32)
            .map(|f| (f, 0.25, 0.75))
            .collect();
        if let Ok(s) = subdiv::patches::evaluate(t, &points, 3, &locations, Derivatives::First) {
            assert!(
                s.values.point.iter().all(|x| x.is_finite()),
                "native limit surface not finite"
            );
        }
        // The first face-varying channel over its patches, local points
        // included.
        if let (Some(fv), Some(ch)) = (t.fvar_channels.first(), case.mesh.fvar_channels.first()) {
            let data = subdiv::patches::PatchData::FaceVarying(0);
            if fv.channel == 0
                && let Ok(values) = native.patch_data_points(t, data, ch.width, &ch.values)
            {
                let map = subdiv::patches::PatchMap::new(t);
                if let Ok(s) = subdiv::patches::evaluate_data(
                    &map,
                    t,
                    data,
                    &values,
                    ch.width,
                    &locations,
                    Derivatives::First,
                ) {
                    assert!(
                        s.values.point.iter().all(|x| x.is_finite()),
                        "native face-varying limit not finite"
                    );
                }
            }
        }
    }
    let patches = match theirs.patch_table(&options, &adaptive.faces) {
        Ok(p) => p,
        Err(e) => {
            // B-spline end caps (or unspecified ones) also refuse interior
            // vertices of valence 2.
            let bspline = matches!(end_caps, EndCapType::None | EndCapType::BSplineBasis);
            // Loop end caps over two triangles folded onto each other, left
            // unrefined.
            let folded = case.options.scheme == subdiv::Scheme::Loop
                && matches!(&e, subdiv::Error::Osd(o) if o.message.contains("valence 2"));
            assert!(
                repeats || end_caps == EndCapType::LegacyGregory || bspline || folded,
                "patch table refused: {e}"
            );
            assert!(
                matches!(&e, subdiv::Error::Osd(o) if o.kind == subdiv::OsdErrorKind::Unsafe)
                    || end_caps == EndCapType::LegacyGregory,
                "patch table refused: {e}"
            );
            return;
        }
    };
    assert!(!repeats, "a face repeating a vertex was not refused");
    check_location_stencils(native, theirs, adaptive);
    let t = patches.table();
    match mine {
        Ok(m) => assert!(m == *t, "native patch table differs from OpenSubdiv's"),
        Err(e) => panic!("native patch table refused: {e}"),
    }
    let points = (0..=theirs.max_level())
        .map(|l| theirs.level_counts(l).map_or(0, |c| c.vertices))
        .sum::<usize>()
        + t.local_points;
    for a in &t.arrays {
        assert_eq!(
            a.control_vertices.len(),
            a.len() * a.patch_type.control_vertices()
        );
        assert!(a.control_vertices.iter().all(|&v| (v as usize) < points));
    }
    let map = subdiv::patches::PatchMap::new(t);
    for face in 0..t.ptex_faces.min(16) as u32 {
        for (u, v) in [(0.5, 0.5), (0.0, 1.0), (0.25, 0.75)] {
            let found = patches
                .find_patch(face, u, v)
                .expect("a ptex face in range");
            assert_eq!(
                map.find_patch(face, u, v),
                found,
                "native PatchMap, face {face} ({u}, {v})"
            );
            let Some(h) = found else {
                continue;
            };
            let ty = t.arrays[h.array].patch_type;
            if !ty.is_evaluable() {
                continue;
            }
            let w = patches
                .evaluate_basis(h, u, v, Derivatives::Second)
                .expect("an evaluable patch");
            let sum: f64 = w.point.iter().sum();
            assert!((sum - 1.0).abs() < 1e-9, "basis sums to {sum}");
            // The native basis where it exists.
            let param = t.arrays[h.array].params[h.patch];
            if let Ok(mine) = subdiv::patches::evaluate_basis(ty, param, u, v, Derivatives::Second)
            {
                let scale = f64::from(1u32 << param.depth());
                for (a, b) in mine.point.iter().zip(&w.point) {
                    assert!((a - b).abs() <= 1e-12, "{ty:?} {param:?}: {a} vs {b}");
                }
                for (a, b) in mine.du.iter().zip(&w.du).chain(mine.dv.iter().zip(&w.dv)) {
                    assert!(
                        (a - b).abs() <= 1e-12 * scale,
                        "{ty:?} {param:?}: {a} vs {b}"
                    );
                }
            }
        }
    }
    check_eval_patches(native, &patches, &base);
}

/// OpenSubdiv's CPU evaluator (`EvalPatches`, `f32`) over the native
/// engine's points against the native evaluation of the same `f32` points:
/// both refuse the same locations (holes, patches without a basis) or give
/// positions within `f32` rounding (where both are finite).
fn check_eval_patches(
    native: &subdiv::refiner::AdaptiveRefiner,
    patches: &subdiv::osd::OsdPatchTable,
    base: &[f64],
) {
    let t = patches.table();
    // EvalPatches is refused for a whole table with patches it has no basis
    // for (legacy Gregory), the native engine only where they are asked for.
    if t.arrays
        .iter()
        .any(|a| !a.is_empty() && !a.patch_type.is_evaluable())
    {
        return;
    }
    let Ok(points) = native.patch_points(t, 3, base) else {
        return;
    };
    let points: Vec<f32> = points.iter().map(|&x| x as f32).collect();
    let locations: Vec<(u32, f64, f64)> = (0..t.ptex_faces.min(16) as u32)
        .flat_map(|f| [(f, 0.5, 0.5), (f, 0.0, 1.0), (f, 0.25, 0.75)])
        .collect();
    let cpu = patches.cpu_patch_table().expect("a CPU patch table");
    use subdiv::patches::Derivatives;
    let theirs = cpu.evaluate(&points, 3, &locations, Derivatives::First);
    let mine = subdiv::patches::evaluate(t, &points, 3, &locations, Derivatives::First);
    let (theirs, mine) = match (theirs, mine) {
        (Ok(a), Ok(b)) => (a, b),
        (Err(_), Err(_)) => return,
        (a, b) => panic!("EvalPatches {a:?}, native {b:?}"),
    };
    let size = 1.0
        + points
            .iter()
            .fold(0.0f64, |m, &x| m.max(f64::from(x).abs()));
    for (a, b) in theirs.values.point.iter().zip(&mine.values.point) {
        if a.is_finite() && b.is_finite() {
            assert!(
                f64::from((a - b).abs()) <= 1e-4 * size,
                "EvalPatches {a} against native {b}"
            );
        }
    }
}

// ---------------------------------------------------------------------------
// OBJ
// ---------------------------------------------------------------------------

/// `parse_obj` on any bytes: the same result or error as the general parser
/// alone (the fast path and the chunked reader change nothing); an error
/// names a real line; a success writes back to text that reads as the same
/// mesh; small valid meshes refine.
pub fn check_obj(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    let file = Path::new("fuzz.obj");
    let general = parse_obj_general(&text, file);
    assert_eq!(
        parse_obj(&text, file),
        general,
        "the fast path and the general parser differ"
    );
    assert_eq!(
        parse_obj_chunked(&text, file, 3),
        general,
        "the chunked reader and the general parser differ"
    );
    // The raw bytes, a block at a time: blocks cutting lines and UTF-8
    // sequences, lines longer than the buffer.
    assert_eq!(
        parse_obj_streamed(data, file, 1 + data.len() % 7),
        general,
        "the streaming reader and the general parser differ"
    );
    let lines = text
        .strip_prefix('\u{feff}')
        .unwrap_or(&text)
        .lines()
        .count();
    let shape = match parse_obj(&text, file) {
        Err(e) => {
            assert_eq!(e.file, file);
            assert!(
                e.line >= 1 && e.line <= lines,
                "error on line {} of {lines}: {e}",
                e.line
            );
            assert!(!matches!(e.kind, ObjErrorKind::Io(_)), "{e}");
            let message = e.to_string();
            assert!(
                message.starts_with(&format!("fuzz.obj:{}: ", e.line)),
                "{message}"
            );
            return;
        }
        Ok(shape) => shape,
    };
    for w in &shape.warnings {
        assert!(w.line >= 1 && w.line <= lines, "warning on line {}", w.line);
    }
    let mesh = &shape.mesh;
    assert_eq!(mesh.face_offsets.len(), mesh.face_count() + 1);
    assert!(mesh.positions.iter().all(|p| p.is_finite()));
    // The writer's output reads back as the same mesh.
    let written = mesh_to_obj_string(mesh, Precision::F64);
    let back = parse_obj(&written, Path::new("written.obj"))
        .unwrap_or_else(|e| panic!("the writer's output does not parse: {e}\n{written}"));
    assert_eq!(&back.mesh, mesh, "round trip through the writer");
    // Small valid meshes refine with the file's own options.
    if mesh.face_count() <= 64 && mesh.face_vertices.len() <= 256 && mesh.validate().is_ok() {
        let scheme = [Scheme::Catmark, Scheme::Loop, Scheme::Bilinear][data.len() % 3];
        let case = MeshCase {
            mesh: shape.mesh.clone(),
            options: shape.options().with_scheme(scheme),
            level: 1,
            faces_first: false,
            full_topology: false,
            precision: Precision::F64,
            limit: false,
        };
        check_native(&case);
        #[cfg(feature = "osd")]
        check_osd(&case);
    }
}

// ---------------------------------------------------------------------------
// Curves
// ---------------------------------------------------------------------------

/// Most points a curve refinement may produce in one run of the fuzzer.
const CURVE_BUDGET: usize = 50_000;

/// `parse_points` on any text (after 6 configuration bytes), then every
/// scheme's refinement, flattening and evaluation of what it returns.
pub fn check_curve(data: &[u8]) {
    if data.len() < 6 {
        return;
    }
    let (cfg, rest) = data.split_at(6);
    let text = String::from_utf8_lossy(rest);
    let file = Path::new("fuzz.txt");
    let lines = text.lines().count();
    let parsed = match points_io::parse_points(&text, file) {
        Err(e) => {
            assert!(
                e.line >= 1 && e.line <= lines,
                "error on line {} of {lines}: {e}",
                e.line
            );
            assert!(!matches!(e.kind, PointsErrorKind::Io(_)), "{e}");
            assert!(
                e.to_string().starts_with(&format!("fuzz.txt:{}: ", e.line)),
                "{e}"
            );
            return;
        }
        Ok(p) => p,
    };
    assert_eq!(parsed.lines.len(), parsed.points.len());
    assert!(parsed.lines.windows(2).all(|w| w[0] < w[1]));
    assert!(
        parsed
            .lines
            .iter()
            .all(|&l| l >= 1 && l <= parsed.line_count)
    );
    let tension = [
        curve::DEFAULT_TENSION,
        0.0,
        -1.0,
        0.1,
        1e300,
        f64::NAN,
        f64::INFINITY,
        -0.0625,
    ][usize::from(cfg[2] % 8)];
    let configured = match cfg[0] % 4 {
        0 => CurveScheme::Chaikin,
        1 => CurveScheme::BSpline {
            degree: usize::from(cfg[1] % 18),
        },
        2 => CurveScheme::FourPoint { tension },
        _ => CurveScheme::Jarek,
    };
    let closed = cfg[3] & 1 == 1;
    let levels = u32::from(cfg[4] % 32);
    let tolerance = [0.5, 0.1, 1e-3, 1e-6, 0.0, -1.0, f64::NAN, 1e-300][usize::from(cfg[5] % 8)];
    let schemes = [
        configured,
        CurveScheme::Chaikin,
        CurveScheme::BSpline { degree: 3 },
        CurveScheme::four_point(),
        CurveScheme::Jarek,
    ];
    for scheme in schemes {
        let required = parsed.require(&scheme, closed);
        let ok = match &parsed.points {
            Points::Planar(p) => curve_scheme(p, scheme, closed, levels, tolerance, cfg),
            Points::Spatial(p) => curve_scheme(p, scheme, closed, levels, tolerance, cfg),
        };
        if scheme.check().is_ok() {
            assert_eq!(
                required.is_ok(),
                ok,
                "require() and refinement disagree for {scheme}: {required:?}"
            );
        }
        if let Err(e) = required {
            assert!(e.line >= 1, "{e}");
        }
    }
    // Text round trip: what format_points writes reads back exactly.
    let round_trip =
        |text: String| points_io::parse_points(&text, file).expect("formatted points parse");
    let formatted = match &parsed.points {
        Points::Planar(p) => points_io::format_points(p),
        Points::Spatial(p) => points_io::format_points(p),
    };
    assert_eq!(
        round_trip(formatted).points,
        parsed.points,
        "text round trip"
    );
}

/// Equal coordinates, bit for bit (NaN included).
fn same_bits<P: Point>(a: &[P], b: &[P]) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).all(|(p, q)| {
            let (p, q) = (p.to_dvec3().to_array(), q.to_dvec3().to_array());
            p.iter().zip(&q).all(|(x, y)| x.to_bits() == y.to_bits())
        })
}

fn bbox<P: Point>(points: &[P]) -> (DVec3, DVec3) {
    points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p.to_dvec3()), hi.max(p.to_dvec3())),
    )
}

/// Refines `points` with one scheme; returns whether refinement was accepted.
fn curve_scheme<P: Point>(
    points: &[P],
    scheme: CurveScheme,
    closed: bool,
    levels: u32,
    tolerance: f64,
    cfg: &[u8],
) -> bool {
    let n = points.len();
    let tame = points
        .iter()
        .all(|p| p.to_dvec3().abs().max_element() <= 1e6);
    // Levels that would produce too many points are refused before anything is allocated.
    let mut levels = levels;
    match curve::refined_count(n, scheme, closed, levels) {
        Err(CurveError::TooManyPoints) => {
            let r = curve::refine_levels(points, scheme, closed, levels);
            assert!(
                matches!(
                    r,
                    Err(CurveError::TooManyPoints
                        | CurveError::TooFewPoints { .. }
                        | CurveError::BadDegree { .. }
                        | CurveError::BadTension(_)
                        | CurveError::Overflow { .. })
                ),
                "{scheme}: {:?}",
                r.map(|v| v.len())
            );
        }
        Err(e) => panic!("refined_count: {e}"),
        Ok(_) => {}
    }
    while levels > 0
        && !matches!(curve::refined_count(n, scheme, closed, levels), Ok(c) if c <= CURVE_BUDGET)
    {
        levels -= 1;
    }
    let all = match curve::refine_levels(points, scheme, closed, levels) {
        Ok(all) => all,
        // The points are acceptable; a level overflows f64 (huge coordinates
        // or tension): refused whole, and refine_once agrees on level 1.
        Err(CurveError::Overflow { level, .. }) => {
            assert!(
                level >= 1 && level <= levels,
                "{scheme}: overflow at level {level}"
            );
            if level == 1 {
                assert!(matches!(
                    curve::refine_once(points, scheme, closed),
                    Err(CurveError::Overflow { level: 1, .. })
                ));
            }
            return true;
        }
        Err(e) => {
            assert!(
                matches!(
                    e,
                    CurveError::TooFewPoints { .. }
                        | CurveError::BadDegree { .. }
                        | CurveError::BadTension(_)
                ),
                "{scheme}: {e}"
            );
            assert!(curve::refine_once(points, scheme, closed).is_err());
            return false;
        }
    };
    assert_eq!(all.len(), levels as usize + 1);
    assert_eq!(all[0], points);
    for (k, level) in all.iter().enumerate() {
        assert_eq!(
            Ok(level.len()),
            curve::refined_count(n, scheme, closed, k as u32),
            "{scheme}: level {k} size"
        );
        if k > 0 {
            let once = curve::refine_once(&all[k - 1], scheme, closed).expect("one more level");
            assert!(
                same_bits(level, &once),
                "{scheme}: refine_levels vs refine_once at level {k}"
            );
        }
    }
    let (lo, hi) = bbox(points);
    let slack = 1e-12 * (1.0 + lo.abs().max(hi.abs()).max_element());
    match scheme {
        // Averaging: every refined point is in the convex hull, so in the box.
        CurveScheme::Chaikin | CurveScheme::BSpline { .. } if tame => {
            for level in &all {
                for p in level {
                    let q = p.to_dvec3();
                    assert!(
                        q.cmpge(lo - slack).all() && q.cmple(hi + slack).all(),
                        "{scheme}: {q} outside the control box {lo}..{hi}"
                    );
                }
            }
        }
        // Interpolating: the old points stay, exactly.
        CurveScheme::FourPoint { .. } if levels >= 1 => {
            for (i, p) in points.iter().enumerate() {
                assert_eq!(all[1][2 * i], *p, "{scheme}: old point {i} moved");
            }
        }
        _ => {}
    }
    // Whatever the input, a returned level is finite (an overflow is an error).
    assert!(all.iter().flatten().all(|p| p.is_finite()));
    if let Some(degree) = scheme.limit_degree() {
        let curve = BSplineCurve::new(points.to_vec(), degree, closed).expect("valid B-spline");
        let (min, max) = curve.domain();
        let at = |b: u8| match b % 6 {
            0 => min,
            1 => max,
            2 => 0.5 * (min + max),
            3 => max + 1.0,
            4 => f64::NAN,
            _ => min + (max - min) * f64::from(b) / 255.0,
        };
        for &b in cfg {
            let s = at(b);
            let inside = s >= min && s <= max;
            match curve.eval(s) {
                Ok(p) => assert!(inside || closed && s.is_finite(), "eval({s}) = {p:?}"),
                Err(e) => {
                    assert!(!inside, "eval({s}) inside [{min}, {max}]: {e}");
                    assert!(matches!(e, CurveError::ParameterOutOfRange { .. }));
                }
            }
        }
        for seg in 0..curve.segment_count() {
            assert_eq!(curve.segment_bezier(seg).map(|b| b.len()), Some(degree + 1));
        }
        assert!(curve.segment_bezier(curve.segment_count()).is_none());
        // Flatten only where it stays small: a tolerance not far below the size.
        let size = (hi - lo).length();
        if tame && n <= 64 && (tolerance.is_nan() || tolerance <= 0.0 || tolerance >= size * 1e-6) {
            match curve::flatten(points, scheme, closed, tolerance) {
                Ok(line) => {
                    assert!(tolerance > 0.0);
                    assert_eq!(line.points.len(), line.params.len());
                    assert!(line.params.windows(2).all(|w| w[0] < w[1]));
                    let scale = 1.0 + lo.abs().max(hi.abs()).max_element();
                    for (p, &s) in line.points.iter().zip(&line.params) {
                        let on = curve.eval(s).expect("a parameter of the polyline");
                        assert!(
                            (on - *p).length() <= 1e-9 * scale,
                            "flattened point {p:?} at {s} is not on the curve ({on:?})"
                        );
                    }
                }
                Err(e) => assert!(
                    matches!(
                        e,
                        CurveError::BadTolerance(_)
                            | CurveError::ToleranceTooSmall { .. }
                            | CurveError::TooManyPoints
                    ),
                    "flatten: {e}"
                ),
            }
        }
    }
    true
}
