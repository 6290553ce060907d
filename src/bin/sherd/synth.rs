//! `sherd synth -o DIR [--count N] [--seed S] [--faces F] [--part P | --hard-case H]
//! [--vessel]`: synthetic sherds with known axes as `NAME.ply` + `NAME.truth.json`, the
//! test bed for orientation and drawing (one file pair per sherd or per fragment).

use std::path::PathBuf;

use rayon::prelude::*;
use sherd::synth::{
    generate_vessel, synthetic_sherd, write_sherd, HardCase, SherdOptions, SherdPart, SynthSherd, VesselOptions, VesselShape,
};
use sherd::{Error, Result};

/// Arguments of `sherd synth`.
#[derive(clap::Args)]
pub struct SynthArgs {
    /// Output folder (created when missing).
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// Number of sherds (sherd i uses seed S + i).
    #[arg(long, default_value_t = 1)]
    pub count: u64,
    /// First seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Approximate number of triangles per sherd.
    #[arg(long, default_value_t = 20_000)]
    pub faces: usize,
    /// Part of the vessel: rim, body, base, rim_to_base or flat (random when absent).
    #[arg(long)]
    pub part: Option<SherdPart>,
    /// A fragment orientation must refuse: flat_base, near_spherical or tiny.
    #[arg(long, conflicts_with = "part")]
    pub hard_case: Option<HardCase>,
    /// Vessel family: bowl, carinated_bowl, jar, plate, beaker or globular (random when absent).
    #[arg(long)]
    pub shape: Option<VesselShape>,
    /// Standard deviation of the noise on every coordinate, mm.
    #[arg(long, default_value_t = 0.02)]
    pub noise_mm: f64,
    /// Circumference angle range of the sherds, degrees, as LOW,HIGH.
    #[arg(long, value_delimiter = ',', num_args = 2, default_values_t = [15.0, 60.0])]
    pub sector_deg: Vec<f64>,
    /// No ovality, rim tilt or wobble: an ideal surface of revolution.
    #[arg(long)]
    pub ideal: bool,
    /// Leave the sherds in the vessel frame (axis on z, standing plane z = 0) instead of
    /// moving each by a random rigid motion.
    #[arg(long)]
    pub no_motion: bool,
    /// Break whole vessels instead: every fragment of COUNT vessels (--faces is then
    /// ignored; --cell-mm sets the resolution).
    #[arg(long, conflicts_with_all = ["part", "hard_case"])]
    pub vessel: bool,
    /// Fragments per vessel with --vessel.
    #[arg(long, default_value_t = 24)]
    pub fragments: usize,
    /// Mesh cell size with --vessel, mm.
    #[arg(long, default_value_t = 2.0)]
    pub cell_mm: f64,
}

pub fn run(arguments: &SynthArgs) -> Result<()> {
    check(arguments)?;
    std::fs::create_dir_all(&arguments.output).map_err(|e| Error::io(&arguments.output, e))?;
    let seeds: Vec<u64> = (0..arguments.count).map(|i| arguments.seed.wrapping_add(i)).collect();
    let written: Vec<Vec<String>> = seeds
        .par_iter()
        .map(|&seed| -> Result<Vec<String>> {
            let sherds: Vec<SynthSherd> = if arguments.vessel {
                let options = VesselOptions {
                    shape: arguments.shape,
                    fragment_count: arguments.fragments,
                    cell_size_mm: arguments.cell_mm,
                    noise_mm: arguments.noise_mm,
                    deformation_scale: if arguments.ideal { 0.0 } else { 1.0 },
                    random_motion: !arguments.no_motion,
                    ..Default::default()
                };
                generate_vessel(seed, &options).fragments
            } else {
                let options = SherdOptions {
                    target_faces: arguments.faces,
                    noise_mm: arguments.noise_mm,
                    part: arguments.part,
                    sector_deg: [arguments.sector_deg[0], arguments.sector_deg[1]],
                    shape: arguments.shape,
                    deformation_scale: if arguments.ideal { 0.0 } else { 1.0 },
                    random_motion: !arguments.no_motion,
                    hard_case: arguments.hard_case,
                    ..Default::default()
                };
                vec![synthetic_sherd(seed, &options)]
            };
            sherds.iter().map(|sherd| Ok(line(&write_sherd(&arguments.output, sherd)?, sherd))).collect()
        })
        .collect::<Result<_>>()?;
    for line in written.iter().flatten() {
        println!("{line}");
    }
    Ok(())
}

fn check(arguments: &SynthArgs) -> Result<()> {
    let invalid = |message: String| Err(Error::InvalidArgument(message));
    if arguments.count == 0 {
        return invalid("--count must be at least 1".into());
    }
    if arguments.faces < 100 {
        return invalid(format!("--faces {} is too few for a closed sherd: give at least 100", arguments.faces));
    }
    if arguments.faces > sherd::synth::MAX_TARGET_FACES {
        return invalid(format!("--faces {} is too many: give at most {}", arguments.faces, sherd::synth::MAX_TARGET_FACES));
    }
    if !(arguments.noise_mm >= 0.0 && arguments.noise_mm.is_finite()) {
        return invalid(format!("--noise-mm {} must be a finite number >= 0", arguments.noise_mm));
    }
    let [low, high] = [arguments.sector_deg[0], arguments.sector_deg[1]];
    if !(low > 0.0 && low <= high && high <= 360.0) {
        return invalid(format!("--sector-deg {low},{high} must satisfy 0 < LOW <= HIGH <= 360"));
    }
    if arguments.vessel && !(arguments.cell_mm >= 0.1 && arguments.cell_mm.is_finite()) {
        return invalid(format!("--cell-mm {} must be at least 0.1", arguments.cell_mm));
    }
    if arguments.vessel && arguments.fragments < 2 {
        return invalid(format!("--fragments {} must be at least 2", arguments.fragments));
    }
    Ok(())
}

/// One line per written sherd: path, part, faces, sector, rim radius.
fn line(path: &std::path::Path, sherd: &SynthSherd) -> String {
    let truth = &sherd.truth;
    let rim = truth.rim_radius_mm.map_or("-".to_string(), |r| format!("{r:.1}"));
    format!(
        "{}\t{}\t{} faces\tsector {:.1} deg\trim radius {rim} mm",
        path.display(),
        truth.part.name(),
        sherd.mesh.face_count(),
        truth.sector_angle_deg
    )
}
