"""Sherd: orient and measure 3D scans of pottery sherds from Blender's sidebar.

The add-on holds no algorithm: it passes the active mesh to the sherd library (its C ABI
through the vendored ``sherd`` Python package) as arrays and shows what comes back. It
installs as a Blender 4.2+ extension (``blender_manifest.toml``) or as a legacy add-on
in Blender 3.x (``bl_info``).
"""

bl_info = {
    "name": "Sherd",
    "author": "sherd developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "3D View > Sidebar > Sherd",
    "description": "Orient, refine, measure, draw and reconstruct scans of archaeological pottery sherds",
    "category": "Mesh",
}

import bpy  # noqa: E402 - bl_info must come first for Blender's add-on scanner

from . import operators, panel  # noqa: E402

_classes = operators.classes + panel.classes


def register():
    for cls in _classes:
        bpy.utils.register_class(cls)
    bpy.types.Scene.sherd = bpy.props.PointerProperty(type=panel.SherdSettings)


def unregister():
    del bpy.types.Scene.sherd
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)
