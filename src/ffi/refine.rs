//! Refinement of a pre-oriented axis (Wilczek et al. 2018, section 2.3) behind a result
//! handle, `SherdRefinement`, that holds the refined axis, its report and the Pareto
//! front.

use super::buffer::{SherdBuffer, hand_out_report, hand_out_text};
use super::builder::{Builder, assign, at_most, builder, finite_positive, free_builder, new_builder, options_or_default, set};
use super::enums::{CEnum, SherdCircleFit, SherdCriterion, SherdEdge, SherdParetoChoice, SherdProfileMethod, SherdSurface};
use super::error::{Failure, FfiResult};
use super::mesh::{SherdMesh, mesh_ref};
use super::orient::{SherdAxis, read_axis};
use super::panic::guard;
use super::pointers::{SizedStruct, borrow, host_slice_mut, require, write_out, write_sized};
use super::status::SherdStatus;
use crate::refine::pareto::ParetoOptions;
use crate::refine::superposition::{ProfileMethod, ProfileMethodKind};
use crate::refine::{EdgeChoice, MAX_SEARCH_BOUND_DEG, RefineOptions, Refinement};

/// A refined axis with its report and, for the Pareto criterion, the front. Created by
/// `sherd_refine`, released with `sherd_refinement_free`.
pub struct SherdRefinement {
    refinement: Refinement,
}

/// The summary of a refinement. Set `size` to `sizeof(SherdRefineReport)` first.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SherdRefineReport {
    /// `sizeof(SherdRefineReport)`, set by the caller.
    pub size: usize,
    /// The criterion used (a `SHERD_CRITERION_*` value; `AUTO` resolves to the one chosen).
    pub criterion: u32,
    /// The surface used (a `SHERD_SURFACE_*` value).
    pub surface: u32,
    /// Objective evaluations or optimiser iterations.
    pub iterations: u64,
    /// The criterion's residual at the start axis, millimetres; infinite where the
    /// criterion is undefined (AUTO kept its start: see `flagged`).
    pub start_residual_mm: f64,
    /// The criterion's residual at the refined axis, millimetres.
    pub residual_mm: f64,
    /// Angle between the start and refined directions, degrees.
    pub tilt_deg: f64,
    /// Distance between the start and refined axes near the sherd, millimetres.
    pub shift_mm: f64,
    /// Horizontal sections used.
    pub section_count: usize,
    /// Points on the Pareto front (0 unless the criterion is Pareto).
    pub pareto_point_count: usize,
    /// 1 when the refinement doubts its own axis: the skins barely fix its position,
    /// (AUTO) no level rim or base and no wall skin was left to refine by and the start
    /// axis is returned, or (TANGENT) the plane turned the axis to or past the search
    /// bound (`flag_reason` in `sherd_refinement_report_json` says which); 0 otherwise.
    /// `sherd_measure`'s intervals say how far such an axis may be off (on dense scans it
    /// is often right: the test was calibrated on coarse fragments). A caller whose `size`
    /// ends before this field (an older header) is not written to here.
    pub flagged: u32,
}

unsafe impl SizedStruct for SherdRefineReport {
    const NAME: &'static str = "SherdRefineReport";
    /// The first version ended before `flagged`.
    const MIN_SIZE: usize = std::mem::offset_of!(SherdRefineReport, flagged);
}

/// One non-dominated solution of the Pareto criterion (Eq. 3-4): the tilts of the axis
/// from the start axis and its two costs. An element of an array: its layout is fixed.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SherdParetoPoint {
    /// Turn about the start frame's x axis, degrees.
    pub tilt_x_deg: f64,
    /// Turn about the start frame's y axis, degrees.
    pub tilt_y_deg: f64,
    /// Eq. 3: sector-weighted dispersion of the circle centres, mm^2.
    pub centre_dispersion_mm2: f64,
    /// Eq. 4: sector-weighted mean squared circle residual, mm^2.
    pub circle_residual_mm2: f64,
}

/// Refines `axis` (from `sherd_orient_*`) on `mesh` with the criterion and surface of
/// `options` (NULL: the defaults, criterion AUTO on both surfaces). The result handle
/// `*out_refinement` gives the refined axis, the report and the Pareto front.
///
/// Errors: `SHERD_STATUS_DEGENERATE_GEOMETRY` (too few sections, no surface of the
/// requested kind), `SHERD_STATUS_NOT_CONVERGED`, `SHERD_STATUS_INVALID_ARGUMENT`.
///
/// # Safety
/// `mesh` must be a live handle; `axis` must have its `size` set; `options` NULL or
/// live; `out_refinement` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refine(
    mesh: *const SherdMesh,
    axis: *const SherdAxis,
    options: *const SherdRefineOptions,
    out_refinement: *mut *mut SherdRefinement,
) -> SherdStatus {
    guard("sherd_refine", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let axis = unsafe { read_axis(axis, "axis") }?;
        let options = unsafe { options_or_default(options, |builder| &builder.options) }?;
        require(out_refinement.cast_const(), "out_refinement")?;
        let refinement = crate::refine::refine(mesh, &axis, &options)?;
        let handle = Box::into_raw(Box::new(SherdRefinement { refinement }));
        unsafe { write_out(out_refinement, handle, "out_refinement") }
    })
}

unsafe fn refinement_ref<'a>(refinement: *const SherdRefinement) -> FfiResult<&'a Refinement> {
    unsafe { borrow(refinement, "refinement") }.map(|handle| &handle.refinement)
}

/// Writes the refined axis (base to rim, the mesh's frame) to `*out_axis` (`size` set).
///
/// # Safety
/// `refinement` must be a live handle; `out_axis` writable with its `size` set.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refinement_axis(refinement: *const SherdRefinement, out_axis: *mut SherdAxis) -> SherdStatus {
    guard("sherd_refinement_axis", || {
        let refinement = unsafe { refinement_ref(refinement) }?;
        unsafe { write_sized(out_axis, SherdAxis::from_axis(&refinement.axis), "out_axis") }
    })
}

/// Writes the summary of the refinement to `*out_report` (`size` set).
///
/// # Safety
/// `refinement` must be a live handle; `out_report` writable with its `size` set.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refinement_report(refinement: *const SherdRefinement, out_report: *mut SherdRefineReport) -> SherdStatus {
    guard("sherd_refinement_report", || {
        let refinement = unsafe { refinement_ref(refinement) }?;
        let report = &refinement.report;
        let summary = SherdRefineReport {
            size: size_of::<SherdRefineReport>(),
            criterion: SherdCriterion::value_of(report.method),
            surface: SherdSurface::value_of(report.surface),
            iterations: report.iterations,
            start_residual_mm: report.start_residual_mm,
            residual_mm: report.residual_mm,
            tilt_deg: report.tilt_deg,
            shift_mm: report.shift_mm,
            section_count: report.section_count,
            pareto_point_count: refinement.pareto_front.as_ref().map_or(0, Vec::len),
            flagged: u32::from(report.flagged),
        };
        unsafe { write_sized(out_report, summary, "out_report") }
    })
}

/// Writes the full report (method, reason for the choice, parameters, timings...) as a
/// JSON object into a new buffer `*out_report_json`.
///
/// # Safety
/// `refinement` must be a live handle; `out_report_json` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refinement_report_json(
    refinement: *const SherdRefinement,
    out_report_json: *mut *mut SherdBuffer,
) -> SherdStatus {
    guard("sherd_refinement_report_json", || {
        let refinement = unsafe { refinement_ref(refinement) }?;
        require(out_report_json.cast_const(), "out_report_json")?;
        unsafe { hand_out_report(out_report_json, &refinement.report) }
    })
}

/// Writes the Pareto front drawn as an SVG plot (centre dispersion, Eq. 3, against circle
/// residual, Eq. 4, the chosen solution circled) into a new text buffer `*out_svg`, for a
/// host to save or show. `SHERD_STATUS_INVALID_ARGUMENT` when the refinement has no front
/// (its criterion was not Pareto).
///
/// # Safety
/// `refinement` must be a live handle; `out_svg` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refinement_pareto_plot_svg(refinement: *const SherdRefinement, out_svg: *mut *mut SherdBuffer) -> SherdStatus {
    guard("sherd_refinement_pareto_plot_svg", || {
        let refinement = unsafe { refinement_ref(refinement) }?;
        require(out_svg.cast_const(), "out_svg")?;
        let svg = refinement.pareto_plot_svg().ok_or_else(|| {
            Failure::invalid(format!(
                "the refinement has no Pareto front to plot (its criterion was {:?})",
                refinement.report.method
            ))
        })?;
        unsafe { hand_out_text(out_svg, svg) }
    })
}

/// Copies the Pareto front into `out_points` (room for `capacity` points) and writes the
/// number of points to `*out_count`. Pass `out_points` NULL and `capacity` 0 to learn the
/// count first. The front is empty unless the criterion was Pareto.
/// `SHERD_STATUS_BUFFER_TOO_SMALL` (with `*out_count` written) when `capacity` is short.
///
/// # Safety
/// `refinement` must be a live handle; `out_points` NULL (with `capacity` 0) or room for
/// `capacity` points; `out_count` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refinement_pareto_front(
    refinement: *const SherdRefinement,
    out_points: *mut SherdParetoPoint,
    capacity: usize,
    out_count: *mut usize,
) -> SherdStatus {
    guard("sherd_refinement_pareto_front", || {
        let refinement = unsafe { refinement_ref(refinement) }?;
        let front = refinement.pareto_front.as_deref().unwrap_or_default();
        unsafe { write_out(out_count, front.len(), "out_count") }?;
        if capacity < front.len() {
            return Err(Failure::new(
                SherdStatus::BufferTooSmall,
                format!("the front has {} points, the buffer room for {capacity}", front.len()),
            ));
        }
        let out = unsafe { host_slice_mut(out_points, front.len(), 1, "out_points") }?;
        for (slot, point) in out.iter_mut().zip(front) {
            *slot = SherdParetoPoint {
                tilt_x_deg: point.tilt_x_deg,
                tilt_y_deg: point.tilt_y_deg,
                centre_dispersion_mm2: point.centre_dispersion_mm2,
                circle_residual_mm2: point.circle_residual_mm2,
            };
        }
        Ok(())
    })
}

/// Releases a refinement; NULL is ignored. Freeing twice is undefined behaviour.
///
/// # Safety
/// `refinement` must be NULL or a live handle not freed before.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refinement_free(refinement: *mut SherdRefinement) {
    if !refinement.is_null() {
        drop(unsafe { Box::from_raw(refinement) });
    }
}

// ---------------------------------------------------------------- options

/// Options of `sherd_refine`.
pub struct SherdRefineOptions {
    pub(crate) options: RefineOptions,
}

builder!(SherdRefineOptions => RefineOptions);

/// The profile criterion's form for a method and parameter from the host.
fn profile_method(method: u32, parameter: f64) -> FfiResult<ProfileMethod> {
    let whole = || {
        if parameter.fract() == 0.0 && (0.0..=1e6).contains(&parameter) {
            Ok(parameter as usize)
        } else {
            Err(Failure::invalid(format!("`parameter` must be a whole number for this method, got {parameter}")))
        }
    };
    let method = match SherdProfileMethod::parse(method, "method")? {
        ProfileMethodKind::Reference => ProfileMethod::ReferenceProfile { vertical_sections: whole()? },
        ProfileMethodKind::Polynomial => ProfileMethod::Polynomial { degree: whole()? },
        ProfileMethodKind::Spline => ProfileMethod::Spline { knot_spacing_mm: parameter },
    };
    Ok(method.validated()?)
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
    assign("sherd_refine_options_set_criterion", options, |o| &mut o.criterion, || SherdCriterion::parse(criterion, "criterion"))
}

/// The surface: a `SHERD_SURFACE_*` value; others give `SHERD_STATUS_INVALID_ARGUMENT`.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refine_options_set_surface(options: *mut SherdRefineOptions, surface: u32) -> SherdStatus {
    assign("sherd_refine_options_set_surface", options, |o| &mut o.surface, || SherdSurface::parse(surface, "surface"))
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
        *pareto = ParetoOptions { choice: SherdParetoChoice::parse(choice, "choice")?.with_count(count), ..*pareto }.validated()?;
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
        *pareto = ParetoOptions { min_section_points: min_points, min_sector_angle_deg: min_sector_deg, ..*pareto }
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
    assign("sherd_refine_options_set_profile_method", options, |o| &mut o.profile_method, || profile_method(method, parameter))
}

/// The circle fit of the Pareto criterion's sections: a `SHERD_CIRCLE_FIT_*` value.
///
/// # Safety
/// `options` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_refine_options_set_circle_fit(options: *mut SherdRefineOptions, method: u32) -> SherdStatus {
    assign("sherd_refine_options_set_circle_fit", options, |o| &mut o.pareto.circle_fit, || SherdCircleFit::parse(method, "method"))
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
    assign("sherd_refine_options_set_edge", options, |o| &mut o.edge, || SherdEdge::parse(edge, "edge").map(EdgeChoice::edge))
}
