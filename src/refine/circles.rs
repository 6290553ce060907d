//! Horizontal circle adjustment using the radius (Wilczek et al. 2018, section 2.3.1,
//! Eq. 2): the sum over horizontal sections of the variance of the distances of the
//! section's points to the candidate axis. Each section of each skin has its own mean,
//! so the wall thickness does not count as variance when both skins are used.

use super::objective::Objective;
use super::sections::{AxisParameters, CandidateFrame, PreparedSurface};

/// Sections with fewer points are skipped (the original skips 5 or fewer).
pub const MIN_SECTION_POINTS: usize = 6;

/// Eq. 2 on a prepared fragment.
pub struct CirclesObjective<'a> {
    /// The fragment.
    pub surface: &'a PreparedSurface,
}

impl Objective for CirclesObjective<'_> {
    fn value(&self, parameters: &AxisParameters) -> f64 {
        let frame = CandidateFrame::new(parameters);
        let sections = self.surface.horizontal_sections(&frame);
        let mut total = 0.0;
        let mut used = 0;
        for section in sections.iter().filter(|s| s.points.len() >= MIN_SECTION_POINTS) {
            let weight_sum: f64 = section.weights.iter().sum();
            let radii: Vec<f64> = section.points.iter().map(|p| p[0].hypot(p[1])).collect();
            let mean = radii.iter().zip(&section.weights).map(|(r, w)| r * w).sum::<f64>() / weight_sum;
            total += radii.iter().zip(&section.weights).map(|(r, w)| w * (r - mean).powi(2)).sum::<f64>() / weight_sum;
            used += 1;
        }
        if used == 0 { f64::INFINITY } else { total / used as f64 }
    }
}
