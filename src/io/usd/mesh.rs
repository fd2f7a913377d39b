//! One `Mesh` prim to a [`Mesh`] and its [`Options`], as USD's OpenSubdiv
//! adapter (`pxr/imaging/pxOsd/refinerFactory.cpp`) reads it: the scheme and
//! option tokens with `UsdGeomMesh`'s fallbacks, the faces, creases,
//! corners and holes, then the primvars ([`super::primvars`]).

use super::UsdMesh;
use super::primvars;
use super::values::{Context, Ints};
use crate::error::{Error, UsdErrorKind};
use crate::mesh::{Corner, Crease, Mesh, MeshError, MeshWarning, SHARPNESS_INFINITE};
use crate::options::{
    BoundaryInterpolation, CreasingMethod, FVarLinearInterpolation, Options, Scheme,
    TriangleSubdivision,
};

/// What one `Mesh` prim gives.
pub(super) enum Outcome {
    /// A subdivision mesh.
    Mesh(Box<UsdMesh>),
    /// A mesh that is not read, and why.
    Skipped(String),
}

/// Reads the mesh of `ctx`'s prim.
pub(super) fn read_mesh(ctx: &mut Context<'_>) -> Result<Outcome, Error> {
    let scheme = match ctx.token("subdivisionScheme", "catmullClark")?.as_str() {
        "catmullClark" => Scheme::Catmark,
        "loop" => Scheme::Loop,
        "bilinear" => Scheme::Bilinear,
        "none" => {
            return Ok(Outcome::Skipped(
                "subdivisionScheme is \"none\": not subdivided".to_string(),
            ));
        }
        other => return Err(unknown(ctx, "subdivisionScheme", other, SCHEMES)),
    };
    let options = read_options(ctx, scheme)?;
    let left_handed = match ctx.token("orientation", "rightHanded")?.as_str() {
        "rightHanded" => false,
        "leftHanded" => true,
        other => return Err(unknown(ctx, "orientation", other, ORIENTATIONS)),
    };

    let (face_offsets, indices) = read_faces(ctx)?;
    let face_count = face_offsets.len() - 1;
    if face_count == 0 {
        return Ok(Outcome::Skipped("the mesh has no faces".to_string()));
    }
    let Some(positions) = ctx.points("points")? else {
        let kind = UsdErrorKind::Missing {
            faces: face_count,
            time_samples: ctx.time.is_none() && ctx.has_samples("points")?,
        };
        return Err(ctx.error("points", kind));
    };
    let face_vertices = indices
        .indices(positions.len())
        .map_err(|(position, index)| {
            ctx.error(
                "faceVertexIndices",
                UsdErrorKind::IndexOutOfRange {
                    position,
                    index,
                    count: positions.len(),
                    of: "points",
                },
            )
        })?;
    drop(indices);
    let creases = read_creases(ctx, positions.len())?;
    let corners = read_corners(ctx, positions.len())?;
    let holes = ctx
        .ints("holeIndices")?
        .indices(face_count)
        .map_err(|(position, index)| {
            ctx.error(
                "holeIndices",
                UsdErrorKind::IndexOutOfRange {
                    position,
                    index,
                    count: face_count,
                    of: "faces",
                },
            )
        })?;
    let primvars = primvars::read(ctx, positions.len(), face_vertices.len())?;

    let mesh = Mesh {
        positions,
        face_offsets,
        face_vertices,
        creases,
        corners,
        holes,
        fvar_channels: primvars.channels,
        left_handed,
    };
    let validation = mesh
        .validate()
        .map_err(|e| invalid_mesh(ctx, &primvars.fvar_names, e))?;
    for warning in validation.warnings {
        match warning {
            MeshWarning::CreaseWithoutEdge { v0, v1, .. } => ctx.warn(
                "creaseIndices",
                format!(
                    "points {v0} and {v1} share no edge: that crease edge is ignored, as \
                     OpenSubdiv ignores it"
                ),
            ),
        }
    }
    Ok(Outcome::Mesh(Box::new(UsdMesh {
        path: ctx.prim_path.clone(),
        mesh,
        options,
        fvar_names: primvars.fvar_names,
        primvars: primvars.primvars,
    })))
}

const SCHEMES: &str = "catmullClark, loop, bilinear, none";
const ORIENTATIONS: &str = "rightHanded, leftHanded";
const BOUNDARIES: &str = "none, edgeOnly, edgeAndCorner";
const FVARS: &str = "none, cornersOnly, cornersPlus1, cornersPlus2, boundaries, all";
const TRIANGLES: &str = "catmullClark, smooth";

fn unknown(ctx: &Context<'_>, attribute: &str, token: &str, allowed: &'static str) -> Error {
    ctx.error(
        attribute,
        UsdErrorKind::UnknownToken {
            token: token.to_string(),
            allowed,
        },
    )
}

/// The options of a mesh of `scheme`: `UsdGeomMesh`'s tokens and
/// fallbacks; bilinear meshes take edge-and-corner boundaries whatever is
/// authored (the token is still checked), as `pxOsd` forces them.
fn read_options(ctx: &mut Context<'_>, scheme: Scheme) -> Result<Options, Error> {
    let boundary = match ctx.token("interpolateBoundary", "edgeAndCorner")?.as_str() {
        "none" => BoundaryInterpolation::None,
        "edgeOnly" => BoundaryInterpolation::EdgeOnly,
        "edgeAndCorner" => BoundaryInterpolation::EdgeAndCorner,
        other => return Err(unknown(ctx, "interpolateBoundary", other, BOUNDARIES)),
    };
    let fvar = match ctx
        .token("faceVaryingLinearInterpolation", "cornersPlus1")?
        .as_str()
    {
        "none" => FVarLinearInterpolation::None,
        "cornersOnly" => FVarLinearInterpolation::CornersOnly,
        "cornersPlus1" => FVarLinearInterpolation::CornersPlus1,
        "cornersPlus2" => FVarLinearInterpolation::CornersPlus2,
        "boundaries" => FVarLinearInterpolation::Boundaries,
        "all" => FVarLinearInterpolation::All,
        other => return Err(unknown(ctx, "faceVaryingLinearInterpolation", other, FVARS)),
    };
    let triangles = match ctx
        .token("triangleSubdivisionRule", "catmullClark")?
        .as_str()
    {
        "catmullClark" => TriangleSubdivision::Catmark,
        "smooth" => TriangleSubdivision::Smooth,
        other => return Err(unknown(ctx, "triangleSubdivisionRule", other, TRIANGLES)),
    };
    Ok(Options {
        scheme,
        boundary: if scheme == Scheme::Bilinear {
            BoundaryInterpolation::EdgeAndCorner
        } else {
            boundary
        },
        fvar,
        creasing: CreasingMethod::Uniform,
        triangles,
    })
}

/// `faceVertexCounts` as face offsets, with `faceVertexIndices` unchecked
/// against the points (their sum checked against its length).
fn read_faces(ctx: &mut Context<'_>) -> Result<(Vec<u32>, Ints), Error> {
    let counts = ctx.ints("faceVertexCounts")?;
    let indices = ctx.ints("faceVertexIndices")?;
    let too_large = |what, count| UsdErrorKind::TooLarge { what, count };
    if indices.len() > u32::MAX as usize {
        return Err(ctx.error(
            "faceVertexIndices",
            too_large("face corners", indices.len()),
        ));
    }
    if counts.len() >= u32::MAX as usize {
        return Err(ctx.error("faceVertexCounts", too_large("faces", counts.len())));
    }
    let mut sum: u64 = 0;
    for (position, count) in counts.iter().enumerate() {
        if count < 0 {
            return Err(ctx.error(
                "faceVertexCounts",
                UsdErrorKind::NegativeCount { position, count },
            ));
        }
        sum = sum.saturating_add(count as u64);
    }
    if sum != indices.len() as u64 {
        return Err(ctx.error(
            "faceVertexCounts",
            UsdErrorKind::FaceVertexCounts {
                sum,
                indices: indices.len(),
            },
        ));
    }
    // Every count is at most the number of indices, itself below 2^32.
    let mut offsets = Vec::with_capacity(counts.len() + 1);
    offsets.push(0u32);
    let mut end = 0u32;
    for count in counts.iter() {
        end += count as u32;
        offsets.push(end);
    }
    Ok((offsets, indices))
}

/// Reports a malformed crease or corner: an error, or in lenient mode a
/// warning saying what is dropped.
fn malformed(
    ctx: &mut Context<'_>,
    attribute: &str,
    kind: UsdErrorKind,
    dropped: &str,
) -> Result<(), Error> {
    if ctx.lenient {
        ctx.warn(attribute, format!("{kind}: {dropped}"));
        Ok(())
    } else {
        Err(ctx.error(attribute, kind))
    }
}

/// A sharpness as `pxOsd` passes it to OpenSubdiv, `max(0, s)` (so NaN and
/// negative values are smooth), with `+inf` as
/// [`SHARPNESS_INFINITE`] (OpenSubdiv treats both alike).
fn sharpness(s: f32) -> f32 {
    if s.is_nan() || s < 0.0 {
        0.0
    } else if s.is_infinite() {
        SHARPNESS_INFINITE
    } else {
        s
    }
}

/// `creaseIndices`, `creaseLengths` and `creaseSharpnesses` as one
/// [`Crease`] per crease edge; sharpnesses are one per crease when there are
/// as many as creases, else one per crease edge.
fn read_creases(ctx: &mut Context<'_>, points: usize) -> Result<Vec<Crease>, Error> {
    let indices = ctx.ints("creaseIndices")?;
    let lengths = ctx.ints("creaseLengths")?;
    let sharpnesses = ctx.floats("creaseSharpnesses")?;
    const ALL: &str = "every crease is dropped";
    if let Some((position, count)) = lengths.iter().enumerate().find(|&(_, l)| l < 0) {
        let kind = UsdErrorKind::NegativeCount { position, count };
        malformed(ctx, "creaseLengths", kind, ALL)?;
        return Ok(Vec::new());
    }
    let sum = lengths.iter().fold(0u64, |s, l| s.saturating_add(l as u64));
    if sum != indices.len() as u64 {
        let kind = UsdErrorKind::CreaseLengths {
            sum,
            indices: indices.len(),
        };
        malformed(ctx, "creaseLengths", kind, ALL)?;
        return Ok(Vec::new());
    }
    // Every length is at most the number of indices now.
    let edges: usize = lengths.iter().map(|l| (l as usize).saturating_sub(1)).sum();
    let per_crease = sharpnesses.len() == lengths.len();
    if !per_crease && sharpnesses.len() != edges {
        let kind = UsdErrorKind::CreaseSharpnessCount {
            found: sharpnesses.len(),
            creases: lengths.len(),
            edges,
        };
        malformed(ctx, "creaseSharpnesses", kind, ALL)?;
        return Ok(Vec::new());
    }
    let mut creases = Vec::with_capacity(edges);
    let (mut start, mut next_sharpness) = (0usize, 0usize);
    for (crease, length) in lengths.iter().enumerate() {
        let length_usize = length as usize;
        if length < 2 {
            let kind = UsdErrorKind::CreaseTooShort { crease, length };
            malformed(
                ctx,
                "creaseLengths",
                kind,
                &format!("crease {crease} is dropped"),
            )?;
        }
        for j in 0..length_usize.saturating_sub(1) {
            let s = sharpnesses
                .get(if per_crease {
                    next_sharpness
                } else {
                    next_sharpness + j
                })
                .copied()
                .unwrap_or(0.0);
            let mut ends = [0u32; 2];
            let mut valid = true;
            for (end, position) in ends.iter_mut().zip([start + j, start + j + 1]) {
                let index = indices.get(position).unwrap_or(-1);
                match u32::try_from(index) {
                    Ok(v) if (v as usize) < points => *end = v,
                    _ => {
                        let kind = UsdErrorKind::IndexOutOfRange {
                            position,
                            index,
                            count: points,
                            of: "points",
                        };
                        let dropped = format!("the edge {} of crease {crease} is dropped", j);
                        malformed(ctx, "creaseIndices", kind, &dropped)?;
                        valid = false;
                    }
                }
            }
            if valid {
                creases.push(Crease {
                    vertices: ends,
                    sharpness: sharpness(s),
                });
            }
        }
        next_sharpness += if per_crease {
            1
        } else {
            length_usize.saturating_sub(1)
        };
        start += length_usize;
    }
    Ok(creases)
}

/// `cornerIndices` and `cornerSharpnesses` as [`Corner`]s.
fn read_corners(ctx: &mut Context<'_>, points: usize) -> Result<Vec<Corner>, Error> {
    let indices = ctx.ints("cornerIndices")?;
    let sharpnesses = ctx.floats("cornerSharpnesses")?;
    if sharpnesses.len() != indices.len() {
        let kind = UsdErrorKind::CornerSharpnessCount {
            found: sharpnesses.len(),
            corners: indices.len(),
        };
        malformed(ctx, "cornerSharpnesses", kind, "every corner is dropped")?;
        return Ok(Vec::new());
    }
    let mut corners = Vec::with_capacity(indices.len());
    for ((position, index), &s) in indices.iter().enumerate().zip(&sharpnesses) {
        match u32::try_from(index) {
            Ok(vertex) if (vertex as usize) < points => corners.push(Corner {
                vertex,
                sharpness: sharpness(s),
            }),
            _ => {
                let kind = UsdErrorKind::IndexOutOfRange {
                    position,
                    index,
                    count: points,
                    of: "points",
                };
                malformed(ctx, "cornerIndices", kind, "that corner is dropped")?;
            }
        }
    }
    Ok(corners)
}

/// A [`Mesh::validate`] error as an error naming the attribute it comes
/// from.
fn invalid_mesh(ctx: &Context<'_>, fvar_names: &[String], error: MeshError) -> Error {
    let attribute = match &error {
        MeshError::BadOffsets(_)
        | MeshError::FaceTooSmall { .. }
        | MeshError::FaceTooLarge { .. } => "faceVertexCounts".to_string(),
        MeshError::VertexOutOfRange { .. } => "faceVertexIndices".to_string(),
        MeshError::NonFiniteCoordinate { .. } => "points".to_string(),
        MeshError::CreaseVertexOutOfRange { .. } | MeshError::CreaseWithoutEdge { .. } => {
            "creaseIndices".to_string()
        }
        MeshError::CornerVertexOutOfRange { .. } => "cornerIndices".to_string(),
        MeshError::HoleOutOfRange { .. } => "holeIndices".to_string(),
        MeshError::BadSharpness { what, .. } if what.starts_with("corner") => {
            "cornerSharpnesses".to_string()
        }
        MeshError::BadSharpness { .. } => "creaseSharpnesses".to_string(),
        MeshError::BadFVarChannel { channel, .. } => fvar_names
            .get(*channel)
            .map_or_else(String::new, |name| format!("primvars:{name}")),
        _ => String::new(),
    };
    ctx.error(&attribute, UsdErrorKind::Mesh(error))
}
