"""Rigs from glTF files, read as `myoshell fit RIG.glb#shape` reads them."""
import numpy as np
import pytest

import myoshell


def test_ict_rig(shared_data, cli):
    path = shared_data / "ict" / "ict_arkit_rig.glb"
    rig = myoshell.read_rig(path)
    n = rig.vertex_count
    assert rig.rest_positions().shape == (n, 3) and rig.triangles().dtype == np.int32
    assert len(rig.shape_names) == 37 and "jawOpen" in rig.shape_names  # ICT names its halves _L, _R
    assert myoshell.load_head(shared_data / "ict").vertex_count == n  # the head the rig was made for
    jaw = rig.shape("jawOpen")
    assert jaw.shape == (n, 3)
    assert np.array_equal(rig.delta("jawOpen"), jaw - rig.rest_positions())
    assert np.abs(rig.delta("jawOpen")).max() > 0.5  # cm: the jaw opens
    with pytest.raises(myoshell.InputError) as python:
        rig.shape("noSuchShape")
    result = cli("fit", f"{path}#noSuchShape", check=False)
    assert result.returncode != 0 and str(python.value) in result.stderr


def test_missing_rig_file(tmp_path):
    with pytest.raises(myoshell.InputError):
        myoshell.read_rig(tmp_path / "none.glb")
