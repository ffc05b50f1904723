"""Shared fixtures: the source tree and the rootsim binary the Python package is compared against.

ctest sets ROOTSIM_SOURCE_DIR and ROOTSIM_BINARY (python/CMakeLists.txt); by hand:
    PYTHONPATH=build/python /usr/bin/python3 -m pytest python/tests
"""
import os
import pathlib
import subprocess

import pytest

SOURCE = pathlib.Path(os.environ.get("ROOTSIM_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
BINARY = pathlib.Path(os.environ.get("ROOTSIM_BINARY", SOURCE / "build" / "rootsim"))


@pytest.fixture
def scenes() -> pathlib.Path:
    return SOURCE / "scenes"


def cli(*args, check=True):
    """Runs the rootsim binary; returns the CompletedProcess (text output)."""
    r = subprocess.run([str(BINARY), *map(str, args)], capture_output=True, text=True)
    if check and r.returncode != 0:
        raise AssertionError(f"rootsim {' '.join(map(str, args))} exited {r.returncode}: {r.stderr}")
    return r


def read_csv_independently(path):
    """A CSV file parsed by Python alone (float() is correctly rounded, like from_chars): the reference
    the package's arrays must equal bit for bit."""
    lines = pathlib.Path(path).read_text().splitlines()
    names = lines[0].split(",")
    cols = {n: [] for n in names}
    for line in lines[1:]:
        for n, cell in zip(names, line.split(",")):
            cols[n].append(float(cell))
    return names, cols
