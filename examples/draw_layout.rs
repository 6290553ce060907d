//! Draws synthetic sherds of every part, a plate and a jar with their true axes, in both
//! placements, with every annotation, as PNG and SVG into the folder given as the first
//! argument (default `target/draw_layout`): the layout to look at.
//!
//!     cargo run --release --example draw_layout [OUT_DIR]

use std::path::PathBuf;

use sherd::draw::{Annotations, DrawOptions, Drawing, Placement, SectionFill, Style};
use sherd::synth::{synthetic_sherd, SherdOptions, SherdPart, VesselShape};

fn main() -> sherd::Result<()> {
    let out = std::env::args().nth(1).map(PathBuf::from).unwrap_or_else(|| PathBuf::from("target/draw_layout"));
    std::fs::create_dir_all(&out).map_err(|e| sherd::Error::io(&out, e))?;
    let cases = [
        ("rim", SherdPart::Rim, None, [15.0, 60.0]),
        ("body", SherdPart::Body, None, [15.0, 60.0]),
        ("base", SherdPart::Base, None, [15.0, 60.0]),
        ("profile", SherdPart::RimToBase, None, [15.0, 60.0]),
        ("plate", SherdPart::RimToBase, Some(VesselShape::Plate), [20.0, 40.0]),
        ("jar_wide", SherdPart::Rim, Some(VesselShape::Jar), [100.0, 150.0]),
    ];
    for (name, part, shape, sector_deg) in cases {
        let sherd = synthetic_sherd(11, &SherdOptions { target_faces: 30_000, shape, sector_deg, ..SherdOptions::for_part(part) });
        for (placement, fill, tag) in [(Placement::Beside, SectionFill::Black, "beside"), (Placement::TrueDistance, SectionFill::Hatched, "true_distance")] {
            let options = DrawOptions {
                style: Style::parse("light,occlusion")?,
                placement,
                section_fill: fill,
                annotations: Annotations::ALL,
                dpi: 150.0,
                title: Some(format!("{name} ({tag})")),
                ..Default::default()
            };
            let drawing = Drawing::build(&sherd.mesh, &sherd.truth.axis, &options)?;
            for extension in ["png", "svg"] {
                drawing.write(&out.join(format!("{name}_{tag}.{extension}")))?;
            }
            match sherd.truth.rim_sector_angle_deg {
                Some(deg) => println!("{name} {tag}: {:.0} x {:.0} mm; true rim arc {deg:.1} deg ({:.1}% of rim)", drawing.width_mm, drawing.height_mm, deg / 3.6),
                None => println!("{name} {tag}: {:.0} x {:.0} mm", drawing.width_mm, drawing.height_mm),
            }
        }
    }
    Ok(())
}
