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

/// ASCII whitespace as `str::split_ascii_whitespace` counts it.
#[inline]
pub(super) fn is_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\n' | b'\x0C' | b'\r')
}

/// The next field of `line` from `*at` (skipping whitespace first), or
/// `None` at the end of the line.
#[inline]
fn field<'a>(line: &'a [u8], at: &mut usize) -> Option<&'a [u8]> {
    let mut i = *at;
    while i < line.len() && is_space(line[i]) {
        i += 1;
    }
    if i == line.len() {
        *at = i;
        return None;
    }
    let start = i;
    while i < line.len() && !is_space(line[i]) {
        i += 1;
    }
    *at = i;
    Some(&line[start..i])
}

/// A finite number of plain decimal syntax, or `None`: a field starting
/// (after an optional sign) with a digit or a point, so never `inf` or
/// `nan`, that `fast-float2` reads whole. Where it reads a field whole, it
/// and Rust's parser agree on the syntax and round to the same value; a
/// field it reads only in part (`1e`, `1_0`, `0x1`, `1,5`) is left to the
/// general parser.
#[inline]
fn number(s: &[u8]) -> Option<f64> {
    let unsigned = match s.first()? {
        b'+' | b'-' => &s[1..],
        _ => s,
    };
    if !matches!(unsigned.first()?, b'0'..=b'9' | b'.') {
        return None;
    }
    let (x, used): (f64, usize) = fast_float2::parse_partial(s).ok()?;
    (used == s.len() && x.is_finite()).then_some(x)
}

/// Exactly `N` finite numbers after the keyword (`line` starts after it),
/// nothing else on the line.
#[inline]
pub(super) fn numbers<const N: usize>(line: &[u8]) -> Option<[f64; N]> {
    let mut at = 0;
    let mut out = [0.0; N];
    for x in &mut out {
        *x = number(field(line, &mut at)?)?;
    }
    field(line, &mut at).is_none().then_some(out)
}

/// A positive decimal index of at most nine digits (no sign, no overflow).
#[inline]
fn index(s: &[u8]) -> Option<u32> {
    if s.is_empty() || s.len() > 9 {
        return None;
    }
    let mut n = 0u32;
    for &b in s {
        if !b.is_ascii_digit() {
            return None;
        }
        n = n * 10 + u32::from(b - b'0');
    }
    (n > 0).then_some(n)
}

/// Whether a normal index is an integer the general parser accepts without
/// a second look: an optional minus and at most 18 digits.
#[inline]
fn normal_index(s: &[u8]) -> bool {
    let digits = s.strip_prefix(b"-").unwrap_or(s);
    !digits.is_empty() && digits.len() <= 18 && digits.iter().all(u8::is_ascii_digit)
}

/// Whether `line` is a statement the reader ignores whatever follows its
/// keyword (normals, objects, groups, smoothing groups, materials).
#[inline]
pub(super) fn ignored(line: &[u8]) -> bool {
    [&b"vn"[..], b"o", b"g", b"s", b"usemtl", b"mtllib"]
        .iter()
        .any(|k| line.starts_with(k) && line.get(k.len()).is_none_or(|&b| is_space(b)))
}

/// The corners of a face line (`line` starts after the `f`) whose every
/// corner is `v`, `v/vt`, `v//vn` or `v/vt/vn` with plain positive vertex
/// and texture-coordinate indices (and integer normal indices, which are
/// not checked against anything): their 0-based vertex
/// and texture-coordinate indices into `vertices` and `uvs` (cleared first),
/// and whether the corners have texture coordinates. `None` for anything
/// else — other forms, indices out of range (`vertex_count`, `uv_count`),
/// mixed corners, fewer than 3 or more than `max` corners — which the
/// general parser reads.
pub(super) fn face(
    line: &[u8],
    vertex_count: usize,
    uv_count: usize,
    max: usize,
    vertices: &mut Vec<u32>,
    uvs: &mut Vec<u32>,
) -> Option<bool> {
    vertices.clear();
    uvs.clear();
    let mut at = 0;
    let mut with_uv = None;
    while let Some(corner) = field(line, &mut at) {
        let mut parts = corner.split(|&b| b == b'/');
        let v = parts.next().unwrap_or_default();
        let (t, n) = (parts.next(), parts.next());
        if parts.next().is_some() {
            return None;
        }
        // `v//vn`: no texture coordinate. A normal index is read but not
        // checked against the normals, as the general parser does.
        let t = t.filter(|t| !(t.is_empty() && n.is_some()));
        if n.is_some_and(|n| !normal_index(n)) {
            return None;
        }
        let v = index(v)? as usize;
        if v > vertex_count || *with_uv.get_or_insert(t.is_some()) != t.is_some() {
            return None;
        }
        vertices.push((v - 1) as u32);
        if let Some(t) = t {
            let t = index(t)? as usize;
            if t > uv_count {
                return None;
            }
            uvs.push((t - 1) as u32);
        }
        if vertices.len() > max {
            return None;
        }
    }
    (vertices.len() >= 3).then_some(with_uv.unwrap_or(false))
}

#[cfg(test)]
mod tests {
    use super::*;

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
        assert_eq!(numbers::<3>(b" 1 2 3"), Some([1.0, 2.0, 3.0]));
        assert_eq!(numbers::<3>(b"\t1\t2  3 \r"), Some([1.0, 2.0, 3.0]));
        assert_eq!(numbers::<3>(b" 1 2"), None);
        assert_eq!(numbers::<3>(b" 1 2 3 4"), None);
        assert_eq!(numbers::<3>(b" 1 2 3 # comment"), None);
        assert_eq!(numbers::<2>(b" 0.5 0.25"), Some([0.5, 0.25]));
    }

    #[test]
    fn faces_of_plain_indices_only() {
        let (mut v, mut t) = (Vec::new(), Vec::new());
        let mut f = |line: &str, nv, nt| face(line.as_bytes(), nv, nt, 8, &mut v, &mut t);
        assert_eq!(f(" 1 2 3", 3, 0), Some(false));
        assert_eq!(f(" 1/1 2/2 3/3 4/1", 4, 3), Some(true));
        // Normals: read as integers, not checked.
        assert_eq!(f(" 1//7 2//-1 3//0", 3, 0), Some(false));
        assert_eq!(f(" 1/1/9 2/2/9 3/1/9", 3, 2), Some(true));
        // Out of range, zero, negative, signs, normals, mixed, too few or many.
        for line in [
            " 1 2 4",
            " 0 1 2",
            " -1 1 2",
            " +1 2 3",
            " 1//x 2//1 3//1",
            " 1/1/ 2/2/2 3/3/3",
            " 1/1/1/1 2/2 3/3",
            " 1// 2// 3//",
            " 1/1 2//1 3/1",
            " 1/1 2 3",
            " 1 2",
            " 1 2 3 1 2 3 1 2 3",
            " 1/4 2/1 3/1",
            " 1 2 3 #",
            " 1 2 1234567890",
        ] {
            assert_eq!(f(line, 3, 3), None, "{line:?}");
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
