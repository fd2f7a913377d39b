//! Conformance of `subdiv refine` (both engines) with an independent OpenSubdiv
//! driver (`cpp/osd_driver.cpp`), index by index.
//!
//! The driver is a from-scratch C++ program over OpenSubdiv's Far layer: its
//! own OBJ parser, a `Far::TopologyDescriptor`, `RefineUniform` and
//! `PrimvarRefinerReal<double>`. Both programs print the last level with
//! `%.17g`, so for every shape below the two output files must be
//! byte-identical: same vertex order, same face-varying values, same faces,
//! same doubles.
//!
//! The shapes are generated in code (`subdiv::shapes`, edited here where a
//! case needs it, and written by the library's OBJ writer), after
//! OpenSubdiv's regression shapes: creases, corners, holes, boundaries,
//! n-gons, UV seams, non-manifold topology, Loop and bilinear meshes, and the
//! less common `Sdc::Options`.

#![cfg(feature = "osd")]

mod support;

use glam::DVec3;
use std::fmt::Write as _;
use std::fs;
use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;
use subdiv::{FVarChannel, Mesh, shapes};
use support::{obj_text, scratch, subdiv_bin};

// ---------------------------------------------------------------------------
// Harness

const DRIVER_SOURCE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/cpp/osd_driver.cpp");

/// The reference driver, compiled once per test run.
fn driver() -> &'static Path {
    static DRIVER: OnceLock<PathBuf> = OnceLock::new();
    DRIVER.get_or_init(|| {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR"));
        fs::create_dir_all(dir).expect("create CARGO_TARGET_TMPDIR");
        let exe = dir.join("osd_driver");
        // Build under a per-process name, then rename: another test process
        // running at the same time never sees a half-written executable.
        let tmp = dir.join(format!("osd_driver.{}.tmp", std::process::id()));
        let out = Command::new("g++")
            .args(["-std=c++14", "-O2", DRIVER_SOURCE, "-losdCPU", "-o"])
            .arg(&tmp)
            .output()
            .expect("run g++ (is it installed?)");
        if !out.status.success() {
            let _ = fs::remove_file(&tmp);
            panic!(
                "compiling the reference driver failed ({}):\n{}",
                out.status,
                String::from_utf8_lossy(&out.stderr)
            );
        }
        fs::rename(&tmp, &exe).expect("install the reference driver");
        exe
    })
}

fn show(cmd: &Command) -> String {
    let mut s = cmd.get_program().to_string_lossy().into_owned();
    for a in cmd.get_args() {
        s.push(' ');
        s.push_str(&a.to_string_lossy());
    }
    s
}

fn run(cmd: &mut Command) -> Output {
    cmd.output()
        .unwrap_or_else(|e| panic!("cannot start `{}`: {e}", show(cmd)))
}

fn expect_success(what: &str, cmd: &mut Command) {
    let out = run(cmd);
    if !out.status.success() {
        panic!(
            "{what} failed ({}): `{}`\nstderr:\n{}",
            out.status,
            show(cmd),
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

/// Counts of the lines of an output OBJ.
#[derive(Debug, Default, PartialEq, Eq)]
struct Counts {
    vertices: usize,
    uvs: usize,
    faces: usize,
    face_corners: usize,
    other: usize,
}

fn counts(text: &str) -> Counts {
    let mut c = Counts::default();
    for line in text.lines() {
        let mut it = line.split_whitespace();
        match it.next() {
            Some("v") => c.vertices += 1,
            Some("vt") => c.uvs += 1,
            Some("f") => {
                c.faces += 1;
                c.face_corners += it.count();
            }
            _ => c.other += 1,
        }
    }
    c
}

/// Compares the driver's and the crate's outputs; panics with the first
/// differing line when they are not byte-identical.
fn compare(case: &str, engine: &str, level: u32, reference: &[u8], ours: &[u8]) {
    let ref_text = String::from_utf8_lossy(reference);
    let our_text = String::from_utf8_lossy(ours);
    let ref_counts = counts(&ref_text);
    let our_counts = counts(&our_text);
    if reference == ours {
        assert_eq!(ref_counts, our_counts);
        // Faces may legitimately all be holes (boundary `none` on a mesh whose
        // every face touches the boundary); vertices are always written.
        assert!(
            ref_counts.vertices > 0,
            "{case} level {level}: no vertices in the output"
        );
        return;
    }
    let mut msg = format!(
        "{case} level {level}: `subdiv refine --engine {engine}` differs from the reference driver\n"
    );
    let _ = writeln!(msg, "  driver counts: {ref_counts:?}");
    let _ = writeln!(msg, "  crate  counts: {our_counts:?}");
    if ref_counts != our_counts {
        let _ = writeln!(msg, "  COUNTS DIFFER");
    }
    let mut a = reference.split(|&b| b == b'\n');
    let mut b = ours.split(|&b| b == b'\n');
    let mut line_no = 0usize;
    loop {
        line_no += 1;
        match (a.next(), b.next()) {
            (Some(x), Some(y)) if x == y => continue,
            (x, y) => {
                let fmt = |l: Option<&[u8]>| match l {
                    Some(l) => format!("{:?}", String::from_utf8_lossy(l)),
                    None => "<end of file>".to_string(),
                };
                let _ = writeln!(msg, "  first difference at line {line_no}:");
                let _ = writeln!(msg, "    driver: {}", fmt(x));
                let _ = writeln!(msg, "    crate:  {}", fmt(y));
                break;
            }
        }
    }
    panic!("{msg}");
}

/// Refines `obj` with both programs at every level of `levels` and compares,
/// in a fresh directory named after the case.
fn check(case: &str, obj: &str, flags: &[&str], levels: RangeInclusive<u32>) {
    let dir = scratch(case);
    let input = dir.join(format!("{case}.obj"));
    fs::write(&input, obj).expect("write the input OBJ");
    for level in levels {
        let lv = level.to_string();
        let ref_out = dir.join(format!("{case}.L{level}.driver.obj"));

        expect_success(
            &format!("{case} level {level}: reference driver"),
            Command::new(driver())
                .arg(&input)
                .arg(&ref_out)
                .args(["--level", &lv])
                .args(flags),
        );
        let reference = fs::read(&ref_out).expect("read the driver's output");
        // Both engines must write exactly the driver's file.
        for engine in ["osd", "native"] {
            let our_out = dir.join(format!("{case}.L{level}.{engine}.obj"));
            expect_success(
                &format!("{case} level {level}: subdiv refine --engine {engine}"),
                Command::new(subdiv_bin())
                    .arg("refine")
                    .arg(&input)
                    .arg("-o")
                    .arg(&our_out)
                    .args(["--engine", engine, "--level", &lv])
                    .args(flags),
            );
            let ours = fs::read(&our_out).unwrap_or_else(|e| {
                panic!("{case} level {level}: subdiv --engine {engine} wrote no output file: {e}")
            });
            compare(case, engine, level, &reference, &ours);
        }
    }
}

macro_rules! conformance {
    ($( $(#[$meta:meta])* $name:ident: $shape:expr, [$($flag:expr),* $(,)?], $levels:expr; )+) => {
        $(
            $(#[$meta])*
            #[test]
            fn $name() {
                let obj: String = $shape;
                check(stringify!($name), &obj, &[$($flag),*], $levels);
            }
        )+
    };
}

// ---------------------------------------------------------------------------
// Shapes
//
// Meshes of `subdiv::shapes` (some edited: heights, UVs, a subset), written
// by the library's OBJ writer, followed by raw tag lines. Only the two cubes
// that exercise the OBJ syntax are written by hand.

/// OBJ text of `mesh` ([`support::obj_text`]), then `tags`, one per line.
fn obj(mesh: &Mesh, tags: &[&str]) -> String {
    let mut s = obj_text(mesh);
    for t in tags {
        s.push_str(t);
        s.push('\n');
    }
    s
}

/// A face-varying channel of 2-D values: `values`, and per face the indices
/// of its corners' values.
fn uv_channel(values: &[[f64; 2]], face_values: &[Vec<usize>]) -> FVarChannel {
    FVarChannel {
        width: 2,
        values: values.iter().flatten().copied().collect(),
        indices: face_values.iter().flatten().map(|&i| i as u32).collect(),
    }
}

/// Sets the height of every vertex of a `shapes::grid(n, _)` from its column and row.
fn set_heights(mesh: &mut Mesh, n: u32, z: impl Fn(u32, u32) -> f64) {
    for (k, p) in (0u32..).zip(mesh.positions.iter_mut()) {
        p.z = z(k % (n + 1), k / (n + 1));
    }
}

/// The unit cube in OpenSubdiv's numbering (the tags below name its vertices).
fn cube(tags: &[&str]) -> String {
    obj(&shapes::tutorial_cube(), tags)
}

/// A cube whose UVs are cut. The four faces around the x axis are a strip
/// whose two ends do not meet (a seam along the edge 0-1); the x+ cap hangs
/// off the strip (sharing the UVs of the edge 3-5, as in a cross unwrap) and
/// the x- cap is a separate island. UV regions around a vertex thus have one,
/// two or three faces, and the strip's UVs are jittered so that its borders
/// are not straight lines (linear and smooth face-varying boundaries differ).
fn cube_uv_seam(tags: &[&str]) -> String {
    let mut mesh = shapes::tutorial_cube();
    // Ring position of each vertex around the x axis, and its side (x- = 0).
    let ring = |v: usize| v / 2;
    let side = |v: usize| v % 2;
    let mut uvs: Vec<[f64; 2]> = Vec::new();
    for i in 0..=4 {
        for s in 0..2 {
            let jitter = [0.0, 0.04, -0.03, 0.05, 0.02][i];
            uvs.push([
                i as f64 * 0.25 + 0.03 * s as f64,
                0.3 + 0.35 * s as f64 + jitter,
            ]);
        }
    }
    let mut face_uvs = Vec::new();
    for (k, f) in mesh.faces().enumerate().take(4) {
        face_uvs.push(
            f.iter()
                .map(|&v| {
                    let v = v as usize;
                    // Face k spans ring positions k and k+1 (the last face wraps
                    // to position 4, a distinct UV on the seam).
                    let i = if ring(v) == k { k } else { k + 1 };
                    i * 2 + side(v)
                })
                .collect::<Vec<_>>(),
        );
    }
    // x+ cap [1, 7, 5, 3]: vertices 3 and 5 reuse the strip's UVs of face 1
    // (ring positions 1 and 2, side 1); vertices 1 and 7 get new UVs.
    let (uv1, uv7) = (uvs.len(), uvs.len() + 1);
    uvs.push([0.27, 0.97]);
    uvs.push([0.55, 1.0]);
    let strip_uv = |ring: usize, side: usize| ring * 2 + side;
    face_uvs.push(vec![uv1, uv7, strip_uv(2, 1), strip_uv(1, 1)]);
    // x- cap [6, 0, 2, 4]: an island of its own.
    let base = uvs.len();
    for c in [[0.6, 0.02], [0.9, 0.0], [0.95, 0.25], [0.62, 0.22]] {
        uvs.push(c);
    }
    face_uvs.push((base..base + 4).collect());
    mesh.fvar_channels.push(uv_channel(&uvs, &face_uvs));
    obj(&mesh, tags)
}

/// An open `n` x `n` grid of quads in the xy plane, with a gentle bump in z.
fn grid(n: u32, tags: &[&str]) -> String {
    let mut mesh = shapes::grid(n, n);
    mesh.fvar_channels.clear();
    set_heights(
        &mut mesh,
        n,
        |i, j| if (i + j) % 3 == 0 { 0.25 } else { 0.0 },
    );
    obj(&mesh, tags)
}

/// A grid with per-vertex UVs (no seams), for face-varying boundary modes.
fn grid_uv(n: u32, tags: &[&str]) -> String {
    let mut mesh = shapes::grid(n, n);
    set_heights(&mut mesh, n, |i, j| ((i * j) % 2) as f64 * 0.3);
    obj(&mesh, tags)
}

/// A 4 x 4 grid whose UVs are cut into four regions: the left half (A), the
/// bottom-right block (B), the top-right block without its corner face (C)
/// and that corner face (D). Vertex (2,2) is a junction of three regions,
/// vertex (3,3) a concave corner of C, so each face-varying linear mode
/// gives a different result.
fn grid_uv_regions(tags: &[&str]) -> String {
    let n = 4;
    let mut mesh = shapes::grid(n as u32, n as u32);
    set_heights(&mut mesh, n as u32, |i, j| {
        if (i + 2 * j) % 4 == 1 { 0.3 } else { 0.0 }
    });
    let region = |i: usize, j: usize| match (i >= 2, j >= 2) {
        (false, _) => 0,
        (true, false) => 1,
        (true, true) if i == 3 && j == 3 => 3,
        (true, true) => 2,
    };
    let mut uvs: Vec<[f64; 2]> = Vec::new();
    let mut uv_of = std::collections::BTreeMap::new();
    let mut face_uvs = Vec::new();
    // The grid's faces, row by row, each from its lower-left corner (i, j)
    // counterclockwise.
    for j in 0..n {
        for i in 0..n {
            let r = region(i, j);
            let corners = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
            face_uvs.push(
                corners
                    .iter()
                    .map(|&(x, y)| {
                        *uv_of.entry((r, x, y)).or_insert_with(|| {
                            let jitter = ((x * 7 + y * 3 + r) % 5) as f64 * 0.01;
                            uvs.push([
                                x as f64 * 0.2 + r as f64 * 0.05 + jitter,
                                y as f64 * 0.2 - r as f64 * 0.03 + 0.5 * jitter,
                            ]);
                            uvs.len() - 1
                        })
                    })
                    .collect::<Vec<_>>(),
            );
        }
    }
    mesh.fvar_channels = vec![uv_channel(&uvs, &face_uvs)];
    obj(&mesh, tags)
}

/// A pyramid on a regular pentagon: one 5-gon and five triangles, the apex
/// straight above the centre.
fn pyramid_pentagon(tags: &[&str]) -> String {
    let mut mesh = shapes::pyramid(5);
    mesh.positions[5] = DVec3::new(0.0, 0.0, 1.25);
    obj(&mesh, tags)
}

/// Three quads sharing the edge 0-1 (a non-manifold fin), on a base quad:
/// the fin of `shapes::fin` without its fourth quad.
fn fin() -> String {
    let full = shapes::fin();
    let faces: Vec<&[u32]> = full.faces().take(3).collect();
    obj(&Mesh::from_faces(full.positions[..8].to_vec(), &faces), &[])
}

/// Two quads touching at one vertex only (a bowtie).
fn bowtie() -> String {
    let mesh = Mesh::from_faces(
        vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(2.0, 1.0, 0.5),
            DVec3::new(2.0, 2.0, 0.0),
            DVec3::new(1.0, 2.0, 0.5),
        ],
        &[&[0, 1, 2, 3], &[2, 4, 5, 6]],
    );
    obj(&mesh, &[])
}

fn tetrahedron(tags: &[&str]) -> String {
    obj(&shapes::tetrahedron(), tags)
}

fn octahedron(tags: &[&str]) -> String {
    obj(&shapes::octahedron(), tags)
}

fn icosahedron(tags: &[&str]) -> String {
    obj(&shapes::icosahedron(), tags)
}

/// An open fan of five triangles around vertex 0 (the centre is on the
/// boundary too: the sixth triangle is missing).
fn triangle_fan_mesh() -> Mesh {
    let mut mesh = Mesh::default();
    mesh.positions.push(DVec3::new(0.0, 0.0, 0.3));
    for k in 0..6 {
        let a = std::f64::consts::TAU * k as f64 / 6.0;
        mesh.positions.push(DVec3::new(a.cos(), a.sin(), 0.0));
    }
    for k in 1..6 {
        mesh.add_face(&[0, k, k + 1]);
    }
    mesh
}

fn triangle_fan(tags: &[&str]) -> String {
    obj(&triangle_fan_mesh(), tags)
}

/// An open `n` x `n` grid of quads, each split into two triangles along the
/// same diagonal, sheared in y, with its interior vertices raised.
fn triangle_grid(n: u32, tags: &[&str]) -> String {
    let quads = shapes::grid(n, n);
    let mut mesh = Mesh {
        positions: quads.positions.clone(),
        ..Mesh::default()
    };
    for (k, p) in (0u32..).zip(mesh.positions.iter_mut()) {
        let (i, j) = (k % (n + 1), k / (n + 1));
        p.y = j as f64 + 0.1 * i as f64;
        p.z = if i > 0 && j > 0 && i < n && j < n {
            0.5
        } else {
            0.0
        };
    }
    for f in quads.faces() {
        mesh.add_face(&[f[0], f[1], f[2]]);
        mesh.add_face(&[f[0], f[2], f[3]]);
    }
    obj(&mesh, tags)
}

/// The open fan with UVs cut between its first two and last three faces.
fn triangle_fan_uv() -> String {
    let mut mesh = triangle_fan_mesh();
    let mut uvs: Vec<[f64; 2]> = Vec::new();
    let mut face_uvs = Vec::new();
    let mut uv_of = std::collections::BTreeMap::new();
    for (k, f) in mesh.faces().enumerate() {
        let region = usize::from(k >= 2);
        face_uvs.push(
            f.iter()
                .map(|&v| {
                    *uv_of.entry((region, v)).or_insert_with(|| {
                        let p = mesh.positions[v as usize];
                        uvs.push([0.5 + 0.4 * p.x + 0.1 * region as f64, 0.5 + 0.45 * p.y]);
                        uvs.len() - 1
                    })
                })
                .collect::<Vec<_>>(),
        );
    }
    mesh.fvar_channels.push(uv_channel(&uvs, &face_uvs));
    obj(&mesh, &[])
}

/// Quads, triangles and a pentagon with UVs, for the bilinear scheme.
fn mixed_uv() -> String {
    let mut mesh = Mesh::from_faces(
        vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.1),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.2),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(2.0, 1.0, 0.3),
            DVec3::new(3.0, 0.5, 0.0),
            DVec3::new(1.5, 2.0, 0.4),
        ],
        &[&[0, 1, 4, 3], &[1, 2, 5, 4], &[2, 6, 5], &[3, 4, 5, 7]],
    );
    mesh.fvar_channels.push(FVarChannel {
        width: 2,
        values: mesh
            .positions
            .iter()
            .flat_map(|p| [p.x / 3.0, p.y / 2.0])
            .collect(),
        indices: mesh.face_vertices.clone(),
    });
    obj(&mesh, &[])
}

/// The cube written with every corner syntax: `v//vn`, `v/vt/vn` and
/// negative (relative) indices, with comments, groups and smoothing lines.
fn cube_obj_syntax() -> String {
    let cube = shapes::tutorial_cube();
    let mut s = String::from("# cube, exotic syntax\no cube\n");
    for p in &cube.positions {
        let _ = writeln!(s, "v {} {} {}", p.x, p.y, p.z);
    }
    for t in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] {
        let _ = writeln!(s, "vt {} {}", t[0], t[1]);
    }
    s.push_str("vn 0 0 1\ng all\ns off\n");
    for f in cube.faces() {
        s.push('f');
        for (k, &v) in f.iter().enumerate() {
            // Negative indices: -8 is the first vertex, -4 the first vt, -1 the normal.
            let vi = i64::from(v) - 8;
            let ti = k as i64 - 4;
            let _ = write!(s, " {vi}/{ti}/-1");
        }
        s.push('\n');
    }
    s
}

fn cube_vn_only() -> String {
    let cube = shapes::tutorial_cube();
    let mut s = String::new();
    for p in &cube.positions {
        let _ = writeln!(s, "v {} {} {}", p.x, p.y, p.z);
    }
    s.push_str("vn 0 0 1\n");
    for f in cube.faces() {
        s.push('f');
        for v in f {
            let _ = write!(s, " {}//1", v + 1);
        }
        s.push('\n');
    }
    s
}

const SEMI_SHARP_CHAIN: &str = "t crease 4/3/0 0 1 3 5 0.5 1.3 2.7";
const SEMI_SHARP_CORNER: &str = "t corner 1/1/0 6 2.0";
// A loop of six edges around the cube (not a face boundary): it cuts the cube
// into two halves.
const SHARP_LOOP: &str = "t crease 7/1/0 0 1 3 5 4 6 0 10";

// ---------------------------------------------------------------------------
// Cases

conformance! {
    // Catmull-Clark basics.
    catmark_cube: cube(&[]), [], 1..=4;
    catmark_cube_semisharp: cube(&[SEMI_SHARP_CHAIN, SEMI_SHARP_CORNER]), [], 1..=3;
    catmark_cube_sharp_loop: cube(&[SHARP_LOOP]), [], 1..=3;
    catmark_cube_mixed_tags: cube(&["t crease 2/1/0 0 1 0.8", "t crease 3/2/0 4 5 7 3.0 10", "t corner 2/2/0 2 7 0.7 10"]), [], 1..=3;
    catmark_pyramid_pentagon: pyramid_pentagon(&[]), [], 1..=3;
    catmark_pyramid_pentagon_crease: pyramid_pentagon(&["t crease 6/1/0 0 1 2 3 4 0 1.7"]), [], 1..=3;

    // Open grids and boundary interpolation.
    catmark_grid_boundary_none: grid(4, &[]), ["--boundary", "none"], 1..=3;
    catmark_grid_boundary_edge_only: grid(4, &[]), ["--boundary", "edge-only"], 1..=3;
    catmark_grid_boundary_edge_and_corner: grid(4, &[]), ["--boundary", "edge-and-corner"], 1..=3;
    catmark_grid_default_boundary: grid(4, &[]), [], 1..=3;
    catmark_grid_tag_interpolateboundary_0: grid(4, &["t interpolateboundary 1/0/0 0"]), [], 1..=3;
    catmark_grid_tag_interpolateboundary_1: grid(4, &["t interpolateboundary 1/0/0 1"]), [], 1..=3;
    catmark_grid_tag_interpolateboundary_2: grid(4, &["t interpolateboundary 1/0/0 2"]), [], 1..=3;
    catmark_grid_flag_overrides_tag: grid(4, &["t interpolateboundary 1/0/0 0"]), ["--boundary", "edge-and-corner"], 1..=2;
    catmark_grid_boundary_none_creased_border: grid(4, &["t crease 5/1/0 0 1 2 3 4 10"]), ["--boundary", "none"], 1..=3;

    // Holes.
    catmark_grid_holes: grid(4, &["t hole 2/0/0 5 10"]), [], 1..=3;
    catmark_grid_holes_boundary_none: grid(4, &["t hole 1/0/0 6"]), ["--boundary", "none"], 1..=3;
    catmark_cube_hole: cube(&["t hole 1/0/0 2"]), [], 1..=3;

    // Face-varying data across a UV seam, under every linear interpolation.
    catmark_uv_seam_fvar_none: cube_uv_seam(&[]), ["--fvar", "none"], 1..=3;
    catmark_uv_seam_fvar_corners_only: cube_uv_seam(&[]), ["--fvar", "corners-only"], 1..=3;
    catmark_uv_seam_fvar_corners_plus1: cube_uv_seam(&[]), ["--fvar", "corners-plus1"], 1..=3;
    catmark_uv_seam_fvar_corners_plus2: cube_uv_seam(&[]), ["--fvar", "corners-plus2"], 1..=3;
    catmark_uv_seam_fvar_boundaries: cube_uv_seam(&[]), ["--fvar", "boundaries"], 1..=3;
    catmark_uv_seam_fvar_all: cube_uv_seam(&[]), ["--fvar", "all"], 1..=3;
    catmark_uv_seam_fvar_default: cube_uv_seam(&[]), [], 1..=2;
    catmark_uv_seam_tag_fvar_1: cube_uv_seam(&["t facevaryinginterpolateboundary 1/0/0 1"]), [], 1..=2;
    catmark_uv_seam_tag_fvar_3: cube_uv_seam(&["t facevaryinginterpolateboundary 1/0/0 3"]), [], 1..=2;
    catmark_uv_regions_fvar_none: grid_uv_regions(&[]), ["--fvar", "none"], 1..=3;
    catmark_uv_regions_fvar_corners_only: grid_uv_regions(&[]), ["--fvar", "corners-only"], 1..=3;
    catmark_uv_regions_fvar_corners_plus1: grid_uv_regions(&[]), ["--fvar", "corners-plus1"], 1..=3;
    catmark_uv_regions_fvar_corners_plus2: grid_uv_regions(&[]), ["--fvar", "corners-plus2"], 1..=3;
    catmark_uv_regions_fvar_boundaries: grid_uv_regions(&[]), ["--fvar", "boundaries"], 1..=3;
    catmark_uv_regions_fvar_all: grid_uv_regions(&[]), ["--fvar", "all"], 1..=3;
    loop_uv_fan_fvar_corners_plus2: triangle_fan_uv(), ["--scheme", "loop", "--fvar", "corners-plus2"], 1..=3;
    catmark_uv_seam_creased: cube_uv_seam(&[SEMI_SHARP_CHAIN]), ["--fvar", "corners-plus1"], 1..=3;
    catmark_grid_uv_fvar_none: grid_uv(3, &[]), ["--fvar", "none"], 1..=3;
    catmark_grid_uv_fvar_boundaries_edge_and_corner: grid_uv(3, &[]), ["--fvar", "boundaries", "--boundary", "edge-and-corner"], 1..=3;

    // OBJ corner syntax.
    catmark_obj_syntax_negative_indices: cube_obj_syntax(), ["--fvar", "corners-only"], 1..=2;
    catmark_obj_syntax_normals_only: cube_vn_only(), [], 1..=2;

    // Non-manifold topology.
    catmark_nonmanifold_fin: fin(), [], 1..=3;
    catmark_nonmanifold_bowtie: bowtie(), [], 1..=3;
    catmark_nonmanifold_bowtie_edge_and_corner: bowtie(), ["--boundary", "edge-and-corner"], 1..=2;

    // Loop.
    loop_tetrahedron: tetrahedron(&[]), ["--scheme", "loop"], 1..=4;
    loop_tetrahedron_crease: tetrahedron(&["t crease 3/1/0 0 1 2 2.0"]), ["--scheme", "loop"], 1..=3;
    loop_icosahedron: icosahedron(&[]), ["--scheme", "loop"], 1..=3;
    loop_icosahedron_crease: icosahedron(&["t crease 4/3/0 0 11 5 1 1.5 10 0.4", "t corner 1/1/0 3 4.0"]), ["--scheme", "loop"], 1..=3;
    loop_fan_edge_only: triangle_fan(&[]), ["--scheme", "loop", "--boundary", "edge-only"], 1..=3;
    loop_fan_edge_and_corner: triangle_fan(&[]), ["--scheme", "loop", "--boundary", "edge-and-corner"], 1..=3;
    // Every face of the fan touches the boundary: under `none` all are holes.
    loop_fan_boundary_none_all_holes: triangle_fan(&[]), ["--scheme", "loop", "--boundary", "none"], 1..=2;
    loop_triangle_grid_boundary_none: triangle_grid(4, &[]), ["--scheme", "loop", "--boundary", "none"], 1..=3;
    loop_triangle_grid_edge_and_corner: triangle_grid(4, &["t hole 1/0/0 9"]), ["--scheme", "loop", "--boundary", "edge-and-corner"], 1..=3;

    // Bilinear.
    bilinear_cube: cube(&[SEMI_SHARP_CHAIN]), ["--scheme", "bilinear"], 1..=3;
    bilinear_mixed_uv: mixed_uv(), ["--scheme", "bilinear"], 1..=3;
    bilinear_pyramid_pentagon: pyramid_pentagon(&[]), ["--scheme", "bilinear"], 1..=2;

    // Chaikin creasing on fractional sharpness.
    catmark_chaikin_flag: cube(&[SEMI_SHARP_CHAIN, SEMI_SHARP_CORNER]), ["--creasing", "chaikin"], 1..=3;
    catmark_chaikin_tag: cube(&[SEMI_SHARP_CHAIN, "t creasemethod 0/0/1 chaikin"]), [], 1..=3;
    catmark_chaikin_flag_overrides_tag: cube(&[SEMI_SHARP_CHAIN, "t creasemethod 0/0/1 chaikin"]), ["--creasing", "uniform"], 1..=3;
    loop_chaikin_icosahedron: icosahedron(&["t crease 4/3/0 0 11 5 1 0.3 1.6 2.2"]), ["--scheme", "loop", "--creasing", "chaikin"], 1..=3;

    // Smooth triangles on a Catmull-Clark triangle mesh.
    catmark_triangles_catmark: octahedron(&[]), ["--triangles", "catmark"], 1..=3;
    catmark_triangles_smooth: octahedron(&[]), ["--triangles", "smooth"], 1..=3;
    catmark_triangles_smooth_tag: octahedron(&["t smoothtriangles 0/0/1 smooth"]), [], 1..=3;
    catmark_triangles_smooth_pyramid: pyramid_pentagon(&[]), ["--triangles", "smooth"], 1..=3;

    // A crease between two vertices that share no edge: OpenSubdiv warns and
    // ignores it (the other crease on the same line still applies).
    catmark_crease_without_edge: cube(&["t crease 2/1/0 0 3 2.0", "t crease 2/1/0 0 1 2.0"]), [], 1..=3;
}

// ---------------------------------------------------------------------------
// The driver itself, and a case the crate must refuse.

/// The reference driver gets the well-known counts of a Catmull-Clark cube.
#[test]
fn driver_cube_counts() {
    let dir = scratch("driver_cube_counts");
    let input = dir.join("driver_cube_counts.obj");
    fs::write(&input, cube(&[])).unwrap();
    for (level, vertices, faces) in [(1, 26, 24), (2, 98, 96), (3, 386, 384)] {
        let out = dir.join(format!("driver_cube_counts.L{level}.obj"));
        expect_success(
            "reference driver",
            Command::new(driver())
                .arg(&input)
                .arg(&out)
                .args(["--level", &level.to_string()]),
        );
        let c = counts(&fs::read_to_string(&out).unwrap());
        assert_eq!(
            c,
            Counts {
                vertices,
                uvs: 0,
                faces,
                face_corners: 4 * faces,
                other: 0
            },
            "level {level}"
        );
    }
}

/// Loop refuses quads: both programs fail, and the crate leaves no output file.
#[test]
fn loop_on_quads_fails() {
    let dir = scratch("loop_on_quads_fails");
    let input = dir.join("loop_on_quads_fails.obj");
    fs::write(&input, cube(&[])).unwrap();

    let ref_out = dir.join("loop_on_quads_fails.driver.obj");
    let out = run(Command::new(driver())
        .arg(&input)
        .arg(&ref_out)
        .args(["--scheme", "loop", "--level", "1"]));
    assert!(
        !out.status.success(),
        "the reference driver accepted quads under Loop"
    );

    let our_out = dir.join("loop_on_quads_fails.crate.obj");
    let mut cmd = Command::new(subdiv_bin());
    cmd.arg("refine")
        .arg(&input)
        .arg("-o")
        .arg(&our_out)
        .args(["--engine", "osd", "--scheme", "loop", "--level", "1"]);
    let out = run(&mut cmd);
    assert!(
        !out.status.success(),
        "`{}` succeeded on a quad mesh; stdout:\n{}",
        show(&cmd),
        String::from_utf8_lossy(&out.stdout)
    );
    assert!(
        !our_out.exists(),
        "`{}` failed but left its output file behind",
        show(&cmd)
    );
}

/// The harness itself reports the first differing line (and is not vacuous).
#[test]
#[should_panic(expected = "first difference at line 2")]
fn harness_reports_first_difference() {
    compare(
        "harness_self_test",
        "osd",
        1,
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        b"v 0 0 0\nv 1 0 1.0000000000000001e-17\nv 0 1 0\nf 1 2 3\n",
    );
}

/// A small deterministic generator (no dependency): random meshes the engines
/// have never seen, compared with the independent driver.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        self.0 >> 33
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
    fn unit(&mut self) -> f64 {
        self.below(1_000_000) as f64 / 1_000_000.0
    }
}

/// A jittered grid with random cells dropped, split into triangles or left as
/// quads, plus random creases and corners; every 3rd mesh is all triangles.
fn random_mesh(seed: u64) -> (String, bool) {
    let mut rng = Lcg(seed);
    let (nx, ny) = (2 + rng.below(4) as usize, 2 + rng.below(3) as usize);
    let all_triangles = seed.is_multiple_of(3);
    let mut positions = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            positions.push(DVec3::new(
                i as f64 + 0.3 * rng.unit(),
                j as f64 + 0.3 * rng.unit(),
                rng.unit() - 0.5,
            ));
        }
    }
    let at = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
    let mut faces = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let q = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
            match if all_triangles { 1 } else { rng.below(6) } {
                0 if faces.len() > 1 => {}
                1 => {
                    faces.push(vec![q[0], q[1], q[2]]);
                    faces.push(vec![q[0], q[2], q[3]]);
                }
                _ => faces.push(q.to_vec()),
            }
        }
    }
    let mut tags = Vec::new();
    for _ in 0..rng.below(4) {
        let f = &faces[rng.below(faces.len() as u64) as usize];
        let k = rng.below(f.len() as u64) as usize;
        let s = [0.5, 1.0, 2.25, 10.0][rng.below(4) as usize];
        tags.push(format!(
            "t crease 2/1/0 {} {} {s}",
            f[k],
            f[(k + 1) % f.len()]
        ));
    }
    if rng.below(2) == 0 {
        tags.push(format!(
            "t corner 1/1/0 {} 3.5",
            rng.below(positions.len() as u64)
        ));
    }
    let tags: Vec<&str> = tags.iter().map(String::as_str).collect();
    let faces: Vec<&[u32]> = faces.iter().map(Vec::as_slice).collect();
    (
        obj(&Mesh::from_faces(positions, &faces), &tags),
        all_triangles,
    )
}

#[test]
fn random_meshes_match_the_driver() {
    for seed in 1..=24u64 {
        let (text, triangles) = random_mesh(seed);
        let scheme = if triangles {
            "loop"
        } else {
            ["catmark", "bilinear"][(seed % 2) as usize]
        };
        let boundary = ["edge-only", "edge-and-corner", "none"][(seed % 3) as usize];
        let creasing = ["uniform", "chaikin"][((seed / 2) % 2) as usize];
        check(
            &format!("random_{seed}"),
            &text,
            &[
                "--scheme",
                scheme,
                "--boundary",
                boundary,
                "--creasing",
                creasing,
            ],
            1..=3,
        );
    }
}

// ---------------------------------------------------------------------------
// Feature-adaptive refinement: `subdiv refine --adaptive N --levels-json`
// (both engines) against the driver's `RefineAdaptive`, level by level.

/// The levels of a `--levels-json` file: counts, faces and positions.
#[derive(Debug, PartialEq)]
struct AdaptiveLevel {
    counts: [u64; 3],
    faces: Vec<Vec<u64>>,
    positions: Vec<[f64; 3]>,
}

fn adaptive_levels(path: &Path) -> Vec<AdaptiveLevel> {
    let text = fs::read_to_string(path).expect("read a levels JSON file");
    let json: serde_json::Value = serde_json::from_str(&text).expect("parse a levels JSON file");
    let num = |v: &serde_json::Value| v.as_u64().expect("a count");
    json["levels"]
        .as_array()
        .expect("a levels array")
        .iter()
        .map(|l| AdaptiveLevel {
            counts: [num(&l["vertices"]), num(&l["edges"]), num(&l["faces"])],
            faces: serde_json::from_value(l["face_vertices"].clone()).expect("faces"),
            positions: serde_json::from_value(l["positions"].clone()).expect("positions"),
        })
        .collect()
}

/// A flag as the CLI spells it, and as the driver does.
type FlagPair<'a> = (&'a [&'a str], &'a [&'a str]);

/// Refines `obj` adaptively to `isolation` with both programs (`flags` as
/// (CLI flag, driver flag and value) pairs) and compares every level: counts
/// and faces exactly, positions within 1e-9 of the base mesh's bounding-box
/// diagonal (the bound; in practice they agree bit for bit, up to
/// JSON's decimal round trip).
fn check_adaptive(case: &str, obj: &str, isolation: u32, flags: &[FlagPair]) {
    let dir = scratch(case);
    let input = dir.join(format!("{case}.obj"));
    fs::write(&input, obj).expect("write the input OBJ");
    let iso = isolation.to_string();
    let ref_out = dir.join(format!("{case}.driver.json"));
    expect_success(
        &format!("{case}: reference driver"),
        Command::new(driver())
            .arg(&input)
            .arg(&ref_out)
            .args(["--adaptive", &iso])
            .args(flags.iter().flat_map(|(_, d)| d.iter())),
    );
    let reference = adaptive_levels(&ref_out);
    let base = &reference[0].positions;
    let (lo, hi) = base.iter().fold(
        (DVec3::splat(f64::MAX), DVec3::splat(f64::MIN)),
        |(lo, hi), p| (lo.min(DVec3::from(*p)), hi.max(DVec3::from(*p))),
    );
    let tolerance = 1e-9 * (hi - lo).length().max(1.0);
    for engine in ["osd", "native"] {
        let our_out = dir.join(format!("{case}.{engine}.json"));
        expect_success(
            &format!("{case}: subdiv refine --engine {engine}"),
            Command::new(subdiv_bin())
                .arg("refine")
                .arg(&input)
                .args(["--engine", engine, "--adaptive", &iso, "--levels-json"])
                .arg(&our_out)
                .args(flags.iter().flat_map(|(c, _)| c.iter())),
        );
        let ours = adaptive_levels(&our_out);
        assert_eq!(
            ours.len(),
            reference.len(),
            "{case} ({engine}): number of levels"
        );
        for (l, (a, b)) in ours.iter().zip(&reference).enumerate() {
            assert_eq!(a.counts, b.counts, "{case} ({engine}): counts of level {l}");
            assert_eq!(a.faces, b.faces, "{case} ({engine}): faces of level {l}");
            assert_eq!(a.positions.len(), b.positions.len());
            for (v, (p, q)) in a.positions.iter().zip(&b.positions).enumerate() {
                let d = (DVec3::from(*p) - DVec3::from(*q)).length();
                assert!(
                    d <= tolerance,
                    "{case} ({engine}): level {l} vertex {v} is {p:?}, the driver's {q:?}"
                );
            }
        }
    }
}

/// The driver's adaptive counts of a Catmull-Clark cube, derived by hand in
/// native_adaptive.rs.
#[test]
fn driver_adaptive_cube_counts() {
    let dir = scratch("driver_adaptive_cube_counts");
    let input = dir.join("cube.obj");
    fs::write(&input, cube(&[])).unwrap();
    let out = dir.join("cube.json");
    expect_success(
        "reference driver",
        Command::new(driver())
            .arg(&input)
            .arg(&out)
            .args(["--adaptive", "3"]),
    );
    let counts: Vec<[u64; 3]> = adaptive_levels(&out).iter().map(|l| l.counts).collect();
    assert_eq!(
        counts,
        [[8, 12, 6], [26, 48, 24], [98, 192, 96], [296, 504, 216]]
    );
}

/// Shapes after OpenSubdiv's regression shapes (creases, corners, holes,
/// boundaries, n-gons, UV seams, non-manifold, Loop and bilinear) × the
/// adaptive options that change the selection.
#[test]
fn adaptive_matches_the_driver() {
    let catmark: &[(&str, String)] = &[
        ("cube", cube(&[])),
        (
            "cube_semisharp",
            cube(&[SEMI_SHARP_CHAIN, SEMI_SHARP_CORNER]),
        ),
        ("cube_sharp_loop", cube(&[SHARP_LOOP])),
        (
            "pyramid_pentagon_crease",
            pyramid_pentagon(&["t crease 6/1/0 0 1 2 3 4 0 1.7"]),
        ),
        ("grid_holes", grid(4, &["t hole 2/0/0 5 10"])),
        (
            "grid_creased_border",
            grid(4, &["t crease 5/1/0 0 1 2 3 4 10"]),
        ),
        ("uv_seam", cube_uv_seam(&[])),
        ("fin", fin()),
        ("bowtie", bowtie()),
    ];
    let option_sets: &[(&str, &[FlagPair])] = &[
        ("default", &[]),
        (
            "secondary1",
            &[(&["--secondary", "1"], &["--secondary", "1"])],
        ),
        (
            "single_crease",
            &[(&["--single-crease"], &["--single-crease", "yes"])],
        ),
        (
            "inf_sharp",
            &[
                (&["--inf-sharp"], &["--inf-sharp", "yes"]),
                (&["--boundary", "none"], &["--boundary", "none"]),
            ],
        ),
        (
            "faces_first_chaikin",
            &[
                (&["--faces-first"], &["--faces-first", "yes"]),
                (&["--creasing", "chaikin"], &["--creasing", "chaikin"]),
            ],
        ),
    ];
    for (name, obj) in catmark {
        for (set, flags) in option_sets {
            for isolation in [2, 4] {
                check_adaptive(
                    &format!("adaptive_{name}_{set}_{isolation}"),
                    obj,
                    isolation,
                    flags,
                );
            }
        }
    }
    let loop_flags: &[FlagPair] = &[(&["--scheme", "loop"], &["--scheme", "loop"])];
    check_adaptive(
        "adaptive_loop_icosahedron",
        &icosahedron(&[]),
        3,
        loop_flags,
    );
    check_adaptive(
        "adaptive_loop_creased",
        &icosahedron(&["t crease 4/3/0 0 11 5 1 0.3 1.6 2.2"]),
        4,
        loop_flags,
    );
    let bilinear: &[FlagPair] = &[(&["--scheme", "bilinear"], &["--scheme", "bilinear"])];
    check_adaptive(
        "adaptive_bilinear_pyramid",
        &pyramid_pentagon(&[]),
        3,
        bilinear,
    );
}

// ---------------------------------------------------------------------------
// Bfr: `subdiv eval --surface bfr` and `subdiv tessellate` (both engines)
// against the driver's own use of Bfr (`--bfr-eval`, `--bfr-tessellate`):
// `Bfr::RefinerSurfaceFactory`, `Surface::Evaluate` and `Bfr::Tessellation`
// from scratch, each face's points evaluated on their own.

/// The mesh and options of a case as `subdiv` reads them (the OBJ's tags
/// under the case's flags).
fn bfr_mesh(obj: &str, flags: &[&str]) -> (Mesh, subdiv::Options) {
    let shape = subdiv::io::parse_obj(obj, Path::new("<case>")).expect("the case parses");
    let mut options = shape.options();
    for pair in flags.chunks(2) {
        let value = pair[1];
        match pair[0] {
            "--scheme" => options.scheme = value.parse().expect("scheme"),
            "--boundary" => options.boundary = value.parse().expect("boundary"),
            "--fvar" => options.fvar = value.parse().expect("fvar"),
            "--creasing" => options.creasing = value.parse().expect("creasing"),
            "--triangles" => options.triangles = value.parse().expect("triangles"),
            other => panic!("unknown flag {other}"),
        }
    }
    (shape.mesh, options)
}

/// The rows of `x y z dx/du dy/du dz/du dx/dv dy/dv dz/dv` of a file.
fn bfr_rows(path: &Path) -> Vec<[f64; 9]> {
    fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .lines()
        .map(|l| {
            let v: Vec<f64> = l.split(' ').map(|x| x.parse().expect("a number")).collect();
            v.try_into().expect("9 numbers")
        })
        .collect()
}

/// The `v` positions and the number of facets of an OBJ file: its `f`
/// lines, or the driver's `# facets N`.
fn bfr_obj(path: &Path) -> (Vec<DVec3>, usize) {
    let text = fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut points = Vec::new();
    let mut faces = 0;
    for line in text.lines() {
        let mut f = line.split_whitespace();
        match f.next() {
            Some("v") => {
                let c: Vec<f64> = f.map(|x| x.parse().expect("a coordinate")).collect();
                points.push(DVec3::new(c[0], c[1], c[2]));
            }
            Some("f") => faces += 1,
            Some("#") if line.starts_with("# facets ") => {
                faces = line["# facets ".len()..].parse().expect("a facet count");
            }
            _ => {}
        }
    }
    (points, faces)
}

/// Whether every point of `a` has one of `b` within `tol`.
fn bfr_covered(a: &[DVec3], b: &[DVec3], tol: f64) -> Option<DVec3> {
    let mut sorted = b.to_vec();
    sorted.sort_by(|p, q| p.x.total_cmp(&q.x));
    a.iter().copied().find(|p| {
        let from = sorted.partition_point(|q| q.x < p.x - tol);
        !sorted[from..]
            .iter()
            .take_while(|q| q.x <= p.x + tol)
            .any(|q| (*q - *p).abs().max_element() <= tol)
    })
}

/// One case: four random locations on every face with a limit surface,
/// evaluated by the driver and by `subdiv eval --surface bfr` (positions
/// within 1e-9 of the bounding box's diagonal, derivatives within 1e-7);
/// tessellations at rates 1, 3 and 8 and with quads kept, by the driver
/// (points at base vertices and inside base edges evaluated by the first
/// face using them, as OpenSubdiv's bfr tutorial 2_2 does) and by `subdiv
/// tessellate`: the same facet count and the same set of points (within
/// 1e-9 of the diagonal). `false` (nothing run) where the
/// OpenSubdiv bridge refuses a face: Debian's 3.5.0 Bfr reads memory it
/// does not own there (docs/CONFORMANCE.md), which the driver would too.
fn check_bfr(case: &str, obj: &str, flags: &[&str], seed: u64) -> bool {
    use subdiv::bfr::{MeshSurfaces, Parameterization, ParameterizationType, SurfaceOptions};
    let (mesh, options) = bfr_mesh(obj, flags);
    let so = SurfaceOptions::default();
    let theirs = subdiv::osd::bfr::Surfaces::new(&mesh, &options, &so).expect("the bridge");
    if (0..mesh.face_count()).any(|f| matches!(theirs.face_info(f), Err(subdiv::Error::Osd(_)))) {
        return false;
    }
    let ours = MeshSurfaces::new(&mesh, &options, &so).expect("native surfaces");
    let dir = scratch(&format!("bfr_{case}"));
    let input = dir.join("input.obj");
    fs::write(&input, obj).expect("write the input");
    let (lo, hi) = mesh.positions.iter().fold(
        (DVec3::splat(f64::MAX), DVec3::splat(f64::MIN)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let diag = (hi - lo).length().max(1.0);

    // Evaluation at random locations.
    let mut rng = Lcg(seed);
    let mut at = String::new();
    for f in (0..mesh.face_count()).filter(|&f| ours.has_surface(f)) {
        let param = Parameterization::new(options.scheme, mesh.face(f).len()).expect("a face");
        for _ in 0..4 {
            let (u, v) = (rng.unit(), rng.unit());
            let [u, v] = match param.kind() {
                ParameterizationType::Quad => [u, v],
                ParameterizationType::Triangle if u + v > 1.0 => [1.0 - u, 1.0 - v],
                ParameterizationType::Triangle => [u, v],
                ParameterizationType::QuadSubfaces => {
                    let sub = rng.below(param.face_size() as u64) as usize;
                    param
                        .subface_to_coord(sub, [u, v], true)
                        .expect("a sub-face")
                }
            };
            writeln!(at, "{f} {u:.17e} {v:.17e}").unwrap();
        }
    }
    let at_path = dir.join("at.txt");
    fs::write(&at_path, &at).expect("write the locations");
    let reference = dir.join("eval.driver.txt");
    expect_success(
        &format!("{case}: driver --bfr-eval"),
        Command::new(driver())
            .arg(&input)
            .arg(&reference)
            .arg("--bfr-eval")
            .arg(&at_path)
            .args(flags),
    );
    let reference = bfr_rows(&reference);
    assert_eq!(reference.len(), at.lines().count(), "{case}");
    for engine in ["native", "osd"] {
        let out = dir.join(format!("eval.{engine}.txt"));
        expect_success(
            &format!("{case}: subdiv eval --surface bfr --engine {engine}"),
            Command::new(subdiv_bin())
                .args([
                    "eval",
                    "--surface",
                    "bfr",
                    "--derivatives",
                    "--engine",
                    engine,
                ])
                .arg(&input)
                .arg("--at")
                .arg(&at_path)
                .arg("-o")
                .arg(&out)
                .args(flags),
        );
        let rows = bfr_rows(&out);
        assert_eq!(rows.len(), reference.len(), "{case} {engine}");
        for (i, (a, b)) in rows.iter().zip(&reference).enumerate() {
            for k in 0..9 {
                let tol = if k < 3 { 1e-9 } else { 1e-7 } * diag;
                assert!(
                    (a[k] - b[k]).abs() <= tol,
                    "{case} {engine}: location {} (line {}), value {k}: {} against the driver's {}",
                    at.lines().nth(i).unwrap_or(""),
                    i + 1,
                    a[k],
                    b[k]
                );
            }
        }
    }

    // Tessellation.
    for (rate, quads) in [(1, false), (3, false), (8, false), (3, true)] {
        let r = rate.to_string();
        let reference = dir.join(format!("tess{rate}{quads}.driver.obj"));
        expect_success(
            &format!("{case}: driver --bfr-tessellate {rate}"),
            Command::new(driver())
                .arg(&input)
                .arg(&reference)
                .args([
                    "--bfr-tessellate",
                    &r,
                    "--bfr-quads",
                    if quads { "yes" } else { "no" },
                ])
                .args(flags),
        );
        let (points, facets) = bfr_obj(&reference);
        for engine in ["native", "osd"] {
            let out = dir.join(format!("tess{rate}{quads}.{engine}.obj"));
            let mut cmd = Command::new(subdiv_bin());
            cmd.args(["tessellate", "--rate", &r, "--engine", engine])
                .arg(&input)
                .arg("-o")
                .arg(&out)
                .args(flags);
            if quads {
                cmd.arg("--quads");
            }
            expect_success(
                &format!("{case}: subdiv tessellate --engine {engine}"),
                &mut cmd,
            );
            let (ours, our_facets) = bfr_obj(&out);
            let what = format!("{case} {engine} rate {rate} quads {quads}");
            assert_eq!(our_facets, facets, "{what}: facets");
            let tol = 1e-9 * diag;
            if let Some(p) = bfr_covered(&points, &ours, tol) {
                panic!("{what}: the driver's point {p} is not in subdiv's mesh");
            }
            if let Some(p) = bfr_covered(&ours, &points, tol) {
                panic!("{what}: subdiv's point {p} is not in the driver's mesh");
            }
        }
    }
    true
}

/// The refinement cases' shapes (those Bfr reads: vertex data, tags,
/// scheme, boundary, creasing and triangle options) and random meshes.
#[test]
fn bfr_evaluation_and_tessellation_match_the_driver() {
    let mut cases: Vec<(String, String, Vec<&str>)> = vec![
        ("cube".into(), cube(&[]), vec![]),
        (
            "cube_semisharp".into(),
            cube(&[SEMI_SHARP_CHAIN, SEMI_SHARP_CORNER]),
            vec![],
        ),
        ("cube_sharp_loop".into(), cube(&[SHARP_LOOP]), vec![]),
        ("cube_hole".into(), cube(&["t hole 1/0/0 2"]), vec![]),
        (
            "cube_chaikin".into(),
            cube(&[SEMI_SHARP_CHAIN]),
            vec!["--creasing", "chaikin"],
        ),
        (
            "pyramid_pentagon".into(),
            pyramid_pentagon(&["t crease 6/1/0 0 1 2 3 4 0 1.7"]),
            vec![],
        ),
        (
            "grid_edge_only".into(),
            grid(4, &["t hole 2/0/0 5 10"]),
            vec!["--boundary", "edge-only"],
        ),
        (
            "grid_edge_and_corner".into(),
            grid(4, &[]),
            vec!["--boundary", "edge-and-corner"],
        ),
        ("grid_none".into(), grid(4, &[]), vec!["--boundary", "none"]),
        (
            "uv_seam".into(),
            cube_uv_seam(&[]),
            vec!["--fvar", "corners-plus1"],
        ),
        ("fin".into(), fin(), vec![]),
        (
            "bowtie".into(),
            bowtie(),
            vec!["--boundary", "edge-and-corner"],
        ),
        (
            "octahedron_smooth".into(),
            octahedron(&[]),
            vec!["--triangles", "smooth"],
        ),
        (
            "loop_icosahedron".into(),
            icosahedron(&["t crease 4/3/0 0 11 5 1 1.5 10 0.4"]),
            vec!["--scheme", "loop"],
        ),
        (
            "loop_fan".into(),
            triangle_fan(&[]),
            vec!["--scheme", "loop", "--boundary", "edge-and-corner"],
        ),
        (
            "loop_grid".into(),
            triangle_grid(4, &["t hole 1/0/0 9"]),
            vec!["--scheme", "loop"],
        ),
        (
            "bilinear_mixed".into(),
            mixed_uv(),
            vec!["--scheme", "bilinear"],
        ),
    ];
    for seed in 1..=16u64 {
        let (text, triangles) = random_mesh(seed);
        let scheme = if triangles {
            "loop"
        } else {
            ["catmark", "bilinear"][(seed % 2) as usize]
        };
        let boundary = ["edge-only", "edge-and-corner"][(seed % 2) as usize];
        let creasing = ["uniform", "chaikin"][((seed / 2) % 2) as usize];
        cases.push((
            format!("random_{seed}"),
            text,
            vec![
                "--scheme",
                scheme,
                "--boundary",
                boundary,
                "--creasing",
                creasing,
            ],
        ));
    }
    let mut checked = 0;
    for (k, (name, obj, flags)) in cases.iter().enumerate() {
        checked += usize::from(check_bfr(name, obj, flags, 1000 + k as u64));
    }
    assert!(
        checked + 2 >= cases.len(),
        "{checked} of {} cases checked",
        cases.len()
    );
}
