//! `sherd export SCAN [--axis FILE.json] --oriented out.ply | --reconstruction out.ply |
//! --profile out.csv | --regularity out.ply`: the oriented model, the vessel revolved from
//! the profile, the profile itself, and the regularity map as vertex colours and quality.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use sherd::mesh::io::{write_ply, PlyEncoding};
use sherd::profile::regularity::{ideal_vessel_map, regularity_mesh};
use sherd::profile::revolve::{oriented_mesh, revolve_profile};
use sherd::profile::section::{most_informative_angle, profile_section};

use crate::common::{analyse_or_read_axis, AnalysisArgs};

/// Segments around the axis of the reconstruction by revolution.
const REVOLUTION_SEGMENTS: usize = 180;

#[derive(Args, Debug)]
#[command(
    about = "Write the oriented model, the reconstruction by revolution, the profile or the regularity map",
    after_help = "Examples:\n  sherd export A011.ply --oriented A011.oriented.ply\n  sherd export A011.ply --reconstruction vessel.ply --profile profile.csv\n  sherd orient A011.ply --json > axis.json && sherd export A011.ply --axis axis.json --regularity regularity.ply\n  sherd export A011.ply --oriented o.ply --json    # also prints the axis and measurements\n\n\
The oriented model has the axis on z, rim up, in millimetres. The profile CSV has the\n\
columns curve,index,r_mm,z_mm,closed: one row per point of each curve of the section\n\
through the axis (curve number, point number along it, radius and height in mm, and\n\
whether the curve is a closed loop)."
)]
pub struct ExportArgs {
    /// The scan: .ply, .obj, .stl, .xyz or .pts.
    pub scan: PathBuf,
    /// An axis from `sherd orient --json` instead of orienting again.
    #[arg(long, value_name = "FILE.json")]
    pub axis: Option<PathBuf>,
    /// The model with the axis on z, rim up (PLY).
    #[arg(long, value_name = "OUT.ply")]
    pub oriented: Option<PathBuf>,
    /// The whole vessel revolved from the profile (PLY, watertight).
    #[arg(long, value_name = "OUT.ply")]
    pub reconstruction: Option<PathBuf>,
    /// The profile section through the axis (CSV: curve,index,r_mm,z_mm,closed).
    #[arg(long, value_name = "OUT.csv")]
    pub profile: Option<PathBuf>,
    /// Distance to the ideal vessel as vertex quality and colours (PLY, oriented).
    #[arg(long, value_name = "OUT.ply")]
    pub regularity: Option<PathBuf>,
    /// Write PLY as ASCII instead of binary.
    #[arg(long)]
    pub ascii: bool,
    #[command(flatten)]
    pub analysis: AnalysisArgs,
    /// Print one JSON object on stdout: the orientation and measurements (as `sherd
    /// orient --json`), the axis file used, and the files written.
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: ExportArgs) -> Result<ExitCode, String> {
    if args.oriented.is_none() && args.reconstruction.is_none() && args.profile.is_none() && args.regularity.is_none() {
        return Err("nothing to export: give --oriented, --reconstruction, --profile or --regularity".into());
    }
    let oriented = analyse_or_read_axis(&args.scan, args.axis.as_deref(), &args.analysis)?;
    let (mesh, axis) = (&oriented.mesh, &oriented.axis);
    let encoding = if args.ascii { PlyEncoding::Ascii } else { PlyEncoding::BinaryLittleEndian };
    let section = profile_section(mesh, axis, most_informative_angle(mesh, axis));
    if let Some(path) = &args.oriented {
        write_ply(path, &oriented_mesh(mesh, axis), encoding).map_err(|e| e.to_string())?;
    }
    if let Some(path) = &args.reconstruction {
        let vessel = revolve_profile(&section, REVOLUTION_SEGMENTS).map_err(|e| e.to_string())?;
        write_ply(path, &vessel, encoding).map_err(|e| e.to_string())?;
    }
    if let Some(path) = &args.profile {
        section.write_csv(path).map_err(|e| e.to_string())?;
    }
    if let Some(path) = &args.regularity {
        let (distances, map) = ideal_vessel_map(mesh, axis, &section).map_err(|e| e.to_string())?;
        let coloured = regularity_mesh(&oriented_mesh(mesh, axis), &distances, &map).map_err(|e| e.to_string())?;
        write_ply(path, &coloured, encoding).map_err(|e| e.to_string())?;
    }
    if args.json {
        let written: Vec<&std::path::Path> =
            [&args.oriented, &args.reconstruction, &args.profile, &args.regularity].into_iter().flatten().map(|p| p.as_path()).collect();
        println!("{}", oriented.json(&args.scan, args.axis.as_deref(), &written));
    }
    Ok(ExitCode::SUCCESS)
}
