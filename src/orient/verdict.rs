//! Honest failure: the verdict an orientation carries ([`Verdict`]), the few limits the
//! automatic orientation applies before it judges the whole-sphere search's landscape
//! (`super::landscape`, in units the fragment's own noise explains), and the figures of
//! the normals its report gives.

use nalgebra::{Matrix3, SymmetricEigen};
use serde::{Deserialize, Serialize};

use crate::axis::Axis;
use crate::statistics::weighted_median_abs;
use super::normal_lines::NormalLines;
use super::line_complex::CenteredLines;

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

/// The limits the automatic orientation applies before it reads the landscape.
#[derive(Clone, Copy, Debug)]
pub struct VerdictThresholds {
    /// Fewest lines on the surface of revolution.
    pub min_lines: usize,
    /// Smallest second/first eigenvalue of the normals' scatter (flat piece below).
    pub min_normal_spread: f64,
    /// Smallest confidence in the sense base to rim (see
    /// [`super::direction::DirectionEvidence`]): below it the axis line may be right but
    /// the piece would be drawn upside down as often as not.
    pub min_sense_confidence: f64,
}

impl Default for VerdictThresholds {
    fn default() -> Self {
        VerdictThresholds { min_lines: 50, min_normal_spread: 0.002, min_sense_confidence: 0.55 }
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

/// Angle beyond which a competing axis crosses the winner rather than tilts it, degrees:
/// such a competitor makes the piece a surface of revolution about the other principal
/// curvature, and only a level lip tells the two apart.
pub const CROSSING_COMPETITOR_ANGLE_DEG: f64 = 45.0;

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Point, Vector};

    /// Lines of a cylinder of radius 50 mm about the z axis, normals outward.
    fn cylinder_lines() -> NormalLines {
        let mut lines = NormalLines::default();
        for step in 0..72 {
            let angle = step as f64 * std::f64::consts::TAU / 72.0;
            for z in [0.0, 10.0, 20.0] {
                lines.points.push(Point::new(50.0 * angle.cos(), 50.0 * angle.sin(), z));
                lines.directions.push(Vector::new(angle.cos(), angle.sin(), 0.0));
                lines.weights.push(1.0);
                lines.vertex_indices.push(lines.points.len() - 1);
            }
        }
        lines
    }

    #[test]
    fn the_normals_of_a_cylinder_spread_and_meet_its_axis() {
        let lines = cylinder_lines();
        assert!((normal_spread(&CenteredLines::new(&lines)) - 1.0).abs() < 1e-9);
        let all = vec![true; lines.len()];
        assert!(axis_residual_angle_deg(&lines, &Axis::z(), &all) < 1e-9);
        // Moved 5 mm off, the axis is missed by up to atan(5/50) = 5.7 degrees.
        let moved = Axis::new(Point::new(5.0, 0.0, 0.0), Vector::z());
        let missed = axis_residual_angle_deg(&lines, &moved, &all);
        assert!(missed > 1.0 && missed < 6.0, "{missed}");
    }

    #[test]
    fn parallel_normals_do_not_spread() {
        let mut lines = cylinder_lines();
        lines.directions.iter_mut().for_each(|d| *d = Vector::z());
        assert!(normal_spread(&CenteredLines::new(&lines)) < 1e-12);
    }
}
