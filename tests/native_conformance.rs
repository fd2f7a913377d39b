//! The native engine against OpenSubdiv, index by index, over the generated
//! corpus and every option combination that applies.
#![cfg(feature = "osd")]

use subdiv::compare::compare;
use subdiv::{
    BoundaryInterpolation, CreasingMethod, Engine, Mesh, Options, Precision, Scheme,
    TriangleSubdivision, UniformOptions, osd, refiner, shapes,
};

/// Positions must agree to this fraction of the bounding-box diagonal.
const TOLERANCE: f64 = 1e-12;

fn check(
    name: &str,
    mesh: &Mesh,
    options: &Options,
    uniform: UniformOptions,
    precision: Precision,
    limit: bool,
) -> Result<(), String> {
    let expected = osd::refine(
        mesh,
        options,
        subdiv::Request::from(uniform)
            .precision(precision)
            .limit(limit),
    );
    let actual = refiner::refine(
        mesh,
        options,
        subdiv::Request::from(uniform)
            .precision(precision)
            .limit(limit),
    );
    let (expected, actual) = match (expected, actual) {
        (Ok(e), Ok(a)) => (e, a),
        (Err(e), Err(a)) => {
            return if std::mem::discriminant(&e) == std::mem::discriminant(&a) {
                Ok(())
            } else {
                Err(format!(
                    "{name} {options:?}: both fail differently: osd {e} / native {a}"
                ))
            };
        }
        (e, a) => {
            return Err(format!(
                "{name} {options:?} {uniform:?}: osd {:?} vs native {:?}",
                e.err(),
                a.err()
            ));
        }
    };
    let tolerance = match precision {
        Precision::F64 => TOLERANCE,
        Precision::F32 => 1e-6,
    };
    for c in compare(&actual, &expected) {
        if !c.agrees(tolerance) {
            let l = c.level as usize;
            let face = c.first_face_difference.map(|f| {
                format!(
                    "face {f}: native {:?} osd {:?}",
                    actual.levels[l].faces().nth(f),
                    expected.levels[l].faces().nth(f)
                )
            });
            return Err(format!(
                "{name} {options:?} {uniform:?} {precision}: level {l}: counts {:?}, {face:?}, tags equal {}, limit {:?}, \
                 position deviation {:e} (relative {:e}) at vertex {:?}: native {:?} osd {:?}",
                c.counts,
                c.tags_equal,
                c.limit_deviation,
                c.max_position_deviation,
                c.relative_position_deviation,
                c.worst_vertex,
                c.worst_vertex.map(|v| actual.positions[l][v]),
                c.worst_vertex.map(|v| expected.positions[l][v]),
            ));
        }
    }
    Ok(())
}

fn options_for(mesh: &Mesh) -> Vec<Options> {
    let has_triangles = mesh.faces().any(|f| f.len() == 3);
    let mut out = Vec::new();
    for &scheme in mesh.applicable_schemes() {
        for &boundary in BoundaryInterpolation::ALL {
            for &creasing in CreasingMethod::ALL {
                for &triangles in TriangleSubdivision::ALL {
                    if triangles == TriangleSubdivision::Smooth
                        && (!has_triangles || scheme != Scheme::Catmark)
                    {
                        continue;
                    }
                    out.push(Options {
                        scheme,
                        boundary,
                        creasing,
                        triangles,
                        ..Options::default()
                    });
                }
            }
        }
    }
    out
}

/// Every shape is refined to level 4 (levels 1-3 are compared on the way).
fn max_level(_mesh: &Mesh) -> u32 {
    4
}

fn run_corpus(filter: impl Fn(&str) -> bool) {
    let mut failures = Vec::new();
    let mut checked = 0;
    for (name, mut mesh) in shapes::corpus() {
        if !filter(&name) {
            continue;
        }
        // Face-varying data is checked separately.
        mesh.fvar_channels.clear();
        for options in options_for(&mesh) {
            let level = max_level(&mesh);
            for uniform in [
                UniformOptions::new(level),
                UniformOptions::new(2).faces_first(true),
                UniformOptions::new(2).full_topology(true),
            ] {
                checked += 1;
                if let Err(e) = check(&name, &mesh, &options, uniform, Precision::F64, false) {
                    failures.push(e);
                }
            }
            // The fin's tangents hit OpenSubdiv's mask-buffer overlap (see
            // tests/native_limit.rs, which compares the rest of its limit).
            if name == "fin" {
                continue;
            }
            checked += 1;
            if let Err(e) = check(
                &name,
                &mesh,
                &options,
                UniformOptions::new(2),
                Precision::F64,
                true,
            ) {
                failures.push(e);
            }
        }
        let options = Options::shape_file_defaults();
        checked += 1;
        if let Err(e) = check(
            &name,
            &mesh,
            &options,
            UniformOptions::new(2),
            Precision::F32,
            false,
        ) {
            failures.push(e);
        }
    }
    assert!(checked > 0);
    eprintln!("checked {checked} cases");
    if !failures.is_empty() {
        let n = failures.len();
        failures.truncate(8);
        panic!(
            "{n} of {checked} cases differ from OpenSubdiv; first ones:\n{}",
            failures.join("\n")
        );
    }
}

#[test]
fn closed_shapes() {
    run_corpus(|n| {
        n.starts_with("cube")
            || n.starts_with("torus")
            || n.starts_with("prism")
            || n.starts_with("pole")
            || n == "four-boxes"
    });
}

#[test]
fn open_and_triangle_shapes() {
    run_corpus(|n| {
        n.starts_with("grid")
            || n.starts_with("tri-")
            || n.starts_with("fan")
            || n.starts_with("pyramid")
            || n == "tetrahedron"
            || n == "icosahedron"
    });
}

#[test]
fn non_manifold_shapes() {
    run_corpus(|n| matches!(n, "fin" | "bowtie" | "inconsistent" | "crease-without-edge"));
}

/// `refine_last` (levels released as it goes, and tables only the split
/// reads before the last level's values) gives the counts and last-level
/// positions of a full refinement, bit for bit, and OpenSubdiv's, under
/// each scheme; `Engine::refine_counts_owned` (the mesh consumed) the same
/// counts as `refine_counts`.
#[test]
fn refine_last_equals_full_refinement_and_opensubdiv() {
    let schemes = [Scheme::Catmark, Scheme::Bilinear, Scheme::Loop];
    for ((name, mesh), scheme) in shapes::corpus()
        .into_iter()
        .flat_map(|m| schemes.map(|s| (m.clone(), s)))
    {
        let options = subdiv::Options::shape_file_defaults().with_scheme(scheme);
        if scheme == Scheme::Loop && mesh.faces().any(|f| f.len() != 3) {
            continue;
        }
        let base: Vec<f64> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
        for level in 1..=3 {
            let name = &format!("{name} {scheme:?}");
            let request = subdiv::Request::new(level);
            let borrowed = Engine::Native
                .refine_counts(&mesh, &options, request)
                .unwrap();
            let owned = Engine::Native
                .refine_counts_owned(mesh.clone(), &options, request)
                .unwrap();
            assert_eq!(owned, borrowed, "{name} L{level}");
            let uniform = UniformOptions::new(level);
            let mut full = refiner::Refiner::new(&mesh, &options).unwrap();
            full.refine_uniform(uniform).unwrap();
            let (counts, last) = refiner::refine_last(&mesh, &options, uniform, 3, &base).unwrap();
            assert_eq!(
                last,
                full.interpolate_last(3, &base).unwrap(),
                "{name} L{level}"
            );
            for (l, c) in counts.iter().enumerate() {
                // (A full refinement keeps all of a last level's topology when
                // the mesh has face-varying channels; refine_last does not.)
                let f = full.level_counts(l as u32).unwrap();
                let sizes =
                    |c: &subdiv::LevelCounts| (c.vertices, c.edges, c.faces, c.face_vertices);
                assert_eq!(sizes(c), sizes(&f), "{name} L{level} level {l}");
            }
            let mut o = osd::TopologyRefiner::new(&mesh, &options).unwrap();
            o.refine_uniform(uniform).unwrap();
            assert_eq!(
                &last[..],
                o.interpolate_last(3, &base).unwrap(),
                "{name} L{level} osd"
            );
            assert_eq!(
                counts[level as usize].vertices,
                o.level_counts(level).unwrap().vertices
            );
        }
    }
}
