//! STL, ascii and binary. The encoding is recognised by content (exporters write binary
//! files that begin with "solid"), and corners at bit-identical positions are merged so
//! that the mesh is indexed and its topology can be analysed, as MeshLab does on import.

use std::collections::HashMap;

use super::{ReadReport, fan_triangles, show_token};
use crate::mesh::{Mesh, Point};
use crate::{Error, Result};

const BINARY_HEADER_BYTES: usize = 84;
const BINARY_TRIANGLE_BYTES: usize = 50;

pub(super) fn parse_stl(bytes: &[u8], name: &str) -> Result<(Mesh, ReadReport)> {
    let declared = (bytes.len() >= BINARY_HEADER_BYTES).then(|| u32::from_le_bytes(bytes[80..84].try_into().expect("4 bytes")) as usize);
    let binary_size_matches = declared.is_some_and(|n| BINARY_HEADER_BYTES + BINARY_TRIANGLE_BYTES * n == bytes.len());
    let text_start = bytes.iter().position(|b| !b.is_ascii_whitespace()).unwrap_or(bytes.len());
    let looks_ascii = bytes[text_start..].starts_with(b"solid") && !binary_size_matches;
    if looks_ascii {
        return parse_ascii(bytes, name);
    }
    let Some(declared) = declared else {
        return Err(Error::parse(name, format!("byte {}", bytes.len()), format!("{} bytes: too short for a binary STL (84-byte header) and not an ascii STL (no \"solid\")", bytes.len())));
    };
    let needed = BINARY_HEADER_BYTES as u128 + BINARY_TRIANGLE_BYTES as u128 * declared as u128;
    if needed > bytes.len() as u128 {
        return Err(Error::parse(
            name,
            "byte 80 (triangle count)",
            format!("binary STL declares {declared} triangles, which need {needed} bytes, but the file has {} (truncated or lying header)", bytes.len()),
        ));
    }
    parse_binary(bytes, name, declared)
}

/// Gives each distinct position one index. `-0.0` and `0.0` are the same point.
struct VertexMerger {
    index_of: HashMap<[u32; 3], u32>,
    positions: Vec<Point>,
}

impl VertexMerger {
    fn with_capacity(capacity: usize) -> Self {
        VertexMerger { index_of: HashMap::with_capacity(capacity), positions: Vec::with_capacity(capacity) }
    }

    fn index(&mut self, corner: [f32; 3]) -> u32 {
        let key = corner.map(|c| if c == 0.0 { 0 } else { c.to_bits() });
        *self.index_of.entry(key).or_insert_with(|| {
            self.positions.push(Point::new(corner[0] as f64, corner[1] as f64, corner[2] as f64));
            (self.positions.len() - 1) as u32
        })
    }
}

fn parse_binary(bytes: &[u8], name: &str, count: usize) -> Result<(Mesh, ReadReport)> {
    let mut report = ReadReport::new("stl binary");
    let trailing = bytes.len() - BINARY_HEADER_BYTES - BINARY_TRIANGLE_BYTES * count;
    if trailing > 0 {
        report.warn(format!("{trailing} bytes after the {count} triangles ignored"));
    }
    // A closed triangle mesh has about half as many vertices as triangles.
    let mut merger = VertexMerger::with_capacity(count / 2 + 3);
    let mut triangles = Vec::with_capacity(count);
    for face in 0..count {
        let start = BINARY_HEADER_BYTES + BINARY_TRIANGLE_BYTES * face;
        let record = &bytes[start..start + BINARY_TRIANGLE_BYTES];
        let mut triangle = [0u32; 3];
        for (corner, index) in triangle.iter_mut().enumerate() {
            let at = 12 + 12 * corner;
            let value = |k: usize| f32::from_le_bytes(record[at + 4 * k..at + 4 * k + 4].try_into().expect("4 bytes"));
            let position = [value(0), value(1), value(2)];
            if let Some(k) = position.iter().position(|c| !c.is_finite()) {
                return Err(Error::parse(
                    name,
                    format!("byte {} (triangle {face} of {count}, corner {corner})", start + at + 4 * k),
                    format!("coordinate {} is {}", ["x", "y", "z"][k], position[k]),
                ));
            }
            *index = merger.index(position);
        }
        triangles.push(triangle);
    }
    Ok((Mesh::new(merger.positions, triangles), report))
}

fn parse_ascii(bytes: &[u8], name: &str) -> Result<(Mesh, ReadReport)> {
    let mut report = ReadReport::new("stl ascii");
    let mut merger = VertexMerger::with_capacity(1024);
    let mut triangles = Vec::new();
    let mut corners: Vec<u32> = Vec::new();
    let mut facet_start_line = 0;
    let mut facet_count = 0usize;
    let mut ended = false;
    for (number, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let line_number = number + 1;
        let at = || format!("line {line_number}");
        let mut words = raw.split(|b| b.is_ascii_whitespace()).filter(|w| !w.is_empty());
        let Some(keyword) = words.next() else { continue };
        match keyword {
            b"solid" | b"outer" | b"endsolid" => ended |= keyword == b"endsolid",
            b"facet" => {
                facet_start_line = line_number;
                corners.clear();
            }
            b"vertex" => {
                let mut position = [0f32; 3];
                for (k, coordinate) in position.iter_mut().enumerate() {
                    let word = words.next().ok_or_else(|| Error::parse(name, at(), format!("vertex has {k} coordinates, expected 3")))?;
                    let value = std::str::from_utf8(word).ok().and_then(|w| w.parse::<f32>().ok());
                    *coordinate = value.ok_or_else(|| Error::parse(name, at(), format!("coordinate {} is {}, not a number", ["x", "y", "z"][k], show_token(word))))?;
                    if !coordinate.is_finite() {
                        return Err(Error::parse(name, at(), format!("coordinate {} is {}", ["x", "y", "z"][k], coordinate)));
                    }
                }
                corners.push(merger.index(position));
            }
            b"endloop" => {}
            b"endfacet" => {
                facet_count += 1;
                match corners.len() {
                    0..=2 => {
                        return Err(Error::parse(name, format!("line {facet_start_line} (facet {})", facet_count - 1), format!("facet has {} vertices, expected 3", corners.len())));
                    }
                    3 => {}
                    _ => report.polygons_triangulated += 1,
                }
                triangles.extend(fan_triangles(corners.len()).map(|t| t.map(|c| corners[c])));
                corners.clear();
            }
            other => {
                return Err(Error::parse(name, at(), format!("unexpected {} in an ascii STL (expected facet, vertex, endloop, endfacet...)", show_token(other))));
            }
        }
    }
    if !corners.is_empty() {
        return Err(Error::parse(name, format!("line {facet_start_line} (facet {facet_count})"), "the file ends inside this facet (truncated)"));
    }
    if triangles.is_empty() {
        return Err(Error::parse(name, "line 1", "the ascii STL contains no facets"));
    }
    if !ended {
        report.warn("no endsolid line: the file may be truncated after the last complete facet");
    }
    Ok((Mesh::new(merger.positions, triangles), report))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn binary_starting_with_solid_is_read_as_binary_and_corners_are_merged() {
        let mut bytes = b"solid but binary".to_vec();
        bytes.resize(80, b' ');
        bytes.extend(2u32.to_le_bytes());
        for triangle in [[[0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [[1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, -0.0]]] {
            bytes.extend([0u8; 12]);
            for corner in triangle {
                for c in corner {
                    bytes.extend(c.to_le_bytes());
                }
            }
            bytes.extend([0u8; 2]);
        }
        let (mesh, report) = parse_stl(&bytes, "t.stl").unwrap();
        assert_eq!(report.format, "stl binary");
        assert_eq!(mesh.vertex_count(), 4);
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [1, 3, 2]]);
    }

    #[test]
    fn ascii_error_names_the_line() {
        let text = b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 zero\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
        let message = parse_stl(text, "t.stl").unwrap_err().to_string();
        assert!(message.contains("line 5") && message.contains("\"zero\""), "{message}");
    }
}
