//! `sherd orient SCAN [--manual ...] [--refine ...] [--surface ...] [--json]
//! [--pareto-plot FRONT.svg]`: the axis, the rim radius, the sector and how far to trust
//! them.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use sherd::mesh::atomic::write_bytes_atomically;
use sherd::pipeline::{self, RecordStatus, SherdRecord};
use sherd::refine::Criterion;

use crate::common::{AnalysisArgs, RefineChoice};

#[derive(Args, Debug)]
#[command(
    about = "Find the rotation axis of the vessel a sherd came from, and measure it",
    after_help = "Examples:\n  sherd orient A011.ply\n  sherd orient A011.ply --json > A011.axis.json\n  sherd orient A011.ply --refine tangent --surface outer\n  sherd orient body.ply --manual \"10,2,40;-31,5,38;4,-28,41\"   # three points on a rill\n\n\
The axis is given in the scan's own frame and units, pointing from base to rim.\n\
A sherd whose shape does not determine an axis (flat, near spherical, too small) is\n\
reported as needs_manual_orientation with the reason, the axis its search found as a\n\
best guess not to be trusted (\"best_guess\" in the JSON: --axis of draw and export\n\
takes that object) and, where wheel rills are traced on it, three points on the\n\
longest for --manual; one whose axis line is found but not which way is up (no level\n\
rim, no floor, a wall that hardly flares) as sense_uncertain, still refined and\n\
measured; one whose axis is found but not pinned down (the 95% interval of its\n\
direction or of its position is wide) as axis_uncertain, with the reason: check it\n\
before using its figures. The exit code is 0 for all three. The rills' slope under\n\
the axis (0 when it puts them horizontal) is printed when any are traced."
)]
pub struct OrientArgs {
    /// The scan: .ply, .obj, .stl, .xyz or .pts.
    pub scan: PathBuf,
    #[command(flatten)]
    pub analysis: AnalysisArgs,
    /// Print one JSON object on stdout instead of text.
    #[arg(long)]
    pub json: bool,
    /// With `--refine pareto`: write the Pareto front (centre dispersion, Eq. 3, against
    /// circle residual, Eq. 4; the chosen solution circled in red) as an SVG plot.
    #[arg(long, value_name = "FRONT.svg")]
    pub pareto_plot: Option<PathBuf>,
}

pub fn run(args: OrientArgs) -> Result<ExitCode, String> {
    let options = args.analysis.pipeline_options()?;
    if args.pareto_plot.is_some() && args.analysis.refine != RefineChoice(Some(Criterion::Pareto)) {
        return Err("--pareto-plot draws the Pareto criterion's front: add --refine pareto".into());
    }
    let file = args.scan.display().to_string();
    let analysis = pipeline::analyse_file(&args.scan, &options);
    let record = match &analysis {
        Ok(analysis) => SherdRecord::from_analysis(file, analysis),
        Err(error) => SherdRecord::failed(file, error),
    };
    if record.status == RecordStatus::Error {
        return Err(record.error.unwrap_or_default());
    }
    if let (Some(path), Ok(analysis)) = (&args.pareto_plot, &analysis) {
        let Some(svg) = analysis.refinement.as_ref().and_then(|r| r.pareto_plot_svg()) else {
            return Err(format!(
                "{}: no Pareto front to plot: {}",
                args.scan.display(),
                record.reason.as_deref().unwrap_or("the refinement did not run")
            ));
        };
        write_bytes_atomically(path, svg.as_bytes()).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&record).map_err(|e| e.to_string())?);
    } else {
        print!("{}", crate::common::describe(&record));
    }
    Ok(ExitCode::SUCCESS)
}
