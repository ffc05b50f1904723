"""rootsim.sweep: points as they finish, the command line's table, resuming, the same numbers as a run."""
import numpy as np
import pytest

import rootsim
from conftest import SOURCE, cli

SCENE = SOURCE / "scenes/fig2a_alpha40.toml"


def test_grid_sweep_yields_every_point_and_matches_single_runs(tmp_path):
    s = rootsim.sweep(scene=SCENE, grid={"plane.alpha_deg": [20, 80], "tropism.beta": [0.2]},
                      set={"growth.steps": 60}, out=tmp_path / "sw", jobs=2)
    points = sorted(s, key=lambda p: p.index)
    assert [p.index for p in points] == [0, 1]
    # the grid values as the sweep's table has them (TOML text; floats with 17 digits)
    assert [{k: float(v) for k, v in p.grid.items()} for p in points] == [{"plane.alpha_deg": 20, "tropism.beta": 0.2},
                                                                          {"plane.alpha_deg": 80, "tropism.beta": 0.2}]
    assert all(p.ok and not p.skipped for p in points)
    assert s.summary == {"ran": 2, "skipped": 0, "failed": 0, "interrupted": False, "points": 2}
    assert s.table.is_file() and len(s.table.read_text().splitlines()) == 3
    for p, alpha in zip(points, (20, 80)):
        r = p.run
        assert r.result["alpha_deg"] == alpha and r.summary["steps"] == 60
        one = rootsim.run(SCENE, set={"plane.alpha_deg": alpha, "tropism.beta": 0.2, "growth.steps": 60},
                          out=tmp_path / f"one{alpha}")
        for name, col in one.timeseries.items():
            assert np.array_equal(col, r.timeseries[name], equal_nan=True), name
    # resumed: nothing is run again, every point is still yielded
    again = list(rootsim.sweep(scene=SCENE, grid={"plane.alpha_deg": [20, 80], "tropism.beta": [0.2]},
                               set={"growth.steps": 60}, out=tmp_path / "sw"))
    assert sorted(p.index for p in again) == [0, 1] and all(p.skipped for p in again)


def test_sweep_file_gives_the_command_lines_table(tmp_path):
    f = tmp_path / "small.toml"
    f.write_text(f'[sweep]\nscene = "{SCENE}"\n[grid]\n"plane.alpha_deg" = [30, 60]\n'
                 '[set]\n"growth.steps" = 40\n')
    cli("sweep", f, "--quiet", "--out", tmp_path / "cli")
    py = rootsim.sweep(f, out=tmp_path / "py")
    names = sorted(p.name for p in py)
    assert names == ["run_0000_alpha_deg=30", "run_0001_alpha_deg=60"]
    assert (tmp_path / "py" / "table.csv").read_bytes() == (tmp_path / "cli" / "table.csv").read_bytes()
    for n in names:
        assert (tmp_path / "py" / n / "timeseries.csv").read_bytes() == (tmp_path / "cli" / n / "timeseries.csv").read_bytes()


def test_bad_grid_key_is_refused_before_anything_runs(tmp_path):
    with pytest.raises(ValueError, match=r"point 0: --set plane.alpah_deg=20: unknown key plane.alpah_deg "
                                         r"\(did you mean plane.alpha_deg\?\)"):
        rootsim.sweep(scene=SCENE, grid={"plane.alpah_deg": [20, 40]}, out=tmp_path / "bad")
    assert not (tmp_path / "bad").exists()


def test_cancelled_sweep_stops(tmp_path):
    with rootsim.sweep(scene=SCENE, grid={"plane.alpha_deg": [10, 20, 30, 40, 50, 60]},
                       set={"growth.steps": 2000}, out=tmp_path / "c", jobs=1) as s:
        pass  # leaving the block cancels: the running point stops between growth steps
    assert s.summary["interrupted"] and s.summary["ran"] < 6
    assert not any((tmp_path / "c").glob("*.incomplete"))
