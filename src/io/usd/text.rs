//! Scanning `.usda` text without parsing it: strings, asset paths and
//! comments skipped ([`skip_string`], [`skip_asset`], [`skip_line`]), for
//! the legacy type rewrite ([`super::legacy`]) and the checks that keep
//! the `openusd` crate out of harm ([`check_text`]).

/// Whether `b` can start an identifier.
pub(super) fn is_ident_start(b: u8) -> bool {
    b.is_ascii_alphabetic() || b == b'_'
}

/// Whether `b` can continue an identifier.
pub(super) fn is_ident(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_'
}

/// The end of the line starting at `i` (the newline's position).
pub(super) fn skip_line(bytes: &[u8], i: usize) -> usize {
    bytes
        .get(i..)
        .and_then(|rest| rest.iter().position(|&c| c == b'\n'))
        .map_or(bytes.len(), |p| i + p)
}

/// A quoted string in the text.
pub(super) struct Quoted {
    /// Where its content starts and ends.
    pub body: std::ops::Range<usize>,
    /// Past its closing quotes (or the end of the line or text).
    pub end: usize,
    /// Whether its closing quotes are there.
    pub closed: bool,
}

/// The string starting at `i` (single, double or triple quotes, with
/// backslash escapes; a single-quoted one ends at the end of its line).
pub(super) fn quoted(bytes: &[u8], i: usize) -> Quoted {
    let quote = bytes.get(i).copied().unwrap_or(b'"');
    let triple = [quote; 3];
    let open = if bytes.get(i..i + 3) == Some(&triple[..]) {
        3
    } else {
        1
    };
    let start = i + open;
    let mut j = start;
    while let Some(&c) = bytes.get(j) {
        let closes = if open == 3 {
            bytes.get(j..j + 3) == Some(&triple[..])
        } else {
            c == quote
        };
        if closes {
            return Quoted {
                body: start..j,
                end: j + open,
                closed: true,
            };
        }
        match c {
            b'\\' => j += 2,
            b'\n' if open == 1 => break,
            _ => j += 1,
        }
    }
    let end = j.min(bytes.len());
    Quoted {
        body: start.min(end)..end,
        end,
        closed: false,
    }
}

/// Past the string starting at `i` ([`quoted`]).
pub(super) fn skip_string(bytes: &[u8], i: usize) -> usize {
    quoted(bytes, i).end
}

/// Past the asset path starting at `i` (`@…@` or `@@@…@@@`).
pub(super) fn skip_asset(bytes: &[u8], i: usize) -> usize {
    let (close, start): (&[u8], usize) = if bytes.get(i..i + 3) == Some(b"@@@") {
        (b"@@@", i + 3)
    } else {
        (b"@", i + 1)
    };
    bytes
        .get(start..)
        .and_then(|rest| rest.windows(close.len()).position(|w| w == close))
        .map_or(bytes.len(), |p| start + p + close.len())
}

/// The deepest nesting of `(`, `[` and `{` [`check_text`] accepts: far
/// beyond real files (a prim hierarchy 256 levels deep), within what the
/// `openusd` crate's recursive parser does on the reader's stack.
pub(super) const MAX_NESTING: usize = 256;

/// The deepest nesting of `[` alone [`check_text`] accepts (USD's values
/// nest them twice at most: the crate parses nested `[` in time and memory
/// exponential in their depth — 30 levels take 5 s and 800 MB).
pub(super) const MAX_BRACKETS: usize = 8;

/// Refuses text that Pixar's parser refuses and the `openusd` crate reads
/// to its harm, before the crate parses it: the quoted name after `def`,
/// `over` or `class` (and an optional type name) must be an identifier
/// ([`super::is_identifier`]) — a `}` in one sends the crate's composition
/// into unbounded recursion, a stack overflow that aborts the process —;
/// a path (`</World/Body>`) may hold only the characters of names and path
/// punctuation ([`path_char`]) — an `inherits` path with NUL bytes and
/// blanks sends it into a loop that allocates until memory runs out —; and
/// brackets may nest [`MAX_NESTING`] deep, `[` [`MAX_BRACKETS`] deep.
pub(super) fn check_text(text: &str) -> Result<(), String> {
    let bytes = text.as_bytes();
    // 0: nothing; 1: after `def`/`over`/`class`; 2: after its type name.
    let mut state = 0u8;
    let (mut depth, mut brackets) = (0usize, 0usize);
    let mut i = 0;
    while let Some(&b) = bytes.get(i) {
        match b {
            b'#' => i = skip_line(bytes, i),
            b'"' | b'\'' => {
                let string = quoted(bytes, i);
                if state != 0 {
                    let body = text.get(string.body.clone()).unwrap_or("");
                    if !string.closed || !super::is_identifier(body) {
                        return Err(format!("the prim name {body:?} is not an identifier"));
                    }
                    state = 0;
                }
                i = string.end;
            }
            b'@' => {
                i = skip_asset(bytes, i);
                state = 0;
            }
            b'<' => {
                let body = bytes.get(i + 1..).unwrap_or(&[]);
                let Some(len) = body.iter().position(|&c| c == b'>') else {
                    return Err("a path (<…>) is not closed".to_string());
                };
                let path = text.get(i + 1..i + 1 + len).unwrap_or("");
                if let Some(c) = path.chars().find(|&c| !path_char(c)) {
                    let mut shown: String =
                        path.chars().take(40).flat_map(char::escape_debug).collect();
                    if path.chars().nth(40).is_some() {
                        shown.push('…');
                    }
                    return Err(format!("the path <{shown}> has the character {c:?}"));
                }
                i += len + 2;
                state = 0;
            }
            _ if is_ident_start(b) => {
                let start = i;
                while bytes
                    .get(i)
                    .is_some_and(|&c| is_ident(c) || matches!(c, b':' | b'.'))
                {
                    i += 1;
                }
                state = match (state, &text[start..i]) {
                    (_, "def" | "over" | "class") => 1,
                    (1, _) => 2,
                    _ => 0,
                };
            }
            b' ' | b'\t' | b'\r' | b'\n' => i += 1,
            _ => {
                match b {
                    b'(' | b'[' | b'{' => {
                        depth += 1;
                        brackets += usize::from(b == b'[');
                        if depth > MAX_NESTING || brackets > MAX_BRACKETS {
                            return Err(format!(
                                "brackets nest deeper than {MAX_NESTING} levels ({MAX_BRACKETS} for [)"
                            ));
                        }
                    }
                    b')' | b']' | b'}' => {
                        depth = depth.saturating_sub(1);
                        if b == b']' {
                            brackets = brackets.saturating_sub(1);
                        }
                    }
                    _ => {}
                }
                i += 1;
                state = 0;
            }
        }
    }
    Ok(())
}

/// Whether `c` may appear in a path: letters, digits, `_`, and the
/// punctuation of paths (`/ . : [ ] { } = - |`).
fn path_char(c: char) -> bool {
    c.is_alphanumeric()
        || matches!(
            c,
            '_' | '/' | '.' | ':' | '[' | ']' | '{' | '}' | '=' | '-' | '|'
        )
}

#[cfg(test)]
mod tests {
    use super::check_text;

    #[test]
    fn names_paths_and_nesting_are_checked() {
        let ok = "#usda 1.0\ndef Xform \"World\" (doc = \"a}\")\n{\n    over \"O\" {}\n    \
                  class \"_C\" {}\n    def Mesh \"M_1\" { token t = \"def\" }\n    \
                  string def = \"}\"\n    def '''Tri''' {}\n    \
                  def \"R\" (references = @a.usda@</A/B{v=x-1}C.attr:ns[/T]> inherits = <../S>) {}\n}\n\
                  # def \"}\" <a b>\n";
        assert_eq!(check_text(ok), Ok(()));
        let deep = format!(
            "{}{}",
            "def \"P\" {\n".repeat(247),
            "(x = [[[[[[[[]]]]]]]])"
        );
        assert_eq!(check_text(&deep), Ok(()));
        for bad in [
            "def \"Pa}\" {}",
            "def Xform \"a.b\" {}",
            "over Mesh \"\" {}",
            "class '''x y''' {}",
            "def \"unterminated",
            "def '''Open''",
            "def \"A\" (inherits = </_ F>) {}",
            "def \"A\" (inherits = </_\0F>) {}",
            "def \"A\" (inherits = </_F) {}",
            &format!("(doc = {}{})", "[".repeat(9), "]".repeat(9)),
            &"def \"P\" {\n".repeat(257),
        ] {
            assert!(check_text(bad).is_err(), "{bad}");
        }
    }
}
