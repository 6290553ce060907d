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

use crate::draw::model::{Anchor, Drawing, Element, Path, Rgb};
use crate::draw::DrawOptions;
use crate::mesh::normals::{compute_vertex_normals, NormalWeighting};
use crate::mesh::{planar_length, Mesh};
use crate::orient::Axis;
use crate::profile::measure::{measure, MeasureOptions};
use crate::profile::section::{most_informative_angle, oriented_frame, section_of_oriented};
use crate::{Error, Result};

mod ambient;
mod canvas;
mod labels;
mod legend;
mod lines;
mod preservation;
mod profile;
mod scale_bar;
mod section;
mod shelf;
mod views;

use canvas::Canvas;
use labels::{add_labels, annotations};
use legend::legend;
use lines::{add_lines, add_outline};
use preservation::preservation_figures;
use profile::OuterProfile;
use scale_bar::scale_bar;
use section::add_section;
use shelf::Shelf;
use views::{draw_views, PlacedView, Views};

const BLACK: Rgb = [0, 0, 0];
const WHITE: Rgb = [255, 255, 255];
/// How far the axis line reaches beyond the fragment's top and bottom, paper mm.
const AXIS_OVERSHOOT_MM: f64 = 4.0;
/// Size of the diameter labels and annotations, paper mm.
const LABEL_SIZE_MM: f64 = 3.2;

/// Most pixels a rendered view may have: 50 million, about 800 MB of depth, face, colour
/// and darkness buffers. A scan in metres read as millimetres, or 4800 dpi at natural
/// size of a large sherd, would otherwise allocate without bound.
const MAX_VIEW_PIXELS: f64 = 50e6;

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
