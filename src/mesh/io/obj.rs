//! Wavefront OBJ as scanners and photogrammetry export it: `v` (optionally with an RGB
//! colour), `vt`, `vn`, `f` polygons in the `v`, `v/vt`, `v//vn` and `v/vt/vn` forms with
//! positive or negative (relative) indices, and `mtllib` + `usemtl` + `map_Kd` for the
//! texture (PNG or JPEG). Texture coordinates are kept per triangle corner, so seams cost
//! no duplicated vertices; OBJ's per-corner normals are averaged per vertex.

use std::path::Path;

use super::{ReadReport, fan_triangles, show_token, texture};
use crate::mesh::{Mesh, Point, Vector};
use crate::{Error, Result};

/// The corner of a face: vertex, optional texture coordinate and normal indices (0-based).
#[derive(Clone, Copy)]
struct Corner {
    vertex: u32,
    uv: Option<u32>,
    normal: Option<u32>,
}

struct Parser<'a> {
    name: &'a str,
    line_number: usize,
    report: ReadReport,
    positions: Vec<Point>,
    vertex_colours: Vec<[u8; 4]>,
    uvs: Vec<[f32; 2]>,
    normals: Vec<Vector>,
    triangles: Vec<[u32; 3]>,
    corner_uvs: Vec<[f32; 2]>,
    corners_without_uv: usize,
    normal_sums: Vec<Vector>,
    vertices_with_normals: usize,
    /// Each `mtllib` name with its line number.
    material_libraries: Vec<(String, usize)>,
    used_materials: Vec<String>,
}

impl Parser<'_> {
    fn error(&self, message: String) -> Error {
        Error::parse(self.name, format!("line {}", self.line_number), message)
    }

    fn numbers(&self, words: &[&[u8]], keyword: &str) -> Result<Vec<f64>> {
        words
            .iter()
            .map(|w| {
                let value = std::str::from_utf8(w).ok().and_then(|w| w.parse::<f64>().ok());
                value.ok_or_else(|| self.error(format!("{keyword} value {} is not a number", show_token(w))))
            })
            .collect()
    }

    /// Resolves an OBJ index (1-based, or negative from the end of what is defined so far).
    fn resolve(&self, word: &[u8], defined: usize, what: &str, plural: &str) -> Result<u32> {
        let value = std::str::from_utf8(word).ok().and_then(|w| w.parse::<i64>().ok());
        let value = value.ok_or_else(|| self.error(format!("{what} index {} is not an integer", show_token(word))))?;
        let index = if value > 0 { value - 1 } else { defined as i64 + value };
        if value == 0 || index < 0 || index >= defined as i64 {
            return Err(self.error(format!("{what} index {value} is out of range: {defined} {plural} defined before this line")));
        }
        Ok(index as u32)
    }

    fn face(&mut self, words: &[&[u8]]) -> Result<()> {
        let mut corners = Vec::with_capacity(words.len());
        for word in words {
            let mut parts = word.split(|&b| b == b'/');
            let vertex = self.resolve(parts.next().unwrap_or_default(), self.positions.len(), "vertex", "vertices")?;
            let uv = match parts.next() {
                Some(part) if !part.is_empty() => Some(self.resolve(part, self.uvs.len(), "texture coordinate", "texture coordinates")?),
                _ => None,
            };
            let normal = match parts.next() {
                Some(part) if !part.is_empty() => Some(self.resolve(part, self.normals.len(), "normal", "normals")?),
                _ => None,
            };
            corners.push(Corner { vertex, uv, normal });
        }
        match corners.len() {
            0..=2 => self.report.degenerate_faces_dropped += 1,
            3 => {}
            _ => self.report.polygons_triangulated += 1,
        }
        for corner in &corners {
            if let Some(normal) = corner.normal {
                if self.normal_sums.len() < self.positions.len() {
                    self.normal_sums.resize(self.positions.len(), Vector::zeros());
                }
                let sum = &mut self.normal_sums[corner.vertex as usize];
                if *sum == Vector::zeros() {
                    self.vertices_with_normals += 1;
                }
                *sum += self.normals[normal as usize];
            }
        }
        for triangle in fan_triangles(corners.len()) {
            self.triangles.push(triangle.map(|c| corners[c].vertex));
            for c in triangle {
                match corners[c].uv {
                    Some(uv) => self.corner_uvs.push(self.uvs[uv as usize]),
                    None => {
                        self.corners_without_uv += 1;
                        self.corner_uvs.push([0.0, 0.0]);
                    }
                }
            }
        }
        Ok(())
    }

    fn line(&mut self, raw: &[u8]) -> Result<()> {
        let mut parts = raw.splitn(2, |&b| b == b'#');
        let raw = parts.next().unwrap_or_default();
        if let Some(comment) = parts.next()
            && self.report.declared_unit.is_none()
        {
            self.report.declared_unit = super::unit_declared_in(&String::from_utf8_lossy(comment));
        }
        let words: Vec<&[u8]> = raw.split(|b| b.is_ascii_whitespace()).filter(|w| !w.is_empty()).collect();
        let Some((&keyword, arguments)) = words.split_first() else { return Ok(()) };
        match keyword {
            b"v" => {
                let values = self.numbers(arguments, "v")?;
                if values.len() < 3 {
                    return Err(self.error(format!("v has {} coordinates, expected 3", values.len())));
                }
                let position = Point::new(values[0], values[1], values[2]);
                if let Some(k) = (0..3).find(|&k| !position[k].is_finite()) {
                    return Err(self.error(format!("vertex {}: coordinate {} is {}", self.positions.len(), ["x", "y", "z"][k], position[k])));
                }
                if values.len() == 6 || values.len() == 7 {
                    // "v x y z r g b": the colour extension MeshLab and photogrammetry tools write, 0-1.
                    let channel = |k: usize| (values[k] * 255.0).round().clamp(0.0, 255.0) as u8;
                    self.vertex_colours.push([channel(3), channel(4), channel(5), 255]);
                }
                self.positions.push(position);
            }
            b"vt" => {
                let values = self.numbers(arguments, "vt")?;
                let Some(&u) = values.first() else { return Err(self.error("vt without coordinates".into())) };
                self.uvs.push([u as f32, values.get(1).copied().unwrap_or(0.0) as f32]);
            }
            b"vn" => {
                let values = self.numbers(arguments, "vn")?;
                if values.len() != 3 {
                    return Err(self.error(format!("vn has {} values, expected 3", values.len())));
                }
                self.normals.push(Vector::new(values[0], values[1], values[2]));
            }
            b"f" | b"fo" => self.face(arguments)?,
            b"mtllib" => self.material_libraries.push((String::from_utf8_lossy(raw.trim_ascii()[6..].trim_ascii()).into_owned(), self.line_number)),
            b"usemtl" => {
                let material = String::from_utf8_lossy(raw.trim_ascii()[6..].trim_ascii()).into_owned();
                if !self.used_materials.contains(&material) {
                    self.used_materials.push(material);
                }
            }
            b"o" | b"g" | b"s" | b"vp" => {}
            b"l" | b"p" => {
                let what = if keyword == b"l" { "line" } else { "point" };
                let message = format!("{what} elements (\"{}\") skipped", String::from_utf8_lossy(keyword));
                if !self.report.warnings.contains(&message) {
                    self.report.warn(message);
                }
            }
            other => {
                let message = format!("unknown OBJ keyword {} skipped", show_token(other));
                if !self.report.warnings.contains(&message) {
                    self.report.warn(message);
                }
            }
        }
        Ok(())
    }
}

/// The `map_Kd` file of each material of a MTL file, in order, with its line number.
fn parse_material_library(text: &str) -> Vec<(String, Option<(String, usize)>)> {
    let mut materials: Vec<(String, Option<(String, usize)>)> = Vec::new();
    for (index, line) in text.lines().enumerate() {
        let line = line.trim();
        if let Some(name) = line.strip_prefix("newmtl") {
            materials.push((name.trim().to_string(), None));
        } else if let Some(arguments) = line.strip_prefix("map_Kd") {
            if let Some((_, map)) = materials.last_mut() {
                *map = Some((texture_file_of(arguments.trim()), index + 1));
            }
        }
    }
    materials
}

/// The file name of a `map_Kd` statement, after its options (`-s 1 1 1`, `-bm 0.5`...).
/// Options take a fixed number of values; what follows them is the file name, which may
/// contain spaces.
fn texture_file_of(arguments: &str) -> String {
    // Each word with its byte offset, so that the name is cut where its first word starts
    // (searching the text for that word would find an earlier copy of it, an option
    // repeated, and never move on).
    let mut words = Vec::new();
    let mut start = None;
    for (at, c) in arguments.char_indices().chain([(arguments.len(), ' ')]) {
        match (c.is_whitespace(), start) {
            (false, None) => start = Some(at),
            (true, Some(from)) => {
                words.push((from, &arguments[from..at]));
                start = None;
            }
            _ => {}
        }
    }
    let mut first = 0;
    while let Some((_, option)) = words.get(first).filter(|(_, w)| w.starts_with('-')) {
        let values = match *option {
            "-o" | "-s" | "-t" => 3,
            "-mm" => 2,
            _ => 1,
        };
        // Skip the option and its values, but never all remaining words.
        if first + 1 + values >= words.len() {
            break;
        }
        first += 1 + values;
    }
    let name = words.get(first).map_or("", |&(at, _)| &arguments[at..]);
    name.trim().replace('\\', "/")
}

pub(super) fn parse_obj(bytes: &[u8], name: &str, folder: Option<&Path>) -> Result<(Mesh, ReadReport)> {
    let mut parser = Parser {
        name,
        line_number: 0,
        report: ReadReport::new("obj"),
        positions: Vec::new(),
        vertex_colours: Vec::new(),
        uvs: Vec::new(),
        normals: Vec::new(),
        triangles: Vec::new(),
        corner_uvs: Vec::new(),
        corners_without_uv: 0,
        normal_sums: Vec::new(),
        vertices_with_normals: 0,
        material_libraries: Vec::new(),
        used_materials: Vec::new(),
    };
    for raw in bytes.split(|&b| b == b'\n') {
        parser.line_number += 1;
        parser.line(raw)?;
    }
    if parser.positions.is_empty() {
        return Err(Error::parse(name, format!("line {}", parser.line_number), "the OBJ file defines no vertex (\"v\" line)"));
    }
    let Parser { mut report, positions, vertex_colours, normals, triangles, corner_uvs, corners_without_uv, mut normal_sums, vertices_with_normals, material_libraries, used_materials, uvs, .. } = parser;
    let vertex_count = positions.len();
    let mut mesh = Mesh::new(positions, triangles);
    if vertex_colours.len() == vertex_count {
        mesh.colors = Some(vertex_colours);
    } else if !vertex_colours.is_empty() {
        report.warn(format!("only {} of {vertex_count} vertices have a colour: colours dropped", vertex_colours.len()));
    }
    if mesh.triangles.is_empty() && normals.len() == vertex_count {
        // A point cloud writes one vn per v, in the same order.
        mesh.normals = Some(normals.iter().map(|n| n.try_normalize(0.0).unwrap_or_else(Vector::zeros)).collect());
    } else if vertices_with_normals > 0 {
        normal_sums.resize(vertex_count, Vector::zeros());
        if vertices_with_normals < vertex_count {
            report.warn(format!("only {vertices_with_normals} of {vertex_count} vertices have a normal: the others are zero"));
        }
        mesh.normals = Some(normal_sums.iter().map(|n| n.try_normalize(0.0).unwrap_or_else(Vector::zeros)).collect());
    }
    let has_uvs = !uvs.is_empty() && corner_uvs.len() > corners_without_uv;
    if has_uvs {
        if corners_without_uv > 0 {
            report.warn(format!("{corners_without_uv} face corners have no texture coordinate: set to (0, 0)"));
        }
        mesh.corner_uvs = Some(corner_uvs);
    }
    load_material_texture(&mut mesh, &mut report, name, folder, &material_libraries, &used_materials, has_uvs);
    Ok((mesh, report))
}

/// Loads the texture of the first used material that has a `map_Kd`; anything missing on
/// the way (MTL file, image) or outside the scan's folder is a warning, not an error: the
/// geometry is still usable.
fn load_material_texture(mesh: &mut Mesh, report: &mut ReadReport, name: &str, folder: Option<&Path>, libraries: &[(String, usize)], used: &[String], has_uvs: bool) {
    let Some(folder) = folder else {
        if !libraries.is_empty() {
            report.warn("material library not loaded: reading from a stream, its folder is unknown");
        }
        return;
    };
    // Each material with its texture file and where that file is named ("x.mtl line 4").
    let mut materials: Vec<(String, Option<(String, String)>)> = Vec::new();
    for (library, line) in libraries {
        let path = match super::file_in_scan_folder(folder, library, "material library", &format!("{name} line {line}")) {
            Ok(path) => path,
            Err(refusal) => {
                report.warn(refusal);
                continue;
            }
        };
        match super::read_regular_file(&path, super::MAX_MATERIAL_LIBRARY_BYTES) {
            Ok(bytes) => materials.extend(
                parse_material_library(&String::from_utf8_lossy(&bytes))
                    .into_iter()
                    .map(|(material, map)| (material, map.map(|(file, line)| (file, format!("{} line {line}", path.display()))))),
            ),
            Err(error) => report.warn(format!("material library not loaded: {error}")),
        }
    }
    let mut textures: Vec<&(String, String)> = Vec::new();
    for (material, map) in &materials {
        if let Some(map) = map {
            if (used.is_empty() || used.contains(material)) && !textures.iter().any(|(file, _)| *file == map.0) {
                textures.push(map);
            }
        }
    }
    let Some((first, named_at)) = textures.first() else { return };
    if textures.len() > 1 {
        report.warn(format!("{} textures are used; only the first ({first}) is kept", textures.len()));
    }
    if !has_uvs {
        report.warn(format!("texture {first} not loaded: the faces have no texture coordinates"));
        return;
    }
    let path = match super::file_in_scan_folder(folder, first, "texture", named_at) {
        Ok(path) => path,
        Err(refusal) => return report.warn(refusal),
    };
    match texture::load_texture(&path) {
        Ok(image) => mesh.texture = Some(image),
        Err(error) => report.warn(format!("texture missing or unreadable, not loaded: {error}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polygon_with_negative_indices_and_mixed_forms() {
        let text = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nf -4/1/1 -3/2/1 -2/3/1 -1/4/1\n";
        let (mesh, report) = parse_obj(text, "t.obj", None).unwrap();
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(mesh.corner_uvs.as_ref().unwrap()[5], [0.0, 1.0]);
        assert_eq!(mesh.normals.as_ref().unwrap()[3], Vector::new(0.0, 0.0, 1.0));
        assert_eq!(report.polygons_triangulated, 1);
    }

    #[test]
    fn out_of_range_index_names_the_line() {
        let message = parse_obj(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "t.obj", None).unwrap_err().to_string();
        assert!(message.contains("line 4") && message.contains("vertex index 4"), "{message}");
    }

    #[test]
    fn map_kd_options_are_skipped() {
        assert_eq!(texture_file_of("-s 1 1 1 -bm 0.5 my texture.jpg"), "my texture.jpg");
        assert_eq!(texture_file_of("tex.png"), "tex.png");
    }

    /// Found by the obj_mtl fuzz target (fuzz/regressions/obj_mtl/): an option repeated
    /// after its value made the old text search find the first copy again, for ever.
    #[test]
    fn repeated_map_kd_options_end() {
        assert_eq!(texture_file_of("-x 1 -x -x foo"), "foo");
        assert_eq!(texture_file_of("-s 1 1 1 -s"), "-s");
        assert_eq!(texture_file_of("-bm 1 -bm 1 t\\x.png"), "t/x.png");
    }
}
