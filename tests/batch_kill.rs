//! `sherd batch` killed with SIGKILL while it writes its outputs leaves no partial file:
//! every drawing, result and report in the output folder parses, a sherd's result exists
//! only with its drawing, and a rerun (without `--force`) skips the sherds done, redoes
//! the rest and completes with every sherd in its reports (issue 10).

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::Value;

fn sherd() -> Command {
    Command::new(env!("CARGO_BIN_EXE_sherd"))
}

fn file_names(folder: &Path) -> Vec<String> {
    let Ok(entries) = fs::read_dir(folder) else { return Vec::new() };
    entries.filter_map(|e| e.ok()).map(|e| e.file_name().to_string_lossy().into_owned()).collect()
}

fn is_temporary(name: &str) -> bool {
    name.starts_with('.') && name.contains(".sherd-tmp-")
}

/// Every output file of `folder` parses as what its extension says; returns the names of
/// the sherds with a result file. Temporaries (hidden, removed by the next run) are
/// skipped: they are what an interrupted write leaves instead of a partial file.
fn check_outputs_whole(folder: &Path) -> BTreeSet<String> {
    let mut results = BTreeSet::new();
    for name in file_names(folder).into_iter().filter(|n| !is_temporary(n)) {
        let path = folder.join(&name);
        let bytes = fs::read(&path).unwrap();
        let context = format!("{} ({} bytes) is partial or broken", path.display(), bytes.len());
        if let Some(stem) = name.strip_suffix(".result.json") {
            let record: Value = serde_json::from_slice(&bytes).expect(&context);
            assert!(record["file"].is_string(), "{context}");
            if record["status"] == "ok" || record["status"] == "axis_uncertain" {
                assert!(folder.join(format!("{stem}.svg")).exists(), "{name} is written before its drawing");
            }
            results.insert(stem.to_string());
        } else if name.ends_with(".json") {
            let report: Value = serde_json::from_slice(&bytes).expect(&context);
            assert!(report.is_array(), "{context}");
        } else if name.ends_with(".svg") {
            usvg::Tree::from_data(&bytes, &usvg::Options::default()).expect(&context);
            assert!(String::from_utf8_lossy(&bytes).trim_end().ends_with("</svg>"), "{context}");
        } else if name.ends_with(".csv") {
            let text = String::from_utf8(bytes).expect(&context);
            let mut lines = text.lines();
            let columns = lines.next().expect(&context).split(',').count();
            assert!(text.ends_with('\n'), "{context}");
            for line in lines {
                // Quoted fields hold no commas in these reports' numbers; names are quoted.
                assert!(line.split(',').count() >= columns, "{context}: short row {line:?}");
            }
        } else {
            panic!("unexpected output {}", path.display());
        }
    }
    results
}

#[test]
fn killed_batch_leaves_only_whole_files_and_a_rerun_completes() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("scans");
    let output = dir.path().join("out");
    let made = sherd()
        .args(["synth", "--seed", "51", "--count", "8", "--part", "rim", "--faces", "3000", "-o"])
        .arg(&input)
        .output()
        .unwrap();
    assert!(made.status.success(), "{}", String::from_utf8_lossy(&made.stderr));
    let scans: Vec<PathBuf> = fs::read_dir(&input)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "ply"))
        .collect();
    assert_eq!(scans.len(), 8);

    // Kill at the first sight of a temporary file (a write under way), several times, so
    // that some kills land inside a write; each run resumes where the last one stopped.
    let mut kills_mid_write = 0;
    let mut kills = 0;
    for _attempt in 0..8 {
        let before = file_names(&output).into_iter().filter(|n| n.ends_with(".result.json")).count();
        if before == scans.len() {
            break;
        }
        let mut child = sherd()
            .arg("batch")
            .arg(&input)
            .arg("-o")
            .arg(&output)
            .args(["--jobs", "1", "--dpi", "150"])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let started = Instant::now();
        let mut saw_temporary = false;
        loop {
            if child.try_wait().unwrap().is_some() {
                break;
            }
            // The stale temporaries of the previous kill are removed at start: wait for
            // a write of this run (a result count grown, or a new temporary).
            let names = file_names(&output);
            let results = names.iter().filter(|n| n.ends_with(".result.json")).count();
            if names.iter().any(|n| is_temporary(n)) && results >= before && started.elapsed() > Duration::from_millis(50) {
                saw_temporary = true;
                child.kill().unwrap();
                break;
            }
            assert!(started.elapsed() < Duration::from_secs(300), "batch took more than 5 minutes");
            std::thread::sleep(Duration::from_micros(200));
        }
        let status = child.wait().unwrap();
        if !status.success() {
            kills += 1;
            kills_mid_write += saw_temporary as usize;
        }
        check_outputs_whole(&output);
        if kills_mid_write >= 3 {
            break;
        }
    }
    eprintln!("{kills} kills, {kills_mid_write} of them while a temporary file existed");
    assert!(kills_mid_write >= 1, "no kill landed during a write ({kills} kills)");

    let done_before = check_outputs_whole(&output).len();
    let rerun = sherd().arg("batch").arg(&input).arg("-o").arg(&output).args(["--jobs", "2", "--dpi", "150"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&rerun.stderr);
    assert!(rerun.status.success(), "{stderr}");
    if done_before > 0 {
        assert!(stderr.contains(&format!("{done_before} sherds already done")), "{stderr}");
    }
    let results = check_outputs_whole(&output);
    assert_eq!(results.len(), scans.len(), "every sherd has its result after the rerun");
    let report: Value = serde_json::from_slice(&fs::read(output.join("report.json")).unwrap()).unwrap();
    assert_eq!(report.as_array().unwrap().len(), scans.len());
    let rows = fs::read_to_string(output.join("report.csv")).unwrap().lines().count();
    assert_eq!(rows, scans.len() + 1, "report.csv has a header and a row per sherd");
    let leftovers: Vec<String> = file_names(&output).into_iter().filter(|n| is_temporary(n)).collect();
    assert!(leftovers.is_empty(), "the rerun leaves no temporary file: {leftovers:?}");
}
