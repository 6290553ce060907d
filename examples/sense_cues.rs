//! How the sense cues (`orient::direction`) fare under the true axis line, on the tuning
//! corpus: per part, how often they speak, and how often rightly.
//! Run: `cargo run --release --example sense_cues [VESSELS] [FIRST_SEED] [CELL_MM]
//! [NOISE_MM] [DEFORMATION]` (defaults: 4 vessels from seed 0, 0.8 mm cells, the
//! generator's noise and deformation).
use sherd::orient::{orient_automatic, OrientOptions};
use sherd::synth::{generate_vessel, VesselOptions};

fn main() {
    let args: Vec<f64> = std::env::args().skip(1).map(|a| a.parse().expect("numbers")).collect();
    let (vessels, first) = (args.first().map_or(4, |v| *v as u64), args.get(1).map_or(0, |v| *v as u64));
    let defaults = VesselOptions::default();
    let cell_size_mm = args.get(2).copied().unwrap_or(0.8);
    let noise_mm = args.get(3).copied().unwrap_or(defaults.noise_mm);
    let deformation_scale = args.get(4).copied().unwrap_or(defaults.deformation_scale);
    let options = OrientOptions::default();
    let mut table = std::collections::BTreeMap::new();
    for seed in first..first + vessels {
        let vessel = generate_vessel(seed, &VesselOptions { cell_size_mm, noise_mm, deformation_scale, random_motion: true, ..defaults.clone() });
        for (index, fragment) in vessel.fragments.iter().enumerate() {
            let orientation = orient_automatic(&fragment.mesh, &options).unwrap();
            let Some(inputs) = orientation.sense_inputs.clone() else { continue };
            // Half the time the line is given upside down: the cue must not care.
            let axis = if index % 2 == 0 { fragment.truth.axis } else { fragment.truth.axis.flipped() };
            let truth_sign = if index % 2 == 0 { 1.0 } else { -1.0 };
            let (_, evidence) = inputs.judge(&axis);
            let entry = table.entry(format!("{:?}", fragment.truth.part)).or_insert([0usize; 4]);
            entry[0] += 1;
            if evidence.score.abs() >= options.thresholds.min_sense_confidence {
                entry[1] += 1;
                if evidence.score * truth_sign > 0.0 { entry[2] += 1 } else {
                    println!("WRONG vessel {seed} fragment {index} {:?}: {} ({:.2}) finished {:.2}/{:.2}", fragment.truth.part, evidence.cue, evidence.score, evidence.cues.upper_finished_share, evidence.cues.lower_finished_share);
                }
            } else {
                entry[3] += 1;
                println!("silent vessel {seed} fragment {index} {:?}: {} ({:.2}) {:?}", fragment.truth.part, evidence.cue, evidence.score, evidence.cues);
            }
        }
    }
    for (part, [n, spoke, right, _]) in table {
        println!("{part}: {n} fragments, the cues decide {spoke}, rightly {right}");
    }
}
