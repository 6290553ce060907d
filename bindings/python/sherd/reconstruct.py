"""The vessel reconstructed by revolution and the regularity maps, as numpy arrays for
hosts that show them themselves (a new object and vertex colours in Blender)."""

import ctypes
import math
from dataclasses import dataclass

import numpy as np

from . import _library as c
from .axis import as_pointer
from .errors import check
from .mesh import Mesh
from .vocabulary import Vocabulary, value_of


def _angle(angle_rad):
    return math.nan if angle_rad is None else float(angle_rad)


def reconstruct(mesh, axis, angle_rad=None, segments=0):
    """The preserved part of the vessel: the profile section at ``angle_rad`` (None: the
    most informative) revolved a full turn in ``segments`` steps (0: 180), as a new
    watertight :class:`Mesh` in the oriented frame (axis on z, rim up). Place it with
    the scan by the inverse of ``mesh.oriented_transform(axis)``."""
    handle = c.SherdMesh_p()
    c_axis = axis.to_c()
    check(c.lib.sherd_reconstruct(mesh.handle, ctypes.byref(c_axis), _angle(angle_rad), int(segments),
                                  ctypes.byref(handle)))
    return Mesh(handle)


@dataclass
class Regularity:
    """A regularity map of a mesh (``kind`` as asked for): ``values`` (n,) float32 in mm, one per vertex in the
    mesh's order; ``colors`` (n, 4) uint8 RGBA of the map's colour scale; ``value_range``
    the values at the scale's low and high ends (for a legend)."""

    kind: str
    values: np.ndarray
    colors: np.ndarray
    value_range: tuple


def regularity(mesh, axis, kind="ideal_vessel", angle_rad=None):
    """The regularity map of ``mesh`` about ``axis`` (the paper's section 2.4.4), as
    ``sherd export --regularity`` colours it: ``"axis_distance"`` (each vertex's radius,
    rainbow scale) or ``"ideal_vessel"`` (signed distance to the vessel revolved from the
    section at ``angle_rad``, None: the most informative; blue inside, red outside)."""
    count = mesh.vertex_count
    values = np.empty(count, dtype=np.float32)
    colors = np.empty((count, 4), dtype=np.uint8)
    value_range = np.empty(2, dtype=np.float64)
    c_axis = axis.to_c()
    check(c.lib.sherd_regularity(mesh.handle, ctypes.byref(c_axis), value_of(Vocabulary.REGULARITY, kind, "regularity"),
                                 _angle(angle_rad), as_pointer(values, ctypes.c_float),
                                 as_pointer(colors, ctypes.c_uint8), count, as_pointer(value_range, ctypes.c_double)))
    return Regularity(kind, values, colors, (float(value_range[0]), float(value_range[1])))
