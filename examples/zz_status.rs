use rayon::prelude::*;
use sherd::orient::mean_point_distance_mm;
use sherd::pipeline::{analyse, PipelineOptions, SherdRecord};
use sherd::synth::{generate_vessel, VesselOptions};
fn main() {
    let vessels: u64 = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(3);
    let sherds: Vec<_> = (0..vessels).flat_map(|seed| {
        let vessel = generate_vessel(seed, &VesselOptions { fragment_count: 34, random_motion: true, ..Default::default() });
        vessel.fragments.into_iter().enumerate().map(move |(i, f)| (seed * 1000 + i as u64, f))
    }).filter(|(_, s)| s.truth.hard_case.is_none()).collect();
    let rows: Vec<(u64, String, f64, String)> = sherds.par_iter().map(|(seed, s)| {
        let options = PipelineOptions { refine: Some(Default::default()), ..Default::default() };
        match analyse(s.mesh.clone(), &options) {
            Ok(a) => {
                let r = SherdRecord::from_analysis(seed.to_string(), &a);
                (*seed, r.status.clone(), mean_point_distance_mm(&s.mesh.positions, a.axis(), &s.truth.axis), r.reason.unwrap_or_default())
            }
            Err(e) => (*seed, "error".into(), f64::NAN, e.to_string()),
        }
    }).collect();
    let mut counts = std::collections::BTreeMap::new();
    for (seed, status, d, reason) in &rows {
        let e = counts.entry(status.clone()).or_insert((0, 0));
        e.0 += 1;
        if *d > 4.0 { e.1 += 1; }
        if status == "axis_uncertain" || (status == "ok" && *d > 4.0) { println!("{seed} {status} {d:.2} {reason}"); }
    }
    println!("{counts:?} (status: (count, >4 mm))");
}
