"""The Blender add-on on ICT's head (ctest blender.ict, labels blender and slow), headless:

    blender -b --factory-startup --python-exit-code 1 --python tests/blender/test_addon_ict.py [-- ZIP]

ICT-FaceKit's skin (../shared/data/ict: 11,248 vertices in cm, UV seams), imported as an artist
imports the OBJ. Checks that the add-on's 52 ARKit shape keys equal the GLB `myoshell rig` writes for
that head to 1e-6 m (the head's vertices: the GLB's seam duplicates, appended after them, aside),
and that a take imported by the add-on equals drive's OBJ frames to 0.1 mm at frames 0, 1, 2.
Skipped (exit 77) without the data folder: run_test.sh checks before Blender starts, and so does
this script when run by hand. The basis cache ($MYOSHELL_CACHE, the build's test_cache under ctest)
keeps both faces' bases (the add-on's head went through Blender's float32, so it has its own),
so a second run builds neither.
"""
import glob
import os
import sys
import tempfile
import time

import bpy
import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import (FRAME_TOLERANCE_M, ROOT, SHAPE_TOLERANCE_M, check, coordinates,  # noqa: E402
                    evaluated_coordinates, import_obj, install_addon, shared_data, to_blender_m)

TAKE = ROOT / "tests" / "anim" / "performances" / "livelink_take.csv"


def read_obj_vertices(path):
    rows = [line.split()[1:4] for line in open(path) if line.startswith("v ")]
    return np.array(rows, dtype=np.float64)


def main():
    data = shared_data()
    if data is None:
        print("blender.ict: SKIPPED: the shared data folder (../shared/data with ict/) is absent; set MYOSHELL_DATA")
        sys.exit(77)
    ict = data / "ict"
    head_obj, landmarks = ict / "head_skin.obj", ict / "landmarks_multipie68.json"
    tmp = tempfile.mkdtemp(prefix="myoshell_blender_ict_")
    install_addon(tmp)
    import myoshell
    cache = os.environ.get("MYOSHELL_CACHE") or os.path.join(tmp, "cache")
    os.environ["MYOSHELL_CACHE"] = cache

    head = myoshell.load_head(str(head_obj), landmarks=str(landmarks))
    n = head.vertex_count
    obj = import_obj(head_obj)
    check(obj is not None and len(obj.data.vertices) == n, "ICT's head imported: %d vertices" % n)
    rest_m = to_blender_m(head.rest_positions())
    err = np.abs(coordinates(obj.data.vertices, n, obj) - rest_m).max()
    check(err < 1e-7, "Blender kept ICT's vertex order (rest within %.1e m)" % err)

    # The 52 ARKit shape keys against the GLB `rig` writes for this head.
    bpy.context.scene.myoshell.landmarks = str(landmarks)
    started = time.monotonic()
    check(bpy.ops.myoshell.make_shape_keys() == {'FINISHED'}, "make_shape_keys finished (%.1f s)"
          % (time.monotonic() - started))
    glb = os.path.join(tmp, "ict_rig.glb")
    started = time.monotonic()
    myoshell.rig(head=str(head_obj), landmarks=str(landmarks), cache=cache, out=glb)
    print("the reference rig.glb in %.1f s" % (time.monotonic() - started))
    rig = myoshell.read_rig(glb)
    check(list(rig.shape_names) == list(myoshell.arkit_names()), "the GLB's 52 shapes in ARKit's order")
    blocks = obj.data.shape_keys.key_blocks
    check([b.name for b in blocks] == ["Basis"] + list(rig.shape_names), "52 shape keys after the basis, in ARKit's order")
    base = rig.rest_positions()
    check(base.shape[0] >= n and np.abs(to_blender_m(base[:n]) - rest_m).max() < 1e-7,
          "the GLB's first %d vertices are the head's (%d in the file as read)" % (n, base.shape[0]))
    worst, moved = 0.0, 0.0
    for name in rig.shape_names:
        expected = to_blender_m(rig.shape(name)[:n])
        worst = max(worst, np.abs(coordinates(blocks[name].data, n, obj) - expected).max())
        moved = max(moved, np.abs(to_blender_m(rig.delta(name)[:n])).max())
    check(moved > 1e-3, "the shapes move the face (largest %.2f mm)" % (moved * 1e3))
    check(worst < SHAPE_TOLERANCE_M, "the shape keys equal rig's GLB within %.1e m (largest %.2e m)"
          % (SHAPE_TOLERANCE_M, worst))

    # A take at three frames against drive's OBJ frames (ICT's unit, cm).
    check(bpy.ops.myoshell.import_performance(filepath=str(TAKE)) == {'FINISHED'}, "import_performance finished")
    out = os.path.join(tmp, "drive")
    take = myoshell.drive(str(TAKE), head=str(head_obj), landmarks=str(landmarks), cache=cache, out=out,
                          formats=["obj"])
    files = sorted(glob.glob(os.path.join(out, "obj", "*.obj")))
    scene = bpy.context.scene
    check(abs(scene.render.fps / scene.render.fps_base - take["fps"]) < 1e-9, "scene at the take's %g fps" % take["fps"])
    check(len(files) >= 3 and (scene.frame_start, scene.frame_end) == (0, len(files) - 1),
          "scene frames 0-%d, one per OBJ frame" % (len(files) - 1))
    for k in range(3):
        scene.frame_set(k)
        expected = to_blender_m(read_obj_vertices(files[k]))
        err = np.abs(evaluated_coordinates(obj, n) - expected).max()
        away = np.abs(expected - rest_m).max()
        check(err < FRAME_TOLERANCE_M, "frame %d: Blender's vertices equal drive's OBJ within 0.1 mm (largest %.2e m; "
              "the frame is %.2f mm from rest)" % (k, err, away * 1e3))
    print("test_addon_ict: all checks passed")


main()
