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
sets="--set growth.steps=$steps --set output.vtk=false"
t0=$(date +%s.%N)
for k in $(seq 1 "$n"); do "$build/rootsim" run "$scene" $sets --out "$work/single_$k" --quiet; done
t1=$(date +%s.%N)
"$build/rootsim" run "$work/plate.toml" $sets --out "$work/plate" --quiet
t2=$(date +%s.%N)
python3 - "$t0" "$t1" "$t2" "$n" "$steps" <<'PY'
import sys
t0, t1, t2 = map(float, sys.argv[1:4]); n, steps = sys.argv[4], sys.argv[5]
single, plate = t1 - t0, t2 - t1
print(f"{n} single runs of {steps} steps: {single:.1f} s; one plate of {n} seedlings: {plate:.1f} s; ratio {plate / single:.3f}")
PY
# the roots apart are the single root's run: the same final shape, byte for byte
cmp "$work/single_1/shape.csv" "$work/plate/roots/s1/shape.csv" && echo "roots/s1/shape.csv is the single run's, byte for byte"
