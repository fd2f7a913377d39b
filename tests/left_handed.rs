//! Left-handed meshes (`Mesh::left_handed`, OpenSubdiv's
//! `TopologyDescriptor::isLeftHanded`, USD's `orientation = "leftHanded"`):
//! each face is read from its first corner backwards, face-varying indices
//! alike. Every shape of the corpus is written clockwise (first corner
//! kept, the others reversed) and marked left-handed; both engines must then
//! refine and evaluate it exactly as they do the original counter-clockwise
//! mesh — which also proves the flag reaches OpenSubdiv (without it,
//! OpenSubdiv's faces would come out in the other order) — and the native
//! engine must equal OpenSubdiv on it.
#![cfg(feature = "osd")]

use subdiv::bfr::{LimitSurfaces, SurfaceOptions};
use subdiv::patches::Derivatives;
use subdiv::{Mesh, Options, Request, Scheme, UniformOptions, osd, refiner, shapes};

/// `mesh` written clockwise and marked left-handed.
fn clockwise(mesh: &Mesh) -> Mesh {
    let mut out = mesh.clone();
    let flip = |list: &mut Vec<u32>| {
        for w in mesh.face_offsets.windows(2) {
            list[w[0] as usize + 1..w[1] as usize].reverse();
        }
    };
    flip(&mut out.face_vertices);
    for channel in &mut out.fvar_channels {
        flip(&mut channel.indices);
    }
    out.left_handed = true;
    out
}

fn corpus_with_uvs() -> Vec<(String, Mesh)> {
    let mut all = shapes::corpus();
    all.push(("cube-with-uvs".into(), shapes::cube_with_uvs()));
    all.push(("production-12x10".into(), shapes::production(12, 10)));
    all.push((
        "torus-mixed-uvs".into(),
        shapes::with_torus_uvs(shapes::torus_mixed(8, 6), 8, 6),
    ));
    all
}

#[test]
fn right_handed_reads_a_clockwise_mesh_back_as_the_original() {
    for (name, mesh) in corpus_with_uvs() {
        let left = clockwise(&mesh);
        assert_ne!(left.face_vertices, mesh.face_vertices, "{name}");
        assert_eq!(*left.right_handed(), mesh, "{name}");
        assert!(matches!(mesh.right_handed(), std::borrow::Cow::Borrowed(_)));
    }
}

#[test]
fn both_engines_refine_a_left_handed_mesh_as_the_original_and_agree() {
    let mut checked = 0;
    for (name, mesh) in corpus_with_uvs() {
        let left = clockwise(&mesh);
        for &scheme in mesh.applicable_schemes() {
            let options = Options::shape_file_defaults()
                .with_scheme(scheme)
                .with_fvar(subdiv::FVarLinearInterpolation::CornersPlus1);
            let request = Request::from(UniformOptions::new(2)).limit(scheme != Scheme::Bilinear);
            let (Ok(osd_right), Ok(osd_left)) = (
                osd::refine(&mesh, &options, request),
                osd::refine(&left, &options, request),
            ) else {
                // Shapes OpenSubdiv refuses are refused by both readings.
                assert_eq!(
                    osd::refine(&mesh, &options, request).is_err(),
                    osd::refine(&left, &options, request).is_err(),
                    "{name} {scheme:?}"
                );
                continue;
            };
            assert_eq!(osd_left, osd_right, "{name} {scheme:?}: OpenSubdiv");
            let native_left = refiner::refine(&left, &options, request).unwrap();
            assert_eq!(
                native_left, osd_left,
                "{name} {scheme:?}: native vs OpenSubdiv"
            );
            checked += 1;
        }
    }
    assert!(checked > 40, "only {checked} refinements compared");
}

#[test]
fn bfr_surfaces_of_a_left_handed_mesh_are_the_original_faces_surfaces() {
    let coords: Vec<[f64; 2]> = (0..5)
        .flat_map(|i| (0..5).map(move |j| [i as f64 / 4.0, j as f64 / 4.0]))
        .collect();
    for mesh in [
        shapes::production(6, 5),
        shapes::with_torus_uvs(shapes::torus_mixed(6, 4), 6, 4),
    ] {
        let left = clockwise(&mesh);
        let options = Options::default();
        let surface = SurfaceOptions::default();
        let osd_right = osd::bfr::Surfaces::new(&mesh, &options, &surface).unwrap();
        let osd_left = osd::bfr::Surfaces::new(&left, &options, &surface).unwrap();
        let native_left = LimitSurfaces::new(&left, &options, &surface).unwrap();
        for f in 0..mesh.face_count() {
            if mesh.holes.contains(&(f as u32)) || mesh.face(f).len() != 4 {
                continue;
            }
            let a = osd_right.evaluate(f, &coords, Derivatives::First).unwrap();
            let b = osd_left.evaluate(f, &coords, Derivatives::First).unwrap();
            let c = native_left
                .evaluate(f, &coords, Derivatives::First)
                .unwrap();
            assert_eq!(a.values, b.values, "face {f}: OpenSubdiv");
            for (x, y) in b.values.point.iter().zip(&c.values.point) {
                assert!(
                    (x - y).abs() < 1e-9,
                    "face {f}: native {y} vs OpenSubdiv {x}"
                );
            }
            let uv_right = osd_right.evaluate_fvar(f, 0, &coords, Derivatives::None);
            let uv_left = osd_left.evaluate_fvar(f, 0, &coords, Derivatives::None);
            assert_eq!(
                uv_right.unwrap().values,
                uv_left.unwrap().values,
                "face {f}: UVs"
            );
        }
    }
}
