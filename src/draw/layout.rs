//! The layout of the archaeological illustration (Wilczek et al. 2018, sections 2.4.1
//! and 2.4.2; Griffiths, Jenner and Wilson 1990): the
//! axis as a vertical dash-dot line; left of it the section at its true radius, filled,
//! and the interior view between the section and the axis; right of it the exterior view
//! inside the vessel's outline (the outer profile mirrored, dashed where the view does
//! not show it); horizontal lines at rim, carinations and base across both halves; the
//! diameter above; below, the scale bar, the preservation figure of the rim (or base) and
//! the optional annotations, in rows that never overlap.
//!
//! A view that does not fit its half is cut at the axis, as an illustrator cuts it: it is
//! never moved outside the section, so the figure stays about twice the vessel's largest
//! radius wide.
//!
//! Everything is first placed in object millimetres (x right with the axis at 0, z up);
//! [`Canvas::finish`] maps it to paper millimetres at the publication scale.

use rayon::prelude::*;

use crate::draw::model::{bounds_of, element_extent, Anchor, Dots, Drawing, Element, Group, Image, Path, Rgb, Segment, Stroke, Text};
use crate::draw::stipple::stipple_dots;
use crate::draw::view::{crease_edges, outline_loops, render_view, visible_crease_lines, OcclusionField, Shading, Surface, View};
use crate::draw::{Annotations, DrawOptions, Placement, RegularityKind, SectionFill};
use crate::mesh::normals::{compute_vertex_normals, NormalWeighting};
use super::occlusion::near_and_far_light;
use crate::mesh::{planar_length, Mesh};
use crate::orient::Axis;
use crate::profile::measure::{measure, MeasureOptions, Measurements};
use crate::profile::regularity::{axis_distance_map, ideal_vessel_map, ColorMap, ColorScale};
use crate::profile::section::{angular_extent, most_informative_angle, oriented_frame, section_of_oriented, ProfileSection};
use crate::statistics::central_range;
use crate::{Error, Result};

const BLACK: Rgb = [0, 0, 0];
const WHITE: Rgb = [255, 255, 255];
/// Paper margin around everything, mm.
const MARGIN_MM: f64 = 8.0;
/// Gap between the axis and a view drawn beside it, paper mm.
const GAP_MM: f64 = 4.0;
/// How far the axis line reaches beyond the fragment's top and bottom, paper mm.
const AXIS_OVERSHOOT_MM: f64 = 4.0;
/// Space between the items below the drawing and between their rows, paper mm.
const ITEM_GAP_MM: f64 = 4.0;
/// Size of the diameter labels and annotations, paper mm.
const LABEL_SIZE_MM: f64 = 3.2;
/// Radius of the preservation figure's circle, paper mm.
const PRESERVATION_RADIUS_MM: f64 = 5.0;

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

    /// The rectangle (object millimetres, z up) `elements` cover.
    fn bounds(&self, elements: &[Element]) -> Option<[f64; 4]> {
        bounds_of(|include| elements.iter().for_each(|e| element_extent(e, self.scale, true, include)))
    }

    /// Maps object coordinates to paper millimetres and wraps up the drawing.
    fn finish(mut self, dpi: f64) -> Drawing {
        let all: Vec<Element> = self.layers.iter().map(|g| Element::Group(g.clone())).collect();
        let [x0, z0, x1, z1] = self.bounds(&all).unwrap_or([0.0, 0.0, 1.0, 1.0]);
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
    let profile = OuterProfile::of(&section);
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
        || draw_views(mesh, axis, &oriented, &normals, &section, &profile, options),
    );
    let Views { exterior, interior, regularity_map } = drawn?;
    let scale = options.scale_denominator as f64;
    let mut canvas = Canvas { scale, layers: Vec::new() };
    let exterior_right = exterior.as_ref().map_or(0.0, PlacedView::right);
    if let Some(view) = &exterior {
        canvas.layer("exterior-view").extend(view.elements.iter().cloned());
    }
    if let Some(view) = &interior {
        canvas.layer("interior-view").extend(view.elements.iter().cloned());
    }
    add_section(&mut canvas, &section, options.section_fill);
    let z_top = oriented.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max);
    let z_bottom = oriented.iter().map(|p| p.z).fold(f64::INFINITY, f64::min);
    let overshoot = AXIS_OVERSHOOT_MM * scale;
    let axis_path = Path::polyline(
        &[[0.0, z_top + overshoot], [0.0, z_bottom - overshoot]],
        false,
        None,
        Some(canvas.stroke(0.25, &[4.0, 1.0, 0.5, 1.0])),
    );
    canvas.layer("axis").push(Element::Path(axis_path));
    add_lines(&mut canvas, &profile, &measurements, exterior_right, options);
    if options.prolongation {
        add_outline(&mut canvas, &profile, &measurements, exterior.as_ref());
    }
    // Everything else goes above and below the fragment, within the vessel's width.
    let largest_radius = oriented.iter().map(|p| planar_length(p.x, p.y)).fold(profile.outer_radius_max, f64::max);
    let labels_top = add_labels(&mut canvas, &measurements, z_top + overshoot);
    if let Some(title) = &options.title {
        let size = 4.0;
        canvas.text("title", [-largest_radius, labels_top + 0.25 * size * scale + 2.0 * scale], title.clone(), size, Anchor::Start);
    }
    let mut shelf = Shelf::below(&canvas, -largest_radius, largest_radius, z_bottom - overshoot);
    let mut bar = vec![scale_bar(&canvas, 2.0 * largest_radius)];
    shelf.place(&canvas, &mut bar);
    canvas.layer("scale-bar").extend(bar);
    for mut figure in preservation_figures(&canvas, &measurements) {
        shelf.place(&canvas, &mut figure);
        canvas.layer("preservation").extend(figure);
    }
    let mut notes = annotations(&measurements, options.annotations, scale);
    if !notes.is_empty() {
        shelf.place(&canvas, &mut notes);
        canvas.layer("annotations").extend(notes);
    }
    if let Some(map) = &regularity_map {
        let mut legend = legend(&canvas, map);
        shelf.place(&canvas, &mut legend);
        canvas.layer("legend").extend(legend);
    }
    Ok(canvas.finish(options.dpi))
}

impl Canvas {
    fn text(&mut self, layer: &str, position: [f64; 2], content: String, size_mm: f64, anchor: Anchor) {
        self.layer(layer).push(Element::Text(Text { position, content, size_mm, anchor, color: BLACK }));
    }
}

/// Rows of items below the drawing, filled left to right between `left` and `right`
/// (object millimetres) and wrapped to a new row when the next item does not fit: no item
/// overlaps another or the drawing above.
struct Shelf {
    left: f64,
    right: f64,
    gap: f64,
    cursor: f64,
    row_top: f64,
    row_bottom: f64,
}

impl Shelf {
    fn below(canvas: &Canvas, left: f64, right: f64, z: f64) -> Shelf {
        let gap = ITEM_GAP_MM * canvas.scale;
        Shelf { left, right, gap, cursor: left, row_top: z - gap, row_bottom: z - gap }
    }

    /// Moves `item` (built anywhere) to the next free place.
    fn place(&mut self, canvas: &Canvas, item: &mut [Element]) {
        let Some([x0, z0, x1, z1]) = canvas.bounds(item) else { return };
        if self.cursor > self.left && self.cursor + (x1 - x0) > self.right {
            self.row_top = self.row_bottom - self.gap;
            self.cursor = self.left;
        }
        let offset = [self.cursor - x0, self.row_top - z1];
        item.iter_mut().for_each(|e| translate_element(e, offset));
        self.cursor += x1 - x0 + self.gap;
        self.row_bottom = self.row_bottom.min(self.row_top - (z1 - z0));
    }
}

/// The rendered views and the regularity map their colours follow.
struct Views {
    /// `None` when the whole view was cut away.
    exterior: Option<PlacedView>,
    interior: Option<PlacedView>,
    regularity_map: Option<ColorMap>,
}

/// Which half of the drawing a view belongs to.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Half {
    /// Right of the axis: the outside of the vessel.
    Exterior,
    /// Left of the axis, between the section and the axis: the inside.
    Interior,
}

/// A view at its place: cut at the axis, its vector content in object millimetres.
struct PlacedView {
    view: View,
    /// How far the view moved along x from where it was rendered, object mm.
    shift: f64,
    /// Raster image, stipple dots, crease lines and outline, in place.
    elements: Vec<Element>,
}

impl PlacedView {
    /// The right edge of the view, object mm.
    fn right(&self) -> f64 {
        self.view.top_left()[0] + self.shift + self.view.camera.width as f64 * self.view.camera.pixel_mm
    }

    /// Whether a covered pixel lies within `reach` object mm of `[x, z]`.
    fn covers(&self, point: [f64; 2], reach: f64) -> bool {
        let [left, top] = self.view.top_left();
        let pixel = self.view.camera.pixel_mm;
        let (width, height) = (self.view.camera.width as i64, self.view.camera.height as i64);
        let column = ((point[0] - left - self.shift) / pixel).floor() as i64;
        let row = ((top - point[1]) / pixel).floor() as i64;
        let k = (reach / pixel).ceil() as i64;
        (row - k..=row + k).filter(|r| (0..height).contains(r)).any(|r| {
            (column - k..=column + k)
                .filter(|c| (0..width).contains(c))
                .any(|c| self.view.buffer.face[(r * width + c) as usize] != super::raster::NO_FACE)
        })
    }
}

/// How far along x a rendered view moves to its place, object mm.
///
/// The exterior view stays inside the vessel's outline, the outer profile mirrored right
/// of the axis, touching it where they meet: at the true distance it already is (its
/// edge at angle 0 is the profile), beside the axis it starts [`GAP_MM`] right of the
/// axis unless it would cross the outline there. The interior view stays right of the
/// section: beside the axis against the section's inner side, at the true distance where
/// it is (its edge is the section's outer side), moved right only where the fragment's
/// edge passes the section.
fn view_shift(view: &View, half: Half, placement: Placement, profile: &OuterProfile, gap: f64) -> f64 {
    let [left, top] = view.top_left();
    let pixel = view.camera.pixel_mm;
    // Per covered row: its height and the object x of its first and last covered pixel's outer edges.
    let rows: Vec<(f64, f64, f64)> = view
        .covered_columns()
        .iter()
        .enumerate()
        .filter_map(|(y, c)| c.map(|(a, b)| (top - (y as f64 + 0.5) * pixel, left + a as f64 * pixel, left + (b + 1) as f64 * pixel)))
        .collect();
    if rows.is_empty() {
        return 0.0;
    }
    let right_of = |radius_at: &dyn Fn(f64) -> f64| rows.iter().map(|&(z, l, _)| -radius_at(z) - l).fold(f64::NEG_INFINITY, f64::max);
    match half {
        Half::Exterior => {
            let wanted = match placement {
                Placement::Beside => gap - rows.iter().map(|r| r.1).fold(f64::INFINITY, f64::min),
                Placement::TrueDistance => 0.0,
            };
            let room = rows.iter().map(|&(z, _, r)| profile.outer_at(z) - r).fold(f64::INFINITY, f64::min);
            wanted.min(room)
        }
        Half::Interior => match placement {
            Placement::Beside => right_of(&|z| profile.inner_at(z)),
            Placement::TrueDistance => right_of(&|z| profile.outer_at(z)).max(0.0),
        },
    }
}

/// Cuts a view moved by `shift` at the axis: the columns on the other half go.
fn cut_at_axis(view: &mut View, half: Half, shift: f64) {
    let left = view.top_left()[0] + shift;
    let pixel = view.camera.pixel_mm;
    let width = view.camera.width;
    // Columns whose left (right) edge is at or beyond the axis, counted from the left.
    let axis_column = -left / pixel;
    match half {
        Half::Exterior => view.crop_columns(axis_column.ceil().clamp(0.0, width as f64) as usize, width),
        Half::Interior => view.crop_columns(0, axis_column.floor().clamp(0.0, width as f64) as usize),
    }
}

fn translate_element(e: &mut Element, offset: [f64; 2]) {
    let moved = |q: &mut [f64; 2]| {
        q[0] += offset[0];
        q[1] += offset[1];
    };
    match e {
        Element::Path(p) => p.segments.iter_mut().for_each(|s| match s {
            Segment::MoveTo(q) | Segment::LineTo(q) => moved(q),
            Segment::Close => {}
        }),
        Element::Dots(d) => d.centers.iter_mut().for_each(moved),
        Element::Text(t) => moved(&mut t.position),
        Element::Image(i) => {
            i.x_mm += offset[0];
            i.y_mm += offset[1];
        }
        Element::Group(g) => g.children.iter_mut().for_each(|c| translate_element(c, offset)),
    }
}

/// Shading data (occlusion, regularity) and the crease edges side by side, then the
/// exterior and interior views, each on its own task, placed and cut at the axis.
fn draw_views(
    mesh: &Mesh,
    axis: &Axis,
    oriented: &[crate::mesh::Point],
    normals: &[crate::mesh::Vector],
    section: &ProfileSection,
    profile: &OuterProfile,
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
    let gap = GAP_MM * options.scale_denominator as f64;
    let draw = |turn: f64, half: Half| {
        let mut view = render_view(&surface, turn, pixel_mm, &shading);
        let shift = view_shift(&view, half, options.placement, profile, gap);
        cut_at_axis(&mut view, half, shift);
        if view.camera.width == 0 {
            return None;
        }
        let mut elements = view_elements(&view, &creases, options);
        elements.iter_mut().for_each(|e| translate_element(e, [shift, 0.0]));
        Some(PlacedView { view, shift, elements })
    };
    let (exterior, interior) = rayon::join(
        || draw(exterior_turn, Half::Exterior),
        || if options.interior_view { draw(interior_turn, Half::Interior) } else { None },
    );
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
    let (near, full) = rayon::join(|| smooth_over_neighbours(mesh, light.near, 4), || smooth_over_neighbours(mesh, light.full, 4));
    let far_factor: Vec<f32> = full.iter().zip(&near).map(|(&f, &n)| if n > 0.0 { (f / n).min(1.0) } else { 1.0 }).collect();
    let (low, high) = central_range(full.iter().copied()).unwrap_or((0.0, 1.0));
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
            // A crease whose middle is in view may end beyond a cut at the axis.
            for piece in lines.iter().flat_map(|line| clip_to_columns(line, width as f64)) {
                let object: Vec<[f64; 2]> = piece.into_iter().map(to_object).collect();
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

/// The pieces of a polyline (pixel coordinates) between the columns 0 and `width`.
fn clip_to_columns(line: &[[f64; 2]], width: f64) -> Vec<Vec<[f64; 2]>> {
    let inside = |p: &[f64; 2]| (0.0..=width).contains(&p[0]);
    let mut pieces = Vec::new();
    let mut current: Vec<[f64; 2]> = Vec::new();
    for (i, p) in line.iter().enumerate() {
        if i > 0 && inside(&line[i - 1]) != inside(p) {
            let q = line[i - 1];
            let edge = if p[0].max(q[0]) > width { width } else { 0.0 };
            let t = (edge - q[0]) / (p[0] - q[0]);
            current.push([edge, q[1] + t * (p[1] - q[1])]);
        }
        if inside(p) {
            current.push(*p);
        } else if !current.is_empty() {
            pieces.push(std::mem::take(&mut current));
        }
    }
    pieces.push(current);
    pieces.retain(|piece| piece.len() >= 2);
    pieces
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
        SectionFill::Black => {
            shape.fill = Some(BLACK);
            canvas.layer("section").push(Element::Path(shape));
        }
        SectionFill::Hatched => {
            // Filled white under the hatching: the interior view it covers must not show through.
            shape.fill = Some(WHITE);
            canvas.layer("section").push(Element::Path(shape));
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

    /// The outer and inner radius at height `z`, interpolated between the samples and
    /// held at the end samples beyond them.
    fn radii_at(&self, z: f64) -> (f64, f64) {
        let samples = &self.samples;
        let Some(first) = samples.first() else { return (self.outer_radius_max, self.inner_radius_min) };
        let i = samples.partition_point(|s| s.0 < z);
        if i == 0 {
            return (first.1, first.2);
        }
        if i == samples.len() {
            let last = samples[i - 1];
            return (last.1, last.2);
        }
        let (a, b) = (samples[i - 1], samples[i]);
        let t = (z - a.0) / (b.0 - a.0).max(1e-12);
        (a.1 + t * (b.1 - a.1), a.2 + t * (b.2 - a.2))
    }

    fn outer_at(&self, z: f64) -> f64 {
        self.radii_at(z).0
    }

    fn inner_at(&self, z: f64) -> f64 {
        self.radii_at(z).1
    }

    /// The samples on the outer skin: without the ends where the outermost crossing runs
    /// along a slanted break face (the wall narrows there to nothing), unless that end is
    /// the base (`keep_bottom`) or the rim (`keep_top`), whose rounding is the vessel's own.
    fn outer_skin(&self, keep_bottom: bool, keep_top: bool) -> &[(f64, f64, f64)] {
        let mut widths: Vec<f64> = self.samples.iter().map(|s| s.1 - s.2).collect();
        if widths.is_empty() {
            return &self.samples;
        }
        let wall = crate::statistics::quantile(&mut widths, 0.5);
        let on_wall = |s: &(f64, f64, f64)| s.1 - s.2 >= 0.6 * wall;
        let start = if keep_bottom { 0 } else { self.samples.iter().position(on_wall).unwrap_or(0) };
        let end = if keep_top { self.samples.len() } else { self.samples.iter().rposition(on_wall).map_or(self.samples.len(), |i| i + 1) };
        &self.samples[start..end.max(start)]
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
/// found them preserved), across both halves: to the mirrored outline when it is drawn,
/// else to the exterior view's edge.
fn add_lines(canvas: &mut Canvas, profile: &OuterProfile, measurements: &Measurements, exterior_right: f64, options: &DrawOptions) {
    let right_end = |r: f64| if options.prolongation { r } else { exterior_right.max(0.0) };
    let mut lines = Path { segments: Vec::new(), fill: None, stroke: Some(canvas.stroke(0.15, &[])) };
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
        canvas.layer("lines").push(Element::Path(lines));
    }
}

/// The vessel's outline right of the axis: the outer profile mirrored at its true radius,
/// dashed, where the exterior view does not already draw it. Beside the axis the view
/// touches it; at the true distance the view's edge is the profile itself.
fn add_outline(canvas: &mut Canvas, profile: &OuterProfile, measurements: &Measurements, exterior: Option<&PlacedView>) {
    // Near the view its own outline stands for the vessel's: at the true distance the
    // view's edge is a break beside the section's angle, a little off the section's radius
    // on a vessel that is not quite round.
    let reach = 1.5 * canvas.scale;
    let mut dashed = Path { segments: Vec::new(), fill: None, stroke: Some(canvas.stroke(0.2, &[1.5, 1.0])) };
    let mut run: Vec<[f64; 2]> = Vec::new();
    let outer_skin = profile.outer_skin(measurements.base_radius_mm.is_some(), measurements.rim_radius_mm.is_some());
    for &(z, r, _) in outer_skin {
        let point = [r, z];
        if exterior.is_some_and(|view| view.covers(point, reach)) {
            if run.len() >= 2 {
                dashed.extend_polyline(&run, false);
            }
            run.clear();
        } else {
            run.push(point);
        }
    }
    if run.len() >= 2 {
        dashed.extend_polyline(&run, false);
    }
    if !dashed.segments.is_empty() {
        canvas.layer("outline").push(Element::Path(dashed));
    }
}

/// The diameters, centred on the axis above `z` (the axis line's top), one line each;
/// returns the height of the top of the last (`z` when there is none).
fn add_labels(canvas: &mut Canvas, measurements: &Measurements, z: f64) -> f64 {
    let scale = canvas.scale;
    let mut labels = Vec::new();
    if let Some(d) = measurements.rim_diameter_mm {
        labels.push(match measurements.rim_diameter_interval_mm {
            Some([lo, hi]) => format!("Ø {d:.0} mm ({lo:.0}-{hi:.0})"),
            None => format!("Ø {d:.0} mm"),
        });
    }
    if let Some(d) = measurements.base_diameter_mm {
        labels.push(match measurements.base_diameter_interval_mm {
            Some([lo, hi]) => format!("base Ø {d:.0} mm ({lo:.0}-{hi:.0})"),
            None => format!("base Ø {d:.0} mm"),
        });
    }
    let line = 1.4 * LABEL_SIZE_MM * scale;
    let mut baseline = z + 0.25 * LABEL_SIZE_MM * scale + 1.5 * scale;
    let mut top = z;
    // The base's label nearest the drawing, the rim's above it, as the edges stand.
    for label in labels.into_iter().rev() {
        canvas.text("labels", [0.0, baseline], label, LABEL_SIZE_MM, Anchor::Middle);
        top = baseline + 0.8 * LABEL_SIZE_MM * scale;
        baseline += line;
    }
    top
}

/// A scale bar of a round length at most half of `span` (alternating black and white
/// centimetres) with its label, as a group at the origin.
fn scale_bar(canvas: &Canvas, span: f64) -> Element {
    let scale = canvas.scale;
    let length = [10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0]
        .into_iter()
        .rev()
        .find(|&l| l <= 0.5 * span)
        .unwrap_or(10.0);
    let pieces = if length <= 100.0 { (length / 10.0) as usize } else { 5 };
    let step = length / pieces as f64;
    let height = 1.5 * scale;
    let mut group = Group { id: "scale-bar-graphic".into(), children: Vec::new() };
    for i in 0..pieces {
        let x = i as f64 * step;
        let fill = if i % 2 == 0 { BLACK } else { WHITE };
        let rect = [[x, 0.0], [x + step, 0.0], [x + step, -height], [x, -height]];
        group.children.push(Element::Path(Path::polyline(&rect, true, Some(fill), Some(canvas.stroke(0.15, &[])))));
    }
    let label = if length >= 10.0 { format!("{} cm", length / 10.0) } else { format!("{length} mm") };
    let text = |position, content: String| Element::Text(Text { position, content, size_mm: 3.0, anchor: Anchor::Middle, color: BLACK });
    group.children.push(text([0.0, -height - 4.0 * scale], "0".into()));
    group.children.push(text([length, -height - 4.0 * scale], label));
    Element::Group(group)
}

/// The preserved share of the rim and of the base, each as the usual figure: a thin
/// circle with the preserved arc drawn bold at its top, and the share written under it
/// ("9% of rim", the rim's own arc, not the whole sherd's). A fragment with neither gives
/// the arc of circumference it spans. Each figure is a group at the origin.
fn preservation_figures(canvas: &Canvas, measurements: &Measurements) -> Vec<Vec<Element>> {
    let mut arcs = Vec::new();
    if let Some(deg) = measurements.rim_sector_deg {
        arcs.push(("rim", deg));
    }
    if let Some(deg) = measurements.base_sector_deg {
        arcs.push(("base", deg));
    }
    if arcs.is_empty() && measurements.sector_angle_deg > 0.0 {
        arcs.push(("circumference", measurements.sector_angle_deg));
    }
    let scale = canvas.scale;
    let radius = PRESERVATION_RADIUS_MM * scale;
    let circle_points = |from_deg: f64, to_deg: f64| -> Vec<[f64; 2]> {
        let steps = ((to_deg - from_deg).abs() / 3.0).ceil().max(2.0) as usize;
        (0..=steps)
            .map(|i| {
                let a = (from_deg + (to_deg - from_deg) * i as f64 / steps as f64).to_radians();
                [radius * a.cos(), radius * a.sin()]
            })
            .collect()
    };
    arcs.into_iter()
        .map(|(edge, deg)| {
            let deg = deg.clamp(0.0, 360.0);
            let mut children = vec![
                Element::Path(Path::polyline(&circle_points(0.0, 360.0), true, None, Some(canvas.stroke(0.15, &[])))),
                Element::Path(Path::polyline(&circle_points(90.0 - deg / 2.0, 90.0 + deg / 2.0), false, None, Some(canvas.stroke(0.9, &[])))),
            ];
            let percent = deg / 360.0 * 100.0;
            let content = if edge == "circumference" { format!("{deg:.0}° of circumference") } else { format!("{percent:.0}% of {edge}") };
            children.push(Element::Text(Text {
                position: [0.0, -radius - (1.5 + 0.8 * LABEL_SIZE_MM) * scale],
                content,
                size_mm: LABEL_SIZE_MM,
                anchor: Anchor::Middle,
                color: BLACK,
            }));
            vec![Element::Group(Group { id: format!("preservation-{edge}"), children })]
        })
        .collect()
}

/// The annotations asked for, one line each, left-aligned at the origin.
fn annotations(measurements: &Measurements, wanted: Annotations, scale: f64) -> Vec<Element> {
    let mut lines = Vec::new();
    if wanted.height {
        lines.push(format!("height {:.0} mm", measurements.height_mm));
    }
    if wanted.wall_thickness {
        if let Some(t) = measurements.wall_thickness_mm {
            lines.push(format!("wall {t:.1} mm"));
        }
    }
    if wanted.capacity {
        if let Some(litres) = measurements.capacity_litres {
            lines.push(format!("capacity {litres:.2} l"));
        }
    }
    lines
        .into_iter()
        .enumerate()
        .map(|(i, content)| {
            Element::Text(Text {
                position: [0.0, -(i as f64) * 1.4 * LABEL_SIZE_MM * scale],
                content,
                size_mm: LABEL_SIZE_MM,
                anchor: Anchor::Start,
                color: BLACK,
            })
        })
        .collect()
}

/// The colour scale of a regularity map: a vertical bar with values and title, its top
/// left corner at the origin.
fn legend(canvas: &Canvas, map: &ColorMap) -> Vec<Element> {
    let scale = canvas.scale;
    let (x, top) = (0.0, 0.0);
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
    children
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
