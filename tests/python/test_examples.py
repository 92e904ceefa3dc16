"""The examples in examples/python run, and write what docs/python.md says."""
import os
import subprocess
import sys

import numpy as np

from conftest import SOURCE_TREE, read_obj_vertices


def run_example(name, cwd, cache_dir, *args):
    env = dict(os.environ, MYOSHELL_CACHE=str(cache_dir))
    result = subprocess.run([sys.executable, str(SOURCE_TREE / "examples" / "python" / name), *args], cwd=cwd,
                            env=env, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    return result.stdout


def test_quickstart(face, cache_dir, tmp_path):
    out = run_example("quickstart.py", tmp_path, cache_dir)
    assert "wrote smile.obj" in out
    smile = read_obj_vertices(tmp_path / "smile.obj")
    assert np.array_equal(smile, face.pose({"zygomaticus_major_left": 0.8, "zygomaticus_major_right": 0.8}))


def test_make_dataset(face, cache_dir, tmp_path):
    run_example("make_dataset.py", tmp_path, cache_dir, "--n", "3", "--out", "d.npz")
    data = np.load(tmp_path / "d.npz")
    n, m = face.vertex_count, len(face.muscle_names)
    assert data["activations"].shape == (3, m)
    assert ((data["activations"] >= 0) & (data["activations"] <= 1)).all()
    assert ((data["activations"] > 0).sum(axis=1) >= 1).all()
    assert data["displacements"].shape == (3, n, 3) and data["displacements"].dtype == np.float32
    assert list(data["muscle_names"]) == face.muscle_names
    first = dict(zip(face.muscle_names, data["activations"][0]))
    expected = (face.pose(first) - face.rest_positions()).astype(np.float32)
    assert np.array_equal(data["displacements"][0], expected)
