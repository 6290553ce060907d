//! The options of the automatic and the manual pre-orientation, and the bounds the
//! automatic one holds them to.

use super::line_complex::SamplerOptions;
use super::revolution_search;
use super::verdict::VerdictThresholds;
use crate::{Error, Result};

/// Most Laplacian smoothing iterations [`orient_automatic`](super::orient_automatic) accepts: smoothing past a
/// few hundred iterations has flattened any sherd, and the bound keeps a hostile option
/// value (a C caller's `SIZE_MAX`) from running for ever.
pub const MAX_SMOOTHING_ITERATIONS: usize = 1000;

/// Options of [`orient_automatic`](super::orient_automatic).
#[derive(Clone, Debug)]
pub struct OrientOptions {
    /// Vertex count of the working copy (the paper: about 10,000).
    pub target_vertex_count: usize,
    /// Laplacian smoothing iterations of the working copy (DACORD: 5).
    pub smoothing_iterations: usize,
    /// Confidence of the opposite-normal test (the paper: 0.95); `None` skips the test.
    pub opposite_normal_confidence: Option<f64>,
    /// The sampling initialiser.
    pub sampler: SamplerOptions,
    /// The whole-sphere search.
    pub search: revolution_search::SearchOptions,
    /// When the result is judged unreliable.
    pub thresholds: VerdictThresholds,
}

impl Default for OrientOptions {
    fn default() -> Self {
        OrientOptions {
            target_vertex_count: 10_000,
            smoothing_iterations: 5,
            opposite_normal_confidence: Some(0.95),
            sampler: SamplerOptions::default(),
            search: revolution_search::SearchOptions::default(),
            thresholds: VerdictThresholds::default(),
        }
    }
}

/// Options of [`orient_from_three_points`](super::orient_from_three_points).
#[derive(Clone, Copy, Debug)]
pub struct ManualOptions {
    /// Fraction of vertices kept as the pertinent surface, lowest normal-line-to-axis
    /// distance first (the paper: 50%).
    pub keep_fraction: f64,
    /// A picked point farther than this from every vertex is an error; `None`: 2% of the
    /// bounding-box diagonal.
    pub max_pick_distance_mm: Option<f64>,
}

impl Default for ManualOptions {
    fn default() -> Self {
        ManualOptions { keep_fraction: 0.5, max_pick_distance_mm: None }
    }
}

/// Option values that would make orientation run for ever or decimate to nothing.
pub(super) fn check_options(options: &OrientOptions) -> Result<()> {
    if options.smoothing_iterations > MAX_SMOOTHING_ITERATIONS {
        return Err(Error::InvalidArgument(format!(
            "smoothing_iterations must be at most {MAX_SMOOTHING_ITERATIONS}, got {}",
            options.smoothing_iterations
        )));
    }
    if options.target_vertex_count == 0 {
        return Err(Error::InvalidArgument("target_vertex_count must be at least 1".into()));
    }
    Ok(())
}
