"""Makes the wheel a platform wheel when the native library is inside the package
(bindings/python/build_wheel.sh puts it there); otherwise the package is pure Python.
Everything else is in pyproject.toml."""

from pathlib import Path

from setuptools import setup
from setuptools.dist import Distribution

LIBRARIES = ("libsherd.so", "libsherd.dylib", "sherd.dll")


class SherdDistribution(Distribution):
    def has_ext_modules(self):
        package = Path(__file__).resolve().parent / "sherd"
        return any((package / name).is_file() for name in LIBRARIES)


setup(distclass=SherdDistribution)
