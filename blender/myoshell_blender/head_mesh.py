"""A Blender mesh as the module's head, and the module's positions back on the mesh.

The module works in cm in its head's frame: y up, the face towards +z (the built-in head, and OBJ
heads as they are usually written). The head is the mesh as it stands in the scene: its local
coordinates through the object's world matrix, in the scene's metres, with Blender's z up turned to
the head's y up the way Blender's OBJ importer and exporter turn them (forward −Z, up Y): head
(x, y, z) = 100 · (x, z, −y) of the world position in metres. So an OBJ imported with Blender's
defaults (which in 3.4 keeps the file's coordinates in the mesh and puts the turn and
`global_scale` on the object) is written back in its own coordinates. Displacements come back
through the inverse of the same linear map, into the mesh's local coordinates, where shape keys
live. Vertex order is kept: row i is mesh vertex i.
"""

import os

import numpy as np

# World (Blender: z up, front view along +y) to the head's axes (y up, the face towards +z).
_AXES = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]])


class HeadError(ValueError):
    """A mesh that cannot be a head; its message is the report."""


class Placement:
    """The affine map from the mesh's local coordinates to the head's cm: head = L · local + t."""

    def __init__(self, obj, scene):
        world = np.array(obj.matrix_world, dtype=np.float64)
        units = scene.unit_settings
        metres = units.scale_length if units.system != 'NONE' else 1.0
        self.linear = 100.0 * metres * _AXES @ world[:3, :3]
        self.offset = 100.0 * metres * _AXES @ world[:3, 3]
        if abs(np.linalg.det(self.linear)) < 1e-12:
            raise HeadError("%s: the object's scale flattens it (scale %s); fix its transform"
                            % (obj.name, tuple(round(v, 6) for v in obj.scale)))
        self.inverse = np.linalg.inv(self.linear)

    def to_head(self, local):
        """Mesh-local coordinates (n, 3) to the head's cm."""
        return local @ self.linear.T + self.offset

    def displacement_to_local(self, delta_cm):
        """A displacement in the head's cm (…, 3) to mesh-local coordinates."""
        return np.asarray(delta_cm, dtype=np.float64) @ self.inverse.T


def basis_coordinates(mesh):
    """(n, 3) float64: the mesh's rest shape (its reference shape key when it has keys)."""
    n = len(mesh.vertices)
    co = np.empty(n * 3, dtype=np.float32)
    keys = mesh.shape_keys
    if keys is not None and keys.reference_key is not None:
        keys.reference_key.data.foreach_get("co", co)
    else:
        mesh.vertices.foreach_get("co", co)
    return co.reshape(n, 3).astype(np.float64)


def triangles(mesh):
    mesh.calc_loop_triangles()
    m = len(mesh.loop_triangles)
    if m == 0:
        raise HeadError("%s: the mesh has no faces" % mesh.name)
    tri = np.empty(m * 3, dtype=np.int32)
    mesh.loop_triangles.foreach_get("vertices", tri)
    return tri.reshape(m, 3)


def write_obj(path, obj, scene):
    """Writes the object's mesh as an OBJ in cm (vertices in the mesh's order, faces as triangles)
    and returns (its Placement, the rest shape in local coordinates)."""
    if obj is None or obj.type != 'MESH':
        raise HeadError("select a mesh object as the head")
    mesh = obj.data
    if len(mesh.vertices) < 4:
        raise HeadError("%s: %d vertices is no head" % (obj.name, len(mesh.vertices)))
    placement = Placement(obj, scene)
    local = basis_coordinates(mesh)
    head = placement.to_head(local)
    tri = triangles(mesh) + 1
    with open(path, "w", encoding="utf-8") as f:
        f.write("# %s from Blender (myoshell add-on): %d vertices, cm\n" % (obj.name, len(head)))
        # %.17g: the doubles the module reads are exactly these.
        f.write("".join("v %.17g %.17g %.17g\n" % tuple(p) for p in head))
        f.write("".join("f %d %d %d\n" % tuple(t) for t in tri))
    return placement, local


def landmark_file(obj, settings):
    """The landmark file for this object: the panel's field, else the built-in head's file for a
    mesh "Add the built-in head" made (still its 6990 vertices), else None: the module finds them
    (automatic_landmarks)."""
    from . import module
    path = settings.landmarks.strip()
    if path:
        import bpy
        path = bpy.path.abspath(path)
        if not os.path.isfile(path):
            raise HeadError("landmark file %s: no such file" % path)
        return path
    if obj.get("myoshell_head") == "default" and len(obj.data.vertices) == obj.get("myoshell_vertices", -1):
        return module.DEFAULT_LANDMARKS
    return None


def automatic_landmarks(m, obj_path, cache):
    """The landmarks of the head written to obj_path found by the module, as every command finds
    them for an OBJ without --landmarks (docs/heads.md): kept in the cache folder, keyed on the
    file's bytes, so the same mesh is searched once."""
    return m.find_landmarks(obj_path, units="cm", cache=cache)["path"]
