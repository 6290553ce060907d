//! The illustration, end to end on synthetic sherds with known axes: every format parses
//! with a real reader, the layout follows the conventions (section left of the axis, rim
//! at the top at its true radius, scale bar as long as its label says), PNG size follows
//! the resolution and publication scale.

use std::process::Command;

mod support;

use sherd::draw::{DrawOptions, Drawing, Element, Format, Segment, Style, StyleKind};
use sherd::vocabulary::Vocabulary;
use sherd::mesh::Mesh;
use sherd::orient::Axis;
use sherd::synth::{synthetic_sherd, SherdOptions, SherdPart, SynthSherd};

fn rim_sherd() -> SynthSherd {
    synthetic_sherd(3, &SherdOptions { target_faces: 8_000, ..SherdOptions::for_part(SherdPart::Rim) })
}

fn build(sherd: &SynthSherd, style: &str, scale: u32, dpi: f64) -> Drawing {
    let options = DrawOptions { style: Style::parse(style).unwrap(), scale_denominator: scale, dpi, ..Default::default() };
    Drawing::build(&sherd.mesh, &sherd.truth.axis, &options).unwrap()
}

fn axis_x_mm(drawing: &Drawing) -> f64 {
    match &drawing.layer("axis").expect("axis layer").children[0] {
        Element::Path(p) => match p.segments[0] {
            Segment::MoveTo(q) => q[0],
            _ => panic!("axis path starts with a move"),
        },
        _ => panic!("axis is a path"),
    }
}

fn section_points(drawing: &Drawing) -> Vec<[f64; 2]> {
    let mut points = Vec::new();
    for e in &drawing.layer("section").expect("section layer").children {
        if let Element::Path(p) = e {
            if p.fill.is_some() {
                for s in &p.segments {
                    if let Segment::MoveTo(q) | Segment::LineTo(q) = s {
                        points.push(*q);
                    }
                }
            }
        }
    }
    points
}

fn decode_png(bytes: &[u8]) -> (u32, u32, Vec<u8>, Option<png::PixelDimensions>) {
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().unwrap();
    let dims = reader.info().pixel_dims;
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    // The page is opaque: RGB, expanded here to RGBA for the pixel checks.
    let rgba = match info.color_type {
        png::ColorType::Rgb => buf.chunks_exact(3).flat_map(|p| [p[0], p[1], p[2], 255]).collect(),
        png::ColorType::Rgba => buf,
        other => panic!("unexpected PNG colour type {other:?}"),
    };
    (info.width, info.height, rgba, dims)
}

#[test]
fn section_is_left_of_the_axis_with_the_rim_on_top_at_its_true_radius() {
    let sherd = rim_sherd();
    let drawing = build(&sherd, "light", 1, 150.0);
    let axis_x = axis_x_mm(&drawing);
    let points = section_points(&drawing);
    assert!(!points.is_empty());
    assert!(points.iter().all(|p| p[0] < axis_x), "the section lies left of the axis");
    // The topmost section point is at the rim: its distance to the axis is the rim radius.
    let top = points.iter().copied().min_by(|a, b| a[1].total_cmp(&b[1])).unwrap();
    let rim = sherd.truth.rim_radius_mm.expect("a rim sherd has a rim");
    let wall = points.iter().map(|p| axis_x - p[0]).fold(0.0, f64::max) - points.iter().map(|p| axis_x - p[0]).fold(f64::MAX, f64::min);
    assert!(((axis_x - top[0]) - rim).abs() < wall + 1.0, "rim at {} mm, expected {rim} mm", axis_x - top[0]);

    // The diameter label comes from the measurements and matches the truth.
    let label = drawing
        .layer("labels")
        .unwrap()
        .children
        .iter()
        .find_map(|e| match e {
            Element::Text(t) if t.content.starts_with("Ø ") => Some(t.content.clone()),
            _ => None,
        })
        .expect("a diameter label");
    let diameter: f64 = label[3..].split(' ').next().unwrap().parse().unwrap();
    assert!((diameter - 2.0 * rim).abs() < 0.03 * 2.0 * rim + 1.0, "{label} vs {:.0} mm", 2.0 * rim);

    // The same in pixels: black section pixels left of the axis column, the exterior view
    // (shaded, not white) right of it.
    let bytes = drawing.to_bytes(Format::Png).unwrap();
    let (width, height, rgba, _) = decode_png(&bytes);
    let per_mm = 150.0 / 25.4;
    let axis_column = (axis_x * per_mm) as u32;
    let (mut black_left, mut black_right, mut shaded_right) = (0, 0, 0);
    let section_rows = {
        let (lo, hi) = points.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| (lo.min(p[1]), hi.max(p[1])));
        ((lo * per_mm) as u32 + 2, (hi * per_mm) as u32 - 2)
    };
    for y in section_rows.0..section_rows.1 {
        for x in 0..width {
            let i = ((y * width + x) * 4) as usize;
            let (r, g, b) = (rgba[i], rgba[i + 1], rgba[i + 2]);
            let black = r < 30 && g < 30 && b < 30;
            let shaded = !black && (r < 245 || g < 245 || b < 245) && r.abs_diff(g) < 40;
            if x + 3 < axis_column && black {
                black_left += 1;
            }
            if x > axis_column + 3 && black {
                black_right += 1;
            }
            if x > axis_column + 3 && shaded {
                shaded_right += 1;
            }
        }
    }
    assert!(height > 0 && black_left > 200, "section pixels left of the axis: {black_left}");
    assert!(shaded_right > 20 * black_right.max(1) / 10 && shaded_right > 1000, "exterior view right: {shaded_right} shaded, {black_right} black");
}

#[test]
fn png_size_follows_resolution_and_publication_scale() {
    let sherd = rim_sherd();
    for (scale, dpi) in [(1, 100.0), (2, 100.0), (3, 200.0)] {
        let drawing = build(&sherd, "linear", scale, dpi);
        let (width, height, _, dims) = decode_png(&drawing.to_bytes(Format::Png).unwrap());
        assert_eq!(width, (drawing.width_mm * dpi / 25.4).round() as u32);
        assert_eq!(height, (drawing.height_mm * dpi / 25.4).round() as u32);
        let dims = dims.expect("pHYs chunk");
        assert_eq!(dims.xppu, (dpi / 0.0254).round() as u32);
        if scale == 2 {
            // Half the object size on paper: the section's height halves.
            let full = build(&sherd, "linear", 1, dpi);
            let height_of = |d: &Drawing| {
                let p = section_points(d);
                p.iter().map(|q| q[1]).fold(f64::MIN, f64::max) - p.iter().map(|q| q[1]).fold(f64::MAX, f64::min)
            };
            assert!((height_of(&full) / height_of(&drawing) - 2.0).abs() < 0.02);
        }
    }
}

#[test]
fn scale_bar_is_as_long_as_its_label_in_pixels() {
    let sherd = rim_sherd();
    for scale in [1u32, 2] {
        let dpi = 200.0;
        let drawing = build(&sherd, "linear", scale, dpi);
        let group = match &drawing.layer("scale-bar").unwrap().children[0] {
            Element::Group(g) => g,
            _ => panic!("scale bar group"),
        };
        let label = group
            .children
            .iter()
            .find_map(|e| match e {
                Element::Text(t) if t.content.ends_with(" cm") || t.content.ends_with(" mm") => Some(t.content.clone()),
                _ => None,
            })
            .unwrap();
        let (number, unit) = label.split_once(' ').unwrap();
        let object_mm = number.parse::<f64>().unwrap() * if unit == "cm" { 10.0 } else { 1.0 };
        let (mut x0, mut x1, mut y_mid) = (f64::MAX, f64::MIN, 0.0);
        for e in &group.children {
            if let Element::Path(p) = e {
                for s in &p.segments {
                    if let Segment::MoveTo(q) | Segment::LineTo(q) = s {
                        x0 = x0.min(q[0]);
                        x1 = x1.max(q[0]);
                        y_mid = q[1];
                    }
                }
            }
        }
        assert!(((x1 - x0) - object_mm / scale as f64).abs() < 1e-9);
        // Measure it in the PNG: the bar's outline spans the expected number of pixels.
        let (width, _, rgba, _) = decode_png(&drawing.to_bytes(Format::Png).unwrap());
        let per_mm = dpi / 25.4;
        let row = ((y_mid - 0.75) * per_mm) as u32;
        let dark: Vec<u32> = (0..width)
            .filter(|&x| {
                let i = ((row * width + x) * 4) as usize;
                rgba[i] < 128
            })
            .filter(|&x| (x as f64) > (x0 - 2.0) * per_mm && (x as f64) < (x1 + 2.0) * per_mm)
            .collect();
        let measured = (dark.last().unwrap() - dark.first().unwrap() + 1) as f64;
        let expected = object_mm / scale as f64 * per_mm;
        assert!((measured - expected).abs() <= 3.0, "{label} at 1:{scale}: {measured} px, expected {expected:.1}");
    }
}

#[test]
fn svg_parses_with_usvg_and_keeps_its_layers() {
    let sherd = rim_sherd();
    let drawing = build(&sherd, "light,stipple,regularity", 1, 100.0);
    let bytes = drawing.to_bytes(Format::Svg).unwrap();
    let tree = usvg::Tree::from_data(&bytes, &usvg::Options::default()).expect("usvg parses the SVG");
    assert!(tree.size().width() > 10.0);
    let text = String::from_utf8(bytes).unwrap();
    for layer in ["section", "exterior-view", "interior-view", "axis", "lines", "labels", "scale-bar", "preservation", "legend"] {
        assert!(text.contains(&format!("<g id=\"{layer}\" inkscape:groupmode=\"layer\"")), "layer {layer}");
        assert!(tree.node_by_id(layer).is_some(), "usvg sees {layer}");
    }
    assert!(text.contains("<text") && text.contains("cm</text>"), "real text");
    assert!(text.contains("data:image/png;base64,"), "raster views embedded");
    assert!(text.matches("<circle").count() > 100, "stipple dots are vector circles");
}

fn ghostscript() -> Option<&'static str> {
    let found = Command::new("gs").arg("--version").output().map(|o| o.status.success()).unwrap_or(false);
    if !found && std::env::var("SHERD_REQUIRE_TOOLS").as_deref() == Ok("1") {
        panic!("SHERD_REQUIRE_TOOLS=1 but ghostscript (gs) is not installed");
    }
    found.then_some("gs")
}

fn render_with_ghostscript(bytes: &[u8], extension: &str, extra: &[&str]) -> Option<(u32, u32, Vec<u8>)> {
    let gs = ghostscript()?;
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join(format!("in.{extension}"));
    std::fs::write(&input, bytes).unwrap();
    let output = dir.path().join("out.png");
    let run = Command::new(gs)
        .args(["-q", "-dSAFER", "-dBATCH", "-dNOPAUSE", "-sDEVICE=pngalpha", "-r72"])
        .args(extra)
        .arg(format!("-sOutputFile={}", output.display()))
        .arg(&input)
        .output()
        .unwrap();
    assert!(run.status.success(), "ghostscript failed on the {extension}: {}{}", String::from_utf8_lossy(&run.stdout), String::from_utf8_lossy(&run.stderr));
    assert!(run.stderr.is_empty() && !String::from_utf8_lossy(&run.stdout).contains("Error"), "ghostscript complained: {}", String::from_utf8_lossy(&run.stdout));
    let (w, h, rgba, _) = decode_png(&std::fs::read(&output).unwrap());
    Some((w, h, rgba))
}

#[test]
fn pdf_and_eps_are_well_formed_and_render() {
    let sherd = rim_sherd();
    let drawing = build(&sherd, "colour,light,stipple", 1, 100.0);
    let pdf = drawing.to_bytes(Format::Pdf).unwrap();
    assert!(pdf.starts_with(b"%PDF-1.4") && pdf.ends_with(b"%%EOF\n"));
    // The cross-reference table points at each object's header (binary streams: bytes).
    let find = |needle: &[u8], from: usize| pdf[from..].windows(needle.len()).position(|w| w == needle).map(|i| i + from);
    let mut last = 0;
    while let Some(i) = find(b"startxref\n", last + 1) {
        last = i;
    }
    let tail = String::from_utf8(pdf[last..].to_vec()).unwrap();
    let startxref: usize = tail.lines().nth(1).unwrap().parse().unwrap();
    let table = String::from_utf8(pdf[startxref..].to_vec()).unwrap();
    assert!(table.starts_with("xref"));
    let entries: Vec<usize> = table.lines().skip(3).take_while(|l| l.ends_with(" n ")).map(|l| l[..10].parse().unwrap()).collect();
    assert!(entries.len() >= 5);
    for (i, offset) in entries.iter().enumerate() {
        assert!(pdf[*offset..].starts_with(format!("{} 0 obj", i + 1).as_bytes()), "object {} at {offset}", i + 1);
    }
    let text = String::from_utf8_lossy(&pdf);
    assert!(text.contains("/BaseFont /Helvetica"));
    let eps = drawing.to_bytes(Format::Eps).unwrap();
    assert!(eps.starts_with(b"%!PS-Adobe-3.0 EPSF-3.0\n%%BoundingBox: 0 0 "));
    let points_wide = (drawing.width_mm * 72.0 / 25.4).ceil() as u32;
    for (bytes, extension, extra) in [(&pdf, "pdf", &[][..]), (&eps, "eps", &["-dEPSCrop"][..])] {
        let Some((w, _, rgba)) = render_with_ghostscript(bytes, extension, extra) else {
            println!("SKIP: ghostscript not installed, {extension} only checked structurally");
            continue;
        };
        assert!((w as i64 - points_wide as i64).abs() <= 1, "{extension} page width {w} pt vs {points_wide}");
        let dark = rgba.chunks_exact(4).filter(|p| p[3] > 200 && p[0] < 60 && p[1] < 60 && p[2] < 60).count();
        assert!(dark > 200, "{extension}: ghostscript drew the section and lines ({dark} dark pixels)");
    }
}

#[test]
fn bad_requests_are_clear_errors() {
    assert!(Style::parse("light,sepia").unwrap_err().to_string().contains("sepia"));
    assert!(Style::parse("").is_err());
    assert!(Format::from_path(std::path::Path::new("x.jpg")).unwrap_err().to_string().contains("x.jpg"));
    let sherd = rim_sherd();
    let bad_scale = DrawOptions { scale_denominator: 0, ..Default::default() };
    assert!(Drawing::build(&sherd.mesh, &sherd.truth.axis, &bad_scale).unwrap_err().to_string().contains("1:0"));
    let points = Mesh::new(sherd.mesh.positions.clone(), vec![]);
    assert!(Drawing::build(&points, &sherd.truth.axis, &DrawOptions::default()).is_err());
    // A section plane behind the axis misses the fragment.
    let behind = DrawOptions { section_angle_rad: Some(std::f64::consts::PI), ..Default::default() };
    assert!(Drawing::build(&sherd.mesh, &sherd.truth.axis, &behind).unwrap_err().to_string().contains("misses"));
    let drawing = build(&sherd, "linear", 1, 50.0);
    let missing = std::path::Path::new("/nonexistent-dir/out.svg");
    assert!(drawing.write(missing).is_err());
    let _ = Axis::z();
}

/// Found by the C ABI property test: a mesh with coordinates near 1e300 (finite, so
/// valid) made the view size overflow to zero and the rasterizer panic; a mesh far too
/// large for its resolution would allocate without bound. Both are refused before any
/// raster is allocated, naming the size and what to change.
#[test]
fn views_too_large_to_render_are_refused_before_allocating() {
    use sherd::draw::{DrawOptions, Drawing};
    use sherd::mesh::{Mesh, Point, Vector};
    use sherd::orient::Axis;
    let tetrahedron = |size: f64| {
        Mesh::new(
            vec![Point::new(0.0, 0.0, 0.0), Point::new(size, 0.0, 0.0), Point::new(0.0, size, 0.0), Point::new(0.0, 0.0, size)],
            vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        )
    };
    let axis = Axis::new(Point::new(0.0, 0.0, 0.0), Vector::z());
    for size in [1e300, 1e7] {
        let message = match Drawing::build(&tetrahedron(size), &axis, &DrawOptions::default()) {
            Ok(_) => panic!("a {size} mm tetrahedron was drawn"),
            Err(error) => error.to_string(),
        };
        assert!(message.contains("million") && message.contains("lower the resolution"), "{message}");
    }
    assert!(Drawing::build(&tetrahedron(50.0), &axis, &DrawOptions::default()).is_ok());
}

/// The ideal-vessel regularity drawing shows the signed distances on the diverging scale
/// of `sherd export --regularity` and the C ABI: the legend reads the export's range.
#[test]
fn regularity_legend_is_the_export_scale() {
    use sherd::profile::regularity::{ideal_vessel_map, ColorScale};
    use sherd::profile::section::{most_informative_angle, profile_section};
    let sherd = rim_sherd();
    let (mesh, axis) = (&sherd.mesh, &sherd.truth.axis);
    let drawing = build(&sherd, "regularity", 1, 100.0);
    let (_, export) = ideal_vessel_map(mesh, axis, &profile_section(mesh, axis, most_informative_angle(mesh, axis))).unwrap();
    assert_eq!(export.scale, ColorScale::Diverging);
    assert!(export.low < 0.0 && export.high > 0.0 && (export.low + export.high).abs() < 1e-12);
    let texts: Vec<String> = drawing
        .layer("legend")
        .expect("a legend")
        .children
        .iter()
        .filter_map(|e| match e {
            Element::Text(t) => Some(t.content.clone()),
            _ => None,
        })
        .collect();
    let values: Vec<f64> = texts.iter().filter_map(|t| t.strip_suffix(" mm")?.parse().ok()).collect();
    assert_eq!(values.len(), 3, "{texts:?}");
    assert!((values[0] - export.low).abs() <= 0.005 && (values[2] - export.high).abs() <= 0.005, "legend {texts:?} vs export {} .. {}", export.low, export.high);
    assert!(texts.iter().any(|t| t.starts_with('+')) && texts.contains(&"0 mm".to_string()), "signed labels: {texts:?}");
    assert!(texts.contains(&export.title), "{texts:?}");
}

/// Every style alone and all together, in every format, each file read back by a real
/// reader: usvg, the PNG decoder, ghostscript for PDF and EPS (skipped with a message
/// when gs is absent, unless SHERD_REQUIRE_TOOLS=1).
fn every_style_in_every_format(name: &str, mesh: &Mesh, axis: &Axis, measurements: Option<sherd::profile::measure::Measurements>) {
    let mut styles: Vec<&str> = StyleKind::names();
    let all = StyleKind::names().join(",");
    styles.push(&all);
    for style in styles {
        let options = DrawOptions { style: Style::parse(style).unwrap(), dpi: 100.0, measurements: measurements.clone(), ..Default::default() };
        let drawing = Drawing::build(mesh, axis, &options).unwrap_or_else(|e| panic!("{name} {style}: {e}"));
        let svg = drawing.to_bytes(Format::Svg).unwrap();
        let tree = usvg::Tree::from_data(&svg, &usvg::Options::default()).unwrap_or_else(|e| panic!("{name} {style}: usvg: {e}"));
        assert!((tree.size().width() as f64 - drawing.width_mm * 96.0 / 25.4).abs() < 2.0, "{name} {style}: SVG width");
        let (w, h, rgba, _) = decode_png(&drawing.to_bytes(Format::Png).unwrap());
        assert!(w > 50 && h > 50, "{name} {style}: PNG {w}x{h}");
        let dark = rgba.chunks_exact(4).filter(|p| p[3] > 200 && p[0] < 60 && p[1] < 60 && p[2] < 60).count();
        assert!(dark > 200, "{name} {style}: PNG has {dark} dark pixels");
        for format in [Format::Pdf, Format::Eps] {
            let (extension, extra) = if format == Format::Pdf { ("pdf", &[][..]) } else { ("eps", &["-dEPSCrop"][..]) };
            match render_with_ghostscript(&drawing.to_bytes(format).unwrap(), extension, extra) {
                Some((_, _, rgba)) => {
                    let dark = rgba.chunks_exact(4).filter(|p| p[3] > 200 && p[0] < 60 && p[1] < 60 && p[2] < 60).count();
                    assert!(dark > 100, "{name} {style}: ghostscript drew {dark} dark pixels of the {extension}");
                }
                None => println!("SKIP: ghostscript not installed, {name} {style} {extension} not rendered"),
            }
        }
    }
}

#[test]
fn every_style_and_format_of_a_synthetic_sherd_reads_back() {
    let sherd = rim_sherd();
    every_style_in_every_format("synthetic rim sherd", &sherd.mesh, &sherd.truth.axis, None);
}

#[test]
fn every_style_and_format_of_the_real_scan_a011_reads_back() {
    let Some(path) = support::shared_data_file("every_style_and_format_of_the_real_scan_a011_reads_back", "dacord/A011.ply") else {
        println!("SKIP: ../shared/data/dacord/A011.ply is absent");
        return;
    };
    let analysis = sherd::pipeline::analyse_file(&path, &sherd::pipeline::PipelineOptions::default()).unwrap();
    let axis = *analysis.axis();
    every_style_in_every_format("A011", &analysis.mesh, &axis, analysis.measurements.clone());
}

/// Closed polygon area times the distance its centroid travels (Pappus), mm³.
fn pappus_volume_mm3(outlines: &[Vec<[f64; 2]>]) -> f64 {
    let mut moment = 0.0;
    for o in outlines {
        for i in 0..o.len() {
            let (a, b) = (o[i], o[(i + 1) % o.len()]);
            let cross = a[0] * b[1] - b[0] * a[1];
            moment += (a[0] + b[0]) * cross / 6.0;
        }
    }
    2.0 * std::f64::consts::PI * moment.abs()
}

/// Every directed edge once and its reverse once: closed and consistently oriented.
fn is_watertight(mesh: &Mesh) -> bool {
    let mut edges = std::collections::HashMap::new();
    for t in &mesh.triangles {
        for k in 0..3 {
            *edges.entry((t[k], t[(k + 1) % 3])).or_insert(0) += 1;
        }
    }
    edges.iter().all(|(&(a, b), &n)| n == 1 && edges.get(&(b, a)) == Some(&1))
}

/// The reconstruction by revolution of complete profiles (rim to base): watertight, with
/// the Pappus volume of its section; and the cavity it encloses, revolved from the same
/// section, holds what the capacity measurement says, within 2%.
#[test]
fn reconstruction_is_watertight_and_holds_the_measured_capacity() {
    use sherd::profile::measure::{measure, MeasureOptions};
    use sherd::profile::revolve::{enclosed_volume_mm3, revolve_profile};
    use sherd::profile::section::{most_informative_angle, profile_section, ProfileCurve, ProfileSection};
    let mut checked = 0;
    for seed in 0..12 {
        let sherd = synthetic_sherd(seed, &SherdOptions { target_faces: 8000, ..SherdOptions::for_part(SherdPart::RimToBase).ideal() });
        if sherd.truth.part != SherdPart::RimToBase {
            continue;
        }
        let (mesh, axis) = (&sherd.mesh, &sherd.truth.axis);
        let section = profile_section(mesh, axis, most_informative_angle(mesh, axis));
        let outlines = section.closed_outlines();
        let vessel = revolve_profile(&section, 720).unwrap();
        assert!(is_watertight(&vessel), "seed {seed}: the reconstruction has a hole or a flipped face");
        let (volume, pappus) = (enclosed_volume_mm3(&vessel), pappus_volume_mm3(&outlines));
        assert!((volume - pappus).abs() < 0.001 * pappus, "seed {seed}: reconstruction {volume} mm³ vs Pappus {pappus} mm³");

        let mut options = MeasureOptions::default();
        options.bootstrap.samples = 0;
        let Some(capacity) = measure(mesh, axis, &options).capacity_litres else {
            println!("seed {seed}: no capacity measured (round bottom)");
            continue;
        };
        // The cavity: from the floor (highest point at the innermost radius) up the inner
        // wall (innermost crossing at each height) to the rim top, closed along the axis.
        let points: Vec<[f64; 2]> = outlines.iter().flatten().copied().collect();
        let innermost = points.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min);
        let floor = points.iter().filter(|p| p[0] <= innermost + 1.0).map(|p| p[1]).fold(f64::NEG_INFINITY, f64::max);
        let top = points.iter().map(|p| p[1]).fold(f64::NEG_INFINITY, f64::max);
        let inner_radius = |z: f64| {
            let mut r = f64::INFINITY;
            for o in &outlines {
                for i in 0..o.len() {
                    let (a, b) = (o[i], o[(i + 1) % o.len()]);
                    if (a[1] <= z) != (b[1] <= z) {
                        r = r.min(a[0] + (z - a[1]) / (b[1] - a[1]) * (b[0] - a[0]));
                    }
                }
            }
            r
        };
        let steps = 400;
        let mut cavity = vec![[0.0, floor]];
        cavity.extend((0..=steps).map(|k| {
            let z = (floor + (top - floor) * k as f64 / steps as f64).clamp(floor + 1e-6, top - 1e-6);
            [inner_radius(z), z]
        }));
        cavity.push([0.0, top]);
        let cavity = ProfileSection { angle_rad: section.angle_rad, curves: vec![ProfileCurve { points: cavity, closed: true }] };
        let inside = revolve_profile(&cavity, 720).unwrap();
        assert!(is_watertight(&inside), "seed {seed}: the cavity is not closed");
        let litres = enclosed_volume_mm3(&inside).abs() * 1e-6;
        assert!((litres - capacity).abs() < 0.02 * capacity, "seed {seed}: revolved cavity {litres:.4} l vs measured capacity {capacity:.4} l");
        checked += 1;
    }
    assert!(checked >= 2, "only {checked} complete profiles with a capacity");
}
