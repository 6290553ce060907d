"""The archaeological drawing: built once, written to files or to bytes in SVG, EPS,
PDF or PNG."""

import ctypes
import os

from . import _library as c
from .errors import InvalidArgumentError, Status, check
from .handle import Handle
from .options import Options, enum_value, take_buffer

STYLES = {"linear": 1, "colour": 2, "color": 2, "light": 4, "occlusion": 8, "stipple": 16, "regularity": 32}
FORMATS = {"svg": 0, "eps": 1, "pdf": 2, "png": 3}
FILLS = {"black": 0, "hatched": 1}
PLACEMENTS = {"beside": 0, "true_distance": 1, "true-distance": 1}
REGULARITY = {"axis_distance": 0, "ideal_vessel": 1, "axis-distance": 0, "ideal-vessel": 1}
#: The measurements under the drawing (SHERD_ANNOTATION_* bits); all and none stand alone.
ANNOTATIONS = {"height": 1, "wall_thickness": 2, "wall-thickness": 2, "capacity": 4, "all": 7, "none": 0}


def _bits(names, value, what):
    """The or of the bits of a list or comma-separated string of names; an int as it is
    (the C ABI checks it)."""
    if isinstance(value, str):
        value = [name.strip() for name in value.split(",") if name.strip()]
    if isinstance(value, (list, tuple, set, frozenset)):
        bits = 0
        for name in value:
            bits |= enum_value(names, name, what)
        return bits
    return int(value)


def _styles(value):
    return _bits(STYLES, value, "style")


def _annotations(value):
    """``annotations``: names among height, wall_thickness, capacity, or all, or none
    (a list may also be empty: none, as a host's empty set of check boxes)."""
    if isinstance(value, str):
        if not value.strip():
            raise InvalidArgumentError(Status.INVALID_ARGUMENT, "no annotation given; say \"none\" for none")
        value = [name.strip() for name in value.split(",") if name.strip()]
    if isinstance(value, (list, tuple, set, frozenset)) and len(value) > 1 \
            and {str(name).lower() for name in value} & {"all", "none"}:
        raise InvalidArgumentError(Status.INVALID_ARGUMENT,
                                   f"annotations {list(value)}: all and none cannot be combined with others")
    return _bits(ANNOTATIONS, value, "annotation")


class Drawing(Handle):
    """A finished drawing (``SherdDrawing``), freed when garbage-collected or on close."""

    _kind = "drawing"

    def __init__(self, mesh, axis, *, style="light,occlusion", scale_denominator=None, dpi=None,
                 section_angle_rad=None, section_fill=None, placement=None, regularity=None, title=None,
                 interior_view=None, prolongation=None, annotations=None):
        """Builds the drawing of ``mesh`` oriented by ``axis``; ``style`` is a list or a
        comma-separated string of linear, colour, light, occlusion, stipple, regularity
        (the default, light and occlusion, is the library's and ``sherd draw``'s).
        ``placement`` is beside or true_distance, ``section_fill`` black or hatched,
        ``interior_view`` and ``prolongation`` True or False, ``section_angle_rad`` the
        section's angle about the axis (None: the most informative profile),
        ``annotations`` the measurements written under the drawing: a list or
        comma-separated string of height, wall_thickness, capacity, or "all", or "none"
        (the default); None keeps the library's default."""
        setters = {
            "style": _styles,
            "scale_denominator": int,
            "dpi": float,
            "section_angle_rad": float,
            "section_fill": lambda v: enum_value(FILLS, v, "section fill"),
            "placement": lambda v: enum_value(PLACEMENTS, v, "placement"),
            "regularity": lambda v: enum_value(REGULARITY, v, "regularity"),
            "title": lambda v: v.encode("utf-8"),
            "interior_view": bool,
            "prolongation": bool,
            "annotations": _annotations,
        }
        values = dict(style=style, scale_denominator=scale_denominator, dpi=dpi, section_angle_rad=section_angle_rad,
                      section_fill=section_fill, placement=placement, regularity=regularity, title=title,
                      interior_view=interior_view, prolongation=prolongation, annotations=annotations)
        super().__init__(None)
        handle = c.SherdDrawing_p()
        c_axis = axis.to_c()
        with Options("draw", values, setters) as options:
            check(c.lib.sherd_drawing_build(mesh.handle, ctypes.byref(c_axis), options, ctypes.byref(handle)))
        self._handle = handle

    def to_bytes(self, format="svg"):
        """The drawing in ``format`` (svg, eps, pdf, png)."""
        buffer = c.SherdBuffer_p()
        check(c.lib.sherd_drawing_to_buffer(self.handle, enum_value(FORMATS, format, "format"), ctypes.byref(buffer)))
        return take_buffer(buffer)

    def write(self, path):
        """Writes the drawing, the format chosen by the file's extension (atomically)."""
        check(c.lib.sherd_drawing_write(self.handle, os.fsencode(path)))
