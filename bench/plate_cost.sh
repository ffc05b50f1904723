#!/usr/bin/env bash
# The cost of a plate (docs/plate.md, Cost): a plate of N seedlings of the paper's waving root (Fig. 2B,
# 3000 growth steps: 31 mm each), sown 10 mm apart so that they never meet, against N runs of the same
# root alone, one after the other in this one process tree. Prints both wall times and their ratio.
# Usage: bash bench/plate_cost.sh BUILD_DIR [N] [STEPS]
#
# The cost of roots that touch: `bash bench/plate_cost.sh BUILD_DIR collision [REPEATS] [OTHER_BUILD_DIR]`
# runs scenes/plate_collision.toml (the two roots meet after ~11 h and stay pressed together) and the same
# two seedlings sown 15 mm apart ("across" at [35, 7] mm), side by side (one of each in turn), REPEATS
# times (5); prints the median CPU of each, their ratio, and the closest approach of the two roots
# (min_root_distance_r of summary.json). With OTHER_BUILD_DIR, the same with that build's rootsim in the
# same loop (a before/after comparison).
set -euo pipefail
build=${1:?usage: bench/plate_cost.sh BUILD_DIR [N] [STEPS] | BUILD_DIR collision [REPEATS] [OTHER_BUILD_DIR]}
if [ "${2:-}" = collision ]; then
  repeats=${3:-5}
  other=${4:-}
  here=$(cd "$(dirname "$0")/.." && pwd)
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  sed 's/^position_mm = \[23, 7\]$/position_mm = [35, 7]/' "$here/scenes/plate_collision.toml" > "$work/apart.toml"
  grep -q '^position_mm = \[35, 7\]$' "$work/apart.toml"
  python3 - "$build/rootsim" "${other:+$other/rootsim}" "$here/scenes/plate_collision.toml" "$work" "$repeats" <<'PY'
import json, resource, statistics, subprocess, sys
exe, other, collision, work, repeats = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5])
def cpu(cmd):
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, check=True)
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
builds = [("this", exe)] + ([("other", other)] if other else [])
times = {(b, s): [] for b, _ in builds for s in ("touching", "apart")}
for k in range(repeats):
    for b, e in builds:
        for s, scene in (("touching", collision), ("apart", f"{work}/apart.toml")):
            out = f"{work}/{b}_{s}_{k}"
            times[(b, s)].append(cpu([e, "run", scene, "--set", "output.vtk=false", "--quiet", "--out", out]))
for b, e in builds:
    t, a = statistics.median(times[(b, "touching")]), statistics.median(times[(b, "apart")])
    summary = json.load(open(f"{work}/{b}_touching_0/summary.json"))
    closest = summary.get("min_root_distance_r", summary.get("min_gap_over_contact"))
    print(f"{e}: plate_collision {t:.2f} s CPU, apart {a:.2f} s CPU (medians of {repeats}); "
          f"ratio {t / a:.2f}; closest approach {closest} (Ra + Rb); most sweeps a step {summary['max_sweeps_per_step']}")
PY
  exit 0
fi
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
