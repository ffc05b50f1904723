"""rootsim.Simulation: stepping by hand gives the run's numbers; state copies; tropism changes; the step
count argument and the end of growth; one Simulation used from several threads."""
import dataclasses
import signal
import threading
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
    # the final state is the run's last frame (frames are read back from the trajectory: equal to rounding)
    last = r.frames[-1]
    snap = sim.snapshot()
    assert snap.step == last.step == 200
    for name in ("positions_mm", "lateral_mm", "downhill_mm", "height_mm", "radius_mm"):
        np.testing.assert_allclose(getattr(snap, name), getattr(last, name), rtol=1e-15, atol=1e-15, err_msg=name)
    np.testing.assert_allclose(snap.d1, last.d1, rtol=0, atol=1e-15)
    np.testing.assert_allclose(snap.d3, last.d3, rtol=0, atol=1e-15)


def test_state_views_shapes_and_contents():
    sim = rootsim.Simulation(SCENE, set=STEPS)
    sim.step(30)
    st = sim.state()
    n = sim.record()["elements"]
    assert st.step == 30 and st.time_h == pytest.approx(30 * 0.05)
    assert st.positions_mm.shape == (n + 1, 3) and st.velocities_mm_per_s.shape == (n + 1, 3)
    assert st.lateral_mm.shape == st.downhill_mm.shape == st.height_mm.shape == (n + 1,)
    assert st.directors.shape == (n, 3, 3) and st.rest_lengths_mm.shape == (n,)
    assert st.s_mm.shape == (n + 1,) and st.kappa0_vector_per_mm.shape == (n - 1, 3)
    # kappa0_per_mm is the Frame's per-node magnitude; the State's vector has its own name, the old one says so
    with pytest.raises(AttributeError, match="renamed kappa0_vector_per_mm.*per-node magnitude"):
        st.kappa0_per_mm
    assert st.angular_velocities_rad_per_s.shape == (n, 3) and st.clamp_frame.shape == (3, 3)
    for name in ("anchors_mm", "plate_sticks_mm", "obstacle_sticks_mm"):
        assert getattr(st, name).shape == (n + 1, 3), name
    for name in ("anchored", "has_plate_stick", "has_obstacle_stick"):
        assert getattr(st, name).shape == (n + 1,) and getattr(st, name).dtype == np.bool_, name
    # the base is clamped to the first element's frame at the start: an orthonormal frame
    np.testing.assert_allclose(st.clamp_frame @ st.clamp_frame.T, np.eye(3), atol=1e-12)
    # copies: owned, C-contiguous arrays (float64; the flags bool)
    arrays = [v for v in vars(st).values() if isinstance(v, np.ndarray)]
    assert len(arrays) == len(dataclasses.fields(rootsim.State)) - 2  # all but step and time_h
    for a in arrays:
        assert a.dtype in (np.float64, np.bool_) and a.flags.owndata and a.flags.c_contiguous
    # the positions are the snapshot's node positions; directors orthonormal and d1, d3 the snapshot's
    snap = sim.snapshot()
    for name in ("positions_mm", "lateral_mm", "downhill_mm", "height_mm"):
        assert np.array_equal(getattr(st, name), getattr(snap, name)), name
    assert np.array_equal(st.directors[:, 0, :], snap.d1) and np.array_equal(st.directors[:, 2, :], snap.d3)
    for Q in st.directors:
        np.testing.assert_allclose(Q @ Q.T, np.eye(3), atol=1e-12)
    # rest lengths add up to the recorded length; S is their running sum
    assert st.rest_lengths_mm.sum() == pytest.approx(sim.record()["length_mm"], rel=1e-13)
    np.testing.assert_allclose(np.diff(st.s_mm), st.rest_lengths_mm, rtol=1e-12)
    # state(copy=True) is still accepted (the arrays are always copies)
    kept = sim.state(copy=True)
    sim.step(1)
    assert kept.positions_mm.flags.owndata and kept.step == 30


def test_state_holds_every_field_of_the_rod_states_list():
    # the binding walks the C++ field list (rod_fields.hpp): State declares each of its Python names, and
    # nothing else besides the step and the plate coordinates; each field has one value per node, element
    # or interior node (Voronoi domain) as the list says, or one for the rod
    listed = dict(rootsim._rootsim.state_fields())
    assert len(listed) == len(rootsim._rootsim.state_fields()) > 0
    declared = [f.name for f in dataclasses.fields(rootsim.State)]
    assert sorted(declared) == sorted(list(listed) + ["step", "lateral_mm", "downhill_mm", "height_mm"])
    sim = rootsim.Simulation(SCENE, set=STEPS)
    sim.step(30)
    st = sim.state()
    n = sim.record()["elements"]
    count = {"node": n + 1, "element": n, "voronoi": n - 1}
    for name, along in listed.items():
        value = getattr(st, name)
        if along == "rod":
            assert np.ndim(value) in (0, 2), name  # a number, or a frame
        else:
            assert value.shape[0] == count[along], name


def test_one_unit_system_the_files_units():
    # the state, the snapshot and the time-series row in the same units (mm): the same numbers, unconverted
    sim = rootsim.Simulation(SCENE, set=STEPS)
    sim.step(40)
    st, snap, row = sim.state(), sim.snapshot(), sim.record()
    tip = [row["tip_x_mm"], row["tip_y_mm"], row["tip_z_mm"]]
    assert np.array_equal(st.positions_mm[-1], tip) and np.array_equal(snap.positions_mm[-1], tip)
    assert st.s_mm[-1] == pytest.approx(row["length_mm"], rel=1e-13)
    assert st.time_h == snap.time_h == row["time_h"]
    R = tomllib.loads(sim.scene.to_toml())["root"]["radius_mm"]
    assert snap.radius_mm == pytest.approx(R, rel=0.01)  # R / sqrt(stretch), stretch within 1e-4 of 1
    # curvatures in 1/mm: a waving root of wavelength ~2.3 mm bends at ~1/mm, not ~1000/m
    assert 0.05 < np.abs(st.kappa0_vector_per_mm).max() < 20
    assert 0.05 < snap.kappa0_per_mm.max() < 20
    # the old SI names say what they became
    with pytest.raises(AttributeError, match=r"State\.positions was renamed positions_mm"):
        st.positions
    with pytest.raises(AttributeError, match=r"Frame\.x was renamed positions_mm"):
        snap.x
    with pytest.raises(AttributeError, match="has no attribute 'nonsense'"):
        st.nonsense


def test_options_are_keywords():
    with pytest.raises(TypeError):
        rootsim.Simulation(SCENE, STEPS)  # set= is a keyword
    sim = rootsim.Simulation(SCENE, set=STEPS)
    with pytest.raises(TypeError):
        sim.state(True)
    with pytest.raises(TypeError, match="colour"):
        rootsim.Simulation(SCENE, colour=1)


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


def test_state_arrays_keep_their_values_across_steps():
    # growth splits elements and reallocates the rod's arrays: a view would then read freed memory
    sim = rootsim.Simulation(SCENE, set=STEPS)
    sim.step(10)
    st = sim.state()
    at_the_time = {k: np.array(v, copy=True) for k, v in vars(st).items() if isinstance(v, np.ndarray)}
    n0 = sim.record()["elements"]
    sim.step(60)
    assert sim.record()["elements"] > n0  # elements were split: the arrays were reallocated
    for name, values in at_the_time.items():
        assert np.array_equal(getattr(st, name), values), name
    assert st.positions_mm.shape == (n0 + 1, 3) and 1.0 < np.linalg.norm(st.positions_mm, axis=1).max() < 30  # mm
    # and the arrays are the caller's: writing them changes nothing in the simulation
    st.positions_mm[:] = 0.0
    assert np.array_equal(sim.state().positions_mm, sim.snapshot().positions_mm) and sim.state().positions_mm.any()


def test_step_takes_a_positive_int_only():
    sim = rootsim.Simulation(SCENE, set=STEPS)
    for bad in (1.5, 2.0, "2", True, False, None, [1]):
        with pytest.raises(TypeError, match=r"step\(n\): n must be a positive int"):
            sim.step(bad)
    for bad in (0, -1, -(2**70)):
        with pytest.raises(ValueError, match=r"step\(n\): n must be a positive int"):
            sim.step(bad)
    assert sim.step_count == 0
    sim.step(np.int64(2))  # numpy integers are ints
    sim.step()
    assert sim.step_count == 3


def test_step_stops_at_growth_steps():
    sim = rootsim.Simulation(SCENE, set={"growth.steps": 3})
    assert sim.steps_left == 3
    sim.step(2)
    with pytest.raises(ValueError, match=r"^step\(5\): only 1 growth steps left of growth.steps = 3 "):
        sim.step(5)
    assert sim.step_count == 2  # refused before any step ran
    sim.step(1)
    assert sim.steps_left == 0
    with pytest.raises(ValueError, match=r"^step\(1\): only 0 growth steps left of growth.steps = 3 "):
        sim.step()
    with pytest.raises(ValueError, match=r"only 0 growth steps left"):
        sim.step(2**40)
    assert sim.step_count == 3 and sim.record()["step"] == 3


def test_two_threads_stepping_one_simulation_are_serialised():
    sim = rootsim.Simulation(SCENE, set={"growth.steps": 100})
    errors, seen = [], []

    def stepper():
        try:
            for _ in range(50):
                r = sim.step(1)
                assert 1 <= r["step"] <= 100
        except BaseException as e:  # noqa: BLE001 (reported below)
            errors.append(e)

    def reader():
        try:
            while any(t.is_alive() for t in steppers):
                st = sim.state()
                assert st.positions_mm.shape[0] == st.rest_lengths_mm.shape[0] + 1
                seen.append(st.step)
                sim.record(), sim.snapshot(), sim.step_count
        except BaseException as e:  # noqa: BLE001
            errors.append(e)

    steppers = [threading.Thread(target=stepper) for _ in range(2)]
    for t in steppers:
        t.start()
    watcher = threading.Thread(target=reader)
    watcher.start()
    for t in steppers + [watcher]:
        t.join()
    assert errors == []
    assert sim.step_count == 100 and sim.steps_left == 0
    assert seen == sorted(seen)  # the reader saw whole steps, in order
    # the same root as 100 steps in one thread, to the last bit
    one = rootsim.Simulation(SCENE, set={"growth.steps": 100})
    one.step(100)
    assert same(sim.record(), one.record())
    assert np.array_equal(sim.state().positions_mm, one.state().positions_mm)


def test_a_call_from_inside_its_own_step_is_refused_not_deadlocked():
    # a signal handler runs between growth steps, in the thread that holds the Simulation
    sim = rootsim.Simulation(SCENE, set=STEPS)
    seen = []

    def handler(signum, frame):
        try:
            sim.record()
        except RuntimeError as e:
            seen.append(str(e))

    old = signal.signal(signal.SIGALRM, handler)
    try:
        signal.setitimer(signal.ITIMER_REAL, 0.0005, 0.0005)  # every 0.5 ms, during steps of ~0.2-2 ms
        sim.step(190)
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)
    assert sim.step_count == 190
    assert seen and all(m.startswith("Simulation is busy in this thread") for m in seen)
    assert sim.record()["step"] == 190  # and usable again once step() has returned
