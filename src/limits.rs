//! Limits checked before a refinement allocates anything: the deepest level
//! ([`MAX_LEVEL`]), OpenSubdiv's 32-bit indices, and the memory the machine
//! has.

use crate::error::{Error, LevelRefusal, Result};
use crate::mesh::Mesh;
use crate::options::{MAX_LEVEL, Options, Scheme};
use crate::real::Precision;

/// Refuses a level before anything is allocated: above [`MAX_LEVEL`], one whose
/// face-vertex count would not fit OpenSubdiv's 32-bit indices, or one whose
/// estimated memory (from 1 MiB) exceeds what this machine has available.
pub fn check_level(mesh: &Mesh, options: &Options, level: u32) -> Result<()> {
    check_level_counts(
        mesh.face_count(),
        mesh.face_vertices.len(),
        options.scheme,
        level,
    )
}

/// Refuses a mesh whose positions or face-varying values `precision` cannot
/// hold (in `f32`, a finite value beyond about ±3.4e38 would become
/// infinite). Values that are not finite to begin with are left to
/// [`Mesh::validate`], which names them as such.
pub fn check_precision(mesh: &Mesh, precision: Precision) -> Result<()> {
    if precision == Precision::F64 {
        return Ok(());
    }
    let fits = |x: f64| !x.is_finite() || (x as f32).is_finite();
    let beyond = |what, index, value| Error::BeyondPrecision {
        what,
        index,
        value,
        precision,
    };
    for (v, p) in mesh.positions.iter().enumerate() {
        if let Some(&x) = p.to_array().iter().find(|&&x| !fits(x)) {
            return Err(beyond("vertex", v, x));
        }
    }
    for channel in &mesh.fvar_channels {
        if let Some((i, &x)) = channel.values.iter().enumerate().find(|(_, x)| !fits(**x)) {
            return Err(beyond("face-varying value", i / channel.width.max(1), x));
        }
    }
    Ok(())
}

/// Bytes per refined face corner and per refined vertex that a refinement
/// needs, roughly (topology tables of every level plus f64 positions).
const BYTES_PER_CORNER: f64 = 40.0;
const BYTES_PER_VERTEX: f64 = 64.0;

/// Estimates below this are not compared with the memory available.
/// Asking costs reading three /proc files and the cgroup's (10-20 µs):
/// more than refining the few faces around one face, which Bfr does for
/// each irregular face's surface (5% of tessellating the Loop torus with
/// UVs went to those reads). An estimate this small that still does not
/// fit is refused by the allocations themselves ([`Error::OutOfMemory`]).
const CHECKED_BYTES: f64 = (1u64 << 20) as f64;

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
    if bytes >= CHECKED_BYTES
        && let Some(available) = available_memory()
        && bytes > available as f64
    {
        return Err(Error::Level {
            level,
            reason: LevelRefusal::OutOfMemory {
                needed: bytes,
                available,
            },
        });
    }
    Ok(())
}

/// Memory a new allocation of this process can get: the least of the
/// machine's available memory (`MemAvailable`), what the address-space and
/// data-size limits (`ulimit -v`, `ulimit -d`: RLIMIT_AS, RLIMIT_DATA) leave
/// above what the process already uses, and what its cgroup's memory limit
/// leaves (v2 `memory.max`, v1 `memory.limit_in_bytes`, less the usage).
/// `None` where none of these can be read (not Linux).
pub fn available_memory() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let limits = std::fs::read_to_string("/proc/self/limits").unwrap_or_default();
    let meminfo = std::fs::read_to_string("/proc/meminfo").unwrap_or_default();
    [
        kib_field(&meminfo, "MemAvailable:"),
        rlimit_headroom(&limits, "Max address space", kib_field(&status, "VmSize:")),
        rlimit_headroom(&limits, "Max data size", kib_field(&status, "VmData:")),
        cgroup_headroom(),
    ]
    .into_iter()
    .flatten()
    .min()
}

/// Whether the process runs under an address-space or data-size limit
/// (`ulimit -v`, `ulimit -d`: a finite soft RLIMIT_AS or RLIMIT_DATA in
/// /proc/self/limits), read once.
pub(crate) fn address_space_limited() -> bool {
    static LIMITED: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *LIMITED.get_or_init(|| {
        let limits = std::fs::read_to_string("/proc/self/limits").unwrap_or_default();
        ["Max address space", "Max data size"]
            .iter()
            .any(|name| rlimit_headroom(&limits, name, None).is_some())
    })
}

/// A `Name:  1234 kB` field of a /proc file, in bytes.
fn kib_field(text: &str, name: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with(name))?;
    let kib: u64 = line[name.len()..].split_whitespace().next()?.parse().ok()?;
    Some(kib.saturating_mul(1024))
}

/// What the soft resource limit `name` of /proc/self/limits leaves above
/// `used` bytes; `None` when unlimited or unknown.
fn rlimit_headroom(limits: &str, name: &str, used: Option<u64>) -> Option<u64> {
    let line = limits.lines().find(|l| l.starts_with(name))?;
    let soft: u64 = line[name.len()..].split_whitespace().next()?.parse().ok()?;
    Some(soft.saturating_sub(used.unwrap_or(0)))
}

/// What the process's memory cgroup leaves: its limit less its usage
/// (cgroup v2, else v1); `None` without a limit.
fn cgroup_headroom() -> Option<u64> {
    let cgroups = std::fs::read_to_string("/proc/self/cgroup").ok()?;
    let read =
        |path: String| -> Option<u64> { std::fs::read_to_string(path).ok()?.trim().parse().ok() };
    for line in cgroups.lines() {
        let mut parts = line.splitn(3, ':');
        let (id, controllers, path) = (parts.next()?, parts.next()?, parts.next()?);
        let (limit, usage) = if id == "0" && controllers.is_empty() {
            let dir = format!("/sys/fs/cgroup{path}");
            (
                read(format!("{dir}/memory.max")),
                read(format!("{dir}/memory.current")),
            )
        } else if controllers.split(',').any(|c| c == "memory") {
            let dir = format!("/sys/fs/cgroup/memory{path}");
            (
                read(format!("{dir}/memory.limit_in_bytes")),
                read(format!("{dir}/memory.usage_in_bytes")),
            )
        } else {
            continue;
        };
        // v1 writes "no limit" as a huge number (PAGE_COUNTER_MAX pages).
        if let Some(limit) = limit.filter(|&l| l < 1 << 60) {
            return Some(limit.saturating_sub(usage.unwrap_or(0)));
        }
    }
    None
}

/// Refuses an interpolation from level `level - 1` to `level` of a refiner
/// refined to `last` levels ([`Error::NoSuchLevel`]: the levels to
/// interpolate are `1..=last`) or of values zero wide ([`Error::ZeroWidth`]),
/// as every engine's interpolation calls do.
pub(crate) fn check_interpolation_call(level: u32, last: u32, width: usize) -> Result<()> {
    if level == 0 || level > last {
        return Err(Error::NoSuchLevel {
            level,
            first: 1,
            last,
        });
    }
    if width == 0 {
        return Err(Error::ZeroWidth);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    #[test]
    fn f32_refuses_finite_values_beyond_its_range_and_leaves_the_rest_to_validation() {
        let mut mesh = shapes::cube_with_uvs();
        assert!(check_precision(&mesh, Precision::F32).is_ok());
        mesh.positions[5].y = -1e39;
        let err = check_precision(&mesh, Precision::F32).unwrap_err();
        assert!(
            matches!(err, Error::BeyondPrecision { what: "vertex", index: 5, value, .. } if value == -1e39),
            "{err:?}"
        );
        assert_eq!(
            err.to_string(),
            "vertex 5 has the value -1e39, beyond the range of f32; refine in f64"
        );
        assert!(check_precision(&mesh, Precision::F64).is_ok());
        // 3.4e38 rounds to f32's largest finite value: it fits.
        mesh.positions[5].y = 3.4e38;
        assert!(check_precision(&mesh, Precision::F32).is_ok());
        // A UV: the value's index (not the number's).
        let width = mesh.fvar_channels[0].width;
        mesh.fvar_channels[0].values[3 * width + 1] = 1e300;
        let err = check_precision(&mesh, Precision::F32).unwrap_err();
        assert!(
            matches!(
                err,
                Error::BeyondPrecision {
                    what: "face-varying value",
                    index: 3,
                    ..
                }
            ),
            "{err:?}"
        );
        // Infinity and NaN are the validation's to name.
        mesh.fvar_channels[0].values[3 * width + 1] = 0.5;
        mesh.positions[2].x = f64::INFINITY;
        assert!(check_precision(&mesh, Precision::F32).is_ok());
        let refused = crate::refiner::refine(
            &mesh,
            &crate::Options::shape_file_defaults(),
            crate::Request::new(1).precision(Precision::F32),
        );
        assert!(matches!(refused, Err(Error::Mesh(_))), "{refused:?}");
        // An invalid mesh is named as such before its values are judged.
        mesh.positions[2].x = 1e300;
        mesh.face_offsets.pop();
        let request = crate::Request::new(1).precision(Precision::F32);
        let options = crate::Options::shape_file_defaults();
        let refused = crate::refiner::refine(&mesh, &options, request);
        assert!(matches!(refused, Err(Error::Mesh(_))), "{refused:?}");
        let refused = crate::Engine::Native.refine_counts(&mesh, &options, request);
        assert!(matches!(refused, Err(Error::Mesh(_))), "{refused:?}");
    }

    #[test]
    fn resource_limits_are_read_from_proc() {
        let limits = "Limit                     Soft Limit           Hard Limit           Units\n\
                      Max data size             unlimited            unlimited            bytes\n\
                      Max address space         4294967296           unlimited            bytes\n";
        assert_eq!(
            rlimit_headroom(limits, "Max address space", Some(1 << 30)),
            Some(3 << 30)
        );
        assert_eq!(
            rlimit_headroom(limits, "Max data size", Some(1 << 30)),
            None
        );
        let status = "Name:\tsubdiv\nVmSize:\t  102400 kB\nVmData:\t 2048 kB\n";
        assert_eq!(kib_field(status, "VmSize:"), Some(100 << 20));
        assert_eq!(kib_field(status, "VmData:"), Some(2 << 20));
        assert_eq!(kib_field(status, "VmRSS:"), None);
        // This process: whatever limits it has, the least is a number.
        if std::path::Path::new("/proc/meminfo").exists() {
            assert!(available_memory().is_some_and(|a| a > 0));
        }
    }

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
