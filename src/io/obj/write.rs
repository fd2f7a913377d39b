//! The OBJ writer: `%.17g` / `%.9g` numbers, UVs, normals, faces without holes, atomic files.

use crate::error::Error;
use crate::io::number::{g_format, push_u64};
use crate::mesh::Mesh;
use crate::real::Precision;
use glam::DVec3;
use std::io::{self, BufWriter, Write};
use std::path::Path;

/// What [`write_obj_to`] writes: positions, faces and optional UVs, borrowed.
#[derive(Debug, Clone, Copy)]
pub struct ObjOutput<'a> {
    /// Vertex positions, written as `v` lines.
    pub positions: &'a [DVec3],
    /// Start of each face in `face_vertices`, plus one final entry.
    pub face_offsets: &'a [u32],
    /// 0-based vertex indices of all faces, concatenated.
    pub face_vertices: &'a [u32],
    /// One flag per face; faces flagged `true` are left out.
    pub holes: Option<&'a [bool]>,
    /// Face-varying values written as `vt` lines and `v/vt` face corners.
    pub uv: Option<UvOutput<'a>>,
    /// One normal per position, written as `vn` lines, each corner naming
    /// its vertex's (`v//vn`, or `v/vt/vn` with UVs).
    pub normals: Option<&'a [DVec3]>,
    /// `F64` writes `%.17g` (exact); `F32` rounds to `f32` and writes `%.9g`.
    pub precision: Precision,
}

/// Face-varying values for [`ObjOutput::uv`].
#[derive(Debug, Clone, Copy)]
pub struct UvOutput<'a> {
    /// Components per value; every component goes on the value's `vt` line.
    pub width: usize,
    /// The values, `width` components each, flattened.
    pub values: &'a [f64],
    /// 0-based value index of every face corner, parallel to `face_vertices`.
    pub face_values: &'a [u32],
}

fn invalid(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, message)
}

/// Checks the shape of an [`ObjOutput`], so that writing cannot panic.
fn check_output(data: &ObjOutput<'_>) -> io::Result<()> {
    let corners = data.face_vertices.len();
    if let Some(i) = data
        .face_offsets
        .windows(2)
        .position(|w| w[1] < w[0] || w[1] as usize > corners)
    {
        return Err(invalid(format!(
            "face offsets {} and {} ({} and {}) are decreasing or beyond the {corners} face vertices",
            i,
            i + 1,
            data.face_offsets[i],
            data.face_offsets[i + 1]
        )));
    }
    if let Some(&first) = data.face_offsets.first()
        && first as usize > corners
    {
        return Err(invalid(format!(
            "face offset 0 ({first}) is beyond the {corners} face vertices"
        )));
    }
    let faces = data.face_offsets.len().saturating_sub(1);
    if let Some(holes) = data.holes
        && holes.len() != faces
    {
        return Err(invalid(format!(
            "{} hole flags for {faces} faces",
            holes.len()
        )));
    }
    // Never an `inf` or `nan` in the file: the reader would refuse it.
    let finite = |x: f64| match data.precision {
        Precision::F64 => x.is_finite(),
        Precision::F32 => (x as f32).is_finite(),
    };
    let not_finite = |what: &str, index: usize, x: f64| {
        invalid(format!(
            "{what} {index} has the value {x:e}, which {} cannot write as a finite number{}",
            data.precision,
            if data.precision == Precision::F32 && x.is_finite() {
                " (beyond its range: use f64)"
            } else {
                ""
            }
        ))
    };
    if let Some((v, x)) = data.positions.iter().enumerate().find_map(|(v, p)| {
        p.to_array()
            .into_iter()
            .find(|&x| !finite(x))
            .map(|x| (v, x))
    }) {
        return Err(not_finite("vertex", v, x));
    }
    if let Some(normals) = data.normals {
        if normals.len() != data.positions.len() {
            return Err(invalid(format!(
                "{} normals for {} vertices",
                normals.len(),
                data.positions.len()
            )));
        }
        if let Some((v, x)) = normals.iter().enumerate().find_map(|(v, n)| {
            n.to_array()
                .into_iter()
                .find(|&x| !finite(x))
                .map(|x| (v, x))
        }) {
            return Err(not_finite("normal", v, x));
        }
    }
    if let Some(uv) = &data.uv {
        if let Some((i, &x)) = uv.values.iter().enumerate().find(|(_, x)| !finite(**x)) {
            return Err(not_finite("texture coordinate", i / uv.width.max(1), x));
        }
        if uv.width == 0 || uv.values.len() % uv.width != 0 {
            return Err(invalid(format!(
                "{} UV components do not make values of width {}",
                uv.values.len(),
                uv.width
            )));
        }
        if uv.face_values.len() != corners {
            return Err(invalid(format!(
                "{} UV indices for {corners} face corners",
                uv.face_values.len()
            )));
        }
    }
    Ok(())
}

/// Bytes gathered before they are handed to the writer.
const CHUNK: usize = 1 << 16;

/// Formats numbers at a fixed precision into a reusable buffer.
struct LineWriter<W: Write> {
    out: BufWriter<W>,
    buf: Vec<u8>,
    single: bool,
}

impl<W: Write> LineWriter<W> {
    fn new(out: W, precision: Precision) -> Self {
        LineWriter {
            out: BufWriter::with_capacity(CHUNK, out),
            buf: Vec::with_capacity(CHUNK + 1024),
            single: matches!(precision, Precision::F32),
        }
    }

    fn number(&mut self, x: f64) {
        if self.single {
            g_format(f64::from(x as f32), 9, &mut self.buf);
        } else {
            g_format(x, 17, &mut self.buf);
        }
    }

    /// Ends a line, handing the buffer over when it is full.
    fn end_line(&mut self) -> io::Result<()> {
        self.buf.push(b'\n');
        if self.buf.len() >= CHUNK {
            self.out.write_all(&self.buf)?;
            self.buf.clear();
        }
        Ok(())
    }

    fn finish(mut self) -> io::Result<()> {
        self.out.write_all(&self.buf)?;
        self.out.flush()
    }
}

/// Writes positions, UVs and faces as OBJ text.
///
/// Writes `v x y z` for every position, `vt` with all `width` components for
/// every UV value, and an `f` line per face that is not a hole, with 1-based
/// `v/vt` corners (plain `v` without UVs). Numbers are formatted as C's
/// `%.17g` ([`Precision::F64`]) or `%.9g` of the value rounded to `f32`
/// ([`Precision::F32`]); see [`format_g`](crate::io::number::format_g).
///
/// Malformed input (decreasing offsets, a hole flag count or UV index count
/// that does not match) is an [`io::ErrorKind::InvalidInput`] error before
/// anything is written. Indices themselves are written as given.
pub fn write_obj_to<W: Write>(out: W, data: &ObjOutput<'_>) -> io::Result<()> {
    check_output(data)?;
    let mut w = LineWriter::new(out, data.precision);
    for p in data.positions {
        w.buf.push(b'v');
        for c in p.to_array() {
            w.buf.push(b' ');
            w.number(c);
        }
        w.end_line()?;
    }
    if let Some(uv) = &data.uv {
        for value in uv.values.chunks_exact(uv.width) {
            w.buf.extend_from_slice(b"vt");
            for &c in value {
                w.buf.push(b' ');
                w.number(c);
            }
            w.end_line()?;
        }
    }
    for n in data.normals.unwrap_or(&[]) {
        w.buf.extend_from_slice(b"vn");
        for c in n.to_array() {
            w.buf.push(b' ');
            w.number(c);
        }
        w.end_line()?;
    }
    for (f, range) in data.face_offsets.windows(2).enumerate() {
        if data.holes.is_some_and(|holes| holes[f]) {
            continue;
        }
        let (start, end) = (range[0] as usize, range[1] as usize);
        w.buf.push(b'f');
        for i in start..end {
            w.buf.push(b' ');
            push_u64(u64::from(data.face_vertices[i]) + 1, &mut w.buf);
            if let Some(uv) = &data.uv {
                w.buf.push(b'/');
                push_u64(u64::from(uv.face_values[i]) + 1, &mut w.buf);
            }
            if data.normals.is_some() {
                w.buf
                    .extend_from_slice(if data.uv.is_some() { b"/" } else { b"//" });
                push_u64(u64::from(data.face_vertices[i]) + 1, &mut w.buf);
            }
        }
        w.end_line()?;
    }
    w.finish()
}

/// Writes an OBJ file atomically: the text goes to a temporary file in the
/// same directory, which then replaces `path`. On any error `path` is left
/// untouched and the temporary file is removed.
///
/// Any failure is an [`Error::Io`] naming `path`.
pub fn write_obj(path: &Path, data: &ObjOutput<'_>) -> Result<(), Error> {
    crate::io::atomic::write_with(path, |file| write_obj_to(file, data))
}

/// Writes a [`Mesh`] as OBJ text with its tags, so that [`parse_obj`](super::parse_obj) reads
/// the same mesh back (exactly, with [`Precision::F64`]).
///
/// Writes the positions, face-varying channel 0 as `vt` when its width is 2
/// (other channels are not written), every face (holes included), then one
/// `t crease 2/1/0 a b s` line per crease, one `t corner` line for all corners
/// and one `t hole` line for all holes. Sharpness is written with 9 significant
/// digits, which is exact for `f32`. Option tags are not written. OBJ faces
/// are counter-clockwise: a [`Mesh::left_handed`] mesh is written as
/// [`Mesh::right_handed`] reads it.
pub fn write_mesh_obj_to<W: Write>(
    mut out: W,
    mesh: &Mesh,
    precision: Precision,
) -> io::Result<()> {
    let mesh = &*mesh.right_handed();
    let uv = mesh
        .fvar_channels
        .first()
        .filter(|channel| channel.width == 2)
        .map(|channel| UvOutput {
            width: 2,
            values: &channel.values,
            face_values: &channel.indices,
        });
    let data = ObjOutput {
        positions: &mesh.positions,
        face_offsets: &mesh.face_offsets,
        face_vertices: &mesh.face_vertices,
        holes: None,
        uv,
        normals: None,
        precision,
    };
    write_obj_to(&mut out, &data)?;
    let mut buf = Vec::new();
    let sharpness = |s: f32, buf: &mut Vec<u8>| {
        g_format(f64::from(s), 9, buf);
    };
    for crease in &mesh.creases {
        buf.extend_from_slice(b"t crease 2/1/0 ");
        push_u64(crease.vertices[0].into(), &mut buf);
        buf.push(b' ');
        push_u64(crease.vertices[1].into(), &mut buf);
        buf.push(b' ');
        sharpness(crease.sharpness, &mut buf);
        buf.push(b'\n');
    }
    if !mesh.corners.is_empty() {
        let n = mesh.corners.len() as u64;
        buf.extend_from_slice(b"t corner ");
        push_u64(n, &mut buf);
        buf.push(b'/');
        push_u64(n, &mut buf);
        buf.extend_from_slice(b"/0");
        for corner in &mesh.corners {
            buf.push(b' ');
            push_u64(corner.vertex.into(), &mut buf);
        }
        for corner in &mesh.corners {
            buf.push(b' ');
            sharpness(corner.sharpness, &mut buf);
        }
        buf.push(b'\n');
    }
    if !mesh.holes.is_empty() {
        buf.extend_from_slice(b"t hole ");
        push_u64(mesh.holes.len() as u64, &mut buf);
        buf.extend_from_slice(b"/0/0");
        for &face in &mesh.holes {
            buf.push(b' ');
            push_u64(face.into(), &mut buf);
        }
        buf.push(b'\n');
    }
    out.write_all(&buf)?;
    out.flush()
}

/// [`write_mesh_obj_to`] into a `String`.
///
/// # Panics
///
/// If the mesh's face offsets or face-varying channel 0 are malformed
/// (which [`Mesh::validate`] reports).
pub fn mesh_to_obj_string(mesh: &Mesh, precision: Precision) -> String {
    let mut out = Vec::new();
    if let Err(e) = write_mesh_obj_to(&mut out, mesh, precision) {
        panic!("cannot write the mesh as OBJ: {e}");
    }
    String::from_utf8(out).expect("OBJ output is ASCII")
}

/// [`write_mesh_obj_to`] into a file, atomically as [`write_obj`] does.
pub fn write_mesh_obj(path: &Path, mesh: &Mesh, precision: Precision) -> Result<(), Error> {
    crate::io::atomic::write_with(path, |file| write_mesh_obj_to(file, mesh, precision))
}
