"""rootsim.render is `rootsim render`: the same pictures, the same option checks."""
import pytest

import rootsim
from conftest import SOURCE, cli

pytestmark = pytest.mark.skipif(not rootsim._rootsim.have_render, reason="built without the renderer")


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory):
    d = tmp_path_factory.mktemp("render") / "wave"
    rootsim.run(SOURCE / "scenes/fig2b_waving.toml", set={"growth.steps": 200}, out=d)
    return d


def test_final_png_is_the_command_lines(run_dir, tmp_path):
    cli("render", run_dir, "--final-png", tmp_path / "cli.png", "--size", "256x192", "--quiet")
    written = rootsim.render(run_dir, final_png=tmp_path / "py.png", size="256x192")
    assert written == [tmp_path / "py.png"]
    png = (tmp_path / "py.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    assert png == (tmp_path / "cli.png").read_bytes()  # same input, same pixels
    assert not (run_dir / "movie.mp4").exists()  # only what was asked for


def test_png_frames_with_a_look(run_dir, tmp_path):
    rootsim.render(run_dir, png_dir=tmp_path / "frames", size="128x128", color_by="twist", plot=["theta_tip", "Eb"])
    assert len(list((tmp_path / "frames").glob("*.png"))) == len(rootsim.load_run(run_dir).frames)


def test_bad_options_have_the_command_lines_messages(run_dir, tmp_path):
    for args, kwargs in ((["--size", "3x3"], {"size": "3x3"}),
                         (["--color-by", "rainbow"], {"color_by": "rainbow"}),
                         (["--field-mm", "3"], {"field_mm": 3})):
        r = cli("render", run_dir, "--final-png", tmp_path / "x.png", *args, check=False)
        assert r.returncode == 2
        with pytest.raises(ValueError) as e:
            rootsim.render(run_dir, final_png=tmp_path / "x.png", **kwargs)
        assert r.stderr.strip().splitlines()[-1] == "rootsim: error: " + str(e.value)
