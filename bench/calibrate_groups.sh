#!/usr/bin/env bash
# The calibration of the group fit's contrasts over seeds (docs/experiments.md, "Calibration of the
# contrasts' p-values"): bench/fit_groups.sh's plate (3 + 3 seedlings, 15 mm, each seedling's runs sown at
# its sheet's angle) for every seed FIRST..LAST, its "seed ..." lines appended to LOG (a seed already in
# LOG is skipped, so a killed calibration resumes), then the table of LOG (bench/calibration_table.py).
# MUT_TWIST: the mutants' tropism.twist_r_tau (0.05: one key differs, beta equal; 0: a null plate).
# PLATE drawn (the default): each seed a new plate, its seedlings' sowing angles drawn from the seed as
# well as the tracing's noise (a contrast's sigma is its error over repeated plates, and a plate's
# seedlings and their runs' jumps are part of that error); fixed: one plate, the tracing's noise alone.
# Usage: bash bench/calibrate_groups.sh BUILD_DIR LOG FIRST LAST [MUT_TWIST] [BUDGET] [JOBS] [PLATE]
set -euo pipefail
build=${1:?usage: bench/calibrate_groups.sh BUILD_DIR LOG FIRST LAST [MUT_TWIST] [BUDGET] [JOBS]}
log=${2:?LOG}
first=${3:?FIRST}
last=${4:?LAST}
twist=${5:-0.05}
budget=${6:-40}
jobs=${7:-2}
plate=${8:-drawn}
here=$(cd "$(dirname "$0")" && pwd)
touch "$log"
for ((s = first; s <= last; s++)); do
  if grep -q "^seed $s " "$log"; then continue; fi
  out=$(bash "$here/fit_groups.sh" "$build" "$s" "$budget" "$jobs" sheet 3 15 "$twist" 2 "$plate" 2>/dev/null) || {
    echo "bench/calibrate_groups.sh: seed $s failed" >&2
    exit 1
  }
  printf '%s\n' "$out" | grep '^wall ' | sed "s/^/# seed $s /" >> "$log"
  printf '%s\n' "$out" | grep '^seed ' >> "$log"
done
${PYTHON:-/usr/bin/python3} "$here/calibration_table.py" "$log" --truth-twist "$twist"
