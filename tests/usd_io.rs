//! `subdiv::io::usd`: USD stages authored here with the `openusd` crate (as
//! `.usda`, `.usdc` and `.usdz`) read into meshes equal to ones built by
//! hand, attribute by attribute and fallback by fallback; refined alike by
//! both engines and as the same mesh written as OBJ; malformed attributes
//! refused with typed errors naming the prim and the attribute, or dropped
//! in lenient mode; refined meshes written back as `.usda` and read back
//! exactly.
#![cfg(feature = "usd")]

mod support;

use glam::DVec3;
use openusd::gf;
use openusd::sdf::{self, Value};
use openusd::usd;
use std::path::{Path, PathBuf};
use subdiv::io::usd::{
    UsdFVarOut, UsdInterpolation, UsdMeshOut, UsdPrimvar, UsdPrimvarOut, UsdReadOptions, UsdStage,
    read_usd, write_usda, write_usda_to,
};
use subdiv::{
    BoundaryInterpolation, Corner, Crease, CreasingMethod, Engine, Error, FVarChannel,
    FVarLinearInterpolation, Mesh, MeshError, Options, Precision, Request, Scheme,
    TriangleSubdivision, UsdError, UsdErrorKind,
};
use support::scratch;

// ---------------------------------------------------------------------------
// Authoring with the openusd crate.

/// A stage being authored in memory, exported to files.
struct Author {
    stage: usd::Stage,
}

impl Author {
    fn new() -> Author {
        Author {
            stage: usd::Stage::builder().in_memory("root.usda").unwrap(),
        }
    }

    /// `def TYPE "…"` at `path` (`TYPE` empty: typeless).
    fn def(&self, path: &str, type_name: &str) -> &Author {
        let prim = self.stage.define_prim(path).unwrap();
        if !type_name.is_empty() {
            prim.set_type_name(type_name).unwrap();
        }
        self
    }

    /// An attribute's default value.
    fn set(&self, attr: &str, type_name: &str, value: Value) -> &Author {
        self.stage
            .create_attribute(attr, type_name)
            .unwrap()
            .set(value)
            .unwrap();
        self
    }

    /// An attribute's time sample.
    fn sample(&self, attr: &str, type_name: &str, time: f64, value: Value) -> &Author {
        self.stage
            .create_attribute(attr, type_name)
            .unwrap()
            .set_at(value, usd::TimeCode::new(time))
            .unwrap();
        self
    }

    /// A uniform token attribute.
    fn token(&self, attr: &str, token: &str) -> &Author {
        self.stage
            .create_attribute(attr, "token")
            .unwrap()
            .set_variability(sdf::Variability::Uniform)
            .unwrap()
            .set(Value::Token(token.into()))
            .unwrap();
        self
    }

    /// `primvars:NAME` with its interpolation, optional indices and
    /// elementSize.
    fn primvar(
        &self,
        prim: &str,
        name: &str,
        type_name: &str,
        value: Value,
        interpolation: &str,
        (indices, element_size): (Option<Vec<i32>>, Option<i32>),
    ) -> &Author {
        let attr = self
            .stage
            .create_attribute(format!("{prim}.primvars:{name}").as_str(), type_name)
            .unwrap()
            .set(value)
            .unwrap()
            .set_metadata("interpolation", Value::Token(interpolation.into()))
            .unwrap();
        if let Some(n) = element_size {
            attr.set_metadata("elementSize", Value::Int(n)).unwrap();
        }
        if let Some(indices) = indices {
            self.set(
                &format!("{prim}.primvars:{name}:indices"),
                "int[]",
                Value::IntVec(indices),
            );
        }
        self
    }

    /// Writes the layer to `path` (format by extension: usda, usdc, usdz).
    fn export(&self, path: &Path) -> PathBuf {
        self.stage
            .root_layer()
            .export(path.to_str().unwrap())
            .unwrap();
        path.to_path_buf()
    }
}

fn ints(v: &[i32]) -> Value {
    Value::IntVec(v.to_vec())
}

fn floats(v: &[f32]) -> Value {
    Value::FloatVec(v.to_vec())
}

fn points(v: &[[f32; 3]]) -> Value {
    Value::Vec3fVec(v.iter().map(|&p| gf::Vec3f::from(p)).collect())
}

fn uvs(v: &[[f32; 2]]) -> Value {
    Value::Vec2fVec(v.iter().map(|&p| gf::Vec2f::from(p)).collect())
}

fn read(path: &Path) -> UsdStage {
    read_usd(path, &UsdReadOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

// ---------------------------------------------------------------------------
// The test mesh: a 3×3 grid of quads, gently curved.

const N: usize = 4; // vertices per side

fn grid_points() -> Vec<[f32; 3]> {
    let mut p = Vec::new();
    for j in 0..N {
        for i in 0..N {
            let (x, y) = (i as f32, j as f32);
            p.push([x, y, 0.1 * (x * x) - 0.05 * y * x + 0.3]);
        }
    }
    p
}

fn grid_faces() -> (Vec<i32>, Vec<i32>) {
    let mut counts = Vec::new();
    let mut indices = Vec::new();
    for j in 0..N - 1 {
        for i in 0..N - 1 {
            let v = (j * N + i) as i32;
            counts.push(4);
            indices.extend([v, v + 1, v + N as i32 + 1, v + N as i32]);
        }
    }
    (counts, indices)
}

/// The grid at `prim` with only its topology and points authored.
fn author_grid(a: &Author, prim: &str) {
    let (counts, indices) = grid_faces();
    a.def(prim, "Mesh")
        .set(
            &format!("{prim}.points"),
            "point3f[]",
            points(&grid_points()),
        )
        .set(&format!("{prim}.faceVertexCounts"), "int[]", ints(&counts))
        .set(
            &format!("{prim}.faceVertexIndices"),
            "int[]",
            ints(&indices),
        );
}

/// The grid as a `Mesh`, built by hand from the same arrays.
fn grid_mesh() -> Mesh {
    let positions = grid_points()
        .iter()
        .map(|p| DVec3::new(p[0].into(), p[1].into(), p[2].into()))
        .collect();
    let (_, indices) = grid_faces();
    let faces: Vec<Vec<u32>> = indices
        .chunks(4)
        .map(|f| f.iter().map(|&v| v as u32).collect())
        .collect();
    let refs: Vec<&[u32]> = faces.iter().map(|f| &f[..]).collect();
    Mesh::from_faces(positions, &refs)
}

/// USD's fallback options for a Catmull-Clark mesh.
fn usd_defaults() -> Options {
    Options {
        scheme: Scheme::Catmark,
        boundary: BoundaryInterpolation::EdgeAndCorner,
        fvar: FVarLinearInterpolation::CornersPlus1,
        creasing: CreasingMethod::Uniform,
        triangles: TriangleSubdivision::Catmark,
    }
}

// ---------------------------------------------------------------------------

#[test]
fn fallbacks_when_nothing_but_the_topology_is_authored() {
    let dir = scratch("fallbacks");
    let a = Author::new();
    author_grid(&a, "/Grid");
    for ext in ["usda", "usdc", "usdz"] {
        let file = a.export(&dir.join(format!("grid.{ext}")));
        let stage = read(&file);
        assert_eq!(stage.meshes.len(), 1, "{ext}");
        assert!(
            stage.skipped.is_empty() && stage.warnings.is_empty(),
            "{ext}: {stage:?}"
        );
        let m = &stage.meshes[0];
        assert_eq!(m.path, "/Grid");
        assert_eq!(m.mesh, grid_mesh(), "{ext}");
        assert_eq!(m.options, usd_defaults(), "{ext}");
        assert!(m.fvar_names.is_empty() && m.primvars.is_empty());
    }
}

/// The grid with every subdivision attribute and primvar kind authored.
fn author_full(a: &Author, prim: &str) {
    author_grid(a, prim);
    let at = |name: &str| format!("{prim}.{name}");
    a.token(&at("subdivisionScheme"), "catmullClark")
        .token(&at("interpolateBoundary"), "edgeOnly")
        .token(&at("faceVaryingLinearInterpolation"), "cornersOnly")
        .token(&at("triangleSubdivisionRule"), "smooth")
        .token(&at("orientation"), "leftHanded")
        // Not a mesh attribute: ignored, as USD ignores it.
        .token(&at("boundaryInterpolation"), "bogus")
        .set(
            &at("creaseIndices"),
            "int[]",
            ints(&[0, 1, 2, 3, 12, 13, 5, 9]),
        )
        .set(&at("creaseLengths"), "int[]", ints(&[4, 2, 2]))
        // One per crease edge (3 + 1 + 1); negative means smooth (0).
        .set(
            &at("creaseSharpnesses"),
            "float[]",
            floats(&[1.0, 2.0, 3.0, 10.0, -1.0]),
        )
        .set(&at("cornerIndices"), "int[]", ints(&[0, 15]))
        .set(&at("cornerSharpnesses"), "float[]", floats(&[2.5, 4.0]))
        .set(&at("holeIndices"), "int[]", ints(&[4]));
    let (_, indices) = grid_faces();
    let st: Vec<[f32; 2]> = grid_points()
        .iter()
        .map(|p| [p[0] / 3.0, p[1] / 3.0])
        .collect();
    a.primvar(
        prim,
        "st",
        "texCoord2f[]",
        uvs(&st),
        "faceVarying",
        (Some(indices.clone()), None),
    );
    let uv2: Vec<[f32; 2]> = (0..indices.len()).map(|c| [c as f32, 0.5]).collect();
    a.primvar(
        prim,
        "uv2",
        "float2[]",
        uvs(&uv2),
        "faceVarying",
        (None, None),
    );
    let colors = Value::Vec3fVec(vec![gf::vec3f(1.0, 0.0, 0.0), gf::vec3f(0.0, 0.25, 1.0)]);
    let color_of: Vec<i32> = (0..N * N).map(|v| (v % 2) as i32).collect();
    a.primvar(
        prim,
        "displayColor",
        "color3f[]",
        colors,
        "vertex",
        (Some(color_of), None),
    );
    let weights: Vec<f32> = (0..2 * N * N).map(|i| i as f32 * 0.125).collect();
    a.primvar(
        prim,
        "weights",
        "float[]",
        floats(&weights),
        "varying",
        (None, Some(2)),
    );
    a.primvar(
        prim,
        "displayOpacity",
        "float[]",
        floats(&[0.5]),
        "constant",
        (None, None),
    );
    a.primvar(
        prim,
        "faceId",
        "int[]",
        ints(&[0; 9]),
        "uniform",
        (None, None),
    );
    let labels = Value::TokenVec((0..N * N).map(|_| "x".into()).collect());
    a.primvar(prim, "labels", "token[]", labels, "vertex", (None, None));
}

/// What [`author_full`] describes, built by hand.
fn full_mesh() -> (Mesh, Vec<String>, Vec<UsdPrimvar>) {
    let mut mesh = grid_mesh();
    mesh.left_handed = true;
    for (v, s) in [
        ([0, 1], 1.0),
        ([1, 2], 2.0),
        ([2, 3], 3.0),
        ([12, 13], 10.0),
        ([5, 9], 0.0),
    ] {
        mesh.creases.push(Crease {
            vertices: v,
            sharpness: s,
        });
    }
    mesh.corners = vec![
        Corner {
            vertex: 0,
            sharpness: 2.5,
        },
        Corner {
            vertex: 15,
            sharpness: 4.0,
        },
    ];
    mesh.holes = vec![4];
    let st: Vec<f64> = grid_points()
        .iter()
        .flat_map(|p| [f64::from(p[0] / 3.0), f64::from(p[1] / 3.0)])
        .collect();
    mesh.fvar_channels.push(FVarChannel {
        width: 2,
        values: st,
        indices: mesh.face_vertices.clone(),
    });
    let corners = mesh.face_vertices.len();
    mesh.fvar_channels.push(FVarChannel {
        width: 2,
        values: (0..corners).flat_map(|c| [c as f64, 0.5]).collect(),
        indices: (0..corners as u32).collect(),
    });
    let primvars = vec![
        UsdPrimvar {
            name: "displayColor".into(),
            interpolation: UsdInterpolation::Vertex,
            width: 3,
            values: (0..N * N)
                .flat_map(|v| {
                    if v % 2 == 0 {
                        [1.0, 0.0, 0.0]
                    } else {
                        [0.0, 0.25, 1.0]
                    }
                })
                .collect(),
        },
        UsdPrimvar {
            name: "weights".into(),
            interpolation: UsdInterpolation::Varying,
            width: 2,
            values: (0..2 * N * N).map(|i| i as f64 * 0.125).collect(),
        },
    ];
    (mesh, vec!["st".into(), "uv2".into()], primvars)
}

#[test]
fn every_attribute_is_mapped_as_usds_adapter_maps_it() {
    let dir = scratch("every_attribute");
    let a = Author::new();
    a.def("/World", "Xform").def("/World/Geo", "Scope");
    author_full(&a, "/World/Geo/Body");
    let (mesh, fvar_names, primvars) = full_mesh();
    for ext in ["usda", "usdc", "usdz"] {
        let stage = read(&a.export(&dir.join(format!("full.{ext}"))));
        assert_eq!(stage.meshes.len(), 1, "{ext}");
        let m = &stage.meshes[0];
        assert_eq!(m.path, "/World/Geo/Body");
        assert_eq!(m.mesh, mesh, "{ext}");
        assert_eq!(
            m.options,
            Options {
                scheme: Scheme::Catmark,
                boundary: BoundaryInterpolation::EdgeOnly,
                fvar: FVarLinearInterpolation::CornersOnly,
                creasing: CreasingMethod::Uniform,
                triangles: TriangleSubdivision::Smooth,
            },
            "{ext}"
        );
        assert_eq!(m.fvar_names, fvar_names, "{ext}");
        assert_eq!(m.primvars, primvars, "{ext}");
        // The token primvar is the one thing set aside.
        assert_eq!(stage.warnings.len(), 1, "{ext}: {:?}", stage.warnings);
        let w = &stage.warnings[0];
        assert_eq!(
            (w.prim.as_str(), w.attribute.as_str()),
            ("/World/Geo/Body", "primvars:labels")
        );
        assert!(w.to_string().contains("not numbers"), "{w}");
    }
}

#[test]
fn scheme_and_option_tokens() {
    let dir = scratch("tokens");
    let cases: &[(&str, &str, &str, Options)] = &[
        (
            "loop",
            "none",
            "all",
            Options {
                scheme: Scheme::Loop,
                boundary: BoundaryInterpolation::None,
                fvar: FVarLinearInterpolation::All,
                ..usd_defaults()
            },
        ),
        // Bilinear meshes take edge-and-corner boundaries whatever is authored.
        (
            "bilinear",
            "none",
            "boundaries",
            Options {
                scheme: Scheme::Bilinear,
                boundary: BoundaryInterpolation::EdgeAndCorner,
                fvar: FVarLinearInterpolation::Boundaries,
                ..usd_defaults()
            },
        ),
        (
            "catmullClark",
            "edgeAndCorner",
            "cornersPlus2",
            Options {
                fvar: FVarLinearInterpolation::CornersPlus2,
                ..usd_defaults()
            },
        ),
        (
            "catmullClark",
            "edgeOnly",
            "none",
            Options {
                boundary: BoundaryInterpolation::EdgeOnly,
                fvar: FVarLinearInterpolation::None,
                ..usd_defaults()
            },
        ),
        (
            "catmullClark",
            "none",
            "cornersPlus1",
            Options {
                boundary: BoundaryInterpolation::None,
                ..usd_defaults()
            },
        ),
    ];
    for (i, (scheme, boundary, fvar, expected)) in cases.iter().enumerate() {
        let a = Author::new();
        let prim = "/M";
        if *scheme == "loop" {
            // Loop needs triangles: the grid's quads split in two.
            let (_, quads) = grid_faces();
            let tris: Vec<i32> = quads
                .chunks(4)
                .flat_map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]])
                .collect();
            a.def(prim, "Mesh")
                .set("/M.points", "point3f[]", points(&grid_points()))
                .set(
                    "/M.faceVertexCounts",
                    "int[]",
                    ints(&vec![3; tris.len() / 3]),
                )
                .set("/M.faceVertexIndices", "int[]", ints(&tris));
        } else {
            author_grid(&a, prim);
        }
        a.token("/M.subdivisionScheme", scheme)
            .token("/M.interpolateBoundary", boundary)
            .token("/M.faceVaryingLinearInterpolation", fvar);
        let stage = read(&a.export(&dir.join(format!("case{i}.usda"))));
        assert_eq!(stage.meshes[0].options, *expected, "case {i}");
    }
    // Catmull-Clark's triangle rule, and scheme "none": skipped, with why.
    let a = Author::new();
    author_grid(&a, "/Smooth");
    a.token("/Smooth.triangleSubdivisionRule", "smooth");
    author_grid(&a, "/Cage");
    a.token("/Cage.subdivisionScheme", "none");
    let stage = read(&a.export(&dir.join("none.usda")));
    assert_eq!(stage.meshes.len(), 1);
    assert_eq!(
        stage.meshes[0].options.triangles,
        TriangleSubdivision::Smooth
    );
    assert_eq!(stage.skipped.len(), 1);
    assert_eq!(stage.skipped[0].prim, "/Cage");
    assert!(
        stage.skipped[0].reason.contains("none"),
        "{:?}",
        stage.skipped
    );
}

#[test]
fn crease_sharpness_per_crease_or_per_edge() {
    let dir = scratch("crease_sharpness");
    // One per crease: both edges of the first crease take 2.5.
    let a = Author::new();
    author_grid(&a, "/M");
    a.set("/M.creaseIndices", "int[]", ints(&[0, 1, 2, 4, 8]))
        .set("/M.creaseLengths", "int[]", ints(&[3, 2]))
        .set("/M.creaseSharpnesses", "float[]", floats(&[2.5, 7.0]));
    let m = &read(&a.export(&dir.join("per_crease.usdc"))).meshes[0].mesh;
    let edges: Vec<([u32; 2], f32)> = m
        .creases
        .iter()
        .map(|c| (c.vertices, c.sharpness))
        .collect();
    assert_eq!(edges, [([0, 1], 2.5), ([1, 2], 2.5), ([4, 8], 7.0)]);
    // One per edge.
    a.set("/M.creaseSharpnesses", "float[]", floats(&[1.0, 2.0, 3.0]));
    let m = &read(&a.export(&dir.join("per_edge.usdc"))).meshes[0].mesh;
    let edges: Vec<([u32; 2], f32)> = m
        .creases
        .iter()
        .map(|c| (c.vertices, c.sharpness))
        .collect();
    assert_eq!(edges, [([0, 1], 1.0), ([1, 2], 2.0), ([4, 8], 3.0)]);
}

#[test]
fn channel_zero_is_st_or_the_only_two_component_face_varying_primvar() {
    let dir = scratch("channel_zero");
    let (_, indices) = grid_faces();
    let corners = indices.len();
    let two: Vec<[f32; 2]> = (0..corners).map(|c| [c as f32, 1.0]).collect();
    let three = Value::Vec3fVec(
        (0..corners)
            .map(|c| gf::vec3f(c as f32, 0.0, 2.0))
            .collect(),
    );
    // Pixar's own files: `st_faceVarying`, with a wider primvar sorting first.
    let a = Author::new();
    author_grid(&a, "/M");
    a.primvar(
        "/M",
        "a3",
        "float3[]",
        three.clone(),
        "faceVarying",
        (None, None),
    )
    .primvar(
        "/M",
        "st_faceVarying",
        "texCoord2f[]",
        uvs(&two),
        "faceVarying",
        (None, None),
    );
    let m = &read(&a.export(&dir.join("st_facevarying.usda"))).meshes[0];
    assert_eq!(m.fvar_names, ["st_faceVarying", "a3"]);
    assert_eq!(m.mesh.fvar_channels[0].width, 2);
    assert_eq!(m.mesh.fvar_channels[1].width, 3);
    // Two two-component primvars and no `st`: by name.
    a.primvar(
        "/M",
        "b2",
        "float2[]",
        uvs(&two),
        "faceVarying",
        (None, None),
    );
    let m = &read(&a.export(&dir.join("two.usda"))).meshes[0];
    assert_eq!(m.fvar_names, ["a3", "b2", "st_faceVarying"]);
    // `st` first whatever else there is, even a vertex-interpolated `st` elsewhere.
    a.primvar(
        "/M",
        "st",
        "texCoord2f[]",
        uvs(&two),
        "faceVarying",
        (None, None),
    );
    let m = &read(&a.export(&dir.join("st.usda"))).meshes[0];
    assert_eq!(m.fvar_names, ["st", "a3", "b2", "st_faceVarying"]);
}

/// Stages covering the schemes, orientations, creases, corners, holes and
/// face-varying channels, read back.
fn sample_meshes(dir: &Path) -> Vec<subdiv::io::UsdMesh> {
    let a = Author::new();
    a.def("/World", "Xform");
    author_full(&a, "/World/Full");
    author_full(&a, "/World/Right");
    a.token("/World/Right.orientation", "rightHanded")
        .token("/World/Right.interpolateBoundary", "none")
        .token(
            "/World/Right.faceVaryingLinearInterpolation",
            "cornersPlus1",
        );
    author_full(&a, "/World/Bilinear");
    a.token("/World/Bilinear.subdivisionScheme", "bilinear");
    let (_, quads) = grid_faces();
    let tris: Vec<i32> = quads
        .chunks(4)
        .flat_map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]])
        .collect();
    a.def("/World/Loop", "Mesh")
        .set("/World/Loop.points", "point3f[]", points(&grid_points()))
        .set(
            "/World/Loop.faceVertexCounts",
            "int[]",
            ints(&vec![3; tris.len() / 3]),
        )
        .set("/World/Loop.faceVertexIndices", "int[]", ints(&tris))
        .token("/World/Loop.subdivisionScheme", "loop")
        .token("/World/Loop.orientation", "leftHanded")
        .set("/World/Loop.creaseIndices", "int[]", ints(&[0, 1, 2]))
        .set("/World/Loop.creaseLengths", "int[]", ints(&[3]))
        .set("/World/Loop.creaseSharpnesses", "float[]", floats(&[1.5]))
        .primvar(
            "/World/Loop",
            "st",
            "texCoord2f[]",
            uvs(&grid_points()
                .iter()
                .map(|p| [p[0], p[1]])
                .collect::<Vec<_>>()),
            "faceVarying",
            (Some(tris.clone()), None),
        );
    let stage = read(&a.export(&dir.join("samples.usdc")));
    assert_eq!(stage.meshes.len(), 4);
    stage.meshes
}

#[cfg(feature = "osd")]
#[test]
fn both_engines_refine_every_read_mesh_alike() {
    let dir = scratch("engines");
    for m in sample_meshes(&dir) {
        for level in 1..=3 {
            let request = Request::new(level);
            let native = Engine::Native.refine(&m.mesh, &m.options, request).unwrap();
            let osd = Engine::Osd.refine(&m.mesh, &m.options, request).unwrap();
            assert_eq!(native, osd, "{} level {level}", m.path);
        }
    }
}

/// The same mesh as an OBJ shape file with its `t` tags, read back, refines
/// to the identical positions, faces and UVs (channel 0: OBJ carries no
/// other).
#[test]
fn the_same_mesh_written_as_obj_refines_identically() {
    let dir = scratch("obj");
    for m in sample_meshes(&dir) {
        let obj = dir.join(format!("{}.obj", &m.path[7..]));
        subdiv::io::write_mesh_obj(&obj, &m.mesh, Precision::F64).unwrap();
        let shape = subdiv::io::read_obj(&obj).unwrap();
        let mut engines = vec![Engine::Native];
        if cfg!(feature = "osd") {
            engines.push(Engine::Osd);
        }
        for engine in engines {
            let request = Request::new(2);
            let usd = engine.refine(&m.mesh, &m.options, request).unwrap();
            let obj = engine.refine(&shape.mesh, &m.options, request).unwrap();
            assert_eq!(usd.positions, obj.positions, "{} {engine:?}", m.path);
            for (u, o) in usd.levels.iter().zip(&obj.levels) {
                assert_eq!(u.face_vertices, o.face_vertices, "{}", m.path);
                assert_eq!(u.face_holes, o.face_holes, "{}", m.path);
                assert_eq!(u.fvar[0], o.fvar[0], "{}", m.path);
            }
            for (u, o) in usd.fvar_values.iter().zip(&obj.fvar_values) {
                assert_eq!(u[0], o[0], "{}", m.path);
            }
        }
    }
}

/// `orientation = "leftHanded"` reads each face from its first corner
/// backwards, as OpenSubdiv's `isLeftHanded` does: the grid authored with
/// its faces (and UV indices) listed clockwise refines exactly as the grid
/// listed counter-clockwise — in both engines, which agree.
#[test]
fn left_handed_faces_are_read_backwards() {
    let dir = scratch("left_handed");
    let a = Author::new();
    author_full(&a, "/Ccw");
    a.token("/Ccw.orientation", "rightHanded");
    author_full(&a, "/Cw");
    let (_, indices) = grid_faces();
    let clockwise: Vec<i32> = indices
        .chunks(4)
        .flat_map(|f| [f[0], f[3], f[2], f[1]])
        .collect();
    a.set("/Cw.faceVertexIndices", "int[]", ints(&clockwise))
        .set("/Cw.primvars:st:indices", "int[]", ints(&clockwise));
    let stage = read(&a.export(&dir.join("orientation.usda")));
    let (ccw, cw) = (&stage.meshes[0], &stage.meshes[1]);
    assert!(!ccw.mesh.left_handed && cw.mesh.left_handed);
    assert_eq!(cw.mesh.right_handed().face_vertices, ccw.mesh.face_vertices);
    let mut engines = vec![Engine::Native];
    if cfg!(feature = "osd") {
        engines.push(Engine::Osd);
    }
    let mut results = Vec::new();
    for engine in engines {
        for m in [ccw, cw] {
            // The second UV channel is per corner, numbered in file order:
            // compare positions, topology and `st` only.
            let r = engine
                .refine(&m.mesh, &ccw.options, Request::new(2))
                .unwrap();
            results.push((engine, r));
        }
    }
    let (_, first) = &results[0];
    for (engine, r) in &results[1..] {
        assert_eq!(r.positions, first.positions, "{engine:?}");
        assert_eq!(r.levels[2].face_vertices, first.levels[2].face_vertices);
        assert_eq!(r.levels[2].fvar[0], first.levels[2].fvar[0]);
        assert_eq!(r.fvar_values[2][0], first.fvar_values[2][0]);
    }
}

/// The grid's arrays as `.usda` text: `(points, counts, indices)`.
fn grid_text() -> (String, String, String) {
    let list = |v: Vec<String>| format!("[{}]", v.join(", "));
    let pts = grid_points()
        .iter()
        .map(|p| format!("({:?}, {:?}, {:?})", p[0], p[1], p[2]))
        .collect();
    let (counts, indices) = grid_faces();
    (
        list(pts),
        list(counts.iter().map(|c| c.to_string()).collect()),
        list(indices.iter().map(|c| c.to_string()).collect()),
    )
}

/// Sdf's legacy type names, which Pixar's parser accepts and the `openusd`
/// crate's does not, read as their current names — in a plain layer, in a
/// layer it references and in a `.usdz` package — and in a binary layer.
#[test]
fn legacy_type_names_are_read() {
    let dir = scratch("legacy");
    let (pts, counts, indices) = grid_text();
    let colors: Vec<String> = (0..N * N).map(|v| format!("({v}, 0.5, 1)")).collect();
    let old = format!(
        "#usda 1.0\n(\n    defaultPrim = \"Old\"\n)\n\ndef Mesh \"Old\"\n{{\n    \
         PointFloat[] points = {pts}\n    int[] faceVertexCounts = {counts}\n    \
         PointIndex[] faceVertexIndices = {indices}\n    \
         ColorFloat[] primvars:displayColor = [{}] (\n        interpolation = \"vertex\"\n    )\n    \
         Vec3f[] primvars:offset = [{}] (\n        interpolation = \"varying\"\n    )\n    \
         PointIndex[] cornerIndices = [0, 3]\n    float[] cornerSharpnesses = [inf, 1e30]\n}}\n",
        colors.join(", "),
        colors.join(", "),
    );
    // The crate's own parser refuses the file as it is.
    assert!(openusd::usda::parse(&old).is_err());
    let file = support::write(&dir, "old.usda", &old);
    let referencing = support::write(
        &dir,
        "scene.usda",
        "#usda 1.0\ndef Xform \"World\"\n{\n    def \"Asset\" (\n        references = @./old.usda@\n    )\n    {\n    }\n}\n",
    );
    let usdz = dir.join("old.usdz");
    {
        let mut archive = openusd::usdz::ArchiveWriter::create(&usdz).unwrap();
        archive.add_layer("old.usda", old.as_bytes()).unwrap();
        archive.finish().unwrap();
    }
    let mut expected = grid_mesh();
    // +inf is OpenSubdiv's infinitely sharp (10); 1e30 is kept as it is.
    expected.corners = vec![
        Corner {
            vertex: 0,
            sharpness: 10.0,
        },
        Corner {
            vertex: 3,
            sharpness: 1e30,
        },
    ];
    let rgb: Vec<f64> = (0..N * N).flat_map(|v| [v as f64, 0.5, 1.0]).collect();
    // In a binary layer the type names are only names: the values are typed.
    let binary = Author::new();
    let (counts, indices) = grid_faces();
    let colors = Value::Vec3fVec((0..N * N).map(|v| gf::vec3f(v as f32, 0.5, 1.0)).collect());
    binary
        .def("/Old", "Mesh")
        .set("/Old.points", "PointFloat[]", points(&grid_points()))
        .set("/Old.faceVertexCounts", "int[]", ints(&counts))
        .set("/Old.faceVertexIndices", "PointIndex[]", ints(&indices))
        .set("/Old.cornerIndices", "PointIndex[]", ints(&[0, 3]))
        .set(
            "/Old.cornerSharpnesses",
            "float[]",
            floats(&[f32::INFINITY, 1e30]),
        )
        .primvar(
            "/Old",
            "displayColor",
            "ColorFloat[]",
            colors.clone(),
            "vertex",
            (None, None),
        )
        .primvar("/Old", "offset", "Vec3f[]", colors, "varying", (None, None));
    let crate_file = binary.export(&dir.join("old.usdc"));
    for (path, prim) in [
        (&file, "/Old"),
        (&referencing, "/World/Asset"),
        (&usdz, "/Old"),
        (&crate_file, "/Old"),
    ] {
        let stage = read(path);
        let m = &stage.meshes[0];
        assert_eq!(m.path, prim);
        assert_eq!(m.mesh, expected, "{}", path.display());
        assert_eq!(m.primvars.len(), 2);
        assert_eq!(m.primvars[0].name, "displayColor");
        assert_eq!(m.primvars[0].values, rgb);
        assert_eq!(m.primvars[1].name, "offset");
        assert_eq!(m.primvars[1].interpolation, UsdInterpolation::Varying);
        assert_eq!(m.primvars[1].values, rgb);
    }
}

/// Composition as the crate resolves it: references, payloads, inherits
/// from a class, variant selections, instances; `class` prims, inactive
/// prims and prims under an `over` are not read.
#[test]
fn composed_stages() {
    let dir = scratch("composition");
    let asset = Author::new();
    asset.def("/Asset", "Xform");
    author_grid(&asset, "/Asset/Body");
    asset.stage.set_default_prim("Asset").unwrap();
    asset.export(&dir.join("asset.usdc"));
    let payload = Author::new();
    payload.def("/Thing", "Xform");
    author_grid(&payload, "/Thing/Part");
    payload.token("/Thing/Part.subdivisionScheme", "bilinear");
    payload.export(&dir.join("payload.usda"));
    let (pts, counts, indices) = grid_text();
    let grid = format!(
        "point3f[] points = {pts}\n        int[] faceVertexCounts = {counts}\n        \
         int[] faceVertexIndices = {indices}"
    );
    let scene = format!(
        r#"#usda 1.0
class "_Sharp"
{{
    uniform token interpolateBoundary = "edgeOnly"
    int[] cornerIndices = [5]
    float[] cornerSharpnesses = [3]
}}

class Mesh "Proto"
{{
    {grid}
}}

def Xform "World"
{{
    def "Ref" (
        references = @./asset.usdc@
    )
    {{
    }}

    def "Pay" (
        payload = @./payload.usda@</Thing>
    )
    {{
    }}

    def Mesh "Inherits" (
        inherits = </_Sharp>
    )
    {{
        {grid}
    }}

    def "Choice" (
        variants = {{
            string shape = "loose"
        }}
        prepend variantSets = "shape"
    )
    {{
        variantSet "shape" = {{
            "tight" {{
                def Mesh "Tight"
                {{
                    {grid}
                }}
            }}
            "loose" {{
                def Mesh "Loose"
                {{
                    {grid}
                    uniform token interpolateBoundary = "none"
                }}
            }}
        }}
    }}

    def "Instance" (
        instanceable = true
        references = @./asset.usdc@
    )
    {{
    }}

    def Mesh "Off" (
        active = false
    )
    {{
        {grid}
    }}

    over "Ghost"
    {{
        def Mesh "Under"
        {{
            {grid}
        }}
    }}
}}
"#
    );
    let file = support::write(&dir, "scene.usda", &scene);
    let stage = read(&file);
    let paths: Vec<&str> = stage.meshes.iter().map(|m| m.path.as_str()).collect();
    assert_eq!(
        paths,
        [
            "/World/Ref/Body",
            "/World/Pay/Part",
            "/World/Inherits",
            "/World/Choice/Loose",
            "/World/Instance/Body",
        ]
    );
    for m in &stage.meshes {
        let mut expected = grid_mesh();
        if m.path == "/World/Inherits" {
            expected.corners = vec![Corner {
                vertex: 5,
                sharpness: 3.0,
            }];
        }
        assert_eq!(m.mesh, expected, "{}", m.path);
    }
    let option = |i: usize| stage.meshes[i].options;
    assert_eq!(option(0), usd_defaults());
    assert_eq!(option(1).scheme, Scheme::Bilinear);
    assert_eq!(option(2).boundary, BoundaryInterpolation::EdgeOnly);
    assert_eq!(option(3).boundary, BoundaryInterpolation::None);
    assert!(stage.warnings.is_empty(), "{:?}", stage.warnings);
}

/// Values at a time as USD resolves them: the sample there, the first or
/// last one outside their range, and between two samples floating-point
/// arrays interpolated as `GfLerp` does (a `float3` term by term in
/// `float`, a `float` in `double` rounded once), integers held; without a
/// time the default value, and an attribute with samples only has none.
#[test]
fn time_samples_as_usd_resolves_them() {
    let dir = scratch("time");
    let a = Author::new();
    author_grid(&a, "/M");
    let lifted = |dz: f32| {
        let p: Vec<[f32; 3]> = grid_points()
            .iter()
            .map(|p| [p[0], p[1], p[2] + dz])
            .collect();
        points(&p)
    };
    a.sample("/M.points", "point3f[]", 1.0, lifted(1.0))
        .sample("/M.points", "point3f[]", 3.0, lifted(3.0))
        .sample("/M.cornerIndices", "int[]", 2.0, ints(&[7]))
        .sample("/M.cornerIndices", "int[]", 4.0, ints(&[8]))
        .sample("/M.cornerSharpnesses", "float[]", 2.0, floats(&[4.0]))
        .sample("/M.cornerSharpnesses", "float[]", 4.0, floats(&[5.0]));
    let file = a.export(&dir.join("animated.usda"));
    let z = |stage: &UsdStage| stage.meshes[0].mesh.positions[0].z;
    let z0 = grid_points()[0][2];
    let corners = |stage: &UsdStage| -> Vec<(u32, f32)> {
        stage.meshes[0]
            .mesh
            .corners
            .iter()
            .map(|c| (c.vertex, c.sharpness))
            .collect()
    };
    let at = |file: &Path, time: Option<f64>| {
        read_usd(
            file,
            &UsdReadOptions {
                time,
                ..UsdReadOptions::default()
            },
        )
    };
    let stage = at(&file, None).unwrap();
    assert_eq!(z(&stage), f64::from(z0));
    assert_eq!(corners(&stage), []);
    let attributes: Vec<&str> = stage
        .warnings
        .iter()
        .map(|w| w.attribute.as_str())
        .collect();
    assert_eq!(attributes, ["cornerIndices", "cornerSharpnesses"]);
    assert!(
        stage.warnings[1].message.contains("no default value"),
        "{}",
        stage.warnings[1]
    );
    // GfLerp on a GfVec3f: each term rounded to float, then added in float.
    let vec3f = |a: f32, b: f32, alpha: f64| {
        f64::from((f64::from(a) * (1.0 - alpha)) as f32 + (f64::from(b) * alpha) as f32)
    };
    let between = vec3f(z0 + 1.0, z0 + 3.0, 0.75);
    for (time, z_expected, corner) in [
        (0.0, f64::from(z0 + 1.0), (7, 4.0)),
        (1.0, f64::from(z0 + 1.0), (7, 4.0)),
        (2.5, between, (7, 4.25)),
        (3.0, f64::from(z0 + 3.0), (7, 4.5)),
        (3.1, f64::from(z0 + 3.0), (7, 4.55)),
        (4.0, f64::from(z0 + 3.0), (8, 5.0)),
        (9.0, f64::from(z0 + 3.0), (8, 5.0)),
    ] {
        let stage = at(&file, Some(time)).unwrap();
        assert_eq!(z(&stage), z_expected, "time {time}");
        assert_eq!(corners(&stage), [corner], "time {time}");
        assert!(stage.warnings.is_empty());
    }
    // Points with samples only: none at the default time.
    let a = Author::new();
    author_grid(&a, "/M");
    let b = Author::new();
    let (counts, indices) = grid_faces();
    b.def("/M", "Mesh")
        .set("/M.faceVertexCounts", "int[]", ints(&counts))
        .set("/M.faceVertexIndices", "int[]", ints(&indices))
        .sample("/M.points", "point3f[]", 1.0, lifted(1.0));
    let file = b.export(&dir.join("sampled_points.usda"));
    let e = usd_error(&file, &UsdReadOptions::default());
    assert!(
        matches!(
            e.kind,
            UsdErrorKind::Missing {
                faces: 9,
                time_samples: true
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("read at a time"), "{e}");
    assert_eq!(z(&at(&file, Some(5.0)).unwrap()), f64::from(z0 + 1.0));
    let e = usd_error(
        &file,
        &UsdReadOptions {
            time: Some(f64::NAN),
            ..UsdReadOptions::default()
        },
    );
    assert!(matches!(e.kind, UsdErrorKind::Open(_)), "{e}");
}

// ---------------------------------------------------------------------------
// Malformed attributes.

/// Reads `file` and returns its `UsdError`, checking that the message
/// names the file, the prim and the attribute.
fn usd_error(file: &Path, options: &UsdReadOptions) -> UsdError {
    match read_usd(file, options) {
        Err(Error::Usd(e)) => {
            let message = e.to_string();
            assert!(
                message.starts_with(&file.display().to_string()),
                "{message}"
            );
            let place = match (e.prim.is_empty(), e.attribute.is_empty()) {
                (false, false) => format!(": {}.{}: ", e.prim, e.attribute),
                (false, true) => format!(": {}: ", e.prim),
                _ => ": ".to_string(),
            };
            assert!(message.contains(&place), "{message}");
            *e
        }
        other => panic!("{}: expected a USD error, got {other:?}", file.display()),
    }
}

/// The full grid at `/M` with one attribute changed by `edit`.
fn malformed(dir: &Path, name: &str, edit: impl FnOnce(&Author)) -> PathBuf {
    let a = Author::new();
    author_full(&a, "/M");
    edit(&a);
    a.export(&dir.join(format!("{name}.usda")))
}

#[test]
fn malformed_attributes_give_typed_errors_naming_prim_and_attribute() {
    use UsdErrorKind as K;
    let dir = scratch("malformed");
    let (counts, indices) = grid_faces();
    let with = |i: usize, v: i32| {
        let mut x = indices.clone();
        x[i] = v;
        ints(&x)
    };
    type Check = fn(&UsdErrorKind) -> bool;
    type Case<'a> = (
        &'static str,
        Box<dyn FnOnce(&Author) + 'a>,
        &'static str,
        Check,
    );
    let cases: Vec<Case<'_>> = vec![
        (
            "face_vertex_out_of_range",
            Box::new(|a| {
                a.set("/M.faceVertexIndices", "int[]", with(5, 16));
            }),
            "faceVertexIndices",
            |k| {
                matches!(
                    k,
                    K::IndexOutOfRange {
                        position: 5,
                        index: 16,
                        count: 16,
                        of: "points"
                    }
                )
            },
        ),
        (
            "face_vertex_negative",
            Box::new(|a| {
                a.set("/M.faceVertexIndices", "int[]", with(0, -1));
            }),
            "faceVertexIndices",
            |k| {
                matches!(
                    k,
                    K::IndexOutOfRange {
                        position: 0,
                        index: -1,
                        ..
                    }
                )
            },
        ),
        (
            "counts_do_not_sum",
            Box::new(|a| {
                a.set("/M.faceVertexCounts", "int[]", ints(&[4; 8]));
            }),
            "faceVertexCounts",
            |k| {
                matches!(
                    k,
                    K::FaceVertexCounts {
                        sum: 32,
                        indices: 36
                    }
                )
            },
        ),
        (
            "negative_count",
            Box::new(|a| {
                a.set(
                    "/M.faceVertexCounts",
                    "int[]",
                    ints(&[4, 4, 4, 4, -4, 4, 4, 4, 12]),
                );
            }),
            "faceVertexCounts",
            |k| {
                matches!(
                    k,
                    K::NegativeCount {
                        position: 4,
                        count: -4
                    }
                )
            },
        ),
        (
            "face_of_two",
            Box::new(|a| {
                a.set(
                    "/M.faceVertexCounts",
                    "int[]",
                    ints(&[4, 4, 4, 4, 4, 4, 4, 4, 2, 2]),
                );
            }),
            "faceVertexCounts",
            |k| matches!(k, K::Mesh(MeshError::FaceTooSmall { face: 8, size: 2 })),
        ),
        (
            "crease_index_out_of_range",
            Box::new(|a| {
                a.set(
                    "/M.creaseIndices",
                    "int[]",
                    ints(&[0, 1, 2, 3, 12, 13, 5, 99]),
                );
            }),
            "creaseIndices",
            |k| {
                matches!(
                    k,
                    K::IndexOutOfRange {
                        position: 7,
                        index: 99,
                        count: 16,
                        ..
                    }
                )
            },
        ),
        (
            "crease_lengths_do_not_sum",
            Box::new(|a| {
                a.set("/M.creaseLengths", "int[]", ints(&[4, 2, 3]));
            }),
            "creaseLengths",
            |k| matches!(k, K::CreaseLengths { sum: 9, indices: 8 }),
        ),
        (
            "crease_length_negative",
            Box::new(|a| {
                a.set("/M.creaseLengths", "int[]", ints(&[4, -2, 6]));
            }),
            "creaseLengths",
            |k| {
                matches!(
                    k,
                    K::NegativeCount {
                        position: 1,
                        count: -2
                    }
                )
            },
        ),
        (
            "crease_of_one_vertex",
            Box::new(|a| {
                a.set("/M.creaseLengths", "int[]", ints(&[4, 2, 1, 1])).set(
                    "/M.creaseSharpnesses",
                    "float[]",
                    floats(&[1.0, 2.0, 3.0, 4.0]),
                );
            }),
            "creaseLengths",
            |k| {
                matches!(
                    k,
                    K::CreaseTooShort {
                        crease: 2,
                        length: 1
                    }
                )
            },
        ),
        (
            "crease_sharpness_count",
            Box::new(|a| {
                a.set("/M.creaseSharpnesses", "float[]", floats(&[1.0, 2.0]));
            }),
            "creaseSharpnesses",
            |k| {
                matches!(
                    k,
                    K::CreaseSharpnessCount {
                        found: 2,
                        creases: 3,
                        edges: 5
                    }
                )
            },
        ),
        (
            "corner_index_out_of_range",
            Box::new(|a| {
                a.set("/M.cornerIndices", "int[]", ints(&[0, 16]));
            }),
            "cornerIndices",
            |k| {
                matches!(
                    k,
                    K::IndexOutOfRange {
                        position: 1,
                        index: 16,
                        ..
                    }
                )
            },
        ),
        (
            "corner_sharpness_count",
            Box::new(|a| {
                a.set("/M.cornerSharpnesses", "float[]", floats(&[1.0]));
            }),
            "cornerSharpnesses",
            |k| {
                matches!(
                    k,
                    K::CornerSharpnessCount {
                        found: 1,
                        corners: 2
                    }
                )
            },
        ),
        (
            "hole_out_of_range",
            Box::new(|a| {
                a.set("/M.holeIndices", "int[]", ints(&[9]));
            }),
            "holeIndices",
            |k| {
                matches!(
                    k,
                    K::IndexOutOfRange {
                        position: 0,
                        index: 9,
                        count: 9,
                        of: "faces"
                    }
                )
            },
        ),
        (
            "primvar_index_out_of_range",
            Box::new(|a| {
                a.set("/M.primvars:st:indices", "int[]", with(35, 16));
            }),
            "primvars:st:indices",
            |k| {
                matches!(
                    k,
                    K::IndexOutOfRange {
                        position: 35,
                        index: 16,
                        count: 16,
                        of: "values"
                    }
                )
            },
        ),
        (
            "face_varying_count",
            Box::new(|a| {
                let v: Vec<[f32; 2]> = (0..35).map(|c| [c as f32, 0.0]).collect();
                a.set("/M.primvars:uv2", "float2[]", uvs(&v));
            }),
            "primvars:uv2",
            |k| {
                matches!(
                    k,
                    K::PrimvarCount {
                        interpolation: "faceVarying",
                        found: 35,
                        expected: 36
                    }
                )
            },
        ),
        (
            "vertex_indices_count",
            Box::new(|a| {
                a.set("/M.primvars:displayColor:indices", "int[]", ints(&[0; 15]));
            }),
            "primvars:displayColor:indices",
            |k| {
                matches!(
                    k,
                    K::PrimvarCount {
                        interpolation: "vertex",
                        found: 15,
                        expected: 16
                    }
                )
            },
        ),
        (
            "element_size",
            Box::new(|a| {
                a.stage
                    .attribute("/M.primvars:weights")
                    .set_metadata("elementSize", Value::Int(3))
                    .unwrap();
            }),
            "primvars:weights",
            |k| {
                matches!(
                    k,
                    K::ElementSize {
                        element_size: 3,
                        values: 32
                    }
                )
            },
        ),
        (
            "unknown_interpolation",
            Box::new(|a| {
                a.stage
                    .attribute("/M.primvars:weights")
                    .set_metadata("interpolation", Value::Token("perPoint".into()))
                    .unwrap();
            }),
            "primvars:weights",
            |k| matches!(k, K::UnknownToken { token, .. } if token == "perPoint"),
        ),
        (
            "unknown_scheme",
            Box::new(|a| {
                a.token("/M.subdivisionScheme", "catmark");
            }),
            "subdivisionScheme",
            |k| matches!(k, K::UnknownToken { token, .. } if token == "catmark"),
        ),
        (
            "unknown_boundary",
            Box::new(|a| {
                a.token("/M.interpolateBoundary", "edgeAndCorners");
            }),
            "interpolateBoundary",
            |k| matches!(k, K::UnknownToken { .. }),
        ),
        (
            "unknown_fvar",
            Box::new(|a| {
                a.token("/M.faceVaryingLinearInterpolation", "cornersPlus3");
            }),
            "faceVaryingLinearInterpolation",
            |k| matches!(k, K::UnknownToken { .. }),
        ),
        (
            "unknown_triangles",
            Box::new(|a| {
                a.token("/M.triangleSubdivisionRule", "loop");
            }),
            "triangleSubdivisionRule",
            |k| matches!(k, K::UnknownToken { .. }),
        ),
        (
            "unknown_orientation",
            Box::new(|a| {
                a.token("/M.orientation", "clockwise");
            }),
            "orientation",
            |k| matches!(k, K::UnknownToken { .. }),
        ),
        (
            "wrong_type",
            Box::new(|a| {
                a.set("/M.faceVertexIndices", "float[]", floats(&[0.0; 36]));
            }),
            "faceVertexIndices",
            |k| matches!(k, K::WrongType { expected: "int[]", found } if found == "FloatVec"),
        ),
        (
            "non_finite_point",
            Box::new(|a| {
                let mut p = grid_points();
                p[3][1] = f32::NAN;
                a.set("/M.points", "point3f[]", points(&p));
            }),
            "points",
            |k| matches!(k, K::Mesh(MeshError::NonFiniteCoordinate { vertex: 3, .. })),
        ),
    ];
    let count = cases.len();
    for (name, edit, attribute, check) in cases {
        let file = malformed(&dir, name, edit);
        let e = usd_error(&file, &UsdReadOptions::default());
        assert_eq!(
            (e.prim.as_str(), e.attribute.as_str()),
            ("/M", attribute),
            "{name}: {e}"
        );
        assert!(check(&e.kind), "{name}: {e}");
        // Lenient mode forgives creases and corners only.
        let lenient = UsdReadOptions {
            lenient: true,
            ..UsdReadOptions::default()
        };
        let forgiven = attribute.starts_with("crease") || attribute.starts_with("corner");
        assert_eq!(read_usd(&file, &lenient).is_ok(), forgiven, "{name}");
    }
    assert_eq!(count, 25);
    // A mesh without points.
    let a = Author::new();
    let (counts_only, indices_only) = (ints(&counts), ints(&indices));
    a.def("/P", "Mesh")
        .set("/P.faceVertexCounts", "int[]", counts_only)
        .set("/P.faceVertexIndices", "int[]", indices_only);
    let e = usd_error(
        &a.export(&dir.join("no_points.usda")),
        &UsdReadOptions::default(),
    );
    assert_eq!(e.attribute, "points");
    assert!(
        matches!(
            e.kind,
            K::Missing {
                faces: 9,
                time_samples: false
            }
        ),
        "{e}"
    );
}

#[test]
fn lenient_mode_drops_malformed_creases_and_corners_with_warnings() {
    let dir = scratch("lenient");
    let lenient = UsdReadOptions {
        lenient: true,
        ..UsdReadOptions::default()
    };
    let (full, _, _) = full_mesh();
    let read_lenient = |file: &Path| {
        let stage = read_usd(file, &lenient).unwrap();
        let m = stage.meshes[0].mesh.clone();
        let warned: Vec<(String, String)> = stage
            .warnings
            .iter()
            .filter(|w| w.attribute != "primvars:labels")
            .map(|w| (w.prim.clone(), w.attribute.clone()))
            .collect();
        (m, warned, stage.warnings)
    };
    let at = |attribute: &str| vec![("/M".to_string(), attribute.to_string())];
    // An edge whose vertex does not exist: that edge goes (pxOsd skips it).
    let file = malformed(&dir, "crease_index", |a| {
        a.set(
            "/M.creaseIndices",
            "int[]",
            ints(&[0, 1, 2, 3, 12, 13, 5, 99]),
        );
    });
    let (m, warned, warnings) = read_lenient(&file);
    assert_eq!(m.creases, full.creases[..4]);
    assert_eq!(warned, at("creaseIndices"));
    assert!(
        warnings.iter().any(|w| w.message.contains("dropped")),
        "{warnings:?}"
    );
    // Sharpnesses that fit neither count: every crease goes, as in pxOsd.
    let file = malformed(&dir, "crease_sharpness", |a| {
        a.set("/M.creaseSharpnesses", "float[]", floats(&[1.0, 2.0]));
    });
    let (m, warned, _) = read_lenient(&file);
    assert!(m.creases.is_empty());
    assert_eq!(m.corners, full.corners);
    assert_eq!(warned, at("creaseSharpnesses"));
    // Lengths that do not add up: every crease goes.
    let file = malformed(&dir, "crease_lengths", |a| {
        a.set("/M.creaseLengths", "int[]", ints(&[4, 2, 3]));
    });
    let (m, warned, _) = read_lenient(&file);
    assert!(m.creases.is_empty());
    assert_eq!(warned, at("creaseLengths"));
    // A crease of one vertex: that crease goes (it has no edge).
    let file = malformed(&dir, "crease_short", |a| {
        a.set(
            "/M.creaseIndices",
            "int[]",
            ints(&[0, 1, 2, 3, 12, 13, 5, 9, 10]),
        )
        .set("/M.creaseLengths", "int[]", ints(&[4, 2, 1, 2]))
        .set(
            "/M.creaseSharpnesses",
            "float[]",
            floats(&[1.0, 2.0, 9.0, 3.0]),
        );
    });
    let (m, warned, _) = read_lenient(&file);
    let edges: Vec<([u32; 2], f32)> = m
        .creases
        .iter()
        .map(|c| (c.vertices, c.sharpness))
        .collect();
    assert_eq!(
        edges,
        [
            ([0, 1], 1.0),
            ([1, 2], 1.0),
            ([2, 3], 1.0),
            ([12, 13], 2.0),
            ([9, 10], 3.0)
        ]
    );
    assert_eq!(warned, at("creaseLengths"));
    // A corner whose vertex does not exist goes; one whose sharpnesses do
    // not match: every corner goes.
    let file = malformed(&dir, "corner_index", |a| {
        a.set("/M.cornerIndices", "int[]", ints(&[0, -3]));
    });
    let (m, warned, _) = read_lenient(&file);
    assert_eq!(m.corners, full.corners[..1]);
    assert_eq!(m.creases, full.creases);
    assert_eq!(warned, at("cornerIndices"));
    let file = malformed(&dir, "corner_sharpness", |a| {
        a.set("/M.cornerSharpnesses", "float[]", floats(&[1.0, 2.0, 3.0]));
    });
    let (m, warned, _) = read_lenient(&file);
    assert!(m.corners.is_empty());
    assert_eq!(warned, at("cornerSharpnesses"));
    // A crease between points that share no edge is kept and warned about
    // in either mode (OpenSubdiv ignores it).
    let file = malformed(&dir, "no_edge", |a| {
        a.set(
            "/M.creaseIndices",
            "int[]",
            ints(&[0, 1, 2, 3, 12, 13, 5, 10]),
        );
    });
    for options in [UsdReadOptions::default(), lenient.clone()] {
        let stage = read_usd(&file, &options).unwrap();
        assert_eq!(stage.meshes[0].mesh.creases.len(), 5);
        assert!(
            stage
                .warnings
                .iter()
                .any(|w| w.attribute == "creaseIndices" && w.message.contains("share no edge")),
            "{:?}",
            stage.warnings
        );
    }
}

#[test]
fn prim_patterns_select_meshes() {
    let dir = scratch("patterns");
    let a = Author::new();
    a.def("/World", "Xform")
        .def("/World/A", "Xform")
        .def("/World/B", "Xform");
    for prim in ["/World/A/Body", "/World/B/Body", "/World/B/Arm", "/Other"] {
        author_grid(&a, prim);
    }
    // A malformed mesh no pattern selects is never read.
    author_grid(&a, "/World/Bad");
    a.token("/World/Bad.subdivisionScheme", "wobbly");
    let file = a.export(&dir.join("patterns.usda"));
    let select = |patterns: &[&str]| {
        let options = UsdReadOptions {
            prims: patterns.iter().map(|p| p.to_string()).collect(),
            ..UsdReadOptions::default()
        };
        let stage = read_usd(&file, &options).unwrap();
        let paths: Vec<String> = stage.meshes.iter().map(|m| m.path.clone()).collect();
        (paths, stage.warnings)
    };
    assert_eq!(
        select(&["/World/*/Body"]).0,
        ["/World/A/Body", "/World/B/Body"]
    );
    assert_eq!(select(&["/**/Body"]).0, ["/World/A/Body", "/World/B/Body"]);
    assert_eq!(
        select(&["/World/B/*", "/Other"]).0,
        ["/World/B/Body", "/World/B/Arm", "/Other"]
    );
    assert_eq!(select(&["/World/?/A*"]).0, ["/World/B/Arm"]);
    let (paths, warnings) = select(&["/World/A/Body", "/Nothing/**"]);
    assert_eq!(paths, ["/World/A/Body"]);
    assert_eq!(warnings.len(), 1);
    assert!(
        warnings[0].message.contains("\"/Nothing/**\""),
        "{}",
        warnings[0]
    );
    // Everything: the malformed mesh is read, and refused.
    let e = usd_error(&file, &UsdReadOptions::default());
    assert_eq!(
        (e.prim.as_str(), e.attribute.as_str()),
        ("/World/Bad", "subdivisionScheme")
    );
    // A relative pattern is refused.
    let e = usd_error(
        &file,
        &UsdReadOptions {
            prims: vec!["World/*".into()],
            ..UsdReadOptions::default()
        },
    );
    assert!(matches!(e.kind, UsdErrorKind::Pattern { .. }), "{e}");
}

#[test]
fn files_that_cannot_be_read() {
    let dir = scratch("unreadable");
    for (name, bytes) in [
        ("missing.usda", None),
        (
            "garbage.usda",
            Some(&b"#usda 1.0\ndef Mesh \"M\" { int[] x = [1, 2 }"[..]),
        ),
        ("garbage.usdc", Some(&b"PXR-USDC not really"[..])),
        ("garbage.usdz", Some(&b"PK\x03\x04 not a zip"[..])),
        ("empty.usda", Some(&b""[..])),
    ] {
        let file = dir.join(name);
        if let Some(bytes) = bytes {
            std::fs::write(&file, bytes).unwrap();
        }
        let e = usd_error(&file, &UsdReadOptions::default());
        assert!(e.prim.is_empty() && e.attribute.is_empty(), "{e}");
        assert!(matches!(e.kind, UsdErrorKind::Open(_)), "{name}: {e}");
    }
}

// ---------------------------------------------------------------------------
// Writing.

/// An attribute's value as the crate reads it back.
fn get(stage: &usd::Stage, attr: &str) -> Value {
    stage
        .attribute(attr)
        .get::<Value>()
        .unwrap()
        .unwrap_or_else(|| panic!("{attr} is not authored"))
}

fn flat3d(v: Value) -> Vec<f64> {
    match v {
        Value::Vec3dVec(v) => v.into_iter().flat_map(<[f64; 3]>::from).collect(),
        Value::Vec3fVec(v) => v
            .into_iter()
            .flat_map(|p| <[f32; 3]>::from(p).map(f64::from))
            .collect(),
        other => panic!("not 3-vectors: {other:?}"),
    }
}

/// Refined meshes written as `.usda` read back through the `openusd` crate
/// with every value exact: points, faces, holes, face-varying channels and
/// their indices, primvars, the prim hierarchy and `subdivisionScheme =
/// "none"` — in `f64` types and in `f32` ones.
#[test]
fn refined_meshes_written_as_usda_read_back_exactly() {
    let dir = scratch("write");
    let meshes = sample_meshes(&dir);
    let refined: Vec<_> = meshes
        .iter()
        .map(|m| {
            Engine::Native
                .refine(&m.mesh, &m.options, Request::new(2))
                .unwrap()
        })
        .collect();
    let rest: Vec<Vec<f64>> = refined
        .iter()
        .map(|r| {
            r.last_positions()
                .iter()
                .flat_map(|p| p.to_array())
                .collect()
        })
        .collect();
    let wide: Vec<Vec<f64>> = rest
        .iter()
        .map(|r| {
            r.chunks(3)
                .flat_map(|p| [p[0], p[1], p[2], 1.0 / 3.0, -0.0, 1e-300])
                .collect()
        })
        .collect();
    let outs: Vec<UsdMeshOut<'_>> = meshes
        .iter()
        .zip(&refined)
        .zip(rest.iter().zip(&wide))
        .map(|((m, r), (rest, wide))| {
            let mut out = UsdMeshOut::from_refinement(&m.path, r, &m.fvar_names);
            out.primvars = vec![
                UsdPrimvarOut {
                    name: "rest".into(),
                    interpolation: UsdInterpolation::Vertex,
                    width: 3,
                    values: rest,
                },
                UsdPrimvarOut {
                    name: "wide".into(),
                    interpolation: UsdInterpolation::Varying,
                    width: 6,
                    values: wide,
                },
            ];
            out
        })
        .collect();
    for precision in [Precision::F64, Precision::F32] {
        let round = |x: f64| match precision {
            Precision::F64 => x,
            Precision::F32 => f64::from(x as f32),
        };
        let file = dir.join(format!("refined-{precision}.usda"));
        write_usda(&file, &outs, precision).unwrap();
        let stage = usd::Stage::open(file.to_str().unwrap()).unwrap();
        assert_eq!(
            stage.prim("/World").type_name().unwrap().unwrap().as_str(),
            "Xform"
        );
        for ((m, r), out) in meshes.iter().zip(&refined).zip(&outs) {
            let at = |name: &str| format!("{}.{name}", m.path);
            let level = r.last_level();
            assert_eq!(
                stage
                    .prim(m.path.as_str())
                    .type_name()
                    .unwrap()
                    .unwrap()
                    .as_str(),
                "Mesh"
            );
            assert_eq!(
                get(&stage, &at("subdivisionScheme")),
                Value::Token("none".into())
            );
            // `point3f[]` whatever the precision: UsdGeomMesh's type.
            let to_f32 = |x: f64| f64::from(x as f32);
            let points: Vec<f64> = r
                .last_positions()
                .iter()
                .flat_map(|p| p.to_array().map(to_f32))
                .collect();
            assert_eq!(
                flat3d(get(&stage, &at("points"))),
                points,
                "{} {precision}",
                m.path
            );
            let counts: Vec<i32> = level.faces().map(|f| f.len() as i32).collect();
            assert_eq!(get(&stage, &at("faceVertexCounts")), Value::IntVec(counts));
            let indices: Vec<i32> = level.face_vertices.iter().map(|&v| v as i32).collect();
            assert_eq!(
                get(&stage, &at("faceVertexIndices")),
                Value::IntVec(indices)
            );
            let holes: Vec<i32> = (0..level.face_count())
                .filter(|&f| level.face_holes.get(f) == Some(&true))
                .map(|f| f as i32)
                .collect();
            if holes.is_empty() {
                assert!(
                    stage
                        .attribute(at("holeIndices").as_str())
                        .get::<Value>()
                        .unwrap()
                        .is_none()
                );
            } else {
                assert_eq!(get(&stage, &at("holeIndices")), Value::IntVec(holes));
            }
            for (c, name) in m.fvar_names.iter().enumerate() {
                let attr = at(&format!("primvars:{name}"));
                let values: Vec<f64> = match get(&stage, &attr) {
                    Value::Vec2dVec(v) => v.into_iter().flat_map(<[f64; 2]>::from).collect(),
                    Value::Vec2fVec(v) => v
                        .into_iter()
                        .flat_map(|p| <[f32; 2]>::from(p).map(f64::from))
                        .collect(),
                    other => panic!("{attr}: {other:?}"),
                };
                // Texture coordinates are `texCoord2f[]` whatever the precision.
                let round_c = |x: f64| if c == 0 { to_f32(x) } else { round(x) };
                let expected: Vec<f64> = r
                    .last_fvar(c)
                    .unwrap()
                    .iter()
                    .map(|&x| round_c(x))
                    .collect();
                assert_eq!(values, expected, "{attr}");
                let indices: Vec<i32> = level.fvar[c]
                    .face_values
                    .iter()
                    .map(|&v| v as i32)
                    .collect();
                assert_eq!(
                    get(&stage, &format!("{attr}:indices")),
                    Value::IntVec(indices)
                );
                let attribute = stage.attribute(attr.as_str());
                let interpolation = attribute.get_metadata::<Value>("interpolation").unwrap();
                assert_eq!(interpolation, Some(Value::Token("faceVarying".into())));
                let type_name = attribute.type_name().unwrap().unwrap();
                let expected_type = match (c, precision) {
                    (0, _) => "texCoord2f[]",
                    (_, Precision::F64) => "double2[]",
                    (_, Precision::F32) => "float2[]",
                };
                assert_eq!(type_name.as_str(), expected_type);
            }
            assert_eq!(
                flat3d(get(&stage, &at("primvars:rest"))),
                out.primvars[0]
                    .values
                    .iter()
                    .map(|&x| round(x))
                    .collect::<Vec<_>>()
            );
            let wide = stage.attribute(at("primvars:wide").as_str());
            assert_eq!(
                wide.get_metadata::<Value>("elementSize").unwrap(),
                Some(Value::Int64(6))
            );
            let values: Vec<f64> = match wide.get::<Value>().unwrap().unwrap() {
                Value::DoubleVec(v) => v,
                Value::FloatVec(v) => v.into_iter().map(f64::from).collect(),
                other => panic!("{other:?}"),
            };
            let expected: Vec<f64> = out.primvars[1].values.iter().map(|&x| round(x)).collect();
            assert_eq!(values.len(), expected.len());
            assert!(
                values
                    .iter()
                    .zip(&expected)
                    .all(|(a, b)| a.to_bits() == b.to_bits())
            );
        }
        // read_usd sees them as meshes that are not subdivided.
        let stage = read(&file);
        assert!(stage.meshes.is_empty());
        assert_eq!(stage.skipped.len(), meshes.len());
    }
}

#[test]
fn malformed_output_is_refused_before_anything_is_written() {
    let dir = scratch("write_refused");
    let positions = [DVec3::ZERO, DVec3::X, DVec3::Y];
    let mesh = |path: &'static str| UsdMeshOut {
        path,
        positions: &positions,
        face_offsets: &[0, 3],
        face_vertices: &[0, 1, 2],
        holes: Vec::new(),
        left_handed: false,
        fvar: Vec::new(),
        primvars: Vec::new(),
    };
    let file = dir.join("out.usda");
    std::fs::write(&file, "before").unwrap();
    let uv = [0.0, 0.0, 1.0, 0.0];
    let cases: Vec<(Vec<UsdMeshOut<'_>>, &str)> = vec![
        (vec![mesh("/A"), mesh("/A")], "given twice"),
        (vec![mesh("A")], "not an absolute prim path"),
        (vec![mesh("/A/b c")], "not an absolute prim path"),
        (
            vec![UsdMeshOut {
                face_vertices: &[0, 1, 3],
                ..mesh("/A")
            }],
            "face vertex 2 is 3",
        ),
        (
            vec![UsdMeshOut {
                face_offsets: &[0, 2],
                ..mesh("/A")
            }],
            "face offsets",
        ),
        (
            vec![UsdMeshOut {
                holes: vec![1],
                ..mesh("/A")
            }],
            "hole 1",
        ),
        (
            vec![UsdMeshOut {
                fvar: vec![UsdFVarOut {
                    name: "st".into(),
                    width: 2,
                    values: &uv,
                    face_values: &[0, 1, 2],
                }],
                ..mesh("/A")
            }],
            "index 2 is 2",
        ),
        (
            vec![UsdMeshOut {
                fvar: vec![UsdFVarOut {
                    name: "a:indices".into(),
                    width: 2,
                    values: &uv,
                    face_values: &[0, 1, 1],
                }],
                ..mesh("/A")
            }],
            "not a primvar name",
        ),
        (
            vec![UsdMeshOut {
                primvars: vec![UsdPrimvarOut {
                    name: "p".into(),
                    interpolation: UsdInterpolation::Vertex,
                    width: 2,
                    values: &uv,
                }],
                ..mesh("/A")
            }],
            "4 values for 3 points",
        ),
        (
            vec![UsdMeshOut {
                positions: &[DVec3::ZERO, DVec3::X, DVec3::NAN],
                ..mesh("/A")
            }],
            "points: value 6 is NaN, not a finite number",
        ),
    ];
    for (meshes, expected) in cases {
        let e = write_usda(&file, &meshes, Precision::F64).unwrap_err();
        assert!(matches!(e, Error::Io { .. }), "{e}");
        assert!(e.to_string().contains(expected), "{e}");
        assert_eq!(std::fs::read_to_string(&file).unwrap(), "before");
    }
    // Only the file itself: no temporary file left behind.
    assert_eq!(support::file_names(&dir), ["out.usda"]);
    // Points beyond f32's range: `point3f[]` cannot hold them, in either precision.
    let big = [DVec3::ZERO, DVec3::X, DVec3::new(0.0, 1e300, 0.0)];
    let wide = UsdMeshOut {
        positions: &big,
        ..mesh("/A")
    };
    for precision in [Precision::F32, Precision::F64] {
        let e = write_usda_to(Vec::new(), std::slice::from_ref(&wide), precision).unwrap_err();
        assert!(e.to_string().contains("points: value 7 is 1e300"), "{e}");
    }
    // Infinite and NaN primvar values are written as USD spells them.
    let odd = [f64::INFINITY, f64::NEG_INFINITY, -f64::NAN];
    let with_odd = UsdMeshOut {
        primvars: vec![UsdPrimvarOut {
            name: "odd".into(),
            interpolation: UsdInterpolation::Varying,
            width: 1,
            values: &odd,
        }],
        ..mesh("/A")
    };
    for precision in [Precision::F64, Precision::F32] {
        let mut text = Vec::new();
        write_usda_to(&mut text, std::slice::from_ref(&with_odd), precision).unwrap();
        let file = support::write(&dir, "odd.usda", &String::from_utf8(text).unwrap());
        let stage = usd::Stage::open(file.to_str().unwrap()).unwrap();
        let values: Vec<f64> = match get(&stage, "/A.primvars:odd") {
            Value::DoubleVec(v) => v,
            Value::FloatVec(v) => v.into_iter().map(f64::from).collect(),
            other => panic!("{other:?}"),
        };
        assert_eq!(values[..2], [f64::INFINITY, f64::NEG_INFINITY]);
        assert!(values[2].is_nan());
    }
}

/// What the `openusd` crate reads but Pixar's USD does not: a layer with a
/// prim name that is not an identifier is refused (with a `}`, the crate's
/// composition recurses until the stack overflows), and one with a path
/// holding characters no path has; a layer that is not a regular file
/// (`@/dev/zero@`) is not read.
#[test]
fn names_usd_refuses_and_files_that_are_not_layers() {
    let dir = scratch("not_usd");
    let (pts, counts, indices) = grid_text();
    let mesh = |name: &str| {
        format!(
            "def Mesh \"{name}\"\n{{\n    point3f[] points = {pts}\n    \
             int[] faceVertexCounts = {counts}\n    int[] faceVertexIndices = {indices}\n}}\n"
        )
    };
    // In text, refused as the layer is opened (a `}` in a prim name would
    // send the crate's composition into unbounded recursion).
    for name in ["Bo#dy", "Pa}", "a.b"] {
        let text = format!("#usda 1.0\n{}", mesh(name));
        let file = support::write(&dir, "bad_name.usda", &text);
        let e = usd_error(&file, &UsdReadOptions::default());
        assert!(matches!(e.kind, UsdErrorKind::Open(_)), "{e}");
        assert!(e.to_string().contains("is not an identifier"), "{e}");
    }
    // A path with characters no path has (here a NUL byte): the crate's
    // composition of such an `inherits` allocates until memory runs out.
    let text = format!(
        "#usda 1.0\ndef Mesh \"Body\" (\n    inherits = </_\0 F>\n)\n{{\n}}\n{}",
        mesh("Other")
    );
    let file = support::write(&dir, "bad_path.usda", &text);
    let e = usd_error(&file, &UsdReadOptions::default());
    assert!(e.to_string().contains("has the character '\\0'"), "{e}");
    // Brackets nested deeper than USD ever nests them: the crate's parser
    // takes time and memory exponential in the depth of `[`, and stack in
    // the depth of everything.
    let text = format!(
        "#usda 1.0\n(\n    doc = {}{}\n)\n{}",
        "[".repeat(30),
        "]".repeat(30),
        mesh("Body")
    );
    let file = support::write(&dir, "brackets.usda", &text);
    let e = usd_error(&file, &UsdReadOptions::default());
    assert!(e.to_string().contains("nest deeper than"), "{e}");
    // A prim hierarchy 254 levels deep, brackets 256 deep in its points
    // (`{`, then `[(`), is read, on the reader's own stack.
    let text = format!(
        "#usda 1.0\n{}{}{}",
        "def \"P\" {\n".repeat(253),
        mesh("Body").replace("{{", "{").replace("}}", "}"),
        "}\n".repeat(253)
    );
    let file = support::write(&dir, "deep.usda", &text);
    let stage = read(&file);
    assert_eq!(stage.meshes[0].path.len(), "/P".len() * 253 + "/Body".len());
    // Dictionaries 250 deep: beyond a test thread's 2 MiB stack in a debug
    // build, within the reader's.
    let dictionaries: String = (0..250)
        .map(|i| format!("dictionary d{i} = {{\n"))
        .collect();
    let text = format!(
        "#usda 1.0\n(\n    customLayerData = {{\n{dictionaries}int x = 1\n{}}}\n)\n{}",
        "}\n".repeat(250),
        mesh("Body")
    );
    let file = support::write(&dir, "deep_dictionaries.usda", &text);
    assert_eq!(read(&file).meshes.len(), 1);
    // In a binary layer too.
    let a = Author::new();
    author_grid(&a, "/Bo_dy");
    let crate_file = a.export(&dir.join("bad_name.usdc"));
    let mut bytes = std::fs::read(&crate_file).unwrap();
    let at = bytes.windows(5).position(|w| w == b"Bo_dy").unwrap();
    bytes[at + 2] = b'}';
    std::fs::write(&crate_file, bytes).unwrap();
    let e = usd_error(&crate_file, &UsdReadOptions::default());
    let message = e.to_string();
    assert!(
        message.contains("\"Bo}dy\"") && message.contains("not an identifier"),
        "{e}"
    );
    for arc in ["references = @/dev/zero@", "payload = @/dev/zero@"] {
        let text = format!(
            "#usda 1.0\ndef Xform \"World\" (\n    {arc}\n)\n{{\n}}\n{}",
            mesh("Body")
        );
        let file = support::write(&dir, "zero.usda", &text);
        let stage = read(&file);
        assert_eq!(stage.meshes.len(), 1, "{arc}");
        assert!(!stage.warnings.is_empty(), "{arc}");
    }
    let file = support::write(
        &dir,
        "zero_sublayer.usda",
        &format!(
            "#usda 1.0\n(\n    subLayers = [@/dev/zero@]\n)\n{}",
            mesh("Body")
        ),
    );
    match read_usd(&file, &UsdReadOptions::default()) {
        Ok(stage) => assert!(!stage.warnings.is_empty()),
        Err(e) => assert!(e.to_string().contains("/dev/zero"), "{e}"),
    }
}
