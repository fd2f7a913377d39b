//! Atomic file output: a file appears under its final name only when it was
//! written whole.
//!
//! The data goes to a temporary file in the destination's directory (named
//! `.NAME.XXXXXX.tmp`, with the permissions a plain `File::create` gives),
//! which is renamed over the destination at the end; on any failure the
//! temporary file is removed and the destination is left as it was.

use crate::error::Error;
use std::fs::File;
use std::io::{self, Write as _};
use std::path::Path;

/// Writes `path` atomically: `write` fills a temporary file in the same
/// directory, which is then renamed to `path`. Errors name `path`.
pub fn write_with(
    path: &Path,
    write: impl FnOnce(&mut File) -> io::Result<()>,
) -> Result<(), Error> {
    let io_error = |source: io::Error| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let file_name = path.file_name().ok_or_else(|| {
        io_error(io::Error::new(
            io::ErrorKind::InvalidInput,
            "the path does not name a file",
        ))
    })?;
    let dir = match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    };
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
    let mut temp = builder.tempfile_in(dir).map_err(io_error)?;
    write(temp.as_file_mut()).map_err(io_error)?;
    temp.persist(path).map_err(|e| io_error(e.error))?;
    Ok(())
}

/// Writes `bytes` to `path` atomically (see [`write_with`]).
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    write_with(path, |file| file.write_all(bytes))
}
