//! Which way the axis points: from the base to the rim. The normals fix the axis as a
//! line; its sense comes from the shape of the vessel seen in the rz half-plane:
//! - a floor: surface facing along the axis that reaches in towards the axis from the
//!   wall is a base, and the wall rises from it;
//! - a free end (rim): at one end of the profile the two skins close in a lip that faces
//!   away from the sherd and does not reach in towards the axis;
//! - the opening: a vessel widens from its base more often than it narrows (the weakest
//!   cue, used alone only when the others are silent).

use super::axis::Axis;
use super::normal_lines::NormalLines;
use crate::mesh::Vector;

/// The evidence for the sense of an axis.
#[derive(Clone, Debug)]
pub struct DirectionEvidence {
    /// Positive when the axis as given points from base to rim; its magnitude is the
    /// strength of the evidence (about 1 for a clear floor or lip, below 0.2 for the
    /// opening cue alone).
    pub score: f64,
    /// Which cue decided, for the report.
    pub cue: String,
}

struct Sample {
    radius: f64,
    height: f64,
    normal_radial: f64,
    normal_axial: f64,
    weight: f64,
}

/// Weighs the cues for `axis` on the lines that lie on the surface of revolution
/// (`lines` with `on_surface[i]`) and, for the lip, on all the sherd's lines (the lip has
/// no opposite partner, so the opposite-normal test drops it); `lip_tolerance_mm` is how
/// close a normal line must pass to the axis to be on the surface of revolution.
pub fn direction_evidence(
    lines: &NormalLines,
    on_surface: &[bool],
    all_lines: &NormalLines,
    axis: &Axis,
    lip_tolerance_mm: f64,
) -> DirectionEvidence {
    let d = axis.direction.into_inner();
    let samples: Vec<Sample> = (0..lines.len())
        .filter(|&i| on_surface[i])
        .map(|i| {
            let q = lines.points[i] - axis.point;
            let height = q.dot(&d);
            let radial: Vector = q - d * height;
            let radius = radial.norm();
            let e_r = if radius > 0.0 { radial / radius } else { Vector::zeros() };
            let n = lines.directions[i];
            Sample { radius, height, normal_radial: n.dot(&e_r), normal_axial: n.dot(&d), weight: lines.weights[i] }
        })
        .collect();
    let total: f64 = samples.iter().map(|s| s.weight).sum();
    if samples.is_empty() || !(total > 0.0) {
        return DirectionEvidence { score: 0.0, cue: "no surface of revolution to judge from".into() };
    }
    let wall: Vec<&Sample> = samples.iter().filter(|s| s.normal_radial.abs() > 0.5).collect();
    let flat: Vec<&Sample> = samples.iter().filter(|s| s.normal_axial.abs() > 0.85).collect();
    let wall_weight: f64 = wall.iter().map(|s| s.weight).sum();
    let flat_weight: f64 = flat.iter().map(|s| s.weight).sum();

    // Floor: flat surface reaching well inside the wall's radius.
    if flat_weight > 0.05 * total && wall_weight > 0.05 * total {
        let wall_radius = weighted_median(wall.iter().map(|s| (s.radius, s.weight)));
        let flat_inner_radius = weighted_quantile(flat.iter().map(|s| (s.radius, s.weight)), 0.25);
        if flat_inner_radius < 0.8 * wall_radius {
            let flat_height = weighted_median(flat.iter().map(|s| (s.height, s.weight)));
            let wall_height = weighted_median(wall.iter().map(|s| (s.height, s.weight)));
            let sense = (wall_height - flat_height).signum();
            return DirectionEvidence { score: sense, cue: "floor: the wall rises from a flat base".into() };
        }
    }
    if let Some(score) = lip_evidence(all_lines, axis, lip_tolerance_mm) {
        return DirectionEvidence { score, cue: "rim: a lip closes one end of the profile".into() };
    }
    if wall_weight <= 0.0 {
        return DirectionEvidence { score: 0.0, cue: "no wall to judge from".into() };
    }
    // Opening: the mean slope dr/dz of the wall.
    let slope: f64 = wall
        .iter()
        .map(|s| (-s.normal_axial / s.normal_radial.abs()).clamp(-2.0, 2.0) * s.weight)
        .sum::<f64>()
        / wall_weight;
    DirectionEvidence { score: 0.2 * slope.clamp(-1.0, 1.0), cue: "opening: the wall widens towards the rim".into() }
}

/// The lip: at one end of the sherd's height, surface whose normals meet the axis (it is
/// turned, not broken: a fracture's normals miss the axis) and point away from the sherd
/// along the axis. A rim has one at the top; when one end has three times the other's lip
/// area, that end is the rim.
fn lip_evidence(lines: &NormalLines, axis: &Axis, tolerance_mm: f64) -> Option<f64> {
    let d = axis.direction.into_inner();
    let heights: Vec<f64> = lines.points.iter().map(|p| (p - axis.point).dot(&d)).collect();
    let (low, high) = heights.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), h| (lo.min(*h), hi.max(*h)));
    let zone = 0.15 * (high - low);
    let total: f64 = lines.weights.iter().sum();
    let (mut top, mut bottom) = (0.0, 0.0);
    for i in 0..lines.len() {
        let axial = lines.directions[i].dot(&d);
        if axial.abs() < 0.5 {
            continue;
        }
        if super::surfaces::normal_line_distance(axis, &lines.points[i], &lines.directions[i]) > tolerance_mm {
            continue;
        }
        if axial > 0.0 && heights[i] > high - zone {
            top += lines.weights[i];
        } else if axial < 0.0 && heights[i] < low + zone {
            bottom += lines.weights[i];
        }
    }
    if top + bottom < 0.005 * total {
        return None;
    }
    if top >= 3.0 * bottom {
        Some(0.6)
    } else if bottom >= 3.0 * top {
        Some(-0.6)
    } else {
        None
    }
}

fn weighted_quantile(values: impl Iterator<Item = (f64, f64)>, quantile: f64) -> f64 {
    let mut pairs: Vec<(f64, f64)> = values.collect();
    if pairs.is_empty() {
        return f64::NAN;
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let target = pairs.iter().map(|p| p.1).sum::<f64>() * quantile;
    let mut running = 0.0;
    for (v, w) in &pairs {
        running += w;
        if running >= target {
            return *v;
        }
    }
    pairs[pairs.len() - 1].0
}

fn weighted_median(values: impl Iterator<Item = (f64, f64)>) -> f64 {
    weighted_quantile(values, 0.5)
}
