//! The `sherd` command-line tool: the contract others script against (README.md,
//! "Command line"). One file per sub-command; no
//! algorithm lives here, only argument parsing, calls into the library and output.
//! Errors go to stderr with exit code 1 (2 for bad arguments, from clap).

mod batch;
mod choices;
mod common;
mod demo;
mod draw;
mod export;
mod info;
mod orient;
mod synth;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Orient 3D scans of pottery sherds and draw them as archaeological illustrations.
#[derive(Parser)]
#[command(name = "sherd", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Describe a scan: counts, bounding box, units guess, attributes, what repair did.
    Info(info::InfoArgs),
    /// Break a synthetic vessel into 20-40 sherds with known axes (NAME.ply + NAME.truth.json).
    Synth(synth::SynthArgs),
    /// Find the rotation axis, rim/base diameter and preserved sector of a sherd.
    Orient(orient::OrientArgs),
    /// Draw a sherd as an archaeological illustration (SVG, EPS, PDF, PNG).
    Draw(draw::DrawArgs),
    /// Write the oriented model, the reconstruction by revolution, the profile, the regularity map.
    Export(export::ExportArgs),
    /// Orient, measure and draw every scan of a folder, in parallel, with a report.
    Batch(batch::BatchArgs),
    /// Make a synthetic sherd, orient, measure and draw it (demo.svg, demo.png).
    Demo(demo::DemoArgs),
}

fn main() -> ExitCode {
    // Rust ignores SIGPIPE, so `sherd orient x.ply --json | head` would panic in println!
    // once head exits; like every Unix filter, sherd should end quietly instead.
    #[cfg(unix)]
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let cli = Cli::parse();
    let library = |result: sherd::Result<()>| result.map(|()| ExitCode::SUCCESS).map_err(|e| e.to_string());
    let result = match cli.command {
        Command::Info(arguments) => library(info::run(&arguments)),
        Command::Synth(arguments) => library(synth::run(&arguments)),
        Command::Orient(arguments) => orient::run(arguments),
        Command::Draw(arguments) => draw::run(arguments),
        Command::Export(arguments) => export::run(arguments),
        Command::Batch(arguments) => batch::run(arguments),
        Command::Demo(arguments) => demo::run(arguments),
    };
    match result {
        Ok(code) => code,
        Err(error) => {
            eprintln!("sherd: {error}");
            ExitCode::FAILURE
        }
    }
}
