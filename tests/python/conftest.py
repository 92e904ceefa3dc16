"""Shared fixtures: one basis cache and one face on the built-in head for the whole session, the
command-line program to compare with, and the team's data folder (tests needing it skip without)."""
import os
import pathlib
import shutil
import subprocess

import pytest

import myoshell

SOURCE_TREE = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def cache_dir(tmp_path_factory):
    return tmp_path_factory.mktemp("basis_cache")


@pytest.fixture(scope="session")
def face(cache_dir):
    """The anatomical face on the built-in head with the whole face's 40 muscles (the default library)."""
    return myoshell.Face(cache=str(cache_dir))


@pytest.fixture(scope="session")
def cli():
    """Runs the command-line program (MYOSHELL_BIN, set by ctest; else build/bin/myoshell)."""
    program = os.environ.get("MYOSHELL_BIN") or str(SOURCE_TREE / "build" / "bin" / "myoshell")
    if not os.access(program, os.X_OK):
        pytest.skip(f"no myoshell program at {program} (build it, or set MYOSHELL_BIN)")

    def run(*args, check=True):
        result = subprocess.run([program, *map(str, args)], capture_output=True, text=True)
        if check and result.returncode != 0:
            raise AssertionError(f"myoshell {' '.join(map(str, args))} failed ({result.returncode}):\n{result.stderr}")
        return result

    return run


@pytest.fixture(scope="session")
def shared_data():
    """The team's data folder (../shared/data beside the source tree, or MYOSHELL_DATA)."""
    candidates = [os.environ.get("MYOSHELL_DATA"), os.environ.get("MYO_SHARED_DIR") and
                  os.path.join(os.environ["MYO_SHARED_DIR"], "data"), str(SOURCE_TREE.parent / "shared" / "data")]
    for c in candidates:
        if c and os.path.isdir(os.path.join(c, "ict")):
            return pathlib.Path(c)
    pytest.skip("the shared data folder (../shared/data with ict/) is absent: set MYOSHELL_DATA to run this test")


def read_obj_vertices(path):
    """The `v` lines of an OBJ as an (n, 3) float64 array (the writer prints round-trip text)."""
    import numpy as np

    rows = [line.split()[1:4] for line in open(path) if line.startswith("v ")]
    return np.array(rows, dtype=np.float64)
