# %% [markdown]
# # Waving, coiling, straight: a small sweep of the plate's tilt α (the paper's Fig. 2A)
# A plain script with notebook cells (`# %%`: VS Code, Jupyter via jupytext, Spyder). Run it with
#
#     PYTHONPATH=build/python /usr/bin/python3 examples/alpha_sweep.py [OUT.png]
#
# It sweeps α over five values (900 growth steps each, the scene's own, both cores), plots the tip angle θ_tip of every
# run against time, and the phase each run ends in (straight / waving / coiling) against α.

# %%
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")  # no display needed; the figure goes to a PNG
import matplotlib.pyplot as plt

import rootsim

try:
    ROOT = pathlib.Path(__file__).resolve().parents[1]
except NameError:  # in a notebook: run from the repository
    ROOT = pathlib.Path.cwd()
OUT = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 and sys.argv[1].endswith(".png") else pathlib.Path("alpha_sweep.png")

# %% the sweep: one run per α; points arrive as they finish (the GIL is released while simulating)
alphas = [0, 20, 40, 60, 80]
runs = {}
for point in rootsim.sweep(scene=ROOT / "scenes/fig2a_alpha40.toml", grid={"plane.alpha_deg": alphas},
                           set={"growth.steps": 900}, jobs=2):
    alpha = float(point.grid["plane.alpha_deg"])
    runs[alpha] = point.run
    print(f"alpha = {alpha:4.0f} deg: {runs[alpha].summary['pattern']:9s} ({point.wall_s:.1f} s)")

# %% θ_tip(t) of every run, and the phase against α
phases = ["straight", "waving", "coiling"]
phases += sorted({r.summary["pattern"] for r in runs.values()} - set(phases))  # e.g. "skewing"
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4), gridspec_kw={"width_ratios": [2, 1]})
for alpha in sorted(runs):
    ts = runs[alpha].timeseries
    ax1.plot(ts["time_h"], ts["theta_tip_deg"], label=f"α = {alpha:.0f}°")
ax1.set_xlabel("time [h]")
ax1.set_ylabel("θ_tip [°]")
ax1.set_title("tip angle")
ax1.legend(fontsize=8)
ax2.scatter(sorted(runs), [phases.index(runs[a].summary["pattern"]) for a in sorted(runs)], s=60)
ax2.set_yticks(range(len(phases)), phases)
ax2.set_xlabel("plate tilt α [°]")
ax2.set_title("phase after 900 steps (45 h)")
ax2.set_xlim(-10, 90)
fig.tight_layout()
fig.savefig(OUT, dpi=110)
print(f"wrote {OUT}")
