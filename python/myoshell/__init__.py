"""Myoshell: physically based animation of human faces (docs/python.md).

Lengths are in cm, angles in degrees, activations in [0, 1]; arrays are NumPy copies:
positions float64 (n, 3), triangles int32 (m, 3).

    import myoshell
    face = myoshell.Face(cache="cache")              # the built-in head, the whole face's 40 muscles
    smile = face.pose({"zygomaticus_major_left": 0.8, "zygomaticus_major_right": 0.8})
    face.write_obj("smile.obj", smile)
"""

from ._myoshell import (
    Face,
    Head,
    InputError,
    IoError,
    LiveFace,
    LiveSample,
    LiveSender,
    LiveSource,
    Rig,
    ScenePlayer,
    SimulationError,
    Simulator,
    arkit_names,
    drive,
    find_landmarks,
    fit_rig,
    live_clock,
    load_head,
    muscle_meshes,
    muscle_names,
    read_rig,
    rig,
    set_threads,
    threads,
    write_glb,
    write_obj_sequence,
    write_pc2,
)

__all__ = [
    "Face",
    "Head",
    "InputError",
    "IoError",
    "LiveFace",
    "LiveSample",
    "LiveSender",
    "LiveSource",
    "Rig",
    "ScenePlayer",
    "SimulationError",
    "Simulator",
    "arkit_names",
    "drive",
    "find_landmarks",
    "fit_rig",
    "live_clock",
    "load_head",
    "muscle_meshes",
    "muscle_names",
    "pose",
    "read_rig",
    "rig",
    "set_threads",
    "threads",
    "write_glb",
    "write_obj",
    "write_obj_sequence",
    "write_pc2",
]


def pose(activations=None, head=None, library="face", cache=None, **settings):
    """The settled shape of a face built for this call, as `myoshell pose`: float64 (n, 3), cm.

    head: a Head (default the built-in one); library, cache: as Face(); settings: Face.pose's
    gravity, head_pose, jaw. Build a Face once instead when posing it more than once.
    """
    return Face(head=head, library=library, cache=cache).pose(activations, **settings)


def write_obj(path, head, positions=None):
    """Writes positions (float (n, 3), cm; default the rest shape) as an OBJ of `head` (a Head or a
    Face) in its own unit, as `myoshell pose --out` does."""
    if isinstance(head, Face):
        head = head.head
    head.write_obj(path, positions)
