//! Option builders: opaque handles holding the Rust options of one operation, created
//! with their defaults, changed through typed setters that check each value, and passed
//! (or NULL for the defaults) to the operation. Freeing a builder twice is undefined
//! behaviour, as with `free`; set your pointer to NULL after `_free`.

use super::error::{Failure, FfiResult};
use super::panic::guard;
use super::pointers::{borrow, borrow_mut, require, write_out};
use super::status::SherdStatus;
use super::refine::{SherdCriterion, SherdSurface};
use crate::draw::{DrawOptions, Placement, RegularityKind, SectionFill, Style};
use crate::mesh::repair::RepairOptions;
use crate::orient::{ManualOptions, OrientOptions};
use crate::profile::measure::MeasureOptions;
use crate::refine::RefineOptions;

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

/// `value` when it is at most `maximum`: counts that set iterations or sizes are bounded,
/// so that no option value makes an operation run for ever or exhaust memory.
fn at_most(value: usize, maximum: usize, name: &str) -> FfiResult<usize> {
    if value <= maximum {
        Ok(value)
    } else {
        Err(Failure::invalid(format!("`{name}` must be at most {maximum}, got {value}")))
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

/// Laplacian smoothing iterations of the working copy (default 5; 0 disables; at most
/// 1000).
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_orient_options_set_smoothing_iterations(options: *mut SherdOrientOptions, iterations: usize) -> SherdStatus {
    set("sherd_orient_options_set_smoothing_iterations", options, |builder| {
        builder.options.smoothing_iterations = at_most(iterations, crate::orient::MAX_SMOOTHING_ITERATIONS, "iterations")?;
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

// ---------------------------------------------------------------- refinement

/// Options of `sherd_refine`.
pub struct SherdRefineOptions {
    pub(crate) options: RefineOptions,
}

/// Creates refinement options with the library's defaults (criterion AUTO, both surfaces).
///
/// # Safety
/// `out_options` must be writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refine_options_new(out_options: *mut *mut SherdRefineOptions) -> SherdStatus {
    guard("sherd_refine_options_new", || unsafe {
        new_builder(out_options, SherdRefineOptions { options: RefineOptions::default() })
    })
}

/// Releases refinement options; NULL is ignored.
///
/// # Safety
/// `options` must be NULL or a live handle, not freed before.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refine_options_free(options: *mut SherdRefineOptions) {
    unsafe { free_builder(options) }
}

/// The criterion: a `SHERD_CRITERION_*` value; others give `SHERD_STATUS_INVALID_ARGUMENT`.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refine_options_set_criterion(options: *mut SherdRefineOptions, criterion: u32) -> SherdStatus {
    set("sherd_refine_options_set_criterion", options, |builder| {
        builder.options.criterion = SherdCriterion::parse(criterion)?;
        Ok(())
    })
}

/// The surface: a `SHERD_SURFACE_*` value; others give `SHERD_STATUS_INVALID_ARGUMENT`.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refine_options_set_surface(options: *mut SherdRefineOptions, surface: u32) -> SherdStatus {
    set("sherd_refine_options_set_surface", options, |builder| {
        builder.options.surface = SherdSurface::parse(surface)?;
        Ok(())
    })
}

/// Number of horizontal sections (at most 10000); 0 lets the library choose from the
/// sherd's height.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refine_options_set_section_count(options: *mut SherdRefineOptions, section_count: usize) -> SherdStatus {
    set("sherd_refine_options_set_section_count", options, |builder| {
        let section_count = at_most(section_count, crate::refine::MAX_SECTION_COUNT, "section_count")?;
        builder.options.section_count = (section_count > 0).then_some(section_count);
        Ok(())
    })
}

/// Largest tilt from the start axis the search considers, degrees (finite, positive,
/// below 90).
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refine_options_set_search_bound_deg(options: *mut SherdRefineOptions, bound_deg: f64) -> SherdStatus {
    set("sherd_refine_options_set_search_bound_deg", options, |builder| {
        let bound = finite_positive(bound_deg, "bound_deg")?;
        if bound >= 90.0 {
            return Err(Failure::invalid(format!("`bound_deg` must be below 90, got {bound}")));
        }
        builder.options.search_bound_deg = bound;
        Ok(())
    })
}

// ---------------------------------------------------------------- measurements

/// Options of `sherd_measure`.
pub struct SherdMeasureOptions {
    pub(crate) options: MeasureOptions,
}

/// Creates measurement options with the library's defaults (intervals from a bootstrap
/// of the default refinement).
///
/// # Safety
/// `out_options` must be writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_measure_options_new(out_options: *mut *mut SherdMeasureOptions) -> SherdStatus {
    guard("sherd_measure_options_new", || unsafe {
        new_builder(out_options, SherdMeasureOptions { options: MeasureOptions::default() })
    })
}

/// Releases measurement options; NULL is ignored.
///
/// # Safety
/// `options` must be NULL or a live handle, not freed before.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_measure_options_free(options: *mut SherdMeasureOptions) {
    unsafe { free_builder(options) }
}

/// The refinement the intervals' bootstrap repeats: a copy of `refine_options` (pass the
/// options the axis was refined with).
///
/// # Safety
/// `options` and `refine_options` must be live handles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_measure_options_set_refine_options(
    options: *mut SherdMeasureOptions,
    refine_options: *const SherdRefineOptions,
) -> SherdStatus {
    set("sherd_measure_options_set_refine_options", options, |builder| {
        builder.options.refine = unsafe { borrow(refine_options, "refine_options") }?.options.clone();
        Ok(())
    })
}

/// Number of bootstrap resamples behind the intervals (at most 10000); 0 gives no
/// intervals (NaN), and so do fewer than 5 usable resamples.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_measure_options_set_bootstrap_samples(options: *mut SherdMeasureOptions, samples: usize) -> SherdStatus {
    set("sherd_measure_options_set_bootstrap_samples", options, |builder| {
        builder.options.bootstrap.samples =
            at_most(samples, crate::refine::uncertainty::MAX_BOOTSTRAP_SAMPLES, "samples")?;
        Ok(())
    })
}

/// Seed of the bootstrap's resampling (the same seed gives the same intervals).
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_measure_options_set_bootstrap_seed(options: *mut SherdMeasureOptions, seed: u64) -> SherdStatus {
    set("sherd_measure_options_set_bootstrap_seed", options, |builder| {
        builder.options.bootstrap.seed = seed;
        Ok(())
    })
}

/// Confidence level of the intervals, in (0, 1) (default 0.95).
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_measure_options_set_confidence(options: *mut SherdMeasureOptions, confidence: f64) -> SherdStatus {
    set("sherd_measure_options_set_confidence", options, |builder| {
        if !(confidence > 0.0 && confidence < 1.0) {
            return Err(Failure::invalid(format!("`confidence` must be in (0, 1), got {confidence}")));
        }
        builder.options.bootstrap.confidence = confidence;
        Ok(())
    })
}

// ---------------------------------------------------------------- drawing

/// Options of `sherd_drawing_build`.
pub struct SherdDrawOptions {
    pub(crate) options: DrawOptions,
}

/// Rendering styles, combined as bits for `sherd_draw_options_set_style`.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SherdStyle {
    /// Outlines and crease lines only.
    Linear = 1,
    /// Vertex colours or the texture.
    Colour = 2,
    /// Directional light from the upper left.
    Light = 4,
    /// Ambient occlusion.
    Occlusion = 8,
    /// Dots, denser in darker areas.
    Stipple = 16,
    /// Vessel regularity as a colour map with its legend.
    Regularity = 32,
}

/// How the section is filled (`sherd_draw_options_set_section_fill`).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SherdSectionFill {
    /// Solid black, the usual convention for pottery.
    Black = 0,
    /// 45-degree hatching.
    Hatched = 1,
}

/// Where the views stand relative to the axis (`sherd_draw_options_set_placement`).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SherdPlacement {
    /// Beside the axis, whatever the true radius.
    Beside = 0,
    /// At the fragment's true distance from the axis.
    TrueDistance = 1,
}

/// Which map the regularity style shows (`sherd_draw_options_set_regularity`).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SherdRegularity {
    /// Distance of each point to the axis.
    AxisDistance = 0,
    /// Distance to the ideal vessel revolved from the section.
    IdealVessel = 1,
}

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
    set("sherd_draw_options_set_style", options, |builder| {
        const ALL: u32 = 63;
        if styles == 0 || styles & !ALL != 0 {
            return Err(Failure::invalid(format!(
                "`styles` {styles:#x} must be a non-empty combination of SHERD_STYLE_* bits (mask {ALL:#x})"
            )));
        }
        let has = |style: SherdStyle| styles & style as u32 != 0;
        builder.options.style = Style {
            linear: has(SherdStyle::Linear),
            colour: has(SherdStyle::Colour),
            light: has(SherdStyle::Light),
            occlusion: has(SherdStyle::Occlusion),
            stipple: has(SherdStyle::Stipple),
            regularity: has(SherdStyle::Regularity),
        };
        Ok(())
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
    set("sherd_draw_options_set_section_angle_rad", options, |builder| {
        if angle_rad.is_nan() {
            builder.options.section_angle_rad = None;
            return Ok(());
        }
        crate::profile::section::check_angle(angle_rad)?;
        builder.options.section_angle_rad = Some(angle_rad);
        Ok(())
    })
}

/// Section fill: a `SHERD_SECTION_FILL_*` value.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_draw_options_set_section_fill(options: *mut SherdDrawOptions, fill: u32) -> SherdStatus {
    set("sherd_draw_options_set_section_fill", options, |builder| {
        builder.options.section_fill = match fill {
            0 => SectionFill::Black,
            1 => SectionFill::Hatched,
            other => return Err(Failure::invalid(format!("`fill` {other} is not a SHERD_SECTION_FILL_* value (0 or 1)"))),
        };
        Ok(())
    })
}

/// View placement: a `SHERD_PLACEMENT_*` value.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_draw_options_set_placement(options: *mut SherdDrawOptions, placement: u32) -> SherdStatus {
    set("sherd_draw_options_set_placement", options, |builder| {
        builder.options.placement = match placement {
            0 => Placement::Beside,
            1 => Placement::TrueDistance,
            other => return Err(Failure::invalid(format!("`placement` {other} is not a SHERD_PLACEMENT_* value (0 or 1)"))),
        };
        Ok(())
    })
}

/// The map of the regularity style: a `SHERD_REGULARITY_*` value.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_draw_options_set_regularity(options: *mut SherdDrawOptions, regularity: u32) -> SherdStatus {
    set("sherd_draw_options_set_regularity", options, |builder| {
        builder.options.regularity = match regularity {
            0 => RegularityKind::AxisDistance,
            1 => RegularityKind::IdealVessel,
            other => return Err(Failure::invalid(format!("`regularity` {other} is not a SHERD_REGULARITY_* value (0 or 1)"))),
        };
        Ok(())
    })
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

/// A title (inventory number...) as a NUL-terminated UTF-8 string; NULL removes it.
///
/// # Safety
/// `options` must be a live handle; `title` NULL or a NUL-terminated string.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_draw_options_set_title(options: *mut SherdDrawOptions, title: *const std::ffi::c_char) -> SherdStatus {
    set("sherd_draw_options_set_title", options, |builder| {
        builder.options.title = if title.is_null() {
            None
        } else {
            let text = unsafe { std::ffi::CStr::from_ptr(title) };
            Some(text.to_str().map_err(|e| Failure::invalid(format!("`title` is not UTF-8: {e}")))?.to_string())
        };
        Ok(())
    })
}
