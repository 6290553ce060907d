//! The PLY header: the scalar and property types, the elements with their counts, and
//! the body encoding, all known before a byte of the body is read, so that the reader
//! can check the counts against the file size before allocating.

use crate::mesh::io::{LengthUnit, show_token, unit_declared_in};
use crate::{Error, Result};

/// The scalar types of the PLY format, under both their old and their sized names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum ScalarType {
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

    pub(super) fn size(self) -> usize {
        match self {
            ScalarType::I8 | ScalarType::U8 => 1,
            ScalarType::I16 | ScalarType::U16 => 2,
            ScalarType::I32 | ScalarType::U32 | ScalarType::F32 => 4,
            ScalarType::F64 => 8,
        }
    }

    pub(super) fn is_integer(self) -> bool {
        !matches!(self, ScalarType::F32 | ScalarType::F64)
    }

    /// The largest value of an integer type, used to scale integer colours to 0-255.
    pub(super) fn max_value(self) -> f64 {
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
pub(super) enum PropertyType {
    Scalar(ScalarType),
    List { count: ScalarType, item: ScalarType },
}

#[derive(Clone, Debug)]
pub(super) struct Property {
    pub(super) name: String,
    pub(super) kind: PropertyType,
}

#[derive(Clone, Debug)]
pub(super) struct Element {
    pub(super) name: String,
    pub(super) count: u64,
    pub(super) properties: Vec<Property>,
    /// 1-based header line of the `element` declaration, for messages.
    pub(super) line: usize,
}

impl Element {
    /// The fewest bytes one instance can take in the body: what the file must hold at
    /// least, checked before allocating anything.
    pub(super) fn minimum_bytes(&self, encoding: Encoding) -> u64 {
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
pub(super) enum Encoding {
    Ascii,
    BinaryLittleEndian,
    BinaryBigEndian,
}

pub(super) struct Header {
    pub(super) encoding: Encoding,
    pub(super) elements: Vec<Element>,
    /// Each `comment TextureFile` name with its header line.
    pub(super) texture_files: Vec<(String, usize)>,
    /// The unit the first comment naming one declares.
    pub(super) declared_unit: Option<LengthUnit>,
    /// Byte offset of the body.
    pub(super) body_start: usize,
    /// Number of header lines, so that ascii body lines are numbered as in an editor.
    pub(super) line_count: usize,
}

pub(super) fn parse_header(bytes: &[u8], name: &str) -> Result<Header> {
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
                declared_unit = declared_unit.or_else(|| unit_declared_in(&rest.join(" ")));
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
