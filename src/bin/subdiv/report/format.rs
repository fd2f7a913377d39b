//! Numbers and labels as the report prints them.

use subdiv::options::Options;

// ---------------------------------------------------------------------------
// Formatting
// ---------------------------------------------------------------------------

/// A short label of all five options.
pub fn options_label(o: &Options) -> String {
    format!(
        "{}, boundary {}, creasing {}, triangles {}, fvar {}",
        o.scheme.name(),
        o.boundary.name(),
        o.creasing.name(),
        o.triangles.name(),
        o.fvar.name()
    )
}

/// A deviation for tables: `0`, `∞` or `3.1e-16`.
pub fn format_deviation(d: f64) -> String {
    if d == 0.0 {
        "0".into()
    } else if !d.is_finite() {
        "∞".into()
    } else {
        format!("{d:.1e}")
    }
}

/// A deviation for summaries: zero reads `0 (bit-identical)`.
pub(crate) fn format_worst(d: f64) -> String {
    if d == 0.0 {
        "0 (bit-identical)".into()
    } else {
        format_deviation(d)
    }
}

/// Seconds as milliseconds with 3 significant digits or so.
pub fn format_ms(seconds: f64) -> String {
    let ms = seconds * 1e3;
    if ms < 0.01 {
        format!("{ms:.4}")
    } else if ms < 1.0 {
        format!("{ms:.3}")
    } else if ms < 100.0 {
        format!("{ms:.2}")
    } else {
        format!("{ms:.0}")
    }
}

/// A file-name-safe version of `name`, prefixed with its index.
pub(crate) fn slug(index: usize, name: &str) -> String {
    let mut s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '-'
            }
        })
        .collect();
    s.truncate(40);
    format!("{:02}-{}", index + 1, s.trim_matches('-'))
}
