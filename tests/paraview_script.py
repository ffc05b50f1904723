#!/usr/bin/python3
"""ctest paraview_script: Debian's ParaView opens `rootsim export RUN --paraview DIR` (docs/paraview.md).

A short real run of Fig. 4A's skewing root (its material frame twists, so from above both stripes show
as a helix) is exported; pvpython runs the folder's open_in_paraview.py offscreen (under xvfb-run: Debian's
ParaView renders through GLX, so it needs an X server even offscreen) and saves two screenshots, at the
first snapshot and at the last (the time slider's two ends). Checks: the first shows the tube's stripes,
the last both pink (+d1) and orange (-d1) stripe pixels; the two differ, and the root reaches further down
the screen at the end (it grows downhill, which the top camera puts down the screen).

Exit 77 (ctest SKIPPED) when pvpython or xvfb-run is not installed, unless ROOTSIM_REQUIRE_CONSUMERS=1 (CI,
which installs them: scripts/install-deps.sh), where that is a failure.
usage: paraview_script.py ROOTSIM_BINARY SCENE WORKDIR
"""
import colorsys
import os
import shutil
import struct
import subprocess
import sys
import time
import zlib

SKIP = 77


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def read_png(path):
    """An 8-bit RGB or RGBA non-interlaced PNG (what ParaView's screenshots are) -> (width, height, rows of
    (r, g, b) bytes)."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        fail(path + " is not a PNG")
    pos, idat, ihdr = 8, b"", None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    w, h, depth, ctype, _, _, interlace = ihdr
    if depth != 8 or ctype not in (2, 6) or interlace:
        fail("%s: unexpected PNG form (depth %d, colour type %d, interlace %d)" % (path, depth, ctype, interlace))
    bpp = 3 if ctype == 2 else 4
    raw = zlib.decompress(idat)
    stride = w * bpp
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        if f == 1:
            for i in range(bpp, stride):
                line[i] = (line[i] + line[i - bpp]) & 255
        elif f == 2:
            for i in range(stride):
                line[i] = (line[i] + prev[i]) & 255
        elif f == 3:
            for i in range(stride):
                left = line[i - bpp] if i >= bpp else 0
                line[i] = (line[i] + ((left + prev[i]) >> 1)) & 255
        elif f == 4:
            for i in range(stride):
                a = line[i - bpp] if i >= bpp else 0
                b = prev[i]
                c = prev[i - bpp] if i >= bpp else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        elif f != 0:
            fail("%s: bad PNG filter %d" % (path, f))
        rows.append(bytes(line[k] for k in range(stride) if k % bpp < 3) if bpp == 4 else bytes(line))
        prev = line
    return w, h, rows


def classify(png):
    """Pixel counts and the lowest row of each kind: 'pink' (hue 300-350 deg), 'orange' (hue 15-45 deg),
    both saturated and not dark (the lit stripe colours); 'tube' = pink + orange + ivory-ish body pixels are
    not separable from the plate by colour, so the stripes stand for the tube."""
    w, h, rows = png
    count = {"pink": 0, "orange": 0}
    lowest = {"pink": -1, "orange": -1}
    for y, row in enumerate(rows):
        for x in range(w):
            r, g, b = row[3 * x], row[3 * x + 1], row[3 * x + 2]
            hh, s, v = colorsys.rgb_to_hsv(r / 255.0, g / 255.0, b / 255.0)
            if s < 0.45 or v < 0.35:
                continue
            deg = hh * 360.0
            kind = "pink" if 300.0 <= deg <= 350.0 else "orange" if 15.0 <= deg <= 45.0 else None
            if kind:
                count[kind] += 1
                lowest[kind] = y
    return count, lowest


def main():
    binary, scene, work = sys.argv[1:4]
    pvpython, xvfb = shutil.which("pvpython"), shutil.which("xvfb-run")
    if not pvpython or not xvfb:
        missing = "pvpython (python3-paraview)" if not pvpython else "xvfb-run (xvfb)"
        if os.environ.get("ROOTSIM_REQUIRE_CONSUMERS") == "1":
            fail(missing + " not found and ROOTSIM_REQUIRE_CONSUMERS=1: bash scripts/install-deps.sh")
        print("skipped: %s not found (bash scripts/install-deps.sh installs it)" % missing)
        return SKIP
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    run, pv = os.path.join(work, "run"), os.path.join(work, "pv")
    subprocess.run([binary, "run", scene, "--set", "growth.steps=400", "--set", "output.every_steps=40", "--quiet",
                    "--out", run], check=True)
    subprocess.run([binary, "export", run, "--paraview", pv, "--quiet"], check=True)
    first, last = os.path.join(work, "first.png"), os.path.join(work, "last.png")
    # xvfb-run starts a fresh X server for pvpython. Under a loaded ctest -j2 run that server once refused
    # pvpython's connection ("bad X server connection", SIGABRT before the script ran) and the same test
    # passed alone and in parallel every time after: a start-up race of the X server, not of rootsim's
    # files. Such an abort is retried with a new server, at most three times, and said; anything else fails.
    xvfb_log = os.path.join(work, "xvfb.log")
    for attempt in range(1, 4):
        t0 = time.time()
        p = subprocess.run([xvfb, "-a", "-e", xvfb_log, "-s", "-screen 0 1280x1024x24", pvpython,
                            "--force-offscreen-rendering", os.path.join(pv, "open_in_paraview.py"),
                            "--size", "900", "600", "--at-h", "0", "--screenshot", first,
                            "--at-h", "1e9", "--screenshot", last], capture_output=True, text=True, timeout=600)
        seconds = time.time() - t0
        if p.returncode == 0 or "bad X server connection" not in p.stdout + p.stderr or attempt == 3:
            break
        print("attempt %d: the X server refused pvpython's connection; retrying with a new one" % attempt)
    if p.returncode != 0:
        xlog = open(xvfb_log, errors="replace").read() if os.path.exists(xvfb_log) else ""
        fail("pvpython exited %d:\n%s\n%s\nXvfb: %s" % (p.returncode, p.stdout, p.stderr, xlog))
    for line in (p.stdout + p.stderr).splitlines():
        # ParaView reports a failed filter (a Calculator that does not parse, a missing array) as ERR
        if "ERR|" in line or "Traceback" in line:
            fail("pvpython reported an error: " + line)
    a, b = read_png(first), read_png(last)
    if (a[0], a[1]) != (900, 600) or (b[0], b[1]) != (900, 600):
        fail("screenshot size %dx%d, %dx%d (asked 900x600)" % (a[0], a[1], b[0], b[1]))
    ca, la = classify(a)
    cb, lb = classify(b)
    print("pvpython %.1f s; first snapshot: %s, lowest rows %s; last: %s, lowest rows %s" % (seconds, ca, la, cb, lb))
    # the first snapshot is a straight 1.1 mm root: one stripe faces up
    if ca["pink"] + ca["orange"] < 30:
        fail("the first screenshot has %s stripe pixels: no tube" % ca)
    for kind in ("pink", "orange"):
        if cb[kind] < 100:
            fail("the last screenshot has %d %s pixels: no %s stripe on the tube" % (cb[kind], kind, kind))
    if a[2] == b[2]:
        fail("the first and last snapshots give the same picture: the time slider does not step")
    # fig2b grows downhill: at the end the stripes reach further down the screen
    if max(lb.values()) <= max(la.values()) + 20:
        fail("the root does not reach further down the screen at the end (rows %s then %s)" % (la, lb))
    shutil.rmtree(work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
