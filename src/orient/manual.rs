//! The manual pre-orientation from three points picked on one horizontal feature (a rim,
//! a foot, a rill), for the pieces whose normals do not fix the axis.

use super::normal_lines::NormalLines;
use super::options::ManualOptions;
use super::report::{OrientReport, Orientation};
use super::verdict::Verdict;
use super::{direction, surfaces, three_points};
use crate::axis::Axis;
use crate::mesh::{Mesh, Point};
use crate::{Error, Result};

/// Manual pre-orientation from three points picked on one horizontal feature.
pub fn orient_from_three_points(mesh: &Mesh, points: [Point; 3], options: &ManualOptions) -> Result<Orientation> {
    mesh.validate()?;
    if mesh.positions.is_empty() {
        return Err(Error::DegenerateGeometry("the mesh is empty: no vertex to orient".into()));
    }
    let circle = three_points::fit_circle(&points)?;
    let (low, high) = mesh.bounding_box().expect("non-empty");
    let tolerance = options.max_pick_distance_mm.unwrap_or(0.02 * (high - low).norm());
    for (k, p) in points.iter().enumerate() {
        let nearest = mesh.positions.iter().map(|v| (v - p).norm()).fold(f64::INFINITY, f64::min);
        if nearest > tolerance {
            return Err(Error::InvalidArgument(format!(
                "point {} ({:.3}, {:.3}, {:.3}) is {:.3} mm from the nearest vertex (at most {:.3} allowed): pick it on the sherd",
                k + 1,
                p.x,
                p.y,
                p.z,
                nearest,
                tolerance
            )));
        }
    }
    let lines = NormalLines::from_mesh(mesh)?;
    let mut axis = Axis::new(circle.center, circle.normal);
    let keep = surfaces::pertinent_mask(
        &lines,
        &axis,
        &surfaces::SegmentOptions { max_line_distance_mm: None, keep_fraction: Some(options.keep_fraction) },
    );
    let evidence = direction::direction_evidence(&lines, &keep, &lines.points, &axis);
    if evidence.score < 0.0 {
        axis = axis.flipped();
    }
    let kept_vertex_count = keep.iter().filter(|k| **k).count();
    let report = OrientReport {
        method: "three points".into(),
        input_vertex_count: mesh.vertex_count(),
        working_vertex_count: mesh.vertex_count(),
        kept_vertex_count,
        opposite_filter: "not applied (manual)".into(),
        direction_cue: evidence.cue,
        direction_strength: evidence.score.abs(),
        sense_cues: evidence.cues,
        circle_radius_mm: Some(circle.radius_mm),
        ..Default::default()
    };
    Ok(Orientation {
        axis: axis.normalized(&circle.center),
        verdict: Verdict::Oriented,
        doubts: Vec::new(),
        angle_uncertainty_deg: f64::NAN,
        competitor_reach: None,
        position_uncertainty_mm: f64::NAN,
        kept_vertex_count,
        report,
        sense_inputs: None,
    })
}
