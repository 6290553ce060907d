//! Horizontal circle adjustment using the radius (Wilczek et al. 2018, section 2.3.1,
//! Eq. 2): the sum over horizontal sections of the variance of the distances of the
//! section's points to the candidate axis. Each section of each skin has its own mean,
//! so the wall thickness does not count as variance when both skins are used.

use super::objective::Objective;
use super::sections::{AxisParameters, CandidateFrame, HorizontalSection, PreparedSurface};
use crate::statistics::quantile;
use crate::mesh::planar_length;

/// Sections with fewer points are skipped (the original skips 5 or fewer).
pub const MIN_SECTION_POINTS: usize = 6;

/// Eq. 2 on a prepared fragment.
pub struct CirclesObjective<'a> {
    /// The fragment.
    pub surface: &'a PreparedSurface,
    /// Optional weight per section (in [`PreparedSurface::horizontal_sections`] order),
    /// as a bootstrap draws them; `None` weighs every section 1.
    pub section_weights: Option<&'a [f64]>,
}

impl<'a> CirclesObjective<'a> {
    /// Eq. 2 with every section weighted 1.
    pub fn new(surface: &'a PreparedSurface) -> Self {
        CirclesObjective { surface, section_weights: None }
    }
}

/// Points farther than this many robust standard deviations (1.4826 MAD) from the
/// section's median radius are left out: break faces that join a skin at a blunt angle
/// and spikes of the scan would otherwise dominate the variance.
const TRIM_SIGMAS: f64 = 3.0;
/// The trimming never drops points closer than this to the median radius, mm.
const TRIM_FLOOR_MM: f64 = 0.3;

/// The weighted variance of the distances to the axis of a section's points, after
/// dropping the outliers.
pub fn trimmed_variance(section: &HorizontalSection) -> f64 {
    let (radii, median, limit) = section_radii(section);
    let (mut weight_sum, mut weighted_sum) = (0.0, 0.0);
    for (r, w) in radii.iter().zip(&section.weights) {
        if (r - median).abs() <= limit {
            weight_sum += w;
            weighted_sum += w * r;
        }
    }
    if weight_sum <= 0.0 {
        return 0.0;
    }
    let mean = weighted_sum / weight_sum;
    radii
        .iter()
        .zip(&section.weights)
        .filter(|(r, _)| (*r - median).abs() <= limit)
        .map(|(r, w)| w * (r - mean).powi(2))
        .sum::<f64>()
        / weight_sum
}

/// A section's points' distances to the candidate axis, their median, and how far from
/// it a distance may lie before [`trimmed_variance`] leaves the point out.
pub(crate) fn section_radii(section: &HorizontalSection) -> (Vec<f64>, f64, f64) {
    let radii: Vec<f64> = section.points.iter().map(|p| planar_length(p[0], p[1])).collect();
    let mut sorted = radii.clone();
    let median = quantile(&mut sorted, 0.5);
    let mut deviations: Vec<f64> = radii.iter().map(|r| (r - median).abs()).collect();
    let limit = (TRIM_SIGMAS * 1.4826 * quantile(&mut deviations, 0.5)).max(TRIM_FLOOR_MM);
    (radii, median, limit)
}

impl Objective for CirclesObjective<'_> {
    fn value(&self, parameters: &AxisParameters) -> f64 {
        let frame = CandidateFrame::new(parameters);
        let sections = self.surface.horizontal_sections(&frame);
        let mut total = 0.0;
        let mut used = 0.0;
        for (index, section) in sections.iter().enumerate() {
            let section_weight = self.section_weights.map_or(1.0, |w| w[index]);
            if section.points.len() < MIN_SECTION_POINTS || section_weight == 0.0 {
                continue;
            }
            let variance = trimmed_variance(section);
            total += section_weight * variance;
            used += section_weight;
        }
        if used == 0.0 { f64::INFINITY } else { total / used }
    }
}
