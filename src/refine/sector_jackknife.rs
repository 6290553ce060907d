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
use crate::statistics::equal_count_bins;

/// Number of equal-count sectors of the arc, each left out in turn: a quarter still
/// leaves three quarters of the arc to refine on, and costs four refinements.
pub const SECTOR_COUNT: usize = 4;

/// The refinement by `options` made again from `axis` with each of [`SECTOR_COUNT`]
/// equal-count sectors of `mesh` (by the vertices' angle about `axis`) left out: the
/// largest mean point distance (the paper's measure, over all of `mesh`'s vertices)
/// between `axis` and those refined axes, mm. `None` when no sector could be left out and
/// the rest refined.
pub fn sector_jackknife_move_mm(mesh: &Mesh, axis: &Axis, options: &RefineOptions) -> Option<f64> {
    let frame = axis.to_oriented_frame(&mesh.centroid()?);
    // The centroid lies on +x: the arc's angles do not wrap unless it is nearly whole.
    let angles: Vec<f64> = mesh.positions.iter().map(|p| frame * p).map(|q| q.y.atan2(q.x)).collect();
    let sector = equal_count_bins(&angles, &(0..angles.len()).collect::<Vec<_>>(), SECTOR_COUNT);
    let moves: Vec<f64> = (0..SECTOR_COUNT)
        .into_par_iter()
        .filter_map(|left_out| {
            let mut rest = Mesh { normals: mesh.normals.clone(), ..Mesh::new(mesh.positions.clone(), mesh.triangles.clone()) };
            rest.keep_vertices(&sector.iter().map(|s| *s != left_out).collect::<Vec<_>>());
            let refined = refine(&rest, axis, options).ok()?;
            Some(mean_point_distance_mm(&mesh.positions, &refined.axis, axis))
        })
        .collect();
    moves.into_iter().reduce(f64::max)
}
