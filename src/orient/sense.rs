//! The sense cues' inputs, which an automatic orientation keeps so that the sense base to
//! rim can be read again once a refinement has moved the axis.

use super::normal_lines::NormalLines;
use super::verdict::Verdict;
use super::{direction, revolution_search};
use crate::axis::Axis;
use crate::mesh::Point;

/// What the sense cues read, kept with an automatic orientation so that the sense can be
/// judged again under the refined axis: the cues read the ends, floor and slope of the
/// profile, which a pre-orientation a few degrees off blurs.
#[derive(Debug)]
pub struct SenseInputs {
    pub(super) samples: Option<revolution_search::RevolutionSamples>,
    pub(super) all_samples: Option<revolution_search::RevolutionSamples>,
    pub(super) lines: NormalLines,
    pub(super) all_points: Vec<Point>,
    pub(super) loss_scale_mm: f64,
    pub(super) min_confidence: f64,
}

impl SenseInputs {
    /// Which lines lie on the surface of revolution about `axis`.
    pub(super) fn on_surface(&self, axis: &Axis) -> Vec<bool> {
        on_surface_of(self.samples.as_ref(), self.lines.len(), axis, self.loss_scale_mm)
    }

    /// The line of `axis` pointed from base to rim as the cues say, and the cues.
    pub fn judge(&self, axis: &Axis) -> (Axis, direction::DirectionEvidence) {
        let finished = self.all_samples.as_ref().map(|_| on_surface_of(self.all_samples.as_ref(), self.all_points.len(), axis, self.loss_scale_mm));
        let evidence = direction::direction_evidence_finished(&self.lines, &self.on_surface(axis), &self.all_points, finished.as_deref(), axis);
        let oriented = if evidence.score < 0.0 { axis.flipped() } else { *axis };
        (oriented, evidence)
    }

    /// [`Verdict::Oriented`] when the cues are confident, [`Verdict::SenseUncertain`]
    /// otherwise.
    pub fn verdict(&self, evidence: &direction::DirectionEvidence) -> Verdict {
        if evidence.score.abs() >= self.min_confidence {
            Verdict::Oriented
        } else {
            Verdict::SenseUncertain {
                reason: format!(
                    "the axis line is found but not which way is up (base to rim): {} (confidence {:.2} < {:.2})",
                    evidence.cue,
                    evidence.score.abs(),
                    self.min_confidence
                ),
            }
        }
    }
}

/// Which of the `count` points of `samples` (all of their lines) lie on the surface of
/// revolution about `axis`: all of them when there are no samples.
fn on_surface_of(samples: Option<&revolution_search::RevolutionSamples>, count: usize, axis: &Axis, loss_scale_mm: f64) -> Vec<bool> {
    match samples {
        Some(all) => revolution_search::point_losses(all, axis, loss_scale_mm).iter().map(|l| *l < ON_SURFACE_LOSS).collect(),
        None => vec![true; count],
    }
}

/// Robust loss under which a point counts as on the surface of revolution for the sense
/// cues (a residual of about a loss scale).
const ON_SURFACE_LOSS: f64 = 0.5;
