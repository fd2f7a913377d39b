//! Face-varying patch channels: which channels a table has, each one's
//! levels and value offsets; and the patches of linear channels:
//! OpenSubdiv's patch for a face in a linear channel is the face itself in
//! the channel's topology — its corners' values, offset by the values of
//! the levels before — with the vertex patch's parameter
//! (`assignFacePoints` and `BuildUniformPolygons` in
//! `far/patchTableFactory.cpp`). Non-linear channels are built in
//! `fvar_patches.rs`.

use super::super::{FVarPatches, PatchOptions, PatchType};
use crate::error::{Error, Result};
use crate::options::FVarLinearInterpolation;
use crate::topology::Level;
use crate::topology::fvar::ChannelLevel;

/// The channels a table gets face-varying patches for: none without
/// `generateFVarTables`, the listed ones, or every one of the `count` the
/// refiner has when none is listed.
pub(crate) fn requested(options: &PatchOptions, count: usize) -> Result<Vec<usize>> {
    if let Some(&c) = options.fvar_channels.iter().find(|&&c| c >= count) {
        return Err(Error::NoSuchChannel { channel: c, count });
    }
    Ok(if !options.fvar_tables {
        Vec::new()
    } else if options.fvar_channels.is_empty() {
        (0..count).collect()
    } else {
        options.fvar_channels.clone()
    })
}

/// Whether a table's face-varying patches are linear
/// (`isFVarChannelLinear`): legacy linear patches asked for, or channels
/// interpolated linearly everywhere.
pub(crate) fn is_linear(options: &PatchOptions, mode: FVarLinearInterpolation) -> bool {
    options.fvar_legacy_linear_patches || mode == FVarLinearInterpolation::All
}

/// Refuses more channels listed than the refiner has, as the `osd` engine
/// does (OpenSubdiv would read the channel numbered as a listed channel's
/// place in the list).
pub(crate) fn check_listed(options: &PatchOptions, count: usize) -> Result<()> {
    if options.fvar_channels.len() > count {
        return Err(Error::PatchOptions {
            reason: format!(
                "{} face-varying channels listed, the refiner has {count}",
                options.fvar_channels.len()
            ),
        });
    }
    Ok(())
}

/// One channel whose patches are being built: its levels and the offset of
/// each level's values (those of every level before it, base first).
pub(crate) struct Channel<'a> {
    pub(crate) channel: usize,
    levels: &'a [ChannelLevel],
    pub(crate) offsets: Vec<u32>,
    /// Values of every level.
    total: u32,
    /// The refiner's channel numbered as this one's place in the table,
    /// which OpenSubdiv's regularity test reads.
    regularity: Option<&'a [ChannelLevel]>,
}

impl<'a> Channel<'a> {
    /// Channel `channel` over `levels`, each level's values numbered after
    /// those of every level before it; `regularity` the levels of the
    /// refiner's channel numbered as its place in the table.
    pub(crate) fn new(
        channel: usize,
        levels: &'a [ChannelLevel],
        regularity: Option<&'a [ChannelLevel]>,
    ) -> Self {
        let mut offsets = Vec::with_capacity(levels.len());
        let mut at = 0u32;
        for l in levels {
            offsets.push(at);
            at += l.value_count() as u32;
        }
        Channel {
            channel,
            levels,
            offsets,
            total: at,
            regularity,
        }
    }

    /// The channel at `level`.
    pub(crate) fn level(&self, level: usize) -> &'a ChannelLevel {
        &self.levels[level]
    }

    /// Number of values of every level (the first local point's index).
    pub(crate) fn total_values(&self) -> u32 {
        self.total
    }

    /// The channel OpenSubdiv's regularity test reads at `level`.
    pub(crate) fn regularity_level(&self, level: usize) -> Option<&'a ChannelLevel> {
        self.regularity.and_then(|l| l.get(level))
    }

    /// Number of values at `level`.
    pub(crate) fn value_count(&self, level: usize) -> usize {
        self.levels[level].value_count()
    }

    /// The values of face `f` of `level` (whose topology is `topology`),
    /// offset by `offset`.
    pub(crate) fn face<'s>(
        &'s self,
        topology: &'s Level,
        level: usize,
        f: usize,
        offset: u32,
    ) -> impl Iterator<Item = u32> + 's {
        let values = self.levels[level].face_values_of(topology, f);
        values.iter().map(move |&x| x + offset)
    }

    /// The finished channel: `values` (in table order) and the patches'
    /// parameters, all of type `ty`.
    pub(crate) fn finish(
        channel: usize,
        ty: PatchType,
        values: Vec<u32>,
        params: Vec<super::super::PatchParam>,
    ) -> FVarPatches {
        FVarPatches {
            channel,
            regular_type: ty,
            irregular_type: ty,
            stride: ty.control_vertices(),
            values,
            params,
            local_point_stencils: Default::default(),
        }
    }
}
