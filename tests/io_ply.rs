//! PLY reading and writing: round trips of every attribute in both encodings, the type
//! and layout variants scanners write, and the real scans of `../shared/data`.

use std::io::Cursor;
use std::path::{Path, PathBuf};

use sherd::mesh::io::{PlyEncoding, read_mesh, read_mesh_with_report, read_ply_from, read_ply_from_with_report, write_ply, write_ply_to};
use sherd::mesh::{Mesh, Point, Texture, Vector};

/// A square pyramid with every optional attribute, values chosen to be exact in f32.
fn pyramid_with_attributes() -> Mesh {
    let positions = vec![
        Point::new(0.0, 0.0, 0.0),
        Point::new(10.0, 0.0, 0.0),
        Point::new(10.0, 10.0, 0.0),
        Point::new(0.0, 10.0, 0.0),
        Point::new(5.0, 5.0, 7.5),
    ];
    let triangles = vec![[0, 2, 1], [0, 3, 2], [0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]];
    let mut mesh = Mesh::new(positions, triangles);
    mesh.normals = Some(vec![
        Vector::new(0.0, 0.0, -1.0),
        Vector::new(1.0, 0.0, 0.0),
        Vector::new(0.0, 1.0, 0.0),
        Vector::new(-1.0, 0.0, 0.0),
        Vector::new(0.0, 0.0, 1.0),
    ]);
    mesh.colors = Some(vec![[255, 0, 0, 255], [0, 255, 0, 128], [0, 0, 255, 0], [12, 34, 56, 78], [200, 201, 202, 203]]);
    mesh.quality = Some(vec![0.0, 0.25, -1.5, 1000.0, 3.0]);
    mesh
}

fn assert_same_mesh(read: &Mesh, written: &Mesh) {
    assert_eq!(read.triangles, written.triangles);
    assert_eq!(read.positions.len(), written.positions.len());
    for (a, b) in read.positions.iter().zip(&written.positions) {
        assert!((a - b).norm() < 1e-5, "{a} vs {b}");
    }
    assert_eq!(read.colors, written.colors);
    assert_eq!(read.quality, written.quality);
    match (&read.normals, &written.normals) {
        (Some(a), Some(b)) => assert!(a.iter().zip(b).all(|(a, b)| (a - b).norm() < 1e-6)),
        (None, None) => {}
        other => panic!("normals differ: {other:?}"),
    }
    assert_eq!(read.corner_uvs, written.corner_uvs);
}

#[test]
fn binary_and_ascii_round_trips_keep_every_attribute() {
    let mesh = pyramid_with_attributes();
    for encoding in [PlyEncoding::BinaryLittleEndian, PlyEncoding::Ascii] {
        let mut bytes = Vec::new();
        write_ply_to(&mut bytes, &mesh, encoding).unwrap();
        let (read, report) = read_ply_from_with_report(&mut Cursor::new(bytes), "memory.ply").unwrap();
        assert_same_mesh(&read, &mesh);
        assert!(report.warnings.is_empty(), "{encoding:?}: {:?}", report.warnings);
    }
}

#[test]
fn write_ply_is_atomic_and_textured_meshes_get_their_image_beside() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("pot.ply");
    let mut mesh = pyramid_with_attributes();
    mesh.corner_uvs = Some((0..18).map(|i| [i as f32 / 18.0, 1.0 - i as f32 / 36.0]).collect());
    let rgba: Vec<u8> = (0..4 * 3 * 2).map(|i| (i * 10) as u8).collect();
    mesh.texture = Some(Texture { width: 3, height: 2, rgba: rgba.clone(), source: None });
    write_ply(&path, &mesh, PlyEncoding::BinaryLittleEndian).unwrap();
    let mut names: Vec<String> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    assert_eq!(names, vec!["pot.ply", "pot_texture.png"]);
    let (read, report) = read_mesh_with_report(&path).unwrap();
    assert!(report.warnings.is_empty(), "{:?}", report.warnings);
    assert_same_mesh(&read, &mesh);
    let texture = read.texture.expect("texture loaded from the TextureFile comment");
    assert_eq!((texture.width, texture.height, texture.rgba), (3, 2, rgba));
}

/// Builds a PLY file from a header body and little- or big-endian value writers.
fn header(format: &str, lines: &[&str]) -> Vec<u8> {
    let mut text = format!("ply\nformat {format} 1.0\n");
    for line in lines {
        text += line;
        text.push('\n');
    }
    text += "end_header\n";
    text.into_bytes()
}

#[test]
fn float_colours_uint_indices_and_unknown_elements() {
    let mut bytes = header(
        "binary_little_endian",
        &[
            "comment made by hand",
            "element vertex 3",
            "property float x",
            "property float y",
            "property float z",
            "property float red",
            "property float green",
            "property float blue",
            "property list uchar uchar flags",
            "element face 1",
            "property uchar material",
            "property list int uint vertex_index",
            "property float face_quality",
            "element edge 1",
            "property int vertex1",
            "property int vertex2",
        ],
    );
    for (position, colour) in [([0f32, 0.0, 0.0], [1.0f32, 0.0, 0.5]), ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]), ([0.0, 1.0, 0.0], [0.2, 0.4, 0.6])] {
        for c in position.iter().chain(&colour) {
            bytes.extend(c.to_le_bytes());
        }
        bytes.extend([2u8, 7, 9]);
    }
    bytes.push(4);
    bytes.extend(3i32.to_le_bytes());
    for i in [0u32, 1, 2] {
        bytes.extend(i.to_le_bytes());
    }
    bytes.extend(0.5f32.to_le_bytes());
    bytes.extend(0i32.to_le_bytes());
    bytes.extend(1i32.to_le_bytes());
    let (mesh, report) = read_ply_from_with_report(&mut Cursor::new(bytes), "hand.ply").unwrap();
    assert_eq!(mesh.triangles, vec![[0, 1, 2]]);
    assert_eq!(mesh.colors.unwrap(), vec![[255, 0, 128, 255], [0, 255, 0, 255], [51, 102, 153, 255]]);
    let warnings = report.warnings.join("\n");
    for skipped in ["vertex property flags", "face property material", "face property face_quality", "element edge"] {
        assert!(warnings.contains(skipped), "{skipped} not in {warnings}");
    }
}

#[test]
fn big_endian_with_ascii_twin_reads_identically() {
    let lines = [
        "element vertex 4",
        "property double x",
        "property double y",
        "property double z",
        "property uchar red",
        "property uchar green",
        "property uchar blue",
        "property uchar alpha",
        "property float quality",
        "element face 1",
        "property list uchar int vertex_indices",
    ];
    let vertices = [[0.0, 0.0, 0.0], [2.5, 0.0, 0.0], [2.5, 2.5, 0.125], [0.0, 2.5, 0.0f64]];
    let mut binary = header("binary_big_endian", &lines);
    let mut ascii = header("ascii", &lines);
    for (i, v) in vertices.iter().enumerate() {
        for c in v {
            binary.extend(c.to_be_bytes());
        }
        binary.extend([i as u8 * 60, 1, 2, 255]);
        binary.extend((i as f32 * 0.5).to_be_bytes());
        ascii.extend(format!("{} {} {} {} 1 2 255 {}\n", v[0], v[1], v[2], i * 60, i as f32 * 0.5).bytes());
    }
    binary.push(4);
    for i in [0i32, 1, 2, 3] {
        binary.extend(i.to_be_bytes());
    }
    ascii.extend(b"4 0 1 2 3\n");
    let (from_binary, report) = read_ply_from_with_report(&mut Cursor::new(binary), "be.ply").unwrap();
    let from_ascii = read_ply_from(&mut Cursor::new(ascii), "ascii.ply").unwrap();
    assert_eq!(from_binary, from_ascii);
    assert_eq!(from_binary.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    assert_eq!(from_binary.positions[2], Point::new(2.5, 2.5, 0.125));
    assert_eq!(from_binary.quality.as_ref().unwrap()[3], 1.5);
    assert_eq!(report.format, "ply binary_big_endian");
    assert_eq!(report.polygons_triangulated, 1);
}

#[test]
fn per_vertex_texture_coordinates_become_corner_coordinates() {
    let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty float s\nproperty float t\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 2 1 0\n";
    let mesh = read_ply_from(&mut Cursor::new(text), "st.ply").unwrap();
    assert_eq!(mesh.corner_uvs.unwrap(), vec![[0.0, 1.0], [1.0, 0.0], [0.0, 0.0]]);
}

#[test]
fn missing_texture_is_a_warning_not_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("textured.ply");
    let text = "ply\nformat ascii 1.0\ncomment TextureFile absent.png\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nproperty list uchar float texcoord\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 6 0 0 1 0 0 1\n";
    std::fs::write(&path, text).unwrap();
    let (mesh, report) = read_mesh_with_report(&path).unwrap();
    assert_eq!(mesh.corner_uvs.unwrap()[2], [0.0, 1.0]);
    assert!(mesh.texture.is_none());
    assert!(report.warnings.iter().any(|w| w.contains("absent.png")), "{:?}", report.warnings);
}

fn shared_data(relative: &str) -> Option<PathBuf> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data").join(relative);
    if path.exists() {
        Some(path)
    } else {
        println!("SKIPPED: {} is absent", path.display());
        None
    }
}

#[test]
fn real_scan_a011_has_its_known_counts_and_attributes() {
    let Some(path) = shared_data("dacord/A011.ply") else { return };
    let (mesh, report) = read_mesh_with_report(&path).unwrap();
    assert_eq!(mesh.vertex_count(), 34_345);
    assert_eq!(mesh.face_count(), 68_601);
    assert!(mesh.normals.is_some() && mesh.colors.is_some());
    assert!(mesh.validate().is_ok());
    assert_eq!(report.format, "ply binary_little_endian");
    // Written and read again, it is the same mesh (within float precision).
    let mut bytes = Vec::new();
    write_ply_to(&mut bytes, &mesh, PlyEncoding::BinaryLittleEndian).unwrap();
    let again = read_ply_from(&mut Cursor::new(bytes), "again.ply").unwrap();
    assert_same_mesh(&again, &mesh);
}

#[test]
fn real_point_clouds_load_without_faces() {
    if let Some(path) = shared_data("vessel_fragment_uja/AL_12B_1024p.ply") {
        let (mesh, report) = read_mesh_with_report(&path).unwrap();
        assert_eq!((mesh.vertex_count(), mesh.face_count()), (1024, 0));
        assert!(report.warnings.iter().any(|w| w.contains("element camera")), "{:?}", report.warnings);
    }
    if let Some(path) = shared_data("vessel_fragment_uja/CC_04_4_5f_128r_9it.ply") {
        let mesh = read_mesh(&path).unwrap();
        assert_eq!(mesh.vertex_count(), 5120);
        assert!(mesh.is_point_cloud() && mesh.colors.is_some());
    }
}
