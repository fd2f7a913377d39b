//! The engine-independent result of a uniform refinement.

use crate::error::{Error, Result};
use crate::level::LevelTopology;
use crate::mesh::Mesh;
use crate::options::{MAX_LEVEL, Options, Scheme, UniformOptions};
use glam::DVec3;
use std::fmt;
use std::str::FromStr;

/// The floating-point type primvars are interpolated in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Precision {
    /// Single precision (`f32`), OpenSubdiv's usual choice.
    F32,
    /// Double precision (`f64`).
    #[default]
    F64,
}

impl Precision {
    /// The name used on the command line: `f32` or `f64`.
    pub fn name(self) -> &'static str {
        match self {
            Precision::F32 => "f32",
            Precision::F64 => "f64",
        }
    }
}

impl fmt::Display for Precision {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Precision {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        match s {
            "f32" => Ok(Precision::F32),
            "f64" => Ok(Precision::F64),
            _ => Err(format!("unknown precision '{s}' (expected f32 or f64)")),
        }
    }
}

/// Limit values and both tangents of one primvar (`width` components per
/// vertex) at the vertices of one level.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LimitData<T> {
    /// Limit values, `width` per vertex.
    pub positions: Vec<T>,
    /// First tangents, `width` per vertex.
    pub du: Vec<T>,
    /// Second tangents, `width` per vertex.
    pub dv: Vec<T>,
}

/// Limit positions, tangents and face-varying values at the vertices of one level.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Limit {
    /// Limit position of every vertex.
    pub positions: Vec<DVec3>,
    /// First tangent (`du`) of every vertex.
    pub du: Vec<DVec3>,
    /// Second tangent (`dv`) of every vertex.
    pub dv: Vec<DVec3>,
    /// Limit values of every face-varying channel, flattened like [`crate::FVarChannel::values`].
    pub fvar_values: Vec<Vec<f64>>,
}

impl Limit {
    /// Unit normals `du × dv` (zero where the tangents are degenerate).
    pub fn normals(&self) -> Vec<DVec3> {
        self.du
            .iter()
            .zip(&self.dv)
            .map(|(a, b)| a.cross(*b).normalize_or_zero())
            .collect()
    }
}

/// A mesh refined uniformly: the topology and the interpolated data of every level.
#[derive(Debug, Clone, PartialEq)]
pub struct Refinement {
    /// The options the mesh was refined with.
    pub options: Options,
    /// The uniform refinement options.
    pub uniform: UniformOptions,
    /// The precision primvars were interpolated in.
    pub precision: Precision,
    /// Topology of levels `0..=uniform.level`.
    pub levels: Vec<LevelTopology>,
    /// Vertex positions of every level.
    pub positions: Vec<Vec<DVec3>>,
    /// Widths of the face-varying channels.
    pub fvar_widths: Vec<usize>,
    /// Face-varying values of every level and channel: `fvar_values[level][channel]`.
    pub fvar_values: Vec<Vec<Vec<f64>>>,
    /// Limit data at the last level, when it was asked for.
    pub limit: Option<Limit>,
}

impl Refinement {
    /// The topology of the last level.
    pub fn last_level(&self) -> &LevelTopology {
        self.levels
            .last()
            .expect("a refinement has at least level 0")
    }

    /// The positions of the last level.
    pub fn last_positions(&self) -> &[DVec3] {
        self.positions.last().map(Vec::as_slice).unwrap_or(&[])
    }

    /// The face-varying values of `channel` at the last level.
    pub fn last_fvar(&self, channel: usize) -> Option<&[f64]> {
        self.fvar_values.last()?.get(channel).map(Vec::as_slice)
    }
}

/// Refuses a level before anything is allocated: above [`MAX_LEVEL`], one whose
/// face-vertex count would not fit OpenSubdiv's 32-bit indices, or one whose
/// estimated memory exceeds what this machine has available.
pub fn check_level(mesh: &Mesh, options: &Options, level: u32) -> Result<()> {
    check_level_counts(
        mesh.face_count(),
        mesh.face_vertices.len(),
        options.scheme,
        level,
    )
}

/// Bytes per refined face corner and per refined vertex that a refinement
/// needs, roughly (topology tables of every level plus f64 positions).
const BYTES_PER_CORNER: f64 = 40.0;
const BYTES_PER_VERTEX: f64 = 64.0;

/// [`check_level`] from the base counts alone.
pub fn check_level_counts(faces: usize, corners: usize, scheme: Scheme, level: u32) -> Result<()> {
    if level > MAX_LEVEL {
        return Err(Error::Level {
            level,
            reason: format!("the deepest supported level is {MAX_LEVEL}"),
        });
    }
    if level == 0 {
        return Ok(());
    }
    // After one level every face has become quads (one per corner) or, under
    // Loop, four triangles; each later level multiplies the faces by four.
    let first = match scheme {
        Scheme::Loop => 4.0 * faces as f64 * 3.0,
        _ => corners as f64 * 4.0,
    };
    let face_vertices = first * 4f64.powi(level as i32 - 1);
    if face_vertices > i32::MAX as f64 {
        return Err(Error::Level {
            level,
            reason: format!(
                "level {level} of this mesh has about {face_vertices:.3e} face corners, \
                 more than 32-bit indices address"
            ),
        });
    }
    // All levels together hold about 4/3 of the last one; a quad mesh has
    // about as many vertices as faces.
    let all_corners = face_vertices * 4.0 / 3.0;
    let bytes = all_corners * BYTES_PER_CORNER + all_corners / 4.0 * BYTES_PER_VERTEX;
    if let Some(available) = available_memory() {
        if bytes > available as f64 {
            return Err(Error::Level {
                level,
                reason: format!(
                    "level {level} of this mesh needs about {:.1} GiB, more than the {:.1} GiB available",
                    bytes / GIB,
                    available as f64 / GIB
                ),
            });
        }
    }
    Ok(())
}

const GIB: f64 = 1024.0 * 1024.0 * 1024.0;

/// Memory available to a new allocation, from `/proc/meminfo` where there is one.
fn available_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    #[test]
    fn absurd_levels_are_refused() {
        let cube = shapes::cube();
        let opts = Options::default();
        assert!(check_level(&cube, &opts, 10).is_ok());
        assert!(matches!(
            check_level(&cube, &opts, 11),
            Err(Error::Level { level: 11, .. })
        ));
        let grid = shapes::grid(200, 200);
        assert!(check_level(&grid, &opts, 4).is_ok());
        let err = check_level(&grid, &opts, 9).unwrap_err();
        assert!(matches!(err, Error::Level { level: 9, .. }));
        assert!(err.to_string().contains("4.194e10 face corners"), "{err}");
        // About 2e9 corners at level 5: fits 32 bits, but needs over 100 GiB.
        if let Some(avail) = available_memory() {
            let err = check_level_counts(500_000, 2_000_000, Scheme::Catmark, 5);
            if (avail as f64) < 1e11 {
                let err = err.unwrap_err().to_string();
                assert!(err.contains("GiB"), "{err}");
            }
        }
    }
}
