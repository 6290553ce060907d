//! Mesh processing on a 500k-face mesh (a rippled torus, 250k vertices): repair (of the
//! welded mesh and of its triangle soup), topology, normals, face orientation, Laplacian
//! and HC smoothing, and the spatial indices (build and queries).
//!
//!     cargo bench --bench mesh_processing
//!     python3 benches/pymeshlab_bench.py     # MeshLab's times for the same operations
//!
//! Figures are in BENCHMARKS.md, "Mesh processing".

#[path = "../tests/support/mod.rs"]
mod support;

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use sherd::mesh::normals::{NormalWeighting, compute_vertex_normals, orient_faces_outward};
use sherd::mesh::repair::{RepairOptions, repair};
use sherd::mesh::smooth::{SmoothOptions, hc_smooth, laplacian_smooth};
use sherd::mesh::spatial::{Bvh, KdTree};
use sherd::mesh::topology::Topology;
use sherd::mesh::{Mesh, Point, Vector};

/// The benchmark mesh: 1000 x 250 quads = 500k faces, as benches/pymeshlab_bench.py builds it.
fn benchmark_mesh() -> Mesh {
    support::torus(1000, 250, 100.0, 30.0, 0.05)
}

fn processing(c: &mut Criterion) {
    let mesh = benchmark_mesh();
    assert_eq!(mesh.face_count(), 500_000);
    let soup = support::triangle_soup(&mesh);
    let mut group = c.benchmark_group("mesh_processing_500k");
    group.sample_size(10);
    group.bench_function("repair_welded", |b| {
        b.iter_batched(|| mesh.clone(), |mut m| repair(&mut m, &RepairOptions::default()), BatchSize::LargeInput)
    });
    group.bench_function("repair_soup_1.5M_vertices", |b| {
        b.iter_batched(|| soup.clone(), |mut m| repair(&mut m, &RepairOptions::default()), BatchSize::LargeInput)
    });
    group.bench_function("repair_soup_tolerance_1e-3", |b| {
        let options = RepairOptions { merge_tolerance_mm: Some(1e-3), keep_largest_component: false };
        b.iter_batched(|| soup.clone(), |mut m| repair(&mut m, &options), BatchSize::LargeInput)
    });
    group.bench_function("topology", |b| b.iter(|| Topology::new(&mesh)));
    group.bench_function("normals_angle", |b| b.iter(|| compute_vertex_normals(&mesh, NormalWeighting::Angle)));
    group.bench_function("normals_area", |b| b.iter(|| compute_vertex_normals(&mesh, NormalWeighting::Area)));
    group.bench_function("orient_faces_outward", |b| {
        b.iter_batched(|| mesh.clone(), |mut m| orient_faces_outward(&mut m), BatchSize::LargeInput)
    });
    group.bench_function("laplacian_3_steps_cotangent", |b| {
        b.iter_batched(|| mesh.clone(), |mut m| laplacian_smooth(&mut m, &SmoothOptions::default()), BatchSize::LargeInput)
    });
    group.bench_function("hc_1_step", |b| {
        b.iter_batched(|| mesh.clone(), |mut m| hc_smooth(&mut m, 1), BatchSize::LargeInput)
    });
    group.finish();
}

fn spatial(c: &mut Criterion) {
    let mesh = benchmark_mesh();
    // Query points near the surface, as vertex merging, normal fitting and distance
    // measures ask: every 2.5th vertex moved by up to 1 mm along each axis. (Points deep
    // in the torus's hole are equidistant from a whole ring of vertices, which no k-d tree
    // answers quickly, and no part of the pipeline asks.)
    let queries: Vec<Point> = (0..100_000u64)
        .map(|i| {
            let vertex = mesh.positions[(i as usize * 5 / 2) % mesh.vertex_count()];
            vertex + Vector::new(support::hash_unit(3 * i), support::hash_unit(3 * i + 1), support::hash_unit(3 * i + 2))
        })
        .collect();
    let mut group = c.benchmark_group("spatial_500k");
    group.sample_size(10);
    group.bench_function("kd_tree_build_250k_points", |b| b.iter(|| KdTree::new(&mesh.positions)));
    let tree = KdTree::new(&mesh.positions);
    group.bench_function("kd_tree_100k_nearest", |b| {
        b.iter(|| queries.iter().map(|q| tree.nearest(q).map_or(0, |n| n.index)).sum::<usize>())
    });
    group.bench_function("kd_tree_100k_16_nearest", |b| {
        b.iter(|| queries.iter().map(|q| tree.k_nearest(q, 16).len()).sum::<usize>())
    });
    group.bench_function("bvh_build_500k_faces", |b| b.iter(|| Bvh::new(&mesh)));
    let bvh = Bvh::new(&mesh);
    // Rays from those points towards the torus's core circle (through the tube): they
    // hit the near side of the tube, or the far side for points just inside.
    let rays: Vec<(Point, Vector)> = queries
        .iter()
        .map(|q| {
            let core = Vector::new(q.x, q.y, 0.0).normalize() * 100.0;
            (*q, Point::from(core) - q)
        })
        .collect();
    group.bench_function("bvh_100k_closest_hit", |b| {
        b.iter(|| rays.iter().filter(|(o, d)| bvh.closest_hit(o, d).is_some()).count())
    });
    group.bench_function("bvh_100k_any_hit", |b| {
        b.iter(|| rays.iter().filter(|(o, d)| bvh.any_hit(o, d, 1000.0)).count())
    });
    group.bench_function("bvh_100k_closest_point", |b| {
        b.iter(|| queries.iter().map(|q| bvh.closest_point(q).map_or(0.0, |p| p.distance)).sum::<f64>())
    });
    group.finish();
}

criterion_group!(benches, processing, spatial);
criterion_main!(benches);
