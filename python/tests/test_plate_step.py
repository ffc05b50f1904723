"""A plate stepped from Python (rootsim.Plate, docs/python.md): the same roots, laterals, steps and
numbers as `rootsim run` of the scene; roots named, with their parents and orders; a scene it cannot
step refused naming why."""
import math

import numpy as np
import pytest

import rootsim
from conftest import SOURCE, cli, read_csv_independently

# two seedlings 1 mm apart (one with its own gamma, both with a drawn beta) whose laterals emerge
# within the 120 steps and come within reach of each other (min_gap_over_contact from step 60)
SCENE = """
[root]
radius_mm = 0.1
initial_length_mm = 1.1
element_length_mm = 0.05

[growth]
growth_zone_mm = 1.0
rate_per_h = 0.2
steps = 120
step_h = 0.05

[tropism]
beta = 0.2
gamma = 0.1

[plane]
alpha_deg = 40

[output]
every_steps = 10

[plate]
width_mm = 20
length_mm = 20

[laterals]
enabled = true
first_mm = 0.6
spacing_mm = 0.3
apical_unbranched_mm = 0.7
insertion_deg = 65
radius_mm = 0.06
rate_per_h = 0.1
growth_zone_mm = 0.6
initial_length_mm = 0.3
set_point_deg = 55

[population]
seed = 7

[population.spread]
"tropism.beta" = { normal_sd = 0.02 }

[[seedling]]
name = "left"
position_mm = [9, 2]

[[seedling]]
name = "right"
position_mm = [10, 2]
angle_deg = 20
[seedling.set]
"tropism.gamma" = 0.2
"""
STEPS, STEP_H, EVERY = 120, 0.05, 10


@pytest.fixture(scope="module")
def cli_run(tmp_path_factory):
    d = tmp_path_factory.mktemp("plate_step")
    (d / "two.toml").write_text(SCENE)
    cli("run", d / "two.toml", "--out", d / "run")
    return d


def plate_table(run):
    """plate_timeseries.csv as floats (an empty min_gap_over_contact: no two roots within reach, NaN)."""
    _, cols = read_table(run / "plate_timeseries.csv")
    return {n: [float(c) if c else math.nan for c in v] for n, v in cols.items()}


def test_a_plate_stepped_in_python_is_rootsim_run(cli_run):
    run = cli_run / "run"
    plate = rootsim.Simulation(cli_run / "two.toml")  # a plate scene: a Plate
    assert isinstance(plate, rootsim.Plate)
    assert [r.name for r in plate.roots] == ["left", "right"] and plate.time_h == 0.0
    series = plate_table(run)
    rows = {int(s): k for k, s in enumerate(series["step"])}
    emerged_at = {}
    for k in range(1, STEPS + 1):
        row = plate.step()
        assert row["step"] == k and plate.step_count == k
        assert plate.time_h == pytest.approx(k * STEP_H, rel=1e-12)
        for name in row["emerged"]:
            emerged_at[name] = k
        assert row["roots"] == len(plate.roots)
        if k in rows:  # the plate's step record: the file's row, the same doubles
            i = rows[k]
            assert row["touching_pairs"] == series["touching_pairs"][i] and row["sweeps"] == series["sweeps"][i]
            gap = series["min_gap_over_contact"][i]
            assert (math.isnan(row["min_gap_over_contact"]) and math.isnan(gap)) or row["min_gap_over_contact"] == gap
    assert plate.steps_left == 0
    assert not math.isnan(plate.record()["min_gap_over_contact"])  # the roots came within reach
    with pytest.raises(ValueError, match="only 0 growth steps left"):
        plate.step()

    # the same roots, named, with their parents and orders, as plate.csv lists them
    names, table = read_table(run / "plate.csv")
    roots = plate.roots
    assert [r.name for r in roots] == table["root"] and len(roots) == 10
    for r, parent, order, eh in zip(roots, table["parent"], table["order"], table["emerged_h"]):
        assert (r.parent, r.order) == (parent, int(order))
        assert r.emerged_h == pytest.approx(float(eh), rel=1e-12, abs=1e-12)
        # laterals emerge at the step of the run: emerged_h is that step's time
        assert r.emerged_step == round(float(eh) / STEP_H)
        assert (r.order == 0) == (r.name not in emerged_at)
        if r.order:
            assert emerged_at[r.name] == r.emerged_step and r.parent in ("left", "right")
    assert plate.root("right").overrides == table["overrides"][1].split(";")
    with pytest.raises(KeyError, match="no root 'middle'.*left, right, left.1"):
        plate.root("middle")

    # each root's final nodes: roots/NAME/shape.csv's, to 1e-12 mm (the same frame: its base's foot at the
    # origin), and the root's state, snapshot and record are a Simulation's
    for r in roots:
        _, shape = read_csv_independently(run / "roots" / r.name / "shape.csv")
        st = r.state()
        # a root counts its own growth steps (a lateral's from its emergence, as its roots/NAME), on the
        # plate's clock
        assert isinstance(st, rootsim.State) and st.step == STEPS - r.emerged_step
        assert st.time_h == pytest.approx(STEPS * STEP_H, rel=1e-12)
        lab = np.column_stack([shape["x_mm"], shape["y_mm"], shape["z_mm"]])
        np.testing.assert_allclose(st.positions_mm, lab, rtol=0, atol=1e-12, err_msg=r.name)
        for c in ("lateral_mm", "downhill_mm", "height_mm", "s_mm"):
            np.testing.assert_allclose(getattr(st, c), shape[c], rtol=0, atol=1e-12, err_msg=f"{r.name} {c}")
        f = r.snapshot()
        assert isinstance(f, rootsim.Frame)
        np.testing.assert_array_equal(f.positions_mm, st.positions_mm)
        _, ts = read_csv_independently(run / "roots" / r.name / "timeseries.csv")
        rec = r.record()
        assert rec["step"] == ts["step"][-1] == st.step and rec["length_mm"] == ts["length_mm"][-1] and rec["time_h"] == ts["time_h"][-1]


def read_table(path):
    """A CSV of text cells: column -> list of strings."""
    lines = path.read_text().splitlines()
    names = lines[0].split(",")
    cols = {n: [] for n in names}
    for line in lines[1:]:
        for n, cell in zip(names, line.split(",")):
            cols[n].append(cell)
    return names, cols


def test_run_steps_what_is_left_and_steps_the_same(cli_run):
    a = rootsim.Plate(cli_run / "two.toml", set={"growth.steps": 30})
    a.step(7)
    last = a.run()
    assert last["step"] == 30 and a.steps_left == 0 and a.run()["step"] == 30
    # the laterals of step 20, in the row of the 23 steps that ran it; record() has the last step's alone
    assert last["emerged"] == ["left.1", "right.1"] and a.record()["emerged"] == []
    b = rootsim.Plate(cli_run / "two.toml", set={"growth.steps": 30})
    b.step(30)
    assert [r.name for r in a.roots] == [r.name for r in b.roots] == ["left", "right", "left.1", "right.1"]
    for ra, rb in zip(a.roots, b.roots):
        np.testing.assert_array_equal(ra.state().positions_mm, rb.state().positions_mm)


def test_a_scene_it_cannot_step_is_refused(cli_run):
    # one root: a Simulation's, named
    with pytest.raises(rootsim.SceneError, match=r"fig2a_alpha40.toml\): the scene has no \[\[seedling\]\] tables"):
        rootsim.Plate(SOURCE / "scenes/fig2a_alpha40.toml")
    assert isinstance(rootsim.Simulation(SOURCE / "scenes/fig2a_alpha40.toml"), rootsim.Simulation)
    # the one-root stepper under Simulation never takes a plate's first root for the plate
    from rootsim import _rootsim
    with pytest.raises(rootsim.SceneError, match=r"a plate of 2 seedling\(s\) with laterals; .*rootsim.Plate"):
        _rootsim._Simulation(rootsim.Scene.load(cli_run / "two.toml")._scene)
    # no growth: nothing to step
    p = rootsim.Plate(cli_run / "two.toml", set={"growth.enabled": False})
    with pytest.raises(rootsim.SceneError, match="growth.enabled = false: nothing to step"):
        p.step()
    assert p.steps_left == 0
    with pytest.raises(ValueError, match="n must be a positive int"):
        rootsim.Plate(cli_run / "two.toml").step(0)
    with pytest.raises(ValueError, match=r"step\(121\): only 120 growth steps left"):
        rootsim.Plate(cli_run / "two.toml").step(121)
