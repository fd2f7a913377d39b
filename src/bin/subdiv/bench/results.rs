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

/// A whole benchmark run.
#[derive(Debug, Clone, serde::Serialize)]
pub struct BenchReport {
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

/// A named series of (level, native seconds, OpenSubdiv seconds).
pub(crate) type LevelSeries = (String, Vec<(u32, f64, f64)>);
