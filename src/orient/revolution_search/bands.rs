//! The score of an axis: every point placed in the rz half-plane and in its band, each
//! band's total-least-squares line, and the robust mean of the points' distances to them.

use nalgebra::Vector2;

use super::loss::{robust_loss, MAX_RADIUS_MM, MAX_TANGENTIAL_NORMAL, MIN_BAND_POINTS, OUTLIER_LOSS};
use super::samples::{floor_index, project, Projected, ProjectedSamples, RevolutionSamples};
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

/// Band tables in one vector: inward walls, outward walls, downward flats and upward flats,
/// each run offset by its least index. A point's slot in it is found once per evaluation
/// and read by every later pass instead of its key.
pub(super) struct Bands<T> {
    pub(super) table: Vec<T>,
    wall_low: i64,
    wall_len: usize,
    flat_low: i64,
    flat_len: usize,
}

/// The number of indices in an inclusive range, 0 where `low > high`.
fn range_len((low, high): (i64, i64)) -> usize {
    (high - low + 1).max(0) as usize
}

impl<T> Bands<T> {
    /// Empty wall bands for indices in `wall_range` (inclusive), and no flat bands yet.
    pub(super) fn walls_only(wall_range: (i64, i64)) -> Self
    where
        T: Default + Clone,
    {
        let wall_len = range_len(wall_range);
        Bands { table: vec![T::default(); 2 * wall_len], wall_low: wall_range.0, wall_len, flat_low: 0, flat_len: 0 }
    }

    /// Adds empty flat bands for indices in `flat_range` (inclusive) after the walls.
    fn add_flats(&mut self, flat_range: (i64, i64))
    where
        T: Default + Clone,
    {
        self.flat_low = flat_range.0;
        self.flat_len = range_len(flat_range);
        self.table.resize(2 * (self.wall_len + self.flat_len), T::default());
    }

    /// Tables of another kind over the same bands.
    pub(super) fn map<U>(&self, f: impl FnMut(&T) -> U) -> Bands<U> {
        Bands { table: self.table.iter().map(f).collect(), wall_low: self.wall_low, wall_len: self.wall_len, flat_low: self.flat_low, flat_len: self.flat_len }
    }

    /// The slot of a band in [`Bands::table`].
    pub(super) fn slot(&self, key: BandKey) -> usize {
        match key {
            BandKey::Wall { outward, index } => outward as usize * self.wall_len + (index - self.wall_low) as usize,
            BandKey::Flat { upward, index } => 2 * self.wall_len + upward as usize * self.flat_len + (index - self.flat_low) as usize,
        }
    }

    /// The wall bands, inward then outward, each by rising index.
    pub(super) fn walls(&self) -> &[T] {
        &self.table[..2 * self.wall_len]
    }
}

/// A point in the rz half-plane of a candidate axis (its height is its [`Projected`]'s)
/// and its band's slot. Kept small: an evaluation writes one per point and reads it back
/// in each later pass.
#[derive(Clone, Copy)]
pub(super) struct Placed {
    pub(super) radius: f64,
    /// The normal's turn out of the meridian plane (its component across it) times the
    /// band width: a residual in millimetres beside the distance to the band's line.
    tangential_mm: f64,
    /// The band's slot in the evaluation's tables ([`Bands::slot`]), [`NO_SLOT`] off
    /// the surface of revolution or before the evaluation has placed it.
    pub(super) slot: u32,
}

/// The slot of a point in no band.
pub(super) const NO_SLOT: u32 = u32::MAX;

/// The point's place under the axis through `centre`, and its band, `None` off the
/// surface of revolution; `band_mm` is the samples' band width, which their wall band
/// indices were taken with.
#[inline]
pub(super) fn place(p: &Projected, centre: &Vector2<f64>, band_mm: f64) -> (Placed, Option<BandKey>) {
    let offset = p.planar - centre;
    let radius = offset.norm();
    if !(radius > 1e-9) || radius > MAX_RADIUS_MM {
        return (Placed { radius, tangential_mm: 0.0, slot: NO_SLOT }, None);
    }
    let radial = offset / radius;
    let normal_radial = p.normal_planar.dot(&radial);
    let normal_tangential = p.normal_planar.x * radial.y - p.normal_planar.y * radial.x;
    let tangential_mm = normal_tangential * band_mm;
    if normal_tangential.abs() > MAX_TANGENTIAL_NORMAL {
        return (Placed { radius, tangential_mm, slot: NO_SLOT }, None);
    }
    let key = if normal_radial.abs() >= p.normal_axial.abs() {
        BandKey::Wall { outward: normal_radial > 0.0, index: p.wall_band }
    } else {
        BandKey::Flat { upward: p.normal_axial > 0.0, index: floor_index(radius / band_mm) }
    };
    (Placed { radius, tangential_mm, slot: NO_SLOT }, Some(key))
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
        self.lines.table.get(at.slot as usize).copied().flatten()
    }
}

/// The distance of the point at `height` placed as `at` from its band's line.
pub(super) fn residual(at: &Placed, height: f64, (mean, normal): BandLine) -> f64 {
    (at.radius - mean[0]) * normal[0] + (height - mean[1]) * normal[1]
}

/// The robust loss of a point on its band: its distance to the band's line and its
/// normal's turn out of the meridian plane (Wilczek et al. 2018, Fig. 1 a and c at once).
fn point_loss(at: &Placed, height: f64, line: BandLine, loss_scale_mm: f64) -> f64 {
    robust_loss(residual(at, height, line).powi(2) + at.tangential_mm.powi(2), loss_scale_mm)
}

/// The robust mean loss of the points about the axis through `centre` along the frame's
/// direction, with the share of the weight on the surface of revolution.
pub(super) fn evaluate_bands(projected: &ProjectedSamples, centre: &Vector2<f64>, loss_scale_mm: f64) -> BandEvaluation {
    let points = &projected.points;
    // The wall bands' range is the direction's; the flat bands' depends on the position
    // and is only known once every point is placed, so their sums wait for a second pass
    // over the few points on them. Each band still sums its points in their order.
    let mut bands: Bands<LineSums> = Bands::walls_only(projected.wall_range);
    let mut placed: Vec<Placed> = Vec::with_capacity(points.len());
    let mut on_flats: Vec<(usize, BandKey)> = Vec::new();
    let mut flat = (i64::MAX, i64::MIN);
    for p in points {
        let (mut at, key) = place(p, centre, projected.band_mm);
        match key {
            Some(key @ BandKey::Wall { .. }) => {
                let slot = bands.slot(key);
                at.slot = slot as u32;
                bands.table[slot].add(at.radius, p.height, p.weight);
            }
            Some(key @ BandKey::Flat { index, .. }) => {
                flat = (flat.0.min(index), flat.1.max(index));
                on_flats.push((placed.len(), key));
            }
            None => {}
        }
        placed.push(at);
    }
    if !on_flats.is_empty() {
        bands.add_flats(flat);
        for &(i, key) in &on_flats {
            let at = &mut placed[i];
            let slot = bands.slot(key);
            at.slot = slot as u32;
            bands.table[slot].add(at.radius, points[i].height, points[i].weight);
        }
    }
    let lines: Bands<Option<BandLine>> = bands.map(LineSums::line);
    let mut evaluation = BandEvaluation { placed, lines, cost: 0.0, inlier_share: 0.0 };
    let (mut total, mut inlier) = (0.0, 0.0);
    for (p, at) in points.iter().zip(&evaluation.placed) {
        match evaluation.line_of(at) {
            Some(line) => {
                total += p.weight * point_loss(at, p.height, line, loss_scale_mm);
                inlier += p.weight;
            }
            None => total += p.weight * OUTLIER_LOSS,
        }
    }
    evaluation.cost = total / projected.weight.max(1e-300);
    evaluation.inlier_share = inlier / projected.weight.max(1e-300);
    evaluation
}

/// Each sample's robust loss under `axis` (no position solved): [`OUTLIER_LOSS`] off the
/// surface of revolution, the loss of its distance to its band's line on it.
pub fn point_losses(samples: &RevolutionSamples, axis: &Axis, loss_scale_mm: f64) -> Vec<f64> {
    let d = axis.direction.into_inner();
    let (e1, e2) = perpendicular_frame(&d);
    let projected = project(samples, &d, &e1, &e2);
    let offset = axis.point - samples.centroid;
    let centre = Vector2::new(offset.dot(&e1), offset.dot(&e2));
    let evaluation = evaluate_bands(&projected, &centre, loss_scale_mm);
    evaluation
        .placed
        .iter()
        .zip(&projected.points)
        .map(|(at, p)| evaluation.line_of(at).map_or(OUTLIER_LOSS, |line| point_loss(at, p.height, line, loss_scale_mm)))
        .collect()
}
