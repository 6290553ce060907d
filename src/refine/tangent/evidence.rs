//! Evidence that a fragment keeps a rim or base: its sections' extremes lie level, and
//! do not sag towards the ends of the arc as a rounded surface's do.

use serde::{Deserialize, Serialize};

use super::{Edge, TangentObjective};
use crate::mesh::{planar_length, Point};
use crate::refine::sections::{AxisParameters, CandidateFrame, PreparedSurface};

/// Evidence that a fragment keeps a rim or base: the extremes of its vertical sections
/// under a given axis lie on one horizontal plane.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct EdgeEvidence {
    /// The edge tested.
    pub edge: Edge,
    /// Share of vertical sections whose extreme lies within the tolerance of the median extreme.
    pub level_fraction: f64,
    /// Spread (median absolute deviation) of the extremes of those sections, millimetres.
    pub spread_mm: f64,
    /// How far the level extremes fall away from the plane towards the ends of the arc,
    /// millimetres ([`edge_sag_mm`]): an edge lies flat, a rounded surface rocks.
    pub sag_mm: f64,
}

/// Half-width of the band about the median extreme that [`edge_sag_mm`] is fitted to in
/// the edge evidence, mm: a rim or base broken off at one end of the arc leaves its last
/// sections a millimetre or so off the plane, a step that a parabola through them would
/// read as sag (synthetic base 1003 from its pre-orientation: 0.28 mm with them, 0.05
/// without), while a rocking surface's parabola runs through the band.
const SAG_BAND_MM: f64 = 0.3;

/// How far the `level` extremes (points in the candidate frame) fall away from their
/// plane towards the two ends of the arc, in millimetres: the end value of the quadratic
/// `h(u) = a + b u + c u^2` fitted to their heights over the azimuth `u` scaled to
/// [-1, 1], `c`, signed so that positive is away from the vessel (down for a rim, up
/// for a base).
///
/// A rim or base that survives lies on its plane along the whole arc, within the scan's
/// noise and the vessel's unevenness. A rounded surface with no edge, such as the convex
/// underside of a bowl whose standing ring broke off, also has a lowest point in every
/// vertical section, and a plane tilted onto it touches it in the middle of the arc: the
/// extremes rise towards both ends, a parabola in the azimuth, whatever the tilt. Level
/// edges sag by hundredths of a millimetre, rocking undersides by tenths
/// (`docs/calibration.md`, `EDGE_MAX_SAG_MM`).
pub fn edge_sag_mm(level: &[Point], edge: Edge) -> f64 {
    if level.len() < 4 {
        return 0.0;
    }
    let (sum_x, sum_y) = level.iter().fold((0.0, 0.0), |(x, y), p| {
        let r = planar_length(p.x, p.y).max(1e-12);
        (x + p.x / r, y + p.y / r)
    });
    let middle = sum_y.atan2(sum_x);
    let (sin, cos) = middle.sin_cos();
    let azimuths: Vec<f64> = level.iter().map(|p| (p.y * cos - p.x * sin).atan2(p.x * cos + p.y * sin)).collect();
    let half_arc = azimuths.iter().map(|a| a.abs()).fold(0.0, f64::max);
    if !(half_arc > 1e-9) {
        return 0.0;
    }
    let away = -edge.outward();
    let mut normal = nalgebra::Matrix3::<f64>::zeros();
    let mut right = nalgebra::Vector3::<f64>::zeros();
    for (p, azimuth) in level.iter().zip(&azimuths) {
        let u = azimuth / half_arc;
        let row = nalgebra::Vector3::new(1.0, u, u * u);
        normal += row * row.transpose();
        right += row * (away * p.z);
    }
    normal.cholesky().map_or(0.0, |c| c.solve(&right)[2])
}

/// Tests whether the fragment keeps `edge` level under the axis `parameters` of `surface`.
pub fn edge_evidence(
    surface: &PreparedSurface,
    edge: Edge,
    tolerance_mm: f64,
    section_count: usize,
    parameters: &AxisParameters,
) -> EdgeEvidence {
    edge_evidence_anchored(surface, edge, tolerance_mm, section_count, parameters, false)
}

/// [`edge_evidence`], with the level set hung from the top (rim) or bottom (base)
/// extreme when `from_top` instead of from the median of all sections: where the rim
/// survives over a third of the arc, the break lines hold the median and the rim would
/// count as not level.
pub fn edge_evidence_anchored(
    surface: &PreparedSurface,
    edge: Edge,
    tolerance_mm: f64,
    section_count: usize,
    parameters: &AxisParameters,
    from_top: bool,
) -> EdgeEvidence {
    let objective = TangentObjective::new(surface, edge, tolerance_mm, section_count);
    let points = objective.extreme_points(&CandidateFrame::new(parameters));
    let mut extremes: Vec<f64> = points.iter().map(|p| p.z).collect();
    if extremes.is_empty() {
        return EdgeEvidence { edge, level_fraction: 0.0, spread_mm: f64::INFINITY, sag_mm: 0.0 };
    }
    let top = match edge {
        Edge::Rim => extremes.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        Edge::Base => extremes.iter().copied().fold(f64::INFINITY, f64::min),
    };
    let mut near_top: Vec<f64> = extremes.iter().copied().filter(|z| (z - top).abs() <= tolerance_mm).collect();
    let median = crate::statistics::quantile(if from_top { &mut near_top } else { &mut extremes }, 0.5);
    let level: Vec<f64> = extremes.iter().map(|z| (z - median).abs()).filter(|d| *d <= tolerance_mm).collect();
    let mut deviations = level.clone();
    let spread = if deviations.is_empty() { f64::INFINITY } else { crate::statistics::quantile(&mut deviations, 0.5) };
    let level_points: Vec<Point> = points.into_iter().filter(|p| (p.z - median).abs() <= tolerance_mm.min(SAG_BAND_MM)).collect();
    EdgeEvidence {
        edge,
        level_fraction: level.len() as f64 / extremes.len() as f64,
        spread_mm: spread,
        sag_mm: edge_sag_mm(&level_points, edge),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_level_arc_does_not_sag_and_a_rounded_one_does() {
        // 40 degrees of a 60 mm circle: level with 0.02 mm of alternating noise, and
        // rising by 0.3 mm towards both ends.
        let arc = |lift: &dyn Fn(f64) -> f64| -> Vec<Point> {
            (0..25)
                .map(|i| {
                    let u = i as f64 / 12.0 - 1.0;
                    let azimuth = 1.0 + u * 20f64.to_radians();
                    Point::new(60.0 * azimuth.cos(), 60.0 * azimuth.sin(), lift(u) + if i % 2 == 0 { 0.02 } else { -0.02 })
                })
                .collect()
        };
        let level = arc(&|_| 0.0);
        let rounded = arc(&|u| 0.3 * u * u);
        assert!(edge_sag_mm(&level, Edge::Base).abs() < 0.02);
        assert!((edge_sag_mm(&rounded, Edge::Base) - 0.3).abs() < 0.02);
        // For a rim "away from the vessel" is down: the same points rise, a negative sag.
        assert!((edge_sag_mm(&rounded, Edge::Rim) + 0.3).abs() < 0.02);
    }
}
