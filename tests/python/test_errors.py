"""Bad arguments raise InputError (a ValueError) with the command line's message."""
import pytest

import myoshell


def test_exception_classes():
    assert issubclass(myoshell.InputError, ValueError)
    assert issubclass(myoshell.SimulationError, RuntimeError)


def cli_error(cli, *args):
    result = cli(*args, check=False)
    assert result.returncode != 0
    return result.stderr


def test_unknown_muscle_as_the_cli(face, cli, cache_dir):
    with pytest.raises(myoshell.InputError) as python:
        face.pose({"zygomaticus": 0.5})
    message = str(python.value)
    assert message.startswith("unknown muscle 'zygomaticus' (the anatomical model's muscles: frontalis_medial_left,")
    assert message in cli_error(cli, "pose", "--set", "zygomaticus=0.5", "--cache", cache_dir)
    with pytest.raises(myoshell.InputError, match="^unknown muscle 'zygomaticus'"):
        myoshell.Simulator(face).set_activation("zygomaticus", 0.5)


@pytest.mark.parametrize("value", [1.5, -0.25])
def test_activation_out_of_range_as_the_cli(face, cli, cache_dir, value):
    with pytest.raises(myoshell.InputError) as python:
        face.pose({"zygomaticus_major_left": value})
    message = str(python.value)
    assert message == f"zygomaticus_major_left={value}: an activation must lie in [0, 1] under the anatomical model"
    assert message in cli_error(cli, "pose", f"--set=zygomaticus_major_left={value}", "--cache", cache_dir)
    sim = myoshell.Simulator(face)
    with pytest.raises(myoshell.InputError, match="an activation must lie in"):
        sim.set_activation("zygomaticus_major_left", value)
    with pytest.raises(myoshell.InputError):
        sim.set_activations({"zygomaticus_major_right": 0.5, "zygomaticus_major_left": value})
    assert sim.activation("zygomaticus_major_right") == 0.0  # all checked before any is set


def test_bad_head_arguments_as_the_cli(cli):
    with pytest.raises(myoshell.InputError) as python:
        myoshell.load_head("no_such_head.obj")
    assert str(python.value) in cli_error(cli, "pose", "--head", "no_such_head.obj")
    with pytest.raises(myoshell.InputError, match="unknown length unit 'inch'"):
        myoshell.load_head("no_such_head.obj", landmarks="x.json", units="inch")


def test_bad_shapes_and_ranges(face, tmp_path):
    with pytest.raises(myoshell.InputError, match=r"expected an \(n, 3\) array, got shape \(4, 2\)"):
        face.write_obj(str(tmp_path / "x.obj"), [[0.0, 0.0]] * 4)
    with pytest.raises(myoshell.InputError, match="one per vertex"):
        face.fit([[0.0, 0.0, 0.0]])
    with pytest.raises(myoshell.InputError, match="no such folder"):
        face.write_obj(str(tmp_path / "missing" / "x.obj"), face.rest_positions())
    with pytest.raises(myoshell.InputError, match="jaw"):
        face.pose(jaw=(60, 0, 0))
    with pytest.raises(myoshell.InputError, match="align"):
        face.fit(face.rest_positions(), align="affine")
    with pytest.raises(myoshell.InputError):
        myoshell.Simulator(face).step(-1)
    with pytest.raises(myoshell.InputError, match="is not a number"):
        face.pose({"zygomaticus_major_left": "much"})
