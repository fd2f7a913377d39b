//! [`write_usda`]: refined meshes as a `.usda` layer, with their prim paths,
//! `subdivisionScheme = "none"`, their holes and their primvars, every
//! number written so that it reads back exactly.

use super::{UsdInterpolation, is_identifier, is_primvar_name};
use crate::error::Error;
use crate::io::number::format_g;
use crate::output::Refinement;
use crate::real::Precision;
use glam::DVec3;
use std::borrow::Cow;
use std::io::{self, BufWriter, Write};
use std::path::Path;

/// One refined mesh for [`write_usda`]: a `Mesh` prim at `path`, its data
/// borrowed.
#[derive(Debug, Clone)]
pub struct UsdMeshOut<'a> {
    /// The prim's path (`/World/Body`): absolute, each name an identifier.
    /// Missing ancestors are written as `Xform` prims.
    pub path: &'a str,
    /// Vertex positions: `points`.
    pub positions: &'a [DVec3],
    /// Start of each face in `face_vertices`, plus one final entry:
    /// `faceVertexCounts`.
    pub face_offsets: &'a [u32],
    /// Vertex indices of all faces, concatenated: `faceVertexIndices`.
    pub face_vertices: &'a [u32],
    /// Faces that are holes: `holeIndices` (written when not empty).
    pub holes: Vec<u32>,
    /// Faces listed clockwise: `orientation = "leftHanded"` (refined meshes
    /// come out counter-clockwise, `false`).
    pub left_handed: bool,
    /// Face-varying primvars, indexed.
    pub fvar: Vec<UsdFVarOut<'a>>,
    /// Vertex and varying primvars.
    pub primvars: Vec<UsdPrimvarOut<'a>>,
}

/// A face-varying primvar of a [`UsdMeshOut`]: `primvars:NAME` with
/// `interpolation = "faceVarying"` and `primvars:NAME:indices`.
#[derive(Debug, Clone)]
pub struct UsdFVarOut<'a> {
    /// The primvar's name, without `primvars:` (`st`).
    pub name: Cow<'a, str>,
    /// Values per element (2 for UVs).
    pub width: usize,
    /// The values, `width` per element.
    pub values: &'a [f64],
    /// The element of every face corner, parallel to
    /// [`UsdMeshOut::face_vertices`].
    pub face_values: &'a [u32],
}

/// A vertex or varying primvar of a [`UsdMeshOut`].
#[derive(Debug, Clone)]
pub struct UsdPrimvarOut<'a> {
    /// The primvar's name, without `primvars:` (`displayColor`).
    pub name: Cow<'a, str>,
    /// [`UsdInterpolation::Vertex`] or [`UsdInterpolation::Varying`].
    pub interpolation: UsdInterpolation,
    /// Values per point.
    pub width: usize,
    /// `width` values per point.
    pub values: &'a [f64],
}

impl<'a> UsdMeshOut<'a> {
    /// The last level of `refinement` as the mesh at `path`: its positions,
    /// faces, holes and face-varying channels, channel `c` named
    /// `fvar_names[c]` — or, where that name is missing, `st` for channel 0
    /// and `fvarC` for the others.
    pub fn from_refinement(
        path: &'a str,
        refinement: &'a Refinement,
        fvar_names: &'a [String],
    ) -> UsdMeshOut<'a> {
        let level = refinement.last_level();
        let holes = level
            .face_holes
            .iter()
            .enumerate()
            .filter(|(_, hole)| **hole)
            .map(|(f, _)| f as u32)
            .collect();
        let fvar = level
            .fvar
            .iter()
            .enumerate()
            .map(|(c, topology)| UsdFVarOut {
                name: match fvar_names.get(c) {
                    Some(name) => Cow::Borrowed(name.as_str()),
                    None if c == 0 => Cow::Borrowed("st"),
                    None => Cow::Owned(format!("fvar{c}")),
                },
                width: refinement.fvar_widths.get(c).copied().unwrap_or(0),
                values: refinement.last_fvar(c).unwrap_or(&[]),
                face_values: &topology.face_values,
            })
            .collect();
        UsdMeshOut {
            path,
            positions: refinement.last_positions(),
            face_offsets: &level.face_offsets,
            face_vertices: &level.face_vertices,
            holes,
            left_handed: false,
            fvar,
            primvars: Vec::new(),
        }
    }
}

/// Writes `meshes` as a `.usda` layer to `path`, atomically (as
/// [`write_obj`](crate::io::write_obj) does): see [`write_usda_to`].
///
/// Any failure is an [`Error::Io`] naming `path`; malformed meshes are
/// refused (kind [`io::ErrorKind::InvalidInput`]) before anything is written.
pub fn write_usda(
    path: &Path,
    meshes: &[UsdMeshOut<'_>],
    precision: Precision,
) -> Result<(), Error> {
    crate::io::atomic::write_with(path, |file| write_usda_to(file, meshes, precision))
}

/// Writes `meshes` as `.usda` text: one `def Mesh` per mesh at its path
/// (ancestors as `def Xform`, the first root prim as `defaultPrim`), with
/// `faceVertexCounts`, `faceVertexIndices`, `holeIndices`, `orientation`
/// when left-handed, `points`, the primvars and
/// `uniform token subdivisionScheme = "none"`.
///
/// `points` and face-varying channel 0 of width 2 have the types
/// `UsdGeomMesh` and USD's renderers expect whatever the precision,
/// `point3f[]` and `texCoord2f[]` (a `point3d[] points` is a type mismatch
/// for USD: its validator reports it, and extents and bounds are not
/// computed from it): their values are rounded to `f32` and written as
/// `%.9g`, exact for every `f32`. Other primvars are `double` types written
/// as `%.17g` with [`Precision::F64`] (`double3[]`…), exact for every
/// `f64`, and `float` types as `%.9g` with [`Precision::F32`]. Values of
/// widths 1 to 4 are scalars or tuples, wider ones flat with `elementSize`.
/// Infinite and NaN primvar values are written `inf`, `-inf` and `nan`.
///
/// Malformed input — a path that is not an absolute path of identifiers or
/// that is given twice, offsets or indices out of range, values that do not
/// fill their width, a count beyond USD's 32-bit `int`, a name that is not a
/// primvar name or is used twice, a point that is not finite, a finite value
/// beyond `f32`'s range written in `f32` — is an
/// [`io::ErrorKind::InvalidInput`] error naming the prim, before anything
/// is written.
pub fn write_usda_to<W: Write>(
    out: W,
    meshes: &[UsdMeshOut<'_>],
    precision: Precision,
) -> io::Result<()> {
    for mesh in meshes {
        check(mesh, precision).map_err(|e| invalid(format!("{}: {e}", mesh.path)))?;
    }
    let tree = Tree::new(meshes)?;
    let mut w = Writer {
        out: BufWriter::new(out),
        buf: String::new(),
        precision,
    };
    w.text("#usda 1.0\n(\n")?;
    if let Some(first) = tree.roots.first() {
        w.text(&format!(
            "    defaultPrim = \"{}\"\n",
            tree.nodes[*first].name
        ))?;
    }
    w.text("    doc = \"Refined meshes written by subdiv\"\n)\n")?;
    for &root in &tree.roots {
        w.text("\n")?;
        w.node(&tree, root, meshes, 0)?;
    }
    w.flush_buf()?;
    w.out.flush()
}

/// Whether face-varying channel `c` of `width` is written as texture
/// coordinates (`texCoord2f[]`): channel 0 when two wide.
fn is_tex_coord(c: usize, width: usize) -> bool {
    c == 0 && width == 2
}

fn invalid(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, message)
}

/// Checks everything [`write_usda_to`] refuses in one mesh.
fn check(mesh: &UsdMeshOut<'_>, precision: Precision) -> Result<(), String> {
    const INT_MAX: usize = i32::MAX as usize;
    let corners = mesh.face_vertices.len();
    let faces = mesh.face_offsets.len().saturating_sub(1);
    if mesh.face_offsets.first().is_some_and(|&o| o != 0)
        || mesh
            .face_offsets
            .last()
            .map_or(corners != 0, |&o| o as usize != corners)
        || mesh.face_offsets.windows(2).any(|w| w[1] < w[0])
    {
        return Err(format!(
            "the face offsets must start at 0, not decrease and end at the {corners} face vertices"
        ));
    }
    if corners > INT_MAX || mesh.positions.len() > INT_MAX {
        return Err(format!(
            "{corners} face corners and {} points: beyond USD's 32-bit int",
            mesh.positions.len()
        ));
    }
    if let Some((i, &v)) = mesh
        .face_vertices
        .iter()
        .enumerate()
        .find(|(_, v)| **v as usize >= mesh.positions.len())
    {
        return Err(format!(
            "face vertex {i} is {v}, but there are {} points",
            mesh.positions.len()
        ));
    }
    if let Some(&h) = mesh.holes.iter().find(|h| **h as usize >= faces) {
        return Err(format!("hole {h} is not one of the {faces} faces"));
    }
    // Points must be finite (a mesh with others is refused when read);
    // primvar values may be infinite or NaN (`inf`, `-inf`, `nan`), but a
    // finite value must stay finite in the precision written.
    let representable = |what: &str,
                         values: &mut dyn Iterator<Item = f64>,
                         all_finite: bool,
                         precision: Precision| {
        let ok = |x: f64| match (x.is_finite(), precision) {
            (false, _) => !all_finite,
            (true, Precision::F64) => true,
            (true, Precision::F32) => (x as f32).is_finite(),
        };
        match values.enumerate().find(|(_, x)| !ok(*x)) {
            Some((i, x)) if x.is_finite() => Err(format!(
                "{what}: value {i} is {x:e}, beyond the range of the {precision} it is written in"
            )),
            Some((i, x)) => Err(format!("{what}: value {i} is {x}, not a finite number")),
            None => Ok(()),
        }
    };
    representable(
        "points",
        &mut mesh.positions.iter().flat_map(|p| p.to_array()),
        true,
        Precision::F32,
    )?;
    let mut names: Vec<&str> = Vec::new();
    let name = |names: &[&str], name: &str| -> Result<(), String> {
        if !is_primvar_name(name) {
            return Err(format!("{name:?} is not a primvar name"));
        }
        if names.contains(&name) {
            return Err(format!("two primvars are named {name:?}"));
        }
        Ok(())
    };
    for (c, channel) in mesh.fvar.iter().enumerate() {
        name(&names, &channel.name)?;
        names.push(&channel.name);
        let what = format!("primvars:{}", channel.name);
        if channel.width == 0 || channel.values.len() % channel.width != 0 {
            return Err(format!(
                "{what}: {} values do not make whole elements of width {}",
                channel.values.len(),
                channel.width
            ));
        }
        if channel.face_values.len() != corners {
            return Err(format!(
                "{what}: {} indices for {corners} face corners",
                channel.face_values.len()
            ));
        }
        let count = channel.values.len() / channel.width;
        if let Some((i, &v)) = channel
            .face_values
            .iter()
            .enumerate()
            .find(|(_, v)| **v as usize >= count)
        {
            return Err(format!(
                "{what}: index {i} is {v}, but there are {count} values"
            ));
        }
        if count > INT_MAX {
            return Err(format!("{what}: {count} values, beyond USD's 32-bit int"));
        }
        let precision = if is_tex_coord(c, channel.width) {
            Precision::F32
        } else {
            precision
        };
        representable(&what, &mut channel.values.iter().copied(), false, precision)?;
    }
    for primvar in &mesh.primvars {
        name(&names, &primvar.name)?;
        names.push(&primvar.name);
        let what = format!("primvars:{}", primvar.name);
        if !matches!(
            primvar.interpolation,
            UsdInterpolation::Vertex | UsdInterpolation::Varying
        ) {
            return Err(format!(
                "{what}: interpolation {} (only vertex and varying primvars are written)",
                primvar.interpolation
            ));
        }
        let expected = mesh.positions.len().checked_mul(primvar.width);
        if primvar.width == 0 || expected != Some(primvar.values.len()) {
            return Err(format!(
                "{what}: {} values for {} points of width {}",
                primvar.values.len(),
                mesh.positions.len(),
                primvar.width
            ));
        }
        representable(&what, &mut primvar.values.iter().copied(), false, precision)?;
    }
    Ok(())
}

/// The prims to write: every mesh's path and its ancestors, in order of
/// first appearance.
struct Tree {
    nodes: Vec<Node>,
    roots: Vec<usize>,
}

struct Node {
    name: String,
    children: Vec<usize>,
    mesh: Option<usize>,
}

impl Tree {
    fn new(meshes: &[UsdMeshOut<'_>]) -> io::Result<Tree> {
        let mut tree = Tree {
            nodes: Vec::new(),
            roots: Vec::new(),
        };
        for (m, mesh) in meshes.iter().enumerate() {
            let names: Vec<&str> = match mesh.path.strip_prefix('/') {
                Some(rest) => rest.split('/').collect(),
                None => Vec::new(),
            };
            if names.is_empty() || !names.iter().all(|n| is_identifier(n)) {
                return Err(invalid(format!(
                    "{:?} is not an absolute prim path of identifiers",
                    mesh.path
                )));
            }
            let mut parent: Option<usize> = None;
            for name in names {
                let siblings = match parent {
                    Some(p) => &tree.nodes[p].children,
                    None => &tree.roots,
                };
                let found = siblings
                    .iter()
                    .copied()
                    .find(|&n| tree.nodes[n].name == name);
                let node = match found {
                    Some(n) => n,
                    None => {
                        tree.nodes.push(Node {
                            name: name.to_string(),
                            children: Vec::new(),
                            mesh: None,
                        });
                        let n = tree.nodes.len() - 1;
                        match parent {
                            Some(p) => tree.nodes[p].children.push(n),
                            None => tree.roots.push(n),
                        }
                        n
                    }
                };
                parent = Some(node);
            }
            if let Some(node) = parent
                && tree.nodes[node].mesh.replace(m).is_some()
            {
                return Err(invalid(format!("{}: the path is given twice", mesh.path)));
            }
        }
        Ok(tree)
    }
}

/// Text out, through a buffer flushed every 64 KiB.
struct Writer<W: Write> {
    out: BufWriter<W>,
    buf: String,
    precision: Precision,
}

impl<W: Write> Writer<W> {
    fn flush_buf(&mut self) -> io::Result<()> {
        self.out.write_all(self.buf.as_bytes())?;
        self.buf.clear();
        Ok(())
    }

    fn maybe_flush(&mut self) -> io::Result<()> {
        if self.buf.len() >= 1 << 16 {
            self.flush_buf()?;
        }
        Ok(())
    }

    fn text(&mut self, s: &str) -> io::Result<()> {
        self.buf.push_str(s);
        self.maybe_flush()
    }

    fn number(&mut self, x: f64) {
        if x.is_nan() {
            // USD's spelling; `-nan` (C's, for a NaN with its sign set) is
            // not one the parser takes.
            self.buf.push_str("nan");
            return;
        }
        match self.precision {
            Precision::F64 => format_g(x, 17, &mut self.buf),
            Precision::F32 => format_g(f64::from(x as f32), 9, &mut self.buf),
        }
    }

    /// `[a, b, …]` of integers.
    fn ints(&mut self, values: impl Iterator<Item = u64>) -> io::Result<()> {
        self.buf.push('[');
        let mut itoa = itoa::Buffer::new();
        for (i, v) in values.enumerate() {
            if i > 0 {
                self.buf.push_str(", ");
            }
            self.buf.push_str(itoa.format(v));
            self.maybe_flush()?;
        }
        self.buf.push(']');
        Ok(())
    }

    /// `[x, …]` or `[(x, y), …]` of elements of `width` values (tuples for
    /// widths 2 to 4, flat otherwise).
    fn reals(&mut self, values: &[f64], width: usize) -> io::Result<()> {
        let tuple = (2..=4).contains(&width);
        self.buf.push('[');
        for (i, element) in values.chunks(width.max(1)).enumerate() {
            if i > 0 {
                self.buf.push_str(", ");
            }
            if tuple {
                self.buf.push('(');
            }
            for (j, &x) in element.iter().enumerate() {
                if j > 0 {
                    self.buf.push_str(", ");
                }
                self.number(x);
            }
            if tuple {
                self.buf.push(')');
            }
            self.maybe_flush()?;
        }
        self.buf.push(']');
        Ok(())
    }

    /// The array type of values of `width` (`double3[]`, `float2[]`).
    fn array_type(&self, width: usize) -> String {
        let scalar = match self.precision {
            Precision::F64 => "double",
            Precision::F32 => "float",
        };
        match width {
            2..=4 => format!("{scalar}{width}[]"),
            _ => format!("{scalar}[]"),
        }
    }

    /// [`Writer::reals`] in `precision` rather than the writer's.
    fn reals_in(&mut self, values: &[f64], width: usize, precision: Precision) -> io::Result<()> {
        let own = std::mem::replace(&mut self.precision, precision);
        let written = self.reals(values, width);
        self.precision = own;
        written
    }

    fn node(
        &mut self,
        tree: &Tree,
        n: usize,
        meshes: &[UsdMeshOut<'_>],
        depth: usize,
    ) -> io::Result<()> {
        let node = &tree.nodes[n];
        let pad = "    ".repeat(depth);
        let kind = if node.mesh.is_some() { "Mesh" } else { "Xform" };
        self.text(&format!("{pad}def {kind} \"{}\"\n{pad}{{\n", node.name))?;
        if let Some(m) = node.mesh {
            self.mesh(&meshes[m], &format!("{pad}    "))?;
        }
        for (i, &child) in node.children.iter().enumerate() {
            if i > 0 || node.mesh.is_some() {
                self.text("\n")?;
            }
            self.node(tree, child, meshes, depth + 1)?;
        }
        self.text(&format!("{pad}}}\n"))
    }

    fn mesh(&mut self, mesh: &UsdMeshOut<'_>, pad: &str) -> io::Result<()> {
        self.text(&format!("{pad}int[] faceVertexCounts = "))?;
        self.ints(mesh.face_offsets.windows(2).map(|w| u64::from(w[1] - w[0])))?;
        self.text(&format!("\n{pad}int[] faceVertexIndices = "))?;
        self.ints(mesh.face_vertices.iter().map(|&v| u64::from(v)))?;
        self.text("\n")?;
        if !mesh.holes.is_empty() {
            self.text(&format!("{pad}int[] holeIndices = "))?;
            self.ints(mesh.holes.iter().map(|&h| u64::from(h)))?;
            self.text("\n")?;
        }
        if mesh.left_handed {
            self.text(&format!(
                "{pad}uniform token orientation = \"leftHanded\"\n"
            ))?;
        }
        self.text(&format!("{pad}point3f[] points = "))?;
        let flat: &[f64] = bytemuck::cast_slice(mesh.positions);
        self.reals_in(flat, 3, Precision::F32)?;
        self.text("\n")?;
        for (c, channel) in mesh.fvar.iter().enumerate() {
            if is_tex_coord(c, channel.width) {
                self.primvar_head(pad, "texCoord2f[]", &channel.name)?;
                self.reals_in(channel.values, channel.width, Precision::F32)?;
            } else {
                let ty = self.array_type(channel.width);
                self.primvar_head(pad, &ty, &channel.name)?;
                self.reals(channel.values, channel.width)?;
            }
            self.primvar_tail(pad, UsdInterpolation::FaceVarying, channel.width)?;
            self.text(&format!("{pad}int[] primvars:{}:indices = ", channel.name))?;
            self.ints(channel.face_values.iter().map(|&v| u64::from(v)))?;
            self.text("\n")?;
        }
        for primvar in &mesh.primvars {
            let ty = self.array_type(primvar.width);
            self.primvar_head(pad, &ty, &primvar.name)?;
            self.reals(primvar.values, primvar.width)?;
            self.primvar_tail(pad, primvar.interpolation, primvar.width)?;
        }
        self.text(&format!(
            "{pad}uniform token subdivisionScheme = \"none\"\n"
        ))
    }

    fn primvar_head(&mut self, pad: &str, ty: &str, name: &str) -> io::Result<()> {
        self.text(&format!("{pad}{ty} primvars:{name} = "))
    }

    fn primvar_tail(
        &mut self,
        pad: &str,
        interpolation: UsdInterpolation,
        width: usize,
    ) -> io::Result<()> {
        self.text(&format!(
            " (\n{pad}    interpolation = \"{interpolation}\"\n"
        ))?;
        if !(1..=4).contains(&width) {
            self.text(&format!("{pad}    elementSize = {width}\n"))?;
        }
        self.text(&format!("{pad})\n"))
    }
}
