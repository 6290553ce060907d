//! Speed of the synthetic sherd generator: one fragment at 20k, 100k and 500k faces, and
//! a whole vessel broken into 24 fragments.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use sherd::synth::{generate_vessel, synthetic_sherd, SherdOptions, VesselOptions};

fn sherds(c: &mut Criterion) {
    let mut group = c.benchmark_group("synthetic_sherd");
    group.sample_size(10);
    for faces in [20_000usize, 100_000, 500_000] {
        let options = SherdOptions { target_faces: faces, ..Default::default() };
        group.bench_with_input(BenchmarkId::from_parameter(faces), &options, |b, options| {
            let mut seed = 0u64;
            b.iter(|| {
                seed += 1;
                synthetic_sherd(seed % 8, options)
            })
        });
    }
    group.finish();
}

fn vessels(c: &mut Criterion) {
    let mut group = c.benchmark_group("generate_vessel");
    group.sample_size(10);
    let options = VesselOptions::default();
    group.bench_function("24_fragments_2mm_cells", |b| {
        let mut seed = 0u64;
        b.iter(|| {
            seed += 1;
            generate_vessel(seed % 8, &options)
        })
    });
    group.finish();
}

criterion_group!(benches, sherds, vessels);
criterion_main!(benches);
