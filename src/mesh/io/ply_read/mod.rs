//! The PLY reader (ascii, binary little and big endian), hand-written rather than built
//! on ply-rs-bw because it is measurably faster on a 500k-face scan (`benches/ply.rs`;
//! BENCHMARKS.md, "PLY reading", has the figures): ply-rs-bw hands every value
//! to a callback by property name (or builds a hash map of them per element), this reader
//! decodes fixed-size records from one slice straight into the mesh's arrays. It also
//! gives what ply-rs-bw does not: it checks, before allocating, that the file can hold
//! what the header declares, and names in every error the file, the header line or body
//! line (ascii) or byte offset (binary), the element and its index, and the value.
//!
//! The header is parsed by [`header`], the records are read from a binary or ascii
//! [`body`], and [`builder`] places each property's value in the mesh.

mod body;
mod builder;
mod header;

use std::io::Read;
use std::path::Path;

use super::{ReadReport, texture};
use crate::mesh::Mesh;
use crate::{Error, Result};
use body::{AsciiBody, BinaryBody, Body};
use builder::{Builder, read_body};
use header::{Encoding, parse_header};

/// Reads a PLY file from any reader; `name` is used in messages. A texture named in the
/// header cannot be located from a stream, so it is reported as a warning and not loaded.
pub fn read_ply_from(reader: &mut dyn Read, name: &str) -> Result<Mesh> {
    read_ply_from_with_report(reader, name).map(|(mesh, _)| mesh)
}

/// [`read_ply_from`] with the [`ReadReport`] of what was skipped.
pub fn read_ply_from_with_report(reader: &mut dyn Read, name: &str) -> Result<(Mesh, ReadReport)> {
    let mut bytes = Vec::new();
    reader.read_to_end(&mut bytes).map_err(|e| Error::io(name, e))?;
    parse_ply(&bytes, name, None)
}

/// Parses a whole PLY file held in memory; `folder` locates a texture named by a
/// `comment TextureFile` line.
pub(super) fn parse_ply(bytes: &[u8], name: &str, folder: Option<&Path>) -> Result<(Mesh, ReadReport)> {
    if bytes.is_empty() {
        return Err(Error::parse(name, "byte 0", "the file is empty"));
    }
    let header = parse_header(bytes, name)?;
    let body = &bytes[header.body_start..];
    let Some(vertex_element) = header.elements.iter().find(|e| e.name == "vertex") else {
        return Err(Error::parse(name, "header", "the header declares no vertex element"));
    };
    // Refuse counts the file cannot hold before any allocation.
    let mut needed: u128 = 0;
    for element in &header.elements {
        needed += element.count as u128 * element.minimum_bytes(header.encoding) as u128;
        if needed > body.len() as u128 + 1 {
            return Err(Error::parse(
                name,
                format!("header line {}", element.line),
                format!(
                    "the header declares {} {} elements, which need at least {} bytes with those before them, but only {} bytes follow the header (lying header or truncated file)",
                    element.count, element.name, needed, body.len()
                ),
            ));
        }
    }
    if vertex_element.count > u32::MAX as u64 {
        return Err(Error::parse(name, format!("header line {}", vertex_element.line), format!("{} vertices declared: more than the 4294967295 a mesh can index", vertex_element.count)));
    }
    let format = match header.encoding {
        Encoding::Ascii => "ply ascii",
        Encoding::BinaryLittleEndian => "ply binary_little_endian",
        Encoding::BinaryBigEndian => "ply binary_big_endian",
    };
    let mut builder = Builder {
        name,
        mesh: Mesh::default(),
        report: ReadReport::new(format),
        declared_vertex_count: vertex_element.count,
        vertex_uvs: None,
    };
    let trailing = match header.encoding {
        Encoding::Ascii => {
            let mut reader = AsciiBody { data: body, position: 0, line: header.line_count + 1, record_line: None };
            read_body(&mut builder, &mut reader, &header)?;
            body[reader.position..].iter().any(|b| !b.is_ascii_whitespace()).then(|| reader.location())
        }
        Encoding::BinaryLittleEndian | Encoding::BinaryBigEndian => {
            let mut reader = BinaryBody { data: body, position: 0, big_endian: header.encoding == Encoding::BinaryBigEndian, base: header.body_start, record_start: 0 };
            read_body(&mut builder, &mut reader, &header)?;
            (reader.position < body.len()).then(|| format!("byte {} ({} bytes)", header.body_start + reader.position, body.len() - reader.position))
        }
    };
    if let Some(location) = trailing {
        builder.report.warn(format!("data after the last element ignored, from {location}"));
    }
    let Builder { mut mesh, mut report, vertex_uvs, .. } = builder;
    report.declared_unit = header.declared_unit;
    if mesh.corner_uvs.is_none() {
        if let Some(uvs) = vertex_uvs {
            mesh.corner_uvs = Some(mesh.triangles.iter().flat_map(|t| t.map(|v| uvs[v as usize])).collect());
        }
    }
    if let Some((file, line)) = header.texture_files.first() {
        match folder {
            Some(folder) => match super::file_in_scan_folder(folder, file, "texture", &format!("{name} header line {line}")) {
                Ok(path) => match texture::load_texture(&path) {
                    Ok(image) => mesh.texture = Some(image),
                    Err(error) => report.warn(format!("texture {file} named in the header not loaded: {error}")),
                },
                Err(refusal) => report.warn(refusal),
            },
            None => report.warn(format!("texture {file} named in the header not loaded: reading from a stream, its folder is unknown")),
        }
        if mesh.corner_uvs.is_none() {
            report.warn(format!("texture {file} named in the header, but the file has no texture coordinates"));
        }
    }
    Ok((mesh, report))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Point;

    fn parse(text: &[u8]) -> Result<(Mesh, ReadReport)> {
        parse_ply(text, "test.ply", None)
    }

    #[test]
    fn ascii_quad_is_fan_triangulated_with_colours() {
        let text = b"ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n0 1 0 10 20 30\n4 0 1 2 3\n";
        let (mesh, report) = parse(text).unwrap();
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(mesh.colors.as_ref().unwrap()[3], [10, 20, 30, 255]);
        assert_eq!(report.polygons_triangulated, 1);
        assert_eq!(report.format, "ply ascii");
    }

    #[test]
    fn big_endian_doubles_and_short_indices() {
        let mut bytes = b"ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\nelement face 1\nproperty list ushort short vertex_index\nend_header\n".to_vec();
        for v in [[0.0, 0.0, 0.0], [1.5, 0.0, 0.0], [0.0, 2.25, -1.0f64]] {
            for c in v {
                bytes.extend(c.to_be_bytes());
            }
        }
        bytes.extend(3u16.to_be_bytes());
        for i in [0i16, 1, 2] {
            bytes.extend(i.to_be_bytes());
        }
        let (mesh, report) = parse(&bytes).unwrap();
        assert_eq!(mesh.positions[2], Point::new(0.0, 2.25, -1.0));
        assert_eq!(mesh.triangles, vec![[0, 1, 2]]);
        assert!(report.warnings.is_empty(), "{:?}", report.warnings);
    }

    #[test]
    fn lying_vertex_count_is_refused_before_allocation() {
        let text = b"ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n\0\0\0\0";
        let message = parse(text).unwrap_err().to_string();
        assert!(message.contains("header line 3") && message.contains("1000000000000"), "{message}");
    }

    #[test]
    fn ascii_errors_name_the_line_and_element() {
        let text = b"ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 zero 0\n";
        let message = parse(text).unwrap_err().to_string();
        assert!(message.contains("line 9") && message.contains("vertex 1 of 2") && message.contains("\"zero\""), "{message}");
        let short = b"ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n0.5 0\n1 0 0\n";
        let message = parse(short).unwrap_err().to_string();
        assert!(message.contains("line 8") && message.contains("vertex 0 of 2") && message.contains("line ends"), "{message}");
    }

    #[test]
    fn crlf_ascii_files_read_like_lf_ones() {
        let lf = b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        let crlf: Vec<u8> = lf.iter().flat_map(|&b| if b == b'\n' { vec![b'\r', b'\n'] } else { vec![b] }).collect();
        assert_eq!(parse(lf).unwrap().0, parse(&crlf).unwrap().0);
    }

    #[test]
    fn binary_index_error_points_at_the_offending_index() {
        let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 2\nproperty list uchar uint vertex_indices\nend_header\n".to_vec();
        let body_start = bytes.len();
        bytes.extend([0u8; 36]);
        for face in [[0u32, 1, 2], [2, 1, 9]] {
            bytes.push(3);
            face.iter().for_each(|i| bytes.extend(i.to_le_bytes()));
        }
        let message = parse(&bytes).unwrap_err().to_string();
        // Vertices, the first face (13 bytes), the count and two indices of the second.
        let offset = body_start + 36 + 13 + 1 + 8;
        assert!(message.contains(&format!("byte {offset} (face 1 of 2, property vertex_indices)")) && message.contains("vertex index 9"), "{message}");
    }
}
