//! The body of a PLY file read value by value, binary records from their bytes and ascii
//! ones from whitespace-separated tokens, behind one `Body` trait so that the decoding
//! of elements is written once for both.

use super::header::ScalarType;
use crate::mesh::io::show_token;

/// Why a body value could not be read.
pub(super) enum Fault {
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
    pub(super) fn message(&self, expected: ScalarType) -> String {
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
pub(super) trait Body {
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

pub(super) struct BinaryBody<'a> {
    pub(super) data: &'a [u8],
    pub(super) position: usize,
    pub(super) big_endian: bool,
    /// Offset of the body in the file, so that locations are file offsets.
    pub(super) base: usize,
    pub(super) record_start: usize,
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

/// Decodes one scalar at the start of `bytes` (which holds at least its size).
#[inline(always)]
pub(super) fn decode_scalar(bytes: &[u8], kind: ScalarType, big_endian: bool) -> f64 {
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

pub(super) struct AsciiBody<'a> {
    pub(super) data: &'a [u8],
    pub(super) position: usize,
    /// Line of the next unread byte.
    pub(super) line: usize,
    /// Line of the current record's first value, while inside a record.
    pub(super) record_line: Option<usize>,
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
