//! The PLY writer, in the layout MeshLab (VCG) writes and Blender's importer reads: float
//! positions, float normals, uchar RGBA colours, float quality, `uchar int vertex_indices`
//! and, for textured meshes, MeshLab's per-corner `texcoord` list with a
//! `comment TextureFile` line.

use std::io::Write;
use std::path::Path;

use super::texture;
use crate::mesh::Mesh;
use crate::mesh::atomic::{write_atomically, write_bytes_atomically};
use crate::{Error, Result};

/// How a PLY body is stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlyEncoding {
    /// `binary_little_endian`: compact and fast; what scanners and MeshLab write.
    BinaryLittleEndian,
    /// `ascii`: readable, for small files and diffs.
    Ascii,
}

/// Coordinates beyond this magnitude are written as double: a float's resolution there
/// (2^16 / 2^24 = 0.004) would no longer be negligible against scanner noise in mm.
const LARGEST_FLOAT_COORDINATE: f64 = 65536.0;

/// Writes `mesh` as PLY at `path`, atomically (a failed write leaves no file and keeps an
/// older one). A texture is written beside it as `<stem>_texture.png` and named in the
/// header, as MeshLab does.
pub fn write_ply(path: &Path, mesh: &Mesh, encoding: PlyEncoding) -> Result<()> {
    mesh.validate()?;
    let texture_name = match (&mesh.texture, &mesh.corner_uvs) {
        (Some(image), Some(_)) => {
            let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "mesh".into());
            let name = format!("{stem}_texture.png");
            let mut bytes = Vec::new();
            texture::encode_png(image, &mut bytes)?;
            write_bytes_atomically(&path.with_file_name(&name), &bytes)?;
            Some(name)
        }
        _ => None,
    };
    let name = path.display().to_string();
    write_atomically(path, |writer| write_ply_body(writer, mesh, encoding, texture_name.as_deref(), &name))
}

/// Writes `mesh` as PLY to any writer. A texture is named in the header by the file name
/// of its `source` (the caller places the image); its pixels are not written.
pub fn write_ply_to(writer: &mut dyn Write, mesh: &Mesh, encoding: PlyEncoding) -> Result<()> {
    mesh.validate()?;
    let texture_name = mesh
        .texture
        .as_ref()
        .and_then(|t| t.source.as_ref())
        .and_then(|p| p.file_name())
        .map(|n| n.to_string_lossy().into_owned());
    write_ply_body(writer, mesh, encoding, texture_name.as_deref(), "<stream>")
}

fn write_ply_body(writer: &mut dyn Write, mesh: &Mesh, encoding: PlyEncoding, texture_name: Option<&str>, name: &str) -> Result<()> {
    let io_error = |e| Error::io(name, e);
    let double = mesh.positions.iter().any(|p| p.iter().any(|c| c.abs() > LARGEST_FLOAT_COORDINATE));
    let coordinate_type = if double { "double" } else { "float" };
    let uvs = mesh.corner_uvs.as_ref();
    let mut header = String::from("ply\n");
    header += match encoding {
        PlyEncoding::BinaryLittleEndian => "format binary_little_endian 1.0\n",
        PlyEncoding::Ascii => "format ascii 1.0\n",
    };
    header += &format!("comment Created by sherd {}\n", env!("CARGO_PKG_VERSION"));
    if let (Some(texture), Some(_)) = (texture_name, uvs) {
        header += &format!("comment TextureFile {texture}\n");
    }
    header += &format!("element vertex {}\n", mesh.positions.len());
    for axis in ["x", "y", "z"] {
        header += &format!("property {coordinate_type} {axis}\n");
    }
    if mesh.normals.is_some() {
        header += "property float nx\nproperty float ny\nproperty float nz\n";
    }
    if mesh.colors.is_some() {
        header += "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n";
    }
    if mesh.quality.is_some() {
        header += "property float quality\n";
    }
    header += &format!("element face {}\nproperty list uchar int vertex_indices\n", mesh.triangles.len());
    if uvs.is_some() {
        header += "property list uchar float texcoord\n";
    }
    header += "end_header\n";
    writer.write_all(header.as_bytes()).map_err(io_error)?;

    // Rows are gathered in a buffer and written in large blocks: one write call per
    // value costs more than the encoding itself.
    let mut buffer: Vec<u8> = Vec::with_capacity(1 << 16);
    let mut flush = |buffer: &mut Vec<u8>, force: bool| -> Result<()> {
        if force || buffer.len() > (1 << 16) - 256 {
            writer.write_all(buffer).map_err(io_error)?;
            buffer.clear();
        }
        Ok(())
    };
    for (vertex, position) in mesh.positions.iter().enumerate() {
        match encoding {
            PlyEncoding::BinaryLittleEndian => {
                for c in position.iter() {
                    if double {
                        buffer.extend(c.to_le_bytes());
                    } else {
                        buffer.extend((*c as f32).to_le_bytes());
                    }
                }
                if let Some(normals) = &mesh.normals {
                    for c in normals[vertex].iter() {
                        buffer.extend((*c as f32).to_le_bytes());
                    }
                }
                if let Some(colors) = &mesh.colors {
                    buffer.extend(colors[vertex]);
                }
                if let Some(quality) = &mesh.quality {
                    buffer.extend(quality[vertex].to_le_bytes());
                }
            }
            PlyEncoding::Ascii => {
                use std::fmt::Write as _;
                let mut line = if double {
                    format!("{} {} {}", position.x, position.y, position.z)
                } else {
                    format!("{} {} {}", position.x as f32, position.y as f32, position.z as f32)
                };
                if let Some(normals) = &mesh.normals {
                    let n = normals[vertex];
                    let _ = write!(line, " {} {} {}", n.x as f32, n.y as f32, n.z as f32);
                }
                if let Some(colors) = &mesh.colors {
                    let [r, g, b, a] = colors[vertex];
                    let _ = write!(line, " {r} {g} {b} {a}");
                }
                if let Some(quality) = &mesh.quality {
                    let _ = write!(line, " {}", quality[vertex]);
                }
                line.push('\n');
                buffer.extend(line.as_bytes());
            }
        }
        flush(&mut buffer, false)?;
    }
    for (face, triangle) in mesh.triangles.iter().enumerate() {
        let corner_uvs = uvs.map(|uvs| &uvs[3 * face..3 * face + 3]);
        match encoding {
            PlyEncoding::BinaryLittleEndian => {
                buffer.push(3);
                for &v in triangle {
                    buffer.extend((v as i32).to_le_bytes());
                }
                if let Some(corner_uvs) = corner_uvs {
                    buffer.push(6);
                    for c in corner_uvs.iter().flatten() {
                        buffer.extend(c.to_le_bytes());
                    }
                }
            }
            PlyEncoding::Ascii => {
                let mut line = format!("3 {} {} {}", triangle[0], triangle[1], triangle[2]);
                if let Some(corner_uvs) = corner_uvs {
                    line += " 6";
                    for c in corner_uvs.iter().flatten() {
                        line += &format!(" {c}");
                    }
                }
                line.push('\n');
                buffer.extend(line.as_bytes());
            }
        }
        flush(&mut buffer, false)?;
    }
    flush(&mut buffer, true)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Point;

    #[test]
    fn ascii_header_lists_only_present_attributes() {
        let mut mesh = Mesh::new(vec![Point::new(0.0, 0.0, 0.0), Point::new(1.0, 0.0, 0.0), Point::new(0.0, 1.0, 0.5)], vec![[0, 1, 2]]);
        mesh.quality = Some(vec![0.0, 1.0, 2.5]);
        let mut bytes = Vec::new();
        write_ply_to(&mut bytes, &mesh, PlyEncoding::Ascii).unwrap();
        let text = String::from_utf8(bytes).unwrap();
        assert!(text.contains("property float quality\n"));
        assert!(!text.contains("nx") && !text.contains("red"));
        assert!(text.ends_with("end_header\n0 0 0 0\n1 0 0 1\n0 1 0.5 2.5\n3 0 1 2\n"), "{text}");
    }

    #[test]
    fn far_coordinates_are_written_as_double() {
        let mesh = Mesh::new(vec![Point::new(500000.125, 0.0, 0.0)], vec![]);
        let mut bytes = Vec::new();
        write_ply_to(&mut bytes, &mesh, PlyEncoding::BinaryLittleEndian).unwrap();
        let header_end = bytes.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
        assert!(String::from_utf8_lossy(&bytes[..header_end]).contains("property double x"));
        assert_eq!(f64::from_le_bytes(bytes[header_end..header_end + 8].try_into().unwrap()), 500000.125);
    }

    #[test]
    fn invalid_mesh_is_refused_and_no_file_is_left() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("bad.ply");
        let mesh = Mesh::new(vec![Point::origin()], vec![[0, 1, 2]]);
        assert!(write_ply(&path, &mesh, PlyEncoding::BinaryLittleEndian).is_err());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }
}
