//! Blender as the second host of sherd's PLY files: a real Blender, run headless, imports
//! what sherd writes (same counts, positions, colours), and sherd reads what Blender's
//! exporter writes (per-vertex UVs, normals, colours). Skips when `blender` is not
//! installed, fails instead when SHERD_REQUIRE_TOOLS=1 (as `tests/run_all.sh` sets).

use std::path::Path;
use std::process::Command;

use sherd::mesh::io::{PlyEncoding, read_mesh_with_report, write_ply};
use sherd::mesh::{Mesh, Point, Vector};

fn blender_available() -> bool {
    let found = Command::new("blender").arg("--version").output().is_ok_and(|o| o.status.success());
    if !found {
        if std::env::var("SHERD_REQUIRE_TOOLS").as_deref() == Ok("1") {
            panic!("Blender is required (SHERD_REQUIRE_TOOLS=1) but `blender --version` fails");
        }
        println!("SKIPPED: Blender is not installed (apt-get install blender)");
    }
    found
}

/// Runs a Python script inside headless Blender; its line starting with `RESULT ` holds JSON.
fn blender_json(script: &str, arguments: &[&Path]) -> serde_json::Value {
    let output = Command::new("blender")
        .args(["--background", "--factory-startup", "--python-exit-code", "1", "--python-expr", script, "--"])
        .args(arguments)
        .output()
        .expect("blender runs");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "blender failed:\n{stdout}\n{}", String::from_utf8_lossy(&output.stderr));
    let line = stdout.lines().find_map(|l| l.strip_prefix("RESULT ")).unwrap_or_else(|| panic!("no RESULT line in:\n{stdout}"));
    serde_json::from_str(line).expect("JSON")
}

/// A closed octahedron 60 mm across with normals and colours.
fn octahedron() -> Mesh {
    let r = 30.0;
    let positions = vec![
        Point::new(r, 0.0, 0.0),
        Point::new(-r, 0.0, 0.0),
        Point::new(0.0, r, 0.0),
        Point::new(0.0, -r, 0.0),
        Point::new(0.0, 0.0, r),
        Point::new(0.0, 0.0, -r),
    ];
    let triangles = vec![[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]];
    let mut mesh = Mesh::new(positions, triangles);
    mesh.normals = Some(mesh.positions.iter().map(|p| p.coords / r).collect::<Vec<Vector>>());
    mesh.colors = Some((0..6).map(|i| [40 * i as u8, 255 - 40 * i as u8, 7, 255]).collect());
    mesh
}

const IMPORT: &str = r#"
import bpy, sys, json
path = sys.argv[sys.argv.index("--") + 1]
for o in list(bpy.data.objects):
    bpy.data.objects.remove(o)
bpy.ops.import_mesh.ply(filepath=path)
m = bpy.context.selected_objects[0].data
colours = m.vertex_colors[0].data if len(m.vertex_colors) else None
print("RESULT " + json.dumps({
    "vertices": len(m.vertices), "faces": len(m.polygons),
    "first": list(m.vertices[0].co), "last": list(m.vertices[-1].co),
    "has_colours": colours is not None,
}))
"#;

#[test]
fn blender_imports_what_sherd_writes() {
    if !blender_available() {
        return;
    }
    let mesh = octahedron();
    let dir = tempfile::tempdir().unwrap();
    for (encoding, file) in [(PlyEncoding::BinaryLittleEndian, "binary.ply"), (PlyEncoding::Ascii, "ascii.ply")] {
        let path = dir.path().join(file);
        write_ply(&path, &mesh, encoding).unwrap();
        let seen = blender_json(IMPORT, &[&path]);
        assert_eq!((seen["vertices"].as_u64(), seen["faces"].as_u64()), (Some(6), Some(8)), "{file}: {seen}");
        let last: Vec<f64> = serde_json::from_value(seen["last"].clone()).unwrap();
        assert!((Point::new(last[0], last[1], last[2]) - mesh.positions[5]).norm() < 1e-5, "{file}: {seen}");
        assert_eq!(seen["has_colours"], true, "{file}: {seen}");
    }
}

#[test]
fn sherd_reads_what_blender_writes() {
    if !blender_available() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("monkey.ply");
    let script = r#"
import bpy, sys, json
path = sys.argv[sys.argv.index("--") + 1]
for o in list(bpy.data.objects):
    bpy.data.objects.remove(o)
bpy.ops.mesh.primitive_monkey_add(size=100.0)
obj = bpy.context.active_object
m = obj.data
m.vertex_colors.new()
bpy.ops.export_mesh.ply(filepath=path, use_selection=True, use_normals=True, use_uv_coords=True, use_colors=True, use_ascii=False)
triangles = sum(len(p.vertices) - 2 for p in m.polygons)
print("RESULT " + json.dumps({"polygons": len(m.polygons), "triangles": triangles, "vertices": len(m.vertices)}))
"#;
    let made = blender_json(script, &[&path]);
    let (mesh, report) = read_mesh_with_report(&path).unwrap();
    assert!(report.warnings.is_empty(), "{:?}", report.warnings);
    // Blender splits vertices along UV seams and normal creases, so there are at least as
    // many as in its mesh; the triangles are those of its polygons, fan-triangulated.
    assert!(mesh.vertex_count() as u64 >= made["vertices"].as_u64().unwrap());
    assert_eq!(mesh.face_count() as u64, made["triangles"].as_u64().unwrap());
    assert!(report.polygons_triangulated > 0);
    assert!(mesh.normals.is_some() && mesh.colors.is_some() && mesh.corner_uvs.is_some());
    let (low, high) = mesh.bounding_box().unwrap();
    assert!(((high - low).max() - 100.0 * 1.367).abs() < 3.0, "{low} {high}");
}
