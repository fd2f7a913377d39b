//! Attribute values at a time code, resolved as USD resolves them
//! (`pxr/usd/usd/interpolators.cpp`): the sample at the time, the first or
//! last sample outside their range, and between two samples the linear
//! interpolation of floating-point arrays of the same length — computed as
//! `GfLerp` computes it, so the values are USD's bit for bit — or the
//! earlier sample (held) for every other value.

use super::values::library;
use crate::error::UsdErrorKind;
use openusd::sdf::Value;
use openusd::usd;

/// The value of `attr` at `time`, or `None` when it has none there (not
/// authored, or blocked).
pub(super) fn value_at(attr: &usd::Attribute, time: f64) -> Result<Option<Value>, UsdErrorKind> {
    // The stage reads with held interpolation: `get_at` gives the sample at
    // or before a time (the first sample before the first one), or the
    // default value when there are no samples.
    let held = |t: f64| -> Result<Option<Value>, UsdErrorKind> {
        let value = attr
            .get_at::<Value>(usd::TimeCode::new(t))
            .map_err(library)?;
        Ok(value.filter(|v| !matches!(v, Value::ValueBlock)))
    };
    let Some((lower, upper)) = attr.bracketing_time_samples(time).map_err(library)? else {
        return held(time);
    };
    // `GfIsClose(lower, upper, 1e-6)`: one sample.
    if (lower - upper).abs() < 1e-6 {
        return held(lower);
    }
    let Some(low) = held(lower)? else {
        return Ok(None);
    };
    let Some(high) = held(upper)? else {
        return Ok(Some(low));
    };
    let alpha = (time - lower) / (upper - lower);
    if alpha == 0.0 {
        return Ok(Some(low));
    }
    Ok(Some(lerp(low, high, alpha)))
}

/// `Usd_Interpolate` of two samples: `GfLerp(alpha, a, b)`, that is
/// `(1 - alpha) * a + alpha * b`, element by element, for arrays of the same
/// type and length of `float`, `double` and their 2-, 3- and 4-vectors;
/// `lower` otherwise (half-precision values are held too).
///
/// The rounding is `GfLerp`'s: a `float` is interpolated in `double` and
/// rounded once; a `GfVec3f` term by term (`(1 - alpha) * a` and
/// `alpha * b` each rounded to `float`, then added in `float`); `double`s
/// and `GfVec3d`s in `double`.
fn lerp(lower: Value, upper: Value, alpha: f64) -> Value {
    fn arrays<T: Copy>(a: Vec<T>, b: Vec<T>, alpha: f64, f: impl Fn(T, T) -> T) -> Vec<T> {
        if alpha == 1.0 {
            return b;
        }
        a.into_iter().zip(b).map(|(a, b)| f(a, b)).collect()
    }
    let keep = 1.0 - alpha;
    // `float` and `double` scalars: in `double`, rounded once.
    let float = |a: f32, b: f32| (keep * f64::from(a) + alpha * f64::from(b)) as f32;
    let double = |a: f64, b: f64| keep * a + alpha * b;
    // A component of a `GfVecNf`: each term rounded to `float`.
    let component = |a: f32, b: f32| (f64::from(a) * keep) as f32 + (f64::from(b) * alpha) as f32;
    macro_rules! vectors {
        ($a:expr, $b:expr, $n:literal, $t:ty, $f:expr) => {
            arrays($a, $b, alpha, |a, b| {
                let (a, b) = (<[$t; $n]>::from(a), <[$t; $n]>::from(b));
                std::array::from_fn::<$t, $n, _>(|i| $f(a[i], b[i])).into()
            })
        };
    }
    match (lower, upper) {
        (Value::FloatVec(a), Value::FloatVec(b)) if a.len() == b.len() => {
            Value::FloatVec(arrays(a, b, alpha, float))
        }
        (Value::DoubleVec(a), Value::DoubleVec(b)) if a.len() == b.len() => {
            Value::DoubleVec(arrays(a, b, alpha, double))
        }
        (Value::Vec2fVec(a), Value::Vec2fVec(b)) if a.len() == b.len() => {
            Value::Vec2fVec(vectors!(a, b, 2, f32, component))
        }
        (Value::Vec3fVec(a), Value::Vec3fVec(b)) if a.len() == b.len() => {
            Value::Vec3fVec(vectors!(a, b, 3, f32, component))
        }
        (Value::Vec4fVec(a), Value::Vec4fVec(b)) if a.len() == b.len() => {
            Value::Vec4fVec(vectors!(a, b, 4, f32, component))
        }
        (Value::Vec2dVec(a), Value::Vec2dVec(b)) if a.len() == b.len() => {
            Value::Vec2dVec(vectors!(a, b, 2, f64, double))
        }
        (Value::Vec3dVec(a), Value::Vec3dVec(b)) if a.len() == b.len() => {
            Value::Vec3dVec(vectors!(a, b, 3, f64, double))
        }
        (Value::Vec4dVec(a), Value::Vec4dVec(b)) if a.len() == b.len() => {
            Value::Vec4dVec(vectors!(a, b, 4, f64, double))
        }
        (lower, _) => lower,
    }
}
