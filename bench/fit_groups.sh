#!/usr/bin/env bash
# A traced plate fitted by group (docs/experiments.md, "A plate by group"; docs/performance.md): a plate
# of two genotypes of N seedlings each (default 3; the waving root at the quick resolution, grown to
# LENGTH mm, default 15; wild type twist 0, mutant tropism.twist_r_tau = MUT_TWIST, default 0.05, 0 for a
# null plate; beta 0.2 in both, each seedling sown at its own angle), exported, traced as a scan
# (examples/synthetic_trace.py --plate --whole-px: 20 px/mm, a point every 4 px, 0.5 px jitter, whole
# pixels; seeded), then `rootsim fit --groups` with beta and the twist free (KEYS 2, the default) or the
# twist alone (KEYS 1, beta fixed at its truth). Prints the fit's table, its wall and CPU seconds (user +
# sys of the child processes), its runs, and a line "seed S twist_diff D sigma P beta_diff D sigma P
# verdicts V V chi2 C/DOF C/DOF answer_scale A A" for a calibration over seeds (bench/calibrate_groups.sh).
# PLATE fixed (the default): every seed the same plate (its sowing angles below), only the tracing's noise
# drawn from SEED; drawn: each seedling's sowing angle drawn from SEED too (uniform in [-4, 4] deg, to
# 0.1 deg), so that seeds are plates of the same genotypes, as repeated experiments are.
# Usage: bash bench/fit_groups.sh BUILD_DIR [SEED] [BUDGET] [JOBS] [trace|sheet|straight] [N] [LENGTH] [MUT_TWIST] [KEYS] [PLATE]
set -euo pipefail
build=${1:?usage: bench/fit_groups.sh BUILD_DIR [SEED] [BUDGET] [JOBS] [trace|sheet|straight] [N] [LENGTH] [MUT_TWIST] [KEYS]}
seed=${2:-1}
budget=${3:-40}
jobs=${4:-2}
sowing=${5:-trace}  # trace: each seedling's runs sown at its trace's start angle; sheet: at its true angle (the sheet's
                    # angle_deg); straight: every run at 0 (angle_deg 0)
per=${6:-3}         # seedlings per group, 2 to 6
length=${7:-15}     # mm, an integer: grown length + 0.1 (steps of 0.02 mm of growth)
twist=${8:-0.05}    # the mutants' tropism.twist_r_tau (the wild type's is 0)
nkeys=${9:-2}
plate=${10:-fixed}
case $per in [2-6]) ;; *) echo "bench/fit_groups.sh: N $per: expected 2 to 6 seedlings per group" >&2; exit 2 ;; esac
case $plate in fixed | drawn) ;; *) echo "bench/fit_groups.sh: PLATE $plate: expected fixed or drawn" >&2; exit 2 ;; esac
case $nkeys in 1) free=tropism.twist_r_tau=-0.05:0.1 ;; 2) free=tropism.beta=0.1:0.3,tropism.twist_r_tau=-0.05:0.1 ;;
  *) echo "bench/fit_groups.sh: KEYS $nkeys: expected 1 (the twist) or 2 (beta and the twist)" >&2; exit 2 ;; esac
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
# each group's sowing angles [deg] (the first three the 3-seedling plate's)
wt_angles=(-3 2 4 -1 1 -4)
mut_angles=(3 -2 -4 1 -1 4)
if [ "$plate" = drawn ]; then
  read -r -a drawn <<< "$("$py" -c "import random, sys; r = random.Random(int(sys.argv[1])); print(' '.join(f'{r.uniform(-4, 4):.1f}' for _ in range(12)))" "$seed")"
  wt_angles=("${drawn[@]:0:6}")
  mut_angles=("${drawn[@]:6:6}")
fi
names=() angles=() groups=()
for ((i = 0; i < per; i++)); do names+=("w$((i + 1))"); angles+=("${wt_angles[i]}"); groups+=(WT); done
for ((i = 0; i < per; i++)); do names+=("m$((i + 1))"); angles+=("${mut_angles[i]}"); groups+=(mut); done
{
  printf '%s\n' "$base" | sed "s/^step_h = 0.1\$/step_h = 0.1\nsteps = $(( (length - 1) * 50 ))/"
  printf 'vtk = false\n[plate]\nwidth_mm = %d\nlength_mm = %d\n' $(( 22 * per > 70 ? 22 * per + 10 : 80 )) $(( length + 15 ))
  for ((i = 0; i < 2 * per; i++)); do
    printf '[[seedling]]\nname = "%s"\nposition_mm = [%d, 5]\nangle_deg = %s\n' "${names[i]}" $((5 + 11 * i)) "${angles[i]}"
    if [ "${groups[i]}" = mut ]; then printf 'set = { "tropism.twist_r_tau" = %s }\n' "$twist"; fi
  done
} > "$work/plate.toml"
{
  case $sowing in
    sheet) printf 'plant,group,angle_deg\n'; for ((i = 0; i < 2 * per; i++)); do printf '%s,%s,%s\n' "${names[i]}" "${groups[i]}" "${angles[i]}"; done ;;
    straight) printf 'plant,group,angle_deg\n'; for ((i = 0; i < 2 * per; i++)); do printf '%s,%s,0\n' "${names[i]}" "${groups[i]}"; done ;;
    *) printf 'plant,group\n'; for ((i = 0; i < 2 * per; i++)); do printf '%s,%s\n' "${names[i]}" "${groups[i]}"; done ;;
  esac
} > "$work/sheet.csv"
"$exe" run "$work/plate.toml" --out "$work/run" --quiet
"$exe" export "$work/run" --rsml "$work/plate.rsml" --quiet
"$py" "$here/examples/synthetic_trace.py" "$work/plate.rsml" "$work/traced.rsml" --plate --whole-px --noise-px 0.5 --seed "$seed"
"$py" - "$exe" "$work" "$budget" "$jobs" "$seed" "$free" <<'PY'
import json, os, resource, subprocess, sys, time
exe, work, budget, jobs, seed, free = sys.argv[1:]
r0, t0 = resource.getrusage(resource.RUSAGE_CHILDREN), time.monotonic()
subprocess.run([exe, "fit", f"{work}/traced.rsml", "--px-per-mm", "20", "--groups", f"{work}/sheet.csv", "--scene", f"{work}/base.toml",
                "--free", free, "--budget", budget, "-j", jobs, "--quiet", "--out", f"{work}/fit"], check=True)
r1, t1 = resource.getrusage(resource.RUSAGE_CHILDREN), time.monotonic()
fit = json.load(open(f"{work}/fit/fit.json"))
groups = {g: json.load(open(f"{work}/fit/groups/{g}/fit.json")) for g in fit["groups"]}
evals = sum(groups[g]["evaluations"] for g in groups)
runs = sum(len(os.listdir(f"{work}/fit/groups/{g}/runs")) for g in groups)
print(f"wall {t1 - t0:.1f} s, CPU {(r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime):.1f} s, evaluations {evals}, runs {runs}")
c = {x["key"]: x for x in fit["contrasts"]}
def part(k):
    if k not in c:
        return "fixed - -"
    x = c[k]
    if x["difference"] == "flat":
        return "flat - -"
    return f"{x['difference']:.4g} {x['sigma']:.3g} {x['p_value']:.3g}"
good = {g: fit["groups"][g]["goodness"] for g in ("WT", "mut")}
print(f"seed {seed} twist_diff {part('tropism.twist_r_tau')} beta_diff {part('tropism.beta')} "
      f"verdicts {good['WT']['verdict']} {good['mut']['verdict']} "
      f"chi2 {good['WT']['chi2']:.3g}/{good['WT']['dof']} {good['mut']['chi2']:.3g}/{good['mut']['dof']} "
      f"answer_scale {groups['WT'].get('answer_scale', float('nan')):.3g} {groups['mut'].get('answer_scale', float('nan')):.3g}")
PY
