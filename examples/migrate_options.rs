//! Migration guide (docs/MIGRATING.md), row 2: `Sdc::Options` and
//! `Sdc::SchemeType` → `subdiv::Options`.
//!
//! Checks that the enums carry OpenSubdiv's numeric values, that
//! `Options::default()` is `Sdc::Options()`, and (with the `osd` feature) that
//! every combination of scheme and options refines identically in both
//! engines.
//!
//! Run with `cargo run --example migrate_options`.

use subdiv::{
    BoundaryInterpolation, CreasingMethod, FVarLinearInterpolation, Options, Scheme,
    TriangleSubdivision,
};

fn main() {
    // [options]
    let options = Options::default() // Sdc::Options() with Sdc::SCHEME_CATMARK
        .with_scheme(Scheme::Catmark)
        .with_boundary(BoundaryInterpolation::EdgeOnly)
        .with_fvar(FVarLinearInterpolation::CornersPlus1)
        .with_creasing(CreasingMethod::Chaikin)
        .with_triangles(TriangleSubdivision::Smooth);
    // [end]
    println!("options: {options:?}");
    assert_eq!(options.boundary.code(), 1); // VTX_BOUNDARY_EDGE_ONLY
    assert_eq!(options.fvar.code(), 2); // FVAR_LINEAR_CORNERS_PLUS1

    // [defaults]
    // Sdc::Options(): VTX_BOUNDARY_NONE, FVAR_LINEAR_ALL, CREASE_UNIFORM, TRI_SUB_CATMARK.
    let sdc_default = Options::default();
    assert_eq!(sdc_default.scheme, Scheme::Catmark);
    assert_eq!(sdc_default.boundary, BoundaryInterpolation::None);
    assert_eq!(sdc_default.fvar, FVarLinearInterpolation::All);
    assert_eq!(sdc_default.creasing, CreasingMethod::Uniform);
    assert_eq!(sdc_default.triangles, TriangleSubdivision::Catmark);
    // OpenSubdiv's shape files (and `subdiv refine` without tags) assume
    // edge-only boundaries instead.
    let shapes = Options::shape_file_defaults();
    assert_eq!(shapes.boundary, BoundaryInterpolation::EdgeOnly);
    assert_eq!(
        shapes,
        sdc_default.with_boundary(BoundaryInterpolation::EdgeOnly)
    );
    // [end]

    // [codes]
    // Integers stored by OpenSubdiv code (Sdc enum values) convert both ways.
    assert_eq!(Scheme::from_code(2), Some(Scheme::Loop)); // SCHEME_LOOP
    assert_eq!(
        FVarLinearInterpolation::from_code(4),
        Some(FVarLinearInterpolation::Boundaries) // FVAR_LINEAR_BOUNDARIES
    );
    assert_eq!(BoundaryInterpolation::EdgeAndCorner.code(), 2);
    assert_eq!(BoundaryInterpolation::from_code(3), None); // not an Sdc value
    // The names of the command line and of reports parse back.
    assert_eq!(
        "corners-plus2".parse::<FVarLinearInterpolation>(),
        Ok(FVarLinearInterpolation::CornersPlus2)
    );
    // [end]

    // Every enum lists its values in Sdc's numeric order, from 0.
    let codes = |c: Vec<i32>| c.iter().enumerate().all(|(i, &c)| c == i as i32);
    assert!(codes(Scheme::ALL.iter().map(|v| v.code()).collect()));
    assert!(codes(
        BoundaryInterpolation::ALL
            .iter()
            .map(|v| v.code())
            .collect()
    ));
    assert!(codes(
        FVarLinearInterpolation::ALL
            .iter()
            .map(|v| v.code())
            .collect()
    ));
    assert!(codes(
        CreasingMethod::ALL.iter().map(|v| v.code()).collect()
    ));
    assert!(codes(
        TriangleSubdivision::ALL.iter().map(|v| v.code()).collect()
    ));
    for s in Scheme::ALL {
        println!("Sdc::SchemeType {} -> Scheme::{s:?} ({s})", s.code());
    }
    for f in FVarLinearInterpolation::ALL {
        println!(
            "Sdc::Options::FVarLinearInterpolation {} -> FVarLinearInterpolation::{f:?} ({f})",
            f.code()
        );
    }

    #[cfg(feature = "osd")]
    every_combination_matches_opensubdiv();
    #[cfg(not(feature = "osd"))]
    println!("(built without the `osd` feature: the OpenSubdiv comparison is skipped)");
}

/// Every scheme × boundary × face-varying × creasing × triangle rule, on a
/// grid with a semi-sharp crease chain, a corner and UVs (triangulated for
/// Loop, and for Catmull-Clark's triangle rule): native == OpenSubdiv.
#[cfg(feature = "osd")]
fn every_combination_matches_opensubdiv() {
    use subdiv::{LevelTopology, Mesh, UniformOptions, osd, refiner, shapes};
    let mut quads = shapes::grid(3, 3);
    quads.positions[5].z = 0.5;
    quads.add_crease(4, 5, 3.0);
    quads.add_crease(5, 6, 1.0);
    quads.add_corner(15, 2.0);
    let triangles = shapes::triangulate_with_uvs(&quads);
    // The last level (topology, tags, positions and UVs as bits), after
    // checking that both engines agree on every level.
    let run = |mesh: &Mesh, options: &Options| -> (LevelTopology, Vec<u64>) {
        let uniform = UniformOptions::new(2);
        let native = refiner::refine(mesh, options, uniform).unwrap();
        let osd = osd::refine(mesh, options, uniform).unwrap();
        assert_eq!(native, osd, "{options:?}");
        let positions = native.last_positions().iter().flat_map(|p| p.to_array());
        let uvs = native.last_fvar(0).unwrap().iter().copied();
        let bits = positions.chain(uvs).map(f64::to_bits).collect();
        (native.last_level().clone(), bits)
    };
    let mut runs = 0;
    for &scheme in Scheme::ALL {
        for &boundary in BoundaryInterpolation::ALL {
            for &fvar in FVarLinearInterpolation::ALL {
                for &creasing in CreasingMethod::ALL {
                    for &triangles_rule in TriangleSubdivision::ALL {
                        let options = Options {
                            scheme,
                            boundary,
                            fvar,
                            creasing,
                            triangles: triangles_rule,
                        };
                        if scheme != Scheme::Loop {
                            run(&quads, &options);
                            runs += 1;
                        }
                        run(&triangles, &options);
                        runs += 1;
                    }
                }
            }
        }
    }
    println!("{runs} refinements (every option combination): native == OpenSubdiv bit for bit");
    // Each option reaches the engines: changing only it changes the result.
    let base = Options::default().with_fvar(FVarLinearInterpolation::None);
    let reference = run(&triangles, &base);
    for changed in [
        base.with_scheme(Scheme::Loop),
        base.with_scheme(Scheme::Bilinear),
        base.with_boundary(BoundaryInterpolation::EdgeOnly),
        base.with_boundary(BoundaryInterpolation::EdgeAndCorner),
        base.with_fvar(FVarLinearInterpolation::CornersOnly),
        base.with_fvar(FVarLinearInterpolation::Boundaries),
        base.with_fvar(FVarLinearInterpolation::All),
        base.with_creasing(CreasingMethod::Chaikin),
        base.with_triangles(TriangleSubdivision::Smooth),
    ] {
        assert_ne!(run(&triangles, &changed), reference, "{changed:?}");
    }
    println!("changing any single option changes the result (positions, UVs or hole tags)");
}
