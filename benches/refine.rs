//! Criterion benchmarks: the native engine against OpenSubdiv (the bridge), on
//! the same inputs in the same run, per scheme and level. `subdiv bench` runs
//! the same comparisons without criterion and checks the targets.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::time::Duration;
use subdiv::shapes::{BenchShape, bench_shapes};
use subdiv::{UniformOptions, osd, refiner};

fn flat32(input: &BenchShape) -> Vec<f32> {
    input
        .mesh
        .positions
        .iter()
        .flat_map(|p| p.as_vec3().to_array())
        .collect()
}

fn engines(c: &mut Criterion) {
    let quick = std::env::var_os("SUBDIV_BENCH_FULL").is_none();
    for input in bench_shapes(quick) {
        let options = input.options;
        let base = flat32(&input);
        let mut group = c.benchmark_group(format!("{} {}", input.name, input.options.scheme));
        group
            .sample_size(10)
            .measurement_time(Duration::from_secs(2))
            .warm_up_time(Duration::from_millis(300));
        group.bench_function("native/base topology", |b| {
            b.iter(|| refiner::Refiner::new(black_box(&input.mesh), &options).unwrap())
        });
        group.bench_function("osd/base topology", |b| {
            b.iter(|| osd::TopologyRefiner::new(black_box(&input.mesh), &options).unwrap())
        });
        for level in 1..=input.max_level {
            let uniform = UniformOptions::new(level);
            group.bench_with_input(BenchmarkId::new("native/refine", level), &level, |b, _| {
                b.iter(|| {
                    let mut r = refiner::Refiner::new(&input.mesh, &options).unwrap();
                    r.refine_uniform(uniform).unwrap();
                    r
                })
            });
            group.bench_with_input(BenchmarkId::new("osd/refine", level), &level, |b, _| {
                b.iter(|| {
                    let mut r = osd::TopologyRefiner::new(&input.mesh, &options).unwrap();
                    r.refine_uniform(uniform).unwrap();
                    r
                })
            });
            let mut n = refiner::Refiner::new(&input.mesh, &options).unwrap();
            n.refine_uniform(uniform.full_topology(true)).unwrap();
            let mut o = osd::TopologyRefiner::new(&input.mesh, &options).unwrap();
            o.refine_uniform(uniform.full_topology(true)).unwrap();
            group.bench_with_input(
                BenchmarkId::new("native/positions", level),
                &level,
                |b, _| b.iter(|| n.interpolate_all(3, black_box(&base)).unwrap()),
            );
            group.bench_with_input(BenchmarkId::new("osd/positions", level), &level, |b, _| {
                b.iter(|| o.interpolate_all(3, black_box(&base)).unwrap())
            });
            let last = n.interpolate_all(3, &base).unwrap().pop().unwrap();
            group.bench_with_input(BenchmarkId::new("native/limit", level), &level, |b, _| {
                b.iter(|| n.limit(3, black_box(&last)).unwrap())
            });
            group.bench_with_input(BenchmarkId::new("osd/limit", level), &level, |b, _| {
                b.iter(|| o.limit(3, black_box(&last)).unwrap())
            });
            if level == input.max_level {
                group.bench_function("native/stencil build", |b| {
                    b.iter(|| n.stencil_table().unwrap())
                });
                group.bench_function("osd/stencil build", |b| {
                    b.iter(|| osd::StencilEvaluator::new(&o).unwrap())
                });
                // The same stencils as OpenSubdiv's float table (built in
                // f32), applied to the same f32 frame.
                let table = n.stencil_table_f32().unwrap();
                let evaluator = osd::StencilEvaluator::new(&o).unwrap();
                let mut out = vec![0f32; table.len() * 3];
                group.bench_function("native/stencil apply", |b| {
                    b.iter(|| table.apply_into(3, black_box(&base), &mut out).unwrap())
                });
                let mut out = vec![0f32; evaluator.len() * 3];
                group.bench_function("osd/stencil apply", |b| {
                    b.iter(|| evaluator.eval_into(3, black_box(&base), &mut out).unwrap())
                });
            }
        }
        group.finish();
    }
}

criterion_group!(benches, engines);
criterion_main!(benches);
