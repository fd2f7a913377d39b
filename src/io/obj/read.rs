//! The OBJ reader: statements, `t` tags, file:line errors.

use super::{ObjWarning, ShapeFile, ShapeTags, chunks, fast};
use crate::error::{ObjError, ObjErrorKind};
use crate::mesh::{Corner, Crease, FVarChannel, MAX_VALENCE, Mesh};
use crate::options::{
    BoundaryInterpolation, CreasingMethod, FVarLinearInterpolation, TriangleSubdivision,
};
use glam::DVec3;
use std::borrow::Cow;
use std::path::Path;
use std::str::SplitAsciiWhitespace;

/// Reads an OBJ shape file.
///
/// Failing to read the file is an [`ObjErrorKind::Io`] error on line 0. Bytes
/// that are not UTF-8 are replaced (they can only matter inside a number, where
/// they are a syntax error), and a leading byte-order mark is skipped.
///
/// On one thread, or for a file under 4 MiB, the file is read a block at a
/// time and parsed as it arrives, in a buffer that stays in the
/// processor's cache; a larger file on a pool of several threads is read
/// whole and parsed in chunks on every thread ([`parse_obj`]). The result
/// and the first error are the same either way.
pub fn read_obj(path: &Path) -> Result<ShapeFile, ObjError> {
    let io = |e: std::io::Error| error_at(path, 0, ObjErrorKind::Io(e.to_string()));
    let mut file = std::fs::File::open(path).map_err(io)?;
    let len = file.metadata().map_err(io)?.len();
    // One thread, or a file too small to share: read a block at a time.
    if rayon::current_num_threads() == 1 || len < PARALLEL_BYTES as u64 {
        let len = usize::try_from(len).unwrap_or(usize::MAX);
        return read_streaming(&mut file, path, BLOCK, len);
    }
    let bytes = read_bytes(file, len, path).map_err(io)?;
    // Read as bytes: the fast path's lines are ASCII by construction, and
    // only the general parser's lines are checked for UTF-8 (and their bad
    // bytes replaced), which reads the same text as checking and replacing
    // first.
    let result = parse(&bytes, path, true);
    // The text back to the system, not to the pool of tables: the peak
    // memory of reading and refining stays what it was with a vector.
    bytes.free();
    result
}

/// The bytes read from the file at a time by [`read_streaming`]: small
/// enough for the buffer to stay in the processor's second-level cache
/// while the parser reads it, large enough for the system calls not to
/// count.
const BLOCK: usize = 1 << 18;

/// The file (`source`) read `block` bytes at a time into one buffer and its whole lines
/// parsed as they arrive ([`Parser::lines`]), the line a block cuts
/// carried over to the next: the same lines, results and errors as
/// reading the whole text first ([`parse_lines`]), without a table the
/// size of the file — no page of it to fault in and zero, no copy of the
/// text out of the processor's cache before the parser reads it. A line
/// longer than the buffer grows it. A file that cannot be read is an I/O
/// error on line 0, unless a line already read is an error: lines are
/// judged in order, as they arrive. `expected` is the source's length as
/// far as known (0 when not): after each block the tables the lines fill
/// get room for the rest of it at the block's rate
/// ([`Parser::reserve_ahead`]), so that they are not copied as they grow.
fn read_streaming(
    source: &mut impl std::io::Read,
    path: &Path,
    block: usize,
    expected: usize,
) -> Result<ShapeFile, ObjError> {
    let io = |e: &dyn std::fmt::Display| error_at(path, 0, ObjErrorKind::Io(e.to_string()));
    let mut buffer = Vec::new();
    buffer.try_reserve_exact(block).map_err(|e| io(&e))?;
    buffer.resize(block.max(1), 0);
    let mut parser = Parser::default();
    let mut line = 0;
    // Bytes in the buffer not yet parsed (the start of a line), and whether
    // the first line (which may start with a byte-order mark) is still to
    // come.
    let (mut held, mut first) = (0, true);
    // Bytes of the source parsed so far.
    let mut parsed = 0;
    loop {
        if held == buffer.len() {
            // A line longer than the buffer.
            buffer.try_reserve_exact(buffer.len()).map_err(|e| io(&e))?;
            buffer.resize(2 * buffer.len(), 0);
        }
        let read = match source.read(&mut buffer[held..]) {
            Ok(read) => read,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(io(&e)),
        };
        let end_of_file = read == 0;
        let text = &buffer[..held + read];
        // Whole lines only, but at the end of the file.
        let whole = match memchr::memrchr(b'\n', &text[held..]) {
            Some(at) => held + at + 1,
            None if end_of_file => text.len(),
            None => {
                held = text.len();
                continue;
            }
        };
        let mut lines = &text[..whole];
        if first {
            lines = strip_bom(lines);
            first = false;
        }
        let before = parser.table_lengths();
        parser
            .lines(lines, &mut line, true)
            .map_err(|(line, kind)| error_at(path, line, kind))?;
        if end_of_file {
            break;
        }
        parsed += whole;
        parser.reserve_ahead(before, whole, expected.saturating_sub(parsed));
        held = text.len() - whole;
        buffer.copy_within(whole..whole + held, 0);
    }
    parser.trim_reserved();
    parser
        .finish()
        .map_err(|(line, kind)| error_at(path, line, kind))
}

/// The whole of the open `file` (`len` bytes, as its metadata says), read
/// into a table (a huge-page map from 2 MiB: a large file costs a few
/// hundred page faults instead of one per 4 KiB); the standard library's
/// `fs::read` of `path` when the file changes size while read.
/// A file the parser reads in chunks ([`PARALLEL_BYTES`] and more, on a
/// pool of several threads) is read in as many pieces at once, one per
/// thread, so that the copy out of the page cache and the table's page
/// faults are shared too.
fn read_bytes(
    mut file: std::fs::File,
    len: u64,
    path: &Path,
) -> std::io::Result<crate::topology::Table<u8>> {
    let len = usize::try_from(len).unwrap_or(usize::MAX);
    // Memory refused: `fs::read` reports it as an I/O error.
    let table = crate::alloc::guard(None, || {
        Ok(crate::topology::Table::<u8>::for_overwrite(len))
    });
    if let Ok(mut table) = table
        && read_whole(&mut file, &mut table)?
    {
        return Ok(table);
    }
    Ok(crate::topology::Table::from(std::fs::read(path)?))
}

/// Whether `file` filled `buffer` exactly (no fewer bytes, none more); an
/// error only where the check for more bytes fails.
fn read_whole(file: &mut std::fs::File, buffer: &mut [u8]) -> std::io::Result<bool> {
    #[cfg(unix)]
    {
        use rayon::prelude::*;
        use std::os::unix::fs::FileExt;
        let threads = rayon::current_num_threads();
        if threads > 1 && buffer.len() >= PARALLEL_BYTES {
            let piece = buffer.len().div_ceil(threads);
            let file = &*file;
            let filled = buffer
                .par_chunks_mut(piece)
                .enumerate()
                .all(|(k, part)| file.read_exact_at(part, (k * piece) as u64).is_ok());
            let mut more = [0u8; 1];
            return Ok(filled && file.read_at(&mut more, buffer.len() as u64)? == 0);
        }
    }
    use std::io::Read;
    let mut more = [0u8; 1];
    Ok(file.read_exact(buffer).is_ok() && file.read(&mut more)? == 0)
}

/// Parses the text of an OBJ shape file; `file` only names it in errors
/// (use `Path::new("<memory>")` for in-memory text). Text of 4 MiB or more
/// is read on every thread of the current rayon pool, in chunks of whole
/// lines; the result and the first error are those of reading it line by
/// line.
///
/// ```
/// use std::path::Path;
/// use subdiv::io::parse_obj;
/// let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nt crease 2/1/0 0 1 10\n";
/// let shape = parse_obj(text, Path::new("<memory>"))?;
/// assert_eq!(shape.mesh.face_vertices, [0, 1, 2, 3]);
/// assert_eq!(shape.mesh.creases[0].vertices, [0, 1]);
/// # Ok::<(), subdiv::ObjError>(())
/// ```
pub fn parse_obj(text: &str, file: &Path) -> Result<ShapeFile, ObjError> {
    parse(text.as_bytes(), file, true)
}

/// [`parse_obj`] with every line read by the general parser, none by the
/// fast path: the reference the fast path is tested and fuzzed against.
#[doc(hidden)]
pub fn parse_obj_general(text: &str, file: &Path) -> Result<ShapeFile, ObjError> {
    parse(text.as_bytes(), file, false)
}

/// [`parse_obj`] reading the text in `chunks` pieces in parallel (when every
/// piece can be read so; else line by line), whatever its size: the
/// parallel reader is tested and fuzzed with it.
#[doc(hidden)]
pub fn parse_obj_chunked(text: &str, file: &Path, chunks: usize) -> Result<ShapeFile, ObjError> {
    let text = strip_bom(text.as_bytes());
    parse_chunked(text, file, chunks.max(1)).unwrap_or_else(|| parse_lines(text, file, true))
}

/// The bytes of an OBJ file (UTF-8 or not) read as [`read_obj`] reads a
/// file a block at a time, in blocks of `block` bytes: the streaming
/// reader is tested and fuzzed with it.
#[doc(hidden)]
pub fn parse_obj_streamed(bytes: &[u8], file: &Path, block: usize) -> Result<ShapeFile, ObjError> {
    read_streaming(&mut &bytes[..], file, block, bytes.len())
}

/// Files from this size are read on every thread of the pool.
const PARALLEL_BYTES: usize = 1 << 22;

/// `text` without its byte-order mark (U+FEFF in UTF-8), if it has one.
fn strip_bom(text: &[u8]) -> &[u8] {
    text.strip_prefix("\u{feff}".as_bytes()).unwrap_or(text)
}

/// The text (UTF-8 or not: [`fast::Cursor`]) read by the chunks or line
/// by line.
fn parse(text: &[u8], file: &Path, fast_path: bool) -> Result<ShapeFile, ObjError> {
    let text = strip_bom(text);
    let threads = rayon::current_num_threads();
    if fast_path
        && threads > 1
        && text.len() >= PARALLEL_BYTES
        && let Some(result) = parse_chunked(text, file, threads)
    {
        return result;
    }
    parse_lines(text, file, fast_path)
}

fn error_at(file: &Path, line: usize, kind: ObjErrorKind) -> ObjError {
    ObjError {
        file: file.to_path_buf(),
        line,
        kind,
    }
}

/// The chunks' tables joined in order: the first chunk's grown (in place,
/// or moved by the allocator without a copy) to the whole size once, the
/// others appended, so no table is copied twice or grows step by step.
fn join<T: Copy>(parts: Vec<Vec<T>>) -> Vec<T> {
    let total = parts.iter().map(Vec::len).sum::<usize>();
    let mut parts = parts.into_iter();
    let mut all = parts.next().unwrap_or_default();
    all.reserve_exact(total - all.len());
    for part in parts {
        all.extend_from_slice(&part);
    }
    all
}

/// The text read in `count` chunks in parallel ([`chunks`]) and joined;
/// `None` when it must be read line by line instead.
fn parse_chunked(text: &[u8], file: &Path, count: usize) -> Option<Result<ShapeFile, ObjError>> {
    let mut read = chunks::read_chunks(text, count)?;
    let mut p = Parser::default();
    let (mut vertices_before, mut uvs_before) = (0, 0);
    let mut first_line = 0;
    let mut deferred = Vec::new();
    p.mesh
        .face_offsets
        .reserve_exact(read.iter().map(|c| c.face_ends.len()).sum());
    let mut corners_before = 0;
    for c in &mut read {
        if c.needs.0 > vertices_before || c.needs.1 > uvs_before {
            return None;
        }
        if let Some((with_uv, line)) = c.first_face {
            match p.uv_mode {
                Some((mode, _)) if mode != with_uv => return None,
                Some(_) => {}
                None => p.uv_mode = Some((with_uv, first_line + line)),
            }
        }
        for &end in &c.face_ends {
            let end = u32::try_from(corners_before + end as usize).ok()?;
            p.mesh.face_offsets.push(end);
        }
        vertices_before += c.positions.len();
        uvs_before += c.uv_values.len() / 2;
        corners_before += c.face_vertices.len();
        deferred.extend(
            std::mem::take(&mut c.deferred)
                .into_iter()
                .map(|(line, s)| (first_line + line, s)),
        );
        first_line += c.lines;
    }
    p.mesh.positions = join(
        read.iter_mut()
            .map(|c| std::mem::take(&mut c.positions))
            .collect(),
    );
    p.mesh.face_vertices = join(
        read.iter_mut()
            .map(|c| std::mem::take(&mut c.face_vertices))
            .collect(),
    );
    p.uv_values = join(
        read.iter_mut()
            .map(|c| std::mem::take(&mut c.uv_values))
            .collect(),
    );
    p.uv_indices = join(
        read.iter_mut()
            .map(|c| std::mem::take(&mut c.uv_indices))
            .collect(),
    );
    for (line, statement) in deferred {
        if let Err(kind) = p.statement(line, &statement) {
            return Some(Err(error_at(file, line, kind)));
        }
    }
    Some(
        p.finish()
            .map_err(|(line, kind)| error_at(file, line, kind)),
    )
}

/// The text read line by line (by the fast path where it can, when
/// `fast_path`).
fn parse_lines(text: &[u8], file: &Path, fast_path: bool) -> Result<ShapeFile, ObjError> {
    let mut parser = Parser::default();
    let error = |(line, kind)| error_at(file, line, kind);
    parser.lines(text, &mut 0, fast_path).map_err(error)?;
    parser.finish().map_err(error)
}

/// A `crease`, `corner` or `hole` tag, kept until every vertex and face is known.
struct ElementTag {
    line: usize,
    kind: ElementKind,
    ints: Vec<i64>,
    floats: Vec<f32>,
}

#[derive(Clone, Copy, PartialEq)]
enum ElementKind {
    Crease,
    Corner,
    Hole,
}

impl ElementKind {
    fn name(self) -> &'static str {
        match self {
            ElementKind::Crease => "crease",
            ElementKind::Corner => "corner",
            ElementKind::Hole => "hole",
        }
    }
}

/// The line-by-line state of [`parse_obj`].
#[derive(Default)]
struct Parser {
    mesh: Mesh,
    uv_values: Vec<f64>,
    uv_indices: Vec<u32>,
    /// Whether face corners carry texture coordinates, and the line of the
    /// first face corner, which decided it.
    uv_mode: Option<(bool, usize)>,
    tags: ShapeTags,
    /// The line of the last tag setting each option of [`ShapeTags`], in field order.
    option_lines: [usize; 4],
    element_tags: Vec<ElementTag>,
    warnings: Vec<ObjWarning>,
}

/// Why `text` is no `i64`: an integer too large, or no integer at all.
fn not_an_integer(text: &str) -> &'static str {
    let digits = text.strip_prefix(['-', '+']).unwrap_or(text);
    if !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) {
        "is out of range"
    } else {
        "is not an integer"
    }
}

/// What is wrong with `text` as an `f32` sharpness that parsed to a
/// non-finite value: beyond `f32`'s range, or not finite at all.
fn not_a_finite_f32(text: &str) -> &'static str {
    if text.parse::<f64>().is_ok_and(f64::is_finite) {
        "is beyond the range of f32 (about ±3.4e38)"
    } else {
        "is not a finite number"
    }
}

/// At most this many characters of a field are quoted in a message.
const QUOTE_LIMIT: usize = 40;

/// Text from a file made safe for a message: control characters and other
/// unprintable ones are escaped as Rust writes them (`\0`, `\t`, `\u{1b}`...)
/// and `\` is written `\\`, so that a message can never carry a terminal
/// escape sequence or a line break. Quotes are kept as they are.
pub(crate) fn escape(text: &str) -> Cow<'_, str> {
    let plain = |c: char| c == '\'' || c == '"' || c.escape_debug().len() == 1;
    if text.chars().all(plain) {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if plain(c) {
            out.push(c);
        } else {
            out.extend(c.escape_debug());
        }
    }
    Cow::Owned(out)
}

/// A field of the file for a message: at most [`QUOTE_LIMIT`] characters of
/// it (then `...`), [`escape`]d.
fn quote(field: &str) -> Cow<'_, str> {
    match field.char_indices().nth(QUOTE_LIMIT) {
        Some((end, _)) => Cow::Owned(format!("{}...", escape(&field[..end]))),
        None => escape(field),
    }
}

fn syntax(message: String) -> ObjErrorKind {
    ObjErrorKind::Syntax(message)
}

/// Parses a coordinate named `name` of a `statement`, which must be a finite number.
fn coordinate(field: &str, statement: &str, name: &str) -> Result<f64, ObjErrorKind> {
    let value: f64 = field.parse().map_err(|_| {
        syntax(format!(
            "'{statement}' statement: {name} '{}' is not a number",
            quote(field)
        ))
    })?;
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ObjErrorKind::NonFinite(format!(
            "{name} = {} in a '{statement}' statement",
            quote(field)
        )))
    }
}

/// The 0-based index of a 1-based or negative (relative) OBJ index among
/// `count` elements defined so far.
fn resolve(index: i64, count: usize, what: &'static str) -> Result<u32, ObjErrorKind> {
    let out_of_range = || ObjErrorKind::IndexOutOfRange { what, index, count };
    let zero_based = if index > 0 {
        let i = (index - 1) as u64;
        if i >= count as u64 {
            return Err(out_of_range());
        }
        i
    } else if index < 0 {
        let back = index.unsigned_abs();
        if back > count as u64 {
            return Err(out_of_range());
        }
        count as u64 - back
    } else {
        return Err(out_of_range());
    };
    u32::try_from(zero_based).map_err(|_| {
        syntax(format!(
            "{what} index {index} does not fit the 32-bit indices of a mesh"
        ))
    })
}

impl Parser {
    fn warn(&mut self, line: usize, message: String, ignored: bool) {
        self.warnings.push(ObjWarning {
            line,
            message,
            ignored,
        });
    }

    /// The lengths of the tables lines fill, as [`Parser::reserve_ahead`]
    /// takes them: positions, texture coordinates, face vertices, face
    /// texture-coordinate indices, face offsets.
    fn table_lengths(&self) -> [usize; 5] {
        [
            self.mesh.positions.len(),
            self.uv_values.len(),
            self.mesh.face_vertices.len(),
            self.uv_indices.len(),
            self.mesh.face_offsets.len(),
        ]
    }

    /// Room in each table for the `remaining` bytes still to come, at the
    /// rate the last `block` bytes filled it (from `before`, its
    /// [`Parser::table_lengths`]), when it has less: reserved once, where
    /// doubling would copy a table again and again as it grows (on the
    /// heap, under the C allocator's map threshold, a grown vector is a
    /// copy). An estimate — a table filled only at the start of the file
    /// is given too much, pages never touched and handed back by
    /// [`Parser::trim_reserved`] — and room refused is no error: the table
    /// then grows as it would have. Asked through
    /// [`crate::alloc::reserve`], which gives the room back when it would
    /// leave too little address space for the small allocations after it
    /// (an over-estimate must not turn a limit into an abort).
    fn reserve_ahead(&mut self, before: [usize; 5], block: usize, remaining: usize) {
        fn ahead<T>(table: &mut Vec<T>, before: usize, block: usize, remaining: usize) {
            let grown = table.len().saturating_sub(before) as u128;
            let wanted = grown * remaining as u128 / block.max(1) as u128;
            let wanted = usize::try_from(wanted).unwrap_or(usize::MAX);
            if table.capacity() - table.len() < wanted {
                // Refused: the table grows as it would have.
                let _ = crate::alloc::reserve(table, wanted);
            }
        }
        let [p, t, v, u, o] = before;
        ahead(&mut self.mesh.positions, p, block, remaining);
        ahead(&mut self.uv_values, t, block, remaining);
        ahead(&mut self.mesh.face_vertices, v, block, remaining);
        ahead(&mut self.uv_indices, u, block, remaining);
        ahead(&mut self.mesh.face_offsets, o, block, remaining);
    }

    /// The room [`Parser::reserve_ahead`] gave beyond a quarter of what a
    /// table holds handed back (in place: a smaller block of the same
    /// memory, nothing copied).
    fn trim_reserved(&mut self) {
        fn trim<T>(table: &mut Vec<T>) {
            if table.capacity() - table.len() > table.len() / 4 {
                table.shrink_to_fit();
            }
        }
        trim(&mut self.mesh.positions);
        trim(&mut self.uv_values);
        trim(&mut self.mesh.face_vertices);
        trim(&mut self.uv_indices);
        trim(&mut self.mesh.face_offsets);
    }

    /// Reads one line by the fast path ([`fast`]) if it can — `text` is the
    /// text from the line on — and says where the line ends in `text` (its
    /// line feed, or the end of the text), with the same effect as
    /// [`Parser::statement`]; `None` (nothing changed) for a line the
    /// general parser must read.
    fn fast_statement(&mut self, line: usize, text: &[u8]) -> Option<usize> {
        match text {
            [b'v', s, rest @ ..] if fast::is_blank(*s) => {
                let (p, end) = fast::numbers::<3>(rest)?;
                self.mesh.positions.push(DVec3::from_array(p));
                Some(2 + end)
            }
            [b'v', b't', s, rest @ ..] if fast::is_blank(*s) => {
                let (uv, end) = fast::numbers::<2>(rest)?;
                self.uv_values.extend_from_slice(&uv);
                Some(3 + end)
            }
            [b'f', s, rest @ ..] if fast::is_blank(*s) => {
                let vertex_count = self.mesh.positions.len();
                let uv_count = self.uv_values.len() / 2;
                let (vertices, uvs) = (&mut self.mesh.face_vertices, &mut self.uv_indices);
                let (had_vertices, had_uvs) = (vertices.len(), uvs.len());
                let (with_uv, end) =
                    fast::face(rest, vertex_count, uv_count, MAX_VALENCE, vertices, uvs)?;
                let last = u32::try_from(vertices.len());
                let (Ok(last), true) = (last, self.uv_mode.is_none_or(|(m, _)| m == with_uv))
                else {
                    vertices.truncate(had_vertices);
                    uvs.truncate(had_uvs);
                    return None;
                };
                self.uv_mode.get_or_insert((with_uv, line));
                self.mesh.face_offsets.push(last);
                Some(2 + end)
            }
            _ => {
                let end = fast::line_end(text);
                fast::ignored(&text[..end]).then_some(end)
            }
        }
    }

    /// Reads the lines of `text` (by the fast path where it can, when
    /// `fast_path`), numbered on from `*line`, which ends at the last; the
    /// first error with its line. `text` is whole lines: a line cut short
    /// at its end would be read as a shorter line.
    fn lines(
        &mut self,
        text: &[u8],
        line: &mut usize,
        fast_path: bool,
    ) -> Result<(), (usize, ObjErrorKind)> {
        let mut cursor = fast::Cursor::new(text);
        while !cursor.is_done() {
            *line += 1;
            if fast_path && let Some(end) = self.fast_statement(*line, cursor.rest()) {
                cursor.skip(end);
                continue;
            }
            self.statement(*line, &cursor.take_line())
                .map_err(|kind| (*line, kind))?;
        }
        Ok(())
    }

    /// Reads one line.
    fn statement(&mut self, line: usize, text: &str) -> Result<(), ObjErrorKind> {
        let text = match text.find('#') {
            Some(i) => &text[..i],
            None => text,
        };
        let mut fields = text.split_ascii_whitespace();
        let Some(keyword) = fields.next() else {
            return Ok(());
        };
        match keyword {
            "v" => self.vertex(fields),
            "vt" => self.texcoord(fields),
            "vn" => Ok(()),
            "f" => self.face(line, fields),
            "t" => self.tag(line, fields),
            "o" | "g" | "s" | "usemtl" | "mtllib" => Ok(()),
            "l" | "p" => {
                let what = if keyword == "l" { "line" } else { "point" };
                self.warn(
                    line,
                    format!("'{keyword}' ({what}) elements are not supported"),
                    true,
                );
                Ok(())
            }
            _ => {
                self.warn(
                    line,
                    format!("unknown statement '{}'", quote(keyword)),
                    true,
                );
                Ok(())
            }
        }
    }

    /// `v x y z [w]`, also accepting the common `v x y z r g b` colour extension.
    fn vertex(&mut self, fields: SplitAsciiWhitespace<'_>) -> Result<(), ObjErrorKind> {
        let mut raw = [""; 6];
        let mut n = 0;
        for field in fields {
            if n < raw.len() {
                raw[n] = field;
            }
            n += 1;
        }
        let names: &[&str] = match n {
            3 => &["x", "y", "z"],
            4 => &["x", "y", "z", "w"],
            6 => &["x", "y", "z", "red", "green", "blue"],
            _ => {
                return Err(syntax(format!(
                    "a 'v' statement needs x y z [w] (or x y z r g b), found {n} values"
                )));
            }
        };
        let mut xyz = [0.0; 3];
        for (i, name) in names.iter().enumerate() {
            let value = coordinate(raw[i], "v", name)?;
            if i < 3 {
                xyz[i] = value;
            }
        }
        self.mesh.positions.push(DVec3::from_array(xyz));
        Ok(())
    }

    /// `vt u v [w]`.
    fn texcoord(&mut self, fields: SplitAsciiWhitespace<'_>) -> Result<(), ObjErrorKind> {
        let mut uv = [0.0; 2];
        let mut n = 0;
        for field in fields {
            if n < 3 {
                let value = coordinate(field, "vt", ["u", "v", "w"][n])?;
                if n < 2 {
                    uv[n] = value;
                }
            }
            n += 1;
        }
        if !(2..=3).contains(&n) {
            return Err(syntax(format!(
                "a 'vt' statement needs u v [w], found {n} values"
            )));
        }
        self.uv_values.extend_from_slice(&uv);
        Ok(())
    }

    /// `f v v/vt v//vn v/vt/vn ...`.
    fn face(&mut self, line: usize, fields: SplitAsciiWhitespace<'_>) -> Result<(), ObjErrorKind> {
        let size = fields.clone().count();
        if size < 3 {
            return Err(ObjErrorKind::FaceTooSmall(size));
        }
        if size > MAX_VALENCE {
            return Err(ObjErrorKind::FaceTooLarge(size));
        }
        let vertex_count = self.mesh.positions.len();
        let uv_count = self.uv_values.len() / 2;
        for (k, field) in fields.enumerate() {
            let corner = k + 1;
            let mut parts = field.split('/');
            let v = parts.next().unwrap_or("");
            let vt = parts.next();
            let vn = parts.next();
            if parts.next().is_some() {
                return Err(syntax(format!(
                    "face corner {corner} '{}' has more than three '/'-separated indices",
                    quote(field)
                )));
            }
            let index = |text: &str, what: &str| -> Result<i64, ObjErrorKind> {
                if text.is_empty() {
                    return Err(syntax(format!(
                        "face corner {corner} '{}': the {what} index is missing",
                        quote(field)
                    )));
                }
                text.parse().map_err(|_| {
                    syntax(format!(
                        "face corner {corner} '{}': {what} index '{}' {}",
                        quote(field),
                        quote(text),
                        not_an_integer(text)
                    ))
                })
            };
            let vertex = resolve(index(v, "vertex")?, vertex_count, "vertex")?;
            let uv = match (vt, vn) {
                (None, _) => None,
                (Some(""), Some(_)) => None,
                (Some(t), _) => Some(resolve(
                    index(t, "texture coordinate")?,
                    uv_count,
                    "texture coordinate",
                )?),
            };
            if let Some(n) = vn {
                // Normals are ignored, as OpenSubdiv ignores them: the index
                // must be an integer, but is not checked against the `vn` count.
                index(n, "normal")?;
            }
            self.check_uv_mode(line, corner, uv.is_some())?;
            self.mesh.face_vertices.push(vertex);
            if let Some(t) = uv {
                self.uv_indices.push(t);
            }
        }
        let end = u32::try_from(self.mesh.face_vertices.len())
            .map_err(|_| syntax("too many face corners for 32-bit indices".into()))?;
        self.mesh.face_offsets.push(end);
        Ok(())
    }

    /// Either every face corner has a texture coordinate, or none has.
    fn check_uv_mode(
        &mut self,
        line: usize,
        corner: usize,
        has_uv: bool,
    ) -> Result<(), ObjErrorKind> {
        let (mode, first_line) = *self.uv_mode.get_or_insert((has_uv, line));
        if mode == has_uv {
            return Ok(());
        }
        let this = if has_uv {
            "has a texture coordinate"
        } else {
            "has none"
        };
        let first = if mode { "has one" } else { "has none" };
        Err(ObjErrorKind::InconsistentTexcoords(if first_line == line {
            format!("corner {corner} of this face {this} but its corner 1 {first}")
        } else {
            format!(
                "corner {corner} of this face {this} but the first face corner (line {first_line}) {first}"
            )
        }))
    }

    /// `t NAME nI/nF/nS ints... floats... strings...`.
    fn tag(
        &mut self,
        line: usize,
        mut fields: SplitAsciiWhitespace<'_>,
    ) -> Result<(), ObjErrorKind> {
        let Some(name) = fields.next() else {
            return Err(syntax("a 't' statement needs a tag name".into()));
        };
        let bad = |message: String| ObjErrorKind::BadTag {
            tag: quote(name).into_owned(),
            message,
        };
        let Some(counts) = fields.next() else {
            return Err(bad(
                "the argument counts 'ints/floats/strings' are missing".into()
            ));
        };
        let parse_counts = || -> Option<[usize; 3]> {
            let mut it = counts.split('/');
            let c = [
                it.next()?.parse().ok()?,
                it.next()?.parse().ok()?,
                it.next()?.parse().ok()?,
            ];
            it.next().is_none().then_some(c)
        };
        let [ni, nf, ns] = parse_counts().ok_or_else(|| {
            bad(format!(
                "the argument counts must be written 'ints/floats/strings', found '{}'",
                quote(counts)
            ))
        })?;
        let args: Vec<&str> = fields.collect();
        let announced = ni.checked_add(nf).and_then(|n| n.checked_add(ns));
        if announced != Some(args.len()) {
            return Err(bad(format!(
                "the counts {counts} announce {} arguments but {} follow",
                announced.map_or_else(|| "too many".to_string(), |n| n.to_string()),
                args.len()
            )));
        }
        let ints = args[..ni]
            .iter()
            .enumerate()
            .map(|(i, s)| {
                s.parse::<i64>().map_err(|_| {
                    bad(format!(
                        "integer argument {} '{}' {}",
                        i + 1,
                        quote(s),
                        not_an_integer(s)
                    ))
                })
            })
            .collect::<Result<Vec<i64>, _>>()?;
        let float_args = &args[ni..ni + nf];
        let floats = float_args
            .iter()
            .enumerate()
            .map(|(i, s)| {
                s.parse::<f32>().map_err(|_| {
                    bad(format!(
                        "float argument {} '{}' is not a number",
                        i + 1,
                        quote(s)
                    ))
                })
            })
            .collect::<Result<Vec<f32>, _>>()?;
        let strings = &args[ni + nf..];
        let shape = |want: [usize; 3]| -> Result<(), ObjErrorKind> {
            if [ni, nf, ns] == want {
                Ok(())
            } else {
                Err(bad(format!(
                    "expects {}/{}/{} arguments, found {counts}",
                    want[0], want[1], want[2]
                )))
            }
        };
        let sharpness_ok = |floats: &[f32]| -> Result<(), ObjErrorKind> {
            match floats.iter().position(|s| !s.is_finite()) {
                Some(i) => Err(bad(format!(
                    "sharpness {} '{}' {}",
                    i + 1,
                    quote(float_args[i]),
                    not_a_finite_f32(float_args[i])
                ))),
                None => Ok(()),
            }
        };
        let kind = match name {
            "crease" => {
                if ns != 0 {
                    return Err(bad(format!("takes no string arguments, found {ns}")));
                }
                if ni < 2 {
                    return Err(bad(format!(
                        "needs a chain of at least 2 vertices, found {ni}"
                    )));
                }
                let edges = ni - 1;
                if nf != 1 && nf != edges {
                    return Err(bad(if edges == 1 {
                        format!("needs 1 sharpness, found {nf}")
                    } else {
                        format!(
                            "{ni} vertices make {edges} edges: give 1 sharpness for all or {edges} (one per edge), found {nf}"
                        )
                    }));
                }
                sharpness_ok(&floats)?;
                ElementKind::Crease
            }
            "corner" => {
                if ns != 0 {
                    return Err(bad(format!("takes no string arguments, found {ns}")));
                }
                if ni < 1 {
                    return Err(bad("names no vertex".into()));
                }
                if nf != 1 && nf != ni {
                    return Err(bad(format!(
                        "give 1 sharpness for all {ni} vertices or one each, found {nf}"
                    )));
                }
                sharpness_ok(&floats)?;
                ElementKind::Corner
            }
            "hole" => {
                if nf != 0 || ns != 0 {
                    return Err(bad(format!(
                        "takes only face indices (n/0/0), found {counts}"
                    )));
                }
                if ni < 1 {
                    return Err(bad("names no face".into()));
                }
                ElementKind::Hole
            }
            "interpolateboundary" => {
                shape([1, 0, 0])?;
                let value = match ints[0] {
                    0 => BoundaryInterpolation::None,
                    1 => BoundaryInterpolation::EdgeAndCorner,
                    2 => BoundaryInterpolation::EdgeOnly,
                    v => {
                        return Err(bad(format!(
                            "unknown value {v}: expected 0 (none), 1 (edge and corner) or 2 (edge only)"
                        )));
                    }
                };
                self.set_option(0, line, name);
                self.tags.boundary = Some(value);
                return Ok(());
            }
            "facevaryinginterpolateboundary" => {
                shape([1, 0, 0])?;
                let value = FVarLinearInterpolation::from_code(ints[0]).ok_or_else(|| {
                    bad(format!(
                        "unknown value {}: expected 0 (none) to 5 (all)",
                        ints[0]
                    ))
                })?;
                self.set_option(1, line, name);
                self.tags.fvar = Some(value);
                return Ok(());
            }
            "creasemethod" => {
                shape([0, 0, 1])?;
                let value = match strings[0] {
                    "normal" => CreasingMethod::Uniform,
                    "chaikin" => CreasingMethod::Chaikin,
                    s => {
                        return Err(bad(format!(
                            "unknown value '{}': expected 'normal' or 'chaikin'",
                            quote(s)
                        )));
                    }
                };
                self.set_option(2, line, name);
                self.tags.creasing = Some(value);
                return Ok(());
            }
            "smoothtriangles" => {
                shape([0, 0, 1])?;
                let value = match strings[0] {
                    "catmark" => TriangleSubdivision::Catmark,
                    "smooth" => TriangleSubdivision::Smooth,
                    s => {
                        return Err(bad(format!(
                            "unknown value '{}': expected 'catmark' or 'smooth'",
                            quote(s)
                        )));
                    }
                };
                self.set_option(3, line, name);
                self.tags.triangles = Some(value);
                return Ok(());
            }
            _ => {
                self.warn(line, format!("unknown tag '{}'", quote(name)), true);
                return Ok(());
            }
        };
        self.element_tags.push(ElementTag {
            line,
            kind,
            ints,
            floats,
        });
        Ok(())
    }

    /// Records the line of an option tag, warning when it overrides an earlier one.
    fn set_option(&mut self, slot: usize, line: usize, name: &str) {
        let previous = std::mem::replace(&mut self.option_lines[slot], line);
        if previous != 0 {
            self.warn(
                line,
                format!("this '{name}' tag overrides the one at line {previous}"),
                false,
            );
        }
    }

    /// Resolves the element tags and assembles the result.
    fn finish(mut self) -> Result<ShapeFile, (usize, ObjErrorKind)> {
        let vertex_count = self.mesh.positions.len();
        let face_count = self.mesh.face_count();
        for tag in &self.element_tags {
            let (what, count) = match tag.kind {
                ElementKind::Hole => ("face", face_count),
                _ => ("vertex", vertex_count),
            };
            let mut indices = Vec::with_capacity(tag.ints.len());
            for &index in &tag.ints {
                if index < 0 || index as u64 >= count as u64 {
                    return Err((
                        tag.line,
                        ObjErrorKind::TagOutOfRange {
                            tag: tag.kind.name().to_string(),
                            what,
                            index,
                            count,
                        },
                    ));
                }
                indices.push(index as u32);
            }
            let sharpness = |i: usize| {
                if tag.floats.len() == 1 {
                    tag.floats[0]
                } else {
                    tag.floats[i]
                }
            };
            match tag.kind {
                ElementKind::Crease => {
                    self.mesh
                        .creases
                        .extend(indices.windows(2).enumerate().map(|(i, pair)| Crease {
                            vertices: [pair[0], pair[1]],
                            sharpness: sharpness(i),
                        }));
                }
                ElementKind::Corner => {
                    self.mesh
                        .corners
                        .extend(indices.iter().enumerate().map(|(i, &vertex)| Corner {
                            vertex,
                            sharpness: sharpness(i),
                        }));
                }
                ElementKind::Hole => self.mesh.holes.extend_from_slice(&indices),
            }
        }
        if let Some((true, _)) = self.uv_mode {
            self.mesh.fvar_channels = vec![FVarChannel {
                width: 2,
                values: self.uv_values,
                indices: self.uv_indices,
            }];
        }
        Ok(ShapeFile {
            mesh: self.mesh,
            tags: self.tags,
            warnings: self.warnings,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resolve_counts_relative_indices_from_the_end() {
        assert_eq!(resolve(1, 3, "vertex"), Ok(0));
        assert_eq!(resolve(3, 3, "vertex"), Ok(2));
        assert_eq!(resolve(-1, 3, "vertex"), Ok(2));
        assert_eq!(resolve(-3, 3, "vertex"), Ok(0));
        for bad in [0, 4, -4, i64::MIN, i64::MAX] {
            assert_eq!(
                resolve(bad, 3, "vertex"),
                Err(ObjErrorKind::IndexOutOfRange {
                    what: "vertex",
                    index: bad,
                    count: 3
                })
            );
        }
    }

    #[test]
    fn long_fields_are_shortened_in_messages() {
        let long = "x".repeat(100);
        assert_eq!(quote(&long).len(), QUOTE_LIMIT + 3);
        assert_eq!(quote("abc"), "abc");
    }

    #[test]
    fn quoted_fields_escape_control_characters() {
        assert!(matches!(
            quote("plain 'text' \"é\" \u{fffd}"),
            Cow::Borrowed(_)
        ));
        assert_eq!(quote("\u{1b}[2J"), "\\u{1b}[2J");
        assert_eq!(quote("a\tb\0\r\u{7f}"), "a\\tb\\0\\r\\u{7f}");
        assert_eq!(quote("back\\slash"), "back\\\\slash");
        assert_eq!(quote("\u{202e}rtl"), "\\u{202e}rtl");
        // The limit counts the field's characters, before escaping.
        let long = "\u{1b}".repeat(100);
        assert_eq!(
            quote(&long),
            format!("{}...", "\\u{1b}".repeat(QUOTE_LIMIT))
        );
        // Warnings quote the same way.
        let shape = parse_obj("\u{1b}]0;title\u{7} 1 2\n", Path::new("<memory>")).unwrap();
        assert_eq!(
            shape.warnings[0].message,
            "unknown statement '\\u{1b}]0;title\\u{7}'"
        );
        assert!(shape.warnings[0].ignored);
        assert_eq!(
            shape.warnings[0].to_string(),
            "line 1: unknown statement '\\u{1b}]0;title\\u{7}'; the line is ignored"
        );
    }
}

#[cfg(test)]
mod read_tests {
    use super::*;

    /// A file of several huge pages reads into a map with the bytes
    /// `fs::read` gives; a file whose size the metadata does not tell
    /// (`/proc`) is read whole all the same.
    #[test]
    fn files_read_whole() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("big.obj");
        let bytes: Vec<u8> = (0..(5 << 20) + 123).map(|i| (i * 7 % 251) as u8).collect();
        std::fs::write(&path, &bytes).unwrap();
        let read_bytes = |path: &Path| {
            let file = std::fs::File::open(path)?;
            let len = file.metadata()?.len();
            read_bytes(file, len, path)
        };
        let read = read_bytes(&path).unwrap();
        // (Unless maps are turned off for the run.)
        assert!(read.is_mapped() || std::env::var("SUBDIV_HUGE_PAGES").as_deref() == Ok("0"));
        assert!(read.as_slice() == bytes.as_slice());
        // In pieces, one per thread of the pool.
        for threads in [2, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let read = pool.install(|| read_bytes(&path)).unwrap();
            assert!(read.as_slice() == bytes.as_slice(), "{threads} threads");
        }
        let status = read_bytes(Path::new("/proc/self/status")).unwrap();
        assert!(
            status.starts_with(b"Name:"),
            "{:?}",
            &status[..status.len().min(20)]
        );
    }

    /// A file of many blocks, read a block at a time (one thread, or a
    /// file under 4 MiB) and whole in chunks (a larger one on several
    /// threads): what parsing its text gives, an error on the same line;
    /// a directory is an I/O error on line 0.
    #[test]
    fn files_read_a_block_at_a_time() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("torus.obj");
        let mesh = crate::shapes::with_torus_uvs(crate::shapes::torus(250, 200), 250, 200);
        crate::io::write_mesh_obj(&path, &mesh, crate::Precision::F64).unwrap();
        let mut text = std::fs::read_to_string(&path).unwrap();
        assert!(text.len() > PARALLEL_BYTES, "{}", text.len());
        // A line longer than the buffer.
        text.push_str(&format!("# {}\n", "x".repeat(3 * BLOCK)));
        for bad in [false, true] {
            if bad {
                text.push_str("f 1 2 999999\n");
            }
            let want = parse_obj_general(&text, &path);
            assert_eq!(want.is_err(), bad);
            // The whole text, and its first lines only.
            for part in [text.len(), text[..2 * BLOCK + 7].rfind('\n').unwrap() + 1] {
                let whole = part == text.len();
                let text = &text[..part];
                std::fs::write(&path, text).unwrap();
                let want = if whole {
                    want.clone()
                } else {
                    parse_obj_general(text, &path)
                };
                for threads in [1, 2] {
                    let pool = rayon::ThreadPoolBuilder::new()
                        .num_threads(threads)
                        .build()
                        .unwrap();
                    let got = pool.install(|| read_obj(&path));
                    assert_eq!(got, want, "{threads} threads, {} bytes", text.len());
                }
            }
        }
        let error = read_obj(dir.path()).unwrap_err();
        assert!(matches!(error.kind, ObjErrorKind::Io(_)) && error.line == 0);
    }

    /// Text that is not UTF-8 everywhere — bad bytes in numbers, keywords,
    /// tags, comments and ignored statements, at line ends, before a
    /// carriage return, cut sequences, a byte-order mark — reads as its
    /// `String::from_utf8_lossy` replacement reads: the same mesh, warnings
    /// and first error, line by line and in chunks.
    #[test]
    fn bytes_read_as_their_lossy_text() {
        /// Text read at most `most` bytes at a time.
        struct Trickle<'a> {
            text: &'a [u8],
            most: usize,
        }
        impl std::io::Read for Trickle<'_> {
            fn read(&mut self, buffer: &mut [u8]) -> std::io::Result<usize> {
                let n = buffer.len().min(self.most).min(self.text.len());
                buffer[..n].copy_from_slice(&self.text[..n]);
                self.text = &self.text[n..];
                Ok(n)
            }
        }
        let pieces: [&[u8]; 16] = [
            b"v 0 0 0\n",
            b"v 1 0 0\r\n",
            b"vt 0 1\n",
            b"f 1 2 3\n",
            b"f 1/1 2/1 3/1\n",
            b"# \xff\xfe comment\n",
            b"vn 0 \xe2\x82 1\n",
            b"g \xc3\n",
            b"v 1 \xff 0\n",
            b"\xffv 0 0 0\n",
            b"x\xe2\x82\r\n",
            b"t crease 2/1/0 0 1 \xf0\x9f\x98\n",
            b"s off\xe9\n",
            b"v 2 2 2 # \xe9\xe9\n",
            b"\xef\xbb\xbf\n",
            b"f 1 2 3 \xc0\n",
        ];
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let file = Path::new("u.obj");
        for round in 0..600u32 {
            let mut text: Vec<u8> = if round.is_multiple_of(5) {
                b"\xef\xbb\xbf".to_vec()
            } else {
                Vec::new()
            };
            text.extend_from_slice(b"v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\n");
            for _ in 0..1 + round % 9 {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                // Mostly good lines, now and then a bad one.
                let pick = if x.is_multiple_of(3) {
                    x >> 8
                } else {
                    (x >> 8) % 5
                };
                text.extend_from_slice(pieces[pick as usize % pieces.len()]);
            }
            if x.is_multiple_of(4) {
                text.pop();
            }
            let lossy = String::from_utf8_lossy(&text);
            let want = parse_obj_general(&lossy, file);
            assert_eq!(parse(&text, file, true), want, "{lossy:?}");
            // A block at a time, blocks cutting lines, carriage returns,
            // byte-order marks and UTF-8 sequences anywhere, lines longer
            // than the buffer, reads shorter than asked for.
            for block in [1, 2, 3, 5, 8, 13, 64] {
                for most in [1, 4, usize::MAX] {
                    let mut source = Trickle { text: &text, most };
                    let got = read_streaming(&mut source, file, block, text.len() * (most % 2));
                    assert_eq!(got, want, "block {block}, reads of {most}: {lossy:?}");
                }
            }
            for chunks in [2, 3] {
                let text = strip_bom(&text);
                let got = parse_chunked(text, file, chunks)
                    .unwrap_or_else(|| parse_lines(text, file, true));
                assert_eq!(got, want, "{chunks} chunks: {lossy:?}");
            }
        }
    }
}
