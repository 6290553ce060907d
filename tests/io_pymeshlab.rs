//! MeshLab (pymeshlab) as the reference for PLY: what sherd writes, MeshLab loads with
//! the same counts, positions, colours and quality; what MeshLab writes, sherd reads
//! identically. Skips when pymeshlab is missing, fails instead when
//! SHERD_REQUIRE_PYMESHLAB=1 (as `tests/run_all.sh` sets).

use std::path::Path;
use std::process::Command;

use sherd::mesh::io::{PlyEncoding, read_mesh, write_ply};
use sherd::mesh::{Mesh, Point, Vector};

mod support;

/// Runs a Python snippet with `sys.argv[1:] = arguments` and parses its last stdout line as JSON.
fn python_json(script: &str, arguments: &[&Path]) -> serde_json::Value {
    let output = Command::new("python3").arg("-c").arg(script).args(arguments).output().expect("python3 runs");
    assert!(output.status.success(), "python failed: {}", String::from_utf8_lossy(&output.stderr));
    let stdout = String::from_utf8_lossy(&output.stdout);
    serde_json::from_str(stdout.lines().last().expect("one JSON line")).expect("JSON")
}

/// A wavy 40 x 30 grid: 1,200 vertices, 2,262 triangles, with every attribute.
fn wavy_grid() -> Mesh {
    let (columns, rows) = (40usize, 30usize);
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    let mut colours = Vec::new();
    let mut quality = Vec::new();
    for row in 0..rows {
        for column in 0..columns {
            let (x, y) = (column as f64 * 1.25, row as f64 * 1.5);
            positions.push(Point::new(x, y, (x * 0.3).sin() * 2.0));
            normals.push(Vector::new(-(x * 0.3).cos() * 0.6, 0.0, 1.0).normalize());
            colours.push([(column * 6) as u8, (row * 8) as u8, 77, 255]);
            quality.push((row * columns + column) as f32 * 0.5);
        }
    }
    let mut triangles = Vec::new();
    for row in 0..rows - 1 {
        for column in 0..columns - 1 {
            let corner = (row * columns + column) as u32;
            let columns = columns as u32;
            triangles.push([corner, corner + 1, corner + columns + 1]);
            triangles.push([corner, corner + columns + 1, corner + columns]);
        }
    }
    let mut mesh = Mesh::new(positions, triangles);
    mesh.normals = Some(normals);
    mesh.colors = Some(colours);
    mesh.quality = Some(quality);
    mesh
}

const DESCRIBE: &str = r#"
import sys, json, pymeshlab
ms = pymeshlab.MeshSet()
ms.load_new_mesh(sys.argv[1])
m = ms.current_mesh()
v = m.vertex_matrix(); f = m.face_matrix()
out = {"vertices": m.vertex_number(), "faces": m.face_number(),
       "first_vertex": v[0].tolist(), "last_vertex": v[-1].tolist(), "face_5": f[5].tolist(),
       "has_colour": m.has_vertex_color(), "has_quality": m.has_vertex_scalar()}
if m.has_vertex_color():
    out["colour_7"] = [round(c * 255) for c in m.vertex_color_matrix()[7].tolist()]
if m.has_vertex_scalar():
    out["quality_9"] = float(m.vertex_scalar_array()[9])
print(json.dumps(out))
"#;

#[test]
fn meshlab_loads_what_sherd_writes() {
    if !support::pymeshlab_available("io_pymeshlab") {
        return;
    }
    let mesh = wavy_grid();
    let dir = tempfile::tempdir().unwrap();
    for (encoding, file) in [(PlyEncoding::BinaryLittleEndian, "binary.ply"), (PlyEncoding::Ascii, "ascii.ply")] {
        let path = dir.path().join(file);
        write_ply(&path, &mesh, encoding).unwrap();
        let seen = python_json(DESCRIBE, &[&path]);
        assert_eq!(seen["vertices"], 1200, "{file}: {seen}");
        assert_eq!(seen["faces"], 2262, "{file}: {seen}");
        let last: Vec<f64> = serde_json::from_value(seen["last_vertex"].clone()).unwrap();
        assert!((Point::new(last[0], last[1], last[2]) - mesh.positions[1199]).norm() < 1e-5, "{file}: {last:?}");
        let face: Vec<u32> = serde_json::from_value(seen["face_5"].clone()).unwrap();
        assert_eq!(face, mesh.triangles[5].to_vec(), "{file}");
        let colour: Vec<u8> = serde_json::from_value(seen["colour_7"].clone()).unwrap();
        assert_eq!(colour, mesh.colors.as_ref().unwrap()[7].to_vec(), "{file}");
        assert_eq!(seen["quality_9"].as_f64().unwrap(), 4.5, "{file}");
    }
}

#[test]
fn sherd_reads_what_meshlab_writes() {
    if !support::pymeshlab_available("io_pymeshlab") {
        return;
    }
    let mesh = wavy_grid();
    let dir = tempfile::tempdir().unwrap();
    let ours = dir.path().join("ours.ply");
    write_ply(&ours, &mesh, PlyEncoding::BinaryLittleEndian).unwrap();
    let binary = dir.path().join("meshlab_binary.ply");
    let ascii = dir.path().join("meshlab_ascii.ply");
    let sphere = dir.path().join("meshlab_sphere.ply");
    let script = r#"
import sys, json, pymeshlab
ms = pymeshlab.MeshSet()
ms.load_new_mesh(sys.argv[1])
ms.save_current_mesh(sys.argv[2], binary=True, save_vertex_color=True, save_vertex_normal=True, save_vertex_quality=True)
ms.save_current_mesh(sys.argv[3], binary=False, save_vertex_color=True, save_vertex_normal=True, save_vertex_quality=True)
ms.create_sphere(subdiv=4)
ms.save_current_mesh(sys.argv[4], binary=True)
m = ms.current_mesh()
print(json.dumps({"vertices": m.vertex_number(), "faces": m.face_number(), "first_vertex": m.vertex_matrix()[0].tolist()}))
"#;
    let sphere_seen = python_json(script, &[&ours, &binary, &ascii, &sphere]);
    for path in [&binary, &ascii] {
        let read = read_mesh(path).unwrap();
        assert_eq!(read.triangles, mesh.triangles, "{}", path.display());
        assert!(read.positions.iter().zip(&mesh.positions).all(|(a, b)| (a - b).norm() < 1e-5), "{}", path.display());
        assert_eq!(read.colors, mesh.colors, "{}", path.display());
        assert_eq!(read.quality, mesh.quality, "{}", path.display());
        let normals = read.normals.expect("normals");
        assert!(normals.iter().zip(mesh.normals.as_ref().unwrap()).all(|(a, b)| (a - b).norm() < 1e-5), "{}", path.display());
    }
    let read = read_mesh(&sphere).unwrap();
    assert_eq!(read.vertex_count() as u64, sphere_seen["vertices"].as_u64().unwrap());
    assert_eq!(read.face_count() as u64, sphere_seen["faces"].as_u64().unwrap());
    let first: Vec<f64> = serde_json::from_value(sphere_seen["first_vertex"].clone()).unwrap();
    assert!((read.positions[0] - Point::new(first[0], first[1], first[2])).norm() < 1e-6);
}
