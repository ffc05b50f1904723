"""rootsim: growing plant roots as Cosserat rods (Porat et al., PNAS 2024), from Python.

    import rootsim
    r = rootsim.run("scenes/fig2a_alpha40.toml", set={"growth.steps": 100})
    r.summary["pattern"]            # summary.json as a dict
    r.timeseries["theta_tip_deg"]   # timeseries.csv's columns as numpy arrays (the same doubles)
    f = r.frames[-1]                # a trajectory snapshot: positions_mm, directors, radius_mm, ...
    plt.plot(f.lateral_mm, f.downhill_mm)   # the root on the plate (plate coordinates, mm)

Units: one system, the run directory's files' (lengths mm, time h, angles deg, curvatures 1/mm, forces
N; velocities mm/s), named in every field and column (``positions_mm``, ``downhill_mm``, ``time_h``,
``theta_tip_deg``, ``kappa0_per_mm``, ``plate_force_n``): nothing to convert. Scene values (``set=``,
``Scene.set``, sweep grids) are in the scene keys' units, named in the key (``plane.alpha_deg``).

- ``run(scene_or_path, set=..., out=..., progress=...)`` -> ``Run`` (options: keywords only); ``load_run(dir)``
- ``Scene.load(path)``, ``scene.set(key, value)``, ``scene.to_toml()``, ``scene.check()``
- ``sweep(...)`` yields points as they finish; ``render(run_dir, ...)`` is ``rootsim render``;
  ``export(run_dir, rsml=...)`` is ``rootsim export`` (RSML); every command is a function whose keywords
  are its flags (``check``, ``modes``, ``montage``, ``figure``, ``analyze``, ``compare``, ``fit``)
- ``Simulation(scene)``: ``step(n)``, ``state()`` (numpy copies, mm), ``set("tropism.beta", ...)``;
  one Simulation may be shared by threads: its calls are serialised; of a plate scene it returns a
  ``Plate``: ``step(n)``, ``run()``, ``roots`` (each a ``PlateRoot``: name, parent, order, ``state()``)

Errors are the command line's: ``SceneError`` (a ValueError: bad key, value, path or option; the
message names file:line or the --set flag) and ``RunError`` (a RuntimeError: the run failed, naming
the growth step and node). Ctrl-C raises KeyboardInterrupt between growth steps; an interrupted run
directory stays ``DIR.partial/``. Built with the project (PYTHONPATH=build/python) for Debian's
/usr/bin/python3.
"""
from ._api import (Analysis, Frame, Plate, PlateRoot, Run, RunError, Scene, SceneError, Simulation, State, Sweep, SweepPoint, analyze,
                   check, compare, export, figure, fit, load_run, modes, montage, render, run, sweep)
from ._rootsim import __version__

__all__ = ["Analysis", "Frame", "Plate", "PlateRoot", "Run", "RunError", "Scene", "SceneError", "Simulation", "State", "Sweep", "SweepPoint",
           "analyze", "check", "compare", "export", "figure", "fit", "load_run", "modes", "montage", "render", "run",
           "sweep", "__version__"]
