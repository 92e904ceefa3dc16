"""The add-on's operators: the panel's buttons, and what scripts call (docs/blender.md)."""

import os
import re
import tempfile

import bpy
import numpy as np
from bpy.props import EnumProperty, StringProperty

from . import head_mesh, jobs, module, muscles

INPUTS = [
    ('AUTO', "From the file", "OpenFace CSV, Live Link Face CSV or MediaPipe JSON Lines, told by the file's header"),
    ('openface', "OpenFace", "OpenFace 2 CSV (action units)"),
    ('livelink', "Live Link Face", "Live Link Face CSV (ARKit weights)"),
    ('mediapipe', "MediaPipe", "MediaPipe Face Landmarker blendshapes, JSON Lines"),
]


def preferences(context):
    addon = context.preferences.addons.get(__package__)
    return addon.preferences if addon is not None else None


def myoshell(context):
    prefs = preferences(context)
    m = module.load(prefs.module_path if prefs else "")
    m.set_threads(prefs.threads if prefs else 0)
    return m


def cache_folder(context):
    """The basis cache the command line uses too (docs/paths.md), unless the preferences name one."""
    prefs = preferences(context)
    if prefs and prefs.cache_dir.strip():
        return bpy.path.abspath(prefs.cache_dir.strip())
    return os.environ.get("MYOSHELL_CACHE") or os.path.join(os.path.expanduser("~"), ".cache", "myoshell")


class HeadInput:
    """The selected mesh written for the module: a temporary OBJ in cm and its landmark file; or,
    when the mesh is the built-in head as the module has it, that head itself (builtin)."""

    def __init__(self, context, m):
        obj = context.active_object
        if obj is None or obj.type != 'MESH':
            raise head_mesh.HeadError("select a mesh object as the head")
        self.object = obj
        self.landmarks = head_mesh.landmark_file(obj, context.scene.myoshell)
        self.folder = tempfile.TemporaryDirectory(prefix="myoshell_blender_")
        self.obj_path = os.path.join(self.folder.name, re.sub(r"[^A-Za-z0-9_.-]", "_", obj.name) + ".obj")
        self.placement, self.rest_local = head_mesh.write_obj(self.obj_path, obj, context.scene)
        self.builtin = head_mesh.is_builtin_head(m, obj, self.placement, self.rest_local, self.landmarks)

    def module_head(self, m, cache):
        """The keywords naming this head to the module (head, units, landmarks). The built-in head,
        unedited, is given as the module's own ("default"): its doubles, not their float32 copies in
        Blender, whose rounding the settle answers by up to 2e-6 m."""
        if self.builtin:
            return {"head": "default"}
        return {"head": self.obj_path, "units": "cm",
                "landmarks": self.landmarks or head_mesh.automatic_landmarks(m, self.obj_path, cache)}

    def close(self):
        self.folder.cleanup()


class MYOSHELL_OT_add_head(bpy.types.Operator):
    """Add the module's built-in head (MediaPipe's canonical mesh, subdivided) as a mesh in metres"""
    bl_idname = "myoshell.add_head"
    bl_label = "Add the Built-in Head"
    bl_options = {'REGISTER', 'UNDO'}

    def execute(self, context):
        try:
            m = myoshell(context)
            with tempfile.TemporaryDirectory(prefix="myoshell_blender_") as tmp:
                path = os.path.join(tmp, "myoshell_head.obj")
                head = m.load_head()
                head.write_obj(path)
                # The OBJ is in cm: Blender's importer turns it z up and scales it to metres on the
                # object (its mesh keeps the file's cm), the inverse of head_mesh.Placement.
                bpy.ops.wm.obj_import(filepath=path, global_scale=0.01)
        except Exception as e:
            self.report({'ERROR'}, jobs.message(e))
            return {'CANCELLED'}
        obj = context.view_layer.objects.active
        if obj is None or obj.type != 'MESH':
            self.report({'ERROR'}, "the built-in head was not imported")
            return {'CANCELLED'}
        obj["myoshell_head"] = "default"
        obj["myoshell_vertices"] = len(obj.data.vertices)
        self.report({'INFO'}, "the built-in head: %d vertices" % len(obj.data.vertices))
        return {'FINISHED'}


class MYOSHELL_OT_make_shape_keys(jobs.ModuleJobOperator, bpy.types.Operator):
    """Make the 52 ARKit shape keys on the selected mesh by physics (as `myoshell rig`)"""
    bl_idname = "myoshell.make_shape_keys"
    bl_label = "Make ARKit Shape Keys"
    bl_options = {'REGISTER', 'UNDO'}

    title = "Myoshell: settling the 52 ARKit shapes"
    expected_seconds = 25.0

    def prepare(self, context):
        m = myoshell(context)
        self.head = HeadInput(context, m)
        head, cache = self.head, cache_folder(context)
        return lambda: m.rig(cache=cache, **head.module_head(m, cache))

    def finish(self, context, result):
        head = self.head
        try:
            obj = head.object
            n = len(obj.data.vertices)
            deltas = np.asarray(result["deltas"])[:, :n, :]
            names = list(result["shape_names"])
            if obj.data.shape_keys is None:
                obj.shape_key_add(name="Basis", from_mix=False)
            blocks = obj.data.shape_keys.key_blocks
            for name in names:  # made again: removed first, so the 52 stay in ARKit's order
                if name in blocks:
                    obj.shape_key_remove(blocks[name])
            for name, delta in zip(names, deltas):
                key = obj.shape_key_add(name=name, from_mix=False)
                co = head.rest_local + head.placement.displacement_to_local(delta)
                key.data.foreach_set("co", co.astype(np.float32).ravel())
                key.value = 0.0
            obj.data.update()
        finally:
            head.close()
        made = result.get("shapes_made", len(names))
        return "%d ARKit shape keys on %s (%d moved by the physics; settled in %.1f s)" % (
            len(names), obj.name, made, result.get("settle_seconds", 0.0))


class MYOSHELL_OT_show_muscles(bpy.types.Operator):
    """Show or hide the muscles on the selected head: the library's muscles as the simulator places
    them, an overlay parented to the head"""
    bl_idname = "myoshell.show_muscles"
    bl_label = "Show Muscles"
    bl_options = {'REGISTER', 'UNDO'}

    action: EnumProperty(name="Action", default='TOGGLE', items=[
        ('TOGGLE', "Toggle", "Show the muscles, or hide them when shown"),
        ('SHOW', "Show", "Show the muscles (placed again when shown)"),
        ('HIDE', "Hide", "Remove the overlay")])

    def execute(self, context):
        try:
            obj = muscles.head_of(context.active_object)
            if obj is None or obj.type != 'MESH':
                raise head_mesh.HeadError("select a mesh object as the head")
            shown = muscles.overlay_of(obj)
            if shown is not None:
                muscles.remove(shown)
            if self.action == 'HIDE' or (self.action == 'TOGGLE' and shown is not None):
                if "myoshell_muscles" in obj:
                    del obj["myoshell_muscles"]
                self.report({'INFO'}, "muscles of %s hidden" % obj.name)
                return {'FINISHED'}
            m = myoshell(context)
            context.view_layer.objects.active = obj
            head = HeadInput(context, m)
            try:
                shells = m.muscle_meshes(m.load_head(**head.module_head(m, cache_folder(context))))
                collection = muscles.add(context, obj, shells, head.placement)
            finally:
                head.close()
        except Exception as e:
            self.report({'ERROR'}, jobs.message(e))
            return {'CANCELLED'}
        self.report({'INFO'}, "%d muscles on %s (collection %s)" % (len(shells), obj.name, collection.name))
        return {'FINISHED'}


def frame_rate(fps):
    """Blender's (fps, fps_base) for a rate: fps / fps_base is the rate."""
    whole = max(1, min(1000, int(round(fps))))
    return whole, whole / fps


class MYOSHELL_OT_import_performance(jobs.ModuleJobOperator, bpy.types.Operator):
    """Play a recorded performance on the selected mesh by physics (as `myoshell drive`) and key
    every frame: one shape key per frame, exact at every frame"""
    bl_idname = "myoshell.import_performance"
    bl_label = "Import Performance"
    bl_options = {'REGISTER', 'UNDO'}

    filepath: StringProperty(name="Performance", subtype='FILE_PATH',
                             description="OpenFace CSV, Live Link Face CSV or MediaPipe JSON Lines")
    filter_glob: StringProperty(default="*.csv;*.jsonl;*.json", options={'HIDDEN'})
    input: EnumProperty(name="Input", items=INPUTS, default='AUTO')

    title = "Myoshell: playing the performance"
    expected_seconds = 30.0

    def invoke(self, context, event):
        if not self.filepath:
            settings = context.scene.myoshell
            self.filepath = settings.performance
            self.input = settings.input
        if not self.filepath:
            context.window_manager.fileselect_add(self)
            return {'RUNNING_MODAL'}
        return super().invoke(context, event)

    def prepare(self, context):
        path = bpy.path.abspath(self.filepath)
        if not path:
            raise head_mesh.HeadError("no performance file given")
        if not os.path.isfile(path):
            raise head_mesh.HeadError("performance %s: no such file" % path)
        m = myoshell(context)
        self.head = HeadInput(context, m)
        head, cache = self.head, cache_folder(context)
        kind = None if self.input == 'AUTO' else self.input
        return lambda: m.drive(path, input=kind, cache=cache, **head.module_head(m, cache))

    def finish(self, context, result):
        try:
            return self._key_frames(context, result)
        finally:
            self.head.close()

    def _key_frames(self, context, result):
        head, obj = self.head, self.head.object
        n = len(obj.data.vertices)
        frames = np.asarray(result["frames"])[:, :n, :]
        rest = np.asarray(result["rest"])[:n]
        count, fps, name = frames.shape[0], float(result["fps"]), str(result["name"])[:40]
        if count == 0:
            raise head_mesh.HeadError("the performance has no frames")
        if obj.data.shape_keys is None:
            obj.shape_key_add(name="Basis", from_mix=False)
        keys = obj.data.shape_keys
        pattern = re.compile(re.escape(name) + r" \d{5}$")
        for block in [b for b in keys.key_blocks if pattern.match(b.name)]:  # the same take again
            obj.shape_key_remove(block)
        wm = context.window_manager
        key_names = []
        for k in range(count):
            key = obj.shape_key_add(name="%s %05d" % (name, k), from_mix=False)
            # The basis plus the frame's displacement: the mesh's own rest stays bit for bit.
            co = head.rest_local + head.placement.displacement_to_local(frames[k] - rest)
            key.data.foreach_set("co", co.astype(np.float32).ravel())
            key.value = 0.0
            key_names.append(key.name)
            if k % 16 == 0:
                wm.progress_update(90 + 9 * k / count)
        # Frame k of the take at scene frame k: its key 1 there and 0 at its neighbours (linear in
        # between), so at every whole frame exactly one key is on and the mesh is that frame.
        if keys.animation_data is None:
            keys.animation_data_create()
        action = bpy.data.actions.new("%s (myoshell)" % name)
        keys.animation_data.action = action
        for k, key_name in enumerate(key_names):
            curve = action.fcurves.new('key_blocks["%s"].value' % key_name)
            points = [(f, 1.0 if f == k else 0.0) for f in (k - 1, k, k + 1) if 0 <= f < count]
            curve.keyframe_points.add(len(points))
            curve.keyframe_points.foreach_set("co", [v for p in points for v in p])
            for p in curve.keyframe_points:
                p.interpolation = 'LINEAR'
            curve.update()
        scene = context.scene
        scene.render.fps, scene.render.fps_base = frame_rate(fps)
        scene.frame_start, scene.frame_end = 0, count - 1
        scene.frame_set(0)
        return "%s: %d frames at %g fps (%.2f s) keyed on %s, scene frames 0-%d" % (
            name, count, fps, count / fps, obj.name, count - 1)


CLASSES = (MYOSHELL_OT_add_head, MYOSHELL_OT_make_shape_keys, MYOSHELL_OT_import_performance, MYOSHELL_OT_show_muscles)
