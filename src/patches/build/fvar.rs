//! Face-varying patch channels of linear channels: OpenSubdiv's patch for a
//! face in a linear channel is the face itself in the channel's topology —
//! its corners' values, offset by the values of the levels before — with
//! the vertex patch's parameter (`assignFacePoints` and
//! `BuildUniformPolygons` in `far/patchTableFactory.cpp`).

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

/// Refuses adaptive face-varying patches that are not linear (the channel's
/// own regular and end-cap patches, not built natively yet).
pub(crate) fn check_linear(options: &PatchOptions, mode: FVarLinearInterpolation) -> Result<()> {
    if options.fvar_legacy_linear_patches || mode == FVarLinearInterpolation::All {
        Ok(())
    } else {
        Err(Error::NotYetSupported(
            "non-linear face-varying patch tables (generateFVarLegacyLinearPatches off)",
        ))
    }
}

/// One channel whose patches are being built: its levels and the offset of
/// each level's values (those of every level before it, base first).
pub(crate) struct Channel<'a> {
    pub(crate) channel: usize,
    levels: &'a [ChannelLevel],
    pub(crate) offsets: Vec<u32>,
}

impl<'a> Channel<'a> {
    /// Channel `channel` over `levels`, each level's values numbered after
    /// those of every level before it.
    pub(crate) fn new(channel: usize, levels: &'a [ChannelLevel]) -> Self {
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
        }
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
        }
    }
}
