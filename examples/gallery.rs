//! Writes the README's gallery: SVG pictures of every curve scheme (open and
//! closed, levels in colours), of B-splines of several degrees, of an adaptive
//! flattening, of a NURBS circle with its knots, and of Doo-Sabin and
//! Catmull-Clark cubes.
//!
//! ```text
//! cargo run --example gallery            # into docs/gallery/
//! cargo run --example gallery -- DIR     # into DIR
//! ```

use glam::{DVec2, DVec3};
use std::path::{Path, PathBuf};
use subdiv::curve::{self, CurveScheme};
use subdiv::doo_sabin::{self, Boundary, Weights};
use subdiv::io::svg::{self, Layer, MeshPanel, MeshStyle, Projection};
use subdiv::nurbs::NurbsCurve;
use subdiv::{Mesh, Options, UniformOptions};

type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

/// The open control polygon of the curve figures.
fn open_polygon() -> Vec<DVec2> {
    [
        (0.0, 0.0),
        (1.0, 2.2),
        (2.2, 0.4),
        (3.4, 2.8),
        (5.0, 2.6),
        (5.6, 0.2),
        (7.0, 1.4),
    ]
    .iter()
    .map(|&(x, y)| DVec2::new(x, y))
    .collect()
}

/// The closed control polygon: a non-convex heptagon.
fn closed_polygon() -> Vec<DVec2> {
    [
        (0.0, 0.0),
        (3.0, -0.6),
        (5.0, 1.0),
        (3.4, 1.6),
        (4.4, 3.6),
        (1.6, 3.0),
        (-0.6, 3.4),
    ]
    .iter()
    .map(|&(x, y)| DVec2::new(x, y))
    .collect()
}

fn write(dir: &Path, name: &str, text: &str) -> Result<()> {
    let path = dir.join(name);
    svg::write_svg(&path, text)?;
    println!("wrote {}", path.display());
    Ok(())
}

/// The mesh of the last level of a native Catmull-Clark refinement.
fn catmull_clark(mesh: &Mesh, level: u32) -> Result<Vec<Mesh>> {
    let r = subdiv::refiner::refine(mesh, &Options::default(), UniformOptions::new(level))?;
    Ok(r.levels
        .iter()
        .zip(&r.positions)
        .map(|(topology, positions)| Mesh {
            positions: positions.clone(),
            face_offsets: topology.face_offsets.clone(),
            face_vertices: topology.face_vertices.clone(),
            ..Mesh::default()
        })
        .collect())
}

fn main() -> Result<()> {
    let dir: PathBuf = match std::env::args_os().nth(1) {
        Some(d) => d.into(),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/gallery"),
    };
    std::fs::create_dir_all(&dir)?;

    // Every curve scheme, open and closed, three levels.
    let schemes = [
        ("chaikin", "Chaikin", CurveScheme::Chaikin),
        ("bspline", "Cubic B-spline", CurveScheme::bspline(3)),
        (
            "four-point",
            "Four-point (w = 1/16)",
            CurveScheme::four_point(),
        ),
        ("jarek", "Jarek", CurveScheme::Jarek),
    ];
    for (file, title, scheme) in schemes {
        for (closed, polygon) in [(false, open_polygon()), (true, closed_polygon())] {
            let shape = if closed { "closed" } else { "open" };
            let levels = curve::refine_levels(&polygon, scheme, closed, 3)?;
            let text = svg::curve_levels_svg(&format!("{title}, {shape}"), &levels, closed);
            write(&dir, &format!("curve-{file}-{shape}.svg"), &text)?;
        }
    }

    // B-splines of degrees 1 to 5 on one polygon: the limit curves (5 levels).
    let polygon = closed_polygon();
    let curves: Vec<(String, Vec<DVec2>)> = (1..=5)
        .map(|d| {
            let points = curve::refine(&polygon, CurveScheme::bspline(d), true, 5)?;
            Ok((format!("degree {d}"), points))
        })
        .collect::<Result<_>>()?;
    let mut layers = vec![Layer {
        label: "control polygon",
        points: &polygon,
        closed: true,
    }];
    layers.extend(curves.iter().map(|(label, points)| Layer {
        label,
        points,
        closed: true,
    }));
    write(
        &dir,
        "curve-bspline-degrees.svg",
        &svg::curve_svg(
            "Uniform B-splines of degrees 1 to 5, closed",
            &layers,
            &Projection::PLAN,
        ),
    )?;

    // Adaptive flattening of Chaikin's limit curve.
    let polygon = open_polygon();
    let eps = 0.01;
    let line = curve::flatten(&polygon, CurveScheme::Chaikin, false, eps)?;
    let label = format!(
        "limit curve within {eps} ({} points, midpoint splitting)",
        line.points.len()
    );
    write(
        &dir,
        "curve-chaikin-flattened.svg",
        &svg::curve_svg(
            "Chaikin's limit curve, flattened adaptively",
            &[
                Layer {
                    label: "control polygon",
                    points: &polygon,
                    closed: false,
                },
                Layer {
                    label: &label,
                    points: &line.points,
                    closed: false,
                },
            ],
            &Projection::PLAN,
        ),
    )?;

    // The unit circle as a rational quadratic (NURBS), before and after
    // inserting the knots 0.5 and 2.5, with its knots marked.
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let square: Vec<DVec2> = [
        (1., 0.),
        (1., 1.),
        (0., 1.),
        (-1., 1.),
        (-1., 0.),
        (-1., -1.),
        (0., -1.),
        (1., -1.),
        (1., 0.),
    ]
    .iter()
    .map(|&(x, y)| DVec2::new(x, y))
    .collect();
    let circle = NurbsCurve::new(
        square.clone(),
        2,
        vec![0., 0., 0., 1., 1., 2., 2., 3., 3., 4., 4., 4.],
        Some(vec![1.0, h, 1.0, h, 1.0, h, 1.0, h, 1.0]),
    )?;
    let finer = circle.insert_many(&[0.5, 2.5])?;
    write(
        &dir,
        "nurbs-circle.svg",
        &svg::nurbs_curve_svg(
            "The unit circle as a rational quadratic (NURBS)",
            &finer,
            &[
                Layer {
                    label: "control polygon (9 points)",
                    points: &square,
                    closed: false,
                },
                Layer {
                    label: "after inserting 0.5 and 2.5 (11 points)",
                    points: finer.points(),
                    closed: false,
                },
            ],
            &Projection::PLAN,
        )?,
    )?;

    // Cubes: Doo-Sabin and Catmull-Clark, levels 0 to 3.
    let view = Projection::orbit(-35.0, 28.0);
    let cube = subdiv::shapes::cube();
    let ds = doo_sabin::refine(&cube, &doo_sabin::DooSabinOptions::default(), 3)?;
    let cc = catmull_clark(&cube, 3)?;
    for (file, title, meshes) in [
        ("doo-sabin-cube.svg", "Doo-Sabin cube", &ds),
        ("catmull-clark-cube.svg", "Catmull-Clark cube", &cc),
    ] {
        let labels: Vec<String> = meshes
            .iter()
            .enumerate()
            .map(|(k, m)| format!("level {k}: {} faces", m.face_count()))
            .collect();
        let panels: Vec<MeshPanel<'_>> = meshes
            .iter()
            .zip(&labels)
            .map(|(mesh, label)| MeshPanel { label, mesh })
            .collect();
        write(
            &dir,
            file,
            &svg::mesh_svg(title, &panels, &view, MeshStyle::Shaded),
        )?;
    }

    // Doo-Sabin boundaries: a cube without its top, with both rules, and the
    // original against the centroid weights on a triangulated pyramid.
    let open_cube = {
        let faces: Vec<&[u32]> = cube.faces().filter(|f| f != &[4, 5, 6, 7]).collect();
        Mesh::from_faces(cube.positions.clone(), &faces)
    };
    let rules: Vec<(String, Mesh)> = [Boundary::Open, Boundary::Chaikin]
        .into_iter()
        .map(|boundary| {
            let options = doo_sabin::DooSabinOptions {
                weights: Weights::Original,
                boundary,
            };
            let mut levels = doo_sabin::refine(&open_cube, &options, 3)?;
            Ok((format!("{boundary} boundary, level 3"), levels.remove(3)))
        })
        .collect::<Result<_>>()?;
    let mut panels = vec![MeshPanel {
        label: "open cube, level 0",
        mesh: &open_cube,
    }];
    panels.extend(rules.iter().map(|(label, mesh)| MeshPanel { label, mesh }));
    write(
        &dir,
        "doo-sabin-boundaries.svg",
        &svg::mesh_svg(
            "Doo-Sabin boundary rules",
            &panels,
            &Projection::orbit(-35.0, 40.0),
            MeshStyle::Shaded,
        ),
    )?;

    // A bicubic tube (periodic around, open along), split by the curve rule.
    let tube = subdiv::patch::ControlGrid::from_fn(8, 6, 3, true, false, |i, j| {
        let a = std::f64::consts::TAU * i as f64 / 8.0;
        let r = [1.0, 1.6, 0.7, 1.3, 0.6, 1.0][j] * if i % 2 == 0 { 1.0 } else { 0.8 };
        DVec3::new(r * a.cos(), r * a.sin(), j as f64 * 0.9)
    })?;
    let grids = [
        tube.to_mesh(),
        tube.refine_levels(1)?.to_mesh(),
        tube.refine_levels(3)?.to_mesh(),
    ];
    let labels = [
        "control grid 8 × 6",
        "split once: 16 × 9",
        "three times: 64 × 27",
    ];
    let view = Projection::orbit(-60.0, 20.0);
    let panels: Vec<MeshPanel<'_>> = grids
        .iter()
        .zip(labels)
        .map(|(mesh, label)| MeshPanel { label, mesh })
        .collect();
    write(
        &dir,
        "patch-bicubic.svg",
        &svg::mesh_svg(
            "Bicubic tube, periodic around and open along, split",
            &panels,
            &view,
            MeshStyle::Shaded,
        ),
    )?;
    Ok(())
}
