//! The lines the outer profile gives across the drawing: horizontals at rim, carinations
//! and base, and the vessel's dashed outline where the exterior view does not draw it.

use crate::draw::model::{Element, Path};
use crate::draw::DrawOptions;
use crate::profile::measure::Measurements;

use super::canvas::Canvas;
use super::profile::OuterProfile;
use super::views::PlacedView;

/// Horizontal lines at rim, carinations and base (rim and base where the measurements
/// found them preserved), across both halves: to the mirrored outline when it is drawn,
/// else to the exterior view's edge.
pub(super) fn add_lines(canvas: &mut Canvas, profile: &OuterProfile, measurements: &Measurements, exterior_right: f64, options: &DrawOptions) {
    let right_end = |r: f64| if options.prolongation { r } else { exterior_right.max(0.0) };
    let mut lines = Path { segments: Vec::new(), fill: None, stroke: Some(canvas.stroke(0.15, &[])) };
    let top = profile.top_radius();
    if measurements.rim_radius_mm.is_some() {
        lines.extend_polyline(&[[-top, profile.z_top], [right_end(top), profile.z_top]], false);
    }
    for (z, r) in profile.carinations() {
        lines.extend_polyline(&[[-r, z], [right_end(r), z]], false);
    }
    if measurements.base_radius_mm.is_some() {
        let r = profile.bottom_radius();
        lines.extend_polyline(&[[-r, profile.z_bottom], [right_end(r), profile.z_bottom]], false);
    }
    if !lines.segments.is_empty() {
        canvas.layer("lines").push(Element::Path(lines));
    }
}

/// The vessel's outline right of the axis: the outer profile mirrored at its true radius,
/// dashed, where the exterior view does not already draw it. Beside the axis the view
/// touches it; at the true distance the view's edge is the profile itself.
pub(super) fn add_outline(canvas: &mut Canvas, profile: &OuterProfile, measurements: &Measurements, exterior: Option<&PlacedView>) {
    // Near the view its own outline stands for the vessel's: at the true distance the
    // view's edge is a break beside the section's angle, a little off the section's radius
    // on a vessel that is not quite round.
    let reach = 1.5 * canvas.scale;
    let mut dashed = Path { segments: Vec::new(), fill: None, stroke: Some(canvas.stroke(0.2, &[1.5, 1.0])) };
    let mut run: Vec<[f64; 2]> = Vec::new();
    let outer_skin = profile.outer_skin(measurements.base_radius_mm.is_some(), measurements.rim_radius_mm.is_some());
    for &(z, r, _) in outer_skin {
        let point = [r, z];
        if exterior.is_some_and(|view| view.covers(point, reach)) {
            if run.len() >= 2 {
                dashed.extend_polyline(&run, false);
            }
            run.clear();
        } else {
            run.push(point);
        }
    }
    if run.len() >= 2 {
        dashed.extend_polyline(&run, false);
    }
    if !dashed.segments.is_empty() {
        canvas.layer("outline").push(Element::Path(dashed));
    }
}
