//! How noisy the working copy's normals are, per fragment of a `sherd synth` corpus: the
//! median and 90th percentile of their turn out of the meridian plane under the true axis
//! (0 on a perfect surface of revolution), the filter's passes, and the whole-sphere
//! search's mean loss at the true axis. Tuning corpora only (their `.truth.json` beside
//! each scan).
//! Run: `cargo run --release --example normal_noise -- DIR/vessel_500_fragment_003.ply ...`

use sherd::axis::Axis;
use sherd::mesh::io::read_mesh;
use sherd::mesh::{Point, Vector};
use sherd::orient::revolution_search::{point_losses, RevolutionSamples};
use sherd::orient::{decimated_copy, surface_of_revolution_lines, working_copy, OrientOptions};

fn main() {
    let options = OrientOptions::default();
    for path in std::env::args().skip(1) {
        let run = || -> Result<String, Box<dyn std::error::Error>> {
            let mesh = read_mesh(std::path::Path::new(&path))?;
            let truth: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(path.replace(".ply", ".truth.json"))?)?;
            let coordinate = |key: &str, i: usize| truth["axis"][key][i].as_f64().ok_or("the truth has no axis");
            let axis = Axis::new(
                Point::new(coordinate("point", 0)?, coordinate("point", 1)?, coordinate("point", 2)?),
                Vector::new(coordinate("direction", 0)?, coordinate("direction", 1)?, coordinate("direction", 2)?),
            );
            let decimated = decimated_copy(&mesh, &options)?;
            let working = working_copy(&mesh, decimated.as_ref(), &options)?;
            let normals = sherd::mesh::normals::compute_vertex_normals(&working, sherd::mesh::normals::NormalWeighting::Area);
            let passes = sherd::mesh::normal_filter::freed_of_roughness(&working, normals, &sherd::mesh::normals::vertex_areas(&working)).passes;
            let lines = surface_of_revolution_lines(&working, &options)?;
            let samples = RevolutionSamples::from_lines(&lines, options.search.final_points, options.search.band_spacings, options.search.min_band_mm)
                .ok_or("too few points on the surface of revolution")?;
            let losses = point_losses(&samples, &axis, options.search.loss_scale_bands * samples.band_mm);
            let d = axis.direction.into_inner();
            let mut turns: Vec<f64> = lines
                .points
                .iter()
                .zip(&lines.directions)
                .filter_map(|(p, n)| {
                    let q = p - axis.point;
                    Some(n.dot(&d.cross(&(q - d * q.dot(&d))).try_normalize(1e-9)?).abs())
                })
                .collect();
            turns.sort_by(f64::total_cmp);
            let mean_loss = losses.iter().sum::<f64>() / losses.len().max(1) as f64;
            Ok(format!(
                "{} working vertices, {passes} filter passes: normal out of the meridian plane median {:.3}, p90 {:.3}; mean loss at the true axis {mean_loss:.3}",
                working.vertex_count(),
                turns[turns.len() / 2],
                turns[turns.len() * 9 / 10]
            ))
        };
        match run() {
            Ok(line) => println!("{path}: {line}"),
            Err(error) => println!("{path}: {error}"),
        }
    }
}
