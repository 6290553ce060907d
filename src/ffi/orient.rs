//! Orientation: automatic and from three points, the axis as the host sees it
//! (`SherdAxis`), and the oriented frame as a 4x4 matrix hosts apply to their objects.

use super::buffer::{SherdBuffer, hand_out_report};
use super::error::{Failure, FfiResult};
use super::mesh::{SherdMesh, mesh_ref};
use super::builder::{assign, builder, fraction, free_builder, new_builder, options_or_default, positive_count, positive_or_default, at_most};
use super::panic::guard;
use super::pointers::{SizedStruct, checked_size, host_slice, host_slice_mut, read_sized, require, write_out, write_sized};
use super::status::SherdStatus;
use crate::mesh::Point;
use crate::orient::{Axis, AxisRecord, ManualOptions, OrientOptions, Orientation, Verdict};
use crate::profile::rills::{three_points_on, trace_rills_under, RillOptions};
use crate::profile::section::oriented_frame;

/// A vessel's rotation axis in the scan's frame and units: a point on it and a unit
/// direction pointing from the base towards the rim.
///
/// Set `size` to `sizeof(SherdAxis)` before passing the struct to any function, as
/// input or output: later versions of the library may add fields at the end, and read or
/// write only the fields your header declares.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SherdAxis {
    /// `sizeof(SherdAxis)`, set by the caller.
    pub size: usize,
    /// `x, y, z` of a point on the axis.
    pub point: [f64; 3],
    /// `dx, dy, dz`: unit length on output; any non-zero length on input.
    pub direction: [f64; 3],
}

unsafe impl SizedStruct for SherdAxis {
    const NAME: &'static str = "SherdAxis";
    const MIN_SIZE: usize = size_of::<SherdAxis>();
}

impl SherdAxis {
    /// The C form of `axis`.
    pub(crate) fn from_axis(axis: &Axis) -> Self {
        let record = axis.record();
        SherdAxis { size: size_of::<SherdAxis>(), point: record.point, direction: record.direction }
    }
}

/// Reads and checks the host's axis: finite values, non-zero direction.
pub(crate) unsafe fn read_axis(axis: *const SherdAxis, name: &str) -> FfiResult<Axis> {
    let axis = unsafe { read_sized(axis, name) }?;
    Axis::from_record(&AxisRecord { point: axis.point, direction: axis.direction }).ok_or_else(|| {
        Failure::invalid(format!(
            "`{name}` must have a finite point and a finite non-zero direction, got point {:?} direction {:?}",
            axis.point, axis.direction
        ))
    })
}

/// Writes `transform` as a row-major 4x4 matrix into `out_matrix`.
fn write_matrix(transform: &nalgebra::Isometry3<f64>, out_matrix: *mut f64) -> FfiResult {
    let out = unsafe { host_slice_mut(out_matrix, 16, 1, "out_matrix") }?;
    let matrix = transform.to_homogeneous();
    for row in 0..4 {
        for column in 0..4 {
            out[4 * row + column] = matrix[(row, column)];
        }
    }
    Ok(())
}

/// Writes the rigid transform from the scan's frame to the oriented frame as a
/// row-major 4x4 matrix (`out_matrix[4 * row + column]`, 16 doubles) acting on column
/// vectors `(x, y, z, 1)`: the axis becomes the z axis, base down and rim up, and
/// `reference_point` (3 doubles; usually the fragment's centroid) lands on the +x
/// half-plane, where the drawing shows the exterior.
///
/// Row-major is numpy's, Blender's `Matrix(rows)` and VCG's `Matrix44` (MeshLab's layer
/// transform, `m[row][column]`) layout; OpenGL's column-major arrays take the transpose.
///
/// # Safety
/// `axis` must point to a `SherdAxis` with `size` set; `reference_point` to 3 doubles;
/// `out_matrix` to room for 16 doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_axis_oriented_transform(
    axis: *const SherdAxis,
    reference_point: *const f64,
    out_matrix: *mut f64,
) -> SherdStatus {
    guard("sherd_axis_oriented_transform", || {
        let axis = unsafe { read_axis(axis, "axis") }?;
        let reference = unsafe { host_slice(reference_point, 1, 3, "reference_point") }?;
        if !reference.iter().all(|c| c.is_finite()) {
            return Err(Failure::invalid(format!("`reference_point` is not finite: {reference:?}")));
        }
        let reference = Point::new(reference[0], reference[1], reference[2]);
        write_matrix(&axis.to_oriented_frame(&reference), out_matrix)
    })
}

/// Like `sherd_axis_oriented_transform` with the centroid of `mesh`'s vertices as the
/// reference point: the frame every profile, measurement, drawing and export uses.
///
/// # Safety
/// `mesh` must be a live handle; otherwise as for `sherd_axis_oriented_transform`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_oriented_transform(
    mesh: *const SherdMesh,
    axis: *const SherdAxis,
    out_matrix: *mut f64,
) -> SherdStatus {
    guard("sherd_mesh_oriented_transform", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let axis = unsafe { read_axis(axis, "axis") }?;
        write_matrix(&oriented_frame(mesh, &axis), out_matrix)
    })
}

/// How far to trust an orientation (written by `sherd_orient_automatic` and
/// `sherd_orient_from_three_points` when the caller passes one). Set `size` to
/// `sizeof(SherdOrientReport)` first.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SherdOrientReport {
    /// `sizeof(SherdOrientReport)`, set by the caller.
    pub size: usize,
    /// True when the data determine the axis and its sense; false with
    /// `SHERD_STATUS_NEEDS_MANUAL_ORIENTATION` and `SHERD_STATUS_SENSE_UNCERTAIN`.
    pub oriented: bool,
    /// How far the direction can turn, degrees, before the axis fits the sherd worse
    /// region by region (the width of its valley in units of the sherd's own noise and
    /// deformation; the pipeline's bootstrap gives the calibrated interval). NaN for a
    /// manual axis; infinite when the automatic orientation found no axis at all (the
    /// axis written is then no guess: see `sherd_orient_automatic`).
    pub angle_uncertainty_deg: f64,
    /// The same for a move of the axis across itself near the sherd, millimetres.
    pub position_uncertainty_mm: f64,
    /// Vertices of the working copy kept as the surface of revolution.
    pub kept_vertex_count: usize,
}

unsafe impl SizedStruct for SherdOrientReport {
    const NAME: &'static str = "SherdOrientReport";
    const MIN_SIZE: usize = size_of::<SherdOrientReport>();
}

/// Hands an orientation to the host: the axis always (the best estimate, also when it
/// needs a human), the report when asked for, and `NEEDS_MANUAL_ORIENTATION` with the
/// reason as the status when the data do not determine the axis, `SENSE_UNCERTAIN` when
/// they determine its line but not which way it points.
unsafe fn hand_out_orientation(
    orientation: &Orientation,
    out_axis: *mut SherdAxis,
    out_report: *mut SherdOrientReport,
    out_report_json: *mut *mut SherdBuffer,
) -> FfiResult {
    unsafe { write_sized(out_axis, SherdAxis::from_axis(&orientation.axis), "out_axis") }?;
    if !out_report.is_null() {
        let report = SherdOrientReport {
            size: size_of::<SherdOrientReport>(),
            oriented: orientation.verdict.is_oriented(),
            angle_uncertainty_deg: orientation.angle_uncertainty_deg,
            position_uncertainty_mm: orientation.position_uncertainty_mm,
            kept_vertex_count: orientation.kept_vertex_count,
        };
        unsafe { write_sized(out_report, report, "out_report") }?;
    }
    unsafe { hand_out_report(out_report_json, &orientation.report) }?;
    match &orientation.verdict {
        Verdict::Oriented => Ok(()),
        Verdict::NeedsManualOrientation { reason } => {
            Err(Failure::new(SherdStatus::NeedsManualOrientation, reason.clone()))
        }
        Verdict::SenseUncertain { reason } => Err(Failure::new(SherdStatus::SenseUncertain, reason.clone())),
    }
}

/// Checks the output pointers before a long computation, so that a mistake is reported
/// at once.
fn check_orientation_outputs(out_axis: *mut SherdAxis, out_report: *mut SherdOrientReport) -> FfiResult {
    checked_size(out_axis.cast_const(), "out_axis")?;
    if !out_report.is_null() {
        checked_size(out_report.cast_const(), "out_report")?;
    }
    Ok(())
}

/// Finds the rotation axis from the surface normals (Wilczek et al. 2018, section 2.2).
///
/// `options` may be NULL for the defaults. `out_axis` (its `size` set) receives the
/// axis, base to rim, in the mesh's frame. `out_report` (its `size` set) and
/// `out_report_json` (the full report as JSON) may be NULL.
///
/// Returns `SHERD_STATUS_NEEDS_MANUAL_ORIENTATION` when the fragment does not determine
/// its axis (a flat base piece, a near-spherical piece, one too small): the axis is
/// still written, as a best guess not to be trusted, and the message gives the reason;
/// ask the user for three points (`sherd_orient_from_three_points`). When the fragment
/// gave no axis at all (too few points on a surface of revolution), the report's
/// `angle_uncertainty_deg` is infinite and the axis written is only a vertical through
/// the centroid, no guess.
/// Returns `SHERD_STATUS_SENSE_UNCERTAIN` when the axis line is determined but not which
/// way is up (base to rim): the axis is written, its sense a guess.
///
/// # Safety
/// `mesh` must be a live handle; `options` NULL or live; the out-pointers writable or,
/// where allowed, NULL.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_orient_automatic(
    mesh: *const SherdMesh,
    options: *const SherdOrientOptions,
    out_axis: *mut SherdAxis,
    out_report: *mut SherdOrientReport,
    out_report_json: *mut *mut SherdBuffer,
) -> SherdStatus {
    guard("sherd_orient_automatic", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let options = unsafe { options_or_default(options, |builder| &builder.options) }?;
        check_orientation_outputs(out_axis, out_report)?;
        let orientation = crate::orient::orient_automatic(mesh, &options)?;
        unsafe { hand_out_orientation(&orientation, out_axis, out_report, out_report_json) }
    })
}

/// Finds the rotation axis from three points the user picked on one horizontal feature
/// (the rim's edge, a groove, the base's edge): `points` holds 9 doubles, `x y z` of each,
/// in the mesh's frame. The points must lie on the sherd (within the options' pick
/// distance) and not on one line.
///
/// Outputs as for `sherd_orient_automatic`.
///
/// # Safety
/// `mesh` must be a live handle; `points` must hold 9 doubles; `options` NULL or live;
/// the out-pointers writable or, where allowed, NULL.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_orient_from_three_points(
    mesh: *const SherdMesh,
    points: *const f64,
    options: *const SherdManualOptions,
    out_axis: *mut SherdAxis,
    out_report: *mut SherdOrientReport,
    out_report_json: *mut *mut SherdBuffer,
) -> SherdStatus {
    guard("sherd_orient_from_three_points", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let values = unsafe { host_slice(points, 3, 3, "points") }?;
        if let Some(i) = values.iter().position(|v| !v.is_finite()) {
            return Err(Failure::invalid(format!("point {} has a non-finite coordinate", i / 3 + 1)));
        }
        let picked = [0, 1, 2].map(|k| Point::new(values[3 * k], values[3 * k + 1], values[3 * k + 2]));
        let options = unsafe { options_or_default(options, |builder| &builder.options) }?;
        check_orientation_outputs(out_axis, out_report)?;
        let orientation = crate::orient::orient_from_three_points(mesh, picked, &options)?;
        unsafe { hand_out_orientation(&orientation, out_axis, out_report, out_report_json) }
    })
}

/// Three points on the longest wheel rill traced under `axis`, for
/// `sherd_orient_from_three_points`: where to pick on a sherd `sherd_orient_automatic`
/// declines, under the axis it still wrote (the command-line tool's
/// `manual_points_on_rill`, without orienting the sherd a second time). `out_points` (room
/// for 9 doubles: `x y z` of each point, in the mesh's frame and units) is written and
/// `*out_point_count` set to 3 when a rill is traced; on a smooth wall nothing is written
/// and it is set to 0. Wheel rills are found by their depth in millimetres: `mesh` is in
/// millimetres.
///
/// # Safety
/// `mesh` must be a live handle; `axis` must have its `size` set; `out_points` writable
/// for 9 doubles; `out_point_count` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_points_on_longest_rill(
    mesh: *const SherdMesh,
    axis: *const SherdAxis,
    out_points: *mut f64,
    out_point_count: *mut usize,
) -> SherdStatus {
    guard("sherd_points_on_longest_rill", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let axis = unsafe { read_axis(axis, "axis") }?;
        let out = unsafe { host_slice_mut(out_points, 3, 3, "out_points") }?;
        require(out_point_count.cast_const(), "out_point_count")?;
        let rills = trace_rills_under(mesh, &axis, &RillOptions::default());
        let count = match rills.first() {
            Some(longest) => {
                for (chunk, point) in out.chunks_exact_mut(3).zip(three_points_on(longest)) {
                    chunk.copy_from_slice(&[point.x, point.y, point.z]);
                }
                3
            }
            None => 0,
        };
        unsafe { write_out(out_point_count, count, "out_point_count") }
    })
}

// ---------------------------------------------------------------- automatic orientation options

/// Options of `sherd_orient_automatic`.
pub struct SherdOrientOptions {
    pub(crate) options: OrientOptions,
}

builder!(SherdOrientOptions => OrientOptions);

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

// ---------------------------------------------------------------- manual orientation options

/// Options of `sherd_orient_from_three_points`.
pub struct SherdManualOptions {
    pub(crate) options: ManualOptions,
}

builder!(SherdManualOptions => ManualOptions);

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
