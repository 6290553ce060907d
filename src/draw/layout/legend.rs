//! The legend of a regularity map's colours, drawn when the views are coloured by it.

use crate::draw::model::{Anchor, Element, Path, Text};
use crate::profile::regularity::{ColorMap, ColorScale};

use super::canvas::Canvas;
use super::BLACK;

/// The colour scale of a regularity map: a vertical bar with values and title, its top
/// left corner at the origin.
pub(super) fn legend(canvas: &Canvas, map: &ColorMap) -> Vec<Element> {
    let scale = canvas.scale;
    let (x, top) = (0.0, 0.0);
    let (width, height, steps) = (4.0 * scale, 40.0 * scale, 32);
    let mut children = Vec::new();
    for (i, (_, color)) in map.legend(steps).iter().enumerate() {
        let z1 = top - height + height * (i + 1) as f64 / steps as f64;
        let z0 = top - height + height * i as f64 / steps as f64;
        let rect = [[x, z0], [x + width, z0], [x + width, z1], [x, z1]];
        children.push(Element::Path(Path::polyline(&rect, true, Some(*color), None)));
    }
    let frame = [[x, top - height], [x + width, top - height], [x + width, top], [x, top]];
    children.push(Element::Path(Path::polyline(&frame, true, None, Some(canvas.stroke(0.15, &[])))));
    for (value, z) in [(map.low, top - height), (0.5 * (map.low + map.high), top - height / 2.0), (map.high, top)] {
        // A diverging scale is signed: "-0.08 mm", "0 mm", "+0.08 mm".
        let content = match map.scale {
            ColorScale::Diverging if value.abs() < 1e-12 => format!("0 {}", map.unit),
            ColorScale::Diverging => format!("{value:+.2} {}", map.unit),
            ColorScale::Rainbow => format!("{value:.2} {}", map.unit),
        };
        children.push(Element::Text(Text {
            position: [x + width + 1.5 * scale, z - 1.0 * scale],
            content,
            size_mm: 2.6,
            anchor: Anchor::Start,
            color: BLACK,
        }));
    }
    children.push(Element::Text(Text {
        position: [x, top + 3.0 * scale],
        content: map.title.clone(),
        size_mm: 2.8,
        anchor: Anchor::Start,
        color: BLACK,
    }));
    children
}
