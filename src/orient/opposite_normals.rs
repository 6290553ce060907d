//! Elimination of vertices that are not on the surface of revolution (Wilczek et al. 2018,
//! section 2.2.2, Fig. 3a): a vertex of the inner or outer skin has, straight through the
//! wall, a partner on the other skin whose normal points the opposite way; a vertex of a
//! fracture face or of a plastic decoration usually has not.
//!
//! The probability test: the angle `θ` between `n_i` and the reversed normal of the hit
//! is modelled as the deviation of a Fisher (von Mises-Fisher) direction around the
//! antiparallel one, whose concentration `κ` is estimated from the data (the median
//! deviation of all pairs, since most pairs of a sherd are true skin pairs). The
//! probability of a deviation at least as large as observed is
//! `p = exp(-κ (1 - cos θ))`; a vertex is kept when antiparallelism is not rejected at the
//! confidence level (0.95 in the paper: kept when `p > 1 - 0.95`).

use rayon::prelude::*;

use super::normal_lines::NormalLines;
use crate::mesh::{Point, Vector};

/// What the filter did.
#[derive(Clone, Debug)]
pub struct OppositeFilter {
    /// Per line: kept (on the surface of revolution) or not.
    pub keep: Vec<bool>,
    /// Lines kept.
    pub kept_count: usize,
    /// The median deviation from antiparallel, degrees (the noise level the test used).
    pub median_deviation_deg: f64,
    /// The median distance to the opposite skin, millimetres: the wall thickness.
    pub median_thickness_mm: f64,
}

/// Runs the test on every line. `cast(origin, direction)` returns the unit normal of the
/// first surface hit and its distance, or `None`; the ray starts just inside the surface
/// and goes against the normal, into the wall.
pub fn filter_opposite_normals<F>(lines: &NormalLines, confidence: f64, cast: F) -> OppositeFilter
where
    F: Fn(&Point, &Vector) -> Option<(Vector, f64)> + Sync,
{
    let hits: Vec<Option<(f64, f64)>> = (0..lines.len())
        .into_par_iter()
        .map(|i| {
            let n = lines.directions[i];
            let origin = lines.points[i];
            cast(&origin, &-n).map(|(hit_normal, distance)| {
                let cosine = (-hit_normal.normalize()).dot(&n).clamp(-1.0, 1.0);
                (cosine, distance)
            })
        })
        .collect();
    let mut deviations: Vec<f64> = hits.iter().flatten().map(|(c, _)| c.acos()).collect();
    let mut distances: Vec<f64> = hits.iter().flatten().map(|(_, d)| *d).collect();
    let hit_count = deviations.len();
    if hit_count == 0 {
        return OppositeFilter {
            keep: vec![false; lines.len()],
            kept_count: 0,
            median_deviation_deg: f64::NAN,
            median_thickness_mm: f64::NAN,
        };
    }
    let median = |values: &mut Vec<f64>| {
        values.sort_unstable_by(f64::total_cmp);
        values[values.len() / 2]
    };
    let median_deviation = median(&mut deviations);
    let median_thickness = median(&mut distances);
    // The wall tapers and the scan is noisy: a floor of 2 degrees keeps the test from
    // rejecting good pairs on an ideal surface, a ceiling of 20 from accepting anything.
    let typical = median_deviation.clamp(2f64.to_radians(), 20f64.to_radians());
    let kappa = std::f64::consts::LN_2 / (1.0 - typical.cos());
    let significance = 1.0 - confidence;
    // A ray through a fracture face runs along the wall and meets the far side well
    // beyond the wall thickness.
    let thickness_bound = 3.0 * median_thickness;
    let keep: Vec<bool> = hits
        .iter()
        .map(|hit| match hit {
            Some((cosine, distance)) => {
                let probability = (-kappa * (1.0 - cosine)).exp();
                probability > significance && *distance <= thickness_bound
            }
            None => false,
        })
        .collect();
    let kept_count = keep.iter().filter(|k| **k).count();
    OppositeFilter {
        keep,
        kept_count,
        median_deviation_deg: median_deviation.to_degrees(),
        median_thickness_mm: median_thickness,
    }
}
