"""rootsim.export(run, gltf=...) is `rootsim export --gltf`: the same bytes, the same checks (docs/gltf.md)."""
import json
import struct

import pytest

import rootsim
from conftest import SOURCE, cli

pytestmark = pytest.mark.skipif(not rootsim._rootsim.have_render, reason="built without the renderer")


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory):
    d = tmp_path_factory.mktemp("gltf") / "wave"
    rootsim.run(SOURCE / "scenes/fig2b_waving.toml", set={"growth.steps": 40, "output.every_steps": 4}, out=d)
    return d


def glb_json(data):
    """the JSON chunk of a GLB file"""
    magic, version, length = struct.unpack("<4sII", data[:12])
    assert (magic, version, length) == (b"glTF", 2, len(data))
    n, kind = struct.unpack("<I4s", data[12:20])
    assert kind == b"JSON"
    return json.loads(data[20:20 + n])


def test_gltf_is_the_command_lines(run_dir, tmp_path):
    cli("export", run_dir, "--gltf", tmp_path / "cli.glb", "--quiet")
    assert rootsim.export(run_dir, gltf=tmp_path / "py.glb") == [tmp_path / "py.glb"]
    data = (tmp_path / "py.glb").read_bytes()
    assert data == (tmp_path / "cli.glb").read_bytes()  # same input, same bytes
    doc = glb_json(data)
    frames = [n for n in doc["nodes"] if n.get("name", "").startswith("frame ")]
    assert len(frames) == len(rootsim.load_run(run_dir).frames)
    assert doc["asset"]["generator"].startswith("rootsim-output")
    # a still: the snapshot nearest at_h, no animation
    rootsim.export(run_dir, gltf=tmp_path / "still.glb", at_h=1.0)
    still = glb_json((tmp_path / "still.glb").read_bytes())
    assert "animations" not in still
    assert [n["extras"]["time_h"] for n in still["nodes"] if n.get("name", "").startswith("frame ")] == [pytest.approx(1.0)]


def test_bad_gltf_names_have_the_command_lines_messages(run_dir, tmp_path):
    r = cli("export", run_dir, "--gltf", tmp_path / "x.gltf", check=False)
    assert r.returncode == 2
    with pytest.raises(rootsim.SceneError) as e:
        rootsim.export(run_dir, gltf=tmp_path / "x.gltf")
    assert r.stderr.strip().splitlines()[-1] == "rootsim: error: " + str(e.value)
    assert not (tmp_path / "x.gltf").exists()
