//! Reading a large OBJ file on several threads: the text is cut into chunks
//! of whole lines, each read by the fast path ([`super::fast`]) on its own
//! thread, and the chunks are joined in order. A face's indices are
//! absolute, so a chunk needs nothing from the chunks before it but their
//! vertex and texture-coordinate counts, which only the checks need: each
//! chunk records how many it needs before it, and the join checks them.
//!
//! Lines whose meaning does not depend on what came before (`t` tags,
//! statements that only warn) are kept with their line numbers and read by
//! the general parser after the join, in file order. A `v`, `vt` or `f`
//! line the fast path does not take, or any doubt in the join, gives up:
//! the caller then reads the whole file line by line, so the result and
//! the first error are always the sequential reader's.

use super::fast;
use glam::DVec3;
use rayon::prelude::*;
use std::borrow::Cow;

/// What one chunk read.
#[derive(Default)]
pub(super) struct Chunk<'a> {
    /// Lines in the chunk.
    pub lines: usize,
    pub positions: Vec<DVec3>,
    pub uv_values: Vec<f64>,
    /// 0-based vertex of every face corner.
    pub face_vertices: Vec<u32>,
    /// Where each face ends in `face_vertices`.
    pub face_ends: Vec<u32>,
    pub uv_indices: Vec<u32>,
    /// Vertices (texture coordinates) the chunks before must have defined
    /// for every index of this chunk's faces to be in range.
    pub needs: (usize, usize),
    /// Whether the first face has texture coordinates, and its line (in
    /// the chunk, 1-based); every face of the chunk agrees with it.
    pub first_face: Option<(bool, usize)>,
    /// Lines for the general parser, with their line numbers in the chunk.
    pub deferred: Vec<(usize, Cow<'a, str>)>,
}

/// Reads one chunk; `None` when a line needs the sequential reader.
fn read_chunk(text: &[u8]) -> Option<Chunk<'_>> {
    let mut c = Chunk::default();
    let mut cursor = fast::Cursor::new(text);
    let mut line = 0;
    while !cursor.is_done() {
        line += 1;
        c.lines = line;
        let rest = cursor.rest();
        let end = match rest {
            [b'v', s, tail @ ..] if fast::is_blank(*s) => {
                let (p, end) = fast::numbers::<3>(tail)?;
                c.positions.push(DVec3::from_array(p));
                2 + end
            }
            [b'v', b't', s, tail @ ..] if fast::is_blank(*s) => {
                let (uv, end) = fast::numbers::<2>(tail)?;
                c.uv_values.extend_from_slice(&uv);
                3 + end
            }
            [b'f', s, tail @ ..] if fast::is_blank(*s) => {
                let (had_vertices, had_uvs) = (c.face_vertices.len(), c.uv_indices.len());
                let (with_uv, end) = fast::face(
                    tail,
                    usize::MAX,
                    usize::MAX,
                    crate::mesh::MAX_VALENCE,
                    &mut c.face_vertices,
                    &mut c.uv_indices,
                )?;
                if c.first_face.get_or_insert((with_uv, line)).0 != with_uv {
                    return None;
                }
                let need = |indices: &[u32], have: usize| {
                    let top = indices.iter().max().map_or(0, |&m| m as usize + 1);
                    top.saturating_sub(have)
                };
                let (vertices, uvs) = (&c.face_vertices[had_vertices..], &c.uv_indices[had_uvs..]);
                c.needs.0 = c.needs.0.max(need(vertices, c.positions.len()));
                c.needs.1 = c.needs.1.max(need(uvs, c.uv_values.len() / 2));
                c.face_ends.push(u32::try_from(c.face_vertices.len()).ok()?);
                2 + end
            }
            _ => {
                let end = fast::line_end(rest);
                if !fast::ignored(&rest[..end]) {
                    let text = cursor.take_line();
                    // What the general parser takes for the keyword.
                    let keyword = text
                        .split('#')
                        .next()
                        .unwrap_or("")
                        .split_ascii_whitespace()
                        .next();
                    match keyword {
                        None => {}
                        Some("v" | "vt" | "f") => return None,
                        Some(_) => c.deferred.push((line, text)),
                    }
                    continue;
                }
                end
            }
        };
        cursor.skip(end);
    }
    Some(c)
}

/// `text` (no byte-order mark; UTF-8 or not, as [`fast::Cursor`] reads it) cut into `count` chunks of whole lines, read
/// in parallel; `None` when some chunk needs the sequential reader.
pub(super) fn read_chunks(text: &[u8], count: usize) -> Option<Vec<Chunk<'_>>> {
    let mut pieces = Vec::with_capacity(count);
    let mut rest = text;
    for k in (1..count).rev() {
        let target = rest.len() / (k + 1);
        let cut = match rest[target..].iter().position(|&b| b == b'\n') {
            Some(p) => target + p + 1,
            None => rest.len(),
        };
        let (piece, tail) = rest.split_at(cut);
        pieces.push(piece);
        rest = tail;
    }
    pieces.push(rest);
    pieces.into_par_iter().map(read_chunk).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::{mesh_to_obj_string, parse_obj_chunked, parse_obj_general};
    use std::path::Path;

    /// A production-like file with UVs and tags: every chunking reads it in
    /// parallel (no chunk gives up) and joins it into the sequential result;
    /// a face pointing past the vertices defined so far makes the join give
    /// up, and the error is the sequential reader's.
    #[test]
    fn chunks_join_into_the_sequential_result() {
        let mesh = crate::shapes::production(16, 9);
        let text = mesh_to_obj_string(&mesh, crate::Precision::F64);
        assert!(text.contains("\nt crease ") && text.contains("\nvt "));
        let file = Path::new("p.obj");
        let general = parse_obj_general(&text, file);
        assert!(general.is_ok());
        for pieces in [1, 2, 3, 5, 16, 200] {
            let read = read_chunks(text.as_bytes(), pieces).expect("every line is read in chunks");
            assert_eq!(read.len(), pieces);
            let lines: usize = read.iter().map(|c| c.lines).sum();
            assert_eq!(lines, text.lines().count());
            assert_eq!(lines, fast::lines(text.as_bytes()).count());
            assert_eq!(parse_obj_chunked(&text, file, pieces), general, "{pieces}");
        }
        // A face before the vertex it names: the chunks read, the join
        // gives up, and the error is the line-by-line one.
        let early = "f 1 2 4\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n".repeat(3);
        let expected = parse_obj_general(&early, file);
        assert!(
            expected.as_ref().is_err_and(|e| e.line == 1),
            "{expected:?}"
        );
        assert!(read_chunks(early.as_bytes(), 3).is_some());
        assert_eq!(parse_obj_chunked(&early, file, 3), expected);
    }
}
