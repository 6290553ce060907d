//! The axis's position from the normal lines once its direction is known (Wilczek et
//! al. 2018, Eq. 1 with the direction held): every normal of a surface of revolution
//! meets the axis, so with the axis vertical the horizontal part of each normal line
//! passes through the axis's footprint, a point of the plane found by least squares.
//!
//! Why: a base levelled by its tangent plane (Eq. 7) has its direction to a few
//! hundredths of a degree, but its position must come from elsewhere. Eq. 2 needs
//! horizontal sections through the skins, and a floor with only the turn of its foot
//! (a few millimetres of height) gives none that Eq. 2 can use, while the start axis from
//! the normals is pulled tens of millimetres off by the floor's near-vertical normals.
//! The turn's normals, nearly horizontal, point straight at the axis.
//!
//! The floor's own normals (nearly vertical) carry no position and are left out. Break
//! faces running along a radius have tangential normals that miss the axis by the
//! radius: a sample-consensus start over pairs of lines, then an iteratively reweighted
//! fit (Tukey's biweight), leave them out. The position is returned only when its
//! standard error, inflated for the correlation of neighbouring normals, is small.

use std::collections::HashMap;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::sections::{AxisParameters, CandidateFrame, PreparedSurface};
use crate::mesh::{Mesh, Point, Vector};

/// Normals closer to the axis's direction than this carry no position (floors, lip tops).
const MIN_HORIZONTAL_NORMAL: f64 = 0.34; // sin 20 degrees
/// Side of the cubes the faces are gathered in, mm (see [`place_by_normal_lines`]).
const PATCH_MM: f64 = 2.0;
/// Width of the bins of the direction a face faces (its normal's azimuth) within a cube,
/// radians: a skin and the break face beside it are not averaged.
const FACING_BIN_RAD: f64 = std::f64::consts::FRAC_PI_4;
/// Fewest lines the placement works on.
const MIN_LINES: usize = 30;
/// Pairs of lines tried by the consensus start.
const CONSENSUS_PAIRS: usize = 300;
/// A line agrees with a candidate footprint when it passes within this angle of it, as
/// seen from the line's face (face normals of a scan deviate by a degree or two).
const CONSENSUS_ANGLE_DEG: f64 = 3.0;
/// The consensus counts agreement on at most this many lines (an even stride of all).
const CONSENSUS_SAMPLE: usize = 4000;
/// Reweighting rounds after the consensus start.
const REWEIGHT_ROUNDS: usize = 8;
/// Neighbouring faces share vertices, and so their normals' noise: the standard error
/// from independent residuals is multiplied by this.
const CORRELATION_INFLATION: f64 = 5.0;
/// The placement is kept when its inflated standard error is at most this, mm
/// (`docs/calibration.md`).
pub const MAX_POSITION_ERROR_MM: f64 = 1.0;
/// ... and when at least this share of the lines agree with it ...
const MIN_AGREEING_SHARE: f64 = 0.3;
/// ... and their angles' robust spread is at most this (sine): a fit of scattered
/// normals has a small standard error only because there are many.
const MAX_ANGLE_SPREAD: f64 = 0.1;

/// A horizontal normal line: the face's footprint and the unit horizontal direction of
/// its normal.
#[derive(Clone, Copy, Debug)]
struct PlanarLine {
    point: [f64; 2],
    normal: [f64; 2],
}

impl PlanarLine {
    /// Signed distance from `centre` to the line.
    fn distance(&self, centre: [f64; 2]) -> f64 {
        (centre[0] - self.point[0]) * -self.normal[1] + (centre[1] - self.point[1]) * self.normal[0]
    }

    /// How much the line's distance counts for a footprint at `centre`: the residual is
    /// the angle at which the line misses it, seen from the face (normals are noisy in
    /// angle), the distance times this.
    fn gain(&self, centre: [f64; 2]) -> f64 {
        1.0 / (centre[0] - self.point[0]).hypot(centre[1] - self.point[1]).max(1.0)
    }

    /// The sine of the angle at which the line misses `centre`, seen from its face.
    fn residual(&self, centre: [f64; 2]) -> f64 {
        self.distance(centre) * self.gain(centre)
    }
}

/// Where two lines cross, `None` when they are within a degree of parallel.
fn crossing(a: &PlanarLine, b: &PlanarLine) -> Option<[f64; 2]> {
    let determinant = a.normal[0] * b.normal[1] - a.normal[1] * b.normal[0];
    if determinant.abs() < 0.017 {
        return None;
    }
    let dx = [b.point[0] - a.point[0], b.point[1] - a.point[1]];
    let t = (dx[0] * b.normal[1] - dx[1] * b.normal[0]) / determinant;
    Some([a.point[0] + t * a.normal[0], a.point[1] + t * a.normal[1]])
}

/// The footprint minimising the weighted squared distances, and the inverse of the 2x2
/// normal matrix; `None` when the lines do not fix a point.
fn weighted_footprint(lines: &[PlanarLine], weights: &[f64]) -> Option<([f64; 2], [[f64; 2]; 2])> {
    // distance = c . m - p . m with m = (-n_y, n_x)
    let (mut a00, mut a01, mut a11, mut b0, mut b1) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (line, &w) in lines.iter().zip(weights) {
        let m = [-line.normal[1], line.normal[0]];
        let q = line.point[0] * m[0] + line.point[1] * m[1];
        a00 += w * m[0] * m[0];
        a01 += w * m[0] * m[1];
        a11 += w * m[1] * m[1];
        b0 += w * m[0] * q;
        b1 += w * m[1] * q;
    }
    let determinant = a00 * a11 - a01 * a01;
    if !(determinant > 1e-12 * (a00 + a11).powi(2)) {
        return None;
    }
    let inverse = [[a11 / determinant, -a01 / determinant], [-a01 / determinant, a00 / determinant]];
    let centre = [inverse[0][0] * b0 + inverse[0][1] * b1, inverse[1][0] * b0 + inverse[1][1] * b1];
    Some((centre, inverse))
}

/// The placement found: the axis parameters and its inflated standard error.
#[derive(Clone, Copy, Debug)]
pub struct NormalLinePlacement {
    /// The axis with the direction of the candidate and the position of the normals.
    pub parameters: AxisParameters,
    /// Inflated standard error of the position along its worst direction, mm.
    pub position_error_mm: f64,
    /// Share of the lines that agree with the position.
    pub agreeing_share: f64,
}

/// The axis with the tilts of `tilted` placed where the horizontal parts of the
/// normals meet, with its standard error; `None` when too few normals are horizontal
/// enough, they do not agree on a point, or the point is not fixed to
/// [`MAX_POSITION_ERROR_MM`].
pub fn place_by_normal_lines(mesh: &Mesh, surface: &PreparedSurface, tilted: AxisParameters) -> Option<NormalLinePlacement> {
    let frame = CandidateFrame::new(&tilted);
    // Face normals, not vertex normals: a vertex on the border of a skin and a break face
    // averages the two, and its line misses the axis by much of the radius. The faces are
    // gathered into patches of about the corpus's 2 mm cells first (`PATCH_MM`), each
    // patch's lines by the direction they face: a fine mesh's faces turn with the scan's
    // noise (0.02 mm over 0.8 mm edges is two degrees), and counted one by one they
    // made a footprint far along a short arc's lines look fixed (a base placed 56 mm off
    // from 5,600 lines of 0.8 mm faces, its standard error 0.6 mm).
    // Per patch (cube and facing): the sum of its faces' cross products and of their
    // centres weighted by the cross products' lengths.
    let mut patches: HashMap<[i64; 4], (Vector, Vector)> = HashMap::new();
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|v| frame.apply(&surface.points[v as usize]));
        let n = (b - a).cross(&(c - a));
        let length = n.norm();
        let horizontal = n.x.hypot(n.y);
        if !(horizontal >= MIN_HORIZONTAL_NORMAL * length) || !(length > 0.0) {
            continue;
        }
        let centre = (a.coords + b.coords + c.coords) / 3.0;
        let facing = (n.y.atan2(n.x) / FACING_BIN_RAD).floor() as i64;
        let key = [(centre.x / PATCH_MM).floor() as i64, (centre.y / PATCH_MM).floor() as i64, (centre.z / PATCH_MM).floor() as i64, facing];
        let entry = patches.entry(key).or_insert((Vector::zeros(), Vector::zeros()));
        entry.0 += n;
        entry.1 += centre * length;
    }
    let mut keyed: Vec<_> = patches.into_iter().collect();
    keyed.sort_unstable_by_key(|(key, _)| *key);
    let lines: Vec<PlanarLine> = keyed
        .into_iter()
        .filter_map(|(_, (n, weighted_centre))| {
            let length = n.norm();
            let horizontal = n.x.hypot(n.y);
            if !(horizontal >= MIN_HORIZONTAL_NORMAL * length) || !(length > 0.0) {
                return None;
            }
            let centre = weighted_centre / length;
            Some(PlanarLine { point: [centre.x, centre.y], normal: [n.x / horizontal, n.y / horizontal] })
        })
        .collect();
    let footprint = footprint(&lines)?;
    let direction = frame.direction();
    let on_axis = frame.to_start(&Point::new(footprint.centre[0], footprint.centre[1], 0.0));
    let at_zero = on_axis + direction * (-on_axis.z / direction.z);
    Some(NormalLinePlacement {
        parameters: [tilted[0], tilted[1], at_zero.x, at_zero.y],
        position_error_mm: footprint.position_error_mm,
        agreeing_share: footprint.agreeing_share,
    })
}

/// Where the lines meet, when they agree on one point closely enough.
struct Footprint {
    centre: [f64; 2],
    position_error_mm: f64,
    agreeing_share: f64,
}

/// The robust meeting point of `lines`: a consensus start over pairs, then Tukey
/// reweighting of the angles at which the lines miss it.
fn footprint(lines: &[PlanarLine]) -> Option<Footprint> {
    if lines.len() < MIN_LINES {
        return None;
    }
    // A line agrees with a footprint when it misses it by a small angle.
    let tolerance = CONSENSUS_ANGLE_DEG.to_radians().sin();
    let agrees = |line: &PlanarLine, centre: [f64; 2]| line.residual(centre).abs() <= tolerance;
    let sample: Vec<PlanarLine> = lines.iter().step_by(lines.len().div_ceil(CONSENSUS_SAMPLE)).copied().collect();
    let mut rng = ChaCha8Rng::seed_from_u64(0x5ee0);
    let mut best: Option<([f64; 2], usize)> = None;
    for _ in 0..CONSENSUS_PAIRS {
        let (i, j) = (rng.random_range(0..sample.len()), rng.random_range(0..sample.len()));
        let Some(centre) = crossing(&sample[i], &sample[j]) else { continue };
        let count = sample.iter().filter(|l| agrees(l, centre)).count();
        if best.is_none_or(|(_, c)| count > c) {
            best = Some((centre, count));
        }
    }
    let (mut centre, _) = best?;
    let mut weights = vec![0.0; lines.len()];
    let mut inverse = [[0.0; 2]; 2];
    let mut scale = 0.0;
    for _ in 0..REWEIGHT_ROUNDS {
        let residuals: Vec<f64> = lines.iter().map(|l| l.residual(centre)).collect();
        let mut magnitudes: Vec<f64> = residuals.iter().map(|r| r.abs()).collect();
        magnitudes.sort_unstable_by(f64::total_cmp);
        scale = (1.4826 * magnitudes[magnitudes.len() / 2]).max(tolerance / 4.0);
        for ((w, r), line) in weights.iter_mut().zip(&residuals).zip(lines) {
            *w = tukey_weight(r / scale, 4.685) * line.gain(centre).powi(2);
        }
        let (next, next_inverse) = weighted_footprint(lines, &weights)?;
        centre = next;
        inverse = next_inverse;
    }
    let agreeing = lines.iter().filter(|l| agrees(l, centre)).count();
    // Residual variance of the angles over the lines that count.
    let (mut sum, mut weight_sum) = (0.0, 0.0);
    for line in lines {
        let r = line.residual(centre);
        let w = tukey_weight(r / scale, 4.685);
        sum += w * r * r;
        weight_sum += w;
    }
    if !(weight_sum > 0.0) || scale <= 0.0 {
        return None;
    }
    let variance = sum / weight_sum;
    let trace = inverse[0][0] + inverse[1][1];
    let determinant = inverse[0][0] * inverse[1][1] - inverse[0][1] * inverse[1][0];
    let largest_eigenvalue = trace / 2.0 + ((trace / 2.0).powi(2) - determinant).max(0.0).sqrt();
    // `inverse` is of the weighted gains: the variance of the estimate is the residuals'
    // variance times it.
    let position_error_mm = CORRELATION_INFLATION * (variance * largest_eigenvalue).sqrt();
    let agreeing_share = agreeing as f64 / lines.len() as f64;
    (position_error_mm <= MAX_POSITION_ERROR_MM && agreeing_share >= MIN_AGREEING_SHARE && scale <= MAX_ANGLE_SPREAD)
        .then_some(Footprint { centre, position_error_mm, agreeing_share })
}

/// Tukey's biweight IRLS weight `psi(t)/t` (up to a constant): 0 beyond `c`, so that a
/// line that misses the axis by more than `c` scales carries no weight.
fn tukey_weight(t: f64, c: f64) -> f64 {
    let u = t / c;
    if u.abs() >= 1.0 {
        0.0
    } else {
        let v = 1.0 - u * u;
        v * v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Lines from an arc of `arc_deg` at `radius_mm` about `centre`, every `outlier_every`-th
    /// one turned 90 degrees (a break face along a radius).
    fn arc_lines(centre: [f64; 2], radius_mm: f64, arc_deg: f64, count: usize, outlier_every: usize) -> Vec<PlanarLine> {
        (0..count)
            .map(|k| {
                let angle = (arc_deg * k as f64 / count as f64).to_radians();
                let (sin, cos) = angle.sin_cos();
                // A small deterministic wobble of the normal, about half a degree.
                let wobble = 0.009 * ((k * 7919) % 13) as f64 / 13.0 - 0.0045;
                let (ws, wc) = wobble.sin_cos();
                let mut normal = [cos * wc - sin * ws, sin * wc + cos * ws];
                if outlier_every > 0 && k % outlier_every == 0 {
                    normal = [-normal[1], normal[0]];
                }
                PlanarLine { point: [centre[0] + radius_mm * cos, centre[1] + radius_mm * sin], normal }
            })
            .collect()
    }

    #[test]
    fn the_lines_of_an_arc_meet_at_its_centre_despite_break_faces() {
        let lines = arc_lines([3.0, -2.0], 80.0, 60.0, 600, 3);
        let found = footprint(&lines).expect("a 60 degree arc fixes its centre");
        assert!((found.centre[0] - 3.0).hypot(found.centre[1] + 2.0) < 0.2, "{:?}", found.centre);
        assert!(found.position_error_mm < MAX_POSITION_ERROR_MM);
        assert!((found.agreeing_share - 2.0 / 3.0).abs() < 0.05, "{}", found.agreeing_share);
    }

    #[test]
    fn lines_that_meet_nowhere_or_barely_turn_give_no_position() {
        // Two degrees of arc: the lines are nearly parallel and the centre slides along them.
        assert!(footprint(&arc_lines([0.0, 0.0], 80.0, 2.0, 600, 0)).is_none());
        // Every direction at random: no point is met by a third of them.
        let scattered: Vec<PlanarLine> = (0..600)
            .map(|k| {
                let angle = ((k * 2654435761usize) % 360) as f64;
                let (sin, cos) = angle.to_radians().sin_cos();
                PlanarLine { point: [(k % 37) as f64 * 3.0, (k % 23) as f64 * 4.0], normal: [cos, sin] }
            })
            .collect();
        assert!(footprint(&scattered).is_none());
    }
}
