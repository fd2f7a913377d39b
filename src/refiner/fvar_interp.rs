//! Face-varying interpolation — in progress.
use super::Refiner;
use crate::error::{Error, Result};
use crate::real::Real;

impl Refiner {
    /// Interpolates face-varying `channel` from level `level - 1` to `level`
    /// (not available yet in the native engine).
    pub fn interpolate_face_varying<T: Real>(
        &self,
        _channel: usize,
        _level: u32,
        _width: usize,
        _src: &[T],
    ) -> Result<Vec<T>> {
        Err(Error::Unavailable(
            "native face-varying interpolation is still being written".into(),
        ))
    }
}
