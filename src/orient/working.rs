//! The copy of a scan that the automatic pre-orientation works on, decimated and smoothed
//! because decoration and scan noise carry nothing on the axis and bias it, and the
//! normal lines of that copy that lie on the surface of revolution.

use super::normal_lines::NormalLines;
use super::opposite_normals;
use super::options::{check_options, OrientOptions};
use super::report::OrientReport;
use crate::mesh::Mesh;
use crate::{Error, Result};

/// The decimated copy of `mesh` the automatic pre-orientation works on, before it is
/// smoothed: about two faces per wanted vertex (quadric edge collapse), or the mesh itself
/// when it has at most a quarter more faces than that. `None` when the mesh is a point
/// cloud or has no more faces than that already (it is then not smoothed either). The pipeline refines
/// and bootstraps on the same copy, so that a large scan is decimated once.
pub fn decimated_copy(mesh: &Mesh, options: &OrientOptions) -> Result<Option<Mesh>> {
    check_options(options)?;
    let target_faces = 2 * options.target_vertex_count;
    if mesh.is_point_cloud() || mesh.face_count() <= target_faces {
        return Ok(None);
    }
    // Within a quarter of the working size, the mesh is its own working copy (still
    // smoothed): collapsing the last few percent of faces changes nothing the axis
    // depends on and cost as much as the rest of a 10k-vertex orientation's fit.
    if mesh.face_count() * 4 <= target_faces * 5 {
        return Ok(Some(mesh.clone()));
    }
    crate::mesh::decimate::decimate_shape(mesh, target_faces).map(Some)
}

/// The working copy the paper orients on: decimated to about the target vertex count
/// (`decimated`, from [`decimated_copy`]) and smoothed (meshes); point clouds are thinned
/// by an even stride.
pub fn working_copy(mesh: &Mesh, decimated: Option<&Mesh>, options: &OrientOptions) -> Result<Mesh> {
    if mesh.is_point_cloud() {
        if mesh.normals.is_none() {
            return Err(Error::InvalidArgument(
                "a point cloud without normals cannot be oriented: give normals or faces".into(),
            ));
        }
        if mesh.vertex_count() <= options.target_vertex_count {
            return Ok(mesh.clone());
        }
        let step = mesh.vertex_count() as f64 / options.target_vertex_count as f64;
        let picked: Vec<usize> =
            (0..options.target_vertex_count).map(|k| ((k as f64 * step) as usize).min(mesh.vertex_count() - 1)).collect();
        let normals = mesh.normals.as_ref().expect("checked above");
        return Ok(Mesh::from_points_and_normals(
            picked.iter().map(|&i| mesh.positions[i]).collect(),
            picked.iter().map(|&i| normals[i]).collect(),
        ));
    }
    // Quadric decimation to about two faces per wanted vertex, then Laplacian smoothing:
    // decoration and scan noise carry no information on the axis, and noisy normals bias
    // a least-squares axis (errors in the variables).
    // A mesh already coarser than the target is not smoothed: its edges are long next to
    // the wall thickness and smoothing would round the whole sherd (measured: rim pieces
    // of 2 mm cells went 80 degrees wrong), while its normals are not noisy at that scale.
    let mut working = match decimated {
        Some(decimated) => decimated.clone(),
        None => mesh.clone(),
    };
    if decimated.is_some() && options.smoothing_iterations > 0 {
        let smoothing = crate::mesh::smooth::SmoothOptions {
            iterations: options.smoothing_iterations,
            ..Default::default()
        };
        crate::mesh::smooth::laplacian_smooth(&mut working, &smoothing);
    }
    working.normals = None; // recomputed from the smoothed faces by NormalLines
    Ok(working)
}

/// The normal lines of `working` (a [`working_copy`]) on the surface of revolution, as the
/// opposite-normal test leaves them (all of them where it cannot run or keeps too few).
pub fn surface_of_revolution_lines(working: &Mesh, options: &OrientOptions) -> Result<NormalLines> {
    let all_lines = NormalLines::from_mesh_freed_of_roughness(working)?;
    Ok(select_surface_of_revolution(working, &all_lines, options, &mut OrientReport::default()))
}

/// The lines on the surface of revolution: the opposite-normal test on meshes, all lines
/// of point clouds (they carry no faces to cast rays at).
pub(super) fn select_surface_of_revolution(
    working: &Mesh,
    lines: &NormalLines,
    options: &OrientOptions,
    report: &mut OrientReport,
) -> NormalLines {
    let Some(confidence) = options.opposite_normal_confidence else {
        report.opposite_filter = "not applied (disabled)".into();
        return lines.clone();
    };
    if working.is_point_cloud() {
        report.opposite_filter = "not applied (point cloud: no faces to cast rays at)".into();
        return lines.clone();
    }
    let bvh = crate::mesh::spatial::Bvh::new(working);
    // Start a hair inside the surface so that the vertex's own faces are not hit.
    let inset = 1e-6 * lines.size_mm();
    let filter = opposite_normals::filter_opposite_normals(lines, confidence, |origin, direction| {
        let start = origin + direction * inset;
        bvh.closest_hit(&start, direction).map(|hit| {
            (working.face_normal_scaled(hit.face).normalize(), hit.distance + inset)
        })
    });
    report.wall_thickness_mm = filter.median_thickness_mm.is_finite().then_some(filter.median_thickness_mm);
    // A piece that is mostly fracture (tiny sherds) or a single skin (an open scan) leaves
    // too little: then the robust regression alone separates the outliers.
    if filter.kept_count < options.thresholds.min_lines.max(lines.len() / 5) {
        report.opposite_filter = format!(
            "not applied: only {} of {} vertices have an opposite partner (single skin or mostly fracture)",
            filter.kept_count,
            lines.len()
        );
        return lines.clone();
    }
    report.opposite_filter = format!(
        "kept {} of {} vertices (median deviation {:.1} deg, wall {:.2} mm)",
        filter.kept_count,
        lines.len(),
        filter.median_deviation_deg,
        filter.median_thickness_mm
    );
    lines.filtered(|i| filter.keep[i])
}
