//! Where a subcommand writes its result: a file, written atomically (the
//! library's `io::atomic`: a link is written through, a FIFO or device in
//! place), or standard output for `-o -`. A file that is the input itself is
//! refused: writing it would destroy the input.

use crate::Failure;
use std::io::{self, Write};
use std::path::Path;
use subdiv::Error;

/// Writes the output at `path` with `write`: stdout when `path` is `-`, else
/// the file, atomically. `input` is the file the command read, refused as an
/// output.
pub(crate) fn write_output(
    path: &Path,
    input: Option<&Path>,
    write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> Result<(), Failure> {
    if path == Path::new("-") {
        let mut out = io::stdout().lock();
        return write(&mut out)
            .and_then(|()| out.flush())
            .map_err(|e| Failure::Message(format!("cannot write to standard output: {e}")));
    }
    if let Some(input) = input.filter(|input| same_file(input, path)) {
        return Err(Failure::Usage(format!(
            "-o {} names the input file {}: choose another output",
            path.display(),
            input.display()
        )));
    }
    let mut write = Some(write);
    subdiv::io::atomic::write_with(path, |file| match write.take() {
        Some(write) => write(file),
        None => Ok(()),
    })
    .map_err(|e: Error| Failure::Error(e))
}

/// Whether `a` and `b` are the same existing file (through links and
/// different spellings of its path).
fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        #[cfg(unix)]
        (Ok(x), Ok(y)) => {
            use std::os::unix::fs::MetadataExt;
            x.dev() == y.dev() && x.ino() == y.ino()
        }
        #[cfg(not(unix))]
        (Ok(_), Ok(_)) => std::fs::canonicalize(a).ok() == std::fs::canonicalize(b).ok(),
        _ => false,
    }
}
