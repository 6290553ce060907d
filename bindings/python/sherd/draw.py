"""The archaeological drawing: built once, written to files or to bytes in SVG, EPS,
PDF or PNG."""

import ctypes
import os

from . import _library as c
from .errors import InvalidArgumentError, Status, check
from .handle import Handle
from .options import Options, take_buffer
from .vocabulary import Vocabulary, mapping, value_of

#: ``{name: value}`` of each vocabulary of the drawing, as the library names them.
STYLES = mapping(Vocabulary.STYLE)
FORMATS = mapping(Vocabulary.FORMAT)
FILLS = mapping(Vocabulary.SECTION_FILL)
PLACEMENTS = mapping(Vocabulary.PLACEMENT)
REGULARITY = mapping(Vocabulary.REGULARITY)
ANNOTATIONS = mapping(Vocabulary.ANNOTATION)
#: The words that stand alone for every annotation and for none (``sherd draw --annotations``).
_ALL_ANNOTATIONS, _NO_ANNOTATION = "all", "none"


def _bits(vocabulary, value, what, words=None):
    """The or of the bits of a list or comma-separated string of names (``words`` maps
    extra words to their bits); an int as it is (the C ABI checks it)."""
    words = words or {}
    if isinstance(value, str):
        value = [name.strip() for name in value.split(",") if name.strip()]
    if isinstance(value, (list, tuple, set, frozenset)):
        bits = 0
        for name in value:
            known = words.get(str(name).lower())
            bits |= known if known is not None else value_of(vocabulary, name, what)
        return bits
    return int(value)


def _styles(value):
    return _bits(Vocabulary.STYLE, value, "style")


def _annotations(value):
    """``annotations``: names among height, wall_thickness, capacity, or all, or none
    (a list may also be empty: none, as a host's empty set of check boxes)."""
    if isinstance(value, str):
        if not value.strip():
            raise InvalidArgumentError(Status.INVALID_ARGUMENT, "no annotation given; say \"none\" for none")
        value = [name.strip() for name in value.split(",") if name.strip()]
    if isinstance(value, (list, tuple, set, frozenset)) and len(value) > 1 \
            and {str(name).lower() for name in value} & {_ALL_ANNOTATIONS, _NO_ANNOTATION}:
        raise InvalidArgumentError(Status.INVALID_ARGUMENT,
                                   f"annotations {list(value)}: all and none cannot be combined with others")
    every = 0
    for bit in ANNOTATIONS.values():
        every |= bit
    return _bits(Vocabulary.ANNOTATION, value, "annotation", {_ALL_ANNOTATIONS: every, _NO_ANNOTATION: 0})


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
            "section_fill": lambda v: value_of(Vocabulary.SECTION_FILL, v, "section fill"),
            "placement": lambda v: value_of(Vocabulary.PLACEMENT, v, "placement"),
            "regularity": lambda v: value_of(Vocabulary.REGULARITY, v, "regularity"),
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
        check(c.lib.sherd_drawing_to_buffer(self.handle, value_of(Vocabulary.FORMAT, format, "format"), ctypes.byref(buffer)))
        return take_buffer(buffer)

    def write(self, path):
        """Writes the drawing, the format chosen by the file's extension (atomically)."""
        check(c.lib.sherd_drawing_write(self.handle, os.fsencode(path)))
