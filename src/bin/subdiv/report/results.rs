//! What a report found: per level, per option set, per input.

use super::settings::Settings;
use subdiv::options::Options;

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
    /// Largest tangent deviation (both tangents, relative to the diagonal).
    pub tangent_deviation: f64,
    /// Largest face-varying limit value deviation, when the mesh has UVs.
    pub fvar_deviation: Option<f64>,
    /// Whether positions, tangents and face-varying values are within the
    /// tolerance.
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
    /// OpenSubdiv was not asked for the limit because it would read or write
    /// out of bounds on this input (a known fault of OpenSubdiv 3.5, refused
    /// by the bridge: docs/CONFORMANCE.md): why. Not a check, not a failure.
    pub limit_refused: Option<String>,
    /// OpenSubdiv was not asked to refine at all, for the same reason (the
    /// Catmull-Clark vertex rule overflowing past 46,340 faces at a vertex):
    /// why. No level is compared; not a failure.
    pub refused: Option<String>,
}

impl SetResult {
    /// Why OpenSubdiv was not asked for this set's refinement or its limit,
    /// if it was not.
    pub fn refusal(&self) -> Option<&str> {
        self.refused.as_deref().or(self.limit_refused.as_deref())
    }

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
    /// How many of them were run (chosen by the input's size).
    pub coverage: super::coverage::Coverage,
    /// Every option set's comparisons.
    pub sets: Vec<SetResult>,
    /// Benchmarks per level.
    pub timings: Vec<Timing>,
    /// The refined shape.
    pub picture: Picture,
    /// The limit surface through both engines' patch tables.
    pub limit_surface: LimitSurface,
    /// The limit surface tessellated the Bfr way by both engines.
    pub tessellated: super::tessellated::Tessellated,
}

/// Both engines' patch tables of an input (its default options, isolation
/// [`LIMIT_ISOLATION`], Gregory basis end caps) and the limit surfaces they
/// evaluate.
#[derive(Debug, Clone, PartialEq)]
pub enum LimitSurface {
    /// Compared.
    Compared {
        /// Patches in the native table.
        patches: usize,
        /// Local points (native, OpenSubdiv).
        local_points: [usize; 2],
        /// Where the tables first differ (none: identical).
        first_difference: Option<String>,
        /// Locations evaluated.
        locations: usize,
        /// Largest position deviation, relative to the diagonal.
        deviation: f64,
        /// Largest derivative deviation, relative to the largest derivative.
        derivative_deviation: f64,
        /// Whether it all agrees within the report's tolerance.
        agrees: bool,
        /// The evaluated surface coloured by deviation (SVG).
        picture: String,
    },
    /// Not compared, and why (a table the native engine does not build
    /// yet, an input OpenSubdiv refuses).
    NotCompared(String),
}

/// The isolation level of the report's patch tables.
pub const LIMIT_ISOLATION: u32 = 3;

impl LimitSurface {
    /// One sentence for the report.
    pub fn sentence(&self) -> String {
        match self {
            LimitSurface::Compared {
                patches,
                local_points,
                first_difference,
                locations,
                deviation,
                derivative_deviation,
                agrees,
                ..
            } => format!(
                "Limit surface (patch tables at isolation {LIMIT_ISOLATION}, Gregory basis end caps): tables {} ({patches} patches, {}/{} local points); the surface at {locations} locations (u, v in {{0, 1/4, 1/2, 3/4, 1}} on every ptex face) deviates by at most {deviation:.2e} of the diagonal, derivatives {derivative_deviation:.2e} of their largest: {}.",
                match first_difference {
                    None => "identical".to_string(),
                    Some(d) => format!("DIFFERENT (first at {d})"),
                },
                local_points[0],
                local_points[1],
                if *agrees { "agrees" } else { "DIFFERS" }
            ),
            LimitSurface::NotCompared(why) => {
                format!("Limit surface: not compared ({why}).")
            }
        }
    }
}

impl InputReport {
    /// What the option sets varied, as the report says it (`nothing` when
    /// no option applies).
    pub fn varied_label(&self, nothing: &str) -> String {
        use super::coverage::Coverage;
        if self.varied.is_empty() {
            return nothing.to_string();
        }
        let applies = self.varied.join(", ");
        match self.coverage {
            Coverage::Every => applies,
            Coverage::OneAtATime => format!("{applies}, one at a time"),
            Coverage::Own => format!(
                "nothing, for the mesh's size (options that apply: {applies}; `--all-options` runs every combination)"
            ),
        }
    }

    /// Checks made.
    pub fn cases(&self) -> usize {
        self.sets.iter().map(SetResult::cases).sum()
    }

    /// Checks passed.
    pub fn agreeing(&self) -> usize {
        self.sets.iter().map(SetResult::agreeing).sum()
    }

    /// Whether every check passed (the limit surface's and the tessellated
    /// surface's too, where they were compared).
    pub fn conforms(&self) -> bool {
        self.agreeing() == self.cases()
            && !matches!(
                self.limit_surface,
                LimitSurface::Compared { agrees: false, .. }
            )
            && self.tessellated.conforms()
    }

    /// The largest deviation of any check.
    pub fn worst_deviation(&self) -> f64 {
        self.sets
            .iter()
            .map(SetResult::worst_deviation)
            .fold(0.0, f64::max)
    }

    /// Option sets whose refinement or limit OpenSubdiv could not be asked
    /// for safely.
    pub fn refusals(&self) -> usize {
        self.sets.iter().filter(|s| s.refusal().is_some()).count()
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
        let sets = || self.inputs.iter().flat_map(|i| &i.sets);
        let whole = sets().filter(|s| s.refused.is_some()).count();
        let limit = sets().filter(|s| s.limit_refused.is_some()).count();
        let mut known = String::new();
        if whole > 0 {
            known.push_str(&format!(
                " Not compared: {whole} option set(s) OpenSubdiv 3.5 cannot refine correctly (a Catmull-Clark vertex of more than 46,340 faces; docs/CONFORMANCE.md)."
            ));
        }
        if limit > 0 {
            known.push_str(&format!(
                " Not compared: the limit of {limit} option set(s), where OpenSubdiv 3.5's PrimvarRefiner::Limit would write past its masks (high-valence non-manifold vertices; docs/CONFORMANCE.md)."
            ));
        }
        if total == 0 {
            return format!("NOTHING COMPARED: no check could be made.{known}");
        }
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

    pub(crate) fn levels_label(&self) -> String {
        let s = &self.settings;
        if s.first_level == s.last_level {
            format!("level {}", s.first_level)
        } else {
            format!("levels {}..{}", s.first_level, s.last_level)
        }
    }
}
