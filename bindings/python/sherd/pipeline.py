"""The pipeline over the C ABI: synthetic sherds, orientation, refinement, measurements,
and the whole pipeline in one call (the record ``sherd orient --json`` prints)."""

import ctypes
import math
import os
from dataclasses import dataclass, field

import numpy as np

from . import _library as c
from .axis import Axis, as_pointer
from .errors import Status, check, error_for, last_error_message
from .mesh import Mesh
from .options import Options, enum_value, take_buffer, take_json
from .vocabulary import RecordStatus, Vocabulary, mapping, name_of, value_of


SYNTH_KINDS = {"random": 0, "rim": 1, "body": 2, "base": 3, "rim_to_base": 4, "flat_base": 5,
               "near_spherical": 6, "tiny": 7}
#: ``{name: SHERD_CRITERION_* value}``, as the library names them.
CRITERIA = mapping(Vocabulary.CRITERION)
#: ``{name: SHERD_SURFACE_* value}``, as the library names them.
SURFACES = mapping(Vocabulary.SURFACE)


def synthetic_sherd(seed, kind="random", target_faces=0, noise_mm=0.02):
    """A synthetic sherd with a known axis: ``(mesh, true_axis, truth)`` where ``truth``
    is the ground truth as a dict (radii, sector angle, height, profile...)."""
    mesh, axis, truth = c.SherdMesh_p(), c.SherdAxis(), c.SherdBuffer_p()
    axis.size = ctypes.sizeof(c.SherdAxis)
    check(c.lib.sherd_synthetic_sherd(seed, enum_value(SYNTH_KINDS, kind, "kind"), target_faces, noise_mm,
                                      ctypes.byref(mesh), ctypes.byref(axis), ctypes.byref(truth)))
    return Mesh(mesh), Axis.from_c(axis), take_json(truth)


@dataclass
class BestGuess:
    """The axis the automatic orientation still found for a sherd it declined (needs
    manual orientation): not an answer, but where to start looking. ``axis`` is in the
    scan's frame and units, pointed base to rim as the sense cues read it under it (negate
    its direction to flip it); ``against`` says what speaks against it (why the sherd was
    declined); ``sense_known`` is True when the cues say which end is the rim as firmly as
    an oriented sherd's must, False when which way is up is a guess too, None where the
    call does not judge it (:attr:`Orientation.best_guess`)."""

    axis: Axis
    against: str
    sense_known: object = None


@dataclass
class Orientation:
    """The result of an orientation. ``oriented`` is False when the data do not determine
    the axis: ``axis`` is then only a guess and ``reason`` says why (ask for three points).
    ``sense_uncertain`` is True when the axis line is found but not which way is up (status
    ``SENSE_UNCERTAIN``): ``oriented`` is then False too, and the axis's line holds."""

    axis: Axis
    oriented: bool
    reason: str
    angle_uncertainty_deg: float
    position_uncertainty_mm: float
    kept_vertex_count: int
    report: dict = field(default_factory=dict)
    sense_uncertain: bool = False

    @property
    def best_guess(self):
        """A declined orientation's axis as a :class:`BestGuess` (``against`` its reason
        without the function's name, ``sense_known`` None); None when the axis is an answer (``oriented`` or
        ``sense_uncertain``) and when no axis was found at all (too few points:
        ``angle_uncertainty_deg`` is infinite and ``axis`` only a vertical through the
        centroid)."""
        if self.oriented or self.sense_uncertain or self.angle_uncertainty_deg == math.inf:
            return None
        return BestGuess(self.axis, self.reason.removeprefix("sherd_orient_automatic: "))


def _orientation(status, axis, summary, report):
    reason = ""
    if status in (Status.NEEDS_MANUAL_ORIENTATION, Status.SENSE_UNCERTAIN):
        reason = last_error_message()
    elif status != Status.OK:
        take_buffer(report)
        raise error_for(status)
    return Orientation(Axis.from_c(axis), bool(summary.oriented), reason, summary.angle_uncertainty_deg,
                       summary.position_uncertainty_mm, summary.kept_vertex_count, take_json(report),
                       status == Status.SENSE_UNCERTAIN)


def _outputs():
    axis, summary, report = c.SherdAxis(), c.SherdOrientReport(), c.SherdBuffer_p()
    axis.size = ctypes.sizeof(c.SherdAxis)
    summary.size = ctypes.sizeof(c.SherdOrientReport)
    return axis, summary, report


def orient_automatic(mesh, *, target_vertex_count=None, smoothing_iterations=None,
                     opposite_normal_confidence=None):
    """The rotation axis from the normals (the paper's section 2.2). Returns an
    :class:`Orientation`; check ``oriented`` (a fragment that does not determine its
    axis is not an exception: it is an answer)."""
    setters = {
        "target_vertex_count": int,
        "smoothing_iterations": int,
        "opposite_normal_confidence": float,
    }
    values = dict(target_vertex_count=target_vertex_count, smoothing_iterations=smoothing_iterations,
                  opposite_normal_confidence=opposite_normal_confidence)
    axis, summary, report = _outputs()
    with Options("orient", values, setters) as options:
        status = c.lib.sherd_orient_automatic(mesh.handle, options, ctypes.byref(axis), ctypes.byref(summary),
                                              ctypes.byref(report))
    return _orientation(status, axis, summary, report)


def orient_from_three_points(mesh, points, *, keep_fraction=None, max_pick_distance_mm=None):
    """The rotation axis from three points picked on one horizontal feature (rim edge,
    groove, base edge): ``points`` is (3, 3)."""
    picked = np.ascontiguousarray(points, dtype=np.float64).reshape(9)
    setters = {
        "keep_fraction": float,
        "max_pick_distance_mm": float,
    }
    values = dict(keep_fraction=keep_fraction, max_pick_distance_mm=max_pick_distance_mm)
    axis, summary, report = _outputs()
    with Options("manual", values, setters) as options:
        status = c.lib.sherd_orient_from_three_points(mesh.handle, as_pointer(picked, ctypes.c_double), options,
                                                      ctypes.byref(axis), ctypes.byref(summary),
                                                      ctypes.byref(report))
    return _orientation(status, axis, summary, report)


def points_on_longest_rill(mesh, axis):
    """Three points, (3, 3), on the longest wheel rill traced under ``axis`` (millimetres):
    where to pick for :func:`orient_from_three_points` on a sherd :func:`orient_automatic`
    declines, under the axis it still gives. None on a smooth wall."""
    points = np.zeros(9, dtype=np.float64)
    count = ctypes.c_size_t()
    c_axis = axis.to_c()
    check(c.lib.sherd_points_on_longest_rill(mesh.handle, ctypes.byref(c_axis), as_pointer(points, ctypes.c_double),
                                             ctypes.byref(count)))
    return points.reshape(3, 3) if count.value == 3 else None


@dataclass
class Refinement:
    """A refined axis, the criterion and surface used, the residuals, the full report and
    the Pareto front as an (n, 4) array of ``tilt_x_deg, tilt_y_deg,
    centre_dispersion_mm2, circle_residual_mm2`` (empty unless the criterion is Pareto)."""

    axis: Axis
    criterion: str
    surface: str
    iterations: int
    start_residual_mm: float
    residual_mm: float
    tilt_deg: float
    shift_mm: float
    section_count: int
    pareto_front: np.ndarray
    report: dict
    flagged: bool = False
    """The refinement doubts its axis: the skins barely fix its position, the automatic
    criterion found nothing to refine by and kept the start, or the tangent plane asked for
    by name reached the search bound. ``report["flag_reason"]`` says which;
    :func:`measure`'s intervals say how far off it may be."""
    pareto_plot_svg: str = ""
    """The Pareto front drawn as an SVG plot (the chosen solution circled); empty unless
    the criterion is Pareto."""


PARETO_CHOICES = mapping(Vocabulary.PARETO_CHOICE)
EDGES = mapping(Vocabulary.EDGE)
PROFILE_METHODS = mapping(Vocabulary.PROFILE_METHOD)
CIRCLE_FITS = mapping(Vocabulary.CIRCLE_FIT)


def _pareto_choice(value):
    """"knee", "centres", "residuals", or ("mean_of_best", n): the C setter's two arguments."""
    if isinstance(value, (tuple, list)):
        name, count = value
        return value_of(Vocabulary.PARETO_CHOICE, name, "pareto_choice"), int(count)
    return value_of(Vocabulary.PARETO_CHOICE, value, "pareto_choice"), 0


def _profile_method(value):
    """("reference", vertical sections), ("polynomial", degree) or ("spline", knot spacing mm)."""
    name, parameter = value
    return value_of(Vocabulary.PROFILE_METHOD, name, "profile_method"), float(parameter)


def _refine_options(criterion="auto", surface="both", section_count=0, search_bound_deg=None, pareto_choice=None,
                    pareto_section_limits=None, tangent_tolerance_mm=None, edge=None, profile_method=None,
                    circle_fit=None):
    setters = {
        "criterion": lambda v: value_of(Vocabulary.CRITERION, v, "criterion"),
        "surface": lambda v: value_of(Vocabulary.SURFACE, v, "surface"),
        "section_count": int,
        "search_bound_deg": float,
        "pareto_choice": _pareto_choice,
        "pareto_section_limits": lambda v: (int(v[0]), float(v[1])),
        "tangent_tolerance_mm": float,
        "edge": lambda v: value_of(Vocabulary.EDGE, v, "edge"),
        "profile_method": _profile_method,
        "circle_fit": lambda v: value_of(Vocabulary.CIRCLE_FIT, v, "circle_fit"),
    }
    values = dict(criterion=criterion, surface=surface, section_count=section_count,
                  search_bound_deg=search_bound_deg, pareto_choice=pareto_choice,
                  pareto_section_limits=pareto_section_limits, tangent_tolerance_mm=tangent_tolerance_mm, edge=edge,
                  profile_method=profile_method, circle_fit=circle_fit)
    return Options("refine", values, setters)


def refine(mesh, axis, *, criterion="auto", surface="both", section_count=0, search_bound_deg=None,
           pareto_choice=None, pareto_section_limits=None, tangent_tolerance_mm=None, edge=None,
           profile_method=None, circle_fit=None):
    """Refines ``axis`` on ``mesh`` (the paper's section 2.3). ``pareto_choice`` picks the
    Pareto criterion's solution: "knee" (the default), "centres" (Eq. 3 alone), "residuals"
    (Eq. 4 alone) or ("mean_of_best", n); ``pareto_section_limits`` is (fewest points,
    smallest arc in degrees) of a section the Pareto criterion keeps (10, 3.0);
    ``tangent_tolerance_mm`` is Eq. 7's epsilon (3.0) and ``edge`` the edge the tangent
    plane rests on: "detect" (the default), "rim" or "base". ``profile_method`` is the
    profile criterion's form: ("reference", vertical sections) for Eq. 5, ("polynomial",
    degree) or ("spline", knot spacing in mm; the default ("spline", 1.5)) for Eq. 6;
    ``circle_fit`` the Pareto criterion's circle fit per section: "kasa", "pratt",
    "taubin" (the default) or "geometric"."""
    handle = c.SherdRefinement_p()
    c_axis = axis.to_c()
    with _refine_options(criterion, surface, section_count, search_bound_deg, pareto_choice, pareto_section_limits,
                         tangent_tolerance_mm, edge, profile_method, circle_fit) as options:
        check(c.lib.sherd_refine(mesh.handle, ctypes.byref(c_axis), options, ctypes.byref(handle)))
    try:
        refined, summary, report = c.SherdAxis(), c.SherdRefineReport(), c.SherdBuffer_p()
        refined.size = ctypes.sizeof(c.SherdAxis)
        summary.size = ctypes.sizeof(c.SherdRefineReport)
        check(c.lib.sherd_refinement_axis(handle, ctypes.byref(refined)))
        check(c.lib.sherd_refinement_report(handle, ctypes.byref(summary)))
        check(c.lib.sherd_refinement_report_json(handle, ctypes.byref(report)))
        count = ctypes.c_size_t()
        points = (c.SherdParetoPoint * max(summary.pareto_point_count, 1))()
        check(c.lib.sherd_refinement_pareto_front(handle, points, summary.pareto_point_count, ctypes.byref(count)))
        front = np.array([[p.tilt_x_deg, p.tilt_y_deg, p.centre_dispersion_mm2, p.circle_residual_mm2]
                          for p in points[:count.value]], dtype=np.float64).reshape(-1, 4)
        plot = ""
        if count.value:
            svg = c.SherdBuffer_p()
            check(c.lib.sherd_refinement_pareto_plot_svg(handle, ctypes.byref(svg)))
            plot = take_buffer(svg).decode("utf-8")
        return Refinement(Axis.from_c(refined), name_of(Vocabulary.CRITERION, summary.criterion),
                          name_of(Vocabulary.SURFACE, summary.surface), summary.iterations,
                          summary.start_residual_mm, summary.residual_mm, summary.tilt_deg, summary.shift_mm,
                          summary.section_count, front, take_json(report), bool(summary.flagged), plot)
    finally:
        c.lib.sherd_refinement_free(handle)


@dataclass
class Measurements:
    """Measurements of an oriented fragment (mm, degrees, litres); NaN where the fragment
    does not determine a figure; intervals as (low, high). ``details`` holds everything
    as the library reports it (wall thickness along the profile, notes)."""

    rim_radius_mm: float
    rim_diameter_mm: float
    rim_diameter_interval_mm: tuple
    base_radius_mm: float
    base_diameter_mm: float
    base_diameter_interval_mm: tuple
    sector_angle_deg: float
    sector_percent: float
    height_mm: float
    wall_thickness_mm: float
    capacity_litres: float
    axis_angle_interval_deg: tuple
    details: dict
    axis_uncertain: bool = False
    """The axis angle interval reaches past 4 degrees, the distance interval past 5 mm, or
    the axis refined without a quarter of the preserved arc moves by more than 1.5 mm:
    the axis and these figures want a look before they are used (``details["notes"]``
    says how far)."""
    axis_distance_interval_mm: tuple = (float("nan"), float("nan"))
    """(0, upper): the paper's mean point distance between the true axis and this one, mm."""


def measure(mesh, axis, *, bootstrap_samples=None, bootstrap_seed=None, confidence=None, refine_options=None):
    """Measures ``mesh`` oriented by ``axis``; ``refine_options`` (a dict of
    :func:`refine`'s keywords) is the refinement the intervals' bootstrap repeats."""
    setters = {
        "bootstrap_samples": int,
        "bootstrap_seed": int,
        "confidence": float,
    }
    values = dict(bootstrap_samples=bootstrap_samples, bootstrap_seed=bootstrap_seed, confidence=confidence)
    out, details = c.SherdMeasurements(), c.SherdBuffer_p()
    out.size = ctypes.sizeof(c.SherdMeasurements)
    c_axis = axis.to_c()
    with Options("measure", values, setters) as options:
        if refine_options is not None:
            with _refine_options(**refine_options) as refine_handle:
                check(c.lib.sherd_measure_options_set_refine_options(options, refine_handle))
        check(c.lib.sherd_measure(mesh.handle, ctypes.byref(c_axis), options, ctypes.byref(out),
                                  ctypes.byref(details)))
    return Measurements(out.rim_radius_mm, out.rim_diameter_mm, tuple(out.rim_diameter_interval_mm),
                        out.base_radius_mm, out.base_diameter_mm, tuple(out.base_diameter_interval_mm),
                        out.sector_angle_deg, out.sector_percent, out.height_mm, out.wall_thickness_mm,
                        out.capacity_litres, tuple(out.axis_angle_interval_deg), take_json(details),
                        bool(out.axis_uncertain), tuple(out.axis_distance_interval_mm))


@dataclass
class Analysis:
    """What the whole pipeline found for one scan: ``record`` is the JSON object
    ``sherd orient --json`` prints (as a dict), ``axis`` the final axis in the scan's frame
    and units (None when the axis line is not found; ``reason`` then says why). ``oriented``
    is False also when only the sense is uncertain: ``sense_uncertain`` is then True (record
    status ``sense_uncertain``) and the axis is given, its line found, its sense (base to
    rim) a guess. ``axis_uncertain`` is True (record status ``axis_uncertain``, its
    ``reason`` saying why) when the axis is found but not pinned down: ``oriented`` stays
    True, and the axis wants a look before its figures are used. A sherd that needs
    manual orientation has no ``axis``; :attr:`best_guess` gives the one its orientation
    still found, not to be trusted."""

    axis: Axis
    oriented: bool
    reason: str
    record: dict
    sense_uncertain: bool = False

    @property
    def axis_uncertain(self):
        return self.record.get("status") == RecordStatus.AXIS_UNCERTAIN.value

    @property
    def best_guess(self):
        """For a sherd that needs manual orientation (``axis`` None): the record's
        ``best_guess``, the axis the orientation still found, as a :class:`BestGuess`
        (scan frame and units); None for every other status and when it found no axis."""
        guess = self.record.get("best_guess")
        if not guess:
            return None
        return BestGuess(Axis(guess["axis"]["point"], guess["axis"]["direction"]), guess["against"],
                         bool(guess["sense_known"]))


def _analysis(call, refine_options, millimetres_per_unit):
    axis, record = c.SherdAxis(), c.SherdBuffer_p()
    axis.size = ctypes.sizeof(c.SherdAxis)
    with _refine_options(**(refine_options or {})) as options:
        status = call(options, float(millimetres_per_unit), ctypes.byref(axis), ctypes.byref(record))
    if status not in (Status.OK, Status.NEEDS_MANUAL_ORIENTATION, Status.SENSE_UNCERTAIN):
        take_buffer(record)
        raise error_for(status)
    oriented = status == Status.OK
    has_line = status in (Status.OK, Status.SENSE_UNCERTAIN)
    record = take_json(record)
    reason = (record.get("reason") or "") if oriented else last_error_message()
    return Analysis(Axis.from_c(axis) if has_line else None, oriented, reason, record,
                    status == Status.SENSE_UNCERTAIN)


def process_file(path, *, refine_options=None, millimetres_per_unit=1.0):
    """Reads, repairs, orients, refines and measures the scan at ``path`` exactly as
    ``sherd orient PATH --json`` does; ``refine_options`` is a dict of :func:`refine`'s
    keywords (None: criterion auto on both surfaces). Returns an :class:`Analysis`; a
    scan that cannot be read raises."""
    return _analysis(lambda *args: c.lib.sherd_process_file(os.fsencode(path), *args), refine_options,
                     millimetres_per_unit)


def analyse(mesh, *, refine_options=None, millimetres_per_unit=1.0):
    """Like :func:`process_file` for a :class:`Mesh` in memory (the record's ``file`` is
    ``"<memory>"``); ``mesh`` is not changed."""
    return _analysis(lambda *args: c.lib.sherd_analyse(mesh.handle, *args), refine_options, millimetres_per_unit)
