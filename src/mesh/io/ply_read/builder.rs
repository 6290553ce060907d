//! Decodes the body's records into the mesh: vertex properties into their slots, faces
//! into fan triangles, and any other element skipped with a warning, so that a file
//! carrying more than sherd keeps is still read.

use super::body::{Body, decode_scalar};
use super::header::{Element, Header, Property, PropertyType, ScalarType};
use crate::mesh::io::{ReadReport, fan_triangles};
use crate::mesh::{Mesh, Point, Vector};
use crate::{Error, Result};

/// Where a vertex property goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum VertexSlot {
    X,
    Y,
    Z,
    NormalX,
    NormalY,
    NormalZ,
    Red,
    Green,
    Blue,
    Alpha,
    Quality,
    U,
    V,
    Skip,
}

impl VertexSlot {
    fn for_name(name: &str) -> Self {
        match name {
            "x" => VertexSlot::X,
            "y" => VertexSlot::Y,
            "z" => VertexSlot::Z,
            "nx" => VertexSlot::NormalX,
            "ny" => VertexSlot::NormalY,
            "nz" => VertexSlot::NormalZ,
            "red" | "diffuse_red" | "r" => VertexSlot::Red,
            "green" | "diffuse_green" | "g" => VertexSlot::Green,
            "blue" | "diffuse_blue" | "b" => VertexSlot::Blue,
            "alpha" | "diffuse_alpha" | "a" => VertexSlot::Alpha,
            "quality" | "scalar_quality" => VertexSlot::Quality,
            "s" | "u" | "texture_u" | "texture_s" => VertexSlot::U,
            "t" | "v" | "texture_v" | "texture_t" => VertexSlot::V,
            _ => VertexSlot::Skip,
        }
    }
}

const SLOT_COUNT: usize = VertexSlot::Skip as usize;

/// Converts a colour channel to 0-255: floats are 0-1, integers are scaled from their range.
#[inline]
fn colour_channel(value: f64, kind: ScalarType) -> u8 {
    if kind == ScalarType::U8 {
        // Exact already (a uchar read as f64); `as` saturates what an ascii file overstates.
        return value as u8;
    }
    (value * 255.0 / kind.max_value()).round().clamp(0.0, 255.0) as u8
}

/// Builds the error for a fault while reading `property` of element `index` of `element`.
fn body_error(name: &str, location: String, element: &Element, index: u64, property: &Property, message: String) -> Error {
    Error::parse(
        name,
        format!("{location} ({} {index} of {}, property {})", element.name, element.count, property.name),
        message,
    )
}

/// The mesh under construction and what is known of the file.
pub(super) struct Builder<'a> {
    pub(super) name: &'a str,
    pub(super) mesh: Mesh,
    pub(super) report: ReadReport,
    /// The vertex count the header declares, known before any face is read.
    pub(super) declared_vertex_count: u64,
    pub(super) vertex_uvs: Option<Vec<[f32; 2]>>,
}

impl Builder<'_> {
    fn read_vertices<B: Body>(&mut self, body: &mut B, element: &Element) -> Result<()> {
        let slots: Vec<VertexSlot> = element.properties.iter().map(|p| VertexSlot::for_name(&p.name)).collect();
        let has = |slot: VertexSlot| slots.contains(&slot);
        for required in [VertexSlot::X, VertexSlot::Y, VertexSlot::Z] {
            if !has(required) {
                return Err(Error::parse(self.name, format!("header line {}", element.line), format!("the vertex element has no {:?} property", required).to_lowercase()));
            }
        }
        let keep_normals = has(VertexSlot::NormalX) && has(VertexSlot::NormalY) && has(VertexSlot::NormalZ);
        let keep_colours = has(VertexSlot::Red) && has(VertexSlot::Green) && has(VertexSlot::Blue);
        let keep_quality = has(VertexSlot::Quality);
        let keep_uvs = has(VertexSlot::U) && has(VertexSlot::V);
        for (property, slot) in element.properties.iter().zip(&slots) {
            let unused = match slot {
                VertexSlot::Skip => true,
                VertexSlot::NormalX | VertexSlot::NormalY | VertexSlot::NormalZ => !keep_normals,
                VertexSlot::Red | VertexSlot::Green | VertexSlot::Blue | VertexSlot::Alpha => !keep_colours,
                VertexSlot::U | VertexSlot::V => !keep_uvs,
                _ => false,
            };
            if unused || matches!(property.kind, PropertyType::List { .. }) {
                self.report.warn(format!("vertex property {} skipped", property.name));
            }
        }
        let count = element.count as usize;
        let mut positions = Vec::with_capacity(count);
        let mut normals = keep_normals.then(|| Vec::with_capacity(count));
        let mut colours = keep_colours.then(|| Vec::with_capacity(count));
        let mut quality = keep_quality.then(|| Vec::with_capacity(count));
        let mut uvs = keep_uvs.then(|| Vec::with_capacity(count));
        let mut colour_types = [ScalarType::U8; 4];
        for (property, slot) in element.properties.iter().zip(&slots) {
            if let (PropertyType::Scalar(kind), VertexSlot::Red | VertexSlot::Green | VertexSlot::Blue | VertexSlot::Alpha) = (property.kind, slot) {
                colour_types[*slot as usize - VertexSlot::Red as usize] = kind;
            }
        }
        // Records without lists have one size: binary ones are decoded from one slice, with
        // one bounds check per vertex instead of one per value.
        let fixed_record_size: Option<usize> = element
            .properties
            .iter()
            .map(|p| match p.kind {
                PropertyType::Scalar(kind) => Some(kind.size()),
                PropertyType::List { .. } => None,
            })
            .sum();
        let mut fixed_layout = Vec::new();
        let mut offset = 0;
        for (property, &slot) in element.properties.iter().zip(&slots) {
            if let PropertyType::Scalar(kind) = property.kind {
                if slot != VertexSlot::Skip {
                    fixed_layout.push((offset, kind, slot));
                }
                offset += kind.size();
            }
        }
        let mut non_unit_normals = 0usize;
        for index in 0..element.count {
            body.begin_record();
            let mut values = [f64::NAN; SLOT_COUNT];
            values[VertexSlot::Alpha as usize] = colour_types[3].max_value();
            let big_endian = body.big_endian();
            if let Some(record) = fixed_record_size.and_then(|size| body.take(size)) {
                for &(offset, kind, slot) in &fixed_layout {
                    values[slot as usize] = decode_scalar(&record[offset..], kind, big_endian);
                }
            } else {
                for (property, &slot) in element.properties.iter().zip(&slots) {
                    match property.kind {
                        PropertyType::Scalar(kind) => {
                            let value = body.float(kind).map_err(|f| body_error(self.name, body.location(), element, index, property, f.message(kind)))?;
                            if slot != VertexSlot::Skip {
                                values[slot as usize] = value;
                            }
                        }
                        PropertyType::List { count, item } => skip_list(body, count, item).map_err(|(at, message)| body_error(self.name, at, element, index, property, message))?,
                    }
                }
            }
            body.end_record().map_err(|f| body_error(self.name, body.location(), element, index, element.properties.last().expect("a vertex has properties"), f.message(ScalarType::F32)))?;
            let position = Point::new(values[0], values[1], values[2]);
            if let Some(axis) = (0..3).find(|&axis| !position[axis].is_finite()) {
                return Err(Error::parse(
                    self.name,
                    format!("{} ({} {index} of {})", body.record_location(), element.name, element.count),
                    format!("coordinate {} is {} (vertex at ({}, {}, {}))", ["x", "y", "z"][axis], position[axis], position.x, position.y, position.z),
                ));
            }
            positions.push(position);
            if let Some(normals) = &mut normals {
                let normal = Vector::new(values[3], values[4], values[5]);
                let length = normal.norm();
                if length.is_finite() && length > 0.0 {
                    if (length - 1.0).abs() > 1e-3 {
                        non_unit_normals += 1;
                    }
                    normals.push(normal / length);
                } else {
                    non_unit_normals += 1;
                    normals.push(Vector::zeros());
                }
            }
            if let Some(colours) = &mut colours {
                let channel = |k: usize| colour_channel(values[VertexSlot::Red as usize + k], colour_types[k]);
                colours.push([channel(0), channel(1), channel(2), channel(3)]);
            }
            if let Some(quality) = &mut quality {
                quality.push(values[VertexSlot::Quality as usize] as f32);
            }
            if let Some(uvs) = &mut uvs {
                uvs.push([values[VertexSlot::U as usize] as f32, values[VertexSlot::V as usize] as f32]);
            }
        }
        if non_unit_normals > 0 {
            self.report.warn(format!("{non_unit_normals} vertex normals were not of unit length (normalised; zero or non-finite ones set to zero)"));
        }
        self.mesh.positions = positions;
        self.mesh.normals = normals;
        self.mesh.colors = colours;
        self.mesh.quality = quality;
        self.vertex_uvs = uvs;
        Ok(())
    }

    fn read_faces<B: Body>(&mut self, body: &mut B, element: &Element) -> Result<()> {
        if element.count == 0 {
            // Point cloud writers (PCL) declare "element face 0" without properties.
            return Ok(());
        }
        let indices_at = element.properties.iter().position(|p| p.name == "vertex_indices" || p.name == "vertex_index");
        let Some(indices_at) = indices_at else {
            return Err(Error::parse(self.name, format!("header line {}", element.line), "the face element has no vertex_indices list"));
        };
        let (index_count_type, index_type) = match element.properties[indices_at].kind {
            PropertyType::List { count, item } if item.is_integer() => (count, item),
            kind => {
                return Err(Error::parse(self.name, format!("header line {}", element.line), format!("face property {} must be a list of integers, not {kind:?}", element.properties[indices_at].name)));
            }
        };
        let texcoords_at = element.properties.iter().position(|p| p.name == "texcoord" && matches!(p.kind, PropertyType::List { .. }));
        for (at, property) in element.properties.iter().enumerate() {
            if at != indices_at && Some(at) != texcoords_at {
                self.report.warn(format!("face property {} skipped", property.name));
            }
        }
        // A triangle takes at least the count and three indices; capacity beyond what the
        // file can hold would only be an allocation a lying header asked for.
        let smallest_triangle = if body.is_text() { 8 } else { index_count_type.size() + 3 * index_type.size() };
        let mut triangles = Vec::with_capacity((element.count as usize).min(body.remaining() / smallest_triangle));
        let mut corner_uvs: Option<Vec<[f32; 2]>> = texcoords_at.map(|_| Vec::with_capacity(triangles.capacity() * 3));
        let mut corners: Vec<u32> = Vec::new();
        let mut face_uvs: Vec<f32> = Vec::new();
        let vertex_count = self.declared_vertex_count;
        for index in 0..element.count {
            body.begin_record();
            corners.clear();
            face_uvs.clear();
            for (at, property) in element.properties.iter().enumerate() {
                let fail = |location: String, message: String| body_error(self.name, location, element, index, property, message);
                if at == indices_at {
                    let mark = body.mark();
                    let n = body.integer(index_count_type).map_err(|f| fail(body.location_at(mark), f.message(index_count_type)))?;
                    if n < 0 || !body.can_hold(n as u64, index_type) {
                        return Err(fail(body.location_at(mark), format!("list length {n} is impossible here (negative, or more than the rest of the file can hold)")));
                    }
                    let out_of_range = |vertex: i64| format!("vertex index {vertex} is out of range: the file has {vertex_count} vertices");
                    let start = body.mark();
                    let size = index_type.size();
                    let big_endian = body.big_endian();
                    if let Some(bytes) = body.take(n as usize * size) {
                        for (k, value) in bytes.chunks_exact(size).enumerate() {
                            let vertex = decode_scalar(value, index_type, big_endian) as i64;
                            if vertex < 0 || vertex as u64 >= vertex_count {
                                return Err(fail(body.location_at(start + k * size), out_of_range(vertex)));
                            }
                            corners.push(vertex as u32);
                        }
                    } else {
                        for _ in 0..n {
                            let mark = body.mark();
                            let vertex = body.integer(index_type).map_err(|f| fail(body.location_at(mark), f.message(index_type)))?;
                            if vertex < 0 || vertex as u64 >= vertex_count {
                                return Err(fail(body.location_at(mark), out_of_range(vertex)));
                            }
                            corners.push(vertex as u32);
                        }
                    }
                } else if Some(at) == texcoords_at {
                    let PropertyType::List { count, item } = property.kind else { unreachable!("texcoord is a list") };
                    let mark = body.mark();
                    let n = body.integer(count).map_err(|f| fail(body.location_at(mark), f.message(count)))?;
                    if n < 0 || !body.can_hold(n as u64, item) {
                        return Err(fail(body.location_at(mark), format!("list length {n} is impossible here (negative, or more than the rest of the file can hold)")));
                    }
                    for _ in 0..n {
                        let mark = body.mark();
                        face_uvs.push(body.float(item).map_err(|f| fail(body.location_at(mark), f.message(item)))? as f32);
                    }
                } else {
                    match property.kind {
                        PropertyType::Scalar(kind) => {
                            let mark = body.mark();
                            body.skip(kind).map_err(|f| fail(body.location_at(mark), f.message(kind)))?;
                        }
                        PropertyType::List { count, item } => skip_list(body, count, item).map_err(|(location, message)| fail(location, message))?,
                    }
                }
            }
            body.end_record().map_err(|f| body_error(self.name, body.location(), element, index, element.properties.last().expect("a face has properties"), f.message(index_type)))?;
            if let Some(corner_uvs) = &mut corner_uvs {
                if face_uvs.len() != 2 * corners.len() {
                    return Err(Error::parse(
                        self.name,
                        format!("{} ({} {index} of {})", body.record_location(), element.name, element.count),
                        format!("texcoord has {} values for a face of {} corners (expected {})", face_uvs.len(), corners.len(), 2 * corners.len()),
                    ));
                }
                for triangle in fan_triangles(corners.len()) {
                    corner_uvs.extend(triangle.map(|c| [face_uvs[2 * c], face_uvs[2 * c + 1]]));
                }
            }
            match corners.len() {
                0..=2 => self.report.degenerate_faces_dropped += 1,
                3 => {}
                _ => self.report.polygons_triangulated += 1,
            }
            triangles.extend(fan_triangles(corners.len()).map(|t| t.map(|c| corners[c])));
        }
        self.mesh.triangles = triangles;
        self.mesh.corner_uvs = corner_uvs;
        Ok(())
    }
}

/// Skips one list value; returns where and why it failed.
fn skip_list<B: Body>(body: &mut B, count: ScalarType, item: ScalarType) -> std::result::Result<(), (String, String)> {
    let mark = body.mark();
    let n = body.integer(count).map_err(|f| (body.location_at(mark), f.message(count)))?;
    if n < 0 || !body.can_hold(n as u64, item) {
        return Err((body.location_at(mark), format!("list length {n} is impossible here (negative, or more than the rest of the file can hold)")));
    }
    for _ in 0..n {
        let mark = body.mark();
        body.skip(item).map_err(|f| (body.location_at(mark), f.message(item)))?;
    }
    Ok(())
}

fn skip_element<B: Body>(name: &str, body: &mut B, element: &Element) -> Result<()> {
    if element.properties.is_empty() {
        // Nothing to read, however large the count: never loop over a lying count.
        return Ok(());
    }
    for index in 0..element.count {
        body.begin_record();
        for property in &element.properties {
            match property.kind {
                PropertyType::Scalar(kind) => {
                    let mark = body.mark();
                    body.skip(kind).map_err(|f| body_error(name, body.location_at(mark), element, index, property, f.message(kind)))?;
                }
                PropertyType::List { count, item } => {
                    skip_list(body, count, item).map_err(|(location, message)| body_error(name, location, element, index, property, message))?
                }
            }
        }
        if let Some(last) = element.properties.last() {
            body.end_record().map_err(|f| body_error(name, body.location(), element, index, last, f.message(ScalarType::F32)))?;
        }
    }
    Ok(())
}

pub(super) fn read_body<B: Body>(builder: &mut Builder, body: &mut B, header: &Header) -> Result<()> {
    let mut seen_vertices = false;
    let mut seen_faces = false;
    for element in &header.elements {
        match element.name.as_str() {
            "vertex" if !seen_vertices => {
                seen_vertices = true;
                builder.read_vertices(body, element)?;
            }
            "face" if !seen_faces => {
                seen_faces = true;
                builder.read_faces(body, element)?;
            }
            _ => {
                if element.count > 0 {
                    builder.report.warn(format!("element {} ({} entries) skipped", element.name, element.count));
                }
                skip_element(builder.name, body, element)?;
            }
        }
    }
    Ok(())
}
