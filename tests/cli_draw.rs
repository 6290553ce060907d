//! `sherd draw` and `sherd batch` as a user runs them: every layout choice of the
//! library under the names of the C ABI and Python, the default style shared with the
//! library, the help texts, and bad input refused with a message naming the file or value.

use std::fs;
use std::path::{Path, PathBuf};

use assert_cmd::Command;

use sherd::draw::{AnnotationKind, Annotations, DrawOptions, Drawing, Placement, SectionFill, Style};
use sherd::vocabulary::Vocabulary;
use sherd::orient::{Axis, AxisRecord};

fn sherd() -> Command {
    Command::cargo_bin("sherd").expect("the sherd binary is built")
}

/// One synthetic sherd of `part` written by `sherd synth`, and its true axis file.
fn synth_one(dir: &Path, part: &str, seed: &str) -> (PathBuf, PathBuf) {
    let out = dir.join(format!("{part}-{seed}"));
    sherd().arg("synth").arg(&out).args(["--part", part, "--seed", seed, "--faces", "12000"]).assert().success();
    let scan = fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|e| e == "ply"))
        .expect("sherd synth wrote a PLY");
    let truth = scan.with_extension("truth.json");
    assert!(truth.exists(), "{} has no truth file", scan.display());
    (scan, truth)
}

/// Runs `sherd` and returns its stderr, asserting that it failed cleanly (exit code,
/// no panic, nothing written on stdout).
fn fails(args: &[&std::ffi::OsStr]) -> String {
    let output = sherd().args(args).output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert!(!output.status.success(), "{args:?} succeeded");
    assert!(!stderr.contains("panicked"), "{args:?} panicked: {stderr}");
    assert!(output.stdout.is_empty(), "{args:?} printed on stdout");
    stderr
}

fn os(text: &str) -> &std::ffi::OsStr {
    std::ffi::OsStr::new(text)
}

#[test]
fn every_layout_choice_reaches_the_library_under_its_name() {
    let dir = tempfile::tempdir().unwrap();
    let (scan, truth) = synth_one(dir.path(), "rim", "4");
    let cli_svg = dir.path().join("cli.svg");
    let output = sherd()
        .arg("draw")
        .arg(&scan)
        .arg("--axis")
        .arg(&truth)
        .args(["--style", "linear,light", "--placement", "true-distance", "--section-fill", "hatched"])
        .args(["--interior-view", "false", "--prolongation", "false", "--title", "Inv. 7/12: 5 mm", "--section-angle", "-2"])
        .args(["--dpi", "60", "--annotations", "height,wall-thickness"])
        .arg("-o")
        .arg(&cli_svg)
        .output()
        .unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    // The same drawing made through the library with the options named alike.
    let mesh = sherd::mesh::io::read_mesh(&scan).unwrap();
    let value: serde_json::Value = serde_json::from_slice(&fs::read(&truth).unwrap()).unwrap();
    let record: AxisRecord = serde_json::from_value(value["axis"].clone()).unwrap();
    let axis = Axis::from_record(&record).unwrap();
    let options = DrawOptions {
        style: Style::parse("linear,light").unwrap(),
        placement: Placement::TrueDistance,
        section_fill: SectionFill::Hatched,
        interior_view: false,
        prolongation: false,
        annotations: Annotations { height: true, wall_thickness: true, capacity: false },
        title: Some("Inv. 7/12: 5 mm".into()),
        section_angle_rad: Some((-2f64).to_radians()),
        dpi: 60.0,
        ..Default::default()
    };
    let library_svg = Drawing::build(&mesh, &axis, &options).unwrap().to_bytes(sherd::draw::Format::Svg).unwrap();
    let cli = fs::read(&cli_svg).unwrap();
    assert!(cli == library_svg, "the command's drawing differs from the library's with the same options");
    // And the options change the drawing: the defaults give another one.
    let default_svg = Drawing::build(&mesh, &axis, &DrawOptions { style: options.style, dpi: 60.0, ..Default::default() })
        .unwrap()
        .to_bytes(sherd::draw::Format::Svg)
        .unwrap();
    assert!(default_svg != cli);
    assert!(String::from_utf8_lossy(&cli).contains("Inv. 7/12: 5 mm"), "the title is in the SVG");
    let text = String::from_utf8_lossy(&cli);
    assert!(text.contains(">height ") && text.contains(">wall "), "the annotations asked for are in the SVG");
    assert!(!String::from_utf8_lossy(&default_svg).contains(">height "), "no annotation by default");
}

#[test]
fn the_command_line_default_style_is_the_librarys() {
    let output = sherd().args(["draw", "--help"]).output().unwrap();
    let help = String::from_utf8_lossy(&output.stdout);
    let default = help
        .split("--style <STYLE>")
        .nth(1)
        .and_then(|rest| rest.split("[default: ").nth(1))
        .and_then(|rest| rest.split(']').next())
        .unwrap_or_else(|| panic!("no default style in draw --help: {help}"));
    assert_eq!(Style::parse(default).unwrap(), DrawOptions::default().style, "draw --help's default {default:?}");
    assert_eq!(default, Style::DEFAULT.to_string());
    for name in ["--placement", "beside", "true-distance", "--section-fill", "hatched", "--interior-view", "--title", "--section-angle", "--annotations", "wall_thickness", "capacity"] {
        assert!(help.contains(name), "draw --help lacks {name}");
    }
    // The format is the output's extension: --format belongs to batch alone.
    assert!(!help.contains("--format"), "draw --help lists --format");
    let batch_help = String::from_utf8_lossy(&sherd().args(["batch", "--help"]).output().unwrap().stdout).into_owned();
    assert!(batch_help.contains("--format") && batch_help.contains("--placement"), "{batch_help}");
    assert!(batch_help.contains("--annotations <LIST>") && batch_help.contains("[default: none]"), "{batch_help}");
}

#[test]
fn annotation_lists_parse_by_name_all_and_none() {
    assert_eq!(Annotations::parse("all").unwrap(), Annotations::ALL);
    assert_eq!(Annotations::parse("none").unwrap(), Annotations::default());
    assert_eq!(Annotations::parse(" Capacity , wall-thickness").unwrap(), Annotations { height: false, wall_thickness: true, capacity: true });
    assert_eq!(Annotations::parse(&AnnotationKind::names().join(",")).unwrap(), Annotations::ALL);
    for (bad, says) in [("height,volume", "\"volume\""), ("", "no annotation"), (" , ", "no annotation"), ("all,height", "\"all\""), ("height,none", "\"none\"")] {
        let message = Annotations::parse(bad).unwrap_err().to_string();
        assert!(message.contains(says) && message.contains("wall_thickness"), "{bad:?}: {message}");
    }
}

#[test]
fn export_help_gives_the_profile_columns_the_file_has() {
    let dir = tempfile::tempdir().unwrap();
    let (scan, truth) = synth_one(dir.path(), "rim", "5");
    let csv = dir.path().join("profile.csv");
    sherd().arg("export").arg(&scan).arg("--axis").arg(&truth).arg("--profile").arg(&csv).assert().success();
    let header = fs::read_to_string(&csv).unwrap().lines().next().unwrap().to_owned();
    let help = String::from_utf8_lossy(&sherd().args(["export", "--help"]).output().unwrap().stdout).into_owned();
    assert!(help.contains(&header), "export --help does not give the columns {header:?}: {help}");
    assert!(!help.contains("curve,r_mm,z_mm"), "{help}");
}

#[test]
fn bad_input_to_draw_is_a_clear_error_naming_the_file_or_value() {
    let dir = tempfile::tempdir().unwrap();
    let (rim, _) = synth_one(dir.path(), "rim", "4");
    let (base, _) = synth_one(dir.path(), "base", "6");
    let out = dir.path().join("out.svg");
    let axis_of = |scan: &Path, name: &str| {
        let output = sherd().arg("orient").arg(scan).args(["--json", "--refine", "none"]).output().unwrap();
        assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
        let path = dir.path().join(name);
        fs::write(&path, &output.stdout).unwrap();
        path
    };
    let rim_axis = axis_of(&rim, "rim-axis.json");
    // Its own axis is taken.
    sherd().arg("draw").arg(&rim).arg("--axis").arg(&rim_axis).args(["--dpi", "40", "-o"]).arg(&out).assert().success();
    // The axis of another scan: the record says which scan it was found on.
    let stderr = fails(&[os("draw"), base.as_os_str(), os("--axis"), rim_axis.as_os_str(), os("-o"), out.as_os_str()]);
    assert!(stderr.contains("rim-axis.json") && stderr.contains("another scan") && stderr.contains(&*base.display().to_string()), "{stderr}");
    // `export` reads its axis file the same way.
    let csv = dir.path().join("profile.csv");
    let stderr = fails(&[os("export"), base.as_os_str(), os("--axis"), rim_axis.as_os_str(), os("--profile"), csv.as_os_str()]);
    assert!(stderr.contains("another scan") && !csv.exists(), "{stderr}");
    // An axis without a record of its scan, far outside the scan.
    let far = dir.path().join("far-axis.json");
    fs::write(&far, r#"{"point": [25000, 0, 0], "direction": [0, 0, 1]}"#).unwrap();
    let stderr = fails(&[os("draw"), rim.as_os_str(), os("--axis"), far.as_os_str(), os("-o"), out.as_os_str()]);
    assert!(stderr.contains("far-axis.json") && stderr.contains("mm from the nearest point"), "{stderr}");
    // A scale of 0, an unknown style, an unknown format, a wrong placement.
    let stderr = fails(&[os("draw"), rim.as_os_str(), os("--axis"), rim_axis.as_os_str(), os("--scale"), os("0"), os("-o"), out.as_os_str()]);
    assert!(stderr.contains("1:0"), "{stderr}");
    let stderr = fails(&[os("draw"), rim.as_os_str(), os("--style"), os("light,sepia"), os("-o"), out.as_os_str()]);
    assert!(stderr.contains("\"sepia\"") && stderr.contains("--style"), "{stderr}");
    let jpeg = dir.path().join("out.jpg");
    let stderr = fails(&[os("draw"), rim.as_os_str(), os("-o"), jpeg.as_os_str()]);
    assert!(stderr.contains("out.jpg"), "{stderr}");
    let stderr = fails(&[os("draw"), rim.as_os_str(), os("--placement"), os("far"), os("-o"), out.as_os_str()]);
    assert!(stderr.contains("far") && stderr.contains("true-distance"), "{stderr}");
    let stderr = fails(&[os("draw"), rim.as_os_str(), os("--annotations"), os("height,volume"), os("-o"), out.as_os_str()]);
    assert!(stderr.contains("--annotations") && stderr.contains("\"volume\"") && stderr.contains("capacity"), "{stderr}");
    let stderr = fails(&[os("draw"), rim.as_os_str(), os("--format"), os("png"), os("-o"), out.as_os_str()]);
    assert!(stderr.contains("--format"), "{stderr}");
    assert!(!out.with_extension("png").exists());
}

#[test]
fn batch_draws_with_the_layout_options_in_the_format_asked() {
    let dir = tempfile::tempdir().unwrap();
    let (rim, _) = synth_one(dir.path(), "rim", "4");
    let results = dir.path().join("results");
    let output = sherd()
        .arg("batch")
        .arg(&rim)
        .arg("-o")
        .arg(&results)
        .args(["--format", "png", "--dpi", "50", "--section-fill", "hatched", "--placement", "true-distance", "--title", "R4"])
        .args(["--annotations", "all"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    let record: serde_json::Value =
        serde_json::from_slice(&fs::read(results.join(format!("{}.result.json", rim.file_stem().unwrap().to_string_lossy()))).unwrap())
            .unwrap();
    if record["drawing"].is_null() {
        // Only sherds with an answer are drawn; this one must be one.
        panic!("no drawing: {record:#} {stderr}");
    }
    let drawing = PathBuf::from(record["drawing"].as_str().unwrap());
    assert_eq!(drawing.extension().unwrap(), "png");
    assert!(fs::read(&drawing).unwrap().starts_with(b"\x89PNG"), "{}", drawing.display());
}
