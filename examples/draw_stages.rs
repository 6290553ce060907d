//! Wall and CPU time of each stage of the illustration of a 500k-face synthetic rim sherd, and of
//! the whole build per style (CPU time: user + system of all threads, what a busy machine
//! does not inflate as much as the wall clock).
//!
//!     cargo run --release --example draw_stages [FACES]

use std::time::Instant;

use sherd::draw::{DrawOptions, Drawing, Format, Style};
use sherd::draw::occlusion::{ambient_occlusion, OcclusionOptions};
use sherd::profile::section::{most_informative_angle, profile_section};
use sherd::synth::{synthetic_sherd, SherdOptions, SherdPart};

fn main() -> sherd::Result<()> {
    let faces = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(500_000);
    let sherd = synthetic_sherd(5, &SherdOptions { target_faces: faces, ..SherdOptions::for_part(SherdPart::Rim) });
    let (mesh, axis) = (&sherd.mesh, &sherd.truth.axis);
    println!("{} faces, {} vertices", mesh.face_count(), mesh.vertex_count());
    // CPU seconds (user + system, all threads) beside the wall clock: on a shared machine
    // the wall clock measures the load, CPU time the work.
    let time = |name: &str, f: &mut dyn FnMut()| {
        let (start, cpu) = (Instant::now(), cpu_seconds());
        f();
        println!("{name:<48} {:>8.3} s wall {:>8.3} CPU-s", start.elapsed().as_secs_f64(), cpu_seconds() - cpu);
    };
    let mut angle = 0.0;
    time("most_informative_angle", &mut || angle = most_informative_angle(mesh, axis));
    time("profile_section", &mut || {
        profile_section(mesh, axis, angle);
    });
    time("measure (no bootstrap)", &mut || {
        let mut options = sherd::profile::measure::MeasureOptions::default();
        options.bootstrap.samples = 0;
        sherd::profile::measure::measure(mesh, axis, &options);
    });
    for (directions, resolution) in [(32, 512), (64, 512), (128, 1024)] {
        time(&format!("ambient_occlusion {directions} x {resolution}"), &mut || {
            ambient_occlusion(mesh, &OcclusionOptions { directions, resolution }).unwrap();
        });
    }
    // MeshLab on the same mesh, same number of rays, when pymeshlab is installed.
    let dir = std::env::temp_dir().join(format!("sherd-draw-stages-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| sherd::Error::io(&dir, e))?;
    let input = dir.join("sherd.ply");
    sherd::mesh::io::write_ply(&input, mesh, sherd::mesh::io::PlyEncoding::BinaryLittleEndian)?;
    for rays in [32, 128] {
        let script = format!(
            "import pymeshlab, time\nms = pymeshlab.MeshSet()\nms.load_new_mesh({:?})\nt, c = time.time(), time.process_time()\n\
             ms.compute_scalar_ambient_occlusion(rays={rays})\nprint(f'{{time.time() - t:8.3f}} s wall {{time.process_time() - c:8.3f}} CPU-s')\n",
            input.to_str().unwrap_or_default()
        );
        match std::process::Command::new("python3").args(["-c", &script]).output() {
            Ok(out) if out.status.success() => println!(
                "{:<48} {}",
                format!("pymeshlab ambient occlusion rays={rays}"),
                String::from_utf8_lossy(&out.stdout).trim()
            ),
            _ => println!("pymeshlab not available"),
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    let mut measure_options = sherd::profile::measure::MeasureOptions::default();
    measure_options.bootstrap.samples = 0;
    let measured = sherd::profile::measure::measure(mesh, axis, &measure_options);
    let all = Style::parse("linear,colour,light,occlusion,stipple,regularity")?;
    let given = DrawOptions { style: all, measurements: Some(measured), ..Default::default() };
    time("build all six styles, measurements given", &mut || {
        Drawing::build(mesh, axis, &given).unwrap();
    });
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
            // The PNG's two halves: rasterizing the page, and compressing it.
            let mut pixmap = None;
            time("    of which rasterize (tiny-skia)", &mut || pixmap = Some(sherd::draw::png::render(&drawing, drawing.dpi).unwrap()));
            let pixmap = pixmap.unwrap();
            time("    of which compress (png)", &mut || {
                sherd::draw::png::encode_pixmap(&pixmap, Some(drawing.dpi)).unwrap();
            });
        }
    }
    Ok(())
}

/// User + system CPU time of the whole process so far, seconds (0 where unavailable).
fn cpu_seconds() -> f64 {
    #[cfg(unix)]
    {
        let mut usage = std::mem::MaybeUninit::<libc::rusage>::zeroed();
        // SAFETY: getrusage fills the struct it is given; RUSAGE_SELF is always valid.
        if unsafe { libc::getrusage(libc::RUSAGE_SELF, usage.as_mut_ptr()) } == 0 {
            let usage = unsafe { usage.assume_init() };
            let seconds = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 * 1e-6;
            return seconds(usage.ru_utime) + seconds(usage.ru_stime);
        }
    }
    0.0
}
