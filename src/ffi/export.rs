//! Exports in the oriented frame: the oriented mesh and the 3D reconstruction as PLY (or
//! as a mesh handle), the profile section as CSV (to a file or to memory), and the vessel
//! regularity painted on a copy of the mesh.

use std::ffi::c_char;

use super::buffer::{SherdBuffer, hand_out_text};
use super::error::{Failure, FfiResult};
use super::mesh::{SherdMesh, hand_out, mesh_ref, ply_encoding};
use super::orient::{SherdAxis, read_axis};
use super::panic::guard;
use super::pointers::{path_from, require, write_out};
use super::status::SherdStatus;
use crate::mesh::Mesh;
use crate::orient::Axis;
use crate::profile::regularity::{ColorMap, ColorScale, distance_to_axis, distance_to_ideal_vessel, regularity_mesh};
use crate::profile::revolve::{oriented_mesh, revolve_profile};
use crate::profile::section::{ProfileSection, most_informative_angle, profile_section};

/// The section at `angle_rad`, or at the most informative angle when it is NaN.
fn section_at(mesh: &Mesh, axis: &Axis, angle_rad: f64) -> FfiResult<ProfileSection> {
    let angle = if angle_rad.is_nan() { most_informative_angle(mesh, axis) } else { angle_rad };
    crate::profile::section::check_angle(angle)?;
    let section = profile_section(mesh, axis, angle);
    if section.is_empty() {
        return Err(Failure::new(
            SherdStatus::DegenerateGeometry,
            format!("the half-plane at {angle} rad does not cut the mesh: no profile there"),
        ));
    }
    Ok(section)
}

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

/// Steps per turn of a reconstruction when the caller passes 0: 2 degrees each.
const DEFAULT_REVOLUTION_SEGMENTS: usize = 180;

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
        Ok(crate::mesh::io::write_ply(&path, &reconstruction(mesh, &axis, angle_rad, segments)?, ply_encoding(binary))?)
    })
}

/// The revolved section of `sherd_export_reconstruction_ply` and `sherd_reconstruction_mesh`.
fn reconstruction(mesh: &Mesh, axis: &Axis, angle_rad: f64, segments: usize) -> FfiResult<Mesh> {
    let segments = if segments == 0 { DEFAULT_REVOLUTION_SEGMENTS } else { segments };
    Ok(revolve_profile(&section_at(mesh, axis, angle_rad)?, segments)?)
}

/// Like `sherd_export_reconstruction_ply`, into a new mesh `*out_mesh` (in the oriented
/// frame: axis on z, base down, as `sherd_mesh_oriented_transform` moves the scan), for
/// hosts that show the reconstruction as a layer or object of their own.
///
/// # Safety
/// `mesh` must be a live handle; `axis` must have its `size` set; `out_mesh` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_reconstruction_mesh(
    mesh: *const SherdMesh,
    axis: *const SherdAxis,
    angle_rad: f64,
    segments: usize,
    out_mesh: *mut *mut SherdMesh,
) -> SherdStatus {
    guard("sherd_reconstruction_mesh", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let axis = unsafe { read_axis(axis, "axis") }?;
        require(out_mesh.cast_const(), "out_mesh")?;
        let vessel = reconstruction(mesh, &axis, angle_rad, segments)?;
        unsafe { hand_out(out_mesh, vessel) }
    })
}

/// Paints vessel regularity (Wilczek et al. 2018, section 2.4.4) on a copy of `mesh`:
/// `*out_mesh` receives the same vertices and triangles, in the mesh's own frame, with
/// each vertex's value as its quality (`sherd_mesh_copy_quality`) and its colour on the
/// map (`sherd_mesh_copy_colors`). `regularity` is a `SHERD_REGULARITY_*` value:
/// `AXIS_DISTANCE` gives the distance to the axis in mm (rainbow map, as the drawing's
/// regularity style); `IDEAL_VESSEL` the signed distance in mm to the vessel revolved
/// from the section at `angle_rad` (NaN: the most informative angle), positive outside
/// (blue-white-red map centred on 0, as `sherd export --regularity`).
/// `SHERD_STATUS_DEGENERATE_GEOMETRY` when that section has no closed outline.
///
/// # Safety
/// `mesh` must be a live handle; `axis` must have its `size` set; `out_mesh` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_regularity_mesh(
    mesh: *const SherdMesh,
    axis: *const SherdAxis,
    regularity: u32,
    angle_rad: f64,
    out_mesh: *mut *mut SherdMesh,
) -> SherdStatus {
    guard("sherd_regularity_mesh", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let axis = unsafe { read_axis(axis, "axis") }?;
        require(out_mesh.cast_const(), "out_mesh")?;
        let (values, map) = match regularity {
            0 => {
                let values = distance_to_axis(mesh, &axis);
                let map = ColorMap::fitted(&values, ColorScale::Rainbow, "distance to axis", "mm");
                (values, map)
            }
            1 => {
                let values = distance_to_ideal_vessel(mesh, &axis, &section_at(mesh, &axis, angle_rad)?)?;
                let map = ColorMap::fitted(&values, ColorScale::Diverging, "distance to the ideal vessel", "mm");
                (values, map)
            }
            other => return Err(Failure::invalid(format!("`regularity` {other} is not a SHERD_REGULARITY_* value (0 or 1)"))),
        };
        unsafe { hand_out(out_mesh, regularity_mesh(mesh, &values, &map)?) }
    })
}
