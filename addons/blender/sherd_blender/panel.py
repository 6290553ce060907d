"""The "Sherd" tab in the 3D View sidebar (N panel)."""

import math

import bpy

from . import operators


class SherdSettings(bpy.types.PropertyGroup):
    """The panel's choices, kept with the scene."""

    criterion: bpy.props.EnumProperty(name="Criterion", items=operators.CRITERION_ITEMS, default=operators.DEFAULT_CRITERION)
    surface: bpy.props.EnumProperty(name="Surface", items=operators.SURFACE_ITEMS, default=operators.DEFAULT_SURFACE)
    pareto_choice: bpy.props.EnumProperty(name="Solution", items=operators.PARETO_CHOICE_ITEMS, default=operators.DEFAULT_PARETO_CHOICE)
    pareto_mean_count: bpy.props.IntProperty(name="Best averaged", default=2, min=1, max=100)
    edge: bpy.props.EnumProperty(name="Edge", items=operators.EDGE_ITEMS, default=operators.DEFAULT_EDGE)
    tangent_tolerance_mm: bpy.props.FloatProperty(name="Epsilon (mm)", default=3.0, min=0.01, max=100.0)
    pareto_min_points: bpy.props.IntProperty(name="Fewest points", default=10, min=3, max=100000)
    pareto_min_arc_deg: bpy.props.FloatProperty(name="Smallest arc (deg)", default=3.0, min=0.0, max=360.0)
    circle_fit: bpy.props.EnumProperty(name="Circle fit", items=operators.CIRCLE_FIT_ITEMS, default=operators.DEFAULT_CIRCLE_FIT)
    profile_form: bpy.props.EnumProperty(name="Profile", items=operators.PROFILE_FORM_ITEMS, default=operators.DEFAULT_PROFILE_FORM)
    profile_knot_spacing_mm: bpy.props.FloatProperty(name="Knots (mm)", default=1.5, min=0.1, max=1000.0)
    profile_degree: bpy.props.IntProperty(name="Degree", default=6, min=1, max=20)
    profile_sections: bpy.props.IntProperty(name="Vertical sections", default=12, min=2, max=1000)
    drawing_path: bpy.props.StringProperty(name="File", subtype='FILE_PATH', default="//sherd.svg")
    drawing_style: bpy.props.EnumProperty(name="Style", items=operators.STYLE_ITEMS, options={'ENUM_FLAG'},
                                          default=operators.DEFAULT_STYLES)
    drawing_scale_denominator: bpy.props.IntProperty(name="Scale 1:", default=1, min=1, max=100)
    drawing_dpi: bpy.props.FloatProperty(name="DPI", default=300.0, min=10.0, max=2400.0)
    drawing_placement: bpy.props.EnumProperty(name="Placement", items=operators.PLACEMENT_ITEMS, default=operators.DEFAULT_PLACEMENT)
    drawing_section_fill: bpy.props.EnumProperty(name="Section fill", items=operators.SECTION_FILL_ITEMS,
                                                 default=operators.DEFAULT_SECTION_FILL)
    drawing_interior_view: bpy.props.BoolProperty(name="Interior view", default=True)
    drawing_prolongation: bpy.props.BoolProperty(name="Prolongation", default=True)
    drawing_annotations: bpy.props.EnumProperty(name="Annotations", items=operators.ANNOTATION_ITEMS,
                                                options={'ENUM_FLAG'}, default=set())
    drawing_title: bpy.props.StringProperty(name="Title", default="")
    drawing_section_angle_auto: bpy.props.BoolProperty(name="Most informative section", default=True)
    drawing_section_angle_rad: bpy.props.FloatProperty(name="Section angle", subtype='ANGLE', default=0.0,
                                                       min=-math.pi, max=math.pi)
    reconstruction_segments: bpy.props.IntProperty(name="Segments", default=180, min=3, max=3600)
    regularity_kind: bpy.props.EnumProperty(name="Map", items=operators.REGULARITY_ITEMS, default=operators.DEFAULT_REGULARITY)


#: Points of the Pareto front listed in the panel (all are in the custom property).
PARETO_ROWS = 6

#: The settings the Refine button passes on to its operator.
REFINE_SETTINGS = ("criterion", "surface", "pareto_choice", "pareto_mean_count", "edge", "tangent_tolerance_mm",
                   "pareto_min_points", "pareto_min_arc_deg", "circle_fit", "profile_form", "profile_knot_spacing_mm",
                   "profile_degree", "profile_sections")

#: The setting of each profile form's one parameter.
PROFILE_PARAMETERS = {"spline": "profile_knot_spacing_mm", "polynomial": "profile_degree", "reference": "profile_sections"}


def _row(layout, label, value, unit, label_share=0.5):
    # The sidebar is narrow: rows whose values are long (intervals) give their labels less.
    row = layout.split(factor=label_share)
    row.label(text=label)
    row.label(text=f"{value} {unit}".strip())


class SHERD_PT_panel(bpy.types.Panel):
    """Orient, refine and measure the active mesh object"""

    bl_idname = "SHERD_PT_panel"
    bl_label = "Sherd"
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = "Sherd"

    def draw(self, context):
        layout = self.layout
        obj = context.active_object
        if obj is None or obj.type != 'MESH':
            layout.label(text="Select a mesh object", icon='INFO')
            return
        settings = context.scene.sherd

        column = layout.column(align=True)
        column.label(text="Orientation")
        column.operator(operators.SHERD_OT_orient_automatic.bl_idname)
        column.operator(operators.SHERD_OT_orient_three_points.bl_idname)
        if operators.BEST_GUESS_POINT in obj:
            # A declined sherd: its best guess, offered as what it is.
            column.operator(operators.SHERD_OT_use_best_guess.bl_idname, icon='ERROR')

        # The sidebar is narrow: one value per row, choices without their labels in a row.
        box = layout.box()
        box.label(text="Refinement: criterion, surface")
        row = box.row(align=True)
        row.prop(settings, "criterion", text="")
        row.prop(settings, "surface", text="")
        # The paper's parameters of the criterion chosen, and only those.
        if settings.criterion == "pareto":
            box.prop(settings, "pareto_choice")
            if settings.pareto_choice == "mean_of_best":
                box.prop(settings, "pareto_mean_count")
            box.prop(settings, "pareto_min_points")
            box.prop(settings, "pareto_min_arc_deg")
            box.prop(settings, "circle_fit")
        if settings.criterion == "profile":
            row = box.row(align=True)
            row.prop(settings, "profile_form", text="")
            row.prop(settings, PROFILE_PARAMETERS[settings.profile_form])
        if settings.criterion in ("tangent", "auto"):
            row = box.row(align=True)
            row.prop(settings, "edge", text="")
            row.prop(settings, "tangent_tolerance_mm", text="ε mm")
        refine = box.operator(operators.SHERD_OT_refine.bl_idname)
        for name in REFINE_SETTINGS:
            setattr(refine, name, getattr(settings, name))
        if "sherd_refine_residual_mm" in obj:
            _row(box, "Residual", f"{obj['sherd_refine_residual_mm']:.3f}", "mm")
            _row(box, "Tilt", f"{obj['sherd_refine_tilt_deg']:.2f}", "deg")
            front = obj.get("sherd_pareto_front", [])
            if len(front):
                _row(box, "Pareto front", f"{len(front)}", "points")
                # The trade-off along the front: each point's two costs, the first few.
                column = box.column(align=True)
                column.label(text="dispersion / residual, mm²")
                for *_, dispersion, residual in list(front)[:PARETO_ROWS]:
                    column.label(text=f"{dispersion:.4f} / {residual:.4f}")
                if len(front) > PARETO_ROWS:
                    column.label(text=f"... {len(front) - PARETO_ROWS} more (sherd_pareto_front)")
                if operators.PARETO_PLOT in obj:
                    box.operator(operators.SHERD_OT_save_pareto_plot.bl_idname)

        column = layout.column(align=True)
        column.operator(operators.SHERD_OT_apply_orientation.bl_idname)
        column.operator(operators.SHERD_OT_add_axis_empty.bl_idname)

        box = layout.box()
        box.operator(operators.SHERD_OT_measure.bl_idname)
        if operators.AXIS_SOURCE in obj:
            box.label(text=f"Axis: {obj[operators.AXIS_SOURCE]}")
        keys = operators.MEASUREMENT_KEYS
        for edge in ("rim", "base"):
            if keys[f"{edge}_diameter_mm"] in obj:
                _row(box, f"{edge.capitalize()} diameter", f"{obj[keys[f'{edge}_diameter_mm']]:.1f}", "mm")
                low, high = obj.get(keys[f"{edge}_diameter_interval_mm"], (math.nan, math.nan))
                _row(box, "   95%", f"{low:.1f}–{high:.1f}", "mm", label_share=0.3)
        if keys["sector_angle_deg"] in obj:
            _row(box, "Sector", f"{obj[keys['sector_angle_deg']]:.1f}", "deg")
        if keys["sector_percent"] in obj:
            _row(box, "Preserved", f"{obj[keys['sector_percent']]:.1f}", "%")
        if keys["height_mm"] in obj:
            _row(box, "Height", f"{obj[keys['height_mm']]:.1f}", "mm")
        if keys["wall_thickness_mm"] in obj:
            _row(box, "Wall", f"{obj[keys['wall_thickness_mm']]:.1f}", "mm")
        if keys["capacity_litres"] in obj:
            _row(box, "Capacity", f"{obj[keys['capacity_litres']]:.3f}", "l")
        # The upper ends of the 95% intervals of the axis's error (the lower ends are 0).
        if keys["axis_angle_interval_deg"] in obj and keys["axis_distance_interval_mm"] in obj:
            angle = obj[keys["axis_angle_interval_deg"]][1]
            distance = obj[keys["axis_distance_interval_mm"]][1]
            _row(box, "Axis within", f"{angle:.1f}° / {distance:.1f}", "mm", label_share=0.42)

        box = layout.box()
        box.label(text="Drawing")
        box.grid_flow(row_major=True, columns=2, align=True).prop(settings, "drawing_style", expand=True)
        box.prop(settings, "drawing_scale_denominator")
        box.prop(settings, "drawing_dpi")
        box.prop(settings, "drawing_placement")
        box.prop(settings, "drawing_section_fill")
        box.prop(settings, "drawing_interior_view")
        box.prop(settings, "drawing_prolongation")
        box.label(text="Annotations")
        box.grid_flow(row_major=True, columns=2, align=True).prop(settings, "drawing_annotations", expand=True)
        box.prop(settings, "drawing_title")
        box.prop(settings, "drawing_section_angle_auto")
        if not settings.drawing_section_angle_auto:
            box.prop(settings, "drawing_section_angle_rad")
        box.prop(settings, "drawing_path", text="")
        draw = box.operator(operators.SHERD_OT_draw.bl_idname)
        draw.filepath = settings.drawing_path
        draw.style = settings.drawing_style
        draw.scale_denominator = settings.drawing_scale_denominator
        draw.dpi = settings.drawing_dpi
        for name in operators.LAYOUT_SETTINGS:
            setattr(draw, name, getattr(settings, f"drawing_{name}"))

        box = layout.box()
        box.label(text="Reconstruction")
        box.prop(settings, "reconstruction_segments")
        box.operator(operators.SHERD_OT_reconstruct.bl_idname).segments = settings.reconstruction_segments
        box.prop(settings, "regularity_kind", text="")
        box.operator(operators.SHERD_OT_regularity.bl_idname).kind = settings.regularity_kind
        if "sherd_regularity_range_mm" in obj:
            low, high = obj["sherd_regularity_range_mm"]
            names = {"ideal_vessel": ("inside", "outside"), "axis_distance": ("near", "far")}
            inner, outer = names.get(obj.get("sherd_regularity_kind"), ("low", "high"))
            _row(box, f"Blue: {inner}", f"{low:.2f}", "mm")
            _row(box, f"Red: {outer}", f"{high:.2f}", "mm")


classes = (SherdSettings, SHERD_PT_panel)
