"""Every command of the command line is a Python function whose keywords are the command's flags: the
flags `rootsim COMMAND --help` lists, each a keyword of rootsim.COMMAND named as the flag ('-' as '_',
--no-X as X=False), and nothing else but the Python-only arguments named here. Valued options default to
None (the command's own default, never a copy of it)."""
import inspect
import re

import pytest

import rootsim
from conftest import cli

# arguments a Python function has beyond its command's flags, and why
PYTHON_ONLY = {
    "run": {"progress"},              # a callback between growth steps
    "sweep": {"scene", "grid", "set"},  # a sweep given in Python instead of a sweep file
}
# the Python name of a positional whose flag name would shadow what the function takes
POSITIONAL_NAMES = {("run", "scene"): "scene_or_path", ("sweep", "sweep"): "sweep_file"}
# a further positional the Python function takes as a list in another argument: fit's more RSML files
# (`fit A.rsml B.rsml --groups ...`) are rootsim.fit's trace given as a list
FOLDED_INTO = {("fit", "more"): "trace"}
COMMANDS = ["run", "check", "render", "modes", "export", "analyze", "compare", "fit", "montage", "sweep", "figure"]


def cli_options(command):
    """(python name, negated, positional, required) of every option `rootsim COMMAND --help` lists."""
    text = cli(command, "--help").stdout
    out = []
    section = None
    for line in text.splitlines():
        if re.match(r"^\S.*:\s*$", line):
            section = line.strip().rstrip(":").upper()
            continue
        m = re.match(r"^  ((?:-\w,)?--[\w-]+|\w+)\b(.*)$", line)  # a continued help line is indented further
        if not m or section not in ("POSITIONALS", "OPTIONS"):
            continue
        flag = m.group(1).split(",")[-1]
        if flag == "--help":
            continue
        name = flag.lstrip("-")
        negated = name.startswith("no-") and "TEXT" not in m.group(2) and "INT" not in m.group(2)
        if negated:
            name = name[3:]
        positional = not flag.startswith("-")
        py = POSITIONAL_NAMES.get((command, name), name.replace("-", "_"))
        out.append((py, negated, positional, "REQUIRED" in m.group(2)))
    return out


def test_the_command_line_lists_every_command():
    text = cli("--help").stdout
    listed = re.findall(r"^  (\w+)\s{2,}", text.split("Subcommands:")[1], re.M)
    assert sorted(listed) == sorted(COMMANDS)


@pytest.mark.parametrize("command", COMMANDS)
def test_python_keywords_are_the_command_flags(command):
    sig = inspect.signature(getattr(rootsim, command))
    params = sig.parameters
    options = cli_options(command)
    assert options, f"rootsim {command} --help lists no options"
    for (c, name), into in FOLDED_INTO.items():
        if c == command:
            assert into in params, f"{command}: {name} goes into {into}"
    options = [o for o in options if (command, o[0]) not in FOLDED_INTO]
    names = {o[0] for o in options}
    assert set(params) == names | PYTHON_ONLY.get(command, set()), command
    for py, negated, positional, required in options:
        p = params[py]
        if positional:
            assert p.kind == p.POSITIONAL_OR_KEYWORD, f"{command}: {py} is the command's positional"
            continue
        assert p.kind == p.KEYWORD_ONLY, f"{command}: {py} is a keyword (options are keywords only)"
        if required:
            assert p.default is p.empty, f"{command}: {py} is required, as the command's flag"
        elif py == "quiet":
            assert p.default is True, f"{command}: a library call prints nothing unless asked"
        elif negated:
            assert p.default is True, f"{command}: {py}=False is --no-{py}"
        else:
            assert p.default in (None, False), f"{command}: {py} defaults to {p.default!r}, a copy of the command's default"


def test_the_binding_table_agrees_with_the_command_line():
    # the keywords the C++ binding reads are the command line's flags (one table: src/cli/options.hpp)
    table = rootsim._rootsim.command_table()
    assert sorted(table) == sorted(COMMANDS)
    for command in COMMANDS:
        assert [t[0] for t in table[command]] == [o[0] for o in cli_options(command)], command


def test_an_unknown_keyword_is_named():
    with pytest.raises(TypeError, match="colour"):
        rootsim.modes("nowhere", colour="red")
    with pytest.raises(ValueError, match="modes: unknown option colour"):
        rootsim._rootsim.modes({"run_dir": "nowhere", "colour": "red"})
    with pytest.raises(ValueError, match="modes: option count has the wrong type"):
        rootsim._rootsim.modes({"run_dir": "nowhere", "count": "six"})
    # the command line's checks, from the same table
    with pytest.raises(ValueError, match="modes: --count: Value 0 not in range 1 to 1000"):
        rootsim.modes("nowhere", count=0)
    with pytest.raises(ValueError, match="sweep: --jobs: Value 0 not in range 1 to 1024"):
        rootsim.sweep("nowhere.toml", jobs=0)


def test_check_is_the_command_line_check(scenes):
    got = rootsim.check(scenes / "fig2b_waving.toml", set={"plane.alpha_deg": 30})
    assert "alpha_deg = 30" in got["resolved_toml"]
    assert got["theory"]
    out = cli("check", scenes / "fig2b_waving.toml", "--set", "plane.alpha_deg=30").stdout
    assert got["resolved_toml"] in out
    with pytest.raises(ValueError, match="plane.alpha_deg must be in"):
        rootsim.check(scenes / "fig2b_waving.toml", set={"plane.alpha_deg": 120})


SMALL = {"growth.steps": 20, "output.every_steps": 10}


@pytest.mark.skipif(not rootsim._rootsim.have_render, reason="built without the renderer")
def test_run_takes_the_movie_flags(scenes, tmp_path):
    with pytest.raises(ValueError, match="shape the movie; add --movie"):
        rootsim.run(scenes / "fig2b_waving.toml", set=SMALL, out=tmp_path / "no", camera="follow")
    assert not (tmp_path / "no").exists() and not (tmp_path / "no.partial").exists()
    r = rootsim.run(scenes / "fig2b_waving.toml", set=SMALL, out=tmp_path / "m", movie=True, camera="follow")
    assert (r.dir / "movie.mp4").stat().st_size > 0 and (r.dir / "final_top.png").stat().st_size > 0


def test_modes_is_the_command_line_modes(scenes, tmp_path):
    cli("run", scenes / "fig2b_waving.toml", *[f"--set={k}={v}" for k, v in SMALL.items()], "--out",
        tmp_path / "c", "--quiet")
    cli("modes", tmp_path / "c", "--count", "2", "--quiet")
    r = rootsim.run(scenes / "fig2b_waving.toml", set=SMALL, out=tmp_path / "p")
    written = rootsim.modes(r.dir, count=2)
    assert written == [r.dir / "modes.csv", r.dir / "modes.vtp"]
    assert (r.dir / "modes.csv").read_bytes() == (tmp_path / "c" / "modes.csv").read_bytes()
