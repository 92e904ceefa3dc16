"""myoshell.drive against `myoshell drive`, and the exports (write_glb, write_pc2,
write_obj_sequence) against the files drive writes: byte for byte, frames bit for bit."""
import os
import subprocess
import sys

import numpy as np
import pytest

import myoshell
from conftest import read_obj_vertices


def openface_take(path, frames=9, fps=30.0):
    """A short OpenFace take (intensities already in [0, 1]): a smile rising, a frown, a nod."""
    rows = ["timestamp,pose_Rx,pose_Ry,pose_Rz,AU12_r,AU04_r"]
    for k in range(frames):
        s = k / (frames - 1)
        rows.append(f"{k / fps:.6f},{0.3 * s:.6f},{-0.1 * s:.6f},0.05,{0.9 * s:.6f},{0.4 * (1 - s):.6f}")
    path.write_text("\n".join(rows) + "\n")
    return path


@pytest.fixture(scope="module")
def driven(cli, cache_dir, tmp_path_factory):
    """The take driven by the command line and by Python, every format, the head turned."""
    folder = tmp_path_factory.mktemp("drive")
    take = openface_take(folder / "take.csv")
    cli("drive", take, "--library", "builtin", "--format", "obj,glb,pc2", "--head-motion", "--out", folder / "cli",
        "--cache", cache_dir)
    python = myoshell.drive(take, library="builtin", formats=["obj", "glb", "pc2"], head_motion=True,
                            out=folder / "python", cache=cache_dir)
    return folder, python


def test_drive_writes_the_cli_files(driven):
    folder, python = driven
    frames = python["frames"]
    assert frames.dtype == np.float64 and frames.ndim == 3 and frames.shape[2] == 3
    count = frames.shape[0]
    assert python["name"] == "take" and python["fps"] == pytest.approx(30.0, abs=1e-3)
    assert np.allclose(python["times"], np.arange(count) / python["fps"])
    expected = [f"obj/take_{k:04d}.obj" for k in range(count)] + ["take.glb", "take.pc2"]
    assert python["written"] == expected
    for rel in expected:
        assert (folder / "python" / rel).read_bytes() == (folder / "cli" / rel).read_bytes(), rel
    for k in (0, count // 2, count - 1):  # the OBJ prints round-trip numbers: the frames bit for bit
        assert np.array_equal(read_obj_vertices(folder / "cli" / "obj" / f"take_{k:04d}.obj"), frames[k])
    assert python["performance"]["input"] == "openface" and python["performance"]["frames"] == 9
    assert np.abs(frames[-1] - frames[0]).max() > 0.1  # cm: the face moved (and turned)


def test_without_out_the_frames_are_the_same(driven, cache_dir):
    folder, python = driven
    # The builtin library lacks some of AU4's muscles: drive's warning, as a UserWarning.
    with pytest.warns(UserWarning, match="muscles this model does not have, left out: depressor_supercilii_left"):
        again = myoshell.drive(str(folder / "take.csv"), library="builtin", head_motion=True, cache=str(cache_dir))
    assert again["written"] == []
    assert np.array_equal(again["frames"], python["frames"])
    upright = myoshell.drive(folder / "take.csv", library="builtin", cache=cache_dir)["frames"]
    assert not np.array_equal(upright[-1], python["frames"][-1])  # head_motion turns the exported frames


def test_exports_of_python_frames_equal_drives(driven, tmp_path):
    folder, python = driven
    head = myoshell.load_head()
    frames = python["frames"]
    report = myoshell.write_glb(tmp_path / "take.glb", head, frames, fps=python["fps"], name=python["name"])
    assert (tmp_path / "take.glb").read_bytes() == (folder / "cli" / "take.glb").read_bytes()
    # What the GLB holds: every frame within 0.05 mm, a key per frame, at the take's rate.
    assert report == python["glb"]
    assert report["frames"] == len(frames) and report["fps"] == python["fps"]
    assert 1 <= report["targets"] <= len(frames) and report["max_error_mm"] <= 0.05 and report["within_tolerance"]
    assert report["tolerance_mm"] == 0.05
    # glb_tolerance (--glb-tolerance): a looser bound, fewer targets, every frame still within it.
    loose = myoshell.write_glb(tmp_path / "loose.glb", head, frames, fps=python["fps"], glb_tolerance=2.0)
    assert loose["tolerance_mm"] == 2.0 and loose["max_error_mm"] <= 2.0 and loose["within_tolerance"]
    assert loose["targets"] < report["targets"]
    for bad in (0, -1, float("nan")):
        with pytest.raises(myoshell.InputError, match="glb_tolerance: must be a number > 0 \\(mm\\), got"):
            myoshell.write_glb(tmp_path / "bad.glb", head, frames, glb_tolerance=bad)
        with pytest.raises(myoshell.InputError, match="glb_tolerance: must be a number > 0"):
            myoshell.drive(folder / "take.csv", library="builtin", out=tmp_path / "bad", glb_tolerance=bad)
    assert not (tmp_path / "bad.glb").exists() and not (tmp_path / "bad").exists()
    myoshell.write_pc2(tmp_path / "take.pc2", frames)
    assert (tmp_path / "take.pc2").read_bytes() == (folder / "cli" / "take.pc2").read_bytes()
    written = myoshell.write_obj_sequence(tmp_path / "seq", head, list(frames), name="take")
    assert written == [f"obj/take_{k:04d}.obj" for k in range(len(frames))]
    for rel in written:
        assert (tmp_path / "seq" / rel).read_bytes() == (folder / "cli" / rel).read_bytes()


def cli_error(cli, *args):
    result = cli(*args, check=False)
    assert result.returncode == 2, result.stderr
    return result.stderr


def test_bad_arguments_as_the_cli(driven, cli, tmp_path):
    folder, python = driven
    take = folder / "take.csv"
    out = tmp_path / "out"
    cases = [
        (dict(performance=tmp_path / "none.csv"), (tmp_path / "none.csv",), "cannot open performance file"),
        (dict(filter="maybe"), ("--filter", "maybe"), "--filter: expected on or off (got 'maybe')"),
        (dict(start=5, end=2), ("--start", "5", "--end", "2"), "--end 2 must lie after --start 5"),
        (dict(input="livelink"), ("--input", "livelink"), ""),
        (dict(formats=["glb", "fbx"]), ("--format", "glb,fbx"), "unknown export format 'fbx' (use glb, pc2 or obj)"),
    ]
    for kwargs, args, expected in cases:
        performance = kwargs.pop("performance", take)
        with pytest.raises(myoshell.InputError) as raised:
            myoshell.drive(performance, library="builtin", out=out, **kwargs)
        message = str(raised.value)
        assert expected in message
        cli_args = args if args[0] == performance else (performance, *args)
        assert message in cli_error(cli, "drive", *cli_args, "--library", "builtin", "--out", out)
    (tmp_path / "file").write_text("")
    with pytest.raises(myoshell.InputError, match="output path exists and is not a folder"):
        myoshell.drive(take, library="builtin", out=tmp_path / "file")
    with pytest.raises(myoshell.InputError, match=r"expected an \(F, n, 3\) array"):
        myoshell.write_pc2(tmp_path / "x.pc2", python["frames"][0])
    with pytest.raises(myoshell.InputError, match="vertices a frame"):
        myoshell.write_glb(tmp_path / "x.glb", myoshell.load_head(), python["frames"][:, :10])
    with pytest.raises(myoshell.InputError, match="head: expected a Head"):
        myoshell.write_glb(tmp_path / "x.glb", "default", python["frames"])
    with pytest.raises(myoshell.InputError, match="au_scale: expected a number > 0, got -1"):
        myoshell.drive(take, au_scale=-1)
    with pytest.raises(myoshell.InputError, match="end: expected a number"):
        myoshell.drive(take, end="soon")


# A write past RLIMIT_FSIZE fails with EFBIG ("File too large"): the system's failure, IoError, an
# OSError, with no file left behind. Run in a child so the limit binds nothing else.
IO_FAILURE = """
import resource, signal, sys
import numpy as np
import myoshell
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
resource.setrlimit(resource.RLIMIT_FSIZE, (4096, 4096))
try:
    myoshell.write_pc2(sys.argv[1], np.zeros((10, 500, 3)))
except myoshell.IoError as e:
    print("IoError", isinstance(e, OSError), e)
"""


def test_a_full_disk_is_an_io_error(tmp_path):
    target = tmp_path / "big.pc2"
    result = subprocess.run([sys.executable, "-c", IO_FAILURE, str(target)], capture_output=True, text=True,
                            env=dict(os.environ))
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith("IoError True " + str(target) + ":"), result.stdout
    assert "File too large" in result.stdout
    assert os.listdir(tmp_path) == []
    assert issubclass(myoshell.IoError, OSError)
