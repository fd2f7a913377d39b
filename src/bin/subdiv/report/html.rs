//! The report as a self-contained HTML page.

use super::format::{format_deviation, format_ms, format_worst, options_label, slug};
use super::markdown::sentence;
use super::plot::{deviation_svg, inline_svg, time_svg};
use super::results::{InputReport, LimitSurface, Report};
use super::settings::{MAX_PICTURE_FACES, Settings};
use super::tessellated::Tessellated;
use std::fmt::Write as _;
use subdiv::io::svg::escape;

impl Report {
    /// The report as one self-contained HTML page: inline CSS, inline SVG,
    /// no scripts and no external resources.
    pub fn html(&self) -> String {
        let last = self.settings.last_level;
        let ok = self.conforms();
        let mut h = String::new();
        h.push_str("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>subdiv: native engine against OpenSubdiv</title>\n<style>\n");
        h.push_str(CSS);
        h.push_str("</style>\n</head>\n<body>\n<header>\n<h1>subdiv: native engine against OpenSubdiv</h1>\n<dl class=\"meta\">\n");
        for (k, v) in self.meta_lines() {
            let _ = writeln!(h, "<dt>{k}</dt><dd>{}</dd>", escape(&v));
        }
        h.push_str("</dl>\n");
        let _ = writeln!(
            h,
            "<p class=\"verdict {}\">{}</p>\n</header>",
            if ok { "pass" } else { "fail" },
            escape(&self.verdict())
        );
        h.push_str("<h2>Summary</h2>\n<table class=\"summary\">\n<thead><tr><th>input</th><th>faces</th><th>option sets</th><th>agree / cases</th><th>worst deviation</th>");
        let _ = write!(
            h,
            "<th>native L{last} ms</th><th>OpenSubdiv L{last} ms</th><th>speed-up</th></tr></thead>\n<tbody>\n"
        );
        for i in &self.inputs {
            let t = i.last_timing();
            let w = i.worst_deviation();
            let _ = writeln!(
                h,
                "<tr><td><a href=\"#{}\">{}</a></td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n {}\">{}/{}</td><td class=\"{}\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td></tr>",
                anchor(&i.name),
                escape(&i.name),
                i.faces,
                i.sets.len(),
                if i.conforms() { "pass" } else { "fail" },
                i.agreeing(),
                i.cases(),
                deviation_class(w, self.settings.tolerance),
                escape(&format_worst(w)),
                t.map_or("-".into(), |t| format_ms(t.native)),
                t.map_or("-".into(), |t| format_ms(t.osd)),
                t.map_or("-".into(), |t| format!("{:.2}×", t.speedup())),
            );
        }
        let total_t: (f64, f64) = self
            .inputs
            .iter()
            .filter_map(InputReport::last_timing)
            .fold((0.0, 0.0), |(a, b), t| (a + t.native, b + t.osd));
        let _ = writeln!(
            h,
            "</tbody>\n<tfoot><tr><td>all</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n {}\">{}/{}</td><td class=\"{}\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td></tr></tfoot>\n</table>",
            self.inputs.iter().map(|i| i.faces).sum::<usize>(),
            self.inputs.iter().map(|i| i.sets.len()).sum::<usize>(),
            if ok { "pass" } else { "fail" },
            self.agreeing(),
            self.cases(),
            deviation_class(
                self.inputs
                    .iter()
                    .map(InputReport::worst_deviation)
                    .fold(0.0, f64::max),
                self.settings.tolerance
            ),
            escape(&format_worst(
                self.inputs
                    .iter()
                    .map(InputReport::worst_deviation)
                    .fold(0.0, f64::max)
            )),
            format_ms(total_t.0),
            format_ms(total_t.1),
            if total_t.0 > 0.0 {
                format!("{:.2}×", total_t.1 / total_t.0)
            } else {
                "-".into()
            }
        );
        h.push_str("<p class=\"note\">A <em>case</em> is one level of one option set, or the limit at the last level. Deviations are the largest distance between corresponding vertices (or face-varying values, or limit positions and tangents) of the two engines, relative to the bounding-box diagonal; <b>0 means bit-identical</b>. Times are medians of interleaved runs of “refine + positions” (topology refinement and f64 positions of every level) with each input’s default options, the native engine on one thread; speed-up is OpenSubdiv’s time over the native time.</p>\n");
        for (idx, i) in self.inputs.iter().enumerate() {
            let _ = writeln!(
                h,
                "<section id=\"{}\">\n<h2>{} <span class=\"badge {}\">{}/{} agree</span></h2>",
                anchor(&i.name),
                escape(&i.name),
                if i.conforms() { "pass" } else { "fail" },
                i.agreeing(),
                i.cases()
            );
            let _ = writeln!(
                h,
                "<p>{}. {} vertices, {} faces. Default options: <code>{}</code>. Varied: {}.</p>",
                escape(&sentence(&i.description)),
                i.vertices,
                i.faces,
                escape(&options_label(&i.options)),
                escape(&i.varied_label("nothing (no option can change this mesh's result)"))
            );
            h.push_str("<div class=\"figs\">\n");
            let _ = writeln!(
                h,
                "<figure>{}<figcaption>Worst deviation over the option sets, per level.</figcaption></figure>",
                inline_svg(&deviation_svg(i, &self.settings))
            );
            let _ = writeln!(
                h,
                "<figure>{}<figcaption>Refine + positions, default options.</figcaption></figure>",
                inline_svg(&time_svg(i))
            );
            let cap = if i.picture.level < last {
                format!(
                    "Level {} ({} faces; level {last} has more than {MAX_PICTURE_FACES}).",
                    i.picture.level, i.picture.faces
                )
            } else {
                format!("Level {}, default options.", i.picture.level)
            };
            let _ = writeln!(
                h,
                "<figure>{}<figcaption>{}</figcaption></figure>",
                inline_svg(&i.picture.svg.replacen(
                    &format!("devscale-{}", slug(0, &i.name)),
                    &format!("devscale-{}", slug(idx, &i.name)),
                    2
                )),
                escape(&cap)
            );
            h.push_str("</div>\n");
            let _ = writeln!(h, "<p>{}</p>", escape(&i.limit_surface.sentence()));
            if let LimitSurface::Compared { picture, .. } = &i.limit_surface {
                let _ = writeln!(
                    h,
                    "<div class=\"figs\"><figure>{}<figcaption>The limit surface at the evaluated locations (native positions), coloured by their distance from OpenSubdiv's.</figcaption></figure></div>",
                    inline_svg(&picture.replacen(
                        &format!("limscale-{}", slug(0, &i.name)),
                        &format!("limscale-{}", slug(idx, &i.name)),
                        2
                    ))
                );
            }
            let _ = writeln!(h, "<p>{}</p>", escape(&i.tessellated.sentence()));
            if let Tessellated::Compared { picture, .. } = &i.tessellated {
                let _ = writeln!(
                    h,
                    "<div class=\"figs\"><figure>{}<figcaption>The limit surface tessellated the Bfr way (native surfaces), each facet coloured by the distance of its points from those of OpenSubdiv's Bfr.</figcaption></figure></div>",
                    inline_svg(&picture.replacen(
                        &format!("tesscale-{}", slug(0, &i.name)),
                        &format!("tesscale-{}", slug(idx, &i.name)),
                        2
                    ))
                );
            }
            let _ = writeln!(
                h,
                "<details{}><summary>{} option sets × {} — every case</summary>",
                if i.conforms() { "" } else { " open" },
                i.sets.len(),
                self.levels_label()
            );
            h.push_str(&sets_html(i, &self.settings));
            h.push_str("</details>\n</section>\n");
        }
        let _ = writeln!(
            h,
            "<footer>Generated by <code>subdiv report</code> {} in {:.1} s. Self-contained: no scripts, no external resources.</footer>\n</body>\n</html>",
            escape(&self.subdiv_version),
            self.seconds
        );
        h
    }
}

pub(crate) fn anchor(name: &str) -> String {
    let s = slug(0, name);
    format!("input-{}", s.trim_start_matches("01-"))
}

pub(crate) fn deviation_class(d: f64, tolerance: f64) -> &'static str {
    if d == 0.0 {
        "exact"
    } else if d <= tolerance {
        "pass"
    } else {
        "fail"
    }
}

pub(crate) fn sets_html(i: &InputReport, s: &Settings) -> String {
    let levels: Vec<u32> = (s.first_level..=s.last_level).collect();
    let mut out = String::from(
        "<table class=\"cases\"><thead><tr><th>scheme</th><th>boundary</th><th>creasing</th><th>triangles</th><th>fvar</th>",
    );
    for l in &levels {
        let _ = write!(out, "<th>L{l}</th>");
    }
    out.push_str("<th>limit</th><th>result</th></tr></thead><tbody>\n");
    for set in &i.sets {
        let o = &set.options;
        let _ = write!(
            out,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>",
            o.scheme.name(),
            o.boundary.name(),
            o.creasing.name(),
            o.triangles.name(),
            o.fvar.name()
        );
        for l in &levels {
            match set.levels.iter().find(|c| c.level == *l) {
                Some(c) => {
                    let title = format!(
                        "{} vertices, {} faces; positions {}{}; topology {}",
                        c.vertices,
                        c.faces,
                        format_deviation(c.position_deviation),
                        c.fvar_deviation.map_or(String::new(), |f| format!(
                            ", face-varying {}",
                            format_deviation(f)
                        )),
                        if c.topology_equal { "equal" } else { "DIFFERS" }
                    );
                    let class = if c.agrees {
                        deviation_class(c.deviation(), s.tolerance)
                    } else {
                        "fail"
                    };
                    let text = if c.topology_equal {
                        format_deviation(c.deviation())
                    } else {
                        "topology".into()
                    };
                    let _ = write!(
                        out,
                        "<td class=\"n {class}\" title=\"{}\">{}</td>",
                        escape(&title),
                        escape(&text)
                    );
                }
                None if set.refused.is_some() => {
                    out.push_str("<td class=\"n\">not compared<sup>‡</sup></td>")
                }
                None => out.push_str("<td class=\"n\">-</td>"),
            }
        }
        match &set.limit {
            Some(l) => {
                let title = format!(
                    "level {}: positions {}, tangents {}{}",
                    l.level,
                    format_deviation(l.position_deviation),
                    format_deviation(l.tangent_deviation),
                    l.fvar_deviation.map_or(String::new(), |f| format!(
                        ", face-varying {}",
                        format_deviation(f)
                    )),
                );
                let class = if l.agrees {
                    deviation_class(l.deviation(), s.tolerance)
                } else {
                    "fail"
                };
                let _ = write!(
                    out,
                    "<td class=\"n {class}\" title=\"{}\">{}</td>",
                    escape(&title),
                    format_deviation(l.deviation())
                );
            }
            None if set.refusal().is_some() => {
                let why = set.refusal().unwrap_or_default();
                let _ = write!(
                    out,
                    "<td class=\"n\" title=\"{}\">not compared<sup>‡</sup></td>",
                    escape(why)
                );
            }
            None => out.push_str("<td class=\"n\">-</td>"),
        }
        match &set.error {
            Some(e) => {
                let _ = write!(out, "<td class=\"fail\">ERROR: {}</td>", escape(e));
            }
            None if set.refused.is_some() => out.push_str("<td>not compared<sup>‡</sup></td>"),
            None if set.agreeing() == set.cases() => out.push_str("<td class=\"pass\">ok</td>"),
            None => out.push_str("<td class=\"fail\">DIFFERS</td>"),
        }
        out.push_str("</tr>\n");
    }
    out.push_str("</tbody></table>\n");
    if i.refusals() > 0 {
        let _ = writeln!(
            out,
            "<p class=\"note\">‡ Not compared: {} Hover for the vertex.</p>",
            escape(super::markdown::REFUSAL_NOTE)
        );
    }
    out
}

pub(crate) const CSS: &str = r#"
:root { color-scheme: light; }
body { font-family: system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", sans-serif; color: #1b1f24; background: #f6f7f9; margin: 0; padding: 20px 24px 40px; line-height: 1.45; }
header, section, body > table, body > h2, body > p, footer { max-width: 1240px; margin-left: auto; margin-right: auto; }
h1 { font-size: 26px; margin: 0 0 10px; }
h2 { font-size: 20px; margin: 28px auto 10px; }
section h2 { margin-top: 0; }
section { background: white; border: 1px solid #d8dde3; border-radius: 8px; padding: 16px 18px; margin-top: 22px; }
dl.meta { display: grid; grid-template-columns: max-content 1fr; gap: 2px 14px; margin: 0 0 12px; font-size: 14px; }
dl.meta dt { font-weight: 600; color: #555; }
dl.meta dd { margin: 0; }
.verdict { font-size: 16px; font-weight: 600; padding: 10px 14px; border-radius: 6px; margin: 8px 0; }
.verdict.pass { background: #e3f4e6; border: 1px solid #5aa469; color: #1d5b2a; }
.verdict.fail { background: #fbe4e4; border: 1px solid #c94a4a; color: #7a1212; }
table { border-collapse: collapse; background: white; font-size: 14px; }
table.summary { width: 100%; border: 1px solid #d8dde3; }
th, td { padding: 5px 10px; border-bottom: 1px solid #e6e9ed; text-align: left; }
th { background: #eef1f5; font-weight: 600; }
tfoot td { font-weight: 600; background: #f6f8fa; }
td.n, th.n { text-align: right; font-variant-numeric: tabular-nums; }
td.exact { color: #1f5fa8; }
td.pass { color: #1d6b2f; }
td.fail { color: #b01515; font-weight: 600; }
a { color: #1f5fa8; text-decoration: none; }
.badge { font-size: 13px; font-weight: 600; padding: 2px 8px; border-radius: 10px; vertical-align: middle; margin-left: 8px; }
.badge.pass { background: #e3f4e6; color: #1d5b2a; }
.badge.fail { background: #fbe4e4; color: #7a1212; }
.figs { display: grid; grid-template-columns: repeat(auto-fit, minmax(330px, 1fr)); gap: 12px; margin: 12px 0; align-items: start; }
figure { margin: 0; border: 1px solid #e1e4e8; border-radius: 6px; background: white; padding: 4px; }
figure svg { display: block; width: 100%; height: auto; }
figcaption { font-size: 12px; color: #555; padding: 2px 6px 4px; }
details { margin-top: 8px; }
summary { cursor: pointer; font-weight: 600; font-size: 14px; color: #333; }
table.cases { margin-top: 8px; font-size: 12.5px; }
table.cases td, table.cases th { padding: 3px 8px; }
code { font-size: 13px; background: #f0f2f5; padding: 1px 4px; border-radius: 3px; }
.note { font-size: 13px; color: #444; }
footer { margin-top: 24px; font-size: 12px; color: #666; }
"#;
