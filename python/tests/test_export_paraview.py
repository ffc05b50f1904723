"""rootsim.export(run, paraview=DIR) is `rootsim export RUN --paraview DIR`: the same folder, the same
write rule (docs/paraview.md)."""
import pytest

import rootsim
from conftest import SOURCE, cli

pytestmark = pytest.mark.skipif(not rootsim._rootsim.have_render, reason="built without the app library")


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory):
    d = tmp_path_factory.mktemp("export_paraview") / "skew"
    rootsim.run(SOURCE / "scenes/fig4a_skewing.toml", set={"growth.steps": 60, "output.every_steps": 20}, out=d)
    return d


def tree(d):
    """name -> bytes; the script's line naming its own folder left out (the one difference of two folders),
    and with it the marker's record of the script (its SHA-256 follows that line)"""
    out = {p.name: p.read_bytes() for p in sorted(d.iterdir())}
    script = out["open_in_paraview.py"].decode()
    assert ('WRITTEN_TO = "%s"\n' % d) in script
    out["open_in_paraview.py"] = script.replace('WRITTEN_TO = "%s"\n' % d, "")
    marker = out[".rootsim-paraview"].decode().splitlines(keepends=True)
    assert any(line.startswith("file open_in_paraview.py ") for line in marker)
    out[".rootsim-paraview"] = "".join(line for line in marker if not line.startswith("file open_in_paraview.py "))
    return out


def test_the_folder_is_the_command_lines(run_dir, tmp_path):
    cli("export", run_dir, "--paraview", tmp_path / "cli", "--quiet")
    written = rootsim.export(run_dir, paraview=tmp_path / "py")
    assert written == [tmp_path / "py"]
    assert tree(tmp_path / "py") == tree(tmp_path / "cli")
    names = set(tree(tmp_path / "py"))
    assert {"root.pvd", "plate.vtp", "open_in_paraview.py", "step_000000.vtp", "step_000060.vtp"} <= names


def test_at_h_one_snapshot_and_force(run_dir, tmp_path):
    rootsim.export(run_dir, paraview=tmp_path / "pv")
    with pytest.raises(rootsim.SceneError, match="--force"):
        rootsim.export(run_dir, paraview=tmp_path / "pv", at_h=2)
    rootsim.export(run_dir, paraview=tmp_path / "pv", at_h=2, force=True)
    vtps = sorted(p.name for p in (tmp_path / "pv").glob("step_*.vtp"))
    assert vtps == ["step_000040.vtp"]


def test_a_users_folder_is_refused(run_dir, tmp_path):
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "notes.txt").write_text("mine")
    with pytest.raises(rootsim.SceneError, match="not a rootsim ParaView folder"):
        rootsim.export(run_dir, paraview=tmp_path / "mine", force=True)
    assert (tmp_path / "mine" / "notes.txt").read_text() == "mine"
