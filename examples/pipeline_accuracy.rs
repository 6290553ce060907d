//! Accuracy and time of the whole pipeline (`sherd::pipeline::analyse`: repair,
//! automatic pre-orientation, refinement, measurements with bootstrap intervals) on
//! large synthetic sherds, side by side on the same sherds, in three modes:
//!
//! * `full`: refinement and bootstrap on the full-resolution mesh;
//! * `full-refine`: refinement on the full-resolution mesh, bootstrap on the
//!   pre-orientation's decimated copy (`refine_on_full_resolution`);
//! * `default`: both on the decimated copy (`PipelineOptions::default()`).
//!
//! Run: `cargo run --release --example pipeline_accuracy [COUNT] [FACES] [full,full-refine,default]`
//! (defaults: 12 sherds of 100,000 faces, seeds 0.., parts cycled rim/body/base, all modes).

use std::time::Instant;

use sherd::statistics::nearest_rank_quantile;
use sherd::orient::mean_point_distance_mm;
use sherd::pipeline::{analyse, PipelineOptions};
use sherd::refine::RefineOptions;
use sherd::synth::{synthetic_sherd, SherdOptions, SherdPart};

/// One sherd's outcome under one mode.
struct Outcome {
    oriented: bool,
    /// Oriented, but the record's status is `axis_uncertain` (its intervals doubt it).
    axis_uncertain: bool,
    angle_deg: f64,
    distance_mm: f64,
    rim_error_percent: Option<f64>,
    rim_covered: Option<bool>,
    angle_covered: Option<bool>,
    refine_s: f64,
    measure_s: f64,
    total_s: f64,
}

/// The upper median (rank `n / 2`, as `round((n - 1) / 2)` gives it), NaN for none.
fn median(mut values: Vec<f64>) -> f64 {
    nearest_rank_quantile(&mut values, 0.5)
}

fn maximum(values: &[f64]) -> f64 {
    values.iter().copied().fold(f64::NAN, f64::max)
}

/// "N (W)": how many outcomes, and how many of them more than 4 mm off (the paper's test).
fn with_wrong<'a>(outcomes: impl Iterator<Item = &'a &'a Outcome>) -> String {
    let distances: Vec<f64> = outcomes.map(|o| o.distance_mm).collect();
    format!("{} ({})", distances.len(), distances.iter().filter(|&&d| d > 4.0).count())
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let count: u64 = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(12);
    let faces: usize = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(100_000);
    let modes: Vec<String> =
        args.get(3).map(|a| a.split(',').map(str::to_string).collect()).unwrap_or_else(|| ["full", "full-refine", "default"].map(String::from).to_vec());
    let parts = [SherdPart::Rim, SherdPart::Body, SherdPart::Base];
    let mut table: Vec<(String, Vec<Outcome>)> = modes.iter().map(|m| (m.clone(), Vec::new())).collect();
    for seed in 0..count {
        let part = parts[seed as usize % parts.len()];
        let sherd = synthetic_sherd(seed, &SherdOptions { target_faces: faces, ..SherdOptions::for_part(part) });
        let truth = &sherd.truth;
        for (mode, outcomes) in &mut table {
            let options = PipelineOptions {
                refine: Some(RefineOptions::default()),
                refine_on_full_resolution: mode != "default",
                bootstrap_on_full_resolution: mode == "full",
                ..Default::default()
            };
            let started = Instant::now();
            let analysis = match analyse(sherd.mesh.clone(), &options) {
                Ok(analysis) => analysis,
                Err(error) => {
                    eprintln!("seed {seed} {mode}: error {error}");
                    continue;
                }
            };
            let total_s = started.elapsed().as_secs_f64();
            let axis = analysis.axis();
            let rim = analysis.measurements.as_ref().and_then(|m| m.rim_radius_mm.zip(truth.rim_radius_mm));
            let rim_interval = analysis.measurements.as_ref().and_then(|m| m.rim_diameter_interval_mm);
            let outcome = Outcome {
                oriented: analysis.is_oriented(),
                axis_uncertain: !analysis.axis_doubts().is_empty(),
                angle_deg: axis.line_angle_to_deg(&truth.axis),
                distance_mm: mean_point_distance_mm(&sherd.mesh.positions, axis, &truth.axis),
                rim_error_percent: rim.map(|(measured, true_radius)| 100.0 * (measured - true_radius).abs() / true_radius),
                rim_covered: truth
                    .rim_radius_mm
                    .zip(rim_interval)
                    .map(|(r, [low, high])| (low..=high).contains(&(2.0 * r))),
                angle_covered: analysis
                    .measurements
                    .as_ref()
                    .and_then(|m| m.axis_angle_interval_deg)
                    .map(|[_, upper]| axis.line_angle_to_deg(&truth.axis) <= upper),
                refine_s: analysis.timings.refine_s,
                measure_s: analysis.timings.measure_s,
                total_s,
            };
            eprintln!(
                "seed {seed} {part:?} {} faces {mode}: oriented {} angle {:.3} deg, distance {:.3} mm, rim error {:?} %, refine {:.2} s, measure {:.2} s, total {:.2} s",
                sherd.mesh.face_count(),
                outcome.oriented,
                outcome.angle_deg,
                outcome.distance_mm,
                outcome.rim_error_percent.map(|e| (e * 1000.0).round() / 1000.0),
                outcome.refine_s,
                outcome.measure_s,
                outcome.total_s
            );
            outcomes.push(outcome);
        }
    }
    println!("| mode | sherds | oriented | median angle deg | max angle deg (oriented) | median dist mm | max dist mm (oriented) | rim radius error median % (n) | rim interval coverage | angle interval coverage | ok (> 4 mm off) | axis_uncertain (> 4 mm off) | median refine s | median measure s | median total s |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (mode, outcomes) in &table {
        let oriented: Vec<&Outcome> = outcomes.iter().filter(|o| o.oriented).collect();
        let rim_errors: Vec<f64> = oriented.iter().filter_map(|o| o.rim_error_percent).collect();
        let covered: Vec<bool> = oriented.iter().filter_map(|o| o.rim_covered).collect();
        let angle_covered: Vec<bool> = oriented.iter().filter_map(|o| o.angle_covered).collect();
        println!(
            "| {mode} | {} | {} | {:.3} | {:.3} | {:.3} | {:.3} | {:.2} ({}) | {}/{} | {}/{} | {} | {} | {:.2} | {:.2} | {:.2} |",
            outcomes.len(),
            oriented.len(),
            median(oriented.iter().map(|o| o.angle_deg).collect()),
            maximum(&oriented.iter().map(|o| o.angle_deg).collect::<Vec<_>>()),
            median(oriented.iter().map(|o| o.distance_mm).collect()),
            maximum(&oriented.iter().map(|o| o.distance_mm).collect::<Vec<_>>()),
            median(rim_errors.clone()),
            rim_errors.len(),
            covered.iter().filter(|c| **c).count(),
            covered.len(),
            angle_covered.iter().filter(|c| **c).count(),
            angle_covered.len(),
            with_wrong(oriented.iter().filter(|o| !o.axis_uncertain)),
            with_wrong(oriented.iter().filter(|o| o.axis_uncertain)),
            median(outcomes.iter().map(|o| o.refine_s).collect()),
            median(outcomes.iter().map(|o| o.measure_s).collect()),
            median(outcomes.iter().map(|o| o.total_s).collect()),
        );
    }
}
