//! What a report run covers.

/// The largest accepted deviation, relative to the bounding-box diagonal.
pub const DEFAULT_TOLERANCE: f64 = 1e-6;

/// Pictures show the deepest compared level with at most this many faces.
pub const MAX_PICTURE_FACES: usize = 8192;

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
    /// Every combination of options for every input, whatever its size
    /// (see [`super::coverage::choose`]).
    pub all_options: bool,
}

impl Settings {
    /// Levels 1..4 (1..2 when `quick`), tolerance [`DEFAULT_TOLERANCE`].
    pub fn new(quick: bool) -> Settings {
        Settings {
            first_level: 1,
            last_level: if quick { 2 } else { 4 },
            quick,
            tolerance: DEFAULT_TOLERANCE,
            all_options: false,
        }
    }

    /// The benchmarked levels: the compared ones, level 0 left out.
    pub fn timed_levels(&self) -> std::ops::RangeInclusive<u32> {
        self.first_level.max(1)..=self.last_level
    }
}
