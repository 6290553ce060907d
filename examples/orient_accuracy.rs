//! Accuracy of the automatic pre-orientation, measured: on synthetic vessels broken into
//! fragments (fixed seeds), on the hard presets that must be flagged, on the real SfS++
//! sherds against their reference axes and on the DACORD example A011.
//!
//! `cargo run --release --example orient_accuracy [VESSELS] [FRAGMENTS_PER_VESSEL] [CSV]`
//! (defaults 10, 30, no CSV).

#[path = "../tests/support/evaluation.rs"]
mod evaluation;

use std::path::{Path, PathBuf};

use sherd::mesh::io::read_mesh;
use rayon::prelude::*;
use evaluation::{evaluate, read_sfspp_pot_c, FragmentOutcome, SfsppPiece, Summary};
use sherd::orient::{orient_automatic, OrientOptions, Orientation};
use sherd::synth::{generate_vessel, synthetic_sherd, HardCase, SherdOptions, SherdPart, VesselOptions};

fn shared_data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data")
}

fn verdict_text(orientation: &Orientation) -> String {
    match &orientation.verdict {
        sherd::orient::Verdict::Oriented => "oriented".into(),
        sherd::orient::Verdict::NeedsManualOrientation { reason } => format!("NEEDS_MANUAL ({reason})"),
        sherd::orient::Verdict::SenseUncertain { reason } => format!("SENSE_UNCERTAIN ({reason})"),
    }
}

/// The SfS++ pot C sherds: both skins' subsampled points with normals, against the
/// derived per-piece reference axis (known to about 3 deg / 2 mm).
fn real_sfspp(options: &OrientOptions) {
    let folder = shared_data().join("sfspp_pot_C");
    let pieces = match read_sfspp_pot_c(&folder) {
        Ok(pieces) => pieces,
        Err(error) => return println!("SKIP SfS++: {error}"),
    };
    println!("\n## SfS++ pot C (reference A, per piece; tolerance of the reference ~3 deg / 2 mm)");
    println!("| piece | points | line angle deg | axis offset at sherd mm | verdict |");
    println!("|---|---|---|---|---|");
    for (piece, SfsppPiece { cloud, reference, .. }) in (1..).zip(pieces) {
        match orient_automatic(&cloud, options) {
            Ok(orientation) => {
                let centroid = cloud.centroid().unwrap();
                let offset = reference.distance_to(&orientation.axis.closest_point(&centroid));
                println!(
                    "| {piece} | {} | {:.2} | {:.2} | {} |",
                    cloud.vertex_count(),
                    orientation.axis.line_angle_to_deg(&reference),
                    offset,
                    verdict_text(&orientation)
                );
            }
            Err(error) => println!("| {piece} | {} | - | - | error: {error} |", cloud.vertex_count()),
        }
    }
}

/// The DACORD example: no published axis; the radius and the verdict are printed.
fn real_a011(options: &OrientOptions) {
    let path = shared_data().join("dacord/A011.ply");
    let Ok(mesh) = read_mesh(&path) else {
        println!("SKIP A011: {} absent", path.display());
        return;
    };
    println!("\n## DACORD A011 ({} vertices, {} faces)", mesh.vertex_count(), mesh.face_count());
    let started = std::time::Instant::now();
    match orient_automatic(&mesh, options) {
        Ok(orientation) => {
            let mut radii: Vec<f64> = mesh.positions.iter().map(|p| orientation.axis.distance_to(p)).collect();
            radii.sort_by(f64::total_cmp);
            println!(
                "verdict {}; direction {:?}; radius of the points: median {:.1} mm, max {:.1} mm; +-{:.2} deg; {:.0} ms",
                verdict_text(&orientation),
                orientation.axis.direction.into_inner().as_slice(),
                radii[radii.len() / 2],
                radii[radii.len() - 1],
                orientation.angle_uncertainty_deg,
                started.elapsed().as_secs_f64() * 1e3
            );
            println!("report: {}", serde_json::to_string(&orientation.report).unwrap());
        }
        Err(error) => println!("error: {error}"),
    }
}

fn synthetic(options: &OrientOptions, vessels: u64, fragments: usize, csv: Option<&str>) {
    // 0.8 mm cells: fragments of a few thousand faces, closer to a decimated scan than the
    // generator's default 2 mm.
    let vessel_options =
        VesselOptions { fragment_count: fragments, random_motion: true, cell_size_mm: 0.8, ..Default::default() };
    let mut outcomes: Vec<FragmentOutcome> = (0..vessels)
        .into_par_iter()
        .flat_map(|v| {
            let vessel = generate_vessel(1000 + v, &vessel_options);
            vessel
                .fragments
                .par_iter()
                .enumerate()
                .map(|(k, sherd)| evaluate(format!("vessel{v}-{k}"), sherd, options))
                .collect::<Vec<_>>()
        })
        .collect();
    outcomes.sort_by(|a, b| a.id.cmp(&b.id));
    println!("## Synthetic: {vessels} vessels broken into {fragments} fragments each, random poses");
    println!("{}", Summary::table_header());
    println!("{}", Summary::of(&outcomes).table_row("all"));
    for part in SherdPart::ALL {
        let subset: Vec<FragmentOutcome> = outcomes.iter().filter(|o| o.part == part).cloned().collect();
        if !subset.is_empty() {
            println!("{}", Summary::of(&subset).table_row(part.name()));
        }
    }
    for (low, high) in [(0.0, 20.0), (20.0, 40.0), (40.0, 70.0), (70.0, 361.0)] {
        let subset: Vec<FragmentOutcome> =
            outcomes.iter().filter(|o| o.sector_angle_deg >= low && o.sector_angle_deg < high).cloned().collect();
        if !subset.is_empty() {
            println!("{}", Summary::of(&subset).table_row(&format!("sector {low:.0}-{high:.0} deg")));
        }
    }
    let mut times: Vec<f64> = outcomes.iter().map(|o| o.elapsed_ms).collect();
    times.sort_by(f64::total_cmp);
    println!("orientation time per fragment (parallel run, indicative only): median {:.0} ms", times[times.len() / 2]);

    println!("\n## Mixed parts from synthetic_sherd (seeds 0..{})", 2 * fragments);
    let mixed: Vec<FragmentOutcome> = (0..2 * fragments as u64)
        .into_par_iter()
        .map(|seed| evaluate(format!("sherd{seed}"), &synthetic_sherd(seed, &SherdOptions::default()), options))
        .collect();
    println!("{}", Summary::table_header());
    println!("{}", Summary::of(&mixed).table_row("mixed"));

    println!("\n## Hard presets (must be flagged)");
    println!("| preset | n | flagged | wrong >5deg unflagged |\n|---|---|---|---|");
    let mut hard_all = Vec::new();
    for case in [HardCase::FlatBase, HardCase::NearSpherical, HardCase::Tiny] {
        let hard: Vec<FragmentOutcome> = (0..10u64)
            .into_par_iter()
            .map(|seed| evaluate(format!("{case:?}{seed}"), &synthetic_sherd(seed, &SherdOptions::hard_case(case)), options))
            .collect();
        let s = Summary::of(&hard);
        println!("| {case:?} | {} | {:.0}% | {:.0}% |", s.count, 100.0 * s.flagged_fraction, 100.0 * s.wrong_angle_unflagged_fraction);
        hard_all.extend(hard);
    }
    if let Some(path) = csv {
        let mut text = String::from("id,part,sector_deg,angle_err,sense_ok,mpd,line_mpd,flagged,spread,concurrency,resid_angle,pos_unc,comp_angle,comp_ratio,inliers,dir_strength,dir_cue,ms,reason,shape,floor,level,upper_spread,lower_spread,opening,slope,upper_frac,lower_frac,sense_uncertain\n");
        for o in outcomes.iter().chain(&mixed).chain(&hard_all) {
            let (ca, cr) = o.competitor.unwrap_or((0.0, f64::INFINITY));
            text += &format!(
                "{},{},{:.1},{:.3},{},{:.3},{:.3},{},{:.4},{:.4},{:.3},{:.3},{:.1},{:.3},{:.3},{:.3},{},{:.1},\"{}\",{:?},{},{:.3},{:.3},{:.3},{:.3},{:.3},{:.3},{:.3},{}\n",
                o.id, o.part.name(), o.sector_angle_deg, o.line_angle_error_deg, o.sense_correct, o.mean_point_distance_mm,
                o.line_point_distance_mm, o.flagged, o.normal_spread, o.concurrency_ratio,
                o.residual_angle_deg, o.position_uncertainty_mm, ca, cr, o.inlier_fraction, o.direction_strength,
                o.direction_cue.replace(',', ";"), o.elapsed_ms, o.reason.replace('"', "'"), o.shape, o.sense_cues.floor,
                o.sense_cues.level_edge, o.sense_cues.upper_end_spread_mm, o.sense_cues.lower_end_spread_mm,
                o.sense_cues.opening, o.sense_cues.wall_slope, o.sense_cues.upper_level_fraction,
                o.sense_cues.lower_level_fraction, o.sense_uncertain
            );
        }
        std::fs::write(path, text).expect("CSV written");
        println!("per-fragment figures written to {path}");
    }
}

fn main() {
    let arguments: Vec<String> = std::env::args().collect();
    let vessels = arguments.get(1).and_then(|a| a.parse().ok()).unwrap_or(10);
    let fragments = arguments.get(2).and_then(|a| a.parse().ok()).unwrap_or(30);
    let options = OrientOptions::default();
    synthetic(&options, vessels, fragments, arguments.get(3).map(String::as_str));
    real_sfspp(&options);
    real_a011(&options);
}
