"""What the Blender tests (test_addon.py, test_addon_ict.py) share: checks, the module's cm to
Blender's metres, world coordinates, and the add-on installed from its zip.

Units: a head's OBJ in cm imported with global_scale 0.01 and Blender's default axes: Blender 3.4's
importer keeps the file's cm in the mesh and puts the scale and the turn to z up on the object, so in
the world the head is in metres, (x, y, z) = 0.01 · (x, −z, y) of the module's cm. The comparisons
are of world positions (the object's matrix applied to the mesh's or shape key's coordinates) in
metres.
"""
import os
import pathlib
import sys
import zipfile

import addon_utils
import bpy
import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
ARGS = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
ZIP = pathlib.Path(ARGS[0] if ARGS else os.environ.get("MYO_BLENDER_ADDON_ZIP", ROOT / "build" / "myoshell-blender.zip"))
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


def evaluated_coordinates(obj, n):
    """World positions in metres of the object's vertices as Blender shows them now (shape keys
    and their animation applied)."""
    evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
    mesh = evaluated.to_mesh()
    got = coordinates(mesh.vertices, n, obj)
    evaluated.to_mesh_clear()
    return got


def import_obj(path):
    """An OBJ in cm imported as an artist imports it (metres, Blender's default axes); the new object."""
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o)
    bpy.ops.wm.obj_import(filepath=str(path), global_scale=0.01)
    return bpy.context.view_layer.objects.active


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
    check(all(hasattr(bpy.ops.myoshell, op) for op in ("make_shape_keys", "import_performance", "show_muscles")),
          "its operators are registered")
    check(np.__dict__.get("bool") is bool, "numpy's np.bool alias is back for Blender 3.4's glTF importer")


def shared_data():
    """The team's data folder with ict/ (as tests/python/conftest.py finds it), or None."""
    candidates = [os.environ.get("MYOSHELL_DATA"),
                  os.environ.get("MYO_SHARED_DIR") and os.path.join(os.environ["MYO_SHARED_DIR"], "data"),
                  str(ROOT.parent / "shared" / "data")]
    for c in candidates:
        if c and os.path.isdir(os.path.join(c, "ict")):
            return pathlib.Path(c)
    return None
