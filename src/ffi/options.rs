//! Option builders: opaque handles holding the Rust options of one operation, created
//! with their defaults, changed through typed setters that check each value, and passed
//! (or NULL for the defaults) to the operation. Freeing a builder twice is undefined
//! behaviour, as with `free`; set your pointer to NULL after `_free`.

use super::error::{Failure, FfiResult};
use super::panic::guard;
use super::pointers::{borrow, borrow_mut, require, write_out};
use super::status::SherdStatus;
use crate::mesh::repair::RepairOptions;
use crate::orient::{ManualOptions, OrientOptions};

/// Creates a builder holding `T::default()`.
unsafe fn new_builder<B>(out: *mut *mut B, builder: B) -> FfiResult {
    require(out.cast_const(), "out_options")?;
    unsafe { write_out(out, Box::into_raw(Box::new(builder)), "out_options") }
}

/// Frees a builder; NULL is ignored.
unsafe fn free_builder<B>(builder: *mut B) {
    if !builder.is_null() {
        drop(unsafe { Box::from_raw(builder) });
    }
}

/// Runs a setter on the builder behind `options`.
fn set<B>(function: &str, options: *mut B, setter: impl FnOnce(&mut B) -> FfiResult) -> SherdStatus {
    guard(function, || setter(unsafe { borrow_mut(options, "options") }?))
}

/// The options behind a nullable builder pointer: the builder's, or the defaults.
pub(crate) unsafe fn options_or_default<B, T: Clone + Default>(options: *const B, get: impl FnOnce(&B) -> &T) -> FfiResult<T> {
    if options.is_null() {
        return Ok(T::default());
    }
    Ok(get(unsafe { borrow(options, "options") }?).clone())
}

fn finite_positive(value: f64, name: &str) -> FfiResult<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Failure::invalid(format!("`{name}` must be finite and positive, got {value}")))
    }
}

fn fraction(value: f64, name: &str) -> FfiResult<f64> {
    if value > 0.0 && value <= 1.0 {
        Ok(value)
    } else {
        Err(Failure::invalid(format!("`{name}` must be in (0, 1], got {value}")))
    }
}

fn positive_count(value: usize, name: &str) -> FfiResult<usize> {
    if value > 0 { Ok(value) } else { Err(Failure::invalid(format!("`{name}` must be at least 1"))) }
}

// ---------------------------------------------------------------- repair

/// Options of `sherd_mesh_repair`.
pub struct SherdRepairOptions {
    pub(crate) options: RepairOptions,
}

/// Creates repair options with the library's defaults.
///
/// # Safety
/// `out_options` must be writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_repair_options_new(out_options: *mut *mut SherdRepairOptions) -> SherdStatus {
    guard("sherd_repair_options_new", || unsafe {
        new_builder(out_options, SherdRepairOptions { options: RepairOptions::default() })
    })
}

/// Releases repair options; NULL is ignored.
///
/// # Safety
/// `options` must be NULL or a live handle, not freed before.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_repair_options_free(options: *mut SherdRepairOptions) {
    unsafe { free_builder(options) }
}

/// Merges vertices closer than `tolerance_mm` (finite, positive); 0 merges only exact
/// duplicates.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_repair_options_set_merge_tolerance_mm(options: *mut SherdRepairOptions, tolerance_mm: f64) -> SherdStatus {
    set("sherd_repair_options_set_merge_tolerance_mm", options, |builder| {
        builder.options.merge_tolerance_mm =
            if tolerance_mm == 0.0 { None } else { Some(finite_positive(tolerance_mm, "tolerance_mm")?) };
        Ok(())
    })
}

/// Keeps only the largest connected component (scanner debris removed) when `keep` is true.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_repair_options_set_keep_largest_component(options: *mut SherdRepairOptions, keep: bool) -> SherdStatus {
    set("sherd_repair_options_set_keep_largest_component", options, |builder| {
        builder.options.keep_largest_component = keep;
        Ok(())
    })
}

// ---------------------------------------------------------------- automatic orientation

/// Options of `sherd_orient_automatic`.
pub struct SherdOrientOptions {
    pub(crate) options: OrientOptions,
}

/// Creates automatic-orientation options with the library's defaults (the paper's).
///
/// # Safety
/// `out_options` must be writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_orient_options_new(out_options: *mut *mut SherdOrientOptions) -> SherdStatus {
    guard("sherd_orient_options_new", || unsafe {
        new_builder(out_options, SherdOrientOptions { options: OrientOptions::default() })
    })
}

/// Releases orientation options; NULL is ignored.
///
/// # Safety
/// `options` must be NULL or a live handle, not freed before.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_orient_options_free(options: *mut SherdOrientOptions) {
    unsafe { free_builder(options) }
}

/// Vertex count of the decimated working copy the axis is estimated on (default 10000,
/// as in the paper); at least 1.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_orient_options_set_target_vertex_count(options: *mut SherdOrientOptions, count: usize) -> SherdStatus {
    set("sherd_orient_options_set_target_vertex_count", options, |builder| {
        builder.options.target_vertex_count = positive_count(count, "count")?;
        Ok(())
    })
}

/// Laplacian smoothing iterations of the working copy (default 5; 0 disables).
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_orient_options_set_smoothing_iterations(options: *mut SherdOrientOptions, iterations: usize) -> SherdStatus {
    set("sherd_orient_options_set_smoothing_iterations", options, |builder| {
        builder.options.smoothing_iterations = iterations;
        Ok(())
    })
}

/// Confidence of the opposite-normal test that separates the inner and outer surfaces
/// (default 0.95, in (0, 1)); 0 skips the test.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_orient_options_set_opposite_normal_confidence(options: *mut SherdOrientOptions, confidence: f64) -> SherdStatus {
    set("sherd_orient_options_set_opposite_normal_confidence", options, |builder| {
        builder.options.opposite_normal_confidence = match confidence {
            0.0 => None,
            c if c > 0.0 && c < 1.0 => Some(c),
            c => return Err(Failure::invalid(format!("`confidence` must be 0 or in (0, 1), got {c}"))),
        };
        Ok(())
    })
}

// ---------------------------------------------------------------- manual orientation

/// Options of `sherd_orient_from_three_points`.
pub struct SherdManualOptions {
    pub(crate) options: ManualOptions,
}

/// Creates manual-orientation options with the library's defaults.
///
/// # Safety
/// `out_options` must be writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_manual_options_new(out_options: *mut *mut SherdManualOptions) -> SherdStatus {
    guard("sherd_manual_options_new", || unsafe {
        new_builder(out_options, SherdManualOptions { options: ManualOptions::default() })
    })
}

/// Releases manual-orientation options; NULL is ignored.
///
/// # Safety
/// `options` must be NULL or a live handle, not freed before.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_manual_options_free(options: *mut SherdManualOptions) {
    unsafe { free_builder(options) }
}

/// Fraction of the vertices kept as the surface the axis is fitted to, those whose
/// normal lines pass closest to the picked axis first (default 0.5, the paper's; in (0, 1]).
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_manual_options_set_keep_fraction(options: *mut SherdManualOptions, keep_fraction: f64) -> SherdStatus {
    set("sherd_manual_options_set_keep_fraction", options, |builder| {
        builder.options.keep_fraction = fraction(keep_fraction, "keep_fraction")?;
        Ok(())
    })
}

/// A picked point farther than `distance_mm` from every vertex is an error (default:
/// 2% of the bounding-box diagonal, restored by passing 0).
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_manual_options_set_max_pick_distance_mm(options: *mut SherdManualOptions, distance_mm: f64) -> SherdStatus {
    set("sherd_manual_options_set_max_pick_distance_mm", options, |builder| {
        builder.options.max_pick_distance_mm =
            if distance_mm == 0.0 { None } else { Some(finite_positive(distance_mm, "distance_mm")?) };
        Ok(())
    })
}
