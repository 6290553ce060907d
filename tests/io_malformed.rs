//! The malformed-file corpus (`tests/malformed/`, written by its `generate.py`): every
//! file is refused with a message naming the file and containing the expected text, or
//! (a missing texture or material library) read with that warning, or (degenerate,
//! non-manifold, duplicated geometry) read and repaired as its table says; none panics.

use std::collections::BTreeSet;
use std::path::Path;

use sherd::mesh::io::{ReadReport, read_mesh_with_report};
use sherd::mesh::Mesh;
use sherd::mesh::repair::{RepairOptions, repair};
use sherd::orient::{OrientOptions, orient_automatic};

/// What is wrong with a "repair" case, if anything: the mesh read is repaired with the
/// default options, the fields named in `expected` ("field=value; ..." over the read and
/// the repair report, values as JSON or plain strings) must have those values, and the
/// automatic orientation of the repaired mesh must answer (an error is an answer) without
/// panicking.
fn check_repair(mut mesh: Mesh, read: &ReadReport, expected: &str) -> Option<String> {
    let report = repair(&mut mesh, &RepairOptions::default());
    if let Err(error) = mesh.validate() {
        return Some(format!("repair left an invalid mesh: {error}"));
    }
    let mut fields = serde_json::to_value(read).unwrap();
    let serde_json::Value::Object(repair_fields) = serde_json::to_value(&report).unwrap() else { unreachable!() };
    fields.as_object_mut().unwrap().extend(repair_fields);
    let mut wrong = Vec::new();
    for pair in expected.split("; ") {
        let (field, value) = pair.split_once('=').unwrap_or_else(|| panic!("{pair:?} is not field=value"));
        let value = serde_json::from_str(value).unwrap_or_else(|_| serde_json::Value::String(value.to_string()));
        match fields.get(field) {
            Some(actual) if *actual == value => {}
            actual => wrong.push(format!("{field} is {actual:?}, expected {value}")),
        }
    }
    if std::panic::catch_unwind(|| orient_automatic(&mesh, &OrientOptions::default())).is_err() {
        wrong.push("the orientation of the repaired mesh PANICKED".into());
    }
    (!wrong.is_empty()).then(|| wrong.join("; "))
}

#[test]
fn every_malformed_file_gives_its_expected_error_and_none_panics() {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/malformed");
    let table = std::fs::read_to_string(folder.join("expected.tsv")).expect("tests/malformed/expected.tsv");
    let mut listed = BTreeSet::new();
    let mut errors = 0;
    let mut repaired = 0;
    let mut failures = Vec::new();
    for line in table.lines().filter(|l| !l.starts_with('#') && !l.trim().is_empty()) {
        let fields: Vec<&str> = line.split('\t').collect();
        let [file, kind, expected] = fields[..] else { panic!("malformed table line {line:?}") };
        listed.insert(file.to_string());
        if kind == "aux" {
            continue;
        }
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
            ("repair", Ok(Ok((mesh, report)))) => {
                repaired += 1;
                check_repair(mesh, &report, expected)
            }
            ("repair", Ok(Err(error))) => Some(format!("expected a repairable mesh, got the error {error}")),
            (other, _) => Some(format!("unknown kind {other:?}")),
        };
        if let Some(problem) = problem {
            failures.push(format!("{file}: {problem}"));
        }
    }
    assert!(failures.is_empty(), "{} of {} files wrong:\n{}", failures.len(), listed.len(), failures.join("\n"));
    assert!(errors >= 50, "only {errors} malformed files expect an error");
    assert!(repaired >= 15, "only {repaired} broken meshes expect a repair");
    // Every file of the folder is in the table (auxiliary files such as the .mtl a listed
    // .obj refers to as "aux"), except the generator and the table.
    for entry in std::fs::read_dir(&folder).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        let own = name == "generate.py" || name == "expected.tsv";
        assert!(own || listed.contains(&name), "{name} is in tests/malformed but not in expected.tsv");
    }
}

/// Every prefix of valid files, and thousands of random byte corruptions of them, give a
/// mesh or an error: never a panic. (Deterministic: a fixed seed.)
#[test]
fn truncated_and_corrupted_files_never_panic() {
    use rand::{Rng, SeedableRng};
    use sherd::mesh::io::{PlyEncoding, write_ply_to};
    use sherd::mesh::{Mesh, Point, Vector};

    let mut mesh = Mesh::new(
        vec![Point::new(0.0, 0.0, 0.0), Point::new(10.0, 0.0, 0.0), Point::new(0.0, 10.0, 0.0), Point::new(0.0, 0.0, 10.0)],
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    );
    mesh.normals = Some(vec![Vector::z(); 4]);
    mesh.colors = Some(vec![[1, 2, 3, 4]; 4]);
    mesh.quality = Some(vec![0.5; 4]);
    mesh.corner_uvs = Some(vec![[0.25, 0.75]; 12]);
    let mut samples: Vec<(&str, Vec<u8>)> = Vec::new();
    for (name, encoding) in [("binary.ply", PlyEncoding::BinaryLittleEndian), ("ascii.ply", PlyEncoding::Ascii)] {
        let mut bytes = Vec::new();
        write_ply_to(&mut bytes, &mesh, encoding).unwrap();
        samples.push((name, bytes));
    }
    samples.push(("mesh.obj", b"mtllib none.mtl\nv 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nv 0 0 1 1 1 1\nvt 0 0\nvt 1 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/1/1 4/2/1\nf -1//1 -2//1 -3//1\n".to_vec()));
    samples.push(("mesh.stl", b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n".to_vec()));
    let mut binary_stl = vec![0u8; 80];
    binary_stl.extend(1u32.to_le_bytes());
    binary_stl.extend((0..12).flat_map(|i| (i as f32).to_le_bytes()));
    binary_stl.extend([0, 0]);
    samples.push(("binary.stl", binary_stl));
    samples.push(("cloud.xyz", b"0 0 0 0 0 1\n1 0 0 0 1 0\n0 1 0 1 0 0\n".to_vec()));
    samples.push(("cloud.pts", b"2\n0 0 0 5 1 2 3\n1 1 1 6 4 5 6\n".to_vec()));

    let dir = tempfile::tempdir().unwrap();
    let mut random = rand_chacha::ChaCha8Rng::seed_from_u64(2018);
    let mut attempts = 0;
    for (name, bytes) in &samples {
        let path = dir.path().join(name);
        let mut variants: Vec<Vec<u8>> = (0..bytes.len()).map(|n| bytes[..n].to_vec()).collect();
        for _ in 0..300 {
            let mut corrupted = bytes.clone();
            for _ in 0..random.random_range(1..4) {
                let at = random.random_range(0..corrupted.len());
                corrupted[at] = match random.random_range(0..4) {
                    0 => random.random(),
                    1 => b' ',
                    2 => b'\n',
                    _ => b"0123456789-.e"[random.random_range(0..13)],
                };
            }
            variants.push(corrupted);
        }
        for variant in variants {
            std::fs::write(&path, &variant).unwrap();
            attempts += 1;
            let outcome = std::panic::catch_unwind(|| read_mesh_with_report(&path));
            match outcome {
                Err(_) => panic!("{name} panicked on {:?}", String::from_utf8_lossy(&variant)),
                Ok(Ok((mesh, _))) => assert!(mesh.validate().is_ok(), "{name}: invalid mesh from {:?}", String::from_utf8_lossy(&variant)),
                Ok(Err(error)) => assert!(error.to_string().contains(name), "{error}"),
            }
        }
    }
    assert!(attempts > 3000, "{attempts}");
}

/// A scan whose file name is not UTF-8 (Linux allows any bytes but `/` and NUL) is read,
/// and an error about such a file names it (lossily) instead of failing on the name.
#[test]
fn non_utf8_file_names_are_read_and_named() {
    use std::os::unix::ffi::OsStrExt;
    let dir = tempfile::tempdir().unwrap();
    let good = dir.path().join(std::ffi::OsStr::from_bytes(b"tesson caf\xe9 \xff.ply"));
    std::fs::write(&good, b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap();
    let (mesh, _) = read_mesh_with_report(&good).expect("a valid PLY under a non-UTF-8 name");
    assert_eq!(mesh.triangles.len(), 1);
    let bad = dir.path().join(std::ffi::OsStr::from_bytes(b"bris\xe9.obj"));
    std::fs::write(&bad, b"v 0 0 0\nf 1 2 3\n").unwrap();
    let message = read_mesh_with_report(&bad).unwrap_err().to_string();
    assert!(message.contains("bris\u{fffd}.obj") && message.contains("out of range"), "{message}");
}
