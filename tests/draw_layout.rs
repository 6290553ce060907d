//! The layout by the conventions of pottery drawing, over more than a hundred synthetic
//! sherds of every part and vessel family drawn with their true axes, in both placements
//! and both fills: the section at its true radius, the interior view between the section
//! and the axis, the exterior view right of it, nothing overlapping, the figure no wider
//! than the vessel, and the preserved share of the rim as the truth has it.

use sherd::draw::{bounds_overlap, Annotations, Bounds, DrawOptions, Drawing, Element, Placement, SectionFill, Segment, Style};
use sherd::synth::{synthetic_sherd, SherdOptions, SherdPart, SynthSherd, VesselShape};

const SHERDS: u64 = 104;

/// The sherd of `seed`: parts, families and sector ranges in turn, wide ones among them
/// (views that must be cut at the axis); ideal surfaces of revolution, so that the truth's
/// profile is the surface's.
fn sherd(seed: u64) -> SynthSherd {
    let parts = [SherdPart::Rim, SherdPart::RimToBase, SherdPart::Base, SherdPart::Body];
    let shapes = [None, Some(VesselShape::Bowl), Some(VesselShape::CarinatedBowl), Some(VesselShape::Jar), Some(VesselShape::Plate), Some(VesselShape::Beaker)];
    let sectors = [[15.0, 60.0], [60.0, 150.0], [20.0, 40.0]];
    let options = SherdOptions {
        target_faces: 3_000,
        part: Some(parts[seed as usize % parts.len()]),
        shape: shapes[(seed / 4) as usize % shapes.len()],
        sector_deg: sectors[(seed / 2) as usize % sectors.len()],
        colours: false,
        ..SherdOptions::default().ideal()
    };
    synthetic_sherd(1000 + seed, &options)
}

fn options(seed: u64) -> DrawOptions {
    DrawOptions {
        style: Style::parse("linear").unwrap(),
        dpi: 60.0,
        placement: if seed % 2 == 0 { Placement::Beside } else { Placement::TrueDistance },
        section_fill: if seed % 3 == 0 { SectionFill::Hatched } else { SectionFill::Black },
        annotations: Annotations::ALL,
        ..Default::default()
    }
}

fn points_of(element: &Element, out: &mut Vec<[f64; 2]>) {
    match element {
        Element::Path(p) => out.extend(p.segments.iter().filter_map(|s| match s {
            Segment::MoveTo(q) | Segment::LineTo(q) => Some(*q),
            Segment::Close => None,
        })),
        Element::Group(g) => g.children.iter().for_each(|c| points_of(c, out)),
        _ => {}
    }
}

fn layer_bounds(drawing: &Drawing, id: &str) -> Option<Bounds> {
    drawing.layer(id).and_then(|g| g.bounds())
}

/// Every text of the drawing.
fn texts(drawing: &Drawing) -> Vec<String> {
    drawing
        .elements()
        .into_iter()
        .filter_map(|(_, e)| match e {
            Element::Text(t) => Some(t.content.clone()),
            _ => None,
        })
        .collect()
}

/// Whether `p` is inside the closed polygon (even-odd).
fn inside(p: [f64; 2], polygon: &[[f64; 2]]) -> bool {
    let mut inside = false;
    for i in 0..polygon.len() {
        let (a, b) = (polygon[i], polygon[(i + 1) % polygon.len()]);
        if (a[1] > p[1]) != (b[1] > p[1]) && p[0] < a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]) {
            inside = !inside;
        }
    }
    inside
}

fn segment_distance(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let t = (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy).max(1e-18)).clamp(0.0, 1.0);
    (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
}

/// How far `p` ([r, z]) lies outside the vessel's wall, 0 inside.
fn outside_wall(p: [f64; 2], wall: &[[f64; 2]]) -> f64 {
    if inside(p, wall) {
        return 0.0;
    }
    (0..wall.len()).map(|i| segment_distance(p, wall[i], wall[(i + 1) % wall.len()])).fold(f64::INFINITY, f64::min)
}

/// The vessel's wall in the rz-plane: the outer skin up to the rim, a half circle over the
/// lip (the widest a rounded rim rises above its edges), the inner skin back down.
fn wall_polygon(sherd: &SynthSherd) -> Vec<[f64; 2]> {
    let truth = &sherd.truth;
    let mut wall = truth.profile.clone();
    let (outer_top, inner_top) = (*truth.profile.last().unwrap(), *truth.inner_profile.last().unwrap());
    let centre = [(outer_top[0] + inner_top[0]) / 2.0, (outer_top[1] + inner_top[1]) / 2.0];
    let half = ((outer_top[0] - inner_top[0]).hypot(outer_top[1] - inner_top[1])) / 2.0;
    let start = (outer_top[1] - centre[1]).atan2(outer_top[0] - centre[0]);
    for k in 1..16 {
        let a = start + std::f64::consts::PI * k as f64 / 16.0;
        wall.push([centre[0] + half * a.cos(), centre[1] + half * a.sin()]);
    }
    wall.extend(truth.inner_profile.iter().rev());
    // Points a millimetre apart: within 0.03 mm of the skins on their tightest bends, and
    // fast to search.
    let mut sparse = vec![wall[0]];
    for &p in &wall[1..] {
        let last = *sparse.last().unwrap();
        if (p[0] - last[0]).hypot(p[1] - last[1]) >= 1.0 {
            sparse.push(p);
        }
    }
    sparse
}

/// The largest distance (mm) of the drawn section's points (paper `[x, y]`, at 1:1) to
/// the vessel's wall, with the height offset that fits them best: the radius is what the
/// drawing must get right, the paper's height origin is the layout's choice.
fn section_radius_error_mm(points: &[[f64; 2]], axis_x: f64, wall: &[[f64; 2]], heights: [f64; 2]) -> f64 {
    let rz = |p: &[f64; 2], offset: f64| [axis_x - p[0], offset - p[1]];
    let error = |offset: f64, step: usize| points.iter().step_by(step).map(|p| outside_wall(rz(p, offset), wall)).fold(0.0, f64::max);
    let y_top = points.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min);
    // The section's top lies within the sherd's heights.
    let (first, last) = (y_top + heights[0] - 1.0, y_top + heights[1] + 1.0);
    let coarse_step = (points.len() / 60).max(1);
    let mut best = (f64::INFINITY, first);
    let mut offset = first;
    while offset <= last {
        let e = error(offset, coarse_step);
        if e < best.0 {
            best = (e, offset);
        }
        offset += 0.25;
    }
    let centre = best.1;
    (-50..=50).map(|k| error(centre + k as f64 * 0.01, 1)).fold(f64::INFINITY, f64::min)
}

#[test]
fn layout_follows_the_conventions_over_a_hundred_synthetic_sherds() {
    let (mut rim_errors, mut worst_radius, mut cut_views, mut checked_rims) = (Vec::new(), 0.0f64, 0, 0);
    let mut missed_rims = Vec::new();
    let mut failures = Vec::new();
    for seed in 0..SHERDS {
        let sherd = sherd(seed);
        let options = options(seed);
        let name = format!("seed {seed} {:?} {:?} {:?}", sherd.truth.part, sherd.truth.vessel.shape, options.placement);
        let drawing = Drawing::build(&sherd.mesh, &sherd.truth.axis, &options).unwrap_or_else(|e| panic!("{name}: {e}"));
        let mut fail = |what: String| failures.push(format!("{name}: {what}"));

        let mut axis = Vec::new();
        drawing.layer("axis").expect("an axis").children.iter().for_each(|e| points_of(e, &mut axis));
        let axis_x = axis[0][0];
        assert!(axis.iter().all(|p| (p[0] - axis_x).abs() < 1e-9), "{name}: the axis is vertical");
        let dash = drawing.layer("axis").unwrap().children.iter().find_map(|e| match e {
            Element::Path(p) => p.stroke.as_ref().map(|s| s.dash_mm.len()),
            _ => None,
        });
        assert_eq!(dash, Some(4), "{name}: the axis is dash-dot");

        // The section, left of the axis at its true radius.
        let mut section = Vec::new();
        drawing.layer("section").unwrap().children.iter().for_each(|e| points_of(e, &mut section));
        let section_bounds = layer_bounds(&drawing, "section").unwrap();
        if section_bounds[2] > axis_x + 1e-9 {
            fail(format!("the section reaches right of the axis to {:.2} mm", section_bounds[2] - axis_x));
        }
        let heights = sherd.mesh.positions.iter().map(|p| sherd.truth.axis.height_of(p)).fold([f64::INFINITY, f64::NEG_INFINITY], |h, z| [h[0].min(z), h[1].max(z)]);
        let radius_error = section_radius_error_mm(&section, axis_x, &wall_polygon(&sherd), heights);
        worst_radius = worst_radius.max(radius_error);
        if radius_error > 0.5 {
            fail(format!("the section is {radius_error:.2} mm off the vessel's wall"));
        }

        // The views in their halves.
        let tolerance = 1e-6;
        if let Some(interior) = layer_bounds(&drawing, "interior-view") {
            if interior[0] < section_bounds[0] - tolerance || interior[2] > axis_x + tolerance {
                fail(format!(
                    "interior view from {:.2} to {:.2} mm, outside the section ({:.2}) and the axis ({axis_x:.2})",
                    interior[0], interior[2], section_bounds[0]
                ));
            }
            if (interior[2] - axis_x).abs() < 0.5 {
                cut_views += 1;
            }
        }
        match layer_bounds(&drawing, "exterior-view") {
            Some(exterior) if exterior[0] < axis_x - tolerance => fail(format!("exterior view starts {:.2} mm left of the axis", axis_x - exterior[0])),
            Some(_) => {}
            None => fail("no exterior view".into()),
        }

        // Nothing overlaps: views, each label, the scale bar, each preservation figure,
        // the annotations; the texts and figures also keep off the axis and the lines.
        let mut items: Vec<(String, Bounds)> = Vec::new();
        for id in ["exterior-view", "interior-view", "section", "scale-bar", "annotations", "title", "legend"] {
            if let Some(b) = layer_bounds(&drawing, id) {
                items.push((id.into(), b));
            }
        }
        for id in ["labels", "preservation"] {
            for (i, e) in drawing.layer(id).map(|g| g.children.as_slice()).unwrap_or(&[]).iter().enumerate() {
                items.push((format!("{id} {i}"), e.bounds().unwrap()));
            }
        }
        for i in 0..items.len() {
            for j in i + 1..items.len() {
                let pair = [items[i].0.as_str(), items[j].0.as_str()];
                // The interior view runs under the section it continues.
                if pair.contains(&"section") && pair.contains(&"interior-view") {
                    continue;
                }
                if bounds_overlap(&items[i].1, &items[j].1) {
                    fail(format!("{} overlaps {}: {:?} and {:?}", pair[0], pair[1], items[i].1, items[j].1));
                }
            }
        }
        let drawn_lines: Vec<(&str, Bounds)> = ["axis", "lines", "outline"].iter().filter_map(|id| Some((*id, layer_bounds(&drawing, id)?))).collect();
        for (item, bounds) in items.iter().filter(|(id, _)| !id.ends_with("-view") && id != "section") {
            for (line, line_bounds) in &drawn_lines {
                if bounds_overlap(bounds, line_bounds) {
                    fail(format!("{item} overlaps the {line}"));
                }
            }
        }

        // No wider than the vessel: twice its largest radius, plus the margins.
        let largest_radius = sherd.mesh.positions.iter().map(|p| sherd.truth.axis.distance_to(p)).fold(0.0, f64::max);
        let everything = drawing.layers.iter().filter_map(|g| g.bounds()).fold([f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY], |a, b| {
            [a[0].min(b[0]), a[1].min(b[1]), a[2].max(b[2]), a[3].max(b[3])]
        });
        let margins = everything[0] + (drawing.width_mm - everything[2]);
        if everything[2] - everything[0] > 2.0 * largest_radius + 0.5 {
            fail(format!(
                "{:.1} mm wide for a largest radius of {largest_radius:.1} mm (plus {margins:.1} mm margins)",
                everything[2] - everything[0]
            ));
        }
        if (drawing.width_mm - (everything[2] - everything[0]) - margins).abs() > 1e-6 || margins > 20.0 {
            fail(format!("margins of {margins:.1} mm"));
        }

        // The rim's own preserved share, where the measurements find a rim: one level over
        // at least 30% of the sherd's arc (`profile::measure`).
        if let Some(truth_deg) = sherd.truth.rim_sector_angle_deg {
            let truth_percent = truth_deg / 3.6;
            let printed = texts(&drawing).iter().find_map(|t| t.strip_suffix("% of rim")?.parse::<f64>().ok());
            match printed {
                Some(percent) => {
                    checked_rims += 1;
                    rim_errors.push(percent - truth_percent);
                    if (percent - truth_percent).abs() > 1.0 {
                        fail(format!("{percent}% of rim printed, truth {truth_percent:.2}%"));
                    }
                }
                None if truth_deg >= 0.3 * sherd.truth.sector_angle_deg => {
                    missed_rims.push(format!("{name}: no share of rim printed (truth {truth_percent:.2}%): {:?}", texts(&drawing)))
                }
                None => {}
            }
        }
    }
    let worst_rim = rim_errors.iter().map(|e| e.abs()).fold(0.0, f64::max);
    println!(
        "{SHERDS} sherds: section within {worst_radius:.3} mm of the wall; {checked_rims} rim shares, worst {worst_rim:.2} points off; {cut_views} interior views cut at the axis"
    );
    assert!(failures.is_empty(), "{} failures over {SHERDS} sherds:\n{}", failures.len(), failures.join("\n"));
    assert!(checked_rims >= SHERDS as usize / 3, "only {checked_rims} rim shares checked");
    // A rim the measurements do not see (a plate's, issue 34) prints no share at all; a
    // few such sherds in a hundred are the measurements' to fix, not the layout's.
    assert!(missed_rims.len() <= checked_rims / 20, "{} rims unmeasured:\n{}", missed_rims.len(), missed_rims.join("\n"));
    for missed in &missed_rims {
        println!("rim not measured: {missed}");
    }
    assert!(cut_views >= 5, "only {cut_views} views were wide enough to be cut: the test misses the cut");
}
