"""The rotation axis and the oriented frame."""

import ctypes

import numpy as np

from . import _library as c
from .errors import check


class Axis:
    """A vessel's rotation axis in the scan's frame: ``point`` on it and unit
    ``direction`` from the base towards the rim (numpy arrays of 3 floats)."""

    __slots__ = ("point", "direction")

    def __init__(self, point, direction):
        self.point = np.array(point, dtype=np.float64).reshape(3)
        self.direction = np.array(direction, dtype=np.float64).reshape(3)

    def __repr__(self):
        return f"Axis(point={self.point.tolist()}, direction={self.direction.tolist()})"

    def to_c(self):
        """The ``SherdAxis`` struct, its ``size`` set."""
        axis = c.SherdAxis()
        axis.size = ctypes.sizeof(c.SherdAxis)
        axis.point[:] = self.point.tolist()
        axis.direction[:] = self.direction.tolist()
        return axis

    @classmethod
    def from_c(cls, axis):
        """From a ``SherdAxis`` struct."""
        return cls(list(axis.point), list(axis.direction))

    def record(self):
        """The JSON form, as ``sherd orient --json`` writes it."""
        return {"point": self.point.tolist(), "direction": self.direction.tolist()}


def as_pointer(array, ctype):
    """A ctypes pointer to a contiguous numpy array's data (kept alive by the caller)."""
    return array.ctypes.data_as(ctypes.POINTER(ctype))


def oriented_transform(axis, reference_point):
    """The 4x4 transform (numpy, row-major, acting on column vectors) from the scan's
    frame to the oriented frame: ``axis`` onto +z, ``reference_point`` onto the +x
    half-plane."""
    reference = np.ascontiguousarray(reference_point, dtype=np.float64).reshape(3)
    matrix = np.zeros((4, 4), dtype=np.float64)
    c_axis = axis.to_c()
    check(c.lib.sherd_axis_oriented_transform(
        ctypes.byref(c_axis), as_pointer(reference, ctypes.c_double), as_pointer(matrix, ctypes.c_double)))
    return matrix
