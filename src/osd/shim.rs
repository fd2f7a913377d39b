//! Calling the C shim: error buffers, its typed (`f32`/`f64`) entry points,
//! and the checks every call makes first.

use super::ERR_LEN;
use super::TopologyRefiner;
use super::ffi;
use crate::error::{Buffer, Error, OsdError, OsdErrorKind, Result};
use std::ffi::CStr;
use std::os::raw::c_char;

/// An error-message buffer for one shim call.
pub struct ErrBuf([c_char; ERR_LEN]);

impl ErrBuf {
    pub fn new() -> Self {
        ErrBuf([0; ERR_LEN])
    }

    pub fn ptr(&mut self) -> *mut c_char {
        self.0.as_mut_ptr()
    }

    /// Runs one shim call with this buffer and turns its status into a `Result`.
    pub fn run(&mut self, call: impl FnOnce(*mut c_char) -> i32) -> Result<()> {
        let status = call(self.ptr());
        self.check(status)
    }

    /// Turns a shim status into a `Result`.
    pub fn check(&self, status: i32) -> Result<()> {
        if status == ffi::SDV_OK {
            return Ok(());
        }
        // SAFETY: the shim always NUL-terminates within ERR_LEN (and the
        // buffer starts zeroed), so the bytes form a valid C string.
        let msg = unsafe { CStr::from_ptr(self.0.as_ptr()) }
            .to_string_lossy()
            .into_owned();
        use crate::error::OsdErrorKind as Kind;
        let (kind, message) = match status {
            ffi::SDV_ERR_INVALID => (Kind::Refused, msg),
            ffi::SDV_ERR_OSD => (Kind::Failed, msg),
            ffi::SDV_ERR_UNSAFE => (Kind::Unsafe, msg),
            ffi::SDV_ERR_CAPACITY => (Kind::Internal, format!("internal buffer mismatch: {msg}")),
            _ if msg.is_empty() => (Kind::Internal, format!("shim status {status}")),
            _ => (Kind::Internal, msg),
        };
        Err(Error::Osd(crate::error::OsdError { kind, message }))
    }
}

/// The shim's entry points of one real type (`f32`, `f64`); private.
pub trait ShimReal: Sized {
    #[allow(clippy::too_many_arguments)]
    fn interpolate(
        r: &TopologyRefiner,
        kind: i32,
        channel: i32,
        level: i32,
        width: i32,
        src: &[Self],
        dst: &mut [Self],
        err: &mut ErrBuf,
    ) -> i32;
    fn limit(
        r: &TopologyRefiner,
        width: i32,
        src: &[Self],
        out: [&mut [Self]; 3],
        err: &mut ErrBuf,
    ) -> i32;
    fn limit_fvar(
        r: &TopologyRefiner,
        channel: i32,
        width: i32,
        src: &[Self],
        dst: &mut [Self],
        err: &mut ErrBuf,
    ) -> i32;
}

/// Evaluates `$body` with `$S` standing for the shim's real type of `$T`
/// (`f32` or `f64`, the two types [`Real`] is sealed to), so that `[T]`
/// slices can be cast to `[$S]` for the shim's typed entry points.
macro_rules! with_shim_type {
    ($T:ty, |$S:ident| $body:expr) => {
        match <$T as Real>::PRECISION {
            Precision::F32 => {
                type $S = f32;
                $body
            }
            Precision::F64 => {
                type $S = f64;
                $body
            }
        }
    };
}
pub(super) use with_shim_type;

macro_rules! impl_real {
    ($t:ty, $interp:ident, $limit:ident, $limit_fvar:ident) => {
        impl ShimReal for $t {
            fn interpolate(
                r: &TopologyRefiner,
                kind: i32,
                channel: i32,
                level: i32,
                width: i32,
                src: &[Self],
                dst: &mut [Self],
                err: &mut ErrBuf,
            ) -> i32 {
                // SAFETY: the raw refiner is live for `r`'s lifetime; the
                // shim checks both lengths against the refiner's counts
                // before reading or writing the buffers.
                unsafe {
                    ffi::$interp(
                        r.raw.as_ptr(),
                        kind,
                        channel,
                        level,
                        width,
                        src.as_ptr(),
                        src.len(),
                        dst.as_mut_ptr(),
                        dst.len(),
                        err.ptr(),
                        ERR_LEN,
                    )
                }
            }
            fn limit(
                r: &TopologyRefiner,
                width: i32,
                src: &[Self],
                out: [&mut [Self]; 3],
                err: &mut ErrBuf,
            ) -> i32 {
                let [pos, t1, t2] = out;
                if t1.len() != pos.len() || t2.len() != pos.len() {
                    return ffi::SDV_ERR_CAPACITY;
                }
                // SAFETY: as above; the three outputs have the same length,
                // which the shim checks against the last level's count.
                unsafe {
                    ffi::$limit(
                        r.raw.as_ptr(),
                        width,
                        src.as_ptr(),
                        src.len(),
                        pos.as_mut_ptr(),
                        t1.as_mut_ptr(),
                        t2.as_mut_ptr(),
                        pos.len(),
                        err.ptr(),
                        ERR_LEN,
                    )
                }
            }
            fn limit_fvar(
                r: &TopologyRefiner,
                channel: i32,
                width: i32,
                src: &[Self],
                dst: &mut [Self],
                err: &mut ErrBuf,
            ) -> i32 {
                // SAFETY: as above.
                unsafe {
                    ffi::$limit_fvar(
                        r.raw.as_ptr(),
                        channel,
                        width,
                        src.as_ptr(),
                        src.len(),
                        dst.as_mut_ptr(),
                        dst.len(),
                        err.ptr(),
                        ERR_LEN,
                    )
                }
            }
        }
    };
}

impl_real!(f32, sdv_interpolate_f32, sdv_limit_f32, sdv_limit_fvar_f32);
impl_real!(f64, sdv_interpolate_f64, sdv_limit_f64, sdv_limit_fvar_f64);

pub(super) fn to_i32(n: usize, what: &'static str) -> Result<i32> {
    i32::try_from(n).map_err(|_| Error::TooLarge {
        what,
        count: n,
        bits: 32,
    })
}

/// Refuses a buffer of `got` values where `expected` are needed.
pub(super) fn check_length(buffer: Buffer, expected: usize, got: usize) -> Result<()> {
    if got == expected {
        Ok(())
    } else {
        Err(Error::BufferLength {
            buffer,
            expected,
            got,
        })
    }
}

/// A defect of the bridge (an object it should have returned), as an error.
pub(super) fn internal(message: &str) -> Error {
    Error::Osd(OsdError {
        kind: OsdErrorKind::Internal,
        message: message.to_string(),
    })
}
