"""Errors as on the command line: the same messages, ValueError for bad input, RuntimeError for runs."""
import pytest

import rootsim
from conftest import SOURCE, cli


def cli_error(*args):
    r = cli(*args, check=False)
    assert r.returncode == 2, r.stderr
    line = r.stderr.strip().splitlines()[-1]
    prefix = "rootsim: error: "
    assert line.startswith(prefix), line
    return line[len(prefix):]


def test_unknown_key_in_a_file_has_the_command_lines_message(tmp_path):
    f = tmp_path / "my.toml"
    f.write_text("[growth]\nsteps = 10\n[tropism]\nbta = 0.2\n")
    want = cli_error("run", f, "--out", tmp_path / "o")
    assert want == f"{f}:4: unknown key tropism.bta (did you mean tropism.beta?)"
    with pytest.raises(ValueError) as e:
        rootsim.run(f, out=tmp_path / "o")
    assert str(e.value) == want
    assert isinstance(e.value, rootsim.SceneError)
    with pytest.raises(ValueError) as e:
        rootsim.Scene.load(f)
    assert str(e.value) == want
    assert not (tmp_path / "o").exists() and not (tmp_path / "o.partial").exists()  # a bad scene writes nothing


def test_bad_override_has_the_command_lines_message(tmp_path):
    scene = SOURCE / "scenes/fig2b_waving.toml"
    want = cli_error("run", scene, "--set", "tropism.bta=0.2", "--out", tmp_path / "o")
    with pytest.raises(ValueError) as e:
        rootsim.run(scene, set={"tropism.bta": 0.2}, out=tmp_path / "o")
    assert str(e.value) == want == "--set tropism.bta=0.2: unknown key tropism.bta (did you mean tropism.beta?)"
    want = cli_error("run", scene, "--set", "plane.alpha_deg=120", "--out", tmp_path / "o")
    sc = rootsim.Scene.load(scene)
    with pytest.raises(ValueError) as e:
        sc.set("plane.alpha_deg", 120)
    assert str(e.value) == want
    sc.set("plane.alpha_deg", 60)  # a failed set changed nothing; a good one is applied
    assert sc.overrides == ["plane.alpha_deg=60"]
    assert "alpha_deg = 60" in sc.to_toml()


def test_scene_check_gives_the_theory_of_rootsim_check():
    sc = rootsim.Scene.load(SOURCE / "scenes/fig2b_waving.toml")
    t = sc.check()
    out = cli("check", SOURCE / "scenes/fig2b_waving.toml").stdout
    assert sc.to_toml() in out
    assert t and all(f'"{k}"' in out for k in t)
    assert rootsim.Scene.load(SOURCE / "scenes/cantilever_tip_load.toml").check() == {}


def test_output_folder_that_is_not_a_run_is_refused(tmp_path):
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "notes.txt").write_text("mine")
    scene = SOURCE / "scenes/fig2a_alpha40.toml"
    want = cli_error("run", scene, "--set", "growth.steps=5", "--out", tmp_path / "mine", "--force")
    with pytest.raises(ValueError) as e:
        rootsim.run(scene, set={"growth.steps": 5}, out=tmp_path / "mine", force=True)
    assert str(e.value) == want
    assert (tmp_path / "mine" / "notes.txt").read_text() == "mine"


def test_failed_run_raises_runtime_error_naming_the_node(tmp_path):
    # a free 1 mm rod on a plate tilted by 60 deg, mu_s below cot(60 deg): no static equilibrium
    # (the scene of test_cli.cpp's "slides" case)
    f = tmp_path / "slide.toml"
    f.write_text("[root]\ninitial_length_mm = 1\n[growth]\nenabled = false\n[plane]\nalpha_deg = 60\n"
                 "[adhesion]\nenabled = false\n[load]\nbase = \"free\"\ngravity = true\n[friction]\n"
                 "enabled = true\nmu_static = 0.55\nmu_kinetic = 0.5\n[solver]\nforce_tol = 1e-9\n")
    r = cli("run", f, "--quiet", "--out", tmp_path / "cli", check=False)
    assert r.returncode == 1
    with pytest.raises(RuntimeError) as e:
        rootsim.run(f, out=tmp_path / "py")
    assert isinstance(e.value, rootsim.RunError)
    msg = str(e.value)
    assert "slides: no static equilibrium" in msg and "node " in msg
    assert r.stderr.strip().splitlines()[-1] == "rootsim: run failed: " + msg
    assert (tmp_path / "py.incomplete" / "ERROR.txt").read_text().strip() == msg


def test_growth_failure_names_the_growth_step_and_node(tmp_path):
    # the explicit relaxation capped at 10 sub-steps cannot reach equilibrium in the first growth step
    scene = SOURCE / "scenes/fig2b_waving.toml"
    sets = {"growth.steps": 20, "solver.kind": "dynamic", "solver.max_substeps": 10}
    r = cli("run", scene, *[a for k, v in sets.items() for a in ("--set", f"{k}={v}")], "--quiet", "--out",
            tmp_path / "cli", check=False)
    assert r.returncode == 1
    with pytest.raises(RuntimeError) as e:
        rootsim.run(scene, set=sets, out=tmp_path / "py")
    assert r.stderr.strip().splitlines()[-1] == "rootsim: run failed: " + str(e.value)
    assert str(e.value).startswith("growth step 1 (") and " at node " in str(e.value)
    assert (tmp_path / "py.incomplete" / "ERROR.txt").is_file()
    # the stepping API raises the same
    sim = rootsim.Simulation(scene, set=sets)
    with pytest.raises(rootsim.RunError, match=r"^growth step 1 \(.* at node "):
        sim.step()


def test_help_is_useful():
    import pydoc
    text = pydoc.render_doc(rootsim.run, renderer=pydoc.plaintext)
    for word in ("scene_or_path", "set", "out", "progress", "KeyboardInterrupt", "SceneError", "RunError", ".partial"):
        assert word in text, word
    for f in (rootsim.load_run, rootsim.sweep, rootsim.render, rootsim.Scene.load, rootsim.Scene.set,
              rootsim.Simulation, rootsim.Simulation.step, rootsim.Simulation.state):
        assert f.__doc__ and len(f.__doc__) > 40, f
