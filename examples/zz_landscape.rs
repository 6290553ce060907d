use nalgebra::{Unit, UnitQuaternion};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use sherd::mesh::Vector;
use sherd::orient::Axis;
use sherd::refine::objective::Objective;
use sherd::refine::{refine, Criterion, RefineOptions};
use sherd::synth::{generate_vessel, VesselOptions};
fn env_number(name: &str, default: f64) -> f64 { std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default) }
fn perturbed(truth: &Axis, seed: u64) -> Axis {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5eed);
    let frame_back = truth.rotation_from_z();
    let azimuth: f64 = rng.random_range(0.0..std::f64::consts::TAU);
    let turn_axis = Unit::new_normalize(frame_back * Vector::new(azimuth.cos(), azimuth.sin(), 0.0));
    let direction = UnitQuaternion::from_axis_angle(&turn_axis, 3f64.to_radians()) * truth.direction.into_inner();
    let shift_azimuth: f64 = rng.random_range(0.0..std::f64::consts::TAU);
    let shift = frame_back * Vector::new(shift_azimuth.cos(), shift_azimuth.sin(), 0.0) * 2.0;
    Axis::new(truth.point + shift, direction)
}
fn main() {
    let seeds: Vec<u64> = std::env::args().skip(1).map(|a| a.parse().unwrap()).collect();
    for seed in seeds {
        let vessel = generate_vessel(seed / 1000, &VesselOptions { fragment_count: 34, random_motion: true,
            deformation_scale: env_number("D", 1.0), noise_mm: env_number("N", 0.02), ..Default::default() });
        let sherd = &vessel.fragments[(seed % 1000) as usize];
        let truth = &sherd.truth.axis;
        let start = perturbed(truth, seed);
        let r = refine(&sherd.mesh, &start, &RefineOptions { criterion: Criterion::Circles, ..Default::default() }).unwrap();
        let surface = sherd::refine::sections::PreparedSurface::new(&sherd.mesh, &start, sherd::refine::Surface::Both, None).unwrap();
        let circles = sherd::refine::circles::CirclesObjective::new(&surface);
        let a = surface.parameters_of(&r.axis);
        let b = surface.parameters_of(truth);
        println!("seed {seed} sections {} result angle {:.3} iterations {}", surface.section_heights_mm.len(), r.axis.line_angle_to_deg(truth), r.report.iterations);
        let mut line = String::new();
        for k in 0..=20 {
            let t = k as f64 / 20.0;
            let p = [0, 1, 2, 3].map(|i| a[i] + t * (b[i] - a[i]));
            line += &format!("{:.3e} ", circles.value(&p));
        }
        println!("  result->truth: {line}");
    }
}
// residual histogram helper appended
