//! The measurements written on the drawing: the diameters above the axis and the
//! annotations asked for below it.

use crate::draw::model::{Anchor, Element, Text};
use crate::draw::Annotations;
use crate::profile::measure::Measurements;

use super::canvas::Canvas;
use super::{BLACK, LABEL_SIZE_MM};

/// The diameters, centred on the axis above `z` (the axis line's top), one line each;
/// returns the height of the top of the last (`z` when there is none).
pub(super) fn add_labels(canvas: &mut Canvas, measurements: &Measurements, z: f64) -> f64 {
    let scale = canvas.scale;
    let mut labels = Vec::new();
    if let Some(d) = measurements.rim_diameter_mm {
        labels.push(match measurements.rim_diameter_interval_mm {
            Some([lo, hi]) => format!("Ø {d:.0} mm ({lo:.0}-{hi:.0})"),
            None => format!("Ø {d:.0} mm"),
        });
    }
    if let Some(d) = measurements.base_diameter_mm {
        labels.push(match measurements.base_diameter_interval_mm {
            Some([lo, hi]) => format!("base Ø {d:.0} mm ({lo:.0}-{hi:.0})"),
            None => format!("base Ø {d:.0} mm"),
        });
    }
    let line = 1.4 * LABEL_SIZE_MM * scale;
    let mut baseline = z + 0.25 * LABEL_SIZE_MM * scale + 1.5 * scale;
    let mut top = z;
    // The base's label nearest the drawing, the rim's above it, as the edges stand.
    for label in labels.into_iter().rev() {
        canvas.text("labels", [0.0, baseline], label, LABEL_SIZE_MM, Anchor::Middle);
        top = baseline + 0.8 * LABEL_SIZE_MM * scale;
        baseline += line;
    }
    top
}

/// The annotations asked for, one line each, left-aligned at the origin.
pub(super) fn annotations(measurements: &Measurements, wanted: Annotations, scale: f64) -> Vec<Element> {
    let mut lines = Vec::new();
    if wanted.height {
        lines.push(format!("height {:.0} mm", measurements.height_mm));
    }
    if wanted.wall_thickness {
        if let Some(t) = measurements.wall_thickness_mm {
            lines.push(format!("wall {t:.1} mm"));
        }
    }
    if wanted.capacity {
        if let Some(litres) = measurements.capacity_litres {
            lines.push(format!("capacity {litres:.2} l"));
        }
    }
    lines
        .into_iter()
        .enumerate()
        .map(|(i, content)| {
            Element::Text(Text {
                position: [0.0, -(i as f64) * 1.4 * LABEL_SIZE_MM * scale],
                content,
                size_mm: LABEL_SIZE_MM,
                anchor: Anchor::Start,
                color: BLACK,
            })
        })
        .collect()
}
