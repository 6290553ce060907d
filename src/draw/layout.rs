//! The layout of the archaeological illustration (Wilczek et al. 2018, sections 2.4.1
//! and 2.4.2; design.md "Drawing conventions"): the axis as a vertical dash-dot line,
//! the profile section filled left of it with the interior view, the exterior view right
//! of it, the rim at the top, horizontal lines at rim, carinations and base, the missing
//! profile prolonged dashed to the full diameter, scale bar, diameter and sector labels.
//!
//! Everything is first placed in object millimetres (x right with the axis at 0, z up);
//! [`Canvas::finish`] maps it to paper millimetres at the publication scale.

use rayon::prelude::*;

use crate::draw::model::{helvetica_width_mm, Anchor, Dots, Drawing, Element, Group, Image, Path, Rgb, Segment, Stroke, Text};
use crate::draw::font::text_width_mm;
use crate::draw::stipple::stipple_dots;
use crate::draw::view::{crease_edges, outline_loops, render_view, visible_crease_lines, OcclusionField, Shading, Surface, View};
use crate::draw::{DrawOptions, Placement, RegularityKind, SectionFill};
use crate::mesh::normals::{compute_vertex_normals, NormalWeighting};
use crate::mesh::occlusion::near_and_far_light;
use crate::mesh::Mesh;
use crate::orient::Axis;
use crate::profile::measure::{measure, MeasureOptions, Measurements};
use crate::profile::regularity::{axis_distance_map, ideal_vessel_map, ColorMap, ColorScale};
use crate::profile::section::{angular_extent, most_informative_angle, oriented_frame, section_of_oriented, ProfileSection};
use crate::{Error, Result};

const BLACK: Rgb = [0, 0, 0];
const WHITE: Rgb = [255, 255, 255];
/// Paper margin around everything, mm.
const MARGIN_MM: f64 = 8.0;
/// Gap between the axis and a view drawn beside it, paper mm.
const GAP_MM: f64 = 4.0;

/// Most pixels a rendered view may have: 50 million, about 800 MB of depth, face, colour
/// and darkness buffers. A scan in metres read as millimetres, or 4800 dpi at natural
/// size of a large sherd, would otherwise allocate without bound.
const MAX_VIEW_PIXELS: f64 = 50e6;

/// Elements in object coordinates, grouped in layers, with the publication scale.
struct Canvas {
    /// Object millimetres per paper millimetre (2 for 1:2).
    scale: f64,
    layers: Vec<Group>,
}

impl Canvas {
    fn layer(&mut self, id: &str) -> &mut Vec<Element> {
        if let Some(i) = self.layers.iter().position(|g| g.id == id) {
            return &mut self.layers[i].children;
        }
        self.layers.push(Group { id: id.into(), children: Vec::new() });
        &mut self.layers.last_mut().expect("just pushed").children
    }

    fn stroke(&self, width_mm: f64, dash_mm: &[f64]) -> Stroke {
        Stroke { color: BLACK, width_mm, dash_mm: dash_mm.to_vec() }
    }

    fn text(&mut self, layer: &str, position: [f64; 2], content: String, size_mm: f64, anchor: Anchor) {
        self.layer(layer).push(Element::Text(Text { position, content, size_mm, anchor, color: BLACK }));
    }

    /// Maps object coordinates to paper millimetres and wraps up the drawing.
    fn finish(mut self, dpi: f64) -> Drawing {
        let (mut x0, mut x1, mut z0, mut z1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
        let mut include = |x: f64, z: f64| {
            x0 = x0.min(x);
            x1 = x1.max(x);
            z0 = z0.min(z);
            z1 = z1.max(z);
        };
        fn visit(e: &Element, scale: f64, include: &mut dyn FnMut(f64, f64)) {
            match e {
                Element::Path(p) => p.segments.iter().for_each(|s| match s {
                    Segment::MoveTo(q) | Segment::LineTo(q) => include(q[0], q[1]),
                    Segment::Close => {}
                }),
                Element::Dots(d) => d.centers.iter().for_each(|c| include(c[0], c[1])),
                Element::Text(t) => {
                    // The PNG's stroke font is a little wider than Helvetica: room for both.
                    let width = helvetica_width_mm(&t.content, t.size_mm).max(text_width_mm(&t.content, t.size_mm)) * scale;
                    let left = match t.anchor {
                        Anchor::Start => t.position[0],
                        Anchor::Middle => t.position[0] - width / 2.0,
                        Anchor::End => t.position[0] - width,
                    };
                    include(left, t.position[1] - 0.25 * t.size_mm * scale);
                    include(left + width, t.position[1] + 0.8 * t.size_mm * scale);
                }
                Element::Image(i) => {
                    include(i.x_mm, i.y_mm);
                    include(i.x_mm + i.width_mm, i.y_mm - i.height_mm);
                }
                Element::Group(g) => g.children.iter().for_each(|c| visit(c, scale, include)),
            }
        }
        for layer in &self.layers {
            for e in &layer.children {
                visit(e, self.scale, &mut include);
            }
        }
        if !x0.is_finite() {
            (x0, x1, z0, z1) = (0.0, 1.0, 0.0, 1.0);
        }
        let scale = self.scale;
        let map = move |p: [f64; 2]| [(p[0] - x0) / scale + MARGIN_MM, (z1 - p[1]) / scale + MARGIN_MM];
        fn convert(e: &mut Element, scale: f64, map: &dyn Fn([f64; 2]) -> [f64; 2]) {
            match e {
                Element::Path(p) => p.segments.iter_mut().for_each(|s| match s {
                    Segment::MoveTo(q) | Segment::LineTo(q) => *q = map(*q),
                    Segment::Close => {}
                }),
                Element::Dots(d) => d.centers.iter_mut().for_each(|c| *c = map(*c)),
                Element::Text(t) => t.position = map(t.position),
                Element::Image(i) => {
                    let corner = map([i.x_mm, i.y_mm]);
                    (i.x_mm, i.y_mm) = (corner[0], corner[1]);
                    i.width_mm /= scale;
                    i.height_mm /= scale;
                }
                Element::Group(g) => g.children.iter_mut().for_each(|c| convert(c, scale, map)),
            }
        }
        for layer in &mut self.layers {
            for e in &mut layer.children {
                convert(e, scale, &map);
            }
        }
        Drawing {
            width_mm: (x1 - x0) / scale + 2.0 * MARGIN_MM,
            height_mm: (z1 - z0) / scale + 2.0 * MARGIN_MM,
            dpi,
            layers: self.layers,
        }
    }
}

/// Refuses a drawing whose views would exceed [`MAX_VIEW_PIXELS`], before any raster is
/// allocated. A view of the oriented fragment fits in its bounding cylinder about the
/// axis: at most twice the largest radius wide and the height tall.
fn check_view_size(oriented: &[crate::mesh::Point], options: &DrawOptions) -> Result<()> {
    let pixel_mm = options.scale_denominator as f64 * 25.4 / options.dpi;
    let radius_mm = oriented.iter().map(|p| p.x * p.x + p.y * p.y).fold(0.0, f64::max).sqrt();
    let (low, high) = oriented.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| (l.min(p.z), h.max(p.z)));
    let width_px = 2.0 * radius_mm / pixel_mm + 5.0;
    let height_px = (high - low) / pixel_mm + 5.0;
    let pixels = width_px * height_px;
    if !(pixels.is_finite() && pixels <= MAX_VIEW_PIXELS) {
        return Err(Error::InvalidArgument(format!(
            "the views would be up to {width_px:.0} x {height_px:.0} pixels at {} dpi and 1:{}, more than the {} million \
             a view may have: lower the resolution or raise the scale denominator (or check the scan's units)",
            options.dpi,
            options.scale_denominator,
            MAX_VIEW_PIXELS / 1e6
        )));
    }
    Ok(())
}

/// Builds the illustration; see [`crate::draw::Drawing::build`].
pub(crate) fn build(mesh: &Mesh, axis: &Axis, options: &DrawOptions) -> Result<Drawing> {
    mesh.validate()?;
    if mesh.triangles.is_empty() {
        return Err(Error::InvalidArgument("drawing needs a mesh with faces; a point cloud has no surface to draw".into()));
    }
    options.check()?;
    let frame = oriented_frame(mesh, axis);
    let oriented: Vec<_> = mesh.positions.par_iter().map(|p| frame * p).collect();
    check_view_size(&oriented, options)?;
    let computed_normals;
    let scan_normals = match &mesh.normals {
        Some(n) => n,
        None => {
            computed_normals = compute_vertex_normals(mesh, NormalWeighting::Angle);
            &computed_normals
        }
    };
    let normals: Vec<_> = scan_normals.par_iter().map(|n| frame.rotation * n).collect();
    let angle = match options.section_angle_rad {
        Some(a) => a,
        None => most_informative_angle(mesh, axis),
    };
    let section = section_of_oriented(mesh, &oriented, angle);
    if section.is_empty() {
        return Err(Error::DegenerateGeometry(format!(
            "the section plane at {:.1} deg misses the fragment; choose another angle",
            angle.to_degrees()
        )));
    }
    // The measurements (single-threaded, about as long as everything else together) run
    // beside the shading and the views; they only label the drawing.
    let (measurements, drawn) = rayon::join(
        || match &options.measurements {
            Some(m) => m.clone(),
            None => {
                let mut measure_options = MeasureOptions::default();
                measure_options.bootstrap.samples = 0;
                measure(mesh, axis, &measure_options)
            }
        },
        || draw_views(mesh, axis, &oriented, &normals, &section, options),
    );
    let Views { exterior, interior, regularity_map } = drawn?;
    let scale = options.scale_denominator as f64;
    let pixel_mm = scale * 25.4 / options.dpi;
    let mut canvas = Canvas { scale, layers: Vec::new() };
    let profile = OuterProfile::of(&section);
    let exterior_shift = match options.placement {
        Placement::Beside => GAP_MM * scale - exterior.view.top_left()[0],
        Placement::TrueDistance => 0.0,
    };
    let exterior_right = exterior.view.top_left()[0] + exterior_shift + exterior.view.camera.width as f64 * pixel_mm;
    canvas.layer("exterior-view").extend(exterior.elements(exterior_shift));
    if let Some(interior) = interior {
        let width = interior.view.camera.width as f64 * pixel_mm;
        let shift = match options.placement {
            Placement::Beside => {
                // Between the section and the axis when it fits, else left of the section.
                let left = -profile.inner_radius_min + GAP_MM * scale;
                if left + width <= -GAP_MM * scale {
                    left - interior.view.top_left()[0]
                } else {
                    -profile.outer_radius_max - GAP_MM * scale - width - interior.view.top_left()[0]
                }
            }
            Placement::TrueDistance => 0.0,
        };
        canvas.layer("interior-view").extend(interior.elements(shift));
    }

    add_section(&mut canvas, &section, options.section_fill);
    let z_top = oriented.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max);
    let z_bottom = oriented.iter().map(|p| p.z).fold(f64::INFINITY, f64::min);
    let axis_path = Path::polyline(
        &[[0.0, z_top + 4.0 * scale], [0.0, z_bottom - 4.0 * scale]],
        false,
        None,
        Some(canvas.stroke(0.25, &[4.0, 1.0, 0.5, 1.0])),
    );
    canvas.layer("axis").push(Element::Path(axis_path));
    add_annotations(&mut canvas, &profile, &measurements, exterior_right, options);
    add_scale_bar(&mut canvas, z_bottom - 9.0 * scale, exterior_right, &profile);
    if let Some(map) = &regularity_map {
        // Right of everything: the dashed prolongation reaches the full radius, often
        // beyond the exterior view, and must not run through the legend's labels.
        let right = if options.prolongation { exterior_right.max(profile.outer_radius_max) } else { exterior_right };
        add_legend(&mut canvas, map, right + 8.0 * scale, z_top);
    }
    if let Some(title) = &options.title {
        let x = -profile.outer_radius_max;
        canvas.text("annotations", [x, z_top + 21.0 * scale], title.clone(), 4.0, Anchor::Start);
    }
    Ok(canvas.finish(options.dpi))
}

/// The rendered views and the regularity map their colours follow.
struct Views {
    exterior: DrawnView,
    interior: Option<DrawnView>,
    regularity_map: Option<ColorMap>,
}

/// One view with its vector content in object millimetres, before it is shifted along x
/// to its place.
struct DrawnView {
    view: View,
    /// Raster image, stipple dots, crease lines and outline, unshifted.
    elements: Vec<Element>,
}

impl DrawnView {
    /// The elements moved by `shift` object millimetres along x.
    fn elements(self, shift: f64) -> Vec<Element> {
        let mut elements = self.elements;
        for e in &mut elements {
            shift_element(e, shift);
        }
        elements
    }
}

fn shift_element(e: &mut Element, shift: f64) {
    match e {
        Element::Path(p) => p.segments.iter_mut().for_each(|s| match s {
            Segment::MoveTo(q) | Segment::LineTo(q) => q[0] += shift,
            Segment::Close => {}
        }),
        Element::Dots(d) => d.centers.iter_mut().for_each(|c| c[0] += shift),
        Element::Text(t) => t.position[0] += shift,
        Element::Image(i) => i.x_mm += shift,
        Element::Group(g) => g.children.iter_mut().for_each(|c| shift_element(c, shift)),
    }
}

/// Shading data (occlusion, regularity) and the crease edges side by side, then the
/// exterior and interior views with their vector content, each on its own task.
fn draw_views(
    mesh: &Mesh,
    axis: &Axis,
    oriented: &[crate::mesh::Point],
    normals: &[crate::mesh::Vector],
    section: &ProfileSection,
    options: &DrawOptions,
) -> Result<Views> {
    let style = options.style;
    let ((occlusion, regularity), creases) = rayon::join(
        || {
            rayon::join(
                || -> Result<Option<OcclusionField>> {
                    if !(style.occlusion || style.stipple) {
                        return Ok(None);
                    }
                    occlusion_field(mesh, options).map(Some)
                },
                || -> Result<Option<(Vec<f32>, ColorMap)>> {
                    if !style.regularity {
                        return Ok(None);
                    }
                    Ok(Some(match options.regularity {
                        RegularityKind::AxisDistance => axis_distance_map(mesh, axis),
                        // The signed map on the diverging scale, as the PLY export and the
                        // C ABI give it: the legend reads the same range as the export.
                        RegularityKind::IdealVessel => ideal_vessel_map(mesh, axis, section)?,
                    }))
                },
            )
        },
        || if style.linear { crease_edges(mesh, 50.0) } else { Vec::new() },
    );
    let (occlusion, regularity) = (occlusion?, regularity?);
    let surface = Surface {
        mesh,
        oriented,
        normals,
        occlusion: occlusion.as_ref(),
        regularity: regularity.as_ref().map(|(v, m)| (v.as_slice(), m)),
    };
    let shading = Shading {
        colour: style.colour,
        light: style.light || style.stipple,
        occlusion: style.occlusion || style.stipple,
        regularity: style.regularity,
        light_direction: options.light_direction,
    };
    let pixel_mm = options.scale_denominator as f64 * 25.4 / options.dpi;
    // Angular placement of the views (section 2.4.1): beside the axis in front view, or
    // turned so that the fragment sits at its true distance from the axis.
    let (low, high) = angular_extent(oriented);
    let middle = 0.5 * (low + high);
    let (exterior_turn, interior_turn) = match options.placement {
        Placement::Beside => (-std::f64::consts::FRAC_PI_2 - middle, std::f64::consts::FRAC_PI_2 - middle),
        Placement::TrueDistance => (-high, std::f64::consts::PI - high),
    };
    let draw = |turn: f64| {
        let view = render_view(&surface, turn, pixel_mm, &shading);
        let elements = view_elements(&view, &creases, options);
        DrawnView { view, elements }
    };
    let (exterior, interior) = rayon::join(|| draw(exterior_turn), || options.interior_view.then(|| draw(interior_turn)));
    Ok(Views { exterior, interior, regularity_map: regularity.map(|(_, map)| map) })
}

/// Share of the mesh's bounding-box diagonal within which an occluder's shadow stays sharp
/// in a drawing (grooves, rills, the crease of a carination); farther shadows are smoothed
/// over the view (see [`near_and_far_light`]).
const NEAR_OCCLUSION_REACH_SHARE: f64 = 0.06;

/// The ambient light a view shades with: the near light per vertex, the rest as a factor
/// the view smooths, and the stretch of their product over the fragment's 2nd..98th
/// percentiles (sherds are mostly open: unstretched occlusion would be invisible).
fn occlusion_field(mesh: &Mesh, options: &DrawOptions) -> Result<OcclusionField> {
    let (lo, hi) = mesh.bounding_box().ok_or_else(|| Error::DegenerateGeometry("no vertex to shade".into()))?;
    let reach_mm = ((hi - lo).norm() * NEAR_OCCLUSION_REACH_SHARE).max(1e-6);
    let light = near_and_far_light(mesh, &options.occlusion, reach_mm)?;
    let near = smooth_over_neighbours(mesh, light.near, 4);
    let full = smooth_over_neighbours(mesh, light.full, 4);
    let far_factor: Vec<f32> = full.iter().zip(&near).map(|(&f, &n)| if n > 0.0 { (f / n).min(1.0) } else { 1.0 }).collect();
    let mut sorted: Vec<f32> = full.iter().copied().filter(|v| v.is_finite()).collect();
    sorted.sort_by(f32::total_cmp);
    let (low, high) = match sorted.len() {
        0 => (0.0, 1.0),
        n => (sorted[n * 2 / 100], sorted[(n * 98 / 100).min(n - 1)]),
    };
    Ok(OcclusionField { near, far_factor, low, span: (high - low).max(1e-6) })
}

/// Averages each vertex's value with its neighbours' `passes` times: the shadow edges of
/// near occluders soften over a few vertices.
fn smooth_over_neighbours(mesh: &Mesh, mut values: Vec<f32>, passes: usize) -> Vec<f32> {
    for _ in 0..passes {
        let mut sum = values.clone();
        let mut count = vec![1u32; values.len()];
        for t in &mesh.triangles {
            for k in 0..3 {
                let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
                sum[a] += values[b];
                count[a] += 1;
                sum[b] += values[a];
                count[b] += 1;
            }
        }
        values = sum.iter().zip(&count).map(|(s, &c)| s / c as f32).collect();
    }
    values
}

/// One view's elements in object millimetres: its raster image (raster styles), stipple
/// dots, for the linear style the visible ones of `creases`, and its outline.
fn view_elements(view: &View, creases: &[[u32; 2]], options: &DrawOptions) -> Vec<Element> {
    let style = options.style;
    let raster = style.colour || style.light || style.occlusion || style.regularity;
    let scale = options.scale_denominator as f64;
    let stroke = |width_mm: f64| Some(Stroke { color: BLACK, width_mm, dash_mm: Vec::new() });
    let [left, top] = view.top_left();
    let pixel = view.camera.pixel_mm;
    let (width, height) = (view.camera.width, view.camera.height);
    let to_object = |p: [f64; 2]| [left + p[0] * pixel, top - p[1] * pixel];
    let mut children = Vec::new();
    if raster {
        children.push(Element::Image(Image {
            x_mm: left,
            y_mm: top,
            width_mm: width as f64 * pixel,
            height_mm: height as f64 * pixel,
            width_px: width as u32,
            height_px: height as u32,
            rgba: view.rgba.clone(),
        }));
    }
    if style.stipple {
        let spacing_px = options.stipple_spacing_mm * scale / pixel;
        let dots = stipple_dots(&view.darkness, width, height, spacing_px, 0x5eed);
        children.push(Element::Dots(Dots {
            centers: dots.iter().map(|d| to_object(*d)).collect(),
            radius_mm: options.stipple_dot_radius_mm,
            color: BLACK,
        }));
    }
    if style.linear {
        // A quarter pixel: far below the 0.12 mm line's width at the drawing's resolution.
        let lines = visible_crease_lines(creases, view, 0.25);
        if !lines.is_empty() {
            let mut path = Path { segments: Vec::new(), fill: None, stroke: stroke(0.12) };
            for line in lines {
                let object: Vec<[f64; 2]> = line.into_iter().map(to_object).collect();
                path.extend_polyline(&object, false);
            }
            children.push(Element::Path(path));
        }
    }
    let mut outline = Path { segments: Vec::new(), fill: None, stroke: stroke(0.3) };
    for contour in outline_loops(&view.buffer, 0.8) {
        let points: Vec<[f64; 2]> = contour.iter().map(|p| to_object(*p)).collect();
        outline.extend_polyline(&points, true);
    }
    children.push(Element::Path(outline));
    children
}

/// The section left of the axis (x = -r), filled black or hatched, outlined.
fn add_section(canvas: &mut Canvas, section: &ProfileSection, fill: SectionFill) {
    let outlines: Vec<Vec<[f64; 2]>> =
        section.closed_outlines().into_iter().map(|o| o.into_iter().map(|p| [-p[0], p[1]]).collect()).collect();
    let mut shape = Path { segments: Vec::new(), fill: None, stroke: Some(canvas.stroke(0.25, &[])) };
    for o in &outlines {
        shape.extend_polyline(o, true);
    }
    match fill {
        SectionFill::Black => shape.fill = Some(BLACK),
        SectionFill::Hatched => {
            let spacing = 0.8 * canvas.scale;
            let hatch = hatch_lines(&outlines, spacing);
            let mut lines = Path { segments: Vec::new(), fill: None, stroke: Some(canvas.stroke(0.15, &[])) };
            for [a, b] in hatch {
                lines.segments.push(Segment::MoveTo(a));
                lines.segments.push(Segment::LineTo(b));
            }
            canvas.layer("section").push(Element::Path(lines));
        }
    }
    canvas.layer("section").push(Element::Path(shape));
}

/// 45-degree hatching of the polygons (even-odd), as segments.
fn hatch_lines(polygons: &[Vec<[f64; 2]>], spacing: f64) -> Vec<[[f64; 2]; 2]> {
    // In coordinates u = x - z (constant along a 45 deg line) the lines are u = k * spacing.
    let us = polygons.iter().flatten().map(|p| p[0] - p[1]);
    let (lo, hi) = us.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), u| (a.min(u), b.max(u)));
    let mut segments = Vec::new();
    if !lo.is_finite() {
        return segments;
    }
    let mut k = (lo / spacing).ceil();
    while k * spacing <= hi {
        let u = k * spacing;
        // Crossings with each edge, parameterised by v = x + z along the line.
        let mut crossings = Vec::new();
        for polygon in polygons {
            for i in 0..polygon.len() {
                let (a, b) = (polygon[i], polygon[(i + 1) % polygon.len()]);
                let (ua, ub) = (a[0] - a[1], b[0] - b[1]);
                if (ua <= u) != (ub <= u) {
                    let t = (u - ua) / (ub - ua);
                    let (x, z) = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]));
                    crossings.push(x + z);
                }
            }
        }
        crossings.sort_unstable_by(f64::total_cmp);
        for pair in crossings.chunks_exact(2) {
            let point = |v: f64| [(u + v) / 2.0, (v - u) / 2.0];
            segments.push([point(pair[0]), point(pair[1])]);
        }
        k += 1.0;
    }
    segments
}

/// The outer (largest radius) and inner outline of the section as functions of height.
struct OuterProfile {
    /// `(z, r_outer, r_inner)` from bottom to top.
    samples: Vec<(f64, f64, f64)>,
    outer_radius_max: f64,
    inner_radius_min: f64,
    z_bottom: f64,
    z_top: f64,
}

impl OuterProfile {
    fn of(section: &ProfileSection) -> Self {
        let outlines = section.closed_outlines();
        let (r0, r1, z0, z1) = section.bounds().unwrap_or((0.0, 0.0, 0.0, 0.0));
        let steps = 400;
        let mut samples = Vec::with_capacity(steps + 1);
        for i in 0..=steps {
            let z = z0 + (z1 - z0) * (i as f64 + 0.5) / (steps as f64 + 1.0);
            let (mut outer, mut inner) = (f64::NEG_INFINITY, f64::INFINITY);
            for o in &outlines {
                for k in 0..o.len() {
                    let (a, b) = (o[k], o[(k + 1) % o.len()]);
                    if (a[1] <= z) != (b[1] <= z) {
                        let r = a[0] + (z - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
                        outer = outer.max(r);
                        inner = inner.min(r);
                    }
                }
            }
            if outer.is_finite() {
                samples.push((z, outer, inner));
            }
        }
        OuterProfile { samples, outer_radius_max: r1, inner_radius_min: r0, z_bottom: z0, z_top: z1 }
    }

    /// The outer radius at the top (the rim radius, for a rim sherd).
    fn top_radius(&self) -> f64 {
        self.samples.last().map(|s| s.1).unwrap_or(self.outer_radius_max)
    }

    fn bottom_radius(&self) -> f64 {
        self.samples.first().map(|s| s.1).unwrap_or(self.outer_radius_max)
    }

    /// Heights where the outer profile turns sharply (carinations): the direction over
    /// 3 mm before and after differs by more than 25 degrees, at the local maximum.
    fn carinations(&self) -> Vec<(f64, f64)> {
        let n = self.samples.len();
        if n < 5 {
            return Vec::new();
        }
        let dz = (self.z_top - self.z_bottom) / n as f64;
        let window = ((3.0 / dz.max(1e-9)).round() as usize).clamp(1, n / 4 + 1);
        let turn: Vec<f64> = (0..n)
            .map(|i| {
                if i < window || i + window >= n {
                    return 0.0;
                }
                let (a, b, c) = (self.samples[i - window], self.samples[i], self.samples[i + window]);
                let before = (b.1 - a.1).atan2(b.0 - a.0);
                let after = (c.1 - b.1).atan2(c.0 - b.0);
                (after - before).abs().to_degrees()
            })
            .collect();
        // Only the strongest turn within the window counts, and not the rounding of the
        // rim's lip or the base's edge.
        let margin = 4.0;
        (1..n - 1)
            .filter(|&i| {
                let neighbourhood = &turn[i.saturating_sub(window)..(i + window + 1).min(n)];
                turn[i] > 25.0 && neighbourhood.iter().all(|&t| t <= turn[i]) && turn[i] > turn[i - 1]
            })
            .map(|i| (self.samples[i].0, self.samples[i].1))
            .filter(|&(z, _)| z > self.z_bottom + margin && z < self.z_top - margin)
            .collect()
    }
}

/// Horizontal lines at rim, carinations and base (rim and base where the measurements
/// found them preserved), the dashed prolongation of the outer profile mirrored at the
/// full diameter, and the diameter and sector labels.
fn add_annotations(canvas: &mut Canvas, profile: &OuterProfile, measurements: &Measurements, exterior_right: f64, options: &DrawOptions) {
    let scale = canvas.scale;
    let thin = canvas.stroke(0.15, &[]);
    let right_end = |r: f64| if options.prolongation { r } else { exterior_right.max(0.0) };
    let mut lines = Path { segments: Vec::new(), fill: None, stroke: Some(thin) };
    let top = profile.top_radius();
    if measurements.rim_radius_mm.is_some() {
        lines.extend_polyline(&[[-top, profile.z_top], [right_end(top), profile.z_top]], false);
    }
    for (z, r) in profile.carinations() {
        lines.extend_polyline(&[[-r, z], [right_end(r), z]], false);
    }
    if measurements.base_radius_mm.is_some() {
        let r = profile.bottom_radius();
        lines.extend_polyline(&[[-r, profile.z_bottom], [right_end(r), profile.z_bottom]], false);
    }
    if !lines.segments.is_empty() {
        canvas.layer("annotations").push(Element::Path(lines));
    }
    if options.prolongation {
        let mirrored: Vec<[f64; 2]> = profile.samples.iter().map(|&(z, r, _)| [r, z]).collect();
        let dashed = Path::polyline(&mirrored, false, None, Some(canvas.stroke(0.2, &[1.5, 1.0])));
        canvas.layer("annotations").push(Element::Path(dashed));
    }
    let mut labels = Vec::new();
    if let Some(d) = measurements.rim_diameter_mm {
        labels.push(match measurements.rim_diameter_interval_mm {
            Some([lo, hi]) => format!("Ø {d:.0} mm ({lo:.0}-{hi:.0})"),
            None => format!("Ø {d:.0} mm"),
        });
        labels.push(format!("{:.0}% of rim", measurements.sector_percent));
    } else {
        labels.push(format!("{:.0}° of circumference", measurements.sector_angle_deg));
    }
    if let Some(d) = measurements.base_diameter_mm {
        labels.push(format!("base Ø {d:.0} mm"));
    }
    for (i, label) in labels.into_iter().enumerate() {
        let z = profile.z_top + (6.0 + 4.5 * (2 - i.min(2)) as f64) * scale;
        canvas.text("annotations", [0.0, z], label, 3.2, Anchor::Middle);
    }
}

/// A scale bar of a round length (alternating black and white centimetres) with its
/// label, below the drawing.
fn add_scale_bar(canvas: &mut Canvas, z: f64, exterior_right: f64, profile: &OuterProfile) {
    let scale = canvas.scale;
    let left = -profile.outer_radius_max;
    let span = (exterior_right - left).max(10.0);
    let length = [10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0]
        .into_iter()
        .rev()
        .find(|&l| l <= 0.5 * span)
        .unwrap_or(10.0);
    let pieces = if length <= 100.0 { (length / 10.0) as usize } else { 5 };
    let step = length / pieces as f64;
    let height = 1.5 * scale;
    let mut group = Group { id: "scale-bar".into(), children: Vec::new() };
    for i in 0..pieces {
        let x = left + i as f64 * step;
        let fill = if i % 2 == 0 { BLACK } else { WHITE };
        let rect = [[x, z], [x + step, z], [x + step, z - height], [x, z - height]];
        group.children.push(Element::Path(Path::polyline(&rect, true, Some(fill), Some(canvas.stroke(0.15, &[])))));
    }
    let label = if length >= 10.0 { format!("{} cm", length / 10.0) } else { format!("{length} mm") };
    let text = |position, content: String, anchor| {
        Element::Text(Text { position, content, size_mm: 3.0, anchor, color: BLACK })
    };
    group.children.push(text([left, z - height - 4.0 * scale], "0".into(), Anchor::Middle));
    group.children.push(text([left + length, z - height - 4.0 * scale], label, Anchor::Middle));
    canvas.layer("scale-bar").push(Element::Group(group));
}

/// The colour scale of a regularity map: a vertical bar with values and title.
fn add_legend(canvas: &mut Canvas, map: &ColorMap, x: f64, top: f64) {
    let scale = canvas.scale;
    let (width, height, steps) = (4.0 * scale, 40.0 * scale, 32);
    let mut children = Vec::new();
    for (i, (_, color)) in map.legend(steps).iter().enumerate() {
        let z1 = top - height + height * (i + 1) as f64 / steps as f64;
        let z0 = top - height + height * i as f64 / steps as f64;
        let rect = [[x, z0], [x + width, z0], [x + width, z1], [x, z1]];
        children.push(Element::Path(Path::polyline(&rect, true, Some(*color), None)));
    }
    let frame = [[x, top - height], [x + width, top - height], [x + width, top], [x, top]];
    children.push(Element::Path(Path::polyline(&frame, true, None, Some(canvas.stroke(0.15, &[])))));
    for (value, z) in [(map.low, top - height), (0.5 * (map.low + map.high), top - height / 2.0), (map.high, top)] {
        // A diverging scale is signed: "-0.08 mm", "0 mm", "+0.08 mm".
        let content = match map.scale {
            ColorScale::Diverging if value.abs() < 1e-12 => format!("0 {}", map.unit),
            ColorScale::Diverging => format!("{value:+.2} {}", map.unit),
            ColorScale::Rainbow => format!("{value:.2} {}", map.unit),
        };
        children.push(Element::Text(Text {
            position: [x + width + 1.5 * scale, z - 1.0 * scale],
            content,
            size_mm: 2.6,
            anchor: Anchor::Start,
            color: BLACK,
        }));
    }
    children.push(Element::Text(Text {
        position: [x, top + 3.0 * scale],
        content: map.title.clone(),
        size_mm: 2.8,
        anchor: Anchor::Start,
        color: BLACK,
    }));
    canvas.layer("legend").extend(children);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hatching_fills_a_square_with_45_degree_lines() {
        let square = vec![vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]]];
        let lines = hatch_lines(&square, 1.0);
        assert!(lines.len() >= 18 && lines.len() <= 21, "{}", lines.len());
        for [a, b] in &lines {
            assert!(((b[1] - a[1]) - (b[0] - a[0])).abs() < 1e-9, "45 degrees");
            for p in [a, b] {
                assert!(p[0] >= -1e-9 && p[0] <= 10.0 + 1e-9 && p[1] >= -1e-9 && p[1] <= 10.0 + 1e-9);
            }
        }
    }
}
