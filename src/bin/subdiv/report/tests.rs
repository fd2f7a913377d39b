use super::format::{format_deviation, format_worst, slug};
use super::inputs::{embedded_inputs, option_sets};
use super::picture::picture;
use super::plot::{deviation_color, hex};
use super::run::run;
use super::settings::Settings;
use subdiv::compare::bbox_diagonal;
use subdiv::{Scheme, UniformOptions, refiner};

#[test]
fn embedded_inputs_are_valid_and_named_uniquely() {
    let inputs = embedded_inputs();
    let mut names: Vec<&str> = inputs.iter().map(|i| i.name.as_str()).collect();
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), inputs.len());
    for i in &inputs {
        i.mesh.validate().unwrap();
        assert!(!option_sets(i, true).is_empty());
    }
}

#[test]
fn option_sets_vary_what_applies() {
    let inputs = embedded_inputs();
    let by = |n: &str| inputs.iter().find(|i| i.name == n).unwrap();
    // A closed quad mesh: catmark and bilinear, nothing else varies.
    assert_eq!(option_sets(by("cube"), false).len(), 2);
    // Loop only on all-triangle meshes.
    let ico = option_sets(by("icosahedron"), false);
    assert_eq!(ico[0].scheme, Scheme::Loop);
    assert!(
        option_sets(by("pole"), false)
            .iter()
            .all(|o| o.scheme != Scheme::Loop)
    );
    // UVs on an open mesh: 3 boundaries × 6 face-varying modes per scheme.
    assert_eq!(option_sets(by("grid-uv-regions"), false).len(), 2 * 3 * 6);
    assert!(option_sets(by("grid-uv-regions"), true).len() < 2 * 3 * 6);
}

#[test]
fn pictures_colour_deviations() {
    let input = embedded_inputs().swap_remove(0);
    let n = refiner::refine(&input.mesh, &input.options, UniformOptions::new(2)).unwrap();
    let exact = picture(&input, &n, &n, 1e-6);
    assert_eq!(exact.max_deviation, 0.0);
    assert!(exact.svg.contains("0 (bit-identical to OpenSubdiv)"));
    // Deviations from 0 (every third vertex) through 1e-16 to 1e-5.
    let mut o = n.clone();
    let diag = bbox_diagonal(&n.positions[2]);
    let count = o.positions[2].len();
    for (i, p) in o.positions[2].iter_mut().enumerate() {
        if i % 3 != 0 {
            p.x += diag * 10f64.powf(-16.0 + 11.0 * i as f64 / count as f64);
        }
    }
    let pic = picture(&input, &n, &o, 1e-6);
    assert!(pic.max_deviation > 1e-6 && pic.max_deviation < 1e-4);
    assert!(pic.svg.contains("largest deviation"));
    for d in [0.0, 1e-3] {
        let c = hex(deviation_color(d, 1e-6));
        assert!(pic.svg.contains(&c[..5]), "{c}");
    }
    if let Some(path) = std::env::var_os("SUBDIV_REPORT_PICTURE") {
        std::fs::write(path, &pic.svg).unwrap();
    }
}

#[test]
fn a_difference_fails_the_verdict() {
    let inputs = vec![embedded_inputs().swap_remove(0)];
    let mut rep = run(&inputs, &Settings::new(true), |_| {}).unwrap();
    assert!(rep.conforms());
    assert!(rep.verdict().starts_with("CONFORMS"));
    let c = &mut rep.inputs[0].sets[0].levels[0];
    c.position_deviation = 1e-3;
    c.agrees = false;
    assert!(!rep.conforms());
    assert!(rep.verdict().starts_with("DIFFERS: 1 of"));
    let html = rep.html();
    assert!(html.contains("verdict fail") && html.contains("DIFFERS"));
    assert!(rep.markdown().contains("DIFFERS"));
}

#[test]
fn colours_and_formats() {
    assert_eq!(format_deviation(0.0), "0");
    assert_eq!(format_worst(0.0), "0 (bit-identical)");
    assert_eq!(format_deviation(f64::INFINITY), "∞");
    assert_ne!(
        hex(deviation_color(0.0, 1e-6)),
        hex(deviation_color(1e-16, 1e-6))
    );
    assert_eq!(
        hex(deviation_color(1e-3, 1e-6)),
        hex(deviation_color(f64::INFINITY, 1e-6))
    );
    assert_eq!(slug(2, "My Shape.obj"), "03-my-shape-obj");
}

/// The option sets follow the input's size: every combination for the
/// embedded meshes, one option varied at a time, then the mesh's own options
/// only as the production-like mesh grows; `--all-options` runs them all.
#[test]
fn coverage_follows_the_size() {
    use super::coverage::{Coverage, WORK_BUDGET, choose, faces_at};
    use super::inputs::Input;
    let mut settings = Settings::new(false);
    settings.last_level = 2;
    for i in embedded_inputs() {
        let (coverage, sets) = choose(&i, &settings);
        assert_eq!(coverage, Coverage::Every, "{}", i.name);
        assert_eq!(sets, option_sets(&i, false), "{}", i.name);
    }
    let usd = subdiv::Options::default()
        .with_boundary(subdiv::BoundaryInterpolation::EdgeAndCorner)
        .with_fvar(subdiv::FVarLinearInterpolation::CornersPlus1);
    let production = |nu, nv| Input::new("p", "", subdiv::shapes::production(nu, nv), usd);
    // Level 2 of the quad split: four faces per corner.
    let small = production(16, 9);
    assert_eq!(
        faces_at(&small, Scheme::Catmark, 2),
        4.0 * small.mesh.face_vertices.len() as f64
    );
    let expect = [
        ((80, 60), Coverage::Every),
        ((300, 240), Coverage::OneAtATime),
        ((560, 480), Coverage::Own),
    ];
    for ((nu, nv), want) in expect {
        let input = production(nu, nv);
        let (coverage, sets) = choose(&input, &settings);
        assert_eq!(coverage, want, "{nu}x{nv}");
        assert_eq!(sets[0], usd, "the mesh's own options first");
        let work = sets.len() as f64 * faces_at(&input, Scheme::Catmark, 2);
        assert!(
            work <= WORK_BUDGET || coverage == Coverage::Own,
            "{nu}x{nv}"
        );
        if coverage == Coverage::Own {
            assert_eq!(sets, [usd]);
        }
    }
    let big = production(560, 480);
    settings.all_options = true;
    let (coverage, sets) = choose(&big, &settings);
    assert_eq!(
        (coverage, sets.len()),
        (Coverage::Every, option_sets(&big, false).len())
    );
    // --quick stops at one option at a time.
    let quick = Settings::new(true);
    assert_eq!(choose(&production(80, 60), &quick).0, Coverage::OneAtATime);
}
