//! The report's inputs: OBJ files or the embedded set, and the option sets each is compared with.

use std::collections::HashMap;
use std::path::Path;
use subdiv::mesh::{FVarChannel, Mesh};
use subdiv::options::{
    BoundaryInterpolation, CreasingMethod, FVarLinearInterpolation, Options, Scheme,
    TriangleSubdivision,
};
use subdiv::{Result, shapes};

/// One input of the report: a mesh and the options it is refined with by default.
#[derive(Debug, Clone)]
pub struct Input {
    /// Short name (a file name for OBJ inputs).
    pub name: String,
    /// One line saying what the input exercises.
    pub description: String,
    /// The mesh.
    pub mesh: Mesh,
    /// The default options: the ones benchmarked and pictured; the
    /// comparisons vary them (see [`option_sets`]).
    pub options: Options,
}

impl Input {
    /// An input from its parts.
    pub fn new(
        name: impl Into<String>,
        description: impl Into<String>,
        mesh: Mesh,
        options: Options,
    ) -> Input {
        Input {
            name: name.into(),
            description: description.into(),
            mesh,
            options,
        }
    }
}

/// A warning met reading an input: its line (0 for the mesh as a whole), what
/// identifies repeats of it, and its text.
pub type Warning = (usize, String, String);

/// Reads the inputs of one file: an OBJ shape file ([`read_input`]) or, with
/// the `usd` feature, every subdivision mesh of a USD stage selected by
/// `prims` (all when empty), each named `FILE:PRIM` with the prim's options
/// (USD's fallbacks where unauthored). Prims the stage skips
/// (`subdivisionScheme = "none"`) come back as warnings.
pub fn read_inputs(path: &Path, prims: &[String]) -> Result<Vec<(Input, Vec<Warning>)>> {
    if !crate::args::is_usd(path) {
        return Ok(vec![read_input(path)?]);
    }
    read_usd_inputs(path, prims)
}

#[cfg(feature = "usd")]
fn read_usd_inputs(path: &Path, prims: &[String]) -> Result<Vec<(Input, Vec<Warning>)>> {
    let read = subdiv::io::usd::UsdReadOptions {
        prims: prims.to_vec(),
        ..Default::default()
    };
    let stage = subdiv::io::usd::read_usd(path, &read)?;
    let file = path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let mut shared: Vec<Warning> = stage
        .warnings
        .iter()
        .map(|w| (0, w.message.clone(), w.to_string()))
        .collect();
    shared.extend(stage.skipped.iter().map(|s| {
        let text = format!("{} skipped: {}", s.prim, s.reason);
        (0, text.clone(), text)
    }));
    let mut out = Vec::with_capacity(stage.meshes.len());
    for (k, m) in stage.meshes.into_iter().enumerate() {
        let description = format!("{} prim {}: {}", path.display(), m.path, describe(&m.mesh));
        let warnings = if k == 0 {
            std::mem::take(&mut shared)
        } else {
            Vec::new()
        };
        out.push((
            Input::new(format!("{file}:{}", m.path), description, m.mesh, m.options),
            warnings,
        ));
    }
    Ok(out)
}

#[cfg(not(feature = "usd"))]
fn read_usd_inputs(path: &Path, _prims: &[String]) -> Result<Vec<(Input, Vec<Warning>)>> {
    Err(subdiv::Error::Io {
        path: path.to_path_buf(),
        source: std::io::Error::new(
            std::io::ErrorKind::Unsupported,
            "this build reads no USD (rebuild with the default feature `usd`)",
        ),
    })
}

/// Reads an OBJ shape file as an input: its options are the file's tags over
/// OpenSubdiv's shape-file defaults. Returns the input and the warnings of
/// the reader and of the mesh validation. A malformed file is an
/// [`Error::Obj`] naming the file and line; an invalid mesh an [`Error::Mesh`].
pub fn read_input(path: &Path) -> Result<(Input, Vec<Warning>)> {
    let shape = subdiv::io::read_obj(path)?;
    let mut warnings: Vec<Warning> = shape
        .warnings
        .iter()
        .map(|w| (w.line, w.message.clone(), w.to_string()))
        .collect();
    let validation = shape.mesh.validate()?;
    warnings.extend(validation.warnings.iter().map(|w| {
        let text = w.to_string();
        (0, text.clone(), text)
    }));
    let name = path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let description = format!("{}: {}", path.display(), describe(&shape.mesh));
    let options = shape.options();
    Ok((Input::new(name, description, shape.mesh, options), warnings))
}

/// What a file's mesh holds: `N vertices, M faces, creases/corners, holes, UVs`.
fn describe(m: &Mesh) -> String {
    format!(
        "{} vertices, {} faces{}{}{}{}",
        m.vertex_count(),
        m.face_count(),
        if m.creases.is_empty() && m.corners.is_empty() {
            ""
        } else {
            ", creases/corners"
        },
        if m.holes.is_empty() { "" } else { ", holes" },
        if m.fvar_channels.is_empty() {
            ""
        } else {
            ", UVs"
        },
        if m.left_handed { ", left-handed" } else { "" },
    )
}

/// A 4×4 grid of unit quads with a gentle wave in z (for nicer pictures).
pub(crate) fn wavy_grid() -> Mesh {
    let mut m = shapes::grid(4, 4);
    for p in &mut m.positions {
        p.z = 0.35 * (1.1 * p.x).sin() * (0.8 * p.y).cos();
    }
    m
}

/// A box whose top edges are semi-sharp creases of different sharpness (so
/// uniform and Chaikin creasing differ), a semi-sharp vertical edge and a
/// semi-sharp corner.
pub(crate) fn creased_box() -> Mesh {
    let mut m = shapes::cube();
    for p in &mut m.positions {
        p.x *= 1.6;
    }
    m.add_crease(4, 5, 0.5);
    m.add_crease(5, 6, 1.5);
    m.add_crease(6, 7, 2.5);
    m.add_crease(7, 4, 3.3);
    m.add_crease(1, 5, 2.0);
    m.add_corner(0, 2.5);
    m
}

/// The wavy grid with three faces tagged as holes.
pub(crate) fn grid_with_holes() -> Mesh {
    let mut m = wavy_grid();
    m.fvar_channels.clear();
    m.holes.extend([5, 6, 15]);
    m
}

/// The wavy grid whose UVs form four regions (its quadrants), each mapped to
/// its own part of the texture: the channel splits along the seams between them.
pub(crate) fn grid_uv_regions() -> Mesh {
    let mut m = wavy_grid();
    m.fvar_channels.clear();
    let n = 4u32;
    let mut values = Vec::new();
    let mut indices = Vec::new();
    let mut index_of: HashMap<(u32, u32), u32> = HashMap::new();
    for f in 0..m.face_count() {
        let (i, j) = (f as u32 % n, f as u32 / n);
        let region = u32::from(i >= n / 2) + 2 * u32::from(j >= n / 2);
        for &v in m.face(f) {
            let next = index_of.len() as u32;
            let k = *index_of.entry((v, region)).or_insert_with(|| {
                let (x, y) = (v % (n + 1), v / (n + 1));
                values.extend_from_slice(&[
                    0.45 * f64::from(x) / f64::from(n) + 0.5 * f64::from(region % 2),
                    0.45 * f64::from(y) / f64::from(n) + 0.5 * f64::from(region / 2),
                ]);
                next
            });
            indices.push(k);
        }
    }
    m.fvar_channels.push(FVarChannel {
        width: 2,
        values,
        indices,
    });
    m
}

/// The inputs shipped in the binary, generated in code: closed and open
/// meshes, semi-sharp creases and a corner, an extraordinary pole, holes, UV
/// seams, several components, a Loop mesh, a bilinear mesh and a
/// non-manifold fin.
pub fn embedded_inputs() -> Vec<Input> {
    let d = Options::shape_file_defaults();
    vec![
        Input::new(
            "cube",
            "the unit cube: 6 quads, 8 valence-3 vertices, closed",
            shapes::cube(),
            d,
        ),
        Input::new(
            "torus",
            "a closed 8×4 quad torus: every vertex regular",
            shapes::torus(8, 4),
            d,
        ),
        Input::new(
            "creased-box",
            "a box with semi-sharp creases (sharpness 0.5 to 3.3) and a semi-sharp corner (2.5)",
            creased_box(),
            d,
        ),
        Input::new(
            "pole",
            "a valence-7 pole: 7 triangles around one vertex, a ring of quads, a heptagon",
            shapes::pole(7),
            d,
        ),
        Input::new(
            "holes",
            "an open wavy 4×4 grid with three faces tagged as holes",
            grid_with_holes(),
            d,
        ),
        Input::new(
            "cube-uv",
            "the cube with one UV square per face: UV seams along every edge",
            shapes::cube_with_uvs(),
            d,
        ),
        Input::new(
            "grid-uv-regions",
            "an open wavy 4×4 grid whose UVs form 4 regions, with seams between them",
            grid_uv_regions(),
            d,
        ),
        Input::new(
            "four-boxes",
            "four disjoint boxes of different sizes in one mesh",
            shapes::four_boxes(),
            d,
        ),
        Input::new(
            "icosahedron",
            "a regular icosahedron (20 triangles, valence 5), refined with Loop",
            shapes::icosahedron(),
            d.with_scheme(Scheme::Loop),
        ),
        Input::new(
            "bilinear-prism",
            "a twisted hexagonal prism (hexagons and quads), refined bilinearly",
            shapes::prism(6),
            d.with_scheme(Scheme::Bilinear),
        ),
        Input::new(
            "fin",
            "a non-manifold fin: three quads on one edge, and a quad on each side",
            shapes::fin(),
            d,
        ),
    ]
}

/// What a mesh has that makes options matter.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Traits {
    /// Some edge has one face (or more than two).
    pub(crate) boundary: bool,
    /// Creases or corners.
    pub(crate) creases: bool,
    /// Some face is a triangle.
    pub(crate) triangles: bool,
    /// Every face is a triangle.
    pub(crate) all_triangles: bool,
    /// A face-varying channel.
    pub(crate) uvs: bool,
}

pub(crate) fn edge_face_counts<'a>(
    faces: impl Iterator<Item = &'a [u32]>,
) -> HashMap<(u32, u32), u32> {
    let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
    for f in faces {
        for (i, &a) in f.iter().enumerate() {
            let b = f[(i + 1) % f.len()];
            if a != b {
                *edges.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
    }
    edges
}

pub(crate) fn traits(mesh: &Mesh) -> Traits {
    let sizes = mesh.face_sizes();
    Traits {
        boundary: edge_face_counts(mesh.faces()).values().any(|&n| n != 2),
        creases: !mesh.creases.is_empty() || !mesh.corners.is_empty(),
        triangles: sizes.contains(&3),
        all_triangles: !sizes.is_empty() && sizes.iter().all(|&n| n == 3),
        uvs: !mesh.fvar_channels.is_empty(),
    }
}

/// The option sets an input is compared with. Schemes: the input's own
/// first, then Catmull-Clark and bilinear, and Loop when every face is a
/// triangle. An option is varied only where it can change the result: the
/// three boundary modes on meshes with a boundary, both creasing methods with
/// creases or corners (not under bilinear), both triangle rules under
/// Catmull-Clark with triangles, the six face-varying modes with UVs. The full
/// report takes every combination; `quick` varies one option at a time.
pub fn option_sets(input: &Input, quick: bool) -> Vec<Options> {
    let t = traits(&input.mesh);
    let base = input.options;
    let mut schemes = vec![base.scheme];
    for s in [Scheme::Catmark, Scheme::Bilinear, Scheme::Loop] {
        if !schemes.contains(&s) && (s != Scheme::Loop || t.all_triangles) {
            schemes.push(s);
        }
    }
    schemes.retain(|&s| s != Scheme::Loop || t.all_triangles);
    let mut out: Vec<Options> = Vec::new();
    let mut push = |o: Options| {
        if !out.contains(&o) {
            out.push(o);
        }
    };
    for scheme in schemes {
        let b = base.with_scheme(scheme);
        let boundaries: Vec<BoundaryInterpolation> = if t.boundary {
            BoundaryInterpolation::ALL.to_vec()
        } else {
            vec![b.boundary]
        };
        let creasings: Vec<CreasingMethod> = if t.creases && scheme != Scheme::Bilinear {
            CreasingMethod::ALL.to_vec()
        } else {
            vec![b.creasing]
        };
        let triangles: Vec<TriangleSubdivision> = if t.triangles && scheme == Scheme::Catmark {
            TriangleSubdivision::ALL.to_vec()
        } else {
            vec![b.triangles]
        };
        let fvars: Vec<FVarLinearInterpolation> = if t.uvs {
            FVarLinearInterpolation::ALL.to_vec()
        } else {
            vec![b.fvar]
        };
        push(b);
        if quick {
            boundaries.iter().for_each(|&x| push(b.with_boundary(x)));
            creasings.iter().for_each(|&x| push(b.with_creasing(x)));
            triangles.iter().for_each(|&x| push(b.with_triangles(x)));
            fvars.iter().for_each(|&x| push(b.with_fvar(x)));
        } else {
            for &bd in &boundaries {
                for &c in &creasings {
                    for &tr in &triangles {
                        for &f in &fvars {
                            push(
                                b.with_boundary(bd)
                                    .with_creasing(c)
                                    .with_triangles(tr)
                                    .with_fvar(f),
                            );
                        }
                    }
                }
            }
        }
    }
    out
}
