//! What `subdiv bench` measures: its rows, as printed and as JSON.

/// One comparison: the same work done by both engines.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Row {
    /// The input.
    pub input: String,
    /// The scheme.
    pub scheme: String,
    /// The level.
    pub level: u32,
    /// What was measured.
    pub task: String,
    /// Median native time, seconds.
    pub native: f64,
    /// Median OpenSubdiv time, seconds.
    pub osd: f64,
    /// Vertices produced (for rates).
    pub vertices: usize,
}

impl Row {
    /// OpenSubdiv's time over the native time (above 1: native is faster).
    pub fn speedup(&self) -> f64 {
        self.osd / self.native
    }
}

/// OpenSubdiv's deepest "topology + positions" time measured twice: with no
/// native run in between, and interleaved with the native engine (the time
/// in [`BenchReport::rows`]). Both engines share the process's C allocator, so
/// each can leave the other's heap warmer or colder; the pair shows whether
/// the reference in the table runs as it does on its own.
#[derive(Debug, Clone, serde::Serialize)]
pub struct AloneRow {
    /// The input.
    pub input: String,
    /// The scheme.
    pub scheme: String,
    /// The level.
    pub level: u32,
    /// Median OpenSubdiv time alone, seconds.
    pub alone: f64,
    /// Median OpenSubdiv time interleaved with the native engine, seconds.
    pub interleaved: f64,
}

/// A whole benchmark run: what `subdiv bench` prints and writes as
/// bench.json. Measurements and ratios only; the project's own targets are
/// judged from the JSON by scripts/check-targets.py.
#[derive(Debug, Clone, serde::Serialize)]
pub struct BenchReport {
    /// The date (UTC, YYYY-MM-DD).
    pub date: String,
    /// When and where it ran.
    pub machine: String,
    /// Native threads used.
    pub threads: usize,
    /// Memory copy bandwidth measured with `threads` threads, bytes per
    /// second.
    pub bandwidth: f64,
    /// All comparisons.
    pub rows: Vec<Row>,
    /// Stencil apply: native and OpenSubdiv bytes moved per second, on the
    /// input where the native rate is lowest.
    pub stencil_bandwidth: Option<(f64, f64)>,
    /// Parallel use of the library: many frames of one topology
    /// ([`frames_row`]) and many meshes ([`meshes_row`]), both engines over
    /// the same pool of `threads` threads.
    pub parallel: Vec<ParallelRow>,
    /// OpenSubdiv alone against OpenSubdiv interleaved, per input.
    pub osd_alone: Vec<AloneRow>,
    /// Feature-adaptive refinement (issue #23): topology and positions at
    /// isolation levels 3 and 6, apart from [`BenchReport::rows`] (whose
    /// levels are uniform levels).
    pub adaptive: Vec<AdaptiveRow>,
    /// Tessellation of the limit surface the Bfr way (issue #25): the
    /// Catmull-Clark tori at rates 4 and 16.
    pub tessellation: Vec<TessellationRow>,
    /// Whole programs: the first input at level 4, and each input refined
    /// at most two levels (the big ones) at levels 1 and 2 (standard inputs
    /// only).
    pub whole_process: Vec<WholeProcess>,
    /// The OBJ writer's rate on the first input (standard inputs only).
    pub obj_writer: Option<ObjWriterRate>,
    /// The OBJ reader's rate on each big input (refined at most two levels,
    /// 100,000 faces or more at full size; standard inputs only).
    pub obj_reader: Vec<ObjReaderRate>,
    /// Sections that could not run, with the reason.
    pub skipped: Vec<String>,
}

/// Which program a whole-process run is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ProgramKind {
    /// `subdiv refine` natively on the bench's `--threads` threads.
    Native,
    /// `subdiv refine` natively as typed (every core), when that differs.
    NativeAsTyped,
    /// `subdiv refine --engine osd`.
    Osd,
    /// The C++ program against OpenSubdiv (cpp/osd_driver.cpp).
    Cpp,
}

/// One program of the whole-process section.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ProgramResult {
    /// Which program.
    pub kind: ProgramKind,
    /// Its description.
    pub name: String,
    /// Median wall time, seconds.
    pub seconds: f64,
    /// Peak resident memory it reported, bytes (0: not reported).
    pub peak_bytes: u64,
}

/// Whole programs refining the same OBJ file, interleaved.
#[derive(Debug, Clone, serde::Serialize)]
pub struct WholeProcess {
    /// The input.
    pub input: String,
    /// The refinement level.
    pub level: u32,
    /// The bench's native threads.
    pub threads: usize,
    /// The machine's cores (what `subdiv refine` uses as typed).
    pub cores: usize,
    /// Every program, in the order run.
    pub programs: Vec<ProgramResult>,
}

impl WholeProcess {
    /// The program of `kind`, if it ran.
    pub fn program(&self, kind: ProgramKind) -> Option<&ProgramResult> {
        self.programs.iter().find(|p| p.kind == kind)
    }

    /// `subdiv refine` as a user types it: every core.
    pub fn as_typed(&self) -> Option<&ProgramResult> {
        self.program(ProgramKind::NativeAsTyped)
            .or_else(|| self.program(ProgramKind::Native))
    }

    /// The larger peak memory of the native runs.
    pub fn native_peak(&self) -> u64 {
        self.programs
            .iter()
            .filter(|p| matches!(p.kind, ProgramKind::Native | ProgramKind::NativeAsTyped))
            .map(|p| p.peak_bytes)
            .max()
            .unwrap_or(0)
    }
}

/// The OBJ writer's best time writing one refined level.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ObjWriterRate {
    /// The input.
    pub input: String,
    /// The level written.
    pub level: u32,
    /// The file's size.
    pub bytes: u64,
    /// The best of three writes, seconds.
    pub seconds: f64,
}

/// The OBJ reader's best times reading one input's file (`subdiv::io::read_obj`,
/// as `subdiv refine` does: the file read, then parsed), on one thread and on
/// the run's threads.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ObjReaderRate {
    /// The input.
    pub input: String,
    /// The file's size (positions, UVs, faces and tags).
    pub bytes: u64,
    /// The best of three reads on one thread, seconds.
    pub seconds_one_thread: f64,
    /// The run's threads.
    pub threads: usize,
    /// The best of three reads on the run's threads, seconds.
    pub seconds: f64,
}

impl ObjReaderRate {
    /// Megabytes (10^6 bytes) per second on one thread and on the run's threads.
    pub fn mb_per_s(&self) -> (f64, f64) {
        let mb = self.bytes as f64 / 1e6;
        (mb / self.seconds_one_thread, mb / self.seconds)
    }
}

impl ObjWriterRate {
    /// Megabytes (10^6 bytes) per second.
    pub fn mb_per_s(&self) -> f64 {
        self.bytes as f64 / self.seconds / 1e6
    }
}

/// One comparison of the parallel-use section.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ParallelRow {
    /// What the batch is made of: "frames" or "meshes".
    pub unit: String,
    /// How many frames or meshes the batch has.
    pub count: usize,
    /// The times of the whole batch (`vertices` counts every frame's or
    /// mesh's refined vertices).
    #[serde(flatten)]
    pub row: Row,
}

impl ParallelRow {
    /// Frames or meshes per second: natively, and in OpenSubdiv.
    pub fn rates(&self) -> (f64, f64) {
        let n = self.count as f64;
        (n / self.row.native, n / self.row.osd)
    }
}

/// One comparison of the adaptive section: `row.level` is the isolation
/// level, `row.vertices` counts the vertices of every refined level.
#[derive(Debug, Clone, serde::Serialize)]
pub struct AdaptiveRow {
    /// The isolation level asked for.
    pub isolation: u32,
    /// The deepest level both engines refined (below `isolation` when a
    /// level selected nothing; 0 on a mesh without features).
    pub max_level: u32,
    /// The times.
    #[serde(flatten)]
    pub row: Row,
}

/// One comparison of the tessellation section: `row.vertices` counts the
/// mesh's points.
#[derive(Debug, Clone, serde::Serialize)]
pub struct TessellationRow {
    /// The rate of every edge.
    pub rate: u32,
    /// Triangles of the mesh (a kept quad counts as two).
    pub triangles: usize,
    /// The times.
    #[serde(flatten)]
    pub row: Row,
}

impl TessellationRow {
    /// Triangles per second: native, OpenSubdiv.
    pub fn rates(&self) -> (f64, f64) {
        let n = self.triangles as f64;
        (n / self.row.native, n / self.row.osd)
    }
}

/// A named series of (level, native seconds, OpenSubdiv seconds).
pub(crate) type LevelSeries = (String, Vec<(u32, f64, f64)>);
