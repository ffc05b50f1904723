# %% [markdown]
# # Stepping a simulation by hand, and changing gravitropism half-way
# `rootsim.Simulation` runs the loop of `rootsim run` one growth step at a time, so other code can look
# at (or react to) the root between steps. Here a waving root (the paper's Fig. 2B: α = 40°, β = 0.2)
# grows for 20 h; one copy keeps β, the other gets a five times stronger gravitropism (β = 1) half-way.
#
#     PYTHONPATH=build/python /usr/bin/python3 examples/step_and_change_beta.py [OUT.png]

# %%
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import rootsim

try:
    ROOT = pathlib.Path(__file__).resolve().parents[1]
except NameError:  # in a notebook: run from the repository
    ROOT = pathlib.Path.cwd()
OUT = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 and sys.argv[1].endswith(".png") else pathlib.Path("step_and_change_beta.png")

# %% two identical simulations; 400 growth steps of 0.05 h
STEPS, HALF = 400, 200
scene = rootsim.Scene.load(ROOT / "scenes/fig2b_waving.toml").set("growth.steps", STEPS)
kept, changed = rootsim.Simulation(scene), rootsim.Simulation(scene)
rows = {"kept": [kept.record()], "changed": [changed.record()]}
tips = {"kept": [], "changed": []}
for k in range(1, STEPS + 1):
    if k == HALF + 1:
        changed.set("tropism.beta", 1.0)  # from this growth step on
    for name, sim in (("kept", kept), ("changed", changed)):
        rows[name].append(sim.step())
        if k % 100 == 0:
            # the state as numpy copies (they stay valid after later steps), in mm like the files
            st = sim.state()
            tips[name].append((st.lateral_mm[-1], st.downhill_mm[-1]))
for name in rows:
    lat, down = tips[name][-1]
    print(f"{name:8s}: theta_tip = {rows[name][-1]['theta_tip_deg']:7.2f} deg after {STEPS} steps, "
          f"tip {down:.3f} mm downhill, {lat:+.3f} mm lateral (plate coordinates)")

# %% θ_tip(t) and the final centrelines on the plate (plate coordinates: lateral, downhill; mm)
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
for name, label in (("kept", "β = 0.2 throughout"), ("changed", "β = 0.2 → 1 at 10 h")):
    t = [r["time_h"] for r in rows[name]]
    ax1.plot(t, [r["theta_tip_deg"] for r in rows[name]], label=label)
    st = (kept if name == "kept" else changed).state()
    ax2.plot(st.lateral_mm, st.downhill_mm, label=label)
ax1.axvline(HALF * 0.05, color="grey", lw=0.8, ls="--")
ax1.set_xlabel("time [h]")
ax1.set_ylabel("θ_tip [°]")
ax1.legend(fontsize=8)
ax2.set_aspect("equal")
ax2.invert_yaxis()  # downhill is down the page
ax2.set_xlabel("lateral [mm]")
ax2.set_ylabel("downhill [mm]")
ax2.set_title("final centreline")
fig.tight_layout()
fig.savefig(OUT, dpi=110)
print(f"wrote {OUT}")
