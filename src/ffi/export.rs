//! Exports in the oriented frame: the oriented mesh and the 3D reconstruction as PLY, the
//! profile section as CSV (to a file or to memory).

use std::ffi::c_char;

use super::buffer::{SherdBuffer, hand_out_text};
use super::mesh::{SherdMesh, mesh_ref, ply_encoding};
use super::orient::{SherdAxis, read_axis};
use super::panic::guard;
use super::pointers::{path_from, require, write_out};
use super::status::SherdStatus;
use super::reconstruct::{reconstruction, section_at};
use crate::profile::revolve::oriented_mesh;
use crate::profile::section::most_informative_angle;

/// Writes the mesh moved into the oriented frame (axis on z, base down, the fragment's
/// centroid on +x: `sherd_mesh_oriented_transform`) as PLY, binary little-endian when
/// `binary` is true; normals are rotated with it. Atomic: no half-written file on error.
///
/// # Safety
/// `mesh` must be a live handle; `axis` must have its `size` set; `path` must be a
/// NUL-terminated string.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_export_oriented_ply(
    mesh: *const SherdMesh,
    axis: *const SherdAxis,
    path: *const c_char,
    binary: bool,
) -> SherdStatus {
    guard("sherd_export_oriented_ply", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let axis = unsafe { read_axis(axis, "axis") }?;
        let path = unsafe { path_from(path, "path") }?;
        Ok(crate::mesh::io::write_ply(&path, &oriented_mesh(mesh, &axis), ply_encoding(binary))?)
    })
}

/// Writes the most informative angle for the profile (the tallest cut, away from the
/// fracture faces), radians about the axis from the fragment's centroid, to `*out_angle_rad`.
///
/// # Safety
/// `mesh` must be a live handle; `axis` must have its `size` set; `out_angle_rad` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_profile_most_informative_angle(
    mesh: *const SherdMesh,
    axis: *const SherdAxis,
    out_angle_rad: *mut f64,
) -> SherdStatus {
    guard("sherd_profile_most_informative_angle", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let axis = unsafe { read_axis(axis, "axis") }?;
        require(out_angle_rad.cast_const(), "out_angle_rad")?;
        unsafe { write_out(out_angle_rad, most_informative_angle(mesh, &axis), "out_angle_rad") }
    })
}

/// Writes the profile section at `angle_rad` about the axis (NaN: the most informative
/// angle) as CSV `curve,index,r_mm,z_mm,closed`, one line per point in the oriented
/// frame. Atomic. `SHERD_STATUS_DEGENERATE_GEOMETRY` when the cut misses the mesh.
///
/// # Safety
/// `mesh` must be a live handle; `axis` must have its `size` set; `path` must be a
/// NUL-terminated string.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_export_profile_csv(
    mesh: *const SherdMesh,
    axis: *const SherdAxis,
    angle_rad: f64,
    path: *const c_char,
) -> SherdStatus {
    guard("sherd_export_profile_csv", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let axis = unsafe { read_axis(axis, "axis") }?;
        let path = unsafe { path_from(path, "path") }?;
        Ok(section_at(mesh, &axis, angle_rad)?.write_csv(&path)?)
    })
}

/// Like `sherd_export_profile_csv`, into a new NUL-terminated buffer `*out_csv`.
///
/// # Safety
/// `mesh` must be a live handle; `axis` must have its `size` set; `out_csv` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_profile_csv(
    mesh: *const SherdMesh,
    axis: *const SherdAxis,
    angle_rad: f64,
    out_csv: *mut *mut SherdBuffer,
) -> SherdStatus {
    guard("sherd_profile_csv", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let axis = unsafe { read_axis(axis, "axis") }?;
        require(out_csv.cast_const(), "out_csv")?;
        let csv = section_at(mesh, &axis, angle_rad)?.to_csv();
        unsafe { hand_out_text(out_csv, csv) }
    })
}

/// Writes the 3D reconstruction of the preserved part of the vessel as PLY: the closed
/// outlines of the profile section at `angle_rad` (NaN: the most informative angle)
/// revolved a full turn about the axis with `segments` steps (0: 180, 2 degrees each; at
/// least 3 otherwise), in the oriented frame, watertight. Atomic.
/// `SHERD_STATUS_DEGENERATE_GEOMETRY` when the section has no closed outline.
///
/// # Safety
/// `mesh` must be a live handle; `axis` must have its `size` set; `path` must be a
/// NUL-terminated string.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_export_reconstruction_ply(
    mesh: *const SherdMesh,
    axis: *const SherdAxis,
    angle_rad: f64,
    segments: usize,
    path: *const c_char,
    binary: bool,
) -> SherdStatus {
    guard("sherd_export_reconstruction_ply", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let axis = unsafe { read_axis(axis, "axis") }?;
        let path = unsafe { path_from(path, "path") }?;
        let vessel = reconstruction(mesh, &axis, angle_rad, segments)?;
        Ok(crate::mesh::io::write_ply(&path, &vessel, ply_encoding(binary))?)
    })
}
