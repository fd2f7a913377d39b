//! A mesh's primvars: face-varying ones as face-varying channels, vertex
//! and varying ones as [`UsdPrimvar`]s, constant and uniform ones not read.
//! Values are counted in elements of `elementSize` values, as
//! `UsdGeomPrimvar` counts them; indexed primvars (`primvars:NAME:indices`)
//! index those elements.

use super::values::{Context, library, numeric, type_name};
use super::{UsdInterpolation, UsdPrimvar, is_primvar_name};
use crate::error::{Error, UsdErrorKind};
use crate::mesh::FVarChannel;
use openusd::sdf::Value;

/// The primvars of one mesh.
pub(super) struct Primvars {
    /// The face-varying channels, channel 0 first.
    pub channels: Vec<FVarChannel>,
    /// Their primvar names.
    pub fvar_names: Vec<String>,
    /// The vertex and varying primvars, by name.
    pub primvars: Vec<UsdPrimvar>,
}

const INTERPOLATIONS: &str = "constant, uniform, varying, vertex, faceVarying";

/// Reads the primvars of `ctx`'s prim, whose mesh has `points` points and
/// `corners` face corners.
pub(super) fn read(
    ctx: &mut Context<'_>,
    points: usize,
    corners: usize,
) -> Result<Primvars, Error> {
    let attributes = ctx
        .prim
        .attributes()
        .map_err(|e| ctx.error("", library(e)))?;
    let prefix = format!("{}.", ctx.prim_path);
    let mut names: Vec<String> = attributes
        .iter()
        .filter_map(|a| a.path().as_str().strip_prefix(&prefix).map(str::to_string))
        .filter(|name| name.starts_with("primvars:") && !name.ends_with(":indices"))
        .collect();
    names.sort();
    names.dedup();

    let mut fvar: Vec<(String, FVarChannel)> = Vec::new();
    let mut primvars = Vec::new();
    for attribute in names {
        if !is_primvar_name(&attribute["primvars:".len()..]) {
            ctx.warn(&attribute, "is not a primvar name: ignored".to_string());
            continue;
        }
        let Some(read) = read_one(ctx, &attribute, points, corners)? else {
            continue;
        };
        let name = attribute["primvars:".len()..].to_string();
        match read.interpolation {
            UsdInterpolation::FaceVarying => fvar.push((
                name,
                FVarChannel {
                    width: read.width,
                    indices: read
                        .indices
                        .unwrap_or_else(|| (0..corners as u32).collect()),
                    values: read.values,
                },
            )),
            interpolation => {
                let values = match read.indices {
                    None => read.values,
                    Some(indices) => indices
                        .iter()
                        .flat_map(|&i| {
                            let start = i as usize * read.width;
                            read.values
                                .get(start..start + read.width)
                                .unwrap_or(&[])
                                .iter()
                                .copied()
                        })
                        .collect(),
                };
                primvars.push(UsdPrimvar {
                    name,
                    interpolation,
                    width: read.width,
                    values,
                });
            }
        }
    }

    // Channel 0: `st`, or else the only two-component face-varying primvar.
    let first = fvar.iter().position(|(name, _)| name == "st").or_else(|| {
        let mut pairs = fvar.iter().enumerate().filter(|(_, (_, c))| c.width == 2);
        match (pairs.next(), pairs.next()) {
            (Some((i, _)), None) => Some(i),
            _ => None,
        }
    });
    if let Some(i) = first {
        let channel = fvar.remove(i);
        fvar.insert(0, channel);
    }
    let (fvar_names, channels) = fvar.into_iter().unzip();
    Ok(Primvars {
        channels,
        fvar_names,
        primvars,
    })
}

/// One primvar's values, checked against its interpolation.
struct Read {
    interpolation: UsdInterpolation,
    /// Values per element.
    width: usize,
    /// The values, `width` per element.
    values: Vec<f64>,
    /// The element of each point or corner, when indexed (checked).
    indices: Option<Vec<u32>>,
}

/// Reads `attribute` (`primvars:NAME`), or `None` when it is constant or
/// uniform, has no value, or holds no numbers (with a warning).
fn read_one(
    ctx: &mut Context<'_>,
    attribute: &str,
    points: usize,
    corners: usize,
) -> Result<Option<Read>, Error> {
    let interpolation = match ctx.metadata(attribute, "interpolation")? {
        None => UsdInterpolation::Constant,
        Some(Value::Token(t)) => token(ctx, attribute, t.as_str())?,
        Some(Value::String(s)) => token(ctx, attribute, &s)?,
        Some(other) => return Err(ctx.wrong_type(attribute, "token (interpolation)", &other)),
    };
    let expected = match interpolation {
        UsdInterpolation::Constant | UsdInterpolation::Uniform => return Ok(None),
        UsdInterpolation::Vertex | UsdInterpolation::Varying => points,
        UsdInterpolation::FaceVarying => corners,
    };
    let element_size = match ctx.metadata(attribute, "elementSize")? {
        None => 1,
        Some(value) => match integer(&value) {
            Some(n) => n,
            None => return Err(ctx.wrong_type(attribute, "int (elementSize)", &value)),
        },
    };
    let Some(value) = ctx.value(attribute)? else {
        return Ok(None);
    };
    let found = type_name(&value);
    let Some((components, values)) = numeric(value) else {
        ctx.warn(
            attribute,
            format!("holds {found} values, not numbers: the primvar is ignored"),
        );
        return Ok(None);
    };
    let scalars = values.len() / components;
    let bad_size = || {
        ctx.error(
            attribute,
            UsdErrorKind::ElementSize {
                element_size,
                values: scalars,
            },
        )
    };
    let size = usize::try_from(element_size)
        .ok()
        .filter(|&n| n >= 1 && scalars % n == 0)
        .ok_or_else(bad_size)?;
    let width = components.checked_mul(size).ok_or_else(bad_size)?;
    let elements = scalars / size;
    let count = |found| UsdErrorKind::PrimvarCount {
        interpolation: interpolation.token(),
        found,
        expected,
    };
    let indices_name = format!("{attribute}:indices");
    let indices = match ctx.value(&indices_name)? {
        None => {
            if elements != expected {
                return Err(ctx.error(attribute, count(elements)));
            }
            None
        }
        Some(value) => {
            let ints = super::values::Ints::from_value(value)
                .map_err(|t| ctx.wrong_type_named(&indices_name, "int[]", t))?;
            if ints.len() != expected {
                return Err(ctx.error(&indices_name, count(ints.len())));
            }
            let indices = ints.indices(elements).map_err(|(position, index)| {
                ctx.error(
                    &indices_name,
                    UsdErrorKind::IndexOutOfRange {
                        position,
                        index,
                        count: elements,
                        of: "values",
                    },
                )
            })?;
            Some(indices)
        }
    };
    Ok(Some(Read {
        interpolation,
        width,
        values,
        indices,
    }))
}

fn token(ctx: &Context<'_>, attribute: &str, token: &str) -> Result<UsdInterpolation, Error> {
    UsdInterpolation::from_token(token).ok_or_else(|| {
        ctx.error(
            attribute,
            UsdErrorKind::UnknownToken {
                token: token.to_string(),
                allowed: INTERPOLATIONS,
            },
        )
    })
}

/// An integer metadata value.
fn integer(value: &Value) -> Option<i64> {
    match *value {
        Value::Int(n) => Some(i64::from(n)),
        Value::Int64(n) => Some(n),
        Value::Uint(n) => Some(i64::from(n)),
        Value::Uint64(n) => i64::try_from(n).ok(),
        Value::Uchar(n) => Some(i64::from(n)),
        _ => None,
    }
}
