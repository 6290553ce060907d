//! The best axis of one direction: its position solved where the normal lines meet, then
//! from the wall bands' circles, then polished by Gauss-Newton steps on the score itself.

use nalgebra::{Matrix2, Vector2};

use super::bands::{evaluate_bands, place, residual, BandEvaluation, BandKey, Bands, NO_SLOT};
use super::loss::{robust_weight, MIN_BAND_POINTS};
use super::samples::{project, Projected, ProjectedSamples, RevolutionSamples};
use crate::mesh::Vector;
use crate::axis::perpendicular_frame;

// For the doc links only.
#[cfg(doc)]
use super::loss::OUTLIER_LOSS;

/// Scale of the angle by which a normal line may miss the axis in the robust fit of the
/// axis's position (Cauchy weights): a smoothed scan's normals scatter by a few degrees.
const NORMAL_LINE_SCALE_RAD: f64 = 0.05;

/// Second over first eigenvalue of the projected normals' scatter under which a piece is
/// a short arc, whose break faces' normal lines [`normal_line_centre`] first weighs down:
/// the skins' normals over an arc of 2a spread with a ratio of about `a^2 / 3`, so this is
/// an arc of about 110 degrees.
const SHORT_ARC_SPREAD: f64 = 0.3;

/// The best axis of one direction and its score.
#[derive(Clone, Copy, Debug)]
pub struct DirectionFit {
    /// Unit direction (sense arbitrary).
    pub direction: Vector,
    /// The axis's point in the plane through the centroid perpendicular to `direction`,
    /// relative to the centroid, mm.
    pub centre: Vector,
    /// The robust mean loss per unit weight (dimensionless, 0 for a perfect surface of
    /// revolution, [`OUTLIER_LOSS`] when no point is on one).
    pub cost: f64,
    /// Share of the weight on the surface of revolution (normal in the meridian plane, in
    /// a band of enough points).
    pub inlier_share: f64,
    /// Whether the points fix the axis's position for this direction (the wall bands or
    /// the normal lines); a flat piece's do not.
    pub position_fixed: bool,
}

/// Solves the 2x2 system `a x = b` when it is well conditioned (smaller eigenvalue at
/// least `relative` times the larger).
fn solve_conditioned(a: &Matrix2<f64>, b: &Vector2<f64>, relative: f64) -> Option<Vector2<f64>> {
    let trace = a[(0, 0)] + a[(1, 1)];
    let det = a.determinant();
    let disc = ((a[(0, 0)] - a[(1, 1)]).powi(2) + 4.0 * a[(0, 1)] * a[(1, 0)]).max(0.0).sqrt();
    let (small, large) = ((trace - disc) / 2.0, (trace + disc) / 2.0);
    if !(large > 0.0) || !(small >= relative * large) || det == 0.0 {
        return None;
    }
    a.try_inverse().map(|inverse| inverse * b)
}

/// Where the normal lines, projected on the plane perpendicular to the direction, meet:
/// the weighted least-squares point, reweighted by the angle at which each line misses it
/// (Cauchy, `scale_rad`). `None` when the projected normals are nearly parallel (a flat
/// piece).
///
/// The skins' normals are mostly radial, those of the breaks between them mostly across
/// the radius: on a short arc the skins' lines are nearly parallel, and the breaks' lines,
/// which run through the sherd, would pin the point onto the sherd. So where the projected
/// normals keep to one direction (the second eigenvalue of their scatter under
/// [`SHORT_ARC_SPREAD`] of the first), each line is first weighted by the fourth power of
/// its alignment with it (the mean radial direction).
fn normal_line_centre(points: &[Projected], scale_rad: f64) -> Option<Vector2<f64>> {
    let mut scatter = Matrix2::zeros();
    for p in points {
        scatter += p.normal_planar * p.normal_planar.transpose() * p.weight;
    }
    let eigen = nalgebra::SymmetricEigen::new(scatter);
    let (large, small) = if eigen.eigenvalues[0] >= eigen.eigenvalues[1] { (0, 1) } else { (1, 0) };
    let main = eigen.eigenvectors.column(large);
    let main = Vector2::new(main[0], main[1]);
    let short_arc = eigen.eigenvalues[small] < SHORT_ARC_SPREAD * eigen.eigenvalues[large];
    let prior: Vec<f64> = points
        .iter()
        .map(|p| {
            let length = p.normal_planar.norm();
            let alignment = if length > 1e-9 { p.normal_planar.dot(&main) / length } else { 0.0 };
            if short_arc { p.weight * alignment.powi(4) } else { p.weight }
        })
        .collect();
    let mut centre: Option<Vector2<f64>> = None;
    for _ in 0..3 {
        let (mut a, mut b) = (Matrix2::zeros(), Vector2::zeros());
        for (p, prior) in points.iter().zip(&prior) {
            // The line through `planar` along `normal_planar`: its normal is `perp`.
            let perp = Vector2::new(p.normal_planar.y, -p.normal_planar.x);
            let mut w = *prior;
            if let Some(c) = centre {
                let length = perp.norm();
                let reach = (c - p.planar).norm();
                if length < 1e-6 || reach < 1e-9 {
                    continue;
                }
                let angle = perp.dot(&(c - p.planar)) / (length * reach);
                w /= 1.0 + (angle / scale_rad).powi(2);
            }
            a += perp * perp.transpose() * w;
            b += perp * perp.dot(&p.planar) * w;
        }
        centre = Some(solve_conditioned(&a, &b, 1e-4)?);
    }
    centre
}

/// The position from the circles of the wall bands, linearised (Kåsa): in every band the
/// squared radius about the axis is `|q|^2 - 2 q.c + |c|^2`, a line in the height with the
/// band's own coefficients, so after the band's own mean and slope are projected out
/// `|q|^2` is linear in `c` alone. Solved about `start`; `None` when the bands do not fix
/// it (too few, or all on one short arc in one direction).
fn wall_circles_centre(projected: &ProjectedSamples, start: &Vector2<f64>) -> Option<Vector2<f64>> {
    // Per band: sums of w times 1, h, h^2, and of x, y, Q and their products with h, and
    // the cross products, for the projection onto the complement of [1, h].
    #[derive(Clone, Copy, Default)]
    struct KasaSums {
        count: usize,
        s: [f64; 14],
    }
    let band_mm = projected.band_mm;
    let mut bands: Bands<KasaSums> = Bands::walls_only(projected.wall_range);
    for p in &projected.points {
        let Some(key @ BandKey::Wall { .. }) = place(p, start, band_mm).1 else { continue };
        let q = p.planar - start;
        let (x, y, h) = (q.x, q.y, p.height);
        let big_q = x * x + y * y;
        let w = p.weight;
        let slot = bands.slot(key);
        let sums = &mut bands.table[slot];
        sums.count += 1;
        let s = &mut sums.s;
        s[0] += w;
        s[1] += w * h;
        s[2] += w * h * h;
        s[3] += w * x;
        s[4] += w * y;
        s[5] += w * big_q;
        s[6] += w * h * x;
        s[7] += w * h * y;
        s[8] += w * h * big_q;
        s[9] += w * x * x;
        s[10] += w * x * y;
        s[11] += w * y * y;
        s[12] += w * x * big_q;
        s[13] += w * y * big_q;
    }
    let (mut a, mut b) = (Matrix2::zeros(), Vector2::zeros());
    let mut used = 0;
    for sums in bands.walls() {
        if sums.count < MIN_BAND_POINTS {
            continue;
        }
        let s = &sums.s;
        // A band whose points all lie at one height (one row of a regular grid) has no
        // slope to project out, and its moment matrix is singular up to rounding: only
        // its mean is projected out there.
        let height_variance = s[2] / s[0] - (s[1] / s[0]).powi(2);
        let m_inverse = if height_variance > 1e-6 * band_mm * band_mm {
            let Some(inverse) = Matrix2::new(s[0], s[1], s[1], s[2]).try_inverse() else { continue };
            inverse
        } else {
            Matrix2::new(1.0 / s[0], 0.0, 0.0, 0.0)
        };
        // Projected covariance of u and v: S_uv - [S_u, S_hu] M^-1 [S_v, S_hv]^T.
        let first = |u_sum: f64, hu_sum: f64| Vector2::new(u_sum, hu_sum);
        let (fx, fy, fq) = (first(s[3], s[6]), first(s[4], s[7]), first(s[5], s[8]));
        let cov = |uv: f64, fu: &Vector2<f64>, fv: &Vector2<f64>| uv - fu.dot(&(m_inverse * fv));
        let cxx = cov(s[9], &fx, &fx);
        let cxy = cov(s[10], &fx, &fy);
        let cyy = cov(s[11], &fy, &fy);
        let cxq = cov(s[12], &fx, &fq);
        let cyq = cov(s[13], &fy, &fq);
        // Algebraic residuals of squared radii are 2 r times the geometric ones.
        let mean_square_radius = (s[5] / s[0]).max(1e-12);
        let band_weight = 1.0 / (4.0 * mean_square_radius);
        a += Matrix2::new(cxx, cxy, cxy, cyy) * band_weight;
        b += Vector2::new(cxq, cyq) * band_weight;
        used += 1;
    }
    if used < 2 {
        return None;
    }
    solve_conditioned(&a, &(b / 2.0), 1e-6).map(|shift| start + shift)
}

/// One robust Gauss-Newton step of the axis's position on the band residuals: each
/// residual moves with the centre by the band line's radial normal times the radial
/// direction, less its band's mean move (the band's line follows its points' mean), and
/// the Cauchy weights of the loss. `None` when the bands do not fix the position.
fn position_step(projected: &ProjectedSamples, evaluation: &BandEvaluation, centre: &Vector2<f64>, loss_scale_mm: f64) -> Option<Vector2<f64>> {
    #[derive(Clone, Copy, Default)]
    struct MeanMove {
        weight: f64,
        sum: Vector2<f64>,
    }
    let mut moves: Bands<MeanMove> = evaluation.lines.map(|_| MeanMove::default());
    let mut rows: Vec<(u32, Vector2<f64>, f64, f64)> = Vec::with_capacity(projected.points.len());
    for (p, at) in projected.points.iter().zip(&evaluation.placed) {
        let Some(line) = evaluation.line_of(at) else {
            rows.push((NO_SLOT, Vector2::zeros(), 0.0, 0.0));
            continue;
        };
        let r = residual(at, p.height, line);
        let radial = (p.planar - centre) / at.radius;
        let jacobian = -radial * line.1[0];
        let w = p.weight * robust_weight(r, loss_scale_mm);
        let entry = &mut moves.table[at.slot as usize];
        entry.weight += w;
        entry.sum += jacobian * w;
        rows.push((at.slot, jacobian, r, w));
    }
    let (mut normal, mut rhs) = (Matrix2::zeros(), Vector2::zeros());
    for (slot, jacobian, r, w) in rows {
        if slot == NO_SLOT {
            continue;
        }
        let mean = &moves.table[slot as usize];
        let centred = jacobian - mean.sum / mean.weight.max(1e-300);
        normal += centred * centred.transpose() * w;
        rhs += centred * (r * w);
    }
    solve_conditioned(&normal, &(-rhs), 1e-6)
}

/// The position polished by robust Gauss-Newton steps from `start`, each kept only where
/// it lowers the score (halved up to three times otherwise).
fn polish_position(projected: &ProjectedSamples, start: Vector2<f64>, loss_scale_mm: f64, steps: usize) -> (Vector2<f64>, BandEvaluation) {
    let mut centre = start;
    let mut evaluation = evaluate_bands(projected, &centre, loss_scale_mm);
    for _ in 0..steps {
        let Some(step) = position_step(projected, &evaluation, &centre, loss_scale_mm) else { break };
        let mut scale = 1.0;
        let mut improved = false;
        for _ in 0..4 {
            let candidate = centre + step * scale;
            let trial = evaluate_bands(projected, &candidate, loss_scale_mm);
            if trial.cost < evaluation.cost {
                centre = candidate;
                evaluation = trial;
                improved = true;
                break;
            }
            scale *= 0.5;
        }
        if !improved || (step * scale).norm() < 1e-3 {
            break;
        }
    }
    (centre, evaluation)
}

/// The best axis along `direction` and its score: the position where the normal lines
/// meet, then by the wall bands' circles, the better of the two polished by robust
/// Gauss-Newton steps on the score itself.
pub fn fit_direction(samples: &RevolutionSamples, direction: &Vector, loss_scale_mm: f64) -> DirectionFit {
    fit_direction_with(samples, direction, loss_scale_mm, POLISH_STEPS)
}

/// Gauss-Newton steps of [`fit_direction`].
const POLISH_STEPS: usize = 4;

pub(super) fn fit_direction_with(samples: &RevolutionSamples, direction: &Vector, loss_scale_mm: f64, polish_steps: usize) -> DirectionFit {
    let d = direction.normalize();
    let (e1, e2) = perpendicular_frame(&d);
    let projected = project(samples, &d, &e1, &e2);
    let (centre, position_fixed) = match normal_line_centre(&projected.points, NORMAL_LINE_SCALE_RAD) {
        Some(by_normals) => {
            // The circles' fit is exact on a surface of revolution and the normals' is not;
            // where the walls give no circles the polish starts from the normals'.
            (wall_circles_centre(&projected, &by_normals).unwrap_or(by_normals), true)
        }
        // No position: a flat piece, scored about its centroid's line.
        None => (Vector2::zeros(), false),
    };
    let (centre, evaluation) = if position_fixed {
        polish_position(&projected, centre, loss_scale_mm, polish_steps)
    } else {
        let evaluation = evaluate_bands(&projected, &centre, loss_scale_mm);
        (centre, evaluation)
    };
    DirectionFit {
        direction: d,
        centre: e1 * centre.x + e2 * centre.y,
        cost: evaluation.cost,
        inlier_share: evaluation.inlier_share,
        position_fixed,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use super::super::test_patch::patch;

    #[test]
    fn the_true_direction_gets_the_true_position() {
        let lines = patch(30.0, -20.0, |z| 80.0 + 0.3 * z, |_| 0.3, (0.2, 0.9), (0.0, 50.0));
        let samples = RevolutionSamples::from_lines(&lines, 10_000, 2.5, 1.0).unwrap();
        let fit = fit_direction(&samples, &Vector::z(), 0.25 * samples.band_mm);
        let centre = samples.centroid + fit.centre;
        assert!((centre.x - 30.0).abs() < 0.1 && (centre.y + 20.0).abs() < 0.1, "{centre:?} cost {}", fit.cost);
        assert!(fit.cost < 0.01, "cost {}", fit.cost);
    }
}
