//! Property tests: random meshes, tags and options refine identically in the
//! native engine and in OpenSubdiv, uniformly and feature-adaptively (random
//! `AdaptiveOptions` and selected faces: levels, relations, child maps and
//! positions bit for bit).
#![cfg(feature = "osd")]

mod support;

use proptest::prelude::*;
use subdiv::compare::{compare, compare_adaptive};
use subdiv::{AdaptiveOptions, Error, Mesh, Options, Scheme, UniformOptions, osd, refiner};
use support::strategies::{options, soup, structured, triangulated};

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
