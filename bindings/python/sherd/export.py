"""Exports in the oriented frame: the oriented mesh as PLY, the profile section as CSV."""

import ctypes
import math
import os

import numpy as np

from . import _library as c
from .errors import check
from .options import take_buffer


def export_oriented_ply(mesh, axis, path, binary=True):
    """Writes ``mesh`` moved into the oriented frame (axis on z, rim up, centroid on +x)."""
    c_axis = axis.to_c()
    check(c.lib.sherd_export_oriented_ply(mesh.handle, ctypes.byref(c_axis), os.fsencode(path), bool(binary)))


def most_informative_angle(mesh, axis):
    """The profile's most informative cut angle, radians about the axis."""
    angle = ctypes.c_double()
    c_axis = axis.to_c()
    check(c.lib.sherd_profile_most_informative_angle(mesh.handle, ctypes.byref(c_axis), ctypes.byref(angle)))
    return angle.value


def profile_csv(mesh, axis, angle_rad=None):
    """The profile section as CSV text (``curve,index,r_mm,z_mm,closed``); ``angle_rad``
    None takes the most informative angle."""
    buffer = c.SherdBuffer_p()
    c_axis = axis.to_c()
    angle = math.nan if angle_rad is None else float(angle_rad)
    check(c.lib.sherd_profile_csv(mesh.handle, ctypes.byref(c_axis), angle, ctypes.byref(buffer)))
    return take_buffer(buffer).decode("utf-8")


def profile_section(mesh, axis, angle_rad=None):
    """The profile section as a list of ``(points, closed)`` curves, ``points`` an (n, 2)
    array of ``r_mm, z_mm`` in the oriented frame."""
    curves = {}
    for line in profile_csv(mesh, axis, angle_rad).splitlines()[1:]:
        curve, _, r, z, closed = line.split(",")
        curves.setdefault(int(curve), ([], closed == "true"))[0].append((float(r), float(z)))
    return [(np.array(points, dtype=np.float64), closed) for _, (points, closed) in sorted(curves.items())]


def export_profile_csv(mesh, axis, path, angle_rad=None):
    """Writes the profile section as CSV (atomically)."""
    c_axis = axis.to_c()
    angle = math.nan if angle_rad is None else float(angle_rad)
    check(c.lib.sherd_export_profile_csv(mesh.handle, ctypes.byref(c_axis), angle, os.fsencode(path)))


def export_reconstruction_ply(mesh, axis, path, angle_rad=None, segments=0, binary=True):
    """Writes the 3D reconstruction (the profile revolved about the axis) as PLY;
    ``segments`` 0 takes the library's default (180)."""
    c_axis = axis.to_c()
    angle = math.nan if angle_rad is None else float(angle_rad)
    check(c.lib.sherd_export_reconstruction_ply(mesh.handle, ctypes.byref(c_axis), angle, int(segments),
                                                os.fsencode(path), bool(binary)))
