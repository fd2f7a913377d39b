//! The refined shape, each face coloured by its deviation from OpenSubdiv.

use super::format::{format_deviation, slug};
use super::inputs::{Input, edge_face_counts};
use super::plot::{deviation_color, hex, scale_position, svg_open};
use super::results::Picture;
use super::settings::MAX_PICTURE_FACES;
use glam::{DVec2, DVec3};
use std::fmt::Write as _;
use subdiv::Refinement;
use subdiv::compare::bbox_diagonal;
use subdiv::io::svg::{Projection, escape};

/// The native refined shape at the deepest level with at most
/// [`MAX_PICTURE_FACES`] faces, shaded, each face coloured by the largest
/// deviation of its vertices from OpenSubdiv.
pub(crate) fn picture(
    input: &Input,
    native: &Refinement,
    osd: &Refinement,
    tolerance: f64,
) -> Picture {
    let level = (0..native.levels.len())
        .rev()
        .find(|&l| native.levels[l].face_count() <= MAX_PICTURE_FACES)
        .unwrap_or(0);
    let topo = &native.levels[level];
    let pos = &native.positions[level];
    let empty = Vec::new();
    let reference = osd.positions.get(level).unwrap_or(&empty);
    let diag = bbox_diagonal(reference).max(f64::MIN_POSITIVE);
    let dev: Vec<f64> = (0..pos.len())
        .map(|i| match reference.get(i) {
            Some(q) => {
                let d = (pos[i] - *q).length() / diag;
                if d.is_nan() { f64::INFINITY } else { d }
            }
            None => f64::INFINITY,
        })
        .collect();
    let max_dev = if pos.len() == reference.len() {
        dev.iter().copied().fold(0.0, f64::max)
    } else {
        f64::INFINITY
    };
    let worst_vertex = dev
        .iter()
        .enumerate()
        .filter(|(_, d)| **d > 0.0)
        .max_by(|a, b| a.1.total_cmp(b.1))
        .map(|(i, _)| i);
    let projection = Projection::orbit(-58.0, 28.0);
    let (width, max_h, top) = (400.0, 290.0, 42.0);
    // Faces to draw: not holes; on a closed manifold level, only those facing the viewer.
    let counts = edge_face_counts(topo.faces());
    let closed = counts.values().all(|&n| n == 2) && !topo.face_holes.iter().any(|&h| h);
    let mut faces: Vec<(f64, usize, DVec3)> = Vec::new();
    let mut lo = DVec2::splat(f64::INFINITY);
    let mut hi = DVec2::splat(f64::NEG_INFINITY);
    for (f, verts) in topo.faces().enumerate() {
        if topo.face_holes.get(f).copied().unwrap_or(false) {
            continue;
        }
        let p = |v: u32| pos.get(v as usize).copied().unwrap_or_default();
        let mut n = DVec3::ZERO;
        for (i, &a) in verts.iter().enumerate() {
            let (a, b) = (p(a), p(verts[(i + 1) % verts.len()]));
            n += DVec3::new(
                (a.y - b.y) * (a.z + b.z),
                (a.z - b.z) * (a.x + b.x),
                (a.x - b.x) * (a.y + b.y),
            );
        }
        let n = n.normalize_or_zero();
        for &v in verts {
            let q = projection.project(p(v));
            if q.is_finite() {
                lo = lo.min(q);
                hi = hi.max(q);
            }
        }
        if closed && n.dot(projection.toward_viewer) < -1e-9 {
            continue;
        }
        let depth = verts.iter().map(|&v| projection.depth(p(v))).sum::<f64>() / verts.len() as f64;
        faces.push((depth, f, n));
    }
    faces.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    if lo.x > hi.x {
        (lo, hi) = (DVec2::ZERO, DVec2::ZERO);
    }
    let extent = (hi - lo).max(DVec2::splat(1e-12));
    let scale = ((width - 30.0) / extent.x).min(max_h / extent.y);
    let box_h = (extent.y * scale).max(120.0);
    let centre = (lo + hi) * 0.5;
    let px = |p: DVec3| {
        let q = (projection.project(p) - centre) * scale;
        DVec2::new(width / 2.0 + q.x, top + box_h / 2.0 - q.y)
    };
    let legend_top = top + box_h + 14.0;
    let height = legend_top + 56.0;
    let title = format!("native level {level}, coloured by deviation");
    let mut out = String::new();
    svg_open(&mut out, width, height, &title);
    let _ = write!(
        out,
        r##"<text x="{:.1}" y="34" text-anchor="middle" font-size="10" fill="#555">{} faces, {} vertices; {}</text>"##,
        width / 2.0,
        topo.face_count(),
        topo.vertex_count,
        escape(&input.name)
    );
    let to_light =
        (projection.up * 0.6 - projection.right * 0.4 + projection.toward_viewer * 0.7).normalize();
    let stroke_w = if faces.len() > 3000 { 0.25 } else { 0.45 };
    let _ = write!(
        out,
        r##"<g stroke-width="{stroke_w}" stroke-linejoin="round">"##
    );
    for (_, f, n) in &faces {
        let verts = topo.face(*f);
        let d = verts
            .iter()
            .map(|&v| dev.get(v as usize).copied().unwrap_or(f64::INFINITY))
            .fold(0.0, f64::max);
        let facing = n.dot(projection.toward_viewer) >= 0.0;
        let light = n.dot(to_light).abs().mul_add(0.55, 0.45);
        let base = deviation_color(d, tolerance) * if facing { light } else { 0.6 * light };
        let mut pts = String::new();
        for (i, &v) in verts.iter().enumerate() {
            let q = px(pos.get(v as usize).copied().unwrap_or_default());
            if i > 0 {
                pts.push(' ');
            }
            let _ = write!(pts, "{:.1},{:.1}", q.x, q.y);
        }
        let _ = write!(
            out,
            r##"<polygon points="{pts}" fill="{}" stroke="{}"/>"##,
            hex(base),
            hex(base * 0.62)
        );
    }
    out.push_str("</g>");
    // The legend: the exact colour, the colour bar, the failure colour.
    let y = legend_top;
    let gid = format!("devscale-{}", slug(0, &input.name));
    let bar_x = 150.0;
    let bar_w = 170.0;
    let _ = write!(
        out,
        r##"<defs><linearGradient id="{gid}" x1="0" x2="1" y1="0" y2="0"><stop offset="0" stop-color="{}"/><stop offset="0.5" stop-color="{}"/><stop offset="1" stop-color="{}"/></linearGradient></defs>"##,
        hex(deviation_color(1e-16, tolerance)),
        hex(deviation_color(
            10f64.powf(-8.0 + tolerance.max(1e-15).log10() / 2.0),
            tolerance
        )),
        hex(deviation_color(tolerance, tolerance)),
    );
    let _ = write!(
        out,
        r##"<rect x="12" y="{y:.1}" width="16" height="12" fill="{}" stroke="#555"/><text x="32" y="{:.1}" font-size="10">0 (bit-identical)</text>"##,
        hex(deviation_color(0.0, tolerance)),
        y + 10.0
    );
    let _ = write!(
        out,
        r##"<rect x="{bar_x}" y="{y:.1}" width="{bar_w}" height="12" fill="url(#{gid})" stroke="#555"/><text x="{bar_x}" y="{:.1}" font-size="9" text-anchor="middle">1e-16</text><text x="{:.1}" y="{:.1}" font-size="9" text-anchor="middle">{:.0e}</text>"##,
        y + 23.0,
        bar_x + bar_w,
        y + 23.0,
        tolerance
    );
    let _ = write!(
        out,
        r##"<rect x="{:.1}" y="{y:.1}" width="16" height="12" fill="{}" stroke="#555"/><text x="{:.1}" y="{:.1}" font-size="10">&gt; tol.</text>"##,
        bar_x + bar_w + 10.0,
        hex(deviation_color(f64::INFINITY, tolerance)),
        bar_x + bar_w + 30.0,
        y + 10.0
    );
    let note = if max_dev == 0.0 {
        format!(
            "all {} vertices: 0 (bit-identical to OpenSubdiv)",
            pos.len()
        )
    } else if let Some(v) = worst_vertex {
        format!(
            "largest deviation {} (relative to the diagonal) at vertex {v}",
            format_deviation(max_dev)
        )
    } else {
        format!("largest deviation {}", format_deviation(max_dev))
    };
    let _ = write!(
        out,
        r##"<text x="{:.1}" y="{:.1}" font-size="11" text-anchor="middle">{}</text>"##,
        width / 2.0,
        y + 44.0,
        escape(&note)
    );
    if max_dev == 0.0 {
        // Mark where on the bar zero would be: nowhere; say so.
        let _ = write!(
            out,
            r##"<text x="{:.1}" y="{:.1}" font-size="9" fill="#555" text-anchor="middle">(colour bar unused)</text>"##,
            bar_x + bar_w / 2.0,
            y + 23.0
        );
    } else if max_dev.is_finite() && max_dev <= tolerance {
        let mx = bar_x + bar_w * scale_position(max_dev, tolerance);
        let _ = write!(
            out,
            r##"<path d="M{mx:.1} {:.1} l-4 -6 h8 z" fill="#000"/>"##,
            y - 1.0
        );
    }
    out.push_str("</svg>\n");
    Picture {
        level: level as u32,
        faces: topo.face_count(),
        max_deviation: max_dev,
        svg: out,
    }
}
