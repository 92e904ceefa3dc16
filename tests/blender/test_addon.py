"""The Blender add-on (blender/, docs/blender.md) in Blender itself, headless:

    blender -b --factory-startup --python-exit-code 1 --python tests/blender/test_addon.py [-- ZIP]

(ctest: blender.addon, label blender, through tests/blender/run_test.sh). Installs and enables the
add-on from the zip `make blender-addon` builds (into $BLENDER_USER_SCRIPTS when set, else from the
zip unpacked into a temporary folder), makes the 52 ARKit shape keys on the built-in head and
compares them with the module's rig, imports a Live Link take and compares Blender's evaluated
vertices with the module's drive frames.

Units: the head's OBJ is in cm and is imported with global_scale 0.01 and Blender's default axes:
Blender 3.4's importer keeps the file's cm in the mesh and puts the scale and the turn to z up on the
object, so in the world the head is in metres, (x, y, z) = 0.01 · (x, −z, y) of the module's cm. The
comparisons are of world positions (the object's matrix applied to the mesh's or shape key's
coordinates) in metres.
"""
import os
import pathlib
import sys
import tempfile
import zipfile

import addon_utils
import bpy
import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
ARGS = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
ZIP = pathlib.Path(ARGS[0] if ARGS else os.environ.get("MYO_BLENDER_ADDON_ZIP", ROOT / "build" / "myoshell-blender.zip"))
TAKE = ROOT / "tests" / "anim" / "performances" / "livelink_take.csv"
LANDMARKS = ROOT / "assets" / "default_head" / "landmarks_multipie68.json"
SHAPE_TOLERANCE_M = 1e-6
FRAME_TOLERANCE_M = 1e-4  # 0.1 mm


def check(condition, what):
    if not condition:
        raise AssertionError(what)
    print("ok:", what)


def to_blender_m(cm):
    """The module's cm to Blender's metres as the OBJ importer (global_scale 0.01) places them."""
    cm = np.asarray(cm, dtype=np.float64)
    return np.stack([cm[..., 0], -cm[..., 2], cm[..., 1]], axis=-1) * 0.01


def coordinates(collection, n, obj):
    """World positions in metres of a mesh's vertices or a shape key's points."""
    co = np.empty(n * 3, dtype=np.float32)
    collection.foreach_get("co", co)
    world = np.array(obj.matrix_world, dtype=np.float64)
    return co.reshape(n, 3).astype(np.float64) @ world[:3, :3].T + world[:3, 3]


def install_addon(tmp):
    if not ZIP.is_file():
        raise AssertionError("%s is missing: build it with `make blender-addon`" % ZIP)
    if os.environ.get("BLENDER_USER_SCRIPTS"):
        bpy.ops.preferences.addon_install(filepath=str(ZIP), overwrite=True)
        print("installed from", ZIP, "into", os.environ["BLENDER_USER_SCRIPTS"])
    else:  # no user folder of ours to install into: the zip's folder, unpacked
        with zipfile.ZipFile(ZIP) as z:
            z.extractall(tmp)
        sys.path.insert(0, tmp)
        print("unpacked", ZIP, "into", tmp)
    addon_utils.modules_refresh()
    bpy.ops.preferences.addon_enable(module="myoshell_blender")
    check("myoshell_blender" in bpy.context.preferences.addons, "the add-on is enabled")
    check(hasattr(bpy.ops.myoshell, "make_shape_keys") and hasattr(bpy.ops.myoshell, "import_performance"),
          "its operators are registered")
    check(np.__dict__.get("bool") is bool, "numpy's np.bool alias is back for Blender 3.4's glTF importer")


def main():
    tmp = tempfile.mkdtemp(prefix="myoshell_blender_test_")
    install_addon(tmp)
    import myoshell  # the module the add-on carries
    check(pathlib.Path(myoshell.__file__).parent.parent.name == "lib", "the module is the zip's: %s" % myoshell.__file__)
    cache = os.environ.get("MYOSHELL_CACHE") or os.path.join(tmp, "cache")
    os.environ["MYOSHELL_CACHE"] = cache  # the add-on's and this test's builds share one basis cache

    # The built-in head through an OBJ, as an artist's mesh arrives.
    head = myoshell.load_head()
    obj_path = os.path.join(tmp, "head.obj")
    head.write_obj(obj_path)
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o)
    bpy.ops.wm.obj_import(filepath=obj_path, global_scale=0.01)
    obj = bpy.context.view_layer.objects.active
    n = head.vertex_count
    check(obj is not None and obj.type == 'MESH' and len(obj.data.vertices) == n, "the head imported: %d vertices" % n)
    rest_m = to_blender_m(head.rest_positions())
    err = np.abs(coordinates(obj.data.vertices, n, obj) - rest_m).max()
    check(err < 1e-7, "Blender kept the head's vertex order (rest within %.1e m)" % err)

    # An error is a Blender report (a RuntimeError for a script), not a traceback of the add-on.
    bpy.context.scene.myoshell.landmarks = os.path.join(tmp, "missing.json")
    try:
        bpy.ops.myoshell.make_shape_keys()
        raise AssertionError("a missing landmark file was accepted")
    except RuntimeError as e:
        check("missing.json" in str(e), "a missing landmark file is reported: %s" % str(e).strip())

    # (2) The 52 ARKit shape keys against the module's rig of the built-in head.
    bpy.context.scene.myoshell.landmarks = str(LANDMARKS)
    check(bpy.ops.myoshell.make_shape_keys() == {'FINISHED'}, "make_shape_keys finished")
    reference = myoshell.rig(cache=cache)
    names = list(reference["shape_names"])
    blocks = obj.data.shape_keys.key_blocks
    check([b.name for b in blocks] == ["Basis"] + names and len(names) == 52,
          "52 shape keys after the basis, in ARKit's order")
    worst, moved = 0.0, 0.0
    for name, delta in zip(names, reference["deltas"]):
        expected = to_blender_m(head.rest_positions() + delta[:n])
        worst = max(worst, np.abs(coordinates(blocks[name].data, n, obj) - expected).max())
        moved = max(moved, np.abs(to_blender_m(delta[:n])).max())
    check(moved > 1e-3, "the shapes move the face (largest %.2f mm)" % (moved * 1e3))
    check(worst < SHAPE_TOLERANCE_M, "the shape keys equal the module's rig within %.1e m (largest %.2e m)"
          % (SHAPE_TOLERANCE_M, worst))

    # (3) A Live Link take: the scene's rate and range, and each frame exact.
    check(bpy.ops.myoshell.import_performance(filepath=str(TAKE)) == {'FINISHED'}, "import_performance finished")
    take = myoshell.drive(str(TAKE), cache=cache)
    frames, fps = take["frames"], take["fps"]
    scene = bpy.context.scene
    check(abs(scene.render.fps / scene.render.fps_base - fps) < 1e-9, "scene at the take's %g fps" % fps)
    check((scene.frame_start, scene.frame_end) == (0, len(frames) - 1),
          "scene frames 0-%d, one per take frame" % (len(frames) - 1))
    duration = (scene.frame_end - scene.frame_start) / (scene.render.fps / scene.render.fps_base)
    check(abs(duration - take["performance"]["duration"]) < 1e-6,
          "last frame at the take's duration, %.4f s" % duration)
    check(len(frames) >= 3, "the take has %d frames" % len(frames))
    for k in range(3):
        scene.frame_set(k)
        evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
        mesh = evaluated.to_mesh()
        got = coordinates(mesh.vertices, n, obj)
        evaluated.to_mesh_clear()
        expected = to_blender_m(frames[k][:n])
        err = np.abs(got - expected).max()
        away = np.abs(expected - rest_m).max()
        check(err < FRAME_TOLERANCE_M, "frame %d: Blender's vertices equal drive's within 0.1 mm (largest %.2e m; "
              "the frame is %.2f mm from rest)" % (k, err, away * 1e3))
    print("test_addon: all checks passed")


main()
