//! The whole pipeline in one call, as the command-line tool, the C ABI and batch runs use
//! it: read, repair, orient (automatic or three points), refine, measure, and optionally
//! draw. Data flows one way, each layer handing its result to the next; this module only
//! chains the layers and records what each did, it holds no algorithm.

use std::path::Path;
use std::time::Instant;

use serde::{Deserialize, Serialize};

use crate::draw::{DrawOptions, Drawing};
use crate::mesh::fingerprint::ScanFingerprint;
use crate::mesh::io::read_mesh_with_report;
use crate::mesh::repair::{repair, RepairOptions, RepairReport};
use crate::mesh::{Mesh, Point};
use crate::orient::{decimated_copy, orient_automatic_with_decimated, orient_from_three_points, Axis, AxisRecord, ManualOptions, OrientOptions, Orientation, Verdict};
use crate::profile::measure::{measure_with_bootstrap_mesh, MeasureOptions, Measurements, AXIS_DOUBT_NOTE};
use crate::profile::rills::{rill_check, three_points_on, trace_rills_under, Rill, RillCheck, RillOptions};
use crate::refine::{chosen_criterion, refine, refine_placing_on, Criterion, RefineOptions, Refinement};
use crate::vocabulary::Vocabulary;
use crate::{Error, Result};

/// What to do with a scan.
#[derive(Clone, Debug, Default)]
pub struct PipelineOptions {
    /// Millimetres per scan unit (1 for mm, 10 for cm, 1000 for m); 0 (the default)
    /// means: the unit the file declares ([`crate::mesh::io::unit_declared_in`]), else mm.
    pub millimetres_per_unit: f64,
    /// Repair before processing.
    pub repair: RepairOptions,
    /// Automatic pre-orientation.
    pub orient: OrientOptions,
    /// Three points on one horizontal feature: manual pre-orientation instead of automatic.
    pub manual_points: Option<[Point; 3]>,
    /// Options of the manual pre-orientation.
    pub manual: ManualOptions,
    /// Refinement after pre-orientation (also of an axis whose sense is uncertain);
    /// `None` keeps the pre-orientation.
    pub refine: Option<RefineOptions>,
    /// Measurements. Where the pipeline refines the axis, its intervals refine their
    /// resampled axes with the same options ([`PipelineOptions::refine`]), whatever
    /// `measure.refine` holds: an interval is about the axis the pipeline gives.
    pub measure: MeasureOptions,
    /// Refine on the full-resolution mesh instead of the pre-orientation's decimated copy
    /// (a scan larger than the working size). Off by default: on 48 synthetic sherds of
    /// 200k faces the axes the circles criterion refined on the 20k-face copy were as
    /// close to the truth as on the full mesh (`examples/pipeline_accuracy.rs`: the
    /// vessel's deformation and the noise limit the axis, not the sections' density) at
    /// a fifth of the time. The tangent plane to a rim or base always levels the axis on
    /// the full mesh (it rests on a few extreme points) and places it by circles on the
    /// copy ([`crate::refine::refine_placing_on`]); the measurements always run on the
    /// full mesh.
    pub refine_on_full_resolution: bool,
    /// Bootstrap the intervals on the full-resolution mesh instead of the
    /// pre-orientation's decimated copy. Off by default: the bootstrap refines the axis
    /// 24 times and was two thirds of the pipeline's time on large scans; the
    /// measurements themselves always use the full-resolution mesh.
    pub bootstrap_on_full_resolution: bool,
}

/// Everything the pipeline found for one scan.
#[derive(Clone, Debug)]
pub struct Analysis {
    /// The repaired mesh, in millimetres, in the scan's frame.
    pub mesh: Mesh,
    /// The scan as given, before repair and unit conversion: the record carries it so
    /// that its axis is not used on another scan.
    pub scan: ScanFingerprint,
    /// What repair changed.
    pub repair: RepairReport,
    /// The pre-orientation and its verdict.
    pub orientation: Orientation,
    /// The refinement, when asked for and the pre-orientation succeeded.
    pub refinement: Option<Refinement>,
    /// Measurements along the final axis, when the axis line is found (sense certain or not).
    pub measurements: Option<Measurements>,
    /// For a sherd without measurements (it needs manual orientation): the wheel rills
    /// traced under the declined axis, longest first, where to pick three points. An
    /// oriented sherd's are in its measurements; [`Analysis::rills`] gives either.
    pub declined_axis_rills: Vec<Rill>,
    /// Seconds spent in each step.
    pub timings: Timings,
    /// Millimetres per unit of the scan's file (given, or declared by the file).
    pub millimetres_per_unit: f64,
    /// The confidence in the sense (base to rim) the orientation's thresholds ask for
    /// ([`crate::orient::VerdictThresholds::min_sense_confidence`]): the record's best
    /// guess of a declined sherd calls its sense known from it.
    pub min_sense_confidence: f64,
}

/// Seconds spent in each step of the pipeline.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize)]
pub struct Timings {
    pub read_s: f64,
    pub repair_s: f64,
    pub orient_s: f64,
    pub refine_s: f64,
    pub measure_s: f64,
    pub draw_s: f64,
}

impl Analysis {
    /// The final axis: refined if refinement ran, else the pre-orientation's.
    pub fn axis(&self) -> &Axis {
        self.refinement.as_ref().map_or(&self.orientation.axis, |r| &r.axis)
    }

    /// The wheel rills traced under the final axis (the measurements'), or under the
    /// declined axis of a sherd that needs manual orientation; longest first.
    pub fn rills(&self) -> &[Rill] {
        self.measurements.as_ref().map_or(&self.declined_axis_rills, |m| &m.rills)
    }

    /// True when the sherd got an axis the pipeline stands behind, sense included.
    pub fn is_oriented(&self) -> bool {
        self.orientation.verdict.is_oriented()
    }

    /// True when the orientation found an axis, trusted or not; false when it found none
    /// at all (too few points on the surface of revolution: it then stands in with an
    /// arbitrary vertical axis through the centroid, marked by an infinite angle
    /// uncertainty).
    pub fn found_an_axis(&self) -> bool {
        self.orientation.angle_uncertainty_deg != f64::INFINITY
    }

    /// Why the final axis wants a look before its figures are used, although the
    /// orientation found it: the orientation's own doubts (another axis fits the piece
    /// about as well, [`Orientation::doubts`]) and the measurements' (the bootstrap's 95%
    /// intervals of its direction or position reach what makes an axis wrong, or it moves
    /// when a quarter of the arc is left out; see [`Measurements::axis_doubts`]). Empty
    /// when there are none.
    pub fn axis_doubts(&self) -> Vec<String> {
        let measured = self.measurements.as_ref().map_or(&[][..], |m| &m.axis_doubts[..]);
        self.orientation.doubts.iter().chain(measured).cloned().collect()
    }
}

/// Runs repair, orientation, refinement and measurement on `mesh` (in scan units).
pub fn analyse(mut mesh: Mesh, options: &PipelineOptions) -> Result<Analysis> {
    let scale = options.scale();
    mesh.validate()?;
    let scan = ScanFingerprint::of(&mesh);
    if scale != 1.0 {
        for p in &mut mesh.positions {
            p.coords *= scale;
        }
    }
    let mut timings = Timings::default();
    let clock = Instant::now();
    let repair_report = repair(&mut mesh, &options.repair);
    timings.repair_s = clock.elapsed().as_secs_f64();

    let clock = Instant::now();
    // One decimated copy of a large scan serves the automatic pre-orientation, the
    // refinement and the bootstrap of the intervals; the measurements themselves (radii,
    // sector, profile) are taken on the full-resolution mesh.
    let wants_copy = options.manual_points.is_none()
        || (options.refine.is_some() && !options.refine_on_full_resolution)
        || (!options.bootstrap_on_full_resolution && options.measure.bootstrap.samples > 0);
    let decimated = if wants_copy { decimated_copy(&mesh, &options.orient)? } else { None };
    let mut orientation = match options.manual_points {
        Some(points) => {
            let points = points.map(|p| Point::from(p.coords * scale));
            orient_from_three_points(&mesh, points, &options.manual)?
        }
        None => orient_automatic_with_decimated(&mesh, decimated.as_ref(), &options.orient)?,
    };
    timings.orient_s = clock.elapsed().as_secs_f64();
    let refine_mesh = match (&decimated, options.refine_on_full_resolution) {
        (Some(decimated), false) => decimated,
        _ => &mesh,
    };
    let bootstrap_mesh = match (&decimated, options.bootstrap_on_full_resolution) {
        (Some(decimated), false) => decimated,
        _ => &mesh,
    };

    // The line is refined and measured when only its sense is uncertain: radii, sector and
    // thickness do not depend on which way is up.
    let has_line = orientation.verdict.has_axis_line();
    let clock = Instant::now();
    let refinement = match (&options.refine, has_line) {
        (Some(refine_options), true) => {
            // The tangent plane rests on the few highest (lowest) points of the rim (base),
            // which decimation moves: on 13 rim sherds its axis came out 0.05-0.5 degrees
            // further from the truth on the copy. The circles criterion averages thousands
            // of section points and is as good on the copy, where it costs a fifth: so a
            // rim is levelled on the full mesh and placed by circles on the copy.
            let on_copy = !std::ptr::eq(refine_mesh, &mesh);
            if on_copy && chosen_criterion(refine_mesh, &orientation.axis, refine_options)? == Criterion::Tangent {
                Some(refine_placing_on(&mesh, refine_mesh, &orientation.axis, refine_options)?)
            } else {
                Some(refine(refine_mesh, &orientation.axis, refine_options)?)
            }
        }
        _ => None,
    };
    // The sense cues read the ends, floor and slope of the profile, which the refined
    // axis shows more sharply than the pre-orientation's.
    let refinement = refinement.map(|mut refinement| {
        refinement.axis = orientation.rejudge_sense(&refinement.axis);
        refinement
    });
    timings.refine_s = clock.elapsed().as_secs_f64();

    let mut measurements = None;
    if has_line {
        let clock = Instant::now();
        let axis = refinement.as_ref().map_or(&orientation.axis, |r| &r.axis);
        let valley = (orientation.angle_uncertainty_deg, orientation.position_uncertainty_mm);
        // A rim or base levelled by its tangent plane has its turn from evidence the
        // landscape does not weigh (a level edge), but its position from the same skins
        // as any other axis: the valley's move widens its position interval alone. A
        // manual axis (NaN) has no landscape.
        let levelled = refinement.as_ref().is_some_and(|r| r.report.method == Criterion::Tangent);
        let valley = if levelled { (f64::NAN, valley.1) } else { valley };
        let measure_options = MeasureOptions {
            axis_valley_width: valley.1.is_finite().then_some(valley),
            axis_competitor_reach: orientation.competitor_reach,
            refine: options.refine.clone().unwrap_or_else(|| options.measure.refine.clone()),
            ..options.measure.clone()
        };
        measurements = Some(measure_with_bootstrap_mesh(&mesh, bootstrap_mesh, axis, &measure_options));
        timings.measure_s = clock.elapsed().as_secs_f64();
    }
    let mut analysis = Analysis {
        mesh,
        scan,
        repair: repair_report,
        orientation,
        refinement,
        measurements,
        declined_axis_rills: Vec::new(),
        timings,
        millimetres_per_unit: scale,
        min_sense_confidence: options.orient.thresholds.min_sense_confidence,
    };
    // Without measurements (a sherd that needs manual orientation) the rills are traced
    // under the declined axis: where to pick three points. An orientation that found no
    // axis at all (too few points) stands in with an arbitrary one, under which level
    // bumps are no rills.
    if analysis.measurements.is_none() && analysis.found_an_axis() {
        let clock = Instant::now();
        analysis.declined_axis_rills = trace_rills_under(&analysis.mesh, &analysis.orientation.axis, &RillOptions::default());
        analysis.timings.measure_s += clock.elapsed().as_secs_f64();
    }
    Ok(analysis)
}

impl PipelineOptions {
    /// Millimetres per scan unit, 1 when unset.
    pub fn scale(&self) -> f64 {
        if self.millimetres_per_unit > 0.0 { self.millimetres_per_unit } else { 1.0 }
    }

    /// These options for a file that declares `declared` as its unit: an unset unit
    /// takes the file's; one given explicitly is kept.
    pub fn with_declared_unit(&self, declared: Option<crate::mesh::io::LengthUnit>) -> Self {
        let mut options = self.clone();
        if options.millimetres_per_unit <= 0.0
            && let Some(millimetres) = declared.and_then(|unit| unit.millimetres())
        {
            options.millimetres_per_unit = millimetres;
        }
        options
    }
}

/// Reads `path` and analyses it, in the unit the file declares when `options` give none;
/// the error says why it could not (the C ABI turns its kind into a status,
/// [`process_file`] into a record).
pub fn analyse_file(path: &Path, options: &PipelineOptions) -> Result<Analysis> {
    let clock = Instant::now();
    let (mesh, report) = read_mesh_with_report(path)?;
    let read_s = clock.elapsed().as_secs_f64();
    let mut analysis = analyse(mesh, &options.with_declared_unit(report.declared_unit))?;
    analysis.timings.read_s = read_s;
    Ok(analysis)
}

/// Reads `path`, analyses it and, when `drawing` is given and the sherd is oriented (its
/// sense certain: a drawing upside down would mislead), draws it to that file. Never fails: an unreadable or unorientable scan is a record whose
/// status says so, so that a batch goes on.
pub fn process_file(path: &Path, options: &PipelineOptions, drawing: Option<(&DrawOptions, &Path)>) -> SherdRecord {
    let file = path.display().to_string();
    let analysis = match analyse_file(path, options) {
        Ok(analysis) => analysis,
        Err(error) => return SherdRecord::failed(file, &error),
    };
    let mut record = SherdRecord::from_analysis(file, &analysis);
    if let (Some((draw_options, output)), true) = (drawing, analysis.is_oriented()) {
        let clock = Instant::now();
        // The measurements just made (with their intervals) label the drawing, rather
        // than being made again without intervals.
        let labelled;
        let draw_options = match (&draw_options.measurements, &analysis.measurements) {
            (None, Some(measurements)) => {
                labelled = DrawOptions { measurements: Some(measurements.clone()), ..draw_options.clone() };
                &labelled
            }
            _ => draw_options,
        };
        let written = Drawing::build(&analysis.mesh, analysis.axis(), draw_options).and_then(|d| d.write(output));
        record.timings.draw_s = clock.elapsed().as_secs_f64();
        match written {
            Ok(()) => record.drawing = Some(output.display().to_string()),
            Err(error) => {
                record.status = RecordStatus::Error;
                record.error = Some(format!("drawing: {error}"));
            }
        }
    }
    record
}

crate::vocabulary! {
    /// What became of one sherd: the `status` of its record (`sherd orient --json`, the
    /// batch reports), written by its name.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub enum RecordStatus: "record status", "record statuses" {
        /// Oriented and measured.
        #[default]
        Ok = "ok" => "Oriented and measured",
        /// Oriented, refined, measured (and drawn in a batch), but the axis is not pinned
        /// down: the bootstrap's intervals of its direction or position are wide
        /// ([`Analysis::axis_doubts`], in `reason`). A best guess to check before its
        /// figures are used.
        AxisUncertain = "axis_uncertain" => "Oriented and measured, but the axis is not pinned down: check it",
        /// The axis line is found, refined and measured, but not which way is up (base to
        /// rim): not drawn.
        SenseUncertain = "sense_uncertain" => "The axis line is found but not which way is up",
        /// The data do not determine an axis.
        NeedsManualOrientation = "needs_manual_orientation" => "The data do not determine an axis: give three points",
        /// The sherd could not be processed (the reason is in `error`).
        Error = "error" => "The scan could not be processed",
    }
}

/// Records write their status by name.
impl Serialize for RecordStatus {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> std::result::Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for RecordStatus {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> std::result::Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        name.parse().map_err(serde::de::Error::custom)
    }
}

/// The axis the automatic orientation found for a sherd it declined (the best of its
/// whole-sphere search), kept in the record of a `needs_manual_orientation` sherd: not an
/// answer, but where to start looking. Use it as it is (`sherd draw --axis` and `sherd
/// export --axis` take this object), flip it (negate `direction`) when the rim is at the
/// bottom, or orient the sherd properly from three points (`--manual`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BestGuess {
    /// The axis in the scan's own frame and units, pointed from base to rim as the sense
    /// cues read it under this axis.
    pub axis: AxisRecord,
    /// What speaks against it: why the orientation declined (the record's `reason`).
    pub against: String,
    /// True when the sense cues under this axis say which end is the rim as firmly as an
    /// oriented sherd's must; false when which way is up is a guess too.
    pub sense_known: bool,
}

/// One row of a batch report and the body of `sherd orient --json`.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct SherdRecord {
    /// The scan file.
    pub file: String,
    /// What became of the sherd.
    pub status: RecordStatus,
    /// Why the sherd needs manual orientation, why its sense is uncertain, or why its axis
    /// is (each doubt after a semicolon).
    pub reason: Option<String>,
    /// The error's message, when `status` is `error`.
    pub error: Option<String>,
    /// The axis in the scan's own frame and units, base to rim.
    pub axis: Option<AxisRecord>,
    /// Pre-orientation method and refinement criterion, e.g. "automatic + tangent".
    pub method: Option<String>,
    /// Residual of the final criterion (refinement) or of the normal lines (pre-orientation), mm.
    pub residual_mm: Option<f64>,
    /// 95% interval of the axis angle error `[0, upper]`, degrees.
    pub axis_angle_interval_deg: Option<[f64; 2]>,
    /// 95% interval of the paper's mean point distance between the true axis and this
    /// one `[0, upper]`, mm.
    pub axis_distance_interval_mm: Option<[f64; 2]>,
    /// Outer rim radius, mm; null when no level rim is preserved.
    pub rim_radius_mm: Option<f64>,
    /// Rim diameter, mm.
    pub rim_diameter_mm: Option<f64>,
    /// 95% interval of the rim diameter, mm.
    pub rim_diameter_interval_mm: Option<[f64; 2]>,
    /// Base diameter, mm.
    pub base_diameter_mm: Option<f64>,
    /// 95% interval of the base diameter, mm.
    pub base_diameter_interval_mm: Option<[f64; 2]>,
    /// Preserved arc, degrees.
    pub sector_angle_deg: Option<f64>,
    /// Preserved arc, percent of the circumference.
    pub sector_percent: Option<f64>,
    /// The arc of the rim itself, degrees (what a rim chart reads: the rim's own share of
    /// its circumference, often less than the sherd's); null without a rim.
    #[serde(default)]
    pub rim_sector_deg: Option<f64>,
    /// The arc of the base's edge itself, degrees; null without a base.
    #[serde(default)]
    pub base_sector_deg: Option<f64>,
    /// Preserved height, mm.
    pub height_mm: Option<f64>,
    /// Median wall thickness, mm.
    pub wall_thickness_mm: Option<f64>,
    /// Capacity of the whole vessel, litres, when the profile runs from base to rim.
    pub capacity_litres: Option<f64>,
    /// The wheel rills under the axis: how many were traced and how far from horizontal
    /// the axis puts them (null when none were traced).
    pub rills: Option<RillCheck>,
    /// For a sherd that needs manual orientation: three points on its longest rill, in the
    /// scan's units, to give to `--manual` (or to check in a viewer first).
    pub manual_points_on_rill: Option<[[f64; 3]; 3]>,
    /// For a sherd that needs manual orientation: the axis the orientation still found,
    /// not trusted (`axis` stays null: this is no answer). Null for every other status,
    /// and when the orientation found no axis at all (too few points).
    #[serde(default)]
    pub best_guess: Option<BestGuess>,
    /// What could not be measured and why (no level rim preserved, no capacity...); empty
    /// when there is nothing to say. The axis's doubts are in `reason`, not here.
    #[serde(default)]
    pub notes: Vec<String>,
    /// The drawing written, if any.
    pub drawing: Option<String>,
    /// The scan the axis was found on (counts and checksum as read, before repair): `sherd
    /// draw` and `sherd export` refuse an axis file whose scan is another.
    #[serde(default)]
    pub scan: Option<ScanFingerprint>,
    /// Seconds per step.
    pub timings: Timings,
}

impl SherdRecord {
    /// The record of a scan that could not be processed.
    pub fn failed(file: String, error: &Error) -> Self {
        SherdRecord { file, status: RecordStatus::Error, error: Some(error.to_string()), ..Default::default() }
    }

    /// The record of an analysis, its axis brought back to the scan's own units.
    pub fn from_analysis(file: String, analysis: &Analysis) -> Self {
        let orientation = &analysis.orientation;
        let mut record =
            SherdRecord { file, timings: analysis.timings, scan: Some(analysis.scan.clone()), ..Default::default() };
        let mut method = orientation.report.method.clone();
        if let Some(refinement) = &analysis.refinement {
            method = format!("{method} + {}", refinement.report.method);
        }
        record.method = Some(method);
        match &orientation.verdict {
            Verdict::Oriented => record.status = RecordStatus::Ok,
            Verdict::SenseUncertain { reason } => {
                record.status = RecordStatus::SenseUncertain;
                record.reason = Some(reason.clone());
            }
            Verdict::NeedsManualOrientation { reason } => {
                record.status = RecordStatus::NeedsManualOrientation;
                record.reason = Some(reason.clone());
                record.manual_points_on_rill = analysis.rills().first().map(|rill| {
                    three_points_on(rill).map(|p| (p.coords / analysis.millimetres_per_unit).into())
                });
                record.best_guess = analysis.found_an_axis().then(|| BestGuess {
                    axis: in_scan_units(&orientation.axis, analysis.millimetres_per_unit).record(),
                    against: reason.clone(),
                    sense_known: orientation.report.direction_strength >= analysis.min_sense_confidence,
                });
                return record;
            }
        }
        let doubts = analysis.axis_doubts();
        if !doubts.is_empty() {
            if record.status == RecordStatus::Ok {
                record.status = RecordStatus::AxisUncertain;
            }
            let doubts = doubts.join("; ");
            // Beside a sense left open, say that the line itself is in doubt too: "the
            // axis line is found" alone would read as a line to trust.
            record.reason = Some(match record.reason.take() {
                Some(sense) => format!("{sense}; and the axis line itself is uncertain: {doubts}"),
                None => doubts,
            });
        }
        record.axis = Some(in_scan_units(analysis.axis(), analysis.millimetres_per_unit).record());
        record.residual_mm = Some(match &analysis.refinement {
            Some(refinement) => refinement.report.residual_mm,
            None => orientation.report.residual_scale_mm,
        });
        if let Some(m) = &analysis.measurements {
            record.axis_angle_interval_deg = m.axis_angle_interval_deg;
            record.axis_distance_interval_mm = m.axis_distance_interval_mm;
            record.rim_radius_mm = m.rim_radius_mm;
            record.rim_diameter_mm = m.rim_diameter_mm;
            record.rim_diameter_interval_mm = m.rim_diameter_interval_mm;
            record.base_diameter_mm = m.base_diameter_mm;
            record.base_diameter_interval_mm = m.base_diameter_interval_mm;
            record.sector_angle_deg = Some(m.sector_angle_deg);
            record.sector_percent = Some(m.sector_percent);
            record.height_mm = Some(m.height_mm);
            record.wall_thickness_mm = m.wall_thickness_mm;
            record.capacity_litres = m.capacity_litres;
            record.rim_sector_deg = m.rim_sector_deg;
            record.base_sector_deg = m.base_sector_deg;
            // The axis's doubts are in `reason` already.
            record.notes = m.notes.iter().filter(|note| !note.starts_with(AXIS_DOUBT_NOTE)).cloned().collect();
        }
        record.rills = rill_check(analysis.rills());
        record
    }

    /// The columns of `report.csv`. New columns are added at the end, so that a reader
    /// that takes them by position keeps working; the best guess's (a declined sherd's)
    /// are empty on every other row.
    pub const CSV_HEADER: &'static str = "file,status,reason,rim_diameter_mm,rim_diameter_low_mm,rim_diameter_high_mm,base_diameter_mm,base_diameter_low_mm,base_diameter_high_mm,sector_angle_deg,sector_percent,height_mm,wall_thickness_mm,capacity_litres,axis_angle_upper_deg,residual_mm,method,drawing,read_s,repair_s,orient_s,refine_s,measure_s,draw_s,rill_count,rill_slope_deg,axis_distance_upper_mm,best_guess_point_x,best_guess_point_y,best_guess_point_z,best_guess_direction_x,best_guess_direction_y,best_guess_direction_z,best_guess_sense_known,rim_sector_deg,base_sector_deg,notes";

    /// This record as a row of `report.csv` (RFC 4180 quoting).
    pub fn csv_row(&self) -> String {
        let number = |v: Option<f64>| v.map(|v| format!("{v:.3}")).unwrap_or_default();
        let low = |v: Option<[f64; 2]>| number(v.map(|i| i[0]));
        let high = |v: Option<[f64; 2]>| number(v.map(|i| i[1]));
        let reason = self.error.clone().or_else(|| self.reason.clone()).unwrap_or_default();
        let status = if self.error.is_some() { format!("{}: {reason}", RecordStatus::Error) } else { self.status.to_string() };
        let t = &self.timings;
        let guess = self.best_guess.as_ref();
        let coordinate = |v: Option<f64>| v.map(|v| format!("{v:.6}")).unwrap_or_default();
        let point = |i: usize| coordinate(guess.map(|g| g.axis.point[i]));
        let direction = |i: usize| coordinate(guess.map(|g| g.axis.direction[i]));
        [
            csv_quote(&self.file),
            csv_quote(&status),
            csv_quote(&reason),
            number(self.rim_diameter_mm),
            low(self.rim_diameter_interval_mm),
            high(self.rim_diameter_interval_mm),
            number(self.base_diameter_mm),
            low(self.base_diameter_interval_mm),
            high(self.base_diameter_interval_mm),
            number(self.sector_angle_deg),
            number(self.sector_percent),
            number(self.height_mm),
            number(self.wall_thickness_mm),
            number(self.capacity_litres),
            high(self.axis_angle_interval_deg),
            number(self.residual_mm),
            csv_quote(self.method.as_deref().unwrap_or("")),
            csv_quote(self.drawing.as_deref().unwrap_or("")),
            format!("{:.3}", t.read_s),
            format!("{:.3}", t.repair_s),
            format!("{:.3}", t.orient_s),
            format!("{:.3}", t.refine_s),
            format!("{:.3}", t.measure_s),
            format!("{:.3}", t.draw_s),
            self.rills.map(|r| r.count.to_string()).unwrap_or_default(),
            number(self.rills.map(|r| r.slope_deg)),
            high(self.axis_distance_interval_mm),
            point(0),
            point(1),
            point(2),
            direction(0),
            direction(1),
            direction(2),
            guess.map(|g| g.sense_known.to_string()).unwrap_or_default(),
            number(self.rim_sector_deg),
            number(self.base_sector_deg),
            csv_quote(&self.notes.join("; ")),
        ]
        .join(",")
    }
}

/// `axis` (in millimetres) in the scan's units.
fn in_scan_units(axis: &Axis, millimetres_per_unit: f64) -> Axis {
    Axis { point: Point::from(axis.point.coords / millimetres_per_unit), direction: axis.direction }
}

fn csv_quote(field: &str) -> String {
    if field.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", field.replace('"', "\"\""))
    } else {
        field.to_owned()
    }
}
