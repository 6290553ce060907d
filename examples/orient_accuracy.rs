//! Accuracy of the automatic pre-orientation, measured: on the real SfS++ sherds against
//! their reference axes and on the DACORD example A011.
//!
//! `cargo run --release --example orient_accuracy`

use std::path::{Path, PathBuf};

use sherd::mesh::io::read_mesh;
use sherd::mesh::{Mesh, Point, Vector};
use sherd::orient::{orient_automatic, Axis, OrientOptions, Orientation};

fn shared_data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data")
}

fn verdict_text(orientation: &Orientation) -> String {
    match &orientation.verdict {
        sherd::orient::Verdict::Oriented => "oriented".into(),
        sherd::orient::Verdict::NeedsManualOrientation { reason } => format!("NEEDS_MANUAL ({reason})"),
    }
}

/// The SfS++ pot C sherds: both skins' subsampled points with normals, against the
/// derived per-piece reference axis (known to about 3 deg / 2 mm).
fn real_sfspp(options: &OrientOptions) {
    let folder = shared_data().join("sfspp_pot_C");
    let reference_file = folder.join("ground_truth/reference_axis_derived.txt");
    let Ok(reference_text) = std::fs::read_to_string(&reference_file) else {
        println!("SKIP SfS++: {} absent", reference_file.display());
        return;
    };
    println!("\n## SfS++ pot C (reference A, per piece; tolerance of the reference ~3 deg / 2 mm)");
    println!("| piece | points | line angle deg | axis offset at sherd mm | verdict |");
    println!("|---|---|---|---|---|");
    for piece in 1..=4 {
        let name = format!("Pot_C_Piece_0{piece}");
        // The first block of per-piece lines is reference A.
        let Some(line) = reference_text.lines().find(|l| l.starts_with(&format!("{name} "))) else { continue };
        let values: Vec<f64> = line.split_whitespace().skip(1).filter_map(|t| t.parse().ok()).collect();
        let truth = Axis::new(Point::new(values[0], values[1], values[2]), Vector::new(values[3], values[4], values[5]));
        let mut positions = Vec::new();
        let mut normals = Vec::new();
        for surface in 0..2 {
            let pattern = format!("{name}_Surface_{surface}.");
            let Some(path) = std::fs::read_dir(folder.join("surfaces_subsample"))
                .ok()
                .and_then(|dir| dir.flatten().map(|e| e.path()).find(|p| p.to_string_lossy().contains(&pattern)))
            else {
                continue;
            };
            let mesh = read_mesh(&path).expect("SfS++ surface readable");
            positions.extend(mesh.positions.iter().copied());
            normals.extend(mesh.normals.expect("SfS++ surfaces carry normals"));
        }
        let cloud = Mesh::from_points_and_normals(positions, normals);
        match orient_automatic(&cloud, options) {
            Ok(orientation) => {
                let centroid = cloud.centroid().unwrap();
                let offset = truth.distance_to(&orientation.axis.closest_point(&centroid));
                println!(
                    "| {piece} | {} | {:.2} | {:.2} | {} |",
                    cloud.vertex_count(),
                    orientation.axis.line_angle_to_deg(&truth),
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

fn main() {
    let options = OrientOptions::default();
    real_sfspp(&options);
    real_a011(&options);
}
