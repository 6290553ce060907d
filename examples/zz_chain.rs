use nalgebra::{Unit, UnitQuaternion};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use sherd::mesh::Vector;
use sherd::orient::{mean_point_distance_mm, Axis};
use sherd::refine::{refine, Criterion, RefineOptions};
use sherd::synth::{generate_vessel, VesselOptions, SherdPart};
fn env_number(name: &str, default: f64) -> f64 { std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default) }
fn perturbed(truth: &Axis, seed: u64) -> Axis {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5eed);
    let frame_back = truth.rotation_from_z();
    let azimuth: f64 = rng.random_range(0.0..std::f64::consts::TAU);
    let turn_axis = Unit::new_normalize(frame_back * Vector::new(azimuth.cos(), azimuth.sin(), 0.0));
    let direction = UnitQuaternion::from_axis_angle(&turn_axis, env_number("T", 3.0).to_radians()) * truth.direction.into_inner();
    let shift_azimuth: f64 = rng.random_range(0.0..std::f64::consts::TAU);
    let shift = frame_back * Vector::new(shift_azimuth.cos(), shift_azimuth.sin(), 0.0) * 2.0;
    Axis::new(truth.point + shift, direction)
}
fn median(mut v: Vec<f64>) -> f64 { v.sort_by(f64::total_cmp); if v.is_empty() { f64::NAN } else { v[v.len() / 2] } }
fn main() {
    let bound = env_number("B", 2.0);
    let sherds: Vec<_> = (0..10u64).flat_map(|seed| {
        let vessel = generate_vessel(seed, &VesselOptions { fragment_count: 34, random_motion: true,
            deformation_scale: env_number("D", 1.0), noise_mm: env_number("N", 0.02), ..Default::default() });
        vessel.fragments.into_iter().enumerate().map(move |(i, f)| (seed * 1000 + i as u64, f))
    }).filter(|(_, s)| s.truth.hard_case.is_none()).collect();
    let rows: Vec<(SherdPart, f64, f64, f64, f64, f64, f64, usize)> = sherds.par_iter().filter_map(|(seed, s)| {
        let truth = &s.truth.axis;
        let start = perturbed(truth, *seed);
        let a = refine(&s.mesh, &start, &RefineOptions { criterion: Criterion::Auto, ..Default::default() }).ok()?;
        let b = refine(&s.mesh, &a.axis, &RefineOptions { criterion: Criterion::Profile, search_bound_deg: bound, ..Default::default() }).ok();
        let b_axis = b.as_ref().map_or(a.axis, |b| b.axis);
        let d = |x: &Axis| mean_point_distance_mm(&s.mesh.positions, x, truth);
        Some((s.truth.part, a.axis.line_angle_to_deg(truth), d(&a.axis), b_axis.line_angle_to_deg(truth), d(&b_axis), 0.0, 0.0, s.mesh.vertex_count()))
    }).collect();
    for part in [SherdPart::Rim, SherdPart::Body, SherdPart::Base, SherdPart::RimToBase] {
        let r: Vec<_> = rows.iter().filter(|r| r.0 == part).collect();
        let n = r.len();
        println!("{part:?} n {n} verts median {} | auto median {:.3} within4 {} | +profile median {:.3} within4 {}", median(r.iter().map(|x| x.7 as f64).collect()),
            median(r.iter().map(|x| x.1).collect()), r.iter().filter(|x| x.2 <= 4.0).count(),
            median(r.iter().map(|x| x.3).collect()), r.iter().filter(|x| x.4 <= 4.0).count());
    }
    println!("all: auto {:.3} {} | +profile {:.3} {}", median(rows.iter().map(|x| x.1).collect()), rows.iter().filter(|x| x.2 <= 4.0).count(), median(rows.iter().map(|x| x.3).collect()), rows.iter().filter(|x| x.4 <= 4.0).count());
}
