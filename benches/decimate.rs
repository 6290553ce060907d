//! Quadric decimation of a 500k-face noisy vessel wall to 20k faces, the reduction
//! the orientation applies to every scan first.
//!
//!     cargo bench --bench decimate

#[path = "../tests/support/decimation_vessel.rs"]
mod vessel;

use criterion::{criterion_group, criterion_main, Criterion};
use sherd::mesh::decimate::{decimate_with_options, DecimateOptions};

fn decimate_500k_to_20k(c: &mut Criterion) {
    let input = vessel::noisy_vessel(500_000, 0.1, 11);
    let options = DecimateOptions::with_target_faces(20_000);
    let mut group = c.benchmark_group("decimate");
    group.sample_size(10);
    group.bench_function(format!("{}k faces to 20k", input.face_count() / 1000), |b| {
        b.iter(|| decimate_with_options(&input, &options).unwrap())
    });
    group.finish();
}

criterion_group!(benches, decimate_500k_to_20k);
criterion_main!(benches);
