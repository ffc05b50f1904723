#!/usr/bin/env python3
"""A run's root as a plate scan's tracing would give it (docs/experiments.md, "Validation").

Reads an RSML file rootsim exported (millimetres, plate coordinates: x lateral, y downhill) and writes
the primary root as a tracing tool would: in pixels of a scan at --px-per-mm, points every --step-px
along the root, each moved by Gaussian noise of --noise-px (seeded) and rounded to 0.1 px, the image's
+y downhill. `rootsim analyze/compare/fit ... --px-per-mm R` read it back. --plate: every plant's primary
root of a plate's export, each plant keeping its label (the seedling's name) and its place on the plate;
--whole-px: whole-pixel coordinates after the noise (a tracer's pixel snapping) instead of 0.1 px.

    python3 examples/synthetic_trace.py run.rsml trace.rsml --px-per-mm 20 --noise-px 0.5 --seed 1
    python3 examples/synthetic_trace.py plate.rsml traced.rsml --plate --whole-px --noise-px 0.7 --seed 1
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np


def primary_polyline(path):
    root = ET.parse(path).getroot()
    for r in root.iter("root"):
        pts = r.find("geometry/polyline")
        if pts is None:
            continue
        xy = [(float(p.get("x")), float(p.get("y"))) for p in pts.findall("point")]
        if len(xy) >= 2:
            return np.array(xy)
    sys.exit(f"{path}: no root with a polyline")


def plate_polylines(path):
    """(plant id, plant label, points) of each plant's first root with a polyline"""
    out = []
    for pl in ET.parse(path).getroot().iter("plant"):
        for r in pl.iter("root"):
            pts = r.find("geometry/polyline")
            if pts is None:
                continue
            xy = [(float(p.get("x")), float(p.get("y"))) for p in pts.findall("point")]
            if len(xy) >= 2:
                out.append((pl.get("id") or pl.get("ID"), pl.get("label") or "", np.array(xy)))
                break
    if not out:
        sys.exit(f"{path}: no plant with a root")
    return out


def resample(xy, step):
    seg = np.linalg.norm(np.diff(xy, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    n = max(1, int(round(s[-1] / step)))
    t = np.linspace(0.0, s[-1], n + 1)
    return np.column_stack([np.interp(t, s, xy[:, 0]), np.interp(t, s, xy[:, 1])])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run_rsml")
    ap.add_argument("out")
    ap.add_argument("--px-per-mm", type=float, default=20.0)
    ap.add_argument("--step-px", type=float, default=4.0, help="distance between traced points [px]")
    ap.add_argument("--noise-px", type=float, default=0.5, help="standard deviation of each point's position [px]")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--margin-px", type=float, default=200.0, help="the seed's distance from the image's corner [px]")
    ap.add_argument("--plate", action="store_true", help="every plant's primary root, each keeping its plant's id and label")
    ap.add_argument("--whole-px", action="store_true", help="whole-pixel coordinates (a tracer's pixel snapping)")
    a = ap.parse_args()
    if os.path.exists(a.out):
        sys.exit(f"{a.out}: exists; give a new file")
    rng = np.random.default_rng(a.seed)
    plants = plate_polylines(a.run_rsml) if a.plate else [("1", "synthetic", primary_polyline(a.run_rsml))]
    rsml = ET.Element("rsml")
    meta = ET.SubElement(rsml, "metadata")
    for tag, text in (("version", "1"), ("unit", "pixel"), ("resolution", "1"),
                      ("last-modified", "1970-01-01T00:00:00"), ("software", "synthetic_trace.py")):
        ET.SubElement(meta, tag).text = text
    scene = ET.SubElement(rsml, "scene")
    for pid, label, pts in plants:
        xy = resample(pts * a.px_per_mm, a.step_px)
        xy = xy + rng.normal(0.0, a.noise_px, xy.shape) + a.margin_px
        xy = np.round(xy) if a.whole_px else np.round(xy, 1)
        plant = ET.SubElement(scene, "plant", id=pid, label=label)
        root = ET.SubElement(plant, "root", id=f"{pid}.1", label="primary")
        poly = ET.SubElement(ET.SubElement(root, "geometry"), "polyline")
        for x, y in xy:
            ET.SubElement(poly, "point", x=f"{x:.1f}", y=f"{y:.1f}")
    ET.indent(rsml)
    ET.ElementTree(rsml).write(a.out, encoding="UTF-8", xml_declaration=True)


if __name__ == "__main__":
    main()
