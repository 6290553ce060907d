use rayon::prelude::*;
use sherd::mesh::Mesh;
use sherd::orient::{decimated_copy, mean_point_distance_mm, Axis, OrientOptions};
use sherd::pipeline::{analyse, PipelineOptions, SherdRecord};
use sherd::refine::uncertainty::{bootstrap_axes, BootstrapOptions};
use sherd::refine::RefineOptions;
use sherd::synth::{generate_vessel, VesselOptions};
fn row(name: String, mesh: &Mesh, truth: &Axis) -> Option<String> {
    let options = PipelineOptions { refine: Some(RefineOptions::default()), ..Default::default() };
    let a = analyse(mesh.clone(), &options).ok()?;
    let r = SherdRecord::from_analysis(name.clone(), &a);
    if !(r.status == "ok" || r.status == "axis_uncertain") { return None; }
    let copy = decimated_copy(&a.mesh, &OrientOptions::default()).ok()?.unwrap_or_else(|| a.mesh.clone());
    let reps = bootstrap_axes(&copy, a.axis(), &RefineOptions::default(), &BootstrapOptions::default()).ok()?;
    let mut d: Vec<f64> = reps.iter().map(|x| mean_point_distance_mm(&a.mesh.positions, x, a.axis())).collect();
    d.sort_by(f64::total_cmp);
    let q = if d.len() >= 5 { d[((d.len() - 1) as f64 * 0.95).round() as usize] * 2.5 } else { f64::NAN };
    let off = mean_point_distance_mm(&a.mesh.positions, a.axis(), truth);
    let refine_flag = a.refinement.as_ref().is_some_and(|x| x.report.flagged);
    let angle_upper = r.axis_angle_interval_deg.map_or(f64::NAN, |i| i[1]);
    Some(format!("ROW {name} {} off {off:.2} spread_upper {q:.2} refine_flag {refine_flag} angle_upper {angle_upper:.2} reps {}", r.status, d.len()))
}
fn main() {
    let mode = std::env::args().nth(1).unwrap_or("corpus".into());
    let rows: Vec<String> = if mode == "corpus" {
        let sherds: Vec<_> = (0..10u64).flat_map(|seed| {
            let vessel = generate_vessel(seed, &VesselOptions { fragment_count: 34, random_motion: true, ..Default::default() });
            vessel.fragments.into_iter().enumerate().map(move |(i, f)| (seed * 1000 + i as u64, f))
        }).filter(|(_, s)| s.truth.hard_case.is_none()).collect();
        sherds.par_iter().filter_map(|(seed, s)| row(seed.to_string(), &s.mesh, &s.truth.axis)).collect()
    } else {
        let files: Vec<_> = std::fs::read_dir(&mode).unwrap().filter_map(|e| e.ok()).map(|e| e.path()).filter(|p| p.extension().is_some_and(|x| x == "ply")).collect();
        files.iter().filter_map(|p| {
            let mesh = sherd::mesh::io::read_mesh(p).ok()?;
            let truth: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(p.with_extension("truth.json")).ok()?).ok()?;
            let v = |k: &str| { let a = &truth["axis"][k]; sherd::mesh::Vector::new(a[0].as_f64().unwrap(), a[1].as_f64().unwrap(), a[2].as_f64().unwrap()) };
            let axis = Axis::new(sherd::mesh::Point::from(v("point")), v("direction"));
            row(p.file_name().unwrap().to_string_lossy().into(), &mesh, &axis)
        }).collect()
    };
    for r in rows { println!("{r}"); }
}
