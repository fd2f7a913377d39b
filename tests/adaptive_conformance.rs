//! Native feature-adaptive refinement against OpenSubdiv's
//! `TopologyRefiner::RefineAdaptive`, element by element, over the corpus:
//! every scheme (Catmull-Clark, bilinear, Loop on the triangle meshes) × boundary
//! interpolation × option sets × isolation levels, and selected-face sets.
//! Levels (face-varying topology in every linear-interpolation mode
//! included), relations, rules and tags, parent-to-child maps, and positions,
//! varying data and face-varying values interpolated level by level must be
//! identical, bit for bit.
#![cfg(feature = "osd")]

use subdiv::refiner::{AdaptiveRefiner, Refiner};
use subdiv::{
    AdaptiveOptions, BoundaryInterpolation, FVarLinearInterpolation, Mesh, Options, Scheme, osd,
    shapes,
};

/// Compares the engines; returns the deepest level refined (0 also when
/// both refuse the mesh, as Loop refuses non-triangles: tested elsewhere).
fn compare(name: &str, mesh: &Mesh, options: &Options, ao: AdaptiveOptions, faces: &[u32]) -> u32 {
    let Ok(native) = Refiner::new(mesh, options) else {
        return 0;
    };
    let native: AdaptiveRefiner = native.refine_adaptive(ao, faces).unwrap();
    let mut theirs = osd::TopologyRefiner::new(mesh, options).unwrap();
    theirs.refine_adaptive(ao, faces).unwrap();
    let case = format!("{name} {options:?} {ao:?} faces {faces:?}");
    assert_eq!(native.max_level(), theirs.max_level(), "{case}");
    let base: Vec<f64> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
    let (mut mine, mut osds) = (base.clone(), base.clone());
    let (mut mine_var, mut osds_var) = (base.clone(), base);
    let mut channels: Vec<(Vec<f64>, Vec<f64>)> = mesh
        .fvar_channels
        .iter()
        .map(|c| (c.values.clone(), c.values.clone()))
        .collect();
    for level in 0..=native.max_level() {
        let (a, b) = (native.level(level).unwrap(), theirs.level(level).unwrap());
        assert_eq!(a, b, "{case}: level {level}");
        assert_eq!(
            native.relations(level).unwrap(),
            theirs.relations(level).unwrap(),
            "{case}: relations of level {level}"
        );
        if level < native.max_level() {
            assert_eq!(
                native.child_maps(level).unwrap(),
                theirs.child_maps(level).unwrap(),
                "{case}: child maps of level {level}"
            );
        }
        if level > 0 {
            mine = native.interpolate(level, 3, &mine).unwrap();
            osds = theirs.interpolate(level, 3, &osds).unwrap();
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(
                bits(&mine),
                bits(&osds),
                "{case}: positions of level {level}"
            );
            mine_var = native.interpolate_varying(level, 3, &mine_var).unwrap();
            osds_var = theirs.interpolate_varying(level, 3, &osds_var).unwrap();
            assert_eq!(
                bits(&mine_var),
                bits(&osds_var),
                "{case}: varying of level {level}"
            );
            for (k, (mine_fv, osds_fv)) in channels.iter_mut().enumerate() {
                let width = mesh.fvar_channels[k].width;
                *mine_fv = native
                    .interpolate_face_varying(k, level, width, mine_fv)
                    .unwrap();
                *osds_fv = theirs
                    .interpolate_face_varying(k, level, width, osds_fv)
                    .unwrap();
                assert_eq!(
                    bits(mine_fv),
                    bits(osds_fv),
                    "{case}: face-varying channel {k} of level {level}"
                );
            }
        }
    }
    native.max_level()
}

fn option_sets(isolation: u32) -> [AdaptiveOptions; 5] {
    let ao = AdaptiveOptions::new(isolation);
    [
        ao,
        ao.secondary(1),
        ao.single_crease_patch(true),
        ao.inf_sharp_patch(true).single_crease_patch(true),
        ao.faces_first(true),
    ]
}

#[test]
fn corpus_matches_opensubdiv() {
    // Levels refined per scheme: each scheme must really be exercised.
    let mut levels = [0u32; 3];
    for (name, mesh) in shapes::corpus() {
        for scheme in [Scheme::Catmark, Scheme::Bilinear, Scheme::Loop] {
            for boundary in [
                BoundaryInterpolation::None,
                BoundaryInterpolation::EdgeOnly,
                BoundaryInterpolation::EdgeAndCorner,
            ] {
                let options = Options::shape_file_defaults()
                    .with_scheme(scheme)
                    .with_boundary(boundary);
                for isolation in [1, 3, 6] {
                    for ao in option_sets(isolation) {
                        levels[scheme.code() as usize] += compare(&name, &mesh, &options, ao, &[]);
                    }
                }
                // Face-varying channels refine sparsely in every mode.
                if !mesh.fvar_channels.is_empty() {
                    for fvar in [
                        FVarLinearInterpolation::None,
                        FVarLinearInterpolation::CornersOnly,
                        FVarLinearInterpolation::CornersPlus1,
                        FVarLinearInterpolation::CornersPlus2,
                        FVarLinearInterpolation::Boundaries,
                    ] {
                        let options = options.with_fvar(fvar);
                        for ao in [
                            AdaptiveOptions::new(2),
                            AdaptiveOptions::new(4).faces_first(true),
                            AdaptiveOptions::new(3).consider_fvar(true),
                            AdaptiveOptions::new(4)
                                .consider_fvar(true)
                                .inf_sharp_patch(true)
                                .secondary(2),
                        ] {
                            compare(&name, &mesh, &options, ao, &[]);
                        }
                    }
                }
            }
        }
    }
    assert!(
        levels.iter().all(|&l| l > 100),
        "levels refined per scheme: {levels:?}"
    );
}

/// Selected faces: every third face, the last face, and a pseudo-random
/// subset with repeats, at isolation 2 and 4.
#[test]
fn selected_faces_match_opensubdiv() {
    let options = Options::shape_file_defaults();
    for (name, mesh) in shapes::corpus() {
        let n = mesh.face_count() as u32;
        let mut state = 0x9e37_79b9u32 ^ n;
        let mut random = Vec::new();
        for _ in 0..n.div_ceil(2) {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            random.push((state >> 8) % n);
        }
        let sets = [(0..n).step_by(3).collect::<Vec<_>>(), vec![n - 1], random];
        for faces in &sets {
            for isolation in [2, 4] {
                compare(
                    &name,
                    &mesh,
                    &options,
                    AdaptiveOptions::new(isolation),
                    faces,
                );
            }
        }
    }
}

/// `compare::compare_adaptive` over `adaptive_levels` of both engines: equal
/// on the corpus; a changed table is found at its first differing element.
#[test]
fn compare_adaptive_finds_the_first_difference() {
    use subdiv::compare::{TableDifference, compare_adaptive};
    let options = Options::shape_file_defaults();
    for (name, mesh) in shapes::corpus() {
        let ao = AdaptiveOptions::new(3);
        let Ok(native) = Refiner::new(&mesh, &options) else {
            continue;
        };
        let native = native
            .refine_adaptive(ao, &[])
            .unwrap()
            .adaptive_levels(&mesh.positions)
            .unwrap();
        let mut theirs = osd::TopologyRefiner::new(&mesh, &options).unwrap();
        theirs.refine_adaptive(ao, &[]).unwrap();
        let theirs = theirs.adaptive_levels(&mesh.positions).unwrap();
        for c in compare_adaptive(&native, &theirs) {
            assert!(c.identical(), "{name}: {c:?}");
        }
    }
    let cube = shapes::cube();
    let levels = Refiner::new(&cube, &options)
        .unwrap()
        .refine_adaptive(AdaptiveOptions::new(2), &[])
        .unwrap()
        .adaptive_levels(&cube.positions)
        .unwrap();
    let mut changed = levels.clone();
    changed[1].topology.face_vertices[9] += 1; // face 2 (4 corners each)
    changed[1].relations.vertex_edges[0] += 1;
    changed[0].child_maps.as_mut().unwrap().edge_child_vertex[5] = 0;
    changed[2].positions[7].y += 1e-12;
    let c = compare_adaptive(&levels, &changed);
    let diff = |table, index| Some(TableDifference { table, index });
    assert_eq!(c[0].first_difference, diff("edge_child_vertex", 5));
    assert_eq!(c[1].first_difference, diff("face_vertices", 2));
    assert!(c[1].positions.identical());
    assert_eq!(c[2].first_difference, None);
    assert_eq!(c[2].positions.first_difference, Some(7));
    assert_eq!(c[2].positions.worst, Some(7));
    // A level only one side has.
    let c = compare_adaptive(&levels, &levels[..2]);
    assert_eq!(c.len(), 3);
    assert_eq!(c[2].first_difference, diff("vertex_count", 0));
}
