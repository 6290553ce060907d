//! `sherd demo`: the README's main job. A synthetic sherd with a known axis is made,
//! oriented, measured and drawn, and what sherd found is printed beside the truth.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use sherd::draw::Drawing;
use sherd::mesh::io::{write_ply, PlyEncoding};
use sherd::pipeline::{self, SherdRecord};
use sherd::synth::{synthetic_sherd, SherdOptions, SherdPart};

use crate::common::{describe, AnalysisArgs, DrawingArgs};

#[derive(Args, Debug)]
#[command(
    about = "Make a synthetic rim sherd, orient, measure and draw it: sherd in one minute",
    after_help = "Examples:\n  sherd demo                     # demo.ply, demo.svg, demo.png in the current folder\n  sherd demo -o out/ --seed 12 --style linear,occlusion\n\n\
The scan is written as demo.ply so that you can open it in MeshLab or Blender, and\n\
run the other commands on it: sherd orient demo.ply --json"
)]
pub struct DemoArgs {
    /// Folder for demo.ply, demo.truth.json, demo.svg and demo.png.
    #[arg(short, long, default_value = ".")]
    pub output: PathBuf,
    /// Seed of the synthetic sherd.
    #[arg(long, default_value_t = 13)]
    pub seed: u64,
    /// Triangles of the synthetic scan.
    #[arg(long, default_value_t = 200_000)]
    pub faces: usize,
    #[command(flatten)]
    pub analysis: AnalysisArgs,
    #[command(flatten)]
    pub drawing: DrawingArgs,
}

pub fn run(args: DemoArgs) -> Result<ExitCode, String> {
    std::fs::create_dir_all(&args.output).map_err(|e| format!("{}: {e}", args.output.display()))?;
    let options = SherdOptions { target_faces: args.faces, part: Some(SherdPart::Rim), noise_mm: 0.01, ..Default::default() };
    let sherd = synthetic_sherd(args.seed, &options);
    let scan = args.output.join("demo.ply");
    write_ply(&scan, &sherd.mesh, PlyEncoding::BinaryLittleEndian).map_err(|e| e.to_string())?;
    let truth_json = serde_json::to_vec_pretty(&sherd.truth).map_err(|e| e.to_string())?;
    sherd::mesh::atomic::write_bytes_atomically(&args.output.join("demo.truth.json"), &truth_json)
        .map_err(|e| e.to_string())?;
    println!(
        "made a synthetic rim sherd: {} vertices, {} faces, rim diameter {:.1} mm, sector {:.1} deg -> {}",
        sherd.mesh.vertex_count(),
        sherd.mesh.face_count(),
        2.0 * sherd.truth.rim_radius_mm.unwrap_or(f64::NAN),
        sherd.truth.sector_angle_deg,
        scan.display()
    );

    let pipeline_options = args.analysis.pipeline_options()?;
    let analysis = pipeline::analyse(sherd.mesh.clone(), &pipeline_options).map_err(|e| e.to_string())?;
    let mut record = SherdRecord::from_analysis(scan.display().to_string(), &analysis, 1.0);
    if analysis.is_oriented() {
        let axis = analysis.axis();
        println!(
            "axis error: {:.2} deg, mean point distance {:.2} mm (the paper's measure)",
            axis.angle_to_deg(&sherd.truth.axis),
            sherd::orient::mean_point_distance_mm(&sherd.mesh.positions, axis, &sherd.truth.axis)
        );
        let draw_options = args.drawing.draw_options()?;
        let drawing = Drawing::build(&analysis.mesh, axis, &draw_options).map_err(|e| e.to_string())?;
        for extension in ["svg", "png"] {
            let path = args.output.join(format!("demo.{extension}"));
            drawing.write(&path).map_err(|e| e.to_string())?;
        }
        record.drawing = Some(args.output.join("demo.svg").display().to_string());
    }
    print!("{}", describe(&record));
    Ok(ExitCode::SUCCESS)
}
