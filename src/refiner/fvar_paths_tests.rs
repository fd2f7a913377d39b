//! The two ways a level of a face-varying channel is computed give the same
//! values, bit for bit: the vertex kernel's path (the channel's values that
//! follow the vertex topology refined as vertex data, the rest by the
//! face-varying pass), which every pool takes for a channel that mostly
//! follows the vertices, and the face-varying pass alone, which linear
//! channels, channels wider than the kernel takes and channels that are
//! mostly seams take — on one thread and in parallel chunks of parents.
//! The conformance suite (tests/native_fvar.rs) compares the first with
//! OpenSubdiv; this carries the comparison to the second.

use super::Refiner;
use super::fvar_interp::fvar_level;
use crate::options::{BoundaryInterpolation, FVarLinearInterpolation, Options, Scheme};
use crate::{UniformOptions, shapes};

#[test]
fn the_pass_alone_gives_the_kernels_values() {
    let usd = Options::default()
        .with_boundary(BoundaryInterpolation::EdgeAndCorner)
        .with_fvar(FVarLinearInterpolation::CornersPlus1);
    // More than 4,096 parent faces, edges and vertices from level 1 on
    // (the pass's parallel chunks), two seam loops; the production-like
    // mesh's creases, corners, holes and seams.
    let cases = [
        (
            "quad torus",
            shapes::with_torus_uvs(shapes::torus(70, 70), 70, 70),
            usd,
        ),
        (
            "Loop torus",
            shapes::with_torus_uvs(shapes::torus_triangles(70, 35), 70, 35),
            usd.with_scheme(Scheme::Loop),
        ),
        ("production-like", shapes::production(24, 20), usd),
    ];
    let pools = [1, 2].map(|threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a pool")
    });
    for (name, mesh, options) in cases {
        let mut r = Refiner::new(&mesh, &options).expect("refiner");
        r.refine_uniform(UniformOptions::new(2)).expect("refined");
        let width = mesh.fvar_channels[0].width;
        let mut src = mesh.fvar_channels[0].values.clone();
        for level in 1..=2usize {
            let n = r.fvar[0][level].value_count() * width;
            let mut scratch = vec![0.0; n];
            assert!(
                r.fvar_by_vertex_kernel(0, level, width, &src, &mut scratch)
                    .is_some(),
                "{name} level {level}: the vertex kernel's path is not taken"
            );
            let mut kernel = vec![f64::NAN; n];
            r.interpolate_fvar_level(0, level, width, &src, &mut kernel);
            for pool in &pools {
                let mut alone = vec![f64::NAN; n];
                pool.install(|| fvar_level(&r.fvar_step(0, level), width, &src, &mut alone));
                let differ = (0..n).find(|&i| alone[i].to_bits() != kernel[i].to_bits());
                assert_eq!(
                    differ,
                    None,
                    "{name} level {level}, {} thread(s)",
                    pool.current_num_threads()
                );
            }
            src = kernel;
        }
    }
}
