//! Speed of the automatic pre-orientation on a 10k-vertex synthetic sherd (the size the
//! paper orients on) and of its steps. The goals are for one core: run with
//! `RAYON_NUM_THREADS=1 cargo bench --bench orient`.

use criterion::{criterion_group, criterion_main, Criterion};
use sherd::orient::line_complex::{fit_complex, CenteredLines};
use sherd::orient::normal_lines::NormalLines;
use sherd::orient::revolution_search::{search, SearchOptions};
use sherd::orient::{orient_automatic, OrientOptions};
use sherd::synth::{synthetic_sherd, SherdOptions, SherdPart};

fn orientation(c: &mut Criterion) {
    let sherd = synthetic_sherd(3, &SherdOptions { target_faces: 20_000, ..SherdOptions::for_part(SherdPart::Rim) });
    let mesh = &sherd.mesh;
    let options = OrientOptions::default();
    let once = orient_automatic(mesh, &options).unwrap();
    eprintln!("steps of one run (ms): {:?}", once.report.timings_ms);
    let mut group = c.benchmark_group("orient");
    group.sample_size(10);
    group.bench_function(format!("orient_automatic {} vertices", mesh.vertex_count()), |b| {
        b.iter(|| orient_automatic(mesh, &options).unwrap())
    });
    let lines = NormalLines::from_mesh(mesh).unwrap();
    group.bench_function(format!("whole-sphere search {} lines", lines.len()), |b| {
        b.iter(|| search(&lines, &SearchOptions::default()).unwrap())
    });
    group.bench_function(format!("bvh build {} faces", mesh.face_count()), |b| {
        b.iter(|| sherd::mesh::spatial::Bvh::new(mesh))
    });
    let centered = CenteredLines::new(&lines);
    group.bench_function(format!("line complex closed form {} lines", lines.len()), |b| {
        b.iter(|| fit_complex(&centered, None, None).unwrap())
    });
    group.finish();
}

criterion_group!(benches, orientation);
criterion_main!(benches);
