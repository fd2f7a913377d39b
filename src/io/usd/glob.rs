//! Prim path patterns ([`UsdReadOptions::prims`](super::UsdReadOptions::prims)):
//! `*` and `?` within a path segment, `**` across segments.

/// One element of a compiled pattern.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Token {
    /// This byte.
    Byte(u8),
    /// One byte other than `/`.
    One,
    /// Any run of bytes other than `/`.
    Segment,
    /// Any run of bytes.
    Any,
    /// `/**/`: a single `/`, or `/`, any run, `/`.
    Dirs,
}

/// A compiled prim path pattern.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct Pattern {
    text: String,
    tokens: Vec<Token>,
}

impl Pattern {
    /// Compiles `text`, or says why it cannot match a prim path.
    pub(super) fn new(text: &str) -> Result<Pattern, &'static str> {
        if !text.starts_with('/') {
            return Err("does not start with '/' (prim paths are absolute)");
        }
        let bytes = text.as_bytes();
        let mut tokens = Vec::with_capacity(bytes.len());
        let mut i = 0;
        while let Some(&b) = bytes.get(i) {
            if bytes[i..].starts_with(b"/**/") {
                tokens.push(Token::Dirs);
                i += 4;
                continue;
            }
            match b {
                b'*' if bytes.get(i + 1) == Some(&b'*') => {
                    tokens.push(Token::Any);
                    i += 2;
                    // `***` and longer mean `**`.
                    while bytes.get(i) == Some(&b'*') {
                        i += 1;
                    }
                }
                b'*' => {
                    tokens.push(Token::Segment);
                    i += 1;
                }
                b'?' => {
                    tokens.push(Token::One);
                    i += 1;
                }
                _ => {
                    tokens.push(Token::Byte(b));
                    i += 1;
                }
            }
        }
        Ok(Pattern {
            text: text.to_string(),
            tokens,
        })
    }

    /// The pattern as given.
    pub(super) fn text(&self) -> &str {
        &self.text
    }

    /// Whether `path` matches the whole pattern: dynamic programming over
    /// (token, byte) pairs, so no pattern takes more than
    /// `tokens × bytes` steps.
    pub(super) fn matches(&self, path: &str) -> bool {
        let path = path.as_bytes();
        let n = path.len();
        // `reach[j]`: the tokens matched so far can end before byte `j`.
        let mut reach = vec![false; n + 1];
        reach[0] = true;
        for &token in &self.tokens {
            let mut next = vec![false; n + 1];
            match token {
                Token::Byte(b) => {
                    for j in 0..n {
                        next[j + 1] = reach[j] && path[j] == b;
                    }
                }
                Token::One => {
                    for j in 0..n {
                        next[j + 1] = reach[j] && path[j] != b'/';
                    }
                }
                Token::Segment => {
                    let mut open = false;
                    for j in 0..=n {
                        open = reach[j] || (open && j > 0 && path[j - 1] != b'/');
                        next[j] = open;
                    }
                }
                Token::Any => {
                    let mut open = false;
                    for j in 0..=n {
                        open = open || reach[j];
                        next[j] = open;
                    }
                }
                Token::Dirs => {
                    // `/`, then any run ending in `/`, or just the one `/`.
                    let mut open = false;
                    for j in 0..n {
                        open = open || (reach[j] && path[j] == b'/');
                        next[j + 1] = open && path[j] == b'/';
                    }
                }
            }
            reach = next;
        }
        reach[n]
    }
}

#[cfg(test)]
mod tests {
    use super::Pattern;

    fn m(pattern: &str, path: &str) -> bool {
        Pattern::new(pattern).unwrap().matches(path)
    }

    #[test]
    fn stars_within_and_across_segments() {
        assert!(m("/World/Body", "/World/Body"));
        assert!(!m("/World/Body", "/World/Body2"));
        assert!(m("/World/*", "/World/Body"));
        assert!(!m("/World/*", "/World/Geo/Body"));
        assert!(!m("/World/*", "/World"));
        assert!(m("/World/B*y", "/World/Body"));
        assert!(m("/World/*dy", "/World/Body"));
        assert!(m("/World/Bod?", "/World/Body"));
        assert!(!m("/World/Bod?", "/World/Bod/"));
        assert!(m("/World/**", "/World/Geo/Body"));
        assert!(m("/World/**", "/World/Body"));
        assert!(!m("/World/**", "/World"));
        assert!(m("/**", "/A"));
        assert!(m("/**/Body", "/Body"));
        assert!(m("/**/Body", "/A/B/Body"));
        assert!(!m("/**/Body", "/A/BBody"));
        assert!(m("/A/**/Body", "/A/Body"));
        assert!(m("/A/**/Body", "/A/x/y/Body"));
        assert!(!m("/A/**/Body", "/AB/Body"));
        assert!(m("/A/**Body", "/A/x/yBody"));
        assert!(m("/*/*/Body", "/A/B/Body"));
        assert!(!m("/*/Body", "/A/B/Body"));
        assert!(m("/***", "/A/B"));
    }

    #[test]
    fn relative_patterns_are_refused() {
        assert!(Pattern::new("World/*").is_err());
        assert!(Pattern::new("").is_err());
    }
}
