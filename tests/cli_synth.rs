//! `sherd synth`: writes the sherds the library makes, as PLY + truth JSON pairs.

use assert_cmd::Command;
use sherd::mesh::io::read_mesh;
use sherd::synth::{read_truth, synthetic_sherd, SherdOptions, SherdPart};

#[test]
fn synth_writes_the_library_sherds() {
    let dir = tempfile::tempdir().unwrap();
    let output = Command::cargo_bin("sherd")
        .unwrap()
        .args(["synth", "--count", "3", "--seed", "5", "--faces", "3000", "--part", "rim", "-o"])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert_eq!(stdout.lines().count(), 3, "{stdout}");
    for seed in 5..8u64 {
        let expected = synthetic_sherd(seed, &SherdOptions { target_faces: 3000, ..SherdOptions::for_part(SherdPart::Rim) });
        let mesh = read_mesh(&dir.path().join(format!("sherd_{seed}_rim.ply"))).unwrap();
        assert_eq!(mesh.triangles, expected.mesh.triangles);
        assert_eq!(mesh.colors, expected.mesh.colors);
        let worst = mesh.positions.iter().zip(&expected.mesh.positions).map(|(a, b)| (a - b).norm()).fold(0.0, f64::max);
        // PLY stores single-precision floats unless told otherwise: micrometre agreement.
        assert!(worst < 1e-3, "seed {seed}: positions differ by {worst} mm");
        let truth = read_truth(&dir.path().join(format!("sherd_{seed}_rim.truth.json"))).unwrap();
        assert_eq!(truth.part, SherdPart::Rim);
        assert!(truth.axis.angle_to_deg(&expected.truth.axis) < 1e-9);
        assert!((truth.sector_angle_deg - expected.truth.sector_angle_deg).abs() < 1e-9);
        assert!(stdout.contains(&format!("sherd_{seed}_rim.ply")), "{stdout}");
    }
}

#[test]
fn synth_writes_every_fragment_of_a_vessel() {
    let dir = tempfile::tempdir().unwrap();
    let status = Command::cargo_bin("sherd")
        .unwrap()
        .args(["synth", "--vessel", "--fragments", "6", "--cell-mm", "4", "--seed", "2", "-o"])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(status.status.success(), "{}", String::from_utf8_lossy(&status.stderr));
    let plys = std::fs::read_dir(dir.path()).unwrap().filter(|e| e.as_ref().unwrap().path().extension().is_some_and(|x| x == "ply")).count();
    assert!((5..=6).contains(&plys), "{plys} fragments written");
    let truth = read_truth(&dir.path().join("vessel_2_fragment_000.truth.json")).unwrap();
    assert_eq!(truth.fragment_index, Some(0));
}

#[test]
fn synth_rejects_bad_arguments_clearly() {
    let dir = tempfile::tempdir().unwrap();
    let output = Command::cargo_bin("sherd").unwrap().args(["synth", "--part", "handle", "-o"]).arg(dir.path()).output().unwrap();
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("handle") && stderr.contains("rim_to_base"), "{stderr}");

    let output = Command::cargo_bin("sherd").unwrap().args(["synth", "--faces", "10", "-o"]).arg(dir.path()).output().unwrap();
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("--faces 10"), "{stderr}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "nothing written on a bad argument");
}
