//! The conformance and performance report (`subdiv report`): the native
//! engine against OpenSubdiv on a set of inputs, for every scheme and option
//! that applies, with benchmarks, written as Markdown and as a self-contained
//! HTML page (inline CSS and inline SVG plots and pictures).
//!
//! For each [`Input`], [`run`]:
//!
//! - refines the mesh with both engines ([`refiner::refine_with`] and
//!   [`osd::refine_with`]) for every option set of [`option_sets`] and
//!   compares them level by level ([`crate::compare::compare`]): topology,
//!   positions relative to the bounding-box diagonal, face-varying values;
//!   then evaluates the limit at the last level with both and compares limit
//!   positions, tangents and face-varying values;
//! - times "refine + positions" (topology refinement and `f64` position
//!   interpolation of every level) per level with the input's own options,
//!   both engines interleaved, medians ([`bench::interleaved`]), the native
//!   engine on one thread;
//! - draws the native refined shape, each face coloured by how far its
//!   vertices are from OpenSubdiv's.
//!
//! ```no_run
//! use subdiv::report::{self, Settings};
//! let inputs = report::embedded_inputs();
//! let rep = report::run(&inputs, &Settings::new(true), |_| {})?;
//! rep.write(std::path::Path::new("report"))?;
//! assert!(rep.conforms());
//! # Ok::<(), subdiv::Error>(())
//! ```

use crate::compare::{bbox_diagonal, compare};
use crate::io::svg::{Projection, write_atomically};
use crate::level::LevelTopology;
use crate::mesh::{FVarChannel, Mesh};
use crate::options::{
    BoundaryInterpolation, CreasingMethod, FVarLinearInterpolation, Options, Scheme,
    TriangleSubdivision, UniformOptions,
};
use crate::refinement::{Precision, Refinement, check_level};
use crate::{Error, Result, bench, osd, refiner, shapes};
use glam::{DVec2, DVec3};
use std::collections::HashMap;
use std::fmt::Write as _;
use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

/// The largest accepted deviation, relative to the bounding-box diagonal.
pub const DEFAULT_TOLERANCE: f64 = 1e-6;

/// Pictures show the deepest compared level with at most this many faces.
pub const MAX_PICTURE_FACES: usize = 8192;

/// One input of the report: a mesh and the options it is refined with by default.
#[derive(Debug, Clone)]
pub struct Input {
    /// Short name (a file name for OBJ inputs).
    pub name: String,
    /// One line saying what the input exercises.
    pub description: String,
    /// The mesh.
    pub mesh: Mesh,
    /// The default options: the ones benchmarked and pictured; the
    /// comparisons vary them (see [`option_sets`]).
    pub options: Options,
}

impl Input {
    /// An input from its parts.
    pub fn new(
        name: impl Into<String>,
        description: impl Into<String>,
        mesh: Mesh,
        options: Options,
    ) -> Input {
        Input {
            name: name.into(),
            description: description.into(),
            mesh,
            options,
        }
    }
}

/// Reads an OBJ shape file as an input: its options are the file's tags over
/// OpenSubdiv's shape-file defaults. Returns the input and the warnings of
/// the reader and of the mesh validation. A malformed file is an
/// [`Error::Obj`] naming the file and line; an invalid mesh an [`Error::Mesh`].
pub fn read_input(path: &Path) -> Result<(Input, Vec<String>)> {
    let shape = crate::io::read_obj(path)?;
    let mut warnings: Vec<String> = shape.warnings.iter().map(ToString::to_string).collect();
    let validation = shape.mesh.validate()?;
    warnings.extend(validation.warnings.iter().map(ToString::to_string));
    let name = path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let m = &shape.mesh;
    let description = format!(
        "{}: {} vertices, {} faces{}{}{}",
        path.display(),
        m.vertex_count(),
        m.face_count(),
        if m.creases.is_empty() && m.corners.is_empty() {
            ""
        } else {
            ", creases/corners"
        },
        if m.holes.is_empty() { "" } else { ", holes" },
        if m.fvar_channels.is_empty() {
            ""
        } else {
            ", UVs"
        },
    );
    let options = shape.options();
    Ok((Input::new(name, description, shape.mesh, options), warnings))
}

/// A 4×4 grid of unit quads with a gentle wave in z (for nicer pictures).
fn wavy_grid() -> Mesh {
    let mut m = shapes::grid(4, 4);
    for p in &mut m.positions {
        p.z = 0.35 * (1.1 * p.x).sin() * (0.8 * p.y).cos();
    }
    m
}

/// A box whose top edges are semi-sharp creases of different sharpness (so
/// uniform and Chaikin creasing differ), a semi-sharp vertical edge and a
/// semi-sharp corner.
fn creased_box() -> Mesh {
    let mut m = shapes::cube();
    for p in &mut m.positions {
        p.x *= 1.6;
    }
    m.add_crease(4, 5, 0.5);
    m.add_crease(5, 6, 1.5);
    m.add_crease(6, 7, 2.5);
    m.add_crease(7, 4, 3.3);
    m.add_crease(1, 5, 2.0);
    m.add_corner(0, 2.5);
    m
}

/// The wavy grid with three faces tagged as holes.
fn grid_with_holes() -> Mesh {
    let mut m = wavy_grid();
    m.fvar_channels.clear();
    m.holes.extend([5, 6, 15]);
    m
}

/// The wavy grid whose UVs form four regions (its quadrants), each mapped to
/// its own part of the texture: the channel splits along the seams between them.
fn grid_uv_regions() -> Mesh {
    let mut m = wavy_grid();
    m.fvar_channels.clear();
    let n = 4u32;
    let mut values = Vec::new();
    let mut indices = Vec::new();
    let mut index_of: HashMap<(u32, u32), u32> = HashMap::new();
    for f in 0..m.face_count() {
        let (i, j) = (f as u32 % n, f as u32 / n);
        let region = u32::from(i >= n / 2) + 2 * u32::from(j >= n / 2);
        for &v in m.face(f) {
            let next = index_of.len() as u32;
            let k = *index_of.entry((v, region)).or_insert_with(|| {
                let (x, y) = (v % (n + 1), v / (n + 1));
                values.extend_from_slice(&[
                    0.45 * f64::from(x) / f64::from(n) + 0.5 * f64::from(region % 2),
                    0.45 * f64::from(y) / f64::from(n) + 0.5 * f64::from(region / 2),
                ]);
                next
            });
            indices.push(k);
        }
    }
    m.fvar_channels.push(FVarChannel {
        width: 2,
        values,
        indices,
    });
    m
}

/// The inputs shipped in the binary, generated in code: closed and open
/// meshes, semi-sharp creases and a corner, an extraordinary pole, holes, UV
/// seams, several components, a Loop mesh, a bilinear mesh and a
/// non-manifold fin.
pub fn embedded_inputs() -> Vec<Input> {
    let d = Options::shape_file_defaults();
    vec![
        Input::new(
            "cube",
            "the unit cube: 6 quads, 8 valence-3 vertices, closed",
            shapes::cube(),
            d,
        ),
        Input::new(
            "torus",
            "a closed 8×4 quad torus: every vertex regular",
            shapes::torus(8, 4),
            d,
        ),
        Input::new(
            "creased-box",
            "a box with semi-sharp creases (sharpness 0.5 to 3.3) and a semi-sharp corner (2.5)",
            creased_box(),
            d,
        ),
        Input::new(
            "pole",
            "a valence-7 pole: 7 triangles around one vertex, a ring of quads, a heptagon",
            shapes::pole(7),
            d,
        ),
        Input::new(
            "holes",
            "an open wavy 4×4 grid with three faces tagged as holes",
            grid_with_holes(),
            d,
        ),
        Input::new(
            "cube-uv",
            "the cube with one UV square per face: UV seams along every edge",
            shapes::cube_with_uvs(),
            d,
        ),
        Input::new(
            "grid-uv-regions",
            "an open wavy 4×4 grid whose UVs form 4 regions, with seams between them",
            grid_uv_regions(),
            d,
        ),
        Input::new(
            "four-boxes",
            "four disjoint boxes of different sizes in one mesh",
            shapes::four_boxes(),
            d,
        ),
        Input::new(
            "icosahedron",
            "a regular icosahedron (20 triangles, valence 5), refined with Loop",
            shapes::icosahedron(),
            d.with_scheme(Scheme::Loop),
        ),
        Input::new(
            "bilinear-prism",
            "a twisted hexagonal prism (hexagons and quads), refined bilinearly",
            shapes::prism(6),
            d.with_scheme(Scheme::Bilinear),
        ),
        Input::new(
            "fin",
            "a non-manifold fin: three quads on one edge, and a quad on each side",
            shapes::fin(),
            d,
        ),
    ]
}

/// What a mesh has that makes options matter.
#[derive(Debug, Clone, Copy, Default)]
struct Traits {
    /// Some edge has one face (or more than two).
    boundary: bool,
    /// Creases or corners.
    creases: bool,
    /// Some face is a triangle.
    triangles: bool,
    /// Every face is a triangle.
    all_triangles: bool,
    /// A face-varying channel.
    uvs: bool,
}

fn edge_face_counts<'a>(faces: impl Iterator<Item = &'a [u32]>) -> HashMap<(u32, u32), u32> {
    let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
    for f in faces {
        for (i, &a) in f.iter().enumerate() {
            let b = f[(i + 1) % f.len()];
            if a != b {
                *edges.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
    }
    edges
}

fn traits(mesh: &Mesh) -> Traits {
    let sizes = mesh.face_sizes();
    Traits {
        boundary: edge_face_counts(mesh.faces()).values().any(|&n| n != 2),
        creases: !mesh.creases.is_empty() || !mesh.corners.is_empty(),
        triangles: sizes.contains(&3),
        all_triangles: !sizes.is_empty() && sizes.iter().all(|&n| n == 3),
        uvs: !mesh.fvar_channels.is_empty(),
    }
}

/// The option sets an input is compared with. Schemes: the input's own
/// first, then Catmull-Clark and bilinear, and Loop when every face is a
/// triangle. An option is varied only where it can change the result: the
/// three boundary modes on meshes with a boundary, both creasing methods with
/// creases or corners (not under bilinear), both triangle rules under
/// Catmull-Clark with triangles, the six face-varying modes with UVs. The full
/// report takes every combination; `quick` varies one option at a time.
pub fn option_sets(input: &Input, quick: bool) -> Vec<Options> {
    let t = traits(&input.mesh);
    let base = input.options;
    let mut schemes = vec![base.scheme];
    for s in [Scheme::Catmark, Scheme::Bilinear, Scheme::Loop] {
        if !schemes.contains(&s) && (s != Scheme::Loop || t.all_triangles) {
            schemes.push(s);
        }
    }
    schemes.retain(|&s| s != Scheme::Loop || t.all_triangles);
    let mut out: Vec<Options> = Vec::new();
    let mut push = |o: Options| {
        if !out.contains(&o) {
            out.push(o);
        }
    };
    for scheme in schemes {
        let b = base.with_scheme(scheme);
        let boundaries: Vec<BoundaryInterpolation> = if t.boundary {
            BoundaryInterpolation::ALL.to_vec()
        } else {
            vec![b.boundary]
        };
        let creasings: Vec<CreasingMethod> = if t.creases && scheme != Scheme::Bilinear {
            CreasingMethod::ALL.to_vec()
        } else {
            vec![b.creasing]
        };
        let triangles: Vec<TriangleSubdivision> = if t.triangles && scheme == Scheme::Catmark {
            TriangleSubdivision::ALL.to_vec()
        } else {
            vec![b.triangles]
        };
        let fvars: Vec<FVarLinearInterpolation> = if t.uvs {
            FVarLinearInterpolation::ALL.to_vec()
        } else {
            vec![b.fvar]
        };
        push(b);
        if quick {
            boundaries.iter().for_each(|&x| push(b.with_boundary(x)));
            creasings.iter().for_each(|&x| push(b.with_creasing(x)));
            triangles.iter().for_each(|&x| push(b.with_triangles(x)));
            fvars.iter().for_each(|&x| push(b.with_fvar(x)));
        } else {
            for &bd in &boundaries {
                for &c in &creasings {
                    for &tr in &triangles {
                        for &f in &fvars {
                            push(
                                b.with_boundary(bd)
                                    .with_creasing(c)
                                    .with_triangles(tr)
                                    .with_fvar(f),
                            );
                        }
                    }
                }
            }
        }
    }
    out
}

/// What a report run covers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// The first compared level.
    pub first_level: u32,
    /// The last compared level (refined, benchmarked, limit-evaluated).
    pub last_level: u32,
    /// Fewer option sets (one option varied at a time) and shorter benchmarks.
    pub quick: bool,
    /// The largest accepted deviation, relative to the bounding-box diagonal.
    pub tolerance: f64,
}

impl Settings {
    /// Levels 1..4 (1..2 when `quick`), tolerance [`DEFAULT_TOLERANCE`].
    pub fn new(quick: bool) -> Settings {
        Settings {
            first_level: 1,
            last_level: if quick { 2 } else { 4 },
            quick,
            tolerance: DEFAULT_TOLERANCE,
        }
    }

    /// The benchmarked levels: the compared ones, level 0 left out.
    pub fn timed_levels(&self) -> std::ops::RangeInclusive<u32> {
        self.first_level.max(1)..=self.last_level
    }
}

/// One level of one option set: native against OpenSubdiv.
#[derive(Debug, Clone, PartialEq)]
pub struct LevelResult {
    /// The level.
    pub level: u32,
    /// Vertices (OpenSubdiv's count).
    pub vertices: usize,
    /// Faces (OpenSubdiv's count).
    pub faces: usize,
    /// Whether counts, face-vertex lists, sharpness, holes and face-varying
    /// topology are equal.
    pub topology_equal: bool,
    /// Largest position deviation relative to the bounding-box diagonal.
    pub position_deviation: f64,
    /// Largest face-varying value deviation, when the mesh has UVs.
    pub fvar_deviation: Option<f64>,
    /// Whether everything is within the tolerance.
    pub agrees: bool,
}

impl LevelResult {
    /// The larger of the position and face-varying deviations.
    pub fn deviation(&self) -> f64 {
        self.position_deviation
            .max(self.fvar_deviation.unwrap_or(0.0))
    }
}

/// The limit at the last level of one option set: native against OpenSubdiv.
#[derive(Debug, Clone, PartialEq)]
pub struct LimitResult {
    /// The level the limit was evaluated at.
    pub level: u32,
    /// Largest limit position deviation, relative to the bounding-box diagonal.
    pub position_deviation: f64,
    /// Largest tangent deviation (both tangents, relative to the diagonal),
    /// outside the vertices of the known difference.
    pub tangent_deviation: f64,
    /// Largest face-varying limit value deviation, when the mesh has UVs.
    pub fvar_deviation: Option<f64>,
    /// Vertices on non-manifold edges whose tangents differ: OpenSubdiv 3.5's
    /// known tangent bug there (docs/CONFORMANCE.md), not counted as failures.
    pub known_difference_vertices: usize,
    /// Whether positions, tangents (known difference excepted) and
    /// face-varying values are within the tolerance.
    pub agrees: bool,
}

impl LimitResult {
    /// The largest deviation counted for conformance.
    pub fn deviation(&self) -> f64 {
        self.position_deviation
            .max(self.tangent_deviation)
            .max(self.fvar_deviation.unwrap_or(0.0))
    }
}

/// All comparisons of one option set.
#[derive(Debug, Clone, PartialEq)]
pub struct SetResult {
    /// The options.
    pub options: Options,
    /// Levels `first_level..=last_level`.
    pub levels: Vec<LevelResult>,
    /// The limit at the last level.
    pub limit: Option<LimitResult>,
    /// An engine failed (one failing case): which and why.
    pub error: Option<String>,
}

impl SetResult {
    /// Checks made: one per level, one for the limit, one for an error.
    pub fn cases(&self) -> usize {
        self.levels.len() + usize::from(self.limit.is_some()) + usize::from(self.error.is_some())
    }

    /// Checks passed.
    pub fn agreeing(&self) -> usize {
        self.levels.iter().filter(|l| l.agrees).count()
            + usize::from(self.limit.as_ref().is_some_and(|l| l.agrees))
    }

    /// The largest deviation of any check (infinite after an error).
    pub fn worst_deviation(&self) -> f64 {
        if self.error.is_some() {
            return f64::INFINITY;
        }
        self.levels
            .iter()
            .map(LevelResult::deviation)
            .chain(self.limit.iter().map(LimitResult::deviation))
            .fold(0.0, f64::max)
    }
}

/// The median time of "refine + positions" at one level.
#[derive(Debug, Clone, PartialEq)]
pub struct Timing {
    /// The level.
    pub level: u32,
    /// Faces at that level.
    pub faces: usize,
    /// Native median, seconds.
    pub native: f64,
    /// OpenSubdiv median, seconds.
    pub osd: f64,
    /// Repetitions of each.
    pub reps: usize,
}

impl Timing {
    /// OpenSubdiv's time over the native time (above 1: native is faster).
    pub fn speedup(&self) -> f64 {
        self.osd / self.native
    }
}

/// The picture of one input's refined shape.
#[derive(Debug, Clone, PartialEq)]
pub struct Picture {
    /// The pictured level.
    pub level: u32,
    /// Its faces.
    pub faces: usize,
    /// The largest per-vertex deviation from OpenSubdiv, relative to the diagonal.
    pub max_deviation: f64,
    /// The SVG document.
    pub svg: String,
}

/// Everything the report says about one input.
#[derive(Debug, Clone, PartialEq)]
pub struct InputReport {
    /// The input's name.
    pub name: String,
    /// Its description.
    pub description: String,
    /// Base vertices.
    pub vertices: usize,
    /// Base faces.
    pub faces: usize,
    /// The default options (benchmarked and pictured).
    pub options: Options,
    /// What the option sets vary.
    pub varied: Vec<&'static str>,
    /// Every option set's comparisons.
    pub sets: Vec<SetResult>,
    /// Benchmarks per level.
    pub timings: Vec<Timing>,
    /// The refined shape.
    pub picture: Picture,
}

impl InputReport {
    /// Checks made.
    pub fn cases(&self) -> usize {
        self.sets.iter().map(SetResult::cases).sum()
    }

    /// Checks passed.
    pub fn agreeing(&self) -> usize {
        self.sets.iter().map(SetResult::agreeing).sum()
    }

    /// Whether every check passed.
    pub fn conforms(&self) -> bool {
        self.agreeing() == self.cases()
    }

    /// The largest deviation of any check.
    pub fn worst_deviation(&self) -> f64 {
        self.sets
            .iter()
            .map(SetResult::worst_deviation)
            .fold(0.0, f64::max)
    }

    /// Vertices with the known limit-tangent difference, over all option sets.
    pub fn known_differences(&self) -> usize {
        self.sets
            .iter()
            .filter_map(|s| s.limit.as_ref())
            .map(|l| l.known_difference_vertices)
            .sum()
    }

    /// The timing at the last level.
    pub fn last_timing(&self) -> Option<&Timing> {
        self.timings.last()
    }
}

/// A whole report.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// The date (UTC, YYYY-MM-DD).
    pub date: String,
    /// The machine ([`bench::machine_description`]).
    pub machine: String,
    /// OpenSubdiv's version.
    pub osd_version: String,
    /// subdiv's version.
    pub subdiv_version: String,
    /// What was run.
    pub settings: Settings,
    /// One entry per input.
    pub inputs: Vec<InputReport>,
    /// How long the run took, seconds.
    pub seconds: f64,
}

/// Today's date (UTC) as YYYY-MM-DD.
pub fn today() -> String {
    let days = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs() / 86_400) as i64;
    // Civil-from-days (Howard Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!("{y:04}-{m:02}-{d:02}")
}

/// How many progress steps [`run`] reports for these inputs.
pub fn steps(inputs: &[Input], settings: &Settings) -> u64 {
    inputs
        .iter()
        .map(|i| {
            option_sets(i, settings.quick).len() as u64 + settings.timed_levels().count() as u64
        })
        .sum()
}

/// Runs the report: every comparison, benchmark and picture. `progress` is
/// called once per step (see [`steps`]) with a description of the step.
///
/// Invalid meshes and levels too deep for an input are errors before any
/// work; an engine failing on an option set is recorded as a failing case.
pub fn run(
    inputs: &[Input],
    settings: &Settings,
    mut progress: impl FnMut(&str),
) -> Result<Report> {
    let start = Instant::now();
    if settings.first_level > settings.last_level {
        return Err(Error::InvalidArgument(format!(
            "the level range {}..{} is empty",
            settings.first_level, settings.last_level
        )));
    }
    if settings.tolerance.is_nan() || settings.tolerance < 0.0 {
        return Err(Error::InvalidArgument(format!(
            "the tolerance {} is not a non-negative number",
            settings.tolerance
        )));
    }
    let mut plans = Vec::with_capacity(inputs.len());
    for input in inputs {
        input
            .mesh
            .validate()
            .map_err(|e| Error::InvalidArgument(format!("{}: invalid mesh: {e}", input.name)))?;
        let sets = option_sets(input, settings.quick);
        for o in &sets {
            check_level(&input.mesh, o, settings.last_level)?;
        }
        plans.push(sets);
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .map_err(|e| Error::InvalidArgument(format!("cannot start a thread pool: {e}")))?;
    let mut reports = Vec::with_capacity(inputs.len());
    for (input, sets) in inputs.iter().zip(plans) {
        reports.push(run_input(input, sets, settings, &pool, &mut progress)?);
    }
    Ok(Report {
        date: today(),
        machine: bench::machine_description(),
        osd_version: osd::version(),
        subdiv_version: env!("CARGO_PKG_VERSION").to_string(),
        settings: *settings,
        inputs: reports,
        seconds: start.elapsed().as_secs_f64(),
    })
}

fn run_input(
    input: &Input,
    sets: Vec<Options>,
    settings: &Settings,
    pool: &rayon::ThreadPool,
    progress: &mut impl FnMut(&str),
) -> Result<InputReport> {
    let t = traits(&input.mesh);
    let mut varied = Vec::new();
    let mut schemes: Vec<Scheme> = sets.iter().map(|o| o.scheme).collect();
    schemes.dedup();
    if schemes.len() > 1 {
        varied.push("scheme");
    }
    for (yes, what) in [
        (t.boundary, "boundary"),
        (t.creases, "creasing"),
        (t.triangles, "triangles"),
        (t.uvs, "face-varying"),
    ] {
        if yes {
            varied.push(what);
        }
    }
    let mut results = Vec::with_capacity(sets.len());
    let mut pictured: Option<(Refinement, Refinement)> = None;
    for (k, options) in sets.iter().enumerate() {
        progress(&format!(
            "{}: {} ({}/{})",
            input.name,
            options_label(options),
            k + 1,
            sets.len()
        ));
        let (result, pair) = compare_set(&input.mesh, options, settings);
        if *options == input.options {
            pictured = pair;
        }
        results.push(result);
    }
    let mut timings = Vec::new();
    for level in settings.timed_levels() {
        progress(&format!("{}: timing level {level}", input.name));
        timings
            .push(pool.install(|| time_level(&input.mesh, &input.options, level, settings.quick))?);
    }
    let picture = match &pictured {
        Some((native, osd)) => picture(input, native, osd, settings.tolerance),
        None => Picture {
            level: 0,
            faces: 0,
            max_deviation: f64::INFINITY,
            svg: String::new(),
        },
    };
    Ok(InputReport {
        name: input.name.clone(),
        description: input.description.clone(),
        vertices: input.mesh.vertex_count(),
        faces: input.mesh.face_count(),
        options: input.options,
        varied,
        sets: results,
        timings,
        picture,
    })
}

/// Compares one option set; returns the refinements too (for the picture).
fn compare_set(
    mesh: &Mesh,
    options: &Options,
    settings: &Settings,
) -> (SetResult, Option<(Refinement, Refinement)>) {
    let mut result = SetResult {
        options: *options,
        levels: Vec::new(),
        limit: None,
        error: None,
    };
    let uniform = UniformOptions::new(settings.last_level);
    let both = |limit: bool| -> std::result::Result<(Refinement, Refinement), String> {
        let n = refiner::refine_with(mesh, options, uniform, Precision::F64, limit)
            .map_err(|e| format!("native engine{}: {e}", if limit { " (limit)" } else { "" }))?;
        let o = osd::refine_with(mesh, options, uniform, Precision::F64, limit)
            .map_err(|e| format!("osd engine{}: {e}", if limit { " (limit)" } else { "" }))?;
        Ok((n, o))
    };
    let pair = match both(false) {
        Ok(pair) => pair,
        Err(e) => {
            result.error = Some(e);
            return (result, None);
        }
    };
    let has_uvs = !mesh.fvar_channels.is_empty();
    for c in compare(&pair.0, &pair.1) {
        if c.level < settings.first_level {
            continue;
        }
        result.levels.push(LevelResult {
            level: c.level,
            vertices: c.counts[1][0],
            faces: c.counts[1][2],
            topology_equal: c.topology_equal(),
            position_deviation: c.relative_position_deviation,
            fvar_deviation: has_uvs.then_some(c.max_fvar_deviation),
            agrees: c.agrees(settings.tolerance),
        });
    }
    match both(true) {
        Ok((n, o)) => {
            result.limit = compare_limit(&n, &o, settings.tolerance);
            if result.limit.is_none() {
                result.error = Some("an engine returned no limit".into());
            }
        }
        Err(e) => result.error = Some(e),
    }
    (result, Some(pair))
}

/// Vertices of a level that lie on an edge shared by more than two faces.
fn nonmanifold_vertices(level: &LevelTopology) -> Vec<bool> {
    let mut out = vec![false; level.vertex_count];
    for ((a, b), n) in edge_face_counts(level.faces()) {
        if n > 2 {
            for v in [a, b] {
                if let Some(x) = out.get_mut(v as usize) {
                    *x = true;
                }
            }
        }
    }
    out
}

fn compare_limit(n: &Refinement, o: &Refinement, tolerance: f64) -> Option<LimitResult> {
    let (ln, lo) = (n.limit.as_ref()?, o.limit.as_ref()?);
    let diag = bbox_diagonal(&lo.positions).max(f64::MIN_POSITIVE);
    let dist = |a: DVec3, b: DVec3| {
        let d = (a - b).length() / diag;
        if d.is_nan() { f64::INFINITY } else { d }
    };
    let mut position = if ln.positions.len() == lo.positions.len() {
        0.0f64
    } else {
        f64::INFINITY
    };
    for (a, b) in ln.positions.iter().zip(&lo.positions) {
        position = position.max(dist(*a, *b));
    }
    let nonmanifold = nonmanifold_vertices(o.last_level());
    let mut tangent = if ln.du.len() == lo.du.len() && ln.dv.len() == lo.dv.len() {
        0.0f64
    } else {
        f64::INFINITY
    };
    let mut known = 0;
    for (i, ((a, b), (c, d))) in ln
        .du
        .iter()
        .zip(&lo.du)
        .zip(ln.dv.iter().zip(&lo.dv))
        .enumerate()
    {
        let dev = dist(*a, *b).max(dist(*c, *d));
        if nonmanifold.get(i).copied().unwrap_or(false) {
            known += usize::from(dev > tolerance);
        } else {
            tangent = tangent.max(dev);
        }
    }
    let fvar = (!lo.fvar_values.is_empty() || !ln.fvar_values.is_empty()).then(|| {
        let mut worst = if ln.fvar_values.len() == lo.fvar_values.len() {
            0.0f64
        } else {
            f64::INFINITY
        };
        for (x, y) in ln.fvar_values.iter().zip(&lo.fvar_values) {
            if x.len() != y.len() {
                worst = f64::INFINITY;
            }
            for (p, q) in x.iter().zip(y) {
                let d = (p - q).abs();
                worst = worst.max(if d.is_nan() { f64::INFINITY } else { d });
            }
        }
        worst
    });
    let agrees =
        position <= tolerance && tangent <= tolerance && fvar.is_none_or(|f| f <= tolerance);
    Some(LimitResult {
        level: o.uniform.level,
        position_deviation: position,
        tangent_deviation: tangent,
        fvar_deviation: fvar,
        known_difference_vertices: known,
        agrees,
    })
}

fn time_level(mesh: &Mesh, options: &Options, level: u32, quick: bool) -> Result<Timing> {
    let base: Vec<f64> = mesh.flat_positions();
    let uniform = UniformOptions::new(level);
    let native = || -> Result<usize> {
        let mut r = refiner::Refiner::new(mesh, options)?;
        r.refine_uniform(uniform)?;
        let p = r.interpolate_all(3, &base)?;
        Ok(black_box(p).last().map_or(0, |l| l.len()))
    };
    let opensubdiv = || -> Result<usize> {
        let mut r = osd::Refiner::new(mesh, options)?;
        r.refine_uniform(uniform)?;
        let p = r.interpolate_all(3, &base)?;
        Ok(black_box(p).last().map_or(0, Vec::len))
    };
    // One run of each: errors surface here, and it sizes the repetitions.
    let t0 = Instant::now();
    native()?;
    opensubdiv()?;
    let once = t0.elapsed().as_secs_f64().max(1e-7);
    let (budget, min_reps) = if quick { (0.02, 3) } else { (0.25, 7) };
    let reps = ((budget / once) as usize).clamp(min_reps, 2001) | 1;
    // Warm up (caches, allocator, clock) for a tenth of the budget.
    for _ in 0..reps / 10 {
        let _ = black_box(native());
        let _ = black_box(opensubdiv());
    }
    let (tn, to) = bench::interleaved(
        reps,
        || {
            let _ = black_box(native());
        },
        || {
            let _ = black_box(opensubdiv());
        },
    );
    let faces = osd::refine(mesh, options, uniform)
        .map(|r| r.last_level().face_count())
        .unwrap_or(0);
    Ok(Timing {
        level,
        faces,
        native: tn,
        osd: to,
        reps,
    })
}

// ---------------------------------------------------------------------------
// Formatting
// ---------------------------------------------------------------------------

/// A short label of all five options.
pub fn options_label(o: &Options) -> String {
    format!(
        "{}, boundary {}, creasing {}, triangles {}, fvar {}",
        o.scheme.name(),
        o.boundary.name(),
        o.creasing.name(),
        o.triangles.name(),
        o.fvar.name()
    )
}

/// A deviation for tables: `0`, `∞` or `3.1e-16`.
pub fn format_deviation(d: f64) -> String {
    if d == 0.0 {
        "0".into()
    } else if !d.is_finite() {
        "∞".into()
    } else {
        format!("{d:.1e}")
    }
}

/// A deviation for summaries: zero reads `0 (bit-identical)`.
fn format_worst(d: f64) -> String {
    if d == 0.0 {
        "0 (bit-identical)".into()
    } else {
        format_deviation(d)
    }
}

/// Seconds as milliseconds with 3 significant digits or so.
pub fn format_ms(seconds: f64) -> String {
    let ms = seconds * 1e3;
    if ms < 0.01 {
        format!("{ms:.4}")
    } else if ms < 1.0 {
        format!("{ms:.3}")
    } else if ms < 100.0 {
        format!("{ms:.2}")
    } else {
        format!("{ms:.0}")
    }
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A file-name-safe version of `name`, prefixed with its index.
fn slug(index: usize, name: &str) -> String {
    let mut s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '-'
            }
        })
        .collect();
    s.truncate(40);
    format!("{:02}-{}", index + 1, s.trim_matches('-'))
}

const SVG_NS: &str = " xmlns=\"http://www.w3.org/2000/svg\"";

/// An SVG document as an inline HTML element (HTML needs no namespace).
fn inline_svg(svg: &str) -> String {
    svg.replacen(SVG_NS, "", 1)
}

const NATIVE_COLOR: &str = "#1f77b4";
const OSD_COLOR: &str = "#d62728";
const FVAR_COLOR: &str = "#2ca02c";
const LIMIT_COLOR: &str = "#ff7f0e";

/// A plot with levels along x and a log scale along y.
struct LogPlot {
    width: f64,
    left: f64,
    right: f64,
    top: f64,
    bottom: f64,
    lo: i32,
    hi: i32,
    levels: Vec<u32>,
}

impl LogPlot {
    fn x(&self, level: u32) -> f64 {
        let n = self.levels.len();
        let i = self.levels.iter().position(|&l| l == level).unwrap_or(0);
        if n <= 1 {
            (self.left + self.width - self.right) / 2.0
        } else {
            let pad = 24.0;
            self.left
                + pad
                + (self.width - self.right - self.left - 2.0 * pad) * i as f64 / (n - 1) as f64
        }
    }

    fn y(&self, v: f64) -> f64 {
        let t = (v.log10().clamp(f64::from(self.lo), f64::from(self.hi)) - f64::from(self.lo))
            / f64::from(self.hi - self.lo);
        self.bottom - t * (self.bottom - self.top)
    }

    /// Frame, decade grid lines (labelled by `label`) and level ticks.
    fn axes(&self, out: &mut String, every: i32, label: impl Fn(i32) -> String) {
        let (l, r) = (self.left, self.width - self.right);
        for d in self.lo..=self.hi {
            let y = self.y(10f64.powi(d));
            let _ = write!(
                out,
                r##"<line x1="{l}" y1="{y:.1}" x2="{r}" y2="{y:.1}" stroke="#e4e4e4"/>"##
            );
            if (d - self.lo) % every == 0 || d == self.hi {
                let _ = write!(
                    out,
                    r##"<text x="{:.1}" y="{:.1}" text-anchor="end" font-size="10" fill="#333">{}</text>"##,
                    l - 5.0,
                    y + 3.5,
                    label(d)
                );
            }
        }
        let _ = write!(
            out,
            r##"<rect x="{l}" y="{}" width="{}" height="{}" fill="none" stroke="#888"/>"##,
            self.top,
            r - l,
            self.bottom - self.top
        );
    }

    fn level_labels(&self, out: &mut String, y: f64) {
        for &lv in &self.levels {
            let _ = write!(
                out,
                r##"<text x="{:.1}" y="{y:.1}" text-anchor="middle" font-size="11">{lv}</text>"##,
                self.x(lv)
            );
        }
        let _ = write!(
            out,
            r##"<text x="{:.1}" y="{:.1}" text-anchor="middle" font-size="11" fill="#555">level</text>"##,
            (self.left + self.width - self.right) / 2.0,
            y + 15.0
        );
    }
}

fn svg_open(out: &mut String, width: f64, height: f64, title: &str) {
    let _ = write!(
        out,
        r##"<svg{SVG_NS} width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="sans-serif" role="img"><title>{}</title><rect width="{width:.0}" height="{height:.0}" fill="white"/><text x="{:.1}" y="18" text-anchor="middle" font-size="13" font-weight="bold">{}</text>"##,
        escape(title),
        width / 2.0,
        escape(title)
    );
}

fn marker(out: &mut String, shape: &str, x: f64, y: f64, color: &str) {
    match shape {
        "square" => {
            let _ = write!(
                out,
                r##"<rect x="{:.1}" y="{:.1}" width="7" height="7" fill="{color}"/>"##,
                x - 3.5,
                y - 3.5
            );
        }
        "diamond" => {
            let _ = write!(
                out,
                r##"<polygon points="{:.1},{:.1} {:.1},{:.1} {:.1},{:.1} {:.1},{:.1}" fill="{color}"/>"##,
                x,
                y - 5.0,
                x + 5.0,
                y,
                x,
                y + 5.0,
                x - 5.0,
                y
            );
        }
        _ => {
            let _ = write!(
                out,
                r##"<circle cx="{x:.1}" cy="{y:.1}" r="3.8" fill="{color}"/>"##
            );
        }
    }
}

fn legend(out: &mut String, y: f64, x0: f64, items: &[(&str, &str, &str, bool)]) {
    let mut x = x0;
    for &(label, color, shape, dashed) in items {
        let dash = if dashed {
            r#" stroke-dasharray="5,3""#
        } else {
            ""
        };
        let _ = write!(
            out,
            r##"<line x1="{x:.1}" y1="{y:.1}" x2="{:.1}" y2="{y:.1}" stroke="{color}" stroke-width="2"{dash}/>"##,
            x + 22.0
        );
        marker(out, shape, x + 11.0, y, color);
        let _ = write!(
            out,
            r##"<text x="{:.1}" y="{:.1}" font-size="11">{}</text>"##,
            x + 27.0,
            y + 4.0,
            escape(label)
        );
        x += 36.0 + 6.2 * label.chars().count() as f64;
    }
}

/// A plotted series: label, colour, marker shape, (level, value) points.
type Series = (&'static str, &'static str, &'static str, Vec<(u32, f64)>);

/// The deviation plot of one input: the worst deviation over its option sets
/// per level (positions, face-varying values) and of the limit, on a log
/// scale, exact zeros on their own row.
fn deviation_svg(r: &InputReport, s: &Settings) -> String {
    let levels: Vec<u32> = (s.first_level..=s.last_level).collect();
    let mut series: Vec<Series> = Vec::new();
    let ok_sets: Vec<&SetResult> = r.sets.iter().filter(|x| x.error.is_none()).collect();
    let per_level = |f: &dyn Fn(&LevelResult) -> Option<f64>| -> Vec<(u32, f64)> {
        levels
            .iter()
            .filter_map(|&l| {
                let vals: Vec<f64> = ok_sets
                    .iter()
                    .filter_map(|x| x.levels.iter().find(|c| c.level == l))
                    .filter_map(f)
                    .collect();
                (!vals.is_empty()).then(|| (l, vals.into_iter().fold(0.0, f64::max)))
            })
            .collect()
    };
    series.push((
        "positions",
        NATIVE_COLOR,
        "circle",
        per_level(&|c| Some(c.position_deviation)),
    ));
    let fv = per_level(&|c| c.fvar_deviation);
    if !fv.is_empty() {
        series.push(("face-varying", FVAR_COLOR, "square", fv));
    }
    let limits: Vec<f64> = ok_sets
        .iter()
        .filter_map(|x| x.limit.as_ref())
        .map(LimitResult::deviation)
        .collect();
    if !limits.is_empty() {
        series.push((
            "limit",
            LIMIT_COLOR,
            "diamond",
            vec![(s.last_level, limits.into_iter().fold(0.0, f64::max))],
        ));
    }
    let nonzero: Vec<f64> = series
        .iter()
        .flat_map(|x| x.3.iter().map(|p| p.1))
        .filter(|&v| v > 0.0 && v.is_finite())
        .collect();
    let max_dec = nonzero
        .iter()
        .map(|v| v.log10().ceil() as i32)
        .max()
        .unwrap_or(-6);
    let min_dec = nonzero
        .iter()
        .map(|v| v.log10().floor() as i32)
        .min()
        .unwrap_or(-16);
    let hi = (max_dec.max((s.tolerance.max(1e-300)).log10().ceil() as i32) + 1).min(3);
    let lo = min_dec.clamp(-40, -17);
    let (width, height) = (400.0, 280.0);
    let plot = LogPlot {
        width,
        left: 104.0,
        right: 14.0,
        top: 30.0,
        bottom: 178.0,
        lo,
        hi,
        levels: levels.clone(),
    };
    let zero_y = 200.0;
    let mut out = String::new();
    svg_open(
        &mut out,
        width,
        height,
        "deviation from OpenSubdiv (log scale)",
    );
    plot.axes(&mut out, 3, |d| format!("1e{d}"));
    // The zero row, below a break.
    let (l, rr) = (plot.left, width - plot.right);
    let _ = write!(
        out,
        r##"<rect x="{l}" y="{:.1}" width="{:.1}" height="20" fill="#eef6ee" stroke="#888"/><text x="{:.1}" y="{:.1}" text-anchor="end" font-size="10" fill="#333">0 (bit-identical)</text>"##,
        zero_y - 10.0,
        rr - l,
        l - 5.0,
        zero_y + 3.5
    );
    if s.tolerance > 0.0 {
        let ty = plot.y(s.tolerance);
        let _ = write!(
            out,
            r##"<line x1="{l}" y1="{ty:.1}" x2="{rr}" y2="{ty:.1}" stroke="{OSD_COLOR}" stroke-dasharray="6,4"/><text x="{:.1}" y="{:.1}" text-anchor="end" font-size="10" fill="{OSD_COLOR}">tolerance {:.0e}</text>"##,
            rr - 4.0,
            ty - 4.0,
            s.tolerance
        );
    }
    let k = series.len() as f64;
    for (i, (_, color, shape, pts)) in series.iter().enumerate() {
        let dx = (i as f64 - (k - 1.0) / 2.0) * 7.0;
        let pos = |&(lv, v): &(u32, f64)| {
            let y = if v == 0.0 { zero_y } else { plot.y(v) };
            (plot.x(lv) + dx, y)
        };
        if pts.len() > 1 {
            let line: Vec<String> = pts
                .iter()
                .map(pos)
                .map(|(x, y)| format!("{x:.1},{y:.1}"))
                .collect();
            let _ = write!(
                out,
                r##"<polyline points="{}" fill="none" stroke="{color}" stroke-width="1.5"/>"##,
                line.join(" ")
            );
        }
        for p in pts {
            let (x, y) = pos(p);
            marker(&mut out, shape, x, y, color);
        }
    }
    plot.level_labels(&mut out, 226.0);
    legend(
        &mut out,
        height - 18.0,
        plot.left - 60.0,
        &series
            .iter()
            .map(|(n, c, sh, _)| (*n, *c, *sh, false))
            .collect::<Vec<_>>(),
    );
    out.push_str("</svg>\n");
    out
}

/// The time plot of one input: native against OpenSubdiv per level, log scale.
fn time_svg(r: &InputReport) -> String {
    let (width, height) = (400.0, 280.0);
    let levels: Vec<u32> = r.timings.iter().map(|t| t.level).collect();
    let ms: Vec<f64> = r
        .timings
        .iter()
        .flat_map(|t| [t.native * 1e3, t.osd * 1e3])
        .filter(|v| *v > 0.0)
        .collect();
    let lo = ms
        .iter()
        .map(|v| v.log10().floor() as i32)
        .min()
        .unwrap_or(-2);
    let hi = ms
        .iter()
        .map(|v| v.log10().ceil() as i32)
        .max()
        .unwrap_or(0)
        .max(lo + 1);
    let plot = LogPlot {
        width,
        left: 70.0,
        right: 14.0,
        top: 30.0,
        bottom: 190.0,
        lo,
        hi,
        levels,
    };
    let mut out = String::new();
    svg_open(&mut out, width, height, "refine + positions: median time");
    plot.axes(&mut out, 1, |d| {
        let v = 10f64.powi(d);
        if d < 0 {
            format!("{v:.*} ms", (-d) as usize)
        } else {
            format!("{v:.0} ms")
        }
    });
    for (who, color, shape, dashed) in [
        ("native", NATIVE_COLOR, "circle", false),
        ("osd", OSD_COLOR, "square", true),
    ] {
        let pts: Vec<(f64, f64)> = r
            .timings
            .iter()
            .map(|t| {
                let v = if who == "native" { t.native } else { t.osd };
                (plot.x(t.level), plot.y(v * 1e3))
            })
            .collect();
        let dash = if dashed {
            r#" stroke-dasharray="6,4""#
        } else {
            ""
        };
        let line: Vec<String> = pts.iter().map(|(x, y)| format!("{x:.1},{y:.1}")).collect();
        let _ = write!(
            out,
            r##"<polyline points="{}" fill="none" stroke="{color}" stroke-width="2"{dash}/>"##,
            line.join(" ")
        );
        for (x, y) in pts {
            marker(&mut out, shape, x, y, color);
        }
    }
    plot.level_labels(&mut out, 206.0);
    // Speed-ups under the levels.
    let _ = write!(
        out,
        r##"<text x="{:.1}" y="240" text-anchor="end" font-size="10" fill="#555">speed-up</text>"##,
        plot.left - 5.0
    );
    for t in &r.timings {
        let _ = write!(
            out,
            r##"<text x="{:.1}" y="240" text-anchor="middle" font-size="10" fill="#555">{:.2}×</text>"##,
            plot.x(t.level),
            t.speedup()
        );
    }
    legend(
        &mut out,
        height - 16.0,
        plot.left - 40.0,
        &[
            ("native (1 thread)", NATIVE_COLOR, "circle", false),
            ("OpenSubdiv", OSD_COLOR, "square", true),
        ],
    );
    out.push_str("</svg>\n");
    out
}

/// The colour of a relative deviation: blue for exactly 0, yellow-green to
/// orange for 1e-16..tolerance (log scale), red above the tolerance.
fn deviation_color(d: f64, tolerance: f64) -> DVec3 {
    const EXACT: DVec3 = DVec3::new(0.56, 0.72, 0.95);
    const LOW: DVec3 = DVec3::new(0.55, 0.82, 0.36);
    const MID: DVec3 = DVec3::new(0.99, 0.85, 0.30);
    const HIGH: DVec3 = DVec3::new(0.96, 0.45, 0.18);
    const BAD: DVec3 = DVec3::new(0.80, 0.08, 0.12);
    if d == 0.0 {
        return EXACT;
    }
    if d > tolerance || !d.is_finite() {
        return BAD;
    }
    let t = scale_position(d, tolerance);
    if t < 0.5 {
        LOW.lerp(MID, t * 2.0)
    } else {
        MID.lerp(HIGH, t * 2.0 - 1.0)
    }
}

/// Where `d` sits on the colour bar: 0 at 1e-16, 1 at the tolerance.
fn scale_position(d: f64, tolerance: f64) -> f64 {
    let top = tolerance.max(1e-15).log10();
    ((d.log10() + 16.0) / (top + 16.0)).clamp(0.0, 1.0)
}

fn hex(c: DVec3) -> String {
    let c = (c.clamp(DVec3::ZERO, DVec3::ONE) * 255.0).round();
    format!("#{:02x}{:02x}{:02x}", c.x as u8, c.y as u8, c.z as u8)
}

/// The native refined shape at the deepest level with at most
/// [`MAX_PICTURE_FACES`] faces, shaded, each face coloured by the largest
/// deviation of its vertices from OpenSubdiv.
fn picture(input: &Input, native: &Refinement, osd: &Refinement, tolerance: f64) -> Picture {
    let level = (0..native.levels.len())
        .rev()
        .find(|&l| native.levels[l].face_count() <= MAX_PICTURE_FACES)
        .unwrap_or(0);
    let topo = &native.levels[level];
    let pos = &native.positions[level];
    let empty = Vec::new();
    let reference = osd.positions.get(level).unwrap_or(&empty);
    let diag = bbox_diagonal(reference).max(f64::MIN_POSITIVE);
    let dev: Vec<f64> = (0..pos.len())
        .map(|i| match reference.get(i) {
            Some(q) => {
                let d = (pos[i] - *q).length() / diag;
                if d.is_nan() { f64::INFINITY } else { d }
            }
            None => f64::INFINITY,
        })
        .collect();
    let max_dev = if pos.len() == reference.len() {
        dev.iter().copied().fold(0.0, f64::max)
    } else {
        f64::INFINITY
    };
    let worst_vertex = dev
        .iter()
        .enumerate()
        .filter(|(_, d)| **d > 0.0)
        .max_by(|a, b| a.1.total_cmp(b.1))
        .map(|(i, _)| i);
    let projection = Projection::orbit(-58.0, 28.0);
    let (width, max_h, top) = (400.0, 290.0, 42.0);
    // Faces to draw: not holes; on a closed manifold level, only those facing the viewer.
    let counts = edge_face_counts(topo.faces());
    let closed = counts.values().all(|&n| n == 2) && !topo.face_holes.iter().any(|&h| h);
    let mut faces: Vec<(f64, usize, DVec3)> = Vec::new();
    let mut lo = DVec2::splat(f64::INFINITY);
    let mut hi = DVec2::splat(f64::NEG_INFINITY);
    for (f, verts) in topo.faces().enumerate() {
        if topo.face_holes.get(f).copied().unwrap_or(false) {
            continue;
        }
        let p = |v: u32| pos.get(v as usize).copied().unwrap_or_default();
        let mut n = DVec3::ZERO;
        for (i, &a) in verts.iter().enumerate() {
            let (a, b) = (p(a), p(verts[(i + 1) % verts.len()]));
            n += DVec3::new(
                (a.y - b.y) * (a.z + b.z),
                (a.z - b.z) * (a.x + b.x),
                (a.x - b.x) * (a.y + b.y),
            );
        }
        let n = n.normalize_or_zero();
        for &v in verts {
            let q = projection.project(p(v));
            if q.is_finite() {
                lo = lo.min(q);
                hi = hi.max(q);
            }
        }
        if closed && n.dot(projection.toward_viewer) < -1e-9 {
            continue;
        }
        let depth = verts.iter().map(|&v| projection.depth(p(v))).sum::<f64>() / verts.len() as f64;
        faces.push((depth, f, n));
    }
    faces.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    if lo.x > hi.x {
        (lo, hi) = (DVec2::ZERO, DVec2::ZERO);
    }
    let extent = (hi - lo).max(DVec2::splat(1e-12));
    let scale = ((width - 30.0) / extent.x).min(max_h / extent.y);
    let box_h = (extent.y * scale).max(120.0);
    let centre = (lo + hi) * 0.5;
    let px = |p: DVec3| {
        let q = (projection.project(p) - centre) * scale;
        DVec2::new(width / 2.0 + q.x, top + box_h / 2.0 - q.y)
    };
    let legend_top = top + box_h + 14.0;
    let height = legend_top + 56.0;
    let title = format!("native level {level}, coloured by deviation");
    let mut out = String::new();
    svg_open(&mut out, width, height, &title);
    let _ = write!(
        out,
        r##"<text x="{:.1}" y="34" text-anchor="middle" font-size="10" fill="#555">{} faces, {} vertices; {}</text>"##,
        width / 2.0,
        topo.face_count(),
        topo.vertex_count,
        escape(&input.name)
    );
    let to_light =
        (projection.up * 0.6 - projection.right * 0.4 + projection.toward_viewer * 0.7).normalize();
    let stroke_w = if faces.len() > 3000 { 0.25 } else { 0.45 };
    let _ = write!(
        out,
        r##"<g stroke-width="{stroke_w}" stroke-linejoin="round">"##
    );
    for (_, f, n) in &faces {
        let verts = topo.face(*f);
        let d = verts
            .iter()
            .map(|&v| dev.get(v as usize).copied().unwrap_or(f64::INFINITY))
            .fold(0.0, f64::max);
        let facing = n.dot(projection.toward_viewer) >= 0.0;
        let light = n.dot(to_light).abs().mul_add(0.55, 0.45);
        let base = deviation_color(d, tolerance) * if facing { light } else { 0.6 * light };
        let mut pts = String::new();
        for (i, &v) in verts.iter().enumerate() {
            let q = px(pos.get(v as usize).copied().unwrap_or_default());
            if i > 0 {
                pts.push(' ');
            }
            let _ = write!(pts, "{:.1},{:.1}", q.x, q.y);
        }
        let _ = write!(
            out,
            r##"<polygon points="{pts}" fill="{}" stroke="{}"/>"##,
            hex(base),
            hex(base * 0.62)
        );
    }
    out.push_str("</g>");
    // The legend: the exact colour, the colour bar, the failure colour.
    let y = legend_top;
    let gid = format!("devscale-{}", slug(0, &input.name));
    let bar_x = 150.0;
    let bar_w = 170.0;
    let _ = write!(
        out,
        r##"<defs><linearGradient id="{gid}" x1="0" x2="1" y1="0" y2="0"><stop offset="0" stop-color="{}"/><stop offset="0.5" stop-color="{}"/><stop offset="1" stop-color="{}"/></linearGradient></defs>"##,
        hex(deviation_color(1e-16, tolerance)),
        hex(deviation_color(
            10f64.powf(-8.0 + tolerance.max(1e-15).log10() / 2.0),
            tolerance
        )),
        hex(deviation_color(tolerance, tolerance)),
    );
    let _ = write!(
        out,
        r##"<rect x="12" y="{y:.1}" width="16" height="12" fill="{}" stroke="#555"/><text x="32" y="{:.1}" font-size="10">0 (bit-identical)</text>"##,
        hex(deviation_color(0.0, tolerance)),
        y + 10.0
    );
    let _ = write!(
        out,
        r##"<rect x="{bar_x}" y="{y:.1}" width="{bar_w}" height="12" fill="url(#{gid})" stroke="#555"/><text x="{bar_x}" y="{:.1}" font-size="9" text-anchor="middle">1e-16</text><text x="{:.1}" y="{:.1}" font-size="9" text-anchor="middle">{:.0e}</text>"##,
        y + 23.0,
        bar_x + bar_w,
        y + 23.0,
        tolerance
    );
    let _ = write!(
        out,
        r##"<rect x="{:.1}" y="{y:.1}" width="16" height="12" fill="{}" stroke="#555"/><text x="{:.1}" y="{:.1}" font-size="10">&gt; tol.</text>"##,
        bar_x + bar_w + 10.0,
        hex(deviation_color(f64::INFINITY, tolerance)),
        bar_x + bar_w + 30.0,
        y + 10.0
    );
    let note = if max_dev == 0.0 {
        format!(
            "all {} vertices: 0 (bit-identical to OpenSubdiv)",
            pos.len()
        )
    } else if let Some(v) = worst_vertex {
        format!(
            "largest deviation {} (relative to the diagonal) at vertex {v}",
            format_deviation(max_dev)
        )
    } else {
        format!("largest deviation {}", format_deviation(max_dev))
    };
    let _ = write!(
        out,
        r##"<text x="{:.1}" y="{:.1}" font-size="11" text-anchor="middle">{}</text>"##,
        width / 2.0,
        y + 44.0,
        escape(&note)
    );
    if max_dev == 0.0 {
        // Mark where on the bar zero would be: nowhere; say so.
        let _ = write!(
            out,
            r##"<text x="{:.1}" y="{:.1}" font-size="9" fill="#555" text-anchor="middle">(colour bar unused)</text>"##,
            bar_x + bar_w / 2.0,
            y + 23.0
        );
    } else if max_dev.is_finite() && max_dev <= tolerance {
        let mx = bar_x + bar_w * scale_position(max_dev, tolerance);
        let _ = write!(
            out,
            r##"<path d="M{mx:.1} {:.1} l-4 -6 h8 z" fill="#000"/>"##,
            y - 1.0
        );
    }
    out.push_str("</svg>\n");
    Picture {
        level: level as u32,
        faces: topo.face_count(),
        max_deviation: max_dev,
        svg: out,
    }
}

impl Report {
    /// Checks made.
    pub fn cases(&self) -> usize {
        self.inputs.iter().map(InputReport::cases).sum()
    }

    /// Checks passed.
    pub fn agreeing(&self) -> usize {
        self.inputs.iter().map(InputReport::agreeing).sum()
    }

    /// Whether every check of every input passed.
    pub fn conforms(&self) -> bool {
        self.inputs.iter().all(InputReport::conforms)
    }

    /// Checks whose every deviation is exactly zero.
    pub fn bit_identical(&self) -> usize {
        self.inputs
            .iter()
            .flat_map(|i| &i.sets)
            .map(|s| {
                s.levels
                    .iter()
                    .filter(|l| l.topology_equal && l.deviation() == 0.0)
                    .count()
                    + usize::from(s.limit.as_ref().is_some_and(|l| l.deviation() == 0.0))
            })
            .sum()
    }

    /// The conformance verdict, one sentence.
    pub fn verdict(&self) -> String {
        let (ok, total) = (self.agreeing(), self.cases());
        let known: usize = self.inputs.iter().map(InputReport::known_differences).sum();
        let known = if known > 0 {
            format!(
                " Known OpenSubdiv difference (limit tangents at non-manifold vertices, docs/CONFORMANCE.md): {known} vertex tangents, not counted."
            )
        } else {
            String::new()
        };
        if self.conforms() {
            format!(
                "CONFORMS: all {total} checks agree within {:.0e} of the bounding-box diagonal; {} of them bit-identical.{known}",
                self.settings.tolerance,
                self.bit_identical()
            )
        } else {
            let bad: Vec<&str> = self
                .inputs
                .iter()
                .filter(|i| !i.conforms())
                .map(|i| i.name.as_str())
                .collect();
            format!(
                "DIFFERS: {} of {total} checks fail (tolerance {:.0e} of the bounding-box diagonal) on {}.{known}",
                total - ok,
                self.settings.tolerance,
                bad.join(", ")
            )
        }
    }

    fn levels_label(&self) -> String {
        let s = &self.settings;
        if s.first_level == s.last_level {
            format!("level {}", s.first_level)
        } else {
            format!("levels {}..{}", s.first_level, s.last_level)
        }
    }

    /// The summary table as aligned text (for the terminal).
    pub fn summary_text(&self) -> String {
        let last = self.settings.last_level;
        let mut rows: Vec<[String; 7]> = vec![[
            "input".into(),
            "option sets".into(),
            "agree/cases".into(),
            "worst deviation".into(),
            format!("native L{last} ms"),
            format!("OpenSubdiv L{last} ms"),
            "speed-up".into(),
        ]];
        for i in &self.inputs {
            let t = i.last_timing();
            rows.push([
                i.name.clone(),
                i.sets.len().to_string(),
                format!("{}/{}", i.agreeing(), i.cases()),
                format_worst(i.worst_deviation()),
                t.map_or("-".into(), |t| format_ms(t.native)),
                t.map_or("-".into(), |t| format_ms(t.osd)),
                t.map_or("-".into(), |t| format!("{:.2}x", t.speedup())),
            ]);
        }
        let widths: Vec<usize> = (0..7)
            .map(|c| rows.iter().map(|r| r[c].chars().count()).max().unwrap_or(0))
            .collect();
        let mut s = String::new();
        for r in &rows {
            for (c, cell) in r.iter().enumerate() {
                let pad = widths[c] - cell.chars().count();
                if c == 0 || c == 3 {
                    let _ = write!(s, "{cell}{}  ", " ".repeat(pad));
                } else {
                    let _ = write!(s, "{}{cell}  ", " ".repeat(pad));
                }
            }
            s = s.trim_end().to_string();
            s.push('\n');
        }
        let _ = writeln!(s, "{}", self.verdict());
        s
    }

    fn meta_lines(&self) -> Vec<(&'static str, String)> {
        let s = &self.settings;
        vec![
            ("Date", self.date.clone()),
            ("Machine", self.machine.clone()),
            ("OpenSubdiv", self.osd_version.clone()),
            ("subdiv", self.subdiv_version.clone()),
            (
                "Run",
                format!(
                    "{}, {} option sets ({}), tolerance {:.0e} of the bounding-box diagonal, f64; {:.1} s",
                    self.levels_label(),
                    self.inputs.iter().map(|i| i.sets.len()).sum::<usize>(),
                    if s.quick {
                        "quick: one option varied at a time"
                    } else {
                        "every combination of the options that apply"
                    },
                    s.tolerance,
                    self.seconds
                ),
            ),
        ]
    }

    /// The report as Markdown; figures are linked as `figures/*.svg`
    /// (written by [`Report::write`]).
    pub fn markdown(&self) -> String {
        let last = self.settings.last_level;
        let mut s = String::from("# subdiv: native engine against OpenSubdiv\n\n");
        for (k, v) in self.meta_lines() {
            let _ = writeln!(s, "- **{k}:** {v}");
        }
        let _ = writeln!(s, "\n**Verdict: {}**\n", self.verdict());
        s.push_str("## Summary\n\n");
        let _ = writeln!(
            s,
            "| input | faces | option sets | agree / cases | worst deviation | native L{last} ms | OpenSubdiv L{last} ms | speed-up |"
        );
        s.push_str("| --- | ---: | ---: | ---: | --- | ---: | ---: | ---: |\n");
        for i in &self.inputs {
            let t = i.last_timing();
            let _ = writeln!(
                s,
                "| [{}](#{}) | {} | {} | {}/{} | {} | {} | {} | {} |",
                i.name,
                markdown_anchor(&i.name),
                i.faces,
                i.sets.len(),
                i.agreeing(),
                i.cases(),
                format_worst(i.worst_deviation()),
                t.map_or("-".into(), |t| format_ms(t.native)),
                t.map_or("-".into(), |t| format_ms(t.osd)),
                t.map_or("-".into(), |t| format!("{:.2}x", t.speedup())),
            );
        }
        s.push_str(
            "\nDeviations are the largest distance between corresponding vertices (or face-varying values, or limit positions and tangents) of the two engines, relative to the bounding-box diagonal; 0 means bit-identical. Times are medians of interleaved runs of \"refine + positions\" (topology refinement and f64 positions of every level) with each input's default options, the native engine on one thread; speed-up is OpenSubdiv's time over the native time.\n\n",
        );
        for (idx, i) in self.inputs.iter().enumerate() {
            let sl = slug(idx, &i.name);
            let _ = writeln!(s, "## {}\n", i.name);
            let _ = writeln!(
                s,
                "{}. {} vertices, {} faces; default options: {}. Varied: {}.\n",
                sentence(&i.description),
                i.vertices,
                i.faces,
                options_label(&i.options),
                if i.varied.is_empty() {
                    "nothing".into()
                } else {
                    i.varied.join(", ")
                }
            );
            let _ = writeln!(
                s,
                "![deviation per level](figures/{sl}-deviation.svg) ![time per level](figures/{sl}-time.svg) ![refined shape](figures/{sl}-shape.svg)\n"
            );
            s.push_str(&sets_markdown(i, &self.settings));
            s.push_str("\n| level | faces | native ms | OpenSubdiv ms | speed-up | repetitions |\n| ---: | ---: | ---: | ---: | ---: | ---: |\n");
            for t in &i.timings {
                let _ = writeln!(
                    s,
                    "| {} | {} | {} | {} | {:.2}x | {} |",
                    t.level,
                    t.faces,
                    format_ms(t.native),
                    format_ms(t.osd),
                    t.speedup(),
                    t.reps
                );
            }
            s.push('\n');
        }
        s
    }

    /// The report as one self-contained HTML page: inline CSS, inline SVG,
    /// no scripts and no external resources.
    pub fn html(&self) -> String {
        let last = self.settings.last_level;
        let ok = self.conforms();
        let mut h = String::new();
        h.push_str("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>subdiv: native engine against OpenSubdiv</title>\n<style>\n");
        h.push_str(CSS);
        h.push_str("</style>\n</head>\n<body>\n<header>\n<h1>subdiv: native engine against OpenSubdiv</h1>\n<dl class=\"meta\">\n");
        for (k, v) in self.meta_lines() {
            let _ = writeln!(h, "<dt>{k}</dt><dd>{}</dd>", escape(&v));
        }
        h.push_str("</dl>\n");
        let _ = writeln!(
            h,
            "<p class=\"verdict {}\">{}</p>\n</header>",
            if ok { "pass" } else { "fail" },
            escape(&self.verdict())
        );
        h.push_str("<h2>Summary</h2>\n<table class=\"summary\">\n<thead><tr><th>input</th><th>faces</th><th>option sets</th><th>agree / cases</th><th>worst deviation</th>");
        let _ = write!(
            h,
            "<th>native L{last} ms</th><th>OpenSubdiv L{last} ms</th><th>speed-up</th></tr></thead>\n<tbody>\n"
        );
        for i in &self.inputs {
            let t = i.last_timing();
            let w = i.worst_deviation();
            let _ = writeln!(
                h,
                "<tr><td><a href=\"#{}\">{}</a></td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n {}\">{}/{}</td><td class=\"{}\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td></tr>",
                anchor(&i.name),
                escape(&i.name),
                i.faces,
                i.sets.len(),
                if i.conforms() { "pass" } else { "fail" },
                i.agreeing(),
                i.cases(),
                deviation_class(w, self.settings.tolerance),
                escape(&format_worst(w)),
                t.map_or("-".into(), |t| format_ms(t.native)),
                t.map_or("-".into(), |t| format_ms(t.osd)),
                t.map_or("-".into(), |t| format!("{:.2}×", t.speedup())),
            );
        }
        let total_t: (f64, f64) = self
            .inputs
            .iter()
            .filter_map(InputReport::last_timing)
            .fold((0.0, 0.0), |(a, b), t| (a + t.native, b + t.osd));
        let _ = writeln!(
            h,
            "</tbody>\n<tfoot><tr><td>all</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n {}\">{}/{}</td><td class=\"{}\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td></tr></tfoot>\n</table>",
            self.inputs.iter().map(|i| i.faces).sum::<usize>(),
            self.inputs.iter().map(|i| i.sets.len()).sum::<usize>(),
            if ok { "pass" } else { "fail" },
            self.agreeing(),
            self.cases(),
            deviation_class(
                self.inputs
                    .iter()
                    .map(InputReport::worst_deviation)
                    .fold(0.0, f64::max),
                self.settings.tolerance
            ),
            escape(&format_worst(
                self.inputs
                    .iter()
                    .map(InputReport::worst_deviation)
                    .fold(0.0, f64::max)
            )),
            format_ms(total_t.0),
            format_ms(total_t.1),
            if total_t.0 > 0.0 {
                format!("{:.2}×", total_t.1 / total_t.0)
            } else {
                "-".into()
            }
        );
        h.push_str("<p class=\"note\">A <em>case</em> is one level of one option set, or the limit at the last level. Deviations are the largest distance between corresponding vertices (or face-varying values, or limit positions and tangents) of the two engines, relative to the bounding-box diagonal; <b>0 means bit-identical</b>. Times are medians of interleaved runs of “refine + positions” (topology refinement and f64 positions of every level) with each input’s default options, the native engine on one thread; speed-up is OpenSubdiv’s time over the native time.</p>\n");
        for (idx, i) in self.inputs.iter().enumerate() {
            let _ = writeln!(
                h,
                "<section id=\"{}\">\n<h2>{} <span class=\"badge {}\">{}/{} agree</span></h2>",
                anchor(&i.name),
                escape(&i.name),
                if i.conforms() { "pass" } else { "fail" },
                i.agreeing(),
                i.cases()
            );
            let _ = writeln!(
                h,
                "<p>{}. {} vertices, {} faces. Default options: <code>{}</code>. Varied: {}.</p>",
                escape(&sentence(&i.description)),
                i.vertices,
                i.faces,
                escape(&options_label(&i.options)),
                if i.varied.is_empty() {
                    "nothing (no option can change this mesh's result)".into()
                } else {
                    escape(&i.varied.join(", "))
                }
            );
            h.push_str("<div class=\"figs\">\n");
            let _ = writeln!(
                h,
                "<figure>{}<figcaption>Worst deviation over the option sets, per level.</figcaption></figure>",
                inline_svg(&deviation_svg(i, &self.settings))
            );
            let _ = writeln!(
                h,
                "<figure>{}<figcaption>Refine + positions, default options.</figcaption></figure>",
                inline_svg(&time_svg(i))
            );
            let cap = if i.picture.level < last {
                format!(
                    "Level {} ({} faces; level {last} has more than {MAX_PICTURE_FACES}).",
                    i.picture.level, i.picture.faces
                )
            } else {
                format!("Level {}, default options.", i.picture.level)
            };
            let _ = writeln!(
                h,
                "<figure>{}<figcaption>{}</figcaption></figure>",
                inline_svg(&i.picture.svg.replacen(
                    &format!("devscale-{}", slug(0, &i.name)),
                    &format!("devscale-{}", slug(idx, &i.name)),
                    2
                )),
                escape(&cap)
            );
            h.push_str("</div>\n");
            let _ = writeln!(
                h,
                "<details{}><summary>{} option sets × {} — every case</summary>",
                if i.conforms() { "" } else { " open" },
                i.sets.len(),
                self.levels_label()
            );
            h.push_str(&sets_html(i, &self.settings));
            h.push_str("</details>\n</section>\n");
        }
        let _ = writeln!(
            h,
            "<footer>Generated by <code>subdiv report</code> {} in {:.1} s. Self-contained: no scripts, no external resources.</footer>\n</body>\n</html>",
            escape(&self.subdiv_version),
            self.seconds
        );
        h
    }

    /// Writes `dir/report.md`, `dir/report.html` and `dir/figures/*.svg`
    /// (creating the directories), each file atomically.
    pub fn write(&self, dir: &Path) -> Result<()> {
        let figures = dir.join("figures");
        std::fs::create_dir_all(&figures).map_err(|source| Error::Io {
            path: figures.clone(),
            source,
        })?;
        for (idx, i) in self.inputs.iter().enumerate() {
            let sl = slug(idx, &i.name);
            write_atomically(
                &figures.join(format!("{sl}-deviation.svg")),
                deviation_svg(i, &self.settings).as_bytes(),
            )?;
            write_atomically(
                &figures.join(format!("{sl}-time.svg")),
                time_svg(i).as_bytes(),
            )?;
            write_atomically(
                &figures.join(format!("{sl}-shape.svg")),
                i.picture.svg.as_bytes(),
            )?;
        }
        write_atomically(&dir.join("report.md"), self.markdown().as_bytes())?;
        write_atomically(&dir.join("report.html"), self.html().as_bytes())?;
        Ok(())
    }
}

/// The anchor Markdown renderers (GitHub's) give the heading `## name`.
fn markdown_anchor(name: &str) -> String {
    name.chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c.to_ascii_lowercase()),
            _ => None,
        })
        .collect()
}

/// `text` with its first letter in upper case.
fn sentence(text: &str) -> String {
    let mut c = text.chars();
    c.next()
        .map_or_else(String::new, |f| f.to_uppercase().chain(c).collect())
}

fn anchor(name: &str) -> String {
    let s = slug(0, name);
    format!("input-{}", s.trim_start_matches("01-"))
}

fn deviation_class(d: f64, tolerance: f64) -> &'static str {
    if d == 0.0 {
        "exact"
    } else if d <= tolerance {
        "pass"
    } else {
        "fail"
    }
}

fn sets_markdown(i: &InputReport, s: &Settings) -> String {
    let mut out = String::from("| scheme | boundary | creasing | triangles | fvar |");
    let levels: Vec<u32> = (s.first_level..=s.last_level).collect();
    for l in &levels {
        let _ = write!(out, " L{l} |");
    }
    out.push_str(" limit | result |\n| --- | --- | --- | --- | --- |");
    for _ in &levels {
        out.push_str(" ---: |");
    }
    out.push_str(" ---: | --- |\n");
    for set in &i.sets {
        let o = &set.options;
        let _ = write!(
            out,
            "| {} | {} | {} | {} | {} |",
            o.scheme.name(),
            o.boundary.name(),
            o.creasing.name(),
            o.triangles.name(),
            o.fvar.name()
        );
        for l in &levels {
            let cell = match set.levels.iter().find(|c| c.level == *l) {
                Some(c) if !c.topology_equal => "topology differs".into(),
                Some(c) => format_deviation(c.deviation()),
                None => "-".into(),
            };
            let _ = write!(out, " {cell} |");
        }
        let limit = set.limit.as_ref().map_or("-".into(), |l| {
            let mut c = format_deviation(l.deviation());
            if l.known_difference_vertices > 0 {
                let _ = write!(c, " (known: {} tangents)", l.known_difference_vertices);
            }
            c
        });
        let result = match &set.error {
            Some(e) => format!("ERROR: {e}"),
            None if set.agreeing() == set.cases() => "ok".into(),
            None => "DIFFERS".into(),
        };
        let _ = writeln!(out, " {limit} | {result} |");
    }
    if i.known_differences() > 0 {
        out.push_str("\n\"known\": limit tangents differ at vertices on non-manifold edges, OpenSubdiv 3.5's known limit-mask bug (docs/CONFORMANCE.md, \"Known differences\"); limit positions agree, and these tangents are not counted.\n");
    }
    out
}

fn sets_html(i: &InputReport, s: &Settings) -> String {
    let levels: Vec<u32> = (s.first_level..=s.last_level).collect();
    let mut out = String::from(
        "<table class=\"cases\"><thead><tr><th>scheme</th><th>boundary</th><th>creasing</th><th>triangles</th><th>fvar</th>",
    );
    for l in &levels {
        let _ = write!(out, "<th>L{l}</th>");
    }
    out.push_str("<th>limit</th><th>result</th></tr></thead><tbody>\n");
    for set in &i.sets {
        let o = &set.options;
        let _ = write!(
            out,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>",
            o.scheme.name(),
            o.boundary.name(),
            o.creasing.name(),
            o.triangles.name(),
            o.fvar.name()
        );
        for l in &levels {
            match set.levels.iter().find(|c| c.level == *l) {
                Some(c) => {
                    let title = format!(
                        "{} vertices, {} faces; positions {}{}; topology {}",
                        c.vertices,
                        c.faces,
                        format_deviation(c.position_deviation),
                        c.fvar_deviation.map_or(String::new(), |f| format!(
                            ", face-varying {}",
                            format_deviation(f)
                        )),
                        if c.topology_equal { "equal" } else { "DIFFERS" }
                    );
                    let class = if c.agrees {
                        deviation_class(c.deviation(), s.tolerance)
                    } else {
                        "fail"
                    };
                    let text = if c.topology_equal {
                        format_deviation(c.deviation())
                    } else {
                        "topology".into()
                    };
                    let _ = write!(
                        out,
                        "<td class=\"n {class}\" title=\"{}\">{}</td>",
                        escape(&title),
                        escape(&text)
                    );
                }
                None => out.push_str("<td class=\"n\">-</td>"),
            }
        }
        match &set.limit {
            Some(l) => {
                let title = format!(
                    "level {}: positions {}, tangents {}{}{}",
                    l.level,
                    format_deviation(l.position_deviation),
                    format_deviation(l.tangent_deviation),
                    l.fvar_deviation.map_or(String::new(), |f| format!(
                        ", face-varying {}",
                        format_deviation(f)
                    )),
                    if l.known_difference_vertices > 0 {
                        format!(
                            "; {} non-manifold vertices with OpenSubdiv's known tangent difference",
                            l.known_difference_vertices
                        )
                    } else {
                        String::new()
                    }
                );
                let class = if l.agrees {
                    deviation_class(l.deviation(), s.tolerance)
                } else {
                    "fail"
                };
                let known = if l.known_difference_vertices > 0 {
                    "<sup>†</sup>"
                } else {
                    ""
                };
                let _ = write!(
                    out,
                    "<td class=\"n {class}\" title=\"{}\">{}{known}</td>",
                    escape(&title),
                    format_deviation(l.deviation())
                );
            }
            None => out.push_str("<td class=\"n\">-</td>"),
        }
        match &set.error {
            Some(e) => {
                let _ = write!(out, "<td class=\"fail\">ERROR: {}</td>", escape(e));
            }
            None if set.agreeing() == set.cases() => out.push_str("<td class=\"pass\">ok</td>"),
            None => out.push_str("<td class=\"fail\">DIFFERS</td>"),
        }
        out.push_str("</tr>\n");
    }
    out.push_str("</tbody></table>\n");
    if i.known_differences() > 0 {
        out.push_str("<p class=\"note\">† Limit tangents differ at vertices on non-manifold edges: OpenSubdiv 3.5 sizes the limit masks by the level's maximum valence and overwrites a weight there (docs/CONFORMANCE.md, “Known differences”). Limit positions agree; these tangents are not counted.</p>\n");
    }
    out
}

const CSS: &str = r#"
:root { color-scheme: light; }
body { font-family: system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", sans-serif; color: #1b1f24; background: #f6f7f9; margin: 0; padding: 20px 24px 40px; line-height: 1.45; }
header, section, body > table, body > h2, body > p, footer { max-width: 1240px; margin-left: auto; margin-right: auto; }
h1 { font-size: 26px; margin: 0 0 10px; }
h2 { font-size: 20px; margin: 28px auto 10px; }
section h2 { margin-top: 0; }
section { background: white; border: 1px solid #d8dde3; border-radius: 8px; padding: 16px 18px; margin-top: 22px; }
dl.meta { display: grid; grid-template-columns: max-content 1fr; gap: 2px 14px; margin: 0 0 12px; font-size: 14px; }
dl.meta dt { font-weight: 600; color: #555; }
dl.meta dd { margin: 0; }
.verdict { font-size: 16px; font-weight: 600; padding: 10px 14px; border-radius: 6px; margin: 8px 0; }
.verdict.pass { background: #e3f4e6; border: 1px solid #5aa469; color: #1d5b2a; }
.verdict.fail { background: #fbe4e4; border: 1px solid #c94a4a; color: #7a1212; }
table { border-collapse: collapse; background: white; font-size: 14px; }
table.summary { width: 100%; border: 1px solid #d8dde3; }
th, td { padding: 5px 10px; border-bottom: 1px solid #e6e9ed; text-align: left; }
th { background: #eef1f5; font-weight: 600; }
tfoot td { font-weight: 600; background: #f6f8fa; }
td.n, th.n { text-align: right; font-variant-numeric: tabular-nums; }
td.exact { color: #1f5fa8; }
td.pass { color: #1d6b2f; }
td.fail { color: #b01515; font-weight: 600; }
a { color: #1f5fa8; text-decoration: none; }
.badge { font-size: 13px; font-weight: 600; padding: 2px 8px; border-radius: 10px; vertical-align: middle; margin-left: 8px; }
.badge.pass { background: #e3f4e6; color: #1d5b2a; }
.badge.fail { background: #fbe4e4; color: #7a1212; }
.figs { display: grid; grid-template-columns: repeat(auto-fit, minmax(330px, 1fr)); gap: 12px; margin: 12px 0; align-items: start; }
figure { margin: 0; border: 1px solid #e1e4e8; border-radius: 6px; background: white; padding: 4px; }
figure svg { display: block; width: 100%; height: auto; }
figcaption { font-size: 12px; color: #555; padding: 2px 6px 4px; }
details { margin-top: 8px; }
summary { cursor: pointer; font-weight: 600; font-size: 14px; color: #333; }
table.cases { margin-top: 8px; font-size: 12.5px; }
table.cases td, table.cases th { padding: 3px 8px; }
code { font-size: 13px; background: #f0f2f5; padding: 1px 4px; border-radius: 3px; }
.note { font-size: 13px; color: #444; }
footer { margin-top: 24px; font-size: 12px; color: #666; }
"#;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn embedded_inputs_are_valid_and_named_uniquely() {
        let inputs = embedded_inputs();
        let mut names: Vec<&str> = inputs.iter().map(|i| i.name.as_str()).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), inputs.len());
        for i in &inputs {
            i.mesh.validate().unwrap();
            assert!(!option_sets(i, true).is_empty());
        }
    }

    #[test]
    fn option_sets_vary_what_applies() {
        let inputs = embedded_inputs();
        let by = |n: &str| inputs.iter().find(|i| i.name == n).unwrap();
        // A closed quad mesh: catmark and bilinear, nothing else varies.
        assert_eq!(option_sets(by("cube"), false).len(), 2);
        // Loop only on all-triangle meshes.
        let ico = option_sets(by("icosahedron"), false);
        assert_eq!(ico[0].scheme, Scheme::Loop);
        assert!(
            option_sets(by("pole"), false)
                .iter()
                .all(|o| o.scheme != Scheme::Loop)
        );
        // UVs on an open mesh: 3 boundaries × 6 face-varying modes per scheme.
        assert_eq!(option_sets(by("grid-uv-regions"), false).len(), 2 * 3 * 6);
        assert!(option_sets(by("grid-uv-regions"), true).len() < 2 * 3 * 6);
    }

    #[test]
    fn pictures_colour_deviations() {
        let input = embedded_inputs().swap_remove(0);
        let n = refiner::refine(&input.mesh, &input.options, UniformOptions::new(2)).unwrap();
        let exact = picture(&input, &n, &n, 1e-6);
        assert_eq!(exact.max_deviation, 0.0);
        assert!(exact.svg.contains("0 (bit-identical to OpenSubdiv)"));
        // Deviations from 0 (every third vertex) through 1e-16 to 1e-5.
        let mut o = n.clone();
        let diag = bbox_diagonal(&n.positions[2]);
        let count = o.positions[2].len();
        for (i, p) in o.positions[2].iter_mut().enumerate() {
            if i % 3 != 0 {
                p.x += diag * 10f64.powf(-16.0 + 11.0 * i as f64 / count as f64);
            }
        }
        let pic = picture(&input, &n, &o, 1e-6);
        assert!(pic.max_deviation > 1e-6 && pic.max_deviation < 1e-4);
        assert!(pic.svg.contains("largest deviation"));
        for d in [0.0, 1e-3] {
            let c = hex(deviation_color(d, 1e-6));
            assert!(pic.svg.contains(&c[..5]), "{c}");
        }
        if let Some(path) = std::env::var_os("SUBDIV_REPORT_PICTURE") {
            std::fs::write(path, &pic.svg).unwrap();
        }
    }

    #[test]
    fn a_difference_fails_the_verdict() {
        let inputs = vec![embedded_inputs().swap_remove(0)];
        let mut rep = run(&inputs, &Settings::new(true), |_| {}).unwrap();
        assert!(rep.conforms());
        assert!(rep.verdict().starts_with("CONFORMS"));
        let c = &mut rep.inputs[0].sets[0].levels[0];
        c.position_deviation = 1e-3;
        c.agrees = false;
        assert!(!rep.conforms());
        assert!(rep.verdict().starts_with("DIFFERS: 1 of"));
        let html = rep.html();
        assert!(html.contains("verdict fail") && html.contains("DIFFERS"));
        assert!(rep.markdown().contains("DIFFERS"));
    }

    #[test]
    fn colours_and_formats() {
        assert_eq!(format_deviation(0.0), "0");
        assert_eq!(format_worst(0.0), "0 (bit-identical)");
        assert_eq!(format_deviation(f64::INFINITY), "∞");
        assert_ne!(
            hex(deviation_color(0.0, 1e-6)),
            hex(deviation_color(1e-16, 1e-6))
        );
        assert_eq!(
            hex(deviation_color(1e-3, 1e-6)),
            hex(deviation_color(f64::INFINITY, 1e-6))
        );
        assert_eq!(slug(2, "My Shape.obj"), "03-my-shape-obj");
    }
}
