//! Face-varying channel topology — in progress: the native engine refuses
//! meshes with face-varying channels until this lands (see `Refiner::new`).
use super::{Level, Refinement};
use crate::options::Options;

/// One face-varying channel at one level.
#[derive(Debug, Clone, Default)]
pub struct FVarLevel {
    value_count: usize,
    face_values: Vec<u32>,
}

impl FVarLevel {
    /// Number of values.
    pub fn value_count(&self) -> usize {
        self.value_count
    }
    /// Value index of every face corner.
    pub fn face_values(&self) -> &[u32] {
        &self.face_values
    }
}

/// Base channel.
pub fn build_base(
    _level: &Level,
    _options: &Options,
    value_count: usize,
    indices: &[u32],
) -> FVarLevel {
    FVarLevel {
        value_count,
        face_values: indices.to_vec(),
    }
}

/// Child channel: unreachable while `Refiner::new` refuses face-varying channels.
pub fn refine(
    _parent: &Level,
    _child: &Level,
    _r: &Refinement,
    p: &FVarLevel,
    _options: &Options,
) -> FVarLevel {
    p.clone()
}
