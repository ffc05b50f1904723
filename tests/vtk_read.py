#!/usr/bin/python3
"""Reads rootsim's zlib-compressed ParaView files with VTK's own XML reader (ParaView's pvpython from Debian's python3-paraview, or python3 with python3-vtk9) and
compares every point and cell value with trajectory.bin (docs/outputs.md), bit for bit, and checks the
point data (docs/paraview.md): every array per node, the node frame orthonormal with d2 = d3 x d1. An independent
check of the appended-data encoding: the C++ test decodes it with our understanding of the format, this
one with VTK's. Exit 77 (skipped) when VTK's Python module is not installed.

Usage: vtk_read.py ROOTSIM_BINARY SCENE WORKDIR
"""
import os
import shutil
import struct
import subprocess
import sys


def read_trajectory_bin(path):
    """trajectory.bin -> list of dicts (x_mm, d1, d3, radius_mm as lists of tuples / floats)."""
    b = open(path, "rb").read()
    assert b[:8] == b"RSTRAJ01", "magic"
    (version,) = struct.unpack_from("<I", b, 8)
    assert version == 1
    pos, frames = 16, []
    while pos < len(b):
        frame, step, n, fields = struct.unpack_from("<iiiI", b, pos)
        (t,) = struct.unpack_from("<d", b, pos + 16)
        pos += 24

        def take(count):
            nonlocal pos
            vals = struct.unpack_from("<%dd" % count, b, pos)
            pos += 8 * count
            return vals

        x = take(3 * n)
        d1 = take(3 * (n - 1))
        d3 = take(3 * (n - 1))
        radius = take(n - 1)
        if fields & 1:
            take(n)
        if fields & 2:
            take(n)
        if fields & 4:
            take(3 * n)
        frames.append({"frame": frame, "step": step, "time_h": t, "x": x, "d1": d1, "d3": d3, "radius": radius})
    return frames


def main():
    try:
        from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    except ImportError:
        print("skipped: VTK's Python module is not installed (apt-get install python3-paraview, whose pvpython has it)")
        return 77
    binary, scene, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    out = os.path.join(work, "run")
    subprocess.run([binary, "run", scene, "--set", "growth.steps=200", "--set", "output.every_steps=20", "--quiet",
                    "--out", out], check=True)
    frames = read_trajectory_bin(os.path.join(out, "trajectory.bin"))
    assert len(frames) == 11, len(frames)
    checked = 0
    for f in frames:
        path = os.path.join(out, "vtk", "step_%06d.vtp" % f["step"])
        r = vtkXMLPolyDataReader()
        r.SetFileName(path)
        r.Update()
        pd = r.GetOutput()
        n = len(f["x"]) // 3
        assert pd.GetNumberOfPoints() == n, (path, pd.GetNumberOfPoints(), n)
        assert pd.GetNumberOfLines() == n - 1, (path, pd.GetNumberOfLines())
        for i in range(n):
            assert pd.GetPoint(i) == tuple(f["x"][3 * i:3 * i + 3]), (path, i, pd.GetPoint(i))
        cd = pd.GetCellData()
        rad, d1, d3 = cd.GetArray("radius_mm"), cd.GetArray("d1"), cd.GetArray("d3")
        for i in range(n - 1):
            assert rad.GetValue(i) == f["radius"][i], (path, i)
            assert d1.GetTuple3(i) == tuple(f["d1"][3 * i:3 * i + 3]), (path, i)
            assert d3.GetTuple3(i) == tuple(f["d3"][3 * i:3 * i + 3]), (path, i)
        # the point data (docs/paraview.md): every array one value per node; the node frame orthonormal and
        # right-handed (d2 = d3 x d1); the radius and stretch the adjacent elements' means
        pdata = pd.GetPointData()
        names = [pdata.GetArrayName(k) for k in range(pdata.GetNumberOfArrays())]
        for name in ("radius_mm", "d1", "d2", "d3", "material_angle_deg", "curvature_per_mm", "twist_rad_per_mm",
                     "kappa0_per_mm", "stretch", "growth_zone", "plate_force_n", "contact_plate_n", "contact_self_n",
                     "contact_obstacle_n"):
            assert name in names, (path, name, names)
            assert pdata.GetArray(name).GetNumberOfTuples() == n, (path, name)
        p1, p2, p3, prad = pdata.GetArray("d1"), pdata.GetArray("d2"), pdata.GetArray("d3"), pdata.GetArray("radius_mm")
        for i in range(n):
            a, b, t = p1.GetTuple3(i), p2.GetTuple3(i), p3.GetTuple3(i)
            cross = (t[1] * a[2] - t[2] * a[1], t[2] * a[0] - t[0] * a[2], t[0] * a[1] - t[1] * a[0])
            assert max(abs(b[k] - cross[k]) for k in range(3)) < 1e-12, (path, i, b, cross)
            assert abs(sum(x * x for x in a) - 1) < 1e-12 and abs(sum(x * t[k] for k, x in enumerate(a))) < 1e-12
            ea, eb = max(i - 1, 0), min(i, n - 2)
            assert abs(prad.GetValue(i) - 0.5 * (f["radius"][ea] + f["radius"][eb])) < 1e-15, (path, i)
        # the polyline joins node i to i + 1
        ids = pd.GetLines().GetData()
        assert ids.GetNumberOfTuples() == 3 * (n - 1), ids.GetNumberOfTuples()
        assert [ids.GetValue(k) for k in range(3)] == [2, 0, 1]
        checked += 1
    shutil.rmtree(work, ignore_errors=True)
    print("VTK %s read %d .vtp files; every point and cell value equals trajectory.bin" % (
        __import__("vtkmodules.vtkCommonCore").vtkCommonCore.vtkVersion.GetVTKVersion(), checked))
    return 0


if __name__ == "__main__":
    sys.exit(main())
