//! `SherdMesh`: a mesh built from the host's arrays (Blender's and MeshLab's vertex and
//! face buffers, no temporary files) or read from a scan file, and copied back out.

use std::ffi::c_char;

use super::buffer::{SherdBuffer, hand_out_report};
use super::error::{Failure, FfiResult};
use super::builder::{assign, builder, free_builder, new_builder, options_or_default, positive_or_default};
use super::panic::guard;
use super::pointers::{borrow, borrow_mut, host_slice, host_slice_mut, path_from, require, write_out};
use super::status::SherdStatus;
use crate::mesh::io::PlyEncoding;
use crate::mesh::repair::RepairOptions;
use crate::mesh::{Mesh, Point, Vector};

/// An owned triangle mesh (or point cloud) in the scan's frame and units.
///
/// Create it with `sherd_mesh_from_arrays`, `sherd_mesh_from_arrays_f32`,
/// `sherd_mesh_read` or `sherd_mesh_clone`; release it with `sherd_mesh_free`. A mesh may be used from any
/// thread, and different meshes concurrently; one mesh must not be modified (the
/// `_set_` functions) while another thread uses it.
pub struct SherdMesh {
    pub(crate) mesh: Mesh,
}

/// The optional attributes a mesh may carry, as bits of the set
/// `sherd_mesh_attributes` writes.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SherdMeshAttribute {
    /// Unit vertex normals, 3 values per vertex.
    Normals = 1,
    /// RGBA colours, 4 bytes per vertex.
    Colors = 2,
    /// Texture coordinates per triangle corner, 2 floats per corner, 3 corners per triangle.
    CornerUvs = 4,
    /// A texture image (read from a scan file with its material).
    Texture = 8,
    /// A scalar per vertex (MeshLab's quality: occlusion, regularity).
    Quality = 16,
}

/// Hands a new mesh to the host through `out_mesh`.
/// The pointer is checked before the box is released, which would leak otherwise.
pub(crate) unsafe fn hand_out(out_mesh: *mut *mut SherdMesh, mesh: Mesh) -> FfiResult {
    require(out_mesh.cast_const(), "out_mesh")?;
    unsafe { write_out(out_mesh, Box::into_raw(Box::new(SherdMesh { mesh })), "out_mesh") }
}

/// The mesh behind a handle the host passed in.
pub(crate) unsafe fn mesh_ref<'a>(mesh: *const SherdMesh, name: &str) -> FfiResult<&'a Mesh> {
    unsafe { borrow(mesh, name) }.map(|handle| &handle.mesh)
}

fn mesh_mut<'a>(mesh: *mut SherdMesh) -> FfiResult<&'a mut Mesh> {
    unsafe { borrow_mut(mesh, "mesh") }.map(|handle| &mut handle.mesh)
}

fn build_mesh(positions: impl Iterator<Item = Point>, triangles: &[u32], vertex_count: usize) -> FfiResult<Mesh> {
    if vertex_count == 0 {
        return Err(Failure::invalid("`vertex_count` is 0: a mesh needs at least one vertex"));
    }
    let triangles = triangles.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
    let mesh = Mesh::new(positions.collect(), triangles);
    mesh.validate()?;
    Ok(mesh)
}

/// Creates a mesh from host arrays of double-precision positions.
///
/// `positions` holds `3 * vertex_count` values `x0 y0 z0 x1 ...` (millimetres unless the
/// scan says otherwise); `triangles` holds `3 * triangle_count` vertex indices, counter-
/// clockwise seen from outside. `triangles` may be NULL when `triangle_count` is 0 (a
/// point cloud, which then needs normals: `sherd_mesh_set_normals`). The arrays are
/// copied; the host keeps ownership of them.
///
/// Errors: `SHERD_STATUS_NULL_POINTER` for a NULL array or `out_mesh`,
/// `SHERD_STATUS_INVALID_ARGUMENT` for `vertex_count` 0, a non-finite coordinate or an
/// index not below `vertex_count` (the message names the vertex or face). On error
/// `*out_mesh` is left unchanged.
///
/// # Safety
/// The arrays must hold the stated number of values; `out_mesh` must be writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_from_arrays(
    positions: *const f64,
    vertex_count: usize,
    triangles: *const u32,
    triangle_count: usize,
    out_mesh: *mut *mut SherdMesh,
) -> SherdStatus {
    guard("sherd_mesh_from_arrays", || {
        require(out_mesh.cast_const(), "out_mesh")?;
        let positions = unsafe { host_slice(positions, vertex_count, 3, "positions") }?;
        let triangles = unsafe { host_slice(triangles, triangle_count, 3, "triangles") }?;
        let points = positions.chunks_exact(3).map(|p| Point::new(p[0], p[1], p[2]));
        let mesh = build_mesh(points, triangles, vertex_count)?;
        unsafe { hand_out(out_mesh, mesh) }
    })
}

/// Like `sherd_mesh_from_arrays` with single-precision positions (Blender's and
/// MeshLab's vertex buffers); they are widened to double precision.
///
/// # Safety
/// As for `sherd_mesh_from_arrays`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_from_arrays_f32(
    positions: *const f32,
    vertex_count: usize,
    triangles: *const u32,
    triangle_count: usize,
    out_mesh: *mut *mut SherdMesh,
) -> SherdStatus {
    guard("sherd_mesh_from_arrays_f32", || {
        require(out_mesh.cast_const(), "out_mesh")?;
        let positions = unsafe { host_slice(positions, vertex_count, 3, "positions") }?;
        let triangles = unsafe { host_slice(triangles, triangle_count, 3, "triangles") }?;
        let points = positions.chunks_exact(3).map(|p| Point::new(p[0].into(), p[1].into(), p[2].into()));
        let mesh = build_mesh(points, triangles, vertex_count)?;
        unsafe { hand_out(out_mesh, mesh) }
    })
}

/// Creates an independent copy of `mesh` (for example to decimate it while keeping the
/// full resolution for drawing).
///
/// # Safety
/// `mesh` must be a live handle; `out_mesh` must be writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_clone(mesh: *const SherdMesh, out_mesh: *mut *mut SherdMesh) -> SherdStatus {
    guard("sherd_mesh_clone", || {
        let copy = unsafe { mesh_ref(mesh, "mesh") }?.clone();
        unsafe { hand_out(out_mesh, copy) }
    })
}

/// Releases a mesh. NULL is accepted and ignored. Freeing the same handle twice, or
/// using it after this call, is undefined behaviour (as for `free`): the library cannot
/// detect it. Set your pointer to NULL after freeing it.
///
/// # Safety
/// `mesh` must be NULL or a handle from this library not freed before.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_free(mesh: *mut SherdMesh) {
    if !mesh.is_null() {
        // Dropping a Mesh only frees vectors; it cannot panic.
        drop(unsafe { Box::from_raw(mesh) });
    }
}

fn widen_normals(values: impl Iterator<Item = Vector>) -> FfiResult<Vec<Vector>> {
    values
        .enumerate()
        .map(|(vertex, normal)| {
            if !normal.iter().all(|c| c.is_finite()) {
                return Err(Failure::invalid(format!(
                    "normal of vertex {vertex} is not finite ({}, {}, {})",
                    normal.x, normal.y, normal.z
                )));
            }
            // Scanners leave zero normals on isolated vertices; keep them zero.
            Ok(normal.try_normalize(0.0).unwrap_or(normal))
        })
        .collect()
}

fn check_vertex_count(mesh: &Mesh, vertex_count: usize) -> FfiResult {
    if vertex_count != mesh.vertex_count() {
        return Err(Failure::invalid(format!(
            "`vertex_count` is {vertex_count}, but the mesh has {} vertices",
            mesh.vertex_count()
        )));
    }
    Ok(())
}

/// Sets the vertex normals from `3 * vertex_count` doubles; `vertex_count` must equal the
/// mesh's. Normals are normalised (zero normals stay zero); non-finite values are refused.
///
/// # Safety
/// `mesh` must be a live handle not used by another thread; `normals` must hold the
/// stated number of values.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_set_normals(mesh: *mut SherdMesh, normals: *const f64, vertex_count: usize) -> SherdStatus {
    guard("sherd_mesh_set_normals", || {
        let mesh = mesh_mut(mesh)?;
        check_vertex_count(mesh, vertex_count)?;
        let values = unsafe { host_slice(normals, vertex_count, 3, "normals") }?;
        mesh.normals = Some(widen_normals(values.chunks_exact(3).map(|n| Vector::new(n[0], n[1], n[2])))?);
        Ok(())
    })
}

/// Like `sherd_mesh_set_normals` with single-precision values.
///
/// # Safety
/// As for `sherd_mesh_set_normals`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_set_normals_f32(mesh: *mut SherdMesh, normals: *const f32, vertex_count: usize) -> SherdStatus {
    guard("sherd_mesh_set_normals_f32", || {
        let mesh = mesh_mut(mesh)?;
        check_vertex_count(mesh, vertex_count)?;
        let values = unsafe { host_slice(normals, vertex_count, 3, "normals") }?;
        let normals = values.chunks_exact(3).map(|n| Vector::new(n[0].into(), n[1].into(), n[2].into()));
        mesh.normals = Some(widen_normals(normals)?);
        Ok(())
    })
}

/// Sets the vertex colours from `4 * vertex_count` bytes `r g b a`; `vertex_count` must
/// equal the mesh's.
///
/// # Safety
/// `mesh` must be a live handle not used by another thread; `rgba` must hold the stated
/// number of bytes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_set_colors(mesh: *mut SherdMesh, rgba: *const u8, vertex_count: usize) -> SherdStatus {
    guard("sherd_mesh_set_colors", || {
        let mesh = mesh_mut(mesh)?;
        check_vertex_count(mesh, vertex_count)?;
        let values = unsafe { host_slice(rgba, vertex_count, 4, "rgba") }?;
        mesh.colors = Some(values.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]).collect());
        Ok(())
    })
}

/// Sets texture coordinates per triangle corner from `2 * corner_count` floats `u v`,
/// where `corner_count` must be `3 * triangle_count` (corner `3 * f + k` is corner `k` of
/// triangle `f`, as Blender's UV layers and MeshLab's wedge coordinates store them).
///
/// # Safety
/// `mesh` must be a live handle not used by another thread; `uvs` must hold the stated
/// number of values.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_set_corner_uvs(mesh: *mut SherdMesh, uvs: *const f32, corner_count: usize) -> SherdStatus {
    guard("sherd_mesh_set_corner_uvs", || {
        let mesh = mesh_mut(mesh)?;
        if corner_count != 3 * mesh.face_count() {
            return Err(Failure::invalid(format!(
                "`corner_count` is {corner_count}, expected 3 * {} triangles = {}",
                mesh.face_count(),
                3 * mesh.face_count()
            )));
        }
        let values = unsafe { host_slice(uvs, corner_count, 2, "uvs") }?;
        if let Some(i) = values.iter().position(|v| !v.is_finite()) {
            return Err(Failure::invalid(format!("texture coordinate of corner {} is not finite", i / 2)));
        }
        mesh.corner_uvs = Some(values.chunks_exact(2).map(|uv| [uv[0], uv[1]]).collect());
        Ok(())
    })
}

/// Writes the number of vertices to `*out_count`.
///
/// # Safety
/// `mesh` must be a live handle; `out_count` must be writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_vertex_count(mesh: *const SherdMesh, out_count: *mut usize) -> SherdStatus {
    guard("sherd_mesh_vertex_count", || {
        let count = unsafe { mesh_ref(mesh, "mesh") }?.vertex_count();
        unsafe { write_out(out_count, count, "out_count") }
    })
}

/// Writes the number of triangles to `*out_count` (0 for a point cloud).
///
/// # Safety
/// `mesh` must be a live handle; `out_count` must be writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_face_count(mesh: *const SherdMesh, out_count: *mut usize) -> SherdStatus {
    guard("sherd_mesh_face_count", || {
        let count = unsafe { mesh_ref(mesh, "mesh") }?.face_count();
        unsafe { write_out(out_count, count, "out_count") }
    })
}

/// Writes the set of optional attributes the mesh carries: the bitwise or of the
/// `SHERD_MESH_ATTRIBUTE_*` values present.
///
/// # Safety
/// `mesh` must be a live handle; `out_attributes` must be writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_attributes(mesh: *const SherdMesh, out_attributes: *mut u32) -> SherdStatus {
    guard("sherd_mesh_attributes", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let bits = [
            (mesh.normals.is_some(), SherdMeshAttribute::Normals),
            (mesh.colors.is_some(), SherdMeshAttribute::Colors),
            (mesh.corner_uvs.is_some(), SherdMeshAttribute::CornerUvs),
            (mesh.texture.is_some(), SherdMeshAttribute::Texture),
            (mesh.quality.is_some(), SherdMeshAttribute::Quality),
        ];
        let attributes = bits.iter().filter(|(present, _)| *present).fold(0, |set, (_, bit)| set | *bit as u32);
        unsafe { write_out(out_attributes, attributes, "out_attributes") }
    })
}

/// Copies `items` (each `N` scalars) into the host's array of `capacity` items.
pub(crate) fn copy_out<T: Copy, const N: usize>(items: &[[T; N]], out: *mut T, capacity: usize, what: &str) -> FfiResult {
    if capacity < items.len() {
        return Err(Failure::new(
            SherdStatus::BufferTooSmall,
            format!("the mesh has {} {what}, the buffer room for {capacity}", items.len()),
        ));
    }
    let out = unsafe { host_slice_mut(out, items.len(), N, "out") }?;
    for (chunk, item) in out.chunks_exact_mut(N).zip(items) {
        chunk.copy_from_slice(item);
    }
    Ok(())
}

fn absent(what: &str) -> Failure {
    Failure::new(SherdStatus::NotAvailable, format!("the mesh has no {what}"))
}

/// Copies the positions into `out` (`3 * vertex_capacity` doubles); `vertex_capacity`
/// must be at least the vertex count (`SHERD_STATUS_BUFFER_TOO_SMALL` otherwise, with
/// nothing written).
///
/// # Safety
/// `mesh` must be a live handle; `out` must have room for `3 * vertex_capacity` values.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_copy_positions(mesh: *const SherdMesh, out: *mut f64, vertex_capacity: usize) -> SherdStatus {
    guard("sherd_mesh_copy_positions", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let points: Vec<[f64; 3]> = mesh.positions.iter().map(|p| p.coords.into()).collect();
        copy_out(&points, out, vertex_capacity, "vertices")
    })
}

/// Like `sherd_mesh_copy_positions`, rounded to single precision.
///
/// # Safety
/// As for `sherd_mesh_copy_positions`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_copy_positions_f32(mesh: *const SherdMesh, out: *mut f32, vertex_capacity: usize) -> SherdStatus {
    guard("sherd_mesh_copy_positions_f32", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let points: Vec<[f32; 3]> = mesh.positions.iter().map(|p| p.coords.cast::<f32>().into()).collect();
        copy_out(&points, out, vertex_capacity, "vertices")
    })
}

/// Copies the triangles' vertex indices into `out` (`3 * triangle_capacity` values).
///
/// # Safety
/// `mesh` must be a live handle; `out` must have room for `3 * triangle_capacity` values.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_copy_triangles(mesh: *const SherdMesh, out: *mut u32, triangle_capacity: usize) -> SherdStatus {
    guard("sherd_mesh_copy_triangles", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        copy_out(&mesh.triangles, out, triangle_capacity, "triangles")
    })
}

/// Copies the vertex normals into `out` (`3 * vertex_capacity` doubles);
/// `SHERD_STATUS_NOT_AVAILABLE` when the mesh has none.
///
/// # Safety
/// `mesh` must be a live handle; `out` must have room for `3 * vertex_capacity` values.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_copy_normals(mesh: *const SherdMesh, out: *mut f64, vertex_capacity: usize) -> SherdStatus {
    guard("sherd_mesh_copy_normals", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let normals = mesh.normals.as_ref().ok_or_else(|| absent("normals"))?;
        let values: Vec<[f64; 3]> = normals.iter().map(|n| (*n).into()).collect();
        copy_out(&values, out, vertex_capacity, "vertices")
    })
}

/// Copies the vertex colours into `out` (`4 * vertex_capacity` bytes RGBA);
/// `SHERD_STATUS_NOT_AVAILABLE` when the mesh has none.
///
/// # Safety
/// `mesh` must be a live handle; `out` must have room for `4 * vertex_capacity` bytes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_copy_colors(mesh: *const SherdMesh, out: *mut u8, vertex_capacity: usize) -> SherdStatus {
    guard("sherd_mesh_copy_colors", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let colors = mesh.colors.as_ref().ok_or_else(|| absent("colours"))?;
        copy_out(colors, out, vertex_capacity, "vertices")
    })
}

/// Copies the per-corner texture coordinates into `out` (`2 * corner_capacity` floats,
/// `3 * triangle_count` corners); `SHERD_STATUS_NOT_AVAILABLE` when the mesh has none.
///
/// # Safety
/// `mesh` must be a live handle; `out` must have room for `2 * corner_capacity` values.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_copy_corner_uvs(mesh: *const SherdMesh, out: *mut f32, corner_capacity: usize) -> SherdStatus {
    guard("sherd_mesh_copy_corner_uvs", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let uvs = mesh.corner_uvs.as_ref().ok_or_else(|| absent("texture coordinates"))?;
        copy_out(uvs, out, corner_capacity, "corners")
    })
}

/// Copies the per-vertex scalar (MeshLab's quality: ambient occlusion, regularity) into
/// `out` (`vertex_capacity` floats); `SHERD_STATUS_NOT_AVAILABLE` when the mesh has none.
///
/// # Safety
/// `mesh` must be a live handle; `out` must have room for `vertex_capacity` values.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_copy_quality(mesh: *const SherdMesh, out: *mut f32, vertex_capacity: usize) -> SherdStatus {
    guard("sherd_mesh_copy_quality", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let quality = mesh.quality.as_ref().ok_or_else(|| absent("quality values"))?;
        let values: Vec<[f32; 1]> = quality.iter().map(|&q| [q]).collect();
        copy_out(&values, out, vertex_capacity, "vertices")
    })
}

/// Reads a scan: PLY (ASCII or binary), OBJ (with its MTL and texture), STL, XYZ or PTS,
/// chosen by the file's extension. `path` is a NUL-terminated path (UTF-8, or the OS's
/// bytes on Unix).
///
/// Errors: `SHERD_STATUS_IO` (cannot open or read), `SHERD_STATUS_PARSE` (malformed; the
/// message names the file and the line or element), `SHERD_STATUS_INVALID_ARGUMENT`
/// (unknown extension, invalid content such as an index past the vertex count).
///
/// # Safety
/// `path` must be a NUL-terminated string; `out_mesh` must be writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_read(path: *const c_char, out_mesh: *mut *mut SherdMesh) -> SherdStatus {
    guard("sherd_mesh_read", || {
        let path = unsafe { path_from(path, "path") }?;
        require(out_mesh.cast_const(), "out_mesh")?;
        let mesh = crate::mesh::io::read_mesh(&path)?;
        unsafe { hand_out(out_mesh, mesh) }
    })
}

/// Writes the mesh as PLY (binary little-endian when `binary` is true, ASCII otherwise)
/// with its normals, colours and quality. The file is replaced atomically: on error no
/// half-written file is left.
///
/// # Safety
/// `mesh` must be a live handle; `path` a NUL-terminated string.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_write_ply(mesh: *const SherdMesh, path: *const c_char, binary: bool) -> SherdStatus {
    guard("sherd_mesh_write_ply", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        let path = unsafe { path_from(path, "path") }?;
        Ok(crate::mesh::io::write_ply(&path, mesh, ply_encoding(binary))?)
    })
}

/// The PLY encoding for the `binary` flag of the C API.
pub(crate) fn ply_encoding(binary: bool) -> PlyEncoding {
    if binary { PlyEncoding::BinaryLittleEndian } else { PlyEncoding::Ascii }
}

/// Repairs the mesh in place: merges duplicate (or close) vertices, removes degenerate
/// and duplicate faces and unreferenced vertices, optionally keeps only the largest
/// component. `options` may be NULL for the defaults. When `out_report_json` is not
/// NULL it receives what was changed, as a JSON object in a new `SherdBuffer`.
///
/// # Safety
/// `mesh` must be a live handle not used by another thread; `options` NULL or live;
/// `out_report_json` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_repair(
    mesh: *mut SherdMesh,
    options: *const SherdRepairOptions,
    out_report_json: *mut *mut SherdBuffer,
) -> SherdStatus {
    guard("sherd_mesh_repair", || {
        let mesh = mesh_mut(mesh)?;
        let options = unsafe { options_or_default(options, |builder| &builder.options) }?;
        let report = crate::mesh::repair::repair(mesh, &options);
        unsafe { hand_out_report(out_report_json, &report) }
    })
}

/// Creates a decimated copy of `mesh` with about `target_faces` triangles (quadric edge
/// collapse keeping boundaries, topology, interpolated colours and per-corner texture
/// coordinates, which never cross a texture seam); `mesh` is unchanged.
/// A mesh already at or below the target is copied as it is.
///
/// # Safety
/// `mesh` must be a live handle; `out_mesh` must be writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_mesh_decimate(mesh: *const SherdMesh, target_faces: usize, out_mesh: *mut *mut SherdMesh) -> SherdStatus {
    guard("sherd_mesh_decimate", || {
        let mesh = unsafe { mesh_ref(mesh, "mesh") }?;
        require(out_mesh.cast_const(), "out_mesh")?;
        if target_faces == 0 {
            return Err(Failure::invalid("`target_faces` must be at least 1"));
        }
        let decimated = crate::mesh::decimate::decimate(mesh, target_faces)?;
        unsafe { hand_out(out_mesh, decimated) }
    })
}

// ---------------------------------------------------------------- repair options

/// Options of `sherd_mesh_repair`.
pub struct SherdRepairOptions {
    pub(crate) options: RepairOptions,
}

builder!(SherdRepairOptions => RepairOptions);

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
