"""A Blender mesh as the module's head, and the module's positions back on the mesh.

The module works in cm in its head's frame: y up, the face towards +z (the built-in head, and OBJ
heads as they are usually written). The head is the mesh as it stands in the scene: its local
coordinates through the object's world matrix, in the scene's metres, with Blender's z up turned to
the head's y up the way Blender's OBJ importer and exporter turn them (forward −Z, up Y): head
(x, y, z) = 100 · (x, z, −y) of the world position in metres. So an OBJ imported with Blender's
defaults (which in 3.4 keeps the file's coordinates in the mesh and puts the turn and
`global_scale` on the object) is written back in its own coordinates. Displacements come back
through the inverse of the same linear map, into the mesh's local coordinates, where shape keys
live. Vertex order is kept: row i is mesh vertex i; faces are written as they are (polygons()).
"""

import os

import numpy as np

# World (Blender: z up, front view along +y) to the head's axes (y up, the face towards +z).
_AXES = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]])


class HeadError(ValueError):
    """A mesh that cannot be a head; its message is the report."""


def _float32_digits(m):
    """Numbers that went through float32 (Blender's matrices and coordinates) at float32's
    precision: each the double of its shortest decimal at 7 significant digits, and entries below
    1e-6 of the largest made 0. So the importer's global_scale 0.01 (0.0099999998 as float32) times
    100 is 1, and its quarter turn's cos 90° (-4.4e-8) is 0."""
    m = np.asarray(m, dtype=np.float64)
    out = np.array([float("%.7g" % x) for x in m.ravel()]).reshape(m.shape)
    out[np.abs(m) < 1e-6 * max(np.abs(m).max(), 1e-300)] = 0.0
    return out


def shortest_decimals(co32):
    """float32 coordinates as the doubles of their shortest decimals (numpy's unique repr): a mesh
    read from a text file with at most 7 significant digits (ICT's OBJ: 6) gives back the file's
    numbers, so the module reads the head the file is, not one perturbed by float32's rounding (on
    ICT that rounding moved the settled shapes by up to 8e-6 m)."""
    flat = np.asarray(co32, dtype=np.float32).ravel()
    return np.array([float(np.format_float_scientific(v, unique=True)) for v in flat]).reshape(np.shape(co32))


class Placement:
    """The affine map from the mesh's local coordinates to the head's cm: head = L · local + t, L
    and t at float32's precision (_float32_digits): an OBJ imported with Blender's defaults and
    global_scale 0.01 gets L a signed permutation of ones, so its coordinates reach the head exactly."""

    def __init__(self, obj, scene):
        world = np.array(obj.matrix_world, dtype=np.float64)
        units = scene.unit_settings
        metres = units.scale_length if units.system != 'NONE' else 1.0
        self.linear = _float32_digits(100.0 * metres * _AXES @ world[:3, :3])
        self.offset = _float32_digits(100.0 * metres * _AXES @ world[:3, 3])
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

    def point_to_local(self, head_cm):
        """A point in the head's cm (…, 3) to mesh-local coordinates (the inverse of to_head)."""
        return (np.asarray(head_cm, dtype=np.float64) - self.offset) @ self.inverse.T


def basis_coordinates(mesh):
    """(n, 3) float64: the mesh's rest shape (its reference shape key when it has keys)."""
    n = len(mesh.vertices)
    co = np.empty(n * 3, dtype=np.float32)
    keys = mesh.shape_keys
    if keys is not None and keys.reference_key is not None:
        keys.reference_key.data.foreach_get("co", co)
    else:
        mesh.vertices.foreach_get("co", co)
    return shortest_decimals(co.reshape(n, 3))


def polygons(mesh):
    """The mesh's faces as they are (triangles, quads, n-gons), each a list of vertex indices in its
    loop order. Written so, the module triangulates them as it triangulates an OBJ file: a mesh
    imported from an OBJ is that file's head, triangle for triangle. (Blender's own triangles,
    loop_triangles, may cut a quad along the other diagonal: on ICT's quads that moved its shapes by
    up to 3.9 mm.)"""
    m = len(mesh.polygons)
    if m == 0:
        raise HeadError("%s: the mesh has no faces" % mesh.name)
    starts = np.empty(m, dtype=np.int64)
    counts = np.empty(m, dtype=np.int64)
    mesh.polygons.foreach_get("loop_start", starts)
    mesh.polygons.foreach_get("loop_total", counts)
    loops = np.empty(len(mesh.loops), dtype=np.int64)
    mesh.loops.foreach_get("vertex_index", loops)
    return [loops[s:s + c] for s, c in zip(starts, counts)]


def write_obj(path, obj, scene):
    """Writes the object's mesh as an OBJ in cm (vertices in the mesh's order, faces as they are)
    and returns (its Placement, the rest shape in local coordinates)."""
    if obj is None or obj.type != 'MESH':
        raise HeadError("select a mesh object as the head")
    mesh = obj.data
    if len(mesh.vertices) < 4:
        raise HeadError("%s: %d vertices is no head" % (obj.name, len(mesh.vertices)))
    placement = Placement(obj, scene)
    local = basis_coordinates(mesh)
    head = placement.to_head(local)
    faces = polygons(mesh)
    with open(path, "w", encoding="utf-8") as f:
        f.write("# %s from Blender (myoshell add-on): %d vertices, cm\n" % (obj.name, len(head)))
        # Python's repr: the shortest text that reads back as the same double, so the module reads
        # exactly these; for a mesh from an OBJ in cm, the file's own numbers.
        f.write("".join("v %r %r %r\n" % (float(p[0]), float(p[1]), float(p[2])) for p in head))
        f.write("".join("f " + " ".join(str(v + 1) for v in face) + "\n" for face in faces))
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


_builtin = {}


def is_builtin_head(m, obj, placement, rest_local, landmarks):
    """Whether the mesh is the module's built-in head unedited: its triangles, its positions to
    float32's rounding (1e-5 cm), placed as Add the Built-in Head places it, and no landmark file
    other than the built-in head's own."""
    if landmarks and os.path.realpath(landmarks) != os.path.realpath(DEFAULT_LANDMARKS()):
        try:
            with open(landmarks, "rb") as a, open(DEFAULT_LANDMARKS(), "rb") as b:
                if a.read() != b.read():
                    return False
        except OSError:
            return False
    if "rest" not in _builtin:
        head = m.load_head()
        _builtin["rest"], _builtin["triangles"] = head.rest_positions(), head.triangles()
    rest, tri = _builtin["rest"], _builtin["triangles"]
    mesh = obj.data
    if len(mesh.vertices) != len(rest) or len(mesh.polygons) != len(tri):
        return False
    if np.abs(placement.to_head(rest_local) - rest).max() > 1e-5:
        return False
    faces = polygons(mesh)
    if any(len(f) != 3 for f in faces):
        return False
    return np.array_equal(np.array(faces), tri)


def DEFAULT_LANDMARKS():
    from . import module
    return module.DEFAULT_LANDMARKS


def automatic_landmarks(m, obj_path, cache):
    """The landmarks of the head written to obj_path found by the module, as every command finds
    them for an OBJ without --landmarks (docs/heads.md): kept in the cache folder, keyed on the
    file's bytes, so the same mesh is searched once."""
    return m.find_landmarks(obj_path, units="cm", cache=cache)["path"]
