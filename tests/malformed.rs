//! Malformed input through the library.
//!
//! Every file of `tests/malformed/` gets exactly the error asserted here: its
//! kind, its line and its message (the corpus and its errors are in
//! `tests/support/malformed.rs`; `tests/cli/malformed.rs` runs `subdiv refine`
//! and `subdiv curve` on the same files). The OpenSubdiv bridge refuses every
//! malformed mesh itself, even without Rust's validation in front of it.
//! Absurd levels are refused before anything is allocated, and the native
//! refiner can be shared by threads.
//!
//! Tests marked `#[ignore = "bug: ..."]` state the behaviour that is wanted
//! and fails today (run them with `cargo test --test malformed -- --ignored`).

mod support;

use subdiv::io::points::PointsErrorKind;
use subdiv::io::read_obj;
use subdiv::refiner::{self, Refiner};
use subdiv::{Error, MeshError, Options, Scheme, UniformOptions, shapes};
use support::malformed::{curve_errors, curve_too_few, file as malformed, obj_errors};

#[test]
fn the_corpus_is_complete() {
    // Every file of tests/malformed/ is asserted somewhere.
    let sources = [
        include_str!("malformed.rs"),
        include_str!("support/malformed.rs"),
        include_str!("cli/malformed.rs"),
    ]
    .concat();
    for entry in std::fs::read_dir(malformed("")).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        assert!(
            sources.contains(&format!("\"{name}\"")),
            "tests/malformed/{name} is not asserted in tests/malformed.rs, \
             tests/support/malformed.rs or tests/cli/malformed.rs"
        );
    }
}

#[test]
fn every_malformed_obj_gets_its_exact_error() {
    for (name, line, kind, message) in obj_errors() {
        let path = malformed(name);
        let err = read_obj(&path).expect_err(name);
        assert_eq!(err.file, path, "{name}");
        assert_eq!((err.line, &err.kind), (line, &kind), "{name}");
        assert_eq!(
            err.to_string(),
            format!("{}:{line}: {message}", path.display()),
            "{name}"
        );
        assert!(!err.to_string().contains('\r'), "{name}");
        assert!(
            !err.to_string().chars().any(char::is_control),
            "{name}: a control character in {:?}",
            err.to_string()
        );
        // Through the crate's error type as well.
        let err = Error::from(err);
        assert!(matches!(&err, Error::Obj(e) if e.line == line), "{name}");
    }
}

/// Files that read without a syntax error but are no usable mesh.
#[test]
fn readable_but_unusable_files() {
    // Empty, or nothing but comments: an empty mesh, refused by both engines
    // with the same error, before OpenSubdiv sees it.
    for name in ["empty.obj", "comments_only.obj"] {
        let shape = read_obj(&malformed(name)).unwrap();
        assert_eq!(shape.mesh.vertex_count(), 0, "{name}");
        assert_eq!(shape.mesh.face_count(), 0, "{name}");
        assert!(shape.warnings.is_empty(), "{name}");
        assert!(shape.mesh.validate().is_ok(), "{name}");
        let err =
            refiner::refine(&shape.mesh, &shape.options(), UniformOptions::new(1)).unwrap_err();
        assert!(matches!(err, Error::EmptyMesh), "{name}: {err:?}");
        assert_eq!(
            err.to_string(),
            "the mesh has no faces: there is nothing to refine"
        );
        #[cfg(feature = "osd")]
        {
            let err = subdiv::osd::refine(&shape.mesh, &shape.options(), UniformOptions::new(1))
                .unwrap_err();
            assert!(matches!(err, Error::EmptyMesh), "{name}: {err:?}");
        }
    }
    // A face of 70000 corners (face_70000_corners.obj is refused by the
    // reader): validation refuses it too, as OpenSubdiv supports 65535.
    let shape = {
        let mut mesh = subdiv::Mesh {
            positions: vec![glam::DVec3::ZERO, glam::DVec3::X, glam::DVec3::Y],
            ..subdiv::Mesh::default()
        };
        mesh.face_vertices = (0..70000).map(|i| i % 3).collect();
        mesh.face_offsets = vec![0, 70000];
        subdiv::io::ShapeFile {
            mesh,
            tags: Default::default(),
            warnings: Vec::new(),
        }
    };
    assert_eq!(shape.mesh.face_sizes(), [70000]);
    let expected = MeshError::FaceTooLarge {
        face: 0,
        size: 70000,
    };
    assert_eq!(shape.mesh.validate(), Err(expected.clone()));
    let err = refiner::refine(&shape.mesh, &shape.options(), UniformOptions::new(1)).unwrap_err();
    assert!(matches!(&err, Error::Mesh(e) if *e == expected), "{err:?}");
    assert_eq!(
        err.to_string(),
        "invalid mesh: face 0 has 70000 vertices; at most 65535 are supported"
    );
    #[cfg(feature = "osd")]
    {
        let err =
            subdiv::osd::refine(&shape.mesh, &shape.options(), UniformOptions::new(1)).unwrap_err();
        assert!(matches!(&err, Error::Mesh(e) if *e == expected), "{err:?}");
        // The shim's own check, without Rust's validation in front of it.
        let err = subdiv::osd::TopologyRefiner::new_unvalidated(&shape.mesh, &shape.options())
            .unwrap_err();
        assert!(
            matches!(&err, Error::Osd(subdiv::OsdError { kind: subdiv::OsdErrorKind::Refused, message })
                if message == "face 0 has 70000 vertices; at most 65535 are supported"),
            "{err:?}"
        );
    }
    // Unknown tags are warnings (with their line); --strict makes them errors.
    let shape = read_obj(&malformed("tag_unknown.obj")).unwrap();
    assert_eq!(shape.warnings.len(), 1);
    assert_eq!(shape.warnings[0].line, 7);
    assert_eq!(shape.warnings[0].message, "unknown tag 'foo'");
    assert!(shape.warnings[0].ignored);
    assert_eq!(
        shape.warnings[0].to_string(),
        "line 7: unknown tag 'foo'; the line is ignored"
    );
    assert_eq!(
        shape.mesh.creases.len(),
        1,
        "a tag before the vertices it names"
    );
}

#[test]
fn every_malformed_curve_gets_its_exact_error() {
    for (name, line, kind, message) in curve_errors() {
        let path = malformed(name);
        let err = subdiv::io::points::read_points(&path).expect_err(name);
        assert_eq!(err.file, path, "{name}");
        assert_eq!((err.line, &err.kind), (line, &kind), "{name}");
        assert_eq!(
            err.to_string(),
            format!("{}:{line}: {message}", path.display()),
            "{name}"
        );
        assert!(!err.to_string().chars().any(char::is_control), "{name}");
    }
}

#[test]
fn too_few_points_name_the_last_line() {
    for (name, scheme, _, closed, got, needed, line, message) in curve_too_few() {
        let path = malformed(name);
        let file = subdiv::io::points::read_points(&path).unwrap();
        assert_eq!(file.points.len(), got, "{name}");
        let err = file.require(&scheme, closed).unwrap_err();
        assert_eq!(err.line, line, "{name} {scheme}");
        assert_eq!(
            err.kind,
            PointsErrorKind::TooFewPoints {
                got,
                needed,
                scheme: scheme.name(),
                closed
            }
        );
        assert_eq!(
            err.to_string(),
            format!("{}:{line}: {message}", path.display())
        );
    }
}

#[test]
fn binary_curve_file_is_refused() {
    let path = malformed("curve_binary_garbage.txt");
    let err = subdiv::io::points::read_points(&path).unwrap_err();
    assert_eq!(err.line, 3);
    assert_eq!(
        err.kind,
        PointsErrorKind::InvalidUtf8 {
            column: 1,
            byte: 0xFF
        }
    );
}

#[test]
fn binary_curve_file_names_its_line() {
    let path = malformed("curve_binary_garbage.txt");
    let err = subdiv::io::points::read_points(&path).unwrap_err();
    assert_eq!(err.line, 3, "{err}");
    assert!(
        err.to_string()
            .starts_with(&format!("{}:3: ", path.display())),
        "{err}"
    );
}

// ---------------------------------------------------------------------------
// Levels and threads
// ---------------------------------------------------------------------------

/// The library refuses level 11 and beyond; `subdiv refine` refuses them
/// too, and levels too large for memory (`tests/cli/malformed.rs`).
#[test]
fn absurd_levels_are_refused_by_the_library() {
    let err = refiner::refine(
        &shapes::cube(),
        &Options::default(),
        UniformOptions::new(11),
    )
    .unwrap_err();
    assert!(matches!(err, Error::Level { level: 11, .. }), "{err:?}");
    let mut r = Refiner::new(&shapes::cube(), &Options::default()).unwrap();
    assert!(matches!(
        r.refine_uniform(UniformOptions::new(u32::MAX)),
        Err(Error::Level { .. })
    ));
}

#[test]
fn native_refiner_is_shared_by_threads() {
    fn assert_send_sync<T: Send + Sync>() {}
    assert_send_sync::<Refiner>();
    for (mesh, options) in [
        (shapes::torus(10, 6), Options::default()),
        (
            shapes::triangulate_with_uvs(&shapes::cube_with_uvs()),
            Options::shape_file_defaults().with_scheme(Scheme::Loop),
        ),
    ] {
        let mut r = Refiner::new(&mesh, &options).unwrap();
        r.refine_uniform(UniformOptions::new(3).full_topology(true))
            .unwrap();
        let base: Vec<f64> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
        let single: Vec<f32> = base.iter().map(|&x| x as f32).collect();
        let run = |r: &Refiner| {
            let levels = r.interpolate_all(3, &base).unwrap();
            let last = levels.last().unwrap().clone();
            let narrow = r.interpolate_all(3, &single).unwrap();
            let limit = r.limit(3, &last).unwrap();
            let stencils = r.stencil_table().unwrap();
            let topology = r.level(3).unwrap();
            let fvar: Vec<Vec<f64>> = mesh
                .fvar_channels
                .iter()
                .enumerate()
                .map(|(c, ch)| {
                    let mut v = ch.values.clone();
                    for level in 1..=3 {
                        v = r.interpolate_face_varying(c, level, ch.width, &v).unwrap();
                    }
                    v
                })
                .collect();
            (levels, narrow, limit, stencils, topology, fvar)
        };
        let expected = run(&r);
        let shared = &r;
        std::thread::scope(|s| {
            let handles: Vec<_> = (0..6).map(|_| s.spawn(|| run(shared))).collect();
            for h in handles {
                let got = h.join().unwrap();
                // Bit for bit: the same floating-point operations in the same order.
                assert!(got == expected, "a thread got a different result");
            }
        });
        // Moved to another thread, too.
        let moved = std::thread::scope(|s| s.spawn(move || run(&r)).join().unwrap());
        assert!(moved == expected);
    }
}

// ---------------------------------------------------------------------------
// The OpenSubdiv bridge
// ---------------------------------------------------------------------------

#[cfg(feature = "osd")]
mod osd_bridge {
    use super::*;
    use glam::DVec3;
    use subdiv::osd;
    use subdiv::{Buffer, FVarChannel, Mesh, OsdError, OsdErrorKind};

    fn quad() -> Mesh {
        Mesh::from_faces(
            vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
            &[&[0, 1, 2, 3]],
        )
    }

    fn uv(indices: Vec<u32>) -> FVarChannel {
        FVarChannel {
            width: 2,
            values: vec![0.0; 8],
            indices,
        }
    }

    /// Malformed meshes: what the shim says without Rust's validation, and
    /// what `osd::TopologyRefiner::new` (validating first) says.
    #[test]
    fn the_shim_refuses_every_malformed_mesh() {
        type Edit = fn(&mut Mesh);
        let cases: Vec<(Edit, &str, MeshError)> = vec![
            (
                (|m: &mut Mesh| m.face_vertices[1] = u32::MAX) as Edit,
                "face 0 corner 1: vertex index -1 is out of range (4 vertices)",
                MeshError::VertexOutOfRange {
                    face: 0,
                    corner: 1,
                    index: u32::MAX,
                    count: 4,
                },
            ),
            (
                (|m: &mut Mesh| m.face_vertices[1] = i32::MAX as u32) as Edit,
                "face 0 corner 1: vertex index 2147483647 is out of range (4 vertices)",
                MeshError::VertexOutOfRange {
                    face: 0,
                    corner: 1,
                    index: i32::MAX as u32,
                    count: 4,
                },
            ),
            (
                (|m: &mut Mesh| m.add_face(&[0, 1])) as Edit,
                "face 1 has 2 vertices; at least 3 are needed",
                MeshError::FaceTooSmall { face: 1, size: 2 },
            ),
            (
                (|m: &mut Mesh| m.add_face(&[])) as Edit,
                "face 1 has 0 vertices; at least 3 are needed",
                MeshError::FaceTooSmall { face: 1, size: 0 },
            ),
            (
                (|m: &mut Mesh| m.add_crease(0, 7, 1.0)) as Edit,
                "crease 0: vertex 7 is out of range (4 vertices)",
                MeshError::CreaseVertexOutOfRange {
                    crease: 0,
                    vertex: 7,
                    count: 4,
                },
            ),
            (
                (|m: &mut Mesh| m.add_crease(0, 1, f32::NAN)) as Edit,
                "crease 0: sharpness is not finite",
                MeshError::BadSharpness {
                    what: "crease 0".into(),
                    value: f32::NAN,
                },
            ),
            (
                (|m: &mut Mesh| m.add_corner(4, 1.0)) as Edit,
                "corner 0: vertex 4 is out of range (4 vertices)",
                MeshError::CornerVertexOutOfRange {
                    corner: 0,
                    vertex: 4,
                    count: 4,
                },
            ),
            (
                (|m: &mut Mesh| m.holes.push(u32::MAX)) as Edit,
                "hole 0: face -1 is out of range (1 faces)",
                MeshError::HoleOutOfRange {
                    hole: 0,
                    face: u32::MAX,
                    count: 1,
                },
            ),
            (
                (|m: &mut Mesh| m.fvar_channels.push(uv(vec![0, 1, 2, 4]))) as Edit,
                "face-varying channel 0: value index 4 at face corner 3 is out of range (4 values)",
                MeshError::BadFVarChannel {
                    channel: 0,
                    problem:
                        "face 0 corner 3: value index 4 is out of range (the channel has 4 values)"
                            .into(),
                },
            ),
            (
                (|m: &mut Mesh| m.fvar_channels.push(uv(vec![0, 1, 2]))) as Edit,
                "malformed face offsets or face-varying channel",
                MeshError::BadFVarChannel {
                    channel: 0,
                    problem: "3 value indices for 4 face corners".into(),
                },
            ),
            (
                (|m: &mut Mesh| m.face_offsets = vec![0, 5]) as Edit,
                "malformed face offsets or face-varying channel",
                MeshError::BadOffsets("the last offset is 5 but there are 4 face vertices".into()),
            ),
            (
                (|m: &mut Mesh| m.face_offsets.clear()) as Edit,
                "malformed face offsets or face-varying channel",
                MeshError::BadOffsets("the first offset must be 0".into()),
            ),
        ];
        for (edit, shim_message, mesh_error) in cases {
            let mut mesh = quad();
            edit(&mut mesh);
            let options = Options::default();
            let err = osd::TopologyRefiner::new_unvalidated(&mesh, &options).unwrap_err();
            assert!(
                matches!(&err, Error::Osd(OsdError { kind: OsdErrorKind::Refused, message })
                    if message == shim_message),
                "{shim_message}: {err:?}"
            );
            let err = osd::TopologyRefiner::new(&mesh, &options).unwrap_err();
            // Display, not ==: a NaN sharpness is not equal to itself.
            assert!(
                matches!(&err, Error::Mesh(e) if e.to_string() == mesh_error.to_string()),
                "{mesh_error}: {err:?}"
            );
            let err = refiner::refine(&mesh, &options, UniformOptions::new(1)).unwrap_err();
            assert!(
                matches!(&err, Error::Mesh(e) if e.to_string() == mesh_error.to_string()),
                "native, {mesh_error}: {err:?}"
            );
        }
        // No faces (with or without vertices): refused as by the native
        // engine, before OpenSubdiv; the shim refuses it as well.
        let points_only = Mesh {
            positions: vec![DVec3::ZERO; 3],
            ..Mesh::default()
        };
        for mesh in [Mesh::default(), points_only] {
            let err = osd::TopologyRefiner::new(&mesh, &Options::default()).unwrap_err();
            assert!(matches!(err, Error::EmptyMesh), "{err:?}");
            let err = Refiner::new(&mesh, &Options::default()).unwrap_err();
            assert!(matches!(err, Error::EmptyMesh), "native: {err:?}");
            let err =
                osd::TopologyRefiner::new_unvalidated(&mesh, &Options::default()).unwrap_err();
            assert!(
                matches!(&err, Error::Osd(OsdError { kind: OsdErrorKind::Refused, message })
                    if message == "the mesh has no faces: there is nothing to refine"),
                "{err:?}"
            );
        }
    }

    /// Wrong buffers and levels are refused by the bridge, not passed on.
    #[test]
    fn the_bridge_refuses_wrong_arguments() {
        let cube = shapes::cube_with_uvs();
        let mut r = osd::TopologyRefiner::new(&cube, &Options::default()).unwrap();
        assert!(matches!(
            r.refine_uniform(UniformOptions::new(11)),
            Err(Error::Level { level: 11, .. })
        ));
        r.refine_uniform(UniformOptions::new(2)).unwrap();
        let base: Vec<f64> = cube.positions.iter().flat_map(|p| p.to_array()).collect();
        let no_level = |level| Error::NoSuchLevel {
            level,
            first: 1,
            last: 2,
        };
        let short = |got| Error::BufferLength {
            buffer: Buffer::Source,
            expected: 24,
            got,
        };
        for (level, width, len, expected) in [
            (0, 3, 24, no_level(0)),
            (3, 3, 24, no_level(3)),
            (1, 0, 0, Error::ZeroWidth),
            (1, 3, 23, short(23)),
            (1, 3, 25, short(25)),
        ] {
            let src = vec![0.0f64; len];
            let err = r.interpolate(level, width, &src).unwrap_err();
            assert_eq!(
                format!("{err:?}"),
                format!("{expected:?}"),
                "level {level} width {width} len {len}"
            );
        }
        assert!(r.interpolate(1, 3, &base).is_ok());
        assert!(
            r.interpolate_face_varying::<f64>(1, 1, 2, &[0.0; 28])
                .is_err()
        );
        assert!(
            r.interpolate_face_varying::<f64>(0, 1, 2, &[0.0; 3])
                .is_err()
        );
        assert!(
            r.limit::<f64>(3, &base).is_err(),
            "limit needs the last level's data"
        );
        assert!(r.level(3).is_err());
        let e = osd::StencilEvaluator::new(&r).unwrap();
        let src = vec![0.0f32; 8 * 3];
        assert!(e.eval(3, &src).is_ok());
        assert!(e.eval(3, &src[..23]).is_err());
        assert!(e.eval(0, &src).is_err());
    }

    /// The malformed files through the bridge: every one refused with a typed error.
    #[test]
    fn malformed_files_through_the_bridge() {
        for (name, line, _, _) in obj_errors() {
            let err = read_obj(&malformed(name)).unwrap_err();
            assert_eq!(err.line, line);
        }
        for name in ["empty.obj", "comments_only.obj"] {
            let shape = read_obj(&malformed(name)).unwrap();
            for level in 0..=2 {
                assert!(
                    osd::refine(&shape.mesh, &shape.options(), UniformOptions::new(level)).is_err(),
                    "{name} level {level}"
                );
            }
            let _ =
                osd::TopologyRefiner::new_unvalidated(&shape.mesh, &shape.options()).unwrap_err();
        }
    }

    /// A face naming a vertex twice can leave it "smooth" with unpaired faces
    /// and edges; OpenSubdiv's own assertion would abort on it. Both engines
    /// refuse the mesh with the same typed error (and the CLI exits 1:
    /// `tests/cli/malformed.rs`).
    #[test]
    fn repeated_vertex_does_not_abort_the_bridge() {
        let path = malformed("osd_abort_repeated_vertex.obj");
        let shape = read_obj(&path).unwrap();
        assert!(shape.mesh.validate().is_ok());
        let native = refiner::refine(&shape.mesh, &shape.options(), UniformOptions::new(1));
        let err = native
            .expect_err("native must refuse an unpaired smooth vertex")
            .to_string();
        assert!(err.contains("vertex 3") && err.contains("pair up"), "{err}");
        let bridge = subdiv::osd::refine(&shape.mesh, &shape.options(), UniformOptions::new(1));
        let err = bridge
            .expect_err("the bridge must refuse it before OpenSubdiv asserts")
            .to_string();
        assert!(err.contains("vertex 3") && err.contains("pair up"), "{err}");
        // Made a semi-sharp corner, the vertex passes level 0 and becomes
        // smooth one level down, where adaptive refinement (which selects
        // the faces around its semi-sharp feature) refuses it in both engines.
        let options = shape.options();
        let mut mesh = shape.mesh.clone();
        mesh.corners.push(subdiv::Corner {
            vertex: 3,
            sharpness: 1.0,
        });
        let adaptive = subdiv::AdaptiveOptions::new(2);
        let native = refiner::Refiner::new(&mesh, &options)
            .unwrap()
            .refine_adaptive(adaptive, &[])
            .expect_err("native adaptive must refuse an unpaired smooth vertex")
            .to_string();
        assert!(
            native.contains("vertex 3") && native.contains("pair up"),
            "{native}"
        );
        let mut theirs = osd::TopologyRefiner::new(&mesh, &options).unwrap();
        let err = theirs
            .refine_adaptive(adaptive, &[])
            .expect_err("the bridge must refuse it after RefineAdaptive")
            .to_string();
        assert!(err.contains("vertex 3") && err.contains("pair up"), "{err}");
    }

    #[test]
    fn level_zero_reports_the_base_edges_like_opensubdiv() {
        let cube = shapes::cube();
        let options = Options::default();
        let native = refiner::refine(&cube, &options, UniformOptions::new(0)).unwrap();
        let osd = osd::refine(&cube, &options, UniformOptions::new(0)).unwrap();
        assert_eq!(osd.levels[0].edge_vertices.len(), 12);
        assert_eq!(native.levels[0].edge_vertices, osd.levels[0].edge_vertices);
        for c in subdiv::compare::compare(&native, &osd) {
            assert!(
                c.agrees(1e-12),
                "level {}: tags equal {}",
                c.level,
                c.tags_equal
            );
        }
    }
}
