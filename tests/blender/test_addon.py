"""The Blender add-on (blender/, docs/blender.md) in Blender itself, headless:

    blender -b --factory-startup --python-exit-code 1 --python tests/blender/test_addon.py [-- ZIP]

(ctest: blender.addon, label blender, through tests/blender/run_test.sh). Installs and enables the
add-on from the zip `make blender-addon` builds (into $BLENDER_USER_SCRIPTS when set, else from the
zip unpacked into a temporary folder), makes the 52 ARKit shape keys on the built-in head and
compares them with the module's rig, imports a Live Link take and compares Blender's evaluated
vertices with the module's drive frames.

The muscles overlay (show_muscles) is checked here too. test_addon_ict.py makes the same checks on
ICT's head (ctest blender.ict). Units: common.py.
"""
import os
import pathlib
import sys
import tempfile

import bpy
import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import (FRAME_TOLERANCE_M, ROOT, SHAPE_TOLERANCE_M, check, coordinates,  # noqa: E402
                    evaluated_coordinates, import_obj, install_addon, to_blender_m)

TAKE = ROOT / "tests" / "anim" / "performances" / "livelink_take.csv"
LANDMARKS = ROOT / "assets" / "default_head" / "landmarks_multipie68.json"
# A muscle lies under the skin: every node of its shell within this of the skin's nearest vertex
# (the deepest, the buccinators, 12.2 mm; tests/python/test_muscles.py asks the same).
MUSCLE_SKIN_DISTANCE_M = 0.015


def check_muscles(myoshell, head, obj, n):
    """(4) The muscles overlay: the library's muscles as the module places them, parented to the
    head, under its skin; the operator toggles it."""
    import mathutils
    check(bpy.ops.myoshell.show_muscles() == {'FINISHED'}, "show_muscles finished")
    collection = bpy.data.collections.get("Myoshell muscles (%s)" % obj.name)
    check(collection is not None, "the overlay is a collection of its own")
    names = myoshell.muscle_names("face")
    shown = {o["myoshell_muscle"]: o for o in collection.objects}
    check(sorted(shown) == sorted(names), "one object per muscle of the library: %d" % len(names))
    check(all(o.parent is obj for o in shown.values()), "every muscle is parented to the head")
    reference = {s["name"]: s for s in myoshell.muscle_meshes(head)}
    skin = mathutils.kdtree.KDTree(n)
    for i, p in enumerate(to_blender_m(head.rest_positions())):
        skin.insert(p, i)
    skin.balance()
    worst_place, farthest = 0.0, 0.0
    for name, o in shown.items():
        m = len(o.data.vertices)
        got = coordinates(o.data.vertices, m, o)
        worst_place = max(worst_place, np.abs(got - to_blender_m(reference[name]["vertices"])).max())
        farthest = max(farthest, max(skin.find(p)[2] for p in got))
    check(worst_place < 1e-6, "the muscles are where the module places them (largest %.1e m)" % worst_place)
    check(farthest < MUSCLE_SKIN_DISTANCE_M, "every muscle node lies within %.0f mm of the skin (farthest %.1f mm)"
          % (MUSCLE_SKIN_DISTANCE_M * 1e3, farthest * 1e3))
    overlay = collection.name
    bpy.context.view_layer.objects.active = next(iter(shown.values()))  # a muscle picked: its head's overlay
    check(bpy.ops.myoshell.show_muscles() == {'FINISHED'} and bpy.data.collections.get(overlay) is None
          and not any(o.get("myoshell_muscle") for o in bpy.data.objects), "show_muscles again hides them")
    bpy.context.view_layer.objects.active = obj


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
    obj = import_obj(obj_path)
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
        got = evaluated_coordinates(obj, n)
        expected = to_blender_m(frames[k][:n])
        err = np.abs(got - expected).max()
        away = np.abs(expected - rest_m).max()
        check(err < FRAME_TOLERANCE_M, "frame %d: Blender's vertices equal drive's within 0.1 mm (largest %.2e m; "
              "the frame is %.2f mm from rest)" % (k, err, away * 1e3))

    # (4) The muscles overlay.
    check_muscles(myoshell, head, obj, n)
    print("test_addon: all checks passed")


main()
