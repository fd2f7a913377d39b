//! Property tests: random meshes, tags and options refine identically in the
//! native engine and in OpenSubdiv, uniformly and feature-adaptively (random
//! `AdaptiveOptions` and selected faces: levels, relations, child maps and
//! positions bit for bit).
#![cfg(feature = "osd")]

use glam::DVec3;
use proptest::prelude::*;
use subdiv::compare::{compare, compare_adaptive};
use subdiv::{
    AdaptiveOptions, BoundaryInterpolation, CreasingMethod, Error, Mesh, Options, Scheme,
    TriangleSubdivision, UniformOptions, osd, refiner,
};

fn options() -> impl Strategy<Value = Options> {
    (
        prop_oneof![
            Just(Scheme::Catmark),
            Just(Scheme::Bilinear),
            Just(Scheme::Loop)
        ],
        prop::sample::select(BoundaryInterpolation::ALL),
        prop::sample::select(CreasingMethod::ALL),
        prop::sample::select(TriangleSubdivision::ALL),
    )
        .prop_map(|(scheme, boundary, creasing, triangles)| Options {
            scheme,
            boundary,
            creasing,
            triangles,
            ..Options::default()
        })
}

fn sharpness() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(0.0f32),
        Just(10.0),
        Just(1.0),
        0.0f32..4.0,
        -1.0f32..12.0
    ]
}

/// A perturbed grid with random faces removed, quads split into triangles or
/// merged into hexagons, and random creases, corners and holes.
fn structured() -> impl Strategy<Value = Mesh> {
    (2u32..6, 2u32..5)
        .prop_flat_map(|(nx, ny)| {
            let cells = (nx * ny) as usize;
            let verts = ((nx + 1) * (ny + 1)) as usize;
            (
                Just((nx, ny)),
                prop::collection::vec(0u8..10, cells),
                prop::collection::vec((-0.3f64..0.3, -0.3f64..0.3, -0.5f64..0.5), verts),
                prop::collection::vec((0usize..1000, sharpness()), 0..6),
                prop::collection::vec((0usize..1000, sharpness()), 0..3),
                prop::collection::vec(0usize..1000, 0..2),
            )
        })
        .prop_map(|((nx, ny), kinds, jitter, creases, corners, holes)| {
            // One mesh in four is all triangles, so that Loop applies.
            let all_triangles = kinds[0] == 9;
            let mut m = Mesh::default();
            for j in 0..=ny {
                for i in 0..=nx {
                    let (dx, dy, dz) = jitter[(j * (nx + 1) + i) as usize];
                    m.positions
                        .push(DVec3::new(i as f64 + dx, j as f64 + dy, dz));
                }
            }
            let at = |i: u32, j: u32| j * (nx + 1) + i;
            let mut skip_next = false;
            for j in 0..ny {
                for i in 0..nx {
                    let kind = if all_triangles {
                        1
                    } else {
                        kinds[(j * nx + i) as usize]
                    };
                    if std::mem::take(&mut skip_next) {
                        continue;
                    }
                    let q = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                    match kind {
                        0 => {} // removed: a hole in the surface
                        1 => {
                            m.add_face(&[q[0], q[1], q[2]]);
                            m.add_face(&[q[0], q[2], q[3]]);
                        }
                        2 if i + 1 < nx => {
                            // A hexagon over two cells.
                            m.add_face(&[q[0], q[1], at(i + 2, j), at(i + 2, j + 1), q[2], q[3]]);
                            skip_next = true;
                        }
                        _ => m.add_face(&q),
                    }
                }
            }
            if m.face_count() == 0 {
                m.add_face(&[0, 1, at(1, 1), at(0, 1)]);
            }
            let edges: Vec<[u32; 2]> = m
                .faces()
                .flat_map(|f| (0..f.len()).map(move |k| [f[k], f[(k + 1) % f.len()]]))
                .collect();
            for (e, s) in creases {
                let [a, b] = edges[e % edges.len()];
                m.add_crease(a, b, s);
            }
            let nv = m.positions.len();
            for (v, s) in corners {
                m.add_corner((v % nv) as u32, s);
            }
            let nf = m.face_count();
            m.holes.extend(holes.into_iter().map(|f| (f % nf) as u32));
            m
        })
}

/// Random polygons over a handful of vertices: non-manifold edges, bowties,
/// inconsistent winding, repeated vertices — whatever comes.
fn soup() -> impl Strategy<Value = Mesh> {
    (4usize..10)
        .prop_flat_map(|nv| {
            (
                prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0), nv),
                prop::collection::vec(prop::collection::vec(0..nv as u32, 3..6), 1..7),
                any::<bool>(),
                prop::collection::vec((0usize..100, sharpness()), 0..4),
            )
        })
        .prop_map(|(points, mut faces, triangles, creases)| {
            if triangles {
                for f in &mut faces {
                    f.truncate(3);
                }
            }
            let mut m = Mesh {
                positions: points
                    .into_iter()
                    .map(|(x, y, z)| DVec3::new(x, y, z))
                    .collect(),
                ..Mesh::default()
            };
            for f in &faces {
                m.add_face(f);
            }
            let edges: Vec<[u32; 2]> = faces
                .iter()
                .flat_map(|f| (0..f.len()).map(move |k| [f[k], f[(k + 1) % f.len()]]))
                .collect();
            for (e, s) in creases {
                let [a, b] = edges[e % edges.len()];
                m.add_crease(a, b, s);
            }
            m
        })
}

/// `m` with every face of more than three corners split into a fan of
/// triangles (creases and corners kept, a hole's first triangle a hole): for
/// Loop.
fn triangulated(m: Mesh) -> Mesh {
    let mut out = Mesh {
        positions: m.positions.clone(),
        creases: m.creases.clone(),
        corners: m.corners.clone(),
        ..Mesh::default()
    };
    for (i, f) in m.faces().enumerate() {
        if m.holes.contains(&(i as u32)) {
            out.holes.push(out.face_count() as u32);
        }
        for k in 1..f.len().saturating_sub(1) {
            out.add_face(&[f[0], f[k], f[k + 1]]);
        }
    }
    out
}

fn assert_same(
    mesh: &Mesh,
    options: &Options,
    level: u32,
    faces_first: bool,
) -> Result<(), TestCaseError> {
    let uniform = UniformOptions::new(level).faces_first(faces_first);
    let expected = osd::refine(mesh, options, subdiv::Request::from(uniform));
    let actual = refiner::refine(mesh, options, subdiv::Request::from(uniform));
    match (expected, actual) {
        (Ok(e), Ok(a)) => {
            for c in compare(&a, &e) {
                prop_assert!(
                    c.agrees(1e-12),
                    "level {}: counts {:?}, first differing face {:?}, tags equal {}, deviation {:e}",
                    c.level,
                    c.counts,
                    c.first_face_difference,
                    c.tags_equal,
                    c.relative_position_deviation
                );
            }
            Ok(())
        }
        (Err(e), Err(_)) => {
            // Both refuse: fine, as long as it is not a crash.
            let _ = e;
            Ok(())
        }
        (e, a) => Err(TestCaseError::fail(format!(
            "osd {:?} vs native {:?}",
            e.err(),
            a.err()
        ))),
    }
}

/// Every field of `AdaptiveOptions` at random: isolation 0-6, secondary
/// 0-15 (past the isolation level half the time), the patch flags, the
/// face-varying flag (no channel here, so it changes nothing) and the vertex
/// order.
fn adaptive_options() -> impl Strategy<Value = AdaptiveOptions> {
    (
        0u32..=6,
        0u32..=15,
        any::<bool>(),
        any::<bool>(),
        any::<bool>(),
        any::<bool>(),
    )
        .prop_map(|(isolation, secondary, single, inf, fvar, faces_first)| {
            AdaptiveOptions::new(isolation)
                .secondary(secondary)
                .single_crease_patch(single)
                .inf_sharp_patch(inf)
                .consider_fvar(fvar)
                .faces_first(faces_first)
        })
}

/// Selected base faces, as indices to reduce modulo the face count: none
/// (every face) one time in three, else a few, repeats allowed.
fn selection() -> impl Strategy<Value = Vec<usize>> {
    prop_oneof![Just(Vec::new()), prop::collection::vec(0usize..1000, 1..6)]
}

/// The kind of a refusal, as far as a caller can tell: the name of the
/// error's variant, where the bridge's `Osd(Refused)` for a non-triangle
/// under Loop and for an unpaired smooth vertex count as the native
/// engine's typed `NotTriangles` and `UnpairedSmoothVertex` (the same
/// conditions, found by the shim).
fn refusal_kind(e: &Error) -> String {
    match e {
        Error::Osd(o) if o.message.contains("Loop scheme needs triangles") => "NotTriangles".into(),
        Error::Osd(o) if o.message.contains("do not pair up") => "UnpairedSmoothVertex".into(),
        _ => format!("{e:?}")
            .chars()
            .take_while(|c| c.is_alphanumeric())
            .collect(),
    }
}

/// Both engines refine `mesh` adaptively: both refuse with the same kind of
/// error, or every level agrees, element by element and bit for bit.
fn assert_same_adaptive(
    mesh: &Mesh,
    options: &Options,
    ao: AdaptiveOptions,
    selection: &[usize],
) -> Result<(), TestCaseError> {
    let nf = mesh.face_count().max(1);
    let faces: Vec<u32> = selection.iter().map(|&f| (f % nf) as u32).collect();
    let native = refiner::Refiner::new(mesh, options).and_then(|r| r.refine_adaptive(ao, &faces));
    let theirs = osd::TopologyRefiner::new(mesh, options).and_then(|mut r| {
        r.refine_adaptive(ao, &faces)?;
        Ok(r)
    });
    let (native, theirs) = match (native, theirs) {
        (Ok(a), Ok(b)) => (a, b),
        (Err(a), Err(b)) => {
            prop_assert_eq!(
                refusal_kind(&a),
                refusal_kind(&b),
                "native {:?} vs osd {:?}",
                a,
                b
            );
            return Ok(());
        }
        (a, b) => {
            return Err(TestCaseError::fail(format!(
                "native {:?} vs osd {:?}",
                a.err(),
                b.err()
            )));
        }
    };
    prop_assert_eq!(native.max_level(), theirs.max_level(), "levels refined");
    let mine = native.adaptive_levels(&mesh.positions).unwrap();
    let osds = theirs.adaptive_levels(&mesh.positions).unwrap();
    for c in compare_adaptive(&mine, &osds) {
        prop_assert!(
            c.identical(),
            "level {}: counts {:?}, first difference {:?}, positions {:?}",
            c.level,
            c.counts,
            c.first_difference,
            c.positions
        );
    }
    // Varying data too, bit for bit.
    let base: Vec<f64> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
    let (mut a, mut b) = (base.clone(), base);
    for level in 1..=native.max_level() {
        a = native.interpolate_varying(level, 3, &a).unwrap();
        b = theirs.interpolate_varying(level, 3, &b).unwrap();
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        prop_assert_eq!(bits(&a), bits(&b), "varying data of level {}", level);
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, .. ProptestConfig::default() })]

    #[test]
    fn structured_meshes_match(mesh in structured(), options in options(), level in 1u32..4, faces_first in any::<bool>()) {
        assert_same(&mesh, &options, level, faces_first)?;
    }

    #[test]
    fn polygon_soups_match(mesh in soup(), options in options(), level in 1u32..4, faces_first in any::<bool>()) {
        assert_same(&mesh, &options, level, faces_first)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, .. ProptestConfig::default() })]

    #[test]
    fn structured_meshes_match_adaptively(
        mesh in structured(),
        options in options(),
        ao in adaptive_options(),
        faces in selection(),
    ) {
        assert_same_adaptive(&mesh, &options, ao, &faces)?;
    }

    #[test]
    fn triangle_meshes_match_adaptively_under_loop(
        mesh in structured().prop_map(triangulated),
        options in options(),
        ao in adaptive_options(),
        faces in selection(),
    ) {
        assert_same_adaptive(&mesh, &options.with_scheme(Scheme::Loop), ao, &faces)?;
    }

    #[test]
    fn polygon_soups_match_adaptively(
        mesh in soup(),
        options in options(),
        ao in adaptive_options(),
        faces in selection(),
    ) {
        assert_same_adaptive(&mesh, &options, ao, &faces)?;
    }
}
