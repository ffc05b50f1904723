# %% [markdown]
# # A traced plate and what `rootsim analyze` made of it
# Draws every root of an RSML file (any dialect: `x`/`coord_x`, `id`/`ID`) in millimetres, coloured by the
# observation at which each point was reached when the file is a time-lapse (RSML 2D+t), and beside it
# each root's length over time from the analysis folder's growth.csv (docs/experiments.md):
#
#     ./build/rootsim analyze PLATE.rsml --out analysis/plate
#     /usr/bin/python3 examples/trace_growth.py PLATE.rsml analysis/plate OUT.png [MM_PER_UNIT]
#
# MM_PER_UNIT: millimetres per file coordinate (1 / --px-per-mm for a pixel file; RootSystemTracker's
# <size> and SmartRoot's resolution are read from the file when it is not given).

# %%
import csv
import sys
import xml.etree.ElementTree as ET
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

path, folder, out = sys.argv[1], sys.argv[2], sys.argv[3]
doc = ET.parse(path).getroot()
meta = doc.find("metadata")
unit = (meta.findtext("unit") or "pixel").strip().lower()
if len(sys.argv) > 4:
    scale = float(sys.argv[4])
elif unit.startswith("pixel(") and unit.endswith(")"):
    scale = float(meta.findtext("size")) * {"um": 1e-3, "mm": 1.0, "cm": 10.0}[unit[6:-1]]
else:
    scale = {"mm": 1.0, "cm": 10.0, "inch": 25.4, "pixel": 1.0}[unit] / float(meta.findtext("resolution") or 1)


def coord(p, c):
    v = p.get(c)
    return float(v if v is not None else p.get("coord_" + c))


# %% every root's polyline [mm] and, in a time-lapse, each point's observation index
roots = []
for plant in doc.iter("plant"):
    for root in plant.iter("root"):
        pts = root.findall("./geometry/polyline/point")
        xs = [coord(p, "x") * scale for p in pts]
        ys = [coord(p, "y") * scale for p in pts]
        ts = [float(p.get("coord_t")) for p in pts] if pts and pts[0].get("coord_t") is not None else None
        roots.append((xs, ys, ts))

rows = list(csv.DictReader(open(f"{folder}/growth.csv")))
series = defaultdict(list)
for r in rows:
    series[r["track"]].append((float(r["time_h"]), float(r["length_mm"])))

fig, (a, b) = plt.subplots(1, 2, figsize=(11, 6), gridspec_kw={"width_ratios": [1.2, 1]})
last = max((max(t) for _, _, t in roots if t), default=0)
for xs, ys, ts in roots:
    a.plot(xs, ys, color="0.75", lw=0.8, zorder=1)
    if ts:
        sc = a.scatter(xs, ys, c=ts, s=4, cmap="viridis", vmin=0, vmax=last, zorder=2)
    else:
        a.plot(xs, ys, ".", ms=2, color="#0d338c", zorder=2)
if last:
    fig.colorbar(sc, ax=a, label="observation reached (coord_t)")
a.set_aspect("equal")
a.invert_yaxis()
a.set_xlabel("x [mm]")
a.set_ylabel("y [mm] (downhill)")
a.set_title(path.split("/")[-1], fontsize=9)
for track, pts in sorted(series.items()):
    t, length = zip(*sorted(pts))
    b.plot(t, length, "o-", ms=3, lw=1)
b.set_xlabel("time [h]")
b.set_ylabel("length [mm]")
b.set_title(f"growth.csv: {len(series)} roots, {len(rows)} rows", fontsize=9)
fig.tight_layout()
fig.savefig(out, dpi=110)
print(f"wrote {out}")
