"""sherd: orient 3D scans of archaeological pottery sherds and draw them.

A ctypes binding of the libsherd C ABI (``include/sherd.h``), numpy arrays in and out,
exceptions from status codes. The library is found through ``SHERD_LIBRARY``, next to
this package, or on the system's library path.
"""

from ._library import ABI_VERSION, lib
from .axis import Axis, oriented_transform
from .errors import (
    BufferTooSmallError,
    DegenerateGeometryError,
    InvalidArgumentError,
    NeedsManualOrientationError,
    SenseUncertainError,
    NotAvailableError,
    NotConvergedError,
    NullPointerError,
    PanicError,
    ParseError,
    SherdError,
    SherdIOError,
    Status,
    last_error_message,
)
from .draw import Drawing
from .export import (export_oriented_ply, export_profile_csv, export_reconstruction_ply, most_informative_angle,
                     profile_csv, profile_section)
from .mesh import Attribute, Mesh
from .pipeline import (Analysis, BestGuess, Measurements, Orientation, Refinement, analyse, measure, orient_automatic,
                       orient_from_three_points, points_on_longest_rill, process_file, refine, synthetic_sherd)
from .reconstruct import Regularity, reconstruct, regularity
from .vocabulary import RecordStatus, Vocabulary

if lib.sherd_abi_version() != ABI_VERSION:
    raise ImportError(
        f"libsherd has ABI version {lib.sherd_abi_version()}, this binding expects {ABI_VERSION}")

#: The loaded library's version string.
__version__ = lib.sherd_version().decode()

__all__ = [
    "Analysis", "analyse", "BestGuess", "process_file", "Regularity", "reconstruct", "regularity",
    "Attribute", "Axis", "Drawing", "BufferTooSmallError", "DegenerateGeometryError", "InvalidArgumentError", "Mesh",
    "NeedsManualOrientationError", "SenseUncertainError", "NotAvailableError", "NotConvergedError", "NullPointerError", "PanicError",
    "ParseError", "SherdError", "SherdIOError", "Status", "export_oriented_ply", "export_profile_csv",
    "export_reconstruction_ply", "Measurements", "measure", "Refinement", "refine",
    "last_error_message", "most_informative_angle", "orient_automatic", "orient_from_three_points", "Orientation", "points_on_longest_rill",
    "oriented_transform", "profile_csv", "profile_section", "synthetic_sherd", "RecordStatus", "Vocabulary",
]
