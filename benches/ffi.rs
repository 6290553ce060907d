//! The cost of the C boundary: automatic orientation of a 10k-vertex synthetic sherd
//! through the Rust API and through the C ABI from host arrays (mesh created from the
//! arrays, normals set, oriented, freed), as the Blender add-on does it.

use std::hint::black_box;
use std::ptr;

use criterion::{Criterion, criterion_group, criterion_main};
use sherd::ffi::*;
use sherd::orient::{OrientOptions, orient_automatic};
use sherd::synth::{SherdOptions, SherdPart, synthetic_sherd};

fn boundary(c: &mut Criterion) {
    // About 20k faces give about 10k vertices; seed 10 is a rim piece the layer orients.
    let options = SherdOptions { target_faces: 20_000, ..SherdOptions::for_part(SherdPart::Rim) };
    let sherd = synthetic_sherd(10, &options);
    let mesh = sherd.mesh;
    let positions: Vec<f64> = mesh.positions.iter().flat_map(|p| [p.x, p.y, p.z]).collect();
    let triangles: Vec<u32> = mesh.triangles.iter().flatten().copied().collect();
    let normals: Vec<f64> = mesh.normals.as_ref().expect("synthetic sherds have normals").iter().flat_map(|n| [n.x, n.y, n.z]).collect();
    let vertex_count = mesh.vertex_count();
    let face_count = mesh.face_count();

    let mut group = c.benchmark_group(format!("orient_automatic_{vertex_count}_vertices"));
    group.sample_size(20);
    group.bench_function("rust_api", |b| {
        b.iter(|| orient_automatic(black_box(&mesh), &OrientOptions::default()).expect("orients"))
    });
    group.bench_function("c_abi_from_arrays", |b| {
        b.iter(|| unsafe {
            let mut handle = ptr::null_mut();
            let status = sherd_mesh_from_arrays(positions.as_ptr(), vertex_count, triangles.as_ptr(), face_count, &mut handle);
            assert_eq!(status, SherdStatus::Ok);
            assert_eq!(sherd_mesh_set_normals(handle, normals.as_ptr(), vertex_count), SherdStatus::Ok);
            let mut axis = SherdAxis { size: size_of::<SherdAxis>(), ..Default::default() };
            let status = sherd_orient_automatic(handle, ptr::null(), &mut axis, ptr::null_mut(), ptr::null_mut());
            sherd_mesh_free(handle);
            black_box((status, axis))
        })
    });
    group.finish();
}

criterion_group!(benches, boundary);
criterion_main!(benches);
