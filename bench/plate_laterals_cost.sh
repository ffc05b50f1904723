#!/usr/bin/env bash
# How a plate with lateral roots costs (docs/plate.md, Cost): plates of N = 1, 2, 4, 8 seedlings of the
# paper's waving root with laterals (the [laterals] of scenes/plate_wildtype.toml), sown 12 mm apart so that
# the seedlings' root systems never meet, 3000 growth steps (150 h). Prints, per N, the wall time, the
# roots (seedlings and laterals), the root length grown (every root's final length less its initial one)
# and the CPU time per root-millimetre grown. Usage: bash bench/plate_laterals_cost.sh BUILD_DIR [STEPS]
set -euo pipefail
build=${1:?usage: bench/plate_laterals_cost.sh BUILD_DIR [STEPS]}
steps=${2:-3000}
here=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# the plate-wide tables of plate_wildtype.toml, without its seedlings and population
sed -n '/^\[root\]/,/^\[population\]/p' "$here/scenes/plate_wildtype.toml" | sed '$d' | sed '/^\[plate\]/,/^$/d' > "$work/head.toml"
for n in 1 2 4 8; do
  {
    cat "$work/head.toml"
    printf '\n[plate]\nwidth_mm = %d\nlength_mm = 60\n' $((12 * n + 12))
    for k in $(seq 1 "$n"); do printf '\n[[seedling]]\nname = "s%d"\nposition_mm = [%d, 5]\n' "$k" $((12 * k)); done
  } > "$work/plate_$n.toml"
  python3 - "$work/run_$n" "$n" "$build/rootsim" "$work/plate_$n.toml" "$steps" <<'PY'
import csv, resource, subprocess, sys, time, tomllib
run, n, exe, scene, steps = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4], sys.argv[5]
r0, t0 = resource.getrusage(resource.RUSAGE_CHILDREN), time.monotonic()
subprocess.run([exe, "run", scene, "--set", f"growth.steps={steps}", "--set", "output.vtk=false", "--out", run, "--quiet"], check=True)
r1, t1 = resource.getrusage(resource.RUSAGE_CHILDREN), time.monotonic()
cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
rows = list(csv.DictReader(open(f"{run}/plate.csv")))
with open(f"{run}/scene.toml", "rb") as f:
    scene = tomllib.load(f)
l0, l0lat = scene["root"]["initial_length_mm"], scene["laterals"]["initial_length_mm"]
grown = sum(float(r["length_mm"]) - (l0 if r["parent"] == "" else l0lat) for r in rows)
wall = t1 - t0
print(f"N = {n}: {wall:6.1f} s wall, {cpu:6.1f} s CPU, {len(rows):3d} roots ({len(rows) - n} laterals), {grown:7.1f} mm grown, "
      f"{1000 * cpu / grown:5.1f} ms CPU per root-mm, {cpu / n:5.2f} s CPU per seedling")
PY
done
