#!/usr/bin/env python3
"""rootsim's glTF read by its real consumers (ctest gltf_fixture, gltf_validator, gltf_blender; docs/gltf.md).

  consumers.py export ROOTSIM WORKDIR SCENE   a short run of SCENE and `rootsim export --gltf` of it:
                                              WORKDIR/run, WORKDIR/run.glb (the fixture of the two below)
  consumers.py validator WORKDIR              the Khronos glTF-Validator (Node, npm gltf-validator) on it
  consumers.py blender WORKDIR                Debian's Blender imports it and renders a frame (blender_check.py)
  consumers.py blender-plate WORKDIR          the same for a plate's run (blender_plate_check.py): every
                                              root's group and snapshots, one shown per emerged root

A missing consumer (node, the npm package, blender) exits 77 (ctest: skipped) on a developer's machine,
and fails (exit 1) when ROOTSIM_REQUIRE_CONSUMERS=1, as CI sets it (.ci/run): CI installs them
(scripts/install-deps.sh), so there a missing one is a broken setup, never a pass.
"""
import os
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SKIP = 77
# the run: 200 growth steps with a snapshot every 20 (the initial one included: 11 snapshots)
STEPS, EVERY = 200, 20
FRAMES = STEPS // EVERY + 1


def missing(what):
    if os.environ.get("ROOTSIM_REQUIRE_CONSUMERS") == "1":
        print("FAIL: %s is not installed, and ROOTSIM_REQUIRE_CONSUMERS=1 (CI) requires it" % what)
        sys.exit(1)
    print("SKIPPED: %s is not installed (scripts/install-deps.sh installs it)" % what)
    sys.exit(SKIP)


def run(cmd):
    print("$ " + " ".join(cmd), flush=True)
    t0 = time.monotonic()
    p = subprocess.run(cmd)
    print("(%.1f s, exit %d)" % (time.monotonic() - t0, p.returncode), flush=True)
    return p.returncode


def main():
    what, work = sys.argv[1], None
    if what == "export":
        rootsim, work, scene = sys.argv[2:5]
        shutil.rmtree(work, ignore_errors=True)
        os.makedirs(work)
        rc = run([rootsim, "run", scene, "--set", "growth.steps=%d" % STEPS, "--set", "output.every_steps=%d" % EVERY,
                  "--out", os.path.join(work, "run"), "--quiet"])
        if rc == 0:
            rc = run([rootsim, "export", os.path.join(work, "run"), "--gltf", os.path.join(work, "run.glb")])
        return 1 if rc else 0
    work = sys.argv[2]
    glb = os.path.join(work, "run.glb")
    if not os.path.isfile(glb):
        print("FAIL: no %s (the fixture gltf_fixture did not run or failed)" % glb)
        return 1
    if what == "validator":
        node = shutil.which("node")
        if not node:
            missing("node (Debian's nodejs)")
        rc = run([node, os.path.join(HERE, "validate.js"), glb])
        if rc == SKIP:
            missing("the npm package gltf-validator")
        return 1 if rc else 0
    if what == "blender":
        blender = shutil.which("blender")
        if not blender:
            missing("blender (Debian's blender)")
        png = os.path.join(work, "blender.png")
        if os.path.exists(png):
            os.remove(png)
        rc = run([blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python",
                  os.path.join(HERE, "blender_check.py"), "--", glb, png, str(FRAMES)])
        return 1 if rc else 0
    if what == "blender-plate":
        blender = shutil.which("blender")
        if not blender:
            missing("blender (Debian's blender)")
        png = os.path.join(work, "blender.png")
        if os.path.exists(png):
            os.remove(png)
        roots = sorted(os.listdir(os.path.join(work, "run", "roots")))
        rc = run([blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python",
                  os.path.join(HERE, "blender_plate_check.py"), "--", glb, png, ",".join(roots), str(FRAMES)])
        return 1 if rc else 0
    print("usage: consumers.py export|validator|blender|blender-plate ...")
    return 2


if __name__ == "__main__":
    sys.exit(main())
