//! Wall time of each stage of the illustration of a 500k-face synthetic rim sherd, and of
//! the whole build per style. Run under `/usr/bin/time -v` for CPU time on a busy machine.
//!
//!     cargo run --release --example draw_stages [FACES]

use std::time::Instant;

use sherd::draw::{DrawOptions, Drawing, Format, Style};
use sherd::mesh::occlusion::{ambient_occlusion, OcclusionOptions};
use sherd::profile::section::{most_informative_angle, profile_section};
use sherd::synth::{synthetic_sherd, SherdOptions, SherdPart};

fn main() -> sherd::Result<()> {
    let faces = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(500_000);
    let sherd = synthetic_sherd(5, &SherdOptions { target_faces: faces, ..SherdOptions::for_part(SherdPart::Rim) });
    let (mesh, axis) = (&sherd.mesh, &sherd.truth.axis);
    println!("{} faces, {} vertices", mesh.face_count(), mesh.vertex_count());
    let time = |name: &str, f: &mut dyn FnMut()| {
        let start = Instant::now();
        f();
        println!("{name:<48} {:>8.3} s", start.elapsed().as_secs_f64());
    };
    let mut angle = 0.0;
    time("most_informative_angle", &mut || angle = most_informative_angle(mesh, axis));
    time("profile_section", &mut || {
        profile_section(mesh, axis, angle);
    });
    for (directions, resolution) in [(32, 512), (64, 512), (128, 1024)] {
        time(&format!("ambient_occlusion {directions} x {resolution}"), &mut || {
            ambient_occlusion(mesh, &OcclusionOptions { directions, resolution }).unwrap();
        });
    }
    for style in ["linear", "light", "colour", "regularity", "light,occlusion", "stipple", "linear,colour,light,occlusion,stipple,regularity"] {
        let options = DrawOptions { style: Style::parse(style)?, ..Default::default() };
        let mut drawing = None;
        time(&format!("build {style}"), &mut || drawing = Some(Drawing::build(mesh, axis, &options).unwrap()));
        if style.contains("stipple") {
            let drawing = drawing.unwrap();
            for format in [Format::Svg, Format::Eps, Format::Pdf, Format::Png] {
                time(&format!("  encode {format:?}"), &mut || {
                    drawing.to_bytes(format).unwrap();
                });
            }
        }
    }
    Ok(())
}
