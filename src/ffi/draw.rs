//! The archaeological drawing (`draw`): built once from a mesh and its axis, then written
//! to a file or to memory in SVG, EPS, PDF or PNG.

use std::ffi::c_char;

use super::buffer::{SherdBuffer, hand_out_bytes};
use super::error::{Failure, FfiResult};
use super::mesh::{SherdMesh, mesh_ref};
use super::options::{SherdDrawOptions, options_or_default};
use super::orient::{SherdAxis, read_axis};
use super::panic::guard;
use super::pointers::{borrow, path_from, require, write_out};
use super::status::SherdStatus;
use crate::draw::{Drawing, Format};

/// Output formats of `sherd_drawing_to_buffer`.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SherdFormat {
    /// SVG, one layer per part of the drawing (editable in Inkscape, Illustrator).
    Svg = 0,
    /// Encapsulated PostScript, level 3.
    Eps = 1,
    /// PDF 1.4.
    Pdf = 2,
    /// PNG at the options' resolution.
    Png = 3,
}

fn parse_format(value: u32) -> FfiResult<Format> {
    Ok(match value {
        0 => Format::Svg,
        1 => Format::Eps,
        2 => Format::Pdf,
        3 => Format::Png,
        other => return Err(Failure::invalid(format!("`format` {other} is not a SHERD_FORMAT_* value (0 to 3)"))),
    })
}

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
        let format = parse_format(format)?;
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
