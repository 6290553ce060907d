//! What a decimation is asked to do and what it reports: the boundary policy, the options
//! and the report.

use serde::{Deserialize, Serialize};

// For the doc links only.
#[cfg(doc)]
use super::decimate_with_options;

/// How boundary edges (edges with one face) are kept.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum BoundaryPolicy {
    /// Boundary vertices never move and are never removed (MeshLab's "Preserve
    /// Boundary"): the boundary stays exactly as it was, but keeps all its vertices.
    Fixed,
    /// Each boundary edge adds the quadric of the plane through it perpendicular to its
    /// face, weighted by `weight` times the squared edge length: boundary vertices may
    /// slide along the boundary but pay heavily for leaving it (Garland and Heckbert,
    /// section 6.1).
    Weighted {
        /// Relative weight of the boundary planes (face planes are weighted by area).
        weight: f64,
    },
}

/// Parameters of [`decimate_with_options`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DecimateOptions {
    /// Number of faces to reach. Each interior collapse removes two faces, a boundary
    /// one removes one, so the result has `target_faces` or one fewer, unless the
    /// topology or the boundary forbid further collapses (see the report).
    pub target_faces: usize,
    /// When set, decimation also stops once at most this many vertices remain
    /// (whichever target is reached first): the orientation asks for ~10k vertices.
    pub target_vertices: Option<usize>,
    /// How boundaries are kept.
    pub boundary: BoundaryPolicy,
    /// Collapses that turn any remaining face's normal by more than this, from its
    /// current or from its input direction, are refused; 90 degrees or more would
    /// allow flipped faces.
    pub max_normal_change_deg: f64,
    /// MeshLab's quality threshold: a collapse whose worst new triangle has a quality
    /// `q < threshold` (`q` = 1 for equilateral, 0 for degenerate; `4√3 area / Σ edge²`)
    /// has its cost multiplied by `threshold / q`. `None` ignores triangle shape.
    pub quality_threshold: Option<f64>,
    /// Place the kept vertex at the quadric's minimiser (true) or at the best point of
    /// the collapsed edge (false).
    pub optimal_placement: bool,
    /// Keep per-corner texture coordinates and the texture through decimation (texture
    /// seams then constrain the collapses); false drops them, for uses that only need the
    /// shape (the orientation).
    #[serde(default = "keep_by_default")]
    pub keep_texture_coordinates: bool,
}

fn keep_by_default() -> bool {
    true
}

impl Default for DecimateOptions {
    /// The settings the orientation uses: 20k faces (about 10k vertices), weighted
    /// boundary, normals turned at most 60°, quality threshold 0.3, optimal placement.
    fn default() -> Self {
        DecimateOptions {
            target_faces: 20_000,
            target_vertices: None,
            boundary: BoundaryPolicy::Weighted { weight: 100.0 },
            max_normal_change_deg: 60.0,
            quality_threshold: Some(0.3),
            optimal_placement: true,
            keep_texture_coordinates: true,
        }
    }
}

impl DecimateOptions {
    /// The default options with another target face count.
    pub fn with_target_faces(target_faces: usize) -> Self {
        DecimateOptions { target_faces, ..Default::default() }
    }

    /// The default options aiming at a vertex count instead (the face target is then
    /// one face, so only the vertex target stops decimation).
    pub fn with_target_vertices(target_vertices: usize) -> Self {
        DecimateOptions { target_faces: 1, target_vertices: Some(target_vertices), ..Default::default() }
    }
}

/// What [`decimate_with_options`] did.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct DecimateReport {
    /// Vertices of the input.
    pub input_vertices: usize,
    /// Faces of the input.
    pub input_faces: usize,
    /// Vertices of the result (unreferenced input vertices are dropped).
    pub output_vertices: usize,
    /// Faces of the result.
    pub output_faces: usize,
    /// Input faces with a repeated vertex, dropped before decimating.
    pub degenerate_faces_dropped: usize,
    /// Edge collapses performed.
    pub collapses: usize,
    /// Candidate collapses refused because they would change the topology.
    pub refused_for_topology: usize,
    /// Candidate collapses refused because a face would turn by more than the limit or
    /// degenerate.
    pub refused_for_normals: usize,
    /// Vertices that never moved: on non-manifold edges, and on the boundary with
    /// [`BoundaryPolicy::Fixed`].
    pub frozen_vertices: usize,
    /// Boundary edges before and after.
    pub boundary_edges_before: usize,
    /// Boundary edges after decimation.
    pub boundary_edges_after: usize,
    /// Edges with more than two faces in the input (their vertices are frozen).
    pub non_manifold_edges: usize,
    /// True when the target face (or vertex) count was reached.
    pub reached_target: bool,
    /// Largest collapse cost accepted, as an RMS distance in mm (the square root of
    /// the quadric error divided by the quadric's total area weight).
    pub max_collapse_error_mm: f64,
    /// Candidate collapses refused because they would drag texture coordinates across a
    /// texture seam.
    pub refused_for_texture_seams: usize,
    /// Vertices of the input on a texture seam (two or more UVs).
    pub seam_vertices: usize,
    /// Texture coordinates (and the texture) were dropped, as
    /// [`DecimateOptions::keep_texture_coordinates`] asked.
    pub texture_dropped: bool,
    /// Wall-clock time of the decimation.
    pub elapsed_seconds: f64,
}
