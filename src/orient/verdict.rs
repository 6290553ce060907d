//! Honest failure: whether the normals determine the axis, decided from the data (the
//! spread of the normals, the conditioning of the line complex, the precision of the fit,
//! its residuals and its competitors), never from the size of the sherd alone. The
//! thresholds are calibrated on the synthetic corpus (`examples/orient_accuracy.rs`
//! prints the figures they were read from).

use nalgebra::{Matrix3, SymmetricEigen};
use serde::{Deserialize, Serialize};

use crate::axis::Axis;
use super::halir::HalirFit;
use crate::statistics::weighted_median_abs;
use super::normal_lines::NormalLines;
use crate::mesh::Point;
use super::line_complex::CenteredLines;
use super::OrientReport;

/// Whether an orientation can be used.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Verdict {
    /// The axis is determined by the data.
    Oriented,
    /// The data do not determine an axis: give three points on a horizontal feature.
    NeedsManualOrientation {
        /// Why, in the archaeologist's terms, with the figure that decided.
        reason: String,
    },
    /// The axis line is determined but not which way it points (base to rim): the sense
    /// cues are weak or disagree. The line can be refined and measured (radii and the
    /// sector do not depend on the sense); a drawing would be upside down as often as not.
    SenseUncertain {
        /// Which cues were weak or disagreed, with their figures.
        reason: String,
    },
}

impl Verdict {
    /// True for [`Verdict::Oriented`].
    pub fn is_oriented(&self) -> bool {
        matches!(self, Verdict::Oriented)
    }

    /// True when the axis line can be used: [`Verdict::Oriented`] or
    /// [`Verdict::SenseUncertain`].
    pub fn has_axis_line(&self) -> bool {
        matches!(self, Verdict::Oriented | Verdict::SenseUncertain { .. })
    }

    /// Why the verdict is not [`Verdict::Oriented`], if it is not.
    pub fn reason(&self) -> Option<&str> {
        match self {
            Verdict::Oriented => None,
            Verdict::NeedsManualOrientation { reason } | Verdict::SenseUncertain { reason } => Some(reason),
        }
    }
}

/// The limits beyond which an orientation is flagged.
#[derive(Clone, Copy, Debug)]
pub struct VerdictThresholds {
    /// Fewest lines on the surface of revolution.
    pub min_lines: usize,
    /// Smallest second/first eigenvalue of the normals' scatter (flat piece below).
    pub min_normal_spread: f64,
    /// Largest `λ1/λ2` of the line complex (near-spherical piece above).
    pub max_concurrency_ratio: f64,
    /// Smallest ratio of the sphere's residual angle to the axis's (near-spherical piece
    /// below: a sphere explains the normals about as well as the axis). 3 rather than 1:
    /// on the synthetic corpus the pieces with ratios 1-3 (lower bodies and bases of
    /// rounded bowls) were wrong by over 4 mm in 9 cases of 14.
    pub min_sphere_to_axis_ratio: f64,
    /// Largest calibrated direction uncertainty, degrees.
    pub max_angle_uncertainty_deg: f64,
    /// Largest calibrated position uncertainty, millimetres.
    pub max_position_uncertainty_mm: f64,
    /// Largest typical angle by which the normals miss the axis, degrees. The right axes
    /// of both synthetic corpora (`examples/orient_accuracy.rs` and the 34-fragment one of
    /// `examples/refine_accuracy.rs`) stay under 1.4 degrees and A011's is 0.8; two small
    /// rim pieces (136 and 174 vertices) whose axis was put through their lip, 73 degrees
    /// off, gave 2.8 and 3.6.
    pub max_residual_angle_deg: f64,
    /// Smallest fraction of lines the M-step keeps.
    pub min_inlier_fraction: f64,
    /// Smallest curvature radius of the surface where the axis passes through the sherd,
    /// millimetres (see [`axis_crossing_curvature_radius_mm`]). On the synthetic corpus the
    /// right axes that cross their sherd (bases) give 17-515 mm, the wrong ones 0.2-6.4 mm;
    /// a floor curved tighter than 10 mm at its centre would be a knob or a pointed toe,
    /// whose axis the normals of a sherd cannot be trusted with either.
    pub min_axis_crossing_curvature_radius_mm: f64,
    /// A competing axis more than 10 degrees away whose cost is within this ratio of the
    /// best makes the answer ambiguous.
    pub competitor_cost_ratio: f64,
    /// The same ratio for a competitor more than [`CROSSING_COMPETITOR_ANGLE_DEG`] away
    /// when nothing on the sherd gives the winner's sense (no floor, level edge or slope
    /// under it). A doubly curved body piece, the belly of a jar, is nearly a surface of
    /// revolution about the vessel's axis and about the horizontal line through its
    /// profile's centre: the normals rate the two within 1.2-1.5 of each other either
    /// way (on the 34-fragment corpus of `examples/refine_accuracy.rs` the wrong one won
    /// twice, at 1.21 and 1.28, the right one five times, at 1.17-1.48), and only the
    /// vessel's anatomy under the winner would tell them apart.
    pub crossing_competitor_cost_ratio_without_sense: f64,
    /// Largest turn of the axis when one region of the sherd is left out, degrees (see
    /// [`super::region_stability::MAX_REGION_TURN_DEG`]).
    pub max_region_turn_deg: f64,
    /// Smallest confidence in the sense base to rim (see
    /// [`super::direction::DirectionEvidence`]): below it the axis line may be right but
    /// the piece would be drawn upside down as often as not.
    pub min_sense_confidence: f64,
    /// Factor from the fit's standard errors (which ignore the correlation of neighbouring
    /// normals) to the calibrated uncertainties.
    pub angle_sigma_factor: f64,
}

impl Default for VerdictThresholds {
    /// Calibrated on 360 synthetic fragments (10 vessels x 30 fragments, 0.8 mm cells, and
    /// 60 `synthetic_sherd`s; `examples/orient_accuracy.rs` writes the per-fragment CSV):
    /// the actual angle error is a median 3.5 times, and at the 90th percentile 16 times,
    /// the fit's standard error (neighbouring normals and the vessel's deformation are
    /// correlated, which the standard error ignores), hence the factor 5; the limits are
    /// the loosest that keep the fragments wrong by more than 5 degrees and not flagged
    /// under 4% of that corpus.
    fn default() -> Self {
        VerdictThresholds {
            min_lines: 50,
            min_normal_spread: 0.002,
            max_concurrency_ratio: 0.6,
            min_sphere_to_axis_ratio: 3.0,
            max_angle_uncertainty_deg: 5.0,
            max_position_uncertainty_mm: 5.0,
            max_residual_angle_deg: 2.5,
            min_inlier_fraction: 0.3,
            min_axis_crossing_curvature_radius_mm: 10.0,
            competitor_cost_ratio: 1.1,
            crossing_competitor_cost_ratio_without_sense: 1.5,
            max_region_turn_deg: super::region_stability::MAX_REGION_TURN_DEG,
            min_sense_confidence: 0.55,
            angle_sigma_factor: 5.0,
        }
    }
}

/// Second over first eigenvalue of the weighted scatter `Σ w n nᵀ` of the normals: 0 when
/// they are all parallel (a flat base), about 1 on a cylinder or cone.
pub fn normal_spread(lines: &CenteredLines) -> f64 {
    let mut scatter = Matrix3::zeros();
    for (n, w) in lines.directions.iter().zip(&lines.weights) {
        scatter += n * n.transpose() * *w;
    }
    let mut values: Vec<f64> = SymmetricEigen::new(scatter).eigenvalues.iter().copied().collect();
    values.sort_by(|a, b| b.total_cmp(a));
    values[1] / values[0].max(1e-300)
}

/// Angle beyond which a competing axis crosses the winner rather than tilts it, degrees
/// (see [`VerdictThresholds::crossing_competitor_cost_ratio_without_sense`]).
pub const CROSSING_COMPETITOR_ANGLE_DEG: f64 = 45.0;

/// The best refined candidate more than 10 degrees from the winner: (angle in degrees,
/// its cost over the winner's).
pub fn best_competitor(fit: &HalirFit) -> Option<(f64, f64)> {
    let best_cost = fit.cost.max(1e-300);
    fit.alternatives
        .iter()
        .map(|(direction, cost)| (direction.dot(&fit.direction).abs().min(1.0).acos().to_degrees(), cost / best_cost))
        .filter(|(angle, _)| *angle > 10.0)
        .min_by(|a, b| a.1.total_cmp(&b.1))
}

/// The verdict from the report's figures.
pub fn judge(
    report: &OrientReport,
    angle_uncertainty_deg: f64,
    position_uncertainty_mm: f64,
    limits: &VerdictThresholds,
) -> Verdict {
    let flag = |reason: String| Verdict::NeedsManualOrientation { reason };
    if report.normal_spread < limits.min_normal_spread {
        return flag(format!(
            "the normals are nearly parallel (spread {:.3} < {:.3}): a flat piece does not fix the axis position",
            report.normal_spread, limits.min_normal_spread
        ));
    }
    if report.concurrency_ratio > limits.max_concurrency_ratio {
        return flag(format!(
            "the normal lines nearly meet in one point (ratio {:.2} > {:.2}): a near-spherical piece fits many axes",
            report.concurrency_ratio, limits.max_concurrency_ratio
        ));
    }
    let sphere_ratio = report.sphere_residual_angle_deg / report.residual_angle_deg.max(1e-9);
    if sphere_ratio < limits.min_sphere_to_axis_ratio {
        return flag(format!(
            "a sphere explains the normals almost as well as an axis (they miss its centre by {:.2} deg, the axis by {:.2} deg): a near-spherical piece",
            report.sphere_residual_angle_deg, report.residual_angle_deg
        ));
    }
    if report.inlier_fraction < limits.min_inlier_fraction {
        return flag(format!(
            "only {:.0}% of the normal lines agree on an axis (at least {:.0}% needed)",
            100.0 * report.inlier_fraction,
            100.0 * limits.min_inlier_fraction
        ));
    }
    if !(report.residual_angle_deg <= limits.max_residual_angle_deg) {
        return flag(format!(
            "the normals miss the axis by {:.1} deg typically ({:.2} mm at radius {:.1} mm; at most {:.1} deg accepted)",
            report.residual_angle_deg, report.residual_scale_mm, report.median_radius_mm, limits.max_residual_angle_deg
        ));
    }
    if let Some(radius_mm) = report.axis_crossing_curvature_radius_mm {
        if !(radius_mm >= limits.min_axis_crossing_curvature_radius_mm) {
            return flag(format!(
                "the axis would pass through the sherd where its surface is curved like a knob (curvature radius {radius_mm:.1} mm < {:.0} mm): a vessel's floor meets its axis flat or gently domed, so this is a curved wall taken for a floor",
                limits.min_axis_crossing_curvature_radius_mm
            ));
        }
    }
    if !(angle_uncertainty_deg <= limits.max_angle_uncertainty_deg) {
        return flag(format!(
            "the axis direction is uncertain: +-{:.1} deg (at most {:.1} deg accepted)",
            angle_uncertainty_deg, limits.max_angle_uncertainty_deg
        ));
    }
    if !(position_uncertainty_mm <= limits.max_position_uncertainty_mm) {
        return flag(format!(
            "the axis position is uncertain: +-{:.1} mm (at most {:.1} mm accepted)",
            position_uncertainty_mm, limits.max_position_uncertainty_mm
        ));
    }
    if let Some((angle, ratio)) = report.competitor {
        if ratio < limits.competitor_cost_ratio {
            return flag(format!(
                "two axes {angle:.0} deg apart fit almost equally well (cost ratio {ratio:.2})"
            ));
        }
    }
    // NaN (a refit that failed to give a number) is flagged too.
    if report.region_turn_deg.is_nan() || report.region_turn_deg > limits.max_region_turn_deg {
        // Which tilt is loose tells the user what is unknown: the slant of the profile
        // (meridian plane), or the level of the rills and rim.
        let which = if report.region_turn_in_meridian_deg >= 0.8 * report.region_turn_deg {
            format!(", {:.1} of them in the sherd's meridian plane: the slant of its profile is not fixed", report.region_turn_in_meridian_deg)
        } else {
            String::new()
        };
        return flag(format!(
            "the axis rests on one region of the sherd: leaving it out turns the axis by {:.1} deg (at most {:.1} deg accepted){which}",
            report.region_turn_deg, limits.max_region_turn_deg
        ));
    }
    if !(report.direction_strength >= limits.min_sense_confidence) {
        if let Some((angle, ratio)) = report.competitor {
            if angle > CROSSING_COMPETITOR_ANGLE_DEG && ratio < limits.crossing_competitor_cost_ratio_without_sense {
                return flag(format!(
                    "two axes {angle:.0} deg apart fit almost equally well (cost ratio {ratio:.2}) and nothing on the sherd (floor, level edge, slope) says which is the vessel's"
                ));
            }
        }
        return Verdict::SenseUncertain { reason: format!(
            "the axis line is found but not which way is up (base to rim): {} (confidence {:.2} < {:.2})",
            report.direction_cue, report.direction_strength, limits.min_sense_confidence
        ) };
    }
    Verdict::Oriented
}

/// Where `axis` passes through the sherd (the points closer to it than `near_mm`): the
/// median distance from those points along their normals to the axis, `r / sin(angle
/// between normal and axis)`, millimetres; `None` where fewer than 5 points are that close.
///
/// On a surface of revolution this distance is the radius of curvature of the parallel
/// circle, and where the surface meets its axis it is the curvature radius of the floor
/// there: a vessel's floor meets the axis square, flat or gently domed, so the distance is
/// large. A few millimetres means that the axis was put through a curved wall, where no
/// vessel's axis can run (a shoulder taken for a dome).
pub fn axis_crossing_curvature_radius_mm(lines: &NormalLines, axis: &Axis, near_mm: f64) -> Option<f64> {
    let direction = axis.direction.into_inner();
    let (distances, weights): (Vec<f64>, Vec<f64>) = (0..lines.len())
        .filter_map(|i| {
            let radius = axis.distance_to(&lines.points[i]);
            (radius < near_mm).then(|| {
                let sine = lines.directions[i].cross(&direction).norm();
                ((radius / sine.max(1e-9)).min(1e9), lines.weights[i])
            })
        })
        .unzip();
    (distances.len() >= 5).then(|| weighted_median_abs(&distances, &weights))
}

/// By how much the normals typically miss `axis`, as an angle seen from the axis:
/// weighted median of `atan(distance(normal line, axis) / radius)`, degrees, over the
/// lines `use_line` accepts.
pub fn axis_residual_angle_deg(lines: &NormalLines, axis: &Axis, use_line: &[bool]) -> f64 {
    let (angles, weights): (Vec<f64>, Vec<f64>) = (0..lines.len())
        .filter(|&i| use_line[i])
        .map(|i| {
            let distance = super::surfaces::normal_line_distance(axis, &lines.points[i], &lines.directions[i]);
            let radius = axis.distance_to(&lines.points[i]).max(1e-9);
            ((distance / radius).atan().to_degrees(), lines.weights[i])
        })
        .unzip();
    weighted_median_abs(&angles, &weights)
}

/// The same for the best common point of the lines (the centre of the best sphere): how
/// well a sphere explains the normals. When it does about as well as the axis, the axis is
/// decided by small departures from a sphere (deformation), not by the vessel's shape.
pub fn sphere_residual_angle_deg(lines: &NormalLines, use_line: &[bool]) -> f64 {
    let mut normal = Matrix3::zeros();
    let mut rhs = nalgebra::Vector3::zeros();
    for i in (0..lines.len()).filter(|&i| use_line[i]) {
        let n = lines.directions[i];
        let projector = Matrix3::identity() - n * n.transpose();
        normal += projector * lines.weights[i];
        rhs += projector * lines.points[i].coords * lines.weights[i];
    }
    let Some(center) = normal.try_inverse().map(|inverse| Point::from(inverse * rhs)) else {
        return 0.0;
    };
    let (angles, weights): (Vec<f64>, Vec<f64>) = (0..lines.len())
        .filter(|&i| use_line[i])
        .map(|i| {
            let offset = center - lines.points[i];
            let n = lines.directions[i];
            let distance = (offset - n * offset.dot(&n)).norm();
            ((distance / offset.norm().max(1e-9)).atan().to_degrees(), lines.weights[i])
        })
        .unzip();
    weighted_median_abs(&angles, &weights)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Vector;

    /// Lines of a cap `z = f(r)` about the z axis, on a polar grid out to `r_max`, with the
    /// cap's normals.
    fn cap_lines(slope: impl Fn(f64) -> f64, r_max: f64) -> NormalLines {
        let mut lines = NormalLines::default();
        for ring in 0..=20 {
            let r = r_max * ring as f64 / 20.0;
            for step in 0..24 {
                let angle = step as f64 * std::f64::consts::TAU / 24.0;
                let (c, s) = (angle.cos(), angle.sin());
                // z = f(r): the normal is (-f'(r) cos, -f'(r) sin, 1), normalised.
                let d = slope(r);
                lines.points.push(Point::new(r * c, r * s, 0.0));
                lines.directions.push(Vector::new(-d * c, -d * s, 1.0).normalize());
                lines.weights.push(1.0);
                lines.vertex_indices.push(lines.points.len() - 1);
            }
        }
        lines
    }

    #[test]
    fn a_floor_meets_its_axis_flat_and_a_knob_does_not() {
        let axis = Axis::z();
        // A floor domed with a 60 mm radius of curvature, and a knob of 4 mm: the normals of
        // a sphere of radius R meet the axis R away, whatever the point.
        let sphere_slope = |radius: f64| move |r: f64| r / (radius * radius - r * r).sqrt();
        let floor = axis_crossing_curvature_radius_mm(&cap_lines(sphere_slope(60.0), 3.0), &axis, 3.5).unwrap();
        let knob = axis_crossing_curvature_radius_mm(&cap_lines(sphere_slope(4.0), 3.0), &axis, 3.5).unwrap();
        assert!((floor - 60.0).abs() < 0.5, "floor {floor}");
        assert!((knob - 4.0).abs() < 0.1, "knob {knob}");
        // A flat floor: the normals are parallel to the axis, the radius is unbounded.
        let flat = axis_crossing_curvature_radius_mm(&cap_lines(|_| 0.0, 3.0), &axis, 3.5).unwrap();
        assert!(flat > 1e6, "flat {flat}");
        // An axis that runs clear of the sherd gives nothing to judge.
        let aside = Axis::new(Point::new(50.0, 0.0, 0.0), Vector::z());
        assert_eq!(axis_crossing_curvature_radius_mm(&cap_lines(|_| 0.0, 3.0), &aside, 3.5), None);
    }

    /// The report of a sherd every test of the verdict passes: spread normals that meet
    /// one line (1 degree off) and no sphere, nearly all inliers, a floor or level edge
    /// under the axis. Each test spoils one figure.
    fn clear_report() -> OrientReport {
        OrientReport {
            normal_spread: 0.5,
            concurrency_ratio: 0.1,
            residual_angle_deg: 1.0,
            sphere_residual_angle_deg: 10.0,
            inlier_fraction: 0.9,
            direction_strength: 1.0,
            ..Default::default()
        }
    }

    #[test]
    fn an_axis_through_a_knob_is_flagged() {
        let mut report = OrientReport { axis_crossing_curvature_radius_mm: Some(60.0), ..clear_report() };
        let limits = VerdictThresholds::default();
        assert_eq!(judge(&report, 1.0, 1.0, &limits), Verdict::Oriented);
        report.axis_crossing_curvature_radius_mm = Some(4.8);
        let verdict = judge(&report, 1.0, 1.0, &limits);
        assert!(verdict.reason().is_some_and(|r| r.contains("4.8 mm")), "{verdict:?}");
    }

    #[test]
    fn a_crossing_competitor_is_ruled_out_only_by_the_sense_cues() {
        let mut report = OrientReport {
            residual_angle_deg: 0.3,
            sphere_residual_angle_deg: 4.0,
            competitor: Some((90.0, 1.21)),
            ..clear_report()
        };
        let limits = VerdictThresholds::default();
        // A floor or a level rim under the winner: the vessel's anatomy picks it.
        assert_eq!(judge(&report, 1.0, 1.0, &limits), Verdict::Oriented);
        // No cue: the line is not known either.
        report.direction_strength = 0.0;
        let verdict = judge(&report, 1.0, 1.0, &limits);
        assert!(matches!(verdict, Verdict::NeedsManualOrientation { .. }), "{verdict:?}");
        assert!(verdict.reason().is_some_and(|r| r.contains("90 deg apart") && r.contains("1.21")), "{verdict:?}");
        // A competitor that only tilts the axis, or a clear winner, leaves the line usable.
        for competitor in [(30.0, 1.21), (90.0, 1.8)] {
            report.competitor = Some(competitor);
            assert!(matches!(judge(&report, 1.0, 1.0, &limits), Verdict::SenseUncertain { .. }), "{competitor:?}");
        }
    }

    #[test]
    fn normals_that_miss_the_axis_by_degrees_are_flagged() {
        let mut report = OrientReport { residual_angle_deg: 1.4, ..clear_report() };
        let limits = VerdictThresholds::default();
        assert_eq!(judge(&report, 1.0, 1.0, &limits), Verdict::Oriented);
        report.residual_angle_deg = 2.8;
        let verdict = judge(&report, 1.0, 1.0, &limits);
        assert!(verdict.reason().is_some_and(|r| r.contains("2.8 deg")), "{verdict:?}");
    }
}
