//! Text point clouds: XYZ (`x y z` or `x y z nx ny nz`, as SfS++ and CloudCompare write
//! them) and PTS (Leica: an optional count line, then `x y z intensity [r g b]`).
//! Separators may be spaces, tabs, commas or semicolons; `#` starts a comment line.

use super::{ReadReport, show_token};
use crate::mesh::{Mesh, Point, Vector};
use crate::{Error, Result};

/// What the columns of a row mean, from their count.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Layout {
    Positions,
    PositionsIntensity,
    PositionsNormals,
    PositionsIntensityColour,
}

impl Layout {
    fn for_columns(columns: usize) -> Option<Self> {
        Some(match columns {
            3 => Layout::Positions,
            4 => Layout::PositionsIntensity,
            6 => Layout::PositionsNormals,
            7 => Layout::PositionsIntensityColour,
            _ => return None,
        })
    }
}

pub(super) fn parse_points(bytes: &[u8], name: &str) -> Result<(Mesh, ReadReport)> {
    let mut report = ReadReport::new("xyz");
    let mut layout = None;
    let mut declared_count: Option<(usize, usize)> = None;
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    let mut intensities = Vec::new();
    let mut colours = Vec::new();
    let mut values: Vec<f64> = Vec::with_capacity(8);
    for (number, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let line_number = number + 1;
        let point_index = positions.len();
        let at = || format!("line {line_number} (point {point_index})");
        let trimmed = raw.trim_ascii();
        if trimmed.is_empty() || trimmed.starts_with(b"#") || trimmed.starts_with(b"//") {
            continue;
        }
        values.clear();
        for word in trimmed.split(|b| b.is_ascii_whitespace() || *b == b',' || *b == b';').filter(|w| !w.is_empty()) {
            let value = std::str::from_utf8(word).ok().and_then(|w| w.parse::<f64>().ok());
            values.push(value.ok_or_else(|| Error::parse(name, at(), format!("{} is not a number", show_token(word))))?);
        }
        if layout.is_none() && positions.is_empty() && declared_count.is_none() && values.len() == 1 {
            // The PTS count line.
            let count = values[0];
            if count < 0.0 || count.fract() != 0.0 {
                return Err(Error::parse(name, at(), format!("point count {count} is not a non-negative integer")));
            }
            declared_count = Some((count as usize, line_number));
            report.format = "pts".into();
            continue;
        }
        let this_layout = Layout::for_columns(values.len()).ok_or_else(|| {
            Error::parse(name, at(), format!("{} values: expected 3 (x y z), 4 (x y z intensity), 6 (x y z nx ny nz) or 7 (x y z intensity r g b)", values.len()))
        })?;
        match layout {
            None => {
                layout = Some(this_layout);
                // Each row holds at least two bytes per value: a bound on what the file can hold.
                let capacity = bytes.len() / (2 * values.len());
                positions.reserve(capacity);
            }
            Some(expected) if expected != this_layout => {
                return Err(Error::parse(name, at(), format!("{} values, but the first point has a different count ({expected:?})", values.len())));
            }
            Some(_) => {}
        }
        let position = Point::new(values[0], values[1], values[2]);
        if let Some(k) = (0..3).find(|&k| !position[k].is_finite()) {
            return Err(Error::parse(name, at(), format!("coordinate {} is {}", ["x", "y", "z"][k], position[k])));
        }
        positions.push(position);
        match this_layout {
            Layout::Positions => {}
            Layout::PositionsIntensity => intensities.push(values[3] as f32),
            Layout::PositionsNormals => {
                let normal = Vector::new(values[3], values[4], values[5]);
                let length = normal.norm();
                if !(length.is_finite() && length > 0.0) {
                    return Err(Error::parse(name, at(), format!("normal ({}, {}, {}) has no direction", normal.x, normal.y, normal.z)));
                }
                normals.push(normal / length);
            }
            Layout::PositionsIntensityColour => {
                intensities.push(values[3] as f32);
                let channel = |k: usize| values[k].round().clamp(0.0, 255.0) as u8;
                colours.push([channel(4), channel(5), channel(6), 255]);
            }
        }
    }
    if positions.is_empty() {
        return Err(Error::parse(name, "line 1", "the file contains no points"));
    }
    if let Some((count, line)) = declared_count {
        if count != positions.len() {
            report.warn(format!("line {line} declares {count} points, the file has {}", positions.len()));
        }
    }
    let mut mesh = Mesh::new(positions, Vec::new());
    match layout {
        Some(Layout::PositionsNormals) => mesh.normals = Some(normals),
        Some(Layout::PositionsIntensity) => mesh.quality = Some(intensities),
        Some(Layout::PositionsIntensityColour) => {
            mesh.quality = Some(intensities);
            mesh.colors = Some(colours);
        }
        _ => {}
    }
    Ok((mesh, report))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normals_are_read_and_normalised() {
        let (mesh, report) = parse_points(b"# comment\n1 2 3 0 0 2\n4,5,6,1,0,0\n", "p.xyz").unwrap();
        assert_eq!(report.format, "xyz");
        assert_eq!(mesh.positions[1], Point::new(4.0, 5.0, 6.0));
        assert_eq!(mesh.normals.unwrap()[0], Vector::new(0.0, 0.0, 1.0));
    }

    #[test]
    fn pts_count_line_and_colours() {
        let (mesh, report) = parse_points(b"2\n0 0 0 -100 255 0 0\n1 1 1 50 0 0 255\n", "p.pts").unwrap();
        assert_eq!(report.format, "pts");
        assert!(report.warnings.is_empty());
        assert_eq!(mesh.colors.unwrap()[1], [0, 0, 255, 255]);
        assert_eq!(mesh.quality.unwrap(), vec![-100.0, 50.0]);
    }

    #[test]
    fn changing_column_count_names_the_line() {
        let message = parse_points(b"0 0 0\n1 1 1\n2 2\n", "p.xyz").unwrap_err().to_string();
        assert!(message.contains("line 3") && message.contains("2 values"), "{message}");
    }
}
