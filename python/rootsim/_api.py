"""The user-facing API of the rootsim package (docs/python.md); the C++ work is done by _rootsim."""
from __future__ import annotations

import json
import math
import numbers
import os
import pathlib
import re
import tempfile
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, Callable, Dict, Iterator, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _rootsim as _c

SceneError = _c.SceneError
RunError = _c.RunError
SceneError.__module__ = "rootsim"
RunError.__module__ = "rootsim"

PathLike = Union[str, "os.PathLike[str]"]
Value = Union[bool, int, float, str, Sequence[Any]]

_BARE = re.compile(r"[A-Za-z0-9_.+-]+")


def _value_text(key: str, v: Any) -> str:
    """A Python value as the TOML text `--set key=...` takes."""
    if isinstance(v, (bool, np.bool_)):
        return "true" if v else "false"
    if isinstance(v, numbers.Integral):
        return str(int(v))
    if isinstance(v, numbers.Real):
        f = float(v)
        if math.isnan(f):
            return "nan"
        if math.isinf(f):
            return "inf" if f > 0 else "-inf"
        return repr(f)  # the shortest text that reads back as the same double
    if isinstance(v, str):
        return v if _BARE.fullmatch(v) else json.dumps(v)  # bare words as on the command line
    if isinstance(v, (list, tuple, np.ndarray)):
        return "[" + ",".join(_value_text(key, x) for x in v) + "]"
    raise TypeError(f"set[{key!r}]: expected a bool, number, string or list (got {type(v).__name__})")


def _overrides(values: Optional[Mapping[str, Value]]) -> List[str]:
    if values is None:
        return []
    if not isinstance(values, Mapping):
        raise TypeError(f"set: expected a dict of scene keys to values (got {type(values).__name__})")
    out = []
    for k, v in values.items():
        if not isinstance(k, str):
            raise TypeError(f"set: keys are 'section.key' strings (got {k!r})")
        out.append(f"{k}={_value_text(k, v)}")
    return out


def _options(args: Mapping[str, Any]) -> Dict[str, Any]:
    """A function's arguments as its command's options, by keyword: the C++ binding reads them through the
    command's option table (src/cli/options.hpp: the command line's flags), so names, defaults and checks
    are the command line's. None leaves an option at the command's default; paths become text."""
    return {k: os.fspath(v) if isinstance(v, os.PathLike) else v for k, v in args.items()}


def _need_render(command: str) -> None:
    if not _c.have_render:
        raise SceneError(f"{command}: this rootsim was built without the renderer and the app library "
                         "(ROOTSIM_BUILD_RENDER=OFF)")


# ---------------------------------------------------------------------------------------------------
# scenes


class Scene:
    """A validated scene: a TOML file (or text) plus overrides, checked against the key schema.

    Every change is validated at once: a bad key or value raises ``rootsim.SceneError`` (a ``ValueError``)
    with the command line's message, e.g. ``my.toml:3: unknown key tropism.bta (did you mean
    tropism.beta?)`` or ``--set plane.alpha_deg=120: plane.alpha_deg must be in [0, 90] (got 120)``.

    Units: the scene keys' own, named in each key (plane.alpha_deg in degrees, root.radius_mm in mm,
    growth.step_h in hours; docs/cli.md lists them); values are given and read back in them.
    """

    def __init__(self, _scene: Any, _path: Optional[str], _text: Optional[str], _overrides: List[str],
                 _source: str = ""):
        self._scene = _scene
        self._path = _path
        self._text = _text  # for a scene from text: the text and the name it was given
        self._source = _source
        self._overrides = list(_overrides)

    @classmethod
    def load(cls, path: PathLike, *, set: Optional[Mapping[str, Value]] = None) -> "Scene":
        """Reads and validates a scene file; ``set`` overrides keys ({"plane.alpha_deg": 60}).

        Units: the scene keys' own, named in each key (plane.alpha_deg, root.radius_mm, growth.step_h)."""
        p = os.fspath(path)
        ov = _overrides(set)
        return cls(_c.load_scene(p, ov), p, None, ov)

    @classmethod
    def from_toml(cls, text: str, *, name: str = "scene", set: Optional[Mapping[str, Value]] = None) -> "Scene":
        """A scene from TOML text; ``name`` plays the file's part in messages and names the run.

        Units: the scene keys' own, named in each key (plane.alpha_deg, root.radius_mm, growth.step_h)."""
        ov = _overrides(set)
        return cls(_c.parse_scene(text, name, ov), None, text, ov, name)

    def _parse(self, overrides: List[str]) -> Any:
        if self._path is not None:
            return _c.load_scene(self._path, overrides)
        return _c.parse_scene(self._text, self._source, overrides)

    def set(self, key: str, value: Value) -> "Scene":
        """Overrides one key (validated now, as ``--set key=value``); returns the scene itself.

        Units: the key's own, named in it (``scene.set("plane.alpha_deg", 60)``: degrees)."""
        ov = self._overrides + _overrides({key: value})
        self._scene = self._parse(ov)
        self._overrides = ov
        return self

    def copy(self) -> "Scene":
        return Scene(self._scene, self._path, self._text, self._overrides, self._source)

    def to_toml(self) -> str:
        """Every key with its value, defaults filled in: the scene.toml a run directory holds.

        Units: the scene keys' own, named in each key."""
        return self._scene.resolved_toml

    def check(self) -> Dict[str, Any]:
        """Validates the scene again (from its file) and returns the theory's predictions for it
        (docs/model.md, Theory: the block ``rootsim check`` prints; empty for a mechanics-only scene).

        Units: named in each key, as in summary.json (``wavelength_mm_eq9``, ``alpha_..._deg_eq12``)."""
        self._scene = self._parse(self._overrides)
        t = _c.theory_json(self._scene)
        return {} if t is None else json.loads(t)

    @property
    def name(self) -> str:
        """The scene's name (its file's stem): the default run directory's name."""
        return self._scene.name

    @property
    def path(self) -> Optional[str]:
        """The file it was read from (None for text)."""
        return self._path

    @property
    def overrides(self) -> List[str]:
        """The overrides applied, as ``key=value`` texts (what ``--set`` takes)."""
        return list(self._overrides)

    @property
    def steps(self) -> int:
        """Growth steps the scene runs (0 for a mechanics-only scene)."""
        return self._scene.steps

    def __repr__(self) -> str:
        src = self._path if self._path is not None else "<text>"
        return f"rootsim.Scene({src!r}, overrides={self._overrides!r})"


def _scene_of(scene_or_path: Union[Scene, PathLike], set: Optional[Mapping[str, Value]]) -> Scene:
    if isinstance(scene_or_path, Scene):
        sc = scene_or_path.copy()
        for k, v in (set or {}).items():
            sc.set(k, v)
        return sc
    return Scene.load(scene_or_path, set=set)


# ---------------------------------------------------------------------------------------------------
# run directories


_UNITS_RENAME = "the package's units are the files': mm, h, deg, N; docs/python.md, Units"


def _renamed(cls_name: str, renames: Mapping[str, str],
             why: Optional[Mapping[str, str]] = None) -> Callable[[Any, str], Any]:
    """A __getattr__ naming the field an old name became (why: the reason per name; default the units)."""

    def __getattr__(self: Any, name: str) -> Any:
        if name in renames:
            reason = (why or {}).get(name, _UNITS_RENAME)
            raise AttributeError(f"{cls_name}.{name} was renamed {renames[name]} ({reason})")
        raise AttributeError(f"{cls_name!r} object has no attribute {name!r}")

    return __getattr__


@dataclass(frozen=True)
class Frame:
    """One snapshot of the trajectory (trajectory.bin or trajectory.csv: what ``rootsim render`` draws).

    Units: those of trajectory.csv (lengths mm, time h, curvatures 1/mm, forces N), named in each field.

    ``positions_mm`` node positions, lab frame [mm] (nodes x 3); ``lateral_mm``, ``downhill_mm``,
    ``height_mm`` the same nodes in plate coordinates [mm] (nodes each; see below); ``d1``, ``d3``
    element directors, lab frame, unit vectors (elements x 3; d2 = d3 x d1); ``radius_mm`` element radius
    R/sqrt(lambda_e) [mm] (elements); ``kappa0_per_mm`` |intrinsic curvature| per node [1/mm] and
    ``plate_force_n`` the plate's normal force per node [N] (nodes), and ``contact_force_n`` |plate|,
    |self|, |obstacle| contact force per node [N] (nodes x 3): None when the trajectory predates them.

    Plate coordinates: ``PlateFrame::coords`` of the scene's plate, tilted by plane.alpha_deg from the
    vertical: lateral along the plate's lateral axis (lab x), downhill along the plate's downhill line,
    height along its normal, with the origin at the foot of the base node on the plate (the root starts
    at lateral = downhill = 0, height = R). Plot (lateral_mm, downhill_mm) for the plate as seen from
    above; lab x-y is squashed by sin(alpha). A scene without the plate (plane.enabled = false, a free
    organ) has the same frame, the one the plate would have: the initial root lies along downhill, and
    gravity is still lab -z (for alpha = 0, downhill is straight down).
    """

    step: int
    time_h: float
    positions_mm: np.ndarray
    lateral_mm: np.ndarray
    downhill_mm: np.ndarray
    height_mm: np.ndarray
    d1: np.ndarray
    d3: np.ndarray
    radius_mm: np.ndarray
    kappa0_per_mm: Optional[np.ndarray]
    plate_force_n: Optional[np.ndarray]
    contact_force_n: Optional[np.ndarray]

    __getattr__ = _renamed("Frame", {"x": "positions_mm", "radius": "radius_mm", "kappa0": "kappa0_per_mm",
                                     "plate_force": "plate_force_n", "contact_force": "contact_force_n"})


_PLATE_COLUMNS = ("lateral_mm", "downhill_mm", "height_mm")


class Run:
    """A run directory and what it holds, read on first access through rootsim's own C++ readers.

    Units: the files' (lengths mm, time h, angles deg, curvatures 1/mm, forces N), named in every column
    and field; nothing to convert.

    - ``dir``: the directory (``pathlib.Path``)
    - ``timeseries``: dict column name -> numpy float64 array, the columns of timeseries.csv (step,
      time_h, length_mm, theta_tip_deg, Eb, Et, Wr, Tw, ...): the very doubles the file holds
    - ``shape``: dict column name -> array, the final centreline of shape.csv (s_mm, x_mm, y_mm, z_mm,
      ..., radius_mm) and its plate coordinates lateral_mm, downhill_mm, height_mm (shape.csv's own
      columns where it has them, else computed from x_mm, y_mm, z_mm as ``Frame``'s)
    - ``frames``: list of ``Frame``, one per snapshot of the trajectory (trajectory.bin or .csv), with
      plate coordinates
    - ``summary``: summary.json as a dict; ``result``: the row of result.csv (a sweep table's columns)
    - ``scene``: the resolved scene.toml as a ``Scene`` (its keys in the scene keys' units: alpha_deg, ...)

    A run made with ``out=None`` lives in a temporary directory that is deleted when the Run object is
    garbage-collected: keep the object (or pass ``out=``) as long as you need the files.
    """

    def __init__(self, dir: PathLike, _tmp: Optional[tempfile.TemporaryDirectory] = None):
        self.dir = pathlib.Path(dir)
        self._tmp = _tmp  # keeps a temporary run directory alive as long as this object

    @cached_property
    def timeseries(self) -> Dict[str, np.ndarray]:
        """timeseries.csv's columns. Units: named in each column (time_h, length_mm, theta_tip_deg, ...)."""
        self._one_root("timeseries")
        return _c.read_csv(str(self.dir / "timeseries.csv"))

    @cached_property
    def shape(self) -> Dict[str, np.ndarray]:
        """shape.csv's columns and lateral_mm, downhill_mm, height_mm (plate coordinates, as ``Frame``'s).

        Units: named in each column (s_mm, x_mm, kappa1_per_mm, radius_mm; stretch and directors are
        dimensionless)."""
        self._one_root("shape")
        cols = _c.read_csv(str(self.dir / "shape.csv"))
        if not all(c in cols for c in _PLATE_COLUMNS):  # an older shape.csv: the same coordinates, here
            lab = np.column_stack([cols["x_mm"], cols["y_mm"], cols["z_mm"]])
            plate = _c.plate_coords(self.scene._scene, lab)
            for k, c in enumerate(_PLATE_COLUMNS):
                cols.setdefault(c, np.ascontiguousarray(plate[:, k]))
        return cols

    @cached_property
    def frames(self) -> List[Frame]:
        """The trajectory's snapshots. Units: trajectory.csv's (mm, h, 1/mm, N), named in each field."""
        self._one_root("frames")
        return [Frame(**f) for f in _c.read_trajectory(str(self.dir / "trajectory.csv"), self.scene._scene)]

    @cached_property
    def summary(self) -> Dict[str, Any]:
        """summary.json. Units: named in each key (wavelength_mm, wall_time_s, ...)."""
        with open(self.dir / "summary.json", encoding="utf-8") as f:
            return json.load(f)

    @cached_property
    def result(self) -> Dict[str, Any]:
        """result.csv's row. Units: named in each column, as the sweep table's."""
        self._one_root("result")
        return _c.read_result(str(self.dir / "result.csv"))

    @cached_property
    def scene(self) -> Scene:
        """The resolved scene.toml. Units: the scene keys' own (plane.alpha_deg, root.radius_mm, ...)."""
        # the resolved scene.toml, named as the run's scene (a file named scene.toml would be "scene")
        text = (self.dir / "scene.toml").read_text(encoding="utf-8")
        return Scene.from_toml(text, name=self.summary.get("scene", "scene"))

    def _one_root(self, what: str) -> None:
        if self.is_plate:
            names = ", ".join(sd["name"] for sd in self.summary["roots"])
            raise SceneError(f"{self.dir}: a plate's run has no {what} of its own; each root's: "
                             f"run.roots[NAME].{what} (roots: {names})")

    @property
    def is_plate(self) -> bool:
        """True for a plate's run (a scene with ``[[seedling]]`` tables, docs/plate.md)."""
        return self.summary.get("kind") == "plate"

    @cached_property
    def roots(self) -> Dict[str, "Run"]:
        """A plate's roots: name -> the ``Run`` of its folder ``roots/NAME``: the seedlings in the scene's
        order, then the lateral roots (``s1.3``: the third lateral of s1) as they emerged. Each is read as a
        run of that root alone (positions in its own frame, its base's foot at the origin; ``plate_roots``
        gives where each is). Empty for a run of one root."""
        if not self.is_plate:
            return {}
        out: Dict[str, Run] = {}
        for sd in self.summary["roots"]:
            r = Run(self.dir / sd["folder"])
            r._tmp = self._tmp  # a temporary plate run stays alive as long as its roots
            out[sd["name"]] = r
        return out

    @property
    def plate_roots(self) -> List[Dict[str, Any]]:
        """A plate's roots as summary.json lists them: name, genotype, parent ("" for a seedling), order,
        emerged_h, set_point_deg, folder, position_lateral_mm, position_downhill_mm, angle_deg, overrides.
        Units: named in each key (mm, deg, h). Empty for one root."""
        return list(self.summary.get("roots", [])) if self.is_plate else []

    def render(self, **options: Any) -> List[pathlib.Path]:
        """``rootsim.render(self.dir, **options)``: keyword options only (units: ``field_mm`` in mm)."""
        return render(self.dir, **options)

    def __repr__(self) -> str:
        return f"rootsim.Run({str(self.dir)!r})"


def load_run(dir: PathLike) -> Run:
    """Opens a complete run directory (written by ``rootsim run``, ``rootsim sweep`` or ``rootsim.run``).

    Raises SceneError when ``dir`` is not one (an interrupted run is ``DIR.partial``, a failed one
    ``DIR.incomplete`` with ERROR.txt).

    Units: the files' (lengths mm, time h, angles deg, forces N), named in each column and field."""
    d = pathlib.Path(dir)
    if not (d / "scene.toml").is_file() or not (d / "summary.json").is_file():
        why = "not a complete run directory (no scene.toml and summary.json)"
        for suffix, what in ((".partial", "an interrupted run"), (".incomplete", "a failed run, see ERROR.txt")):
            if pathlib.Path(str(d) + suffix).is_dir():
                why += f"; {d}{suffix}/ is {what}"
        raise SceneError(f"{d}: {why}")
    return Run(d)


def run(scene_or_path: Union[Scene, PathLike], *, set: Optional[Mapping[str, Value]] = None,
        out: Optional[PathLike] = None, progress: Optional[Callable[[int, int], None]] = None,
        force: bool = False, resume: bool = False, movie: bool = False, camera: Optional[str] = None,
        field_mm: Optional[float] = None, inset: bool = False, color_by: Optional[str] = None,
        plot: Union[str, Sequence[str], None] = None, shadows: bool = False, quiet: bool = True) -> Run:
    """Simulates a scene into a run directory, exactly as ``rootsim run SCENE --set ... --out OUT``.

    Units: ``set`` values are in the scene keys' units (named in the key: plane.alpha_deg is degrees);
    the returned Run's arrays in the files' (lengths mm, time h, angles deg, forces N), named in each
    column and field.

    scene_or_path: a scene file or a ``Scene``. The options are keywords only.
    set: overrides, ``{"plane.alpha_deg": 60, "growth.steps": 100}`` (validated first, as ``--set``).
    out: the run directory; written as ``OUT.partial/`` and renamed when complete. An existing run there
        is replaced only with ``force=True`` (never a folder rootsim did not write). ``None``: a temporary
        directory, deleted when the returned Run is garbage-collected (``run.dir`` tells where it is).
    resume: continue a killed run from its last checkpoint in ``OUT.partial/`` (``--resume``).
    movie, camera, field_mm, inset, color_by, plot, shadows: ``--movie`` and its look, as the command
        line's (movie.mp4 and final_top.png in the run directory; the look without ``movie`` is refused).
    quiet: no progress output on stderr (``quiet=False`` prints the command line's progress).
    progress: called as ``progress(step, total)`` after every growth step (from the calling thread).
        An exception it raises stops the run and propagates; the directory stays ``OUT.partial/``
        (with ``out=None`` the temporary directory is removed: nothing is kept).

    Returns a ``Run`` (``timeseries``, ``shape``, ``frames``, ``summary``, ``result``, ``dir``).
    Raises SceneError (ValueError) for a bad scene, key, value or output path, before anything is
    written; RunError (RuntimeError) when the run fails, naming the growth step and node (the directory
    is then ``OUT.incomplete/`` with ERROR.txt); KeyboardInterrupt on Ctrl-C, after the growth step in
    progress (the directory stays ``OUT.partial/``).

    The GIL is released while simulating: several runs can go on in threads at once.

    Example::

        r = rootsim.run("scenes/fig2a_alpha40.toml", set={"growth.steps": 100})
        r.summary["pattern"], r.timeseries["theta_tip_deg"][-1]
        f = r.frames[-1]; plt.plot(f.lateral_mm, f.downhill_mm)   # the root on the plate, in mm
    """
    if plot is not None and not isinstance(plot, str):
        plot = ",".join(plot)
    # the command's options: every keyword but the scene (made here, with set) and the callback
    options = _options({k: v for k, v in locals().items() if k not in ("scene_or_path", "set", "progress")})
    if progress is not None and not callable(progress):
        raise TypeError(f"progress: expected a callable progress(step, total) (got {type(progress).__name__})")
    scene = _scene_of(scene_or_path, set)
    tmp = None
    if out is None:
        tmp = tempfile.TemporaryDirectory(prefix="rootsim-")
        target = os.path.join(tmp.name, scene.name)
    else:
        target = os.fspath(out)
    options["out"] = target
    try:
        done = _c.run_scene(scene._scene, options, progress)
    except BaseException:
        if tmp is not None:
            tmp.cleanup()
        raise
    return Run(done, tmp)


# ---------------------------------------------------------------------------------------------------
# sweeps


@dataclass
class SweepPoint:
    """One finished point of a sweep: ``index`` in the grid, ``grid`` (key -> value, typed as the TOML
    value of the sweep's grid was: int, float, bool, str or list; ``{"plane.alpha_deg": 20,
    "tropism.beta": 0.2}``), ``dir`` its run directory, ``error`` (None, or why it failed: the directory
    is then DIR.incomplete), ``skipped`` (complete before this sweep started), ``wall_s`` (seconds of
    wall time). ``run`` opens it (``load_run``).

    Units: ``grid`` values are in the scene keys' units (named in the key: plane.alpha_deg in degrees);
    the run's arrays in the files' (mm, h, deg, N), as ``Run``."""

    index: int
    name: str
    grid: Dict[str, Any]
    dir: pathlib.Path
    error: Optional[str]
    skipped: bool
    wall_s: float
    _tmp: Any = field(default=None, repr=False, compare=False)  # keeps a temporary sweep folder alive

    @property
    def ok(self) -> bool:
        return self.error is None

    @property
    def run(self) -> Run:
        if self.error is not None:
            raise RunError(f"{self.name}: {self.error}")
        r = load_run(self.dir)
        r._tmp = self._tmp
        return r


class Sweep:
    """A running sweep (``rootsim.sweep``): iterate it for the points as they finish.

    ``out`` is the sweep folder, ``table`` its table.csv (written when the sweep ends), ``summary``
    the counts (ran, skipped, failed, interrupted) once it is over; ``cancel()`` stops it (running points
    stop between growth steps and stay DIR.partial). Also a context manager that cancels on exit.

    Units: as ``SweepPoint`` (grid values in the scene keys' units; runs in the files': mm, h, deg, N).
    """

    def __init__(self, runner: Any, out: str, tmp: Any, keep: Any, _grid: Optional[Dict[str, list]] = None):
        self._runner = runner
        self.out = pathlib.Path(out)
        self._tmp = tmp
        self._keep = keep  # the generated sweep file's folder, alive while the sweep runs
        self._grid = _grid  # the sweep file's [grid] arrays as TOML values (None: not readable here)
        self._over = False

    def __iter__(self) -> "Sweep":
        return self

    def __next__(self) -> SweepPoint:
        if self._over:
            raise StopIteration
        try:
            d = self._runner.next()
        except BaseException:
            self.cancel()
            raise
        if d is None:
            self._over = True
            raise StopIteration
        return SweepPoint(d["index"], d["name"], _typed_grid(d["index"], d["grid"], self._grid),
                          pathlib.Path(d["dir"]), d["error"], d["skipped"], d["wall_s"], self._tmp)

    def cancel(self) -> None:
        if not self._over:
            self._over = True
            self._runner.cancel()

    @property
    def table(self) -> pathlib.Path:
        return self.out / "table.csv"

    @property
    def summary(self) -> Dict[str, Any]:
        return self._runner.summary()

    def __enter__(self) -> "Sweep":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.cancel()


def sweep(sweep_file: Optional[PathLike] = None, *, scene: Union[Scene, PathLike, None] = None,
          grid: Optional[Mapping[str, Sequence[Value]]] = None, set: Optional[Mapping[str, Value]] = None,
          out: Optional[PathLike] = None, jobs: Optional[int] = None, shard: Optional[str] = None, force: bool = False,
          quiet: bool = True) -> Sweep:
    """Runs a grid of scenes, as ``rootsim sweep``, and yields each point as it finishes.

    Either a sweep file (``rootsim.sweep("sweeps/fig3d_phase.toml", jobs=2)``) or the same in Python:
    ``rootsim.sweep(scene="scenes/fig2a_alpha40.toml", grid={"plane.alpha_deg": [20, 60]},
    set={"growth.steps": 200})`` (every combination of the grid, first key slowest; ``set`` fixed).
    Every point is validated before any runs (SceneError naming the point and key). The options are
    keywords only.

    Units: ``grid`` and ``set`` values are in the scene keys' units (named in the key: plane.alpha_deg
    in degrees, growth.step_h in hours); each point's Run in the files' (mm, h, deg, N).

    out: the sweep folder (one run directory per point, table.csv); resumable: points already complete
        there are not run again (they are yielded with ``skipped=True``). ``None``: a temporary folder,
        deleted when the Sweep and every point taken from it are garbage-collected.
    jobs: parallel runs (threads; the GIL is not held while simulating; default: the command line's).
    shard: "K/N", as ``--shard``. quiet: False prints the command line's line per point on stderr.

    Returns a ``Sweep``: ``for p in rootsim.sweep(...): print(p.grid, p.run.summary["pattern"])``.
    Ctrl-C while iterating stops the sweep (KeyboardInterrupt); leaving the loop early (break) does not:
    call ``cancel()`` or use ``with rootsim.sweep(...) as s:``.
    """
    if (sweep_file is None) == (scene is None):
        raise TypeError("sweep: give either a sweep file or scene= (with grid= and set=)")
    if sweep_file is None and not grid:
        raise TypeError("sweep: scene= needs grid= (a dict of key -> list of values)")
    if sweep_file is not None and (grid is not None or set is not None):
        raise TypeError("sweep: grid= and set= go with scene=; a sweep file has its own [grid] and [set]")
    keep = None
    if sweep_file is None:
        # the same plan as a sweep file: written to a temporary folder and read by the C++ loader
        keep = tempfile.TemporaryDirectory(prefix="rootsim-sweep-")
        if isinstance(scene, Scene):
            base = os.path.join(keep.name, scene.name + ".toml")
            with open(base, "w", encoding="utf-8") as f:
                f.write(scene.to_toml())
        else:
            base = os.path.abspath(os.fspath(scene))
        lines = ["[sweep]", f"scene = {json.dumps(base)}", "[grid]"]
        for key, values in grid.items():
            if isinstance(values, (str, bytes)) or not isinstance(values, (Sequence, np.ndarray)):
                raise TypeError(f"grid[{key!r}]: expected a list of values")
            lines.append(f"{json.dumps(key)} = [{', '.join(_toml_literal(key, v) for v in values)}]")
        lines.append("[set]")
        for key, v in (set or {}).items():
            lines.append(f"{json.dumps(key)} = {_toml_literal(key, v)}")
        sweep_path = os.path.join(keep.name, "sweep.toml")
        with open(sweep_path, "w", encoding="utf-8") as f:
            f.write("\n".join(lines) + "\n")
    else:
        sweep_path = os.fspath(sweep_file)
    tmp = None
    if out is None:
        tmp = tempfile.TemporaryDirectory(prefix="rootsim-")
        out = os.path.join(tmp.name, "sweep")
    grid_arrays = _grid_arrays(sweep_path)  # read before the C++ reads it
    runner = _c._SweepRunner(_options(dict(sweep_file=sweep_path, out=out, jobs=jobs, shard=shard, force=force,
                                           quiet=quiet)))
    return Sweep(runner, os.fspath(out), tmp, keep, grid_arrays)


# The C++ sweep reports a point's grid values as text (the text --set takes); the Python API gives them
# typed as the sweep file's TOML values: the point's values are picked from the file's [grid] arrays by
# its index (every combination, first key slowest, keys in the order the point lists them), each
# checked against its text; a value that cannot be (no tomllib, an unreadable file) is read from its text.

_MISSING = object()


def _grid_arrays(sweep_path: str) -> Optional[Dict[str, list]]:
    """The [grid] arrays of a sweep file as TOML values, or None when it cannot be read here."""
    try:
        import tomllib
    except ImportError:  # Python < 3.11
        return None
    try:
        with open(sweep_path, "rb") as f:
            doc = tomllib.load(f)
    except (OSError, ValueError):  # the C++ loader reports it, with its message
        return None
    g = doc.get("grid")
    if not isinstance(g, dict):
        return None
    return {k: v for k, v in g.items() if isinstance(v, list) and v}


def _value_of_text(text: str) -> Any:
    """A grid value's text as a TOML value when it reads as a number, boolean or array; else the string."""
    if text in ("true", "false"):
        return text == "true"
    try:
        import tomllib

        v = tomllib.loads(f"v = {text}")["v"]
        if isinstance(v, (bool, int, float, list)):
            return v
    except ImportError:
        for conv in (int, float):
            try:
                return conv(text)
            except ValueError:
                pass
    except ValueError:
        pass
    return text


def _matches(v: Any, text: str) -> bool:
    """Whether the TOML value v is the one the C++ wrote as text."""
    if isinstance(v, bool):
        return text == ("true" if v else "false")
    if isinstance(v, int):
        try:
            return int(text) == v
        except ValueError:
            return False
    if isinstance(v, float):
        try:
            f = float(text)
        except ValueError:
            return False
        return f == v or (math.isnan(f) and math.isnan(v))
    if isinstance(v, str):
        return text == v
    return isinstance(v, list) and text.startswith("[")


def _typed_grid(index: int, grid: Mapping[str, str], arrays: Optional[Dict[str, list]]) -> Dict[str, Any]:
    picked: Dict[str, Any] = {}
    keys = list(grid)
    if arrays is not None and all(k in arrays for k in keys):
        rem = int(index)
        for k in reversed(keys):
            picked[k] = arrays[k][rem % len(arrays[k])]
            rem //= len(arrays[k])
        if rem != 0:  # not a point of these arrays
            picked = {}
    out: Dict[str, Any] = {}
    for k, text in grid.items():
        v = picked.get(k, _MISSING)
        out[k] = v if v is not _MISSING and _matches(v, text) else _value_of_text(text)
    return out


def _toml_literal(key: str, v: Any) -> str:
    """A TOML value literal (strings always quoted) for a generated sweep file."""
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_toml_literal(key, x) for x in v) + "]"
    return _value_text(key, v)


# ---------------------------------------------------------------------------------------------------
# pictures


def render(run_dir: PathLike, *, mp4: Optional[PathLike] = None, png_dir: Optional[PathLike] = None,
           final_png: Optional[PathLike] = None, png: Optional[PathLike] = None, at_h: Optional[float] = None,
           frame: Optional[int] = None, from_h: Optional[float] = None, to_h: Optional[float] = None,
           hours_per_second: Optional[float] = None, view: Optional[str] = None, size: Optional[str] = None,
           fps: Optional[int] = None, crf: Optional[int] = None, whiskers: bool = False, transparent: bool = False,
           overlays: bool = True, shader_dir: Optional[PathLike] = None, camera: Optional[str] = None,
           field_mm: Optional[float] = None, inset: bool = False, color_by: Optional[str] = None,
           plot: Union[str, Sequence[str], None] = None, shadows: bool = False, trace: Optional[PathLike] = None,
           trace_root: Optional[str] = None, trace_px_per_mm: Optional[float] = None,
           trace_downhill: Union[str, float, None] = None, root: Optional[str] = None, plate_view: bool = False,
           whole_plate: bool = False, scan: Optional[float] = None, force: bool = False, quiet: bool = True) -> List[pathlib.Path]:
    """Renders a saved run, as ``rootsim render RUN_DIR`` with the same options (the same C++ code).

    ``trace``: a traced root (RSML) drawn over every frame, aligned at the run's seed (``--trace``; its
    ``trace_root``, ``trace_px_per_mm``, ``trace_downhill`` as ``--trace-root`` ...; docs/experiments.md).

    Writes only what is asked for: ``mp4`` (H.264 movie), ``png_dir`` (every frame as PNG), ``final_png``
    (the movie's last frame, the same look); with none of them, RUN_DIR/movie.mp4 and RUN_DIR/final_top.png.
    A still: ``png`` with ``at_h`` (the snapshot nearest that growth time, ties to the earlier) or ``frame``
    (the movie's frame number): the movie's frame with these options, pixel for pixel. ``from_h``/``to_h``
    keep the snapshots in [from_h, to_h]; ``hours_per_second`` paces the movie (growth hours per second
    at ``fps``; as ``--hours-per-second``).
    view "top" | "3d"; size "WxH" (even) or "auto"; camera "fit" | "follow" (``field_mm`` wide);
    ``inset``; color_by none|curvature|kappa1|kappa2|twist|kappa0|stretch|contact; plot: any of theta_tip, Eb, Et, Wr,
    Tw (a list or "a,b"); ``shadows``; ``whiskers``; ``transparent`` (PNG frames only);
    ``overlays=False`` is ``--no-overlays``. An output that exists is replaced only if rootsim wrote it
    and ``force=True`` (the command line's write rule). Returns the files and folders written.
    Bad options raise SceneError with the command line's message; render failures RunError. The options
    are keywords only: a positional option or an unknown keyword raises TypeError naming it.

    A plate's run: ``root`` (the root drawn last, the one ``camera="follow"`` follows), ``plate_view``
    (the sown area with a margin, the plate outlined; ``whole_plate`` the whole plate), ``scan`` (a scanner's picture at that many px/mm, into ``png``).
    An option left at None is the command line's default (``rootsim render --help``, docs/cli.md).

    Units: ``field_mm`` in mm (the camera's field of view, as ``--field-mm``); ``fps`` frames per second.
    """
    _need_render("render")
    if plot is not None and not isinstance(plot, str):
        plot = ",".join(plot)
    _c.render_run(_options(locals()))
    if png is not None:
        return [pathlib.Path(png)]
    if mp4 is None and png_dir is None and final_png is None:
        d = pathlib.Path(run_dir)
        return [d / "movie.mp4", d / "final_top.png"]
    return [pathlib.Path(p) for p in (mp4, png_dir, final_png) if p is not None]


def montage(run_dirs: Sequence[PathLike], *, mp4: Optional[PathLike] = None, png_dir: Optional[PathLike] = None,
            size: Optional[str] = None, labels: Union[str, Sequence[str], None] = None, view: Optional[str] = None,
            fps: Optional[int] = None, crf: Optional[int] = None, color_by: Optional[str] = None,
            shadows: bool = False, force: bool = False, quiet: bool = True) -> List[pathlib.Path]:
    """Several runs side by side on one scale and one clock, as ``rootsim montage RUN_DIR...`` (the same C++
    code): ``mp4`` (H.264 movie) and/or ``png_dir`` (every frame as PNG); ``labels`` one per run (a list
    or "a,b"; default the scene keys that differ); ``size``, ``view``, ``fps``, ``crf``, ``color_by``,
    ``shadows`` as ``render``'s. An option left at None is the command line's default. Returns the files
    and folders written. Bad options raise SceneError with the command line's message. Keywords only.

    Units: ``fps`` frames per second; ``size`` pixels."""
    _need_render("montage")
    if labels is not None and not isinstance(labels, str):
        labels = ",".join(labels)
    args = _options(locals())
    args["run_dirs"] = [os.fspath(d) for d in run_dirs]
    _c.montage(args)
    return [pathlib.Path(p) for p in (mp4, png_dir) if p is not None]


def modes(run_dir: PathLike, *, count: Optional[int] = None, root: Optional[str] = None, force: bool = False,
          quiet: bool = True) -> List[pathlib.Path]:
    """The softest stiffness modes of a run's final state, as ``rootsim modes RUN_DIR`` (the same C++
    code): repeats the run from its scene.toml and writes modes.csv (eigenvalue, per-node displacement)
    and modes.vtp (ParaView) into the run directory; ``count`` modes (default: the command line's). A
    plate's run: ``root`` names the root (or pass its folder roots/NAME); the whole plate is repeated and
    the root's folder receives the files. Returns the two files. Bad input raises SceneError with the command line's message. Keywords only.

    Units: eigenvalues in N/m (modes.csv's columns name them)."""
    _c.modes(_options(locals()))
    d = pathlib.Path(run_dir) if root is None else pathlib.Path(run_dir) / "roots" / root
    return [d / "modes.csv", d / "modes.vtp"]


def check(scene: PathLike, *, set: Optional[Mapping[str, Value]] = None) -> Dict[str, Any]:
    """Validates a scene file, as ``rootsim check SCENE --set ...``: a bad key or value raises SceneError
    with the command line's message. Returns {"resolved_toml": every key with its value, "theory": the
    theory's predictions (docs/model.md, Theory; {} for a mechanics-only scene)}.

    Units: the scene keys' own (``set`` values too); the theory's named in each key."""
    got = _c.check_scene(dict(scene=os.fspath(scene), set=_overrides(set)))
    return {"resolved_toml": got["resolved_toml"], "theory": {} if got["theory"] is None else json.loads(got["theory"])}


def figure(name: str, *, quick: bool = False, out: Optional[PathLike] = None, jobs: Optional[int] = None,
           force: bool = False, quiet: bool = True, dpi: Optional[float] = None, width_mm: Optional[float] = None,
           title: bool = True) -> pathlib.Path:
    """The paper's figure panels, as ``rootsim figure NAME`` (the same C++ code): NAME one of fig2a fig2b
    fig2cde fig3a fig3b fig3d fig3d_gamma1 fig3d_apical fig4a fig4g, or "all" (with report.md and
    report.html); PDF + SVG + PNG per panel into ``out``. ``quick``: coarsened runs; ``jobs``: parallel
    simulations; ``dpi``: the PNGs' resolution; ``width_mm``: each panel's physical width;
    ``title=False`` is ``--no-title``. An option left at None is the command line's default. Returns
    the folder written. Bad input raises SceneError with the command line's message. Keywords only.

    Units: ``width_mm`` in mm; ``dpi`` pixels per inch."""
    return pathlib.Path(_c.figure(_options(locals())))


def export(run_dir: PathLike, *, rsml: Optional[PathLike] = None, gltf: Optional[PathLike] = None,
           paraview: Optional[PathLike] = None, at_h: Optional[float] = None, every_h: Optional[float] = None,
           force: bool = False, quiet: bool = True) -> List[pathlib.Path]:
    """Exports a saved run, as ``rootsim export RUN_DIR`` with the same options (the same C++ code).

    ``rsml``: an RSML 1.0 file (docs/rsml.md: plate coordinates in mm with the origin at the seed,
    per-node diameter, frame_angle, curvature and age, the run's observables as root properties).
    ``gltf``: a glTF 2.0 binary .glb file for Blender and three.js (docs/gltf.md: metres, +Y up, the
    root as a tube with the stripes as materials "stripe +d1" and "stripe -d1", the plate with its grid,
    obstacles, a top camera); every snapshot as an animation (24 snapshots a second) by default, the one
    nearest ``at_h`` as a still, or the ``every_h`` snapshots animated in the one file. ``paraview`` (a
    folder) is the command line's other format. At least one output. RSML: the final snapshot by default; ``at_h``: the snapshot nearest that growth time (ties to
    the earlier; outside the run's snapshots a SceneError); ``every_h``: one file every that many hours
    from the first snapshot, named FILE_t<time>h.EXT. An output that exists is replaced only if rootsim
    wrote it and ``force=True``. Returns the files written (for ``every_h``, the series' files, in time
    order). Bad options raise SceneError with the command line's message. Keywords only.

    Units: ``at_h``, ``every_h`` in hours of growth time."""
    _need_render("export")
    return [pathlib.Path(p) for p in _c.export_run(_options(locals()))]


def _columns(rows: List[Dict[str, Any]], names: Sequence[str]) -> Dict[str, np.ndarray]:
    """A table's rows as one numpy array per column: float64 for numbers (NaN for an empty cell), str
    for text."""
    out: Dict[str, np.ndarray] = {}
    for name in names:
        values = [r[name] for r in rows]
        if values and isinstance(values[0], str):
            out[name] = np.array(values, dtype=str)
        elif values:
            out[name] = np.array(values, dtype=np.float64)
        else:
            out[name] = np.array([], dtype=np.float64)
    return out


class Analysis(list):
    """``rootsim.analyze``'s answer: a list of one dict per root (analysis.csv's rows), and as numpy
    arrays, one per column: ``columns`` (analysis.csv), ``plants`` (plants.csv: one row per seedling),
    ``growth`` (growth.csv: each root at each time of a time-lapse or a dated series); ``warnings``: the
    implausible lengths the command line prints."""

    columns: Dict[str, np.ndarray]
    plants: Dict[str, np.ndarray]
    growth: Dict[str, np.ndarray]
    warnings: List[str]


def analyze(files: Union[PathLike, Sequence[PathLike]], *, px_per_mm: Optional[float] = None,
            downhill: Union[str, float, None] = None, times: Union[str, Sequence[float], None] = None,
            ds_mm: Optional[float] = None, exclude_tip_mm: Optional[float] = None,
            radius_mm: Optional[float] = None, out: Optional[PathLike] = None, force: bool = False,
            quiet: bool = True) -> Analysis:
    """The traits and run observables of every root of RSML files, as ``rootsim analyze`` computes them
    (docs/experiments.md; the same C++ code), one dict per root with analysis.csv's columns (numbers as
    floats, NaN where the CSV cell is empty); the same as numpy arrays in ``.columns``, and plants.csv
    and growth.csv's columns in ``.plants`` and ``.growth`` (an :class:`Analysis`). Writes nothing unless ``out`` is given: then also the command line's folder
    (analysis.csv, analysis.json, curves.csv, plants.csv, growth.csv; replaced only with ``force``).

    ``px_per_mm``: for files whose unit is pixel; ``downhill``: "+y", "-y" or an angle in degrees from
    +y towards +x; ``times``: one growth time per file [h] (growth rates across files of one plate);
    ``ds_mm``, ``exclude_tip_mm``, ``radius_mm``: as the command line's flags. Bad input raises
    SceneError with the command line's message. Keywords only."""
    files = [os.fspath(files)] if isinstance(files, (str, os.PathLike)) else [os.fspath(f) for f in files]
    if times is not None and not isinstance(times, str):
        times = ",".join(repr(float(t)) for t in times)
    if downhill is not None:
        downhill = str(downhill)
    got = _c.analyze_traces(_options(locals()))
    out = Analysis(dict(r) for r in got["roots"])
    out.columns = _columns(got["roots"], got["root_columns"])
    out.plants = _columns(got["plants"], got["plant_columns"])
    out.growth = _columns(got["growth"], got["growth_columns"])
    out.warnings = list(got["warnings"])
    return out


def compare(run_dir: PathLike, trace: PathLike, *, root: Optional[str] = None, px_per_mm: Optional[float] = None,
            downhill: Union[str, float, None] = None, sigma_mm: Optional[float] = None, at_h: Optional[float] = None,
            out: Optional[PathLike] = None, groups: Optional[PathLike] = None, force: bool = False,
            quiet: bool = True) -> Dict[str, Any]:
    """A traced root (RSML) over a run's root, as ``rootsim compare RUN_DIR TRACE`` (docs/experiments.md;
    the same C++ code): writes compare.json, compare.csv and the picture (compare.pdf/.svg/.png) into
    ``out`` (default compare/<run>_vs_<trace>) and returns compare.json as a dict, with "out" added: the
    observables side by side with the trace's uncertainties, chi2, and the shape distances
    ("distance_mm": RMS at equal arc length; "frechet_mm").

    ``root``: the traced root (id, #k or plant/root; default the file's one primary root); ``px_per_mm``:
    for a pixel file; ``downhill``: "+y", "-y" or an angle in degrees; ``sigma_mm``: a traced point's
    uncertainty [mm]; ``at_h``: the run's snapshot nearest this time [h] (default: the first as long as
    the trace); ``groups``: a plate's run, a sample sheet pairing plants with seedlings (docs/plate.md).
    Bad input raises SceneError with the command line's message. Keywords only."""
    if downhill is not None:
        downhill = str(downhill)
    folder = _c.compare_trace(_options(locals()))
    with open(os.path.join(folder, "compare.json"), encoding="utf-8") as f:
        result = json.load(f)
    result["out"] = pathlib.Path(folder)
    return result


def fit(trace: Union[PathLike, Sequence[PathLike]], *, scene: PathLike, free: Union[str, Dict[str, Sequence[float]]],
        out: PathLike, root: Optional[str] = None, px_per_mm: Optional[float] = None,
        downhill: Union[str, float, None] = None, sigma_mm: Optional[float] = None, objective: Optional[str] = None,
        jobs: Optional[int] = None, budget: Optional[int] = None, groups: Optional[PathLike] = None,
        force: bool = False, design_only: bool = False, quiet: bool = True) -> Dict[str, Any]:
    """Fits free scene keys to a traced root, as ``rootsim fit TRACE --scene SCENE --free ... --out OUT``
    (docs/experiments.md; the same C++ code). ``free``: {"tropism.beta": (0.05, 0.5), ...} or the command
    line's "KEY=LO:HI,..." text. Every evaluation is a run directory in OUT/runs: a fit called again with
    the same arguments finds them and runs nothing twice. Returns fit.json as a dict, with "out" added:
    "best" maps each key to its value, sigma and bounds; "notes" says what the trace cannot determine;
    "goodness" is {"chi2", "dof", "p_value", "verdict"} of the answer's run against the trace's
    uncertainty ("consistent" or "poor", with "misfit" saying why); "scene_fixed" the fixed keys that
    shape the answer (the plate's tilt and the growth rate first).

    ``objective``: "observables" (skew, wavelength, amplitude), "shape" (the centreline at 8 fractions
    of its length) or "timelapse" (length, tip position and tip angle at every observation time of a 2D+t
    trace); None: timelapse for a trace with times, else observables; ``jobs``: simultaneous runs; ``budget``: most runs (None: the command line's defaults). The trace's keywords as
    rootsim.compare's. Bad input raises SceneError, a fit whose runs all fail RunError. Keywords only.

    ``groups``: a sample sheet (CSV ``plant,group``), as ``rootsim fit PLATE.rsml [MORE.rsml...] --groups
    SHEET``: ``trace`` is then the plate's RSML file or a list of them, every group's keys are fitted to its
    seedlings together, and the result is the group fit's fit.json: "groups" maps each group's name to
    {"best": {KEY: {"value", "sigma"}}, "goodness", "flat", "notes", "observables", "plants", ...} with
    "values" and "sigmas" added as numpy arrays in the order of the free keys; "contrasts" is a list of
    {"key", "groups": [A, B], "difference" (A - B, or "flat"), "sigma", "p_value"} for every pair; "keys"
    lists the free keys. Each group's own fit folder is OUT/groups/NAME.

    ``design_only``: write the start design's sweep file (each group's: OUT/groups/NAME/design.toml) and
    stop, as ``--design-only``; returns {"out", "designs": [paths]}. Run them with ``rootsim sweep DESIGN
    --out DIR/runs --shard K/N`` (a cluster), then call fit again without it: it finds those runs."""
    more: List[PathLike] = []
    if not isinstance(trace, (str, bytes, os.PathLike)):
        trace, *more = list(trace)
        if groups is None:
            raise SceneError("fit: several RSML files are a plate fitted by group; give groups=SHEET")
    if not isinstance(free, str):
        free = ",".join(f"{k}={float(lo)!r}:{float(hi)!r}" for k, (lo, hi) in free.items())
    if downhill is not None:
        downhill = str(downhill)
    args = {k: v for k, v in locals().items() if k not in ("more",)}
    if more:
        args["more"] = [os.fspath(m) for m in more]
    folder = _c.fit_trace(_options(args))
    if design_only:
        base = pathlib.Path(folder)
        designs = [base / "groups" / d / "design.toml" for d in sorted(os.listdir(base / "groups"))
                   if (base / "groups" / d / "design.toml").is_file()] if groups is not None else [base / "design.toml"]
        return {"out": base, "designs": designs}
    with open(os.path.join(folder, "fit.json"), encoding="utf-8") as f:
        result = json.load(f)
    result["out"] = pathlib.Path(folder)
    if groups is not None:
        keys = result["keys"]
        for g in result["groups"].values():
            # null (a flat key's sigma) as NaN
            g["values"] = np.array([g["best"][k]["value"] for k in keys], dtype=float)
            g["sigmas"] = np.array([g["best"][k]["sigma"] for k in keys], dtype=float)
    return result


# ---------------------------------------------------------------------------------------------------
# stepping


@dataclass(frozen=True)
class State:
    """The rod's state as numpy arrays that are copies: owned by the State, unaffected by later
    ``step()`` calls, free to modify. Every field of the rod's state is here (the field list in the
    C++ header rod_fields.hpp names each one's Python name; ``_rootsim.state_fields()``), with the step and
    the nodes' plate coordinates.

    Units: the files' (lengths mm, time h, curvatures 1/mm), velocities mm/s (of the relaxation, whose
    clock is seconds), named in each field.

    ``positions_mm`` node positions, lab frame [mm] (nodes x 3); ``lateral_mm``, ``downhill_mm``,
    ``height_mm`` the nodes in plate coordinates [mm] (nodes each; as ``Frame``'s); ``velocities_mm_per_s``
    [mm/s] (nodes x 3); ``directors`` element frames, ``directors[e, i]`` is d_{i+1} of element e in lab
    components, unit vectors (elements x 3 x 3); ``angular_velocities_rad_per_s`` each element's angular
    velocity, material components [rad/s] (elements x 3); ``rest_lengths_mm`` [mm] (elements); ``s_mm``
    rest arc length of each node from the base [mm] (nodes; shape.csv's s_mm); ``kappa0_vector_per_mm``
    intrinsic curvature per rest length of each Voronoi domain (interior node), material components
    [1/mm] (elements-1 x 3): the vector whose bending part's magnitude is ``Frame.kappa0_per_mm``;
    ``anchors_mm`` each node's adhesion anchor [mm] (nodes x 3) and ``anchored`` whether the node is
    pinned to it (bool, nodes); ``plate_sticks_mm``, ``obstacle_sticks_mm`` each node's friction stick
    point on the plate and on an obstacle [mm] (nodes x 3), valid where ``has_plate_stick``,
    ``has_obstacle_stick`` (bool, nodes); ``clamp_frame`` the clamped base's frame, ``clamp_frame[i]`` is
    d_{i+1} (3 x 3); ``time_h`` growth time [h].
    """

    step: int
    time_h: float
    positions_mm: np.ndarray
    lateral_mm: np.ndarray
    downhill_mm: np.ndarray
    height_mm: np.ndarray
    velocities_mm_per_s: np.ndarray
    directors: np.ndarray
    angular_velocities_rad_per_s: np.ndarray
    rest_lengths_mm: np.ndarray
    s_mm: np.ndarray
    kappa0_vector_per_mm: np.ndarray
    anchors_mm: np.ndarray
    anchored: np.ndarray
    plate_sticks_mm: np.ndarray
    has_plate_stick: np.ndarray
    obstacle_sticks_mm: np.ndarray
    has_obstacle_stick: np.ndarray
    clamp_frame: np.ndarray

    __getattr__ = _renamed("State", {"positions": "positions_mm", "velocities": "velocities_mm_per_s",
                                     "rest_lengths": "rest_lengths_mm", "material_coordinates": "s_mm",
                                     "kappa0": "kappa0_vector_per_mm", "kappa0_per_mm": "kappa0_vector_per_mm"},
                           {"kappa0_per_mm": "Frame.kappa0_per_mm is the per-node magnitude trajectory.csv "
                                             "holds; the State's is the per-Voronoi vector"})


def _step_count_arg(n: Any) -> int:
    """``n`` of ``step(n)``: a positive int (a bool, float or string is refused, not rounded or parsed)."""
    if isinstance(n, (bool, np.bool_)) or not isinstance(n, numbers.Integral):
        raise TypeError(f"step(n): n must be a positive int (got {type(n).__name__} {n!r})")
    n = int(n)
    if n <= 0:
        raise ValueError(f"step(n): n must be a positive int (got {n})")
    return n


class Simulation:
    """A simulation to step by hand (for coupling to other code): the loop ``rootsim run`` runs.

    ``Simulation(scene)`` builds the initial rod and relaxes it (growth step 0); ``step(n)`` runs n
    growth steps (grow, relax, observe; the GIL is released meanwhile, Ctrl-C raises KeyboardInterrupt
    after a whole step); ``record()`` is the time-series row of the last step (timeseries.csv's columns
    and units); ``state()`` the rod's arrays (copies); ``snapshot()`` the ``Frame`` a trajectory would
    hold; ``set("tropism.beta", 0.4)`` changes a tropism key between steps.

    Units: the files' throughout (lengths mm, time h, angles deg, curvatures 1/mm, forces N), named in
    every field and column (``length_mm``, ``theta_tip_deg``, ``positions_mm``, ``downhill_mm``);
    ``set`` and the scene's overrides take the scene keys' units (named in the key).

    A run's time series holds the rows of steps 0, every ``output.every_steps`` and the last; stepping
    the same scene gives the same numbers. A Simulation steps at most ``growth.steps`` times (the
    scene's growth, which its element cap was checked against): ``step(n)`` beyond that raises
    ValueError, running nothing.

    A plate scene (``[[seedling]]`` tables, docs/plate.md): ``Simulation(scene)`` returns a ``Plate``,
    whose roots step together (their contacts, their laterals), never its first root alone.

    Threads: every method holds the Simulation's own lock, so calls from several threads on one
    Simulation are serialised (a second ``step()`` waits until the first returns; each runs whole
    growth steps, never interleaved). Separate Simulations step in parallel (the GIL is released while
    they compute).
    """

    def __new__(cls, scene: Union[Scene, PathLike], *, set: Optional[Mapping[str, Value]] = None):
        # a plate scene ([[seedling]] tables): its roots step together, as a Plate
        sc = _scene_of(scene, set)
        if cls is Simulation and sc._scene.is_plate:
            return Plate(sc)
        obj = super().__new__(cls)
        obj.scene = sc
        return obj

    def __init__(self, scene: Union[Scene, PathLike], *, set: Optional[Mapping[str, Value]] = None):
        # self.scene: made by __new__ (the scene with set applied)
        self._sim = _c._Simulation(self.scene._scene)

    def step(self, n: int = 1) -> Dict[str, Any]:
        """Runs n growth steps; returns the last one's time-series row (a dict, timeseries.csv's columns).

        Units: timeseries.csv's, named in each column (length_mm, time_h, theta_tip_deg, tip_x_mm, ...).

        ``n`` is a positive int: TypeError for a float, string or bool, ValueError for n <= 0. Raises
        ValueError, before running any step, when fewer than n of the scene's ``growth.steps`` are left
        (``steps_left``); RuntimeError when the next step could split the rod past the element cap
        (20000); RunError naming the step and node when relaxation fails. Called from several threads,
        the calls run one after the other."""
        n = _step_count_arg(n)
        if n > 2**31 - 1:  # beyond any growth.steps (an int)
            left = self._sim.steps_left
            raise ValueError(f"step({n}): only {left} growth steps left of growth.steps = {self.scene.steps}")
        return self._sim.step(n)

    def set(self, key: str, value: Value) -> None:
        """Changes a ``tropism.*`` key (beta, gamma, sensing, twist_r_tau, circumnutation_*) from the next
        growth step on, validated as ``--set`` (SceneError); the rest of the model is constant.

        Units: the key's own, named in it where it has one (tropism.circumnutation_period_h: hours)."""
        self._sim.set(key, _value_text(key, value))
        self.scene.set(key, value)

    def record(self) -> Dict[str, Any]:
        """The time-series row of the last step (step 0 after construction).

        Units: timeseries.csv's, named in each column (length_mm, time_h, theta_tip_deg, ...)."""
        return self._sim.record()

    def state(self, *, copy: bool = True) -> State:
        """The rod's state now, as copies: arrays that stay as they are after later steps.

        Units: mm, h, 1/mm, mm/s, named in each field (``positions_mm``, ``downhill_mm``, ...; ``State``).

        ``copy`` is accepted for compatibility: the arrays are always copies (views into the rod's memory
        would dangle after the next ``step()``, which reallocates it). Copying costs a few per cent of a
        growth step (docs/performance.md, "A state's copy in Python")."""
        return State(**self._sim.state())

    def snapshot(self) -> Frame:
        """The snapshot of the current state, as a trajectory frame (copies).

        Units: trajectory.csv's (mm, h, 1/mm, N), named in each field (``Frame``)."""
        return Frame(**self._sim.snapshot())

    @property
    def step_count(self) -> int:
        """Growth steps done so far."""
        return self._sim.step_count

    @property
    def steps_left(self) -> int:
        """Growth steps ``step()`` may still run: ``growth.steps - step_count`` (0 without growth)."""
        return self._sim.steps_left

    def __repr__(self) -> str:
        return f"rootsim.Simulation({self.scene.name!r}, step {self.step_count})"


class PlateRoot:
    """One root of a ``Plate``, as it is now: a seedling or a lateral that emerged. ``state()``,
    ``snapshot()`` and ``record()`` are a ``Simulation``'s (``State``, ``Frame``, a timeseries.csv row),
    in the root's own frame: its base's foot at the origin of the plate coordinates, as ``roots/NAME`` of
    the plate's run directory (``offset_mm``: the lab vector from the plate's origin to that foot).

    ``name``, ``genotype``, ``parent`` (the parent's name, "" for a seedling), ``order`` (0 for a
    seedling), ``emerged_h`` and ``emerged_step`` (the growth time and step it emerged at; 0 for a
    seedling), ``position_lateral_mm``, ``position_downhill_mm`` (its seed's place on the plate; a
    lateral's: its parent's), ``overrides`` (its keys that differ from the plate's, "section.key=value")."""

    def __init__(self, plate: "Plate", index: int):
        self._plate = plate
        self.index = index
        info = plate._plate.root_info(index)
        self.name: str = info["name"]
        self.genotype: str = info["genotype"]
        self.parent: str = info["parent"]
        self.order: int = info["order"]
        self.emerged_h: float = info["emerged_h"]
        self.emerged_step: int = info["emerged_step"]
        self.offset_mm: Tuple[float, float, float] = info["offset_mm"]
        self.position_lateral_mm: float = info["position_lateral_mm"]
        self.position_downhill_mm: float = info["position_downhill_mm"]
        self.overrides: List[str] = list(info["overrides"])

    def state(self) -> State:
        """The root's state now, as copies (``Simulation.state``'s fields and units)."""
        return State(**self._plate._plate.root_state(self.index))

    def snapshot(self) -> Frame:
        """The root's snapshot now, as a trajectory frame (``Simulation.snapshot``'s)."""
        return Frame(**self._plate._plate.root_snapshot(self.index))

    def record(self) -> Dict[str, Any]:
        """The root's time-series row of the last step (timeseries.csv's columns and units)."""
        return self._plate._plate.root_record(self.index)

    def __repr__(self) -> str:
        return f"rootsim.PlateRoot({self.name!r}, order {self.order})"


class Plate:
    """A plate scene (``[[seedling]]`` tables, docs/plate.md) stepped by hand: every root grows and relaxes
    together, through the plate's simulation ``rootsim run`` uses, from the scene as the scene loader
    resolves it (each seedling's ``[seedling.set]`` keys and the values ``[population]`` draws for it):
    the same scene gives the same numbers as ``rootsim run``. ``rootsim.Simulation(plate_scene)`` returns
    one.

    ``step(n)`` runs n growth steps of the plate (at most ``growth.steps``, as ``Simulation.step``) and
    returns the plate's row of the last one; ``run()`` runs the steps left. ``record()`` is that row:
    plate_timeseries.csv's columns (``step``, ``time_h``, ``touching_pairs`` element pairs of two roots in
    contact, ``min_gap_over_contact`` the closest approach of two roots' centrelines over Ra + Rb, NaN
    when no two roots are within reach, ``sweeps``) with ``roots`` (how many there are now) and
    ``emerged`` (the names of the laterals that emerged in that step; in ``step(n)``'s row, in any of
    its n steps).

    ``roots``: a list of ``PlateRoot``, the seedlings in the scene's order, then the laterals in the order
    they emerged (the list grows as they do); ``root(name)`` one of them.

    Threads: as a ``Simulation``'s (every call holds the Plate's own lock).
    """

    def __init__(self, scene: Union[Scene, PathLike], *, set: Optional[Mapping[str, Value]] = None):
        self.scene = _scene_of(scene, set)
        self._plate = _c._Plate(self.scene._scene)
        self._roots: List[PlateRoot] = []

    def step(self, n: int = 1) -> Dict[str, Any]:
        """Runs n growth steps of every root; returns the plate's row of the last one (``record()``).

        ``n`` as ``Simulation.step``'s: TypeError for a float, string or bool, ValueError for n <= 0 or
        beyond ``steps_left`` (nothing run); RunError naming the root when relaxation fails."""
        n = _step_count_arg(n)
        if n > 2**31 - 1:
            raise ValueError(f"step({n}): only {self.steps_left} growth steps left of growth.steps = "
                             f"{self.scene.steps}")
        return self._plate.step(n)

    def run(self) -> Dict[str, Any]:
        """Runs the growth steps left (``steps_left``); returns the plate's row of the last step."""
        left = self.steps_left
        return self._plate.step(left) if left > 0 else self._plate.record()

    def record(self) -> Dict[str, Any]:
        """The plate's row of the last step (step 0 after construction; see the class)."""
        return self._plate.record()

    @property
    def roots(self) -> List[PlateRoot]:
        """Every root now: the seedlings, then the laterals as they emerged."""
        for i in range(len(self._roots), self._plate.size):
            self._roots.append(PlateRoot(self, i))
        return list(self._roots)

    def root(self, name: str) -> PlateRoot:
        """The root called ``name`` (KeyError naming the roots there are)."""
        roots = self.roots
        for r in roots:
            if r.name == name:
                return r
        raise KeyError(f"no root {name!r} on the plate (roots: {', '.join(r.name for r in roots)})")

    @property
    def time_h(self) -> float:
        """Growth time now [h]."""
        return float(self._plate.record()["time_h"])

    @property
    def step_count(self) -> int:
        """Growth steps done so far."""
        return self._plate.step_count

    @property
    def steps_left(self) -> int:
        """Growth steps ``step()`` may still run: ``growth.steps - step_count`` (0 without growth)."""
        return self._plate.steps_left

    def __repr__(self) -> str:
        return f"rootsim.Plate({self.scene.name!r}, {self._plate.size} roots, step {self.step_count})"
