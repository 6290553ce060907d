//! `sherd info`: on a synthetic scan written by the library, on a broken file, and on
//! the real scan A011.ply (skipped where ../shared/data is absent).

use std::path::Path;

use assert_cmd::Command;
use sherd::mesh::io::{PlyEncoding, write_ply};
use sherd::mesh::{Mesh, Point};

fn info_json(path: &Path) -> serde_json::Value {
    let output = Command::cargo_bin("sherd").unwrap().args(["info", "--json"]).arg(path).output().unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    serde_json::from_slice(&output.stdout).expect("one JSON object on stdout")
}

/// A closed tetrahedron 40 mm across, with colours.
fn coloured_tetrahedron() -> Mesh {
    let mut mesh = Mesh::new(
        vec![Point::new(0.0, 0.0, 0.0), Point::new(40.0, 0.0, 0.0), Point::new(0.0, 30.0, 0.0), Point::new(0.0, 0.0, 20.0)],
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    );
    mesh.colors = Some(vec![[200, 150, 100, 255]; 4]);
    mesh
}

#[test]
fn info_describes_a_synthetic_scan() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("tetra.ply");
    write_ply(&path, &coloured_tetrahedron(), PlyEncoding::BinaryLittleEndian).unwrap();
    let info = info_json(&path);
    assert_eq!(info["vertex_count"], 4);
    assert_eq!(info["face_count"], 4);
    assert_eq!(info["point_cloud"], false);
    assert_eq!(info["bounding_box"]["size"], serde_json::json!([40.0, 30.0, 20.0]));
    assert_eq!(info["units_guess"]["unit"], "millimetres");
    assert_eq!((info["has_colours"].as_bool(), info["has_normals"].as_bool()), (Some(true), Some(false)));
    assert_eq!(info["format"], "ply binary_little_endian");

    let text = Command::cargo_bin("sherd").unwrap().arg("info").arg(&path).output().unwrap();
    let text = String::from_utf8(text.stdout).unwrap();
    assert!(text.contains("vertices:   4\n") && text.contains("units:      mm"), "{text}");
}

#[test]
fn info_on_a_broken_file_fails_with_the_file_and_place() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("broken.ply");
    std::fs::write(&path, "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 x 0\n").unwrap();
    let output = Command::cargo_bin("sherd").unwrap().arg("info").arg(&path).output().unwrap();
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("broken.ply") && stderr.contains("line 9") && stderr.contains("vertex 1 of 2"), "{stderr}");
    assert!(output.stdout.is_empty());
}

#[test]
fn info_on_the_real_scan_a011() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/dacord/A011.ply");
    if !path.exists() {
        println!("SKIPPED: {} is absent", path.display());
        return;
    }
    let info = info_json(&path);
    assert_eq!(info["vertex_count"], 34_345);
    assert_eq!(info["face_count"], 68_601);
    assert_eq!((info["has_colours"].as_bool(), info["has_normals"].as_bool()), (Some(true), Some(true)));
    assert_eq!(info["units_guess"]["unit"], "millimetres");
}
