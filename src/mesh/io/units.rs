//! Which length unit a scan is probably in. Scan formats carry no unit; a sherd is 1 to
//! 50 cm across, so its largest extent tells the unit where the ranges do not overlap.

use serde::Serialize;

use crate::mesh::Mesh;

/// A length unit a scan may be stored in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum LengthUnit {
    /// Millimetres: what structured-light scanners and MeshLab exports use.
    Millimetres,
    /// Centimetres.
    Centimetres,
    /// Metres: what photogrammetry tools and Blender default to.
    Metres,
    /// No unit gives a plausible sherd size.
    Unknown,
}

impl LengthUnit {
    /// The usual symbol ("mm", "cm", "m"), or "unknown".
    pub fn symbol(self) -> &'static str {
        match self {
            LengthUnit::Millimetres => "mm",
            LengthUnit::Centimetres => "cm",
            LengthUnit::Metres => "m",
            LengthUnit::Unknown => "unknown",
        }
    }
}

impl LengthUnit {
    /// Millimetres in one unit; `None` for [`LengthUnit::Unknown`].
    pub fn millimetres(self) -> Option<f64> {
        match self {
            LengthUnit::Millimetres => Some(1.0),
            LengthUnit::Centimetres => Some(10.0),
            LengthUnit::Metres => Some(1000.0),
            LengthUnit::Unknown => None,
        }
    }
}

/// The unit a file's comment declares, as some scanners and tools write it in a PLY
/// `comment` or `obj_info` line or an OBJ `#` comment: "units mm", "unit: millimeters",
/// "length_unit = cm", "Units: m". `None` when the comment names no unit.
pub fn unit_declared_in(comment: &str) -> Option<LengthUnit> {
    let lowered = comment.to_ascii_lowercase();
    let words: Vec<&str> =
        lowered.split(|c: char| c.is_whitespace() || matches!(c, ':' | '=' | ',' | ';' | '"' | '\'')).filter(|w| !w.is_empty()).collect();
    let at = words.iter().position(|w| matches!(*w, "unit" | "units" | "length_unit" | "length_units" | "lengthunit"))?;
    match *words.get(at + 1)? {
        "mm" | "millimeter" | "millimeters" | "millimetre" | "millimetres" => Some(LengthUnit::Millimetres),
        "cm" | "centimeter" | "centimeters" | "centimetre" | "centimetres" => Some(LengthUnit::Centimetres),
        "m" | "meter" | "meters" | "metre" | "metres" => Some(LengthUnit::Metres),
        _ => None,
    }
}

/// The unit guessed for a scan, with the extent it was guessed from and why.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct UnitsGuess {
    /// The probable unit.
    pub unit: LengthUnit,
    /// The largest side of the bounding box, in file units.
    pub largest_extent: f64,
    /// One sentence saying why, for people.
    pub reason: String,
}

/// Guesses the unit of `mesh` from its largest bounding-box extent: 10 to 2,000 is a sherd
/// (or a whole vessel) in millimetres, 1 to 10 in centimetres (a sherd under 1 cm is not
/// drawn), 0.005 to 1 in metres; anything else is unknown. `None` for an empty mesh.
pub fn guess_units(mesh: &Mesh) -> Option<UnitsGuess> {
    let (low, high) = mesh.bounding_box()?;
    let extent = high - low;
    let largest_extent = extent.max();
    let (unit, reason) = if (10.0..=2000.0).contains(&largest_extent) {
        (LengthUnit::Millimetres, "tens to hundreds of units: a sherd or vessel in millimetres")
    } else if (1.0..10.0).contains(&largest_extent) {
        (LengthUnit::Centimetres, "a few units: a sherd in centimetres")
    } else if (0.005..1.0).contains(&largest_extent) {
        (LengthUnit::Metres, "under one unit: a sherd in metres")
    } else {
        (LengthUnit::Unknown, "no unit makes this a plausible sherd size (0.5 cm to 2 m)")
    };
    Some(UnitsGuess { unit, largest_extent, reason: format!("largest extent {largest_extent:.4}: {reason}") })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Point;

    fn segment(length: f64) -> Mesh {
        Mesh::new(vec![Point::origin(), Point::new(0.0, length, length / 3.0)], Vec::new())
    }

    #[test]
    fn declared_units_are_read_from_comments() {
        assert_eq!(unit_declared_in("units mm"), Some(LengthUnit::Millimetres));
        assert_eq!(unit_declared_in("Unit: Centimeters"), Some(LengthUnit::Centimetres));
        assert_eq!(unit_declared_in("length_unit = m"), Some(LengthUnit::Metres));
        assert_eq!(unit_declared_in("Created by sherd 0.1.0"), None);
        assert_eq!(unit_declared_in("units"), None);
        assert_eq!(unit_declared_in("units furlongs"), None);
        assert_eq!(LengthUnit::Centimetres.millimetres(), Some(10.0));
    }

    #[test]
    fn units_follow_the_extent() {
        assert_eq!(guess_units(&segment(85.0)).unwrap().unit, LengthUnit::Millimetres);
        assert_eq!(guess_units(&segment(8.5)).unwrap().unit, LengthUnit::Centimetres);
        assert_eq!(guess_units(&segment(0.085)).unwrap().unit, LengthUnit::Metres);
        assert_eq!(guess_units(&segment(1e6)).unwrap().unit, LengthUnit::Unknown);
        assert_eq!(guess_units(&segment(0.0)).unwrap().unit, LengthUnit::Unknown);
        assert!(guess_units(&Mesh::default()).is_none());
    }
}
