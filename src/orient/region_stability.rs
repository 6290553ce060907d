//! Leave-one-region-out stability of the axis: the Halíř/MM fit ([`super::halir`],
//! Wilczek et al. 2018, section 2.2.2, equation (1)) made again with each spatial region
//! of the sherd left out in turn.
//!
//! Why: when the normals give a wrong axis, the error is usually carried by one region of
//! the sherd (a stretch of decoration, a deformed or badly scanned patch, a fracture face
//! the opposite-normal test let through, the turn of a carination): the other regions
//! agree with each other and not with it. The fit's own standard error cannot see this,
//! since it assumes independent normals, while a region's normals are correlated and
//! pull together. If leaving out any one region turns the axis by more than a few
//! degrees, the axis rests on that region alone and is not a confident answer.
//!
//! The regions are cells of the sherd unrolled about the estimated axis: equal-count
//! slices of the angle about the axis, each cut into equal-count bands of height, with
//! the numbers of slices and bands chosen so that the cells are about as long along the
//! circumference as they are high.

use rayon::prelude::*;

use super::halir::{HalirFit, HalirOptions, refined_direction};
use super::line_complex::CenteredLines;
use crate::mesh::Vector;
use crate::statistics::{equal_count_bins, upper_median};

/// Number of regions the sherd is cut into: enough that one region is a local part of the
/// sherd (a sixth of it), few enough that each region left out still leaves most of the
/// sherd to fit and that the check costs a handful of refinements.
pub const REGION_COUNT: usize = 6;

/// Largest turn of the axis, degrees, when one region is left out, before the axis is
/// flagged. Read from the synthetic corpus (`cargo run --release --example orient_accuracy
/// 10 30 FILE.csv`, column `region_turn`): on the fragments that the other tests let
/// through and that are right (mean point distance under 4 mm) the turn is a median
/// 0.7 degrees, 3.1 at the 95th percentile and 4.3 at the 98th; a limit of 3 to 8 degrees
/// trades 68% to 65% of the fragments flagged against 2.3% to 3.7% wrong and not flagged.
/// 6.5 flags the wrong axes held by one region (turns of 6 to 80 degrees) while leaving
/// the right ones of small pieces alone (their turns reach 4-5 degrees).
pub const MAX_REGION_TURN_DEG: f64 = 6.5;

/// Cosine of the angle (1 degree) within which two refined candidates are one start for
/// the refits.
const SAME_START_COS: f64 = 0.999_847_695;

/// What leaving out one region at a time did to the axis.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RegionStability {
    /// Number of regions the lines were cut into.
    pub region_count: usize,
    /// Largest angle between the axis of all lines and the axis with one region left
    /// out, degrees.
    pub largest_turn_deg: f64,
    /// The region whose absence turned the axis most, `0..region_count`.
    pub decisive_region: usize,
    /// The part of that largest turn in the sherd's meridian plane (the plane of the axis
    /// and the sherd's centre), degrees: the tilt that slants the profile, which a body
    /// sherd fixes only at second order in its arc. The rest turns the axis about the
    /// sherd's radial direction (and would slant its rills).
    pub largest_turn_in_meridian_deg: f64,
}

/// The region (`0..count`) of every line: cells of the sherd unrolled about the axis
/// `(point, direction)` (centred frame), equal-count slices of angle then equal-count
/// bands of height within each slice.
pub fn region_labels(
    lines: &CenteredLines,
    point: &Vector,
    direction: &Vector,
    count: usize,
) -> Vec<usize> {
    let n = lines.len();
    if n == 0 || count <= 1 {
        return vec![0; n];
    }
    let direction = direction.normalize();
    let (e1, e2) = reference_frame(point, &direction);
    let (mut angles, mut heights, mut radii) = (
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
    );
    for p in &lines.points {
        let q = p - point;
        let (x, y) = (q.dot(&e1), q.dot(&e2));
        angles.push(y.atan2(x));
        heights.push(q.dot(&direction));
        radii.push(x.hypot(y));
    }
    let arc_length = (spread(&angles) * upper_median(&radii)).max(1e-12);
    let height = spread(&heights).max(1e-12);
    // The factorisation of `count` into slices x bands whose cells are closest to square.
    let slices = (1..=count)
        .filter(|s| count % s == 0)
        .min_by(|a, b| {
            let squareness = |s: usize| {
                ((arc_length / s as f64) / (height / (count / s) as f64))
                    .ln()
                    .abs()
            };
            squareness(*a).total_cmp(&squareness(*b))
        })
        .unwrap_or(1);
    let bands = count / slices;
    let slice_of = equal_count_bins(&angles, &(0..n).collect::<Vec<_>>(), slices);
    let mut labels = vec![0; n];
    for slice in 0..slices {
        let members: Vec<usize> = (0..n).filter(|&i| slice_of[i] == slice).collect();
        let band_of = equal_count_bins(&heights, &members, bands);
        for &i in &members {
            labels[i] = slice * bands + band_of[i];
        }
    }
    labels
}

/// Unit vectors perpendicular to `direction`, the first towards the lines' centroid (the
/// origin of the centred frame), so that the angles of the sherd do not wrap around.
fn reference_frame(point: &Vector, direction: &Vector) -> (Vector, Vector) {
    let to_centroid = -point;
    let mut e1 = to_centroid - direction * to_centroid.dot(direction);
    if e1.norm() < 1e-12 {
        e1 = super::halir::perpendicular_frame(direction).0;
    }
    let e1 = e1.normalize();
    (e1, direction.cross(&e1))
}

fn spread(values: &[f64]) -> f64 {
    let (low, high) = values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
            (l.min(*v), h.max(*v))
        });
    high - low
}

/// The fit made again with each of [`REGION_COUNT`] regions left out (its lines weighted
/// 0), from the directions `fit` compared (its winner and its competitors, so that a
/// competitor the left-out region was holding down can win), with the same options.
pub fn leave_one_region_out(
    lines: &CenteredLines,
    fit: &HalirFit,
    options: &HalirOptions,
) -> RegionStability {
    let labels = region_labels(lines, &fit.point, &fit.direction, REGION_COUNT);
    // Candidates that converged to one direction would give one refit: start from the
    // cheapest of each (the alternatives come cheapest first).
    let mut starts: Vec<Vector> = Vec::new();
    for (direction, _) in &fit.alternatives {
        let close = |kept: &Vector| kept.normalize().dot(&direction.normalize()).abs() >= SAME_START_COS;
        if !starts.iter().any(close) {
            starts.push(*direction);
        }
    }
    if starts.is_empty() {
        starts.push(fit.direction);
    }
    let direction = fit.direction.normalize();
    let centre = lines.points.iter().fold(Vector::zeros(), |sum, p| sum + p) / lines.len().max(1) as f64;
    let offset = centre - fit.point;
    let radial = (offset - direction * direction.dot(&offset)).try_normalize(1e-12).unwrap_or_else(|| direction.cross(&Vector::x()));
    // (turn, its part in the meridian plane), degrees.
    let turns: Vec<(f64, f64)> = (0..REGION_COUNT)
        .into_par_iter()
        .map(|left_out| {
            let mut rest = lines.clone();
            for (weight, label) in rest.weights.iter_mut().zip(&labels) {
                if *label == left_out {
                    *weight = 0.0;
                }
            }
            match refined_direction(&rest, &starts, options) {
                Some(refit) => {
                    let refit = refit.normalize() * refit.normalize().dot(&direction).signum();
                    let turn = refit.dot(&direction).min(1.0).acos().to_degrees();
                    (turn, meridian_tilt_deg(&radial, &refit))
                }
                None => (90.0, 90.0),
            }
        })
        .collect();
    let (decisive_region, &(largest_turn_deg, largest_turn_in_meridian_deg)) = turns
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.0.total_cmp(&b.1.0))
        .unwrap_or((0, &(0.0, 0.0)));
    RegionStability {
        region_count: REGION_COUNT,
        largest_turn_deg,
        decisive_region,
        largest_turn_in_meridian_deg,
    }
}

/// The tilt of the unit direction `refit` towards the unit `radial` direction (the sherd's
/// centre seen from the axis, perpendicular to it), degrees: how far it leans in the
/// meridian plane, whatever it turned about `radial`.
fn meridian_tilt_deg(radial: &Vector, refit: &Vector) -> f64 {
    refit.dot(radial).clamp(-1.0, 1.0).asin().to_degrees().abs()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::orient::halir::refine_candidates;
    use crate::mesh::Point;
    use crate::orient::normal_lines::NormalLines;

    /// Normal lines of a cone patch about the z axis: every line meets the axis.
    fn cone_lines(tilt: f64) -> CenteredLines {
        let mut lines = NormalLines::default();
        for i in 0..40 {
            for j in 0..20 {
                let angle = -0.6 + 1.2 * i as f64 / 39.0;
                let height = 30.0 * j as f64 / 19.0;
                let radius = 60.0 + 0.3 * height;
                let point = Point::new(radius * angle.cos(), radius * angle.sin(), height);
                // Deterministic noise of about 1 degree, as a smoothed scan's normals have.
                let noise = Vector::new(
                    (12.9898 * (i * 20 + j) as f64).sin(),
                    (78.233 * (i * 20 + j) as f64).sin(),
                    (37.719 * (i * 20 + j) as f64).sin(),
                );
                let mut normal = (Vector::new(angle.cos(), angle.sin(), -0.3).normalize()
                    + noise * 0.02)
                    .normalize();
                // One corner of the patch whose normals turn sideways together and miss the axis.
                if angle > 0.3 && height > 15.0 {
                    normal =
                        (normal + Vector::new(-angle.sin(), angle.cos(), 0.0) * tilt).normalize();
                }
                lines.push(point, normal, 1.0, lines.len());
            }
        }
        CenteredLines::new(&lines)
    }

    #[test]
    fn regions_have_equal_counts() {
        let lines = cone_lines(0.0);
        let (point, direction) = lines.from_scan_frame(&crate::orient::Axis::z());
        let labels = region_labels(&lines, &point, &direction, REGION_COUNT);
        for region in 0..REGION_COUNT {
            let count = labels.iter().filter(|l| **l == region).count();
            assert!(
                (count as f64 - 800.0 / 6.0).abs() <= 2.0,
                "region {region}: {count} lines"
            );
        }
    }

    #[test]
    fn a_clean_cone_is_stable_and_a_region_pulling_apart_is_seen() {
        let options = HalirOptions::default();
        let turn = |tilt: f64| {
            let lines = cone_lines(tilt);
            let (_, direction) = lines.from_scan_frame(&crate::orient::Axis::z());
            let fit = refine_candidates(&lines, &[direction], &options).expect("fit");
            leave_one_region_out(&lines, &fit, &options).largest_turn_deg
        };
        let clean = turn(0.0);
        let tilted = turn(0.05);
        assert!(clean < 1.0, "clean cone turned by {clean} deg");
        assert!(
            tilted > MAX_REGION_TURN_DEG,
            "a region pulling the axis 3 degrees sideways turned it by only {tilted} deg"
        );
    }

    #[test]
    fn the_turn_is_split_into_the_meridian_tilt_and_the_rest() {
        let options = HalirOptions::default();
        for tilt in [0.0, 0.05] {
            let lines = cone_lines(tilt);
            let (_, direction) = lines.from_scan_frame(&crate::orient::Axis::z());
            let fit = refine_candidates(&lines, &[direction], &options).expect("fit");
            let stability = leave_one_region_out(&lines, &fit, &options);
            assert!(stability.largest_turn_in_meridian_deg <= stability.largest_turn_deg + 1e-9);
            // A body patch's loose tilt is the meridian one: the corner pulling sideways
            // (8.3 deg) moves the axis in the meridian plane by 8.1 deg.
            if tilt > 0.0 {
                assert!(stability.largest_turn_in_meridian_deg > 0.8 * stability.largest_turn_deg, "{stability:?}");
            }
        }
        // The split itself, on known turns of the z axis, the sherd's centre along +x.
        let radial = Vector::x();
        let turned = |about: Vector, degrees: f64| {
            nalgebra::UnitQuaternion::from_axis_angle(&nalgebra::Unit::new_normalize(about), degrees.to_radians()) * Vector::z()
        };
        assert!((meridian_tilt_deg(&radial, &turned(Vector::y(), 5.0)) - 5.0).abs() < 1e-9);
        assert!(meridian_tilt_deg(&radial, &turned(Vector::x(), 5.0)) < 1e-9);
    }
}
