"""Makes docs/blender_panel.png, the README's picture of the add-on: Blender's 3D Viewport
with a synthetic sherd oriented, measured and painted with its regularity map, the
Sherd tab open in the sidebar. Blender draws its UI only with a display, so run it under
Xvfb (after addons/blender/build.sh):

    BLENDER_USER_SCRIPTS=$(mktemp -d) xvfb-run -a -s "-screen 0 1600x1200x24" \
        blender --factory-startup --enable-event-simulate --python addons/blender/screenshot.py

Every figure in the picture is computed by the add-on. Blender 3.x has no API to choose
the sidebar's tab, so the script clicks down the sidebar's tab strip as a user would
(simulated events) until the Sherd panel is drawn.
"""

import math
import sys
from pathlib import Path

import bpy
from mathutils import Euler

ROOT = Path(__file__).resolve().parents[2]
ZIP = ROOT / "target" / "blender" / "sherd_blender.zip"
OUTPUT = ROOT / "docs" / "blender_panel.png"


def setup():
    bpy.context.preferences.view.show_splash = False
    units = bpy.context.scene.unit_settings
    units.system, units.scale_length, units.length_unit = 'METRIC', 0.001, 'MILLIMETERS'
    bpy.ops.preferences.addon_install(filepath=str(ZIP), overwrite=True)
    bpy.ops.preferences.addon_enable(module="sherd_blender")
    import sherd_blender.sherd as sherd

    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    mesh, _, _ = sherd.synthetic_sherd(13, "rim", target_faces=20000)
    data = bpy.data.meshes.new("sherd 13")
    data.from_pydata(mesh.positions.tolist(), [], mesh.triangles.tolist())
    obj = bpy.data.objects.new("sherd 13", data)
    bpy.context.collection.objects.link(obj)
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj
    for operator in (bpy.ops.sherd.orient_automatic, bpy.ops.sherd.refine, bpy.ops.sherd.measure,
                     bpy.ops.sherd.apply_orientation, bpy.ops.sherd.add_axis_empty):
        assert operator() == {'FINISHED'}, operator
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    assert bpy.ops.sherd.reconstruct(segments=36) == {'FINISHED'}
    bpy.data.objects[obj["sherd_reconstruction"]].display_type = 'WIRE'
    for other in bpy.data.objects:
        other.select_set(other == obj)
    bpy.context.scene.sherd.regularity_kind = "axis_distance"


def view_3d():
    window = bpy.context.window_manager.windows[0]
    area = max((a for a in window.screen.areas if a.type == 'VIEW_3D'), key=lambda a: a.width * a.height)
    return window, area


def frame():
    """Once the window is drawn: the regularity colours, the sherd framed, the sidebar open."""
    window, area = view_3d()
    space = area.spaces.active
    space.show_region_ui = True
    region = next(r for r in area.regions if r.type == 'WINDOW')
    sherd_object = bpy.context.view_layer.objects.active
    vessel = bpy.data.objects[sherd_object["sherd_reconstruction"]]
    with bpy.context.temp_override(window=window, area=area, region=region):
        assert bpy.ops.sherd.regularity(kind="axis_distance") == {'FINISHED'}
        space.shading.color_type = 'VERTEX'
        space.overlay.show_floor = space.overlay.show_axis_x = space.overlay.show_axis_y = False
        # From a little above and in front of the sherd (on +x after Apply orientation), the
        # whole vessel in the frame, its wires light on the dark background.
        bpy.context.preferences.themes[0].view_3d.wire = (0.55, 0.55, 0.55)
        space.region_3d.view_rotation = Euler((math.radians(70), 0, math.radians(70))).to_quaternion()
        vessel.select_set(True)
        bpy.ops.view3d.view_selected()
        vessel.select_set(False)
    bpy.app.timers.register(next_tab, first_interval=1.0)


CLICKS = []


def next_tab():
    """Clicks the next point down the tab strip at the sidebar's right edge; the Sherd
    panel's draw records that it was drawn, which ends the search."""
    window, area = view_3d()
    ui = next(r for r in area.regions if r.type == 'UI')
    if DRAWN["sherd"]:
        bpy.app.timers.register(lambda: shoot(window, area), first_interval=1.0)
        return None
    step_px = 12
    y = ui.y + ui.height - 20 - step_px * len(CLICKS)
    if y < ui.y + ui.height // 2:
        print("the Sherd tab was not found")
        sys.exit(1)
    CLICKS.append(y)
    x = ui.x + ui.width - 8
    window.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
    window.event_simulate(type='LEFTMOUSE', value='PRESS', x=x, y=y)
    window.event_simulate(type='LEFTMOUSE', value='RELEASE', x=x, y=y)
    return 0.3


DRAWN = {"sherd": False}


def watch_the_panel():
    """Wraps the Sherd panel's draw to learn when Blender shows it."""
    import sherd_blender.panel as panel
    draw = panel.SHERD_PT_panel.draw

    def recorded(self, context):
        DRAWN["sherd"] = True
        draw(self, context)

    panel.SHERD_PT_panel.draw = recorded


def shoot(window, area):
    OUTPUT.parent.mkdir(exist_ok=True)
    with bpy.context.temp_override(window=window, area=area):
        bpy.ops.screen.screenshot_area(filepath=str(OUTPUT))
    print(f"wrote {OUTPUT}")
    bpy.ops.wm.quit_blender()


def main():
    setup()
    watch_the_panel()
    # The window must exist and be drawn before the view can be framed.
    bpy.app.timers.register(frame, first_interval=2.0)


try:
    main()
except Exception:  # noqa: BLE001 - any failure ends Blender with an error code
    import traceback
    traceback.print_exc()
    sys.exit(1)
