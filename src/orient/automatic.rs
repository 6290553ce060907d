//! The automatic pre-orientation, step by step from the working copy to the verdict, and
//! the limits that decide whether its axis is given, given with a doubt, or declined.

use std::time::Instant;

use super::line_complex::{self, CenteredLines};
use super::normal_lines::NormalLines;
use super::options::{check_options, OrientOptions};
use super::report::{record_sense, CompetitorReach, OrientReport, Orientation};
use super::sense::SenseInputs;
use super::verdict::{self, Verdict};
use super::working::{decimated_copy, select_surface_of_revolution, working_copy};
use super::{landscape, revolution_search};
use crate::axis::{mean_line_distance_mm, Axis};
use crate::mesh::{Mesh, Point};
use crate::{Error, Result};

/// The automatic pre-orientation of a mesh or of a point cloud with normals.
pub fn orient_automatic(mesh: &Mesh, options: &OrientOptions) -> Result<Orientation> {
    check_orientable(mesh, options)?;
    let clock = Instant::now();
    let decimated = decimated_copy(mesh, options)?;
    let decimation_ms = clock.elapsed().as_secs_f64() * 1e3;
    let mut orientation = orient_automatic_with_decimated(mesh, decimated.as_ref(), options)?;
    orientation.report.timings_ms.insert(0, ("decimation".into(), decimation_ms));
    Ok(orientation)
}

/// [`orient_automatic`] given `decimated`, the [`decimated_copy`] of `mesh` with the same
/// options (made beforehand by a caller that uses it again).
pub fn orient_automatic_with_decimated(mesh: &Mesh, decimated: Option<&Mesh>, options: &OrientOptions) -> Result<Orientation> {
    let started = Instant::now();
    let mut timings = Vec::new();
    let mut lap = |name: &str, since: &mut Instant| {
        timings.push((name.to_string(), since.elapsed().as_secs_f64() * 1e3));
        *since = Instant::now();
    };
    let mut clock = started;
    check_orientable(mesh, options)?;
    let working = working_copy(mesh, decimated, options)?;
    lap("working copy", &mut clock);
    let all_lines = NormalLines::from_mesh_freed_of_roughness(&working)?;
    let mut report = OrientReport {
        method: "automatic".into(),
        input_vertex_count: mesh.vertex_count(),
        working_vertex_count: working.vertex_count(),
        ..Default::default()
    };
    let lines = select_surface_of_revolution(&working, &all_lines, options, &mut report);
    lap("opposite normals", &mut clock);
    report.kept_vertex_count = lines.len();
    if lines.len() < options.thresholds.min_lines {
        let reason = format!(
            "too few points on the surface of revolution: {} kept of {} (at least {} needed)",
            lines.len(),
            all_lines.len(),
            options.thresholds.min_lines
        );
        return Ok(unoriented(mesh, reason, report, lines.len()));
    }
    let centered = CenteredLines::new(&lines);
    report.normal_spread = verdict::normal_spread(&centered);
    report.concurrency_ratio = line_complex::fit_complex(&centered, None, None).map_or(1.0, |g| g.concurrency_ratio());
    let Some(landscape) = revolution_search::search(&lines, &options.search) else {
        let reason = format!("too few points on the surface of revolution: {} kept", lines.len());
        return Ok(unoriented(mesh, reason, report, lines.len()));
    };
    lap("whole-sphere search", &mut clock);
    let Some(best) = landscape.valleys.first().copied() else {
        let reason = "no axis makes the piece a surface of revolution".to_string();
        return Ok(unoriented(mesh, reason, report, lines.len()));
    };
    let mut axis = best.axis(&landscape.samples);
    report.search_cost = best.fit.cost;
    report.inlier_fraction = best.fit.inlier_share;
    let blocks = landscape::sample_blocks(&landscape.samples);
    let competitors = landscape::competing_valleys(&landscape, &blocks, MIN_COMPETITOR_ANGLE_DEG);
    let closest = competitors.iter().min_by(|a, b| a.separation.t_statistic.total_cmp(&b.separation.t_statistic));
    report.competitor = closest.map(|c| (c.angle_deg, c.separation.t_statistic));
    report.position_hold = landscape::position_hold(&landscape.samples, &axis, POSITION_PROBE_MM, landscape.loss_scale_mm);
    let (angle_uncertainty_deg, position_uncertainty_mm) = landscape::valley_width(&landscape.samples, &blocks, &axis, landscape.loss_scale_mm);
    lap("landscape verdict", &mut clock);

    let sense_inputs = SenseInputs {
        samples: revolution_search::RevolutionSamples::from_lines(&lines, lines.len(), options.search.band_spacings, options.search.min_band_mm),
        all_samples: revolution_search::RevolutionSamples::from_lines(&all_lines, all_lines.len(), options.search.band_spacings, options.search.min_band_mm),
        lines: lines.clone(),
        all_points: all_lines.points.clone(),
        loss_scale_mm: landscape.loss_scale_mm,
        min_confidence: options.thresholds.min_sense_confidence,
    };
    let (oriented, evidence) = sense_inputs.judge(&axis);
    axis = oriented.normalized(&lines.centroid());
    let on_surface = sense_inputs.on_surface(&axis);
    let mut radii: Vec<f64> = lines.points.iter().map(|p| axis.distance_to(p)).collect();
    radii.sort_unstable_by(f64::total_cmp);
    report.median_radius_mm = radii[radii.len() / 2];
    report.residual_angle_deg = verdict::axis_residual_angle_deg(&lines, &axis, &on_surface);
    lap("direction", &mut clock);

    let sense_verdict = sense_inputs.verdict(&evidence);
    let mut doubts = Vec::new();
    let mut crossing_unresolved = None;
    let unresolved: Vec<&landscape::CompetingValley> = competitors.iter().filter(|c| !(c.separation.t_statistic >= MIN_SEPARATION_T)).collect();
    let competitor_reach = CompetitorReach::of(&unresolved, &axis, &lines.points);
    let describe = |competitor: &&landscape::CompetingValley| {
        format!(
            "another axis {:.0} degrees away fits the piece almost as well (the best fits better in {} blocks of the piece by t = {:.1}, at least {MIN_SEPARATION_T} wanted)",
            competitor.angle_deg, competitor.separation.blocks, competitor.separation.t_statistic
        )
    };
    // An axis across the best one makes the piece a surface of revolution about the other
    // principal curvature (a jar's belly, a near-spherical piece, a tiny piece): only a
    // lip level under the best tells the two apart. Not a floor: under a wrong axis
    // through a near-spherical piece its cap reads as one.
    let level_lip = evidence.cues.level_edge.abs() >= options.thresholds.min_sense_confidence;
    // A crossing competitor the best still beats at the 5% level (though not at 1%) leaves
    // an answer to give with its doubt; below that the two are a coin toss.
    let undecided = |competitor: &&&landscape::CompetingValley| {
        competitor.angle_deg > verdict::CROSSING_COMPETITOR_ANGLE_DEG && !(competitor.separation.t_statistic >= MIN_CROSSING_SEPARATION_T)
    };
    if let Some(crossing) = unresolved.iter().find(undecided).filter(|_| !level_lip) {
        crossing_unresolved = Some(describe(crossing));
    } else if let Some(nearest) = unresolved.iter().min_by(|a, b| a.separation.t_statistic.total_cmp(&b.separation.t_statistic)) {
        doubts.push(describe(nearest));
    }
    let line_verdict = if !best.fit.position_fixed || report.normal_spread < options.thresholds.min_normal_spread {
        Some(Verdict::NeedsManualOrientation {
            reason: format!(
                "the normals are nearly parallel (spread {:.3}): a flat piece gives the axis's direction but not its position",
                report.normal_spread
            ),
        })
    } else if !(report.position_hold >= MIN_POSITION_HOLD) {
        Some(Verdict::NeedsManualOrientation {
            reason: format!(
                "the piece does not fix the axis's position: moved {POSITION_PROBE_MM} mm, the axis fits it at worst {:.0}% worse (at least {:.0}% wanted): a flat piece, or a floor without its foot",
                100.0 * report.position_hold,
                100.0 * MIN_POSITION_HOLD
            ),
        })
    } else if best.fit.inlier_share < MIN_INLIER_SHARE {
        Some(Verdict::NeedsManualOrientation {
            reason: format!(
                "no axis makes more than {:.0}% of the piece a surface of revolution (the best: {:.0}%)",
                100.0 * MIN_INLIER_SHARE,
                100.0 * best.fit.inlier_share
            ),
        })
    } else {
        crossing_unresolved.map(|competitor| Verdict::NeedsManualOrientation {
            reason: format!("{competitor}, and nothing on the sherd (floor, level edge) says which is the vessel's: a doubly curved or near-spherical piece"),
        })
    };
    let verdict = line_verdict.unwrap_or(sense_verdict);
    if !verdict.has_axis_line() {
        // A declined piece's reason says what is wrong; doubts are about answers.
        doubts.clear();
    }
    record_sense(&mut report, &evidence);
    report.timings_ms = timings;
    let kept_vertex_count = lines.len();
    Ok(Orientation {
        axis,
        verdict,
        doubts,
        angle_uncertainty_deg,
        position_uncertainty_mm,
        competitor_reach,
        kept_vertex_count,
        report,
        sense_inputs: Some(std::sync::Arc::new(sense_inputs)),
    })
}

impl CompetitorReach {
    /// The reach of `unresolved` competitors from `axis`, over the fragment's `points`;
    /// `None` when there are none.
    fn of(unresolved: &[&landscape::CompetingValley], axis: &Axis, points: &[Point]) -> Option<Self> {
        unresolved.iter().map(|c| CompetitorReach { angle_deg: c.angle_deg, distance_mm: mean_line_distance_mm(points, &c.axis, axis) }).reduce(|a, b| CompetitorReach {
            angle_deg: a.angle_deg.max(b.angle_deg),
            distance_mm: a.distance_mm.max(b.distance_mm),
        })
    }
}

/// Valleys of the landscape nearer than this to the best lie in the refinement's reach,
/// degrees (it searches 10 degrees about its start): they are not competitors.
const MIN_COMPETITOR_ANGLE_DEG: f64 = 15.0;
/// The least t statistic of the best valley over a competitor, block by block, for the
/// landscape to have picked one axis (a one-sided test at about 1% with 10-16 blocks);
/// below it the axis is given as uncertain.
const MIN_SEPARATION_T: f64 = 3.0;
/// The least t statistic of the best valley over a competitor across it (more than
/// [`verdict::CROSSING_COMPETITOR_ANGLE_DEG`] away) for the best to be given as an answer
/// at all, with its doubt below [`MIN_SEPARATION_T`]: a one-sided test at about 5%.
const MIN_CROSSING_SEPARATION_T: f64 = 2.0;
/// How far the position probe moves the best axis, mm: well past what makes an axis
/// wrong (4 mm of mean point distance).
const POSITION_PROBE_MM: f64 = 10.0;
/// The least relative rise of the loss over that move for the piece to fix the axis's
/// position: a tenth, where a flat piece's loss moves by a few percent either way (its
/// noise) and a wall's, even a short arc's, at least doubles.
const MIN_POSITION_HOLD: f64 = 0.1;
/// The least share of the piece the best axis must put on a surface of revolution.
const MIN_INLIER_SHARE: f64 = 0.5;

/// Options in their bounds and a valid, non-empty mesh whose vertices are not all in one plane.
fn check_orientable(mesh: &Mesh, options: &OrientOptions) -> Result<()> {
    check_options(options)?;
    mesh.validate()?;
    if mesh.positions.is_empty() {
        return Err(Error::DegenerateGeometry("the mesh is empty: no vertex to orient".into()));
    }
    reject_coplanar(mesh)
}

/// All vertices in one plane: no thickness and no curvature, nothing to orient (an error,
/// unlike a flat but thick base piece, which is a verdict).
fn reject_coplanar(mesh: &Mesh) -> Result<()> {
    let center = mesh.centroid().expect("non-empty");
    let mut scatter = nalgebra::Matrix3::zeros();
    for p in &mesh.positions {
        let d = p - center;
        scatter += d * d.transpose();
    }
    let eigen = nalgebra::SymmetricEigen::new(scatter);
    let largest = eigen.eigenvalues.max();
    if mesh.vertex_count() < 4 || eigen.eigenvalues.min() <= largest * 1e-12 {
        return Err(Error::DegenerateGeometry(format!(
            "all {} vertices lie in one plane (or on a line): a sherd has thickness and curvature",
            mesh.vertex_count()
        )));
    }
    Ok(())
}

fn unoriented(mesh: &Mesh, reason: String, report: OrientReport, kept: usize) -> Orientation {
    let center = mesh.centroid().unwrap_or_else(Point::origin);
    Orientation {
        axis: Axis::new(center, crate::mesh::Vector::z()),
        verdict: Verdict::NeedsManualOrientation { reason },
        doubts: Vec::new(),
        angle_uncertainty_deg: f64::INFINITY,
        position_uncertainty_mm: f64::INFINITY,
        competitor_reach: None,
        kept_vertex_count: kept,
        report,
        sense_inputs: None,
    }
}
