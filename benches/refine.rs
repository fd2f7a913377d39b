//! Refinement benchmarks. For now only the OpenSubdiv engine exists; the native
//! engine joins it here, on the same inputs in the same run.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use subdiv::{Options, UniformOptions, shapes};

fn osd_refine(c: &mut Criterion) {
    {
        let torus = shapes::torus(100, 100);
        let opts = Options::default();
        let mut group = c.benchmark_group("osd/torus-10k-quads");
        group.sample_size(10);
        for level in 1..=3u32 {
            group.bench_with_input(BenchmarkId::new("topology", level), &level, |b, &level| {
                b.iter(|| {
                    let mut r = subdiv::osd::Refiner::new(black_box(&torus), &opts).unwrap();
                    r.refine_uniform(UniformOptions::new(level)).unwrap();
                    r
                })
            });
            let mut r = subdiv::osd::Refiner::new(&torus, &opts).unwrap();
            r.refine_uniform(UniformOptions::new(level)).unwrap();
            let base: Vec<f32> = torus
                .positions
                .iter()
                .flat_map(|p| p.as_vec3().to_array())
                .collect();
            group.bench_with_input(BenchmarkId::new("positions-f32", level), &level, |b, _| {
                b.iter(|| r.interpolate_all(3, black_box(&base)).unwrap())
            });
        }
        group.finish();
    }
    #[cfg(not(feature = "osd"))]
    let _ = (
        c,
        shapes::cube(),
        Options::default(),
        UniformOptions::new(1),
    );
}

criterion_group!(benches, osd_refine);
criterion_main!(benches);
