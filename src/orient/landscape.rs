//! The verdict of the whole-sphere search ([`super::revolution_search`]): whether its
//! landscape picks out one axis, judged by the fragment itself rather than by thresholds
//! read off a corpus. The fragment is cut into blocks; a competing axis (the next valley,
//! or the best axis moved by what makes an axis wrong) is as good as the best one unless
//! the best fits better in block after block: the paired differences of the blocks' mean
//! losses are tested against their own spread (a one-sided t statistic). The scan's noise
//! and the vessel's deformation enter through that spread, whatever their size.

use crate::axis::Axis;
use super::revolution_search::{point_losses, Landscape, RevolutionSamples};
use crate::mesh::{Point, Vector};
use crate::statistics::principal_axes;

/// Blocks along each of the fragment's two longest principal directions.
const BLOCKS_PER_SIDE: usize = 4;
/// Least share of the points a block must hold to count (a corner of the grid the
/// fragment barely reaches is noise).
const MIN_BLOCK_SHARE: f64 = 0.02;

/// How much better the best axis fits than a competitor, block by block.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Separation {
    /// The mean over the blocks of the competitor's mean loss minus the best's.
    pub mean_difference: f64,
    /// That mean over its standard error (infinite when every block agrees exactly).
    pub t_statistic: f64,
    /// Blocks compared.
    pub blocks: usize,
}

/// The block of each sample: a grid over the fragment's two longest principal directions.
pub fn sample_blocks(samples: &RevolutionSamples) -> Vec<Option<usize>> {
    let points: Vec<Point> = samples.points.iter().map(|p| Point::from(*p)).collect();
    let Some((_, _, axes)) = principal_axes(points.iter().zip(samples.weights.iter().copied())) else {
        return vec![None; samples.len()];
    };
    let (u, v): (Vector, Vector) = (axes[2], axes[1]);
    let coordinates: Vec<(f64, f64)> = samples.points.iter().map(|p| (p.dot(&u), p.dot(&v))).collect();
    let range = |pick: fn(&(f64, f64)) -> f64| {
        coordinates.iter().map(pick).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| (lo.min(x), hi.max(x)))
    };
    let ((u_low, u_high), (v_low, v_high)) = (range(|c| c.0), range(|c| c.1));
    let cell = |x: f64, low: f64, high: f64| (((x - low) / (high - low).max(1e-9) * BLOCKS_PER_SIDE as f64) as usize).min(BLOCKS_PER_SIDE - 1);
    let indices: Vec<usize> = coordinates.iter().map(|&(a, b)| cell(a, u_low, u_high) * BLOCKS_PER_SIDE + cell(b, v_low, v_high)).collect();
    let mut counts = [0usize; BLOCKS_PER_SIDE * BLOCKS_PER_SIDE];
    for &i in &indices {
        counts[i] += 1;
    }
    let least = (MIN_BLOCK_SHARE * samples.len() as f64).ceil() as usize;
    indices.into_iter().map(|i| (counts[i] >= least.max(1)).then_some(i)).collect()
}

/// How much better `best` fits the samples than `competitor`, block by block.
pub fn separation(samples: &RevolutionSamples, blocks: &[Option<usize>], best: &Axis, competitor: &Axis, loss_scale_mm: f64) -> Separation {
    separation_from(samples, blocks, &point_losses(samples, best, loss_scale_mm), competitor, loss_scale_mm)
}

/// [`separation`] with the best axis's point losses computed once by the caller.
fn separation_from(samples: &RevolutionSamples, blocks: &[Option<usize>], best_losses: &[f64], competitor: &Axis, loss_scale_mm: f64) -> Separation {
    let other_losses = point_losses(samples, competitor, loss_scale_mm);
    let mut sums = vec![(0.0, 0.0); BLOCKS_PER_SIDE * BLOCKS_PER_SIDE];
    for (k, block) in blocks.iter().enumerate() {
        if let Some(b) = block {
            let w = samples.weights[k];
            sums[*b].0 += w * (other_losses[k] - best_losses[k]);
            sums[*b].1 += w;
        }
    }
    let differences: Vec<f64> = sums.iter().filter(|(_, w)| *w > 0.0).map(|(d, w)| d / w).collect();
    let n = differences.len();
    if n < 2 {
        return Separation { mean_difference: f64::NAN, t_statistic: f64::NAN, blocks: n };
    }
    let mean = differences.iter().sum::<f64>() / n as f64;
    let variance = differences.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
    let error = (variance / n as f64).sqrt();
    let t_statistic = if error > 0.0 { mean / error } else if mean > 0.0 { f64::INFINITY } else { 0.0 };
    Separation { mean_difference: mean, t_statistic, blocks: n }
}

/// A valley of the landscape other than the best: its axis, how far its line turns from
/// the best's, and how much better the best fits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CompetingValley {
    /// The valley's axis.
    pub axis: Axis,
    /// Angle between its line and the best valley's, degrees.
    pub angle_deg: f64,
    /// How much better the best valley's axis fits, block by block.
    pub separation: Separation,
}

/// The competitors of the landscape's best valley: the other valleys farther from it than
/// `min_angle_deg` (nearer ones lie in the reach of the refinement), best first, with
/// their separation from the best.
pub fn competing_valleys(landscape: &Landscape, blocks: &[Option<usize>], min_angle_deg: f64) -> Vec<CompetingValley> {
    let Some(best) = landscape.valleys.first() else { return Vec::new() };
    let best_axis = best.axis(&landscape.samples);
    landscape
        .valleys
        .iter()
        .skip(1)
        .filter_map(|valley| {
            let axis = valley.axis(&landscape.samples);
            let angle_deg = axis.line_angle_to_deg(&best_axis);
            (angle_deg > min_angle_deg).then(|| CompetingValley {
                axis,
                angle_deg,
                separation: separation(&landscape.samples, blocks, &best_axis, &axis, landscape.loss_scale_mm),
            })
        })
        .collect()
}

/// The least rise of the mean loss when the best axis moves `shift_mm` at the fragment's
/// centroid in any of eight horizontal directions, relative to the best's own mean loss: a
/// piece whose loss barely rises however its axis is moved (a flat piece, a floor without
/// its foot) does not fix the axis's position.
pub fn position_hold(samples: &RevolutionSamples, best: &Axis, shift_mm: f64, loss_scale_mm: f64) -> f64 {
    let d = best.direction.into_inner();
    let (e1, e2) = crate::axis::perpendicular_frame(&d);
    let weighted_mean = |losses: Vec<f64>| {
        let total: f64 = samples.weights.iter().sum();
        losses.iter().zip(&samples.weights).map(|(l, w)| l * w).sum::<f64>() / total.max(1e-300)
    };
    let at_best = weighted_mean(point_losses(samples, best, loss_scale_mm)).max(1e-12);
    (0..8)
        .map(|k| {
            let angle = k as f64 * std::f64::consts::FRAC_PI_4;
            let offset = (e1 * angle.cos() + e2 * angle.sin()) * shift_mm;
            let moved = Axis::new(best.point + offset, d);
            (weighted_mean(point_losses(samples, &moved, loss_scale_mm)) - at_best) / at_best
        })
        .fold(f64::INFINITY, f64::min)
}

/// The t statistic at which a moved axis counts as fitting worse than the best one: one
/// sided, about 5% with the 10-16 blocks of [`sample_blocks`].
pub const UNCERTAINTY_T: f64 = 2.0;

/// The moves, degrees or millimetres, at which [`valley_width`] compares a moved axis:
/// doubling, so that a bound is found to within a factor of two in eight comparisons.
const PROBE_STEPS: [f64; 9] = [0.125, 0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0];

/// How far the best axis can turn (degrees) and move across itself (millimetres) before
/// it fits the fragment worse, block by block, at [`UNCERTAINTY_T`]: the width of its
/// valley in units the fragment's own noise and deformation set. The turn is probed in
/// four directions with the position solved anew for each, the move in eight; the widest
/// direction gives the bound, interpolated between the doubling steps. Where no probe up
/// to 32 degrees (millimetres) separates, 64: the valley is at least that wide.
pub fn valley_width(samples: &RevolutionSamples, blocks: &[Option<usize>], best: &Axis, loss_scale_mm: f64) -> (f64, f64) {
    let d = best.direction.into_inner();
    let (e1, e2) = crate::axis::perpendicular_frame(&d);
    let anchor = best.closest_point(&samples.centroid);
    let best_losses = point_losses(samples, best, loss_scale_mm);
    let bound = |separates: &dyn Fn(f64) -> f64| {
        // The first step whose t reaches the limit, interpolated in the logarithm of the
        // step between it and the one before.
        let mut previous: Option<(f64, f64)> = None;
        for &step in &PROBE_STEPS {
            let t = separates(step);
            if t >= UNCERTAINTY_T {
                return match previous {
                    Some((step_before, t_before)) if t > t_before => {
                        let share = ((UNCERTAINTY_T - t_before) / (t - t_before)).clamp(0.0, 1.0);
                        step_before * (step / step_before).powf(share)
                    }
                    _ => step,
                };
            }
            previous = Some((step, if t.is_finite() { t } else { 0.0 }));
        }
        2.0 * PROBE_STEPS[PROBE_STEPS.len() - 1]
    };
    let turn_deg = (0..4)
        .map(|k| {
            let angle = k as f64 * std::f64::consts::FRAC_PI_2;
            let across = e1 * angle.cos() + e2 * angle.sin();
            bound(&|step_deg: f64| {
                let turned = (d * step_deg.to_radians().cos() + across * step_deg.to_radians().sin()).normalize();
                let fit = super::revolution_search::fit_direction(samples, &turned, loss_scale_mm);
                let moved = Axis::new(samples.centroid + fit.centre, turned);
                separation_from(samples, blocks, &best_losses, &moved, loss_scale_mm).t_statistic
            })
        })
        .fold(0.0, f64::max);
    let shift_mm = (0..8)
        .map(|k| {
            let angle = k as f64 * std::f64::consts::FRAC_PI_4;
            let across = e1 * angle.cos() + e2 * angle.sin();
            bound(&|step_mm: f64| separation_from(samples, blocks, &best_losses, &Axis::new(anchor + across * step_mm, d), loss_scale_mm).t_statistic)
        })
        .fold(0.0, f64::max);
    (turn_deg, shift_mm)
}
