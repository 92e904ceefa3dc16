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
    with pytest.raises(myoshell.InputError, match="landmarks"):
        myoshell.load_head(str(ict / "head_skin.obj"))
