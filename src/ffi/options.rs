//! Option builders: opaque handles holding the Rust options of one operation, created
//! with their defaults, changed through typed setters that check each value, and passed
//! (or NULL for the defaults) to the operation. Freeing a builder twice is undefined
//! behaviour, as with `free`; set your pointer to NULL after `_free`.

use super::error::{Failure, FfiResult};
use super::panic::guard;
use super::pointers::{borrow, borrow_mut, require, write_out};
use super::status::SherdStatus;
use super::refine::{SherdCircleFit, SherdCriterion, SherdEdge, SherdParetoChoice, SherdProfileMethod, SherdSurface};
use crate::draw::{Annotations, DrawOptions, Placement, RegularityKind, SectionFill, Style};
use crate::mesh::repair::RepairOptions;
use crate::orient::{ManualOptions, OrientOptions};
use crate::profile::measure::MeasureOptions;
use crate::refine::pareto::ParetoOptions;
use crate::refine::{RefineOptions, MAX_SEARCH_BOUND_DEG};

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

/// An option builder: a handle around the Rust options of one operation.
trait Builder {
    type Options;
    fn options_mut(&mut self) -> &mut Self::Options;
}

/// The setter of one option: checks the handle, then the value (`value` refuses it with
/// its reason), and stores it in the `field` of the builder's options.
fn assign<B: Builder, V>(
    function: &str,
    options: *mut B,
    field: impl FnOnce(&mut B::Options) -> &mut V,
    value: impl FnOnce() -> FfiResult<V>,
) -> SherdStatus {
    set(function, options, |builder| {
        *field(builder.options_mut()) = value()?;
        Ok(())
    })
}

macro_rules! builders {
    ($($builder:ident => $options:ty),* $(,)?) => {$(
        impl Builder for $builder {
            type Options = $options;
            fn options_mut(&mut self) -> &mut $options {
                &mut self.options
            }
        }
    )*};
}

builders!(
    SherdRepairOptions => RepairOptions,
    SherdOrientOptions => OrientOptions,
    SherdManualOptions => ManualOptions,
    SherdRefineOptions => RefineOptions,
    SherdMeasureOptions => MeasureOptions,
    SherdDrawOptions => DrawOptions,
);

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

/// A finite positive length, or `None` (the library's default) for 0.
fn positive_or_default(value: f64, name: &str) -> FfiResult<Option<f64>> {
    if value == 0.0 { Ok(None) } else { finite_positive(value, name).map(Some) }
}

/// A confidence level, strictly between 0 and 1.
fn confidence_level(value: f64, name: &str) -> FfiResult<f64> {
    if value > 0.0 && value < 1.0 {
        Ok(value)
    } else {
        Err(Failure::invalid(format!("`{name}` must be in (0, 1), got {value}")))
    }
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
    assign("sherd_repair_options_set_merge_tolerance_mm", options, |o| &mut o.merge_tolerance_mm, || {
        positive_or_default(tolerance_mm, "tolerance_mm")
    })
}

/// Keeps only the largest connected component (scanner debris removed) when `keep` is true.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_repair_options_set_keep_largest_component(options: *mut SherdRepairOptions, keep: bool) -> SherdStatus {
    assign("sherd_repair_options_set_keep_largest_component", options, |o| &mut o.keep_largest_component, || Ok(keep))
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
    assign("sherd_orient_options_set_target_vertex_count", options, |o| &mut o.target_vertex_count, || {
        positive_count(count, "count")
    })
}

/// Laplacian smoothing iterations of the working copy (default 5; 0 disables; at most
/// 1000).
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_orient_options_set_smoothing_iterations(options: *mut SherdOrientOptions, iterations: usize) -> SherdStatus {
    assign("sherd_orient_options_set_smoothing_iterations", options, |o| &mut o.smoothing_iterations, || {
        at_most(iterations, crate::orient::MAX_SMOOTHING_ITERATIONS, "iterations")
    })
}

/// Confidence of the opposite-normal test that separates the inner and outer surfaces
/// (default 0.95, in (0, 1)); 0 skips the test.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_orient_options_set_opposite_normal_confidence(options: *mut SherdOrientOptions, confidence: f64) -> SherdStatus {
    assign("sherd_orient_options_set_opposite_normal_confidence", options, |o| &mut o.opposite_normal_confidence, || {
        match confidence {
            0.0 => Ok(None),
            c if c > 0.0 && c < 1.0 => Ok(Some(c)),
            c => Err(Failure::invalid(format!("`confidence` must be 0 (no test) or in (0, 1), got {c}"))),
        }
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
    assign("sherd_manual_options_set_keep_fraction", options, |o| &mut o.keep_fraction, || {
        fraction(keep_fraction, "keep_fraction")
    })
}

/// A picked point farther than `distance_mm` from every vertex is an error (default:
/// 2% of the bounding-box diagonal, restored by passing 0).
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_manual_options_set_max_pick_distance_mm(options: *mut SherdManualOptions, distance_mm: f64) -> SherdStatus {
    assign("sherd_manual_options_set_max_pick_distance_mm", options, |o| &mut o.max_pick_distance_mm, || {
        positive_or_default(distance_mm, "distance_mm")
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
    assign("sherd_refine_options_set_criterion", options, |o| &mut o.criterion, || SherdCriterion::parse(criterion))
}

/// The surface: a `SHERD_SURFACE_*` value; others give `SHERD_STATUS_INVALID_ARGUMENT`.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refine_options_set_surface(options: *mut SherdRefineOptions, surface: u32) -> SherdStatus {
    assign("sherd_refine_options_set_surface", options, |o| &mut o.surface, || SherdSurface::parse(surface))
}

/// Number of horizontal sections (at most 10000); 0 lets the library choose from the
/// sherd's height.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refine_options_set_section_count(options: *mut SherdRefineOptions, section_count: usize) -> SherdStatus {
    assign("sherd_refine_options_set_section_count", options, |o| &mut o.section_count, || {
        let section_count = at_most(section_count, crate::refine::MAX_SECTION_COUNT, "section_count")?;
        Ok((section_count > 0).then_some(section_count))
    })
}

/// Largest tilt from the start axis the search considers, degrees (finite, positive, at
/// most 45; the paper's 10 by default).
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refine_options_set_search_bound_deg(options: *mut SherdRefineOptions, bound_deg: f64) -> SherdStatus {
    assign("sherd_refine_options_set_search_bound_deg", options, |o| &mut o.search_bound_deg, || {
        match finite_positive(bound_deg, "bound_deg")? {
            bound if bound <= MAX_SEARCH_BOUND_DEG => Ok(bound),
            bound => Err(Failure::invalid(format!("`bound_deg` must be at most {MAX_SEARCH_BOUND_DEG}, got {bound}"))),
        }
    })
}

/// Which solution of the Pareto front becomes the axis: a `SHERD_PARETO_CHOICE_*` value;
/// `count` is the number of best solutions averaged by `SHERD_PARETO_CHOICE_MEAN_OF_BEST`
/// (at least 1) and is ignored by the others.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refine_options_set_pareto_choice(options: *mut SherdRefineOptions, choice: u32, count: usize) -> SherdStatus {
    set("sherd_refine_options_set_pareto_choice", options, |builder| {
        let pareto = &mut builder.options_mut().pareto;
        *pareto = ParetoOptions { choice: SherdParetoChoice::parse(choice, count)?, ..pareto.clone() }.validated()?;
        Ok(())
    })
}

/// The Pareto criterion's limits per horizontal section (Eq. 3-4): sections with fewer
/// than `min_points` points (at least 3) or an arc under `min_sector_deg` degrees (finite,
/// 0 to 360) are left out. The defaults are 10 points and 3 degrees.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refine_options_set_pareto_section_limits(
    options: *mut SherdRefineOptions,
    min_points: usize,
    min_sector_deg: f64,
) -> SherdStatus {
    set("sherd_refine_options_set_pareto_section_limits", options, |builder| {
        let pareto = &mut builder.options_mut().pareto;
        *pareto = ParetoOptions { min_section_points: min_points, min_sector_angle_deg: min_sector_deg, ..pareto.clone() }
            .validated()?;
        Ok(())
    })
}

/// The form of the profile criterion: a `SHERD_PROFILE_METHOD_*` value and its parameter
/// (the number of vertical sections of Eq. 5, the degree of Eq. 6's polynomial, or the
/// knot spacing of its spline in mm; see the values).
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refine_options_set_profile_method(options: *mut SherdRefineOptions, method: u32, parameter: f64) -> SherdStatus {
    assign("sherd_refine_options_set_profile_method", options, |o| &mut o.profile_method, || SherdProfileMethod::parse(method, parameter))
}

/// The circle fit of the Pareto criterion's sections: a `SHERD_CIRCLE_FIT_*` value.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refine_options_set_circle_fit(options: *mut SherdRefineOptions, method: u32) -> SherdStatus {
    assign("sherd_refine_options_set_circle_fit", options, |o| &mut o.pareto.circle_fit, || SherdCircleFit::parse(method))
}

/// The tangent plane's tolerance epsilon (Eq. 7), mm (finite, positive; 3 by default): a
/// vertical section whose extreme lies farther than this below the rim's highest point
/// (above the base's lowest) is taken for damaged and left out.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refine_options_set_tangent_tolerance_mm(options: *mut SherdRefineOptions, tolerance_mm: f64) -> SherdStatus {
    assign("sherd_refine_options_set_tangent_tolerance_mm", options, |o| &mut o.tangent_tolerance_mm, || {
        finite_positive(tolerance_mm, "tolerance_mm")
    })
}

/// The edge the tangent plane rests on: a `SHERD_EDGE_*` value (`SHERD_EDGE_DETECT`, the
/// default, takes the one whose extremes are level).
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refine_options_set_edge(options: *mut SherdRefineOptions, edge: u32) -> SherdStatus {
    assign("sherd_refine_options_set_edge", options, |o| &mut o.edge, || SherdEdge::parse(edge))
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
    assign("sherd_measure_options_set_refine_options", options, |o| &mut o.refine, || {
        Ok(unsafe { borrow(refine_options, "refine_options") }?.options.clone())
    })
}

/// Number of bootstrap resamples behind the intervals (at most 10000); 0 gives no
/// intervals (NaN), and so do fewer than 5 usable resamples.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_measure_options_set_bootstrap_samples(options: *mut SherdMeasureOptions, samples: usize) -> SherdStatus {
    assign("sherd_measure_options_set_bootstrap_samples", options, |o| &mut o.bootstrap.samples, || {
        at_most(samples, crate::refine::uncertainty::MAX_BOOTSTRAP_SAMPLES, "samples")
    })
}

/// Seed of the bootstrap's resampling (the same seed gives the same intervals).
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_measure_options_set_bootstrap_seed(options: *mut SherdMeasureOptions, seed: u64) -> SherdStatus {
    assign("sherd_measure_options_set_bootstrap_seed", options, |o| &mut o.bootstrap.seed, || Ok(seed))
}

/// Confidence level of the intervals, in (0, 1) (default 0.95).
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_measure_options_set_confidence(options: *mut SherdMeasureOptions, confidence: f64) -> SherdStatus {
    assign("sherd_measure_options_set_confidence", options, |o| &mut o.bootstrap.confidence, || {
        confidence_level(confidence, "confidence")
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

/// The measurements written under the drawing, combined as bits for
/// `sherd_draw_options_set_annotations` (the `annotations` of `sherd draw --annotations`,
/// Python, Blender and MeshLab). The diameters and the preserved share are always written.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SherdAnnotation {
    /// The preserved height along the axis.
    Height = 1,
    /// The median wall thickness.
    WallThickness = 2,
    /// The capacity, litres (only where the profile runs from base to rim).
    Capacity = 4,
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

impl SherdRegularity {
    /// The map for a value from the host.
    pub(crate) fn parse(value: u32) -> FfiResult<RegularityKind> {
        match value {
            0 => Ok(RegularityKind::AxisDistance),
            1 => Ok(RegularityKind::IdealVessel),
            other => Err(Failure::invalid(format!("`regularity` {other} is not a SHERD_REGULARITY_* value (0 or 1)"))),
        }
    }
}

/// `value` checked as a combination of the bits in `all` (named `prefix`*), and non-empty
/// unless `empty_allowed`: a bit outside them would be no choice of the library's.
fn flags(name: &str, value: u32, all: u32, prefix: &str, empty_allowed: bool) -> FfiResult<u32> {
    if (value == 0 && !empty_allowed) || value & !all != 0 {
        let kind = if empty_allowed { "a combination (0 for none)" } else { "a non-empty combination" };
        return Err(Failure::invalid(format!("`{name}` {value:#x} must be {kind} of {prefix}* bits (mask {all:#x})")));
    }
    Ok(value)
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
    assign("sherd_draw_options_set_style", options, |o| &mut o.style, || {
        let bits = flags("styles", styles, 63, "SHERD_STYLE_", false)?;
        let has = |style: SherdStyle| bits & style as u32 != 0;
        Ok(Style {
            linear: has(SherdStyle::Linear),
            colour: has(SherdStyle::Colour),
            light: has(SherdStyle::Light),
            occlusion: has(SherdStyle::Occlusion),
            stipple: has(SherdStyle::Stipple),
            regularity: has(SherdStyle::Regularity),
        })
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
    assign("sherd_draw_options_set_section_fill", options, |o| &mut o.section_fill, || match fill {
        0 => Ok(SectionFill::Black),
        1 => Ok(SectionFill::Hatched),
        other => Err(Failure::invalid(format!("`fill` {other} is not a SHERD_SECTION_FILL_* value (0 or 1)"))),
    })
}

/// View placement: a `SHERD_PLACEMENT_*` value.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_draw_options_set_placement(options: *mut SherdDrawOptions, placement: u32) -> SherdStatus {
    assign("sherd_draw_options_set_placement", options, |o| &mut o.placement, || match placement {
        0 => Ok(Placement::Beside),
        1 => Ok(Placement::TrueDistance),
        other => Err(Failure::invalid(format!("`placement` {other} is not a SHERD_PLACEMENT_* value (0 or 1)"))),
    })
}

/// The map of the regularity style: a `SHERD_REGULARITY_*` value.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_draw_options_set_regularity(options: *mut SherdDrawOptions, regularity: u32) -> SherdStatus {
    assign("sherd_draw_options_set_regularity", options, |o| &mut o.regularity, || SherdRegularity::parse(regularity))
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
        let bits = flags("annotations", annotations, 7, "SHERD_ANNOTATION_", true)?;
        let has = |annotation: SherdAnnotation| bits & annotation as u32 != 0;
        Ok(Annotations {
            height: has(SherdAnnotation::Height),
            wall_thickness: has(SherdAnnotation::WallThickness),
            capacity: has(SherdAnnotation::Capacity),
        })
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
        let text = unsafe { std::ffi::CStr::from_ptr(title) };
        Ok(Some(text.to_str().map_err(|e| Failure::invalid(format!("`title` is not UTF-8: {e}")))?.to_string()))
    })
}
