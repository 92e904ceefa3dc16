"""docs/figures/blender_shape_keys.png, rendered by Blender itself without a window (Cycles on the
CPU): the built-in head added by the add-on, its 52 ARKit shape keys made by the add-on, shown four
times side by side: at rest and with jawOpen, eyeBlinkLeft and mouthSmileLeft at 1. Run by
scripts/make_blender_pictures:

    blender -b --factory-startup --python scripts/blender_shape_keys_picture.py -- ZIP OUT.png
"""
import math
import os
import sys

import bpy
from mathutils import Vector

ZIP, OUT = sys.argv[sys.argv.index("--") + 1:][:2]
SHAPES = [("rest", None), ("jawOpen", "jawOpen"), ("eyeBlinkLeft", "eyeBlinkLeft"), ("mouthSmileLeft", "mouthSmileLeft")]
SKIN = (0.62, 0.42, 0.33, 1.0)

bpy.ops.preferences.addon_install(filepath=ZIP, overwrite=True)
bpy.ops.preferences.addon_enable(module="myoshell_blender")
for o in list(bpy.data.objects):
    bpy.data.objects.remove(o)
scene = bpy.context.scene
assert bpy.ops.myoshell.add_head() == {'FINISHED'}
head = bpy.context.view_layer.objects.active
assert bpy.ops.myoshell.make_shape_keys() == {'FINISHED'}

skin = bpy.data.materials.new("skin")
skin.use_nodes = True
bsdf = skin.node_tree.nodes["Principled BSDF"]
bsdf.inputs["Base Color"].default_value = SKIN
bsdf.inputs["Roughness"].default_value = 0.55
head.data.materials.clear()
head.data.materials.append(skin)
for p in head.data.polygons:
    p.use_smooth = True

corners = [head.matrix_world @ Vector(c) for c in head.bound_box]
lo = Vector([min(c[i] for c in corners) for i in range(3)])
hi = Vector([max(c[i] for c in corners) for i in range(3)])
size = hi - lo
step = size.x * 1.15
heads = []
for i, (label, key) in enumerate(SHAPES):
    obj = head if i == 0 else head.copy()
    if i:
        obj.data = head.data.copy()  # its own shape keys' values
        scene.collection.objects.link(obj)
    obj.location.x += i * step
    for block in obj.data.shape_keys.key_blocks[1:]:
        block.value = 0.0
    if key:
        obj.data.shape_keys.key_blocks[key].value = 1.0
    heads.append(obj)
    text = bpy.data.curves.new("label " + label, type='FONT')
    text.body = label
    text.size = size.z * 0.075
    text.align_x = 'CENTER'
    t = bpy.data.objects.new("label " + label, text)
    t.location = (lo.x + size.x / 2 + i * step, lo.y - 0.01, lo.z - size.z * 0.12)
    t.rotation_euler = (math.pi / 2, 0.0, 0.0)  # facing the camera, which looks along +y
    dark = bpy.data.materials.get("label") or bpy.data.materials.new("label")
    dark.diffuse_color = (0.05, 0.05, 0.05, 1.0)
    dark.use_nodes = True
    dark.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.03, 0.03, 0.03, 1.0)
    text.materials.append(dark)
    scene.collection.objects.link(t)

width = step * (len(SHAPES) - 1) + size.x
centre = Vector((lo.x + width / 2, lo.y, lo.z + size.z * 0.43))
camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
camera.data.type = 'ORTHO'
camera.data.ortho_scale = width * 1.06
camera.location = (centre.x, lo.y - 1.0, centre.z)
camera.rotation_euler = (math.pi / 2, 0.0, 0.0)
scene.collection.objects.link(camera)
scene.camera = camera
key = bpy.data.objects.new("key", bpy.data.lights.new("key", type='SUN'))
key.data.energy = 2.2
key.rotation_euler = (math.radians(60), 0.0, math.radians(-25))
scene.collection.objects.link(key)
fill = bpy.data.objects.new("fill", bpy.data.lights.new("fill", type='SUN'))
fill.data.energy = 0.5
fill.rotation_euler = (math.radians(80), 0.0, math.radians(40))
scene.collection.objects.link(fill)
world = bpy.data.worlds.new("world")
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.9, 0.9, 0.92, 1.0)
world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.35
scene.world = world

scene.render.engine = 'CYCLES'
scene.cycles.device = 'CPU'
scene.cycles.samples = 32
scene.cycles.use_denoising = False
scene.render.resolution_x = 1600
scene.render.resolution_y = int(1600 * (size.z * 1.3) / (width * 1.06))
scene.render.resolution_percentage = 100
scene.render.film_transparent = False
scene.view_settings.view_transform = 'Standard'
scene.render.image_settings.file_format = 'PNG'
scene.render.filepath = OUT
bpy.ops.render.render(write_still=True)
print("wrote", OUT, os.path.getsize(OUT), "bytes")
