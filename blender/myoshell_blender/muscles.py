"""The muscles overlay: the library's muscles as the simulator places them on the head (the module's
`muscle_meshes`, the C++ placement every face build uses), one mesh object per muscle in a collection
of their own, parented to the head so they follow it (docs/blender.md, "Muscles overlay")."""

import bpy
import numpy as np

from . import head_mesh

MATERIAL = "Myoshell muscle"
COLOUR = (0.75, 0.12, 0.10, 1.0)  # the viewer's and the renderer's muscle red


def collection_name(head):
    return "Myoshell muscles (%s)" % head.name


def overlay_of(head):
    """The head's overlay collection, or None."""
    return bpy.data.collections.get(collection_name(head))


def head_of(obj):
    """The head an object belongs to: the object itself, or the parent of one of its muscles."""
    if obj is not None and obj.get("myoshell_muscle") and obj.parent is not None:
        return obj.parent
    return obj


def remove(collection):
    for o in list(collection.objects):
        mesh = o.data
        bpy.data.objects.remove(o, do_unlink=True)
        if mesh is not None and mesh.users == 0:
            bpy.data.meshes.remove(mesh)
    bpy.data.collections.remove(collection)


def material():
    mat = bpy.data.materials.get(MATERIAL)
    if mat is None:
        mat = bpy.data.materials.new(MATERIAL)
        mat.diffuse_color = COLOUR  # the viewport's solid colour
        mat.use_nodes = True  # and the renderers'
        bsdf = mat.node_tree.nodes.get("Principled BSDF")
        if bsdf is not None:
            bsdf.inputs["Base Color"].default_value = COLOUR
    return mat


def add(context, head_obj, shells, placement):
    """One mesh object per muscle shell (vertices in the head's cm, its frame) in a new collection,
    parented to head_obj with the shells taken back into the head mesh's local coordinates, so that
    the head's transform places them. Returns the collection."""
    collection = bpy.data.collections.new(collection_name(head_obj))
    context.scene.collection.children.link(collection)
    mat = material()
    for shell in shells:
        local = placement.point_to_local(np.asarray(shell["vertices"], dtype=np.float64))
        triangles = np.asarray(shell["triangles"], dtype=np.int64)
        mesh = bpy.data.meshes.new("muscle " + shell["name"])
        mesh.from_pydata(local.tolist(), [], triangles.tolist())
        mesh.materials.append(mat)
        mesh.update()
        obj = bpy.data.objects.new("muscle " + shell["name"], mesh)
        obj["myoshell_muscle"] = shell["name"]
        obj.parent = head_obj  # identity parent inverse: local = the head's local coordinates
        obj.show_in_front = True  # seen through the skin, as the viewer's --muscles draws them
        obj.hide_select = False
        collection.objects.link(obj)
    head_obj["myoshell_muscles"] = collection.name
    return collection
