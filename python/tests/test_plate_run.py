"""A plate's run from Python (docs/plate.md): rootsim.run of a plate scene, each root's data through
run.roots, the seedlings' places; a root apart is the single root's run."""
import numpy as np
import pytest

import rootsim
from conftest import SOURCE

SCENE = SOURCE / "scenes/plate_genotypes.toml"


def test_a_plate_run_gives_each_root(tmp_path):
    r = rootsim.run(SCENE, set={"growth.steps": 40, "output.vtk": False}, out=tmp_path / "plate")
    assert r.is_plate
    assert list(r.roots) == ["wt1", "wt2", "wt3", "tw1", "tw2", "tw3"]
    seeds = {sd["name"]: sd for sd in r.plate_roots}
    assert seeds["tw1"]["genotype"] == "twisted"
    assert seeds["tw1"]["position_lateral_mm"] == 51.0
    assert "tropism.twist_r_tau=0.4" in seeds["tw1"]["overrides"]
    for name, root in r.roots.items():
        assert not root.is_plate
        assert root.timeseries["step"][-1] == 40
        assert root.summary["steps"] == 40
        # each root in its own frame: its base's foot at the origin of the plate coordinates
        f = root.frames[0]
        assert abs(f.lateral_mm[0]) < 1e-12 and abs(f.downhill_mm[0]) < 1e-12
    # the twisted genotype got its twist, the wild type none
    assert r.roots["tw2"].result["r_tau"] == 0.4
    assert r.roots["wt2"].result["r_tau"] == 0.0
    # the plate itself has no time series of its own: it says where to look
    with pytest.raises(rootsim.SceneError, match=r"run.roots\[NAME\].timeseries"):
        r.timeseries


def test_a_single_root_has_no_roots(tmp_path):
    r = rootsim.run(SOURCE / "scenes/fig2a_alpha40.toml", set={"growth.steps": 5}, out=tmp_path / "one")
    assert not r.is_plate
    assert r.roots == {}
    assert r.plate_roots == []


def test_a_simulation_of_a_plate_is_the_plate():
    """A Simulation steps one root; a plate's roots step together (contacts, laterals): Simulation of a
    plate scene is a Plate of all its roots, never its first root alone (test_plate_step.py steps it)."""
    p = rootsim.Simulation(SOURCE / "scenes/plate_collision.toml")
    assert isinstance(p, rootsim.Plate) and [r.name for r in p.roots] == ["down", "across"]
    p = rootsim.Simulation(SOURCE / "scenes/plate_wildtype.toml", set={"growth.steps": 3})
    assert isinstance(p, rootsim.Plate) and len(p.roots) == 6 and p.steps_left == 3
