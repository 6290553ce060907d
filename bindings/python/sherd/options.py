"""Buffers, option builders and enum values shared by the binding's modules."""

import ctypes
import json

from . import _library as c
from .errors import check


def take_buffer(buffer):
    """The bytes of a ``SherdBuffer*`` (then freed); None for a NULL buffer."""
    if not buffer:
        return None
    try:
        data, size = ctypes.c_void_p(), ctypes.c_size_t()
        check(c.lib.sherd_buffer_contents(buffer, ctypes.byref(data), ctypes.byref(size)))
        return ctypes.string_at(data.value, size.value) if size.value else b""
    finally:
        c.lib.sherd_buffer_free(buffer)


def take_json(buffer):
    """The JSON object in a ``SherdBuffer*`` (then freed)."""
    raw = take_buffer(buffer)
    return None if raw is None else json.loads(raw.decode("utf-8"))
