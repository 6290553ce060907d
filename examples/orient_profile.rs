//! A driver for instruction-count profiles of the automatic pre-orientation: runs it N
//! times on a ~10k-vertex synthetic rim sherd (seed 3 is the mesh of `cargo bench --bench
//! orient`, seed 10 that of `cargo bench --bench ffi`), through the Rust API (`rust`) or
//! through the C ABI from host arrays as the ffi bench does (`c`). Under load, wall-clock
//! benchmarks vary by 2-3x; instruction counts do not:
//!
//!     valgrind --tool=callgrind target/release/examples/orient_profile 1 rust 3
//!     valgrind --tool=callgrind target/release/examples/orient_profile 3 rust 3
//!
//! and the difference of the two totals over 2 is the cost of one orientation, on all
//! threads (rayon's workers included). A fourth argument `body` takes the body sherd of
//! `cargo bench --bench refine` instead, and a fifth `refine` adds the refinement.

use std::ptr;

use sherd::ffi::*;
use sherd::orient::{orient_automatic, OrientOptions};
use sherd::refine::{refine, RefineOptions};
use sherd::synth::{synthetic_sherd, SherdOptions, SherdPart};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let runs: usize = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(1);
    let through_c = args.get(2).is_some_and(|a| a == "c");
    let seed: u64 = args.get(3).and_then(|a| a.parse().ok()).unwrap_or(3);
    let part = if args.get(4).is_some_and(|a| a == "body") { SherdPart::Body } else { SherdPart::Rim };
    let with_refinement = args.get(5).is_some_and(|a| a == "refine");
    let sherd = synthetic_sherd(seed, &SherdOptions { target_faces: 20_000, ..SherdOptions::for_part(part) });
    let mesh = sherd.mesh;
    let positions: Vec<f64> = mesh.positions.iter().flat_map(|p| [p.x, p.y, p.z]).collect();
    let triangles: Vec<u32> = mesh.triangles.iter().flatten().copied().collect();
    let normals: Vec<f64> = mesh.normals.as_ref().expect("synthetic sherds have normals").iter().flat_map(|n| [n.x, n.y, n.z]).collect();
    for _ in 0..runs {
        if through_c {
            // SAFETY: the arrays hold the counts given, the handle is freed once.
            let axis = unsafe {
                let mut handle = ptr::null_mut();
                let status = sherd_mesh_from_arrays(positions.as_ptr(), mesh.vertex_count(), triangles.as_ptr(), mesh.face_count(), &mut handle);
                assert_eq!(status, SherdStatus::Ok);
                assert_eq!(sherd_mesh_set_normals(handle, normals.as_ptr(), mesh.vertex_count()), SherdStatus::Ok);
                let mut axis = SherdAxis { size: size_of::<SherdAxis>(), ..Default::default() };
                sherd_orient_automatic(handle, ptr::null(), &mut axis, ptr::null_mut(), ptr::null_mut());
                sherd_mesh_free(handle);
                axis
            };
            println!("{:?} {:?}", axis.point, axis.direction);
        } else {
            let orientation = orient_automatic(&mesh, &OrientOptions::default()).expect("the bench sherd orients");
            let axis = if with_refinement {
                refine(&mesh, &orientation.axis, &RefineOptions::default()).expect("the bench sherd refines").axis
            } else {
                orientation.axis
            };
            println!("{:?} {:?}", axis.point, axis.direction);
        }
    }
}
