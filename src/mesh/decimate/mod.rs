//! Quadric edge-collapse decimation (Garland and Heckbert 1997), as MeshLab's
//! "Quadric Edge Collapse Decimation" does it: every vertex carries the error quadric
//! (`crate::mesh::quadric::Quadric`) of its faces' planes (area weighted), edges are
//! collapsed cheapest first to the point minimising the sum of their endpoints'
//! quadrics, and a collapse is refused when it would change the topology (the link
//! condition of Dey et al. 1999), flip or fold a face (normal check), or it is
//! penalised when it creates slivers (MeshLab's quality threshold). Boundaries are kept
//! by quadrics of planes through each boundary edge perpendicular to its face (section
//! 6.1 of the paper), or frozen ([`BoundaryPolicy`]). Colours, normals and quality are
//! interpolated at the kept vertex's new place, with its barycentric coordinates in the
//! collapsed edge's face it falls most inside of (along the edge when it stays on it).
//!
//! Texture coordinates are per corner (wedges, as MeshLab keeps them), so a vertex on a
//! texture seam has one position and two or more UVs. A collapse moves each corner's UV
//! with the vertex: the new UV of a wedge is interpolated between the UVs the two
//! endpoints have in the same chart, read from the collapsed edge's own faces. A
//! collapse is refused when a moving vertex has a wedge the edge's faces do not reach
//! (it would drag a chart across a seam); seam vertices are placed like boundary
//! vertices (they stay on the seam polyline, which gets a boundary-like quadric), and
//! where three or more charts meet the vertex is kept in place.
//!
//! Speed: the orientation decimates 500k-face scans to about 20k faces first, so the
//! structures are flat arrays: per-vertex circular lists of face corners threaded
//! through one `next_corner` array, a binary heap of candidate edges with lazy
//! deletion (an entry is stale when either endpoint changed after it was pushed), and
//! no hash map. Candidates are re-evaluated when popped, since their neighbourhood
//! may have changed.
//!
//! Why not a crate: meshoptimizer's simplifier (the `meshopt` crate) was measured by an
//! earlier implementation to break topology on scans (non-manifold edges; its issue
//! tracker has such reports, e.g. zeux/meshoptimizer#699), has no link condition to
//! enable, and collapses onto existing vertices rather than the quadric's optimum.
//! It was not re-measured for this implementation.
//!
//! Files, each importing only those before it: `options` (what is asked and reported),
//! `queue` (candidates, cheapest first), `barycentric` (the weights of a new place in a
//! face), `collapser` (the flat arrays, the collapse loop, the result), `evaluation` (a
//! candidate's place, cost and checks) and `seams` (texture seams); the last two add
//! methods to the collapser.

mod barycentric;
mod collapser;
mod evaluation;
mod options;
mod queue;
mod seams;

use std::time::Instant;

use collapser::Collapser;
use crate::mesh::Mesh;
use crate::{Error, Result};

pub use options::{BoundaryPolicy, DecimateOptions, DecimateReport};

/// Decimates `mesh` to `target_faces` faces with the default options (see
/// [`DecimateOptions::default`]).
pub fn decimate(mesh: &Mesh, target_faces: usize) -> Result<Mesh> {
    decimate_with_options(mesh, &DecimateOptions::with_target_faces(target_faces)).map(|(mesh, _)| mesh)
}

/// `mesh` decimated to `target_faces` for its shape alone (the default options without
/// texture coordinates): texture seams would only hold collapses back where nothing
/// looks at the texture (orientation, refinement).
pub fn decimate_shape(mesh: &Mesh, target_faces: usize) -> Result<Mesh> {
    let options = DecimateOptions { keep_texture_coordinates: false, ..DecimateOptions::with_target_faces(target_faces) };
    decimate_with_options(mesh, &options).map(|(decimated, _)| decimated)
}

/// Decimates `mesh` by quadric edge collapse; returns the result and what was done.
///
/// Errors: an invalid mesh ([`Mesh::validate`]), a point cloud, a zero target, a
/// non-finite or non-positive option.
pub fn decimate_with_options(mesh: &Mesh, options: &DecimateOptions) -> Result<(Mesh, DecimateReport)> {
    let started = Instant::now();
    mesh.validate()?;
    if mesh.is_point_cloud() {
        return Err(Error::InvalidArgument("decimation needs a mesh with faces, got a point cloud".into()));
    }
    if options.target_faces == 0 || options.target_vertices == Some(0) {
        return Err(Error::InvalidArgument("decimation target must be at least one face and one vertex".into()));
    }
    if !(options.max_normal_change_deg > 0.0 && options.max_normal_change_deg <= 180.0) {
        return Err(Error::InvalidArgument(format!(
            "max_normal_change_deg must be in (0, 180], got {}",
            options.max_normal_change_deg
        )));
    }
    if let Some(threshold) = options.quality_threshold
        && !(threshold > 0.0 && threshold <= 1.0)
    {
        return Err(Error::InvalidArgument(format!("quality_threshold must be in (0, 1], got {threshold}")));
    }
    if let BoundaryPolicy::Weighted { weight } = options.boundary
        && !(weight.is_finite() && weight >= 0.0)
    {
        return Err(Error::InvalidArgument(format!("boundary weight must be finite and >= 0, got {weight}")));
    }

    if mesh.face_count() <= options.target_faces || options.target_vertices.is_some_and(|n| mesh.vertex_count() <= n) {
        let report = DecimateReport {
            input_vertices: mesh.vertex_count(),
            input_faces: mesh.face_count(),
            output_vertices: mesh.vertex_count(),
            output_faces: mesh.face_count(),
            reached_target: true,
            elapsed_seconds: started.elapsed().as_secs_f64(),
            ..Default::default()
        };
        return Ok((mesh.clone(), report));
    }
    let mut collapser = Collapser::new(mesh, options);
    collapser.run(options.target_faces, options.target_vertices.unwrap_or(0));
    let (mut result, mut report) = collapser.finish();
    if result.corner_uvs.is_some() {
        result.texture = mesh.texture.clone();
    }
    report.elapsed_seconds = started.elapsed().as_secs_f64();
    Ok((result, report))
}
