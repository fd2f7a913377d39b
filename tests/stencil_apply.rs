//! The per-frame stencil path: `StencilTableF32` (built by the refiner in
//! `f32`, or converted from an `f64` table) applied by its specialised
//! kernels, against a plain reference loop and, bit for bit, against
//! OpenSubdiv's `Osd::CpuEvaluator::EvalStencils`.

use subdiv::refiner::Refiner;
use subdiv::stencil::{StencilTable, StencilTableF32};
use subdiv::{BoundaryInterpolation, Mesh, Options, Scheme, UniformOptions, shapes};

/// OpenSubdiv's `CpuEvalStencils`, written out: each value starts at zero and
/// gets `value * weight` added per term, in order.
fn reference(t: &StencilTableF32, width: usize, base: &[f32]) -> Vec<f32> {
    let mut out = vec![0.0f32; t.len() * width];
    for (r, dst) in out.chunks_exact_mut(width).enumerate() {
        let (idx, w) = t.row(r);
        for (&i, &w) in idx.iter().zip(w) {
            for (k, d) in dst.iter_mut().enumerate() {
                *d += base[i as usize * width + k] * w;
            }
        }
    }
    out
}

fn bits(v: &[f32]) -> Vec<u32> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// Deterministic pseudo-random values in [-1, 1).
fn noise(n: usize, seed: u64) -> Vec<f32> {
    let mut s = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    (0..n)
        .map(|_| {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            ((s >> 40) as f32 / (1u64 << 24) as f32) * 2.0 - 1.0
        })
        .collect()
}

fn flat32(mesh: &Mesh) -> Vec<f32> {
    mesh.positions
        .iter()
        .flat_map(|p| p.as_vec3().to_array())
        .collect()
}

fn refiner(mesh: &Mesh, scheme: Scheme, level: u32) -> Refiner {
    let options = Options::default()
        .with_scheme(scheme)
        .with_boundary(BoundaryInterpolation::EdgeOnly);
    let mut r = Refiner::new(mesh, &options).unwrap();
    r.refine_uniform(UniformOptions::new(level)).unwrap();
    r
}

/// Every width (1-4 have their own kernels, 3 two of them), small tables
/// (serial) and large ones (parallel, padded base) equal the reference loop
/// bit for bit, on random data.
#[test]
fn kernels_equal_the_reference_loop() {
    let meshes = [
        (shapes::torus(6, 5), Scheme::Catmark, 2),
        (shapes::torus_mixed(8, 8), Scheme::Catmark, 4),
        (shapes::torus_triangles(10, 6), Scheme::Loop, 4),
        (shapes::grid(40, 30), Scheme::Catmark, 2),
    ];
    for (mesh, scheme, level) in meshes {
        let t = refiner(&mesh, scheme, level).stencil_table_f32().unwrap();
        let count = mesh.positions.len();
        assert_eq!(t.min_base_count(), count);
        for width in 1..=7 {
            let base = noise(count * width, width as u64);
            let expected = reference(&t, width, &base);
            let mut out = vec![f32::NAN; t.len() * width];
            t.apply_into(width, &base, &mut out).unwrap();
            assert_eq!(
                bits(&out),
                bits(&expected),
                "{scheme} L{level} width {width}"
            );
            // More base vertices than the table reads is fine.
            let mut longer = base.clone();
            longer.extend(noise(width * 5, 99));
            assert_eq!(bits(&t.apply(width, &longer).unwrap()), bits(&expected));
        }
    }
}

/// Hand-built tables: long rows (beyond the unrolled sizes), empty rows,
/// repeated indices, few terms over a large base (width 3 without padding),
/// non-finite values.
#[test]
fn hand_built_tables() {
    let count = 5000;
    let sizes = [0usize, 1, 2, 3, 16, 17, 40, 5, 0, 9];
    let mut offsets = vec![0u32];
    let mut indices = Vec::new();
    for (r, &n) in sizes.iter().cycle().take(300).enumerate() {
        for k in 0..n {
            indices.push(((r * 7919 + k * 104_729) % count) as u32);
        }
        indices.push((r % 3) as u32); // index 0-2 repeated across rows
        offsets.push(indices.len() as u32);
    }
    let weights = noise(indices.len(), 7);
    let t = StencilTableF32::from_parts(offsets, indices, weights).unwrap();
    for width in 1..=5 {
        let mut base = noise(count * width, 3);
        base[0] = f32::INFINITY;
        base[width + 1] = f32::NAN;
        let expected = reference(&t, width, &base);
        let out = t.apply(width, &base).unwrap();
        assert_eq!(bits(&out), bits(&expected), "width {width}");
    }
}

#[test]
fn buffers_are_checked() {
    let t = StencilTableF32::from_parts(vec![0, 2, 3], vec![0, 4, 2], vec![0.5, 0.5, 1.0]).unwrap();
    assert_eq!((t.len(), t.term_count(), t.min_base_count()), (2, 3, 5));
    let base = vec![1.0f32; 15];
    let mut out = vec![0.0f32; 6];
    t.apply_into(3, &base, &mut out).unwrap();
    assert_eq!(out, vec![1.0; 6]);
    assert!(t.apply_into(3, &base[..12], &mut out).is_err()); // vertex 4 missing
    assert!(t.apply_into(3, &base[..14], &mut out).is_err()); // not whole vertices
    assert!(t.apply_into(0, &base, &mut out).is_err());
    assert!(t.apply_into(3, &base, &mut out[..5]).is_err());
    assert!(t.apply_into(2, &base, &mut out).is_err()); // out is 3 rows of 2
    for (offsets, indices, weights) in [
        (vec![], vec![], vec![]),
        (vec![1, 1], vec![0], vec![1.0]),
        (vec![0, 2, 1], vec![0, 1], vec![1.0, 1.0]),
        (vec![0, 1], vec![0, 1], vec![1.0, 1.0]),
        (vec![0, 2], vec![0, 1], vec![1.0]),
    ] {
        assert!(StencilTableF32::from_parts(offsets, indices, weights).is_err());
    }
    let empty = StencilTableF32::default();
    assert!(empty.is_empty());
    assert_eq!(empty.apply(3, &[]).unwrap(), Vec::<f32>::new());
}

/// `StencilTable::to_f32` keeps the rows; applying it equals the `f64`
/// table's `apply_par_f32_into` (which rounds each weight as it goes), in
/// rayon pools of one and two threads alike.
#[test]
fn converted_tables_and_thread_pools() {
    let mesh = shapes::torus(12, 10);
    let r = refiner(&mesh, Scheme::Catmark, 3);
    let table: StencilTable = r.stencil_table().unwrap();
    let fast = table.to_f32().unwrap();
    assert_eq!(fast.len(), table.len());
    assert_eq!(fast.term_count(), table.indices.len());
    for i in [0, table.len() / 2, table.len() - 1] {
        let (a, w) = fast.row(i);
        let (b, x) = table.row(i);
        assert_eq!(a, b);
        assert!(w.iter().zip(x).all(|(&w, &x)| w == x as f32));
    }
    let base = flat32(&mesh);
    let mut legacy = vec![0.0f32; table.len() * 3];
    table.apply_par_f32_into(3, &base, &mut legacy).unwrap();
    let expected = reference(&fast, 3, &base);
    assert_eq!(bits(&legacy), bits(&expected));
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let out = pool.install(|| fast.apply(3, &base).unwrap());
        assert_eq!(bits(&out), bits(&expected), "{threads} thread(s)");
    }
    // The f64 path still works and agrees to rounding.
    let base64: Vec<f64> = base.iter().map(|&x| x as f64).collect();
    let out64 = table.apply_par(3, &base64).unwrap();
    assert_eq!(out64, table.apply(3, &base64).unwrap());
    assert!(
        out64
            .iter()
            .zip(&expected)
            .all(|(&a, &b)| (a - b as f64).abs() < 1e-5)
    );
}

/// The refiner's `f32` table has the same rows (indices in the same order)
/// as its `f64` table, with weights that differ only by `f32` rounding.
#[test]
fn f32_table_matches_the_f64_table() {
    for (name, mut mesh) in shapes::corpus() {
        mesh.fvar_channels.clear();
        let scheme = if mesh.faces().all(|f| f.len() == 3) {
            Scheme::Loop
        } else {
            Scheme::Catmark
        };
        let r = refiner(&mesh, scheme, 2);
        let (t64, t32) = (r.stencil_table().unwrap(), r.stencil_table_f32().unwrap());
        assert_eq!(t32.len(), t64.len(), "{name}");
        for i in 0..t64.len() {
            let ((a, w), (b, x)) = (t32.row(i), t64.row(i));
            assert_eq!(a, b, "{name} row {i}");
            for (&w, &x) in w.iter().zip(x) {
                assert!(
                    (w as f64 - x).abs() <= 1e-5 * x.abs().max(1e-3),
                    "{name} row {i}"
                );
            }
        }
    }
}

#[cfg(feature = "osd")]
mod opensubdiv {
    use super::*;
    use subdiv::options::{CreasingMethod, TriangleSubdivision};
    use subdiv::osd;

    /// Native `f32` stencils applied by the fast kernels against OpenSubdiv's
    /// float stencil table applied by `Osd::CpuEvaluator::EvalStencils`: equal
    /// bit for bit, for widths 1 to 5.
    fn check(name: &str, mesh: &Mesh, scheme: Scheme, level: u32) {
        let options = Options::default()
            .with_scheme(scheme)
            .with_boundary(BoundaryInterpolation::EdgeOnly);
        check_with(name, mesh, &options, level);
    }

    /// [`check`] under any options.
    fn check_with(name: &str, mesh: &Mesh, options: &Options, level: u32) {
        let (options, scheme) = (*options, options.scheme);
        let uniform = UniformOptions::new(level);
        let mut n = Refiner::new(mesh, &options).unwrap();
        n.refine_uniform(uniform).unwrap();
        let mut o = osd::TopologyRefiner::new(mesh, &options).unwrap();
        o.refine_uniform(uniform).unwrap();
        let table = n.stencil_table_f32().unwrap();
        let evaluator = osd::StencilEvaluator::new(&o).unwrap();
        assert_eq!(table.len(), evaluator.len(), "{name}");
        let count = mesh.positions.len();
        for width in 1..=5 {
            let base = if width == 3 {
                flat32(mesh)
            } else {
                noise(count * width, width as u64 + 11)
            };
            let mut ours = vec![f32::NAN; table.len() * width];
            table.apply_into(width, &base, &mut ours).unwrap();
            let theirs = evaluator.eval(width, &base).unwrap();
            let differ = ours
                .iter()
                .zip(&theirs)
                .filter(|(a, b)| a.to_bits() != b.to_bits())
                .count();
            assert_eq!(
                differ,
                0,
                "{name} {scheme} L{level} width {width}: {differ} of {} values differ",
                ours.len()
            );
        }
    }

    #[test]
    fn equal_to_opensubdiv_on_generated_meshes() {
        check("torus quads", &shapes::torus(20, 16), Scheme::Catmark, 3);
        check(
            "torus mixed",
            &shapes::torus_mixed(12, 12),
            Scheme::Catmark,
            3,
        );
        check(
            "torus triangles",
            &shapes::torus_triangles(16, 8),
            Scheme::Catmark,
            3,
        );
        check(
            "torus triangles",
            &shapes::torus_triangles(16, 8),
            Scheme::Loop,
            3,
        );
        let mut grid = shapes::grid(30, 20);
        grid.fvar_channels.clear();
        check("grid", &grid, Scheme::Catmark, 2);
        check("grid", &grid, Scheme::Bilinear, 2);
    }

    /// A table large enough to be built in parallel chunks (over 131,072
    /// rows), on two threads: the one built on one thread, and OpenSubdiv's
    /// results bit for bit.
    #[test]
    fn built_in_parallel_equal_to_opensubdiv() {
        let mesh = shapes::production(100, 80);
        let r = refiner(&mesh, Scheme::Catmark, 2);
        assert!(r.level_counts(2).unwrap().vertices > 2 * (1 << 16));
        let pool = |n| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .unwrap()
        };
        let one = pool(1).install(|| r.stencil_table_f32().unwrap());
        let two = pool(2).install(|| r.stencil_table_f32().unwrap());
        assert!(one == two, "tables built on one and two threads differ");
        let (one, two) = (
            pool(1).install(|| r.stencil_table().unwrap()),
            pool(2).install(|| r.stencil_table().unwrap()),
        );
        assert!(one == two, "f64 tables built on one and two threads differ");
        pool(2).install(|| check("production 100x80", &mesh, Scheme::Catmark, 2));
    }

    /// Catmull-Clark's smooth-triangle rule (the masks of smooth edges
    /// beside triangles differ) and Chaikin's creasing, on every corpus
    /// shape with triangles or tags and on the mixed torus.
    #[test]
    fn equal_to_opensubdiv_with_smooth_triangles_and_chaikin_creasing() {
        let options = Options::default()
            .with_triangles(TriangleSubdivision::Smooth)
            .with_creasing(CreasingMethod::Chaikin);
        check_with("torus mixed", &shapes::torus_mixed(12, 12), &options, 3);
        for (name, mut mesh) in shapes::corpus() {
            mesh.fvar_channels.clear();
            if mesh.applicable_schemes().contains(&Scheme::Catmark) {
                check_with(&name, &mesh, &options, 2);
            }
        }
    }

    #[test]
    fn equal_to_opensubdiv_on_the_corpus() {
        for (name, mut mesh) in shapes::corpus() {
            mesh.fvar_channels.clear();
            for &scheme in mesh.applicable_schemes() {
                check(&name, &mesh, scheme, 2);
            }
        }
    }
}
