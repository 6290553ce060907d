//! Inner/outer surface segmentation (Wilczek et al. 2018, end of section 2.2.1): with the
//! axis known, a vertex whose normal line passes near the axis is on the surface of
//! revolution, and it is on the inner skin when a step along its normal brings it closer
//! to the axis, on the outer skin otherwise.

use serde::{Deserialize, Serialize};

use crate::axis::Axis;
use super::normal_lines::NormalLines;
use crate::mesh::{Mesh, Point, Vector};
use crate::Result;

/// Which skin a vertex belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Skin {
    /// The inside of the vessel: the normal points towards the axis.
    Inner,
    /// The outside: the normal points away from the axis.
    Outer,
    /// Not on the surface of revolution (fracture, decoration), or no usable normal.
    Other,
}

/// How the pertinent surface is chosen.
#[derive(Clone, Copy, Debug, Default)]
pub struct SegmentOptions {
    /// Keep the vertices whose normal line passes within this distance of the axis; `None`
    /// derives it from the data: 3 times the median distance (a robust 2-sigma bound when
    /// most vertices are on the skins), at least 0.5% of the median radius.
    pub max_line_distance_mm: Option<f64>,
    /// Alternatively keep this fraction of the vertices with the lowest distances (the
    /// paper's manual procedure keeps 50%); used instead of the distance when set.
    pub keep_fraction: Option<f64>,
}

/// Distance between the normal line `(point, normal)` and `axis` (equation (1) of the
/// paper; for a line parallel to the axis, the distance between the parallels).
pub fn normal_line_distance(axis: &Axis, point: &Point, normal: &Vector) -> f64 {
    let d = axis.direction.into_inner();
    let cross = normal.cross(&d);
    let sine = cross.norm();
    if sine < 1e-9 {
        return axis.distance_to(point);
    }
    (point - axis.point).dot(&cross).abs() / sine
}

/// Per vertex: inner, outer or other, with the default options.
pub fn segment_surfaces(mesh: &Mesh, axis: &Axis) -> Result<Vec<Skin>> {
    segment_surfaces_with(mesh, axis, &SegmentOptions::default())
}

/// Per vertex: inner, outer or other.
pub fn segment_surfaces_with(mesh: &Mesh, axis: &Axis, options: &SegmentOptions) -> Result<Vec<Skin>> {
    let lines = NormalLines::from_mesh(mesh)?;
    let mask = pertinent_mask(&lines, axis, options);
    let mut skins = vec![Skin::Other; mesh.vertex_count()];
    for (i, keep) in mask.iter().enumerate() {
        if !keep {
            continue;
        }
        let point = lines.points[i];
        // A step of a small fraction of the radius: large enough for floating point, small
        // enough not to cross the axis.
        let radius = axis.distance_to(&point);
        let step = (radius * 1e-3).max(1e-9);
        let moved = axis.distance_to(&(point + lines.directions[i] * step));
        skins[lines.vertex_indices[i]] = if moved < radius { Skin::Inner } else { Skin::Outer };
    }
    Ok(skins)
}

/// Which lines are on the pertinent surface for `axis`.
pub fn pertinent_mask(lines: &NormalLines, axis: &Axis, options: &SegmentOptions) -> Vec<bool> {
    let distances: Vec<f64> =
        (0..lines.len()).map(|i| normal_line_distance(axis, &lines.points[i], &lines.directions[i])).collect();
    let mut sorted = distances.clone();
    sorted.sort_unstable_by(f64::total_cmp);
    if sorted.is_empty() {
        return Vec::new();
    }
    let threshold = if let Some(fraction) = options.keep_fraction {
        let k = ((fraction.clamp(0.0, 1.0) * sorted.len() as f64).ceil() as usize).clamp(1, sorted.len());
        sorted[k - 1]
    } else if let Some(limit) = options.max_line_distance_mm {
        limit
    } else {
        let mut radii: Vec<f64> = lines.points.iter().map(|p| axis.distance_to(p)).collect();
        radii.sort_unstable_by(f64::total_cmp);
        (3.0 * sorted[sorted.len() / 2]).max(0.005 * radii[radii.len() / 2])
    };
    distances.iter().map(|d| *d <= threshold).collect()
}
