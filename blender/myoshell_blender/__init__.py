"""Myoshell in Blender: the 52 ARKit shape keys made by physics on a head, and recorded
performances played on it, through the Python module `myoshell` (docs/blender.md)."""

bl_info = {
    "name": "Myoshell",
    "author": "Myoshell",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > Myoshell",
    "description": "Physics-based facial animation: ARKit shape keys and performances on a head",
    "category": "Animation",
}

import bpy

from . import module, operators, panel

_CLASSES = panel.CLASSES + operators.CLASSES


def register():
    module.restore_np_bool()
    for cls in _CLASSES:
        bpy.utils.register_class(cls)
    panel.register_properties()
    try:  # loaded now so that the panel and preferences can say when it cannot be
        module.load(operators.preferences(bpy.context).module_path if operators.preferences(bpy.context) else "")
    except ImportError as e:
        print("myoshell add-on:", e)


def unregister():
    panel.unregister_properties()
    for cls in reversed(_CLASSES):
        bpy.utils.unregister_class(cls)
