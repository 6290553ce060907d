//! Our decimation against MeshLab's "Quadric Edge Collapse Decimation" (pymeshlab's
//! `meshing_decimation_quadric_edge_collapse`) on the same inputs: the sampled
//! Hausdorff distance to the original, both directions, measured by pymeshlab for
//! both results, must be at most 1.1 times MeshLab's (mean and max).
//!
//! Skips when pymeshlab is missing, unless SHERD_REQUIRE_PYMESHLAB=1 (then fails).

mod support;
#[path = "support/decimation_vessel.rs"]
mod vessel;

use std::process::Command;

use sherd::mesh::decimate::{decimate_with_options, DecimateOptions};
use sherd::mesh::io::{read_mesh, write_ply, PlyEncoding};
use sherd::mesh::Mesh;

/// Decimates the input with MeshLab at MeshLab's boundary-, topology- and
/// normal-preserving settings, then measures both results against the input.
const MESHLAB_SCRIPT: &str = r#"
import json, sys, pymeshlab
original, ours, target = sys.argv[1], sys.argv[2], int(sys.argv[3])
ms = pymeshlab.MeshSet()
ms.load_new_mesh(original)             # id 0
ms.load_new_mesh(original)             # id 1: MeshLab's decimation
ms.meshing_decimation_quadric_edge_collapse(targetfacenum=target, qualitythr=0.3,
    preserveboundary=True, preservetopology=True, preservenormal=True, optimalplacement=True)
ms.load_new_mesh(ours)                 # id 2
samples = 2 * ms.mesh(0).face_number()
def both_ways(decimated):
    there = ms.get_hausdorff_distance(sampledmesh=decimated, targetmesh=0, sampleface=True, samplenum=samples)
    back = ms.get_hausdorff_distance(sampledmesh=0, targetmesh=decimated, sampleface=True, samplenum=samples)
    return {"max": max(there["max"], back["max"]), "mean": (there["mean"] + back["mean"]) / 2,
            "faces": ms.mesh(decimated).face_number()}
print(json.dumps({"meshlab": both_ways(1), "ours": both_ways(2)}))
"#;

#[derive(Debug)]
struct Distances {
    max: f64,
    mean: f64,
    faces: u64,
}

fn parse(json: &serde_json::Value, who: &str) -> Distances {
    let field = |name: &str| json[who][name].as_f64().unwrap_or_else(|| panic!("no {who}.{name} in {json}"));
    Distances { max: field("max"), mean: field("mean"), faces: field("faces") as u64 }
}

/// Decimates `input` with both tools and asserts ours is within 1.1x of MeshLab's.
fn compare_with_meshlab(name: &str, input: &Mesh, target_faces: usize) {
    let directory = tempfile::tempdir().unwrap();
    let (original_path, ours_path) = (directory.path().join("original.ply"), directory.path().join("ours.ply"));
    let (ours, report) = decimate_with_options(input, &DecimateOptions::with_target_faces(target_faces)).unwrap();
    write_ply(&original_path, input, PlyEncoding::BinaryLittleEndian).unwrap();
    write_ply(&ours_path, &ours, PlyEncoding::BinaryLittleEndian).unwrap();
    let output = Command::new("python3")
        .args(["-c", MESHLAB_SCRIPT])
        .arg(&original_path)
        .arg(&ours_path)
        .arg(target_faces.to_string())
        .output()
        .unwrap();
    assert!(output.status.success(), "pymeshlab failed: {}", String::from_utf8_lossy(&output.stderr));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let (meshlab, ours_distances) = (parse(&json, "meshlab"), parse(&json, "ours"));
    eprintln!("{name}: MeshLab {meshlab:?}\n{name}: sherd   {ours_distances:?} ({report:?})");
    assert!(ours_distances.faces.abs_diff(target_faces as u64) <= 1);
    assert!(ours_distances.mean <= 1.1 * meshlab.mean, "{name}: mean Hausdorff {} vs MeshLab {}", ours_distances.mean, meshlab.mean);
    assert!(ours_distances.max <= 1.1 * meshlab.max, "{name}: max Hausdorff {} vs MeshLab {}", ours_distances.max, meshlab.max);
}

#[test]
fn noisy_vessel_as_close_as_meshlab() {
    if !support::pymeshlab_available("noisy_vessel_as_close_as_meshlab") {
        return;
    }
    compare_with_meshlab("noisy vessel", &vessel::noisy_vessel(100_000, 0.2, 7), 10_000);
}

#[test]
fn real_scan_as_close_as_meshlab() {
    let path = support::repo_root().join("../shared/data/dacord/A011.ply");
    if !path.exists() {
        eprintln!("SKIPPED real_scan_as_close_as_meshlab: {} is absent", path.display());
        return;
    }
    if !support::pymeshlab_available("real_scan_as_close_as_meshlab") {
        return;
    }
    let scan = read_mesh(&path).unwrap();
    // 68.6k faces to 10k: the ~5k vertices of the orientation's working copy.
    compare_with_meshlab("A011", &scan, 10_000);
}
