//! Measurements of an oriented fragment with their intervals (`profile::measure`):
//! rim and base diameters, preserved arc, height, wall thickness, capacity.

use super::buffer::{SherdBuffer, hand_out_report};
use super::error::FfiResult;
use super::mesh::{SherdMesh, mesh_ref};
use super::builder::{assign, at_most, builder, confidence_level, free_builder, new_builder, options_or_default};
use super::orient::{SherdAxis, read_axis};
use super::panic::guard;
use super::pointers::{SizedStruct, checked_size, write_sized};
use super::status::SherdStatus;
use super::refine::SherdRefineOptions;
use super::pointers::borrow;
use crate::profile::measure::{MeasureOptions, Measurements};

/// The measurements of an oriented fragment, in millimetres, degrees and litres. A
/// figure the fragment does not determine (no rim preserved, no interval computed, a
/// profile that does not reach from base to rim for the capacity) is NaN. Intervals are
/// `[low, high]` at the options' confidence (95% by default). Set `size` to
/// `sizeof(SherdMeasurements)` first.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SherdMeasurements {
    /// `sizeof(SherdMeasurements)`, set by the caller.
    pub size: usize,
    /// Radius of the rim (its outer edge), mm.
    pub rim_radius_mm: f64,
    /// Diameter of the rim, mm.
    pub rim_diameter_mm: f64,
    /// Interval of the rim diameter, mm.
    pub rim_diameter_interval_mm: [f64; 2],
    /// Radius of the base (its outer edge), mm.
    pub base_radius_mm: f64,
    /// Diameter of the base, mm.
    pub base_diameter_mm: f64,
    /// Interval of the base diameter, mm.
    pub base_diameter_interval_mm: [f64; 2],
    /// Preserved arc of the circumference, degrees.
    pub sector_angle_deg: f64,
    /// Preserved arc as a share of the circumference, percent.
    pub sector_percent: f64,
    /// Preserved height along the axis, mm.
    pub height_mm: f64,
    /// Median wall thickness along the profile, mm.
    pub wall_thickness_mm: f64,
    /// Volume inside the revolved inner profile, litres (complete profiles only).
    pub capacity_litres: f64,
    /// Interval of the axis direction's error, degrees.
    pub axis_angle_interval_deg: [f64; 2],
    /// Interval `[0, upper]` of the paper's mean point distance between the true and the
    /// given axis, mm. A caller whose `size` ends before this field (an older header) is
    /// not written to here, nor in the fields after it.
    pub axis_distance_interval_mm: [f64; 2],
    /// 1 when the angle interval reaches past 4 degrees, the distance interval past
    /// 5 mm, or the axis refined without a quarter of the preserved arc moves by more
    /// than 1.5 mm of mean point distance: the axis is uncertain, and it and these
    /// figures want a look before they are used (the JSON's notes say how far); 0
    /// otherwise.
    pub axis_uncertain: u32,
}

impl Default for SherdMeasurements {
    fn default() -> Self {
        SherdMeasurements {
            size: size_of::<SherdMeasurements>(),
            rim_radius_mm: f64::NAN,
            rim_diameter_mm: f64::NAN,
            rim_diameter_interval_mm: [f64::NAN; 2],
            base_radius_mm: f64::NAN,
            base_diameter_mm: f64::NAN,
            base_diameter_interval_mm: [f64::NAN; 2],
            sector_angle_deg: f64::NAN,
            sector_percent: f64::NAN,
            height_mm: f64::NAN,
            wall_thickness_mm: f64::NAN,
            capacity_litres: f64::NAN,
            axis_angle_interval_deg: [f64::NAN; 2],
            axis_distance_interval_mm: [f64::NAN; 2],
            axis_uncertain: 0,
        }
    }
}

unsafe impl SizedStruct for SherdMeasurements {
    const NAME: &'static str = "SherdMeasurements";
    /// The first version ended before `axis_distance_interval_mm`.
    const MIN_SIZE: usize = std::mem::offset_of!(SherdMeasurements, axis_distance_interval_mm);
}

impl SherdMeasurements {
    fn from_measurements(m: &Measurements) -> Self {
        let or_nan = |value: Option<f64>| value.unwrap_or(f64::NAN);
        let interval = |value: Option<[f64; 2]>| value.unwrap_or([f64::NAN; 2]);
        SherdMeasurements {
            size: size_of::<SherdMeasurements>(),
            rim_radius_mm: or_nan(m.rim_radius_mm),
            rim_diameter_mm: or_nan(m.rim_diameter_mm),
            rim_diameter_interval_mm: interval(m.rim_diameter_interval_mm),
            base_radius_mm: or_nan(m.base_radius_mm),
            base_diameter_mm: or_nan(m.base_diameter_mm),
            base_diameter_interval_mm: interval(m.base_diameter_interval_mm),
            sector_angle_deg: m.sector_angle_deg,
            sector_percent: m.sector_percent,
            height_mm: m.height_mm,
            wall_thickness_mm: or_nan(m.wall_thickness_mm),
            capacity_litres: or_nan(m.capacity_litres),
            axis_angle_interval_deg: interval(m.axis_angle_interval_deg),
            axis_distance_interval_mm: interval(m.axis_distance_interval_mm),
            axis_uncertain: u32::from(m.axis_uncertain),
        }
    }
}

/// Measures `mesh` oriented by `axis` (the refined axis). `options` may be NULL for the
/// defaults (which include a bootstrap for the intervals: a few refinements more).
/// `out_measurements` (its `size` set) receives the figures; `out_json` (or NULL) all of
/// them as JSON, with the wall thickness along the profile and notes on what could not
/// be measured and why.
///
/// # Safety
/// `mesh` must be a live handle; `axis` must have its `size` set; `options` NULL or
/// live; `out_measurements` writable with its `size` set; `out_json` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_measure(
    mesh: *const SherdMesh,
    axis: *const SherdAxis,
    options: *const SherdMeasureOptions,
    out_measurements: *mut SherdMeasurements,
    out_json: *mut *mut SherdBuffer,
) -> SherdStatus {
    guard("sherd_measure", || -> FfiResult {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let axis = unsafe { read_axis(axis, "axis") }?;
        let options = unsafe { options_or_default(options, |builder| &builder.options) }?;
        checked_size(out_measurements.cast_const(), "out_measurements")?;
        let measurements = crate::profile::measure::measure(mesh, &axis, &options);
        unsafe { write_sized(out_measurements, SherdMeasurements::from_measurements(&measurements), "out_measurements") }?;
        unsafe { hand_out_report(out_json, &measurements) }
    })
}

// ---------------------------------------------------------------- options

/// Options of `sherd_measure`.
pub struct SherdMeasureOptions {
    pub(crate) options: MeasureOptions,
}

builder!(SherdMeasureOptions => MeasureOptions);

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
