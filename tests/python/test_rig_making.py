"""myoshell.rig and myoshell.fit_rig against `myoshell rig` and `myoshell fit-rig`: the same files
byte for byte, the same figures, the same messages for bad arguments."""
import json

import numpy as np
import pytest

import myoshell

# tests/cli/rig_test.cpp's map: mirror pairs, a jaw made of the lower-lip depressors, a corrective
# (mouthClose on jawOpen) and an unreachable eye rotation.
MAP = {"format": "myoshell-retarget-map", "version": 1, "model": "anatomical", "shapes": [
    {"name": "eyeLookInLeft", "reachable": False, "reason": "eye rotation"},
    {"name": "jawOpen", "activations": {"depressor_labii_inferioris_left": 0.5, "depressor_labii_inferioris_right": 0.5}},
    {"name": "mouthClose", "corrective_of": "jawOpen", "activations": {"zygomaticus_major_left": 0.1}},
    {"name": "mouthSmile_L", "activations": {"zygomaticus_major_left": 0.8}},
    {"name": "mouthSmile_R", "activations": {"zygomaticus_major_right": 0.8}},
    {"name": "browDownLeft", "activations": {"corrugator_supercilii_left": 0.7}}]}


@pytest.fixture(scope="module")
def made(cli, cache_dir, tmp_path_factory):
    """The map's rig made by the command line and by Python, in one folder."""
    folder = tmp_path_factory.mktemp("rig")
    (folder / "map.json").write_text(json.dumps(MAP))
    report = json.loads(cli("rig", "--head", "default", "--map", folder / "map.json", "--out", folder / "cli.glb",
                            "--cache", cache_dir, "--json").stdout)
    python = myoshell.rig(folder / "map.json", head="default", cache=cache_dir, out=folder / "python.glb")
    return folder, report, python


def test_rig_equals_cli(made):
    folder, report, python = made
    assert (folder / "python.glb").read_bytes() == (folder / "cli.glb").read_bytes()
    assert python["shapes_made"] == report["shapes_made"] == 5
    n = report["vertices"]
    assert python["vertices"] == n and python["head"] == report["head"]
    assert python["deltas"].shape == (52, n, 3) and python["deltas"].dtype == np.float64
    for mine, theirs in zip(python["shapes"], report["shapes"], strict=True):
        assert mine == theirs  # name, mapped, largest displacement and its vertex: the same doubles
    # The arrays are the file's shapes (written as float32 metres, read back in cm).
    back = myoshell.read_rig(folder / "python.glb")
    assert back.shape_names == python["shape_names"]
    k = python["shape_names"].index("mouthSmileLeft")
    assert np.abs(back.delta("mouthSmileLeft") - python["deltas"][k]).max() < 1e-5
    assert np.abs(python["deltas"][k]).max() > 0.05  # cm: the smile moves
    assert not python["deltas"][python["shape_names"].index("cheekPuff")].any()  # unmapped: zero


def test_rig_without_out_returns_the_same_arrays(made, cache_dir):
    folder, _, python = made
    again = myoshell.rig(str(folder / "map.json"), cache=str(cache_dir))
    assert again["out"] is None
    assert np.array_equal(again["deltas"], python["deltas"])


def test_fit_rig_equals_cli(made, cli, cache_dir):
    folder, _, _ = made
    report = json.loads(cli("fit-rig", folder / "cli.glb", "--head", "default", "--lambda", "0", "--out",
                            folder / "cli_map.json", "--cache", cache_dir, "--json").stdout)
    rig = myoshell.read_rig(folder / "cli.glb")
    python = myoshell.fit_rig(rig, head="default", sparsity=0, cache=cache_dir, out=folder / "python_map.json")
    assert (folder / "python_map.json").read_bytes() == (folder / "cli_map.json").read_bytes()
    assert python["map"] == (folder / "cli_map.json").read_text()  # the file is the map's text
    assert python["median_cosine"] == report["median_cosine"] and python["median_rms_mm"] == report["median_rms_mm"]
    assert python["skipped"] == report["skipped"]
    keys = ("name", "reachable", "reason", "sources", "cosine", "magnitude_ratio", "rms_mm", "max_mm",
            "compared_vertices", "activations", "jaw")
    for mine, theirs in zip(python["shapes"], report["shapes"], strict=True):
        for key in keys:
            assert mine[key] == theirs[key], (mine["name"], key)
        assert mine["corrective_of"] == theirs.get("corrective_of")
        assert python["activations"][mine["name"]] == theirs["activations"]
    # No sparsity, a physics-made rig: the map's activations come back.
    assert abs(python["activations"]["mouthSmileLeft"]["zygomaticus_major_left"] - 0.8) < 1e-3
    smile = next(s for s in python["shapes"] if s["name"] == "mouthSmileLeft")
    assert smile["target"].shape == smile["displacement"].shape == (rig.vertex_count, 3)


def cli_error(cli, *args):
    result = cli(*args, check=False)
    assert result.returncode == 2, result.stderr
    return result.stderr


def test_bad_arguments_as_the_cli(made, cli, tmp_path):
    folder, _, _ = made
    the_map = folder / "map.json"
    cases = [
        (lambda: myoshell.rig(the_map, out=tmp_path / "rig.obj"),
         ("rig", "--map", the_map, "--out", tmp_path / "rig.obj"),
         "--out: a rig is written as a glTF binary; give a file name ending in .glb"),
        (lambda: myoshell.rig(the_map, out=tmp_path / "nowhere" / "rig.glb"),
         ("rig", "--map", the_map, "--out", tmp_path / "nowhere" / "rig.glb"), "--out: no such folder"),
        (lambda: myoshell.fit_rig(folder / "cli.glb", head="default", sparsity=-1),
         ("fit-rig", folder / "cli.glb", "--head", "default", "--lambda", "-1"), "--lambda: '-1' is not a number ≥ 0"),
        (lambda: myoshell.fit_rig(tmp_path / "missing.glb", head="default"),
         ("fit-rig", tmp_path / "missing.glb", "--head", "default"), "missing.glb"),
    ]
    for call, args, expected in cases:
        with pytest.raises(myoshell.InputError) as python:
            call()
        assert expected in str(python.value)
        assert str(python.value) in cli_error(cli, *args)

    face_map = tmp_path / "face_map.json"
    face_map.write_text(json.dumps({"format": "myoshell-retarget-map", "version": 1, "shapes": [
        {"name": "mouthShrugLower", "activations": {"mentalis_left": 1}}]}))
    with pytest.raises(myoshell.InputError) as python:
        myoshell.rig(face_map, library="builtin")
    assert str(python.value).endswith("the map uses the whole face's muscles (mentalis_left, …): give --library face")
    assert str(python.value) in cli_error(cli, "rig", "--map", face_map, "--library", "builtin", "--out", tmp_path / "rig.glb")
    assert not (tmp_path / "rig.glb").exists()


def test_threads_change_nothing(made, cache_dir):
    folder, _, _ = made
    rig = myoshell.read_rig(folder / "cli.glb")
    assert myoshell.threads() == 1  # the module's default
    one = myoshell.fit_rig(rig, head="default", cache=cache_dir)
    myoshell.set_threads(2)
    try:
        assert myoshell.threads() == 2
        two = myoshell.fit_rig(rig, head="default", cache=cache_dir)
    finally:
        myoshell.set_threads(1)
    assert one["map"] == two["map"]
    assert [s["rms_mm"] for s in one["shapes"]] == [s["rms_mm"] for s in two["shapes"]]
    with pytest.raises(myoshell.InputError):
        myoshell.set_threads(-1)
