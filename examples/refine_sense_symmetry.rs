//! Whether a refinement criterion's line depends on which way its start points. The
//! criteria fit surfaces of revolution, which have no up and down, so a start and the same
//! start flipped should refine to one line; where they do not, improving the sense cues
//! moves axis lines (A011's automatic line went from 0.2 to 1.4 degrees off its rill axis
//! when its weak sense hint flipped).
//!
//! On the tuning corpus (broken synthetic vessels, randomly moved), each fragment's
//! automatic orientation is refined by each criterion from its axis and from its axis
//! flipped; the angle between the two refined lines is counted, and, for each start, how
//! far the line lies from the truth (the paper's mean point distance, sense aside).
//!
//! Run: `cargo run --release --example refine_sense_symmetry [VESSELS] [FIRST_SEED]
//! [CELL_MM] [NOISE_MM] [DEFORMATION]` (defaults: 2 vessels from seed 100, 0.8 mm cells,
//! the generator's noise and deformation).

use sherd::orient::{mean_line_distance_mm, orient_automatic, OrientOptions};
use sherd::refine::{refine, Criterion, RefineOptions};
use sherd::statistics::nearest_rank_quantile;
use sherd::synth::{generate_vessel, VesselOptions};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let vessels: u64 = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(2);
    let first: u64 = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(100);
    let cell_size_mm: f64 = args.get(3).and_then(|a| a.parse().ok()).unwrap_or(0.8);
    let defaults = VesselOptions::default();
    let noise_mm: f64 = args.get(4).and_then(|a| a.parse().ok()).unwrap_or(defaults.noise_mm);
    let deformation_scale: f64 = args.get(5).and_then(|a| a.parse().ok()).unwrap_or(defaults.deformation_scale);
    let criteria = [Criterion::Circles, Criterion::Profile, Criterion::Auto];
    // Per criterion: angles between the two lines, and fragments within 4 mm from each start.
    let mut apart_deg: Vec<Vec<f64>> = vec![Vec::new(); criteria.len()];
    let mut within = vec![[0usize; 2]; criteria.len()];
    let mut fragments = 0usize;
    for seed in first..first + vessels {
        let vessel = generate_vessel(seed, &VesselOptions { cell_size_mm, noise_mm, deformation_scale, random_motion: true, ..defaults.clone() });
        for (index, fragment) in vessel.fragments.iter().enumerate() {
            let Ok(orientation) = orient_automatic(&fragment.mesh, &OrientOptions::default()) else { continue };
            if !orientation.verdict.has_axis_line() {
                continue;
            }
            fragments += 1;
            let truth = &fragment.truth.axis;
            let mut line = format!("vessel {seed} fragment {index} {:?}:", fragment.truth.part);
            for (slot, &criterion) in criteria.iter().enumerate() {
                let options = RefineOptions { criterion, ..Default::default() };
                let (Ok(from_start), Ok(from_flipped)) =
                    (refine(&fragment.mesh, &orientation.axis, &options), refine(&fragment.mesh, &orientation.axis.flipped(), &options))
                else {
                    continue;
                };
                let apart = from_start.axis.line_angle_to_deg(&from_flipped.axis);
                apart_deg[slot].push(apart);
                for (side, refined) in [&from_start, &from_flipped].into_iter().enumerate() {
                    let distance = mean_line_distance_mm(&fragment.mesh.positions, &refined.axis, truth);
                    within[slot][side] += (distance <= 4.0) as usize;
                }
                line += &format!(" {criterion:?} {apart:.2} deg apart;");
            }
            println!("{line}");
        }
    }
    println!("\n{fragments} fragments given an axis line");
    println!("| criterion | lines apart: median | 90th percentile | over 1 degree | within 4 mm from the start / flipped |");
    println!("|---|---|---|---|---|");
    for (slot, criterion) in criteria.iter().enumerate() {
        let angles = &mut apart_deg[slot];
        if angles.is_empty() {
            continue;
        }
        let over_one = angles.iter().filter(|a| **a > 1.0).count();
        let count = angles.len();
        println!(
            "| {criterion:?} | {:.3} deg | {:.3} deg | {over_one} of {count} | {} / {} |",
            nearest_rank_quantile(angles, 0.5),
            nearest_rank_quantile(angles, 0.9),
            within[slot][0],
            within[slot][1]
        );
    }
}
