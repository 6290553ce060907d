//! The `sherd` command-line tool: the contract others script against
//! (`../shared/design.md`, "The command-line tool"). One file per sub-command; no
//! algorithm lives here, only argument parsing, calls into the library and output.
//! Errors go to stderr with exit code 1 (2 for bad arguments, from clap).

mod info;
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
    /// Write synthetic sherds with known axes (NAME.ply + NAME.truth.json).
    Synth(synth::SynthArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Info(arguments) => info::run(&arguments),
        Command::Synth(arguments) => synth::run(&arguments),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("sherd: {error}");
            ExitCode::FAILURE
        }
    }
}
