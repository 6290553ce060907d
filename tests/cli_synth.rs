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

/// The `.ply` files of a folder, sorted.
fn plys(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "ply"))
        .collect();
    files.sort();
    files
}

#[test]
fn synth_outdir_breaks_a_whole_vessel_into_20_to_40_fragments_as_the_issue_says() {
    let dir = tempfile::tempdir().unwrap();
    let positional = dir.path().join("positional");
    let output = Command::cargo_bin("sherd").unwrap().args(["synth", "--seed", "3", "--cell-mm", "4"]).arg(&positional).output().unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let fragments = plys(&positional);
    assert!((20..=40).contains(&fragments.len()), "{} fragments", fragments.len());
    for (k, ply) in fragments.iter().enumerate() {
        let truth = read_truth(&ply.with_extension("truth.json")).unwrap();
        assert!(truth.fragment_index.is_some(), "{}", ply.display());
        assert!(ply.file_name().unwrap().to_string_lossy().starts_with("vessel_3_fragment_"), "{k}: {}", ply.display());
    }
    // `-o DIR` is the same folder argument, and the same seed gives the same files.
    let option = dir.path().join("option");
    Command::cargo_bin("sherd").unwrap().args(["synth", "--seed", "3", "--cell-mm", "4", "-o"]).arg(&option).assert().success();
    let again = plys(&option);
    assert_eq!(again.len(), fragments.len());
    for (a, b) in fragments.iter().zip(&again) {
        assert_eq!(std::fs::read(a).unwrap(), std::fs::read(b).unwrap(), "{} differs", a.display());
    }
    // Both at once is ambiguous; neither is an error naming what is missing.
    let both = Command::cargo_bin("sherd").unwrap().args(["synth", "-o"]).arg(&option).arg(&positional).output().unwrap();
    assert_eq!(both.status.code(), Some(2));
    let neither = Command::cargo_bin("sherd").unwrap().args(["synth", "--seed", "3"]).output().unwrap();
    assert_eq!(neither.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&neither.stderr).contains("OUTDIR"), "{}", String::from_utf8_lossy(&neither.stderr));
}

#[test]
fn synth_part_or_faces_asks_for_one_sherd_per_seed() {
    let dir = tempfile::tempdir().unwrap();
    let output = Command::cargo_bin("sherd").unwrap().args(["synth", "--count", "2", "--faces", "2000"]).arg(dir.path()).output().unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let files = plys(dir.path());
    assert_eq!(files.len(), 2, "{files:?}");
    assert!(files.iter().all(|f| f.file_name().unwrap().to_string_lossy().starts_with("sherd_")), "{files:?}");
    // Vessel options make no sense for one sherd: refused, not ignored.
    let output = Command::cargo_bin("sherd").unwrap().args(["synth", "--part", "rim", "--fragments", "30"]).arg(dir.path()).output().unwrap();
    assert_eq!(output.status.code(), Some(2), "{}", String::from_utf8_lossy(&output.stderr));
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

/// `--relief-mm` moves the vessel's surface and is recorded in the truth; without it the
/// files are those of before (no relief, no draw from the vessel's random stream); a
/// negative or non-finite relief is refused with the flag's name.
#[test]
fn synth_relief_moves_the_surface_and_is_recorded() {
    let dir = tempfile::tempdir().unwrap();
    let make = |name: &str, extra: &[&str]| {
        let out = dir.path().join(name);
        Command::cargo_bin("sherd").unwrap().args(["synth", "--vessel", "--fragments", "4", "--cell-mm", "3", "--seed", "9", "-o"]).arg(&out).args(extra).assert().success();
        out
    };
    let plain = make("plain", &[]);
    let relief = make("relief", &["--relief-mm", "0.3", "--relief-wavelength-mm", "8"]);
    let name = "vessel_9_fragment_000";
    let truth = read_truth(&relief.join(format!("{name}.truth.json"))).unwrap();
    assert_eq!((truth.relief.amplitude_mm, truth.relief.wavelength_mm), (0.3, 8.0));
    assert_eq!(read_truth(&plain.join(format!("{name}.truth.json"))).unwrap().relief.amplitude_mm, 0.0);
    let (a, b) = (read_mesh(&plain.join(format!("{name}.ply"))).unwrap(), read_mesh(&relief.join(format!("{name}.ply"))).unwrap());
    assert_eq!(a.triangles, b.triangles, "the relief moves vertices, it does not remesh");
    let rms = (a.positions.iter().zip(&b.positions).map(|(p, q)| (p - q).norm_squared()).sum::<f64>() / a.positions.len() as f64).sqrt();
    assert!((0.15..0.45).contains(&rms), "rms move {rms} mm for a 0.3 mm relief");
    for bad in ["--relief-mm=-0.1", "--relief-mm=NaN"] {
        let refused = Command::cargo_bin("sherd").unwrap().args(["synth", bad, "-o"]).arg(dir.path().join("bad")).output().unwrap();
        assert!(!refused.status.success());
        assert!(String::from_utf8_lossy(&refused.stderr).contains("--relief-mm"), "{}", String::from_utf8_lossy(&refused.stderr));
    }
}
