//! What an orientation gives back: the axis with its verdict and uncertainties, the report
//! of how it was found for the archaeologist's record, and the sense read again under a
//! refined axis.

use serde::{Deserialize, Serialize};

use super::direction;
use super::sense::SenseInputs;
use super::verdict::Verdict;
use crate::axis::Axis;

/// What the orientation found and how far to trust it.
#[derive(Clone, Debug)]
pub struct Orientation {
    /// The axis in the input's frame, base to rim.
    pub axis: Axis,
    /// Whether the axis can be used.
    pub verdict: Verdict,
    /// Why an axis given as found may still be wrong (another axis fits about as well):
    /// such an axis is `axis_uncertain`. Empty when there is none.
    pub doubts: Vec<String>,
    /// How far the direction can turn, degrees, before the axis fits the piece worse
    /// block by block ([`landscape::valley_width`](super::landscape::valley_width)): the width of its valley in units of
    /// the piece's own noise and deformation. NaN for a manual axis, infinite when no axis
    /// was found.
    pub angle_uncertainty_deg: f64,
    /// The same for a move of the axis across itself near the sherd, millimetres.
    pub position_uncertainty_mm: f64,
    /// How far the valleys of the search that the fragment does not rule out lie from
    /// the axis: an answer's intervals reach them. `None` when every other valley fits
    /// clearly worse, and for a manual axis.
    pub competitor_reach: Option<CompetitorReach>,
    /// Vertices of the working copy kept as the surface of revolution.
    pub kept_vertex_count: usize,
    /// The details, for `--json` and the archaeologist's record.
    pub report: OrientReport,
    /// What the sense cues read, for [`Orientation::rejudge_sense`] (automatic
    /// orientations).
    pub sense_inputs: Option<std::sync::Arc<SenseInputs>>,
}

/// Serialisable details of an orientation.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct OrientReport {
    /// "automatic" or "three points".
    pub method: String,
    /// Vertices of the input.
    pub input_vertex_count: usize,
    /// Vertices of the working copy.
    pub working_vertex_count: usize,
    /// Vertices kept by the opposite-normal test (or by the distance rule, for a manual axis).
    pub kept_vertex_count: usize,
    /// Whether the opposite-normal test ran, and why not if it did not.
    pub opposite_filter: String,
    /// Wall thickness seen by the opposite-normal test, millimetres.
    pub wall_thickness_mm: Option<f64>,
    /// Robust scale of the normal-line-to-axis residuals, millimetres.
    pub residual_scale_mm: f64,
    /// By how much the normals typically miss the axis, seen from it, degrees (see
    /// [`verdict::axis_residual_angle_deg`](super::verdict::axis_residual_angle_deg)).
    pub residual_angle_deg: f64,
    /// Median distance of the kept points to the axis, millimetres.
    pub median_radius_mm: f64,
    /// Share of the points' weight on the surface of revolution about the search's axis.
    pub inlier_fraction: f64,
    /// Second eigenvalue of the normals' scatter over the first (0 for a flat piece).
    pub normal_spread: f64,
    /// `λ1/λ2` of the line complex (near 1 for a near-spherical piece).
    pub concurrency_ratio: f64,
    /// Angle to the best competing axis, degrees, and the t statistic by which the best
    /// fits the piece better, block by block (see [`landscape::separation`](super::landscape::separation)).
    pub competitor: Option<(f64, f64)>,
    /// The whole-sphere search's robust score of the axis (0 for a perfect surface of
    /// revolution, 0.9 when no point is on one).
    #[serde(default)]
    pub search_cost: f64,
    /// The least relative rise of that score when the axis moves 10 mm across itself (see
    /// [`landscape::position_hold`](super::landscape::position_hold)): near 0 where the piece does not fix the position.
    #[serde(default)]
    pub position_hold: f64,
    /// The cue that set the sense base to rim, or why none could.
    pub direction_cue: String,
    /// Confidence in the sense base to rim, 0 to 1 (see [`direction::DirectionEvidence`]).
    pub direction_strength: f64,
    /// The figures of each sense cue.
    pub sense_cues: direction::SenseCues,
    /// Radius of the picked circle (manual), millimetres.
    pub circle_radius_mm: Option<f64>,
    /// Wall-clock milliseconds per step.
    pub timings_ms: Vec<(String, f64)>,
}

/// The farthest of the competing axes the fragment does not rule out (the best fits
/// better by less than the verdict's t), as an angle and as the paper's mean point
/// distance between the lines. The bootstrap and the valley's width measure the spread
/// about the best valley; where another valley fits the piece about as well, the axis
/// may lie there, and a 95% interval that stops short of it claims what the piece does
/// not show.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CompetitorReach {
    /// The largest angle between an unresolved competitor's line and the axis, degrees.
    pub angle_deg: f64,
    /// The largest mean point distance between an unresolved competitor's line and the
    /// axis's, up and down aside, millimetres.
    pub distance_mm: f64,
}

/// Writes the cues into the report.
pub(super) fn record_sense(report: &mut OrientReport, evidence: &direction::DirectionEvidence) {
    report.direction_cue = evidence.cue.clone();
    report.direction_strength = evidence.score.abs();
    report.sense_cues = evidence.cues.clone();
}

impl Orientation {
    /// The sense judged again under `axis` (a refinement of this orientation's axis line):
    /// `axis` pointed from base to rim as the cues read it there, with the verdict and the
    /// report updated. An orientation that declined, or a manual one, keeps its verdict and
    /// only points `axis` like its own.
    pub fn rejudge_sense(&mut self, axis: &Axis) -> Axis {
        let Some(inputs) = self.sense_inputs.clone().filter(|_| self.verdict.has_axis_line()) else {
            return if axis.direction.dot(&self.axis.direction) < 0.0 { axis.flipped() } else { *axis };
        };
        let (oriented, evidence) = inputs.judge(axis);
        self.verdict = inputs.verdict(&evidence);
        record_sense(&mut self.report, &evidence);
        self.axis = if oriented.direction.dot(&self.axis.direction) < 0.0 { self.axis.flipped() } else { self.axis };
        oriented
    }
}
