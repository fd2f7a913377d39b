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
    // Faces to draw: not holes.
    let counts = edge_face_counts(topo.faces());
    let closed = counts.values().all(|&n| n == 2) && !topo.face_holes.iter().any(|&h| h);
    let faces: Vec<&[u32]> = topo
        .faces()
        .enumerate()
        .filter(|&(f, _)| !topo.face_holes.get(f).copied().unwrap_or(false))
        .map(|(_, verts)| verts)
        .collect();
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
    let out = render(&Shaded {
        title: format!("native level {level}, coloured by deviation"),
        subtitle: format!(
            "{} faces, {} vertices; {}",
            topo.face_count(),
            topo.vertex_count,
            input.name
        ),
        faces: &faces,
        closed,
        positions: pos,
        deviations: &dev,
        max_deviation: max_dev,
        note,
        gradient: format!("devscale-{}", slug(0, &input.name)),
        tolerance,
    });
    Picture {
        level: level as u32,
        faces: topo.face_count(),
        max_deviation: max_dev,
        svg: out,
    }
}

/// A surface to draw shaded, each face coloured by the largest deviation of
/// its vertices.
pub(super) struct Shaded<'a> {
    pub(super) title: String,
    pub(super) subtitle: String,
    pub(super) faces: &'a [&'a [u32]],
    /// A closed manifold surface: only the faces toward the viewer are drawn.
    pub(super) closed: bool,
    pub(super) positions: &'a [DVec3],
    /// Per vertex, relative to the diagonal (infinite: no counterpart).
    pub(super) deviations: &'a [f64],
    pub(super) max_deviation: f64,
    pub(super) note: String,
    /// The colour bar's gradient id (unique in a page).
    pub(super) gradient: String,
    pub(super) tolerance: f64,
}

/// The picture of `s`: an orbit view, faces sorted back to front, lit, a
/// colour bar from bit-identical to the tolerance.
pub(super) fn render(s: &Shaded) -> String {
    let projection = Projection::orbit(-58.0, 28.0);
    let (width, max_h, top) = (400.0, 290.0, 42.0);
    // On a closed manifold surface, only the faces facing the viewer.
    let (pos, dev, tolerance) = (s.positions, s.deviations, s.tolerance);
    let mut faces: Vec<(f64, usize, DVec3)> = Vec::new();
    let mut lo = DVec2::splat(f64::INFINITY);
    let mut hi = DVec2::splat(f64::NEG_INFINITY);
    for (f, &verts) in s.faces.iter().enumerate() {
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
        if s.closed && n.dot(projection.toward_viewer) < -1e-9 {
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
    let mut out = String::new();
    svg_open(&mut out, width, height, &s.title);
    let _ = write!(
        out,
        r##"<text x="{:.1}" y="34" text-anchor="middle" font-size="10" fill="#555">{}</text>"##,
        width / 2.0,
        escape(&s.subtitle)
    );
    let to_light =
        (projection.up * 0.6 - projection.right * 0.4 + projection.toward_viewer * 0.7).normalize();
    let stroke_w = if faces.len() > 3000 { 0.25 } else { 0.45 };
    let _ = write!(
        out,
        r##"<g stroke-width="{stroke_w}" stroke-linejoin="round">"##
    );
    for (_, f, n) in &faces {
        let verts = s.faces[*f];
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
    let gid = &s.gradient;
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
    let max_dev = s.max_deviation;
    let _ = write!(
        out,
        r##"<text x="{:.1}" y="{:.1}" font-size="11" text-anchor="middle">{}</text>"##,
        width / 2.0,
        y + 44.0,
        escape(&s.note)
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
    out
}

/// The limit surface both engines evaluate (`subdiv compare --patches`'
/// locations: u, v in {0, 1/4, 1/2, 3/4, 1} on every ptex face off the
/// holes), drawn as the quads between neighbouring locations of each ptex
/// face at the native positions, each coloured by the largest distance of
/// its corners from OpenSubdiv's (relative to the diagonal).
pub(crate) fn limit_picture(
    name: &str,
    samples: &[((u32, f64, f64), DVec3, f64)],
    tolerance: f64,
) -> String {
    use crate::compare_patches::STEPS;
    let step = |x: f64| STEPS.iter().position(|&s| s == x);
    let mut at = std::collections::HashMap::new();
    for (k, &((f, u, v), _, _)) in samples.iter().enumerate() {
        if let (Some(i), Some(j)) = (step(u), step(v)) {
            at.insert((f, i, j), k as u32);
        }
    }
    let mut quads: Vec<[u32; 4]> = Vec::new();
    for &((f, u, v), _, _) in samples {
        let (Some(i), Some(j)) = (step(u), step(v)) else {
            continue;
        };
        let corner = |di: usize, dj: usize| at.get(&(f, i + di, j + dj)).copied();
        if let (Some(a), Some(b), Some(c), Some(d)) =
            (corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1))
        {
            quads.push([a, b, c, d]);
        }
    }
    let faces: Vec<&[u32]> = quads.iter().map(|q| &q[..]).collect();
    let positions: Vec<DVec3> = samples.iter().map(|s| s.1).collect();
    let deviations: Vec<f64> = samples
        .iter()
        .map(|s| if s.2.is_nan() { f64::INFINITY } else { s.2 })
        .collect();
    let worst = deviations
        .iter()
        .enumerate()
        .filter(|(_, d)| **d > 0.0)
        .max_by(|a, b| a.1.total_cmp(b.1));
    let max_dev = worst.map_or(0.0, |w| *w.1);
    let note = match worst {
        None => format!(
            "all {} locations: 0 (bit-identical to OpenSubdiv)",
            samples.len()
        ),
        Some((k, d)) => {
            let (f, u, v) = samples[k].0;
            format!(
                "largest deviation {} at ptex face {f} ({u}, {v})",
                format_deviation(*d)
            )
        }
    };
    render(&Shaded {
        title: "limit surface, coloured by deviation".into(),
        subtitle: format!(
            "{} quads between {} evaluated locations; {}",
            quads.len(),
            samples.len(),
            name
        ),
        faces: &faces,
        closed: false,
        positions: &positions,
        deviations: &deviations,
        max_deviation: max_dev,
        note,
        gradient: format!("limscale-{}", slug(0, name)),
        tolerance,
    })
}
