#!/usr/bin/env bash
# Runs the libFuzzer harnesses of a ROOTSIM_FUZZ build (fuzz/CMakeLists.txt) for a fixed time each.
# Usage: scripts/fuzz.sh BUILD_DIR SECONDS [scene|sweep|trajectory|rsml ...]   (default: all four)
# Seeds: fuzz/seeds/<harness>, the repository's scenes/ or sweeps/ (rsml: tests/data/rsml), and the kept crashers in
# fuzz/regressions/<harness>. Each harness must survive: no crash, sanitizer report, leak, timeout
# (> 10 s for one input) or memory blow-up (> 1 GiB RSS, > 512 MiB in one allocation). A failing input
# is left as BUILD_DIR/fuzz-artifacts/<harness>-crash-* (or -timeout-, -oom-, -leak-): fix the bug and
# keep the input in fuzz/regressions/<harness>/ (ctest's fuzz_replay_<harness> runs it in every build).
set -euo pipefail
build=${1:?usage: scripts/fuzz.sh BUILD_DIR SECONDS [harness...]}
seconds=${2:?usage: scripts/fuzz.sh BUILD_DIR SECONDS [harness...]}
shift 2
src=$(cd "$(dirname "$0")/.." && pwd)
harnesses=("$@")
((${#harnesses[@]})) || harnesses=(scene sweep trajectory rsml)
mkdir -p "$build/fuzz-artifacts"
status=0
for h in "${harnesses[@]}"; do
  bin="$build/fuzz/fuzz_$h"
  [ -x "$bin" ] || { echo "fuzz.sh: $bin not built (configure with -DROOTSIM_FUZZ=ON, clang)"; exit 2; }
  corpus="$build/fuzz-corpus/$h"
  mkdir -p "$corpus"
  seeds=("$src/fuzz/seeds/$h")
  [ "$h" = scene ] && seeds+=("$src/scenes")
  [ "$h" = sweep ] && seeds+=("$src/sweeps")
  [ "$h" = rsml ] && seeds+=("$src/tests/data/rsml" "$src/tests/data/rsml/bad")
  [ -d "$src/fuzz/regressions/$h" ] && seeds+=("$src/fuzz/regressions/$h")
  log="$build/fuzz-artifacts/$h.log"
  start=$(date +%s)
  if "$bin" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=1024 -malloc_limit_mb=512 -print_final_stats=1 \
       -artifact_prefix="$build/fuzz-artifacts/$h-" "$corpus" "${seeds[@]}" >"$log" 2>&1; then
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
    echo "fuzz $h: ok, $runs inputs in $(( $(date +%s) - start )) s"
  else
    echo "fuzz $h: FAILED (log: $log)"
    grep -E '^fuzz:|ERROR|runtime error|SUMMARY|Test unit written' "$log" | head -20 || true
    status=1
  fi
done
exit $status
