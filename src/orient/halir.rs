//! Halíř's axis estimate (Halíř 1999, "An automatic estimation of the axis of rotation of
//! fragments of archaeological pottery"; Wilczek et al. 2018, section 2.2.2 and
//! equation (1)): the line minimising the squared distances to the normal lines.
//!
//! For a candidate direction `N0` the distance of normal line `i` to an axis through `X0`
//! is linear in `X0`: `(X_i - X0)·(N_i x N0)`, so the point is solved in closed form
//! (2x2 normal equations in the plane perpendicular to `N0`) and only the two angles of
//! `N0` are searched, with argmin's Nelder-Mead. Differences from the paper, all measured
//! on the synthetic corpus (`examples/orient_accuracy.rs`):
//! - many starts (hypotheses of the line complex and of the sampler, and a Fibonacci
//!   cover of the hemisphere on a subsample), not one;
//! - the robust regression is an MM-estimate of the whole axis (direction and point), not
//!   of the point alone: the S-scale of the best start is held fixed and the Tukey
//!   biweight M-step reweights the lines between Nelder-Mead searches;
//! - the residual is by default the distance times `|N_i x N0|` (the line-complex
//!   residual): lines parallel to the axis (base bottoms) carry no distance information
//!   and would otherwise be large outliers.

use argmin::core::{CostFunction, Executor};
use argmin::solver::neldermead::NelderMead;
use nalgebra::{Matrix2, Vector2};
use rayon::prelude::*;

use super::line_complex::{CenteredLines, Hypothesis};
use super::mm_regression::{m_scale, m_step_cost, m_step_weights};
use crate::mesh::Vector;

/// Which distance between a normal line and the axis is squared.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ResidualKind {
    /// The distance times the sine of the angle between the lines (the complex residual).
    Algebraic,
    /// The distance itself, as in the paper (lines within 3 degrees of parallel capped).
    Geometric,
}

/// Two unit vectors completing `direction` to a right-handed orthonormal frame.
pub fn perpendicular_frame(direction: &Vector) -> (Vector, Vector) {
    let helper = if direction.x.abs() < 0.6 { Vector::x() } else { Vector::y() };
    let e1 = direction.cross(&helper).normalize();
    let e2 = direction.cross(&e1);
    (e1, e2)
}

/// The lines, a weight per line and a subset to work on.
pub struct HalirProblem<'a> {
    /// The centred lines.
    pub lines: &'a CenteredLines,
    /// Weight per line (prior times robust), same length as the lines.
    pub weights: Vec<f64>,
    /// Indices of the lines used (all when empty is not allowed: list them).
    pub indices: Vec<usize>,
    /// The residual squared.
    pub kind: ResidualKind,
}

impl<'a> HalirProblem<'a> {
    /// All lines with their prior weights.
    pub fn new(lines: &'a CenteredLines, kind: ResidualKind) -> Self {
        HalirProblem { lines, weights: lines.weights.clone(), indices: (0..lines.len()).collect(), kind }
    }

    /// `(A_i, q_i)` with `residual = q_i - A_i·X0` for line `i` and direction `d`.
    #[inline]
    fn row(&self, i: usize, direction: &Vector) -> (Vector, f64) {
        let mut a = direction.cross(&self.lines.directions[i]);
        if self.kind == ResidualKind::Geometric {
            a /= a.norm().max(0.05);
        }
        (a, self.lines.points[i].dot(&a))
    }

    /// The axis point (perpendicular to `direction`, closest to the centroid) minimising the
    /// weighted squared residuals, and the weighted mean squared residual.
    pub fn solve_point(&self, direction: &Vector) -> (Vector, f64) {
        let rows = self.indices.iter().map(|&i| (&self.lines.points[i], &self.lines.directions[i], self.weights[i]));
        solve_point_over(rows, self.kind, direction)
    }

    /// The lines of the subset with a positive weight, packed side by side: a search
    /// evaluates the cost hundreds of times over the same lines and weights, and reading
    /// them in order is what its inner loop is bound by.
    fn packed(&self) -> Vec<PackedLine> {
        self.indices
            .iter()
            .filter(|&&i| self.weights[i] > 0.0)
            .map(|&i| PackedLine { point: self.lines.points[i], direction: self.lines.directions[i], weight: self.weights[i] })
            .collect()
    }

    /// Residual of every line (not only the subset) for the axis `(point, direction)`.
    pub fn residuals(&self, point: &Vector, direction: &Vector) -> Vec<f64> {
        (0..self.lines.len()).map(|i| self.residual(i, point, direction)).collect()
    }

    /// Residual of each line of the subset, in the subset's order: what the robust steps
    /// weigh (a tenth of the lines of a 10k-vertex copy), without the rest.
    fn subset_residuals(&self, point: &Vector, direction: &Vector) -> Vec<f64> {
        self.indices.iter().map(|&i| self.residual(i, point, direction)).collect()
    }

    #[inline]
    fn residual(&self, i: usize, point: &Vector, direction: &Vector) -> f64 {
        let (a, q) = self.row(i, direction);
        q - a.dot(point)
    }

    /// 2x2 covariance factor `(Σ w x xᵀ)⁻¹` of the point coordinates, for the point's uncertainty.
    pub fn point_information(&self, direction: &Vector) -> Matrix2<f64> {
        let (e1, e2) = perpendicular_frame(direction);
        let mut normal = Matrix2::zeros();
        for &i in &self.indices {
            let w = self.weights[i];
            if w > 0.0 {
                let (a, _) = self.row(i, direction);
                let x = Vector2::new(a.dot(&e1), a.dot(&e2));
                normal += x * x.transpose() * w;
            }
        }
        normal
    }

    /// Nelder-Mead over the two angles around `start`, with an initial simplex of
    /// `step_rad`; returns the direction found and its cost.
    pub fn search(&self, start: &Vector, step_rad: f64, max_iterations: u64) -> (Vector, f64) {
        let (e1, e2) = perpendicular_frame(start);
        let packed = self.packed();
        let chart = Chart { lines: &packed, kind: self.kind, start: *start, e1, e2 };
        let step = step_rad.tan();
        let simplex = vec![vec![0.0, 0.0], vec![step, 0.0], vec![0.0, step]];
        let solver = match NelderMead::new(simplex).with_sd_tolerance(SEARCH_COST_TOLERANCE) {
            Ok(solver) => solver,
            Err(_) => return (*start, self.solve_point(start).1),
        };
        match Executor::new(chart, solver).configure(|state| state.max_iters(max_iterations)).run() {
            Ok(result) => {
                let state = result.state();
                let param = state.best_param.clone().unwrap_or_else(|| vec![0.0, 0.0]);
                let direction = (start + e1 * param[0] + e2 * param[1]).normalize();
                (direction, state.best_cost)
            }
            Err(_) => (*start, self.solve_point(start).1),
        }
    }

    /// Numerical Hessian of the profiled cost (weighted sum of squares, not mean) with
    /// respect to the two angles at `direction`, step `h` radians.
    pub fn profiled_hessian(&self, direction: &Vector, h: f64) -> Matrix2<f64> {
        let (e1, e2) = perpendicular_frame(direction);
        let total: f64 = self.indices.iter().map(|&i| self.weights[i].max(0.0)).sum();
        let f = |u: f64, v: f64| self.solve_point(&(direction + e1 * u + e2 * v).normalize()).1 * total;
        let f0 = f(0.0, 0.0);
        let fuu = (f(h, 0.0) - 2.0 * f0 + f(-h, 0.0)) / (h * h);
        let fvv = (f(0.0, h) - 2.0 * f0 + f(0.0, -h)) / (h * h);
        let fuv = (f(h, h) - f(h, -h) - f(-h, h) + f(-h, -h)) / (4.0 * h * h);
        Matrix2::new(fuu, fuv, fuv, fvv)
    }
}

/// The search stops when its simplex's costs spread less than this. The lines are
/// dimensionless (scaled by the sherd's size), so costs are about the squared relative
/// noise, 1e-4: the simplex then spans some 3e-4 radians, 0.02 degrees, well below the
/// axis's own uncertainty. 1e-12 made the orientation a tenth slower (`cargo bench
/// --bench orient`: 50.3 against 45.4 ms) for the same tables of
/// `examples/orient_accuracy.rs` and of `examples/refine_accuracy.rs`'s pipeline (within
/// a sherd or two: axes on a knife edge go one way or the other); 1e-10 (43 ms) lost four
/// pipeline sherds from within 4 mm.
const SEARCH_COST_TOLERANCE: f64 = 1e-11;

/// One line of [`HalirProblem::packed`].
struct PackedLine {
    point: Vector,
    direction: Vector,
    weight: f64,
}

/// [`HalirProblem::solve_point`] over `(point, line direction, weight)` rows; rows of
/// weight zero or less are skipped. The sums are accumulated in plain scalars in the
/// order the rows come, so packed and indexed rows give the same bits.
#[inline]
fn solve_point_over<'l>(
    rows: impl Iterator<Item = (&'l Vector, &'l Vector, f64)>,
    kind: ResidualKind,
    direction: &Vector,
) -> (Vector, f64) {
    let (e1, e2) = perpendicular_frame(direction);
    let (mut n00, mut n01, mut n11) = (0.0, 0.0, 0.0);
    let (mut r0, mut r1) = (0.0, 0.0);
    let (mut qq, mut total) = (0.0, 0.0);
    for (point, line_direction, w) in rows {
        if w <= 0.0 {
            continue;
        }
        // `(A_i, q_i)` with `residual = q_i - A_i·X0` (see `HalirProblem::row`).
        let mut a = direction.cross(line_direction);
        if kind == ResidualKind::Geometric {
            a /= a.norm().max(0.05);
        }
        let q = point.dot(&a);
        let (x0, x1) = (a.dot(&e1), a.dot(&e2));
        n00 += x0 * x0 * w;
        n01 += x0 * x1 * w;
        n11 += x1 * x1 * w;
        let qw = q * w;
        r0 += x0 * qw;
        r1 += x1 * qw;
        qq += q * q * w;
        total += w;
    }
    if !(total > 0.0) {
        return (Vector::zeros(), f64::INFINITY);
    }
    let normal = Matrix2::new(n00, n01, n01, n11);
    let rhs = Vector2::new(r0, r1);
    // A tiny ridge keeps the point finite when the lines do not fix it (flat piece);
    // the verdict reports that case from the point's uncertainty.
    let ridge = normal.trace() * 1e-9 + 1e-300;
    let regularised = normal + Matrix2::identity() * ridge;
    let uv = regularised.try_inverse().map_or(Vector2::zeros(), |inv| inv * rhs);
    let cost = ((qq - 2.0 * uv.dot(&rhs) + (uv.transpose() * normal * uv)[0]) / total).max(0.0);
    (e1 * uv.x + e2 * uv.y, cost)
}

/// The gnomonic chart around a start direction: parameters `(u, v)` map to
/// `normalize(start + u e1 + v e2)`, smooth and without poles within 90 degrees.
struct Chart<'p> {
    lines: &'p [PackedLine],
    kind: ResidualKind,
    start: Vector,
    e1: Vector,
    e2: Vector,
}

impl CostFunction for Chart<'_> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, param: &Self::Param) -> Result<f64, argmin::core::Error> {
        let direction = (self.start + self.e1 * param[0] + self.e2 * param[1]).normalize();
        let rows = self.lines.iter().map(|l| (&l.point, &l.direction, l.weight));
        Ok(solve_point_over(rows, self.kind, &direction).1)
    }
}

/// Unit directions spread evenly over the upper hemisphere (Fibonacci spiral).
pub fn hemisphere_starts(count: usize) -> Vec<Vector> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..count)
        .map(|k| {
            let z = 1.0 - (k as f64 + 0.5) / count as f64; // (0, 1]
            let r = (1.0 - z * z).sqrt();
            let phi = golden * k as f64;
            Vector::new(r * phi.cos(), r * phi.sin(), z)
        })
        .collect()
}

/// Options of the robust refinement.
#[derive(Clone, Copy, Debug)]
pub struct HalirOptions {
    /// The residual squared.
    pub kind: ResidualKind,
    /// Starts spread over the hemisphere for the multi-start search.
    pub hemisphere_start_count: usize,
    /// Lines of the subsample the multi-start search runs on.
    pub search_subsample: usize,
    /// Lines the final MM refinement runs on at most (an even stride of all lines).
    pub refine_subsample: usize,
    /// Number of distinct candidates refined on the full set.
    pub candidates_refined: usize,
    /// Reweighting rounds of the M-step.
    pub m_step_rounds: usize,
}

impl Default for HalirOptions {
    fn default() -> Self {
        HalirOptions {
            kind: ResidualKind::Geometric,
            hemisphere_start_count: 12,
            search_subsample: 400,
            refine_subsample: 1500,
            candidates_refined: 3,
            m_step_rounds: 3,
        }
    }
}

/// The robust axis and what is known of its precision.
#[derive(Clone, Debug)]
pub struct HalirFit {
    /// Unit direction (sign arbitrary), centred frame.
    pub direction: Vector,
    /// Axis point closest to the centroid, centred frame.
    pub point: Vector,
    /// Residual of every line, centred units.
    pub residuals: Vec<f64>,
    /// Final M-step weight of every line (0 for outliers).
    pub robust_weights: Vec<f64>,
    /// The S-scale held fixed in the M-step, centred units.
    pub scale: f64,
    /// MM cost (mean biweight loss at that scale).
    pub cost: f64,
    /// Standard error of the direction from the profiled Hessian, radians (largest axis of
    /// the 2x2 covariance): an uncalibrated figure, see `verdict`.
    pub angle_sigma_rad: f64,
    /// Standard error of the point, centred units (largest axis).
    pub point_sigma: f64,
    /// Candidates refined, cheapest first: (direction, cost).
    pub alternatives: Vec<(Vector, f64)>,
}

fn stride_subset(n: usize, count: usize) -> Vec<usize> {
    if n <= count {
        return (0..n).collect();
    }
    // A multiplicative stride visits the lines in a scattered order, so that the subset
    // covers the whole sherd rather than the first scanned patch.
    let step = n as f64 / count as f64;
    (0..count).map(|k| ((k as f64 * step) as usize).min(n - 1)).collect()
}

/// Multi-start Nelder-Mead on a subsample: the distinct local minima, cheapest first.
pub fn multi_start(lines: &CenteredLines, seeds: &[Hypothesis], options: &HalirOptions) -> Vec<Hypothesis> {
    let mut problem = HalirProblem::new(lines, options.kind);
    problem.indices = stride_subset(lines.len(), options.search_subsample);
    let mut starts: Vec<Vector> = seeds.iter().map(|h| h.direction).collect();
    starts.extend(hemisphere_starts(options.hemisphere_start_count));
    // The searches are independent: one per core, results in the order of the starts.
    let mut found: Vec<Hypothesis> = starts
        .par_iter()
        .map(|start| {
            let (direction, cost) = problem.search(start, 0.15, 80);
            let (point, _) = problem.solve_point(&direction);
            Hypothesis { direction, point, cost }
        })
        .collect();
    // The robust sampler's seeds are kept with their own (robust) ranking too: least
    // squares on a subsample may prefer an outlier-driven minimum.
    found.extend(seeds.iter().copied().map(|mut h| {
        h.cost = problem.solve_point(&h.direction).1;
        h
    }));
    super::line_complex::merge_hypotheses(found, 5.0, options.candidates_refined + seeds.len())
}

/// MM refinement of candidate directions on (a large subsample of) all lines; the fit with
/// the lowest MM cost.
pub fn refine_candidates(lines: &CenteredLines, candidates: &[Vector], options: &HalirOptions) -> Option<HalirFit> {
    let MmSearch { mut problem, subset_prior, scale, mut results } = mm_search(lines, candidates, options)?;
    let alternatives: Vec<(Vector, f64)> = results.iter().map(|r| (r.0, r.2)).collect();
    let (direction, point, cost) = results.swap_remove(0);
    let residuals = problem.residuals(&point, &direction);
    let robust_weights = m_step_weights(&residuals, scale);
    // Precision: Gauss-Newton covariance of the profiled least squares with the final
    // weights, residual variance from the weighted residuals of the inliers.
    problem.weights = subset_prior.iter().zip(&robust_weights).map(|(p, r)| p * r).collect();
    let used: Vec<usize> = problem.indices.iter().copied().filter(|&i| problem.weights[i] > 0.0).collect();
    let total: f64 = used.iter().map(|&i| problem.weights[i]).sum();
    let sum_squares: f64 = used.iter().map(|&i| problem.weights[i] * residuals[i] * residuals[i]).sum();
    let dof = (used.len() as f64 - 4.0).max(1.0);
    // Weights are normalised to mean 1 over the used lines so the sum of squares is a count.
    let variance = sum_squares / total * used.len() as f64 / dof;
    let mean_weight = total / used.len().max(1) as f64;
    let hessian = problem.profiled_hessian(&direction, 1e-3) / mean_weight;
    let angle_sigma_rad = largest_std(&hessian, 2.0 * variance);
    let information = problem.point_information(&direction) / mean_weight;
    let point_sigma = largest_std(&information, variance);
    Some(HalirFit { direction, point, residuals, robust_weights, scale, cost, angle_sigma_rad, point_sigma, alternatives })
}

/// The direction [`refine_candidates`] finds, without the precision figures, the
/// residuals of every line and the competitors (what the leave-one-region-out refits need).
pub fn refined_direction(lines: &CenteredLines, candidates: &[Vector], options: &HalirOptions) -> Option<Vector> {
    mm_search(lines, candidates, options).map(|search| search.results[0].0)
}

/// The MM search of [`refine_candidates`]: the problem on the subset, the prior weights
/// of the subset's lines (0 elsewhere), the S-scale held fixed, and the candidates
/// refined `(direction, point, cost)`, cheapest first.
struct MmSearch<'a> {
    problem: HalirProblem<'a>,
    subset_prior: Vec<f64>,
    scale: f64,
    results: Vec<(Vector, Vector, f64)>,
}

fn mm_search<'a>(lines: &'a CenteredLines, candidates: &[Vector], options: &HalirOptions) -> Option<MmSearch<'a>> {
    if candidates.is_empty() || lines.len() < 3 {
        return None;
    }
    let mut problem = HalirProblem::new(lines, options.kind);
    problem.indices = stride_subset(lines.len(), options.refine_subsample);
    let subset_prior: Vec<f64> = {
        let mut mask = vec![0.0; lines.len()];
        for &i in &problem.indices {
            mask[i] = lines.weights[i];
        }
        mask
    };
    // The robust steps see the subset only (the other lines have prior weight 0 there and
    // would add exact zeros to every sum): its prior weights in the subset's order.
    let prior_in_subset: Vec<f64> = problem.indices.iter().map(|&i| lines.weights[i]).collect();
    // S-step: the smallest M-scale among the candidates (each with its best point).
    let scales: Vec<f64> = candidates
        .iter()
        .map(|d| {
            let (point, _) = problem.solve_point(d);
            m_scale(&problem.subset_residuals(&point, d), &prior_in_subset)
        })
        .collect();
    let scale = scales.iter().copied().filter(|s| *s > 0.0).fold(f64::INFINITY, f64::min);
    let scale = if scale.is_finite() { scale } else { 1e-12 };
    // The candidates are refined independently, one per core, each with its own weights;
    // collected in their order, so the result is the same as one after the other.
    let mut results: Vec<(Vector, Vector, f64)> = candidates
        .par_iter()
        .map(|start| {
            let mut problem = HalirProblem { weights: problem.weights.clone(), indices: problem.indices.clone(), ..problem };
            let mut direction = *start;
            let mut point = problem.solve_point(&direction).0;
            for round in 0..options.m_step_rounds {
                let robust = m_step_weights(&problem.subset_residuals(&point, &direction), scale);
                for ((&i, prior), r) in problem.indices.iter().zip(&prior_in_subset).zip(&robust) {
                    problem.weights[i] = prior * r;
                }
                let step = if round == 0 { 0.05 } else { 0.01 };
                let (next, _) = problem.search(&direction, step, if round == 0 { 100 } else { 50 });
                let moved = next.dot(&direction).abs().min(1.0).acos();
                direction = next;
                point = problem.solve_point(&direction).0;
                if moved < 1e-5 {
                    break;
                }
            }
            let cost = m_step_cost(&problem.subset_residuals(&point, &direction), &prior_in_subset, scale);
            (direction, point, cost)
        })
        .collect();
    results.sort_by(|a, b| a.2.total_cmp(&b.2));
    Some(MmSearch { problem, subset_prior, scale, results })
}

/// `sqrt` of the largest eigenvalue of `numerator * information⁻¹`; infinite when singular.
fn largest_std(information: &Matrix2<f64>, numerator: f64) -> f64 {
    let symmetric = (information + information.transpose()) * 0.5;
    let eigen = nalgebra::SymmetricEigen::new(symmetric);
    let smallest = eigen.eigenvalues.min();
    if !(smallest > 0.0) {
        return f64::INFINITY;
    }
    (numerator / smallest).sqrt()
}
