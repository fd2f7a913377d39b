//! The benchmark report as Markdown and SVG plots.

use super::results::{BenchReport, LevelSeries, ProgramKind, Row, WholeProcess};
use std::fmt::Write as _;

impl BenchReport {
    /// The report as Markdown: the comparison table, then the stencil
    /// bandwidth, OpenSubdiv alone, adaptive refinement, parallel use, whole
    /// programs and the OBJ writer.
    pub fn markdown(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "Measured {} on {} ({} native thread(s)); memory bandwidth {:.1} GB/s (a copy on as many threads).\n",
            self.date,
            self.machine,
            self.threads,
            self.bandwidth / 1e9
        );
        if !self.rows.is_empty() || !self.parallel.is_empty() {
            let _ = writeln!(
                s,
                "| input | scheme | level | task | native ms | OpenSubdiv ms | speed-up |"
            );
            let _ = writeln!(s, "| --- | --- | ---: | --- | ---: | ---: | ---: |");
        }
        for r in self.rows.iter().chain(self.parallel.iter().map(|p| &p.row)) {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {:.2} | {:.2} | {:.2}x |",
                r.input,
                r.scheme,
                r.level,
                r.task,
                r.native * 1e3,
                r.osd * 1e3,
                r.speedup()
            );
        }
        if let Some((n, o)) = self.stencil_bandwidth {
            let _ = writeln!(
                s,
                "\nStencil apply moves {:.1} GB/s natively ({:.0}% of the measured bandwidth) and {:.1} GB/s in OpenSubdiv.",
                n / 1e9,
                100.0 * n / self.bandwidth,
                o / 1e9
            );
        }
        if !self.osd_alone.is_empty() {
            let _ = writeln!(
                s,
                "\nOpenSubdiv's deepest topology + positions alone (back to back, no native run in between) and as measured above (interleaved with the native engine; both share the C allocator):"
            );
            for a in &self.osd_alone {
                let _ = writeln!(
                    s,
                    "- {} ({}, level {}): alone {:.1} ms, interleaved {:.1} ms",
                    a.input,
                    a.scheme,
                    a.level,
                    a.alone * 1e3,
                    a.interleaved * 1e3
                );
            }
        }
        if !self.adaptive.is_empty() {
            let _ = writeln!(
                s,
                "\nAdaptive refinement ({} thread(s); Refiner::new + refine_adaptive against TopologyRefinerFactory::Create + RefineAdaptive, then every level's positions interpolated level by level; levels and positions checked equal bit for bit before timing; vertices: all refined levels):\n",
                self.threads
            );
            let _ = writeln!(
                s,
                "| input | scheme | isolation | levels refined | task | vertices | native ms | OpenSubdiv ms | speed-up |"
            );
            let _ = writeln!(
                s,
                "| --- | --- | ---: | ---: | --- | ---: | ---: | ---: | ---: |"
            );
            for a in &self.adaptive {
                let r = &a.row;
                let _ = writeln!(
                    s,
                    "| {} | {} | {} | {} | {} | {} | {:.2} | {:.2} | {:.2}x |",
                    r.input,
                    r.scheme,
                    a.isolation,
                    a.max_level,
                    r.task,
                    r.vertices,
                    r.native * 1e3,
                    r.osd * 1e3,
                    r.speedup()
                );
            }
        }
        if !self.tessellation.is_empty() {
            let _ = writeln!(
                s,
                "\nTessellation of the limit surface, the Bfr way ({} thread(s); `MeshSurfaces::new` + `bfr::tessellate` against OpenSubdiv's RefinerSurfaceFactory + Surface + Tessellation in one C++ loop (bfr tutorial 2_2's, one thread); meshes checked equal before timing):\n",
                self.threads
            );
            let _ = writeln!(
                s,
                "| input | scheme | task | points | triangles | native ms | OpenSubdiv ms | speed-up | native Mtri/s | OpenSubdiv Mtri/s |"
            );
            let _ = writeln!(
                s,
                "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
            );
            for t in &self.tessellation {
                let (r, (rn, ro)) = (&t.row, t.rates());
                let _ = writeln!(
                    s,
                    "| {} | {} | {} | {} | {} | {:.2} | {:.2} | {:.2}x | {:.2} | {:.2} |",
                    r.input,
                    r.scheme,
                    r.task,
                    r.vertices,
                    t.triangles,
                    r.native * 1e3,
                    r.osd * 1e3,
                    r.speedup(),
                    rn / 1e6,
                    ro / 1e6
                );
            }
        }
        if !self.parallel.is_empty() {
            let _ = writeln!(
                s,
                "\nParallel use ({} thread(s); each engine's batch spread over the same rayon pool: one shared refiner for the frames, one refiner per mesh; results checked equal bit for bit before timing):",
                self.threads
            );
            for p in &self.parallel {
                let (r, (rn, ro)) = (&p.row, p.rates());
                let _ = writeln!(
                    s,
                    "- {} ({}, level {}): native {:.1} ms ({:.0} {unit}/s), OpenSubdiv {:.1} ms ({:.0} {unit}/s), {:.2}x",
                    r.input,
                    r.scheme,
                    r.level,
                    r.native * 1e3,
                    rn,
                    r.osd * 1e3,
                    ro,
                    r.speedup(),
                    unit = p.unit,
                );
            }
        }
        for w in &self.whole_process {
            s.push_str(&w.markdown());
        }
        if let Some(o) = &self.obj_writer {
            let _ = writeln!(
                s,
                "\nOBJ writer ({}, level {}, f64 positions, {:.0} MB): {:.0} MB/s",
                o.input,
                o.level,
                o.bytes as f64 / 1e6,
                o.mb_per_s()
            );
        }
        if !self.obj_reader.is_empty() {
            s.push('\n');
        }
        for o in &self.obj_reader {
            let (one, many) = o.mb_per_s();
            let _ = write!(
                s,
                "OBJ reader ({}, {:.1} MB file): {one:.0} MB/s on 1 thread",
                o.input,
                o.bytes as f64 / 1e6,
            );
            if o.threads > 1 {
                let _ = write!(s, ", {many:.0} MB/s on {} threads", o.threads);
            }
            s.push('\n');
        }
        for why in &self.skipped {
            let _ = writeln!(s, "\nSkipped: {why}");
        }
        s
    }

    /// An SVG line chart of "topology + positions" time per level, native
    /// against OpenSubdiv, one pair of lines per input.
    pub fn svg_time_per_level(&self) -> String {
        let series: Vec<LevelSeries> = {
            let mut out: Vec<LevelSeries> = Vec::new();
            for r in self
                .rows
                .iter()
                .filter(|r| r.task == "topology + positions")
            {
                let key = format!("{} {}", r.input, r.scheme);
                match out.iter_mut().find(|(k, _)| *k == key) {
                    Some((_, v)) => v.push((r.level, r.native, r.osd)),
                    None => out.push((key, vec![(r.level, r.native, r.osd)])),
                }
            }
            out
        };
        let max = self
            .rows
            .iter()
            .filter(|r| r.task == "topology + positions")
            .map(|r| r.native.max(r.osd))
            .fold(1e-6, f64::max);
        let (w, h, left, bottom) = (640.0, 360.0, 60.0, 40.0);
        let x = |l: u32| left + (l as f64 - 1.0) / 3.0 * (w - left - 20.0);
        let y = |t: f64| h - bottom - (t / max) * (h - bottom - 20.0);
        let colors = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e"];
        let mut s = format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="11">"#
        );
        let _ = write!(
            s,
            r#"<rect width="{w}" height="{h}" fill="white"/><line x1="{left}" y1="{}" x2="{}" y2="{}" stroke="black"/><line x1="{left}" y1="20" x2="{left}" y2="{}" stroke="black"/>"#,
            h - bottom,
            w - 20.0,
            h - bottom,
            h - bottom
        );
        for l in 1..=4 {
            let _ = write!(
                s,
                r#"<text x="{}" y="{}" text-anchor="middle">level {l}</text>"#,
                x(l),
                h - bottom + 16.0
            );
        }
        let _ = write!(s, r#"<text x="8" y="14">ms (max {:.1})</text>"#, max * 1e3);
        for (i, (name, pts)) in series.iter().enumerate() {
            let c = colors[i % colors.len()];
            for (osd, dash) in [(false, ""), (true, r#" stroke-dasharray="5,4""#)] {
                let path: Vec<String> = pts
                    .iter()
                    .map(|&(l, n, o)| format!("{:.1},{:.1}", x(l), y(if osd { o } else { n })))
                    .collect();
                let _ = write!(
                    s,
                    r#"<polyline fill="none" stroke="{c}" stroke-width="2"{dash} points="{}"/>"#,
                    path.join(" ")
                );
            }
            let _ = write!(
                s,
                r#"<text x="{}" y="{}" fill="{c}">{name} (solid: native, dashed: OpenSubdiv)</text>"#,
                left + 10.0,
                32.0 + 14.0 * i as f64
            );
        }
        s.push_str("</svg>\n");
        s
    }

    /// An SVG bar chart of refined vertices per second at the deepest level
    /// against the rate the measured memory bandwidth would allow for the
    /// bytes each refined vertex needs (its f32 position written once).
    pub fn svg_rate_vs_bandwidth(&self) -> String {
        let rows: Vec<&Row> = self
            .rows
            .iter()
            .filter(|r| r.task == "positions (f32)")
            .collect();
        let bound = self.bandwidth / 12.0;
        let max = rows
            .iter()
            .map(|r| (r.vertices as f64 / r.native).max(r.vertices as f64 / r.osd))
            .fold(bound, f64::max);
        let (w, bar) = (640.0, 18.0);
        let h = 40.0 + rows.len() as f64 * 2.0 * (bar + 4.0) + 30.0;
        let scale = |v: f64| (v / max) * (w - 260.0);
        let mut s = format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="11"><rect width="{w}" height="{h}" fill="white"/>"#
        );
        let _ = write!(
            s,
            r#"<text x="8" y="16">refined vertices per second (positions, f32); line: bandwidth bound {:.2e}/s</text>"#,
            bound
        );
        let mut yy = 30.0;
        for r in rows {
            for (who, t, c) in [("native", r.native, "#1f77b4"), ("osd", r.osd, "#d62728")] {
                let rate = r.vertices as f64 / t;
                let _ = write!(
                    s,
                    r#"<text x="8" y="{}">{} {} {who}</text><rect x="250" y="{yy}" width="{:.1}" height="{bar}" fill="{c}"/><text x="{:.1}" y="{}">{:.2e}</text>"#,
                    yy + 13.0,
                    r.input,
                    r.scheme,
                    scale(rate),
                    254.0 + scale(rate),
                    yy + 13.0,
                    rate
                );
                yy += bar + 4.0;
            }
        }
        let bx = 250.0 + scale(bound);
        let _ = write!(
            s,
            r#"<line x1="{bx:.1}" y1="24" x2="{bx:.1}" y2="{yy}" stroke="black" stroke-dasharray="3,3"/></svg>"#
        );
        s.push('\n');
        s
    }
}

impl WholeProcess {
    /// The section as Markdown: each program's median and peak memory, then
    /// the ratios.
    fn markdown(&self) -> String {
        let mut s = format!(
            "\nWhole process, {} at level {}, no output file (OpenSubdiv is single-threaded; medians of interleaved runs):\n",
            self.input, self.level
        );
        for p in &self.programs {
            let _ = write!(s, "  {}: {:.1} ms", p.name, p.seconds * 1e3);
            if p.peak_bytes > 0 {
                let _ = write!(
                    s,
                    ", peak memory {:.0} MiB",
                    p.peak_bytes as f64 / 1048576.0
                );
            }
            s.push('\n');
        }
        let native = self.program(ProgramKind::Native);
        if let (Some(n), Some(o)) = (native, self.program(ProgramKind::Osd))
            && n.peak_bytes > 0
            && o.peak_bytes > 0
        {
            let _ = writeln!(
                s,
                "  peak memory native / subdiv --engine osd: {:.2}",
                n.peak_bytes as f64 / o.peak_bytes as f64
            );
        }
        let Some(cpp) = self.program(ProgramKind::Cpp) else {
            s.push_str("  C++ program: skipped (g++ or libosd-dev not available)\n");
            return s;
        };
        if let (Some(n), Some(_)) = (native, self.program(ProgramKind::NativeAsTyped)) {
            let _ = writeln!(
                s,
                "  speed-up over the C++ program with {} thread(s): {:.2}x",
                self.threads,
                cpp.seconds / n.seconds
            );
        }
        if let Some(typed) = self.as_typed() {
            let _ = writeln!(
                s,
                "  whole-process speed-up of `subdiv refine INPUT.obj --level {}` as typed ({} threads, its default) over the C++ program: {:.2}x",
                self.level,
                self.cores,
                cpp.seconds / typed.seconds
            );
        }
        if self.native_peak() > 0 && cpp.peak_bytes > 0 {
            let _ = writeln!(
                s,
                "  peak memory native (the larger of its runs) / C++ program: {:.2}",
                self.native_peak() as f64 / cpp.peak_bytes as f64
            );
        }
        s
    }
}
