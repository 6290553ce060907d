//! The evaluation harnesses shared by the accuracy examples, the refinement's tests and
//! its benches (each includes this file as a module): the simulated pre-orientation errors
//! and the refinement corpus, the orientation's figures against synthetic ground truth,
//! and the reader of the SfS++ pot C dataset. They measure the library and are not part
//! of it.
#![allow(dead_code)] // each includer uses part of it

use serde::Serialize;

use sherd::orient::{mean_point_distance_mm, orient_automatic, Axis, OrientOptions, Orientation};
use sherd::statistics::nearest_rank_quantile;
use sherd::synth::{SherdPart, SynthSherd};

// ----------------------------------------------------------------------------- fragments on disk

/// The fragments of `folder` that carry their truth: each `NAME.ply` with a
/// `NAME.truth.json` beside it (`sherd synth`'s or the report corpus's), sorted by name.
pub fn fragments_with_truth(folder: &std::path::Path) -> std::io::Result<Vec<std::path::PathBuf>> {
    let mut plys: Vec<std::path::PathBuf> = std::fs::read_dir(folder)?
        .filter_map(|entry| entry.ok().map(|entry| entry.path()))
        .filter(|path| path.extension().is_some_and(|extension| extension == "ply") && path.with_extension("truth.json").exists())
        .collect();
    plys.sort();
    Ok(plys)
}

/// The fields of a truth file the examples read.
#[derive(serde::Deserialize)]
struct TruthRecord {
    axis: sherd::orient::AxisRecord,
    part: String,
}

/// The true axis and the part (`rim`, `base`...) of the fragment `ply`, from its
/// `NAME.truth.json`; `None` where that cannot be read.
pub fn truth_of(ply: &std::path::Path) -> Option<(Axis, String)> {
    let truth: TruthRecord = serde_json::from_str(&std::fs::read_to_string(ply.with_extension("truth.json")).ok()?).ok()?;
    Some((Axis::from_record(&truth.axis)?, truth.part))
}

// ----------------------------------------------------------------------------- refinement corpus

/// A simulated pre-orientation error: `truth` turned by `tilt_deg` about the horizontal
/// direction at `tilt_azimuth_rad` and its point moved by `shift_mm` along the horizontal
/// direction at `shift_azimuth_rad`, both azimuths in the axis's own frame
/// ([`Axis::rotation_from_z`]). The refinement's accuracy example, tests and benches start
/// from it.
pub fn perturbed_axis(truth: &Axis, tilt_azimuth_rad: f64, tilt_deg: f64, shift_azimuth_rad: f64, shift_mm: f64) -> Axis {
    let frame = truth.rotation_from_z();
    let horizontal = |azimuth: f64| frame * sherd::mesh::Vector::new(azimuth.cos(), azimuth.sin(), 0.0);
    let turn = nalgebra::UnitQuaternion::from_axis_angle(&nalgebra::Unit::new_normalize(horizontal(tilt_azimuth_rad)), tilt_deg.to_radians());
    Axis::new(truth.point + horizontal(shift_azimuth_rad) * shift_mm, turn * truth.direction.into_inner())
}

/// Fragments per vessel of the refinement corpus (the paper's synthetic vessel broke into 34).
pub const REFINEMENT_CORPUS_FRAGMENTS_PER_VESSEL: usize = 34;

/// Mesh cells of the refinement corpus, mm: the orientation issue's corpus
/// (`examples/orient_accuracy.rs`, `tests/orient.rs`), fragments of a few thousand
/// vertices, as a decimated scan. `REFINE_ACCURACY_CELL_MM=2` gives the synthetic
/// generator's default 2 mm cells instead (a body fragment about 1000 vertices).
pub const REFINEMENT_CORPUS_CELL_MM: f64 = 0.8;

/// The refinement corpus of `examples/refine_accuracy.rs` and `examples/deformation_floor.rs`:
/// vessels `0..vessels`, each broken into 34 fragments moved by random rigid motions, with
/// the deformation scaled by `deformation_scale` (1: the default vessels), scan noise
/// `noise_mm` and mesh cells of `cell_size_mm` ([`REFINEMENT_CORPUS_CELL_MM`] in
/// `refine_accuracy`), the hard cases left out; each fragment with its id
/// `vessel * 1000 + index`.
pub fn refinement_corpus(vessels: u64, deformation_scale: f64, noise_mm: f64, cell_size_mm: f64) -> Vec<(u64, SynthSherd)> {
    let options = sherd::synth::VesselOptions {
        fragment_count: REFINEMENT_CORPUS_FRAGMENTS_PER_VESSEL,
        random_motion: true,
        deformation_scale,
        noise_mm,
        cell_size_mm,
        ..Default::default()
    };
    (0..vessels)
        .flat_map(|seed| {
            let vessel = sherd::synth::generate_vessel(seed, &options);
            vessel.fragments.into_iter().enumerate().map(move |(i, f)| (seed * 1000 + i as u64, f))
        })
        .filter(|(_, s)| s.truth.hard_case.is_none())
        .collect()
}

// ----------------------------------------------------------------------------- orientation figures

/// A fragment counts as wrong above this mean point distance (the paper's 4 mm).
pub const WRONG_DISTANCE_MM: f64 = 4.0;
/// ... or above this angle between the estimated and the true axis lines.
pub const WRONG_ANGLE_DEG: f64 = 5.0;

/// The outcome of orienting one synthetic sherd.
#[derive(Clone, Debug, Serialize)]
pub struct FragmentOutcome {
    /// Seed or index of the fragment.
    pub id: String,
    /// The true part.
    pub part: SherdPart,
    /// The true sector angle, degrees.
    pub sector_angle_deg: f64,
    /// Angle between the estimated and true axis lines, degrees.
    pub line_angle_error_deg: f64,
    /// True when the estimated direction points from base to rim like the truth's.
    pub sense_correct: bool,
    /// The paper's mean point distance with the estimated axis as given (sense included), mm.
    pub mean_point_distance_mm: f64,
    /// The same with the sense taken from the truth: the error of the line alone, mm.
    pub line_point_distance_mm: f64,
    /// Flagged: NEEDS_MANUAL_ORIENTATION or SENSE_UNCERTAIN.
    pub flagged: bool,
    /// Flagged SENSE_UNCERTAIN (the axis line accepted, its sense not).
    pub sense_uncertain: bool,
    /// The flag's reason, or the error message.
    pub reason: String,
    /// The report's figures used by the verdict.
    pub normal_spread: f64,
    /// λ1/λ2 of the line complex.
    pub concurrency_ratio: f64,
    /// Typical angle by which the normals miss the axis, degrees.
    pub residual_angle_deg: f64,
    /// Position uncertainty (calibrated), mm.
    pub position_uncertainty_mm: f64,
    /// Competitor (angle, cost ratio).
    pub competitor: Option<(f64, f64)>,
    /// Fraction of inliers.
    pub inlier_fraction: f64,
    /// Strength of the sense cue.
    pub direction_strength: f64,
    /// Which cue set the sense.
    pub direction_cue: String,
    /// The figures of each sense cue.
    pub sense_cues: sherd::orient::direction::SenseCues,
    /// The vessel family the fragment came from.
    pub shape: sherd::synth::VesselShape,
    /// Milliseconds the orientation took.
    pub elapsed_ms: f64,
}

impl FragmentOutcome {
    /// Wrong by the line angle and not flagged.
    pub fn wrong_angle_unflagged(&self) -> bool {
        !self.flagged && self.line_angle_error_deg > WRONG_ANGLE_DEG
    }

    /// Wrong by the paper's distance (sense included) and not flagged.
    pub fn wrong_distance_unflagged(&self) -> bool {
        !self.flagged && self.mean_point_distance_mm > WRONG_DISTANCE_MM
    }
}

/// Orients `sherd` and compares with its truth.
pub fn evaluate(id: String, sherd: &SynthSherd, options: &OrientOptions) -> FragmentOutcome {
    let truth = &sherd.truth;
    let started = std::time::Instant::now();
    let result = orient_automatic(&sherd.mesh, options);
    let elapsed_ms = started.elapsed().as_secs_f64() * 1e3;
    let mut outcome = FragmentOutcome {
        id,
        part: truth.part,
        sector_angle_deg: truth.sector_angle_deg,
        line_angle_error_deg: 90.0,
        sense_correct: false,
        mean_point_distance_mm: f64::INFINITY,
        line_point_distance_mm: f64::INFINITY,
        flagged: true,
        sense_uncertain: false,
        reason: String::new(),
        normal_spread: 0.0,
        concurrency_ratio: 1.0,
        residual_angle_deg: f64::INFINITY,
        position_uncertainty_mm: f64::INFINITY,
        competitor: None,
        inlier_fraction: 0.0,
        direction_strength: 0.0,
        direction_cue: String::new(),
        sense_cues: Default::default(),
        shape: sherd.truth.vessel.shape,
        elapsed_ms,
    };
    match result {
        Ok(orientation) => fill(&mut outcome, sherd, &orientation),
        Err(error) => outcome.reason = format!("error: {error}"),
    }
    outcome
}

fn fill(outcome: &mut FragmentOutcome, sherd: &SynthSherd, orientation: &Orientation) {
    let truth = &sherd.truth.axis;
    let axis = &orientation.axis;
    outcome.line_angle_error_deg = axis.line_angle_to_deg(truth);
    outcome.sense_correct = axis.angle_to_deg(truth) < 90.0;
    let points = &sherd.mesh.positions;
    outcome.mean_point_distance_mm = mean_point_distance_mm(points, axis, truth);
    let same_sense = if outcome.sense_correct { *axis } else { axis.flipped() };
    outcome.line_point_distance_mm = mean_point_distance_mm(points, &same_sense, truth);
    outcome.flagged = !orientation.verdict.is_oriented();
    outcome.sense_uncertain = matches!(orientation.verdict, sherd::orient::Verdict::SenseUncertain { .. });
    if let Some(reason) = orientation.verdict.reason() {
        outcome.reason = reason.to_owned();
    }
    let report = &orientation.report;
    outcome.normal_spread = report.normal_spread;
    outcome.concurrency_ratio = report.concurrency_ratio;
    outcome.residual_angle_deg = report.residual_angle_deg;
    outcome.position_uncertainty_mm = orientation.position_uncertainty_mm;
    outcome.competitor = report.competitor;
    outcome.inlier_fraction = report.inlier_fraction;
    outcome.direction_strength = report.direction_strength;
    outcome.direction_cue = report.direction_cue.clone();
    outcome.sense_cues = report.sense_cues.clone();
}

/// The summary figures of a set of outcomes.
#[derive(Clone, Debug, Serialize)]
pub struct Summary {
    /// Number of fragments.
    pub count: usize,
    /// Median line angle error over all fragments, degrees.
    pub median_angle_deg: f64,
    /// 95th percentile of the line angle error over all fragments, degrees.
    pub p95_angle_deg: f64,
    /// Median line angle error over the unflagged fragments, degrees.
    pub median_angle_unflagged_deg: f64,
    /// 95th percentile over the unflagged fragments, degrees.
    pub p95_angle_unflagged_deg: f64,
    /// Mean of the paper's mean point distance over the unflagged fragments, mm.
    pub mean_point_distance_unflagged_mm: f64,
    /// Median of the paper's distance over all fragments, mm.
    pub median_point_distance_mm: f64,
    /// Fraction flagged (NEEDS_MANUAL_ORIENTATION or SENSE_UNCERTAIN).
    pub flagged_fraction: f64,
    /// Fraction flagged SENSE_UNCERTAIN (the rest of the flagged have their line refused).
    pub sense_uncertain_fraction: f64,
    /// Fraction wrong by angle (over 5 deg) and not flagged.
    pub wrong_angle_unflagged_fraction: f64,
    /// Fraction wrong by distance (over 4 mm, sense included) and not flagged.
    pub wrong_distance_unflagged_fraction: f64,
    /// Fraction of unflagged fragments whose sense (base to rim) is right.
    pub sense_correct_fraction: f64,
}

impl Summary {
    /// Summarises `outcomes`.
    pub fn of(outcomes: &[FragmentOutcome]) -> Summary {
        let n = outcomes.len().max(1) as f64;
        let mut all: Vec<f64> = outcomes.iter().map(|o| o.line_angle_error_deg).collect();
        let unflagged: Vec<&FragmentOutcome> = outcomes.iter().filter(|o| !o.flagged).collect();
        let mut kept: Vec<f64> = unflagged.iter().map(|o| o.line_angle_error_deg).collect();
        let mut distances: Vec<f64> = outcomes.iter().map(|o| o.mean_point_distance_mm).collect();
        let kept_count = unflagged.len().max(1) as f64;
        Summary {
            count: outcomes.len(),
            median_angle_deg: nearest_rank_quantile(&mut all, 0.5),
            p95_angle_deg: nearest_rank_quantile(&mut all, 0.95),
            median_angle_unflagged_deg: nearest_rank_quantile(&mut kept, 0.5),
            p95_angle_unflagged_deg: nearest_rank_quantile(&mut kept, 0.95),
            mean_point_distance_unflagged_mm: unflagged.iter().map(|o| o.mean_point_distance_mm).sum::<f64>() / kept_count,
            median_point_distance_mm: nearest_rank_quantile(&mut distances, 0.5),
            flagged_fraction: outcomes.iter().filter(|o| o.flagged).count() as f64 / n,
            sense_uncertain_fraction: outcomes.iter().filter(|o| o.sense_uncertain).count() as f64 / n,
            wrong_angle_unflagged_fraction: outcomes.iter().filter(|o| o.wrong_angle_unflagged()).count() as f64 / n,
            wrong_distance_unflagged_fraction: outcomes.iter().filter(|o| o.wrong_distance_unflagged()).count() as f64 / n,
            sense_correct_fraction: unflagged.iter().filter(|o| o.sense_correct).count() as f64 / kept_count,
        }
    }

    /// One Markdown table row: `| label | n | ... |`.
    pub fn table_row(&self, label: &str) -> String {
        format!(
            "| {label} | {} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.1}% | {:.1}% | {:.1}% | {:.1}% | {:.1}% | {:.1}% |",
            self.count,
            self.median_angle_deg,
            self.p95_angle_deg,
            self.median_angle_unflagged_deg,
            self.p95_angle_unflagged_deg,
            self.mean_point_distance_unflagged_mm,
            100.0 * self.flagged_fraction,
            100.0 * (self.flagged_fraction - self.sense_uncertain_fraction),
            100.0 * self.sense_uncertain_fraction,
            100.0 * self.wrong_angle_unflagged_fraction,
            100.0 * self.wrong_distance_unflagged_fraction,
            100.0 * self.sense_correct_fraction
        )
    }

    /// The header matching [`Summary::table_row`].
    pub fn table_header() -> String {
        "| set | n | median deg | p95 deg | median deg (unflagged) | p95 deg (unflagged) | mean point dist mm (unflagged) | flagged | line refused | sense uncertain | wrong >5deg unflagged | wrong >4mm unflagged | sense right (unflagged) |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|".into()
    }
}

/// One sherd of the SfS++ pot C dataset: both skins' subsampled points with their normals
/// as one point cloud, and its reference axis.
#[derive(Clone, Debug)]
pub struct SfsppPiece {
    /// `Pot_C_Piece_01`..`Pot_C_Piece_04`.
    pub name: String,
    /// Both skins' points with normals, in the piece's own scan frame.
    pub cloud: sherd::mesh::Mesh,
    /// Reference A of `ground_truth/reference_axis_derived.txt`, in the same frame
    /// (derived from the assembled pot, known to about 3 degrees and 2 mm).
    pub reference: sherd::orient::Axis,
}

/// The four sherds of `folder` (the dataset's `sfspp_pot_C`: `ground_truth/` and
/// `surfaces_subsample/`), the examples' and tests' one reader of it. An error names the
/// file or line that is missing or malformed.
pub fn read_sfspp_pot_c(folder: &std::path::Path) -> sherd::Result<Vec<SfsppPiece>> {
    use sherd::mesh::{Point, Vector};
    let reference_path = folder.join("ground_truth/reference_axis_derived.txt");
    let references = std::fs::read_to_string(&reference_path).map_err(|e| sherd::Error::io(&reference_path, e))?;
    let surfaces = folder.join("surfaces_subsample");
    let mut surface_files: Vec<std::path::PathBuf> = std::fs::read_dir(&surfaces)
        .map_err(|e| sherd::Error::io(&surfaces, e))?
        .flatten()
        .map(|entry| entry.path())
        .collect();
    surface_files.sort();
    (1..=4)
        .map(|piece| {
            let name = format!("Pot_C_Piece_0{piece}");
            // The file lists reference A first, then other derivations: the first line
            // naming the piece is reference A, in the piece's own frame.
            let (number, line) = references
                .lines()
                .enumerate()
                .find(|(_, line)| line.starts_with(&format!("{name} ")))
                .ok_or_else(|| sherd::Error::parse(reference_path.display().to_string(), "file", format!("no line for {name}")))?;
            let values: Vec<f64> = line.split_whitespace().skip(1).filter_map(|value| value.parse().ok()).collect();
            if values.len() != 6 {
                return Err(sherd::Error::parse(
                    reference_path.display().to_string(),
                    format!("line {}", number + 1),
                    format!("{name}: expected a point and a direction (6 numbers), found {} numbers", values.len()),
                ));
            }
            let reference = sherd::orient::Axis::new(Point::new(values[0], values[1], values[2]), Vector::new(values[3], values[4], values[5]));
            let (mut positions, mut normals) = (Vec::new(), Vec::new());
            for path in surface_files.iter().filter(|p| p.file_name().is_some_and(|f| f.to_string_lossy().starts_with(&format!("{name}_Surface_")))) {
                let skin = sherd::mesh::io::read_mesh(path)?;
                let skin_normals = skin.normals.ok_or_else(|| sherd::Error::parse(path.display().to_string(), "header", "the surface carries no normals"))?;
                positions.extend(skin.positions);
                normals.extend(skin_normals);
            }
            if positions.is_empty() {
                return Err(sherd::Error::io(surfaces.join(format!("{name}_Surface_*")), std::io::ErrorKind::NotFound.into()));
            }
            Ok(SfsppPiece { name, cloud: sherd::mesh::Mesh::from_points_and_normals(positions, normals), reference })
        })
        .collect()
}
