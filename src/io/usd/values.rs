//! Attribute values: resolved at the requested time, converted from the
//! USD library's typed values to what the mapping needs, with typed errors
//! naming the file, prim and attribute.

use super::UsdWarning;
use super::time::value_at;
use crate::error::{Error, UsdError, UsdErrorKind};
use glam::DVec3;
use openusd::sdf::Value;
use openusd::usd;
use std::path::Path;

/// Where a mesh is read: the file, the prim, the time, the mode, and the
/// warnings gathered so far.
pub(super) struct Context<'a> {
    /// The file named by the caller.
    pub file: &'a Path,
    /// The prim's path.
    pub prim_path: String,
    /// The prim.
    pub prim: usd::Prim,
    /// [`UsdReadOptions::time`](super::UsdReadOptions::time).
    pub time: Option<f64>,
    /// [`UsdReadOptions::lenient`](super::UsdReadOptions::lenient).
    pub lenient: bool,
    /// Warnings about this prim.
    pub warnings: Vec<UsdWarning>,
}

impl Context<'_> {
    /// An error about `attribute` of this prim.
    pub fn error(&self, attribute: &str, kind: UsdErrorKind) -> Error {
        Error::from(UsdError {
            file: self.file.to_path_buf(),
            prim: self.prim_path.clone(),
            attribute: attribute.to_string(),
            kind,
        })
    }

    /// Records a warning about `attribute` of this prim.
    pub fn warn(&mut self, attribute: &str, message: String) {
        self.warnings.push(UsdWarning {
            prim: self.prim_path.clone(),
            attribute: attribute.to_string(),
            message,
        });
    }

    /// The value of `attribute` at the requested time (see
    /// [`UsdReadOptions::time`](super::UsdReadOptions::time)), or `None`
    /// when it has no value there (not authored, or blocked). At the
    /// default time an attribute with time samples but no default value has
    /// none, as in USD; a warning says so.
    pub fn value(&mut self, attribute: &str) -> Result<Option<Value>, Error> {
        let attr = self.prim.attribute(attribute);
        let value = match self.time {
            Some(t) => value_at(&attr, t).map_err(|kind| self.error(attribute, kind))?,
            None => {
                let value = attr
                    .get::<Value>()
                    .map_err(|e| self.error(attribute, library(e)))?
                    .filter(|v| !matches!(v, Value::ValueBlock));
                if value.is_none() && self.has_samples(attribute)? {
                    self.warn(
                        attribute,
                        "has time samples but no default value: at the default time it has \
                         none, as in USD (read at a time to use its samples)"
                            .to_string(),
                    );
                }
                value
            }
        };
        Ok(value)
    }

    /// Whether `attribute` has time samples.
    pub fn has_samples(&self, attribute: &str) -> Result<bool, Error> {
        self.prim
            .attribute(attribute)
            .num_time_samples()
            .map(|n| n > 0)
            .map_err(|e| self.error(attribute, library(e)))
    }

    /// A metadata field of `attribute` (`interpolation`, `elementSize`).
    pub fn metadata(&self, attribute: &str, key: &str) -> Result<Option<Value>, Error> {
        self.prim
            .attribute(attribute)
            .get_metadata::<Value>(key)
            .map_err(|e| self.error(attribute, library(e)))
    }

    /// A `WrongType` error about `attribute` holding `value`.
    pub fn wrong_type(&self, attribute: &str, expected: &'static str, value: &Value) -> Error {
        self.wrong_type_named(attribute, expected, type_name(value))
    }

    /// A `WrongType` error about `attribute` holding a value of type `found`.
    pub fn wrong_type_named(&self, attribute: &str, expected: &'static str, found: &str) -> Error {
        self.error(
            attribute,
            UsdErrorKind::WrongType {
                expected,
                found: found.to_string(),
            },
        )
    }

    /// A token (or string) attribute, or `fallback` when it has no value.
    pub fn token(&mut self, attribute: &str, fallback: &str) -> Result<String, Error> {
        match self.value(attribute)? {
            None => Ok(fallback.to_string()),
            Some(Value::Token(t)) => Ok(t.as_str().to_string()),
            Some(Value::String(s)) => Ok(s),
            Some(other) => Err(self.wrong_type(attribute, "token", &other)),
        }
    }

    /// An integer array attribute; empty when it has no value.
    pub fn ints(&mut self, attribute: &str) -> Result<Ints, Error> {
        match self.value(attribute)? {
            None => Ok(Ints::I32(Vec::new())),
            Some(value) => {
                Ints::from_value(value).map_err(|t| self.wrong_type_named(attribute, "int[]", t))
            }
        }
    }

    /// A float array attribute (sharpnesses); empty when it has no value.
    pub fn floats(&mut self, attribute: &str) -> Result<Vec<f32>, Error> {
        match self.value(attribute)? {
            None => Ok(Vec::new()),
            Some(Value::FloatVec(v)) => Ok(v),
            Some(Value::DoubleVec(v)) => Ok(v.into_iter().map(|x| x as f32).collect()),
            Some(Value::HalfVec(v)) => Ok(v.into_iter().map(|x| x.to_f32()).collect()),
            Some(other) => Err(self.wrong_type(attribute, "float[]", &other)),
        }
    }

    /// A 3-vector array attribute (points), or `None` when it has no value.
    pub fn points(&mut self, attribute: &str) -> Result<Option<Vec<DVec3>>, Error> {
        let convert = |a: [f64; 3]| DVec3::from_array(a);
        match self.value(attribute)? {
            None => Ok(None),
            Some(Value::Vec3fVec(v)) => Ok(Some(
                v.into_iter()
                    .map(|p| convert(<[f32; 3]>::from(p).map(f64::from)))
                    .collect(),
            )),
            Some(Value::Vec3dVec(v)) => Ok(Some(
                v.into_iter()
                    .map(|p| convert(<[f64; 3]>::from(p)))
                    .collect(),
            )),
            Some(Value::Vec3hVec(v)) => Ok(Some(
                v.into_iter()
                    .map(|p| convert(<[_; 3]>::from(p).map(|x| x.to_f64())))
                    .collect(),
            )),
            Some(other) => Err(self.wrong_type(attribute, "point3f[]", &other)),
        }
    }
}

/// An error of the USD library, with its causes.
pub(super) fn library(e: impl std::fmt::Display) -> UsdErrorKind {
    UsdErrorKind::Open(format!("{e:#}"))
}

/// The USD library's name of a value's type (`FloatVec`, `Token`).
pub(super) fn type_name(value: &Value) -> &'static str {
    value.into()
}

/// An integer array as authored: `int[]` kept as is, wider types widened.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Ints {
    /// `int[]`.
    I32(Vec<i32>),
    /// `int64[]`, `uint[]`, `uint64[]` (beyond `i64::MAX` saturated).
    I64(Vec<i64>),
}

impl Ints {
    /// The integers of an integer array value, or the name of the value's
    /// type.
    pub fn from_value(value: Value) -> Result<Ints, &'static str> {
        match value {
            Value::IntVec(v) => Ok(Ints::I32(v)),
            Value::Int64Vec(v) => Ok(Ints::I64(v)),
            Value::UintVec(v) => Ok(Ints::I64(v.into_iter().map(i64::from).collect())),
            Value::Uint64Vec(v) => Ok(Ints::I64(
                v.into_iter()
                    .map(|x| i64::try_from(x).unwrap_or(i64::MAX))
                    .collect(),
            )),
            other => Err(type_name(&other)),
        }
    }

    /// The number of integers.
    pub fn len(&self) -> usize {
        match self {
            Ints::I32(v) => v.len(),
            Ints::I64(v) => v.len(),
        }
    }

    /// The integers, widened.
    pub fn iter(&self) -> Box<dyn Iterator<Item = i64> + '_> {
        match self {
            Ints::I32(v) => Box::new(v.iter().map(|&x| i64::from(x))),
            Ints::I64(v) => Box::new(v.iter().copied()),
        }
    }

    /// The integer at `i`, if there is one.
    pub fn get(&self, i: usize) -> Option<i64> {
        match self {
            Ints::I32(v) => v.get(i).map(|&x| i64::from(x)),
            Ints::I64(v) => v.get(i).copied(),
        }
    }

    /// Checks that every integer is an index below `count` and returns them
    /// as `u32`, or the position and value of the first that is not.
    pub fn indices(&self, count: usize) -> Result<Vec<u32>, (usize, i64)> {
        let mut out = Vec::with_capacity(self.len());
        for (position, index) in self.iter().enumerate() {
            match u32::try_from(index) {
                Ok(i) if (i as usize) < count => out.push(i),
                _ => return Err((position, index)),
            }
        }
        Ok(out)
    }
}

/// A numeric array value as `f64`s: the number of components of its
/// element type and the flattened components, or `None` when the value is
/// not a numeric array (tokens, strings, booleans, matrices, quaternions).
pub(super) fn numeric(value: Value) -> Option<(usize, Vec<f64>)> {
    fn flat<T: Copy, const N: usize>(v: Vec<T>, f: impl Fn(T) -> [f64; N]) -> (usize, Vec<f64>) {
        (N, v.into_iter().flat_map(f).collect())
    }
    let h = |x: openusd::gf::f16| x.to_f64();
    Some(match value {
        Value::FloatVec(v) => flat(v, |x| [f64::from(x)]),
        Value::DoubleVec(v) => flat(v, |x| [x]),
        Value::HalfVec(v) => flat(v, |x| [h(x)]),
        Value::IntVec(v) => flat(v, |x| [f64::from(x)]),
        Value::UintVec(v) => flat(v, |x| [f64::from(x)]),
        Value::UcharVec(v) => flat(v, |x| [f64::from(x)]),
        Value::Vec2fVec(v) => flat(v, |p| <[f32; 2]>::from(p).map(f64::from)),
        Value::Vec2dVec(v) => flat(v, <[f64; 2]>::from),
        Value::Vec2hVec(v) => flat(v, |p| <[_; 2]>::from(p).map(h)),
        Value::Vec2iVec(v) => flat(v, |p| <[i32; 2]>::from(p).map(f64::from)),
        Value::Vec3fVec(v) => flat(v, |p| <[f32; 3]>::from(p).map(f64::from)),
        Value::Vec3dVec(v) => flat(v, <[f64; 3]>::from),
        Value::Vec3hVec(v) => flat(v, |p| <[_; 3]>::from(p).map(h)),
        Value::Vec3iVec(v) => flat(v, |p| <[i32; 3]>::from(p).map(f64::from)),
        Value::Vec4fVec(v) => flat(v, |p| <[f32; 4]>::from(p).map(f64::from)),
        Value::Vec4dVec(v) => flat(v, <[f64; 4]>::from),
        Value::Vec4hVec(v) => flat(v, |p| <[_; 4]>::from(p).map(h)),
        Value::Vec4iVec(v) => flat(v, |p| <[i32; 4]>::from(p).map(f64::from)),
        _ => return None,
    })
}
