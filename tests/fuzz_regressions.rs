//! Replays the fuzz targets' seed corpora (`fuzz/corpus/TARGET/`) and every input a
//! fuzzer found a bug with (`fuzz/regressions/TARGET/`) through the same harness code the
//! fuzz targets run (`fuzz/src/lib.rs`), under plain `cargo test`: a short smoke run of
//! the fuzzers' properties (no panic, valid meshes, errors naming the file) that needs no
//! nightly flags. The long runs are in FUZZING.md.

#[path = "../fuzz/src/lib.rs"]
#[allow(dead_code)]
mod harness;

use std::path::Path;

#[test]
fn fuzz_corpora_and_regressions_replay_without_a_finding() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz");
    let mut replayed = 0;
    let mut findings = Vec::new();
    for (target, run) in harness::TARGETS {
        let mut inputs = 0;
        for folder in [root.join("corpus").join(target), root.join("regressions").join(target)] {
            let Ok(entries) = std::fs::read_dir(&folder) else { continue };
            for entry in entries {
                let path = entry.unwrap().path();
                let bytes = std::fs::read(&path).unwrap();
                if std::panic::catch_unwind(|| run(&bytes)).is_err() {
                    findings.push(path.display().to_string());
                }
                inputs += 1;
            }
        }
        assert!(inputs > 0, "fuzz target {target} has no seed corpus in fuzz/corpus/{target}");
        replayed += inputs;
    }
    assert!(findings.is_empty(), "{} of {replayed} fuzz inputs fail:\n{}", findings.len(), findings.join("\n"));
}
