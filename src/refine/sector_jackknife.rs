//! Jackknife of the refined axis over sectors of the preserved arc: the refinement
//! (Wilczek et al. 2018, section 2.3, by the criterion the options ask for) made again
//! with each quarter of the arc left out, from the refined axis.
//!
//! Why: the bootstrap ([`super::uncertainty`]) resamples horizontal sections, and every
//! section spans the whole arc. The vessel's ovality and wobble mislead them all alike, so
//! on a clean scan the resamples agree about an axis that is off (without scan noise the
//! bootstrap's angle intervals reached 0.5-1.5 degrees around body sherds 1.3-4.7 degrees
//! off: BENCHMARKS.md, session 22). The deformation differs along the arc: an axis the
//! arc's local shape put where it is, rather than its turning, moves when a quarter of
//! the arc is left out.

use rayon::prelude::*;

use super::{refine, RefineOptions};
use crate::mesh::Mesh;
use crate::orient::{mean_point_distance_mm, Axis};

/// Number of equal-count sectors of the arc, each left out in turn: a quarter still
/// leaves three quarters of the arc to refine on, and costs four refinements.
pub const SECTOR_COUNT: usize = 4;

/// What leaving out each sector of the arc did to the axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SectorJackknife {
    /// Largest mean point distance (the paper's measure, over all the fragment's
    /// vertices) between the refined axis and the axis refined without one sector, mm.
    pub largest_move_mm: f64,
    /// Sectors whose leaving out still left something to refine.
    pub refitted: usize,
}

/// The refinement by `options` made again from `axis` with each of [`SECTOR_COUNT`]
/// equal-count sectors of `mesh` (by the vertices' angle about `axis`) left out; `None`
/// when no sector could be left out and the rest refined.
pub fn sector_jackknife(mesh: &Mesh, axis: &Axis, options: &RefineOptions) -> Option<SectorJackknife> {
    let centroid = mesh.centroid()?;
    let frame = axis.to_oriented_frame(&centroid);
    // The centroid lies on +x: the arc's angles do not wrap unless it is nearly whole.
    let angles: Vec<f64> = mesh.positions.iter().map(|p| {
        let q = frame * p;
        q.y.atan2(q.x)
    }).collect();
    let mut order: Vec<usize> = (0..angles.len()).collect();
    order.sort_by(|a, b| angles[*a].total_cmp(&angles[*b]));
    let mut sector = vec![0; angles.len()];
    for (rank, &i) in order.iter().enumerate() {
        sector[i] = rank * SECTOR_COUNT / order.len().max(1);
    }
    let moves: Vec<f64> = (0..SECTOR_COUNT)
        .into_par_iter()
        .filter_map(|left_out| {
            let rest = without_vertices(mesh, |i| sector[i] == left_out);
            let refined = refine(&rest, axis, options).ok()?;
            Some(mean_point_distance_mm(&mesh.positions, &refined.axis, axis))
        })
        .collect();
    (!moves.is_empty()).then(|| SectorJackknife { largest_move_mm: moves.iter().copied().fold(0.0, f64::max), refitted: moves.len() })
}

/// `mesh` without the vertices `left_out` names and the triangles that use them, with
/// its normals; the other attributes (colours, texture, quality) are not carried.
fn without_vertices(mesh: &Mesh, left_out: impl Fn(usize) -> bool) -> Mesh {
    let mut index = vec![u32::MAX; mesh.positions.len()];
    let mut positions = Vec::new();
    let mut normals = mesh.normals.as_ref().map(|_| Vec::new());
    for i in 0..mesh.positions.len() {
        if left_out(i) {
            continue;
        }
        index[i] = positions.len() as u32;
        positions.push(mesh.positions[i]);
        if let (Some(kept), Some(all)) = (normals.as_mut(), mesh.normals.as_ref()) {
            kept.push(all[i]);
        }
    }
    let triangles = mesh
        .triangles
        .iter()
        .filter_map(|t| {
            let mapped = t.map(|v| index[v as usize]);
            mapped.iter().all(|v| *v != u32::MAX).then_some(mapped)
        })
        .collect();
    Mesh { positions, triangles, normals, ..Default::default() }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Point, Vector};

    #[test]
    fn leaving_out_vertices_drops_their_triangles_and_keeps_the_normals_of_the_rest() {
        let positions = vec![Point::new(0.0, 0.0, 0.0), Point::new(1.0, 0.0, 0.0), Point::new(0.0, 1.0, 0.0), Point::new(1.0, 1.0, 0.0)];
        let normals = (0..4).map(|i| Vector::new(0.0, i as f64, 1.0).normalize()).collect();
        let mesh = Mesh { normals: Some(normals), ..Mesh::new(positions, vec![[0, 1, 2], [1, 3, 2]]) };
        let rest = without_vertices(&mesh, |i| i == 0);
        assert_eq!(rest.positions, vec![Point::new(1.0, 0.0, 0.0), Point::new(0.0, 1.0, 0.0), Point::new(1.0, 1.0, 0.0)]);
        assert_eq!(rest.triangles, vec![[0, 2, 1]]);
        assert_eq!(rest.normals.unwrap()[2], Vector::new(0.0, 3.0, 1.0).normalize());
    }
}
