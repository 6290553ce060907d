//! The axis from the linear line complex of the normal lines (Pottmann, Peternell and
//! Ravani 1999, "An introduction to line geometry with applications", section on
//! surfaces of revolution; the initialiser PotSAC samples).
//!
//! A line with direction `n` and moment `m = p x n` belongs to the linear complex
//! `(c, c̄)` when `c·m + c̄·n = 0`. The normals of a surface of revolution all meet the
//! axis `(a, ā = q x a)`, i.e. they belong to the complex `(a, ā)`. The complex
//! minimising `Σ w (c·m + c̄·n)²` under `|c| = 1` is the generalised eigenproblem
//! `M x = λ D x`, `D = diag(1,1,1,0,0,0)`; eliminating `c̄ = -C⁺ Bᵀ c` leaves the 3x3
//! eigenproblem of the Schur complement `S = A - B C⁺ Bᵀ` (`A = Σ w m mᵀ`,
//! `B = Σ w m nᵀ`, `C = Σ w n nᵀ`): closed form, linear in the number of lines.
//! The residual `c·m + c̄·n` of a line is its distance to the axis times the sine of
//! their angle, so lines parallel to the axis (a flat base) cost nothing and count for
//! nothing, as they should.
//!
//! The eigenvalues of `S` also tell whether the data determine an axis: one small
//! eigenvalue for a surface of revolution, two or three for a sphere (every line through
//! its centre is an axis).

use nalgebra::{Matrix3, SymmetricEigen, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::axis::Axis;
use crate::mesh::{Point, Vector};

/// Lines moved to their weighted centroid and divided by their size, so that the
/// complex's blocks are of comparable magnitude (moments and directions both O(1)).
#[derive(Clone, Debug)]
pub struct CenteredLines {
    /// Point of each line, centred and scaled (dimensionless).
    pub points: Vec<Vector>,
    /// Unit direction of each line.
    pub directions: Vec<Vector>,
    /// Prior weight of each line (area), normalised to mean 1.
    pub weights: Vec<f64>,
    /// The centroid subtracted, in the scan frame.
    pub center: Point,
    /// The length divided by, in millimetres.
    pub scale_mm: f64,
}

impl CenteredLines {
    /// Centres and scales `lines`.
    pub fn new(lines: &super::normal_lines::NormalLines) -> Self {
        let center = lines.centroid();
        let scale_mm = lines.size_mm().max(1e-9);
        let mean_weight = lines.weights.iter().sum::<f64>() / lines.len().max(1) as f64;
        CenteredLines {
            points: lines.points.iter().map(|p| (p - center) / scale_mm).collect(),
            directions: lines.directions.clone(),
            weights: lines.weights.iter().map(|w| w / mean_weight).collect(),
            center,
            scale_mm,
        }
    }

    /// Number of lines.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// True when there are no lines.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// An axis of the centred frame mapped back to the scan frame.
    pub fn to_scan_frame(&self, point: &Vector, direction: &Vector) -> Axis {
        Axis::new(self.center + point * self.scale_mm, *direction)
    }

    /// An axis of the scan frame in the centred frame: (point, direction).
    pub fn from_scan_frame(&self, axis: &Axis) -> (Vector, Vector) {
        ((axis.point - self.center) / self.scale_mm, axis.direction.into_inner())
    }
}

/// The closed-form solution and what its spectrum says about the data.
#[derive(Clone, Copy, Debug)]
pub struct ComplexFit {
    /// Axis direction (unit, sign arbitrary), centred frame.
    pub direction: Vector,
    /// Point of the axis closest to the centroid, centred frame.
    pub point: Vector,
    /// The pitch of the helical motion the complex belongs to, in centred units; near zero
    /// for a surface of revolution.
    pub pitch: f64,
    /// Eigenvalues of the Schur complement, ascending, divided by the total weight: mean
    /// squared algebraic residual of the best, second and third complex.
    pub eigenvalues: [f64; 3],
}

impl ComplexFit {
    /// `λ1/λ2`: near 0 when one axis explains the lines much better than any other, near 1
    /// when the lines are (nearly) concurrent, as on a sphere.
    pub fn concurrency_ratio(&self) -> f64 {
        self.eigenvalues[0] / self.eigenvalues[1].max(1e-300)
    }
}

/// The least-squares linear complex of the lines `indices` (all lines when `None`),
/// with per-line weights multiplying the prior weights.
pub fn fit_complex(lines: &CenteredLines, indices: Option<&[usize]>, extra_weights: Option<&[f64]>) -> Option<ComplexFit> {
    let mut a = Matrix3::zeros();
    let mut b = Matrix3::zeros();
    let mut c = Matrix3::zeros();
    let mut total = 0.0;
    let mut add = |i: usize| {
        let w = lines.weights[i] * extra_weights.map_or(1.0, |e| e[i]);
        if w <= 0.0 {
            return;
        }
        let n = lines.directions[i];
        let m = lines.points[i].cross(&n);
        a += m * m.transpose() * w;
        b += m * n.transpose() * w;
        c += n * n.transpose() * w;
        total += w;
    };
    match indices {
        Some(list) => list.iter().for_each(|&i| add(i)),
        None => (0..lines.len()).for_each(add),
    }
    solve_complex(&a, &b, &c, total)
}

fn solve_complex(a: &Matrix3<f64>, b: &Matrix3<f64>, c: &Matrix3<f64>, total: f64) -> Option<ComplexFit> {
    if !(total > 0.0) {
        return None;
    }
    // Pseudo-inverse of C: on a cylinder C has rank 2 (all normals perpendicular to the
    // axis) and c̄ is free along the axis, which only changes the pitch.
    let eigen_c = SymmetricEigen::new(*c);
    let largest = eigen_c.eigenvalues.amax();
    let mut c_pinv = Matrix3::zeros();
    for k in 0..3 {
        let value = eigen_c.eigenvalues[k];
        if value > largest * 1e-10 {
            let v = eigen_c.eigenvectors.column(k);
            c_pinv += v * v.transpose() / value;
        }
    }
    let schur = a - b * c_pinv * b.transpose();
    let schur = (schur + schur.transpose()) * 0.5;
    let eigen = SymmetricEigen::new(schur);
    let mut order = [0usize, 1, 2];
    order.sort_by(|&i, &j| eigen.eigenvalues[i].total_cmp(&eigen.eigenvalues[j]));
    let direction: Vector3<f64> = eigen.eigenvectors.column(order[0]).into_owned().normalize();
    if !direction.iter().all(|x| x.is_finite()) {
        return None;
    }
    let moment = -(c_pinv * b.transpose() * direction);
    let pitch = direction.dot(&moment);
    let axis_moment = moment - direction * pitch;
    let point = direction.cross(&axis_moment);
    let eigenvalues = [
        eigen.eigenvalues[order[0]].max(0.0) / total,
        eigen.eigenvalues[order[1]].max(0.0) / total,
        eigen.eigenvalues[order[2]].max(0.0) / total,
    ];
    Some(ComplexFit { direction, point, pitch, eigenvalues })
}

/// Distance from the line `(point, direction)` to the axis `(axis_point, axis_direction)`,
/// all in the centred frame.
pub fn line_to_axis_distance(point: &Vector, direction: &Vector, axis_point: &Vector, axis_direction: &Vector) -> f64 {
    let cross = axis_direction.cross(direction);
    let sine = cross.norm();
    let offset = point - axis_point;
    if sine < 1e-9 {
        offset.cross(axis_direction).norm()
    } else {
        offset.dot(&cross).abs() / sine
    }
}

/// An axis hypothesis in the centred frame.
#[derive(Clone, Copy, Debug)]
pub struct Hypothesis {
    /// Unit direction (sign arbitrary).
    pub direction: Vector,
    /// A point of the axis.
    pub point: Vector,
    /// Its cost (lower is better); what it means depends on who made it.
    pub cost: f64,
}

/// Options of the sampling initialiser.
#[derive(Clone, Copy, Debug)]
pub struct SamplerOptions {
    /// Number of random line sets tried.
    pub sample_count: usize,
    /// Lines per set; 5 determine a complex, a few more make each hypothesis less noisy.
    pub lines_per_sample: usize,
    /// Number of lines the hypotheses are scored on (a fixed random subset).
    pub scoring_lines: usize,
    /// Lines farther than this from the axis (centred units) count as outliers with a
    /// constant cost, as PotSAC's truncated cost does.
    pub inlier_distance: f64,
    /// Hypotheses within this angle (degrees) are merged, keeping the cheaper one.
    pub merge_angle_deg: f64,
    /// Number of distinct hypotheses returned.
    pub keep: usize,
    /// Seed, so that a scan always gives the same answer.
    pub seed: u64,
}

impl Default for SamplerOptions {
    fn default() -> Self {
        SamplerOptions {
            sample_count: 300,
            lines_per_sample: 8,
            scoring_lines: 800,
            inlier_distance: 0.05,
            merge_angle_deg: 10.0,
            keep: 4,
            seed: 0x5eed,
        }
    }
}

/// PotSAC-style sampling: complexes of random small line sets, scored by a truncated
/// squared distance of all (scoring) lines to their axis; the best distinct hypotheses,
/// cheapest first. A hypothesis needs only its inliers to be right, so a minority of
/// good lines (a sherd with large fracture faces) still gives the right axis.
pub fn sample_hypotheses(lines: &CenteredLines, options: &SamplerOptions) -> Vec<Hypothesis> {
    let n = lines.len();
    if n < options.lines_per_sample {
        return Vec::new();
    }
    let mut rng = ChaCha8Rng::seed_from_u64(options.seed);
    let scoring: Vec<usize> = if n <= options.scoring_lines {
        (0..n).collect()
    } else {
        (0..options.scoring_lines).map(|_| rng.random_range(0..n)).collect()
    };
    let truncation = options.inlier_distance * options.inlier_distance;
    let score = |point: &Vector, direction: &Vector| -> f64 {
        let sum: f64 = scoring
            .iter()
            .map(|&i| {
                let d = line_to_axis_distance(&lines.points[i], &lines.directions[i], point, direction);
                lines.weights[i] * (d * d).min(truncation)
            })
            .sum();
        sum / scoring.len() as f64
    };
    let mut hypotheses: Vec<Hypothesis> = Vec::with_capacity(options.sample_count + 1);
    if let Some(global) = fit_complex(lines, None, None) {
        hypotheses.push(Hypothesis { direction: global.direction, point: global.point, cost: score(&global.point, &global.direction) });
    }
    let mut sample = vec![0usize; options.lines_per_sample];
    for _ in 0..options.sample_count {
        for slot in sample.iter_mut() {
            *slot = rng.random_range(0..n);
        }
        if let Some(fit) = fit_complex(lines, Some(&sample), None) {
            let cost = score(&fit.point, &fit.direction);
            hypotheses.push(Hypothesis { direction: fit.direction, point: fit.point, cost });
        }
    }
    merge_hypotheses(hypotheses, options.merge_angle_deg, options.keep)
}

/// The cheapest hypotheses, dropping any within `merge_angle_deg` (as lines) of a cheaper one.
pub fn merge_hypotheses(mut hypotheses: Vec<Hypothesis>, merge_angle_deg: f64, keep: usize) -> Vec<Hypothesis> {
    hypotheses.retain(|h| h.cost.is_finite());
    hypotheses.sort_by(|a, b| a.cost.total_cmp(&b.cost));
    let cos_merge = merge_angle_deg.to_radians().cos();
    let mut kept: Vec<Hypothesis> = Vec::new();
    for h in hypotheses {
        if kept.iter().all(|k| k.direction.dot(&h.direction).abs() < cos_merge) {
            kept.push(h);
            if kept.len() == keep {
                break;
            }
        }
    }
    kept
}
