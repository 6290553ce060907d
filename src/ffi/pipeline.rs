//! The whole pipeline in one call (`pipeline`): what `sherd orient --json` does, for
//! hosts that want the command-line tool's record without running it.

use std::ffi::c_char;

use super::buffer::{SherdBuffer, hand_out_report};
use super::error::{Failure, FfiResult};
use super::mesh::{SherdMesh, mesh_ref};
use super::refine::SherdRefineOptions;
use super::orient::SherdAxis;
use super::panic::guard;
use super::pointers::{borrow, checked_size, path_from, write_sized};
use super::status::SherdStatus;
use crate::orient::Axis;
use crate::pipeline::{Analysis, PipelineOptions, RecordStatus, SherdRecord};

/// The pipeline's options: scan units and the refinement (NULL: the command-line tool's
/// default, criterion AUTO on both surfaces). Checks `out_axis` too, before the long work.
unsafe fn pipeline_options(
    refine_options: *const SherdRefineOptions,
    millimetres_per_unit: f64,
    out_axis: *const SherdAxis,
) -> FfiResult<PipelineOptions> {
    if !out_axis.is_null() {
        checked_size(out_axis, "out_axis")?;
    }
    if !(millimetres_per_unit.is_finite() && millimetres_per_unit > 0.0) {
        return Err(Failure::invalid(format!(
            "`millimetres_per_unit` must be finite and positive (1 for mm, 10 for cm), got {millimetres_per_unit}"
        )));
    }
    let refine = if refine_options.is_null() {
        Default::default()
    } else {
        unsafe { borrow(refine_options, "refine_options") }?.options.clone()
    };
    let mut options = PipelineOptions { millimetres_per_unit, ..Default::default() };
    options.refine = Some(refine);
    Ok(options)
}

/// Hands the pipeline's outcome to the host: the record as JSON (a failed one on error;
/// a declined sherd's with its `best_guess`), the axis (scan frame and units) when the
/// sherd is oriented (also when only its sense is uncertain), and the status: the
/// error's own, NEEDS_MANUAL_ORIENTATION or SENSE_UNCERTAIN with the reason, or OK.
unsafe fn hand_out_analysis(
    file: String,
    analysis: crate::Result<Analysis>,
    out_axis: *mut SherdAxis,
    out_record_json: *mut *mut SherdBuffer,
) -> FfiResult {
    let analysis = match analysis {
        Ok(analysis) => analysis,
        Err(error) => {
            unsafe { hand_out_report(out_record_json, &SherdRecord::failed(file, &error)) }?;
            return Err(error.into());
        }
    };
    let record = SherdRecord::from_analysis(file, &analysis);
    if let (false, Some(axis)) = (out_axis.is_null(), record.axis.as_ref().and_then(Axis::from_record)) {
        unsafe { write_sized(out_axis, SherdAxis::from_axis(&axis), "out_axis") }?;
    }
    unsafe { hand_out_report(out_record_json, &record) }?;
    match record.status {
        RecordStatus::NeedsManualOrientation => Err(Failure::new(SherdStatus::NeedsManualOrientation, record.reason.clone().unwrap_or_default())),
        RecordStatus::SenseUncertain => Err(Failure::new(SherdStatus::SenseUncertain, record.reason.clone().unwrap_or_default())),
        _ => Ok(()),
    }
}

/// Reads, repairs, orients, refines and measures the scan at `path`, exactly as
/// `sherd orient SCAN --json` does: `*out_record_json` (or NULL) receives the same JSON
/// object the command prints, `out_axis` (its `size` set, or NULL) the final axis in the
/// scan's frame and units. `refine_options` may be NULL (criterion AUTO);
/// `millimetres_per_unit` is 1 for scans in millimetres.
///
/// Returns `SHERD_STATUS_NEEDS_MANUAL_ORIENTATION` (record written, `out_axis` not) when
/// the sherd does not determine its axis: the record's `"axis"` is null and its
/// `"best_guess"` holds the axis the orientation still found, not to be trusted
/// (`{"axis": {"point": [x, y, z], "direction": [dx, dy, dz]}, "against": reason,
/// "sense_known": bool}`, scan frame and units, base to rim as the sense cues read it;
/// null when it found none, too few points); `SHERD_STATUS_SENSE_UNCERTAIN` (record and axis
/// written, refined and measured) when it determines the axis line but not which way is up;
/// `SHERD_STATUS_OK` with the record's `"status"` `"axis_uncertain"` (and its `"reason"`)
/// when the axis is found but not pinned down: check it before using its figures. When
/// the scan cannot be read or processed the
/// record (status `"error"`) is still written, no axis, and the status says why:
/// `SHERD_STATUS_IO`, `SHERD_STATUS_PARSE`, `SHERD_STATUS_NOT_CONVERGED`...
///
/// # Safety
/// `path` must be a NUL-terminated string; `refine_options` NULL or live; the
/// out-pointers NULL or writable (`out_axis` with its `size` set).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_process_file(
    path: *const c_char,
    refine_options: *const SherdRefineOptions,
    millimetres_per_unit: f64,
    out_axis: *mut SherdAxis,
    out_record_json: *mut *mut SherdBuffer,
) -> SherdStatus {
    guard("sherd_process_file", || {
        let path = unsafe { path_from(path, "path") }?;
        let options = unsafe { pipeline_options(refine_options, millimetres_per_unit, out_axis) }?;
        let analysis = crate::pipeline::analyse_file(&path, &options);
        unsafe { hand_out_analysis(path.display().to_string(), analysis, out_axis, out_record_json) }
    })
}

/// Like `sherd_process_file` for a mesh the host already holds (its record's `file` is
/// `"<memory>"`); `mesh` is not changed (the pipeline repairs a copy).
///
/// # Safety
/// `mesh` must be a live handle; otherwise as for `sherd_process_file`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_analyse(
    mesh: *const SherdMesh,
    refine_options: *const SherdRefineOptions,
    millimetres_per_unit: f64,
    out_axis: *mut SherdAxis,
    out_record_json: *mut *mut SherdBuffer,
) -> SherdStatus {
    guard("sherd_analyse", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let options = unsafe { pipeline_options(refine_options, millimetres_per_unit, out_axis) }?;
        let analysis = crate::pipeline::analyse(mesh.clone(), &options);
        unsafe { hand_out_analysis("<memory>".into(), analysis, out_axis, out_record_json) }
    })
}
