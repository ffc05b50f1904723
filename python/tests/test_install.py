"""`cmake --install` puts the rootsim binary and the Python package into a prefix, and both work from there:
the package imports from the prefix's site-packages alone (no build folder on the path) and runs a tiny
scene; the binary prints its version and runs the same scene.

ctest sets ROOTSIM_BUILD_DIR, CMAKE_COMMAND and ROOTSIM_PYTHON_INSTALL_DIR (python/CMakeLists.txt)."""
import os
import pathlib
import subprocess
import sys
import textwrap

import pytest

from conftest import SOURCE

BUILD = pathlib.Path(os.environ.get("ROOTSIM_BUILD_DIR", SOURCE / "build"))
CMAKE = os.environ.get("CMAKE_COMMAND", "cmake")
PY_DIR = os.environ.get("ROOTSIM_PYTHON_INSTALL_DIR", "")
SCENE = SOURCE / "scenes/fig2a_alpha40.toml"


@pytest.fixture(scope="module")
def prefix(tmp_path_factory):
    if not PY_DIR or os.path.isabs(PY_DIR):
        pytest.skip(f"ROOTSIM_PYTHON_INSTALL_DIR={PY_DIR!r} is not relative to the prefix: installing would "
                    "write outside a test prefix")
    p = tmp_path_factory.mktemp("prefix")  # under the build folder (ctest's --basetemp)
    r = subprocess.run([CMAKE, "--install", str(BUILD), "--prefix", str(p)], capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    return p


def clean_env(**extra):
    """The environment without the build folder's package on the path (PYTHONPATH only what is given)."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "ROOTSIM_BINARY")}
    env.update(extra)
    return env


def test_the_package_and_the_binary_are_installed(prefix):
    pkg = prefix / PY_DIR / "rootsim"
    for f in ("__init__.py", "_api.py", "_rootsim.pyi", "py.typed"):
        assert (pkg / f).is_file(), f
    assert len(list(pkg.glob("_rootsim*.so"))) == 1
    assert os.access(prefix / "bin" / "rootsim", os.X_OK)


def test_the_installed_package_imports_and_runs_a_scene(prefix, tmp_path):
    site = prefix / PY_DIR
    script = textwrap.dedent(f"""
        import pathlib, rootsim
        assert pathlib.Path(rootsim.__file__).resolve().is_relative_to(pathlib.Path({str(site)!r}).resolve()), rootsim.__file__
        r = rootsim.run({str(SCENE)!r}, set={{"growth.steps": 4}}, out={str(tmp_path / "run")!r})
        assert list(r.timeseries["step"]) == [0, 4], r.timeseries["step"]
        f = r.frames[-1]
        assert f.step == 4 and f.positions_mm.shape[1] == 3 and f.downhill_mm[-1] > 1.0
        sim = rootsim.Simulation({str(SCENE)!r}, set={{"growth.steps": 3}})
        sim.step(3)
        assert sim.record()["length_mm"] > 1.1
        print(rootsim.__version__)
    """)
    # cwd: not the source tree (its python/rootsim has no extension); -s: no user site-packages
    r = subprocess.run([sys.executable, "-s", "-c", script], capture_output=True, text=True, cwd=tmp_path,
                       env=clean_env(PYTHONPATH=str(site)))
    assert r.returncode == 0, r.stdout + r.stderr
    version = r.stdout.strip()
    # the installed binary: its version is the package's, and it runs the same scene
    b = subprocess.run([str(prefix / "bin" / "rootsim"), "--version"], capture_output=True, text=True,
                       env=clean_env(), cwd=tmp_path)
    assert b.returncode == 0, b.stderr
    assert b.stdout.strip() == f"rootsim {version}"
    b = subprocess.run([str(prefix / "bin" / "rootsim"), "run", str(SCENE), "--set", "growth.steps=4", "--quiet",
                        "--out", str(tmp_path / "cli")], capture_output=True, text=True, env=clean_env(), cwd=tmp_path)
    assert b.returncode == 0, b.stderr
    assert (tmp_path / "cli" / "timeseries.csv").read_bytes() == (tmp_path / "run" / "timeseries.csv").read_bytes()
