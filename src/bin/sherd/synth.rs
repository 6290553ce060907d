//! `sherd synth OUTDIR [--seed S] [--count N]`: synthetic sherds with known axes as
//! `NAME.ply` + `NAME.truth.json`, the test bed for orientation and drawing. By default a
//! whole vessel is broken into 20-40 fragments, as a dropped pot is; `--part`,
//! `--hard-case` or `--faces` ask for one sherd per seed instead. `-o OUTDIR` is the
//! same as the positional folder.

use std::path::{Path, PathBuf};

use rand::{RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use sherd::synth::{
    generate_vessel, synthetic_sherd, write_sherd, BaseForm, HardCase, ProfileForms, RimForm, SherdOptions, SherdPart, SynthSherd,
    VesselOptions, VesselShape,
};
use sherd::{Error, Result};

/// Fewest and most fragments a vessel is broken into by default.
const DEFAULT_FRAGMENTS: [usize; 2] = [20, 40];
/// Triangles of a single sherd when `--part` or `--hard-case` is given without `--faces`.
const DEFAULT_SHERD_FACES: usize = 20_000;

/// Arguments of `sherd synth`.
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  sherd synth out/                          # one vessel broken into 20-40 fragments, seed 1\n  sherd synth out/ --seed 7 --count 3       # three vessels (seeds 7, 8, 9)\n  sherd synth out/ --fragments 30 --cell-mm 1\n  sherd synth out/ --part rim --faces 200000 --seed 13   # one rim sherd per seed\n  sherd synth out/ --lip-forms flat,rounded,thickened --base-forms flat,ring_foot\n  sherd synth -o out/ --hard-case flat_base     # a piece orientation must refuse\n\n\
Each sherd is NAME.ply (moved by a random rigid motion unless --no-motion) beside\n\
NAME.truth.json: the axis point and direction in the file's frame, rim radius, sector\n\
angle and part. The same seed and options give the same files."
)]
#[command(group = clap::ArgGroup::new("folder").required(true).args(["outdir", "output"]))]
pub struct SynthArgs {
    /// Output folder (created when missing).
    #[arg(value_name = "OUTDIR")]
    pub outdir: Option<PathBuf>,
    /// Output folder, as an option (the same as OUTDIR).
    #[arg(short = 'o', long = "output", value_name = "OUTDIR")]
    pub output: Option<PathBuf>,
    /// Number of vessels, or of single sherds (number i uses seed S + i).
    #[arg(long, default_value_t = 1)]
    pub count: u64,
    /// First seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// One sherd per seed of about this many triangles, instead of a broken vessel
    /// (20000 when --part or --hard-case is given alone).
    #[arg(long)]
    pub faces: Option<usize>,
    /// One sherd per seed from this part of the vessel: rim, body, base, rim_to_base or
    /// flat (instead of a broken vessel).
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
    /// Standard deviation of the surface's relief, mm: a slow undulation along the
    /// normals, neighbouring vertices moving together (hand finishing), 0 for none.
    #[arg(long, default_value_t = 0.0)]
    pub relief_mm: f64,
    /// Typical distance between the relief's crests, mm.
    #[arg(long, default_value_t = 6.0)]
    pub relief_wavelength_mm: f64,
    /// Circumference angle range of the sherds, degrees, as LOW,HIGH.
    #[arg(long, value_delimiter = ',', num_args = 2, default_values_t = [15.0, 60.0])]
    pub sector_deg: Vec<f64>,
    /// No ovality, rim tilt or wobble: an ideal surface of revolution.
    #[arg(long, conflicts_with = "deformation")]
    pub ideal: bool,
    /// Size of the ovality, rim tilt and wobble: 1 is a carefully thrown vessel (rim
    /// ovality up to 0.6%, rim tilt up to 0.3 degrees), 3 a roughly thrown one, 0 none.
    #[arg(long, default_value_t = 1.0)]
    pub deformation: f64,
    /// Leave the sherds in the vessel frame (axis on z, standing plane z = 0) instead of
    /// moving each by a random rigid motion.
    #[arg(long)]
    pub no_motion: bool,
    /// Break whole vessels (the default; kept so that scripts can say so).
    #[arg(long, conflicts_with_all = ["part", "hard_case", "faces"])]
    pub vessel: bool,
    /// Voronoi seeds per vessel (fragments; a sliver too small to keep is dropped).
    /// Drawn from 20 to 40 with the seed when absent.
    #[arg(long, conflicts_with_all = ["part", "hard_case", "faces"])]
    pub fragments: Option<usize>,
    /// Lip forms the vessels are drawn from, comma-separated: flat, rounded, thickened
    /// (a bead outside, below the top).
    #[arg(long, value_delimiter = ',', default_value = "flat,rounded")]
    pub lip_forms: Vec<RimForm>,
    /// Base forms the vessels are drawn from, comma-separated: flat, ring_foot.
    #[arg(long, value_delimiter = ',', default_value = "flat")]
    pub base_forms: Vec<BaseForm>,
    /// Mesh cell size of a broken vessel, mm (each cell gives four triangles per skin).
    #[arg(long, default_value_t = 2.0, conflicts_with_all = ["part", "hard_case", "faces"])]
    pub cell_mm: f64,
}

impl SynthArgs {
    /// The lip and base forms asked for.
    fn forms(&self) -> ProfileForms {
        ProfileForms { lips: self.lip_forms.clone(), bases: self.base_forms.clone() }
    }

    /// The output folder, positional or `-o`.
    fn folder(&self) -> &Path {
        self.outdir.as_deref().or(self.output.as_deref()).expect("clap requires OUTDIR or -o")
    }

    /// True for whole vessels broken into fragments, false for one sherd per seed.
    fn relief(&self) -> sherd::synth::Relief {
        sherd::synth::Relief { amplitude_mm: self.relief_mm, wavelength_mm: self.relief_wavelength_mm }
    }

    fn breaks_vessels(&self) -> bool {
        self.part.is_none() && self.hard_case.is_none() && self.faces.is_none()
    }

    /// The number of fragments of the vessel of `seed`.
    fn fragment_count(&self, seed: u64) -> usize {
        self.fragments.unwrap_or_else(|| {
            let [fewest, most] = DEFAULT_FRAGMENTS;
            fewest + (ChaCha8Rng::seed_from_u64(seed ^ FRAGMENT_COUNT_STREAM).next_u64() % (most - fewest + 1) as u64) as usize
        })
    }
}

/// Mixed into the seed when drawing the default fragment count, so the count does not
/// share its random stream with the vessel itself.
const FRAGMENT_COUNT_STREAM: u64 = 0x5eed_f4a9_0c0f_4a7e;

pub fn run(arguments: &SynthArgs) -> Result<()> {
    check(arguments)?;
    let folder = arguments.folder();
    std::fs::create_dir_all(folder).map_err(|e| Error::io(folder, e))?;
    let seeds: Vec<u64> = (0..arguments.count).map(|i| arguments.seed.wrapping_add(i)).collect();
    let written: Vec<Vec<String>> = seeds
        .par_iter()
        .map(|&seed| -> Result<Vec<String>> {
            let sherds: Vec<SynthSherd> = if arguments.breaks_vessels() {
                let options = VesselOptions {
                    shape: arguments.shape,
                    fragment_count: arguments.fragment_count(seed),
                    cell_size_mm: arguments.cell_mm,
                    noise_mm: arguments.noise_mm,
                    relief: arguments.relief(),
                    deformation_scale: if arguments.ideal { 0.0 } else { arguments.deformation },
                    random_motion: !arguments.no_motion,
                    forms: arguments.forms(),
                    ..Default::default()
                };
                generate_vessel(seed, &options).fragments
            } else {
                let options = SherdOptions {
                    target_faces: arguments.faces.unwrap_or(DEFAULT_SHERD_FACES),
                    noise_mm: arguments.noise_mm,
                    relief: arguments.relief(),
                    part: arguments.part,
                    sector_deg: [arguments.sector_deg[0], arguments.sector_deg[1]],
                    shape: arguments.shape,
                    deformation_scale: if arguments.ideal { 0.0 } else { arguments.deformation },
                    random_motion: !arguments.no_motion,
                    hard_case: arguments.hard_case,
                    forms: arguments.forms(),
                    ..Default::default()
                };
                vec![synthetic_sherd(seed, &options)]
            };
            sherds.iter().map(|sherd| Ok(line(&write_sherd(folder, sherd)?, sherd))).collect()
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
    if let Some(faces) = arguments.faces {
        if faces < 100 {
            return invalid(format!("--faces {faces} is too few for a closed sherd: give at least 100"));
        }
        if faces > sherd::synth::MAX_TARGET_FACES {
            return invalid(format!("--faces {faces} is too many: give at most {}", sherd::synth::MAX_TARGET_FACES));
        }
    }
    if !(arguments.noise_mm >= 0.0 && arguments.noise_mm.is_finite()) {
        return invalid(format!("--noise-mm {} must be a finite number >= 0", arguments.noise_mm));
    }
    if !(arguments.relief_mm >= 0.0 && arguments.relief_mm.is_finite()) {
        return invalid(format!("--relief-mm {} must be a finite number >= 0", arguments.relief_mm));
    }
    if !(arguments.relief_wavelength_mm > 0.0 && arguments.relief_wavelength_mm.is_finite()) {
        return invalid(format!("--relief-wavelength-mm {} must be a finite number > 0", arguments.relief_wavelength_mm));
    }
    if !(arguments.deformation >= 0.0 && arguments.deformation <= 10.0) {
        return invalid(format!("--deformation {} must be a number from 0 to 10", arguments.deformation));
    }
    let [low, high] = [arguments.sector_deg[0], arguments.sector_deg[1]];
    if !(low > 0.0 && low <= high && high <= 360.0) {
        return invalid(format!("--sector-deg {low},{high} must satisfy 0 < LOW <= HIGH <= 360"));
    }
    if !(arguments.cell_mm >= 0.1 && arguments.cell_mm.is_finite()) {
        return invalid(format!("--cell-mm {} must be at least 0.1", arguments.cell_mm));
    }
    if let Some(fragments) = arguments.fragments
        && fragments < 2
    {
        return invalid(format!("--fragments {fragments} must be at least 2"));
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
