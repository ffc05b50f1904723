"""rootsim.run and rootsim.load_run against the command line's files for the same scene."""
import json
import os
import signal
import subprocess
import sys
import textwrap
import threading

import numpy as np
import pytest

import rootsim
from conftest import BINARY, SOURCE, cli, read_csv_independently

# a waving root (Fig. 2B) grown far enough to wave: 400 growth steps, 1.1 mm -> 5.1 mm
WAVE = {"growth.steps": 400}
WAVE_ARGS = ["--set", "growth.steps=400"]


def assert_bitwise_equal(a, b, what):
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    assert a.shape == b.shape, f"{what}: shape {a.shape} != {b.shape}"
    same = (a.view(np.uint64) == b.view(np.uint64))
    assert same.all(), f"{what}: {np.count_nonzero(~same)} values differ, first at {np.argmin(same)}: {a[~same][:3]} vs {b[~same][:3]}"


@pytest.fixture(scope="module")
def cli_run(tmp_path_factory):
    d = tmp_path_factory.mktemp("cli") / "fig2b"
    cli("run", SOURCE / "scenes/fig2b_waving.toml", *WAVE_ARGS, "--quiet", "--out", d)
    return d


def test_run_numbers_are_the_command_lines_to_the_last_bit(cli_run, tmp_path):
    r = rootsim.run(SOURCE / "scenes/fig2b_waving.toml", set=WAVE, out=tmp_path / "py")
    assert r.dir == tmp_path / "py" and (r.dir / ".rootsim-run").is_file()
    assert r.summary["pattern"] == "waving"  # the scene really waves at 400 steps: a non-trivial run
    names, ref = read_csv_independently(cli_run / "timeseries.csv")
    assert list(r.timeseries) == names
    assert len(ref["step"]) == 41  # step 0 and every 10th
    for n in names:
        assert_bitwise_equal(r.timeseries[n], ref[n], f"timeseries {n}")
    names, ref = read_csv_independently(cli_run / "shape.csv")
    # shape.csv's columns, then the plate coordinates where the file has none
    plate = [c for c in ("lateral_mm", "downhill_mm", "height_mm") if c not in names]
    assert list(r.shape) == names + plate
    for n in names:
        assert_bitwise_equal(r.shape[n], ref[n], f"shape {n}")
    # the files themselves are the same bytes (summary.json differs only in its wall time)
    for f in ("timeseries.csv", "shape.csv", "trajectory.bin", "result.csv", "scene.toml"):
        assert (r.dir / f).read_bytes() == (cli_run / f).read_bytes(), f
    want = json.loads((cli_run / "summary.json").read_text())
    got = dict(r.summary)
    want.pop("wall_time_s"), got.pop("wall_time_s")
    assert got == want


def test_frames_are_the_trajectory_snapshots(cli_run, tmp_path):
    r = rootsim.load_run(cli_run)
    frames = r.frames
    assert [f.step for f in frames] == list(range(0, 401, 10))
    last = frames[-1]
    n = int(r.timeseries["elements"][-1])
    assert last.positions_mm.shape == (n + 1, 3) and last.d1.shape == (n, 3) and last.d3.shape == (n, 3)
    assert last.radius_mm.shape == (n,) and last.kappa0_per_mm.shape == (n + 1,)
    assert last.plate_force_n.shape == (n + 1,) and last.contact_force_n.shape == (n + 1, 3)
    assert last.lateral_mm.shape == last.downhill_mm.shape == last.height_mm.shape == (n + 1,)
    # the final frame is the final shape: the same units (mm), nothing to convert
    for k, c in enumerate(("x_mm", "y_mm", "z_mm")):
        np.testing.assert_allclose(last.positions_mm[:, k], r.shape[c], rtol=0, atol=1e-12, err_msg=c)
    for c in ("lateral_mm", "downhill_mm", "height_mm"):
        np.testing.assert_allclose(getattr(last, c), r.shape[c], rtol=0, atol=1e-12, err_msg=c)
    np.testing.assert_allclose(last.radius_mm, 0.5 * (r.shape["radius_mm"][:-1] + r.shape["radius_mm"][1:]), rtol=1e-3)
    np.testing.assert_allclose(np.linalg.norm(last.d1, axis=1), 1.0, atol=1e-12)
    # the tip of each frame is the time series' tip
    np.testing.assert_allclose([f.positions_mm[-1, 0] for f in frames], r.timeseries["tip_x_mm"], rtol=0, atol=1e-12)


def test_options_are_keywords(tmp_path):
    with pytest.raises(TypeError):
        rootsim.run(SOURCE / "scenes/fig2a_alpha40.toml", {"growth.steps": 2})  # set= is a keyword
    with pytest.raises(TypeError, match="colour"):
        rootsim.run(SOURCE / "scenes/fig2a_alpha40.toml", set={"growth.steps": 2}, colour="red")
    with pytest.raises(TypeError):
        rootsim.Scene.load(SOURCE / "scenes/fig2a_alpha40.toml", {"growth.steps": 2})
    assert not list(tmp_path.iterdir())


def test_load_run_of_a_command_line_run(cli_run):
    r = rootsim.load_run(str(cli_run))
    names, ref = read_csv_independently(cli_run / "timeseries.csv")
    for n in names:
        assert_bitwise_equal(r.timeseries[n], ref[n], f"timeseries {n}")
    assert r.summary == json.loads((cli_run / "summary.json").read_text())
    assert r.result["pattern"] == "waving" and r.result["scene"] == "fig2b_waving"
    assert r.result["steps"] == 400
    assert r.scene.steps == 400 and r.scene.name == "fig2b_waving"
    assert r.scene.to_toml() == (cli_run / "scene.toml").read_text()


def test_load_run_refuses_what_is_not_a_complete_run(tmp_path):
    with pytest.raises(ValueError, match="not a complete run directory"):
        rootsim.load_run(tmp_path)
    (tmp_path / "x.partial").mkdir()
    with pytest.raises(rootsim.SceneError, match=r"x\.partial/ is an interrupted run"):
        rootsim.load_run(tmp_path / "x")


def test_out_none_is_a_temporary_directory_kept_by_the_run():
    r = rootsim.run(SOURCE / "scenes/fig2a_alpha40.toml", set={"growth.steps": 20})
    d = r.dir
    assert d.is_dir() and r.timeseries["step"][-1] == 20
    del r
    import gc
    gc.collect()
    assert not d.exists()


def test_runs_in_threads_give_the_numbers_of_one_run(tmp_path):
    # the GIL is released while simulating: two runs at once, each the same as alone
    alone = rootsim.run(SOURCE / "scenes/fig2a_alpha80.toml", set={"growth.steps": 100}, out=tmp_path / "alone")
    outs = {}

    def go(k):
        outs[k] = rootsim.run(SOURCE / "scenes/fig2a_alpha80.toml", set={"growth.steps": 100}, out=tmp_path / k)

    ts = [threading.Thread(target=go, args=(k,)) for k in ("a", "b")]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    for k in ("a", "b"):
        assert (outs[k].dir / "timeseries.csv").read_bytes() == (alone.dir / "timeseries.csv").read_bytes()


def test_progress_callback_sees_every_step(tmp_path):
    seen = []
    rootsim.run(SOURCE / "scenes/fig2a_alpha40.toml", set={"growth.steps": 30}, out=tmp_path / "p",
                progress=lambda k, n: seen.append((k, n)))
    assert seen == [(k, 30) for k in range(1, 31)]


def test_keyboard_interrupt_from_progress_leaves_partial(tmp_path):
    def stop(k, n):
        if k == 15:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        rootsim.run(SOURCE / "scenes/fig2a_alpha40.toml", set={"growth.steps": 50}, out=tmp_path / "i", progress=stop)
    assert (tmp_path / "i.partial" / ".rootsim-run").is_file()
    assert not (tmp_path / "i").exists() and not (tmp_path / "i.incomplete").exists()
    # any other exception of the callback propagates the same way
    with pytest.raises(ZeroDivisionError):
        rootsim.run(SOURCE / "scenes/fig2a_alpha40.toml", set={"growth.steps": 50}, out=tmp_path / "z",
                    progress=lambda k, n: 1 / 0)
    assert (tmp_path / "z.partial").is_dir() and not (tmp_path / "z.incomplete").exists()
    # and the interrupted run is replaced with force, as on the command line
    r = rootsim.run(SOURCE / "scenes/fig2a_alpha40.toml", set={"growth.steps": 5}, out=tmp_path / "i", force=True)
    assert r.summary["steps"] == 5 and not (tmp_path / "i.partial").exists()


def test_sigint_stops_a_run_between_growth_steps(tmp_path):
    # a real Ctrl-C (SIGINT to the process) while the C++ loop runs without any Python callback
    out = tmp_path / "long"
    script = textwrap.dedent(f"""
        import os, signal, sys, threading, rootsim
        def progress(k, n):
            if k == 1:
                print("running", flush=True)
        try:
            rootsim.run({str(SOURCE / 'scenes/fig2b_waving.toml')!r}, set={{"growth.steps": 5000}},
                        out={str(out)!r}, progress=progress)
        except KeyboardInterrupt:
            print("KeyboardInterrupt", flush=True)
            sys.exit(3)
    """)
    p = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         env=dict(os.environ))
    assert p.stdout.readline().strip() == "running"
    p.send_signal(signal.SIGINT)
    out_text, err = p.communicate(timeout=120)
    assert p.returncode == 3, err
    assert "KeyboardInterrupt" in out_text
    assert (tmp_path / "long.partial" / "scene.toml").is_file()
    assert not out.exists() and not (tmp_path / "long.incomplete").exists()


def test_two_threads_writing_one_out_never_race(tmp_path):
    # a second thread of this process writing the same `out` while the first holds it is refused with
    # the holder's PID (the lock is re-entrant only for the thread that holds it); the first ends whole
    out = tmp_path / "same"
    errors, done = [], threading.Event()

    def second():
        try:
            rootsim.run(SOURCE / "scenes/fig2a_alpha80.toml", set={"growth.steps": 20}, out=out)
        except Exception as e:  # noqa: BLE001 - the message is what is checked
            errors.append(str(e))
        finally:
            done.set()

    def progress(k, n):
        if k == 1:
            threading.Thread(target=second).start()
            assert done.wait(60)

    r = rootsim.run(SOURCE / "scenes/fig2a_alpha80.toml", set={"growth.steps": 20}, out=out, progress=progress)
    assert len(errors) == 1, errors
    assert "being written by another rootsim thread of this process" in errors[0]
    assert f"PID {os.getpid()}" in errors[0]
    assert (r.dir / "summary.json").is_file() and not (tmp_path / "same.partial").exists()
