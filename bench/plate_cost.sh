#!/usr/bin/env bash
# The cost of a plate (docs/plate.md, Cost): a plate of N seedlings of the paper's waving root (Fig. 2B,
# 3000 growth steps: 31 mm each), sown 10 mm apart so that they never meet, against N runs of the same
# root alone, one after the other in this one process tree. Prints both wall times and their ratio.
# Usage: bash bench/plate_cost.sh BUILD_DIR [N] [STEPS]
set -euo pipefail
build=${1:?usage: bench/plate_cost.sh BUILD_DIR [N] [STEPS]}
n=${2:-10}
steps=${3:-3000}
here=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scene="$here/scenes/fig2b_waving.toml"
{
  cat "$scene"
  printf '\n[plate]\nwidth_mm = %d\nlength_mm = 60\n' $((10 * n + 10))
  for k in $(seq 1 "$n"); do printf '\n[[seedling]]\nname = "s%d"\nposition_mm = [%d, 5]\n' "$k" $((10 * k)); done
} > "$work/plate.toml"
python3 - "$build/rootsim" "$scene" "$work" "$n" "$steps" <<'PY'
import resource, subprocess, sys, time
exe, scene, work, n, steps = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), sys.argv[5]
sets = ["--set", f"growth.steps={steps}", "--set", "output.vtk=false", "--quiet"]
def timed(cmds):
    r0, t0 = resource.getrusage(resource.RUSAGE_CHILDREN), time.monotonic()
    for c in cmds:
        subprocess.run(c, check=True)
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return time.monotonic() - t0, (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
sw, sc = timed([[exe, "run", scene, *sets, "--out", f"{work}/single_{k}"] for k in range(1, n + 1)])
pw, pc = timed([[exe, "run", f"{work}/plate.toml", *sets, "--out", f"{work}/plate"]])
print(f"{n} single runs of {steps} steps: {sw:.1f} s wall, {sc:.1f} s CPU; one plate of {n} seedlings: "
      f"{pw:.1f} s wall, {pc:.1f} s CPU; ratio {pw / sw:.3f} wall, {pc / sc:.3f} CPU")
PY
# the roots apart are the single root's run: the same final shape, byte for byte
cmp "$work/single_1/shape.csv" "$work/plate/roots/s1/shape.csv" && echo "roots/s1/shape.csv is the single run's, byte for byte"
