//! The report's SVG plots: deviation per level and time per level.

use super::results::{InputReport, LevelResult, LimitResult, SetResult};
use super::settings::Settings;
use glam::DVec3;
use std::fmt::Write as _;
use subdiv::io::svg::escape;

pub(crate) const SVG_NS: &str = " xmlns=\"http://www.w3.org/2000/svg\"";

/// An SVG document as an inline HTML element (HTML needs no namespace).
pub(crate) fn inline_svg(svg: &str) -> String {
    svg.replacen(SVG_NS, "", 1)
}

pub(crate) const NATIVE_COLOR: &str = "#1f77b4";
pub(crate) const OSD_COLOR: &str = "#d62728";
pub(crate) const FVAR_COLOR: &str = "#2ca02c";
pub(crate) const LIMIT_COLOR: &str = "#ff7f0e";

/// A plot with levels along x and a log scale along y.
pub(crate) struct LogPlot {
    width: f64,
    left: f64,
    right: f64,
    top: f64,
    bottom: f64,
    lo: i32,
    hi: i32,
    levels: Vec<u32>,
}

impl LogPlot {
    fn x(&self, level: u32) -> f64 {
        let n = self.levels.len();
        let i = self.levels.iter().position(|&l| l == level).unwrap_or(0);
        if n <= 1 {
            (self.left + self.width - self.right) / 2.0
        } else {
            let pad = 24.0;
            self.left
                + pad
                + (self.width - self.right - self.left - 2.0 * pad) * i as f64 / (n - 1) as f64
        }
    }

    fn y(&self, v: f64) -> f64 {
        let t = (v.log10().clamp(f64::from(self.lo), f64::from(self.hi)) - f64::from(self.lo))
            / f64::from(self.hi - self.lo);
        self.bottom - t * (self.bottom - self.top)
    }

    /// Frame, decade grid lines (labelled by `label`) and level ticks.
    fn axes(&self, out: &mut String, every: i32, label: impl Fn(i32) -> String) {
        let (l, r) = (self.left, self.width - self.right);
        for d in self.lo..=self.hi {
            let y = self.y(10f64.powi(d));
            let _ = write!(
                out,
                r##"<line x1="{l}" y1="{y:.1}" x2="{r}" y2="{y:.1}" stroke="#e4e4e4"/>"##
            );
            if (d - self.lo) % every == 0 || d == self.hi {
                let _ = write!(
                    out,
                    r##"<text x="{:.1}" y="{:.1}" text-anchor="end" font-size="10" fill="#333">{}</text>"##,
                    l - 5.0,
                    y + 3.5,
                    label(d)
                );
            }
        }
        let _ = write!(
            out,
            r##"<rect x="{l}" y="{}" width="{}" height="{}" fill="none" stroke="#888"/>"##,
            self.top,
            r - l,
            self.bottom - self.top
        );
    }

    fn level_labels(&self, out: &mut String, y: f64) {
        for &lv in &self.levels {
            let _ = write!(
                out,
                r##"<text x="{:.1}" y="{y:.1}" text-anchor="middle" font-size="11">{lv}</text>"##,
                self.x(lv)
            );
        }
        let _ = write!(
            out,
            r##"<text x="{:.1}" y="{:.1}" text-anchor="middle" font-size="11" fill="#555">level</text>"##,
            (self.left + self.width - self.right) / 2.0,
            y + 15.0
        );
    }
}

pub(crate) fn svg_open(out: &mut String, width: f64, height: f64, title: &str) {
    let _ = write!(
        out,
        r##"<svg{SVG_NS} width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="sans-serif" role="img"><title>{}</title><rect width="{width:.0}" height="{height:.0}" fill="white"/><text x="{:.1}" y="18" text-anchor="middle" font-size="13" font-weight="bold">{}</text>"##,
        escape(title),
        width / 2.0,
        escape(title)
    );
}

pub(crate) fn marker(out: &mut String, shape: &str, x: f64, y: f64, color: &str) {
    match shape {
        "square" => {
            let _ = write!(
                out,
                r##"<rect x="{:.1}" y="{:.1}" width="7" height="7" fill="{color}"/>"##,
                x - 3.5,
                y - 3.5
            );
        }
        "diamond" => {
            let _ = write!(
                out,
                r##"<polygon points="{:.1},{:.1} {:.1},{:.1} {:.1},{:.1} {:.1},{:.1}" fill="{color}"/>"##,
                x,
                y - 5.0,
                x + 5.0,
                y,
                x,
                y + 5.0,
                x - 5.0,
                y
            );
        }
        _ => {
            let _ = write!(
                out,
                r##"<circle cx="{x:.1}" cy="{y:.1}" r="3.8" fill="{color}"/>"##
            );
        }
    }
}

pub(crate) fn legend(out: &mut String, y: f64, x0: f64, items: &[(&str, &str, &str, bool)]) {
    let mut x = x0;
    for &(label, color, shape, dashed) in items {
        let dash = if dashed {
            r#" stroke-dasharray="5,3""#
        } else {
            ""
        };
        let _ = write!(
            out,
            r##"<line x1="{x:.1}" y1="{y:.1}" x2="{:.1}" y2="{y:.1}" stroke="{color}" stroke-width="2"{dash}/>"##,
            x + 22.0
        );
        marker(out, shape, x + 11.0, y, color);
        let _ = write!(
            out,
            r##"<text x="{:.1}" y="{:.1}" font-size="11">{}</text>"##,
            x + 27.0,
            y + 4.0,
            escape(label)
        );
        x += 36.0 + 6.2 * label.chars().count() as f64;
    }
}

/// A plotted series: label, colour, marker shape, (level, value) points.
pub(crate) type PlotSeries = (&'static str, &'static str, &'static str, Vec<(u32, f64)>);

/// The deviation plot of one input: the worst deviation over its option sets
/// per level (positions, face-varying values) and of the limit, on a log
/// scale, exact zeros on their own row.
pub(crate) fn deviation_svg(r: &InputReport, s: &Settings) -> String {
    let levels: Vec<u32> = (s.first_level..=s.last_level).collect();
    let mut series: Vec<PlotSeries> = Vec::new();
    let ok_sets: Vec<&SetResult> = r.sets.iter().filter(|x| x.error.is_none()).collect();
    let per_level = |f: &dyn Fn(&LevelResult) -> Option<f64>| -> Vec<(u32, f64)> {
        levels
            .iter()
            .filter_map(|&l| {
                let vals: Vec<f64> = ok_sets
                    .iter()
                    .filter_map(|x| x.levels.iter().find(|c| c.level == l))
                    .filter_map(f)
                    .collect();
                (!vals.is_empty()).then(|| (l, vals.into_iter().fold(0.0, f64::max)))
            })
            .collect()
    };
    series.push((
        "positions",
        NATIVE_COLOR,
        "circle",
        per_level(&|c| Some(c.position_deviation)),
    ));
    let fv = per_level(&|c| c.fvar_deviation);
    if !fv.is_empty() {
        series.push(("face-varying", FVAR_COLOR, "square", fv));
    }
    let limits: Vec<f64> = ok_sets
        .iter()
        .filter_map(|x| x.limit.as_ref())
        .map(LimitResult::deviation)
        .collect();
    if !limits.is_empty() {
        series.push((
            "limit",
            LIMIT_COLOR,
            "diamond",
            vec![(s.last_level, limits.into_iter().fold(0.0, f64::max))],
        ));
    }
    let nonzero: Vec<f64> = series
        .iter()
        .flat_map(|x| x.3.iter().map(|p| p.1))
        .filter(|&v| v > 0.0 && v.is_finite())
        .collect();
    let max_dec = nonzero
        .iter()
        .map(|v| v.log10().ceil() as i32)
        .max()
        .unwrap_or(-6);
    let min_dec = nonzero
        .iter()
        .map(|v| v.log10().floor() as i32)
        .min()
        .unwrap_or(-16);
    let hi = (max_dec.max((s.tolerance.max(1e-300)).log10().ceil() as i32) + 1).min(3);
    let lo = min_dec.clamp(-40, -17);
    let (width, height) = (400.0, 280.0);
    let plot = LogPlot {
        width,
        left: 104.0,
        right: 14.0,
        top: 30.0,
        bottom: 178.0,
        lo,
        hi,
        levels: levels.clone(),
    };
    let zero_y = 200.0;
    let mut out = String::new();
    svg_open(
        &mut out,
        width,
        height,
        "deviation from OpenSubdiv (log scale)",
    );
    plot.axes(&mut out, 3, |d| format!("1e{d}"));
    // The zero row, below a break.
    let (l, rr) = (plot.left, width - plot.right);
    let _ = write!(
        out,
        r##"<rect x="{l}" y="{:.1}" width="{:.1}" height="20" fill="#eef6ee" stroke="#888"/><text x="{:.1}" y="{:.1}" text-anchor="end" font-size="10" fill="#333">0 (bit-identical)</text>"##,
        zero_y - 10.0,
        rr - l,
        l - 5.0,
        zero_y + 3.5
    );
    if s.tolerance > 0.0 {
        let ty = plot.y(s.tolerance);
        let _ = write!(
            out,
            r##"<line x1="{l}" y1="{ty:.1}" x2="{rr}" y2="{ty:.1}" stroke="{OSD_COLOR}" stroke-dasharray="6,4"/><text x="{:.1}" y="{:.1}" text-anchor="end" font-size="10" fill="{OSD_COLOR}">tolerance {:.0e}</text>"##,
            rr - 4.0,
            ty - 4.0,
            s.tolerance
        );
    }
    let k = series.len() as f64;
    for (i, (_, color, shape, pts)) in series.iter().enumerate() {
        let dx = (i as f64 - (k - 1.0) / 2.0) * 7.0;
        let pos = |&(lv, v): &(u32, f64)| {
            let y = if v == 0.0 { zero_y } else { plot.y(v) };
            (plot.x(lv) + dx, y)
        };
        if pts.len() > 1 {
            let line: Vec<String> = pts
                .iter()
                .map(pos)
                .map(|(x, y)| format!("{x:.1},{y:.1}"))
                .collect();
            let _ = write!(
                out,
                r##"<polyline points="{}" fill="none" stroke="{color}" stroke-width="1.5"/>"##,
                line.join(" ")
            );
        }
        for p in pts {
            let (x, y) = pos(p);
            marker(&mut out, shape, x, y, color);
        }
    }
    plot.level_labels(&mut out, 226.0);
    legend(
        &mut out,
        height - 18.0,
        plot.left - 60.0,
        &series
            .iter()
            .map(|(n, c, sh, _)| (*n, *c, *sh, false))
            .collect::<Vec<_>>(),
    );
    out.push_str("</svg>\n");
    out
}

/// The time plot of one input: native against OpenSubdiv per level, log scale.
pub(crate) fn time_svg(r: &InputReport) -> String {
    let (width, height) = (400.0, 280.0);
    let levels: Vec<u32> = r.timings.iter().map(|t| t.level).collect();
    let ms: Vec<f64> = r
        .timings
        .iter()
        .flat_map(|t| [t.native * 1e3, t.osd * 1e3])
        .filter(|v| *v > 0.0)
        .collect();
    let lo = ms
        .iter()
        .map(|v| v.log10().floor() as i32)
        .min()
        .unwrap_or(-2);
    let hi = ms
        .iter()
        .map(|v| v.log10().ceil() as i32)
        .max()
        .unwrap_or(0)
        .max(lo + 1);
    let plot = LogPlot {
        width,
        left: 70.0,
        right: 14.0,
        top: 30.0,
        bottom: 190.0,
        lo,
        hi,
        levels,
    };
    let mut out = String::new();
    svg_open(&mut out, width, height, "refine + positions: median time");
    plot.axes(&mut out, 1, |d| {
        let v = 10f64.powi(d);
        if d < 0 {
            format!("{v:.*} ms", (-d) as usize)
        } else {
            format!("{v:.0} ms")
        }
    });
    for (who, color, shape, dashed) in [
        ("native", NATIVE_COLOR, "circle", false),
        ("osd", OSD_COLOR, "square", true),
    ] {
        let pts: Vec<(f64, f64)> = r
            .timings
            .iter()
            .map(|t| {
                let v = if who == "native" { t.native } else { t.osd };
                (plot.x(t.level), plot.y(v * 1e3))
            })
            .collect();
        let dash = if dashed {
            r#" stroke-dasharray="6,4""#
        } else {
            ""
        };
        let line: Vec<String> = pts.iter().map(|(x, y)| format!("{x:.1},{y:.1}")).collect();
        let _ = write!(
            out,
            r##"<polyline points="{}" fill="none" stroke="{color}" stroke-width="2"{dash}/>"##,
            line.join(" ")
        );
        for (x, y) in pts {
            marker(&mut out, shape, x, y, color);
        }
    }
    plot.level_labels(&mut out, 206.0);
    // Speed-ups under the levels.
    let _ = write!(
        out,
        r##"<text x="{:.1}" y="240" text-anchor="end" font-size="10" fill="#555">speed-up</text>"##,
        plot.left - 5.0
    );
    for t in &r.timings {
        let _ = write!(
            out,
            r##"<text x="{:.1}" y="240" text-anchor="middle" font-size="10" fill="#555">{:.2}×</text>"##,
            plot.x(t.level),
            t.speedup()
        );
    }
    legend(
        &mut out,
        height - 16.0,
        plot.left - 40.0,
        &[
            ("native (1 thread)", NATIVE_COLOR, "circle", false),
            ("OpenSubdiv", OSD_COLOR, "square", true),
        ],
    );
    out.push_str("</svg>\n");
    out
}

/// The colour of a relative deviation: blue for exactly 0, yellow-green to
/// orange for 1e-16..tolerance (log scale), red above the tolerance.
pub(crate) fn deviation_color(d: f64, tolerance: f64) -> DVec3 {
    const EXACT: DVec3 = DVec3::new(0.56, 0.72, 0.95);
    const LOW: DVec3 = DVec3::new(0.55, 0.82, 0.36);
    const MID: DVec3 = DVec3::new(0.99, 0.85, 0.30);
    const HIGH: DVec3 = DVec3::new(0.96, 0.45, 0.18);
    const BAD: DVec3 = DVec3::new(0.80, 0.08, 0.12);
    if d == 0.0 {
        return EXACT;
    }
    if d > tolerance || !d.is_finite() {
        return BAD;
    }
    let t = scale_position(d, tolerance);
    if t < 0.5 {
        LOW.lerp(MID, t * 2.0)
    } else {
        MID.lerp(HIGH, t * 2.0 - 1.0)
    }
}

/// Where `d` sits on the colour bar: 0 at 1e-16, 1 at the tolerance.
pub(crate) fn scale_position(d: f64, tolerance: f64) -> f64 {
    let top = tolerance.max(1e-15).log10();
    ((d.log10() + 16.0) / (top + 16.0)).clamp(0.0, 1.0)
}

pub(crate) fn hex(c: DVec3) -> String {
    let c = (c.clamp(DVec3::ZERO, DVec3::ONE) * 255.0).round();
    format!("#{:02x}{:02x}{:02x}", c.x as u8, c.y as u8, c.z as u8)
}
