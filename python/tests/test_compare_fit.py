"""rootsim.compare and rootsim.fit are `rootsim compare` and `rootsim fit`: the same files, the same checks."""
import json

import numpy as np
import pytest

import rootsim
from conftest import SOURCE, cli

pytestmark = pytest.mark.skipif(not rootsim._rootsim.have_render, reason="the run is exported to RSML by rootsim.export: built without the renderer")

QUICK = {"growth.steps": 300, "root.element_length_mm": 0.1, "growth.step_h": 0.1, "output.vtk": False}


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    d = tmp_path_factory.mktemp("quick")
    run = rootsim.run(SOURCE / "scenes/fig2b_waving.toml", set=QUICK, out=d / "run")
    rootsim.export(run.dir, rsml=d / "run.rsml")
    scene = d / "quick.toml"
    text = (SOURCE / "scenes/fig2b_waving.toml").read_text()
    scene.write_text(text.replace("element_length_mm = 0.05", "element_length_mm = 0.1").replace("step_h = 0.05", "step_h = 0.1"))
    return run, d / "run.rsml", scene


def test_compare_is_the_command_lines(tmp_path, quick):
    run, trace, _ = quick
    res = rootsim.compare(run.dir, trace, out=tmp_path / "py")
    cli("compare", run.dir, trace, "--out", tmp_path / "cli", "--quiet")
    assert res["out"] == tmp_path / "py"
    del res["out"]
    assert res == json.loads((tmp_path / "cli" / "compare.json").read_text())
    assert res["distance_mm"] < 1e-9
    assert res["observables"]["wavelength_mm"]["used"] is True
    assert (tmp_path / "py" / "compare.png").stat().st_size > 1000


def test_fit_finds_the_trace_of_its_own_scene(tmp_path, quick):
    _, trace, scene = quick
    res = rootsim.fit(trace, scene=scene, free={"tropism.beta": (0.1, 0.3), "tropism.twist_r_tau": (-0.2, 0.2)},
                      budget=60, jobs=2, out=tmp_path / "fit")
    beta = res["best"]["tropism.beta"]
    assert abs(beta["value"] - 0.2) < 3 * beta["sigma"]
    assert res["evaluations"] <= 60
    # what the fit claims: its goodness against the trace's uncertainty, and the keys it held fixed
    assert res["goodness"]["verdict"] == "consistent"
    assert res["goodness"]["p_value"] >= 1e-3
    assert res["scene_fixed"]["plane.alpha_deg"]["source"] == "scene"
    assert "tropism.beta" not in res["scene_fixed"]
    # the same arguments again: every run is found, the same answer
    again = rootsim.fit(trace, scene=scene, free="tropism.beta=0.1:0.3,tropism.twist_r_tau=-0.2:0.2", budget=60,
                        jobs=2, out=tmp_path / "fit")
    assert again == res


def test_bad_options_raise_the_command_lines_message(tmp_path, quick):
    run, trace, scene = quick
    with pytest.raises(rootsim.SceneError, match="tropism.betta"):
        rootsim.fit(trace, scene=scene, free={"tropism.betta": (0.1, 0.3)}, out=tmp_path / "f")
    with pytest.raises(rootsim.SceneError, match="--budget 0"):
        rootsim.fit(trace, scene=scene, free={"tropism.beta": (0.1, 0.3)}, budget=0, out=tmp_path / "f")
    with pytest.raises(rootsim.SceneError, match="--sigma-mm -1"):
        rootsim.compare(run.dir, trace, sigma_mm=-1, out=tmp_path / "c")
    assert not (tmp_path / "f").exists() and not (tmp_path / "c").exists()


BASE = """[root]
radius_mm = 0.1
initial_length_mm = 1.1
element_length_mm = 0.1
[growth]
growth_zone_mm = 1.0
rate_per_h = 0.2
step_h = 0.1
[tropism]
beta = 0.2
gamma = 0.1
sensing = "local"
[plane]
alpha_deg = 40
[output]
every_steps = 50
"""


def test_fit_by_group_is_the_command_lines(tmp_path):
    # two seedlings of each genotype (twist 0 and 0.05), 7 mm, exported: fitted in the twist by group
    plate = BASE.replace("step_h = 0.1\n", "step_h = 0.1\nsteps = 300\n") + "vtk = false\n[plate]\nwidth_mm = 60\nlength_mm = 20\n"
    for i, (name, angle) in enumerate([("w1", -3), ("w2", 2), ("m1", 3), ("m2", -2)]):
        plate += f'[[seedling]]\nname = "{name}"\nposition_mm = [{5 + 12 * i}, 5]\nangle_deg = {angle}\n'
        if name.startswith("m"):
            plate += 'set = { "tropism.twist_r_tau" = 0.05 }\n'
    (tmp_path / "plate.toml").write_text(plate)
    (tmp_path / "base.toml").write_text(BASE)
    (tmp_path / "sheet.csv").write_text("plant,group\nw1,WT\nw2,WT\nm1,mut\nm2,mut\n")
    run = rootsim.run(tmp_path / "plate.toml", out=tmp_path / "run")
    rsml = tmp_path / "plate.rsml"
    rootsim.export(run.dir, rsml=rsml)
    free = {"tropism.twist_r_tau": (-0.05, 0.1)}
    res = rootsim.fit([rsml], scene=tmp_path / "base.toml", free=free, groups=tmp_path / "sheet.csv", budget=18, jobs=2,
                      out=tmp_path / "py")
    cli("fit", rsml, "--scene", tmp_path / "base.toml", "--free", "tropism.twist_r_tau=-0.05:0.1", "--groups", tmp_path / "sheet.csv",
        "--budget", "18", "-j", "2", "--out", tmp_path / "cli", "--quiet")
    ours = json.loads((tmp_path / "cli" / "fit.json").read_text())
    assert res["keys"] == ["tropism.twist_r_tau"]
    assert list(res["groups"]) == ["WT", "mut"]
    for name, g in res["groups"].items():
        assert g["plants"] == ours["groups"][name]["plants"]
        assert g["best"] == ours["groups"][name]["best"]
        assert isinstance(g["values"], np.ndarray) and g["values"].shape == (1,)
        assert g["values"][0] == g["best"]["tropism.twist_r_tau"]["value"]
        assert g["goodness"]["verdict"] in ("consistent", "poor")
    (c,) = res["contrasts"]
    assert c == ours["contrasts"][0]
    assert c["groups"] == ["WT", "mut"] and c["key"] == "tropism.twist_r_tau"
    # the mutant twists more: WT - mut is negative
    assert c["difference"] < 0
    (tmp_path / "solo.csv").write_text("plant,group\nw1,WT\nw2,WT\nm1,mut\nm2,solo\n")
    with pytest.raises(rootsim.SceneError, match="solo.csv:4: group mut has one seedling"):
        rootsim.fit(rsml, scene=tmp_path / "base.toml", free=free, groups=tmp_path / "solo.csv", out=tmp_path / "bad")
    assert not (tmp_path / "bad").exists()
