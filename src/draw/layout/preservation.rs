//! The preservation figures: how much of the rim's or base's circle the fragment keeps.

use crate::draw::model::{Anchor, Element, Group, Path, Text};
use crate::profile::measure::Measurements;

use super::canvas::Canvas;
use super::{BLACK, LABEL_SIZE_MM};

/// Radius of the preservation figure's circle, paper mm.
const PRESERVATION_RADIUS_MM: f64 = 5.0;

/// The preserved share of the rim and of the base, each as the usual figure: a thin
/// circle with the preserved arc drawn bold at its top, and the share written under it
/// ("9% of rim", the rim's own arc, not the whole sherd's). A fragment with neither gives
/// the arc of circumference it spans. Each figure is a group at the origin.
pub(super) fn preservation_figures(canvas: &Canvas, measurements: &Measurements) -> Vec<Vec<Element>> {
    let mut arcs = Vec::new();
    if let Some(deg) = measurements.rim_sector_deg {
        arcs.push(("rim", deg));
    }
    if let Some(deg) = measurements.base_sector_deg {
        arcs.push(("base", deg));
    }
    if arcs.is_empty() && measurements.sector_angle_deg > 0.0 {
        arcs.push(("circumference", measurements.sector_angle_deg));
    }
    let scale = canvas.scale;
    let radius = PRESERVATION_RADIUS_MM * scale;
    let circle_points = |from_deg: f64, to_deg: f64| -> Vec<[f64; 2]> {
        let steps = ((to_deg - from_deg).abs() / 3.0).ceil().max(2.0) as usize;
        (0..=steps)
            .map(|i| {
                let a = (from_deg + (to_deg - from_deg) * i as f64 / steps as f64).to_radians();
                [radius * a.cos(), radius * a.sin()]
            })
            .collect()
    };
    arcs.into_iter()
        .map(|(edge, deg)| {
            let deg = deg.clamp(0.0, 360.0);
            let mut children = vec![
                Element::Path(Path::polyline(&circle_points(0.0, 360.0), true, None, Some(canvas.stroke(0.15, &[])))),
                Element::Path(Path::polyline(&circle_points(90.0 - deg / 2.0, 90.0 + deg / 2.0), false, None, Some(canvas.stroke(0.9, &[])))),
            ];
            let percent = deg / 360.0 * 100.0;
            let content = if edge == "circumference" { format!("{deg:.0}° of circumference") } else { format!("{percent:.0}% of {edge}") };
            children.push(Element::Text(Text {
                position: [0.0, -radius - (1.5 + 0.8 * LABEL_SIZE_MM) * scale],
                content,
                size_mm: LABEL_SIZE_MM,
                anchor: Anchor::Middle,
                color: BLACK,
            }));
            vec![Element::Group(Group { id: format!("preservation-{edge}"), children })]
        })
        .collect()
}
