"""rootsim.Simulation: stepping by hand gives the run's numbers; state views; tropism changes."""
import tomllib

import numpy as np
import pytest

import rootsim
from conftest import SOURCE

SCENE = SOURCE / "scenes/fig2b_waving.toml"
STEPS = {"growth.steps": 200}


def same(r1, r2):
    """Two time-series rows equal bit for bit (NaN included)."""
    return r1.keys() == r2.keys() and all(np.float64(r1[k]).tobytes() == np.float64(r2[k]).tobytes() for k in r1)


def test_stepping_gives_the_runs_time_series_to_the_last_bit(tmp_path):
    r = rootsim.run(SCENE, set=STEPS, out=tmp_path / "run")
    sim = rootsim.Simulation(SCENE, set=STEPS)
    rows = [sim.record()]
    for _ in range(20):
        rows.append(sim.step(10))
    assert sim.step_count == 200
    assert list(rows[0]) == list(r.timeseries)  # the same columns, in the same order
    for name, col in r.timeseries.items():
        got = np.array([row[name] for row in rows], dtype=np.float64)
        assert np.array_equal(got.view(np.uint64), col.view(np.uint64)), name
    # the final state is the run's last frame (frames are read back from mm text: equal to rounding)
    last = r.frames[-1]
    snap = sim.snapshot()
    assert snap.step == last.step == 200
    np.testing.assert_allclose(snap.x, last.x, rtol=1e-15, atol=1e-18)
    np.testing.assert_allclose(snap.d1, last.d1, rtol=0, atol=1e-15)
    np.testing.assert_allclose(snap.d3, last.d3, rtol=0, atol=1e-15)
    np.testing.assert_allclose(snap.radius, last.radius, rtol=1e-15)


def test_state_views_shapes_and_contents():
    sim = rootsim.Simulation(SCENE, set=STEPS)
    sim.step(30)
    st = sim.state()
    n = sim.record()["elements"]
    assert st.step == 30 and st.time_h == pytest.approx(30 * 0.05)
    assert st.positions.shape == (n + 1, 3) and st.velocities.shape == (n + 1, 3)
    assert st.directors.shape == (n, 3, 3) and st.rest_lengths.shape == (n,)
    assert st.material_coordinates.shape == (n + 1,) and st.kappa0.shape == (n - 1, 3)
    # views, not copies, and read-only
    assert not st.positions.flags.owndata and not st.positions.flags.writeable
    with pytest.raises(ValueError):
        st.positions[0, 0] = 1.0
    # the positions are the snapshot's node positions; directors orthonormal and d1, d3 the snapshot's
    snap = sim.snapshot()
    assert np.array_equal(st.positions, snap.x)
    assert np.array_equal(st.directors[:, 0, :], snap.d1) and np.array_equal(st.directors[:, 2, :], snap.d3)
    for Q in st.directors:
        np.testing.assert_allclose(Q @ Q.T, np.eye(3), atol=1e-12)
    # rest lengths add up to the recorded length; S is their running sum
    assert st.rest_lengths.sum() * 1e3 == pytest.approx(sim.record()["length_mm"], rel=1e-13)
    np.testing.assert_allclose(np.diff(st.material_coordinates), st.rest_lengths, rtol=1e-12)
    # a copy survives stepping
    kept = sim.state(copy=True)
    sim.step(1)
    assert kept.positions.flags.owndata and kept.step == 30


def test_length_grows_by_the_growth_law():
    sim = rootsim.Simulation(SCENE, set=STEPS)
    toml = tomllib.loads(sim.scene.to_toml())
    g = toml["growth"]
    l0 = toml["root"]["initial_length_mm"]
    # only the zone of length Lgz behind the tip grows, at eps0: dL/dt = eps0 * min(L, Lgz)
    assert l0 >= g["growth_zone_mm"]
    per_step = g["rate_per_h"] * g["step_h"] * g["growth_zone_mm"]
    assert sim.record()["length_mm"] == l0
    for k in (1, 5, 50):
        sim.step(k)
    assert sim.step_count == 56
    assert sim.record()["length_mm"] == pytest.approx(l0 + 56 * per_step, rel=1e-12)
    assert sim.record()["time_h"] == pytest.approx(56 * g["step_h"], rel=1e-12)


def test_changing_beta_half_way():
    a = rootsim.Simulation(SCENE, set=STEPS)
    b = rootsim.Simulation(SCENE, set=STEPS)
    a.step(100)
    b.step(100)
    assert same(a.record(), b.record())
    b.set("tropism.beta", 0.8)
    assert b.scene.overrides[-1] == "tropism.beta=0.8" and "beta = 0.8" in b.scene.to_toml()
    a.step(100)
    b.step(100)
    # the stronger gravitropism turns the tip further downhill: a different root from step 101 on
    assert a.record()["theta_tip_deg"] != b.record()["theta_tip_deg"]
    assert a.record()["length_mm"] == b.record()["length_mm"]  # growth itself is unchanged
    # the same as a run with beta = 0.8 from the start? no: the first 100 steps were grown with 0.2
    c = rootsim.Simulation(SCENE, set={**STEPS, "tropism.beta": 0.8})
    c.step(200)
    assert c.record()["theta_tip_deg"] != b.record()["theta_tip_deg"]
    with pytest.raises(ValueError, match=r"^--set tropism.beta=-1: tropism.beta must be in \[0, 100\] \(got -1\)$"):
        b.set("tropism.beta", -1)
    with pytest.raises(ValueError, match="only tropism"):
        b.set("plane.alpha_deg", 10)


def test_mechanics_only_scene_has_no_steps():
    sim = rootsim.Simulation(SOURCE / "scenes/cantilever_tip_load.toml")
    assert sim.step_count == 0 and sim.record()["step"] == 0
    with pytest.raises(ValueError, match="nothing to step"):
        sim.step()
