//! Stencil tables in every mode of `Far::StencilTableFactory::Options`
//! (`StencilOptions`): the native builder against OpenSubdiv's
//! `StencilTableFactoryReal<double>::Create`, on adaptive refiners
//! (isolation 1-4, two adaptive option sets, Catmull-Clark with the three
//! boundary interpolations and bilinear) and uniform ones (levels 1-3 in
//! both vertex orders, Catmull-Clark, bilinear and Loop), over corpus shapes. Tables must be identical:
//! the same rows, sizes, offsets and indices in the same order, and weights
//! bit for bit. Also: face-varying tables in every linear-interpolation option,
//! hand-derived rows, the refusals of both engines, and tables applied to
//! base positions and values against level-by-level interpolation.
#![cfg(feature = "osd")]

use subdiv::refiner::{AdaptiveRefiner, Refiner};
use subdiv::stencil::{StencilInterpolation, StencilOptions, StencilTable};
use subdiv::{
    AdaptiveOptions, BoundaryInterpolation, Error, Mesh, Options, Scheme, UniformOptions, osd,
    shapes,
};

/// Every combination of the options: interpolation (vertex, varying) ×
/// offsets × control vertices × intermediate levels × factorization ×
/// max level (0, 1, 2, 10).
fn all_options() -> Vec<StencilOptions> {
    let mut out = Vec::new();
    for mode in [StencilInterpolation::Vertex, StencilInterpolation::Varying] {
        for bits in 0..16u32 {
            for max in [0, 1, 2, 10] {
                out.push(
                    StencilOptions::new()
                        .interpolation(mode)
                        .offsets(bits & 1 != 0)
                        .control_vertices(bits & 2 != 0)
                        .intermediate_levels(bits & 4 != 0)
                        .factorize(bits & 8 != 0)
                        .max_level(max),
                );
            }
        }
    }
    out
}

/// Whether OpenSubdiv 3.5 cannot build these options on a refiner refined
/// to `refined` levels (both engines refuse them).
fn unbuildable(o: &StencilOptions, refined: u32) -> bool {
    o.max_level.min(refined) > 0
        && o.generate_control_vertices
        && !o.generate_intermediate_levels
        && !o.factorize_intermediate_levels
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// The two tables are the same, weights bit for bit.
fn same(case: &str, mine: &StencilTable, theirs: &StencilTable) {
    assert_eq!(mine.len(), theirs.len(), "{case}: stencil count");
    assert_eq!(mine.sizes, theirs.sizes, "{case}: sizes");
    assert_eq!(mine.offsets, theirs.offsets, "{case}: offsets");
    assert_eq!(mine.indices, theirs.indices, "{case}: indices");
    assert_eq!(
        bits(&mine.weights),
        bits(&theirs.weights),
        "{case}: weights"
    );
}

/// Both engines' tables for every option set of `options`, or the same
/// refusal.
fn compare_all(
    case: &str,
    options: Vec<StencilOptions>,
    refined: u32,
    mine: impl Fn(&StencilOptions) -> subdiv::Result<StencilTable>,
    theirs: impl Fn(&StencilOptions) -> subdiv::Result<StencilTable>,
) -> usize {
    let mut tables = 0;
    for o in options {
        let case = format!("{case} {o:?}");
        if unbuildable(&o, refined) {
            assert!(
                matches!(mine(&o), Err(Error::StencilOptions { .. })),
                "{case}"
            );
            assert!(
                matches!(theirs(&o), Err(Error::StencilOptions { .. })),
                "{case}"
            );
            continue;
        }
        same(&case, &mine(&o).unwrap(), &theirs(&o).unwrap());
        tables += 1;
    }
    tables
}

/// Corpus shapes: every other one, so the test stays quick in debug builds.
fn shapes_for_test() -> Vec<(String, Mesh)> {
    shapes::corpus().into_iter().step_by(2).collect()
}

fn adaptive_pair(
    mesh: &Mesh,
    options: &Options,
    ao: AdaptiveOptions,
) -> Option<(AdaptiveRefiner, osd::TopologyRefiner)> {
    let native = Refiner::new(mesh, options)
        .ok()?
        .refine_adaptive(ao, &[])
        .ok()?;
    let mut theirs = osd::TopologyRefiner::new(mesh, options).unwrap();
    theirs.refine_adaptive(ao, &[]).unwrap();
    assert_eq!(native.max_level(), theirs.max_level());
    Some((native, theirs))
}

#[test]
fn adaptive_tables_match_opensubdiv() {
    let mut tables = 0;
    for (name, mesh) in shapes_for_test() {
        for (scheme, boundary) in [
            (Scheme::Catmark, BoundaryInterpolation::EdgeAndCorner),
            (Scheme::Catmark, BoundaryInterpolation::EdgeOnly),
            (Scheme::Catmark, BoundaryInterpolation::None),
            (Scheme::Bilinear, BoundaryInterpolation::EdgeAndCorner),
        ] {
            let options = Options::shape_file_defaults()
                .with_scheme(scheme)
                .with_boundary(boundary);
            for isolation in 1..=4 {
                let ao = AdaptiveOptions::new(isolation);
                for ao in [ao, ao.single_crease_patch(true).faces_first(true)] {
                    let Some((native, theirs)) = adaptive_pair(&mesh, &options, ao) else {
                        continue;
                    };
                    let case = format!("{name} {scheme:?} {boundary:?} {ao:?}");
                    tables += compare_all(
                        &case,
                        all_options(),
                        native.max_level(),
                        |o| native.stencil_table_with(o),
                        |o| theirs.stencil_table_with(o),
                    );
                }
            }
        }
    }
    assert!(tables > 1000, "{tables} tables compared");
}

#[test]
fn uniform_tables_match_opensubdiv() {
    let mut tables = 0;
    for (name, mesh) in shapes_for_test() {
        for scheme in [Scheme::Catmark, Scheme::Bilinear, Scheme::Loop] {
            let options = Options::shape_file_defaults().with_scheme(scheme);
            let Ok(mut native) = Refiner::new(&mesh, &options) else {
                continue;
            };
            let mut theirs = osd::TopologyRefiner::new(&mesh, &options).unwrap();
            for level in 1..=3 {
                for faces_first in [false, true] {
                    let uo = UniformOptions::new(level).faces_first(faces_first);
                    native.refine_uniform(uo).unwrap();
                    theirs.refine_uniform(uo).unwrap();
                    let case = format!("{name} {scheme:?} {uo:?}");
                    tables += compare_all(
                        &case,
                        all_options(),
                        level,
                        |o| native.stencil_table_with(o),
                        |o| theirs.stencil_table_with(o),
                    );
                    // The last level alone is the fast builder's table.
                    let last = StencilOptions::new().intermediate_levels(false);
                    same(
                        &case,
                        &native.stencil_table_with(&last).unwrap(),
                        &native.stencil_table().unwrap(),
                    );
                }
            }
        }
    }
    assert!(tables > 1000, "{tables} tables compared");
}

/// A refiner not refined: identity rows with control vertices, nothing
/// without; an adaptive refinement that selected nothing likewise.
#[test]
fn unrefined_refiners() {
    let grid = shapes::grid(2, 2);
    let native = Refiner::new(&grid, &Options::default()).unwrap();
    let theirs = osd::TopologyRefiner::new(&grid, &Options::default()).unwrap();
    for o in all_options() {
        let (a, b) = (
            native.stencil_table_with(&o).unwrap(),
            theirs.stencil_table_with(&o).unwrap(),
        );
        same(&format!("{o:?}"), &a, &b);
        if o.generate_control_vertices {
            assert_eq!(a.len(), 9);
            assert!((0..9).all(|i| a.row(i) == (&[i as u32][..], &[1.0][..])));
        } else {
            assert!(a.is_empty());
        }
    }
    // A regular grid selects nothing adaptively.
    let (adaptive, theirs) =
        adaptive_pair(&grid, &Options::default(), AdaptiveOptions::new(3)).unwrap();
    assert_eq!(adaptive.max_level(), 0);
    let o = StencilOptions::new().control_vertices(true);
    same(
        "grid adaptive",
        &adaptive.stencil_table_with(&o).unwrap(),
        &theirs.stencil_table_with(&o).unwrap(),
    );
}

/// Hand-derived rows on a bilinear quad refined once: control rows are the
/// identity; the face point is four quarters; edge points are halves; vertex
/// points copy their parent. Level 1 numbers (OpenSubdiv's default order)
/// vertex points, then the face point, then edge points... whichever order
/// the refiner reports, the rows are checked through the child maps.
#[test]
fn bilinear_quad_by_hand() {
    let quad = shapes::grid(1, 1);
    let options = Options::default().with_scheme(Scheme::Bilinear);
    let mut r = Refiner::new(&quad, &options).unwrap();
    r.refine_uniform(UniformOptions::new(1).faces_first(true))
        .unwrap();
    let t = r
        .stencil_table_with(&StencilOptions::new().control_vertices(true))
        .unwrap();
    assert_eq!(t.len(), 4 + 9);
    for i in 0..4 {
        assert_eq!(t.row(i), (&[i as u32][..], &[1.0][..]));
    }
    // Faces first: the face point is level-1 vertex 0, over the face's
    // corners in the face's order.
    let corners: Vec<u32> = quad.faces().next().unwrap().to_vec();
    assert_eq!(t.row(4), (&corners[..], &[0.25; 4][..]));
    // Then four edge points, halves of two corners each.
    for e in 5..9 {
        let (i, w) = t.row(e);
        assert_eq!(i.len(), 2);
        assert_eq!(w, &[0.5, 0.5]);
    }
    // Then the vertex points.
    for v in 0..4 {
        assert_eq!(t.row(9 + v), (&[v as u32][..], &[1.0][..]));
    }
    // Level 2 not factorized: over level 1's own numbering.
    r.refine_uniform(UniformOptions::new(2).faces_first(true))
        .unwrap();
    let t = r
        .stencil_table_with(&StencilOptions::new().factorize(false))
        .unwrap();
    assert_eq!(t.len(), 9 + 25);
    // The first face point of level 2 averages the corners of level 1's
    // first face, which are level-1 vertices (local indices below 9).
    let (i, w) = t.row(9);
    assert_eq!(w, &[0.25; 4]);
    assert!(i.iter().all(|&i| i < 9));
}

/// OpenSubdiv 3.5's surprise: neither factorized nor with intermediate
/// levels, the table still holds every row (identity and all levels).
#[test]
fn unfactorized_last_level_holds_everything() {
    let cube = shapes::cube();
    let mut r = Refiner::new(&cube, &Options::default()).unwrap();
    r.refine_uniform(UniformOptions::new(2)).unwrap();
    let o = StencilOptions::new()
        .intermediate_levels(false)
        .factorize(false);
    let t = r.stencil_table_with(&o).unwrap();
    assert_eq!(t.len(), 8 + 26 + 98);
    assert_eq!(t.row(3), (&[3u32][..], &[1.0][..]));
}

fn positions(mesh: &Mesh) -> Vec<f64> {
    mesh.positions.iter().flat_map(|p| p.to_array()).collect()
}

fn close(case: &str, a: &[f64], b: &[f64]) {
    assert_eq!(a.len(), b.len(), "{case}");
    for (k, (x, y)) in a.iter().zip(b).enumerate() {
        assert!(
            (x - y).abs() <= 1e-12 * (1.0 + y.abs()),
            "{case}: value {k}: {x} vs {y}"
        );
    }
}

/// A factorized table with control vertices and intermediate levels,
/// applied to the base positions, gives every level's positions; an
/// unfactorized one, applied level by level to the previous level's values,
/// too. Not bit for bit: the table sums merged products of weights, the
/// levels sum weighted values, so roundings differ (at most 1e-12 relative
/// here).
#[test]
fn applied_tables_equal_levels() {
    for (name, mesh) in [
        ("cube", shapes::cube()),
        ("prism-5", shapes::prism(5)),
        ("pole-6", shapes::pole(6)),
    ] {
        let base = positions(&mesh);
        let adaptive = Refiner::new(&mesh, &Options::default())
            .unwrap()
            .refine_adaptive(AdaptiveOptions::new(3), &[])
            .unwrap();
        assert!(adaptive.max_level() > 0, "{name}");
        let levels: Vec<Vec<f64>> = adaptive
            .refine_positions(&mesh.positions)
            .unwrap()
            .into_iter()
            .map(|l| l.iter().flat_map(|p| p.to_array()).collect())
            .collect();
        let all = adaptive
            .stencil_table_with(&StencilOptions::new().control_vertices(true))
            .unwrap();
        close(name, &all.apply(3, &base).unwrap(), &levels.concat());
        // Unfactorized: level l's rows over level l - 1.
        let steps = adaptive
            .stencil_table_with(&StencilOptions::new().factorize(false))
            .unwrap();
        let mut row = 0;
        for l in 1..levels.len() {
            let n = levels[l].len() / 3;
            let (a, b) = (
                steps.offsets[row] as usize,
                steps.offsets[row + n - 1] as usize + steps.sizes[row + n - 1] as usize,
            );
            let part = StencilTable {
                sizes: steps.sizes[row..row + n].to_vec().into(),
                offsets: steps.offsets[row..row + n]
                    .iter()
                    .map(|&o| o - a as u32)
                    .collect(),
                indices: steps.indices[a..b].to_vec().into(),
                weights: steps.weights[a..b].to_vec().into(),
            };
            close(
                &format!("{name} level {l}"),
                &part.apply(3, &levels[l - 1]).unwrap(),
                &levels[l],
            );
            row += n;
        }
        assert_eq!(row, steps.len());
        // Varying: the last level only.
        let varying = adaptive
            .stencil_table_with(
                &StencilOptions::new()
                    .interpolation(StencilInterpolation::Varying)
                    .intermediate_levels(false),
            )
            .unwrap();
        let mut v = base.clone();
        for l in 1..=adaptive.max_level() {
            v = adaptive.interpolate_varying(l, 3, &v).unwrap();
        }
        close(name, &varying.apply(3, &base).unwrap(), &v);
    }
}

/// Refusals, the same from both engines.
#[test]
fn refusals() {
    let mesh = shapes::cube_with_uvs();
    let options = Options::default();
    let mut native = Refiner::new(&mesh, &options).unwrap();
    let mut theirs = osd::TopologyRefiner::new(&mesh, &options).unwrap();
    native.refine_uniform(UniformOptions::new(2)).unwrap();
    theirs.refine_uniform(UniformOptions::new(2)).unwrap();
    let too_deep = StencilOptions::new().max_level(16);
    assert!(matches!(
        native.stencil_table_with(&too_deep),
        Err(Error::Level { level: 16, .. })
    ));
    assert!(matches!(
        theirs.stencil_table_with(&too_deep),
        Err(Error::Level { level: 16, .. })
    ));
    let missing = StencilOptions::new().face_varying(1);
    assert!(matches!(
        native.stencil_table_with(&missing),
        Err(Error::NoSuchChannel {
            channel: 1,
            count: 1
        })
    ));
    assert!(matches!(
        theirs.stencil_table_with(&missing),
        Err(Error::NoSuchChannel {
            channel: 1,
            count: 1
        })
    ));
}

/// Shapes with face-varying channels: seams, n-gons, triangles, creases
/// and corners under the seams, holes; whether Loop applies.
fn fvar_shapes() -> Vec<(&'static str, Mesh, bool)> {
    let mut creased = shapes::cube_with_uvs();
    creased.add_crease(0, 1, 1.5);
    creased.add_crease(1, 2, 0.5);
    creased.add_crease(2, 3, 10.0);
    creased.add_corner(5, 2.3);
    vec![
        ("cube-uv", shapes::cube_with_uvs(), false),
        ("cube-uv-creased", creased, false),
        (
            "cube-uv-triangulated",
            shapes::triangulate_with_uvs(&shapes::cube_with_uvs()),
            true,
        ),
        (
            "torus-uv-mixed",
            shapes::with_torus_uvs(shapes::torus_mixed(6, 4), 6, 4),
            false,
        ),
        (
            "torus-uv-triangles",
            shapes::with_torus_uvs(shapes::torus_triangles(6, 4), 6, 4),
            true,
        ),
        ("production", shapes::production(6, 4), false),
    ]
}

/// Every option set with face-varying interpolation of channel 0.
fn fvar_options() -> Vec<StencilOptions> {
    all_options()
        .into_iter()
        .filter(|o| o.interpolation == StencilInterpolation::Vertex)
        .map(|o| o.face_varying(0))
        .collect()
}

/// Face-varying stencil tables (`INTERPOLATE_FACE_VARYING`) in every mode,
/// in all six linear-interpolation options, after uniform refinement (both
/// vertex orders, Catmull-Clark, bilinear, Loop) and adaptive refinement
/// (with and without `considerFVarChannels`): identical to OpenSubdiv's,
/// weights bit for bit.
#[test]
fn face_varying_tables_match_opensubdiv() {
    use subdiv::FVarLinearInterpolation as F;
    let mut tables = 0;
    for (name, mesh, triangles) in fvar_shapes() {
        let schemes: &[Scheme] = if triangles {
            &[Scheme::Catmark, Scheme::Loop]
        } else {
            &[Scheme::Catmark, Scheme::Bilinear]
        };
        for &scheme in schemes {
            for &fvar in F::ALL {
                let options = Options::shape_file_defaults()
                    .with_scheme(scheme)
                    .with_fvar(fvar);
                let mut native = Refiner::new(&mesh, &options).unwrap();
                let mut theirs = osd::TopologyRefiner::new(&mesh, &options).unwrap();
                for (level, faces_first) in [(1, false), (2, true), (3, false)] {
                    let uo = UniformOptions::new(level).faces_first(faces_first);
                    native.refine_uniform(uo).unwrap();
                    theirs.refine_uniform(uo).unwrap();
                    let case = format!("{name} {scheme:?} {fvar:?} {uo:?}");
                    tables += compare_all(
                        &case,
                        fvar_options(),
                        level,
                        |o| native.stencil_table_with(o),
                        |o| theirs.stencil_table_with(o),
                    );
                }
                if scheme == Scheme::Loop {
                    continue;
                }
                for ao in [
                    AdaptiveOptions::new(2),
                    AdaptiveOptions::new(3)
                        .consider_fvar(true)
                        .faces_first(true),
                ] {
                    let Some((native, theirs)) = adaptive_pair(&mesh, &options, ao) else {
                        continue;
                    };
                    let case = format!("{name} {scheme:?} {fvar:?} {ao:?}");
                    tables += compare_all(
                        &case,
                        fvar_options(),
                        native.max_level(),
                        |o| native.stencil_table_with(o),
                        |o| theirs.stencil_table_with(o),
                    );
                }
            }
        }
    }
    assert!(tables > 5000, "{tables} tables compared");
}

/// A face-varying table with control vertices and intermediate levels,
/// applied to the base values, gives the values of every level as the
/// face-varying interpolation computes them (to rounding: the table sums
/// merged products of weights).
#[test]
fn applied_face_varying_table_equals_levels() {
    for (name, mesh, _) in fvar_shapes() {
        let mut r = Refiner::new(&mesh, &Options::default()).unwrap();
        r.refine_uniform(UniformOptions::new(3)).unwrap();
        let t = r
            .stencil_table_with(&StencilOptions::new().face_varying(0).control_vertices(true))
            .unwrap();
        let base = mesh.fvar_channels[0].values.clone();
        let width = mesh.fvar_channels[0].width;
        let mut levels = vec![base.clone()];
        for l in 1..=3 {
            let next = r
                .interpolate_face_varying(0, l, width, levels.last().unwrap())
                .unwrap();
            levels.push(next);
        }
        close(name, &t.apply(width, &base).unwrap(), &levels.concat());
    }
}

/// Face-varying tables from the bridge after adaptive refinement: applied
/// to the base values, they give every level's face-varying values.
#[test]
fn face_varying_after_adaptive_refinement() {
    let mesh = shapes::cube_with_uvs();
    let mut theirs = osd::TopologyRefiner::new(&mesh, &Options::default()).unwrap();
    theirs
        .refine_adaptive(AdaptiveOptions::new(2), &[])
        .unwrap();
    let channel = &mesh.fvar_channels[0];
    let mut levels = vec![channel.values.clone()];
    for l in 1..=theirs.max_level() {
        let next = theirs
            .interpolate_face_varying(0, l, channel.width, levels.last().unwrap())
            .unwrap();
        levels.push(next);
    }
    let t = theirs
        .stencil_table_with(&StencilOptions::new().face_varying(0).control_vertices(true))
        .unwrap();
    close(
        "uv adaptive",
        &t.apply(channel.width, &channel.values).unwrap(),
        &levels.concat(),
    );
}
