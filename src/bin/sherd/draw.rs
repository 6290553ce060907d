//! `sherd draw SCAN [--axis FILE.json] --style ... -o out.svg|.eps|.pdf|.png`: the
//! archaeological illustration.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use sherd::draw::{Drawing, Format};

use crate::common::{analyse_or_read_axis, AnalysisArgs, DrawingArgs};

#[derive(Args, Debug)]
#[command(
    about = "Draw a sherd as an archaeological illustration (section left of the axis, exterior right)",
    after_help = "Examples:\n  sherd draw A011.ply -o A011.svg\n  sherd draw A011.ply --style linear,occlusion,stipple -o A011.pdf --scale 2   # 1:2\n  sherd draw A011.ply --style colour,light -o A011.png --dpi 600\n  sherd orient A011.ply --json > axis.json && sherd draw A011.ply --axis axis.json -o A011.eps\n  sherd draw A011.ply -o A011.svg --json    # also prints the axis and measurements\n  sherd draw A011.ply -o A011.pdf --placement true-distance --section-fill hatched --title A011\n\n\
Styles combine: linear (outlines), colour (vertex colours or texture), light\n\
(directional), occlusion (ambient occlusion), stipple (dots), regularity (distance to\n\
the ideal vessel, with a legend); the default, light,occlusion, is the library's.\n\
The layout: --placement beside|true-distance, --section-fill black|hatched,\n\
--interior-view true|false, --prolongation true|false, --title TEXT, --section-angle DEG,\n\
--annotations height,wall_thickness,capacity|all|none (measurements under the drawing)\n\
(the names of the C ABI's and Python's options). The output's extension picks the format:\n\
.svg, .eps, .pdf or .png. An --axis file from `sherd orient --json` records the scan it was\n\
found on; an axis of another scan is refused."
)]
pub struct DrawArgs {
    /// The scan: .ply, .obj, .stl, .xyz or .pts.
    pub scan: PathBuf,
    /// An axis from `sherd orient --json` instead of orienting again.
    #[arg(long, value_name = "FILE.json")]
    pub axis: Option<PathBuf>,
    /// Output file: .svg, .eps, .pdf or .png.
    #[arg(short, long)]
    pub output: PathBuf,
    #[command(flatten)]
    pub drawing: DrawingArgs,
    #[command(flatten)]
    pub analysis: AnalysisArgs,
    /// Print one JSON object on stdout: the orientation and measurements (as `sherd
    /// orient --json`), the axis file used, and the files written.
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: DrawArgs) -> Result<ExitCode, String> {
    // Bad arguments are refused before the scan is read and oriented.
    Format::from_path(&args.output).map_err(|e| e.to_string())?;
    let draw_options = args.drawing.draw_options()?;
    let mut oriented = analyse_or_read_axis(&args.scan, args.axis.as_deref(), &args.analysis)?;
    let draw_options = sherd::draw::DrawOptions { measurements: oriented.measurements.take(), ..draw_options };
    let drawing = Drawing::build(&oriented.mesh, &oriented.axis, &draw_options).map_err(|e| e.to_string())?;
    drawing.write(&args.output).map_err(|e| e.to_string())?;
    if args.json {
        if let Some(record) = &mut oriented.record {
            record.drawing = Some(args.output.display().to_string());
        }
        println!("{}", oriented.json(&args.scan, args.axis.as_deref(), &[&args.output]));
    }
    Ok(ExitCode::SUCCESS)
}
