//! The search itself: an even cover of the hemisphere scored, its lowest valleys followed
//! down by Nelder-Mead over the direction's tilts, and the landscape of valleys returned.

use rayon::prelude::*;

use super::position::{fit_direction_with, DirectionFit};
use super::samples::RevolutionSamples;
use crate::mesh::Vector;
use crate::axis::Axis;
use crate::axis::perpendicular_frame;
use crate::orient::normal_lines::NormalLines;

// For the doc links only.
#[cfg(doc)]
use super::position::fit_direction;

/// Directions spread evenly over the upper hemisphere (a Fibonacci spiral), `count` of
/// them.
pub fn hemisphere_directions(count: usize) -> Vec<Vector> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..count)
        .map(|i| {
            let z = 1.0 - (i as f64 + 0.5) / count as f64;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = golden * i as f64;
            Vector::new(r * phi.cos(), r * phi.sin(), z)
        })
        .collect()
}

/// A valley of the landscape followed to its bottom.
#[derive(Clone, Copy, Debug)]
pub struct Valley {
    /// Its best axis.
    pub fit: DirectionFit,
    /// The score of the coarse direction it was followed from.
    pub coarse_cost: f64,
}

impl Valley {
    /// The valley's axis in the scan frame (sense arbitrary).
    pub fn axis(&self, samples: &RevolutionSamples) -> Axis {
        Axis::new(samples.centroid + self.fit.centre, self.fit.direction)
    }
}

/// Settings of [`search`].
#[derive(Clone, Copy, Debug)]
pub struct SearchOptions {
    /// Directions of the coarse cover of the hemisphere.
    pub coarse_directions: usize,
    /// Points the coarse cover is scored on.
    pub coarse_points: usize,
    /// Valleys followed down from the coarse cover's lowest local minima.
    pub valleys: usize,
    /// Points the valleys are followed down on.
    pub descent_points: usize,
    /// Valleys, lowest first, followed to their bottom on all the points (at most
    /// `final_points`) and returned.
    pub final_valleys: usize,
    /// Points of the final descent.
    pub final_points: usize,
    /// Two valleys whose bottoms lie closer than this are one, degrees.
    pub distinct_deg: f64,
    /// The robust loss's scale, as a share of the band width.
    pub loss_scale_bands: f64,
    /// Band width in typical point spacings.
    pub band_spacings: f64,
    /// Least band width, mm.
    pub min_band_mm: f64,
    /// Gauss-Newton steps of the position at each direction of the coarse cover, of the
    /// descents and of the final descents.
    pub polish_steps: [usize; 3],
    /// Nelder-Mead iterations of the descents and of the final descents.
    pub iterations: [usize; 2],
}

impl Default for SearchOptions {
    fn default() -> Self {
        SearchOptions {
            coarse_directions: 700,
            coarse_points: 1200,
            valleys: 5,
            descent_points: 2500,
            final_valleys: 3,
            final_points: 6000,
            distinct_deg: 5.0,
            loss_scale_bands: 0.25,
            band_spacings: 2.5,
            min_band_mm: 1.0,
            polish_steps: [2, 2, 3],
            iterations: [40, 25],
        }
    }
}

/// The landscape's valleys, lowest first: the coarse cover scored on a subsample of the
/// lines, its local minima (no neighbour lower) followed down on a larger subsample, and
/// the lowest of them followed to their bottom on all the lines (at most
/// [`SearchOptions::final_points`]). The valleys' costs are comparable with each other
/// (the same points and loss), and with [`Landscape::samples`]' scores.
pub fn search(lines: &NormalLines, options: &SearchOptions) -> Option<Landscape> {
    let sampled = |count: usize| RevolutionSamples::from_lines(lines, count, options.band_spacings, options.min_band_mm);
    let coarse = sampled(options.coarse_points)?;
    let descent = sampled(options.descent_points)?;
    let samples = sampled(options.final_points)?;
    let directions = hemisphere_directions(options.coarse_directions.max(8));
    let coarse_scale = options.loss_scale_bands * coarse.band_mm;
    let fits: Vec<DirectionFit> = directions.par_iter().map(|d| fit_direction_with(&coarse, d, coarse_scale, options.polish_steps[0])).collect();
    // Neighbours: within 1.8 spacings of the cover (a line's two senses are one direction).
    let spacing = (2.0 * std::f64::consts::PI / directions.len() as f64).sqrt();
    let near = (1.8 * spacing).cos();
    let mut minima: Vec<usize> = (0..directions.len())
        .filter(|&i| {
            directions.iter().enumerate().all(|(j, d)| j == i || d.dot(&directions[i]).abs() < near || fits[j].cost >= fits[i].cost)
        })
        .collect();
    minima.sort_by(|&a, &b| fits[a].cost.total_cmp(&fits[b].cost));
    let distinct = options.distinct_deg.to_radians().cos();
    let mut starts: Vec<usize> = Vec::new();
    for i in minima {
        if starts.iter().all(|&s| directions[s].dot(&directions[i]).abs() < distinct) {
            starts.push(i);
        }
        if starts.len() >= options.valleys {
            break;
        }
    }
    let descent_scale = options.loss_scale_bands * descent.band_mm;
    // Beside the cover's minima, the two directions the normals point to without a search:
    // across all of them (a cylinder's or a cone's axis: the least eigenvector of their
    // scatter) and along most of them (a floor's normal: the largest). A valley narrower
    // than the cover's spacing (a base whose position only its small foot fixes) is
    // reached from there.
    let mut start_directions: Vec<(Vector, f64)> = starts.iter().map(|&i| (directions[i], fits[i].cost)).collect();
    for direction in normal_scatter_axes(&coarse) {
        if start_directions.iter().all(|(d, _)| d.dot(&direction).abs() < distinct) {
            start_directions.push((direction, f64::NAN));
        }
    }
    let mut followed: Vec<(DirectionFit, f64)> = start_directions
        .par_iter()
        .map(|(direction, coarse_cost)| {
            let fit = descend(&descent, direction, 1.2 * spacing, DESCENT_TOLERANCE_DEG.to_radians(), descent_scale, options.polish_steps[1], options.iterations[0]);
            (fit, *coarse_cost)
        })
        .collect();
    followed.sort_by(|a, b| a.0.cost.total_cmp(&b.0.cost));
    let followed = distinct_fits(followed, distinct);
    let scale = options.loss_scale_bands * samples.band_mm;
    let mut valleys: Vec<(DirectionFit, f64)> = followed
        .par_iter()
        .take(options.final_valleys)
        .map(|(fit, coarse_cost)| {
            (descend(&samples, &fit.direction, FINAL_STEP_DEG.to_radians(), FINAL_TOLERANCE_DEG.to_radians(), scale, options.polish_steps[2], options.iterations[1]), *coarse_cost)
        })
        .collect();
    valleys.sort_by(|a, b| a.0.cost.total_cmp(&b.0.cost));
    let valleys = distinct_fits(valleys, distinct).into_iter().map(|(fit, coarse_cost)| Valley { fit, coarse_cost }).collect();
    Some(Landscape { valleys, samples, loss_scale_mm: scale })
}

/// The least and the largest eigenvectors of the weighted scatter of the normals.
fn normal_scatter_axes(samples: &RevolutionSamples) -> [Vector; 2] {
    let mut scatter = nalgebra::Matrix3::zeros();
    for (n, w) in samples.normals.iter().zip(&samples.weights) {
        scatter += n * n.transpose() * *w;
    }
    let eigen = nalgebra::SymmetricEigen::new(scatter);
    let pick = |largest: bool| {
        let mut best = 0;
        for k in 1..3 {
            let better = if largest { eigen.eigenvalues[k] > eigen.eigenvalues[best] } else { eigen.eigenvalues[k] < eigen.eigenvalues[best] };
            if better {
                best = k;
            }
        }
        eigen.eigenvectors.column(best).into_owned()
    };
    [pick(false), pick(true)]
}

/// First simplex step of the final descent, degrees.
const FINAL_STEP_DEG: f64 = 1.0;
/// The descents stop when their simplex is smaller than this, degrees: the refinement
/// that follows the search settles the last tenths of a degree.
const DESCENT_TOLERANCE_DEG: f64 = 0.3;
/// The same for the final descents.
const FINAL_TOLERANCE_DEG: f64 = 0.05;

/// The fits (lowest first) with those closer than `distinct` (a cosine) to a lower one
/// dropped.
fn distinct_fits(fits: Vec<(DirectionFit, f64)>, distinct: f64) -> Vec<(DirectionFit, f64)> {
    let mut kept: Vec<(DirectionFit, f64)> = Vec::new();
    for (fit, coarse) in fits {
        if kept.iter().all(|(k, _)| k.direction.dot(&fit.direction).abs() < distinct) {
            kept.push((fit, coarse));
        }
    }
    kept
}

/// The valleys of the landscape, lowest first, and the points and loss they were scored
/// with.
#[derive(Clone, Debug)]
pub struct Landscape {
    /// The valleys, lowest first, their bottoms at least [`SearchOptions::distinct_deg`]
    /// apart.
    pub valleys: Vec<Valley>,
    /// The points of the final descent.
    pub samples: RevolutionSamples,
    /// The loss scale of the final descent, mm.
    pub loss_scale_mm: f64,
}

/// Follows the valley of `start` down: Nelder-Mead over two tilts of the direction, the
/// position solved for each ([`fit_direction`] with `polish_steps`), from a simplex of
/// side `step_rad`, until the simplex is smaller than `tolerance_rad` or after
/// `iterations`. Written here rather than taken from argmin, whose Nelder-Mead stops on
/// the spread of the costs only: the score jitters as points change band, and the
/// simplex went on shrinking onto that jitter long after the axis had stopped moving.
pub fn descend(samples: &RevolutionSamples, start: &Vector, step_rad: f64, tolerance_rad: f64, scale_mm: f64, polish_steps: usize, iterations: usize) -> DirectionFit {
    let start = start.normalize();
    let (e1, e2) = perpendicular_frame(&start);
    let fit = |tilts: [f64; 2]| {
        let direction = (start + e1 * tilts[0].tan() + e2 * tilts[1].tan()).normalize();
        fit_direction_with(samples, &direction, scale_mm, polish_steps)
    };
    let mut simplex: Vec<([f64; 2], DirectionFit)> =
        [[0.0, 0.0], [step_rad, 0.0], [0.0, step_rad]].into_iter().map(|t| (t, fit(t))).collect();
    for _ in 0..iterations {
        simplex.sort_by(|a, b| a.1.cost.total_cmp(&b.1.cost));
        let size = (1..3).map(|k| (simplex[k].0[0] - simplex[0].0[0]).hypot(simplex[k].0[1] - simplex[0].0[1])).fold(0.0, f64::max);
        if size < tolerance_rad {
            break;
        }
        let centroid = [(simplex[0].0[0] + simplex[1].0[0]) / 2.0, (simplex[0].0[1] + simplex[1].0[1]) / 2.0];
        let worst = simplex[2].0;
        let along = |factor: f64| [centroid[0] + factor * (worst[0] - centroid[0]), centroid[1] + factor * (worst[1] - centroid[1])];
        let reflected = along(-1.0);
        let reflected_fit = fit(reflected);
        if reflected_fit.cost < simplex[0].1.cost {
            let expanded = along(-2.0);
            let expanded_fit = fit(expanded);
            simplex[2] = if expanded_fit.cost < reflected_fit.cost { (expanded, expanded_fit) } else { (reflected, reflected_fit) };
        } else if reflected_fit.cost < simplex[1].1.cost {
            simplex[2] = (reflected, reflected_fit);
        } else {
            let contracted = if reflected_fit.cost < simplex[2].1.cost { along(-0.5) } else { along(0.5) };
            let contracted_fit = fit(contracted);
            if contracted_fit.cost < simplex[2].1.cost.min(reflected_fit.cost) {
                simplex[2] = (contracted, contracted_fit);
            } else {
                // Shrink towards the best.
                let best = simplex[0].0;
                for vertex in simplex.iter_mut().skip(1) {
                    let t = [(vertex.0[0] + best[0]) / 2.0, (vertex.0[1] + best[1]) / 2.0];
                    *vertex = (t, fit(t));
                }
            }
        }
    }
    simplex.into_iter().map(|(_, f)| f).min_by(|a, b| a.cost.total_cmp(&b.cost)).expect("three vertices")
}

#[cfg(test)]
mod tests {
    use super::*;
    use super::super::test_patch::patch;
    use crate::mesh::Point;

    /// The search finds a cone's axis from nothing, on a 40-degree arc of it tilted away
    /// from every axis of the frame, and ranks it first: no start is given.
    #[test]
    fn the_whole_sphere_search_finds_a_cone_from_nothing() {
        let lines = patch(10.0, 5.0, |z| 60.0 + 0.5 * z, |_| 0.5, (0.0, 0.7), (0.0, 40.0));
        let rotation = nalgebra::Rotation3::from_euler_angles(0.7, -0.4, 1.1);
        let mut moved = NormalLines::default();
        for i in 0..lines.len() {
            moved.push(rotation * lines.points[i], rotation * lines.directions[i], 1.0, i);
        }
        let landscape = search(&moved, &SearchOptions::default()).expect("enough points");
        let truth = Axis::new(rotation * Point::new(10.0, 5.0, 0.0), rotation * Vector::z());
        let best = landscape.valleys[0].axis(&landscape.samples);
        assert!(best.line_angle_to_deg(&truth) < 0.2, "{:.3} deg", best.line_angle_to_deg(&truth));
        assert!(truth.distance_to(&best.closest_point(&landscape.samples.centroid)) < 0.3);
    }

    /// The coarse cover leaves no direction farther than one and a half spacings from it.
    #[test]
    fn hemisphere_directions_cover_the_sphere_evenly() {
        let directions = hemisphere_directions(500);
        assert!(directions.iter().all(|d| (d.norm() - 1.0).abs() < 1e-12 && d.z >= 0.0));
        // Every direction of the upper hemisphere lies within twice the mean spacing.
        let spacing = (2.0 * std::f64::consts::PI / 500.0).sqrt();
        for probe in hemisphere_directions(2000) {
            let nearest = directions.iter().map(|d| d.dot(&probe).clamp(-1.0, 1.0).acos()).fold(f64::INFINITY, f64::min);
            assert!(nearest < 1.5 * spacing, "{probe:?} is {nearest:.3} rad from the cover");
        }
    }
}
