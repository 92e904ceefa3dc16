"""The sidebar panel (3D view, N, tab "Myoshell"), its settings and the add-on's preferences."""

import bpy
from bpy.props import EnumProperty, IntProperty, PointerProperty, StringProperty

from . import module
from .operators import INPUTS


class MyoshellSettings(bpy.types.PropertyGroup):
    landmarks: StringProperty(
        name="Landmarks", subtype='FILE_PATH',
        description="The head's landmark file (docs/heads.md); not needed for the built-in head")
    performance: StringProperty(
        name="Performance", subtype='FILE_PATH',
        description="OpenFace CSV, Live Link Face CSV or MediaPipe JSON Lines")
    input: EnumProperty(name="Input", items=INPUTS, default='AUTO')


class MyoshellPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    module_path: StringProperty(
        name="Module folder", subtype='DIR_PATH',
        description="A folder holding a myoshell package built for this Blender's Python "
                    "(tried before the one the zip carries)")
    cache_dir: StringProperty(
        name="Basis cache", subtype='DIR_PATH',
        description="Where faces' bases are kept between builds (default $MYOSHELL_CACHE or ~/.cache/myoshell)")
    threads: IntProperty(name="Threads", default=0, min=0, max=256,
                         description="Threads for a face's build (0: every core)")

    def draw(self, context):
        col = self.layout.column()
        col.prop(self, "module_path")
        col.prop(self, "cache_dir")
        col.prop(self, "threads")
        if module.error():
            col.label(text=module.error(), icon='ERROR')


class VIEW3D_PT_myoshell(bpy.types.Panel):
    bl_label = "Myoshell"
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = "Myoshell"

    def draw(self, context):
        settings = context.scene.myoshell
        obj = context.active_object
        layout = self.layout

        box = layout.box()
        box.label(text="Head", icon='USER')
        if obj is not None and obj.type == 'MESH':
            box.label(text=obj.name, icon='MESH_DATA')
            builtin = obj.get("myoshell_head") == "default"
            box.label(text="%d vertices%s" % (len(obj.data.vertices), ", built-in head" if builtin else ""))
        else:
            box.label(text="Select a mesh as the head", icon='INFO')
        box.label(text="Landmark file:")
        box.prop(settings, "landmarks", text="")
        box.operator("myoshell.add_head", icon='ADD')

        box = layout.box()
        box.label(text="ARKit shape keys", icon='SHAPEKEY_DATA')
        box.operator("myoshell.make_shape_keys", icon='MOD_PHYSICS')

        box = layout.box()
        box.label(text="Performance", icon='ACTION')
        box.prop(settings, "performance", text="")
        box.prop(settings, "input", text="")
        op = box.operator("myoshell.import_performance", icon='IMPORT')
        op.filepath = settings.performance
        op.input = settings.input

        box = layout.box()
        box.label(text="Muscles", icon='HIDE_OFF')
        from . import muscles
        head = muscles.head_of(obj)
        shown = head is not None and muscles.overlay_of(head) is not None
        box.operator("myoshell.show_muscles", text="Hide Muscles" if shown else "Show Muscles",
                     icon='HIDE_ON' if shown else 'HIDE_OFF')

        if module.error():
            layout.label(text="Module not loaded (see the preferences)", icon='ERROR')


CLASSES = (MyoshellSettings, MyoshellPreferences, VIEW3D_PT_myoshell)


def register_properties():
    bpy.types.Scene.myoshell = PointerProperty(type=MyoshellSettings)


def unregister_properties():
    del bpy.types.Scene.myoshell
