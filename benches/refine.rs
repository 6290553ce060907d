//! Pre-orientation + refinement of a ~10k-vertex synthetic rim sherd and of a body sherd
//! (the goal: under 500 ms on one core, `RAYON_NUM_THREADS=1 cargo bench --bench refine`;
//! the rim is levelled by the tangent plane, the body refined by the circles criterion),
//! and each criterion alone from a start 3 degrees off.

#[path = "../tests/support/evaluation.rs"]
mod evaluation;

use criterion::{criterion_group, criterion_main, Criterion as Bench};
use evaluation::perturbed_axis;
use sherd::orient::{orient_automatic, OrientOptions};
use sherd::refine::{refine, Criterion, RefineOptions};
use sherd::synth::{synthetic_sherd, SherdOptions, SherdPart};

fn bench(c: &mut Bench) {
    let sherd = synthetic_sherd(7, &SherdOptions { target_faces: 20_000, ..SherdOptions::for_part(SherdPart::Rim) });
    eprintln!("bench sherd: {} vertices, {} faces", sherd.mesh.vertex_count(), sherd.mesh.face_count());
    let mut group = c.benchmark_group("refine");
    group.sample_size(10);
    group.bench_function("orient_automatic + refine(Auto), 10k vertices", |b| {
        b.iter(|| {
            let orientation = orient_automatic(&sherd.mesh, &OrientOptions::default()).unwrap();
            refine(&sherd.mesh, &orientation.axis, &RefineOptions::default()).unwrap()
        })
    });
    let body = synthetic_sherd(3, &SherdOptions { target_faces: 20_000, ..SherdOptions::for_part(SherdPart::Body) });
    eprintln!("bench body sherd: {} vertices, {} faces", body.mesh.vertex_count(), body.mesh.face_count());
    group.bench_function("orient_automatic + refine(Auto), 10k-vertex body sherd", |b| {
        b.iter(|| {
            let orientation = orient_automatic(&body.mesh, &OrientOptions::default()).unwrap();
            refine(&body.mesh, &orientation.axis, &RefineOptions::default()).unwrap()
        })
    });
    let start = perturbed_axis(&sherd.truth.axis, 0.0, 3.0, 0.0, 0.0);
    for criterion in [Criterion::Circles, Criterion::Tangent, Criterion::Profile, Criterion::Pareto] {
        group.bench_function(format!("refine({criterion:?}) from 3 deg off"), |b| {
            // A criterion may refuse this sherd (an error is an answer, and its cost is measured too).
            b.iter(|| std::hint::black_box(refine(&sherd.mesh, &start, &RefineOptions { criterion, ..Default::default() }).is_ok()))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
