//! The malformed-file corpus (`tests/malformed/`, written by its `generate.py`): every
//! file is refused with a message naming the file and containing the expected text (or,
//! for a missing texture or material library, read with that warning), and none panics.

use std::collections::BTreeSet;
use std::path::Path;

use sherd::mesh::io::read_mesh_with_report;

#[test]
fn every_malformed_file_gives_its_expected_error_and_none_panics() {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/malformed");
    let table = std::fs::read_to_string(folder.join("expected.tsv")).expect("tests/malformed/expected.tsv");
    let mut listed = BTreeSet::new();
    let mut errors = 0;
    let mut failures = Vec::new();
    for line in table.lines().filter(|l| !l.starts_with('#') && !l.trim().is_empty()) {
        let fields: Vec<&str> = line.split('\t').collect();
        let [file, kind, expected] = fields[..] else { panic!("malformed table line {line:?}") };
        listed.insert(file.to_string());
        let path = folder.join(file);
        let outcome = std::panic::catch_unwind(|| read_mesh_with_report(&path));
        let problem = match (kind, outcome) {
            (_, Err(_)) => Some("PANICKED".to_string()),
            ("error", Ok(Err(error))) => {
                errors += 1;
                let message = error.to_string();
                (!(message.contains(expected) && message.contains(file))).then(|| format!("error {message:?} lacks {expected:?} or the file name"))
            }
            ("error", Ok(Ok((mesh, _)))) => Some(format!("read without error: {} vertices", mesh.vertex_count())),
            ("warning", Ok(Ok((_, report)))) => {
                (!report.warnings.iter().any(|w| w.contains(expected))).then(|| format!("warnings {:?} lack {expected:?}", report.warnings))
            }
            ("warning", Ok(Err(error))) => Some(format!("expected a warning, got the error {error}")),
            (other, _) => Some(format!("unknown kind {other:?}")),
        };
        if let Some(problem) = problem {
            failures.push(format!("{file}: {problem}"));
        }
    }
    assert!(failures.is_empty(), "{} of {} files wrong:\n{}", failures.len(), listed.len(), failures.join("\n"));
    assert!(errors >= 50, "only {errors} malformed files expect an error");
    // Every file of the folder is in the table (except the generator, the table and
    // auxiliary files such as a .mtl a listed .obj refers to).
    for entry in std::fs::read_dir(&folder).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        let auxiliary = name.ends_with(".mtl") || name == "generate.py" || name == "expected.tsv";
        assert!(auxiliary || listed.contains(&name), "{name} is in tests/malformed but not in expected.tsv");
    }
}
