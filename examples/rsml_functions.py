# %% [markdown]
# # A simulated root as RSML, read by another program
# `rootsim export RUN --rsml FILE` writes the root as RSML (docs/rsml.md), the format root-phenotyping
# tools exchange. This script reads such a file with Python's own XML parser only (no rootsim), as any
# RSML reader would, and plots the root's lateral position and its four per-point functions along it:
#
#     ./build/rootsim run scenes/fig2b_waving.toml --out runs/fig2b_waving
#     ./build/rootsim export runs/fig2b_waving --rsml fig2b.rsml
#     /usr/bin/python3 examples/rsml_functions.py fig2b.rsml [OUT.png]

# %%
import math
import sys
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

path = sys.argv[1] if len(sys.argv) > 1 else "fig2b.rsml"
out = sys.argv[2] if len(sys.argv) > 2 else "rsml_functions.png"

# %% the first root of the first plant: points (mm, plate coordinates) and functions (one sample per point)
root = ET.parse(path).getroot().find("./scene/plant/root")
points = [(float(p.get("x")), float(p.get("y")), float(p.get("z"))) for p in root.findall("./geometry/polyline/point")]
functions = {f.get("name"): [float(s.get("value")) for s in f.findall("sample")]
             for f in root.findall("./functions/function")}
arc = [0.0]
for a, b in zip(points, points[1:]):
    arc.append(arc[-1] + math.dist(a, b))

# %% lateral position, diameter, frame angle, curvature and age against the arc length from the seed
panels = [([p[0] for p in points], "x = lateral [mm]"), (functions["diameter"], "diameter [mm]"),
          (functions["frame_angle"], "frame_angle [deg]"), (functions["curvature"], "curvature [1/mm]"),
          (functions["age"], "age [h]")]
fig, axes = plt.subplots(len(panels), 1, figsize=(7, 8.5), sharex=True)
for ax, (values, label) in zip(axes, panels):
    ax.plot(arc, values, lw=1.2)
    ax.set_ylabel(label, fontsize=9)
    ax.ticklabel_format(useOffset=False)
axes[-1].set_xlabel("arc length from the seed [mm]")
fig.tight_layout()
fig.savefig(out, dpi=70)
print(f"{path}: {len(points)} points, {arc[-1]:.2f} mm; curvature up to {max(functions['curvature']):.3f} 1/mm; "
      f"age up to {max(functions['age']):.1f} h; wrote {out}")
