#!/usr/bin/env python3
"""The traced roots of a `rootsim analyze` folder drawn as analyze measured them (docs/experiments.md, "Noise").

For each chosen root: the traced points (grey), the curve analyze measured (blue: the trace smoothed at
its `smoothing_mm`), its mature part's counted peaks (red: excursions above the tracing limit
`peak_threshold_mm`, one root diameter and the smoothed curve's noise), and the root's analysis.csv
verdict in the title. The lateral axis is stretched (its scale is printed) so excursions of a few pixels show.

    rootsim analyze plate.rsml --px-per-mm 24 --out an
    python3 examples/plot_trace_noise.py an noise.png --order 0
"""
import argparse
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rows_of(path):
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("analysis", help="a folder `rootsim analyze` wrote (analysis.csv, curves.csv)")
    ap.add_argument("out", help="the PNG to write")
    ap.add_argument("--order", type=int, default=0, help="draw the roots of this branching order (default 0)")
    ap.add_argument("--half-width-mm", type=float, default=1.0, help="lateral half-range of each panel [mm]")
    a = ap.parse_args()
    table = rows_of(os.path.join(a.analysis, "analysis.csv"))
    curves = rows_of(os.path.join(a.analysis, "curves.csv"))
    chosen = [r for r in table if int(float(r["order"])) == a.order]
    if not chosen:
        sys.exit(f"{a.analysis}: no root of order {a.order}")
    fig, axes = plt.subplots(1, len(chosen), figsize=(2.6 * len(chosen), 7.5), squeeze=False)
    for ax, r in zip(axes[0], chosen):
        key = (r["file"], r["plant"], r["root"])
        pts = [c for c in curves if (c["file"], c["plant"], c["root"]) == key]
        raw = [c for c in pts if c["kind"] == "trace"]
        cur = [c for c in pts if c["kind"] == "measured"]
        lat = [float(c["lateral_mm"]) for c in cur]
        down = [float(c["downhill_mm"]) for c in cur]
        mid = 0.5 * (min(lat) + max(lat))
        if raw:
            ax.plot([float(c["lateral_mm"]) - mid for c in raw], [float(c["downhill_mm"]) for c in raw], ".-",
                    color="0.6", ms=2.5, lw=0.5, label="trace")
        ax.plot([x - mid for x in lat], down, "-", color="tab:blue", lw=1.2, label="measured curve")
        peaks = [c for c in cur if c["peak"] == "1"]
        ax.plot([float(c["lateral_mm"]) - mid for c in peaks], [float(c["downhill_mm"]) for c in peaks], "o",
                color="tab:red", ms=4, label="counted peaks")
        ax.set_xlim(-a.half_width_mm, a.half_width_mm)
        ax.invert_yaxis()
        noise = float(r["noise_mm"]) if r["noise_mm"] else math.nan
        amp = f"{float(r['amplitude_mm']):.3g}" if r["amplitude_mm"] else "–"
        ax.set_title(f"{r['plant']}/{r['root']}: {r['pattern']}\nσ {noise * 1000:.0f} µm, "
                     f"smoothing {float(r['smoothing_mm']):.2f} mm\nlimit {float(r['peak_threshold_mm']):.3g} mm: "
                     f"{r['lateral_peaks']} peaks, A {amp} mm",
                     fontsize=8)
        ax.set_xlabel("lateral [mm]", fontsize=8)
        ax.tick_params(labelsize=7)
    axes[0][0].set_ylabel("downhill [mm]")
    axes[0][0].legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)


if __name__ == "__main__":
    main()
