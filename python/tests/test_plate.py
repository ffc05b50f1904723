"""Plate coordinates (lateral, downhill, height above the plate) of every centreline the package returns,
against the closed form of a straight root grown downhill on a tilted plate; the same coordinates from
the run's files, the Simulation and shape.csv; shape.csv's own columns passed through."""
import shutil
import tomllib

import numpy as np
import pytest

import rootsim
from conftest import SOURCE

SCENE = SOURCE / "scenes/fig2a_alpha40.toml"


def resolved(scene):
    return tomllib.loads(scene.to_toml())


def lab_of_plate(f, alpha_deg):
    """The closed form of the tilted plate (docs/model.md, Frames and signs), written out here: lateral
    along lab x, downhill (0, -sin a, -cos a), normal (0, -cos a, sin a), origin at the base's foot."""
    a = np.radians(alpha_deg)
    downhill, normal = np.array([0.0, -np.sin(a), -np.cos(a)]), np.array([0.0, -np.cos(a), np.sin(a)])
    return (f.lateral_mm[:, None] * np.array([1.0, 0.0, 0.0]) + f.downhill_mm[:, None] * downhill
            + f.height_mm[:, None] * normal)


@pytest.mark.parametrize("alpha", [40, 20])
def test_a_straight_root_grown_downhill(alpha):
    # 50 growth steps of the Fig. 2A root (1.1 mm -> 1.6 mm): still straight (waves come later), at the
    # scene's own gravitropism; alpha = 20 shows the run's tilt is used, not the default 40
    r = rootsim.run(SCENE, set={"growth.steps": 50, "plane.alpha_deg": alpha})
    assert r.summary["pattern"] == "straight"
    keys = resolved(r.scene)
    R, eps = keys["root"]["radius_mm"], keys["solver"]["perturbation"]
    sh = r.shape
    for f in (r.frames[0], r.frames[-1]):
        # the coordinates are the lab positions in the plate's frame, to rounding
        np.testing.assert_allclose(lab_of_plate(f, alpha), f.positions_mm, rtol=0, atol=1e-13)
        # lateral: only the seeded perturbation (nodes moved by eps * R * u, |u| <= 1), not amplified yet
        assert np.abs(f.lateral_mm).max() <= eps * R
        # the base node sits on the plate's origin, at one radius above it
        assert f.lateral_mm[0] == 0.0 and abs(f.downhill_mm[0]) < 1e-15 and f.height_mm[0] == pytest.approx(R, rel=1e-14)
        assert np.all(np.diff(f.downhill_mm) > 0)  # downhill all along
    # the relaxed initial rod is the closed form itself: downhill = rest arc length, height = R
    s0 = r.frames[0]
    seg0 = np.linalg.norm(np.diff(s0.positions_mm, axis=0), axis=1)
    np.testing.assert_allclose(s0.downhill_mm, np.concatenate([[0.0], np.cumsum(seg0)]), rtol=0, atol=1e-12)
    np.testing.assert_allclose(s0.height_mm, R, rtol=0, atol=1e-12)
    # the grown root: downhill is the arc length up to the polyline's out-of-plane excursions (for an
    # element of length l rising dh and moving dlat: l - d(downhill) = (dh^2 + dlat^2) / (l + d(downhill)),
    # between 0 and (dh^2 + dlat^2) / l), and the arc length is the rest arc length s_mm stretched by
    # at most max|stretch - 1|
    f = r.frames[-1]
    l = np.linalg.norm(np.diff(f.positions_mm, axis=0), axis=1)
    arc = np.concatenate([[0.0], np.cumsum(l)])
    bound = np.concatenate([[0.0], np.cumsum((np.diff(f.height_mm) ** 2 + np.diff(f.lateral_mm) ** 2) / l)])
    assert np.all(arc - f.downhill_mm >= -1e-12) and np.all(arc - f.downhill_mm <= bound + 1e-12)
    stretch = np.abs(sh["stretch"] - 1.0).max()
    assert np.all(np.abs(arc - sh["s_mm"]) <= sh["s_mm"] * stretch + 1e-12)
    assert f.downhill_mm[-1] == pytest.approx(r.timeseries["length_mm"][-1], rel=1e-2)
    # height: R at the clamped base (above); the grown root arches (the gravitropic tip pressed into the
    # plate lifts the root behind it: 0.3 R at alpha = 40, mechanics, not a closed form): radius-scale,
    # within R/2 of R, with the pressed tip at or below R
    assert np.all(np.abs(f.height_mm - R) < 0.5 * R) and f.height_mm[-1] <= R and f.plate_force_n[-1] > 0
    # shape.csv's centreline: the same coordinates as the last frame
    for c in ("lateral_mm", "downhill_mm", "height_mm"):
        np.testing.assert_allclose(sh[c], getattr(f, c), rtol=0, atol=1e-12, err_msg=c)


def test_lab_x_y_is_squashed_plate_coordinates_are_not():
    # the user's first plot: lab y of a root along the downhill line is sin(alpha) of its length
    sim = rootsim.Simulation(SCENE, set={"growth.steps": 20})
    sim.step(20)
    st = sim.state()
    a = np.radians(40)
    L = st.downhill_mm[-1]
    assert -st.positions_mm[-1, 1] == pytest.approx(L * np.sin(a) + st.height_mm[-1] * np.cos(a), rel=1e-12)
    assert L == pytest.approx(sim.record()["length_mm"], rel=1e-2)
    snap = sim.snapshot()
    for c in ("lateral_mm", "downhill_mm", "height_mm"):
        assert np.array_equal(getattr(st, c), getattr(snap, c)), c


def test_a_free_organ_keeps_the_frame_the_plate_would_have():
    # no plate (plane.enabled = false): the frame of plane.alpha_deg, in which the initial root lies along
    # downhill at height R; gravity is lab -z, so the organ bends out of that plane as it grows
    sim = rootsim.Simulation(SOURCE / "scenes/fig2c_free_organ.toml", set={"growth.steps": 30})
    keys = resolved(sim.scene)
    assert keys["plane"]["enabled"] is False
    R, alpha = keys["root"]["radius_mm"], keys["plane"]["alpha_deg"]
    st = sim.state()
    np.testing.assert_allclose(st.downhill_mm, st.s_mm, rtol=0, atol=1e-12)
    np.testing.assert_allclose(st.height_mm, R, rtol=0, atol=1e-12)
    sim.step(30)
    f = sim.snapshot()
    np.testing.assert_allclose(lab_of_plate(f, alpha), f.positions_mm, rtol=0, atol=1e-13)
    assert f.plate_force_n is None or not f.plate_force_n.any()


def test_shape_passes_shape_csvs_own_plate_columns_through(tmp_path):
    r = rootsim.run(SCENE, set={"growth.steps": 10}, out=tmp_path / "run")
    computed = r.shape
    # a shape.csv that has the columns (as the writer will): they are taken as they are, not recomputed
    d = tmp_path / "copy"
    shutil.copytree(r.dir, d)
    lines = (d / "shape.csv").read_text().splitlines()
    marks = [f"{1000 + i},{2000 + i},{3000 + i}" for i in range(len(lines) - 1)]
    (d / "shape.csv").write_text("\n".join([lines[0] + ",lateral_mm,downhill_mm,height_mm"] +
                                           [a + "," + m for a, m in zip(lines[1:], marks)]) + "\n")
    got = rootsim.load_run(d).shape
    n = len(lines) - 1
    assert np.array_equal(got["lateral_mm"], 1000 + np.arange(n)) and np.array_equal(got["height_mm"], 3000 + np.arange(n))
    assert list(got)[-3:] == ["lateral_mm", "downhill_mm", "height_mm"]
    for c in ("x_mm", "s_mm", "radius_mm"):
        assert np.array_equal(got[c], computed[c]), c
