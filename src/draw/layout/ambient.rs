//! The ambient light the views shade with: sharp near occlusion per vertex, the far part
//! smoothed, stretched over the fragment's own range.

use crate::draw::occlusion::near_and_far_light;
use crate::draw::view::OcclusionField;
use crate::draw::DrawOptions;
use crate::mesh::Mesh;
use crate::statistics::central_range;
use crate::{Error, Result};

/// Share of the mesh's bounding-box diagonal within which an occluder's shadow stays sharp
/// in a drawing (grooves, rills, the crease of a carination); farther shadows are smoothed
/// over the view (see [`near_and_far_light`]).
const NEAR_OCCLUSION_REACH_SHARE: f64 = 0.06;

/// The ambient light a view shades with: the near light per vertex, the rest as a factor
/// the view smooths, and the stretch of their product over the fragment's 2nd..98th
/// percentiles (sherds are mostly open: unstretched occlusion would be invisible).
pub(super) fn occlusion_field(mesh: &Mesh, options: &DrawOptions) -> Result<OcclusionField> {
    let (lo, hi) = mesh.bounding_box().ok_or_else(|| Error::DegenerateGeometry("no vertex to shade".into()))?;
    let reach_mm = ((hi - lo).norm() * NEAR_OCCLUSION_REACH_SHARE).max(1e-6);
    let light = near_and_far_light(mesh, &options.occlusion, reach_mm)?;
    let (near, full) = rayon::join(|| smooth_over_neighbours(mesh, light.near, 4), || smooth_over_neighbours(mesh, light.full, 4));
    let far_factor: Vec<f32> = full.iter().zip(&near).map(|(&f, &n)| if n > 0.0 { (f / n).min(1.0) } else { 1.0 }).collect();
    let (low, high) = central_range(full.iter().copied()).unwrap_or((0.0, 1.0));
    Ok(OcclusionField { near, far_factor, low, span: (high - low).max(1e-6) })
}

/// Averages each vertex's value with its neighbours' `passes` times: the shadow edges of
/// near occluders soften over a few vertices.
fn smooth_over_neighbours(mesh: &Mesh, mut values: Vec<f32>, passes: usize) -> Vec<f32> {
    for _ in 0..passes {
        let mut sum = values.clone();
        let mut count = vec![1u32; values.len()];
        for t in &mesh.triangles {
            for k in 0..3 {
                let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
                sum[a] += values[b];
                count[a] += 1;
                sum[b] += values[a];
                count[b] += 1;
            }
        }
        values = sum.iter().zip(&count).map(|(s, &c)| s / c as f32).collect();
    }
    values
}
