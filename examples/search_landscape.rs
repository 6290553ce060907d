//! Where the true axis lies in the whole-sphere search's landscape
//! (`orient::revolution_search`), on the tuning corpus (broken synthetic vessels, randomly
//! moved, never the report corpus): per fragment, the rank of the first valley within 4 mm
//! of the truth (the paper's mean point distance, sense aside), the angles and scores of
//! the valleys, the t statistic by which the best beats its nearest competitor farther
//! than 15 degrees (`orient::landscape`), and the search's time; then the ranks counted.
//!
//! Each line also gives the valley of the true direction (followed down from it): when it
//! scores lower than the best valley the search missed it; when higher, the criterion
//! itself prefers a wrong axis.
//!
//! Run: `cargo run --release --example search_landscape [VESSELS] [FIRST_SEED] [CELL_MM]
//! [NOISE_MM] [DEFORMATION] [SHAPE|any] [RELIEF_MM]` (defaults: 3 vessels from seed 0, 0.8 mm cells, the
//! generator's noise and deformation; `sherd synth --noise-mm 0.15 --deformation 3`
//! makes rough vessels).

use std::time::Instant;

use sherd::orient::landscape::{competing_valleys, sample_blocks};
use sherd::axis::Axis;
use sherd::orient::revolution_search::{descend, point_losses, search, DirectionFit, RevolutionSamples, SearchOptions};
use sherd::orient::{decimated_copy, mean_line_distance_mm, surface_of_revolution_lines, working_copy, OrientOptions};
use sherd::statistics::nearest_rank_quantile;
use sherd::synth::{generate_vessel, VesselOptions};

/// The axis of a direction's fit, in the scan frame.
fn truth_valley_axis(samples: &RevolutionSamples, fit: &DirectionFit) -> Axis {
    Axis::new(samples.centroid + fit.centre, fit.direction)
}

/// The weighted mean loss of `axis` over the samples, as the search scores a fit.
fn mean_loss(samples: &RevolutionSamples, axis: &Axis, loss_scale_mm: f64) -> f64 {
    let losses = point_losses(samples, axis, loss_scale_mm);
    let total: f64 = samples.weights.iter().sum();
    losses.iter().zip(&samples.weights).map(|(l, w)| l * w).sum::<f64>() / total
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let vessels: u64 = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(3);
    let first: u64 = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(0);
    let cell_size_mm: f64 = args.get(3).and_then(|a| a.parse().ok()).unwrap_or(0.8);
    let defaults = VesselOptions::default();
    let noise_mm: f64 = args.get(4).and_then(|a| a.parse().ok()).unwrap_or(defaults.noise_mm);
    let deformation_scale: f64 = args.get(5).and_then(|a| a.parse().ok()).unwrap_or(defaults.deformation_scale);
    // SHAPE: a vessel family by name (bowl, plate...); random when absent.
    let shape = args.get(6).filter(|name| *name != "any").map(|name| name.parse().expect("a vessel family: bowl, carinated_bowl, jar, plate, beaker or globular"));
    // RELIEF_MM: the surface's relief (6 mm wavelength), none when absent.
    let relief = sherd::synth::Relief { amplitude_mm: args.get(7).and_then(|a| a.parse().ok()).unwrap_or(0.0), wavelength_mm: 6.0 };
    let options = OrientOptions::default();
    // Fragments whose best valley is wrong: the true valley lower (missed) or higher.
    let (mut missed, mut outscored) = (0usize, 0usize);
    // Experiments: SHERD_LOSS_SCALE_BANDS, SHERD_MIN_BAND_MM, SHERD_BAND_SPACINGS,
    // SHERD_COARSE_DIRECTIONS, SHERD_VALLEYS and SHERD_FINAL_VALLEYS override the search's
    // settings.
    let from_env = |name: &str| std::env::var(name).ok().and_then(|v| v.parse::<f64>().ok());
    let mut search_options = SearchOptions::default();
    if let Some(value) = from_env("SHERD_LOSS_SCALE_BANDS") {
        search_options.loss_scale_bands = value;
    }
    if let Some(value) = from_env("SHERD_COARSE_DIRECTIONS") {
        search_options.coarse_directions = value as usize;
    }
    if let Some(value) = from_env("SHERD_VALLEYS") {
        search_options.valleys = value as usize;
    }
    if let Some(value) = from_env("SHERD_FINAL_VALLEYS") {
        search_options.final_valleys = value as usize;
    }
    if let Some(value) = from_env("SHERD_MIN_BAND_MM") {
        search_options.min_band_mm = value;
    }
    if let Some(value) = from_env("SHERD_BAND_SPACINGS") {
        search_options.band_spacings = value;
    }
    // Rank 0 to 5 of the first valley within 4 mm; 6: none is.
    let mut ranks = [0usize; 7];
    let mut times_ms = Vec::new();
    for seed in first..first + vessels {
        let vessel = generate_vessel(seed, &VesselOptions { cell_size_mm, noise_mm, deformation_scale, random_motion: true, shape, relief, ..defaults.clone() });
        for (index, fragment) in vessel.fragments.iter().enumerate() {
            let decimated = decimated_copy(&fragment.mesh, &options).unwrap();
            let working = working_copy(&fragment.mesh, decimated.as_ref(), &options).unwrap();
            let lines = surface_of_revolution_lines(&working, &options).unwrap();
            let started = Instant::now();
            let Some(landscape) = search(&lines, &search_options) else {
                println!("vessel {seed} fragment {index}: too few points");
                continue;
            };
            times_ms.push(started.elapsed().as_secs_f64() * 1e3);
            let truth = fragment.truth.axis;
            let valleys: Vec<_> = landscape.valleys.iter().map(|v| v.axis(&landscape.samples)).collect();
            let distances: Vec<f64> = valleys
                .iter()
                .map(|axis| {
                    let positions = &fragment.mesh.positions;
                    mean_line_distance_mm(positions, axis, &truth)
                })
                .collect();
            let rank = distances.iter().position(|d| *d <= 4.0).unwrap_or(6).min(6);
            ranks[rank] += 1;
            // The true direction's own valley, followed down as the final descents are.
            let samples = &landscape.samples;
            let truth_valley = descend(samples, &truth.direction, 1f64.to_radians(), 0.05f64.to_radians(), landscape.loss_scale_mm, 3, 25);
            let truth_cost = truth_valley.cost;
            let truth_valley_mm = mean_line_distance_mm(&fragment.mesh.positions, &truth_valley_axis(samples, &truth_valley), &truth);
            // The score of the exact true axis, its position not solved: lower than the
            // true valley's when the position solve misses.
            let exact_cost = mean_loss(samples, &truth, landscape.loss_scale_mm);
            let best_cost = landscape.valleys.first().map(|v| v.fit.cost).unwrap_or(f64::INFINITY);
            if rank != 0 {
                if truth_cost < best_cost {
                    missed += 1;
                } else {
                    outscored += 1;
                }
            }
            let blocks = sample_blocks(&landscape.samples);
            let competitor_t = competing_valleys(&landscape, &blocks, 15.0).iter().map(|c| c.separation.t_statistic).fold(f64::INFINITY, f64::min);
            let list = |values: Vec<String>| values.join(" ");
            println!(
                "vessel {seed} fragment {index} {:?} sector {:.0} deg: rank {rank}, distances [{}] mm, angles [{}] deg, scores [{}], true valley {truth_cost:.4} at {truth_valley_mm:.1} mm, exact truth {exact_cost:.4}, competitor t {competitor_t:.1}, {:.0} ms",
                fragment.truth.part,
                fragment.truth.sector_angle_deg,
                list(distances.iter().map(|d| format!("{d:.1}")).collect()),
                list(valleys.iter().map(|a| format!("{:.1}", a.line_angle_to_deg(&truth))).collect()),
                list(landscape.valleys.iter().map(|v| format!("{:.4}", v.fit.cost)).collect()),
                times_ms.last().unwrap()
            );
        }
    }
    let total: usize = ranks.iter().sum();
    println!(
        "{total} fragments: the best valley within 4 mm for {}, a later one for {}, none for {}; median search {:.0} ms",
        ranks[0],
        ranks[1..6].iter().sum::<usize>(),
        ranks[6],
        nearest_rank_quantile(&mut times_ms, 0.5)
    );
    println!("best valley wrong: the true valley lower (the search missed it) for {missed}, higher (the criterion prefers a wrong axis) for {outscored}");
}
