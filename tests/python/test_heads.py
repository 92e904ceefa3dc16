"""Heads from the shared data folder."""

import numpy as np
import pytest

import myoshell
from conftest import read_obj_vertices


def test_ict_head_folder(shared_data, tmp_path):
    head = myoshell.load_head(str(shared_data / "ict"))
    assert head.name == "head_skin" and head.obj_path.endswith("head_skin.obj")
    rest = head.rest_positions()
    assert rest.shape == (head.vertex_count, 3)
    # Written back in the head's own unit as a copy of its file: the same positions.
    path = tmp_path / "ict.obj"
    head.write_obj(str(path))
    assert np.allclose(read_obj_vertices(path) * {"cm": 1, "mm": 0.1, "m": 100}[head.units], rest)


def test_obj_head_with_landmarks(shared_data):
    ict = shared_data / "ict"
    by_folder = myoshell.load_head(str(ict))
    by_file = myoshell.load_head(str(ict / "head_skin.obj"), landmarks=str(ict / "landmarks_multipie68.json"),
                                 units=by_folder.units)
    assert np.array_equal(by_file.rest_positions(), by_folder.rest_positions())
    assert by_file.landmarks() == by_folder.landmarks()


def test_obj_head_without_landmarks_finds_them(shared_data, tmp_path):
    # As every command does without --landmarks: found, kept in the cache folder, said in a warning;
    # ICT's unit inferred from its size; the named points within the measured accuracy of docs/heads.md
    # (mean 2.6 mm) of ICT's given ones.
    ict = shared_data / "ict"
    given = myoshell.load_head(str(ict))
    with pytest.warns(UserWarning, match="found the landmarks of .* automatically"):
        found = myoshell.load_head(str(ict / "head_skin.obj"), cache=str(tmp_path))
    assert found.units == given.units
    assert np.array_equal(found.rest_positions(), given.rest_positions())
    rest = given.rest_positions()
    named = [n for n in given.landmarks() if n in found.landmarks()]
    distances = [np.linalg.norm(rest[found.landmarks()[n]] - rest[given.landmarks()[n]]) for n in named]
    assert len(named) >= 10
    assert np.mean(distances) <= 0.3, np.mean(distances)  # cm, the 3 mm


def test_find_landmarks_keeps_the_file_in_the_cache_and_reuses_it(tmp_path):
    obj = tmp_path / "head.obj"
    myoshell.load_head().write_obj(str(obj))
    cache = tmp_path / "cache"
    first = myoshell.find_landmarks(obj, cache=str(cache))
    assert first["path"].startswith(str(cache / "landmarks")) and not first["reused"]
    assert (first["units"], first["units_inferred"], first["eyes"], first["mouth"]) == ("cm", True, "open", "open")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cache", "head.obj"]  # nothing beside the OBJ
    again = myoshell.find_landmarks(obj, cache=str(cache))
    assert again["reused"] and again["path"] == first["path"] and again["seconds"] == 0.0
    with pytest.warns(UserWarning, match="using the landmarks of .* found automatically before"):
        head = myoshell.load_head(str(obj), cache=str(cache))
    assert head.landmarks() == myoshell.load_head(str(obj), landmarks=first["path"]).landmarks()
    with pytest.raises(myoshell.InputError, match="unknown length unit"):
        myoshell.find_landmarks(obj, units="inch", cache=str(cache))
