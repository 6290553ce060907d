"""Buffers, option builders and enum values shared by the binding's modules."""

import ctypes
import json

from . import _library as c
from .errors import InvalidArgumentError, Status, check


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


class Options:
    """An option builder ``sherd_<name>_options``, freed on exit. ``values`` maps each
    keyword to its value (None keeps the library's default), ``setters`` each keyword to
    the converter of its value for the C setter ``sherd_<name>_options_set_<keyword>``
    (a tuple for a setter of several arguments)."""

    def __init__(self, name, values, setters):
        self.name = name
        self.handle = c.SherdOptions_p()
        check(getattr(c.lib, f"sherd_{name}_options_new")(ctypes.byref(self.handle)))
        try:
            for key, value in values.items():
                if value is None:
                    continue
                if key not in setters:
                    raise TypeError(f"unknown {name} option {key!r}")
                setter = getattr(c.lib, f"sherd_{name}_options_set_{key}")
                arguments = setters[key](value)
                check(setter(self.handle, *(arguments if isinstance(arguments, tuple) else (arguments,))))
        except BaseException:
            self.close()
            raise

    def close(self):
        handle, self.handle = self.handle, None
        if handle:
            getattr(c.lib, f"sherd_{self.name}_options_free")(handle)

    def __enter__(self):
        return self.handle

    def __exit__(self, *exc):
        self.close()


def enum_value(names, value, what):
    if isinstance(value, str):
        try:
            return names[value.lower()]
        except KeyError:
            raise InvalidArgumentError(Status.INVALID_ARGUMENT,
                                       f"unknown {what} {value!r}; one of {sorted(names)}") from None
    return int(value)
