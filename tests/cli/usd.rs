//! USD stages through the commands: `refine`, `compare`, `report` and
//! `tessellate` take a stage's subdivision meshes (one per prim, `--prim`
//! selecting), `refine -o OUT.usda` writes them back at their prim paths.
//! The stages are written here as text from the library's shapes; the same
//! meshes as OBJ files with `t` tags (and USD's fallback options given on the
//! command line) must give byte-identical outputs.

use crate::support::{obj_text, scratch, stderr, stdout, subdiv, write};
use subdiv::{Mesh, shapes};

/// `mesh` as a `def Mesh` block of USD text: points, faces, one crease of
/// two vertices per crease edge, corners, holes, channel 0 as indexed
/// `primvars:st`, and `extra` lines (orientation, scheme, ...).
fn usd_mesh(name: &str, mesh: &Mesh, extra: &str) -> String {
    let list = |items: Vec<String>| items.join(", ");
    let ints = |v: &[u32]| list(v.iter().map(u32::to_string).collect());
    let floats = |v: Vec<f32>| list(v.iter().map(|x| format!("{x:?}")).collect());
    let mut out = format!("    def Mesh \"{name}\" {{\n");
    let points = mesh
        .positions
        .iter()
        .map(|p| format!("({:?}, {:?}, {:?})", p.x, p.y, p.z))
        .collect();
    out += &format!("        point3f[] points = [{}]\n", list(points));
    let counts: Vec<u32> = mesh.faces().map(|f| f.len() as u32).collect();
    out += &format!("        int[] faceVertexCounts = [{}]\n", ints(&counts));
    out += &format!(
        "        int[] faceVertexIndices = [{}]\n",
        ints(&mesh.face_vertices)
    );
    if !mesh.creases.is_empty() {
        let pairs: Vec<u32> = mesh.creases.iter().flat_map(|c| c.vertices).collect();
        out += &format!("        int[] creaseIndices = [{}]\n", ints(&pairs));
        out += &format!(
            "        int[] creaseLengths = [{}]\n",
            ints(&vec![2; mesh.creases.len()])
        );
        out += &format!(
            "        float[] creaseSharpnesses = [{}]\n",
            floats(mesh.creases.iter().map(|c| c.sharpness).collect())
        );
    }
    if !mesh.corners.is_empty() {
        let vertices: Vec<u32> = mesh.corners.iter().map(|c| c.vertex).collect();
        out += &format!("        int[] cornerIndices = [{}]\n", ints(&vertices));
        out += &format!(
            "        float[] cornerSharpnesses = [{}]\n",
            floats(mesh.corners.iter().map(|c| c.sharpness).collect())
        );
    }
    if !mesh.holes.is_empty() {
        out += &format!("        int[] holeIndices = [{}]\n", ints(&mesh.holes));
    }
    if let Some(uv) = mesh.fvar_channels.first() {
        let values = uv
            .values
            .chunks_exact(2)
            .map(|v| format!("({:?}, {:?})", v[0], v[1]))
            .collect();
        out += &format!(
            "        texCoord2f[] primvars:st = [{}] (interpolation = \"faceVarying\")\n",
            list(values)
        );
        out += &format!(
            "        int[] primvars:st:indices = [{}]\n",
            ints(&uv.indices)
        );
    }
    out += extra;
    out + "    }\n"
}

/// A stage of `meshes` under `/World`.
fn stage(meshes: &[String]) -> String {
    format!("#usda 1.0\ndef Xform \"World\" {{\n{}}}\n", meshes.concat())
}

/// A mesh whose values survive `f32` (USD's `point3f[]`, `texCoord2f[]`):
/// the production-like shape with coordinates and UVs rounded to `f32`.
fn production() -> Mesh {
    let mut mesh = shapes::production(8, 6);
    for p in &mut mesh.positions {
        *p = p.as_vec3().as_dvec3();
    }
    for channel in &mut mesh.fvar_channels {
        for v in &mut channel.values {
            *v = f64::from(*v as f32);
        }
    }
    mesh
}

/// `mesh` written clockwise (first corner kept), for `orientation = "leftHanded"`.
fn clockwise(mesh: &Mesh) -> Mesh {
    let mut left = mesh.clone();
    for w in mesh.face_offsets.windows(2) {
        left.face_vertices[w[0] as usize + 1..w[1] as usize].reverse();
        for channel in &mut left.fvar_channels {
            channel.indices[w[0] as usize + 1..w[1] as usize].reverse();
        }
    }
    left
}

#[test]
fn a_usd_prim_refines_as_the_same_mesh_given_as_obj_with_usds_fallbacks() {
    let dir = scratch("usd_vs_obj");
    let mesh = production();
    let usd = write(
        &dir,
        "stage.usda",
        &stage(&[
            usd_mesh("Right", &mesh, ""),
            usd_mesh(
                "Left",
                &clockwise(&mesh),
                "        uniform token orientation = \"leftHanded\"\n",
            ),
        ]),
    );
    let obj = write(&dir, "mesh.obj", &obj_text(&mesh));
    // USD's fallbacks: edge-and-corner boundaries, face-varying corners-plus1.
    let fallbacks = ["--boundary", "edge-and-corner", "--fvar", "corners-plus1"];
    let from_obj = dir.join("obj.obj");
    let mut args = vec!["refine", obj.to_str().unwrap(), "--level", "2", "-o"];
    args.push(from_obj.to_str().unwrap());
    args.extend(fallbacks);
    assert!(subdiv(&args).status.success());
    let expected = std::fs::read_to_string(&from_obj).unwrap();
    for prim in ["/World/Right", "/World/Left", "/World/L*"] {
        for engine in crate::engines() {
            let out = dir.join("usd.obj");
            let o = subdiv(&[
                "refine",
                usd.to_str().unwrap(),
                "--prim",
                prim,
                "--level",
                "2",
                "--engine",
                engine,
                "-o",
                out.to_str().unwrap(),
            ]);
            assert!(o.status.success(), "{prim} {engine}: {}", stderr(&o));
            assert_eq!(
                std::fs::read_to_string(&out).unwrap(),
                expected,
                "{prim} {engine}"
            );
        }
    }
}

#[test]
fn several_prims_need_a_usda_output_or_a_prim() {
    let dir = scratch("usd_several");
    let cube = shapes::cube();
    let text = stage(&[
        usd_mesh("A", &cube, ""),
        usd_mesh("B", &shapes::tetrahedron(), ""),
        usd_mesh(
            "Flat",
            &cube,
            "        uniform token subdivisionScheme = \"none\"\n",
        ),
    ]);
    let usd = write(&dir, "two.usda", &text);
    let usd = usd.to_str().unwrap();

    // A summary per prim; the unsubdivided prim is noted.
    let o = subdiv(&["refine", usd, "--level", "1"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let lines: Vec<String> = stdout(&o).lines().map(str::to_string).collect();
    assert_eq!(lines.len(), 2, "{lines:?}");
    assert!(lines[0].starts_with(&format!("{usd}:/World/A: catmark level 1")));
    assert!(
        lines[0].contains("vertices 8→26, faces 6→24"),
        "{}",
        lines[0]
    );
    assert!(lines[1].starts_with(&format!("{usd}:/World/B:")));
    assert!(stderr(&o).contains("/World/Flat skipped: subdivisionScheme is \"none\""));

    // One OBJ cannot hold both; a command of one mesh names them.
    let obj = dir.join("x.obj");
    let o = subdiv(&["refine", usd, "-o", obj.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("choose one with --prim PATH"));
    assert!(!obj.exists());
    let o = subdiv(&[
        "tessellate",
        usd,
        "--rate",
        "2",
        "-o",
        obj.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("2 subdivision meshes (/World/A, /World/B)"),
        "{}",
        stderr(&o)
    );
    let o = subdiv(&[
        "tessellate",
        usd,
        "--prim",
        "/World/A",
        "--rate",
        "2",
        "-o",
        obj.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // 6 quads at rate 2: 8 corners + 12 edge midpoints + 6 centres.
    let text = std::fs::read_to_string(&obj).unwrap();
    assert_eq!(text.lines().filter(|l| l.starts_with("v ")).count(), 26);

    // A pattern that matches nothing is a warning, then nothing to refine.
    let o = subdiv(&["refine", usd, "--prim", "/Nope"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("prim pattern \"/Nope\" matches no Mesh prim"));
    // USD options on an OBJ input are refused.
    let cube_obj = write(&dir, "cube.obj", &obj_text(&cube));
    let o = subdiv(&["refine", cube_obj.to_str().unwrap(), "--prim", "/A"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("apply to USD inputs"));
}

#[test]
fn refine_writes_a_usda_layer_with_the_prims_refined() {
    use subdiv::io::usd::{UsdReadOptions, read_usd};
    let dir = scratch("usd_out");
    let mesh = production();
    let usd = write(&dir, "in.usda", &stage(&[usd_mesh("P", &mesh, "")]));
    let out = dir.join("out.usda");
    let o = subdiv(&[
        "refine",
        usd.to_str().unwrap(),
        "--level",
        "1",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // Read back: not subdivided any more, so it is skipped as a mesh to refine...
    let back = read_usd(&out, &UsdReadOptions::default()).unwrap();
    assert!(back.meshes.is_empty());
    assert_eq!(back.skipped.len(), 1);
    assert_eq!(back.skipped[0].prim, "/World/P");
    // ...and its geometry is the refinement's, as the OBJ output has it.
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.contains("uniform token subdivisionScheme = \"none\""));
    let expected = subdiv::refiner::refine(
        &mesh,
        &subdiv::Options::default()
            .with_boundary(subdiv::BoundaryInterpolation::EdgeAndCorner)
            .with_fvar(subdiv::FVarLinearInterpolation::CornersPlus1),
        subdiv::UniformOptions::new(1),
    )
    .unwrap();
    let level = expected.last_level();
    let counts = level
        .faces()
        .map(|f| f.len().to_string())
        .collect::<Vec<_>>()
        .join(", ");
    assert!(text.contains(&format!("int[] faceVertexCounts = [{counts}]")));
    assert!(text.contains("primvars:st"));
    assert!(text.contains("holeIndices"), "the refined holes are kept");
}

#[cfg(feature = "osd")]
#[test]
fn compare_and_report_give_one_row_per_prim() {
    let dir = scratch("usd_compare");
    let mesh = production();
    let usd = write(
        &dir,
        "stage.usda",
        &stage(&[
            usd_mesh("Prod", &mesh, ""),
            usd_mesh(
                "Left",
                &clockwise(&mesh),
                "        uniform token orientation = \"leftHanded\"\n        uniform token interpolateBoundary = \"edgeOnly\"\n",
            ),
            usd_mesh(
                "Cube",
                &shapes::cube(),
                "        uniform token subdivisionScheme = \"bilinear\"\n",
            ),
        ]),
    );
    let usd = usd.to_str().unwrap();
    let o = subdiv(&["compare", usd, "--levels", "1..2"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    assert!(text.contains(&format!(
        "{usd}:/World/Prod: catmark boundary=edge-and-corner fvar=corners-plus1"
    )));
    assert!(text.contains(&format!("{usd}:/World/Left: catmark boundary=edge-only")));
    assert!(text.contains(&format!(
        "{usd}:/World/Cube: bilinear boundary=edge-and-corner"
    )));
    assert!(text.contains("3 meshes compared: the engines agree on every one"));
    let o = subdiv(&["compare", usd, "--levels", "1..2", "--json"]);
    let json: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let reports = json.as_array().expect("a list for a stage");
    assert_eq!(reports.len(), 3);
    assert!(reports.iter().all(|r| r["agrees"] == true));

    let out = dir.join("report");
    let o = subdiv(&[
        "report",
        usd,
        "--prim",
        "/World/P*",
        "--prim",
        "/World/Cube",
        "--quick",
        "--levels",
        "1..1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("stage.usda:/World/Prod"));
    assert!(md.contains("stage.usda:/World/Cube"));
    assert!(!md.contains("stage.usda:/World/Left"));
}

#[test]
fn malformed_usd_names_the_file_prim_and_attribute() {
    let dir = scratch("usd_malformed");
    let mut text = stage(&[usd_mesh("Bad", &shapes::cube(), "")]);
    text = text.replace(
        "int[] faceVertexIndices = [0,",
        "int[] faceVertexIndices = [99,",
    );
    let usd = write(&dir, "bad.usda", &text);
    let o = subdiv(&["refine", usd.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(err.contains("bad.usda"), "{err}");
    assert!(err.contains("/World/Bad"), "{err}");
    assert!(err.contains("faceVertexIndices"), "{err}");
    assert!(err.contains("99"), "{err}");
}

#[cfg(feature = "osd")]
#[test]
fn bench_takes_a_stages_prims_with_their_own_options() {
    let dir = scratch("usd_bench");
    let usd = write(
        &dir,
        "stage.usda",
        &stage(&[
            usd_mesh(
                "Cube",
                &shapes::cube(),
                "        uniform token subdivisionScheme = \"bilinear\"\n",
            ),
            usd_mesh("Other", &shapes::cube(), ""),
        ]),
    );
    let o = subdiv(&[
        "bench",
        usd.to_str().unwrap(),
        "--prim",
        "/World/Cube",
        "--quick",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    let rows: Vec<&str> = text
        .lines()
        .filter(|l| l.contains("stage.usda:/World/"))
        .collect();
    assert!(rows.len() > 10, "{text}");
    assert!(
        rows.iter()
            .all(|r| r.contains("stage.usda:/World/Cube") && r.contains("bilinear")),
        "{rows:?}"
    );
}
