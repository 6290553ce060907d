//! The real scans of `../shared/data`, fully automatic through the whole pipeline (as
//! `sherd orient` runs them): the four SfS++ pot C sherds against their reference axes
//! (known to about 3 degrees), and the DACORD sherd A011 against the axis three points on
//! one of its wheel rills give (the README's `--manual` example).
//!
//! `cargo run --release --example real_scans`

#[path = "../tests/support/evaluation.rs"]
mod evaluation;

use std::path::Path;

use sherd::mesh::Point;
use sherd::pipeline::{analyse, analyse_file, Analysis, PipelineOptions, RecordStatus, SherdRecord};

/// Three points on A011's longest wheel rill, in the scan's frame (the README's example).
const A011_RILL_POINTS: [[f64; 3]; 3] = [[30.508, -66.920, 39.363], [18.614, -75.548, 43.705], [8.663, -86.138, 42.986]];

fn row(name: &str, analysis: &Analysis, reference: &sherd::orient::Axis, reference_name: &str) {
    let record = SherdRecord::from_analysis(name.into(), analysis);
    let axis = analysis.axis();
    let line_deg = axis.line_angle_to_deg(reference);
    let up = axis.direction.dot(&reference.direction) > 0.0;
    let rills = record.rills.as_ref().map_or("-".to_string(), |r| format!("{} (slope {:.2} deg)", r.count, r.slope_deg));
    println!(
        "| {name} | {} | {line_deg:.2} deg from {reference_name} | {} | {rills} |",
        record.status,
        if matches!(record.status, RecordStatus::NeedsManualOrientation | RecordStatus::SenseUncertain) { "-" } else if up { "yes" } else { "no" },
    );
}

fn main() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data");
    if !data.exists() {
        println!("SKIP: {} is absent", data.display());
        return;
    }
    let options = PipelineOptions { refine: Some(Default::default()), ..Default::default() };
    println!("| scan | status | axis line | right way up | wheel rills |");
    println!("|---|---|---|---|---|");
    let folder = data.join("sfspp_pot_C");
    match evaluation::read_sfspp_pot_c(&folder) {
        Ok(pieces) => {
            for piece in pieces {
                match analyse(piece.cloud, &options) {
                    Ok(analysis) => row(&piece.name, &analysis, &piece.reference, "its reference"),
                    Err(error) => println!("| {} | error: {error} | | | |", piece.name),
                }
            }
        }
        Err(error) => println!("| SfS++ pot C | not read: {error} | | | |"),
    }
    let a011 = data.join("dacord/A011.ply");
    let manual = PipelineOptions { manual_points: Some(A011_RILL_POINTS.map(Point::from)), ..options.clone() };
    match (analyse_file(&a011, &options), analyse_file(&a011, &manual)) {
        (Ok(automatic), Ok(by_rill)) => row("A011", &automatic, by_rill.axis(), "the rill points' axis"),
        (Err(error), _) | (_, Err(error)) => println!("| A011 | error: {error} | | | |"),
    }
}
