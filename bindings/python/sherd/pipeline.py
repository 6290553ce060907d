"""The pipeline over the C ABI: synthetic sherds, orientation, refinement."""

import ctypes
from dataclasses import dataclass, field

import numpy as np

from . import _library as c
from .axis import Axis, as_pointer
from .errors import Status, check, error_for, last_error_message
from .mesh import Mesh
from .options import Options, enum_value, take_buffer, take_json


SYNTH_KINDS = {"random": 0, "rim": 1, "body": 2, "base": 3, "rim_to_base": 4, "flat_base": 5,
               "near_spherical": 6, "tiny": 7}


def synthetic_sherd(seed, kind="random", target_faces=0, noise_mm=0.02):
    """A synthetic sherd with a known axis: ``(mesh, true_axis, truth)`` where ``truth``
    is the ground truth as a dict (radii, sector angle, height, profile...)."""
    mesh, axis, truth = c.SherdMesh_p(), c.SherdAxis(), c.SherdBuffer_p()
    axis.size = ctypes.sizeof(c.SherdAxis)
    check(c.lib.sherd_synthetic_sherd(seed, enum_value(SYNTH_KINDS, kind, "kind"), target_faces, noise_mm,
                                      ctypes.byref(mesh), ctypes.byref(axis), ctypes.byref(truth)))
    return Mesh(mesh), Axis.from_c(axis), take_json(truth)


@dataclass
class Orientation:
    """The result of an orientation. ``oriented`` is False when the data do not determine
    the axis: ``axis`` is then only a guess and ``reason`` says why (ask for three points)."""

    axis: Axis
    oriented: bool
    reason: str
    angle_uncertainty_deg: float
    position_uncertainty_mm: float
    kept_vertex_count: int
    report: dict = field(default_factory=dict)


def _orientation(status, axis, summary, report):
    reason = ""
    if status == Status.NEEDS_MANUAL_ORIENTATION:
        reason = last_error_message()
    elif status != Status.OK:
        take_buffer(report)
        raise error_for(status)
    return Orientation(Axis.from_c(axis), bool(summary.oriented), reason, summary.angle_uncertainty_deg,
                       summary.position_uncertainty_mm, summary.kept_vertex_count, take_json(report))


def _outputs():
    axis, summary, report = c.SherdAxis(), c.SherdOrientReport(), c.SherdBuffer_p()
    axis.size = ctypes.sizeof(c.SherdAxis)
    summary.size = ctypes.sizeof(c.SherdOrientReport)
    return axis, summary, report


def orient_automatic(mesh, *, target_vertex_count=None, smoothing_iterations=None,
                     opposite_normal_confidence=None):
    """The rotation axis from the normals (the paper's section 2.2). Returns an
    :class:`Orientation`; check ``oriented`` (a fragment that does not determine its
    axis is not an exception: it is an answer)."""
    setters = {
        "target_vertex_count": ("sherd_orient_options_set_target_vertex_count", int),
        "smoothing_iterations": ("sherd_orient_options_set_smoothing_iterations", int),
        "opposite_normal_confidence": ("sherd_orient_options_set_opposite_normal_confidence", float),
    }
    values = dict(target_vertex_count=target_vertex_count, smoothing_iterations=smoothing_iterations,
                  opposite_normal_confidence=opposite_normal_confidence)
    axis, summary, report = _outputs()
    with Options("orient", values, setters) as options:
        status = c.lib.sherd_orient_automatic(mesh.handle, options, ctypes.byref(axis), ctypes.byref(summary),
                                              ctypes.byref(report))
    return _orientation(status, axis, summary, report)


def orient_from_three_points(mesh, points, *, keep_fraction=None, max_pick_distance_mm=None):
    """The rotation axis from three points picked on one horizontal feature (rim edge,
    groove, base edge): ``points`` is (3, 3)."""
    picked = np.ascontiguousarray(points, dtype=np.float64).reshape(9)
    setters = {
        "keep_fraction": ("sherd_manual_options_set_keep_fraction", float),
        "max_pick_distance_mm": ("sherd_manual_options_set_max_pick_distance_mm", float),
    }
    values = dict(keep_fraction=keep_fraction, max_pick_distance_mm=max_pick_distance_mm)
    axis, summary, report = _outputs()
    with Options("manual", values, setters) as options:
        status = c.lib.sherd_orient_from_three_points(mesh.handle, as_pointer(picked, ctypes.c_double), options,
                                                      ctypes.byref(axis), ctypes.byref(summary),
                                                      ctypes.byref(report))
    return _orientation(status, axis, summary, report)
