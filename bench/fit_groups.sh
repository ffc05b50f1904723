#!/usr/bin/env bash
# A traced plate fitted by group (docs/experiments.md, "A plate by group"; docs/performance.md): a plate
# of two genotypes of three seedlings each (the waving root at the quick resolution, 15 mm; wild type twist
# 0, mutant tropism.twist_r_tau = 0.05, beta 0.2 in both, each seedling sown at its own angle), exported,
# traced as a scan (examples/synthetic_trace.py --plate --whole-px: 20 px/mm, a point every 4 px, 0.5 px
# jitter, whole pixels; seeded), then `rootsim fit --groups` with beta and the twist free. Prints the
# fit's table, its wall and CPU seconds (user + sys of the child processes), and a line
# "seed S twist_diff D sigma S p P beta_diff D sigma S p P" for a calibration over seeds.
# Usage: bash bench/fit_groups.sh BUILD_DIR [SEED] [BUDGET] [JOBS] [trace|sheet|straight]
set -euo pipefail
build=${1:?usage: bench/fit_groups.sh BUILD_DIR [SEED] [BUDGET] [JOBS] [trace|sheet|straight]}
seed=${2:-1}
budget=${3:-40}
jobs=${4:-2}
sowing=${5:-trace}  # trace: each seedling's runs sown at its trace's start angle; sheet: at its true angle (the sheet's
                    # angle_deg); straight: every run at 0 (angle_deg 0)
py=${PYTHON:-/usr/bin/python3}  # numpy: Debian python3-numpy
here=$(cd "$(dirname "$0")/.." && pwd)
exe=$(cd "$build" && pwd)/rootsim
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
base='[root]
radius_mm = 0.1
initial_length_mm = 1.1
element_length_mm = 0.1
[growth]
growth_zone_mm = 1.0
rate_per_h = 0.2
step_h = 0.1
[tropism]
beta = 0.2
gamma = 0.1
sensing = "local"
[plane]
alpha_deg = 40
[output]
every_steps = 50'
printf '%s\n' "$base" > "$work/base.toml"
{
  printf '%s\n' "$base" | sed 's/^step_h = 0.1$/step_h = 0.1\nsteps = 700/'
  printf 'vtk = false\n[plate]\nwidth_mm = 80\nlength_mm = 30\n'
  i=0
  for s in w1:-3 w2:2 w3:4 m1:3 m2:-2 m3:-4; do
    printf '[[seedling]]\nname = "%s"\nposition_mm = [%d, 5]\nangle_deg = %s\n' "${s%%:*}" $((5 + 11 * i)) "${s#*:}"
    case $s in m*) printf 'set = { "tropism.twist_r_tau" = 0.05 }\n' ;; esac
    i=$((i + 1))
  done
} > "$work/plate.toml"
if [ "$sowing" = sheet ]; then
  printf 'plant,group,angle_deg\nw1,WT,-3\nw2,WT,2\nw3,WT,4\nm1,mut,3\nm2,mut,-2\nm3,mut,-4\n' > "$work/sheet.csv"
elif [ "$sowing" = straight ]; then
  printf 'plant,group,angle_deg\nw1,WT,0\nw2,WT,0\nw3,WT,0\nm1,mut,0\nm2,mut,0\nm3,mut,0\n' > "$work/sheet.csv"
else
  printf 'plant,group\nw1,WT\nw2,WT\nw3,WT\nm1,mut\nm2,mut\nm3,mut\n' > "$work/sheet.csv"
fi
"$exe" run "$work/plate.toml" --out "$work/run" --quiet
"$exe" export "$work/run" --rsml "$work/plate.rsml" --quiet
"$py" "$here/examples/synthetic_trace.py" "$work/plate.rsml" "$work/traced.rsml" --plate --whole-px --noise-px 0.5 --seed "$seed"
"$py" - "$exe" "$work" "$budget" "$jobs" "$seed" <<'PY'
import json, resource, subprocess, sys, time
exe, work, budget, jobs, seed = sys.argv[1:]
r0, t0 = resource.getrusage(resource.RUSAGE_CHILDREN), time.monotonic()
subprocess.run([exe, "fit", f"{work}/traced.rsml", "--px-per-mm", "20", "--groups", f"{work}/sheet.csv", "--scene", f"{work}/base.toml",
                "--free", "tropism.beta=0.1:0.3,tropism.twist_r_tau=-0.05:0.1", "--budget", budget, "-j", jobs, "--quiet",
                "--out", f"{work}/fit"], check=True)
r1, t1 = resource.getrusage(resource.RUSAGE_CHILDREN), time.monotonic()
print(f"wall {t1 - t0:.1f} s, CPU {(r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime):.1f} s")
fit = json.load(open(f"{work}/fit/fit.json"))
c = {x["key"]: x for x in fit["contrasts"]}
def part(k):
    x = c[k]
    if x["difference"] == "flat":
        return "flat - -"
    return f"{x['difference']:.4g} {x['sigma']:.3g} {x['p_value']:.3g}"
print(f"seed {seed} twist_diff {part('tropism.twist_r_tau')} beta_diff {part('tropism.beta')} "
      f"verdicts {fit['groups']['WT']['goodness']['verdict']} {fit['groups']['mut']['goodness']['verdict']}")
PY
