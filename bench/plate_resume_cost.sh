#!/usr/bin/env bash
# The cost of resuming a killed plate (docs/performance.md, "A plate killed and resumed"): SCENE (default
# scenes/plate_wildtype.toml: six seedlings with laterals, 3000 steps) run whole, then run by the test binary
# rootsim_killable with a checkpoint after growth step K and a kill right after it (K: half the steps),
# then resumed with `run --resume`. Prints the CPU (user + sys of the child) of each, the resumed run's
# CPU over the whole run's and both attempts' over it, and checks that the resumed plate's files are the
# whole run's bytes (summary.json's wall time aside).
# Usage: bash bench/plate_resume_cost.sh BUILD_DIR [SCENE] [K]
set -euo pipefail
build=${1:?usage: bench/plate_resume_cost.sh BUILD_DIR [SCENE] [K]}
here=$(cd "$(dirname "$0")/.." && pwd)
scene=${2:-$here/scenes/plate_wildtype.toml}
steps=$(sed -n 's/^steps *= *\([0-9]*\).*/\1/p' "$scene" | head -1)
k=${3:-$((steps / 2))}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 - "$build/rootsim" "$build/tests/rootsim_killable" "$scene" "$work" "$k" <<'PY'
import os, resource, subprocess, sys, filecmp, re
exe, killable, scene, work, k = sys.argv[1:6]
def cpu(cmd, env=None, ok=(0,)):
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    code = subprocess.run(cmd, env=env).returncode
    assert code in ok, (cmd, code)
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
whole = cpu([exe, "run", scene, "--quiet", "--out", f"{work}/a"])
env = dict(os.environ, ROOTSIM_TEST_KILL=f"{k}:{k}")
first = cpu([killable, "run", scene, "--quiet", "--out", f"{work}/b"], env=env, ok=(137,))
resumed = cpu([exe, "run", scene, "--quiet", "--out", f"{work}/b", "--resume"])
def tree(d):
    out = {}
    for root, _, files in os.walk(d):
        for f in files:
            p = os.path.join(root, f)
            b = open(p, "rb").read()
            if f == "summary.json":
                b = re.sub(rb'\n *"wall_time_s"[^\n]*', b"", b)
            out[os.path.relpath(p, d)] = b
    return out
a, b = tree(f"{work}/a"), tree(f"{work}/b")
same = a == b
print(f"scene {os.path.basename(scene)}, killed after step {k}")
print(f"whole run CPU {whole:.2f} s; killed attempt {first:.2f} s; resumed {resumed:.2f} s")
print(f"resumed / whole {resumed / whole:.2f}; both attempts / whole {(first + resumed) / whole:.2f}")
print(f"resumed plate's {len(b)} files the same bytes as the whole run's: {same}")
sys.exit(0 if same else 1)
PY
