//! Draws synthetic sherds and the real scan A011 in every style and format, into the
//! folder given as the first argument (default `target/draw_gallery`).
//!
//!     cargo run --release --example draw_gallery [OUT_DIR]

use std::path::{Path, PathBuf};
use std::time::Instant;

use sherd::draw::{DrawOptions, Drawing, Placement, RegularityKind, SectionFill, Style};
use sherd::mesh::io::read_mesh;
use sherd::orient::{orient_automatic, Axis, OrientOptions};
use sherd::synth::{synthetic_sherd, SherdOptions, SherdPart};

fn draw(mesh: &sherd::mesh::Mesh, axis: &Axis, name: &str, options: &DrawOptions, formats: &[&str], out: &Path) -> sherd::Result<()> {
    let start = Instant::now();
    let drawing = Drawing::build(mesh, axis, options)?;
    let built = start.elapsed();
    for format in formats {
        let path = out.join(format!("{name}.{format}"));
        drawing.write(&path)?;
    }
    println!("{name}: {} faces, built in {:.2} s, {:.0} x {:.0} mm", mesh.face_count(), built.as_secs_f64(), drawing.width_mm, drawing.height_mm);
    Ok(())
}

fn main() -> sherd::Result<()> {
    let out = std::env::args().nth(1).map(PathBuf::from).unwrap_or_else(|| PathBuf::from("target/draw_gallery"));
    std::fs::create_dir_all(&out).map_err(|e| sherd::Error::io(&out, e))?;
    let styles = ["linear", "colour", "light", "occlusion", "stipple", "regularity", "light,occlusion", "linear,stipple"];
    let formats = ["svg", "eps", "pdf", "png"];
    for (part, name) in [(SherdPart::Rim, "rim"), (SherdPart::RimToBase, "profile"), (SherdPart::Base, "base")] {
        let sherd = synthetic_sherd(11, &SherdOptions { target_faces: 60_000, ..SherdOptions::for_part(part) });
        for style in styles {
            let options = DrawOptions { style: Style::parse(style)?, ..Default::default() };
            draw(&sherd.mesh, &sherd.truth.axis, &format!("synthetic_{name}_{}", style.replace(',', "+")), &options, &formats, &out)?;
        }
        let options = DrawOptions {
            style: Style::parse("light,occlusion")?,
            placement: Placement::TrueDistance,
            section_fill: SectionFill::Hatched,
            scale_denominator: 2,
            ..Default::default()
        };
        draw(&sherd.mesh, &sherd.truth.axis, &format!("synthetic_{name}_true_distance_hatched_1to2"), &options, &["png", "pdf"], &out)?;
        let options = DrawOptions { style: Style::parse("regularity")?, regularity: RegularityKind::AxisDistance, ..Default::default() };
        draw(&sherd.mesh, &sherd.truth.axis, &format!("synthetic_{name}_axis_distance"), &options, &["png"], &out)?;
    }
    let scan = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/dacord/A011.ply");
    if scan.exists() {
        let mesh = read_mesh(&scan)?;
        let orientation = orient_automatic(&mesh, &OrientOptions::default())?;
        println!("A011: {:?}", orientation.verdict);
        for style in styles {
            let options = DrawOptions { style: Style::parse(style)?, ..Default::default() };
            draw(&mesh, &orientation.axis, &format!("A011_{}", style.replace(',', "+")), &options, &formats, &out)?;
        }
    } else {
        println!("SKIP A011: {} is absent", scan.display());
    }
    Ok(())
}
