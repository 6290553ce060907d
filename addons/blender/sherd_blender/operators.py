"""The operators of the Sherd panel. They hold no algorithm: the active mesh goes to the
sherd library as arrays (world transform applied, so results are in world coordinates),
the results come back as custom properties on the object (``sherd_*``) and as its new
transform. Library errors become Blender reports and ``{'CANCELLED'}``."""

import contextlib
import math
import os
import tempfile

import bpy
import numpy as np
from mathutils import Matrix, Vector

from .library import LibraryMissingError, is_sherd_error, sherd, vocabulary_items

AXIS_POINT = "sherd_axis_point"
AXIS_DIRECTION = "sherd_axis_direction"
AXIS_SOURCE = "sherd_axis_source"
#: A declined sherd's best guess (the axis the automatic orientation found but does not
#: trust, world coordinates) and what speaks against it.
BEST_GUESS_POINT = "sherd_best_guess_point"
BEST_GUESS_DIRECTION = "sherd_best_guess_direction"
BEST_GUESS_AGAINST = "sherd_best_guess_against"
#: The axis source of an object placed along its best guess.
BEST_GUESS_SOURCE = "best guess (not trusted: check it)"
PARETO_PLOT = "sherd_pareto_plot_svg"
MEASUREMENT_KEYS = {
    "rim_diameter_mm": "sherd_rim_diameter_mm",
    "rim_diameter_interval_mm": "sherd_rim_diameter_interval_mm",
    "base_diameter_mm": "sherd_base_diameter_mm",
    "base_diameter_interval_mm": "sherd_base_diameter_interval_mm",
    "sector_angle_deg": "sherd_sector_angle_deg",
    "sector_percent": "sherd_sector_percent",
    "height_mm": "sherd_height_mm",
    "wall_thickness_mm": "sherd_wall_thickness_mm",
    "capacity_litres": "sherd_capacity_litres",
    "axis_angle_interval_deg": "sherd_axis_angle_interval_deg",
    "axis_distance_interval_mm": "sherd_axis_distance_interval_mm",
}

#: The defaults of the choices below (the library's defaults), by the library's names.
DEFAULT_CRITERION = "auto"
DEFAULT_SURFACE = "both"
DEFAULT_PARETO_CHOICE = "knee"
DEFAULT_EDGE = "detect"
DEFAULT_CIRCLE_FIT = "taubin"
DEFAULT_PROFILE_FORM = "spline"

#: The choices of the refinement: the library's names and descriptions, read when the
#: add-on loads.
CRITERION_ITEMS = vocabulary_items("CRITERION", DEFAULT_CRITERION)
SURFACE_ITEMS = vocabulary_items("SURFACE", DEFAULT_SURFACE)
PARETO_CHOICE_ITEMS = vocabulary_items("PARETO_CHOICE", DEFAULT_PARETO_CHOICE)
EDGE_ITEMS = vocabulary_items("EDGE", DEFAULT_EDGE)
CIRCLE_FIT_ITEMS = vocabulary_items("CIRCLE_FIT", DEFAULT_CIRCLE_FIT)
PROFILE_FORM_ITEMS = vocabulary_items("PROFILE_METHOD", DEFAULT_PROFILE_FORM)


class InputError(Exception):
    """The selection or the object cannot be used (reported, never raised to Blender)."""


def active_mesh_object(context):
    """The active object if it is a mesh, else :class:`InputError`."""
    obj = context.active_object
    if obj is None:
        raise InputError("no active object")
    if obj.type != 'MESH':
        raise InputError(f"the active object {obj.name!r} is a {obj.type.lower()}, not a mesh")
    return obj


def world_arrays(obj):
    """(positions (n, 3) float64 in world coordinates, triangles (m, 3), selected (n,) bool)
    of a mesh object, read with ``foreach_get`` (the edit-mode state included)."""
    if obj.mode == 'EDIT':
        obj.update_from_editmode()
    data = obj.data
    count = len(data.vertices)
    if count == 0:
        raise InputError(f"the mesh {obj.name!r} has no vertices")
    local = np.empty(count * 3, dtype=np.float32)
    data.vertices.foreach_get("co", local)
    selected = np.empty(count, dtype=bool)
    data.vertices.foreach_get("select", selected)
    data.calc_loop_triangles()
    triangles = np.empty(len(data.loop_triangles) * 3, dtype=np.int32)
    data.loop_triangles.foreach_get("vertices", triangles)
    if len(triangles) == 0:
        raise InputError(f"the mesh {obj.name!r} has no faces")
    matrix = np.array(obj.matrix_world, dtype=np.float64)
    positions = local.reshape(-1, 3).astype(np.float64) @ matrix[:3, :3].T + matrix[:3, 3]
    return positions, triangles.reshape(-1, 3), selected


def library_mesh(obj):
    """The object's mesh as a ``sherd.Mesh`` in world coordinates, and the selection mask."""
    positions, triangles, selected = world_arrays(obj)
    return sherd().Mesh.from_arrays(positions, triangles), selected


def stored_axis(obj):
    """The axis stored on the object by an orientation, else :class:`InputError`."""
    if AXIS_POINT not in obj or AXIS_DIRECTION not in obj:
        raise InputError(f"{obj.name!r} has no axis yet: orient it first")
    return sherd().Axis(list(obj[AXIS_POINT]), list(obj[AXIS_DIRECTION]))


def store_axis(obj, axis, source):
    obj[AXIS_POINT] = [float(v) for v in axis.point]
    obj[AXIS_DIRECTION] = [float(v) for v in axis.direction]
    obj[AXIS_SOURCE] = source


@contextlib.contextmanager
def progress(context, steps):
    """Blender's progress indicator around a long call; yields ``update(step)``."""
    window_manager = context.window_manager
    window_manager.progress_begin(0, steps)
    try:
        yield window_manager.progress_update
    finally:
        window_manager.progress_end()


def with_stored_axis(context, call):
    """Runs ``call(mesh, axis)`` on the active mesh object's world arrays and its stored
    axis, with progress; returns ``(object, mesh, axis, call's result)``."""
    obj = active_mesh_object(context)
    axis = stored_axis(obj)
    with progress(context, 2) as update:
        mesh, _ = library_mesh(obj)
        update(1)
        return obj, mesh, axis, call(mesh, axis)


#: The reports of the Sherd operators, newest last, as ``(types, message)`` (Blender
#: gives scripts no access to an operator's reports; tests and scripts read them here).
REPORTS = []


class SherdOperator:
    """Runs :meth:`run` and turns every expected failure into a report."""

    bl_options = {'REGISTER', 'UNDO'}

    def notify(self, types, message):
        """``report`` that also records in :data:`REPORTS` (RNA's ``report`` cannot be overridden)."""
        REPORTS.append((set(types), message))
        del REPORTS[:-100]
        self.report(types, message)

    @classmethod
    def poll(cls, context):
        # Deliberately permissive: a wrong object is reported by execute, with the reason.
        return context.active_object is not None

    def execute(self, context):
        try:
            return self.run(context)
        except InputError as error:
            self.notify({'ERROR'}, str(error))
        except LibraryMissingError as error:
            self.notify({'ERROR'}, str(error))
        except Exception as error:  # noqa: BLE001 - only sherd's own errors are reported, others re-raised
            if not is_sherd_error(error):
                raise
            self.notify({'ERROR'}, f"sherd: {error}")
        return {'CANCELLED'}


def keep_best_guess(obj, guess):
    """Stores a declined orientation's best guess on the object (``sherd_best_guess_*``),
    or removes an earlier one when there is none; returns what to tell the user."""
    if guess is None:
        forget_best_guess(obj)
        return ""
    obj[BEST_GUESS_POINT] = [float(v) for v in guess.axis.point]
    obj[BEST_GUESS_DIRECTION] = [float(v) for v in guess.axis.direction]
    obj[BEST_GUESS_AGAINST] = guess.against
    return ". Its best guess, not trusted, is kept: Use best guess places the object along it"


def forget_best_guess(obj):
    for key in (BEST_GUESS_POINT, BEST_GUESS_DIRECTION, BEST_GUESS_AGAINST):
        if key in obj:
            del obj[key]


def _finish_orientation(operator, obj, orientation, source, offer=""):
    if not orientation.oriented:
        what = "sense uncertain (check which way is up)" if orientation.sense_uncertain else "needs manual orientation"
        operator.notify({'WARNING'}, f"{what}: {orientation.reason}{offer}")
        return {'CANCELLED'}
    forget_best_guess(obj)
    store_axis(obj, orientation.axis, source)
    obj["sherd_angle_uncertainty_deg"] = float(orientation.angle_uncertainty_deg)
    uncertainty = orientation.angle_uncertainty_deg
    known = f", uncertainty {uncertainty:.2f} deg" if math.isfinite(uncertainty) else ""
    operator.notify({'INFO'}, f"oriented ({source}){known}")
    return {'FINISHED'}


class SHERD_OT_orient_automatic(SherdOperator, bpy.types.Operator):
    """Find the rotation axis from the surface normals (the automatic method)"""

    bl_idname = "sherd.orient_automatic"
    bl_label = "Orient"

    def run(self, context):
        obj = active_mesh_object(context)
        with progress(context, 2) as update:
            mesh, _ = library_mesh(obj)
            update(1)
            orientation = sherd().orient_automatic(mesh)
        # A declined sherd's axis is kept as its best guess, for Use best guess.
        offer = keep_best_guess(obj, orientation.best_guess)
        # Declined, or up and down not told apart: three points on a wheel rill settle both.
        if not orientation.oriented and _select_rill_points(obj, mesh, orientation.axis):
            what = "sense uncertain (check which way is up)" if orientation.sense_uncertain else "needs manual orientation"
            self.notify({'WARNING'}, f"{what}: {orientation.reason}. Three vertices on its "
                        f"longest wheel rill are now selected: check them in Edit Mode, then Orient from 3 vertices{offer}")
            return {'CANCELLED'}
        return _finish_orientation(self, obj, orientation, "automatic", offer)


def _select_rill_points(obj, mesh, declined_axis):
    """Selects the vertices of ``obj`` nearest to the three points the library suggests on
    the sherd's longest wheel rill under the axis the orientation declined (what the
    pipeline's ``manual_points_on_rill`` gives, world coordinates); False, selection
    untouched, when it traced no rill."""
    points = sherd().points_on_longest_rill(mesh, declined_axis)
    if points is None:
        return False
    positions = mesh.positions
    nearest = [int(np.argmin(((positions - np.asarray(p, dtype=np.float64)) ** 2).sum(axis=1))) for p in points]
    editing = obj.mode == 'EDIT'
    if editing:
        bpy.ops.object.mode_set(mode='OBJECT')
    data = obj.data
    selection = np.zeros(len(data.vertices), dtype=bool)
    selection[nearest] = True
    data.vertices.foreach_set("select", selection)
    data.edges.foreach_set("select", np.zeros(len(data.edges), dtype=bool))
    data.polygons.foreach_set("select", np.zeros(len(data.polygons), dtype=bool))
    data.update()
    if editing:
        bpy.ops.object.mode_set(mode='EDIT')
    return True


class SHERD_OT_orient_three_points(SherdOperator, bpy.types.Operator):
    """Find the axis from three vertices selected in Edit Mode on one horizontal feature
    (rim edge, groove, base edge)"""

    bl_idname = "sherd.orient_three_points"
    bl_label = "Orient from 3 vertices"

    def run(self, context):
        obj = active_mesh_object(context)
        with progress(context, 2) as update:
            mesh, selected = library_mesh(obj)
            count = int(selected.sum())
            if count != 3:
                raise InputError(f"select exactly 3 vertices in Edit Mode ({count} selected)")
            update(1)
            points = mesh.positions[selected]
            orientation = sherd().orient_from_three_points(mesh, points)
        return _finish_orientation(self, obj, orientation, "three points")


class SHERD_OT_refine(SherdOperator, bpy.types.Operator):
    """Refine the stored axis with the chosen criterion and surface (and, for the Pareto
    criterion, the solution taken, its sections' limits and circle fit; for the profile
    criterion, its form; for the tangent plane, its edge and epsilon)"""

    bl_idname = "sherd.refine"
    bl_label = "Refine"

    criterion: bpy.props.EnumProperty(name="Criterion", items=CRITERION_ITEMS, default=DEFAULT_CRITERION)
    surface: bpy.props.EnumProperty(name="Surface", items=SURFACE_ITEMS, default=DEFAULT_SURFACE)
    pareto_choice: bpy.props.EnumProperty(name="Pareto solution", items=PARETO_CHOICE_ITEMS, default=DEFAULT_PARETO_CHOICE)
    pareto_mean_count: bpy.props.IntProperty(name="Best averaged", default=2, min=1, max=100)
    edge: bpy.props.EnumProperty(name="Edge", items=EDGE_ITEMS, default=DEFAULT_EDGE)
    tangent_tolerance_mm: bpy.props.FloatProperty(name="Epsilon (mm)", default=3.0, min=0.01, max=100.0)
    pareto_min_points: bpy.props.IntProperty(name="Fewest points", default=10, min=3, max=100000)
    pareto_min_arc_deg: bpy.props.FloatProperty(name="Smallest arc (deg)", default=3.0, min=0.0, max=360.0)
    circle_fit: bpy.props.EnumProperty(name="Circle fit", items=CIRCLE_FIT_ITEMS, default=DEFAULT_CIRCLE_FIT)
    profile_form: bpy.props.EnumProperty(name="Profile", items=PROFILE_FORM_ITEMS, default=DEFAULT_PROFILE_FORM)
    profile_knot_spacing_mm: bpy.props.FloatProperty(name="Knots (mm)", default=1.5, min=0.1, max=1000.0)
    profile_degree: bpy.props.IntProperty(name="Degree", default=6, min=1, max=20)
    profile_sections: bpy.props.IntProperty(name="Vertical sections", default=12, min=2, max=1000)

    def run(self, context):
        choice = (self.pareto_choice, self.pareto_mean_count) if self.pareto_choice == "mean_of_best" else self.pareto_choice
        profile_parameter = {"spline": self.profile_knot_spacing_mm, "polynomial": self.profile_degree,
                             "reference": self.profile_sections}[self.profile_form]
        options = dict(criterion=self.criterion, surface=self.surface, pareto_choice=choice, edge=self.edge,
                       tangent_tolerance_mm=self.tangent_tolerance_mm,
                       pareto_section_limits=(self.pareto_min_points, self.pareto_min_arc_deg),
                       circle_fit=self.circle_fit, profile_method=(self.profile_form, profile_parameter))
        obj, _, _, refinement = with_stored_axis(context, lambda mesh, axis: sherd().refine(mesh, axis, **options))
        store_axis(obj, refinement.axis, f"refined ({refinement.criterion}, {refinement.surface})")
        obj["sherd_refine_residual_mm"] = float(refinement.residual_mm)
        obj["sherd_refine_tilt_deg"] = float(refinement.tilt_deg)
        obj["sherd_pareto_point_count"] = len(refinement.pareto_front)
        # Each point: tilt about x and y (deg), centre dispersion and circle residual (mm^2).
        obj["sherd_pareto_front"] = refinement.pareto_front.tolist()
        # The front drawn by the library, kept for Save Pareto plot (a few kB).
        if refinement.pareto_plot_svg:
            obj[PARETO_PLOT] = refinement.pareto_plot_svg
        elif PARETO_PLOT in obj:
            del obj[PARETO_PLOT]
        summary = f"refined: tilt {refinement.tilt_deg:.2f} deg, residual {refinement.residual_mm:.3f} mm"
        if refinement.flagged:
            # Kept and stored (the best guess); the measurements' intervals say how far off.
            self.notify({'WARNING'}, f"{summary}; {refinement.report.get('flag_reason')}: Measure gives the intervals")
        else:
            self.notify({'INFO'}, summary)
        return {'FINISHED'}


def _is_number(value):
    return isinstance(value, (int, float)) and math.isfinite(value)


class SHERD_OT_measure(SherdOperator, bpy.types.Operator):
    """Measure the oriented sherd: rim and base diameters with their intervals, sector
    angle and share of the circumference, height, wall thickness, capacity, and how far
    the axis may be off (stored as custom properties)"""

    bl_idname = "sherd.measure"
    bl_label = "Measure"

    def run(self, context):
        obj, _, _, measurements = with_stored_axis(context, lambda mesh, axis: sherd().measure(mesh, axis))
        for field, key in MEASUREMENT_KEYS.items():
            value = getattr(measurements, field)
            # A figure the fragment does not determine (NaN) is removed, not stored as a number.
            if isinstance(value, tuple):
                value = [float(v) for v in value]
                known = all(_is_number(v) for v in value)
            else:
                value = float(value)
                known = _is_number(value)
            if known:
                obj[key] = value
            elif key in obj:
                del obj[key]
        if measurements.axis_uncertain:
            doubts = "; ".join(measurements.details.get("axis_doubts", []))
            self.notify({'WARNING'}, f"measured; the axis is uncertain: {doubts}: check the axis before using these figures")
        else:
            self.notify({'INFO'}, "measured")
        return {'FINISHED'}


class SHERD_OT_apply_orientation(SherdOperator, bpy.types.Operator):
    """Move the object so its axis is on Z, rim up (the object's transform; the mesh
    data are unchanged)"""

    bl_idname = "sherd.apply_orientation"
    bl_label = "Apply orientation"

    def run(self, context):
        obj = active_mesh_object(context)
        apply_orientation(obj, stored_axis(obj))
        return {'FINISHED'}


def apply_orientation(obj, axis):
    """Moves ``obj`` so that ``axis`` (world coordinates) is on Z, rim up, and stores the
    moved axis with the object's axis source."""
    mesh, _ = library_mesh(obj)
    transform = mesh.oriented_transform(axis)
    obj.matrix_world = Matrix(transform.tolist()) @ obj.matrix_world
    rotation, translation = transform[:3, :3], transform[:3, 3]
    moved = sherd().Axis(rotation @ axis.point + translation, rotation @ axis.direction)
    store_axis(obj, moved, obj.get(AXIS_SOURCE, "unknown"))


class SHERD_OT_use_best_guess(SherdOperator, bpy.types.Operator):
    """Place the object along the best guess Orient kept for a sherd it declined (axis on
    Z, rim up as the guess points): not trusted, check it; three vertices orient the
    sherd properly"""

    bl_idname = "sherd.use_best_guess"
    bl_label = "Use best guess"

    def run(self, context):
        obj = active_mesh_object(context)
        if BEST_GUESS_POINT not in obj or BEST_GUESS_DIRECTION not in obj:
            raise InputError(f"{obj.name!r} has no best guess: Orient keeps one when it declines a sherd")
        guess = sherd().Axis(list(obj[BEST_GUESS_POINT]), list(obj[BEST_GUESS_DIRECTION]))
        against = obj.get(BEST_GUESS_AGAINST, "")
        # The guess becomes the stored axis, flagged as one by its source, and is used up:
        # after the move its world coordinates no longer hold.
        store_axis(obj, guess, BEST_GUESS_SOURCE)
        forget_best_guess(obj)
        apply_orientation(obj, guess)
        self.notify({'WARNING'}, f"placed along the best guess, not trusted (against it: {against}): check it, "
                    "turn it over if the rim is down, or orient from 3 vertices")
        return {'FINISHED'}


class SHERD_OT_add_axis_empty(SherdOperator, bpy.types.Operator):
    """Add an arrow Empty on the stored axis (base to rim), keeping the object as it is"""

    bl_idname = "sherd.add_axis_empty"
    bl_label = "Add axis Empty"

    def run(self, context):
        obj = active_mesh_object(context)
        axis = stored_axis(obj)
        positions, _, _ = world_arrays(obj)
        heights = (positions - axis.point) @ axis.direction
        empty = bpy.data.objects.new(f"{obj.name} axis", None)
        empty.empty_display_type = 'SINGLE_ARROW'
        base = Vector(axis.point) + Vector(axis.direction) * float(heights.min())
        empty.location = base
        empty.rotation_mode = 'QUATERNION'
        empty.rotation_quaternion = Vector(axis.direction).to_track_quat('Z', 'Y')
        empty.empty_display_size = max(float(heights.max() - heights.min()), 1e-6) * 1.5
        context.collection.objects.link(empty)
        return {'FINISHED'}


#: The library's default styles (``sherd draw``'s), placement and section fill.
DEFAULT_STYLES = {"light", "occlusion"}
DEFAULT_PLACEMENT = "beside"
DEFAULT_SECTION_FILL = "black"

#: The drawing's choices: the library's names and descriptions. Where the views stand
#: (placement), how the section is filled (section_fill), the measurements written under
#: the drawing (annotations; ``sherd draw --annotations``).
STYLE_ITEMS = vocabulary_items("STYLE", *sorted(DEFAULT_STYLES))
PLACEMENT_ITEMS = vocabulary_items("PLACEMENT", DEFAULT_PLACEMENT)
SECTION_FILL_ITEMS = vocabulary_items("SECTION_FILL", DEFAULT_SECTION_FILL)
ANNOTATION_ITEMS = vocabulary_items("ANNOTATION")

#: The drawing's layout choices, as the Draw operator and the panel's settings name them
#: (the panel's carry a "drawing_" prefix).
LAYOUT_SETTINGS = ("placement", "section_fill", "interior_view", "prolongation", "annotations", "title",
                   "section_angle_auto", "section_angle_rad")


def show_image(context, path):
    """Loads a PNG and shows it in an Image Editor of the current screen, if one is open."""
    image = bpy.data.images.load(path, check_existing=False)
    screen = context.screen
    for area in (screen.areas if screen is not None else ()):
        if area.type == 'IMAGE_EDITOR':
            area.spaces.active.image = image
            break
    return image


class SHERD_OT_draw(SherdOperator, bpy.types.Operator):
    """Write the archaeological drawing of the oriented sherd (SVG, EPS, PDF or PNG by
    the file's extension); a PNG is opened in the Image Editor"""

    bl_idname = "sherd.draw"
    bl_label = "Draw"

    filepath: bpy.props.StringProperty(name="File", subtype='FILE_PATH', default="//sherd.svg")
    style: bpy.props.EnumProperty(name="Style", items=STYLE_ITEMS, options={'ENUM_FLAG'},
                                  default=DEFAULT_STYLES)
    scale_denominator: bpy.props.IntProperty(name="Scale 1:", default=1, min=1, max=100)
    dpi: bpy.props.FloatProperty(name="DPI", default=300.0, min=10.0, max=2400.0)
    placement: bpy.props.EnumProperty(name="Placement", items=PLACEMENT_ITEMS, default=DEFAULT_PLACEMENT)
    section_fill: bpy.props.EnumProperty(name="Section fill", items=SECTION_FILL_ITEMS, default=DEFAULT_SECTION_FILL)
    interior_view: bpy.props.BoolProperty(name="Interior view", default=True,
                                          description="Draw the interior view between the section and the axis")
    prolongation: bpy.props.BoolProperty(name="Prolongation", default=True,
                                         description="Prolong the outer profile, dashed, to the full diameter")
    annotations: bpy.props.EnumProperty(name="Annotations", items=ANNOTATION_ITEMS, options={'ENUM_FLAG'}, default=set(),
                                        description="Measurements written under the drawing")
    title: bpy.props.StringProperty(name="Title", default="", description="A title (inventory number...)")
    section_angle_auto: bpy.props.BoolProperty(name="Most informative section", default=True,
                                               description="Cut the most informative profile; off: at Section angle")
    section_angle_rad: bpy.props.FloatProperty(name="Section angle", subtype='ANGLE', default=0.0,
                                               min=-math.pi, max=math.pi,
                                               description="The section's angle about the axis from the fragment's centroid")

    def run(self, context):
        obj = active_mesh_object(context)
        axis = stored_axis(obj)
        path = bpy.path.abspath(self.filepath)
        if not path or path.startswith("//"):
            raise InputError("save the .blend file first or give an absolute path for the drawing")
        if not self.style:
            raise InputError("choose at least one drawing style")
        with progress(context, 3) as update:
            mesh, _ = library_mesh(obj)
            update(1)
            drawing = sherd().Drawing(mesh, axis, style=sorted(self.style),
                                      scale_denominator=self.scale_denominator, dpi=self.dpi,
                                      placement=self.placement, section_fill=self.section_fill,
                                      interior_view=self.interior_view, prolongation=self.prolongation,
                                      annotations=sorted(self.annotations),
                                      title=self.title or None,
                                      section_angle_rad=None if self.section_angle_auto else self.section_angle_rad)
            update(2)
            drawing.write(path)
        if path.lower().endswith(".png"):
            show_image(context, path)
        obj["sherd_drawing_path"] = path
        self.notify({'INFO'}, f"drawing written to {path}")
        return {'FINISHED'}


class SHERD_OT_save_pareto_plot(SherdOperator, bpy.types.Operator):
    """Save the last Pareto refinement's front as an SVG plot (centre dispersion against
    circle residual, the chosen solution circled), to read it as the paper does"""

    bl_idname = "sherd.save_pareto_plot"
    bl_label = "Save Pareto plot"

    filepath: bpy.props.StringProperty(name="File", subtype='FILE_PATH', default="//pareto_front.svg")

    def invoke(self, context, event):
        # From the panel's button: ask where, as Blender's exporters do.
        context.window_manager.fileselect_add(self)
        return {'RUNNING_MODAL'}

    def run(self, context):
        obj = active_mesh_object(context)
        if PARETO_PLOT not in obj:
            raise InputError(f"{obj.name!r} has no Pareto front: refine it with the Pareto criterion first")
        path = bpy.path.abspath(self.filepath)
        if not path or path.startswith("//"):
            raise InputError("save the .blend file first or give an absolute path for the plot")
        # Written beside and renamed, so that a failure leaves no half-written file.
        folder = os.path.dirname(os.path.abspath(path))
        with tempfile.NamedTemporaryFile("w", encoding="utf-8", dir=folder, suffix=".svg.part", delete=False) as part:
            part.write(obj[PARETO_PLOT])
        os.replace(part.name, path)
        self.notify({'INFO'}, f"Pareto plot written to {path}")
        return {'FINISHED'}


DEFAULT_REGULARITY = "ideal_vessel"
REGULARITY_ITEMS = vocabulary_items("REGULARITY", DEFAULT_REGULARITY)
#: The colour attribute the regularity map writes, and the float attribute of its values.
REGULARITY_COLORS = "Sherd regularity"
REGULARITY_VALUES = "sherd_regularity_mm"


class SHERD_OT_reconstruct(SherdOperator, bpy.types.Operator):
    """Add the vessel reconstructed by revolving the sherd's profile about the stored axis
    as a new mesh object, placed with the sherd"""

    bl_idname = "sherd.reconstruct"
    bl_label = "Reconstruct vessel"

    segments: bpy.props.IntProperty(name="Segments", description="Steps of the revolution around the axis",
                                    default=180, min=3, max=3600)

    def run(self, context):
        obj, mesh, axis, vessel = with_stored_axis(
            context, lambda mesh, axis: sherd().reconstruct(mesh, axis, segments=self.segments))
        # The library gives the vessel in the oriented frame of the world positions.
        to_oriented = mesh.oriented_transform(axis)
        data = bpy.data.meshes.new(f"{obj.name} vessel")
        data.from_pydata(vessel.positions.tolist(), [], vessel.triangles.tolist())
        data.update()
        reconstruction = bpy.data.objects.new(f"{obj.name} vessel", data)
        reconstruction.matrix_world = Matrix(np.linalg.inv(to_oriented).tolist())
        context.collection.objects.link(reconstruction)
        obj["sherd_reconstruction"] = reconstruction.name
        self.notify({'INFO'}, f"reconstruction {reconstruction.name!r}: {len(data.vertices)} vertices")
        return {'FINISHED'}


def show_vertex_colors(context):
    """Switches the solid shading of the open 3D Viewports to the colour attribute."""
    screen = context.screen
    for area in (screen.areas if screen is not None else ()):
        if area.type == 'VIEW_3D':
            area.spaces.active.shading.color_type = 'VERTEX'


class SHERD_OT_regularity(SherdOperator, bpy.types.Operator):
    """Paint the regularity map on the sherd as vertex colours (attribute "Sherd
    regularity"; the values in mm as the attribute "sherd_regularity_mm")"""

    bl_idname = "sherd.regularity"
    bl_label = "Regularity colours"

    kind: bpy.props.EnumProperty(name="Map", items=REGULARITY_ITEMS, default=DEFAULT_REGULARITY)

    def run(self, context):
        obj, _, _, regularity = with_stored_axis(context, lambda mesh, axis: sherd().regularity(mesh, axis, self.kind))
        editing = obj.mode == 'EDIT'
        if editing:
            # Attributes written in Edit Mode would be overwritten by the edit mesh.
            bpy.ops.object.mode_set(mode='OBJECT')
        data = obj.data
        for name in (REGULARITY_COLORS, REGULARITY_VALUES):
            if name in data.attributes:
                data.attributes.remove(data.attributes[name])
        colors = data.color_attributes.new(REGULARITY_COLORS, 'BYTE_COLOR', 'POINT')
        colors.data.foreach_set("color_srgb", (regularity.colors.astype(np.float32) / 255.0).ravel())
        data.color_attributes.active_color = colors
        values = data.attributes.new(REGULARITY_VALUES, 'FLOAT', 'POINT')
        values.data.foreach_set("value", regularity.values)
        data.update()
        if editing:
            bpy.ops.object.mode_set(mode='EDIT')
        obj["sherd_regularity_kind"] = self.kind
        obj["sherd_regularity_range_mm"] = [float(v) for v in regularity.value_range]
        show_vertex_colors(context)
        low, high = regularity.value_range
        self.notify({'INFO'}, f"regularity ({self.kind}): {low:.2f} to {high:.2f} mm")
        return {'FINISHED'}


classes = (SHERD_OT_reconstruct, SHERD_OT_regularity, SHERD_OT_draw, SHERD_OT_orient_automatic, SHERD_OT_orient_three_points, SHERD_OT_refine, SHERD_OT_measure,
           SHERD_OT_apply_orientation, SHERD_OT_use_best_guess, SHERD_OT_add_axis_empty, SHERD_OT_save_pareto_plot)
