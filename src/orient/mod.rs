//! Pre-orientation (Wilczek et al. 2018, section 2.2): the rotation axis of the vessel a
//! fragment came from, from its normals or from three points on a horizontal feature,
//! with an honest verdict when the data do not determine it.
//!
//! Automatic pipeline ([`orient_automatic`]): working copy (decimated, smoothed,
//! area-weighted normals) -> normal lines -> opposite-normal filter (`opposite_normals`)
//! -> whole-sphere search of the directions, each axis placed where the normal lines meet
//! and scored as a surface of revolution ([`revolution_search`]) -> the verdict of its
//! landscape ([`landscape`]) -> sense base to rim ([`direction`]) -> verdict ([`verdict`]).

pub mod direction;
pub mod landscape;
pub mod line_complex;
pub mod normal_lines;
pub(crate) mod opposite_normals;
pub mod revolution_search;
pub(crate) mod surfaces;
pub(crate) mod three_points;
pub mod verdict;

use std::time::Instant;

use serde::{Deserialize, Serialize};

pub use crate::axis::{angle_between_deg, mean_line_distance_mm, mean_point_distance_mm, Axis, AxisRecord};
pub use surfaces::{segment_surfaces, Skin};
pub use verdict::{Verdict, VerdictThresholds};

use crate::mesh::{Mesh, Point};
use crate::{Error, Result};
use line_complex::{CenteredLines, SamplerOptions};
use normal_lines::NormalLines;

/// Most Laplacian smoothing iterations [`orient_automatic`] accepts: smoothing past a
/// few hundred iterations has flattened any sherd, and the bound keeps a hostile option
/// value (a C caller's `SIZE_MAX`) from running for ever.
pub const MAX_SMOOTHING_ITERATIONS: usize = 1000;


/// Options of [`orient_automatic`].
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

/// Options of [`orient_from_three_points`].
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

/// What the orientation found and how far to trust it.
#[derive(Clone, Debug)]
pub struct Orientation {
    /// The axis in the input's frame, base to rim.
    pub axis: Axis,
    /// Whether the axis can be used.
    pub verdict: Verdict,
    /// Why an axis given as found may still be wrong (another axis fits about as well):
    /// such an axis is `axis_uncertain`. Empty when there is none.
    pub doubts: Vec<String>,
    /// How far the direction can turn, degrees, before the axis fits the piece worse
    /// block by block ([`landscape::valley_width`]): the width of its valley in units of
    /// the piece's own noise and deformation. NaN for a manual axis, infinite when no axis
    /// was found.
    pub angle_uncertainty_deg: f64,
    /// The same for a move of the axis across itself near the sherd, millimetres.
    pub position_uncertainty_mm: f64,
    /// How far the valleys of the search that the fragment does not rule out lie from
    /// the axis: an answer's intervals reach them. `None` when every other valley fits
    /// clearly worse, and for a manual axis.
    pub competitor_reach: Option<CompetitorReach>,
    /// Vertices of the working copy kept as the surface of revolution.
    pub kept_vertex_count: usize,
    /// The details, for `--json` and the archaeologist's record.
    pub report: OrientReport,
    /// What the sense cues read, for [`Orientation::rejudge_sense`] (automatic
    /// orientations).
    pub sense_inputs: Option<std::sync::Arc<SenseInputs>>,
}

/// Serialisable details of an orientation.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct OrientReport {
    /// "automatic" or "three points".
    pub method: String,
    /// Vertices of the input.
    pub input_vertex_count: usize,
    /// Vertices of the working copy.
    pub working_vertex_count: usize,
    /// Vertices kept by the opposite-normal test (or by the distance rule, for a manual axis).
    pub kept_vertex_count: usize,
    /// Whether the opposite-normal test ran, and why not if it did not.
    pub opposite_filter: String,
    /// Wall thickness seen by the opposite-normal test, millimetres.
    pub wall_thickness_mm: Option<f64>,
    /// Robust scale of the normal-line-to-axis residuals, millimetres.
    pub residual_scale_mm: f64,
    /// By how much the normals typically miss the axis, seen from it, degrees (see
    /// [`verdict::axis_residual_angle_deg`]).
    pub residual_angle_deg: f64,
    /// Median distance of the kept points to the axis, millimetres.
    pub median_radius_mm: f64,
    /// Share of the points' weight on the surface of revolution about the search's axis.
    pub inlier_fraction: f64,
    /// Second eigenvalue of the normals' scatter over the first (0 for a flat piece).
    pub normal_spread: f64,
    /// `λ1/λ2` of the line complex (near 1 for a near-spherical piece).
    pub concurrency_ratio: f64,
    /// Angle to the best competing axis, degrees, and the t statistic by which the best
    /// fits the piece better, block by block (see [`landscape::separation`]).
    pub competitor: Option<(f64, f64)>,
    /// The whole-sphere search's robust score of the axis (0 for a perfect surface of
    /// revolution, 0.9 when no point is on one).
    #[serde(default)]
    pub search_cost: f64,
    /// The least relative rise of that score when the axis moves 10 mm across itself (see
    /// [`landscape::position_hold`]): near 0 where the piece does not fix the position.
    #[serde(default)]
    pub position_hold: f64,
    /// The cue that set the sense base to rim, or why none could.
    pub direction_cue: String,
    /// Confidence in the sense base to rim, 0 to 1 (see [`direction::DirectionEvidence`]).
    pub direction_strength: f64,
    /// The figures of each sense cue.
    pub sense_cues: direction::SenseCues,
    /// Radius of the picked circle (manual), millimetres.
    pub circle_radius_mm: Option<f64>,
    /// Wall-clock milliseconds per step.
    pub timings_ms: Vec<(String, f64)>,
}

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
    let all_lines = NormalLines::from_mesh(&working)?;
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

/// The farthest of the competing axes the fragment does not rule out (the best fits
/// better by less than the verdict's t), as an angle and as the paper's mean point
/// distance between the lines. The bootstrap and the valley's width measure the spread
/// about the best valley; where another valley fits the piece about as well, the axis
/// may lie there, and a 95% interval that stops short of it claims what the piece does
/// not show.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CompetitorReach {
    /// The largest angle between an unresolved competitor's line and the axis, degrees.
    pub angle_deg: f64,
    /// The largest mean point distance between an unresolved competitor's line and the
    /// axis's, up and down aside, millimetres.
    pub distance_mm: f64,
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

/// What the sense cues read, kept with an automatic orientation so that the sense can be
/// judged again under the refined axis: the cues read the ends, floor and slope of the
/// profile, which a pre-orientation a few degrees off blurs.
#[derive(Debug)]
pub struct SenseInputs {
    samples: Option<revolution_search::RevolutionSamples>,
    all_samples: Option<revolution_search::RevolutionSamples>,
    lines: NormalLines,
    all_points: Vec<Point>,
    loss_scale_mm: f64,
    min_confidence: f64,
}

impl SenseInputs {
    /// Which lines lie on the surface of revolution about `axis`.
    fn on_surface(&self, axis: &Axis) -> Vec<bool> {
        on_surface_of(self.samples.as_ref(), self.lines.len(), axis, self.loss_scale_mm)
    }

    /// The line of `axis` pointed from base to rim as the cues say, and the cues.
    pub fn judge(&self, axis: &Axis) -> (Axis, direction::DirectionEvidence) {
        let finished = self.all_samples.as_ref().map(|_| on_surface_of(self.all_samples.as_ref(), self.all_points.len(), axis, self.loss_scale_mm));
        let evidence = direction::direction_evidence_finished(&self.lines, &self.on_surface(axis), &self.all_points, finished.as_deref(), axis);
        let oriented = if evidence.score < 0.0 { axis.flipped() } else { *axis };
        (oriented, evidence)
    }

    /// [`Verdict::Oriented`] when the cues are confident, [`Verdict::SenseUncertain`]
    /// otherwise.
    pub fn verdict(&self, evidence: &direction::DirectionEvidence) -> Verdict {
        if evidence.score.abs() >= self.min_confidence {
            Verdict::Oriented
        } else {
            Verdict::SenseUncertain {
                reason: format!(
                    "the axis line is found but not which way is up (base to rim): {} (confidence {:.2} < {:.2})",
                    evidence.cue,
                    evidence.score.abs(),
                    self.min_confidence
                ),
            }
        }
    }
}

/// Which of the `count` points of `samples` (all of their lines) lie on the surface of
/// revolution about `axis`: all of them when there are no samples.
fn on_surface_of(samples: Option<&revolution_search::RevolutionSamples>, count: usize, axis: &Axis, loss_scale_mm: f64) -> Vec<bool> {
    match samples {
        Some(all) => revolution_search::point_losses(all, axis, loss_scale_mm).iter().map(|l| *l < ON_SURFACE_LOSS).collect(),
        None => vec![true; count],
    }
}

/// Writes the cues into the report.
fn record_sense(report: &mut OrientReport, evidence: &direction::DirectionEvidence) {
    report.direction_cue = evidence.cue.clone();
    report.direction_strength = evidence.score.abs();
    report.sense_cues = evidence.cues.clone();
}

impl Orientation {
    /// The sense judged again under `axis` (a refinement of this orientation's axis line):
    /// `axis` pointed from base to rim as the cues read it there, with the verdict and the
    /// report updated. An orientation that declined, or a manual one, keeps its verdict and
    /// only points `axis` like its own.
    pub fn rejudge_sense(&mut self, axis: &Axis) -> Axis {
        let Some(inputs) = self.sense_inputs.clone().filter(|_| self.verdict.has_axis_line()) else {
            return if axis.direction.dot(&self.axis.direction) < 0.0 { axis.flipped() } else { *axis };
        };
        let (oriented, evidence) = inputs.judge(axis);
        self.verdict = inputs.verdict(&evidence);
        record_sense(&mut self.report, &evidence);
        self.axis = if oriented.direction.dot(&self.axis.direction) < 0.0 { self.axis.flipped() } else { self.axis };
        oriented
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
/// Robust loss under which a point counts as on the surface of revolution for the sense
/// cues (a residual of about a loss scale).
const ON_SURFACE_LOSS: f64 = 0.5;

/// Options in their bounds and a valid, non-empty mesh whose vertices are not all in one plane.
fn check_orientable(mesh: &Mesh, options: &OrientOptions) -> Result<()> {
    check_options(options)?;
    mesh.validate()?;
    if mesh.positions.is_empty() {
        return Err(Error::DegenerateGeometry("the mesh is empty: no vertex to orient".into()));
    }
    reject_coplanar(mesh)
}

/// Option values that would make orientation run for ever or decimate to nothing.
fn check_options(options: &OrientOptions) -> Result<()> {
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
    let all_lines = NormalLines::from_mesh(working)?;
    Ok(select_surface_of_revolution(working, &all_lines, options, &mut OrientReport::default()))
}

/// The lines on the surface of revolution: the opposite-normal test on meshes, all lines
/// of point clouds (they carry no faces to cast rays at).
fn select_surface_of_revolution(
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
