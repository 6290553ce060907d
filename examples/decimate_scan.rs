//! Decimates one scan file and writes the result as binary PLY; prints the
//! [`sherd::mesh::decimate::DecimateReport`] as JSON. It is what
//! `benches/pipeline_vs_meshlab.py` runs under `/usr/bin/time -v` for peak memory:
//!
//!     cargo run --release --example decimate_scan -- INPUT.ply OUTPUT.ply 20000

use std::path::PathBuf;
use std::process::ExitCode;

use sherd::mesh::decimate::{decimate_with_options, DecimateOptions};
use sherd::mesh::io::{read_mesh, write_ply, PlyEncoding};

fn main() -> ExitCode {
    let arguments: Vec<String> = std::env::args().skip(1).collect();
    let [input, output, target] = arguments.as_slice() else {
        eprintln!("usage: decimate_scan INPUT OUTPUT.ply TARGET_FACES");
        return ExitCode::from(2);
    };
    let Ok(target_faces) = target.parse::<usize>() else {
        eprintln!("TARGET_FACES must be a whole number, got {target:?}");
        return ExitCode::from(2);
    };
    let run = || -> sherd::Result<String> {
        let mesh = read_mesh(&PathBuf::from(input))?;
        let (decimated, report) = decimate_with_options(&mesh, &DecimateOptions::with_target_faces(target_faces))?;
        drop(mesh);
        write_ply(&PathBuf::from(output), &decimated, PlyEncoding::BinaryLittleEndian)?;
        Ok(serde_json::to_string(&report).expect("the report serialises"))
    };
    match run() {
        Ok(json) => {
            println!("{json}");
            ExitCode::SUCCESS
        }
        Err(error) => {
            eprintln!("{error}");
            ExitCode::FAILURE
        }
    }
}
