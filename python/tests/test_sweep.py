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
    # the grid values typed as given (TOML integers and floats), not their text
    assert [p.grid for p in points] == [{"plane.alpha_deg": 20, "tropism.beta": 0.2},
                                        {"plane.alpha_deg": 80, "tropism.beta": 0.2}]
    assert all(type(p.grid["plane.alpha_deg"]) is int and type(p.grid["tropism.beta"]) is float for p in points)
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


def test_grid_values_are_typed_as_the_sweep_files_toml_values(tmp_path):
    f = tmp_path / "typed.toml"
    f.write_text(f'[sweep]\nscene = "{SCENE}"\n[grid]\n"tropism.beta" = [0.1, 0.25]\n'
                 '"tropism.sensing" = ["local", "apical"]\n"plane.alpha_deg" = [30]\n'
                 '[set]\n"growth.steps" = 2\n')
    points = sorted(rootsim.sweep(f, out=tmp_path / "sw", jobs=2), key=lambda p: p.index)
    assert [p.grid for p in points] == [
        {"tropism.beta": 0.1, "tropism.sensing": "local", "plane.alpha_deg": 30},
        {"tropism.beta": 0.1, "tropism.sensing": "apical", "plane.alpha_deg": 30},
        {"tropism.beta": 0.25, "tropism.sensing": "local", "plane.alpha_deg": 30},
        {"tropism.beta": 0.25, "tropism.sensing": "apical", "plane.alpha_deg": 30}]
    for p in points:
        assert type(p.grid["tropism.beta"]) is float and type(p.grid["plane.alpha_deg"]) is int
        assert p.run.result["beta"] == p.grid["tropism.beta"]


def test_grid_value_text_is_read_as_a_number_when_the_file_cannot_say():
    from rootsim._api import _typed_grid

    text = {"a": "20", "b": "0.20000000000000001", "c": "true", "d": "apical", "e": "1e-05", "f": "[1,2.5]"}
    got = _typed_grid(0, text, None)
    assert got == {"a": 20, "b": 0.2, "c": True, "d": "apical", "e": 1e-5, "f": [1, 2.5]}
    assert [type(got[k]) for k in "abcde"] == [int, float, bool, str, float]
    # a typed array that disagrees with the text (the file changed since) gives way to the text
    assert _typed_grid(0, {"a": "20"}, {"a": [30]}) == {"a": 20}
    assert _typed_grid(1, {"a": "20", "b": "x"}, {"a": [20], "b": ["w", "x"]}) == {"a": 20, "b": "x"}


def test_the_write_rule_holds_for_python_sweeps(tmp_path):
    mine = tmp_path / "myproj"
    mine.mkdir()
    (mine / "table.csv").write_text("my,table\n")
    with pytest.raises(ValueError, match="not a rootsim sweep folder"):
        list(rootsim.sweep(scene=SCENE, grid={"plane.alpha_deg": [20]}, set={"growth.steps": 20}, out=mine))
    assert (mine / "table.csv").read_text() == "my,table\n"
    out = tmp_path / "sw"
    assert len(list(rootsim.sweep(scene=SCENE, grid={"plane.alpha_deg": [20]}, set={"growth.steps": 20}, out=out))) == 1
    # the same folder with another fixed value: the point is stale, rerun only with force=True
    with pytest.raises(ValueError, match="1 point\\(s\\) hold runs that cannot be kept"):
        list(rootsim.sweep(scene=SCENE, grid={"plane.alpha_deg": [20]}, set={"growth.steps": 30}, out=out))
    points = list(rootsim.sweep(scene=SCENE, grid={"plane.alpha_deg": [20]}, set={"growth.steps": 30}, out=out,
                                force=True))
    assert [p.run.summary["steps"] for p in points] == [30]
