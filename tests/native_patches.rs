//! Native patch tables (`AdaptiveRefiner::patch_table`) against
//! OpenSubdiv's `Far::PatchTableFactory`, over the corpus: every scheme ×
//! boundary interpolation × adaptive and patch options × isolation levels ×
//! selected faces. Arrays, types, control vertices, `PatchParam` words,
//! sharpness, the legacy Gregory quad-offset and valence tables, and the
//! local points' stencils (Catmull-Clark and Loop end caps of every type),
//! and the face-varying patch channels — linear and non-linear, with their
//! own local points' stencils — must be identical.
#![cfg(feature = "osd")]

use subdiv::patches::{EndCapType, PatchOptions, PatchTable, PatchType};
use subdiv::refiner::Refiner;
use subdiv::{AdaptiveOptions, BoundaryInterpolation, Error, Mesh, Options, Scheme, osd, shapes};

/// What one comparison found.
#[derive(Default, Debug)]
struct Tally {
    identical: usize,
    patches: usize,
    legacy_irregular: usize,
    single_crease: usize,
    refused_both: usize,
    osd_unsafe: usize,
    local_points: usize,
    carried_sharpness: usize,
    carried_boundary: usize,
    not_yet_fvar: usize,
    fvar_patches: usize,
    /// Loop end caps compared: Gregory triangles, irregular box-spline
    /// patches, linear triangles, and the local points of Loop tables.
    loop_gregory: usize,
    loop_box_spline: usize,
    loop_linear: usize,
    loop_local_points: usize,
    /// Non-linear face-varying patches compared: regular ones, irregular
    /// ones (end caps, with local points unless legacy Gregory), and the
    /// channels' local points.
    fvar_regular: usize,
    fvar_irregular: usize,
    fvar_local_points: usize,
    /// Under Loop: non-linear face-varying irregular patches and local
    /// points.
    loop_fvar_irregular: usize,
    loop_fvar_local_points: usize,
}

fn compare(
    name: &str,
    mesh: &Mesh,
    options: &Options,
    po: &PatchOptions,
    faces: &[u32],
    t: &mut Tally,
) {
    compare_refined(
        name,
        mesh,
        options,
        po.refine_adaptive_options(),
        po,
        faces,
        t,
    );
}

/// As [`compare`], with the refinement's own adaptive options (which
/// OpenSubdiv does not require to match the table's).
fn compare_refined(
    name: &str,
    mesh: &Mesh,
    options: &Options,
    ao: AdaptiveOptions,
    po: &PatchOptions,
    faces: &[u32],
    t: &mut Tally,
) {
    let Ok(native) = Refiner::new(mesh, options) else {
        return;
    };
    let Ok(native) = native.refine_adaptive(ao, faces) else {
        return;
    };
    let mut theirs = osd::TopologyRefiner::new(mesh, options).unwrap();
    theirs.refine_adaptive(ao, faces).unwrap();
    let case = format!("{name} {options:?} {po:?} faces {faces:?}");
    let mine = native.patch_table(po, faces);
    let osds = theirs.patch_table(po, faces);
    match (mine, osds) {
        (Ok(a), Ok(b)) => {
            same_table(&a, b.table(), &case);
            t.identical += 1;
            t.patches += a.patch_count();
            t.fvar_patches += a
                .fvar_channels
                .iter()
                .map(|c| c.params.len())
                .sum::<usize>();
            t.local_points += a.local_points;
            let nonlinear = !po.fvar_legacy_linear_patches;
            for c in a.fvar_channels.iter().filter(|_| nonlinear) {
                let irregular = c.params.iter().filter(|p| !p.is_regular()).count();
                t.fvar_irregular += irregular;
                t.fvar_regular += c.params.len() - irregular;
                t.fvar_local_points += c.local_point_stencils.sizes.len();
                if options.scheme == Scheme::Loop {
                    t.loop_fvar_irregular += irregular;
                    t.loop_fvar_local_points += c.local_point_stencils.sizes.len();
                }
            }
            if options.scheme == Scheme::Loop {
                t.loop_local_points += a.local_points;
                for arr in &a.arrays {
                    match arr.patch_type {
                        PatchType::GregoryTriangle => t.loop_gregory += arr.len(),
                        PatchType::Loop => {
                            t.loop_box_spline +=
                                arr.params.iter().filter(|p| !p.is_regular()).count()
                        }
                        PatchType::Triangles => t.loop_linear += arr.len(),
                        _ => {}
                    }
                }
            }
            if !a.quad_offsets.is_empty() {
                t.legacy_irregular += 1;
            }
            if a.arrays
                .iter()
                .any(|a| a.sharpness.iter().any(|&s| s > 0.0))
            {
                t.single_crease += 1;
            }
            // OpenSubdiv's values carried over from the previous patch: the
            // sharpness of an irregular patch, the boundary bits of a legacy
            // Gregory patch.
            for arr in &a.arrays {
                for (p, &s) in arr.params.iter().zip(&arr.sharpness) {
                    t.carried_sharpness += usize::from(!p.is_regular() && s > 0.0);
                    t.carried_boundary += usize::from(!p.is_regular() && p.boundary() != 0);
                }
            }
        }
        (Err(Error::NotYetSupported(_)), Ok(b))
            if po.fvar_tables
                && !po.fvar_legacy_linear_patches
                && !b.table().fvar_channels.is_empty() =>
        {
            // Non-linear face-varying patches (none left: asserted 0).
            t.not_yet_fvar += 1;
        }
        (Err(Error::PatchOptions { .. }), Err(Error::Osd(_))) => t.refused_both += 1,
        // Where OpenSubdiv would overrun its buffers (a face repeating a
        // vertex) the bridge refuses; the native engine builds the table
        // or says what it does not build yet.
        (Ok(_) | Err(Error::NotYetSupported(_)), Err(Error::Osd(e)))
            if e.kind == subdiv::OsdErrorKind::Unsafe =>
        {
            t.osd_unsafe += 1
        }
        (a, b) => panic!(
            "{case}: native {a:?}, osd {:?}",
            b.map(|b| b.table().clone())
        ),
    }
}

fn same_table(a: &PatchTable, b: &PatchTable, case: &str) {
    assert_eq!(a.arrays.len(), b.arrays.len(), "{case}: arrays");
    for (i, (x, y)) in a.arrays.iter().zip(&b.arrays).enumerate() {
        assert_eq!(x.patch_type, y.patch_type, "{case}: type of array {i}");
        assert_eq!(x.len(), y.len(), "{case}: patches of array {i}");
        for p in 0..x.len() {
            assert_eq!(
                x.patch_vertices(p),
                y.patch_vertices(p),
                "{case}: control vertices of patch {p} of array {i}"
            );
            assert_eq!(
                x.params[p], y.params[p],
                "{case}: param of patch {p} of array {i}"
            );
            assert_eq!(
                x.sharpness[p].to_bits(),
                y.sharpness[p].to_bits(),
                "{case}: sharpness of patch {p} of array {i}"
            );
            assert_eq!(
                x.patch_varying_vertices(p),
                y.patch_varying_vertices(p),
                "{case}: varying vertices of patch {p} of array {i}"
            );
        }
        assert_eq!(
            x.varying_vertices.len(),
            y.varying_vertices.len(),
            "{case}: varying vertices of array {i}"
        );
    }
    for (name, x, y) in [
        (
            "local points",
            &a.local_point_stencils,
            &b.local_point_stencils,
        ),
        (
            "varying local points",
            &a.local_point_varying_stencils,
            &b.local_point_varying_stencils,
        ),
    ] {
        assert_eq!(x.sizes, y.sizes, "{case}: sizes of the {name}' stencils");
        assert_eq!(
            x.indices, y.indices,
            "{case}: indices of the {name}' stencils"
        );
        if let Some(k) =
            (0..x.weights.len()).find(|&k| x.weights[k].to_bits() != y.weights[k].to_bits())
        {
            panic!(
                "{case}: weight {k} of the {name}' stencils: {} against {}",
                x.weights[k], y.weights[k]
            );
        }
    }
    assert_eq!(
        a.fvar_channels.len(),
        b.fvar_channels.len(),
        "{case}: face-varying channels"
    );
    for (k, (x, y)) in a.fvar_channels.iter().zip(&b.fvar_channels).enumerate() {
        let head = |c: &subdiv::patches::FVarPatches| {
            (c.channel, c.regular_type, c.irregular_type, c.stride)
        };
        assert_eq!(head(x), head(y), "{case}: face-varying channel {k}");
        assert_eq!(x.params, y.params, "{case}: params of channel {k}");
        assert_eq!(x.values, y.values, "{case}: values of channel {k}");
        let (xs, ys) = (&x.local_point_stencils, &y.local_point_stencils);
        assert_eq!(xs.sizes, ys.sizes, "{case}: stencil sizes of channel {k}");
        assert_eq!(xs.indices, ys.indices, "{case}: stencils of channel {k}");
        if let Some(i) =
            (0..xs.weights.len()).find(|&i| xs.weights[i].to_bits() != ys.weights[i].to_bits())
        {
            panic!(
                "{case}: weight {i} of channel {k}'s local points: {} against {}",
                xs.weights[i], ys.weights[i]
            );
        }
    }
    assert_eq!(a.quad_offsets, b.quad_offsets, "{case}: quad offsets");
    assert_eq!(
        a.vertex_valences, b.vertex_valences,
        "{case}: vertex valences"
    );
    let rest = |t: &PatchTable| {
        (
            t.local_points,
            t.local_points_varying,
            t.max_valence,
            t.ptex_faces,
            t.feature_adaptive,
            t.varying_patch_type,
        )
    };
    assert_eq!(rest(a), rest(b), "{case}: the rest of the table");
    assert_eq!(a, b, "{case}");
}

fn patch_option_sets(isolation: u32) -> Vec<PatchOptions> {
    let o = PatchOptions::new().max_isolation(isolation);
    let mut sets = Vec::new();
    for end_caps in [
        EndCapType::LegacyGregory,
        EndCapType::GregoryBasis,
        EndCapType::BilinearBasis,
        EndCapType::BSplineBasis,
    ] {
        let o = o.clone().end_caps(end_caps);
        sets.push(o.clone());
        sets.push(o.clone().single_crease_patch(true));
        sets.push(o.clone().inf_sharp_patch(true));
        sets.push(o.clone().inf_sharp_patch(true).single_crease_patch(true));
        sets.push(PatchOptions {
            legacy_sharp_corner_patches: false,
            ..o.clone()
        });
        sets.push(PatchOptions {
            share_end_cap_points: false,
            varying_local_points: false,
            ..o.clone().double_precision(true)
        });
    }
    // Face-varying patches: OpenSubdiv's default legacy linear ones, and its
    // non-linear ones.
    let fvar = PatchOptions {
        fvar_tables: true,
        ..o.clone()
    };
    sets.push(fvar.clone());
    sets.push(PatchOptions {
        fvar_legacy_linear_patches: false,
        ..fvar
    });
    sets
}

#[test]
fn corpus_tables_match_opensubdiv() {
    let mut t = Tally::default();
    for (name, mesh) in shapes::corpus() {
        for scheme in [Scheme::Catmark, Scheme::Bilinear, Scheme::Loop] {
            for boundary in [
                BoundaryInterpolation::EdgeOnly,
                BoundaryInterpolation::EdgeAndCorner,
            ] {
                let options = Options::shape_file_defaults()
                    .with_scheme(scheme)
                    .with_boundary(boundary);
                for isolation in [1, 2, 4] {
                    for po in patch_option_sets(isolation) {
                        compare(&name, &mesh, &options, &po, &[], &mut t);
                    }
                }
            }
        }
    }
    // Tables whose options differ from the refinement's: a deeper maximum
    // isolation lets last-level patches be single-crease ones, whose
    // sharpness OpenSubdiv carries over to the irregular patch after them.
    for (name, mesh) in shapes::corpus() {
        let options = Options::shape_file_defaults();
        for end_caps in [EndCapType::GregoryBasis, EndCapType::LegacyGregory] {
            for isolation in [1, 2] {
                let ao = AdaptiveOptions::new(isolation).single_crease_patch(true);
                let po = PatchOptions::new()
                    .max_isolation(isolation + 2)
                    .end_caps(end_caps)
                    .single_crease_patch(true);
                compare_refined(&name, &mesh, &options, ao, &po, &[], &mut t);
            }
        }
    }
    eprintln!("{t:?}");
    // Every kind of table must really be compared.
    assert!(t.identical > 500 && t.patches > 100_000, "{t:?}");
    assert!(t.legacy_irregular > 50 && t.single_crease > 10, "{t:?}");
    assert!(t.local_points > 100_000, "{t:?}");
    assert!(t.carried_sharpness > 0 && t.carried_boundary > 0, "{t:?}");
    assert!(t.fvar_patches > 10_000, "{t:?}");
    // The shape files' channels are linear everywhere: the non-linear
    // patches are compared in `face_varying_tables_match_opensubdiv`.
    assert_eq!(t.not_yet_fvar, 0, "{t:?}");
    // Loop's end caps of every type, with their local points.
    assert!(t.loop_gregory > 1000 && t.loop_box_spline > 1000, "{t:?}");
    assert!(
        t.loop_linear > 1000 && t.loop_local_points > 10_000,
        "{t:?}"
    );
}

/// Face-varying patches in every face-varying interpolation mode, legacy
/// linear and non-linear (the channel's own regular patches and end caps
/// of every type, with their local points), over meshes with UV seams:
/// identical to OpenSubdiv's.
#[test]
fn face_varying_tables_match_opensubdiv() {
    use subdiv::FVarLinearInterpolation as F;
    let mut meshes: Vec<(String, Mesh)> = shapes::corpus()
        .into_iter()
        .filter(|(_, m)| !m.fvar_channels.is_empty())
        .collect();
    meshes.push(("cube with uvs".into(), shapes::cube_with_uvs()));
    meshes.push((
        "torus with uvs".into(),
        shapes::with_torus_uvs(shapes::torus(6, 5), 6, 5),
    ));
    meshes.push(("production".into(), shapes::production(8, 6)));
    meshes.push((
        "mixed torus with uvs".into(),
        shapes::with_torus_uvs(shapes::torus_mixed(6, 5), 6, 5),
    ));
    // Triangles, for Loop's face-varying patches.
    meshes.push((
        "triangle torus with uvs".into(),
        shapes::with_torus_uvs(shapes::torus_triangles(6, 5), 6, 5),
    ));
    // Two channels, tables of some of them: OpenSubdiv's regularity test
    // reads the refiner's channel numbered as the table's.
    let mut two = shapes::with_torus_uvs(shapes::torus_mixed(6, 5), 6, 5);
    two.fvar_channels.insert(
        0,
        subdiv::FVarChannel {
            width: 3,
            values: two.flat_positions::<f64>(),
            indices: two.face_vertices.clone(),
        },
    );
    let mut total = Tally::default();
    for fvar in [F::CornersOnly, F::Boundaries] {
        let options = Options::shape_file_defaults().with_fvar(fvar);
        for channels in [vec![1], vec![1, 0], vec![0, 1], vec![1, 1]] {
            let po = PatchOptions {
                fvar_tables: true,
                fvar_legacy_linear_patches: false,
                fvar_channels: channels,
                ..PatchOptions::new().max_isolation(2)
            };
            compare("two channels", &two, &options, &po, &[], &mut total);
        }
    }
    assert_eq!(total.identical, 8, "{total:?}");
    for fvar in [
        F::None,
        F::CornersOnly,
        F::CornersPlus1,
        F::CornersPlus2,
        F::Boundaries,
        F::All,
    ] {
        let mut t = Tally::default();
        for (name, mesh) in &meshes {
            for scheme in [Scheme::Catmark, Scheme::Loop] {
                let options = Options::shape_file_defaults()
                    .with_scheme(scheme)
                    .with_fvar(fvar);
                for legacy in [true, false] {
                    for isolation in [1, 3] {
                        let base = PatchOptions {
                            fvar_tables: true,
                            fvar_legacy_linear_patches: legacy,
                            ..PatchOptions::new().max_isolation(isolation)
                        };
                        let mut sets = vec![base.clone()];
                        if !legacy {
                            for end_caps in [
                                EndCapType::BSplineBasis,
                                EndCapType::BilinearBasis,
                                EndCapType::LegacyGregory,
                            ] {
                                sets.push(base.clone().end_caps(end_caps));
                            }
                            sets.push(base.clone().inf_sharp_patch(true).single_crease_patch(true));
                            sets.push(PatchOptions {
                                share_end_cap_points: false,
                                legacy_sharp_corner_patches: false,
                                fvar_patch_precision_double: true,
                                ..base.clone()
                            });
                        }
                        for po in sets {
                            compare(name, mesh, &options, &po, &[], &mut t);
                        }
                    }
                }
            }
        }
        eprintln!("{fvar:?}: {t:?}");
        assert_eq!(t.not_yet_fvar, 0, "{fvar:?}: {t:?}");
        if fvar != F::All {
            // Non-linear patches, regular and irregular, with local points.
            assert!(
                t.fvar_regular > 1000 && t.fvar_irregular > 100 && t.fvar_local_points > 1000,
                "{fvar:?}: {t:?}"
            );
        }
        total.fvar_patches += t.fvar_patches;
        total.loop_fvar_irregular += t.loop_fvar_irregular;
        total.loop_fvar_local_points += t.loop_fvar_local_points;
    }
    assert!(total.fvar_patches > 50_000, "{total:?}");
    assert!(
        total.loop_fvar_irregular > 100 && total.loop_fvar_local_points > 1000,
        "{total:?}"
    );
}

/// Tables of selected faces, depth first under each face.
#[test]
fn selected_face_tables_match_opensubdiv() {
    let mut t = Tally::default();
    let options = Options::shape_file_defaults();
    for (name, mesh) in shapes::corpus() {
        let n = mesh.face_count() as u32;
        let sets = [(0..n).step_by(3).collect::<Vec<_>>(), vec![n - 1]];
        for faces in &sets {
            for po in patch_option_sets(3) {
                compare(&name, &mesh, &options, &po, faces, &mut t);
            }
        }
    }
    eprintln!("{t:?}");
    assert!(t.identical > 50, "{t:?}");
}

/// The limit surface from native tables (native refinement, local points,
/// `PatchMap` and basis) against OpenSubdiv's `EvaluateBasis` on its own
/// tables: positions alone, with first derivatives and with second
/// derivatives, within 1e-12 of the mesh's size, at u, v ∈ {0, 0.3, 0.5, 1}
/// on every ptex face. Under Loop, the regular patches' positions and first
/// derivatives come from their polynomials, with the phantom points of
/// boundary patches folded in. A Loop mesh's faces are triangles: only
/// the locations on them (u + v ≤ 1) are compared (past the triangle,
/// where the surface is extrapolated, the derivatives of Gregory
/// triangles differ from OpenSubdiv's by up to about 2e-12 of the mesh's
/// size, before and after the polynomials).
#[test]
fn native_evaluation_matches_opensubdiv() {
    use subdiv::patches::{self, Derivatives};
    let mut compared = 0usize;
    for (name, mesh) in shapes::corpus() {
        for scheme in [Scheme::Catmark, Scheme::Bilinear, Scheme::Loop] {
            let options = Options::shape_file_defaults().with_scheme(scheme);
            for end_caps in [
                EndCapType::GregoryBasis,
                EndCapType::BSplineBasis,
                EndCapType::BilinearBasis,
            ] {
                let po = PatchOptions::new()
                    .max_isolation(3)
                    .end_caps(end_caps)
                    .double_precision(true);
                let Ok(native) = Refiner::new(&mesh, &options) else {
                    continue;
                };
                let native = native
                    .refine_adaptive(po.refine_adaptive_options(), &[])
                    .unwrap();
                let mut theirs = osd::TopologyRefiner::new(&mesh, &options).unwrap();
                theirs
                    .refine_adaptive(po.refine_adaptive_options(), &[])
                    .unwrap();
                let (Ok(mine), Ok(osds)) =
                    (native.patch_table(&po, &[]), theirs.patch_table(&po, &[]))
                else {
                    continue;
                };
                let base = mesh.flat_positions::<f64>();
                let points = native.patch_points(&mine, 3, &base).unwrap();
                let mut locations = Vec::new();
                for face in 0..mine.ptex_faces as u32 {
                    for u in [0.0, 0.3, 0.5, 1.0] {
                        for v in [0.0, 0.3, 0.5, 1.0] {
                            if scheme != Scheme::Loop || u + v <= 1.0 {
                                locations.push((face, u, v));
                            }
                        }
                    }
                }
                // Each set of derivatives: positions alone and with first
                // derivatives take the native B-spline patches' curve sums,
                // second derivatives their sixteen weights.
                for derivatives in [Derivatives::None, Derivatives::First, Derivatives::Second] {
                    let a = patches::evaluate(&mine, &points, 3, &locations, derivatives);
                    let b = osds.evaluate(&theirs, 3, &base, &locations, derivatives);
                    let case = format!("{name} {scheme:?} {end_caps:?} {derivatives:?}");
                    let (a, b) = match (a, b) {
                        (Ok(a), Ok(b)) => (a, b),
                        // Holes: both refuse the same location.
                        (Err(Error::NoPatchAt { .. }), Err(Error::NoPatchAt { .. })) => continue,
                        (a, b) => panic!("{case}: native {a:?}, osd {b:?}"),
                    };
                    let size = mesh
                        .positions
                        .iter()
                        .fold(0.0f64, |m, p| m.max(p.abs().max_element()))
                        .max(1.0);
                    for (what, x, y) in [
                        ("point", &a.values.point, &b.values.point),
                        ("du", &a.values.du, &b.values.du),
                        ("dv", &a.values.dv, &b.values.dv),
                        ("duu", &a.values.duu, &b.values.duu),
                        ("duv", &a.values.duv, &b.values.duv),
                        ("dvv", &a.values.dvv, &b.values.dvv),
                    ] {
                        assert_eq!(x.len(), y.len(), "{case}: {what}");
                        for (k, (p, q)) in x.iter().zip(y).enumerate() {
                            assert!(
                                (p - q).abs() <= 1e-12 * size,
                                "{case}: {what} {k} of location {:?}: {p} against {q}",
                                locations[k / 3]
                            );
                        }
                    }
                    assert_eq!(a.values.point.len(), 3 * locations.len(), "{case}");
                    compared += locations.len();
                }
            }
        }
    }
    assert!(compared > 10_000, "{compared} locations compared");
}

/// Found by fuzzing: two triangles folded onto each other (interior
/// vertices of valence 2, one of them a dart once creased), bilinear end
/// caps. The source patch of an end cap next to such corners names a point
/// past its own count; OpenSubdiv writes that point into its buffer and its
/// matrix reads it back, and the native table must do the same to be
/// identical.
#[test]
fn folded_triangles_with_bilinear_end_caps_match_opensubdiv() {
    use glam::DVec3;
    use subdiv::{Corner, Crease, CreasingMethod, FVarLinearInterpolation};
    let positions = (0..5)
        .map(|i| DVec3::new(i as f64, (i * i) as f64 * 0.5, 1.0 - i as f64))
        .collect();
    let mut mesh = Mesh::from_faces(positions, &[&[0, 3, 1], &[1, 3, 0]]);
    for (vertices, sharpness) in [
        ([3, 1], 1.5),
        ([3, 1], 3.25),
        ([0, 0], 0.5),
        ([3, 1], 11.0),
        ([1, 0], 1e-7),
    ] {
        mesh.creases.push(Crease {
            vertices,
            sharpness,
        });
    }
    for (vertex, sharpness) in [(2, 0.5), (0, 0.0), (4, 0.0)] {
        mesh.corners.push(Corner { vertex, sharpness });
    }
    mesh.holes.push(0);
    let options = Options::shape_file_defaults()
        .with_boundary(BoundaryInterpolation::None)
        .with_fvar(FVarLinearInterpolation::Boundaries)
        .with_creasing(CreasingMethod::Chaikin);
    let ao = AdaptiveOptions::new(4)
        .secondary(2)
        .single_crease_patch(true)
        .inf_sharp_patch(true)
        .consider_fvar(true)
        .faces_first(true);
    let po = PatchOptions {
        legacy_sharp_corner_patches: false,
        ..PatchOptions::new()
            .max_isolation(4)
            .end_caps(EndCapType::BilinearBasis)
            .single_crease_patch(true)
            .inf_sharp_patch(true)
    };
    let mut t = Tally::default();
    compare_refined(
        "folded triangles",
        &mesh,
        &options,
        ao,
        &po,
        &[1, 0],
        &mut t,
    );
    assert_eq!(t.identical, 1, "{t:?}");
    assert!(t.local_points > 0, "{t:?}");
}

/// Loop end caps at the corners the corpus has few of: interior vertices
/// of valence 2 (two triangles folded onto each other, whose source
/// patches repeat points), single faces, a non-manifold edge, darts and
/// infinitely sharp creases and corners, with every end-cap type, both
/// precisions, shared points or not — identical to OpenSubdiv's tables
/// (where the bridge builds them: not B-spline end caps around an interior
/// vertex of valence 2).
#[test]
fn loop_end_caps_at_odd_corners_match_opensubdiv() {
    use glam::DVec3;
    use subdiv::{Corner, Crease};
    let points = |n: usize| {
        (0..n)
            .map(|i| DVec3::new(i as f64, (i * i) as f64 * 0.5, 1.0 - i as f64))
            .collect::<Vec<_>>()
    };
    let mut meshes = vec![
        Mesh::from_faces(points(3), &[&[0, 1, 2], &[0, 2, 1]]),
        Mesh::from_faces(points(4), &[&[0, 1, 2], &[0, 2, 1], &[1, 3, 2]]),
        Mesh::from_faces(points(5), &[&[0, 1, 2], &[0, 3, 4]]),
        Mesh::from_faces(points(3), &[&[0, 1, 2]]),
        Mesh::from_faces(points(5), &[&[0, 1, 2], &[1, 0, 3], &[0, 1, 4]]),
    ];
    let fan = |n: usize| {
        let faces: Vec<[u32; 3]> = (0..n as u32)
            .map(|i| [0, 1 + i, 1 + (i + 1) % n as u32])
            .collect();
        let faces: Vec<&[u32]> = faces.iter().map(|f| &f[..]).collect();
        Mesh::from_faces(points(n + 1), &faces)
    };
    let mut creased = fan(4);
    creased.creases.push(Crease {
        vertices: [0, 2],
        sharpness: 10.0,
    });
    creased.corners.push(Corner {
        vertex: 0,
        sharpness: 2.0,
    });
    let mut dart = fan(5);
    dart.creases.push(Crease {
        vertices: [0, 2],
        sharpness: 10.0,
    });
    meshes.extend([creased, dart]);
    let mut t = Tally::default();
    for mesh in &meshes {
        for boundary in [
            BoundaryInterpolation::None,
            BoundaryInterpolation::EdgeOnly,
            BoundaryInterpolation::EdgeAndCorner,
        ] {
            let options = Options::shape_file_defaults()
                .with_scheme(Scheme::Loop)
                .with_boundary(boundary);
            for isolation in [1, 3] {
                for end_caps in [
                    EndCapType::GregoryBasis,
                    EndCapType::BSplineBasis,
                    EndCapType::BilinearBasis,
                    EndCapType::None,
                ] {
                    let o = PatchOptions::new()
                        .max_isolation(isolation)
                        .end_caps(end_caps);
                    for po in [
                        o.clone().inf_sharp_patch(true).single_crease_patch(true),
                        PatchOptions {
                            legacy_sharp_corner_patches: false,
                            share_end_cap_points: false,
                            ..o.clone().double_precision(true)
                        },
                    ] {
                        compare(&format!("{mesh:?}"), mesh, &options, &po, &[], &mut t);
                    }
                }
            }
        }
    }
    eprintln!("{t:?}");
    assert!(t.identical > 250 && t.osd_unsafe > 0, "{t:?}");
    assert!(
        t.loop_gregory > 0 && t.loop_box_spline > 0 && t.loop_linear > 0,
        "{t:?}"
    );
}

/// Found by fuzzing: two triangles folded onto each other, one a hole, left
/// unrefined (secondary level 0). OpenSubdiv reads the end cap's source
/// points from uninitialised memory there (a local-point stencil naming
/// vertex 941292184, and its limit stencils reading out of bounds): the
/// bridge refuses; the native engine builds every end-cap type from the
/// level's points.
#[test]
fn folded_loop_triangles_left_unrefined_are_refused_by_the_bridge() {
    use glam::DVec3;
    let positions = vec![
        DVec3::new(-1.4375, 0.0, 5.4375),
        DVec3::new(-5.125, 6.0625, -5.0),
        DVec3::new(-4.4375, 5.75, -2.6875),
        DVec3::new(-1.4375, 0.0, -7.5),
    ];
    let mut mesh = Mesh::from_faces(positions, &[&[0, 3, 1], &[1, 3, 0]]);
    mesh.holes.push(0);
    let options = Options::shape_file_defaults().with_scheme(Scheme::Loop);
    let ao = AdaptiveOptions::new(6).secondary(0);
    for end_caps in [
        EndCapType::GregoryBasis,
        EndCapType::BSplineBasis,
        EndCapType::BilinearBasis,
    ] {
        let po = PatchOptions::new().max_isolation(6).end_caps(end_caps);
        refused_by_the_bridge(&mesh, &options, ao, &po, 1);
    }
}

/// After refining `mesh` adaptively with `ao`, the native engine builds
/// `po`'s table (with local points) and limit stencils at ptex face `face`;
/// the bridge refuses both as unsafe. Returns the bridge's refusal of the
/// table.
fn refused_by_the_bridge(
    mesh: &Mesh,
    options: &Options,
    ao: AdaptiveOptions,
    po: &PatchOptions,
    face: u32,
) -> Error {
    use subdiv::patches::LimitStencilOptions;
    let native = Refiner::new(mesh, options)
        .unwrap()
        .refine_adaptive(ao, &[])
        .unwrap();
    let mut theirs = osd::TopologyRefiner::new(mesh, options).unwrap();
    theirs.refine_adaptive(ao, &[]).unwrap();
    let unsafe_refusal =
        |e: &Error| matches!(e, Error::Osd(o) if o.kind == subdiv::OsdErrorKind::Unsafe);
    let table = native.patch_table(po, &[]).unwrap();
    assert!(table.local_points > 0, "{po:?}");
    let Err(e) = theirs.patch_table(po, &[]) else {
        panic!("{po:?}: the bridge built the table");
    };
    assert!(unsafe_refusal(&e), "{po:?}: {e}");
    let at = [(face, 0.25, 0.5)];
    let o = LimitStencilOptions::new();
    assert_eq!(native.location_stencils(&at, &o).unwrap().len(), 1);
    assert!(unsafe_refusal(
        &theirs.location_stencils(&at, &o).unwrap_err()
    ));
    e
}

/// An n-gon and a quad folded onto it along two edges at vertex 0, an
/// interior vertex of valence 2, one of whose edges is infinitely sharp (a
/// dart). Beside it a Gregory patch's corner ring names one source point
/// past the patch's count: OpenSubdiv writes it into its 64-entry buffer
/// and reads it back, and the native tables do the same — identical on the
/// hexagon. The 40-gon's patch beside the dart gathers more than 64 points,
/// OpenSubdiv's buffer is then on the heap and the write lands past it
/// (Valgrind): the bridge refuses it (tables and limit stencils), the native
/// engine builds both.
#[test]
fn valence2_darts_beside_large_faces_are_refused_by_the_bridge() {
    let options = Options::default().with_boundary(BoundaryInterpolation::EdgeOnly);
    let ao = AdaptiveOptions::new(1).inf_sharp_patch(true);
    for n in [6u32, 40] {
        let positions = (0..=n)
            .map(|i| {
                let a = std::f64::consts::TAU * f64::from(i) / f64::from(n);
                let r = if i == n { 0.5 } else { 1.0 };
                glam::DVec3::new(r * a.cos(), r * a.sin(), 0.1 * f64::from(i % 3))
            })
            .collect();
        let ngon: Vec<u32> = (0..n).collect();
        let mut mesh = Mesh::from_faces(positions, &[&ngon, &[1, 0, n - 1, n]]);
        mesh.add_crease(0, n - 1, 10.0);
        for end_caps in [EndCapType::GregoryBasis, EndCapType::BilinearBasis] {
            let po = PatchOptions::new()
                .max_isolation(1)
                .inf_sharp_patch(true)
                .end_caps(end_caps);
            if n == 6 {
                let mut t = Tally::default();
                compare_refined("hexagon dart", &mesh, &options, ao, &po, &[], &mut t);
                assert_eq!((t.identical, t.osd_unsafe), (1, 0), "{end_caps:?}");
                assert!(t.local_points > 0);
                continue;
            }
            let e = refused_by_the_bridge(&mesh, &options, ao, &po, 0);
            assert!(e.to_string().contains("valence 2"), "{e}");
        }
    }
}

/// Uniform patch tables (`BuildUniformPolygons`): every scheme, levels 0-3,
/// last or all levels, with or without the base level's indices, quads or
/// triangulated — identical to OpenSubdiv's.
#[test]
fn uniform_tables_match_opensubdiv() {
    use subdiv::UniformOptions;
    let mut compared = 0;
    for (name, mesh) in shapes::corpus() {
        for scheme in [Scheme::Catmark, Scheme::Bilinear, Scheme::Loop] {
            let options = Options::shape_file_defaults().with_scheme(scheme);
            for level in 0..=3 {
                let Ok(mut native) = Refiner::new(&mesh, &options) else {
                    continue;
                };
                let mut theirs = osd::TopologyRefiner::new(&mesh, &options).unwrap();
                if level > 0 {
                    native.refine_uniform(UniformOptions::new(level)).unwrap();
                    theirs.refine_uniform(UniformOptions::new(level)).unwrap();
                }
                for (all, base, triangulate) in [
                    (false, true, false),
                    (true, true, false),
                    (true, false, true),
                    (false, false, true),
                ] {
                    // Face-varying patches of every channel, their values
                    // offset past the base level's or not.
                    let po = PatchOptions {
                        generate_all_levels: all,
                        include_base_level_indices: base,
                        include_fvar_base_level_indices: !base,
                        triangulate_quads: triangulate,
                        fvar_tables: true,
                        ..PatchOptions::new()
                    };
                    let case = format!("{name} {scheme:?} level {level} {po:?}");
                    match (native.patch_table(&po), theirs.patch_table(&po, &[])) {
                        (Ok(a), Ok(b)) => {
                            same_table(&a, b.table(), &case);
                            compared += 1;
                            // Every level's patches overlap: OpenSubdiv's
                            // PatchMap would overrun, the bridge has none;
                            // the native one stays within its nodes.
                            let map = subdiv::patches::PatchMap::new(&a);
                            for face in 0..a.ptex_faces as u32 {
                                let _ = map.find_patch(face, 0.3, 0.6);
                            }
                            let found = b.find_patch(0, 0.3, 0.6);
                            if a.arrays.len() > 1 {
                                assert!(
                                    matches!(&found, Err(Error::Osd(e)) if e.kind == subdiv::OsdErrorKind::Unsafe),
                                    "{case}: {found:?}"
                                );
                            } else if level > 0 {
                                assert_eq!(found.unwrap(), map.find_patch(0, 0.3, 0.6), "{case}");
                            }
                        }
                        (a, b) => panic!(
                            "{case}: native {a:?}, osd {:?}",
                            b.map(|b| b.table().clone())
                        ),
                    }
                }
            }
        }
    }
    assert!(compared > 1000, "{compared}");
}

/// `evaluate_with` a map built once gives `evaluate`'s values; a map of
/// another table is refused or answers, never panics.
#[test]
fn evaluation_with_a_prebuilt_map() {
    use subdiv::patches::{self, Derivatives, PatchMap};
    let po = PatchOptions::new().max_isolation(2);
    let build = |mesh: &Mesh| {
        let r = Refiner::new(mesh, &Options::default())
            .unwrap()
            .refine_adaptive(po.refine_adaptive_options(), &[])
            .unwrap();
        let t = r.patch_table(&po, &[]).unwrap();
        let p = r.patch_points(&t, 3, &mesh.flat_positions()).unwrap();
        (t, p)
    };
    let (cube, cube_points) = build(&shapes::cube());
    let map = PatchMap::new(&cube);
    let at = [(0, 0.2, 0.7), (5, 1.0, 0.0)];
    let once = patches::evaluate(&cube, &cube_points, 3, &at, Derivatives::First).unwrap();
    let with =
        patches::evaluate_with(&map, &cube, &cube_points, 3, &at, Derivatives::First).unwrap();
    assert_eq!(once, with);
    // The map of a bigger table over a smaller one.
    let (torus, _) = build(&shapes::torus_mixed(6, 4));
    let big = PatchMap::new(&torus);
    for face in 0..6 {
        let r = patches::evaluate_with(
            &big,
            &cube,
            &cube_points,
            3,
            &[(face, 0.9, 0.9)],
            Derivatives::None,
        );
        assert!(matches!(r, Ok(_) | Err(Error::NoSuchPatch { .. })), "{r:?}");
    }
}

/// Face-varying data evaluated over non-linear face-varying patches
/// (`patches::evaluate_data` with `PatchData::FaceVarying` over
/// `patch_data_points`, the channel's local points included): a channel
/// that follows the vertex topology of a closed mesh has the vertex
/// patches (OpenSubdiv reuses them), so positions given as its values
/// evaluate as the vertex positions do; over a channel with seams, constant
/// data stays constant.
#[test]
fn face_varying_data_over_nonlinear_patches() {
    use subdiv::patches::{self, Derivatives, PatchData, PatchMap};
    use subdiv::{FVarChannel, FVarLinearInterpolation};
    let mut compared = 0;
    for (name, mut mesh) in [
        ("cube", shapes::cube()),
        ("mixed torus", shapes::torus_mixed(6, 5)),
        (
            "seamed torus",
            shapes::with_torus_uvs(shapes::torus(6, 5), 6, 5),
        ),
    ] {
        let seams = !mesh.fvar_channels.is_empty();
        if !seams {
            mesh.fvar_channels.push(FVarChannel {
                width: 3,
                values: mesh.flat_positions::<f64>(),
                indices: mesh.face_vertices.clone(),
            });
        }
        let options =
            Options::shape_file_defaults().with_fvar(FVarLinearInterpolation::CornersPlus1);
        let po = PatchOptions {
            fvar_tables: true,
            fvar_legacy_linear_patches: false,
            fvar_patch_precision_double: true,
            ..PatchOptions::new().max_isolation(3).double_precision(true)
        };
        let r = Refiner::new(&mesh, &options)
            .unwrap()
            .refine_adaptive(po.refine_adaptive_options(), &[])
            .unwrap();
        let table = r.patch_table(&po, &[]).unwrap();
        // End caps over the channel (the seamed torus has no extraordinary
        // values: regular patches, boundaries and corners only).
        assert_eq!(
            table.fvar_channels[0].local_point_stencils.is_empty(),
            seams,
            "{name}"
        );
        let map = PatchMap::new(&table);
        let locs: Vec<(u32, f64, f64)> = (0..table.ptex_faces as u32)
            .flat_map(|f| {
                [(0.0, 0.0), (0.3, 0.7), (0.5, 0.5), (1.0, 0.25), (0.9, 1.0)]
                    .map(|(u, v)| (f, u, v))
            })
            .collect();
        let eval = |data, width, base: &[f64]| {
            let points = r.patch_data_points(&table, data, width, base).unwrap();
            patches::evaluate_data(
                &map,
                &table,
                data,
                &points,
                width,
                &locs,
                Derivatives::First,
            )
            .unwrap()
            .values
        };
        if seams {
            let uv = &mesh.fvar_channels[0];
            let constant = vec![0.25; uv.values.len()];
            let got = eval(PatchData::FaceVarying(0), uv.width, &constant);
            for (&x, &d) in got.point.iter().zip(&got.du) {
                assert!((x - 0.25).abs() < 1e-12 && d.abs() < 1e-12, "{name}");
                compared += 1;
            }
        } else {
            let base = mesh.flat_positions::<f64>();
            let want = eval(PatchData::Vertex, 3, &base);
            let got = eval(PatchData::FaceVarying(0), 3, &base);
            for (what, x, y) in [
                ("point", &got.point, &want.point),
                ("du", &got.du, &want.du),
                ("dv", &got.dv, &want.dv),
            ] {
                assert_eq!(x.len(), y.len(), "{name}");
                for (p, q) in x.iter().zip(y) {
                    assert!((p - q).abs() < 1e-12, "{name} {what}: {p} against {q}");
                    compared += 1;
                }
            }
        }
    }
    assert!(compared > 1000, "{compared}");
}
