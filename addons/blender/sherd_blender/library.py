"""Finds the sherd Python package: the copy vendored in this add-on (with its bundled
``libsherd.so``, as addons/blender/build.sh assembles it) or an installed ``sherd``
(which honours ``SHERD_LIBRARY``). Imported lazily so the add-on registers, and says why,
even when the library cannot be loaded."""

import importlib

_module = None


class LibraryMissingError(Exception):
    """The sherd package or its native library could not be loaded."""


def sherd():
    """The ``sherd`` module; raises :class:`LibraryMissingError` with the reason."""
    global _module
    if _module is not None:
        return _module
    errors = []
    for name in (f"{__package__}.sherd", "sherd"):
        try:
            _module = importlib.import_module(name)
            return _module
        except ImportError as error:
            errors.append(f"{name}: {error}")
    raise LibraryMissingError("the sherd library could not be loaded (" + "; ".join(errors) + ")")


def is_sherd_error(error):
    """True for an exception raised by the sherd library (``sherd.SherdError``)."""
    return _module is not None and isinstance(error, _module.SherdError)


def vocabulary_items(vocabulary, *defaults):
    """Blender enum items ``(name, label, description)`` for one of the library's
    vocabularies (``"CRITERION"``: ``sherd.Vocabulary.CRITERION``), in the library's
    order, the names and descriptions the library's. Without the library the items are
    the ``defaults`` alone, so that the add-on still registers and says why it cannot work."""
    try:
        module = sherd()
        entries = module.vocabulary.entries(module.Vocabulary[vocabulary])
    except LibraryMissingError as error:
        return [(name, label(name), str(error)) for name in defaults]
    return [(name, label(name), description) for name, _, description in entries]


def label(name):
    """How Blender shows a library name: ``mean_of_best`` as "Mean of best"."""
    return name.replace("_", " ").capitalize()
