//! The exterior and interior views: rendered from the shaded surface, moved to their half
//! beside the axis, cut at it, and turned into drawing elements.

use crate::draw::model::{Dots, Element, Image, Path, Stroke};
use crate::draw::stipple::stipple_dots;
use crate::draw::view::{crease_edges, outline_loops, render_view, visible_crease_lines, OcclusionField, Shading, Surface, View};
use crate::draw::{DrawOptions, Placement, RegularityKind};
use crate::mesh::Mesh;
use crate::orient::Axis;
use crate::profile::regularity::{axis_distance_map, ideal_vessel_map, ColorMap};
use crate::profile::section::{angular_extent, ProfileSection};
use crate::Result;

use super::ambient::occlusion_field;
use super::canvas::translate_element;
use super::profile::OuterProfile;
use super::BLACK;

/// Gap between the axis and a view drawn beside it, paper mm.
const GAP_MM: f64 = 4.0;

/// The rendered views and the regularity map their colours follow.
pub(super) struct Views {
    /// `None` when the whole view was cut away.
    pub(super) exterior: Option<PlacedView>,
    pub(super) interior: Option<PlacedView>,
    pub(super) regularity_map: Option<ColorMap>,
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
pub(super) struct PlacedView {
    view: View,
    /// How far the view moved along x from where it was rendered, object mm.
    shift: f64,
    /// Raster image, stipple dots, crease lines and outline, in place.
    pub(super) elements: Vec<Element>,
}

impl PlacedView {
    /// The right edge of the view, object mm.
    pub(super) fn right(&self) -> f64 {
        self.view.top_left()[0] + self.shift + self.view.camera.width as f64 * self.view.camera.pixel_mm
    }

    /// Whether a covered pixel lies within `reach` object mm of `[x, z]`.
    pub(super) fn covers(&self, point: [f64; 2], reach: f64) -> bool {
        let [left, top] = self.view.top_left();
        let pixel = self.view.camera.pixel_mm;
        let (width, height) = (self.view.camera.width as i64, self.view.camera.height as i64);
        let column = ((point[0] - left - self.shift) / pixel).floor() as i64;
        let row = ((top - point[1]) / pixel).floor() as i64;
        let k = (reach / pixel).ceil() as i64;
        (row - k..=row + k).filter(|r| (0..height).contains(r)).any(|r| {
            (column - k..=column + k)
                .filter(|c| (0..width).contains(c))
                .any(|c| self.view.buffer.face[(r * width + c) as usize] != crate::draw::raster::NO_FACE)
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

/// Shading data (occlusion, regularity) and the crease edges side by side, then the
/// exterior and interior views, each on its own task, placed and cut at the axis.
pub(super) fn draw_views(
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
