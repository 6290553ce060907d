//! The points the search scores, centred and weighted, and their view from a candidate
//! direction: height along it, position and normal across it.

use nalgebra::Vector2;

use super::loss::MIN_BAND_POINTS;
use crate::mesh::{Point, Vector};
use crate::orient::normal_lines::NormalLines;

/// The fragment's points, normals and area weights, centred on their centroid, ready to
/// be scored against any axis.
#[derive(Clone, Debug)]
pub struct RevolutionSamples {
    /// Positions relative to `centroid`, mm.
    pub points: Vec<Vector>,
    /// Unit normals.
    pub normals: Vec<Vector>,
    /// Area weights, mean 1.
    pub weights: Vec<f64>,
    /// The centroid subtracted, scan frame.
    pub centroid: Point,
    /// Width of a band along the profile, mm.
    pub band_mm: f64,
}

impl RevolutionSamples {
    /// At most `max_count` of `lines` (an even stride through them), with bands wide enough
    /// to hold several points of each skin: `band_factor` times the typical spacing of the
    /// points kept, at least `min_band_mm`.
    pub fn from_lines(lines: &NormalLines, max_count: usize, band_factor: f64, min_band_mm: f64) -> Option<Self> {
        let n = lines.len();
        if n < 2 * MIN_BAND_POINTS {
            return None;
        }
        let count = n.min(max_count.max(1));
        let picked: Vec<usize> = (0..count).map(|k| (k * n) / count).collect();
        let total_weight: f64 = picked.iter().map(|&i| lines.weights[i]).sum();
        if !(total_weight > 0.0) {
            return None;
        }
        let centroid = Point::from(
            picked.iter().map(|&i| lines.points[i].coords * lines.weights[i]).sum::<Vector>() / total_weight,
        );
        let mean_weight = total_weight / count as f64;
        // The surface area of all lines, shared by the kept points.
        let area: f64 = lines.weights.iter().sum();
        let spacing_mm = if lines.weights.iter().all(|w| *w == 1.0) {
            // A point cloud carries no areas: its spread stands in.
            let spread = picked.iter().map(|&i| (lines.points[i] - centroid).norm_squared()).sum::<f64>() / count as f64;
            (4.0 * spread / count as f64).sqrt()
        } else {
            (area / count as f64).sqrt()
        };
        Some(RevolutionSamples {
            points: picked.iter().map(|&i| lines.points[i] - centroid).collect(),
            normals: picked.iter().map(|&i| lines.directions[i]).collect(),
            weights: picked.iter().map(|&i| lines.weights[i] / mean_weight).collect(),
            centroid,
            band_mm: (band_factor * spacing_mm).max(min_band_mm),
        })
    }

    /// Root mean square distance of the points to their centroid, mm.
    pub fn size_mm(&self) -> f64 {
        let total: f64 = self.weights.iter().sum();
        (self.points.iter().zip(&self.weights).map(|(p, w)| p.norm_squared() * w).sum::<f64>() / total.max(1e-300)).sqrt()
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// True when there are no points.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }
}

/// A point in the frame of a candidate direction: height along it, position in the
/// perpendicular plane, and the normal's parts.
#[derive(Clone, Copy)]
pub(super) struct Projected {
    pub(super) height: f64,
    pub(super) planar: Vector2<f64>,
    pub(super) normal_planar: Vector2<f64>,
    pub(super) normal_axial: f64,
    pub(super) weight: f64,
    /// The index of the wall band holding the point, `floor(height / band_mm)`: it does
    /// not depend on the axis's position, so every trial position of a direction reads
    /// it instead of dividing again.
    pub(super) wall_band: i64,
}

/// `value.floor() as i64` without `f64::floor`, which is a call into libm on the baseline
/// target and was a twentieth of the search's instructions (placing every point in its
/// band, for every candidate axis).
pub(super) fn floor_index(value: f64) -> i64 {
    let truncated = value as i64;
    truncated.saturating_sub(((truncated as f64) > value) as i64)
}

/// The samples in the frame of one candidate direction, with what does not depend on
/// the axis's position along it.
pub(super) struct ProjectedSamples {
    pub(super) points: Vec<Projected>,
    /// The least and greatest wall band index of the points: every wall band any trial
    /// position can fill.
    pub(super) wall_range: (i64, i64),
    /// The samples' band width, mm.
    pub(super) band_mm: f64,
    /// The points' total weight.
    pub(super) weight: f64,
}

pub(super) fn project(samples: &RevolutionSamples, d: &Vector, e1: &Vector, e2: &Vector) -> ProjectedSamples {
    let points: Vec<Projected> = samples
        .points
        .iter()
        .zip(&samples.normals)
        .zip(&samples.weights)
        .map(|((p, n), w)| {
            let height = p.dot(d);
            Projected {
                height,
                planar: Vector2::new(p.dot(e1), p.dot(e2)),
                normal_planar: Vector2::new(n.dot(e1), n.dot(e2)),
                normal_axial: n.dot(d),
                weight: *w,
                wall_band: floor_index(height / samples.band_mm),
            }
        })
        .collect();
    let wall_range = points.iter().fold((i64::MAX, i64::MIN), |(low, high), p| (low.min(p.wall_band), high.max(p.wall_band)));
    let weight = points.iter().fold(0.0, |total, p| total + p.weight);
    ProjectedSamples { points, wall_range, band_mm: samples.band_mm, weight }
}

#[cfg(test)]
mod tests {
    use super::floor_index;

    #[test]
    fn floor_index_is_floor() {
        for value in [-2.5, -2.0, -1e-12, -0.0, 0.0, 1e-12, 0.999_999, 1.0, 3.5, 1e20, -1e20, f64::NAN] {
            assert_eq!(floor_index(value), value.floor() as i64, "{value}");
        }
    }
}
