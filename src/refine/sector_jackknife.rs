//! Jackknife of the refined axis over sectors of the preserved arc: the refinement
//! (Wilczek et al. 2018, section 2.3, by the criterion the options ask for) made again
//! with each quarter of the arc left out, from the refined axis.
//!
//! Why: the bootstrap ([`super::uncertainty`]) resamples horizontal sections, and every
//! section spans the whole arc. The vessel's ovality and wobble mislead them all alike, so
//! on a clean scan the resamples agree about an axis that is off (without scan noise the
//! bootstrap's angle intervals reached 0.5-1.5 degrees around body sherds 1.3-4.7 degrees
//! off). The deformation differs along the arc: an axis the
//! arc's local shape put where it is, rather than its turning, moves when a quarter of
//! the arc is left out.

use rayon::prelude::*;

use super::{refine, RefineOptions};
use crate::mesh::Mesh;
use crate::orient::{mean_point_distance_mm, Axis};
use crate::statistics::{equal_count_bins, student_t_95};

/// Number of equal-count sectors of the arc, each left out in turn: a quarter still
/// leaves three quarters of the arc to refine on, and costs four refinements.
pub const SECTOR_COUNT: usize = 4;

/// The refinement by `options` made again from `axis` with each of [`SECTOR_COUNT`]
/// equal-count sectors of `mesh` (by the vertices' angle about `axis`) left out: the
/// refined axes, one per sector that could be left out and the rest refined.
pub fn sector_jackknife_axes(mesh: &Mesh, axis: &Axis, options: &RefineOptions) -> Vec<Axis> {
    let Some(centroid) = mesh.centroid() else { return Vec::new() };
    let frame = axis.to_oriented_frame(&centroid);
    // The centroid lies on +x: the arc's angles do not wrap unless it is nearly whole.
    let angles: Vec<f64> = mesh.positions.iter().map(|p| frame * p).map(|q| q.y.atan2(q.x)).collect();
    let sector = equal_count_bins(&angles, &(0..angles.len()).collect::<Vec<_>>(), SECTOR_COUNT);
    (0..SECTOR_COUNT)
        .into_par_iter()
        .filter_map(|left_out| {
            let mut rest = Mesh { normals: mesh.normals.clone(), ..Mesh::new(mesh.positions.clone(), mesh.triangles.clone()) };
            rest.keep_vertices(&sector.iter().map(|s| *s != left_out).collect::<Vec<_>>());
            refine(&rest, axis, options).ok().map(|refined| refined.axis)
        })
        .collect()
}

/// The largest mean point distance (the paper's measure, over all of `mesh`'s vertices)
/// between `axis` and the axes of [`sector_jackknife_axes`], mm. `None` when no sector
/// could be left out and the rest refined.
pub fn sector_jackknife_move_mm(mesh: &Mesh, axis: &Axis, options: &RefineOptions) -> Option<f64> {
    sector_jackknife_axes(mesh, axis, options).iter().map(|refined| mean_point_distance_mm(&mesh.positions, refined, axis)).reduce(f64::max)
}

/// The jackknife's standard error of an estimate from the deviations of its leave-one-out
/// estimates from it (Quenouille and Tukey): `sqrt((n - 1) / n * sum d^2)`. The full
/// estimate stands in for the mean of the leave-out ones, which can only widen it. `None`
/// with fewer than two.
pub fn jackknife_standard_error(deviations: &[f64]) -> Option<f64> {
    let n = deviations.len();
    (n >= 2).then(|| ((n - 1) as f64 / n as f64 * deviations.iter().map(|d| d * d).sum::<f64>()).sqrt())
}

/// Half the width of the 95% interval the jackknife's `deviations` give: their standard
/// error ([`jackknife_standard_error`]) times Student's t point with one degree of freedom
/// fewer than the replicates, as a standard error from a few replicates calls for.
pub fn jackknife_half_width_95(deviations: &[f64]) -> Option<f64> {
    Some(jackknife_standard_error(deviations)? * student_t_95(deviations.len() - 1)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// For a mean the jackknife's standard error is exactly the textbook one, the sample
    /// standard deviation over the square root of the count.
    #[test]
    fn jackknife_standard_error_of_a_mean_is_the_textbook_one() {
        let values = [3.0, 7.5, 4.25, 9.0, 1.5];
        let n = values.len() as f64;
        let mean = values.iter().sum::<f64>() / n;
        let leave_outs: Vec<f64> = values.iter().map(|v| (mean * n - v) / (n - 1.0) - mean).collect();
        let sample_sd = (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        let jackknife = jackknife_standard_error(&leave_outs).unwrap();
        assert!((jackknife - sample_sd / n.sqrt()).abs() < 1e-12, "{jackknife} against {}", sample_sd / n.sqrt());
        assert_eq!(jackknife_standard_error(&[1.0]), None);
    }

    /// Four replicates leave three degrees of freedom: the interval is 3.182 standard
    /// errors wide on each side, not the normal's 1.96.
    #[test]
    fn four_replicates_take_the_t_point_of_three_degrees_of_freedom() {
        let deviations = [0.5, -1.0, 2.0, 0.25];
        let error = jackknife_standard_error(&deviations).unwrap();
        assert!((jackknife_half_width_95(&deviations).unwrap() - 3.182 * error).abs() < 1e-12);
        assert_eq!(jackknife_half_width_95(&[1.0]), None);
        assert_eq!(crate::statistics::student_t_95(1000), Some(1.960));
    }
}
