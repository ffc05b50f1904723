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


def test_the_write_rule_holds_in_python(run_dir, tmp_path):
    # a user's file is never replaced, force or not; rootsim's own picture only with force=True
    mine = tmp_path / "mine.png"
    mine.write_bytes(b"my picture")
    for force in (False, True):
        with pytest.raises(ValueError, match="was not written by rootsim"):
            rootsim.render(run_dir, final_png=mine, size="128x128", force=force)
    assert mine.read_bytes() == b"my picture"
    ours = tmp_path / "ours.png"
    rootsim.render(run_dir, final_png=ours, size="128x128")
    with pytest.raises(ValueError, match="pass --force to replace it"):
        rootsim.render(run_dir, final_png=ours, size="128x128")
    rootsim.render(run_dir, final_png=ours, size="128x128", force=True)
    # the run's own data is an input, never an output
    before = (run_dir / "trajectory.bin").read_bytes()
    with pytest.raises(ValueError, match="which this command reads"):
        rootsim.render(run_dir, mp4=run_dir / "trajectory.bin", force=True)
    assert (run_dir / "trajectory.bin").read_bytes() == before


def test_render_options_are_named_not_positional(run_dir, tmp_path):
    with pytest.raises(ValueError, match="unknown option colour"):
        rootsim._rootsim.render_run({"run_dir": str(run_dir), "final_png": str(tmp_path / "x.png"), "colour": "twist"})


def test_render_takes_keywords_only(run_dir, tmp_path):
    # the public calls: a positional option or an unknown keyword is a TypeError naming it, nothing drawn
    with pytest.raises(TypeError, match="colour"):
        rootsim.render(run_dir, final_png=tmp_path / "x.png", colour="twist")
    with pytest.raises(TypeError, match="colour"):
        rootsim.load_run(run_dir).render(final_png=tmp_path / "x.png", colour="twist")
    with pytest.raises(TypeError, match="positional"):
        rootsim.render(run_dir, tmp_path / "x.mp4")
    assert not (tmp_path / "x.png").exists() and not (tmp_path / "x.mp4").exists()


def test_a_still_is_the_movies_frame(run_dir, tmp_path):
    # rootsim.render(png=..., at_h=...) is `rootsim render --png --at-h` and the movie's frame, pixel for pixel
    frames = rootsim.load_run(run_dir).frames
    k = len(frames) // 2
    look = dict(size="256x192", camera="follow", color_by="twist")
    rootsim.render(run_dir, png_dir=tmp_path / "frames", from_h=0.0, **look)
    written = rootsim.render(run_dir, png=tmp_path / "py.png", at_h=frames[k].time_h, from_h=0.0, **look)
    assert written == [tmp_path / "py.png"]
    cli("render", run_dir, "--png", tmp_path / "cli.png", "--frame", str(k), "--size", "256x192",
        "--camera", "follow", "--color-by", "twist", "--quiet")
    movie = (tmp_path / "frames" / f"frame_{k:05d}.png").read_bytes()
    assert (tmp_path / "py.png").read_bytes() == movie
    assert (tmp_path / "cli.png").read_bytes() == movie
    # a window and a speed: frame count from the documented rule
    t0, t1 = frames[2].time_h, frames[-3].time_h
    rootsim.render(run_dir, png_dir=tmp_path / "win", size="128x128", from_h=t0, to_h=t1)
    assert len(list((tmp_path / "win").glob("*.png"))) == len(frames) - 4
    # bad values: the command line's messages
    with pytest.raises(ValueError, match="--from-h 2: after --to-h 1"):
        rootsim.render(run_dir, mp4=tmp_path / "bad.mp4", from_h=2.0, to_h=1.0)
    with pytest.raises(ValueError, match=r"--hours-per-second 0: expected a finite number in \(0, 1e\+06\] h/s"):
        rootsim.render(run_dir, mp4=tmp_path / "bad.mp4", hours_per_second=0.0)
    with pytest.raises(ValueError, match="--at-h 1e\\+06: outside the run's snapshots"):
        rootsim.render(run_dir, png=tmp_path / "bad.png", at_h=1e6)
    assert not (tmp_path / "bad.mp4").exists() and not (tmp_path / "bad.png").exists()
