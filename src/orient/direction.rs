//! Which way the axis points: from the base to the rim. The normals fix the axis as a
//! line; its sense comes from the shape of the vessel seen in the rz half-plane:
//! - a floor: surface facing along the axis that reaches in towards the axis from the
//!   wall is a base, and the wall rises from it;
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
/// (`lines` with `on_surface[i]`).
pub fn direction_evidence(lines: &NormalLines, on_surface: &[bool], axis: &Axis) -> DirectionEvidence {
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
