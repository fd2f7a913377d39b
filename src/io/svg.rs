//! SVG pictures of curves and meshes, written by code (the README's gallery,
//! `subdiv curve -o OUT.svg`).
//!
//! Curves are drawn as the classic figures draw them: the control polygon in
//! grey, dashed, with its points as dots, and each refinement level (or a
//! flattened limit curve) in its own colour, with a legend. A B-spline or
//! NURBS curve ([`nurbs_curve_svg`]) is drawn with its knots: a diamond at
//! the curve point of each distinct knot of the domain, labelled with its
//! value. Meshes are drawn
//! as an orthographic projection ([`Projection`]), either as shaded faces with
//! their edges (painter's algorithm: faces sorted back to front) or as a plain
//! wireframe. Everything is deterministic: the same input gives the same file.
//!
//! ```
//! use glam::DVec2;
//! use subdiv::curve::{refine_levels, CurveScheme};
//! use subdiv::io::svg::curve_levels_svg;
//!
//! let p = [DVec2::ZERO, DVec2::new(1.0, 2.0), DVec2::new(3.0, 2.0), DVec2::new(4.0, 0.0)];
//! let levels = refine_levels(&p, CurveScheme::Chaikin, false, 3)?;
//! let svg = curve_levels_svg("Chaikin", &levels, false);
//! assert!(svg.starts_with("<svg") && svg.contains("level 3 (18 points)"));
//! # Ok::<(), subdiv::curve::CurveError>(())
//! ```

use crate::curve::Point;
use crate::error::Error;
use crate::io::number::format_g;
use crate::mesh::Mesh;
use crate::nurbs::{NurbsCurve, NurbsError};
use glam::{DVec2, DVec3};
use std::collections::HashSet;
use std::fmt::Write as _;

use std::path::Path;

/// The colours of refinement levels 1, 2, 3, … (then repeating).
pub const PALETTE: [&str; 8] = [
    "#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf",
];

/// The colour of the control polygon.
pub const CONTROL_COLOR: &str = "#7f7f7f";

/// An orthographic projection: a 3-D point maps to its coordinates along the
/// screen's `right` and `up` axes; `toward_viewer` orders faces by depth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// The screen's x axis, in world coordinates (unit length).
    pub right: DVec3,
    /// The screen's y axis, in world coordinates (unit length).
    pub up: DVec3,
    /// The direction from the scene toward the viewer (unit length).
    pub toward_viewer: DVec3,
}

impl Default for Projection {
    fn default() -> Self {
        Projection::PLAN
    }
}

impl Projection {
    /// The x-y plane seen from +z: x to the right, y up (for 2-D data).
    pub const PLAN: Projection = Projection {
        right: DVec3::X,
        up: DVec3::Y,
        toward_viewer: DVec3::Z,
    };

    /// A view from the direction at `azimuth` degrees around the z axis (0 = from
    /// +x) and `elevation` degrees above the x-y plane, with z up on the screen.
    /// The elevation is clamped to ±89.9°.
    pub fn orbit(azimuth: f64, elevation: f64) -> Projection {
        let (az, el) = (
            azimuth.to_radians(),
            elevation.clamp(-89.9, 89.9).to_radians(),
        );
        let toward_viewer = DVec3::new(el.cos() * az.cos(), el.cos() * az.sin(), el.sin());
        let right = DVec3::Z.cross(toward_viewer).normalize();
        let up = toward_viewer.cross(right);
        Projection {
            right,
            up,
            toward_viewer,
        }
    }

    /// The default view of points of type `P`: [`PLAN`](Self::PLAN) for 2-D,
    /// [`orbit(-60, 25)`](Self::orbit) for 3-D.
    pub fn for_points<P: Point>() -> Projection {
        if P::DIM == 2 {
            Projection::PLAN
        } else {
            Projection::orbit(-60.0, 25.0)
        }
    }

    /// The screen coordinates of `p` (y up).
    pub fn project(&self, p: DVec3) -> DVec2 {
        DVec2::new(p.dot(self.right), p.dot(self.up))
    }

    /// How near `p` is to the viewer (larger is nearer).
    pub fn depth(&self, p: DVec3) -> f64 {
        p.dot(self.toward_viewer)
    }
}

/// One polygon of a curve figure.
#[derive(Debug, Clone, Copy)]
pub struct Layer<'a, P: Point> {
    /// The legend text.
    pub label: &'a str,
    /// The points.
    pub points: &'a [P],
    /// Whether the last point joins the first.
    pub closed: bool,
}

/// Maps world (projected) coordinates into a pixel box, y down.
#[derive(Debug, Clone, Copy)]
struct Frame {
    scale: f64,
    origin: DVec2, // world point at the box's centre
    centre: DVec2, // the box's centre in pixels
}

impl Frame {
    fn fit(points: impl Iterator<Item = DVec2>, size: DVec2, centre: DVec2) -> Frame {
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for p in points {
            if p.is_finite() {
                lo = lo.min(p);
                hi = hi.max(p);
            }
        }
        if lo.x > hi.x || lo.x.is_nan() {
            (lo, hi) = (DVec2::ZERO, DVec2::ZERO);
        }
        let extent = (hi - lo).max(DVec2::splat(1e-12));
        let scale = (size.x / extent.x).min(size.y / extent.y);
        Frame {
            scale,
            origin: (lo + hi) * 0.5,
            centre,
        }
    }

    fn px(&self, p: DVec2) -> DVec2 {
        let d = (p - self.origin) * self.scale;
        DVec2::new(self.centre.x + d.x, self.centre.y - d.y)
    }
}

/// `text` escaped for XML and HTML text and attribute values (`&`, `<`,
/// `>` and `"`).
pub fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn points_attr(points: impl Iterator<Item = DVec2>) -> String {
    let mut s = String::new();
    for (i, p) in points.enumerate() {
        if i > 0 {
            s.push(' ');
        }
        let _ = write!(s, "{:.2},{:.2}", p.x, p.y);
    }
    s
}

fn header(out: &mut String, width: f64, height: f64, title: &str) {
    let _ = writeln!(
        out,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width:.0}\" height=\"{height:.0}\" viewBox=\"0 0 {width:.0} {height:.0}\" font-family=\"sans-serif\">"
    );
    let _ = writeln!(out, "<title>{}</title>", escape(title));
    let _ = writeln!(
        out,
        "<rect width=\"{width:.0}\" height=\"{height:.0}\" fill=\"white\"/>"
    );
    let _ = writeln!(
        out,
        "<text x=\"{:.1}\" y=\"24\" font-size=\"16\" text-anchor=\"middle\">{}</text>",
        width / 2.0,
        escape(title)
    );
}

/// The colour of layer `k` of a curve figure: grey for the control polygon
/// (`k = 0`), then [`PALETTE`].
pub fn layer_color(k: usize) -> &'static str {
    if k == 0 {
        CONTROL_COLOR
    } else {
        PALETTE[(k - 1) % PALETTE.len()]
    }
}

/// A curve figure: layer 0 is drawn as the control polygon (grey, dashed,
/// with dots), layer `k ≥ 1` in [`layer_color(k)`](layer_color), thinner for
/// later layers, with dots at its points while it has at most 200 of them.
pub fn curve_svg<P: Point>(
    title: &str,
    layers: &[Layer<'_, P>],
    projection: &Projection,
) -> String {
    curve_figure(title, layers, &[], projection)
}

/// A knot marked on a curve figure: the curve point `C(t)` at a distinct
/// knot `t` of the domain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KnotMark<P> {
    /// The knot value.
    pub t: f64,
    /// How many times it occurs in the knot vector.
    pub multiplicity: usize,
    /// The curve point `C(t)`.
    pub point: P,
}

/// The knot marks of a curve: one per distinct knot of its domain
/// `[u_d, u_{m-d}]`, at the curve point (a closed curve: the break points of
/// one period, `s_n` left out as the image of `s_0`).
pub fn knot_marks<P: Point>(curve: &NurbsCurve<P>) -> Result<Vec<KnotMark<P>>, NurbsError> {
    let mut breaks = curve.knots().breaks().to_vec();
    breaks.dedup();
    if curve.is_closed() {
        breaks.pop();
    }
    breaks
        .into_iter()
        .map(|t| {
            Ok(KnotMark {
                t,
                multiplicity: curve.knots().multiplicity(t),
                point: curve.eval(t)?,
            })
        })
        .collect()
}

/// The curve sampled densely enough to draw: 48 points per non-empty span
/// of the domain, between 201 and 8001 in all, uniform in the parameter,
/// both ends included.
pub fn dense_samples<P: Point>(curve: &NurbsCurve<P>) -> Result<Vec<P>, NurbsError> {
    let mut breaks = curve.knots().breaks().to_vec();
    breaks.dedup();
    let spans = breaks.len().saturating_sub(1);
    curve.sample(spans.saturating_mul(48).saturating_add(1).clamp(201, 8001))
}

/// A curve figure with its knots marked ([`curve_svg`] plus a marker and a
/// label per [`KnotMark`], and a legend line for them).
pub fn curve_knots_svg<P: Point>(
    title: &str,
    layers: &[Layer<'_, P>],
    marks: &[KnotMark<P>],
    projection: &Projection,
) -> String {
    curve_figure(title, layers, marks, projection)
}

/// The figure of a B-spline or NURBS curve: `polygons` (the first drawn as
/// the control polygon: pass e.g. the given control points, then the ones
/// after an insertion), the curve itself sampled densely ([`dense_samples`]),
/// and its knots marked ([`knot_marks`]).
///
/// ```
/// use glam::DVec2;
/// use subdiv::io::svg::{nurbs_curve_svg, Layer, Projection};
/// use subdiv::nurbs::NurbsCurve;
/// let p = vec![DVec2::ZERO, DVec2::new(1.0, 2.0), DVec2::new(3.0, 2.0), DVec2::new(4.0, 0.0)];
/// let c = NurbsCurve::new(p.clone(), 2, vec![0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0], None)?;
/// let polygon = [Layer { label: "control polygon", points: &p, closed: false }];
/// let svg = nurbs_curve_svg("quadratic", &c, &polygon, &Projection::PLAN)?;
/// assert!(svg.starts_with("<svg") && svg.contains("3 distinct knots"));
/// # Ok::<(), subdiv::nurbs::NurbsError>(())
/// ```
pub fn nurbs_curve_svg<P: Point>(
    title: &str,
    curve: &NurbsCurve<P>,
    polygons: &[Layer<'_, P>],
    projection: &Projection,
) -> Result<String, NurbsError> {
    let samples = dense_samples(curve)?;
    let label = curve_label(curve);
    let mut layers = polygons.to_vec();
    layers.push(Layer {
        label: &label,
        points: &samples,
        closed: false,
    });
    Ok(curve_figure(
        title,
        &layers,
        &knot_marks(curve)?,
        projection,
    ))
}

/// `curve (degree d, rational, closed)`: the legend of a curve's layer.
pub fn curve_label<P: Point>(curve: &NurbsCurve<P>) -> String {
    format!(
        "curve (degree {}{}{})",
        curve.degree(),
        if curve.is_rational() {
            ", rational"
        } else {
            ""
        },
        if curve.is_closed() { ", closed" } else { "" }
    )
}

/// [`curve_svg`] with knot marks.
fn curve_figure<P: Point>(
    title: &str,
    layers: &[Layer<'_, P>],
    marks: &[KnotMark<P>],
    projection: &Projection,
) -> String {
    const WIDTH: f64 = 640.0;
    const PLOT: f64 = 560.0;
    // Coordinates near f64::MAX would overflow the projection and the extent:
    // draw such a figure at 2^-64 of its size (exact; the picture is the same).
    let largest = layers
        .iter()
        .flat_map(|l| l.points)
        .map(|p| p.to_dvec3().abs().max_element())
        .filter(|m| m.is_finite())
        .fold(0.0, f64::max);
    let shrink = if largest > 1e300 {
        f64::from_bits((1023 - 64) << 52)
    } else {
        1.0
    };
    let projected: Vec<Vec<DVec2>> = layers
        .iter()
        .map(|l| {
            l.points
                .iter()
                .map(|p| projection.project(p.to_dvec3() * shrink))
                .collect()
        })
        .collect();
    let all = projected.iter().flatten().copied();
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for p in all.clone() {
        lo = lo.min(p);
        hi = hi.max(p);
    }
    let extent = if lo.x <= hi.x {
        (hi - lo).max(DVec2::splat(1e-12))
    } else {
        DVec2::ONE
    };
    // The plot keeps the data's aspect ratio, at most PLOT × PLOT pixels.
    let scale = (PLOT / extent.x).min(PLOT / extent.y);
    let plot_h = (extent.y * scale).max(40.0);
    let top = 44.0;
    let legend_top = top + plot_h + 24.0;
    let rows = layers.len() + usize::from(!marks.is_empty());
    let height = legend_top + 20.0 * rows as f64 + 8.0;
    let frame = Frame::fit(
        all,
        DVec2::new(PLOT, plot_h),
        DVec2::new(WIDTH / 2.0, top + plot_h / 2.0),
    );
    let mut out = String::new();
    header(&mut out, WIDTH, height, title);
    for (k, (layer, pts)) in layers.iter().zip(&projected).enumerate() {
        let color = layer_color(k);
        let px: Vec<DVec2> = pts.iter().map(|&p| frame.px(p)).collect();
        let element = if layer.closed { "polygon" } else { "polyline" };
        let (width, dash) = if k == 0 {
            (1.5, " stroke-dasharray=\"6 4\"")
        } else {
            ((2.4 - 0.3 * (k as f64 - 1.0)).max(1.0), "")
        };
        let _ = writeln!(
            out,
            "<{element} points=\"{}\" fill=\"none\" stroke=\"{color}\" stroke-width=\"{width:.1}\" stroke-linejoin=\"round\"{dash}/>",
            points_attr(px.iter().copied())
        );
        if k == 0 || px.len() <= 200 {
            let r = if k == 0 { 4.0 } else { 2.2 };
            let _ = writeln!(out, "<g fill=\"{color}\">");
            for p in &px {
                let _ = writeln!(
                    out,
                    "<circle cx=\"{:.2}\" cy=\"{:.2}\" r=\"{r}\"/>",
                    p.x, p.y
                );
            }
            let _ = writeln!(out, "</g>");
        }
        let y = legend_top + 20.0 * k as f64;
        let _ = writeln!(
            out,
            "<line x1=\"40\" y1=\"{y:.1}\" x2=\"80\" y2=\"{y:.1}\" stroke=\"{color}\" stroke-width=\"{width:.1}\"{dash}/>"
        );
        let _ = writeln!(
            out,
            "<text x=\"90\" y=\"{:.1}\" font-size=\"13\">{}</text>",
            y + 4.5,
            escape(layer.label)
        );
    }
    if !marks.is_empty() {
        let y = legend_top + 20.0 * layers.len() as f64;
        draw_knot_marks(&mut out, marks, WIDTH, |p| {
            frame.px(projection.project(p.to_dvec3() * shrink))
        });
        let _ = writeln!(out, "<g class=\"knot-legend\">");
        diamond(&mut out, DVec2::new(60.0, y));
        let count = marks.len();
        let _ = writeln!(
            out,
            "<text x=\"90\" y=\"{:.1}\" font-size=\"13\">knots: C(t) at the {count} distinct knot{} of the domain</text>\n</g>",
            y + 4.5,
            if count == 1 { "" } else { "s" }
        );
    }
    out.push_str("</svg>\n");
    out
}

/// A knot marker: a diamond, white with a black outline.
fn diamond(out: &mut String, c: DVec2) {
    const R: f64 = 5.0;
    let _ = writeln!(
        out,
        "<path d=\"M{:.2},{:.2}L{:.2},{:.2}L{:.2},{:.2}L{:.2},{:.2}Z\" fill=\"white\" stroke=\"black\" stroke-width=\"1.3\"/>",
        c.x,
        c.y - R,
        c.x + R,
        c.y,
        c.x,
        c.y + R,
        c.x - R,
        c.y
    );
}

/// The knot markers, labelled with their values (and multiplicities above
/// 1) while there are at most 24 of them.
fn draw_knot_marks<P: Point>(
    out: &mut String,
    marks: &[KnotMark<P>],
    width: f64,
    px: impl Fn(P) -> DVec2,
) {
    let _ = writeln!(out, "<g class=\"knots\">");
    for mark in marks {
        diamond(out, px(mark.point));
    }
    if marks.len() <= 24 {
        // One label per marker position: knots at the same point (the ends
        // of a closed curve) share it.
        let mut labels: Vec<(DVec2, String)> = Vec::new();
        for mark in marks {
            let c = px(mark.point);
            let mut label = String::new();
            format_g(mark.t, 6, &mut label);
            if mark.multiplicity > 1 {
                let _ = write!(label, " (\u{d7}{})", mark.multiplicity);
            }
            match labels.iter_mut().find(|(at, _)| at.distance(c) < 1.0) {
                Some((_, text)) => {
                    text.push_str(", ");
                    text.push_str(&label);
                }
                None => labels.push((c, label)),
            }
        }
        let _ = writeln!(out, "<g font-size=\"11\" fill=\"#333333\">");
        for (c, label) in labels {
            // Right of the marker, or left of it where the text (about 6.5
            // pixels a character) would leave the picture.
            let fits = c.x + 7.0 + 6.5 * label.chars().count() as f64 <= width;
            let (x, anchor) = if fits {
                (c.x + 7.0, "")
            } else {
                (c.x - 7.0, " text-anchor=\"end\"")
            };
            let _ = writeln!(
                out,
                "<text x=\"{x:.2}\" y=\"{:.2}\"{anchor}>{}</text>",
                c.y - 7.0,
                escape(&label)
            );
        }
        let _ = writeln!(out, "</g>");
    }
    let _ = writeln!(out, "</g>");
}

/// The classic figure of a refinement: `levels[0]` is the control polygon,
/// `levels[k]` level `k`, each in its own colour, labelled with its point
/// count. 3-D points are drawn with [`Projection::for_points`].
pub fn curve_levels_svg<P: Point>(title: &str, levels: &[Vec<P>], closed: bool) -> String {
    let labels: Vec<String> = levels
        .iter()
        .enumerate()
        .map(|(k, l)| {
            if k == 0 {
                format!("control polygon ({} points)", l.len())
            } else {
                format!("level {k} ({} points)", l.len())
            }
        })
        .collect();
    let layers: Vec<Layer<'_, P>> = levels
        .iter()
        .zip(&labels)
        .map(|(points, label)| Layer {
            label,
            points,
            closed,
        })
        .collect();
    curve_svg(title, &layers, &Projection::for_points::<P>())
}

/// How [`mesh_svg`] draws faces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MeshStyle {
    /// Filled faces, shaded by their angle to the viewer, with their edges,
    /// sorted back to front (faces turned away are drawn darker).
    #[default]
    Shaded,
    /// Every edge once, no fill.
    Wireframe,
}

/// One panel of a mesh figure.
#[derive(Debug, Clone, Copy)]
pub struct MeshPanel<'a> {
    /// The caption under the panel.
    pub label: &'a str,
    /// The mesh (its positions and faces; tags are not drawn).
    pub mesh: &'a Mesh,
}

/// Meshes side by side, in one orthographic projection and one scale, each
/// with its caption.
pub fn mesh_svg(
    title: &str,
    panels: &[MeshPanel<'_>],
    projection: &Projection,
    style: MeshStyle,
) -> String {
    const PANEL: f64 = 240.0;
    const INNER: f64 = 210.0;
    let width = (PANEL * panels.len().max(1) as f64).max(320.0);
    let top = 40.0;
    let height = top + PANEL + 30.0;
    let mut out = String::new();
    header(&mut out, width, height, title);
    // One scale for all panels: fit the largest extent into INNER.
    let mut extent = DVec2::splat(1e-12);
    for panel in panels {
        let f = Frame::fit(
            panel.mesh.positions.iter().map(|&p| projection.project(p)),
            DVec2::splat(INNER),
            DVec2::ZERO,
        );
        extent = extent.max(DVec2::splat(INNER / f.scale));
    }
    let scale = INNER / extent.x.max(extent.y);
    let x0 = (width - PANEL * panels.len() as f64) / 2.0;
    for (k, panel) in panels.iter().enumerate() {
        let mesh = panel.mesh;
        let fit = Frame::fit(
            mesh.positions.iter().map(|&p| projection.project(p)),
            DVec2::splat(INNER),
            DVec2::ZERO,
        );
        let frame = Frame {
            scale,
            origin: fit.origin,
            centre: DVec2::new(x0 + PANEL * (k as f64 + 0.5), top + PANEL / 2.0),
        };
        let px = |v: u32| {
            mesh.positions
                .get(v as usize)
                .map_or(frame.centre, |&p| frame.px(projection.project(p)))
        };
        match style {
            MeshStyle::Shaded => {
                let face_list: Vec<&[u32]> = mesh.faces().collect();
                let mut faces: Vec<(f64, usize)> = face_list
                    .iter()
                    .enumerate()
                    .map(|(f, verts)| {
                        let depth = verts
                            .iter()
                            .filter_map(|&v| mesh.positions.get(v as usize))
                            .map(|&p| projection.depth(p))
                            .sum::<f64>()
                            / verts.len().max(1) as f64;
                        (depth, f)
                    })
                    .collect();
                faces.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                let _ = writeln!(
                    out,
                    "<g stroke=\"#1a1a1a\" stroke-width=\"0.6\" stroke-linejoin=\"round\">"
                );
                for &(_, f) in &faces {
                    let verts = face_list[f];
                    let normal = newell_normal(mesh, verts);
                    let facing = normal.dot(projection.toward_viewer);
                    // Lit from the upper left, in front of the viewer.
                    let to_light = (projection.up * 0.6 - projection.right * 0.4
                        + projection.toward_viewer * 0.7)
                        .normalize();
                    let light = normal.dot(to_light).abs().mul_add(0.6, 0.38);
                    let (r, g, b) = if facing >= 0.0 {
                        (0.62 * light, 0.78 * light, 1.0 * light)
                    } else {
                        (0.45 * light, 0.42 * light, 0.5 * light)
                    };
                    let _ = writeln!(
                        out,
                        "<polygon points=\"{}\" fill=\"#{:02x}{:02x}{:02x}\"/>",
                        points_attr(verts.iter().map(|&v| px(v))),
                        (r * 255.0).round() as u8,
                        (g * 255.0).round() as u8,
                        (b * 255.0).round() as u8
                    );
                }
                let _ = writeln!(out, "</g>");
            }
            MeshStyle::Wireframe => {
                let mut seen = HashSet::new();
                let _ = writeln!(out, "<g stroke=\"#1f4e9c\" stroke-width=\"0.8\">");
                for verts in mesh.faces() {
                    for (i, &a) in verts.iter().enumerate() {
                        let b = verts[(i + 1) % verts.len()];
                        if seen.insert((a.min(b), a.max(b))) {
                            let (p, q) = (px(a), px(b));
                            let _ = writeln!(
                                out,
                                "<line x1=\"{:.2}\" y1=\"{:.2}\" x2=\"{:.2}\" y2=\"{:.2}\"/>",
                                p.x, p.y, q.x, q.y
                            );
                        }
                    }
                }
                let _ = writeln!(out, "</g>");
            }
        }
        let _ = writeln!(
            out,
            "<text x=\"{:.1}\" y=\"{:.1}\" font-size=\"13\" text-anchor=\"middle\">{}</text>",
            frame.centre.x,
            top + PANEL + 16.0,
            escape(panel.label)
        );
    }
    out.push_str("</svg>\n");
    out
}

/// The unit normal of a polygon by Newell's method (zero for a degenerate one).
fn newell_normal(mesh: &Mesh, verts: &[u32]) -> DVec3 {
    let mut n = DVec3::ZERO;
    let p = |v: u32| mesh.positions.get(v as usize).copied().unwrap_or_default();
    for (i, &a) in verts.iter().enumerate() {
        let (a, b) = (p(a), p(verts[(i + 1) % verts.len()]));
        n += DVec3::new(
            (a.y - b.y) * (a.z + b.z),
            (a.z - b.z) * (a.x + b.x),
            (a.x - b.x) * (a.y + b.y),
        );
    }
    n.normalize_or_zero()
}

/// Writes an SVG text to `path` atomically.
pub fn write_svg(path: &Path, svg: &str) -> Result<(), Error> {
    super::atomic::write_bytes(path, svg.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn circle(closed: bool) -> NurbsCurve<DVec2> {
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let p: Vec<DVec2> = [(1., 0.), (1., 1.), (0., 1.), (-1., 1.), (-1., 0.)]
            .iter()
            .chain(&[(-1., -1.), (0., -1.), (1., -1.), (1., 0.)])
            .map(|&(x, y)| DVec2::new(x, y))
            .collect();
        let w = [1.0, h, 1.0, h, 1.0, h, 1.0, h, 1.0];
        if closed {
            let breaks = vec![0., 1., 1., 2., 2., 3., 3., 4., 4.];
            NurbsCurve::closed(p[..8].to_vec(), 2, breaks, Some(w[..8].to_vec())).unwrap()
        } else {
            let knots = vec![0., 0., 0., 1., 1., 2., 2., 3., 3., 4., 4., 4.];
            NurbsCurve::new(p, 2, knots, Some(w.to_vec())).unwrap()
        }
    }

    #[test]
    fn knot_marks_are_the_distinct_knots_of_the_domain() {
        let open = knot_marks(&circle(false)).unwrap();
        let ts: Vec<(f64, usize)> = open.iter().map(|m| (m.t, m.multiplicity)).collect();
        assert_eq!(ts, [(0., 3), (1., 2), (2., 2), (3., 2), (4., 3)]);
        for (m, p) in open
            .iter()
            .zip([(1., 0.), (0., 1.), (-1., 0.), (0., -1.), (1., 0.)])
        {
            assert!((m.point - DVec2::new(p.0, p.1)).length() < 1e-15);
        }
        // Closed: the break point s_n = 4 is s_0 again and is left out.
        let closed = knot_marks(&circle(true)).unwrap();
        let ts: Vec<f64> = closed.iter().map(|m| m.t).collect();
        assert_eq!(ts, [0., 1., 2., 3.]);
    }

    #[test]
    fn dense_samples_take_48_points_a_span_within_bounds() {
        // Four spans: 193 points, raised to the minimum of 201.
        assert_eq!(dense_samples(&circle(false)).unwrap().len(), 201);
        let p: Vec<DVec2> = (0..20)
            .map(|i| DVec2::new(i as f64, (i % 3) as f64))
            .collect();
        let line = NurbsCurve::new(p, 1, (0..22).map(f64::from).collect(), None).unwrap();
        assert_eq!(dense_samples(&line).unwrap().len(), 19 * 48 + 1);
    }

    #[test]
    fn knots_at_one_point_share_a_label() {
        let c = circle(false);
        let square = c.points().to_vec();
        let svg = nurbs_curve_svg(
            "circle",
            &c,
            &[Layer {
                label: "control polygon",
                points: &square,
                closed: false,
            }],
            &Projection::PLAN,
        )
        .unwrap();
        // 0 and 4 are both at (1, 0), at the right edge: one label, turned left.
        assert!(svg.contains("text-anchor=\"end\">0 (\u{d7}3), 4 (\u{d7}3)</text>"));
        assert_eq!(svg.matches("<text x=").count(), 1 + 2 + 4 + 1); // title, legend, labels, knots legend
        assert!(svg.contains("curve (degree 2, rational)"));
        assert!(svg.contains("5 distinct knots"));
    }
}
