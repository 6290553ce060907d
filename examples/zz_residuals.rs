use sherd::synth::{generate_vessel, VesselOptions};
use sherd::mesh::planar_length;
fn env_number(name: &str, default: f64) -> f64 { std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default) }
fn main() {
    let seeds: Vec<u64> = std::env::args().skip(1).map(|a| a.parse().unwrap()).collect();
    for seed in seeds {
        let vessel = generate_vessel(seed / 1000, &VesselOptions { fragment_count: 34, random_motion: true,
            deformation_scale: env_number("D", 1.0), noise_mm: env_number("N", 0.02), ..Default::default() });
        let sherd = &vessel.fragments[(seed % 1000) as usize];
        let truth = &sherd.truth.axis;
        let surface = sherd::refine::sections::PreparedSurface::new(&sherd.mesh, truth, sherd::refine::Surface::Both, None).unwrap();
        let frame = sherd::refine::sections::CandidateFrame::new(&[0.0; 4]);
        let sections = surface.horizontal_sections(&frame);
        for (i, s) in sections.iter().enumerate() {
            if s.points.len() < 6 { continue; }
            let radii: Vec<f64> = s.points.iter().map(|p| planar_length(p[0], p[1])).collect();
            let mut sorted = radii.clone(); sorted.sort_by(f64::total_cmp);
            let med = sorted[sorted.len() / 2];
            let mut dev: Vec<f64> = radii.iter().map(|r| (r - med).abs()).collect(); dev.sort_by(f64::total_cmp);
            let n = dev.len();
            println!("seed {seed} section {i} skin {:?} n {n} median r {med:.2} dev p50 {:.4} p90 {:.4} p99 {:.4} max {:.4} var {:.3e}",
                s.skin, dev[n / 2], dev[n * 9 / 10], dev[n * 99 / 100], dev[n - 1], sherd::refine::circles::trimmed_variance(s));
        }
    }
}
