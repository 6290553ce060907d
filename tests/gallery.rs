//! Pixel regression of the gallery (`docs/gallery`): every drawing of
//! `docs/gallery/gallery.tsv` rendered afresh by `docs/gallery/make.sh` and compared with
//! its committed reference, so that any change of the drawing is seen. After a deliberate
//! change, refresh the references with `bash docs/gallery/make.sh` and look at them.
//! The drawings of A011 are rendered and compared where `../shared/data` is present.

use std::path::{Path, PathBuf};
use std::process::Command;

mod support;

/// A pixel differs when one of its channels is off by more than this.
const CHANNEL_TOLERANCE: u8 = 48;

/// Share of a drawing's pixels that may differ (antialiasing, rounding of the last digit).
const MAX_DIFFERING_SHARE: f64 = 0.002;

fn decode(path: &Path) -> (u32, u32, Vec<u8>) {
    let file = std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut reader = png::Decoder::new(std::io::BufReader::new(file)).read_info().unwrap();
    let mut buffer = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buffer).unwrap();
    buffer.truncate(info.buffer_size());
    let rgb = match info.color_type {
        png::ColorType::Rgb => buffer,
        png::ColorType::Rgba => buffer.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect(),
        other => panic!("{}: unexpected colour type {other:?}", path.display()),
    };
    (info.width, info.height, rgb)
}

/// The share of pixels of `fresh` that differ from `reference`, or why they cannot be
/// compared.
fn differing_share(reference: &Path, fresh: &Path) -> Result<f64, String> {
    let (rw, rh, r) = decode(reference);
    let (fw, fh, f) = decode(fresh);
    if (rw, rh) != (fw, fh) {
        return Err(format!("{rw} x {rh} pixels in the reference, {fw} x {fh} now"));
    }
    let differing = r.chunks_exact(3).zip(f.chunks_exact(3)).filter(|(a, b)| a.iter().zip(b.iter()).any(|(x, y)| x.abs_diff(*y) > CHANNEL_TOLERANCE)).count();
    Ok(differing as f64 / (rw as f64 * rh as f64))
}

/// The gallery's names, from its manifest.
fn gallery_names(root: &Path) -> Vec<(String, bool)> {
    std::fs::read_to_string(root.join("docs/gallery/gallery.tsv"))
        .unwrap()
        .lines()
        .filter(|line| !line.trim().is_empty() && !line.starts_with('#'))
        .map(|line| {
            let mut fields = line.split('\t');
            let name = fields.next().unwrap().to_owned();
            let shared = fields.next().is_some_and(|scan| scan.starts_with("shared:"));
            (name, shared)
        })
        .collect()
}

#[test]
fn gallery_drawings_match_their_references() {
    let root = support::repo_root();
    let names = gallery_names(root);
    assert!(names.len() >= 12, "the gallery has {} drawings", names.len());
    let out = tempfile::tempdir().unwrap();
    let sherd = PathBuf::from(env!("CARGO_BIN_EXE_sherd"));
    let run = Command::new("bash")
        .arg(root.join("docs/gallery/make.sh"))
        .env("SHERD", &sherd)
        .env("GALLERY_OUT", out.path())
        .output()
        .unwrap();
    assert!(run.status.success(), "make.sh failed: {}", String::from_utf8_lossy(&run.stderr));
    let mut failures = Vec::new();
    let mut compared = 0;
    for (name, shared) in &names {
        let (reference, fresh) = (root.join(format!("docs/gallery/{name}.png")), out.path().join(format!("{name}.png")));
        if !fresh.exists() {
            assert!(*shared, "{name}: make.sh rendered no drawing");
            println!("SKIP {name}: ../shared/data is absent");
            continue;
        }
        assert!(reference.exists(), "{name}: no reference {}; run bash docs/gallery/make.sh", reference.display());
        compared += 1;
        match differing_share(&reference, &fresh) {
            Ok(share) if share <= MAX_DIFFERING_SHARE => println!("{name}: {:.3}% of pixels differ", 100.0 * share),
            Ok(share) => failures.push(format!("{name}: {:.2}% of pixels differ", 100.0 * share)),
            Err(why) => failures.push(format!("{name}: {why}")),
        }
    }
    assert!(
        failures.is_empty(),
        "{compared} drawings compared; these differ from their references (after a deliberate change: bash docs/gallery/make.sh):\n  {}",
        failures.join("\n  ")
    );
}

/// The comparison itself sees a change: a drawing against another of the gallery, and a
/// drawing with a small mark drawn on it.
#[test]
fn the_comparison_sees_a_changed_drawing() {
    let root = support::repo_root();
    let first = root.join("docs/gallery/rim-light.png");
    let (width, height, mut pixels) = decode(&first);
    assert_eq!(differing_share(&first, &first), Ok(0.0));
    let dir = tempfile::tempdir().unwrap();
    // A 60 x 60 pixel black square: a label moved, a line added.
    for y in 10..70 {
        for x in 10..70 {
            pixels[3 * (y * width as usize + x)..][..3].fill(0);
        }
    }
    let changed = dir.path().join("changed.png");
    let mut encoder = png::Encoder::new(std::fs::File::create(&changed).unwrap(), width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.write_header().unwrap().write_image_data(&pixels).unwrap();
    let share = differing_share(&first, &changed).unwrap();
    assert!(share > MAX_DIFFERING_SHARE, "a 60 x 60 mark changes {:.3}% of the pixels only", 100.0 * share);
    // Another layout of the same sherd: another size, or other pixels.
    match differing_share(&first, &root.join("docs/gallery/rim-true-distance.png")) {
        Ok(share) => assert!(share > MAX_DIFFERING_SHARE, "{share}"),
        Err(why) => assert!(why.contains("pixels"), "{why}"),
    }
}
