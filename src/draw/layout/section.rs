//! The section left of the axis at its true radius, filled black or hatched.

use crate::draw::model::{Element, Path, Segment};
use crate::draw::SectionFill;
use crate::profile::section::ProfileSection;

use super::canvas::Canvas;
use super::{BLACK, WHITE};

/// The section left of the axis (x = -r), filled black or hatched, outlined.
pub(super) fn add_section(canvas: &mut Canvas, section: &ProfileSection, fill: SectionFill) {
    let outlines: Vec<Vec<[f64; 2]>> =
        section.closed_outlines().into_iter().map(|o| o.into_iter().map(|p| [-p[0], p[1]]).collect()).collect();
    let mut shape = Path { segments: Vec::new(), fill: None, stroke: Some(canvas.stroke(0.25, &[])) };
    for o in &outlines {
        shape.extend_polyline(o, true);
    }
    match fill {
        SectionFill::Black => {
            shape.fill = Some(BLACK);
            canvas.layer("section").push(Element::Path(shape));
        }
        SectionFill::Hatched => {
            // Filled white under the hatching: the interior view it covers must not show through.
            shape.fill = Some(WHITE);
            canvas.layer("section").push(Element::Path(shape));
            let spacing = 0.8 * canvas.scale;
            let hatch = hatch_lines(&outlines, spacing);
            let mut lines = Path { segments: Vec::new(), fill: None, stroke: Some(canvas.stroke(0.15, &[])) };
            for [a, b] in hatch {
                lines.segments.push(Segment::MoveTo(a));
                lines.segments.push(Segment::LineTo(b));
            }
            canvas.layer("section").push(Element::Path(lines));
        }
    }
}

/// 45-degree hatching of the polygons (even-odd), as segments.
fn hatch_lines(polygons: &[Vec<[f64; 2]>], spacing: f64) -> Vec<[[f64; 2]; 2]> {
    // In coordinates u = x - z (constant along a 45 deg line) the lines are u = k * spacing.
    let us = polygons.iter().flatten().map(|p| p[0] - p[1]);
    let (lo, hi) = us.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), u| (a.min(u), b.max(u)));
    let mut segments = Vec::new();
    if !lo.is_finite() {
        return segments;
    }
    let mut k = (lo / spacing).ceil();
    while k * spacing <= hi {
        let u = k * spacing;
        // Crossings with each edge, parameterised by v = x + z along the line.
        let mut crossings = Vec::new();
        for polygon in polygons {
            for i in 0..polygon.len() {
                let (a, b) = (polygon[i], polygon[(i + 1) % polygon.len()]);
                let (ua, ub) = (a[0] - a[1], b[0] - b[1]);
                if (ua <= u) != (ub <= u) {
                    let t = (u - ua) / (ub - ua);
                    let (x, z) = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]));
                    crossings.push(x + z);
                }
            }
        }
        crossings.sort_unstable_by(f64::total_cmp);
        for pair in crossings.chunks_exact(2) {
            let point = |v: f64| [(u + v) / 2.0, (v - u) / 2.0];
            segments.push([point(pair[0]), point(pair[1])]);
        }
        k += 1.0;
    }
    segments
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hatching_fills_a_square_with_45_degree_lines() {
        let square = vec![vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]]];
        let lines = hatch_lines(&square, 1.0);
        assert!(lines.len() >= 18 && lines.len() <= 21, "{}", lines.len());
        for [a, b] in &lines {
            assert!(((b[1] - a[1]) - (b[0] - a[0])).abs() < 1e-9, "45 degrees");
            for p in [a, b] {
                assert!(p[0] >= -1e-9 && p[0] <= 10.0 + 1e-9 && p[1] >= -1e-9 && p[1] <= 10.0 + 1e-9);
            }
        }
    }
}
