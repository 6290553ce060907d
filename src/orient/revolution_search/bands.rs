//! The score of an axis: every point placed in the rz half-plane and in its band, each
//! band's total-least-squares line, and the robust mean of the points' distances to them.

use nalgebra::Vector2;

use super::loss::{robust_loss, MAX_RADIUS_MM, MAX_TANGENTIAL_NORMAL, MIN_BAND_POINTS, OUTLIER_LOSS};
use super::samples::{project, Projected, RevolutionSamples};
use crate::axis::Axis;
use crate::axis::perpendicular_frame;

/// The band of a point under an axis: wall bands by height, flat bands by radius, each
/// side apart.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum BandKey {
    Wall { outward: bool, index: i64 },
    Flat { upward: bool, index: i64 },
}

/// The line sums of one band in the rz half-plane.
#[derive(Clone, Copy, Default)]
struct LineSums {
    count: usize,
    w: f64,
    r: f64,
    z: f64,
    rr: f64,
    rz: f64,
    zz: f64,
}

impl LineSums {
    fn add(&mut self, r: f64, z: f64, w: f64) {
        self.count += 1;
        self.w += w;
        self.r += w * r;
        self.z += w * z;
        self.rr += w * r * r;
        self.rz += w * r * z;
        self.zz += w * z * z;
    }

    /// The total-least-squares line: its mean point and unit normal.
    fn line(&self) -> Option<([f64; 2], [f64; 2])> {
        if self.count < MIN_BAND_POINTS || !(self.w > 0.0) {
            return None;
        }
        let (mr, mz) = (self.r / self.w, self.z / self.w);
        let crr = self.rr / self.w - mr * mr;
        let crz = self.rz / self.w - mr * mz;
        let czz = self.zz / self.w - mz * mz;
        // The normal is the eigenvector of the smaller eigenvalue of the 2x2 scatter.
        let angle = 0.5 * (2.0 * crz).atan2(crr - czz); // direction of the line
        Some(([mr, mz], [-angle.sin(), angle.cos()]))
    }
}

/// Band tables indexed by key: a vector per kind and side, offset by the least index.
pub(super) struct Bands<T> {
    pub(super) wall: [Vec<T>; 2],
    pub(super) flat: [Vec<T>; 2],
    pub(super) wall_low: i64,
    pub(super) flat_low: i64,
}

impl<T: Default + Clone> Bands<T> {
    pub(super) fn new(wall_range: (i64, i64), flat_range: (i64, i64)) -> Self {
        let wall_len = (wall_range.1 - wall_range.0 + 1).max(0) as usize;
        let flat_len = (flat_range.1 - flat_range.0 + 1).max(0) as usize;
        Bands {
            wall: [vec![T::default(); wall_len], vec![T::default(); wall_len]],
            flat: [vec![T::default(); flat_len], vec![T::default(); flat_len]],
            wall_low: wall_range.0,
            flat_low: flat_range.0,
        }
    }

    pub(super) fn get_mut(&mut self, key: BandKey) -> &mut T {
        match key {
            BandKey::Wall { outward, index } => &mut self.wall[outward as usize][(index - self.wall_low) as usize],
            BandKey::Flat { upward, index } => &mut self.flat[upward as usize][(index - self.flat_low) as usize],
        }
    }

    pub(super) fn get(&self, key: BandKey) -> &T {
        match key {
            BandKey::Wall { outward, index } => &self.wall[outward as usize][(index - self.wall_low) as usize],
            BandKey::Flat { upward, index } => &self.flat[upward as usize][(index - self.flat_low) as usize],
        }
    }
}

/// A point in the rz half-plane of a candidate axis with its band, or `None` off the
/// surface of revolution.
#[derive(Clone, Copy)]
pub(super) struct Placed {
    pub(super) radius: f64,
    height: f64,
    /// The normal's turn out of the meridian plane (its component across it) times the
    /// band width: a residual in millimetres beside the distance to the band's line.
    tangential_mm: f64,
    pub(super) key: Option<BandKey>,
}

/// `value.floor() as i64` without `f64::floor`, which is a call into libm on the baseline
/// target and was a twentieth of the search's instructions (placing every point in its
/// band, for every candidate axis).
fn floor_index(value: f64) -> i64 {
    let truncated = value as i64;
    truncated.saturating_sub(((truncated as f64) > value) as i64)
}

pub(super) fn place(p: &Projected, centre: &Vector2<f64>, band_mm: f64) -> Placed {
    let offset = p.planar - centre;
    let radius = offset.norm();
    if !(radius > 1e-9) || radius > MAX_RADIUS_MM {
        return Placed { radius, height: p.height, tangential_mm: 0.0, key: None };
    }
    let radial = offset / radius;
    let normal_radial = p.normal_planar.dot(&radial);
    let normal_tangential = p.normal_planar.x * radial.y - p.normal_planar.y * radial.x;
    let tangential_mm = normal_tangential * band_mm;
    if normal_tangential.abs() > MAX_TANGENTIAL_NORMAL {
        return Placed { radius, height: p.height, tangential_mm, key: None };
    }
    let key = if normal_radial.abs() >= p.normal_axial.abs() {
        BandKey::Wall { outward: normal_radial > 0.0, index: floor_index(p.height / band_mm) }
    } else {
        BandKey::Flat { upward: p.normal_axial > 0.0, index: floor_index(radius / band_mm) }
    };
    Placed { radius, height: p.height, tangential_mm, key: Some(key) }
}

/// A band's total-least-squares line in the rz half-plane: its mean point and unit normal.
pub(super) type BandLine = ([f64; 2], [f64; 2]);

/// The points of a candidate axis in its rz half-plane, their bands' lines and the score.
pub(super) struct BandEvaluation {
    pub(super) placed: Vec<Placed>,
    pub(super) lines: Bands<Option<BandLine>>,
    pub(super) cost: f64,
    pub(super) inlier_share: f64,
}

impl BandEvaluation {
    /// The line of a placed point's band, if it has one.
    pub(super) fn line_of(&self, at: &Placed) -> Option<BandLine> {
        at.key.and_then(|key| *self.lines.get(key))
    }
}

pub(super) fn residual(at: &Placed, (mean, normal): BandLine) -> f64 {
    (at.radius - mean[0]) * normal[0] + (at.height - mean[1]) * normal[1]
}

/// The robust loss of a point on its band: its distance to the band's line and its
/// normal's turn out of the meridian plane (Wilczek et al. 2018, Fig. 1 a and c at once).
fn point_loss(at: &Placed, line: BandLine, loss_scale_mm: f64) -> f64 {
    robust_loss(residual(at, line).powi(2) + at.tangential_mm.powi(2), loss_scale_mm)
}

/// The robust mean loss of the points about the axis through `centre` along the frame's
/// direction, with the share of the weight on the surface of revolution.
pub(super) fn evaluate_bands(points: &[Projected], centre: &Vector2<f64>, band_mm: f64, loss_scale_mm: f64) -> BandEvaluation {
    let placed: Vec<Placed> = points.iter().map(|p| place(p, centre, band_mm)).collect();
    let (mut wall, mut flat) = ((i64::MAX, i64::MIN), (i64::MAX, i64::MIN));
    for p in &placed {
        match p.key {
            Some(BandKey::Wall { index, .. }) => wall = (wall.0.min(index), wall.1.max(index)),
            Some(BandKey::Flat { index, .. }) => flat = (flat.0.min(index), flat.1.max(index)),
            None => {}
        }
    }
    let mut bands: Bands<LineSums> = Bands::new(wall, flat);
    for (p, at) in points.iter().zip(&placed) {
        if let Some(key) = at.key {
            bands.get_mut(key).add(at.radius, at.height, p.weight);
        }
    }
    let lines: Bands<Option<BandLine>> = Bands {
        wall: bands.wall.map(|v| v.iter().map(LineSums::line).collect()),
        flat: bands.flat.map(|v| v.iter().map(LineSums::line).collect()),
        wall_low: bands.wall_low,
        flat_low: bands.flat_low,
    };
    let mut evaluation = BandEvaluation { placed, lines, cost: 0.0, inlier_share: 0.0 };
    let (mut total, mut weight, mut inlier) = (0.0, 0.0, 0.0);
    for (p, at) in points.iter().zip(&evaluation.placed) {
        weight += p.weight;
        match evaluation.line_of(at) {
            Some(line) => {
                total += p.weight * point_loss(at, line, loss_scale_mm);
                inlier += p.weight;
            }
            None => total += p.weight * OUTLIER_LOSS,
        }
    }
    evaluation.cost = total / weight.max(1e-300);
    evaluation.inlier_share = inlier / weight.max(1e-300);
    evaluation
}

/// Each sample's robust loss under `axis` (no position solved): [`OUTLIER_LOSS`] off the
/// surface of revolution, the loss of its distance to its band's line on it.
pub fn point_losses(samples: &RevolutionSamples, axis: &Axis, loss_scale_mm: f64) -> Vec<f64> {
    let d = axis.direction.into_inner();
    let (e1, e2) = perpendicular_frame(&d);
    let points = project(samples, &d, &e1, &e2);
    let offset = axis.point - samples.centroid;
    let centre = Vector2::new(offset.dot(&e1), offset.dot(&e2));
    let evaluation = evaluate_bands(&points, &centre, samples.band_mm, loss_scale_mm);
    evaluation
        .placed
        .iter()
        .map(|at| evaluation.line_of(at).map_or(OUTLIER_LOSS, |line| point_loss(at, line, loss_scale_mm)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floor_index_is_floor() {
        for value in [-2.5, -2.0, -1e-12, -0.0, 0.0, 1e-12, 0.999_999, 1.0, 3.5, 1e20, -1e20, f64::NAN] {
            assert_eq!(floor_index(value), value.floor() as i64, "{value}");
        }
    }
}
