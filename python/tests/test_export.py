"""rootsim.export is `rootsim export`: the same files, the same option checks, the same write rule."""
import xml.etree.ElementTree as ET

import pytest

import rootsim
from conftest import SOURCE, cli

pytestmark = pytest.mark.skipif(not rootsim._rootsim.have_render, reason="built without the app library")


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory):
    d = tmp_path_factory.mktemp("export") / "wave"
    rootsim.run(SOURCE / "scenes/fig2b_waving.toml", set={"growth.steps": 100}, out=d)
    return d


def test_rsml_is_the_command_lines(run_dir, tmp_path):
    cli("export", run_dir, "--rsml", tmp_path / "cli.rsml", "--quiet")
    written = rootsim.export(run_dir, rsml=tmp_path / "py.rsml")
    assert written == [tmp_path / "py.rsml"]
    assert (tmp_path / "py.rsml").read_bytes() == (tmp_path / "cli.rsml").read_bytes()


def test_the_points_are_the_final_frames_plate_coordinates(run_dir, tmp_path):
    rootsim.export(run_dir, rsml=tmp_path / "r.rsml")
    # read by Python's own XML parser: the file is plain RSML
    points = ET.parse(tmp_path / "r.rsml").getroot().findall("./scene/plant/root/geometry/polyline/point")
    frame = rootsim.load_run(run_dir).frames[-1]
    assert len(points) == len(frame.lateral_mm)
    for p, x, y, z in zip(points, frame.lateral_mm, frame.downhill_mm, frame.height_mm):
        assert abs(float(p.get("x")) - x) < 1e-9
        assert abs(float(p.get("y")) - y) < 1e-9
        assert abs(float(p.get("z")) - z) < 1e-9


def test_every_h_returns_the_series_in_time_order(run_dir, tmp_path):
    written = rootsim.export(run_dir, rsml=tmp_path / "s.rsml", every_h=2)
    assert [p.name for p in written] == ["s_t000.00h.rsml", "s_t002.00h.rsml", "s_t004.00h.rsml"]
    assert all(p.is_file() for p in written)


def test_bad_options_have_the_command_lines_messages(run_dir, tmp_path):
    for args, kwargs in (([], {}),
                         (["--at-h", "99"], {"at_h": 99}),
                         (["--at-h", "1", "--every-h", "1"], {"at_h": 1, "every_h": 1})):
        r = cli("export", run_dir, *(["--rsml", tmp_path / "x.rsml"] if kwargs else []), *args, check=False)
        assert r.returncode == 2
        with pytest.raises(ValueError) as e:
            rootsim.export(run_dir, **({"rsml": tmp_path / "x.rsml"} if kwargs else {}), **kwargs)
        assert r.stderr.strip().splitlines()[-1] == "rootsim: error: " + str(e.value)
    assert not (tmp_path / "x.rsml").exists()


def test_three_formats_in_one_call_and_no_two_at_one_path(run_dir, tmp_path):
    written = rootsim.export(run_dir, rsml=tmp_path / "a.rsml", gltf=tmp_path / "a.glb", paraview=tmp_path / "a_pv",
                             at_h=2)
    assert written == [tmp_path / "a.rsml", tmp_path / "a.glb", tmp_path / "a_pv"]
    assert (tmp_path / "a_pv" / "open_in_paraview.py").is_file()
    with pytest.raises(rootsim.SceneError, match="--paraview .*: the same path as --rsml"):
        rootsim.export(run_dir, rsml=tmp_path / "same", paraview=tmp_path / "same")
    assert not (tmp_path / "same").exists()
    assert not (tmp_path / "same.partial").exists()


def test_the_write_rule_holds_in_python(run_dir, tmp_path):
    mine = tmp_path / "mine.rsml"
    mine.write_text("my roots")
    for force in (False, True):
        with pytest.raises(ValueError, match="was not written by rootsim"):
            rootsim.export(run_dir, rsml=mine, force=force)
    assert mine.read_text() == "my roots"
    own = tmp_path / "own.rsml"
    rootsim.export(run_dir, rsml=own)
    with pytest.raises(ValueError, match="pass --force"):
        rootsim.export(run_dir, rsml=own, at_h=1)
    rootsim.export(run_dir, rsml=own, at_h=1, force=True)
    assert '<time_h value="1"/>' in own.read_text()


def test_options_are_keywords_only(run_dir, tmp_path):
    with pytest.raises(TypeError):
        rootsim.export(run_dir, tmp_path / "k.rsml")  # type: ignore[misc]


def test_the_example_reads_the_file_without_rootsim(run_dir, tmp_path):
    import subprocess
    import sys
    rootsim.export(run_dir, rsml=tmp_path / "e.rsml")
    r = subprocess.run([sys.executable, str(SOURCE / "examples/rsml_functions.py"), str(tmp_path / "e.rsml"),
                        str(tmp_path / "e.png")], capture_output=True, text=True, check=True)
    frame = rootsim.load_run(run_dir).frames[-1]
    assert f": {len(frame.lateral_mm)} points," in r.stdout
    assert f"age up to {frame.time_h:.1f} h" in r.stdout  # the base has been mature since the start
    assert (tmp_path / "e.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
