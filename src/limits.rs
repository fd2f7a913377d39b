//! Limits checked before a refinement allocates anything: the deepest level
//! ([`MAX_LEVEL`]), OpenSubdiv's 32-bit indices, and the memory the machine
//! has.

use crate::error::{Error, LevelRefusal, Result};
use crate::mesh::Mesh;
use crate::options::{MAX_LEVEL, Options, Scheme};

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
            reason: LevelRefusal::TooDeep { max: MAX_LEVEL },
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
            reason: LevelRefusal::TooManyCorners {
                corners: face_vertices,
            },
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
                reason: LevelRefusal::OutOfMemory {
                    needed: bytes,
                    available,
                },
            });
        }
    }
    Ok(())
}

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
