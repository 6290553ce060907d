"""``Mesh``: a libsherd mesh built from numpy arrays (Blender's ``foreach_get`` buffers,
MeshLab's vertex and face matrices) and copied back out as numpy arrays."""

import ctypes
import enum
import os

import numpy as np

from . import _library as c
from .axis import as_pointer
from .errors import InvalidArgumentError, Status, check
from .handle import Handle
from .options import Options, take_json


class Attribute(enum.IntFlag):
    """``SHERD_MESH_ATTRIBUTE_*``: the optional attributes a mesh carries."""

    NORMALS = 1
    COLORS = 2
    CORNER_UVS = 4
    TEXTURE = 8
    QUALITY = 16


def _array(values, dtype, columns, name):
    """``values`` as a C-contiguous ``(n, columns)`` array of ``dtype``."""
    array = np.ascontiguousarray(values, dtype=dtype)
    if array.ndim == 1 and array.size % columns == 0:
        array = array.reshape(-1, columns)
    if array.ndim != 2 or array.shape[1] != columns:
        raise InvalidArgumentError(Status.INVALID_ARGUMENT,
                                   f"{name} must have shape (n, {columns}), got {np.shape(values)}")
    return array


class Mesh(Handle):
    """An owned mesh (``SherdMesh``). Freed when garbage-collected or on :meth:`close`;
    build it with the class methods."""

    _kind = "mesh"

    @classmethod
    def from_arrays(cls, positions, triangles=None, normals=None, colors=None, corner_uvs=None):
        """A mesh from ``positions`` (n, 3) and ``triangles`` (m, 3) vertex indices (None
        for a point cloud), with optional ``normals`` (n, 3), ``colors`` (n, 4) uint8 RGBA
        and ``corner_uvs`` (3m, 2). float32 positions are passed as they are (no copy to
        float64 on the Python side); anything else is converted to float64."""
        is_single = getattr(positions, "dtype", None) == np.float32
        points = _array(positions, np.float32 if is_single else np.float64, 3, "positions")
        faces = _array(np.zeros((0, 3)) if triangles is None else triangles, np.uint32, 3, "triangles")
        if triangles is not None and np.size(triangles) and (np.min(triangles) < 0):
            raise InvalidArgumentError(Status.INVALID_ARGUMENT, "triangles contain a negative index")
        handle = c.SherdMesh_p()
        create = c.lib.sherd_mesh_from_arrays_f32 if is_single else c.lib.sherd_mesh_from_arrays
        check(create(as_pointer(points, ctypes.c_float if is_single else ctypes.c_double), len(points),
                     as_pointer(faces, ctypes.c_uint32), len(faces), ctypes.byref(handle)))
        mesh = cls(handle)
        if normals is not None:
            mesh.set_normals(normals)
        if colors is not None:
            mesh.set_colors(colors)
        if corner_uvs is not None:
            mesh.set_corner_uvs(corner_uvs)
        return mesh

    def copy(self):
        """An independent copy."""
        handle = c.SherdMesh_p()
        check(c.lib.sherd_mesh_clone(self.handle, ctypes.byref(handle)))
        return Mesh(handle)

    def _count(self, function):
        count = ctypes.c_size_t()
        check(function(self.handle, ctypes.byref(count)))
        return count.value

    @property
    def vertex_count(self):
        return self._count(c.lib.sherd_mesh_vertex_count)

    @property
    def face_count(self):
        return self._count(c.lib.sherd_mesh_face_count)

    @property
    def attributes(self):
        """The :class:`Attribute` flags present."""
        bits = ctypes.c_uint32()
        check(c.lib.sherd_mesh_attributes(self.handle, ctypes.byref(bits)))
        return Attribute(bits.value)

    def _copy_out(self, function, rows, shape, dtype, ctype, attribute=None):
        if attribute is not None and attribute not in self.attributes:
            return None
        out = np.empty(shape, dtype=dtype)
        check(function(self.handle, as_pointer(out, ctype), rows))
        return out

    @property
    def positions(self):
        """(n, 3) float64."""
        n = self.vertex_count
        return self._copy_out(c.lib.sherd_mesh_copy_positions, n, (n, 3), np.float64, ctypes.c_double)

    def positions_f32(self):
        """(n, 3) float32, for hosts that store single precision."""
        n = self.vertex_count
        return self._copy_out(c.lib.sherd_mesh_copy_positions_f32, n, (n, 3), np.float32, ctypes.c_float)

    @property
    def triangles(self):
        """(m, 3) uint32."""
        m = self.face_count
        return self._copy_out(c.lib.sherd_mesh_copy_triangles, m, (m, 3), np.uint32, ctypes.c_uint32)

    @property
    def normals(self):
        """(n, 3) float64 unit normals, or None."""
        n = self.vertex_count
        return self._copy_out(c.lib.sherd_mesh_copy_normals, n, (n, 3), np.float64, ctypes.c_double,
                              Attribute.NORMALS)

    @property
    def colors(self):
        """(n, 4) uint8 RGBA, or None."""
        n = self.vertex_count
        return self._copy_out(c.lib.sherd_mesh_copy_colors, n, (n, 4), np.uint8, ctypes.c_uint8, Attribute.COLORS)

    @property
    def corner_uvs(self):
        """(3m, 2) float32 texture coordinates per triangle corner, or None."""
        corners = 3 * self.face_count
        return self._copy_out(c.lib.sherd_mesh_copy_corner_uvs, corners, (corners, 2), np.float32, ctypes.c_float,
                              Attribute.CORNER_UVS)

    @property
    def quality(self):
        """(n,) float32 per-vertex scalar (occlusion, regularity), or None."""
        n = self.vertex_count
        return self._copy_out(c.lib.sherd_mesh_copy_quality, n, (n,), np.float32, ctypes.c_float, Attribute.QUALITY)

    def set_normals(self, normals):
        """Vertex normals (n, 3), float32 or float64; normalised by the library."""
        if getattr(normals, "dtype", None) == np.float32:
            values = _array(normals, np.float32, 3, "normals")
            check(c.lib.sherd_mesh_set_normals_f32(self.handle, as_pointer(values, ctypes.c_float), len(values)))
        else:
            values = _array(normals, np.float64, 3, "normals")
            check(c.lib.sherd_mesh_set_normals(self.handle, as_pointer(values, ctypes.c_double), len(values)))

    def set_colors(self, colors):
        """Vertex colours (n, 4) uint8 RGBA; float arrays in [0, 1] are scaled to bytes."""
        array = np.asarray(colors)
        if np.issubdtype(array.dtype, np.floating):
            array = np.clip(np.rint(array * 255.0), 0, 255)
        values = _array(array, np.uint8, 4, "colors")
        check(c.lib.sherd_mesh_set_colors(self.handle, as_pointer(values, ctypes.c_uint8), len(values)))

    def set_corner_uvs(self, uvs):
        """Texture coordinates per triangle corner (3m, 2)."""
        values = _array(uvs, np.float32, 2, "corner_uvs")
        check(c.lib.sherd_mesh_set_corner_uvs(self.handle, as_pointer(values, ctypes.c_float), len(values)))

    def oriented_transform(self, axis):
        """The 4x4 transform placing this fragment in the oriented frame (its centroid on +x)."""
        matrix = np.zeros((4, 4), dtype=np.float64)
        c_axis = axis.to_c()
        check(c.lib.sherd_mesh_oriented_transform(self.handle, ctypes.byref(c_axis),
                                                  as_pointer(matrix, ctypes.c_double)))
        return matrix

    @classmethod
    def read(cls, path):
        """Reads a scan (PLY, OBJ with MTL and texture, STL, XYZ, PTS; by extension)."""
        handle = c.SherdMesh_p()
        check(c.lib.sherd_mesh_read(os.fsencode(path), ctypes.byref(handle)))
        return cls(handle)

    def write_ply(self, path, binary=True):
        """Writes the mesh as PLY (atomically)."""
        check(c.lib.sherd_mesh_write_ply(self.handle, os.fsencode(path), bool(binary)))

    def repair(self, *, merge_tolerance_mm=None, keep_largest_component=None):
        """Repairs in place; returns the report (a dict of what changed)."""
        setters = {
            "merge_tolerance_mm": float,
            "keep_largest_component": bool,
        }
        values = dict(merge_tolerance_mm=merge_tolerance_mm, keep_largest_component=keep_largest_component)
        report = c.SherdBuffer_p()
        with Options("repair", values, setters) as options:
            check(c.lib.sherd_mesh_repair(self.handle, options, ctypes.byref(report)))
        return take_json(report)

    def decimate(self, target_faces):
        """A decimated copy with about ``target_faces`` triangles."""
        handle = c.SherdMesh_p()
        check(c.lib.sherd_mesh_decimate(self.handle, int(target_faces), ctypes.byref(handle)))
        return Mesh(handle)
