"""Shared fixtures of the Python tests: the source tree, the CLI built beside the module,
and a runner of the CLI (the reference the module's numbers are checked against)."""
import os
import pathlib
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("PRONK_SOURCE_DIR", pathlib.Path(__file__).parents[2]))


@pytest.fixture(scope="session")
def source_dir():
    return SOURCE_DIR


@pytest.fixture(scope="session")
def pronk_exe():
    exe = os.environ.get("PRONK_EXE")
    if not exe or not os.path.exists(exe):
        pytest.skip("PRONK_EXE (the pronk CLI of the same build) is not set")
    return exe


@pytest.fixture(scope="session")
def run_cli(pronk_exe):
    def run(*args, check=True):
        p = subprocess.run([pronk_exe, *map(str, args)], capture_output=True, text=True)
        if check and p.returncode not in (0, 1):
            raise AssertionError(f"pronk {' '.join(map(str, args))}: exit {p.returncode}\n{p.stderr}")
        return p

    return run
