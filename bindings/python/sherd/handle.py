"""``Handle``: ownership of one library handle (a mesh, a drawing), freed exactly once."""

from . import _library as c


class Handle:
    """Owns a pointer from the C API and frees it with ``sherd_<_kind>_free`` when
    garbage-collected, on :meth:`close` or on leaving a ``with`` block."""

    #: The handle's C name after ``sherd_``, e.g. ``"mesh"`` for ``sherd_mesh_free``.
    _kind = None

    def __init__(self, handle):
        """Takes ownership of ``handle`` (use the classes' constructors)."""
        self._handle = handle

    @property
    def handle(self):
        """The C pointer, still owned by this object."""
        if not getattr(self, "_handle", None):
            raise ValueError(f"the {self._kind} was closed")
        return self._handle

    def close(self):
        """Frees the handle now; the object is unusable afterwards."""
        handle, self._handle = getattr(self, "_handle", None), None
        if handle:
            getattr(c.lib, f"sherd_{self._kind}_free")(handle)

    def __del__(self):
        self.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
