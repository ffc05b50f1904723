#!/usr/bin/env bash
# The cost of a fit by group (docs/performance.md, "A plate fitted by group"): bench/fit_groups.sh's plate
# of two genotypes grown to 20 mm, each seedling's runs sown at its sheet's angle, budget 40, -j 2; two
# groups of 2, 4 and 6 seedlings with two free keys (beta, the twist), and of 6 seedlings with the twist
# alone. Prints a line per case: seedlings per group, keys, the fit's CPU and wall seconds, its
# evaluations and runs, and its CPU as a ratio to the 6-seedling two-key case.
# Usage: bash bench/fit_groups_cost.sh BUILD_DIR [SEED]
set -euo pipefail
build=${1:?usage: bench/fit_groups_cost.sh BUILD_DIR [SEED]}
seed=${2:-1}
here=$(cd "$(dirname "$0")" && pwd)
rows=()
for c in 6:2 4:2 2:2 6:1; do
  out=$(bash "$here/fit_groups.sh" "$build" "$seed" 40 2 sheet "${c%%:*}" 20 0.05 "${c#*:}" 2>/dev/null)
  printf '%s\n' "$out" | grep -E '^(WT|mut|wall|seed) ' | sed "s/^/[${c%%:*} per group, ${c#*:} keys] /" >&2
  w=$(printf '%s\n' "$out" | sed -n 's/^wall \([0-9.]*\) s, CPU \([0-9.]*\) s, evaluations \([0-9]*\), runs \([0-9]*\)$/\1 \2 \3 \4/p')
  rows+=("${c%%:*} ${c#*:} $w")
done
ref=$(printf '%s\n' "${rows[0]}" | awk '{print $4}')
printf 'seedlings_per_group keys cpu_s wall_s evaluations runs cpu_ratio\n'
for r in "${rows[@]}"; do
  set -- $r
  awk -v n="$1" -v k="$2" -v w="$3" -v c="$4" -v e="$5" -v u="$6" -v ref="$ref" 'BEGIN { printf "%s %s %s %s %s %s %.2f\n", n, k, c, w, e, u, c / ref }'
done
