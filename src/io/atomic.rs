//! Output files that appear whole or not at all.
//!
//! A regular file is written to a temporary file in the destination's
//! directory (named `.NAME.XXXXXX.tmp`, with the permissions a plain
//! `File::create` gives), which is renamed over the destination at the end;
//! on any failure the temporary file is removed and the destination is left
//! as it was. A symbolic link is followed: its target is written, atomically
//! in the target's directory, and the link stays. A destination that exists
//! and is not a regular file (a FIFO, a terminal, `/dev/stdout`) cannot be
//! replaced by a rename and is written directly.
//!
//! A process that is interrupted while writing (SIGINT, SIGTERM, SIGHUP)
//! should call [`remove_pending`] from its signal-handling thread: the
//! temporary files being written are registered until they are renamed or
//! removed. A flag set by the signal handler itself ([`abandon_when`]) also
//! stops a write that is about to be renamed, so that a signal that came
//! first is never followed by a new output.

use crate::error::Error;
use std::fs::File;
use std::io::{self, Write as _};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

/// Set by [`abandon_when`]: once it is true, writes give up.
static ABANDON: OnceLock<Arc<AtomicBool>> = OnceLock::new();

/// Makes every write give up once `flag` is true — before it creates its
/// temporary file or renames it into place, removing it — with an error of
/// kind [`io::ErrorKind::Interrupted`]. Meant for a flag a signal handler
/// sets (`signal_hook::flag::register`). The first call wins; later ones are
/// ignored.
pub fn abandon_when(flag: Arc<AtomicBool>) {
    let _ = ABANDON.set(flag);
}

/// Whether the process is ending: [`abandon_when`]'s flag set.
fn abandoned() -> bool {
    ABANDON.get().is_some_and(|f| f.load(Ordering::SeqCst))
}

fn ending_error() -> io::Error {
    io::Error::new(
        io::ErrorKind::Interrupted,
        "the process is ending (a signal)",
    )
}

/// Temporary files being written right now, and whether the process is
/// ending ([`remove_pending`] was called: no new temporary file is made).
/// A temporary file is created and registered under the lock, so none
/// escapes [`remove_pending`].
static PENDING: Mutex<Pending> = Mutex::new(Pending {
    files: Vec::new(),
    ending: false,
});

struct Pending {
    files: Vec<PathBuf>,
    ending: bool,
}

/// Removes every temporary file being written and makes every later write
/// fail before it creates one — for a signal handler that is about to end
/// the process. Returns how many files it removed.
pub fn remove_pending() -> usize {
    let mut pending = PENDING.lock().unwrap_or_else(|e| e.into_inner());
    pending.ending = true;
    pending
        .files
        .drain(..)
        .filter(|p| std::fs::remove_file(p).is_ok())
        .count()
}

/// A temporary file registered for [`remove_pending`] while it lives.
struct Registered(PathBuf);

impl Registered {
    /// Creates a temporary file with `builder` in `dir` and registers it, in
    /// one step under the lock; refused once the process is ending.
    fn create(
        builder: &tempfile::Builder<'_, '_>,
        dir: &Path,
    ) -> io::Result<(tempfile::NamedTempFile, Registered)> {
        let mut pending = PENDING.lock().unwrap_or_else(|e| e.into_inner());
        if pending.ending || abandoned() {
            return Err(ending_error());
        }
        let temp = builder.tempfile_in(dir)?;
        pending.files.push(temp.path().to_path_buf());
        let registered = Registered(temp.path().to_path_buf());
        Ok((temp, registered))
    }
}

impl Drop for Registered {
    fn drop(&mut self) {
        let mut pending = PENDING.lock().unwrap_or_else(|e| e.into_inner());
        pending.files.retain(|p| *p != self.0);
    }
}

/// Where writing `path` really goes: `path`, or the file a chain of
/// symbolic links at `path` leads to (at most 40 links, as the kernel
/// allows).
fn destination(path: &Path) -> io::Result<PathBuf> {
    let mut target = path.to_path_buf();
    for _ in 0..40 {
        match std::fs::symlink_metadata(&target) {
            Ok(meta) if meta.file_type().is_symlink() => {
                let link = std::fs::read_link(&target)?;
                target = match target.parent() {
                    Some(dir) if link.is_relative() => dir.join(link),
                    _ => link,
                };
            }
            _ => return Ok(target),
        }
    }
    Err(io::Error::other("too many levels of symbolic links"))
}

/// Writes `path` atomically (see the module documentation): `write` fills a
/// temporary file in the destination's directory, which is then renamed to
/// the destination. Errors name `path` and say what is wrong with it (a
/// directory, a missing directory), never the temporary file.
pub fn write_with(
    path: &Path,
    write: impl FnOnce(&mut File) -> io::Result<()>,
) -> Result<(), Error> {
    let io_error = |source: io::Error| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let plain = |message: String| io_error(io::Error::other(message));
    // What the path leads to, links followed by the kernel (also through
    // /proc/self/fd, whose pipes are no path a rename could reach).
    match std::fs::metadata(path) {
        Ok(meta) if meta.is_dir() => return Err(plain("it is a directory".into())),
        Ok(meta) if !meta.is_file() => {
            // A FIFO, a terminal, a pipe, a device: written in place.
            let mut file = std::fs::OpenOptions::new()
                .write(true)
                .open(path)
                .map_err(io_error)?;
            return write(&mut file).map_err(io_error);
        }
        _ => {}
    }
    let target = destination(path).map_err(io_error)?;
    let file_name = target
        .file_name()
        .ok_or_else(|| plain("the path does not name a file".into()))?;
    let dir = match target.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    };
    match std::fs::metadata(dir) {
        Ok(meta) if !meta.is_dir() => {
            return Err(plain(format!("{} is not a directory", dir.display())));
        }
        Err(e) if e.kind() == io::ErrorKind::NotFound => {
            return Err(plain(format!(
                "the directory {} does not exist",
                dir.display()
            )));
        }
        _ => {}
    }
    let mut prefix = std::ffi::OsString::from(".");
    prefix.push(file_name);
    prefix.push(".");
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".tmp");
    // A temporary file is private (0600) by default; ask for the mode a plain
    // `File::create` uses (0666 less the umask), as the file becomes `path`.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let (mut temp, registered) = Registered::create(&builder, dir).map_err(io_error)?;
    write(temp.as_file_mut()).map_err(io_error)?;
    {
        // Renamed under the lock, unless the process is ending: then the
        // temporary file goes (dropped) and the destination stays as it was.
        let pending = PENDING.lock().unwrap_or_else(|e| e.into_inner());
        if pending.ending || abandoned() {
            return Err(io_error(ending_error()));
        }
        temp.persist(&target).map_err(|e| io_error(e.error))?;
    }
    drop(registered);
    Ok(())
}

/// Writes `bytes` to `path` atomically (see [`write_with`]).
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    write_with(path, |file| file.write_all(bytes))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_appear_whole_links_are_followed_and_errors_name_the_path() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out.txt");
        write_bytes(&out, b"one").unwrap();
        assert_eq!(std::fs::read(&out).unwrap(), b"one");
        // A failing writer leaves the old file and no temporary file.
        let err = write_with(&out, |f| {
            f.write_all(b"half")?;
            Err(io::Error::other("interrupted"))
        })
        .unwrap_err();
        assert!(
            err.to_string().starts_with(&out.display().to_string()),
            "{err}"
        );
        assert_eq!(std::fs::read(&out).unwrap(), b"one");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
        // While writing, the temporary file is pending; remove_pending
        // removes it (what a signal handler does).
        let seen = write_with(&dir.path().join("second.txt"), |f| {
            f.write_all(b"x")?;
            let ours = |p: &PathBuf| {
                p.file_name()
                    .is_some_and(|n| n.to_string_lossy().starts_with(".second.txt."))
            };
            let pending = PENDING.lock().unwrap().files.clone();
            assert!(pending.iter().any(|p| ours(p) && p.exists()), "{pending:?}");
            Ok(())
        });
        seen.unwrap();
        let ours = |p: &PathBuf| p.parent() == Some(dir.path());
        assert!(!PENDING.lock().unwrap().files.iter().any(ours));
        // Directories and missing directories are named as such.
        let err = write_bytes(dir.path(), b"x").unwrap_err().to_string();
        assert!(err.ends_with("it is a directory"), "{err}");
        let err = write_bytes(&dir.path().join("missing/deeper/o.obj"), b"x")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("does not exist") && !err.contains(".o.obj."),
            "{err}"
        );
        #[cfg(unix)]
        {
            // A link is written through: the target changes, the link stays.
            let target = dir.path().join("target.txt");
            let link = dir.path().join("link.txt");
            std::os::unix::fs::symlink("target.txt", &link).unwrap();
            write_bytes(&link, b"through").unwrap();
            assert!(
                std::fs::symlink_metadata(&link)
                    .unwrap()
                    .file_type()
                    .is_symlink()
            );
            assert_eq!(std::fs::read(&target).unwrap(), b"through");
            // /dev/null is not a regular file: written in place, not replaced.
            write_bytes(Path::new("/dev/null"), b"gone").unwrap();
            assert!(!std::fs::metadata("/dev/null").unwrap().is_file());
        }
    }
}
