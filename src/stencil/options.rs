//! [`StencilOptions`]: what a stencil table holds, as
//! `Far::StencilTableFactory::Options` of OpenSubdiv 3.5 says it.

use crate::error::{Error, LevelRefusal, Result};

/// The deepest level `StencilTableFactory::Options::maxLevel` holds (4 bits).
pub const MAX_STENCIL_LEVEL: u32 = 15;

/// Which primvar the stencils interpolate
/// (`Far::StencilTableFactory::Mode`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[non_exhaustive]
pub enum StencilInterpolation {
    /// Vertex data: the scheme's masks (`INTERPOLATE_VERTEX`).
    #[default]
    Vertex,
    /// Varying data: linear masks (`INTERPOLATE_VARYING`).
    Varying,
    /// The values of face-varying channel
    /// [`StencilOptions::fvar_channel`] (`INTERPOLATE_FACE_VARYING`): rows
    /// and indices are face-varying values, not vertices.
    FaceVarying,
}

impl StencilInterpolation {
    /// OpenSubdiv's numeric value of the mode (0, 1, 2).
    pub fn code(self) -> i32 {
        match self {
            StencilInterpolation::Vertex => 0,
            StencilInterpolation::Varying => 1,
            StencilInterpolation::FaceVarying => 2,
        }
    }
}

/// What a stencil table holds: `Far::StencilTableFactory::Options` of
/// OpenSubdiv 3.5, field for field, with its defaults
/// ([`StencilOptions::new`]).
///
/// The table's rows (stencils), as OpenSubdiv 3.5 produces them, number the
/// vertices of all levels one after the other — base vertices, then level 1,
/// level 2, ... up to `min(max_level, deepest refined level)`:
///
/// * with [`generate_control_vertices`](Self::generate_control_vertices),
///   first one identity row per base vertex (index `i`, weight 1);
/// * with [`generate_intermediate_levels`](Self::generate_intermediate_levels),
///   then the rows of every level in level order, each level in vertex
///   order; without it, the rows of the last level only;
/// * with [`factorize_intermediate_levels`](Self::factorize_intermediate_levels),
///   every row is over the base vertices; without it, the rows of level `l`
///   are over the vertices of level `l - 1`, numbered from 0 within that
///   level (so only level 1's rows, and the identity rows, are over the base).
///   OpenSubdiv 3.5 then also ignores "last level only": a table neither
///   factorized nor with intermediate levels holds the identity rows and
///   every level's rows, as if both control vertices and intermediate levels
///   had been asked for. Adding control vertices to that combination makes
///   OpenSubdiv 3.5 loop and write out of bounds; both engines refuse it
///   ([`Error::StencilOptions`]).
/// * [`generate_offsets`](Self::generate_offsets) changes nothing in 3.5
///   (`Create` fills the offsets whatever it says); it is kept and passed on.
/// * A `max_level` of 0, or a refiner not refined, gives the identity rows
///   with control vertices, and an empty table without.
///
/// Within a row, the base indices come in the order of their first
/// contribution, each weight accumulated in the order OpenSubdiv's stencil
/// builder adds it; mask terms of weight zero are skipped.
///
/// ```
/// use subdiv::stencil::{StencilInterpolation, StencilOptions};
/// let o = StencilOptions::new()
///     .interpolation(StencilInterpolation::Varying)
///     .control_vertices(true)
///     .intermediate_levels(false)
///     .max_level(2);
/// assert!(o.factorize_intermediate_levels && !o.generate_offsets);
/// assert_eq!(StencilOptions::default().max_level, 10);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub struct StencilOptions {
    /// The primvar interpolated (`interpolationMode`): vertex by default.
    pub interpolation: StencilInterpolation,
    /// `generateOffsets` (false): no effect on the table in OpenSubdiv 3.5.
    pub generate_offsets: bool,
    /// `generateControlVerts` (false): identity rows for the base vertices
    /// first.
    pub generate_control_vertices: bool,
    /// `generateIntermediateLevels` (true): the rows of every level, not just
    /// the last.
    pub generate_intermediate_levels: bool,
    /// `factorizeIntermediateLevels` (true): rows over the base vertices
    /// rather than over the previous level's.
    pub factorize_intermediate_levels: bool,
    /// `maxLevel` (10): the deepest level with rows, at most
    /// [`MAX_STENCIL_LEVEL`] (OpenSubdiv keeps it in 4 bits); levels beyond
    /// the refiner's deepest are ignored.
    pub max_level: u32,
    /// `fvarChannel` (0): the face-varying channel of
    /// [`StencilInterpolation::FaceVarying`]; unread otherwise.
    pub fvar_channel: usize,
}

impl Default for StencilOptions {
    fn default() -> Self {
        StencilOptions::new()
    }
}

impl StencilOptions {
    /// OpenSubdiv's defaults: vertex interpolation, no offsets, no control
    /// vertices, intermediate levels factorized, `max_level` 10, channel 0.
    pub fn new() -> Self {
        StencilOptions {
            interpolation: StencilInterpolation::Vertex,
            generate_offsets: false,
            generate_control_vertices: false,
            generate_intermediate_levels: true,
            factorize_intermediate_levels: true,
            max_level: 10,
            fvar_channel: 0,
        }
    }

    /// Returns these options with another interpolation mode.
    pub fn interpolation(mut self, mode: StencilInterpolation) -> Self {
        self.interpolation = mode;
        self
    }

    /// Returns these options interpolating face-varying channel `channel`.
    pub fn face_varying(mut self, channel: usize) -> Self {
        self.interpolation = StencilInterpolation::FaceVarying;
        self.fvar_channel = channel;
        self
    }

    /// Returns these options with `generateOffsets` set.
    pub fn offsets(mut self, yes: bool) -> Self {
        self.generate_offsets = yes;
        self
    }

    /// Returns these options with `generateControlVerts` set.
    pub fn control_vertices(mut self, yes: bool) -> Self {
        self.generate_control_vertices = yes;
        self
    }

    /// Returns these options with `generateIntermediateLevels` set.
    pub fn intermediate_levels(mut self, yes: bool) -> Self {
        self.generate_intermediate_levels = yes;
        self
    }

    /// Returns these options with `factorizeIntermediateLevels` set.
    pub fn factorize(mut self, yes: bool) -> Self {
        self.factorize_intermediate_levels = yes;
        self
    }

    /// Returns these options with another `maxLevel`.
    pub fn max_level(mut self, level: u32) -> Self {
        self.max_level = level;
        self
    }

    /// Returns these options with another `fvarChannel` (the mode unchanged).
    pub fn fvar_channel(mut self, channel: usize) -> Self {
        self.fvar_channel = channel;
        self
    }

    /// The checks both engines make before building anything, for a refiner
    /// refined to `refined` levels with `channels` face-varying channels:
    /// `max_level` beyond [`MAX_STENCIL_LEVEL`] ([`Error::Level`]), a missing
    /// face-varying channel ([`Error::NoSuchChannel`]), and the combination
    /// OpenSubdiv 3.5 cannot build ([`Error::StencilOptions`]). Returns the
    /// deepest level with rows.
    pub(crate) fn check(&self, refined: u32, channels: usize) -> Result<u32> {
        if self.max_level > MAX_STENCIL_LEVEL {
            return Err(Error::Level {
                level: self.max_level,
                reason: LevelRefusal::TooDeep {
                    max: MAX_STENCIL_LEVEL,
                },
            });
        }
        if self.interpolation == StencilInterpolation::FaceVarying && self.fvar_channel >= channels
        {
            return Err(Error::NoSuchChannel {
                channel: self.fvar_channel,
                count: channels,
            });
        }
        let last = self.max_level.min(refined);
        if last > 0
            && self.generate_control_vertices
            && !self.generate_intermediate_levels
            && !self.factorize_intermediate_levels
        {
            return Err(Error::StencilOptions {
                reason: "control vertices with neither intermediate levels nor factorization \
                         (OpenSubdiv 3.5 loops and writes out of bounds on it)",
            });
        }
        Ok(last)
    }
}
