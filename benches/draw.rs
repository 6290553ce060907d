//! The illustration of a 500k-face scan: build (all styles) and encode, and ambient
//! occlusion alone. `cargo bench --bench draw`; figures in BENCHMARKS.md, "## Drawing".

use criterion::{criterion_group, criterion_main, Criterion};

use sherd::draw::{DrawOptions, Drawing, Format, Style};
use sherd::draw::occlusion::{ambient_occlusion, OcclusionOptions};
use sherd::synth::{synthetic_sherd, SherdOptions, SherdPart};

fn bench_draw(c: &mut Criterion) {
    let sherd = synthetic_sherd(5, &SherdOptions { target_faces: 500_000, ..SherdOptions::for_part(SherdPart::Rim) });
    eprintln!("synthetic rim sherd: {} faces, {} vertices", sherd.mesh.face_count(), sherd.mesh.vertex_count());
    let (mesh, axis) = (&sherd.mesh, &sherd.truth.axis);
    let mut group = c.benchmark_group("draw_500k");
    group.sample_size(10);
    for style in ["linear", "light", "light,occlusion", "linear,colour,light,occlusion,stipple,regularity"] {
        let options = DrawOptions { style: Style::parse(style).unwrap(), ..Default::default() };
        group.bench_function(format!("build {style}"), |b| b.iter(|| Drawing::build(mesh, axis, &options).unwrap()));
    }
    let options = DrawOptions { style: Style::parse("light,occlusion,stipple").unwrap(), ..Default::default() };
    let drawing = Drawing::build(mesh, axis, &options).unwrap();
    for format in [Format::Svg, Format::Eps, Format::Pdf, Format::Png] {
        group.bench_function(format!("encode {format:?}"), |b| b.iter(|| drawing.to_bytes(format).unwrap()));
    }
    for (directions, resolution) in [(64, 512), (128, 1024)] {
        let options = OcclusionOptions { directions, resolution };
        group.bench_function(format!("ambient occlusion {directions} x {resolution}px"), |b| {
            b.iter(|| ambient_occlusion(mesh, &options).unwrap())
        });
    }
    group.finish();
    meshlab_occlusion_seconds(mesh, 64);
}

/// The same occlusion (64 rays) by pymeshlab on the same mesh, timed once inside Python,
/// printed for BENCHMARKS.md; skipped when pymeshlab is missing.
fn meshlab_occlusion_seconds(mesh: &sherd::mesh::Mesh, rays: usize) {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("bench.ply");
    sherd::mesh::io::write_ply(&input, mesh, sherd::mesh::io::PlyEncoding::BinaryLittleEndian).unwrap();
    let script = format!(
        "import pymeshlab, time\nms = pymeshlab.MeshSet()\nms.load_new_mesh({:?})\nt = time.time()\n\
         ms.compute_scalar_ambient_occlusion(rays={rays})\nprint(time.time() - t)\n",
        input.to_str().unwrap()
    );
    match std::process::Command::new("python3").args(["-c", &script]).output() {
        Ok(out) if out.status.success() => {
            eprintln!("pymeshlab compute_scalar_ambient_occlusion(rays={rays}): {} s", String::from_utf8_lossy(&out.stdout).trim())
        }
        _ => eprintln!("pymeshlab not available: no MeshLab timing"),
    }
}

criterion_group!(benches, bench_draw);
criterion_main!(benches);
