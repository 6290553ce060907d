"""The library's named values (criteria, surfaces, styles, record statuses...), read from
libsherd at load time (``sherd_vocabulary_entry``) so that the binding offers the names the
library defines instead of a copy of them."""

import ctypes
import enum
import functools

from . import _library as c
from .errors import InvalidArgumentError, Status, check


class Vocabulary(enum.IntEnum):
    """``SHERD_VOCABULARY_*`` (tests check these against ``sherd.h``)."""

    CRITERION = 0
    SURFACE = 1
    PARETO_CHOICE = 2
    EDGE = 3
    PROFILE_METHOD = 4
    CIRCLE_FIT = 5
    STYLE = 6
    ANNOTATION = 7
    SECTION_FILL = 8
    PLACEMENT = 9
    REGULARITY = 10
    FORMAT = 11
    RECORD_STATUS = 12


@functools.lru_cache(maxsize=None)
def entries(vocabulary):
    """``(name, value, description)`` of every named value of ``vocabulary``, in the
    library's order (the strings are the library's; they never change while it is loaded)."""
    count = ctypes.c_size_t()
    check(c.lib.sherd_vocabulary_count(int(vocabulary), ctypes.byref(count)))
    listed = []
    for index in range(count.value):
        entry = c.SherdVocabularyEntry(size=ctypes.sizeof(c.SherdVocabularyEntry))
        check(c.lib.sherd_vocabulary_entry(int(vocabulary), index, ctypes.byref(entry)))
        listed.append((entry.name.decode("utf-8"), entry.value, entry.description.decode("utf-8")))
    return tuple(listed)


def names(vocabulary):
    """The names of ``vocabulary``, in the library's order."""
    return [name for name, _, _ in entries(vocabulary)]


def mapping(vocabulary):
    """``{name: value}`` of ``vocabulary``."""
    return {name: value for name, value, _ in entries(vocabulary)}


def name_of(vocabulary, value):
    """The name of ``value`` in ``vocabulary``; the number as text for a value it lacks."""
    return next((name for name, known, _ in entries(vocabulary) if known == value), str(value))


def value_of(vocabulary, value, what):
    """The value a name stands for, as the library reads it (any case, hyphens for
    underscores, aliases such as "color"); an int as it is (the C ABI checks it).
    ``what`` names the argument in the error."""
    if not isinstance(value, str):
        return int(value)
    found = ctypes.c_uint32()
    if c.lib.sherd_vocabulary_value(int(vocabulary), value.encode("utf-8"), ctypes.byref(found)) != Status.OK:
        raise InvalidArgumentError(Status.INVALID_ARGUMENT,
                                   f"unknown {what} {value!r}; one of {sorted(names(vocabulary))}") from None
    return found.value


#: The ``"status"`` of a pipeline record (``sherd orient --json``), e.g.
#: ``RecordStatus.AXIS_UNCERTAIN.value == "axis_uncertain"``.
RecordStatus = enum.Enum("RecordStatus", {name.upper(): name for name in names(Vocabulary.RECORD_STATUS)},
                         module=__name__)
