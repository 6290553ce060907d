//! OBJ (+MTL, PNG and JPEG textures), STL (ascii and binary) and XYZ/PTS reading, and
//! `read_mesh`'s dispatch by extension.

use std::path::{Path, PathBuf};

use sherd::mesh::io::{read_mesh, read_mesh_with_report};
use sherd::mesh::{Point, Vector};

const TEXTURED_QUAD_OBJ: &str = "# photogrammetry export\nmtllib quad.mtl\no quad\nv 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nusemtl clay\ns off\nf 1/1/1 2/2/1 3/3/1 4/4/1\n";

fn write_png(path: &Path, width: u32, height: u32, rgb: &[u8]) {
    let file = std::fs::File::create(path).unwrap();
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.write_header().unwrap().write_image_data(rgb).unwrap();
}

fn textured_quad(dir: &Path, map: &str) -> PathBuf {
    std::fs::write(dir.join("quad.mtl"), format!("newmtl clay\nKd 1 1 1\nmap_Kd {map}\n")).unwrap();
    let path = dir.join("quad.obj");
    std::fs::write(&path, TEXTURED_QUAD_OBJ).unwrap();
    path
}

#[test]
fn obj_with_png_texture() {
    let dir = tempfile::tempdir().unwrap();
    let rgb: Vec<u8> = (0..2 * 3 * 3).map(|i| (i * 13) as u8).collect();
    write_png(&dir.path().join("clay colour.png"), 2, 3, &rgb);
    let path = textured_quad(dir.path(), "-s 1 1 1 clay colour.png");
    let (mesh, report) = read_mesh_with_report(&path).unwrap();
    assert!(report.warnings.is_empty(), "{:?}", report.warnings);
    assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    assert_eq!(mesh.corner_uvs.as_ref().unwrap(), &vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
    assert!(mesh.normals.as_ref().unwrap().iter().all(|n| *n == Vector::z()));
    let texture = mesh.texture.unwrap();
    assert_eq!((texture.width, texture.height), (2, 3));
    assert_eq!(&texture.rgba[4..8], &[rgb[3], rgb[4], rgb[5], 255]);
}

#[test]
fn obj_with_jpeg_texture() {
    let dir = tempfile::tempdir().unwrap();
    let (width, height) = (16u16, 8u16);
    let rgb: Vec<u8> = std::iter::repeat_n([200u8, 120, 40], width as usize * height as usize).flatten().collect();
    jpeg_encoder::Encoder::new_file(dir.path().join("clay.jpg"), 95).unwrap().encode(&rgb, width, height, jpeg_encoder::ColorType::Rgb).unwrap();
    let path = textured_quad(dir.path(), "clay.jpg");
    let (mesh, report) = read_mesh_with_report(&path).unwrap();
    assert!(report.warnings.is_empty(), "{:?}", report.warnings);
    let texture = mesh.texture.unwrap();
    assert_eq!((texture.width, texture.height), (16, 8));
    for pixel in texture.rgba.chunks_exact(4) {
        for (got, want) in pixel.iter().zip([200u8, 120, 40, 255]) {
            assert!(got.abs_diff(want) <= 6, "{pixel:?}");
        }
    }
}

#[test]
fn obj_missing_texture_and_missing_library_are_warnings() {
    let dir = tempfile::tempdir().unwrap();
    let path = textured_quad(dir.path(), "gone.png");
    let (mesh, report) = read_mesh_with_report(&path).unwrap();
    assert_eq!(mesh.face_count(), 2);
    assert!(mesh.texture.is_none() && mesh.corner_uvs.is_some());
    assert!(report.warnings.iter().any(|w| w.contains("texture missing") && w.contains("gone.png")), "{:?}", report.warnings);
    std::fs::remove_file(dir.path().join("quad.mtl")).unwrap();
    let (_, report) = read_mesh_with_report(&path).unwrap();
    assert!(report.warnings.iter().any(|w| w.contains("material library") && w.contains("quad.mtl")), "{:?}", report.warnings);
}

#[test]
fn obj_vertex_colours_and_point_cloud_normals() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("coloured.obj");
    std::fs::write(&path, "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 0.5\nf 1 2 3\n").unwrap();
    let mesh = read_mesh(&path).unwrap();
    assert_eq!(mesh.colors.unwrap(), vec![[255, 0, 0, 255], [0, 255, 0, 255], [0, 0, 128, 255]]);
    let path = dir.path().join("cloud.OBJ");
    std::fs::write(&path, "v 0 0 0\nvn 0 0 3\nv 1 0 0\nvn 1 0 0\n").unwrap();
    let mesh = read_mesh(&path).unwrap();
    assert!(mesh.is_point_cloud());
    assert_eq!(mesh.normals.unwrap(), vec![Vector::z(), Vector::x()]);
}

#[test]
fn obj_and_ply_comments_declaring_a_unit_are_reported() {
    use sherd::mesh::io::LengthUnit;
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("metres.obj");
    std::fs::write(&obj, "# exported by a photogrammetry tool\n# Units: meters\nv 0 0 0\nv 0.1 0 0\nv 0 0.1 0 # a vertex\nf 1 2 3\n").unwrap();
    assert_eq!(read_mesh_with_report(&obj).unwrap().1.declared_unit, Some(LengthUnit::Metres));
    let ply = dir.path().join("cm.ply");
    std::fs::write(&ply, "ply\nformat ascii 1.0\nobj_info length_unit = cm\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap();
    assert_eq!(read_mesh_with_report(&ply).unwrap().1.declared_unit, Some(LengthUnit::Centimetres));
    let silent = dir.path().join("silent.obj");
    std::fs::write(&silent, TEXTURED_QUAD_OBJ.replace("mtllib quad.mtl\n", "")).unwrap();
    assert_eq!(read_mesh_with_report(&silent).unwrap().1.declared_unit, None, "a comment without a unit declares none");
}

fn tetrahedron_corners() -> [[[f32; 3]; 3]; 4] {
    let p = [[0.0f32, 0.0, 0.0], [10.0, 0.0, 0.0], [0.0, 10.0, 0.0], [0.0, 0.0, 10.0]];
    [[p[0], p[2], p[1]], [p[0], p[1], p[3]], [p[0], p[3], p[2]], [p[1], p[2], p[3]]]
}

#[test]
fn stl_ascii_and_binary_give_the_same_indexed_mesh() {
    let dir = tempfile::tempdir().unwrap();
    let mut ascii = String::from("solid tetra\n");
    let mut binary = vec![0u8; 80];
    binary.extend(4u32.to_le_bytes());
    for triangle in tetrahedron_corners() {
        ascii += "  facet normal 0 0 0\n    outer loop\n";
        binary.extend([0u8; 12]);
        for corner in triangle {
            ascii += &format!("      vertex {} {} {}\n", corner[0], corner[1], corner[2]);
            corner.iter().for_each(|c| binary.extend(c.to_le_bytes()));
        }
        ascii += "    endloop\n  endfacet\n";
        binary.extend([0u8; 2]);
    }
    ascii += "endsolid tetra\n";
    std::fs::write(dir.path().join("a.stl"), ascii).unwrap();
    std::fs::write(dir.path().join("b.STL"), binary).unwrap();
    let (from_ascii, ascii_report) = read_mesh_with_report(&dir.path().join("a.stl")).unwrap();
    let (from_binary, binary_report) = read_mesh_with_report(&dir.path().join("b.STL")).unwrap();
    assert_eq!((ascii_report.format.as_str(), binary_report.format.as_str()), ("stl ascii", "stl binary"));
    assert_eq!(from_ascii, from_binary);
    assert_eq!(from_ascii.vertex_count(), 4);
    assert_eq!(from_ascii.triangles, vec![[0, 1, 2], [0, 2, 3], [0, 3, 1], [2, 1, 3]]);
    assert!((from_ascii.surface_area() - (150.0 + 50.0 * 3f64.sqrt())).abs() < 1e-9);
}

#[test]
fn sfspp_xyz_surface_with_normals() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/sfspp_pot_C/surfaces_subsample/Pot_C_Piece_01_Surface_0.first128.xyz");
    if !path.exists() {
        println!("SKIPPED: {} is absent", path.display());
        return;
    }
    let mesh = read_mesh(&path).unwrap();
    assert_eq!(mesh.vertex_count(), 128);
    assert!(mesh.is_point_cloud());
    assert!((mesh.positions[0] - Point::new(10.3342, 24.8276, 444.979)).norm() < 1e-9);
    assert!(mesh.normals.unwrap().iter().all(|n| (n.norm() - 1.0).abs() < 1e-9));
}

#[test]
fn unknown_extension_is_refused_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scan.fbx");
    std::fs::write(&path, "whatever").unwrap();
    let message = read_mesh(&path).unwrap_err().to_string();
    assert!(message.contains("scan.fbx") && message.contains("unsupported extension"), "{message}");
}
