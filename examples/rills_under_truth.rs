//! Wheel rills traced under the true axis, on folders of `NAME.ply` + `NAME.truth.json`
//! (`sherd synth`'s or the report corpus's). Neither generator cuts rills, so every groove
//! reported there is a false one: a profile's bend, or a chance chain of the surface's
//! relief. Per rill, its fragment, skin, strips, arc, depth, straightness, slope and
//! height; then the counts per folder.
//!
//! Run: `cargo run --release --example rills_under_truth FOLDER [FOLDER...]`.

use std::path::{Path, PathBuf};

use rayon::prelude::*;
use sherd::mesh::io::read_mesh;
use sherd::mesh::repair::{repair, RepairOptions};
use sherd::profile::rills::{trace_rills_under, Rill, RillOptions};

#[path = "../tests/support/evaluation.rs"]
mod evaluation;

/// A fragment's part and its rills under its true axis.
type Traced = (String, Vec<Rill>);

/// The rills of one fragment under its true axis, with its part; `None` when the scan or
/// its truth cannot be read.
fn rills_of(ply: &Path) -> Option<Traced> {
    let (axis, part) = evaluation::truth_of(ply)?;
    let mut mesh = read_mesh(ply).ok()?;
    repair(&mut mesh, &RepairOptions::default());
    Some((part, trace_rills_under(&mesh, &axis, &RillOptions::default())))
}

fn main() {
    let folders: Vec<PathBuf> = std::env::args().skip(1).map(PathBuf::from).collect();
    if folders.is_empty() {
        eprintln!("usage: rills_under_truth FOLDER [FOLDER...] (NAME.ply + NAME.truth.json)");
        std::process::exit(2);
    }
    for folder in folders {
        let Ok(plys) = evaluation::fragments_with_truth(&folder) else {
            eprintln!("{}: cannot read the folder", folder.display());
            std::process::exit(2);
        };
        let results: Vec<(Option<Traced>, PathBuf)> = plys.into_par_iter().map(|ply| (rills_of(&ply), ply)).collect();
        let (mut read, mut with_rills, mut total) = (0usize, 0usize, 0usize);
        for (result, ply) in &results {
            let Some((part, rills)) = result else { continue };
            read += 1;
            with_rills += usize::from(!rills.is_empty());
            total += rills.len();
            let name = ply.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
            for rill in rills {
                println!(
                    "{name} {part}: {:?} strips {} arc {:.1} mm depth {:.3} mm straightness {:.3} mm slope {:.2} deg height {:.1} mm",
                    rill.skin,
                    rill.points.len(),
                    rill.arc_length_mm,
                    rill.depth_mm,
                    rill.straightness_rms_mm,
                    rill.slope_deg,
                    rill.height_mm
                );
            }
        }
        println!("{}: {read} fragments, {with_rills} with rills, {total} rills in all", folder.display());
    }
}
