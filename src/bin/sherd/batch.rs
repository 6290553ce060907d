//! `sherd batch`: every scan of an excavation oriented, measured and drawn in parallel,
//! with `report.csv` and `report.json`, resumable and safe to interrupt.
//!
//! Each sherd's result is first written as `OUTDIR/NAME.result.json` (atomically, after
//! its drawing), and the reports are rebuilt from those files at the end. So a killed
//! run leaves only whole files, a rerun skips the sherds whose result exists (unless
//! `--force`), and the reports always cover every sherd done so far.

use std::fs;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Mutex;
use std::time::Instant;

use clap::Args;
use rayon::prelude::*;

use sherd::mesh::atomic::{write_atomically, write_bytes_atomically};
use sherd::draw::Format;
use sherd::pipeline::{self, RecordStatus, SherdRecord};

use crate::choices::{Choices, cli_name};
use crate::common::{AnalysisArgs, DrawingArgs};

/// Scan file extensions a directory walk picks up.
const SCAN_EXTENSIONS: [&str; 5] = ["ply", "obj", "stl", "xyz", "pts"];

#[derive(Args, Debug)]
#[command(
    about = "Orient, measure and draw every scan of a folder or a list of files",
    after_help = "Examples:\n  sherd batch excavation/ -o results/\n  sherd batch a.ply b.ply -o results/ --jobs 2 --format png\n  sherd batch excavation/ -o results/ --force     # redo sherds already done\n\n\
The folder OUTDIR receives a drawing per sherd, NAME.result.json per sherd, report.csv and\n\
report.json. A rerun skips the sherds already done, so an interrupted batch resumes.\n\n\
Exit code: 0 when every row of the report is an answer (any status but an error:\n\
ok, needs_manual_orientation, ...); 1 when any row is an error (or a scan has no row),\n\
after every scan was processed and the reports written complete; 2 for bad arguments."
)]
pub struct BatchArgs {
    /// Scan files, or folders searched (recursively) for .ply .obj .stl .xyz .pts files.
    #[arg(required = true)]
    pub inputs: Vec<PathBuf>,
    /// Output folder (created if missing).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Parallel jobs (default: all cores).
    #[arg(long)]
    pub jobs: Option<usize>,
    /// Redo sherds whose result already exists.
    #[arg(long)]
    pub force: bool,
    #[command(flatten)]
    pub analysis: AnalysisArgs,
    #[command(flatten)]
    pub drawing: DrawingArgs,
    /// Format of the drawings.
    #[arg(long, value_parser = Choices::of(|_| None, |format: Format| format), default_value = cli_name(Format::Svg))]
    pub format: Format,
}

pub fn run(args: BatchArgs) -> Result<ExitCode, String> {
    let scans = collect_scans(&args.inputs)?;
    if scans.is_empty() {
        return Err("no scan files (.ply .obj .stl .xyz .pts) among the inputs".into());
    }
    fs::create_dir_all(&args.output)
        .map_err(|e| format!("{}: cannot create the output folder: {e}", args.output.display()))?;
    remove_stale_temporaries(&args.output);

    let names = unique_names(&scans);
    let pending: Vec<usize> = (0..scans.len())
        .filter(|&i| args.force || !result_path(&args.output, &names[i]).exists())
        .collect();
    let skipped = scans.len() - pending.len();
    let progress = Progress::new(pending.len() as u64, skipped);

    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.jobs.unwrap_or(0))
        .build()
        .map_err(|e| format!("cannot start {} jobs: {e}", args.jobs.unwrap_or(0)))?;
    let options = args.analysis.pipeline_options()?;
    let draw_options = args.drawing.draw_options()?;
    let extension = args.format;
    let started = Instant::now();
    pool.install(|| {
        pending.par_iter().for_each(|&i| {
            let drawing_path = args.output.join(format!("{}.{extension}", names[i]));
            let record =
                pipeline::process_file(&scans[i], &options, Some((&draw_options, &drawing_path)));
            let json = serde_json::to_vec_pretty(&record).expect("a record always serialises");
            let write = write_bytes_atomically(&result_path(&args.output, &names[i]), &json);
            let line = match (&write, record.error.as_deref()) {
                (Err(e), _) => format!("{}: cannot write its result: {e}", scans[i].display()),
                (Ok(()), Some(reason)) => format!("{}: {}: {reason}", scans[i].display(), RecordStatus::Error),
                (Ok(()), None) => format!("{}: {}", scans[i].display(), record.status),
            };
            progress.done(&line);
        })
    });
    progress.finish();

    let records: Vec<SherdRecord> = names
        .iter()
        .filter_map(|name| {
            let bytes = fs::read(result_path(&args.output, name)).ok()?;
            serde_json::from_slice(&bytes).ok()
        })
        .collect();
    write_reports(&args.output, &records)?;
    let failures: Vec<&SherdRecord> = records.iter().filter(|r| is_error_row(r)).collect();
    eprintln!(
        "{} sherds in {:.1} s ({} done before, skipped); {} ok, {} axis uncertain (drawn: check them), {} sense uncertain (not drawn), {} need manual orientation, {} errors; reports in {}",
        records.len(),
        started.elapsed().as_secs_f64(),
        skipped,
        records.iter().filter(|r| r.status == RecordStatus::Ok).count(),
        records.iter().filter(|r| r.status == RecordStatus::AxisUncertain).count(),
        records.iter().filter(|r| r.status == RecordStatus::SenseUncertain).count(),
        records.iter().filter(|r| r.status == RecordStatus::NeedsManualOrientation).count(),
        failures.len(),
        args.output.display()
    );
    for failure in &failures {
        eprintln!("  {}: {}", failure.file, failure.error.as_deref().unwrap_or(""));
    }
    let without_row = scans.len() - records.len();
    if without_row > 0 {
        eprintln!("  {without_row} scans have no row (their result could not be written or read back)");
    }
    // A script running a batch learns from the exit code alone whether a row needs a
    // look; only errors count: every other status (needs_manual_orientation, ...) is an
    // answer, as for `sherd orient`.
    Ok(if failures.is_empty() && without_row == 0 { ExitCode::SUCCESS } else { ExitCode::FAILURE })
}

/// An error row: the report writes its status as `error: <reason>`; every other status
/// is an answer about the sherd.
fn is_error_row(record: &SherdRecord) -> bool {
    record.error.is_some() || record.status == RecordStatus::Error
}

/// The scan files among `inputs`, folders walked recursively, in a stable order.
fn collect_scans(inputs: &[PathBuf]) -> Result<Vec<PathBuf>, String> {
    let mut scans = Vec::new();
    for input in inputs {
        if input.is_dir() {
            walk(input, &mut scans).map_err(|e| format!("{}: {e}", input.display()))?;
        } else if input.exists() {
            scans.push(input.clone());
        } else {
            return Err(format!("{}: no such file or folder", input.display()));
        }
    }
    Ok(scans)
}

fn walk(folder: &Path, scans: &mut Vec<PathBuf>) -> std::io::Result<()> {
    let mut entries: Vec<PathBuf> = fs::read_dir(folder)?.filter_map(|e| e.ok().map(|e| e.path())).collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            walk(&path, scans)?;
        } else if is_scan(&path) {
            scans.push(path);
        }
    }
    Ok(())
}

fn is_scan(path: &Path) -> bool {
    let extension = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    extension.is_some_and(|e| SCAN_EXTENSIONS.contains(&e.as_str()))
}

/// One output name per scan: the file stem, with a numeric suffix where two scans in
/// different folders share a stem, so no sherd's drawing overwrites another's.
fn unique_names(scans: &[PathBuf]) -> Vec<String> {
    let mut seen = std::collections::HashMap::<String, usize>::new();
    scans
        .iter()
        .map(|path| {
            let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
            let count = seen.entry(stem.clone()).or_insert(0);
            *count += 1;
            if *count == 1 { stem } else { format!("{stem}-{count}") }
        })
        .collect()
}

fn result_path(output: &Path, name: &str) -> PathBuf {
    output.join(format!("{name}.result.json"))
}

/// Temporaries of an interrupted run (`.NAME.sherd-tmp-*`, see `write_atomically`).
fn remove_stale_temporaries(output: &Path) {
    let Ok(entries) = fs::read_dir(output) else { return };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if name.starts_with('.') && name.contains(".sherd-tmp-") {
            let _ = fs::remove_file(entry.path());
        }
    }
}

fn write_reports(output: &Path, records: &[SherdRecord]) -> Result<(), String> {
    let json = serde_json::to_vec_pretty(records).map_err(|e| e.to_string())?;
    write_bytes_atomically(&output.join("report.json"), &json).map_err(|e| e.to_string())?;
    write_atomically(&output.join("report.csv"), |w| {
        let io = |e: std::io::Error| sherd::Error::io(output.join("report.csv"), e);
        writeln!(w, "{}", SherdRecord::CSV_HEADER).map_err(io)?;
        for record in records {
            writeln!(w, "{}", record.csv_row()).map_err(io)?;
        }
        Ok(())
    })
    .map_err(|e| e.to_string())
}

/// A progress bar on a terminal, one plain line per sherd otherwise (logs, CI).
struct Progress {
    bar: Option<indicatif::ProgressBar>,
    lock: Mutex<()>,
}

impl Progress {
    fn new(total: u64, skipped: usize) -> Self {
        if skipped > 0 {
            eprintln!("{skipped} sherds already done (use --force to redo them)");
        }
        let bar = std::io::stderr().is_terminal().then(|| {
            let bar = indicatif::ProgressBar::new(total);
            bar.set_style(
                indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} sherds, {eta} left  {msg}")
                    .expect("a valid template"),
            );
            bar
        });
        Progress { bar, lock: Mutex::new(()) }
    }

    fn done(&self, line: &str) {
        match &self.bar {
            Some(bar) => {
                bar.set_message(line.to_owned());
                bar.inc(1);
            }
            None => {
                let _guard = self.lock.lock();
                eprintln!("{line}");
            }
        }
    }

    fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
