//! Refinement of a pre-oriented axis (Wilczek et al. 2018, section 2.3) behind a result
//! handle, `SherdRefinement`, that holds the refined axis, its report and the Pareto
//! front.

use super::buffer::{SherdBuffer, hand_out_report, hand_out_text};
use super::error::{Failure, FfiResult};
use super::mesh::{SherdMesh, mesh_ref};
use super::options::{SherdRefineOptions, options_or_default};
use super::orient::{SherdAxis, read_axis};
use super::panic::guard;
use super::pointers::{SizedStruct, borrow, host_slice_mut, require, write_out, write_sized};
use super::status::SherdStatus;
use crate::refine::circle_fit::CircleFitMethod;
use crate::refine::pareto::ParetoChoice;
use crate::refine::profile::ProfileMethod;
use crate::refine::tangent::Edge;
use crate::refine::{Criterion, Refinement, Surface};

/// The refinement criteria (`SherdRefineOptions`' criterion, and the one a report says
/// was used).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SherdCriterion {
    /// Horizontal circles: radius variance (Eq. 2).
    Circles = 0,
    /// Circle centres and residuals on a Pareto front (Eq. 3-4).
    Pareto = 1,
    /// Vertical profile superposition (Eq. 5-6).
    Profile = 2,
    /// Tangent plane to the rim or base (Eq. 7), then circles for the position.
    Tangent = 3,
    /// The tangent plane when the fragment keeps a level rim or base; otherwise circles,
    /// averaged with the profile criterion where the two agree within 5 degrees.
    Auto = 4,
}

impl SherdCriterion {
    /// The criterion for a value from the host.
    pub(crate) fn parse(value: u32) -> FfiResult<Criterion> {
        Ok(match value {
            0 => Criterion::Circles,
            1 => Criterion::Pareto,
            2 => Criterion::Profile,
            3 => Criterion::Tangent,
            4 => Criterion::Auto,
            other => return Err(Failure::invalid(format!("`criterion` {other} is not a SHERD_CRITERION_* value (0 to 4)"))),
        })
    }

    fn of(criterion: Criterion) -> Self {
        match criterion {
            Criterion::Circles => SherdCriterion::Circles,
            Criterion::Pareto => SherdCriterion::Pareto,
            Criterion::Profile => SherdCriterion::Profile,
            Criterion::Tangent => SherdCriterion::Tangent,
            Criterion::Auto => SherdCriterion::Auto,
        }
    }
}

/// Which solution of the Pareto front becomes the axis (`sherd_refine_options_set_pareto_choice`).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SherdParetoChoice {
    /// The knee: the smallest product of the two costs (the default).
    Knee = 0,
    /// The best centre dispersion (Eq. 3 alone).
    Centres = 1,
    /// The best circle residual (Eq. 4 alone).
    Residuals = 2,
    /// The mean of the tilts of the `count` best solutions by their scaled costs (the
    /// original tool takes 2).
    MeanOfBest = 3,
}

impl SherdParetoChoice {
    /// The choice for a value and count from the host.
    pub(crate) fn parse(value: u32, count: usize) -> FfiResult<ParetoChoice> {
        Ok(match value {
            0 => ParetoChoice::Knee,
            1 => ParetoChoice::Centres,
            2 => ParetoChoice::Residuals,
            3 => ParetoChoice::MeanOfBest(count),
            other => return Err(Failure::invalid(format!("`choice` {other} is not a SHERD_PARETO_CHOICE_* value (0 to 3)"))),
        })
    }
}

/// The edge the tangent plane (Eq. 7) rests on (`sherd_refine_options_set_edge`).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SherdEdge {
    /// The one whose extremes are level (the default).
    Detect = 0,
    /// The rim: the highest point per vertical section.
    Rim = 1,
    /// The base: the lowest point per vertical section.
    Base = 2,
}

impl SherdEdge {
    /// The edge for a value from the host (`None`: detect it).
    pub(crate) fn parse(value: u32) -> FfiResult<Option<Edge>> {
        Ok(match value {
            0 => None,
            1 => Some(Edge::Rim),
            2 => Some(Edge::Base),
            other => return Err(Failure::invalid(format!("`edge` {other} is not a SHERD_EDGE_* value (0 to 2)"))),
        })
    }
}

/// The form of the profile criterion (`sherd_refine_options_set_profile_method`).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SherdProfileMethod {
    /// Eq. 5: distance to the longest vertical profile; the parameter is the number of
    /// vertical sections (2 to 1000).
    Reference = 0,
    /// Eq. 6: a polynomial profile per skin; the parameter is its degree (1 to 20).
    Polynomial = 1,
    /// Eq. 6 with a cubic spline profile per skin (the default); the parameter is the
    /// distance between its knots, mm (0.1 to 1000; 1.5 by default).
    Spline = 2,
}

impl SherdProfileMethod {
    /// The method for a value and parameter from the host.
    pub(crate) fn parse(value: u32, parameter: f64) -> FfiResult<ProfileMethod> {
        let whole = || {
            if parameter.fract() == 0.0 && (0.0..=1e6).contains(&parameter) {
                Ok(parameter as usize)
            } else {
                Err(Failure::invalid(format!("`parameter` must be a whole number for this method, got {parameter}")))
            }
        };
        let method = match value {
            0 => ProfileMethod::ReferenceProfile { vertical_sections: whole()? },
            1 => ProfileMethod::Polynomial { degree: whole()? },
            2 => ProfileMethod::Spline { knot_spacing_mm: parameter },
            other => return Err(Failure::invalid(format!("`method` {other} is not a SHERD_PROFILE_METHOD_* value (0 to 2)"))),
        };
        Ok(method.validated()?)
    }
}

/// The circle fit of each horizontal section in the Pareto criterion (Chernov), for
/// `sherd_refine_options_set_circle_fit`.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SherdCircleFit {
    /// Kåsa's algebraic fit: fast, biased towards small radii on short arcs.
    Kasa = 0,
    /// Pratt's algebraic fit.
    Pratt = 1,
    /// Taubin's algebraic fit: nearly unbiased (the default).
    Taubin = 2,
    /// The geometric fit (orthogonal distances), started from Taubin's.
    Geometric = 3,
}

impl SherdCircleFit {
    /// The fit for a value from the host.
    pub(crate) fn parse(value: u32) -> FfiResult<CircleFitMethod> {
        Ok(match value {
            0 => CircleFitMethod::Kasa,
            1 => CircleFitMethod::Pratt,
            2 => CircleFitMethod::Taubin,
            3 => CircleFitMethod::Geometric,
            other => return Err(Failure::invalid(format!("`method` {other} is not a SHERD_CIRCLE_FIT_* value (0 to 3)"))),
        })
    }
}

/// The surfaces a refinement looks at.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SherdSurface {
    /// The inside of the vessel.
    Inner = 0,
    /// The outside of the vessel.
    Outer = 1,
    /// Both skins, each on its own.
    Both = 2,
}

impl SherdSurface {
    /// The surface for a value from the host.
    pub(crate) fn parse(value: u32) -> FfiResult<Surface> {
        Ok(match value {
            0 => Surface::Inner,
            1 => Surface::Outer,
            2 => Surface::Both,
            other => return Err(Failure::invalid(format!("`surface` {other} is not a SHERD_SURFACE_* value (0 to 2)"))),
        })
    }

    fn of(surface: Surface) -> Self {
        match surface {
            Surface::Inner => SherdSurface::Inner,
            Surface::Outer => SherdSurface::Outer,
            Surface::Both => SherdSurface::Both,
        }
    }
}

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
            criterion: SherdCriterion::of(report.method) as u32,
            surface: SherdSurface::of(report.surface) as u32,
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
