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

    assert_eq!(info["watertight"], true);
    assert_eq!(info["repair"]["component_face_counts"], serde_json::json!([4]));

    let text = Command::cargo_bin("sherd").unwrap().arg("info").arg(&path).output().unwrap();
    let text = String::from_utf8(text.stdout).unwrap();
    assert!(text.contains("vertices:   4\n") && text.contains("units:      mm"), "{text}");
    assert!(text.contains("watertight: yes") && text.contains("repair:     nothing to repair"), "{text}");
}

#[test]
fn info_says_what_repair_did() {
    // The tetrahedron with vertex 0 written twice (faces use either copy), one face
    // written twice and one degenerate face: repair merges, removes, and closes it.
    let mut mesh = coloured_tetrahedron();
    mesh.positions.push(mesh.positions[0]);
    mesh.colors.as_mut().unwrap().push([0, 0, 0, 255]);
    mesh.triangles[1] = [4, 1, 3];
    mesh.triangles.push([1, 2, 3]);
    mesh.triangles.push([1, 1, 2]);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("dirty.ply");
    write_ply(&path, &mesh, PlyEncoding::Ascii).unwrap();
    let info = info_json(&path);
    assert_eq!((info["vertex_count"].as_u64(), info["face_count"].as_u64()), (Some(5), Some(6)));
    let repair = &info["repair"];
    assert_eq!(repair["duplicate_vertices_merged"], 1);
    assert_eq!(repair["duplicate_faces_removed"], 1);
    assert_eq!(repair["degenerate_faces_removed"], 1);
    assert_eq!((repair["vertices_after"].as_u64(), repair["faces_after"].as_u64()), (Some(4), Some(4)));
    assert_eq!(info["watertight"], true);
    let text = Command::cargo_bin("sherd").unwrap().arg("info").arg(&path).output().unwrap();
    let text = String::from_utf8(text.stdout).unwrap();
    assert!(text.contains("1 duplicate vertices merged") && text.contains("4 vertices, 4 faces after"), "{text}");
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
    // A011 as read is already clean: repair finds nothing to change.
    assert_eq!(info["repair"]["vertices_after"], 34_345);
    assert_eq!(info["repair"]["faces_after"], 68_601);
}

/// Counts a scan file declares or holds, found without sherd: the PLY header's element
/// counts, or the non-empty lines of a text point cloud.
fn independent_counts(path: &Path) -> (u64, u64) {
    let bytes = std::fs::read(path).unwrap();
    if path.extension().is_some_and(|e| e == "ply") {
        let header_end = bytes.windows(10).position(|w| w == b"end_header").unwrap();
        let header = String::from_utf8_lossy(&bytes[..header_end]);
        let count = |element: &str| {
            header.lines().find_map(|l| l.strip_prefix(&format!("element {element} "))).map_or(0, |n| n.trim().parse().unwrap())
        };
        (count("vertex"), count("face"))
    } else {
        (String::from_utf8_lossy(&bytes).lines().filter(|l| !l.trim().is_empty()).count() as u64, 0)
    }
}

#[test]
fn info_on_every_scan_of_the_shared_data() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data");
    if !data.exists() {
        println!("SKIPPED: {} is absent", data.display());
        return;
    }
    let mut folders = vec![data];
    let mut scans = 0;
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(folder).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                folders.push(path);
                continue;
            }
            if !path.extension().is_some_and(|e| e == "ply" || e == "xyz") {
                continue;
            }
            let info = info_json(&path);
            let (vertices, faces) = independent_counts(&path);
            assert_eq!(info["vertex_count"].as_u64(), Some(vertices), "{}", path.display());
            // Every face of these files is a triangle.
            assert_eq!(info["face_count"].as_u64(), Some(faces), "{}", path.display());
            assert_eq!(info["point_cloud"].as_bool(), Some(faces == 0), "{}", path.display());
            scans += 1;
        }
    }
    assert!(scans >= 10, "only {scans} scans found");
}
