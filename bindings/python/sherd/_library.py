"""Loading libsherd and declaring the C signatures (ctypes: Blender's Python has no compiler).

The library is looked for, in order: at the path in the ``SHERD_LIBRARY`` environment
variable; next to this package (``sherd/libsherd.so``, as a wheel ships it); on the
system's library path.
"""

import ctypes
import ctypes.util
import os
import sys
from pathlib import Path

#: The ABI version of the header this binding was written against (``SHERD_ABI_VERSION``).
ABI_VERSION = 1

_NAMES = {"linux": "libsherd.so", "darwin": "libsherd.dylib", "win32": "sherd.dll"}


def _candidates():
    explicit = os.environ.get("SHERD_LIBRARY")
    if explicit:
        yield Path(explicit)
        return
    yield Path(__file__).resolve().parent / _NAMES.get(sys.platform, "libsherd.so")
    found = ctypes.util.find_library("sherd")
    if found:
        yield Path(found)


def _load():
    tried = []
    for path in _candidates():
        tried.append(str(path))
        if path.is_absolute() and not path.exists():
            continue
        try:
            return ctypes.CDLL(str(path))
        except OSError as error:
            tried[-1] += f" ({error})"
    raise ImportError(
        "libsherd not found; set SHERD_LIBRARY to the path of libsherd.so "
        "(cargo build --release gives target/release/libsherd.so). Tried: " + "; ".join(tried)
    )


lib = _load()

c_double_p = ctypes.POINTER(ctypes.c_double)
c_float_p = ctypes.POINTER(ctypes.c_float)
c_uint32_p = ctypes.POINTER(ctypes.c_uint32)
c_uint8_p = ctypes.POINTER(ctypes.c_uint8)
c_size_t_p = ctypes.POINTER(ctypes.c_size_t)


class SherdMesh(ctypes.Structure):
    """Opaque handle."""


class SherdAxis(ctypes.Structure):
    """Mirror of the C struct; ``size`` must be set to its size."""

    _fields_ = [
        ("size", ctypes.c_size_t),
        ("point", ctypes.c_double * 3),
        ("direction", ctypes.c_double * 3),
    ]


SherdMesh_p = ctypes.POINTER(SherdMesh)
Status = ctypes.c_uint32


def _declare(name, restype, *argtypes):
    function = getattr(lib, name)
    function.restype = restype
    function.argtypes = list(argtypes)


_declare("sherd_version", ctypes.c_char_p)
_declare("sherd_abi_version", ctypes.c_uint32)
_declare("sherd_status_name", ctypes.c_char_p, ctypes.c_uint32)
_declare("sherd_last_error_message", ctypes.c_char_p)


class SherdVocabularyEntry(ctypes.Structure):
    """Mirror of the C struct; ``size`` must be set to its size."""

    _fields_ = [
        ("size", ctypes.c_size_t),
        ("name", ctypes.c_char_p),
        ("value", ctypes.c_uint32),
        ("description", ctypes.c_char_p),
    ]


_declare("sherd_vocabulary_count", ctypes.c_uint32, ctypes.c_uint32, ctypes.POINTER(ctypes.c_size_t))
_declare("sherd_vocabulary_entry", ctypes.c_uint32, ctypes.c_uint32, ctypes.c_size_t,
         ctypes.POINTER(SherdVocabularyEntry))
_declare("sherd_vocabulary_value", ctypes.c_uint32, ctypes.c_uint32, ctypes.c_char_p, ctypes.POINTER(ctypes.c_uint32))

_declare("sherd_mesh_from_arrays", Status, c_double_p, ctypes.c_size_t, c_uint32_p, ctypes.c_size_t,
         ctypes.POINTER(SherdMesh_p))
_declare("sherd_mesh_from_arrays_f32", Status, c_float_p, ctypes.c_size_t, c_uint32_p, ctypes.c_size_t,
         ctypes.POINTER(SherdMesh_p))
_declare("sherd_mesh_clone", Status, SherdMesh_p, ctypes.POINTER(SherdMesh_p))
_declare("sherd_mesh_free", None, SherdMesh_p)
_declare("sherd_mesh_set_normals", Status, SherdMesh_p, c_double_p, ctypes.c_size_t)
_declare("sherd_mesh_set_normals_f32", Status, SherdMesh_p, c_float_p, ctypes.c_size_t)
_declare("sherd_mesh_set_colors", Status, SherdMesh_p, c_uint8_p, ctypes.c_size_t)
_declare("sherd_mesh_set_corner_uvs", Status, SherdMesh_p, c_float_p, ctypes.c_size_t)
_declare("sherd_mesh_vertex_count", Status, SherdMesh_p, c_size_t_p)
_declare("sherd_mesh_face_count", Status, SherdMesh_p, c_size_t_p)
_declare("sherd_mesh_attributes", Status, SherdMesh_p, c_uint32_p)
_declare("sherd_mesh_copy_positions", Status, SherdMesh_p, c_double_p, ctypes.c_size_t)
_declare("sherd_mesh_copy_positions_f32", Status, SherdMesh_p, c_float_p, ctypes.c_size_t)
_declare("sherd_mesh_copy_triangles", Status, SherdMesh_p, c_uint32_p, ctypes.c_size_t)
_declare("sherd_mesh_copy_normals", Status, SherdMesh_p, c_double_p, ctypes.c_size_t)
_declare("sherd_mesh_copy_colors", Status, SherdMesh_p, c_uint8_p, ctypes.c_size_t)
_declare("sherd_mesh_copy_corner_uvs", Status, SherdMesh_p, c_float_p, ctypes.c_size_t)
_declare("sherd_mesh_copy_quality", Status, SherdMesh_p, c_float_p, ctypes.c_size_t)

_declare("sherd_axis_oriented_transform", Status, ctypes.POINTER(SherdAxis), c_double_p, c_double_p)
_declare("sherd_mesh_oriented_transform", Status, SherdMesh_p, ctypes.POINTER(SherdAxis), c_double_p)



class SherdBuffer(ctypes.Structure):
    """Opaque handle."""


SherdBuffer_p = ctypes.POINTER(SherdBuffer)
SherdAxis_p = ctypes.POINTER(SherdAxis)

_declare("sherd_buffer_contents", Status, SherdBuffer_p, ctypes.POINTER(ctypes.c_void_p), c_size_t_p)
_declare("sherd_buffer_free", None, SherdBuffer_p)

_declare("sherd_mesh_read", Status, ctypes.c_char_p, ctypes.POINTER(SherdMesh_p))
_declare("sherd_mesh_write_ply", Status, SherdMesh_p, ctypes.c_char_p, ctypes.c_bool)

_declare("sherd_export_oriented_ply", Status, SherdMesh_p, SherdAxis_p, ctypes.c_char_p, ctypes.c_bool)
_declare("sherd_export_profile_csv", Status, SherdMesh_p, SherdAxis_p, ctypes.c_double, ctypes.c_char_p)
_declare("sherd_profile_csv", Status, SherdMesh_p, SherdAxis_p, ctypes.c_double, ctypes.POINTER(SherdBuffer_p))
_declare("sherd_profile_most_informative_angle", Status, SherdMesh_p, SherdAxis_p, c_double_p)


class SherdOptions(ctypes.Structure):
    """Opaque handle (any option builder)."""


class SherdOrientReport(ctypes.Structure):
    _fields_ = [
        ("size", ctypes.c_size_t),
        ("oriented", ctypes.c_bool),
        ("angle_uncertainty_deg", ctypes.c_double),
        ("position_uncertainty_mm", ctypes.c_double),
        ("kept_vertex_count", ctypes.c_size_t),
    ]


SherdOptions_p = ctypes.POINTER(SherdOptions)

_declare("sherd_mesh_repair", Status, SherdMesh_p, SherdOptions_p, ctypes.POINTER(SherdBuffer_p))
_declare("sherd_mesh_decimate", Status, SherdMesh_p, ctypes.c_size_t, ctypes.POINTER(SherdMesh_p))
_declare("sherd_synthetic_sherd", Status, ctypes.c_uint64, ctypes.c_uint32, ctypes.c_size_t, ctypes.c_double,
         ctypes.POINTER(SherdMesh_p), SherdAxis_p, ctypes.POINTER(SherdBuffer_p))

for _builder in ("repair", "orient", "manual"):
    _declare(f"sherd_{_builder}_options_new", Status, ctypes.POINTER(SherdOptions_p))
    _declare(f"sherd_{_builder}_options_free", None, SherdOptions_p)
_declare("sherd_repair_options_set_merge_tolerance_mm", Status, SherdOptions_p, ctypes.c_double)
_declare("sherd_repair_options_set_keep_largest_component", Status, SherdOptions_p, ctypes.c_bool)
_declare("sherd_orient_options_set_target_vertex_count", Status, SherdOptions_p, ctypes.c_size_t)
_declare("sherd_orient_options_set_smoothing_iterations", Status, SherdOptions_p, ctypes.c_size_t)
_declare("sherd_orient_options_set_opposite_normal_confidence", Status, SherdOptions_p, ctypes.c_double)
_declare("sherd_manual_options_set_keep_fraction", Status, SherdOptions_p, ctypes.c_double)
_declare("sherd_manual_options_set_max_pick_distance_mm", Status, SherdOptions_p, ctypes.c_double)

_declare("sherd_orient_automatic", Status, SherdMesh_p, SherdOptions_p, SherdAxis_p,
         ctypes.POINTER(SherdOrientReport), ctypes.POINTER(SherdBuffer_p))
_declare("sherd_orient_from_three_points", Status, SherdMesh_p, c_double_p, SherdOptions_p, SherdAxis_p,
         ctypes.POINTER(SherdOrientReport), ctypes.POINTER(SherdBuffer_p))
_declare("sherd_points_on_longest_rill", Status, SherdMesh_p, SherdAxis_p, c_double_p, c_size_t_p)


class SherdRefinement(ctypes.Structure):
    """Opaque handle."""


class SherdRefineReport(ctypes.Structure):
    _fields_ = [
        ("size", ctypes.c_size_t),
        ("criterion", ctypes.c_uint32),
        ("surface", ctypes.c_uint32),
        ("iterations", ctypes.c_uint64),
        ("start_residual_mm", ctypes.c_double),
        ("residual_mm", ctypes.c_double),
        ("tilt_deg", ctypes.c_double),
        ("shift_mm", ctypes.c_double),
        ("section_count", ctypes.c_size_t),
        ("pareto_point_count", ctypes.c_size_t),
        ("flagged", ctypes.c_uint32),
    ]


class SherdParetoPoint(ctypes.Structure):
    _fields_ = [
        ("tilt_x_deg", ctypes.c_double),
        ("tilt_y_deg", ctypes.c_double),
        ("centre_dispersion_mm2", ctypes.c_double),
        ("circle_residual_mm2", ctypes.c_double),
    ]


class SherdMeasurements(ctypes.Structure):
    _fields_ = [
        ("size", ctypes.c_size_t),
        ("rim_radius_mm", ctypes.c_double),
        ("rim_diameter_mm", ctypes.c_double),
        ("rim_diameter_interval_mm", ctypes.c_double * 2),
        ("base_radius_mm", ctypes.c_double),
        ("base_diameter_mm", ctypes.c_double),
        ("base_diameter_interval_mm", ctypes.c_double * 2),
        ("sector_angle_deg", ctypes.c_double),
        ("sector_percent", ctypes.c_double),
        ("height_mm", ctypes.c_double),
        ("wall_thickness_mm", ctypes.c_double),
        ("capacity_litres", ctypes.c_double),
        ("axis_angle_interval_deg", ctypes.c_double * 2),
        ("axis_distance_interval_mm", ctypes.c_double * 2),
        ("axis_uncertain", ctypes.c_uint32),
    ]


SherdRefinement_p = ctypes.POINTER(SherdRefinement)

for _builder in ("refine", "measure"):
    _declare(f"sherd_{_builder}_options_new", Status, ctypes.POINTER(SherdOptions_p))
    _declare(f"sherd_{_builder}_options_free", None, SherdOptions_p)
_declare("sherd_refine_options_set_criterion", Status, SherdOptions_p, ctypes.c_uint32)
_declare("sherd_refine_options_set_surface", Status, SherdOptions_p, ctypes.c_uint32)
_declare("sherd_refine_options_set_section_count", Status, SherdOptions_p, ctypes.c_size_t)
_declare("sherd_refine_options_set_search_bound_deg", Status, SherdOptions_p, ctypes.c_double)
_declare("sherd_refine_options_set_pareto_choice", Status, SherdOptions_p, ctypes.c_uint32, ctypes.c_size_t)
_declare("sherd_refine_options_set_pareto_section_limits", Status, SherdOptions_p, ctypes.c_size_t, ctypes.c_double)
_declare("sherd_refine_options_set_tangent_tolerance_mm", Status, SherdOptions_p, ctypes.c_double)
_declare("sherd_refine_options_set_edge", Status, SherdOptions_p, ctypes.c_uint32)
_declare("sherd_refine_options_set_profile_method", Status, SherdOptions_p, ctypes.c_uint32, ctypes.c_double)
_declare("sherd_refine_options_set_circle_fit", Status, SherdOptions_p, ctypes.c_uint32)
_declare("sherd_measure_options_set_refine_options", Status, SherdOptions_p, SherdOptions_p)
_declare("sherd_measure_options_set_bootstrap_samples", Status, SherdOptions_p, ctypes.c_size_t)
_declare("sherd_measure_options_set_bootstrap_seed", Status, SherdOptions_p, ctypes.c_uint64)
_declare("sherd_measure_options_set_confidence", Status, SherdOptions_p, ctypes.c_double)

_declare("sherd_refine", Status, SherdMesh_p, SherdAxis_p, SherdOptions_p, ctypes.POINTER(SherdRefinement_p))
_declare("sherd_refinement_axis", Status, SherdRefinement_p, SherdAxis_p)
_declare("sherd_refinement_report", Status, SherdRefinement_p, ctypes.POINTER(SherdRefineReport))
_declare("sherd_refinement_report_json", Status, SherdRefinement_p, ctypes.POINTER(SherdBuffer_p))
_declare("sherd_refinement_pareto_front", Status, SherdRefinement_p, ctypes.POINTER(SherdParetoPoint),
         ctypes.c_size_t, c_size_t_p)
_declare("sherd_refinement_pareto_plot_svg", Status, SherdRefinement_p, ctypes.POINTER(SherdBuffer_p))
_declare("sherd_refinement_free", None, SherdRefinement_p)
_declare("sherd_measure", Status, SherdMesh_p, SherdAxis_p, SherdOptions_p, ctypes.POINTER(SherdMeasurements),
         ctypes.POINTER(SherdBuffer_p))
_declare("sherd_export_reconstruction_ply", Status, SherdMesh_p, SherdAxis_p, ctypes.c_double, ctypes.c_size_t,
         ctypes.c_char_p, ctypes.c_bool)


class SherdDrawing(ctypes.Structure):
    """Opaque handle."""


SherdDrawing_p = ctypes.POINTER(SherdDrawing)

_declare("sherd_draw_options_new", Status, ctypes.POINTER(SherdOptions_p))
_declare("sherd_draw_options_free", None, SherdOptions_p)
_declare("sherd_draw_options_set_style", Status, SherdOptions_p, ctypes.c_uint32)
_declare("sherd_draw_options_set_scale_denominator", Status, SherdOptions_p, ctypes.c_uint32)
_declare("sherd_draw_options_set_dpi", Status, SherdOptions_p, ctypes.c_double)
_declare("sherd_draw_options_set_section_angle_rad", Status, SherdOptions_p, ctypes.c_double)
_declare("sherd_draw_options_set_section_fill", Status, SherdOptions_p, ctypes.c_uint32)
_declare("sherd_draw_options_set_placement", Status, SherdOptions_p, ctypes.c_uint32)
_declare("sherd_draw_options_set_regularity", Status, SherdOptions_p, ctypes.c_uint32)
_declare("sherd_draw_options_set_title", Status, SherdOptions_p, ctypes.c_char_p)
_declare("sherd_draw_options_set_interior_view", Status, SherdOptions_p, ctypes.c_bool)
_declare("sherd_draw_options_set_prolongation", Status, SherdOptions_p, ctypes.c_bool)
_declare("sherd_draw_options_set_annotations", Status, SherdOptions_p, ctypes.c_uint32)
_declare("sherd_drawing_build", Status, SherdMesh_p, SherdAxis_p, SherdOptions_p, ctypes.POINTER(SherdDrawing_p))
_declare("sherd_drawing_write", Status, SherdDrawing_p, ctypes.c_char_p)
_declare("sherd_drawing_to_buffer", Status, SherdDrawing_p, ctypes.c_uint32, ctypes.POINTER(SherdBuffer_p))
_declare("sherd_drawing_free", None, SherdDrawing_p)

_declare("sherd_reconstruct", Status, SherdMesh_p, SherdAxis_p, ctypes.c_double, ctypes.c_size_t,
         ctypes.POINTER(SherdMesh_p))
_declare("sherd_regularity", Status, SherdMesh_p, SherdAxis_p, ctypes.c_uint32, ctypes.c_double, c_float_p, c_uint8_p,
         ctypes.c_size_t, c_double_p)
_declare("sherd_process_file", Status, ctypes.c_char_p, SherdOptions_p, ctypes.c_double, SherdAxis_p,
         ctypes.POINTER(SherdBuffer_p))
_declare("sherd_analyse", Status, SherdMesh_p, SherdOptions_p, ctypes.c_double, SherdAxis_p,
         ctypes.POINTER(SherdBuffer_p))
