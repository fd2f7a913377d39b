//! The reader's fast path for the lines that make up nearly all of a large
//! OBJ file — `v x y z`, `vt u v` and faces of plain positive indices
//! (`f 1 2 3`, `f 1/1 2/2 3/3`) — read byte by byte without splitting the
//! line into strings. A line it does not fully understand, or one that would
//! be an error or a warning, is left to the general parser (`read.rs`),
//! which then reads it as it always does: the results and the file:line
//! errors are the same either way.
//!
//! Numbers are parsed by `fast-float2`, only from fields of plain decimal
//! syntax (`[+-]digits[.digits][e[+-]digits]`), which it and Rust's own
//! parser both round correctly, to the same value.

use std::borrow::Cow;

/// A reading position in a text, at the start of a line. The fast path
/// reads the line where it stands ([`Cursor::rest`]: the text from the
/// line on, which the fast path reads up to the line feed) and moves past
/// it ([`Cursor::skip`]); the general parser takes the line as `str::lines`
/// cuts it ([`Cursor::take_line`]). So the fast path's lines are found by
/// the parsers' own pass over their bytes, and only the others by a search.
///
/// The text is bytes, not yet checked to be UTF-8: the fast path takes
/// only lines of ASCII characters, and the general parser's lines are
/// checked (or their bad bytes replaced) one at a time, as the whole text
/// would have been — a line feed is never part of a longer UTF-8 sequence.
pub(super) struct Cursor<'a> {
    text: &'a [u8],
    at: usize,
}

impl<'a> Cursor<'a> {
    /// At the first line of `text`.
    pub(super) fn new(text: &'a [u8]) -> Self {
        Cursor { text, at: 0 }
    }

    /// Whether every line has been read (`str::lines` gives no empty line
    /// after a final line feed).
    pub(super) fn is_done(&self) -> bool {
        self.at == self.text.len()
    }

    /// The text from the line at the cursor to the end.
    pub(super) fn rest(&self) -> &'a [u8] {
        &self.text[self.at..]
    }

    /// Moves past the line the fast path read, whose end (its line feed, or
    /// the end of the text) is at `end` in [`Cursor::rest`].
    pub(super) fn skip(&mut self, end: usize) {
        self.at = (self.at + end + 1).min(self.text.len());
    }

    /// The line at the cursor as `str::lines` cuts it — up to the line feed,
    /// a carriage return before it dropped — found by `memchr`'s vectorised
    /// search, with bytes that are not UTF-8 replaced as
    /// `String::from_utf8_lossy` replaces them; the cursor moves past it.
    pub(super) fn take_line(&mut self) -> Cow<'a, str> {
        let rest = &self.text[self.at..];
        let line = match memchr::memchr(b'\n', rest) {
            Some(end) => {
                self.at += end + 1;
                let line = &rest[..end];
                line.strip_suffix(b"\r").unwrap_or(line)
            }
            None => {
                self.at = self.text.len();
                rest
            }
        };
        String::from_utf8_lossy(line)
    }
}

/// The lines of `text` as `str::lines` cuts them, by [`Cursor::take_line`].
#[cfg(test)]
pub(super) fn lines(text: &[u8]) -> impl Iterator<Item = Cow<'_, str>> {
    let mut cursor = Cursor::new(text);
    std::iter::from_fn(move || (!cursor.is_done()).then(|| cursor.take_line()))
}

/// Whitespace within a line: ASCII whitespace but the line feed, which
/// ends it.
#[inline]
pub(super) fn is_blank(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\x0C' | b'\r')
}

/// Whether the line ends at `text[at]`: a line feed, or the end of the text.
#[inline]
fn is_line_end(text: &[u8], at: usize) -> bool {
    text.get(at).is_none_or(|&b| b == b'\n')
}

/// The end of the line that starts `text`: its line feed, or the end of the
/// text.
#[inline]
pub(super) fn line_end(text: &[u8]) -> usize {
    memchr::memchr(b'\n', text).unwrap_or(text.len())
}

/// ASCII whitespace as `str::split_ascii_whitespace` counts it.
#[inline]
pub(super) fn is_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\n' | b'\x0C' | b'\r')
}

/// A finite number of plain decimal syntax, or `None`: a field starting
/// (after an optional sign) with a digit or a point, so never `inf` or
/// `nan`, that `fast-float2` reads whole. Where it reads a field whole, it
/// and Rust's parser agree on the syntax and round to the same value; a
/// field it reads only in part (`1e`, `1_0`, `0x1`, `1,5`) is left to the
/// general parser.
#[cfg(test)]
fn number(s: &[u8]) -> Option<f64> {
    let mut at = 0;
    let x = number_at(s, &mut at)?;
    (at == s.len()).then_some(x)
}

/// The number at `line[*at..]` (which starts a field), `*at` moved past
/// it, when it is of plain decimal syntax, finite, and the whole field
/// ([`number`]'s rules): read where it stands, the field's end found by the
/// parser itself. A number's characters are never whitespace, so the
/// parser stops where the field ends or earlier. The field's syntax is
/// `fast-float2`'s to judge: what it reads other than plain decimals
/// (`inf`, `infinity`, `nan`) is never finite.
#[inline]
fn number_at(line: &[u8], at: &mut usize) -> Option<f64> {
    // `fast-float2` reads a field that starts (after an optional sign)
    // with a digit or a point as a number, or else `inf`, `infinity` or
    // `nan`, which are not finite.
    let (x, used): (f64, usize) = fast_float2::parse_partial(line.get(*at..)?).ok()?;
    *at += used;
    let whole = line.get(*at).is_none_or(|&b| is_space(b));
    (whole && x.is_finite()).then_some(x)
}

/// `*at` moved past the whitespace at `line[*at..]`, not past the line's end.
#[inline]
fn skip_blank(line: &[u8], at: &mut usize) {
    while line.get(*at).copied().is_some_and(is_blank) {
        *at += 1;
    }
}

/// Exactly `N` finite numbers after the keyword, nothing else on the line:
/// `line` starts after the keyword and runs to its line feed (or further:
/// the rest of the text). The numbers and where the line ends in `line`.
#[inline]
pub(super) fn numbers<const N: usize>(line: &[u8]) -> Option<([f64; N], usize)> {
    let mut at = 0;
    let mut out = [0.0; N];
    for x in &mut out {
        skip_blank(line, &mut at);
        *x = number_at(line, &mut at)?;
    }
    skip_blank(line, &mut at);
    is_line_end(line, at).then_some((out, at))
}

/// The digits at `line[*at..]` (at least one, at most `most`) as a
/// number, `*at` moved past them; `None` without a digit or with more than
/// `most` (at most 19, so the value fits).
#[inline(always)]
fn digits(line: &[u8], at: &mut usize, most: usize) -> Option<u64> {
    if let Some(n) = digits_in_word(line, at, most) {
        return n;
    }
    let start = *at;
    let mut n = 0u64;
    while let Some(&b) = line.get(*at) {
        if !b.is_ascii_digit() {
            break;
        }
        if *at - start == most {
            return None;
        }
        n = n * 10 + u64::from(b - b'0');
        *at += 1;
    }
    (*at > start).then_some(n)
}

/// [`digits`] eight bytes at a time, when the number ends within the eight
/// bytes at `line[*at..]` (face indices nearly always do): `None` when it
/// cannot tell (fewer than eight bytes left, eight digits), else
/// [`digits`]' answer.
#[inline(always)]
fn digits_in_word(line: &[u8], at: &mut usize, most: usize) -> Option<Option<u64>> {
    let (n, v, _) = word_digits(line, *at)?;
    if n == 0 || n > most {
        return Some(None);
    }
    *at += n;
    Some(Some(v))
}

/// The digits that start the eight bytes at `line[at..]`, when a
/// non-digit ends them within the eight: how many (0-7), their value and
/// the byte after them. `None` with fewer than eight bytes left or eight
/// digits.
#[inline(always)]
fn word_digits(line: &[u8], at: usize) -> Option<(usize, u64, u8)> {
    const ONES: u64 = 0x0101_0101_0101_0101;
    let word = u64::from_le_bytes(*line.get(at..)?.first_chunk::<8>()?);
    // Byte by byte (the first in the lowest byte): minus b'0', a digit is
    // 0-9 and no borrow; plus 0x46, a digit does not reach 0x80. The
    // lowest byte with a high bit set in either is the first non-digit;
    // the bytes below it borrowed and carried nothing into it.
    let value = word.wrapping_sub(ONES * u64::from(b'0'));
    let non_digit = (value | word.wrapping_add(ONES * 0x46)) & (ONES * 0x80);
    if non_digit == 0 {
        return None;
    }
    let n = (non_digit.trailing_zeros() / 8) as usize;
    let next = (word >> (8 * n)) as u8;
    if n == 0 {
        return Some((0, 0, next));
    }
    // The n digits moved up to the top bytes (leading zeros below them),
    // pairs combined, then the four pairs by two independent products
    // whose high halves add up to the eight-digit value.
    let mut v = value << (8 * (8 - n));
    v = (v * 10 + (v >> 8)) & 0x00ff_00ff_00ff_00ff;
    let low = (v & 0x0000_00ff_0000_00ff).wrapping_mul(100 + (1_000_000 << 32));
    let high = ((v >> 16) & 0x0000_00ff_0000_00ff).wrapping_mul(1 + (10_000 << 32));
    Some((n, low.wrapping_add(high) >> 32, next))
}

/// A positive decimal index of at most nine digits (no sign, no overflow)
/// at `line[*at..]`, `*at` moved past it.
#[inline(always)]
fn index(line: &[u8], at: &mut usize) -> Option<usize> {
    digits(line, at, 9).filter(|&n| n > 0).map(|n| n as usize)
}

/// [`index`], and the byte after it ([`byte`]), taken from the eight
/// bytes the index was read from when it ends within them.
#[inline(always)]
fn index_and_next(line: &[u8], at: &mut usize) -> Option<(usize, u8)> {
    match word_digits(line, *at) {
        Some((0, ..)) => None,
        Some((n, v, next)) => {
            *at += n;
            (v > 0).then_some((v as usize, next))
        }
        None => {
            let v = index(line, at)?;
            Some((v, byte(line, *at)))
        }
    }
}

/// A normal index at `line[*at..]` the general parser accepts without a
/// second look — an optional minus and at most 18 digits — skipped.
#[inline(always)]
fn skip_normal_index(line: &[u8], at: &mut usize) -> Option<()> {
    if line.get(*at) == Some(&b'-') {
        *at += 1;
    }
    digits(line, at, 18).map(drop)
}

/// Whether `line` is a statement the reader ignores whatever follows its
/// keyword (normals, objects, groups, smoothing groups, materials).
#[inline]
pub(super) fn ignored(line: &[u8]) -> bool {
    [&b"vn"[..], b"o", b"g", b"s", b"usemtl", b"mtllib"]
        .iter()
        .any(|k| line.starts_with(k) && line.get(k.len()).is_none_or(|&b| is_space(b)))
}

/// The corners of a face line (`line` starts after the `f` and runs to its
/// line feed, or further: the rest of the text) whose every
/// corner is `v`, `v/vt`, `v//vn` or `v/vt/vn` with plain positive vertex
/// and texture-coordinate indices (and integer normal indices, which are
/// not checked against anything): their 0-based vertex and
/// texture-coordinate indices appended to `vertices` and `uvs`, whether
/// the corners have texture coordinates, and where the line ends in
/// `line`. `None` for anything else — other
/// forms, indices out of range (`vertex_count`, `uv_count`), mixed corners,
/// fewer than 3 or more than `max` corners — which the general parser
/// reads; `vertices` and `uvs` are then as they were.
///
/// One pass over the bytes: each corner's numbers are read where they
/// stand, with no field split first.
pub(super) fn face(
    line: &[u8],
    vertex_count: usize,
    uv_count: usize,
    max: usize,
    vertices: &mut Vec<u32>,
    uvs: &mut Vec<u32>,
) -> Option<(bool, usize)> {
    let (had_vertices, had_uvs) = (vertices.len(), uvs.len());
    let read = corners(line, max, vertices, uvs).filter(|c| {
        vertices.len() - had_vertices >= 3 && c.top_vertex <= vertex_count && c.top_uv <= uv_count
    });
    match read {
        Some(c) => Some((c.with_uv, c.end)),
        None => {
            vertices.truncate(had_vertices);
            uvs.truncate(had_uvs);
            None
        }
    }
}

/// What [`corners`] read of a face line.
struct Corners {
    /// Whether the corners have texture coordinates.
    with_uv: bool,
    /// Where the line ends.
    end: usize,
    /// The largest (1-based) vertex and texture-coordinate indices.
    top_vertex: usize,
    top_uv: usize,
}

/// The byte at `line[at]`, a line feed past the end of the text (which
/// ends the line as a line feed does).
#[inline(always)]
fn byte(line: &[u8], at: usize) -> u8 {
    line.get(at).copied().unwrap_or(b'\n')
}

/// [`face`]'s pass over the corners, appending their 0-based indices,
/// at most `max` corners, all of one form; their indices' range is left to
/// the caller, which checks the largest once. `None` (what was appended
/// left for the caller to take back) for a line the general parser reads.
#[inline(always)]
fn corners(
    line: &[u8],
    max: usize,
    vertices: &mut Vec<u32>,
    uvs: &mut Vec<u32>,
) -> Option<Corners> {
    let mut at = 0;
    // Whether the first corner had a texture coordinate; every other
    // corner must agree.
    let mut with_uv = None;
    let (mut top_vertex, mut top_uv, mut count) = (0, 0, 0);
    loop {
        while is_blank(byte(line, at)) {
            at += 1;
        }
        if byte(line, at) == b'\n' {
            return Some(Corners {
                with_uv: with_uv.unwrap_or(false),
                end: at,
                top_vertex,
                top_uv,
            });
        }
        let (v, mut next) = index_and_next(line, &mut at)?;
        // 0: no texture coordinate.
        let mut t = 0;
        if next == b'/' {
            at += 1;
            if byte(line, at) == b'/' {
                // `v//vn`: a normal index, read but not checked against the
                // normals, as the general parser does.
                at += 1;
                skip_normal_index(line, &mut at)?;
                next = byte(line, at);
            } else {
                (t, next) = index_and_next(line, &mut at)?;
                if next == b'/' {
                    at += 1;
                    skip_normal_index(line, &mut at)?;
                    next = byte(line, at);
                }
            }
        }
        // The corner ends here, or the line is not one the fast path reads.
        if !is_space(next) || *with_uv.get_or_insert(t != 0) != (t != 0) {
            return None;
        }
        count += 1;
        if count > max {
            return None;
        }
        top_vertex = top_vertex.max(v);
        vertices.push((v - 1) as u32);
        if t != 0 {
            top_uv = top_uv.max(t);
            uvs.push((t - 1) as u32);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Digits read eight bytes at a time or one by one: the same numbers,
    /// the same ends, the same refusals, on random text of digits, spaces,
    /// slashes, letters and bytes beyond ASCII.
    #[test]
    fn digits_by_word_and_by_byte_agree() {
        let by_byte = |line: &[u8], at: &mut usize, most: usize| {
            let start = *at;
            let mut n = 0u64;
            while let Some(&b) = line.get(*at).filter(|b| b.is_ascii_digit()) {
                if *at - start == most {
                    return None;
                }
                n = n * 10 + u64::from(b - b'0');
                *at += 1;
            }
            (*at > start).then_some(n)
        };
        let alphabet = b"0123456789012345678901234567890123456789 /-\n:/\x80\xb9\xff";
        let mut x = 0x853c_49e6_748f_ea9bu64;
        let mut words = 0;
        for _ in 0..300_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let len = (x % 14) as usize;
            let line: Vec<u8> = (0..len)
                .map(|k| alphabet[((x >> (3 * k + 5)) % alphabet.len() as u64) as usize])
                .collect();
            let most = [1, 3, 7, 9, 18][(x >> 60) as usize % 5];
            let (mut a, mut b) = (0, 0);
            let got = digits(&line, &mut a, most);
            let want = by_byte(&line, &mut b, most);
            // Where a refused number leaves `at` does not matter.
            assert_eq!(got, want, "{line:?} {most}");
            if got.is_some() {
                assert_eq!(a, b, "{line:?} {most}");
            }
            words += usize::from(digits_in_word(&line, &mut 0, most).is_some());
        }
        assert!(words > 50_000, "{words}");
    }

    #[test]
    fn lines_are_cut_as_str_lines_cuts_them() {
        for text in [
            "",
            "\n",
            "\n\n",
            "a",
            "a\n",
            "a\r\n",
            "a\r",
            "\r",
            "\r\n\r\n",
            "a\n\nb",
            "a\rb\r\n c\r\r\n",
            "é\n\r\nü",
            " \r\r",
        ] {
            let ours: Vec<Cow<'_, str>> = lines(text.as_bytes()).collect();
            assert_eq!(ours, text.lines().collect::<Vec<_>>(), "{text:?}");
        }
    }

    #[test]
    fn plain_numbers_only_and_the_same_values_as_std() {
        for s in [
            "0",
            "-0",
            "1",
            "+1.5",
            "-2.25e-3",
            "1E10",
            ".5",
            "5.",
            "-.5e+2",
            "123456789.123456789",
            "4.9406564584124654e-324",
            "1.7976931348623157e308",
            "0.1",
            "2.2250738585072011e-308",
        ] {
            let want: f64 = s.parse().unwrap();
            let got = number(s.as_bytes()).unwrap_or_else(|| panic!("{s}"));
            assert_eq!(got.to_bits(), want.to_bits(), "{s}");
        }
        for s in [
            "", "+", "-", ".", "e5", "1e", "1e+", "1.2.3", "inf", "nan", "infinity", "1_0", "0x10",
            "1e999", "-1e999", "1,5", "1 ", "١",
        ] {
            assert_eq!(number(s.as_bytes()), None, "{s:?}");
        }
    }

    /// Random fields over the characters of numbers: whatever the fast path
    /// reads, Rust's parser reads to the same bits; and it reads every field
    /// Rust's parser reads to a finite value.
    #[test]
    fn random_fields_agree_with_std() {
        let alphabet = b"0123456789.eE+-";
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut taken = 0;
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let len = 1 + (x % 12) as usize;
            let field: Vec<u8> = (0..len)
                .map(|k| alphabet[((x >> (4 * k + 4)) % alphabet.len() as u64) as usize])
                .collect();
            let text = std::str::from_utf8(&field).unwrap();
            let std = text.parse::<f64>().ok().filter(|v| v.is_finite());
            let fast = number(&field);
            assert_eq!(fast.map(f64::to_bits), std.map(f64::to_bits), "{text:?}");
            taken += usize::from(fast.is_some());
        }
        assert!(taken > 10_000, "{taken}");
    }

    #[test]
    fn numbers_take_exactly_n_fields() {
        let n3 = |s: &str| numbers::<3>(s.as_bytes());
        assert_eq!(n3(" 1 2 3"), Some(([1.0, 2.0, 3.0], 6)));
        assert_eq!(n3("\t1\t2  3 \r"), Some(([1.0, 2.0, 3.0], 9)));
        // The line ends at its line feed; what follows is the next line's.
        assert_eq!(n3(" 1 2 3\nv 4 5 6"), Some(([1.0, 2.0, 3.0], 6)));
        assert_eq!(n3(" 1 2 3\r\n"), Some(([1.0, 2.0, 3.0], 7)));
        assert_eq!(n3(" 1 2\n3"), None);
        assert_eq!(n3(" 1 2\n 3\n"), None);
        assert_eq!(n3(" 1 2"), None);
        assert_eq!(n3(" 1 2 3 4"), None);
        assert_eq!(n3(" 1 2 3 # comment"), None);
        assert_eq!(numbers::<2>(b" 0.5 0.25"), Some(([0.5, 0.25], 9)));
    }

    #[test]
    fn faces_of_plain_indices_only() {
        let (mut v, mut t) = (vec![7], vec![9]);
        let mut f = |line: &str, nv, nt| {
            let read = face(line.as_bytes(), nv, nt, 8, &mut v, &mut t);
            (read, v.split_off(1), t.split_off(1))
        };
        assert_eq!(f(" 1 2 3", 3, 0), (Some((false, 6)), vec![0, 1, 2], vec![]));
        assert_eq!(
            f(" 1/1 2/2 3/3 4/1", 4, 3),
            (Some((true, 16)), vec![0, 1, 2, 3], vec![0, 1, 2, 0])
        );
        // Normals: read as integers, not checked.
        assert_eq!(
            f(" 1//7 2//-1 3//0", 3, 0),
            (Some((false, 16)), vec![0, 1, 2], vec![])
        );
        assert_eq!(
            f("\t3/1/9  2/2/9\x0c1/1/-000000000000000009 \r", 3, 2),
            (Some((true, 39)), vec![2, 1, 0], vec![0, 1, 0])
        );
        assert_eq!(
            f(" 999999999 1 2", 999_999_999, 0),
            (Some((false, 14)), vec![999_999_998, 0, 1], vec![])
        );
        // The line ends at its line feed, wherever the next line's digits
        // are.
        assert_eq!(
            f(" 1 2 3\n4 5 6", 6, 0),
            (Some((false, 6)), vec![0, 1, 2], vec![])
        );
        assert_eq!(
            f(" 1/1 2/2 3/3\r\n12345678", 3, 3),
            (Some((true, 13)), vec![0, 1, 2], vec![0, 1, 2])
        );
        // Out of range, zero, negative, signs, normals, mixed, too few or
        // many, digits too many, anything after a corner, a line cut short
        // by its line feed: nothing appended.
        for line in [
            " 1 2 4",
            " 0 1 2",
            " -1 1 2",
            " +1 2 3",
            " 1//x 2//1 3//1",
            " 1/1/ 2/2/2 3/3/3",
            " 1/1/1/1 2/2 3/3",
            " 1// 2// 3//",
            " 1//- 2//1 3//1",
            " 1//1234567890123456789 2//1 3//1",
            " 1/ 2/ 3/",
            " 1/1 2//1 3/1",
            " 1/1 2 3",
            " 1 2",
            " 1 2\n3",
            " 1/1 2/2 3/\n3",
            " 1 2 3 1 2 3 1 2 3",
            " 1/4 2/1 3/1",
            " 1 2 3 #",
            " 1 2 3#",
            " 1 2 3a",
            " 1 2 0001234567",
            " 1 2 1234567890",
        ] {
            assert_eq!(f(line, 3, 3), (None, vec![], vec![]), "{line:?}");
        }
    }

    /// Random files of lines the fast path reads and lines it leaves (other
    /// number syntaxes, comments, negative and out-of-range indices,
    /// normals, mixed corners, tags, garbage): the result, or the error with
    /// its line, is the general parser's.
    #[test]
    fn the_fast_path_changes_nothing() {
        use crate::io::{parse_obj, parse_obj_chunked, parse_obj_general};
        use std::path::Path;
        let state = std::cell::Cell::new(0x9e37_79b9_7f4a_7c15u64);
        let next = |n: u64| {
            let mut x = state.get();
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            state.set(x);
            x % n
        };
        let numbers = [
            "0",
            "1",
            "-2.5",
            "1e3",
            "+.5",
            "5.",
            "inf",
            "nan",
            "1e999",
            "0x1",
            "1,5",
            "-0",
            "3.14159265358979323846",
            "1e-320",
            "#",
            "",
        ];
        let mut ok = 0;
        for _ in 0..3000 {
            let mut text = String::from("v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 1\n");
            for _ in 0..next(12) + 1 {
                // Mostly numbers both read; now and then one only the general
                // parser judges.
                let num = || {
                    let pick = if next(20) == 0 {
                        next(numbers.len() as u64)
                    } else {
                        next(7)
                    };
                    numbers[pick as usize].to_string()
                };
                let line = match next(9) {
                    0..=2 => format!("v {} {} {}", num(), num(), num()),
                    3 => format!("vt {} {}", num(), num()),
                    4 => format!("v  {}\t{} {} {}", num(), num(), num(), num()),
                    5..=7 => {
                        let corners = next(5) + 2;
                        let form = if next(5) == 0 { next(6) } else { next(2) * 2 };
                        let mut l = String::from("f");
                        for _ in 0..corners {
                            // Now and then out of range, zero or negative.
                            let v = if next(15) == 0 {
                                next(9) as i64 - 4
                            } else {
                                next(3) as i64 + 1
                            };
                            let t = if next(15) == 0 {
                                next(5) as i64 - 1
                            } else {
                                next(2) as i64 + 1
                            };
                            l.push(' ');
                            l.push_str(&match form {
                                0 | 1 => format!("{v}"),
                                2 | 3 => format!("{v}/{t}"),
                                4 => format!("{v}//{t}"),
                                _ => format!("{v}/{t}/1"),
                            });
                        }
                        l
                    }
                    _ => [
                        "# c",
                        "",
                        "vn 0 0 1",
                        "t crease 2/1/0 0 1 2",
                        "x y",
                        "f",
                        "v",
                        "g",
                        "s off",
                        "usemtl m#x",
                        "o#",
                        "vn",
                        "mtllibx a",
                    ][next(13) as usize]
                        .to_string(),
                };
                text.push_str(&line);
                text.push_str(if next(5) == 0 { "\r\n" } else { "\n" });
            }
            let fast = parse_obj(&text, Path::new("t.obj"));
            let general = parse_obj_general(&text, Path::new("t.obj"));
            assert_eq!(fast, general, "{text}");
            // Read in chunks on several threads (`chunks.rs`): the same.
            for pieces in [2, 3, 7] {
                let chunked = parse_obj_chunked(&text, Path::new("t.obj"), pieces);
                assert_eq!(chunked, general, "{pieces} chunks: {text}");
            }
            ok += usize::from(fast.is_ok_and(|s| s.mesh.face_count() > 0));
        }
        // Enough files that parse, with faces, for the fast path to matter.
        assert!(ok > 100, "{ok}");
    }
}
