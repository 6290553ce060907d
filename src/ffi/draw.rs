//! The archaeological drawing (`draw`): built once from a mesh and its axis, then written
//! to a file or to memory in SVG, EPS, PDF or PNG.

use std::ffi::c_char;

use super::buffer::{SherdBuffer, hand_out_bytes};
use super::error::FfiResult;
use super::mesh::{SherdMesh, mesh_ref};
use super::builder::{assign, builder, free_builder, new_builder, options_or_default, set};
use super::enums::{CEnum, SherdAnnotation, SherdFormat, SherdPlacement, SherdRegularity, SherdSectionFill, SherdStyle, flags};
use super::orient::{SherdAxis, read_axis};
use super::panic::guard;
use super::pointers::{borrow, path_from, require, text_from, write_out};
use super::status::SherdStatus;
use crate::draw::{Annotations, DrawOptions, Drawing, Style};

/// A finished drawing. Created by `sherd_drawing_build`, released with
/// `sherd_drawing_free`; writing it in several formats does not redo the work.
pub struct SherdDrawing {
    drawing: Drawing,
}

/// Builds the drawing of `mesh` (the full-resolution scan, in its own frame) oriented by
/// `axis`: axis as a dash-dot line, section and interior view on the left, exterior view
/// on the right, rim up, scale bar; styles and layout from `options` (NULL: light and
/// occlusion, natural size, 300 dpi, the most informative section).
///
/// # Safety
/// `mesh` must be a live handle; `axis` must have its `size` set; `options` NULL or live;
/// `out_drawing` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_drawing_build(
    mesh: *const SherdMesh,
    axis: *const SherdAxis,
    options: *const SherdDrawOptions,
    out_drawing: *mut *mut SherdDrawing,
) -> SherdStatus {
    guard("sherd_drawing_build", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let axis = unsafe { read_axis(axis, "axis") }?;
        let options = unsafe { options_or_default(options, |builder| &builder.options) }?;
        require(out_drawing.cast_const(), "out_drawing")?;
        let drawing = Drawing::build(mesh, &axis, &options)?;
        unsafe { write_out(out_drawing, Box::into_raw(Box::new(SherdDrawing { drawing })), "out_drawing") }
    })
}

unsafe fn drawing_ref<'a>(drawing: *const SherdDrawing) -> FfiResult<&'a Drawing> {
    unsafe { borrow(drawing, "drawing") }.map(|handle| &handle.drawing)
}

/// Writes the drawing to `path`, the format chosen by the extension (.svg, .eps, .pdf,
/// .png). Atomic: no half-written file on error.
///
/// # Safety
/// `drawing` must be a live handle; `path` a NUL-terminated string.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_drawing_write(drawing: *const SherdDrawing, path: *const c_char) -> SherdStatus {
    guard("sherd_drawing_write", || {
        let drawing = unsafe { drawing_ref(drawing) }?;
        let path = unsafe { path_from(path, "path") }?;
        Ok(drawing.write(&path)?)
    })
}

/// Writes the drawing in `format` (a `SHERD_FORMAT_*` value) into a new buffer
/// `*out_buffer`, for hosts that keep it in memory (a database, a preview).
///
/// # Safety
/// `drawing` must be a live handle; `out_buffer` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_drawing_to_buffer(
    drawing: *const SherdDrawing,
    format: u32,
    out_buffer: *mut *mut SherdBuffer,
) -> SherdStatus {
    guard("sherd_drawing_to_buffer", || {
        let drawing = unsafe { drawing_ref(drawing) }?;
        let format = SherdFormat::parse(format, "format")?;
        require(out_buffer.cast_const(), "out_buffer")?;
        let bytes = drawing.to_bytes(format)?;
        unsafe { hand_out_bytes(out_buffer, bytes) }
    })
}

/// Releases a drawing; NULL is ignored. Freeing twice is undefined behaviour.
///
/// # Safety
/// `drawing` must be NULL or a live handle not freed before.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_drawing_free(drawing: *mut SherdDrawing) {
    if !drawing.is_null() {
        drop(unsafe { Box::from_raw(drawing) });
    }
}

// ---------------------------------------------------------------- options

/// Options of `sherd_drawing_build`.
pub struct SherdDrawOptions {
    pub(crate) options: DrawOptions,
}

builder!(SherdDrawOptions => DrawOptions);

/// Applies `change` to a copy of the drawing options and keeps it only when the drawing
/// layer accepts the result, so that a refused value leaves the options as they were.
fn set_checked(function: &str, options: *mut SherdDrawOptions, change: impl FnOnce(&mut DrawOptions)) -> SherdStatus {
    set(function, options, |builder| {
        let mut candidate = builder.options.clone();
        change(&mut candidate);
        candidate.check()?;
        builder.options = candidate;
        Ok(())
    })
}

/// Creates drawing options with the library's defaults (light and occlusion, 1:1,
/// 300 dpi, black section, views beside the axis, interior view and prolongation on).
///
/// # Safety
/// `out_options` must be writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_draw_options_new(out_options: *mut *mut SherdDrawOptions) -> SherdStatus {
    guard("sherd_draw_options_new", || unsafe {
        new_builder(out_options, SherdDrawOptions { options: DrawOptions::default() })
    })
}

/// Releases drawing options; NULL is ignored.
///
/// # Safety
/// `options` must be NULL or a live handle, not freed before.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_draw_options_free(options: *mut SherdDrawOptions) {
    unsafe { free_builder(options) }
}

/// The styles: a non-empty bitwise or of `SHERD_STYLE_*` values.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_draw_options_set_style(options: *mut SherdDrawOptions, styles: u32) -> SherdStatus {
    assign("sherd_draw_options_set_style", options, |o| &mut o.style, || {
        Ok(Style::of(flags::<SherdStyle>("styles", styles, false)?))
    })
}

/// Publication scale 1:`denominator` (1 to 100; 1 is natural size).
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_draw_options_set_scale_denominator(options: *mut SherdDrawOptions, denominator: u32) -> SherdStatus {
    set_checked("sherd_draw_options_set_scale_denominator", options, |draw| draw.scale_denominator = denominator)
}

/// Resolution of raster content and PNG output, dots per inch (10 to 4800).
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_draw_options_set_dpi(options: *mut SherdDrawOptions, dpi: f64) -> SherdStatus {
    set_checked("sherd_draw_options_set_dpi", options, |draw| draw.dpi = dpi)
}

/// Angle of the section about the axis, radians from the fragment's centroid; NaN picks
/// the most informative profile (the default).
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_draw_options_set_section_angle_rad(options: *mut SherdDrawOptions, angle_rad: f64) -> SherdStatus {
    assign("sherd_draw_options_set_section_angle_rad", options, |o| &mut o.section_angle_rad, || {
        if angle_rad.is_nan() {
            return Ok(None);
        }
        crate::profile::section::check_angle(angle_rad)?;
        Ok(Some(angle_rad))
    })
}

/// Section fill: a `SHERD_SECTION_FILL_*` value.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_draw_options_set_section_fill(options: *mut SherdDrawOptions, fill: u32) -> SherdStatus {
    assign("sherd_draw_options_set_section_fill", options, |o| &mut o.section_fill, || SherdSectionFill::parse(fill, "fill"))
}

/// View placement: a `SHERD_PLACEMENT_*` value.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_draw_options_set_placement(options: *mut SherdDrawOptions, placement: u32) -> SherdStatus {
    assign("sherd_draw_options_set_placement", options, |o| &mut o.placement, || {
        SherdPlacement::parse(placement, "placement")
    })
}

/// The map of the regularity style: a `SHERD_REGULARITY_*` value.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_draw_options_set_regularity(options: *mut SherdDrawOptions, regularity: u32) -> SherdStatus {
    assign("sherd_draw_options_set_regularity", options, |o| &mut o.regularity, || SherdRegularity::parse(regularity, "regularity"))
}

/// Whether the interior view is drawn left of the axis, and whether the outer profile is
/// prolonged (dashed) to the full diameter.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_draw_options_set_views(options: *mut SherdDrawOptions, interior_view: bool, prolongation: bool) -> SherdStatus {
    set("sherd_draw_options_set_views", options, |builder| {
        builder.options.interior_view = interior_view;
        builder.options.prolongation = prolongation;
        Ok(())
    })
}

/// Whether the interior view is drawn between the section and the axis (default true);
/// the `interior_view` of `sherd draw --interior-view`, Python, Blender and MeshLab.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_draw_options_set_interior_view(options: *mut SherdDrawOptions, interior_view: bool) -> SherdStatus {
    assign("sherd_draw_options_set_interior_view", options, |o| &mut o.interior_view, || Ok(interior_view))
}

/// Whether the outer profile is prolonged, dashed, to the full diameter (default true).
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_draw_options_set_prolongation(options: *mut SherdDrawOptions, prolongation: bool) -> SherdStatus {
    assign("sherd_draw_options_set_prolongation", options, |o| &mut o.prolongation, || Ok(prolongation))
}

/// The measurements written under the drawing: a bitwise or of `SHERD_ANNOTATION_*`
/// values, 0 for none (the default). Each is left out where it was not measured. Other
/// bits are refused and leave the options as they were.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_draw_options_set_annotations(options: *mut SherdDrawOptions, annotations: u32) -> SherdStatus {
    assign("sherd_draw_options_set_annotations", options, |o| &mut o.annotations, || {
        let mut chosen = Annotations::default();
        for kind in flags::<SherdAnnotation>("annotations", annotations, true)? {
            *chosen.flag_mut(kind) = true;
        }
        Ok(chosen)
    })
}

/// A title (inventory number...) as a NUL-terminated UTF-8 string; NULL removes it.
///
/// # Safety
/// `options` must be a live handle; `title` NULL or a NUL-terminated string.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_draw_options_set_title(options: *mut SherdDrawOptions, title: *const std::ffi::c_char) -> SherdStatus {
    assign("sherd_draw_options_set_title", options, |o| &mut o.title, || {
        if title.is_null() {
            return Ok(None);
        }
        Ok(Some(unsafe { text_from(title, "title") }?.to_string()))
    })
}
