"""myoshell.muscle_meshes and Face.muscle_meshes: the library's muscles as the simulator places them
on a head (the Blender add-on's muscles overlay draws these)."""
import numpy as np
import pytest

import myoshell


def nearest_skin_distance(points, skin, chunk=512):
    """Each point's distance to the nearest skin vertex (cm)."""
    out = np.empty(len(points))
    for i in range(0, len(points), chunk):
        d = np.linalg.norm(points[i:i + chunk, None, :] - skin[None, :, :], axis=2)
        out[i:i + chunk] = d.min(axis=1)
    return out


@pytest.fixture(scope="module")
def head():
    return myoshell.load_head()


def test_every_muscle_of_the_library_placed_under_the_skin(head):
    shells = myoshell.muscle_meshes(head)
    assert [s["name"] for s in shells] == myoshell.muscle_names("face")
    skin = head.rest_positions()
    farthest = 0.0
    for s in shells:
        v, t = s["vertices"], s["triangles"]
        assert v.dtype == np.float64 and v.ndim == 2 and v.shape[1] == 3 and len(v) >= 4, s["name"]
        assert t.dtype == np.int32 and t.min() >= 0 and t.max() < len(v), s["name"]
        assert s["kind"] in ("linear", "ring") and s["rest_length"] > 0.5, s["name"]
        d = nearest_skin_distance(v, skin)
        assert np.median(d) < 1.0, s["name"]  # cm: the bulk of each muscle just under the skin
        farthest = max(farthest, d.max())
    # Under the skin, not floating off it: every node within 1.5 cm of the skin's nearest vertex (the
    # deepest, the buccinators under the cheeks, reach 1.22 cm; the built-in head is 21 cm tall). The
    # Blender test asks the same of the overlay.
    assert 0.05 < farthest < 1.5, farthest


def test_the_face_placed_the_same_muscles(face):
    from_face = face.muscle_meshes()
    alone = myoshell.muscle_meshes(face.head)
    assert [s["name"] for s in from_face] == face.muscle_names
    for a, b in zip(from_face, alone):
        assert np.array_equal(a["vertices"], b["vertices"]) and np.array_equal(a["triangles"], b["triangles"]), a["name"]


def test_units_and_selection(head):
    cm = myoshell.muscle_meshes(head, library="builtin", muscles=["zygomaticus_major_left"])
    m = myoshell.muscle_meshes(head, library="builtin", muscles=["zygomaticus_major_left"], units="m")
    assert len(cm) == 1 and cm[0]["name"] == "zygomaticus_major_left"
    assert np.allclose(m[0]["vertices"], 0.01 * cm[0]["vertices"], rtol=0, atol=1e-15)
    assert np.allclose(m[0]["origin"], 0.01 * np.asarray(cm[0]["origin"]), rtol=0, atol=1e-15)
    assert np.array_equal(myoshell.muscle_meshes(head, units="head")[0]["vertices"],
                          myoshell.muscle_meshes(head)[0]["vertices"])  # the built-in head is in cm
    with pytest.raises(myoshell.InputError, match="units: 'inch' is not one of cm, m, mm, head"):
        myoshell.muscle_meshes(head, units="inch")
    with pytest.raises(myoshell.InputError, match="buccinator"):
        myoshell.muscle_meshes(head, muscles=["buccinator"])
