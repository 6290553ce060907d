"""Status codes of the C ABI and the exceptions they become."""

import enum

from ._library import lib


def _status_members():
    """``SHERD_STATUS_*`` as the library names them (``sherd_status_name``), from 0 up to
    the first value it does not know."""
    members = {}
    while True:
        name = lib.sherd_status_name(len(members)).decode("ascii")
        if name == "SHERD_STATUS_UNKNOWN":
            return members
        members[name.removeprefix("SHERD_STATUS_")] = len(members)


#: ``SHERD_STATUS_*``, named by the library (tests check these against ``sherd.h``).
Status = enum.IntEnum("Status", _status_members(), module=__name__)


class SherdError(Exception):
    """A call into libsherd failed. ``status`` is the :class:`Status`, ``message`` the
    library's message (naming the function, the argument or element and the value)."""

    status = None

    def __init__(self, status, message):
        super().__init__(message)
        self.status = status
        self.message = message


class InvalidArgumentError(SherdError, ValueError):
    """An argument had a value the function does not accept."""


class NullPointerError(SherdError, ValueError):
    """A required pointer was NULL (a bug in the binding or the caller)."""


class BufferTooSmallError(SherdError):
    """An output buffer was too small."""


class NotAvailableError(SherdError):
    """The mesh has no such attribute."""


class SherdIOError(SherdError, OSError):
    """A file could not be opened, read or written."""


class ParseError(SherdError, ValueError):
    """A file's content is malformed."""


class DegenerateGeometryError(SherdError):
    """The geometry cannot support the operation."""


class NotConvergedError(SherdError):
    """An optimisation stopped at its bound without meeting its tolerance."""


class NeedsManualOrientationError(SherdError):
    """The data do not determine an axis: give three points."""


class SenseUncertainError(SherdError):
    """The axis line is found but not which way is up (base to rim)."""


class PanicError(SherdError):
    """A bug inside libsherd, caught at the boundary; please report it."""


_EXCEPTIONS = {
    Status.INVALID_ARGUMENT: InvalidArgumentError,
    Status.NULL_POINTER: NullPointerError,
    Status.BUFFER_TOO_SMALL: BufferTooSmallError,
    Status.NOT_AVAILABLE: NotAvailableError,
    Status.IO: SherdIOError,
    Status.PARSE: ParseError,
    Status.DEGENERATE_GEOMETRY: DegenerateGeometryError,
    Status.NOT_CONVERGED: NotConvergedError,
    Status.NEEDS_MANUAL_ORIENTATION: NeedsManualOrientationError,
    Status.PANIC: PanicError,
    Status.SENSE_UNCERTAIN: SenseUncertainError,
}


def last_error_message():
    """This thread's last error message from the library."""
    return lib.sherd_last_error_message().decode("utf-8", "replace")


def error_for(status):
    """The exception for a non-OK ``status`` with the thread's message."""
    try:
        status = Status(status)
    except ValueError:
        return SherdError(status, f"unknown status {status}: {last_error_message()}")
    return _EXCEPTIONS.get(status, SherdError)(status, last_error_message())


def check(status):
    """Raises the exception for ``status`` unless it is OK."""
    if status != Status.OK:
        raise error_for(status)
