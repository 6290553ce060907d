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
    after_help = "Examples:\n  sherd demo                     # demo.ply, demo.svg, demo.png in the current folder\n  sherd demo -o out/ --seed 12 --style linear,occlusion\n  sherd demo -o out/ --json        # truth, what was found and the axis error as JSON\n\n\
The scan is written as demo.ply so that you can open it in MeshLab or Blender, and\n\
run the other commands on it: sherd orient demo.ply --json"
)]
pub struct DemoArgs {
    /// Folder for demo.ply, demo.truth.json, demo.svg and demo.png.
    #[arg(short, long, default_value = ".")]
    pub output: PathBuf,
    /// Seed of the synthetic sherd.
    #[arg(long, default_value_t = 6)]
    pub seed: u64,
    /// Triangles of the synthetic scan.
    #[arg(long, default_value_t = 200_000)]
    pub faces: usize,
    #[command(flatten)]
    pub analysis: AnalysisArgs,
    #[command(flatten)]
    pub drawing: DrawingArgs,
    /// Print one JSON object on stdout instead of text: the truth, what sherd found (as
    /// `sherd orient --json`), the axis error and the files written.
    #[arg(long)]
    pub json: bool,
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
    // With --json, stdout carries the one JSON object only.
    let say = |line: String| if !args.json { println!("{line}") };
    say(format!(
        "made a synthetic rim sherd: {} vertices, {} faces, rim diameter {:.1} mm, sector {:.1} deg -> {}",
        sherd.mesh.vertex_count(),
        sherd.mesh.face_count(),
        2.0 * sherd.truth.rim_radius_mm.unwrap_or(f64::NAN),
        sherd.truth.sector_angle_deg,
        scan.display()
    ));

    let pipeline_options = args.analysis.pipeline_options()?;
    let analysis = pipeline::analyse(sherd.mesh.clone(), &pipeline_options).map_err(|e| e.to_string())?;
    let mut record = SherdRecord::from_analysis(scan.display().to_string(), &analysis);
    let mut written = vec![scan.clone(), args.output.join("demo.truth.json")];
    let mut axis_error = None;
    if analysis.is_oriented() {
        let axis = analysis.axis();
        let error_deg = axis.angle_to_deg(&sherd.truth.axis);
        let distance_mm = sherd::orient::mean_point_distance_mm(&sherd.mesh.positions, axis, &sherd.truth.axis);
        axis_error = Some((error_deg, distance_mm));
        say(format!("axis error: {error_deg:.2} deg, mean point distance {distance_mm:.2} mm (the paper's measure)"));
        let draw_options = args.drawing.draw_options()?;
        let drawing = Drawing::build(&analysis.mesh, axis, &draw_options).map_err(|e| e.to_string())?;
        for extension in ["svg", "png"] {
            let path = args.output.join(format!("demo.{extension}"));
            drawing.write(&path).map_err(|e| e.to_string())?;
            written.push(path);
        }
        record.drawing = Some(args.output.join("demo.svg").display().to_string());
    }
    if args.json {
        let value = serde_json::json!({
            "truth": sherd.truth,
            "found": record,
            "axis_error_deg": axis_error.map(|(degrees, _)| degrees),
            "mean_point_distance_mm": axis_error.map(|(_, millimetres)| millimetres),
            "written": written.iter().map(|path| path.display().to_string()).collect::<Vec<_>>(),
        });
        println!("{}", serde_json::to_string_pretty(&value).map_err(|e| e.to_string())?);
    } else {
        print!("{}", describe(&record));
    }
    Ok(ExitCode::SUCCESS)
}
