//! Where each refinement criterion settles when it starts on the true axis: a diagnostic
//! of the criteria themselves, apart from the search. A fragment whose criterion moves the
//! axis past 4 mm from a perfect start cannot be oriented within 4 mm by any search that
//! the criterion judges: its best-fitting axis of revolution is not the vessel's (a thrown
//! pot's ovality and waves bend a short arc's circles about another axis).
//!
//! Reads folders of `NAME.ply` + `NAME.truth.json` (the report corpus's or `sherd synth`'s),
//! repairs and decimates each scan as the pipeline does, refines it from its true axis by
//! each criterion, and prints, by part, how many refined lines lie within 4 mm (the paper's
//! mean point distance, sense aside) and the median distance and angle.
//!
//! Run: `cargo run --release --example refine_from_truth FOLDER [FOLDER...]`
//! (`REFINE_FROM_TRUTH_EACH=1` also prints every fragment's line;
//! `REFINE_FROM_TRUTH_SHIFT_MM=10` starts 10 mm toward the sherd from the true axis).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use rayon::prelude::*;
use sherd::mesh::io::read_mesh;
use sherd::mesh::repair::{repair, RepairOptions};
use sherd::mesh::{Point, Vector};
use sherd::orient::{decimated_copy, mean_line_distance_mm, Axis, OrientOptions};
use sherd::refine::{refine, Criterion, RefineOptions};
use sherd::statistics::nearest_rank_quantile;

#[path = "../tests/support/evaluation.rs"]
mod evaluation;

const CRITERIA: [Criterion; 3] = [Criterion::Circles, Criterion::Profile, Criterion::Auto];
const RIGHT_MM: f64 = 4.0;

/// One fragment: its part and, per criterion, the refined line's distance and angle from
/// the truth (`None` when the criterion failed).
struct Row {
    name: String,
    part: String,
    settled: Vec<Option<(f64, f64)>>,
}

fn evaluate(ply: &Path) -> Option<Row> {
    let (truth, part) = evaluation::truth_of(ply)?;
    let mut mesh = read_mesh(ply).ok()?;
    repair(&mut mesh, &RepairOptions::default());
    let copy = decimated_copy(&mesh, &OrientOptions::default()).ok()?;
    let working = copy.as_ref().unwrap_or(&mesh);
    // REFINE_FROM_TRUTH_SHIFT_MM moves the start across the axis, toward the sherd: whether
    // the criterion brings a start off in position back, or keeps wherever it starts.
    let shift_mm: f64 = std::env::var("REFINE_FROM_TRUTH_SHIFT_MM").ok().and_then(|v| v.parse().ok()).unwrap_or(0.0);
    let centroid = Point::from(mesh.positions.iter().map(|p| p.coords).sum::<Vector>() / mesh.positions.len().max(1) as f64);
    let foot = truth.point + truth.direction.into_inner() * (centroid - truth.point).dot(&truth.direction);
    let toward = (centroid - foot).try_normalize(1e-12).unwrap_or_else(Vector::zeros);
    let start = Axis::new(truth.point + toward * shift_mm, truth.direction.into_inner());
    let settled = CRITERIA
        .iter()
        .map(|&criterion| {
            let options = RefineOptions { criterion, ..RefineOptions::default() };
            let refined = refine(working, &start, &options).ok()?;
            Some((mean_line_distance_mm(&mesh.positions, &refined.axis, &truth), refined.axis.line_angle_to_deg(&truth)))
        })
        .collect();
    let name = ply.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    Some(Row { name, part, settled })
}

fn main() {
    let folders: Vec<PathBuf> = std::env::args().skip(1).map(PathBuf::from).collect();
    if folders.is_empty() {
        eprintln!("usage: refine_from_truth FOLDER [FOLDER...] (NAME.ply + NAME.truth.json)");
        std::process::exit(2);
    }
    let mut plys: Vec<PathBuf> = Vec::new();
    for folder in &folders {
        let Ok(found) = evaluation::fragments_with_truth(folder) else {
            eprintln!("{}: cannot read the folder", folder.display());
            std::process::exit(2);
        };
        plys.extend(found);
    }
    plys.sort();
    let rows: Vec<Row> = plys.par_iter().filter_map(|p| evaluate(p)).collect();
    if std::env::var_os("REFINE_FROM_TRUTH_EACH").is_some() {
        for row in &rows {
            let cells: Vec<String> = row.settled.iter().map(|s| s.map_or("-".into(), |(d, a)| format!("{d:.2} mm {a:.2} deg"))).collect();
            println!("{} {}: {}", row.name, row.part, cells.join(", "));
        }
    }
    let mut by_part: BTreeMap<String, Vec<&Row>> = BTreeMap::new();
    for row in &rows {
        by_part.entry(row.part.clone()).or_default().push(row);
        by_part.entry("all".into()).or_default().push(row);
    }
    println!("Refined from the true axis ({} fragments of {}): within {RIGHT_MM} mm, median distance, median angle", rows.len(), plys.len());
    print!("| part | n |");
    for criterion in CRITERIA {
        print!(" {criterion} |");
    }
    println!();
    println!("|---|---|{}", "---|".repeat(CRITERIA.len()));
    for (part, rows) in &by_part {
        print!("| {part} | {} |", rows.len());
        for index in 0..CRITERIA.len() {
            let settled: Vec<(f64, f64)> = rows.iter().filter_map(|r| r.settled[index]).collect();
            let within = settled.iter().filter(|(d, _)| *d <= RIGHT_MM).count();
            let mut distances: Vec<f64> = settled.iter().map(|s| s.0).collect();
            let mut angles: Vec<f64> = settled.iter().map(|s| s.1).collect();
            let (distance, angle) = (nearest_rank_quantile(&mut distances, 0.5), nearest_rank_quantile(&mut angles, 0.5));
            print!(" {within}/{} ({:.0}%), {distance:.2} mm, {angle:.2} deg |", rows.len(), 100.0 * within as f64 / rows.len() as f64);
        }
        println!();
    }
}
