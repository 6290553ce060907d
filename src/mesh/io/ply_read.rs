//! The PLY reader (ascii, binary little and big endian), hand-written rather than built
//! on ply-rs-bw because it is measurably faster on a 500k-face scan (`benches/ply.rs`;
//! BENCHMARKS.md, "PLY reading", has the figures): ply-rs-bw hands every value
//! to a callback by property name (or builds a hash map of them per element), this reader
//! decodes fixed-size records from one slice straight into the mesh's arrays. It also
//! gives what ply-rs-bw does not: a size check of the header's counts before allocating,
//! and errors naming the byte or line, the element index and the value.
//!
//! It checks, before allocating, that the file can hold what the header declares, and
//! names in every error the file, the header line or body line (ascii) or byte offset
//! (binary), the element and its index, and the value.

use std::io::Read;
use std::path::Path;

use super::{ReadReport, fan_triangles, show_token, texture};
use crate::mesh::{Mesh, Point, Vector};
use crate::{Error, Result};

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

/// The scalar types of the PLY format, under both their old and their sized names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum ScalarType {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl ScalarType {
    fn parse(name: &str) -> Option<Self> {
        Some(match name {
            "char" | "int8" => ScalarType::I8,
            "uchar" | "uint8" => ScalarType::U8,
            "short" | "int16" => ScalarType::I16,
            "ushort" | "uint16" => ScalarType::U16,
            "int" | "int32" => ScalarType::I32,
            "uint" | "uint32" => ScalarType::U32,
            "float" | "float32" => ScalarType::F32,
            "double" | "float64" => ScalarType::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            ScalarType::I8 | ScalarType::U8 => 1,
            ScalarType::I16 | ScalarType::U16 => 2,
            ScalarType::I32 | ScalarType::U32 | ScalarType::F32 => 4,
            ScalarType::F64 => 8,
        }
    }

    fn is_integer(self) -> bool {
        !matches!(self, ScalarType::F32 | ScalarType::F64)
    }

    /// The largest value of an integer type, used to scale integer colours to 0-255.
    fn max_value(self) -> f64 {
        match self {
            ScalarType::I8 => i8::MAX as f64,
            ScalarType::U8 => u8::MAX as f64,
            ScalarType::I16 => i16::MAX as f64,
            ScalarType::U16 => u16::MAX as f64,
            ScalarType::I32 => i32::MAX as f64,
            ScalarType::U32 => u32::MAX as f64,
            ScalarType::F32 | ScalarType::F64 => 1.0,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum PropertyType {
    Scalar(ScalarType),
    List { count: ScalarType, item: ScalarType },
}

#[derive(Clone, Debug)]
struct Property {
    name: String,
    kind: PropertyType,
}

#[derive(Clone, Debug)]
struct Element {
    name: String,
    count: u64,
    properties: Vec<Property>,
    /// 1-based header line of the `element` declaration, for messages.
    line: usize,
}

impl Element {
    /// The fewest bytes one instance can take in the body: what the file must hold at
    /// least, checked before allocating anything.
    fn minimum_bytes(&self, encoding: Encoding) -> u64 {
        self.properties
            .iter()
            .map(|p| match (encoding, p.kind) {
                // A value is at least one character and one separator.
                (Encoding::Ascii, _) => 2,
                (_, PropertyType::Scalar(t)) => t.size() as u64,
                (_, PropertyType::List { count, .. }) => count.size() as u64,
            })
            .sum()
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Encoding {
    Ascii,
    BinaryLittleEndian,
    BinaryBigEndian,
}

struct Header {
    encoding: Encoding,
    elements: Vec<Element>,
    /// Each `comment TextureFile` name with its header line.
    texture_files: Vec<(String, usize)>,
    /// The unit the first comment naming one declares.
    declared_unit: Option<super::LengthUnit>,
    /// Byte offset of the body.
    body_start: usize,
    /// Number of header lines, so that ascii body lines are numbered as in an editor.
    line_count: usize,
}

fn parse_header(bytes: &[u8], name: &str) -> Result<Header> {
    let header_error = |line: usize, message: String| Error::parse(name, format!("header line {line}"), message);
    let mut position = 0;
    let mut line_number = 0;
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    let mut texture_files = Vec::new();
    let mut declared_unit = None;
    loop {
        line_number += 1;
        let Some(length) = bytes[position..].iter().position(|&b| b == b'\n') else {
            if line_number == 1 {
                return Err(Error::parse(name, "byte 0", format!("not a PLY file: it starts with {}", show_token(&bytes[..bytes.len().min(16)]))));
            }
            return Err(header_error(line_number, "the header has no end_header line (file truncated, or not a PLY file)".into()));
        };
        let raw = &bytes[position..position + length];
        position += length + 1;
        let raw = raw.strip_suffix(b"\r").unwrap_or(raw);
        let Ok(line) = std::str::from_utf8(raw) else {
            if line_number == 1 {
                return Err(Error::parse(name, "byte 0", format!("not a PLY file: it starts with {}", show_token(&raw[..raw.len().min(16)]))));
            }
            return Err(header_error(line_number, format!("header line is not text: {}", show_token(raw))));
        };
        if line_number == 1 {
            if line.trim() != "ply" {
                return Err(Error::parse(name, "byte 0", format!("not a PLY file: it starts with {}, not \"ply\"", show_token(raw))));
            }
            continue;
        }
        let mut words = line.split_whitespace();
        let keyword = words.next().unwrap_or("");
        match keyword {
            "" => {}
            "comment" | "obj_info" => {
                let rest: Vec<&str> = words.collect();
                declared_unit = declared_unit.or_else(|| super::unit_declared_in(&rest.join(" ")));
                if rest.first().is_some_and(|w| w.eq_ignore_ascii_case("TextureFile")) && rest.len() > 1 {
                    texture_files.push((rest[1..].join(" "), line_number));
                }
            }
            "format" => {
                encoding = Some(match words.next() {
                    Some("ascii") => Encoding::Ascii,
                    Some("binary_little_endian") => Encoding::BinaryLittleEndian,
                    Some("binary_big_endian") => Encoding::BinaryBigEndian,
                    other => {
                        return Err(header_error(line_number, format!("unknown format {:?}: expected ascii, binary_little_endian or binary_big_endian", other.unwrap_or(""))));
                    }
                });
            }
            "element" => {
                let (Some(element_name), Some(count), None) = (words.next(), words.next(), words.next()) else {
                    return Err(header_error(line_number, format!("malformed element line {line:?}: expected \"element NAME COUNT\"")));
                };
                let count: u64 = count.parse().map_err(|_| {
                    header_error(line_number, format!("element {element_name} has count {count:?}, which is not a non-negative integer"))
                })?;
                elements.push(Element { name: element_name.to_string(), count, properties: Vec::new(), line: line_number });
            }
            "property" => {
                let Some(element) = elements.last_mut() else {
                    return Err(header_error(line_number, "property declared before any element".into()));
                };
                let words: Vec<&str> = words.collect();
                let unknown = |t: &str| header_error(line_number, format!("unknown property type {t:?}"));
                let property = match words.as_slice() {
                    ["list", count, item, property_name] => {
                        let count_type = ScalarType::parse(count).ok_or_else(|| unknown(count))?;
                        let item_type = ScalarType::parse(item).ok_or_else(|| unknown(item))?;
                        if !count_type.is_integer() {
                            return Err(header_error(line_number, format!("list {property_name} has a {count} count: list counts must be integers")));
                        }
                        Property { name: property_name.to_string(), kind: PropertyType::List { count: count_type, item: item_type } }
                    }
                    [scalar, property_name] => Property {
                        name: property_name.to_string(),
                        kind: PropertyType::Scalar(ScalarType::parse(scalar).ok_or_else(|| unknown(scalar))?),
                    },
                    _ => return Err(header_error(line_number, format!("malformed property line {line:?}"))),
                };
                element.properties.push(property);
            }
            "end_header" => break,
            other => return Err(header_error(line_number, format!("unknown header keyword {other:?}"))),
        }
    }
    let encoding = encoding.ok_or_else(|| header_error(2, "the header has no format line".into()))?;
    Ok(Header { encoding, elements, texture_files, declared_unit, body_start: position, line_count: line_number })
}

/// Why a body value could not be read.
enum Fault {
    /// The file ends before the value.
    End,
    /// A text token that is not a number.
    NotANumber(String),
    /// A text token that is not an integer where the header declares an integer type.
    NotAnInteger(String),
    /// An ascii element whose values run past its line.
    LineEnded,
    /// An ascii element with more values on its line than the header declares.
    ExtraValue(String),
}

impl Fault {
    fn message(&self, expected: ScalarType) -> String {
        match self {
            Fault::End => format!("the file ends here, in the middle of the body (truncated, or the header declares more than there is); expected a {expected:?} value"),
            Fault::NotANumber(token) => format!("{token} is not a number"),
            Fault::NotAnInteger(token) => format!("{token} is not an integer, but the header declares {expected:?}"),
            Fault::LineEnded => "the line ends before all the properties the header declares for this element".into(),
            Fault::ExtraValue(token) => format!("unexpected value {token} at the end of the line: the header declares fewer properties for this element"),
        }
    }
}

/// The two body encodings behind one interface, so that element decoding is written once
/// and monomorphised for each.
trait Body {
    fn float(&mut self, kind: ScalarType) -> std::result::Result<f64, Fault>;
    fn integer(&mut self, kind: ScalarType) -> std::result::Result<i64, Fault>;
    fn skip(&mut self, kind: ScalarType) -> std::result::Result<(), Fault>;
    /// A cheap token for the current place (computed per value), turned into words by
    /// [`Body::location_at`] only when an error needs it.
    fn mark(&self) -> usize;
    /// "byte N" or "line N" for a mark.
    fn location_at(&self, mark: usize) -> String;
    /// "byte N" or "line N": where the next value is.
    fn location(&self) -> String {
        self.location_at(self.mark())
    }
    /// Where the current record (element instance) began.
    fn record_location(&self) -> String;
    /// Whether `count` more values of `kind` can possibly fit in the rest of the file.
    fn can_hold(&self, count: u64, kind: ScalarType) -> bool;
    fn begin_record(&mut self) {}
    fn end_record(&mut self) -> std::result::Result<(), Fault> {
        Ok(())
    }
    fn remaining(&self) -> usize;
    fn is_text(&self) -> bool;
    /// The next `size` bytes of a binary body, consumed, if they are there: the fast path
    /// for records of fixed size. Text bodies return `None`.
    fn take(&mut self, size: usize) -> Option<&[u8]>;
    fn big_endian(&self) -> bool {
        false
    }
}

struct BinaryBody<'a> {
    data: &'a [u8],
    position: usize,
    big_endian: bool,
    /// Offset of the body in the file, so that locations are file offsets.
    base: usize,
    record_start: usize,
}

impl Body for BinaryBody<'_> {
    #[inline]
    fn float(&mut self, kind: ScalarType) -> std::result::Result<f64, Fault> {
        let big_endian = self.big_endian;
        let bytes = self.take(kind.size()).ok_or(Fault::End)?;
        Ok(decode_scalar(bytes, kind, big_endian))
    }

    #[inline]
    fn integer(&mut self, kind: ScalarType) -> std::result::Result<i64, Fault> {
        // Every integer type of PLY (at most 32 bits) is exact in an f64.
        let value = self.float(kind)?;
        if !kind.is_integer() && (value.fract() != 0.0 || !value.is_finite()) {
            return Err(Fault::NotAnInteger(value.to_string()));
        }
        Ok(value as i64)
    }

    #[inline]
    fn skip(&mut self, kind: ScalarType) -> std::result::Result<(), Fault> {
        if self.position + kind.size() > self.data.len() {
            return Err(Fault::End);
        }
        self.position += kind.size();
        Ok(())
    }

    fn mark(&self) -> usize {
        self.position
    }

    fn location_at(&self, mark: usize) -> String {
        format!("byte {}", self.base + mark)
    }

    fn record_location(&self) -> String {
        format!("byte {}", self.base + self.record_start)
    }

    fn begin_record(&mut self) {
        self.record_start = self.position;
    }

    fn can_hold(&self, count: u64, kind: ScalarType) -> bool {
        (count as u128) * (kind.size() as u128) <= self.remaining() as u128
    }

    fn remaining(&self) -> usize {
        self.data.len() - self.position
    }

    fn is_text(&self) -> bool {
        false
    }

    #[inline]
    fn take(&mut self, size: usize) -> Option<&[u8]> {
        let bytes = self.data.get(self.position..self.position + size)?;
        self.position += size;
        Some(bytes)
    }

    fn big_endian(&self) -> bool {
        self.big_endian
    }
}

struct AsciiBody<'a> {
    data: &'a [u8],
    position: usize,
    /// Line of the next unread byte.
    line: usize,
    /// Line of the current record's first value, while inside a record.
    record_line: Option<usize>,
}

impl<'a> AsciiBody<'a> {
    fn token(&mut self) -> std::result::Result<&'a [u8], Fault> {
        let data = self.data;
        while let Some(&byte) = data.get(self.position) {
            if byte == b'\n' {
                if self.record_line.is_some_and(|line| line == self.line) {
                    return Err(Fault::LineEnded);
                }
                self.line += 1;
            } else if !byte.is_ascii_whitespace() {
                break;
            }
            self.position += 1;
        }
        if self.position >= data.len() {
            return Err(Fault::End);
        }
        if self.record_line.is_none() {
            self.record_line = Some(self.line);
        }
        let start = self.position;
        while self.position < data.len() && !data[self.position].is_ascii_whitespace() {
            self.position += 1;
        }
        Ok(&data[start..self.position])
    }
}

fn parse_float_token(token: &[u8]) -> Option<f64> {
    std::str::from_utf8(token).ok()?.parse::<f64>().ok()
}

impl Body for AsciiBody<'_> {
    fn float(&mut self, _kind: ScalarType) -> std::result::Result<f64, Fault> {
        let token = self.token()?;
        parse_float_token(token).ok_or_else(|| Fault::NotANumber(show_token(token)))
    }

    fn integer(&mut self, _kind: ScalarType) -> std::result::Result<i64, Fault> {
        let token = self.token()?;
        let text = std::str::from_utf8(token).map_err(|_| Fault::NotAnInteger(show_token(token)))?;
        text.parse::<i64>().map_err(|_| Fault::NotAnInteger(show_token(token)))
    }

    fn skip(&mut self, _kind: ScalarType) -> std::result::Result<(), Fault> {
        self.token().map(|_| ())
    }

    fn mark(&self) -> usize {
        self.position
    }

    /// Ascii records are one line each: the record's line says where.
    fn location_at(&self, _mark: usize) -> String {
        format!("line {}", self.record_line.unwrap_or(self.line))
    }

    fn record_location(&self) -> String {
        format!("line {}", self.record_line.unwrap_or(self.line))
    }

    fn can_hold(&self, count: u64, _kind: ScalarType) -> bool {
        (count as u128) * 2 <= self.remaining() as u128 + 1
    }

    fn begin_record(&mut self) {
        self.record_line = None;
    }

    fn end_record(&mut self) -> std::result::Result<(), Fault> {
        while let Some(&byte) = self.data.get(self.position) {
            if byte == b'\n' {
                break;
            }
            if !byte.is_ascii_whitespace() {
                let start = self.position;
                let end = self.data[start..].iter().position(|b| b.is_ascii_whitespace()).map_or(self.data.len(), |n| start + n);
                return Err(Fault::ExtraValue(show_token(&self.data[start..end])));
            }
            self.position += 1;
        }
        self.record_line = None;
        Ok(())
    }

    fn remaining(&self) -> usize {
        self.data.len() - self.position
    }

    fn is_text(&self) -> bool {
        true
    }

    fn take(&mut self, _size: usize) -> Option<&[u8]> {
        None
    }
}

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

/// Decodes one scalar at the start of `bytes` (which holds at least its size).
#[inline(always)]
fn decode_scalar(bytes: &[u8], kind: ScalarType, big_endian: bool) -> f64 {
    macro_rules! decode {
        ($type:ty) => {{
            let array = bytes[..std::mem::size_of::<$type>()].try_into().expect("the record holds the value");
            (if big_endian { <$type>::from_be_bytes(array) } else { <$type>::from_le_bytes(array) }) as f64
        }};
    }
    match kind {
        ScalarType::I8 => decode!(i8),
        ScalarType::U8 => decode!(u8),
        ScalarType::I16 => decode!(i16),
        ScalarType::U16 => decode!(u16),
        ScalarType::I32 => decode!(i32),
        ScalarType::U32 => decode!(u32),
        ScalarType::F32 => decode!(f32),
        ScalarType::F64 => decode!(f64),
    }
}

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
struct Builder<'a> {
    name: &'a str,
    mesh: Mesh,
    report: ReadReport,
    /// The vertex count the header declares, known before any face is read.
    declared_vertex_count: u64,
    vertex_uvs: Option<Vec<[f32; 2]>>,
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

fn read_body<B: Body>(builder: &mut Builder, body: &mut B, header: &Header) -> Result<()> {
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
