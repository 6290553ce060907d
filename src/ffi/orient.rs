//! The axis as the host sees it (`SherdAxis`) and the oriented frame as a 4x4 matrix
//! hosts apply to their own objects.

use super::error::{Failure, FfiResult};
use super::mesh::{SherdMesh, mesh_ref};
use super::panic::guard;
use super::pointers::{SizedStruct, host_slice, host_slice_mut, read_sized};
use super::status::SherdStatus;
use crate::mesh::Point;
use crate::orient::{Axis, AxisRecord};

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
/// Row-major is numpy's and Blender's `Matrix(rows)` layout; OpenGL and VCG hosts take
/// the transpose.
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
/// reference point: the transform that places the fragment in the drawing's frame.
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
        let centroid = mesh.centroid().ok_or_else(|| Failure::invalid("the mesh has no vertices"))?;
        write_matrix(&axis.to_oriented_frame(&centroid), out_matrix)
    })
}
