//! The scale bar below the drawing, in round centimetres at the publication scale.

use crate::draw::model::{Anchor, Element, Group, Path, Text};

use super::canvas::Canvas;
use super::{BLACK, WHITE};

/// A scale bar of a round length at most half of `span` (alternating black and white
/// centimetres) with its label, as a group at the origin.
pub(super) fn scale_bar(canvas: &Canvas, span: f64) -> Element {
    let scale = canvas.scale;
    let length = [10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0]
        .into_iter()
        .rev()
        .find(|&l| l <= 0.5 * span)
        .unwrap_or(10.0);
    let pieces = if length <= 100.0 { (length / 10.0) as usize } else { 5 };
    let step = length / pieces as f64;
    let height = 1.5 * scale;
    let mut group = Group { id: "scale-bar-graphic".into(), children: Vec::new() };
    for i in 0..pieces {
        let x = i as f64 * step;
        let fill = if i % 2 == 0 { BLACK } else { WHITE };
        let rect = [[x, 0.0], [x + step, 0.0], [x + step, -height], [x, -height]];
        group.children.push(Element::Path(Path::polyline(&rect, true, Some(fill), Some(canvas.stroke(0.15, &[])))));
    }
    let label = if length >= 10.0 { format!("{} cm", length / 10.0) } else { format!("{length} mm") };
    let text = |position, content: String| Element::Text(Text { position, content, size_mm: 3.0, anchor: Anchor::Middle, color: BLACK });
    group.children.push(text([0.0, -height - 4.0 * scale], "0".into()));
    group.children.push(text([length, -height - 4.0 * scale], label));
    Element::Group(group)
}
