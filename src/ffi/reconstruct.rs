//! The 3D reconstruction and the regularity map as arrays for hosts that show them
//! themselves (a new object in Blender, a layer in MeshLab) instead of reading a file.
//!
//! Arrays follow the rules of `sherd_mesh_copy_*`: the host asks for the count
//! (`sherd_mesh_vertex_count`), passes buffers with room for that many items and their
//! capacity; a smaller capacity gives `SHERD_STATUS_BUFFER_TOO_SMALL` with nothing written.

use super::error::{Failure, FfiResult};
use super::mesh::{SherdMesh, copy_out, hand_out, mesh_ref};
use super::enums::{CEnum, SherdRegularity};
use super::orient::{SherdAxis, read_axis};
use super::panic::guard;
use super::pointers::{host_slice_mut, require};
use super::status::SherdStatus;
use crate::draw::RegularityKind;
use crate::mesh::Mesh;
use crate::orient::Axis;
use crate::profile::regularity::{ColorMap, axis_distance_map, ideal_vessel_map};
use crate::profile::revolve::revolve_profile;
use crate::profile::section::{ProfileSection, most_informative_angle, profile_section};

/// Steps per turn of a reconstruction when the caller passes 0: 2 degrees each.
pub(crate) const DEFAULT_REVOLUTION_SEGMENTS: usize = 180;

/// The section at `angle_rad`, or at the most informative angle when it is NaN.
pub(crate) fn section_at(mesh: &Mesh, axis: &Axis, angle_rad: f64) -> FfiResult<ProfileSection> {
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

/// The preserved part of the vessel revolved from the section at `angle_rad` (NaN: the
/// most informative angle) with `segments` steps (0: the default).
pub(crate) fn reconstruction(mesh: &Mesh, axis: &Axis, angle_rad: f64, segments: usize) -> FfiResult<Mesh> {
    let segments = if segments == 0 { DEFAULT_REVOLUTION_SEGMENTS } else { segments };
    Ok(revolve_profile(&section_at(mesh, axis, angle_rad)?, segments)?)
}

/// Creates the 3D reconstruction of the preserved part of the vessel as a new mesh: the
/// closed outlines of the profile section at `angle_rad` (NaN: the most informative angle)
/// revolved a full turn with `segments` steps (0: 180, 2 degrees each; at least 3
/// otherwise). It is watertight, with outward-facing triangles, in the oriented frame
/// (axis on z, rim up): place it with the scan by applying the inverse of
/// `sherd_mesh_oriented_transform`. Read it with `sherd_mesh_vertex_count`,
/// `sherd_mesh_copy_positions` and `sherd_mesh_copy_triangles`; free it with
/// `sherd_mesh_free`. `SHERD_STATUS_DEGENERATE_GEOMETRY` when the section has no closed
/// outline; `*out_mesh` is left unchanged on error.
///
/// # Safety
/// `mesh` must be a live handle; `axis` must have its `size` set; `out_mesh` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_reconstruct(
    mesh: *const SherdMesh,
    axis: *const SherdAxis,
    angle_rad: f64,
    segments: usize,
    out_mesh: *mut *mut SherdMesh,
) -> SherdStatus {
    guard("sherd_reconstruct", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let axis = unsafe { read_axis(axis, "axis") }?;
        require(out_mesh.cast_const(), "out_mesh")?;
        let vessel = reconstruction(mesh, &axis, angle_rad, segments)?;
        unsafe { hand_out(out_mesh, vessel) }
    })
}

/// The values of one regularity map and its colour scale.
fn regularity_map(mesh: &Mesh, axis: &Axis, kind: RegularityKind, angle_rad: f64) -> FfiResult<(Vec<f32>, ColorMap)> {
    Ok(match kind {
        RegularityKind::AxisDistance => axis_distance_map(mesh, axis),
        RegularityKind::IdealVessel => ideal_vessel_map(mesh, axis, &section_at(mesh, axis, angle_rad)?)?,
    })
}

/// Computes a regularity map of `mesh` (the paper's section 2.4.4), one value per vertex
/// in the mesh's order, as `sherd export --regularity` writes it:
///
/// - `SHERD_REGULARITY_AXIS_DISTANCE`: each vertex's distance to the axis, mm, on a
///   rainbow scale (blue near, red far) spanning the 2nd to 98th percentile;
/// - `SHERD_REGULARITY_IDEAL_VESSEL`: the signed distance, mm, to the vessel revolved from
///   the section at `angle_rad` (NaN: the most informative angle), positive where the
///   surface stands out of the ideal wall, on a diverging scale symmetric about 0 (blue
///   inside, white on it, red outside).
///
/// Writes, for each of these out-pointers that is not NULL (at least one must be given):
/// `out_values`, `vertex_capacity` floats; `out_rgba`, `4 * vertex_capacity` bytes of
/// the values' colours (alpha 255); `out_value_range`, 2 doubles: the values at the low
/// and high ends of the colour scale (for a legend). `vertex_capacity` must be at least
/// the vertex count (`SHERD_STATUS_BUFFER_TOO_SMALL` otherwise, nothing written).
/// `SHERD_STATUS_DEGENERATE_GEOMETRY` when the section for the ideal vessel has no
/// closed outline.
///
/// # Safety
/// `mesh` must be a live handle; `axis` must have its `size` set; each out-pointer NULL
/// or with room for the stated number of values.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_regularity(
    mesh: *const SherdMesh,
    axis: *const SherdAxis,
    regularity: u32,
    angle_rad: f64,
    out_values: *mut f32,
    out_rgba: *mut u8,
    vertex_capacity: usize,
    out_value_range: *mut f64,
) -> SherdStatus {
    guard("sherd_regularity", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let axis = unsafe { read_axis(axis, "axis") }?;
        let kind = SherdRegularity::parse(regularity, "regularity")?;
        if out_values.is_null() && out_rgba.is_null() && out_value_range.is_null() {
            return Err(Failure::new(
                SherdStatus::NullPointer,
                "`out_values`, `out_rgba` and `out_value_range` are all NULL: nothing to write",
            ));
        }
        if (!out_values.is_null() || !out_rgba.is_null()) && vertex_capacity < mesh.vertex_count() {
            return Err(Failure::new(
                SherdStatus::BufferTooSmall,
                format!("the mesh has {} vertices, the buffers room for {vertex_capacity}", mesh.vertex_count()),
            ));
        }
        let (values, map) = regularity_map(mesh, &axis, kind, angle_rad)?;
        if !out_values.is_null() {
            let values: Vec<[f32; 1]> = values.iter().map(|&v| [v]).collect();
            copy_out(&values, out_values, vertex_capacity, "vertices")?;
        }
        if !out_rgba.is_null() {
            copy_out(&map.rgba(&values), out_rgba, vertex_capacity, "vertices")?;
        }
        if !out_value_range.is_null() {
            unsafe { host_slice_mut(out_value_range, 1, 2, "out_value_range") }?.copy_from_slice(&[map.low, map.high]);
        }
        Ok(())
    })
}
