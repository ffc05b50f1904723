#!/usr/bin/env python3
"""report.html of `rootsim figure all` in Debian's headless chromium (ctest figures_report_html).

Checks: the page is self-contained (no src/href that is not a data: URI or an in-page #anchor); it holds one
inline picture per panel PNG of the figure folder, each a whole PNG (CRCs, IEND, inflating); in the browser every picture loaded (the page's own load
script marks each <img> data-loaded="yes"/"no"), the console stayed silent, and a 1200 x 3000 screenshot is
not blank. Exit 77 (ctest SKIPPED) when no chromium is installed: never a pass without the browser.
usage: report_html_check.py FIGURE_DIR
"""
import base64
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

SKIP = 77


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def png_chunks(data, what):
    """IHDR fields and the joined IDAT of a whole PNG: every chunk's CRC right, IEND last, the image data
    inflating completely (a truncated or corrupt picture fails)."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        fail(what + " is not a PNG")
    pos, idat, ihdr, end = 8, b"", None, False
    while pos + 12 <= len(data) and not end:
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if len(body) != n or pos + 12 + n > len(data):
            fail(what + ": truncated in chunk " + kind.decode("latin-1"))
        (crc,) = struct.unpack(">I", data[pos + 8 + n:pos + 12 + n])
        if zlib.crc32(kind + body) & 0xFFFFFFFF != crc:
            fail(what + ": bad CRC in chunk " + kind.decode("latin-1"))
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            end = True
        pos += 12 + n
    if ihdr is None or not end:
        fail(what + ": no IHDR or no IEND (truncated)")
    z = zlib.decompressobj()
    try:
        z.decompress(idat)
    except zlib.error as e:
        fail(what + ": image data does not inflate: " + str(e))
    if not z.eof:
        fail(what + ": image data ends early")
    return ihdr, idat


def png_pixels(path):
    """(width, height, channels, rows as bytes) of an 8-bit non-interlaced PNG (what chromium writes)."""
    ihdr, idat = png_chunks(open(path, "rb").read(), path)
    w, h, depth, ctype, _, _, interlace = ihdr
    if depth != 8 or interlace != 0 or ctype not in (0, 2, 4, 6):
        fail("screenshot PNG format not handled: depth %d colour type %d interlace %d" % (depth, ctype, interlace))
    ch = {0: 1, 2: 3, 4: 2, 6: 4}[ctype]
    raw = zlib.decompress(idat)
    stride = w * ch
    rows, prev, p = [], bytearray(stride), 0
    for _ in range(h):
        f = raw[p]
        line = bytearray(raw[p + 1:p + 1 + stride])
        p += 1 + stride
        for i in range(stride):
            a = line[i - ch] if i >= ch else 0
            b = prev[i]
            c = prev[i - ch] if i >= ch else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return w, h, ch, rows


def main():
    if len(sys.argv) != 2:
        fail("usage: report_html_check.py FIGURE_DIR")
    folder = os.path.abspath(sys.argv[1])
    page = os.path.join(folder, "report.html")
    if not os.path.isfile(page):
        fail(page + " was not written")
    html = open(page, encoding="utf-8").read()
    # self-contained: every reference is a data: URI or an anchor in the page
    for ref in re.findall(r'(?:src|href)\s*=\s*"([^"]*)"', html):
        if not (ref.startswith("data:") or ref.startswith("#")):
            fail("report.html refers to an outside resource: " + ref[:80])
    if re.search(r"url\(|@import|<link|<iframe|<object|<embed", html):
        fail("report.html loads something through CSS or an embedded frame")
    panels = sorted(f[:-4] for f in os.listdir(folder) if f.endswith(".png"))
    if not panels:
        fail("no panel PNGs in " + folder)
    for name in panels:
        if not re.search(r'<h2 id="%s">[^<]*</h2>\s*<img class="panel" alt="%s" src="data:image/png;base64,'
                         % (re.escape(name), re.escape(name)), html):
            fail("panel %s is not inline in report.html" % name)
    # each inline picture is a whole PNG (the browser's naturalWidth alone passes a truncated one)
    for i, data in enumerate(re.findall(r'src="data:image/png;base64,([^"]*)"', html)):
        try:
            raw = base64.b64decode(data, validate=True)
        except ValueError as e:
            fail("inline picture %d is not base64: %s" % (i, e))
        png_chunks(raw, "inline picture %d" % i)
    for word in ("agrees", "claims agree", "rootsim figure all", "<table id=\"claims\">"):
        if word not in html:
            fail("report.html lacks " + word)

    browser = shutil.which("chromium") or shutil.which("chromium-browser")
    if not browser:
        print("SKIPPED: no chromium installed (apt-get install chromium)")
        sys.exit(SKIP)
    url = "file://" + page
    with tempfile.TemporaryDirectory() as tmp:
        base = [browser, "--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                "--no-first-run", "--user-data-dir=" + os.path.join(tmp, "profile"),
                "--virtual-time-budget=10000", "--enable-logging=stderr", "--v=0"]
        dom = subprocess.run(base + ["--dump-dom", url], capture_output=True, text=True, timeout=300)
        if dom.returncode != 0:
            fail("chromium --dump-dom exited %d: %s" % (dom.returncode, dom.stderr[-2000:]))
        shot = os.path.join(tmp, "report.png")
        pic = subprocess.run(base + ["--screenshot=" + shot, "--window-size=1200,3000", url],
                             capture_output=True, text=True, timeout=300)
        if pic.returncode != 0 or not os.path.isfile(shot):
            fail("chromium --screenshot exited %d: %s" % (pic.returncode, pic.stderr[-2000:]))
        # the console: any message the page logs (errors, uncaught exceptions) fails
        console = [l for l in (dom.stderr + pic.stderr).splitlines() if ":CONSOLE" in l or "Uncaught" in l]
        if console:
            fail("console messages:\n" + "\n".join(console[:20]))
        # every picture present and loaded, as the page's load script marked them
        m = re.search(r'<body[^>]*data-images="(\d+) (\d+)"', dom.stdout)
        if not m:
            fail("the page's load script did not run (no data-images on <body>)")
        count, bad = int(m.group(1)), int(m.group(2))
        loaded = re.findall(r'<img[^>]*data-loaded="(yes|no)"', dom.stdout)
        if count != len(panels) or len(loaded) != len(panels):
            fail("the browser saw %d pictures (%d marked), the folder has %d panels" % (count, len(loaded), len(panels)))
        if bad or loaded.count("no"):
            fail("%d of %d pictures did not load (naturalWidth 0)" % (bad, count))
        # the screenshot is not blank: the grey levels vary
        w, h, ch, rows = png_pixels(shot)
        n, s, s2 = 0, 0.0, 0.0
        for y in range(0, h, 4):
            row = rows[y]
            for x in range(0, w * ch, 4 * ch):
                g = sum(row[x:x + min(ch, 3)]) / min(ch, 3)
                n += 1
                s += g
                s2 += g * g
        mean = s / n
        var = s2 / n - mean * mean
        print("report.html: %d panels loaded, screenshot %dx%d grey mean %.1f variance %.1f" % (count, w, h, mean, var))
        if var < 100.0:
            fail("the screenshot is blank (grey variance %.1f < 100)" % var)
    print("report.html passes")


if __name__ == "__main__":
    main()
