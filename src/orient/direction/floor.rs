//! The floor cue, the strongest of the sense cues: a base is a flat surface facing along
//! the axis that reaches in from the wall, and the side the wall rises on is up.

use super::{Sample, MIN_WALL_SHARE};
use crate::statistics::{weighted_median, weighted_quantile};

/// Share of the surface a flat part must have to decide the sense as a floor.
pub(super) const MIN_FLOOR_SHARE: f64 = 0.05;
/// Share of the surface a flat part needs to veto a level edge that says the other way: a
/// base whose wall rises from a narrow strip of underside otherwise reads its level foot
/// as a rim (`docs/calibration.md`).
pub(super) const MIN_SMALL_FLOOR_SHARE: f64 = 0.02;
/// A floor reaches inside this fraction of the wall's median radius (a quarter of its
/// flat area does): a rim's flat top lies at the wall's radius.
pub(super) const FLOOR_INNER_RADIUS_RATIO: f64 = 0.8;
/// The same for a small floor, which only vetoes: the strip of underside beside a foot
/// lies closer to the wall.
pub(super) const SMALL_FLOOR_INNER_RADIUS_RATIO: f64 = 0.9;

/// The floor cue on the lines of the surface of revolution: `Some(sense)` when a flat
/// surface (normal within [`FLOOR_NORMAL_DEG`] of the axis) of at least `min_share` of the
/// piece reaches inside `max_inner_radius_ratio` of the median radius of the rest of the
/// piece (normals farther than [`RISE_NORMAL_DEG`] from the axis: a wall, or a plate's low
/// rise), and the rest reaches past the floor's two faces on one side more than on the
/// other: the wall rises from the floor. The rest need not be steep: a dish's floor turns into a wall a few degrees from
/// flat, which the floor's own normals already tell from it.
pub(super) fn floor_cue(samples: &[Sample], min_share: f64, max_inner_radius_ratio: f64) -> Option<f64> {
    let total: f64 = samples.iter().map(|s| s.weight).sum();
    let flat_limit = FLOOR_NORMAL_DEG.to_radians().cos();
    let rise_limit = RISE_NORMAL_DEG.to_radians().cos();
    let rest: Vec<&Sample> = samples.iter().filter(|s| s.normal_axial.abs() <= rise_limit).collect();
    let flat: Vec<&Sample> = samples.iter().filter(|s| s.normal_axial.abs() > flat_limit).collect();
    let rest_weight: f64 = rest.iter().map(|s| s.weight).sum();
    let flat_weight: f64 = flat.iter().map(|s| s.weight).sum();
    if !(flat_weight > min_share * total && rest_weight > MIN_WALL_SHARE * total) {
        return None;
    }
    let rest_radius = weighted_median(rest.iter().map(|s| (s.radius, s.weight)));
    let flat_radius = weighted_median(flat.iter().map(|s| (s.radius, s.weight)));
    let flat_inner_radius = weighted_quantile(flat.iter().map(|s| (s.radius, s.weight)), 0.25);
    if flat_inner_radius >= max_inner_radius_ratio * rest_radius || flat_radius >= rest_radius {
        return None;
    }
    // The wall rises from both faces of the floor: its outer skin from the underside, its
    // inner skin from the floor's top, so the rest reaches past the floor's farther face
    // on the rim's side and not on the other. Medians mislead where the piece holds only a
    // stub of wall: the floor's two faces, weighted by what the scan kept of each, put the
    // floor's median height on either face.
    let flat_height = |fraction: f64| weighted_quantile(flat.iter().map(|s| (s.height, s.weight)), fraction);
    let rest_height = |fraction: f64| weighted_quantile(rest.iter().map(|s| (s.height, s.weight)), fraction);
    let reach_up = rest_height(1.0 - FLOOR_EXTREME_QUANTILE) - flat_height(1.0 - FLOOR_EXTREME_QUANTILE);
    let reach_down = flat_height(FLOOR_EXTREME_QUANTILE) - rest_height(FLOOR_EXTREME_QUANTILE);
    let rise = reach_up - reach_down;
    (rise.abs() >= MIN_FLOOR_RISE_MM).then(|| rise.signum())
}

/// A floor's normals keep within this angle of the axis, degrees (a flat base, a slightly
/// domed or sagging floor).
const FLOOR_NORMAL_DEG: f64 = 8.0;
/// The rest of a base piece turns farther than this from the axis, degrees: a dish's
/// floor turns into a wall rising a few degrees from flat.
const RISE_NORMAL_DEG: f64 = FLOOR_NORMAL_DEG;
/// The rest of the piece must reach at least this much farther past the floor on one side
/// than on the other, along the axis, for the floor to tell which way is up, mm: several
/// times a smoothed scan's noise, in quantiles over hundreds of points.
const MIN_FLOOR_RISE_MM: f64 = 0.25;
/// The quantile of the heights that stands for a surface's lowest (and, from the top, its
/// highest) reach: clear of single points off the scan, within the floor's faces.
const FLOOR_EXTREME_QUANTILE: f64 = 0.1;

#[cfg(test)]
mod tests {
    use super::*;

    /// A base piece with only a stub of wall: the floor's top face outweighs its underside
    /// (or the other way), which puts the floor's median height on either face; the wall's
    /// reach past the faces still says which way it rises, and the reversed axis reads the
    /// other way.
    #[test]
    fn a_stub_of_wall_tells_the_floor_whichever_face_weighs_more() {
        let sample = |radius: f64, height: f64, normal_axial: f64, weight: f64| Sample {
            radius,
            height,
            normal_radial: (1.0 - normal_axial * normal_axial).sqrt(),
            normal_axial,
            weight,
        };
        for (top_weight, under_weight) in [(3.0, 1.0), (1.0, 3.0)] {
            let mut samples = Vec::new();
            for i in 0..200 {
                let radius = 10.0 + 0.2 * i as f64;
                samples.push(sample(radius, 4.0, 1.0, top_weight));
                samples.push(sample(radius, 0.0, -1.0, under_weight));
            }
            // The wall's stub at the floor's edge: the outer skin from the underside, the
            // inner skin from the top, both ending 1.5 mm above the top.
            for i in 0..30 {
                samples.push(sample(55.0, 5.5 * i as f64 / 29.0, 0.0, 1.0));
                samples.push(sample(50.0, 4.0 + 1.5 * i as f64 / 29.0, 0.0, 1.0));
            }
            let up = floor_cue(&samples, MIN_FLOOR_SHARE, FLOOR_INNER_RADIUS_RATIO);
            for s in &mut samples {
                s.height = -s.height;
                s.normal_axial = -s.normal_axial;
            }
            let down = floor_cue(&samples, MIN_FLOOR_SHARE, FLOOR_INNER_RADIUS_RATIO);
            assert_eq!((up, down), (Some(1.0), Some(-1.0)), "faces weighted {top_weight} (top) and {under_weight} (underside)");
        }
    }
}
